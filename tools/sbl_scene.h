/* sbl_scene.h - deterministic synthetic stereo scene source for testing stereoblend.h
 *
 * An analytic ray caster (boxes + spheres, ~30 primitives, no dependencies beyond libc/libm)
 * that produces, per frame and eye: a 1-spp Monte-Carlo colour, a reference (mean of ref_spp
 * samples of the same estimator, so E[1 spp] = reference), and exact point-sampled G-buffers
 * (planar depth, world normal, object id, backward motion vectors) plus camera matrices.
 *
 *   #define SBL_SCENE_IMPLEMENTATION
 *   #include "sbl_scene.h"
 *
 * Conventions (the same as ../shared/data/README.md, the Blender renders):
 *   - world is Z-up, metres (like Blender). Camera space: looks down -z, +y up, +x right.
 *   - pixel (i, j) has its centre at (u, v) = (i + 0.5, j + 0.5), u right, v DOWN, row 0 = top;
 *     principal point (W/2, H/2); fx = fy = focal_px.
 *   - depth is planar (along the view axis), metres; background = 1e10.
 *   - parallel stereo rig: the head sits between the eyes, left = head - b/2 * right,
 *     right = head + b/2 * right, same orientation; the right-eye match of left pixel (u, v)
 *     at planar depth z is (u - focal_px * b / z, v).
 *   - motion (mx, my) in pixels, row-down: the surface point seen at the pixel centre was at
 *     (u + mx, v + my) in the previous frame (frame - 1, same eye). Blender's Vector pass
 *     would be (X, Y) = (mx, -my). Camera and object motion included; shading motion
 *     (moving light, highlights) is not, as in a real engine.
 *   - world_to_cam, proj: row-major 4x4; clip = proj * world_to_cam * (x, y, z, 1);
 *     u = (ndc_x + 1) / 2 * W, v = (1 - ndc_y) / 2 * H. near 0.05, far 200.
 *
 * Scene (an open-roofed court, ids by name via sbl_scene_object_name): checker floor with
 * 4 cm grain and a slight gloss, brick back wall, plaster side wall, two stone columns, three
 * wooden crates, a glossy red sphere, a gold metal sphere, a small green sphere, a railing of
 * 17 posts 2 cm wide at ~9 m (~0.3 px at 160 px wide), a ball rolling across the floor
 * (rotating: object motion + disocclusion), a 2 m square area light circling at 4 m height,
 * sky. Values: reference 0..~7, mean ~0.4.
 *
 * Noise: one sample = box-filter AA jitter in the pixel + one area-light sample + one cosine
 * hemisphere sample (one-bounce indirect / sky occlusion) + one glossy-lobe sample (MIS with
 * the light sample), clamped to 10 per sample (as Cycles' clamp: applied to every render, so
 * E[1 spp] = reference still). Every random number is a counter-based hash of (seed, stream,
 * frame, eye, x, y, sample, dimension): any row split or evaluation order gives identical
 * bytes, and frames, eyes and the colour/reference/ladder streams are independent. Samples are
 * not stratified. Bytes are identical across gcc/clang on x86-64; -ffast-math or FMA
 * contraction (other targets) may change the last bits.
 *
 * Thread safety: the render functions only read their arguments; split rows between threads.
 */
#ifndef SBL_SCENE_H
#define SBL_SCENE_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sbl_scene_kind {
    SBL_SCENE_DYNAMIC = 0,   /* everything: moving camera (smooth + jitter), moving object, moving light, glossy, thin posts */
    SBL_SCENE_STATIC,        /* nothing moves: fixed camera, fixed light (for convergence tests) */
    SBL_SCENE_SHADOW,        /* fixed camera and geometry, only the light moves (motion vectors are exactly 0) */
    SBL_SCENE_PAN            /* camera translates smoothly sideways, no jitter, static scene and light */
} sbl_scene_kind;

typedef struct sbl_scene_desc {
    int width, height;   /* 0 -> 160 x 90 (if only one is 0 it follows 16:9 from the other) */
    int frames;          /* 0 -> 16 (only used to time the animation: t = frame / frames) */
    unsigned seed;       /* noise seed (does not change geometry or camera jitter) */
    int ref_spp;         /* 0 -> 64 */
    sbl_scene_kind kind;
    int jitter;          /* camera head-tracking jitter on (DYNAMIC only) */
    /* additions (0 = default) */
    float baseline;      /* 0 -> 0.065 m */
    float hfov_deg;      /* 0 -> 65 degrees horizontal field of view */
    int bg_motion;       /* 0: motion 0 on the background (as Blender); 1: rotation-only motion of the sky */
    /* Heavy-tailed samples (0 = off): each sample of the colour and ladder streams is, with
       probability spike_rate, (1 + spike_gain) times its radiance, otherwise 1 times, both
       divided by (1 + spike_rate spike_gain) so that the mean, and so the reference (rendered
       without spikes), are unchanged: a fraction r g / (1 + r g) of the energy arrives in
       the rare samples, as unclamped light paths of low probability deliver it. Applied after
       the per-sample clamp. */
    float spike_rate, spike_gain;
} sbl_scene_desc;

typedef struct sbl_scene_view {   /* one eye, one frame; caller allocates every non-NULL array */
    float *color;      /* w*h*3, 1 spp (may be NULL to skip) */
    float *reference;  /* w*h*3, ref_spp (may be NULL to skip) */
    float *depth;      /* w*h, planar depth along the view axis (positive, metres); background (sky) = 1e10f */
    float *normal;     /* w*h*3 world-space unit normal at the pixel centre; 0,0,0 on background */
    float *id;         /* w*h object id as float, >0 distinct per object, 0 = background */
    float *motion;     /* w*h*2 backward motion in pixels, row-down (see above) */
    float world_to_cam[16]; /* row-major; camera looks down -z, +y up, +x right (OpenGL/Blender) */
    float proj[16];         /* row-major OpenGL-style clip matrix */
    float focal_px, baseline;
} sbl_scene_view;

#define SBL_SCENE_OK 0
#define SBL_SCENE_EBADARG 1

/* Fills zero fields with defaults. */
void sbl_scene_defaults(sbl_scene_desc *d);
/* Render eye (0 = left, 1 = right) of frame (>= 0). Rows [y0,y1) only (so callers can thread);
 * the matrices, focal_px and baseline are always filled. Returns 0 on success, nonzero on bad
 * arguments. */
int sbl_scene_render(const sbl_scene_desc *d, int frame, int eye, sbl_scene_view *out, int y0, int y1);
/* Mean of spp samples with a seed independent of color/reference and of other spp values
 * (for effective-spp ladders): w*h*3, rows [y0,y1). */
int sbl_scene_render_spp(const sbl_scene_desc *d, int frame, int eye, int spp, float *color, int y0, int y1);
/* Per-pixel statistics of one 1-spp colour sample (spikes included, as in the colour
 * stream) from spp >= 2 samples of a stream of their own: their mean (if mean is not NULL;
 * a reference independent of the others) and their unbiased sample variance, each w*h*3,
 * rows [y0,y1). The variance is what a renderer would call the pixel's noise level; the
 * bench's statistics oracle uses both. */
