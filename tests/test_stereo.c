/* Stereo tests: reprojection round trips on the three rigs (parallel, disparity images,
   camera matrices), occlusion (depth test and back-check), beta on two unbiased eyes and
   on view-dependent highlights, fill mode and merge, eye-swap and mirror symmetry, row
   bands, and the error codes of every stereo and fill entry point.
   Scenes are built here: a parallel rig with focal length f (pixels) and baseline b, a
   fronto-parallel far plane and, for occlusion, a near box in front of it. The right
   eye's match of left pixel u at depth z is u - f b / z. */
#include <stdlib.h>
#include "../stereoblend.h"
/* tst_alloc: the context of the counting, failing allocator hooks that the
   implementation object (tests/sbl_impl.c) is built with */
#include "sbl_test_alloc.h"
#include "sbl_test.h"

static sbl_image view(const sbt_img *im)
{
    sbl_image v;
    memset(&v, 0, sizeof v);
    v.data = im->mem; v.width = im->w; v.height = im->h; v.channels = im->c; v.stride = im->stride;
    return v;
}

static void img_fill(sbt_img *im, float v)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k) sbt_at(im, x, y)[k] = v;
}

static size_t img_floats(const sbt_img *im) { return (size_t)im->stride * (size_t)im->h; }

/* ---- the synthetic stereo scene ------------------------------------------------- */

typedef struct stereo {
    int w, h, c;
    float f, b;
    float zfar, znear;       /* znear <= 0: no box                                   */
    double bx0, bx1;         /* box: continuous left-image x range [bx0, bx1) ...     */
    int by0, by1;            /* ... and rows [by0, by1)                               */
    sbt_img col[2], dep[2], disp[2], len[2], ids[2];
    sbl_camera cam[2];
} stereo;

static void st_init(stereo *s, int w, int h, int c, float f, float b)
{
    int e, i;
    memset(s, 0, sizeof *s);
    s->w = w; s->h = h; s->c = c; s->f = f; s->b = b;
    for (e = 0; e < 2; ++e) {
        s->col[e] = sbt_img_new(w, h, c, 1 + e);
        s->dep[e] = sbt_img_new(w, h, 1, 2 - e);
        s->disp[e] = sbt_img_new(w, h, 1, 1);
        s->len[e] = sbt_img_new(w, h, 1, e);
        s->ids[e] = sbt_img_new(w, h, 1, 3);
        img_fill(&s->len[e], 1.0f);
        /* OpenGL projection, fx = fy = f pixels, principal point at the centre,
           near 0.1, far 100; left eye at the origin, right eye at x = +b */
        for (i = 0; i < 16; ++i) s->cam[e].world_to_view[i] = (i % 5 == 0) ? 1.0f : 0.0f;
        memset(s->cam[e].view_to_clip, 0, sizeof s->cam[e].view_to_clip);
        s->cam[e].view_to_clip[0] = 2.0f * f / (float)w;
        s->cam[e].view_to_clip[5] = 2.0f * f / (float)h;
        s->cam[e].view_to_clip[10] = -(100.0f + 0.1f) / (100.0f - 0.1f);
        s->cam[e].view_to_clip[11] = -2.0f * 100.0f * 0.1f / (100.0f - 0.1f);
        s->cam[e].view_to_clip[14] = -1.0f;
    }
    s->cam[1].world_to_view[3] = -b;
}

static void st_free(stereo *s)
{
    int e;
    for (e = 0; e < 2; ++e) {
        free(s->col[e].mem); free(s->dep[e].mem); free(s->disp[e].mem);
        free(s->len[e].mem); free(s->ids[e].mem);
    }
}

/* Same float expression as the library: focal_px * baseline / z. */
static float st_disp(const stereo *s, float z) { return s->f * s->b / z; }

/* Is pixel (u, y) of eye e on the near box? */
static int st_box(const stereo *s, int e, int u, int y)
{
    double cx;
    if (!(s->znear > 0.0f) || y < s->by0 || y >= s->by1) return 0;
    cx = u + 0.5 + (e ? (double)st_disp(s, s->znear) : 0.0);
    return cx >= s->bx0 && cx < s->bx1;
}

static void st_geometry(stereo *s, float zfar, float znear, double bx0, double bx1, int by0,
                        int by1)
{
    int e, x, y;
    s->zfar = zfar; s->znear = znear; s->bx0 = bx0; s->bx1 = bx1; s->by0 = by0; s->by1 = by1;
    for (e = 0; e < 2; ++e)
        for (y = 0; y < s->h; ++y)
            for (x = 0; x < s->w; ++x) {
                int box = st_box(s, e, x, y);
                float z = box ? znear : zfar;
                *sbt_at(&s->dep[e], x, y) = z;
                *sbt_at(&s->disp[e], x, y) = st_disp(s, z);
                *sbt_at(&s->ids[e], x, y) = box ? 2.0f : 1.0f;
            }
}

/* Analytic answer for target eye t at (u, y): *bx = match in source pixel-index space
   (the source pixel whose centre is the match is bx when bx is an integer). Valid iff
   the match lies inside the source image and the source sees the same surface there. */
static int st_expect(const stereo *s, int t, int u, int y, double *bx)
{
    int box = st_box(s, t, u, y);
    double d = st_disp(s, box ? s->znear : s->zfar);
    double sx;
    *bx = t == SBL_EYE_LEFT ? u - d : u + d;
    sx = *bx + 0.5;
    if (!(sx >= 0.0 && sx < s->w)) return 0;
    return st_box(s, !t, (int)floor(sx), y) == box;
}
static int st_match_inside(const stereo *s, int t, int u, int y)
{
    double bx, sx;
    (void)st_expect(s, t, u, y, &bx);
    sx = bx + 0.5;
    return sx >= 0.0 && sx < s->w;
}

static sbl_eye st_eye(stereo *s, int e, int rig)
{
    sbl_eye v;
    memset(&v, 0, sizeof v);
    v.color = view(&s->col[e]);
    if (rig != SBL_RIG_DISPARITY) v.gbuffer.depth = view(&s->dep[e]);
    if (rig == SBL_RIG_DISPARITY) v.disparity = view(&s->disp[e]);
    if (rig == SBL_RIG_MATRICES) v.camera = &s->cam[e];
    return v;
}

static sbl_stereo_desc st_desc(const stereo *s, int rig)
{
    sbl_stereo_desc d;
    memset(&d, 0, sizeof d);
    d.rig = (sbl_stereo_rig)rig;
    d.focal_px = s->f;
    d.baseline = s->b;
    return d;
}

static void st_random_colors(stereo *s, sbt_rng *rng)
{
    int e, x, y, k;
    for (e = 0; e < 2; ++e)
        for (y = 0; y < s->h; ++y)
            for (x = 0; x < s->w; ++x)
                for (k = 0; k < s->c; ++k) sbt_at(&s->col[e], x, y)[k] = (float)sbt_uniform(rng);
}

/* The occlusion scene used by several tests: 48 x 16, f b = 12, far plane at z = 3
   (disparity 4), near box at z = 1 (disparity 12) over left columns [24, 34) and rows
   [4, 12) (right columns [12, 22)). In the left eye the far plane in columns [16, 24) of
   the box rows is hidden from the right eye, in the right eye columns [22, 30); the
   match is outside the other image in left columns 0..3 and right columns 44..47. */
static void st_occlusion_scene(stereo *s, int c)
{
    st_init(s, 48, 16, c, 24.0f, 0.5f);
    st_geometry(s, 3.0f, 1.0f, 24.0, 34.0, 4, 12);
}

/* ---- 1. exact round trips and the three rigs ------------------------------------ */

