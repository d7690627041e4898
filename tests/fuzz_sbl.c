/* libFuzzer harness for stereoblend.h.

   The input is decoded into one call of a public entry point (temporal filter, temporal
   reprojection, 3x3 moments, stereo blend, stereo reprojection, stereo fill, and the
   *_frame, merge and depth-conversion calls): sizes, strides, channel counts, which
   optional buffers exist, conventions, enums (including out-of-range ones), float
   parameters (defaults, ordinary values, NaN / inf / negative / denormal / huge, raw
   bits), cameras, row ranges, scratch sizes and every buffer's contents. Each image is
   allocated at exactly (h - 1) * stride + w * c floats, so ASan sees any over-read
   past it; geometry mutations only ever shrink what an image claims or make it
   invalid, never claim memory that is not there.

   Checked after every call (abort() on failure, which libFuzzer records as a crash):
   - the result code is one of sbl_result;
   - a rejected call wrote nothing (every output float still holds its sentinel);
   - an accepted call wrote only rows [y0, y1) and never the row padding;
   - temporal filter: new frame finite -> output colour finite; N finite, 0 <= N <=
     max_history; alpha in [0, 1];
   - reprojection: inputs finite -> x* and N finite, N >= 0; stereo valid in {0, 1};
   - moments: input finite -> mean finite; variance >= 0, finite unless the input has
     magnitudes whose squares leave float range;
   - stereo blend: inputs finite -> colour and N finite, N >= 0;
   - stereo fill: mask in {0, 1}, count = number of 1s, colour finite;
   - merge: dst changes only where the mask is 1, to the traced value.

   Build:  clang -g -O1 -fsanitize=fuzzer,address,undefined tests/fuzz_sbl.c -lm
   Replay without libFuzzer:
           cc -DSBL_FUZZ_STANDALONE -g -fsanitize=address,undefined tests/fuzz_sbl.c -lm
           ./a.out FILE...            (replays each file; prints each result code)
           ./a.out --write-seeds DIR  (writes one accepted input per entry point) */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- input reader ---------------------------------------------------------------- */

typedef struct rd { const uint8_t *p; size_t n, i; } rd;

static unsigned u8(rd *r) { return r->i < r->n ? r->p[r->i++] : 0u; }
static float f_bits(uint32_t u) { float f; memcpy(&f, &u, sizeof f); return f; }
static uint32_t bits_f(float f) { uint32_t u; memcpy(&u, &f, sizeof u); return u; }
static int fin(float f) { return (bits_f(f) & 0x7f800000u) != 0x7f800000u; }
static float raw_f32(rd *r)
{
    uint32_t u = u8(r);
    u |= (uint32_t)u8(r) << 8;
    u |= (uint32_t)u8(r) << 16;
    u |= (uint32_t)u8(r) << 24;
    return f_bits(u);
}

static float special(unsigned b)
{
    switch (b % 16u) {
    case 0: return f_bits(0x7fc00000u);  /* NaN        */
    case 1: return f_bits(0x7f800000u);  /* +inf       */
    case 2: return f_bits(0xff800000u);  /* -inf       */
    case 3: return f_bits(0x7f800001u);  /* sNaN       */
    case 4: return 0.0f;
    case 5: return f_bits(0x80000000u);  /* -0         */
    case 6: return -1.0f;
    case 7: return FLT_MAX;
    case 8: return -FLT_MAX;
    case 9: return f_bits(0x00000001u);  /* denormal   */
    case 10: return 1e-39f;
    case 11: return 1e30f;
    case 12: return 1e-30f;
    case 13: return 3e9f;
    case 14: return FLT_MIN;
    default: return 1e38f;
    }
}

/* Roles of a buffer decide its "ordinary" values. */
enum role { R_COLOR, R_DEPTH, R_NORMAL, R_ID, R_MOTION, R_LENGTH, R_DISP };

static float ordinary(enum role role, unsigned b, int k)
{
    switch (role) {
    case R_DEPTH: return 2.0f + (float)(b % 8u) * 0.5f;
    case R_NORMAL: return (b % 4u) == (unsigned)k ? 1.0f : ((b % 4u) == 3 ? 0.6f : 0.0f);
    case R_ID: return (float)(b % 3u);
    case R_MOTION: return ((float)(int)(b ^ 0x80u) - 128.0f) / 16.0f;
    case R_LENGTH: return 1.0f + (float)b / 4.0f;
    case R_DISP: return (float)(b % 32u) / 4.0f;
    default: return 0.5f + (float)b / 64.0f;
    }
}

/* ---- images ------------------------------------------------------------------------ */

#define SENTINEL 0x7fb00badu /* a NaN nobody computes */
#define MAXBUF 40 /* the combined pipeline makes up to 30 */

typedef struct fbuf {
    float *mem;
    size_t n;
    int w, h, c, stride; /* the real allocation */
    sbl_image im;        /* what the library is told (maybe mutated) */
    int is_output;
} fbuf;

typedef struct ctx {
    sbl_result expect; /* what the validation said */
    fbuf bufs[MAXBUF];
    int nbufs;
    void *extra[4];
    int nextra;
} ctx;

static fbuf *new_buf(ctx *cx, int w, int h, int c, int pad)
{
    fbuf *b;
    if (cx->nbufs >= MAXBUF) abort(); /* a harness bug, not the library's */
    b = &cx->bufs[cx->nbufs++];
    memset(b, 0, sizeof *b);
    b->w = w; b->h = h; b->c = c; b->stride = w * c + pad;
    b->n = (size_t)(h - 1) * (size_t)b->stride + (size_t)w * (size_t)c;
    b->mem = (float *)malloc(b->n * sizeof(float));
    b->im.data = b->mem; b->im.width = w; b->im.height = h; b->im.channels = c;
    b->im.stride = b->stride;
    return b;
}