int sbl_scene_render_variance(const sbl_scene_desc *d, int frame, int eye, int spp, float *mean,
                              float *variance, int y0, int y1);
/* Object ids are 1..sbl_scene_object_count(); names for reports ("floor", "ball", "post03"...). */
int sbl_scene_object_count(void);
const char *sbl_scene_object_name(int id);   /* NULL for unknown ids */

#ifdef __cplusplus
}
#endif

#endif /* SBL_SCENE_H */

#ifdef SBL_SCENE_IMPLEMENTATION
#ifndef SBL_SCENE_IMPLEMENTATION_DONE
#define SBL_SCENE_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>
#include <stdint.h>

#define SBL_SCENE__PI 3.14159265358979323846
#define SBL_SCENE__MAXOBJ 40
#define SBL_SCENE__NPOST 17
#define SBL_SCENE__EPS 1e-4          /* ray offset (m); posts are 2 cm, so well below detail */
#define SBL_SCENE__CLAMP 10.0        /* per-sample clamp (like Cycles' clamp): keeps fireflies
                                        moderate; applied to reference too, so E[1 spp] = ref */
#define SBL_SCENE__NEAR 0.05
#define SBL_SCENE__FAR 200.0

enum { SBL_SCENE__BOX = 0, SBL_SCENE__SPHERE = 1 };
enum {
    SBL_SCENE__M_FLOOR = 0, SBL_SCENE__M_BRICK, SBL_SCENE__M_PLASTER, SBL_SCENE__M_STONE,
    SBL_SCENE__M_WOOD, SBL_SCENE__M_RED, SBL_SCENE__M_METAL, SBL_SCENE__M_POST,
    SBL_SCENE__M_BALL, SBL_SCENE__M_GREEN
};
/* object ids (1-based, stable: tests may refer to names) */
enum {
    SBL_SCENE__ID_FLOOR = 1, SBL_SCENE__ID_BACKWALL, SBL_SCENE__ID_SIDEWALL, SBL_SCENE__ID_COLUMN0,
    SBL_SCENE__ID_COLUMN1, SBL_SCENE__ID_CRATE0, SBL_SCENE__ID_CRATE1, SBL_SCENE__ID_CRATE2,
    SBL_SCENE__ID_GLOSSY, SBL_SCENE__ID_METAL, SBL_SCENE__ID_SMALL, SBL_SCENE__ID_BALL,
    SBL_SCENE__ID_RAIL, SBL_SCENE__ID_POST0
};
#define SBL_SCENE__NOBJ (SBL_SCENE__ID_POST0 + SBL_SCENE__NPOST - 1)

typedef struct sbl_scene__obj {
    int kind, id, mat;
    double lo[3], hi[3];          /* box bounds */
    double c[3], r;               /* sphere centre, radius */
    double rot[9];                /* sphere orientation (local -> world), row-major */
    double pc[3], prot[9];        /* previous frame centre and orientation */
    int moved;                    /* pose differs from the previous frame */
} sbl_scene__obj;

typedef struct sbl_scene__cam {
    double pos[3];
    double rot[9];   /* row-major, columns = camera right, up, back (+z) in world */
} sbl_scene__cam;

typedef struct sbl_scene__world {
    sbl_scene__obj obj[SBL_SCENE__MAXOBJ];
    int nobj, nmain;               /* objects [nmain, nobj) are the railing, behind one bound */
    double glo[3], ghi[3];         /* railing bound */
    double lc[3], lex[3], ley[3], larea, le[3];  /* rectangular area light, emits down (-z) */
    sbl_scene__cam cam, pcam;
    int cam_moved;
    int w, h;
    double f;
    int bg_motion;
} sbl_scene__world;

typedef struct sbl_scene__hit {
    double t;
    int obj;
    double n[3];   /* outward geometric normal */
} sbl_scene__hit;

/* ---------- random numbers: counter-based, order independent ---------- */

static uint32_t sbl_scene__mix(uint32_t x)
{
    /* MurmurHash3 32-bit finaliser constants: a bijective, well-avalanched mixer */
    x ^= x >> 16; x *= 0x85ebca6bu;
    x ^= x >> 13; x *= 0xc2b2ae35u;
    x ^= x >> 16;
    return x;
}

static uint32_t sbl_scene__key(uint32_t k, uint32_t v)
{
    return sbl_scene__mix(k + 0x9e3779b9u + sbl_scene__mix(v ^ 0x5bd1e995u));
}

static double sbl_scene__rnd(uint32_t sample_key, int dim)
{
    uint32_t h = sbl_scene__mix(sample_key + (uint32_t)(dim + 1) * 0x9e3779b9u);
    return (double)(h >> 8) * (1.0 / 16777216.0);   /* [0, 1) */
}

/* ---------- small vector helpers ---------- */

static double sbl_scene__dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void sbl_scene__norm(double a[3])
{
    double l = sqrt(sbl_scene__dot(a, a));
    if (l > 0.0) { a[0] /= l; a[1] /= l; a[2] /= l; }
}

static void sbl_scene__cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static void sbl_scene__basis(const double n[3], double t[3], double b[3])
{
    double a[3] = { 0.0, 0.0, 0.0 };
    if (fabs(n[0]) < 0.6) a[0] = 1.0; else a[1] = 1.0;
    sbl_scene__cross(n, a, t); sbl_scene__norm(t);
    sbl_scene__cross(n, t, b);
}

/* m (row-major 3x3) times v */
static void sbl_scene__mul3(const double m[9], const double v[3], double r[3])
{
    r[0] = m[0] * v[0] + m[1] * v[1] + m[2] * v[2];
    r[1] = m[3] * v[0] + m[4] * v[1] + m[5] * v[2];
    r[2] = m[6] * v[0] + m[7] * v[1] + m[8] * v[2];
}

/* transpose(m) times v */
static void sbl_scene__mul3t(const double m[9], const double v[3], double r[3])
{
    r[0] = m[0] * v[0] + m[3] * v[1] + m[6] * v[2];
    r[1] = m[1] * v[0] + m[4] * v[1] + m[7] * v[2];
    r[2] = m[2] * v[0] + m[5] * v[1] + m[8] * v[2];
}

/* ---------- animation ---------- */

static void sbl_scene__apply_defaults(sbl_scene_desc *d)
{
    if (d->width <= 0 && d->height <= 0) { d->width = 160; d->height = 90; }
    else if (d->width <= 0) d->width = (d->height * 16 + 8) / 9;
    else if (d->height <= 0) d->height = (d->width * 9 + 8) / 16;
    if (d->frames <= 0) d->frames = 16;
    if (d->ref_spp <= 0) d->ref_spp = 64;
    if (!(d->baseline > 0.0f)) d->baseline = 0.065f;
    if (!(d->hfov_deg > 0.0f)) d->hfov_deg = 65.0f;
}

#define SBL_SCENE__T_FIXED 0.35   /* the animation time used by everything that does not move */

