/* The two paths of the fused row kernel against each other on the same ring rows: the
   SIMD lane kernel (float) and the reference path (double) must agree in semantics,
   not only in the tests that happen to exercise one of them. Calls the internal
   kernel directly, so it includes the implementation statically. Random rows for every
   estimator, rectification, weight mode, temporal / stereo / stereo fill, 1-4 channels,
   some invalid x*, and (for stereo) an own N that is sometimes +inf (which the lane
   kernel must refuse like the reference path sanitises it). */
#define STEREOBLEND_STATIC
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"

#define PW 40
#define PH 3
typedef struct paths_gather { float x[PH][PW][4]; float n[PH][PW]; } paths_gather;

static float paths_gather_fn(const void *ctx, int x, int y, float *out)
{
    const paths_gather *g = (const paths_gather *)ctx;
    int c;
    for (c = 0; c < 4; ++c) out[c] = g->x[y][x][c];
    return g->n[y][x];
}

/* Column spans and row bands of the kernel against one whole-image run, bit for bit:
   the lane / reference choice and the gathered values must not depend on the range.
   Random images with isolated values outside the lane range (tiny, denormal, huge,
   NaN), so that spans start and end next to pixels of either path. */
#define SW 53
#define SH 9
typedef struct span_gather { float x[SH][SW][4]; float n[SH][SW]; } span_gather;

static float span_gather_fn(const void *ctx, int x, int y, float *out)
{
    const span_gather *g = (const span_gather *)ctx;
    int c;
    for (c = 0; c < 4; ++c) out[c] = g->x[y][x][c];
    return g->n[y][x];
}

