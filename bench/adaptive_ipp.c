/* Instructions per pixel of the adaptive stereo blend's parts on a real sequence, for
   callgrind (bench/adaptive_ipp.sh), which does not drift with the machine's load:
   the per-eye temporal filter (Mono), the consistency mask on the two eyes' luminances,
   the stereo blend everywhere (FSA) and the masked blend with that mask, at frame F of
   the sequence (the temporal outputs come from bench/sbl_runner.h's "default").

   usage: adaptive_ipp SCENE_DIR [FRAME] [THRESHOLD]   (prints the marked share) */
#define _POSIX_C_SOURCE 200809L
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"
#define SBL_RUNNER_IMPLEMENTATION
#include "sbl_runner.h"
#include <stdio.h>

typedef struct grab { int frame; float *rgb[2]; } grab;

static void grab_frame(void *ctx, int frame, int eye, const float *rgb, int w, int h)
{
    grab *g = (grab *)ctx;
    if (frame == g->frame) memcpy(g->rgb[eye], rgb, (size_t)w * h * 3 * sizeof(float));
}

static sbl_eye eye_of(const sbr_seq *s, int frame, int e, float *rgb)
{
    const sbr_view *v = &s->views[frame * 2 + e];
    sbl_eye eye;
    memset(&eye, 0, sizeof eye);
    eye.color = sbl_image_make(rgb, s->width, s->height, 3);
    eye.gbuffer.depth = sbl_image_make(v->depth, s->width, s->height, 1);
    eye.gbuffer.normals = sbl_image_make(v->normal, s->width, s->height, 3);
    eye.gbuffer.ids = sbl_image_make(v->id, s->width, s->height, 1);
    return eye;
}

int main(int argc, char **argv)
{
    sbr_seq s;
    sbr_method mono;
    sbr_result r;
    grab g;
    char err[512];
    int frame = argc > 2 ? atoi(argv[2]) : 8, e, w, h;
    float threshold = argc > 3 ? (float)atof(argv[3]) : 0.0f;
    size_t n, bytes;
    float *lum[2], *out;
    unsigned char *mask[2];
    void *scratch;
    sbl_stereo_desc d;
    sbl_eye eye[2];
    long marked = 0, blended, tiles_run = 0, tiles_all = 0;
    if (argc < 2) { fprintf(stderr, "usage: adaptive_ipp SCENE_DIR [FRAME] [THRESHOLD]\n"); return 2; }
    if (sbr_seq_dataset(&s, argv[1], frame + 1, err, sizeof err) != 0) { fprintf(stderr, "%s\n", err); return 1; }
    w = s.width; h = s.height; n = (size_t)w * h;
    if (sbr_find_method("default", &mono) != 0) return 1;
    g.frame = frame;
    for (e = 0; e < 2; ++e) {
        g.rgb[e] = (float *)malloc(n * 3 * sizeof(float));
        lum[e] = (float *)malloc(n * sizeof(float));
        mask[e] = (unsigned char *)malloc(n);
    }
    out = (float *)malloc(n * 3 * sizeof(float));
    bytes = sbl_stereo_scratch_size(w, 3);
    scratch = malloc(bytes);
    if (sbr_run(&s, &mono, &r, grab_frame, &g) != 0) return 1; /* sbl_temporal_filter_frame */
    memset(&d, 0, sizeof d);
    d.rig = SBL_RIG_PARALLEL;
    d.focal_px = s.focal_px;
    d.baseline = s.baseline;
    for (e = 0; e < 2; ++e) eye[e] = eye_of(&s, frame, e, g.rgb[e]);
    for (e = 0; e < 2; ++e) sbr_luminance(g.rgb[e], lum[e], n);
    for (e = 0; e < 2; ++e) {
        sbl_consistency_counts c;
        sbl_stereo_consistency(&d, threshold, (sbl_eye_index)e, &eye[e], &eye[!e],
                               sbl_image_make(lum[e], w, h, 1), sbl_image_make(lum[!e], w, h, 1),
                               mask[e], w, 0, h, NULL, 0, &c);
        marked += c.inconsistent;
    }
    for (e = 0; e < 2; ++e)
        sbl_stereo_blend(&d, (sbl_eye_index)e, &eye[e], &eye[!e], sbl_image_make(out, w, h, 3),
                         sbl_image_make(NULL, 0, 0, 0), 0, h, scratch, bytes);
    {   /* the one-pass call on the colour's luminance (the same test as above) */
        size_t ab = sbl_stereo_adaptive_scratch_size(w, 3);
        void *as = malloc(ab);
        sbl_adaptive_desc ad;
        memset(&ad, 0, sizeof ad);
        ad.threshold = threshold;
        for (e = 0; e < 2; ++e) {
            long tb = 0, ta = 0;
            sbl_stereo_blend_adaptive(&d, &ad, (sbl_eye_index)e, &eye[e], &eye[!e],
                                      sbl_image_make(out, w, h, 3), sbl_image_make(NULL, 0, 0, 0),
                                      NULL, 0, 0, h, as, ab, NULL, &tb, &ta);
            tiles_run += tb; tiles_all += ta;
        }
        free(as);
    }
    for (e = 0; e < 2; ++e)
        sbl_stereo_blend_masked(&d, (sbl_eye_index)e, &eye[e], &eye[!e], mask[e], w,
                                sbl_image_make(out, w, h, 3), sbl_image_make(NULL, 0, 0, 0), 0, h,
                                scratch, bytes, &blended);
    printf("%s frame %d: %d x %d, %d frames filtered, marked %.2f %% of all pixels, tiles %.2f %% (threshold %.3f)\n",
           s.name, frame, w, h, frame + 1, 100.0 * (double)marked / (2.0 * (double)n),
           tiles_all ? 100.0 * (double)tiles_run / (double)tiles_all : 0.0,
           threshold > 0 ? threshold : SBL_WEBER_THRESHOLD);
    sbr_seq_free(&s);
    return 0;
}
