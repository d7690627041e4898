/* make bench-ipp: instructions per pixel of sbl_temporal_filter, sbl_temporal_display and
   sbl_stereo_blend,
   counted by callgrind inside the public call only (--toggle-collect). Instruction
   counts do not drift with machine load, so this is the figure to steer by (and the one
   CI may watch with a generous margin).

   The case of issue 9: 640x360 RGB, motion (0.37, -0.21) px plus a slow sine, depth
   ramp, history N = 8 (every tap valid). Other cases:
     hard    per-pixel random sub-pixel motion and a moving object disoccluding ~10 %
     tiny    the easy case with one 1e-14 value in every row of the new frame
     static  camera at rest: zero motion, unchanged depth
     normals the easy case with normals and ids in every G-buffer (frame, history, both
             eyes): the normal and id tap tests, as a renderer passes them
     slant   the easy case on a surface turned about the vertical axis (depth also
             rising along each row, as most surfaces in a render: no two vectors of a
             row hold the same depth bits, unlike the ramp of the other cases)
     uv      the easy case with its motion vectors in UV units (fractions of the width
             and height, as Unity gives them): the plan's positions in double lanes
     offset  the easy case's stereo blend on a parallel rig with a disparity offset of
             0.75 px (Middlebury's doffs; a rig whose principal points differ)
     far     the easy case 10^4 times farther (depth 2e4: disparities ~2.6e-3 px, below
             the float lane plan's 2^-8, as geometry beyond 256 f b gives them)
     camera  the easy content with camera matrices instead of motion vectors (a pinhole
             camera moved ~(0.37, -0.21) px at depth 2; the temporal camera source) and a
             two-camera stereo rig (SBL_RIG_PINHOLE, baseline 6.5 cm): a parallel pair,
             which the stereo blend runs as SBL_RIG_PARALLEL (sbl__rig_as_parallel)
     toed    the camera case with the right eye toed in by 0.5 degrees (a canted rig):
             the camera maps and their plans in double lanes, and the rig's back-check
     two-eyes the easy case with the stereo blend of both eyes (each eye's temporal
             output blended with the other's, as bench/perf.c's stereo pipeline runs it;
             ipp.sh divides the blend's count by 2 calls)
   Each case with "-ev" appended (easy-ev, hard-ev, ...) passes the optional evidence
   plane in and out (sbl_history.evidence / sbl_temporal_output.evidence), and each
   eye's output plane on to the stereo blend (sbl_eye.evidence); with "-tail"
   appended (easy-tail, ...) the evidence and the tail planes (sbl_history.tail /
   sbl_temporal_output.tail), as the README's recommended setup does.

   IPP_SHARED_BIAS=c in the environment: the temporal filter as the combined pipeline runs
   it (stereo_shared_bias c), on inputs where the resampling blur's bias (ESTIMATORS 4.12)
   matters: frame and history carry a fine texture (texture(); the history's shifted by
   the pixel's motion, so that the fetch lands on the frame's), and the history sits at
   the frame's mean (its noise's mean 0.1 added: else that 0.1 is a change at every pixel,
   which wins the bias term). The blur's term then wins the bias term's max on ~53 % of
   the lanes of easy-ev and ~64 % of hard-ev, and its 3x3 bound binds on ~47 % / ~31 % of
   the channels (session 17, a debug count); on the smooth sine alone it never wins.

   sbl_temporal_display runs after each eye's temporal filter (counted when IPP_FUNCTIONS
   names it): in every case above but with IPP_SHARED_BIAS nearly every output is young
   (N <= 3: the history sits 0.1 from the frame's mean, a change the filter resets on),
   so its count is that of the lean at every pixel, the worst case; with IPP_SHARED_BIAS
   the outputs are old but for hard's disoccluded ~9 %.

   usage: ipp CASE [hash]   (runs each call once: meant for callgrind; hash: also print
   an FNV-1a hash of every output, to compare builds and code changes bit for bit; and one
   of the displays, on a line of its own) */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#define W 640