static void sbl_scene__camera(const sbl_scene_desc *d, int frame, int eye, sbl_scene__cam *c)
{
    double t = (double)frame / (double)d->frames;
    double ts = (d->kind == SBL_SCENE_DYNAMIC) ? t : SBL_SCENE__T_FIXED;
    double pos[3], yaw, pitch, roll = 0.0;
    double fw[3], rt[3], up[3], upw[3] = { 0.0, 0.0, 1.0 }, cr, sr, r2[3], u2[3];
    int i;
    /* smooth path: dolly forward with a slow yaw and a little sway */
    pos[0] = 0.25 * sin(SBL_SCENE__PI * ts);
    pos[1] = -1.6 + 1.5 * ts;
    pos[2] = 1.6 + 0.02 * sin(2.0 * SBL_SCENE__PI * ts);
    yaw = 0.10 * sin(SBL_SCENE__PI * (ts - 0.3));
    pitch = -0.11;
    if (d->kind == SBL_SCENE_PAN) pos[0] += -0.5 + 1.0 * t;
    if (d->kind == SBL_SCENE_DYNAMIC && d->jitter) {
        /* head-tracking jitter: per-frame random, independent of the noise seed so that
           references rendered with another seed see the same geometry */
        uint32_t k = sbl_scene__key(0x1e4d7a11u, (uint32_t)frame);
        yaw += 0.0040 * (2.0 * sbl_scene__rnd(k, 0) - 1.0);     /* ~0.23 deg ~ 0.5 px */
        pitch += 0.0040 * (2.0 * sbl_scene__rnd(k, 1) - 1.0);
        roll += 0.0030 * (2.0 * sbl_scene__rnd(k, 2) - 1.0);
        pos[0] += 0.003 * (2.0 * sbl_scene__rnd(k, 3) - 1.0);
        pos[1] += 0.003 * (2.0 * sbl_scene__rnd(k, 4) - 1.0);
        pos[2] += 0.003 * (2.0 * sbl_scene__rnd(k, 5) - 1.0);
    }
    fw[0] = sin(yaw) * cos(pitch); fw[1] = cos(yaw) * cos(pitch); fw[2] = sin(pitch);
    sbl_scene__cross(fw, upw, rt); sbl_scene__norm(rt);
    sbl_scene__cross(rt, fw, up);
    cr = cos(roll); sr = sin(roll);
    for (i = 0; i < 3; ++i) { r2[i] = cr * rt[i] + sr * up[i]; u2[i] = -sr * rt[i] + cr * up[i]; }
    for (i = 0; i < 3; ++i) {
        c->rot[i * 3 + 0] = r2[i];
        c->rot[i * 3 + 1] = u2[i];
        c->rot[i * 3 + 2] = -fw[i];
        c->pos[i] = pos[i] + (eye ? 0.5 : -0.5) * (double)d->baseline * r2[i];
    }
}

static double sbl_scene__obj_t(const sbl_scene_desc *d, int frame)
{
    return d->kind == SBL_SCENE_DYNAMIC ? (double)frame / (double)d->frames : SBL_SCENE__T_FIXED;
}

static double sbl_scene__light_t(const sbl_scene_desc *d, int frame)
{
    return (d->kind == SBL_SCENE_DYNAMIC || d->kind == SBL_SCENE_SHADOW)
        ? (double)frame / (double)d->frames : SBL_SCENE__T_FIXED;
}

/* rolling ball: moves along +x on the floor, rotating about +y by distance / radius */
#define SBL_SCENE__BALL_R 0.3
static void sbl_scene__ball_pose(double t, double c[3], double rot[9])
{
    double dist = 3.0 * t, a = dist / SBL_SCENE__BALL_R, ca = cos(a), sa = sin(a);
    c[0] = -2.6 + dist; c[1] = 2.6; c[2] = SBL_SCENE__BALL_R;
    rot[0] = ca;  rot[1] = 0.0; rot[2] = sa;
    rot[3] = 0.0; rot[4] = 1.0; rot[5] = 0.0;
    rot[6] = -sa; rot[7] = 0.0; rot[8] = ca;
}

static sbl_scene__obj *sbl_scene__add(sbl_scene__world *w, int kind, int id, int mat)
{
    sbl_scene__obj *o = &w->obj[w->nobj++];
    memset(o, 0, sizeof(*o));
    o->kind = kind; o->id = id; o->mat = mat;
    o->rot[0] = o->rot[4] = o->rot[8] = 1.0;
    o->prot[0] = o->prot[4] = o->prot[8] = 1.0;
    return o;
}

static void sbl_scene__box(sbl_scene__world *w, int id, int mat, double x0, double y0, double z0,
                           double x1, double y1, double z1)
{
    sbl_scene__obj *o = sbl_scene__add(w, SBL_SCENE__BOX, id, mat);
    o->lo[0] = x0; o->lo[1] = y0; o->lo[2] = z0;
    o->hi[0] = x1; o->hi[1] = y1; o->hi[2] = z1;
}

static sbl_scene__obj *sbl_scene__sphere(sbl_scene__world *w, int id, int mat, double x, double y,
                                         double z, double r)
{
    sbl_scene__obj *o = sbl_scene__add(w, SBL_SCENE__SPHERE, id, mat);
    o->c[0] = o->pc[0] = x; o->c[1] = o->pc[1] = y; o->c[2] = o->pc[2] = z;
    o->r = r;
    return o;
}

