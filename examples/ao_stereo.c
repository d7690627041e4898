/* ao_stereo.c - the case of Wu's adaptive stereo-consistent SSAO (seed 004, after Shi,
   Billeter and Eisemann 2022), built on stereoblend.h's consistency mask.

   Not part of the library (the header filters images; AO here is a test effect). Per
   stereo frame, from depth + normals of both eyes (parallel rig):
     raw obscurance    Alchemy-style (McGuire 2011): N samples on a world-space disk in
                       the tangent plane of the shading point P, each projected into the
                       view; the G-buffer point Q there gives max(0, v.n - beta z) /
                       (v.v + eps), v = Q - P (only |v| < R counts).
       mono            samples projected into the pixel's own view; the disk is turned
                       per pixel by a 4x4 interleaved pattern (as HBAO+).
       stereo-aware    each sample projected into both views: where both views hold the
                       same surface point the two contributions are averaged, otherwise
                       the larger counts (the occluder one view misses). Computed in the
                       left view; a right pixel takes the value of its back-checked left
                       match, and computes its own where it has none.
     filter            separable cross-bilateral (spatial sigma 3, radius 6; weight on the
                       world-position distance, sigma 10 % of the depth), which also
                       returns its weight sum W.
       mono            each view on its own: F(p), W(p).
       stereo-aware    A(p) = w F(p) + (1 - w) F(p*), p* the back-checked match, with
                       w = smoothstep(0.45, 0.55, W(p) / (W(p) + W(p*))). The seed prints
                       the edges as (0.45, 0.50); a ramp centred on 0.5 is what makes the
                       pair agree (w(a) + w(1 - a) = 1, so A(p) = A(p*) where the weights
                       are mirrored), and the view whose neighbourhood holds more of the
                       same surface still wins where they differ.
   Configurations (the seed's Table 3):
     Mono      mono estimate + mono filter
     FSA       stereo-aware estimate + stereo-aware filter everywhere
     Variant1  Mono, then sbl_stereo_consistency (Weber, T) on the two AO maps; on the
               inconsistent pixels: stereo-aware estimate and stereo-aware filter
     Variant2  stereo-aware estimate + mono filter, then the mask; on the inconsistent
               pixels: the stereo-aware filter
   Measured: the inconsistency ratio of the final pair (sbl_stereo_consistency at 2 %,
   both eyes, over pixels with a correspondence; sky has none), MAE against FSA, and ms
   per stereo frame (median thread CPU time, the configurations run side by side); then ms
   against the threshold (0.01 .. 0.1, Figure 11).

   With --only CONFIG [--scene NAME] it runs just that configuration once per frame (no
   tables): the run to count instructions under callgrind, which does not drift with the
   machine's load (bench/ao_ipp.sh).

   usage: ao_stereo [--quick] [--data DIR] [--frames N] [--reps N] [--samples N]
                    [--only Mono|FSA|Variant1|Variant2 [--scene NAME] [--threshold T]] */
#define _POSIX_C_SOURCE 200809L
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#include "sbl_dataset.h"
#include "sbl_exr.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define AO_RADIUS 0.5f      /* world units (metres in every scene here) */
#define AO_BETA 0.002f      /* depth-scaled bias against self-occlusion */
#define AO_EPS 0.01f
#define AO_SIGMA 1.0f       /* intensity */
#define BF_RADIUS 6         /* 2 sigma, sigma 3 pixels (the seed's spatial sigma) */
#define BF_SIGMA 3.0f
#define BF_GEO 0.1f         /* geometric sigma: 10 % of the centre pixel's depth */
#define SAME_SURFACE 0.02f  /* two views hold one surface point: within 2 % of depth */

/* Thread CPU time: on a shared machine the slices given to other processes would
   otherwise count (wall time drifted by 2x between rows of one run). */
static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* ---- a stereo G-buffer pair -------------------------------------------------------- */

typedef struct view {
    float *depth;   /* planar depth; 0 = no geometry (sky)                  */
    float *normal;  /* camera space: x right, y down, z forward (unit)      */
    float *id;
    float *pos;     /* camera-space position of each pixel (x, y, z)        */
} view;

typedef struct pair {
    int w, h;
    float f, b;     /* focal length (pixels), baseline; right = left + b along x */
    view v[2];
    int samples;
} pair;

static void *xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

/* From planar depth (background >= 1e9 -> no geometry), world normals and the eye's
   world_to_cam (Blender camera: x right, y up, looking down -z). */
