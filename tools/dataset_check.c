/* dataset_check.c - verify numerically, on a real scene directory, the
 * conventions sbl_dataset.h promises (stereo disparity sign, motion-vector
 * sign, camera matrices, noisy/ref agreement) and time the loader.
 *
 *   dataset_check [DIR]      (default ../shared/data/atrium)
 *
 * Prints the measurements and ends with "dataset_check: N passed, M failed";
 * exits nonzero if any check failed. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime */

#include "sbl_dataset.h"
#include "sbl_exr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int g_pass, g_fail;

static void check(int ok, const char *what)
{
    printf("  [%s] %s\n", ok ? "PASS" : "FAIL", what);
    if (ok) ++g_pass; else ++g_fail;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void mat_vec(const float m[16], const double x[4], double y[4])
{
    int r;
    for (r = 0; r < 4; ++r)
        y[r] = m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3] * x[3];
}

/* Pixel-centre coordinates (u, v) with planar depth z -> world point, using
 * proj (inverted for x, y at fixed camera z = -z) and cam_to_world. */
static int unproject(const sbl_dataset *ds, int f, int e, double u, double v, double z, double world[3])
{
    const float *P = ds->proj[f][e];
    double nx = 2.0 * u / ds->width - 1.0, ny = 1.0 - 2.0 * v / ds->height;
    double a[4], b[4], det, cam[4], w[4];
    int i;
    for (i = 0; i < 4; ++i) {
        a[i] = P[i] - nx * P[12 + i];
        b[i] = P[4 + i] - ny * P[12 + i];
    }
    /* a0 x + a1 y = -(a2 (-z) + a3), same for b. */
    det = a[0] * b[1] - a[1] * b[0];
    if (fabs(det) < 1e-12) return -1;
    {
        double ra = -(a[2] * -z + a[3]), rb = -(b[2] * -z + b[3]);
        cam[0] = (ra * b[1] - a[1] * rb) / det;
        cam[1] = (a[0] * rb - ra * b[0]) / det;
    }
    cam[2] = -z;
    cam[3] = 1.0;
    mat_vec(ds->cam_to_world[f][e], cam, w);
    world[0] = w[0] / w[3];
    world[1] = w[1] / w[3];
    world[2] = w[2] / w[3];
    return 0;
}

/* World point -> pixel coordinates and planar depth in camera (f, e). */
static int project(const sbl_dataset *ds, int f, int e, const double world[3], double *u, double *v, double *depth)
{
    double x[4], cam[4], clip[4];
    x[0] = world[0]; x[1] = world[1]; x[2] = world[2]; x[3] = 1.0;
    mat_vec(ds->world_to_cam[f][e], x, cam);
    mat_vec(ds->proj[f][e], cam, clip);
    if (!(clip[3] > 1e-9)) return -1;
    *u = (clip[0] / clip[3] + 1.0) * 0.5 * ds->width;
    *v = (1.0 - clip[1] / clip[3]) * 0.5 * ds->height;
    *depth = -cam[2];
    return 0;
}

static int valid_depth(float z) { return z > 0.0f && z < 1e9f; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, size_t n)
{
    if (!n) return 0.0;
    qsort(v, n, sizeof(double), cmp_double);
    return v[n / 2];
}

static double percentile(double *sorted, size_t n, double p)
{
    size_t k;
    if (!n) return 0.0;
    k = (size_t)(p * (double)(n - 1));
    return sorted[k];
}

/* ---------------------------------------------------------------------- */