static void sbl_scene__build(const sbl_scene_desc *d, int frame, int eye, sbl_scene__world *w)
{
    double tl, phi, lsz = 2.0;
    int i;
    sbl_scene__obj *o;
    memset(w, 0, sizeof(*w));
    w->w = d->width; w->h = d->height;
    w->f = 0.5 * d->width / tan(0.5 * (double)d->hfov_deg * SBL_SCENE__PI / 180.0);
    w->bg_motion = d->bg_motion;
    sbl_scene__camera(d, frame, eye, &w->cam);
    sbl_scene__camera(d, frame - 1, eye, &w->pcam);
    w->cam_moved = memcmp(&w->cam, &w->pcam, sizeof(w->cam)) != 0;

    sbl_scene__box(w, SBL_SCENE__ID_FLOOR, SBL_SCENE__M_FLOOR, -6.0, -6.0, -0.2, 14.0, 40.0, 0.0);
    sbl_scene__box(w, SBL_SCENE__ID_BACKWALL, SBL_SCENE__M_BRICK, -6.0, 10.0, 0.0, 6.0, 10.4, 3.2);
    sbl_scene__box(w, SBL_SCENE__ID_SIDEWALL, SBL_SCENE__M_PLASTER, -6.4, -6.0, 0.0, -6.0, 10.4, 3.2);
    sbl_scene__box(w, SBL_SCENE__ID_COLUMN0, SBL_SCENE__M_STONE, -3.3, 6.0, 0.0, -2.9, 6.4, 3.2);
    sbl_scene__box(w, SBL_SCENE__ID_COLUMN1, SBL_SCENE__M_STONE, 4.2, 6.0, 0.0, 4.6, 6.4, 3.2);
    sbl_scene__box(w, SBL_SCENE__ID_CRATE0, SBL_SCENE__M_WOOD, -2.2, 3.6, 0.0, -1.4, 4.4, 0.8);
    sbl_scene__box(w, SBL_SCENE__ID_CRATE1, SBL_SCENE__M_WOOD, -2.0, 3.8, 0.8, -1.6, 4.2, 1.2);
    sbl_scene__box(w, SBL_SCENE__ID_CRATE2, SBL_SCENE__M_WOOD, 1.6, 4.5, 0.0, 2.3, 5.2, 0.7);
    sbl_scene__sphere(w, SBL_SCENE__ID_GLOSSY, SBL_SCENE__M_RED, -0.4, 5.0, 0.55, 0.55);
    sbl_scene__sphere(w, SBL_SCENE__ID_METAL, SBL_SCENE__M_METAL, 0.9, 3.3, 0.4, 0.4);
    sbl_scene__sphere(w, SBL_SCENE__ID_SMALL, SBL_SCENE__M_GREEN, 1.95, 4.85, 0.95, 0.25);
    o = sbl_scene__sphere(w, SBL_SCENE__ID_BALL, SBL_SCENE__M_BALL, 0.0, 0.0, 0.0, SBL_SCENE__BALL_R);
    sbl_scene__ball_pose(sbl_scene__obj_t(d, frame), o->c, o->rot);
    sbl_scene__ball_pose(sbl_scene__obj_t(d, frame - 1), o->pc, o->prot);
    o->moved = memcmp(o->c, o->pc, sizeof(o->c)) != 0 || memcmp(o->rot, o->prot, sizeof(o->rot)) != 0;
    w->nmain = w->nobj;

    /* railing of thin posts: 2 cm wide at ~9 m, i.e. ~0.3 px at 160 px wide */
    sbl_scene__box(w, SBL_SCENE__ID_RAIL, SBL_SCENE__M_POST, 0.99, 7.99, 1.0, 5.01, 8.01, 1.02);
    for (i = 0; i < SBL_SCENE__NPOST; ++i) {
        double x = 1.0 + 0.25 * i;
        sbl_scene__box(w, SBL_SCENE__ID_POST0 + i, SBL_SCENE__M_POST, x - 0.01, 7.99, 0.0, x + 0.01, 8.01, 1.0);
    }
    for (i = 0; i < 3; ++i) { w->glo[i] = 1e30; w->ghi[i] = -1e30; }
    for (i = w->nmain; i < w->nobj; ++i) {
        int a;
        for (a = 0; a < 3; ++a) {
            if (w->obj[i].lo[a] < w->glo[a]) w->glo[a] = w->obj[i].lo[a];
            if (w->obj[i].hi[a] > w->ghi[a]) w->ghi[a] = w->obj[i].hi[a];
        }
    }

    /* area light circling above the scene: moving soft shadows over static geometry */
    tl = sbl_scene__light_t(d, frame);
    phi = 0.5 + SBL_SCENE__PI * tl;
    w->lc[0] = 0.3 + 2.2 * cos(phi); w->lc[1] = 4.5 + 2.2 * sin(phi); w->lc[2] = 4.0;
    w->lex[0] = lsz; w->ley[1] = lsz;
    w->larea = lsz * lsz;
    w->le[0] = 36.0; w->le[1] = 34.0; w->le[2] = 30.0;
}

/* ---------- intersection ---------- */

static int sbl_scene__box_hit(const double lo[3], const double hi[3], const double o[3],
                              const double inv[3], double tmin, double tmax, double *th, int *axis)
{
    int a, ax = -1;
    for (a = 0; a < 3; ++a) {
        double t0 = (lo[a] - o[a]) * inv[a], t1 = (hi[a] - o[a]) * inv[a];
        if (t0 > t1) { double tt = t0; t0 = t1; t1 = tt; }
        if (t0 > tmin) { tmin = t0; ax = a; }
        if (t1 < tmax) tmax = t1;
        if (tmin > tmax) return 0;
    }
    /* ax < 0: the entry is behind the origin (origin inside): rays start outside, no hit */
    if (ax < 0) return 0;
    *th = tmin; *axis = ax;
    return 1;
}

/* does the segment [0, tmax] overlap the box (origin inside counts) */
static int sbl_scene__bound_hit(const double lo[3], const double hi[3], const double o[3],
                                const double inv[3], double tmax)
{
    double tmin = 0.0;
    int a;
    for (a = 0; a < 3; ++a) {
        double t0 = (lo[a] - o[a]) * inv[a], t1 = (hi[a] - o[a]) * inv[a];
        if (t0 > t1) { double tt = t0; t0 = t1; t1 = tt; }
        if (t0 > tmin) tmin = t0;
        if (t1 < tmax) tmax = t1;
        if (tmin > tmax) return 0;
    }
    return 1;
}

static int sbl_scene__sphere_hit(const sbl_scene__obj *s, const double o[3], const double dir[3],
                                 double tmin, double tmax, double *th)
{
    double oc[3], b, cc, disc, t;
    oc[0] = o[0] - s->c[0]; oc[1] = o[1] - s->c[1]; oc[2] = o[2] - s->c[2];
    b = sbl_scene__dot(oc, dir);
    cc = sbl_scene__dot(oc, oc) - s->r * s->r;
    disc = b * b - cc;
    if (disc < 0.0) return 0;
    t = -b - sqrt(disc);   /* entry only: rays start outside */
    if (t <= tmin || t >= tmax) return 0;
    *th = t;
    return 1;
}

static void sbl_scene__inv(const double d[3], double inv[3])
{
    int a;
    for (a = 0; a < 3; ++a) {
        double v = d[a];
        if (fabs(v) < 1e-15) v = v < 0.0 ? -1e-15 : 1e-15;
        inv[a] = 1.0 / v;
    }
}

/* closest hit in (SBL_SCENE__EPS, tmax); dir must be unit length */
static int sbl_scene__trace(const sbl_scene__world *w, const double o[3], const double dir[3],
                            double tmax, sbl_scene__hit *h)
{
    double inv[3], t, best = tmax;
    int i, ax, bi = -1, bax = 0, e0 = 0, e1 = w->nmain, pass;
    sbl_scene__inv(dir, inv);
    for (pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            if (!sbl_scene__bound_hit(w->glo, w->ghi, o, inv, best)) break;
            e0 = w->nmain; e1 = w->nobj;
        }
        for (i = e0; i < e1; ++i) {
            const sbl_scene__obj *ob = &w->obj[i];
            if (ob->kind == SBL_SCENE__BOX) {
                if (sbl_scene__box_hit(ob->lo, ob->hi, o, inv, SBL_SCENE__EPS, best, &t, &ax)) {
                    best = t; bi = i; bax = ax;
                }
            } else if (sbl_scene__sphere_hit(ob, o, dir, SBL_SCENE__EPS, best, &t)) {
                best = t; bi = i; bax = -1;
            }
        }
    }
    if (bi < 0) return 0;
    h->t = best; h->obj = bi;
    if (bax >= 0) {
        h->n[0] = h->n[1] = h->n[2] = 0.0;
        h->n[bax] = dir[bax] > 0.0 ? -1.0 : 1.0;
    } else {
        const sbl_scene__obj *ob = &w->obj[bi];
        int a;
        for (a = 0; a < 3; ++a) h->n[a] = (o[a] + best * dir[a] - ob->c[a]) / ob->r;
        sbl_scene__norm(h->n);
    }
    return 1;
}

