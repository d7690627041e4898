/* A minimal integration: the frame loop of a renderer that owns its buffers and its
   job system. Per eye and frame: the temporal filter on row bands with caller-owned
   scratch (no allocation in the loop), the history ping-ponged; then the stereo blend
   for display (the history keeps the temporal result). The "renderer" here is a noisy
   textured plane seen by a parallel stereo rig, panning one pixel per frame.

   cc -std=c99 -O2 -I. examples/minimal.c -lm && ./a.out */
#define STEREOBLEND_IMPLEMENTATION
#include "stereoblend.h" /* -I the repository, or the installed header (pkg-config, CMake) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { W = 96, H = 64, FRAMES = 24, BANDS = 4 };
static const float FOCAL = 80.0f, BASELINE = 0.065f, DEPTH = 2.0f;

static float texture(float u, float v, int c) /* the plane's albedo at world position */
{
    return 0.5f + 0.25f * sinf(u * 0.21f + (float)c) * cosf(v * 0.17f);
}

static unsigned rng_state = 1u;
static float noise(void) /* uniform in [-0.5, 0.5) */
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return (float)(rng_state >> 8) / 16777216.0f - 0.5f;
}

/* "Render" eye e of frame f: 1 spp colour, depth, motion. The plane slides one pixel
   to the right per frame: what is seen at x was at x - 1, so mv = (-1, 0). */
static void render(int f, int e, float *rgb, float *ref, float *depth, float *mv)
{
    float disparity = FOCAL * BASELINE / DEPTH; /* the right eye sees the plane shifted */
    int x, y, c;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            float u = (float)x - (float)f + (e ? disparity : 0.0f), v = (float)y;
            size_t i = (size_t)y * W + x;
            for (c = 0; c < 3; ++c) {
                ref[i * 3 + c] = texture(u, v, c);
                rgb[i * 3 + c] = ref[i * 3 + c] + 0.6f * noise(); /* heavy 1-spp noise */
            }
            depth[i] = DEPTH;
            mv[i * 2] = -1.0f;
            mv[i * 2 + 1] = 0.0f;
        }
}

static double rmse(const float *a, const float *b, size_t n)
{
    double s = 0;
    size_t i;
    for (i = 0; i < n; ++i) s += (double)(a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s / (double)n);
}