static void check_cameras(const sbl_dataset *ds)
{
    double inv_err = 0, fx_err = 0, fy_err = 0, base_err = 0, base_perp = 0, cx_err = 0;
    int f, e, r, c, k;
    printf("cameras:\n");
    for (f = 0; f < ds->frames; ++f) {
        for (e = 0; e < 2; ++e) {
            const float *A = ds->world_to_cam[f][e], *B = ds->cam_to_world[f][e], *P = ds->proj[f][e];
            for (r = 0; r < 4; ++r)
                for (c = 0; c < 4; ++c) {
                    double s = 0;
                    for (k = 0; k < 4; ++k) s += (double)A[4 * r + k] * B[4 * k + c];
                    s -= (r == c);
                    if (fabs(s) > inv_err) inv_err = fabs(s);
                }
            /* OpenGL projection: P00 = 2 fx / W, P11 = 2 fy / H, principal point centred. */
            fx_err = fmax(fx_err, fabs(P[0] * ds->width * 0.5 / ds->focal_px[f][e] - 1.0));
            fy_err = fmax(fy_err, fabs(P[5] * ds->height * 0.5 / ds->focal_px[f][e] - 1.0));
            cx_err = fmax(cx_err, fmax(fabs(P[2]), fabs(P[6])));
        }
        {
            /* R centre - L centre, in L's camera axes (columns of cam_to_world). */
            const float *L = ds->cam_to_world[f][0], *R = ds->cam_to_world[f][1];
            double d[3], along = 0, perp2 = 0, proj_k;
            for (k = 0; k < 3; ++k) d[k] = (double)R[4 * k + 3] - L[4 * k + 3];
            for (k = 0; k < 3; ++k) along += d[k] * L[4 * k + 0];
            for (c = 1; c < 3; ++c) {
                proj_k = 0;
                for (k = 0; k < 3; ++k) proj_k += d[k] * L[4 * k + c];
                perp2 += proj_k * proj_k;
            }
            base_err = fmax(base_err, fabs(along - ds->baseline));
            base_perp = fmax(base_perp, sqrt(perp2));
        }
    }
    printf("  max |world_to_cam*cam_to_world - I| = %.3g\n", inv_err);
    printf("  max rel. error of focal_px vs proj: fx %.3g, fy %.3g; max |principal offset term| %.3g\n",
           fx_err, fy_err, cx_err);
    printf("  R-L camera centre along L +x: max |d - baseline(%.4f)| = %.3g m, max off-axis %.3g m\n",
           ds->baseline, base_err, base_perp);
    check(inv_err < 1e-4, "world_to_cam is the inverse of cam_to_world");
    check(fx_err < 1e-4 && fy_err < 1e-4 && cx_err < 1e-6, "proj agrees with focal_px, centred principal point");
    check(base_err < 1e-4 && base_perp < 1e-4, "R eye = L eye moved by baseline along camera +x");
}

static void check_projection(const sbl_dataset *ds, const sbl_dataset_frame *fr, int f, int e,
                             double *max_err, double *sum_err, long *count, double *max_pinhole)
{
    int i, j, W = ds->width, H = ds->height;
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            float z = fr->depth[j * W + i];
            double u = i + 0.5, v = j + 0.5, wpt[3], pu, pv, pz, err, cam[4], x[4];
            if (!valid_depth(z)) continue;
            if (unproject(ds, f, e, u, v, z, wpt) || project(ds, f, e, wpt, &pu, &pv, &pz)) continue;
            err = hypot(pu - u, pv - v);
            *max_err = fmax(*max_err, err);
            *sum_err += err;
            ++*count;
            /* The pinhole model of the README: x_cam = (u - W/2) z / f. */
            x[0] = wpt[0]; x[1] = wpt[1]; x[2] = wpt[2]; x[3] = 1;
            mat_vec(ds->world_to_cam[f][e], x, cam);
            *max_pinhole = fmax(*max_pinhole, fabs(cam[0] - (u - 0.5 * W) * z / ds->focal_px[f][e]) / z);
            *max_pinhole = fmax(*max_pinhole, fabs(cam[1] + (v - 0.5 * H) * z / ds->focal_px[f][e]) / z);
            *max_pinhole = fmax(*max_pinhole, fabs(pz - z) / z);
        }
}

/* Stereo: left pixel with depth z matches right pixel (u - f b / z, v).
 * sign = +1 tests that rule, -1 the opposite for contrast. */
typedef struct { long n, id_ok, depth_ok; double formula_vs_3d_max; } stereo_stats;

