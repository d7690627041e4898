/* cr_seeds.c - the default temporal filter and the default combined pipeline with the
   bilinear and the Catmull-Rom history fetch, on one synthetic scene rendered with
   several noise seeds (the bench uses seed 7): is a difference between the two fetches
   systematic or the noise of one render? Prints effective spp (RMSE) per method.
     cc -O2 -Ibench -Itools bench/cr_seeds.c -o build/cr_seeds -lm
     ./build/cr_seeds KIND FIRST_SEED LAST_SEED     (KIND: 0 dynamic .. 3 pan, sbl_scene.h) */
#define _POSIX_C_SOURCE 199309L /* clock_gettime (sbl_runner.h) */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"
#define SBR_NO_DATASET
#define SBL_RUNNER_IMPLEMENTATION
#include "sbl_runner.h"
#include <stdlib.h>
int main(int argc, char **argv)
{
    int kind, s0, s1, seed, i;
    const char *names[4] = {"default", "default-cr", "default-stereo", "default-stereo-cr"};
    if (argc != 4) {
        fprintf(stderr, "usage: cr_seeds KIND FIRST_SEED LAST_SEED\n");
        return 2;
    }
    kind = atoi(argv[1]); s0 = atoi(argv[2]); s1 = atoi(argv[3]);
    for (seed = s0; seed <= s1; ++seed) {
        sbl_scene_desc d; sbr_seq seq;
        memset(&d, 0, sizeof d);
        d.kind = (sbl_scene_kind)kind; d.jitter = kind == SBL_SCENE_DYNAMIC;
        d.width = 160; d.height = 90; d.frames = 24; d.ref_spp = 128; d.seed = (unsigned)seed;
        if (sbr_seq_synthetic(&seq, &d, "s", 1)) return 1;
        printf("kind %d seed %d:", kind, seed);
        for (i = 0; i < 4; ++i) {
            sbr_method m; sbr_result r;
            sbr_find_method(names[i], &m);
            sbr_run(&seq, &m, &r, NULL, NULL);
            printf(" %s %.3f (%.5f)", names[i], r.eff_spp, r.rmse);
        }
        printf("\n"); fflush(stdout);
        sbr_seq_free(&seq);
    }
    return 0;
}
