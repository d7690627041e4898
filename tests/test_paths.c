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

#define view sbt_view

#define PW 40
#define PH 3
/* a gather callback's image (the history's x* and N), room for the largest of the tests'
   images: PW x PH, and test_restart_lean_paths' 45 x 5 */
#define PGW 45
#define PGH 5
typedef struct paths_gather { float x[PGH][PGW][4]; float n[PGH][PGW]; } paths_gather;

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
        int ch = 1 + it % 4, stereo = (it >> 2) & 1, x, y, c, t, o, w = (it / SBL_ESTIMATOR_COUNT) % 3 == 0 ? 17 : SW;
        for (y = 0; y < SH; ++y)
            for (x = 0; x < SW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * SW + x) * 4 + c] = (float)(0.1 + sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.1 + sbt_uniform(&rng));
                }
                /* (every third case few invalid pairs, so that a chunk can be full in
                   one range and not in the other: the full chunk's column code is
                   another instance, which -ffast-math may round differently) */
                G.n[y][x] = sbt_uniform(&rng) < ((it / SBL_ESTIMATOR_COUNT) % 3 == 1 ? 0.01 : 0.2) ? 0.0f : (float)(1 + 40 * sbt_uniform(&rng));
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

/* The row gather against the pixel gather it replaces, bit for bit, on hostile
   content: taps outside the image, rejected taps (3x3 fallback on and off), NaN / inf /
   FLT_MAX / 0 / negative history colour and N, sky and invalid depth, zero, integer,
   huge and NaN motion in every unit convention, no N buffer, no depth buffer, a
   bottom-up history, depth and N with a pixel step of 2. */
#ifdef SBL__ROW_GATHER
/* 1 if this translation unit's compiler contracts a * b + c into a fused multiply-add
   (clang -mfma does, gcc in ISO C mode does not), or compiles with -ffast-math (which
   lets it reassociate and rewrite the float arithmetic of either path): then the pixel
   gather's sums may differ from the lanes' in the last bits, and the comparison allows
   1e-6 relative (1e-5 absolute where the sums cancel). The validity (ring v) is still
   compared bit for bit: a tap decision must not depend on the path. */
static int compiler_contracts(void)
{
#ifdef __FAST_MATH__
    return 1;
#else
    volatile float a = 1.0f + 1.0f / 4096.0f, c = -(1.0f + 1.0f / 2048.0f);
    float b = a;
    return a * b + c != 0.0f;
#endif
}

static int same_float(float a, float b, int contracts)
{
    if (memcmp(&a, &b, sizeof a) == 0) return 1;
    /* colours here are of order 1 and may cancel: an absolute floor of 1e-5 */
    return contracts && fabs((double)a - b) <= 1e-6 * (fabs(a) + fabs(b)) + 1e-5;
}
#endif

#ifdef SBL__ROW_GATHER
/* Row y's pixels [xa, xb): the row gather's ring row ra against the pixel gather written
   into rb, bit for bit (within same_float where the compiler contracts); counts pixels,
   mismatches and pixels the pixel gather left without history (*empty). */
static void compare_with_pixel_gather(sbl__temporal_rp *rp, const sbl__ring_row *ra, sbl__ring_row *rb,
                                      int y, int xa, int xb, int ch, int contracts, const char *what,
                                      int it, int w, int h, int *pixels, int *mismatches, int *empty)
{
    int x, c;
    for (x = xa; x < xb; ++x) {
        float tmp[4] = {0, 0, 0, 0};
        sbl__ring_put(rb, x, sbl__temporal_rp_pixel(rp, x, y, tmp), tmp, ch);
    }
    for (x = xa; x < xb; ++x) {
        int bad = !same_float(ra->n[x], rb->n[x], contracts) || memcmp(&ra->v[x], &rb->v[x], 4) != 0;
        for (c = 0; c < ch; ++c) bad |= !same_float(ra->x[c][x], rb->x[c][x], contracts);
        if (bad && *mismatches < 5)
            printf("  %s case %d (%dx%dx%d) pixel (%d,%d): n %.9g vs %.9g, x0 %.9g vs %.9g\n", what,
                   it, w, h, ch, x, y, ra->n[x], rb->n[x], ra->x[0][x], rb->x[0][x]);
        *mismatches += bad;
        *empty += !(rb->n[x] > 0.0f);
        ++*pixels;
    }
}

/* The stereo counterpart: row y of the stereo row gather (all w pixels) in ra against
   the pixel gather written into rb */
static void compare_stereo_with_pixel_gather(sbl__stereo_rp *rp, sbl__ring_row *ra, sbl__ring_row *rb, int y,
                                             int w, int ch, int contracts, const char *what, int it, int rig,
                                             int *pixels, int *mismatches, int *empty)
{
    int x, c;
    sbl__stereo_rp_row(rp, ra, y, 0, w);
    for (x = 0; x < w; ++x) {
        float tmp[4] = {0, 0, 0, 0};
        sbl__ring_put(rb, x, sbl__stereo_rp_pixel(rp, x, y, tmp), tmp, ch);
    }
    for (x = 0; x < w; ++x) {
        int bad = !same_float(ra->n[x], rb->n[x], contracts) || memcmp(&ra->v[x], &rb->v[x], 4) != 0;
        for (c = 0; c < ch; ++c) bad |= !same_float(ra->x[c][x], rb->x[c][x], contracts);
        if (bad && *mismatches < 5)
            printf("  %s case %d (rig %d) pixel (%d,%d): n %.9g vs %.9g\n", what, it, rig, x, y, ra->n[x],
                   rb->n[x]);
        *mismatches += bad;
        *empty += !(rb->n[x] > 0.0f);
        ++*pixels;
    }
}

/* Two ring rows (ra, rb) over the caller's planes, float[2][P][W] with P >= 7: x (4
   channels), n, v and y[0], one after the other, each row's planes filled with 0xff
   bytes (NaN) so that a value the gather should have written and did not shows. */
static void bind_ring_rows(sbl__ring_row *ra, sbl__ring_row *rb, float *planes, int nplanes, int width,
                           unsigned char *unsafe)
{
    int i, c;
    for (i = 0; i < 2; ++i) {
        sbl__ring_row *r = i ? rb : ra;
        float *p = planes + (size_t)i * nplanes * width;
        for (c = 0; c < 4; ++c) r->x[c] = p + c * width;
        r->n = p + 4 * width;
        r->v = p + 5 * width;
        r->y[0] = p + 6 * width;
        r->unsafe = unsafe;
        memset(p, 0xff, sizeof(float) * nplanes * width);
    }
}
#define BIND_RING_ROWS(ra, rb, planes, unsafe)                                                        \
    bind_ring_rows(&(ra), &(rb), &(planes)[0][0][0], (int)(sizeof(planes)[0] / sizeof(planes)[0][0]), \
                   (int)(sizeof(planes)[0][0] / sizeof(float)), (unsafe))

#endif

static void test_row_gather(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    static const float specials[8] = {0.0f, -1.0f, 1e30f, FLT_MAX, 1e-39f, -FLT_MAX, 0.0f, FLT_MAX};
    sbt_rng rng = {99};
    int it, pixels = 0, mismatches = 0, redone = 0, flagged = 0, flag_mismatches = 0;
    for (it = 0; it < 600; ++it) {
        int w = 2 + (int)(sbt_uniform(&rng) * 80), h = 2 + (int)(sbt_uniform(&rng) * 10);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, c;
        int with_len = it % 5 != 0, with_depth = it % 7 != 0;
        sbt_img cur = sbt_img_new(w, h, ch, 1), hist = sbt_img_new(w, h, ch, 2);
        sbt_img len = sbt_img_new(w, h, 1, 0), depth = sbt_img_new(w, h, 1, 1);
        sbt_img pdepth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 1);
        sbt_img pair = sbt_img_new(w, h, 2, 1);
        sbl_reproject_desc rd;
        sbl_frame f;
        sbl_history hi;
        sbl__temporal_rp rp;
        float planes[2][7][96];
        unsigned char unsafe[96];
        sbl__ring_row ra, rb;
        double mscale;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 4 == 1;
        rd.motion.units = (sbl_motion_units)(it % 3);
        rd.motion.y_up = (it / 3) % 2;
        rd.motion.forward = (it / 6) % 2;
        mscale = rd.motion.units == SBL_MOTION_PIXELS ? 1.0 : 1.0 / w;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                float r0 = (float)sbt_uniform(&rng);
                for (c = 0; c < ch; ++c) {
                    sbt_at(&cur, x, y)[c] = (float)sbt_uniform(&rng);
                    sbt_at(&hist, x, y)[c] = (float)(sbt_uniform(&rng) * 2 - 0.2);
                }
                *sbt_at(&len, x, y) = (float)(sbt_uniform(&rng) * 30);
                *sbt_at(&depth, x, y) = (float)(3.0 + 0.01 * x + (r0 < 0.15 ? 5.0 : 0.0));
                *sbt_at(&pdepth, x, y) = (float)(3.0 + 0.01 * x + (sbt_uniform(&rng) < 0.15 ? 5.0 : 0.0));
                sbt_at(&mv, x, y)[0] = (float)((sbt_uniform(&rng) * 6 - 3) * mscale);
                sbt_at(&mv, x, y)[1] = (float)((sbt_uniform(&rng) * 4 - 2) * mscale);
                if (r0 > 0.9) { sbt_at(&mv, x, y)[0] = 0.0f; sbt_at(&mv, x, y)[1] = 0.0f; }
                else if (r0 > 0.85) { sbt_at(&mv, x, y)[0] = -1.0f; sbt_at(&mv, x, y)[1] = 1.0f; }
                if (sbt_uniform(&rng) < 0.04) sbt_at(&hist, x, y)[(int)(sbt_uniform(&rng) * ch)] = specials[it % 8];
                if (sbt_uniform(&rng) < 0.02) sbt_at(&hist, x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) sbt_at(&hist, x, y)[ch - 1] = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.03) *sbt_at(&len, x, y) = specials[(it + x) % 8];
                if (sbt_uniform(&rng) < 0.01) *sbt_at(&len, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = specials[(it + y) % 4];
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&depth, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) sbt_at(&mv, x, y)[1] = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) sbt_at(&mv, x, y)[0] = 1e30f;
                if (sbt_uniform(&rng) < 0.01) sbt_at(&mv, x, y)[0] = 1e-40f;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&depth, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) *sbt_at(&depth, x, y) = -(float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) /* x + 0.5 + m not exact in double */
                    sbt_at(&mv, x, y)[(x + y) & 1] = (float)(sbt_uniform(&rng) * 3e-8);
                if (sbt_uniform(&rng) < 0.05) /* small motions, some below 2^-8 */
                    sbt_at(&mv, x, y)[(x + y) & 1] = (float)((sbt_uniform(&rng) - 0.5) * 1e-2 * pow(10.0, -4.0 * sbt_uniform(&rng)));
            }
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        if (with_depth) f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        if (with_len) hi.length = view(&len);
        if (with_depth) hi.gbuffer.depth = view(&pdepth);
        if (it % 3 == 0) { /* bottom-up history colour: the last row first */
            hi.color.data = sbt_at(&hist, 0, h - 1);
            hi.color.stride = -hist.stride;
        }
        if (it % 4 == 2) { /* depth and N as one channel of two-channel buffers */
            int k;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    sbt_at(&pair, x, y)[0] = *sbt_at(&pdepth, x, y);
                    sbt_at(&pair, x, y)[1] = *sbt_at(&len, x, y);
                }
            for (k = 0; k < 2; ++k) {
                sbl_image *v = k ? &hi.length : &hi.gbuffer.depth;
                if (!v->data) continue;
                *v = view(&pair);
                v->data = pair.mem + k;
                v->channels = 1;
                v->pixel_bytes = 2 * (int)sizeof(float);
            }
        }
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &f, &hi), SBL_OK);
        if (!sbl__row_gather_ok(&rp.src)) { CHECK(0); continue; }
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        for (y = 0; y < h; ++y) {
            int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * w), xb = it % 2 ? w : xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
            memset(unsafe, 0, sizeof unsafe);
            sbl__temporal_rp_row(&rp, &ra, y, xa, xb);
            /* its unsafe flags, set as it writes: those of sbl__ring_gather's check */
            CHECK_EQ(ra.gather_flags, 1);
            {
                int want = 0;
                for (x = xa; x < xb; ++x) {
                    int safe = sbl__lane_value_ok(ra.n[x]);
                    for (c = 0; c < ch; ++c) safe &= sbl__lane_value_ok(ra.x[c][x]);
                    safe |= !(ra.v[x] > 0.0f);
                    if (unsafe[x] != !safe) ++flag_mismatches;
                    want += !safe;
                }
                if (ra.gather_unsafe != want) ++flag_mismatches;
                flagged += want;
            }
            compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "row gather", it, w, h,
                                      &pixels, &mismatches, &redone);
        }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(pdepth.mem); free(mv.mem);
        free(pair.mem);
    }
    printf("  %s row gather vs pixel gather: %d pixels (%d without x*), %d differ (%s)\n", SBL_SIMD_NAME,
           pixels, redone, mismatches, contracts ? "contracted or fast-math: 1e-6 relative" : "bit for bit");
    CHECK(mismatches == 0);
    CHECK(redone > pixels / 20 && redone < pixels / 2);
    printf("  %s row gather's own unsafe flags: %d pixels flagged, %d differ from the re-check\n",
           SBL_SIMD_NAME, flagged, flag_mismatches);
    CHECK(flag_mismatches == 0);
    CHECK(flagged > 0);
#else
    printf("  %s: no row gather on this path (the pixel gather runs)\n", SBL_SIMD_NAME);
#endif
}

/* Blocks whose pixels share one motion vector (sbl__temporal_uniform_block: a pan, a
   drift) against the pixel gather, bit for bit: one vector per row (integers, fractions,
   small, negative, exact or not), a few rows broken by one pixel, footprints leaving the
   image on either side, hostile history depth (0, -0, negatives, NaN, +-inf) and N, and
   depth tolerances below and above 1 (limits below and above the expectation: the full
   vectors' test, sbl__full_lanes). Also checks the uniform plan was taken. */
static void test_row_gather_uniform(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    static const float bad_depth[8] = {0.0f, -0.0f, -1.0f, 1e-30f, -(float)HUGE_VAL, (float)HUGE_VAL, 0.0f, 2.9f};
    static const float moves[8] = {0.37f, -0.21f, 1.0f, -2.0f, 0.0f, 0.00390625f, -1.75f, 2.5f};
    sbt_rng rng = {4242};
    int it, pixels = 0, mismatches = 0, empty = 0, uniform_blocks = 0, blocks = 0, run_entries = 0;
    for (it = 0; it < 400; ++it) {
        int w = 8 + (int)(sbt_uniform(&rng) * 88), h = 3 + (int)(sbt_uniform(&rng) * 6);
        int ch = 1 + it % 4, x, y, c;
        sbt_img cur = sbt_img_new(w, h, ch, 1), hist = sbt_img_new(w, h, ch, 0);
        sbt_img len = sbt_img_new(w, h, 1, 0), depth = sbt_img_new(w, h, 1, 1);
        sbt_img pdepth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 1);
        sbl_reproject_desc rd;
        sbl_frame f;
        sbl_history hi;
        sbl__temporal_rp rp;
        float planes[2][7][96];
        unsigned char unsafe[96];
        sbl__ring_row ra, rb;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 4 == 1;
        rd.depth_tolerance = it % 3 == 0 ? 1.5f : (it % 3 == 1 ? 0.05f : 0.3f);
        rd.motion.y_up = (it / 3) % 2;
        rd.motion.forward = (it / 6) % 2;
        for (y = 0; y < h; ++y) {
            const float mx = moves[(it + y) % 8] + (it % 5 == 0 ? (float)(w / 2) * (y % 2 ? 1 : -1) : 0.0f);
            const float my = moves[(it + 3 * y) % 8] * (it % 7 == 0 ? 0.0f : 1.0f);
            const int broken = sbt_uniform(&rng) < 0.15 ? (int)(sbt_uniform(&rng) * w) : -1;
            for (x = 0; x < w; ++x) {
                for (c = 0; c < ch; ++c) {
                    sbt_at(&cur, x, y)[c] = (float)sbt_uniform(&rng);
                    sbt_at(&hist, x, y)[c] = (float)(sbt_uniform(&rng) * 2 - 0.2);
                }
                *sbt_at(&len, x, y) = (float)(sbt_uniform(&rng) * 30);
                *sbt_at(&depth, x, y) = (float)(3.0 + 0.01 * x + 0.02 * y);
                *sbt_at(&pdepth, x, y) = (float)(3.0 + 0.01 * x + 0.02 * y + (sbt_uniform(&rng) < 0.1 ? 2.0 : 0.0));
                sbt_at(&mv, x, y)[0] = x == broken ? mx + 0.125f : mx;
                sbt_at(&mv, x, y)[1] = my;
                if (sbt_uniform(&rng) < 0.05) *sbt_at(&pdepth, x, y) = bad_depth[(it + x) % 8];
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&depth, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) *sbt_at(&depth, x, y) = 0.02f; /* a limit above z */
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&len, x, y) = bad_depth[(it + y) % 8];
                if (sbt_uniform(&rng) < 0.01) sbt_at(&hist, x, y)[0] = (float)HUGE_VAL;
            }
        }
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&pdepth);
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &f, &hi), SBL_OK);
        if (!sbl__row_gather_ok(&rp.src)) { CHECK(0); continue; }
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        for (y = 0; y < h; ++y) {
            int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * w / 2), xb = w, x0;
            if (sbl__temporal_plan_lanes_ok(&rp, y)) /* the blocks the row gather plans */
                for (x0 = xa; x0 + SBL__VW <= xb; x0 += SBL__BLOCK) {
                    sbl__block b;
                    int l;
                    b.x0 = x0;
                    b.y = y;
                    b.n = xb - x0 < SBL__BLOCK ? xb - x0 : SBL__BLOCK;
                    b.sky = 0;
                    sbl__temporal_uniform_block(&rp, &b);
                    uniform_blocks += b.uni;
                    ++blocks;
                    /* the entries the row gather settles in its uniform pass (rb: scratch,
                       written again below) */
                    for (l = 0; l < SBL__VW; ++l) b.p.lane_step[0][l] = l * ch;
                    memset(unsafe, 0, sizeof unsafe);
                    run_entries += sbl__temporal_uniform_run(&rp, &rb, &b, !rd.no_fallback, 0);
                }
            memset(unsafe, 0, sizeof unsafe);
            sbl__temporal_rp_row(&rp, &ra, y, xa, xb);
            compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "uniform motion", it, w, h,
                                      &pixels, &mismatches, &empty);
        }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(pdepth.mem); free(mv.mem);
    }
    printf("  %s uniform-motion row gather vs pixel gather: %d pixels (%d without), %d differ; "
           "%d of %d blocks planned as uniform, %d entries settled by their uniform pass\n",
           SBL_SIMD_NAME, pixels, empty, mismatches, uniform_blocks, blocks, run_entries);
    CHECK(mismatches == 0);
    CHECK(uniform_blocks > blocks / 3 && uniform_blocks < blocks);
    CHECK(run_entries > 0); /* (the uniform pass taken: packed RGB, full vectors) */
#else
    printf("  %s: no row gather on this path (the pixel gather runs)\n", SBL_SIMD_NAME);
#endif
}

/* The stereo row gather against sbl__stereo_rp_pixel, bit for bit (or within the
   contraction tolerance): parallel and disparity rigs (one and two channels), both
   eyes as target, back-check on and off, hostile depth / disparity / colour / N. */
