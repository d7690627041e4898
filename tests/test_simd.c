/* Every SIMD path against the scalar path (issue: speed). This translation unit is
   built with the SIMD flags under test; tests/simd_scalar_tu.c with -DSBL_NO_SIMD.
   Random sizes (1x1, odd widths, thin strips), random strides whose padding holds
   canaries, random estimators / rectification / weight modes / motion.

   Determinism policy checked here: both paths run the same float operations in the
   same order per pixel, and every pixel takes the lane kernel or the reference path
   by a rule that does not depend on the vector width, so they agree bit for bit
   (measured with gcc 12 on SSE2, AVX2, AVX-512) unless the compiler contracts a*b+c
   into a fused multiply-add on one path and not the other (clang does with -mfma:
   measured up to 1e-6 relative). The tolerance allows that: 1e-5 relative on colour,
   1e-4 relative on N, 1e-5 on the weight; where the compiler does not contract (gcc in
   ISO C mode; probed at run time) the comparison is exact. */
#include "../stereoblend.h"
#include "sbl_test.h"

/* the path under test is the configuration's implementation object (tests/sbl_impl.c) */
const char *tst_simd_name(void);
#define SBL_SIMD_NAME tst_simd_name()
const char *scalar_simd_name(void);
sbl_result scalar_temporal_filter(const sbl_temporal_desc *d, const sbl_frame *f,
                                  const sbl_history *h, const sbl_temporal_output *o);
sbl_result scalar_stereo_blend(const sbl_stereo_desc *d, const sbl_eye *l, const sbl_eye *r,
                               sbl_image ol, sbl_image orr);

#define view sbt_view

static void fill(sbt_img *im, sbt_rng *r, double lo, double hi)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k) sbt_at(im, x, y)[k] = (float)(lo + (hi - lo) * sbt_uniform(r));
}

static double max_rel(const sbt_img *a, const sbt_img *b, double floor_abs)
{
    double m = 0;
    int x, y, k;
    for (y = 0; y < a->h; ++y)
        for (x = 0; x < a->w; ++x)
            for (k = 0; k < a->c; ++k) {
                double u = sbt_at(a, x, y)[k], v = sbt_at(b, x, y)[k];
                double d = fabs(u - v) / (fabs(u) + fabs(v) + floor_abs);
                if (!(d <= m)) m = d; /* NaN counts as a mismatch */
            }
    return m;
}

/* 1 if the compiler contracts a * b + c into a fused multiply-add here (clang -mfma
   does, gcc in ISO C mode does not); both translation units are built alike */
static int compiler_contracts(void)
{
    volatile float a = 1.0f + 1.0f / 4096.0f, c = -(1.0f + 1.0f / 2048.0f);
    float b = a;
    return a * b + c != 0.0f;
}

/* The temporal filter on this build's SIMD path and on the scalar path into fresh
   outputs (colour, N and, with_plane, the evidence plane): equal bit for bit, within the
   stated tolerance where the compiler contracts; what / iter name the case. */
static void temporal_both_paths(const sbl_temporal_desc *d, const sbl_frame *f, const sbl_history *hi,
                                int with_plane, int pad, double scale, int contracts, const char *what,
                                int iter)
{
    const int w = f->color.width, h = f->color.height, c = f->color.channels;
    sbt_img oc[2], on[2], oe[2];
    sbl_temporal_output o[2];
    int i, ok;
    double ec, en, ee = 0.0;
    for (i = 0; i < 2; ++i) {
        oc[i] = sbt_img_new(w, h, c, pad + 2);
        on[i] = sbt_img_new(w, h, 1, 1);
        oe[i] = sbt_img_new(w, h, 1, 2);
        memset(&o[i], 0, sizeof o[i]);
        o[i].color = view(&oc[i]);
        o[i].length = view(&on[i]);
        if (with_plane) o[i].evidence = view(&oe[i]);
    }
    CHECK_EQ(sbl_temporal_filter_frame(d, f, hi, &o[0]), SBL_OK);
    CHECK_EQ(scalar_temporal_filter(d, f, hi, &o[1]), SBL_OK);
    ec = max_rel(&oc[0], &oc[1], 1e-6 * scale);
    en = max_rel(&on[0], &on[1], 1e-6);
    if (with_plane) ee = max_rel(&oe[0], &oe[1], 1e-6);
    ok = ec <= 1e-5 && en <= 1e-4 && ee <= 1e-5;
    if (!contracts) ok = ok && ec == 0.0 && en == 0.0 && ee == 0.0;
    if (!ok) printf("  %s iter %d (%dx%dx%d): colour %.3g N %.3g evidence %.3g\n", what, iter, w, h, c, ec, en, ee);
    CHECK(ok);
    for (i = 0; i < 2; ++i) {
        CHECK(sbt_canaries_ok(&oc[i]) && sbt_canaries_ok(&on[i]) && sbt_canaries_ok(&oe[i]));
        free(oc[i].mem); free(on[i].mem); free(oe[i].mem);
    }
}

