/* Adaptive computation tests (section 10): the stereo consistency mask against a
   hand-computed case (no correspondence, zero / negative / non-finite values in either
   image), the ratio, row bands equal to a whole call, rejected calls write nothing.
   Scenes: a parallel rig, f b = 12, a far plane at z = 6 (disparity 2, an integer, so
   the right-eye match of left pixel x is exactly right pixel x - 2 and its bilinear
   value is that pixel's value) and, for occlusion, a near box. */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"

static sbl_image view(const sbt_img *im)
{
    sbl_image v;
    memset(&v, 0, sizeof v); /* fields not named here take their defaults */
    v.data = im->mem; v.width = im->w; v.height = im->h; v.channels = im->c; v.stride = im->stride;
    return v;
}

typedef struct rig {
    int w, h;
    sbt_img dep[2], val[2];
    sbl_eye eye[2];
    sbl_stereo_desc d;
} rig;

/* Both eyes see a far plane at z = zfar (disparity 12 / zfar); rows [by0, by1) of the
   left-eye columns [bx0, bx1) see a near box at z = 1 (disparity 12), in the right eye
   at columns [bx0 - 12, bx1 - 12). */
static void rig_init(rig *r, int w, int h, int ch, float zfar, int bx0, int bx1, int by0,
                     int by1)
{
    int e, x, y;
    memset(r, 0, sizeof *r);
    r->w = w; r->h = h;
    for (e = 0; e < 2; ++e) {
        r->dep[e] = sbt_img_new(w, h, 1, 1 + e);
        r->val[e] = sbt_img_new(w, h, ch, 2 - e);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int lx = e ? x + 12 : x; /* left column of the box point seen here */
                int box = y >= by0 && y < by1 && lx >= bx0 && lx < bx1;
                *sbt_at(&r->dep[e], x, y) = box ? 1.0f : zfar;
            }
        r->eye[e].gbuffer.depth = view(&r->dep[e]);
        /* the eyes' colour is not read by the consistency call: leave it unset */
    }
    r->d.rig = SBL_RIG_PARALLEL;
    r->d.focal_px = 24.0f;
    r->d.baseline = 0.5f;
}

static void rig_free(rig *r)
{
    int e;
    for (e = 0; e < 2; ++e) { free(r->dep[e].mem); free(r->val[e].mem); }
}

/* The mask by the pixel path (no scratch); every call also checks that the row path
   (with scratch) writes the same classes and counts, bit for bit. */
static sbl_result rig_mask(rig *r, float threshold, int t, unsigned char *mask, int y0, int y1,
                           sbl_consistency_counts *c)
{
    const int ch = r->val[t].c;
    size_t bytes = sbl_stereo_consistency_scratch_size(r->w, ch);
    void *scratch = malloc(bytes);
    unsigned char *m2 = (unsigned char *)malloc((size_t)r->w * r->h);
    sbl_consistency_counts c1, c2;
    sbl_result res, res2;
    int y;
    memcpy(m2, mask, (size_t)r->w * r->h);
    res = sbl_stereo_consistency(&r->d, threshold, (sbl_eye_index)t, &r->eye[t], &r->eye[!t],
                                 view(&r->val[t]), view(&r->val[!t]), mask, r->w, y0, y1, NULL, 0, &c1);
    res2 = sbl_stereo_consistency(&r->d, threshold, (sbl_eye_index)t, &r->eye[t], &r->eye[!t],
                                  view(&r->val[t]), view(&r->val[!t]), m2, r->w, y0, y1, scratch,
                                  bytes, &c2);
    CHECK_EQ(res2, res);
    CHECK(memcmp(m2, mask, (size_t)r->w * r->h) == 0);
    if (res == SBL_OK)
        CHECK(c1.consistent == c2.consistent && c1.inconsistent == c2.inconsistent &&
              c1.no_correspondence == c2.no_correspondence);
    if (res == SBL_OK && y1 > y0) {
        /* a scratch one byte short is refused, writing nothing */
        for (y = y0; y < y1; ++y) memset(m2 + (size_t)y * r->w, 0x33, (size_t)r->w);
        CHECK_EQ(sbl_stereo_consistency(&r->d, threshold, (sbl_eye_index)t, &r->eye[t], &r->eye[!t],
                                        view(&r->val[t]), view(&r->val[!t]), m2, r->w, y0, y1,
                                        scratch, bytes - 1, NULL),
                 SBL_ERROR_SCRATCH_TOO_SMALL);
        CHECK_EQ(sbl_stereo_consistency(&r->d, threshold, (sbl_eye_index)t, &r->eye[t], &r->eye[!t],
                                        view(&r->val[t]), view(&r->val[!t]), m2, r->w, y0, y1,
                                        NULL, bytes, NULL),
                 SBL_ERROR_NULL_POINTER);
        CHECK(m2[(size_t)y0 * r->w] == 0x33);
    }
    if (c) *c = c1;
    free(scratch);
    free(m2);
    return res;
}

/* ---- 1. the hand-computed case ---------------------------------------------------- */