#define H 360

typedef struct eye_bufs {
    float *color, *depth, *prev_depth, *motion, *hist, *hlen, *out, *olen, *stereo_out;
    float *hev, *oev; /* evidence plane in / out */
    float *htl, *otl; /* tail plane in / out (2 channels) */
    float *normal, *prev_normal, *id, *prev_id; /* case normals */
    float *display; /* the temporal output's display (sbl_temporal_display) */
} eye_bufs;

static float *falloc(size_t n)
{
    float *p = (float *)calloc(n, sizeof(float));
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

/* the texture of the IPP_SHARED_BIAS cases at (u, v), channel c: a period of ~3 px, whose
   second differences are ~2.5 times its amplitude; the amplitude sets the blur's term
   near the noise's share of it (G var_X), so that the term wins on about half the pixels */
static float texture(float u, float v, int c)
{
    return 0.05f * sinf(2.2f * u + 1.3f * (float)c) * cosf(1.9f * v + 0.7f * (float)c);
}

/* case 0 easy, 1 hard, 2 tiny, 3 static, 4 normals, 5 slant; tex: add texture() */
static void fill_eye(eye_bufs *b, int eye, int kind, int tex)
{
    size_t n = (size_t)W * H, i;
    unsigned s = 12345u + 77u * (unsigned)eye;
    b->color = falloc(n * 3); b->depth = falloc(n); b->prev_depth = falloc(n);
    b->motion = falloc(n * 2); b->hist = falloc(n * 3); b->hlen = falloc(n);
    b->out = falloc(n * 3); b->olen = falloc(n); b->stereo_out = falloc(n * 3);
    b->hev = falloc(n); b->oev = falloc(n);
    b->htl = falloc(n * 2); b->otl = falloc(n * 2);
    b->normal = falloc(n * 3); b->prev_normal = falloc(n * 3); b->id = falloc(n); b->prev_id = falloc(n);
    b->display = falloc(n * 3);
    for (i = 0; i < n; ++i) {
        int x = (int)(i % W), y = (int)(i / W), c;
        for (c = 0; c < 3; ++c) {
            s = s * 1664525u + 1013904223u;
            b->color[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c) +
                                  (float)(s >> 8) * (1.0f / 16777216.0f) * 0.2f;
            b->hist[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c);
        }
        b->depth[i] = (2.0f + 0.001f * (float)y + (kind == 5 ? 0.0002f * (float)x : 0.0f)) * (kind == 9 ? 1e4f : 1.0f);
        b->prev_depth[i] = b->depth[i];
        b->motion[i * 2] = 0.37f + 0.1f * sinf(y * 0.01f);
        b->motion[i * 2 + 1] = -0.21f;
        b->hlen[i] = 8.0f;
        /* a carried ratio near its no-change mean 1, a few pixels above the threshold */
        s = s * 1664525u + 1013904223u;
        b->hev[i] = 0.8f + (float)(s >> 8) * (1.0f / 16777216.0f) * 0.6f +
                    ((s >> 4) % 61u == 0u ? 2.5f : 0.0f);
        /* a carried tail: mostly nothing seen, a rate of a few % at one pixel in 16 */
        b->htl[i * 2] = (s >> 12) % 16u == 0u ? 0.03f : 0.0f;
        b->htl[i * 2 + 1] = b->htl[i * 2] * 2.0f;
        if (kind == 1) {
            /* random sub-pixel motion; a nearer disc of radius 110 moved 50 px since
               the last frame: where it was, history depth is the object's, where it
               is now, history depth is the background's (~9 % of the pixels) */
            int dx = x - W / 2, dy = y - H / 2, dxp = x - (W / 2 - 50), inside, was;
            s = s * 1664525u + 1013904223u;
            b->motion[i * 2] = ((float)(s >> 8) * (1.0f / 16777216.0f) - 0.5f) * 1.8f;
            s = s * 1664525u + 1013904223u;
            b->motion[i * 2 + 1] = ((float)(s >> 8) * (1.0f / 16777216.0f) - 0.5f) * 1.8f;
            inside = dx * dx + dy * dy < 110 * 110;
            was = dxp * dxp + dy * dy < 110 * 110;
            if (inside) b->depth[i] = 1.0f;
            if (was) b->prev_depth[i] = 1.0f;
        } else if (kind == 3) {
            b->motion[i * 2] = 0.0f;
            b->motion[i * 2 + 1] = 0.0f;
        }
        if (tex) /* the history's fetch at (x, y) + motion lands on the frame's texture */
            for (c = 0; c < 3; ++c) {
                b->color[i * 3 + c] += texture((float)x, (float)y, c);
                b->hist[i * 3 + c] += 0.1f + texture((float)x - b->motion[i * 2], (float)y - b->motion[i * 2 + 1], c);
            }
        if (kind == 2 && x == (y * 37) % W) b->color[i * 3 + (y % 3)] = 1e-14f;
        if (kind == 6) { /* the same motion in UV units (fractions of the width / height) */
            b->motion[i * 2] /= (float)W;
            b->motion[i * 2 + 1] /= (float)H;
        }
        /* a gently curved surface (every tap within the normal threshold), two objects */
        b->normal[i * 3] = b->prev_normal[i * 3] = 0.2f * sinf(x * 0.01f);
        b->normal[i * 3 + 1] = b->prev_normal[i * 3 + 1] = 0.1f * cosf(y * 0.02f);
        b->normal[i * 3 + 2] = b->prev_normal[i * 3 + 2] = 1.0f;
        b->id[i] = b->prev_id[i] = x < W / 2 ? 1.0f : 2.0f;
    }
}

/* called through pointers, so that the calls stay calls callgrind can toggle on */
static sbl_result (*volatile temporal_fn)(const sbl_temporal_desc *, const sbl_frame *,
                                          const sbl_history *, const sbl_temporal_output *,
                                          int, int, void *, size_t) = sbl_temporal_filter;
static sbl_result (*volatile stereo_fn)(const sbl_stereo_desc *, sbl_eye_index, const sbl_eye *,
                                        const sbl_eye *, sbl_image, sbl_image, int, int, void *,
                                        size_t) = sbl_stereo_blend;
static sbl_result (*volatile display_fn)(const sbl_display_desc *, const sbl_frame *,
                                         const sbl_temporal_output *, sbl_image, int,
                                         int) = sbl_temporal_display;

/* FNV-1a over the bytes of n floats */
static unsigned long long fnv(unsigned long long h, const float *p, size_t n)
{
    const unsigned char *c = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n * sizeof(float); ++i) h = (h ^ c[i]) * 1099511628211ull;
    return h;
}