static void view_init(pair *p, int e, const float *depth, const float *nworld, const float *id,
                      const float *world_to_cam)
{
    const int w = p->w, h = p->h;
    const size_t n = (size_t)w * h;
    view *v = &p->v[e];
    size_t i;
    v->depth = (float *)xmalloc(n * sizeof(float));
    v->normal = (float *)xmalloc(n * 3 * sizeof(float));
    v->id = (float *)xmalloc(n * sizeof(float));
    v->pos = (float *)xmalloc(n * 3 * sizeof(float));
    for (i = 0; i < n; ++i) {
        float z = depth[i], nx, ny, nz, len;
        const float *m = world_to_cam, *nw = nworld + 3 * i;
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
        if (!(z > 0.0f) || z >= 1e9f) z = 0.0f;
        v->depth[i] = z;
        v->id[i] = id ? id[i] : 0.0f;
        /* rotate into the camera, then to x right, y down, z forward */
        nx = m[0] * nw[0] + m[1] * nw[1] + m[2] * nw[2];
        ny = -(m[4] * nw[0] + m[5] * nw[1] + m[6] * nw[2]);
        nz = -(m[8] * nw[0] + m[9] * nw[1] + m[10] * nw[2]);
        v->pos[3 * i] = (x + 0.5f - 0.5f * w) * z / p->f;
        v->pos[3 * i + 1] = (y + 0.5f - 0.5f * h) * z / p->f;
        v->pos[3 * i + 2] = z;
        /* face the camera */
        if (nx * v->pos[3 * i] + ny * v->pos[3 * i + 1] + nz * z > 0.0f) { nx = -nx; ny = -ny; nz = -nz; }
        len = sqrtf(nx * nx + ny * ny + nz * nz);
        if (len > 0.0f) { nx /= len; ny /= len; nz /= len; }
        v->normal[3 * i] = nx; v->normal[3 * i + 1] = ny; v->normal[3 * i + 2] = nz;
    }
}

static void pair_free(pair *p)
{
    int e;
    for (e = 0; e < 2; ++e) { free(p->v[e].depth); free(p->v[e].normal); free(p->v[e].id); free(p->v[e].pos); }
}

/* The library's view of an eye: depth (0 = no geometry: no correspondence) and ids.
   Normals are left out: ours are in each camera's frame, equal for a parallel rig, but
   the id and depth tests suffice here. */
static sbl_eye lib_eye(const pair *p, int e)
{
    sbl_eye eye;
    memset(&eye, 0, sizeof eye);
    eye.gbuffer.depth = sbl_image_make(p->v[e].depth, p->w, p->h, 1);
    eye.gbuffer.ids = sbl_image_make(p->v[e].id, p->w, p->h, 1);
    return eye;
}

static sbl_stereo_desc lib_desc(const pair *p)
{
    sbl_stereo_desc d;
    memset(&d, 0, sizeof d);
    d.rig = SBL_RIG_PARALLEL;
    d.focal_px = p->f;
    d.baseline = p->b;
    return d;
}

/* Back-checked nearest match of pixel (x, y) of eye e in the other eye (the same rule as
   the library's: disparity f b / z, within a pixel on the way back, same id, depth within
   5 %); -1 if none. */
static int match(const pair *p, int e, int x, int y)
{
    const view *a = &p->v[e], *o = &p->v[!e];
    size_t i = (size_t)y * p->w + x;
    float z = a->depth[i], zo, d, back;
    int mx;
    if (!(z > 0.0f)) return -1;
    d = p->f * p->b / z;
    back = (float)x + 0.5f + (e == 0 ? -d : d);
    mx = (int)floorf(back);
    if (mx < 0 || mx >= p->w) return -1;
    zo = o->depth[(size_t)y * p->w + mx];
    if (!(zo > 0.0f) || fabsf(zo - z) > 0.05f * z || o->id[(size_t)y * p->w + mx] != a->id[i]) return -1;
    back = (float)mx + 0.5f + (e == 0 ? p->f * p->b / zo : -p->f * p->b / zo);
    if (fabsf(back - ((float)x + 0.5f)) > 1.0f) return -1;
    return mx;
}

/* ---- raw obscurance ---------------------------------------------------------------- */

/* The G-buffer point of eye e under camera-space point s (given in eye e's frame);
   0 if outside the image or sky. */
static int fetch(const pair *p, int e, const float *s, float *q)
{
    float u, v;
    int x, y;
    const float *pp;
    if (!(s[2] > 1e-4f)) return 0;
    u = 0.5f * p->w + p->f * s[0] / s[2];
    v = 0.5f * p->h + p->f * s[1] / s[2];
    if (!(u >= 0.0f && v >= 0.0f && u < (float)p->w && v < (float)p->h)) return 0;
    x = (int)u; y = (int)v;
    if (!(p->v[e].depth[(size_t)y * p->w + x] > 0.0f)) return 0;
    pp = p->v[e].pos + 3 * ((size_t)y * p->w + x);
    q[0] = pp[0]; q[1] = pp[1]; q[2] = pp[2];
    return 1;
}

static float contrib(const float *P, const float *n, const float *Q)
{
    float v[3], vv, vn;
    v[0] = Q[0] - P[0]; v[1] = Q[1] - P[1]; v[2] = Q[2] - P[2];
    vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    if (vv > AO_RADIUS * AO_RADIUS) return 0.0f;
    vn = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    vn -= AO_BETA * P[2];
    return vn > 0.0f ? vn / (vv + AO_EPS) : 0.0f;
}