/* An image of role `role`; optional ones may be absent (data NULL). flags: bit 0 absent
   (optional) / NULL (required, rarely), bits 1-2 row padding, bit 3 stride field 0,
   bits 4-7 a geometry mutation (13..15 of 16). */
static sbl_image make_image(rd *r, ctx *cx, enum role role, int w, int h, int c,
                            int optional, int output)
{
    unsigned flags = u8(r), mode, rate, mut;
    int pad = (int)((flags >> 1) & 3u), x, y, k;
    fbuf *b;
    sbl_image none;
    memset(&none, 0, sizeof none);
    if (optional && (flags & 1u)) return none;
    if (!optional && (flags & 1u) && ((flags >> 4) == 15u)) return none; /* NULL required */
    b = new_buf(cx, w, h, c, pad);
    b->is_output = output;
    if ((flags & 8u) && pad == 0) b->im.stride = 0;
    if ((flags & 8u) && pad != 0) { /* the same layout also in bytes, with its size */
        b->im.stride_bytes = b->stride * (int)sizeof(float);
        b->im.size_bytes = b->n * sizeof(float);
    }
    mut = flags >> 4;
    if (mut == 13u) b->im.width = (u8(r) & 1u) ? 0 : -w;
    else if (mut == 14u) b->im.channels = (u8(r) & 1u) ? 0 : 5;
    else if (mut == 15u && !(flags & 1u)) {
        unsigned m2 = u8(r) % 4u;
        if (m2 == 0 && w * c > 1) b->im.stride = w * c - 1;       /* INVALID_STRIDE  */
        else if (m2 == 1 && (flags & 2u)) b->im.stride_bytes = b->stride * 4 + 2; /* INVALID_STRIDE */
        else if (m2 == 1) b->im.size_bytes = b->n * sizeof(float) - 1;  /* INVALID_SIZE */
        else if (m2 == 2 && h > 1) b->im.height = h - 1;          /* shrink: mismatch */
        else if (w > 1) b->im.width = w - 1;                      /* shrink: mismatch */
    }
    if (output) {
        size_t i;
        for (i = 0; i < b->n; ++i) b->mem[i] = f_bits(SENTINEL);
        return b->im;
    }
    {   /* padding poison, then contents */
        size_t i;
        for (i = 0; i < b->n; ++i) b->mem[i] = f_bits(0x7fa5a5a5u);
    }
    mode = u8(r);
    rate = (mode >> 2) & 7u; /* specials: none, then 1/128 .. 1/2 */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < c; ++k) {
                float *p = b->mem + (size_t)y * b->stride + (size_t)x * c + k;
                unsigned v = u8(r);
                if (rate && (v & 127u) < (1u << (rate - 1u)) ) *p = special(u8(r));
                else if ((mode & 3u) == 3u) *p = raw_f32(r);
                else *p = ordinary(role, v, k);
            }
    return b->im;
}

static float param(rd *r)
{
    static const float nice[14] = {0.01f, 0.05f, 0.1f, 0.25f, 0.5f, 0.9f, 1.0f,
                                   1.5f, 2.0f, 3.0f, 8.0f, 64.0f, 100.0f, -1.0f};
    unsigned b = u8(r);
    if (b < 128u) return 0.0f;
    if (b < 192u) return nice[b % 14u];
    if (b < 240u) return special(b);
    return raw_f32(r);
}

static int enum_val(rd *r, int count) { return (int)(u8(r) % (unsigned)(count + 2)) - 1; }

/* The history fetch, from the input's last byte without consuming it (so that every
   other byte keeps its meaning for the corpus): mostly bilinear, sometimes Catmull-Rom,
   sometimes a value out of range (-1 or 2). */
static sbl_history_filter history_filter_of(const rd *r)
{
    unsigned v = r->n ? (unsigned)r->p[r->n - 1] : 0u;
    if (v % 8u < 5u) return SBL_HISTORY_BILINEAR;
    if (v % 8u < 7u) return SBL_HISTORY_CATMULL_ROM;
    return (sbl_history_filter)((v & 8u) ? 2 : -1);
}

/* Estimator, rectification, weight mode: out of range sometimes, mostly valid (same
   byte order as before, so the corpus keeps its meaning). */
static void weight_enums(rd *r, sbl_estimator *e, sbl_rectify *rc, sbl_weight_mode *m)
{
    *e = (sbl_estimator)enum_val(r, SBL_ESTIMATOR_COUNT);
    *rc = (sbl_rectify)enum_val(r, SBL_RECTIFY_COUNT);
    *m = (sbl_weight_mode)enum_val(r, SBL_WEIGHT_MODE_COUNT);
    if ((int)*e < 0 && (u8(r) & 1u)) *e = SBL_ESTIMATOR_HISTORY_AWARE;
    if ((int)*rc < 0 && (u8(r) & 1u)) *rc = SBL_RECTIFY_NONE;
    if ((int)*m < 0 && (u8(r) & 1u)) *m = SBL_WEIGHT_SCALAR;
}

static void perspective(sbl_camera *cam, int w, int h, float f)
{
    int i;
    for (i = 0; i < 16; ++i) cam->world_to_view[i] = (i % 5 == 0) ? 1.0f : 0.0f;
    memset(cam->view_to_clip, 0, sizeof cam->view_to_clip);
    cam->view_to_clip[0] = 2.0f * f / (float)w;
    cam->view_to_clip[5] = 2.0f * f / (float)h;
    cam->view_to_clip[10] = -1.0f;
    cam->view_to_clip[11] = -0.2f;
    cam->view_to_clip[14] = -1.0f;
}