int main(int argc, char **argv)
{
    static const char *names[11] = {"easy", "hard", "tiny", "static", "normals", "slant", "uv", "camera",
                                    "offset", "far", "toed"};
    int kind = 0, ev = 0, tail = 0, two = 0, e, i;
    sbl_camera cam[2]; /* case camera: the history's and the frame's */
    sbl_intrinsics kin;
    eye_bufs b[2];
    size_t bytes = sbl_temporal_scratch_size(W, 3);
    void *scratch = malloc(bytes);
    if (argc > 1 && strcmp(argv[1], "two-eyes") == 0) {
        two = 1; /* the easy content */
    } else if (argc > 1) {
        size_t len = strlen(argv[1]), base;
        ev = len > 3 && strcmp(argv[1] + len - 3, "-ev") == 0;
        tail = len > 5 && strcmp(argv[1] + len - 5, "-tail") == 0;
        base = ev ? len - 3 : tail ? len - 5 : len;
        ev |= tail;
        kind = -1;
        for (i = 0; i < 11; ++i)
            if (strncmp(argv[1], names[i], base) == 0 && strlen(names[i]) == base)
                kind = i;
        if (kind < 0) { /* a name not measured must not pass as the easy case */
            fprintf(stderr, "ipp: unknown case '%s' (easy hard tiny static normals slant uv camera offset far toed, "
                            "each also with -ev or -tail; two-eyes)\n", argv[1]);
            free(scratch);
            return 2;
        }
    }
    for (e = 0; e < 2; ++e) fill_eye(&b[e], e, kind, getenv("IPP_SHARED_BIAS") != NULL);
    memset(&kin, 0, sizeof kin);
    kin.fx = kin.fy = 800.0f;
    kin.cx = 0.5f * W;
    kin.cy = 0.5f * H;
    for (e = 0; e < 2; ++e) { /* (case camera) the frame's camera moved by (-0.93, 0.52) mm */
        float pose[16];
        for (i = 0; i < 16; ++i) pose[i] = i % 5 == 0 ? 1.0f : 0.0f;
        if (e) { pose[3] = -0.00093f; pose[7] = 0.00052f; }
        if (sbl_camera_from_pinhole(&cam[e], &kin, pose, SBL_AXES_OPENCV, 0, W, H) != SBL_OK) return 1;
    }
    for (e = 0; e < 2; ++e) {
        sbl_temporal_desc td;
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o;
        memset(&td, 0, sizeof td); memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi);
        memset(&o, 0, sizeof o);
        f.color = sbl_image_make(b[e].color, W, H, 3);
        f.gbuffer.depth = sbl_image_make(b[e].depth, W, H, 1);
        f.gbuffer.motion = sbl_image_make(b[e].motion, W, H, 2);
        hi.color = sbl_image_make(b[e].hist, W, H, 3);
        hi.length = sbl_image_make(b[e].hlen, W, H, 1);
        hi.gbuffer.depth = sbl_image_make(b[e].prev_depth, W, H, 1);
        o.color = sbl_image_make(b[e].out, W, H, 3);
        o.length = sbl_image_make(b[e].olen, W, H, 1);
        if (ev) {
            hi.evidence = sbl_image_make(b[e].hev, W, H, 1);
            o.evidence = sbl_image_make(b[e].oev, W, H, 1);
        }
        if (tail) {
            hi.tail = sbl_image_make(b[e].htl, W, H, 2);
            o.tail = sbl_image_make(b[e].otl, W, H, 2);
        }
        if (kind == 4) {
            f.gbuffer.normals = sbl_image_make(b[e].normal, W, H, 3);
            f.gbuffer.ids = sbl_image_make(b[e].id, W, H, 1);
            hi.gbuffer.normals = sbl_image_make(b[e].prev_normal, W, H, 3);
            hi.gbuffer.ids = sbl_image_make(b[e].prev_id, W, H, 1);
        }
        /* IPP_SHARED_BIAS=c: the temporal filter as the combined pipeline runs it
           (stereo_shared_bias c; 1 in sbl_stereo_temporal_frame and default-stereo) */
        if (getenv("IPP_SHARED_BIAS")) td.stereo_shared_bias = (float)atof(getenv("IPP_SHARED_BIAS"));
        if (kind == 6) td.reproject.motion.units = SBL_MOTION_UV;
        if (kind == 7 || kind == 10) {
            td.source = SBL_TEMPORAL_CAMERA;
            f.camera = &cam[1];
            hi.camera = &cam[0];
        }
        if (temporal_fn(&td, &f, &hi, &o, 0, H, scratch, bytes) != SBL_OK) return 1;
        /* the display of the output (pixels whose N <= 3 lean on their neighbours: in
           case hard the disoccluded ~9 %, elsewhere none) */
        if (display_fn(NULL, &f, &o, sbl_image_make(b[e].display, W, H, 3), 0, H) != SBL_OK) return 1;
    }
    for (e = 0; e < (two ? 2 : 1); ++e) {
        /* eye e's stereo blend of the two temporal outputs (the left eye's alone but in
           case two-eyes) */
        const eye_bufs *t = &b[e], *o = &b[!e];
        sbl_stereo_desc sd;
        sbl_eye te, se;
        memset(&sd, 0, sizeof sd); memset(&te, 0, sizeof te); memset(&se, 0, sizeof se);
        sd.focal_px = 800.0f;
        sd.baseline = 0.065f;
        if (kind == 8) sd.disparity_offset = 0.75f;
        if (kind == 7 || kind == 10) { /* the same rig as two pinhole cameras (eye 0 the left) */
            sd.rig = SBL_RIG_PINHOLE;
            sd.pinhole.eye[0] = sd.pinhole.eye[1] = kin;
            for (i = 0; i < 16; ++i) sd.pinhole.right_from_left[i] = i % 5 == 0 ? 1.0f : 0.0f;
            sd.pinhole.right_from_left[3] = -0.065f;
            if (kind == 10) { /* toed in: turned 0.5 degrees about the vertical axis */
                const double a = 0.5 * 3.14159265358979 / 180.0;
                sd.pinhole.right_from_left[0] = sd.pinhole.right_from_left[10] = (float)cos(a);
                sd.pinhole.right_from_left[2] = (float)sin(a);
                sd.pinhole.right_from_left[8] = (float)-sin(a);
            }
            sd.pinhole.axes = SBL_AXES_OPENCV;
        }
        te.color = sbl_image_make(t->out, W, H, 3);
        te.length = sbl_image_make(t->olen, W, H, 1);
        te.gbuffer.depth = sbl_image_make(t->depth, W, H, 1);
        se.color = sbl_image_make(o->out, W, H, 3);
        se.length = sbl_image_make(o->olen, W, H, 1);
        se.gbuffer.depth = sbl_image_make(o->depth, W, H, 1);
        if (ev) { /* each eye's evidence, as the README's setup passes it (6.15) */
            te.evidence = sbl_image_make(t->oev, W, H, 1);
            se.evidence = sbl_image_make(o->oev, W, H, 1);
        }
        if (kind == 4) {
            te.gbuffer.normals = sbl_image_make(t->normal, W, H, 3);
            te.gbuffer.ids = sbl_image_make(t->id, W, H, 1);
            se.gbuffer.normals = sbl_image_make(o->normal, W, H, 3);
            se.gbuffer.ids = sbl_image_make(o->id, W, H, 1);
        }
        if (stereo_fn(&sd, (sbl_eye_index)e, &te, &se, sbl_image_make(t->stereo_out, W, H, 3),
                      sbl_image_make(NULL, 0, 0, 1), 0, H, scratch, bytes) != SBL_OK)
            return 1;
    }
    printf("ipp case %s%s%s: %dx%d RGB, %s; pixels per call %d (temporal runs 2 eyes)\n",
           two ? "two-eyes" : names[kind], tail ? " with the evidence and tail planes" : ev ? " with the evidence plane" : "",
           getenv("IPP_SHARED_BIAS") ? ", stereo_shared_bias set" : "", W, H, SBL_SIMD_NAME, W * H);
    if (argc > 2 && strcmp(argv[2], "hash") == 0) {
        unsigned long long h = 14695981039346656037ull;
        size_t n = (size_t)W * H;
        for (e = 0; e < 2; ++e) {
            h = fnv(h, b[e].out, n * 3);
            h = fnv(h, b[e].olen, n);
            if (ev) h = fnv(h, b[e].oev, n);
            if (tail) h = fnv(h, b[e].otl, n * 2);
        }
        h = fnv(h, b[0].stereo_out, n * 3);
        if (two) h = fnv(h, b[1].stereo_out, n * 3);
        printf("hash %016llx\n", h);
        h = 14695981039346656037ull;
        for (e = 0; e < 2; ++e) h = fnv(h, b[e].display, n * 3);
        printf("display-hash %016llx\n", h);
    }
    free(scratch);
    return 0;
}