static void test_hand_case(void)
{
    /* one row of 12 pixels, far plane at z = 6: left x <-> right x - 2 */
    const float inf = (float)HUGE_VAL;
    const float nan = (float)(HUGE_VAL - HUGE_VAL);
    /* left value, right value at x - 2, expected class, hand-computed ratio */
    struct { float a, b; int cls; } c[12];
    rig r;
    unsigned char mask[12];
    sbl_consistency_counts n;
    int x, k;
    rig_init(&r, 12, 1, 1, 6.0f, 0, 0, 0, 0);
    r.d.reproject.no_fallback = 1; /* a dropped tap is then "no correspondence" */
    for (k = 0; k < 12; ++k) { c[k].a = 1.0f; c[k].b = 1.0f; c[k].cls = SBL_CONSISTENT; }
    /* x = 0, 1: the match (x - 2) is outside the right image */
    c[0].cls = SBL_NO_CORRESPONDENCE;
    c[1].cls = SBL_NO_CORRESPONDENCE;
    c[2].a = 1.0f;   c[2].b = 1.01f;  c[2].cls = SBL_CONSISTENT;   /* 0.01 / 1.01 */
    c[3].a = 1.0f;   c[3].b = 1.03f;  c[3].cls = SBL_INCONSISTENT; /* 0.03 / 1.03 = 0.029 */
    c[4].a = 0.0f;   c[4].b = -0.0f;  c[4].cls = SBL_CONSISTENT;   /* both zero: r = 0 */
    c[5].a = 0.0f;   c[5].b = 1e-30f; c[5].cls = SBL_INCONSISTENT; /* one zero: r = 1 */
    c[6].a = -2.0f;  c[6].b = -2.03f; c[6].cls = SBL_CONSISTENT;   /* 0.03 / 2.03 = 0.0148 */
    c[7].a = -1.0f;  c[7].b = 1.0f;   c[7].cls = SBL_INCONSISTENT; /* 2 / 1 = 2 */
    c[8].a = nan;    c[8].b = 1.0f;   c[8].cls = SBL_INCONSISTENT; /* non-finite target */
    c[9].a = 1.0f;   c[9].b = nan;    c[9].cls = SBL_NO_CORRESPONDENCE; /* tap dropped */
    c[10].a = -inf;  c[10].b = 5.0f;  c[10].cls = SBL_INCONSISTENT;
    c[11].a = 3.0f;  c[11].b = inf;   c[11].cls = SBL_NO_CORRESPONDENCE;
    for (x = 0; x < 12; ++x) {
        *sbt_at(&r.val[0], x, 0) = c[x].a;
        if (x >= 2) *sbt_at(&r.val[1], x - 2, 0) = c[x].b;
    }
    memset(mask, 0xab, sizeof mask);
    CHECK_EQ(rig_mask(&r, 0.0f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    for (x = 0; x < 12; ++x) CHECK_EQ(mask[x], c[x].cls);
    /* consistent: 2, 4, 6 -> 3; inconsistent: 3, 5, 7, 8, 10 -> 5; none: 0, 1, 9, 11 */
    CHECK_EQ(n.consistent, 3);
    CHECK_EQ(n.inconsistent, 5);
    CHECK_EQ(n.no_correspondence, 4);
    CHECK_NEAR(n.inconsistent_ratio, 5.0 / 8.0, 1e-12);

    /* the threshold: zero is the default 0.02; 0.0147 catches x = 6 (0.01478) but not
       x = 2 (0.0099); 0.03 releases x = 3 (0.0291) */
    CHECK_EQ(rig_mask(&r, SBL_WEBER_THRESHOLD, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(n.inconsistent, 5);
    CHECK_EQ(rig_mask(&r, 0.0147f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[6], SBL_INCONSISTENT);
    CHECK_EQ(mask[2], SBL_CONSISTENT);
    CHECK_EQ(rig_mask(&r, 0.03f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[3], SBL_CONSISTENT);
    CHECK_EQ(mask[7], SBL_INCONSISTENT);
    /* ratio exactly at the threshold is inconsistent (Wu's Eq. 2 uses >=): 1 vs 2 is 0.5 */
    *sbt_at(&r.val[0], 2, 0) = 1.0f;
    *sbt_at(&r.val[1], 0, 0) = 2.0f;
    CHECK_EQ(rig_mask(&r, 0.5f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[2], SBL_INCONSISTENT);

    /* the right eye: right x <-> left x + 2; the ratio is symmetric, so pairs classify
       alike: right pixel x - 2 of the left hand case */
    for (x = 0; x < 12; ++x) {
        *sbt_at(&r.val[0], x, 0) = c[x].a;
        if (x >= 2) *sbt_at(&r.val[1], x - 2, 0) = c[x].b;
    }
    CHECK_EQ(rig_mask(&r, 0.0f, SBL_EYE_RIGHT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[10], SBL_NO_CORRESPONDENCE); /* match x + 2 = 12: outside */
    CHECK_EQ(mask[11], SBL_NO_CORRESPONDENCE);
    CHECK_EQ(mask[0], SBL_CONSISTENT);    /* left 2  */
    CHECK_EQ(mask[1], SBL_INCONSISTENT);  /* left 3  */
    CHECK_EQ(mask[2], SBL_CONSISTENT);    /* left 4  */
    CHECK_EQ(mask[3], SBL_INCONSISTENT);  /* left 5  */
    CHECK_EQ(mask[4], SBL_CONSISTENT);    /* left 6  */
    CHECK_EQ(mask[5], SBL_INCONSISTENT);  /* left 7  */
    CHECK_EQ(mask[6], SBL_NO_CORRESPONDENCE); /* left 8 is NaN: its tap is dropped */
    CHECK_EQ(mask[7], SBL_INCONSISTENT);  /* own NaN */
    CHECK_EQ(mask[8], SBL_NO_CORRESPONDENCE); /* left 10 is -inf: its tap is dropped */
    CHECK_EQ(mask[9], SBL_INCONSISTENT);  /* own +inf */

    /* with the 3x3 fallback (the default) a dropped tap is replaced by the mean of its
       consistent neighbours: right pixel 7 (left 9's match) is NaN, its neighbours
       right 6 and 8 hold 1.0 and 5.0 -> mean 3.0 against left 9's 1.0: r = 2/3 */
    rig_free(&r);
    rig_init(&r, 12, 1, 1, 6.0f, 0, 0, 0, 0);
    for (x = 0; x < 12; ++x) {
        *sbt_at(&r.val[0], x, 0) = c[x].a;
        if (x >= 2) *sbt_at(&r.val[1], x - 2, 0) = c[x].b;
    }
    CHECK_EQ(rig_mask(&r, 0.66f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[9], SBL_INCONSISTENT);
    CHECK_EQ(rig_mask(&r, 0.67f, SBL_EYE_LEFT, mask, 0, 1, &n), SBL_OK);
    CHECK_EQ(mask[9], SBL_CONSISTENT);
    rig_free(&r);
}

/* ---- 2. occlusion, geometry without depth, several channels ------------------------ */

static void test_occlusion_channels(void)
{
    /* 40 x 6, far plane at z = 6 (disparity 2), box at z = 1 over left columns [20, 28):
       the far plane in left columns [10, 18) lies behind the box in the right eye
       (right columns [8, 16)): no correspondence (depth test / back-check) */
    rig r;
    unsigned char mask[40 * 6];
    sbl_consistency_counts n;
    int x, y, k, expect_none;
    rig_init(&r, 40, 6, 3, 6.0f, 20, 28, 0, 6);
    for (y = 0; y < 6; ++y)
        for (x = 0; x < 40; ++x)
            for (k = 0; k < 3; ++k) {
                sbt_at(&r.val[0], x, y)[k] = 0.5f;
                sbt_at(&r.val[1], x, y)[k] = 0.5f;
            }
    /* right pixel 30 (left 32 on the plane) differs by 4 % in the blue channel only */
    sbt_at(&r.val[1], 30, 2)[2] = 0.52f;
    /* a target pixel without valid depth has no correspondence */
    *sbt_at(&r.dep[0], 35, 3) = 0.0f;
    *sbt_at(&r.dep[0], 36, 3) = (float)(HUGE_VAL - HUGE_VAL);
    CHECK_EQ(rig_mask(&r, 0.0f, SBL_EYE_LEFT, mask, 0, 6, &n), SBL_OK);
    for (y = 0; y < 6; ++y)
        for (x = 0; x < 40; ++x) {
            int m = mask[y * 40 + x];
            expect_none = x < 2 || (x >= 10 && x < 18) || (y == 3 && (x == 35 || x == 36));
            if (expect_none) {
                CHECK_EQ(m, SBL_NO_CORRESPONDENCE);
            } else if (x == 32 && y == 2) {
                CHECK_EQ(m, SBL_INCONSISTENT); /* the largest channel ratio counts */
            } else {
                CHECK_EQ(m, SBL_CONSISTENT);
            }
        }
    CHECK_EQ(n.inconsistent, 1);
    CHECK_EQ(n.no_correspondence, 6 * 10 + 2);
    CHECK_EQ(n.consistent, 40 * 6 - 1 - 6 * 10 - 2);
    rig_free(&r);
}

/* ---- 3. row bands equal a whole call ----------------------------------------------- */

static void test_bands(void)
{
    const int w = 37, h = 23;
    rig r;
    unsigned char whole[37 * 23], band[37 * 23];
    sbl_consistency_counts nw, nb, sum;
    sbt_rng rng = {7};
    int t, x, y, e, y0;
    rig_init(&r, w, h, 2, 6.0f, 14, 25, 5, 17);
    for (e = 0; e < 2; ++e)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                sbt_at(&r.val[e], x, y)[0] = (float)(0.5 + 0.02 * sbt_gauss(&rng));
                sbt_at(&r.val[e], x, y)[1] = (float)(0.2 + 0.01 * sbt_gauss(&rng));
            }
    for (t = 0; t < 2; ++t) {
        memset(whole, 0xcd, sizeof whole);
        memset(band, 0xef, sizeof band);
        CHECK_EQ(rig_mask(&r, 0.0f, t, whole, 0, h, &nw), SBL_OK);
        memset(&sum, 0, sizeof sum);
        for (y0 = 0; y0 < h;) {
            int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 5.0);
            if (y1 > h) y1 = h;
            CHECK_EQ(rig_mask(&r, 0.0f, t, band, y0, y1, &nb), SBL_OK);
            sum.consistent += nb.consistent;
            sum.inconsistent += nb.inconsistent;
            sum.no_correspondence += nb.no_correspondence;
            y0 = y1;
        }
        CHECK(memcmp(whole, band, sizeof whole) == 0);
        CHECK_EQ(sum.consistent, nw.consistent);
        CHECK_EQ(sum.inconsistent, nw.inconsistent);
        CHECK_EQ(sum.no_correspondence, nw.no_correspondence);
        CHECK_EQ(nw.consistent + nw.inconsistent + nw.no_correspondence, (long)w * h);
        /* a noisy pair: both classes occur, and occlusion leaves pixels unmatched */
        CHECK(nw.consistent > 0 && nw.inconsistent > 0 && nw.no_correspondence > 0);
        CHECK_NEAR(nw.inconsistent_ratio,
                   (double)nw.inconsistent / (double)(nw.consistent + nw.inconsistent), 1e-15);
        /* an empty range writes nothing and counts nothing */
        memset(band, 0x11, sizeof band);
        CHECK_EQ(rig_mask(&r, 0.0f, t, band, 5, 5, &nb), SBL_OK);
        CHECK_EQ(nb.consistent + nb.inconsistent + nb.no_correspondence, 0);
        CHECK_NEAR(nb.inconsistent_ratio, 0.0, 0.0);
        for (x = 0; x < w * h; ++x) if (band[x] != 0x11) break;
        CHECK_EQ(x, w * h);
    }
    rig_free(&r);
}

/* ---- 4. rejected calls write nothing ----------------------------------------------- */

static int mask_untouched(const unsigned char *m, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) if (m[i] != 0x5a) return 0;
    return 1;
}

static void test_errors(void)
{
    const int w = 16, h = 4;
    const float nan = (float)(HUGE_VAL - HUGE_VAL);
    rig r;
    unsigned char mask[16 * 4 + 8];
    sbl_consistency_counts n, n0;
    sbl_stereo_desc d;
    sbl_eye e0;
    sbl_image a, b;
    sbt_img other = sbt_img_new(w, h, 2, 0), small = sbt_img_new(w - 1, h, 1, 0);
    sbl_result got;
    rig_init(&r, w, h, 1, 6.0f, 0, 0, 0, 0);
    a = view(&r.val[0]);
    b = view(&r.val[1]);
    memset(&n0, 0x3c, sizeof n0);
#define REJECT(call, code)                                                               \
    do {                                                                                 \
        memset(mask, 0x5a, sizeof mask);                                                 \
        n = n0;                                                                          \
        got = (call);                                                                    \
        CHECK_EQ(got, code);                                                               \
        CHECK(mask_untouched(mask, sizeof mask));                                        \
        CHECK(memcmp(&n, &n0, sizeof n) == 0);                                           \
    } while (0)
    REJECT(sbl_stereo_consistency(NULL, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_NULL_POINTER);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, NULL, &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_NULL_POINTER);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, NULL, w, 0, h, NULL, 0, &n),
           SBL_ERROR_NULL_POINTER);
    REJECT(sbl_stereo_consistency(&r.d, -0.02f, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_PARAM);
    REJECT(sbl_stereo_consistency(&r.d, nan, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_PARAM);
    REJECT(sbl_stereo_consistency(&r.d, (float)HUGE_VAL, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_PARAM);
    REJECT(sbl_stereo_consistency(&r.d, 0, (sbl_eye_index)2, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_PARAM);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w - 1, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_STRIDE);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h + 1, NULL, 0, &n),
           SBL_ERROR_INVALID_ROWS);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 3, 2, NULL, 0, &n),
           SBL_ERROR_INVALID_ROWS);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, view(&other), mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_CHANNEL_MISMATCH);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, view(&small), mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_SIZE_MISMATCH);
    {   /* a value image without data */
        sbl_image none = a;
        none.data = NULL;
        REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], none, b, mask, w, 0, h, NULL, 0, &n),
               SBL_ERROR_NULL_POINTER);
    }
    /* parallel rig without depth in the source eye */
    e0 = r.eye[1];
    memset(&e0.gbuffer.depth, 0, sizeof e0.gbuffer.depth);
    REJECT(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &e0, a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_MISSING_INPUT);
    d = r.d;
    d.focal_px = -1.0f;
    REJECT(sbl_stereo_consistency(&d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, &n),
           SBL_ERROR_INVALID_PARAM);
    {   /* the mask over an input: a value image or the depth */
        unsigned char *over = (unsigned char *)r.val[1].mem;
        unsigned char keep[sizeof(float) * 16];
        memcpy(keep, over, sizeof keep);
        CHECK_EQ(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, over, w, 0, h, NULL, 0, &n),
                 SBL_ERROR_OVERLAP);
        CHECK(memcmp(keep, over, sizeof keep) == 0);
        over = (unsigned char *)r.dep[0].mem;
        memcpy(keep, over, sizeof keep);
        CHECK_EQ(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, over, w, 0, h, NULL, 0, &n),
                 SBL_ERROR_OVERLAP);
        CHECK(memcmp(keep, over, sizeof keep) == 0);
    }
    /* accepted with counts NULL; an over-wide stride is fine */
    memset(mask, 0x5a, sizeof mask);
    CHECK_EQ(sbl_stereo_consistency(&r.d, 0, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], a, b, mask, w, 0, h, NULL, 0, NULL),
             SBL_OK);
    CHECK(mask[0] == SBL_NO_CORRESPONDENCE && mask[2] == SBL_CONSISTENT);
    CHECK(mask[w * h] == 0x5a);