static void test_round_trip(void)
{
    const int w = 32, h = 10, c = 3;
    const float zs[3] = {3.0f, 3.2f, 5.0f}; /* f b = 12: disparity 4, 3.75, 2.4 */
    stereo s;
    sbt_img out[3], val[3];
    sbt_rng rng = {21};
    long leak[3] = {0, 0, 0};
    int zi, t, r, x, y, k;
    st_init(&s, w, h, c, 24.0f, 0.5f);
    st_random_colors(&s, &rng);
    for (r = 0; r < 3; ++r) { out[r] = sbt_img_new(w, h, c, 2); val[r] = sbt_img_new(w, h, 1, 1); }
    for (zi = 0; zi < 3; ++zi) {
        int integer;
        st_geometry(&s, zs[zi], 0.0f, 0, 0, 0, 0);
        integer = st_disp(&s, zs[zi]) == floorf(st_disp(&s, zs[zi]));
        CHECK(integer == (zi == 0));
        for (t = 0; t < 2; ++t) {
            int agree_valid = 1, agree_disp = 1, agree_mat = 1;
            for (r = 0; r < 3; ++r) {
                sbl_stereo_desc d = st_desc(&s, r);
                sbl_eye te = st_eye(&s, t, r), se = st_eye(&s, !t, r);
                const sbt_img *src = &s.col[!t];
                int colour_ok = 1, inside_ok = 1, n_exact = 0;
                /* integer disparity: exact copies (the matrices rig computes the position
                   in double from float matrices, so allow rounding there) */
                double tol = (integer && r != SBL_RIG_MATRICES) ? 0.0 : 1e-6;
                img_fill(&out[r], -7.0f);
                CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out[r]),
                                              view(&val[r]), 0, h), SBL_OK);
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) {
                        double bx;
                        int ev = st_expect(&s, t, x, y, &bx);
                        float v = *sbt_at(&val[r], x, y);
                        if (ev) inside_ok &= v == 1.0f;
                        else leak[r] += v != 0.0f;
                        if (bx >= 0.0 && bx <= w - 1) {
                            int x0 = (int)floor(bx);
                            double fx = bx - x0;
                            for (k = 0; k < c; ++k) {
                                double ref = (1.0 - fx) * sbt_at(src, x0, y)[k] +
                                             (fx > 0.0 ? fx * sbt_at(src, x0 + 1, y)[k] : 0.0);
                                colour_ok &= fabs(sbt_at(&out[r], x, y)[k] - ref) <= tol;
                                n_exact += sbt_at(&out[r], x, y)[k] == (float)ref;
                            }
                        }
                        /* invalid pixels are written as 0 */
                        if (v == 0.0f)
                            for (k = 0; k < c; ++k) colour_ok &= sbt_at(&out[r], x, y)[k] == 0.0f;
                    }
                CHECK(colour_ok);
                CHECK(inside_ok);
                CHECK(n_exact > 0); /* the comparison is not vacuous */
                CHECK(sbt_canaries_ok(&out[r]) && sbt_canaries_ok(&val[r]));
            }
            /* the three rigs agree: same valid set, same colours */
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    agree_valid &= *sbt_at(&val[0], x, y) == *sbt_at(&val[1], x, y) &&
                                   *sbt_at(&val[0], x, y) == *sbt_at(&val[2], x, y);
                    for (k = 0; k < c; ++k) {
                        agree_disp &= sbt_at(&out[0], x, y)[k] == sbt_at(&out[1], x, y)[k];
                        agree_mat &= fabsf(sbt_at(&out[0], x, y)[k] - sbt_at(&out[2], x, y)[k]) <= 1e-6f;
                    }
                }
            CHECK(agree_valid);
            CHECK(agree_disp);
            CHECK(agree_mat);
        }
    }
    /* pixels whose match falls outside the other image are invalid (all rigs) */
    printf("  round trip: valid pixels whose match is outside the source image: parallel %ld, "
           "disparity %ld, matrices %ld\n", leak[0], leak[1], leak[2]);
    CHECK_EQ(leak[0], 0);
    CHECK_EQ(leak[1], 0);
    CHECK_EQ(leak[2], 0);
    /* the same with the 3x3 fallback off, integer disparity: only the bilinear taps */
    {
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        sbl_eye te = st_eye(&s, 0, SBL_RIG_PARALLEL), se = st_eye(&s, 1, SBL_RIG_PARALLEL);
        int ok = 1;
        d.reproject.no_fallback = 1;
        st_geometry(&s, 3.0f, 0.0f, 0, 0, 0, 0);
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &te, &se, view(&out[0]), view(&val[0]), 0, h), SBL_OK);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) ok &= *sbt_at(&val[0], x, y) == (x >= 4 ? 1.0f : 0.0f);
        CHECK(ok);
        /* and right from left: right u takes left u + 4 */
        ok = 1;
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_RIGHT, &se, &te, view(&out[0]), view(&val[0]), 0, h), SBL_OK);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                ok &= *sbt_at(&val[0], x, y) == (x + 4 < w ? 1.0f : 0.0f);
                if (x + 4 < w) ok &= memcmp(sbt_at(&out[0], x, y), sbt_at(&s.col[0], x + 4, y), 3 * sizeof(float)) == 0;
            }
        CHECK(ok);
    }
    /* the sign: left pixel 10 takes right pixel 10 - 4, not 10 + 4 */
    {
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        sbl_eye te = st_eye(&s, 0, SBL_RIG_PARALLEL), se = st_eye(&s, 1, SBL_RIG_PARALLEL);
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &te, &se, view(&out[0]), view(&val[0]), 0, h), SBL_OK);
        CHECK(memcmp(sbt_at(&out[0], 10, 3), sbt_at(&s.col[1], 14, 3), 3 * sizeof(float)) != 0);
        CHECK(memcmp(sbt_at(&out[0], 10, 3), sbt_at(&s.col[1], 6, 3), 3 * sizeof(float)) == 0);
    }
    for (r = 0; r < 3; ++r) { free(out[r].mem); free(val[r].mem); }
    st_free(&s);
}

/* ---- 2. occlusion: depth test, back-check, ids, out of image --------------------- */

/* Counts, for target eye t, the pixels of each class whose validity is wrong. */
typedef struct occ_count { long band_valid, visible_invalid, outside_valid, band_total, valid; } occ_count;

static occ_count occ_classify(const stereo *s, int t, const sbt_img *val)
{
    occ_count n;
    int x, y;
    memset(&n, 0, sizeof n);
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double bx;
            int ev = st_expect(s, t, x, y, &bx), inside = st_match_inside(s, t, x, y);
            int v = *sbt_at(val, x, y) != 0.0f;
            n.valid += v;
            if (!inside) n.outside_valid += v;
            else if (!ev) { n.band_total++; n.band_valid += v; }
            else n.visible_invalid += !v;
        }
    return n;
}

static void test_occlusion(void)
{
    stereo s;
    sbt_img out, val;
    sbt_rng rng = {8};
    int t, r, x, y;
    st_occlusion_scene(&s, 3);
    st_random_colors(&s, &rng);
    out = sbt_img_new(s.w, s.h, 3, 1);
    val = sbt_img_new(s.w, s.h, 1, 2);
    for (t = 0; t < 2; ++t) {
        sbl_eye te = st_eye(&s, t, SBL_RIG_PARALLEL), se = st_eye(&s, !t, SBL_RIG_PARALLEL);
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        occ_count n;
        int colour_ok = 1;
        /* defaults: depth test + back-check */
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_total, 64);      /* 8 columns x 8 rows, as built */
        CHECK_EQ(n.band_valid, 0);
        CHECK_EQ(n.visible_invalid, 0);
        CHECK_EQ(n.outside_valid, 0);
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) {
                double bx;
                if (st_expect(&s, t, x, y, &bx))
                    colour_ok &= memcmp(sbt_at(&out, x, y), sbt_at(&s.col[!t], (int)bx, y), 3 * sizeof(float)) == 0;
            }
        CHECK(colour_ok);
        if (t == 0) printf("  occlusion, defaults: left eye %ld valid of %d (band %ld, outside-but-valid %ld)\n",
                           n.valid, s.w * s.h, n.band_total, n.outside_valid);

        /* depth test off (huge tolerance), no ids: the 1-pixel back-check still rejects
           the band (its round trip lands 8 pixels away) */
        d.reproject.depth_tolerance = 1e30f;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 0);
        CHECK_EQ(n.visible_invalid, 0);
        /* a looser back-check admits more: 7.5 px still rejects, 8.5 px admits the band */
        d.reproject.back_check_pixels = 7.5f;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 0);
        d.reproject.back_check_pixels = 8.5f;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 64);
        CHECK_EQ(n.visible_invalid, 0);

        /* back-check off, depth test on, fallback off: the depth test alone rejects it */
        d = st_desc(&s, SBL_RIG_PARALLEL);
        d.reproject.back_check_pixels = 1e6f;
        d.reproject.no_fallback = 1;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 0);
        CHECK_EQ(n.visible_invalid, 0);
        /* nothing on: the band is (wrongly) accepted, so the tests above can fail */
        d.reproject.depth_tolerance = 1e30f;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 64);
        /* ... and ids alone reject it again */
        te.gbuffer.ids = view(&s.ids[t]);
        se.gbuffer.ids = view(&s.ids[!t]);
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
        n = occ_classify(&s, t, &val);
        CHECK_EQ(n.band_valid, 0);
        CHECK_EQ(n.visible_invalid, 0);
    }
    /* the other rigs find the same valid set (disparity rig: no depth, back-check only) */
    for (r = 1; r < 3; ++r)
        for (t = 0; t < 2; ++t) {
            sbl_eye te = st_eye(&s, t, r), se = st_eye(&s, !t, r);
            sbl_stereo_desc d = st_desc(&s, r);
            occ_count n;
            CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&out), view(&val), 0, s.h), SBL_OK);
            n = occ_classify(&s, t, &val);
            CHECK_EQ(n.band_valid, 0);
            CHECK_EQ(n.visible_invalid, 0);
            CHECK_EQ(n.outside_valid, 0);
        }
    CHECK(sbt_canaries_ok(&out) && sbt_canaries_ok(&val));
    free(out.mem); free(val.mem);
    st_free(&s);
}

/* ---- 3. beta ~ 1/2 for two unbiased eyes of equal noise -------------------------- */

/* Reference weight of the left eye's own sample at (x, y) (ALGORITHMS.md sections 2 and
   4) for the 1-channel plane with disparity 4 and N = 1 in both eyes: 3x3 population
   mean / variance of Y, x* = right pixel x - 4, paired differences over the window. */
static double ref_weight(const stereo *s, int est, int x, int y)
{
    const sbt_img *Y = &s->col[0], *X = &s->col[1];
    double m = 0, v = 0, pd = 0, pv = 0, xs = *sbt_at(X, x - 4, y);
    int n = 0, np = 0, i, j;
    for (j = y - 1; j <= y + 1; ++j)
        for (i = x - 1; i <= x + 1; ++i) { m += *sbt_at(Y, i, j); ++n; }
    m /= n;
    for (j = y - 1; j <= y + 1; ++j)
        for (i = x - 1; i <= x + 1; ++i) {
            v += (*sbt_at(Y, i, j) - m) * (*sbt_at(Y, i, j) - m);
            if (i >= 4) { pd += *sbt_at(X, i - 4, j) - *sbt_at(Y, i, j); ++np; }
        }
    v /= n;
    pd /= np;
    for (j = y - 1; j <= y + 1; ++j)
        for (i = x - 1; i <= x + 1; ++i)
            if (i >= 4) {
                double e = (*sbt_at(X, i - 4, j) - *sbt_at(Y, i, j)) - pd;
                pv += e * e;
            }
    pv /= np - 1;
    if (est == SBL_ESTIMATOR_PAPER) {
        double d2 = (xs - m) * (xs - m);
        return d2 / (d2 + v);
    } else {
        /* ALGORITHMS.md section 4 with the noise read off the pairs (a paired t-test,
           threshold 3): var(x_i - y_i) = var_X + var_Y, N_X = N_Y = 1 */
        double var_y = pv / 2, var_x = pv - var_y;
        double b2 = pd * pd - 9.0 * pv / np;
        if (b2 < 0.0) b2 = 0.0;
        return (b2 + var_x) / (b2 + var_x + var_y);
    }
}

