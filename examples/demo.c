/* make demo: the library's main job on a built-in scene. Renders a small synthetic
   stereo sequence (moving camera with head-tracking jitter, a moving ball that
   disoccludes, a moving light, glossy highlights, thin posts), runs every method of the
   standard table over it and prints RMSE / SSIM / effective spp against the reference
   and the time per stereo frame. */
#define _POSIX_C_SOURCE 199309L
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"
#define SBL_RUNNER_IMPLEMENTATION
#define SBR_NO_DATASET
#include "../bench/sbl_runner.h"
#include <stdio.h>

int main(int argc, char **argv)
{
    sbl_scene_desc d;
    sbr_seq seq;
    sbr_method methods[32];
    int n, i;
    double t0;
    memset(&d, 0, sizeof d);
    d.kind = SBL_SCENE_DYNAMIC;
    d.jitter = 1;
    d.width = 128;
    d.height = 72;
    d.frames = 16;
    d.ref_spp = 64;
    d.seed = 1;
    if (argc > 1) d.frames = atoi(argv[1]);
    t0 = sbr_now_ms();
    if (sbr_seq_synthetic(&seq, &d, "synthetic-dynamic", 1) != 0) {
        fprintf(stderr, "scene render failed\n");
        return 1;
    }
    printf("stereoblend.h demo: synthetic stereo scene %dx%d, %d frames, 2 eyes, 1 spp input,\n"
           "reference %d spp (rendered in %.1f s). Metrics over frames %d..%d, both eyes.\n"
           "ms = library time per stereo frame (both eyes), median; eff spp = n-spp render of\n"
           "equal RMSE; traced = right-eye pixels that still needed a ray.\n\n",
           seq.width, seq.height, seq.frames, d.ref_spp, (sbr_now_ms() - t0) / 1000.0,
           seq.frames / 4, seq.frames - 1);
    printf("%-22s %8s %8s %7s %8s %8s\n", "method", "ms", "RMSE", "SSIM", "eff_spp", "traced%");
    n = sbr_standard_methods(methods, 32);
    for (i = 0; i < n; ++i) {
        sbr_result r;
        if (sbr_run(&seq, &methods[i], &r, NULL, NULL) != 0) return 1;
        printf("%-22s %8.3f %8.5f %7.4f %8.2f %8.1f\n", methods[i].name, r.ms, r.rmse, r.ssim,
               r.eff_spp, r.traced_pct);
    }
    sbr_seq_free(&seq);
    return 0;
}