/* any hit in (EPS, tmax) */
static int sbl_scene__occluded(const sbl_scene__world *w, const double o[3], const double dir[3], double tmax)
{
    double inv[3], t;
    int i, ax;
    sbl_scene__inv(dir, inv);
    for (i = 0; i < w->nmain; ++i) {
        const sbl_scene__obj *ob = &w->obj[i];
        if (ob->kind == SBL_SCENE__BOX) {
            if (sbl_scene__box_hit(ob->lo, ob->hi, o, inv, SBL_SCENE__EPS, tmax, &t, &ax)) return 1;
        } else if (sbl_scene__sphere_hit(ob, o, dir, SBL_SCENE__EPS, tmax, &t)) return 1;
    }
    if (sbl_scene__bound_hit(w->glo, w->ghi, o, inv, tmax)) {
        for (i = w->nmain; i < w->nobj; ++i)
            if (sbl_scene__box_hit(w->obj[i].lo, w->obj[i].hi, o, inv, SBL_SCENE__EPS, tmax, &t, &ax)) return 1;
    }
    return 0;
}

/* ---------- materials and textures ---------- */

static double sbl_scene__h2(int x, int y, uint32_t salt)
{
    uint32_t k = sbl_scene__key(sbl_scene__key(salt, (uint32_t)x), (uint32_t)y);
    return (double)(k >> 8) * (1.0 / 16777216.0);
}

/* smooth value noise in [0,1) */
static double sbl_scene__vnoise(double x, double y, uint32_t salt)
{
    double fx = floor(x), fy = floor(y), tx = x - fx, ty = y - fy;
    int ix = (int)fx, iy = (int)fy;
    double a = sbl_scene__h2(ix, iy, salt), b = sbl_scene__h2(ix + 1, iy, salt);
    double c = sbl_scene__h2(ix, iy + 1, salt), e = sbl_scene__h2(ix + 1, iy + 1, salt);
    tx = tx * tx * (3.0 - 2.0 * tx); ty = ty * ty * (3.0 - 2.0 * ty);
    return (a + (b - a) * tx) * (1.0 - ty) + (c + (e - c) * tx) * ty;
}

static void sbl_scene__set3(double c[3], double r, double g, double b)
{
    c[0] = r; c[1] = g; c[2] = b;
}

/* material: diffuse albedo at p, specular colour ks and Phong exponent */
static void sbl_scene__material(const sbl_scene__world *w, int oi, const double p[3], const double n[3],
                                double alb[3], double ks[3], double *ex)
{
    const sbl_scene__obj *ob = &w->obj[oi];
    double s, a, b;   /* a, b: planar texture coordinates on the face (m) */
    int ax = fabs(n[0]) > 0.5 ? 0 : (fabs(n[1]) > 0.5 ? 1 : 2);
    a = ax == 0 ? p[1] : p[0];
    b = ax == 2 ? p[1] : p[2];
    ks[0] = ks[1] = ks[2] = 0.0;
    *ex = 1.0;
    switch (ob->mat) {
    case SBL_SCENE__M_FLOOR: {
        int tile = ((int)floor(p[0] / 0.5) + (int)floor(p[1] / 0.5)) & 1;
        double g = 0.8 + 0.4 * sbl_scene__vnoise(p[0] * 25.0, p[1] * 25.0, 11u);   /* 4 cm grain */
        double v = 0.9 + 0.2 * sbl_scene__h2((int)floor(p[0] / 0.5), (int)floor(p[1] / 0.5), 12u);
        if (tile) sbl_scene__set3(alb, 0.60, 0.57, 0.52); else sbl_scene__set3(alb, 0.26, 0.25, 0.25);
        s = g * v;
        alb[0] *= s; alb[1] *= s; alb[2] *= s;
        ks[0] = ks[1] = ks[2] = 0.10; *ex = 30.0;
        break;
    }
    case SBL_SCENE__M_BRICK: {
        double bh = 0.085, bw = 0.25, m = 0.012, fa, fb;
        int row = (int)floor(b / bh), col;
        double off = (row & 1) ? 0.5 * bw : 0.0;
        col = (int)floor((a + off) / bw);
        fa = a + off - col * bw; fb = b - row * bh;
        if (fa < m || fb < m) sbl_scene__set3(alb, 0.55, 0.53, 0.50);
        else {
            s = 0.75 + 0.5 * sbl_scene__h2(col, row, 21u);
            sbl_scene__set3(alb, 0.50 * s, 0.24 * s, 0.15 * s);
        }
        break;
    }
    case SBL_SCENE__M_PLASTER:
        s = 0.85 + 0.25 * sbl_scene__vnoise(a * 3.0, b * 3.0, 31u);
        sbl_scene__set3(alb, 0.68 * s, 0.66 * s, 0.60 * s);
        break;
    case SBL_SCENE__M_STONE:
        s = 0.65 + 0.35 * sbl_scene__vnoise(a * 14.0, b * 14.0, 41u + (uint32_t)ax);
        sbl_scene__set3(alb, 0.52 * s, 0.50 * s, 0.46 * s);
        break;
    case SBL_SCENE__M_WOOD: {
        int plank = (int)floor(p[2] / 0.1);
        s = (0.75 + 0.3 * sbl_scene__h2(plank, ob->id, 51u)) *
            (0.85 + 0.15 * sin(a * 40.0 + 6.0 * sbl_scene__vnoise(a * 4.0, b * 4.0, 52u)));
        if (p[2] - plank * 0.1 < 0.008) s *= 0.4;   /* gaps between planks */
        sbl_scene__set3(alb, 0.58 * s, 0.40 * s, 0.22 * s);
        break;
    }
    case SBL_SCENE__M_RED:
        sbl_scene__set3(alb, 0.55, 0.07, 0.05);
        ks[0] = ks[1] = ks[2] = 0.35; *ex = 80.0;
        break;
    case SBL_SCENE__M_METAL:
        sbl_scene__set3(alb, 0.03, 0.03, 0.03);
        sbl_scene__set3(ks, 0.70, 0.58, 0.38); *ex = 120.0;
        break;
    case SBL_SCENE__M_POST:
        sbl_scene__set3(alb, 0.10, 0.10, 0.11);
        ks[0] = ks[1] = ks[2] = 0.3; *ex = 20.0;
        break;
    case SBL_SCENE__M_BALL: {
        /* octant pattern in object space so that the rotation is visible */
        double q[3], d3[3];
        int par;
        d3[0] = p[0] - ob->c[0]; d3[1] = p[1] - ob->c[1]; d3[2] = p[2] - ob->c[2];
        sbl_scene__mul3t(ob->rot, d3, q);
        par = (q[0] > 0.0) ^ (q[1] > 0.0) ^ (q[2] > 0.0);
        if (par) sbl_scene__set3(alb, 0.80, 0.78, 0.70); else sbl_scene__set3(alb, 0.08, 0.22, 0.65);
        ks[0] = ks[1] = ks[2] = 0.15; *ex = 40.0;
        break;
    }
    default: /* SBL_SCENE__M_GREEN */
        sbl_scene__set3(alb, 0.25, 0.50, 0.20);
        break;
    }
}

