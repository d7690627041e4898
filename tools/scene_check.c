/* scene_check.c - self-check of tools/sbl_scene.h
 * build: cc -std=c99 -O2 -Itools tools/scene_check.c -lm
 * run:   ./a.out [-p]      (-p writes PPM previews to /tmp/sbl_scene_*.ppm)
 * Exits non-zero when any check fails; prints the measured numbers. */
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>

static int g_fail = 0;
#define CHECK(cond, ...) do { if (!(cond)) { printf("  FAIL (%s:%d): ", __FILE__, __LINE__); \
    printf(__VA_ARGS__); printf("\n"); g_fail++; } } while (0)

typedef struct bufs { sbl_scene_view v; int w, h; } bufs;

static void *xcalloc(size_t n, size_t s)
{
    void *p = calloc(n, s);
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

static void alloc_view(bufs *b, const sbl_scene_desc *d, int with_color, int with_ref)
{
    size_t n = (size_t)d->width * (size_t)d->height;
    memset(b, 0, sizeof(*b));
    b->w = d->width; b->h = d->height;
    if (with_color) b->v.color = (float *)xcalloc(n * 3, sizeof(float));
    if (with_ref) b->v.reference = (float *)xcalloc(n * 3, sizeof(float));
    b->v.depth = (float *)xcalloc(n, sizeof(float));
    b->v.normal = (float *)xcalloc(n * 3, sizeof(float));
    b->v.id = (float *)xcalloc(n, sizeof(float));
    b->v.motion = (float *)xcalloc(n * 2, sizeof(float));
}

static void free_view(bufs *b)
{
    free(b->v.color); free(b->v.reference); free(b->v.depth);
    free(b->v.normal); free(b->v.id); free(b->v.motion);
}

static int render(const sbl_scene_desc *d, int frame, int eye, bufs *b)
{
    return sbl_scene_render(d, frame, eye, &b->v, 0, d->height);
}

static int same(const float *a, const float *b, size_t n)
{
    if (!a && !b) return 1;
    if (!a || !b) return 0;
    return memcmp(a, b, n * sizeof(float)) == 0;
}

static int same_view(const bufs *a, const bufs *b)
{
    size_t n = (size_t)a->w * (size_t)a->h;
    return same(a->v.color, b->v.color, n * 3) && same(a->v.reference, b->v.reference, n * 3) &&
           same(a->v.depth, b->v.depth, n) && same(a->v.normal, b->v.normal, n * 3) &&
           same(a->v.id, b->v.id, n) && same(a->v.motion, b->v.motion, n * 2) &&
           memcmp(a->v.world_to_cam, b->v.world_to_cam, sizeof(a->v.world_to_cam)) == 0 &&
           memcmp(a->v.proj, b->v.proj, sizeof(a->v.proj)) == 0;
}

/* object id by name (the check does not rely on the header's numbering) */
static float id_of(const char *name)
{
    int i;
    for (i = 1; i <= sbl_scene_object_count(); ++i)
        if (strcmp(sbl_scene_object_name(i), name) == 0) return (float)i;
    printf("  no object named %s\n", name);
    g_fail++;
    return -1.0f;
}

static double now_s(void) { return (double)clock() / CLOCKS_PER_SEC; }

/* ---- matrix helpers (float matrices as the library will see them) ---- */

static void cam_to_world(const float *m, const double c[3], double p[3])
{
    /* m = [A t; 0 1], A orthonormal: p = A^T (c - t) */
    int i;
    for (i = 0; i < 3; ++i)
        p[i] = m[0 * 4 + i] * (c[0] - m[3]) + m[1 * 4 + i] * (c[1] - m[7]) + m[2 * 4 + i] * (c[2] - m[11]);
}

/* world -> pixel through proj * world_to_cam; returns clip w */
static double project(const sbl_scene_view *v, int W, int H, const double p[3], double *u, double *vv)
{
    double c[4], k[4];
    int r;
    for (r = 0; r < 4; ++r)
        c[r] = v->world_to_cam[r * 4] * p[0] + v->world_to_cam[r * 4 + 1] * p[1] + v->world_to_cam[r * 4 + 2] * p[2] + v->world_to_cam[r * 4 + 3];
    for (r = 0; r < 4; ++r)
        k[r] = v->proj[r * 4] * c[0] + v->proj[r * 4 + 1] * c[1] + v->proj[r * 4 + 2] * c[2] + v->proj[r * 4 + 3] * c[3];
    *u = (k[0] / k[3] + 1.0) * 0.5 * W;
    *vv = (1.0 - k[1] / k[3]) * 0.5 * H;
    return k[3];
}

static void unproject(const sbl_scene_view *v, int W, int H, double u, double vv, double z, double p[3])
{
    double c[3];
    c[0] = (u - 0.5 * W) * z / v->focal_px;
    c[1] = -(vv - 0.5 * H) * z / v->focal_px;
    c[2] = -z;
    cam_to_world(v->world_to_cam, c, p);
}

/* ---- previews ---- */

static unsigned char tone(double x)
{
    if (!(x > 0.0)) x = 0.0;
    x = x / (1.0 + x / 4.0);            /* soft shoulder so highlights stay visible */
    x = pow(x, 1.0 / 2.2);
    return (unsigned char)(x >= 1.0 ? 255 : x * 255.0 + 0.5);
}

static void write_ppm_rgb(const char *path, const float *c, int w, int h, int mode)
{
    FILE *f = fopen(path, "wb");
    int i;
    if (!f) return;
    fprintf(f, "P6\n%d %d\n255\n", w, h);
    for (i = 0; i < w * h; ++i) {
        unsigned char px[3];
        if (mode == 0) { px[0] = tone(c[i * 3]); px[1] = tone(c[i * 3 + 1]); px[2] = tone(c[i * 3 + 2]); }
        else if (mode == 1) {   /* depth */
            double z = c[i]; unsigned char g = (unsigned char)(z > 1e9 ? 0 : 255.0 / (1.0 + 0.3 * z));
            px[0] = px[1] = px[2] = g;
        } else if (mode == 2) { /* id */
            unsigned id = (unsigned)c[i];
            px[0] = (unsigned char)(id * 97u); px[1] = (unsigned char)(id * 57u + 40u); px[2] = (unsigned char)(id * 151u + 90u);
            if (!id) px[0] = px[1] = px[2] = 0;
        } else {                /* motion */
            double mx = c[i * 2], my = c[i * 2 + 1];
            px[0] = (unsigned char)(fmin(255.0, fmax(0.0, 128.0 + 12.0 * mx)));
            px[1] = (unsigned char)(fmin(255.0, fmax(0.0, 128.0 + 12.0 * my)));
            px[2] = 128;
        }
        fwrite(px, 1, 3, f);
    }
    fclose(f);
}

/* ---- checks ---- */

static void check_determinism(void)
{
    sbl_scene_desc d;
    bufs a, b, c;
    int y, r;
    size_t n, i, diff_frame = 0, diff_eye = 0, diff_seed = 0;
    printf("[1] determinism\n");
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_DYNAMIC; d.jitter = 1; d.seed = 7;
    sbl_scene_defaults(&d);
    d.ref_spp = 8;
    alloc_view(&a, &d, 1, 1); alloc_view(&b, &d, 1, 1); alloc_view(&c, &d, 1, 1);
    n = (size_t)d.width * (size_t)d.height;
    CHECK(render(&d, 5, 1, &a) == 0, "render failed");
    CHECK(render(&d, 5, 1, &b) == 0, "render failed");
    CHECK(same_view(&a, &b), "two renders differ");
    r = sbl_scene_render(&d, 5, 1, &c.v, 0, d.height / 2);
    r |= sbl_scene_render(&d, 5, 1, &c.v, d.height / 2, d.height);
    CHECK(r == 0 && same_view(&a, &c), "two halves differ from one full render");
    memset(c.v.color, 0, n * 3 * sizeof(float));
    for (y = d.height - 1; y >= 0; --y) r |= sbl_scene_render(&d, 5, 1, &c.v, y, y + 1);
    CHECK(r == 0 && same_view(&a, &c), "rows rendered bottom-up differ");
    /* noise must differ between frames, eyes and seeds (a static scene, so only noise changes) */
    d.kind = SBL_SCENE_STATIC;
    render(&d, 3, 0, &a); render(&d, 4, 0, &b); render(&d, 3, 1, &c);
    for (i = 0; i < n * 3; ++i) { diff_frame += a.v.color[i] != b.v.color[i]; diff_eye += a.v.color[i] != c.v.color[i]; }
    d.seed = 8;
    render(&d, 3, 0, &b);
    for (i = 0; i < n * 3; ++i) diff_seed += a.v.color[i] != b.v.color[i];
    CHECK(same(a.v.depth, b.v.depth, n) && same(a.v.motion, b.v.motion, n * 2), "seed changed the G-buffer");
    printf("  identical bytes on re-render, halves and bottom-up rows: %s\n", g_fail ? "NO" : "yes");
    printf("  colour values differing: frame 3 vs 4 %.1f%%, eye L vs R %.1f%%, seed 7 vs 8 %.1f%%\n",
           100.0 * diff_frame / (n * 3), 100.0 * diff_eye / (n * 3), 100.0 * diff_seed / (n * 3));
    CHECK(diff_frame > n * 3 * 8 / 10 && diff_seed > n * 3 * 8 / 10, "noise too similar across frames/seeds");
    /* bad arguments */
    CHECK(sbl_scene_render(&d, 0, 2, &a.v, 0, 1) != 0, "eye 2 accepted");
    CHECK(sbl_scene_render(&d, -1, 0, &a.v, 0, 1) != 0, "frame -1 accepted");
    CHECK(sbl_scene_render(&d, 0, 0, &a.v, 5, 4) != 0, "y0 > y1 accepted");
    CHECK(sbl_scene_render(&d, 0, 0, &a.v, 0, d.height + 1) != 0, "y1 > h accepted");
    CHECK(sbl_scene_render(NULL, 0, 0, &a.v, 0, 1) != 0, "NULL desc accepted");
    CHECK(sbl_scene_render_spp(&d, 0, 0, 0, a.v.color, 0, 1) != 0, "spp 0 accepted");
    free_view(&a); free_view(&b); free_view(&c);
}

static void check_stereo(void)
{
    sbl_scene_desc d;
    bufs L, R;
    int x, y, e;
    printf("[2] stereo correspondence (STATIC, frame 0): match of (u,v) at depth z is (u -/+ f b / z, v)\n");
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_STATIC;
    sbl_scene_defaults(&d);
    d.ref_spp = 256;
    alloc_view(&L, &d, 0, 1); alloc_view(&R, &d, 0, 1);
    render(&d, 0, 0, &L); render(&d, 0, 1, &R);
    CHECK(L.v.focal_px == R.v.focal_px && L.v.baseline == R.v.baseline, "eyes disagree on intrinsics");
    /* the right camera is the left one moved by +baseline along the left camera's +x */
    {
        double pl[3], pr[3], o[3] = { 0.0, 0.0, 0.0 }, dx;
        cam_to_world(L.v.world_to_cam, o, pl);
        cam_to_world(R.v.world_to_cam, o, pr);
        dx = (pr[0] - pl[0]) * L.v.world_to_cam[0] + (pr[1] - pl[1]) * L.v.world_to_cam[1] + (pr[2] - pl[2]) * L.v.world_to_cam[2];
        printf("  right eye offset along left +x: %.6f m (baseline %.4f)\n", dx, L.v.baseline);
        CHECK(fabs(dx - L.v.baseline) < 1e-5, "right eye is not at +baseline");
    }
    for (e = 0; e < 2; ++e) {
        const bufs *A = e ? &R : &L, *B = e ? &L : &R;
        double sgn = e ? 1.0 : -1.0, gl = 0.0, dl = 0.0;
        long valid = 0, ok = 0, inside = 0, ng = 0, nd = 0;
        for (y = 0; y < d.height; ++y) for (x = 0; x < d.width; ++x) {
            int i = y * d.width + x, j, xb;
            double z = A->v.depth[i], ub;
            if (z > 1e9) continue;
            valid++;
            ub = x + 0.5 + sgn * A->v.focal_px * A->v.baseline / z;
            xb = (int)floor(ub);
            if (xb < 0 || xb >= d.width) continue;
            inside++;
            j = y * d.width + xb;
            if (B->v.id[j] == A->v.id[i] && fabs(B->v.depth[j] - z) < 0.02 * z) {
                int c;
                double s = 0.0;
                ok++;
                for (c = 0; c < 3; ++c) s += fabs(A->v.reference[i * 3 + c] - B->v.reference[j * 3 + c]);
                /* view-dependent shading: the glossy/metal spheres vs the diffuse crates */
                if (A->v.id[i] == id_of("glossy_sphere") || A->v.id[i] == id_of("metal_sphere")) { gl += s; ng++; }
                if (A->v.id[i] == id_of("crate0") || A->v.id[i] == id_of("crate1") || A->v.id[i] == id_of("crate2")) { dl += s; nd++; }
            }
        }
        printf("  %s->%s: %ld surface px, %ld land inside, %.2f%% of those match depth (2%%) and id\n",
               e ? "R" : "L", e ? "L" : "R", valid, inside, 100.0 * ok / (inside ? inside : 1));
        printf("    mean |ref - matched ref| (sum RGB): glossy/metal spheres %.4f (%ld px), diffuse crates %.4f (%ld px)\n",
               ng ? gl / ng : 0.0, ng, nd ? dl / nd : 0.0, nd);
        CHECK(ok > inside * 9 / 10, "stereo match share too low");
        CHECK(ng > 0 && nd > 0 && gl / ng > dl / nd, "glossy surfaces are not more view dependent than diffuse ones");
    }
    free_view(&L); free_view(&R);
}

static void check_motion(sbl_scene_kind kind, int jitter, const char *name)
{
    sbl_scene_desc d;
    bufs P, C;
    int f, e, x, y;
    long valid = 0, inside = 0, ok = 0, nstatic = 0, nonzero = 0;
    double maxerr = 0.0, maxmag = 0.0;
    float ball = id_of("ball");
    memset(&d, 0, sizeof(d));
    d.kind = kind; d.jitter = jitter;
    sbl_scene_defaults(&d);
    alloc_view(&P, &d, 0, 0); alloc_view(&C, &d, 0, 0);
    for (e = 0; e < 2; ++e) {
        render(&d, 0, e, &P);
        for (f = 1; f < d.frames; ++f) {
            render(&d, f, e, &C);
            for (y = 0; y < d.height; ++y) for (x = 0; x < d.width; ++x) {
                int i = y * d.width + x, j, xp, yp;
                double mx = C.v.motion[i * 2], my = C.v.motion[i * 2 + 1], z = C.v.depth[i], up, vp;
                if (mx != 0.0f || my != 0.0f) nonzero++;
                if (fabs(mx) > maxmag) maxmag = fabs(mx);
                if (fabs(my) > maxmag) maxmag = fabs(my);
                if (z > 1e9) continue;
                valid++;
                up = x + 0.5 + mx; vp = y + 0.5 + my;
                xp = (int)floor(up); yp = (int)floor(vp);
                if (C.v.id[i] != ball) {
                    /* static geometry: the vector must equal the one from the matrices exactly */
                    double p[3], u2, v2, zp;
                    unproject(&C.v, d.width, d.height, x + 0.5, y + 0.5, z, p);
                    zp = project(&P.v, d.width, d.height, p, &u2, &v2);
                    nstatic++;
                    if (fabs(u2 - up) > maxerr) maxerr = fabs(u2 - up);
                    if (fabs(v2 - vp) > maxerr) maxerr = fabs(v2 - vp);
                    z = zp;   /* expected depth in the previous frame */
                }
                if (xp < 0 || yp < 0 || xp >= d.width || yp >= d.height) continue;
                inside++;
                j = yp * d.width + xp;
                if (P.v.id[j] == C.v.id[i] && fabs(P.v.depth[j] - z) < 0.05 * z) ok++;
            }
            { bufs t = P; P = C; C = t; }
        }
    }
    printf("  %-22s %ld surface px over %d frame pairs x 2 eyes; %.2f%% land inside; of those %.2f%% hit same id and depth (5%%)\n",
           name, valid, d.frames - 1, 100.0 * inside / (valid ? valid : 1), 100.0 * ok / (inside ? inside : 1));
    printf("  %-22s max |mv - mv from matrices| on static geometry %.2e px (%ld px), max |mv| %.2f px, nonzero %ld\n",
           "", maxerr, nstatic, maxmag, nonzero);
    if (kind == SBL_SCENE_SHADOW || kind == SBL_SCENE_STATIC) {
        CHECK(nonzero == 0, "%s: motion vectors are not exactly 0", name);
    } else {
        CHECK(ok > inside * 9 / 10, "%s: too few motion vectors land on the same surface", name);
        CHECK(maxerr < 0.01, "%s: motion disagrees with the camera matrices", name);
        CHECK(nonzero > 0, "%s: no motion", name);
    }
    free_view(&P); free_view(&C);
}

/* bg_motion = 1: the sky moves with the camera rotation only */
static void check_bg_motion(void)
{
    sbl_scene_desc d;
    bufs P, C;
    int f, x, y, r;
    long nbg = 0;
    double maxerr = 0.0;
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_DYNAMIC; d.jitter = 1; d.bg_motion = 1;
    sbl_scene_defaults(&d);
    alloc_view(&P, &d, 0, 0); alloc_view(&C, &d, 0, 0);
    render(&d, 0, 0, &P);
    for (f = 1; f < d.frames; ++f) {
        render(&d, f, 0, &C);
        for (y = 0; y < d.height; ++y) for (x = 0; x < d.width; ++x) {
            int i = y * d.width + x;
            double dc[3], dw[3], q[3], u, v;
            if (C.v.depth[i] < 1e9) continue;
            dc[0] = (x + 0.5 - 0.5 * d.width) / C.v.focal_px; dc[1] = -(y + 0.5 - 0.5 * d.height) / C.v.focal_px; dc[2] = -1.0;
            for (r = 0; r < 3; ++r) dw[r] = C.v.world_to_cam[r] * dc[0] + C.v.world_to_cam[4 + r] * dc[1] + C.v.world_to_cam[8 + r] * dc[2];
            for (r = 0; r < 3; ++r) q[r] = P.v.world_to_cam[r * 4] * dw[0] + P.v.world_to_cam[r * 4 + 1] * dw[1] + P.v.world_to_cam[r * 4 + 2] * dw[2];
            u = 0.5 * d.width + P.v.focal_px * q[0] / -q[2];
            v = 0.5 * d.height - P.v.focal_px * q[1] / -q[2];
            nbg++;
            if (fabs(u - (x + 0.5 + C.v.motion[i * 2])) > maxerr) maxerr = fabs(u - (x + 0.5 + C.v.motion[i * 2]));
            if (fabs(v - (y + 0.5 + C.v.motion[i * 2 + 1])) > maxerr) maxerr = fabs(v - (y + 0.5 + C.v.motion[i * 2 + 1]));
        }
        { bufs t = P; P = C; C = t; }
    }
    printf("  %-22s %ld sky px: max |mv - rotation-only mv from matrices| %.2e px\n", "DYNAMIC bg_motion=1", nbg, maxerr);
    CHECK(nbg > 0 && maxerr < 0.01, "background motion is not the camera rotation");
    free_view(&P); free_view(&C);
}

static void check_unbiased(void)
{
    sbl_scene_desc d;
    bufs R;
    float *c;
    double *s1, *s2, *q1, *q2, z1 = 0.0, z2 = 0.0, pz1 = 0.0, pz2 = 0.0, bsum = 0.0, bvar = 0.0, rmse16 = 0.0, rmse256 = 0.0, var_sum = 0.0;
    long n, np, i, cnt = 0, pcnt = 0;
    int f, N = 256, spp;
    printf("[4] unbiased noise (STATIC 80x45, mean of %d 1-spp frames vs ref_spp 256)\n", N);
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_STATIC; d.width = 80; d.height = 45; d.ref_spp = 256; d.seed = getenv("SBL_SEED") ? (unsigned)atoi(getenv("SBL_SEED")) : 3u;
    sbl_scene_defaults(&d);
    np = (long)d.width * d.height;
    n = np * 3;
    memset(&R, 0, sizeof(R));
    R.w = d.width; R.h = d.height;
    R.v.reference = (float *)xcalloc((size_t)n, sizeof(float));
    sbl_scene_render(&d, 0, 0, &R.v, 0, d.height);
    c = (float *)xcalloc((size_t)n, sizeof(float));
    s1 = (double *)xcalloc((size_t)n, sizeof(double));
    s2 = (double *)xcalloc((size_t)n, sizeof(double));
    q1 = (double *)xcalloc((size_t)np, sizeof(double));
    q2 = (double *)xcalloc((size_t)np, sizeof(double));
    for (f = 0; f < N; ++f) {
        sbl_scene_view v;
        memset(&v, 0, sizeof(v));
        v.color = c;
        sbl_scene_render(&d, f, 0, &v, 0, d.height);
        for (i = 0; i < n; ++i) { s1[i] += c[i]; s2[i] += (double)c[i] * c[i]; }
        for (i = 0; i < np; ++i) { double q = (double)c[i * 3] + c[i * 3 + 1] + c[i * 3 + 2]; q1[i] += q; q2[i] += q * q; }
        if (f == 15) for (i = 0; i < n; ++i) { double e = s1[i] / 16.0 - R.v.reference[i]; rmse16 += e * e; }
    }
    for (i = 0; i < n; ++i) {
        double m = s1[i] / N, var = (s2[i] - N * m * m) / (N - 1), e = m - R.v.reference[i];
        /* the reference carries the same per-sample variance, over ref_spp samples */
        double sv = var / N + var / d.ref_spp;
        rmse256 += e * e; var_sum += sv;
        if (var > 1e-8) { double z = e / sqrt(sv); z1 += z; z2 += z * z; cnt++; }
    }
    /* per pixel on the RGB sum (channels of one sample are correlated, pixels are not) */
    for (i = 0; i < np; ++i) {
        double m = q1[i] / N, var = (q2[i] - N * m * m) / (N - 1);
        double e = m - ((double)R.v.reference[i * 3] + R.v.reference[i * 3 + 1] + R.v.reference[i * 3 + 2]);
        bsum += e; bvar += var / N + var / d.ref_spp;
        if (var > 1e-8) { double z = e / sqrt(var / N + var / d.ref_spp); pz1 += z; pz2 += z * z; pcnt++; }
    }
    rmse16 = sqrt(rmse16 / n); rmse256 = sqrt(rmse256 / n);
    printf("  per value z = (mean - ref) / predicted sd, %ld values: mean z %+.4f (|.|<0.1), mean z^2 %.4f (~1)\n",
           cnt, z1 / cnt, z2 / cnt);
    printf("  per pixel (RGB sum), %ld px: mean z %+.4f (standard error %.4f), mean z^2 %.4f\n",
           pcnt, pz1 / pcnt, 1.0 / sqrt((double)pcnt), pz2 / pcnt);
    printf("  image-wide bias of the RGB sum %+.2e, standard error %.2e (%+.2f SE)\n", bsum / np, sqrt(bvar) / np, bsum / sqrt(bvar));
    printf("  RMSE(mean,ref) %.4f vs predicted %.4f; RMSE(mean of 16, ref) %.4f -> of 256 %.4f (ratio %.2f)\n",
           rmse256, sqrt(var_sum / n), rmse16, rmse256, rmse16 / rmse256);
    CHECK(fabs(z1 / cnt) < 0.1, "mean z too large: biased");
    CHECK(z2 / cnt > 0.8 && z2 / cnt < 1.25, "mean z^2 off: noise model inconsistent");
    /* (mean z is slightly negative for skewed noise: a pixel that missed its rare bright
       samples also has a small sample variance; the unweighted image-wide bias is the test) */
    CHECK(fabs(pz1 / pcnt) < 0.1, "per-pixel mean z too large");
    CHECK(fabs(bsum) < 4.0 * sqrt(bvar), "image-wide bias beyond 4 standard errors");
    CHECK(fabs(rmse256 / sqrt(var_sum / n) - 1.0) < 0.15, "RMSE not as predicted");

    /* ladder: an n-spp render must carry 1/n of the per-sample variance. Normalising each
       value by its own variance keeps the few highlight pixels from dominating. T pools the
       frames and the reference (512 samples). */
    printf("[4b] effective-spp ladder (same scene; z^2 = (x_n - T)^2 / (var (1/n + 1/512)), T = pooled 512 samples)\n");
    for (spp = 1; spp <= 64; spp *= 4) {
        double zz = 0.0, e2 = 0.0;
        long k = 0;
        sbl_scene_render_spp(&d, 0, 0, spp, c, 0, d.height);
        for (i = 0; i < n; ++i) {
            double m = s1[i] / N, var = (s2[i] - N * m * m) / (N - 1);
            double T = (s1[i] + d.ref_spp * (double)R.v.reference[i]) / (N + d.ref_spp), e = c[i] - T;
            e2 += e * e;
            if (var > 1e-8) { zz += e * e / (var * (1.0 / spp + 1.0 / (N + d.ref_spp))); k++; }
        }
        printf("  spp %2d  RMSE %.4f  mean z^2 %.3f (~1)\n", spp, sqrt(e2 / n), zz / k);
        CHECK(zz / k > 0.8 && zz / k < 1.25, "spp %d: variance is not 1/n of one sample's", spp);
    }
    free(c); free(s1); free(s2); free(q1); free(q2); free(R.v.reference);
}

/* Heavy-tailed samples (sbl_scene_desc.spike_rate): the mean must stay the reference's
   (the spike factor g has E[g] = 1 and is independent of the sample), the share of
   spiked samples must be the rate, and the variance must grow. */
static void check_spikes(void)
{
    sbl_scene_desc d;
    float *c, *c0, *ref;
    double bsum = 0.0, bvar = 0.0, v_spk = 0.0, v_off = 0.0, *q1, *q2, *r1, *r2;
    long np, i, hi = 0, tot = 0;
    int f, N = 128;
    printf("[4c] heavy-tailed samples (STATIC 80x45, spike_rate 0.02, gain 25, %d frames)\n", N);
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_STATIC; d.width = 80; d.height = 45; d.ref_spp = 256; d.seed = 5u;
    d.spike_rate = 0.02f; d.spike_gain = 25.0f;
    sbl_scene_defaults(&d);
    np = (long)d.width * d.height;
    c = (float *)xcalloc((size_t)np * 3, sizeof(float));
    c0 = (float *)xcalloc((size_t)np * 3, sizeof(float));
    ref = (float *)xcalloc((size_t)np * 3, sizeof(float));
    q1 = (double *)xcalloc((size_t)np, sizeof(double)); q2 = (double *)xcalloc((size_t)np, sizeof(double));
    r1 = (double *)xcalloc((size_t)np, sizeof(double)); r2 = (double *)xcalloc((size_t)np, sizeof(double));
    {
        sbl_scene_view v;
        memset(&v, 0, sizeof(v));
        v.reference = ref;
        sbl_scene_render(&d, 0, 0, &v, 0, d.height);
    }
    for (f = 0; f < N; ++f) {
        sbl_scene_view v;
        sbl_scene_desc d0 = d;
        memset(&v, 0, sizeof(v));
        v.color = c;
        sbl_scene_render(&d, f, 0, &v, 0, d.height);
        d0.spike_rate = 0.0f;
        v.color = c0;
        sbl_scene_render(&d0, f, 0, &v, 0, d.height);
        for (i = 0; i < np; ++i) {
            const double q = (double)c[i * 3] + c[i * 3 + 1] + c[i * 3 + 2];
            const double q0 = (double)c0[i * 3] + c0[i * 3 + 1] + c0[i * 3 + 2];
            q1[i] += q; q2[i] += q * q; r1[i] += q0; r2[i] += q0 * q0;
            /* the same sample with and without its factor: q / q0 is the factor itself */
            if (q0 > 1e-6) { hi += q > 2.0 * q0; tot++; }
        }
    }
    for (i = 0; i < np; ++i) {
        const double m = q1[i] / N, var = (q2[i] - N * m * m) / (N - 1);
        const double m0 = r1[i] / N, var0 = (r2[i] - N * m0 * m0) / (N - 1);
        bsum += m - ((double)ref[i * 3] + ref[i * 3 + 1] + ref[i * 3 + 2]);
        bvar += var / N + var / d.ref_spp; /* (the reference's own noise: its variance is var0's) */
        v_spk += var; v_off += var0;
    }
    printf("  spiked share %.4f (rate 0.02); image-wide bias of the RGB sum %+.2e (%+.2f SE); variance x%.2f\n",
           (double)hi / tot, bsum / np, bsum / sqrt(bvar), v_spk / v_off);
    CHECK(fabs((double)hi / tot - 0.02) < 0.002, "spiked share is not the rate");
    CHECK(fabs(bsum) < 4.0 * sqrt(bvar), "spikes moved the mean beyond 4 standard errors");
    CHECK(v_spk > 2.0 * v_off, "spikes did not widen the noise");
    free(c); free(c0); free(ref); free(q1); free(q2); free(r1); free(r2);
}

static void check_projection(void)
{
    sbl_scene_desc d;
    bufs B;
    int x, y, f;
    double err = 0.0, werr = 0.0, floorz = 0.0, focal_err;
    long nfloor = 0;
    printf("[5] projection vs depth buffer (DYNAMIC + jitter, frames 0, 7, 15, both eyes)\n");
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_DYNAMIC; d.jitter = 1;
    sbl_scene_defaults(&d);
    alloc_view(&B, &d, 0, 0);
    for (f = 0; f < 6; ++f) {
        int frame = (f >> 1) == 0 ? 0 : ((f >> 1) == 1 ? 7 : 15);
        render(&d, frame, f & 1, &B);
        for (y = 0; y < d.height; ++y) for (x = 0; x < d.width; ++x) {
            int i = y * d.width + x;
            double p[3], u, v, w, z = B.v.depth[i];
            if (z > 1e9) continue;
            unproject(&B.v, d.width, d.height, x + 0.5, y + 0.5, z, p);
            w = project(&B.v, d.width, d.height, p, &u, &v);
            if (fabs(u - x - 0.5) > err) err = fabs(u - x - 0.5);
            if (fabs(v - y - 0.5) > err) err = fabs(v - y - 0.5);
            if (fabs(w - z) / z > werr) werr = fabs(w - z) / z;
            if (B.v.id[i] == id_of("floor")) { nfloor++; if (fabs(p[2]) > floorz) floorz = fabs(p[2]); }
        }
    }
    focal_err = fabs(B.v.proj[0] * d.width * 0.5 - B.v.focal_px);
    printf("  max reprojection error %.2e px, max |clip w - depth|/depth %.2e, floor points max |world z| %.2e m (%ld px)\n",
           err, werr, floorz, nfloor);
    printf("  focal_px %.4f (hfov %.1f deg), proj[0]*W/2 - focal %.2e, proj[5]*H/2 %.4f\n", B.v.focal_px,
           2.0 * atan(0.5 * d.width / B.v.focal_px) * 180.0 / 3.14159265358979, focal_err, B.v.proj[5] * d.height * 0.5);
    CHECK(err < 1e-2, "unproject/project does not return to the pixel centre");
    CHECK(werr < 1e-4, "clip w differs from depth");
    CHECK(floorz < 1e-3, "depth buffer disagrees with the floor plane");
    CHECK(focal_err < 1e-3, "proj and focal_px disagree");
    free_view(&B);
}

static void check_timing(int previews)
{
    sbl_scene_desc d;
    bufs B;
    double t0, tg, tc, tr, tall;
    int reps = 3, k;
    size_t n, i;
    memset(&d, 0, sizeof(d));
    d.kind = SBL_SCENE_DYNAMIC; d.jitter = 1;
    sbl_scene_defaults(&d);
    n = (size_t)d.width * d.height * 3;
    printf("[6] timing (DYNAMIC %dx%d, ref_spp %d, one eye-frame, single thread, mean of %d)\n",
           d.width, d.height, d.ref_spp, reps);
    alloc_view(&B, &d, 1, 1);
    {
        sbl_scene_view v;
        memset(&v, 0, sizeof(v));
        v.depth = B.v.depth; v.normal = B.v.normal; v.id = B.v.id; v.motion = B.v.motion;
        t0 = now_s(); for (k = 0; k < reps; ++k) sbl_scene_render(&d, 8, 0, &v, 0, d.height); tg = (now_s() - t0) / reps;
        v.depth = v.normal = v.id = v.motion = NULL;
        v.color = B.v.color;
        t0 = now_s(); for (k = 0; k < reps; ++k) sbl_scene_render(&d, 8, 0, &v, 0, d.height); tc = (now_s() - t0) / reps;
        v.color = NULL; v.reference = B.v.reference;
        t0 = now_s(); for (k = 0; k < reps; ++k) sbl_scene_render(&d, 8, 0, &v, 0, d.height); tr = (now_s() - t0) / reps;
    }
    t0 = now_s(); for (k = 0; k < reps; ++k) render(&d, 8, 0, &B); tall = (now_s() - t0) / reps;
    printf("  G-buffer %.2f ms, 1-spp colour %.2f ms, reference %.1f ms, everything %.1f ms\n",
           tg * 1e3, tc * 1e3, tr * 1e3, tall * 1e3);
    CHECK(tall < 1.0, "one eye-frame takes a second or more");
    {
        double mn = 1e30, mxv = -1e30, mean = 0.0, big = 0.0;
        for (i = 0; i < n; ++i) {
            if (B.v.reference[i] < mn) mn = B.v.reference[i];
            if (B.v.reference[i] > mxv) mxv = B.v.reference[i];
            mean += B.v.reference[i];
            if (B.v.color[i] > 4.0f) big += 1.0;
        }
        printf("  reference range [%.3f, %.3f], mean %.3f; 1-spp values > 4: %.2f%%\n", mn, mxv, mean / n, 100.0 * big / n);
        CHECK(mn >= 0.0 && mxv < 64.0, "reference out of the expected range");
    }

    if (previews) {
        bufs R;
        alloc_view(&R, &d, 1, 1);
        render(&d, 8, 1, &R);
        write_ppm_rgb("/tmp/sbl_scene_color_L.ppm", B.v.color, d.width, d.height, 0);
        write_ppm_rgb("/tmp/sbl_scene_ref_L.ppm", B.v.reference, d.width, d.height, 0);
        write_ppm_rgb("/tmp/sbl_scene_ref_R.ppm", R.v.reference, d.width, d.height, 0);
        write_ppm_rgb("/tmp/sbl_scene_depth_L.ppm", B.v.depth, d.width, d.height, 1);
        write_ppm_rgb("/tmp/sbl_scene_id_L.ppm", B.v.id, d.width, d.height, 2);
        write_ppm_rgb("/tmp/sbl_scene_motion_L.ppm", B.v.motion, d.width, d.height, 3);
        printf("  previews written to /tmp/sbl_scene_*.ppm (DYNAMIC frame 8)\n");
        free_view(&R);
    }
    free_view(&B);
}

int main(int argc, char **argv)
{
    int previews = argc > 1 && strcmp(argv[1], "-p") == 0;
    check_determinism();
    check_stereo();
    printf("[3] motion vectors (frame t -> t-1 via mv, nearest pixel)\n");
    check_motion(SBL_SCENE_PAN, 0, "PAN");
    check_motion(SBL_SCENE_DYNAMIC, 0, "DYNAMIC");
    check_motion(SBL_SCENE_DYNAMIC, 1, "DYNAMIC+jitter");
    check_motion(SBL_SCENE_SHADOW, 0, "SHADOW");
    check_motion(SBL_SCENE_STATIC, 0, "STATIC");
    check_bg_motion();
    check_unbiased();
    check_spikes();
    check_projection();
    check_timing(previews);
    printf("%s (%d failure%s)\n", g_fail ? "FAILED" : "all checks passed", g_fail, g_fail == 1 ? "" : "s");
    return g_fail ? 1 : 0;
}