static void test_spans(void)
{
    static float own[SH * SW * 4], own_n[SH * SW], whole[3][SH * SW * 4], part[3][SH * SW * 4];
    static span_gather G;
    static const float odd[5] = {1e-14f, 1e-39f, 3e16f, 0.0f, 2e-13f};
    sbt_rng rng = {4242};
    int it, spans = 0, mismatches = 0;
    void *scratch = malloc(sbl__kernel_scratch_size(SW, 4));
    for (it = 0; it < 400; ++it) {
        sbl__kernel k;
        sbl_image im, imn;
        int ch = 1 + it % 4, stereo = (it >> 2) & 1, x, y, c, t, o, w = it % 3 == 0 ? 17 : SW;
        for (y = 0; y < SH; ++y)
            for (x = 0; x < SW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * SW + x) * 4 + c] = (float)(0.1 + sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.1 + sbt_uniform(&rng));
                }
                G.n[y][x] = sbt_uniform(&rng) < 0.2 ? 0.0f : (float)(1 + 40 * sbt_uniform(&rng));
                own_n[y * SW + x] = (float)(1 + 30 * sbt_uniform(&rng));
            }
        for (t = 0; t < 1 + it % 6; ++t) {
            int tx = (int)(sbt_uniform(&rng) * SW), ty = (int)(sbt_uniform(&rng) * SH);
            float v = t == 5 ? (float)HUGE_VAL - (float)HUGE_VAL : odd[t];
            if (t & 1) G.x[ty][tx][t % 4] = v;
            else own[(ty * SW + tx) * 4 + t % 4] = v;
        }
        memset(&k, 0, sizeof k);
        im = sbl_image_make(own, w, SH, 4);
        im.stride = SW * 4;
        im.channels = ch;
        imn = sbl_image_make(own_n, w, SH, 1);
        imn.stride = SW;
        k.w = w; k.h = SH; k.ch = ch;
        k.wp.estimator = (sbl_estimator)(it % SBL_ESTIMATOR_COUNT);
        k.wp.rectify = (sbl_rectify)((it / 4) % SBL_RECTIFY_COUNT);
        k.wp.mode = (sbl_weight_mode)((it / 12) % SBL_WEIGHT_MODE_COUNT);
        k.wp.constant = 0.3f;
        k.wp.gamma = 1.25f;
        k.wp.bias_threshold = 3.0f;
        k.n_cap = stereo ? FLT_MAX : 64.0f;
        k.temporal = !stereo;
        k.own = &im;
        k.own_n = stereo ? &imn : NULL;
        k.gather = span_gather_fn;
        k.gather_ctx = &G;
        k.out = sbl_image_make(whole[0], w, SH, 4);
        k.out.stride = SW * 4;
        k.out.channels = ch;
        k.out_n = sbl_image_make(whole[1], w, SH, 1);
        k.out_n.stride = SW;
        k.out_a = sbl_image_make(whole[2], w, SH, 1);
        k.out_a.stride = SW;
        sbl__kernel_bind(&k, scratch);
        sbl__kernel_run(&k, 0, SH);
        for (t = 0; t < 6; ++t) {
            int x0 = (int)(sbt_uniform(&rng) * w), x1 = x0 + 1 + (int)(sbt_uniform(&rng) * (w - x0));
            int y0 = (int)(sbt_uniform(&rng) * SH), y1 = y0 + (int)(sbt_uniform(&rng) * (SH + 1 - y0));
            if (t == 0) { x0 = 0; x1 = w; } /* row bands */
            for (o = 0; o < 3; ++o)
                for (x = 0; x < SH * SW * 4; ++x) part[o][x] = -7.0f;
            k.out.data = part[0]; k.out_n.data = part[1]; k.out_a.data = part[2];
            /* poison the scratch (NaN): a value the span did not load cannot pass */
            memset(scratch, 0xff, sbl__kernel_scratch_size(SW, 4));
            sbl__kernel_run_span(&k, y0, y1, x0, x1);
            for (y = 0; y < SH; ++y)
                for (x = 0; x < w; ++x) {
                    int in = y >= y0 && y < y1 && x >= x0 && x < x1, bad = 0;
                    for (c = 0; c < ch; ++c) {
                        /* colour rows are SW * 4 floats apart, pixels ch apart */
                        float a = whole[0][y * SW * 4 + x * ch + c], b = part[0][y * SW * 4 + x * ch + c];
                        bad |= in ? memcmp(&a, &b, sizeof a) != 0 : b != -7.0f;
                    }
                    bad |= in ? memcmp(&whole[1][y * SW + x], &part[1][y * SW + x], 4) != 0
                              : part[1][y * SW + x] != -7.0f;
                    bad |= in ? memcmp(&whole[2][y * SW + x], &part[2][y * SW + x], 4) != 0
                              : part[2][y * SW + x] != -7.0f;
                    if (bad && mismatches < 5)
                        printf("  span case %d: [%d,%d)x[%d,%d) differs at (%d,%d)\n", it, x0, x1, y0,
                               y1, x, y);
                    mismatches += bad;
                }
            k.out.data = whole[0]; k.out_n.data = whole[1]; k.out_a.data = whole[2];
            ++spans;
        }
    }
    printf("  %s kernel spans vs whole run: %d spans, %d pixels differ\n", SBL_SIMD_NAME, spans,
           mismatches);
    CHECK(mismatches == 0);
    free(scratch);
}