static void test_beta_half(void)
{
    const int w = 64, h = 64;
    const double sigma = 0.1, truth = 0.5;
    stereo s;
    sbt_img out, len;
    sbt_rng rng = {1234};
    double rmse[SBL_ESTIMATOR_COUNT], beta[SBL_ESTIMATOR_COUNT], nout[SBL_ESTIMATOR_COUNT];
    int e, x, y, t;
    st_init(&s, w, h, 1, 24.0f, 0.5f);
    st_geometry(&s, 3.0f, 0.0f, 0, 0, 0, 0); /* disparity 4: x* is one pixel, N_X = 1 */
    for (t = 0; t < 2; ++t)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) *sbt_at(&s.col[t], x, y) = (float)(truth + sigma * sbt_gauss(&rng));
    out = sbt_img_new(w, h, 1, 1);
    len = sbt_img_new(w, h, 1, 2);
    {
        size_t bytes = sbl_stereo_scratch_size(w, 1);
        void *scratch = malloc(bytes);
        for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
            double se = 0, sb = 0, sn = 0, sraw = 0;
            long n = 0, nb = 0;
            int own_ok = 1, n2_ok = 1, ref_ok = 1;
            long n_ref = 0;
            sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
            sbl_eye te = st_eye(&s, 0, SBL_RIG_PARALLEL), se_ = st_eye(&s, 1, SBL_RIG_PARALLEL);
            d.estimator = (sbl_estimator)e;
            CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_LEFT, &te, &se_, view(&out), view(&len), 0, h, scratch, bytes), SBL_OK);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    double o = *sbt_at(&out, x, y), yv = *sbt_at(&s.col[0], x, y);
                    if (x < 3) { /* no match (x = 3, the edge column, is test_round_trip's) */
                        own_ok &= o == yv && *sbt_at(&len, x, y) == 1.0f;
                        continue;
                    }
                    if (x < 4) continue;
                    {
                        double xs = *sbt_at(&s.col[1], x - 4, y);
                        se += (o - truth) * (o - truth);
                        sraw += (yv - truth) * (yv - truth);
                        sn += *sbt_at(&len, x, y);
                        ++n;
                        if (fabs(yv - xs) > 1e-3) { sb += (o - xs) / (yv - xs); ++nb; }
                        if (x >= 5 && x < w - 1 && y >= 1 && y < h - 1 &&
                            (e == SBL_ESTIMATOR_PAPER || e == SBL_ESTIMATOR_HISTORY_AWARE)) {
                            double a = ref_weight(&s, e, x, y);
                            ref_ok &= fabs(o - (xs + a * (yv - xs))) <= 1e-5;
                            ++n_ref;
                        }
                        if (e == SBL_ESTIMATOR_PROGRESSIVE || e == SBL_ESTIMATOR_CONSTANT)
                            n2_ok &= fabs(*sbt_at(&len, x, y) - 2.0) < 1e-6;
                    }
                }
            rmse[e] = sqrt(se / n);
            beta[e] = sb / nb;
            nout[e] = sn / n;
            CHECK(own_ok);
            CHECK(n2_ok);
            CHECK(ref_ok);
            CHECK(n_ref == 0 || n_ref == (long)(w - 6) * (h - 2));
            CHECK_NEAR(sqrt(sraw / n), sigma, 0.05 * sigma); /* the input is what we think */
        }
        free(scratch);
    }
    printf("  beta 1/2 (sigma %.2f, target sigma/sqrt2 = %.4f): RMSE history-aware %.4f (beta %.3f, N %.3f), "
           "paper %.4f (beta %.3f, N %.3f), progressive %.4f (beta %.3f, N %.3f), constant %.4f (beta %.3f)\n",
           sigma, sigma / sqrt(2.0), rmse[0], beta[0], nout[0], rmse[1], beta[1], nout[1], rmse[2], beta[2],
           nout[2], rmse[3], beta[3]);
    CHECK_NEAR(rmse[SBL_ESTIMATOR_PROGRESSIVE], sigma / sqrt(2.0), 0.03 * sigma / sqrt(2.0));
    CHECK_NEAR(rmse[SBL_ESTIMATOR_CONSTANT], sigma / sqrt(2.0), 0.03 * sigma / sqrt(2.0));
    CHECK_NEAR(rmse[SBL_ESTIMATOR_HISTORY_AWARE], sigma / sqrt(2.0), 0.05 * sigma / sqrt(2.0));
    CHECK_NEAR(beta[SBL_ESTIMATOR_PROGRESSIVE], 0.5, 1e-5);
    CHECK_NEAR(beta[SBL_ESTIMATOR_CONSTANT], 0.5, 1e-5);
    CHECK_NEAR(beta[SBL_ESTIMATOR_HISTORY_AWARE], 0.5, 0.05);
    CHECK_NEAR(nout[SBL_ESTIMATOR_PROGRESSIVE], 2.0, 1e-6);
    CHECK(nout[SBL_ESTIMATOR_HISTORY_AWARE] > 1.95 && nout[SBL_ESTIMATOR_HISTORY_AWARE] <= 2.0 + 1e-6);
    /* the paper's estimator: E[d^2] / (E[d^2] + E[s^2]) = (10/9) / (10/9 + 8/9) = 0.56,
       but the mean of the per-pixel ratio is lower, and on a flat plane its weight picks
       the sample closer to the 3x3 mean, which beats the fixed 1/2 here (the per-pixel
       formula itself is checked against the reference above). N_out, computed from the
       mean weight as if it were fixed, drops below 2. */
    CHECK(beta[SBL_ESTIMATOR_PAPER] > 0.35 && beta[SBL_ESTIMATOR_PAPER] < 0.6);
    CHECK(rmse[SBL_ESTIMATOR_PAPER] < rmse[SBL_ESTIMATOR_PROGRESSIVE]);
    CHECK(rmse[SBL_ESTIMATOR_PAPER] > sigma / 3.0);
    CHECK(nout[SBL_ESTIMATOR_PAPER] < nout[SBL_ESTIMATOR_HISTORY_AWARE]);
    CHECK(sbt_canaries_ok(&out) && sbt_canaries_ok(&len));
    free(out.mem); free(len.mem);
    st_free(&s);
}

/* ---- 4. beta ~ 1 on view-dependent highlights: no double images ------------------- */

static void test_highlights(void)
{
    const int w = 64, h = 32, c = 3;
    const float base[3] = {0.3f, 0.25f, 0.2f}, amp = 4.0f;
    const int lx = 20, rx = 36, cy = 16; /* left highlight at 20, right one at 36 (ghost at left 40) */
    stereo s;
    sbt_img out[2];
    sbt_rng rng = {77};
    int t, e, x, y, k;
    st_init(&s, w, h, c, 24.0f, 0.5f);
    st_geometry(&s, 3.0f, 0.0f, 0, 0, 0, 0); /* disparity 4 */
    for (t = 0; t < 2; ++t)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int hx = t == 0 ? lx : rx;
                int lit = (x - hx) * (x - hx) + (y - cy) * (y - cy) <= 12; /* disc, radius ~3.5 */
                for (k = 0; k < c; ++k)
                    sbt_at(&s.col[t], x, y)[k] = base[k] + (lit ? amp : 0.0f) + (float)(0.01 * sbt_gauss(&rng));
            }
    for (t = 0; t < 2; ++t) out[t] = sbt_img_new(w, h, c, 1);
    for (e = 0; e < 3; ++e) {
        static const sbl_estimator est[3] = {SBL_ESTIMATOR_HISTORY_AWARE, SBL_ESTIMATOR_PAPER, SBL_ESTIMATOR_CONSTANT};
        static const char *name[3] = {"history-aware", "paper", "constant 0.5"};
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        sbl_eye le = st_eye(&s, 0, SBL_RIG_PARALLEL), re = st_eye(&s, 1, SBL_RIG_PARALLEL);
        double keep_core[2] = {1e9, 1e9}, ghost_core[2] = {0, 0}, ghost_disc[2] = {0, 0};
        d.estimator = est[e];
        CHECK_EQ(sbl_stereo_blend_frame(&d, &le, &re, view(&out[0]), view(&out[1])), SBL_OK);
        for (t = 0; t < 2; ++t) {
            /* own highlight at (own x, cy); the other eye's appears at other x -+ 4 */
            int hx = t == 0 ? lx : rx, gx = t == 0 ? rx + 4 : lx - 4;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    int r_own = (x - hx) * (x - hx) + (y - cy) * (y - cy);
                    int r_gh = (x - gx) * (x - gx) + (y - cy) * (y - cy);
                    for (k = 0; k < c; ++k) {
                        double o = sbt_at(&out[t], x, y)[k];
                        /* core: the 3x3 window lies entirely inside the disc */
                        if (r_own <= 2 && o - base[k] < keep_core[t]) keep_core[t] = o - base[k];
                        if (r_gh <= 2 && fabs(o - base[k]) > ghost_core[t]) ghost_core[t] = fabs(o - base[k]);
                        if (r_gh <= 12 && fabs(o - base[k]) > ghost_disc[t]) ghost_disc[t] = fabs(o - base[k]);
                    }
                }
        }
        printf("  highlights, %s: kept min %.3f / %.1f (left) %.3f (right), ghost max core %.3f / %.3f, "
               "whole disc %.3f / %.3f\n", name[e], keep_core[0], amp, keep_core[1], ghost_core[0],
               ghost_core[1], ghost_disc[0], ghost_disc[1]);
        for (t = 0; t < 2; ++t) {
            if (est[e] == SBL_ESTIMATOR_CONSTANT) {
                /* the fixed 1/2 halves the highlight and draws the other eye's as a ghost */
                CHECK_NEAR(keep_core[t], 0.5 * amp, 0.05 * amp);
                CHECK(ghost_core[t] > 0.45 * amp);
            } else {
                CHECK(keep_core[t] > 0.9 * amp);
                CHECK(ghost_core[t] < 0.1 * amp);
                CHECK(ghost_disc[t] < 0.5 * amp);
            }
        }
    }
    free(out[0].mem); free(out[1].mem);
    st_free(&s);
}

/* ---- 5. fill mode and merge ------------------------------------------------------ */