static void test_stereo_row_gather(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    sbt_rng rng = {123};
    int it, pixels = 0, mismatches = 0, none = 0;
    for (it = 0; it < 300; ++it) {
        int w = 2 + (int)(sbt_uniform(&rng) * 80), h = 2 + (int)(sbt_uniform(&rng) * 8);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, c, e;
        int rig = it % 3, dch = 1 + (it / 3) % 2;
        sbt_img col[2], len[2], dep[2], disp[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl__stereo_rp rp;
        float planes[2][7][96];
        unsigned char unsafe[96];
        sbl__ring_row ra, rb;
        for (e = 0; e < 2; ++e) {
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
            disp[e] = sbt_img_new(w, h, dch, 0);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    float u = (float)sbt_uniform(&rng);
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)sbt_uniform(&rng);
                    *sbt_at(&len[e], x, y) = (float)(sbt_uniform(&rng) * 20);
                    *sbt_at(&dep[e], x, y) = u < 0.1f ? 2.0f : 4.0f;
                    sbt_at(&disp[e], x, y)[0] = u < 0.1f ? 5.0f : 2.5f + 0.01f * x;
                    if (dch > 1) sbt_at(&disp[e], x, y)[1] = (float)(sbt_uniform(&rng) * 0.6 - 0.3);
                    if (sbt_uniform(&rng) < 0.03) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                    if (sbt_uniform(&rng) < 0.02) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                    if (sbt_uniform(&rng) < 0.02) sbt_at(&disp[e], x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
                    if (sbt_uniform(&rng) < 0.02) sbt_at(&col[e], x, y)[0] = (float)HUGE_VAL;
                    if (sbt_uniform(&rng) < 0.02) *sbt_at(&len[e], x, y) = 0.0f;
                }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = view(&col[e]);
            eye[e].length = view(&len[e]);
            eye[e].gbuffer.depth = view(&dep[e]);
            eye[e].disparity = view(&disp[e]);
        }
        memset(&sd, 0, sizeof sd);
        sd.rig = rig == 2 ? SBL_RIG_DISPARITY : SBL_RIG_PARALLEL;
        sd.focal_px = 10.0f;
        sd.baseline = 1.0f;
        if (rig == 1) sd.disparity_offset = 0.75f;
        if (it % 4 == 3) sd.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
        sd.reproject.no_fallback = it % 5 == 1;
        e = it & 1;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)e, &eye[e], &eye[!e], 1), SBL_OK);
        rp.tiles = 0; /* (the far tiles, opt-in and within a bound: test_tiles) */
        CHECK(sbl__row_gather_ok(&rp.src));
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        for (y = 0; y < h; ++y)
            compare_stereo_with_pixel_gather(&rp, &ra, &rb, y, w, ch, contracts, "stereo row gather", it, rig,
                                             &pixels, &mismatches, &none);
        for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); free(dep[e].mem); free(disp[e].mem); }
    }
    printf("  %s stereo row gather vs pixel gather: %d pixels (%d without a match), %d differ\n",
           SBL_SIMD_NAME, pixels, none, mismatches);
    CHECK(mismatches == 0);
    CHECK(none > pixels / 20 && none < pixels / 2);
#endif
}

/* The parallel rig's fused vectors (sbl__stereo_parallel_vec) against the pixel gather,
   bit for bit: rows at one depth (a constant disparity, integer and half-integer ones
   included: tap 1 of weight 0, the back-check's source pixel on either side), slow
   depth ramps (offsets that step inside a vector), steps, matches leaving the image
   (vectors without any, and mixed ones), hostile source depth, N and colour (unsafe
   values: the flags checked against sbl__ring_gather's re-check), the target's sky,
   tolerances whose limits reach the expectation (not full), back-check and fallback on
   and off, both eyes as target, column ranges. Also checks the fused path was taken. */
static void test_stereo_parallel_fused(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    static const float fracs[8] = {0.0f, 0.5f, 0.25f, 0.7f, 0.4999f, 0.125f, 0.9f, 0.5001f};
    static const float bad[8] = {0.0f, -0.0f, -1.0f, 1e-30f, (float)HUGE_VAL, 0.0f, 1e-14f, 3e16f};
    sbt_rng rng = {777};
    int it, pixels = 0, mismatches = 0, none = 0, vectors = 0, fused = 0, flagged = 0, flag_mismatches = 0;
    for (it = 0; it < 400; ++it) {
        const int w = 12 + (int)(sbt_uniform(&rng) * 84), h = 3 + (int)(sbt_uniform(&rng) * 6);
        const int ch = it % 4 == 3 ? 1 + (int)(sbt_uniform(&rng) * 4) : (it % 2 ? 3 : 1);
        const float fb = 12.0f;
        int x, y, c, e;
        sbt_img col[2], len[2], dep[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl__stereo_rp rp;
        float planes[3][7][96];
        unsigned char unsafe[96], scratch_unsafe[96];
        sbl__ring_row ra, rb, rc;
        for (e = 0; e < 2; ++e) {
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
        }
        for (y = 0; y < h; ++y) {
            /* the row's disparity: k + a fraction (fb / z), ramps of slope up to 0.1 px
               per pixel, some rows large enough to leave the image */
            /* (every 6th case: one disparity for the whole image, so that a tap read past
               the row's end would find the next row's pixel at the expected depth) */
            const int kind = it % 6 == 4 ? 0 : (int)(sbt_uniform(&rng) * 4);
            const double d0 = it % 6 == 4 ? 2.0 + fracs[it % 8]
                                          : (it % 5 == 0 ? (double)w * 0.6 : 1.0 + (double)(int)(sbt_uniform(&rng) * 6)) +
                                                fracs[(it + y) % 8];
            const double slope = kind == 1 ? (sbt_uniform(&rng) - 0.5) * 0.2 : 0.0;
            for (x = 0; x < w; ++x) {
                const double d = d0 + slope * x + (kind == 2 && x > w / 2 ? 1.5 : 0.0);
                for (e = 0; e < 2; ++e) {
                    float z = (float)(fb / d);
                    if (kind == 3) z = (float)(fb / (d0 + 0.001 * (x + 3 * e)));
                    *sbt_at(&dep[e], x, y) = z;
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)(sbt_uniform(&rng) * 2 - 0.3);
                    *sbt_at(&len[e], x, y) = (float)(0.5 + sbt_uniform(&rng) * 20);
                    if (e == 1 && sbt_uniform(&rng) < 0.03) *sbt_at(&dep[e], x, y) = bad[(it + x) % 8];
                    if (e == 1 && sbt_uniform(&rng) < 0.01) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                    if (sbt_uniform(&rng) < 0.02) *sbt_at(&len[e], x, y) = bad[(it + y) % 8];
                    if (sbt_uniform(&rng) < 0.02) sbt_at(&col[e], x, y)[0] = bad[(it + x + y) % 8];
                    if (sbt_uniform(&rng) < 0.005) sbt_at(&col[e], x, y)[ch - 1] = (float)HUGE_VAL;
                    if (e == 0 && sbt_uniform(&rng) < 0.01) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                }
            }
        }
        for (e = 0; e < 2; ++e) {
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = view(&col[e]);
            eye[e].length = view(&len[e]);
            eye[e].gbuffer.depth = view(&dep[e]);
        }
        memset(&sd, 0, sizeof sd);
        sd.rig = SBL_RIG_PARALLEL;
        sd.focal_px = fb;
        sd.baseline = 1.0f;
        sd.reproject.depth_tolerance = it % 7 == 0 ? 1.5f : 0.05f;
        sd.reproject.back_check_pixels = it % 3 == 0 ? 0.05f : 1.0f;
        if (it % 4 == 1) sd.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
        sd.reproject.no_fallback = it % 5 == 2;
        e = (it >> 1) & 1;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)e, &eye[e], &eye[!e], 1), SBL_OK);
        rp.tiles = 0; /* (the far tiles, opt-in and within a bound: test_tiles) */
        CHECK(sbl__row_gather_ok(&rp.src));
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        rc = ra; /* (the third set of planes: the vectors tried one at a time) */
        for (c = 0; c < 4; ++c) rc.x[c] = planes[2][c];
        rc.n = planes[2][4];
        rc.v = planes[2][5];
        rc.unsafe = scratch_unsafe;
        for (y = 0; y < h; ++y) {
            const int xa = it % 3 == 1 ? (int)(sbt_uniform(&rng) * w / 3) : 0;
            /* (a disparity of 2.x: the last vector's last footprint ends at the image's
               last pixel, where no later vector overwrites it) */
            const int xb = it % 6 == 4 ? w - 2 : it % 3 == 2 ? w - (int)(sbt_uniform(&rng) * w / 3) : w;
            if (xb - xa >= SBL__VW && sbl__stereo_parallel_ok(&rp, y))
                for (x = xa; x + SBL__VW <= xb; x += SBL__VW) {
                    fused += ch == 3 ? sbl__stereo_parallel_vec(&rp, &rc, x, y, 3, 1, 1, 1.0, 0)
                                     : sbl__stereo_parallel_vec(&rp, &rc, x, y, 1, 1, 1, 1.0, 0);
                    ++vectors;
                }
            memset(unsafe, 0, sizeof unsafe);
            ra.gather_flags = 0;
            sbl__stereo_rp_row(&rp, &ra, y, xa, xb);
            for (x = xa; x < xb; ++x) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put(&rb, x, sbl__stereo_rp_pixel(&rp, x, y, tmp), tmp, ch);
            }
            {   /* the flags the row gather set: sbl__ring_gather's re-check */
                int want = 0;
                for (x = xa; x < xb; ++x) {
                    int safe = sbl__lane_value_ok(ra.n[x]), bad_px;
                    for (c = 0; c < ch; ++c) safe &= sbl__lane_value_ok(ra.x[c][x]);
                    safe |= !(ra.v[x] > 0.0f);
                    if (ra.gather_flags && unsafe[x] != !safe) ++flag_mismatches;
                    want += !safe;
                    bad_px = !same_float(ra.n[x], rb.n[x], contracts) || memcmp(&ra.v[x], &rb.v[x], 4) != 0;
                    for (c = 0; c < ch; ++c) bad_px |= !same_float(ra.x[c][x], rb.x[c][x], contracts);
                    if (bad_px && mismatches < 5)
                        printf("  stereo fused case %d (%dx%dx%d, eye %d) pixel (%d,%d): n %.9g vs %.9g, x0 %.9g vs %.9g\n",
                               it, w, h, ch, e, x, y, ra.n[x], rb.n[x], ra.x[0][x], rb.x[0][x]);
                    mismatches += bad_px;
                    none += !(rb.n[x] > 0.0f);
                    ++pixels;
                }
                if (ra.gather_flags && ra.gather_unsafe != want) ++flag_mismatches;
                flagged += ra.gather_flags ? want : 0;
            }
        }
        for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); free(dep[e].mem); }
    }
    printf("  %s parallel rig's fused vectors vs pixel gather: %d pixels (%d without a match), %d differ; "
           "%d of %d vectors fused; %d flagged, %d flags differ\n",
           SBL_SIMD_NAME, pixels, none, mismatches, fused, vectors, flagged, flag_mismatches);
    CHECK(mismatches == 0);
    /* the fused path must carry a real share of the vectors, and not all (the rest must
       reach the blocks): a vector fuses when its lanes' offsets agree, which the random
       cases make rarer the wider it is (AVX-512: 844 of 2974, SSE2 / AVX2 over a third) */
    CHECK(fused > vectors / 8 && fused < vectors);
    CHECK(none > pixels / 20 && none < pixels / 2);
    CHECK(flag_mismatches == 0);
    CHECK(flagged > 0);
#else
    printf("  %s: no row gather on this path (the pixel gather runs)\n", SBL_SIMD_NAME);
#endif
}


/* Precision of the lane kernel's one-pass 3x3 sums (sbl__lanes_columns /
   sbl__lanes_moments) against the same statistics in double, on the cases a naive sum of
   squares cancels away: a mean 1e4 above noise of 0.05 (mean^2 / variance ~ 4e10), a
   bias of 500 between x* and Y over pair noise of 0.05, and a firefly centre 1e4 times
   its neighbours (which the leave-centre-out m8 / v8 must not see). Variances within
   1e-4 relative (a naive one-pass sum is off by ~100 %), means within 1e-6 of scale. */
static void test_moments_precision(void)
{
    static float own[PH * PW * 4];
    static paths_gather G;
    sbt_rng rng = {99};
    double worst_var = 0, worst_v8 = 0, worst_pv = 0, worst_mean = 0;
    int it, compared = 0;
    for (it = 0; it < 300; ++it) {
        sbl__kernel k;
        sbl_image im;
        void *scratch;
        const sbl__ring_row *R[3];
        sbl__lane_rows W;
        const int ch = 1 + it % 4, kind = (it / 4) % 3;
        const double base = kind == 2 ? 1.0 : (it % 2 ? 1e4 : -3e3), noise = kind == 2 ? 0.01 : 0.05;
        int x, y, c, i, l;
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x) {
                for (c = 0; c < 4; ++c) {
                    double v = base + noise * (sbt_uniform(&rng) - 0.5);
                    if (kind == 2 && y == 1 && x % 3 == 0) v = 1e4 * (1.0 + sbt_uniform(&rng));
                    own[(y * PW + x) * 4 + c] = (float)v;
                    G.x[y][x][c] = (float)(v + (kind == 1 ? 500.0 : 0.0) + noise * (sbt_uniform(&rng) - 0.5));
                }
                G.n[y][x] = sbt_uniform(&rng) < 0.3 ? 0.0f : 4.0f;
            }
        memset(&k, 0, sizeof k);
        im = sbl_image_make(own, PW, PH, 4);
        im.channels = ch;
        k.w = PW; k.h = PH; k.ch = ch;
        k.wp.estimator = SBL_ESTIMATOR_ROBUST;
        k.wp.rectify = (sbl_rectify)(it % SBL_RECTIFY_COUNT);
        k.n_cap = 64.0f;
        k.temporal = 1;
        k.own = &im;
        k.gather = paths_gather_fn;
        k.gather_ctx = &G;
        scratch = malloc(sbl__kernel_scratch_size(PW, ch));
        sbl__kernel_bind(&k, scratch);
        for (i = 0; i < 3; ++i) sbl__ring_load(&k, &k.ring[i], i, 0, PW);
        R[0] = &k.ring[0]; R[1] = &k.ring[1]; R[2] = &k.ring[2];
        CHECK_EQ(R[0]->unsafe_count + R[1]->unsafe_count + R[2]->unsafe_count, 0);
        sbl__lane_rows_of(&W, R, ch);
        sbl__lanes_columns(&k, &W, 0, PW, 0);
        for (x = 1; x + SBL__VW <= PW - 1; x += SBL__VW) {
            sbl__lane_stats st;
            float f[6][SBL__VW];
            sbl__lanes_moments(&k, &W, x, 0, &st);
            for (c = 0; c < ch; ++c) {
                sbl__store(f[0], st.mean[c]); sbl__store(f[1], st.var[c]);
                sbl__store(f[2], st.m8[c]); sbl__store(f[3], st.v8[c]);
                sbl__store(f[4], st.pd[c]); sbl__store(f[5], st.pv[c]);
                for (l = 0; l < SBL__VW; ++l) {
                    const int px = x + l;
                    double s9 = 0, s8 = 0, v9 = 0, v8 = 0, sd = 0, vd = 0, m9, m8, md, scale;
                    int n = 0, j, dx;
                    for (j = 0; j < 3; ++j)
                        for (dx = -1; dx <= 1; ++dx) {
                            const double yy = R[j]->y[c][px + dx];
                            s9 += yy;
                            if (j != 1 || dx != 0) s8 += yy;
                            if (R[j]->v[px + dx] > 0.0f) { sd += (double)R[j]->x[c][px + dx] - yy; ++n; }
                        }
                    m9 = s9 / 9; m8 = s8 / 8; md = n ? sd / n : 0.0;
                    for (j = 0; j < 3; ++j)
                        for (dx = -1; dx <= 1; ++dx) {
                            const double yy = R[j]->y[c][px + dx];
                            v9 += (yy - m9) * (yy - m9);
                            if (j != 1 || dx != 0) v8 += (yy - m8) * (yy - m8);
                            if (R[j]->v[px + dx] > 0.0f) {
                                const double d = (double)R[j]->x[c][px + dx] - yy - md;
                                vd += d * d;
                            }
                        }
                    v9 /= 9; v8 /= 8; vd = n > 1 ? vd / (n - 1) : 0.0;
                    scale = fabs(m9) + sqrt(v9);
                    if (fabs(f[0][l] - m9) / scale > worst_mean) worst_mean = fabs(f[0][l] - m9) / scale;
                    if (fabs(f[2][l] - m8) / scale > worst_mean) worst_mean = fabs(f[2][l] - m8) / scale;
                    /* pairs: only where x* of the centre is valid (else the output resets to Y
                       and the pair statistics are not used) */
                    if (!(R[1]->v[px] > 0.0f)) n = 0;
                    if (n && fabs(f[4][l] - md) / (fabs(md) + sqrt(vd) + 1e-30) > worst_mean)
                        worst_mean = fabs(f[4][l] - md) / (fabs(md) + sqrt(vd) + 1e-30);
                    if (fabs(f[1][l] - v9) / v9 > worst_var) worst_var = fabs(f[1][l] - v9) / v9;
                    if (fabs(f[3][l] - v8) / v8 > worst_v8) worst_v8 = fabs(f[3][l] - v8) / v8;
                    if (n > 1 && vd > 0 && fabs(f[5][l] - vd) / vd > worst_pv) worst_pv = fabs(f[5][l] - vd) / vd;
                    ++compared;
                }
            }
        }
        free(scratch);
    }
    printf("  %s one-pass 3x3 sums vs double (offset 1e4 / noise 0.05, bias 500, firefly 1e4): "
           "%d pixel-channels, worst relative error variance %.3g, leave-centre-out %.3g, "
           "pairs %.3g, means %.3g of scale\n",
           SBL_SIMD_NAME, compared, worst_var, worst_v8, worst_pv, worst_mean);
    CHECK(compared > 0);
    CHECK(worst_var <= 1e-4);
    CHECK(worst_v8 <= 1e-4);
    CHECK(worst_pv <= 1e-4);
    CHECK(worst_mean <= 1e-6);
}


/* A temporal pooled kernel over the PW x PH rows of `own` (ch channels, 4 floats a pixel)
   and the gathered history G, its three ring rows loaded: what the prepass tests below
   run sbl__row_pool / sbl__row_pool_ref on. Returns the scratch to free. */
static void *pool_kernel_setup(sbl__kernel *k, sbl_image *im, float *own, paths_gather *G, int ch,
                               const sbl__ring_row *R[3])
{
    void *scratch;
    int i;
    memset(k, 0, sizeof *k);
    *im = sbl_image_make(own, PW, PH, ch);
    k->w = PW; k->h = PH; k->ch = ch;
    k->wp.estimator = SBL_ESTIMATOR_POOLED;
    k->n_cap = 64.0f;
    k->temporal = 1;
    k->own = im;
    k->gather = paths_gather_fn;
    k->gather_ctx = G;
    scratch = malloc(sbl__kernel_scratch_size(PW, ch));
    sbl__kernel_bind(k, scratch);
    for (i = 0; i < 3; ++i) sbl__ring_load(k, &k->ring[i], i, 0, PW);
    R[0] = &k->ring[0]; R[1] = &k->ring[1]; R[2] = &k->ring[2];
    return scratch;
}

/* The pooled prepass (sbl__row_pool) against its double reference (sbl__row_pool_ref)
   on rows with dim values: a dim y next to a bright valid x* (d = x* - y stays in the
   lane range) keeps the lanes, within float rounding of the reference; a dim pair
   (both values dim: d below 2^-40), a denormal or a NaN sends every pixel within reach
   to the reference, bit for bit. */