static void sbl_scene__sky(const double d[3], double c[3])
{
    if (d[2] >= 0.0) {
        double s = sqrt(d[2]);
        c[0] = 0.70 + (0.25 - 0.70) * s;
        c[1] = 0.72 + (0.38 - 0.72) * s;
        c[2] = 0.76 + (0.75 - 0.76) * s;
    } else {
        sbl_scene__set3(c, 0.18, 0.16, 0.15);
    }
}

/* does the ray reach the light's rectangle (ignoring occluders); distance in *t */
static int sbl_scene__light_hit(const sbl_scene__world *w, const double o[3], const double dir[3], double *t)
{
    double tt, x, y;
    if (dir[2] <= 1e-12) return 0;   /* emits downwards only */
    tt = (w->lc[2] - o[2]) / dir[2];
    if (tt <= SBL_SCENE__EPS) return 0;
    x = o[0] + tt * dir[0] - w->lc[0];
    y = o[1] + tt * dir[1] - w->lc[1];
    if (fabs(x) > 0.5 * w->lex[0] || fabs(y) > 0.5 * w->ley[1]) return 0;
    *t = tt;
    return 1;
}

/* radiance arriving along a secondary ray: sky, or a cheap one-bounce estimate at the hit
   (unshadowed light from the light centre + constant ambient); it only has to be a fixed
   function so that 1 spp and the reference share it. tmax < 1e30 when the ray would reach
   the light: returns 1 (and L untouched) if it does so unoccluded. */
static int sbl_scene__radiance2(const sbl_scene__world *w, const double o[3], const double dir[3],
                                double tmax, double L[3])
{
    sbl_scene__hit h;
    double p[3], alb[3], ks[3], ex, wl[3], d2, cs, cl, e, amb;
    int a;
    if (!sbl_scene__trace(w, o, dir, tmax, &h)) {
        if (tmax < 1e30) return 1;
        sbl_scene__sky(dir, L);
        return 0;
    }
    for (a = 0; a < 3; ++a) p[a] = o[a] + h.t * dir[a];
    if (sbl_scene__dot(h.n, dir) > 0.0) { h.n[0] = -h.n[0]; h.n[1] = -h.n[1]; h.n[2] = -h.n[2]; }
    sbl_scene__material(w, h.obj, p, h.n, alb, ks, &ex);
    for (a = 0; a < 3; ++a) wl[a] = w->lc[a] - p[a];
    d2 = sbl_scene__dot(wl, wl);
    sbl_scene__norm(wl);
    cs = sbl_scene__dot(h.n, wl); cl = wl[2];
    e = (cs > 0.0 && cl > 0.0) ? w->larea * cs * cl / (d2 * SBL_SCENE__PI) : 0.0;
    amb = 0.22 + 0.12 * h.n[2];
    for (a = 0; a < 3; ++a) L[a] = alb[a] * (w->le[a] * e + amb);
    return 0;
}

static void sbl_scene__ray(const sbl_scene__world *w, const sbl_scene__cam *c, double u, double v, double dir[3])
{
    double dc[3];
    dc[0] = (u - 0.5 * w->w) / w->f;
    dc[1] = -(v - 0.5 * w->h) / w->f;
    dc[2] = -1.0;
    sbl_scene__mul3(c->rot, dc, dir);
    sbl_scene__norm(dir);
}

/* one Monte-Carlo sample of pixel (x, y): AA jitter, one area-light sample, one cosine
   hemisphere sample, one glossy-lobe sample */
static void sbl_scene__sample(const sbl_scene__world *w, int x, int y, uint32_t k, double L[3])
{
    sbl_scene__hit h;
    double dir[3], p[3], o[3], n[3], alb[3], ks[3], ex, r[3], q[3], wi[3], t1[3], t2[3], Li[3];
    double u1, u2, d2, dist, cs, cl, m;
    int a;
    sbl_scene__ray(w, &w->cam, x + sbl_scene__rnd(k, 0), y + sbl_scene__rnd(k, 1), dir);
    if (!sbl_scene__trace(w, w->cam.pos, dir, 1e30, &h)) { sbl_scene__sky(dir, L); return; }
    for (a = 0; a < 3; ++a) { p[a] = w->cam.pos[a] + h.t * dir[a]; n[a] = h.n[a]; }
    if (sbl_scene__dot(n, dir) > 0.0) { n[0] = -n[0]; n[1] = -n[1]; n[2] = -n[2]; }
    sbl_scene__material(w, h.obj, p, n, alb, ks, &ex);
    m = -2.0 * sbl_scene__dot(dir, n);
    for (a = 0; a < 3; ++a) { r[a] = dir[a] + m * n[a]; o[a] = p[a] + SBL_SCENE__EPS * n[a]; }
    L[0] = L[1] = L[2] = 0.0;

    /* direct light: one uniform point on the rectangle */
    u1 = sbl_scene__rnd(k, 2) - 0.5; u2 = sbl_scene__rnd(k, 3) - 0.5;
    for (a = 0; a < 3; ++a) { q[a] = w->lc[a] + u1 * w->lex[a] + u2 * w->ley[a]; wi[a] = q[a] - o[a]; }
    d2 = sbl_scene__dot(wi, wi); dist = sqrt(d2);
    for (a = 0; a < 3; ++a) wi[a] /= dist;
    cs = sbl_scene__dot(n, wi); cl = wi[2];
    if (cs > 0.0 && cl > 0.0 && !sbl_scene__occluded(w, o, wi, dist - SBL_SCENE__EPS)) {
        double g = cs * cl * w->larea / d2, rs = sbl_scene__dot(r, wi), sp = 0.0;
        if (rs > 0.0 && ex > 1.0) {
            /* the glossy ray below also reaches the light: balance-heuristic MIS weight */
            double pb = (ex + 1.0) / (2.0 * SBL_SCENE__PI) * pow(rs, ex), pl = d2 / (cl * w->larea);
            sp = (ex + 2.0) / (ex + 1.0) * pb * (pl / (pl + pb));
        }
        for (a = 0; a < 3; ++a) L[a] += w->le[a] * (alb[a] / SBL_SCENE__PI + ks[a] * sp) * g;
    }

    /* diffuse bounce: cosine-weighted, so the estimator is albedo * L_in */
    sbl_scene__basis(n, t1, t2);
    u1 = sbl_scene__rnd(k, 4); u2 = 2.0 * SBL_SCENE__PI * sbl_scene__rnd(k, 5);
    {
        double rr = sqrt(u1), zz = sqrt(1.0 - u1), cx = rr * cos(u2), cy = rr * sin(u2);
        for (a = 0; a < 3; ++a) wi[a] = cx * t1[a] + cy * t2[a] + zz * n[a];
    }
    sbl_scene__radiance2(w, o, wi, 1e30, Li);   /* the light is covered by the direct term */
    for (a = 0; a < 3; ++a) L[a] += alb[a] * Li[a];

    /* glossy lobe: Phong lobe around the mirror direction, pdf (e+1)/(2pi) cos^e; it may
       hit the light (MIS with the direct term) so narrow highlights are not fireflies */
    if (ks[0] + ks[1] + ks[2] > 0.0) {
        double ca, sa, cn;
        sbl_scene__basis(r, t1, t2);
        ca = pow(sbl_scene__rnd(k, 6), 1.0 / (ex + 1.0));
        sa = sqrt(1.0 - ca * ca);
        u2 = 2.0 * SBL_SCENE__PI * sbl_scene__rnd(k, 7);
        for (a = 0; a < 3; ++a) wi[a] = sa * cos(u2) * t1[a] + sa * sin(u2) * t2[a] + ca * r[a];
        cn = sbl_scene__dot(n, wi);
        if (cn > 0.0) {
            double wgt = (ex + 2.0) / (ex + 1.0) * cn, tl = 1e30;
            int lh = sbl_scene__light_hit(w, o, wi, &tl);
            if (sbl_scene__radiance2(w, o, wi, lh ? tl : 1e30, Li)) {
                double pb = (ex + 1.0) / (2.0 * SBL_SCENE__PI) * pow(ca, ex), pl = tl * tl / (wi[2] * w->larea);
                wgt *= pb / (pb + pl);
                for (a = 0; a < 3; ++a) Li[a] = w->le[a];
            }
            for (a = 0; a < 3; ++a) L[a] += ks[a] * wgt * Li[a];
        }
    }

    m = L[0] > L[1] ? L[0] : L[1];
    if (L[2] > m) m = L[2];
    if (m > SBL_SCENE__CLAMP) { m = SBL_SCENE__CLAMP / m; L[0] *= m; L[1] *= m; L[2] *= m; }
}

