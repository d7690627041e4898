/* Engine-facing API: the stereo rigs as calibrations give them (parallel rig with a
   disparity offset, pinhole rig from intrinsics and a relative pose in OpenCV or OpenGL
   axes, 2-D disparity maps, the two-camera rig), a Middlebury-style calibrated pair read
   from calib.txt / PFM files, camera constructors, switchable tests, beta output, byte
   and pixel strides, diagnostics, temporal cameras and per-object transforms.
   Geometry convention of the scenes here (OpenCV axes of the LEFT eye): a point
   (X, Y, Z) projects to u = f X / Z + cx, v = f Y / Z + cy in pixel coordinates whose
   pixel (i, j) has its centre at (i + 0.5, j + 0.5); the right eye sits at X = +b (its
   view space is the left's shifted by -b, plus ty along y when a vertical offset is
   tested). */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"

static sbl_image view(const sbt_img *im)
{
    sbl_image v = sbl_image_make(im->mem, im->w, im->h, im->c);
    v.stride = im->stride;
    return v;
}

static void img_fill(sbt_img *im, float v)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k) sbt_at(im, x, y)[k] = v;
}

/* 4x4 row-major matrices in double, the test's own (independent of the header's) */
static void mat4_apply(double *out, const double *m, const double *v)
{
    int r;
    for (r = 0; r < 4; ++r)
        out[r] = m[r * 4] * v[0] + m[r * 4 + 1] * v[1] + m[r * 4 + 2] * v[2] + m[r * 4 + 3] * v[3];
}

/* inverse by Gauss-Jordan elimination with partial pivoting (the test's matrices are
   rigid transforms, well conditioned) */
static void mat4_invert(double *inv, const double *m)
{
    double a[4][8];
    int r, c, k;
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 8; ++c) a[r][c] = c < 4 ? m[r * 4 + c] : (c - 4 == r ? 1.0 : 0.0);
    for (c = 0; c < 4; ++c) {
        int piv = c;
        double t;
        for (r = c + 1; r < 4; ++r)
            if (fabs(a[r][c]) > fabs(a[piv][c])) piv = r;
        for (k = 0; k < 8; ++k) { t = a[c][k]; a[c][k] = a[piv][k]; a[piv][k] = t; }
        t = a[c][c];
        for (k = 0; k < 8; ++k) a[c][k] /= t;
        for (r = 0; r < 4; ++r) {
            if (r == c) continue;
            t = a[r][c];
            for (k = 0; k < 8; ++k) a[r][k] -= t * a[c][k];
        }
    }
    for (r = 0; r < 4; ++r)
        for (c = 0; c < 4; ++c) inv[r * 4 + c] = a[r][c + 4];
}

static void identity16(float *m)
{
    int i;
    for (i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

/* ---- a calibrated pair: slanted plane + a fronto-parallel box ------------------- */

typedef struct pair {
    int w, h;
    double f, b, cx[2], cy[2], ty;   /* ty: right eye's view = left's + (-b, ty, 0)    */
    double z0, a, c;                 /* plane Z = z0 + a X + c Y (left eye coords)      */
    double zbox, bx0, bx1, by0, by1; /* box at Z = zbox over X in [bx0,bx1), Y in [..) */
    double tex_scale;                /* world units per texture unit                   */
    sbt_img col[2], dep[2], disp[2], disp2[2];
} pair;

/* Depth seen through pixel centre (u, v) of eye e, and the left-eye-space point. */
static double pair_depth(const pair *p, int e, double u, double v, double *X, double *Y)
{
    double xn = (u - p->cx[e]) / p->f, yn = (v - p->cy[e]) / p->f, Z, Xb, Yb;
    /* plane: X = xn Z + (e ? b : 0), Y = yn Z - (e ? ty : 0) */
    double ox = e ? p->b : 0.0, oy = e ? -p->ty : 0.0;
    Z = (p->z0 + p->a * ox + p->c * oy) / (1.0 - p->a * xn - p->c * yn);
    if (p->zbox > 0.0 && p->zbox < Z) {
        Xb = xn * p->zbox + ox;
        Yb = yn * p->zbox + oy;
        if (Xb >= p->bx0 && Xb < p->bx1 && Yb >= p->by0 && Yb < p->by1) Z = p->zbox;
    }
    *X = xn * Z + ox;
    *Y = yn * Z + oy;
    return Z;
}

/* A smooth texture in world units (periods of a few pixels at these depths). */
static double pair_texture(double X, double Y, int k)
{
    return 0.5 + 0.22 * sin(9.0 * X + 2.0 * k) + 0.18 * sin(7.0 * Y + 1.3 * X + k) +
           0.08 * sin(23.0 * X - 5.0 * Y);
}

static void pair_render(pair *p)
{
    int e, x, y, k;
    for (e = 0; e < 2; ++e)
        for (y = 0; y < p->h; ++y)
            for (x = 0; x < p->w; ++x) {
                double X, Y, Z = pair_depth(p, e, x + 0.5, y + 0.5, &X, &Y);
                /* disparity = left position - right position of the same point:
                   u_l - u_r = f b / Z + cx_l - cx_r, v_l - v_r = -f ty / Z + cy_l - cy_r */
                double dx = p->f * p->b / Z - (p->cx[1] - p->cx[0]);
                double dy = -p->f * p->ty / Z - (p->cy[1] - p->cy[0]);
                *sbt_at(&p->dep[e], x, y) = (float)Z;
                *sbt_at(&p->disp[e], x, y) = (float)dx;
                sbt_at(&p->disp2[e], x, y)[0] = (float)dx;
                sbt_at(&p->disp2[e], x, y)[1] = (float)dy;
                for (k = 0; k < 3; ++k)
                    sbt_at(&p->col[e], x, y)[k] = (float)pair_texture(X / p->tex_scale, Y / p->tex_scale, k);
            }
}

static void pair_init(pair *p, int w, int h)
{
    int e;
    memset(p, 0, sizeof *p);
    p->w = w; p->h = h;
    p->tex_scale = 1.0;
    p->f = 40.0; p->b = 0.1;
    p->cx[0] = w * 0.5 + 0.3; p->cx[1] = p->cx[0] + 1.75; /* doffs 1.75 */
    p->cy[0] = p->cy[1] = h * 0.5 - 0.2;
    p->z0 = 1.2; p->a = 0.25; p->c = 0.1;
    p->zbox = 0.8; p->bx0 = -0.05; p->bx1 = 0.1; p->by0 = -0.06; p->by1 = 0.05;
    for (e = 0; e < 2; ++e) {
        p->col[e] = sbt_img_new(w, h, 3, 1 + e);
        p->dep[e] = sbt_img_new(w, h, 1, 2 - e);
        p->disp[e] = sbt_img_new(w, h, 1, 1);
        p->disp2[e] = sbt_img_new(w, h, 2, 3);
    }
}

static void pair_free(pair *p)
{
    int e;
    for (e = 0; e < 2; ++e) {
        free(p->col[e].mem); free(p->dep[e].mem); free(p->disp[e].mem); free(p->disp2[e].mem);
    }
}

enum { FORM_PARALLEL, FORM_DISP1, FORM_DISP2, FORM_PIN_CV, FORM_PIN_GL, FORM_PIN_CV_INT,
       FORM_MAT_PINHOLE, FORM_MAT_HAND, FORM_MAT_W2P, FORM_COUNT };
static const char *form_name[FORM_COUNT] = {
    "parallel+doffs", "disparity 1ch", "disparity 2ch", "pinhole opencv", "pinhole opengl",
    "pinhole opencv int", "matrices (from pinhole)", "matrices (by hand)", "matrices (world-to-pixel)"};

typedef struct rig_setup {
    sbl_stereo_desc d;
    sbl_eye eye[2];
    sbl_camera cam[2];
} rig_setup;

/* One rig form describing the pair's geometry. Returns 0 if the form cannot describe it
   (the parallel rig and 1-channel maps have no vertical offset). */
static int pair_rig(pair *p, int form, rig_setup *r)
{
    int e;
    memset(r, 0, sizeof *r);
    if ((form == FORM_PARALLEL || form == FORM_DISP1) && (p->ty != 0.0 || p->cy[0] != p->cy[1]))
        return 0;
    for (e = 0; e < 2; ++e) {
        r->eye[e].color = view(&p->col[e]);
        r->eye[e].gbuffer.depth = view(&p->dep[e]);
    }
    switch (form) {
    case FORM_PARALLEL:
        r->d.rig = SBL_RIG_PARALLEL;
        r->d.focal_px = (float)p->f;
        r->d.baseline = (float)p->b;
        r->d.disparity_offset = (float)(p->cx[1] - p->cx[0]);
        break;
    case FORM_DISP1: case FORM_DISP2:
        r->d.rig = SBL_RIG_DISPARITY;
        for (e = 0; e < 2; ++e) r->eye[e].disparity = view(form == FORM_DISP1 ? &p->disp[e] : &p->disp2[e]);
        break;
    case FORM_PIN_CV: case FORM_PIN_GL: case FORM_PIN_CV_INT: {
        sbl_pinhole_rig *k = &r->d.pinhole;
        double half = form == FORM_PIN_CV_INT ? 0.5 : 0.0;
        r->d.rig = SBL_RIG_PINHOLE;
        for (e = 0; e < 2; ++e) {
            k->eye[e].fx = k->eye[e].fy = (float)p->f;
            k->eye[e].cx = (float)(p->cx[e] - half);
            k->eye[e].cy = (float)(p->cy[e] - half);
        }
        k->integer_pixel_centers = form == FORM_PIN_CV_INT;
        identity16(k->right_from_left);
        k->right_from_left[3] = (float)-p->b;
        /* +ty along OpenCV's y (down) is -ty along OpenGL's y (up) */
        k->axes = form == FORM_PIN_GL ? SBL_AXES_OPENGL : SBL_AXES_OPENCV;
        k->right_from_left[7] = (float)(form == FORM_PIN_GL ? -p->ty : p->ty);
        break;
    }
    case FORM_MAT_PINHOLE: case FORM_MAT_HAND: case FORM_MAT_W2P:
        r->d.rig = SBL_RIG_MATRICES;
        for (e = 0; e < 2; ++e) {
            float pose[16];
            sbl_intrinsics k;
            identity16(pose);
            pose[3] = e ? (float)-p->b : 0.0f;
            pose[7] = e ? (float)p->ty : 0.0f; /* OpenCV axes */
            k.fx = k.fy = (float)p->f;
            k.cx = (float)p->cx[e];
            k.cy = (float)p->cy[e];
            if (form == FORM_MAT_PINHOLE) {
                CHECK_EQ(sbl_camera_from_pinhole(&r->cam[e], &k, pose, SBL_AXES_OPENCV, 0, p->w, p->h), SBL_OK);
            } else if (form == FORM_MAT_HAND) {
                /* an off-axis OpenGL frustum written out: view = OpenCV pose with y, z
                   flipped; near 0.05, far 50 */
                sbl_camera *c = &r->cam[e];
                float n = 0.05f, fa = 50.0f;
                identity16(c->world_to_view);
                c->world_to_view[3] = pose[3];
                c->world_to_view[5] = -1.0f; c->world_to_view[7] = -pose[7];
                c->world_to_view[10] = -1.0f;
                memset(c->view_to_clip, 0, sizeof c->view_to_clip);
                c->view_to_clip[0] = (float)(2.0 * p->f / p->w);
                c->view_to_clip[2] = (float)(1.0 - 2.0 * p->cx[e] / p->w);
                c->view_to_clip[5] = (float)(2.0 * p->f / p->h);
                c->view_to_clip[6] = (float)(2.0 * p->cy[e] / p->h - 1.0);
                c->view_to_clip[10] = -(fa + n) / (fa - n);
                c->view_to_clip[11] = -2.0f * fa * n / (fa - n);
                c->view_to_clip[14] = -1.0f;
            } else {
                /* P = K [R | t], scaled by -3 (the same camera), integer pixel centres */
                float P[12];
                int i;
                double K[9] = {0};
                K[0] = K[4] = p->f; K[2] = p->cx[e] - 0.5; K[5] = p->cy[e] - 0.5; K[8] = 1.0;
                for (i = 0; i < 3; ++i) {
                    int j;
                    for (j = 0; j < 4; ++j)
                        P[i * 4 + j] = (float)(-3.0 * (K[i * 3 + 0] * pose[j] + K[i * 3 + 1] * pose[4 + j] +
                                                       K[i * 3 + 2] * pose[8 + j]));
                }
                CHECK_EQ(sbl_camera_from_world_to_pixel(&r->cam[e], P, 1, p->w, p->h), SBL_OK);
            }
            r->eye[e].camera = &r->cam[e];
        }
        break;
    default: return 0;
    }
    return 1;
}

/* ---- 1. the rig forms agree, and the sign convention --------------------------- */

static void test_rigs_agree(void)
{
    const int w = 40, h = 24;
    pair p;
    sbt_img out[FORM_COUNT], val[FORM_COUNT];
    int pass, f, t, x, y, k;
    pair_init(&p, w, h);
    for (f = 0; f < FORM_COUNT; ++f) { out[f] = sbt_img_new(w, h, 3, 1); val[f] = sbt_img_new(w, h, 1, 2); }
    for (pass = 0; pass < 2; ++pass) {
        /* pass 1: a vertical offset (ty and cy differ) as rectification leaves it */
        if (pass == 1) { p.ty = 0.004; p.cy[1] = p.cy[0] + 0.35; }
        pair_render(&p);
        for (t = 0; t < 2; ++t) {
            int have[FORM_COUNT], ref = pass == 0 ? FORM_PARALLEL : FORM_DISP2;
            long nvalid = 0, exact_pos = 0, npos = 0;
            double max_pos_err = 0.0;
            for (f = 0; f < FORM_COUNT; ++f) {
                rig_setup r;
                have[f] = pair_rig(&p, f, &r);
                if (!have[f]) continue;
                img_fill(&out[f], -5.0f);
                CHECK_EQ(sbl_reproject_stereo(&r.d, (sbl_eye_index)t, &r.eye[t], &r.eye[!t],
                                              view(&out[f]), view(&val[f]), 0, h), SBL_OK);
                CHECK(sbt_canaries_ok(&out[f]) && sbt_canaries_ok(&val[f]));
            }
            for (f = 0; f < FORM_COUNT; ++f) {
                long diff_valid = 0;
                double maxdiff = 0.0;
                if (!have[f] || f == ref) continue;
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) {
                        float a = *sbt_at(&val[ref], x, y), b = *sbt_at(&val[f], x, y);
                        diff_valid += a != b;
                        if (a == 1.0f && b == 1.0f)
                            for (k = 0; k < 3; ++k) {
                                double dd = fabs(sbt_at(&out[ref], x, y)[k] - sbt_at(&out[f], x, y)[k]);
                                if (dd > maxdiff) maxdiff = dd;
                            }
                    }
                if (diff_valid || maxdiff > 2e-5)
                    printf("  pass %d eye %d %s vs %s: %ld validity differences, max colour diff %.3g\n",
                           pass, t, form_name[f], form_name[ref], diff_valid, maxdiff);
                CHECK_EQ(diff_valid, 0);
                CHECK(maxdiff <= 2e-5);
            }
            /* the reference against the geometry: where valid, the source colour at the
               analytic match position (bilinear of the source texture) */
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    double X, Y, Z, us, vs;
                    if (*sbt_at(&val[ref], x, y) != 1.0f) continue;
                    ++nvalid;
                    Z = pair_depth(&p, t, x + 0.5, y + 0.5, &X, &Y);
                    /* project the point into the source eye */
                    us = p.f * (X - (t ? 0.0 : p.b)) / Z + p.cx[!t];
                    vs = p.f * (Y + (t ? 0.0 : p.ty)) / Z + p.cy[!t];
                    {
                        int x0 = (int)floor(us - 0.5), y0 = (int)floor(vs - 0.5);
                        double fx = us - 0.5 - x0, fy = vs - 0.5 - y0, e = 0.0;
                        if (x0 < 0 || y0 < 0 || x0 + 1 >= w || y0 + 1 >= h) continue;
                        ++npos;
                        for (k = 0; k < 3; ++k) {
                            const sbt_img *s = &p.col[!t];
                            double ref_v = (1 - fy) * ((1 - fx) * sbt_at(s, x0, y0)[k] + fx * sbt_at(s, x0 + 1, y0)[k]) +
                                           fy * ((1 - fx) * sbt_at(s, x0, y0 + 1)[k] + fx * sbt_at(s, x0 + 1, y0 + 1)[k]);
                            double dd = fabs(ref_v - sbt_at(&out[ref], x, y)[k]);
                            if (dd > e) e = dd;
                        }
                        /* taps on the other surface (box edge) are rejected and the rest
                           renormalised: compare only where all four taps are one surface */
                        if (e > max_pos_err) max_pos_err = e;
                        exact_pos += e <= 2e-5;
                    }
                }
            printf("  pass %d target %s: %ld valid, %ld of %ld interior matches equal the analytic "
                   "bilinear value (max diff %.3g)\n", pass, t ? "right" : "left", nvalid, exact_pos,
                   npos, max_pos_err);
            CHECK(nvalid > w * h / 2);
            CHECK(exact_pos >= npos * 9 / 10); /* the rest: box silhouettes */
        }
    }
    for (f = 0; f < FORM_COUNT; ++f) { free(out[f].mem); free(val[f].mem); }
    pair_free(&p);
}