static void check_stereo(const sbl_dataset *ds, const sbl_dataset_frame *L, const sbl_dataset_frame *R, int f,
                         double sign, stereo_stats *st)
{
    int i, j, W = ds->width, H = ds->height;
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            float z = L->depth[j * W + i];
            double u = i + 0.5, v = j + 0.5, d, ur;
            int ir;
            if (!valid_depth(z)) continue;
            d = ds->focal_px[f][0] * ds->baseline / z;
            ur = u - sign * d;
            ir = (int)floor(ur);
            if (ir < 0 || ir >= W) continue;
            ++st->n;
            if (R->id[j * W + ir] == L->id[j * W + i]) ++st->id_ok;
            if (fabs(R->depth[j * W + ir] - z) < 0.01 * z) ++st->depth_ok;
            if (sign > 0) {
                double wpt[3], pu, pv, pz;
                if (!unproject(ds, f, 0, u, v, z, wpt) && !project(ds, f, 1, wpt, &pu, &pv, &pz))
                    st->formula_vs_3d_max = fmax(st->formula_vs_3d_max, hypot(pu - ur, pv - v));
            }
        }
}

/* Motion: pixel (u, v) of frame t was at (u + mx, v + my) in frame t-1.
 * ysign = +1 tests the converted vectors, -1 the unflipped Blender Y. */
typedef struct { long n, id_ok, depth_ok, n_static, reproj_ok; double *reproj; size_t nre; } motion_stats;

static void check_motion(const sbl_dataset *ds, const sbl_dataset_frame *cur, const sbl_dataset_frame *prev,
                         int f, int e, double ysign, motion_stats *st)
{
    int i, j, W = ds->width, H = ds->height;
    for (j = 0; j < H; ++j)
        for (i = 0; i < W; ++i) {
            size_t p = (size_t)j * W + i;
            float z = cur->depth[p];
            double u = i + 0.5, v = j + 0.5, up, vp, wpt[3], pu, pv, pz;
            int ip, jp, have3d;
            if (!valid_depth(z)) continue;
            up = u + cur->motion[2 * p];
            vp = v + ysign * cur->motion[2 * p + 1];
            ip = (int)floor(up);
            jp = (int)floor(vp);
            if (ip < 0 || ip >= W || jp < 0 || jp >= H) continue;
            ++st->n;
            if (prev->id[(size_t)jp * W + ip] == cur->id[p]) ++st->id_ok;
            /* Depth the point had in frame t-1 (static scene assumption);
             * compared with the depth stored where the vector points. */
            have3d = !unproject(ds, f, e, u, v, z, wpt) && !project(ds, f - 1, e, wpt, &pu, &pv, &pz);
            if (have3d && fabs(prev->depth[(size_t)jp * W + ip] - pz) < 0.01 * pz) ++st->depth_ok;
            if (ysign > 0 && have3d) {
                /* Static geometry: the vector must equal the camera reprojection. */
                double err = hypot(pu - up, pv - vp);
                st->reproj[st->nre++] = err;
                if (err < 0.05) ++st->reproj_ok;
            }
        }
}

static void mean_rgb(const float *img, size_t np, double m[3])
{
    size_t i;
    m[0] = m[1] = m[2] = 0;
    for (i = 0; i < np; ++i) {
        m[0] += img[3 * i];
        m[1] += img[3 * i + 1];
        m[2] += img[3 * i + 2];
    }
    m[0] /= (double)np; m[1] /= (double)np; m[2] /= (double)np;
}