/* The stereo blend on both paths, as temporal_both_paths */
static void stereo_both_paths(const sbl_stereo_desc *sd, const sbl_eye *l, const sbl_eye *r, int pad,
                              double scale, int contracts)
{
    const int w = l->color.width, h = l->color.height, c = l->color.channels;
    sbt_img sl[2], sr[2];
    int i;
    for (i = 0; i < 2; ++i) { sl[i] = sbt_img_new(w, h, c, pad); sr[i] = sbt_img_new(w, h, c, 1); }
    CHECK_EQ(sbl_stereo_blend_frame(sd, l, r, view(&sl[0]), view(&sr[0])), SBL_OK);
    CHECK_EQ(scalar_stereo_blend(sd, l, r, view(&sl[1]), view(&sr[1])), SBL_OK);
    CHECK(max_rel(&sl[0], &sl[1], 1e-6 * scale) <= (contracts ? 1e-5 : 0.0));
    CHECK(max_rel(&sr[0], &sr[1], 1e-6 * scale) <= (contracts ? 1e-5 : 0.0));
    for (i = 0; i < 2; ++i) {
        CHECK(sbt_canaries_ok(&sl[i]) && sbt_canaries_ok(&sr[i]));
        free(sl[i].mem); free(sr[i].mem);
    }
}

/* The camera source with the camera at rest (identity pose): the row gather's rest tiles */
static void camera_at_rest(sbl_camera *cam, int w, int h)
{
    sbl_intrinsics kin;
    float pose[16];
    int q;
    for (q = 0; q < 16; ++q) pose[q] = q % 5 == 0 ? 1.0f : 0.0f;
    kin.fx = kin.fy = (float)(0.8 * w + 3); kin.cx = 0.5f * w; kin.cy = 0.5f * h;
    CHECK_EQ(sbl_camera_from_pinhole(cam, &kin, pose, SBL_AXES_OPENCV, 0, w, h), SBL_OK);
}