/* streams keep colour, reference, each ladder level and the variance independent */
enum { SBL_SCENE__S_COLOR = 1, SBL_SCENE__S_REF = 2, SBL_SCENE__S_LADDER = 3, SBL_SCENE__S_VAR = 4 };

/* dst (if not NULL): the mean of spp samples; var (if not NULL, spp >= 2): their unbiased
   variance */
static void sbl_scene__shade_rows_var(const sbl_scene__world *w, const sbl_scene_desc *d, int frame,
                                      int eye, uint32_t stream, int spp, float *dst, float *var,
                                      int y0, int y1);

static void sbl_scene__shade_rows(const sbl_scene__world *w, const sbl_scene_desc *d, int frame, int eye,
                                  uint32_t stream, int spp, float *dst, int y0, int y1)
{
    sbl_scene__shade_rows_var(w, d, frame, eye, stream, spp, dst, NULL, y0, y1);
}

static void sbl_scene__shade_rows_var(const sbl_scene__world *w, const sbl_scene_desc *d, int frame,
                                      int eye, uint32_t stream, int spp, float *dst, float *var,
                                      int y0, int y1)
{
    uint32_t kb = sbl_scene__key(sbl_scene__key(sbl_scene__key(sbl_scene__mix(d->seed), stream),
                                                (uint32_t)frame), (uint32_t)eye);
    double inv = 1.0 / spp;
    /* the spikes (sbl_scene_desc.spike_rate); never in the reference stream */
    const int spikes = stream != SBL_SCENE__S_REF && d->spike_rate > 0.0f && d->spike_gain > 0.0f;
    const double body = 1.0 / (1.0 + (double)d->spike_rate * d->spike_gain);
    const double spike = (1.0 + (double)d->spike_gain) * body;
    int x, y, s;
    for (y = y0; y < y1; ++y) {
        uint32_t ky = sbl_scene__key(kb, (uint32_t)y);
        for (x = 0; x < w->w; ++x) {
            uint32_t kp = sbl_scene__key(ky, (uint32_t)x);
            double acc[3] = { 0.0, 0.0, 0.0 }, sq[3] = { 0.0, 0.0, 0.0 }, L[3];
            const size_t i = (size_t)y * (size_t)w->w + (size_t)x;
            float *px = dst ? dst + i * 3 : NULL;
            int c;
            for (s = 0; s < spp; ++s) {
                const uint32_t ks = sbl_scene__key(kp, (uint32_t)s);
                sbl_scene__sample(w, x, y, ks, L);
                if (spikes) {
                    const double g = sbl_scene__rnd(ks, 8) < (double)d->spike_rate ? spike : body;
                    L[0] *= g; L[1] *= g; L[2] *= g;
                }
                acc[0] += L[0]; acc[1] += L[1]; acc[2] += L[2];
                if (var) { sq[0] += L[0] * L[0]; sq[1] += L[1] * L[1]; sq[2] += L[2] * L[2]; }
            }
            if (px) { px[0] = (float)(acc[0] * inv); px[1] = (float)(acc[1] * inv); px[2] = (float)(acc[2] * inv); }
            for (c = 0; var && c < 3; ++c) {
                const double v = (sq[c] - acc[c] * acc[c] * inv) / (spp - 1);
                var[i * 3 + c] = (float)(v > 0.0 ? v : 0.0);
            }
        }
    }
}

/* project a world point with a camera; returns 0 when it is not in front */
static int sbl_scene__project(const sbl_scene__world *w, const sbl_scene__cam *c, const double p[3],
                              double *u, double *v)
{
    double d[3], q[3];
    d[0] = p[0] - c->pos[0]; d[1] = p[1] - c->pos[1]; d[2] = p[2] - c->pos[2];
    sbl_scene__mul3t(c->rot, d, q);
    if (q[2] > -1e-9) return 0;
    *u = 0.5 * w->w + w->f * q[0] / -q[2];
    *v = 0.5 * w->h - w->f * q[1] / -q[2];
    return 1;
}