/* Raw obscurance of pixel (x, y) of eye e; stereo: samples into both views. Returns the
   accessibility in [0, 1] (1 = open; also sky). */
static float raw_ao(const pair *p, int e, int x, int y, int stereo)
{
    static const float pattern[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
    const size_t i = (size_t)y * p->w + x;
    const float *P = p->v[e].pos + 3 * i, *n = p->v[e].normal + 3 * i;
    const float ox = e == 0 ? -p->b : p->b; /* other eye's frame: x - b (left -> right) */
    float t1[3], t2[3], sum = 0.0f, rot, len;
    int k, N = p->samples;
    if (!(p->v[e].depth[i] > 0.0f)) return 1.0f;
    /* tangent basis */
    if (fabsf(n[0]) < 0.9f) { t1[0] = 0; t1[1] = -n[2]; t1[2] = n[1]; }
    else { t1[0] = n[2]; t1[1] = 0; t1[2] = -n[0]; }
    len = sqrtf(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    t1[0] /= len; t1[1] /= len; t1[2] /= len;
    t2[0] = n[1] * t1[2] - n[2] * t1[1];
    t2[1] = n[2] * t1[0] - n[0] * t1[2];
    t2[2] = n[0] * t1[1] - n[1] * t1[0];
    rot = pattern[(y & 3) * 4 + (x & 3)] * (6.2831853f / 16.0f);
    for (k = 0; k < N; ++k) {
        float a = rot + (float)k * 2.3999632f; /* golden angle */
        float r = AO_RADIUS * sqrtf(((float)k + 0.5f) / (float)N);
        float s[3], q[3], c;
        s[0] = P[0] + r * (cosf(a) * t1[0] + sinf(a) * t2[0]);
        s[1] = P[1] + r * (cosf(a) * t1[1] + sinf(a) * t2[1]);
        s[2] = P[2] + r * (cosf(a) * t1[2] + sinf(a) * t2[2]);
        c = fetch(p, e, s, q) ? contrib(P, n, q) : 0.0f;
        if (stereo) {
            float so[3], qo[3];
            so[0] = s[0] + ox; so[1] = s[1]; so[2] = s[2];
            if (fetch(p, !e, so, qo)) {
                float co, dx, dy, dz;
                qo[0] -= ox; /* back into eye e's frame */
                co = contrib(P, n, qo);
                dx = qo[0] - q[0]; dy = qo[1] - q[1]; dz = qo[2] - q[2];
                if (c > 0.0f || co > 0.0f) {
                    int same = dx * dx + dy * dy + dz * dz <=
                               (SAME_SURFACE * q[2]) * (SAME_SURFACE * q[2]);
                    c = same ? 0.5f * (c + co) : (co > c ? co : c);
                }
            }
        }
        sum += c;
    }
    {
        float ao = 1.0f - 2.0f * AO_SIGMA / (float)N * sum;
        return ao > 0.0f ? ao : 0.0f;
    }
}

/* Stereo-aware raw AO of (x, y) of eye e as the configurations share it: computed in the
   left view; a right pixel with a back-checked left match takes the left value. */
static float raw_stereo(const pair *p, int e, int x, int y)
{
    if (e == 1) {
        int mx = match(p, 1, x, y);
        if (mx >= 0) return raw_ao(p, 0, mx, y, 1);
    }
    return raw_ao(p, e, x, y, 1);
}

/* ---- the filter -------------------------------------------------------------------- */

typedef struct maps {
    float *raw[2], *fh[2], *wh[2], *F[2], *W[2], *A[2];
    unsigned char *mask[2], *sel[2], *hsel[2];
    void *mask_scratch; /* sbl_stereo_consistency's row of reprojection */
    size_t mask_scratch_bytes;
} maps;

static float bf_spatial[2 * BF_RADIUS + 1];

static float geo_w(const float *pc, const float *pq, float inv2s2)
{
    float dx = pq[0] - pc[0], dy = pq[1] - pc[1], dz = pq[2] - pc[2];
    return expf(-(dx * dx + dy * dy + dz * dz) * inv2s2);
}

/* Horizontal pass at (x, y) of eye e. */
static void bf_h(const pair *p, maps *m, int e, int x, int y)
{
    const size_t i = (size_t)y * p->w + x;
    const float *pc = p->v[e].pos + 3 * i;
    float z = p->v[e].depth[i], acc = 0.0f, ws = 0.0f, inv;
    int k;
    if (!(z > 0.0f)) { m->fh[e][i] = m->raw[e][i]; m->wh[e][i] = 1.0f; return; }
    inv = 1.0f / (2.0f * (BF_GEO * z) * (BF_GEO * z));
    for (k = -BF_RADIUS; k <= BF_RADIUS; ++k) {
        int xx = x + k;
        size_t j;
        float wt;
        if (xx < 0 || xx >= p->w) continue;
        j = (size_t)y * p->w + xx;
        if (!(p->v[e].depth[j] > 0.0f)) continue;
        wt = bf_spatial[k + BF_RADIUS] * geo_w(pc, p->v[e].pos + 3 * j, inv);
        acc += wt * m->raw[e][j];
        ws += wt;
    }
    m->fh[e][i] = ws > 0.0f ? acc / ws : m->raw[e][i];
    m->wh[e][i] = ws;
}

/* Vertical pass at (x, y): F = the separable 2D weighted mean, W = its weight sum. */
static void bf_v(const pair *p, maps *m, int e, int x, int y)
{
    const size_t i = (size_t)y * p->w + x;
    const float *pc = p->v[e].pos + 3 * i;
    float z = p->v[e].depth[i], acc = 0.0f, ws = 0.0f, inv;
    int k;
    if (!(z > 0.0f)) { m->F[e][i] = m->raw[e][i]; m->W[e][i] = 1.0f; return; }
    inv = 1.0f / (2.0f * (BF_GEO * z) * (BF_GEO * z));
    for (k = -BF_RADIUS; k <= BF_RADIUS; ++k) {
        int yy = y + k;
        size_t j;
        float wt;
        if (yy < 0 || yy >= p->h) continue;
        j = (size_t)yy * p->w + x;
        if (!(p->v[e].depth[j] > 0.0f)) continue;
        wt = bf_spatial[k + BF_RADIUS] * geo_w(pc, p->v[e].pos + 3 * j, inv) * m->wh[e][j];
        acc += wt * m->fh[e][j];
        ws += wt;
    }
    m->F[e][i] = ws > 0.0f ? acc / ws : m->raw[e][i];
    m->W[e][i] = ws;
}

static float smoothstep(float a, float b, float t)
{
    float u = (t - a) / (b - a);
    u = u < 0.0f ? 0.0f : (u > 1.0f ? 1.0f : u);
    return u * u * (3.0f - 2.0f * u);
}

/* Mono filter of the whole eye: A = F. */
static void filter_mono(const pair *p, maps *m, int e)
{
    int x, y;
    const size_t n = (size_t)p->w * p->h;
    for (y = 0; y < p->h; ++y) for (x = 0; x < p->w; ++x) bf_h(p, m, e, x, y);
    for (y = 0; y < p->h; ++y) for (x = 0; x < p->w; ++x) bf_v(p, m, e, x, y);
    memcpy(m->A[e], m->F[e], n * sizeof(float));
}

/* Stereo-aware filter on the pixels with mask[e] == SBL_INCONSISTENT (all: FSA). Both
   eyes' F and W are needed at the marked pixels and at their matches: with refilter
   (the raw map changed there) the vertical pass runs again there (sel), the horizontal
   pass on the rows it reads (hsel). */
static void filter_stereo(const pair *p, maps *m, int all, int refilter)
{
    const int w = p->w, h = p->h;
    const size_t n = (size_t)w * h;
    int e, x, y, k;
    for (e = 0; e < 2; ++e) {
        if (all) { memset(m->sel[e], 1, n); memset(m->hsel[e], 1, n); }
        else { memset(m->sel[e], 0, n); memset(m->hsel[e], 0, n); }
    }
    if (!all)
        for (e = 0; e < 2; ++e)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    int mx;
                    if (m->mask[e][(size_t)y * w + x] != SBL_INCONSISTENT) continue;
                    m->sel[e][(size_t)y * w + x] = 1;
                    if ((mx = match(p, e, x, y)) >= 0) m->sel[!e][(size_t)y * w + mx] = 1;
                }
    for (e = 0; e < 2 && refilter; ++e) {
        if (!all)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x)
                    if (m->sel[e][(size_t)y * w + x])
                        for (k = y - BF_RADIUS; k <= y + BF_RADIUS; ++k)
                            if (k >= 0 && k < h) m->hsel[e][(size_t)k * w + x] = 1;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                if (m->hsel[e][(size_t)y * w + x]) bf_h(p, m, e, x, y);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                if (m->sel[e][(size_t)y * w + x]) bf_v(p, m, e, x, y);
    }
    for (e = 0; e < 2; ++e)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                size_t i = (size_t)y * w + x;
                int mx;
                if (!all && m->mask[e][i] != SBL_INCONSISTENT) continue;
                mx = match(p, e, x, y);
                if (mx < 0) {
                    m->A[e][i] = m->F[e][i];
                } else {
                    size_t j = (size_t)y * w + mx;
                    float sw = m->W[e][i] + m->W[!e][j];
                    float wt = sw > 0.0f ? smoothstep(0.45f, 0.55f, m->W[e][i] / sw) : 1.0f;
                    m->A[e][i] = wt * m->F[e][i] + (1.0f - wt) * m->F[!e][j];
                }
            }
}