static void test_fill(void)
{
    stereo s;
    sbt_img out, ref, refv, traced, dst;
    sbt_rng rng = {31};
    const int pad = 5;
    unsigned char *mask;
    int mstride, x, y, t;
    st_occlusion_scene(&s, 3);
    st_random_colors(&s, &rng);
    mstride = s.w + pad;
    mask = (unsigned char *)malloc((size_t)mstride * (size_t)s.h);
    out = sbt_img_new(s.w, s.h, 3, 2);
    ref = sbt_img_new(s.w, s.h, 3, 0);
    refv = sbt_img_new(s.w, s.h, 1, 0);
    traced = sbt_img_new(s.w, s.h, 3, 1);
    dst = sbt_img_new(s.w, s.h, 3, 1);
    for (y = 0; y < s.h; ++y)
        for (x = 0; x < s.w; ++x) {
            sbt_at(&traced, x, y)[0] = 100.0f + x;
            sbt_at(&traced, x, y)[1] = 200.0f + y;
            sbt_at(&traced, x, y)[2] = 300.0f;
        }
    for (t = 0; t < 2; ++t) {
        /* the target (not yet traced) eye needs geometry only */
        sbl_eye te = st_eye(&s, t, SBL_RIG_PARALLEL), se = st_eye(&s, !t, SBL_RIG_PARALLEL);
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        long count = -1, set = 0, expected = 0, band_count = 0, outside = 0, band = 0;
        int mask_ok = 1, colour_ok = 1, pad_ok = 1, merge_ok = 1, zero_ok = 1, yb;
        te.color.data = NULL;
        memset(mask, 0xA5, (size_t)mstride * (size_t)s.h);
        CHECK_EQ(sbl_stereo_fill(&d, (sbl_eye_index)t, &te, &se, view(&out), mask, mstride, 0, s.h, &count), SBL_OK);
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&ref), view(&refv), 0, s.h), SBL_OK);
        for (y = 0; y < s.h; ++y) {
            for (x = 0; x < s.w; ++x) {
                unsigned char m = mask[y * mstride + x];
                double bx;
                int ev = st_expect(&s, t, x, y, &bx);
                set += m != 0;
                expected += !ev;
                outside += !st_match_inside(&s, t, x, y);
                band += !ev && st_match_inside(&s, t, x, y);
                mask_ok &= m == (ev ? 0 : 1);
                if (!m) {
                    /* not masked: the reprojected colour (= the source pixel, integer disparity) */
                    colour_ok &= memcmp(sbt_at(&out, x, y), sbt_at(&ref, x, y), 3 * sizeof(float)) == 0;
                    colour_ok &= *sbt_at(&refv, x, y) == 1.0f;
                    if (ev) colour_ok &= memcmp(sbt_at(&out, x, y), sbt_at(&s.col[!t], (int)bx, y), 3 * sizeof(float)) == 0;
                } else {
                    zero_ok &= sbt_at(&out, x, y)[0] == 0.0f && sbt_at(&out, x, y)[2] == 0.0f;
                    colour_ok &= *sbt_at(&refv, x, y) == 0.0f;
                }
            }
            for (x = s.w; x < mstride; ++x) pad_ok &= mask[y * mstride + x] == 0xA5;
        }
        printf("  fill, %s eye: %ld of %d pixels need a ray (%.2f%%), expected %ld = %ld outside + %ld occluded\n",
               t == 0 ? "left" : "right", count, s.w * s.h, 100.0 * count / (s.w * s.h), expected, outside, band);
        CHECK_EQ(count, set);
        CHECK_EQ(band, 64);
        CHECK_EQ(outside, 64);
        CHECK_EQ(count, expected);  /* 128 of 768: 16.7 % */
        CHECK(mask_ok);
        CHECK(colour_ok);
        CHECK(zero_ok);
        CHECK(pad_ok);
        CHECK(sbt_canaries_ok(&out));
        /* in bands: counts add up, rows outside the band untouched */
        memset(mask, 0xA5, (size_t)mstride * (size_t)s.h);
        for (yb = 0; yb < s.h; yb += 5) {
            long c = -1;
            int y1 = yb + 5 > s.h ? s.h : yb + 5;
            CHECK_EQ(sbl_stereo_fill(&d, (sbl_eye_index)t, &te, &se, view(&out), mask, mstride, yb, y1, &c), SBL_OK);
            band_count += c;
            if (yb == 0) CHECK(mask[5 * mstride] == 0xA5 && mask[(s.h - 1) * mstride + s.w - 1] == 0xA5);
        }
        CHECK_EQ(band_count, count);
        {   /* count pointer optional; empty range writes nothing */
            memset(mask, 0xA5, (size_t)mstride * (size_t)s.h);
            CHECK_EQ(sbl_stereo_fill(&d, (sbl_eye_index)t, &te, &se, view(&out), mask, mstride, 3, 3, NULL), SBL_OK);
            CHECK(mask[3 * mstride] == 0xA5);
            CHECK_EQ(sbl_stereo_fill(&d, (sbl_eye_index)t, &te, &se, view(&out), mask, mstride, 0, s.h, NULL), SBL_OK);
        }
        /* merge: traced pixels go exactly where the mask is set */
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) memcpy(sbt_at(&dst, x, y), sbt_at(&out, x, y), 3 * sizeof(float));
        CHECK_EQ(sbl_merge_traced(view(&dst), view(&traced), mask, mstride, 0, s.h), SBL_OK);
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) {
                const float *want = mask[y * mstride + x] ? sbt_at(&traced, x, y) : sbt_at(&out, x, y);
                merge_ok &= memcmp(sbt_at(&dst, x, y), want, 3 * sizeof(float)) == 0;
            }
        CHECK(merge_ok);
        CHECK(sbt_canaries_ok(&dst));
        /* merge in a band leaves the other rows alone */
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) memcpy(sbt_at(&dst, x, y), sbt_at(&out, x, y), 3 * sizeof(float));
        CHECK_EQ(sbl_merge_traced(view(&dst), view(&traced), mask, mstride, 5, 7), SBL_OK);
        merge_ok = 1;
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) {
                int in = y >= 5 && y < 7 && mask[y * mstride + x];
                merge_ok &= memcmp(sbt_at(&dst, x, y), in ? sbt_at(&traced, x, y) : sbt_at(&out, x, y), 3 * sizeof(float)) == 0;
            }
        CHECK(merge_ok);
    }
    /* desc.fill in the blend: the other eye wherever it reprojects, own value elsewhere */
    {
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        sbl_eye le = st_eye(&s, 0, SBL_RIG_PARALLEL), re = st_eye(&s, 1, SBL_RIG_PARALLEL);
        sbt_img len = sbt_img_new(s.w, s.h, 1, 0);
        size_t bytes = sbl_stereo_scratch_size(s.w, 3);
        void *scratch = malloc(bytes);
        int ok = 1;
        d.fill = 1;
        img_fill(&s.len[0], 2.0f);  /* own N where there is no match */
        img_fill(&s.len[1], 3.0f);  /* the other eye's N where there is */
        le.length = view(&s.len[0]);
        re.length = view(&s.len[1]);
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &le, &re, view(&ref), view(&refv), 0, s.h), SBL_OK);
        CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_LEFT, &le, &re, view(&out), view(&len), 0, s.h, scratch, bytes), SBL_OK);
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) {
                int v = *sbt_at(&refv, x, y) != 0.0f;
                ok &= memcmp(sbt_at(&out, x, y), v ? sbt_at(&ref, x, y) : sbt_at(&s.col[0], x, y), 3 * sizeof(float)) == 0;
                ok &= *sbt_at(&len, x, y) == (v ? 3.0f : 2.0f);
            }
        CHECK(ok);
        img_fill(&s.len[0], 1.0f);
        img_fill(&s.len[1], 1.0f);
        free(scratch); free(len.mem);
    }
    free(mask); free(out.mem); free(ref.mem); free(refv.mem); free(traced.mem); free(dst.mem);
    st_free(&s);
}

/* ---- 6. eye swap and mirror symmetry -------------------------------------------- */

static void mirror_into(sbt_img *dst, const sbt_img *src)
{
    int x, y;
    for (y = 0; y < src->h; ++y)
        for (x = 0; x < src->w; ++x)
            memcpy(sbt_at(dst, src->w - 1 - x, y), sbt_at(src, x, y), (size_t)src->c * sizeof(float));
}

/* A noisy textured occlusion scene with fractional disparities (2.25 and ~5.63: no
   match lands on a pixel boundary, where floor() would break the tie one-sidedly) and
   per-pixel N in both eyes. */
static void symmetric_scene(stereo *s, sbt_rng *rng)
{
    int e, x, y, k;
    st_init(s, 40, 14, 3, 20.0f, 0.45f);
    st_geometry(s, 4.0f, 1.6f, 17.3, 26.6, 3, 11);
    for (e = 0; e < 2; ++e)
        for (y = 0; y < s->h; ++y)
            for (x = 0; x < s->w; ++x) {
                double u = x + 0.5 + (e ? (double)st_disp(s, *sbt_at(&s->dep[e], x, y)) : 0.0);
                for (k = 0; k < 3; ++k)
                    sbt_at(&s->col[e], x, y)[k] = (float)(0.5 + 0.3 * sin(0.7 * u + k) * cos(0.5 * y) +
                                                          0.08 * sbt_gauss(rng));
                *sbt_at(&s->len[e], x, y) = (float)(1 + (int)(sbt_uniform(rng) * 6.0));
            }
}

/* Exact pixel compare of a and b, b read mirrored (x -> W-1-x) if mirrored. */
static long diff_pixels(const sbt_img *a, const sbt_img *b, int mirrored, double *maxdiff)
{
    long n = 0;
    int x, y, k;
    *maxdiff = 0.0;
    for (y = 0; y < a->h; ++y)
        for (x = 0; x < a->w; ++x)
            for (k = 0; k < a->c; ++k) {
                float u = sbt_at(a, x, y)[k], v = sbt_at(b, mirrored ? a->w - 1 - x : x, y)[k];
                if (u != v) ++n;
                if (fabs((double)u - v) > *maxdiff) *maxdiff = fabs((double)u - v);
            }
    return n;
}