static const sbl_camera *make_camera(rd *r, sbl_camera *cam, int w, int h)
{
    unsigned mode = u8(r) % 8u;
    int i;
    if (mode == 7u) return NULL;
    perspective(cam, w, h, 2.0f + (float)(u8(r) % 16u));
    cam->world_to_view[3] = ((float)(int)u8(r) - 128.0f) / 64.0f;  /* translation */
    cam->world_to_view[7] = ((float)(int)u8(r) - 128.0f) / 64.0f;
    if (mode == 5u) cam->world_to_view[u8(r) % 16u] = special(u8(r));
    if (mode == 6u) {
        for (i = 0; i < 16; ++i) cam->world_to_view[i] = raw_f32(r);
        for (i = 0; i < 16; ++i) cam->view_to_clip[i] = raw_f32(r);
    }
    return cam;
}

static sbl_gbuffer make_gbuffer(rd *r, ctx *cx, int w, int h, int with_motion)
{
    sbl_gbuffer g;
    g.depth = make_image(r, cx, R_DEPTH, w, h, 1, 1, 0);
    g.normals = make_image(r, cx, R_NORMAL, w, h, 3, 1, 0);
    g.ids = make_image(r, cx, R_ID, w, h, 1, 1, 0);
    if (with_motion) g.motion = make_image(r, cx, R_MOTION, w, h, 2, 1, 0);
    else memset(&g.motion, 0, sizeof g.motion);
    return g;
}

static void rows(rd *r, int h, int *y0, int *y1)
{
    unsigned b = u8(r);
    if (b < 200u) { *y0 = 0; *y1 = h; return; }
    *y0 = (int)(u8(r) % (unsigned)(h + 2)) - 1;
    *y1 = (int)(u8(r) % (unsigned)(h + 2)) - 1;
    if (b >= 250u) { *y0 = (int)(u8(r) % (unsigned)(h + 1)); *y1 = *y0; } /* empty range */
}

/* Scratch of exactly the size asked for (or smaller / NULL to test the checks). */
static void *scratch(rd *r, ctx *cx, size_t need, size_t *bytes)
{
    unsigned b = u8(r) % 16u;
    size_t n = need;
    void *p;
    if (b == 15u) { *bytes = need; return NULL; }
    if (b == 14u && need > 0) n = need - 1 - (u8(r) % need);
    if (n == 0) n = 1;
    p = malloc(n);
    cx->extra[cx->nextra++] = p;
    *bytes = (b == 14u || need == 0) ? n : need;
    if (need == 0) *bytes = 0;
    return p;
}

/* ---- checks ----------------------------------------------------------------------- */

static void fail(const char *what, int line)
{
    fprintf(stderr, "fuzz_sbl: property violated at line %d: %s\n", line, what);
    abort();
}
#define REQUIRE(c) do { if (!(c)) fail(#c, __LINE__); } while (0)

static fbuf *find_buf(ctx *cx, const float *data)
{
    int i;
    for (i = 0; i < cx->nbufs; ++i)
        if (cx->bufs[i].mem == data) return &cx->bufs[i];
    return NULL;
}

/* every value of the image's real allocation finite (the view may be an unvalidated,
   mutated one when the library ignored that buffer) */
static int buf_finite(ctx *cx, const sbl_image *im)
{
    fbuf *b;
    int x, y;
    if (!im->data) return 1;
    b = find_buf(cx, im->data);
    if (!b) return 1;
    for (y = 0; y < b->h; ++y)
        for (x = 0; x < b->w * b->c; ++x)
            if (!fin(b->mem[(size_t)y * b->stride + x])) return 0;
    return 1;
}

/* outputs untouched after a rejected call */
static void check_untouched(ctx *cx)
{
    int i;
    size_t j;
    for (i = 0; i < cx->nbufs; ++i)
        if (cx->bufs[i].is_output)
            for (j = 0; j < cx->bufs[i].n; ++j)
                REQUIRE(bits_f(cx->bufs[i].mem[j]) == SENTINEL);
}

/* after an accepted call: padding and rows outside [y0, y1) untouched, rows inside
   written; returns the view for value checks */
static void check_rows(ctx *cx, const sbl_image *im, int y0, int y1)
{
    fbuf *b = find_buf(cx, im->data);
    int x, y;
    if (!b) return;
    /* an accepted view may be a valid sub-view (shrunk width / height, same stride) */
    for (y = 0; y < b->h; ++y)
        for (x = 0; x < b->stride && (size_t)y * b->stride + x < b->n; ++x) {
            int inside = y >= y0 && y < y1 && y < im->height && x < im->width * im->channels;
            uint32_t v = bits_f(b->mem[(size_t)y * b->stride + x]);
            if (inside) REQUIRE(v != SENTINEL);
            else REQUIRE(v == SENTINEL);
        }
}

/* values of rows [y0, y1) of a 1-channel image within [lo, hi] (and not NaN) */
static void check_range(const sbl_image *im, int y0, int y1, float lo, float hi)
{
    int x, y, s;
    if (!im->data) return;
    s = im->stride ? im->stride : im->width;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < im->width; ++x) {
            float v = im->data[(size_t)y * s + x];
            REQUIRE(fin(v) || (bits_f(v) == 0x7f800000u && hi > FLT_MAX));
            REQUIRE(v >= lo && v <= hi);
        }
}