static void test_pool_dim(void)
{
    static float own[PH * PW * 4];
    static paths_gather G;
    sbt_rng rng = {515};
    double worst = 0;
    int it, lanes_dim = 0, exact = 0;
    for (it = 0; it < 400; ++it) {
        sbl__kernel k;
        sbl_image im;
        void *scratch;
        const sbl__ring_row *R[3];
        float lanes[PW];
        int unsafe_col[PW];
        const int ch = 1 + it % 4;
        int x, y, c, t;
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * PW + x) * 4 + c] = (float)(0.3 + 0.4 * sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.3 + 0.4 * sbt_uniform(&rng) + (x > PW / 2 ? 0.2 : 0.0));
                }
                G.n[y][x] = sbt_uniform(&rng) < 0.1 ? 0.0f : 8.0f;
            }
        memset(unsafe_col, 0, sizeof unsafe_col);
        for (t = 0; t < 1 + it % 4; ++t) {
            const int tx = (int)(sbt_uniform(&rng) * PW), ty = (int)(sbt_uniform(&rng) * PH);
            const int kind = (int)(sbt_uniform(&rng) * 5), tc = (int)(sbt_uniform(&rng) * ch);
            float *yv = &own[(ty * PW + tx) * ch + tc];
            if (kind <= 1) {
                *yv = kind ? 1e-14f : -3e-20f; /* dim y, bright x*: the lanes */
                if (G.n[ty][tx] > 0.0f) ++lanes_dim;
            } else if (kind == 2) {
                *yv = 1e-14f; /* a dim pair: the reference */
                G.x[ty][tx][tc] = 1.3e-14f;
                G.n[ty][tx] = 8.0f;
            } else if (kind == 3) {
                *yv = 1e-39f; /* denormal y, x* invalid: the lanes (only its finiteness counts) */
                G.n[ty][tx] = 0.0f;
            } else {
                *yv = (float)HUGE_VAL - (float)HUGE_VAL;
            }
        }
        /* the columns holding a pixel the prepass's lanes cannot take: y not finite,
           or a valid pair whose float difference is dim (nonzero, below 2^-40) */
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x)
                for (c = 0; c < ch; ++c) {
                    const float yy = own[(y * PW + x) * ch + c];
                    volatile float dd = G.x[y][x][c] - yy;
                    if (!sbl__finite(yy) ||
                        (G.n[y][x] > 0.0f && dd != 0.0f && !(fabsf(dd) >= 0x1p-40f)))
                        unsafe_col[x] = 1;
                }
        scratch = pool_kernel_setup(&k, &im, own, &G, ch, R);
        sbl__row_pool(&k, R, 0, PW);
        memcpy(lanes, k.pool_r, sizeof lanes);
        sbl__row_pool_ref(&k, R, 0, PW);
        for (x = 0; x < PW; ++x) {
            int near = 0, d;
            for (d = -SBL__POOL_REACH; d <= SBL__POOL_REACH; ++d)
                if (x + d >= 0 && x + d < PW && unsafe_col[x + d]) near = 1;
            if (near) {
                CHECK(memcmp(&lanes[x], &k.pool_r[x], sizeof(float)) == 0);
                ++exact;
            } else {
                const double e = fabs((double)lanes[x] - k.pool_r[x]) / (1.0 + SBL_POOLED_BLOCK_SE2 + k.pool_r[x]);
                CHECK(e <= 4e-6); /* measured 4.1e-7 */
                if (e > worst) worst = e;
            }
        }
        free(scratch);
    }
    printf("  %s pooled prepass with dim values vs double: %d dim y kept in the lanes, worst %.3g; "
           "%d pixels near a dim pair / NaN equal to the reference\n",
           SBL_SIMD_NAME, lanes_dim, worst, exact);
    CHECK(lanes_dim > 0);
    CHECK(exact > 0);
}


/* The blocks' threshold where the region's prior applies (the temporal filter with the
   history's evidence plane): SBL_POOLED_BLOCK_SE2_REGION, against SBL_POOLED_BLOCK_SE2
   without the plane (docs/ESTIMATORS.md 6.2). A row whose right half is biased (q ~ 13):
   with a plane of R* = 1 (its garrote at most 0.67 after one frame, ln M = 0), the ratio
   there is the one without the plane raised by the difference of the two thresholds, in
   the reference and in the lanes. */
static void test_pool_region_threshold(void)
{
    static float own[PH * PW * 4], evid_in[PW + 64], evid_out[PW + 64];
    static paths_gather G;
    sbt_rng rng = {616};
    const double lift = SBL_POOLED_BLOCK_SE2 - SBL_POOLED_BLOCK_SE2_REGION;
    double worst = 0;
    int it, compared = 0, e;
    for (e = 0; e < PW + 64; ++e) evid_in[e] = 1.0f; /* R* = 1: no evidence either way */
    for (it = 0; it < 40; ++it) {
        sbl__kernel k;
        sbl_image im;
        void *scratch;
        const sbl__ring_row *R[3];
        float without[PW], with_ref[PW], with_lanes[PW];
        const int ch = 1 + it % 4;
        int x, y, c;
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * PW + x) * 4 + c] = (float)(0.3 + 0.4 * sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.3 + 0.4 * sbt_uniform(&rng) + (x > PW / 2 ? 0.2 : 0.0));
                }
                G.n[y][x] = 8.0f;
            }
        scratch = pool_kernel_setup(&k, &im, own, &G, ch, R);
        sbl__row_pool_ref(&k, R, 0, PW);
        memcpy(without, k.pool_r, sizeof without);
        k.evid_use = 1;
        k.evid_in = evid_in;
        k.evid_out = evid_out;
        k.evid_thr = SBL__EVIDENCE_THR;
        k.evid_garrote = SBL__EVIDENCE_GARROTE;
        k.evid_lnm = 0.0;
        sbl__row_pool_ref(&k, R, 0, PW);
        memcpy(with_ref, k.pool_r, sizeof with_ref);
        sbl__row_pool(&k, R, 0, PW);
        memcpy(with_lanes, k.pool_r, sizeof with_lanes);
        for (x = 0; x < PW; ++x) {
            double e1, e2;
            if (!(without[x] > 1.0f)) continue; /* beyond the plane's garrote: q - c decides */
            e1 = fabs(with_ref[x] - (without[x] + lift)) / (1.0 + without[x]);
            e2 = fabs(with_lanes[x] - (without[x] + lift)) / (1.0 + without[x]);
            CHECK(e1 <= 1e-6);
            CHECK(e2 <= 4e-6);
            if (e1 > worst) worst = e1;
            if (e2 > worst) worst = e2;
            ++compared;
        }
        free(scratch);
    }
    printf("  %s pooled blocks' threshold with the evidence plane: %d biased pixels %.2f above the "
           "ratio without it, worst relative error %.3g\n",
           SBL_SIMD_NAME, compared, lift, worst);
    CHECK(compared > 40 * PW / 4);
}


/* The default configurations' lanes (pooled estimator, no rectification, one weight;
   temporal and stereo) on windows holding dim values (normal floats below the lane
   range's 2^-40): where sbl__lane_window_dim_ok admits the window, the lanes must agree
   with the double reference (4e-6, relative for the colour); dim pairs, two dim
   values in one column, NaN are refused (the reference path). */
static void test_lanes_dim(void)
{
    static float own[PH * PW * 4], own_n[PH * PW];
    static paths_gather G;
    sbt_rng rng = {616};
    double worst = 0;
    int it, admitted = 0, refused = 0;
    for (it = 0; it < 600; ++it) {
        sbl__kernel k;
        sbl_image im, imn;
        void *scratch;
        const sbl__ring_row *R[3];
        float lane_c[PW][4], lane_n[PW], lane_a[PW];
        const int ch = 1 + it % 4, stereo = (it >> 2) & 1;
        int x, y, c, i, t;
        for (y = 0; y < PH; ++y)
            for (x = 0; x < PW; ++x) {
                for (c = 0; c < 4; ++c) {
                    own[(y * PW + x) * ch + c] = (float)(0.2 + 0.6 * sbt_uniform(&rng));
                    G.x[y][x][c] = (float)(0.2 + 0.6 * sbt_uniform(&rng) + (x > PW / 2 ? 0.3 : 0.0));
                }
                G.n[y][x] = sbt_uniform(&rng) < 0.1 ? 0.0f : (float)(1 + 20 * sbt_uniform(&rng));
                own_n[y * PW + x] = (float)(1 + 10 * sbt_uniform(&rng));
            }
        for (t = 0; t < 1 + it % 5; ++t) {
            const int tx = (int)(sbt_uniform(&rng) * PW), ty = (int)(sbt_uniform(&rng) * PH);
            const int kind = (int)(sbt_uniform(&rng) * 6), tc = (int)(sbt_uniform(&rng) * ch);
            const float dim = kind & 1 ? 1e-14f : -4e-20f;
            own[(ty * PW + tx) * ch + tc] = dim;
            if (kind == 2) own[(((ty + 1) % PH) * PW + tx) * ch + tc] = 2e-14f; /* two in a column */
            if (kind == 3) { G.x[ty][tx][tc] = 1.5e-14f; G.n[ty][tx] = 4.0f; } /* a dim pair */
            if (kind == 4) G.x[ty][tx][tc] = 3e-13f; /* dim x*, bright y? (y is dim too) */
            if (kind == 5 && sbt_uniform(&rng) < 0.3) own[(ty * PW + tx) * ch + tc] = (float)HUGE_VAL - (float)HUGE_VAL;
        }
        memset(&k, 0, sizeof k);
        im = sbl_image_make(own, PW, PH, ch);
        imn = sbl_image_make(own_n, PW, PH, 1);
        k.w = PW; k.h = PH; k.ch = ch;
        k.wp.estimator = SBL_ESTIMATOR_POOLED;
        k.wp.rectify = SBL_RECTIFY_NONE;
        k.wp.mode = SBL_WEIGHT_SCALAR;
        k.wp.constant = 0.1f;
        k.wp.gamma = 1.25f;
        k.wp.bias_threshold = 3.0f;
        k.wp.temporal = !stereo;
        k.n_cap = stereo ? FLT_MAX : 64.0f;
        k.temporal = !stereo;
        k.own = &im;
        k.own_n = stereo ? &imn : NULL;
        k.gather = paths_gather_fn;
        k.gather_ctx = &G;
        scratch = malloc(sbl__kernel_scratch_size(PW, ch));
        sbl__kernel_bind(&k, scratch);
        for (i = 0; i < 3; ++i) sbl__ring_load(&k, &k.ring[i], i, 0, PW);
        R[0] = &k.ring[0]; R[1] = &k.ring[1]; R[2] = &k.ring[2];
        CHECK(sbl__kernel_fast(&k));
        /* every interior pixel in lanes (no window mask), then the reference where the
           rule admits a flagged window */
        sbl__kernel_lanes_pooled(&k, R, 0, PW, 1, PW - 1, NULL);
        for (x = 1; x < PW - 1; ++x) {
            for (c = 0; c < ch; ++c) lane_c[x][c] = k.stage[c][x];
            lane_n[x] = k.stage_n[x];
            lane_a[x] = k.stage_a[x];
        }
        for (x = 1; x < PW - 1; ++x) {
            int flagged = 0, j, dx;
            double e, en;
            for (j = 0; j < 3; ++j)
                for (dx = -1; dx <= 1; ++dx) flagged |= R[j]->unsafe[x + dx];
            if (!flagged) continue;
            if (!sbl__lane_window_dim_ok(&k, R, x)) { ++refused; continue; }
            ++admitted;
            sbl__kernel_pixel_ref(&k, R, x);
            e = fabs(lane_a[x] - k.stage_a[x]);
            en = fabs(lane_n[x] - k.stage_n[x]) / (fabs(k.stage_n[x]) + 1.0);
            if (en > e) e = en;
            for (c = 0; c < ch; ++c) { /* relative: the output may itself be dim */
                const double ec = fabs(lane_c[x][c] - k.stage[c][x]) / (fabs(k.stage[c][x]) + FLT_MIN);
                if (!(ec <= e)) e = ec;
            }
            if (!(e <= 4e-6))
                printf("  dim case %d (stereo %d ch %d) x %d: lane a %.6f n %g, ref a %.6f n %g\n", it,
                       stereo, ch, x, lane_a[x], lane_n[x], k.stage_a[x], k.stage_n[x]);
            CHECK(e <= 4e-6); /* measured 4.9e-7 (scalar, SSE2, AVX2, AVX-512) */
            if (e > worst) worst = e;
        }
        free(scratch);
    }
    printf("  %s default lanes on windows with dim values vs double: %d admitted (worst %.3g), "
           "%d refused\n", SBL_SIMD_NAME, admitted, worst, refused);
    CHECK(admitted > 100);
    CHECK(refused > 100);
}

/* The row gather against the pixel gather on disocclusions (session 8: the 3x3
   fallback's depth test in lanes, sbl__fallback_lanes): a nearer rectangle moved
   between the frames, so whole 3x3 windows fail the depth test (and those at its edges
   pass in part), under random sub-pixel motion; sky, NaN and inf depths, NaN colour
   and N <= 0 in the history; fallback on and off; windows at the image border. */
static void test_row_gather_disocclusion(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    sbt_rng rng = {4242};
    int it, pixels = 0, mismatches = 0, empty = 0;
    for (it = 0; it < 300; ++it) {
        int w = 8 + (int)(sbt_uniform(&rng) * 90), h = 3 + (int)(sbt_uniform(&rng) * 10);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, c;
        int ax = (int)(sbt_uniform(&rng) * w * 0.6), ay = (int)(sbt_uniform(&rng) * h * 0.5);
        int aw = 3 + (int)(sbt_uniform(&rng) * w * 0.5), ah = 2 + (int)(sbt_uniform(&rng) * h);
        int shift = 1 + (int)(sbt_uniform(&rng) * 12);
        int with_len = it % 6 != 0;
        sbt_img cur = sbt_img_new(w, h, ch, 1), hist = sbt_img_new(w, h, ch, 2);
        sbt_img len = sbt_img_new(w, h, 1, 0), depth = sbt_img_new(w, h, 1, 1);
        sbt_img pdepth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 1);
        sbl_reproject_desc rd;
        sbl_frame f;
        sbl_history hi;
        sbl__temporal_rp rp;
        float planes[2][7][100];
        unsigned char unsafe[100];
        sbl__ring_row ra, rb;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 5 == 1;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const int now = x >= ax && x < ax + aw && y >= ay && y < ay + ah;
                const int was = x >= ax + shift && x < ax + shift + aw && y >= ay && y < ay + ah;
                for (c = 0; c < ch; ++c) {
                    sbt_at(&cur, x, y)[c] = (float)sbt_uniform(&rng);
                    sbt_at(&hist, x, y)[c] = (float)(sbt_uniform(&rng) * 2);
                }
                *sbt_at(&len, x, y) = (float)(1 + sbt_uniform(&rng) * 30);
                *sbt_at(&depth, x, y) = now ? 1.5f : (float)(4.0 + 0.01 * x);
                *sbt_at(&pdepth, x, y) = was ? 1.5f : (float)(4.0 + 0.01 * x);
                sbt_at(&mv, x, y)[0] = (float)((sbt_uniform(&rng) - 0.5) * 1.8);
                sbt_at(&mv, x, y)[1] = (float)((sbt_uniform(&rng) - 0.5) * 1.8);
                if (it % 4 == 3 && y == 0) { /* a sky row, in both frames */
                    *sbt_at(&depth, x, y) = (float)HUGE_VAL;
                    *sbt_at(&pdepth, x, y) = (float)HUGE_VAL;
                }
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = -1.0f;
                if (sbt_uniform(&rng) < 0.02) sbt_at(&hist, x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.03) *sbt_at(&len, x, y) = 0.0f;
            }
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        if (with_len) hi.length = view(&len);
        hi.gbuffer.depth = view(&pdepth);
        if (it % 3 == 0) { /* bottom-up history depth: the last row first */
            hi.gbuffer.depth.data = sbt_at(&pdepth, 0, h - 1);
            hi.gbuffer.depth.stride = -pdepth.stride;
        }
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &f, &hi), SBL_OK);
        if (!sbl__row_gather_ok(&rp.src)) { CHECK(0); continue; }
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        for (y = 0; y < h; ++y) {
            int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * w), xb = it % 2 ? w : xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
            memset(unsafe, 0, sizeof unsafe);
            sbl__temporal_rp_row(&rp, &ra, y, xa, xb);
            compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "disocclusion", it, w, h,
                                      &pixels, &mismatches, &empty);
        }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(pdepth.mem); free(mv.mem);
    }
    printf("  %s row gather vs pixel gather, disocclusions: %d pixels (%d without x*), %d differ\n",
           SBL_SIMD_NAME, pixels, empty, mismatches);
    CHECK(mismatches == 0);
    CHECK(empty > pixels / 20 && empty < pixels / 2);
#endif
}

/* sbl__all_safe (the one-vector unsafe-value test of the row gather) against
   sbl__lane_value_ok per lane, on values at and around the limits (2^-40, 2^50), zeros
   of either sign, denormals, inf, NaN and random floats: 1 exactly when every lane of
   every vector is safe and nonzero. */
static void test_all_safe(void)
{
#ifdef SBL__ROW_GATHER
    static const unsigned int edges[12] = {0x2b7fffffu, 0x2b800000u, 0x2b800001u, 0x587fffffu,
                                           0x58800000u, 0x587f0000u, 0x00000000u, 0x00000001u,
                                           0x7f800000u, 0x7fc00000u, 0x3f800000u, 0x2b810000u};
    sbt_rng rng = {31337};
    int it, ones = 0, wrong = 0;
    for (it = 0; it < 40000; ++it) {
        float vals[5][SBL__VW];
        sbl__v v[5];
        int cnt = 1 + (int)(sbt_uniform(&rng) * 5), k, l, want = 1, got;
        for (k = 0; k < 5; ++k) v[k] = sbl__set1(0.0f); /* (gcc -Wmaybe-uninitialized) */
        for (k = 0; k < cnt; ++k) {
            for (l = 0; l < SBL__VW; ++l) {
                unsigned int bits;
                double u = sbt_uniform(&rng);
                if (it % 2 && u < 0.9) bits = 0x3e000000u + (unsigned int)(sbt_uniform(&rng) * 0x2000000); /* 0.125 .. 2 */
                else if (u < 0.95) bits = edges[(int)(sbt_uniform(&rng) * 12)];
                else bits = (unsigned int)(sbt_uniform(&rng) * 4294967295.0);
                if (sbt_uniform(&rng) < 0.3) bits |= 0x80000000u;
                memcpy(&vals[k][l], &bits, sizeof bits);
                want &= sbl__lane_value_ok(vals[k][l]) && (bits & 0x7fffffffu) != 0;
            }
            v[k] = sbl__load(vals[k]);
        }
        got = sbl__all_safe(v, cnt);
        wrong += got != want;
        ones += got;
    }
    printf("  %s one-vector unsafe-value test: 40000 cases (%d all safe), %d differ from the lanes'\n",
           SBL_SIMD_NAME, ones, wrong);
    CHECK(wrong == 0);
    CHECK(ones > 1000);
#endif
}

/* The carried evidence (pooled estimator, docs/ESTIMATORS.md 3.7): the lanes' ratio
   (float) against the double reference on random block sums and carried values, and
   bands of rows of the public call against one whole-image call, the output plane
   included, bit for bit. */
