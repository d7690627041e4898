/* Core tests: conventions, temporal reprojection, moments, weights, blend, the fused
   temporal filter and its convergence, and the error codes of every public call. */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"
#include <float.h>
#include <math.h>
#include <string.h>

static sbl_image view(const sbt_img *im)
{
    sbl_image v;
    memset(&v, 0, sizeof v);
    v.data = im->mem; v.width = im->w; v.height = im->h; v.channels = im->c; v.stride = im->stride;
    return v;
}

/* ---- weights and sample counts ------------------------------------------------- */

static void test_weights(void)
{
    int n;
    for (n = 1; n <= 256; n *= 2) {
        float v = 0.37f;
        /* static unbiased: var_X = var_Y / N -> a* = 1/(N+1) */
        CHECK_NEAR(sbl_optimal_weight(0.0f, v / (float)n, v), 1.0 / (n + 1), 1e-6);
        /* Eq. 5 as derived: that alpha turns N into N + 1 */
        CHECK_NEAR(sbl_blend_sample_count(1.0f / (float)(n + 1), (float)n, 1.0f), n + 1.0, 1e-3 * n);
    }
    CHECK_NEAR(sbl_optimal_weight(0.0f, 1.0f, 1.0f), 0.5, 1e-7);      /* two equal eyes */
    CHECK_NEAR(sbl_optimal_weight(1e30f, 1.0f, 1.0f), 1.0, 1e-6);     /* huge bias      */
    CHECK_NEAR(sbl_optimal_weight(0.0f, (float)HUGE_VAL, 1.0f), 1.0, 0); /* no history  */
    CHECK_NEAR(sbl_optimal_weight(0.0f, 0.0f, 0.0f), 0.5, 0);
    CHECK_NEAR(sbl_blend_sample_count(1.0f, 10.0f, 1.0f), 1.0, 1e-6); /* reset keeps Y only */
    CHECK_NEAR(sbl_blend_sample_count(0.5f, 1.0f, 1.0f), 2.0, 1e-6);
}

/* ---- depth conventions ---------------------------------------------------------- */

static void test_depth(void)
{
    const float n = 0.1f, f = 100.0f;
    float z;
    for (z = 0.1f; z < 100.0f; z *= 1.7f) {
        /* encode with the textbook projections, decode with the library */
        double gl = ((f + n) / (f - n) - 2.0 * f * n / ((f - n) * z)); /* [-1,1] */
        double zo = (f / (f - n)) * (1.0 - n / z);                      /* [0,1]  */
        double rev = n * (f - z) / (z * (f - n));                        /* reversed */
        double inf = n / z;
        CHECK_NEAR(sbl_depth_to_linear((float)gl, SBL_DEPTH_NDC_GL, n, f), z, 2e-3 * z * z);
        CHECK_NEAR(sbl_depth_to_linear((float)zo, SBL_DEPTH_NDC_ZERO_ONE, n, f), z, 2e-3 * z * z);
        CHECK_NEAR(sbl_depth_to_linear((float)rev, SBL_DEPTH_REVERSED, n, f), z, 1e-4 * z);
        CHECK_NEAR(sbl_depth_to_linear((float)inf, SBL_DEPTH_REVERSED_INFINITE, n, f), z, 1e-5 * z);
    }
    CHECK(sbl_depth_to_linear(0.0f, SBL_DEPTH_REVERSED_INFINITE, n, f) > 1e30f);
    {
        sbt_img a = sbt_img_new(5, 3, 1, 2);
        int x, y;
        for (y = 0; y < 3; ++y)
            for (x = 0; x < 5; ++x) *sbt_at(&a, x, y) = 0.5f;
        CHECK_EQ(sbl_depth_image_to_linear(view(&a), view(&a), SBL_DEPTH_REVERSED_INFINITE, 0.2f, 0.0f), SBL_OK);
        CHECK_NEAR(*sbt_at(&a, 4, 2), 0.4, 1e-6);
        CHECK(sbt_canaries_ok(&a));
        CHECK_EQ(sbl_depth_image_to_linear(view(&a), view(&a), SBL_DEPTH_NDC_GL, 1.0f, 0.5f), SBL_ERROR_INVALID_PARAM);
        CHECK_EQ(sbl_depth_image_to_linear(view(&a), view(&a), (sbl_depth_encoding)99, 1.0f, 2.0f), SBL_ERROR_INVALID_PARAM);
        free(a.mem);
    }
}

/* ---- reprojection --------------------------------------------------------------- */

typedef struct scene2 {
    int w, h, c;
    sbt_img cur, prev, mv, depth, pdepth, hlen, outc, outn;
} scene2;

static void scene2_init(scene2 *s, int w, int h, int c)
{
    int x, y, k;
    s->w = w; s->h = h; s->c = c;
    s->cur = sbt_img_new(w, h, c, 3);
    s->prev = sbt_img_new(w, h, c, 1);
    s->mv = sbt_img_new(w, h, 2, 2);
    s->depth = sbt_img_new(w, h, 1, 1);
    s->pdepth = sbt_img_new(w, h, 1, 0);
    s->hlen = sbt_img_new(w, h, 1, 2);
    s->outc = sbt_img_new(w, h, c, 2);
    s->outn = sbt_img_new(w, h, 1, 1);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            for (k = 0; k < c; ++k) {
                *(sbt_at(&s->prev, x, y) + k) = (float)(x * 10 + y * 100 + k) * 0.01f;
                *(sbt_at(&s->cur, x, y) + k) = 0.5f;
            }
            *sbt_at(&s->depth, x, y) = 5.0f;
            *sbt_at(&s->pdepth, x, y) = 5.0f;
            *sbt_at(&s->hlen, x, y) = (float)(1 + (x + y) % 7);
        }
}

static void scene2_free(scene2 *s)
{
    free(s->cur.mem); free(s->prev.mem); free(s->mv.mem); free(s->depth.mem);
    free(s->pdepth.mem); free(s->hlen.mem); free(s->outc.mem); free(s->outn.mem);
}

static void scene2_views(scene2 *s, sbl_frame *f, sbl_history *h)
{
    memset(f, 0, sizeof *f);
    memset(h, 0, sizeof *h);
    f->color = view(&s->cur);
    f->gbuffer.depth = view(&s->depth);
    f->gbuffer.motion = view(&s->mv);
    h->color = view(&s->prev);
    h->length = view(&s->hlen);
    h->gbuffer.depth = view(&s->pdepth);
}

static void set_motion(scene2 *s, float mx, float my)
{
    int x, y;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) { sbt_at(&s->mv, x, y)[0] = mx; sbt_at(&s->mv, x, y)[1] = my; }
}

static void test_reproject_integer_and_bilinear(void)
{
    scene2 s;
    sbl_frame f;
    sbl_history h;
    sbl_reproject_desc rd;
    int x, y, k, exact = 1, inside = 1, outside = 1;
    memset(&rd, 0, sizeof rd);
    scene2_init(&s, 13, 9, 3);
    scene2_views(&s, &f, &h);

    /* integer motion: x* is the previous frame shifted exactly, N follows */
    set_motion(&s, 3.0f, -2.0f);
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 9), SBL_OK);
    for (y = 0; y < 9; ++y)
        for (x = 0; x < 13; ++x) {
            int px = x + 3, py = y - 2;
            float n = *sbt_at(&s.outn, x, y);
            if (px >= 0 && px < 13 && py >= 0 && py < 9) {
                for (k = 0; k < 3; ++k) exact &= sbt_at(&s.outc, x, y)[k] == sbt_at(&s.prev, px, py)[k];
                inside &= n == *sbt_at(&s.hlen, px, py);
            } else {
                /* the 3x3 fallback may still find an in-image neighbour at the border */
                if (px < -1 || px > 13 || py < -1 || py > 9) outside &= n == 0.0f;
            }
        }
    CHECK(exact);
    CHECK(inside);
    CHECK(outside);
    CHECK(sbt_canaries_ok(&s.outc) && sbt_canaries_ok(&s.outn));

    /* the same motion in the other conventions */
    {
        float u = 3.0f / 13.0f, v = -2.0f / 9.0f;
        sbl_reproject_desc r2 = rd;
        sbt_img ref = sbt_img_new(13, 9, 3, 2);
        memcpy(ref.mem, s.outc.mem, sizeof(float) * (size_t)ref.stride * 9);
        r2.motion.units = SBL_MOTION_UV;
        set_motion(&s, u, v);
        CHECK_EQ(sbl_reproject_temporal(&r2, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 9), SBL_OK);
        CHECK_NEAR(sbt_at(&s.outc, 4, 5)[1], sbt_at(&ref, 4, 5)[1], 1e-5);
        r2.motion.units = SBL_MOTION_NDC;
        r2.motion.y_up = 1;
        r2.motion.forward = 1; /* p_cur - p_prev with +y up: (-3, -2) in pixel units */
        set_motion(&s, -2.0f * 3.0f / 13.0f, -2.0f * 2.0f / 9.0f);
        CHECK_EQ(sbl_reproject_temporal(&r2, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 9), SBL_OK);
        CHECK_NEAR(sbt_at(&s.outc, 4, 5)[1], sbt_at(&ref, 4, 5)[1], 1e-5);
        free(ref.mem);
    }

    /* sub-pixel motion: bilinear reference */
    {
        float mx = 1.25f, my = 0.75f;
        int ok = 1;
        set_motion(&s, mx, my);
        CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 9), SBL_OK);
        for (y = 0; y < 7; ++y)
            for (x = 0; x < 11; ++x) {
                double bx = x + 0.5 + mx - 0.5, by = y + 0.5 + my - 0.5;
                int x0 = (int)floor(bx), y0 = (int)floor(by);
                double fx = bx - x0, fy = by - y0;
                for (k = 0; k < 3; ++k) {
                    double r = (1 - fx) * (1 - fy) * sbt_at(&s.prev, x0, y0)[k] +
                               fx * (1 - fy) * sbt_at(&s.prev, x0 + 1, y0)[k] +
                               (1 - fx) * fy * sbt_at(&s.prev, x0, y0 + 1)[k] +
                               fx * fy * sbt_at(&s.prev, x0 + 1, y0 + 1)[k];
                    ok &= fabs(r - sbt_at(&s.outc, x, y)[k]) < 1e-5;
                }
            }
        CHECK(ok);
    }
    scene2_free(&s);
}