static double mse_rgb(const float *a, const float *b, size_t np)
{
    size_t i;
    double s = 0;
    for (i = 0; i < 3 * np; ++i) s += ((double)a[i] - b[i]) * ((double)a[i] - b[i]);
    return s / (3.0 * (double)np);
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "../shared/data/atrium";
    sbl_dataset ds;
    sbl_dataset_frame *fr;
    char err[512];
    int f, e, c, k;
    size_t np;
    double t0, t_load;
    stereo_stats st, st_wrong;
    motion_stats mo, mo_wrong;
    double proj_max = 0, proj_sum = 0, pin_max = 0;
    long proj_n = 0;
    double zmax = 0, relmax = 0, mean_n_all[3] = { 0, 0, 0 }, mean_r_all[3] = { 0, 0, 0 };
    int have_ref = 1;

    if (!sbl_exr_available()) {
        printf("dataset_check: built without OpenEXR; nothing to check\n");
        return 0;
    }
    t0 = now_s();
    if (sbl_dataset_open(&ds, dir, err, (int)sizeof(err))) {
        fprintf(stderr, "dataset_check: %s\n", err);
        return 1;
    }
    printf("%s: %d frames, %dx%d, ref_spp %d, baseline %.4f m, focal_px %.3f, clip [%g, %g]\n", ds.dir, ds.frames,
           ds.width, ds.height, ds.ref_spp, ds.baseline, ds.focal_px[0][0], ds.clip_near, ds.clip_far);
    printf("  ladder frames:");
    for (k = 0; k < ds.ladder_frame_count; ++k) printf(" %d", ds.ladder_frames[k]);
    printf("; ladder spp:");
    for (k = 0; k < ds.ladder_spp_count; ++k) printf(" %d", ds.ladder_spp[k]);
    printf(" (json parse %.1f ms)\n", 1e3 * (now_s() - t0));
    np = (size_t)ds.width * ds.height;

    check_cameras(&ds);

    /* Load everything once (also the timing measurement). */
    fr = (sbl_dataset_frame *)calloc((size_t)ds.frames * 2, sizeof(*fr));
    if (!fr) return 1;
    t0 = now_s();
    for (f = 0; f < ds.frames; ++f)
        for (e = 0; e < 2; ++e)
            if (sbl_dataset_load(&ds, f, e, &fr[2 * f + e], err, (int)sizeof(err))) {
                fprintf(stderr, "dataset_check: %s\n", err);
                return 1;
            }
    t_load = now_s() - t0;
    printf("load: %d frame/eye pairs (noisy + ref + gbuf, %d EXR files) in %.3f s = %.1f ms per frame and eye\n",
           2 * ds.frames, 6 * ds.frames, t_load, 1e3 * t_load / (2.0 * ds.frames));

    printf("projection round trip (pixel centre + depth -> world via cam_to_world/proj -> pixel):\n");
    for (f = 0; f < ds.frames; ++f)
        for (e = 0; e < 2; ++e)
            check_projection(&ds, &fr[2 * f + e], f, e, &proj_max, &proj_sum, &proj_n, &pin_max);
    printf("  %ld pixels: max %.2e px, mean %.2e px; pinhole x=(u-W/2)z/f, y=-(v-H/2)z/f, depth: max rel. err %.2e\n",
           proj_n, proj_max, proj_n ? proj_sum / proj_n : 0.0, pin_max);
    check(proj_n > 0 && proj_max < 1e-2, "unproject/project round trip < 0.01 px");
    check(pin_max < 1e-4, "proj/world_to_cam match the pinhole model with focal_px, planar depth");

    printf("stereo (left pixel (u,v), depth z -> right pixel (u - focal_px*baseline/z, v)):\n");
    memset(&st, 0, sizeof(st));
    memset(&st_wrong, 0, sizeof(st_wrong));
    for (f = 0; f < ds.frames; ++f) {
        check_stereo(&ds, &fr[2 * f], &fr[2 * f + 1], f, +1.0, &st);
        check_stereo(&ds, &fr[2 * f], &fr[2 * f + 1], f, -1.0, &st_wrong);
    }
    printf("  u - d: %ld pixels, same IndexOB %.2f%%, depth within 1%% %.2f%%; formula vs 3-D reprojection max %.3f px\n",
           st.n, 100.0 * st.id_ok / (st.n ? st.n : 1), 100.0 * st.depth_ok / (st.n ? st.n : 1), st.formula_vs_3d_max);
    printf("  u + d (wrong sign, for contrast): same IndexOB %.2f%%, depth within 1%% %.2f%%\n",
           100.0 * st_wrong.id_ok / (st_wrong.n ? st_wrong.n : 1),
           100.0 * st_wrong.depth_ok / (st_wrong.n ? st_wrong.n : 1));
    check(st.n > 0 && st.id_ok > 0.9 * st.n && st.depth_ok > 0.9 * st.n, "stereo match (u - f b / z, v) for > 90% of pixels");
    check(st.formula_vs_3d_max < 0.01, "disparity formula = reprojection through the right camera");
    check(st.n - st.depth_ok < (st_wrong.n - st_wrong.depth_ok) / 3, "opposite disparity sign: > 3x more depth mismatches");

    printf("motion (pixel (u,v) of frame t was at (u + mx, v + my) in frame t-1, y down):\n");
    memset(&mo, 0, sizeof(mo));
    memset(&mo_wrong, 0, sizeof(mo_wrong));
    mo.reproj = (double *)malloc(sizeof(double) * np * 2 * (size_t)ds.frames);
    if (!mo.reproj) return 1;
    for (f = 1; f < ds.frames; ++f)
        for (e = 0; e < 2; ++e) {
            check_motion(&ds, &fr[2 * f + e], &fr[2 * (f - 1) + e], f, e, +1.0, &mo);
            check_motion(&ds, &fr[2 * f + e], &fr[2 * (f - 1) + e], f, e, -1.0, &mo_wrong);
        }
    {
        double med = median(mo.reproj, mo.nre);
        printf("  (u+mx, v+my): %ld pixels, same IndexOB %.2f%%, depth = reprojected depth within 1%% %.2f%%\n",
               mo.n, 100.0 * mo.id_ok / (mo.n ? mo.n : 1), 100.0 * mo.depth_ok / (mo.n ? mo.n : 1));
        printf("  vector vs camera reprojection of the static scene: median %.4f px, 90%% %.4f px, 99%% %.3f px,"
               " within 0.05 px %.2f%%\n", med, percentile(mo.reproj, mo.nre, 0.90),
               percentile(mo.reproj, mo.nre, 0.99), 100.0 * mo.reproj_ok / (mo.nre ? (double)mo.nre : 1.0));
        printf("  (u+mx, v-my) (Blender Y unflipped, for contrast): same IndexOB %.2f%%, depth within 1%% %.2f%%\n",
               100.0 * mo_wrong.id_ok / (mo_wrong.n ? mo_wrong.n : 1),
               100.0 * mo_wrong.depth_ok / (mo_wrong.n ? mo_wrong.n : 1));
        check(mo.n > 0 && mo.id_ok > 0.9 * mo.n && mo.depth_ok > 0.9 * mo.n, "motion vectors land on the same surface for > 90% of pixels");
        check(med < 0.01 && mo.reproj_ok > 0.9 * mo.nre, "motion vectors = camera reprojection (static scene) to < 0.05 px for > 90%");
        check(mo.n - mo.depth_ok < (mo_wrong.n - mo_wrong.depth_ok) / 3, "unflipped Y: > 3x more depth mismatches");
    }
    free(mo.reproj);

    printf("noisy (1 spp) vs ref means per frame and eye (z = diff / standard error of the noisy mean):\n");
    for (f = 0; f < ds.frames && have_ref; ++f)
        for (e = 0; e < 2; ++e) {
            const sbl_dataset_frame *x = &fr[2 * f + e];
            double mn[3], mr[3], var[3] = { 0, 0, 0 };
            size_t i;
            if (!x->ref) { have_ref = 0; break; }
            mean_rgb(x->noisy, np, mn);
            mean_rgb(x->ref, np, mr);
            for (i = 0; i < np; ++i)
                for (c = 0; c < 3; ++c) {
                    double d = (double)x->noisy[3 * i + c] - x->ref[3 * i + c] - (mn[c] - mr[c]);
                    var[c] += d * d;
                }
            for (c = 0; c < 3; ++c) {
                double se = sqrt(var[c] / (double)(np - 1) / (double)np);
                double z = (mn[c] - mr[c]) / (se > 0 ? se : 1e-30);
                zmax = fmax(zmax, fabs(z));
                relmax = fmax(relmax, fabs(mn[c] - mr[c]) / fmax(mr[c], 1e-6));
                mean_n_all[c] += mn[c];
                mean_r_all[c] += mr[c];
            }
            if (f % 8 == 0 || f == ds.frames - 1)
                printf("  f%02d %c: noisy %.5f %.5f %.5f  ref %.5f %.5f %.5f\n", f, e ? 'R' : 'L', mn[0], mn[1], mn[2],
                       mr[0], mr[1], mr[2]);
        }
    if (have_ref) {
        for (c = 0; c < 3; ++c) { mean_n_all[c] /= 2.0 * ds.frames; mean_r_all[c] /= 2.0 * ds.frames; }
        printf("  all frames: noisy %.5f %.5f %.5f  ref %.5f %.5f %.5f; max |z| %.2f, max rel. diff %.2f%%\n",
               mean_n_all[0], mean_n_all[1], mean_n_all[2], mean_r_all[0], mean_r_all[1], mean_r_all[2], zmax,
               100.0 * relmax);
        check(zmax < 5.0, "frame means of noisy and ref agree within noise (|z| < 5)");
    } else {
        printf("  no ref renders\n");
    }

    if (have_ref) {
        /* Residual (noisy - ref) correlation at stereo and motion matches:
         * filters rely on independent noise between eyes and frames. */
        double sxy[2] = { 0, 0 }, sxx[2] = { 0, 0 }, syy[2] = { 0, 0 };
        int i, j, W = ds.width, H = ds.height;
        for (f = 0; f < ds.frames; ++f)
            for (j = 0; j < H; ++j)
                for (i = 0; i < W; ++i) {
                    const sbl_dataset_frame *Lf = &fr[2 * f], *Rf = &fr[2 * f + 1];
                    size_t p = (size_t)j * W + i, q;
                    float z = Lf->depth[p];
                    int ir, ip, jp;
                    if (!valid_depth(z)) continue;
                    ir = (int)floor(i + 0.5 - ds.focal_px[f][0] * ds.baseline / z);
                    if (ir >= 0 && ir < W && Rf->id[(size_t)j * W + ir] == Lf->id[p]) {
                        q = (size_t)j * W + ir;
                        for (c = 0; c < 3; ++c) {
                            double a = Lf->noisy[3 * p + c] - Lf->ref[3 * p + c], b = Rf->noisy[3 * q + c] - Rf->ref[3 * q + c];
                            sxy[0] += a * b; sxx[0] += a * a; syy[0] += b * b;
                        }
                    }
                    if (f == 0) continue;
                    ip = (int)floor(i + 0.5 + Lf->motion[2 * p]);
                    jp = (int)floor(j + 0.5 + Lf->motion[2 * p + 1]);
                    if (ip >= 0 && ip < W && jp >= 0 && jp < H && fr[2 * (f - 1)].id[(size_t)jp * W + ip] == Lf->id[p]) {
                        const sbl_dataset_frame *Pf = &fr[2 * (f - 1)];
                        q = (size_t)jp * W + ip;
                        for (c = 0; c < 3; ++c) {
                            double a = Lf->noisy[3 * p + c] - Lf->ref[3 * p + c], b = Pf->noisy[3 * q + c] - Pf->ref[3 * q + c];
                            sxy[1] += a * b; sxx[1] += a * a; syy[1] += b * b;
                        }
                    }
                }
        {
            double cs = sxy[0] / sqrt(sxx[0] * syy[0] + 1e-300), ct = sxy[1] / sqrt(sxx[1] * syy[1] + 1e-300);
            printf("noise independence: corr(noisy - ref) L vs R at stereo matches %.4f, frame t vs t-1 (L) at motion matches %.4f\n",
                   cs, ct);
            check(fabs(cs) < 0.1 && fabs(ct) < 0.1, "1-spp noise uncorrelated between eyes and frames (|corr| < 0.1)");
        }
    }

    if (have_ref && ds.ladder_frame_count > 0) {
        int lf = ds.ladder_frames[0];
        double mse1 = mse_rgb(fr[2 * lf].noisy, fr[2 * lf].ref, np), prev = mse1;
        int monotone = 1, got = 0;
        printf("ladder (frame %d, L): MSE vs ref, 1 spp noisy = %.5f\n", lf, mse1);
        for (k = 0; k < ds.ladder_spp_count; ++k) {
            float *lad = NULL;
            double m;
            if (sbl_dataset_load_ladder(&ds, lf, 0, ds.ladder_spp[k], &lad, err, (int)sizeof(err))) {
                printf("  %3d spp: %s\n", ds.ladder_spp[k], err);
                continue;
            }
            m = mse_rgb(lad, fr[2 * lf].ref, np);
            printf("  %3d spp: MSE %.6f  mse(1 spp)/mse = %.2f\n", ds.ladder_spp[k], m, mse1 / m);
            if (m > prev) monotone = 0;
            prev = m;
            ++got;
            free(lad);
        }
        check(got == ds.ladder_spp_count && monotone, "ladder renders load, MSE falls with spp");
    }

    for (k = 0; k < 2 * ds.frames; ++k) sbl_dataset_frame_free(&fr[k]);
    free(fr);
    sbl_dataset_close(&ds);
    printf("dataset_check: %d passed, %d failed\n", g_pass, g_fail);
    return g_fail ? 1 : 0;
}
