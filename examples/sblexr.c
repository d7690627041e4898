/* sblexr - run a stereoblend.h method over a rendered stereo sequence (EXR, in the
   layout of shared/data/atrium: meta.json, cameras.json, exr/{noisy,ref,gbuf,ladder})
   and write the filtered frames as RGB float EXR: <out>/<eye>/<frame>.exr, eye L or R.
   Prints RMSE / SSIM / effective spp where references exist.

   usage: sblexr SCENE_DIR OUT_DIR [--method NAME] [--frames N] [--list]
   No --method: the library's default temporal filter (every descriptor field zero);
   --method default-stereo: the default combined pipeline (temporal per eye, then the
   default stereo blend for display). These two names stay stable.
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
#include <stdio.h>
#include <sys/stat.h>
#include <errno.h>

typedef struct writer { const char *out; int failed; } writer;

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
}

static int make_dir(const char *p)
{
    if (mkdir(p, 0777) != 0 && errno != EEXIST) { perror(p); return 1; }
    return 0;
}

static void usage(void)
{
    fprintf(stderr, "usage: sblexr SCENE_DIR OUT_DIR [--method NAME] [--frames N]\n"
                    "       (no --method: the default temporal filter; default-stereo: the\n"
                    "       default temporal filter then the default stereo blend)\n"
                    "       sblexr --list        (the method names)\n");
}

int main(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL, *method = "default";
    int frames = 0, i;
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
    wr.out = out;
    wr.failed = 0;
    if (sbr_run(&seq, &m, &r, write_frame, &wr) != 0 || wr.failed) return 1;
    printf("scene %s (%dx%d, %d frames), method %s: %.3f ms per stereo frame", seq.name,
           seq.width, seq.height, seq.frames, m.name, r.ms);
    if (r.eval_frames)
        printf(", RMSE %.5f, SSIM %.4f, effective spp %.2f (ladder), %.2f (independent 1-spp samples)",
               r.rmse, r.ssim, r.eff_spp, r.indep_spp);
    if (m.stereo == SBR_STEREO_FILL) printf(", right-eye pixels traced %.2f%%", r.traced_pct);
    printf("\nwrote %s/{L,R}/0000.exr .. %04d.exr\n", out, seq.frames - 1);
    sbr_seq_free(&seq);
    return 0;
}