static void test_reproject_tap_tests(void)
{
    scene2 s;
    sbl_frame f;
    sbl_history h;
    sbl_reproject_desc rd;
    sbt_img nrm_c, nrm_p, id_c, id_p;
    int x, y, k;
    memset(&rd, 0, sizeof rd);
    scene2_init(&s, 8, 8, 1);
    scene2_views(&s, &f, &h);
    set_motion(&s, 0.5f, 0.5f); /* target (2,2) -> taps (2,2) (3,2) (2,3) (3,3), w 1/4 each */

    /* depth: tap (3,2) belongs to another surface */
    *sbt_at(&s.pdepth, 3, 2) = 9.0f;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    {
        float e = (*sbt_at(&s.prev, 2, 2) + *sbt_at(&s.prev, 2, 3) + *sbt_at(&s.prev, 3, 3)) / 3.0f;
        CHECK_NEAR(*sbt_at(&s.outc, 2, 2), e, 1e-5);
    }
    *sbt_at(&s.pdepth, 3, 2) = 5.0f;

    /* normals: tap (2,3) faces away */
    nrm_c = sbt_img_new(8, 8, 3, 1);
    nrm_p = sbt_img_new(8, 8, 3, 0);
    for (y = 0; y < 8; ++y)
        for (x = 0; x < 8; ++x) { sbt_at(&nrm_c, x, y)[2] = 1.0f; sbt_at(&nrm_p, x, y)[2] = 1.0f; }
    sbt_at(&nrm_p, 2, 3)[2] = 0.0f;
    sbt_at(&nrm_p, 2, 3)[0] = 1.0f;
    f.gbuffer.normals = view(&nrm_c);
    h.gbuffer.normals = view(&nrm_p);
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    {
        float e = (*sbt_at(&s.prev, 2, 2) + *sbt_at(&s.prev, 3, 2) + *sbt_at(&s.prev, 3, 3)) / 3.0f;
        CHECK_NEAR(*sbt_at(&s.outc, 2, 2), e, 1e-5);
    }
    /* normal test off: all four taps again */
    rd.normal_threshold = -1.0f;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    {
        float e = (*sbt_at(&s.prev, 2, 2) + *sbt_at(&s.prev, 2, 3) + *sbt_at(&s.prev, 3, 2) + *sbt_at(&s.prev, 3, 3)) / 4.0f;
        CHECK_NEAR(*sbt_at(&s.outc, 2, 2), e, 1e-5);
    }
    rd.normal_threshold = 0.0f;
    f.gbuffer.normals.data = NULL;
    h.gbuffer.normals.data = NULL;

    /* ids: tap (3,3) is another object */
    id_c = sbt_img_new(8, 8, 1, 0);
    id_p = sbt_img_new(8, 8, 1, 2);
    for (y = 0; y < 8; ++y)
        for (x = 0; x < 8; ++x) { *sbt_at(&id_c, x, y) = 4.0f; *sbt_at(&id_p, x, y) = 4.0f; }
    *sbt_at(&id_p, 3, 3) = 5.0f;
    f.gbuffer.ids = view(&id_c);
    h.gbuffer.ids = view(&id_p);
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    {
        float e = (*sbt_at(&s.prev, 2, 2) + *sbt_at(&s.prev, 2, 3) + *sbt_at(&s.prev, 3, 2)) / 3.0f;
        CHECK_NEAR(*sbt_at(&s.outc, 2, 2), e, 1e-5);
    }

    /* all four taps fail but one 3x3 neighbour matches: fallback takes it */
    /* (the source position is (3.0, 3.0): the fallback searches around pixel (3, 3)) */
    for (y = 0; y < 8; ++y)
        for (x = 0; x < 8; ++x) *sbt_at(&id_p, x, y) = 7.0f;
    *sbt_at(&id_p, 4, 2) = 4.0f;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    CHECK_NEAR(*sbt_at(&s.outc, 2, 2), *sbt_at(&s.prev, 4, 2), 1e-6);
    CHECK_NEAR(*sbt_at(&s.outn, 2, 2), *sbt_at(&s.hlen, 4, 2), 1e-6);
    (void)k;
    /* ... unless the fallback is off: nothing valid, N = 0 (reset) */
    rd.no_fallback = 1;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &f, &h, view(&s.outc), view(&s.outn), 0, 8), SBL_OK);
    CHECK_EQ(*sbt_at(&s.outn, 2, 2), 0);
    rd.no_fallback = 0;

    /* disocclusion through the fused filter: N resets to 1, output = new sample */
    {
        sbl_temporal_desc td;
        sbl_temporal_output out;
        sbt_img alpha = sbt_img_new(8, 8, 1, 1);
        memset(&td, 0, sizeof td);
        memset(&out, 0, sizeof out);
        out.color = view(&s.outc);
        out.length = view(&s.outn);
        out.alpha = view(&alpha);
        for (y = 0; y < 8; ++y)
            for (x = 0; x < 8; ++x) *sbt_at(&id_p, x, y) = 9.0f; /* nothing matches */
        *sbt_at(&s.cur, 5, 5) = 0.75f;
        CHECK_EQ(sbl_temporal_filter_frame(&td, &f, &h, &out), SBL_OK);
        CHECK_EQ(*sbt_at(&s.outn, 5, 5), 1);
        CHECK_NEAR(*sbt_at(&s.outc, 5, 5), 0.75, 0);
        CHECK_NEAR(*sbt_at(&alpha, 5, 5), 1.0, 0);
        CHECK(sbt_canaries_ok(&s.outc) && sbt_canaries_ok(&s.outn) && sbt_canaries_ok(&alpha));
        free(alpha.mem);
    }
    free(nrm_c.mem); free(nrm_p.mem); free(id_c.mem); free(id_p.mem);
    scene2_free(&s);
}

/* Camera reprojection of a static plane under a sideways camera move must agree with
   the exact motion vectors of the same move. */