static void test_symmetry(void)
{
    stereo a, b;
    sbt_rng rng = {4242};
    sbt_img oL, oR, pL, pR;
    sbl_image none;
    int e, t;
    memset(&none, 0, sizeof none);
    symmetric_scene(&a, &rng);
    /* mirrored scene: x -> W-1-x turns the left/right rig into a right/left one, so the
       new left eye is the mirrored right eye and vice versa */
    st_init(&b, a.w, a.h, 3, a.f, a.b);
    for (t = 0; t < 2; ++t) {
        mirror_into(&b.col[t], &a.col[!t]);
        mirror_into(&b.dep[t], &a.dep[!t]);
        mirror_into(&b.disp[t], &a.disp[!t]);
        mirror_into(&b.len[t], &a.len[!t]);
    }
    oL = sbt_img_new(a.w, a.h, 3, 1); oR = sbt_img_new(a.w, a.h, 3, 2);
    pL = sbt_img_new(a.w, a.h, 3, 0); pR = sbt_img_new(a.w, a.h, 3, 3);
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
        sbl_stereo_desc d = st_desc(&a, SBL_RIG_PARALLEL);
        sbl_eye al = st_eye(&a, 0, SBL_RIG_PARALLEL), ar = st_eye(&a, 1, SBL_RIG_PARALLEL);
        sbl_eye bl = st_eye(&b, 0, SBL_RIG_PARALLEL), br = st_eye(&b, 1, SBL_RIG_PARALLEL);
        size_t bytes = sbl_stereo_scratch_size(a.w, 3);
        void *scratch = malloc(bytes);
        double dmax, mL, mR;
        long changed, nL, nR;
        tst_alloc counter;
        memset(&counter, 0, sizeof counter);
        d.estimator = (sbl_estimator)e;
        d.alloc_context = &counter;
        al.length = view(&a.len[0]); ar.length = view(&a.len[1]);
        bl.length = view(&b.len[0]); br.length = view(&b.len[1]);
        img_fill(&oL, -1.0f); img_fill(&oR, -1.0f);
        CHECK_EQ(sbl_stereo_blend_frame(&d, &al, &ar, view(&oL), view(&oR)), SBL_OK);
        CHECK(counter.allocs >= 1 && counter.allocs == counter.frees); /* SBL_MALLOC, no leak */
        CHECK(sbt_canaries_ok(&oL) && sbt_canaries_ok(&oR));
        /* the blend did something (so the comparisons below are not vacuous) */
        changed = diff_pixels(&oL, &a.col[0], 0, &dmax);
        CHECK(changed > a.w * a.h);
        /* per-eye calls, right eye first, give exactly the frame call's outputs: each
           eye reads only the unblended inputs */
        img_fill(&pL, 5.0f); img_fill(&pR, 5.0f);
        CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_RIGHT, &ar, &al, view(&pR), none, 0, a.h, scratch, bytes), SBL_OK);
        CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_LEFT, &al, &ar, view(&pL), none, 0, a.h, scratch, bytes), SBL_OK);
        CHECK_EQ(diff_pixels(&pL, &oL, 0, &dmax), 0);
        CHECK_EQ(diff_pixels(&pR, &oR, 0, &dmax), 0);
        /* mirror: blend_frame of the mirrored scene is the mirrored swap */
        CHECK_EQ(sbl_stereo_blend_frame(&d, &bl, &br, view(&pL), view(&pR)), SBL_OK);
        nL = diff_pixels(&pL, &oR, 1, &mL);
        nR = diff_pixels(&pR, &oL, 1, &mR);
        printf("  mirror, estimator %d: %ld + %ld of %d values differ, max %.3g / %.3g\n", e, nL, nR,
               2 * a.w * a.h * 3, mL, mR);
        /* exact but for float rounding: the 3x3 sums add the same values in mirrored
           order (a wrong tie-break, sign or pixel choice moves values by ~0.1 or more) */
        CHECK(mL <= 1e-6 && mR <= 1e-6);
        /* and the unmirrored comparison would fail: the scene is not symmetric itself */
        CHECK(diff_pixels(&pL, &oL, 1, &dmax) > a.w * a.h);
        free(scratch);
    }
    free(oL.mem); free(oR.mem); free(pL.mem); free(pR.mem);
    st_free(&a); st_free(&b);
}

/* ---- 7. row bands ---------------------------------------------------------------- */

static void test_row_bands(void)
{
    stereo s;
    sbt_rng rng = {99};
    sbt_img wc = sbt_img_new(40, 14, 3, 2), wn = sbt_img_new(40, 14, 1, 1);
    sbt_img bc = sbt_img_new(40, 14, 3, 2), bn = sbt_img_new(40, 14, 1, 1);
    static const int cuts[] = {0, 1, 1, 5, 6, 10, 14};
    size_t bytes;
    void *scratch;
    int e, t, i;
    symmetric_scene(&s, &rng);
    bytes = sbl_stereo_scratch_size(s.w, 3);
    scratch = malloc(bytes);
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e)
        for (t = 0; t < 2; ++t) {
            sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
            sbl_eye te = st_eye(&s, t, SBL_RIG_PARALLEL), se = st_eye(&s, !t, SBL_RIG_PARALLEL);
            d.estimator = (sbl_estimator)e;
            d.rectify = (sbl_rectify)(e % SBL_RECTIFY_COUNT);
            te.length = view(&s.len[t]);
            se.length = view(&s.len[!t]);
            img_fill(&wc, -3.0f); img_fill(&bc, -4.0f); img_fill(&wn, -3.0f); img_fill(&bn, -4.0f);
            CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&wc), view(&wn), 0, s.h, scratch, bytes), SBL_OK);
            for (i = 0; i + 1 < (int)(sizeof cuts / sizeof cuts[0]); ++i)
                CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&bc), view(&bn), cuts[i], cuts[i + 1], scratch, bytes), SBL_OK);
            /* whole buffers, padding included */
            CHECK_EQ(memcmp(wc.mem, bc.mem, img_floats(&wc) * sizeof(float)), 0);
            CHECK_EQ(memcmp(wn.mem, bn.mem, img_floats(&wn) * sizeof(float)), 0);
            if (e == 0) { /* the stage call too */
                CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&wc), view(&wn), 0, s.h), SBL_OK);
                for (i = 0; i + 1 < (int)(sizeof cuts / sizeof cuts[0]); ++i)
                    CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &te, &se, view(&bc), view(&bn), cuts[i], cuts[i + 1]), SBL_OK);
                CHECK_EQ(memcmp(wc.mem, bc.mem, img_floats(&wc) * sizeof(float)), 0);
                CHECK_EQ(memcmp(wn.mem, bn.mem, img_floats(&wn) * sizeof(float)), 0);
            }
        }
    /* a band really writes only its rows */
    {
        sbl_stereo_desc d = st_desc(&s, SBL_RIG_PARALLEL);
        sbl_eye te = st_eye(&s, 0, SBL_RIG_PARALLEL), se = st_eye(&s, 1, SBL_RIG_PARALLEL);
        img_fill(&bc, -4.0f);
        CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_LEFT, &te, &se, view(&bc), view(&bn), 6, 10, scratch, bytes), SBL_OK);
        CHECK(sbt_at(&bc, 20, 5)[0] == -4.0f && sbt_at(&bc, 20, 10)[2] == -4.0f);
        CHECK(sbt_at(&bc, 20, 6)[0] != -4.0f && sbt_at(&bc, 20, 9)[2] != -4.0f);
    }
    free(scratch);
    free(wc.mem); free(wn.mem); free(bc.mem); free(bn.mem);
    st_free(&s);
}

/* The eyes' evidence planes (sbl_eye.evidence, docs/ESTIMATORS.md 6.15) in row bands:
   the flags are formed per row from the target's plane at the pixel and the source's at
   its match, so bands must reproduce the whole image bit for bit, with either plane or
   both, on every rig that maps differently (parallel, disparity, matrices). The planes
   hold ratios on both sides of c_R = 2.118 and values that are not ratios (NaN, inf,
   negative, 0, above the cap), which read as no change: a plane of only those gives the
   blend without planes, bit for bit. And the flags do move the blend. */