/* ---- the configurations ------------------------------------------------------------ */

enum { MONO, FSA, VAR1, VAR2, CONFIGS };
static const char *const config_name[CONFIGS] = {"Mono", "FSA", "Variant1", "Variant2"};

/* The mask of both eyes on the current AO maps; returns the marked share (%). Its
   correspondence is the depth test and the back-check (Wu's correspondence map), without
   the id test: eyes with depth alone let the library reproject a row at a time in vector
   lanes (sbl_stereo_consistency with scratch), several times cheaper than pixel by
   pixel. The measured ratio of the final pair keeps the id test (measure()). */
static double make_mask(const pair *p, maps *m, float threshold)
{
    sbl_stereo_desc d = lib_desc(p);
    sbl_eye eye[2];
    long bad = 0, matched = 0;
    int e;
    eye[0] = lib_eye(p, 0);
    eye[1] = lib_eye(p, 1);
    for (e = 0; e < 2; ++e) memset(&eye[e].gbuffer.ids, 0, sizeof eye[e].gbuffer.ids);
    for (e = 0; e < 2; ++e) {
        sbl_consistency_counts c;
        sbl_result r = sbl_stereo_consistency(&d, threshold, (sbl_eye_index)e, &eye[e], &eye[!e],
                                              sbl_image_make(m->A[e], p->w, p->h, 1),
                                              sbl_image_make(m->A[!e], p->w, p->h, 1), m->mask[e],
                                              p->w, 0, p->h, m->mask_scratch, m->mask_scratch_bytes, &c);
        if (r != SBL_OK) { fprintf(stderr, "sbl_stereo_consistency: %s\n", sbl_result_string(r)); exit(1); }
        bad += c.inconsistent;
        matched += c.consistent + c.inconsistent;
    }
    return matched ? 100.0 * (double)bad / (double)matched : 0.0;
}