static void identity(float *m) { int i; for (i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f; }

static void test_reproject_camera(void)
{
    const int w = 32, h = 24;
    const float f = 20.0f, z = 4.0f, shift = 0.3f; /* camera moves +0.3 along x */
    sbl_camera cur_cam, prev_cam;
    scene2 s;
    sbl_frame fr;
    sbl_history hi;
    sbl_reproject_desc rd;
    sbt_img viac = sbt_img_new(w, h, 3, 0), vian = sbt_img_new(w, h, 1, 0);
    int x, y, ok = 1, valid = 0;
    memset(&rd, 0, sizeof rd);
    scene2_init(&s, w, h, 3);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) { *sbt_at(&s.depth, x, y) = z; *sbt_at(&s.pdepth, x, y) = z; }
    /* projection: fx = fy = f pixels, principal point at the centre */
    memset(cur_cam.view_to_clip, 0, sizeof cur_cam.view_to_clip);
    cur_cam.view_to_clip[0] = 2.0f * f / w;
    cur_cam.view_to_clip[5] = 2.0f * f / h;
    cur_cam.view_to_clip[10] = -1.0f;
    cur_cam.view_to_clip[11] = -0.2f;
    cur_cam.view_to_clip[14] = -1.0f;
    prev_cam = cur_cam;
    identity(prev_cam.world_to_view);
    identity(cur_cam.world_to_view);
    cur_cam.world_to_view[3] = -shift; /* camera at x = +shift */
    scene2_views(&s, &fr, &hi);
    fr.camera = &cur_cam;
    hi.camera = &prev_cam;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&s.outc), view(&s.outn), 0, h), SBL_OK);
    /* the point seen now at u was at u + f * shift / z before */
    set_motion(&s, f * shift / z, 0.0f);
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_MOTION, &fr, &hi, view(&viac), view(&vian), 0, h), SBL_OK);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            /* same taps; only the rounding of the source position differs */
            ok &= fabsf(*sbt_at(&s.outn, x, y) - *sbt_at(&vian, x, y)) < 1e-4f;
            if (*sbt_at(&vian, x, y) > 0) {
                ++valid;
                ok &= fabs(sbt_at(&s.outc, x, y)[0] - sbt_at(&viac, x, y)[0]) < 1e-4;
            }
        }
    CHECK(ok);
    CHECK(valid > w * h / 2);
    /* camera mode needs the cameras */
    fr.camera = NULL;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&s.outc), view(&s.outn), 0, h), SBL_ERROR_MISSING_INPUT);
    fr.camera = &cur_cam;
    prev_cam.view_to_clip[0] = 0.0f; prev_cam.view_to_clip[1] = 0.0f; /* singular */
    cur_cam.view_to_clip[0] = 0.0f;
    CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&s.outc), view(&s.outn), 0, h), SBL_ERROR_INVALID_PARAM);
    free(viac.mem); free(vian.mem);
    scene2_free(&s);
}

/* ---- moments -------------------------------------------------------------------- */

static void test_moments(void)
{
    const int w = 7, h = 5;
    sbt_img src = sbt_img_new(w, h, 3, 1), mean = sbt_img_new(w, h, 3, 2), var = sbt_img_new(w, h, 3, 0);
    sbt_rng rng = {77};
    int x, y, k, ok = 1, nonneg = 1;
    /* bright HDR values with small noise: m2 - m1^2 in float would lose everything */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < 3; ++k)
                sbt_at(&src, x, y)[k] = (float)((k == 0 ? 1e6 : (k == 1 ? 3e4 : 1.0)) + sbt_gauss(&rng));
    CHECK_EQ(sbl_moments_3x3(view(&src), view(&mean), view(&var), 0, h), SBL_OK);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < 3; ++k) {
                double s = 0, v = 0, m;
                int n = 0, i, j;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = x - 1; i <= x + 1; ++i)
                        if (i >= 0 && j >= 0 && i < w && j < h) { s += sbt_at(&src, i, j)[k]; ++n; }
                m = s / n;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = x - 1; i <= x + 1; ++i)
                        if (i >= 0 && j >= 0 && i < w && j < h) v += (sbt_at(&src, i, j)[k] - m) * (sbt_at(&src, i, j)[k] - m);
                v /= n;
                ok &= fabs(sbt_at(&var, x, y)[k] - v) <= 1e-4 * v + 1e-6;
                ok &= fabs(sbt_at(&mean, x, y)[k] - m) <= 1e-6 * fabs(m) + 1e-6;
                nonneg &= sbt_at(&var, x, y)[k] >= 0.0f;
            }
    CHECK(ok);
    CHECK(nonneg);
    CHECK(sbt_canaries_ok(&mean) && sbt_canaries_ok(&var));
    /* constant image: zero variance exactly */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < 3; ++k) sbt_at(&src, x, y)[k] = 3.3e7f;
    CHECK_EQ(sbl_moments_3x3(view(&src), view(&mean), view(&var), 0, h), SBL_OK);
    CHECK_EQ(sbt_at(&var, 3, 2)[1], 0);
    {   /* errors */
        sbl_image none;
        memset(&none, 0, sizeof none);
        CHECK_EQ(sbl_moments_3x3(view(&src), none, none, 0, h), SBL_ERROR_NULL_POINTER);
        CHECK_EQ(sbl_moments_3x3(view(&src), view(&src), view(&var), 0, h), SBL_ERROR_OVERLAP);
        CHECK_EQ(sbl_moments_3x3(view(&src), view(&mean), view(&var), 2, 1), SBL_ERROR_INVALID_ROWS);
        CHECK_EQ(sbl_moments_3x3(view(&src), view(&mean), view(&var), 0, h + 1), SBL_ERROR_INVALID_ROWS);
    }
    free(src.mem); free(mean.mem); free(var.mem);
}

/* ---- the fused temporal filter --------------------------------------------------- */

typedef struct tf {
    int w, h, c;
    sbt_img cur, depth, mv, hist[2], len[2], alpha;
    int ping;
} tf;

static void tf_init(tf *t, int w, int h, int c)
{
    int i;
    t->w = w; t->h = h; t->c = c; t->ping = 0;
    t->cur = sbt_img_new(w, h, c, 1);
    t->depth = sbt_img_new(w, h, 1, 0);
    t->mv = sbt_img_new(w, h, 2, 0);
    for (i = 0; i < 2; ++i) { t->hist[i] = sbt_img_new(w, h, c, 2); t->len[i] = sbt_img_new(w, h, 1, 1); }
    t->alpha = sbt_img_new(w, h, 1, 0);
    for (i = 0; i < w * h; ++i) t->depth.mem[i] = 3.0f;
}
static void tf_free(tf *t)
{
    int i;
    free(t->cur.mem); free(t->depth.mem); free(t->mv.mem); free(t->alpha.mem);
    for (i = 0; i < 2; ++i) { free(t->hist[i].mem); free(t->len[i].mem); }
}
/* one frame: history = hist[ping] (NULL on the first), output into hist[!ping] */
static sbl_result tf_step(tf *t, const sbl_temporal_desc *d, int first)
{
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    sbl_result r;
    memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
    f.color = view(&t->cur);
    f.gbuffer.depth = view(&t->depth);
    f.gbuffer.motion = view(&t->mv);
    h.color = view(&t->hist[t->ping]);
    h.length = view(&t->len[t->ping]);
    h.gbuffer.depth = view(&t->depth);
    o.color = view(&t->hist[!t->ping]);
    o.length = view(&t->len[!t->ping]);
    o.alpha = view(&t->alpha);
    r = sbl_temporal_filter_frame(d, &f, first ? NULL : &h, &o);
    if (r == SBL_OK) t->ping = !t->ping;
    return r;
}

static float truth(int x, int y, int k) /* a textured static scene */
{
    return 0.5f + 0.3f * (float)sin(x * 0.7 + k) * (float)cos(y * 0.45) + ((x / 4 + y / 4) % 2 ? 0.2f : 0.0f);
}

static void tf_noisy(tf *t, sbt_rng *rng, double sigma)
{
    int x, y, k;
    for (y = 0; y < t->h; ++y)
        for (x = 0; x < t->w; ++x)
            for (k = 0; k < t->c; ++k)
                sbt_at(&t->cur, x, y)[k] = truth(x, y, k) + (float)(sigma * sbt_gauss(rng));
}

static double tf_rmse(const sbt_img *im)
{
    double s = 0;
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k) {
                double d = sbt_at(im, x, y)[k] - truth(x, y, k);
                s += d * d;
            }
    return sqrt(s / (im->w * im->h * im->c));
}

static double mean_of(const sbt_img *im)
{
    double s = 0;
    int x, y;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x) s += *sbt_at(im, x, y);
    return s / (im->w * im->h);
}