static void test_evidence_paths(void)
{
    sbt_rng rng = {4242};
    float ein[SBL__VW], eout_l[SBL__VW], eout_r[SBL__VW];
    double worst = 0;
    int it, i;
    for (it = 0; it < 2000; ++it) {
        sbl__kernel k;
        float sm2[SBL__VW], sse2[SBL__VW], rl[SBL__VW];
        memset(&k, 0, sizeof k);
        k.evid_in = ein;
        k.evid_use = it % 4 != 0;
        for (i = 0; i < SBL__VW; ++i) {
            double u = sbt_uniform(&rng);
            ein[i] = (float)(0.3 + 6.0 * sbt_uniform(&rng));
            sse2[i] = u < 0.1 ? 0.0f : (float)(1e-3 + sbt_uniform(&rng));
            sm2[i] = u < 0.05 ? 0.0f : (float)(sse2[i] * 4.0 * sbt_uniform(&rng) + (u < 0.1 ? 0.5 : 0.0));
        }
        {
            sbl__v r0 = sbl__set1(0.0f), r;
            k.evid_out = eout_l;
            r = sbl__evidence_ratio_lanes(&k, 0, sbl__load(sm2), sbl__load(sse2), r0);
            sbl__store(rl, r);
        }
        k.evid_out = eout_r;
        for (i = 0; i < SBL__VW; ++i) {
            double rr = sbl__evidence_ratio_ref(&k, i, sm2[i], sse2[i], 0.0);
            double e = fabs(rr - rl[i]) / (1.0 + fabs(rr));
            double ee = fabs(SBL__CAST(double, eout_l[i]) - eout_r[i]) / (1.0 + fabs(eout_r[i]));
            if (ee > e) e = ee;
            /* the gate: the same side of c_R unless R is within rounding of it */
            if (fabs(eout_r[i] - SBL__EVIDENCE_THR) < 1e-5) continue;
            CHECK(e <= 1e-5);
            if (e > worst) worst = e;
        }
    }
    printf("  evidence ratio, lanes vs double reference: worst difference %.3g\n", worst);
    {   /* bands against the whole image, with the plane in and out */
        const int w = 37, h = 23, c = 3;
        sbt_img cur = sbt_img_new(w, h, c, 1), hist = sbt_img_new(w, h, c, 0), len = sbt_img_new(w, h, 1, 0);
        sbt_img depth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 0), ev = sbt_img_new(w, h, 1, 0);
        sbt_img oc[2], on[2], oe[2];
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o[2];
        size_t bytes = sbl_temporal_scratch_size(w, c);
        void *scratch = malloc(bytes);
        int x, y, k2, y0;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                for (k2 = 0; k2 < c; ++k2) {
                    sbt_at(&cur, x, y)[k2] = (float)(0.5 + 0.2 * sbt_uniform(&rng));
                    sbt_at(&hist, x, y)[k2] = (float)(0.5 + 0.2 * sbt_uniform(&rng) + (x < w / 2 ? 0.1 : 0.0));
                }
                *sbt_at(&len, x, y) = (float)(1 + 30 * sbt_uniform(&rng));
                *sbt_at(&depth, x, y) = (float)(4.0 + 0.1 * sbt_uniform(&rng));
                sbt_at(&mv, x, y)[0] = (float)(sbt_uniform(&rng) - 0.5);
                sbt_at(&mv, x, y)[1] = (float)(sbt_uniform(&rng) - 0.5);
                *sbt_at(&ev, x, y) = (float)(0.5 + 3.0 * sbt_uniform(&rng));
            }
        sbt_at(&cur, 9, 11)[1] = (float)HUGE_VAL - (float)HUGE_VAL; /* a reference-path run */
        memset(&d, 0, sizeof d);
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur); f.gbuffer.depth = view(&depth); f.gbuffer.motion = view(&mv);
        hi.color = view(&hist); hi.length = view(&len); hi.gbuffer.depth = view(&depth);
        hi.evidence = view(&ev);
        for (i = 0; i < 2; ++i) {
            oc[i] = sbt_img_new(w, h, c, 0); on[i] = sbt_img_new(w, h, 1, 0); oe[i] = sbt_img_new(w, h, 1, 0);
            memset(&o[i], 0, sizeof o[i]);
            o[i].color = view(&oc[i]); o[i].length = view(&on[i]); o[i].evidence = view(&oe[i]);
        }
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o[0]), SBL_OK);
        for (y0 = 0; y0 < h;) {
            int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 5);
            if (y1 > h) y1 = h;
            CHECK_EQ(sbl_temporal_filter(&d, &f, &hi, &o[1], y0, y1, scratch, bytes), SBL_OK);
            y0 = y1;
        }
        CHECK(memcmp(oc[0].mem, oc[1].mem, sizeof(float) * (size_t)oc[0].stride * (size_t)h) == 0);
        CHECK(memcmp(oe[0].mem, oe[1].mem, sizeof(float) * (size_t)w * (size_t)h) == 0);
        {   /* the plane moved where the history is shifted, and stays a ratio */
            int moved = 0;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    float e = *sbt_at(&oe[0], x, y);
                    CHECK(e > 0.0f && e < 1e6f);
                    moved += e != *sbt_at(&ev, x, y);
                }
            CHECK(moved > w * h / 2);
        }
        for (i = 0; i < 2; ++i) { free(oc[i].mem); free(on[i].mem); free(oe[i].mem); }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(mv.mem); free(ev.mem);
        free(scratch);
    }
}

/* The evidence plane gathered in the colour's plan (sbl__temporal_rp_row_ev, r->e:
   one more 1-channel plane read with N's tap indices, weights, tests and fallback; rest
   and void tiles; the lanes the plan does not settle by the plane's own pixel gather)
   against the plane's per-pixel gather (sbl__evidence_pixel on a reprojection whose
   colour is the plane), bit for bit, the colour row checked as well. A hard case: random
   sub-pixel motion, a nearer rectangle that moved (windows that fail the depth test, the
   3x3 fallback where part of one passes), zero-motion and no-geometry stretches wider
   than a tile (rest and void tiles), a sky row, the camera source at rest; NaN, inf,
   negative, 0, denormal and above-cap ratios in the plane, NaN colour and N <= 0 in the
   history; fallback on and off, tiles on and off, random column ranges. */
static void test_evidence_row_gather(void)
{
#ifdef SBL__ROW_GATHER
    static const float specials[8] = {0.0f, -1.0f, 1e30f, 2e6f, 1e-39f, -0.0f, 1e-30f, 3.0f};
    const int contracts = compiler_contracts();
    sbt_rng rng = {8181};
    int it, pixels = 0, mismatches = 0, empty = 0, resets = 0, fell = 0, special = 0;
    for (it = 0; it < 400; ++it) {
        int w = 8 + (int)(sbt_uniform(&rng) * 180), h = 3 + (int)(sbt_uniform(&rng) * 9);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, c;
        int ax = (int)(sbt_uniform(&rng) * w * 0.6), ay = (int)(sbt_uniform(&rng) * h * 0.5);
        int aw = 3 + (int)(sbt_uniform(&rng) * w * 0.5), ah = 2 + (int)(sbt_uniform(&rng) * h);
        int shift = 1 + (int)(sbt_uniform(&rng) * 12);
        /* zero motion on columns [rx, rx + rw) (rest tiles), no geometry on [vx, vx + vw) */
        int rx = (int)(sbt_uniform(&rng) * w), rw = it % 3 == 0 ? w : (int)(sbt_uniform(&rng) * 140);
        int vx = (int)(sbt_uniform(&rng) * w), vw = it % 4 == 1 ? (int)(sbt_uniform(&rng) * 150) : 0;
        int camera = it % 7 == 5, flat_ev = it % 11 == 3;
        sbt_img cur = sbt_img_new(w, h, ch, 1), hist = sbt_img_new(w, h, ch, 2);
        sbt_img len = sbt_img_new(w, h, 1, 1), ev = sbt_img_new(w, h, 1, 1), depth = sbt_img_new(w, h, 1, 1);
        sbt_img pdepth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 1);
        sbl_reproject_desc rd;
        sbl_frame f;
        sbl_history hi;
        sbl_camera cam;
        sbl__temporal_rp rp, es;
        float planes[2][8][192];
        unsigned char unsafe[192];
        sbl__ring_row ra, rb;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 5 == 1;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const int now = x >= ax && x < ax + aw && y >= ay && y < ay + ah;
                const int was = x >= ax + shift && x < ax + shift + aw && y >= ay && y < ay + ah;
                for (c = 0; c < ch; ++c) {
                    sbt_at(&cur, x, y)[c] = (float)sbt_uniform(&rng);
                    sbt_at(&hist, x, y)[c] = (float)(sbt_uniform(&rng) * 2);
                }
                *sbt_at(&len, x, y) = (float)(1 + sbt_uniform(&rng) * 30);
                /* flat_ev: one value everywhere (a converged plane) */
                *sbt_at(&ev, x, y) = flat_ev ? 1.25f : (float)(0.2 + sbt_uniform(&rng) * 4);
                *sbt_at(&depth, x, y) = now ? 1.5f : (float)(4.0 + 0.01 * x);
                *sbt_at(&pdepth, x, y) = was ? 1.5f : (float)(4.0 + 0.01 * x);
                sbt_at(&mv, x, y)[0] = (float)((sbt_uniform(&rng) - 0.5) * 1.8);
                sbt_at(&mv, x, y)[1] = (float)((sbt_uniform(&rng) - 0.5) * 1.8);
                if (x >= rx && x < rx + rw) sbt_at(&mv, x, y)[0] = sbt_at(&mv, x, y)[1] = 0.0f;
                if (x >= vx && x < vx + vw) *sbt_at(&depth, x, y) = it % 2 ? 0.0f : (float)HUGE_VAL - (float)HUGE_VAL;
                if (it % 4 == 3 && y == 0) { /* a sky row, in both frames */
                    *sbt_at(&depth, x, y) = (float)HUGE_VAL;
                    *sbt_at(&pdepth, x, y) = (float)HUGE_VAL;
                }
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) *sbt_at(&pdepth, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) sbt_at(&hist, x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.01) sbt_at(&hist, x, y)[ch - 1] = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.03) *sbt_at(&len, x, y) = 0.0f;
                if (sbt_uniform(&rng) < 0.03) *sbt_at(&ev, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&ev, x, y) = (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.04) *sbt_at(&ev, x, y) = specials[(it + x + y) % 8];
            }
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&pdepth);
        hi.evidence = view(&ev);
        if (camera) { /* the camera source with the camera at rest: rest tiles everywhere */
            sbl_intrinsics kin;
            float pose[16];
            int q;
            for (q = 0; q < 16; ++q) pose[q] = q % 5 == 0 ? 1.0f : 0.0f;
            kin.fx = kin.fy = (float)(0.8 * w + 3); kin.cx = 0.5f * w; kin.cy = 0.5f * h;
            CHECK_EQ(sbl_camera_from_pinhole(&cam, &kin, pose, SBL_AXES_OPENCV, 0, w, h), SBL_OK);
            f.camera = &cam;
            hi.camera = &cam;
        }
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, camera ? SBL_TEMPORAL_CAMERA : SBL_TEMPORAL_MOTION, &f, &hi), SBL_OK);
        rp.tiles = it % 6 != 2;
        /* the plane's reprojection, as sbl_temporal_filter sets it up */
        es = rp;
        es.src.color = sbl__flatten(&hi.evidence);
        if (!sbl__row_gather_ok(&rp.src) || !sbl__evidence_fused_ok(&rp.src, &es.src)) { CHECK(0); continue; }
        memset(&ra, 0, sizeof ra);
        memset(&rb, 0, sizeof rb);
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        ra.e = ra.e_plane = planes[0][7];
        ra.e_rp = &es;
        for (y = 0; y < h; ++y) {
            int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * w), xb = it % 2 ? w : xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
            int colour_bad = 0;
            memset(unsafe, 0, sizeof unsafe);
            sbl__temporal_rp_row_ev(&rp, &ra, y, xa, xb);
            compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "evidence (colour)", it, w, h,
                                      &pixels, &colour_bad, &empty);
            mismatches += colour_bad;
            for (x = xa; x < xb; ++x) {
                const float want = sbl__evidence_pixel(&es, x, y), got = ra.e[x];
                const float v = *sbt_at(&ev, x, y);
                if (!same_float(got, want, contracts)) {
                    if (mismatches < 5)
                        printf("  evidence case %d (%dx%dx%d) pixel (%d,%d): %.9g vs %.9g\n", it, w, h, ch,
                               x, y, got, want);
                    ++mismatches;
                }
                resets += want == 1.0f;
                /* the colour reset where the plane's own gather found something: the 3x3
                   fallback (or a value the colour's taps did not use) */
                fell += !(rb.n[x] > 0.0f) && want != 1.0f;
                special += !(v > 0.0f && v <= 1e6f);
            }
        }
        free(cur.mem); free(hist.mem); free(len.mem); free(ev.mem); free(depth.mem); free(pdepth.mem);
        free(mv.mem);
    }
    printf("  %s evidence in the colour's plan vs its pixel gather: %d pixels (%d read as 1, %d no ratio in "
           "the plane, %d where the colour has none), %d differ\n",
           SBL_SIMD_NAME, pixels, resets, special, fell, mismatches);
    CHECK(mismatches == 0);
    CHECK(resets > pixels / 20 && resets < pixels / 2);
    CHECK(special > pixels / 40);
#endif
}

/* ---- normals and ids in the row gather --------------------------------------------
   The temporal and stereo row gathers with normals and ids against the pixel gather,
   bit for bit (within same_float where the compiler contracts; validity always bit for
   bit): normals spread around the threshold's cone (taps on both sides of the test),
   "no normal" pixels (0 and below 1e-12 squared), backfacing, NaN, inf and overflowing
   normals on either side, NaN / inf / -0 ids, a moving object (disocclusions, with and
   without the 3x3 fallback), and the views packed, as channels of wider buffers, and
   bottom-up. */

#ifdef SBL__ROW_GATHER
/* a normal near `dir` (spread: the angle noise), of length 0.5 .. 2, or a special one */
static void nid_normal(float *n, sbt_rng *rng, const float *dir, double spread, double special)
{
    static const float specials[10][3] = {
        {0, 0, 0}, {1e-7f, 0, 0}, {0, 0, -1}, {0, 0, 1e30f}, {0, 1e20f, 0},
        {-0.0f, -0.0f, -0.0f}, {2e-7f, 1e-7f, 5e-7f}, {0, 0, 0}, {0, 0, 1}, {0, 0, 1}};
    const double u = sbt_uniform(rng), len = 0.5 + 1.5 * sbt_uniform(rng);
    int k;
    if (u < special) {
        const int which = (int)(sbt_uniform(rng) * 12);
        for (k = 0; k < 3; ++k) n[k] = which < 10 ? specials[which][k] : dir[k];
        if (which == 10) n[(int)(sbt_uniform(rng) * 3)] = (float)HUGE_VAL - (float)HUGE_VAL;
        if (which == 11) n[(int)(sbt_uniform(rng) * 3)] = -(float)HUGE_VAL;
        return;
    }
    for (k = 0; k < 3; ++k) n[k] = (float)(len * (dir[k] + spread * (sbt_uniform(rng) * 2 - 1)));
}

static float nid_id(sbt_rng *rng, float id, double special)
{
    static const float specials[5] = {0.0f, -0.0f, 7.0f, 0.0f, 0.0f};
    const double u = sbt_uniform(rng);
    if (u < special) {
        const int which = (int)(sbt_uniform(rng) * 6);
        if (which == 3) return (float)HUGE_VAL - (float)HUGE_VAL;
        if (which == 4) return (float)HUGE_VAL;
        if (which == 5) return id == 0.0f ? -0.0f : id; /* -0 == +0 as floats */
        return specials[which];
    }
    return id;
}

/* A normals view of `src` (3 channels, w x h) in layout `lay`: 0 packed, 1 the first
   three of four channels, 2 channels 1 .. 3 of five, bottom-up, 3 packed bottom-up.
   *mem gets the buffer to free. */
static sbl_image nid_normals_view(const sbt_img *src, int lay, float **mem)
{
    return sbt_view3_layout(src, lay, 3, mem);
}

/* An ids view of `src` (1 channel) in layout `lay`: 0 packed, 1 channel 1 of two, 2
   padded rows. */
static sbl_image nid_ids_view(const sbt_img *src, int lay, float **mem)
{
    return sbt_view1_layout(src, lay, 5, mem);
}

/* The scene of the normal / id gather tests: random colours and lengths, a nearer
   rectangle r = {x, y, w, h} that moved r[4] pixels in x, normals and ids with special
   values, a few infinite previous depths and NaN history values. With `mv` (the motion
   vector test) also per-pixel motion, some far previous depths and a row without
   normals; the camera test passes NULL (its motion comes from the cameras). */
/* the moved rectangle of nid_scene_make: x, y, w, h, then its shift 1 .. max_shift */
static void nid_rect(int r[5], sbt_rng *rng, int w, int h, int max_shift)
{
    r[0] = (int)(sbt_uniform(rng) * w * 0.6);
    r[1] = (int)(sbt_uniform(rng) * h * 0.5);
    r[2] = 3 + (int)(sbt_uniform(rng) * w * 0.5);
    r[3] = 2 + (int)(sbt_uniform(rng) * h);
    r[4] = 1 + (int)(sbt_uniform(rng) * max_shift);
}

typedef struct nid_scene {
    sbt_img cur, hist, len, depth, pdepth, nrm, pnrm, ids, pids;
    float *mem[4];
} nid_scene;

static void nid_scene_make(nid_scene *s, sbt_rng *rng, int it, int w, int h, int ch, const int r[5],
                           double depth_slope, double spread, sbt_img *mv)
{
    static const float back_dir[3] = {0.0f, 0.0f, 1.0f}, obj_dir[3] = {0.5f, 0.1f, 0.86f};
    int x, y, c;
    s->cur = sbt_img_new(w, h, ch, 1);
    s->hist = sbt_img_new(w, h, ch, 2);
    s->len = sbt_img_new(w, h, 1, 0);
    s->depth = sbt_img_new(w, h, 1, 1);
    s->pdepth = sbt_img_new(w, h, 1, 0);
    s->nrm = sbt_img_new(w, h, 3, 0);
    s->pnrm = sbt_img_new(w, h, 3, 0);
    s->ids = sbt_img_new(w, h, 1, 0);
    s->pids = sbt_img_new(w, h, 1, 0);
    for (c = 0; c < 4; ++c) s->mem[c] = NULL;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            const int inside = y >= r[1] && y < r[1] + r[3];
            const int now = inside && x >= r[0] && x < r[0] + r[2];
            const int was = inside && x >= r[0] + r[4] && x < r[0] + r[4] + r[2];
            for (c = 0; c < ch; ++c) {
                sbt_at(&s->cur, x, y)[c] = (float)sbt_uniform(rng);
                sbt_at(&s->hist, x, y)[c] = (float)(sbt_uniform(rng) * 2);
            }
            *sbt_at(&s->len, x, y) = (float)(1 + sbt_uniform(rng) * 30);
            /* depth: the object a little nearer only (many of its taps pass the depth
               test and are decided by the normal / id tests) */
            *sbt_at(&s->depth, x, y) = (float)((now ? 3.9 : 4.0) + depth_slope * x);
            *sbt_at(&s->pdepth, x, y) = (float)((was ? 3.9 : 4.0) + depth_slope * x);
            if (mv) {
                if (it % 4 == 0 && sbt_uniform(rng) < 0.1) *sbt_at(&s->pdepth, x, y) = 1.0f;
                sbt_at(mv, x, y)[0] = (float)((sbt_uniform(rng) - 0.5) * 2.5);
                sbt_at(mv, x, y)[1] = (float)((sbt_uniform(rng) - 0.5) * 1.8);
                if (it % 8 == 5) { /* uniform integer motion (the contiguous taps) */
                    sbt_at(mv, x, y)[0] = -1.0f;
                    sbt_at(mv, x, y)[1] = 0.0f;
                }
            }
            nid_normal(sbt_at(&s->nrm, x, y), rng, now ? obj_dir : back_dir, spread, 0.04);
            nid_normal(sbt_at(&s->pnrm, x, y), rng, was ? obj_dir : back_dir, spread, 0.06);
            *sbt_at(&s->ids, x, y) = nid_id(rng, now ? 1.0f : 2.0f, 0.03);
            *sbt_at(&s->pids, x, y) = nid_id(rng, was ? 1.0f : 2.0f, 0.05);
            if (mv && it % 9 == 4 && y == 0) { /* a row without normals, in both frames */
                for (c = 0; c < 3; ++c) sbt_at(&s->nrm, x, y)[c] = sbt_at(&s->pnrm, x, y)[c] = 0.0f;
            }
            if (sbt_uniform(rng) < 0.02) *sbt_at(&s->pdepth, x, y) = (float)HUGE_VAL;
            if (sbt_uniform(rng) < 0.02) sbt_at(&s->hist, x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
            if (sbt_uniform(rng) < 0.03) *sbt_at(&s->len, x, y) = 0.0f;
        }
}