int main(void)
{
    const size_t n = (size_t)W * H;
    /* everything the renderer owns, allocated once */
    float *rgb[2], *ref[2], *depth[2][2], *mv[2], *hist[2][2], *len[2][2], *evid[2][2], *tail[2][2], *display[2];
    void *scratch = malloc(sbl_temporal_scratch_size(W, 3));
    size_t scratch_bytes = sbl_temporal_scratch_size(W, 3);
    int e, f, b, ping = 0;
    sbl_temporal_desc td = {0}; /* zeros: the defaults (pooled estimator) */
    sbl_stereo_desc sd = {0};
    /* the display below is the stereo blend of the two eyes: a bias of the history that
       both eyes share survives it, their noise does not (docs/ESTIMATORS.md 4.7) */
    td.stereo_shared_bias = 1.0f;
    sd.focal_px = FOCAL;
    sd.baseline = BASELINE;
    if (sbl_stereo_scratch_size(W, 3) > scratch_bytes) return 1; /* the same kernel */
    for (e = 0; e < 2; ++e) {
        rgb[e] = (float *)malloc(n * 3 * sizeof(float));
        ref[e] = (float *)malloc(n * 3 * sizeof(float));
        mv[e] = (float *)malloc(n * 2 * sizeof(float));
        display[e] = (float *)malloc(n * 3 * sizeof(float));
        for (b = 0; b < 2; ++b) {
            depth[e][b] = (float *)malloc(n * sizeof(float));
            hist[e][b] = (float *)malloc(n * 3 * sizeof(float));
            len[e][b] = (float *)malloc(n * sizeof(float));
            evid[e][b] = (float *)malloc(n * sizeof(float));
            tail[e][b] = (float *)malloc(n * 2 * sizeof(float));
        }
    }
    printf("frame  RMSE 1 spp   temporal   temporal + stereo\n");
    for (f = 0; f < FRAMES; ++f) {
        double r_in = 0, r_t = 0, r_ts = 0;
        sbl_eye eye[2];
        for (e = 0; e < 2; ++e) {
            sbl_frame cur = {0};
            sbl_history prev = {0};
            sbl_temporal_output out = {0};
            render(f, e, rgb[e], ref[e], depth[e][ping], mv[e]);
            cur.color = sbl_image_make(rgb[e], W, H, 3);
            cur.gbuffer.depth = sbl_image_make(depth[e][ping], W, H, 1);
            cur.gbuffer.motion = sbl_image_make(mv[e], W, H, 2);
            prev.color = sbl_image_make(hist[e][ping], W, H, 3);
            prev.length = sbl_image_make(len[e][ping], W, H, 1);
            prev.evidence = sbl_image_make(evid[e][ping], W, H, 1); /* optional: change */
            prev.tail = sbl_image_make(tail[e][ping], W, H, 2);     /* optional: rare bright samples */
            prev.gbuffer.depth = sbl_image_make(depth[e][!ping], W, H, 1);
            out.color = sbl_image_make(hist[e][!ping], W, H, 3);
            out.length = sbl_image_make(len[e][!ping], W, H, 1);
            out.evidence = sbl_image_make(evid[e][!ping], W, H, 1); /* evidence over frames */
            out.tail = sbl_image_make(tail[e][!ping], W, H, 2);     /* exceedances over frames */
            /* a job system would run these bands on its workers, each with its own
               scratch; here they run one after the other with one scratch */
            for (b = 0; b < BANDS; ++b) {
                sbl_result r = sbl_temporal_filter(&td, &cur, f ? &prev : NULL, &out,
                                                   H * b / BANDS, H * (b + 1) / BANDS,
                                                   scratch, scratch_bytes);
                if (r != SBL_OK) { fprintf(stderr, "temporal: %s\n", sbl_result_string(r)); return 1; }
            }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = out.color;
            eye[e].length = out.length;
            eye[e].evidence = out.evidence; /* a change either eye saw counts for both */
            eye[e].gbuffer.depth = cur.gbuffer.depth;
            r_in += rmse(rgb[e], ref[e], n * 3) / 2;
            r_t += rmse(hist[e][!ping], ref[e], n * 3) / 2;
        }
        /* stereo blend for display, after both eyes' temporal passes (a barrier in a
           job system); the history keeps the temporal result */
        for (e = 0; e < 2; ++e)
            for (b = 0; b < BANDS; ++b) {
                sbl_image none = {0};
                sbl_result r = sbl_stereo_blend(&sd, (sbl_eye_index)e, &eye[e], &eye[!e],
                                                sbl_image_make(display[e], W, H, 3), none,
                                                H * b / BANDS, H * (b + 1) / BANDS, scratch,
                                                scratch_bytes);
                if (r != SBL_OK) { fprintf(stderr, "stereo: %s\n", sbl_result_string(r)); return 1; }
            }
        for (e = 0; e < 2; ++e) r_ts += rmse(display[e], ref[e], n * 3) / 2;
        if (f % 4 == 3 || f == 0) printf("%5d  %10.4f %10.4f %12.4f\n", f, r_in, r_t, r_ts);
        ping = !ping;
    }
    for (e = 0; e < 2; ++e) {
        free(rgb[e]); free(ref[e]); free(mv[e]); free(display[e]);
        for (b = 0; b < 2; ++b) { free(depth[e][b]); free(hist[e][b]); free(len[e][b]); free(evid[e][b]); free(tail[e][b]); }
    }
    free(scratch);
    return 0;
}