static void test_filter_properties(void)
{
    tf t;
    sbt_rng rng = {5};
    sbl_temporal_desc d;
    int e, r, m, x, y, k;
    tf_init(&t, 17, 11, 3);
    /* x* == y leaves y unchanged, whatever the estimator and rectification */
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e)
        for (r = 0; r < SBL_RECTIFY_COUNT; ++r)
            for (m = 0; m < SBL_WEIGHT_MODE_COUNT; ++m) {
                int same = 1, inrange = 1;
                memset(&d, 0, sizeof d);
                d.estimator = (sbl_estimator)e;
                d.rectify = (sbl_rectify)r;
                d.weight_mode = (sbl_weight_mode)m;
                tf_noisy(&t, &rng, 0.2);
                for (y = 0; y < t.h; ++y)
                    for (x = 0; x < t.w; ++x) {
                        for (k = 0; k < 3; ++k) sbt_at(&t.hist[t.ping], x, y)[k] = sbt_at(&t.cur, x, y)[k];
                        *sbt_at(&t.len[t.ping], x, y) = 5.0f;
                    }
                CHECK_EQ(tf_step(&t, &d, 0), SBL_OK);
                for (y = 0; y < t.h; ++y)
                    for (x = 0; x < t.w; ++x) {
                        for (k = 0; k < 3; ++k) same &= fabsf(sbt_at(&t.hist[t.ping], x, y)[k] - sbt_at(&t.cur, x, y)[k]) <= 1e-6f;
                        inrange &= *sbt_at(&t.alpha, x, y) >= 0.0f && *sbt_at(&t.alpha, x, y) <= 1.0f;
                    }
                CHECK(same);
                CHECK(inrange);
                /* and on unrelated history alpha stays within [0, 1] too */
                tf_noisy(&t, &rng, 0.5);
                CHECK_EQ(tf_step(&t, &d, 0), SBL_OK);
                inrange = 1;
                for (y = 0; y < t.h; ++y)
                    for (x = 0; x < t.w; ++x)
                        inrange &= *sbt_at(&t.alpha, x, y) >= 0.0f && *sbt_at(&t.alpha, x, y) <= 1.0f;
                CHECK(inrange);
                CHECK(sbt_canaries_ok(&t.hist[0]) && sbt_canaries_ok(&t.hist[1]) && sbt_canaries_ok(&t.len[0]));
            }
    /* progressive: alpha = 1/(N+1) exactly and N -> N+1 */
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    tf_noisy(&t, &rng, 0.2);
    for (y = 0; y < t.h; ++y)
        for (x = 0; x < t.w; ++x) *sbt_at(&t.len[t.ping], x, y) = 7.0f;
    CHECK_EQ(tf_step(&t, &d, 0), SBL_OK);
    CHECK_NEAR(*sbt_at(&t.alpha, 3, 4), 1.0 / 8.0, 1e-7);
    CHECK_NEAR(*sbt_at(&t.len[t.ping], 3, 4), 8.0, 1e-4);
    /* the cap */
    d.max_history = 4.0f;
    CHECK_EQ(tf_step(&t, &d, 0), SBL_OK);
    CHECK_NEAR(*sbt_at(&t.len[t.ping], 3, 4), 4.0, 1e-5);
    /* first frame: output = input, N = 1 */
    CHECK_EQ(tf_step(&t, &d, 1), SBL_OK);
    CHECK_EQ(memcmp(sbt_at(&t.hist[t.ping], 2, 2), sbt_at(&t.cur, 2, 2), 3 * sizeof(float)), 0);
    CHECK_NEAR(*sbt_at(&t.len[t.ping], 2, 2), 1.0, 0);
    tf_free(&t);
}

/* Static noisy scene: the history-aware estimator converges like 1/(N+1); the paper's
   estimator floors near alpha 0.1 (recorded here so a change to it is noticed). */
static void test_convergence(void)
{
    const int frames = 32;
    const double sigma = 0.2;
    tf t;
    sbl_temporal_desc d;
    sbt_rng rng = {99};
    double rmse_mean32, rmse_ha, rmse_paper, rmse_prog, alpha_paper, alpha_ha;
    int i, e;
    tf_init(&t, 64, 48, 3);
    /* the reference: the plain mean of 32 samples, measured on the same scene */
    {
        sbt_img acc = sbt_img_new(64, 48, 3, 0);
        int n;
        for (i = 0; i < frames; ++i) {
            tf_noisy(&t, &rng, sigma);
            for (n = 0; n < 64 * 48 * 3; ++n) acc.mem[n] += t.cur.mem[(n / 192) * t.cur.stride + n % 192] / frames;
        }
        rmse_mean32 = tf_rmse(&acc);
        free(acc.mem);
    }
    rmse_ha = rmse_paper = rmse_prog = alpha_paper = alpha_ha = 0;
    for (e = 0; e < 3; ++e) {
        memset(&d, 0, sizeof d);
        d.estimator = e == 0 ? SBL_ESTIMATOR_HISTORY_AWARE : (e == 1 ? SBL_ESTIMATOR_PAPER : SBL_ESTIMATOR_PROGRESSIVE);
        for (i = 0; i < frames; ++i) {
            tf_noisy(&t, &rng, sigma);
            CHECK_EQ(tf_step(&t, &d, i == 0), SBL_OK);
        }
        if (e == 0) { rmse_ha = tf_rmse(&t.hist[t.ping]); alpha_ha = mean_of(&t.alpha); }
        if (e == 1) { rmse_paper = tf_rmse(&t.hist[t.ping]); alpha_paper = mean_of(&t.alpha); }
        if (e == 2) rmse_prog = tf_rmse(&t.hist[t.ping]);
    }
    printf("  convergence after %d frames: RMSE mean-of-32 %.5f, progressive %.5f, history-aware %.5f "
           "(alpha %.4f), paper %.5f (alpha %.4f)\n",
           frames, rmse_mean32, rmse_prog, rmse_ha, alpha_ha, rmse_paper, alpha_paper);
    CHECK(rmse_ha <= 1.10 * rmse_mean32);
    CHECK(rmse_prog <= 1.10 * rmse_mean32);
    CHECK(alpha_ha < 0.06);                           /* 1/33 = 0.03 */
    CHECK(alpha_paper > 0.07 && alpha_paper < 0.2);   /* the paper's floor */
    CHECK(rmse_paper > 1.3 * rmse_mean32);
    tf_free(&t);
}

/* The history-aware estimator still reacts where the history is wrong: a step change
   of the scene with zero motion (a light switched on) must be followed within a few
   frames, unlike progressive averaging. */
static void test_reacts_to_change(void)
{
    tf t;
    sbl_temporal_desc d;
    sbt_rng rng = {3};
    double err_ha = 0, err_prog = 0;
    int i, e, x, y, k;
    tf_init(&t, 32, 32, 1);
    for (e = 0; e < 2; ++e) {
        memset(&d, 0, sizeof d);
        d.estimator = e == 0 ? SBL_ESTIMATOR_HISTORY_AWARE : SBL_ESTIMATOR_PROGRESSIVE;
        for (i = 0; i < 24; ++i) {
            double offset = i >= 16 ? 1.0 : 0.0;
            tf_noisy(&t, &rng, 0.1);
            for (y = 0; y < 32; ++y)
                for (x = 0; x < 32; ++x)
                    for (k = 0; k < 1; ++k) sbt_at(&t.cur, x, y)[k] += (float)offset;
            CHECK_EQ(tf_step(&t, &d, i == 0), SBL_OK);
        }
        {
            double s = 0;
            for (y = 0; y < 32; ++y)
                for (x = 0; x < 32; ++x) {
                    double dd = sbt_at(&t.hist[t.ping], x, y)[0] - (truth(x, y, 0) + 1.0);
                    s += dd * dd;
                }
            if (e == 0) err_ha = sqrt(s / 1024); else err_prog = sqrt(s / 1024);
        }
    }
    printf("  step change: RMSE 8 frames after, history-aware %.4f, progressive %.4f\n", err_ha, err_prog);
    CHECK(err_ha < 0.1);
    CHECK(err_prog > 0.3);
    tf_free(&t);
}

/* ---- errors: every code from the temporal entry points --------------------------- */