/* Sign convention with a colour ramp: source colour = x position, so the reprojected
   colour reads the match position off directly. Parallel rig, constant depth: left u
   takes right u - (f b / z - doffs). */
static void test_disparity_sign(void)
{
    const int w = 32, h = 4;
    const float f = 20.0f, b = 0.5f, z = 4.0f, doffs = 1.25f; /* f b / z = 2.5: d = 1.25 */
    sbt_img col[2], dep[2], out = sbt_img_new(w, h, 1, 0), val = sbt_img_new(w, h, 1, 0);
    sbl_stereo_desc d;
    sbl_eye eye[2];
    int e, x, y, t, ok;
    memset(&d, 0, sizeof d);
    memset(eye, 0, sizeof eye);
    for (e = 0; e < 2; ++e) {
        col[e] = sbt_img_new(w, h, 1, 0);
        dep[e] = sbt_img_new(w, h, 1, 0);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) { *sbt_at(&col[e], x, y) = x + 0.5f; *sbt_at(&dep[e], x, y) = z; }
        eye[e].color = view(&col[e]);
        eye[e].gbuffer.depth = view(&dep[e]);
    }
    d.rig = SBL_RIG_PARALLEL; d.focal_px = f; d.baseline = b; d.disparity_offset = doffs;
    for (t = 0; t < 2; ++t) {
        double dir = t == 0 ? -1.0 : 1.0;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)t, &eye[t], &eye[!t], view(&out), view(&val), 0, h), SBL_OK);
        ok = 1;
        for (x = 2; x < w - 2; ++x) {
            double want = x + 0.5 + dir * 1.25;
            ok &= *sbt_at(&val, x, 1) == 1.0f && fabs(*sbt_at(&out, x, 1) - want) < 1e-5;
        }
        CHECK(ok);
    }
    /* a negative disparity (offset larger than f b / z) is a valid match */
    d.disparity_offset = 4.0f; /* d = 2.5 - 4 = -1.5: left u takes right u + 1.5 */
    CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &eye[0], &eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK(*sbt_at(&val, 10, 1) == 1.0f);
    CHECK_NEAR(*sbt_at(&out, 10, 1), 12.0, 1e-5);
    /* sky (z = +inf) matches at d = -doffs */
    for (e = 0; e < 2; ++e)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
    CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &eye[0], &eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK(*sbt_at(&val, 10, 1) == 1.0f);
    CHECK_NEAR(*sbt_at(&out, 10, 1), 14.5, 1e-5);
    /* a non-finite offset is refused and nothing is written */
    img_fill(&out, 9.0f);
    d.disparity_offset = (float)HUGE_VAL;
    CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &eye[0], &eye[1], view(&out), view(&val), 0, h), SBL_ERROR_INVALID_PARAM);
    CHECK(*sbt_at(&out, 3, 2) == 9.0f);
    for (e = 0; e < 2; ++e) { free(col[e].mem); free(dep[e].mem); }
    free(out.mem); free(val.mem);
}

/* OpenCV and OpenGL axes: the same physical rig with a rotation (pitch and yaw) and a
   vertical offset, written in each convention, gives the same warp; the OpenCV pose
   read as OpenGL does not (the flag is not ignored). */