static void check_finite_rows(const sbl_image *im, int y0, int y1)
{
    int x, y, k, s;
    if (!im->data) return;
    s = im->stride ? im->stride : im->width * im->channels;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < im->width; ++x)
            for (k = 0; k < im->channels; ++k)
                REQUIRE(fin(im->data[(size_t)y * s + (size_t)x * im->channels + k]));
}

static void check_rc(sbl_result rc) { REQUIRE((int)rc >= 0 && (int)rc < (int)SBL_RESULT_COUNT); }

/* ---- the entry points -------------------------------------------------------------- */

#define OPS 11

static sbl_result fuzz_temporal(rd *r, ctx *cx, int w, int h, int c, int op)
{
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history hi;
    sbl_temporal_output o;
    sbl_camera cc, pc;
    const sbl_history *hp;
    sbl_result rc;
    int y0, y1, use_hist;
    memset(&d, 0, sizeof d); memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi);
    memset(&o, 0, sizeof o);
    d.source = (sbl_temporal_source)enum_val(r, 2);
    if ((int)d.source < 0) d.source = SBL_TEMPORAL_MOTION; /* mostly valid */
    weight_enums(r, &d.estimator, &d.rectify, &d.weight_mode);
    d.constant_alpha = param(r);
    d.alpha_min = param(r);
    d.max_history = param(r);
    d.clip_gamma = param(r);
    d.bias_threshold = param(r);
    d.reproject.depth_tolerance = param(r);
    d.reproject.normal_threshold = param(r);
    d.reproject.back_check_pixels = param(r);
    d.reproject.no_fallback = (int)(u8(r) & 1u);
    d.reproject.motion.units = (sbl_motion_units)(enum_val(r, 3) < 0 ? -1 : (int)(u8(r) % 3u));
    d.reproject.motion.forward = (int)(u8(r) & 1u);
    d.reproject.motion.y_up = (int)(u8(r) & 1u);
    d.reproject.disabled_tests = (int)(u8(r) % 40u); /* 32..39: an unknown bit */
    d.reproject.history_filter = history_filter_of(r);
    f.color = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
    f.gbuffer = make_gbuffer(r, cx, w, h, 1);
    f.camera = make_camera(r, &cc, w, h);
    {   /* moving objects (camera mode): ids 1..4, sorted or not, maybe singular */
        static sbl_object_motion objs[4];
        int n = (int)(u8(r) % 5u), i, k;
        for (i = 0; i < n; ++i) {
            objs[i].id = (float)(i + 1);
            for (k = 0; k < 16; ++k) {
                objs[i].object_to_world[k] = (k % 5 == 0) ? 1.0f : 0.0f;
                objs[i].prev_object_to_world[k] = (k % 5 == 0) ? 1.0f : 0.0f;
            }
            objs[i].prev_object_to_world[3] = ((float)(int)u8(r) - 128.0f) / 64.0f;
            if ((u8(r) % 16u) == 0) objs[i].object_to_world[u8(r) % 16u] = special(u8(r));
            if ((u8(r) % 16u) == 1) objs[i].id = 2.0f; /* duplicate / unsorted */
        }
        f.objects = n ? objs : NULL;
        f.object_count = n;
    }
    use_hist = (int)(u8(r) % 4u) != 0;
    if (use_hist) {
        hi.color = make_image(r, cx, R_COLOR, w, h, c, (u8(r) % 8u) == 0, 0);
        hi.length = make_image(r, cx, R_LENGTH, w, h, 1, 1, 0);
        hi.gbuffer = make_gbuffer(r, cx, w, h, 0);
        hi.camera = make_camera(r, &pc, w, h);
    }
    hp = use_hist ? &hi : NULL;
    if (op == 1) { /* sbl_reproject_temporal */
        sbl_image oc = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        sbl_image on = make_image(r, cx, R_LENGTH, w, h, 1, 0, 1);
        rows(r, h, &y0, &y1);
        rc = sbl_reproject_temporal(&d.reproject, d.source, &f, hp, oc, on, y0, y1);
        check_rc(rc);
        if (rc != SBL_OK) { check_untouched(cx); return rc; }
        check_rows(cx, &oc, y0, y1);
        check_rows(cx, &on, y0, y1);
        check_range(&on, y0, y1, 0.0f, f_bits(0x7f800000u));
        if (!hp || (buf_finite(cx, &hi.color) && buf_finite(cx, &hi.length))) {
            check_finite_rows(&oc, y0, y1);
            check_finite_rows(&on, y0, y1);
        }
        return rc;
    }
    o.color = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
    o.length = make_image(r, cx, R_LENGTH, w, h, 1, 0, 1);
    o.alpha = make_image(r, cx, R_LENGTH, w, h, 1, 1, 1);
    /* the display (sbl_temporal_filter_frame only; a row call rejects one) */
    if (op == 6) o.display = make_image(r, cx, R_COLOR, w, h, c, 1, 1);
    {   /* the validation: the same code as the call for every argument error, the
           culprit named, nothing written (validated without the display, which is the
           row calls' error; the frame call checks it first) */
        sbl_diag dg;
        sbl_temporal_output ov = o;
        sbl_result vr;
        ov.display.data = NULL;
        vr = sbl_temporal_validate(&d, &f, hp, &ov, &dg);
        check_rc(vr);
        REQUIRE(dg.result == vr);
        REQUIRE((vr == SBL_OK) == (dg.field[0] == '\0'));
        check_untouched(cx);
        cx->expect = vr;
    }
    if (op == 6) {
        rc = sbl_temporal_filter_frame(&d, &f, hp, &o);
        y0 = 0; y1 = f.color.height;
    } else {
        size_t need = sbl_temporal_scratch_size(f.color.width, f.color.channels), bytes;
        void *s = scratch(r, cx, need, &bytes);
        rows(r, h, &y0, &y1);
        rc = sbl_temporal_filter(&d, &f, hp, &o, y0, y1, s, bytes);
    }
    check_rc(rc);
    /* validation OK: only the row range, the scratch or its size can still fail (or,
       with a display, the display's own checks) */
    {
        /* a display's own error comes first: its checks (rows [0, 0) write nothing).
           The display is its own allocation here (make_image), so it overlaps no input
           and the frame call's overlap check cannot fire; this file only uses the
           public API (the asan configuration links it against the object). */
        sbl_result de = SBL_OK;
        if (o.display.data) de = sbl_temporal_display(NULL, &f, &o, o.display, 0, 0);
        if (de != SBL_OK) REQUIRE(rc == de);
        else if (cx->expect != SBL_OK) REQUIRE(rc == cx->expect);
        else REQUIRE(rc == SBL_OK || rc == SBL_ERROR_INVALID_ROWS || rc == SBL_ERROR_NULL_POINTER ||
                     rc == SBL_ERROR_SCRATCH_TOO_SMALL || rc == SBL_ERROR_INVALID_SIZE ||
                     rc == SBL_ERROR_OUT_OF_MEMORY);
    }
    if (rc != SBL_OK) { check_untouched(cx); return rc; }
    if (o.display.data) {
        check_rows(cx, &o.display, y0, y1);
        if (buf_finite(cx, &f.color)) check_finite_rows(&o.display, y0, y1);
    }
    {
        sbl_temporal_desc dd = sbl_temporal_defaults(&d);
        check_rows(cx, &o.color, y0, y1);
        check_rows(cx, &o.length, y0, y1);
        check_rows(cx, &o.alpha, y0, y1);
        check_range(&o.length, y0, y1, 0.0f, dd.max_history);
        check_range(&o.alpha, y0, y1, 0.0f, 1.0f);
        if (buf_finite(cx, &f.color)) check_finite_rows(&o.color, y0, y1);
    }
    return rc;
}

