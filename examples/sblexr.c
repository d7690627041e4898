/* sblexr - run a stereoblend.h method over a rendered stereo sequence (EXR, in the
   layout of shared/data/atrium: meta.json, cameras.json, exr/{noisy,ref,gbuf,ladder})
   and write the filtered frames as RGB float EXR: <out>/<eye>/<frame>.exr, eye L or R.
   Prints RMSE / SSIM / effective spp where references exist.

   usage: sblexr SCENE_DIR OUT_DIR [--method NAME] [--frames N] [--sheet FRAME] [--list]
   OUT_DIR is created with its parents. --sheet FRAME also writes OUT_DIR/sheet_FRAME.png,
   a contact sheet of that frame: one row per eye (left, right), columns input (1 spp),
   output, reference, |output - reference| (x4, black-red-yellow-white), alpha (the
   temporal weight, black 0 .. white 1; blue when the method has no temporal filter).
   Colours are clamped to [0, 1] and sRGB-encoded.
   No --method: the library's default temporal filter (every descriptor field zero, with
   the optional evidence and tail planes carried from frame to frame, as a user gets the
   default's full accuracy; `pooled`: the same without the planes); the frames written
   are its display (sbl_temporal_output.display; `default-nodisplay`: its history
   colour, as before session 39);
   --method default-stereo: the default combined pipeline (temporal per eye, told that a
   stereo blend follows: sbl_temporal_desc.stereo_shared_bias = 1; then the default
   stereo blend for display). These two names stay stable. default-cr and
   default-stereo-cr: the same with the Catmull-Rom history fetch
   (sbl_reproject_desc.history_filter).
*/
#define _POSIX_C_SOURCE 200809L
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"
#define SBL_RUNNER_IMPLEMENTATION
#include "../bench/sbl_runner.h"
#include "sbl_exr.h"
#include "sbl_png.h"
#include <stdio.h>
#include <sys/stat.h>
#include <errno.h>

typedef struct writer {
    const char *out;
    int failed;
    int sheet_frame;          /* -1: no contact sheet */
    float *sheet_out[2];      /* the displayed output of that frame, per eye */
    float *sheet_alpha[2];    /* its temporal weight, per eye (NULL: none) */
} writer;

static void write_frame(void *ctx, int frame, int eye, const float *rgb, int w, int h)
{
    writer *wr = (writer *)ctx;
    char path[2048], err[256];
    if (wr->failed) return;
    snprintf(path, sizeof path, "%s/%c/%04d.exr", wr->out, eye ? 'R' : 'L', frame);
    if (sbl_exr_write(path, rgb, w, h, 3, NULL, err, sizeof err) != 0) {
        fprintf(stderr, "sblexr: %s: %s\n", path, err);
        wr->failed = 1;
    }
    if (frame == wr->sheet_frame && !wr->sheet_out[eye]) {
        wr->sheet_out[eye] = (float *)malloc((size_t)w * (size_t)h * 3 * sizeof(float));
        if (wr->sheet_out[eye]) memcpy(wr->sheet_out[eye], rgb, (size_t)w * (size_t)h * 3 * sizeof(float));
    }
}

static void keep_alpha(void *ctx, int frame, int eye, const float *alpha, int w, int h)
{
    writer *wr = (writer *)ctx;
    if (frame != wr->sheet_frame || wr->sheet_alpha[eye]) return;
    wr->sheet_alpha[eye] = (float *)malloc((size_t)w * (size_t)h * sizeof(float));
    if (wr->sheet_alpha[eye]) memcpy(wr->sheet_alpha[eye], alpha, (size_t)w * (size_t)h * sizeof(float));
}

/* mkdir -p: every missing parent too */
static int make_dir(const char *p)
{
    char buf[2048];
    size_t i, n = strlen(p);
    if (n == 0 || n >= sizeof buf) { fprintf(stderr, "sblexr: bad path '%s'\n", p); return 1; }
    memcpy(buf, p, n + 1);
    for (i = 1; i <= n; ++i) {
        if (buf[i] != '/' && buf[i] != '\0') continue;
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) { perror(buf); return 1; }
        if (i < n) buf[i] = '/';
    }
    return 0;
}

static unsigned char to_srgb8(float v)
{
    double c = v > 0.0f ? (v < 1.0f ? (double)v : 1.0) : 0.0; /* NaN -> 0 */
    c = c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
    return (unsigned char)(c * 255.0 + 0.5);
}

/* the contact sheet of one frame: rows = eyes, columns = input, output, reference,
   |error| x4 (heat), alpha (grey) */