static void test_axes(void)
{
    const int w = 32, h = 24;
    pair p;
    rig_setup r;
    sbt_img o[3], v[3];
    float cv[16], gl[16];
    double ca = cos(0.02), sa = sin(0.02), cb = cos(0.03), sb = sin(0.03);
    int i, x, y, same = 1, differs = 0, valid = 0;
    /* R = Rx(0.02) Ry(0.03) in OpenCV axes; T = (-b, 0.003, 0.001) */
    double R[9];
    R[0] = cb; R[1] = 0; R[2] = sb;
    R[3] = sa * sb; R[4] = ca; R[5] = -sa * cb;
    R[6] = -ca * sb; R[7] = sa; R[8] = ca * cb;
    pair_init(&p, w, h);
    pair_render(&p); /* only colour and depth of the left eye are used as the target */
    identity16(cv);
    for (i = 0; i < 3; ++i) {
        cv[i * 4 + 0] = (float)R[i * 3 + 0];
        cv[i * 4 + 1] = (float)R[i * 3 + 1];
        cv[i * 4 + 2] = (float)R[i * 3 + 2];
    }
    cv[3] = (float)-p.b; cv[7] = 0.003f; cv[11] = 0.001f;
    /* the same pose in OpenGL axes: F M F with F = diag(1, -1, -1, 1) */
    for (i = 0; i < 16; ++i) {
        int row = i / 4, col = i % 4;
        float sr = (row == 1 || row == 2) ? -1.0f : 1.0f, sc = (col == 1 || col == 2) ? -1.0f : 1.0f;
        gl[i] = cv[i] * sr * sc;
    }
    for (i = 0; i < 3; ++i) { o[i] = sbt_img_new(w, h, 3, 0); v[i] = sbt_img_new(w, h, 1, 0); }
    for (i = 0; i < 3; ++i) {
        pair_rig(&p, FORM_PIN_CV, &r);
        r.d.reproject.disabled_tests = SBL_TEST_DEPTH | SBL_TEST_BACK_CHECK; /* geometry only */
        memcpy(r.d.pinhole.right_from_left, i == 1 ? gl : cv, sizeof cv);
        r.d.pinhole.axes = i == 0 ? SBL_AXES_OPENCV : SBL_AXES_OPENGL;
        CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&o[i]), view(&v[i]), 0, h), SBL_OK);
    }
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            valid += *sbt_at(&v[0], x, y) == 1.0f;
            same &= *sbt_at(&v[0], x, y) == *sbt_at(&v[1], x, y);
            if (*sbt_at(&v[0], x, y) == 1.0f && *sbt_at(&v[1], x, y) == 1.0f)
                same &= fabsf(sbt_at(&o[0], x, y)[0] - sbt_at(&o[1], x, y)[0]) < 1e-5f;
            differs += *sbt_at(&v[2], x, y) != *sbt_at(&v[0], x, y) ||
                       fabsf(sbt_at(&o[2], x, y)[0] - sbt_at(&o[0], x, y)[0]) > 1e-3f;
        }
    CHECK(valid > w * h / 2);
    CHECK(same);
    CHECK(differs > w * h / 4);
    /* a single point, by hand, through the public path: left pixel centre at depth z ->
       right position, read back from a right image that holds its own pixel positions
       (bilinear interpolation of a linear ramp is exact up to float rounding) */
    {
        sbl_camera c[2];
        sbl_intrinsics k;
        sbl_stereo_desc d;
        sbl_eye eye[2];
        sbt_img ramp = sbt_img_new(w, h, 3, 0), dep = sbt_img_new(w, h, 1, 0);
        sbt_img out = sbt_img_new(w, h, 3, 0), ok = sbt_img_new(w, h, 1, 0);
        float id[16];
        double X, Y, Z = 2.0, Xr, Yr, Zr;
        k.fx = 30.0f; k.fy = 32.0f; k.cx = 15.0f; k.cy = 11.0f; /* OpenCV: centres at integers */
        identity16(id);
        CHECK_EQ(sbl_camera_from_pinhole(&c[0], &k, id, SBL_AXES_OPENCV, 1, w, h), SBL_OK);
        CHECK_EQ(sbl_camera_from_pinhole(&c[1], &k, cv, SBL_AXES_OPENCV, 1, w, h), SBL_OK);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                sbt_at(&ramp, x, y)[0] = (float)x + 0.5f;
                sbt_at(&ramp, x, y)[1] = (float)y + 0.5f;
                sbt_at(&ramp, x, y)[2] = 0.0f;
                *sbt_at(&dep, x, y) = (float)Z;
            }
        memset(&d, 0, sizeof d);
        memset(eye, 0, sizeof eye);
        d.rig = SBL_RIG_MATRICES;
        d.reproject.disabled_tests = SBL_TEST_DEPTH | SBL_TEST_BACK_CHECK; /* geometry only */
        for (i = 0; i < 2; ++i) {
            eye[i].color = view(&ramp);
            eye[i].gbuffer.depth = view(&dep);
            eye[i].camera = &c[i];
        }
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &eye[0], &eye[1], view(&out), view(&ok), 0, h), SBL_OK);
        /* library pixel (20, 7) = OpenCV pixel centre (20, 7) -> position (20.5, 7.5) */
        X = (20.0 - 15.0) / 30.0 * Z; Y = (7.0 - 11.0) / 32.0 * Z;
        Xr = R[0] * X + R[1] * Y + R[2] * Z - p.b;
        Yr = R[3] * X + R[4] * Y + R[5] * Z + 0.003;
        Zr = R[6] * X + R[7] * Y + R[8] * Z + 0.001;
        CHECK(*sbt_at(&ok, 20, 7) == 1.0f);
        CHECK_NEAR(sbt_at(&out, 20, 7)[0], 30.0 * Xr / Zr + 15.0 + 0.5, 5e-5);
        CHECK_NEAR(sbt_at(&out, 20, 7)[1], 32.0 * Yr / Zr + 11.0 + 0.5, 5e-5);
        free(ramp.mem); free(dep.mem); free(out.mem); free(ok.mem);
    }
    for (i = 0; i < 3; ++i) { free(o[i].mem); free(v[i].mem); }
    pair_free(&p);
}

/* ---- 1b. a Middlebury-style calibrated pair on disk ----------------------------- */

/* PFM (Middlebury's disparity format): "Pf" or "PF", width height, scale (< 0: little
   endian), rows bottom to top. */
static int write_pfm(const char *path, const float *rows_top_down, int w, int h, int c)
{
    FILE *f = fopen(path, "wb");
    int y;
    if (!f) return 0;
    fprintf(f, "%s\n%d %d\n-1\n", c == 3 ? "PF" : "Pf", w, h);
    for (y = h - 1; y >= 0; --y)
        fwrite(rows_top_down + (size_t)y * (size_t)w * (size_t)c, sizeof(float), (size_t)w * (size_t)c, f);
    return fclose(f) == 0;
}

/* Reads a PFM as stored (bottom row first); *c = 1 or 3. Little-endian hosts only. */
static float *read_pfm(const char *path, int *w, int *h, int *c)
{
    FILE *f = fopen(path, "rb");
    char magic[3] = {0, 0, 0};
    double scale;
    float *p;
    size_t n;
    if (!f) return NULL;
    if (fscanf(f, "%2s %d %d %lf", magic, w, h, &scale) != 4 || fgetc(f) != '\n' || scale >= 0.0) {
        fclose(f);
        return NULL;
    }
    *c = magic[1] == 'F' ? 3 : 1;
    n = (size_t)*w * (size_t)*h * (size_t)*c;
    p = (float *)malloc(n * sizeof(float));
    if (p && fread(p, sizeof(float), n, f) != n) { free(p); p = NULL; }
    fclose(f);
    return p;
}

typedef struct mb_calib { double cam[2][9], doffs, baseline; int width, height; } mb_calib;

static int read_calib(const char *path, mb_calib *m)
{
    FILE *f = fopen(path, "r");
    char line[512];
    int got = 0;
    if (!f) return 0;
    memset(m, 0, sizeof *m);
    while (fgets(line, sizeof line, f)) {
        double *k;
        int e;
        if (sscanf(line, "cam%d=", &e) == 1 && (e == 0 || e == 1)) {
            k = m->cam[e];
            if (sscanf(strchr(line, '[') + 1, "%lf %lf %lf; %lf %lf %lf; %lf %lf %lf", &k[0], &k[1],
                       &k[2], &k[3], &k[4], &k[5], &k[6], &k[7], &k[8]) == 9)
                got |= 1 << e;
        } else if (sscanf(line, "doffs=%lf", &m->doffs) == 1) got |= 4;
        else if (sscanf(line, "baseline=%lf", &m->baseline) == 1) got |= 8;
        else if (sscanf(line, "width=%d", &m->width) == 1) got |= 16;
        else if (sscanf(line, "height=%d", &m->height) == 1) got |= 32;
    }
    fclose(f);
    return got == 63;
}

/* Systematic horizontal shift of `warp` against `ref` (channel 0), by least squares on
   the horizontal gradient: warp(u) ~ ref(u + s). Only where valid. */
static double warp_shift(const sbt_img *warp, const sbt_img *val, const float *ref, int w, int h,
                         int c, double *rmse, long *count)
{
    double num = 0.0, den = 0.0, se = 0.0;
    long n = 0;
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 1; x < w - 1; ++x) {
            const float *r = ref + ((size_t)y * w + x) * c;
            double g = 0.5 * (r[c] - r[-c]), e;
            if (*sbt_at(val, x, y) != 1.0f) continue;
            e = sbt_at(warp, x, y)[0] - r[0];
            num += e * g; den += g * g; se += e * e; ++n;
        }
    *rmse = n ? sqrt(se / n) : 0.0;
    *count = n;
    return den > 0.0 ? num / den : 0.0;
}