static void test_errors(void)
{
    tf t;
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    sbt_img small = sbt_img_new(5, 5, 3, 0);
    char scratch[64];
    int i;
    tf_init(&t, 9, 7, 3);
    memset(&d, 0, sizeof d);
#define RESET() do { memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o); \
    f.color = view(&t.cur); f.gbuffer.depth = view(&t.depth); f.gbuffer.motion = view(&t.mv); \
    h.color = view(&t.hist[0]); h.length = view(&t.len[0]); h.gbuffer.depth = view(&t.depth); \
    o.color = view(&t.hist[1]); o.length = view(&t.len[1]); memset(&d, 0, sizeof d); } while (0)
    RESET();
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_OK);
    CHECK_EQ(sbl_temporal_filter_frame(NULL, &f, &h, &o), SBL_ERROR_NULL_POINTER);
    CHECK_EQ(sbl_temporal_filter_frame(&d, NULL, &h, &o), SBL_ERROR_NULL_POINTER);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, NULL), SBL_ERROR_NULL_POINTER);
    RESET(); f.color.data = NULL;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_NULL_POINTER);
    RESET(); f.color.width = 0;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_SIZE);
    RESET(); f.color.height = -3;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_SIZE);
    RESET(); f.color.channels = 5;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_CHANNELS);
    RESET(); f.color.channels = 0;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_CHANNELS);
    RESET(); f.gbuffer.depth.channels = 2;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_CHANNELS);
    RESET(); f.color.stride = 9 * 3 - 1;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_STRIDE);
    RESET(); o.color.stride = -4;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_STRIDE);
    RESET(); h.color = view(&small);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_SIZE_MISMATCH);
    RESET(); f.gbuffer.motion.width = 8;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_SIZE_MISMATCH);
    RESET(); h.color.channels = 2; h.color.stride = t.hist[0].stride;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_CHANNEL_MISMATCH);
    RESET(); o.color.channels = 1; o.color.stride = t.hist[1].stride;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_CHANNEL_MISMATCH);
    RESET(); o.color = view(&t.hist[0]);                   /* in-place history */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
    RESET(); o.color = view(&t.cur);                       /* in-place frame */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
    RESET(); o.length = view(&t.depth);                    /* output over the G-buffer */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
    RESET(); o.alpha = view(&t.len[1]);                    /* two outputs */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
    RESET(); h.evidence = view(&t.alpha); o.alpha = view(&t.alpha); /* over a plane it reads */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
    {   /* the tail plane: 2 channels, the frame's size, disjoint from the other planes */
        sbt_img tl0 = sbt_img_new(9, 7, 2, 1), tl1 = sbt_img_new(9, 7, 2, 0), tls = sbt_img_new(5, 5, 2, 0);
        RESET(); h.tail = view(&tl0); o.tail = view(&tl1);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_OK);
        CHECK(sbt_canaries_ok(&tl0));
        RESET(); h.tail = view(&tl0); o.tail = view(&tl0);   /* in place */
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
        RESET(); o.tail = view(&tl1); o.alpha = sbl_image_make(tl1.mem, 9, 7, 1); /* two outputs */
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_OVERLAP);
        RESET(); o.tail = view(&t.alpha);                      /* 1 channel */
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_CHANNELS);
        RESET(); h.tail = view(&t.alpha);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_CHANNELS);
        RESET(); h.tail = view(&tls);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_SIZE_MISMATCH);
        free(tl0.mem); free(tl1.mem); free(tls.mem);
    }
    /* sbl_reproject_temporal reads (and validates) no evidence plane: an output may lie on it */
    RESET(); h.evidence = view(&t.alpha);
    CHECK_EQ(sbl_reproject_temporal(&d.reproject, SBL_TEMPORAL_MOTION, &f, &h, view(&t.hist[1]),
                                    view(&t.alpha), 0, 7), SBL_OK);
    CHECK_EQ(sbl_reproject_temporal(&d.reproject, SBL_TEMPORAL_MOTION, &f, &h, view(&t.hist[1]),
                                    view(&t.depth), 0, 7), SBL_ERROR_OVERLAP); /* the G-buffer */
    RESET(); d.estimator = (sbl_estimator)17;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.rectify = (sbl_rectify)-1;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.constant_alpha = 1.5f;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.max_history = (float)HUGE_VAL - (float)HUGE_VAL; /* NaN */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.reproject.depth_tolerance = -1.0f;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.source = (sbl_temporal_source)4;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); d.reproject.motion.units = (sbl_motion_units)9;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    RESET(); f.gbuffer.motion.data = NULL;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_MISSING_INPUT);
    RESET(); d.source = SBL_TEMPORAL_CAMERA;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_MISSING_INPUT);
    RESET();
    CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 0, 7, NULL, 0), SBL_ERROR_NULL_POINTER);
    CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 0, 7, scratch, sizeof scratch), SBL_ERROR_SCRATCH_TOO_SMALL);
    CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, -1, 7, scratch, sizeof scratch), SBL_ERROR_INVALID_ROWS);
    CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 0, 8, scratch, sizeof scratch), SBL_ERROR_INVALID_ROWS);
    CHECK_EQ(sbl_temporal_scratch_size(0, 3), 0);
    CHECK_EQ(sbl_temporal_scratch_size(9, 5), 0);

    /* a rejected call writes nothing */
    RESET();
    for (i = 0; i < 9 * 7 * 3; ++i) t.hist[1].mem[(i / 27) * t.hist[1].stride + i % 27] = -42.0f;
    d.constant_alpha = -0.5f;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
    CHECK_EQ(t.hist[1].mem[0], -42);
    CHECK_EQ(t.hist[1].mem[t.hist[1].stride * 6 + 26], -42);

    /* an empty row range is valid and writes nothing */
    RESET();
    {
        size_t bytes = sbl_temporal_scratch_size(9, 3);
        void *mem = malloc(bytes);
        CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 3, 3, mem, bytes), SBL_OK);
        CHECK_EQ(t.hist[1].mem[0], -42);
        free(mem);
    }

    /* every result has its own string */
    for (i = 0; i < SBL_RESULT_COUNT; ++i) {
        int j;
        CHECK(strcmp(sbl_result_string((sbl_result)i), "unknown sbl_result") != 0);
        for (j = 0; j < i; ++j) CHECK(strcmp(sbl_result_string((sbl_result)i), sbl_result_string((sbl_result)j)) != 0);
    }
    CHECK(strcmp(sbl_result_string((sbl_result)999), "unknown sbl_result") == 0);
#undef RESET
    free(small.mem);
    tf_free(&t);
}

/* The two eyes of one side-by-side texture share a stride but no float: input in the
   left half, output in the right half is not an overlap; one pixel further left is. */
static void test_side_by_side(void)
{
    const int w = 16, h = 8;
    sbt_img tex = sbt_img_new(2 * w, h, 3, 0), d = sbt_img_new(w, h, 1, 0), mv = sbt_img_new(w, h, 2, 0);
    sbt_img n = sbt_img_new(2 * w, h, 1, 0);
    sbl_temporal_desc td;
    sbl_frame f;
    sbl_temporal_output o;
    int i;
    memset(&td, 0, sizeof td); memset(&f, 0, sizeof f); memset(&o, 0, sizeof o);
    for (i = 0; i < w * h; ++i) d.mem[i] = 1.0f;
    for (i = 0; i < 2 * w * h * 3; ++i) tex.mem[i] = 0.25f + (float)(i % 7) * 0.1f;
    f.color = sbl_image_make(tex.mem, w, h, 3);
    f.color.stride = 2 * w * 3;
    f.gbuffer.depth = view(&d);
    f.gbuffer.motion = view(&mv);
    o.color = sbl_image_make(tex.mem + w * 3, w, h, 3);
    o.color.stride = 2 * w * 3;
    o.length = sbl_image_make(n.mem, w, h, 1);
    o.length.stride = 2 * w;
    CHECK_EQ(sbl_temporal_filter_frame(&td, &f, NULL, &o), SBL_OK);
    CHECK_NEAR(tex.mem[(size_t)3 * 2 * w * 3 + w * 3 + 4], tex.mem[(size_t)3 * 2 * w * 3 + 4], 0); /* copied */
    o.color.data = tex.mem + w * 3 - 3;
    CHECK_EQ(sbl_temporal_filter_frame(&td, &f, NULL, &o), SBL_ERROR_OVERLAP);
    free(tex.mem); free(d.mem); free(mv.mem); free(n.mem);
}

/* The combined call equals its parts: the temporal filter per eye, then the stereo
   blend of the temporal outputs; a bad display buffer is rejected before anything is
   written. */