static sbl_result fuzz_moments(rd *r, ctx *cx, int w, int h, int c)
{
    sbl_image src = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
    sbl_image mean = make_image(r, cx, R_COLOR, w, h, c, 1, 1);
    sbl_image var = make_image(r, cx, R_COLOR, w, h, c, 1, 1);
    sbl_result rc;
    int y0, y1, x, y, k;
    rows(r, h, &y0, &y1);
    rc = sbl_moments_3x3(src, mean, var, y0, y1);
    check_rc(rc);
    if (rc != SBL_OK) { check_untouched(cx); return rc; }
    check_rows(cx, &mean, y0, y1);
    check_rows(cx, &var, y0, y1);
    {
        float big = 0.0f;
        int s = src.stride ? src.stride : src.width * src.channels;
        for (y = 0; y < src.height; ++y)
            for (x = 0; x < src.width * src.channels; ++x) {
                float v = src.data[(size_t)y * s + x];
                if (fin(v) && (v > big || -v > big)) big = v > 0 ? v : -v;
            }
        check_finite_rows(&mean, y0, y1);
        if (var.data) {
            int vs = var.stride ? var.stride : var.width * var.channels;
            for (y = y0; y < y1; ++y)
                for (x = 0; x < var.width; ++x)
                    for (k = 0; k < var.channels; ++k) {
                        float v = var.data[(size_t)y * vs + (size_t)x * var.channels + k];
                        REQUIRE(v >= 0.0f);
                        if (big < 1e18f) REQUIRE(fin(v));
                    }
        }
    }
    return rc;
}

static void make_eye(rd *r, ctx *cx, sbl_eye *e, int w, int h, int c, int need_color,
                     sbl_camera *cam)
{
    memset(e, 0, sizeof *e);
    e->color = make_image(r, cx, R_COLOR, w, h, c, !need_color, 0);
    e->length = make_image(r, cx, R_LENGTH, w, h, 1, 1, 0);
    e->gbuffer = make_gbuffer(r, cx, w, h, 0);
    e->disparity = make_image(r, cx, R_DISP, w, h, 1 + (int)(u8(r) & 1u), 1, 0);
    e->camera = make_camera(r, cam, w, h);
}

static int eye_finite(ctx *cx, const sbl_eye *e)
{
    return buf_finite(cx, &e->color) && buf_finite(cx, &e->length);
}