/* Stages of the seed's Table 3. */
enum { ST_EST, ST_FILTER, ST_MAP, ST_AEST, ST_AFILTER, STAGES };
static const char *const stage_name[STAGES] = {"obscur. est.", "filtering", "adaptive map",
                                               "adaptive est.", "adaptive filtering"};

/* One configuration on one stereo frame; the AO maps end in m->A. Returns ms; stage[]
   receives the ms of each stage. */
static double run_config(const pair *p, maps *m, int config, float threshold, double *marked,
                         double *stage)
{
    const int w = p->w, h = p->h;
    double t0 = now_ms(), t = t0, t1;
    int e, x, y;
    *marked = 0;
    memset(stage, 0, sizeof(double) * STAGES);
#define STAGE_END(s) (t1 = now_ms(), stage[s] = t1 - t, t = t1)
    for (e = 0; e < 2; ++e)
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                size_t i = (size_t)y * w + x;
                m->raw[e][i] = (config == MONO || config == VAR1) ? raw_ao(p, e, x, y, 0)
                                                                  : raw_stereo(p, e, x, y);
            }
    STAGE_END(ST_EST);
    if (config == FSA) {
        filter_stereo(p, m, 1, 1);
        STAGE_END(ST_FILTER);
    } else {
        for (e = 0; e < 2; ++e) filter_mono(p, m, e);
        STAGE_END(ST_FILTER);
        if (config != MONO) {
            *marked = make_mask(p, m, threshold);
            STAGE_END(ST_MAP);
            if (config == VAR1)
                for (e = 0; e < 2; ++e)
                    for (y = 0; y < h; ++y)
                        for (x = 0; x < w; ++x) {
                            size_t i = (size_t)y * w + x;
                            if (m->mask[e][i] == SBL_INCONSISTENT) m->raw[e][i] = raw_stereo(p, e, x, y);
                        }
            STAGE_END(ST_AEST);
            /* Variant 2 keeps its raw map, so F and W of the mono pass stand: only the
               combination with the other view is left */
            filter_stereo(p, m, 0, config == VAR1);
            STAGE_END(ST_AFILTER);
        }
    }
#undef STAGE_END
    return now_ms() - t0;
}

static void maps_alloc(maps *m, int w, size_t n)
{
    int e;
    m->mask_scratch_bytes = sbl_stereo_consistency_scratch_size(w, 1);
    m->mask_scratch = xmalloc(m->mask_scratch_bytes);
    for (e = 0; e < 2; ++e) {
        m->raw[e] = (float *)xmalloc(n * sizeof(float));
        m->fh[e] = (float *)xmalloc(n * sizeof(float));
        m->wh[e] = (float *)xmalloc(n * sizeof(float));
        m->F[e] = (float *)xmalloc(n * sizeof(float));
        m->W[e] = (float *)xmalloc(n * sizeof(float));
        m->A[e] = (float *)xmalloc(n * sizeof(float));
        m->mask[e] = (unsigned char *)xmalloc(n);
        m->sel[e] = (unsigned char *)xmalloc(n);
        m->hsel[e] = (unsigned char *)xmalloc(n);
    }
}