static void test_stereo_temporal_frame(void)
{
    const int w = 21, h = 13;
    sbt_rng rng = {8};
    sbt_img col[2], dep[2], mv[2], hc[2], hn[2], oc[2][2], on[2][2], disp[2][2];
    sbl_temporal_desc td;
    sbl_stereo_desc sd;
    sbl_stereo_temporal_io io;
    sbl_history hist[2];
    int e, i, x, y, k, pass, differ = 0;
    float first_display[21 * 13 * 3];
    memset(&td, 0, sizeof td);
    memset(&sd, 0, sizeof sd);
    sd.focal_px = 10.0f;
    sd.baseline = 0.3f; /* disparity 1.5 px at depth 2 */
    memset(&io, 0, sizeof io);
    for (e = 0; e < 2; ++e) {
        col[e] = sbt_img_new(w, h, 3, 1); dep[e] = sbt_img_new(w, h, 1, 0);
        mv[e] = sbt_img_new(w, h, 2, 0); hc[e] = sbt_img_new(w, h, 3, 2); hn[e] = sbt_img_new(w, h, 1, 0);
        for (i = 0; i < 2; ++i) {
            oc[e][i] = sbt_img_new(w, h, 3, 0); on[e][i] = sbt_img_new(w, h, 1, 1);
            disp[e][i] = sbt_img_new(w, h, 3, 1);
        }
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                for (k = 0; k < 3; ++k) {
                    sbt_at(&col[e], x, y)[k] = (float)(truth(x, y, k) + 0.2 * sbt_gauss(&rng));
                    sbt_at(&hc[e], x, y)[k] = truth(x, y, k);
                }
                *sbt_at(&dep[e], x, y) = 2.0f;
                sbt_at(&mv[e], x, y)[0] = 0.25f;
                *sbt_at(&hn[e], x, y) = 6.0f;
            }
        memset(&hist[e], 0, sizeof hist[e]);
        hist[e].color = view(&hc[e]);
        hist[e].length = view(&hn[e]);
        hist[e].gbuffer.depth = view(&dep[e]);
        io.frame[e].color = view(&col[e]);
        io.frame[e].gbuffer.depth = view(&dep[e]);
        io.frame[e].gbuffer.motion = view(&mv[e]);
        io.history[e] = &hist[e];
        io.temporal[e].color = view(&oc[e][0]);
        io.temporal[e].length = view(&on[e][0]);
        io.display[e] = view(&disp[e][0]);
    }
    /* pass 0: the call's default shared bias (0 -> 1: a stereo blend follows), by hand
       with 1; pass 1: SBL_SHARED_BIAS_NONE, by hand with per-eye weights (0) */
    for (pass = 0; pass < 2; ++pass) {
        sbl_temporal_desc tc = td, th = td;
        sbl_eye eye[2];
        tc.stereo_shared_bias = pass ? SBL_SHARED_BIAS_NONE : 0.0f;
        th.stereo_shared_bias = pass ? 0.0f : 1.0f;
        CHECK_EQ(sbl_stereo_temporal_frame(&tc, &sd, &io), SBL_OK);
        for (e = 0; e < 2; ++e) {
            sbl_temporal_output o;
            memset(&o, 0, sizeof o);
            o.color = view(&oc[e][1]);
            o.length = view(&on[e][1]);
            CHECK_EQ(sbl_temporal_filter_frame(&th, &io.frame[e], &hist[e], &o), SBL_OK);
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = o.color;
            eye[e].length = o.length;
            eye[e].gbuffer.depth = view(&dep[e]);
        }
        CHECK_EQ(sbl_stereo_blend_frame(&sd, &eye[0], &eye[1], view(&disp[0][1]), view(&disp[1][1])), SBL_OK);
        for (e = 0; e < 2; ++e) {
            int same = 1;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    for (k = 0; k < 3; ++k) {
                        same &= sbt_at(&oc[e][0], x, y)[k] == sbt_at(&oc[e][1], x, y)[k];
                        same &= sbt_at(&disp[e][0], x, y)[k] == sbt_at(&disp[e][1], x, y)[k];
                    }
                    same &= *sbt_at(&on[e][0], x, y) == *sbt_at(&on[e][1], x, y);
                }
            CHECK(same);
            /* the blend did something: display differs from the temporal output */
            CHECK(memcmp(disp[e][0].mem, oc[e][0].mem, sizeof(float) * 3) != 0 ||
                  memcmp(sbt_at(&disp[e][0], 10, 6), sbt_at(&oc[e][0], 10, 6), 3 * sizeof(float)) != 0);
            CHECK(sbt_canaries_ok(&disp[e][0]) && sbt_canaries_ok(&on[e][0]));
        }
        for (y = 0; y < h; ++y) /* the two passes' displays differ (the default acts) */
            for (x = 0; x < w; ++x)
                for (k = 0; k < 3; ++k) {
                    float *kept = &first_display[(y * w + x) * 3 + k];
                    if (pass == 0) *kept = sbt_at(&disp[0][0], x, y)[k];
                    else differ += *kept != sbt_at(&disp[0][0], x, y)[k];
                }
    }
    CHECK(differ > 0);
    /* display over the other eye's new history: rejected, nothing written */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) sbt_at(&oc[0][0], x, y)[0] = -42.0f;
    io.display[1] = view(&oc[0][0]);
    CHECK_EQ(sbl_stereo_temporal_frame(&td, &sd, &io), SBL_ERROR_OVERLAP);
    CHECK_EQ(sbt_at(&oc[0][0], 3, 3)[0], -42);
    CHECK_EQ(*sbt_at(&on[0][0], 3, 3), *sbt_at(&on[0][1], 3, 3)); /* untouched since */
    io.display[1] = view(&disp[1][0]);
    {   /* an eye's temporal outputs over the other eye's history (eye 0 runs first, so it
           would change what eye 1 reads): rejected, nothing written */
        const float n1 = *sbt_at(&hn[1], 3, 3);
        io.temporal[0].evidence = view(&hn[1]);
        CHECK_EQ(sbl_stereo_temporal_frame(&td, &sd, &io), SBL_ERROR_OVERLAP);
        io.temporal[0].evidence = view(&on[1][1]);
        io.temporal[1].evidence = view(&on[1][1]); /* both eyes' planes on one buffer */
        CHECK_EQ(sbl_stereo_temporal_frame(&td, &sd, &io), SBL_ERROR_OVERLAP);
        memset(&io.temporal[0].evidence, 0, sizeof io.temporal[0].evidence);
        memset(&io.temporal[1].evidence, 0, sizeof io.temporal[1].evidence);
        io.temporal[0].color = view(&hc[1]);
        CHECK_EQ(sbl_stereo_temporal_frame(&td, &sd, &io), SBL_ERROR_OVERLAP);
        io.temporal[0].color = view(&oc[0][0]);
        CHECK_EQ(*sbt_at(&hn[1], 3, 3), n1);
    }
    sd.focal_px = -1.0f;
    CHECK_EQ(sbl_stereo_temporal_frame(&td, &sd, &io), SBL_ERROR_INVALID_PARAM);
    CHECK_EQ(sbt_at(&oc[0][0], 3, 3)[0], -42);
    CHECK_EQ(sbl_stereo_temporal_frame(&td, NULL, &io), SBL_ERROR_NULL_POINTER);
    for (e = 0; e < 2; ++e) {
        free(col[e].mem); free(dep[e].mem); free(mv[e].mem); free(hc[e].mem); free(hn[e].mem);
        for (i = 0; i < 2; ++i) { free(oc[e][i].mem); free(on[e][i].mem); free(disp[e][i].mem); }
    }
}

/* Row ranges: filtering in bands (as a job system would) equals one call. */
static void test_row_bands(void)
{
    tf a, b;
    sbl_temporal_desc d;
    sbt_rng r1 = {11}, r2 = {11};
    int i;
    tf_init(&a, 23, 19, 3);
    tf_init(&b, 23, 19, 3);
    memset(&d, 0, sizeof d);
    for (i = 0; i < 4; ++i) {
        sbl_frame f;
        sbl_history h;
        sbl_temporal_output o;
        size_t bytes = sbl_temporal_scratch_size(23, 3);
        void *mem = malloc(bytes);
        int y;
        tf_noisy(&a, &r1, 0.3);
        tf_noisy(&b, &r2, 0.3);
        CHECK_EQ(tf_step(&a, &d, i == 0), SBL_OK);
        memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
        f.color = view(&b.cur); f.gbuffer.depth = view(&b.depth); f.gbuffer.motion = view(&b.mv);
        h.color = view(&b.hist[b.ping]); h.length = view(&b.len[b.ping]); h.gbuffer.depth = view(&b.depth);
        o.color = view(&b.hist[!b.ping]); o.length = view(&b.len[!b.ping]);
        for (y = 0; y < 19; y += 5)
            CHECK_EQ(sbl_temporal_filter(&d, &f, i == 0 ? NULL : &h, &o, y, y + 5 > 19 ? 19 : y + 5, mem, bytes), SBL_OK);
        b.ping = !b.ping;
        free(mem);
    }
    CHECK_EQ(memcmp(a.hist[a.ping].mem, b.hist[b.ping].mem, sizeof(float) * (size_t)a.hist[0].stride * 19), 0);
    CHECK_EQ(memcmp(a.len[a.ping].mem, b.len[b.ping].mem, sizeof(float) * (size_t)a.len[0].stride * 19), 0);
    tf_free(&a);
    tf_free(&b);
}

/* The tail plane (sbl_history.tail): carried in bands of rows it gives the whole
   frame's bits (colour, N and the plane); it records the limit's exceedances (some
   rate where samples hit, none elsewhere); a history plane holding values that are not
   a rate and a variance (NaN, inf, negative, a rate above 1, FLT_MAX) is read as
   nothing seen, and every output stays finite. */