static void test_middlebury(void)
{
    /* the layout of a Middlebury 2014 scene, scaled down: calib.txt with cam0/cam1 (pixel
       centres at integers), doffs = cx1 - cx0, baseline in mm; im0/im1 and the ground
       truth disp0/disp1 (left minus right, PFM, bottom-up rows) */
    const char *dir = "build/middlebury_synth";
    const int w = 96, h = 64;
    char path[256];
    pair p;
    int e, x, y;
    pair_init(&p, w, h);
    p.f = 70.0; p.b = 193.0;                       /* mm */
    p.cx[0] = 40.3 + 0.5; p.cx[1] = 46.8 + 0.5;    /* doffs 6.5 */
    p.cy[0] = p.cy[1] = 31.7 + 0.5;
    p.z0 = 2400.0; p.a = 0.3; p.c = -0.05;         /* mm: f b / z ~ 5.6 px, d ~ -0.9 */
    p.tex_scale = 1000.0;
    p.zbox = 1500.0; p.bx0 = -200.0; p.bx1 = 300.0; p.by0 = -250.0; p.by1 = 200.0;
    pair_render(&p);
    {   /* write the scene */
        FILE *f;
        char cmd[300];
        snprintf(cmd, sizeof cmd, "mkdir -p %s", dir);
        CHECK(system(cmd) == 0);
        snprintf(path, sizeof path, "%s/calib.txt", dir);
        f = fopen(path, "w");
        CHECK(f != NULL);
        if (!f) { pair_free(&p); return; }
        fprintf(f, "cam0=[%.3f 0 %.3f; 0 %.3f %.3f; 0 0 1]\n", p.f, p.cx[0] - 0.5, p.f, p.cy[0] - 0.5);
        fprintf(f, "cam1=[%.3f 0 %.3f; 0 %.3f %.3f; 0 0 1]\n", p.f, p.cx[1] - 0.5, p.f, p.cy[1] - 0.5);
        fprintf(f, "doffs=%.3f\nbaseline=%.3f\nwidth=%d\nheight=%d\nndisp=16\nisint=0\nvmin=0\nvmax=8\n"
                   "dyavg=0\ndymax=0\n", p.cx[1] - p.cx[0], p.b, w, h);
        fclose(f);
        for (e = 0; e < 2; ++e) {
            float *tmp = (float *)malloc((size_t)w * h * 3 * sizeof(float));
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    int k;
                    for (k = 0; k < 3; ++k) tmp[((size_t)y * w + x) * 3 + k] = sbt_at(&p.col[e], x, y)[k];
                }
            snprintf(path, sizeof path, "%s/im%d.pfm", dir, e);
            CHECK(write_pfm(path, tmp, w, h, 3));
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) tmp[(size_t)y * w + x] = *sbt_at(&p.disp[e], x, y);
            snprintf(path, sizeof path, "%s/disp%d.pfm", dir, e);
            CHECK(write_pfm(path, tmp, w, h, 1));
            free(tmp);
        }
    }
    {   /* read it back as a user would, and warp right into left with the parallel rig */
        mb_calib m;
        float *im[2], *disp[2], *depth[2];
        int wi, hi, ci, ok = 1;
        snprintf(path, sizeof path, "%s/calib.txt", dir);
        CHECK(read_calib(path, &m));
        CHECK_EQ(m.width, w);
        CHECK_NEAR(m.doffs, m.cam[1][2] - m.cam[0][2], 1e-9);
        for (e = 0; e < 2; ++e) {
            snprintf(path, sizeof path, "%s/im%d.pfm", dir, e);
            im[e] = read_pfm(path, &wi, &hi, &ci);
            ok &= im[e] && wi == w && hi == h && ci == 3;
            snprintf(path, sizeof path, "%s/disp%d.pfm", dir, e);
            disp[e] = read_pfm(path, &wi, &hi, &ci);
            ok &= disp[e] && wi == w && hi == h && ci == 1;
        }
        CHECK(ok);
        if (ok) {
            sbt_img warp = sbt_img_new(w, h, 3, 0), val = sbt_img_new(w, h, 1, 0);
            float *ref_top_down = (float *)malloc((size_t)w * h * 3 * sizeof(float));
            sbl_stereo_desc d;
            sbl_eye eye[2];
            double shift = 0.0, shift0 = 0.0, rmse = 0.0, rmse0 = 0.0;
            long n = 0, n0 = 0;
            int pass;
            for (e = 0; e < 2; ++e) {
                size_t i, np = (size_t)w * h;
                /* Middlebury: Z = baseline * f / (d + doffs) */
                depth[e] = (float *)malloc(np * sizeof(float));
                for (i = 0; i < np; ++i)
                    depth[e][i] = (float)(m.baseline * m.cam[0][0] / (disp[e][i] + m.doffs));
            }
            for (y = 0; y < h; ++y) /* the reference, top-down, for the shift estimate */
                memcpy(ref_top_down + (size_t)y * w * 3, im[0] + (size_t)(h - 1 - y) * w * 3, (size_t)w * 3 * sizeof(float));
            for (pass = 0; pass < 2; ++pass) {
                memset(&d, 0, sizeof d);
                memset(eye, 0, sizeof eye);
                d.rig = SBL_RIG_PARALLEL;
                d.focal_px = (float)m.cam[0][0];
                d.baseline = (float)m.baseline;
                d.disparity_offset = pass ? 0.0f : (float)m.doffs; /* pass 1: offset ignored */
                for (e = 0; e < 2; ++e) {
                    /* PFM rows are bottom-up: row 0 (top) is the last row in memory */
                    eye[e].color = sbl_image_make(im[e] + (size_t)(h - 1) * w * 3, w, h, 3);
                    eye[e].color.stride_bytes = -w * 3 * (int)sizeof(float);
                    eye[e].gbuffer.depth = sbl_image_make(depth[e] + (size_t)(h - 1) * w, w, h, 1);
                    eye[e].gbuffer.depth.stride_bytes = -w * (int)sizeof(float);
                }
                CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &eye[0], &eye[1], view(&warp), view(&val), 0, h), SBL_OK);
                if (pass == 0) shift0 = warp_shift(&warp, &val, ref_top_down, w, h, 3, &rmse0, &n0);
                else shift = warp_shift(&warp, &val, ref_top_down, w, h, 3, &rmse, &n);
            }
            printf("  middlebury-style pair %dx%d, doffs %.2f: with the offset %ld valid, shift %.4f px, "
                   "RMSE %.4f; offset ignored: %ld valid, shift %.3f px, RMSE %.4f\n",
                   w, h, m.doffs, n0, shift0, rmse0, n, shift, rmse);
            CHECK(n0 > w * h * 7 / 10);
            CHECK(fabs(shift0) < 0.02);   /* no systematic shift */
            CHECK(rmse0 < 0.02);
            CHECK(rmse > 5.0 * rmse0 || n < n0 / 2); /* without it: wrong matches */
            free(warp.mem); free(val.mem); free(ref_top_down);
            for (e = 0; e < 2; ++e) free(depth[e]);
        }
        for (e = 0; e < 2; ++e) { free(im[e]); free(disp[e]); }
    }
    pair_free(&p);
}


/* ---- 2. every test switchable off ---------------------------------------------- */

static long count_valid(const sbt_img *v)
{
    long n = 0;
    int x, y;
    for (y = 0; y < v->h; ++y)
        for (x = 0; x < v->w; ++x) n += *sbt_at(v, x, y) == 1.0f;
    return n;
}

static void test_disabled_tests(void)
{
    const int w = 40, h = 24;
    pair p;
    rig_setup r;
    sbt_img out = sbt_img_new(w, h, 3, 1), val = sbt_img_new(w, h, 1, 1);
    sbt_img ids[2], nrm[2];
    long base, nb, nd, inside = 0;
    int e, x, y;
    pair_init(&p, w, h);
    pair_render(&p);
    for (e = 0; e < 2; ++e) {
        ids[e] = sbt_img_new(w, h, 1, 0);
        nrm[e] = sbt_img_new(w, h, 3, 0);
        img_fill(&ids[e], (float)(1 + e));             /* ids differ everywhere          */
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) sbt_at(&nrm[e], x, y)[2] = e ? -1.0f : 1.0f; /* opposite */
    }
    /* the disparity rig without depth: occlusion is caught by the back-check alone */
    pair_rig(&p, FORM_DISP1, &r);
    for (e = 0; e < 2; ++e) r.eye[e].gbuffer.depth.data = NULL;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    base = count_valid(&val);
    r.d.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    nb = count_valid(&val);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double sx = x + 0.5 - *sbt_at(&p.disp[0], x, y);
            inside += sx >= 0.0 && sx < w;
        }
    printf("  back-check: %ld valid with it, %ld without (matches inside the image: %ld)\n", base, nb, inside);
    CHECK(nb > base);
    CHECK_EQ(nb, inside); /* without the back-check every match inside the image is kept */
    /* the parallel rig: depth test + back-check; both off = every match inside */
    pair_rig(&p, FORM_PARALLEL, &r);
    r.d.reproject.disabled_tests = SBL_TEST_BACK_CHECK | SBL_TEST_FALLBACK;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    nd = count_valid(&val);
    CHECK(nd < inside); /* the depth test alone still rejects the occluded pixels */
    r.d.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK(count_valid(&val) > nd); /* the 3x3 fallback finds the surface beside thin occluders */
    r.d.reproject.disabled_tests = SBL_TEST_BACK_CHECK | SBL_TEST_DEPTH;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK_EQ(count_valid(&val), inside);
    /* ids and normals that never match: nothing valid, unless their test is off */
    pair_rig(&p, FORM_PARALLEL, &r);
    for (e = 0; e < 2; ++e) { r.eye[e].gbuffer.ids = view(&ids[e]); r.eye[e].gbuffer.normals = view(&nrm[e]); }
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK_EQ(count_valid(&val), 0);
    r.d.reproject.disabled_tests = SBL_TEST_ID;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK_EQ(count_valid(&val), 0); /* the normals still differ */
    r.d.reproject.disabled_tests = SBL_TEST_ID | SBL_TEST_NORMAL;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    base = count_valid(&val);
    for (e = 0; e < 2; ++e) { r.eye[e].gbuffer.ids.data = NULL; r.eye[e].gbuffer.normals.data = NULL; }
    r.d.reproject.disabled_tests = 0;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_OK);
    CHECK_EQ(count_valid(&val), base); /* switched off = not given */
    CHECK(base > w * h / 2);
    /* an unknown bit is refused, nothing written */
    img_fill(&out, 3.0f);
    r.d.reproject.disabled_tests = 64;
    CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&out), view(&val), 0, h), SBL_ERROR_INVALID_PARAM);
    CHECK(*sbt_at(&out, 5, 5) == 3.0f);
    for (e = 0; e < 2; ++e) { free(ids[e].mem); free(nrm[e].mem); }
    free(out.mem); free(val.mem);
    pair_free(&p);
}

/* ---- 3. beta out of the stereo blend ------------------------------------------- */