int main(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {2024};
    int iter, worst_iter = -1;
    double worst_c = 0, worst_n = 0, worst_a = 0;
    printf("SIMD path under test: %s (against %s), %s\n", SBL_SIMD_NAME, scalar_simd_name(),
           contracts ? "a*b+c contracted: within tolerance" : "bit for bit");
    CHECK(strcmp(scalar_simd_name(), "scalar") == 0);
    for (iter = 0; iter < 300; ++iter) {
        int w = 1 + (int)(sbt_uniform(&rng) * (iter % 5 == 0 ? 4 : 70));
        int h = 1 + (int)(sbt_uniform(&rng) * (iter % 7 == 0 ? 3 : 40));
        int c = 1 + (int)(sbt_uniform(&rng) * 4);
        int pad = (int)(sbt_uniform(&rng) * 5);
        sbt_img cur = sbt_img_new(w, h, c, pad), hist = sbt_img_new(w, h, c, pad + 1);
        sbt_img len = sbt_img_new(w, h, 1, pad), depth = sbt_img_new(w, h, 1, 1), mv = sbt_img_new(w, h, 2, pad);
        sbt_img oc[2], on[2], oa[2];
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o[2];
        int i, x, y;
        double scale = pow(10.0, -3.0 + 6.0 * sbt_uniform(&rng));
        for (i = 0; i < 2; ++i) {
            oc[i] = sbt_img_new(w, h, c, pad + 2);
            on[i] = sbt_img_new(w, h, 1, 1);
            oa[i] = sbt_img_new(w, h, 1, 2);
        }
        fill(&cur, &rng, 0.0, scale);
        fill(&hist, &rng, 0.0, scale);
        fill(&len, &rng, 0.5, 40.0);
        fill(&depth, &rng, 4.0, 4.2);
        fill(&mv, &rng, -1.5, 1.5);
        /* a few non-finite and out-of-range values on some iterations: the rows they
           touch go to the reference path on both sides */
        if (iter % 4 == 3) {
            sbt_at(&cur, w / 2, h / 2)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
            sbt_at(&hist, 0, h - 1)[c - 1] = 1e20f;
        }
        /* isolated values below the lane range (a history fading to black, a denormal):
           only the pixels whose 3x3 window holds one leave the lane kernel, on every
           build alike */
        if (iter % 4 == 1) {
            int t;
            for (t = 0; t < 1 + w * h / 40; ++t) {
                int tx = (int)(sbt_uniform(&rng) * w), ty = (int)(sbt_uniform(&rng) * h);
                int tc = (int)(sbt_uniform(&rng) * c);
                float v = t % 3 == 2 ? 1e-39f : (float)(1e-14 * scale);
                if (t & 1) sbt_at(&hist, tx, ty)[tc] = v;
                else sbt_at(&cur, tx, ty)[tc] = v;
            }
        }
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                if (sbt_uniform(&rng) < 0.05) *sbt_at(&depth, x, y) = 9.0f; /* some disocclusions */
        memset(&d, 0, sizeof d);
        d.estimator = (sbl_estimator)(iter % SBL_ESTIMATOR_COUNT);
        d.rectify = (sbl_rectify)((iter / 4) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((iter / 12) % SBL_WEIGHT_MODE_COUNT);
        d.alpha_min = iter % 3 == 0 ? 0.05f : 0.0f;
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&depth);
        for (i = 0; i < 2; ++i) {
            memset(&o[i], 0, sizeof o[i]);
            o[i].color = view(&oc[i]);
            o[i].length = view(&on[i]);
            o[i].alpha = view(&oa[i]);
        }
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o[0]), SBL_OK);
        CHECK_EQ(scalar_temporal_filter(&d, &f, &hi, &o[1]), SBL_OK);
        {
            double ec = max_rel(&oc[0], &oc[1], 1e-6 * scale), en = max_rel(&on[0], &on[1], 1e-6);
            double ea = max_rel(&oa[0], &oa[1], 1.0);
            int ok = ec <= 1e-5 && en <= 1e-4 && ea <= 1e-5;
            /* without contraction of a*b+c (gcc in ISO C mode) the paths agree bit for bit */
            if (!contracts) ok = ok && ec == 0.0 && en == 0.0 && ea == 0.0;
            if (!ok) printf("  iter %d (%dx%dx%d, est %d, rect %d, mode %d): colour %.3g N %.3g alpha %.3g\n",
                            iter, w, h, c, d.estimator, d.rectify, d.weight_mode, ec, en, ea);
            CHECK(ok);
            if (ec > worst_c) { worst_c = ec; worst_iter = iter; }
            if (en > worst_n) worst_n = en;
            if (ea > worst_a) worst_a = ea;
        }
        for (i = 0; i < 2; ++i)
            CHECK(sbt_canaries_ok(&oc[i]) && sbt_canaries_ok(&on[i]) && sbt_canaries_ok(&oa[i]));

        /* the stereo blend through the same kernel: left = cur, right = hist */
        {
            sbl_stereo_desc sd;
            sbl_eye l, r;
            memset(&sd, 0, sizeof sd);
            sd.focal_px = 10.0f;
            sd.baseline = 0.5f + (float)sbt_uniform(&rng);
            sd.estimator = d.estimator;
            sd.rectify = d.rectify;
            sd.weight_mode = d.weight_mode;
            memset(&l, 0, sizeof l);
            memset(&r, 0, sizeof r);
            l.color = view(&cur); l.gbuffer.depth = view(&depth); l.length = view(&len);
            r.color = view(&hist); r.gbuffer.depth = view(&depth);
            if (iter & 1) r.length = view(&len); /* N_X > 1: the lean's q is not divided */
            stereo_both_paths(&sd, &l, &r, pad, scale, contracts);
        }
        for (i = 0; i < 2; ++i) { free(oc[i].mem); free(on[i].mem); free(oa[i].mem); }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(mv.mem);
    }
    printf("  worst differences over 300 random cases: colour %.3g (case %d), N %.3g, alpha %.3g (relative)\n",
           worst_c, worst_iter, worst_n, worst_a);

    /* the pooled estimator with the evidence plane carried over frames (history in,
       output plane out): the same on both paths, the plane included */
    for (iter = 0; iter < 120; ++iter) {
        int w = 1 + (int)(sbt_uniform(&rng) * (iter % 5 == 0 ? 6 : 70));
        int h = 1 + (int)(sbt_uniform(&rng) * (iter % 7 == 0 ? 3 : 30));
        int c = 1 + (int)(sbt_uniform(&rng) * 4);
        int pad = (int)(sbt_uniform(&rng) * 3);
        sbt_img cur = sbt_img_new(w, h, c, pad), hist = sbt_img_new(w, h, c, pad + 1);
        sbt_img len = sbt_img_new(w, h, 1, pad), depth = sbt_img_new(w, h, 1, 1), mv = sbt_img_new(w, h, 2, pad);
        sbt_img ev = sbt_img_new(w, h, 1, pad + 1);
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        int x, y;
        double scale = pow(10.0, -3.0 + 6.0 * sbt_uniform(&rng));
        fill(&cur, &rng, 0.0, scale);
        fill(&hist, &rng, 0.0, scale);
        /* a shifted region: bias the blocks see */
        for (y = 0; y < h; ++y)
            for (x = 0; x < w / 2; ++x) sbt_at(&hist, x, y)[0] += (float)(0.3 * scale);
        fill(&len, &rng, 0.5, 40.0);
        fill(&depth, &rng, 4.0, 4.2);
        fill(&mv, &rng, -1.5, 1.5);
        fill(&ev, &rng, 0.2, 8.0);
        if (iter % 3 == 1) { /* values that are no ratio: read as 1 */
            *sbt_at(&ev, w / 2, h / 2) = (float)HUGE_VAL - (float)HUGE_VAL;
            *sbt_at(&ev, 0, 0) = -2.0f;
            *sbt_at(&ev, w - 1, h - 1) = 1e30f;
        }
        if (iter % 4 == 3) sbt_at(&cur, w / 2, h / 2)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                if (sbt_uniform(&rng) < 0.05) *sbt_at(&depth, x, y) = 9.0f;
        memset(&d, 0, sizeof d);
        d.rectify = (sbl_rectify)((iter / 2) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((iter / 6) % SBL_WEIGHT_MODE_COUNT);
        /* a stereo blend follows (docs/ESTIMATORS.md 4.7): the bias counts 1 + c times */
        if (iter % 4 == 1) d.stereo_shared_bias = iter % 8 == 1 ? 1.0f : 0.4f;
        if (iter % 8 == 5) d.estimator = SBL_ESTIMATOR_HISTORY_AWARE; /* its bias term too */
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&depth);
        if (iter % 5 != 4) hi.evidence = view(&ev); /* and without it: the plane still written */
        if (iter % 3 == 2) {
            /* the camera source with a camera at rest: the row gather's rest tiles */
            static sbl_camera cam;
            camera_at_rest(&cam, w, h);
            d.source = SBL_TEMPORAL_CAMERA;
            f.camera = &cam;
            hi.camera = &cam;
        }
        temporal_both_paths(&d, &f, &hi, 1, pad, scale, contracts, "evidence", iter);
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(mv.mem); free(ev.mem);
    }
    /* normals and ids in every G-buffer (the row gather's normal / id tests in lanes, the
       rest tiles' at the pixel): temporal (motion vectors; the camera source at rest) and
       the stereo blend, on both paths. Normals around the threshold's cone, "no normal"
       pixels, NaN normals and ids, a moving object with its own id. */
    for (iter = 0; iter < 120; ++iter) {
        int w = 1 + (int)(sbt_uniform(&rng) * (iter % 5 == 0 ? 6 : 70));
        int h = 1 + (int)(sbt_uniform(&rng) * (iter % 7 == 0 ? 3 : 30));
        int c = 1 + (int)(sbt_uniform(&rng) * 4);
        int pad = (int)(sbt_uniform(&rng) * 3);
        sbt_img cur = sbt_img_new(w, h, c, pad), hist = sbt_img_new(w, h, c, pad + 1);
        sbt_img len = sbt_img_new(w, h, 1, pad), depth = sbt_img_new(w, h, 1, 1), mv = sbt_img_new(w, h, 2, pad);
        sbt_img nrm = sbt_img_new(w, h, 3, pad), pnrm = sbt_img_new(w, h, 3, 1);
        sbt_img ids = sbt_img_new(w, h, 1, pad), pids = sbt_img_new(w, h, 1, 0);
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        int x, y, k;
        const int at_rest = iter % 3 == 2;
        double scale = pow(10.0, -3.0 + 6.0 * sbt_uniform(&rng));
        fill(&cur, &rng, 0.0, scale);
        fill(&hist, &rng, 0.0, scale);
        fill(&len, &rng, 0.5, 40.0);
        fill(&depth, &rng, 4.0, 4.2);
        fill(&mv, &rng, -1.5, 1.5);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const double u = sbt_uniform(&rng);
                const int obj = x > w / 3 && x < w / 2 + 3;
                float *n = sbt_at(&nrm, x, y), *pn = sbt_at(&pnrm, x, y);
                for (k = 0; k < 3; ++k) {
                    n[k] = (float)((k == 2 ? 1.0 : obj && k == 0 ? 0.6 : 0.0) + 0.35 * (sbt_uniform(&rng) - 0.5));
                    pn[k] = at_rest && u < 0.8 ? n[k]
                                               : (float)((k == 2 ? 1.0 : 0.0) + 0.35 * (sbt_uniform(&rng) - 0.5));
                }
                if (u < 0.03) pn[0] = pn[1] = pn[2] = 0.0f;
                else if (u < 0.04) n[0] = n[1] = n[2] = 0.0f;
                else if (u < 0.05) pn[1] = (float)HUGE_VAL - (float)HUGE_VAL;
                else if (u < 0.055) n[2] = (float)HUGE_VAL;
                *sbt_at(&ids, x, y) = obj ? 3.0f : 1.0f;
                *sbt_at(&pids, x, y) = u > 0.97 ? 3.0f : u > 0.96 ? (float)HUGE_VAL - (float)HUGE_VAL : 1.0f;
                if (at_rest) sbt_at(&mv, x, y)[0] = sbt_at(&mv, x, y)[1] = 0.0f;
                if (sbt_uniform(&rng) < 0.05) *sbt_at(&depth, x, y) = 9.0f;
            }
        memset(&d, 0, sizeof d);
        d.rectify = (sbl_rectify)((iter / 2) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((iter / 6) % SBL_WEIGHT_MODE_COUNT);
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        f.gbuffer.normals = view(&nrm);
        f.gbuffer.ids = view(&ids);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&depth);
        hi.gbuffer.normals = view(&pnrm);
        hi.gbuffer.ids = view(&pids);
        if (at_rest && iter % 2) { /* the camera source, at rest */
            static sbl_camera cam;
            camera_at_rest(&cam, w, h);
            d.source = SBL_TEMPORAL_CAMERA;
            f.camera = &cam;
            hi.camera = &cam;
        }
        temporal_both_paths(&d, &f, &hi, 0, pad, scale, contracts, "normals / ids", iter);
        {   /* the stereo blend: left = cur, right = hist, each with its normals and ids */
            sbl_stereo_desc sd;
            sbl_eye l, r;
            memset(&sd, 0, sizeof sd);
            sd.focal_px = 10.0f;
            sd.baseline = 0.5f + (float)sbt_uniform(&rng);
            sd.rectify = d.rectify;
            sd.weight_mode = d.weight_mode;
            memset(&l, 0, sizeof l);
            memset(&r, 0, sizeof r);
            l.color = view(&cur); l.gbuffer.depth = view(&depth); l.length = view(&len);
            l.gbuffer.normals = view(&nrm); l.gbuffer.ids = view(&ids);
            r.color = view(&hist); r.gbuffer.depth = view(&depth);
            r.gbuffer.normals = view(&pnrm); r.gbuffer.ids = view(&pids);
            stereo_both_paths(&sd, &l, &r, pad, scale, contracts);
        }
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(mv.mem);
        free(nrm.mem); free(pnrm.mem); free(ids.mem); free(pids.mem);
    }
    /* the evidence plane laid out as N (the common setup: the ring rows carry it, gathered
       in the colour's plan by the row gather): moving and resting stretches (rest tiles),
       no-geometry stretches (void tiles), a nearer object that moved (disocclusions, the
       3x3 fallback), values that are no ratio; the same on both paths, the plane included */
    for (iter = 0; iter < 80; ++iter) {
        int w = 1 + (int)(sbt_uniform(&rng) * (iter % 5 == 0 ? 6 : 200));
        int h = 1 + (int)(sbt_uniform(&rng) * (iter % 7 == 0 ? 3 : 20));
        int c = 1 + (int)(sbt_uniform(&rng) * 4);
        int pad = (int)(sbt_uniform(&rng) * 3);
        int rx = (int)(sbt_uniform(&rng) * w), rw = iter % 3 == 0 ? w : (int)(sbt_uniform(&rng) * 150);
        int vx = (int)(sbt_uniform(&rng) * w), vw = iter % 4 == 1 ? (int)(sbt_uniform(&rng) * 150) : 0;
        int ax = (int)(sbt_uniform(&rng) * w), aw = 3 + (int)(sbt_uniform(&rng) * w / 2), shift = 1 + iter % 9;
        sbt_img cur = sbt_img_new(w, h, c, pad), hist = sbt_img_new(w, h, c, pad + 1);
        sbt_img len = sbt_img_new(w, h, 1, pad), depth = sbt_img_new(w, h, 1, 1), pdepth = sbt_img_new(w, h, 1, 1);
        sbt_img mv = sbt_img_new(w, h, 2, pad), ev = sbt_img_new(w, h, 1, pad);
        sbl_temporal_desc d;
        sbl_frame f;
        sbl_history hi;
        int x, y;
        double scale = pow(10.0, -3.0 + 6.0 * sbt_uniform(&rng));
        fill(&cur, &rng, 0.0, scale);
        fill(&hist, &rng, 0.0, scale);
        fill(&len, &rng, 0.5, 40.0);
        fill(&mv, &rng, -1.5, 1.5);
        fill(&ev, &rng, 0.2, 8.0);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                *sbt_at(&depth, x, y) = x >= ax && x < ax + aw ? 2.0f : (float)(4.0 + 0.01 * x);
                *sbt_at(&pdepth, x, y) = x >= ax + shift && x < ax + shift + aw ? 2.0f : (float)(4.0 + 0.01 * x);
                if (x >= rx && x < rx + rw) sbt_at(&mv, x, y)[0] = sbt_at(&mv, x, y)[1] = 0.0f;
                if (x >= vx && x < vx + vw) *sbt_at(&depth, x, y) = 0.0f;
                if (x < w / 2) sbt_at(&hist, x, y)[0] += (float)(0.3 * scale);
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&ev, x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                if (sbt_uniform(&rng) < 0.02) *sbt_at(&ev, x, y) = iter % 2 ? -1.0f : 1e30f;
                if (sbt_uniform(&rng) < 0.01) *sbt_at(&len, x, y) = 0.0f;
            }
        if (iter % 4 == 3) sbt_at(&hist, w / 2, h / 2)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
        memset(&d, 0, sizeof d);
        d.rectify = (sbl_rectify)((iter / 2) % SBL_RECTIFY_COUNT);
        d.reproject.no_fallback = iter % 5 == 2;
        memset(&f, 0, sizeof f);
        memset(&hi, 0, sizeof hi);
        f.color = view(&cur);
        f.gbuffer.depth = view(&depth);
        f.gbuffer.motion = view(&mv);
        hi.color = view(&hist);
        hi.length = view(&len);
        hi.gbuffer.depth = view(&pdepth);
        hi.evidence = view(&ev);
        temporal_both_paths(&d, &f, &hi, 1, pad, scale, contracts, "evidence laid out as N", iter);
        free(cur.mem); free(hist.mem); free(len.mem); free(depth.mem); free(pdepth.mem); free(mv.mem);
        free(ev.mem);
    }
    return sbt_finish("test_simd");
}