int main(void)
{
    static float own[PH * PW * 4], own_n[PH * PW], outc[PH * PW * 4], outn[PH * PW], outa[PH * PW];
    static paths_gather G;
    sbt_rng rng = {77};
    double worst = 0;
    int it, compared = 0, refused = 0;
    for (it = 0; it < 5000; ++it) {
        sbl__kernel k;
        sbl_image im, imn;
        void *scratch;
        const sbl__ring_row *R[3];
        float lane_c[PW][4], lane_n[PW], lane_a[PW];
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, c, i, stereo = it & 1;
        float ny = (it % 7 == 0) ? (float)HUGE_VAL : (float)(1 + 30 * sbt_uniform(&rng));
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * PW + x) * 4 + c] = (float)(0.1 + sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.1 + sbt_uniform(&rng));
                }
                G.n[y][x] = sbt_uniform(&rng) < 0.2 ? 0.0f : (float)(1 + 40 * sbt_uniform(&rng));
                own_n[y * PW + x] = ny;
            }
        memset(&k, 0, sizeof k);
        im = sbl_image_make(own, PW, PH, 4);
        im.channels = ch;
        imn = sbl_image_make(own_n, PW, PH, 1);
        k.w = PW; k.h = PH; k.ch = ch;
        k.wp.estimator = (sbl_estimator)(it % SBL_ESTIMATOR_COUNT);
        k.wp.rectify = (sbl_rectify)((it / 4) % SBL_RECTIFY_COUNT);
        k.wp.mode = (sbl_weight_mode)((it / 12) % SBL_WEIGHT_MODE_COUNT);
        k.wp.constant = stereo ? 0.5f : 0.1f;
        k.wp.gamma = 1.25f;
        k.wp.bias_threshold = 3.0f;
        k.n_cap = stereo ? FLT_MAX : 64.0f;
        k.temporal = !stereo;
        k.fill = stereo && (it % 8 == 1);
        k.own = &im;
        k.own_n = stereo ? &imn : NULL;
        k.gather = paths_gather_fn;
        k.gather_ctx = &G;
        k.out = sbl_image_make(outc, PW, PH, 4);
        k.out.channels = ch;
        k.out_n = sbl_image_make(outn, PW, PH, 1);
        k.out_a = sbl_image_make(outa, PW, PH, 1);
        scratch = malloc(sbl__kernel_scratch_size(PW, ch));
        sbl__kernel_bind(&k, scratch);
        for (i = 0; i < 3; ++i) sbl__ring_load(&k, &k.ring[i], i, 0, PW);
        R[0] = &k.ring[0]; R[1] = &k.ring[1]; R[2] = &k.ring[2];
        if (R[0]->unsafe_count || R[1]->unsafe_count || R[2]->unsafe_count) {
            /* only an infinite own N may make these rows unsafe */
            CHECK(stereo && !sbl__finite(ny));
            ++refused;
            free(scratch);
            continue;
        }
        CHECK(sbl__finite(ny) || !stereo);
        x = sbl__kernel_lanes(&k, R, 1, PW - 1);
        if (x < PW - 1) sbl__kernel_lanes(&k, R, PW - 1 - SBL__VW, PW - 1);
        for (x = 1; x < PW - 1; ++x) {
            for (c = 0; c < ch; ++c) lane_c[x][c] = k.stage[c][x];
            lane_n[x] = k.stage_n[x];
            lane_a[x] = k.stage_a[x];
        }
        for (x = 1; x < PW - 1; ++x) sbl__kernel_pixel_ref(&k, R, x);
        for (x = 1; x < PW - 1; ++x) {
            double e = fabs(lane_a[x] - k.stage_a[x]);
            double en = fabs(lane_n[x] - k.stage_n[x]) / (fabs(k.stage_n[x]) + 1.0);
            if (en > e) e = en;
            for (c = 0; c < ch; ++c) {
                double ec = fabs(lane_c[x][c] - k.stage[c][x]);
                if (!(ec <= e)) e = ec;
            }
            if (!(e <= 1e-4))
                printf("  case %d (est %d rect %d mode %d stereo %d fill %d ch %d) x %d: lane c0 %.6f n %g a %.5f, ref c0 %.6f n %g a %.5f\n",
                       it, k.wp.estimator, k.wp.rectify, k.wp.mode, stereo, k.fill, ch, x, lane_c[x][0],
                       lane_n[x], lane_a[x], k.stage[0][x], k.stage_n[x], k.stage_a[x]);
            CHECK(e <= 1e-4);
            if (e > worst) worst = e;
            ++compared;
        }
        free(scratch);
    }
    printf("  %s lane kernel vs double reference: %d pixels, worst difference %.3g; %d cases refused (own N = inf)\n",
           SBL_SIMD_NAME, compared, worst, refused);
    CHECK(refused > 0);
    test_spans();
    return sbt_finish("test_paths");
}