static int write_sheet(const char *path, const sbr_seq *seq, const writer *wr, int frame)
{
    const int w = seq->width, h = seq->height, cols = 5, gap = 4;
    const int W = cols * w + (cols - 1) * gap, H = 2 * h + gap;
    unsigned char *img = (unsigned char *)malloc((size_t)W * (size_t)H * 3);
    int eye, col, x, y, k, rc;
    if (!img) return -1;
    memset(img, 255, (size_t)W * (size_t)H * 3);
    for (eye = 0; eye < 2; ++eye) {
        const sbr_view *v = &seq->views[frame * 2 + eye];
        for (col = 0; col < cols; ++col)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    unsigned char *dst = img + ((size_t)(eye * (h + gap) + y) * (size_t)W +
                                                (size_t)(col * (w + gap) + x)) * 3;
                    size_t i = (size_t)y * (size_t)w + (size_t)x;
                    const float *out = wr->sheet_out[eye] ? wr->sheet_out[eye] + i * 3 : NULL;
                    const float *ref = v->ref ? v->ref + i * 3 : NULL;
                    if (col == 0 || (col == 1 && out) || (col == 2 && ref)) {
                        const float *src = col == 0 ? v->color + i * 3 : (col == 1 ? out : ref);
                        for (k = 0; k < 3; ++k) dst[k] = to_srgb8(src[k]);
                    } else if (col == 3 && out && ref) {
                        double e = 0;
                        for (k = 0; k < 3; ++k) e += fabs((double)out[k] - (double)ref[k]) / 3.0;
                        e *= 4.0; /* black -> red -> yellow -> white over [0, 3] */
                        dst[0] = (unsigned char)(255.0 * (e < 1 ? e : 1));
                        dst[1] = (unsigned char)(255.0 * (e < 1 ? 0 : (e < 2 ? e - 1 : 1)));
                        dst[2] = (unsigned char)(255.0 * (e < 2 ? 0 : (e < 3 ? e - 2 : 1)));
                    } else if (col == 4 && wr->sheet_alpha[eye]) {
                        float a = wr->sheet_alpha[eye][i];
                        unsigned char g = (unsigned char)(255.0f * (a > 0.0f ? (a < 1.0f ? a : 1.0f) : 0.0f));
                        dst[0] = dst[1] = dst[2] = g;
                    } else { /* not available */
                        dst[0] = 40; dst[1] = 60; dst[2] = 140;
                    }
                }
    }
    rc = sbl_png_write_rgb8(path, img, W, H);
    free(img);
    return rc;
}

static void usage(void)
{
    fprintf(stderr, "usage: sblexr SCENE_DIR OUT_DIR [--method NAME] [--frames N] [--sheet FRAME]\n"
                    "       (no --method: the default temporal filter, its evidence and tail planes carried,\n"
                    "       its display written;\n"
                    "       default-stereo: the default temporal filter then the default stereo blend)\n"
                    "       sblexr --list        (the method names)\n");
}

int main(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *method = "default";
    int frames = 0, sheet = -1, i;
    sbr_seq seq;
    sbr_method m;
    sbr_result r;
    writer wr;
    char err[512], dir[2048];
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--list") == 0) {
            sbr_method all[SBR_MAX_METHODS];
            int n = sbr_standard_methods(all, SBR_MAX_METHODS), k;
            for (k = 0; k < n; ++k) printf("%s\n", all[k].name);
            return 0;
        } else if (strcmp(argv[i], "--method") == 0 && i + 1 < argc) method = argv[++i];
        else if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) frames = atoi(argv[++i]);
        else if (strcmp(argv[i], "--sheet") == 0 && i + 1 < argc) sheet = atoi(argv[++i]);
        else if (argv[i][0] == '-') { usage(); return 2; }
        else if (!scene) scene = argv[i];
        else if (!out) out = argv[i];
        else { usage(); return 2; }
    }
    if (!scene || !out) { usage(); return 2; }
    if (!sbl_exr_available()) {
        fprintf(stderr, "sblexr: built without OpenEXR (install libopenexr-dev and rebuild)\n");
        return 3;
    }
    if (sbr_find_method(method, &m) != 0) {
        fprintf(stderr, "sblexr: unknown method '%s' (sblexr --list)\n", method);
        return 2;
    }
    if (sbr_seq_dataset(&seq, scene, frames, err, sizeof err) != 0) {
        fprintf(stderr, "sblexr: %s\n", err);
        return 1;
    }
    snprintf(dir, sizeof dir, "%s/L", out);
    if (make_dir(out) || make_dir(dir)) return 1;
    snprintf(dir, sizeof dir, "%s/R", out);
    if (make_dir(dir)) return 1;
    memset(&wr, 0, sizeof wr);
    wr.out = out;
    wr.sheet_frame = sheet;
    if (sheet >= seq.frames) {
        fprintf(stderr, "sblexr: --sheet %d: the sequence has frames 0..%d\n", sheet, seq.frames - 1);
        return 2;
    }
    if (sbr_run_alpha(&seq, &m, &r, write_frame, sheet >= 0 ? keep_alpha : NULL, &wr) != 0 || wr.failed)
        return 1;
    printf("scene %s (%dx%d, %d frames), method %s: %.3f ms per stereo frame", seq.name,
           seq.width, seq.height, seq.frames, m.name, r.ms);
    if (r.eval_frames)
        printf(", RMSE %.5f, SSIM %.4f, effective spp %.2f (ladder), %.2f (independent 1-spp samples)",
               r.rmse, r.ssim, r.eff_spp, r.indep_spp);
    if (m.stereo == SBR_STEREO_FILL) printf(", right-eye pixels traced %.2f%%", r.traced_pct);
    if (r.eval_frames)
        printf("\nbright pixels (a reference channel above %g x the image mean): %.3f %% of the pixels, "
               "%.1f %% of the MSE; RMSE over the other pixels %.5f",
               SBR_BRIGHT, r.bright_px_pct, r.bright_mse_pct, r.rmse_dim);
    printf("\nwrote %s/{L,R}/0000.exr .. %04d.exr\n", out, seq.frames - 1);
    if (sheet >= 0) {
        snprintf(dir, sizeof dir, "%s/sheet_%04d.png", out, sheet);
        if (write_sheet(dir, &seq, &wr, sheet) != 0) { perror(dir); return 1; }
        printf("wrote %s: rows left, right eye; columns input, output, reference, |error| x4, alpha\n", dir);
    }
    for (i = 0; i < 2; ++i) { free(wr.sheet_out[i]); free(wr.sheet_alpha[i]); }
    sbr_seq_free(&seq);
    return 0;
}