static sbl_result fuzz_stereo(rd *r, ctx *cx, int w, int h, int c, int op)
{
    sbl_stereo_desc d;
    sbl_eye t, s;
    sbl_camera tc, sc;
    sbl_eye_index te;
    sbl_result rc;
    int y0, y1;
    memset(&d, 0, sizeof d);
    d.rig = (sbl_stereo_rig)enum_val(r, SBL_RIG_COUNT);
    if ((int)d.rig < 0 && (u8(r) & 1u)) d.rig = SBL_RIG_DISPARITY;
    d.focal_px = param(r);
    d.baseline = param(r);
    if (u8(r) & 1u) { d.focal_px = 8.0f; d.baseline = 0.5f; }
    d.disparity_offset = (u8(r) & 1u) ? param(r) - 1.0f : 0.0f;
    if (d.rig == SBL_RIG_PINHOLE) {
        int e, k;
        for (e = 0; e < 2; ++e) {
            d.pinhole.eye[e].fx = (u8(r) & 1u) ? param(r) : 8.0f;
            d.pinhole.eye[e].fy = 8.0f;
            d.pinhole.eye[e].cx = (float)w * 0.5f + (float)(u8(r) % 8u) * 0.25f;
            d.pinhole.eye[e].cy = (float)h * 0.5f;
        }
        for (k = 0; k < 16; ++k) d.pinhole.right_from_left[k] = (k % 5 == 0) ? 1.0f : 0.0f;
        d.pinhole.right_from_left[3] = -0.5f;
        if ((u8(r) % 8u) == 0) d.pinhole.right_from_left[u8(r) % 16u] = special(u8(r));
        d.pinhole.axes = (sbl_view_axes)(u8(r) % 3u); /* 2: invalid */
        d.pinhole.integer_pixel_centers = (int)(u8(r) & 1u);
    }
    d.reproject.disabled_tests = (int)(u8(r) % 40u);
    weight_enums(r, &d.estimator, &d.rectify, &d.weight_mode);
    d.constant_beta = param(r);
    d.clip_gamma = param(r);
    d.bias_threshold = param(r);
    d.fill = (int)(u8(r) & 1u);
    d.reproject.depth_tolerance = param(r);
    d.reproject.normal_threshold = param(r);
    d.reproject.back_check_pixels = param(r);
    d.reproject.no_fallback = (int)(u8(r) & 1u);
    te = (sbl_eye_index)((int)(u8(r) % 3u) == 2 ? ((u8(r) & 1u) ? 2 : -1) : (int)(u8(r) & 1u));
    make_eye(r, cx, &t, w, h, c, op == 3 || op == 7, &tc);
    make_eye(r, cx, &s, w, h, c, 1, &sc);
    if (op == 3) {
        sbl_image oc = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        sbl_image on = make_image(r, cx, R_LENGTH, w, h, 1, 1, 1);
        sbl_image ob = make_image(r, cx, R_LENGTH, w, h, 1, 1, 1);
        size_t need = sbl_stereo_scratch_size(t.color.width, t.color.channels), bytes;
        void *sp = scratch(r, cx, need, &bytes);
        sbl_stereo_output so;
        sbl_diag dg;
        sbl_result vr;
        memset(&so, 0, sizeof so);
        so.color = oc; so.length = on; so.beta = ob;
        vr = sbl_stereo_validate(&d, te, &t, &s, &so, &dg);
        check_rc(vr);
        REQUIRE(dg.result == vr);
        REQUIRE((vr == SBL_OK) == (dg.field[0] == '\0'));
        check_untouched(cx);
        rows(r, h, &y0, &y1);
        rc = sbl_stereo_filter(&d, te, &t, &s, &so, y0, y1, sp, bytes);
        check_rc(rc);
        if (vr != SBL_OK) REQUIRE(rc == vr);
        else REQUIRE(rc == SBL_OK || rc == SBL_ERROR_INVALID_ROWS || rc == SBL_ERROR_NULL_POINTER ||
                     rc == SBL_ERROR_SCRATCH_TOO_SMALL || rc == SBL_ERROR_INVALID_SIZE);
        if (rc != SBL_OK) { check_untouched(cx); return rc; }
        check_rows(cx, &ob, y0, y1);
        check_range(&ob, y0, y1, 0.0f, 1.0f);
        check_rows(cx, &oc, y0, y1);
        check_rows(cx, &on, y0, y1);
        check_range(&on, y0, y1, 0.0f, f_bits(0x7f800000u));
        if (eye_finite(cx, &t) && eye_finite(cx, &s)) {
            check_finite_rows(&oc, y0, y1);
            check_finite_rows(&on, y0, y1);
        } else if (buf_finite(cx, &t.color)) {
            check_finite_rows(&oc, y0, y1);
        }
        return rc;
    }
    if (op == 7) { /* both eyes: target = left, source = right */
        sbl_image ol = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        sbl_image orr = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        rc = sbl_stereo_blend_frame(&d, &t, &s, ol, orr);
        check_rc(rc);
        if (rc != SBL_OK) { check_untouched(cx); return rc; }
        check_rows(cx, &ol, 0, h);
        check_rows(cx, &orr, 0, h);
        if (buf_finite(cx, &t.color)) check_finite_rows(&ol, 0, h);
        if (buf_finite(cx, &s.color)) check_finite_rows(&orr, 0, h);
        return rc;
    }
    if (op == 4) {
        sbl_image oc = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        sbl_image ov = make_image(r, cx, R_LENGTH, w, h, 1, 1, 1);
        rows(r, h, &y0, &y1);
        rc = sbl_reproject_stereo(&d, te, &t, &s, oc, ov, y0, y1);
        check_rc(rc);
        if (rc != SBL_OK) { check_untouched(cx); return rc; }
        check_rows(cx, &oc, y0, y1);
        check_rows(cx, &ov, y0, y1);
        check_range(&ov, y0, y1, 0.0f, 1.0f);
        if (buf_finite(cx, &s.color)) check_finite_rows(&oc, y0, y1);
        return rc;
    }
    {   /* op 5: sbl_stereo_fill */
        sbl_image oc = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        int mstride = w + (int)(u8(r) % 3u), x, y;
        size_t mbytes = (size_t)(h - 1) * (size_t)mstride + (size_t)w;
        unsigned char *mask = (unsigned char *)malloc(mbytes);
        long count = -7, ones = 0;
        unsigned mode = u8(r) % 16u;
        memset(mask, 0xEE, mbytes);
        cx->extra[cx->nextra++] = mask;
        rows(r, h, &y0, &y1);
        rc = sbl_stereo_fill(&d, te, &t, &s, oc, mode == 15u ? NULL : mask,
                             mode == 14u ? w - 1 : mstride, y0, y1,
                             mode == 13u ? NULL : &count);
        check_rc(rc);
        if (rc != SBL_OK) {
            size_t i;
            check_untouched(cx);
            for (i = 0; i < mbytes; ++i) REQUIRE(mask[i] == 0xEE);
            return rc;
        }
        check_rows(cx, &oc, y0, y1);
        if (buf_finite(cx, &s.color)) check_finite_rows(&oc, y0, y1);
        for (y = 0; y < h; ++y)
            for (x = 0; x < mstride && (size_t)y * mstride + x < mbytes; ++x) {
                unsigned char v = mask[(size_t)y * mstride + x];
                if (y >= y0 && y < y1 && x < w) { REQUIRE(v <= 1); ones += v; }
                else REQUIRE(v == 0xEE);
            }
        if (mode != 13u) REQUIRE(count == ones);
        return rc;
    }
}