static void test_tail_plane(void)
{
    enum { W = 23, H = 19 };
    tf a, b;
    sbt_img ta[2], tb[2];
    sbl_temporal_desc d;
    sbt_rng r1 = {5}, r2 = {5};
    const size_t bytes = sbl_temporal_scratch_size(W, 3);
    void *mem = malloc(bytes);
    int i, x, y, c, k, rate_ok = 1, finite = 1, n_hits = 0, n_grey = 0;
    double rate_hits = 0.0, rate_grey = 0.0;
    tf_init(&a, W, H, 3);
    tf_init(&b, W, H, 3);
    for (i = 0; i < 2; ++i) { ta[i] = sbt_img_new(W, H, 2, 1); tb[i] = sbt_img_new(W, H, 2, 0); }
    memset(&d, 0, sizeof d);
    for (i = 0; i < 9; ++i) {
        sbl_frame f;
        sbl_history h;
        sbl_temporal_output o;
        tf *t[2];
        t[0] = &a; t[1] = &b;
        for (y = 0; y < H; ++y) /* hit-or-miss on the left half, a noisy grey on the right */
            for (x = 0; x < W; ++x) {
                const double u1 = sbt_uniform(&r1), u2 = sbt_uniform(&r2);
                for (c = 0; c < 3; ++c) {
                    sbt_at(&a.cur, x, y)[c] = (float)(x < W / 2 ? (u1 < 0.1 ? 5.0 : 0.0) : 0.4 + 0.2 * u1);
                    sbt_at(&b.cur, x, y)[c] = (float)(x < W / 2 ? (u2 < 0.1 ? 5.0 : 0.0) : 0.4 + 0.2 * u2);
                }
            }
        if (i == 8) /* garbage in the history's plane of both runs */
            for (k = 0; k < 2; ++k) {
                sbt_img *p = k ? &tb[b.ping] : &ta[a.ping];
                sbt_at(p, 3, 3)[0] = NAN; sbt_at(p, 4, 3)[1] = INFINITY; sbt_at(p, 5, 3)[0] = -1.0f;
                sbt_at(p, 6, 3)[0] = 2.0f; sbt_at(p, 7, 3)[1] = FLT_MAX; sbt_at(p, 8, 3)[1] = -INFINITY;
            }
        for (k = 0; k < 2; ++k) {
            sbt_img *tl = k ? tb : ta;
            memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
            f.color = view(&t[k]->cur); f.gbuffer.depth = view(&t[k]->depth); f.gbuffer.motion = view(&t[k]->mv);
            h.color = view(&t[k]->hist[t[k]->ping]); h.length = view(&t[k]->len[t[k]->ping]);
            h.gbuffer.depth = view(&t[k]->depth); h.tail = view(&tl[t[k]->ping]);
            o.color = view(&t[k]->hist[!t[k]->ping]); o.length = view(&t[k]->len[!t[k]->ping]);
            o.tail = view(&tl[!t[k]->ping]);
            if (k == 0)
                CHECK_EQ(sbl_temporal_filter(&d, &f, i == 0 ? NULL : &h, &o, 0, H, mem, bytes), SBL_OK);
            else
                for (y = 0; y < H; y += 5)
                    CHECK_EQ(sbl_temporal_filter(&d, &f, i == 0 ? NULL : &h, &o, y, y + 5 > H ? H : y + 5, mem, bytes), SBL_OK);
            t[k]->ping = !t[k]->ping;
        }
    }
    CHECK_EQ(memcmp(a.hist[a.ping].mem, b.hist[b.ping].mem, sizeof(float) * (size_t)a.hist[0].stride * H), 0);
    CHECK_EQ(memcmp(a.len[a.ping].mem, b.len[b.ping].mem, sizeof(float) * (size_t)a.len[0].stride * H), 0);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            const float *pa = sbt_at(&ta[a.ping], x, y), *pb = sbt_at(&tb[b.ping], x, y);
            CHECK(memcmp(pa, pb, 2 * sizeof(float)) == 0);
            rate_ok &= pa[0] >= 0.0f && pa[0] <= 1.0f && pa[1] >= 0.0f && pa[1] <= FLT_MAX;
            if (x < W / 2 - 1) { rate_hits += pa[0]; ++n_hits; }
            if (x >= W / 2 + 2) { rate_grey += pa[0]; ++n_grey; }
            for (c = 0; c < 3; ++c) finite &= isfinite(sbt_at(&a.hist[a.ping], x, y)[c]) != 0;
        }
    /* the hits exceed the bound often (lone hits: (1 - 0.1)^8 of them), the grey's
       samples almost never (a corner's three neighbours can give a small sigma; 0.0006) */
    printf("  tail plane: rate %.3f where 10 %% of samples hit, %.4f on a noisy grey\n",
           rate_hits / n_hits, rate_grey / n_grey);
    CHECK(rate_ok);
    CHECK(rate_hits > 0.02 * n_hits); /* measured 0.037 (9 frames) */
    CHECK(rate_grey < 0.01 * n_grey);
    CHECK(finite);
    CHECK(sbt_canaries_ok(&ta[0]) && sbt_canaries_ok(&ta[1]));
    {   /* a history plane of zeros reads as none (sbl_temporal_filter skips its gather):
           check that claim against the full path, which one NaN forces (the gather reads
           the NaN as nothing seen, so the plane is zeros in effect) */
        sbl_frame f;
        sbl_history h;
        sbl_temporal_output o;
        sbt_img oc[2], ol[2], ot[2];
        for (k = 0; k < 2; ++k) {
            oc[k] = sbt_img_new(W, H, 3, 0); ol[k] = sbt_img_new(W, H, 1, 0); ot[k] = sbt_img_new(W, H, 2, 0);
            memset(ta[0].mem, 0, sizeof(float) * (size_t)ta[0].stride * H); /* canaries too: rewritten below */
            for (y = 0; y < H; ++y) sbt_at(&ta[0], W - 1, y)[2] = SBT_CANARY; /* (the 1-float pad) */
            if (k) sbt_at(&ta[0], 7, 9)[1] = NAN;
            memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
            f.color = view(&a.cur); f.gbuffer.depth = view(&a.depth); f.gbuffer.motion = view(&a.mv);
            h.color = view(&a.hist[a.ping]); h.length = view(&a.len[a.ping]);
            h.gbuffer.depth = view(&a.depth); h.tail = view(&ta[0]);
            o.color = view(&oc[k]); o.length = view(&ol[k]); o.tail = view(&ot[k]);
            CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 0, H, mem, bytes), SBL_OK);
        }
        CHECK_EQ(memcmp(oc[0].mem, oc[1].mem, sizeof(float) * (size_t)W * H * 3), 0);
        CHECK_EQ(memcmp(ol[0].mem, ol[1].mem, sizeof(float) * (size_t)W * H), 0);
        CHECK_EQ(memcmp(ot[0].mem, ot[1].mem, sizeof(float) * (size_t)W * H * 2), 0);
        for (k = 0; k < 2; ++k) { free(oc[k].mem); free(ol[k].mem); free(ot[k].mem); }
    }
    for (i = 0; i < 2; ++i) { free(ta[i].mem); free(tb[i].mem); }
    free(mem);
    tf_free(&a);
    tf_free(&b);
}

/* The tail plane laid out as N with offsets doubled (packed, N packed) is gathered in the
   colour's plan (sbl__tail_fused_ok); laid out otherwise (rows padded) it takes a gather
   of its own. Both give the same bits, whole or in bands of rows, with and without the
   evidence plane, on content that reaches every path of the row gather: a camera at rest
   (rest tiles), one motion vector for whole rows (uniform blocks), random motion
   (scattered vectors), a moved disc (disocclusions: the 3x3 fallback), a block narrower
   than any vector at each row's end (checked with counters in a scratch copy: the
   uniform run's tail taps and the narrow blocks' pixel gathers are reached), invalid N, non-finite history colours and tail values that
   are not a rate or a variance (inf and NaN: the pixel gather). */