static void test_beta(void)
{
    const int w = 40, h = 24;
    pair p;
    rig_setup r;
    sbt_img xs = sbt_img_new(w, h, 3, 0), val = sbt_img_new(w, h, 1, 0);
    sbt_img o1 = sbt_img_new(w, h, 3, 1), o2 = sbt_img_new(w, h, 3, 2), beta = sbt_img_new(w, h, 1, 1);
    sbt_img n1 = sbt_img_new(w, h, 1, 0), n2 = sbt_img_new(w, h, 1, 0);
    sbl_stereo_output so;
    size_t bytes = sbl_stereo_scratch_size(w, 3);
    void *scratch = malloc(bytes);
    int est, x, y, k;
    sbt_rng rng = {5};
    pair_init(&p, w, h);
    pair_render(&p);
    /* noise, so that the estimators have something to weigh */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < 3; ++k) {
                sbt_at(&p.col[0], x, y)[k] += (float)(0.05 * sbt_gauss(&rng));
                sbt_at(&p.col[1], x, y)[k] += (float)(0.05 * sbt_gauss(&rng));
            }
    for (est = 0; est < SBL_ESTIMATOR_COUNT; ++est) {
        long checked = 0, bad = 0, invalid_one = 1;
        pair_rig(&p, FORM_PARALLEL, &r);
        r.d.estimator = (sbl_estimator)est;
        CHECK_EQ(sbl_reproject_stereo(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&xs), view(&val), 0, h), SBL_OK);
        memset(&so, 0, sizeof so);
        so.color = view(&o1); so.length = view(&n1); so.beta = view(&beta);
        CHECK_EQ(sbl_stereo_filter(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, 0, h, scratch, bytes), SBL_OK);
        CHECK_EQ(sbl_stereo_blend(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&o2), view(&n2), 0, h, scratch, bytes), SBL_OK);
        for (y = 0; y < h; ++y) /* the same blend with and without beta */
            CHECK(memcmp(sbt_at(&o1, 0, y), sbt_at(&o2, 0, y), (size_t)w * 3 * sizeof(float)) == 0 &&
                  memcmp(sbt_at(&n1, 0, y), sbt_at(&n2, 0, y), (size_t)w * sizeof(float)) == 0);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                float b = *sbt_at(&beta, x, y);
                if (*sbt_at(&val, x, y) != 1.0f) { invalid_one &= b == 1.0f; continue; }
                CHECK(b >= 0.0f && b <= 1.0f);
                /* scalar weight mode, no rectification: out = (1 - beta) x* + beta y
                   (the robust estimator first limits a firefly y: its y is not the input) */
                if (est == SBL_ESTIMATOR_ROBUST) continue;
                for (k = 0; k < 3; ++k) {
                    double want = (1.0 - b) * sbt_at(&xs, x, y)[k] + b * sbt_at(&p.col[0], x, y)[k];
                    bad += fabs(want - sbt_at(&o1, x, y)[k]) > 1e-5;
                    ++checked;
                }
                if (est == SBL_ESTIMATOR_CONSTANT) bad += b != 0.5f;
            }
        CHECK(checked > w * h || est == SBL_ESTIMATOR_ROBUST);
        CHECK_EQ(bad, 0);
        CHECK(invalid_one);
        CHECK(sbt_canaries_ok(&beta));
    }
    /* errors: beta with 2 channels, beta over the colour output, NULL outputs */
    {
        sbt_img b2 = sbt_img_new(w, h, 2, 0);
        img_fill(&o1, 7.0f);
        so.beta = view(&b2);
        CHECK_EQ(sbl_stereo_filter(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, 0, h, scratch, bytes), SBL_ERROR_INVALID_CHANNELS);
        so.beta = view(&o1); so.beta.channels = 1; so.beta.stride = o1.stride;
        CHECK_EQ(sbl_stereo_filter(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, 0, h, scratch, bytes), SBL_ERROR_OVERLAP);
        CHECK_EQ(sbl_stereo_filter(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], NULL, 0, h, scratch, bytes), SBL_ERROR_NULL_POINTER);
        CHECK(*sbt_at(&o1, 3, 3) == 7.0f);
        free(b2.mem);
    }
    free(scratch);
    free(xs.mem); free(val.mem); free(o1.mem); free(o2.mem); free(beta.mem); free(n1.mem); free(n2.mem);
    pair_free(&p);
}

/* ---- 4. buffers: byte strides, bottom-up, channel views, const ------------------ */

enum { LAY_TIGHT, LAY_BOTTOM_UP, LAY_PITCH, LAY_CHANNEL, LAY_CHANNEL_BOTTOM_UP, LAY_COUNT };

typedef struct lay { float *mem; sbl_image im; } lay;

/* A view of layout `mode` holding the tight image `init` (or zeros). */
static lay lay_new(int w, int h, int c, int mode, const float *init)
{
    lay l;
    int pf = (mode == LAY_CHANNEL || mode == LAY_CHANNEL_BOTTOM_UP) ? (c < 4 ? 4 : 5) : c; /* floats per pixel */
    int off = pf - c;                                     /* the channels at the end  */
    int pitch = w * pf + (mode == LAY_PITCH ? 3 : 0) + (mode >= LAY_CHANNEL ? 1 : 0);
    size_t n = (size_t)pitch * (size_t)h, i;
    int x, y, k;
    l.mem = (float *)malloc(n * sizeof(float));
    for (i = 0; i < n; ++i) l.mem[i] = -99.0f;
    memset(&l.im, 0, sizeof l.im);
    l.im.width = w; l.im.height = h; l.im.channels = c;
    l.im.stride_bytes = pitch * (int)sizeof(float);
    l.im.pixel_bytes = pf * (int)sizeof(float);
    l.im.data = l.mem + off;
    if (mode == LAY_BOTTOM_UP || mode == LAY_CHANNEL_BOTTOM_UP) {
        l.im.data = l.mem + (size_t)(h - 1) * (size_t)pitch + off;
        l.im.stride_bytes = -l.im.stride_bytes;
    }
    if (mode == LAY_PITCH) l.im.size_bytes = n * sizeof(float);
    if (mode == LAY_TIGHT) { l.im.stride_bytes = 0; l.im.pixel_bytes = 0; }
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < c; ++k) {
                float *q = l.mem + (l.im.data - l.mem) + (ptrdiff_t)y * (l.im.stride_bytes ? l.im.stride_bytes / 4 : w * c) +
                           (ptrdiff_t)x * pf + k;
                *q = init ? init[((size_t)y * w + x) * c + k] : 0.0f;
            }
    return l;
}

static void lay_read(const lay *l, float *tight)
{
    const sbl_image *im = &l->im;
    int pf = im->pixel_bytes ? im->pixel_bytes / 4 : im->channels;
    ptrdiff_t rs = im->stride_bytes ? im->stride_bytes / 4 : im->width * im->channels;
    int x, y, k;
    for (y = 0; y < im->height; ++y)
        for (x = 0; x < im->width; ++x)
            for (k = 0; k < im->channels; ++k)
                tight[((size_t)y * im->width + x) * im->channels + k] = im->data[y * rs + (ptrdiff_t)x * pf + k];
}

static void test_buffers(void)
{
    const int w = 37, h = 21, c = 3;
    const size_t np = (size_t)w * h;
    float *col = (float *)malloc(np * c * sizeof(float)), *hist = (float *)malloc(np * c * sizeof(float));
    float *hn = (float *)malloc(np * sizeof(float)), *dep = (float *)malloc(np * sizeof(float));
    float *mv = (float *)malloc(np * 2 * sizeof(float));
    float *ref_c = (float *)malloc(np * c * sizeof(float)), *ref_n = (float *)malloc(np * sizeof(float));
    float *ref_a = (float *)malloc(np * sizeof(float)), *got = (float *)malloc(np * c * sizeof(float));
    sbt_rng rng = {77};
    size_t i;
    int mode, pass;
    for (i = 0; i < np; ++i) {
        int k;
        for (k = 0; k < c; ++k) {
            col[i * c + k] = (float)(0.5 + 0.1 * sbt_gauss(&rng));
            hist[i * c + k] = (float)(0.5 + 0.05 * sbt_gauss(&rng));
        }
        hn[i] = (float)(1 + (int)(sbt_uniform(&rng) * 8));
        dep[i] = (float)(2.0 + sbt_uniform(&rng) * 0.01);
        mv[i * 2] = (float)(sbt_uniform(&rng) * 2.0 - 1.0);
        mv[i * 2 + 1] = (float)(sbt_uniform(&rng) * 2.0 - 1.0);
    }
    for (pass = 0; pass < 2; ++pass) /* pass 0: the tight reference; then every layout */
        for (mode = pass ? 1 : 0; mode < (pass ? LAY_COUNT : 1); ++mode) {
            lay lc = lay_new(w, h, c, mode, col), lh = lay_new(w, h, c, mode, hist);
            lay ln = lay_new(w, h, 1, mode, hn), ld = lay_new(w, h, 1, mode, dep), lpd = lay_new(w, h, 1, mode, dep);
            lay lm = lay_new(w, h, 2, mode, mv);
            lay oc = lay_new(w, h, c, mode, NULL), on = lay_new(w, h, 1, mode, NULL), oa = lay_new(w, h, 1, mode, NULL);
            sbl_temporal_desc d;
            sbl_frame fr;
            sbl_history hi;
            sbl_temporal_output out;
            memset(&d, 0, sizeof d); memset(&fr, 0, sizeof fr); memset(&hi, 0, sizeof hi); memset(&out, 0, sizeof out);
            fr.color = lc.im; fr.gbuffer.depth = ld.im; fr.gbuffer.motion = lm.im;
            hi.color = lh.im; hi.length = ln.im; hi.gbuffer.depth = lpd.im;
            out.color = oc.im; out.length = on.im; out.alpha = oa.im;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), SBL_OK);
            if (!pass) {
                lay_read(&oc, ref_c); lay_read(&on, ref_n); lay_read(&oa, ref_a);
            } else {
                int same;
                lay_read(&oc, got);
                same = memcmp(got, ref_c, np * c * sizeof(float)) == 0;
                lay_read(&on, got);
                same &= memcmp(got, ref_n, np * sizeof(float)) == 0;
                lay_read(&oa, got);
                same &= memcmp(got, ref_a, np * sizeof(float)) == 0;
                if (!same) printf("  layout %d differs from the tight buffers\n", mode);
                CHECK(same);
                /* nothing outside the view was written: the padding keeps its -99 */
                {
                    size_t pitch = (size_t)(oc.im.stride_bytes < 0 ? -oc.im.stride_bytes : oc.im.stride_bytes) / 4, j;
                    long touched = 0;
                    for (j = 0; j < pitch * (size_t)h; ++j) touched += oc.mem[j] != -99.0f;
                    CHECK_EQ(touched, (long)(np * c));
                }
            }
            free(lc.mem); free(lh.mem); free(ln.mem); free(ld.mem); free(lpd.mem); free(lm.mem);
            free(oc.mem); free(on.mem); free(oa.mem);
        }
    /* colour RGB and alpha in the A channel of one RGBA output: interleaved, no overlap */
    {
        float *rgba = (float *)malloc(np * 4 * sizeof(float));
        const float *ccol = col; /* const inputs need no cast */
        sbl_temporal_desc d;
        sbl_frame fr;
        sbl_history hi;
        sbl_temporal_output out;
        int same = 1;
        memset(&d, 0, sizeof d); memset(&fr, 0, sizeof fr); memset(&hi, 0, sizeof hi); memset(&out, 0, sizeof out);
        fr.color = sbl_image_make(ccol, w, h, c);
        fr.gbuffer.depth = sbl_image_make(dep, w, h, 1);
        fr.gbuffer.motion = sbl_image_make(mv, w, h, 2);
        hi.color = sbl_image_make(hist, w, h, c);
        hi.length = sbl_image_make(hn, w, h, 1);
        hi.gbuffer.depth = sbl_image_make(dep, w, h, 1);
        out.color = sbl_image_make(rgba, w, h, 3);
        out.color.pixel_bytes = 16;
        out.alpha = sbl_image_make(rgba + 3, w, h, 1);
        out.alpha.pixel_bytes = 16;
        out.length = sbl_image_make(got, w, h, 1);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), SBL_OK);
        for (i = 0; i < np; ++i)
            same &= memcmp(rgba + i * 4, ref_c + i * 3, 3 * sizeof(float)) == 0 && rgba[i * 4 + 3] == ref_a[i];
        CHECK(same);
        /* the alpha view one float to the left sits on the blue channel: overlap */
        out.alpha.data = rgba + 2;
        CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), SBL_ERROR_OVERLAP);
        out.alpha.data = rgba + 3;
        /* layout errors, each refused before anything is written */
        {
            const float before = rgba[5];
            sbl_temporal_output o2 = out;
            rgba[5] = -1.0f;
            o2.color.stride_bytes = w * 16 + 2;                      /* not whole floats */
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_STRIDE);
            o2 = out; o2.color.pixel_bytes = 8;                      /* < 3 channels     */
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_STRIDE);
            o2 = out; o2.color.pixel_bytes = 14;                     /* not whole floats */
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_STRIDE);
            o2 = out; o2.color.stride = w * 4; o2.color.stride_bytes = w * 4; /* disagree */
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_STRIDE);
            o2 = out; o2.color.stride_bytes = -(w - 1) * 16;          /* rows overlap     */
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_STRIDE);
            /* a pitch in bytes put in the float field: caught by the size, before reading */
            fr.color.stride = w * c * 4;
            fr.color.size_bytes = np * c * sizeof(float);
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), SBL_ERROR_INVALID_SIZE);
            fr.color.stride = 0;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), SBL_OK); /* exact size fits */
            fr.color.size_bytes = np * c * sizeof(float) - 4;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_SIZE);
            rgba[5] = -1.0f;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &o2), SBL_ERROR_INVALID_SIZE);
            CHECK(rgba[5] == -1.0f); /* untouched by the refused calls */
            (void)before;
        }
        free(rgba);
    }
    free(col); free(hist); free(hn); free(dep); free(mv); free(ref_c); free(ref_n); free(ref_a); free(got);
}