/* The scene's colour, length and depth on a target (current frame / this eye) and a
   source (history / other eye), and its normals and ids by `tests`: 0 and 4 both, 1
   normals only, 2 ids only, 3 both with normals only on the target; the views in
   layouts that vary with `it` */
static void nid_scene_bind(nid_scene *s, int it, int tests, int with_len, sbl_image *color,
                           sbl_gbuffer *g, sbl_image *src_color, sbl_image *src_len, sbl_gbuffer *src_g)
{
    *color = sbt_view(&s->cur);
    g->depth = sbt_view(&s->depth);
    *src_color = sbt_view(&s->hist);
    if (with_len) *src_len = sbt_view(&s->len);
    src_g->depth = sbt_view(&s->pdepth);
    if (tests != 2) g->normals = nid_normals_view(&s->nrm, it % 4, &s->mem[0]);
    if (tests != 2 && tests != 3) src_g->normals = nid_normals_view(&s->pnrm, (it / 4) % 4, &s->mem[1]);
    if (tests != 1) {
        g->ids = nid_ids_view(&s->ids, it % 3, &s->mem[2]);
        src_g->ids = nid_ids_view(&s->pids, (it / 3) % 3, &s->mem[3]);
    }
}

static void nid_scene_free(nid_scene *s)
{
    int i;
    for (i = 0; i < 4; ++i) free(s->mem[i]);
    free(s->cur.mem); free(s->hist.mem); free(s->len.mem); free(s->depth.mem); free(s->pdepth.mem);
    free(s->nrm.mem); free(s->pnrm.mem); free(s->ids.mem); free(s->pids.mem);
}

/* The reprojection options of iteration `it`: the fallback off now and then; with
   tests == 4 the normal test disabled (by a negative threshold where it & threshold_bit,
   else by the flag), else now and then a threshold other than the default */
static void nid_reproject(sbl_reproject_desc *rd, sbt_rng *rng, int it, int tests, int threshold_bit)
{
    memset(rd, 0, sizeof *rd);
    rd->no_fallback = it % 7 == 1;
    if (tests == 4) {
        if (it & threshold_bit) rd->normal_threshold = -1.0f;
        else rd->disabled_tests = SBL_TEST_NORMAL;
    } else if (it % 4 == 3) {
        rd->normal_threshold = (float)(0.5 + 0.5 * sbt_uniform(rng));
    }
}

#endif

static void test_row_gather_normals(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    sbt_rng rng = {9191};
    int it, pixels = 0, mismatches = 0, empty = 0, spixels = 0, smismatches = 0, sempty = 0;
    int nid_rejected = 0;
    for (it = 0; it < 400; ++it) {
        int w = 8 + (int)(sbt_uniform(&rng) * 80), h = 3 + (int)(sbt_uniform(&rng) * 9);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, e, r[5];
        /* which tests: see nid_scene_bind (4: the normal test disabled) */
        const int tests = it % 5, with_len = it % 6 != 0, stereo = it % 3 == 2;
        double spread;
        nid_scene sc;
        sbt_img mv;
        sbl_reproject_desc rd;
        float planes[2][7][100];
        unsigned char unsafe[100];
        sbl__ring_row ra, rb;
        nid_rect(r, &rng, w, h, 6);
        spread = 0.15 + 0.3 * sbt_uniform(&rng);
        nid_reproject(&rd, &rng, it, tests, 1);
        mv = sbt_img_new(w, h, 2, 1);
        nid_scene_make(&sc, &rng, it, w, h, ch, r, 0.01, spread, &mv);
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        if (!stereo) {
            sbl_frame f;
            sbl_history hi;
            sbl__temporal_rp rp;
            memset(&f, 0, sizeof f);
            memset(&hi, 0, sizeof hi);
            nid_scene_bind(&sc, it, tests, with_len, &f.color, &f.gbuffer, &hi.color, &hi.length, &hi.gbuffer);
            f.gbuffer.motion = view(&mv);
            CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &f, &hi), SBL_OK);
            CHECK(sbl__row_gather_ok(&rp.src));
            CHECK_EQ(rp.src.use_normal, tests == 0 || tests == 1);
            CHECK_EQ(rp.src.use_id, tests != 1);
            for (y = 0; y < h; ++y) {
                int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * w), xb = it % 2 ? w : xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
                memset(unsafe, 0, sizeof unsafe);
                sbl__temporal_rp_row(&rp, &ra, y, xa, xb);
                compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "normals / ids", it, w, h,
                                          &pixels, &mismatches, &empty);
                if (tests < 2) { /* the same pixels without the normal / id tests: some
                                    differ, or the tests decided nothing */
                    sbl__temporal_rp q = rp;
                    q.src.use_normal = q.src.use_id = 0;
                    for (x = xa; x < xb; ++x) {
                        float tmp[4] = {0, 0, 0, 0};
                        nid_rejected += sbl__temporal_rp_pixel(&q, x, y, tmp) > 0.0f && !(rb.n[x] > 0.0f);
                    }
                }
            }
        } else {
            /* the stereo row gather: a parallel rig (f b / z = 2.5 .. 2.6 px) or a
               disparity map, the "history" as the other eye */
            sbl_stereo_desc sd;
            sbl_eye eye[2];
            sbl__stereo_rp rp;
            sbt_img disp = sbt_img_new(w, h, 1, 0), disp2 = sbt_img_new(w, h, 1, 0);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    *sbt_at(&disp, x, y) = (float)(2.5 + 0.3 * sbt_uniform(&rng));
                    *sbt_at(&disp2, x, y) = (float)(2.5 + 0.3 * sbt_uniform(&rng));
                }
            memset(eye, 0, sizeof eye);
            nid_scene_bind(&sc, it, tests, with_len, &eye[0].color, &eye[0].gbuffer, &eye[1].color,
                           &eye[1].length, &eye[1].gbuffer);
            eye[0].disparity = view(&disp);
            eye[1].disparity = view(&disp2);
            memset(&sd, 0, sizeof sd);
            sd.rig = it % 2 ? SBL_RIG_DISPARITY : SBL_RIG_PARALLEL;
            sd.focal_px = 10.0f;
            sd.baseline = 1.0f;
            sd.reproject = rd;
            if (it % 4 == 3) sd.reproject.disabled_tests |= SBL_TEST_BACK_CHECK;
            e = (it / 2) & 1;
            CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)e, &eye[e], &eye[!e], 1), SBL_OK);
            rp.tiles = 0; /* (the far tiles, opt-in and within a bound: test_tiles) */
            CHECK(sbl__row_gather_ok(&rp.src));
            for (y = 0; y < h; ++y)
                compare_stereo_with_pixel_gather(&rp, &ra, &rb, y, w, ch, contracts, "stereo normals / ids", it,
                                                 (int)sd.rig, &spixels, &smismatches, &sempty);
            free(disp.mem); free(disp2.mem);
        }
        nid_scene_free(&sc);
        free(mv.mem);
    }
    printf("  %s row gather vs pixel gather, normals / ids: %d pixels (%d without x*, %d by the normal / id "
           "tests), %d differ; stereo %d pixels (%d without a match), %d differ\n",
           SBL_SIMD_NAME, pixels, empty, nid_rejected, mismatches, spixels, sempty, smismatches);
    CHECK(mismatches == 0);
    CHECK(smismatches == 0);
    CHECK(empty > pixels / 20 && empty < pixels / 2);
    CHECK(sempty > spixels / 20 && sempty < spixels / 2);
    CHECK(nid_rejected > pixels / 50);
#endif
}

/* Bands of rows against one whole-image call, bit for bit (colour, N, the evidence
   plane), over the shapes the row gather specialises: 1-4 channels, with and without
   the evidence plane, normals / ids, sky rows, a moved nearer rectangle (the 3x3
   fallback, disocclusions), a zero-motion stretch (rest tiles), random sub-pixel motion
   elsewhere (scattered vectors: the pair gathers). A band loads the rows above and
   below it too, so every row is gathered by several calls: its x* must not depend on
   which. Run in the -ffast-math build as well, where two compiled instances of the same
   sums may round differently (session 11: halo rows gathered without the plane). */
static void test_bands_every_shape(void)
{
    sbt_rng rng = {5151};
    int it, pixels = 0, differ = 0, calls = 0;
    for (it = 0; it < 96; ++it) {
        const int ch = 1 + it % 4, plane = (it / 4) % 2, nid = (it / 8) % 3;
        const int w = 20 + (int)(sbt_uniform(&rng) * 60), h = 6 + (int)(sbt_uniform(&rng) * 12);
        const int ax = (int)(sbt_uniform(&rng) * w * 0.5), ay = (int)(sbt_uniform(&rng) * h * 0.5);
        const int aw = 4 + (int)(sbt_uniform(&rng) * w * 0.4), ah = 2 + (int)(sbt_uniform(&rng) * h * 0.5);
        const int shift = 1 + (int)(sbt_uniform(&rng) * 5), sky_row = it % 3 == 1 ? (int)(sbt_uniform(&rng) * h) : -1;
        const int rx = (int)(sbt_uniform(&rng) * w), rw = (int)(sbt_uniform(&rng) * 40);
        sbt_img cur = sbt_img_new(w, h, ch, 1), hist = sbt_img_new(w, h, ch, 0), len = sbt_img_new(w, h, 1, 0);
        sbt_img depth = sbt_img_new(w, h, 1, 0), pdepth = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 0);
        sbt_img ev = sbt_img_new(w, h, 1, 0), nrm = sbt_img_new(w, h, 3, 0), pnrm = sbt_img_new(w, h, 3, 0);
        sbt_img ids = sbt_img_new(w, h, 1, 0), pids = sbt_img_new(w, h, 1, 0);
        sbt_img oc[2], on[2], oe[2];
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o[2];
        size_t bytes = sbl_temporal_scratch_size(w, ch);
        void *scratch = malloc(bytes);
        int x, y, c, i, y0;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const int in_rect = x >= ax && x < ax + aw && y >= ay && y < ay + ah;
                const int was_rect = x >= ax + shift && x < ax + aw + shift && y >= ay && y < ay + ah;
                for (c = 0; c < ch; ++c) {
                    sbt_at(&cur, x, y)[c] = (float)(0.5 + 0.2 * sbt_uniform(&rng));
                    sbt_at(&hist, x, y)[c] = (float)(0.5 + 0.2 * sbt_uniform(&rng) + (was_rect ? 0.2 : 0.0));
                }
                *sbt_at(&len, x, y) = (float)(1 + 30 * sbt_uniform(&rng));
                *sbt_at(&depth, x, y) = y == sky_row ? (float)HUGE_VAL : in_rect ? 2.0f : (float)(4.0 + 0.1 * sbt_uniform(&rng));
                *sbt_at(&pdepth, x, y) = y == sky_row ? (float)HUGE_VAL : was_rect ? 2.0f : (float)(4.0 + 0.1 * sbt_uniform(&rng));
                if (in_rect) {
                    sbt_at(&mv, x, y)[0] = (float)shift;
                    sbt_at(&mv, x, y)[1] = 0.0f;
                } else if (x >= rx && x < rx + rw) {
                    sbt_at(&mv, x, y)[0] = sbt_at(&mv, x, y)[1] = 0.0f;
                } else {
                    sbt_at(&mv, x, y)[0] = (float)(sbt_uniform(&rng) - 0.5);
                    sbt_at(&mv, x, y)[1] = (float)(sbt_uniform(&rng) - 0.5);
                }
                *sbt_at(&ev, x, y) = (float)(0.5 + 3.0 * sbt_uniform(&rng));
                for (c = 0; c < 3; ++c) {
                    sbt_at(&nrm, x, y)[c] = (float)((c == 2 ? 1.0 : 0.0) + 0.3 * (sbt_uniform(&rng) - 0.5));
                    sbt_at(&pnrm, x, y)[c] = (float)((c == 2 ? 1.0 : 0.0) + 0.3 * (sbt_uniform(&rng) - 0.5));
                }
                *sbt_at(&ids, x, y) = in_rect ? 2.0f : 1.0f;
                *sbt_at(&pids, x, y) = was_rect ? 2.0f : sbt_uniform(&rng) < 0.05 ? 3.0f : 1.0f;
            }
        memset(&d, 0, sizeof d);
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = sbt_view(&cur); f.gbuffer.depth = sbt_view(&depth); f.gbuffer.motion = sbt_view(&mv);
        hi.color = sbt_view(&hist); hi.length = sbt_view(&len); hi.gbuffer.depth = sbt_view(&pdepth);
        if (nid) {
            f.gbuffer.ids = sbt_view(&ids);
            hi.gbuffer.ids = sbt_view(&pids);
            if (nid == 1) { f.gbuffer.normals = sbt_view(&nrm); hi.gbuffer.normals = sbt_view(&pnrm); }
        }
        if (plane) hi.evidence = sbt_view(&ev);
        for (i = 0; i < 2; ++i) {
            oc[i] = sbt_img_new(w, h, ch, 0); on[i] = sbt_img_new(w, h, 1, 0); oe[i] = sbt_img_new(w, h, 1, 0);
            memset(&o[i], 0, sizeof o[i]);
            o[i].color = sbt_view(&oc[i]); o[i].length = sbt_view(&on[i]);
            if (plane || it % 3 == 0) o[i].evidence = sbt_view(&oe[i]);
        }
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o[0]), SBL_OK);
        for (y0 = 0; y0 < h; ++calls) {
            int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 4);
            if (y1 > h) y1 = h;
            CHECK_EQ(sbl_temporal_filter(&d, &f, &hi, &o[1], y0, y1, scratch, bytes), SBL_OK);
            y0 = y1;
        }
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int bad = memcmp(sbt_at(&oc[0], x, y), sbt_at(&oc[1], x, y), sizeof(float) * (size_t)ch) != 0 ||
                          memcmp(sbt_at(&on[0], x, y), sbt_at(&on[1], x, y), sizeof(float)) != 0;
                if (o[0].evidence.data) bad |= memcmp(sbt_at(&oe[0], x, y), sbt_at(&oe[1], x, y), sizeof(float)) != 0;
                if (bad && differ < 3)
                    printf("  bands vs whole: case %d (ch %d plane %d nid %d) x %d y %d: c0 %.9g / %.9g\n", it, ch,
                           plane, nid, x, y, sbt_at(&oc[0], x, y)[0], sbt_at(&oc[1], x, y)[0]);
                differ += bad;
                ++pixels;
            }
        for (i = 0; i < 2; ++i) { free(oc[i].mem); free(on[i].mem); free(oe[i].mem); }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(pdepth.mem); free(mv.mem);
        free(ev.mem); free(nrm.mem); free(pnrm.mem); free(ids.mem); free(pids.mem);
        free(scratch);
    }
    printf("  %s bands vs whole image, every shape: %d pixels in %d banded calls, %d differ\n", SBL_SIMD_NAME,
           pixels, calls, differ);
    CHECK(differ == 0);
}

/* The camera plans with normals and ids: the moving-camera temporal plan
   (sbl__cam_plan_lanes) and the two-camera stereo plan (the matrices and pinhole rigs),
   both through sbl__cam_lanes_k with a row's constants, map positions in double lanes (on-axis and, every fifth scene, off-axis with a turned
   second camera); the row gather against the pixel gather, bit for bit, on the scenes of
   test_row_gather_normals (normals around the threshold's cone, "no normal", NaN / inf /
   overflowing normals, NaN / inf / -0 ids, a moved nearer object), the views packed,
   as channels and bottom-up. Each row is checked to take the lane plan. */
