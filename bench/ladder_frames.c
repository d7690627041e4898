/* Per ladder frame and eye: the RMSE and effective spp of a default method (the knife
   edge of a scene whose ladder is not monotonic, docs/ESTIMATORS.md 3.8). Scratch, not
   in the Makefile: gcc -std=c99 -O2 -Itools $(pkg-config --cflags OpenEXR)
   bench/ladder_frames.c tools/sbl_dataset.c tools/sbl_exr.c -o build/ladder_frames
   $(pkg-config --libs OpenEXR) -lm; usage: ladder_frames default-stereo ../shared/data/gallery */
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
static sbr_seq seq;
static void cb(void *ctx, int f, int e, const float *rgb, int w, int h)
{
    int i, k;
    (void)ctx;
    for (i = 0; i < seq.ladder_count; ++i) {
        const sbr_ladder *l = &seq.ladder[i];
        double spp[SBR_MAX_LADDER], r[SBR_MAX_LADDER], rm;
        if (l->frame != f || f < seq.frames / 4) continue;
        for (k = 0; k < l->count; ++k) { spp[k] = l->spp[k]; r[k] = sbl_metric_rmse(l->img[e][k], w * 3, seq.views[f * 2 + e].ref, w * 3, w, h, 3); }
        rm = sbl_metric_rmse(rgb, w * 3, seq.views[f * 2 + e].ref, w * 3, w, h, 3);
        printf("frame %2d eye %d rmse %.5f eff %.3f  ladder rmse:", f, e, rm, sbl_metric_effective_spp(rm, spp, r, l->count));
        for (k = 0; k < l->count; ++k) printf(" %g:%.4f", spp[k], r[k]);
        printf("\n");
    }
}
int main(int argc, char **argv)
{
    char err[256];
    sbr_method m = sbr_method_default(argv[1], strstr(argv[1], "stereo") ? SBR_STEREO_ADAPTIVE : SBR_STEREO_NONE);
    sbr_result r;
    (void)argc;
    if (sbr_seq_dataset(&seq, argv[2], 0, err, sizeof err) != 0) { printf("%s\n", err); return 1; }
    sbr_run(&seq, &m, &r, cb, NULL);
    printf("%s: rmse %.5f eff %.3f\n", argv[1], r.rmse, r.eff_spp);
    return 0;
}