static sbl_result fuzz_merge(rd *r, ctx *cx, int w, int h, int c)
{
    sbl_image dst = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
    sbl_image tr = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
    int mstride = w + (int)(u8(r) % 3u), y0, y1, x, y, k;
    size_t mbytes = (size_t)(h - 1) * (size_t)mstride + (size_t)w, i;
    unsigned char *mask = (unsigned char *)malloc(mbytes);
    float *before = NULL;
    fbuf *db = find_buf(cx, dst.data);
    sbl_result rc;
    cx->extra[cx->nextra++] = mask;
    for (i = 0; i < mbytes; ++i) mask[i] = (unsigned char)(u8(r) % 3u == 0);
    rows(r, h, &y0, &y1);
    if (db) {
        before = (float *)malloc(db->n * sizeof(float));
        memcpy(before, db->mem, db->n * sizeof(float));
        cx->extra[cx->nextra++] = before;
    }
    rc = sbl_merge_traced(dst, tr, mask, mstride, y0, y1);
    check_rc(rc);
    if (!db || !tr.data) return rc;
    if (rc != SBL_OK) {
        REQUIRE(memcmp(before, db->mem, db->n * sizeof(float)) == 0);
        return rc;
    }
    for (y = 0; y < db->h; ++y)
        for (x = 0; x < db->w; ++x)
            for (k = 0; k < db->c; ++k) {
                size_t at = (size_t)y * (dst.stride ? dst.stride : dst.width * dst.channels) +
                            (size_t)x * dst.channels + k;
                size_t ta = (size_t)y * (tr.stride ? tr.stride : tr.width * tr.channels) +
                            (size_t)x * tr.channels + k;
                int copied = y >= y0 && y < y1 && x < dst.width && k < dst.channels &&
                             mask[(size_t)y * mstride + x];
                if (at >= db->n) continue;
                if (copied) REQUIRE(bits_f(db->mem[at]) == bits_f(tr.data[ta]));
                else REQUIRE(bits_f(db->mem[at]) == bits_f(before[at]));
            }
    return rc;
}

static sbl_result fuzz_depth(rd *r, ctx *cx, int w, int h)
{
    sbl_image src = make_image(r, cx, R_DEPTH, w, h, 1, 0, 0);
    int in_place = (int)(u8(r) & 1u);
    sbl_image dst = in_place ? src : make_image(r, cx, R_DEPTH, w, h, 1, 0, 1);
    sbl_depth_encoding enc = (sbl_depth_encoding)enum_val(r, SBL_DEPTH_ENCODING_COUNT);
    float n = param(r), f = param(r);
    sbl_result rc;
    if (u8(r) & 1u) { n = 0.1f; f = 100.0f; }
    rc = sbl_depth_image_to_linear(src, dst, enc, n, f);
    check_rc(rc);
    if (rc != SBL_OK && !in_place) check_untouched(cx);
    return rc;
}

/* The combined pipeline: two frames, histories, temporal outputs and displays. */
static sbl_result fuzz_stereo_temporal(rd *r, ctx *cx, int w, int h, int c)
{
    sbl_temporal_desc td;
    sbl_stereo_desc sd;
    sbl_stereo_temporal_io io;
    sbl_history hi[2];
    sbl_camera cams[4];
    sbl_result rc;
    int e, finite_in = 1;
    memset(&td, 0, sizeof td); memset(&sd, 0, sizeof sd); memset(&io, 0, sizeof io);
    td.estimator = (sbl_estimator)enum_val(r, SBL_ESTIMATOR_COUNT);
    if ((int)td.estimator < 0 && (u8(r) & 1u)) td.estimator = SBL_ESTIMATOR_HISTORY_AWARE;
    td.rectify = (sbl_rectify)(u8(r) % (unsigned)SBL_RECTIFY_COUNT);
    td.max_history = param(r);
    td.bias_threshold = param(r);
    sd.rig = (sbl_stereo_rig)(u8(r) % (unsigned)SBL_RIG_COUNT);
    sd.focal_px = param(r);
    sd.baseline = param(r);
    if (u8(r) & 1u) { sd.focal_px = 8.0f; sd.baseline = 0.5f; }
    sd.estimator = (sbl_estimator)(u8(r) % (unsigned)SBL_ESTIMATOR_COUNT);
    sd.fill = (int)(u8(r) & 1u);
    for (e = 0; e < 2; ++e) {
        memset(&hi[e], 0, sizeof hi[e]);
        io.frame[e].color = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
        io.frame[e].gbuffer = make_gbuffer(r, cx, w, h, 1);
        io.frame[e].camera = make_camera(r, &cams[e], w, h);
        io.disparity[e] = make_image(r, cx, R_DISP, w, h, 1, 1, 0);
        if (u8(r) % 4u) {
            hi[e].color = make_image(r, cx, R_COLOR, w, h, c, 0, 0);
            hi[e].length = make_image(r, cx, R_LENGTH, w, h, 1, 1, 0);
            hi[e].gbuffer = make_gbuffer(r, cx, w, h, 0);
            hi[e].camera = make_camera(r, &cams[2 + e], w, h);
            io.history[e] = &hi[e];
            finite_in &= buf_finite(cx, &hi[e].color) && buf_finite(cx, &hi[e].length);
        }
        io.temporal[e].color = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        io.temporal[e].length = make_image(r, cx, R_LENGTH, w, h, 1, 0, 1);
        io.display[e] = make_image(r, cx, R_COLOR, w, h, c, 0, 1);
        finite_in &= buf_finite(cx, &io.frame[e].color);
    }
    rc = sbl_stereo_temporal_frame(&td, &sd, &io);
    check_rc(rc);
    if (rc != SBL_OK) { check_untouched(cx); return rc; }
    for (e = 0; e < 2; ++e) {
        sbl_temporal_desc dd = sbl_temporal_defaults(&td);
        check_rows(cx, &io.temporal[e].color, 0, h);
        check_rows(cx, &io.display[e], 0, h);
        check_range(&io.temporal[e].length, 0, h, 0.0f, dd.max_history);
        if (finite_in) {
            check_finite_rows(&io.temporal[e].color, 0, h);
            check_finite_rows(&io.display[e], 0, h);
        }
    }
    return rc;
}

