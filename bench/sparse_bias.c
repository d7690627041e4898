/* Hit-or-miss samples: does a temporal filter keep the mean? (docs/ESTIMATORS.md 2.3,
   session 30.) A static grey image in vertical bands, every band of mean mu = 0.5:
     hit p     every 1-spp sample is mu / p with probability p and 0 otherwise: what a
               renderer returns for a small light sampled once per pixel, a caustic, a
               sub-pixel highlight (p = 0.02, 0.05, 0.1, 0.2, 0.5);
     spike r,g the other side of the trade: a body with noise (uniform, +-50 % of it) whose
               sample is (1 + g) times larger with probability r, scaled by 1 / (1 + r g)
               (r = 0.02, g = 25 as the bench's synthetic-firefly; r = 0.005, g = 100).
               Here the firefly limit lowers the error, at the price of a bias.
   No motion, so the history's fetch is exact and any bias is the weights'. Each estimator
   runs 60 frames through sbl_temporal_filter (the pooled default with its evidence and
   tail planes, as examples/minimal.c and build/sblexr run it); frames 20..59 are scored,
   away from the band edges:
     bias    mean of (output - mu) / mu          (an unbiased filter: about 0)
     RMSE    against mu                          (hit bands: progressive averaging is the
                                                  floor for an unbiased per-pixel mean)
     a|hit   mean weight of the new sample where it is a hit (spike bands: a sample above
             2 mu); a|miss elsewhere. A weight that depends on the sample (larger on
             misses) biases the mean down.
     kept    the share of a hit's excess over the history that reaches the output: for a
             default-configuration pixel (exact fetch, no clamp) out = x* + a (y' - x*),
             so y' = x* + (out - x*) / a is the sample the blend used; kept = mean of
             (y' - x*) / (y - x*) over hits. 1 without a firefly limit.
   cc -std=c99 -O2 -I. bench/sparse_bias.c -o build/sparse_bias -lm && ./build/sparse_bias */
#define STEREOBLEND_IMPLEMENTATION
#include "stereoblend.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "mc_rng.h"

enum { W = 280, H = 120, CH = 3, FRAMES = 60, SCORED_FROM = 20, BANDS = 7, MARGIN = 3 };
typedef struct band_kind {
    double rate; /* p of a hit, or r of a spike */
    double gain; /* 0: hit-or-miss; else the spike's g */
} band_kind;
static const band_kind BAND[BANDS] = {{0.02, 0}, {0.05, 0}, {0.1, 0}, {0.2, 0}, {0.5, 0}, {0.02, 25}, {0.005, 100}};
static const double MU = 0.5;

typedef struct method {
    const char *name;
    sbl_estimator estimator;
    sbl_rectify rectify;
    int evidence; /* carry the evidence plane (the default's full configuration) */
    int tail;     /* carry the tail plane (sbl_history.tail; the default's full configuration) */
} method;

typedef struct band_stats {
    double err, err2, n;             /* output - mu */
    double a_hit, n_hit, a_miss, n_miss;
    double kept, n_kept;
} band_stats;

