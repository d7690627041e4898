/* Instructions per pixel of perf's stereo case (bench/perf.c, pipeline "stereo"), for
   callgrind: the same contents at a small size (eye 0 after perf's cases tiny, hard,
   static; both eyes' temporal outputs as the stereo blend's inputs), then the stereo
   blend of each eye, called through a pointer callgrind can toggle on.
   usage: stereo_ipp [W H] [hash | zero]
   hash: an FNV-1a hash of every output (both eyes' temporal and stereo outputs).
   zero: no temporal pass, the blend's inputs all 0 (colour and N), as perf's stereo
   case had them with --only stereo before session 17 (fresh pages).
   ipp = callgrind's total inside sbl_stereo_blend / (2 W H):
     valgrind --tool=callgrind --toggle-collect=sbl_stereo_blend build/stereo_ipp-avx2 */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

typedef struct eye_bufs {
    float *color, *depth, *prev_depth, *motion, *hist, *hlen, *out, *olen, *stereo_out;
} eye_bufs;

static float *falloc(size_t n)
{
    float *p = (float *)calloc(n, sizeof(float));
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

/* bench/perf.c's fill_eye */
static void fill_eye(eye_bufs *b, int w, int h, int eye)
{
    size_t n = (size_t)w * h, i;
    unsigned s = 12345u + 77u * (unsigned)eye;
    b->color = falloc(n * 3); b->depth = falloc(n); b->prev_depth = falloc(n);
    b->motion = falloc(n * 2); b->hist = falloc(n * 3); b->hlen = falloc(n);
    b->out = falloc(n * 3); b->olen = falloc(n); b->stereo_out = falloc(n * 3);
    for (i = 0; i < n; ++i) {
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w), c;
        for (c = 0; c < 3; ++c) {
            s = s * 1664525u + 1013904223u;
            b->color[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c) + (float)(s >> 8) * (1.0f / 16777216.0f) * 0.2f;
            b->hist[i * 3 + c] = 0.5f + 0.3f * sinf(x * 0.05f + c);
        }
        b->depth[i] = 2.0f + 0.001f * (float)y;
        b->prev_depth[i] = b->depth[i];
        b->motion[i * 2] = 0.37f + 0.1f * sinf(y * 0.01f);
        b->motion[i * 2 + 1] = -0.21f;
        b->hlen[i] = 8.0f;
    }
}

/* what perf's cases tiny, hard and static leave in eye 0 when the stereo case runs:
   the static case's motion and depth; the colour of the pixels x = 37 y mod w, channel
   y mod 3, set to 0.5 by the hard case */
static void perf_leftovers(eye_bufs *b, int w, int h)
{
    size_t n = (size_t)w * h, i;
    for (i = 0; i < n; ++i) {
        int x = (int)(i % (size_t)w), y = (int)(i / (size_t)w);
        if (x == (int)(((size_t)y * 37u) % (size_t)w)) b->color[i * 3 + (size_t)(y % 3)] = 0.5f;
        b->motion[i * 2] = 0.0f;
        b->motion[i * 2 + 1] = 0.0f;
        b->depth[i] = b->prev_depth[i] = 2.0f + 0.001f * (float)y;
    }
}

static sbl_result (*volatile stereo_fn)(const sbl_stereo_desc *, sbl_eye_index, const sbl_eye *,
                                        const sbl_eye *, sbl_image, sbl_image, int, int, void *,
                                        size_t) = sbl_stereo_blend;

static unsigned long long fnv(unsigned long long h, const float *p, size_t n)
{
    const unsigned char *c = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n * sizeof(float); ++i) h = (h ^ c[i]) * 1099511628211ull;
    return h;
}

int main(int argc, char **argv)
{
    int w = 640, h = 360, e, hash = 0, zero = 0, a = 1;
    eye_bufs b[2];
    size_t bytes, n;
    void *scratch;
    if (argc > 2 && atoi(argv[1]) > 0) { w = atoi(argv[1]); h = atoi(argv[2]); a = 3; }
    if (argc > a && strcmp(argv[a], "hash") == 0) hash = 1;
    if (argc > a && strcmp(argv[a], "zero") == 0) zero = 1;
    n = (size_t)w * h;
    bytes = sbl_temporal_scratch_size(w, 3);
    scratch = malloc(bytes);
    for (e = 0; e < 2; ++e) fill_eye(&b[e], w, h, e);
    perf_leftovers(&b[0], w, h);
    for (e = 0; e < 2 && !zero; ++e) { /* perf's temporal case of two eyes: the blend's inputs */
        sbl_temporal_desc td;
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o;
        memset(&td, 0, sizeof td); memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi);
        memset(&o, 0, sizeof o);
        f.color = sbl_image_make(b[e].color, w, h, 3);
        f.gbuffer.depth = sbl_image_make(b[e].depth, w, h, 1);
        f.gbuffer.motion = sbl_image_make(b[e].motion, w, h, 2);
        hi.color = sbl_image_make(b[e].hist, w, h, 3);
        hi.length = sbl_image_make(b[e].hlen, w, h, 1);
        hi.gbuffer.depth = sbl_image_make(b[e].prev_depth, w, h, 1);
        o.color = sbl_image_make(b[e].out, w, h, 3);
        o.length = sbl_image_make(b[e].olen, w, h, 1);
        if (sbl_temporal_filter(&td, &f, &hi, &o, 0, h, scratch, bytes) != SBL_OK) return 1;
    }
    for (e = 0; e < 2; ++e) { /* perf's run_stereo */
        const eye_bufs *t = &b[e], *s = &b[!e];
        sbl_stereo_desc sd;
        sbl_eye te, se;
        memset(&sd, 0, sizeof sd); memset(&te, 0, sizeof te); memset(&se, 0, sizeof se);
        sd.focal_px = 800.0f;
        sd.baseline = 0.065f;
        te.color = sbl_image_make(t->out, w, h, 3);
        te.length = sbl_image_make(t->olen, w, h, 1);
        te.gbuffer.depth = sbl_image_make(t->depth, w, h, 1);
        se.color = sbl_image_make(s->out, w, h, 3);
        se.length = sbl_image_make(s->olen, w, h, 1);
        se.gbuffer.depth = sbl_image_make(s->depth, w, h, 1);
        if (stereo_fn(&sd, (sbl_eye_index)e, &te, &se, sbl_image_make(b[e].stereo_out, w, h, 3),
                      sbl_image_make(NULL, 0, 0, 1), 0, h, scratch, bytes) != SBL_OK)
            return 1;
    }
    printf("stereo_ipp: perf's stereo case at %dx%d, %s; pixels per eye %zu (2 eyes)\n", w, h,
#if defined(SBL_SIMD_NAME)
           SBL_SIMD_NAME,
#else
           "scalar",
#endif
           n);
    if (hash) {
        unsigned long long hv = 14695981039346656037ull;
        for (e = 0; e < 2; ++e) {
            hv = fnv(hv, b[e].out, n * 3);
            hv = fnv(hv, b[e].olen, n);
            hv = fnv(hv, b[e].stereo_out, n * 3);
        }
        printf("hash %016llx\n", hv);
    }
    for (e = 0; e < 2; ++e) {
        free(b[e].color); free(b[e].depth); free(b[e].prev_depth); free(b[e].motion);
        free(b[e].hist); free(b[e].hlen); free(b[e].out); free(b[e].olen); free(b[e].stereo_out);
    }
    free(scratch);
    return 0;
}