static void test_camera_plans_normals(void)
{
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
    sbt_rng rng = {7373};
    int it, pixels = 0, mismatches = 0, empty = 0, spixels = 0, smismatches = 0, sempty = 0;
    int nid_rejected = 0, lane_rows = 0, rows = 0;
    for (it = 0; it < 160; ++it) {
        int w = 12 + (int)(sbt_uniform(&rng) * 70), h = 4 + (int)(sbt_uniform(&rng) * 8);
        int ch = 1 + (int)(sbt_uniform(&rng) * 4), x, y, i, e, r[5];
        /* which tests: see nid_scene_bind (4: the normal test disabled) */
        const int tests = it % 5, with_len = it % 6 != 0, stereo = it % 2;
        double spread, tx, ty;
        nid_scene sc;
        sbl_reproject_desc rd;
        sbl_intrinsics kin;
        sbl_camera cam[2];
        float pose[2][16];
        float planes[2][7][100];
        unsigned char unsafe[100];
        sbl__ring_row ra, rb;
        nid_rect(r, &rng, w, h, 4);
        spread = 0.15 + 0.3 * sbt_uniform(&rng);
        /* the camera's move: sub-pixel and a few pixels (x), a little in y */
        tx = (sbt_uniform(&rng) - 0.3) * 0.2;
        ty = (sbt_uniform(&rng) - 0.5) * 0.05;
        nid_reproject(&rd, &rng, it, tests, 2);
        nid_scene_make(&sc, &rng, it, w, h, ch, r, 0.001, spread, NULL);
        if (it % 3 == 0) { /* sky (+inf) in both frames / eyes, on interior rows: directions */
            const int sx0 = (int)(sbt_uniform(&rng) * (w - 6));
            for (y = 0; y < h; ++y)
                for (x = sx0; x < sx0 + 6; ++x) {
                    *sbt_at(&sc.depth, x, y) = (float)HUGE_VAL;
                    *sbt_at(&sc.pdepth, x, y) = (float)HUGE_VAL;
                }
        }
        kin.fx = kin.fy = (float)(0.8 * w + 3);
        kin.cx = 0.5f * (float)w;
        kin.cy = 0.5f * (float)h;
        if (it % 5 == 3) { /* off-axis, unequal focal lengths, the second camera turned a little */
            kin.fy = (float)(0.7 * w + 5);
            kin.cx = (float)((0.35 + 0.3 * sbt_uniform(&rng)) * w);
            kin.cy = (float)((0.35 + 0.3 * sbt_uniform(&rng)) * h);
        }
        for (e = 0; e < 2; ++e) {
            for (i = 0; i < 16; ++i) pose[e][i] = i % 5 == 0 ? 1.0f : 0.0f;
            if (e) { pose[e][3] = (float)tx; pose[e][7] = (float)ty; }
            if (e && it % 5 == 3) { /* about y by ~0.3 degrees (a few pixels at this focal length) */
                const float a = (float)(0.005 * (sbt_uniform(&rng) - 0.5));
                pose[e][0] = pose[e][10] = cosf(a);
                pose[e][2] = sinf(a);
                pose[e][8] = -sinf(a);
            }
            CHECK_EQ(sbl_camera_from_pinhole(&cam[e], &kin, pose[e], SBL_AXES_OPENCV, 0, w, h), SBL_OK);
        }
        BIND_RING_ROWS(ra, rb, planes, unsafe);
        if (!stereo) {
            sbl_frame f;
            sbl_history hi;
            sbl__temporal_rp rp;
            memset(&f, 0, sizeof f);
            memset(&hi, 0, sizeof hi);
            nid_scene_bind(&sc, it, tests, with_len, &f.color, &f.gbuffer, &hi.color, &hi.length, &hi.gbuffer);
            f.camera = &cam[1];
            hi.camera = &cam[0];
            CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_CAMERA, &f, &hi), SBL_OK);
            CHECK(sbl__row_gather_ok(&rp.src));
            CHECK_EQ(rp.src.use_normal, tests == 0 || tests == 1);
            CHECK_EQ(rp.src.use_id, tests != 1);
            for (y = 0; y < h; ++y) {
                int xa = it % 4 < 2 ? 0 : (int)(sbt_uniform(&rng) * w);
                int xb = it % 4 < 2 ? w : xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
                memset(unsafe, 0, sizeof unsafe);
                lane_rows += sbl__camera_plan_lanes_ok(&rp, y);
                ++rows;
                sbl__temporal_rp_row(&rp, &ra, y, xa, xb);
                compare_with_pixel_gather(&rp, &ra, &rb, y, xa, xb, ch, contracts, "camera normals / ids", it, w,
                                          h, &pixels, &mismatches, &empty);
                if (tests < 2) { /* the normal / id tests decide some pixels */
                    sbl__temporal_rp q = rp;
                    q.src.use_normal = q.src.use_id = 0;
                    for (x = xa; x < xb; ++x) {
                        float tmp[4] = {0, 0, 0, 0};
                        nid_rejected += sbl__temporal_rp_pixel(&q, x, y, tmp) > 0.0f && !(rb.n[x] > 0.0f);
                    }
                }
            }
        } else {
            /* the matrices rig (eye cameras) or the pinhole rig of the same pair; the
               "history" as the other eye */
            sbl_stereo_desc sd;
            sbl_eye eye[2];
            sbl__stereo_rp rp;
            memset(eye, 0, sizeof eye);
            nid_scene_bind(&sc, it, tests, with_len, &eye[0].color, &eye[0].gbuffer, &eye[1].color,
                           &eye[1].length, &eye[1].gbuffer);
            eye[0].camera = &cam[0];
            eye[1].camera = &cam[1];
            memset(&sd, 0, sizeof sd);
            if (it % 4 == 1) {
                sd.rig = SBL_RIG_MATRICES;
            } else {
                sd.rig = SBL_RIG_PINHOLE;
                sd.pinhole.eye[0] = sd.pinhole.eye[1] = kin;
                memcpy(sd.pinhole.right_from_left, pose[1], sizeof pose[1]);
                sd.pinhole.axes = SBL_AXES_OPENCV;
            }
            sd.reproject = rd;
            sd.reproject.back_check_pixels = 2.0f;
            if (it % 8 == 7) sd.reproject.disabled_tests |= SBL_TEST_BACK_CHECK;
            e = (it / 2) & 1;
            CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)e, &eye[e], &eye[!e], 1), SBL_OK);
            rp.d.rig = sd.rig; /* the camera maps (most of these rigs are parallel: sbl__rig_as_parallel) */
            rp.tiles = 0; /* (the far tiles, opt-in and within a bound: test_tiles) */
            CHECK(sbl__row_gather_ok(&rp.src));
            for (y = 0; y < h; ++y) {
                sbl__block b;
                memset(&b, 0, sizeof b);
                b.y = y;
                b.row_state = -1;
                sbl__stereo_block_start(&rp, &ra, &b);
                lane_rows += b.mode == 2;
                ++rows;
                compare_stereo_with_pixel_gather(&rp, &ra, &rb, y, w, ch, contracts, "camera stereo normals / ids",
                                                 it, (int)sd.rig, &spixels, &smismatches, &sempty);
            }
        }
        nid_scene_free(&sc);
    }
    printf("  %s camera plans vs pixel gather, normals / ids: temporal %d pixels (%d without x*, %d by the "
           "normal / id tests), %d differ; stereo %d pixels (%d without a match), %d differ; %d of %d rows "
           "in the lane plan\n",
           SBL_SIMD_NAME, pixels, empty, nid_rejected, mismatches, spixels, sempty, smismatches, lane_rows, rows);
    CHECK(mismatches == 0);
    CHECK(smismatches == 0);
    CHECK(empty > pixels / 20 && empty < pixels / 2);
    CHECK(sempty > spixels / 20 && sempty < spixels / 2);
    CHECK(nid_rejected > pixels / 50);
    CHECK(lane_rows > rows / 2);
#endif
}

/* The folded camera map (sbl__cam_map_apply, session 28: sbl__cam_map_fold's rows) against
   the matrix chain it replaced (sbl__cam_map_point, view_to_view, sbl__cam_map_project,
   which listed moving objects still take): the same validity and the same position and
   depth within rounding (1e-9 of the image size, 1e-9 relative), for random camera pairs
   (rotated and translated poses, off-axis principal points, unequal focal lengths, a
   world-to-pixel P with a skew, cameras facing away) at depths from 1e-3 to 1e6 and +inf
   (a direction); positions relative to the image's size, or to the position itself
   where it lies far outside. And the double lanes (sbl__cam_lanes) against the folded
   reference, bit for bit (within 1e-9 where the compiler contracts or reorders). test_paths' row-gather checks compare the lanes with the folded
   reference; this one checks the fold itself. */
#ifdef SBL__ROW_GATHER
/* 1 if a camera-map lane (valid bit lane_ok, position o) differs from the reference (r,
   position ref): bit for bit, or within rounding where the compiler contracts (fused or
   reordered) */
static int cam_lane_differs(int contracts, int r, int lane_ok, double ox, double oy, double oz,
                            double rx, double ry, double rz)
{
    if (r != lane_ok) return 1;
    if (!r) return 0;
    if (contracts)
        return !(fabs(ox - rx) <= 1e-9 * fmax(1.0, fabs(rx)) && fabs(oy - ry) <= 1e-9 * fmax(1.0, fabs(ry)) &&
                 (oz == rz || fabs(oz - rz) <= 1e-9 * fabs(rz)));
    return memcmp(&ox, &rx, sizeof rx) != 0 || memcmp(&oy, &ry, sizeof ry) != 0 || memcmp(&oz, &rz, sizeof rz) != 0;
}

#endif
static void test_cam_map_fold(void)
{
    sbt_rng rng = {4242};
    int it, k, maps = 0, valid = 0, bad_valid = 0, bad_pos = 0, sky = 0, lanes = 0, bad_lanes = 0;
    double worst = 0.0;
#ifdef SBL__ROW_GATHER
    const int contracts = compiler_contracts();
#endif
    for (it = 0; it < 400; ++it) {
        const int w = 16 + (int)(sbt_uniform(&rng) * 2000), h = 16 + (int)(sbt_uniform(&rng) * 1200);
        sbl_camera cam[2];
        sbl__cam_map m;
        int e;
        for (e = 0; e < 2; ++e) {
            float pose[16];
            const double ax = (sbt_uniform(&rng) - 0.5) * (it % 7 == 0 ? 6.0 : 0.6),
                         ay = (sbt_uniform(&rng) - 0.5) * (it % 7 == 0 ? 6.0 : 0.6),
                         az = (sbt_uniform(&rng) - 0.5) * 0.6;
            const double cx = cos(ax), sx = sin(ax), cy = cos(ay), sy = sin(ay), cz = cos(az), sz = sin(az);
            /* R = Rz Ry Rx, t random */
            const double R[9] = {cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx,
                                 sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx,
                                 -sy, cy * sx, cy * cx};
            int r, c;
            for (r = 0; r < 3; ++r) {
                for (c = 0; c < 3; ++c) pose[r * 4 + c] = (float)R[r * 3 + c];
                pose[r * 4 + 3] = (float)((sbt_uniform(&rng) - 0.5) * 2.0);
            }
            pose[12] = pose[13] = pose[14] = 0.0f;
            pose[15] = 1.0f;
            if (it % 3 == 2) { /* a world-to-pixel P = K [R | t] with a skew */
                float P[12];
                const double fx = 300 + sbt_uniform(&rng) * 900, fy = 300 + sbt_uniform(&rng) * 900,
                             skew = (sbt_uniform(&rng) - 0.5) * 20.0,
                             pcx = w * (0.3 + 0.4 * sbt_uniform(&rng)), pcy = h * (0.3 + 0.4 * sbt_uniform(&rng));
                for (c = 0; c < 4; ++c) {
                    P[c] = (float)(fx * pose[c] + skew * pose[4 + c] + pcx * pose[8 + c]);
                    P[4 + c] = (float)(fy * pose[4 + c] + pcy * pose[8 + c]);
                    P[8 + c] = pose[8 + c];
                }
                CHECK_EQ(sbl_camera_from_world_to_pixel(&cam[e], P, it % 2, w, h), SBL_OK);
            } else {
                sbl_intrinsics kin;
                kin.fx = (float)(300 + sbt_uniform(&rng) * 900);
                kin.fy = (float)(300 + sbt_uniform(&rng) * 900);
                kin.cx = (float)(w * (0.3 + 0.4 * sbt_uniform(&rng))); /* off-axis */
                kin.cy = (float)(h * (0.3 + 0.4 * sbt_uniform(&rng)));
                CHECK_EQ(sbl_camera_from_pinhole(&cam[e], &kin, pose, it % 2 ? SBL_AXES_OPENGL : SBL_AXES_OPENCV,
                                                 it % 4 == 1, w, h), SBL_OK);
            }
        }
        if (!sbl__cam_map_init(&m, &cam[0], w, h, &cam[1], w, h)) continue;
#ifdef SBL__ROW_GATHER
        for (k = 0; k < 8; ++k) { /* the lanes (sbl__cam_lanes) against the reference, bit for bit */
            double px[SBL__VW], py[SBL__VW], ox[SBL__VW], oy[SBL__VW], oz[SBL__VW];
            float zf[SBL__VW];
            int l, bits;
            for (l = 0; l < SBL__VW; ++l) {
                px[l] = (int)(sbt_uniform(&rng) * w) + 0.5;
                py[l] = (int)(sbt_uniform(&rng) * h) + 0.5;
                zf[l] = l % 5 == 4 ? (float)HUGE_VAL : (float)pow(10.0, -3.0 + 9.0 * sbt_uniform(&rng));
            }
            bits = sbl__cam_lanes(&m, px, py, zf, ox, oy, oz);
            for (l = 0; l < SBL__VW; ++l) {
                double rx = 0, ry = 0, rz = 0;
                const int r = sbl__cam_map_apply(&m, px[l], py[l], zf[l], &rx, &ry, &rz);
                const int bad = cam_lane_differs(contracts, r, (bits >> l) & 1, ox[l], oy[l], oz[l], rx, ry, rz);
                if (bad && bad_lanes < 3)
                    printf("  fold: lanes vs reference, map %d: valid %d / %d, (%.17g, %.17g, %.17g) against "
                           "(%.17g, %.17g, %.17g)\n", it, (bits >> l) & 1, r, ox[l], oy[l], oz[l], rx, ry, rz);
                bad_lanes += bad;
                ++lanes;
            }
        }
        for (k = 0; k < 8; ++k) { /* the row mode (sbl__cam_k_row: a row's constants, the
                                     temporal camera plans and the two-camera rigs), at the
                                     image's first and last rows and columns too */
            sbl__cam_k ck;
            double ox[SBL__VW], oy[SBL__VW], oz[SBL__VW];
            float zf[SBL__VW + 4];
            const int y = k == 0 ? 0 : k == 1 ? h - 1 : (int)(sbt_uniform(&rng) * h);
            const int x = k == 2 ? 0 : k == 3 ? w - SBL__VW : (int)(sbt_uniform(&rng) * (w - SBL__VW + 1));
            int l, bits;
            for (l = 0; l < SBL__VW + 4; ++l)
                zf[l] = l >= SBL__VW ? 0.0f : (l + k) % 5 == 4 ? (float)HUGE_VAL
                                                          : (float)pow(10.0, -3.0 + 9.0 * sbt_uniform(&rng));
            sbl__cam_k_init(&ck, &m);
            sbl__cam_k_row(&ck, y);
            bits = sbl__cam_lanes_k(&ck, 1, x, NULL, NULL, zf, ox, oy, oz);
            for (l = 0; l < SBL__VW; ++l) {
                double rx = 0, ry = 0, rz = 0;
                const int r = sbl__cam_map_apply(&m, x + l + 0.5, y + 0.5, zf[l], &rx, &ry, &rz);
                const int bad = cam_lane_differs(contracts, r, (bits >> l) & 1, ox[l], oy[l], oz[l], rx, ry, rz);
                if (bad && bad_lanes < 3)
                    printf("  fold: row lanes vs reference, map %d, row %d, x %d: valid %d / %d, (%.17g, %.17g, "
                           "%.17g) against (%.17g, %.17g, %.17g)\n", it, y, x + l, (bits >> l) & 1, r, ox[l], oy[l],
                           oz[l], rx, ry, rz);
                bad_lanes += bad;
                ++lanes;
            }
        }
#endif
        for (k = 0; k < 200; ++k) {
            const double px = sbt_uniform(&rng) * w, py = sbt_uniform(&rng) * h;
            const float z = k % 10 == 0 ? (float)HUGE_VAL : (float)pow(10.0, -3.0 + 9.0 * sbt_uniform(&rng));
            double p4[4], v4[4], ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
            const int a = sbl__cam_map_apply(&m, px, py, z, &ax, &ay, &az);
            const int b = sbl__cam_map_point(&m, px, py, z, p4) &&
                          (sbl__mat_apply(v4, m.view_to_view, p4), sbl__cam_map_project(&m, v4, &bx, &by, &bz));
            ++maps;
            if (a != b) {
                if (bad_valid < 3) printf("  fold: map %d: valid %d, the chain %d\n", it, a, b);
                ++bad_valid;
                continue;
            }
            if (!a) continue;
            ++valid;
            sky += sbl__is_pos_inf(z);
            {
                /* relative to the image's size, or to the position where it lies far outside */
                const double scale = fmax(fmax((double)(w > h ? w : h), fabs(bx)), fabs(by));
                const double rel = (fabs(ax - bx) + fabs(ay - by)) / scale,
                             ez = az == bz ? 0.0 : fabs(az - bz) / fabs(bz);
                if (!(rel <= 1e-9 && ez <= 1e-9)) {
                    if (bad_pos < 3)
                        printf("  fold: map %d: (%.17g, %.17g, %.17g) against (%.17g, %.17g, %.17g)\n", it, ax, ay,
                               az, bx, by, bz);
                    ++bad_pos;
                }
                if (rel > worst) worst = rel;
                if (ez > worst) worst = ez;
            }
        }
    }
    printf("  folded camera map vs the matrix chain: %d maps, %d valid (%d directions), validity differs %d, "
           "position / depth beyond 1e-9 %d (worst %.2g relative); %s lanes vs the folded reference: %d maps, "
           "%d differ\n",
           maps, valid, sky, bad_valid, bad_pos, worst, SBL_SIMD_NAME, lanes, bad_lanes);
    CHECK(bad_lanes == 0);
    CHECK(bad_valid == 0);
    CHECK(bad_pos == 0);
    CHECK(valid > maps / 4 && valid < maps);
    CHECK(sky > 0);
}

/* (blur, session 16) The resampling blur's noise factor's fit (docs/ESTIMATORS.md 4.13,
   bench/blur_fit.c; the blur's own tests are in test_accuracy, which cannot reach it) against the sum it
   stands for, G(n, v) = (1 / n) sum_{k < n} g(k v), g(s) = (1 / 2 pi) int_{-pi}^{pi}
   16 sin^4(w / 2) e^{-s w^2} dw by Simpson's rule: within the stated 0.31 % at points
   across n in [1, 200], v in (0, 1/4] (the fit's worst measured, n 1 at v 1/16, among
   them) */
static double blur_g_exact(double s)
{
    const int q = 2000;
    const double pi = 3.14159265358979323846;
    double acc = 0.0;
    int i;
    for (i = 0; i <= q; ++i) {
        const double w = -pi + i * (2.0 * pi / q), sn = sin(0.5 * w);
        acc += (i == 0 || i == q ? 1.0 : (i & 1) ? 4.0 : 2.0) * 16.0 * sn * sn * sn * sn * exp(-s * w * w);
    }
    return acc * (2.0 * pi / q) / 3.0 / (2.0 * pi);
}

/* sbl__rig_as_parallel: two cameras that form a parallel rig (either eye the target; the
   pinhole rig and the matrices rig, world poses turned and moved alike, principal points
   that differ) run as SBL_RIG_PARALLEL with f b and the offset the cameras imply, and
   find the same matches as the camera maps (every pixel of a scene with sky and depth
   steps, both run through the per-pixel reference); with f b a float product that the
   pinhole rig's double maps reproduce exactly, sbl_stereo_blend's output is the parallel
   rig's bit for bit (the matrices rig's float projection holds fx to an ulp: within
   1e-5). A
   rig that is not parallel (toed in by 2e-3 rad, a vertical offset of 1 % of the
   baseline, a depth offset of 5 %, fy 1 % apart, the eyes swapped, the right view scaled
   by 1.001 (its depths, so the disparities, 0.1 % apart), cy 0.01 px apart beside an
   offset, a projection whose rays turn invalid 0.25 px or a quarter of the width inside
   the image, or a vertical baseline whose 8e-4 px at the nearest checked depth halve at
   the next) keeps its cameras. A turn of 1e-9 rad is parallel to far below the tolerance. */