/* ---- 5. diagnostics name the culprit ------------------------------------------- */

static void expect_diag(const sbl_diag *d, sbl_result r, const char *field, const char *msg_part,
                        int line)
{
    int ok = d->result == r && strcmp(d->field, field) == 0 &&
             (!msg_part || strstr(d->message, msg_part) != NULL);
    if (!ok) printf("  line %d: diag %d '%s' '%s', expected %d '%s'\n", line, (int)d->result, d->field,
                    d->message, (int)r, field);
    CHECK(ok);
}
#define EXPECT_DIAG(d, r, field, part) expect_diag(&(d), (r), (field), (part), __LINE__)

static void test_diagnostics(void)
{
    const int w = 24, h = 16, c = 3;
    const size_t np = (size_t)w * h;
    float *col = (float *)calloc(np * c, sizeof(float)), *hist = (float *)calloc(np * c, sizeof(float));
    float *hn = (float *)calloc(np, sizeof(float)), *dep = (float *)calloc(np, sizeof(float));
    float *pdep = (float *)calloc(np, sizeof(float)), *mv = (float *)calloc(np * 2, sizeof(float));
    float *oc = (float *)calloc(np * c, sizeof(float)), *on = (float *)calloc(np, sizeof(float));
    float *oa = (float *)calloc(np, sizeof(float));
    sbl_temporal_desc d, d0;
    sbl_frame fr, fr0;
    sbl_history hi, hi0;
    sbl_temporal_output out, out0;
    sbl_diag dg;
    size_t i;
    for (i = 0; i < np; ++i) { dep[i] = 2.0f; pdep[i] = 2.0f; hn[i] = 1.0f; }
    memset(&d0, 0, sizeof d0); memset(&fr0, 0, sizeof fr0); memset(&hi0, 0, sizeof hi0); memset(&out0, 0, sizeof out0);
    fr0.color = sbl_image_make(col, w, h, c);
    fr0.gbuffer.depth = sbl_image_make(dep, w, h, 1);
    fr0.gbuffer.motion = sbl_image_make(mv, w, h, 2);
    hi0.color = sbl_image_make(hist, w, h, c);
    hi0.length = sbl_image_make(hn, w, h, 1);
    hi0.gbuffer.depth = sbl_image_make(pdep, w, h, 1);
    out0.color = sbl_image_make(oc, w, h, c);
    out0.length = sbl_image_make(on, w, h, 1);
    out0.alpha = sbl_image_make(oa, w, h, 1);
#define RESET() (d = d0, fr = fr0, hi = hi0, out = out0)
#define VALIDATE_T(r, field, part)                                                            \
    do {                                                                                      \
        sbl_result vr = sbl_temporal_validate(&d, &fr, &hi, &out, &dg);                       \
        oc[7] = 12345.0f;                                                                     \
        CHECK_EQ(vr, (r));                                                                    \
        CHECK_EQ(sbl_temporal_filter_frame(&d, &fr, &hi, &out), (r));                         \
        if ((r) != SBL_OK) CHECK(oc[7] == 12345.0f);                                          \
        EXPECT_DIAG(dg, (r), (field), (part));                                                \
    } while (0)
    RESET();
    VALIDATE_T(SBL_OK, "", NULL);
    CHECK(dg.warning[0] == '\0');
    RESET(); hi.gbuffer.depth.data = NULL;   /* silent case: the depth test is off */
    VALIDATE_T(SBL_OK, "", NULL);
    CHECK(strstr(dg.warning, "history->gbuffer.depth") == dg.warning && strstr(dg.warning, "depth test is off"));
    RESET(); hi.length.data = NULL;          /* silent case: N = 1 */
    VALIDATE_T(SBL_OK, "", NULL);
    CHECK(strstr(dg.warning, "history->length") == dg.warning);
    RESET(); fr.gbuffer.depth.stride_bytes = 6;
    VALIDATE_T(SBL_ERROR_INVALID_STRIDE, "frame->gbuffer.depth.stride_bytes", "multiple");
    RESET(); out.color.stride = w * c * 4; out.color.size_bytes = np * c * sizeof(float); /* a byte pitch in floats */
    VALIDATE_T(SBL_ERROR_INVALID_SIZE, "out->color.size_bytes", "pitch in bytes");
    RESET(); out.color.stride = w * c - 1;
    VALIDATE_T(SBL_ERROR_INVALID_STRIDE, "out->color.stride", "rows would overlap");
    RESET(); d.max_history = 0.5f;
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->max_history", NULL);
    RESET(); d.clip_gamma = -1.0f;
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->clip_gamma", "-1");
    RESET(); d.stereo_shared_bias = 2.0f;
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->stereo_shared_bias", "[0, 1]");
    RESET(); d.reproject.depth_tolerance = (float)(HUGE_VAL - HUGE_VAL);
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->reproject.depth_tolerance", NULL);
    RESET(); d.reproject.disabled_tests = 1 << 10;
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->reproject.disabled_tests", NULL);
    RESET(); d.estimator = (sbl_estimator)77;
    VALIDATE_T(SBL_ERROR_INVALID_PARAM, "desc->estimator", "77");
    RESET(); fr.gbuffer.motion.data = NULL;
    VALIDATE_T(SBL_ERROR_MISSING_INPUT, "frame->gbuffer.motion", "motion vectors");
    RESET(); d.source = SBL_TEMPORAL_CAMERA;
    VALIDATE_T(SBL_ERROR_MISSING_INPUT, "frame->camera", NULL);
    RESET(); out.alpha.data = hist + 5;
    VALIDATE_T(SBL_ERROR_OVERLAP, "out->alpha", "overlaps history->color");
    RESET(); out.length.data = oc;
    VALIDATE_T(SBL_ERROR_OVERLAP, "out->length", "out->color");
    RESET(); hi.color.channels = 2; hi.color.stride = w * c;
    VALIDATE_T(SBL_ERROR_CHANNEL_MISMATCH, "history->color.channels", NULL);
    RESET(); hi.length.width = w - 1;
    VALIDATE_T(SBL_ERROR_SIZE_MISMATCH, "history->length.width", "23 x 16");
    RESET(); out.length.data = NULL;
    VALIDATE_T(SBL_ERROR_NULL_POINTER, "out->length.data", NULL);
    RESET(); fr.gbuffer.normals = sbl_image_make(col, w, h, 4);
    VALIDATE_T(SBL_ERROR_INVALID_CHANNELS, "frame->gbuffer.normals.channels", "needs 3");
    /* the evidence planes are named like the others */
    RESET(); out.evidence = sbl_image_make(mv, w, h, 2);
    VALIDATE_T(SBL_ERROR_INVALID_CHANNELS, "out->evidence.channels", "needs 1");
    RESET(); out.evidence = sbl_image_make(pdep, w, h, 1);
    VALIDATE_T(SBL_ERROR_OVERLAP, "out->evidence", "history->gbuffer.depth");
    RESET(); hi.evidence = sbl_image_make(on, w, h, 1);
    VALIDATE_T(SBL_ERROR_OVERLAP, "out->length", "history->evidence");
    RESET(); hi.evidence = sbl_image_make(pdep, w - 1, h, 1);
    VALIDATE_T(SBL_ERROR_SIZE_MISMATCH, "history->evidence.width", "23 x 16");
    RESET();
    CHECK_EQ(sbl_temporal_validate(NULL, &fr, &hi, &out, &dg), SBL_ERROR_NULL_POINTER);
    EXPECT_DIAG(dg, SBL_ERROR_NULL_POINTER, "desc", NULL);
    CHECK_EQ(sbl_temporal_validate(&d, &fr, &hi, &out, NULL), SBL_OK);
#undef VALIDATE_T
#undef RESET
    free(col); free(hist); free(hn); free(dep); free(pdep); free(mv); free(oc); free(on); free(oa);

    {   /* stereo */
        pair p;
        rig_setup r;
        sbl_stereo_output so;
        sbt_img o = sbt_img_new(40, 24, 3, 0), b2 = sbt_img_new(40, 24, 2, 0);
        unsigned char *mask = (unsigned char *)malloc(40 * 24);
        long need_right, need_wrong;
        pair_init(&p, 40, 24);
        pair_render(&p);
        memset(&so, 0, sizeof so);
        so.color = view(&o);
        pair_rig(&p, FORM_PARALLEL, &r);
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_OK);
        EXPECT_DIAG(dg, SBL_OK, "", NULL);
        if (dg.warning[0]) printf("  unexpected warning: %s\n", dg.warning);
        CHECK(dg.warning[0] == '\0');
        memset(&r.d, 0, sizeof r.d);                     /* the all-zero desc */
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_INVALID_PARAM);
        EXPECT_DIAG(dg, SBL_ERROR_INVALID_PARAM, "desc->focal_px", "SBL_RIG_PARALLEL");
        pair_rig(&p, FORM_PIN_CV, &r);
        memset(r.d.pinhole.right_from_left, 0, sizeof r.d.pinhole.right_from_left);
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_INVALID_PARAM);
        EXPECT_DIAG(dg, SBL_ERROR_INVALID_PARAM, "desc->pinhole.right_from_left", "singular");
        pair_rig(&p, FORM_PIN_CV, &r);
        r.d.pinhole.eye[1].fy = 0.0f;
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_INVALID_PARAM);
        EXPECT_DIAG(dg, SBL_ERROR_INVALID_PARAM, "desc->pinhole.eye[1]", NULL);
        pair_rig(&p, FORM_PARALLEL, &r);
        r.eye[0].gbuffer.depth.data = NULL;
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_MISSING_INPUT);
        EXPECT_DIAG(dg, SBL_ERROR_MISSING_INPUT, "target->gbuffer.depth", NULL);
        pair_rig(&p, FORM_PARALLEL, &r);
        so.beta = view(&b2);
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_INVALID_CHANNELS);
        EXPECT_DIAG(dg, SBL_ERROR_INVALID_CHANNELS, "out->beta.channels", NULL);
        so.beta.data = NULL;
        so.color = r.eye[1].gbuffer.depth; so.color.channels = 3; so.color.stride = p.dep[1].stride;
        so.color.width = 40 / 3; /* a size mismatch comes first */
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_SIZE_MISMATCH);
        EXPECT_DIAG(dg, SBL_ERROR_SIZE_MISMATCH, "out->color.width", NULL);
        so.color = view(&o);
        so.length = r.eye[1].gbuffer.depth;
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_OVERLAP);
        EXPECT_DIAG(dg, SBL_ERROR_OVERLAP, "out->length", "source->gbuffer.depth");
        so.length.data = NULL;
        /* the eyes' evidence planes (6.15): named as the caller spells them */
        r.eye[0].evidence = view(&o); /* 3 channels */
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_INVALID_CHANNELS);
        EXPECT_DIAG(dg, SBL_ERROR_INVALID_CHANNELS, "target->evidence.channels", NULL);
        r.eye[0].evidence = r.eye[0].gbuffer.depth; r.eye[0].evidence.width = 20;
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_SIZE_MISMATCH);
        EXPECT_DIAG(dg, SBL_ERROR_SIZE_MISMATCH, "target->evidence.width", NULL);
        r.eye[0].evidence.data = NULL;
        r.eye[1].evidence = r.eye[1].gbuffer.depth;
        so.length = r.eye[1].evidence;
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], &so, &dg), SBL_ERROR_OVERLAP);
        EXPECT_DIAG(dg, SBL_ERROR_OVERLAP, "out->length", "source->evidence");
        r.eye[1].evidence.data = NULL;
        so.length.data = NULL;
        /* the wrong target_eye of the issue: the fill call cannot know, the validation warns */
        CHECK_EQ(sbl_stereo_fill(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], view(&o), mask, 40, 0, 24, &need_right), SBL_OK);
        CHECK_EQ(sbl_stereo_fill(&r.d, SBL_EYE_RIGHT, &r.eye[0], &r.eye[1], view(&o), mask, 40, 0, 24, &need_wrong), SBL_OK);
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], NULL, &dg), SBL_OK);
        CHECK(dg.warning[0] == '\0');
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_RIGHT, &r.eye[0], &r.eye[1], NULL, &dg), SBL_OK);
        printf("  wrong target_eye in a fill: %ld pixels need a ray (right eye: %ld); warning: %s\n",
               need_wrong, need_right, dg.warning);
        CHECK(strstr(dg.warning, "target_eye") == dg.warning);
        pair_rig(&p, FORM_PIN_CV, &r); /* the pinhole rig: the eyes' intrinsics differ */
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_LEFT, &r.eye[0], &r.eye[1], NULL, &dg), SBL_OK);
        CHECK(dg.warning[0] == '\0');
        CHECK_EQ(sbl_stereo_validate(&r.d, SBL_EYE_RIGHT, &r.eye[0], &r.eye[1], NULL, &dg), SBL_OK);
        CHECK(strstr(dg.warning, "target_eye") == dg.warning);
        free(mask); free(o.mem); free(b2.mem);
        pair_free(&p);
    }
}