static void test_evidence_bands(void)
{
    stereo s;
    sbt_rng rng = {4711};
    sbt_img ev[2], junk[2];
    sbt_img wc = sbt_img_new(40, 14, 3, 2), bc = sbt_img_new(40, 14, 3, 2), nc = sbt_img_new(40, 14, 3, 2);
    static const int cuts[] = {0, 2, 3, 7, 8, 13, 14};
    static const int rigs[] = {SBL_RIG_PARALLEL, SBL_RIG_DISPARITY, SBL_RIG_MATRICES};
    size_t bytes;
    void *scratch;
    int e, x, y, t, ri, which, i;
    long moved = 0;
    symmetric_scene(&s, &rng);
    bytes = sbl_stereo_scratch_size(s.w, 3);
    scratch = malloc(bytes);
    for (e = 0; e < 2; ++e) {
        ev[e] = sbt_img_new(s.w, s.h, 1, e);
        junk[e] = sbt_img_new(s.w, s.h, 1, 1 - e);
        for (y = 0; y < s.h; ++y)
            for (x = 0; x < s.w; ++x) {
                static const float bad[5] = {-1.0f, 0.0f, 2e6f, (float)HUGE_VAL, 0.0f};
                const double u = sbt_uniform(&rng);
                *sbt_at(&ev[e], x, y) = u < 0.1 ? bad[(x + y) % 5] : (float)(0.8 + 3.0 * sbt_uniform(&rng));
                *sbt_at(&junk[e], x, y) = (x + y) % 6 == 5 ? (float)HUGE_VAL - (float)HUGE_VAL : bad[(x + 2 * y) % 5];
            }
        *sbt_at(&ev[e], 5, 5) = (float)HUGE_VAL - (float)HUGE_VAL; /* NaN */
    }
    for (ri = 0; ri < 3; ++ri)
        for (t = 0; t < 2; ++t)
            for (which = 1; which <= 3; ++which) {
                sbl_stereo_desc d = st_desc(&s, rigs[ri]);
                sbl_eye te = st_eye(&s, t, rigs[ri]), se = st_eye(&s, !t, rigs[ri]);
                te.length = view(&s.len[t]);
                se.length = view(&s.len[!t]);
                /* without planes first */
                CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&nc), sbl_image_make(NULL, 0, 0, 1), 0, s.h, scratch, bytes), SBL_OK);
                if (which & 1) te.evidence = view(&ev[t]);
                if (which & 2) se.evidence = view(&ev[!t]);
                img_fill(&wc, -3.0f); img_fill(&bc, -4.0f);
                CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&wc), sbl_image_make(NULL, 0, 0, 1), 0, s.h, scratch, bytes), SBL_OK);
                for (i = 0; i + 1 < (int)(sizeof cuts / sizeof cuts[0]); ++i)
                    CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&bc), sbl_image_make(NULL, 0, 0, 1), cuts[i], cuts[i + 1], scratch, bytes), SBL_OK);
                CHECK_EQ(memcmp(wc.mem, bc.mem, img_floats(&wc) * sizeof(float)), 0);
                for (y = 0; y < s.h; ++y)
                    for (x = 0; x < s.w; ++x) {
                        for (i = 0; i < 3; ++i) CHECK(isfinite(sbt_at(&wc, x, y)[i]));
                        moved += sbt_at(&wc, x, y)[0] != sbt_at(&nc, x, y)[0];
                    }
                /* planes of non-ratios only: no change anywhere */
                if (which & 1) te.evidence = view(&junk[t]);
                if (which & 2) se.evidence = view(&junk[!t]);
                CHECK_EQ(sbl_stereo_blend(&d, (sbl_eye_index)t, &te, &se, view(&wc), sbl_image_make(NULL, 0, 0, 1), 0, s.h, scratch, bytes), SBL_OK);
                CHECK_EQ(memcmp(wc.mem, nc.mem, img_floats(&wc) * sizeof(float)), 0);
            }
    printf("  evidence planes in bands: 3 rigs x 2 eyes x 3 plane sets bit for bit; %ld pixels moved by the flags\n", moved);
    CHECK(moved > 3 * 2 * 3 * 20);
    for (e = 0; e < 2; ++e) { free(ev[e].mem); free(junk[e].mem); }
    free(scratch);
    free(wc.mem); free(bc.mem); free(nc.mem);
    st_free(&s);
}

/* Where the flags read the planes: each pixel's flag must come from the target's plane
   at the pixel and the source's at the pixel of its match (ESTIMATORS 6.15), not from a
   neighbour, another row or the target's own position. The source's plane is a
   checkerboard of 3 x 2 cells, 4 (a change) and 1 (none); the blend's beta with it must
   equal, pixel by pixel, either the beta of an all-flagged run (the target's plane all 4)
   or that of the run without planes, as the checkerboard at the known match says.
   Pixels where the flag moves nothing (beta equal in both runs) say nothing and are
   skipped; a pixel without a valid match is never flagged by the source. */
static void test_evidence_at_match(void)
{
    stereo s;
    sbt_rng rng = {4711};
    static const int rigs[] = {SBL_RIG_PARALLEL, SBL_RIG_DISPARITY, SBL_RIG_MATRICES};
    int t, x, y, ri, checked = 0, wrong = 0;
    size_t bytes;
    void *scratch;
    symmetric_scene(&s, &rng);
    bytes = sbl_stereo_scratch_size(s.w, 3);
    scratch = malloc(bytes);
    for (ri = 0; ri < 3; ++ri)
        for (t = 0; t < 2; ++t) {
            sbt_img all = sbt_img_new(s.w, s.h, 1, 0), chk = sbt_img_new(s.w, s.h, 1, 1);
            sbt_img oc = sbt_img_new(s.w, s.h, 3, 0), on = sbt_img_new(s.w, s.h, 1, 0);
            sbt_img b_none = sbt_img_new(s.w, s.h, 1, 0), b_all = sbt_img_new(s.w, s.h, 1, 0);
            sbt_img b_chk = sbt_img_new(s.w, s.h, 1, 0);
            sbl_stereo_desc d = st_desc(&s, rigs[ri]);
            sbl_eye te = st_eye(&s, t, rigs[ri]), se = st_eye(&s, !t, rigs[ri]);
            sbl_stereo_output o;
            for (y = 0; y < s.h; ++y)
                for (x = 0; x < s.w; ++x) {
                    *sbt_at(&all, x, y) = 4.0f;
                    *sbt_at(&chk, x, y) = ((x / 3 + y / 2) & 1) ? 4.0f : 1.0f;
                }
            te.length = view(&s.len[t]);
            se.length = view(&s.len[!t]);
            memset(&o, 0, sizeof o);
            o.color = view(&oc);
            o.length = view(&on);
            o.beta = view(&b_none);
            CHECK_EQ(sbl_stereo_filter(&d, (sbl_eye_index)t, &te, &se, &o, 0, s.h, scratch, bytes), SBL_OK);
            te.evidence = view(&all);
            o.beta = view(&b_all);
            CHECK_EQ(sbl_stereo_filter(&d, (sbl_eye_index)t, &te, &se, &o, 0, s.h, scratch, bytes), SBL_OK);
            memset(&te.evidence, 0, sizeof te.evidence);
            se.evidence = view(&chk);
            o.beta = view(&b_chk);
            CHECK_EQ(sbl_stereo_filter(&d, (sbl_eye_index)t, &te, &se, &o, 0, s.h, scratch, bytes), SBL_OK);
            for (y = 0; y < s.h; ++y)
                for (x = 0; x < s.w; ++x) {
                    const float none = *sbt_at(&b_none, x, y), flagged = *sbt_at(&b_all, x, y);
                    const float got = *sbt_at(&b_chk, x, y);
                    double bx;
                    if (none == flagged) continue; /* the flag moves nothing here */
                    if (!st_expect(&s, t, x, y, &bx)) {
                        wrong += got != none; /* no valid match: no flag from the source */
                        continue;
                    }
                    ++checked;
                    wrong += got != (*sbt_at(&chk, (int)floor(bx + 0.5), y) > 2.118f ? flagged : none);
                }
            free(all.mem); free(chk.mem); free(oc.mem); free(on.mem);
            free(b_none.mem); free(b_all.mem); free(b_chk.mem);
        }
    printf("  evidence planes read at the match: %d pixels checked on 3 rigs x 2 eyes, %d wrong\n",
           checked, wrong);
    CHECK(checked > 1000);
    CHECK_EQ(wrong, 0);
    free(scratch);
    st_free(&s);
}

/* ---- 8. errors: every code of the stereo and fill entry points -------------------- */

#define EF_MAX 24
typedef struct efix {
    stereo s;
    sbt_img out[2], outn, val, traced, small, small1;
    sbl_camera bad_cam;
    unsigned char *mask;
    int mstride;
    sbt_img *all[EF_MAX];
    float *saved[EF_MAX];
    unsigned char *mask_saved;
    int n;
} efix;

static void ef_init(efix *f)
{
    int e, i;
    st_init(&f->s, 12, 8, 3, 24.0f, 0.5f);
    st_geometry(&f->s, 3.0f, 0.0f, 0, 0, 0, 0);
    for (i = 0; i < 2; ++i) f->out[i] = sbt_img_new(12, 8, 3, 1 + i);
    f->outn = sbt_img_new(12, 8, 1, 1);
    f->val = sbt_img_new(12, 8, 1, 0);
    f->traced = sbt_img_new(12, 8, 3, 0);
    f->small = sbt_img_new(10, 8, 3, 0);
    f->small1 = sbt_img_new(12, 7, 1, 0);
    f->bad_cam = f->s.cam[0];
    memset(f->bad_cam.view_to_clip, 0, sizeof f->bad_cam.view_to_clip); /* singular */
    f->mstride = 12 + 3;
    f->mask = (unsigned char *)malloc((size_t)f->mstride * 8);
    f->mask_saved = (unsigned char *)malloc((size_t)f->mstride * 8);
    memset(f->mask, 0x5A, (size_t)f->mstride * 8);
    for (e = 0; e < 2; ++e) img_fill(&f->s.col[e], e ? 0.75f : 0.25f);
    img_fill(&f->traced, 9.0f);
    f->n = 0;
    for (e = 0; e < 2; ++e) {
        f->all[f->n++] = &f->s.col[e]; f->all[f->n++] = &f->s.dep[e]; f->all[f->n++] = &f->s.disp[e];
        f->all[f->n++] = &f->s.len[e]; f->all[f->n++] = &f->s.ids[e];
    }
    f->all[f->n++] = &f->out[0]; f->all[f->n++] = &f->out[1]; f->all[f->n++] = &f->outn;
    f->all[f->n++] = &f->val; f->all[f->n++] = &f->traced; f->all[f->n++] = &f->small;
    f->all[f->n++] = &f->small1;
    for (i = 0; i < f->n; ++i) f->saved[i] = (float *)malloc(img_floats(f->all[i]) * sizeof(float));
}

/* outputs to the sentinel, so that a write of any plausible value shows */
static void ef_sentinel(efix *f)
{
    img_fill(&f->out[0], -42.0f); img_fill(&f->out[1], -42.0f); img_fill(&f->outn, -42.0f);
    img_fill(&f->val, -42.0f);
    memset(f->mask, 0x5A, (size_t)f->mstride * 8);
}
static void ef_snapshot(efix *f)
{
    int i;
    for (i = 0; i < f->n; ++i) memcpy(f->saved[i], f->all[i]->mem, img_floats(f->all[i]) * sizeof(float));
    memcpy(f->mask_saved, f->mask, (size_t)f->mstride * 8);
}
/* 1 if no byte of any buffer changed; restores them either way */
static int ef_untouched(efix *f)
{
    int i, same = 1;
    for (i = 0; i < f->n; ++i) {
        size_t bytes = img_floats(f->all[i]) * sizeof(float);
        if (memcmp(f->saved[i], f->all[i]->mem, bytes) != 0) { same = 0; memcpy(f->all[i]->mem, f->saved[i], bytes); }
    }
    if (memcmp(f->mask_saved, f->mask, (size_t)f->mstride * 8) != 0) {
        same = 0;
        memcpy(f->mask, f->mask_saved, (size_t)f->mstride * 8);
    }
    return same;
}
static void ef_free(efix *f)
{
    int i;
    for (i = 0; i < f->n; ++i) free(f->saved[i]);
    free(f->out[0].mem); free(f->out[1].mem); free(f->outn.mem); free(f->val.mem);
    free(f->traced.mem); free(f->small.mem); free(f->small1.mem);
    free(f->mask); free(f->mask_saved);
    st_free(&f->s);
}

