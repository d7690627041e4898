/* Are a rendered scene's reference spikes real, or the reference's own fireflies? A pixel
   whose reference channel sum is above 30 and 10 times its 3x3 median is a spike; an
   independent render (the ladder's highest rung, another seed) sees a real one at the same
   value and regresses a firefly of the reference to its neighbours. Scratch, not in the
   Makefile: cc -std=c99 -O1 -Itools -Ibench $(pkg-config --cflags OpenEXR) bench/ref_spikes.c
   tools/sbl_dataset.c tools/sbl_exr.c -o build/ref_spikes $(pkg-config --libs OpenEXR) -lm;
   usage: build/ref_spikes ../shared/data/gallery (docs/RESULTS.md, session 25) */
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
static int cmpd(const void *a, const void *b) { double x = *(const double *)a, y = *(const double *)b; return x < y ? -1 : x > y; }
int main(int argc, char **argv)
{
    sbr_seq seq; char err[256]; int i, e;
    if (argc < 2) { printf("usage: ref_spikes SCENE_DIR\n"); return 2; }
    if (sbr_seq_dataset(&seq, argv[1], 0, err, sizeof err)) { printf("%s\n", err); return 1; }
    for (i = 0; i < seq.ladder_count; ++i) {
        const sbr_ladder *l = &seq.ladder[i];
        int f = l->frame, w = seq.width, h = seq.height, x, y, top = l->count - 1;
        for (e = 0; e < 2; ++e) {
            const float *ref = seq.views[f * 2 + e].ref, *lad = l->img[e][top], *in = seq.views[f * 2 + e].color;
            double sr = 0, sl = 0, sm = 0, sl2 = 0, sin = 0; int n = 0, nl = 0;
            for (y = 1; y < h - 1; ++y) for (x = 1; x < w - 1; ++x) {
                double v[9], r, med; int a = 0, dx, dy;
                for (dy = -1; dy <= 1; ++dy) for (dx = -1; dx <= 1; ++dx) {
                    const float *p = ref + ((size_t)(y + dy) * w + x + dx) * 3; v[a++] = (double)p[0] + p[1] + p[2]; }
                r = v[4]; qsort(v, 9, sizeof v[0], cmpd); med = v[4];
                if (r > 30.0 && r > 10.0 * med) {
                    const float *q = lad + ((size_t)y * w + x) * 3, *s = in + ((size_t)y * w + x) * 3;
                    const double lv = (double)q[0] + q[1] + q[2];
                    sr += r; sl += lv; sm += med; n++; sin += (double)s[0] + s[1] + s[2];
                    /* the ladder's own 3x3 median: is its pixel above its neighbours too? */
                    { double u[9]; a = 0; for (dy = -1; dy <= 1; ++dy) for (dx = -1; dx <= 1; ++dx) {
                        const float *p = lad + ((size_t)(y + dy) * w + x + dx) * 3; u[a++] = (double)p[0] + p[1] + p[2]; }
                      qsort(u, 9, sizeof u[0], cmpd); if (lv > 3.0 * u[4] + 1.0) nl++; sl2 += u[4]; }
                }
            }
            if (n) printf("frame %2d eye %d: %3d ref spikes; mean ref %.1f, ref 3x3 median %.1f, ladder %d spp at them %.1f (its 3x3 median %.1f, %d of %d above 3x), 1-spp input %.1f\n",
                          f, e, n, sr / n, sm / n, l->spp[top], sl / n, sl2 / n, nl, n, sin / n);
        }
    }
    return 0;
}