static void maps_free(maps *m)
{
    int e;
    for (e = 0; e < 2; ++e) {
        free(m->raw[e]); free(m->fh[e]); free(m->wh[e]); free(m->F[e]); free(m->W[e]);
        free(m->A[e]); free(m->mask[e]); free(m->sel[e]); free(m->hsel[e]);
    }
    free(m->mask_scratch);
}

/* ---- scenes ------------------------------------------------------------------------ */

#define MAX_FRAMES 8
typedef struct scene { char name[64]; int count; pair frame[MAX_FRAMES]; } scene;

static int scene_synthetic(scene *s, const char *name, sbl_scene_kind kind, int w, int h,
                           int nframes, int samples)
{
    sbl_scene_desc d;
    int f, e;
    memset(&d, 0, sizeof d);
    memset(s, 0, sizeof *s);
    snprintf(s->name, sizeof s->name, "%s", name);
    d.kind = kind; d.width = w; d.height = h; d.frames = 16; d.jitter = kind == SBL_SCENE_DYNAMIC;
    sbl_scene_defaults(&d);
    for (f = 0; f < nframes && f < MAX_FRAMES; ++f) {
        pair *p = &s->frame[s->count++];
        memset(p, 0, sizeof *p);
        p->w = d.width; p->h = d.height; p->samples = samples;
        for (e = 0; e < 2; ++e) {
            size_t n = (size_t)d.width * d.height;
            sbl_scene_view sv;
            float *depth = (float *)xmalloc(n * sizeof(float)), *nor = (float *)xmalloc(n * 3 * sizeof(float)),
                  *id = (float *)xmalloc(n * sizeof(float));
            memset(&sv, 0, sizeof sv);
            sv.depth = depth; sv.normal = nor; sv.id = id;
            if (sbl_scene_render(&d, f * 16 / nframes, e, &sv, 0, d.height) != 0) return 1;
            p->f = sv.focal_px; p->b = sv.baseline;
            view_init(p, e, depth, nor, id, sv.world_to_cam);
            free(depth); free(nor); free(id);
        }
    }
    return 0;
}

static int scene_dataset(scene *s, const char *dir, int nframes, int samples)
{
    sbl_dataset ds;
    char err[512];
    const char *base = strrchr(dir, '/');
    int f, e;
    memset(s, 0, sizeof *s);
    if (sbl_dataset_open(&ds, dir, err, sizeof err) != 0) { printf("(%s skipped: %s)\n", dir, err); return 1; }
    snprintf(s->name, sizeof s->name, "%.63s", base && base[1] ? base + 1 : dir);
    for (f = 0; f < nframes && f < MAX_FRAMES; ++f) {
        int frame = f * ds.frames / nframes;
        pair *p = &s->frame[s->count++];
        memset(p, 0, sizeof *p);
        p->w = ds.width; p->h = ds.height; p->samples = samples;
        p->b = ds.baseline;
        for (e = 0; e < 2; ++e) {
            sbl_dataset_frame fr;
            if (sbl_dataset_load(&ds, frame, e, &fr, err, sizeof err) != 0) {
                printf("(%s skipped: %s)\n", dir, err);
                sbl_dataset_close(&ds);
                return 1;
            }
            p->f = ds.focal_px[frame][e];
            view_init(p, e, fr.depth, fr.normal, fr.id, ds.world_to_cam[frame][e]);
            sbl_dataset_frame_free(&fr);
        }
    }
    sbl_dataset_close(&ds);
    return 0;
}

static void scene_free(scene *s)
{
    int i;
    for (i = 0; i < s->count; ++i) pair_free(&s->frame[i]);
}

/* ---- measuring --------------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

typedef struct row { double ratio, mae, ms, marked, stage[STAGES]; } row;

/* Every configuration on every frame of the scene at threshold T: ratio (2 %) of the
   final pair, MAE against FSA (pixels with geometry, both eyes), median ms. The runs are
   side by side: on each frame, run r of every configuration before run r + 1 of any, so
   that a change in the machine's load falls on all of them alike. */