static void test_errors(void)
{
    efix f;
    sbl_stereo_desc d;
    sbl_eye T, S;
    sbl_image oc, oc2, on, ov, tr;
    sbl_eye_index eye;
    int y0, y1, mstride, i;
    unsigned char *mask;
    long count;
    size_t bytes;
    void *scratch;
    tst_alloc alloc;
    const float inf = (float)HUGE_VAL, nan_ = inf - inf;
    ef_init(&f);
    bytes = sbl_stereo_scratch_size(12, 3);
    scratch = malloc(bytes);
#define RESET() do { d = st_desc(&f.s, SBL_RIG_PARALLEL); T = st_eye(&f.s, 0, SBL_RIG_PARALLEL); \
    S = st_eye(&f.s, 1, SBL_RIG_PARALLEL); oc = view(&f.out[0]); oc2 = view(&f.out[1]); \
    on = view(&f.outn); ov = view(&f.val); tr = view(&f.traced); eye = SBL_EYE_LEFT; y0 = 0; y1 = 8; \
    mask = f.mask; mstride = f.mstride; count = -9; } while (0)
#define B() sbl_stereo_blend(&d, eye, &T, &S, oc, on, y0, y1, scratch, bytes)
#define R() sbl_reproject_stereo(&d, eye, &T, &S, oc, ov, y0, y1)
#define F() sbl_stereo_fill(&d, eye, &T, &S, oc, mask, mstride, y0, y1, &count)
#define BF() sbl_stereo_blend_frame(&d, &T, &S, oc, oc2)
#define M() sbl_merge_traced(oc, tr, mask, mstride, y0, y1)
#define EXPECT(call, code) do { ef_snapshot(&f); CHECK_EQ((call), (code)); CHECK(ef_untouched(&f)); } while (0)
#define EXPECT_BRF(code) do { EXPECT(B(), code); EXPECT(R(), code); EXPECT(F(), code); } while (0)

    /* the baseline calls succeed */
    RESET();
    CHECK_EQ(B(), SBL_OK); CHECK_EQ(R(), SBL_OK); CHECK_EQ(F(), SBL_OK);
    CHECK(count >= 3 * 8 && count <= 4 * 8); /* the edge columns (exact count: test_fill) */
    CHECK_EQ(BF(), SBL_OK); CHECK_EQ(M(), SBL_OK);
    ef_sentinel(&f);

    /* NULL pointers */
    RESET();
    EXPECT(sbl_stereo_blend(NULL, eye, &T, &S, oc, on, 0, 8, scratch, bytes), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend(&d, eye, NULL, &S, oc, on, 0, 8, scratch, bytes), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend(&d, eye, &T, NULL, oc, on, 0, 8, scratch, bytes), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend(&d, eye, &T, &S, oc, on, 0, 8, NULL, bytes), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_reproject_stereo(NULL, eye, &T, &S, oc, ov, 0, 8), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_reproject_stereo(&d, eye, NULL, &S, oc, ov, 0, 8), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_reproject_stereo(&d, eye, &T, NULL, oc, ov, 0, 8), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_fill(NULL, eye, &T, &S, oc, mask, mstride, 0, 8, &count), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_fill(&d, eye, NULL, &S, oc, mask, mstride, 0, 8, &count), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_fill(&d, eye, &T, NULL, oc, mask, mstride, 0, 8, &count), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_fill(&d, eye, &T, &S, oc, NULL, mstride, 0, 8, &count), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend_frame(NULL, &T, &S, oc, oc2), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend_frame(&d, NULL, &S, oc, oc2), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_stereo_blend_frame(&d, &T, NULL, oc, oc2), SBL_ERROR_NULL_POINTER);
    EXPECT(sbl_merge_traced(oc, tr, NULL, mstride, 0, 8), SBL_ERROR_NULL_POINTER);
    RESET(); T.color.data = NULL;
    EXPECT(B(), SBL_ERROR_NULL_POINTER); EXPECT(BF(), SBL_ERROR_NULL_POINTER);
    RESET(); S.color.data = NULL;
    EXPECT_BRF(SBL_ERROR_NULL_POINTER); EXPECT(BF(), SBL_ERROR_NULL_POINTER);
    RESET(); oc.data = NULL;
    EXPECT_BRF(SBL_ERROR_NULL_POINTER); EXPECT(BF(), SBL_ERROR_NULL_POINTER); EXPECT(M(), SBL_ERROR_NULL_POINTER);
    RESET(); oc2.data = NULL;
    EXPECT(BF(), SBL_ERROR_NULL_POINTER);
    RESET(); tr.data = NULL;
    EXPECT(M(), SBL_ERROR_NULL_POINTER);

    /* sizes */
    RESET(); T.color.width = 0;
    EXPECT(B(), SBL_ERROR_INVALID_SIZE); EXPECT(BF(), SBL_ERROR_INVALID_SIZE);
    RESET(); S.color.height = -1;
    EXPECT_BRF(SBL_ERROR_INVALID_SIZE);
    RESET(); T.gbuffer.depth.height = 0;
    EXPECT_BRF(SBL_ERROR_INVALID_SIZE);
    RESET(); oc.width = 0;
    EXPECT_BRF(SBL_ERROR_INVALID_SIZE); EXPECT(M(), SBL_ERROR_INVALID_SIZE);
    RESET(); oc2.height = -2;
    EXPECT(BF(), SBL_ERROR_INVALID_SIZE);
    RESET(); tr.width = -1;
    EXPECT(M(), SBL_ERROR_INVALID_SIZE);

    /* channels */
    RESET(); T.color.channels = 5;
    EXPECT(B(), SBL_ERROR_INVALID_CHANNELS);
    RESET(); S.color.channels = 0;
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); T.gbuffer.depth.channels = 2;
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); S.gbuffer.normals = view(&f.s.ids[1]);              /* normals need 3 */
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); S.gbuffer.ids = view(&f.s.col[1]);                 /* ids need 1 */
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); T.length = view(&f.traced);                        /* N needs 1 */
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); S.evidence = view(&f.traced);                      /* evidence needs 1 */
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS); EXPECT(BF(), SBL_ERROR_INVALID_CHANNELS);
    RESET(); d.rig = SBL_RIG_DISPARITY; T.disparity = view(&f.traced); S.disparity = view(&f.s.disp[1]);
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS);
    RESET(); on = view(&f.out[1]);                               /* out_length needs 1 */
    EXPECT(B(), SBL_ERROR_INVALID_CHANNELS);
    RESET(); ov = view(&f.out[1]);                               /* out_valid needs 1 */
    EXPECT(R(), SBL_ERROR_INVALID_CHANNELS);
    RESET(); oc.channels = 7;
    EXPECT_BRF(SBL_ERROR_INVALID_CHANNELS); EXPECT(M(), SBL_ERROR_INVALID_CHANNELS);
    RESET(); tr.channels = 0;
    EXPECT(M(), SBL_ERROR_INVALID_CHANNELS);

    /* strides */
    RESET(); T.color.stride = 12 * 3 - 1;
    EXPECT(B(), SBL_ERROR_INVALID_STRIDE); EXPECT(BF(), SBL_ERROR_INVALID_STRIDE);
    RESET(); S.gbuffer.depth.stride = -1;
    EXPECT_BRF(SBL_ERROR_INVALID_STRIDE);
    RESET(); oc.stride = 2;
    EXPECT_BRF(SBL_ERROR_INVALID_STRIDE); EXPECT(M(), SBL_ERROR_INVALID_STRIDE);
    RESET(); tr.stride = 35;
    EXPECT(M(), SBL_ERROR_INVALID_STRIDE);
    RESET(); mstride = 11;
    EXPECT(F(), SBL_ERROR_INVALID_STRIDE); EXPECT(M(), SBL_ERROR_INVALID_STRIDE);
    RESET(); mstride = -15;
    EXPECT(F(), SBL_ERROR_INVALID_STRIDE); EXPECT(M(), SBL_ERROR_INVALID_STRIDE);

    /* sizes that must agree */
    RESET(); S.color = view(&f.small);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH); EXPECT(BF(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); S.gbuffer.depth.width = 11;                         /* stride stays valid */
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);
    RESET(); S.gbuffer.ids = view(&f.small1);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);
    RESET(); S.length = view(&f.small1);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);
    RESET(); T.length = view(&f.small1);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);
    RESET(); T.evidence = view(&f.small1);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH); EXPECT(BF(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); d.rig = SBL_RIG_DISPARITY; T.disparity = view(&f.small1); S.disparity = view(&f.s.disp[1]);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);
    RESET(); oc = view(&f.small);
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH); EXPECT(BF(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); oc2 = view(&f.small);
    EXPECT(BF(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); on.height = 7;
    EXPECT(B(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); ov.width = 11;
    EXPECT(R(), SBL_ERROR_SIZE_MISMATCH);
    RESET(); tr = view(&f.small);
    EXPECT(M(), SBL_ERROR_SIZE_MISMATCH);
    /* the target's depth narrower than its colour: the colour-less stage calls must
       notice it as well as the blend (the view stays inside its memory) */
    RESET(); T.gbuffer.depth.width = 11;
    EXPECT_BRF(SBL_ERROR_SIZE_MISMATCH);

    /* channel counts that must agree */
    RESET(); S.color.channels = 1;
    EXPECT_BRF(SBL_ERROR_CHANNEL_MISMATCH); EXPECT(BF(), SBL_ERROR_CHANNEL_MISMATCH);
    RESET(); oc.channels = 1;
    EXPECT_BRF(SBL_ERROR_CHANNEL_MISMATCH); EXPECT(M(), SBL_ERROR_CHANNEL_MISMATCH);
    EXPECT(BF(), SBL_ERROR_CHANNEL_MISMATCH);
    RESET(); oc2.channels = 2;
    EXPECT(BF(), SBL_ERROR_CHANNEL_MISMATCH);                   /* right eye bad: left not written */

    /* overlaps */
    RESET(); oc = S.color;                                       /* out = the source colour */
    EXPECT_BRF(SBL_ERROR_OVERLAP);
    RESET(); oc = T.color;                                       /* in place */
    EXPECT_BRF(SBL_ERROR_OVERLAP); EXPECT(BF(), SBL_ERROR_OVERLAP);
    RESET(); oc2 = T.color;
    EXPECT(BF(), SBL_ERROR_OVERLAP);
    RESET(); oc2 = oc;
    EXPECT(BF(), SBL_ERROR_OVERLAP);
    RESET(); on = T.gbuffer.depth;
    EXPECT(B(), SBL_ERROR_OVERLAP);
    RESET(); S.length = view(&f.s.len[1]); on = S.length;
    EXPECT(B(), SBL_ERROR_OVERLAP);
    RESET(); S.evidence = view(&f.s.len[1]); on = S.evidence;   /* the source's evidence */
    EXPECT(B(), SBL_ERROR_OVERLAP);
    RESET(); T.evidence = view(&f.out[1]); T.evidence.channels = 1; /* in the right output */
    EXPECT(BF(), SBL_ERROR_OVERLAP);
    RESET(); d.rig = SBL_RIG_DISPARITY; T = st_eye(&f.s, 0, SBL_RIG_DISPARITY); S = st_eye(&f.s, 1, SBL_RIG_DISPARITY);
    on = S.disparity; ov = T.disparity;
    EXPECT(B(), SBL_ERROR_OVERLAP); EXPECT(R(), SBL_ERROR_OVERLAP);
    RESET(); ov = S.gbuffer.depth;
    EXPECT(R(), SBL_ERROR_OVERLAP);
    RESET(); on.data = oc.data + 5; on.stride = 12;             /* two outputs */
    EXPECT(B(), SBL_ERROR_OVERLAP);
    RESET(); ov.data = oc.data + 40; ov.stride = 12;
    EXPECT(R(), SBL_ERROR_OVERLAP);
    RESET(); mask = (unsigned char *)(oc.data + 3);              /* mask over the colour output */
    EXPECT(F(), SBL_ERROR_OVERLAP);
    RESET(); tr = oc;
    EXPECT(M(), SBL_ERROR_OVERLAP);
    /* the mask is an output of the fill and an input of the merge: it may overlap no
       image the call reads or writes either */
    RESET(); mask = (unsigned char *)T.gbuffer.depth.data; mstride = 12 * 4;
    EXPECT(F(), SBL_ERROR_OVERLAP);
    RESET(); mask = (unsigned char *)S.color.data;
    EXPECT(F(), SBL_ERROR_OVERLAP);
    RESET(); memset(f.out[0].mem, 0xFF, 8); mask = (unsigned char *)oc.data; mstride = 12 * 12;
    ef_snapshot(&f);
    CHECK_EQ(M(), SBL_ERROR_OVERLAP);
    CHECK(ef_untouched(&f));
    ef_sentinel(&f);

    /* rows */
    RESET(); y0 = -1;
    EXPECT_BRF(SBL_ERROR_INVALID_ROWS); EXPECT(M(), SBL_ERROR_INVALID_ROWS);
    RESET(); y1 = 9;
    EXPECT_BRF(SBL_ERROR_INVALID_ROWS); EXPECT(M(), SBL_ERROR_INVALID_ROWS);
    RESET(); y0 = 3; y1 = 2;
    EXPECT_BRF(SBL_ERROR_INVALID_ROWS); EXPECT(M(), SBL_ERROR_INVALID_ROWS);
    /* an empty range is valid and writes nothing */
    RESET(); y0 = 5; y1 = 5;
    EXPECT_BRF(SBL_OK); EXPECT(M(), SBL_OK);
    CHECK_EQ(count, 0);

    /* parameters */
    RESET(); d.focal_px = 0.0f;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM); EXPECT(BF(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.focal_px = -24.0f;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.focal_px = inf;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.baseline = nan_;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM); EXPECT(BF(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.baseline = 0.0f;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.rig = SBL_RIG_COUNT;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.rig = (sbl_stereo_rig)-1;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); eye = (sbl_eye_index)2;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); eye = (sbl_eye_index)-1;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.constant_beta = 2.0f;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM); EXPECT(BF(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.constant_beta = -0.5f;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.estimator = SBL_ESTIMATOR_COUNT;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.rectify = (sbl_rectify)3;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.weight_mode = (sbl_weight_mode)2;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.clip_gamma = -1.0f;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.bias_threshold = inf;
    EXPECT(B(), SBL_ERROR_INVALID_PARAM);
    RESET(); d.reproject.depth_tolerance = -1.0f;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.reproject.back_check_pixels = nan_;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.reproject.normal_threshold = 1.5f;
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    RESET(); d.rig = SBL_RIG_MATRICES; T = st_eye(&f.s, 0, SBL_RIG_MATRICES); S = st_eye(&f.s, 1, SBL_RIG_MATRICES);
    S.camera = &f.bad_cam;                                       /* singular projection */
    EXPECT_BRF(SBL_ERROR_INVALID_PARAM);
    /* focal length and baseline belong to the parallel rig only */
    RESET(); d.rig = SBL_RIG_DISPARITY; T = st_eye(&f.s, 0, SBL_RIG_DISPARITY); S = st_eye(&f.s, 1, SBL_RIG_DISPARITY);
    d.focal_px = 0.0f; d.baseline = nan_;
    CHECK_EQ(B(), SBL_OK); CHECK_EQ(R(), SBL_OK); CHECK_EQ(F(), SBL_OK);
    ef_sentinel(&f);

    /* missing inputs */
    RESET(); S.gbuffer.depth.data = NULL;                        /* parallel rig, no depth */
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT); EXPECT(BF(), SBL_ERROR_MISSING_INPUT);
    RESET(); T.gbuffer.depth.data = NULL;
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT); EXPECT(BF(), SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_DISPARITY;                          /* no disparity images */
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_DISPARITY; T.disparity = view(&f.s.disp[0]);
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_MATRICES; T = st_eye(&f.s, 0, SBL_RIG_MATRICES); S = st_eye(&f.s, 1, SBL_RIG_MATRICES);
    S.camera = NULL;
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT); EXPECT(BF(), SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_MATRICES; T = st_eye(&f.s, 0, SBL_RIG_MATRICES); S = st_eye(&f.s, 1, SBL_RIG_MATRICES);
    T.camera = NULL;
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_MATRICES; T = st_eye(&f.s, 0, SBL_RIG_MATRICES); S = st_eye(&f.s, 1, SBL_RIG_MATRICES);
    S.gbuffer.depth.data = NULL;
    EXPECT_BRF(SBL_ERROR_MISSING_INPUT);
    RESET(); d.rig = SBL_RIG_MATRICES; T = st_eye(&f.s, 0, SBL_RIG_MATRICES); S = st_eye(&f.s, 1, SBL_RIG_MATRICES);
    CHECK_EQ(B(), SBL_OK); CHECK_EQ(R(), SBL_OK); CHECK_EQ(F(), SBL_OK);
    ef_sentinel(&f);

    /* scratch */
    RESET(); bytes -= 1;
    EXPECT(B(), SBL_ERROR_SCRATCH_TOO_SMALL);
    bytes = 0;
    EXPECT(B(), SBL_ERROR_SCRATCH_TOO_SMALL);
    bytes = sbl_stereo_scratch_size(12, 3);
    CHECK(bytes >= (size_t)3 * 12 * 4 * sizeof(float));
    CHECK_EQ(sbl_stereo_scratch_size(0, 3), 0);
    CHECK_EQ(sbl_stereo_scratch_size(12, 5), 0);
    CHECK_EQ(sbl_stereo_scratch_size(12, 0), 0);

    /* out of memory in the convenience call */
    RESET(); memset(&alloc, 0, sizeof alloc); alloc.fail = 1; d.alloc_context = &alloc;
    EXPECT(BF(), SBL_ERROR_OUT_OF_MEMORY);
    alloc.fail = 0;
    CHECK_EQ(BF(), SBL_OK);
    CHECK(alloc.allocs == 1 && alloc.frees == 1);
    ef_sentinel(&f);

    /* defaults */
    {
        sbl_stereo_desc z, r;
        memset(&z, 0, sizeof z);
        r = sbl_stereo_defaults(&z);
        CHECK_NEAR(r.constant_beta, 0.5, 0);
        CHECK_NEAR(r.clip_gamma, 1.25, 0);
        CHECK_NEAR(r.bias_threshold, 3.0, 0);
        CHECK_NEAR(r.reproject.back_check_pixels, 1.0, 0);
        CHECK_NEAR(r.reproject.depth_tolerance, 0.05, 1e-9);
        CHECK_EQ(r.rig, SBL_RIG_PARALLEL);
        CHECK_EQ(r.estimator, SBL_ESTIMATOR_POOLED);
        z.constant_beta = 0.25f;
        CHECK_NEAR(sbl_stereo_defaults(&z).constant_beta, 0.25, 0);
        CHECK_NEAR(sbl_stereo_defaults(NULL).constant_beta, 0.5, 0);
    }
    for (i = 0; i < f.n; ++i) CHECK(sbt_canaries_ok(f.all[i]));
#undef EXPECT_BRF
#undef EXPECT
#undef M
#undef BF
#undef F
#undef R
#undef B
#undef RESET
    free(scratch);
    ef_free(&f);
}

int main(void)
{
    test_round_trip();
    test_occlusion();
    test_beta_half();
    test_highlights();
    test_fill();
    test_symmetry();
    test_row_bands();
    test_evidence_bands();
    test_evidence_at_match();
    test_errors();
    return sbt_finish("test_stereo");
}