static void test_rig_as_parallel(void)
{
    sbt_rng rng = {8128};
    int it, routed = 0, kept = 0, wrong_route = 0, bad_fb = 0, blends = 0, blend_differ = 0;
    long pixels = 0, valid = 0, differ = 0;
    double worst = 0.0;
    for (it = 0; it < 260; ++it) {
        const int kind = it % 13, w = 24 + (int)(sbt_uniform(&rng) * 48), h = 12 + (int)(sbt_uniform(&rng) * 24);
        const int ch = 3, tgt = (it / 13) & 1, parallel = kind <= 3,
                  matrices = kind == 9 || kind == 11 || (it / 2) % 2;
        const float b = 0.125f;
        sbl_intrinsics kin[2];
        float rfl[16], pose[2][16];
        sbt_img col[2], len[2], dep[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl_camera cam[2];
        sbl__stereo_rp rp, rc;
        int e, x, y, c, i;
        kin[0].fx = 500.0f; kin[0].fy = 480.0f;
        kin[0].cx = (float)(w * (0.35 + 0.3 * sbt_uniform(&rng)));
        kin[0].cy = (float)(h * (0.35 + 0.3 * sbt_uniform(&rng)));
        kin[1] = kin[0];
        if (kind == 1 || kind == 3 || kind == 10) kin[1].cx += (float)(4.0 * sbt_uniform(&rng) - 2.0); /* an offset */
        if (kind == 10) kin[1].cy += 0.01f;
        if (kind == 7) kin[1].fy *= 1.01f;
        /* right_from_left in OpenCV axes: x_r = R x_l + T, the right eye b to the right */
        for (i = 0; i < 16; ++i) rfl[i] = i % 5 == 0 ? 1.0f : 0.0f;
        rfl[3] = -b;
        if (kind == 2 || kind == 4) { /* turned about the vertical axis */
            const double a = kind == 2 ? 1e-9 : 2e-3;
            rfl[0] = rfl[10] = (float)cos(a);
            rfl[2] = (float)sin(a);
            rfl[8] = (float)-sin(a);
        }
        if (kind == 5) rfl[7] = 0.01f * b;
        if (kind == 6) rfl[11] = 0.05f * b;
        if (kind == 8) rfl[3] = b; /* the right eye's camera to the left: swapped */
        if (kind == 12) /* 8e-4 px vertically at the disparity w (fb 62.5), 4e-4 at w / 2 */
            rfl[7] = (float)(8e-4 * 62.5 / ((double)kin[1].fy * w));
        {   /* the same pair as world poses: the left eye turned and moved, the right eye
               rfl after it (composed in double, stored in float as a renderer would) */
            const double ax = 0.3 * (sbt_uniform(&rng) - 0.5), ay = 0.3 * (sbt_uniform(&rng) - 0.5);
            const double R[9] = {cos(ay), sin(ay) * sin(ax), sin(ay) * cos(ax),
                                 0.0, cos(ax), -sin(ax),
                                 -sin(ay), cos(ay) * sin(ax), cos(ay) * cos(ax)};
            double t[3];
            int r;
            for (r = 0; r < 3; ++r) t[r] = floor((sbt_uniform(&rng) - 0.5) * 64.0) / 64.0; /* (t - b exact) */
            for (i = 0; i < 16; ++i) pose[0][i] = pose[1][i] = 0.0f;
            for (r = 0; r < 3; ++r) {
                for (c = 0; c < 3; ++c) pose[0][r * 4 + c] = (float)R[r * 3 + c];
                pose[0][r * 4 + 3] = (float)t[r];
            }
            pose[0][15] = pose[1][15] = 1.0f;
            for (r = 0; r < 3; ++r)
                for (c = 0; c < 4; ++c) {
                    double v = c == 3 ? (double)rfl[r * 4 + 3] : 0.0;
                    int k;
                    for (k = 0; k < 3; ++k) v += (double)rfl[r * 4 + k] * (double)pose[0][k * 4 + c];
                    pose[1][r * 4 + c] = (float)v;
                }
            if (parallel) /* the same rotation bits in both eyes, as a rig's eye offsets give them */
                for (r = 0; r < 3; ++r)
                    for (c = 0; c < 3; ++c) pose[1][r * 4 + c] = pose[0][r * 4 + c];
            if (kind == 9)
                for (r = 0; r < 12; ++r) pose[1][r] *= 1.001f;
        }
        for (e = 0; e < 2; ++e)
            CHECK_EQ(sbl_camera_from_pinhole(&cam[e], &kin[e], pose[e], SBL_AXES_OPENCV, 0, w, h), SBL_OK);
        if (kind == 11) { /* the right eye's depth row (-1, 0, -u0, 1): rays valid right of u0 only */
            float *P = cam[1].view_to_clip;
            const double edge = (it / 26) % 2 ? 0.25 : 0.25 * w, n0 = 2.0 * edge / w - 1.0;
            const double u0 = (n0 + (double)P[2]) / (double)P[0];
            P[8] = -1.0f; P[9] = 0.0f; P[10] = (float)-u0; P[11] = 1.0f;
        }
        for (e = 0; e < 2; ++e) {
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    const double u = sbt_uniform(&rng);
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)sbt_uniform(&rng);
                    *sbt_at(&len[e], x, y) = (float)(1 + sbt_uniform(&rng) * 20);
                    /* disparities of about 3-8 px; depth by rows (planes facing the rig,
                       the same in both eyes), a step every 7 rows */
                    *sbt_at(&dep[e], x, y) = (float)(8.0 + 0.2 * y + (y % 7 < 2 ? 6.0 : 0.0));
                    if (u < 0.05) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = sbt_view(&col[e]);
            eye[e].length = sbt_view(&len[e]);
            eye[e].gbuffer.depth = sbt_view(&dep[e]);
            eye[e].camera = &cam[e];
        }
        memset(&sd, 0, sizeof sd);
        if (matrices) {
            sd.rig = SBL_RIG_MATRICES;
        } else {
            sd.rig = SBL_RIG_PINHOLE;
            sd.pinhole.eye[0] = kin[0];
            sd.pinhole.eye[1] = kin[1];
            memcpy(sd.pinhole.right_from_left, rfl, sizeof rfl);
            sd.pinhole.axes = SBL_AXES_OPENCV;
        }
        sd.reproject.back_check_pixels = 0.5f;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], 1), SBL_OK);
        if (rp.d.rig != (parallel ? SBL_RIG_PARALLEL : sd.rig)) ++wrong_route;
        if (rp.d.rig == SBL_RIG_PARALLEL) {
            ++routed;
            /* f b = fx b; the offset cx_right - cx_left (the disparity's convention) */
            if (!(fabs(rp.fb - 62.5f) <= 62.5f * 1e-6f) ||
                !(fabs(rp.offset - ((double)kin[1].cx - (double)kin[0].cx)) <= 1e-4))
                ++bad_fb;
        } else {
            ++kept;
        }
        rc = rp;
        rc.d.rig = sd.rig; /* the camera maps */
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                float op[4] = {0, 0, 0, 0}, oc[4] = {0, 0, 0, 0};
                const float np = sbl__stereo_rp_pixel(&rp, x, y, op), nc = sbl__stereo_rp_pixel(&rc, x, y, oc);
                ++pixels;
                if ((np > 0.0f) != (nc > 0.0f)) { ++differ; continue; }
                if (!(np > 0.0f)) continue;
                ++valid;
                for (c = 0; c < ch; ++c)
                    if (fabs((double)op[c] - (double)oc[c]) > worst) worst = fabs((double)op[c] - (double)oc[c]);
            }
        if (parallel && kind != 1 && kind != 3) { /* no offset: the public call, bit for bit */
            sbl_stereo_desc pd;
            sbt_img o1 = sbt_img_new(w, h, ch, 0), o2 = sbt_img_new(w, h, ch, 0);
            const size_t bytes = sbl_stereo_scratch_size(w, ch);
            void *scratch = malloc(bytes);
            memset(&pd, 0, sizeof pd);
            pd.rig = SBL_RIG_PARALLEL;
            pd.focal_px = kin[0].fx;
            pd.baseline = b;
            pd.reproject = sd.reproject;
            CHECK_EQ(sbl_stereo_blend(&sd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], sbt_view(&o1),
                                      sbl_image_make(NULL, 0, 0, 1), 0, h, scratch, bytes), SBL_OK);
            CHECK_EQ(sbl_stereo_blend(&pd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], sbt_view(&o2),
                                      sbl_image_make(NULL, 0, 0, 1), 0, h, scratch, bytes), SBL_OK);
            ++blends;
            if (!matrices) { /* the pinhole rig's maps are double: f b is 62.5 exactly */
                if (memcmp(o1.mem, o2.mem, sizeof(float) * (size_t)(w * ch * h)) != 0) ++blend_differ;
            } else { /* a float projection matrix holds fx / w to 6e-8: f b within an ulp */
                for (i = 0; i < w * ch * h; ++i)
                    if (!(fabs((double)o1.mem[i] - (double)o2.mem[i]) <= 1e-5)) break;
                if (i < w * ch * h) ++blend_differ;
            }
            free(scratch);
            free(o1.mem);
            free(o2.mem);
        }
        for (e = 0; e < 2; ++e) {
            free(col[e].mem);
            free(len[e].mem);
            free(dep[e].mem);
        }
    }
    printf("  two cameras as a parallel rig: %d routed, %d kept (%d on the wrong side), f b / offset "
           "off %d; matches against the camera maps: %ld of %ld pixels differ in validity, worst "
           "colour %.2g over %ld valid; the public blend against SBL_RIG_PARALLEL: %d of %d differ\n",
           routed, kept, wrong_route, bad_fb, differ, pixels, worst, valid, blend_differ, blends);
    CHECK_EQ(wrong_route, 0);
    CHECK_EQ(bad_fb, 0);
    CHECK(routed == 80 && kept == 180);
    CHECK(valid > pixels / 2);
    CHECK(differ * 10000 <= pixels);
    CHECK(worst <= 1e-4);
    CHECK_EQ(blend_differ, 0);
    CHECK(blends == 40);
}

/* The restart lean (docs/ESTIMATORS.md 6.3, 6.4, 6.6) in the staged lanes against the double
   reference: rows of a 45 x 5 image (first and last rows with their two-row windows,
   both border columns, full chunks and chunks with invalid x*), a history that jumps
   over a random run of columns so that the weight passes the lean's gate there, at
   value scales 1, 3e13 and 1e-9. The lean's share is continuous in the weight (two
   ramps, 6.6), so no pixel is skipped. The last 600 cases run behind a stereo blend
   (stereo_shared_bias 1 or 0.35, 6.10): the blur's instances, whose lean gates on the
   change's weight and counts the texture 1 + c times, with per-pixel fractional motion
   (some integer: no blur), a quarter of them with the camera source's positions instead
   (at every scale; a fifth of those with the camera at rest and one moving object, where
   only the object's pixels may be fetched at a fraction and blurred);
   two thirds of them with the carried evidence's mix (3.11), some of those with the
   region's M (3.10, sbl__evidence_region), the rest without the evidence plane. */
#define LPW 45
#define LPH 5

/* one row y of the kernel, lanes or the reference, with the lean on or off */
static void lean_row(sbl__kernel *k, int y, int lean, int lanes, float (*oc)[4], float *on,
                     float *oa, int *full)
{
    const sbl__ring_row *R[3];
    int j, x, c;
    for (j = 0; j < 3; ++j) {
        const int ry = y - 1 + j;
        k->ring[j].row = -1;
        if (ry >= 0 && ry < LPH) {
            sbl__ring_load(k, &k->ring[j], ry, 0, LPW);
            sbl__ring_note_valid(&k->ring[j], 0, LPW);
        }
        R[j] = k->ring[j].row >= 0 ? &k->ring[j] : NULL;
    }
    k->wp.lean_restart = lean;
    k->edge_row = y == 0 ? 1 : y == LPH - 1 ? 2 : 0;
    k->edge_ask = 3;
    /* the lanes' run also forms the row's pooled ratio, which the reference reads */
    k->rows_valid = lanes && R[0] && R[2] ? (R[0]->all_valid & R[1]->all_valid & R[2]->all_valid) : 0;
    if (full) *full = k->rows_valid;
    sbl__kernel_lanes_pooled(k, R, 0, LPW, 1, LPW - 1, NULL);
    CHECK_EQ(k->edge_done, 3);
    k->edge_row = 0;
    k->rows_valid = 0;
    if (!lanes)
        for (x = 0; x < LPW; ++x) sbl__kernel_pixel_ref(k, R, x);
    for (x = 0; x < LPW; ++x) {
        for (c = 0; c < k->ch; ++c) oc[x][c] = k->stage[c][x];
        on[x] = k->stage_n[x];
        oa[x] = k->stage_a[x];
    }
}

static void test_restart_lean_paths(void)
{
    static float own[LPH * LPW * 4], motion[LPH * LPW * 2], evid_in[LPW + 64], evid_out[LPW + 64];
    static paths_gather G; /* (LPW x LPH fits: PGW x PGH) */
    sbt_rng rng = {4242};
    long compared = 0, leaned_ref = 0, leaned_lanes = 0, full_rows = 0, behind_leaned = 0, blurred = 0, behind_compared = 0;
    long blurred_cam = 0, cam_compared = 0, blurred_obj = 0, blurred_still = 0, obj_compared = 0;
    static float ids[LPH * LPW];
    double worst = 0.0;
    int it;
    /* the at-rest cases' ids: 2 (columns 9-28) the moving object, 1 the still rest */
    for (it = 0; it < LPH * LPW; ++it) ids[it] = it % LPW >= 9 && it % LPW < 29 ? 2.0f : 1.0f;
    for (it = 0; it < 2100; ++it) {
        const int behind = it >= 1500; /* behind a stereo blend (c > 0) */
        /* the blur's fractions from the camera source (at each scale: it % 10 is 3, 8, 9);
           in some the camera at rest with one object moving (the object's pixels alone
           at fractional positions) */
        const int camera = behind && (it % 5 == 3 || it % 20 == 9);
        const int rest = camera && it % 20 == 13;
        sbl__temporal_rp brp;
        sbl__kernel k;
        sbl_image im;
        void *scratch;
        const int ch = 1 + it % 4, all_valid = it % 3 == 0;
        const double scale = it % 10 == 9 ? 3e13 : it % 10 == 8 ? 1e-9 : 1.0;
        const double amp = 0.2 * sbt_uniform(&rng), jump = 0.05 + 0.6 * sbt_uniform(&rng);
        const double sigma = 0.02 + 0.08 * sbt_uniform(&rng);
        const int x0 = (int)(sbt_uniform(&rng) * LPW), x1 = x0 + (int)(sbt_uniform(&rng) * LPW);
        int x, y, c;
        for (y = 0; y < LPH; ++y)
            for (x = 0; x < LPW; ++x) {
                const double t = 0.5 + amp * sin(0.9 * x + 1.3 * y);
                const double u = sbt_uniform(&rng);
                const float n = (!all_valid && u < 0.1) ? 0.0f
                                : (float)(sbt_uniform(&rng) < 0.3 ? 1 + (int)(3 * sbt_uniform(&rng))
                                                                  : 1 + 40 * sbt_uniform(&rng));
                for (c = 0; c < 4; ++c) {
                    own[(y * LPW + x) * ch + c] = (float)(scale * (t + 0.03 * c + sigma * sbt_gauss(&rng)));
                    G.x[y][x][c] = (float)(scale * (t + 0.03 * c + (x >= x0 && x < x1 ? jump : 0.0) +
                                                    sigma * sbt_gauss(&rng) / sqrt(n > 0.0f ? n : 1.0f)));
                }
                G.n[y][x] = n;
            }
        memset(&k, 0, sizeof k);
        im = sbl_image_make(own, LPW, LPH, ch);
        k.w = LPW; k.h = LPH; k.ch = ch;
        k.wp.estimator = SBL_ESTIMATOR_POOLED;
        k.wp.rectify = SBL_RECTIFY_NONE;
        k.wp.mode = SBL_WEIGHT_SCALAR;
        k.wp.bias_threshold = 3.0f;
        k.wp.temporal = 1;
        k.n_cap = 64.0f;
        k.temporal = 1;
        k.own = &im;
        k.gather = paths_gather_fn;
        k.gather_ctx = &G;
        if (behind) {
            /* as sbl_temporal_filter at c > 0: the blur's term from the fetch's fractions
               (motion vectors, a third of them whole pixels) and the evidence's mix */
            for (y = 0; y < LPH; ++y)
                for (x = 0; x < LPW; ++x) {
                    const int whole = sbt_uniform(&rng) < 0.33;
                    for (c = 0; c < 2; ++c) {
                        const double m = 4.0 * sbt_uniform(&rng) - 2.0;
                        motion[(y * LPW + x) * 2 + c] = (float)(whole ? floor(m) : m);
                    }
                }
            for (x = 0; x < LPW + 64; ++x) evid_in[x] = (float)(0.5 + 8.0 * sbt_uniform(&rng));
            memset(&brp, 0, sizeof brp);
            brp.source = SBL_TEMPORAL_MOTION;
            brp.motion.p = motion;
            brp.motion.stride = LPW * 2;
            brp.motion.step = 2;
            brp.motion.ch = 2;
            brp.motion_kx = brp.motion_ky = 1.0;
            if (camera) {
                /* the camera source (the lanes take each lane's fraction from
                   sbl__blur_fraction at its own pixel): a camera moved sideways and
                   forward over a depth that varies per pixel, so the fractions do; some
                   pixels without depth (no position: no blur) */
                static float depth[LPH * LPW];
                static sbl_camera cam[2];
                static sbl_frame bf;
                static sbl_history bh;
                static sbl_object_motion obj;
                sbl_reproject_desc rd;
                sbl_intrinsics kin;
                int e, q;
                for (y = 0; y < LPH; ++y)
                    for (x = 0; x < LPW; ++x)
                        depth[y * LPW + x] = (x + 3 * y + it) % 11 == 0 ? 0.0f : (float)(3.0 + 1.5 * sin(0.7 * x + 0.4 * y + it));
                kin.fx = kin.fy = 39.0f;
                kin.cx = 0.5f * LPW;
                kin.cy = 0.5f * LPH;
                for (e = 0; e < 2; ++e) {
                    float pose[16];
                    for (q = 0; q < 16; ++q) pose[q] = q % 5 == 0 ? 1.0f : 0.0f;
                    if (e && !rest) {
                        pose[3] = 0.011f * (float)(1 + it % 7);
                        pose[7] = 0.004f * (float)(it % 3);
                        pose[11] = 0.03f;
                    }
                    CHECK_EQ(sbl_camera_from_pinhole(&cam[e], &kin, pose, SBL_AXES_OPENCV, 0, LPW, LPH), SBL_OK);
                }
                memset(&bf, 0, sizeof bf);
                memset(&bh, 0, sizeof bh);
                memset(&rd, 0, sizeof rd);
                bf.color = im;
                bf.gbuffer.depth = sbl_image_make(depth, LPW, LPH, 1);
                bf.camera = &cam[1];
                bh.color = im;
                bh.gbuffer.depth = bf.gbuffer.depth;
                bh.camera = &cam[0];
                if (rest) {
                    /* id 2 moved sideways and up since the history's frame; id 1 still */
                    memset(&obj, 0, sizeof obj);
                    obj.id = 2.0f;
                    for (q = 0; q < 16; ++q)
                        obj.object_to_world[q] = obj.prev_object_to_world[q] = q % 5 == 0 ? 1.0f : 0.0f;
                    obj.object_to_world[3] = 0.013f * (float)(1 + it % 6);
                    obj.object_to_world[7] = -0.005f;
                    bf.gbuffer.ids = bh.gbuffer.ids = sbl_image_make(ids, LPW, LPH, 1);
                    bf.objects = &obj;
                    bf.object_count = 1;
                }
                CHECK_EQ(sbl__temporal_rp_init(&brp, &rd, SBL_TEMPORAL_CAMERA, &bf, &bh), SBL_OK);
                CHECK(brp.at_rest == rest);
                if (rest) {
                    /* the still pixels' fetch is exactly at the pixel (no rounding of the
                       camera map), so their fraction is 0, not merely small */
                    long still_frac = 0;
                    for (y = 0; y < LPH; ++y)
                        for (x = 0; x < LPW; ++x) {
                            float fvx, fvy;
                            if (ids[y * LPW + x] == 2.0f) continue;
                            sbl__blur_fraction(&brp, x, y, &fvx, &fvy);
                            still_frac += fvx != 0.0f || fvy != 0.0f;
                        }
                    CHECK_EQ(still_frac, 0);
                }
            }
            k.blur_rp = &brp;
            k.wp.blur = 1;
            k.wp.shared_bias = (it >> 2) & 1 ? 1.0f : 0.35f; /* (not tied to ch = 1 + it % 4) */
            if ((it >> 3) % 3 != 0) { /* a history with the evidence plane: the mix (cfg 9, 10) */
                k.evid_use = 1;
                k.evid_in = evid_in;
                k.evid_out = evid_out;
                k.wp.evid_mix = 1;
                k.wp.evid_share = (it >> 5) & 1 ? 0.0f : 0.2f;
                /* the region's M (3.10) in some, through the function sbl__evidence_share
                   calls per row; M = 1 (the defaults) in the rest */
                sbl__evidence_region(&k, (it >> 6) & 1 ? (float)(0.5 + 1.7 * (it % 7)) : 1.0f);
            } /* else none (cfg 7, 8): evid_use, evid_out and the mix 0, as sbl_temporal_filter */
        }
        scratch = malloc(sbl__kernel_scratch_size(LPW, ch));
        sbl__kernel_bind(&k, scratch);
        for (y = 0; y < LPH; ++y) {
            float lc[LPW][4], ln[LPW], la[LPW], l0c[LPW][4], l0n[LPW], l0a[LPW];
            float rc[LPW][4], rn[LPW], ra[LPW], r0c[LPW][4], r0n[LPW], r0a[LPW];
            int full = 0;
            lean_row(&k, y, 1, 1, lc, ln, la, &full);
            full_rows += full;
            /* "lanes, lean off" only where it is off: the blur's instances (behind a
               stereo blend) do not read lean_restart */
            if (!behind) lean_row(&k, y, 0, 1, l0c, l0n, l0a, NULL);
            lean_row(&k, y, 1, 0, rc, rn, ra, NULL);
            lean_row(&k, y, 0, 0, r0c, r0n, r0a, NULL);
            if (behind) {
                /* the reference without the blur's term: does it act? (blur off with the
                   lean on at c > 0, like the reference's "lean off" behind the blend, is a state
                   sbl_temporal_filter never makes: these runs feed the counts, never a
                   comparison) */
                float bc[LPW][4], bn[LPW], ba[LPW];
                k.wp.blur = 0;
                lean_row(&k, y, 1, 0, bc, bn, ba, NULL);
                k.wp.blur = 1;
                for (x = 0; x < LPW; ++x) {
                    const int moved = ba[x] != ra[x], on_obj = ids[y * LPW + x] == 2.0f;
                    blurred += moved;
                    blurred_cam += camera && moved;
                    /* at rest only the moving object's pixels are fetched at a fraction:
                       the term must move them and no other (its S is the pixel's own) */
                    blurred_obj += rest && on_obj && moved;
                    blurred_still += rest && !on_obj && moved;
                    obj_compared += rest && on_obj;
                }
                behind_compared += LPW;
                cam_compared += camera ? LPW : 0;
            }
            for (x = 0; x < LPW; ++x) {
                double e = fabs(la[x] - ra[x]), en = fabs(ln[x] - rn[x]) / (fabs(rn[x]) + 1.0);
                if (en > e) e = en;
                for (c = 0; c < ch; ++c) {
                    const double ec = fabs(lc[x][c] - rc[x][c]) / scale;
                    if (!(ec <= e)) e = ec;
                    CHECK(sbl__finite(lc[x][c]) && sbl__finite(rc[x][c]));
                }
                /* (behind a stereo blend the lanes' lean is the blur's instances' own: it
                   does not read lean_restart, so "lanes, lean off" is not off there) */
                leaned_ref += !behind && ra[x] != r0a[x];
                leaned_lanes += !behind && la[x] != l0a[x];
                behind_leaned += behind && ra[x] != r0a[x];
                ++compared;
                if (!(e <= 1e-4))
                    printf("  restart lean case %d ch %d y %d x %d: lanes a %.6f n %g, reference a %.6f n %g\n",
                           it, ch, y, x, la[x], ln[x], ra[x], rn[x]);
                CHECK(e <= 1e-4);
                if (e > worst) worst = e;
            }
        }
        free(scratch);
    }
    printf("  %s restart lean, lanes vs reference: %ld pixels, the lean moved %ld (reference) / %ld "
           "(lanes), %ld full rows, worst difference %.3g; behind a stereo blend %ld pixels, the "
           "lean moved %ld, the blur's term %ld (camera source: %ld of %ld; at rest: %ld of %ld "
           "on the moving object, %ld elsewhere)\n",
           SBL_SIMD_NAME, compared, leaned_ref, leaned_lanes, full_rows, worst, behind_compared,
           behind_leaned, blurred, blurred_cam, cam_compared, blurred_obj, obj_compared, blurred_still);
    /* the lean acts in both paths (the test compares something), and the full chunks
       were taken */
    CHECK(leaned_ref > compared / 20);
    CHECK(leaned_lanes > compared / 20);
    CHECK(full_rows > 0);
    CHECK(behind_leaned > behind_compared / 20);
    CHECK(blurred > behind_compared / 20);
    CHECK(blurred_cam > cam_compared / 20);
    CHECK(blurred_obj > obj_compared / 20);
    CHECK_EQ(blurred_still, 0);
}
#undef LPW
#undef LPH