static void measure(const scene *s, float threshold, int reps, row *out)
{
    int c, f, r, e, k, nt = 0;
    double *times[CONFIGS], stage_sum[CONFIGS][STAGES], marked_sum[CONFIGS], mae[CONFIGS];
    long bad[CONFIGS], matched[CONFIGS], mae_n[CONFIGS];
    for (c = 0; c < CONFIGS; ++c) {
        memset(&out[c], 0, sizeof out[c]);
        times[c] = (double *)xmalloc(sizeof(double) * (size_t)(s->count * reps + 1));
        memset(stage_sum[c], 0, sizeof stage_sum[c]);
        marked_sum[c] = mae[c] = 0.0;
        bad[c] = matched[c] = mae_n[c] = 0;
    }
    for (f = 0; f < s->count; ++f) {
        const pair *p = &s->frame[f];
        const size_t n = (size_t)p->w * p->h;
        maps m[CONFIGS];
        double marked[CONFIGS], st[STAGES];
        for (c = 0; c < CONFIGS; ++c) maps_alloc(&m[c], p->w, n);
        for (r = 0; r < reps; ++r, ++nt)
            for (c = 0; c < CONFIGS; ++c) {
                times[c][nt] = run_config(p, &m[c], c, threshold, &marked[c], st);
                for (k = 0; k < STAGES; ++k) stage_sum[c][k] += st[k];
            }
        for (c = 0; c < CONFIGS; ++c) {
            sbl_stereo_desc d = lib_desc(p);
            sbl_eye eye[2];
            marked_sum[c] += marked[c];
            eye[0] = lib_eye(p, 0);
            eye[1] = lib_eye(p, 1);
            for (e = 0; e < 2; ++e) {   /* consistency of the final pair at 2 % */
                sbl_consistency_counts cnt;
                if (sbl_stereo_consistency(&d, 0.0f, (sbl_eye_index)e, &eye[e], &eye[!e],
                                           sbl_image_make(m[c].A[e], p->w, p->h, 1),
                                           sbl_image_make(m[c].A[!e], p->w, p->h, 1), m[c].mask[e], p->w,
                                           0, p->h, NULL, 0, &cnt) != SBL_OK)
                    exit(1);
                bad[c] += cnt.inconsistent;
                matched[c] += cnt.consistent + cnt.inconsistent;
            }
            for (e = 0; e < 2; ++e) {   /* MAE against FSA's result */
                size_t i;
                for (i = 0; i < n; ++i)
                    if (p->v[e].depth[i] > 0.0f) { mae[c] += fabs((double)m[c].A[e][i] - m[FSA].A[e][i]); ++mae_n[c]; }
            }
        }
        for (c = 0; c < CONFIGS; ++c) maps_free(&m[c]);
    }
    for (c = 0; c < CONFIGS; ++c) {
        qsort(times[c], (size_t)nt, sizeof(double), cmp_double);
        out[c].ms = times[c][nt / 2];
        out[c].ratio = matched[c] ? 100.0 * (double)bad[c] / (double)matched[c] : 0.0;
        out[c].mae = mae_n[c] ? mae[c] / (double)mae_n[c] : 0.0;
        out[c].marked = marked_sum[c] / s->count;
        for (k = 0; k < STAGES; ++k) out[c].stage[k] = stage_sum[c][k] / nt;
        free(times[c]);
    }
}

static void report(const scene *s, int reps, int sweep)
{
    row r[CONFIGS];
    int c;
    const pair *p = &s->frame[0];
    measure(s, 0.0f, reps, r);
    printf("\n## %s (%dx%d, %d frame%s, %d samples per pixel)\n\n", s->name, p->w, p->h, s->count,
           s->count > 1 ? "s" : "", p->samples);
    printf("| config   | inconsistent %% (2 %%) | MAE vs FSA | ms (median) | x Mono | marked %% |\n");
    printf("|----------|---------------------:|-----------:|------------:|-------:|---------:|\n");
    for (c = 0; c < CONFIGS; ++c)
        printf("| %-8s | %20.2f | %10.5f | %11.2f | %6.2f | %8.2f |\n", config_name[c], r[c].ratio,
               r[c].mae, r[c].ms, r[MONO].ms > 0 ? r[c].ms / r[MONO].ms : 0.0, r[c].marked);
    printf("\nstages, mean ms per stereo frame (the seed's Table 3):\n\n| config   |");
    for (c = 0; c < STAGES; ++c) printf(" %s |", stage_name[c]);
    printf(" total |\n|----------|---:|---:|---:|---:|---:|---:|\n");
    for (c = 0; c < CONFIGS; ++c) {
        int k;
        double tot = 0;
        printf("| %-8s |", config_name[c]);
        for (k = 0; k < STAGES; ++k) { printf(" %.2f |", r[c].stage[k]); tot += r[c].stage[k]; }
        printf(" %.2f |\n", tot);
    }
    fflush(stdout);
    if (sweep) {
        static const float T[] = {0.01f, 0.02f, 0.03f, 0.05f, 0.07f, 0.1f};
        unsigned t;
        printf("\n%s: time against the Weber threshold (Figure 11), ms (x Mono) and marked %%\n\n", s->name);
        printf("| threshold | Variant1 ms | Variant1 marked %% | Variant2 ms | Variant2 marked %% | Mono ms | FSA ms |\n");
        printf("|----------:|------------:|------------------:|------------:|------------------:|--------:|-------:|\n");
        for (t = 0; t < sizeof T / sizeof T[0]; ++t) {
            row q[CONFIGS];
            measure(s, T[t], reps, q);
            printf("| %9.2f | %5.2f (%4.2f) | %17.2f | %5.2f (%4.2f) | %17.2f | %7.2f | %6.2f |\n", T[t],
                   q[VAR1].ms, q[VAR1].ms / q[MONO].ms, q[VAR1].marked, q[VAR2].ms,
                   q[VAR2].ms / q[MONO].ms, q[VAR2].marked, q[MONO].ms, q[FSA].ms);
            fflush(stdout);
        }
    }
}