static void test_tail_fused(void)
{
    enum { W = 67, H = 23, RUNS = 3 }; /* (67 = a 64-column block and 3 columns: narrower than any vector) */
    sbt_img cur = sbt_img_new(W, H, 3, 0), depth = sbt_img_new(W, H, 1, 0), pdepth = sbt_img_new(W, H, 1, 0);
    sbt_img mv = sbt_img_new(W, H, 2, 0), hist = sbt_img_new(W, H, 3, 0), len = sbt_img_new(W, H, 1, 0);
    sbt_img evin = sbt_img_new(W, H, 1, 0), tin[2], oc[RUNS], ol[RUNS], oe[RUNS], ot[RUNS];
    const size_t bytes = sbl_temporal_scratch_size(W, 3);
    void *mem = malloc(bytes);
    sbl_temporal_desc d;
    sbt_rng rng = {77};
    int x, y, k, ev, run;
    tin[0] = sbt_img_new(W, H, 2, 0); /* packed: in the colour's plan */
    tin[1] = sbt_img_new(W, H, 2, 5); /* rows padded: its own gather */
    for (run = 0; run < RUNS; ++run) {
        oc[run] = sbt_img_new(W, H, 3, 0); ol[run] = sbt_img_new(W, H, 1, 0);
        oe[run] = sbt_img_new(W, H, 1, 0); ot[run] = sbt_img_new(W, H, 2, 0);
    }
    memset(&d, 0, sizeof d);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            const int in_now = (x - 40) * (x - 40) + (y - 11) * (y - 11) < 25;
            const int in_was = (x - 46) * (x - 46) + (y - 11) * (y - 11) < 25;
            const double u = sbt_uniform(&rng);
            float rate;
            for (k = 0; k < 3; ++k) {
                sbt_at(&cur, x, y)[k] = (float)(0.4 + 0.3 * sbt_uniform(&rng));
                sbt_at(&hist, x, y)[k] = (float)(0.3 + 0.4 * sbt_uniform(&rng));
            }
            *sbt_at(&depth, x, y) = in_now ? 1.0f : 2.0f + 0.01f * (float)y;
            *sbt_at(&pdepth, x, y) = in_was ? 1.0f : 2.0f + 0.01f * (float)y;
            /* one vector for the whole of each row above (uniform blocks), then at rest on
               the left and on the last rows, random elsewhere */
            if ((x < 16 && y >= 8) || y >= 17) {
                sbt_at(&mv, x, y)[0] = sbt_at(&mv, x, y)[1] = 0.0f;
            } else if (y < 8) {
                sbt_at(&mv, x, y)[0] = 0.37f;
                sbt_at(&mv, x, y)[1] = -0.21f;
            } else {
                sbt_at(&mv, x, y)[0] = (float)(1.8 * (sbt_uniform(&rng) - 0.5));
                sbt_at(&mv, x, y)[1] = (float)(1.8 * (sbt_uniform(&rng) - 0.5));
            }
            *sbt_at(&len, x, y) = u < 0.03 ? 0.0f : 8.0f;
            *sbt_at(&evin, x, y) = (float)(0.8 + 0.6 * sbt_uniform(&rng));
            rate = u > 0.6 ? (float)(0.1 * sbt_uniform(&rng)) : 0.0f;
            sbt_at(&tin[0], x, y)[0] = rate;
            sbt_at(&tin[0], x, y)[1] = 3.0f * rate;
        }
    sbt_at(&hist, 20, 5)[1] = INFINITY;
    sbt_at(&hist, 45, 14)[0] = NAN;
    sbt_at(&hist, 5, 20)[2] = INFINITY; /* (at rest) */
    sbt_at(&tin[0], 24, 3)[1] = INFINITY; /* (uniform rows) */
    sbt_at(&tin[0], 30, 6)[0] = NAN;
    sbt_at(&tin[0], 50, 12)[1] = INFINITY; /* (random rows) */
    sbt_at(&tin[0], 36, 10)[0] = 2.0f;
    sbt_at(&tin[0], 8, 19)[1] = INFINITY; /* (at rest) */
    sbt_at(&tin[0], 9, 19)[0] = -1.0f;
    sbt_at(&tin[0], 12, 4)[1] = FLT_MAX;
    sbt_at(&tin[0], W - 1, 9)[1] = INFINITY; /* (the row's end) */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) memcpy(sbt_at(&tin[1], x, y), sbt_at(&tin[0], x, y), 2 * sizeof(float));
    for (ev = 0; ev < 2; ++ev) {
        for (run = 0; run < RUNS; ++run) { /* 0: fused, whole; 1: its own gather; 2: fused, bands */
            sbl_frame f;
            sbl_history h;
            sbl_temporal_output o;
            memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
            f.color = view(&cur); f.gbuffer.depth = view(&depth); f.gbuffer.motion = view(&mv);
            h.color = view(&hist); h.length = view(&len); h.gbuffer.depth = view(&pdepth);
            h.tail = view(&tin[run == 1]);
            o.color = view(&oc[run]); o.length = view(&ol[run]); o.tail = view(&ot[run]);
            if (ev) { h.evidence = view(&evin); o.evidence = view(&oe[run]); }
            if (run < 2)
                CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, 0, H, mem, bytes), SBL_OK);
            else
                for (y = 0; y < H; y += 4)
                    CHECK_EQ(sbl_temporal_filter(&d, &f, &h, &o, y, y + 4 > H ? H : y + 4, mem, bytes), SBL_OK);
        }
        for (run = 1; run < RUNS; ++run) {
            CHECK(memcmp(oc[0].mem, oc[run].mem, sizeof(float) * (size_t)W * H * 3) == 0);
            CHECK(memcmp(ol[0].mem, ol[run].mem, sizeof(float) * (size_t)W * H) == 0);
            CHECK(memcmp(ot[0].mem, ot[run].mem, sizeof(float) * (size_t)W * H * 2) == 0);
            if (ev) CHECK(memcmp(oe[0].mem, oe[run].mem, sizeof(float) * (size_t)W * H) == 0);
        }
        {   /* the plane was read: some rate carried, every value a rate and a variance */
            int some = 0, ok = 1;
            for (k = 0; k < W * H; ++k) {
                const float *t = ot[0].mem + 2 * k;
                some |= t[0] > 0.0f;
                ok &= t[0] >= 0.0f && t[0] <= 1.0f && t[1] >= 0.0f && t[1] <= FLT_MAX;
            }
            CHECK(some);
            CHECK(ok);
        }
    }
    free(cur.mem); free(depth.mem); free(pdepth.mem); free(mv.mem); free(hist.mem); free(len.mem);
    free(evin.mem); free(tin[0].mem); free(tin[1].mem);
    for (run = 0; run < RUNS; ++run) { free(oc[run].mem); free(ol[run].mem); free(oe[run].mem); free(ot[run].mem); }
    free(mem);
}

/* A non-finite sample keeps x* and must record no exceedance in the tail plane, on
   every SIMD build (review, session 31: a lane vector covering the pixel recorded one,
   T = FLT_MAX, on AVX2 only). 24 x 8, the history 0.5 with N = 8, one +inf sample. */
static void test_tail_nonfinite(void)
{
    enum { W = 24, H = 8 };
    tf t;
    sbt_img tl[2];
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    sbt_rng rng = {31};
    int x, y, c, i;
    tf_init(&t, W, H, 3);
    for (i = 0; i < 2; ++i) tl[i] = sbt_img_new(W, H, 2, 0);
    memset(&d, 0, sizeof d);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            for (c = 0; c < 3; ++c) {
                sbt_at(&t.cur, x, y)[c] = (float)(0.4 + 0.2 * sbt_uniform(&rng));
                sbt_at(&t.hist[0], x, y)[c] = 0.5f;
            }
            *sbt_at(&t.len[0], x, y) = 8.0f;
            sbt_at(&tl[0], x, y)[0] = x == 0 && y == 0 ? 0.01f : 0.0f; /* not all zero: the full path */
        }
    sbt_at(&t.cur, 8, 4)[0] = INFINITY;
    memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
    f.color = view(&t.cur); f.gbuffer.depth = view(&t.depth); f.gbuffer.motion = view(&t.mv);
    h.color = view(&t.hist[0]); h.length = view(&t.len[0]); h.gbuffer.depth = view(&t.depth);
    h.tail = view(&tl[0]);
    o.color = view(&t.hist[1]); o.length = view(&t.len[1]); o.tail = view(&tl[1]);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_OK);
    CHECK(sbt_at(&tl[1], 8, 4)[0] == 0.0f);
    CHECK(sbt_at(&tl[1], 8, 4)[1] == 0.0f);
    for (i = 0; i < 2; ++i) free(tl[i].mem);
    tf_free(&t);
}

int main(void)
{
    test_tail_nonfinite();
    test_tail_plane();
    test_tail_fused();
    test_weights();
    test_depth();
    test_reproject_integer_and_bilinear();
    test_reproject_tap_tests();
    test_reproject_camera();
    test_moments();
    test_filter_properties();
    test_convergence();
    test_reacts_to_change();
    test_errors();
    test_row_bands();
    test_side_by_side();
    test_stereo_temporal_frame();
    return sbt_finish("test_core");
}