/* ---- 6. temporal cameras in every form, and objects that move ------------------ */

typedef struct tscene {
    int w, h;
    double f, cx, cy;
    double view[2][16];     /* world -> OpenCV view: [0] previous frame, [1] current      */
    double obj[2][16];      /* object -> world: [0] previous, [1] current                 */
} tscene;

static void rot_trans(double *m, double yaw, double roll, double tx, double ty, double tz)
{
    double cy_ = cos(yaw), sy = sin(yaw), cr = cos(roll), sr = sin(roll);
    /* R = Ry(yaw) Rz(roll) */
    m[0] = cy_ * cr; m[1] = -cy_ * sr; m[2] = sy; m[3] = tx;
    m[4] = sr; m[5] = cr; m[6] = 0; m[7] = ty;
    m[8] = -sy * cr; m[9] = sy * sr; m[10] = cy_; m[11] = tz;
    m[12] = 0; m[13] = 0; m[14] = 0; m[15] = 1;
}

/* Casts pixel centre (u, v) of frame t: depth, id, colour; *local = the surface point
   in its own coordinates (object local, or world for the background). */
static double ts_cast(const tscene *s, int t, double u, double v, float *id, double *col, double *local)
{
    double inv_view[16], inv_obj[16], o[4] = {0, 0, 0, 1}, d[4], C[4], D[4], A[4], B[4];
    double tz, best = HUGE_VAL;
    int k;
    d[0] = (u - s->cx) / s->f; d[1] = (v - s->cy) / s->f; d[2] = 1.0; d[3] = 0.0;
    mat4_invert(inv_view, s->view[t]);
    mat4_apply(C, inv_view, o);
    mat4_apply(D, inv_view, d);
    /* background: world z = 6 */
    tz = (6.0 - C[2]) / D[2];
    if (tz > 0) {
        best = tz; *id = 1.0f;
        for (k = 0; k < 3; ++k) local[k] = C[k] + tz * D[k];
    }
    /* the object: local z = 0, |x|, |y| <= 0.6 */
    mat4_invert(inv_obj, s->obj[t]);
    mat4_apply(A, inv_obj, C);
    mat4_apply(B, inv_obj, D);
    tz = -A[2] / B[2];
    if (tz > 0 && tz < best && fabs(A[0] + tz * B[0]) <= 0.6 && fabs(A[1] + tz * B[1]) <= 0.6) {
        best = tz; *id = 2.0f;
        for (k = 0; k < 3; ++k) local[k] = A[k] + tz * B[k];
    }
    for (k = 0; k < 3; ++k)
        col[k] = *id == 2.0f ? pair_texture(local[0] * 4.0, local[1] * 4.0, k)
                             : pair_texture(local[0] * 1.5, local[1] * 1.5, k + 1);
    return best; /* planar depth: the view z of the point is t (d has z = 1) */
}