#undef REJECT
    free(other.mem); free(small.mem);
    rig_free(&r);
}

/* ---- 5. the adaptive blend: the full blend on marked pixels, the own result elsewhere */

static void test_blend_masked(void)
{
    const int w = 61, h = 37, ch = 3;
    rig r;
    sbt_img col[2], len[2], full = sbt_img_new(w, h, ch, 1), fulln = sbt_img_new(w, h, 1, 2);
    sbt_img out = sbt_img_new(w, h, ch, 3), outn = sbt_img_new(w, h, 1, 1);
    sbt_img band = sbt_img_new(w, h, ch, 0), bandn = sbt_img_new(w, h, 1, 0);
    unsigned char *mask = (unsigned char *)malloc((size_t)(w + 3) * h);
    size_t bytes = sbl_stereo_scratch_size(w, ch);
    void *scratch = malloc(bytes);
    sbt_rng rng = {99};
    long cnt, expect_cnt, cnt_sum;
    int t, x, y, k, e, pass, bad_col, bad_n, y0, ok;
    const int ms = w + 3;
    rig_init(&r, w, h, ch, 6.0f, 20, 34, 8, 25);
    for (e = 0; e < 2; ++e) {
        col[e] = sbt_img_new(w, h, ch, e);
        len[e] = sbt_img_new(w, h, 1, 1);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                for (k = 0; k < ch; ++k)
                    sbt_at(&col[e], x, y)[k] = (float)(0.4 + 0.1 * k + 0.05 * sbt_gauss(&rng));
                *sbt_at(&len[e], x, y) = (float)(1 + (int)(sbt_uniform(&rng) * 8));
            }
        r.eye[e].color = view(&col[e]);
        r.eye[e].length = view(&len[e]);
    }
    /* one own value is NaN and one N is 0: the own result keeps the colour, N -> 1 */
    sbt_at(&col[0], 3, 3)[1] = (float)(HUGE_VAL - HUGE_VAL);
    *sbt_at(&len[0], 4, 3) = 0.0f;
    *sbt_at(&len[1], 4, 3) = 0.0f;
    for (pass = 0; pass < 5; ++pass)
        for (t = 0; t < 2; ++t) {
            /* masks: sparse random (with other byte values, which are not "marked"), one
               marked block, everything marked */
            expect_cnt = 0;
            for (y = 0; y < h; ++y)
                for (x = 0; x < ms; ++x) {
                    unsigned char m;
                    double u = sbt_uniform(&rng);
                    if (pass == 0) m = u < 0.05 ? SBL_INCONSISTENT : (u < 0.5 ? SBL_CONSISTENT : (u < 0.9 ? SBL_NO_CORRESPONDENCE : 7));
                    else if (pass == 1) m = (x >= 17 && x < 23 && y >= 30) ? SBL_INCONSISTENT : SBL_CONSISTENT;
                    else if (pass == 2) m = SBL_INCONSISTENT;
                    else if (pass == 3) /* bands: full, partial, full */
                        m = ((y < 16 && x % 16 == 5) || (y == 20 && x < 10) || (y >= 32 && x % 8 == 0))
                                ? SBL_INCONSISTENT : SBL_CONSISTENT;
                    else /* sparse: partial spans everywhere */
                        m = u < 0.003 ? SBL_INCONSISTENT : SBL_CONSISTENT;
                    mask[(size_t)y * ms + x] = m;
                }
            mask[(size_t)3 * ms + 3] = SBL_CONSISTENT;
            mask[(size_t)3 * ms + 4] = SBL_CONSISTENT;
            expect_cnt = 0;
            for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) expect_cnt += mask[(size_t)y * ms + x] == SBL_INCONSISTENT;
            CHECK_EQ(sbl_stereo_blend(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], view(&full),
                                      view(&fulln), 0, h, scratch, bytes), SBL_OK);
            CHECK_EQ(sbl_stereo_blend_masked(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], mask, ms,
                                             view(&out), view(&outn), 0, h, scratch, bytes, &cnt),
                     SBL_OK);
            CHECK_EQ(cnt, expect_cnt);
            bad_col = bad_n = 0;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    int marked = mask[(size_t)y * ms + x] == SBL_INCONSISTENT;
                    const float *want = marked ? sbt_at(&full, x, y) : sbt_at(&col[t], x, y);
                    float want_n = marked ? *sbt_at(&fulln, x, y)
                                          : (*sbt_at(&len[t], x, y) > 0.0f ? *sbt_at(&len[t], x, y) : 1.0f);
                    bad_col += memcmp(want, sbt_at(&out, x, y), sizeof(float) * ch) != 0;
                    bad_n += memcmp(&want_n, sbt_at(&outn, x, y), sizeof(float)) != 0;
                }
            CHECK_EQ(bad_col, 0);
            CHECK_EQ(bad_n, 0);
            CHECK(sbt_canaries_ok(&out) && sbt_canaries_ok(&outn));
            /* the blend changed the marked pixels (not a copy of the own result) */
            if (pass == 2) {
                int changed = 0;
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x)
                        changed += sbt_at(&out, x, y)[0] != sbt_at(&col[t], x, y)[0];
                CHECK(changed > w * h / 2);
            }
            /* row bands of random heights equal the whole call */
            memset(band.mem, 0, sizeof(float) * (size_t)band.stride * h);
            cnt_sum = 0;
            for (y0 = 0; y0 < h;) {
                int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 20.0);
                if (y1 > h) y1 = h;
                CHECK_EQ(sbl_stereo_blend_masked(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], mask,
                                                 ms, view(&band), view(&bandn), y0, y1, scratch,
                                                 bytes, &cnt), SBL_OK);
                cnt_sum += cnt;
                y0 = y1;
            }
            CHECK_EQ(cnt_sum, expect_cnt);
            ok = 1;
            for (y = 0; y < h; ++y)
                ok &= memcmp(sbt_at(&band, 0, y), sbt_at(&out, 0, y), sizeof(float) * w * ch) == 0 &&
                      memcmp(sbt_at(&bandn, 0, y), sbt_at(&outn, 0, y), sizeof(float) * w) == 0;
            CHECK(ok);
        }

    {   /* rejected calls write nothing */
        sbl_result got;
        size_t nf = (size_t)out.stride * h;
        float *keep = (float *)malloc(nf * sizeof(float));
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) for (k = 0; k < ch; ++k) sbt_at(&out, x, y)[k] = -7.0f;
        memcpy(keep, out.mem, nf * sizeof(float));