static void sbl_scene__gbuffer_rows(const sbl_scene__world *w, sbl_scene_view *out, int y0, int y1)
{
    int x, y, a;
    double fw[3];
    fw[0] = -w->cam.rot[2]; fw[1] = -w->cam.rot[5]; fw[2] = -w->cam.rot[8];
    for (y = y0; y < y1; ++y) {
        for (x = 0; x < w->w; ++x) {
            size_t i = (size_t)y * (size_t)w->w + (size_t)x;
            double dir[3], p[3], d3[3], u = x + 0.5, v = y + 0.5, mx = 0.0, my = 0.0;
            sbl_scene__hit h;
            sbl_scene__ray(w, &w->cam, u, v, dir);
            if (!sbl_scene__trace(w, w->cam.pos, dir, 1e30, &h)) {
                if (out->depth) out->depth[i] = 1e10f;
                if (out->normal) out->normal[i * 3] = out->normal[i * 3 + 1] = out->normal[i * 3 + 2] = 0.0f;
                if (out->id) out->id[i] = 0.0f;
                if (out->motion) {
                    if (w->bg_motion && w->cam_moved) {
                        /* a direction at infinity only sees the camera rotation */
                        double q[3], up, vp;
                        for (a = 0; a < 3; ++a) q[a] = w->pcam.pos[a] + dir[a];
                        if (sbl_scene__project(w, &w->pcam, q, &up, &vp)) { mx = up - u; my = vp - v; }
                    }
                    out->motion[i * 2] = (float)mx; out->motion[i * 2 + 1] = (float)my;
                }
                continue;
            }
            for (a = 0; a < 3; ++a) { p[a] = w->cam.pos[a] + h.t * dir[a]; d3[a] = p[a] - w->cam.pos[a]; }
            if (out->depth) out->depth[i] = (float)sbl_scene__dot(d3, fw);
            if (out->normal) for (a = 0; a < 3; ++a) out->normal[i * 3 + a] = (float)h.n[a];
            if (out->id) out->id[i] = (float)w->obj[h.obj].id;
            if (out->motion) {
                const sbl_scene__obj *ob = &w->obj[h.obj];
                if (w->cam_moved || ob->moved) {
                    double pp[3], up, vp;
                    if (ob->moved) {
                        double loc[3], rel[3];
                        for (a = 0; a < 3; ++a) rel[a] = p[a] - ob->c[a];
                        sbl_scene__mul3t(ob->rot, rel, loc);
                        sbl_scene__mul3(ob->prot, loc, pp);
                        for (a = 0; a < 3; ++a) pp[a] += ob->pc[a];
                    } else {
                        for (a = 0; a < 3; ++a) pp[a] = p[a];
                    }
                    /* behind the previous camera: a huge vector so every reprojection fails */
                    if (sbl_scene__project(w, &w->pcam, pp, &up, &vp)) { mx = up - u; my = vp - v; }
                    else { mx = 1e6; my = 1e6; }
                }
                out->motion[i * 2] = (float)mx; out->motion[i * 2 + 1] = (float)my;
            }
        }
    }
}

static void sbl_scene__matrices(const sbl_scene__world *w, sbl_scene_view *out, float baseline)
{
    int r, c;
    double t[3];
    memset(out->world_to_cam, 0, sizeof(out->world_to_cam));
    memset(out->proj, 0, sizeof(out->proj));
    sbl_scene__mul3t(w->cam.rot, w->cam.pos, t);
    for (r = 0; r < 3; ++r) {
        for (c = 0; c < 3; ++c) out->world_to_cam[r * 4 + c] = (float)w->cam.rot[c * 3 + r];
        out->world_to_cam[r * 4 + 3] = (float)-t[r];
    }
    out->world_to_cam[15] = 1.0f;
    out->proj[0] = (float)(2.0 * w->f / w->w);
    out->proj[5] = (float)(2.0 * w->f / w->h);
    out->proj[10] = (float)(-(SBL_SCENE__FAR + SBL_SCENE__NEAR) / (SBL_SCENE__FAR - SBL_SCENE__NEAR));
    out->proj[11] = (float)(-2.0 * SBL_SCENE__FAR * SBL_SCENE__NEAR / (SBL_SCENE__FAR - SBL_SCENE__NEAR));
    out->proj[14] = -1.0f;
    out->focal_px = (float)w->f;
    out->baseline = baseline;
}

static int sbl_scene__check(const sbl_scene_desc *in, sbl_scene_desc *d, int frame, int eye, int y0, int y1)
{
    if (!in) return 0;
    *d = *in;
    sbl_scene__apply_defaults(d);
    if (frame < 0 || (eye != 0 && eye != 1)) return 0;
    if ((int)d->kind < (int)SBL_SCENE_DYNAMIC || (int)d->kind > (int)SBL_SCENE_PAN) return 0;
    if (d->width > 65536 || d->height > 65536) return 0;
    if (y0 < 0 || y1 > d->height || y0 > y1) return 0;
    if (!(d->spike_rate >= 0.0f && d->spike_rate <= 1.0f) || !(d->spike_gain >= 0.0f && d->spike_gain <= 1e6f)) return 0;
    return 1;
}

void sbl_scene_defaults(sbl_scene_desc *d)
{
    if (d) sbl_scene__apply_defaults(d);
}

int sbl_scene_render(const sbl_scene_desc *desc, int frame, int eye, sbl_scene_view *out, int y0, int y1)
{
    sbl_scene_desc d;
    sbl_scene__world w;
    if (!out || !sbl_scene__check(desc, &d, frame, eye, y0, y1)) return SBL_SCENE_EBADARG;
    sbl_scene__build(&d, frame, eye, &w);
    sbl_scene__matrices(&w, out, d.baseline);
    if (out->depth || out->normal || out->id || out->motion) sbl_scene__gbuffer_rows(&w, out, y0, y1);
    if (out->color) sbl_scene__shade_rows(&w, &d, frame, eye, SBL_SCENE__S_COLOR, 1, out->color, y0, y1);
    if (out->reference) sbl_scene__shade_rows(&w, &d, frame, eye, SBL_SCENE__S_REF, d.ref_spp, out->reference, y0, y1);
    return SBL_SCENE_OK;
}

int sbl_scene_render_spp(const sbl_scene_desc *desc, int frame, int eye, int spp, float *color, int y0, int y1)
{
    sbl_scene_desc d;
    sbl_scene__world w;
    if (!color || spp < 1 || !sbl_scene__check(desc, &d, frame, eye, y0, y1)) return SBL_SCENE_EBADARG;
    sbl_scene__build(&d, frame, eye, &w);
    sbl_scene__shade_rows(&w, &d, frame, eye, sbl_scene__key(SBL_SCENE__S_LADDER, (uint32_t)spp), spp, color, y0, y1);
    return SBL_SCENE_OK;
}

int sbl_scene_render_variance(const sbl_scene_desc *desc, int frame, int eye, int spp, float *mean,
                              float *variance, int y0, int y1)
{
    sbl_scene_desc d;
    sbl_scene__world w;
    if (!variance || spp < 2 || !sbl_scene__check(desc, &d, frame, eye, y0, y1)) return SBL_SCENE_EBADARG;
    sbl_scene__build(&d, frame, eye, &w);
    sbl_scene__shade_rows_var(&w, &d, frame, eye, SBL_SCENE__S_VAR, spp, mean, variance, y0, y1);
    return SBL_SCENE_OK;
}

int sbl_scene_object_count(void)
{
    return SBL_SCENE__NOBJ;
}

const char *sbl_scene_object_name(int id)
{
    static const char *const names[SBL_SCENE__ID_POST0] = {
        "background", "floor", "backwall", "sidewall", "column0", "column1", "crate0", "crate1",
        "crate2", "glossy_sphere", "metal_sphere", "small_sphere", "ball", "rail"
    };
    static const char *const posts[SBL_SCENE__NPOST] = {
        "post00", "post01", "post02", "post03", "post04", "post05", "post06", "post07", "post08",
        "post09", "post10", "post11", "post12", "post13", "post14", "post15", "post16"
    };
    if (id < 1 || id > SBL_SCENE__NOBJ) return NULL;
    if (id < SBL_SCENE__ID_POST0) return names[id];
    return posts[id - SBL_SCENE__ID_POST0];
}

#endif /* SBL_SCENE_IMPLEMENTATION_DONE */
#endif /* SBL_SCENE_IMPLEMENTATION */