/* One configuration on every frame, nothing else (for callgrind --toggle-collect). */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void count_config(const scene *s, int config, float threshold)
{
    int f;
    for (f = 0; f < s->count; ++f) {
        const pair *p = &s->frame[f];
        maps m;
        double marked, st[STAGES];
        maps_alloc(&m, p->w, (size_t)p->w * p->h);
        (void)run_config(p, &m, config, threshold, &marked, st);
        printf("%s %s frame %d: marked %.2f %%\n", s->name, config_name[config], f, marked);
        maps_free(&m);
    }
}

int main(int argc, char **argv)
{
    const char *data = "../shared/data";
    int quick = 0, frames = 3, reps = 3, samples = 8, i, k, only = -1;
    const char *only_scene = "atrium";
    float only_threshold = 0.0f;
    char path[1024];
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0) quick = 1;
        else if (strcmp(argv[i], "--data") == 0 && i + 1 < argc) data = argv[++i];
        else if (strcmp(argv[i], "--frames") == 0 && i + 1 < argc) frames = atoi(argv[++i]);
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--samples") == 0 && i + 1 < argc) samples = atoi(argv[++i]);
        else if (strcmp(argv[i], "--scene") == 0 && i + 1 < argc) only_scene = argv[++i];
        else if (strcmp(argv[i], "--threshold") == 0 && i + 1 < argc) only_threshold = (float)atof(argv[++i]);
        else if (strcmp(argv[i], "--only") == 0 && i + 1 < argc) {
            ++i;
            for (only = 0; only < CONFIGS && strcmp(argv[i], config_name[only]) != 0; ++only) {}
            if (only == CONFIGS) { fprintf(stderr, "unknown configuration %s\n", argv[i]); return 2; }
        }
        else { fprintf(stderr, "usage: ao_stereo [--quick] [--data DIR] [--frames N] [--reps N] [--samples N]\n"); return 2; }
    }
    if (quick) { frames = 1; reps = 1; }
    if (frames < 1) frames = 1;
    if (frames > MAX_FRAMES) frames = MAX_FRAMES;
    if (reps < 1) reps = 1;
    if (samples < 1) samples = 1;
    for (k = 0; k <= 2 * BF_RADIUS; ++k) {
        float d = (float)(k - BF_RADIUS);
        bf_spatial[k] = expf(-d * d / (2.0f * BF_SIGMA * BF_SIGMA));
    }
    if (only >= 0) {
        scene s;
        int bad;
        if (strncmp(only_scene, "synthetic", 9) == 0)
            bad = scene_synthetic(&s, only_scene, strcmp(only_scene, "synthetic-static") == 0
                                                      ? SBL_SCENE_STATIC : SBL_SCENE_DYNAMIC,
                                  320, 180, frames, samples);
        else {
            snprintf(path, sizeof path, "%s/%s", data, only_scene);
            bad = scene_dataset(&s, path, frames, samples);
        }
        if (bad) return 1;
        count_config(&s, only, only_threshold);
        scene_free(&s);
        return 0;
    }
    printf("# stereo-consistent SSAO (Wu's Mono / FSA / Variant 1 / Variant 2) on stereoblend.h's\n"
           "# consistency mask; ms = median thread CPU ms per stereo frame (both eyes), single thread,\n"
           "# %d run%s per frame, the configurations side by side\n",
           reps, reps > 1 ? "s" : "");
    {
        static const struct { const char *name; sbl_scene_kind kind; } synth[] = {
            {"synthetic-dynamic", SBL_SCENE_DYNAMIC}, {"synthetic-static", SBL_SCENE_STATIC}};
        for (i = 0; i < (quick ? 1 : 2); ++i) {
            scene s;
            if (scene_synthetic(&s, synth[i].name, synth[i].kind, quick ? 160 : 320, quick ? 90 : 180,
                                frames, samples) != 0) { fprintf(stderr, "render failed\n"); return 1; }
            report(&s, reps, 0);
            scene_free(&s);
        }
    }
    if (!sbl_exr_available()) {
        printf("\n(real renders skipped: built without OpenEXR)\n");
        return 0;
    }
    {
        static const char *const names[] = {"atrium", "gallery"};
        for (i = 0; i < 2; ++i) {
            scene s;
            snprintf(path, sizeof path, "%s/%s", data, names[i]);
            if (scene_dataset(&s, path, frames, samples) != 0) continue;
            report(&s, reps, !quick && i == 0);
            scene_free(&s);
        }
    }
    return 0;
}