#define REJECT_B(call, code)                                                  \
        do {                                                                  \
            got = (call);                                                     \
            CHECK_EQ(got, code);                                              \
            CHECK(memcmp(keep, out.mem, nf * sizeof(float)) == 0);            \
        } while (0)
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], NULL, ms,
                                         view(&out), view(&outn), 0, h, scratch, bytes, NULL),
                 SBL_ERROR_NULL_POINTER);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, w - 1,
                                         view(&out), view(&outn), 0, h, scratch, bytes, NULL),
                 SBL_ERROR_INVALID_STRIDE);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, ms,
                                         view(&out), view(&outn), 0, h + 1, scratch, bytes, NULL),
                 SBL_ERROR_INVALID_ROWS);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, ms,
                                         view(&out), view(&outn), 0, h, scratch, bytes - 1, NULL),
                 SBL_ERROR_SCRATCH_TOO_SMALL);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, ms,
                                         view(&out), view(&outn), 0, h, NULL, bytes, NULL),
                 SBL_ERROR_NULL_POINTER);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, ms,
                                         view(&out), view(&col[0]), 0, h, scratch, bytes, NULL),
                 SBL_ERROR_INVALID_CHANNELS);
        /* the mask inside an output */
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1],
                                         (const unsigned char *)outn.mem, w, view(&out), view(&outn),
                                         0, h, scratch, bytes, NULL),
                 SBL_ERROR_OVERLAP);
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1],
                                         (const unsigned char *)out.mem, w, view(&out), view(&outn),
                                         0, h, scratch, bytes, NULL),
                 SBL_ERROR_OVERLAP);
        /* an output over an input */
        REJECT_B(sbl_stereo_blend_masked(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], mask, ms,
                                         view(&out), view(&r.dep[0]), 0, h, scratch, bytes, NULL),
                 SBL_ERROR_OVERLAP);