static void test_temporal_cameras(void)
{
    const int w = 48, h = 32;
    const size_t np = (size_t)w * h;
    tscene s;
    sbt_img col[2], dep[2], ids[2], mv = sbt_img_new(w, h, 2, 0), len = sbt_img_new(w, h, 1, 0);
    sbt_img out[6], on[6];
    sbl_camera cam[6][2];
    sbl_object_motion om;
    int t, x, y, k, run, i;
    double maxd[6];
    long diff_valid[6], nvalid[6], obj_px = 0, ghost = 0;
    memset(&s, 0, sizeof s);
    s.w = w; s.h = h; s.f = 36.0; s.cx = w * 0.5 + 0.25; s.cy = h * 0.5 - 0.1;
    rot_trans(s.view[0], 0.0, 0.0, 0.0, 0.0, 0.0);
    rot_trans(s.view[1], 0.015, 0.0, -0.06, 0.02, 0.03);
    rot_trans(s.obj[0], 0.0, 0.05, -0.1, 0.05, 3.5);
    rot_trans(s.obj[1], 0.2, 0.15, 0.1, -0.02, 3.3);
    for (t = 0; t < 2; ++t) {
        col[t] = sbt_img_new(w, h, 3, 1); dep[t] = sbt_img_new(w, h, 1, 0); ids[t] = sbt_img_new(w, h, 1, 0);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                double c3[3], local[3];
                float id = 0.0f;
                double z = ts_cast(&s, t, x + 0.5, y + 0.5, &id, c3, local);
                *sbt_at(&dep[t], x, y) = (float)z;
                *sbt_at(&ids[t], x, y) = id;
                for (k = 0; k < 3; ++k) sbt_at(&col[t], x, y)[k] = (float)c3[k];
                if (t == 1) { /* motion vectors: where this surface point was last frame */
                    double wp[4], pv[4], q[4];
                    q[0] = local[0]; q[1] = local[1]; q[2] = local[2]; q[3] = 1.0;
                    if (id == 2.0f) mat4_apply(wp, s.obj[0], q);
                    else memcpy(wp, q, sizeof q);
                    mat4_apply(pv, s.view[0], wp);
                    sbt_at(&mv, x, y)[0] = (float)(s.f * pv[0] / pv[2] + s.cx - (x + 0.5));
                    sbt_at(&mv, x, y)[1] = (float)(s.f * pv[1] / pv[2] + s.cy - (y + 0.5));
                    obj_px += id == 2.0f;
                }
            }
    }
    img_fill(&len, 4.0f);
    /* the cameras in each form: [1] pinhole OpenCV, [2] pinhole OpenGL, [3] world-to-pixel
       (integer centres, scaled by -2), [4] pinhole OpenCV without the object list */
    for (t = 0; t < 2; ++t) {
        float V[16], G[16], P[12];
        sbl_intrinsics kk;
        for (i = 0; i < 16; ++i) V[i] = (float)s.view[t][i];
        for (i = 0; i < 16; ++i) G[i] = (i >= 4 && i < 12) ? -V[i] : V[i]; /* F V */
        kk.fx = kk.fy = (float)s.f; kk.cx = (float)s.cx; kk.cy = (float)s.cy;
        CHECK_EQ(sbl_camera_from_pinhole(&cam[1][t], &kk, V, SBL_AXES_OPENCV, 0, w, h), SBL_OK);
        CHECK_EQ(sbl_camera_from_pinhole(&cam[2][t], &kk, G, SBL_AXES_OPENGL, 0, w, h), SBL_OK);
        for (i = 0; i < 4; ++i) {
            double K0 = s.f, K2 = s.cx - 0.5, K4 = s.f, K5 = s.cy - 0.5;
            P[i] = (float)(-2.0 * (K0 * s.view[t][i] + K2 * s.view[t][8 + i]));
            P[4 + i] = (float)(-2.0 * (K4 * s.view[t][4 + i] + K5 * s.view[t][8 + i]));
            P[8 + i] = (float)(-2.0 * s.view[t][8 + i]);
        }
        CHECK_EQ(sbl_camera_from_world_to_pixel(&cam[3][t], P, 1, w, h), SBL_OK);
        cam[4][t] = cam[1][t];
    }
    om.id = 2.0f;
    for (i = 0; i < 16; ++i) { om.object_to_world[i] = (float)s.obj[1][i]; om.prev_object_to_world[i] = (float)s.obj[0][i]; }
    for (run = 0; run < 5; ++run) {
        sbl_reproject_desc rd;
        sbl_frame fr;
        sbl_history hi;
        memset(&rd, 0, sizeof rd); memset(&fr, 0, sizeof fr); memset(&hi, 0, sizeof hi);
        /* motion vectors carry no depth change, so motion mode would test the previous
           depth against the current one (the object moves 0.2 towards the camera: 6 %,
           beyond the 5 % tolerance); compare the positions with the depth test off (the
           id test still catches disocclusions) */
        rd.disabled_tests = SBL_TEST_DEPTH;
        out[run] = sbt_img_new(w, h, 3, 0); on[run] = sbt_img_new(w, h, 1, 0);
        fr.color = view(&col[1]); fr.gbuffer.depth = view(&dep[1]); fr.gbuffer.ids = view(&ids[1]);
        hi.color = view(&col[0]); hi.length = view(&len); hi.gbuffer.depth = view(&dep[0]); hi.gbuffer.ids = view(&ids[0]);
        if (run == 0) fr.gbuffer.motion = view(&mv);
        else {
            fr.camera = &cam[run][1]; hi.camera = &cam[run][0];
            if (run != 4) { fr.objects = &om; fr.object_count = 1; }
        }
        CHECK_EQ(sbl_reproject_temporal(&rd, run ? SBL_TEMPORAL_CAMERA : SBL_TEMPORAL_MOTION, &fr, &hi,
                                        view(&out[run]), view(&on[run]), 0, h), SBL_OK);
        maxd[run] = 0.0; diff_valid[run] = 0; nvalid[run] = 0;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int a = *sbt_at(&on[0], x, y) > 0.0f, b = *sbt_at(&on[run], x, y) > 0.0f;
                nvalid[run] += b;
                diff_valid[run] += a != b;
                if (a && b)
                    for (k = 0; k < 3; ++k) {
                        double dd = fabs(sbt_at(&out[0], x, y)[k] - sbt_at(&out[run], x, y)[k]);
                        if (dd > maxd[run]) maxd[run] = dd;
                    }
                if (run == 4 && *sbt_at(&ids[1], x, y) == 2.0f && b) {
                    /* static assumption on a moving object: reused, and how wrong */
                    double e = 0.0;
                    for (k = 0; k < 3; ++k) e += fabs(sbt_at(&out[4], x, y)[k] - sbt_at(&col[1], x, y)[k]);
                    ghost += e > 0.05;
                }
            }
    }
    printf("  temporal cameras (%d x %d, %ld object pixels): motion vectors %ld valid; vs them: "
           "pinhole OpenCV %ld / %ld differ, max %.2g; pinhole OpenGL %ld, max %.2g; world-to-pixel %ld, "
           "max %.2g; without the object list %ld differ, %ld object pixels reused wrongly\n",
           w, h, obj_px, nvalid[0], diff_valid[1], nvalid[1], maxd[1], diff_valid[2], maxd[2],
           diff_valid[3], maxd[3], diff_valid[4], ghost);
    CHECK(obj_px > 100);
    CHECK(nvalid[0] > (long)np / 2);
    for (run = 1; run <= 3; ++run) {
        CHECK(diff_valid[run] <= (long)np / 200);
        CHECK(maxd[run] < 1e-3);
    }
    CHECK(diff_valid[4] + ghost > obj_px / 4); /* the object list is what makes it right */
    /* errors: objects without ids, unsorted ids, a singular transform; nothing written */
    {
        sbl_reproject_desc rd;
        sbl_frame fr;
        sbl_history hi;
        sbl_object_motion two[2];
        sbl_diag dg;
        memset(&rd, 0, sizeof rd); memset(&fr, 0, sizeof fr); memset(&hi, 0, sizeof hi);
        fr.color = view(&col[1]); fr.gbuffer.depth = view(&dep[1]);
        hi.color = view(&col[0]); hi.length = view(&len); hi.gbuffer.depth = view(&dep[0]);
        fr.camera = &cam[1][1]; hi.camera = &cam[1][0];
        fr.objects = &om; fr.object_count = 1;
        img_fill(&out[0], 5.0f);
        CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&out[0]), view(&on[0]), 0, h), SBL_ERROR_MISSING_INPUT);
        fr.gbuffer.ids = view(&ids[1]);
        two[0] = om; two[1] = om;   /* the same id twice */
        fr.objects = two; fr.object_count = 2;
        CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&out[0]), view(&on[0]), 0, h), SBL_ERROR_INVALID_PARAM);
        two[1].id = 3.0f;
        memset(two[1].object_to_world, 0, sizeof two[1].object_to_world);
        CHECK_EQ(sbl_reproject_temporal(&rd, SBL_TEMPORAL_CAMERA, &fr, &hi, view(&out[0]), view(&on[0]), 0, h), SBL_ERROR_INVALID_PARAM);
        CHECK(*sbt_at(&out[0], 4, 4) == 5.0f);
        {   /* the validation names it */
            sbl_temporal_desc td;
            sbl_temporal_output to;
            memset(&td, 0, sizeof td); memset(&to, 0, sizeof to);
            td.source = SBL_TEMPORAL_CAMERA;
            to.color = view(&out[0]); to.length = view(&on[0]);
            CHECK_EQ(sbl_temporal_validate(&td, &fr, &hi, &to, &dg), SBL_ERROR_INVALID_PARAM);
            EXPECT_DIAG(dg, SBL_ERROR_INVALID_PARAM, "frame->objects", "sorted");
            fr.gbuffer.ids.data = NULL;
            CHECK_EQ(sbl_temporal_validate(&td, &fr, &hi, &to, &dg), SBL_ERROR_MISSING_INPUT);
            EXPECT_DIAG(dg, SBL_ERROR_MISSING_INPUT, "frame->gbuffer.ids", NULL);
        }
    }
    for (t = 0; t < 2; ++t) { free(col[t].mem); free(dep[t].mem); free(ids[t].mem); }
    for (run = 0; run < 5; ++run) { free(out[run].mem); free(on[run].mem); }
    free(mv.mem); free(len.mem);
}

/* The stereo blend on every layout: bit-identical to tight buffers, except that an own N
   with a pixel step takes the (double) reference path everywhere: equal within float
   rounding. */
static void test_buffers_stereo(void)
{
    const int w = 40, h = 24;
    const size_t np = (size_t)w * h;
    pair p;
    float *tight[2][3], *ref[3], *got = (float *)malloc(np * 3 * sizeof(float));
    int e, mode, k;
    size_t i;
    sbt_rng rng = {3};
    pair_init(&p, w, h);
    pair_render(&p);
    for (e = 0; e < 2; ++e) {
        tight[e][0] = (float *)malloc(np * 3 * sizeof(float));
        tight[e][1] = (float *)malloc(np * sizeof(float));
        tight[e][2] = (float *)malloc(np * sizeof(float));
        for (i = 0; i < np; ++i) {
            int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
            for (k = 0; k < 3; ++k) tight[e][0][i * 3 + k] = sbt_at(&p.col[e], x, y)[k] + (float)(0.05 * sbt_gauss(&rng));
            tight[e][1][i] = (float)(1 + (int)(sbt_uniform(&rng) * 6));
            tight[e][2][i] = *sbt_at(&p.dep[e], x, y);
        }
    }
    for (k = 0; k < 3; ++k) ref[k] = (float *)malloc(np * 3 * sizeof(float));
    for (mode = 0; mode < LAY_COUNT; ++mode) {
        lay in[2][3], out[3];
        sbl_stereo_desc d;
        sbl_eye eye[2];
        sbl_stereo_output so;
        size_t bytes = sbl_stereo_scratch_size(w, 3);
        void *scratch = malloc(bytes);
        memset(&d, 0, sizeof d); memset(eye, 0, sizeof eye); memset(&so, 0, sizeof so);
        d.rig = SBL_RIG_PARALLEL; d.focal_px = (float)p.f; d.baseline = (float)p.b;
        d.disparity_offset = (float)(p.cx[1] - p.cx[0]);
        for (e = 0; e < 2; ++e) {
            in[e][0] = lay_new(w, h, 3, mode, tight[e][0]);
            in[e][1] = lay_new(w, h, 1, mode, tight[e][1]);
            in[e][2] = lay_new(w, h, 1, mode, tight[e][2]);
            eye[e].color = in[e][0].im; eye[e].length = in[e][1].im; eye[e].gbuffer.depth = in[e][2].im;
        }
        out[0] = lay_new(w, h, 3, mode, NULL); out[1] = lay_new(w, h, 1, mode, NULL); out[2] = lay_new(w, h, 1, mode, NULL);
        so.color = out[0].im; so.length = out[1].im; so.beta = out[2].im;
        CHECK_EQ(sbl_stereo_filter(&d, SBL_EYE_LEFT, &eye[0], &eye[1], &so, 0, h, scratch, bytes), SBL_OK);
        for (k = 0; k < 3; ++k) {
            size_t n = np * (k ? 1u : 3u), j;
            if (mode == 0) { lay_read(&out[k], ref[k]); continue; }
            lay_read(&out[k], got);
            if (mode == LAY_CHANNEL || mode == LAY_CHANNEL_BOTTOM_UP) {
                double md = 0.0;
                for (j = 0; j < n; ++j) {
                    double dd = fabs(got[j] - ref[k][j]) / (fabs(ref[k][j]) + 1.0);
                    if (dd > md) md = dd;
                }
                CHECK(md < 1e-5);
            } else {
                CHECK(memcmp(got, ref[k], n * sizeof(float)) == 0);
            }
        }
        for (e = 0; e < 2; ++e) for (k = 0; k < 3; ++k) free(in[e][k].mem);
        for (k = 0; k < 3; ++k) free(out[k].mem);
        free(scratch);
    }
    for (e = 0; e < 2; ++e) for (k = 0; k < 3; ++k) free(tight[e][k]);
    for (k = 0; k < 3; ++k) free(ref[k]);
    free(got);
    pair_free(&p);
}

int main(void)
{
    test_disparity_sign();
    test_rigs_agree();
    test_axes();
    test_middlebury();
    test_disabled_tests();
    test_beta();
    test_buffers();
    test_buffers_stereo();
    test_diagnostics();
    test_temporal_cameras();
    return sbt_finish("test_engine");
}