/* sbl__evidence_region against what the region's prior M means (docs/ESTIMATORS.md 3.10),
   not against its own expressions: the blocks' ratio moves by ln M; the carried R,
   Gaussian about 1 with variance kappa under no change, gets the threshold at which its
   density is 1 / M of the density at the default threshold (where that lies above R's
   null mean 1; else 1), and the garrote of that threshold; M = 1 the defaults. The
   restart-lean test above compares lanes with the reference, which read the same terms,
   so it cannot see a wrong formula here. */
static void test_evidence_region(void)
{
    const double kap = SBL_EVIDENCE_LAMBDA / (2.0 - SBL_EVIDENCE_LAMBDA);
    const double d0 = exp(-(SBL__EVIDENCE_THR - 1.0) * (SBL__EVIDENCE_THR - 1.0) / (2.0 * kap));
    static const float ms[] = {1.0f, 1.1f, 2.2f, 8.5f, 40.0f, 300.0f, 0.9f, 0.5f, 0.3f, 0.05f, 1e-3f};
    int i, below = 0;
    for (i = 0; i < (int)(sizeof ms / sizeof ms[0]); ++i) {
        sbl__kernel k;
        const double m = (double)ms[i];
        memset(&k, 0, sizeof k);
        k.wp.region_m = -7.0f; /* (overwritten in every case) */
        k.evid_lnm = k.evid_thr = k.evid_garrote = -7.0;
        sbl__evidence_region(&k, ms[i]);
        if (ms[i] == 1.0f) {
            CHECK(k.wp.region_m == 1.0f && k.evid_lnm == 0.0);
            CHECK(k.evid_thr == SBL__EVIDENCE_THR && k.evid_garrote == SBL__EVIDENCE_GARROTE);
            continue;
        }
        CHECK(k.wp.region_m == ((SBL_EVIDENCE_REGION & 1) ? ms[i] : 1.0f));
        CHECK(fabs(k.evid_lnm - ((SBL_EVIDENCE_REGION & 2) ? log(m) : 0.0)) <= 1e-12);
        if (!(SBL_EVIDENCE_REGION & 4)) {
            CHECK(k.evid_thr == SBL__EVIDENCE_THR && k.evid_garrote == SBL__EVIDENCE_GARROTE);
            continue;
        }
        CHECK(k.evid_thr >= 1.0);
        CHECK(fabs(k.evid_garrote - (k.evid_thr - 1.0) * (k.evid_thr - 1.0)) <= 1e-12 * (1.0 + k.evid_garrote));
        if (d0 / m < 1.0) { /* the threshold lies above R's null mean */
            const double d = exp(-(k.evid_thr - 1.0) * (k.evid_thr - 1.0) / (2.0 * kap));
            CHECK(fabs(d * m / d0 - 1.0) <= 1e-9);
            CHECK(m > 1.0 ? k.evid_thr > SBL__EVIDENCE_THR : k.evid_thr < SBL__EVIDENCE_THR);
        } else {
            CHECK(k.evid_thr == 1.0);
            ++below;
        }
    }
    CHECK(below > 0); /* both cases met (M = 1e-3 puts the threshold at the null mean) */
    printf("  region prior M: %d values checked, %d with the threshold at R's null mean\n",
           (int)(sizeof ms / sizeof ms[0]), below);
}

/* sbl_temporal_display: its lanes (float, SIMD layer) against the reference per pixel
   (sbl__display_pixel, double), on random windows: 1-4 channels, padded pixels, young
   and old N, N <= 0 or NaN neighbours, non-finite and huge samples and outputs (which the
   lanes hand to the reference), scales from 1e-9 to 3e13 */
#define DPW 37
#define DPH 9
static void test_display_paths(void)
{
    static float smp[DPH * DPW * 5], out[DPH * DPW * 6], len[DPH * DPW], disp[DPH * DPW * 6],
        disp2[DPH * DPW * 6];
    sbt_rng rng = {777};
    long compared = 0, leaned = 0, differ = 0;
    double worst = 0.0;
    int it;
    for (it = 0; it < 600; ++it) {
        /* (the difference is relative to the scale and the values: a huge output
           leaned in float differs from the double one by its rounding) */
        const int ch = 1 + it % 4, step = ch + (it % 5 == 1), dstep = ch + 2 * (it % 7 == 3);
        const int ostep = step + (it % 3 == 2); /* the outputs' pixel step, not the samples' */
        /* runs of young pixels side by side (sbl__display_run_put) in a third of the cases;
           a longer young history (sbl_display_desc.max_length) in a sixth */
        const double pyoung = it % 3 == 0 ? 0.97 : 0.6;
        const float max_n = it % 6 == 5 ? 6.0f : 0.0f, lean_n = max_n > 0.0f ? max_n : 3.0f;
        const double scale = it % 10 == 9 ? 3e13 : it % 10 == 8 ? 1e-9 : 1.0;
        const double amp = 0.3 * sbt_uniform(&rng), sigma = 0.01 + 0.2 * sbt_uniform(&rng);
        const int odd = it % 4 == 2; /* a few values that are not, or too large for a lane */
        sbl_frame f;
        sbl_temporal_output o;
        sbl_display_desc dd;
        sbl__display_rows rows;
        int x, y, c, j;
        for (y = 0; y < DPH; ++y)
            for (x = 0; x < DPW; ++x) {
                const double t = 0.5 + amp * sin(0.7 * x + 1.1 * y);
                const double u = sbt_uniform(&rng), u2 = (u - pyoung) / (1.0 - pyoung);
                len[y * DPW + x] = u < pyoung ? (float)(1 + (int)(3 * sbt_uniform(&rng)))
                                   : u2 < 0.75 ? (float)(4 + 30 * sbt_uniform(&rng))
                                   : u2 < 0.875 ? 0.0f : u2 < 0.925 ? 0.5f : -1.0f;
                for (c = 0; c < step; ++c)
                    smp[(y * DPW + x) * step + c] = (float)(scale * (t + 0.05 * c + sigma * sbt_gauss(&rng)));
                for (c = 0; c < ostep; ++c)
                    out[(y * DPW + x) * ostep + c] = (float)(scale * (t + 0.05 * c + 0.3 * sigma * sbt_gauss(&rng)));
                if (odd && sbt_uniform(&rng) < 0.03) {
                    const double v = sbt_uniform(&rng);
                    const int in_out = sbt_uniform(&rng) < 0.5;
                    float *p = in_out ? out : smp;
                    p[(y * DPW + x) * (in_out ? ostep : step) + (int)(sbt_uniform(&rng) * ch)] =
                        v < 0.3 ? NAN : v < 0.5 ? INFINITY : v < 0.8 ? 3e37f : -2e38f;
                    if (sbt_uniform(&rng) < 0.3) len[y * DPW + x] = v < 0.5 ? NAN : INFINITY;
                }
            }
        memset(&f, 0, sizeof f);
        memset(&o, 0, sizeof o);
        f.color = sbl_image_make(smp, DPW, DPH, ch);
        f.color.pixel_bytes = step * (int)sizeof(float);
        f.color.stride_bytes = DPW * step * (int)sizeof(float);
        o.color = sbl_image_make(out, DPW, DPH, ch);
        o.color.pixel_bytes = ostep * (int)sizeof(float);
        o.color.stride_bytes = DPW * ostep * (int)sizeof(float);
        o.length = sbl_image_make(len, DPW, DPH, 1);
        memset(&dd, 0, sizeof dd);
        dd.max_length = max_n;
        {
            sbl_image d = sbl_image_make(disp, DPW, DPH, ch);
            d.pixel_bytes = dstep * (int)sizeof(float);
            d.stride_bytes = DPW * dstep * (int)sizeof(float);
            CHECK_EQ(sbl_temporal_display(&dd, &f, &o, d, 0, DPH), SBL_OK);
            if (it % 5 == 4) { /* row bands (one row, then random heights) equal one call */
                int y0 = 0, y1 = 1;
                d.data = disp2;
                while (y0 < DPH) {
                    CHECK_EQ(sbl_temporal_display(&dd, &f, &o, d, y0, y1), SBL_OK);
                    y0 = y1;
                    y1 = y0 + 1 + (int)(7 * sbt_uniform(&rng));
                    if (y1 > DPH) y1 = DPH;
                }
                for (y = 0; y < DPH; ++y)
                    for (x = 0; x < DPW; ++x)
                        CHECK(memcmp(disp + (y * DPW + x) * dstep, disp2 + (y * DPW + x) * dstep,
                                     (size_t)ch * sizeof(float)) == 0);
            }
        }
        rows.sample_step = step;
        rows.out_step = ostep;
        rows.length_step = 1;
        rows.width = DPW;
        rows.channels = ch;
        for (y = 0; y < DPH; ++y) {
            for (j = 0; j < 3; ++j) {
                const int yj = y + j - 1, in = yj >= 0 && yj < DPH;
                rows.sample[j] = in ? smp + yj * DPW * step : NULL;
                rows.out[j] = in ? out + yj * DPW * ostep : NULL;
                rows.length[j] = in ? len + yj * DPW : NULL;
            }
            for (x = 0; x < DPW; ++x) {
                const float *t = out + (y * DPW + x) * ostep, n = len[y * DPW + x];
                const float *dl = disp + (y * DPW + x) * dstep;
                float ref[4];
                double e = 0.0;
                for (c = 0; c < ch; ++c) ref[c] = t[c];
                if (sbl__finite(n) && n > 0.0f && n <= lean_n && !sbl__any_nonfinite(t, ch))
                    sbl__display_pixel(&rows, x, (double)n, t, ref);
                for (c = 0; c < ch; ++c) {
                    const double ec = memcmp(&dl[c], &ref[c], sizeof(float)) == 0
                                          ? 0.0 /* (an inf output copied: inf - inf) */
                                          : fabs((double)dl[c] - (double)ref[c]) /
                                                (scale + fabs((double)t[c]) + fabs((double)ref[c]));
                    if (!(ec <= e)) e = ec;
                    differ += memcmp(&dl[c], &ref[c], sizeof(float)) != 0;
                    leaned += ref[c] != t[c];
                    CHECK(sbl__finite(dl[c]) || !sbl__finite(t[c]));
                }
                if (!(e <= 2e-5))
                    printf("  display case %d ch %d y %d x %d: lanes %.7g, reference %.7g (output %.7g, N %g)\n",
                           it, ch, y, x, dl[0], ref[0], t[0], n);
                CHECK(e <= 2e-5);
                if (e > worst) worst = e;
                ++compared;
            }
        }
    }
    printf("  %s display, lanes vs reference: %ld pixels, %ld channel values leaned, %ld differ in bits, "
           "worst difference %.3g\n", SBL_SIMD_NAME, compared, leaned, differ, worst);
    /* the lean acts, and the lanes (float) computed some of it */
    CHECK(leaned > compared / 4);
    CHECK(differ > 0);
}
#undef DPW
#undef DPH

static void test_blur_noise_fit(void)
{
    static const double pts[][2] = {{1, 0.25}, {1, 0.0625}, {2, 0.25}, {3, 0.1}, {5, 0.2}, {11, 0.001}, {8, 0.25},
                                    {16, 0.05}, {30, 0.16}, {64, 0.25}, {100, 0.02}, {200, 0.01}, {200, 0.25}};
    double worst = 0.0;
    int i, k;
    for (i = 0; i < (int)(sizeof pts / sizeof pts[0]); ++i) {
        const int n = (int)pts[i][0];
        const double v = pts[i][1];
        double sum = 0.0, fit, err;
        for (k = 0; k < n; ++k) sum += blur_g_exact(k * v);
        fit = sbl__blur_noise(1.0f / (float)n, (float)n, (float)v);
        err = fabs(fit / (sum / n) - 1.0);
        if (err > worst) worst = err;
        CHECK(err < 0.0031);
    }
    printf("  the blur's noise factor G(n, v): fit within %.4f %% of the sum at %d points\n", 100.0 * worst,
           (int)(sizeof pts / sizeof pts[0]));
    /* no blur (v = 0): g(0) = 6 at every n */
    CHECK(fabs(sbl__blur_noise(1.0f / 64.0f, 64.0f, 0.0f) / 6.0 - 1.0) < 0.0031);
}

int main(void)
{
    static float own[PH * PW * 4], own_n[PH * PW], outc[PH * PW * 4], outn[PH * PW], outa[PH * PW];
    static paths_gather G;
    static float sev[PW + 16]; /* the stereo change flags of the row (k.sev; VW-readable) */
    sbt_rng rng = {77};
    double worst = 0;
    int it, compared = 0, refused = 0, flag_moved = 0;
    for (it = 0; it < 6000; ++it) { /* 5000 on: temporal cases with stereo_shared_bias */
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
        /* every estimator, rectification and weight mode, temporal and stereo (it % 6
           alone gave the stereo cases only the odd estimators) */
        k.wp.estimator = (sbl_estimator)((it / 2 + it / 12) % SBL_ESTIMATOR_COUNT);
        k.wp.rectify = (sbl_rectify)((it / 4) % SBL_RECTIFY_COUNT);
        k.wp.mode = (sbl_weight_mode)((it / 12) % SBL_WEIGHT_MODE_COUNT);
        k.wp.constant = stereo ? 0.5f : 0.1f;
        k.wp.gamma = 1.25f;
        k.wp.bias_threshold = 3.0f;
        k.wp.shared_bias = it >= 5000 && !stereo ? (it & 2 ? 1.0f : 0.35f) : 0.0f;
        if (it >= 5000) k.wp.temporal = !stereo; /* the field acts on temporal calls only */
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
        if (stereo && !k.fill && k.wp.estimator == SBL_ESTIMATOR_POOLED && it % 3 != 0) {
            /* the eyes' change flags (6.15): both paths read k.sev where wp.stereo_ev */
            for (x = 0; x < PW + 16; ++x) sev[x] = sbt_uniform(&rng) < 0.5 ? 1.0f : 0.0f;
            k.sev = sev;
            k.wp.stereo_ev = 1;
        }
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
        if (k.wp.stereo_ev) { /* the flags move the weight: the reference with and without */
            float ref_a[PW];
            for (x = 1; x < PW - 1; ++x) ref_a[x] = k.stage_a[x];
            k.wp.stereo_ev = 0;
            for (x = 1; x < PW - 1; ++x) {
                sbl__kernel_pixel_ref(&k, R, x);
                if (sev[x] > 0.0f && k.stage_a[x] != ref_a[x]) ++flag_moved;
                if (sev[x] == 0.0f) CHECK(k.stage_a[x] == ref_a[x]); /* unflagged: unchanged */
            }
        }
        free(scratch);
    }
    printf("  %s lane kernel vs double reference: %d pixels, worst difference %.3g; %d cases refused (own N = inf)\n",
           SBL_SIMD_NAME, compared, worst, refused);
    CHECK(refused > 0);
    printf("  stereo change flags: %d flagged pixels' weights moved by them\n", flag_moved);
    CHECK(flag_moved > 1000);
    test_spans();
    test_moments_precision();
    test_pool_dim();
    test_pool_region_threshold();
    test_lanes_dim();
    test_row_gather();
    test_row_gather_uniform();
    test_stereo_row_gather();
    test_stereo_parallel_fused();
    test_row_gather_disocclusion();
    test_all_safe();
    test_evidence_paths();
    test_evidence_row_gather();
    test_row_gather_normals();
    test_bands_every_shape();
    test_camera_plans_normals();
    test_cam_map_fold();
    test_rig_as_parallel();
    test_blur_noise_fit();
    test_restart_lean_paths();
    test_evidence_region();
    test_display_paths();
    return sbt_finish("test_paths");
}