#undef REJECT_B
        free(keep);
    }
    for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); }
    free(full.mem); free(fulln.mem); free(out.mem); free(outn.mem); free(band.mem); free(bandn.mem);
    free(mask); free(scratch);
    rig_free(&r);
}


/* ---- 6. the one-pass adaptive blend ------------------------------------------------- */

/* A colour that depends on the scene point only (left column lx, row y): the two eyes
   agree exactly wherever the match is a whole pixel. */
static float scene_value(int lx, int y, int k)
{
    unsigned u = (unsigned)lx * 73856093u ^ (unsigned)y * 19349663u ^ (unsigned)k * 83492791u;
    u ^= u >> 13; u *= 0x5bd1e995u; u ^= u >> 15;
    return 0.2f + 0.6f * (float)(u & 0xffffu) / 65535.0f;
}

static void test_blend_adaptive(void)
{
    const int w = 61, h = 37, ms = w + 5;
    int ch, pass, t, x, y, k, e, y0, ok;
    for (ch = 1; ch <= 4; ++ch)
        for (pass = 0; pass < 5; ++pass) {
            rig r;
            sbt_img col[2], len[2], full = sbt_img_new(w, h, ch, 1), fulln = sbt_img_new(w, h, 1, 2);
            sbt_img out = sbt_img_new(w, h, ch, 3), outn = sbt_img_new(w, h, 1, 1);
            sbt_img ref = sbt_img_new(w, h, ch, 0), refn = sbt_img_new(w, h, 1, 0);
            sbt_img rp = sbt_img_new(w, h, ch, 0), rpv = sbt_img_new(w, h, 1, 0);
            unsigned char *mask = (unsigned char *)malloc((size_t)ms * h);
            unsigned char *mask2 = (unsigned char *)malloc((size_t)ms * h);
            size_t bytes = sbl_stereo_adaptive_scratch_size(w, ch);
            void *scratch = malloc(bytes);
            sbt_rng rng = {(unsigned)(7 + ch * 3 + pass)};
            sbl_adaptive_desc ad;
            sbl_consistency_counts c, cb;
            long tiles, tiles_all, tb, tab, want_tiles;
            memset(&ad, 0, sizeof ad);
            /* pass 0: default comparison, whole tiles; 1: each channel, marked pixels
               only; 2: every pixel noisy (all marked), whole tiles; 3 and 4: as 0 and 2,
               the test on the nearest pixel of the match */
            ad.per_channel = pass == 1;
            ad.per_pixel = pass == 1;
            ad.nearest = pass >= 3;
            rig_init(&r, w, h, ch, 6.0f, 20, 34, 8, 25);
            for (e = 0; e < 2; ++e) {
                col[e] = sbt_img_new(w, h, ch, e);
                len[e] = sbt_img_new(w, h, 1, 1);
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) {
                        int box = *sbt_at(&r.dep[e], x, y) == 1.0f;
                        int lx = e ? x + (box ? 12 : 2) : x;
                        for (k = 0; k < ch; ++k) {
                            float v = scene_value(lx, y, k);
                            if (pass == 2 || pass == 4) v *= (float)(1.0 + 0.1 * sbt_gauss(&rng));
                            /* every match here is a whole pixel: the nearest pixel is the
                               bilinear value wherever its tap passes */
                            sbt_at(&col[e], x, y)[k] = v;
                        }
                        *sbt_at(&len[e], x, y) = (float)(1 + (int)(sbt_uniform(&rng) * 8));
                    }
                r.eye[e].color = view(&col[e]);
                r.eye[e].length = view(&len[e]);
            }
            /* a few visibly different pixels in the left eye (tiles (0,0) and (2,1)), a
               NaN in the right eye (tile (3,2)), a 1 % difference (consistent) */
            for (k = 0; k < ch; ++k) {
                sbt_at(&col[0], 5, 5)[k] *= 1.1f;
                sbt_at(&col[0], 40, 20)[k] *= 0.85f;
                sbt_at(&col[0], 50, 10)[k] *= 1.01f;
            }
            sbt_at(&col[1], 52, 34)[0] = (float)(HUGE_VAL - HUGE_VAL);
            *sbt_at(&len[0], 4, 3) = 0.0f; /* the own N of an unmarked pixel: 1 */
            for (t = 0; t < 2; ++t) {
                long bad_cls = 0, marked = 0;
                /* the classes from their definition: the reprojection of the other eye's
                   colour and the documented Weber test */
                CHECK_EQ(sbl_reproject_stereo(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], view(&rp),
                                              view(&rpv), 0, h), SBL_OK);
                memset(mask, 0x77, (size_t)ms * h);
                CHECK_EQ(sbl_stereo_blend_adaptive(&r.d, &ad, (sbl_eye_index)t, &r.eye[t], &r.eye[!t],
                                                   view(&out), view(&outn), mask, ms, 0, h, scratch,
                                                   bytes, &c, &tiles, &tiles_all), SBL_OK);
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) {
                        const float *a = sbt_at(&col[t], x, y), *b = sbt_at(&rp, x, y);
                        double q = 0.0;
                        int want, nonfinite = 0;
                        for (k = 0; k < ch; ++k) nonfinite |= !isfinite(a[k]);
                        if (!(*sbt_at(&rpv, x, y) > 0.0f)) want = SBL_NO_CORRESPONDENCE;
                        else if (nonfinite) want = SBL_INCONSISTENT;
                        else {
                            if (ch >= 3 && pass != 1) {
                                double la = 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
                                double lb = 0.2126 * b[0] + 0.7152 * b[1] + 0.0722 * b[2];
                                double m = fabs(la) > fabs(lb) ? fabs(la) : fabs(lb);
                                q = m > 0 ? fabs(la - lb) / m : 0.0;
                            } else {
                                for (k = 0; k < ch; ++k) {
                                    double m = fabs((double)a[k]) > fabs((double)b[k]) ? fabs((double)a[k]) : fabs((double)b[k]);
                                    double qk = m > 0 ? fabs((double)a[k] - (double)b[k]) / m : 0.0;
                                    if (qk > q) q = qk;
                                }
                            }
                            want = q >= 0.02 ? SBL_INCONSISTENT : SBL_CONSISTENT;
                        }
                        bad_cls += mask[(size_t)y * ms + x] != want;
                        marked += want == SBL_INCONSISTENT;
                    }
                if (ad.nearest) {
                    /* the pixel whose tap has N = 0 (the reprojection's 3x3 fallback) and
                       the NaN's match (dropped tap) may differ; nothing else */
                    CHECK(bad_cls <= 2);
                    CHECK(c.inconsistent >= marked - 2 && c.inconsistent <= marked);
                } else {
                    CHECK_EQ(bad_cls, 0);
                    CHECK_EQ(c.inconsistent, marked);
                }
                CHECK_EQ(c.consistent + c.inconsistent + c.no_correspondence, (long)w * h);
                CHECK(c.no_correspondence > 0);
                CHECK(mask[w] == 0x77); /* nothing past the width */
                if (pass != 2 && pass != 4) CHECK(marked >= 2 && marked <= 4); /* right eye: + its NaN, + (2, 3), whose match lost
                                                               its N = 0 tap to the 3x3 fallback */
                else CHECK(marked > w * h / 2);
                /* the output: sbl_stereo_blend's on the marked tiles (per_pixel: pixels),
                   the own colour and N (1 where 0) elsewhere */
                CHECK_EQ(sbl_stereo_blend(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], view(&full),
                                          view(&fulln), 0, h, scratch, bytes), SBL_OK);
                {
                    long bad = 0, blended = 0;
                    for (y = 0; y < h; ++y)
                        for (x = 0; x < w; ++x) {
                            int yy, xx, take = 0;
                            float own_n = *sbt_at(&len[t], x, y) > 0.0f ? *sbt_at(&len[t], x, y) : 1.0f;
                            if (ad.per_pixel) take = mask[(size_t)y * ms + x] == SBL_INCONSISTENT;
                            else
                                for (yy = y / 16 * 16; yy < y / 16 * 16 + 16 && yy < h; ++yy)
                                    for (xx = x / 16 * 16; xx < x / 16 * 16 + 16 && xx < w; ++xx)
                                        take |= mask[(size_t)yy * ms + xx] == SBL_INCONSISTENT;
                            blended += take;
                            bad += memcmp(take ? sbt_at(&full, x, y) : sbt_at(&col[t], x, y),
                                          sbt_at(&out, x, y), sizeof(float) * ch) != 0;
                            bad += memcmp(take ? sbt_at(&fulln, x, y) : &own_n, sbt_at(&outn, x, y),
                                          sizeof(float)) != 0;
                        }
                    CHECK_EQ(bad, 0);
                    CHECK(blended > 0);
                }
                CHECK(sbt_canaries_ok(&out) && sbt_canaries_ok(&outn));
                if (ad.per_pixel) {
                    /* the two-call path with this mask gives the same image */
                    CHECK_EQ(sbl_stereo_blend_masked(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t], mask, ms,
                                                     view(&ref), view(&refn), 0, h, scratch,
                                                     sbl_stereo_scratch_size(w, ch), NULL), SBL_OK);
                    ok = 1;
                    for (y = 0; y < h; ++y)
                        ok &= memcmp(sbt_at(&ref, 0, y), sbt_at(&out, 0, y), sizeof(float) * w * ch) == 0 &&
                              memcmp(sbt_at(&refn, 0, y), sbt_at(&outn, 0, y), sizeof(float) * w) == 0;
                    CHECK(ok);
                }
                /* the blend changed what it ran on (not a copy of the own result) */
                {
                    int changed = 0;
                    for (y = 0; y < h; ++y)
                        for (x = 0; x < w; ++x)
                            changed += mask[(size_t)y * ms + x] == SBL_INCONSISTENT &&
                                       memcmp(sbt_at(&out, x, y), sbt_at(&col[t], x, y), sizeof(float) * ch) != 0;
                    CHECK(changed > 0);
                }
                /* tiles: those holding a marked pixel, out of 4 x 3 */
                want_tiles = 0;
                for (y = 0; y < h; y += 16)
                    for (x = 0; x < w; x += 16) {
                        int yy, xx, any = 0;
                        for (yy = y; yy < y + 16 && yy < h; ++yy)
                            for (xx = x; xx < x + 16 && xx < w; ++xx)
                                any |= mask[(size_t)yy * ms + xx] == SBL_INCONSISTENT;
                        want_tiles += any;
                    }
                CHECK_EQ(tiles_all, 12);
                CHECK_EQ(tiles, want_tiles);
                if (pass != 2 && pass != 4) CHECK(tiles >= 1 && tiles <= 3);
                /* row bands of random heights equal the whole call */
                memset(mask2, 0x77, (size_t)ms * h);
                memset(&cb, 0, sizeof cb);
                for (y0 = 0; y0 < h;) {
                    int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 20.0);
                    sbl_consistency_counts cc;
                    if (y1 > h) y1 = h;
                    CHECK_EQ(sbl_stereo_blend_adaptive(&r.d, &ad, (sbl_eye_index)t, &r.eye[t], &r.eye[!t],
                                                       view(&ref), view(&refn), mask2, ms, y0, y1,
                                                       scratch, bytes, &cc, &tb, &tab), SBL_OK);
                    cb.consistent += cc.consistent; cb.inconsistent += cc.inconsistent;
                    cb.no_correspondence += cc.no_correspondence;
                    y0 = y1;
                }
                CHECK(memcmp(mask, mask2, (size_t)ms * h) == 0);
                CHECK(cb.consistent == c.consistent && cb.inconsistent == c.inconsistent &&
                      cb.no_correspondence == c.no_correspondence);
                ok = 1;
                for (y = 0; y < h; ++y)
                    ok &= memcmp(sbt_at(&ref, 0, y), sbt_at(&out, 0, y), sizeof(float) * w * ch) == 0 &&
                          memcmp(sbt_at(&refn, 0, y), sbt_at(&outn, 0, y), sizeof(float) * w) == 0;
                CHECK(ok);
                {   /* an empty row range writes and counts nothing */
                    sbl_consistency_counts ce;
                    const size_t nb = sizeof(float) * (size_t)ref.stride * h;
                    float *snap = (float *)malloc(nb);
                    memset(mask2, 0x77, (size_t)ms * h);
                    memcpy(snap, ref.mem, nb);
                    CHECK_EQ(sbl_stereo_blend_adaptive(&r.d, &ad, (sbl_eye_index)t, &r.eye[t], &r.eye[!t],
                                                       view(&ref), view(&refn), mask2, ms, 5, 5, scratch,
                                                       bytes, &ce, &tb, &tab), SBL_OK);
                    CHECK(ce.consistent == 0 && ce.inconsistent == 0 && ce.no_correspondence == 0);
                    CHECK(tb == 0 && tab == 0 && mask2[5 * ms] == 0x77);
                    CHECK(memcmp(ref.mem, snap, nb) == 0);
                    free(snap);
                }
                /* without the optional outputs: the same image */
                CHECK_EQ(sbl_stereo_blend_adaptive(&r.d, NULL, (sbl_eye_index)t, &r.eye[t], &r.eye[!t],
                                                   view(&ref), view(&refn), NULL, 0, 0, h, scratch,
                                                   bytes, NULL, NULL, NULL), SBL_OK);
                if (pass == 0) {
                    ok = 1;
                    for (y = 0; y < h; ++y)
                        ok &= memcmp(sbt_at(&ref, 0, y), sbt_at(&out, 0, y), sizeof(float) * w * ch) == 0;
                    CHECK(ok);
                }
            }
            if (ch == 3 && pass == 0) {
                /* rejected calls write nothing */
                sbl_result got;
                size_t nf = (size_t)out.stride * h;
                float *keep = (float *)malloc(nf * sizeof(float));
                unsigned char *mkeep = (unsigned char *)malloc((size_t)ms * h);
                sbl_adaptive_desc bad = ad;
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) for (k = 0; k < ch; ++k) sbt_at(&out, x, y)[k] = -7.0f;
                memcpy(keep, out.mem, nf * sizeof(float));
                memset(mask, 0x5a, (size_t)ms * h);
                memcpy(mkeep, mask, (size_t)ms * h);