static sbl_result run_one(const uint8_t *data, size_t size)
{
    rd r;
    ctx cx;
    int op, w, h, c, i;
    sbl_result rc;
    r.p = data; r.n = size; r.i = 0;
    memset(&cx, 0, sizeof cx);
    op = (int)(u8(&r) % OPS);
    w = 1 + (int)(u8(&r) % 16u);
    h = 1 + (int)(u8(&r) % 12u);
    c = 1 + (int)(u8(&r) % 4u);
    switch (op) {
    case 0: case 1: case 6: rc = fuzz_temporal(&r, &cx, w, h, c, op); break;
    case 2: rc = fuzz_moments(&r, &cx, w, h, c); break;
    case 3: case 4: case 5: case 7: rc = fuzz_stereo(&r, &cx, w, h, c, op); break;
    case 8: rc = fuzz_merge(&r, &cx, w, h, c); break;
    case 10: rc = fuzz_stereo_temporal(&r, &cx, w, h, c); break;
    default: rc = fuzz_depth(&r, &cx, w, h); break;
    }
    for (i = 0; i < cx.nbufs; ++i) free(cx.bufs[i].mem);
    for (i = 0; i < cx.nextra; ++i) free(cx.extra[i]);
    return rc;
}

#ifdef __cplusplus
extern "C"
#endif
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    (void)run_one(data, size);
    return 0;
}

#ifdef SBL_FUZZ_STANDALONE
/* Replays files; or writes seeds: for every entry point, pseudo-random inputs biased
   towards valid calls until one is accepted (SBL_OK). */
static int write_seeds(const char *dir)
{
    unsigned long long s = 0x5eed5eedULL;
    int op, written = 0;
    for (op = 0; op < OPS; ++op) {
        int attempt;
        for (attempt = 0; attempt < 20000; ++attempt) {
            uint8_t buf[3000];
            size_t i, n = 600 + (size_t)(attempt % 5) * 400;
            for (i = 0; i < n; ++i) {
                s ^= s << 13; s ^= s >> 7; s ^= s << 17;
                /* mostly small bytes: flags without mutation, default parameters */
                buf[i] = (uint8_t)((s >> 24) % (attempt % 3 == 0 ? 256u : 64u));
            }
            buf[0] = (uint8_t)op;
            buf[1] = (uint8_t)(4 + op);
            buf[2] = (uint8_t)(3 + op % 5);
            buf[3] = (uint8_t)(op % 4);
            if (run_one(buf, n) == SBL_OK) {
                char path[1024];
                FILE *fp;
                snprintf(path, sizeof path, "%s/seed_op%d", dir, op);
                fp = fopen(path, "wb");
                if (!fp) { perror(path); return 1; }
                fwrite(buf, 1, n, fp);
                fclose(fp);
                ++written;
                break;
            }
        }
    }
    printf("wrote %d seeds to %s\n", written, dir);
    return written == OPS ? 0 : 1;
}

int main(int argc, char **argv)
{
    int i, replayed = 0;
    if (argc == 3 && strcmp(argv[1], "--write-seeds") == 0) return write_seeds(argv[2]);
    for (i = 1; i < argc; ++i) {
        FILE *fp = fopen(argv[i], "rb");
        uint8_t *buf;
        long n;
        if (!fp) { perror(argv[i]); return 1; }
        fseek(fp, 0, SEEK_END);
        n = ftell(fp);
        fseek(fp, 0, SEEK_SET);
        buf = (uint8_t *)malloc(n > 0 ? (size_t)n : 1);
        if (n > 0 && fread(buf, 1, (size_t)n, fp) != (size_t)n) { fclose(fp); free(buf); return 1; }
        fclose(fp);
        printf("%s: %s\n", argv[i], sbl_result_string(run_one(buf, (size_t)n)));
        free(buf);
        ++replayed;
    }
    printf("fuzz_sbl: replayed %d inputs, no property violated\n", replayed);
    return 0;
}
#endif
