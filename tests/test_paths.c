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
        for (i = 0; i < 3; ++i) sbl__ring_load(&k, &k.ring[i], i);
        R[0] = &k.ring[0]; R[1] = &k.ring[1]; R[2] = &k.ring[2];
        if (!(R[0]->lane_safe && R[1]->lane_safe && R[2]->lane_safe)) {
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
    return sbt_finish("test_paths");
}