#define REJECT_A(desc_, m_, stride_, y1_, scr_, nb_, outn_, code)                               \
                do {                                                                            \
                    got = sbl_stereo_blend_adaptive(&r.d, desc_, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], \
                                                    view(&out), outn_, m_, stride_, 0, y1_, scr_,  \
                                                    nb_, &c, NULL, NULL);                        \
                    CHECK_EQ(got, code);                                                        \
                    CHECK(memcmp(keep, out.mem, nf * sizeof(float)) == 0);                      \
                    CHECK(memcmp(mkeep, mask, (size_t)ms * h) == 0);                            \
                } while (0)
                bad.threshold = -0.01f;
                REJECT_A(&bad, mask, ms, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_PARAM);
                bad.threshold = (float)(HUGE_VAL - HUGE_VAL);
                REJECT_A(&bad, mask, ms, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_PARAM);
                bad = ad;
                bad.per_channel = 2;
                REJECT_A(&bad, mask, ms, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_PARAM);
                bad = ad;
                bad.per_pixel = -1;
                REJECT_A(&bad, mask, ms, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_PARAM);
                bad = ad;
                bad.nearest = 2;
                REJECT_A(&bad, mask, ms, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_PARAM);
                REJECT_A(&ad, mask, w - 1, h, scratch, bytes, view(&outn), SBL_ERROR_INVALID_STRIDE);
                REJECT_A(&ad, mask, ms, h + 1, scratch, bytes, view(&outn), SBL_ERROR_INVALID_ROWS);
                REJECT_A(&ad, mask, ms, h, scratch, bytes - 1, view(&outn), SBL_ERROR_SCRATCH_TOO_SMALL);
                /* the blend's own scratch is not enough */
                REJECT_A(&ad, mask, ms, h, scratch, sbl_stereo_scratch_size(w, ch), view(&outn),
                         SBL_ERROR_SCRATCH_TOO_SMALL);
                REJECT_A(&ad, mask, ms, h, NULL, bytes, view(&outn), SBL_ERROR_NULL_POINTER);
                REJECT_A(&ad, mask, ms, h, scratch, bytes, view(&col[0]), SBL_ERROR_INVALID_CHANNELS);
                REJECT_A(&ad, mask, ms, h, scratch, bytes, view(&r.dep[0]), SBL_ERROR_OVERLAP);
                /* the mask over an output or an input */
                memcpy(mkeep, mask, (size_t)ms * h);
                got = sbl_stereo_blend_adaptive(&r.d, &ad, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out),
                                                view(&outn), (unsigned char *)outn.mem, w, 0, h,
                                                scratch, bytes, NULL, NULL, NULL);
                CHECK_EQ(got, SBL_ERROR_OVERLAP);
                CHECK(memcmp(keep, out.mem, nf * sizeof(float)) == 0);
                got = sbl_stereo_blend_adaptive(&r.d, &ad, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out),
                                                view(&outn), (unsigned char *)r.dep[1].mem, w, 0, h,
                                                scratch, bytes, NULL, NULL, NULL);
                CHECK_EQ(got, SBL_ERROR_OVERLAP);
                CHECK(memcmp(keep, out.mem, nf * sizeof(float)) == 0);
                CHECK(isfinite(*sbt_at(&r.dep[1], 0, 0)));
                CHECK_EQ(sbl_stereo_adaptive_scratch_size(0, 3), 0);
                CHECK_EQ(sbl_stereo_adaptive_scratch_size(w, 5), 0);
                CHECK(sbl_stereo_adaptive_scratch_size(w, 3) > sbl_stereo_scratch_size(w, 3));
#undef REJECT_A
                free(keep); free(mkeep);
            }
            for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); }
            free(full.mem); free(fulln.mem); free(out.mem); free(outn.mem); free(ref.mem);
            free(refn.mem); free(rp.mem); free(rpv.mem);
            free(mask); free(mask2); free(scratch);
            rig_free(&r);
        }
}

int main(void)
{
    test_hand_case();
    test_occlusion_channels();
    test_bands();
    test_errors();
    test_blend_masked();
    test_blend_adaptive();
    return sbt_finish("test_adaptive");
}