static int run(const method *m, band_stats *bs)
{
    const size_t n = (size_t)W * H;
    float *rgb = (float *)malloc(n * CH * sizeof(float));
    float *alpha = (float *)malloc(n * sizeof(float));
    float *depth = (float *)malloc(n * sizeof(float));
    float *motion = (float *)calloc(n * 2, sizeof(float));
    float *hist[2], *len[2], *evid[2], *tail[2];
    const size_t scratch_bytes = sbl_temporal_scratch_size(W, CH);
    void *scratch = malloc(scratch_bytes);
    sbl_temporal_desc td;
    int f, b, ping = 0, rc = 0;
    size_t i;
    for (b = 0; b < 2; ++b) {
        hist[b] = (float *)malloc(n * CH * sizeof(float));
        len[b] = (float *)malloc(n * sizeof(float));
        evid[b] = (float *)malloc(n * sizeof(float));
        tail[b] = (float *)malloc(n * 2 * sizeof(float));
        if (!hist[b] || !len[b] || !evid[b] || !tail[b]) rc = (int)SBL_ERROR_OUT_OF_MEMORY;
    }
    if (!rgb || !alpha || !depth || !motion || !scratch) rc = (int)SBL_ERROR_OUT_OF_MEMORY;
    for (i = 0; rc == 0 && i < n; ++i) depth[i] = 2.0f;
    memset(&td, 0, sizeof td);
    td.estimator = m->estimator;
    td.rectify = m->rectify;
    memset(bs, 0, BANDS * sizeof *bs);
    rng_state = 88172645463325252ull; /* the same samples for every method */
    for (f = 0; f < FRAMES && rc == 0; ++f) {
        sbl_frame cur;
        sbl_history prev;
        sbl_temporal_output out;
        memset(&cur, 0, sizeof cur);
        memset(&prev, 0, sizeof prev);
        memset(&out, 0, sizeof out);
        for (i = 0; i < n; ++i) {
            const band_kind *bd = &BAND[(i % W) * BANDS / W];
            float v;
            int c;
            if (bd->gain == 0.0) {
                v = uniform01() < bd->rate ? (float)(MU / bd->rate) : 0.0f;
            } else {
                const double body = MU * (0.5 + uniform01()); /* mean MU */
                const double g = uniform01() < bd->rate ? 1.0 + bd->gain : 1.0;
                v = (float)(body * g / (1.0 + bd->rate * bd->gain));
            }
            for (c = 0; c < CH; ++c) rgb[i * CH + c] = v;
        }
        cur.color = sbl_image_make(rgb, W, H, CH);
        cur.gbuffer.depth = sbl_image_make(depth, W, H, 1);
        cur.gbuffer.motion = sbl_image_make(motion, W, H, 2);
        prev.color = sbl_image_make(hist[ping], W, H, CH);
        prev.length = sbl_image_make(len[ping], W, H, 1);
        prev.gbuffer.depth = sbl_image_make(depth, W, H, 1);
        out.color = sbl_image_make(hist[!ping], W, H, CH);
        out.length = sbl_image_make(len[!ping], W, H, 1);
        out.alpha = sbl_image_make(alpha, W, H, 1);
        if (m->evidence) {
            prev.evidence = sbl_image_make(evid[ping], W, H, 1);
            out.evidence = sbl_image_make(evid[!ping], W, H, 1);
        }
        if (m->tail) {
            prev.tail = sbl_image_make(tail[ping], W, H, 2);
            out.tail = sbl_image_make(tail[!ping], W, H, 2);
        }
        rc = (int)sbl_temporal_filter(&td, &cur, f ? &prev : NULL, &out, 0, H, scratch, scratch_bytes);
        if (rc == 0 && f >= SCORED_FROM) {
            for (i = 0; i < n; ++i) {
                const int x = (int)(i % W), band = x * BANDS / W, in_band = x - band * W / BANDS;
                const double o = hist[!ping][i * CH], xs = hist[ping][i * CH], y = rgb[i * CH];
                const double a = alpha[i];
                band_stats *s = &bs[band];
                if (in_band < MARGIN || in_band >= W / BANDS - MARGIN) continue;
                s->err += o - MU;
                s->err2 += (o - MU) * (o - MU);
                s->n += 1.0;
                if (BAND[band].gain == 0.0 ? y > 0.0 : y > 2.0 * MU) { /* a hit / a spike */
                    s->a_hit += a;
                    s->n_hit += 1.0;
                    if (a > 1e-4 && y - xs > 1e-3) {
                        s->kept += ((o - xs) / a) / (y - xs);
                        s->n_kept += 1.0;
                    }
                } else {
                    s->a_miss += a;
                    s->n_miss += 1.0;
                }
            }
        }
        ping = !ping;
    }
    if (rc != 0) fprintf(stderr, "%s: %s\n", m->name, sbl_result_string((sbl_result)rc));
    for (b = 0; b < 2; ++b) { free(hist[b]); free(len[b]); free(evid[b]); free(tail[b]); }
    free(rgb); free(alpha); free(depth); free(motion); free(scratch);
    return rc;
}

int main(void)
{
    static const method methods[] = {
        {"default (pooled, both planes)", SBL_ESTIMATOR_POOLED, SBL_RECTIFY_NONE, 1, 1},
        {"pooled, evidence, no tail", SBL_ESTIMATOR_POOLED, SBL_RECTIFY_NONE, 1, 0},
        {"pooled, no planes", SBL_ESTIMATOR_POOLED, SBL_RECTIFY_NONE, 0, 0},
        {"robust, tail plane", SBL_ESTIMATOR_ROBUST, SBL_RECTIFY_NONE, 0, 1},
        {"robust", SBL_ESTIMATOR_ROBUST, SBL_RECTIFY_NONE, 0, 0},
        {"history-aware", SBL_ESTIMATOR_HISTORY_AWARE, SBL_RECTIFY_NONE, 0, 0},
        {"paper", SBL_ESTIMATOR_PAPER, SBL_RECTIFY_NONE, 0, 0},
        {"progressive", SBL_ESTIMATOR_PROGRESSIVE, SBL_RECTIFY_NONE, 0, 0},
        {"constant 0.1", SBL_ESTIMATOR_CONSTANT, SBL_RECTIFY_NONE, 0, 0},
        {"constant 0.1 + clamp", SBL_ESTIMATOR_CONSTANT, SBL_RECTIFY_CLAMP, 0, 0},
    };
    band_stats bs[BANDS];
    int k, b;
    printf("hit-or-miss and spiky samples of mean mu = %.1f (bench/sparse_bias.c), %dx%d, frames %d..%d\n",
           MU, W, H, SCORED_FROM, FRAMES - 1);
    printf("%-30s %-15s %8s %8s %7s %7s %6s\n", "method", "samples", "bias", "RMSE", "a|hit", "a|miss", "kept");
    for (k = 0; k < (int)(sizeof methods / sizeof methods[0]); ++k) {
        if (run(&methods[k], bs) != 0) return 1;
        for (b = 0; b < BANDS; ++b) {
            const band_stats *s = &bs[b];
            char label[32];
            if (BAND[b].gain == 0.0) snprintf(label, sizeof label, "hit %.2f", BAND[b].rate);
            else snprintf(label, sizeof label, "spike %g,%g", BAND[b].rate, BAND[b].gain);
            printf("%-30s %-15s %+7.1f%% %8.4f %7.4f %7.4f", b ? "" : methods[k].name, label,
                   100.0 * s->err / s->n / MU, sqrt(s->err2 / s->n), s->a_hit / s->n_hit,
                   s->a_miss / s->n_miss);
            if (methods[k].rectify == SBL_RECTIFY_NONE && s->n_kept > 0.0)
                printf(" %6.3f\n", s->kept / s->n_kept);
            else
                printf(" %6s\n", "-");
        }
    }
    return 0;
}
