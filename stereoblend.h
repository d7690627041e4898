/* stereoblend.h - v0.1 - variance-guided temporal and stereo reuse for rendered frames
   No warranty implied; use at your own risk. Licence at the end of this file.

   WHAT IT DOES
     Per pixel, blends a new noisy estimate Y (this frame / this eye) with another
     estimate X of the same surface (the reprojected history / the other eye) using the
     weight that minimises the expected squared error, a = (B^2 + var_X) / (B^2 + var_X
     + var_Y), estimated from a 3x3 neighbourhood (Philippi et al. 2023), with the
     classic baselines beside it (constant alpha, progressive 1/(N+1), neighbourhood
     clamp, variance clip, fixed beta 0.5) so they can be compared like with like.
     Reprojection is backward: temporal (motion vectors, or camera matrices + depth) and
     stereo (parallel rig, disparity map, or general matrices, with a back-check).

   USAGE
     In exactly one C or C++ file:
         #define STEREOBLEND_IMPLEMENTATION
         #include "stereoblend.h"
     Everywhere else just #include "stereoblend.h".
     #define STEREOBLEND_STATIC before the include to make every function static.

     Per eye, per frame (history is ping-ponged by the caller):

         sbl_temporal_desc desc = {0};           // zeros mean defaults
         sbl_frame   cur  = {0};                  // this frame
         sbl_history prev = {0};                  // last frame's output + G-buffer
         sbl_temporal_output out = {0};
         cur.color          = sbl_image_make(rgb, w, h, 3);
         cur.gbuffer.depth  = sbl_image_make(depth, w, h, 1);
         cur.gbuffer.motion = sbl_image_make(mv, w, h, 2);
         prev.color  = sbl_image_make(hist_rgb, w, h, 3);
         prev.length = sbl_image_make(hist_n, w, h, 1);
         prev.gbuffer.depth = sbl_image_make(prev_depth, w, h, 1);
         out.color  = sbl_image_make(out_rgb, w, h, 3);
         out.length = sbl_image_make(out_n, w, h, 1);
         // whole image, scratch allocated and freed internally:
         sbl_result r = sbl_temporal_filter_frame(&desc, &cur, &prev, &out);
         // or from a job system, rows [y0, y1) with caller-owned scratch:
         //   size_t bytes = sbl_temporal_scratch_size(w, 3);
         //   r = sbl_temporal_filter(&desc, &cur, &prev, &out, y0, y1, scratch, bytes);
         if (r != SBL_OK) puts(sbl_result_string(r));

     First frame: pass prev = NULL (or prev->color.data == NULL): every pixel resets.

     Optional, and recommended: the evidence plane (1 float per pixel), ping-ponged like
     length. The default (pooled) estimator then weighs the evidence of change it has
     seen over the last frames as well as this frame's, and follows lights that move
     every frame more closely (docs/ESTIMATORS.md 3.7). Without it: one frame's evidence.
         prev.evidence = sbl_image_make(hist_ev, w, h, 1);   // last frame's out.evidence
         out.evidence  = sbl_image_make(out_ev, w, h, 1);

     Optional: the tail plane (2 floats per pixel), ping-ponged the same way. The firefly
     limit then admits as much of a bright sample as the rate of such samples at the
     pixel makes worth its variance: small lights, caustics and highlights hit now and
     then keep their mean, lone fireflies are still cut (docs/ESTIMATORS.md 2.4). It
     costs a sixth to a quarter of the temporal filter's instructions again, gathered
     in the colour's plan when laid out as length with offsets doubled (both packed, as
     here).
         prev.tail = sbl_image_make(hist_tail, w, h, 2);     // last frame's out.tail
         out.tail  = sbl_image_make(out_tail, w, h, 2);

     Recommended when nothing else follows (no stereo blend): the display (1 image, same
     size as out.color). Where a history was just dropped or is new (N <= 3) the output
     is about this frame's few samples; the display leans those pixels towards their
     neighbours, where the neighbours agree beyond their noise (not across edges or
     texture). out.color stays the history (docs/ESTIMATORS.md 6.7). Show out.display.
         out.display = sbl_image_make(show_rgb, w, h, 3);
     sbl_temporal_filter_frame writes it; with row bands, call
     sbl_temporal_display(NULL, &cur, &out, display, y0, y1) only after every band is
     filtered (a barrier: it reads the rows above and below its own).

     Stereo: if the display is the stereo blend of the two filtered eyes (sbl_stereo_blend
     after sbl_temporal_filter per eye), set desc.stereo_shared_bias = 1: the blend halves
     each eye's own noise but keeps a bias both eyes share (a light that moved), so the
     temporal weight counts that bias twice (docs/ESTIMATORS.md 4.7), and so does the
     firefly limit's cut of repeated excesses (6.9). Give each sbl_eye its temporal
     output's length and evidence planes (eye.length = out.length, eye.evidence =
     out.evidence): a change either eye's evidence shows is then a change for the stereo
     weight, so the eye whose history lags it is not trusted for its length (6.15). The
     one-call pipeline sbl_stereo_temporal_frame does all this by itself.

   CONVENTIONS (see also README.md)
     Images     fp32, 1-4 interleaved channels, row 0 = top, pixel (i, j) centred at
                (i + 0.5, j + 0.5). sbl_image_make() gives tight rows; otherwise
                stride_bytes (any sign: negative = bottom-up memory, data = the top row)
                and pixel_bytes (a channel view into a wider interleaved buffer), both
                multiples of sizeof(float) (else SBL_ERROR_INVALID_STRIDE). The legacy
                `stride` is in floats; give one of the two. size_bytes (optional) makes
                a layout that reaches past the buffer an error (SBL_ERROR_INVALID_SIZE)
                before anything is read. data is const (const inputs need no cast);
                outputs are written through it. Zero-initialise views built by hand.
     Depth      linear planar view depth (distance along the view axis, > 0); +inf is
                sky and matches only sky. 0, negative or NaN depth = no valid geometry.
                Converters from NDC / reversed-Z buffers: sbl_depth_to_linear().
     Motion     default: pixels, backward (previous position = current + mv), +y down.
                sbl_motion_convention selects UV / NDC units, forward vectors, +y up
                (Blender's Vector pass is pixels, forward=0 for its X,Y pair, y_up=1).
                Motion vectors carry no depth change: the depth test compares the
                previous depth with the current one (camera mode knows the change).
     Cameras    sbl_camera: row-major 4x4, column vectors (p' = M p); OpenGL view space
                (x right, y up, looks down -z); OpenGL-style projection, u = (ndc_x + 1)/2 W,
                v = (1 - ndc_y)/2 H, off-axis allowed; near / far do not matter. Other
                forms: sbl_camera_from_pinhole (fx fy cx cy + a pose in OpenCV axes, x
                right, y down, +z forward, or OpenGL axes) and
                sbl_camera_from_world_to_pixel (one 3x4 P = K [R | t]); integer_pixel_centers
                = 1 for calibrations that centre pixel (i, j) at (i, j) (OpenCV, Middlebury).
                Moving objects: sbl_frame.objects (object-to-world now and before, per id).
     Stereo     disparity d = u_left - u_right (pixels). Parallel rig: d = focal_px *
                baseline / z - disparity_offset (Middlebury doffs = cx_right - cx_left;
                d may be negative); the right-eye match of left pixel u is u - d.
                Disparity maps: 1 channel (d_x) or 2 (d_x, d_y = v_left - v_right), the
                same sign in both eyes' maps. Pinhole rig: intrinsics per eye + the right
                eye's pose relative to the left (x_r = R x_l + T; parallel: T = (-b,0,0)).
                Two cameras (pinhole or matrices rig) that form a parallel rig, to 1e-3
                px, run as the parallel rig (its faster plans).
                The library cannot know which image is left: a swapped target_eye passes
                (symmetric rigs give consistent round trips); sbl_stereo_validate warns
                when the round trips say so. sbl_stereo_desc.fill (take the other eye
                wherever it reprojects, in a blend) is unrelated to sbl_stereo_fill() (the
                mask of pixels that still need a ray).
     Weights    a (alpha, beta) is the weight of the NEW / OWN sample:
                out = (1 - a) X + a Y. Both are returned on request (sbl_temporal_output
                .alpha, sbl_stereo_output.beta).
     History    N per pixel = effective number of samples (Eq. 5), capped, 1 on reset
                (0 where the new sample is not finite and there is no history). A
                history without length means N = 1 everywhere; a history without depth
                (normals, ids) while the frame has it switches that test off silently:
                sbl_temporal_validate warns about both. The history is fetched
                bilinearly; sbl_reproject_desc.history_filter = SBL_HISTORY_CATMULL_ROM
                fetches it with a clamped Catmull-Rom (no resampling blur under
                sub-pixel motion; per-pixel path, about 5x the instructions).
     Defaults   a zero field means its default, so a parameter cannot be set to exactly
                0: use a tiny positive value (e.g. 1e-6f) for that. Tests are switched
                off by flags, never by values: sbl_reproject_desc.disabled_tests
                (SBL_TEST_DEPTH, _NORMAL, _ID, _BACK_CHECK, _FALLBACK).

   THREADING AND MEMORY
     No globals, no threads, no allocation except in the *_frame convenience calls,
     which use SBL_MALLOC / SBL_FREE (define both or neither; they receive the
     desc's alloc_context). Row-range calls on disjoint [y0, y1) may run concurrently.

   ERRORS
     Every call validates all arguments before writing anything and returns an
     sbl_result; sbl_result_string() names it. Bad input never half-writes an output.
     sbl_temporal_validate / sbl_stereo_validate return the same code and fill a
     caller-owned sbl_diag with the culprit field ("frame->gbuffer.depth.stride_bytes")
     and the reason, plus a warning for legal but suspicious input.

   SECTIONS (data-flow order, same in the implementation)
     1. Results          2. Views and conventions   3. Reprojection
     4. Moments          5. Weights                 6. Blend and history length
     7. Temporal filter  8. Stereo                  9. Fill mode (pixels needing a ray)
    10. Adaptive computation (stereo consistency mask, stereo blend where it is needed)
*/
#ifndef STEREOBLEND_H
#define STEREOBLEND_H

#include <stddef.h>

#define SBL_VERSION_MAJOR 0
#define SBL_VERSION_MINOR 1

#ifdef STEREOBLEND_STATIC
#if defined(__GNUC__) || defined(__clang__)
#define SBLDEF static __attribute__((unused)) /* a user may call only some of them */
#else
#define SBLDEF static
#endif
#else
#ifdef __cplusplus
#define SBLDEF extern "C"
#else
#define SBLDEF extern
#endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 1. Results                                                               */
/* ======================================================================== */

typedef enum sbl_result {
    SBL_OK = 0,
    SBL_ERROR_NULL_POINTER,      /* a required pointer (descriptor, buffer data) is NULL  */
    SBL_ERROR_INVALID_SIZE,      /* width or height <= 0, or too large to address          */
    SBL_ERROR_INVALID_CHANNELS,  /* channels outside 1..4, or wrong for the buffer's role  */
    SBL_ERROR_INVALID_STRIDE,    /* stride < width * channels                              */
    SBL_ERROR_SIZE_MISMATCH,     /* buffers that must share width/height do not            */
    SBL_ERROR_CHANNEL_MISMATCH,  /* colour channel counts differ (frame/history/output)    */
    SBL_ERROR_OVERLAP,           /* an output overlaps an input or another output          */
    SBL_ERROR_INVALID_ROWS,      /* not 0 <= y0 <= y1 <= height                            */
    SBL_ERROR_INVALID_PARAM,     /* enum out of range, negative or non-finite parameter    */
    SBL_ERROR_MISSING_INPUT,     /* the chosen mode needs a buffer/camera that is absent   */
    SBL_ERROR_SCRATCH_TOO_SMALL, /* scratch smaller than the *_scratch_size() query        */
    SBL_ERROR_OUT_OF_MEMORY,     /* SBL_MALLOC returned NULL (convenience calls only)      */
    SBL_RESULT_COUNT
} sbl_result;

SBLDEF const char *sbl_result_string(sbl_result result);

/* ======================================================================== */
/* 2. Views and conventions                                                 */
/* ======================================================================== */

/* A view of fp32 pixels: interleaved channels, any row and pixel stride. The library
   writes outputs through `data` (const only so that const inputs need no cast).
   Layouts: tight rows (sbl_image_make); a row pitch in bytes as engines give it
   (D3D RowPitch, Vulkan rowPitch, stb stride_in_bytes); bottom-up memory such as a
   glReadPixels buffer: data = the TOP row (the last in memory), stride_bytes = -pitch;
   a channel view into a wider interleaved buffer: e.g. the XY of an RGBA motion
   target is data = rgba, channels = 2, pixel_bytes = 16 (ZW: data = rgba + 2). */
typedef struct sbl_image {
    const float *data;  /* pixel (0, 0) = top left; NULL = "not given" where optional   */
    int width;
    int height;
    int channels;       /* 1..4, interleaved                                            */
    int stride;         /* row stride in floats (may be negative); 0: see stride_bytes  */
    int stride_bytes;   /* row stride in bytes, a multiple of sizeof(float), may be
                           negative; 0: `stride`, or tight rows if both are 0. If both
                           are given they must agree. |row stride| must cover a row.   */
    int pixel_bytes;    /* bytes from one pixel to the next, a multiple of sizeof(float)
                           and >= channels * sizeof(float); 0: channels * sizeof(float) */
    size_t size_bytes;  /* optional: bytes readable from the lowest address the view
                           touches (the allocation's size for a view at its start);
                           0: not checked. A layout that does not fit is refused
                           (SBL_ERROR_INVALID_SIZE) before any read.                    */
} sbl_image;

/* A tight view (rows of width * channels floats, top row first). */
SBLDEF sbl_image sbl_image_make(const float *data, int width, int height, int channels);

/* G-buffer of one view. Every member is optional: a NULL data pointer skips the test
   that buffer feeds (no depth: no depth test; no ids: no id test, ...). Camera-based
   and parallel-rig reprojection need depth; motion-vector reprojection needs motion. */
typedef struct sbl_gbuffer {
    sbl_image depth;    /* 1 channel, linear planar view depth                    */
    sbl_image normals;  /* 3 channels, any space, same in both views compared     */
    sbl_image ids;      /* 1 channel, object / mesh / material id (exact compare) */
    sbl_image motion;   /* 2 channels, see sbl_motion_convention                  */
} sbl_gbuffer;

typedef enum sbl_motion_units {
    SBL_MOTION_PIXELS = 0,  /* pixels                                    */
    SBL_MOTION_UV,          /* fractions of width / height               */
    SBL_MOTION_NDC          /* NDC units: 2 across the width / height    */
} sbl_motion_units;

typedef struct sbl_motion_convention {
    sbl_motion_units units;
    int forward;  /* 0: mv = p_prev - p_cur (default). 1: mv = p_cur - p_prev      */
    int y_up;     /* 0: +y goes down the rows (default). 1: +y goes up (NDC, Blender) */
} sbl_motion_convention;

/* A perspective camera: row-major, column-vector matrices (p' = M * p). View space has
   OpenGL axes (x right, y up, the camera looks down -z); the projection is OpenGL-style:
   u = (ndc_x + 1)/2 W, v = (1 - ndc_y)/2 H; off-axis (asymmetric) frusta are fine. Near
   and far do not matter: any invertible projection with w_clip = -z_view works, since
   only planar depth (from the depth buffer) places points along the rays.
   Calibrations and other engines give cameras in other forms: the constructors below
   convert them (sbl_camera_from_pinhole, sbl_camera_from_world_to_pixel). */
typedef struct sbl_camera {
    float world_to_view[16];
    float view_to_clip[16];
} sbl_camera;

/* View-space axes of a pose (a world_to_view, or the stereo rig's relative pose). */
typedef enum sbl_view_axes {
    SBL_AXES_OPENGL = 0, /* x right, y up, the camera looks down -z (OpenGL, Vulkan and
                            Blender view space; sbl_camera's convention)               */
    SBL_AXES_OPENCV      /* x right, y down, the camera looks down +z (OpenCV, COLMAP,
                            Middlebury, most calibrations)                             */
} sbl_view_axes;

/* Pinhole intrinsics in pixels: u = fx x/z + cx, v = fy y/z + cy in OpenCV axes
   (u right, v down). */
typedef struct sbl_intrinsics {
    float fx, fy, cx, cy;
} sbl_intrinsics;

/* integer_pixel_centers: 1 if the calibration puts pixel (i, j)'s centre at (i, j)
   (OpenCV, Middlebury, most calibration tools); 0 if at (i + 0.5, j + 0.5), this
   library's convention. */

/* Camera from intrinsics and a pose (world_to_view in the given axes) for a width x
   height image. Writes *out only on SBL_OK (fx, fy > 0, everything finite). */
SBLDEF sbl_result sbl_camera_from_pinhole(sbl_camera *out, const sbl_intrinsics *k,
                                          const float *world_to_view /* 16 */,
                                          sbl_view_axes axes, int integer_pixel_centers,
                                          int width, int height);

/* Camera from one world-to-pixel matrix P (3 rows of 4): (u w, v w, w) = P (x, y, z, 1)
   with u right and v down, as P = K [R | t] (any scale; -P is the same camera). w is
   proportional to planar depth, so the camera is recovered exactly without factoring K
   out. Fails (SBL_ERROR_INVALID_PARAM) if the left 3x3 block is singular. */
SBLDEF sbl_result sbl_camera_from_world_to_pixel(sbl_camera *out,
                                                 const float *world_to_pixel /* 12 */,
                                                 int integer_pixel_centers,
                                                 int width, int height);

typedef enum sbl_depth_encoding {
    SBL_DEPTH_LINEAR = 0,          /* already linear planar depth                         */
    SBL_DEPTH_NDC_GL,              /* OpenGL window depth mapped to [-1,1] (near -1)      */
    SBL_DEPTH_NDC_ZERO_ONE,        /* D3D / Vulkan [0,1] (near 0, far 1)                  */
    SBL_DEPTH_REVERSED,            /* reversed-Z [0,1] (near 1, far 0), finite far plane  */
    SBL_DEPTH_REVERSED_INFINITE,   /* reversed-Z with infinite far plane: z = near / d    */
    SBL_DEPTH_ENCODING_COUNT
} sbl_depth_encoding;

/* Linear planar depth from an encoded depth value (near_z, far_z > 0). Beyond the far
   plane gives +inf (sky); nearer than the near plane, or NaN, gives NaN (no geometry):
   never a wrong finite depth. */
SBLDEF float sbl_depth_to_linear(float encoded, sbl_depth_encoding encoding,
                                 float near_z, float far_z);
/* Whole-image form (src and dst may be the same buffer). */
SBLDEF sbl_result sbl_depth_image_to_linear(sbl_image src, sbl_image dst,
                                            sbl_depth_encoding encoding,
                                            float near_z, float far_z);

/* ======================================================================== */
/* 3. Reprojection                                                          */
/* ======================================================================== */

/* Tests that sbl_reproject_desc.disabled_tests can switch off explicitly (a zero
   tolerance means "default", so switching off is a flag, never a magic value). */
typedef enum sbl_test_flags {
    SBL_TEST_DEPTH = 1,       /* depth test of every tap                                */
    SBL_TEST_NORMAL = 2,      /* normal test of every tap                               */
    SBL_TEST_ID = 4,          /* id test of every tap                                   */
    SBL_TEST_BACK_CHECK = 8,  /* stereo round trip                                      */
    SBL_TEST_FALLBACK = 16,   /* the 3x3 search for thin geometry (same as no_fallback) */
    SBL_TEST_ALL = 31
} sbl_test_flags;

/* How the temporal history is resampled at a sub-pixel position (sbl_reproject_desc.
   history_filter). Bilinear averages its taps, so a history carried by sub-pixel motion
   is low-passed again every frame; Catmull-Rom interpolates without that blur
   (docs/ESTIMATORS.md section 5). Temporal calls only: the stereo warp reads one frame
   once and stays bilinear whatever the field says. */
typedef enum sbl_history_filter {
    SBL_HISTORY_BILINEAR = 0, /* 2x2 taps, renormalised over those that pass the tests  */
    SBL_HISTORY_CATMULL_ROM   /* 4x4 Catmull-Rom taps, clamped to the range of the inner
                                 2x2; the bilinear result wherever a tap it needs fails a
                                 test or lies outside the image. N as bilinear. Runs on the
                                 per-pixel path (slower than the default's row gather). */
} sbl_history_filter;

/* Per-tap consistency tests. Zeros mean defaults; a test runs when both views have its
   buffer and its bit is not in disabled_tests. */
typedef struct sbl_reproject_desc {
    float depth_tolerance;    /* relative depth difference a tap may have; 0 -> 0.05.
                                 A slope term (the pixel's depth gradient) is added.   */
    float normal_threshold;   /* min cosine between normals; 0 -> 0.9; < 0 disables    */
    float back_check_pixels;  /* stereo round-trip tolerance in pixels; 0 -> 1.0        */
    int   no_fallback;        /* 1 disables the 3x3 fallback search for thin geometry  */
    sbl_motion_convention motion;
    int   disabled_tests;     /* SBL_TEST_* bits to switch off; 0: every test on        */
    sbl_history_filter history_filter; /* temporal history fetch; 0: bilinear         */
} sbl_reproject_desc;

typedef enum sbl_temporal_source {
    SBL_TEMPORAL_MOTION = 0,  /* motion vectors of the current frame                   */
    SBL_TEMPORAL_CAMERA       /* depth + both frames' cameras; static geometry, and the
                                 objects of sbl_frame.objects by their own transforms  */
} sbl_temporal_source;

/* An object that moves by its own transform (camera mode): the pixels whose id (the
   G-buffer's ids, exact compare) is `id` are carried back to the previous frame by
   prev_object_to_world * inverse(object_to_world) before the previous camera sees
   them. Any invertible affine transform (rigid, scaled, sheared). */
typedef struct sbl_object_motion {
    float id;                       /* its value in the id buffer                       */
    float object_to_world[16];      /* this frame (row-major, p' = M p)                 */
    float prev_object_to_world[16]; /* the history's frame                              */
} sbl_object_motion;

/* The current frame: colour to filter, its G-buffer, its camera (camera mode). */
typedef struct sbl_frame {
    sbl_image color;
    sbl_gbuffer gbuffer;
    const sbl_camera *camera;
    const sbl_object_motion *objects; /* camera mode, optional: moving objects, sorted by
                                         id (ascending, distinct); needs gbuffer.ids.
                                         Pixels whose id is not listed are static.     */
    int object_count;
} sbl_frame;

/* Last frame's filter output and the G-buffer it was made with. */
typedef struct sbl_history {
    sbl_image color;          /* previous output colour (same channels as the frame)  */
    sbl_image length;         /* previous N per pixel, 1 channel. NULL data: N = 1 for
                                 every pixel, which makes the progressive and
                                 history-aware estimators blend 1:1 - give it.        */
    sbl_gbuffer gbuffer;      /* previous depth / normals / ids for the tap tests      */
    const sbl_camera *camera; /* previous camera (camera mode)                         */
    sbl_image evidence;       /* optional, 1 channel: last frame's out.evidence. The
                                 pooled estimator (the default) then weighs bias
                                 evidence carried over frames as well as this frame's
                                 (docs/ESTIMATORS.md 3.7): faster under moving lights.
                                 NULL data: one frame's evidence, as before.           */
    sbl_image tail;           /* optional, 2 channels: last frame's out.tail. The firefly
                                 limit of the robust and pooled estimators (the default)
                                 then admits as much of a sample's excess as the rate of
                                 such samples at the pixel makes worth its variance, and
                                 the weight counts their variance (docs/ESTIMATORS.md
                                 2.4): hit-or-miss samples (small lights, caustics,
                                 sub-pixel highlights) keep their mean. NULL data: every
                                 excess is cut, as before.                              */
} sbl_history;

/* Reprojected history only (stage 3 on its own): out_color = x*, out_length = N of x*,
   0 where nothing consistent was found (the pixel must reset). */
SBLDEF sbl_result sbl_reproject_temporal(const sbl_reproject_desc *desc,
                                         sbl_temporal_source source,
                                         const sbl_frame *frame, const sbl_history *history,
                                         sbl_image out_color, sbl_image out_length,
                                         int y0, int y1);

/* ======================================================================== */
/* 4. Moments                                                               */
/* ======================================================================== */

/* 3x3 mean and population variance per channel (neighbours outside the image or
   non-finite are left out). Two-pass in double: no m2 - m1^2 cancellation for bright
   HDR values, never negative. mean/var may be NULL-data to skip. */
SBLDEF sbl_result sbl_moments_3x3(sbl_image src, sbl_image mean, sbl_image variance,
                                  int y0, int y1);

/* ======================================================================== */
/* 5. Weights                                                               */
/* ======================================================================== */

typedef enum sbl_estimator {
    SBL_ESTIMATOR_POOLED = 0,        /* default: robust (below), plus bias evidence pooled
                                        along the row (empirical Bayes over five 3x3
                                        blocks, 15 px): catches small changes that cover
                                        a region. Stereo beta on an own eye of N <= 3,
                                        and the temporal weight where the history is
                                        dropped for its bias (c = 0 only): also leans
                                        towards the neighbours' mean where they are
                                        flat (a third estimate); see docs/ESTIMATORS.md
                                        4.2, 6.4 - 6.6                                   */
    SBL_ESTIMATOR_HISTORY_AWARE,     /* var_X from tracked N, bias from paired 3x3
                                        differences beyond their noise level (the
                                        default before the pooled estimator)            */
    SBL_ESTIMATOR_PAPER,             /* Philippi Eq. 4 with Eq. 10/11: a = d^2/(d^2+s^2) */
    SBL_ESTIMATOR_PROGRESSIVE,       /* a = N_Y / (N_X + N_Y): 1/(N+1) for temporal     */
    SBL_ESTIMATOR_CONSTANT,          /* a = constant (alpha 0.1 / beta 0.5 by default)  */
    SBL_ESTIMATOR_ROBUST,            /* history-aware with a soft (Student-t) bias test
                                        and a firefly limit on the new sample; see
                                        docs/ESTIMATORS.md                               */
    SBL_ESTIMATOR_COUNT
} sbl_estimator;

typedef enum sbl_rectify {
    SBL_RECTIFY_NONE = 0,
    SBL_RECTIFY_CLAMP,          /* clamp x* to the 3x3 min/max box of Y              */
    SBL_RECTIFY_VARIANCE_CLIP,  /* clip x* towards the mean into mean +- gamma sigma */
    SBL_RECTIFY_COUNT
} sbl_rectify;

typedef enum sbl_weight_mode {
    SBL_WEIGHT_SCALAR = 0,  /* one weight from squares summed over channels (keeps hue) */
    SBL_WEIGHT_PER_CHANNEL, /* one weight per channel (literal reading of the paper)    */
    SBL_WEIGHT_MODE_COUNT
} sbl_weight_mode;

/* The optimal weight of the new estimate (docs/ALGORITHMS.md section 1):
   a* = (B^2 + var_X) / (B^2 + var_X + var_Y). An infinite var_X or bias gives 1 (no
   usable history); all zero gives 0.5 (nothing tells the two apart). */
SBLDEF float sbl_optimal_weight(float bias2, float var_x, float var_y);

/* Effective sample count after out = lerp(X, Y, a) (Eq. 5 as derived):
   N = N_X N_Y / ((1-a)^2 N_Y + a^2 N_X). */
SBLDEF float sbl_blend_sample_count(float a, float n_x, float n_y);

/* ======================================================================== */
/* 6-7. Temporal filter (reproject, moments, weight, rectify, blend, N)     */
/* ======================================================================== */

typedef struct sbl_temporal_desc {
    sbl_temporal_source source;
    sbl_estimator estimator;
    sbl_rectify rectify;
    sbl_weight_mode weight_mode;
    float constant_alpha;   /* SBL_ESTIMATOR_CONSTANT; 0 -> 0.1                        */
    float alpha_min;        /* lower bound on alpha after estimation; 0 -> none        */
    float max_history;      /* cap on N; 0 -> 64                                        */
    float clip_gamma;       /* SBL_RECTIFY_VARIANCE_CLIP box half-width in sigmas; 0 -> 1.25 */
    float bias_threshold;   /* history-aware / robust: bias counts (fully / with half
                               its posterior) beyond this many standard errors of the
                               mean paired difference; pooled: the local test at 4/3 of
                               it; 0 -> 3                                               */
    sbl_reproject_desc reproject;
    void *alloc_context;    /* passed to SBL_MALLOC / SBL_FREE in *_frame calls        */
    float stereo_shared_bias; /* a stereo blend (beta about 1/2) follows for display:
                               the share c in [0, 1] of the history's bias that the
                               other eye has too (lag, resampling blur). The blend
                               halves independent noise but keeps a shared bias, so
                               the bias counts 1 + c times (docs/ESTIMATORS.md 4.7).
                               c > 0 with the default estimator and a bilinear fetch:
                               the blur of the sub-pixel history fetch counts as a
                               bias too (4.12; a fixed camera has none), and the
                               lean at a restart (6.4) counts its texture, which
                               both eyes' leans share, 1 + c times and ignores the
                               blur's term in its gate (6.10). With the tail plane, the firefly
                               limit admits a larger share of repeated excesses
                               (its cut is a bias too: 6.9).
                               0 -> the call's default: per-eye weights (c = 0) in
                               sbl_temporal_filter, c = 1 (the derived value) in
                               sbl_stereo_temporal_frame, whose output is the blend;
                               SBL_SHARED_BIAS_NONE -> c = 0 in either call        */
} sbl_temporal_desc;

/* sbl_temporal_desc.stereo_shared_bias: per-eye weights even in the combined call */
#define SBL_SHARED_BIAS_NONE (-1.0f)

typedef struct sbl_temporal_output {
    sbl_image color;   /* required; same size and channels as the frame colour    */
    sbl_image length;  /* required; 1 channel: N per pixel for the next frame     */
    sbl_image alpha;   /* optional; 1 channel: the weight used (mean over channels) */
    sbl_image evidence; /* optional; 1 channel: the pooled estimator's bias evidence
                           carried over frames (a ratio, about 1 where nothing changes;
                           1 with the other estimators). Give it to the next frame as
                           sbl_history.evidence, ping-ponged like length.            */
    sbl_image tail;     /* optional; 2 channels: the rate r at which the new samples
                           exceeded the firefly limit's bound and the variance T their
                           excess carried (channel sums), each pixel's average over its
                           history (0 with the estimators that have no limit). Give it
                           to the next frame as sbl_history.tail, ping-ponged.        */
    sbl_image display;  /* optional; same size and channels as color: the image to show
                           when no stereo blend follows (sbl_temporal_display). Written
                           by sbl_temporal_filter_frame only: with row ranges, call
                           sbl_temporal_display once every row is filtered (it reads
                           the rows above and below); sbl_temporal_filter rejects it
                           (SBL_ERROR_INVALID_PARAM). Keep color as the history.      */
} sbl_temporal_output;

/* The descriptor with every zero replaced by its default. */
SBLDEF sbl_temporal_desc sbl_temporal_defaults(const sbl_temporal_desc *desc);

SBLDEF size_t sbl_temporal_scratch_size(int width, int channels);

/* Filter rows [y0, y1). history may be NULL (reset). Outputs may not overlap any input. */
SBLDEF sbl_result sbl_temporal_filter(const sbl_temporal_desc *desc, const sbl_frame *frame,
                                      const sbl_history *history,
                                      const sbl_temporal_output *out, int y0, int y1,
                                      void *scratch, size_t scratch_bytes);

/* Whole image, scratch through SBL_MALLOC / SBL_FREE. */
SBLDEF sbl_result sbl_temporal_filter_frame(const sbl_temporal_desc *desc,
                                            const sbl_frame *frame,
                                            const sbl_history *history,
                                            const sbl_temporal_output *out);

/* The display of a temporal output (docs/ESTIMATORS.md 6.7). Where a pixel's history
   was just dropped or is new (the output's N at most max_length), its value is about
   this frame's few samples: there the displayed value leans towards its eight
   neighbours' mean by the posterior weight V / (V + V_M), V the output's noise (the
   samples' noise, from the differences of adjacent samples along the 3x3 window's
   smoothest direction, over N) and V_M the neighbours' spread beyond their noise plus
   their mean's noise (texture and edges: no lean). Elsewhere display = color.
   The history (filtered->color) is not changed: a lean written into it would carry
   the neighbours' texture bias frame after frame. Not for an output that a stereo
   blend takes next: the stereo blend leans on its own (sbl_stereo_desc). Rows
   [y0, y1) of display; reads rows y0 - 1 .. y1 of filtered->color / length and of
   frame->color, which belong to the neighbouring bands: with row bands, call it only
   once every band's sbl_temporal_filter has finished (a barrier), never right after
   its own band's. desc may be NULL (defaults). display may not overlap an input
   (sbl_temporal_filter_frame: nor the frame's or the history's planes). */
typedef struct sbl_display_desc {
    float max_length;  /* lean where N <= this; 0: SBL_DISPLAY_LEAN_MAX_N (3); < 0: off */
} sbl_display_desc;

SBLDEF sbl_result sbl_temporal_display(const sbl_display_desc *desc, const sbl_frame *frame,
                                       const sbl_temporal_output *filtered, sbl_image display,
                                       int y0, int y1);

/* ======================================================================== */
/* 8. Stereo                                                                */
/* ======================================================================== */

/* Stereo rigs. Disparity d = (position in the left image) - (position in the right
   image) of one surface point, in pixels: the right-eye match of left pixel (u, v) is
   (u - d, v), the left-eye match of right pixel (u, v) is (u + d, v). */
typedef enum sbl_stereo_rig {
    SBL_RIG_PARALLEL = 0,  /* rectified pair: d = focal_px * baseline / depth
                              - disparity_offset (Middlebury: doffs = cx_right - cx_left) */
    SBL_RIG_DISPARITY,     /* per-eye disparity images: 1 channel (d_x, rows aligned) or 2
                              channels (d_x, d_y), both left minus right, in both eyes'
                              maps; non-finite = no match                               */
    SBL_RIG_MATRICES,      /* general rig: each eye's sbl_camera (any model) + depth;
                              a pair that is a parallel rig runs as one (this and
                              PINHOLE: sbl__rig_as_parallel)                             */
    SBL_RIG_PINHOLE,       /* calibration: intrinsics per eye + the right eye's pose
                              relative to the left (sbl_pinhole_rig) + depth           */
    SBL_RIG_COUNT
} sbl_stereo_rig;

/* A calibrated pair (SBL_RIG_PINHOLE). right_from_left maps a point from the left eye's
   view space to the right eye's (OpenCV stereoCalibrate's R, T: x_r = R x_l + T; a
   parallel rig with baseline b in OpenCV or OpenGL axes: T = (-b, 0, 0)). */
typedef struct sbl_pinhole_rig {
    sbl_intrinsics eye[2];        /* left, right                                         */
    float right_from_left[16];    /* rigid pose, row-major 4x4                           */
    sbl_view_axes axes;           /* axes of both view spaces                            */
    int integer_pixel_centers;    /* 1: cx, cy put pixel (i, j)'s centre at (i, j)       */
} sbl_pinhole_rig;

typedef enum sbl_eye_index { SBL_EYE_LEFT = 0, SBL_EYE_RIGHT = 1 } sbl_eye_index;

typedef struct sbl_eye {
    sbl_image color;          /* this eye's colour (after the temporal filter)        */
    sbl_image length;         /* optional: this eye's N (history-aware beta uses it)  */
    sbl_gbuffer gbuffer;      /* depth (parallel, matrices, pinhole), normals, ids    */
    sbl_image disparity;      /* SBL_RIG_DISPARITY: 1 (d_x) or 2 (d_x, d_y) channels  */
    const sbl_camera *camera; /* SBL_RIG_MATRICES                                     */
    sbl_image evidence;       /* optional, 1 channel: this eye's sbl_temporal_output.
                                 evidence of this frame. The pooled stereo beta (the
                                 default) then takes a change that either eye's carried
                                 evidence shows (here at the pixel, the other eye's at
                                 its match) as certain, so that the eye whose history
                                 lags it is not trusted by its length (docs/ESTIMATORS.md
                                 6.15). NULL data: the stereo pair's own test alone.   */
} sbl_eye;

typedef struct sbl_stereo_desc {
    sbl_stereo_rig rig;
    float focal_px;         /* parallel rig: focal length in pixels                     */
    float baseline;         /* parallel rig: eye separation, same units as depth        */
    float disparity_offset; /* parallel rig: cx_right - cx_left in pixels (Middlebury
                               doffs; asymmetric per-eye frusta); 0: same principal point */
    sbl_pinhole_rig pinhole;/* SBL_RIG_PINHOLE                                           */
    sbl_estimator estimator;/* POOLED (default), HISTORY_AWARE, PAPER, PROGRESSIVE,
                               CONSTANT, ROBUST                                          */
    sbl_rectify rectify;
    sbl_weight_mode weight_mode;
    float constant_beta;    /* SBL_ESTIMATOR_CONSTANT; 0 -> 0.5                         */
    float clip_gamma;       /* 0 -> 1.25                                                 */
    float bias_threshold;   /* 0 -> 3                                                    */
    int fill;               /* 1: take the other eye wherever it reprojects (beta = 0)  */
    sbl_reproject_desc reproject;
    void *alloc_context;
} sbl_stereo_desc;

SBLDEF sbl_stereo_desc sbl_stereo_defaults(const sbl_stereo_desc *desc);

/* The other eye reprojected into `target` (rows [y0,y1)): out_color = x*, out_valid =
   1 where the taps passed the tests and the back-check, else 0 (optional, 1 channel). */
SBLDEF sbl_result sbl_reproject_stereo(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                       const sbl_eye *target, const sbl_eye *source,
                                       sbl_image out_color, sbl_image out_valid,
                                       int y0, int y1);

SBLDEF size_t sbl_stereo_scratch_size(int width, int channels);

typedef struct sbl_stereo_output {
    sbl_image color;   /* required; same size and channels as the target eye's colour */
    sbl_image length;  /* optional; 1 channel: the effective N of the blend            */
    sbl_image beta;    /* optional; 1 channel: the weight of the own eye used (mean
                          over channels; 1 where the other eye did not reproject)     */
} sbl_stereo_output;

/* Stereo blend of one eye, rows [y0, y1): out = lerp(other eye reprojected, own, beta),
   with beta and N returned like the temporal filter's alpha and N. Both eyes are read
   unblended, so calling it for each eye is symmetric. */
SBLDEF sbl_result sbl_stereo_filter(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                    const sbl_eye *target, const sbl_eye *source,
                                    const sbl_stereo_output *out, int y0, int y1,
                                    void *scratch, size_t scratch_bytes);

/* sbl_stereo_filter with the outputs colour and length (optional) only. */
SBLDEF sbl_result sbl_stereo_blend(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                   const sbl_eye *target, const sbl_eye *source,
                                   sbl_image out_color, sbl_image out_length,
                                   int y0, int y1, void *scratch, size_t scratch_bytes);

/* Both eyes, whole images, scratch through SBL_MALLOC / SBL_FREE. */
SBLDEF sbl_result sbl_stereo_blend_frame(const sbl_stereo_desc *desc,
                                         const sbl_eye *left, const sbl_eye *right,
                                         sbl_image out_left, sbl_image out_right);

/* The combined pipeline in the paper's order, for both eyes and a whole frame:
   the temporal filter per eye (its output is the next frame's history), then the
   stereo blend of the two temporal outputs into the display images. */
typedef struct sbl_stereo_temporal_io {
    sbl_frame frame[2];               /* this frame, left and right                     */
    const sbl_history *history[2];    /* last frame's temporal outputs (NULL: reset)    */
    sbl_temporal_output temporal[2];  /* the new history (colour and length required;
                                         display NULL: the stereo blend is the display) */
    sbl_image disparity[2];           /* SBL_RIG_DISPARITY only                         */
    sbl_image display[2];             /* the stereo blend, for display                  */
} sbl_stereo_temporal_io;

/* Scratch through SBL_MALLOC / SBL_FREE (td->alloc_context). Everything is validated
   before anything is written. td->stereo_shared_bias 0 means 1 here (the display is
   the stereo blend: docs/ESTIMATORS.md 4.7); SBL_SHARED_BIAS_NONE for per-eye weights. */
SBLDEF sbl_result sbl_stereo_temporal_frame(const sbl_temporal_desc *td,
                                            const sbl_stereo_desc *sd,
                                            const sbl_stereo_temporal_io *io);

/* ======================================================================== */
/* Diagnostics: which field, and why                                        */
/* ======================================================================== */

/* Filled by the validate calls (no globals: the caller owns it). A validate call runs
   the checks of its filter call and names the culprit the way the caller spells it,
   e.g. field "frame->gbuffer.depth.stride_bytes", message "-5 is not a multiple of
   sizeof(float)". It also reports the first input that is legal but probably not what
   was meant (e.g. a history without depth while the frame has depth, which turns the
   depth test off, or a stereo pair whose target_eye looks swapped). */
typedef struct sbl_diag {
    sbl_result result;  /* what the filter call returns for these arguments            */
    char field[80];     /* the culprit; empty when result is SBL_OK                    */
    char message[200];  /* why, in words; empty when result is SBL_OK                  */
    char warning[240];  /* legal but suspicious (the first found); empty if none        */
} sbl_diag;

/* The checks of sbl_temporal_filter (any row range, scratch given) without writing any
   output. diag may be NULL (then this is a plain validation). A row call writes no
   display, so out->display set is an error here (SBL_ERROR_INVALID_PARAM) even where
   sbl_temporal_filter_frame would accept it: validate with display NULL. */
SBLDEF sbl_result sbl_temporal_validate(const sbl_temporal_desc *desc, const sbl_frame *frame,
                                        const sbl_history *history,
                                        const sbl_temporal_output *out, sbl_diag *diag);

/* The checks of sbl_stereo_filter (out given) or of sbl_reproject_stereo /
   sbl_stereo_fill's eyes (out NULL: the target needs no colour). Warns when the
   correspondences of a sample of pixels work far better with target_eye swapped. */
SBLDEF sbl_result sbl_stereo_validate(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                      const sbl_eye *target, const sbl_eye *source,
                                      const sbl_stereo_output *out, sbl_diag *diag);

/* ======================================================================== */
/* 9. Fill mode: which pixels of the second eye still need a ray            */
/* ======================================================================== */

/* Reproject `source` (a traced eye) into `target` (rows [y0,y1)): out_color receives
   the reprojected colour where valid; mask[y * mask_stride + x] = 1 where the pixel
   still needs a ray, else 0. *needs_ray_count (optional) receives the count of 1s
   written in these rows. */
SBLDEF sbl_result sbl_stereo_fill(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                  const sbl_eye *target, const sbl_eye *source,
                                  sbl_image out_color, unsigned char *mask, int mask_stride,
                                  int y0, int y1, long *needs_ray_count);

/* Copy traced pixels into dst where mask is 1 (rows [y0, y1)). */
SBLDEF sbl_result sbl_merge_traced(sbl_image dst, sbl_image traced,
                                   const unsigned char *mask, int mask_stride,
                                   int y0, int y1);

/* ======================================================================== */
/* 10. Adaptive computation                                                 */
/* ======================================================================== */

/* Stereo consistency (Wu, after Weber's law): a value A(p) of the target eye and the
   value A(p*) of the other eye at p's back-checked match p* differ visibly when their
   Weber ratio reaches the threshold:
       r = |A(p) - A(p*)| / max(|A(p)|, |A(p*)|)     (per channel; the largest counts)
   (Wu's Eq. 2 divides by A(p) alone; the larger magnitude makes r symmetric, so the two
   eyes' masks agree pair by pair.) The two images are any per-eye quantity (filtered colour, luminance, AO), 1..4
   channels, the same in both eyes; p* is found by the stereo reprojection of
   sbl_reproject_stereo (tap tests, back-check) with `source_value` in place of the
   source eye's colour, so A(p*) is its bilinear value over the taps that pass.
   Defined cases:
     - both values 0: r = 0 (equal); one 0, the other not: r = 1;
     - negative values: the magnitudes in the denominator, so -a against a gives r = 2;
     - NaN or +-inf in target_value at p: inconsistent (nothing finite can agree);
     - NaN or +-inf in source_value: such taps are dropped as by every reprojection; if
       no tap remains the pixel has no correspondence;
     - a pixel without a correspondence is SBL_NO_CORRESPONDENCE whatever its values.
   The eyes' colour and length are not read (only their geometry); the rig, focal
   length, baseline and tap tests are those of `desc`.
   Cost: one stereo reprojection per pixel, about 70 % of a stereo blend's instructions
   pixel by pixel; with scratch and eyes holding depth alone, a row at a time in lanes
   (about 440 instructions per pixel on SSE2 against 1200). The mask pays where the
   work it lets skip costs more than that (Wu's stereo-aware SSAO) and where the two
   values are smooth: on Monte-Carlo colour it marks noise (independent noise of
   relative sd s in each eye marks a share 2 Phi(-T / (sqrt(2) s)), so fewer than 10 %
   at T = 2 % needs s < 0.9 %: 256-spp references of the shared scenes still mark a
   third of their pixels). */
typedef enum sbl_consistency_class {
    SBL_CONSISTENT = 0,         /* r < threshold                                      */
    SBL_INCONSISTENT = 1,       /* r >= threshold, or a non-finite target value       */
    SBL_NO_CORRESPONDENCE = 2   /* no back-checked match (occluded, outside, no depth) */
} sbl_consistency_class;

typedef struct sbl_consistency_counts {
    long consistent, inconsistent, no_correspondence; /* pixels of the rows written    */
    double inconsistent_ratio; /* inconsistent / (consistent + inconsistent); 0 if none.
                                  For row bands sum the counts and divide again.      */
} sbl_consistency_counts;

#define SBL_WEBER_THRESHOLD 0.02f /* Walter et al. (Lightcuts), used by Wu */

/* Classify rows [y0, y1) of `target_eye`: mask[y * mask_stride + x] receives an
   sbl_consistency_class. threshold 0 -> SBL_WEBER_THRESHOLD; negative or non-finite is
   SBL_ERROR_INVALID_PARAM. counts (optional) receives the counts of these rows.
   scratch (optional: NULL and 0 for none) of sbl_stereo_consistency_scratch_size()
   bytes lets the reprojection run a row at a time in vector lanes where the build and
   the eyes allow it (SIMD, an int-addressable source; normals and ids tested in lanes):
   the same mask, bit for bit, at a fraction of the cost; a smaller scratch is
   SBL_ERROR_SCRATCH_TOO_SMALL. */
SBLDEF size_t sbl_stereo_consistency_scratch_size(int width, int channels);
SBLDEF sbl_result sbl_stereo_consistency(const sbl_stereo_desc *desc, float threshold,
                                         sbl_eye_index target_eye, const sbl_eye *target,
                                         const sbl_eye *source, sbl_image target_value,
                                         sbl_image source_value, unsigned char *mask,
                                         int mask_stride, int y0, int y1, void *scratch,
                                         size_t scratch_bytes, sbl_consistency_counts *counts);

/* Adaptive stereo blend (Wu's adaptive pass): rows [y0, y1) of out_color / out_length
   receive sbl_stereo_blend's result (bit for bit) where mask[y * mask_stride + x] is
   SBL_INCONSISTENT, and the target eye's own colour and N (1 where it has no length)
   everywhere else. The blend runs only on the tiles of 16 x 16 pixels that hold a
   marked pixel, so its time follows the share of such tiles. The mask is typically
   sbl_stereo_consistency's on the two eyes' per-eye results (it is read whole, so
   compute all of it first). With the mask's own reprojection this costs more than the
   blend everywhere unless few tiles are marked: sbl_stereo_blend_adaptive does both in
   one pass.
   Scratch: sbl_stereo_scratch_size(). blended_count (optional): marked pixels of these
   rows. Arguments are checked as by sbl_stereo_blend, before anything is written. */
SBLDEF sbl_result sbl_stereo_blend_masked(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                          const sbl_eye *target, const sbl_eye *source,
                                          const unsigned char *mask, int mask_stride,
                                          sbl_image out_color, sbl_image out_length,
                                          int y0, int y1, void *scratch,
                                          size_t scratch_bytes, long *blended_count);

/* Adaptive stereo blend in one pass: the mask and the blend share one reprojection.
   The two calls above reproject every pixel twice (once for the mask, once for the
   blend on the marked tiles), so on an image where most tiles hold a marked pixel they
   cost more than the blend everywhere. This call reprojects each row once, classifies
   its pixels from that reprojection (the Weber test of sbl_stereo_consistency on the
   eyes' colours: own colour against the other eye's colour at the back-checked match),
   and runs the blend kernel only on the 16 x 16 tiles holding an inconsistent pixel,
   reading the reprojection it already made. Result: sbl_stereo_blend's bit for bit on
   the marked tiles (per_pixel: on the inconsistent pixels only, exactly what
   sbl_stereo_consistency + sbl_stereo_blend_masked give on the same comparison), the
   own colour and N (1 where it has none) elsewhere. Cost: one reprojection (about 70 % of a blend on the shared scenes)
   plus the kernel on the marked tiles; at most that of sbl_stereo_blend plus the test
   and the copies, at least the reprojection. */
typedef struct sbl_adaptive_desc {
    float threshold;  /* Weber threshold T; 0 -> SBL_WEBER_THRESHOLD; < 0 or non-finite:
                         SBL_ERROR_INVALID_PARAM                                     */
    int per_channel;  /* 0: the Rec. 709 luminance 0.2126 c0 + 0.7152 c1 + 0.0722 c2 of
                         3- and 4-channel colour (Weber's law is about luminance), each
                         channel of 1- and 2-channel colour; 1: each channel (the
                         largest ratio counts). Other values: SBL_ERROR_INVALID_PARAM */
    int per_pixel;    /* 0: every pixel of a marked tile takes the blend (the kernel
                         computed it anyway; a kept pixel next to a blended match can
                         turn inconsistent); 1: only the inconsistent pixels, as
                         sbl_stereo_blend_masked. Other values: SBL_ERROR_INVALID_PARAM */
    int nearest;      /* 0: the test reads the reprojection the blend uses (bilinear, every
                         tap test: the classes of sbl_stereo_consistency); 1: the other
                         eye's value at the nearest pixel of the match (depth test and
                         back-check only), so that nothing is reprojected but the marked
                         tiles (and the row above and below each band of them): cheaper
                         below about a third of the tiles, 20-30 % dearer where all are
                         marked; on sub-pixel matches it marks more than the bilinear
                         test. Other values: SBL_ERROR_INVALID_PARAM                     */
} sbl_adaptive_desc;

/* Scratch of sbl_stereo_blend_adaptive: the blend's, plus the reprojection of 18 rows
   and a 16-row mask (0: width or channels out of range). */
SBLDEF size_t sbl_stereo_adaptive_scratch_size(int width, int channels);

/* Rows [y0, y1) of out_color / out_length as described above. adaptive NULL or zeroed:
   the defaults. mask (optional, NULL for none) receives each pixel's
   sbl_consistency_class, counts (optional) the counts of these rows and tiles_blended
   (optional) the tiles of these rows the kernel ran on, out of tiles_total (optional).
   Row bands give the same output as one whole call. Errors: those of sbl_stereo_blend
   (eyes, desc, outputs, rows), then SBL_ERROR_INVALID_PARAM (adaptive->threshold or
   ->per_channel), SBL_ERROR_INVALID_STRIDE (mask_stride < width with a mask),
   SBL_ERROR_OVERLAP (mask over an input or output), SBL_ERROR_NULL_POINTER /
   SBL_ERROR_SCRATCH_TOO_SMALL (scratch); nothing is written on an error. */
SBLDEF sbl_result sbl_stereo_blend_adaptive(const sbl_stereo_desc *desc,
                                            const sbl_adaptive_desc *adaptive,
                                            sbl_eye_index target_eye, const sbl_eye *target,
                                            const sbl_eye *source, sbl_image out_color,
                                            sbl_image out_length, unsigned char *mask,
                                            int mask_stride, int y0, int y1, void *scratch,
                                            size_t scratch_bytes,
                                            sbl_consistency_counts *counts,
                                            long *tiles_blended, long *tiles_total);

#ifdef __cplusplus
}
#endif
#endif /* STEREOBLEND_H */

/* ######################################################################## */
/*                              IMPLEMENTATION                              */
/* ######################################################################## */
#ifdef STEREOBLEND_IMPLEMENTATION
#ifndef STEREOBLEND_IMPLEMENTATION_DONE
#define STEREOBLEND_IMPLEMENTATION_DONE

#include <math.h>
#include <string.h>
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h> /* snprintf: diagnostics */

#if defined(SBL_MALLOC) != defined(SBL_FREE)
#error "define both SBL_MALLOC and SBL_FREE, or neither"
#endif
#ifndef SBL_MALLOC
#include <stdlib.h>
#define SBL_MALLOC(size, context) ((void)(context), malloc(size))
#define SBL_FREE(ptr, context) ((void)(context), free(ptr))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Casts that C++ -Wold-style-cast accepts: value conversions and pointer
   reinterpretations (C: plain casts). */
#ifdef __cplusplus
#define SBL__CAST(T, v) (static_cast<T>(v))
#define SBL__PCAST(T, v) (reinterpret_cast<T>(v))
#else
#define SBL__CAST(T, v) ((T)(v))
#define SBL__PCAST(T, v) ((T)(v))
#endif

/* A hint to fetch the cache line `floats` floats past the float pointer p: the lane
   paths ask one row ahead of the rows they read, which the hardware's stream prefetch
   left to miss (session 18, docs/RESULTS.md); a line is SBL__LINE_FLOATS floats. The
   address is formed in uintptr_t, since a row ahead may lie past the image (a prefetch
   never faults); no-op without GCC's builtin. Changes no value. */
#define SBL__LINE_FLOATS 16
#if defined(__GNUC__) || defined(__clang__)
#define SBL__PREFETCH_AT(p, floats, w) \
    __builtin_prefetch(SBL__PCAST(const void *, SBL__PCAST(uintptr_t, p) + \
                                                    SBL__CAST(uintptr_t, floats) * sizeof(float)), w)
#else
#define SBL__PREFETCH_AT(p, floats, w) ((void)0)
#endif
#define SBL__PREFETCH(p, floats) SBL__PREFETCH_AT(p, floats, 0)
#define SBL__PREFETCH_W(p, floats) SBL__PREFETCH_AT(p, floats, 1) /* (a line about to be written) */

/* ------------------------------------------------------------------------ */
/* 1. Results                                                               */
/* ------------------------------------------------------------------------ */

SBLDEF const char *sbl_result_string(sbl_result result)
{
    switch (result) {
    case SBL_OK: return "ok";
    case SBL_ERROR_NULL_POINTER: return "a required pointer is NULL";
    case SBL_ERROR_INVALID_SIZE: return "width or height is not positive or too large";
    case SBL_ERROR_INVALID_CHANNELS: return "channel count outside 1..4 or wrong for the buffer";
    case SBL_ERROR_INVALID_STRIDE: return "row stride smaller than width * channels";
    case SBL_ERROR_SIZE_MISMATCH: return "buffers differ in width or height";
    case SBL_ERROR_CHANNEL_MISMATCH: return "colour buffers differ in channel count";
    case SBL_ERROR_OVERLAP: return "an output buffer overlaps an input or another output";
    case SBL_ERROR_INVALID_ROWS: return "row range is not within 0 <= y0 <= y1 <= height";
    case SBL_ERROR_INVALID_PARAM: return "a parameter is out of range or not finite";
    case SBL_ERROR_MISSING_INPUT: return "the chosen mode needs a buffer or camera that is absent";
    case SBL_ERROR_SCRATCH_TOO_SMALL: return "scratch memory smaller than the size query";
    case SBL_ERROR_OUT_OF_MEMORY: return "allocation failed";
    case SBL_RESULT_COUNT: break;
    }
    return "unknown sbl_result";
}

/* ------------------------------------------------------------------------ */
/* 2. Views and conventions                                                 */
/* ------------------------------------------------------------------------ */

SBLDEF sbl_image sbl_image_make(const float *data, int width, int height, int channels)
{
    sbl_image im;
    memset(&im, 0, sizeof im);
    im.data = data;
    im.width = width;
    im.height = height;
    im.channels = channels;
    return im; /* stride 0: tight rows and pixels */
}

/* Finite test on the bits, so that -ffast-math (which may assume no NaN/inf and fold
   isfinite() to 1) cannot remove it. */
static int sbl__finite(float v)
{
    unsigned int bits;
    memcpy(&bits, &v, sizeof bits);
    return (bits & 0x7f800000u) != 0x7f800000u;
}
/* 1 if any of the n values is NaN or infinite: one branch for a whole pixel. The
   exponent field plus one overflows into the sign bit exactly when it is all ones. */
static int sbl__any_nonfinite(const float *v, int n)
{
    unsigned int bits, acc = 0;
    int k;
    for (k = 0; k < n; ++k) {
        memcpy(&bits, &v[k], sizeof bits);
        acc |= (bits & 0x7f800000u) + 0x00800000u;
    }
    return SBL__CAST(int, acc >> 31);
}
static int sbl__is_zero(float v) /* +-0 on the bits: NaN is not 0 under -ffast-math */
{
    unsigned int bits;
    memcpy(&bits, &v, sizeof bits);
    return (bits & 0x7fffffffu) == 0u;
}
static int sbl__is_nan(float v)
{
    unsigned int bits;
    memcpy(&bits, &v, sizeof bits);
    return (bits & 0x7fffffffu) > 0x7f800000u;
}
static int sbl__is_pos_inf(float v)
{
    unsigned int bits;
    memcpy(&bits, &v, sizeof bits);
    return bits == 0x7f800000u;
}
/* A depth that is valid geometry: z > 0, finite or +inf (sky); NaN, -inf, 0 and
   negatives are not. The one scalar form of the test (sbl__tap_want_init,
   sbl__valid_depth; the lane form is sbl__lanes_want's). */
static int sbl__depth_is_geometry(float z)
{
    return z > 0.0f && (sbl__finite(z) || sbl__is_pos_inf(z));
}

/* Views are addressed in per-pixel loops of the stage calls: keep these inlined. */
#if defined(__GNUC__) || defined(__clang__)
#define SBL__VIEW_FN static __inline__ __attribute__((always_inline))
#elif defined(_MSC_VER)
#define SBL__VIEW_FN static __forceinline
#else
#define SBL__VIEW_FN static
#endif

/* Row and pixel steps in floats (signed; validated by sbl__check_image first). */
SBL__VIEW_FN int sbl__step_of(const sbl_image *im)
{
    return im->pixel_bytes ? im->pixel_bytes / SBL__CAST(int, sizeof(float)) : im->channels;
}
SBL__VIEW_FN ptrdiff_t sbl__stride(const sbl_image *im)
{
    if (im->stride_bytes)
        return SBL__CAST(ptrdiff_t, im->stride_bytes / SBL__CAST(int, sizeof(float)));
    if (im->stride) return SBL__CAST(ptrdiff_t, im->stride);
    return SBL__CAST(ptrdiff_t, sbl__step_of(im)) * SBL__CAST(ptrdiff_t, im->width);
}

/* Pixel (x, y) of a view, writable: inputs and outputs share sbl_image, whose data is
   const so that const inputs need no cast; an output's memory is the caller's writable
   buffer, and this is the one place the qualifier is dropped. */
SBL__VIEW_FN float *sbl__px(const sbl_image *im, int x, int y)
{
    float *base;
    memcpy(&base, &im->data, sizeof base);
    return base + SBL__CAST(ptrdiff_t, y) * sbl__stride(im) +
           SBL__CAST(ptrdiff_t, x) * sbl__step_of(im);
}

/* Bytes from the lowest to one past the highest byte a view touches (after
   sbl__check_image's limits this fits in ptrdiff_t). */
static size_t sbl__footprint(const sbl_image *im)
{
    ptrdiff_t rs = sbl__stride(im);
    size_t rows = SBL__CAST(size_t, (rs < 0 ? -rs : rs));
    return (SBL__CAST(size_t, im->height - 1) * rows +
            SBL__CAST(size_t, im->width - 1) * SBL__CAST(size_t, sbl__step_of(im)) +
            SBL__CAST(size_t, im->channels)) * sizeof(float);
}

/* Validate one view. want_channels 0 accepts 1..4. */
static sbl_result sbl__check_image(const sbl_image *im, int want_channels)
{
    const int fs = SBL__CAST(int, sizeof(float));
    ptrdiff_t rs, row_floats;
    if (!im->data) return SBL_ERROR_NULL_POINTER;
    if (im->width <= 0 || im->height <= 0) return SBL_ERROR_INVALID_SIZE;
    if (im->channels < 1 || im->channels > 4) return SBL_ERROR_INVALID_CHANNELS;
    if (want_channels && im->channels != want_channels) return SBL_ERROR_INVALID_CHANNELS;
    /* row and pixel offsets must fit in an int-sized stride and in size_t */
    if (im->width > INT_MAX / 4 || im->height > INT_MAX / 4) return SBL_ERROR_INVALID_SIZE;
    /* byte steps address whole floats; the two row strides must agree if both given */
    if (im->stride_bytes % fs != 0 || im->pixel_bytes % fs != 0) return SBL_ERROR_INVALID_STRIDE;
    if (im->pixel_bytes != 0 && im->pixel_bytes < im->channels * fs)
        return SBL_ERROR_INVALID_STRIDE;
    if (im->stride_bytes != 0 && im->stride != 0 && im->stride_bytes / fs != im->stride)
        return SBL_ERROR_INVALID_STRIDE;
    if (im->stride_bytes == 0 && im->stride < 0 && im->stride < -(INT_MAX / fs))
        return SBL_ERROR_INVALID_STRIDE;
    /* a row's extent must be addressable (32-bit ptrdiff_t included) */
    if (SBL__CAST(size_t, sbl__step_of(im)) >
        SBL__CAST(size_t, PTRDIFF_MAX) / sizeof(float) / SBL__CAST(size_t, im->width))
        return SBL_ERROR_INVALID_SIZE;
    /* rows may not overlap each other: |row stride| covers a row's last pixel */
    rs = sbl__stride(im);
    if (rs < 0) rs = -rs;
    row_floats = SBL__CAST(ptrdiff_t, im->width - 1) * SBL__CAST(ptrdiff_t, sbl__step_of(im)) +
                 im->channels;
    if (rs < row_floats) return SBL_ERROR_INVALID_STRIDE;
    /* the whole footprint must be addressable: (h - 1) |stride| + row <= PTRDIFF_MAX */
    if (SBL__CAST(size_t, rs) >
        (SBL__CAST(size_t, PTRDIFF_MAX) / sizeof(float) - SBL__CAST(size_t, row_floats)) /
            SBL__CAST(size_t, im->height))
        return SBL_ERROR_INVALID_SIZE;
    if (im->size_bytes != 0 && sbl__footprint(im) > im->size_bytes) return SBL_ERROR_INVALID_SIZE;
    return SBL_OK;
}

/* Optional view: NULL data is fine (returns OK), else must be a valid image of the
   same size as the reference. */
static sbl_result sbl__check_optional(const sbl_image *im, int want_channels, int w, int h)
{
    sbl_result r;
    if (!im->data) return SBL_OK;
    r = sbl__check_image(im, want_channels);
    if (r != SBL_OK) return r;
    if (im->width != w || im->height != h) return SBL_ERROR_SIZE_MISMATCH;
    return SBL_OK;
}

static sbl_result sbl__check_gbuffer(const sbl_gbuffer *g, int w, int h)
{
    sbl_result r;
    if ((r = sbl__check_optional(&g->depth, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&g->normals, 3, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&g->ids, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&g->motion, 2, w, h)) != SBL_OK) return r;
    return SBL_OK;
}

/* Byte range an image touches: [begin, end), from its lowest address (the last row in
   memory order first when the row stride is negative). */
static void sbl__range(const sbl_image *im, const char **begin, const char **end)
{
    ptrdiff_t rs = sbl__stride(im);
    const float *lo = im->data + (rs < 0 ? SBL__CAST(ptrdiff_t, (im->height - 1)) * rs : 0);
    *begin = SBL__PCAST(const char *, lo);
    *end = *begin + sbl__footprint(im);
}

/* Does the byte range [m0, m1) (a mask, or another view's range) overlap an image's?
   An absent image (NULL data) overlaps nothing. */
static int sbl__overlap_bytes(const char *m0, const char *m1, const sbl_image *im)
{
    const char *c0, *c1;
    if (!im->data) return 0;
    sbl__range(im, &c0, &c1);
    return m0 < c1 && c0 < m1;
}

/* Do two views share a float? Views with the same row period whose rows interleave
   without touching (the two eyes of a side-by-side texture) do not, nor do views with
   the same pixel step whose channels interleave (the colour and a 4th-channel weight
   of one RGBA buffer); anything else is judged by the byte ranges (conservative). */
static int sbl__overlap(const sbl_image *a, const sbl_image *b)
{
    const char *a0, *a1, *b0, *b1;
    ptrdiff_t sa, sb;
    if (!a->data) return 0;
    sbl__range(a, &a0, &a1);
    if (!sbl__overlap_bytes(a0, a1, b)) return 0;
    sbl__range(b, &b0, &b1);
    sa = sbl__stride(a); if (sa < 0) sa = -sa;
    sb = sbl__stride(b); if (sb < 0) sb = -sb;
    if (sa == sb && (a->height > 1 || b->height > 1)) {
        const size_t period = SBL__CAST(size_t, sa) * sizeof(float), fs = sizeof(float);
        const size_t pa = SBL__CAST(size_t, sbl__step_of(a)) * fs;
        const size_t pb = SBL__CAST(size_t, sbl__step_of(b)) * fs;
        const size_t ca = SBL__CAST(size_t, a->channels) * fs;
        const size_t cb = SBL__CAST(size_t, b->channels) * fs;
        const size_t ra = SBL__CAST(size_t, a->width - 1) * pa + ca;
        const size_t rb = SBL__CAST(size_t, b->width - 1) * pb + cb;
        size_t d = SBL__CAST(size_t, (b0 >= a0 ? b0 - a0 : a0 - b0)) % period;
        if (b0 < a0) d = (period - d) % period; /* offset of b's rows within a's period */
        if (d >= ra && d + rb <= period) return 0;
        if (pa == pb && period % pa == 0) { /* channels interleaved within the pixels */
            size_t e = d % pa;
            if (e >= ca && e + cb <= pa) return 0;
        }
        return 1;
    }
    return 1;
}

/* The planes of a G-buffer, a frame, a history and an eye: the one list of each, for the
   overlap checks and the diagnostic walks (whose names follow this order). Each writes
   the planes' addresses to p (room for SBL__PLANES_MAX) and returns their count. */
#define SBL__PLANES_MAX 8
static int sbl__gbuffer_planes(const sbl_gbuffer *g, const sbl_image **p)
{
    p[0] = &g->depth; p[1] = &g->normals; p[2] = &g->ids; p[3] = &g->motion;
    return 4;
}
static int sbl__frame_planes(const sbl_frame *f, const sbl_image **p)
{
    p[0] = &f->color;
    return 1 + sbl__gbuffer_planes(&f->gbuffer, p + 1);
}
/* h may be NULL (none); with_evidence 0: all but the evidence and tail planes (the last) */
static int sbl__history_planes(const sbl_history *h, const sbl_image **p, int with_evidence)
{
    int n;
    if (!h) return 0;
    p[0] = &h->color; p[1] = &h->length;
    n = 2 + sbl__gbuffer_planes(&h->gbuffer, p + 2);
    if (with_evidence) { p[n++] = &h->evidence; p[n++] = &h->tail; }
    return n;
}
static int sbl__eye_planes(const sbl_eye *e, const sbl_image **p)
{
    p[0] = &e->color; p[1] = &e->length; p[2] = &e->disparity; p[3] = &e->evidence;
    return 4 + sbl__gbuffer_planes(&e->gbuffer, p + 4);
}
static int sbl__temporal_output_planes(const sbl_temporal_output *o, const sbl_image **p)
{
    p[0] = &o->color; p[1] = &o->length; p[2] = &o->alpha; p[3] = &o->evidence; p[4] = &o->tail;
    return 5;
}

/* Does view a (or the byte range [m0, m1)) overlap any of the n views p[0 .. n)? */
static int sbl__overlap_any(const sbl_image *a, const sbl_image *const *p, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (sbl__overlap(a, p[i])) return 1;
    return 0;
}
static int sbl__overlap_bytes_any(const char *m0, const char *m1, const sbl_image *const *p,
                                  int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (sbl__overlap_bytes(m0, m1, p[i])) return 1;
    return 0;
}

static int sbl__overlap_gbuffer(const sbl_image *a, const sbl_gbuffer *g)
{
    const sbl_image *p[SBL__PLANES_MAX];
    return sbl__overlap_any(a, p, sbl__gbuffer_planes(g, p));
}

static int sbl__overlap_frame(const sbl_image *a, const sbl_frame *f)
{
    const sbl_image *p[SBL__PLANES_MAX];
    return sbl__overlap_any(a, p, sbl__frame_planes(f, p));
}

static int sbl__overlap_history(const sbl_image *a, const sbl_history *h) /* h may be NULL */
{
    const sbl_image *p[SBL__PLANES_MAX];
    return sbl__overlap_any(a, p, sbl__history_planes(h, p, 1));
}

static int sbl__overlap_eye(const sbl_image *a, const sbl_eye *e)
{
    const sbl_image *p[SBL__PLANES_MAX];
    return sbl__overlap_any(a, p, sbl__eye_planes(e, p));
}

static int sbl__param_ok(float v) /* finite and >= 0 */
{
    return sbl__finite(v) && v >= 0.0f;
}

SBLDEF float sbl_depth_to_linear(float d, sbl_depth_encoding enc, float n, float f)
{
    /* NaN stays NaN ("no geometry"); beyond the far plane is sky (+inf); nearer than
       the near plane cannot be geometry: NaN. Never a wrong finite depth. */
    const float nan_value = SBL__CAST(float, HUGE_VAL - HUGE_VAL);
    if (enc == SBL_DEPTH_LINEAR || !sbl__finite(d)) return d;
    switch (enc) {
    case SBL_DEPTH_NDC_GL: /* d in [-1,1], -1 near: z = 2nf / (f + n - d (f - n)) */
        if (d > 1.0f) return SBL__CAST(float, HUGE_VAL);
        if (d < -1.0f) return nan_value;
        return SBL__CAST(float, 2.0 * SBL__CAST(double, n) * SBL__CAST(double, f) / (SBL__CAST(double, f) + SBL__CAST(double, n) - SBL__CAST(double, d) * (SBL__CAST(double, f) - SBL__CAST(double, n))));
    case SBL_DEPTH_NDC_ZERO_ONE: /* d in [0,1], 0 near: z = nf / (f - d (f - n)) */
        if (d > 1.0f) return SBL__CAST(float, HUGE_VAL);
        if (d < 0.0f) return nan_value;
        return SBL__CAST(float, SBL__CAST(double, n) * SBL__CAST(double, f) / (SBL__CAST(double, f) - SBL__CAST(double, d) * (SBL__CAST(double, f) - SBL__CAST(double, n))));
    case SBL_DEPTH_REVERSED: /* d in [0,1], 1 near: z = nf / (n + d (f - n)) */
        if (d < 0.0f) return SBL__CAST(float, HUGE_VAL);
        if (d > 1.0f) return nan_value;
        return SBL__CAST(float, SBL__CAST(double, n) * SBL__CAST(double, f) / (SBL__CAST(double, n) + SBL__CAST(double, d) * (SBL__CAST(double, f) - SBL__CAST(double, n))));
    case SBL_DEPTH_REVERSED_INFINITE: /* z = n / d; d = 0 is the far plane at infinity */
        if (!(d > 0.0f)) return SBL__CAST(float, HUGE_VAL);
        if (d > 1.0f) return nan_value;
        return n / d;
    case SBL_DEPTH_LINEAR:
    case SBL_DEPTH_ENCODING_COUNT: break;
    }
    return nan_value;
}

SBLDEF sbl_result sbl_depth_image_to_linear(sbl_image src, sbl_image dst,
                                            sbl_depth_encoding enc, float n, float f)
{
    sbl_result r;
    int x, y;
    if ((r = sbl__check_image(&src, 1)) != SBL_OK) return r;
    if ((r = sbl__check_image(&dst, 1)) != SBL_OK) return r;
    if (src.width != dst.width || src.height != dst.height) return SBL_ERROR_SIZE_MISMATCH;
    if (SBL__CAST(int, enc) < 0 || enc >= SBL_DEPTH_ENCODING_COUNT) return SBL_ERROR_INVALID_PARAM;
    if (enc != SBL_DEPTH_LINEAR) {
        if (!sbl__finite(n) || n <= 0.0f) return SBL_ERROR_INVALID_PARAM;
        if (enc != SBL_DEPTH_REVERSED_INFINITE && (!sbl__finite(f) || f <= n))
            return SBL_ERROR_INVALID_PARAM;
    }
    /* in place only with the same layout: otherwise a row could be overwritten
       before it is read */
    if (src.data == dst.data ? sbl__stride(&src) != sbl__stride(&dst) ||
                                   sbl__step_of(&src) != sbl__step_of(&dst)
                             : sbl__overlap(&src, &dst))
        return SBL_ERROR_OVERLAP;
    for (y = 0; y < src.height; ++y)
        for (x = 0; x < src.width; ++x)
            *sbl__px(&dst, x, y) = sbl_depth_to_linear(*sbl__px(&src, x, y), enc, n, f);
    return SBL_OK;
}

/* 4x4 helpers, row-major, computed in double. */
static void sbl__mat_mul(double *out, const double *a, const double *b)
{
    int i, j, k;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) {
            double s = 0.0;
            for (k = 0; k < 4; ++k) s += a[i * 4 + k] * b[k * 4 + j];
            out[i * 4 + j] = s;
        }
}

/* Gauss-Jordan with partial pivoting; returns 0 if singular or non-finite. */
static int sbl__mat_invert(double *out, const double *m)
{
    double a[16];
    int i, j, k;
    memcpy(a, m, sizeof a);
    for (i = 0; i < 16; ++i) out[i] = (i % 5 == 0) ? 1.0 : 0.0;
    for (i = 0; i < 4; ++i) {
        int piv = i;
        double best = fabs(a[i * 4 + i]), inv;
        for (k = i + 1; k < 4; ++k)
            if (fabs(a[k * 4 + i]) > best) { best = fabs(a[k * 4 + i]); piv = k; }
        if (!(best > 1e-300)) return 0; /* also catches NaN */
        if (piv != i)
            for (j = 0; j < 4; ++j) {
                double t = a[i * 4 + j]; a[i * 4 + j] = a[piv * 4 + j]; a[piv * 4 + j] = t;
                t = out[i * 4 + j]; out[i * 4 + j] = out[piv * 4 + j]; out[piv * 4 + j] = t;
            }
        inv = 1.0 / a[i * 4 + i];
        for (j = 0; j < 4; ++j) { a[i * 4 + j] *= inv; out[i * 4 + j] *= inv; }
        for (k = 0; k < 4; ++k) {
            double fct;
            if (k == i) continue;
            fct = a[k * 4 + i];
            if (fct == 0.0) continue;
            for (j = 0; j < 4; ++j) {
                a[k * 4 + j] -= fct * a[i * 4 + j];
                out[k * 4 + j] -= fct * out[i * 4 + j];
            }
        }
    }
    for (i = 0; i < 16; ++i)
        if (out[i] - out[i] != 0.0) return 0; /* non-finite */
    return 1;
}

static void sbl__mat_from_float(double *out, const float *m)
{
    int i;
    for (i = 0; i < 16; ++i) out[i] = SBL__CAST(double, m[i]);
}

/* Maps a pixel of one camera at linear depth z to the pixel of another camera:
   precomputed once per call. */
typedef struct sbl__cam_map {
    double clip_to_view[16];  /* inverse projection of the source (this) camera      */
    double view_to_view[16];  /* this view -> other view                             */
    double other_proj[16];    /* other view -> clip                                   */
    double view_to_world[16]; /* this view -> world (objects that move)               */
    double world_to_other[16];/* world -> other view (objects that move)              */
    double width, height;     /* this image (for pixel -> ndc)                        */
    double other_width, other_height;
    /* The static map folded (sbl__cam_map_fold): each term a row over (ndc x, ndc y, 1)
       for a pixel's ray, q = clip_to_view (ndc x, ndc y, 0, 1), scaled to view depth 1:
       the ray's q2 and q3 (its validity); the other clip's c0, c1, c3 and the other
       view's v2, v3 from the ray's first three terms (through other_proj view_to_view
       and view_to_view), and their columns for the point's w = 1. */
    double ray[2][3], clip[3][3], clip_w[3], view[2][3], view_w[2];
    const sbl_object_motion *objects; /* sorted by id; NULL: everything static        */
    int object_count;
} sbl__cam_map;

/* The other camera forms as the equivalent OpenGL pair (double): a view space with the
   camera looking down -z (its z is minus the planar depth; x and y need not be metric)
   and a clip matrix whose NDC maps to pixels as u = (ndc_x + 1)/2 W, v = (1 - ndc_y)/2 H.
   The depth rows only need to be invertible: rays are cast through ndc z = 0 and
   scaled to the given planar depth. Return 0 if the input is not usable. */
static void sbl__proj_depth_rows(double *proj)
{
    int i;
    for (i = 0; i < 16; ++i) proj[i] = 0.0;
    proj[10] = -1.0; proj[11] = -2.0; proj[14] = -1.0;
}

static int sbl__pinhole_gl(const sbl_intrinsics *k, const float *world_to_view,
                           sbl_view_axes axes, int integer_pixel_centers, int w, int h,
                           double *view, double *proj)
{
    const double half = integer_pixel_centers ? 0.5 : 0.0; /* to centres at i + 0.5 */
    double cx, cy;
    int i;
    if (SBL__CAST(int, axes) != SBL__CAST(int, SBL_AXES_OPENGL) &&
        SBL__CAST(int, axes) != SBL__CAST(int, SBL_AXES_OPENCV))
        return 0;
    if (w <= 0 || h <= 0) return 0;
    if (!sbl__finite(k->fx) || !sbl__finite(k->fy) || !sbl__finite(k->cx) ||
        !sbl__finite(k->cy) || !(k->fx > 0.0f) || !(k->fy > 0.0f))
        return 0;
    for (i = 0; i < 16; ++i)
        if (!sbl__finite(world_to_view[i])) return 0;
    sbl__mat_from_float(view, world_to_view);
    if (axes == SBL_AXES_OPENCV) /* (x, y, z) -> (x, -y, -z) */
        for (i = 4; i < 12; ++i) view[i] = -view[i];
    cx = SBL__CAST(double, k->cx) + half;
    cy = SBL__CAST(double, k->cy) + half;
    sbl__proj_depth_rows(proj);
    /* u = fx x / d + cx with d = -z: ndc_x d = (2 fx / W) x + (1 - 2 cx / W) z */
    proj[0] = 2.0 * SBL__CAST(double, k->fx) / w;
    proj[2] = 1.0 - 2.0 * cx / w;
    /* v = -fy y / d + cy: ndc_y d = (2 fy / H) y + (2 cy / H - 1) z */
    proj[5] = 2.0 * SBL__CAST(double, k->fy) / h;
    proj[6] = 2.0 * cy / h - 1.0;
    return 1;
}

static int sbl__world_to_pixel_gl(const float *P, int integer_pixel_centers, int w, int h,
                                  double *view, double *proj)
{
    /* P = [M | p]: once det M > 0 (else use -P), w = |row 2 of M| * planar depth > 0 in
       front. View space: (u w, v w, -depth). */
    const double half = integer_pixel_centers ? 0.5 : 0.0;
    double m[12], det, s;
    int i;
    if (w <= 0 || h <= 0) return 0;
    for (i = 0; i < 12; ++i) {
        if (!sbl__finite(P[i])) return 0;
        m[i] = SBL__CAST(double, P[i]);
    }
    det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
          m[2] * (m[4] * m[9] - m[5] * m[8]);
    if (!(fabs(det) > 1e-300) || det - det != 0.0) return 0;
    if (det < 0.0)
        for (i = 0; i < 12; ++i) m[i] = -m[i];
    s = sqrt(m[8] * m[8] + m[9] * m[9] + m[10] * m[10]);
    for (i = 0; i < 8; ++i) view[i] = m[i];
    for (i = 8; i < 12; ++i) view[i] = -m[i] / s;
    view[12] = 0.0; view[13] = 0.0; view[14] = 0.0; view[15] = 1.0;
    sbl__proj_depth_rows(proj);
    /* u = U / (s d) + half with U = view x, d = -view z */
    proj[0] = 2.0 / (w * s);
    proj[2] = 1.0 - 2.0 * half / w;
    proj[5] = -2.0 / (h * s);
    proj[6] = 2.0 * half / h - 1.0;
    return 1;
}

static void sbl__camera_store(sbl_camera *out, const double *view, const double *proj)
{
    int i;
    for (i = 0; i < 16; ++i) {
        out->world_to_view[i] = SBL__CAST(float, view[i]);
        out->view_to_clip[i] = SBL__CAST(float, proj[i]);
    }
}

SBLDEF sbl_result sbl_camera_from_pinhole(sbl_camera *out, const sbl_intrinsics *k,
                                          const float *world_to_view, sbl_view_axes axes,
                                          int integer_pixel_centers, int width, int height)
{
    double view[16], proj[16];
    if (!out || !k || !world_to_view) return SBL_ERROR_NULL_POINTER;
    if (width <= 0 || height <= 0) return SBL_ERROR_INVALID_SIZE;
    if (!sbl__pinhole_gl(k, world_to_view, axes, integer_pixel_centers, width, height, view,
                         proj))
        return SBL_ERROR_INVALID_PARAM;
    sbl__camera_store(out, view, proj);
    return SBL_OK;
}

SBLDEF sbl_result sbl_camera_from_world_to_pixel(sbl_camera *out, const float *world_to_pixel,
                                                 int integer_pixel_centers, int width,
                                                 int height)
{
    double view[16], proj[16];
    int i;
    if (!out || !world_to_pixel) return SBL_ERROR_NULL_POINTER;
    if (width <= 0 || height <= 0) return SBL_ERROR_INVALID_SIZE;
    if (!sbl__world_to_pixel_gl(world_to_pixel, integer_pixel_centers, width, height, view,
                                proj))
        return SBL_ERROR_INVALID_PARAM;
    for (i = 0; i < 16; ++i) /* the float matrices must stay finite */
        if (!sbl__finite(SBL__CAST(float, view[i])) || !sbl__finite(SBL__CAST(float, proj[i])))
            return SBL_ERROR_INVALID_PARAM;
    sbl__camera_store(out, view, proj);
    return SBL_OK;
}

/* The folded terms of sbl__cam_map_apply: clip_to_view's rows 2 and 3, and the rows of
   M = other_proj view_to_view (0, 1, 3) and of view_to_view (2, 3) times clip_to_view's
   first three rows, each over (ndc x, ndc y, 1) (clip_to_view's columns 0, 1, 3; ndc z
   is 0). */
static void sbl__cam_map_fold(sbl__cam_map *m)
{
    static const int col[3] = {0, 1, 3}, clip_row[3] = {0, 1, 3};
    const double *C = m->clip_to_view, *V = m->view_to_view;
    double M[16];
    int r, k, j;
    sbl__mat_mul(M, m->other_proj, V);
    for (k = 0; k < 3; ++k) {
        m->ray[0][k] = C[8 + col[k]];
        m->ray[1][k] = C[12 + col[k]];
    }
    for (r = 0; r < 3; ++r) {
        for (k = 0; k < 3; ++k) {
            double t = 0.0;
            for (j = 0; j < 3; ++j) t += M[clip_row[r] * 4 + j] * C[j * 4 + col[k]];
            m->clip[r][k] = t;
        }
        m->clip_w[r] = M[clip_row[r] * 4 + 3];
    }
    for (r = 0; r < 2; ++r) {
        for (k = 0; k < 3; ++k) {
            double t = 0.0;
            for (j = 0; j < 3; ++j) t += V[(2 + r) * 4 + j] * C[j * 4 + col[k]];
            m->view[r][k] = t;
        }
        m->view_w[r] = V[(2 + r) * 4 + 3];
    }
}

/* From view / projection pairs in double (the other camera forms). */
static int sbl__cam_map_init_gl(sbl__cam_map *m, const double *view, const double *proj,
                                int w, int h, const double *other_view,
                                const double *other_proj, int ow, int oh)
{
    memcpy(m->other_proj, other_proj, sizeof m->other_proj);
    memcpy(m->world_to_other, other_view, sizeof m->world_to_other);
    m->objects = NULL;
    m->object_count = 0;
    if (!sbl__mat_invert(m->clip_to_view, proj)) return 0;
    if (!sbl__mat_invert(m->view_to_world, view)) return 0;
    sbl__mat_mul(m->view_to_view, other_view, m->view_to_world);
    m->width = w; m->height = h; m->other_width = ow; m->other_height = oh;
    sbl__cam_map_fold(m);
    return 1;
}

static int sbl__cam_map_init(sbl__cam_map *m, const sbl_camera *from, int w, int h,
                             const sbl_camera *to, int ow, int oh)
{
    double proj[16], view[16], other_view[16], other_proj[16];
    int i;
    for (i = 0; i < 16; ++i) /* NaN / inf entries can still "invert" to a finite matrix */
        if (!sbl__finite(from->world_to_view[i]) || !sbl__finite(from->view_to_clip[i]) ||
            !sbl__finite(to->world_to_view[i]) || !sbl__finite(to->view_to_clip[i]))
            return 0;
    sbl__mat_from_float(proj, from->view_to_clip);
    sbl__mat_from_float(view, from->world_to_view);
    sbl__mat_from_float(other_view, to->world_to_view);
    sbl__mat_from_float(other_proj, to->view_to_clip);
    return sbl__cam_map_init_gl(m, view, proj, w, h, other_view, other_proj, ow, oh);
}

/* Pixel centre (px, py) at planar depth z (may be +inf: a direction) -> the point in this
   camera's view space (p[3] = 0 for a direction). Returns 0 if the ray is degenerate. */
static int sbl__cam_map_point(const sbl__cam_map *m, double px, double py, float z, double *p)
{
    double ndc[4], q[4];
    int i, k;
    ndc[0] = 2.0 * px / m->width - 1.0;
    ndc[1] = 1.0 - 2.0 * py / m->height;
    ndc[2] = 0.0;
    ndc[3] = 1.0;
    for (i = 0; i < 4; ++i) {
        q[i] = 0.0;
        for (k = 0; k < 4; ++k) q[i] += m->clip_to_view[i * 4 + k] * ndc[k];
    }
    /* ray through the pixel, scaled so that its view depth (-z) is 1 */
    if (q[3] == 0.0 || -q[2] / q[3] <= 0.0) return 0;
    for (i = 0; i < 3; ++i) q[i] = (q[i] / q[3]) / (-q[2] / q[3]);
    if (sbl__is_pos_inf(z)) { p[0] = q[0]; p[1] = q[1]; p[2] = q[2]; p[3] = 0.0; }
    else {
        const double zd = SBL__CAST(double, z);
        p[0] = q[0] * zd; p[1] = q[1] * zd; p[2] = q[2] * zd; p[3] = 1.0;
    }
    return 1;
}

/* A point of the other camera's view space -> its pixel position and planar depth. */
static int sbl__cam_map_project(const sbl__cam_map *m, const double *v, double *ox, double *oy,
                                double *oz)
{
    double c[4];
    int i, k;
    for (i = 0; i < 4; ++i) {
        c[i] = 0.0;
        for (k = 0; k < 4; ++k) c[i] += m->other_proj[i * 4 + k] * v[k];
    }
    if (!(c[3] > 0.0)) return 0;
    *ox = (c[0] / c[3] + 1.0) * 0.5 * m->other_width;
    *oy = (1.0 - c[1] / c[3]) * 0.5 * m->other_height;
    *oz = v[3] == 0.0 ? HUGE_VAL : -v[2];
    return 1;
}

static void sbl__mat_apply(double *out, const double *m, const double *p)
{
    int i, k;
    for (i = 0; i < 4; ++i) {
        out[i] = 0.0;
        for (k = 0; k < 4; ++k) out[i] += m[i * 4 + k] * p[k];
    }
}

/* Pixel centre (px, py) at planar depth z (may be +inf: a direction) -> position in the
   other image and the point's planar depth there. Returns 0 if the ray is degenerate or
   the point behind the other camera. The static map, folded (sbl__cam_map_fold): the
   ray q = clip_to_view (n, 0, 1) scaled to view depth 1 is q / -q2 (valid where q2 and
   q3 have opposite signs: -q2 / q3 > 0), and the point at depth z is z q / -q2 with w = 1
   (a direction: q / -q2, w = 0), so each clip or view term is s r(n) + w r_w, with s =
   z / -q2 and r(n) a row over (n, 1): the same map as sbl__cam_map_point, then
   view_to_view, then sbl__cam_map_project, in about half the operations (the lanes:
   sbl__cam_lanes_k, the same operations in the same order). */
static double sbl__cam_row(const double *r, double n0, double n1)
{
    return r[0] * n0 + r[1] * n1 + r[2];
}

static int sbl__cam_map_apply(const sbl__cam_map *m, double px, double py, float z,
                              double *ox, double *oy, double *oz)
{
    const double n0 = 2.0 * px / m->width - 1.0, n1 = 1.0 - 2.0 * py / m->height;
    const double q2 = sbl__cam_row(m->ray[0], n0, n1), q3 = sbl__cam_row(m->ray[1], n0, n1);
    const int sky = sbl__is_pos_inf(z);
    const double w = sky ? 0.0 : 1.0;
    double sc, c0, c1, c3, v2, v3;
    if (!((q2 < 0.0 && q3 > 0.0) || (q2 > 0.0 && q3 < 0.0))) return 0;
    sc = (sky ? 1.0 : SBL__CAST(double, z)) / (0.0 - q2);
    c0 = sc * sbl__cam_row(m->clip[0], n0, n1) + m->clip_w[0] * w;
    c1 = sc * sbl__cam_row(m->clip[1], n0, n1) + m->clip_w[1] * w;
    c3 = sc * sbl__cam_row(m->clip[2], n0, n1) + m->clip_w[2] * w;
    v2 = sc * sbl__cam_row(m->view[0], n0, n1) + m->view_w[0] * w;
    v3 = sc * sbl__cam_row(m->view[1], n0, n1) + m->view_w[1] * w;
    if (!(c3 > 0.0)) return 0;
    *ox = (c0 / c3 + 1.0) * 0.5 * m->other_width;
    *oy = (1.0 - c1 / c3) * 0.5 * m->other_height;
    *oz = v3 == 0.0 ? HUGE_VAL : -v2;
    return 1;
}

/* Solves M q = p for an object_to_world M (float, row-major) in double with partial
   pivoting. Returns 0 if M is singular or not finite. */
static int sbl__mat_solve(const float *mf, const double *p, double *q)
{
    double a[4][5];
    int i, j, k;
    for (i = 0; i < 4; ++i) {
        for (j = 0; j < 4; ++j) a[i][j] = SBL__CAST(double, mf[i * 4 + j]);
        a[i][4] = p[i];
    }
    for (i = 0; i < 4; ++i) {
        int piv = i;
        for (k = i + 1; k < 4; ++k)
            if (fabs(a[k][i]) > fabs(a[piv][i])) piv = k;
        if (!(fabs(a[piv][i]) > 1e-300)) return 0;
        if (piv != i)
            for (j = 0; j < 5; ++j) { double t = a[i][j]; a[i][j] = a[piv][j]; a[piv][j] = t; }
        for (k = i + 1; k < 4; ++k) {
            double f = a[k][i] / a[i][i];
            for (j = i; j < 5; ++j) a[k][j] -= f * a[i][j];
        }
    }
    for (i = 3; i >= 0; --i) {
        double v = a[i][4];
        for (j = i + 1; j < 4; ++j) v -= a[i][j] * q[j];
        q[i] = v / a[i][i];
    }
    return q[0] - q[0] == 0.0 && q[1] - q[1] == 0.0 && q[2] - q[2] == 0.0 && q[3] - q[3] == 0.0;
}

/* The moving object with this id (binary search; ids sorted ascending), or NULL. */
static const sbl_object_motion *sbl__find_object(const sbl__cam_map *m, float id)
{
    int lo = 0, hi = m->object_count - 1;
    while (lo <= hi) {
        int mid = lo + (hi - lo) / 2;
        float v = m->objects[mid].id;
        if (v == id) return &m->objects[mid];
        if (v < id) lo = mid + 1;
        else hi = mid - 1;
    }
    return NULL;
}

/* sbl__cam_map_apply for a pixel with object id `id`: a listed (moving) object is carried
   back by prev_object_to_world * inverse(object_to_world) in world space; anything else
   is static. */
static int sbl__cam_map_apply_id(const sbl__cam_map *m, float id, double px, double py, float z,
                                 double *ox, double *oy, double *oz)
{
    const sbl_object_motion *o;
    double p[4], w[4], q[4], v[4];
    if (!m->object_count || !(o = sbl__find_object(m, id)))
        return sbl__cam_map_apply(m, px, py, z, ox, oy, oz);
    if (!sbl__cam_map_point(m, px, py, z, p)) return 0;
    sbl__mat_apply(w, m->view_to_world, p);
    if (!sbl__mat_solve(o->object_to_world, w, q)) return 0;
    {
        double prev[16];
        sbl__mat_from_float(prev, o->prev_object_to_world);
        sbl__mat_apply(w, prev, q);
    }
    sbl__mat_apply(v, m->world_to_other, w);
    return sbl__cam_map_project(m, v, ox, oy, oz);
}

/* Objects of a frame: finite, invertible, sorted by distinct ids. */
static int sbl__objects_ok(const sbl_object_motion *o, int n)
{
    int i, k;
    if (n < 0 || (n > 0 && !o)) return 0;
    for (i = 0; i < n; ++i) {
        double t[4] = {0, 0, 0, 1}, q[4];
        if (!sbl__finite(o[i].id) || (i > 0 && !(o[i - 1].id < o[i].id))) return 0;
        for (k = 0; k < 16; ++k)
            if (!sbl__finite(o[i].object_to_world[k]) || !sbl__finite(o[i].prev_object_to_world[k]))
                return 0;
        if (!sbl__mat_solve(o[i].object_to_world, t, q)) return 0;
    }
    return 1;
}

/* ------------------------------------------------------------------------ */
/* 3. Reprojection                                                          */
/* ------------------------------------------------------------------------ */

/* A view reduced to what addressing needs, so that the inner loops do not reload
   the descriptor (data, stride, channels) for every tap. p == NULL: absent. */
typedef struct sbl__flat {
    const float *p;
    ptrdiff_t stride; /* floats from one row to the next (may be negative: bottom-up) */
    ptrdiff_t step;   /* floats from one pixel to the next (>= channels)               */
    int ch;           /* channels                                                      */
} sbl__flat;

static sbl__flat sbl__flatten(const sbl_image *im)
{
    sbl__flat f;
    f.p = im ? im->data : NULL;
    f.stride = f.p ? sbl__stride(im) : 0;
    f.step = f.p ? SBL__CAST(ptrdiff_t, sbl__step_of(im)) : 0;
    f.ch = f.p ? im->channels : 0;
    return f;
}

/* Every address of a flattened view is formed here (signed: strides may be negative). */
#define SBL__AT(f, x, y) \
    ((f).p + SBL__CAST(ptrdiff_t, y) * (f).stride + SBL__CAST(ptrdiff_t, x) * (f).step)

/* The source view a gather reads, and the tests it applies: fixed for a call. A test
   runs only when both views have its buffer. */
typedef struct sbl__tap_src {
    sbl__flat color, length, depth, normals, ids;
    int width, height;
    int use_depth, use_normal, use_id;
    float depth_tolerance;
    float normal_threshold2;     /* threshold^2 (threshold >= 0 when used)      */
    int cubic;                   /* 1: sbl__gather resamples with Catmull-Rom (temporal
                                    history, SBL_HISTORY_CATMULL_ROM); 0: bilinear   */
} sbl__tap_src;

/* What the target pixel expects to find. */
typedef struct sbl__tap_want {
    float depth;        /* expected planar depth in the source view           */
    float depth_slack;  /* absolute slack from the target's depth slope       */
    const float *normal;
    float normal_len2;
    float id;
} sbl__tap_want;

static int sbl__depth_match(float expected, float tap, float tol, float slack)
{
    int inf_e = sbl__is_pos_inf(expected), inf_t = sbl__is_pos_inf(tap);
    if (inf_e || inf_t) return inf_e && inf_t; /* sky matches only sky */
    if (!sbl__finite(tap) || !(tap > 0.0f)) return 0;
    return fabsf(tap - expected) <= tol * expected + slack;
}

/* Forced inlining keeps the lane code in registers when optimising; without optimisation
   (debug and sanitizer builds) it only multiplies the compile time (about 15x for the row
   gather's written-out taps under -O0 -fsanitize), so there the compiler decides. */
#if (defined(__GNUC__) || defined(__clang__)) && defined(__OPTIMIZE__)
#define SBL__INLINE static __inline__ __attribute__((always_inline))
#elif defined(__GNUC__) || defined(__clang__)
#define SBL__INLINE static __inline__
#elif defined(_MSC_VER)
#define SBL__INLINE static __forceinline
#else
#define SBL__INLINE static
#endif
/* a function kept on its own: each instance of a large kernel compiled by itself (in one
   function with its siblings, the register allocation of one depends on the others) */
#if defined(__GNUC__) || defined(__clang__)
#define SBL__NOINLINE static __attribute__((noinline))
#elif defined(_MSC_VER)
#define SBL__NOINLINE static __declspec(noinline)
#else
#define SBL__NOINLINE static
#endif

/* Every per-tap test on source pixel (x, y), which must be inside the image. With
   check_values 0 the colour and N finiteness is left to the caller (the optimistic
   path of sbl__gather_ch checks the sums instead and redoes the taps if a NaN or
   inf got in). */
/* The id and normal tests of source pixel (x, y) (inside the image). */
SBL__INLINE int sbl__tap_ok_id_normal(const sbl__tap_src *s, const sbl__tap_want *t, int x,
                                      int y)
{
    if (s->use_id) {
        float id = *SBL__AT(s->ids, x, y);
        if (sbl__is_nan(id) || sbl__is_nan(t->id) || id != t->id) return 0;
    }
    if (s->use_normal) {
        const float *n = SBL__AT(s->normals, x, y), *m = t->normal;
        float dot = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
        float nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (!sbl__finite(dot) || !sbl__finite(nn)) return 0;
        if (nn < 1e-12f || t->normal_len2 < 1e-12f) {
            /* "no normal" (background) only matches itself */
            if (!(nn < 1e-12f && t->normal_len2 < 1e-12f)) return 0;
        } else if (dot < 0.0f || dot * dot < s->normal_threshold2 * nn * t->normal_len2) {
            return 0; /* dot < threshold |n| |m| without a square root */
        }
    }
    return 1;
}

SBL__INLINE int sbl__tap_ok_in(const sbl__tap_src *s, const sbl__tap_want *t, int x, int y,
                               int ch, int check_values)
{
    if (s->use_depth &&
        !sbl__depth_match(t->depth, *SBL__AT(s->depth, x, y), s->depth_tolerance,
                          t->depth_slack))
        return 0;
    if (!sbl__tap_ok_id_normal(s, t, x, y)) return 0;
    if (check_values && sbl__any_nonfinite(SBL__AT(s->color, x, y), ch)) return 0;
    if (s->length.p) {
        float n = *SBL__AT(s->length, x, y);
        if (!(n > 0.0f) || (check_values && !sbl__finite(n))) return 0;
    }
    return 1;
}

/* +-inf -> +-FLT_MAX, on the bits (a "v > FLT_MAX" test is folded away by clang
   -ffast-math, which assumes there are no infinities) */
static float sbl__sat(float v)
{
    unsigned int bits;
    memcpy(&bits, &v, sizeof bits);
    if ((bits & 0x7fffffffu) == 0x7f800000u) return (bits >> 31) ? -FLT_MAX : FLT_MAX;
    return v;
}

SBL__INLINE int sbl__tap_ok(const sbl__tap_src *s, const sbl__tap_want *t, int x, int y,
                            int ch)
{
    if (x < 0 || y < 0 || x >= s->width || y >= s->height) return 0;
    return sbl__tap_ok_in(s, t, x, y, ch, 1);
}

SBL__INLINE void sbl__tap_add(const sbl__tap_src *s, int x, int y, float w, float *acc,
                              float *acc_n, int ch)
{
    const float *c = SBL__AT(s->color, x, y);
    /* written out: `ch` is a constant where this is inlined, so the unused lines go */
    acc[0] += w * c[0];
    if (ch > 1) acc[1] += w * c[1];
    if (ch > 2) acc[2] += w * c[2];
    if (ch > 3) acc[3] += w * c[3];
    *acc_n += w * (s->length.p ? *SBL__AT(s->length, x, y) : 1.0f);
}

/* The four taps of a bilinear footprint wholly inside the source image (the common
   case), with the buffers' addresses and the test parameters held in locals: depth and
   N tests written out, normals and ids through sbl__tap_ok_in. Optimistic about
   values: the caller checks the sums for NaN / inf and redoes the taps if needed.
   Returns the summed weight of the taps that passed. */
SBL__INLINE float sbl__gather_fast(const sbl__tap_src *s, const sbl__tap_want *t, int x0,
                                   int y0, float fx, float fy, float *acc, float *acc_n, int ch)
{
    const float gx = 1.0f - fx, gy = 1.0f - fy;
    float w[4];
    int ok[4] = {1, 1, 1, 1}, k;
    const ptrdiff_t cs = s->color.stride, cx = s->color.step;
    const float *c0 = SBL__AT(s->color, x0, y0);
    const float *cp[4];
    float wsum = 0.0f;
    w[0] = gx * gy; w[1] = fx * gy; w[2] = gx * fy; w[3] = fx * fy;
    cp[0] = c0; cp[1] = c0 + cx; cp[2] = c0 + cs; cp[3] = c0 + cs + cx;
    if (s->use_depth) {
        const ptrdiff_t ds = s->depth.stride, dx = s->depth.step;
        const float *d0 = SBL__AT(s->depth, x0, y0);
        float d[4];
        d[0] = d0[0]; d[1] = d0[dx]; d[2] = d0[ds]; d[3] = d0[ds + dx];
        for (k = 0; k < 4; ++k)
            ok[k] = sbl__depth_match(t->depth, d[k], s->depth_tolerance, t->depth_slack);
    }
    if (s->use_id || s->use_normal)
        for (k = 0; k < 4; ++k)
            if (ok[k]) ok[k] = sbl__tap_ok_id_normal(s, t, x0 + (k & 1), y0 + (k >> 1));
    if (s->length.p) {
        const ptrdiff_t ls = s->length.stride, lx = s->length.step;
        const float *l0 = SBL__AT(s->length, x0, y0);
        float n[4];
        n[0] = l0[0]; n[1] = l0[lx]; n[2] = l0[ls]; n[3] = l0[ls + lx];
        for (k = 0; k < 4; ++k) {
            ok[k] = ok[k] && n[k] > 0.0f && w[k] > 0.0f;
            if (ok[k]) *acc_n += w[k] * n[k];
        }
    } else {
        for (k = 0; k < 4; ++k) {
            ok[k] = ok[k] && w[k] > 0.0f;
            if (ok[k]) *acc_n += w[k];
        }
    }
    for (k = 0; k < 4; ++k) {
        if (!ok[k]) continue;
        acc[0] += w[k] * cp[k][0];
        if (ch > 1) acc[1] += w[k] * cp[k][1];
        if (ch > 2) acc[2] += w[k] * cp[k][2];
        if (ch > 3) acc[3] += w[k] * cp[k][3];
        wsum += w[k];
    }
    return wsum;
}

/* The 3x3 fallback of sbl__gather_ch (every footprint tap rejected, or weights summing
   below 1e-3): the consistent pixels of the 3x3 window around the nearest pixel of
   (sx, sy), averaged; returns their mean N (0: none). The row gather calls it directly
   for lanes whose taps it has already summed. */
SBL__INLINE float sbl__gather_fallback_ch(const sbl__tap_src *s, const sbl__tap_want *t, double sx,
                                          double sy, float *out, int ch)
{
    /* thin geometry: the surface may survive only in a neighbour of the nearest pixel;
       average the consistent ones, summed in double: up to nine finite values near
       FLT_MAX (colour or N) must not overflow before the division */
    int i, j, k;
    int cx = SBL__CAST(int, floor(sx)), cy = SBL__CAST(int, floor(sy)), cnt = 0;
    double dacc[4] = {0, 0, 0, 0}, dn = 0.0;
    if (cx >= 1 && cy >= 1 && cx + 1 < s->width && cy + 1 < s->height && !s->use_id &&
        !s->use_normal) {
        /* the window inside the image, no id or normal test (the common case of a
           disocclusion): sbl__tap_ok's tests written out, the depth test's limit
           formed once (the same float expression) */
        const int inf_e = sbl__is_pos_inf(t->depth);
        const float lim = s->depth_tolerance * t->depth + t->depth_slack;
        for (j = -1; j <= 1; ++j)
            for (i = -1; i <= 1; ++i) {
                const float *c = SBL__AT(s->color, cx + i, cy + j);
                float n = 1.0f;
                if (s->use_depth) { /* sbl__depth_match */
                    const float d = *SBL__AT(s->depth, cx + i, cy + j);
                    const int inf_t = sbl__is_pos_inf(d);
                    if (inf_e || inf_t) {
                        if (!(inf_e && inf_t)) continue;
                    } else if (!sbl__finite(d) || !(d > 0.0f) || !(fabsf(d - t->depth) <= lim)) {
                        continue;
                    }
                }
                if (sbl__any_nonfinite(c, ch)) continue;
                if (s->length.p) {
                    n = *SBL__AT(s->length, cx + i, cy + j);
                    if (!(n > 0.0f) || !sbl__finite(n)) continue;
                }
                dacc[0] += SBL__CAST(double, c[0]);
                if (ch > 1) dacc[1] += SBL__CAST(double, c[1]);
                if (ch > 2) dacc[2] += SBL__CAST(double, c[2]);
                if (ch > 3) dacc[3] += SBL__CAST(double, c[3]);
                dn += SBL__CAST(double, n); /* 1.0 without N */
                ++cnt;
            }
    } else {
        for (j = -1; j <= 1; ++j)
            for (i = -1; i <= 1; ++i)
                if (sbl__tap_ok(s, t, cx + i, cy + j, ch)) {
                    const float *c = SBL__AT(s->color, cx + i, cy + j);
                    for (k = 0; k < ch; ++k) dacc[k] += SBL__CAST(double, c[k]);
                    dn += s->length.p ? SBL__CAST(double, *SBL__AT(s->length, cx + i, cy + j)) : 1.0;
                    ++cnt;
                }
    }
    if (!cnt) return 0.0f;
    for (k = 0; k < ch; ++k) out[k] = SBL__CAST(float, dacc[k] / cnt);
    dn /= cnt;
    return dn > 0.0 ? SBL__CAST(float, dn) : 0.0f;
}

/* Bilinear 2x2 gather at continuous position (sx, sy) with per-tap tests, valid taps
   renormalised; then the 3x3 fallback; returns N of the result (0: nothing valid).
   `ch` is a constant at each call site below, so the accumulators stay in registers. */
SBL__INLINE float sbl__gather_ch(const sbl__tap_src *s, const sbl__tap_want *t, double sx,
                                 double sy, int fallback, float *out, int ch)
{
    float acc[4] = {0, 0, 0, 0}, acc_n = 0.0f, wsum = 0.0f, fx, fy, inv;
    int k, x0, y0, i, j, fast;
    double bx = sx - 0.5, by = sy - 0.5;
    /* far outside (or NaN): no tap can pass; also keeps the int conversion defined */
    if (!(bx > -2.0 && by > -2.0 && bx < SBL__CAST(double, s->width) + 1.0 &&
          by < SBL__CAST(double, s->height) + 1.0))
        return 0.0f;
    x0 = SBL__CAST(int, floor(bx));
    y0 = SBL__CAST(int, floor(by));
    fx = SBL__CAST(float, bx - x0);
    fy = SBL__CAST(float, by - y0);
    fast = x0 >= 0 && y0 >= 0 && x0 + 1 < s->width && y0 + 1 < s->height;
    if (fast) {
        /* all four taps inside (the common case): no bounds tests, and the values'
           finiteness checked once on the sums */
        wsum = sbl__gather_fast(s, t, x0, y0, fx, fy, acc, &acc_n, ch);
        if (sbl__any_nonfinite(acc, ch) || !sbl__finite(acc_n)) {
            for (k = 0; k < 4; ++k) acc[k] = 0.0f;
            acc_n = 0.0f;
            wsum = 0.0f;
            fast = 0; /* a NaN or inf got in: redo with every check */
        }
    }
    if (!fast) {
        for (j = 0; j < 2; ++j)
            for (i = 0; i < 2; ++i) {
                float w = (i ? fx : 1.0f - fx) * (j ? fy : 1.0f - fy);
                if (w <= 0.0f || !sbl__tap_ok(s, t, x0 + i, y0 + j, ch)) continue;
                sbl__tap_add(s, x0 + i, y0 + j, w, acc, &acc_n, ch);
                wsum += w;
            }
    }
    if (wsum < 1e-3f && fallback) return sbl__gather_fallback_ch(s, t, sx, sy, out, ch);
    if (wsum < 1e-3f) return 0.0f;
    inv = 1.0f / wsum;
    /* the weights sum to 1 within rounding, so a mean of values at +-FLT_MAX can round
       past it: saturate (a weighted mean of finite values is finite) */
    for (k = 0; k < ch; ++k) out[k] = sbl__sat(acc[k] * inv);
    acc_n = sbl__sat(acc_n * inv);
    return acc_n > 0.0f ? acc_n : 0.0f;
}

/* Catmull-Rom weights of the four taps at offsets -1, 0, 1, 2 from the tap left of a
   position t in [0, 1) (docs/ESTIMATORS.md section 5): the cubic through four samples
   whose slopes at the inner two are the central differences. They sum to 1, give
   (0, 1, 0, 0) at t = 0 and reproduce polynomials up to degree 2. */
static void sbl__catmull_rom(double t, double *w)
{
    const double t2 = t * t, t3 = t2 * t;
    w[0] = 0.5 * (-t3 + 2.0 * t2 - t);
    w[1] = 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0);
    w[2] = 0.5 * (-3.0 * t3 + 4.0 * t2 + t);
    w[3] = 0.5 * (t3 - t2);
}

/* The history at (sx, sy) by Catmull-Rom: the bilinear gather first (its N is the one
   returned, and its colour the answer wherever the cubic cannot be used); then, if every
   tap the cubic needs (4 per axis, 1 on an axis whose fraction is 0) is inside the image
   and passes every per-tap test, the 4x4 sum in double (rows first: the weights are
   separable), clamped per channel to the range of the inner taps (the bilinear
   footprint): the negative lobes cannot ring past the values they interpolate, so a
   non-negative history stays non-negative, and the result is finite. */
SBL__INLINE float sbl__gather_cubic_ch(const sbl__tap_src *s, const sbl__tap_want *t,
                                       double sx, double sy, int fallback, float *out, int ch)
{
    double wx[4], wy[4], acc[4] = {0, 0, 0, 0}, bx, by, fx, fy;
    float lo[4] = {0, 0, 0, 0}, hi[4] = {0, 0, 0, 0};
    int x0, y0, ix, iy, nx, ny, i, j, k;
    const float n = sbl__gather_ch(s, t, sx, sy, fallback, out, ch);
    if (!(n > 0.0f)) return n; /* nothing valid: the pixel resets */
    bx = sx - 0.5;
    by = sy - 0.5; /* finite and within the image's reach: the bilinear gather found taps */
    x0 = SBL__CAST(int, floor(bx));
    y0 = SBL__CAST(int, floor(by));
    fx = bx - x0;
    fy = by - y0;
    /* an axis at an integer position needs its centre tap only (the weights are exactly
       0, 1, 0, 0): the cubic is then exact there, as the bilinear is */
    nx = fx > 0.0 ? 4 : 1;
    ny = fy > 0.0 ? 4 : 1;
    if (nx == 1 && ny == 1) return n;
    ix = nx == 4 ? x0 - 1 : x0;
    iy = ny == 4 ? y0 - 1 : y0;
    if (ix < 0 || iy < 0 || ix + nx > s->width || iy + ny > s->height) return n;
    if (nx == 4) sbl__catmull_rom(fx, wx); else wx[0] = 1.0;
    if (ny == 4) sbl__catmull_rom(fy, wy); else wy[0] = 1.0;
    for (j = 0; j < ny; ++j) {
        double row[4] = {0, 0, 0, 0};
        for (i = 0; i < nx; ++i) {
            /* sbl__tap_ok_in's tests but the colour's finiteness, which is checked once
               on the sums below (a NaN or inf tap makes them non-finite) */
            const int x = ix + i, y = iy + j;
            const float *c = SBL__AT(s->color, x, y);
            if (s->use_depth && !sbl__depth_match(t->depth, *SBL__AT(s->depth, x, y),
                                                  s->depth_tolerance, t->depth_slack))
                return n;
            if ((s->use_id || s->use_normal) && !sbl__tap_ok_id_normal(s, t, x, y)) return n;
            if (s->length.p) {
                const float l = *SBL__AT(s->length, x, y);
                if (!(l > 0.0f) || !sbl__finite(l)) return n;
            }
            row[0] += wx[i] * SBL__CAST(double, c[0]);
            if (ch > 1) row[1] += wx[i] * SBL__CAST(double, c[1]);
            if (ch > 2) row[2] += wx[i] * SBL__CAST(double, c[2]);
            if (ch > 3) row[3] += wx[i] * SBL__CAST(double, c[3]);
        }
        for (k = 0; k < ch; ++k) acc[k] += wy[j] * row[k];
    }
    /* finite taps cannot overflow these sums (sum |w| < 1.2 per axis, in double) */
    for (k = 0; k < ch; ++k)
        if (!(acc[k] - acc[k] == 0.0)) return n; /* a non-finite tap: bilinear */
    /* the range of the inner taps (rows and columns 1, 2; the only one of an axis at an
       integer position) */
    x0 = nx == 4 ? ix + 1 : ix;
    y0 = ny == 4 ? iy + 1 : iy;
    for (k = 0; k < ch; ++k) lo[k] = hi[k] = SBL__AT(s->color, x0, y0)[k];
    for (j = 0; j < (ny == 4 ? 2 : 1); ++j)
        for (i = 0; i < (nx == 4 ? 2 : 1); ++i) {
            const float *c = SBL__AT(s->color, x0 + i, y0 + j);
            for (k = 0; k < ch; ++k) {
                if (c[k] < lo[k]) lo[k] = c[k];
                if (c[k] > hi[k]) hi[k] = c[k];
            }
        }
    for (k = 0; k < ch; ++k) {
        const double v = acc[k] < SBL__CAST(double, lo[k])   ? SBL__CAST(double, lo[k])
                         : acc[k] > SBL__CAST(double, hi[k]) ? SBL__CAST(double, hi[k])
                                                             : acc[k];
        out[k] = SBL__CAST(float, v);
    }
    return n;
}

static float sbl__gather(const sbl__tap_src *s, const sbl__tap_want *t, double sx, double sy,
                         int fallback, float *out)
{
    if (s->cubic) {
        switch (s->color.ch) {
        case 1: return sbl__gather_cubic_ch(s, t, sx, sy, fallback, out, 1);
        case 2: return sbl__gather_cubic_ch(s, t, sx, sy, fallback, out, 2);
        case 3: return sbl__gather_cubic_ch(s, t, sx, sy, fallback, out, 3);
        default: return sbl__gather_cubic_ch(s, t, sx, sy, fallback, out, 4);
        }
    }
    switch (s->color.ch) {
    case 1: return sbl__gather_ch(s, t, sx, sy, fallback, out, 1);
    case 2: return sbl__gather_ch(s, t, sx, sy, fallback, out, 2);
    case 3: return sbl__gather_ch(s, t, sx, sy, fallback, out, 3);
    default: return sbl__gather_ch(s, t, sx, sy, fallback, out, 4);
    }
}

/* The target side of the tests, flattened once per call. */
typedef struct sbl__target_geo {
    sbl__flat depth, normals, ids;
    int width, height;
} sbl__target_geo;

static sbl__target_geo sbl__target_geo_make(const sbl_gbuffer *g, int w, int h)
{
    sbl__target_geo t;
    t.depth = sbl__flatten(&g->depth);
    t.normals = sbl__flatten(&g->normals);
    t.ids = sbl__flatten(&g->ids);
    t.width = w;
    t.height = h;
    return t;
}

/* One axis of the slack from its one-sided differences da, db (fabsf results: >= 0 or
   NaN, sign bit clear): the value of `da < db ? da : db` where finite, else 0 (a NaN db
   gives 0, a NaN da gives db's answer). On the bits, where unsigned order is the order
   of such floats with NaN above +inf: under -ffast-math the compiler may turn the float
   comparison into a min whose NaN result depends on its operand order (sbl__lanes_want
   has the same rule in lanes). */
static float sbl__slack_axis(float da, float db)
{
    unsigned int a, b, m;
    float d;
    memcpy(&a, &da, sizeof a);
    memcpy(&b, &db, sizeof b);
    m = a < b ? a : b; /* a NaN da (above every non-NaN b) yields b */
    if (m >= 0x7f800000u || b > 0x7f800000u) return 0.0f;
    memcpy(&d, &m, sizeof d);
    return d;
}

/* Slack for the depth test from the target's own depth slope (one-sided minimum so a
   silhouette next to the pixel does not open the tolerance). */
static float sbl__depth_slack(const sbl__target_geo *g, int x, int y, float z)
{
    const float *p = SBL__AT(g->depth, x, y);
    float sx = 0.0f, sy = 0.0f;
    int w = g->width, h = g->height;
    if (!sbl__finite(z)) return 0.0f;
    if (w > 1) {
        float a = x > 0 ? p[-g->depth.step] : z;
        float b = x + 1 < w ? p[g->depth.step] : z;
        float da = fabsf(z - a), db = fabsf(b - z);
        if (x == 0) da = db;
        if (x + 1 == w) db = da;
        sx = sbl__slack_axis(da, db);
    }
    if (h > 1) {
        float a = y > 0 ? *(p - g->depth.stride) : z;
        float b = y + 1 < h ? *(p + g->depth.stride) : z;
        float da = fabsf(z - a), db = fabsf(b - z);
        if (y == 0) da = db;
        if (y + 1 == h) db = da;
        sy = sbl__slack_axis(da, db);
    }
    return sx + sy;
}

/* The target pixel's expectations (depth, slack, normal, id) from its G-buffer.
   Returns 0 if its depth is not valid geometry. */
static int sbl__tap_want_init(sbl__tap_want *t, const sbl__target_geo *g, int x, int y,
                              float *z_out)
{
    float z = 0.0f;
    if (g->depth.p) {
        z = *SBL__AT(g->depth, x, y);
        if (!sbl__depth_is_geometry(z)) return 0;
        t->depth_slack = sbl__depth_slack(g, x, y, z);
    } else {
        t->depth_slack = 0.0f;
    }
    t->depth = z;
    t->id = g->ids.p ? *SBL__AT(g->ids, x, y) : 0.0f;
    t->normal = g->normals.p ? SBL__AT(g->normals, x, y) : NULL;
    t->normal_len2 = t->normal ? t->normal[0] * t->normal[0] + t->normal[1] * t->normal[1] +
                                     t->normal[2] * t->normal[2]
                               : 0.0f;
    if (t->normal && !sbl__finite(t->normal_len2)) return 0;
    *z_out = z;
    return 1;
}

static void sbl__tap_src_init(sbl__tap_src *s, const sbl_image *color, const sbl_image *length,
                              const sbl_gbuffer *src_g, const sbl_gbuffer *dst_g,
                              const sbl_reproject_desc *rp)
{
    s->color = sbl__flatten(color);
    s->length = sbl__flatten(length);
    s->depth = sbl__flatten(&src_g->depth);
    s->normals = sbl__flatten(&src_g->normals);
    s->ids = sbl__flatten(&src_g->ids);
    s->width = color->width;
    s->height = color->height;
    s->use_depth = src_g->depth.data && dst_g->depth.data &&
                   !(rp->disabled_tests & SBL_TEST_DEPTH);
    s->use_id = src_g->ids.data && dst_g->ids.data && !(rp->disabled_tests & SBL_TEST_ID);
    s->use_normal = src_g->normals.data && dst_g->normals.data &&
                    !(rp->normal_threshold < 0.0f) && !(rp->disabled_tests & SBL_TEST_NORMAL);
    s->depth_tolerance = rp->depth_tolerance;
    s->normal_threshold2 = rp->normal_threshold * rp->normal_threshold;
    s->cubic = 0; /* the temporal call switches it on (sbl__temporal_rp_init) */
}

/* Motion vector convention -> factors that turn a vector into the backward
   displacement in pixels, y down: dx = kx * mv.x, dy = ky * mv.y. */
static void sbl__motion_scale(const sbl_motion_convention *c, int w, int h, double *kx,
                              double *ky)
{
    double x = 1.0, y = 1.0;
    if (c->units == SBL_MOTION_UV) { x = w; y = h; }
    else if (c->units == SBL_MOTION_NDC) { x = 0.5 * w; y = 0.5 * h; }
    if (c->y_up) y = -y;
    if (c->forward) { x = -x; y = -y; }
    *kx = x;
    *ky = y;
}

static sbl_reproject_desc sbl__reproject_defaults(const sbl_reproject_desc *d)
{
    sbl_reproject_desc r = *d;
    if (r.disabled_tests & SBL_TEST_FALLBACK) r.no_fallback = 1;
    if (sbl__is_zero(r.depth_tolerance)) r.depth_tolerance = 0.05f;
    if (sbl__is_zero(r.normal_threshold)) r.normal_threshold = 0.9f;
    if (sbl__is_zero(r.back_check_pixels)) r.back_check_pixels = 1.0f;
    return r;
}

static sbl_result sbl__check_reproject_desc(const sbl_reproject_desc *d)
{
    if (!sbl__param_ok(d->depth_tolerance) || !sbl__param_ok(d->back_check_pixels))
        return SBL_ERROR_INVALID_PARAM;
    if (!sbl__finite(d->normal_threshold) || d->normal_threshold > 1.0f)
        return SBL_ERROR_INVALID_PARAM;
    if (SBL__CAST(int, d->motion.units) < 0 || SBL__CAST(int, d->motion.units) > SBL__CAST(int, SBL_MOTION_NDC))
        return SBL_ERROR_INVALID_PARAM;
    if (d->disabled_tests & ~SBL__CAST(int, SBL_TEST_ALL)) return SBL_ERROR_INVALID_PARAM;
    if (SBL__CAST(int, d->history_filter) < 0 ||
        SBL__CAST(int, d->history_filter) > SBL__CAST(int, SBL_HISTORY_CATMULL_ROM))
        return SBL_ERROR_INVALID_PARAM;
    return SBL_OK;
}

/* Temporal reprojection state shared by the stage call and the fused filter. */
typedef struct sbl__temporal_rp {
    sbl_reproject_desc rp;
    sbl_temporal_source source;
    const sbl_frame *frame;
    const sbl_history *history; /* NULL or no colour: everything resets */
    sbl__tap_src src;
    sbl__target_geo geo;
    sbl__flat motion;
    double motion_kx, motion_ky; /* see sbl__motion_scale */
    sbl__cam_map cam;
    /* camera source: the frame's and the history's cameras are equal, so every pixel
       that is not on a moving object maps to itself (sbl__temporal_rp_pos) */
    int at_rest;
    int moving_count;            /* listed objects whose two matrices differ          */
    float moving_lo, moving_hi;  /* the range of their ids                            */
    int tiles;                   /* 1: the row gather's tile shortcuts (tests: 0)     */
} sbl__temporal_rp;

/* Does an object's pose differ between the two frames? */
static int sbl__object_moves(const sbl_object_motion *o)
{
    int i;
    for (i = 0; i < 16; ++i)
        if (o->object_to_world[i] != o->prev_object_to_world[i]) return 1;
    return 0;
}

/* Is a pixel with this id on a moving object (camera source)? */
static int sbl__on_moving_object(const sbl__temporal_rp *s, float id)
{
    const sbl_object_motion *o;
    if (!s->moving_count || !(id >= s->moving_lo && id <= s->moving_hi)) return 0;
    o = sbl__find_object(&s->cam, id);
    return o && sbl__object_moves(o);
}

static sbl_result sbl__temporal_rp_init(sbl__temporal_rp *s, const sbl_reproject_desc *desc,
                                        sbl_temporal_source source, const sbl_frame *frame,
                                        const sbl_history *history)
{
    const sbl_gbuffer *g = &frame->gbuffer;
    sbl_result r;
    int w = frame->color.width, h = frame->color.height;
    if ((r = sbl__check_reproject_desc(desc)) != SBL_OK) return r;
    if (SBL__CAST(int, source) < 0 || SBL__CAST(int, source) > SBL__CAST(int, SBL_TEMPORAL_CAMERA)) return SBL_ERROR_INVALID_PARAM;
    if ((r = sbl__check_gbuffer(g, w, h)) != SBL_OK) return r;
    s->rp = sbl__reproject_defaults(desc);
    s->source = source;
    s->frame = frame;
    s->at_rest = 0;
    s->moving_count = 0;
    s->moving_lo = s->moving_hi = 0.0f;
    s->tiles = 1;
    sbl__motion_scale(&s->rp.motion, w, h, &s->motion_kx, &s->motion_ky);
    s->geo = sbl__target_geo_make(g, w, h);
    s->motion = sbl__flatten(&g->motion);
    s->history = (history && history->color.data) ? history : NULL;
    if (s->history) {
        const sbl_history *hi = s->history;
        if ((r = sbl__check_image(&hi->color, 0)) != SBL_OK) return r;
        if (hi->color.width != w || hi->color.height != h) return SBL_ERROR_SIZE_MISMATCH;
        if (hi->color.channels != frame->color.channels) return SBL_ERROR_CHANNEL_MISMATCH;
        if ((r = sbl__check_optional(&hi->length, 1, w, h)) != SBL_OK) return r;
        if ((r = sbl__check_gbuffer(&hi->gbuffer, w, h)) != SBL_OK) return r;
        sbl__tap_src_init(&s->src, &hi->color, &hi->length, &hi->gbuffer, g, &s->rp);
        s->src.cubic = s->rp.history_filter == SBL_HISTORY_CATMULL_ROM;
    }
    if (source == SBL_TEMPORAL_MOTION && !g->motion.data) return SBL_ERROR_MISSING_INPUT;
    if (source == SBL_TEMPORAL_CAMERA) {
        if (!g->depth.data || !frame->camera) return SBL_ERROR_MISSING_INPUT;
        if (frame->object_count && !g->ids.data) return SBL_ERROR_MISSING_INPUT;
        if (!sbl__objects_ok(frame->objects, frame->object_count)) return SBL_ERROR_INVALID_PARAM;
        if (s->history) {
            if (!s->history->camera) return SBL_ERROR_MISSING_INPUT;
            if (!sbl__cam_map_init(&s->cam, frame->camera, w, h, s->history->camera, w, h))
                return SBL_ERROR_INVALID_PARAM;
            s->cam.objects = frame->objects;
            s->cam.object_count = frame->object_count;
            {   /* a camera at rest: the two cameras' values equal (the matrix chain of
                   sbl__cam_map_apply would give the identity only within rounding) */
                const sbl_camera *a = frame->camera, *b = s->history->camera;
                int i;
                s->at_rest = 1;
                for (i = 0; i < 16; ++i)
                    if (a->world_to_view[i] != b->world_to_view[i] ||
                        a->view_to_clip[i] != b->view_to_clip[i])
                        s->at_rest = 0;
                for (i = 0; i < frame->object_count; ++i) {
                    const sbl_object_motion *o = &frame->objects[i];
                    if (!sbl__object_moves(o)) continue;
                    if (!s->moving_count || o->id < s->moving_lo) s->moving_lo = o->id;
                    if (!s->moving_count || o->id > s->moving_hi) s->moving_hi = o->id;
                    ++s->moving_count;
                }
            }
        }
    }
    return SBL_OK;
}

/* Where target pixel (x, y) finds its history: the source position (*sx, *sy) and what
   the taps must match (*t). Returns 0 when the pixel must reset. Shared by the pixel
   gather below and the row gather (sbl__temporal_rp_row). */
SBL__INLINE int sbl__temporal_rp_pos(const sbl__temporal_rp *s, int x, int y, sbl__tap_want *t,
                                     double *sx, double *sy)
{
    double sz;
    float z;
    if (!sbl__tap_want_init(t, &s->geo, x, y, &z)) return 0;
    if (s->source == SBL_TEMPORAL_MOTION) {
        const float *mv = SBL__AT(s->motion, x, y);
        if (sbl__any_nonfinite(mv, 2)) return 0;
        *sx = x + 0.5 + s->motion_kx * SBL__CAST(double, mv[0]);
        *sy = y + 0.5 + s->motion_ky * SBL__CAST(double, mv[1]);
        sz = SBL__CAST(double, z); /* motion vectors carry no depth change: relative tolerance covers it */
    } else {
        const float id = s->geo.ids.p ? *SBL__AT(s->geo.ids, x, y) : 0.0f;
        if (s->at_rest && !sbl__on_moving_object(s, id)) {
            /* camera at rest, static surface: the pixel itself, exactly */
            *sx = x + 0.5;
            *sy = y + 0.5;
            sz = SBL__CAST(double, z);
        } else if (!sbl__cam_map_apply_id(&s->cam, id, x + 0.5, y + 0.5, z, sx, sy, &sz)) {
            return 0;
        }
    }
    /* came in from outside the previous image: nothing to reuse (edge pixels would
       otherwise be replicated by the renormalisation and the 3x3 fallback) */
    if (!(*sx >= 0.0 && *sx < SBL__CAST(double, s->frame->color.width) && *sy >= 0.0 &&
          *sy < SBL__CAST(double, s->frame->color.height)))
        return 0;
    t->depth = SBL__CAST(float, sz);
    return 1;
}

/* x* and its N for target pixel (x, y); returns 0 when the pixel must reset. */
static float sbl__temporal_rp_pixel(const void *ctx, int x, int y, float *out)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    sbl__tap_want t;
    double sx, sy;
    if (!s->history) return 0.0f;
    if (!sbl__temporal_rp_pos(s, x, y, &t, &sx, &sy)) return 0.0f;
    return sbl__gather(&s->src, &t, sx, sy, !s->rp.no_fallback, out);
}

/* An output of a temporal call must not overlap a plane the call reads. The filter
   (all = 1) reads every plane of the frame and of the history; sbl_reproject_temporal
   (all = 0) reads neither the frame's colour nor the history's evidence plane (which it
   does not validate either): the frame's G-buffer and the history's other planes. */
static int sbl__overlaps_temporal_inputs(const sbl_image *o, const sbl_frame *frame,
                                         const sbl_history *history, int all)
{
    const sbl_image *p[SBL__PLANES_MAX];
    if (all) return sbl__overlap_frame(o, frame) || sbl__overlap_history(o, history);
    return sbl__overlap_gbuffer(o, &frame->gbuffer) ||
           sbl__overlap_any(o, p, sbl__history_planes(history, p, 0));
}

static sbl_result sbl__check_rows(int y0, int y1, int h)
{
    if (y0 < 0 || y1 < y0 || y1 > h) return SBL_ERROR_INVALID_ROWS;
    return SBL_OK;
}

/* The write of the per-pixel reprojection calls (sbl_reproject_temporal,
   sbl_reproject_stereo, sbl_stereo_fill): pixel (x, y) of out_color gets the reprojected
   colour v (ch channels), zeros where it has no correspondence (n, its history length or
   weight, not > 0). Returns whether it has one; each call writes its second output. */
SBL__INLINE int sbl__write_reprojected(const sbl_image *out_color, int x, int y, const float *v,
                                       float n, int ch)
{
    float *o = sbl__px(out_color, x, y);
    const int valid = n > 0.0f;
    int k;
    for (k = 0; k < ch; ++k) o[k] = valid ? v[k] : 0.0f;
    return valid;
}

SBLDEF sbl_result sbl_reproject_temporal(const sbl_reproject_desc *desc,
                                         sbl_temporal_source source,
                                         const sbl_frame *frame, const sbl_history *history,
                                         sbl_image out_color, sbl_image out_length,
                                         int y0, int y1)
{
    sbl__temporal_rp s;
    sbl_result r;
    int x, y, ch;
    if (!desc || !frame) return SBL_ERROR_NULL_POINTER;
    if ((r = sbl__check_image(&frame->color, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&out_color, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&out_length, 1)) != SBL_OK) return r;
    if (out_color.width != frame->color.width || out_color.height != frame->color.height ||
        out_length.width != frame->color.width || out_length.height != frame->color.height)
        return SBL_ERROR_SIZE_MISMATCH;
    if (out_color.channels != frame->color.channels) return SBL_ERROR_CHANNEL_MISMATCH;
    if ((r = sbl__temporal_rp_init(&s, desc, source, frame, history)) != SBL_OK) return r;
    if ((r = sbl__check_rows(y0, y1, frame->color.height)) != SBL_OK) return r;
    if (sbl__overlap(&out_color, &out_length) ||
        sbl__overlaps_temporal_inputs(&out_color, frame, s.history, 0) ||
        sbl__overlaps_temporal_inputs(&out_length, frame, s.history, 0))
        return SBL_ERROR_OVERLAP;
    ch = frame->color.channels;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < frame->color.width; ++x) {
            float v[4] = {0, 0, 0, 0};
            float n = sbl__temporal_rp_pixel(&s, x, y, v);
            sbl__write_reprojected(&out_color, x, y, v, n, ch);
            *sbl__px(&out_length, x, y) = n;
        }
    return SBL_OK;
}

/* ------------------------------------------------------------------------ */
/* 4. Moments                                                               */
/* ------------------------------------------------------------------------ */

/* Statistics of Y's 3x3 neighbourhood and of the paired differences x*_i - y_i. */
typedef struct sbl__moments {
    double mean[4], var[4];     /* population mean / variance of Y per channel      */
    float lo[4], hi[4];         /* min / max of Y per channel                       */
    double pair_diff[4];        /* mean of (x*_i - y_i) over pixels with both valid */
    double pair_var[4];         /* sample variance of (x*_i - y_i) (Bessel), 0 if < 2 */
    double mean8[4], var8[4];   /* mean / population variance of Y without the centre
                                   sample (firefly limit); 0 without a centre         */
    int count, pair_count;
    double pool_r;              /* pooled estimator: prior bias-to-noise ratio tau^2 / se^2
                                   from the blocks along the row (sbl__row_pool); 0 if none */
    double xdev2;               /* sum_c (x*_centre - mean of the neighbours' valid x*)^2:
                                   the history's texture at the pixel (the restart lean);
                                   -1 where undefined (no valid centre x*, or no valid
                                   neighbour x*) */
} sbl__moments;

/* vals[i][c]: the n finite neighbours (centre included, at index `centre`, or -1);
   xv[i] non-NULL where that neighbour also has a valid x*. Two passes in double: exact
   enough for any float input, never negative. */
static void sbl__moments_core(sbl__moments *m, const float (*vals)[4],
                              const float (*xvals)[4], const int *xvalid, int n, int ch,
                              int centre)
{
    /* one channel's values in double, and its valid pairs' x* - y, converted once; each
       sum is taken in the order of the samples: the same additions as one loop per sum */
    double yv[9], dv[9];
    int i, k, np = 0;
    m->count = n;
    m->pool_r = 0.0;
    if (xvalid)
        for (i = 0; i < n; ++i) np += xvalid[i] != 0;
    m->pair_count = np;
    m->xdev2 = -1.0;
    if (xvalid && centre >= 0 && xvalid[centre] && np >= 2) {
        m->xdev2 = 0.0;
        for (k = 0; k < ch; ++k) {
            double sx = 0.0, d;
            for (i = 0; i < n; ++i)
                if (i != centre && xvalid[i]) sx += SBL__CAST(double, xvals[i][k]);
            d = SBL__CAST(double, xvals[centre][k]) - sx / (np - 1);
            m->xdev2 += d * d;
        }
    }
    for (k = 0; k < ch; ++k) {
        /* first pass: the values in double, their sum, the sum without the centre (the
           window without its centre, centred on its own mean: a firefly at the centre
           cannot cancel the others' spread away), the pairs' differences and their sum */
        double s = 0.0, v = 0.0, pd = 0.0, s8 = 0.0, v8 = 0.0;
        float lo = 0.0f, hi = 0.0f;
        const int has8 = centre >= 0 && n >= 2;
        int j = 0;
        for (i = 0; i < n; ++i) {
            const double yi = SBL__CAST(double, vals[i][k]);
            yv[i] = yi;
            s += yi;
            if (i != centre) s8 += yi;
            if (xvalid && xvalid[i]) {
                const double di = SBL__CAST(double, xvals[i][k]) - yi;
                dv[j++] = di;
                pd += di;
            }
        }
        s = n ? s / n : 0.0;
        if (has8) s8 /= n - 1;
        /* second pass: the squares about the means, min / max */
        for (i = 0; i < n; ++i) {
            const double d = yv[i] - s;
            v += d * d;
            if (i != centre) v8 += (yv[i] - s8) * (yv[i] - s8);
            if (i == 0 || vals[i][k] < lo) lo = vals[i][k];
            if (i == 0 || vals[i][k] > hi) hi = vals[i][k];
        }
        m->mean8[k] = has8 ? s8 : 0.0;
        m->var8[k] = has8 ? v8 / (n - 1) : 0.0;
        m->mean[k] = s;
        m->var[k] = n ? v / n : 0.0;
        m->lo[k] = lo;
        m->hi[k] = hi;
        m->pair_diff[k] = np ? pd / np : 0.0;
        m->pair_var[k] = 0.0;
        if (np > 1) {
            double pv = 0.0;
            for (i = 0; i < np; ++i) {
                const double e = dv[i] - m->pair_diff[k];
                pv += e * e;
            }
            m->pair_var[k] = pv / (np - 1);
        }
    }
}

static int sbl__all_finite(const float *p, int ch)
{
    int k, ok = 1;
    for (k = 0; k < ch; ++k) ok &= sbl__finite(p[k]);
    return ok;
}

SBLDEF sbl_result sbl_moments_3x3(sbl_image src, sbl_image mean, sbl_image var, int y0,
                                  int y1)
{
    sbl_result r;
    int x, y, k, ch;
    if ((r = sbl__check_image(&src, 0)) != SBL_OK) return r;
    ch = src.channels;
    if (!mean.data && !var.data) return SBL_ERROR_NULL_POINTER;
    if ((r = sbl__check_optional(&mean, ch, src.width, src.height)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&var, ch, src.width, src.height)) != SBL_OK) return r;
    if ((r = sbl__check_rows(y0, y1, src.height)) != SBL_OK) return r;
    if (sbl__overlap(&mean, &src) || sbl__overlap(&var, &src) || sbl__overlap(&mean, &var))
        return SBL_ERROR_OVERLAP;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < src.width; ++x) {
            float vals[9][4];
            sbl__moments m;
            int n = 0, i, j;
            for (j = y - 1; j <= y + 1; ++j)
                for (i = x - 1; i <= x + 1; ++i) {
                    const float *p;
                    if (i < 0 || j < 0 || i >= src.width || j >= src.height) continue;
                    p = sbl__px(&src, i, j);
                    if (!sbl__all_finite(p, ch)) continue;
                    for (k = 0; k < ch; ++k) vals[n][k] = p[k];
                    ++n;
                }
            sbl__moments_core(&m, SBL__PCAST(const float(*)[4], vals), NULL, NULL, n, ch, -1);
            for (k = 0; k < ch; ++k) {
                if (mean.data) sbl__px(&mean, x, y)[k] = SBL__CAST(float, m.mean[k]);
                /* beyond float range (|values| > ~1e19): saturate, finite in -> finite out */
                if (var.data)
                    sbl__px(&var, x, y)[k] = m.var[k] > SBL__CAST(double, FLT_MAX) ? FLT_MAX : SBL__CAST(float, m.var[k]);
            }
        }
    return SBL_OK;
}

/* ------------------------------------------------------------------------ */
/* 5. Weights                                                               */
/* ------------------------------------------------------------------------ */

SBLDEF float sbl_optimal_weight(float bias2, float var_x, float var_y)
{
    double num = SBL__CAST(double, bias2) + SBL__CAST(double, var_x), den = num + SBL__CAST(double, var_y);
    if (sbl__is_pos_inf(var_x) || sbl__is_pos_inf(bias2)) return 1.0f;
    if (!(den > 0.0)) return 0.5f;
    return SBL__CAST(float, num / den);
}

SBLDEF float sbl_blend_sample_count(float a, float n_x, float n_y)
{
    double A = SBL__CAST(double, a), den = (1.0 - A) * (1.0 - A) * SBL__CAST(double, n_y) + A * A * SBL__CAST(double, n_x), n;
    if (!(den > 0.0)) n = SBL__CAST(double, n_x) + SBL__CAST(double, n_y); /* a blend of nothing: the sum */
    else n = SBL__CAST(double, n_x) * SBL__CAST(double, n_y) / den;
    return n > SBL__CAST(double, FLT_MAX) ? FLT_MAX : SBL__CAST(float, n); /* saturate: finite counts stay finite */
}

/* Resolved weight parameters shared by temporal and stereo. */
typedef struct sbl__weight_params {
    sbl_estimator estimator;
    sbl_rectify rectify;
    sbl_weight_mode mode;
    float constant, alpha_min, gamma, bias_threshold;
    int temporal; /* X is a history (its N is a time since the last change) */
    int stereo_ev; /* stereo, pooled: the kernel has the eyes' change flags (k->sev);
                      the lanes read them (sbl__lane_stats.sev) */
    int stereo_change; /* the reference path's pixel in hand: 1 where flagged */
    float shared_bias; /* temporal: sbl_temporal_desc.stereo_shared_bias c (the bias
                          counts 1 + c times); 0 otherwise */
    float region_m;    /* temporal, pooled, with the evidence plane: the factor M by which
                          the region's share of change raises the prior odds against a
                          change (sbl__evidence_share, set per row); 1 or 0 (a
                          hand-made params block): none */
    int evid_mix;      /* temporal, pooled, the history has the evidence plane and
                          SBL_EVIDENCE_MIX: the weight moves towards the paper's by the
                          carried evidence's shrink (sbl__evidence_share sets it) */
    float evid_sh;     /* the reference path's mix factor of the pixel in hand,
                          max(sh_R, s) (sbl__kernel_pixel_ref_ch); 0: no mixing */
    float evid_share;  /* the region's share s of change (sbl__evidence_share, per row):
                          the mix factor's floor (3.12; with stereo_shared_bias c > 0 net
                          of R's false alarms, 4.14); 0: none */
    int blur;          /* temporal, pooled, default configuration, shared_bias > 0, bilinear
                          fetch: the resampling blur's bias enters the bias energy
                          (docs/ESTIMATORS.md 4.10, 4.12; sbl__blur_terms) */
    int lean_restart;  /* temporal default configuration: the spatial lean where the
                          history is mostly dropped for a change (SBL_LEAN_RESTART_WEIGHT;
                          docs/ESTIMATORS.md 6.3; behind a stereo blend 6.10) */
    double blur_b2, blur_g; /* the reference path's pixel in hand: the blur's predicted
                               bias energy sum_c b_c^2 and its noise factor (B_b^2 =
                               blur_b2 - blur_g var_X, at least 0) */
    float tail_ch;     /* with tail: the channel count (tail_t is a sum over them) */
    int tail;          /* temporal, robust or pooled, the history has the tail plane:
                          Y's variance is floored at the carried tail variance
                          (docs/ESTIMATORS.md 2.4) */
    float tail_r, tail_t; /* the reference path's pixel in hand: the pooled rate and
                             variance (channel sum) of the limit's exceedances */
    float *tail_e, *tail_d; /* the reference path's pixel in hand: where the limit
                               records its exceedance and squared excess; NULL: not */
} sbl__weight_params;

/* Firefly limit of the robust estimator: the new sample may exceed the larger of the
   neighbours' mean and the history by at most this many neighbour standard deviations
   (summed over channels; see docs/ESTIMATORS.md). Where the eight neighbours are equal
   the bound is that larger value for any setting: on hit-or-miss samples a lone hit is
   cut to the history (docs/ESTIMATORS.md 2.3, bench/sparse_bias.c). */
#ifndef SBL_FIREFLY_SIGMAS
#define SBL_FIREFLY_SIGMAS 6.0
#endif

/* Pooled estimator (docs/ESTIMATORS.md section 3): a block's squared mean paired
   difference counts as bias energy only beyond SBL_POOLED_BLOCK_SE2 of its squared
   standard errors (SBL_POOLED_BLOCK_SE2_REGION where the region's prior applies, below),
   and the pixel's own 3x3 test asks for SBL_POOLED_LOCAL_SCALE times
   bias_threshold standard errors. Blocks: 3x3 windows centred SBL__POOL_STEP apart on
   the pixel's row, SBL__POOL_BLOCKS each side. */
#ifndef SBL_POOLED_BLOCK_SE2
#define SBL_POOLED_BLOCK_SE2 3.5
#endif
/* The blocks' threshold where the region's prior raises it by ln M (the temporal filter
   with the history's evidence plane, SBL_EVIDENCE_REGION & 2; docs/ESTIMATORS.md 3.10,
   6.2). 3.5 was chosen (3.2) before that prior existed, as the smallest c at which static
   content lost nothing; with the prior a quiet region asks c + ln M (static: M ~ 40,
   +3.7; a busy region, where more than half the rows' pixels passed c_R, has M < 1 and
   asks down to c - ln 2), so c itself need not carry that protection. Measured on the
   bench's eight scenes: 2.5 gains on the moving-light scenes (combined dynamic +1.5 %,
   shadow +1.2 %) and costs no scene more than 0.3 %; 2.0 costs the firefly scene 0.4 %.
   The stereo blend, and the temporal filter without the plane, have no region prior and
   keep SBL_POOLED_BLOCK_SE2. */
#ifndef SBL_POOLED_BLOCK_SE2_REGION
#define SBL_POOLED_BLOCK_SE2_REGION 2.5
#endif
#ifndef SBL_POOLED_LOCAL_SCALE
#define SBL_POOLED_LOCAL_SCALE (4.0 / 3.0)
#endif
#define SBL__POOL_STEP 3
#define SBL__POOL_RATIO_CAP 1e6
#define SBL__POOL_BLOCKS 2
/* columns a pixel's pooled statistic reads beyond it: the farthest block centre + 1 */
#define SBL__POOL_REACH (SBL__POOL_STEP * SBL__POOL_BLOCKS + 1)

/* The pooled temporal weight moved towards the paper's (Eq. 4 / 10 / 11) where that one
   is the larger, by the carried evidence's own shrink: a = a_d + sh_R (a_p - a_d)+,
   sh_R = r_R / (1 + r_R), r_R the garrote of R beyond its region-raised threshold
   (docs/ESTIMATORS.md 3.11). 0 where R has not passed it (the static case), so the
   paper's floor near 0.1 does not come back; where a change has lasted a few frames
   the paper's weight, which follows the change at once, gets in. Needs the history's
   evidence plane (without it nothing changes, bit for bit).
   2 (the default, 3.12): the mix factor is max(sh_R, s), s the region's share of change
   (the prior probability of 3.10 (c) that the pixel changed): where most of a region
   changes (a moving shadow) the paper's weight gets in before R has passed its threshold
   at the pixel. Behind a stereo blend (stereo_shared_bias c > 0) s is taken net of the
   carried R's false alarms, (s - q0) / (1 - q0) (ESTIMATORS 4.14): the gross share cost
   combined static 2 % and pan 0.7 % (3.12), the net one 0.2 % and 0.3 %. */
#ifndef SBL_EVIDENCE_MIX
#define SBL_EVIDENCE_MIX 2 /* 0: the weight of 3.10 (with SBL_EVIDENCE_REGION 3), bit for
                              bit; 1: 3.11 without 3.12's floor */
#endif

/* Posterior probability that a window changed, from the squared mean paired difference
   pd2 and its squared standard error se2 (robust estimator): 1 / (1 + rho^4.5), rho =
   (1 + k2/8) / (1 + t^2/8), t^2 = pd2 / se2. 0.5 at t^2 = k2, about 0.03 at t = 0 and
   k = 3, tending to 1 as t grows. */
static double sbl__change_posterior(double pd2, double se2, double k2, double prior_odds)
{
    double t2 = se2 > 0.0 ? pd2 / se2 : (pd2 > 0.0 ? HUGE_VAL : 0.0);
    double rho = (1.0 + k2 * 0.125) / (1.0 + t2 * 0.125);
    double r2 = rho * rho;
    return 1.0 / (1.0 + prior_odds * (r2 * r2 * sqrt(rho)));
}

/* Prior odds against a change this frame, relative to a history of one sample: by
   Laplace's rule of succession a pixel unchanged for N frames changes in the next with
   probability 1 / (N + 2), so the odds against grow as (N + 1) / 2. Temporal only (a
   stereo pair has no such memory). */
#ifndef SBL_HISTORY_PRIOR
#define SBL_HISTORY_PRIOR 1
#endif

/* Whose bias the stereo difference is (pooled stereo beta on temporally filtered eyes;
   docs/ESTIMATORS.md section 4.6). The bias term of a* = (B^2 + var_X) / (B^2 + var_X +
   var_Y) takes all of the mean paired difference pd = E[X] - E[Y] as X's, which holds
   when Y is new (a raw eye, every temporal blend). Two filtered eyes both lag a change
   by an amount that grows with their history's length, and each eye restarts on its
   own noise, so the lags are independent: b_X, b_Y zero-mean with variances in the
   ratio u^2 : v^2, u = N_X - 1 and v = N_Y - 1 the frames each history looks back.
   Then the regression of X's bias on pd = b_X - b_Y gives E[b_X (b_X - b_Y)] / E[pd^2]
   = u^2 / (u^2 + v^2) of B^2 as X's: all of it when Y is raw (v = 0, as before), half
   between equal ages, none when X has just restarted and Y is old (the old eye is the
   one that lags). The ages are bounded (SBL__LAG_AGE_MAX) so that no square overflows
   a float. */
/* The stereo blend's spatial lean (docs/ESTIMATORS.md 4.2) acts where the own eye holds
   at most this many samples (N_Y): a raw eye, or a temporal output whose history just
   restarted, whose noise is mostly this frame's samples and so independent of its
   neighbours'. Beyond it the neighbours share the eye's history through the bilinear
   reprojection, their mean follows y's noise and the lean pulls towards the own eye
   (measured on the combined pipeline, 6.5: 3 gains on every scene, 4 and more lose
   synthetic-pan and gallery's RMSE). */
#ifndef SBL_STEREO_LEAN_MAX_N
#define SBL_STEREO_LEAN_MAX_N 3.0
#endif
#ifndef SBL_STEREO_LAG_SHARE
#define SBL_STEREO_LAG_SHARE 1 /* 0: all of the bias is X's, the rule before */
#endif
#define SBL__LAG_AGE_MAX 65536.0
static double sbl__lag_share(double n_x, double n_y)
{
    double u = n_x - 1.0, v = n_y - 1.0;
    if (!(v > 0.0)) return 1.0; /* also NaN */
    if (!(u > 0.0)) u = 0.0;
    if (u > SBL__LAG_AGE_MAX) u = SBL__LAG_AGE_MAX;
    if (v > SBL__LAG_AGE_MAX) v = SBL__LAG_AGE_MAX;
    return u * u / (u * u + v * v);
}

/* The spatial lean of the pooled stereo beta (docs/ESTIMATORS.md section 4.2): a0 the
   weight of the two-estimate blend, V_Y the noise variance of Y and v8u the sample
   variance of its neighbours (without the centre, n8 of them), E = sum (m8 - x*)(y - x*)
   and D = sum (y - x*)^2 (m8 the neighbours' mean): the point of the segment x* .. y
   nearest the posterior mean of the pixel given x*, y and the prior N(m8, V_M),
   V_M = max(0, v8u - V_Y) + V_Y / n8 (the neighbours' spread beyond noise, plus the
   noise of their mean): a = (a0 + q e) / (1 + q), q = a0 V_Y / (V_M max(N_X, 1)) <= n8,
   e = E / D. In the temporal blend (SBL_LEAN_TEMPORAL) the prior counts once per
   history: a history of N_X samples took it in N_X times, with the same texture bias
   each time; the stereo blend and the restart lean pass N_X = 1 (their output is
   displayed, or the history it would be counted against is being dropped). */
static double sbl__lean(double a0, double var_y, double v8u, double n8, double n_x,
                        double lean_e, double lean_d)
{
    double tex = v8u - var_y, vm, q, den;
    if (tex < 0.0) tex = 0.0;
    vm = tex + var_y / n8;
    if (!(vm > 0.0)) return a0;
    q = a0 * var_y / (vm * (n_x > 1.0 ? n_x : 1.0));
    den = (1.0 + q) * lean_d;
    return den > 0.0 ? (a0 * lean_d + q * lean_e) / den : a0;
}

/* The lean in the temporal blend too (measured, not the default: the neighbours'
   texture bias accumulates in the history; docs/ESTIMATORS.md section 4.2) */
#ifndef SBL_LEAN_TEMPORAL
#define SBL_LEAN_TEMPORAL 0
#endif
/* The restart lean (docs/ESTIMATORS.md 6.3, 6.6): the lean in the temporal default only
   where the history is mostly being dropped: the weight a of the new sample above
   SBL_LEAN_RESTART_WEIGHT and above the progressive N_Y / (N_X + N_Y) by more than
   SBL_LEAN_RESTART_EXCESS. There the output is about one noisy sample, and the
   neighbours' mean is the better estimate where the texture is small; elsewhere the
   history would keep the neighbours' texture bias frame after frame (4.5). The lean's
   share rises linearly from 0 at those two thresholds to 1 at SBL_LEAN_RESTART_WEIGHT_FULL
   and SBL_LEAN_RESTART_EXCESS_FULL (the product of the two ramps), so the weight has no
   step. Measured (6.6, 6.7): the ramps 0.1 .. 0.3 and 0.05 .. 0.2 gain the moving-light
   scenes more than the step at 0.3 / 0.15 did, with no scene worse by 0.2 %; the
   excess keeps the lean off young histories, whose weight is high by their length alone.
   SBL_LEAN_RESTART_WEIGHT <= 0: off. A _FULL at or below its threshold: a step. */
#ifndef SBL_LEAN_RESTART_WEIGHT
#define SBL_LEAN_RESTART_WEIGHT 0.1
#endif
#ifndef SBL_LEAN_RESTART_WEIGHT_FULL
#define SBL_LEAN_RESTART_WEIGHT_FULL 0.3
#endif
#ifndef SBL_LEAN_RESTART_EXCESS
#define SBL_LEAN_RESTART_EXCESS 0.05
#endif
#ifndef SBL_LEAN_RESTART_EXCESS_FULL
#define SBL_LEAN_RESTART_EXCESS_FULL 0.2
#endif
/* the restart lean is built in (its instances: sbl__kernel_lanes_pooled_ch) */
#define SBL__LEAN_RESTART_ON (!SBL_LEAN_TEMPORAL && SBL_LEAN_RESTART_WEIGHT > 0.0)
/* the ramps' slopes (a step: 1e6 per unit, full within 1e-6 of its threshold) */
#define SBL__LEAN_RESTART_WSLOPE \
    (SBL_LEAN_RESTART_WEIGHT_FULL - SBL_LEAN_RESTART_WEIGHT > 1e-6 ? 1.0 / (SBL_LEAN_RESTART_WEIGHT_FULL - SBL_LEAN_RESTART_WEIGHT) : 1e6)
#define SBL__LEAN_RESTART_ESLOPE \
    (SBL_LEAN_RESTART_EXCESS_FULL - SBL_LEAN_RESTART_EXCESS > 1e-6 ? 1.0 / (SBL_LEAN_RESTART_EXCESS_FULL - SBL_LEAN_RESTART_EXCESS) : 1e6)
/* the restart lean's share (0 .. 1) at the weight a with the progressive weight prog */
static double sbl__restart_share(double a, double prog)
{
    double fw = (a - SBL_LEAN_RESTART_WEIGHT) * SBL__LEAN_RESTART_WSLOPE;
    double fe = (a - prog - SBL_LEAN_RESTART_EXCESS) * SBL__LEAN_RESTART_ESLOPE;
    fw = fw < 0.0 ? 0.0 : fw > 1.0 ? 1.0 : fw;
    fe = fe < 0.0 ? 0.0 : fe > 1.0 ? 1.0 : fe;
    return fw * fe;
}
/* Weight of Y from squares summed over the channels in use. x_dev2 = (x* - mean)^2,
   s2 = population variance of Y, pd2 = (mean paired difference)^2, pv = sample
   variance of the paired differences x*_i - y_i; v8 = population variance of Y
   without the centre, lean_e / lean_d as sbl__lean (the pooled estimator); x_tex the
   history's texture (sbl__moments.xdev2; < 0: none). *a_two: the weight of the
   two-estimate blend, before the lean (what Eq. 5 counts). */
static float sbl__weight(const sbl__weight_params *p, double x_dev2, double s2, double pd2,
                         double pv, int count, int pair_count, float n_x, float n_y,
                         double pool_r, double v8, double lean_e, double lean_d, double x_tex,
                         float *a_two)
{
    double a, a2 = -1.0;
    double progressive = SBL__CAST(double, n_y) / (SBL__CAST(double, n_x) + SBL__CAST(double, n_y));
    switch (p->estimator) {
    case SBL_ESTIMATOR_PAPER:
        /* Eq. 4 with Eq. 10/11: a = 1 - s^2 / D, D = d^2 + s^2 */
        a = (x_dev2 + s2 > 0.0) ? x_dev2 / (x_dev2 + s2) : progressive;
        break;
    case SBL_ESTIMATOR_PROGRESSIVE:
        a = progressive;
        break;
    case SBL_ESTIMATOR_CONSTANT:
        a = SBL__CAST(double, p->constant);
        break;
    case SBL_ESTIMATOR_POOLED:
    case SBL_ESTIMATOR_ROBUST: {
        /* As history-aware, but the bias enters with the posterior probability that
           the window changed: t = mean paired difference / its standard error is
           Student-t with 8 degrees of freedom if nothing changed; against a flat
           alternative the odds of change grow as (1 + t^2/8)^4.5, set to 1 at t^2 = k^2
           (bias_threshold). Soft, and polynomial rather than exponential in t^2, so
           heavy-tailed noise cannot make a near-certain change out of one sample. */
        double k = SBL__CAST(double, p->bias_threshold), k2;
        double var_x, var_y, se2, bias2 = 0.0, share; /* (share: the restart lean's) */
        double bias2_c = 0.0, a_c; /* the change's bias alone, its weight (the lean's gate) */
        /* pooled: the local test only has to catch what the blocks cannot (a change
           confined to a few pixels), so it asks for more evidence */
        if (p->estimator == SBL_ESTIMATOR_POOLED) k *= SBL_POOLED_LOCAL_SCALE;
        k2 = k * k;
        if (p->temporal && p->tail) {
            /* Y's variance is at least the carried variance of the limit's exceedances
               (2.4): a window of misses shows none of it */
            const double tv = SBL__CAST(double, p->tail_t);
            const double pf = tv * (SBL__CAST(double, n_x) + SBL__CAST(double, n_y)) /
                              (n_x > 1.0f ? SBL__CAST(double, n_x) : 1.0);
            if (pv < pf) pv = pf;
            if (s2 < tv) s2 = tv;
        }
        if (pair_count > 1) {
            var_y = pv * SBL__CAST(double, n_x) / (SBL__CAST(double, n_x) + SBL__CAST(double, n_y));
            var_x = pv - var_y;
            se2 = pv / pair_count;
        } else {
            var_y = count > 1 ? s2 * count / (count - 1) : 0.0;
            var_x = var_y * SBL__CAST(double, n_y) / SBL__CAST(double, n_x);
            se2 = pair_count == 1 ? var_x + var_y : 0.0;
        }
        if (pair_count > 0) {
            /* the history prior's odds (N + 1) / 2; with the region's share of change
               (3.10): 0.5 ((N + 2) M - 1), the same at M = 1 */
            double odds = 1.0;
            if (p->temporal && SBL_HISTORY_PRIOR)
                odds = p->region_m > 0.0f && p->region_m != 1.0f
                           ? 0.5 * ((SBL__CAST(double, n_x) + 2.0) * SBL__CAST(double, p->region_m) - 1.0)
                           : 0.5 * (SBL__CAST(double, n_x) + 1.0);
            /* stereo, where either eye's carried evidence shows a change (6.15): the
               eyes then differ by their lags (4.6), which one window's test mostly
               misses; the change is taken as certain, all of pd^2 is bias */
            bias2 = p->stereo_change ? pd2 : sbl__change_posterior(pd2, se2, k2, odds) * pd2;
        }
        if (pair_count > 1 && pool_r > 0.0) {
            /* empirical Bayes: with B ~ N(0, tau^2) and pd = B + noise(se2), the
               posterior mean of B^2 is sh^2 pd2 + sh se2, sh = tau^2 / (tau^2 + se2) =
               r / (1 + r), r = tau^2 / se2 pooled from the blocks */
            double sh = pool_r / (1.0 + pool_r), b_eb = sh * sh * pd2 + sh * se2;
            if (b_eb > bias2) bias2 = b_eb;
        }
        /* a stereo blend follows: a bias both eyes share counts 1 + c times (4.7) */
        if (p->temporal && p->shared_bias != 0.0f)
            bias2 *= 1.0 + SBL__CAST(double, p->shared_bias);
        bias2_c = bias2;
        if (p->blur && p->temporal) {
            /* the resampling blur's bias (4.12), shared by both eyes as the change's is;
               the change's mean paired difference holds the blur already where the tests
               fire, so the larger of the two, not their sum */
            const double bb = (p->blur_b2 - p->blur_g * var_x) * (1.0 + SBL__CAST(double, p->shared_bias));
            if (bb > bias2) bias2 = bb;
        }
        {
            /* pooled stereo: the part of the bias that is X's (sbl__lag_share) */
            double fx = SBL_STEREO_LAG_SHARE && p->estimator == SBL_ESTIMATOR_POOLED && !p->temporal
                            ? sbl__lag_share(SBL__CAST(double, n_x), SBL__CAST(double, n_y)) : 1.0;
            a = (bias2 + var_x + var_y > 0.0) ? (fx * bias2 + var_x) / (bias2 + var_x + var_y)
                                              : progressive;
        }
        /* the restart lean's gate reads the weight of the change's bias alone (6.10): the
           blur's term drops a history for its texture's curvature, which the neighbours'
           mean blurs the more */
        a_c = a;
        if (p->blur && p->temporal && bias2_c != bias2)
            a_c = (bias2_c + var_x + var_y > 0.0) ? (bias2_c + var_x) / (bias2_c + var_x + var_y)
                                                  : progressive;
        /* towards the paper's weight by the carried evidence's shrink (3.11) */
        if (SBL_EVIDENCE_MIX && p->evid_mix && p->temporal && p->estimator == SBL_ESTIMATOR_POOLED &&
            pair_count > 1 && p->evid_sh > 0.0f) {
            const double ap = (x_dev2 + s2 > 0.0) ? x_dev2 / (x_dev2 + s2) : progressive;
            if (ap > a) a += SBL__CAST(double, p->evid_sh) * (ap - a);
            if (ap > a_c) a_c += SBL__CAST(double, p->evid_sh) * (ap - a_c);
        }
        /* stereo: the neighbours of Y as a third estimate, where they agree (flat).
           Only for an own eye of at most SBL_STEREO_LEAN_MAX_N samples: the prior
           assumes the neighbours' noise independent of each other and of y, which a
           longer filtered eye's is not (its pixels share history through the bilinear
           reprojection). q is divided by N_X only in the temporal blend, whose output
           is the next history; the stereo blend's is displayed, not accumulated */
        if (p->estimator == SBL_ESTIMATOR_POOLED && (SBL_LEAN_TEMPORAL || !p->temporal) &&
            count > 2 && n_y <= SBL__CAST(float, SBL_STEREO_LEAN_MAX_N)) {
            a2 = a;
            a = sbl__lean(a, var_y, v8 * (count - 1) / (count - 2), count - 1.0,
                          p->temporal ? SBL__CAST(double, n_x) : 1.0, lean_e, lean_d);
        } else if (p->lean_restart && count > 2 && (share = sbl__restart_share(a_c, progressive)) > 0.0) {
            /* the restart lean (6.3): q is not divided by N_X (the history it would be
               counted against is being dropped). The texture is also the history's own
               x*'s deviation from its neighbours' where larger: the raw neighbours see
               no texture below one sample's noise. Behind a stereo blend the texture, a
               bias both eyes' leans share, counts 1 + c times (6.10, 4.7's rule) */
            double v8u = v8 * (count - 1) / (count - 2);
            if (x_tex >= 0.0 && x_tex > v8u - var_y) v8u = var_y + x_tex;
            if (p->shared_bias != 0.0f && v8u > var_y)
                v8u = var_y + (1.0 + SBL__CAST(double, p->shared_bias)) * (v8u - var_y);
            a2 = a;
            a = a2 + share * (sbl__lean(a2, var_y, v8u, count - 1.0, 1.0, lean_e, lean_d) - a2);
        }
        break;
    }
    case SBL_ESTIMATOR_HISTORY_AWARE:
    default: {
        /* The paired differences x*_i - y_i cancel texture: their variance is
           var_X + var_Y, with var_X = var_Y N_Y / N_X, and their mean is the bias plus
           noise of variance pv / pairs. Bias counts only beyond bias_threshold standard
           errors (a paired t-test), so that noise is not taken for change. With fewer
           than two pairs, var_Y falls back to the 3x3 variance of Y (Bessel). */
        double k2 = SBL__CAST(double, p->bias_threshold) * SBL__CAST(double, p->bias_threshold);
        double var_x, var_y, bias2 = 0.0;
        if (pair_count > 1) {
            var_y = pv * SBL__CAST(double, n_x) / (SBL__CAST(double, n_x) + SBL__CAST(double, n_y));
            var_x = pv - var_y;
            bias2 = pd2 - k2 * pv / pair_count;
        } else {
            var_y = count > 1 ? s2 * count / (count - 1) : 0.0;
            var_x = var_y * SBL__CAST(double, n_y) / SBL__CAST(double, n_x);
            if (pair_count == 1) bias2 = pd2 - k2 * (var_x + var_y);
        }
        if (bias2 < 0.0) bias2 = 0.0;
        if (p->temporal && p->shared_bias != 0.0f) /* 4.7 */
            bias2 *= 1.0 + SBL__CAST(double, p->shared_bias);
        a = (bias2 + var_x + var_y > 0.0) ? (bias2 + var_x) / (bias2 + var_x + var_y)
                                          : progressive;
        break;
    }
    }
    if (a2 < 0.0) a2 = a;
    if (a < SBL__CAST(double, p->alpha_min)) a = SBL__CAST(double, p->alpha_min);
    if (!(a >= 0.0)) a = 0.0; /* NaN lands here too */
    if (a > 1.0) a = 1.0;
    if (a2 < SBL__CAST(double, p->alpha_min)) a2 = SBL__CAST(double, p->alpha_min);
    if (!(a2 >= 0.0)) a2 = 0.0;
    if (a2 > 1.0) a2 = 1.0;
    *a_two = SBL__CAST(float, a2);
    return SBL__CAST(float, a);
}

/* Neighbourhood clamp / variance clip of x* in place. The box always contains the
   pixel's own new sample y, so a history equal to y is never moved. */
static void sbl__rectify(const sbl__weight_params *p, const sbl__moments *m, const float *y,
                         float *xs, int ch)
{
    int k;
    if (p->rectify == SBL_RECTIFY_CLAMP) {
        for (k = 0; k < ch; ++k)
            xs[k] = xs[k] < m->lo[k] ? m->lo[k] : (xs[k] > m->hi[k] ? m->hi[k] : xs[k]);
    } else if (p->rectify == SBL_RECTIFY_VARIANCE_CLIP) {
        /* shrink the segment mean -> x* until it enters the box (keeps hue). The channel
           that sets t by y's distance, x* on y's side, lands on y exactly (the pooled
           lean's E / D must see D = 0 there, not rounding noise; sbl__lanes_rectify) */
        double t = 1.0, tk[4];
        int on_y[4];
        for (k = 0; k < ch; ++k) {
            double half = SBL__CAST(double, p->gamma) * sqrt(m->var[k]);
            double d = fabs(SBL__CAST(double, xs[k]) - m->mean[k]);
            double dy = fabs(SBL__CAST(double, y[k]) - m->mean[k]);
            on_y[k] = !(half > dy) && (SBL__CAST(double, y[k]) - m->mean[k]) * (SBL__CAST(double, xs[k]) - m->mean[k]) > 0.0;
            if (dy > half) half = dy;
            tk[k] = d > half ? half / d : 1.0;
            if (tk[k] < t) t = tk[k];
        }
        if (t < 1.0)
            for (k = 0; k < ch; ++k)
                xs[k] = on_y[k] && !(tk[k] > t) ? y[k]
                        : SBL__CAST(float, m->mean[k] + (SBL__CAST(double, xs[k]) - m->mean[k]) * t);
    }
}

static sbl__weight_params sbl__weight_params_make(sbl_estimator e, sbl_rectify r,
                                                 sbl_weight_mode m, float constant,
                                                 float alpha_min, float gamma, float bias)
{
    sbl__weight_params p;
    p.estimator = e;
    p.rectify = r;
    p.mode = m;
    p.constant = constant;
    p.alpha_min = alpha_min;
    p.gamma = gamma;
    p.bias_threshold = bias;
    p.temporal = 0;
    p.stereo_ev = p.stereo_change = 0;
    p.shared_bias = 0.0f;
    p.region_m = 1.0f;
    p.evid_mix = 0;
    p.evid_sh = 0.0f;
    p.evid_share = 0.0f;
    p.blur = 0;
    p.lean_restart = 0;
    p.blur_b2 = p.blur_g = 0.0;
    p.tail = 0;
    p.tail_ch = 1.0f;
    p.tail_r = p.tail_t = 0.0f;
    p.tail_e = p.tail_d = NULL;
    return p;
}

static sbl_result sbl__check_weight_params(sbl_estimator e, sbl_rectify r,
                                           sbl_weight_mode m, float constant,
                                           float alpha_min, float gamma, float bias)
{
    if (SBL__CAST(int, e) < 0 || e >= SBL_ESTIMATOR_COUNT) return SBL_ERROR_INVALID_PARAM;
    if (SBL__CAST(int, r) < 0 || r >= SBL_RECTIFY_COUNT) return SBL_ERROR_INVALID_PARAM;
    if (SBL__CAST(int, m) < 0 || m >= SBL_WEIGHT_MODE_COUNT) return SBL_ERROR_INVALID_PARAM;
    if (!sbl__param_ok(constant) || constant > 1.0f) return SBL_ERROR_INVALID_PARAM;
    if (!sbl__param_ok(alpha_min) || alpha_min > 1.0f) return SBL_ERROR_INVALID_PARAM;
    if (!sbl__param_ok(gamma) || !sbl__param_ok(bias)) return SBL_ERROR_INVALID_PARAM;
    return SBL_OK;
}

/* ------------------------------------------------------------------------ */
/* 6. Blend, history length, and the fused row kernel                       */
/* ------------------------------------------------------------------------ */

/* Firefly limit (robust estimator): the new sample y is scaled down (hue kept) so that
   its channel sum exceeds max(neighbours' mean, x*) by at most SBL_FIREFLY_SIGMAS
   neighbour standard deviations (the window without y, summed over channels). Only the
   sample that enters the blend is limited; the window statistics keep it (with a
   firefly in them they drive the weight towards 1/(N+1), see docs/ESTIMATORS.md). */
static void sbl__firefly_limit(const sbl__weight_params *p, const sbl__moments *m, const float *y,
                               const float *xs, int ch, double n_scale, float *ylim)
{
    double sum_y = 0.0, sum_m8 = 0.0, sum_x = 0.0, v8 = 0.0, bound, t = 1.0;
    int k;
    for (k = 0; k < ch; ++k) {
        sum_y += SBL__CAST(double, y[k]);
        sum_m8 += m->mean8[k];
        sum_x += SBL__CAST(double, xs[k]);
        v8 += m->var8[k];
    }
    bound = (sum_m8 > sum_x ? sum_m8 : sum_x) + SBL_FIREFLY_SIGMAS * sqrt(v8 * n_scale);
    /* a relative slack: y equal to x* must stay untouched under any summation order */
    bound += 1e-5 * fabs(bound);
    if (bound < 0.0) bound = 0.0;
    if (p->tail_e) { /* the exceedance, for the carried tail plane (2.4) */
        const int ex = sum_y > bound;
        *p->tail_e = ex ? 1.0f : 0.0f;
        *p->tail_d = ex ? SBL__CAST(float, (sum_y - sum_x) * (sum_y - sum_x) / ch) : 0.0f;
    }
    if (p->tail && sum_y > bound) {
        /* admit the share f = rho / (1 + rho) of the excess, rho = r (N + 1) (2.4);
           behind a stereo blend the eyes' cuts are one bias and their admitted excesses
           two noises, so rho counts the bias 1 + c times, as the weight does (6.9) */
        const double rho = SBL__CAST(double, p->tail_r) * n_scale * (1.0 + SBL__CAST(double, p->shared_bias));
        bound += rho / (1.0 + rho) * (sum_y - bound);
    }
    if (sum_y > bound) t = bound / sum_y;
    for (k = 0; k < ch; ++k) ylim[k] = t < 1.0 ? SBL__CAST(float, SBL__CAST(double, y[k]) * t) : y[k];
}

/* Reference blend of one pixel (double): y = own, xs = other (rectified here), n_x/n_y
   their sample counts. Writes out[ch], returns the new N; *alpha_out = mean weight. */
static float sbl__blend_pixel(const sbl__weight_params *p, const sbl__moments *m,
                              const float *y, float *xs, float n_x, float n_y, int ch,
                              float *out, float *alpha_out)
{
    float a[4], a2[4];
    float a_mean = 0.0f, a2_mean = 0.0f;
    int k;
    float ylim[4];
    if ((p->estimator == SBL_ESTIMATOR_ROBUST || p->estimator == SBL_ESTIMATOR_POOLED) &&
        m->count > 1) {
        /* temporal: the limit bounds the step a sample makes in the output, a (y - x*),
           by the output's own noise (about sigma / sqrt(N + 1) at a = 1 / (N + 1)), so
           its sigmas grow with sqrt(N + 1); 1 for the stereo blend */
        sbl__firefly_limit(p, m, y, xs, ch, p->temporal ? SBL__CAST(double, n_x) + 1.0 : 1.0, ylim);
        y = ylim;
    }
    sbl__rectify(p, m, y, xs, ch);
    if (p->mode == SBL_WEIGHT_PER_CHANNEL) {
        sbl__weight_params pc;
        if (p->tail) { /* the carried variance is a channel sum: a channel's share */
            pc = *p;
            pc.tail_t /= SBL__CAST(float, ch);
            p = &pc;
        }
        for (k = 0; k < ch; ++k) {
            double dev = SBL__CAST(double, xs[k]) - m->mean[k];
            double dy = SBL__CAST(double, y[k]) - SBL__CAST(double, xs[k]);
            a[k] = sbl__weight(p, dev * dev, m->var[k], m->pair_diff[k] * m->pair_diff[k],
                               m->pair_var[k], m->count, m->pair_count, n_x, n_y,
                               m->pool_r, m->var8[k], (m->mean8[k] - SBL__CAST(double, xs[k])) * dy,
                               dy * dy, -1.0, &a2[k]);
            a_mean += a[k];
            a2_mean += a2[k];
        }
        a_mean /= SBL__CAST(float, ch);
        a2_mean /= SBL__CAST(float, ch);
    } else {
        double dev2 = 0.0, s2 = 0.0, pd2 = 0.0, pv = 0.0, v8 = 0.0, le = 0.0, ld = 0.0;
        for (k = 0; k < ch; ++k) {
            double dev = SBL__CAST(double, xs[k]) - m->mean[k];
            double dy = SBL__CAST(double, y[k]) - SBL__CAST(double, xs[k]);
            dev2 += dev * dev;
            s2 += m->var[k];
            pd2 += m->pair_diff[k] * m->pair_diff[k];
            pv += m->pair_var[k];
            v8 += m->var8[k];
            le += (m->mean8[k] - SBL__CAST(double, xs[k])) * dy;
            ld += dy * dy;
        }
        a_mean = sbl__weight(p, dev2, s2, pd2, pv, m->count, m->pair_count, n_x, n_y, m->pool_r,
                             v8, le, ld, m->xdev2, &a2_mean);
        for (k = 0; k < ch; ++k) a[k] = a_mean;
    }
    for (k = 0; k < ch; ++k) {
        /* lerp from the end the weight is nearer: a = 1 gives y and a = 0 gives x*
           exactly, and a dim y next to a bright x* (|x*| >> |y|) is not cancelled away */
        float v = a[k] <= 0.5f ? xs[k] + a[k] * (y[k] - xs[k])
                               : y[k] + (1.0f - a[k]) * (xs[k] - y[k]);
        /* both inputs finite but the lerp overflowed (|x|,|y| near FLT_MAX): form it
           the other way, which cannot overflow when the inputs are finite */
        if (!sbl__finite(v))
            v = SBL__CAST(float, (1.0 - SBL__CAST(double, a[k])) * SBL__CAST(double, xs[k]) + SBL__CAST(double, a[k]) * SBL__CAST(double, y[k]));
        out[k] = v;
    }
    *alpha_out = a_mean;
    /* the count of the two-estimate blend: the lean's gain from the neighbours is not
       counted (their noise is shared with the neighbours' own outputs) */
    return sbl_blend_sample_count(a2_mean, n_x, n_y);
}

/* ---- thin SIMD layer ------------------------------------------------------
   One lane kernel below is written against these few operations. Chosen at compile
   time: AVX-512F, AVX2, SSE2, NEON (AArch64), or plain float (SBL_NO_SIMD, or none of
   them available): the scalar path is the same code with a width of 1.
   The row gather (SBL__ROW_GATHER) adds tap loads at int offsets (hardware gathers on
   AVX2 / AVX-512, emulated on SSE2), mask logic and bit tests that -ffast-math cannot
   fold. The scalar build and NEON gather one pixel at a time with the reference
   gather, which the row gather must equal bit for bit (test_simd, test_paths). */
#if !defined(SBL_NO_SIMD) && defined(__AVX512F__)
/* g++ 12's AVX-512 intrinsics start from `__m512 __Y = __Y;` (an undefined vector) and
   -Wmaybe-uninitialized then flags every inlined min / max / sqrt / gather, and
   -Wuninitialized some (the floor and the double conversions inlined into a function of
   their own): false positives inside the compiler's own header, silenced for that
   header only */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#else
#include <immintrin.h>
#endif
#define SBL_SIMD_NAME "avx512"
#define SBL__VW 16
typedef __m512 sbl__v;
typedef __mmask16 sbl__m;
#define sbl__set1(a) _mm512_set1_ps(a)
#define sbl__load(p) _mm512_loadu_ps(p)
#define sbl__store(p, a) _mm512_storeu_ps(p, a)
#define sbl__add(a, b) _mm512_add_ps(a, b)
#define sbl__sub(a, b) _mm512_sub_ps(a, b)
#define sbl__mul(a, b) _mm512_mul_ps(a, b)
#define sbl__div(a, b) _mm512_div_ps(a, b)
#define sbl__min(a, b) _mm512_min_ps(a, b)
#define sbl__max(a, b) _mm512_max_ps(a, b)
#define sbl__sqrt(a) _mm512_sqrt_ps(a)
#define sbl__abs(a) _mm512_abs_ps(a)
#define sbl__gt(a, b) _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ)
#define sbl__sel(m, a, b) _mm512_mask_blend_ps(m, b, a)
#define sbl__all(m) ((m) == 0xffff) /* every lane's mask set */
#define sbl__true SBL__CAST(__mmask16, 0xffff) /* every lane set */
/* for the row gather: taps at int offsets idx[0..VW) from base, masks, bit tests */
#define SBL__ROW_GATHER 1
#define SBL__SHUFFLE4 1 /* 128-bit float shuffles (sbl__deinterleave / sbl__interleave) */
/* taps at int offsets: lane loads, not a hardware gather, which costs ~1.8x as much on
   the machine measured (make bench-gather; sbl__gather_pairs) */
SBL__INLINE __m128 sbl__load4_at(const float *base, const int *idx)
{
    const __m128 a = _mm_unpacklo_ps(_mm_load_ss(base + idx[0]), _mm_load_ss(base + idx[1]));
    const __m128 c = _mm_unpacklo_ps(_mm_load_ss(base + idx[2]), _mm_load_ss(base + idx[3]));
    return _mm_movelh_ps(a, c);
}
/* lo in lanes 0-7, hi in 8-15 (AVX-512F: no insertf32x8, which is DQ) */
SBL__INLINE __m512 sbl__join8(__m256 lo, __m256 hi)
{
    return _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}
SBL__INLINE __m512 sbl__gatheri(const float *base, const int *idx)
{
    const __m256 lo = _mm256_set_m128(sbl__load4_at(base, idx + 4), sbl__load4_at(base, idx));
    const __m256 hi = _mm256_set_m128(sbl__load4_at(base, idx + 12), sbl__load4_at(base, idx + 8));
    return sbl__join8(lo, hi);
}
#define sbl__le(a, b) _mm512_cmp_ps_mask(a, b, _CMP_LE_OQ)
#define sbl__mand(a, b) SBL__CAST(__mmask16, (a) & (b))
#define sbl__mor(a, b) SBL__CAST(__mmask16, (a) | (b))
#define sbl__mandnot(a, b) SBL__CAST(__mmask16, (a) & ~(b)) /* a and not b */
#define sbl__mbits(m) SBL__CAST(int, m)
#define sbl__nonfinite(a) \
    _mm512_cmpeq_epi32_mask(_mm512_and_si512(_mm512_castps_si512(a), \
                                             _mm512_set1_epi32(0x7f800000)), \
                            _mm512_set1_epi32(0x7f800000))
#define sbl__posinf(a) \
    _mm512_cmpeq_epi32_mask(_mm512_castps_si512(a), _mm512_set1_epi32(0x7f800000))
#define sbl__floor(a) _mm512_roundscale_ps(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)
SBL__INLINE __mmask16 sbl__lane_ok(__m512 a) /* sbl__lane_value_ok per lane (see SSE2) */
{
    const __m512i b = _mm512_and_si512(_mm512_castps_si512(a), _mm512_set1_epi32(0x7fffffff));
    return SBL__CAST(__mmask16, _mm512_cmpeq_epi32_mask(b, _mm512_setzero_si512()) |
                                    _mm512_cmplt_epu32_mask(_mm512_sub_epi32(b, _mm512_set1_epi32(0x2b800000)),
                                                            _mm512_set1_epi32(0x2d000000)));
}
SBL__INLINE __m512 sbl__div_exact(__m512 n, __m512 a) /* see the SSE2 version */
{
#define SBL__HI256(v) _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(v), 1))
    const __m256 lo = _mm512_cvtpd_ps(_mm512_div_pd(_mm512_cvtps_pd(_mm512_castps512_ps256(n)),
                                                    _mm512_cvtps_pd(_mm512_castps512_ps256(a))));
    const __m256 hi = _mm512_cvtpd_ps(_mm512_div_pd(_mm512_cvtps_pd(SBL__HI256(n)),
                                                    _mm512_cvtps_pd(SBL__HI256(a))));
#undef SBL__HI256
    return _mm512_castpd_ps(
        _mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}
#elif !defined(SBL_NO_SIMD) && defined(__AVX2__)
#include <immintrin.h>
#define SBL_SIMD_NAME "avx2"
#define SBL__VW 8
typedef __m256 sbl__v;
typedef __m256 sbl__m;
#define sbl__set1(a) _mm256_set1_ps(a)
#define sbl__load(p) _mm256_loadu_ps(p)
#define sbl__store(p, a) _mm256_storeu_ps(p, a)
#define sbl__add(a, b) _mm256_add_ps(a, b)
#define sbl__sub(a, b) _mm256_sub_ps(a, b)
#define sbl__mul(a, b) _mm256_mul_ps(a, b)
#define sbl__div(a, b) _mm256_div_ps(a, b)
#define sbl__min(a, b) _mm256_min_ps(a, b)
#define sbl__max(a, b) _mm256_max_ps(a, b)
#define sbl__sqrt(a) _mm256_sqrt_ps(a)
/* abs on the bits: -ffast-math (no signed zeros) may fold a -0.0f mask to +0 */
#define sbl__abs(a) _mm256_and_ps(a, _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff)))
#define sbl__gt(a, b) _mm256_cmp_ps(a, b, _CMP_GT_OQ)
#define sbl__sel(m, a, b) _mm256_blendv_ps(b, a, m)
#define sbl__all(m) (_mm256_movemask_ps(m) == 0xff)
#define sbl__true _mm256_castsi256_ps(_mm256_set1_epi32(-1))
#define SBL__ROW_GATHER 1
#define SBL__SHUFFLE4 1 /* 128-bit float shuffles (sbl__deinterleave / sbl__interleave) */
/* taps at int offsets: lane loads, not a hardware gather, which costs ~1.9x as much on
   the machine measured (make bench-gather; sbl__gather_pairs) */
SBL__INLINE __m128 sbl__load4_at(const float *base, const int *idx)
{
    const __m128 a = _mm_unpacklo_ps(_mm_load_ss(base + idx[0]), _mm_load_ss(base + idx[1]));
    const __m128 c = _mm_unpacklo_ps(_mm_load_ss(base + idx[2]), _mm_load_ss(base + idx[3]));
    return _mm_movelh_ps(a, c);
}
SBL__INLINE __m256 sbl__gatheri(const float *base, const int *idx)
{
    return _mm256_set_m128(sbl__load4_at(base, idx + 4), sbl__load4_at(base, idx));
}
#define sbl__le(a, b) _mm256_cmp_ps(a, b, _CMP_LE_OQ)
#define sbl__mand(a, b) _mm256_and_ps(a, b)
#define sbl__mor(a, b) _mm256_or_ps(a, b)
#define sbl__mandnot(a, b) _mm256_andnot_ps(b, a)
#define sbl__mbits(m) _mm256_movemask_ps(m)
#define sbl__nonfinite(a) \
    _mm256_castsi256_ps(_mm256_cmpeq_epi32( \
        _mm256_and_si256(_mm256_castps_si256(a), _mm256_set1_epi32(0x7f800000)), \
        _mm256_set1_epi32(0x7f800000)))
#define sbl__posinf(a) \
    _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_castps_si256(a), \
                                           _mm256_set1_epi32(0x7f800000)))
#define sbl__floor(a) _mm256_floor_ps(a)
SBL__INLINE __m256 sbl__lane_ok(__m256 a) /* sbl__lane_value_ok per lane (see SSE2) */
{
    const __m256i b = _mm256_and_si256(_mm256_castps_si256(a), _mm256_set1_epi32(0x7fffffff));
    return _mm256_castsi256_ps(_mm256_or_si256(
        _mm256_cmpeq_epi32(b, _mm256_setzero_si256()),
        _mm256_cmpgt_epi32(_mm256_set1_epi32(-0x53000000),
                           _mm256_add_epi32(b, _mm256_set1_epi32(0x54800000)))));
}
SBL__INLINE __m256 sbl__div_exact(__m256 n, __m256 a) /* see the SSE2 version */
{
    const __m128 lo = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_cvtps_pd(_mm256_castps256_ps128(n)),
                                                    _mm256_cvtps_pd(_mm256_castps256_ps128(a))));
    const __m128 hi = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_cvtps_pd(_mm256_extractf128_ps(n, 1)),
                                                    _mm256_cvtps_pd(_mm256_extractf128_ps(a, 1))));
    return _mm256_insertf128_ps(_mm256_castps128_ps256(lo), hi, 1);
}
#elif !defined(SBL_NO_SIMD) && (defined(__SSE2__) || defined(_M_X64) || \
                                (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#include <emmintrin.h>
#define SBL_SIMD_NAME "sse2"
#define SBL__VW 4
typedef __m128 sbl__v;
typedef __m128 sbl__m;
#define sbl__set1(a) _mm_set1_ps(a)
#define sbl__load(p) _mm_loadu_ps(p)
#define sbl__store(p, a) _mm_storeu_ps(p, a)
#define sbl__add(a, b) _mm_add_ps(a, b)
#define sbl__sub(a, b) _mm_sub_ps(a, b)
#define sbl__mul(a, b) _mm_mul_ps(a, b)
#define sbl__div(a, b) _mm_div_ps(a, b)
#define sbl__min(a, b) _mm_min_ps(a, b)
#define sbl__max(a, b) _mm_max_ps(a, b)
#define sbl__sqrt(a) _mm_sqrt_ps(a)
/* abs on the bits: -ffast-math (no signed zeros) may fold a -0.0f mask to +0 */
#define sbl__abs(a) _mm_and_ps(a, _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff)))
#define sbl__gt(a, b) _mm_cmpgt_ps(a, b)
#if defined(__GNUC__) || defined(__clang__)
/* the select in the compiler's own vector operators, which it folds where the mask is a
   constant (sbl__true in the full-chunk instances: one operand; _mm_and_ps / _mm_andnot_ps
   are builtins it keeps) */
SBL__INLINE __m128 sbl__sel(__m128 m, __m128 a, __m128 b)
{
    const __m128i mi = _mm_castps_si128(m);
    return _mm_castsi128_ps((mi & _mm_castps_si128(a)) | (~mi & _mm_castps_si128(b)));
}
#else
#define sbl__sel(m, a, b) _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b))
#endif
#define sbl__all(m) (_mm_movemask_ps(m) == 0xf)
#define sbl__true _mm_castsi128_ps(_mm_set1_epi32(-1))
#define SBL__ROW_GATHER 1
#define SBL__SHUFFLE4 1 /* 128-bit float shuffles (sbl__deinterleave / sbl__interleave) */
#define sbl__gatheri(base, idx) \
    _mm_setr_ps((base)[(idx)[0]], (base)[(idx)[1]], (base)[(idx)[2]], (base)[(idx)[3]])
#define sbl__le(a, b) _mm_cmple_ps(a, b)
#define sbl__mand(a, b) _mm_and_ps(a, b)
#define sbl__mor(a, b) _mm_or_ps(a, b)
#define sbl__mandnot(a, b) _mm_andnot_ps(b, a)
#define sbl__mbits(m) _mm_movemask_ps(m)
#define sbl__nonfinite(a) \
    _mm_castsi128_ps(_mm_cmpeq_epi32( \
        _mm_and_si128(_mm_castps_si128(a), _mm_set1_epi32(0x7f800000)), \
        _mm_set1_epi32(0x7f800000)))
#define sbl__posinf(a) \
    _mm_castsi128_ps(_mm_cmpeq_epi32(_mm_castps_si128(a), _mm_set1_epi32(0x7f800000)))
/* n / a as the float division gives it, also under -ffast-math (which lets gcc replace
   a float vector division by a reciprocal estimate): divided in double and rounded once
   more, which for a quotient of floats is the correctly rounded float (53 >= 2 * 24 + 2) */
SBL__INLINE __m128 sbl__div_exact(__m128 n, __m128 a)
{
    const __m128 lo = _mm_cvtpd_ps(_mm_div_pd(_mm_cvtps_pd(n), _mm_cvtps_pd(a)));
    const __m128 hi = _mm_cvtpd_ps(_mm_div_pd(_mm_cvtps_pd(_mm_movehl_ps(n, n)),
                                              _mm_cvtps_pd(_mm_movehl_ps(a, a))));
    return _mm_movelh_ps(lo, hi);
}
/* sbl__lane_value_ok per lane, on the bits b of |a|: b == 0, or the exponent in
   [87, 177), i.e. b - (87 << 23) below (90 << 23) unsigned, compared signed with the top
   bit flipped: b + 0x54800000 < 0xad000000 (= -0x53000000) */
SBL__INLINE __m128 sbl__lane_ok(__m128 a)
{
    const __m128i b = _mm_and_si128(_mm_castps_si128(a), _mm_set1_epi32(0x7fffffff));
    return _mm_castsi128_ps(_mm_or_si128(
        _mm_cmpeq_epi32(b, _mm_setzero_si128()),
        _mm_cmpgt_epi32(_mm_set1_epi32(-0x53000000), _mm_add_epi32(b, _mm_set1_epi32(0x54800000)))));
}
/* floor of |a| < 2^31 (SSE2 has no rounding mode op): truncate, then step down */
SBL__INLINE __m128 sbl__floor(__m128 a)
{
    const __m128 t = _mm_cvtepi32_ps(_mm_cvttps_epi32(a));
    return _mm_sub_ps(t, _mm_and_ps(_mm_cmpgt_ps(t, a), _mm_set1_ps(1.0f)));
}
#elif !defined(SBL_NO_SIMD) && defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>
#define SBL_SIMD_NAME "neon"
#define SBL__VW 4
typedef float32x4_t sbl__v;
typedef uint32x4_t sbl__m;
#define sbl__set1(a) vdupq_n_f32(a)
#define sbl__load(p) vld1q_f32(p)
#define sbl__store(p, a) vst1q_f32(p, a)
#define sbl__add(a, b) vaddq_f32(a, b)
#define sbl__sub(a, b) vsubq_f32(a, b)
#define sbl__mul(a, b) vmulq_f32(a, b)
#define sbl__div(a, b) vdivq_f32(a, b)
#define sbl__min(a, b) vminq_f32(a, b)
#define sbl__max(a, b) vmaxq_f32(a, b)
#define sbl__sqrt(a) vsqrtq_f32(a)
#define sbl__abs(a) vabsq_f32(a)
#define sbl__gt(a, b) vcgtq_f32(a, b)
#define sbl__sel(m, a, b) vbslq_f32(m, a, b)
#define sbl__all(m) (vminvq_u32(m) != 0u)
#define sbl__true vdupq_n_u32(0xffffffffu)
#else
#define SBL_SIMD_NAME "scalar"
#define SBL__VW 1
typedef float sbl__v;
typedef int sbl__m;
#define sbl__set1(a) (a)
#define sbl__load(p) (*(p))
#define sbl__store(p, a) (*(p) = (a))
#define sbl__add(a, b) ((a) + (b))
#define sbl__sub(a, b) ((a) - (b))
#define sbl__mul(a, b) ((a) * (b))
#define sbl__div(a, b) ((a) / (b))
#define sbl__min(a, b) ((a) < (b) ? (a) : (b))
#define sbl__max(a, b) ((a) > (b) ? (a) : (b))
#define sbl__sqrt(a) sqrtf(a)
#define sbl__abs(a) fabsf(a)
#define sbl__gt(a, b) ((a) > (b))
#define sbl__sel(m, a, b) ((m) ? (a) : (b))
#define sbl__all(m) ((m) != 0)
#define sbl__true 1
#endif

/* first = m ? a : b and second = m ? b : a per lane (the two ends of a lerp chosen
   by a mask): two selects, or on SSE2 (a select is three operations there) one select
   and one exclusive or: second = a ^ b ^ first */
#if !defined(SBL_NO_SIMD) && !defined(__AVX2__) && !defined(__AVX512F__) && \
    (defined(__SSE2__) || defined(_M_X64) || (defined(_M_IX86_FP) && _M_IX86_FP >= 2))
#define SBL__SEL2(m, a, b, first, second) \
    do { \
        const __m128 ab_ = _mm_xor_ps(a, b); \
        (first) = _mm_xor_ps(b, _mm_and_ps(m, ab_)); \
        (second) = _mm_xor_ps(ab_, first); \
    } while (0)
#else
#define SBL__SEL2(m, a, b, first, second) \
    do { \
        (first) = sbl__sel(m, a, b); \
        (second) = sbl__sel(m, b, a); \
    } while (0)
#endif

/* ---- the fused row kernel --------------------------------------------------
   Shared by the temporal filter and the stereo blend. Rows of the own estimate Y are
   deinterleaved into planes, and the other estimate x* (reprojected history or other
   eye) is gathered once per row, into a ring of three rows; the 3x3 statistics, the
   weight, the rectification, the blend and Eq. 5 then run over those planes:
   - the lane kernel (SIMD layer above) on interior pixels whose 3x3 window holds only
     values that are finite and within about [1e-12, 1e15] in magnitude (or 0), in
     float;
   - the reference path (sbl__blend_pixel, double) everywhere else: image borders
     (fewer than 9 neighbours), and pixels with a non-finite sample, an extreme
     magnitude or a denormal in their window ("unsafe", flagged per pixel at load).
   Each output pixel takes one of the two paths by a rule that depends only on the
   input, never on the row or column range nor on the vector width, so banded and
   tiled calls reproduce a whole-image call and every SIMD build the scalar one. */

typedef float (*sbl__gather_fn)(const void *ctx, int x, int y, float *out);
struct sbl__ring_row;
/* x*, N and validity of columns [xa, xb) of row y straight into a ring row, equal bit
   for bit to calling the pixel gather on each (one call per row: no pointer per pixel) */
typedef void (*sbl__row_gather_fn)(const void *ctx, struct sbl__ring_row *r, int y, int xa,
                                   int xb);

typedef struct sbl__ring_row {
    float *y[4];   /* own colour, one plane per channel                         */
    float *x[4];   /* x* per channel, 0 where invalid                           */
    float *n;      /* N of x*, 0 where invalid                                  */
    float *v;      /* 1 where x* is valid, else 0                               */
    unsigned char *unsafe; /* 1 where a value of the pixel is outside the lane range */
    int row;       /* image row held (-1: none)                                 */
    int unsafe_count; /* pixels flagged unsafe among the columns loaded          */
    int gather_flags; /* 1: the row gather flagged its own unsafe values (in registers,
                         as it wrote them), so sbl__ring_gather need not re-read them */
    int gather_unsafe; /* pixels that row gather newly flagged                  */
    int all_valid; /* sbl__kernel_run_span, after the load: 1 if x* is valid on every
                      loaded column (0: not known) */
    int inv_lo, inv_hi; /* the first and the last loaded column whose x* is not valid
                           (sbl__ring_note_valid; none: inv_lo > inv_hi) */
    /* the pooled estimator's evidence plane (temporal; sbl__evidence_gather): the
       history's plane gathered in the colour's plan, as one more 1-channel plane read
       with N's tap indices, weights, tests and fallback, stored as the ratio the pooled
       estimator reads (1 where there is none). e: where this load writes it (NULL: not
       wanted); e_plane: this row's plane; e_rp: the plane's reprojection (a copy of the
       colour's whose colour is the plane, laid out as N: sbl__evidence_fused_ok), for
       the lanes the colour's plan does not settle. */
    float *e, *e_plane;
    const sbl__temporal_rp *e_rp;
    /* the tail plane (2.4) gathered in the colour's plan the same way (one plane per
       channel, the rate and the variance, as sbl__tail_pixel stores them), read with N's
       tap indices doubled (sbl__tail_fused_ok): tl, where this load writes it (NULL:
       not wanted); tl_plane, this row's planes; tl_rp, the plane's reprojection */
    float *tl[2], *tl_plane[2];
    const sbl__temporal_rp *tl_rp;
} sbl__ring_row;

typedef struct sbl__kernel {
    int w, h, ch;
    sbl__weight_params wp;
    float n_cap;             /* cap on N_X and on the output N                    */
    int temporal;            /* reset writes N = 1 (temporal) or N_Y (stereo)     */
    int fill;                /* stereo fill: x* wherever it is valid              */
    const sbl_image *own;    /* Y                                                 */
    const sbl_image *own_n;  /* N_Y (NULL data: 1)                                */
    sbl__gather_fn gather;
    const void *gather_ctx;
    sbl__row_gather_fn gather_row; /* NULL: `gather` one pixel at a time          */
    sbl_image out, out_n, out_a; /* out_n / out_a data may be NULL                */
    float *stage[4], *stage_n, *stage_a;
    unsigned char *window_unsafe; /* per row: 1 where the 3x3 window holds an unsafe value */
    unsigned char *column_unsafe; /* per row: 1 where the column's three rows hold one */
    sbl__ring_row ring[3];
    /* column sums of one chunk of the lane kernel (sbl__lanes_columns): per channel a
       block of SBL__COL_PLANES planes (below), and the valid pairs per column */
    float *col[4];
    float *col_n;
    /* pooled estimator (sbl__row_pool): per column of row pool_row, each 3x3 block's
       bias energy, and the prior variance of the bias pooled from the blocks */
    double *pool_m2, *pool_se2; /* per column: a block's sum_c mean_c^2, sum_c se_c^2 (< 0: none) */
    float *pool_r;
    float *pool_col;         /* the lanes' planes of one chunk (SBL__POOL_PLANES)   */
    int pool_row;            /* row pool_r holds (-1: none: the ratio reads as 0)  */
    /* pooled estimator, evidence carried over frames (docs/ESTIMATORS.md 3.7; temporal
       only): evid_in / evid_out per column of row pool_row, the history's carried ratio
       gathered with the colour's taps (1 where it has none) and this frame's; NULL
       evid_out: no plane at all. evid_use: the history has the plane, so it enters r. */
    const void *evid_ctx;    /* the evidence plane's gather (sbl__temporal_rp); NULL: none */
    float *evid_in, *evid_out;
    int evid_use;
    sbl_image out_e;         /* the output plane (data NULL: not written)           */
    int evid_row;            /* 1: gather the plane with the row gather (evid_ring)  */
    sbl__ring_row evid_ring; /* its x[0] / n / v / unsafe planes                      */
    int rows_valid;          /* sbl__kernel_run_span: 1 if the three window rows are
                                all_valid (every chunk full); 0: the lanes look */
    /* 1: the ring rows carry the evidence plane, gathered in the colour's plan by
       sbl__ring_load (the rows in [evid_y0, evid_y1): every row, halo rows included,
       so that a row is gathered the same way in every band); sbl__evidence_gather points
       evid_in at the row's plane. 0: evid_in is evid_buf, filled by a pass of its own */
    int evid_fused, evid_y0, evid_y1;
    float *evid_buf;
    /* the image's border columns in the default configurations' lanes (sbl__lanes_edge):
       edge_ask, set by sbl__kernel_run_span per row, 1 / 2 for column 0 / w - 1 (its
       window safe); edge_done, what sbl__kernel_lanes_pooled computed (the rest take
       the reference path) */
    int edge_ask, edge_done;
    /* 1 / 2: the row in the lanes is the image's first / last (sbl__kernel_run_span);
       its window has two rows: the missing one is the other border-side row again
       (sbl__kernel_lanes_pooled_ch), counted out of the pairs (sbl__lanes_columns_cfg) */
    int edge_row;
    /* the region's prior probability of change (sbl__evidence_share, docs/ESTIMATORS.md
       3.10): the history's evidence plane as it is (NULL: none), the counts of its rows
       share_at - 1 whose R passes c_R (0: not counted), and for the row in hand ln M,
       the carried R's threshold c_R(M) and its garrote's (c_R(M) - 1)^2 */
    const sbl_image *evid_prev;
    /* the firefly limit's exceedances carried over frames (sbl_history.tail,
       docs/ESTIMATORS.md 2.4; temporal, robust and pooled): tail_on, the limit records
       each pixel's exceedance (tail_e: 1 or 0) and its squared excess over x* per
       channel (tail_d) for the output plane; tail_use, the history has the plane: its
       rate and variance, gathered with the colour's taps and pooled over the 3x3
       (tail_r, tail_t), widen the limit and floor Y's variance. Per column of the row
       in hand; tail_ring: the gathered rows y - 1 .. y + 1 (x[0] the rate, x[1] the
       variance). */
    int tail_on, tail_use;
    /* 1: the ring rows carry the plane, gathered in the colour's plan (ring[j].tl, every
       row as evid_fused's), and tail_ring is not used */
    int tail_fused;
    const void *tail_ctx;    /* the plane's gather (sbl__temporal_rp); NULL: none    */
    sbl__ring_row tail_ring[3];
    int tail_xa, tail_xb;    /* the columns the ring rows hold                       */
    float *tail_r, *tail_t, *tail_e, *tail_d;
    sbl_image out_tail;      /* the output plane (data NULL: not written)            */
    long share_cnt[3];
    int share_at[3];
    double evid_lnm, evid_thr, evid_garrote;
    /* the temporal reprojection whose fetch positions give the resampling blur's
       fractions (wp.blur; sbl__blur_terms) */
    const sbl__temporal_rp *blur_rp;
    /* the stereo blend's change evidence (pooled; sbl_eye.evidence, docs/ESTIMATORS.md
       6.15): per column of the row in hand, 1 where either eye's plane shows a change
       (sbl__stereo_evidence_row), else 0; NULL: neither eye gave a plane. sev_rp: the
       stereo reprojection, whose map finds the other eye's pixel */
    float *sev;
    const sbl_image *sev_own, *sev_other;
    const void *sev_rp;
} sbl__kernel;

/* the planes of a channel's column block, SBL__CHUNK_COLS floats each:
   A / B: sum of (y - y_top) and of its square over the column's three rows (y_top: the
   column's top sample); T: the column's pair shift (its first valid x* - y); DA / DB:
   sum of v (x* - y - t) and of its square; LO / HI: min / max of y (clamp only) */
enum { SBL__COL_A, SBL__COL_B, SBL__COL_T, SBL__COL_DA, SBL__COL_DB, SBL__COL_LO, SBL__COL_HI,
       SBL__COL_PLANES };
#define SBL__COLP(block, plane) ((block) + (plane) * SBL__CHUNK_COLS)
/* the chunk's planes as offsets from k->col[0] (floats; sbl__kernel_bind lays them out
   in one block): channel c's column sums, col_n, pool_col. The lanes address every plane
   from one pointer that moves with the column (constant displacements), not a plane
   pointer each, which the loops would reload from the stack on every vector. */
#define SBL__CHUNK_COL(c) ((c) * SBL__COL_PLANES * SBL__CHUNK_COLS)
#define SBL__CHUNK_COLN(ch) SBL__CHUNK_COL(ch)
#define SBL__CHUNK_POOL(ch) (SBL__CHUNK_COLN(ch) + SBL__CHUNK_COLS)

/* lane kernel chunk: columns per chunk, and floats per column plane (the chunk, its two
   neighbour columns, padding) */
#define SBL__CHUNK 128
#define SBL__CHUNK_COLS 144

/* sbl__row_pool's lanes: pixels per chunk, and floats per plane (the chunk and the
   SBL__POOL_REACH columns each side, padded); per channel three planes, then twenty */
#define SBL__POOL_CHUNK 128
#define SBL__POOL_COLS 144
#define SBL__POOL_PLANES(ch) (3 * (ch) + 20)

/* planes per ring row: 2 * channels + 2 float planes and one byte plane; staging:
   channels + 2 float planes and two byte planes; each plane padded to 64 bytes; the
   lane kernel's column sums: SBL__COL_PLANES * channels + 1 planes of SBL__CHUNK_COLS
   floats; the pooled estimator's lanes: SBL__POOL_PLANES(channels) of SBL__POOL_COLS */
static size_t sbl__plane_floats(int width)
{
    return (SBL__CAST(size_t, width) + 15u) & ~SBL__CAST(size_t, 15u);
}

static size_t sbl__kernel_scratch_size(int width, int channels)
{
    size_t pf;
    if (width <= 0 || channels < 1 || channels > 4 || width > INT_MAX / 8) return 0;
    pf = sbl__plane_floats(width);
    /* + 5 planes: the pooled estimator's per-column block statistics (two double
       planes) and its ratio */
    /* + 16 floats ahead of the first plane: the border lanes load column -1 of a ring
       row (a lane they then drop, sbl__lanes_y_channel), which must be memory */
    return SBL__CAST(size_t, 3 * (2 * channels + 2) + channels + 2 + 5) * pf * sizeof(float) + 5 * pf + 64 +
           16 * sizeof(float) +
           SBL__CAST(size_t, SBL__COL_PLANES * channels + 1) * SBL__CHUNK_COLS * sizeof(float) +
           SBL__CAST(size_t, SBL__POOL_PLANES(channels)) * SBL__POOL_COLS * sizeof(float);
}

static void *sbl__align64(void *p)
{
    size_t a = SBL__PCAST(size_t, p);
    return SBL__PCAST(void *, SBL__PCAST(char *, p) + ((64 - (a & 63)) & 63));
}

static void sbl__kernel_bind(sbl__kernel *k, void *scratch)
{
    size_t pf = sbl__plane_floats(k->w);
    float *p = SBL__PCAST(float *, sbl__align64(scratch)) + 16;
    int r, c;
    for (r = 0; r < 3; ++r) {
        for (c = 0; c < k->ch; ++c) { k->ring[r].y[c] = p; p += pf; }
        for (c = 0; c < k->ch; ++c) { k->ring[r].x[c] = p; p += pf; }
        k->ring[r].n = p; p += pf;
        k->ring[r].v = p; p += pf;
        k->ring[r].row = -1;
        k->ring[r].unsafe_count = 0;
    }
    for (c = 0; c < k->ch; ++c) { k->stage[c] = p; p += pf; }
    k->stage_n = p; p += pf;
    k->stage_a = p; p += pf;
    k->pool_m2 = SBL__PCAST(double *, p); p += 2 * pf; /* 64-byte aligned: fit for doubles */
    k->pool_se2 = SBL__PCAST(double *, p); p += 2 * pf;
    k->pool_r = p; p += pf;
    k->pool_row = -1;
    /* one block: the channels' column sums (consecutive), col_n, pool_col: the lanes read
       them at constant distances from col[0] (sbl__pool_planes_of, sbl__pool_lanes_blocks) */
    for (c = 0; c < k->ch; ++c) { k->col[c] = p; p += SBL__COL_PLANES * SBL__CHUNK_COLS; }
    k->col_n = p; p += SBL__CHUNK_COLS;
    k->pool_col = p; p += SBL__POOL_PLANES(k->ch) * SBL__POOL_COLS;
    {   /* byte planes last (pf is a multiple of 16: each stays 16-byte aligned) */
        unsigned char *b = SBL__PCAST(unsigned char *, p);
        for (r = 0; r < 3; ++r) { k->ring[r].unsafe = b; b += pf; }
        k->window_unsafe = b; b += pf;
        k->column_unsafe = b;
    }
}

/* 0, or finite with magnitude in [2^-40, 2^50) (about 9.1e-13 .. 1.1e15): squares and
   sums of nine of them, and squares of differences down to 2^-24 of them, stay normal
   floats, so the lane kernel needs no scaling and does no denormal arithmetic. Read
   off the exponent bits: one test, and immune to -ffast-math. */
static int sbl__lane_value_ok(float v)
{
    unsigned int bits, e;
    memcpy(&bits, &v, sizeof bits);
    e = (bits >> 23) & 0xffu;
    return (bits & 0x7fffffffu) == 0u || e - 87u < 90u;
}

/* SBL_SHORTCUTS: which adaptive shortcuts the passes may take, one bit each (default:
   15, all but the far tiles). For measuring them (bench/shortcuts.c, `make
   bench-shortcuts`): every one but the far tiles gives the general path's bits, so
   switching one off costs only time.
     1  void tiles                  2  tiles at rest               4  sky tiles
     8  full chunks: lane-kernel chunks whose window pairs are all valid run without the
        pair-validity selects (the fallback bookkeeping)
    16  far tiles of the parallel stereo rig (the other eye at the same pixel: not the
        same bits, see SBL__FAR_PX). Opt in (SBL_SHORTCUTS 31) since session 27: they
        are the one shortcut whose result may depend on the span a pixel is gathered in
        (a block of fewer than VW entries takes the exact pixel gather) and on the
        build, against the rule that no result does; they fire only on geometry beyond
        256 f b (13 km at f = 800 px, b = 6.5 cm) and save there 537 against 831 SSE2
        instructions per pixel of the stereo blend (bench/ipp.c with depth 2e4). */
#ifndef SBL_SHORTCUTS
#define SBL_SHORTCUTS 15
#endif

/* One gathered x* (N > 0: valid) into ring column x. */
SBL__INLINE void sbl__ring_put(sbl__ring_row *r, int x, float n, const float *v, int ch)
{
    int c, valid = n > 0.0f;
    r->n[x] = valid ? n : 0.0f;
    r->v[x] = valid ? 1.0f : 0.0f;
    for (c = 0; c < ch; ++c) r->x[c][x] = valid ? v[c] : 0.0f; /* v may be NULL if n <= 0 */
}

/* The evidence plane's value at target pixel (x, y) by the pixel gather (es: the
   reprojection whose colour is the plane): the gathered ratio, or 1 where no tap is
   valid (a reset: no evidence either way) or the value is not a ratio in (0, cap]. */
SBL__NOINLINE float sbl__evidence_pixel(const sbl__temporal_rp *es, int x, int y)
{
    float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    return sbl__temporal_rp_pixel(es, x, y, v) > 0.0f && v[0] > 0.0f &&
                   v[0] <= SBL__CAST(float, SBL__POOL_RATIO_CAP)
               ? v[0]
               : 1.0f;
}

/* A gathered tail-plane pixel into *rate / *var: its values where a tap was valid (ok)
   and they are a rate in (0, 1] and a finite variance > 0, else 0 (nothing seen; the
   comparisons fail for a NaN). The scalar form of every tail gather's test. */
SBL__INLINE void sbl__tail_put(float *rate, float *var, int ok, float r, float t)
{
    *rate = ok && r > 0.0f && r <= 1.0f ? r : 0.0f;
    *var = ok && t > 0.0f && t <= FLT_MAX ? t : 0.0f;
}

#ifdef SBL__ROW_GATHER
/* The tail plane's values at target pixel (x, y) by the pixel gather (r->tl_rp: the
   reprojection whose colour is the plane) into ring column x of r->tl: the gathered rate
   and variance, 0 where no tap is valid (a reset: nothing seen) or a value is not one
   (sbl__tail_gather_row's test). */
SBL__NOINLINE void sbl__tail_pixel(sbl__ring_row *r, int x, int y)
{
    float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const int ok = sbl__temporal_rp_pixel(r->tl_rp, x, y, v) > 0.0f;
    sbl__tail_put(r->tl[0] + x, r->tl[1] + x, ok, v[0], v[1]);
}

/* 1 if every lane of the vectors v[0 .. cnt) holds a safe value (sbl__lane_value_ok)
   other than 0, in one test for them all: the largest |bits| below those of 2^50 and the
   smallest at least those of 2^-40 (a NaN's or an inf's bits lie above every finite
   value's). 0: some lane needs sbl__lane_ok (a 0, which is safe, lands there). */
SBL__INLINE int sbl__all_safe(const sbl__v *v, int cnt)
{
#if SBL__VW == 4
    /* (SSE2 has no unsigned 32-bit min / max: the high 16 bits of |bits|, which hold the
       exponent, as signed 16-bit lanes, two vectors per pack; the limits' low 16 bits
       are 0, so the test on them is the same) */
    const __m128i m = _mm_set1_epi32(0x7fffffff);
    __m128i hi, lo, a, b;
    int k;
    a = _mm_srli_epi32(_mm_and_si128(_mm_castps_si128(v[0]), m), 16);
    b = cnt > 1 ? _mm_srli_epi32(_mm_and_si128(_mm_castps_si128(v[1]), m), 16) : a;
    hi = lo = _mm_packs_epi32(a, b); /* (no saturation: below 0x8000) */
    for (k = 2; k < cnt; k += 2) {
        a = _mm_srli_epi32(_mm_and_si128(_mm_castps_si128(v[k]), m), 16);
        b = k + 1 < cnt ? _mm_srli_epi32(_mm_and_si128(_mm_castps_si128(v[k + 1]), m), 16) : a;
        a = _mm_packs_epi32(a, b);
        hi = _mm_max_epi16(hi, a);
        lo = _mm_min_epi16(lo, a);
    }
    a = _mm_or_si128(_mm_cmpgt_epi16(hi, _mm_set1_epi16(0x587f)), _mm_cmpgt_epi16(_mm_set1_epi16(0x2b80), lo));
    return !_mm_movemask_epi8(a);
#elif SBL__VW == 8
    const __m256i m = _mm256_set1_epi32(0x7fffffff);
    __m256i hi = _mm256_and_si256(_mm256_castps_si256(v[0]), m), lo = hi, b;
    int k;
    for (k = 1; k < cnt; ++k) {
        b = _mm256_and_si256(_mm256_castps_si256(v[k]), m);
        hi = _mm256_max_epu32(hi, b);
        lo = _mm256_min_epu32(lo, b);
    }
    /* hi >= bits(2^50) = 0x58800000 or lo < bits(2^-40) = 0x2b800000 (signed compares
       of values below 2^31) */
    b = _mm256_or_si256(_mm256_cmpgt_epi32(hi, _mm256_set1_epi32(0x587fffff)),
                        _mm256_cmpgt_epi32(_mm256_set1_epi32(0x2b800000), lo));
    return _mm256_testz_si256(b, b);
#else
    const __m512i m = _mm512_set1_epi32(0x7fffffff);
    __m512i hi = _mm512_and_si512(_mm512_castps_si512(v[0]), m), lo = hi, b;
    int k;
    for (k = 1; k < cnt; ++k) {
        b = _mm512_and_si512(_mm512_castps_si512(v[k]), m);
        hi = _mm512_max_epu32(hi, b);
        lo = _mm512_min_epu32(lo, b);
    }
    return !(_mm512_cmpgt_epi32_mask(hi, _mm512_set1_epi32(0x587fffff)) |
             _mm512_cmpgt_epi32_mask(_mm512_set1_epi32(0x2b800000), lo));
#endif
}
#endif

#ifdef SBL__ROW_GATHER
/* Ring columns x + l (bit l of bits) hold a valid x* with an unsafe value: flag the ones
   the own colour did not (rare; the row gathers that flag as they write). */
static void sbl__ring_flag_bits(sbl__ring_row *r, int x, int bits)
{
    int l;
    for (l = 0; bits; ++l, bits >>= 1)
        if ((bits & 1) && !r->unsafe[x + l]) { r->unsafe[x + l] = 1; ++r->gather_unsafe; }
}

/* sbl__ring_put, flagging the pixel if its valid x* holds an unsafe value (the check of
   sbl__ring_gather, done while the values are at hand) */
static void sbl__ring_put_flag(sbl__ring_row *r, int x, float n, const float *v, int ch)
{
    int c, safe = 1;
    sbl__ring_put(r, x, n, v, ch);
    if (!(r->v[x] > 0.0f)) return;
    for (c = 0; c < ch; ++c) safe &= sbl__lane_value_ok(r->x[c][x]);
    safe &= sbl__lane_value_ok(r->n[x]);
    if (!safe) sbl__ring_flag_bits(r, x, 1);
}
#endif

/* The motion vectors of pixels [x, x + VW) of a packed motion plane (pixel step 2, at
   mvp) as one vector of x and one of y components: two loads and shuffles (a gather would
   be a load per lane on SSE2, and costs more than the loads and permutes on AVX-512:
   sbl__gather_pairs), a copy elsewhere */
SBL__INLINE void sbl__motion_packed_lanes(const float *mvp, sbl__v *mx, sbl__v *my)
{
#if SBL__VW == 4 && defined(SBL__ROW_GATHER)
    const __m128 a = _mm_loadu_ps(mvp), b = _mm_loadu_ps(mvp + 4);
    *mx = _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0));
    *my = _mm_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1));
#elif SBL__VW == 8
    const __m256 a = _mm256_loadu_ps(mvp), b = _mm256_loadu_ps(mvp + 8);
    /* per 128-bit half (x0 x1 x4 x5 | x2 x3 x6 x7), then the 64-bit pairs in order */
    *mx = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0))),
                                                 _MM_SHUFFLE(3, 1, 2, 0)));
    *my = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1))),
                                                 _MM_SHUFFLE(3, 1, 2, 0)));
#elif SBL__VW == 16
    const __m512 a = _mm512_loadu_ps(mvp), b = _mm512_loadu_ps(mvp + 16);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    *mx = _mm512_permutex2var_ps(a, even, b);
    *my = _mm512_permutex2var_ps(a, _mm512_add_epi32(even, _mm512_set1_epi32(1)), b);
#else
    float fx[SBL__VW], fy[SBL__VW];
    int l;
    for (l = 0; l < SBL__VW; ++l) { fx[l] = mvp[2 * l]; fy[l] = mvp[2 * l + 1]; }
    *mx = sbl__load(fx);
    *my = sbl__load(fy);
#endif
}

#ifdef SBL__ROW_GATHER
/* ---- the row gather ---------------------------------------------------------
   A scalar pass plans a block of pixels (target tests, source position, floor and
   fraction, the offset of the first tap in each source view; the same code as the
   pixel gather); the taps, their tests and the renormalised bilinear weights then run
   in lanes. Lanes the pixel gather would send anywhere but its fast path (a tap
   outside the image, a rejected footprint that needs the 3x3 fallback, a NaN or inf
   in a sum) are redone by the pixel gather. */
#define SBL__BLOCK 64

/* Double lanes for the row gather: the camera maps (sbl__cam_map_apply: unproject at
   the target's depth, carry into the other view, project) with the reference's
   operations in its order, so every lane gets its bits, and the tap indices (y0 stride
   + x0 step, exact in double). A few operations suffice: set1, load, store, add, sub,
   mul, div; SBL__DW floats in (sbl__dfromf: from VW + 4 readable floats), SBL__DW ints
   out (sbl__dstorei, truncating; the values are integers), SBL__DW floats out
   (sbl__dstoref, rounded as a cast); floor; min / max (x86: the second operand where one
   is NaN); bit masks of a <= b and a < b; x, or +inf where t is 0 (sbl__dinf_at0). And
   the comparisons as lane masks (sbl__dm: a <= b, a < b; and, or, a and not b), made
   bits once (sbl__dm_bits). */
#if SBL__VW == 16
#define SBL__DW 8
typedef __m512d sbl__dv;
#define sbl__dset1(a) _mm512_set1_pd(a)
#define sbl__dload(p) _mm512_loadu_pd(p)
#define sbl__dstore(p, a) _mm512_storeu_pd(p, a)
#define sbl__dadd(a, b) _mm512_add_pd(a, b)
#define sbl__dsub(a, b) _mm512_sub_pd(a, b)
#define sbl__dmul(a, b) _mm512_mul_pd(a, b)
#define sbl__ddiv(a, b) _mm512_div_pd(a, b)
#define sbl__dfromf(p) _mm512_cvtps_pd(_mm256_loadu_ps(p))
#define sbl__dstorei(q, a) _mm256_storeu_si256(SBL__PCAST(__m256i *, q), _mm512_cvttpd_epi32(a))
#define sbl__dmin(a, b) _mm512_min_pd(a, b)
#define sbl__dmax(a, b) _mm512_max_pd(a, b)
#define sbl__dle_bits(a, b) SBL__CAST(int, _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ))
#define sbl__dlt_bits(a, b) SBL__CAST(int, _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ))
typedef __mmask8 sbl__dm;
#define sbl__dle_m(a, b) _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ)
#define sbl__dlt_m(a, b) _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ)
#define sbl__dm_and(a, b) SBL__CAST(__mmask8, (a) & (b))
#define sbl__dm_or(a, b) SBL__CAST(__mmask8, (a) | (b))
#define sbl__dm_andnot(a, b) SBL__CAST(__mmask8, (a) & ~(b))
#define sbl__dm_bits(m) SBL__CAST(int, m)
#define sbl__dinf_at0(x, t) _mm512_mask_blend_pd(_mm512_cmp_pd_mask(t, _mm512_setzero_pd(), _CMP_EQ_OQ), x, _mm512_set1_pd(HUGE_VAL))
#define sbl__dfloor(a) _mm512_roundscale_pd(a, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)
#define sbl__dstoref(q, a) _mm256_storeu_ps(q, _mm512_cvtpd_ps(a))
#elif SBL__VW == 8
#define SBL__DW 4
typedef __m256d sbl__dv;
#define sbl__dset1(a) _mm256_set1_pd(a)
#define sbl__dload(p) _mm256_loadu_pd(p)
#define sbl__dstore(p, a) _mm256_storeu_pd(p, a)
#define sbl__dadd(a, b) _mm256_add_pd(a, b)
#define sbl__dsub(a, b) _mm256_sub_pd(a, b)
#define sbl__dmul(a, b) _mm256_mul_pd(a, b)
#define sbl__ddiv(a, b) _mm256_div_pd(a, b)
#define sbl__dfromf(p) _mm256_cvtps_pd(_mm_loadu_ps(p))
#define sbl__dstorei(q, a) _mm_storeu_si128(SBL__PCAST(__m128i *, q), _mm256_cvttpd_epi32(a))
#define sbl__dmin(a, b) _mm256_min_pd(a, b)
#define sbl__dmax(a, b) _mm256_max_pd(a, b)
#define sbl__dle_bits(a, b) _mm256_movemask_pd(_mm256_cmp_pd(a, b, _CMP_LE_OQ))
#define sbl__dlt_bits(a, b) _mm256_movemask_pd(_mm256_cmp_pd(a, b, _CMP_LT_OQ))
typedef __m256d sbl__dm;
#define sbl__dle_m(a, b) _mm256_cmp_pd(a, b, _CMP_LE_OQ)
#define sbl__dlt_m(a, b) _mm256_cmp_pd(a, b, _CMP_LT_OQ)
#define sbl__dm_and(a, b) _mm256_and_pd(a, b)
#define sbl__dm_or(a, b) _mm256_or_pd(a, b)
#define sbl__dm_andnot(a, b) _mm256_andnot_pd(b, a)
#define sbl__dm_bits(m) _mm256_movemask_pd(m)
#define sbl__dinf_at0(x, t) _mm256_blendv_pd(x, _mm256_set1_pd(HUGE_VAL), _mm256_cmp_pd(t, _mm256_setzero_pd(), _CMP_EQ_OQ))
#define sbl__dfloor(a) _mm256_floor_pd(a)
#define sbl__dstoref(q, a) _mm_storeu_ps(q, _mm256_cvtpd_ps(a))
#else
#define SBL__DW 2
typedef __m128d sbl__dv;
#define sbl__dset1(a) _mm_set1_pd(a)
#define sbl__dload(p) _mm_loadu_pd(p)
#define sbl__dstore(p, a) _mm_storeu_pd(p, a)
#define sbl__dadd(a, b) _mm_add_pd(a, b)
#define sbl__dsub(a, b) _mm_sub_pd(a, b)
#define sbl__dmul(a, b) _mm_mul_pd(a, b)
#define sbl__ddiv(a, b) _mm_div_pd(a, b)
#define sbl__dfromf(p) _mm_cvtps_pd(_mm_loadu_ps(p))
#define sbl__dstorei(q, a) _mm_storel_epi64(SBL__PCAST(__m128i *, q), _mm_cvttpd_epi32(a))
#define sbl__dmin(a, b) _mm_min_pd(a, b)
#define sbl__dmax(a, b) _mm_max_pd(a, b)
#define sbl__dle_bits(a, b) _mm_movemask_pd(_mm_cmple_pd(a, b))
#define sbl__dlt_bits(a, b) _mm_movemask_pd(_mm_cmplt_pd(a, b))
typedef __m128d sbl__dm;
#define sbl__dle_m(a, b) _mm_cmple_pd(a, b)
#define sbl__dlt_m(a, b) _mm_cmplt_pd(a, b)
#define sbl__dm_and(a, b) _mm_and_pd(a, b)
#define sbl__dm_or(a, b) _mm_or_pd(a, b)
#define sbl__dm_andnot(a, b) _mm_andnot_pd(b, a)
#define sbl__dm_bits(m) _mm_movemask_pd(m)
SBL__INLINE __m128d sbl__dinf_at0(__m128d x, __m128d t)
{
    const __m128d m = _mm_cmpeq_pd(t, _mm_setzero_pd());
    return _mm_or_pd(_mm_and_pd(m, _mm_set1_pd(HUGE_VAL)), _mm_andnot_pd(m, x));
}
/* (SSE2 has no floor: truncate, then one less where that rounded up; exact for |a| <
   2^31; larger, NaN or infinite values give a value the callers do not use) */
SBL__INLINE __m128d sbl__dfloor(__m128d a)
{
    const __m128d t = _mm_cvtepi32_pd(_mm_cvttpd_epi32(a));
    return _mm_sub_pd(t, _mm_and_pd(_mm_cmpgt_pd(t, a), _mm_set1_pd(1.0)));
}
#define sbl__dstoref(q, a) _mm_storel_pi(SBL__PCAST(__m64 *, q), _mm_cvtpd_ps(a))
#endif

/* (every path's float vector is two double vectors: sbl__cam_lanes_in) */
typedef char sbl__vw_is_two_dw[SBL__VW == 2 * SBL__DW ? 1 : -1];

/* Each lane's index (x + index: the lanes' columns), as float lanes and as double lanes
   (SBL__DW <= 8). */
static const float sbl__lane_f[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
static const double sbl__lane_d[8] = {0, 1, 2, 3, 4, 5, 6, 7};

/* sbl__gather_fallback_ch for the source's channel count (the row gather's fallback-only
   lanes). */
static float sbl__gather_fallback(const sbl__tap_src *s, const sbl__tap_want *t, double sx,
                                  double sy, float *out)
{
    switch (s->color.ch) {
    case 1: return sbl__gather_fallback_ch(s, t, sx, sy, out, 1);
    case 2: return sbl__gather_fallback_ch(s, t, sx, sy, out, 2);
    case 3: return sbl__gather_fallback_ch(s, t, sx, sy, out, 3);
    default: return sbl__gather_fallback_ch(s, t, sx, sy, out, 4);
    }
}

typedef struct sbl__tap_plan {
    int ci[SBL__BLOCK], di[SBL__BLOCK], li[SBL__BLOCK]; /* tap (x0, y0) in colour, depth, N */
    float fx[SBL__BLOCK], fy[SBL__BLOCK];               /* bilinear fractions              */
    float depth[SBL__BLOCK], slack[SBL__BLOCK];         /* expected depth and its slack    */
    float fast[SBL__BLOCK];         /* 1: four taps inside the image (lanes); 0: reset / redo */
    /* 1: the pixel gather decides; 2: the taps (summed, finite) weigh below 1e-3, only
       the 3x3 fallback is left (sbl__fallback_lanes, else the pixel gather) */
    unsigned char redo[SBL__BLOCK];
    /* 1 at entry i: entries i .. i + VW - 1 are fast and their first taps consecutive
       pixels in every view (planned so together: uniform integer motion); 3: the same,
       and every depth limit finite with no lane expecting sky (sbl__row_taps_ch's
       "full"); 2: planned together and not so (0: unknown) */
    unsigned char uniform[SBL__BLOCK];
    int lane_step[5][SBL__VW];      /* l * pixel step of colour, depth, N, normals, ids (set per call) */
    /* the normal and id tests (sbl__lanes_nid_ok), where the call runs them: tap (x0, y0)
       in the normals and the ids, the target's normal, its squared length and its id */
    int ni[SBL__BLOCK], ii[SBL__BLOCK];
    float tn[3][SBL__BLOCK], tn2[SBL__BLOCK], tid[SBL__BLOCK];
} sbl__tap_plan;

/* ---- the normal and id tests in lanes ------------------------------------------
   sbl__tap_ok_id_normal for VW plan entries at once: the plan carries each entry's
   target normal, its squared length and its id (as sbl__tap_want_init formed them) and
   the taps' indices in the source's normals and ids. */

/* an entry without normal / id test data: tap (0, 0) (a valid address), "no normal" */
SBL__INLINE void sbl__tap_plan_reset_nid(sbl__tap_plan *p, int i)
{
    p->ni[i] = p->ii[i] = 0;
    p->tn[0][i] = p->tn[1][i] = p->tn[2][i] = p->tn2[i] = p->tid[i] = 0.0f;
}

/* entry i's normal / id data from the target's expectations t, footprint at (x0, y0) */
SBL__INLINE void sbl__tap_plan_set_nid(const sbl__tap_src *s, sbl__tap_plan *p, int i,
                                       const sbl__tap_want *t, int x0, int y0)
{
    if (s->use_normal) { /* (the target has normals: t->normal is set) */
        p->ni[i] = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * s->normals.stride + SBL__CAST(ptrdiff_t, x0) * s->normals.step);
        p->tn[0][i] = t->normal[0];
        p->tn[1][i] = t->normal[1];
        p->tn[2][i] = t->normal[2];
        p->tn2[i] = t->normal_len2;
    }
    if (s->use_id) {
        p->ii[i] = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * s->ids.stride + SBL__CAST(ptrdiff_t, x0) * s->ids.step);
        p->tid[i] = t->id;
    }
}

/* The target's expectations of plan entry i for the pixel gather's fallback: depth and
   slack as given, normal (into nbuf) and id from the plan where the call tests them. */
SBL__INLINE void sbl__tap_plan_want(const sbl__tap_src *s, const sbl__tap_plan *p, int i,
                                    sbl__tap_want *t, float *nbuf)
{
    t->normal = NULL;
    t->normal_len2 = 0.0f;
    t->id = 0.0f;
    if (!p) return;
    if (s->use_normal) {
        nbuf[0] = p->tn[0][i];
        nbuf[1] = p->tn[1][i];
        nbuf[2] = p->tn[2][i];
        t->normal = nbuf;
        t->normal_len2 = p->tn2[i];
    }
    if (s->use_id) t->id = p->tid[i];
}

static void sbl__tap_plan_reset(sbl__tap_plan *p, int i)
{
    p->ci[i] = p->di[i] = p->li[i] = 0; /* tap (0, 0): a valid address, result unused */
    p->fx[i] = p->fy[i] = 0.0f;
    p->depth[i] = 1.0f;
    p->slack[i] = 0.0f;
    p->fast[i] = 0.0f;
    p->redo[i] = 0;
    p->uniform[i] = 0;
    sbl__tap_plan_reset_nid(p, i);
}

/* Plan entry i from a source position, as sbl__gather_ch decides: 0 reset, else the
   fast path or (p->redo) the pixel gather. */
SBL__INLINE void sbl__tap_plan_set(const sbl__tap_src *s, sbl__tap_plan *p, int i,
                                   const sbl__tap_want *t, double sx, double sy)
{
    double bx = sx - 0.5, by = sy - 0.5;
    int x0, y0;
    if (!(bx > -2.0 && by > -2.0 && bx < SBL__CAST(double, s->width) + 1.0 &&
          by < SBL__CAST(double, s->height) + 1.0))
        return;
    x0 = SBL__CAST(int, floor(bx));
    y0 = SBL__CAST(int, floor(by));
    if (!(x0 >= 0 && y0 >= 0 && x0 + 1 < s->width && y0 + 1 < s->height)) {
        p->redo[i] = 1;
        return;
    }
    p->fx[i] = SBL__CAST(float, bx - x0);
    p->fy[i] = SBL__CAST(float, by - y0);
    p->depth[i] = t->depth;
    p->slack[i] = t->depth_slack;
    p->ci[i] = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * s->color.stride + SBL__CAST(ptrdiff_t, x0) * s->color.step);
    if (s->use_depth)
        p->di[i] = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * s->depth.stride + SBL__CAST(ptrdiff_t, x0) * s->depth.step);
    if (s->length.p)
        p->li[i] = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * s->length.stride + SBL__CAST(ptrdiff_t, x0) * s->length.step);
    if (s->use_normal || s->use_id) sbl__tap_plan_set_nid(s, p, i, t, x0, y0);
    p->fast[i] = 1.0f;
}

#if SBL__VW == 4
/* Four consecutive packed RGB pixels (12 floats, in a, c, e in memory order) to one
   vector per channel: seven shuffles (SSE2 emulates a gather with four loads); sbl__rgb4
   with the three loads. */
SBL__INLINE void sbl__rgb4_split(__m128 a, __m128 c, __m128 e, __m128 *r, __m128 *g, __m128 *b)
{
    const __m128 rr = _mm_shuffle_ps(c, e, _MM_SHUFFLE(0, 1, 0, 2));  /* r2 . r3 .    */
    const __m128 g01 = _mm_shuffle_ps(a, c, _MM_SHUFFLE(0, 0, 1, 1)); /* g0 g0 g1 g1 */
    const __m128 g23 = _mm_shuffle_ps(c, e, _MM_SHUFFLE(2, 2, 3, 3)); /* g2 g2 g3 g3 */
    const __m128 b01 = _mm_shuffle_ps(a, c, _MM_SHUFFLE(1, 1, 2, 2)); /* b0 b0 b1 b1 */
    *r = _mm_shuffle_ps(a, rr, _MM_SHUFFLE(2, 0, 3, 0));
    *g = _mm_shuffle_ps(g01, g23, _MM_SHUFFLE(2, 0, 2, 0));
    *b = _mm_shuffle_ps(b01, e, _MM_SHUFFLE(3, 0, 2, 0));
}
SBL__INLINE void sbl__rgb4(const float *p, __m128 *r, __m128 *g, __m128 *b)
{
    sbl__rgb4_split(_mm_loadu_ps(p), _mm_loadu_ps(p + 4), _mm_loadu_ps(p + 8), r, g, b);
}
#endif

#if SBL__VW >= 8
/* Eight consecutive packed RGB pixels (24 floats) to one 8-float vector per channel:
   sbl__rgb4's shuffles in each 128-bit half (pixels 0-3 low, 4-7 high; a, c, e as
   sbl__rgb8 loads them). Loads and shuffles instead of three gathers (slow on current
   x86). */
SBL__INLINE void sbl__rgb8_split(__m256 a, __m256 c, __m256 e, __m256 *r, __m256 *g, __m256 *b)
{
    const __m256 rr = _mm256_shuffle_ps(c, e, _MM_SHUFFLE(0, 1, 0, 2));
    const __m256 g01 = _mm256_shuffle_ps(a, c, _MM_SHUFFLE(0, 0, 1, 1));
    const __m256 g23 = _mm256_shuffle_ps(c, e, _MM_SHUFFLE(2, 2, 3, 3));
    const __m256 b01 = _mm256_shuffle_ps(a, c, _MM_SHUFFLE(1, 1, 2, 2));
    *r = _mm256_shuffle_ps(a, rr, _MM_SHUFFLE(2, 0, 3, 0));
    *g = _mm256_shuffle_ps(g01, g23, _MM_SHUFFLE(2, 0, 2, 0));
    *b = _mm256_shuffle_ps(b01, e, _MM_SHUFFLE(3, 0, 2, 0));
}
SBL__INLINE void sbl__rgb8(const float *p, __m256 *r, __m256 *g, __m256 *b)
{
    sbl__rgb8_split(_mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p)), _mm_loadu_ps(p + 12), 1),
                    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 4)), _mm_loadu_ps(p + 16), 1),
                    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(p + 8)), _mm_loadu_ps(p + 20), 1),
                    r, g, b);
}
/* sbl__rgb8 of the 24 floats held in memory order (v0: floats 0-7, v1: 8-15, v2: 16-23):
   its 128-bit halves (floats 0-3 with 12-15, 4-7 with 16-19, 8-11 with 20-23) by two
   blends and one lane permute */
SBL__INLINE void sbl__rgb8_of(__m256 v0, __m256 v1, __m256 v2, __m256 *r, __m256 *g, __m256 *b)
{
    sbl__rgb8_split(_mm256_blend_ps(v0, v1, 0xf0), _mm256_permute2f128_ps(v0, v2, 0x21),
                    _mm256_blend_ps(v1, v2, 0xf0), r, g, b);
}
#endif

/* VW consecutive packed RGB pixels (3 VW floats) to one vector per channel. */
SBL__INLINE void sbl__rgb_lanes(const float *p, sbl__v *r, sbl__v *g, sbl__v *b)
{
#if SBL__VW == 4
    sbl__rgb4(p, r, g, b);
#elif SBL__VW == 8
    sbl__rgb8(p, r, g, b);
#else
    __m256 r0, g0, b0, r1, g1, b1;
    sbl__rgb8(p, &r0, &g0, &b0);
    sbl__rgb8(p + 24, &r1, &g1, &b1);
    *r = sbl__join8(r0, r1);
    *g = sbl__join8(g0, g1);
    *b = sbl__join8(b0, b1);
#endif
}

/* sbl__rgb_lanes of the 3 VW floats held in registers in memory order (v[0]: floats
   0 .. VW - 1, v[1] the next VW, v[2] the last): the same values, without the loads */
SBL__INLINE void sbl__rgb_lanes_of(const sbl__v *v, sbl__v *r, sbl__v *g, sbl__v *b)
{
#if SBL__VW == 4
    sbl__rgb4_split(v[0], v[1], v[2], r, g, b);
#elif SBL__VW == 8
    sbl__rgb8_of(v[0], v[1], v[2], r, g, b);
#else
#define SBL__LO8(a) _mm512_castps512_ps256(a)
#define SBL__HI8(a) _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a), 1))
    __m256 r0, g0, b0, r1, g1, b1;
    sbl__rgb8_of(SBL__LO8(v[0]), SBL__HI8(v[0]), SBL__LO8(v[1]), &r0, &g0, &b0);
    sbl__rgb8_of(SBL__HI8(v[1]), SBL__LO8(v[2]), SBL__HI8(v[2]), &r1, &g1, &b1);
#undef SBL__LO8
#undef SBL__HI8
    *r = sbl__join8(r0, r1);
    *g = sbl__join8(g0, g1);
    *b = sbl__join8(b0, b1);
#endif
}

/* Taps (x0, y0) and (x0 + 1, y0) of VW lanes at once where a view's pixels are packed
   (pixel step = its channel count nf): the 2 nf floats from each lane's index, split into
   out[0 .. 2 nf): out[c] is channel c of tap x0, out[nf + c] of tap x0 + 1, i.e. out[j]
   is float j of every lane's run. Each lane's run is read with plain loads (4 floats, 2
   floats: exactly its 2 nf floats, the addresses a gather would read) and the lanes are
   transposed in registers. Hardware gathers did the same in nf gathers of float pairs
   until session 18: on the machine measured (an AMD EPYC with AVX-512) a gather costs far
   more than its loads (make bench-gather: nf = 3, 3.4x at 16 lanes, 3.6x at 8; Intel's
   gathers are said to be slow since the Downfall (GDS) microcode, not measured here).
   Callgrind counts each gather as one instruction, so the counts rise (hard case, AVX2
   +14 per pixel) where the time falls. SBL__PAIRS 0 turns the pairs off (float taps). */
#ifndef SBL__PAIRS
#define SBL__PAIRS 1
#endif
#if SBL__VW == 16 || SBL__VW == 8
/* lanes l, l + 4 (, l + 8, l + 12) of a run's 4 floats at offset o, one 128-bit block each */
SBL__INLINE sbl__v sbl__quad_lanes(const float *base, const int *idx, int l, int o)
{
#if SBL__VW == 16
    const __m256 lo = _mm256_set_m128(_mm_loadu_ps(base + idx[l + 4] + o), _mm_loadu_ps(base + idx[l] + o));
    const __m256 hi = _mm256_set_m128(_mm_loadu_ps(base + idx[l + 12] + o), _mm_loadu_ps(base + idx[l + 8] + o));
    return sbl__join8(lo, hi);
#else
    return _mm256_set_m128(_mm_loadu_ps(base + idx[l + 4] + o), _mm_loadu_ps(base + idx[l] + o));
#endif
}
/* the 2 floats at offset o of lanes l and l + 1 (low, high half of a 128-bit block) */
SBL__INLINE __m128 sbl__two_pairs(const float *base, const int *idx, int l, int o)
{
    const __m128 a = _mm_castsi128_ps(_mm_loadl_epi64(SBL__PCAST(const __m128i *, SBL__PCAST(const void *, base + idx[l] + o))));
    return _mm_loadh_pi(a, SBL__PCAST(const __m64 *, SBL__PCAST(const void *, base + idx[l + 1] + o)));
}
/* floats o .. o + 3 of every lane's run to out[0 .. 4): a 4x4 transpose per 128-bit
   block (block j holds lanes 4 j .. 4 j + 3) */
SBL__INLINE void sbl__lanes_quad(const float *base, const int *idx, int o, sbl__v *out)
{
    const sbl__v a = sbl__quad_lanes(base, idx, 0, o), b = sbl__quad_lanes(base, idx, 1, o);
    const sbl__v c = sbl__quad_lanes(base, idx, 2, o), d = sbl__quad_lanes(base, idx, 3, o);
#if SBL__VW == 16
#define SBL__UNPK_PS(f, x, y) _mm512_##f##_ps(x, y)
#define SBL__UNPK_PD(f, x, y) _mm512_castpd_ps(_mm512_##f##_pd(_mm512_castps_pd(x), _mm512_castps_pd(y)))
#else
#define SBL__UNPK_PS(f, x, y) _mm256_##f##_ps(x, y)
#define SBL__UNPK_PD(f, x, y) _mm256_castpd_ps(_mm256_##f##_pd(_mm256_castps_pd(x), _mm256_castps_pd(y)))
#endif
    const sbl__v t0 = SBL__UNPK_PS(unpacklo, a, b), t1 = SBL__UNPK_PS(unpackhi, a, b);
    const sbl__v t2 = SBL__UNPK_PS(unpacklo, c, d), t3 = SBL__UNPK_PS(unpackhi, c, d);
    out[0] = SBL__UNPK_PD(unpacklo, t0, t2);
    out[1] = SBL__UNPK_PD(unpackhi, t0, t2);
    out[2] = SBL__UNPK_PD(unpacklo, t1, t3);
    out[3] = SBL__UNPK_PD(unpackhi, t1, t3);
#undef SBL__UNPK_PS
#undef SBL__UNPK_PD
}
/* floats o, o + 1 of every lane's run to out[0], out[1]: e holds lanes (0 1 | 4 5 ..),
   f (2 3 | 6 7 ..) per 128-bit block; one shuffle takes each block's evens, one its odds */
SBL__INLINE void sbl__lanes_pair(const float *base, const int *idx, int o, sbl__v *out)
{
#if SBL__VW == 16
    const sbl__v e = sbl__join8(_mm256_set_m128(sbl__two_pairs(base, idx, 4, o), sbl__two_pairs(base, idx, 0, o)),
                                _mm256_set_m128(sbl__two_pairs(base, idx, 12, o), sbl__two_pairs(base, idx, 8, o)));
    const sbl__v f = sbl__join8(_mm256_set_m128(sbl__two_pairs(base, idx, 6, o), sbl__two_pairs(base, idx, 2, o)),
                                _mm256_set_m128(sbl__two_pairs(base, idx, 14, o), sbl__two_pairs(base, idx, 10, o)));
    out[0] = _mm512_shuffle_ps(e, f, _MM_SHUFFLE(2, 0, 2, 0));
    out[1] = _mm512_shuffle_ps(e, f, _MM_SHUFFLE(3, 1, 3, 1));
#else
    const sbl__v e = _mm256_set_m128(sbl__two_pairs(base, idx, 4, o), sbl__two_pairs(base, idx, 0, o));
    const sbl__v f = _mm256_set_m128(sbl__two_pairs(base, idx, 6, o), sbl__two_pairs(base, idx, 2, o));
    out[0] = _mm256_shuffle_ps(e, f, _MM_SHUFFLE(2, 0, 2, 0));
    out[1] = _mm256_shuffle_ps(e, f, _MM_SHUFFLE(3, 1, 3, 1));
#endif
}
SBL__INLINE void sbl__gather_pairs(const float *base, const int *idx, sbl__v *out, int nf)
{
    /* runs of 2 nf floats: 2 = a pair, 4 = a quad, 6 = quad + pair, 8 = two quads
       (out[2 k], out[2 k + 1] set where k < nf, as the callers read them) */
    if (nf > 1) sbl__lanes_quad(base, idx, 0, out);
    else sbl__lanes_pair(base, idx, 0, out);
    if (nf > 3) sbl__lanes_quad(base, idx, 4, out + 4);
    else if (nf > 2) sbl__lanes_pair(base, idx, 4, out + 4);
}
#else
SBL__INLINE void sbl__gather_pairs(const float *base, const int *idx, sbl__v *out, int nf)
{
    const int i0 = idx[0], i1 = idx[1], i2 = idx[2], i3 = idx[3];
#define SBL__PAIR(k) \
    { \
        const float *q = base + 2 * k; \
        const __m128 a = _mm_loadh_pi(_mm_loadl_pi(_mm_setzero_ps(), SBL__PCAST(const __m64 *, SBL__PCAST(const void *, q + i0))), \
                                      SBL__PCAST(const __m64 *, SBL__PCAST(const void *, q + i1))); \
        const __m128 b = _mm_loadh_pi(_mm_loadl_pi(_mm_setzero_ps(), SBL__PCAST(const __m64 *, SBL__PCAST(const void *, q + i2))), \
                                      SBL__PCAST(const __m64 *, SBL__PCAST(const void *, q + i3))); \
        out[2 * k] = _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0)); \
        out[2 * k + 1] = _mm_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1)); \
    }
    SBL__PAIR(0);
    if (nf > 1) SBL__PAIR(1);
    if (nf > 2) SBL__PAIR(2);
    if (nf > 3) SBL__PAIR(3);
#undef SBL__PAIR
}
#endif

/* VW consecutive packed 2-channel pixels (2 VW floats at p) to one vector per channel */
SBL__INLINE void sbl__lanes2(const float *p, sbl__v *a, sbl__v *b)
{
#if SBL__VW == 4
    const __m128 u = _mm_loadu_ps(p), v = _mm_loadu_ps(p + 4);
    *a = _mm_shuffle_ps(u, v, _MM_SHUFFLE(2, 0, 2, 0));
    *b = _mm_shuffle_ps(u, v, _MM_SHUFFLE(3, 1, 3, 1));
#elif SBL__VW == 8
    const __m256 u = _mm256_loadu_ps(p), v = _mm256_loadu_ps(p + 8);
    const __m256 lo = _mm256_permute2f128_ps(u, v, 0x20), hi = _mm256_permute2f128_ps(u, v, 0x31);
    *a = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
    *b = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
#else
    const __m512 u = _mm512_loadu_ps(p), v = _mm512_loadu_ps(p + 16);
    *a = _mm512_permutex2var_ps(u, _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30), v);
    *b = _mm512_permutex2var_ps(u, _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31), v);
#endif
}

/* NaN lanes, on the bits (-ffast-math may fold a float self-compare): |a| above the
   bits of +inf, compared as signed ints (both non-negative) */
SBL__INLINE sbl__m sbl__lanes_nan(sbl__v a)
{
#if SBL__VW == 16
    return _mm512_cmpgt_epi32_mask(_mm512_and_si512(_mm512_castps_si512(a), _mm512_set1_epi32(0x7fffffff)),
                                   _mm512_set1_epi32(0x7f800000));
#elif SBL__VW == 8
    return _mm256_castsi256_ps(_mm256_cmpgt_epi32(
        _mm256_and_si256(_mm256_castps_si256(a), _mm256_set1_epi32(0x7fffffff)), _mm256_set1_epi32(0x7f800000)));
#else
    return _mm_castsi128_ps(_mm_cmpgt_epi32(_mm_and_si128(_mm_castps_si128(a), _mm_set1_epi32(0x7fffffff)),
                                            _mm_set1_epi32(0x7f800000)));
#endif
}

/* The normal test of sbl__tap_ok_id_normal per lane: tap normal n, target normal m and
   its squared length mm, the squared threshold thr2. */
SBL__INLINE sbl__m sbl__lanes_normal_ok_m(sbl__v n0, sbl__v n1, sbl__v n2, sbl__v m0, sbl__v m1,
                                          sbl__v m2, sbl__v mm, sbl__m none_m, float thr2)
{
    const sbl__v zero = sbl__set1(0.0f), eps = sbl__set1(1e-12f);
    const sbl__v dot = sbl__add(sbl__add(sbl__mul(n0, m0), sbl__mul(n1, m1)), sbl__mul(n2, m2));
    const sbl__v nn = sbl__add(sbl__add(sbl__mul(n0, n0), sbl__mul(n1, n1)), sbl__mul(n2, n2));
    const sbl__v lim = sbl__mul(sbl__mul(sbl__set1(thr2), nn), mm);
    const sbl__m none_n = sbl__gt(eps, nn);
    /* both with a normal: not dot < 0 and not dot^2 < threshold^2 nn mm (no NaN here
       where it matters: dot and nn finite, mm finite for a valid target) */
    const sbl__m agree = sbl__mandnot(sbl__mandnot(sbl__true, sbl__gt(zero, dot)),
                                      sbl__gt(lim, sbl__mul(dot, dot)));
    const sbl__m none = sbl__mor(none_n, none_m);
    const sbl__m match = sbl__mor(sbl__mand(none_n, none_m), sbl__mandnot(agree, none));
    return sbl__mandnot(match, sbl__mor(sbl__nonfinite(dot), sbl__nonfinite(nn)));
}

/* the same with the target's "no normal" lanes (mm below 1e-12) formed here */
SBL__INLINE sbl__m sbl__lanes_normal_ok(sbl__v n0, sbl__v n1, sbl__v n2, sbl__v m0, sbl__v m1,
                                        sbl__v m2, sbl__v mm, float thr2)
{
    return sbl__lanes_normal_ok_m(n0, n1, n2, m0, m1, m2, mm, sbl__gt(sbl__set1(1e-12f), mm), thr2);
}

/* a == b per lane, ordered (a NaN on either side: false), in one compare: the lanes
   where a <= b and b <= a */
SBL__INLINE sbl__m sbl__lanes_eq(sbl__v a, sbl__v b)
{
#if SBL__VW == 16
    return _mm512_cmp_ps_mask(a, b, _CMP_EQ_OQ);
#elif SBL__VW == 8
    return _mm256_cmp_ps(a, b, _CMP_EQ_OQ);
#else
    return _mm_cmpeq_ps(a, b);
#endif
}

/* The id test per lane: equal as floats, a NaN on either side never matching (tested on
   the bits too: -ffast-math may rewrite the compare into one true for NaN). */
SBL__INLINE sbl__m sbl__lanes_id_ok(sbl__v id, sbl__v want)
{
    return sbl__mandnot(sbl__lanes_eq(id, want), sbl__mor(sbl__lanes_nan(id), sbl__lanes_nan(want)));
}

/* The VW pixels x .. x + VW - 1 of row y of a view, channel c (pixel step 1: a load;
   else lanes at l * step). */
SBL__INLINE sbl__v sbl__lanes_px(const sbl__flat *f, int x, int y, int c)
{
    const float *q = SBL__AT(*f, x, y) + c;
    int idx[SBL__VW], l;
    if (f->step == 1) return sbl__load(q);
    for (l = 0; l < SBL__VW; ++l) idx[l] = l * SBL__CAST(int, f->step); /* sbl__geo_nid_lanes_ok */
    return sbl__gatheri(q, idx);
}

/* Can the lanes read the target's normals and ids at l * pixel step (int)? */
static int sbl__geo_nid_lanes_ok(const sbl__target_geo *g)
{
    return g->normals.step < INT_MAX / SBL__VW && g->ids.step < INT_MAX / SBL__VW;
}

/* The target's normals (3 channels) of the VW pixels x .. x + VW - 1 of row y. */
SBL__INLINE void sbl__lanes_normals(const sbl__flat *f, int x, int y, sbl__v *m0, sbl__v *m1, sbl__v *m2)
{
    if (f->step == 3) {
        sbl__rgb_lanes(SBL__AT(*f, x, y), m0, m1, m2);
    } else {
        *m0 = sbl__lanes_px(f, x, y, 0);
        *m1 = sbl__lanes_px(f, x, y, 1);
        *m2 = sbl__lanes_px(f, x, y, 2);
    }
}

/* sbl__tap_ok_id_normal on tap t (0 .. 3: (x0, y0), (x0 + 1, y0), (x0, y0 + 1),
   (x0 + 1, y0 + 1)) of plan entries [i, i + VW): the same float operations in the same
   order per lane (dot, nn, the threshold product), so the same decisions. ids compare
   as floats, a NaN on either side never matching; a tap whose dot or nn is not finite
   fails; "no normal" (squared length below 1e-12) matches only itself. The taps are
   gathered at the plan's indices (any layout: strided or channel views). */
SBL__INLINE sbl__m sbl__lanes_nid_ok(const sbl__tap_src *s, const sbl__tap_plan *p, int i, int t,
                                     int run, const sbl__v *pre)
{
    const ptrdiff_t tx = t & 1, ty = t >> 1;
    sbl__m ok = sbl__true;
    /* the taps' ids and normals: pre (read already, see sbl__lanes_taps), else plain
       loads where run (the lanes' taps are consecutive pixels in both views) and the
       view is packed, else gathers */
    if (s->use_id) {
        const float *ib = s->ids.p + ty * s->ids.stride + tx * s->ids.step;
        const sbl__v id = pre ? pre[0] : run && s->ids.step == 1 ? sbl__load(ib + p->ii[i]) : sbl__gatheri(ib, p->ii + i);
        ok = sbl__lanes_id_ok(id, sbl__load(p->tid + i));
    }
    if (s->use_normal) {
        const float *nb = s->normals.p + ty * s->normals.stride + tx * s->normals.step;
        sbl__v n0, n1, n2;
        if (pre) {
            n0 = pre[1]; n1 = pre[2]; n2 = pre[3];
        } else if (run && s->normals.step == 3) {
            sbl__rgb_lanes(nb + p->ni[i], &n0, &n1, &n2);
        } else {
            n0 = sbl__gatheri(nb, p->ni + i);
            n1 = sbl__gatheri(nb + 1, p->ni + i);
            n2 = sbl__gatheri(nb + 2, p->ni + i);
        }
        ok = sbl__mand(ok, sbl__lanes_normal_ok(n0, n1, n2, sbl__load(p->tn[0] + i), sbl__load(p->tn[1] + i),
                                                sbl__load(p->tn[2] + i), sbl__load(p->tn2 + i),
                                                s->normal_threshold2));
    }
    return ok;
}

/* The target's side of the normal / id tests of plan entries [i, i + VW), read once per
   vector for its four taps (sbl__lanes_nid_run): nid 1 ids, 2 normals, 3 both. */
typedef struct sbl__nid_want {
    sbl__v id, m0, m1, m2, mm;
    sbl__m id_nan, none_m;
    int all_m; /* every lane's target has a normal (none_m false in every lane) */
} sbl__nid_want;

SBL__INLINE void sbl__nid_want_load(const sbl__tap_plan *p, int i, int nid, sbl__nid_want *w)
{
    if (nid & 1) {
        w->id = sbl__load(p->tid + i);
        w->id_nan = sbl__lanes_nan(w->id);
    }
    if (nid & 2) {
        w->m0 = sbl__load(p->tn[0] + i);
        w->m1 = sbl__load(p->tn[1] + i);
        w->m2 = sbl__load(p->tn[2] + i);
        w->mm = sbl__load(p->tn2 + i);
        w->none_m = sbl__gt(sbl__set1(1e-12f), w->mm);
        w->all_m = !sbl__mbits(w->none_m);
    }
}

/* sbl__lanes_nid_ok of tap t for a run whose views are packed (ids: pixel step 1,
   normals: 3), with which views are tested a constant (nid as above) and the target's
   side from w: the same operations per lane, without the tests of the layout. all_m (a
   constant, w->all_m): every lane's target has a normal, so sbl__lanes_normal_ok_m's
   match is "the tap has one and agrees" and the test one union of its failures. */
SBL__INLINE sbl__m sbl__lanes_nid_run(const sbl__tap_src *s, const sbl__tap_plan *p, int i, int t,
                                      int nid, const sbl__nid_want *w, int all_m)
{
    const ptrdiff_t tx = t & 1, ty = t >> 1;
    sbl__m ok = sbl__true;
    if (nid & 1) {
        const sbl__v id = sbl__load(s->ids.p + ty * s->ids.stride + tx + p->ii[i]);
        ok = sbl__mandnot(sbl__lanes_eq(id, w->id), sbl__mor(sbl__lanes_nan(id), w->id_nan));
    }
    if (nid & 2) {
        sbl__v n0, n1, n2;
        sbl__rgb_lanes(s->normals.p + ty * s->normals.stride + 3 * tx + p->ni[i], &n0, &n1, &n2);
        if (all_m) {
            /* sbl__lanes_normal_ok_m with none_m false in every lane, the same float
               operations: fails where dot < 0, dot^2 < thr2 nn mm, nn < 1e-12 (no tap
               normal) or dot or nn is not finite */
            const sbl__v dot = sbl__add(sbl__add(sbl__mul(n0, w->m0), sbl__mul(n1, w->m1)), sbl__mul(n2, w->m2));
            const sbl__v nn = sbl__add(sbl__add(sbl__mul(n0, n0), sbl__mul(n1, n1)), sbl__mul(n2, n2));
            const sbl__v lim = sbl__mul(sbl__mul(sbl__set1(s->normal_threshold2), nn), w->mm);
            const sbl__m fail = sbl__mor(sbl__mor(sbl__gt(sbl__set1(0.0f), dot), sbl__gt(lim, sbl__mul(dot, dot))),
                                         sbl__mor(sbl__gt(sbl__set1(1e-12f), nn),
                                                  sbl__mor(sbl__nonfinite(dot), sbl__nonfinite(nn))));
            ok = sbl__mandnot(ok, fail);
        } else {
            const sbl__m nok = sbl__lanes_normal_ok_m(n0, n1, n2, w->m0, w->m1, w->m2, w->mm, w->none_m,
                                                      s->normal_threshold2);
            ok = (nid & 1) ? sbl__mand(ok, nok) : nok;
        }
    }
    return ok;
}

/* Is a vector "full" (sbl__row_taps_ch): every lane's expected depth ze below +inf and
   its depth limit lim = tol ze + slack (sbl__lanes_taps' expression) finite and below
   ze? The last makes the taps' d > 0 test redundant: |fl(d - ze)| <= lim < ze needs
   fl(d - ze) > -ze, which (rounding is monotone, -ze is a float) needs d > 0; a NaN d
   fails either way. */
/* the taps' depth limit |d - ze| <= lim: tol ze + slack */
SBL__INLINE sbl__v sbl__depth_lim(sbl__v tol, sbl__v ze, sbl__v slack)
{
    return sbl__add(sbl__mul(tol, ze), slack);
}

/* (lim = sbl__depth_lim(tol, ze, slack), as every caller forms it: where ze is +inf, tol
   ze is +-inf or NaN and so is lim, so the test of lim covers "ze is +inf") */
SBL__INLINE int sbl__full_lim(sbl__v ze, sbl__v lim)
{
    return !sbl__mbits(sbl__mor(sbl__nonfinite(lim), sbl__le(ze, lim)));
}

SBL__INLINE int sbl__full_lanes(sbl__v tol, sbl__v ze, sbl__v slack)
{
    return sbl__full_lim(ze, sbl__depth_lim(tol, ze, slack));
}

/* One tap of sbl__lanes_taps: t = 0 .. 3 is the footprint's (x0, y0), (x0 + 1, y0),
   (x0, y0 + 1), (x0 + 1, y0 + 1). sbl__lanes_tap_test: its tests narrow ok (from w > 0),
   returned, with its N in *nt; sbl__lanes_tap_sum: its weighted N, colour and weight
   join the sums where ok (each sum takes the taps in the order 0 .. 3, as the pixel
   gather adds them; masked 0: every lane passed, so no mask is needed). Written once and
   inlined per tap with t constant, so the offsets fold and every vector stays in a
   register. plain: no lane expects sky and every depth limit is finite, so
   sbl__depth_match reduces to d > 0 and |d - z| <= limit (a non-finite d fails the
   second). cidx: the colour's lane indices from the first tap. idx0 (NULL: the plan's):
   the first taps' indices of a contiguous vector (sbl__lanes_taps_in's first). */
SBL__INLINE sbl__m sbl__lanes_tap_test(const sbl__tap_src *s, const sbl__tap_plan *p, int i,
                                       int t, sbl__v w, sbl__v ze, sbl__v lim, sbl__m inf_e,
                                       int plain, sbl__v *nt, int contiguous, int sky, int full,
                                       const sbl__v *pre, int nid_run, const sbl__v *nid_pre,
                                       int nid, sbl__m nid_ok, int wpos, const ptrdiff_t *idx0)
{
    const sbl__v zero = sbl__set1(0.0f);
    const ptrdiff_t tx = t & 1, ty = t >> 1;
    /* wpos (a constant): w > 0 in every lane (sbl__taps_uni), so ok starts as the first
       test's mask, not that mask and the weight's (an and with all ones, which the
       compiler keeps) */
    sbl__m ok = sbl__gt(w, zero);
    int first = wpos;
#define SBL__OK_AND(m) \
    do { \
        if (first) { \
            ok = (m); \
            first = 0; \
        } else { \
            ok = sbl__mand(ok, (m)); \
        } \
    } while (0)
    if (full || s->use_depth) {
        const ptrdiff_t o = ty * s->depth.stride + tx * s->depth.step;
        const sbl__v d = pre ? pre[0]
                             : contiguous ? sbl__load(s->depth.p + o + (idx0 ? idx0[1] : p->di[i]))
                                          : sbl__gatheri(s->depth.p + o, p->di + i);
        if (sky && !full) {
            SBL__OK_AND(sbl__posinf(d));
        } else if (full) { /* (d > 0 implied: sbl__full_lanes) */
            SBL__OK_AND(sbl__le(sbl__abs(sbl__sub(d, ze)), lim));
        } else if (plain) {
            SBL__OK_AND(sbl__mand(sbl__gt(d, zero), sbl__le(sbl__abs(sbl__sub(d, ze)), lim)));
        } else {
            /* sbl__depth_match: sky matches only sky; else a finite, positive depth
               within the tolerance */
            const sbl__m inf_t = sbl__posinf(d);
            const sbl__m near = sbl__mand(sbl__mandnot(sbl__gt(d, zero), sbl__nonfinite(d)),
                                          sbl__le(sbl__abs(sbl__sub(d, ze)), lim));
            const sbl__m match = sbl__mor(sbl__mand(inf_e, inf_t),
                                          sbl__mandnot(near, sbl__mor(inf_e, inf_t)));
            SBL__OK_AND(match);
        }
    }
    if (nid) SBL__OK_AND(nid_ok); /* (sbl__lanes_nid_run, formed before) */
    else if (!full && (s->use_normal || s->use_id)) SBL__OK_AND(sbl__lanes_nid_ok(s, p, i, t, nid_run, nid_pre));
    *nt = zero;
    if (full || s->length.p) {
        const ptrdiff_t o = ty * s->length.stride + tx * s->length.step;
        *nt = pre ? pre[1]
                  : contiguous ? sbl__load(s->length.p + o + (idx0 ? idx0[2] : p->li[i]))
                               : sbl__gatheri(s->length.p + o, p->li + i);
        SBL__OK_AND(sbl__gt(*nt, zero));
    }
#undef SBL__OK_AND
    return ok;
}

SBL__INLINE void sbl__lanes_tap_sum(const sbl__tap_src *s, int t, sbl__v w, sbl__m ok, sbl__v nt,
                                    const int *cidx, const float *cbase, sbl__v *acc,
                                    sbl__v *accn, sbl__v *wsum, int ch, int contiguous, int full,
                                    int masked, const sbl__v *pre, int il, int no_wsum)
{
    const sbl__v zero = sbl__set1(0.0f);
    const ptrdiff_t tx = t & 1, ty = t >> 1;
    const float *cp = cbase + ty * s->color.stride + tx * s->color.step;
    sbl__v v[4];
#define SBL__TAP_ADD(sum, term) (sum = sbl__add(sum, masked ? sbl__sel(ok, term, zero) : (term)))
    if (full || s->length.p) SBL__TAP_ADD(*accn, sbl__mul(w, nt));
    else SBL__TAP_ADD(*accn, w);
    /* the channels written out (gcc -O2 keeps a loop over them, and the sums in memory) */
    if (pre) { /* (paired gathers: sbl__lanes_taps) */
        v[0] = pre[0];
        if (ch > 1) v[1] = pre[1];
        if (ch > 2) v[2] = pre[2];
        if (ch > 3) v[3] = pre[3];
    } else if (il) { /* (sbl__lanes_taps_in: the floats in memory order) */
        v[0] = sbl__load(cp);
        v[1] = sbl__load(cp + SBL__VW);
        v[2] = sbl__load(cp + 2 * SBL__VW);
    } else if (contiguous && ch == 3 && s->color.step == 3) { /* packed RGB */
        sbl__rgb_lanes(cp, &v[0], &v[1], &v[2]);
    } else {
        v[0] = contiguous && ch == 1 && s->color.step == 1 ? sbl__load(cp) : sbl__gatheri(cp, cidx);
        if (ch > 1) v[1] = sbl__gatheri(cp + 1, cidx);
        if (ch > 2) v[2] = sbl__gatheri(cp + 2, cidx);
        if (ch > 3) v[3] = sbl__gatheri(cp + 3, cidx);
    }
    SBL__TAP_ADD(acc[0], sbl__mul(w, v[0]));
    if (ch > 1) SBL__TAP_ADD(acc[1], sbl__mul(w, v[1]));
    if (ch > 2) SBL__TAP_ADD(acc[2], sbl__mul(w, v[2]));
    if (ch > 3) SBL__TAP_ADD(acc[3], sbl__mul(w, v[3]));
    if (!no_wsum) SBL__TAP_ADD(*wsum, w);
#undef SBL__TAP_ADD
}

/* The evidence plane's term of tap t (sbl__lanes_taps with the plane): N's tap index,
   its own sum, as a 1-channel colour's in sbl__lanes_tap_sum; pre: the tap's values
   already read (in pairs) */
SBL__INLINE void sbl__lanes_tap_ev(const sbl__tap_src *s, int t, sbl__v w, sbl__m ok,
                                   const float *ebase, const int *lidx, sbl__v *acce,
                                   int contiguous, int masked, const sbl__v *pre)
{
    const ptrdiff_t o = (t >> 1) * s->length.stride + (t & 1) * s->length.step;
    const sbl__v e = pre ? *pre : contiguous ? sbl__load(ebase + o + lidx[0]) : sbl__gatheri(ebase + o, lidx);
    const sbl__v term = sbl__mul(w, e);
    *acce = sbl__add(*acce, masked ? sbl__sel(ok, term, sbl__set1(0.0f)) : term);
}

/* TAP(t, m) for the taps that weigh in some lane: tap 0; taps 1 / 3 unless every
   lane's x fraction is 0 (skip_x), taps 2 / 3 unless every y fraction is (skip_y); m a
   constant (masked or not), so each inlined instance keeps it fixed */
#define SBL__EACH_TAP(TAP, m)                                                              \
    do {                                                                                   \
        TAP(0, m);                                                                         \
        if (!skip_x) TAP(1, m);                                                            \
        if (!skip_y) {                                                                     \
            TAP(2, m);                                                                     \
            if (!skip_x) TAP(3, m);                                                        \
        }                                                                                  \
    } while (0)

/* The evidence plane of plan entries [i, i + VW) into r->e + x, in the colour's taps
   (sbl__lanes_taps with the plane, after the colour: its weights w, tap masks ok, skipped
   taps, reciprocal weight sum, validity, redo and fast lanes). The plane's own gather
   has the same taps, tests, weights and validity wherever both sums are finite, so its
   value (renormalised and saturated as the colour's) where valid, stored as the ratio
   (sbl__evidence_pixel's test). Lanes the colour keeps whose evidence sum is not finite
   take its pixel gather (redo 3); the colour's redo lanes take theirs with the colour.
   pair: a scattered vector whose views are packed (sbl__lanes_taps): the plane, laid
   out as N (sbl__evidence_fused_ok), read two taps per gather as N is. Returns the mask
   of the lanes it marked (redo 3), 0 if none. */
SBL__INLINE int sbl__lanes_taps_evidence(const sbl__tap_src *s, sbl__tap_plan *p, int i,
                                          sbl__ring_row *r, int x, sbl__v w0, sbl__v w1,
                                          sbl__v w2, sbl__v w3, sbl__m ok0, sbl__m ok1,
                                          sbl__m ok2, sbl__m ok3, int skip_x, int skip_y,
                                          sbl__v inv, sbl__m valid, sbl__m redo, sbl__m fast,
                                          int contiguous, int pair)
{
    const sbl__v zero = sbl__set1(0.0f), fmax = sbl__set1(FLT_MAX);
    const float *ebase = r->e_rp->src.color.p;
    const int *lidx = p->li + i;
    const int masked = sbl__mbits(sbl__mand(sbl__mand(ok0, ok1), sbl__mand(ok2, ok3))) != (1 << SBL__VW) - 1;
    sbl__v acce = zero, e, q[4];
    sbl__m use;
    int c, bits, any;
    /* the next row's new tap row (y0 + 2), as sbl__lanes_taps asks for N's */
    SBL__PREFETCH(ebase + lidx[0], 2 * s->length.stride);
    if (pair) { /* taps 0, 1 (row y0) and 2, 3 (row y0 + 1) */
        sbl__gather_pairs(ebase, lidx, q, 1);
        if (!skip_y) sbl__gather_pairs(ebase + s->length.stride, lidx, q + 2, 1);
        else q[2] = q[3] = zero; /* (not read) */
    }
#define SBL__TAP_EV(t, m) \
    sbl__lanes_tap_ev(s, t, w##t, ok##t, ebase, lidx, &acce, contiguous, m, pair ? q + t : NULL)
    if (!masked) SBL__EACH_TAP(SBL__TAP_EV, 0);
    else SBL__EACH_TAP(SBL__TAP_EV, 1);
#undef SBL__TAP_EV
    e = sbl__min(sbl__max(sbl__mul(acce, inv), sbl__sub(zero, fmax)), fmax);
    use = sbl__mandnot(sbl__mand(valid, sbl__gt(e, zero)),
                       sbl__gt(e, sbl__set1(SBL__CAST(float, SBL__POOL_RATIO_CAP))));
    sbl__store(r->e + x, sbl__sel(use, e, sbl__set1(1.0f)));
    bits = any = sbl__mbits(sbl__mandnot(sbl__mand(fast, sbl__nonfinite(acce)), redo));
    for (c = 0; bits; ++c, bits >>= 1)
        if (bits & 1) p->redo[i + c] = 3;
    return any; /* (the lanes marked) */
}

/* The tail plane of plan entries [i, i + VW) into r->tl[0] / r->tl[1] + x, in the
   colour's taps, as sbl__lanes_taps_evidence takes the evidence plane: the plane's own
   gather (a 2-channel colour) has the same taps, tests, weights and validity wherever its
   sums are finite, each channel's sum the same terms in the same order, so its values;
   then sbl__tail_gather_row's test (0 where not valid or not a rate / a variance). The
   plane is laid out as N with every offset doubled (sbl__tail_fused_ok): tap indices
   2 li, contiguous lanes two floats apart, pairs of taps 4 floats in a run. Lanes the
   colour keeps whose tail sums are not finite are marked for the pixel gather (redo 3,
   as the evidence plane's). Returns the mask of the lanes it marked, 0 if none. */
SBL__INLINE int sbl__lanes_taps_tail(const sbl__tap_src *s, sbl__tap_plan *p, int i,
                                     sbl__ring_row *r, int x, sbl__v w0, sbl__v w1, sbl__v w2,
                                     sbl__v w3, sbl__m ok0, sbl__m ok1, sbl__m ok2, sbl__m ok3,
                                     int skip_x, int skip_y, sbl__v inv, sbl__m valid,
                                     sbl__m redo, sbl__m fast, int contiguous, int pair)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), fmax = sbl__set1(FLT_MAX);
    const float *tbase = r->tl_rp->src.color.p;
    const int *lidx = p->li + i;
    const ptrdiff_t ls = s->length.stride, lx = s->length.step;
    const int masked = sbl__mbits(sbl__mand(sbl__mand(ok0, ok1), sbl__mand(ok2, ok3))) != (1 << SBL__VW) - 1;
    sbl__v acc0 = zero, acc1 = zero, q[4][2], g[4], rate, var;
    sbl__m keep_r, keep_v;
    int tidx[SBL__VW], c, bits, any;
    SBL__PREFETCH(tbase + 2 * SBL__CAST(ptrdiff_t, lidx[0]), 4 * ls);
    if (!contiguous) /* (a contiguous vector's entries past i hold no indices) */
        for (c = 0; c < SBL__VW; ++c) tidx[c] = 2 * lidx[c];
    q[1][0] = q[1][1] = q[2][0] = q[2][1] = q[3][0] = q[3][1] = zero; /* (skipped: not read) */
    if (pair) { /* taps 0, 1 (row y0) and 2, 3 (row y0 + 1): one run of 4 floats each */
        sbl__gather_pairs(tbase, tidx, g, 2);
        q[0][0] = g[0]; q[0][1] = g[1]; q[1][0] = g[2]; q[1][1] = g[3];
        if (!skip_y) {
            sbl__gather_pairs(tbase + 2 * ls, tidx, g, 2);
            q[2][0] = g[0]; q[2][1] = g[1]; q[3][0] = g[2]; q[3][1] = g[3];
        }
    } else {
#define SBL__TL_READ(t) \
    { \
        const ptrdiff_t o = 2 * ((t >> 1) * ls + (t & 1) * lx); \
        if (contiguous) { \
            sbl__lanes2(tbase + o + 2 * SBL__CAST(ptrdiff_t, lidx[0]), &q[t][0], &q[t][1]); \
        } else { \
            q[t][0] = sbl__gatheri(tbase + o, tidx); \
            q[t][1] = sbl__gatheri(tbase + o + 1, tidx); \
        } \
    }
        SBL__TL_READ(0);
        if (!skip_x) SBL__TL_READ(1);
        if (!skip_y) {
            SBL__TL_READ(2);
            if (!skip_x) SBL__TL_READ(3);
        }
#undef SBL__TL_READ
    }
#define SBL__TAP_TL(t, m) \
    { \
        const sbl__v a_ = sbl__mul(w##t, q[t][0]), b_ = sbl__mul(w##t, q[t][1]); \
        acc0 = sbl__add(acc0, m ? sbl__sel(ok##t, a_, zero) : a_); \
        acc1 = sbl__add(acc1, m ? sbl__sel(ok##t, b_, zero) : b_); \
    }
    if (!masked) SBL__EACH_TAP(SBL__TAP_TL, 0);
    else SBL__EACH_TAP(SBL__TAP_TL, 1);
#undef SBL__TAP_TL
    rate = sbl__min(sbl__max(sbl__mul(acc0, inv), sbl__sub(zero, fmax)), fmax);
    var = sbl__min(sbl__max(sbl__mul(acc1, inv), sbl__sub(zero, fmax)), fmax);
    keep_r = sbl__mandnot(sbl__mand(valid, sbl__gt(rate, zero)), sbl__gt(rate, one));
    keep_v = sbl__mand(valid, sbl__gt(var, zero)); /* (saturated: var <= FLT_MAX) */
    sbl__store(r->tl[0] + x, sbl__sel(keep_r, rate, zero));
    sbl__store(r->tl[1] + x, sbl__sel(keep_v, var, zero));
    bits = any = sbl__mbits(sbl__mandnot(sbl__mand(fast, sbl__mor(sbl__nonfinite(acc0), sbl__nonfinite(acc1))), redo));
    for (c = 0; bits; ++c, bits >>= 1)
        if (bits & 1) p->redo[i + c] = 3;
    return any;
}

/* The fast path of sbl__gather_ch (sbl__gather_fast, the check of the sums, the
   renormalisation and saturation) for plan entries [i, i + VW), into ring columns
   [x, x + VW): the same float operations in the same order per lane (a skipped tap
   adds +0 to a sum that cannot be -0), hence the same bits. Lanes whose sums are not
   finite, or whose weight is below 1e-3 with the fallback on, are marked for redo.
   contiguous: the lanes' taps are consecutive pixels in every view (uniform motion, a
   camera at rest, a row of a parallel rig; depth and N packed), read with plain vector
   loads, the colour with one fixed set of lane offsets (cstep: l * its pixel step).
   Taps of weight 0 in every lane are skipped: they would add +0 everywhere.
   sky: every planned lane expects sky (+inf), so its depth test is "the tap is sky"
   (sbl__depth_match with an infinite expectation), without the tolerance. */
/* Prefetch the tap row the next row will read first (y0 + 2, at lane 0's taps: colour,
   depth, N) for the vector at plan entry i; called by the loops over vectors (inside
   sbl__lanes_taps it cost the SSE2 normals case +23 instructions per pixel: registers) */
SBL__INLINE void sbl__taps_prefetch_at(const sbl__tap_src *s, ptrdiff_t ci, ptrdiff_t di, ptrdiff_t li, int ch)
{
    const float *c = s->color.p + ci;
    int o;
    for (o = 0; o < ch * SBL__VW; o += SBL__LINE_FLOATS) SBL__PREFETCH(c, 2 * s->color.stride + o);
    if (s->use_depth) SBL__PREFETCH(s->depth.p + di, 2 * s->depth.stride);
    if (s->length.p) SBL__PREFETCH(s->length.p + li, 2 * s->length.stride);
}

/* (the first tap indices from the plan) */
SBL__INLINE void sbl__taps_prefetch(const sbl__tap_src *s, const sbl__tap_plan *p, int i, int ch)
{
    const float *c = s->color.p + p->ci[i];
    int o;
    for (o = 0; o < ch * SBL__VW; o += SBL__LINE_FLOATS) SBL__PREFETCH(c, 2 * s->color.stride + o);
    if (s->use_depth) SBL__PREFETCH(s->depth.p + p->di[i], 2 * s->depth.stride);
    if (s->length.p) SBL__PREFETCH(s->length.p + p->li[i], 2 * s->length.stride);
}

/* The terms of sbl__lanes_taps_in that depend on the fractions alone, for vectors whose
   lanes all share one pair of fractions (sbl__temporal_uniform_run's block): formed once
   per block by sbl__taps_uni_of, not once per vector; the same expressions, so the same
   values. wsum, inv, lo: the weight sum (the taps taken, in their order, from 0), its
   reciprocal and its "below 1e-3" mask, which are the vector's where every tap passes
   in every lane (no mask). wpos: every weight taken is above 0 in every lane (its test
   always true). */
typedef struct sbl__taps_uni {
    sbl__v w[4], wsum, inv;
    sbl__m lo;
    int skip_x, skip_y, wpos;
} sbl__taps_uni;

/* The bilinear weights of fractions fx, fy (>= 0), and whether the x / y taps can be
   skipped: none above 0 in x (in y) means taps 1 and 3 (2 and 3) weigh 0 in every lane
   (a camera at rest; the rows of a parallel stereo rig) */
SBL__INLINE void sbl__tap_weights(sbl__v fx, sbl__v fy, sbl__v *w, int *skip_x, int *skip_y)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__v gx = sbl__sub(one, fx), gy = sbl__sub(one, fy);
    *skip_x = !sbl__mbits(sbl__gt(fx, zero));
    *skip_y = !sbl__mbits(sbl__gt(fy, zero));
    w[0] = sbl__mul(gx, gy);
    w[1] = sbl__mul(fx, gy);
    w[2] = sbl__mul(gx, fy);
    w[3] = sbl__mul(fx, fy);
}

SBL__INLINE void sbl__taps_uni_of(sbl__taps_uni *u, sbl__v fx, sbl__v fy)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    sbl__m pos;
    sbl__tap_weights(fx, fy, u->w, &u->skip_x, &u->skip_y);
    /* the unmasked sum of sbl__lanes_tap_sum (SBL__EACH_TAP's taps and order) */
    u->wsum = sbl__add(zero, u->w[0]);
    pos = sbl__gt(u->w[0], zero);
    if (!u->skip_x) {
        u->wsum = sbl__add(u->wsum, u->w[1]);
        pos = sbl__mand(pos, sbl__gt(u->w[1], zero));
    }
    if (!u->skip_y) {
        u->wsum = sbl__add(u->wsum, u->w[2]);
        pos = sbl__mand(pos, sbl__gt(u->w[2], zero));
        if (!u->skip_x) {
            u->wsum = sbl__add(u->wsum, u->w[3]);
            pos = sbl__mand(pos, sbl__gt(u->w[3], zero));
        }
    }
    u->inv = sbl__div_exact(one, u->wsum);
    u->lo = sbl__gt(sbl__set1(1e-3f), u->wsum);
    u->wpos = sbl__mbits(pos) == (1 << SBL__VW) - 1;
}

/* sbl__lanes_taps with plan entry i's fractions fx, fy, fast lanes, expected depth ze and
   depth limit lim (read only where full or the depth test needs them) given in registers
   (sbl__temporal_uniform_run has them: no store and reload). u (NULL: none): the terms
   of the fractions, formed per block (then fx, fy are not read). first (NULL: the
   plan's): entry i's first tap indices of a contiguous vector, given in registers (not
   stored in the plan). Returns whether any lane was marked for redo. */
SBL__INLINE int sbl__lanes_taps_in(const sbl__tap_src *s, sbl__tap_plan *p, int i, int fallback,
                                   sbl__ring_row *r, int x, const int *cstep, int ch,
                                   int contiguous, int sky, int full, int flag, int ev, int pair,
                                   int nid_run, int nid, sbl__v fx, sbl__v fy, sbl__m fast,
                                   sbl__v ze_in, sbl__v lim_in, const sbl__taps_uni *u,
                                   const ptrdiff_t *first)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), fmax = sbl__set1(FLT_MAX);
    const int *cidx = contiguous ? cstep : p->ci + i;
    const float *cbase = contiguous ? s->color.p + (first ? first[0] : p->ci[i]) : s->color.p;
    sbl__v w0, w1, w2, w3, acc[4], accn = zero, wsum = zero, inv, n, ze = ze_in, lim = lim_in;
    sbl__m redo, nonfinite, lo, valid, inf_e = sbl__gt(zero, zero), ok0, ok1, ok2, ok3;
    int c, bits, any, plain = 0, unmasked, skip_x, skip_y;
    const int wpos = u ? u->wpos : 0;
    /* il: packed RGB taps of contiguous lanes with u's weights, which are one value in
       every lane: the unmasked colour sums are then taken over the 3 VW floats in memory
       order (acc[c]: floats c VW .. c VW + VW - 1), each float the same terms in the
       same order as its channel's lane, and split into channels once (sbl__rgb_lanes_of)
       instead of at every tap */
    const int il = u && contiguous && !pair && ch == 3 && s->color.step == 3;
    if (u) {
        skip_x = u->skip_x;
        skip_y = u->skip_y;
        w0 = u->w[0];
        w1 = u->w[1];
        w2 = u->w[2];
        w3 = u->w[3];
    } else {
        sbl__v wt[4];
        sbl__tap_weights(fx, fy, wt, &skip_x, &skip_y);
        w0 = wt[0];
        w1 = wt[1];
        w2 = wt[2];
        w3 = wt[3];
    }
    if (!full && s->use_depth && !sky) {
        inf_e = sbl__posinf(ze);
        plain = !sbl__mbits(sbl__mor(inf_e, sbl__nonfinite(lim)));
    }
    acc[0] = acc[1] = acc[2] = acc[3] = zero;
    {   /* the tests of the taps, then the sums: without masks where every lane of every
           tap passed (the common case), each sum's terms and order unchanged. pair: the
           lanes' taps are scattered (not contiguous) and every view is packed: each
           view's taps read by rows, two taps per gather (sbl__gather_pairs) */
        sbl__v n0, n1 = zero, n2 = zero, n3 = zero, dn[4][2], cv[4][4], q[8], nv[4][4];
        sbl__m all, nk[4];
        /* the normal / id tests' taps in pairs too where both views are packed */
        const int nid_pair = pair && !full && (s->use_normal || s->use_id) &&
                             (!s->use_normal || s->normals.step == 3) && (!s->use_id || s->ids.step == 1);
        if (nid) {
            /* the normal / id tests of the taps first: the target's side is live only
               here (registers: SSE2 has 16) */
            sbl__nid_want nw;
            sbl__nid_want_load(p, i, nid, &nw);
#define SBL__NID_TAPS(all_m) \
    { \
        nk[0] = nk[1] = nk[2] = nk[3] = sbl__lanes_nid_run(s, p, i, 0, nid, &nw, all_m); \
        if (!skip_x) nk[1] = sbl__lanes_nid_run(s, p, i, 1, nid, &nw, all_m); \
        if (!skip_y) { \
            nk[2] = sbl__lanes_nid_run(s, p, i, 2, nid, &nw, all_m); \
            if (!skip_x) nk[3] = sbl__lanes_nid_run(s, p, i, 3, nid, &nw, all_m); \
        } \
    }
            /* (all_m a constant in each instance: the targets with a normal everywhere,
               the common case, take the shorter test) */
            if ((nid & 2) && nw.all_m) SBL__NID_TAPS(1)
            else SBL__NID_TAPS(0)
#undef SBL__NID_TAPS
        }
        if (nid_pair) {
            int ty;
            for (ty = 0; ty < (skip_y ? 1 : 2); ++ty) {
                if (s->use_id) {
                    sbl__gather_pairs(s->ids.p + ty * s->ids.stride, p->ii + i, q, 1);
                    nv[2 * ty][0] = q[0]; nv[2 * ty + 1][0] = q[1];
                }
                if (s->use_normal) {
                    sbl__gather_pairs(s->normals.p + ty * s->normals.stride, p->ni + i, q, 3);
                    nv[2 * ty][1] = q[0]; nv[2 * ty][2] = q[1]; nv[2 * ty][3] = q[2];
                    nv[2 * ty + 1][1] = q[3]; nv[2 * ty + 1][2] = q[4]; nv[2 * ty + 1][3] = q[5];
                }
            }
        }
        if (pair) {
            dn[0][0] = dn[1][0] = dn[2][0] = dn[3][0] = zero;
            dn[0][1] = dn[1][1] = dn[2][1] = dn[3][1] = zero;
            if (full || s->use_depth) {
                sbl__gather_pairs(s->depth.p, p->di + i, q, 1);
                dn[0][0] = q[0]; dn[1][0] = q[1];
                if (!skip_y) {
                    sbl__gather_pairs(s->depth.p + s->depth.stride, p->di + i, q, 1);
                    dn[2][0] = q[0]; dn[3][0] = q[1];
                }
            }
            if (full || s->length.p) {
                sbl__gather_pairs(s->length.p, p->li + i, q, 1);
                dn[0][1] = q[0]; dn[1][1] = q[1];
                if (!skip_y) {
                    sbl__gather_pairs(s->length.p + s->length.stride, p->li + i, q, 1);
                    dn[2][1] = q[0]; dn[3][1] = q[1];
                }
            }
        }
#define SBL__TEST(t, nt) \
    sbl__lanes_tap_test(s, p, i, t, w##t, ze, lim, inf_e, plain, nt, contiguous, sky, full, pair ? dn[t] : NULL, \
                        nid_run, nid_pair ? nv[t] : NULL, nid, nid ? nk[t] : sbl__true, wpos, first)
        ok0 = SBL__TEST(0, &n0);
        ok1 = ok2 = ok3 = ok0;
        if (!skip_x) ok1 = SBL__TEST(1, &n1);
        if (!skip_y) {
            ok2 = SBL__TEST(2, &n2);
            if (!skip_x) ok3 = SBL__TEST(3, &n3);
            else ok3 = ok2;
        }
#undef SBL__TEST
        if (pair) { /* the colour of taps 0, 1 (row y0) and 2, 3 (row y0 + 1) */
#define SBL__PAIR_ROW(t, q) \
    { \
        cv[t][0] = q[0]; cv[t + 1][0] = q[ch]; \
        cv[t][1] = q[1]; cv[t + 1][1] = q[ch + 1]; \
        cv[t][2] = q[2]; cv[t + 1][2] = q[ch + 2]; \
        cv[t][3] = q[3]; cv[t + 1][3] = q[ch + 3]; \
    }
            /* (every channel's slot copied, q's unread ones zero: dead code where ch is
               a constant; else gcc -Wmaybe-uninitialized cannot match the reads of
               channel c under ch > c to the writes under nf > c) */
            q[2] = q[3] = q[4] = q[5] = q[6] = q[7] = zero;
            sbl__gather_pairs(cbase, cidx, q, ch);
            SBL__PAIR_ROW(0, q);
            if (!skip_y) {
                sbl__gather_pairs(cbase + s->color.stride, cidx, q, ch);
                SBL__PAIR_ROW(2, q);
            }
#undef SBL__PAIR_ROW
        }
        all = sbl__mand(sbl__mand(ok0, ok1), sbl__mand(ok2, ok3));
#define SBL__SUM(t, m) \
    sbl__lanes_tap_sum(s, t, w##t, ok##t, n##t, cidx, cbase, acc, &accn, &wsum, ch, contiguous, full, m, \
                       pair ? cv[t] : NULL, m ? 0 : il, !m && u)
        unmasked = sbl__mbits(all) == (1 << SBL__VW) - 1;
        if (unmasked) {
            SBL__EACH_TAP(SBL__SUM, 0);
            if (il) { /* the channels of the interleaved sums */
                const sbl__v mixed[3] = {acc[0], acc[1], acc[2]};
                sbl__rgb_lanes_of(mixed, &acc[0], &acc[1], &acc[2]);
            }
        } else {
            SBL__EACH_TAP(SBL__SUM, 1);
        }
#undef SBL__SUM
    }
    nonfinite = sbl__nonfinite(accn);
    /* (the channels written out, as in sbl__lanes_tap_sum) */
    nonfinite = sbl__mor(nonfinite, sbl__nonfinite(acc[0]));
    if (ch > 1) nonfinite = sbl__mor(nonfinite, sbl__nonfinite(acc[1]));
    if (ch > 2) nonfinite = sbl__mor(nonfinite, sbl__nonfinite(acc[2]));
    if (ch > 3) nonfinite = sbl__mor(nonfinite, sbl__nonfinite(acc[3]));
    if (u && unmasked) { /* wsum is u's (the same adds) */
        lo = u->lo;
        inv = u->inv;
    } else {
        lo = sbl__gt(sbl__set1(1e-3f), wsum);
        inv = sbl__div_exact(one, wsum);
    }
    redo = fallback ? sbl__mor(nonfinite, lo) : nonfinite;
    redo = sbl__mand(redo, fast);
    n = sbl__min(sbl__max(sbl__mul(accn, inv), sbl__sub(zero, fmax)), fmax);
    valid = sbl__mandnot(sbl__mandnot(sbl__mand(fast, sbl__gt(n, zero)), lo), redo);
    sbl__store(r->n + x, sbl__sel(valid, n, zero));
    sbl__store(r->v + x, sbl__sel(valid, one, zero));
    /* flag (a constant): the unsafe-value check of sbl__ring_gather on the values
       stored, in registers (redo lanes are not valid here: their pixel gather flags
       them) */
#if SBL__VW == 4
    /* SSE2: one test for the vector first, the lanes' only where it fails (per-lane
       tests cost more there than with AVX2's three-operand integer ops, where the vector
       test gains nothing: measured) */
#define SBL__TAPS_OUT(c) \
    { \
        out[c + 1] = sbl__min(sbl__max(sbl__mul(acc[c], inv), sbl__sub(zero, fmax)), fmax); \
        sbl__store(r->x[c] + x, sbl__sel(valid, out[c + 1], zero)); \
    }
    {
        sbl__v out[5];
        out[0] = n;
        SBL__TAPS_OUT(0);
        if (ch > 1) SBL__TAPS_OUT(1);
        if (ch > 2) SBL__TAPS_OUT(2);
        if (ch > 3) SBL__TAPS_OUT(3);
        if (flag && !sbl__all_safe(out, ch + 1)) {
            sbl__m ok = sbl__lane_ok(out[0]);
            for (c = 1; c <= ch; ++c) ok = sbl__mand(ok, sbl__lane_ok(out[c]));
            bits = sbl__mbits(sbl__mandnot(valid, ok));
            if (bits) sbl__ring_flag_bits(r, x, bits);
        }
    }
#else
#define SBL__TAPS_OUT(c) \
    { \
        const sbl__v out = sbl__min(sbl__max(sbl__mul(acc[c], inv), sbl__sub(zero, fmax)), fmax); \
        sbl__store(r->x[c] + x, sbl__sel(valid, out, zero)); \
        if (flag) ok = sbl__mand(ok, sbl__lane_ok(out)); \
    }
    {
        sbl__m ok = flag ? sbl__lane_ok(n) : valid;
        SBL__TAPS_OUT(0);
        if (ch > 1) SBL__TAPS_OUT(1);
        if (ch > 2) SBL__TAPS_OUT(2);
        if (ch > 3) SBL__TAPS_OUT(3);
        if (flag) {
            bits = sbl__mbits(sbl__mandnot(valid, ok));
            if (bits) sbl__ring_flag_bits(r, x, bits);
        }
    }
#endif
#undef SBL__TAPS_OUT
    any = bits = sbl__mbits(redo);
    if (bits) {
        /* 2: only the fallback is left (sums finite, weight below 1e-3) */
        const int only = fallback ? sbl__mbits(sbl__mandnot(sbl__mand(lo, fast), nonfinite)) : 0;
        for (c = 0; bits; ++c, bits >>= 1)
            if (bits & 1) p->redo[i + c] = SBL__CAST(unsigned char, ((only >> c) & 1) + 1);
    }
    /* (ev: the ring row carries the evidence plane, the tail plane or both) */
    if (ev && r->e) any |= sbl__lanes_taps_evidence(s, p, i, r, x, w0, w1, w2, w3, ok0, ok1, ok2, ok3, skip_x, skip_y,
                                                    inv, valid, redo, fast, contiguous, pair);
    if (ev && r->tl[0]) any |= sbl__lanes_taps_tail(s, p, i, r, x, w0, w1, w2, w3, ok0, ok1, ok2, ok3, skip_x, skip_y,
                                                    inv, valid, redo, fast, contiguous, pair);
    return any;
}

/* sbl__lanes_taps_in with plan entry i's values read from the plan */
SBL__INLINE int sbl__lanes_taps(const sbl__tap_src *s, sbl__tap_plan *p, int i, int fallback,
                                sbl__ring_row *r, int x, const int *cstep, int ch,
                                int contiguous, int sky, int full, int flag, int ev, int pair,
                                int nid_run, int nid)
{
    const sbl__v zero = sbl__set1(0.0f);
    sbl__v ze = zero, lim = zero;
    if (full || (s->use_depth && !sky)) {
        ze = sbl__load(p->depth + i);
        lim = sbl__depth_lim(sbl__set1(s->depth_tolerance), ze, sbl__load(p->slack + i));
    }
    return sbl__lanes_taps_in(s, p, i, fallback, r, x, cstep, ch, contiguous, sky, full, flag, ev,
                              pair, nid_run, nid, sbl__load(p->fx + i), sbl__load(p->fy + i),
                              sbl__gt(sbl__load(p->fast + i), zero), ze, lim, NULL, NULL);
}

/* Are the VW ints at a equal to a[0] + l step, l = 0 .. VW - 1? Four at a time with
   SSE2 integer compares (every build with the row gather has them); the sums wrap like
   the vector adds, and valid tap indices are far from the int range's ends. */
SBL__INLINE int sbl__ints_step(const int *a, int step)
{
    const __m128i off = _mm_setr_epi32(0, step, 2 * step, 3 * step);
    int k, same = 0xffff;
    for (k = 0; k < SBL__VW; k += 4) {
        const unsigned first = SBL__CAST(unsigned, a[0]) + SBL__CAST(unsigned, k) * SBL__CAST(unsigned, step);
        const __m128i want = _mm_add_epi32(_mm_set1_epi32(SBL__CAST(int, first)), off);
        same &= _mm_movemask_epi8(_mm_cmpeq_epi32(_mm_loadu_si128(SBL__PCAST(const __m128i *, a + k)), want));
    }
    return same == 0xffff;
}

/* sbl__lanes_taps of a scattered vector in pairs (pair = 1), out of line: inlined into
   each instance of sbl__row_taps_ch it costs the common contiguous vectors ~9 SSE2
   instructions per pixel (measured: code size, registers); constants for the common
   packed RGB temporal call, the other shapes with the arguments as given. */
SBL__NOINLINE void sbl__lanes_taps_pairs(const sbl__tap_src *s, sbl__tap_plan *p, int i,
                                         int fallback, sbl__ring_row *r, int x,
                                         const int *cstep, int ch, int sky, int full,
                                         int flag, int ev)
{
    if (ch == 3 && !sky && flag && !ev) {
        if (full) sbl__lanes_taps(s, p, i, fallback, r, x, cstep, 3, 0, 0, 1, 1, 0, 1, 0, 0);
        else sbl__lanes_taps(s, p, i, fallback, r, x, cstep, 3, 0, 0, 0, 1, 0, 1, 0, 0);
    } else if (ch == 3 && !sky && flag && ev) {
        /* the same call with the evidence plane (its hard case: scattered vectors) */
        if (full) sbl__lanes_taps(s, p, i, fallback, r, x, cstep, 3, 0, 0, 1, 1, 1, 1, 0, 0);
        else sbl__lanes_taps(s, p, i, fallback, r, x, cstep, 3, 0, 0, 0, 1, 1, 1, 0, 0);
    } else {
        sbl__lanes_taps(s, p, i, fallback, r, x, cstep, ch, 0, sky, full, flag, ev, 1, 0, 0);
    }
}

/* sbl__row_taps for one channel count and sky flag (constants where inlined). */
SBL__INLINE void sbl__row_taps_ch(const sbl__tap_src *s, sbl__tap_plan *p, int i0, int n, int fallback,
                                  sbl__ring_row *r, int x, int ch, int sky, int flag, int ev)
{
    /* contiguous vectors need depth and N packed (plain loads); the colour's fixed lane
       offsets are the plan's lane steps */
    const int packed = (!s->use_depth || s->depth.step == 1) && (!s->length.p || s->length.step == 1);
    /* the common views: depth and N tested (no normal / id test); "full" vectors also have every depth limit
       finite and below its expectation, no lane expecting sky (the plain depth test
       without d > 0: sbl__full_lanes), and take the variant of
       the taps without the tests of the views' presence */
    const int both = !sky && s->use_depth && s->length.p && !s->use_normal && !s->use_id;
    const sbl__v tol = sbl__set1(s->depth_tolerance);
    const int *cstep = p->lane_step[0];
    /* scattered vectors read two taps per gather where every view is packed (colour:
       pixel step = channel count) */
    const int pairs = SBL__PAIRS && packed && s->color.step == ch;
    const int nid = s->use_normal || s->use_id;
    /* the normal / id tests with their views as constants (sbl__lanes_nid_run): packed
       RGB colour, depth and N tested, the normals and ids tested packed; for the
       vectors that are contiguous, full and consecutive in those views too */
    const int nid_const = !sky && ch == 3 && nid && s->use_depth && s->length.p &&
                          (!s->use_normal || s->normals.step == 3) && (!s->use_id || s->ids.step == 1)
                              ? (s->use_id ? 1 : 0) | (s->use_normal ? 2 : 0)
                              : 0;
    int i = i0;
    for (;;) {
        int contiguous, full = 0, nid_run, u;
        if (i + SBL__VW > n) i = n - SBL__VW;
        sbl__taps_prefetch(s, p, i, ch);
        /* every lane's first tap one pixel after the previous lane's, in every view
           (each lane's index is a valid one, so the vector load reads exactly the
           addresses the gather would) */
        u = p->uniform[i];
        contiguous = packed && u != 2 &&
                     (u || (sbl__ints_step(p->ci + i, SBL__CAST(int, s->color.step)) &&
                            (!s->use_depth || sbl__ints_step(p->di + i, 1)) &&
                            (!s->length.p || sbl__ints_step(p->li + i, 1))));
        if (u == 3) {
            full = both || nid_const; /* (the plan's test, sbl__temporal_plan_uni) */
        } else if (both || nid_const) {
            full = sbl__full_lanes(tol, sbl__load(p->depth + i), sbl__load(p->slack + i));
        }
        /* the normal / id taps of contiguous vectors: consecutive in those views too? */
        nid_run = nid && contiguous &&
                  (u == 1 || u == 3 ||
                   ((!s->use_normal || sbl__ints_step(p->ni + i, SBL__CAST(int, s->normals.step))) &&
                    (!s->use_id || sbl__ints_step(p->ii + i, SBL__CAST(int, s->ids.step)))));
        if (nid_const && full && nid_run) {
            /* (full: the plain depth test; the normal / id tests run, their views known) */
            if (nid_const == 3) sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, 3, 1, 0, 1, flag, ev, 0, 1, 3);
            else if (nid_const == 2) sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, 3, 1, 0, 1, flag, ev, 0, 1, 2);
            else sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, 3, 1, 0, 1, flag, ev, 0, 1, 1);
        } else {
            if (nid) full = 0; /* (the full variants below leave the normal / id tests out) */
            if (contiguous) {
                if (full) sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, ch, 1, 0, 1, flag, ev, 0, nid_run, 0);
                else sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, ch, 1, sky, 0, flag, ev, 0, nid_run, 0);
            } else if (pairs) {
                sbl__lanes_taps_pairs(s, p, i, fallback, r, x + i, cstep, ch, sky, full, flag, ev);
            } else {
                if (full) sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, ch, 0, 0, 1, flag, ev, 0, nid_run, 0);
                else sbl__lanes_taps(s, p, i, fallback, r, x + i, cstep, ch, 0, sky, 0, flag, ev, 0, nid_run, 0);
            }
        }
        if (i + SBL__VW >= n) break;
        i += SBL__VW;
    }
}

/* The vector stage over plan entries [i0, n) (n - i0 >= VW) into ring columns [x + i0,
   x + n); the last vector overlaps the one before rather than running past the block. sky: every
   planned entry expects sky (see sbl__lanes_taps). */
static void sbl__row_taps(const sbl__tap_src *s, sbl__tap_plan *p, int i0, int n, int fallback,
                          sbl__ring_row *r, int x, int sky)
{
    if (sky) {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 1, 0, 0); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 1, 0, 0); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 1, 0, 0); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 1, 0, 0); break;
        }
    } else {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 0, 0, 0); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 0, 0, 0); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 0, 0, 0); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 0, 0, 0); break;
        }
    }
}

/* sbl__row_taps, flagging the unsafe values it writes (the temporal row gather) */
static void sbl__row_taps_flag(const sbl__tap_src *s, sbl__tap_plan *p, int i0, int n, int fallback,
                               sbl__ring_row *r, int x, int sky)
{
    if (sky) {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 1, 1, 0); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 1, 1, 0); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 1, 1, 0); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 1, 1, 0); break;
        }
    } else {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 0, 1, 0); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 0, 1, 0); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 0, 1, 0); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 0, 1, 0); break;
        }
    }
}

/* sbl__row_taps_flag with the evidence plane gathered in the same taps (r->e: the
   temporal row gather when the pooled estimator carries it) */
SBL__NOINLINE void sbl__row_taps_flag_ev(const sbl__tap_src *s, sbl__tap_plan *p, int i0, int n,
                                         int fallback, sbl__ring_row *r, int x, int sky)
{
    if (sky) {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 1, 1, 1); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 1, 1, 1); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 1, 1, 1); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 1, 1, 1); break;
        }
    } else {
        switch (s->color.ch) {
        case 1: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 1, 0, 1, 1); break;
        case 2: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 2, 0, 1, 1); break;
        case 3: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 3, 0, 1, 1); break;
        default: sbl__row_taps_ch(s, p, i0, n, fallback, r, x, 4, 0, 1, 1); break;
        }
    }
}

/* A camera map's constants for sbl__cam_lanes_k, in double lanes (sbl__cam_k_init, from
   an sbl__cam_map): its images' sizes and its folded rows (sbl__cam_map_fold) r[0 .. 1]
   the ray's q2, q3, r[2 .. 4] the other clip's c0, c1, c3, r[5 .. 6] the other view's
   v2, v3, each over (ndc x, ndc y, 1), and w[0 .. 4] the columns for w = 1 of r[2 .. 6].
   For the positions of one row (py = y + 0.5 in every lane, sbl__cam_k_row): each row's
   product r[1] n1 (t), formed once per row by the reference's own operations. */
typedef struct sbl__cam_k {
    sbl__dv width, height, other_width, other_height;
    sbl__dv r[7][3], w[5], t[7];
} sbl__cam_k;

/* One block of a row gather: its plan, and what the stereo rigs keep of each match. */
typedef struct sbl__block {
    sbl__tap_plan p;
    double psx[SBL__BLOCK], psy[SBL__BLOCK]; /* stereo: each match's position            */
    sbl__cam_k cam[2]; /* stereo, two cameras: the maps to the source (for this row in
                          lane mode 2) and back to the target (sbl__stereo_block_start);
                          temporal, the camera: cam[0] its map for this row */
    unsigned char snapped[SBL__BLOCK];       /* stereo: a far lane (see SBL__FAR_PX)     */
    int x0, n, y;                            /* columns [x0, x0 + n) of row y            */
    int sky;                                 /* every planned entry expects sky          */
    int mode;                                /* the rig's lane plan for this row (hooks) */
    int row_state;                           /* the hooks' per-row facts (-1: not yet)   */
    /* 1: one motion vector for the whole block (sbl__temporal_uniform_block), the
       footprints of entries [u_lo, u_hi) inside the image: its fractions and the tap
       indices of entry 0 */
    int uni, u_lo, u_hi;
    float u_fx, u_fy;
    int u_first[5]; /* colour, depth, N, normals, ids (as sbl__tap_plan's lane_step) */
} sbl__block;

#if defined(__GNUC__)
#define SBL__RARE __attribute__((noinline)) /* a rare path kept out of the hot loop's code */
#else
#define SBL__RARE
#endif

/* ---- the 3x3 fallback in lanes ----------------------------------------------
   Entries whose taps weigh below 1e-3 (redo 2) take the pixel gather's 3x3 fallback.
   Most of them are disocclusions, where no pixel of the window passes the depth test:
   the fallback then finds nothing and returns 0. That is decided VW entries at a time
   here, before any colour is read: the fallback's depth test (sbl__depth_match, its
   limit formed once as it forms it) on the nine depths in lanes. */

/* Bits of the lanes none of whose nine window pixels passes the depth test; di: the
   depth index of each lane's window corner (cx - 1, cy - 1), the window inside the
   image; ze, sl: the expected depth and its slack. */
SBL__INLINE int sbl__window_fails(const sbl__tap_src *s, const int *di, const float *ze_p,
                                  const float *sl_p)
{
    const sbl__v zero = sbl__set1(0.0f), ze = sbl__load(ze_p);
    const sbl__v lim = sbl__add(sbl__mul(sbl__set1(s->depth_tolerance), ze), sbl__load(sl_p));
    const sbl__m inf_e = sbl__posinf(ze);
    sbl__m any = sbl__gt(zero, zero);
    int i, j;
    for (j = 0; j < 3; ++j)
        for (i = 0; i < 3; ++i) {
            /* (rows 0 .. 2 and columns 0 .. 2 of the view exist: w, h >= 3 here) */
            const sbl__v d = sbl__gatheri(s->depth.p + j * s->depth.stride + i * s->depth.step, di);
            const sbl__m inf_t = sbl__posinf(d);
            const sbl__m near = sbl__mand(sbl__mandnot(sbl__gt(d, zero), sbl__nonfinite(d)),
                                          sbl__le(sbl__abs(sbl__sub(d, ze)), lim));
            any = sbl__mor(any, sbl__mor(sbl__mand(inf_e, inf_t),
                                         sbl__mandnot(near, sbl__mor(inf_e, inf_t))));
        }
    return ~sbl__mbits(any) & ((1 << SBL__VW) - 1);
}

/* sbl__gather_fallback at (sx, sy) with expected depth ze and slack sl into ring column x */
static SBL__RARE void sbl__fallback_put(const sbl__tap_src *s, sbl__ring_row *r, int x, double sx,
                                        double sy, float ze, float sl, int flag,
                                        const sbl__tap_plan *p, int entry)
{
    float tmp[4] = {0, 0, 0, 0}, nbuf[3];
    sbl__tap_want t;
    float n;
    t.depth = ze;
    t.depth_slack = sl;
    sbl__tap_plan_want(s, p, entry, &t, nbuf); /* normal and id (p: the plan, if any) */
    n = sbl__gather_fallback(s, &t, sx, sy, tmp);
    if (flag) sbl__ring_put_flag(r, x, n, tmp, s->color.ch);
    else sbl__ring_put(r, x, n, tmp, s->color.ch);
}

/* The same for the evidence plane into r->e (as a ratio, sbl__evidence_pixel's test).
   Where the colour's taps weigh below 1e-3 the plane's own gather reaches its fallback
   too, at the same position with the same expected depth: with the same tests its
   weights are the same, and a non-finite plane value only drops more taps (a sum of
   fewer non-negative weights is no larger). The tail plane (r->tl) likewise, into its
   rate and variance (sbl__tail_pixel's test). */
static SBL__RARE void sbl__fallback_put_evidence(sbl__ring_row *r, int x, double sx, double sy,
                                                 float ze, float sl, const sbl__tap_plan *p,
                                                 int entry)
{
    float tmp[4] = {0, 0, 0, 0}, nbuf[3];
    sbl__tap_want t;
    float n;
    t.depth = ze;
    t.depth_slack = sl;
    if (r->e) {
        sbl__tap_plan_want(&r->e_rp->src, p, entry, &t, nbuf); /* the colour's normal and id */
        n = sbl__gather_fallback(&r->e_rp->src, &t, sx, sy, tmp);
        r->e[x] = n > 0.0f && tmp[0] > 0.0f && tmp[0] <= SBL__CAST(float, SBL__POOL_RATIO_CAP) ? tmp[0] : 1.0f;
    }
    if (r->tl[0]) {
        float v[4] = {0, 0, 0, 0};
        sbl__tap_plan_want(&r->tl_rp->src, p, entry, &t, nbuf);
        n = sbl__gather_fallback(&r->tl_rp->src, &t, sx, sy, v);
        sbl__tail_put(r->tl[0] + x, r->tl[1] + x, n > 0.0f, v[0], v[1]);
    }
}

/* The 3x3 fallback for ring columns x0 + e[k] (k < n) at source positions (sx[k], sy[k])
   with expected depths ze[e[k]] and slacks sl[e[k]] (the plan's): a reset where sbl__window_fails says the
   window holds nothing (the fallback's own result there), else sbl__gather_fallback.
   flag: the puts flag unsafe values (sbl__ring_put_flag). p: the plan, for the normal and
   id tests' expectations (a window that fails the depth test fails them all the same).
   ev: the evidence plane too (sbl__fallback_lanes_ev). */
SBL__INLINE void sbl__fallback_lanes_in(const sbl__tap_src *s, sbl__ring_row *r, int x0, const int *e,
                                        const double *sx, const double *sy, const float *ze,
                                        const float *sl, int n, int flag, const sbl__tap_plan *p,
                                        int ev)
{
    const int ch = s->color.ch;
    const double wl = SBL__CAST(double, s->width) - 1.0, hl = SBL__CAST(double, s->height) - 1.0;
    int k = 0;
    while (k < n) {
        int di[SBL__VW], lane[SBL__VW], m = 0, none = 0, l;
        float zl[SBL__VW], ll[SBL__VW];
        for (; k < n && m < SBL__VW; ++k) {
            /* floor(sx) in [1, w - 2] (sx >= 1: its truncation), likewise y */
            if (s->use_depth && sx[k] >= 1.0 && sx[k] < wl && sy[k] >= 1.0 && sy[k] < hl) {
                const int cx = SBL__CAST(int, sx[k]), cy = SBL__CAST(int, sy[k]);
                di[m] = SBL__CAST(int, SBL__CAST(ptrdiff_t, cy - 1) * s->depth.stride +
                                           SBL__CAST(ptrdiff_t, cx - 1) * s->depth.step);
                zl[m] = ze[e[k]];
                ll[m] = sl[e[k]];
                lane[m++] = k;
            } else {
                sbl__fallback_put(s, r, x0 + e[k], sx[k], sy[k], ze[e[k]], sl[e[k]], flag, p, e[k]);
                if (ev) sbl__fallback_put_evidence(r, x0 + e[k], sx[k], sy[k], ze[e[k]], sl[e[k]], p, e[k]);
            }
        }
        if (!m) break;
        for (l = m; l < SBL__VW; ++l) { di[l] = di[0]; zl[l] = zl[0]; ll[l] = ll[0]; }
        none = sbl__window_fails(s, di, zl, ll);
        for (l = 0; l < m; ++l) {
            const int j = lane[l];
            if ((none >> l) & 1) {
                sbl__ring_put(r, x0 + e[j], 0.0f, NULL, ch);
                /* (the planes' windows fail the same tests) */
                if (ev && r->e) r->e[x0 + e[j]] = 1.0f;
                if (ev && r->tl[0]) r->tl[0][x0 + e[j]] = r->tl[1][x0 + e[j]] = 0.0f;
            } else {
                sbl__fallback_put(s, r, x0 + e[j], sx[j], sy[j], ze[e[j]], sl[e[j]], flag, p, e[j]);
                if (ev) sbl__fallback_put_evidence(r, x0 + e[j], sx[j], sy[j], ze[e[j]], sl[e[j]], p, e[j]);
            }
        }
    }
}

static void sbl__fallback_lanes(const sbl__tap_src *s, sbl__ring_row *r, int x0, const int *e,
                                const double *sx, const double *sy, const float *ze,
                                const float *sl, int n, int flag, const sbl__tap_plan *p)
{
    sbl__fallback_lanes_in(s, r, x0, e, sx, sy, ze, sl, n, flag, p, 0);
}

/* sbl__fallback_lanes with the evidence plane (r->e): a reset is 1 there, else the
   plane's own fallback */
static SBL__RARE void sbl__fallback_lanes_ev(const sbl__tap_src *s, sbl__ring_row *r, int x0,
                                             const int *e, const double *sx, const double *sy,
                                             const float *ze, const float *sl, int n, int flag,
                                             const sbl__tap_plan *p)
{
    sbl__fallback_lanes_in(s, r, x0, e, sx, sy, ze, sl, n, flag, p, 1);
}

/* The one driver of the row gathers (temporal and stereo): columns [xa, xb) of row y in
   blocks of SBL__BLOCK. Per block: `start` (the tile shortcuts: returns 1 when it wrote
   the block; sets the block's sky and lane mode), the plan (`plan_vec` plans VW entries
   from entry i in lanes and returns the entries it leaves to `plan_one`, or -1 where it
   cannot), the tap stage, then the pixel gather for every entry handed back, or the
   rig's own last step (`after`, when given: far lanes, back-check and that pixel
   gather, in one pass). `run` (optional): settles a block's first entries in a pass of
   its own before the plan and returns how many (no redo among them); the plan and the
   tap stage take the rest. Blocks narrower than a vector take the pixel gather. Inlined
   with constant hooks: no call through a pointer. */
SBL__INLINE void sbl__row_gather_blocks(const void *ctx, sbl__ring_row *r, int y, int xa,
                                        int xb, const sbl__tap_src *src, int fallback,
                                        sbl__gather_fn pixel,
                                        int (*start)(const void *, sbl__ring_row *, sbl__block *),
                                        int (*plan_vec)(const void *, sbl__block *, int),
                                        void (*plan_one)(const void *, sbl__block *, int),
                                        void (*after)(const void *, sbl__ring_row *, sbl__block *),
                                        void (*fallback_block)(const void *, sbl__ring_row *,
                                                               sbl__block *),
                                        int (*run)(const void *, sbl__ring_row *, sbl__block *,
                                                   int, int),
                                        int flag, int ev)
{
    const int ch = src->color.ch;
    sbl__block b;
    int i, i0;
    b.y = y;
    b.row_state = -1;
    for (i = 0; i < SBL__VW; ++i) { /* |step| < INT_MAX / VW: sbl__row_gather_ok */
        b.p.lane_step[0][i] = i * SBL__CAST(int, src->color.step);
        b.p.lane_step[1][i] = i * SBL__CAST(int, src->depth.step);
        b.p.lane_step[2][i] = i * SBL__CAST(int, src->length.step);
        b.p.lane_step[3][i] = src->use_normal ? i * SBL__CAST(int, src->normals.step) : 0;
        b.p.lane_step[4][i] = src->use_id ? i * SBL__CAST(int, src->ids.step) : 0;
    }
    for (b.x0 = xa; b.x0 < xb; b.x0 += SBL__BLOCK) {
        b.n = xb - b.x0 < SBL__BLOCK ? xb - b.x0 : SBL__BLOCK;
        if (b.n < SBL__VW) {
            for (i = 0; i < b.n; ++i) {
                float tmp[4] = {0, 0, 0, 0};
                if (flag) sbl__ring_put_flag(r, b.x0 + i, pixel(ctx, b.x0 + i, y, tmp), tmp, ch);
                else sbl__ring_put(r, b.x0 + i, pixel(ctx, b.x0 + i, y, tmp), tmp, ch);
                if (ev && r->e) r->e[b.x0 + i] = sbl__evidence_pixel(r->e_rp, b.x0 + i, y);
                if (ev && r->tl[0]) sbl__tail_pixel(r, b.x0 + i, y);
            }
            continue;
        }
        b.sky = 0;
        b.mode = 0;
        b.uni = 0;
        if (start(ctx, r, &b)) continue;
        i0 = 0;
        if (run) { /* entries [0, i0) settled already (no redo among them) */
            i0 = run(ctx, r, &b, fallback, ev);
            if (i0 >= b.n) continue;
            if (i0 > b.n - SBL__VW) i0 = b.n - SBL__VW; /* (planned again: the same values) */
        }
        for (i = i0; i < b.n;) {
            int bits = i + SBL__VW <= b.n ? plan_vec(ctx, &b, i) : -1, l = SBL__VW;
            if (bits < 0) { bits = 1; l = 1; }
            for (; bits; ++i, --l, bits >>= 1)
                if (bits & 1) plan_one(ctx, &b, i);
            i += l;
        }
        if (ev) sbl__row_taps_flag_ev(src, &b.p, i0, b.n, fallback, r, b.x0, b.sky);
        else if (flag) sbl__row_taps_flag(src, &b.p, i0, b.n, fallback, r, b.x0, b.sky);
        else sbl__row_taps(src, &b.p, i0, b.n, fallback, r, b.x0, b.sky);
        if (after) {
            after(ctx, r, &b);
            continue;
        }
        {   /* redo is rare: one look at the whole block first */
            uint64_t any = 0, u;
            for (i = 0; i + 8 <= b.n; i += 8) { memcpy(&u, b.p.redo + i, 8); any |= u; }
            for (; i < b.n; ++i) any |= b.p.redo[i];
            if (!any) continue;
        }
        if (fallback_block) fallback_block(ctx, r, &b); /* (clears the redo it settles) */
        for (i = 0; i < b.n; ++i) {
            if (i + 8 <= b.n) { /* eight entries at a time: redo is rare */
                uint64_t any;
                memcpy(&any, b.p.redo + i, 8);
                if (!any) { i += 7; continue; }
            }
            if (b.p.redo[i]) {
                /* (3: only the evidence and tail planes' pixel gathers, see
                   sbl__lanes_taps; a plane whose lanes were finite gets the same bits) */
                if (!ev || b.p.redo[i] != 3) {
                    float tmp[4] = {0, 0, 0, 0};
                    const float nx = pixel(ctx, b.x0 + i, y, tmp);
                    if (flag) sbl__ring_put_flag(r, b.x0 + i, nx, tmp, ch);
                    else sbl__ring_put(r, b.x0 + i, nx, tmp, ch);
                }
                if (ev && r->e) r->e[b.x0 + i] = sbl__evidence_pixel(r->e_rp, b.x0 + i, y);
                if (ev && r->tl[0]) sbl__tail_pixel(r, b.x0 + i, y);
            }
        }
    }
}

/* Can the row gather address every tap of this source with int offsets (every view it
   tests: normals and ids where their tests run, sbl__lanes_nid_ok)? */
static int sbl__row_gather_ok(const sbl__tap_src *s)
{
    const sbl__flat *f[5];
    int i;
    if (s->width < 2 || s->height < 2) return 0;
    f[0] = &s->color; f[1] = &s->depth; f[2] = &s->length;
    f[3] = s->use_normal ? &s->normals : NULL; f[4] = s->use_id ? &s->ids : NULL;
    for (i = 0; i < 5; ++i) {
        double span;
        if (!f[i] || !f[i]->p) continue;
        span = SBL__CAST(double, s->height - 1) * fabs(SBL__CAST(double, f[i]->stride)) +
               SBL__CAST(double, s->width) * SBL__CAST(double, f[i]->step);
        if (!(span < SBL__CAST(double, INT_MAX) / 2)) return 0;
    }
    return 1;
}

/* Can the lane plans take row y of this call at all (sbl__temporal_plan_lanes_scaled, any
   finite scale of the motion vectors: UV, NDC)? Motion vectors, images up to 2^15
   pixels (positions exact in float), target normals and ids read in lanes
   (sbl__lanes_want_nid), and an interior row (the depth slack reads both neighbours);
   motion and target depth packed (pixel steps 2 and 1). */
SBL__INLINE int sbl__temporal_plan_scaled_ok(const sbl__temporal_rp *s, int y)
{
    const int w = s->src.width, h = s->src.height;
    return s->source == SBL_TEMPORAL_MOTION && w <= 32768 && h <= 32768 && sbl__geo_nid_lanes_ok(&s->geo) &&
           y >= 1 && y + 1 < h && s->motion.step == 2 && (!s->geo.depth.p || s->geo.depth.step == 1);
}

/* Can sbl__temporal_plan_lanes (float lanes) plan row y? The same, with motion vectors
   in pixels (|k| = 1: the products are exact). */
SBL__INLINE int sbl__temporal_plan_lanes_ok(const sbl__temporal_rp *s, int y)
{
    return fabs(s->motion_kx) == 1.0 && fabs(s->motion_ky) == 1.0 && sbl__temporal_plan_scaled_ok(s, y);
}

/* The target side of sbl__tap_want_init for the VW pixels x .. x + VW - 1 (in [0, w)) of
   an interior row (rows y - 1 and y + 1 exist), when the target has depth (its normals
   and ids: sbl__lanes_want_nid):
   valid geometry is z > 0 (NaN and -inf fail, +inf is sky); the slack is
   sbl__depth_slack's (sbl__slack_axis per axis, 0 for a non-finite z).
   No NaN may reach a min: -ffast-math (finite-math-only, no signed zeros) makes gcc's
   min intrinsics commutative, so a NaN operand's result depends on register allocation.
   Where every difference is finite (then so is z: the common case) the slack is the sum
   of the mins; else every lane takes sbl__slack_axis's rule written out on the bits. */
/* (dp: the target depth at (x, y), ds: its row stride; the caller's loop may keep its
   row pointer, sbl__temporal_uniform_run. edge: x may be an edge column (0: the caller
   knows it is not, the test skipped) */
SBL__INLINE sbl__m sbl__lanes_want_in(const float *dp, ptrdiff_t ds, int w, int x, sbl__v *z,
                                      sbl__v *slack, int edge)
{
    const sbl__v zero = sbl__set1(0.0f);
    sbl__v dax, dbx, day, dby;
    *z = sbl__load(dp);
    SBL__PREFETCH(dp, 2 * ds); /* (the next row's new row) */
    dax = sbl__abs(sbl__sub(*z, sbl__load(dp - 1)));
    dbx = sbl__abs(sbl__sub(sbl__load(dp + 1), *z));
    if (edge && (x == 0 || x + SBL__VW == w)) {
        /* an edge column (its missing neighbour read from the previous or next row in
           memory, a valid address on an interior row, then replaced before any test): the
           one-sided difference is the other side's, as sbl__depth_slack takes it */
        const sbl__v xl = sbl__add(sbl__set1(SBL__CAST(float, x)), sbl__load(sbl__lane_f));
        dax = sbl__sel(sbl__le(xl, zero), dbx, dax);
        dbx = sbl__sel(sbl__le(sbl__set1(SBL__CAST(float, w - 1)), xl), dax, dbx);
    }
    day = sbl__abs(sbl__sub(*z, sbl__load(dp - ds)));
    dby = sbl__abs(sbl__sub(sbl__load(dp + ds), *z));
    /* >= 0 each: the sum is finite iff all four are (or it overflows: the exact path) */
    if (!sbl__mbits(sbl__nonfinite(sbl__add(sbl__add(dax, dbx), sbl__add(day, dby))))) {
        *slack = sbl__add(sbl__min(dax, dbx), sbl__min(day, dby));
    } else {
        /* da < db ? da : db, then 0 if not finite: a NaN db gives 0 (db -> 0), a NaN da
           gives db (da -> +inf, as is an infinite da); the min of the NaN-free values */
        const sbl__v inf = sbl__set1(SBL__CAST(float, HUGE_VAL));
        sbl__v sx, sy;
        dax = sbl__sel(sbl__nonfinite(dax), inf, dax);
        dbx = sbl__sel(sbl__mandnot(sbl__nonfinite(dbx), sbl__posinf(dbx)), zero, dbx);
        sx = sbl__min(dax, dbx);
        sx = sbl__sel(sbl__nonfinite(sx), zero, sx);
        day = sbl__sel(sbl__nonfinite(day), inf, day);
        dby = sbl__sel(sbl__mandnot(sbl__nonfinite(dby), sbl__posinf(dby)), zero, dby);
        sy = sbl__min(day, dby);
        sy = sbl__sel(sbl__nonfinite(sy), zero, sy);
        *slack = sbl__sel(sbl__nonfinite(*z), zero, sbl__add(sx, sy));
    }
    return sbl__gt(*z, zero);
}

SBL__INLINE sbl__m sbl__lanes_want_at(const float *dp, ptrdiff_t ds, int w, int x, sbl__v *z,
                                      sbl__v *slack)
{
    return sbl__lanes_want_in(dp, ds, w, x, z, slack, 1);
}

SBL__INLINE sbl__m sbl__lanes_want(const sbl__flat *depth, int w, int x, int y, sbl__v *z,
                                   sbl__v *slack)
{
    return sbl__lanes_want_at(SBL__AT(*depth, x, y), depth->stride, w, x, z, slack);
}

/* Tap indices y0 stride + x0 step of a view (NULL: 0) for VW lanes of integer-valued
   floats, in double lanes (exact: the products stay below 2^53, the sums are valid
   indices). */
SBL__INLINE void sbl__plan_index(int *out, const float *x0s, const float *y0s, const sbl__flat *f)
{
    int j;
    if (!f) {
        for (j = 0; j < SBL__VW; ++j) out[j] = 0;
        return;
    }
#if SBL__VW == 8
    /* in int lanes: the products and the sum are the index's exact terms (each a valid
       index's, below INT_MAX / 2: sbl__row_gather_ok) */
    _mm256_storeu_si256(SBL__PCAST(__m256i *, out),
                        _mm256_add_epi32(_mm256_mullo_epi32(_mm256_cvttps_epi32(_mm256_loadu_ps(y0s)),
                                                            _mm256_set1_epi32(SBL__CAST(int, f->stride))),
                                         _mm256_mullo_epi32(_mm256_cvttps_epi32(_mm256_loadu_ps(x0s)),
                                                            _mm256_set1_epi32(SBL__CAST(int, f->step)))));
    return;
#elif SBL__VW == 16
    _mm512_storeu_si512(out, _mm512_add_epi32(_mm512_mullo_epi32(_mm512_cvttps_epi32(_mm512_loadu_ps(y0s)),
                                                                 _mm512_set1_epi32(SBL__CAST(int, f->stride))),
                                              _mm512_mullo_epi32(_mm512_cvttps_epi32(_mm512_loadu_ps(x0s)),
                                                                 _mm512_set1_epi32(SBL__CAST(int, f->step)))));
    return;
#endif
    for (j = 0; j < SBL__VW; j += SBL__DW)
        sbl__dstorei(out + j, sbl__dadd(sbl__dmul(sbl__dfromf(y0s + j), sbl__dset1(SBL__CAST(double, f->stride))),
                                        sbl__dmul(sbl__dfromf(x0s + j), sbl__dset1(SBL__CAST(double, f->step)))));
}

/* Tap indices of a view (NULL: 0) for VW lanes whose first taps are consecutive pixels
   from (x0, y0): y0 stride + (x0 + l) step, in int lanes (each a valid index, and the
   sums exact: |index| < INT_MAX / 2, sbl__row_gather_ok). */
SBL__INLINE void sbl__plan_index_run(int *out, int x0, int y0, const sbl__flat *f,
                                     const int *lane_step)
{
    int j, first;
    if (!f) {
        for (j = 0; j < SBL__VW; ++j) out[j] = 0;
        return;
    }
    first = SBL__CAST(int, SBL__CAST(ptrdiff_t, y0) * f->stride + SBL__CAST(ptrdiff_t, x0) * f->step);
    for (j = 0; j < SBL__VW; j += 4)
        _mm_storeu_si128(SBL__PCAST(__m128i *, out + j),
                         _mm_add_epi32(_mm_set1_epi32(first),
                                       _mm_loadu_si128(SBL__PCAST(const __m128i *, lane_step + j))));
}

/* The normal / id side of sbl__tap_want_init for the VW pixels x .. x + VW - 1 of row y
   into plan entries [i, i + VW): the target's normal, its squared length (the same
   float operations) and its id; lanes whose squared length is not finite leave `keep`
   (sbl__tap_want_init resets them). Returns keep. */
SBL__INLINE sbl__m sbl__lanes_want_nid(const sbl__target_geo *g, const sbl__tap_src *src,
                                       sbl__tap_plan *p, int i, int x, int y, sbl__m keep)
{
    if (g->normals.p) {
        sbl__v m0, m1, m2, mm;
        sbl__lanes_normals(&g->normals, x, y, &m0, &m1, &m2);
        mm = sbl__add(sbl__add(sbl__mul(m0, m0), sbl__mul(m1, m1)), sbl__mul(m2, m2));
        keep = sbl__mandnot(keep, sbl__nonfinite(mm));
        if (src->use_normal) {
            sbl__store(p->tn[0] + i, m0);
            sbl__store(p->tn[1] + i, m1);
            sbl__store(p->tn[2] + i, m2);
            sbl__store(p->tn2 + i, mm);
        }
    }
    if (src->use_id) sbl__store(p->tid + i, sbl__lanes_px(&g->ids, x, y, 0));
    return keep;
}

/* The taps' indices in the source's normals and ids (where their tests run) for plan
   entries [i, i + VW) from the footprints' corners (sbl__plan_index). */
SBL__INLINE void sbl__plan_index_nid(const sbl__tap_src *src, sbl__tap_plan *p, int i,
                                     const float *x0s, const float *y0s)
{
    if (src->use_normal) sbl__plan_index(p->ni + i, x0s, y0s, &src->normals);
    if (src->use_id) sbl__plan_index(p->ii + i, x0s, y0s, &src->ids);
}

/* |m| = 0 or in [2^-8, 2^15) (sbl__plan_lanes' exact motion), on the bits b of |m|: b ==
   0, or b - bits(2^-8) below bits(2^15) - bits(2^-8) unsigned, compared signed with the
   top bit flipped. NaN and inf fail, and no float compare is involved (-ffast-math). */
SBL__INLINE sbl__m sbl__motion_exact(sbl__v m)
{
#if SBL__VW == 16
    const __m512i b = _mm512_and_si512(_mm512_castps_si512(m), _mm512_set1_epi32(0x7fffffff));
    return SBL__CAST(sbl__m, _mm512_cmpeq_epi32_mask(b, _mm512_setzero_si512()) |
                                 _mm512_cmpgt_epi32_mask(_mm512_set1_epi32(-0x74800000),
                                                         _mm512_add_epi32(b, _mm512_set1_epi32(0x44800000))));
#elif SBL__VW == 8
    const __m256i b = _mm256_and_si256(_mm256_castps_si256(m), _mm256_set1_epi32(0x7fffffff));
    return _mm256_castsi256_ps(_mm256_or_si256(
        _mm256_cmpeq_epi32(b, _mm256_setzero_si256()),
        _mm256_cmpgt_epi32(_mm256_set1_epi32(-0x74800000), _mm256_add_epi32(b, _mm256_set1_epi32(0x44800000)))));
#else
    const __m128i b = _mm_and_si128(_mm_castps_si128(m), _mm_set1_epi32(0x7fffffff));
    return _mm_castsi128_ps(_mm_or_si128(
        _mm_cmpeq_epi32(b, _mm_setzero_si128()),
        _mm_cmpgt_epi32(_mm_set1_epi32(-0x74800000), _mm_add_epi32(b, _mm_set1_epi32(0x44800000)))));
#endif
}

/* The plan's stores for VW entries from entry i (pixels x .. x + VW - 1), shared by the
   lane plans: lanes `fast` (bits_fast) get fractions fx, fy, the expected depth z and its
   slack, first taps at (x0f, y0f) (fmx = x0f - x - l, the taps' integer offset); lanes
   bits_redo go to the pixel gather; the others reset. */
SBL__INLINE void sbl__plan_lanes_store(const sbl__tap_src *src, sbl__tap_plan *p, int i, int x, sbl__m fast,
                                       int bits_fast, int bits_redo, sbl__v fx, sbl__v fy, sbl__v fmx,
                                       sbl__v x0f, sbl__v y0f, sbl__v z, sbl__v slack, int flat)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    float x0s[SBL__VW + 4], y0s[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    int l, uniform;
    sbl__store(p->fx + i, sbl__sel(fast, fx, zero));
    sbl__store(p->fy + i, flat ? zero : sbl__sel(fast, fy, zero));
    sbl__store(p->depth + i, sbl__sel(fast, z, one));
    sbl__store(p->slack + i, sbl__sel(fast, slack, zero));
    sbl__store(p->fast + i, sbl__sel(fast, one, zero));
    /* tap (0, 0) where not fast: a valid address, result unused */
    sbl__store(x0s, sbl__sel(fast, x0f, zero));
    sbl__store(y0s, sbl__sel(fast, y0f, zero));
    {   /* redo bytes, four lanes per table entry (x86: little-endian bytes) */
        static const unsigned int bytes[16] = {
            0x00000000u, 0x00000001u, 0x00000100u, 0x00000101u, 0x00010000u, 0x00010001u,
            0x00010100u, 0x00010101u, 0x01000000u, 0x01000001u, 0x01000100u, 0x01000101u,
            0x01010000u, 0x01010001u, 0x01010100u, 0x01010101u};
        const int redo = bits_redo;
        if (!redo) memset(p->redo + i, 0, SBL__VW);
        else for (l = 0; l < SBL__VW; l += 4) memcpy(p->redo + i + l, &bytes[(redo >> l) & 15], 4);
    }
    /* every lane fast, at one integer offset (x0 - x, y0 - y equal in all lanes: uniform
       motion): consecutive first taps, indexed in int lanes and flagged for the taps */
    uniform = bits_fast == (1 << SBL__VW) - 1 &&
              sbl__mbits(sbl__mand(sbl__le(fmx, sbl__set1(x0s[0] - SBL__CAST(float, x))),
                                   sbl__le(sbl__set1(x0s[0] - SBL__CAST(float, x)), fmx))) == (1 << SBL__VW) - 1 &&
              (flat || sbl__mbits(sbl__mand(sbl__le(y0f, sbl__set1(y0s[0])), sbl__le(sbl__set1(y0s[0]), y0f))) ==
                           (1 << SBL__VW) - 1);
    memset(p->uniform + i, 0, SBL__VW);
    if (uniform) {
        const int cx = SBL__CAST(int, x0s[0]), cy = SBL__CAST(int, y0s[0]);
        p->uniform[i] = 1;
        sbl__plan_index_run(p->ci + i, cx, cy, &src->color, p->lane_step[0]);
        sbl__plan_index_run(p->di + i, cx, cy, src->use_depth ? &src->depth : NULL, p->lane_step[1]);
        sbl__plan_index_run(p->li + i, cx, cy, src->length.p ? &src->length : NULL, p->lane_step[2]);
        if (src->use_normal) sbl__plan_index_run(p->ni + i, cx, cy, &src->normals, p->lane_step[3]);
        if (src->use_id) sbl__plan_index_run(p->ii + i, cx, cy, &src->ids, p->lane_step[4]);
        return;
    }
    if (src->use_normal || src->use_id) sbl__plan_index_nid(src, p, i, x0s, y0s);
    p->uniform[i] = 2; /* lanes apart: not contiguous, no need to test (sbl__row_taps_ch) */
    sbl__plan_index(p->ci + i, x0s, y0s, &src->color);
    sbl__plan_index(p->di + i, x0s, y0s, src->use_depth ? &src->depth : NULL);
    sbl__plan_index(p->li + i, x0s, y0s, src->length.p ? &src->length : NULL);
}

/* sbl__tap_plan_set for the VW entries from entry i (pixels x .. x + VW - 1) at source
   positions (sx[l], sy[l]) given in double, for the plans whose positions are not exact
   in float (UV / NDC motion, motion that is nearly 0, the cameras): lanes outside
   bits_keep, and positions outside [0, w) x [0, h), reset (the callers' own test, as
   the reference makes it before sbl__tap_plan_set); footprints with a tap outside the
   image go to the pixel gather; the others are fast, with the reference's double floor
   of sx - 0.5 and its fraction rounded to float once. In double lanes (the floor exact:
   inside, |sx| < 2^15, as the callers' gates allow images up to 2^15 pixels, so the
   taps' corners are exact as floats), then the lane plan's stores with the expected
   depth z and its slack. Returns the lanes that are fast or redone (a position
   inside). */
SBL__INLINE int sbl__plan_lanes_at(const sbl__tap_src *src, sbl__tap_plan *p, int i, int x, int bits_keep,
                                   const double *sx, const double *sy, sbl__v z, sbl__v slack)
{
    const sbl__dv dzero = sbl__dset1(0.0), half = sbl__dset1(0.5), wd = sbl__dset1(SBL__CAST(double, src->width)),
                  hd = sbl__dset1(SBL__CAST(double, src->height)),
                  w2 = sbl__dset1(SBL__CAST(double, src->width - 2)),
                  h2 = sbl__dset1(SBL__CAST(double, src->height - 2));
    const int dmask = (1 << SBL__DW) - 1;
    float fxs[SBL__VW], fys[SBL__VW], x0s[SBL__VW], y0s[SBL__VW], fms[SBL__VW], fast_s[SBL__VW];
    int j, l, bits_fast = 0, bits_in = 0;
    for (j = 0; j < SBL__VW; j += SBL__DW) {
        const sbl__dv sxv = sbl__dload(sx + j), syv = sbl__dload(sy + j);
        const sbl__dv bx = sbl__dsub(sxv, half), by = sbl__dsub(syv, half);
        /* 0 <= s < w: a NaN fails the first test (and so needs no second) */
        const sbl__dm inm = sbl__dm_andnot(sbl__dm_andnot(sbl__dm_and(sbl__dle_m(dzero, sxv), sbl__dle_m(dzero, syv)),
                                                          sbl__dle_m(wd, sxv)),
                                           sbl__dle_m(hd, syv));
        const int in = (bits_keep >> j) & dmask & sbl__dm_bits(inm);
        /* (lanes not inside are not used: their floor may be anything) */
        const sbl__dv x0 = sbl__dfloor(bx), y0 = sbl__dfloor(by);
        const int fast = in & sbl__dm_bits(sbl__dm_and(sbl__dm_and(sbl__dle_m(dzero, x0), sbl__dle_m(dzero, y0)),
                                                       sbl__dm_and(sbl__dle_m(x0, w2), sbl__dle_m(y0, h2))));
        sbl__dstoref(fxs + j, sbl__dsub(bx, x0));
        sbl__dstoref(fys + j, sbl__dsub(by, y0));
        sbl__dstoref(x0s + j, x0);
        sbl__dstoref(y0s + j, y0);
        sbl__dstoref(fms + j, sbl__dsub(x0, sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(SBL__CAST(double, x + j)))));
        bits_fast |= fast << j;
        bits_in |= in << j;
    }
    for (l = 0; l < SBL__VW; ++l) fast_s[l] = SBL__CAST(float, (bits_fast >> l) & 1);
    sbl__plan_lanes_store(src, p, i, x, sbl__gt(sbl__load(fast_s), sbl__set1(0.0f)), bits_fast,
                          bits_in & ~bits_fast, sbl__load(fxs), sbl__load(fys), sbl__load(fms), sbl__load(x0s),
                          sbl__load(y0s), z, slack, 0);
    return bits_in;
}

/* sbl__tap_plan_set for the VW pixels x .. x + VW - 1 of row y at source positions
   (x + 0.5 + mx, y + 0.5 + my), where lanes `keep`, in float lanes with the same
   results: for |m| = 0 or in [2^-8, 2^15) and images up to 2^15 pixels, x + 0.5 + m is
   exact in double, so the reference's floor and fraction are floor(m) and the
   correctly rounded m - floor(m), and its bounds tests are exact float comparisons of
   m. Lanes with any other m are left to the scalar plan (returned as bits). flat (a
   constant where inlined): my is +0 in every lane, as on a parallel rig's rows. */
SBL__INLINE int sbl__plan_lanes(const sbl__tap_src *src, sbl__tap_plan *p, int i, int x, int y,
                                sbl__m keep, sbl__v z, sbl__v slack, sbl__v mx, sbl__v my, int flat)
{
    const sbl__v zero = sbl__set1(0.0f), half = sbl__set1(0.5f);
    const sbl__v wf = sbl__set1(SBL__CAST(float, src->width)), hf = sbl__set1(SBL__CAST(float, src->height));
    const sbl__v xf = sbl__add(sbl__set1(SBL__CAST(float, x)), sbl__load(sbl__lane_f)), yf = sbl__set1(SBL__CAST(float, y));
    sbl__v fmx, fmy, x0f, y0f;
    sbl__m exact, fast;
    int bits_scalar, bits_fast, bits_redo;
    /* flat: my is +0 in every lane (the parallel rig): exact, floor 0, y0 = y, fy = 0 */
    exact = flat ? sbl__motion_exact(mx) : sbl__mand(sbl__motion_exact(mx), sbl__motion_exact(my));
    bits_scalar = sbl__mbits(sbl__mandnot(keep, exact));
    keep = sbl__mand(keep, exact);
    fmx = sbl__floor(mx);
    fmy = flat ? zero : sbl__floor(my);
    x0f = sbl__add(xf, fmx);
    y0f = flat ? yf : sbl__add(yf, fmy);
    /* the four taps inside the image, else the pixel gather decides */
    fast = sbl__mand(sbl__le(zero, x0f), sbl__le(x0f, sbl__set1(SBL__CAST(float, src->width - 2))));
    if (!flat)
        fast = sbl__mand(fast, sbl__mand(sbl__le(zero, y0f), sbl__le(y0f, sbl__set1(SBL__CAST(float, src->height - 2)))));
    else if (!(y >= 0 && y + 2 <= src->height))
        fast = sbl__gt(zero, zero);
    fast = sbl__mand(fast, keep);
    /* the others kept: the pixel gather where the position is inside the image, else a
       reset (four taps inside imply the position inside: only those need the test);
       x + 0.5 + m in [0, w): m >= -(x + 0.5) and m < w - x - 0.5, both sides exact */
    bits_fast = sbl__mbits(fast);
    bits_redo = sbl__mbits(sbl__mandnot(keep, fast));
    if (bits_redo) {
        sbl__m inside = sbl__mand(sbl__le(sbl__sub(zero, sbl__add(xf, half)), mx),
                                  sbl__gt(sbl__sub(sbl__sub(wf, xf), half), mx));
        inside = sbl__mand(inside, sbl__mand(sbl__le(sbl__sub(zero, sbl__add(yf, half)), my),
                                             sbl__gt(sbl__sub(sbl__sub(hf, yf), half), my)));
        bits_redo &= sbl__mbits(inside);
    }
    /* + 0 turns a -0 fraction (from m = -0) into the reference's +0 */
    sbl__plan_lanes_store(src, p, i, x, fast, bits_fast, bits_redo, sbl__add(sbl__sub(mx, fmx), zero),
                          flat ? zero : sbl__add(sbl__sub(my, fmy), zero), fmx, x0f, y0f, z, slack, flat);
    return bits_scalar;
}

/* The target side of sbl__temporal_rp_pos for the VW pixels x .. x + VW - 1 of row y, for
   the temporal lane plans: the lanes with valid geometry (and normal / id data), their
   depth z and its slack; a sky tile: z = +inf, which is valid geometry with slack 0
   (sbl__lanes_want). */
SBL__INLINE sbl__m sbl__temporal_want_lanes(const sbl__temporal_rp *s, sbl__tap_plan *p, int i, int x, int y,
                                           int sky, sbl__v *z, sbl__v *slack)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    sbl__m keep;
    *z = *slack = zero;
    keep = sky ? sbl__gt(one, zero)
               : (s->geo.depth.p ? sbl__lanes_want(&s->geo.depth, s->geo.width, x, y, z, slack)
                                 : sbl__gt(one, zero));
    if (sky) *z = sbl__set1(SBL__CAST(float, HUGE_VAL));
    if (s->geo.normals.p || s->geo.ids.p) keep = sbl__lanes_want_nid(&s->geo, &s->src, p, i, x, y, keep);
    return keep;
}

/* sbl__temporal_rp_pos and sbl__tap_plan_set in lanes (motion vectors in pixels) */
SBL__INLINE int sbl__temporal_plan_lanes(const sbl__temporal_rp *s, sbl__tap_plan *p, int i,
                                         int x, int y, int sky)
{
    const sbl__v zero = sbl__set1(0.0f);
    const float *mvp = SBL__AT(s->motion, x, y);
    sbl__v z, slack, mx, my;
    sbl__m keep = sbl__temporal_want_lanes(s, p, i, x, y, sky, &z, &slack);
    sbl__motion_packed_lanes(mvp, &mx, &my);
    /* a non-finite m is no exact one: sbl__plan_lanes hands it to the scalar plan, which
       resets it */
    if (s->motion_kx < 0.0) mx = sbl__sub(zero, mx); /* exact: -m (a zero's sign is moot) */
    if (s->motion_ky < 0.0) my = sbl__sub(zero, my);
    /* motion carries no depth change: the expected depth is z (sz = z) */
    return sbl__plan_lanes(&s->src, p, i, x, y, keep, z, slack, mx, my, 0);
}

/* sbl__temporal_rp_pos and sbl__tap_plan_set for motion vectors in UV or NDC units (|k|
   not 1, where x + 0.5 + k m is not exact in float and sbl__plan_lanes does not apply),
   and for the vectors of pixel units sbl__plan_lanes leaves (0 < |m| < 2^-8):
   each lane's position with the reference's double operations (x + 0.5 + k m, less 0.5,
   its floor, the fraction rounded to float once), then the lane plan's stores. The same
   decisions as the reference: a non-finite vector or a position outside the image
   resets, taps outside it go to the pixel gather. */
SBL__NOINLINE int sbl__temporal_plan_lanes_scaled(const sbl__temporal_rp *s, sbl__tap_plan *p, int i,
                                                  int x, int y, int sky)
{
    const float *mvp = SBL__AT(s->motion, x, y);
    const sbl__dv kx = sbl__dset1(s->motion_kx), ky = sbl__dset1(s->motion_ky);
    const sbl__dv yh = sbl__dset1(y + 0.5);
    float mxs[SBL__VW + 4], mys[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    double sx[SBL__VW], sy[SBL__VW];
    sbl__v z, slack, mx, my;
    sbl__m keep = sbl__temporal_want_lanes(s, p, i, x, y, sky, &z, &slack);
    int j;
    sbl__motion_packed_lanes(mvp, &mx, &my);
    keep = sbl__mandnot(sbl__mandnot(keep, sbl__nonfinite(mx)), sbl__nonfinite(my)); /* a reset */
    sbl__store(mxs, mx);
    sbl__store(mys, my);
    for (j = 0; j < SBL__VW; j += SBL__DW) { /* (x + l) + 0.5 + k m, as the reference */
        sbl__dstore(sx + j, sbl__dadd(sbl__dadd(sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(SBL__CAST(double, x + j))),
                                                sbl__dset1(0.5)),
                                      sbl__dmul(kx, sbl__dfromf(mxs + j))));
        sbl__dstore(sy + j, sbl__dadd(yh, sbl__dmul(ky, sbl__dfromf(mys + j))));
    }
    sbl__plan_lanes_at(&s->src, p, i, x, sbl__mbits(keep), sx, sy, z, slack);
    return 0;
}

/* ---- tile classification -----------------------------------------------------
   The row gather decides per tile (a block of up to SBL__BLOCK pixels of one row), from
   the data it reads anyway, whether the tile needs the general plan:
   - SBL__TILE_VOID: no target pixel has geometry (depth 0, negative or NaN): every
     pixel resets, without reading history (nor, camera at rest, anything but the
     motion: a tile at rest resets those pixels itself);
   - SBL__TILE_REST: every source position is the pixel itself (zero motion vectors, or
     a camera at rest over static surfaces): the history is read at the same pixel, with
     no position maths, no footprint and one tap test (sbl__rest_tile);
   - SBL__TILE_SKY: every target pixel is sky (+inf) and moves: the general plan and
     tap stage without the target's depth slack, and with the documented rule for sky
     in its cheapest form as the depth test (the tap is sky);
   - SBL__TILE_GENERAL: the plan and the tap stage, which itself drops the masks on its
     sums (the fallback bookkeeping) for a vector whose taps all pass.
   Each shortcut gives the general path's bits (the same operations on the values that
   matter, or operations whose result is exactly the same), so no result depends on where
   a band, a span or a tile starts. */
enum { SBL__TILE_GENERAL = 0, SBL__TILE_VOID = 1, SBL__TILE_REST = 2, SBL__TILE_SKY = 3 };

/* Can this call use the tile shortcuts on its tiles: the views the shortcut reads with
   vector loads packed (pixel step 1: depth, N; normals and ids any, sbl__rest_nid_ok),
   and, for the camera source, no moving object (whose ids decide per pixel)? */
SBL__INLINE int sbl__temporal_tiles_ok(const sbl__temporal_rp *s)
{
    const sbl__tap_src *src = &s->src;
    return s->tiles && s->history && (s->source == SBL_TEMPORAL_MOTION || !s->moving_count) &&
           (!s->geo.depth.p || s->geo.depth.step == 1) && sbl__geo_nid_lanes_ok(&s->geo) &&
           (!src->use_depth || src->depth.step == 1) && (!src->length.p || src->length.step == 1) &&
           (s->source == SBL_TEMPORAL_MOTION || s->at_rest);
}

/* the bits of two vectors OR-ed (AVX-512's masks are not vectors) */
#if SBL__VW == 16
#define sbl__vor(a, b) _mm512_castsi512_ps(_mm512_or_si512(_mm512_castps_si512(a), _mm512_castps_si512(b)))
#else
#define sbl__vor(a, b) sbl__mor(a, b)
#endif

/* Is every lane +-0? On the bits: -ffast-math lets the compiler turn |a| <= 0 into an
   unordered compare, true for NaN (clang -O3 -march=native did: a NaN motion vector
   passed for a tile at rest). */
SBL__INLINE int sbl__lanes_all_zero(sbl__v a)
{
#if defined(__AVX512F__) && SBL__VW == 16
    return _mm512_test_epi32_mask(_mm512_castps_si512(a), _mm512_set1_epi32(0x7fffffff)) == 0;
#elif defined(__AVX2__) && SBL__VW == 8
    return _mm256_testz_si256(_mm256_castps_si256(a), _mm256_set1_epi32(0x7fffffff));
#elif defined(__SSE2__) && SBL__VW == 4 && !defined(SBL_NO_SIMD)
    return _mm_movemask_epi8(_mm_cmpeq_epi32(_mm_and_si128(_mm_castps_si128(a), _mm_set1_epi32(0x7fffffff)),
                                             _mm_setzero_si128())) == 0xffff;
#else
    float t[SBL__VW];
    int l, nonzero = 0;
    sbl__store(t, a);
    for (l = 0; l < SBL__VW; ++l) nonzero |= !sbl__is_zero(t[l]);
    return !nonzero;
#endif
}

/* Are the motion vectors of tile pixels [x0, x0 + n) of row y all +-0 (kx * +-0 = +-0)?
   The tile's bits OR-ed together are 0 but for the sign bit exactly when every component
   is +-0 (any other value, a NaN included, leaves a bit): one load and one OR per vector. */
SBL__INLINE int sbl__tile_motion_zero(const sbl__temporal_rp *s, int y, int x0, int n)
{
    const float *mp = SBL__AT(s->motion, x0, y);
    int i;
    if (s->motion.step == 2) {
        const int m = 2 * n; /* >= 2 VW */
        sbl__v a = sbl__load(mp), b = sbl__load(mp + SBL__VW);
        /* a moving tile usually shows it in its first pixels */
        if (!sbl__lanes_all_zero(sbl__vor(a, b))) return 0;
        for (i = 2 * SBL__VW; i + 2 * SBL__VW <= m; i += 2 * SBL__VW) {
            a = sbl__vor(a, sbl__load(mp + i));
            b = sbl__vor(b, sbl__load(mp + i + SBL__VW));
        }
        if (i < m) { /* the rest: the last two vectors (overlapping the ones before) */
            a = sbl__vor(a, sbl__load(mp + m - 2 * SBL__VW));
            b = sbl__vor(b, sbl__load(mp + m - SBL__VW));
        }
        return sbl__lanes_all_zero(sbl__vor(a, b));
    }
    for (i = 0; i < n; ++i) {
        const float *m = mp + SBL__CAST(ptrdiff_t, i) * s->motion.step;
        if (!sbl__is_zero(m[0]) || !sbl__is_zero(m[1])) return 0;
    }
    return 1;
}

/* The class of tile [x0, x0 + n) of row y (n >= VW; the call passed
   sbl__temporal_tiles_ok). At rest is decided first: a rest tile settles pixels without
   geometry as a void tile does (they reset), so its depth need not be scanned. */
SBL__INLINE int sbl__temporal_tile_class(const sbl__temporal_rp *s, int y, int x0, int n)
{
    const sbl__v zero = sbl__set1(0.0f);
    int i;
    int sky = 0;
    /* camera at rest: a tile without a moving object's id (the call has no ids here
       unless no object moves, see sbl__temporal_tiles_ok) */
    if (s->source == SBL_TEMPORAL_MOTION ? sbl__tile_motion_zero(s, y, x0, n) : !s->moving_count)
        return SBL__TILE_REST;
    if (s->geo.depth.p) { /* no geometry anywhere: NaN, -inf, 0 and negatives fail z > 0 */
        const float *zp = SBL__AT(s->geo.depth, x0, y);
        const int full = (1 << SBL__VW) - 1;
        int any = 0, all_sky = full;
        for (i = 0;; i += SBL__VW) {
            sbl__v z;
            if (i + SBL__VW > n) i = n - SBL__VW;
            z = sbl__load(zp + i);
            any |= sbl__mbits(sbl__gt(z, zero));
            all_sky &= sbl__mbits(sbl__posinf(z));
            if ((any && all_sky != full) || i + SBL__VW >= n) break;
        }
        if (!any) return SBL__TILE_VOID;
        sky = all_sky == full;
    }
    return sky ? SBL__TILE_SKY : SBL__TILE_GENERAL;
}

/* The normal and id tests of a tile at rest for the VW pixels x .. x + VW - 1 of row y:
   the footprint's one tap is the pixel itself, so its test is the history's normal and
   id against the target's at the same pixel (sbl__lanes_normal_ok, sbl__lanes_id_ok).
   A target normal whose squared length (formed as sbl__tap_want_init forms it) is not
   finite fails too: the pixel gather then resets that pixel, as sbl__tap_want_init
   decides. */
SBL__INLINE sbl__m sbl__rest_nid_ok(const sbl__temporal_rp *s, int x, int y)
{
    const sbl__tap_src *src = &s->src;
    sbl__m ok = sbl__true;
    if (s->geo.normals.p) {
        sbl__v m0, m1, m2, mm;
        sbl__lanes_normals(&s->geo.normals, x, y, &m0, &m1, &m2);
        mm = sbl__add(sbl__add(sbl__mul(m0, m0), sbl__mul(m1, m1)), sbl__mul(m2, m2));
        ok = sbl__mandnot(ok, sbl__nonfinite(mm));
        if (src->use_normal) {
            sbl__v n0, n1, n2;
            sbl__lanes_normals(&src->normals, x, y, &n0, &n1, &n2);
            ok = sbl__mand(ok, sbl__lanes_normal_ok(n0, n1, n2, m0, m1, m2, mm, src->normal_threshold2));
        }
    }
    if (src->use_id)
        ok = sbl__mand(ok, sbl__lanes_id_ok(sbl__lanes_px(&src->ids, x, y, 0), sbl__lanes_px(&s->geo.ids, x, y, 0)));
    return ok;
}

/* A tile at rest, columns [x0, x0 + n) of row y (n >= VW). At the pixel itself the
   pixel gather's footprint has weights 1, 0, 0, 0: only the first tap is tested, its
   sums are 0 + 1 * value, the weight sum 1 and the renormalisation a product by 1 (the
   edge columns and rows, which take its bounds-checked path, give the same). So x* is
   the history colour (+ 0: -0 becomes +0) and N its N wherever that tap passes; the
   depth test passes when |history - target| <= tolerance * target (the slack only
   widens it) or both are sky. Lanes with geometry that this does not settle (depth
   moved beyond that, N <= 0, a NaN or inf) are handed to the pixel gather; lanes
   without geometry reset. */
SBL__INLINE void sbl__rest_tile_ch(const sbl__temporal_rp *s, sbl__ring_row *r, int y, int x0,
                                   int n, int ch, int ev)
{
    const sbl__tap_src *src = &s->src;
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__v tol = sbl__set1(src->depth_tolerance);
    const float *zp = s->geo.depth.p ? SBL__AT(s->geo.depth, x0, y) : NULL;
    const float *hp = src->use_depth ? SBL__AT(src->depth, x0, y) : NULL;
    const float *np = src->length.p ? SBL__AT(src->length, x0, y) : NULL;
    const float *cp = SBL__AT(src->color, x0, y);
    /* ev 1: the evidence plane (laid out as N, which is present) at the pixel itself,
       with the colour's tests: its value where they pass and it is finite; ev 2: the tail
       plane's two values (laid out as N with offsets doubled) likewise, each pixel's pair
       read at once, and the evidence plane where r->e is set */
    const int use_e = ev == 1 || (ev == 2 && r->e), use_t = ev == 2;
    const float *ep = use_e ? SBL__AT(r->e_rp->src.color, x0, y) : NULL;
    const float *tp = use_t ? SBL__AT(r->tl_rp->src.color, x0, y) : NULL;
    const ptrdiff_t cs = src->color.step;
    int i = 0, l, idx[SBL__VW];
    for (l = 0; l < SBL__VW; ++l) idx[l] = l * SBL__CAST(int, cs); /* |cs| < INT_MAX / VW: sbl__row_gather_ok */
    for (;;) {
        int x, bits, flag;
        sbl__m keep, valid, ok, valid_e = sbl__gt(zero, zero), valid_t = valid_e;
        sbl__v nv = one, v[4], vals[6], ve = zero, tr = zero, tv = zero;
        if (i + SBL__VW > n) i = n - SBL__VW; /* the last vector overlaps the one before */
        x = x0 + i;
        /* the history colour, one channel per vector (the channels written out: gcc -O2
           keeps a loop over them, with the vectors in memory) */
        if (ch == 3 && cs == 3) {
            sbl__rgb_lanes(cp + SBL__CAST(ptrdiff_t, i) * 3, &v[0], &v[1], &v[2]);
        } else if (cs == 1) { /* (one channel) */
            v[0] = v[1] = v[2] = v[3] = sbl__load(cp + i);
        } else {
            const float *hp_i = cp + SBL__CAST(ptrdiff_t, i) * cs;
            v[0] = sbl__gatheri(hp_i, idx);
            if (ch > 1) v[1] = sbl__gatheri(hp_i + 1, idx);
            if (ch > 2) v[2] = sbl__gatheri(hp_i + 2, idx);
            if (ch > 3) v[3] = sbl__gatheri(hp_i + 3, idx);
        }
        keep = zp ? sbl__gt(sbl__load(zp + i), zero) : sbl__gt(one, zero);
        valid = keep;
        if (hp) {
            const sbl__v z = sbl__load(zp + i), d = sbl__load(hp + i);
            const sbl__m inf_e = sbl__posinf(z), inf_t = sbl__posinf(d);
            const sbl__m near = sbl__mand(sbl__mandnot(sbl__gt(d, zero), sbl__nonfinite(d)),
                                          sbl__le(sbl__abs(sbl__sub(d, z)), sbl__mul(tol, z)));
            valid = sbl__mand(valid, sbl__mor(sbl__mand(inf_e, inf_t),
                                              sbl__mandnot(near, sbl__mor(inf_e, inf_t))));
        }
        if (s->geo.normals.p || s->geo.ids.p) valid = sbl__mand(valid, sbl__rest_nid_ok(s, x, y));
        if (np) nv = sbl__load(np + i);
        if (use_e) ve = sbl__load(ep + i);
        if (use_t) sbl__lanes2(tp + 2 * SBL__CAST(ptrdiff_t, i), &tr, &tv);
        /* the unsafe-value check of sbl__ring_gather on the values a valid lane takes (v +
           0 is unsafe exactly when v is); a safe value is finite, so where every value is
           safe (the common case) the finiteness tests drop out and nothing is flagged */
        for (l = 0; l < ch; ++l) vals[l] = v[l];
        vals[ch] = nv;
        vals[ch + 1] = ve; /* (finite too: then its tests are the colour's; read where use_e) */
        if (sbl__all_safe(vals, ch + 1 + use_e)) {
            if (np) valid = sbl__mand(valid, sbl__gt(nv, zero));
            valid_e = valid_t = valid;
            flag = 0;
        } else {
            if (np) valid = sbl__mand(valid, sbl__mandnot(sbl__gt(nv, zero), sbl__nonfinite(nv)));
            if (use_e) valid_e = sbl__mandnot(valid, sbl__nonfinite(ve));
            valid_t = valid;
            valid = sbl__mandnot(valid, sbl__nonfinite(v[0]));
            if (ch > 1) valid = sbl__mandnot(valid, sbl__nonfinite(v[1]));
            if (ch > 2) valid = sbl__mandnot(valid, sbl__nonfinite(v[2]));
            if (ch > 3) valid = sbl__mandnot(valid, sbl__nonfinite(v[3]));
            ok = sbl__mand(sbl__lane_ok(nv), sbl__lane_ok(v[0]));
            if (ch > 1) ok = sbl__mand(ok, sbl__lane_ok(v[1]));
            if (ch > 2) ok = sbl__mand(ok, sbl__lane_ok(v[2]));
            if (ch > 3) ok = sbl__mand(ok, sbl__lane_ok(v[3]));
            flag = sbl__mbits(sbl__mandnot(valid, ok));
        }
        sbl__store(r->x[0] + x, sbl__sel(valid, sbl__add(zero, v[0]), zero));
        if (ch > 1) sbl__store(r->x[1] + x, sbl__sel(valid, sbl__add(zero, v[1]), zero));
        if (ch > 2) sbl__store(r->x[2] + x, sbl__sel(valid, sbl__add(zero, v[2]), zero));
        if (ch > 3) sbl__store(r->x[3] + x, sbl__sel(valid, sbl__add(zero, v[3]), zero));
        sbl__store(r->n + x, sbl__sel(valid, nv, zero));
        sbl__store(r->v + x, sbl__sel(valid, one, zero));
        /* (a column the overlapping last vector writes again gets the same values and
           the same flag: sbl__ring_flag_bits counts a column once) */
        if (flag) sbl__ring_flag_bits(r, x, flag);
        bits = sbl__mbits(sbl__mandnot(keep, valid));
        for (l = 0; bits; ++l, bits >>= 1)
            if (bits & 1) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put_flag(r, x + l, sbl__temporal_rp_pixel(s, x + l, y, tmp), tmp, ch);
            }
        if (use_e) { /* the ratio (v > 0: v + 0 = v) or 1; the lanes not settled: its pixel gather */
            const sbl__m use = sbl__mandnot(sbl__mand(valid_e, sbl__gt(ve, zero)),
                                            sbl__gt(ve, sbl__set1(SBL__CAST(float, SBL__POOL_RATIO_CAP))));
            sbl__store(r->e + x, sbl__sel(use, ve, one));
            bits = sbl__mbits(sbl__mandnot(keep, valid_e));
            for (l = 0; bits; ++l, bits >>= 1)
                if (bits & 1) r->e[x + l] = sbl__evidence_pixel(r->e_rp, x + l, y);
        }
        if (use_t) { /* valid where the colour's tests pass and both values are finite;
                        then sbl__tail_pixel's test; the lanes not settled: its pixel gather */
            valid_t = sbl__mandnot(valid_t, sbl__mor(sbl__nonfinite(tr), sbl__nonfinite(tv)));
            sbl__store(r->tl[0] + x, sbl__sel(sbl__mandnot(sbl__mand(valid_t, sbl__gt(tr, zero)), sbl__gt(tr, one)),
                                              tr, zero));
            sbl__store(r->tl[1] + x, sbl__sel(sbl__mand(valid_t, sbl__gt(tv, zero)), tv, zero));
            bits = sbl__mbits(sbl__mandnot(keep, valid_t));
            for (l = 0; bits; ++l, bits >>= 1)
                if (bits & 1) sbl__tail_pixel(r, x + l, y);
        }
        if (i + SBL__VW >= n) break;
        i += SBL__VW;
    }
}

static void sbl__rest_tile(const sbl__temporal_rp *s, sbl__ring_row *r, int y, int x0, int n)
{
    switch (s->src.color.ch) {
    case 1: sbl__rest_tile_ch(s, r, y, x0, n, 1, 0); break;
    case 2: sbl__rest_tile_ch(s, r, y, x0, n, 2, 0); break;
    case 3: sbl__rest_tile_ch(s, r, y, x0, n, 3, 0); break;
    default: sbl__rest_tile_ch(s, r, y, x0, n, 4, 0); break;
    }
}

/* sbl__rest_tile with the evidence plane (r->e) */
SBL__NOINLINE void sbl__rest_tile_ev(const sbl__temporal_rp *s, sbl__ring_row *r, int y, int x0, int n)
{
    switch (s->src.color.ch) {
    case 1: sbl__rest_tile_ch(s, r, y, x0, n, 1, 1); break;
    case 2: sbl__rest_tile_ch(s, r, y, x0, n, 2, 1); break;
    case 3: sbl__rest_tile_ch(s, r, y, x0, n, 3, 1); break;
    default: sbl__rest_tile_ch(s, r, y, x0, n, 4, 1); break;
    }
}

/* sbl__rest_tile with the tail plane (r->tl), and the evidence plane where r->e is set */
SBL__NOINLINE void sbl__rest_tile_tl(const sbl__temporal_rp *s, sbl__ring_row *r, int y, int x0, int n)
{
    switch (s->src.color.ch) {
    case 1: sbl__rest_tile_ch(s, r, y, x0, n, 1, 2); break;
    case 2: sbl__rest_tile_ch(s, r, y, x0, n, 2, 2); break;
    case 3: sbl__rest_tile_ch(s, r, y, x0, n, 3, 2); break;
    default: sbl__rest_tile_ch(s, r, y, x0, n, 4, 2); break;
    }
}

/* A tile without geometry: every pixel resets. */
SBL__INLINE void sbl__void_tile(const sbl__tap_src *src, sbl__ring_row *r, int x0, int n)
{
    int c;
    memset(r->n + x0, 0, SBL__CAST(size_t, n) * sizeof(float));
    memset(r->v + x0, 0, SBL__CAST(size_t, n) * sizeof(float));
    for (c = 0; c < src->color.ch; ++c) memset(r->x[c] + x0, 0, SBL__CAST(size_t, n) * sizeof(float));
}

/* ---- camera planning in lanes ---------------------------------------------------
   The camera source's position maths in double lanes (the layer is at the top of the
   row gather). */
/* Do pixels [x0, x0 + n) of a row (n >= VW, motion packed: pixel step 2, at mp) carry
   one motion vector, the same bits in each? Two independent ORs of compares (the loop
   is the cost of a uniform block's test); the last ones overlap the ones before. */
SBL__INLINE int sbl__motion_one(const float *mp, int n)
{
    const int m = 2 * n;
    uint64_t a, b;
    int k;
    memcpy(&a, mp, sizeof a);
    memcpy(&b, mp + 2, sizeof b);
    if (a != b) return 0; /* a varying field shows it at once */
#if SBL__VW >= 8
    {   /* four pixels per compare, two compares per step (m >= 16) */
        long long a64;
        __m256i first, d0 = _mm256_setzero_si256(), d1 = d0;
        memcpy(&a64, mp, sizeof a64);
        first = _mm256_set1_epi64x(a64);
        for (k = 0; k + 16 <= m; k += 16) {
            d0 = _mm256_or_si256(d0, _mm256_xor_si256(_mm256_loadu_si256(SBL__PCAST(const __m256i *, mp + k)), first));
            d1 = _mm256_or_si256(d1, _mm256_xor_si256(_mm256_loadu_si256(SBL__PCAST(const __m256i *, mp + k + 8)), first));
        }
        if (k < m) { /* the rest: the last two (overlapping the ones before) */
            d0 = _mm256_or_si256(d0, _mm256_xor_si256(_mm256_loadu_si256(SBL__PCAST(const __m256i *, mp + m - 16)), first));
            d1 = _mm256_or_si256(d1, _mm256_xor_si256(_mm256_loadu_si256(SBL__PCAST(const __m256i *, mp + m - 8)), first));
        }
        d0 = _mm256_or_si256(d0, d1);
        return _mm256_testz_si256(d0, d0);
    }
#else
    {   /* two pixels per compare, two compares per step (m >= 8) */
        const __m128i first = _mm_unpacklo_epi64(_mm_loadl_epi64(SBL__PCAST(const __m128i *, mp)),
                                                 _mm_loadl_epi64(SBL__PCAST(const __m128i *, mp)));
        __m128i d0 = _mm_setzero_si128(), d1 = d0;
        for (k = 0; k + 8 <= m; k += 8) {
            d0 = _mm_or_si128(d0, _mm_xor_si128(_mm_loadu_si128(SBL__PCAST(const __m128i *, mp + k)), first));
            d1 = _mm_or_si128(d1, _mm_xor_si128(_mm_loadu_si128(SBL__PCAST(const __m128i *, mp + k + 4)), first));
        }
        if (k < m) {
            d0 = _mm_or_si128(d0, _mm_xor_si128(_mm_loadu_si128(SBL__PCAST(const __m128i *, mp + m - 8)), first));
            d1 = _mm_or_si128(d1, _mm_xor_si128(_mm_loadu_si128(SBL__PCAST(const __m128i *, mp + m - 4)), first));
        }
        return _mm_movemask_epi8(_mm_cmpeq_epi32(_mm_or_si128(d0, d1), _mm_setzero_si128())) == 0xffff;
    }
#endif
}

/* sbl__plan_lanes' position terms once for a block whose pixels all carry one motion
   vector m (a camera pan, a uniform drift): with m exact (sbl__motion_exact) every lane
   of every vector has the same floor and fraction, so the entries whose footprints are
   inside the image are one range, and each vector's first taps are consecutive pixels
   (uniform). Sets b->uni, that range, the fractions and the tap indices of entry 0 in
   each view (sbl__plan_index_run's; 0: plan per vector). */
SBL__NOINLINE void sbl__temporal_uniform_block(const sbl__temporal_rp *s, sbl__block *b)
{
    const sbl__tap_src *src = &s->src;
    const float *mp = SBL__AT(s->motion, b->x0, b->y);
    const sbl__v zero = sbl__set1(0.0f);
    const sbl__flat *f[5];
    float fx[SBL__VW], fy[SBL__VW], dx[SBL__VW], dy[SBL__VW];
    sbl__v mx, my, fmx, fmy;
    int cx, cy, v, o;
    b->uni = 0;
    /* the next row's motion (each block's test is the first read of its row) */
    for (o = 0; o < 2 * b->n; o += SBL__LINE_FLOATS) SBL__PREFETCH(mp, s->motion.stride + o);
    if (!sbl__motion_one(mp, b->n)) return;
    mx = sbl__set1(mp[0]);
    my = sbl__set1(mp[1]);
    if (s->motion_kx < 0.0) mx = sbl__sub(zero, mx); /* (as sbl__temporal_plan_lanes) */
    if (s->motion_ky < 0.0) my = sbl__sub(zero, my);
    if (!sbl__mbits(sbl__mand(sbl__motion_exact(mx), sbl__motion_exact(my)))) return;
    fmx = sbl__floor(mx);
    fmy = sbl__floor(my);
    sbl__store(dx, fmx);
    sbl__store(dy, fmy);
    sbl__store(fx, sbl__add(sbl__sub(mx, fmx), zero));
    sbl__store(fy, sbl__add(sbl__sub(my, fmy), zero));
    /* the entries whose four taps are inside: cx + i in [0, w - 2], cy in [0, h - 2]
       (sbl__plan_lanes' fast test, on integers: exact) */
    cx = b->x0 + SBL__CAST(int, dx[0]);
    cy = b->y + SBL__CAST(int, dy[0]);
    if (!(cy >= 0 && cy <= src->height - 2)) return;
    b->u_lo = cx >= 0 ? 0 : -cx;
    b->u_hi = src->width - 1 - cx < b->n ? src->width - 1 - cx : b->n;
    if (b->u_hi - b->u_lo < SBL__VW) return;
    f[0] = &src->color; f[1] = src->use_depth ? &src->depth : NULL;
    f[2] = src->length.p ? &src->length : NULL;
    f[3] = src->use_normal ? &src->normals : NULL; f[4] = src->use_id ? &src->ids : NULL;
    for (v = 0; v < 5; ++v)
        b->u_first[v] = f[v] ? SBL__CAST(int, SBL__CAST(ptrdiff_t, cy) * f[v]->stride +
                                                  SBL__CAST(ptrdiff_t, cx) * f[v]->step)
                             : 0;
    b->u_fx = fx[0];
    b->u_fy = fy[0];
    b->uni = 1;
}

/* The indices of a view for VW entries whose first taps are consecutive pixels from
   index first (sbl__plan_index_run's, the view's product already formed; 0: no view) */
SBL__INLINE void sbl__plan_first_run(int *out, int first, const int *lane_step, int present)
{
    int j;
    for (j = 0; j < SBL__VW; j += 4)
        _mm_storeu_si128(SBL__PCAST(__m128i *, out + j),
                         present ? _mm_add_epi32(_mm_set1_epi32(first),
                                                 _mm_loadu_si128(SBL__PCAST(const __m128i *, lane_step + j)))
                                 : _mm_setzero_si128());
}

/* sbl__temporal_plan_lanes for entries [i, i + VW) of a uniform block (b->uni): the
   target side per vector, the position terms from the block. A vector with a lane the
   target tests reject takes sbl__temporal_plan_lanes (which reads it again). */
SBL__INLINE int sbl__temporal_plan_uni(const sbl__temporal_rp *s, sbl__block *b, int i, int x,
                                       int sky)
{
    const sbl__tap_src *src = &s->src;
    sbl__tap_plan *p = &b->p;
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    sbl__v z = zero, slack = zero;
    sbl__m keep = sky ? sbl__gt(one, zero)
                      : (s->geo.depth.p ? sbl__lanes_want(&s->geo.depth, s->geo.width, x, b->y, &z, &slack)
                                        : sbl__gt(one, zero));
    if (sky) z = sbl__set1(SBL__CAST(float, HUGE_VAL));
    if (s->geo.normals.p || s->geo.ids.p) keep = sbl__lanes_want_nid(&s->geo, src, p, i, x, b->y, keep);
    if (sbl__mbits(keep) != (1 << SBL__VW) - 1) return sbl__temporal_plan_lanes(s, p, i, x, b->y, sky);
    /* every lane fast: sbl__plan_lanes' stores with fast true in every lane */
    sbl__store(p->fx + i, sbl__set1(b->u_fx));
    sbl__store(p->fy + i, sbl__set1(b->u_fy));
    sbl__store(p->depth + i, z);
    sbl__store(p->slack + i, slack);
    sbl__store(p->fast + i, one);
    memset(p->redo + i, 0, SBL__VW);
    memset(p->uniform + i, 0, SBL__VW);
    /* sbl__row_taps_ch's "full" test on the values planned (3) */
    p->uniform[i] = sbl__full_lanes(sbl__set1(src->depth_tolerance), z, slack) ? 3 : 1;
    sbl__plan_first_run(p->ci + i, b->u_first[0] + i * p->lane_step[0][1], p->lane_step[0], 1);
    sbl__plan_first_run(p->di + i, b->u_first[1] + i * p->lane_step[1][1], p->lane_step[1], src->use_depth);
    sbl__plan_first_run(p->li + i, b->u_first[2] + i * p->lane_step[2][1], p->lane_step[2], src->length.p != NULL);
    if (src->use_normal) sbl__plan_first_run(p->ni + i, b->u_first[3] + i * p->lane_step[3][1], p->lane_step[3], 1);
    if (src->use_id) sbl__plan_first_run(p->ii + i, b->u_first[4] + i * p->lane_step[4][1], p->lane_step[4], 1);
    return 0;
}

/* Can sbl__cam_plan_lanes plan row y of this call? The camera source with a moving
   camera and no listed objects (whose ids choose the map per pixel), images up to 2^15
   pixels (sbl__plan_lanes_at: the taps' corners exact in float), an interior row (the
   depth slack reads both neighbours), target depth packed, target normals and ids in
   lanes (sbl__lanes_want_nid). */
SBL__INLINE int sbl__camera_plan_lanes_ok(const sbl__temporal_rp *s, int y)
{
    return s->source == SBL_TEMPORAL_CAMERA && s->history && !s->at_rest &&
           !s->cam.object_count && s->src.width <= 32768 && s->src.height <= 32768 &&
           sbl__geo_nid_lanes_ok(&s->geo) && y >= 1 && y + 1 < s->src.height && s->geo.depth.step == 1;
}

/* sbl__cam_lanes_k's constants from the map (sbl__cam_k). */
SBL__INLINE void sbl__cam_k_init(sbl__cam_k *k, const sbl__cam_map *m)
{
    const double *rows[7];
    int a, c;
    rows[0] = m->ray[0]; rows[1] = m->ray[1];
    rows[2] = m->clip[0]; rows[3] = m->clip[1]; rows[4] = m->clip[2];
    rows[5] = m->view[0]; rows[6] = m->view[1];
    k->width = sbl__dset1(m->width);
    k->height = sbl__dset1(m->height);
    k->other_width = sbl__dset1(m->other_width);
    k->other_height = sbl__dset1(m->other_height);
    for (a = 0; a < 7; ++a)
        for (c = 0; c < 3; ++c) k->r[a][c] = sbl__dset1(rows[a][c]);
    for (a = 0; a < 3; ++a) k->w[a] = sbl__dset1(m->clip_w[a]);
    k->w[3] = sbl__dset1(m->view_w[0]);
    k->w[4] = sbl__dset1(m->view_w[1]);
}

/* The row terms of sbl__cam_k for the positions of row y (py = y + 0.5): n1 and each
   row's r[1] n1, by the operations sbl__cam_lanes_k takes for them per lane. */
SBL__INLINE void sbl__cam_k_row(sbl__cam_k *k, int y)
{
    const sbl__dv n1 = sbl__dsub(sbl__dset1(1.0), sbl__ddiv(sbl__dmul(sbl__dset1(2.0), sbl__dset1(y + 0.5)), k->height));
    int a;
    for (a = 0; a < 7; ++a) k->t[a] = sbl__dmul(k->r[a][1], n1);
}

/* Row a of the folded map at (n0, n1): r0 n0 + r1 n1 + r2, as sbl__cam_row sums it; row
   (a constant where inlined): r1 n1 is the row's term t[a]. */
SBL__INLINE sbl__dv sbl__cam_row_k(const sbl__cam_k *k, int a, sbl__dv n0, sbl__dv n1, int row)
{
    return sbl__dadd(sbl__dadd(sbl__dmul(k->r[a][0], n0), row ? k->t[a] : sbl__dmul(k->r[a][1], n1)),
                     k->r[a][2]);
}

/* sbl__cam_map_apply for VW positions (px[l], py[l]) at planar depths zf[l] (+inf: a
   direction; zf readable to VW + 4): (ox, oy, oz)[l]; bit l of the result is set where
   the map gives a position. The same operations in the same order as the reference.
   row (a constant where inlined): the positions are the pixels x .. x + VW - 1 of the
   row whose terms k holds (sbl__cam_k_row), px and py unused. sky (a constant where
   inlined): some lane is +inf, whose scale is 1 (zmul) and w 0 (wl); else every w is 1,
   and w_a 1 is w_a exactly (the reference's product, without the multiplication). */
SBL__INLINE int sbl__cam_lanes_half(const sbl__cam_k *k, int row, int sky, int x, int j, const double *px,
                                    const double *py, const float *zmul, const float *wl, double *ox,
                                    double *oy, double *oz)
{
    const sbl__dv zero = sbl__dset1(0.0), one = sbl__dset1(1.0), two = sbl__dset1(2.0),
                  half = sbl__dset1(0.5);
    /* (a row's px: (x + l) + 0.5, exact as the reference's x + l + 0.5) */
    const sbl__dv pxv = row ? sbl__dadd(sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(SBL__CAST(double, x + j))), half)
                            : sbl__dload(px + j);
    const sbl__dv n0 = sbl__dsub(sbl__ddiv(sbl__dmul(two, pxv), k->width), one);
    const sbl__dv n1 = row ? zero : sbl__dsub(one, sbl__ddiv(sbl__dmul(two, sbl__dload(py + j)), k->height));
    const sbl__dv q2 = sbl__cam_row_k(k, 0, n0, n1, row), q3 = sbl__cam_row_k(k, 1, n0, n1, row);
    const sbl__dv w = sky ? sbl__dfromf(wl + j) : one;
    const sbl__dv sc = sbl__ddiv(sbl__dfromf(zmul + j), sbl__dsub(zero, q2));
    const sbl__dv c0 = sbl__dadd(sbl__dmul(sc, sbl__cam_row_k(k, 2, n0, n1, row)), sky ? sbl__dmul(k->w[0], w) : k->w[0]);
    const sbl__dv c1 = sbl__dadd(sbl__dmul(sc, sbl__cam_row_k(k, 3, n0, n1, row)), sky ? sbl__dmul(k->w[1], w) : k->w[1]);
    const sbl__dv c3 = sbl__dadd(sbl__dmul(sc, sbl__cam_row_k(k, 4, n0, n1, row)), sky ? sbl__dmul(k->w[2], w) : k->w[2]);
    const sbl__dv v2 = sbl__dadd(sbl__dmul(sc, sbl__cam_row_k(k, 5, n0, n1, row)), sky ? sbl__dmul(k->w[3], w) : k->w[3]);
    const sbl__dv v3 = sbl__dadd(sbl__dmul(sc, sbl__cam_row_k(k, 6, n0, n1, row)), sky ? sbl__dmul(k->w[4], w) : k->w[4]);
    sbl__dstore(ox + j, sbl__dmul(sbl__dmul(sbl__dadd(sbl__ddiv(c0, c3), one), half), k->other_width));
    sbl__dstore(oy + j, sbl__dmul(sbl__dmul(sbl__dsub(one, sbl__ddiv(c1, c3)), half), k->other_height));
    sbl__dstore(oz + j, sbl__dinf_at0(sbl__dsub(zero, v2), v3)); /* -v2; a direction (v3 = 0): +inf */
    (void)wl;
    /* (q2 < 0 and q3 > 0) or (q2 > 0 and q3 < 0), and c3 > 0 */
    return sbl__dm_bits(sbl__dm_and(sbl__dm_or(sbl__dm_and(sbl__dlt_m(q2, zero), sbl__dlt_m(zero, q3)),
                                               sbl__dm_and(sbl__dlt_m(zero, q2), sbl__dlt_m(q3, zero))),
                                    sbl__dlt_m(zero, c3)));
}

/* (VW is 2 DW on every path: the two halves in straight code, the constants read where
   they are used) */
SBL__INLINE int sbl__cam_lanes_in(const sbl__cam_k *k, int row, int sky, int x, const double *px,
                                  const double *py, const float *zmul, const float *wl, double *ox,
                                  double *oy, double *oz)
{
    return sbl__cam_lanes_half(k, row, sky, x, 0, px, py, zmul, wl, ox, oy, oz) |
           sbl__cam_lanes_half(k, row, sky, x, SBL__DW, px, py, zmul, wl, ox, oy, oz) << SBL__DW;
}

SBL__INLINE int sbl__cam_lanes_k(const sbl__cam_k *k, int row, int x, const double *px, const double *py,
                                 const float *zf, double *ox, double *oy, double *oz)
{
    float zmul[SBL__VW + 4], wl[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    const sbl__v z = sbl__load(zf), onef = sbl__set1(1.0f);
    const sbl__m sky = sbl__posinf(z);
    if (!sbl__mbits(sky)) return sbl__cam_lanes_in(k, row, 0, x, px, py, zf, NULL, ox, oy, oz);
    /* a direction for sky (+inf): scale 1, w = 0 (exact in float, then in double) */
    sbl__store(zmul, sbl__sel(sky, onef, z));
    sbl__store(wl, sbl__sel(sky, sbl__set1(0.0f), onef));
    return sbl__cam_lanes_in(k, row, 1, x, px, py, zmul, wl, ox, oy, oz);
}

/* sbl__cam_lanes_k for any VW positions, the constants taken from the map (the tests:
   the lanes against the reference; zf readable to VW). */
SBL__INLINE int sbl__cam_lanes(const sbl__cam_map *m, const double *px, const double *py,
                               const float *zf, double *ox, double *oy, double *oz)
{
    sbl__cam_k k;
    float z[SBL__VW + 4]; /* (sbl__cam_lanes_k reads VW + 4) */
    int l;
    for (l = 0; l < SBL__VW + 4; ++l) z[l] = l < SBL__VW ? zf[l] : 0.0f;
    sbl__cam_k_init(&k, m);
    return sbl__cam_lanes_k(&k, 0, 0, px, py, z, ox, oy, oz);
}

/* The temporal camera source's plans for the VW pixels x .. x + VW - 1 of an interior
   row y: the target's depth, its slack, normals and ids in lanes (sbl__lanes_want,
   sbl__lanes_want_nid: valid geometry is z > 0 or +inf, as sbl__tap_want_init and
   sbl__valid_depth take it), the map in double lanes with the constants of row y (k:
   sbl__cam_k_init, sbl__cam_k_row), the plan from the positions (sbl__plan_lanes_at)
   with the mapped depth expected. (The two-camera stereo rigs: sbl__stereo_cam_plan.) */
SBL__INLINE void sbl__cam_plan_lanes(const sbl__target_geo *geo, const sbl__tap_src *src,
                                     const sbl__cam_k *k, sbl__tap_plan *p, int i, int x, int y)
{
    float zf[SBL__VW + 4], zo[SBL__VW]; /* (sbl__cam_lanes_k reads VW + 4) */
    double ox[SBL__VW], oy[SBL__VW], oz[SBL__VW];
    sbl__v z, slack;
    sbl__m want = sbl__lanes_want(&geo->depth, geo->width, x, y, &z, &slack);
    int keep, l;
    if (geo->normals.p || geo->ids.p) want = sbl__lanes_want_nid(geo, src, p, i, x, y, want);
    keep = sbl__mbits(want);
    sbl__store(zf, z);
    keep &= sbl__cam_lanes_k(k, 1, x, NULL, NULL, zf, ox, oy, oz);
    for (l = 0; l < SBL__VW; l += SBL__DW) sbl__dstoref(zo + l, sbl__dload(oz + l)); /* the expected depth */
    (void)sbl__plan_lanes_at(src, p, i, x, keep, ox, oy, sbl__load(zo), slack);
}

/* The camera's map constants for the block's row (lane mode 2; out of line: once per
   row, and the hooks inlined into the gather keep their registers). */
SBL__NOINLINE void sbl__temporal_cam_row(const sbl__temporal_rp *s, sbl__block *b)
{
    sbl__cam_k_init(&b->cam[0], &s->cam);
    sbl__cam_k_row(&b->cam[0], b->y);
}

/* The temporal row gather's hooks (sbl__row_gather_blocks). Lane modes: 1 motion
   vectors in pixels, 2 the camera, 3 motion vectors in UV / NDC units; bit 0 of the row
   state: the row's tiles may take the shortcuts. */
SBL__INLINE int sbl__temporal_block_start_in(const void *ctx, sbl__ring_row *r, sbl__block *b,
                                             int ev)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    if (b->row_state < 0) { /* once per row: the tiles allowed (bit 0), the lane mode */
        b->row_state = sbl__temporal_tiles_ok(s) |
                       (sbl__temporal_plan_lanes_ok(s, b->y)
                            ? 2
                            : (sbl__camera_plan_lanes_ok(s, b->y) ? 4 : (sbl__temporal_plan_scaled_ok(s, b->y) ? 6 : 0)));
        if ((b->row_state >> 1) == 2) sbl__temporal_cam_row(s, b);
    }
    if (b->row_state & 1) {
        int kind = sbl__temporal_tile_class(s, b->y, b->x0, b->n);
        if (kind && !(SBL_SHORTCUTS & (1 << (kind - 1)))) kind = SBL__TILE_GENERAL;
        if (kind == SBL__TILE_VOID) {
            sbl__void_tile(&s->src, r, b->x0, b->n);
            if (ev && r->e) { /* no evidence either way */
                int i;
                for (i = 0; i < b->n; ++i) r->e[b->x0 + i] = 1.0f;
            }
            if (ev && r->tl[0]) { /* nothing seen */
                memset(r->tl[0] + b->x0, 0, SBL__CAST(size_t, b->n) * sizeof(float));
                memset(r->tl[1] + b->x0, 0, SBL__CAST(size_t, b->n) * sizeof(float));
            }
            return 1;
        }
        if (kind == SBL__TILE_REST) {
            /* (ev 1: the evidence plane alone; the tail plane's instance when r->tl is set) */
            if (ev && r->tl[0]) sbl__rest_tile_tl(s, r, b->y, b->x0, b->n);
            else if (ev) sbl__rest_tile_ev(s, r, b->y, b->x0, b->n);
            else sbl__rest_tile(s, r, b->y, b->x0, b->n);
            return 1;
        }
        b->sky = kind == SBL__TILE_SKY;
    }
    b->mode = b->row_state >> 1;
    if (b->mode == 1) sbl__temporal_uniform_block(s, b);
    return 0;
}

SBL__INLINE int sbl__temporal_block_start(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    return sbl__temporal_block_start_in(ctx, r, b, 0);
}

/* with the evidence plane (r->e) */
static int sbl__temporal_block_start_ev(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    return sbl__temporal_block_start_in(ctx, r, b, 1);
}

SBL__INLINE int sbl__temporal_plan_vec(const void *ctx, sbl__block *b, int i)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    const int x = b->x0 + i;
    if (!b->mode || x < 0 || x + SBL__VW > s->src.width) return -1;
    if (b->mode == 2) {
        sbl__cam_plan_lanes(&s->geo, &s->src, &b->cam[0], &b->p, i, x, b->y);
        return 0;
    }
    if (b->mode == 3) /* (out of line: the pixel-unit plan below keeps its registers) */
        return sbl__temporal_plan_lanes_scaled(s, &b->p, i, x, b->y, b->sky);
    if (b->uni && i >= b->u_lo && i + SBL__VW <= b->u_hi)
        return b->sky ? sbl__temporal_plan_uni(s, b, i, x, 1) : sbl__temporal_plan_uni(s, b, i, x, 0);
    {
        const int bits = b->sky ? sbl__temporal_plan_lanes(s, &b->p, i, x, b->y, 1)
                                : sbl__temporal_plan_lanes(s, &b->p, i, x, b->y, 0);
        /* lanes whose motion the float plan cannot take exactly (0 < |m| < 2^-8: motion
           that is nearly 0, e.g. static geometry with a rounding residue): where two or
           more, the whole vector again with the positions in double lanes (the same
           values as the scalar plan's, and as the float plan's on its other lanes); a
           lone one (random motion) goes to the scalar plan, which costs less there */
        return (bits & (bits - 1)) ? sbl__temporal_plan_lanes_scaled(s, &b->p, i, x, b->y, b->sky) : bits;
    }
}

SBL__INLINE void sbl__temporal_plan_one(const void *ctx, sbl__block *b, int i)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    sbl__tap_want t;
    double sx, sy;
    sbl__tap_plan_reset(&b->p, i);
    if (sbl__temporal_rp_pos(s, b->x0 + i, b->y, &t, &sx, &sy))
        sbl__tap_plan_set(&s->src, &b->p, i, &t, sx, sy);
}

/* The block's entries whose taps weigh below 1e-3 (redo 2): the pixel gather's last
   step, its 3x3 fallback (sbl__fallback_lanes), at the position sbl__temporal_rp_pos
   gives (its expression, for motion vectors; the camera source leaves them to the pixel
   gather) with the planned expected depth and slack, and the planned target normal and
   id where the call tests them (sbl__tap_plan_want). */
SBL__INLINE void sbl__temporal_fallback_block_in(const void *ctx, sbl__ring_row *r, sbl__block *b,
                                                 int ev)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    double sx[SBL__BLOCK], sy[SBL__BLOCK];
    int e[SBL__BLOCK], i, n = 0;
    if (s->source != SBL_TEMPORAL_MOTION) return;
    for (i = 0; i < b->n; ++i) {
        const float *mv;
        if (i + 8 <= b->n) { /* eight entries at a time: redo is rare */
            uint64_t any;
            memcpy(&any, b->p.redo + i, 8);
            if (!any) { i += 7; continue; }
        }
        if (b->p.redo[i] != 2) continue;
        b->p.redo[i] = 0;
        mv = SBL__AT(s->motion, b->x0 + i, b->y);
        sx[n] = b->x0 + i + 0.5 + s->motion_kx * SBL__CAST(double, mv[0]);
        sy[n] = b->y + 0.5 + s->motion_ky * SBL__CAST(double, mv[1]);
        e[n++] = i;
    }
    if (!n) return;
    if (ev) sbl__fallback_lanes_ev(&s->src, r, b->x0, e, sx, sy, b->p.depth, b->p.slack, n, 1, &b->p);
    else sbl__fallback_lanes(&s->src, r, b->x0, e, sx, sy, b->p.depth, b->p.slack, n, 1, &b->p);
}

static void sbl__temporal_fallback_block(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    sbl__temporal_fallback_block_in(ctx, r, b, 0);
}

/* with the evidence plane (r->e) */
static void sbl__temporal_fallback_block_ev(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    sbl__temporal_fallback_block_in(ctx, r, b, 1);
}

/* The row gather's `run` for the temporal call: a uniform block (sbl__temporal_uniform_block)
   whose vectors, from entry 0, are each planned and tapped at once while they are what
   the plan would make its common case: every lane kept by the target tests, "full"
   (uniform 3), packed RGB with depth and N tested and no normal / id test. Each such
   vector gets only the plan entries sbl__lanes_taps reads (plan_uni's values) and the
   same sbl__lanes_taps call as sbl__row_taps_ch makes for it, so the same bits, without
   the plan's other stores and the per-vector dispatch. Stops at the first vector that is
   not so or needs a redo (the plan and the tap stage then take it, writing its columns
   again). Returns the first entry not settled (b->n: all). */
SBL__INLINE int sbl__temporal_uniform_run(const void *ctx, sbl__ring_row *r, sbl__block *b,
                                          int fallback, int ev)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    const sbl__tap_src *src0 = &s->src, *src;
    sbl__tap_plan *p = &b->p;
    const int all = (1 << SBL__VW) - 1;
    sbl__tap_src sc;
    sbl__taps_uni u;
    sbl__v tol;
    const float *zp;
    ptrdiff_t zs, first[3];
    int i = 0, x0, n, u_hi, gw, c0, d0, l0, edge;
    if (!b->uni || b->u_lo > 0 || b->sky || src0->color.ch != 3 || src0->color.step != 3 ||
        !src0->use_depth || src0->depth.step != 1 || !src0->length.p || src0->length.step != 1 ||
        src0->use_normal || src0->use_id || !s->geo.depth.p || s->geo.normals.p || s->geo.ids.p ||
        b->x0 + b->n > src0->width)
        return 0;
    /* a local copy with what was just tested as constants: the taps' tests of the
       views fold, and no store of theirs can alias its fields (not reloaded) */
    sc = *src0;
    sc.color.ch = 3;
    sc.color.step = 3;
    sc.use_depth = 1;
    sc.depth.step = 1;
    sc.length.step = 1;
    sc.use_normal = sc.use_id = 0;
    src = &sc;
    /* the weights and what follows from them, once for the block's vectors */
    sbl__taps_uni_of(&u, sbl__set1(b->u_fx), sbl__set1(b->u_fy));
    tol = sbl__set1(src->depth_tolerance);
    /* the loop's invariants in locals: the plan's and the ring's stores (bytes may alias
       anything) would have the block's and the target's fields loaded again per vector */
    x0 = b->x0;
    n = b->n;
    u_hi = b->u_hi;
    gw = s->geo.width;
    zs = s->geo.depth.stride;
    zp = SBL__AT(s->geo.depth, x0, b->y); /* (depth step 1: sbl__temporal_plan_lanes_ok) */
    c0 = b->u_first[0];
    d0 = b->u_first[1];
    l0 = b->u_first[2];
    edge = x0 == 0 || x0 + n >= gw; /* (else no vector's x is 0 or w - VW) */
    /* the redo bytes of every entry the loop may settle, at once (the block's redo pass
       reads settled entries; the plan rewrites those of a vector handed back) */
    memset(p->redo, 0, SBL__BLOCK);
    for (;;) {
        sbl__v z, slack, lim;
        int any;
        if (i + SBL__VW > n) i = n - SBL__VW;
        if (i + SBL__VW > u_hi) return i;
        if (sbl__mbits(sbl__lanes_want_in(zp + i, zs, gw, x0 + i, &z, &slack, edge)) != all) return i;
        lim = sbl__depth_lim(tol, z, slack);
        if (!sbl__full_lim(z, lim)) return i;
        /* the fractions, fast lanes (all), depth and limit in registers: a settled
           entry's are read by its taps only (the plan writes a vector it hands back
           again, and the block's redo pass reads no settled entry's but redo) */
        /* (contiguous: sbl__lanes_taps reads entry i's first tap indices only, given
           in registers; the evidence plane's taps read N's from the plan) */
        first[0] = c0 + 3 * SBL__CAST(ptrdiff_t, i);
        first[1] = d0 + SBL__CAST(ptrdiff_t, i);
        first[2] = l0 + SBL__CAST(ptrdiff_t, i);
        if (ev) p->li[i] = l0 + i;
        sbl__taps_prefetch_at(src, first[0], first[1], first[2], 3);
        if (ev) any = sbl__lanes_taps_in(src, p, i, fallback, r, x0 + i, p->lane_step[0], 3, 1, 0, 1, 1, 1,
                                         0, 0, 0, sbl__set1(0.0f), sbl__set1(0.0f), sbl__true, z, lim, &u, first);
        else any = sbl__lanes_taps_in(src, p, i, fallback, r, x0 + i, p->lane_step[0], 3, 1, 0, 1, 1, 0,
                                      0, 0, 0, sbl__set1(0.0f), sbl__set1(0.0f), sbl__true, z, lim, &u, first);
        if (any) return i;
        if (i + SBL__VW >= n) return n;
        i += SBL__VW;
    }
}

/* Can the temporal row gather take the tail plane (source t: the colour's whose colour is
   the plane) in the colour's plan (source s)? It reads the plane with N's tap indices
   doubled: N present, the plane's 2 channels laid out as N's pixels with every offset
   doubled (packed N, packed plane: the common case). */
static int sbl__tail_fused_ok(const sbl__tap_src *s, const sbl__tap_src *t)
{
    return s->length.p && t->color.ch == 2 && t->color.stride == 2 * s->length.stride &&
           t->color.step == 2 * s->length.step;
}

/* Can the temporal row gather take the evidence plane (source e: the colour's whose
   colour is the plane) in the colour's plan (source s)? It reads the plane with N's tap
   indices: N present, the plane laid out as N. */
static int sbl__evidence_fused_ok(const sbl__tap_src *s, const sbl__tap_src *e)
{
    return s->length.p && e->color.ch == 1 && e->color.stride == s->length.stride &&
           e->color.step == s->length.step;
}

/* The temporal reprojection of columns [xa, xb) of row y (sbl__row_gather_fn). */
static void sbl__temporal_rp_row(const void *ctx, struct sbl__ring_row *r, int y, int xa,
                                 int xb)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    /* flags its unsafe values as it writes them (no `after` step overwrites a lane) */
    r->gather_flags = 1;
    r->gather_unsafe = 0;
    sbl__row_gather_blocks(ctx, r, y, xa, xb, &s->src, !s->rp.no_fallback, sbl__temporal_rp_pixel,
                           sbl__temporal_block_start, sbl__temporal_plan_vec,
                           sbl__temporal_plan_one, NULL, sbl__temporal_fallback_block,
                           sbl__temporal_uniform_run, 1, 0);
}

/* The same with the evidence plane into r->e (NULL: as sbl__temporal_rp_row) in the
   colour's plan: the row gather of a call that carries the plane (its own instance, so
   the common one stays as it is). */
static void sbl__temporal_rp_row_ev(const void *ctx, struct sbl__ring_row *r, int y, int xa,
                                    int xb)
{
    const sbl__temporal_rp *s = SBL__PCAST(const sbl__temporal_rp *, ctx);
    if (!r->e && !r->tl[0]) {
        sbl__temporal_rp_row(ctx, r, y, xa, xb);
        return;
    }
    r->gather_flags = 1;
    r->gather_unsafe = 0;
    sbl__row_gather_blocks(ctx, r, y, xa, xb, &s->src, !s->rp.no_fallback, sbl__temporal_rp_pixel,
                           sbl__temporal_block_start_ev, sbl__temporal_plan_vec,
                           sbl__temporal_plan_one, NULL, sbl__temporal_fallback_block_ev,
                           sbl__temporal_uniform_run, 1, 1);
}
#endif

#ifdef SBL__SHUFFLE4
SBL__INLINE void sbl__transpose4(__m128 *a, __m128 *b, __m128 *c, __m128 *d)
{
    const __m128 t0 = _mm_unpacklo_ps(*a, *b), t1 = _mm_unpacklo_ps(*c, *d);
    const __m128 t2 = _mm_unpackhi_ps(*a, *b), t3 = _mm_unpackhi_ps(*c, *d);
    *a = _mm_movelh_ps(t0, t1);
    *b = _mm_movehl_ps(t1, t0);
    *c = _mm_movelh_ps(t2, t3);
    *d = _mm_movehl_ps(t3, t2);
}
#endif

/* Pixels [xa, xb) of an interleaved row (pixel step `step` floats, `ch` channels used)
   to one plane per channel, and back. Pure data movement: every build gives the same
   planes; packed rows (step == ch) move four pixels per 128-bit shuffle group. */
static void sbl__deinterleave(const float *src, ptrdiff_t step, int ch, float *const *planes,
                              int xa, int xb)
{
    int x = xa, c;
#ifdef SBL__SHUFFLE4
    if (step == ch && ch >= 2) {
        float *p0 = planes[0], *p1 = planes[1];
        const float *s = src + SBL__CAST(ptrdiff_t, xa) * step;
        if (ch == 2) {
            for (; x + 4 <= xb; x += 4, s += 8) {
                const __m128 a = _mm_loadu_ps(s), b = _mm_loadu_ps(s + 4);
                _mm_storeu_ps(p0 + x, _mm_shuffle_ps(a, b, _MM_SHUFFLE(2, 0, 2, 0)));
                _mm_storeu_ps(p1 + x, _mm_shuffle_ps(a, b, _MM_SHUFFLE(3, 1, 3, 1)));
            }
        } else if (ch == 3) {
            float *p2 = planes[2];
#if SBL__VW >= 8
            /* eight pixels per step: each 128-bit half does the four-pixel shuffles below
               on its own pixels (0-3 low, 4-7 high) */
            for (; x + 8 <= xb; x += 8, s += 24) {
                const __m256 a = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(s)), _mm_loadu_ps(s + 12), 1);
                const __m256 b = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(s + 4)), _mm_loadu_ps(s + 16), 1);
                const __m256 d = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(s + 8)), _mm_loadu_ps(s + 20), 1);
                _mm256_storeu_ps(p0 + x, _mm256_shuffle_ps(a, _mm256_shuffle_ps(b, d, _MM_SHUFFLE(1, 1, 2, 2)),
                                                           _MM_SHUFFLE(2, 0, 3, 0)));
                _mm256_storeu_ps(p1 + x, _mm256_shuffle_ps(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 1, 1)),
                                                           _mm256_shuffle_ps(b, d, _MM_SHUFFLE(2, 2, 3, 3)),
                                                           _MM_SHUFFLE(2, 0, 2, 0)));
                _mm256_storeu_ps(p2 + x, _mm256_shuffle_ps(_mm256_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2)),
                                                           _mm256_shuffle_ps(d, d, _MM_SHUFFLE(3, 3, 0, 0)),
                                                           _MM_SHUFFLE(2, 0, 2, 0)));
            }
#endif
            for (; x + 4 <= xb; x += 4, s += 12) {
                /* a = r0 g0 b0 r1, b = g1 b1 r2 g2, c = b2 r3 g3 b3 */
                const __m128 a = _mm_loadu_ps(s), b = _mm_loadu_ps(s + 4), d = _mm_loadu_ps(s + 8);
                const __m128 r = _mm_shuffle_ps(a, _mm_shuffle_ps(b, d, _MM_SHUFFLE(1, 1, 2, 2)),
                                                _MM_SHUFFLE(2, 0, 3, 0));
                const __m128 g = _mm_shuffle_ps(_mm_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 1, 1)),
                                                _mm_shuffle_ps(b, d, _MM_SHUFFLE(2, 2, 3, 3)),
                                                _MM_SHUFFLE(2, 0, 2, 0));
                const __m128 bl = _mm_shuffle_ps(_mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2)),
                                                 _mm_shuffle_ps(d, d, _MM_SHUFFLE(3, 3, 0, 0)),
                                                 _MM_SHUFFLE(2, 0, 2, 0));
                _mm_storeu_ps(p0 + x, r);
                _mm_storeu_ps(p1 + x, g);
                _mm_storeu_ps(p2 + x, bl);
            }
        } else {
            float *p2 = planes[2], *p3 = planes[3];
            for (; x + 4 <= xb; x += 4, s += 16) {
                __m128 a = _mm_loadu_ps(s), b = _mm_loadu_ps(s + 4), d = _mm_loadu_ps(s + 8),
                       e = _mm_loadu_ps(s + 12);
                sbl__transpose4(&a, &b, &d, &e);
                _mm_storeu_ps(p0 + x, a);
                _mm_storeu_ps(p1 + x, b);
                _mm_storeu_ps(p2 + x, d);
                _mm_storeu_ps(p3 + x, e);
            }
        }
    }
#endif
    if (step == 1 && ch == 1 && x < xb) {
        memcpy(planes[0] + x, src + x, SBL__CAST(size_t, xb - x) * sizeof(float));
        return;
    }
    for (; x < xb; ++x)
        for (c = 0; c < ch; ++c) planes[c][x] = src[SBL__CAST(ptrdiff_t, x) * step + c];
}

static void sbl__interleave(float *dst, ptrdiff_t step, int ch, const float *const *planes,
                            int xa, int xb)
{
    int x = xa, c;
#ifdef SBL__SHUFFLE4
    if (step == ch && ch >= 2) {
        const float *p0 = planes[0], *p1 = planes[1];
        float *d = dst + SBL__CAST(ptrdiff_t, xa) * step;
        if (ch == 2) {
            for (; x + 4 <= xb; x += 4, d += 8) {
                const __m128 r = _mm_loadu_ps(p0 + x), g = _mm_loadu_ps(p1 + x);
                _mm_storeu_ps(d, _mm_unpacklo_ps(r, g));
                _mm_storeu_ps(d + 4, _mm_unpackhi_ps(r, g));
            }
        } else if (ch == 3) {
            const float *p2 = planes[2];
#if SBL__VW >= 8
            /* eight pixels per step: the four-pixel shuffles below in each 128-bit half */
            for (; x + 8 <= xb; x += 8, d += 24) {
                const __m256 r = _mm256_loadu_ps(p0 + x), g = _mm256_loadu_ps(p1 + x),
                             b = _mm256_loadu_ps(p2 + x);
                const __m256 rg_lo = _mm256_unpacklo_ps(r, g), rg_hi = _mm256_unpackhi_ps(r, g);
                const __m256 o0 = _mm256_shuffle_ps(rg_lo, _mm256_shuffle_ps(b, rg_lo, _MM_SHUFFLE(2, 2, 0, 0)),
                                                    _MM_SHUFFLE(2, 0, 1, 0));
                const __m256 o1 = _mm256_shuffle_ps(_mm256_shuffle_ps(rg_lo, b, _MM_SHUFFLE(1, 1, 3, 3)), rg_hi,
                                                    _MM_SHUFFLE(1, 0, 2, 0));
                const __m256 s2 = _mm256_shuffle_ps(rg_hi, b, _MM_SHUFFLE(3, 2, 3, 2));
                const __m256 o2 = _mm256_shuffle_ps(s2, s2, _MM_SHUFFLE(3, 1, 0, 2));
                _mm_storeu_ps(d, _mm256_castps256_ps128(o0));
                _mm_storeu_ps(d + 4, _mm256_castps256_ps128(o1));
                _mm_storeu_ps(d + 8, _mm256_castps256_ps128(o2));
                _mm_storeu_ps(d + 12, _mm256_extractf128_ps(o0, 1));
                _mm_storeu_ps(d + 16, _mm256_extractf128_ps(o1, 1));
                _mm_storeu_ps(d + 20, _mm256_extractf128_ps(o2, 1));
            }
#endif
            for (; x + 4 <= xb; x += 4, d += 12) {
                /* rg_lo = r0 g0 r1 g1, rg_hi = r2 g2 r3 g3; out r0 g0 b0 r1 | g1 b1 r2 g2 |
                   b2 r3 g3 b3 in eight shuffles */
                const __m128 r = _mm_loadu_ps(p0 + x), g = _mm_loadu_ps(p1 + x),
                             b = _mm_loadu_ps(p2 + x);
                const __m128 rg_lo = _mm_unpacklo_ps(r, g), rg_hi = _mm_unpackhi_ps(r, g);
                const __m128 b0r1 = _mm_shuffle_ps(b, rg_lo, _MM_SHUFFLE(2, 2, 0, 0)); /* b0 b0 r1 r1 */
                const __m128 g1b1 = _mm_shuffle_ps(rg_lo, b, _MM_SHUFFLE(1, 1, 3, 3)); /* g1 g1 b1 b1 */
                const __m128 s2 = _mm_shuffle_ps(rg_hi, b, _MM_SHUFFLE(3, 2, 3, 2));   /* r3 g3 b2 b3 */
                _mm_storeu_ps(d, _mm_shuffle_ps(rg_lo, b0r1, _MM_SHUFFLE(2, 0, 1, 0)));
                _mm_storeu_ps(d + 4, _mm_shuffle_ps(g1b1, rg_hi, _MM_SHUFFLE(1, 0, 2, 0)));
                _mm_storeu_ps(d + 8, _mm_shuffle_ps(s2, s2, _MM_SHUFFLE(3, 1, 0, 2)));
            }
        } else {
            const float *p2 = planes[2], *p3 = planes[3];
            for (; x + 4 <= xb; x += 4, d += 16) {
                __m128 a = _mm_loadu_ps(p0 + x), b = _mm_loadu_ps(p1 + x), e = _mm_loadu_ps(p2 + x),
                       f = _mm_loadu_ps(p3 + x);
                sbl__transpose4(&a, &b, &e, &f);
                _mm_storeu_ps(d, a);
                _mm_storeu_ps(d + 4, b);
                _mm_storeu_ps(d + 8, e);
                _mm_storeu_ps(d + 12, f);
            }
        }
    }
#endif
    if (step == 1 && ch == 1 && x < xb) {
        memcpy(dst + x, planes[0] + x, SBL__CAST(size_t, xb - x) * sizeof(float));
        return;
    }
    for (; x < xb; ++x)
        for (c = 0; c < ch; ++c) dst[SBL__CAST(ptrdiff_t, x) * step + c] = planes[c][x];
}

#ifdef SBL__ROW_GATHER
/* The flags of own pixels [x, x + VW) from their values v[0 .. cnt) (the channels, then
   N_Y if ny): bytes one by one only where a lane is unsafe. */
SBL__INLINE void sbl__ring_flag_vec(unsigned char *unsafe, const sbl__v *v, int cnt, int ny, int x,
                                    int *count)
{
    static const unsigned char safe_bytes[16] = {0};
    const int all = (1 << SBL__VW) - 1;
    sbl__m ok;
    int bits, l, c;
#if SBL__VW == 4
    /* SSE2: every value safe in one test of the vectors first (an own N also at most
       2^20; see sbl__lanes_taps). (AVX2: the lane tests alone cost fewer instructions,
       callgrind) */
    if (sbl__all_safe(v, cnt) &&
        (!ny || sbl__mbits(sbl__le(v[cnt - 1], sbl__set1(1048576.0f))) == all)) {
        memcpy(unsafe + x, safe_bytes, SBL__VW);
        return;
    }
#endif
    ok = sbl__lane_ok(v[0]);
    for (c = 1; c < cnt; ++c) ok = sbl__mand(ok, sbl__lane_ok(v[c]));
    if (ny) ok = sbl__mand(ok, sbl__le(v[cnt - 1], sbl__set1(1048576.0f)));
    bits = sbl__mbits(ok);
    if (bits == all) {
        memcpy(unsafe + x, safe_bytes, SBL__VW);
        return;
    }
    for (l = 0; l < SBL__VW; ++l) {
        const int bad = !((bits >> l) & 1);
        unsafe[x + l] = SBL__CAST(unsigned char, bad);
        *count += bad;
    }
}

/* Flags of own pixels [x, xb) a vector at a time, for sbl__ring_load_own (the planes in
   locals: a byte store may alias anything, and would reload them). Returns the first
   pixel not flagged. */
SBL__INLINE int sbl__ring_flag_lanes(sbl__ring_row *r, const float *ny, int x, int xb, int ch,
                                     int *count)
{
    const float *y0 = r->y[0], *y1 = ch > 1 ? r->y[1] : y0, *y2 = ch > 2 ? r->y[2] : y0,
                *y3 = ch > 3 ? r->y[3] : y0;
    unsigned char *unsafe = r->unsafe;
    for (; x + SBL__VW <= xb; x += SBL__VW) {
        sbl__v v[5];
        int cnt = 1;
        v[0] = sbl__load(y0 + x);
        if (ch > 1) v[cnt++] = sbl__load(y1 + x);
        if (ch > 2) v[cnt++] = sbl__load(y2 + x);
        if (ch > 3) v[cnt++] = sbl__load(y3 + x);
        if (ny) v[cnt++] = sbl__load(ny + x);
        sbl__ring_flag_vec(unsafe, v, cnt, ny != NULL, x, count);
    }
    return x;
}

/* Packed RGB (pixel step 3) own pixels [x, xb): deinterleaved into the planes and
   flagged in one pass (the values tested in registers, not loaded again). Returns the
   first pixel not done. */
#if SBL__VW == 4
/* sbl__ring_own_rgb two vectors at a time, with one safety test for both (sbl__ring_flag_vec's
   first test; where it fails, each vector's own tests); has_ny (a constant per instance:
   the vectors' slots fixed, in registers) whether ny is given. Returns the first column
   not done. */
SBL__INLINE int sbl__ring_own_rgb2(sbl__ring_row *r, const float *src, const float *ny, int x,
                                   int xb, ptrdiff_t ahead, ptrdiff_t ahead_n, int *count,
                                   const int has_ny)
{
    static const unsigned char safe_bytes[2 * SBL__VW] = {0};
    const int cnt = has_ny ? 4 : 3;
    float *y0 = r->y[0], *y1 = r->y[1], *y2 = r->y[2];
    unsigned char *unsafe = r->unsafe;
    for (; x + 2 * SBL__VW <= xb; x += 2 * SBL__VW) {
        const float *p = src + SBL__CAST(ptrdiff_t, x) * 3;
        sbl__v v[8];
        int o;
        for (o = 0; o < 6 * SBL__VW; o += SBL__LINE_FLOATS) SBL__PREFETCH(p, ahead + o);
        if (has_ny) SBL__PREFETCH(ny + x, ahead_n);
        sbl__rgb_lanes(p, &v[0], &v[1], &v[2]);
        sbl__rgb_lanes(p + 3 * SBL__VW, &v[cnt], &v[cnt + 1], &v[cnt + 2]);
        sbl__store(y0 + x, v[0]);
        sbl__store(y1 + x, v[1]);
        sbl__store(y2 + x, v[2]);
        sbl__store(y0 + x + SBL__VW, v[cnt]);
        sbl__store(y1 + x + SBL__VW, v[cnt + 1]);
        sbl__store(y2 + x + SBL__VW, v[cnt + 2]);
        if (has_ny) {
            v[3] = sbl__load(ny + x);
            v[7] = sbl__load(ny + x + SBL__VW);
        }
        if (sbl__all_safe(v, 2 * cnt) &&
            (!has_ny || sbl__mbits(sbl__mand(sbl__le(v[3], sbl__set1(1048576.0f)),
                                             sbl__le(v[7], sbl__set1(1048576.0f)))) == 15)) {
            memcpy(unsafe + x, safe_bytes, 2 * SBL__VW);
        } else {
            sbl__ring_flag_vec(unsafe, v, cnt, has_ny, x, count);
            sbl__ring_flag_vec(unsafe, v + cnt, cnt, has_ny, x + SBL__VW, count);
        }
    }
    return x;
}
#endif

SBL__INLINE int sbl__ring_own_rgb(sbl__ring_row *r, const float *src, const float *ny, int x,
                                  int xb, ptrdiff_t ahead, ptrdiff_t ahead_n, int *count)
{
    float *y0 = r->y[0], *y1 = r->y[1], *y2 = r->y[2];
    unsigned char *unsafe = r->unsafe;
#if SBL__VW == 4
    /* SSE2: two vectors per safety test (sbl__ring_own_rgb2); with N_Y (eight vectors)
       it cost more than it saved (stereo normals-ev +0.5 instructions per pixel) */
    if (!ny) x = sbl__ring_own_rgb2(r, src, ny, x, xb, ahead, ahead_n, count, 0);
#endif
    for (; x + SBL__VW <= xb; x += SBL__VW) {
        sbl__v v[4];
        int o;
        /* the next row's colour and N (ahead, ahead_n: their row strides in floats) */
        for (o = 0; o < 3 * SBL__VW; o += SBL__LINE_FLOATS) SBL__PREFETCH(src + SBL__CAST(ptrdiff_t, x) * 3, ahead + o);
        if (ny) SBL__PREFETCH(ny + x, ahead_n);
        sbl__rgb_lanes(src + SBL__CAST(ptrdiff_t, x) * 3, &v[0], &v[1], &v[2]);
        sbl__store(y0 + x, v[0]);
        sbl__store(y1 + x, v[1]);
        sbl__store(y2 + x, v[2]);
        if (ny) v[3] = sbl__load(ny + x);
        sbl__ring_flag_vec(unsafe, v, ny ? 4 : 3, ny != NULL, x, count);
    }
    return x;
}
#endif

/* Own colour Y of columns [xa, xb) of one row, deinterleaved into planes; flags the
   pixels holding a value outside the lane range. Returns the number flagged. */
static int sbl__ring_load_own(const sbl__kernel *k, sbl__ring_row *r, int row, int xa, int xb)
{
    const float *ny = (k->own_n && k->own_n->data) ? sbl__px(k->own_n, 0, row) : NULL;
    const ptrdiff_t ny_step = ny ? SBL__CAST(ptrdiff_t, sbl__step_of(k->own_n)) : 0;
    /* the lanes load N_Y contiguously: another pixel step takes the reference path */
    const int ny_lanes = !ny || ny_step == 1;
    const float *src = sbl__px(k->own, 0, row);
    const ptrdiff_t step = sbl__step_of(k->own);
    int x, c, ch = k->ch, count = 0;
    x = xa;
#ifdef SBL__ROW_GATHER
    if (ny_lanes && ch == 3 && step == 3) {
        /* the usual layout: one pass */
        x = sbl__ring_own_rgb(r, src, ny, x, xb, sbl__stride(k->own), ny ? sbl__stride(k->own_n) : 0, &count);
        if (x < xb) sbl__deinterleave(src, step, ch, r->y, x, xb);
    } else if (ny_lanes) {
        sbl__deinterleave(src, step, ch, r->y, xa, xb);
        /* a vector at a time (the channel count a constant in each call) */
        if (ch == 3) x = sbl__ring_flag_lanes(r, ny, x, xb, 3, &count);
        else if (ch == 1) x = sbl__ring_flag_lanes(r, ny, x, xb, 1, &count);
        else x = sbl__ring_flag_lanes(r, ny, x, xb, ch, &count);
    } else {
        sbl__deinterleave(src, step, ch, r->y, xa, xb);
    }
#else
    sbl__deinterleave(src, step, ch, r->y, xa, xb);
#endif
    for (; x < xb; ++x) {
        int safe = ny_lanes;
        for (c = 0; c < ch; ++c) safe &= sbl__lane_value_ok(r->y[c][x]);
        /* N_Y: the reference path sanitises it */
        if (ny) {
            float n = ny[SBL__CAST(ptrdiff_t, x) * ny_step];
            safe &= sbl__lane_value_ok(n) && n <= 1048576.0f;
        }
        r->unsafe[x] = SBL__CAST(unsigned char, !safe);
        count += !safe;
    }
    return count;
}

/* The check of the x* written to ring columns [xa, xb): flags the valid ones holding an
   unsafe value that the own colour did not. Returns the number newly flagged. */
static int sbl__ring_flag_range(sbl__ring_row *r, int xa, int xb, int ch)
{
    int x = xa, c, count = 0;
#ifdef SBL__ROW_GATHER
    for (; x + SBL__VW <= xb; x += SBL__VW) {
        sbl__m ok;
        int bits, l;
        ok = sbl__lane_ok(sbl__load(r->n + x));
        for (c = 0; c < ch; ++c) ok = sbl__mand(ok, sbl__lane_ok(sbl__load(r->x[c] + x)));
        bits = sbl__mbits(sbl__mandnot(sbl__gt(sbl__load(r->v + x), sbl__set1(0.0f)), ok));
        for (l = 0; bits; ++l, bits >>= 1)
            if ((bits & 1) && !r->unsafe[x + l]) { r->unsafe[x + l] = 1; ++count; }
    }
#endif
    for (; x < xb; ++x) {
        int safe = 1;
        if (!(r->v[x] > 0.0f)) continue;
        for (c = 0; c < ch; ++c) safe &= sbl__lane_value_ok(r->x[c][x]);
        safe &= sbl__lane_value_ok(r->n[x]);
        if (!safe && !r->unsafe[x]) { r->unsafe[x] = 1; ++count; }
    }
    return count;
}

/* The other estimate x* of columns [xa, xb) of one row (reprojected history or other
   eye), its N and validity, into planes; adds its own unsafe values to the flags (the
   own colour is loaded first). Returns the number of pixels newly flagged. */
static int sbl__ring_gather(const sbl__kernel *k, sbl__ring_row *r, int row, int xa, int xb)
{
    int x, ch = k->ch;
    r->gather_flags = 0;
    /* the evidence plane in the colour's plan (on halo rows too: see evid_y0) */
    r->e = k->evid_fused && row >= k->evid_y0 && row < k->evid_y1 ? r->e_plane : NULL;
    r->tl[0] = k->tail_fused ? r->tl_plane[0] : NULL; /* (every row: as evid_y0 says) */
    r->tl[1] = k->tail_fused ? r->tl_plane[1] : NULL;
    if (k->gather_row) {
        k->gather_row(k->gather_ctx, r, row, xa, xb);
        if (r->gather_flags) return r->gather_unsafe;
    } else {
        for (x = xa; x < xb; ++x) {
            float tmp[4] = {0, 0, 0, 0};
            sbl__ring_put(r, x, k->gather(k->gather_ctx, x, row, tmp), tmp, ch);
        }
    }
    return sbl__ring_flag_range(r, xa, xb, ch);
}

static void sbl__ring_load(const sbl__kernel *k, sbl__ring_row *r, int row, int xa, int xb)
{
    int count = sbl__ring_load_own(k, r, row, xa, xb);
    count += sbl__ring_gather(k, r, row, xa, xb);
    r->row = row;
    r->unsafe_count = count;
}

static float sbl__own_n(const sbl__kernel *k, int x, int y)
{
    float n;
    if (!k->own_n || !k->own_n->data) return 1.0f;
    n = *sbl__px(k->own_n, x, y);
    return (sbl__finite(n) && n > 0.0f) ? n : 1.0f;
}

/* One column of the blocks: over rows R[0..2] at column x, the count of pairs (valid
   x*, finite values) and per channel the sums of d = x* - y and of d^2: out[0],
   out[1 + c], out[5 + c]. Zero outside the image. */
SBL__INLINE void sbl__pool_column(const sbl__kernel *k, const sbl__ring_row *const *R, int x,
                                  double *out, const int ch)
{
    /* the channels written out into locals (registers; stores to out could alias the
       ring's floats), each sum in the order of the rows; ch a constant of the caller */
    double n = 0.0, s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, q0 = 0.0, q1 = 0.0, q2 = 0.0, q3 = 0.0;
    int j;
    if (x >= 0 && x < k->w)
        for (j = 0; j < 3; ++j) {
            const sbl__ring_row *r = R[j];
            double d0, d1 = 0.0, d2 = 0.0, d3 = 0.0;
            uint64_t nonfinite;
            if (!r || !(r->v[x] > 0.0f)) continue;
/* both values finite iff d is: the difference in double of two finite floats is finite
   (|d| <= 2 FLT_MAX), of an infinite or NaN one infinite or NaN; one test of the bits
   per channel (exponent all ones: adding its lowest bit carries into the sign bit) */
#define SBL__POOL_D(c, d) \
            do { \
                uint64_t u_; \
                d = SBL__CAST(double, r->x[c][x]) - SBL__CAST(double, r->y[c][x]); \
                memcpy(&u_, &d, sizeof u_); \
                nonfinite |= (u_ & 0x7ff0000000000000u) + 0x0010000000000000u; \
            } while (0)
            nonfinite = 0;
            SBL__POOL_D(0, d0);
            if (ch > 1) SBL__POOL_D(1, d1);
            if (ch > 2) SBL__POOL_D(2, d2);
            if (ch > 3) SBL__POOL_D(3, d3);
#undef SBL__POOL_D
            if (nonfinite >> 63) continue;
            n += 1.0;
            s0 += d0; q0 += d0 * d0;
            if (ch > 1) { s1 += d1; q1 += d1 * d1; }
            if (ch > 2) { s2 += d2; q2 += d2 * d2; }
            if (ch > 3) { s3 += d3; q3 += d3 * d3; }
        }
    out[0] = n;
    out[1] = s0; out[2] = s1; out[3] = s2; out[4] = s3;
    out[5] = q0; out[6] = q1; out[7] = q2; out[8] = q3;
}

/* Evidence carried over frames (docs/ESTIMATORS.md 3.7). The blocks' ratio
   q = sum m2 / sum se2 estimates 1 + tau^2 / se^2 (1 where nothing changes); carried with
   the history as R = (1 - lambda) R* + lambda q (R* the last frame's, reprojected with
   the colour's taps; 1 where there is none), its spread where nothing changes is
   sqrt(lambda / (2 - lambda)) of one frame's. The threshold asks R for the same
   significance as the one-frame test asks q (SBL_POOLED_BLOCK_SE2, 2.5 of a frame's
   spread above the mean 1) in units of R's spread: c_R = 1 + 2.5 sqrt(1/5) = 2.118 at
   lambda = 1/3. Beyond c_R, r is at least the non-negative garrote of R - 1,
   (R - 1) - (c_R - 1)^2 / (R - 1) (docs/ESTIMATORS.md 3.8): 0 at c_R, continuous, and
   tending to the unbiased R - 1 where R - c_R would stay c_R - 1 short of it. lambda = 1/3:
   a shadow edge moving a pixel per frame crosses a 3x3 block in three frames, and older
   evidence is about other pixels. c_R keeps the 3.5 of SBL_POOLED_BLOCK_SE2 where the
   blocks now ask 2.5 (SBL_POOLED_BLOCK_SE2_REGION): beyond c_R the paper's weight comes in
   (the mix, 3.11), a larger step than the blocks' shrink, and c_R from 2.5 cost static
   and pan 3-4 % (docs/ESTIMATORS.md 6.2). */
#ifndef SBL_EVIDENCE_LAMBDA
#define SBL_EVIDENCE_LAMBDA (1.0 / 3.0)
#endif
#ifndef SBL_EVIDENCE_GATE
#define SBL_EVIDENCE_GATE 2 /* 2: the garrote above (default); 0: r >= R - c_R, shrunk by
                               the threshold as the one-frame r = q - SBL_POOLED_BLOCK_SE2
                               is (session 8); 1: beyond c_R, r >= R - 1, a jump at c_R
                               (measured: more under moving lights, a loss on static
                               content and gallery; docs/ESTIMATORS.md 3.7, 3.8) */
#endif
#define SBL__EVIDENCE_THR \
    (1.0 + (SBL_POOLED_BLOCK_SE2 - 1.0) * sqrt(SBL_EVIDENCE_LAMBDA / (2.0 - SBL_EVIDENCE_LAMBDA)))
#define SBL__EVIDENCE_GARROTE ((SBL__EVIDENCE_THR - 1.0) * (SBL__EVIDENCE_THR - 1.0))
/* The most one frame may raise the carried R by: c - 1, the one-frame threshold's distance
   from the no-change mean (q's innovation clipped at (c - 1) / lambda, a Huber step), c
   the blocks' threshold where the plane is (SBL_POOLED_BLOCK_SE2_REGION). A change the
   one-frame test sees (q >= c) is handled in that frame by r = q - c; R is for evidence
   that one frame cannot give. Unclipped, one noise-free jump (q at the cap, 1e6) held R
   near 3e5, and a large q on low-noise content held it for tens of frames (found in
   review, session 8); clipped, a single strong frame leaves R at most c = 2.5 (beyond
   the unraised c_R = 2.118 for a frame or two; in a quiet region, M > 5.6, c_R(M) is
   above 2.5 and one frame cannot pass it), and R still grows under a lasting change. The
   step stays 1.5 in builds whose region prior leaves the blocks out (SBL_EVIDENCE_REGION
   without 2), where the blocks keep 3.5; SBL__EVIDENCE_FALSE_ALARM assumes 1.5. */
#define SBL__EVIDENCE_STEP (SBL_POOLED_BLOCK_SE2_REGION - 1.0)
/* The blocks' one-frame threshold c of kernel k: lower where the region's prior adds
   ln M to it (SBL_POOLED_BLOCK_SE2_REGION). */
#define SBL__POOL_THR(k) \
    ((k)->evid_use && (SBL_EVIDENCE_REGION & 2) ? SBL_POOLED_BLOCK_SE2_REGION : SBL_POOLED_BLOCK_SE2)

/* The history's evidence plane at pixels [xa, xb) of row y into evid_in, gathered with
   the taps, weights, tests and fallback of the colour, bilinear: 1 where no tap is valid
   (a reset: no evidence either way), where the history has no plane, or where the value
   is not a ratio (sbl__evidence_pixel). Where the row gather takes the colour and the
   plane is laid out as N, the ring row already holds it, gathered in the colour's plan
   (sbl__temporal_rp_row_ev): evid_in points there. Else a row gather of its own on the
   plane (laid out otherwise), or the pixel gather: the same bits. */
static void sbl__evidence_gather(sbl__kernel *k, int y, int xa, int xb)
{
    int x;
#ifdef SBL__ROW_GATHER
    if (k->evid_fused) {
        /* gathered with the colour, in its plan, when the ring loaded row y (its columns
           cover [xa, xb) and the pooled estimator's reach) */
        int j;
        for (j = 0; j < 3; ++j)
            if (k->ring[j].row == y && k->ring[j].e) {
                k->evid_in = k->ring[j].e;
                return;
            }
    }
    k->evid_in = k->evid_buf;
    if (k->evid_use && k->evid_row) {
        /* the temporal row gather on the plane (its taps equal the pixel gather's, bit
           for bit: tests/test_paths.c, tests/test_simd.c) */
        sbl__ring_row *r = &k->evid_ring;
        memset(r->unsafe + xa, 0, SBL__CAST(size_t, xb - xa));
        r->row = y;
        sbl__temporal_rp_row(k->evid_ctx, r, y, xa, xb);
        {   /* the test below, in lanes (selects only: the same bits) */
            const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f),
                         cap = sbl__set1(SBL__CAST(float, SBL__POOL_RATIO_CAP));
            for (x = xa; x + SBL__VW <= xb; x += SBL__VW) {
                const sbl__v v = sbl__load(r->x[0] + x);
                const sbl__m ok = sbl__mandnot(sbl__mand(sbl__gt(sbl__load(r->v + x), zero), sbl__gt(v, zero)),
                                               sbl__gt(v, cap));
                sbl__store(k->evid_in + x, sbl__sel(ok, v, one));
            }
        }
        for (; x < xb; ++x) {
            const float v = r->x[0][x];
            k->evid_in[x] = r->v[x] > 0.0f && v > 0.0f && v <= SBL__CAST(float, SBL__POOL_RATIO_CAP) ? v : 1.0f;
        }
        return;
    }
#endif
    for (x = xa; x < xb; ++x)
        k->evid_in[x] = k->evid_use ? sbl__evidence_pixel(SBL__PCAST(const sbl__temporal_rp *, k->evid_ctx), x, y) : 1.0f;
}

/* 1 if any value of the image is other than +-0 (a NaN too), 0 if all are zero. */
static int sbl__plane_nonzero(const sbl_image *im)
{
    const ptrdiff_t step = sbl__step_of(im);
    const size_t row = SBL__CAST(size_t, im->width) * SBL__CAST(size_t, im->channels);
    int y;
    for (y = 0; y < im->height; ++y) {
        const float *p = sbl__px(im, 0, y);
        int any = 0;
        size_t i;
        if (step != im->channels) { /* padded pixels: each pixel's channels */
            int x, c;
            for (x = 0; x < im->width; ++x)
                for (c = 0; c < im->channels; ++c) any |= p[SBL__CAST(ptrdiff_t, x) * step + c] != 0.0f;
        } else {
            for (i = 0; i < row; ++i) any |= p[i] != 0.0f;
        }
        if (any) return 1;
    }
    return 0;
}

/* Row y of the history's tail plane into ring row r over columns [xa, xb), gathered
   with the colour's taps and tests (the row gather where the colour takes it, else the
   pixel gather): x[0] the rate, x[1] the variance; 0 where no tap is valid (a reset:
   nothing seen) and where a value is not one (a rate outside [0, 1], a variance that
   is negative or not finite: the comparisons fail for a NaN). */
static void sbl__tail_gather_row(sbl__kernel *k, sbl__ring_row *r, int y, int xa, int xb)
{
    const sbl__temporal_rp *ts = SBL__PCAST(const sbl__temporal_rp *, k->tail_ctx);
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), big = sbl__set1(FLT_MAX);
    int x;
    r->row = y;
#ifdef SBL__ROW_GATHER
    if (k->gather_row && sbl__row_gather_ok(&ts->src)) {
        memset(r->unsafe + xa, 0, SBL__CAST(size_t, xb - xa));
        sbl__temporal_rp_row(ts, r, y, xa, xb);
    } else
#endif
    {
        for (x = xa; x < xb; ++x) {
            float v[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            r->v[x] = sbl__temporal_rp_pixel(ts, x, y, v) > 0.0f ? 1.0f : 0.0f;
            r->x[0][x] = v[0];
            r->x[1][x] = v[1];
        }
    }
    x = xa;
    if (xb - xa >= SBL__VW)
        for (;;) { /* (selects only: the overlapping last vector sees its own output) */
            const sbl__m ok = sbl__gt(sbl__load(r->v + x), zero);
            const sbl__v rate = sbl__load(r->x[0] + x), var = sbl__load(r->x[1] + x);
            sbl__store(r->x[0] + x, sbl__sel(ok, sbl__sel(sbl__gt(rate, one), zero,
                                                          sbl__sel(sbl__gt(rate, zero), rate, zero)), zero));
            sbl__store(r->x[1] + x, sbl__sel(ok, sbl__sel(sbl__gt(var, big), zero,
                                                          sbl__sel(sbl__gt(var, zero), var, zero)), zero));
            if (x + SBL__VW >= xb) break;
            x += SBL__VW;
            if (x + SBL__VW > xb) x = xb - SBL__VW;
        }
    else
        for (; x < xb; ++x) sbl__tail_put(r->x[0] + x, r->x[1] + x, r->v[x] > 0.0f, r->x[0][x], r->x[1][x]);
}

/* The tail plane for row y (k->tail_on): this frame's records cleared over [xa, xb);
   with the history's plane, rows y - 1 .. y + 1 gathered (each row once per span: the
   ring keeps them) and their 3x3 means into tail_r / tail_t (the rows inside the
   image, the columns inside [xa, xb); a reset pixel counts as nothing seen). The sums
   are separable: each column's rows (into tail_e / tail_d, cleared after), then three
   columns. k->tail_fused: the colour's ring rows hold the rows, gathered with the colour
   (sbl__ring_gather, over the same columns). */
static void sbl__tail_prepare(sbl__kernel *k, int y, int xa, int xb)
{
    const float *rr[3], *tt[3];
    int j, x, n = 0;
    if (k->tail_use && xb > xa) {
        float inv_n;
        if (xa != k->tail_xa || xb != k->tail_xb) { /* another span: nothing held */
            for (j = 0; j < 3; ++j) k->tail_ring[j].row = -1;
            k->tail_xa = xa;
            k->tail_xb = xb;
        }
        for (j = -1; j <= 1; ++j) {
            const int ry = y + j;
            int i, have = -1, free_slot = -1;
            if (ry < 0 || ry >= k->h) continue;
            if (k->tail_fused) { /* (ring[j + 1] holds row ry) */
                rr[n] = k->ring[j + 1].tl[0];
                tt[n++] = k->ring[j + 1].tl[1];
                continue;
            }
            for (i = 0; i < 3; ++i) {
                const int held = k->tail_ring[i].row;
                if (held == ry) have = i;
                else if (free_slot < 0 && (held < 0 || held < y - 1 || held > y + 1)) free_slot = i;
            }
            if (have < 0) {
                have = free_slot;
                sbl__tail_gather_row(k, &k->tail_ring[have], ry, xa, xb);
            }
            rr[n] = k->tail_ring[have].x[0];
            tt[n++] = k->tail_ring[have].x[1];
        }
        {   /* each column's rows (always added in this order), then three columns; in
               lanes where the span holds a vector (the last one overlapping: its
               outputs are not its inputs) */
            const float *r0 = rr[0], *t0 = tt[0];
            const float *r1 = rr[n > 1 ? 1 : 0], *t1 = tt[n > 1 ? 1 : 0];
            const float *r2 = rr[n - 1], *t2 = tt[n - 1];
            float *ce = k->tail_e, *cd = k->tail_d;
            const float w1 = n > 1 ? 1.0f : 0.0f, w2 = n > 2 ? 1.0f : 0.0f;
            inv_n = 1.0f / SBL__CAST(float, 3 * n);
            if (xb - xa >= SBL__VW + 2) {
                const sbl__v v1 = sbl__set1(w1), v2 = sbl__set1(w2), vi = sbl__set1(inv_n);
                for (x = xa;;) {
                    sbl__store(ce + x, sbl__add(sbl__add(sbl__load(r0 + x), sbl__mul(v1, sbl__load(r1 + x))),
                                                sbl__mul(v2, sbl__load(r2 + x))));
                    sbl__store(cd + x, sbl__add(sbl__add(sbl__load(t0 + x), sbl__mul(v1, sbl__load(t1 + x))),
                                                sbl__mul(v2, sbl__load(t2 + x))));
                    if (x + SBL__VW >= xb) break;
                    x += SBL__VW;
                    if (x + SBL__VW > xb) x = xb - SBL__VW;
                }
                for (x = xa + 1;;) {
                    sbl__store(k->tail_r + x, sbl__mul(sbl__add(sbl__add(sbl__load(ce + x - 1), sbl__load(ce + x)),
                                                                sbl__load(ce + x + 1)), vi));
                    sbl__store(k->tail_t + x, sbl__mul(sbl__add(sbl__add(sbl__load(cd + x - 1), sbl__load(cd + x)),
                                                                sbl__load(cd + x + 1)), vi));
                    if (x + SBL__VW >= xb - 1) break;
                    x += SBL__VW;
                    if (x + SBL__VW > xb - 1) x = xb - 1 - SBL__VW;
                }
            } else {
                for (x = xa; x < xb; ++x) {
                    ce[x] = r0[x] + w1 * r1[x] + w2 * r2[x];
                    cd[x] = t0[x] + w1 * t1[x] + w2 * t2[x];
                }
                for (x = xa + 1; x + 1 < xb; ++x) {
                    k->tail_r[x] = (ce[x - 1] + ce[x] + ce[x + 1]) * inv_n;
                    k->tail_t[x] = (cd[x - 1] + cd[x] + cd[x + 1]) * inv_n;
                }
            }
        }
        /* the span's end columns: two columns (one if the span has one) */
        inv_n = 1.0f / SBL__CAST(float, (xb - xa > 1 ? 2 : 1) * n);
        k->tail_r[xa] = (k->tail_e[xa] + (xb - xa > 1 ? k->tail_e[xa + 1] : 0.0f)) * inv_n;
        k->tail_t[xa] = (k->tail_d[xa] + (xb - xa > 1 ? k->tail_d[xa + 1] : 0.0f)) * inv_n;
        if (xb - xa > 1) {
            k->tail_r[xb - 1] = (k->tail_e[xb - 2] + k->tail_e[xb - 1]) * inv_n;
            k->tail_t[xb - 1] = (k->tail_d[xb - 2] + k->tail_d[xb - 1]) * inv_n;
        }
    }
    memset(k->tail_e + xa, 0, SBL__CAST(size_t, xb - xa) * sizeof(float));
    memset(k->tail_d + xa, 0, SBL__CAST(size_t, xb - xa) * sizeof(float));
}

/* Row y's pixels [xa, xb) of the output tail plane: each pixel's running mean of its
   exceedance and squared excess, over its history's length (the history's own value,
   gathered, unpooled, 0 where the history has no plane: nothing seen in its N frames;
   1 / (N + 1) of this frame's record, N the capped length of x*, 0 at a reset); 0 with
   the estimators that have no limit. Formed in tail_r / tail_t,
   then interleaved. */
static void sbl__tail_store(sbl__kernel *k, int y, int xa, int xb)
{
    const float *own = NULL, *own_t = NULL; /* the history's rate and variance at row y */
    const float *planes[2];
    int x, j;
    for (j = 0; j < 3 && k->tail_use && !k->tail_fused; ++j)
        if (k->tail_ring[j].row == y) {
            own = k->tail_ring[j].x[0];
            own_t = k->tail_ring[j].x[1];
        }
    if (k->tail_fused) { /* (the ring's row y, not yet advanced) */
        own = k->ring[1].tl[0];
        own_t = k->ring[1].tl[1];
    }
    if (!k->tail_on) {
        for (x = xa; x < xb; ++x) {
            float *o = sbl__px(&k->out_tail, x, y);
            o[0] = o[1] = 0.0f;
        }
        return;
    }
    /* into tail_r / tail_t (the row's kernel is done with them): in lanes where the span
       holds a vector, the last one overlapping (its outputs are not its inputs) */
    if (xb - xa >= SBL__VW) {
        const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), cap = sbl__set1(k->n_cap);
        const sbl__v big = sbl__set1(FLT_MAX);
        for (x = xa;;) {
            const sbl__v n = sbl__load(k->ring[1].n + x);
            const sbl__m seen = sbl__gt(n, zero);
            const sbl__v nc = sbl__sel(seen, sbl__min(n, cap), zero);
            const sbl__v a = sbl__div(one, sbl__add(nc, one));
            const sbl__v r0 = own ? sbl__sel(seen, sbl__load(own + x), zero) : zero;
            const sbl__v t0 = own ? sbl__sel(seen, sbl__load(own_t + x), zero) : zero;
            const sbl__v t1 = sbl__add(t0, sbl__mul(a, sbl__sub(sbl__load(k->tail_d + x), t0)));
            sbl__store(k->tail_r + x, sbl__add(r0, sbl__mul(a, sbl__sub(sbl__load(k->tail_e + x), r0))));
            sbl__store(k->tail_t + x, sbl__min(t1, big)); /* a finite record of a huge excess */
            if (x + SBL__VW >= xb) break;
            x += SBL__VW;
            if (x + SBL__VW > xb) x = xb - SBL__VW;
        }
    } else {
        for (x = xa; x < xb; ++x) {
            const float n = k->ring[1].n[x];
            const float nc = n > 0.0f ? (n < k->n_cap ? n : k->n_cap) : 0.0f;
            const float a = 1.0f / (nc + 1.0f);
            const float r0 = own && nc > 0.0f ? own[x] : 0.0f, t0 = own && nc > 0.0f ? own_t[x] : 0.0f;
            const float t1 = t0 + a * (k->tail_d[x] - t0);
            k->tail_r[x] = r0 + a * (k->tail_e[x] - r0);
            k->tail_t[x] = t1 <= FLT_MAX ? t1 : FLT_MAX; /* a finite record of a huge excess */
        }
    }
    planes[0] = k->tail_r;
    planes[1] = k->tail_t;
    sbl__interleave(sbl__px(&k->out_tail, 0, y), sbl__step_of(&k->out_tail), 2, planes, xa, xb);
}

/* Row y's pixels [xa, xb) of the output evidence plane: this frame's R (pooled), else 1
   (no evidence: the other estimators compute none). */
static void sbl__evidence_store(const sbl__kernel *k, int y, int xa, int xb, int pooled)
{
    int x;
    if (pooled && sbl__step_of(&k->out_e) == 1 && xa < xb) { /* packed: the row as it is */
        memcpy(sbl__px(&k->out_e, xa, y), k->evid_out + xa, SBL__CAST(size_t, xb - xa) * sizeof(float));
        return;
    }
    for (x = xa; x < xb; ++x) *sbl__px(&k->out_e, x, y) = pooled ? k->evid_out[x] : 1.0f;
}

/* A prior probability of change from the region (docs/ESTIMATORS.md 3.10). A moving
   light changes most of a region, a static scene almost none of it, and the share of
   change says how readily a pixel's own evidence should be believed. s = (k + 1) /
   (n + 2) over the n pixels of rows y - 1 .. y + 1 of the history's evidence plane as it
   is (last frame's R, not reprojected: a region's share needs no pixel's motion, and
   every row-range call can read it), k of them beyond c_R: the rule of succession over
   the region. A Beta prior of mean s and weight 2 for the pixel's probability of change,
   updated by its history's N unchanged frames, gives 2 s / (N + 2): Laplace's 1 / (N + 2)
   (section 2.2) at s = 1/2. So the prior odds against change grow by M = 1 / (2 s), and
   each source of evidence asks for that much more: the local test's odds 0.5 ((N + 2) M
   - 1), the one-frame blocks' threshold c + ln M (the tail of a ratio of unit spread,
   e^-q), the carried R's (c_R - 1)^2 + 2 kappa ln M (Gaussian, variance kappa =
   lambda / (2 - lambda)). Without the history's plane, M = 1: as before, bit for bit. */
#ifndef SBL_EVIDENCE_REGION
/* the sources M applies to: 1 the local test, 2 the blocks, 4 the carried R; 0: none
   (session 10's estimator). With the mix towards the paper's weight (SBL_EVIDENCE_MIX)
   all three: the mix lets the paper's weight in wherever R passes its threshold, so R's
   false alarms need the region's prior too (3.10, 3.11) */
#if SBL_EVIDENCE_MIX
#define SBL_EVIDENCE_REGION 7
#else
#define SBL_EVIDENCE_REGION 3
#endif
#endif

/* Pixels of row y of the plane beyond c_R (ratios only: > the cap is not one). */
static long sbl__evidence_row_count(const sbl_image *plane, int y)
{
    const float *row = sbl__px(plane, 0, y);
    const ptrdiff_t step = sbl__step_of(plane);
    const float thr = SBL__CAST(float, SBL__EVIDENCE_THR), cap = SBL__CAST(float, SBL__POOL_RATIO_CAP);
    long c = 0;
    int x = 0;
#ifdef SBL__ROW_GATHER
    if (step == 1) {
        /* a vector at a time: each lane counts in float (exact below 2^24), flushed to
           c every 2^20 vectors; the same comparisons, so the same count */
        const sbl__v vthr = sbl__set1(thr), vcap = sbl__set1(cap), one = sbl__set1(1.0f),
                     zero = sbl__set1(0.0f);
        float lanes[SBL__VW];
        while (x + SBL__VW <= plane->width) {
            sbl__v acc = zero;
            int j, n = 0;
            for (; n < (1 << 20) && x + SBL__VW <= plane->width; ++n, x += SBL__VW) {
                const sbl__v v = sbl__load(row + x);
                acc = sbl__add(acc, sbl__sel(sbl__mand(sbl__gt(v, vthr), sbl__le(v, vcap)), one, zero));
            }
            sbl__store(lanes, acc);
            for (j = 0; j < SBL__VW; ++j) c += SBL__CAST(long, lanes[j]);
        }
    }
#endif
    for (; x < plane->width; ++x) {
        const float v = row[x * step];
        c += (v > thr) & (v <= cap);
    }
    return c;
}

/* P(R > c_R) where nothing changes, under the blocks' own null model (q ~ Exp(1), the
   tail e^-q their threshold c + ln M assumes; R its carried average with lambda = 1/3 and
   the bounded step, (SBL_POOLED_BLOCK_SE2_REGION - 1) / lambda): 0.0208 (Monte Carlo,
   bench/evidence_null.c; 0.0230 with session 8's step of 2.5 / lambda; the Gaussian tail of R's
   spread, 0.0062, leaves static content a floor of half its false-alarm share). The
   combined pipeline's share floor is the region's share net of it (docs/ESTIMATORS.md 4.14). */
#define SBL__EVIDENCE_FALSE_ALARM 0.0208
/* The region's prior M (docs/ESTIMATORS.md 3.10) into the kernel's per-row terms: the history
   prior's M (wp.region_m), the blocks' ratio moved by ln M (evid_lnm) and the carried
   evidence's threshold and garrote moved with it; M = 1 leaves the defaults. */
static void sbl__evidence_region(sbl__kernel *k, float m)
{
    const double kap = SBL_EVIDENCE_LAMBDA / (2.0 - SBL_EVIDENCE_LAMBDA);
    double lm, v;
    k->wp.region_m = 1.0f;
    k->evid_lnm = 0.0;
    k->evid_thr = SBL__EVIDENCE_THR;
    k->evid_garrote = SBL__EVIDENCE_GARROTE;
    if (m == 1.0f) return;
    lm = log(SBL__CAST(double, m));
    v = (SBL__EVIDENCE_THR - 1.0) * (SBL__EVIDENCE_THR - 1.0) + 2.0 * kap * lm;
    if (SBL_EVIDENCE_REGION & 1) k->wp.region_m = m;
    if (SBL_EVIDENCE_REGION & 2) k->evid_lnm = lm;
    if (SBL_EVIDENCE_REGION & 4) {
        k->evid_thr = 1.0 + sqrt(v > 0.0 ? v : 0.0);
        k->evid_garrote = (k->evid_thr - 1.0) * (k->evid_thr - 1.0);
    }
}

/* Row y's M (k->wp.region_m), ln M and the carried R's threshold and garrote. */
static void sbl__evidence_share(sbl__kernel *k, int y)
{
    long cnt = 0, n = 0;
    int j, i;
    sbl__evidence_region(k, 1.0f);
    k->wp.evid_share = 0.0f;
    k->wp.evid_mix = SBL_EVIDENCE_MIX && k->evid_use && k->wp.temporal &&
                     k->wp.estimator == SBL_ESTIMATOR_POOLED; /* 3.11 */
    if (!SBL_EVIDENCE_REGION || !k->evid_use || !k->evid_prev || !k->evid_prev->data) return;
    for (j = y - 1; j <= y + 1; ++j) {
        long c = -1;
        if (j < 0 || j >= k->h) continue;
        for (i = 0; i < 3; ++i)
            if (k->share_at[i] == j + 1) c = k->share_cnt[i];
        if (c < 0) { /* rows come in order: the slot of row j - 3 is free */
            i = (j % 3 + 3) % 3;
            c = sbl__evidence_row_count(k->evid_prev, j);
            k->share_at[i] = j + 1;
            k->share_cnt[i] = c;
        }
        cnt += c;
        n += k->w;
    }
    {
        const float m = SBL__CAST(float, SBL__CAST(double, n + 2) / (2.0 * SBL__CAST(double, cnt + 1)));
        /* the share itself, s = 1 / (2 M): the prior probability that a pixel of the
           region changed, below which the mix towards the paper's weight does not go */
        if (SBL_EVIDENCE_MIX >= 2 && k->wp.evid_mix) {
            double sh = SBL__CAST(double, cnt + 1) / SBL__CAST(double, n + 2);
            /* behind a stereo blend (c > 0) the floor taken at the rows' gross share
               costs static content its false alarms (4.14: static -2 %): there it is
               the share of change net of R's false-alarm rate q0, (s - q0) / (1 - q0),
               0 where the rows hold no more pixels beyond c_R than noise puts there.
               The temporal filter alone keeps the gross share (3.12) */
            if (k->wp.shared_bias != 0.0f)
                sh = sh > SBL__EVIDENCE_FALSE_ALARM
                         ? (sh - SBL__EVIDENCE_FALSE_ALARM) / (1.0 - SBL__EVIDENCE_FALSE_ALARM)
                         : 0.0;
            k->wp.evid_share = SBL__CAST(float, sh);
        }
        sbl__evidence_region(k, m);
    }
}

/* sbl__row_pool_ref's ratio r of pixel x with the carried evidence (in double): writes
   the pixel's R, returns r raised to the evidence's where the history has the plane
   (and the blocks' r = q - c moved to q - (c + ln M), 3.10). */
static double sbl__evidence_ratio_ref(sbl__kernel *k, int x, double sm2, double sse2, double r)
{
    const double lam = SBL_EVIDENCE_LAMBDA, e0 = SBL__CAST(double, k->evid_in[x]);
    double q = sse2 > 0.0 ? sm2 / sse2 : (sm2 > 0.0 ? SBL__POOL_RATIO_CAP : 0.0), e;
    if (k->evid_lnm != 0.0 && sse2 > 0.0) r -= k->evid_lnm;
    if (q > SBL__POOL_RATIO_CAP) q = SBL__POOL_RATIO_CAP;
    if (!(sse2 + sm2 > 0.0)) q = 1.0; /* no block: no evidence either way */
    if (q > e0 + SBL__EVIDENCE_STEP / lam) q = e0 + SBL__EVIDENCE_STEP / lam; /* bounded step */
    e = e0 + lam * (q - e0);
    k->evid_out[x] = SBL__CAST(float, e);
    if (k->evid_use) {
        const double thr = k->evid_thr;
        double rt;
        if (SBL_EVIDENCE_GATE == 2) /* garrote: (R - 1) - (c_R - 1)^2 / (R - 1) beyond c_R */
            rt = e > thr ? (e - 1.0) - k->evid_garrote / (e - 1.0) : 0.0;
        else
            rt = SBL_EVIDENCE_GATE ? (e > thr ? e - 1.0 : 0.0) : e - thr;
        if (rt > r) r = rt;
    }
    return r;
}

/* The same in lanes (float), for pixels [x, x + VW). */
SBL__INLINE sbl__v sbl__evidence_ratio_lanes(sbl__kernel *k, int x, sbl__v sm2, sbl__v sse2, sbl__v r)
{
    const sbl__v zero = sbl__set1(0.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v cap = sbl__set1(SBL__CAST(float, SBL__POOL_RATIO_CAP));
    const sbl__v lam = sbl__set1(SBL__CAST(float, SBL_EVIDENCE_LAMBDA));
    const sbl__v e0 = sbl__load(k->evid_in + x);
    sbl__v q = sbl__sel(sbl__gt(sse2, zero), sbl__div(sm2, sbl__max(sse2, tiny)),
                        sbl__sel(sbl__gt(sm2, zero), cap, zero)), e;
    q = sbl__min(q, cap);
    q = sbl__sel(sbl__gt(sbl__add(sse2, sm2), zero), q, sbl__set1(1.0f));
    q = sbl__min(q, sbl__add(e0, sbl__set1(SBL__CAST(float, SBL__EVIDENCE_STEP / SBL_EVIDENCE_LAMBDA))));
    e = sbl__add(e0, sbl__mul(lam, sbl__sub(q, e0)));
    sbl__store(k->evid_out + x, e);
    if (k->evid_lnm != 0.0) /* the blocks' threshold c + ln M (3.10), where they have noise */
        r = sbl__sel(sbl__gt(sse2, zero), sbl__sub(r, sbl__set1(SBL__CAST(float, k->evid_lnm))), r);
    if (k->evid_use) {
        const sbl__v thr = sbl__set1(SBL__CAST(float, k->evid_thr));
        sbl__v rt;
        if (SBL_EVIDENCE_GATE == 2) { /* the denominator kept >= c_R - 1 where not taken */
            const sbl__v e1 = sbl__sub(e, sbl__set1(1.0f));
            const sbl__v g = sbl__div(sbl__set1(SBL__CAST(float, k->evid_garrote)),
                                      sbl__max(e1, sbl__set1(SBL__CAST(float, k->evid_thr - 1.0))));
            rt = sbl__sel(sbl__gt(e, thr), sbl__sub(e1, g), zero);
        } else {
            rt = SBL_EVIDENCE_GATE ? sbl__sel(sbl__gt(e, thr), sbl__sub(e, sbl__set1(1.0f)), zero)
                                   : sbl__sub(e, thr);
        }
        r = sbl__max(r, rt);
    }
    return r;
}

/* The factor of the mix towards the paper's weight (SBL_EVIDENCE_MIX, 3.11) at pixel x
   of row pool_row: the carried evidence's own shrink sh_R = r_R / (1 + r_R), r_R as
   sbl__evidence_ratio_ref forms it from the stored (float) R, and not below the region's
   share s of change, the prior probability that the pixel changed (3.12). */
static float sbl__evidence_shrink(const sbl__kernel *k, int x)
{
    const double e = SBL__CAST(double, k->evid_out[x]), thr = k->evid_thr;
    double rt;
    float sh;
    if (SBL_EVIDENCE_GATE == 2)
        rt = e > thr ? (e - 1.0) - k->evid_garrote / (e - 1.0) : 0.0;
    else
        rt = SBL_EVIDENCE_GATE ? (e > thr ? e - 1.0 : 0.0) : e - thr;
    sh = rt > 0.0 ? SBL__CAST(float, rt / (1.0 + rt)) : 0.0f;
#if SBL_EVIDENCE_MIX >= 2
    if (k->wp.evid_share > sh) sh = k->wp.evid_share;
#endif
    return sh;
}

/* The same in lanes (float), for pixels [x, x + VW). */
SBL__INLINE sbl__v sbl__evidence_shrink_lanes(const sbl__kernel *k, int x)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__v e = sbl__load(k->evid_out + x), e1 = sbl__sub(e, one);
    const sbl__v thr = sbl__set1(SBL__CAST(float, k->evid_thr));
    sbl__v rt;
    if (SBL_EVIDENCE_GATE == 2) /* the denominator kept >= c_R - 1 where not taken */
        rt = sbl__sel(sbl__gt(e, thr),
                      sbl__sub(e1, sbl__div(sbl__set1(SBL__CAST(float, k->evid_garrote)),
                                            sbl__max(e1, sbl__set1(SBL__CAST(float, k->evid_thr - 1.0))))),
                      zero);
    else
        rt = SBL_EVIDENCE_GATE ? sbl__sel(sbl__gt(e, thr), e1, zero) : sbl__sub(e, thr);
    rt = sbl__max(rt, zero);
#if SBL_EVIDENCE_MIX >= 2
    return sbl__max(sbl__div(rt, sbl__add(one, rt)), sbl__set1(k->wp.evid_share));
#else
    return sbl__div(rt, sbl__add(one, rt));
#endif
}

/* Pooled estimator, the double reference of sbl__row_pool: the prior bias-to-noise ratio
   r = tau^2 / se^2 at each pixel of [xa, xb) of row R[1]->row (docs/ESTIMATORS.md
   section 3). Each 3x3 block of paired differences d = x* - y (pixels with a valid x*
   and finite values, at least 3) gives its squared mean m2 = sum_c mean_c^2 and the
   squared standard error of that mean se2 = sum_c var_c / n (var_c the sample
   variance); over the blocks centred at x + SBL__POOL_STEP b, |b| <= SBL__POOL_BLOCKS,
   r = max(0, sum m2 / sum se2 - SBL__POOL_THR(k)): the blocks' bias energy beyond
   the threshold, in units of the noise of their means. A ratio: independent of the
   scale of the values (HDR). Reads the ring's columns [xa - SBL__POOL_REACH,
   xb + SBL__POOL_REACH) (clamped to the image). Scalar, in double, in a fixed order:
   the same value whatever span computes the row. The reference of the lanes
   (sbl__row_pool), and what computes the pixels they cannot: rows narrower than a
   vector can be made to fit, and pixels whose reach holds an unsafe value (the float
   sums would overflow or underflow). */
SBL__INLINE void sbl__row_pool_ref_ch(sbl__kernel *k, const sbl__ring_row *const *R, int xa,
                                     int xb, const int ch)
{
    const int w = k->w;
    int za = xa - SBL__POOL_STEP * SBL__POOL_BLOCKS, zb = xb + SBL__POOL_STEP * SBL__POOL_BLOCKS;
    int x, c;
    double cols[3][9], *col[3]; /* columns x - 1, x, x + 1 (rotated) */
    col[0] = cols[0]; col[1] = cols[1]; col[2] = cols[2];
    if (za < 0) za = 0;
    if (zb > w) zb = w;
    if (za < zb) {
        sbl__pool_column(k, R, za - 1, col[0], ch);
        sbl__pool_column(k, R, za, col[1], ch);
    }
    for (x = za; x < zb; ++x) {
        double m2 = 0.0, se2 = 0.0, n, *t;
        sbl__pool_column(k, R, x + 1, col[2], ch);
        /* the block: three column sums, always added in this order (the same value
           whatever column the row's span starts at) */
        n = col[0][0] + col[1][0] + col[2][0];
        k->pool_m2[x] = 0.0;
        k->pool_se2[x] = -1.0; /* no block here */
        if (n >= 3.0) {
            for (c = 0; c < ch; ++c) {
                double s1 = col[0][1 + c] + col[1][1 + c] + col[2][1 + c];
                double s2 = col[0][5 + c] + col[1][5 + c] + col[2][5 + c];
                double mu = s1 / n, v = (s2 - n * mu * mu) / (n - 1.0);
                m2 += mu * mu;
                se2 += (v > 0.0 ? v : 0.0) / n;
            }
            k->pool_m2[x] = m2;
            k->pool_se2[x] = se2;
        }
        t = col[0]; col[0] = col[1]; col[1] = col[2]; col[2] = t;
    }
    for (x = xa; x < xb; ++x) {
        double sm2 = 0.0, sse2 = 0.0, r;
        int b;
        for (b = -SBL__POOL_BLOCKS; b <= SBL__POOL_BLOCKS; ++b) {
            int cx = x + SBL__POOL_STEP * b;
            if (cx < 0 || cx >= w || k->pool_se2[cx] < 0.0) continue;
            sm2 += k->pool_m2[cx];
            sse2 += k->pool_se2[cx];
        }
        if (k->wp.tail) {
            /* each of the five blocks' se^2 at least the tail variance over its 9 pairs
               (2.4): counted as the lanes count them, the blocks outside the image or
               without pairs too (their terms are 0 there) */
            const double tf = SBL__CAST(double, k->tail_t[x]) * (2 * SBL__POOL_BLOCKS + 1) / 9.0;
            if (sse2 < tf) sse2 = tf;
        }
        /* pooled squared mean over pooled squared standard error, less the threshold;
           no noise at all and a mean: certain change (capped) */
        r = sse2 > 0.0 ? sm2 / sse2 - SBL__POOL_THR(k) : (sm2 > 0.0 ? SBL__POOL_RATIO_CAP : 0.0);
        if (k->evid_out) r = sbl__evidence_ratio_ref(k, x, sm2, sse2, r);
        if (r > SBL__POOL_RATIO_CAP) r = SBL__POOL_RATIO_CAP;
        k->pool_r[x] = r > 0.0 ? SBL__CAST(float, r) : 0.0f;
    }
}

/* sbl__row_pool_ref with the channel count a constant: the column sums of the pixels
   with an unsafe window (tests/ipp "tiny") without a branch per channel and row. */
static void sbl__row_pool_ref(sbl__kernel *k, const sbl__ring_row *const *R, int xa, int xb)
{
    switch (k->ch) {
    case 1: sbl__row_pool_ref_ch(k, R, xa, xb, 1); break;
    case 2: sbl__row_pool_ref_ch(k, R, xa, xb, 2); break;
    case 3: sbl__row_pool_ref_ch(k, R, xa, xb, 3); break;
    default: sbl__row_pool_ref_ch(k, R, xa, xb, 4); break;
    }
}

/* The pooled prior bias-to-noise ratio at pixel x of row y (0 if not computed). */
static float sbl__pool_ratio(const sbl__kernel *k, int x, int y)
{
    return (k->wp.estimator == SBL_ESTIMATOR_POOLED && k->pool_row == y) ? k->pool_r[x] : 0.0f;
}

/* ---- the resampling blur's bias (docs/ESTIMATORS.md 4.10, 4.12) -----------------
   A bilinear fetch at fraction f convolves the history with a kernel of variance
   v = f (1 - f) per axis; a history grown from a restart at this fraction every frame
   carries S = (N + 1) v / 2, and to second order its bias is b_c = (S_x d2x_c +
   S_y d2y_c) / 2 (d2: x*'s second differences on the pixel's row and column), at most
   half the 3x3 range of x*_c. Its noise: sample k of N was blurred by k v, and the
   variance of a second difference of unit white noise blurred by a Gaussian of
   variance s is g(s) (6 at s = 0), so E[sum_c b_c^2] exceeds B_b^2 by
   (S_x^2 G_x + S_y^2 G_y) var_X / 4, G = (1 / N) sum_{k < N} g(k v). */

/* G = mean_{k < n} g(k v), fitted (docs/ESTIMATORS.md 4.13; bench/blur_fit.c, degree 6,
   joint): Euler-Maclaurin's form J(t) + (6 - g(t)) / (2 n) + v (g'(t) - g'(0)) / (12 n),
   t = n v, J(t) the mean of g over [0, t], written in r = 1 / sqrt(1 + t) (in (0, 1]; g
   ~ t^-2.5 and J's tail ~ t^-1.5 are smooth in r) as
       G = r^2 A(r) + (H(r) + v K(r)) / n,
   A, H, K polynomials whose coefficients were fitted together to G's relative error
   against the exact sum (so they also take up Euler-Maclaurin's remainder at small n):
   within 0.31 % of the sum for n in [1, 200], v in [0, 1/4], 0.28 % of Euler-Maclaurin
   for n up to 2e5. Float, the same operations in the reference path
   (sbl__blur_noise) and in lanes (sbl__blur_noise_lanes). */
static const float sbl__blur_fa[7] = {1.29068747f, -0.0817370846f, 2.39499319f, -6.72754491f,
                                      20.1641806f, -26.2452072f, 15.2113934f};
static const float sbl__blur_fh[7] = {2.95719318f, 2.1371793f, -21.8357819f, 101.953988f,
                                      -233.956177f, 255.783198f, -107.052042f};
static const float sbl__blur_fk[7] = {3.22245745f, -7.2097095f, 53.0754256f, -200.223387f,
                                      392.935917f, -371.451567f, 131.74315f};

/* G at N = n (in = 1 / n) and kernel variance v, one pixel */
SBL__INLINE float sbl__blur_noise(float in, float n, float v)
{
    const float r = 1.0f / sqrtf(1.0f + n * v);
    float pa = sbl__blur_fa[6], ph = sbl__blur_fh[6], pk = sbl__blur_fk[6];
    int j;
    for (j = 5; j >= 0; --j) {
        pa = pa * r + sbl__blur_fa[j];
        ph = ph * r + sbl__blur_fh[j];
        pk = pk * r + sbl__blur_fk[j];
    }
    return r * r * pa + in * (ph + v * pk);
}

/* v = f (1 - f) of the fraction f of m (a motion in pixels: the fraction of x + m) */
SBL__INLINE float sbl__blur_var(float m)
{
    const float f = m - floorf(m);
    return f * (1.0f - f);
}

/* The bilinear fetch's kernel variance per axis at target pixel (x, y): v = f (1 - f)
   of the fractions of the source position the gather's plan takes (sbl__temporal_rp_pos;
   the plan's fractions whatever the taps' tests then keep: a renormalised subset and the
   3x3 fallback, both rare, get the position's fraction too). Motion vectors: the
   fraction of m = kx mv in float (x + 0.5 + m - 0.5 has the fraction of m; the lanes
   compute it so too, sbl__blur_lanes_var); the camera: the position in double, as the
   gather takes it, then v in float. */
SBL__INLINE void sbl__blur_fraction(const sbl__temporal_rp *s, int x, int y, float *vx, float *vy)
{
    double sx, sy, fx, fy;
    sbl__tap_want t;
    *vx = *vy = 0.0f;
    if (s->source == SBL_TEMPORAL_MOTION) {
        const float *mv = SBL__AT(s->motion, x, y);
        *vx = sbl__blur_var(SBL__CAST(float, s->motion_kx) * mv[0]);
        *vy = sbl__blur_var(SBL__CAST(float, s->motion_ky) * mv[1]);
        return;
    }
    if (!sbl__temporal_rp_pos(s, x, y, &t, &sx, &sy)) return;
    sx -= 0.5;
    sy -= 0.5;
    /* x* is valid: the position is within [-0.5, size) (sbl__temporal_rp_pos), so the
       truncation toward 0 and a step down for negatives is floor (no libm call) */
    if (!(sx > -2.0 && sx < 1e9 && sy > -2.0 && sy < 1e9)) return;
    fx = sx - SBL__CAST(double, SBL__CAST(int, sx));
    fy = sy - SBL__CAST(double, SBL__CAST(int, sy));
    if (fx < 0.0) fx += 1.0;
    if (fy < 0.0) fy += 1.0;
    *vx = SBL__CAST(float, fx * (1.0 - fx));
    *vy = SBL__CAST(float, fy * (1.0 - fy));
}

/* The blur's per-pixel scalars from N (n_x: the ring's, capped, at least 1) and the
   fetch's variances: S = (N + 1) v / 2 per axis and the noise factor of the second
   differences, (S_x^2 G_x + S_y^2 G_y) / 4 (G_x = sbl__blur_noise(N, v_x): a finite
   factor at v = 0, where S = 0) */
SBL__INLINE float sbl__blur_scalars(float n, float vx, float vy, float *sxx, float *syy)
{
    const float in = 1.0f / n, h = 0.5f * (n + 1.0f), sx = h * vx, sy = h * vy;
    *sxx = sx;
    *syy = sy;
    return 0.25f * (sx * sx * sbl__blur_noise(in, n, vx) + sy * sy * sbl__blur_noise(in, n, vy));
}

/* The blur's per-pixel scalars at pixel x of ring row r (sbl__blur_scalars). 0: no blur
   at the pixel (no x*, or a fetch at an integer position). */
SBL__INLINE int sbl__blur_pixel(const sbl__kernel *k, const sbl__ring_row *r, int x,
                                double *sxx, double *syy, double *gn)
{
    float vx, vy, n, fsx, fsy;
    *sxx = *syy = *gn = 0.0;
    if (!(r->v[x] > 0.0f)) return 0;
    sbl__blur_fraction(k->blur_rp, x, r->row, &vx, &vy);
    if (vx == 0.0f && vy == 0.0f) return 0;
    n = r->n[x] < k->n_cap ? r->n[x] : k->n_cap;
    if (!(n >= 1.0f)) n = 1.0f;
    *gn = SBL__CAST(double, sbl__blur_scalars(n, vx, vy, &fsx, &fsy));
    *sxx = SBL__CAST(double, fsx);
    *syy = SBL__CAST(double, fsy);
    return 1;
}

/* The blur's terms at pixel x of row R[1] (x* valid there; R[0] / R[2] NULL outside the
   image): *b2 = sum_c b_c^2 (each |b_c| at most half the 3x3 range of x*_c) and *g the
   noise factor (S_x^2 G_x + S_y^2 G_y) / 4; both 0 where the fetch was at an integer
   position or a value is not finite. */
SBL__INLINE void sbl__blur_terms(const sbl__kernel *k, const sbl__ring_row *const *R, int x,
                                 const int ch, double *b2, double *g)
{
    const sbl__ring_row *r = R[1];
    double sxx, syy, sum = 0.0, gn;
    int c, okx, oky;
    *b2 = *g = 0.0;
    if (!sbl__blur_pixel(k, r, x, &sxx, &syy, &gn)) return;
    okx = x > 0 && x + 1 < k->w && r->v[x - 1] > 0.0f && r->v[x + 1] > 0.0f;
    oky = R[0] && R[2] && R[0]->v[x] > 0.0f && R[2]->v[x] > 0.0f;
    for (c = 0; c < ch; ++c) {
        const double xc = SBL__CAST(double, r->x[c][x]);
        const double dx = okx ? SBL__CAST(double, r->x[c][x - 1]) + SBL__CAST(double, r->x[c][x + 1]) - 2.0 * xc : 0.0;
        const double dy = oky ? SBL__CAST(double, R[0]->x[c][x]) + SBL__CAST(double, R[2]->x[c][x]) - 2.0 * xc : 0.0;
        double b = 0.5 * (sxx * dx + syy * dy), lo = xc, hi = xc, half;
        int i, j;
        for (j = 0; j < 3; ++j) {
            if (!R[j]) continue;
            for (i = x - 1; i <= x + 1; ++i) {
                double q;
                if (i < 0 || i >= k->w || !(R[j]->v[i] > 0.0f)) continue;
                q = SBL__CAST(double, R[j]->x[c][i]);
                if (q < lo) lo = q;
                if (q > hi) hi = q;
            }
        }
        /* a symmetric kernel moves a value at most half-way to its neighbours: the
           Taylor form overshoots at edges and where S is large */
        half = 0.5 * (hi - lo);
        if (b > half) b = half;
        if (b < -half) b = -half;
        sum += b * b;
    }
    if (sbl__finite(SBL__CAST(float, sum)) && sbl__finite(SBL__CAST(float, gn))) {
        *b2 = sum;
        *g = gn;
    }
}

/* Pooled stereo (docs/ESTIMATORS.md 4.15, 4.16): the pairs' variance within the
   window's columns, in place of their variance about the window's mean, where the
   columns differ. A silhouette that crosses the rows biases the pairs of a column alike
   (its mixed pixels match one layer only); their spread about the window's mean is then
   that bias, not noise, and it hid the bias from the window's own test. The window's
   pairs by column (one-way analysis of variance), summed over the channels as the
   window's test sums them: SS_T = (n - 1) pv = SS_B + SS_W, SS_W = sum_j sum_i (d_ij -
   mean_j)^2 on n - J degrees of freedom (J the columns with a pair), s_w^2 = SS_W /
   (n - J). The columns differ when some contrast of their means passes the window's own
   test, k standard errors (k = bias_threshold * SBL_POOLED_LOCAL_SCALE, 4): the largest
   t^2 over the contrasts is SS_B / s_w^2 = (J - 1) F (Scheffe), so the gate is
   SS_B > k^2 s_w^2, in the two variances pv > H s_w^2, H = (n - J + k^2) / (n - 1); none
   below 2 columns or 2 degrees of freedom within. Then every channel's pair variance
   becomes SS_W_c / (n - J). The analysis assumes one noise variance for the columns:
   where the columns' own variances s_j^2 = SS_j / (n_j - 1) (channel sums, n_j >= 2)
   differ by more than sbl__fgate_r (the upper 0.00395 point, P(|t_8| > 4), of Hartley's
   max / min ratio of 3 variances on 2 ch degrees of freedom) the noise is not one (a
   light's samples in one column of one eye, 4.16) and pv stays. */
static const float sbl__fgate_r[4] = {1136.81f, 59.3344f, 21.8773f, 13.0117f};

/* The reference path's pairs and the order of the window's loop in
   sbl__kernel_pixel_ref_ch (in double; the lanes: sbl__lanes_moments,
   sbl__pool_lanes_blocks) */
static void sbl__pair_var_within(sbl__moments *m, const sbl__ring_row *const *R, int i0, int i1,
                                 const int ch, double k2)
{
    double d[3][4], ss[4] = {0.0, 0.0, 0.0, 0.0}, pvs = 0.0, sws = 0.0, smax = 0.0, smin = 0.0;
    int i, j, c, n = 0, cols = 0, vcols = 0;
    for (i = i0; i <= i1; ++i) {
        double s[4] = {0.0, 0.0, 0.0, 0.0}, sc = 0.0;
        int nc = 0, r;
        for (j = 0; j < 3; ++j) {
            int ok = 1;
            if (!R[j] || !(R[j]->v[i] > 0.0f)) continue;
            for (c = 0; c < ch; ++c) ok &= sbl__finite(R[j]->y[c][i]);
            if (!ok) continue;
            for (c = 0; c < ch; ++c) {
                d[nc][c] = SBL__CAST(double, R[j]->x[c][i]) - SBL__CAST(double, R[j]->y[c][i]);
                s[c] += d[nc][c];
            }
            ++nc;
        }
        if (!nc) continue;
        for (c = 0; c < ch; ++c) {
            double sj = 0.0;
            for (r = 0; r < nc; ++r) sj += (d[r][c] - s[c] / nc) * (d[r][c] - s[c] / nc);
            ss[c] += sj;
            sc += sj;
        }
        if (nc > 1) {
            /* the column's own variance (channel sum) */
            sc /= nc - 1;
            if (!vcols || sc > smax) smax = sc;
            if (!vcols || sc < smin) smin = sc;
            ++vcols;
        }
        n += nc;
        ++cols;
    }
    if (cols < 2 || n - cols < 2) return;
    if (vcols && !(smax < SBL__CAST(double, sbl__fgate_r[ch - 1]) * smin)) return;
    for (c = 0; c < ch; ++c) {
        pvs += m->pair_var[c];
        sws += ss[c] / (n - cols);
    }
    if (pvs > (n - cols + k2) / (n - 1) * sws)
        for (c = 0; c < ch; ++c) m->pair_var[c] = ss[c] / (n - cols);
}

/* sbl__pair_var_within's test of one noise variance per lane: 1 where the largest of the
   columns' variances (channel sums; columns with fewer than 2 pairs: 0 and big) is below
   sbl__fgate_r times the smallest */
SBL__INLINE sbl__m sbl__fgate_one_var(sbl__v mx, sbl__v mn, const int ch)
{
    return sbl__gt(sbl__mul(mn, sbl__set1(sbl__fgate_r[ch - 1])), mx);
}

/* k^2 of the window's test in the pooled estimator (sbl__weight) */
SBL__INLINE float sbl__fgate_k2(const sbl__kernel *k)
{
    const float kk = SBL__CAST(float, SBL__CAST(double, k->wp.bias_threshold) * SBL_POOLED_LOCAL_SCALE);
    return kk * kk;
}

/* One column's own variance ss / (n - 1) for the gate's largest (*vmx) and smallest
   (*vmn): a column with fewer than 2 pairs enters as 0 and big, which neither extreme
   takes (as sbl__fgate_lanes). n: its pair count, ss: its sum of squares within it
   (channel sum). sbl__pool_lanes_blocks forms it once per column (each serves three
   blocks). */
SBL__INLINE void sbl__fgate_column(sbl__v n, sbl__v ss, sbl__v *vmx, sbl__v *vmn)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__m has2 = sbl__gt(n, sbl__set1(1.5f));
    const sbl__v v = sbl__mul(ss, sbl__div(one, sbl__max(sbl__sub(n, one), one)));
    *vmx = sbl__sel(has2, v, zero);
    *vmn = sbl__sel(has2, v, sbl__set1(1e35f));
}

/* The gate (sbl__fgate_lanes) from the three columns' sbl__fgate_column terms vmx[j],
   vmn[j] */
SBL__INLINE sbl__m sbl__fgate_cols(const sbl__v vmx[3], const sbl__v vmn[3], sbl__v J, sbl__v dof,
                                   sbl__v inv_n1, sbl__v k2, sbl__v sws, sbl__v pvs, const int ch)
{
    const sbl__v big = sbl__set1(1e35f), lim = sbl__set1(1.5f);
    sbl__v thr = sbl__mul(sbl__mul(sbl__add(dof, k2), inv_n1), sws), mx = sbl__set1(0.0f), mn = big;
    int j;
    for (j = 0; j < 3; ++j) {
        mx = sbl__max(mx, vmx[j]);
        mn = sbl__min(mn, vmn[j]);
    }
    thr = sbl__sel(sbl__gt(J, lim), sbl__sel(sbl__gt(dof, lim), thr, big), big);
    thr = sbl__sel(sbl__fgate_one_var(mx, mn, ch), thr, big);
    return sbl__gt(pvs, thr);
}

/* sbl__pair_var_within's gate in lanes: 1 where the pairs' variance pvs (channel sum)
   exceeds H s_w^2, H = (n - J + k^2) / (n - 1), with 2 columns or more and 2 degrees of
   freedom within (dof = n - J), and the columns' own variances agree. n[j], ss[j]: the
   three columns' pair counts and sums of squares within them (channel sums); sws: s_w^2
   (channel sum); inv_n1: 1 / (n - 1). sbl__lanes_moments; sbl__pool_lanes_blocks takes
   its columns' terms from planes (sbl__fgate_column, sbl__fgate_cols). */
SBL__INLINE sbl__m sbl__fgate_lanes(const sbl__v n[3], const sbl__v ss[3], sbl__v J, sbl__v dof,
                                    sbl__v inv_n1, sbl__v k2, sbl__v sws, sbl__v pvs, const int ch)
{
    sbl__v vmx[3], vmn[3];
    int j;
    for (j = 0; j < 3; ++j) sbl__fgate_column(n[j], ss[j], &vmx[j], &vmn[j]);
    return sbl__fgate_cols(vmx, vmn, J, dof, inv_n1, k2, sws, pvs, ch);
}

/* Reference path for one pixel: borders, non-finite and extreme values. ch a constant
   of the caller (sbl__kernel_pixel_ref). */
SBL__INLINE void sbl__kernel_pixel_ref_ch(sbl__kernel *k, const sbl__ring_row *const *R, int x,
                                          const int ch)
{
    const int y = R[1]->row;
    float yc[4], xs[4], out[4], a = 1.0f, n_out;
    float n_x = R[1]->n[x], n_y = sbl__own_n(k, x, y);
    int c, finite = 1;
    for (c = 0; c < ch; ++c) {
        yc[c] = R[1]->y[c][x];
        xs[c] = R[1]->x[c][x];
        finite &= sbl__finite(yc[c]);
    }
    /* the tail plane's record of this pixel: none unless the limit below runs (a lane
       vector that covered it, e.g. with a non-finite sample, may have left one) */
    if (k->tail_on) k->tail_e[x] = k->tail_d[x] = 0.0f;
    if (!finite) {
        /* no new sample: keep x* if there is one, else black with N = 0 */
        for (c = 0; c < ch; ++c) out[c] = n_x > 0.0f ? xs[c] : 0.0f;
        n_out = n_x > 0.0f ? n_x : 0.0f;
        a = 0.0f;
    } else if (!(n_x > 0.0f)) {
        for (c = 0; c < ch; ++c) out[c] = yc[c]; /* disocclusion / no match: reset */
        n_out = k->temporal ? 1.0f : n_y;
    } else if (k->fill) {
        for (c = 0; c < ch; ++c) out[c] = xs[c];
        n_out = n_x;
        a = 0.0f;
    } else {
        float vals[9][4], xvals[9][4];
        int xvalid[9], n = 0, i, j, centre = -1;
        sbl__moments m;
        /* the window's columns inside the image, row by row (the same order as the
           lanes: rows, then columns) */
        const int i0 = x > 0 ? x - 1 : x, i1 = x + 1 < k->w ? x + 1 : x;
        for (j = 0; j < 3; ++j) {
            const sbl__ring_row *r = R[j];
            if (!r) continue;
            for (i = i0; i <= i1; ++i) {
                int ok = 1;
                for (c = 0; c < ch; ++c) {
                    vals[n][c] = r->y[c][i];
                    xvals[n][c] = r->x[c][i];
                    ok &= sbl__finite(vals[n][c]);
                }
                if (!ok) continue;
                xvalid[n] = r->v[i] > 0.0f;
                if (j == 1 && i == x) centre = n;
                ++n;
            }
        }
        sbl__moments_core(&m, SBL__PCAST(const float(*)[4], vals), SBL__PCAST(const float(*)[4], xvals), xvalid, n, ch,
                          centre);
        m.pool_r = SBL__CAST(double, sbl__pool_ratio(k, x, y));
        if (k->wp.estimator == SBL_ESTIMATOR_POOLED && !k->temporal) sbl__pair_var_within(&m, R, i0, i1, ch, SBL__CAST(double, sbl__fgate_k2(k)));
        if (n_x > k->n_cap) n_x = k->n_cap;
        if ((SBL_EVIDENCE_MIX && k->wp.evid_mix && k->pool_row == y) || k->wp.blur || k->tail_on) {
            sbl__weight_params wp = k->wp;
            if (k->tail_on) { /* the carried tail at this pixel, and where its record goes (2.4) */
                wp.tail_r = k->tail_r[x];
                wp.tail_t = k->tail_t[x];
                wp.tail_e = k->tail_e + x;
                wp.tail_d = k->tail_d + x;
            }
            /* the mix's factor at this pixel (3.11) */
            if (SBL_EVIDENCE_MIX && k->wp.evid_mix && k->pool_row == y) wp.evid_sh = sbl__evidence_shrink(k, x);
            /* the resampling blur's terms at this pixel (4.12) */
            if (k->wp.blur) sbl__blur_terms(k, R, x, ch, &wp.blur_b2, &wp.blur_g);
            n_out = sbl__blend_pixel(&wp, &m, yc, xs, n_x, n_y, ch, out, &a);
        } else if (k->wp.stereo_ev && k->sev[x] > 0.0f) { /* 6.15 */
            sbl__weight_params wp = k->wp;
            wp.stereo_change = 1;
            n_out = sbl__blend_pixel(&wp, &m, yc, xs, n_x, n_y, ch, out, &a);
        } else {
            n_out = sbl__blend_pixel(&k->wp, &m, yc, xs, n_x, n_y, ch, out, &a);
        }
    }
    if (!(n_out <= k->n_cap)) n_out = k->n_cap; /* also NaN */
    for (c = 0; c < ch; ++c) k->stage[c][x] = out[c];
    k->stage_n[x] = n_out;
    k->stage_a[x] = a;
}

static void sbl__kernel_pixel_ref(sbl__kernel *k, const sbl__ring_row *const *R, int x)
{
    switch (k->ch) {
    case 1: sbl__kernel_pixel_ref_ch(k, R, x, 1); break;
    case 2: sbl__kernel_pixel_ref_ch(k, R, x, 2); break;
    case 3: sbl__kernel_pixel_ref_ch(k, R, x, 3); break;
    default: sbl__kernel_pixel_ref_ch(k, R, x, 4); break;
    }
}

/* The lane kernel, as stages named like their reference-path counterparts:
   sbl__lanes_moments (sbl__moments_core), sbl__lanes_rectify (sbl__rectify),
   sbl__lanes_weight (sbl__weight) and sbl__lanes_blend (the rest of sbl__blend_pixel
   and Eq. 5). Same algebra as the reference path with count = 9, in float.

   The 3x3 sums are separable: sbl__lanes_columns sums each column's three rows once
   per output row (a chunk of SBL__CHUNK columns at a time), and sbl__lanes_moments
   adds three columns per pixel, instead of nine loads per pixel and statistic.
   Precision policy: the sums are one-pass (sum of squares minus n mean^2), so every
   sum is taken about a shift that is a sample of the set summed, never about 0: then
   (mean - shift)^2 <= n variance, the subtracted term is at most n times the result,
   and the subtraction loses at most log2(n + 1) bits however large the mean
   (tests/test_paths.c: 1e4 + noise 0.05, a bias of 500, a firefly of 1e4: variances
   measured within 2e-6 relative of double; a sum about 0 is off 1e5-fold). A column
   is summed about its own top sample (Y) and its first valid x* - y (pairs); the
   pixel moves its side columns to the window's shift with sum (e + D)^2 = sum e^2 +
   D (2 sum e + n D), exact algebra whose terms are bounded by the window's spread.
   The window's shifts: Y about its top-centre sample, which also belongs to the
   leave-centre-out set of the robust estimator (m8, v8 are summed without the centre,
   never as the 9-sums minus it: a firefly at the centre would cancel the neighbours'
   variance away); the pairs about the centre column's shift (a valid pair of the
   window wherever the centre's x* is valid; elsewhere the output resets to Y and the
   pair sums are not used). Lanes are independent and every column is computed by the
   same operations whatever the chunk or the vector width, so spans, bands and every
   build give the same bits. */

/* Statistics of one vector of pixels: Y's 3x3 moments and the paired differences. */
typedef struct sbl__lane_stats {
    sbl__v mean[4], var[4], lo[4], hi[4], pd[4], pv[4];
    sbl__v xs[4];   /* x* (rectified by sbl__lanes_rectify)                         */
    sbl__v xr[4];   /* x* as gathered                                               */
    sbl__v yc[4];   /* own sample                                                   */
    sbl__v yb[4];   /* own sample as blended (firefly-limited by the robust estimator) */
    sbl__v m8[4], v8[4]; /* mean / population variance of Y without the centre (robust) */
    sbl__v inv_cnt; /* 1 / max(pairs, 1)                                            */
    sbl__m has_pairs, two_pairs;
    sbl__v pool_r;  /* pooled estimator: prior bias-to-noise ratio (sbl__row_pool)     */
    sbl__v evid_sh; /* the carried evidence's shrink (SBL_EVIDENCE_MIX; read only then) */
    sbl__v sev;     /* stereo: the eyes' change flags (k->sev; read only where wp.stereo_ev) */
    sbl__v a2[4];   /* weight of the two-estimate blend (before the pooled lean): Eq. 5 */
    sbl__v bessel;  /* n / (n - 1), n Y's samples in the window: 9 / 8 inside the image
                       (sbl__lane_edge) */
    sbl__v lean_s, inv_n8; /* (n - 1) / (n - 2) and 1 / (n - 1): 8 / 7 and 1 / 8 inside
                              (the lean's neighbour count, sbl__lanes_lean) */
    sbl__v blur_b2, blur_g; /* the resampling blur's terms (sbl__blur_terms; read only
                               where wp.blur) */
    sbl__v tail_t;  /* the carried tail variance (k->tail_t; read only where wp.tail) */
    sbl__v rl_e, rl_d, rl_v8, rl_xt; /* the restart lean's E, D, the neighbours' variance
                                        and the history's texture (sbl__lanes_lean_inputs;
                                        read only where wp.lean_restart) */
    sbl__v rl_w, rl_vy, rl_f; /* the weight before the restart lean, V_Y, the lean's
                                 share (sbl__restart_share), */
    sbl__m rl_off;            /* and where the share is 0 (sbl__lanes_weight sets them) */
} sbl__lane_stats;

/* The planes of the three window rows, gathered once per call of the lane kernel (one
   load per plane in the channel loops instead of two). */
typedef struct sbl__lane_rows {
    const float *y[3][4], *x[3][4], *v[3];
    /* the same planes as row[j] + off (sbl__kernel_bind lays each ring row's planes out
       at the same distances from its y[0]): three pointers and the offsets for the
       column sums, whose loop would otherwise hold 7 ch + 3 plane pointers */
    const float *row[3];
    ptrdiff_t off_y[4], off_x[4], off_v;
} sbl__lane_rows;

static void sbl__lane_rows_of(sbl__lane_rows *W, const sbl__ring_row *const *R, int ch)
{
    int j, c;
    for (j = 0; j < 3; ++j) {
        for (c = 0; c < ch; ++c) { W->y[j][c] = R[j]->y[c]; W->x[j][c] = R[j]->x[c]; }
        W->v[j] = R[j]->v;
        W->row[j] = R[j]->y[0];
    }
    for (c = 0; c < ch; ++c) {
        W->off_y[c] = R[0]->y[c] - R[0]->y[0];
        W->off_x[c] = R[0]->x[c] - R[0]->y[0];
    }
    W->off_v = R[0]->v - R[0]->y[0];
}

/* Channel c of columns [x, x + VW) (index i in the chunk), for sbl__lanes_columns. */
SBL__INLINE void sbl__lanes_column(sbl__kernel *k, const sbl__lane_rows *W, int x, int i, int c,
                                   sbl__v v1, sbl__v v2, sbl__m ok0, sbl__m ok1, int clamp,
                                   const int full)
{
    const ptrdiff_t iy = x + W->off_y[c], ix = x + W->off_x[c];
    const sbl__v y0 = sbl__load(W->row[0] + iy), y1 = sbl__load(W->row[1] + iy),
                 y2 = sbl__load(W->row[2] + iy);
    const sbl__v a1 = sbl__sub(y1, y0), a2 = sbl__sub(y2, y0);
    const sbl__v d0 = sbl__sub(sbl__load(W->row[0] + ix), y0),
                 d1 = sbl__sub(sbl__load(W->row[1] + ix), y1),
                 d2 = sbl__sub(sbl__load(W->row[2] + ix), y2);
    /* t: the first valid pair's difference; the top pair's own term v0 (d0 - t) is then
       0 (d0 = t where valid, v0 = 0 elsewhere) and left out */
    /* full: every pair of the three rows valid (v = 1 exactly): the same values */
    const sbl__v t = full ? d0 : sbl__sel(ok0, d0, sbl__sel(ok1, d1, d2));
    const sbl__v e1 = full ? sbl__sub(d1, t) : sbl__mul(v1, sbl__sub(d1, t));
    const sbl__v e2 = full ? sbl__sub(d2, t) : sbl__mul(v2, sbl__sub(d2, t));
    float *cp = k->col[0] + i + SBL__CHUNK_COL(c);
    sbl__store(SBL__COLP(cp, SBL__COL_A), sbl__add(a1, a2));
    sbl__store(SBL__COLP(cp, SBL__COL_B), sbl__add(sbl__mul(a1, a1), sbl__mul(a2, a2)));
    sbl__store(SBL__COLP(cp, SBL__COL_T), t);
    sbl__store(SBL__COLP(cp, SBL__COL_DA), sbl__add(e1, e2));
    sbl__store(SBL__COLP(cp, SBL__COL_DB), sbl__add(sbl__mul(e1, e1), sbl__mul(e2, e2)));
    if (clamp) {
        sbl__store(SBL__COLP(cp, SBL__COL_LO), sbl__min(sbl__min(y0, y1), y2));
        sbl__store(SBL__COLP(cp, SBL__COL_HI), sbl__max(sbl__max(y0, y1), y2));
    }
}

/* Under -ffast-math (gcc, clang: __FAST_MATH__; MSVC /fp:fast: _M_FP_FAST), or gcc's
   -funsafe-math-optimizations / -fassociative-math alone (__ASSOCIATIVE_MATH__; clang
   defines no macro for those, so there they are not detected) the compiler
   may reassociate the same sums differently in two instances: the full chunks' code,
   which leaves out selects and products that are identities there, then rounds unlike
   the general code, and since a chunk (or a vector's window) can be full in one call's
   range and not in another's, a pixel's result would depend on the range
   (tests/test_paths.c test_spans: 144 pixels differed, 23 with the columns alone
   general). There the general code runs in every chunk. (With SBL_SHORTCUTS' bit 8.) */
#if defined(__FAST_MATH__) || defined(__ASSOCIATIVE_MATH__) || defined(_M_FP_FAST)
#define SBL__FULL_CHUNKS 0
#else
#define SBL__FULL_CHUNKS ((SBL_SHORTCUTS & 8) != 0)
#endif

/* Column sums of columns [ca, cb) (cb - ca >= VW) of the window rows W, stored at index
   column - base; the last vector overlaps the one before (same values). The channels are
   written out (k->ch is a constant in each instance of sbl__kernel_lanes_ch). fast (a
   constant, sbl__kernel_lanes_pooled's default configuration): no clamp box. */
SBL__INLINE void sbl__lanes_columns_cfg(sbl__kernel *k, const sbl__lane_rows *W, int ca, int cb,
                                        int base, const int fast, const int full, const int erow)
{
    const sbl__v zero = sbl__set1(0.0f);
    const int ch = k->ch, clamp = !fast && k->wp.rectify == SBL_RECTIFY_CLAMP;
    int x = ca;
    for (;;) {
        const int i = x - base;
        const ptrdiff_t iv = x + W->off_v;
        /* full: every v is 1, so the pairs per column are 3 (the same value) */
        const sbl__v v0 = full ? sbl__set1(1.0f) : sbl__load(W->row[0] + iv);
        const sbl__v v1 = full ? sbl__set1(1.0f) : sbl__load(W->row[1] + iv);
        const sbl__v v2 = full ? sbl__set1(1.0f) : sbl__load(W->row[2] + iv);
        const sbl__m ok0 = sbl__gt(v0, zero), ok1 = sbl__gt(v1, zero);
        /* erow (a constant: the image's first or last row, k->edge_row): the window's
           missing row is row 1 again (first) or row 0 again (last), whose sums then
           add 0 (differences to itself, sbl__kernel_lanes_pooled_ch); its pairs are
           not counted */
        sbl__store(k->col[0] + i + SBL__CHUNK_COLN(ch),
                   full ? sbl__set1(3.0f)
                        : erow ? sbl__add(v1, k->edge_row == 1 ? v2 : v0) : sbl__add(sbl__add(v0, v1), v2));
        sbl__lanes_column(k, W, x, i, 0, v1, v2, ok0, ok1, clamp, full);
        if (ch > 1) sbl__lanes_column(k, W, x, i, 1, v1, v2, ok0, ok1, clamp, full);
        if (ch > 2) sbl__lanes_column(k, W, x, i, 2, v1, v2, ok0, ok1, clamp, full);
        if (ch > 3) sbl__lanes_column(k, W, x, i, 3, v1, v2, ok0, ok1, clamp, full);
        if (x + SBL__VW >= cb) break;
        x += SBL__VW;
        if (x + SBL__VW > cb) x = cb - SBL__VW;
    }
}

/* 1 if every pair of columns [ca, cb) (cb - ca >= VW) of the window rows is valid (v is
   0 or 1: its minimum over the three rows is 1 on every lane). Such a chunk (the usual
   case) takes instances in which the selects on the pair validity and the products by
   v fall away: the same values. */
SBL__INLINE int sbl__lanes_full(const sbl__lane_rows *W, int ca, int cb)
{
    sbl__v m = sbl__set1(1.0f);
    int x = ca;
    for (;;) {
        const ptrdiff_t iv = x + W->off_v;
        m = sbl__min(m, sbl__min(sbl__min(sbl__load(W->row[0] + iv), sbl__load(W->row[1] + iv)),
                                 sbl__load(W->row[2] + iv)));
        if (x + SBL__VW >= cb) break;
        x += SBL__VW;
        if (x + SBL__VW > cb) x = cb - SBL__VW;
    }
    return sbl__all(sbl__gt(m, sbl__set1(0.5f)));
}

SBL__INLINE void sbl__lanes_columns(sbl__kernel *k, const sbl__lane_rows *W, int ca, int cb,
                                    int base)
{
    sbl__lanes_columns_cfg(k, W, ca, cb, base, 0, 0, 0);
}

/* One side column moved from its own shift to the window's: D = its shift minus the
   window's, n its count; sum (e + D) = a + n D, sum (e + D)^2 = b + D (a + (a + n D)) */
#define SBL__SIDE(A, B, D, N, OA, OB) \
    do { \
        (OA) = sbl__add((A), sbl__mul((D), (N))); \
        (OB) = sbl__add((B), sbl__mul((D), sbl__add((A), (OA)))); \
    } while (0)

/* A vector of pixels holding one of the image's border columns, or on the image's first
   or last row (the default configurations' lanes, sbl__kernel_lanes_pooled_ch): per
   lane, whether the side columns exist, their samples (3, 2 on a border row, 0 outside
   the image), and the window's count n (9 inside; 6 on a border column or row; 4 at a
   corner) as 1 / n, 1 / (n - 1), n / (n - 1) and (n - 1) / (n - 2) (the lean's). A lane
   inside the image holds the constants of the interior vectors, so it gets their bits. */
typedef struct sbl__lane_edge {
    sbl__m keep_l, keep_r;
    sbl__v n_l, n_r, inv_n, inv_n8, bessel, lean_s;
} sbl__lane_edge;

/* Channel c of Y's moments of pixels [x, x + VW) (index i in the chunk): mean and
   population variance of the window, of the window without its centre, the centre.
   E: NULL inside the image, else the vector's border lanes (sbl__lane_edge): a missing
   side column enters as an empty one (sums 0, count 0, shift 0), whatever its memory
   holds. */
SBL__INLINE void sbl__lanes_y_channel(const sbl__kernel *k, const sbl__lane_rows *W, int x, int i,
                                      int c, sbl__v *mean, sbl__v *var, sbl__v *m8, sbl__v *v8,
                                      sbl__v *yc_out, const int v8_times8, const sbl__lane_edge *E)
{
    const sbl__v zero = sbl__set1(0.0f), three = sbl__set1(3.0f);
    const sbl__v ninth = sbl__set1(1.0f / 9.0f), eighth = sbl__set1(0.125f);
    const float *y0 = W->y[0][c] + x;
    const sbl__v s = sbl__load(y0); /* the window's shift: its top-centre sample */
    const sbl__v yc = sbl__load(W->y[1][c] + x);
    const sbl__v a1 = sbl__sub(yc, s), a2 = sbl__sub(sbl__load(W->y[2][c] + x), s);
    const float *cp = k->col[0] + i + SBL__CHUNK_COL(c);
    sbl__v dl = sbl__sub(sbl__load(y0 - 1), s), dr = sbl__sub(sbl__load(y0 + 1), s);
    sbl__v sal = sbl__load(SBL__COLP(cp, SBL__COL_A) - 1), sbl_ = sbl__load(SBL__COLP(cp, SBL__COL_B) - 1);
    sbl__v sar = sbl__load(SBL__COLP(cp, SBL__COL_A) + 1), sbr = sbl__load(SBL__COLP(cp, SBL__COL_B) + 1);
    sbl__v al, bl, ar, br, a8, b8, a9, b9, q;
    if (E) {
        dl = sbl__sel(E->keep_l, dl, zero);
        sal = sbl__sel(E->keep_l, sal, zero);
        sbl_ = sbl__sel(E->keep_l, sbl_, zero);
        dr = sbl__sel(E->keep_r, dr, zero);
        sar = sbl__sel(E->keep_r, sar, zero);
        sbr = sbl__sel(E->keep_r, sbr, zero);
    }
    /* side columns about s (their top sample is s + D, counted by n = 3) */
    SBL__SIDE(sal, sbl_, dl, E ? E->n_l : three, al, bl);
    SBL__SIDE(sar, sbr, dr, E ? E->n_r : three, ar, br);
    a8 = sbl__add(sbl__add(al, ar), a2);
    b8 = sbl__add(sbl__add(bl, br), sbl__mul(a2, a2));
    a9 = sbl__add(a8, a1);
    b9 = sbl__add(b8, sbl__mul(a1, a1));
    q = sbl__mul(a9, E ? E->inv_n : ninth);
    *mean = sbl__add(s, q);
    *var = sbl__mul(sbl__max(sbl__sub(b9, sbl__mul(a9, q)), zero), E ? E->inv_n : ninth);
    q = sbl__mul(a8, E ? E->inv_n8 : eighth);
    *m8 = sbl__add(s, q);
    *v8 = sbl__max(sbl__sub(b8, sbl__mul(a8, q)), zero);
    /* v8_times8 (a constant): left as 8 v8, for a caller that scales a sum of them (a
       power of two: the same bits as summing the scaled values; E: the caller scales
       by E->inv_n8) */
    if (!v8_times8) *v8 = sbl__mul(*v8, E ? E->inv_n8 : eighth);
    *yc_out = yc;
}

/* Channel c of the moments of pixels [x, x + VW) (index i in the chunk), for
   sbl__lanes_moments: nl / nr are the side columns' pair counts. */
SBL__INLINE void sbl__lanes_moments_channel(const sbl__kernel *k, const sbl__lane_rows *W, int x,
                                            int i, int c, sbl__v nl, sbl__v nr, sbl__v inv_cnt1,
                                            const sbl__v *inv_w, sbl__v *sw, sbl__lane_stats *st)
{
    const sbl__v zero = sbl__set1(0.0f);
    const float *cp = k->col[0] + i + SBL__CHUNK_COL(c);
    const sbl__v tc = sbl__load(SBL__COLP(cp, SBL__COL_T));
    const sbl__v da = sbl__load(SBL__COLP(cp, SBL__COL_DA)), db = sbl__load(SBL__COLP(cp, SBL__COL_DB));
    sbl__v pl, ql, pr, qr, d, dd;
    sbl__lanes_y_channel(k, W, x, i, c, &st->mean[c], &st->var[c], &st->m8[c], &st->v8[c],
                         &st->yc[c], 0, NULL);
    st->xs[c] = st->xr[c] = sbl__load(W->x[1][c] + x);
    /* pairs: side columns about the centre column's shift tc */
    SBL__SIDE(sbl__load(SBL__COLP(cp, SBL__COL_DA) - 1), sbl__load(SBL__COLP(cp, SBL__COL_DB) - 1),
              sbl__sub(sbl__load(SBL__COLP(cp, SBL__COL_T) - 1), tc), nl, pl, ql);
    SBL__SIDE(sbl__load(SBL__COLP(cp, SBL__COL_DA) + 1), sbl__load(SBL__COLP(cp, SBL__COL_DB) + 1),
              sbl__sub(sbl__load(SBL__COLP(cp, SBL__COL_T) + 1), tc), nr, pr, qr);
    d = sbl__add(sbl__add(pl, pr), da);
    dd = sbl__add(sbl__add(ql, qr), db);
    st->pd[c] = sbl__mul(d, st->inv_cnt);
    /* sample variance of the pairs: (sum d^2 - n mean^2) / (n - 1) */
    st->pv[c] = sbl__mul(sbl__max(sbl__sub(dd, sbl__mul(d, st->pd[c])), zero), inv_cnt1);
    if (inv_w) {
        /* pooled stereo: within the columns (sbl__pair_var_within, 4.16); inv_w: 1 / n_j
           of the columns -1, 0, +1, then 1 / (n - J); sbl__lanes_moments gates it */
        sbl__v a = sbl__load(SBL__COLP(cp, SBL__COL_DA) - 1), ssw, t[3];
        int j;
        t[0] = sbl__sub(sbl__load(SBL__COLP(cp, SBL__COL_DB) - 1), sbl__mul(sbl__mul(a, a), inv_w[0]));
        t[1] = sbl__sub(db, sbl__mul(sbl__mul(da, da), inv_w[1]));
        a = sbl__load(SBL__COLP(cp, SBL__COL_DA) + 1);
        t[2] = sbl__sub(sbl__load(SBL__COLP(cp, SBL__COL_DB) + 1), sbl__mul(sbl__mul(a, a), inv_w[2]));
        ssw = sbl__add(sbl__add(t[0], t[1]), t[2]);
        sw[c] = sbl__mul(sbl__max(ssw, zero), inv_w[3]);
        /* sw[4 + j]: the columns' sums of squares, summed over the channels */
        for (j = 0; j < 3; ++j) sw[4 + j] = c == 0 ? t[j] : sbl__add(sw[4 + j], t[j]);
    }
    st->pd[c] = sbl__sel(st->has_pairs, sbl__add(st->pd[c], tc), zero);
    if (k->wp.rectify == SBL_RECTIFY_CLAMP) {
        const float *lo = SBL__COLP(cp, SBL__COL_LO), *hi = SBL__COLP(cp, SBL__COL_HI);
        st->lo[c] = sbl__min(sbl__min(sbl__load(lo - 1), sbl__load(lo)), sbl__load(lo + 1));
        st->hi[c] = sbl__max(sbl__max(sbl__load(hi - 1), sbl__load(hi)), sbl__load(hi + 1));
    } else {
        st->lo[c] = st->hi[c] = st->mean[c];
    }
}

/* Moments of pixels [x, x + VW) from the column sums of the chunk starting at column
   ca (sbl__lanes_columns) and the window rows W (channels written out, as there). */
SBL__INLINE void sbl__lanes_moments(const sbl__kernel *k, const sbl__lane_rows *W, int x, int ca,
                                    sbl__lane_stats *st)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const int i = x - ca, ch = k->ch;
    const float *const qn = k->col[0] + i + SBL__CHUNK_COLN(ch); /* k->col_n + i */
    const sbl__v nl = sbl__load(qn - 1), nr = sbl__load(qn + 1);
    const sbl__v cnt = sbl__add(sbl__add(nl, sbl__load(qn)), nr);
    sbl__v inv_cnt1, inv_w[4], sw[7], J = zero, dof = zero, cn[3];
    const sbl__v *w = NULL;
    sw[0] = sw[1] = sw[2] = sw[3] = sw[4] = sw[5] = sw[6] = zero;
    cn[0] = nl;
    cn[1] = sbl__load(qn);
    cn[2] = nr;
    st->has_pairs = sbl__gt(cnt, zero);
    st->two_pairs = sbl__gt(cnt, one);
    st->inv_cnt = sbl__div(one, sbl__max(cnt, one));
    inv_cnt1 = sbl__div(one, sbl__max(sbl__sub(cnt, one), one));
    if (k->wp.estimator == SBL_ESTIMATOR_POOLED && !k->temporal) {
        /* pooled stereo: the columns' counts for the pairs' variance within them (4.16) */
        const sbl__v nc = sbl__load(qn);
        J = sbl__add(sbl__add(sbl__sel(sbl__gt(nl, zero), one, zero), sbl__sel(sbl__gt(nc, zero), one, zero)),
                     sbl__sel(sbl__gt(nr, zero), one, zero));
        dof = sbl__sub(cnt, J);
        inv_w[0] = sbl__div(one, sbl__max(nl, one));
        inv_w[1] = sbl__div(one, sbl__max(nc, one));
        inv_w[2] = sbl__div(one, sbl__max(nr, one));
        inv_w[3] = sbl__sel(sbl__gt(dof, one), sbl__div(one, sbl__max(dof, one)), zero);
        w = inv_w;
    }
    sbl__lanes_moments_channel(k, W, x, i, 0, nl, nr, inv_cnt1, w, sw, st);
    if (ch > 1) sbl__lanes_moments_channel(k, W, x, i, 1, nl, nr, inv_cnt1, w, sw, st);
    if (ch > 2) sbl__lanes_moments_channel(k, W, x, i, 2, nl, nr, inv_cnt1, w, sw, st);
    if (ch > 3) sbl__lanes_moments_channel(k, W, x, i, 3, nl, nr, inv_cnt1, w, sw, st);
    if (w) {
        /* the gate on the channel sums (sbl__pair_var_within) */
        sbl__v pvs = st->pv[0], sws = sw[0];
        sbl__m gate;
        int c;
        for (c = 1; c < ch; ++c) {
            pvs = sbl__add(pvs, st->pv[c]);
            sws = sbl__add(sws, sw[c]);
        }
        gate = sbl__fgate_lanes(cn, sw + 4, J, dof, inv_cnt1, sbl__set1(sbl__fgate_k2(k)), sws, pvs, ch);
        for (c = 0; c < ch; ++c) st->pv[c] = sbl__sel(gate, sw[c], st->pv[c]);
    }
}
#undef SBL__SIDE

/* Pooled estimator: the prior variance of the bias of pixels [x, x + VW) of row y, as
   sbl__pool_ratio (computed for the row by sbl__row_pool). */
SBL__INLINE void sbl__lanes_pool(const sbl__kernel *k, int x, int y, sbl__lane_stats *st)
{
    st->tail_t = k->wp.tail ? sbl__load(k->tail_t + x) : sbl__set1(0.0f);
    st->pool_r = (k->wp.estimator == SBL_ESTIMATOR_POOLED && k->pool_row == y)
                   ? sbl__load(k->pool_r + x) : sbl__set1(0.0f);
    st->evid_sh = (SBL_EVIDENCE_MIX && k->wp.evid_mix && k->pool_row == y)
                    ? sbl__evidence_shrink_lanes(k, x) : sbl__set1(0.0f);
    st->sev = k->wp.stereo_ev ? sbl__load(k->sev + x) : sbl__set1(0.0f);
}

/* ---- the pooled estimator's prepass in lanes (sbl__row_pool) -----------------
   The same statistic as sbl__row_pool_ref, in float, a chunk of SBL__POOL_CHUNK pixels
   at a time through three passes over planes of k->pool_col: column sums, blocks,
   ratios. Precision as the lane kernel's moments: every one-pass sum is taken about a
   sample of the set summed. A column sums v (d - t) and its square about t, its first
   valid pair's d (the top pair's own term is then 0 and left out); a block moves its
   three columns to one shift s, its centre column's t (or, if that column has no pair,
   its left or else its right one's: a shift taken from an empty column would be an
   unrelated value), with sum (e + D)^2 = sum e^2 + D (2 sum e + n D). Then
   n (mean - s)^2 <= n^2 var and 1e4 + noise keeps its variance. Lanes are independent
   and each column, block and ratio is computed by the same operations whatever the
   chunk, span or vector width. Values outside the lane range (unsafe, flagged at load:
   non-finite, extreme or denormal) would overflow or underflow the float energies:
   every pixel with an unsafe value within SBL__POOL_REACH columns of it, on the three
   rows, is computed by sbl__row_pool_ref instead; so are rows narrower than 18 (the
   lane kernel's rule), on every build. */

/* the planes of k->pool_col: per channel c the column sums A (sum v (d - t)), B (sum of
   its square) and T (t); then N (pairs per column), and per block centre M2 and SE2
   (sum_c mean_c^2, sum_c var_c / n; 0 for no block), and PD2 / PV (sum_c mean_c^2 and
   sum_c var_c whatever the count: the lane kernel's pair terms, sbl__kernel_lanes_pooled) */
#define SBL__POOL_A(c) (3 * (c))
#define SBL__POOL_B(c) (3 * (c) + 1)
#define SBL__POOL_T(c) (3 * (c) + 2)
#define SBL__POOL_N(ch) (3 * (ch))
#define SBL__POOL_M2(ch) (3 * (ch) + 1)
#define SBL__POOL_SE2(ch) (3 * (ch) + 2)
#define SBL__POOL_PD2(ch) (3 * (ch) + 3)
#define SBL__POOL_PV(ch) (3 * (ch) + 4)
#define SBL__POOL_FT(ch) (3 * (ch) + 5) /* staged lanes: the firefly factor t (sbl__lanes_stage_y) */
#define SBL__POOL_S2(ch) (3 * (ch) + 6) /* staged lanes: Y's variance summed over the channels */
#define SBL__POOL_W(ch) (3 * (ch) + 7) /* staged lanes: the weight (sbl__lanes_stage_weight) */
#define SBL__POOL_DEV2(ch) (3 * (ch) + 8) /* staged lanes: |x* - mean|^2 (SBL_EVIDENCE_MIX only) */
#define SBL__POOL_BB(ch) (3 * (ch) + 9) /* staged lanes: the blur's sum_c b_c^2 (wp.blur only) */
#define SBL__POOL_BG(ch) (3 * (ch) + 10) /* staged lanes: the blur's noise factor (wp.blur only) */
#define SBL__POOL_SW(ch) (3 * (ch) + 11) /* pooled stereo: a column's within sum of squares (4.16) */
#define SBL__POOL_VMX(ch) (3 * (ch) + 12) /* pooled stereo: a column's sbl__fgate_column terms */
#define SBL__POOL_VMN(ch) (3 * (ch) + 13)
/* staged lanes with the restart lean (wp.lean_restart only; sbl__lanes_stage_y): the
   neighbours' mean of channel c, their variance summed over the channels; the weight
   before the lean (Eq. 5's, sbl__lanes_stage_weight) */
#define SBL__POOL_LM8(ch, c) (3 * (ch) + 14 + (c))
#define SBL__POOL_LV8(ch) (3 * (ch) + 18)
#define SBL__POOL_A2(ch) (3 * (ch) + 19)
#define SBL__POOL_PLANE(k, plane) ((k)->pool_col + (plane) * SBL__POOL_COLS)

/* The ring rows that exist (the image's first and last rows have fewer than three) */
typedef struct sbl__pool_rows {
    const float *y[3][4], *x[3][4], *v[3];
    const unsigned char *unsafe[3]; /* the ring rows' flags (sbl__pool_pixel_unsafe) */
    int n, ch;
} sbl__pool_rows;

/* Column sums of columns [ca, cb) (inside the image, cb - ca >= VW) of the np rows P,
   stored at index column - base; the last vector overlaps the one before. One channel
   at a time (a small loop body: the planes stay in registers). */
SBL__INLINE void sbl__pool_lanes_columns(sbl__kernel *k, const sbl__pool_rows *P, const int np,
                                         const int ch, int ca, int cb, int base)
{
    const sbl__v zero = sbl__set1(0.0f);
    float *const pool = k->pool_col;
    int x, c, j;
    for (x = ca;;) {
        sbl__v n = sbl__load(P->v[0] + x);
        for (j = 1; j < np; ++j) n = sbl__add(n, sbl__load(P->v[j] + x));
        sbl__store(pool + SBL__POOL_N(ch) * SBL__POOL_COLS + (x - base), n);
        if (x + SBL__VW >= cb) break;
        x += SBL__VW;
        if (x + SBL__VW > cb) x = cb - SBL__VW;
    }
    for (c = 0; c < ch; ++c) {
        float *const pa = pool + SBL__POOL_A(c) * SBL__POOL_COLS;
        float *const pb = pool + SBL__POOL_B(c) * SBL__POOL_COLS;
        float *const pt = pool + SBL__POOL_T(c) * SBL__POOL_COLS;
        if (np == 3) {
            const float *const v0 = P->v[0], *const v1 = P->v[1], *const v2 = P->v[2];
            const float *const y0 = P->y[0][c], *const y1 = P->y[1][c], *const y2 = P->y[2][c];
            const float *const x0 = P->x[0][c], *const x1 = P->x[1][c], *const x2 = P->x[2][c];
            for (x = ca;;) {
                const sbl__v w1 = sbl__load(v1 + x), w2 = sbl__load(v2 + x);
                const sbl__v d0 = sbl__sub(sbl__load(x0 + x), sbl__load(y0 + x)),
                             d1 = sbl__sub(sbl__load(x1 + x), sbl__load(y1 + x)),
                             d2 = sbl__sub(sbl__load(x2 + x), sbl__load(y2 + x));
                /* t: the first valid pair's d; the top pair's own term is then 0 */
                const sbl__v t = sbl__sel(sbl__gt(sbl__load(v0 + x), zero), d0,
                                          sbl__sel(sbl__gt(w1, zero), d1, d2));
                const sbl__v e1 = sbl__mul(w1, sbl__sub(d1, t)), e2 = sbl__mul(w2, sbl__sub(d2, t));
                sbl__store(pa + (x - base), sbl__add(e1, e2));
                sbl__store(pb + (x - base), sbl__add(sbl__mul(e1, e1), sbl__mul(e2, e2)));
                sbl__store(pt + (x - base), t);
                if (x + SBL__VW >= cb) break;
                x += SBL__VW;
                if (x + SBL__VW > cb) x = cb - SBL__VW;
            }
        } else {
            /* the image's first or last row (or a one-row image): the same, over np rows */
            for (x = ca;;) {
                sbl__v d[3], v[3], t, a = zero, b = zero;
                for (j = 0; j < np; ++j) {
                    v[j] = sbl__load(P->v[j] + x);
                    d[j] = sbl__sub(sbl__load(P->x[j][c] + x), sbl__load(P->y[j][c] + x));
                }
                t = d[np - 1];
                for (j = np - 2; j >= 0; --j) t = sbl__sel(sbl__gt(v[j], zero), d[j], t);
                for (j = 1; j < np; ++j) {
                    const sbl__v e = sbl__mul(v[j], sbl__sub(d[j], t));
                    a = j == 1 ? e : sbl__add(a, e);
                    b = j == 1 ? sbl__mul(e, e) : sbl__add(b, sbl__mul(e, e));
                }
                sbl__store(pa + (x - base), a);
                sbl__store(pb + (x - base), b);
                sbl__store(pt + (x - base), t);
                if (x + SBL__VW >= cb) break;
                x += SBL__VW;
                if (x + SBL__VW > cb) x = cb - SBL__VW;
            }
        }
    }
}

/* Where the blocks read their column sums: the prepass's own planes (pool_col), or the
   lane kernel's column sums (k->col, col_n), which hold the same values on an interior
   row (sbl__kernel_lanes_pooled). */
typedef struct sbl__pool_planes {
    float *a[4], *b[4], *t[4], *n;
    ptrdiff_t cstep; /* a[c] - a[0] = c cstep, and so for b and t */
} sbl__pool_planes;

/* own = 1: the prepass's planes; 0: the lane kernel's (per channel one block of
   SBL__COL_PLANES planes, the blocks consecutive: sbl__kernel_bind) */
SBL__INLINE void sbl__pool_planes_of(const sbl__kernel *k, int ch, int own, sbl__pool_planes *Q)
{
    int c;
    Q->cstep = own ? 3 * SBL__POOL_COLS : SBL__COL_PLANES * SBL__CHUNK_COLS;
    for (c = 0; c < ch; ++c) {
        Q->a[c] = own ? SBL__POOL_PLANE(k, SBL__POOL_A(c)) : SBL__COLP(k->col[c], SBL__COL_DA);
        Q->b[c] = own ? SBL__POOL_PLANE(k, SBL__POOL_B(c)) : SBL__COLP(k->col[c], SBL__COL_DB);
        Q->t[c] = own ? SBL__POOL_PLANE(k, SBL__POOL_T(c)) : SBL__COLP(k->col[c], SBL__COL_T);
    }
    Q->n = own ? SBL__POOL_PLANE(k, SBL__POOL_N(ch)) : k->col_n;
}

/* A column outside the image: no pairs, sums 0 (at index column - base). */
static void sbl__pool_column_zero(const sbl__pool_planes *Q, int ch, int i)
{
    int c;
    Q->n[i] = 0.0f;
    for (c = 0; c < ch; ++c) Q->a[c][i] = Q->b[c][i] = Q->t[c][i] = 0.0f;
}

/* One column of a block moved from its own shift t to the block's s: D = t - s,
   sum (e + D) = a + n D, sum (e + D)^2 = b + D (a + (a + n D)) */
#define SBL__POOL_SHIFT(A, B, D, N, OA, OB) \
    do { \
        (OA) = sbl__add((A), sbl__mul((D), (N))); \
        (OB) = sbl__add((B), sbl__mul((D), sbl__add((A), (OA)))); \
    } while (0)

/* Channel c's terms of the blocks of sbl__pool_lanes_blocks at index i: the squared
   mean and the squared standard error, added to *m2 / *se2 (set by channel 0). */
SBL__INLINE void sbl__pool_block_channel(const float *pa, const float *pb, const float *pt,
                                         sbl__m has_c, sbl__m has_l, sbl__v nl, sbl__v nr,
                                         sbl__v inv_n, sbl__v inv_n1, int c, sbl__v *m2,
                                         sbl__v *se2, sbl__v *pv, const int full)
{
    const sbl__v zero = sbl__set1(0.0f);
    const sbl__v tl = sbl__load(pt - 1), tc = sbl__load(pt), tr = sbl__load(pt + 1);
    const sbl__v s = full ? tc : sbl__sel(has_c, tc, sbl__sel(has_l, tl, tr));
    sbl__v al, bl, ar, br, a, b, q, mean, var;
    /* the centre column needs no move: s is its t, or it has no pair (sums 0) */
    SBL__POOL_SHIFT(sbl__load(pa - 1), sbl__load(pb - 1), sbl__sub(tl, s), nl, al, bl);
    SBL__POOL_SHIFT(sbl__load(pa + 1), sbl__load(pb + 1), sbl__sub(tr, s), nr, ar, br);
    a = sbl__add(sbl__add(al, sbl__load(pa)), ar);
    b = sbl__add(sbl__add(bl, sbl__load(pb)), br);
    q = sbl__mul(a, inv_n);
    mean = sbl__add(s, q);
    /* sample variance (sum e^2 - n mean_e^2) / (n - 1), over n for its mean */
    var = sbl__mul(sbl__max(sbl__sub(b, sbl__mul(a, q)), zero), inv_n1);
    if (c == 0) {
        *m2 = sbl__mul(mean, mean);
        *se2 = sbl__mul(var, inv_n);
        *pv = var;
    } else {
        *m2 = sbl__add(*m2, sbl__mul(mean, mean));
        *se2 = sbl__add(*se2, sbl__mul(var, inv_n));
        *pv = sbl__add(*pv, var);
    }
}

/* 1 if the columns at qn[-1 .. VW] (a plane of pairs per column) hold three pairs each:
   the blocks or windows of the VW columns at qn hold only valid pairs */
SBL__INLINE int sbl__cols_three_pairs(const float *qn)
{
    return sbl__all(sbl__gt(sbl__min(sbl__min(sbl__load(qn - 1), sbl__load(qn)), sbl__load(qn + 1)),
                            sbl__set1(2.5f)));
}

/* The blocks centred on the column vector at q (its index in every plane, from
   k->col[0]), for sbl__pool_lanes_blocks (which see). */
SBL__INLINE void sbl__pool_block_vec(float *q, const int ch, const int own, const int pairs,
                                     sbl__v k2, sbl__v h_full, const int full)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), min_pairs = sbl__set1(2.5f);
    /* offsets from k->col[0] (floats): the column sums, then the prepass's planes */
    const ptrdiff_t coln = SBL__CAST(ptrdiff_t, ch) * SBL__COL_PLANES * SBL__CHUNK_COLS;
    const ptrdiff_t pool = coln + SBL__CHUNK_COLS;
    const ptrdiff_t o_n = own ? pool + SBL__POOL_N(ch) * SBL__POOL_COLS : coln;
    const ptrdiff_t o_a = own ? pool + SBL__POOL_A(0) * SBL__POOL_COLS : SBL__COL_DA * SBL__CHUNK_COLS;
    const ptrdiff_t o_b = own ? pool + SBL__POOL_B(0) * SBL__POOL_COLS : SBL__COL_DB * SBL__CHUNK_COLS;
    const ptrdiff_t o_t = own ? pool + SBL__POOL_T(0) * SBL__POOL_COLS : SBL__COL_T * SBL__CHUNK_COLS;
    const ptrdiff_t cstep = own ? 3 * SBL__POOL_COLS : SBL__COL_PLANES * SBL__CHUNK_COLS;
    const ptrdiff_t o_m2 = pool + SBL__POOL_M2(ch) * SBL__POOL_COLS, o_se2 = pool + SBL__POOL_SE2(ch) * SBL__POOL_COLS;
    const ptrdiff_t o_pd2 = pool + SBL__POOL_PD2(ch) * SBL__POOL_COLS, o_pv = pool + SBL__POOL_PV(ch) * SBL__POOL_COLS;
    const ptrdiff_t o_sw = pool + SBL__POOL_SW(ch) * SBL__POOL_COLS;
    const ptrdiff_t o_vmx = pool + SBL__POOL_VMX(ch) * SBL__POOL_COLS, o_vmn = pool + SBL__POOL_VMN(ch) * SBL__POOL_COLS;
    /* full: three pairs in each column, nine in the block (the same values) */
    const sbl__v nl = full ? sbl__set1(3.0f) : sbl__load(q + o_n - 1);
    const sbl__v nc = full ? sbl__set1(3.0f) : sbl__load(q + o_n);
    const sbl__v nr = full ? sbl__set1(3.0f) : sbl__load(q + o_n + 1);
    const sbl__v n = full ? sbl__set1(9.0f) : sbl__add(sbl__add(nl, nc), nr);
    /* full (sbl__lanes_full): every column holds three pairs */
    const sbl__m has_c = full ? sbl__true : sbl__gt(nc, zero);
    const sbl__m has_l = full ? sbl__true : sbl__gt(nl, zero);
    const sbl__m valid = full ? sbl__true : sbl__gt(n, min_pairs);
    const sbl__v inv_n = sbl__div(one, sbl__max(n, one));
    const sbl__v inv_n1 = sbl__div(one, sbl__max(sbl__sub(n, one), one));
    sbl__v m2 = zero, se2 = zero, pv = zero;
#define SBL__POOL_BLOCK_CH(c) \
    sbl__pool_block_channel(q + o_a + (c) * cstep, q + o_b + (c) * cstep, q + o_t + (c) * cstep, \
                            has_c, has_l, nl, nr, inv_n, inv_n1, c, &m2, &se2, &pv, full)
    SBL__POOL_BLOCK_CH(0);
    if (ch > 1) SBL__POOL_BLOCK_CH(1);
    if (ch > 2) SBL__POOL_BLOCK_CH(2);
    if (ch > 3) SBL__POOL_BLOCK_CH(3);
#undef SBL__POOL_BLOCK_CH
    sbl__store(q + o_m2, full ? m2 : sbl__sel(valid, m2, zero));
    sbl__store(q + o_se2, full ? se2 : sbl__sel(valid, se2, zero));
    if (pairs == 2) {
        /* the stereo blend: the pairs' variance within the columns where they differ
           (sbl__pair_var_within, 4.16): SS_W = the three columns' terms, on n - J */
        const sbl__v ssw = sbl__add(sbl__add(sbl__load(q + o_sw - 1), sbl__load(q + o_sw)), sbl__load(q + o_sw + 1));
        if (full) {
            /* the columns' own variances: their sums of squares (2 degrees of freedom each) */
            const sbl__v wl = sbl__load(q + o_sw - 1), wc = sbl__load(q + o_sw), wr = sbl__load(q + o_sw + 1);
            const sbl__v sw = sbl__mul(sbl__max(ssw, zero), sbl__set1(1.0f / 6.0f));
            const sbl__m one_var = sbl__fgate_one_var(sbl__max(sbl__max(wl, wc), wr), sbl__min(sbl__min(wl, wc), wr), ch);
            pv = sbl__sel(sbl__gt(pv, sbl__mul(h_full, sw)), sbl__sel(one_var, sw, pv), pv);
        } else {
            const sbl__v J = sbl__add(sbl__add(sbl__sel(has_l, one, zero), sbl__sel(has_c, one, zero)),
                                      sbl__sel(sbl__gt(nr, zero), one, zero));
            const sbl__v dof = sbl__sub(n, J);
            const sbl__v sw = sbl__mul(sbl__max(ssw, zero), sbl__div(one, sbl__max(dof, one)));
            sbl__v vmx[3], vmn[3];
            int j;
            for (j = 0; j < 3; ++j) {
                vmx[j] = sbl__load(q + o_vmx + j - 1);
                vmn[j] = sbl__load(q + o_vmn + j - 1);
            }
            pv = sbl__sel(sbl__fgate_cols(vmx, vmn, J, dof, inv_n1, k2, sw, pv, ch), sw, pv);
        }
    }
    if (pairs) {
        sbl__store(q + o_pd2, m2);
        sbl__store(q + o_pv, pv);
    }
}

/* Blocks centred on columns [ba, bb) (inside the image, bb - ba >= VW), from the column
   sums at index column - base: M2 and SE2, 0 where the block has fewer than 3 pairs.
   The channels written out (ch is a constant in each instance), in channel order.
   own (a constant): the column sums are the prepass's planes (1) or the lane kernel's
   (0, sbl__pool_planes_of). pairs = 1 (the lane kernel's column sums): also PD2 and PV,
   whatever the count. Every plane is read at a constant distance from one pointer
   (sbl__kernel_bind lays the chunk's planes out in one block: k->col[0..ch), col_n,
   pool_col), which moves with the column: one register for all, so the loop does not
   reload a dozen plane pointers from the stack on each vector. vfull (a constant; not
   with full): in a chunk that is not full, a vector whose blocks' columns all hold three
   pairs takes full's operations (the same values). */
SBL__INLINE void sbl__pool_lanes_blocks(sbl__kernel *k, const sbl__pool_planes *Q, const int ch,
                                        int ba, int bb, int base, const int own, const int pairs,
                                        const int full, const int vfull)
{
    const sbl__v one = sbl__set1(1.0f);
    /* offsets from k->col[0] (floats), as sbl__pool_block_vec's: the pairs per column,
       the channels' column sums, the stereo gate's column planes */
    const ptrdiff_t coln = SBL__CAST(ptrdiff_t, ch) * SBL__COL_PLANES * SBL__CHUNK_COLS;
    const ptrdiff_t pool = coln + SBL__CHUNK_COLS;
    const ptrdiff_t o_n = own ? pool + SBL__POOL_N(ch) * SBL__POOL_COLS : coln;
    const ptrdiff_t o_a = own ? pool + SBL__POOL_A(0) * SBL__POOL_COLS : SBL__COL_DA * SBL__CHUNK_COLS;
    const ptrdiff_t o_b = own ? pool + SBL__POOL_B(0) * SBL__POOL_COLS : SBL__COL_DB * SBL__CHUNK_COLS;
    const ptrdiff_t cstep = own ? 3 * SBL__POOL_COLS : SBL__COL_PLANES * SBL__CHUNK_COLS;
    const ptrdiff_t o_sw = pool + SBL__POOL_SW(ch) * SBL__POOL_COLS;
    const ptrdiff_t o_vmx = pool + SBL__POOL_VMX(ch) * SBL__POOL_COLS, o_vmn = pool + SBL__POOL_VMN(ch) * SBL__POOL_COLS;
    /* the stereo blend's gate (sbl__pair_var_within): k^2, and H of a full window */
    const sbl__v k2 = sbl__set1(pairs == 2 ? sbl__fgate_k2(k) : 0.0f);
    const sbl__v h_full = sbl__mul(sbl__add(sbl__set1(6.0f), k2), sbl__set1(0.125f));
    float *const col0 = k->col[0];
    int x = ba;
    (void)Q;
    if (pairs == 2) {
        /* the stereo blend (4.16): each column's sum of squares within it, summed over the
           channels, sum_c (B_jc - A_jc^2 / n_j) (its sums are about its own shift t_j,
           which the spread within it does not see), once per column: each serves three
           blocks. Columns [ba - 1, bb + 1). */
        const sbl__v third = sbl__set1(1.0f / 3.0f);
        int xc = ba - 1;
        for (;;) {
            float *const q = col0 + (xc - base);
            const sbl__v inv = full ? third : sbl__div(one, sbl__max(sbl__load(q + o_n), one));
            sbl__v a = sbl__load(q + o_a), ssw = sbl__sub(sbl__load(q + o_b), sbl__mul(sbl__mul(a, a), inv));
            int c;
            for (c = 1; c < ch; ++c) {
                a = sbl__load(q + o_a + c * cstep);
                ssw = sbl__add(ssw, sbl__sub(sbl__load(q + o_b + c * cstep), sbl__mul(sbl__mul(a, a), inv)));
            }
            sbl__store(q + o_sw, ssw);
            if (!full) {
                /* the column's own variance for the blocks' gate, once per column (a full
                   block's columns have 3 pairs each: it reads ssw) */
                sbl__v vmx, vmn;
                sbl__fgate_column(sbl__load(q + o_n), ssw, &vmx, &vmn);
                sbl__store(q + o_vmx, vmx);
                sbl__store(q + o_vmn, vmn);
            }
            if (xc + SBL__VW >= bb + 1) break;
            xc += SBL__VW;
            if (xc + SBL__VW > bb + 1) xc = bb + 1 - SBL__VW;
        }
    }
    for (;;) {
        float *const q = col0 + (x - base); /* the column's index in every plane */
        /* vfull: a vector whose blocks' columns all hold three pairs */
        if (vfull && sbl__cols_three_pairs(q + o_n))
            sbl__pool_block_vec(q, ch, own, pairs, k2, h_full, 1);
        else
            sbl__pool_block_vec(q, ch, own, pairs, k2, h_full, full);
        if (x + SBL__VW >= bb) break;
        x += SBL__VW;
        if (x + SBL__VW > bb) x = bb - SBL__VW;
    }
}
#undef SBL__POOL_SHIFT

/* Ratios of pixels [xa, xb) (xb - xa >= VW) from the blocks at index column - base, as
   sbl__row_pool_ref: pooled squared mean over pooled squared standard error, less the
   threshold, in [0, cap]; no noise at all and a mean: the cap. */
SBL__INLINE void sbl__pool_lanes_ratio_cfg(sbl__kernel *k, const int ch, int xa, int xb, int base,
                                           const int evid)
{
    const sbl__v zero = sbl__set1(0.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v cap = sbl__set1(SBL__CAST(float, SBL__POOL_RATIO_CAP));
    const sbl__v thr = sbl__set1(SBL__CAST(float, SBL__POOL_THR(k)));
    const float *pm = SBL__POOL_PLANE(k, SBL__POOL_M2(ch)), *ps = SBL__POOL_PLANE(k, SBL__POOL_SE2(ch));
    int x = xa, b;
    for (;;) {
        const int i = x - base - SBL__POOL_STEP * SBL__POOL_BLOCKS;
        sbl__v sm2 = sbl__load(pm + i), sse2 = sbl__load(ps + i), r;
#if SBL__POOL_BLOCKS == 2 && SBL__POOL_STEP == 3
        /* written out (the same additions in the same order as the loop) */
        sm2 = sbl__add(sbl__add(sbl__add(sbl__add(sm2, sbl__load(pm + i + 3)), sbl__load(pm + i + 6)),
                                sbl__load(pm + i + 9)), sbl__load(pm + i + 12));
        sse2 = sbl__add(sbl__add(sbl__add(sbl__add(sse2, sbl__load(ps + i + 3)), sbl__load(ps + i + 6)),
                                 sbl__load(ps + i + 9)), sbl__load(ps + i + 12));
        (void)b;
#else
        for (b = 1; b <= 2 * SBL__POOL_BLOCKS; ++b) {
            sm2 = sbl__add(sm2, sbl__load(pm + i + SBL__POOL_STEP * b));
            sse2 = sbl__add(sse2, sbl__load(ps + i + SBL__POOL_STEP * b));
        }
#endif
        if (k->wp.tail) /* as sbl__row_pool_ref_ch (2.4) */
            sse2 = sbl__max(sse2, sbl__mul(sbl__load(k->tail_t + x),
                                           sbl__set1(SBL__CAST(float, 2 * SBL__POOL_BLOCKS + 1) / 9.0f)));
        r = sbl__sub(sbl__div(sm2, sbl__max(sse2, tiny)), thr);
        r = sbl__sel(sbl__gt(sse2, zero), r, sbl__sel(sbl__gt(sm2, zero), cap, zero));
        if (evid) r = sbl__evidence_ratio_lanes(k, x, sm2, sse2, r);
        sbl__store(k->pool_r + x, sbl__max(sbl__min(r, cap), zero));
        if (x + SBL__VW >= xb) break;
        x += SBL__VW;
        if (x + SBL__VW > xb) x = xb - SBL__VW;
    }
}

/* evid (a constant of each loop): k->evid_out, tested once per call, not per vector */
SBL__INLINE void sbl__pool_lanes_ratio(sbl__kernel *k, const int ch, int xa, int xb, int base)
{
    if (k->evid_out) sbl__pool_lanes_ratio_cfg(k, ch, xa, xb, base, 1);
    else sbl__pool_lanes_ratio_cfg(k, ch, xa, xb, base, 0);
}

/* Pixel x of pool row j, flagged unsafe at load (a value outside the lane range): 1 if
   the prepass's lanes cannot take it either. They read a pixel only through its pairs'
   differences d = x* - y (in float, as the lanes form them), so what their precision
   needs (see sbl__lane_value_ok) is that every valid pair's d be 0 or within
   [2^-40, 2^50): then, as for two lane-range values, every d lies on the 2^-63 grid
   below 2^51, and the sums, squares and shifts of d stay normal floats without
   overflow. An invalid pair's d is multiplied by 0 (or a select drops it), so y need
   only be finite and below 2^50 (the shifts stay finite). A dim value next to a bright
   history (1e-14 against 0.5: d = -0.5) is then no reason for the double path; a
   non-finite, huge or denormal d (both values dim) still is. A rule on the input alone,
   the same on every build. */
static int sbl__pool_pixel_unsafe(const sbl__pool_rows *P, int j, int x)
{
    const int valid = P->v[j][x] > 0.0f;
    int c;
    for (c = 0; c < P->ch; ++c) {
        const float y = P->y[j][c][x];
        unsigned int bits;
        memcpy(&bits, &y, sizeof bits);
        if ((bits & 0x7fffffffu) >= 0x58800000u) return 1; /* |y| >= 2^50, inf, NaN */
        if (valid) {
            /* volatile: the difference as the lanes round it (no contraction, no
               excess precision) */
            volatile float d = P->x[j][c][x] - y;
            if (!sbl__lane_value_ok(d)) return 1;
        }
    }
    return 0;
}

/* 1 if column x of any of the rows holds a value the prepass's lanes cannot take. */
static int sbl__pool_column_unsafe(const sbl__pool_rows *P, int x)
{
    int j;
    for (j = 0; j < P->n; ++j)
        if (P->unsafe[j][x] && sbl__pool_pixel_unsafe(P, j, x)) return 1;
    return 0;
}

/* The first column of [c, ce) that sbl__pool_column_unsafe flags, else ce: eight
   columns at a time past those no row flagged at load. */
static int sbl__pool_next_unsafe(const sbl__pool_rows *P, int c, int ce)
{
    while (c < ce) {
        uint64_t u = 0, t;
        int j;
        if (c + 8 <= ce) {
            for (j = 0; j < P->n; ++j) {
                memcpy(&t, P->unsafe[j] + c, 8);
                u |= t;
            }
            if (!u) { c += 8; continue; }
        }
        if (sbl__pool_column_unsafe(P, c)) return c;
        ++c;
    }
    return ce;
}

/* The first run [*ra, *rb) of pixels of [xa, xb) each with an unsafe value within
   SBL__POOL_REACH columns of it (the columns clamped to [0, w)); 0 if there is none. */
static int sbl__pool_unsafe_run(const sbl__pool_rows *P, int w, int xa, int xb, int *ra, int *rb)
{
    int c = xa - SBL__POOL_REACH > 0 ? xa - SBL__POOL_REACH : 0;
    const int ce = xb + SBL__POOL_REACH < w ? xb + SBL__POOL_REACH : w;
    int b;
    c = sbl__pool_next_unsafe(P, c, ce);
    if (c >= ce) return 0;
    *ra = c - SBL__POOL_REACH > xa ? c - SBL__POOL_REACH : xa;
    b = c + SBL__POOL_REACH + 1 < xb ? c + SBL__POOL_REACH + 1 : xb;
    /* unsafe columns whose pixels touch the run extend it */
    for (++c; c < ce && c - SBL__POOL_REACH <= b; ++c)
        if (sbl__pool_column_unsafe(P, c)) b = c + SBL__POOL_REACH + 1 < xb ? c + SBL__POOL_REACH + 1 : xb;
    *rb = b;
    return 1;
}

/* sbl__row_pool on a row of at least 18 columns, with np rows and ch channels constant. */
SBL__INLINE void sbl__row_pool_lanes(sbl__kernel *k, const sbl__ring_row *const *R,
                                     const sbl__pool_rows *P, const int np, const int ch, int xa,
                                     int xb, int unsafe)
{
    const int w = k->w, reach = SBL__POOL_REACH, span = SBL__POOL_STEP * SBL__POOL_BLOCKS;
    int x = xa;
    while (x < xb) {
        int e = xb - x > SBL__POOL_CHUNK ? x + SBL__POOL_CHUNK : xb, base, a, b, covered = 0;
        if (e - x < SBL__VW) x = e - SBL__VW; /* the last chunk: a whole vector, overlapping */
        base = x - reach;
        /* a chunk whose every pixel goes to the reference is not computed in lanes */
        if (unsafe && sbl__pool_unsafe_run(P, w, x, e, &a, &b)) covered = a == x && b == e;
        if (!covered) {
            const int ca = x - reach > 0 ? x - reach : 0, cb = e + reach < w ? e + reach : w;
            const int ba = x - span > 0 ? x - span : 0, bb = e + span < w ? e + span : w;
            sbl__pool_planes Q;
            int c;
            sbl__pool_planes_of(k, ch, 1, &Q);
            sbl__pool_lanes_columns(k, P, np, ch, ca, cb, base);
            if (x - reach < 0) sbl__pool_column_zero(&Q, ch, -1 - base);
            if (e + reach > w) sbl__pool_column_zero(&Q, ch, w - base);
            sbl__pool_lanes_blocks(k, &Q, ch, ba, bb, base, 1, 0, 0, 0);
            for (c = x - span; c < 0; ++c)
                SBL__POOL_PLANE(k, SBL__POOL_M2(ch))[c - base] = SBL__POOL_PLANE(k, SBL__POOL_SE2(ch))[c - base] = 0.0f;
            for (c = w; c < e + span; ++c)
                SBL__POOL_PLANE(k, SBL__POOL_M2(ch))[c - base] = SBL__POOL_PLANE(k, SBL__POOL_SE2(ch))[c - base] = 0.0f;
            sbl__pool_lanes_ratio(k, ch, x, e, base);
        }
        if (unsafe) {
            int p = x;
            while (p < e && sbl__pool_unsafe_run(P, w, p, e, &a, &b)) {
                sbl__row_pool_ref(k, R, a, b);
                p = b;
            }
        }
        x = e;
    }
}

/* Pooled estimator, once per row before its pixels: the prior bias-to-noise ratio r at
   each pixel of [xa, xb) of row R[1]->row, as sbl__row_pool_ref (which see) computes it,
   in lanes where it can (above). Reads the ring's columns [xa - SBL__POOL_REACH,
   xb + SBL__POOL_REACH) (clamped to the image); on a row of at least 18 columns,
   xb - xa >= 16 (sbl__kernel_run_span widens its span so). */
/* The ring rows that exist, as sbl__pool_rows; returns 1 if one holds a value the
   prepass's lanes cannot take (sbl__pool_pixel_unsafe) in the columns [xa - reach,
   xb + reach) the prepass of [xa, xb) reads. */
static int sbl__pool_rows_of(sbl__pool_rows *P, const sbl__ring_row *const *R, int ch, int w,
                             int xa, int xb)
{
    int j, c, flagged = 0;
    const int za = xa - SBL__POOL_REACH > 0 ? xa - SBL__POOL_REACH : 0;
    const int zb = xb + SBL__POOL_REACH < w ? xb + SBL__POOL_REACH : w;
    P->n = 0;
    P->ch = ch;
    for (j = 0; j < 3; ++j) {
        if (!R[j]) continue;
        for (c = 0; c < ch; ++c) { P->y[P->n][c] = R[j]->y[c]; P->x[P->n][c] = R[j]->x[c]; }
        P->v[P->n] = R[j]->v;
        P->unsafe[P->n] = R[j]->unsafe;
        flagged |= R[j]->unsafe_count > 0;
        ++P->n;
    }
    return flagged && za < zb && sbl__pool_next_unsafe(P, za, zb) < zb;
}

static void sbl__row_pool(sbl__kernel *k, const sbl__ring_row *const *R, int xa, int xb)
{
    sbl__pool_rows P;
    int unsafe;
    k->pool_row = R[1]->row;
    if (xa >= xb) return;
    if (k->w - 2 < 16 || xb - xa < 16) { /* the second: not reached (see above) */
        sbl__row_pool_ref(k, R, xa, xb);
        return;
    }
    unsafe = sbl__pool_rows_of(&P, R, k->ch, k->w, xa, xb);
#define SBL__POOL_CASE(np) \
    switch (k->ch) { \
    case 1: sbl__row_pool_lanes(k, R, &P, np, 1, xa, xb, unsafe); break; \
    case 2: sbl__row_pool_lanes(k, R, &P, np, 2, xa, xb, unsafe); break; \
    case 3: sbl__row_pool_lanes(k, R, &P, np, 3, xa, xb, unsafe); break; \
    default: sbl__row_pool_lanes(k, R, &P, np, 4, xa, xb, unsafe); break; \
    }
    if (P.n == 3) {
        SBL__POOL_CASE(3)
    } else if (P.n == 2) {
        SBL__POOL_CASE(2)
    } else {
        SBL__POOL_CASE(1)
    }
#undef SBL__POOL_CASE
}

/* The firefly limit's factor t from the channel sums of y, the neighbours' mean m8, x*
   and the neighbours' variance v8 (sbl__firefly_limit; n_xc the capped history length,
   whose sqrt(N + 1) widens the temporal bound), at pixels [x, x + VW) of the row in hand
   (its tail plane's terms: k->tail_on). t <= 1; y t is the limited sample. */
SBL__INLINE sbl__v sbl__lanes_firefly_t(const sbl__kernel *k, sbl__v sum_y, sbl__v sum_m8, sbl__v sum_x,
                                        sbl__v sum_v8, sbl__v n_xc, int x)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    sbl__v bound;
    if (k->wp.temporal) sum_v8 = sbl__mul(sum_v8, sbl__add(n_xc, one));
    bound = sbl__add(sbl__max(sum_m8, sum_x),
                     sbl__mul(sbl__set1(SBL__CAST(float, SBL_FIREFLY_SIGMAS)), sbl__sqrt(sum_v8)));
    bound = sbl__add(bound, sbl__mul(sbl__set1(1e-5f), sbl__abs(bound)));
    bound = sbl__max(bound, zero);
    if (k->tail_on) { /* as sbl__firefly_limit (2.4); a reset lane (x* invalid: n_xc at its
                         floor) keeps its sample and records nothing. The lanes see N = 0 or
                         N >= 2^-40 (a lane-safe N, sbl__lane_value_ok), so n_xc > FLT_MIN is
                         the reference path's n_x > 0 in every lane they process */
        const sbl__v e = sbl__sel(sbl__gt(sum_y, bound), sbl__sel(sbl__gt(n_xc, sbl__set1(FLT_MIN)), one, zero), zero);
        const sbl__v dx = sbl__sub(sum_y, sum_x);
        sbl__store(k->tail_e + x, e);
        sbl__store(k->tail_d + x, sbl__sel(sbl__gt(e, zero), sbl__mul(sbl__mul(dx, dx), sbl__set1(1.0f / SBL__CAST(float, k->ch))), zero));
        if (k->tail_use) {
            const sbl__v rho = sbl__mul(sbl__mul(sbl__load(k->tail_r + x), sbl__add(n_xc, one)),
                                        sbl__set1(1.0f + k->wp.shared_bias)); /* 6.9 */
            bound = sbl__add(bound, sbl__mul(sbl__div(rho, sbl__add(one, rho)),
                                             sbl__max(sbl__sub(sum_y, bound), zero)));
        }
    }
    return sbl__sel(sbl__gt(sum_y, bound), sbl__div(bound, sbl__max(sum_y, tiny)), one);
}

/* Firefly limit of the own sample, as sbl__firefly_limit. */
SBL__INLINE void sbl__lanes_firefly(const sbl__kernel *k, sbl__lane_stats *st, sbl__v n_xc, int x)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    sbl__v sum_y = zero, sum_m8 = zero, sum_x = zero, v8 = zero, t;
    int c, ch = k->ch;
    for (c = 0; c < ch; ++c) {
        sum_y = sbl__add(sum_y, st->yc[c]);
        sum_m8 = sbl__add(sum_m8, st->m8[c]);
        sum_x = sbl__add(sum_x, st->xr[c]);
        v8 = sbl__add(v8, st->v8[c]);
    }
    t = sbl__lanes_firefly_t(k, sum_y, sum_m8, sum_x, v8, n_xc, x);
    for (c = 0; c < ch; ++c) st->yb[c] = sbl__sel(sbl__gt(one, t), sbl__mul(st->yc[c], t), st->yc[c]);
}

/* Neighbourhood clamp / variance clip of x*, as sbl__rectify (after the firefly limit
   of the robust estimator, as in sbl__blend_pixel). */
SBL__INLINE void sbl__lanes_rectify(const sbl__kernel *k, sbl__lane_stats *st, sbl__v n_xc, int x)
{
    const sbl__v one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v gamma = sbl__set1(k->wp.gamma);
    int c, ch = k->ch;
    for (c = 0; c < ch; ++c) st->yb[c] = st->yc[c];
    if (k->wp.estimator == SBL_ESTIMATOR_ROBUST || k->wp.estimator == SBL_ESTIMATOR_POOLED)
        sbl__lanes_firefly(k, st, n_xc, x);
    if (k->wp.rectify == SBL_RECTIFY_CLAMP) {
        for (c = 0; c < ch; ++c) st->xs[c] = sbl__min(sbl__max(st->xs[c], st->lo[c]), st->hi[c]);
    } else if (k->wp.rectify == SBL_RECTIFY_VARIANCE_CLIP) {
        sbl__v t = one, tk[4], hs[4];
        for (c = 0; c < ch; ++c) {
            const sbl__v dist = sbl__abs(sbl__sub(st->xs[c], st->mean[c]));
            sbl__v half;
            hs[c] = sbl__mul(gamma, sbl__sqrt(st->var[c]));
            half = sbl__max(hs[c], sbl__abs(sbl__sub(st->yb[c], st->mean[c])));
            tk[c] = sbl__sel(sbl__gt(dist, half), sbl__div(half, sbl__max(dist, tiny)), one);
            t = sbl__min(t, tk[c]);
        }
        for (c = 0; c < ch; ++c) {
            /* the channel that sets t by y's distance, x* on y's side: x* lands on y
               exactly, as sbl__rectify (float rounding would leave it ulps off, and the
               pooled lean's E / D then reads a segment of rounding noise) */
            const sbl__v dy = sbl__sub(st->yb[c], st->mean[c]), dx = sbl__sub(st->xs[c], st->mean[c]);
            const sbl__v clip = sbl__add(st->mean[c], sbl__mul(dx, t));
            sbl__v v = sbl__sel(sbl__gt(sbl__mul(dy, dx), sbl__set1(0.0f)), st->yb[c], clip);
            v = sbl__sel(sbl__gt(hs[c], sbl__abs(dy)), clip, v);
            v = sbl__sel(sbl__gt(tk[c], t), clip, v);
            st->xs[c] = sbl__sel(sbl__gt(one, t), v, st->xs[c]);
        }
    }
}

/* The pooled stereo beta's spatial lean over channels [c0, c1), as sbl__lean (count 9:
   the neighbours' sample variance is 8/7 of their population variance v8). Bounded:
   q <= 8 and D within the lane range's squares, so no product overflows (V_M N_X may
   overflow to inf: q = 0, no lean). */
SBL__INLINE sbl__v sbl__lanes_lean(const sbl__lane_stats *st, sbl__v a0, sbl__v var_y,
                                   sbl__v n_xc, int c0, int c1)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    sbl__v v8 = zero, e = zero, d = zero, vm, q, den;
    int c;
    for (c = c0; c < c1; ++c) {
        const sbl__v dy = sbl__sub(st->yb[c], st->xs[c]);
        v8 = sbl__add(v8, st->v8[c]);
        e = sbl__add(e, sbl__mul(sbl__sub(st->m8[c], st->xs[c]), dy));
        d = sbl__add(d, sbl__mul(dy, dy));
    }
    vm = sbl__add(sbl__max(sbl__sub(sbl__mul(v8, st->lean_s), var_y), zero),
                  sbl__mul(var_y, st->inv_n8));
    vm = sbl__mul(vm, sbl__max(n_xc, one));
    q = sbl__sel(sbl__gt(vm, zero), sbl__div(sbl__mul(a0, var_y), sbl__max(vm, tiny)), zero);
    den = sbl__mul(sbl__add(one, q), d);
    return sbl__sel(sbl__gt(den, zero),
                    sbl__div(sbl__add(sbl__mul(a0, d), sbl__mul(q, e)), sbl__max(den, tiny)), a0);
}

/* The restart lean (sbl__weight, docs/ESTIMATORS.md 6.3) of the staged temporal lanes:
   as sbl__lanes_lean with q not divided by N_X, the texture the larger of the
   neighbours' beyond noise and the history's own (st->rl_xt; 0 where undefined), times
   texk (1 + c) behind a stereo blend (shared: a constant of the instance, 6.10) */
SBL__INLINE sbl__v sbl__lanes_lean_restart(const sbl__lane_stats *st, sbl__v a0, sbl__v var_y,
                                           const int shared, float texk)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v tex = sbl__max(sbl__max(sbl__sub(sbl__mul(st->rl_v8, st->lean_s), var_y), zero),
                                st->rl_xt);
    const sbl__v vm = sbl__add(shared ? sbl__mul(tex, sbl__set1(texk)) : tex, sbl__mul(var_y, st->inv_n8));
    const sbl__v q = sbl__sel(sbl__gt(vm, zero), sbl__div(sbl__mul(a0, var_y), sbl__max(vm, tiny)), zero);
    const sbl__v den = sbl__mul(sbl__add(one, q), st->rl_d);
    return sbl__sel(sbl__gt(den, zero),
                    sbl__div(sbl__add(sbl__mul(a0, st->rl_d), sbl__mul(q, st->rl_e)), sbl__max(den, tiny)),
                    a0);
}

/* Weight of Y from the squares summed over channels [c0, c1), as sbl__weight:
   dev2 = (x* - mean)^2, s2 = variance of Y, pd2 = (mean paired difference)^2, pvs =
   variance of the paired differences; n_xc = capped N_X, n_y = N_Y. Sets st->a2 of
   the group (the weight before the lean). */
SBL__INLINE sbl__v sbl__lanes_weight(const sbl__weight_params *p, sbl__lane_stats *st,
                                     sbl__v dev2, sbl__v s2, sbl__v pd2, sbl__v pvs,
                                     sbl__v n_xc, sbl__v n_y, int c0, int c1, const int fast)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v prog = sbl__div(n_y, sbl__add(n_xc, n_y));
    const int est = fast ? SBL_ESTIMATOR_POOLED : SBL__CAST(int, p->estimator);
    const int temporal = fast ? fast == 1 : p->temporal; /* fast: 1 temporal, 2 stereo */
    sbl__v w;
    int c;
    if (est == SBL_ESTIMATOR_PAPER) {
        sbl__v den = sbl__add(dev2, s2);
        w = sbl__sel(sbl__gt(den, zero), sbl__div(dev2, sbl__max(den, tiny)), prog);
    } else if (est == SBL_ESTIMATOR_PROGRESSIVE) {
        w = prog;
    } else if (est == SBL_ESTIMATOR_CONSTANT) {
        w = sbl__set1(p->constant);
    } else if (est == SBL_ESTIMATOR_ROBUST || est == SBL_ESTIMATOR_POOLED) {
        /* as sbl__weight: the bias enters with its posterior (sbl__change_posterior) */
        const float kb = est == SBL_ESTIMATOR_POOLED
                             ? SBL__CAST(float, SBL__CAST(double, p->bias_threshold) * SBL_POOLED_LOCAL_SCALE)
                             : p->bias_threshold;
        const sbl__v k2e = sbl__set1(SBL__CAST(float, 1.0 + SBL__CAST(double, kb) * SBL__CAST(double, kb) * 0.125));
        sbl__v vy_s, vx_s, vy_p, vx_p, vy, vx, se2, t2, rho, r2, odds, post, b2, num, den, w2;
        sbl__v b2c, wc; /* the change's bias energy alone, its weight (the restart lean's gate) */
        if (temporal && p->tail) { /* as sbl__weight (2.4): a channel group's share */
            const sbl__v tv = c1 - c0 == SBL__CAST(int, p->tail_ch) ? st->tail_t
                              : sbl__mul(st->tail_t, sbl__set1(SBL__CAST(float, c1 - c0) / p->tail_ch));
            pvs = sbl__max(pvs, sbl__div(sbl__mul(tv, sbl__add(n_xc, n_y)), sbl__max(n_xc, one)));
            s2 = sbl__max(s2, tv);
        }
        vy_s = sbl__mul(s2, st->bessel);
        vx_s = sbl__div(sbl__mul(vy_s, n_y), n_xc);
        vy_p = sbl__div(sbl__mul(pvs, n_xc), sbl__add(n_xc, n_y));
        vx_p = sbl__sub(pvs, vy_p);
        vy = sbl__sel(st->two_pairs, vy_p, vy_s);
        vx = sbl__sel(st->two_pairs, vx_p, vx_s);
        se2 = sbl__sel(st->two_pairs, sbl__mul(pvs, st->inv_cnt),
                       sbl__sel(st->has_pairs, sbl__add(vx_s, vy_s), zero));
        t2 = sbl__div(pd2, sbl__max(se2, tiny));
        rho = sbl__div(k2e, sbl__add(one, sbl__mul(t2, sbl__set1(0.125f))));
        r2 = sbl__mul(rho, rho);
        odds = temporal && SBL_HISTORY_PRIOR ? sbl__mul(sbl__set1(0.5f), sbl__add(n_xc, one)) : one;
        if (temporal && SBL_HISTORY_PRIOR && p->region_m > 0.0f && p->region_m != 1.0f) /* 3.10 */
            odds = sbl__mul(sbl__set1(0.5f), sbl__sub(sbl__mul(sbl__add(n_xc, sbl__set1(2.0f)),
                                                               sbl__set1(p->region_m)), one));
        post = sbl__div(one, sbl__add(one, sbl__mul(odds, sbl__mul(sbl__mul(r2, r2), sbl__sqrt(rho)))));
        if (!temporal && p->stereo_ev) post = sbl__sel(sbl__gt(st->sev, zero), one, post); /* 6.15 */
        b2 = sbl__sel(st->has_pairs, sbl__mul(post, pd2), zero);
        if (est == SBL_ESTIMATOR_POOLED) {
            /* empirical Bayes, as sbl__weight: sh^2 pd2 + sh se2, sh = r / (1 + r) */
            sbl__v sh = sbl__div(st->pool_r, sbl__add(one, st->pool_r));
            sbl__v b_eb = sbl__mul(sh, sbl__add(sbl__mul(sh, pd2), se2));
            b2 = sbl__sel(st->two_pairs, sbl__sel(sbl__gt(st->pool_r, zero), sbl__max(b2, b_eb), b2), b2);
        }
        if (temporal && p->shared_bias != 0.0f) /* 4.7; stereo: always 0 */
            b2 = sbl__mul(b2, sbl__set1(1.0f + p->shared_bias));
        /* the resampling blur's bias, as sbl__weight (4.12): only the temporal default's
           staged lanes (fast 1) hold its terms (wp.blur is set for no other). wc: the
           weight without it, for the restart lean's gate (6.10) */
        b2c = b2;
        if (fast == 1 && p->blur)
            b2 = sbl__max(b2, sbl__mul(sbl__sub(st->blur_b2, sbl__mul(st->blur_g, vx)),
                                       sbl__set1(1.0f + p->shared_bias)));
        if (SBL_STEREO_LAG_SHARE && est == SBL_ESTIMATOR_POOLED && !temporal) {
            /* the part of the bias that is X's, as sbl__lag_share */
            const sbl__v amax = sbl__set1(SBL__CAST(float, SBL__LAG_AGE_MAX));
            sbl__v u = sbl__min(sbl__max(sbl__sub(n_xc, one), zero), amax);
            sbl__v v = sbl__min(sbl__max(sbl__sub(n_y, one), zero), amax);
            sbl__v u2 = sbl__mul(u, u);
            sbl__v fx = sbl__div(u2, sbl__max(sbl__add(u2, sbl__mul(v, v)), tiny));
            fx = sbl__sel(sbl__gt(v, zero), fx, one);
            num = sbl__add(sbl__mul(fx, b2), vx);
            den = sbl__add(sbl__add(b2, vx), vy);
        } else {
            num = sbl__add(b2, vx);
            den = sbl__add(num, vy);
        }
        w = sbl__sel(sbl__gt(den, zero), sbl__div(num, sbl__max(den, tiny)), prog);
        if (fast == 1 && p->blur && p->lean_restart) {
            const sbl__v nc = sbl__add(b2c, vx), dc = sbl__add(nc, vy);
            wc = sbl__sel(sbl__gt(dc, zero), sbl__div(nc, sbl__max(dc, tiny)), prog);
        } else {
            wc = w;
        }
        if (SBL_EVIDENCE_MIX && est == SBL_ESTIMATOR_POOLED && temporal && p->evid_mix) {
            /* towards the paper's weight by the carried evidence's shrink (3.11) */
            const sbl__v dd = sbl__add(dev2, s2);
            const sbl__v ap = sbl__sel(sbl__gt(dd, zero), sbl__div(dev2, sbl__max(dd, tiny)), prog);
            w = sbl__sel(st->two_pairs, sbl__add(w, sbl__mul(st->evid_sh, sbl__max(sbl__sub(ap, w), zero))), w);
            if (fast == 1 && p->blur && p->lean_restart)
                wc = sbl__sel(st->two_pairs, sbl__add(wc, sbl__mul(st->evid_sh, sbl__max(sbl__sub(ap, wc), zero))), wc);
            else
                wc = w;
        }
        if (est == SBL_ESTIMATOR_POOLED && (SBL_LEAN_TEMPORAL || !temporal)) {
            w2 = sbl__min(sbl__max(sbl__max(w, sbl__set1(p->alpha_min)), zero), one);
            for (c = c0; c < c1; ++c) st->a2[c] = w2;
            /* the lean only where N_Y <= SBL_STEREO_LEAN_MAX_N (in float, as the
               reference compares), skipped in vectors whose every lane is above it (on
               converged content most; in bench/ipp.c's noisy cases few: 6.5); q / N_X
               in the temporal blend only */
            const sbl__v lean_n = sbl__set1(SBL__CAST(float, SBL_STEREO_LEAN_MAX_N));
            if (!sbl__all(sbl__gt(n_y, lean_n)))
                w = sbl__sel(sbl__gt(n_y, lean_n), w,
                             sbl__lanes_lean(st, w, vy, temporal ? n_xc : one, c0, c1));
            return sbl__min(sbl__max(sbl__max(w, sbl__set1(p->alpha_min)), zero), one);
        }
        if (fast == 1 && p->lean_restart) {
            /* the restart lean, as sbl__weight (6.3, 6.6): its share the product of the
               ramps in w and in w - N_Y / (N_X + N_Y) (sbl__restart_share). Its inputs
               are formed only in the vectors where some lane's share is above 0 (on
               converged content few; in bench/ipp.c's noisy cases most: 6.4), so
               sbl__lanes_stage_weight applies it; the weight returned is the one before
               it (Eq. 5's) */
            const sbl__v thr = sbl__set1(SBL__CAST(float, SBL_LEAN_RESTART_WEIGHT));
            const sbl__v exc = sbl__set1(SBL__CAST(float, SBL_LEAN_RESTART_EXCESS));
            const sbl__v ws = sbl__set1(SBL__CAST(float, SBL__LEAN_RESTART_WSLOPE));
            const sbl__v es = sbl__set1(SBL__CAST(float, SBL__LEAN_RESTART_ESLOPE));
            const sbl__v fw = sbl__min(sbl__max(sbl__mul(sbl__sub(wc, thr), ws), zero), one);
            const sbl__v fe = sbl__min(sbl__max(sbl__mul(sbl__sub(sbl__sub(wc, prog), exc), es), zero), one);
            st->rl_f = sbl__mul(fw, fe);
            st->rl_off = sbl__gt(sbl__set1(FLT_MIN), st->rl_f); /* (a share is 0 or above 1e-16) */
            st->rl_w = w;
            st->rl_vy = vy;
        }
    } else {
        /* pair statistics with two or more pairs, the 3x3 variance of Y otherwise */
        const sbl__v k2 = sbl__set1(p->bias_threshold * p->bias_threshold);
        sbl__v vy_s = sbl__mul(s2, st->bessel);
        sbl__v vx_s = sbl__div(sbl__mul(vy_s, n_y), n_xc);
        sbl__v vy_p = sbl__div(sbl__mul(pvs, n_xc), sbl__add(n_xc, n_y));
        sbl__v vx_p = sbl__sub(pvs, vy_p);
        sbl__v b2_p = sbl__sub(pd2, sbl__mul(sbl__mul(k2, pvs), st->inv_cnt));
        sbl__v b2_s = sbl__sub(pd2, sbl__mul(k2, sbl__add(vx_s, vy_s)));
        sbl__v vy = sbl__sel(st->two_pairs, vy_p, vy_s);
        sbl__v vx = sbl__sel(st->two_pairs, vx_p, vx_s);
        sbl__v b2 = sbl__sel(st->two_pairs, b2_p, sbl__sel(st->has_pairs, b2_s, zero));
        sbl__v num, den;
        b2 = sbl__max(b2, zero);
        if (temporal && p->shared_bias != 0.0f) /* 4.7 */
            b2 = sbl__mul(b2, sbl__set1(1.0f + p->shared_bias));
        num = sbl__add(b2, vx);
        den = sbl__add(num, vy);
        w = sbl__sel(sbl__gt(den, zero), sbl__div(num, sbl__max(den, tiny)), prog);
    }
    w = sbl__min(sbl__max(sbl__max(w, sbl__set1(p->alpha_min)), zero), one);
    for (c = c0; c < c1; ++c) st->a2[c] = w;
    return w;
}

/* The blend, Eq. 5 and the staged outputs of pixels [x, x + VW); invalid x* resets. */
SBL__INLINE void sbl__lanes_blend(sbl__kernel *k, int x, const sbl__lane_stats *st,
                                  const sbl__v *a, sbl__m valid, sbl__v n_xc, sbl__v n_y)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), tiny = sbl__set1(FLT_MIN);
    const sbl__v cap = sbl__set1(k->n_cap);
    const int fill = k->fill;
    sbl__v a_mean = zero, a2_mean = zero, n_out, one_m, den;
    int c;
    for (c = 0; c < k->ch; ++c) {
        /* two-sided lerp, as in sbl__blend_pixel */
        sbl__v o = sbl__sel(sbl__gt(a[c], sbl__set1(0.5f)),
                            sbl__add(st->yb[c], sbl__mul(sbl__sub(one, a[c]),
                                                         sbl__sub(st->xs[c], st->yb[c]))),
                            sbl__add(st->xs[c], sbl__mul(a[c], sbl__sub(st->yb[c], st->xs[c]))));
        if (fill) o = st->xr[c]; /* fill takes x* unrectified, as the reference path */
        sbl__store(k->stage[c] + x, sbl__sel(valid, o, st->yc[c]));
        a_mean = sbl__add(a_mean, a[c]);
    }
    a_mean = sbl__mul(a_mean, sbl__set1(1.0f / SBL__CAST(float, k->ch)));
    if (fill) a_mean = zero;
    /* Eq. 5: N = N_X N_Y / ((1-a)^2 N_Y + a^2 N_X), with the weight of the two-estimate
       blend (before the pooled estimator's lean, as sbl__blend_pixel) */
    for (c = 0; c < k->ch; ++c) a2_mean = c ? sbl__add(a2_mean, st->a2[c]) : st->a2[c];
    a2_mean = sbl__mul(a2_mean, sbl__set1(1.0f / SBL__CAST(float, k->ch)));
    if (fill) a2_mean = zero;
    one_m = sbl__sub(one, a2_mean);
    den = sbl__add(sbl__mul(sbl__mul(one_m, one_m), n_y), sbl__mul(sbl__mul(a2_mean, a2_mean), n_xc));
    n_out = sbl__sel(sbl__gt(den, zero), sbl__div(sbl__mul(n_xc, n_y), sbl__max(den, tiny)),
                     sbl__add(n_xc, n_y));
    if (fill) n_out = n_xc;
    n_out = sbl__min(n_out, cap);
    sbl__store(k->stage_n + x, sbl__sel(valid, n_out, k->temporal ? one : n_y));
    sbl__store(k->stage_a + x, sbl__sel(valid, a_mean, one));
}

/* Lane kernel over pixels [x0, x1) of an interior row (all nine neighbours exist and
   are lane-safe). Returns the first pixel it did not process (the tail goes to the
   reference path). */
/* Channel c's terms of the weight's sums: dev2 = (x* - mean)^2, s2 = variance of Y,
   pd2 = (mean paired difference)^2, pvs = variance of the paired differences. */
SBL__INLINE void sbl__lanes_group_add(const sbl__lane_stats *st, int c, sbl__v *sums)
{
    const sbl__v e = sbl__sub(st->xs[c], st->mean[c]);
    sums[0] = sbl__add(sums[0], sbl__mul(e, e));
    sums[1] = sbl__add(sums[1], st->var[c]);
    sums[2] = sbl__add(sums[2], sbl__mul(st->pd[c], st->pd[c]));
    sums[3] = sbl__add(sums[3], st->pv[c]);
}

/* The history length n_x (0: reset), the new sample's n_y (1 where absent or not
   positive) and n_x capped for the weight, as every lane kernel reads them */
SBL__INLINE void sbl__lanes_lengths(const sbl__kernel *k, const float *n_row, const float *nyrow,
                                    int x, sbl__v *n_x, sbl__v *n_y, sbl__v *n_xc)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    *n_x = sbl__load(n_row + x);
    *n_y = nyrow ? sbl__load(nyrow + x) : one;
    *n_y = sbl__sel(sbl__gt(*n_y, zero), *n_y, one);
    *n_xc = sbl__max(sbl__min(*n_x, sbl__set1(k->n_cap)), sbl__set1(FLT_MIN));
}

/* One vector of pixels [x, x + VW) of row y: moments from the column sums at index
   column - base (sbl__lanes_columns), the estimator, the blend, staged. */
SBL__INLINE void sbl__lanes_vector(sbl__kernel *k, const sbl__lane_rows *W, const float *n_row,
                                   const float *nyrow, int x, int base, int y, const int ch)
{
    const sbl__v zero = sbl__set1(0.0f);
    sbl__lane_stats st;
    sbl__v a[4], n_x, n_y, n_xc;
    sbl__m valid;
    int c;
    sbl__lanes_lengths(k, n_row, nyrow, x, &n_x, &n_y, &n_xc);
    valid = sbl__gt(n_x, zero);
    sbl__lanes_moments(k, W, x, base, &st);
    st.bessel = sbl__set1(9.0f / 8.0f);
    st.lean_s = sbl__set1(8.0f / 7.0f);
    st.inv_n8 = sbl__set1(0.125f);
    sbl__lanes_pool(k, x, y, &st);
    sbl__lanes_rectify(k, &st, n_xc, x);
    if (k->wp.mode == SBL_WEIGHT_PER_CHANNEL) {
        for (c = 0; c < ch; ++c) {
            sbl__v sums[4] = {zero, zero, zero, zero};
            sbl__lanes_group_add(&st, c, sums);
            a[c] = sbl__lanes_weight(&k->wp, &st, sums[0], sums[1], sums[2], sums[3], n_xc, n_y, c, c + 1, 0);
        }
    } else {
        /* one weight from the squares summed over the channels (written out) */
        sbl__v sums[4] = {zero, zero, zero, zero}, w;
        sbl__lanes_group_add(&st, 0, sums);
        if (ch > 1) sbl__lanes_group_add(&st, 1, sums);
        if (ch > 2) sbl__lanes_group_add(&st, 2, sums);
        if (ch > 3) sbl__lanes_group_add(&st, 3, sums);
        w = sbl__lanes_weight(&k->wp, &st, sums[0], sums[1], sums[2], sums[3], n_xc, n_y, 0, ch, 0);
        for (c = 0; c < ch; ++c) a[c] = w;
    }
    sbl__lanes_blend(k, x, &st, a, valid, n_xc, n_y);
}

/* sbl__lanes_vector in the default configuration (fast: 1 temporal, 2 stereo) with the
   channels written out, so that the per-channel values stay in registers (loops over
   the channels keep the lane statistics in memory): the same operations in the same
   order as sbl__lanes_moments, sbl__lanes_firefly, sbl__lanes_weight and
   sbl__lanes_blend (bit for bit, but the mean weight, below). The pair terms: the
   pooled prepass's blocks. */
#define SBL__LANES_CH(M) do { M(0); if (ch > 1) M(1); if (ch > 2) M(2); if (ch > 3) M(3); } while (0)
SBL__INLINE void sbl__lanes_vector_fast(sbl__kernel *k, const sbl__lane_rows *W, const float *n_row,
                                        const float *nyrow, int x, int base, int y, const int ch,
                                        const int fast, const int full, const sbl__lane_edge *E)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__v cap = sbl__set1(k->n_cap), half = sbl__set1(0.5f);
    const int i = x - base;
    sbl__lane_stats st; /* the fields sbl__lanes_weight reads */
    sbl__v yc[4], xs[4], yb[4], m8[4], v8[4], var[4], mean;
    sbl__v n_x, n_y, n_xc, nl, nr, cnt, s2, w, w2, one_w, f_w, t, a_mean, a2_mean, one_m, den, n_out;
    sbl__v sum_y = zero, sum_m8 = zero, sum_x = zero, sum_v8 = zero;
    sbl__m valid, hi_w;
    sbl__lanes_lengths(k, n_row, nyrow, x, &n_x, &n_y, &n_xc);
    /* full: every x* of the chunk valid (v = 1 exactly where N > 0): no reset lane */
    valid = full ? sbl__true : sbl__gt(n_x, zero);
    /* pair counts (sbl__lanes_moments) */
    nl = full ? sbl__set1(3.0f) : sbl__load(k->col[0] + i + SBL__CHUNK_COLN(ch) - 1);
    nr = full ? sbl__set1(3.0f) : sbl__load(k->col[0] + i + SBL__CHUNK_COLN(ch) + 1);
    cnt = full ? sbl__set1(9.0f) : sbl__add(sbl__add(nl, sbl__load(k->col[0] + i + SBL__CHUNK_COLN(ch))), nr);
    /* full (sbl__lanes_full): nine pairs */
    st.has_pairs = full ? sbl__true : sbl__gt(cnt, zero);
    st.two_pairs = full ? sbl__true : sbl__gt(cnt, one);
    st.inv_cnt = sbl__div(one, sbl__max(cnt, one));
    /* Y's moments; the sums of the firefly limit (sbl__lanes_firefly) */
#define SBL__FAST_Y(c) \
    do { \
        sbl__lanes_y_channel(k, W, x, i, c, &mean, &var[c], &m8[c], &v8[c], &yc[c], 0, E); \
        xs[c] = sbl__load(W->x[1][c] + x); \
        /* the sums start at channel 0's values (0 + v is v: no addition) */ \
        sum_y = (c) ? sbl__add(sum_y, yc[c]) : yc[c]; \
        sum_m8 = (c) ? sbl__add(sum_m8, m8[c]) : m8[c]; \
        sum_x = (c) ? sbl__add(sum_x, xs[c]) : xs[c]; \
        sum_v8 = (c) ? sbl__add(sum_v8, v8[c]) : v8[c]; \
    } while (0)
    SBL__LANES_CH(SBL__FAST_Y);
#undef SBL__FAST_Y
    /* t <= 1 (bound < max(sum_y, tiny) where divided), so y t is y where t = 1: the
       limited sample is y t in every lane, with no select */
    t = sbl__lanes_firefly_t(k, sum_y, sum_m8, sum_x, sum_v8, n_xc, x);
    /* (the copies for the stereo weight's lean are stored in every vector: storing them
       only where the lean runs, a lane of N_Y <= SBL_STEREO_LEAN_MAX_N, left gcc -Wmaybe-uninitialized
       warnings in the scalar build, which cannot see that the weight tests the same) */
#define SBL__FAST_YB(c) \
    do { \
        yb[c] = sbl__mul(yc[c], t); /* (t <= 1, above) */ \
        if (fast == 2) { st.yb[c] = yb[c]; st.xs[c] = xs[c]; st.m8[c] = m8[c]; st.v8[c] = v8[c]; } \
    } while (0)
    SBL__LANES_CH(SBL__FAST_YB);
#undef SBL__FAST_YB
    /* the weight: Y's variance summed over the channels, the blocks' pair terms; the
       pooled ratio of this row (sbl__kernel_lanes_pooled computed it: sbl__lanes_pool) */
    st.pool_r = sbl__load(k->pool_r + x);
    st.sev = k->wp.stereo_ev ? sbl__load(k->sev + x) : sbl__set1(0.0f);
    st.tail_t = k->wp.tail ? sbl__load(k->tail_t + x) : sbl__set1(0.0f);
    st.bessel = E ? E->bessel : sbl__set1(9.0f / 8.0f);
    st.lean_s = E ? E->lean_s : sbl__set1(8.0f / 7.0f);
    st.inv_n8 = E ? E->inv_n8 : sbl__set1(0.125f);
    (void)y;
    s2 = var[0];
    if (ch > 1) s2 = sbl__add(s2, var[1]);
    if (ch > 2) s2 = sbl__add(s2, var[2]);
    if (ch > 3) s2 = sbl__add(s2, var[3]);
    w = sbl__lanes_weight(&k->wp, &st, zero, s2,
                          sbl__load(k->col[0] + i + SBL__CHUNK_POOL(ch) + SBL__POOL_PD2(ch) * SBL__POOL_COLS),
                          sbl__load(k->col[0] + i + SBL__CHUNK_POOL(ch) + SBL__POOL_PV(ch) * SBL__POOL_COLS),
                          n_xc, n_y, 0, ch, fast);
    w2 = st.a2[0]; /* every channel's */
    /* the blend (sbl__lanes_blend with one weight, no fill) */
    hi_w = sbl__gt(w, half);
    one_w = sbl__sub(one, w);
    f_w = sbl__min(w, one_w); /* the two-sided lerp's factor (as the staged lanes) */
#define SBL__FAST_BLEND(c) \
    do { \
        sbl__v from, to, o; \
        SBL__SEL2(hi_w, yb[c], xs[c], from, to); \
        o = sbl__add(from, sbl__mul(f_w, sbl__sub(to, from))); \
        sbl__store(k->stage[c] + x, sbl__sel(valid, o, yc[c])); \
    } while (0)
    SBL__LANES_CH(SBL__FAST_BLEND);
#undef SBL__FAST_BLEND
    /* one weight for every channel: its mean is the weight itself (as the reference's
       sbl__blend_pixel, which takes it unaveraged; sbl__lanes_blend averages the copies) */
    a_mean = w;
    a2_mean = w2;
    one_m = sbl__sub(one, a2_mean);
    den = sbl__add(sbl__mul(sbl__mul(one_m, one_m), n_y), sbl__mul(sbl__mul(a2_mean, a2_mean), n_xc));
    /* sbl__lanes_blend's guards on den fall away: in a valid lane n_xc, n_y >= 2^-40 (lane-safe N,
       a cap >= 1) and one of (1 - a)^2, a^2 is >= 1/4, so den >= 2^-42 (a normal float:
       > 0, > FLT_MIN); the other lanes take the select below */
    n_out = sbl__min(sbl__div(sbl__mul(n_xc, n_y), den), cap);
    sbl__store(k->stage_n + x, sbl__sel(valid, n_out, k->temporal ? one : n_y));
    sbl__store(k->stage_a + x, sbl__sel(valid, a_mean, one));
}
/* The temporal default configuration (sbl__lanes_vector_fast with fast = 1) in three
   stages over the vectors of a run, so that each stage's values fit the registers (one
   pass holding Y's moments, the firefly sums, the weight and the blend spills them) and
   each loop is short enough for the out-of-order core to overlap several vectors' chains
   of divisions (one loop holding the weight and the blend ran them one after another):
   sbl__lanes_stage_y, Y's moments and the firefly limit's factor t, the summed variance
   s2 into two planes of the chunk (index column - base); sbl__lanes_stage_weight, the
   weight into a third; then sbl__lanes_stage_blend, Eq. 5 and the blend. The same
   operations in the same order as sbl__lanes_vector_fast (bit for bit), but for the
   restart lean (wp.lean_restart, 6.3), which only the stages have: the temporal default
   never reaches sbl__lanes_vector_fast with fast = 1 (sbl__kernel_lanes_pooled_ch and
   sbl__lanes_edge run the stages for it). */
/* The history's texture term of channel c at the restart lean (sbl__lanes_stage_y): the
   sum of x*_i - xc over the valid neighbours of row J, columns -1 (into dl), 0 (dm, not
   on the centre row) and +1 (dr); ok*: their masks */
#define SBL__XT_ROW(C, J, okl, okm, okr) \
    do { \
        const float *xr_ = W->x[J][C] + x; \
        dl = sbl__add(dl, sbl__sel(okl, sbl__sub(sbl__load(xr_ - 1), xc), zero)); \
        if ((J) != 1) dm = sbl__add(dm, sbl__sel(okm, sbl__sub(sbl__load(xr_), xc), zero)); \
        dr = sbl__add(dr, sbl__sel(okr, sbl__sub(sbl__load(xr_ + 1), xc), zero)); \
    } while (0)
SBL__INLINE void sbl__lanes_stage_y(sbl__kernel *k, const sbl__lane_rows *W, const float *n_row,
                                    int x, int base, const int ch, const sbl__lane_edge *E,
                                    const int mix, const int lean)
{
    const sbl__v zero = sbl__set1(0.0f);
    const int i = x - base;
    sbl__v mean, var, m8, v8, yc, s2 = zero, t, n_x, n_y, n_xc;
    /* lean (a constant: the restart lean, wp.lean_restart): the channels' m8 kept */
    sbl__v m8c[4];
    sbl__v sum_y = zero, sum_m8 = zero, sum_x = zero, sum_v8 = zero; /* (set by channel 0) */
    /* |x* - mean|^2, for the mix towards the paper's weight (3.11); mix: a constant,
       k->wp.evid_mix (sbl__kernel_lanes_pooled_ch's instances) */
    sbl__v dev2 = zero;
#define SBL__STAGE_Y(c) \
    do { \
        sbl__lanes_y_channel(k, W, x, i, c, &mean, &var, &m8, &v8, &yc, 1, E); \
        if (lean) m8c[c] = m8; \
        if (mix) { \
            const sbl__v e_ = sbl__sub(sbl__load(W->x[1][c] + x), mean); \
            dev2 = (c) ? sbl__add(dev2, sbl__mul(e_, e_)) : sbl__mul(e_, e_); \
        } \
        /* the sums start at channel 0's values (0 + v is v: no addition) */ \
        sum_y = (c) ? sbl__add(sum_y, yc) : yc; \
        sum_m8 = (c) ? sbl__add(sum_m8, m8) : m8; \
        sum_x = (c) ? sbl__add(sum_x, sbl__load(W->x[1][c] + x)) : sbl__load(W->x[1][c] + x); \
        sum_v8 = (c) ? sbl__add(sum_v8, v8) : v8; \
        s2 = (c) ? sbl__add(s2, var) : var; \
    } while (0)
    SBL__LANES_CH(SBL__STAGE_Y);
#undef SBL__STAGE_Y
    (void)mean;
    /* the channels' v8 (sbl__lanes_y_channel) */
    sum_v8 = sbl__mul(sum_v8, E ? E->inv_n8 : sbl__set1(0.125f));
    sbl__lanes_lengths(k, n_row, NULL, x, &n_x, &n_y, &n_xc);
    t = sbl__lanes_firefly_t(k, sum_y, sum_m8, sum_x, sum_v8, n_xc, x);
    sbl__store(k->col[0] + i + SBL__CHUNK_POOL(ch) + SBL__POOL_FT(ch) * SBL__POOL_COLS, t);
    sbl__store(k->col[0] + i + SBL__CHUNK_POOL(ch) + SBL__POOL_S2(ch) * SBL__POOL_COLS, s2);
    if (mix) sbl__store(k->col[0] + i + SBL__CHUNK_POOL(ch) + SBL__POOL_DEV2(ch) * SBL__POOL_COLS, dev2);
    if (lean) { /* the restart lean's (sbl__lanes_lean_inputs) */
        float *const q = k->col[0] + i + SBL__CHUNK_POOL(ch);
#define SBL__LEAN_M8(c) sbl__store(q + SBL__POOL_LM8(ch, c) * SBL__POOL_COLS, m8c[c])
        SBL__LANES_CH(SBL__LEAN_M8);
#undef SBL__LEAN_M8
        sbl__store(q + SBL__POOL_LV8(ch) * SBL__POOL_COLS, sum_v8);
    }
}

/* The restart lean's inputs of pixels [x, x + VW) (sbl__lanes_stage_weight, in the
   vectors where it applies), as sbl__blend_pixel and sbl__moments_core form them: E =
   sum_c (m8 - x*)(y t - x*), D = sum_c (y t - x*)^2, the neighbours' population variance
   (sbl__lanes_stage_y's planes), and the history's texture sum_c (x*_c - mean of the
   valid neighbours' x*)^2, summed about the centre's x* (differences of lane-safe values,
   no sum of large values): (sum_i (x*_i - x*_c))^2 / n^2, n the valid neighbours (the
   window's pairs but the centre's; 0 terms where n = 0). lean (a constant): 2 a full
   chunk, every x* valid; 3 the image's first or last row (k->edge_row: the missing row
   is a copy, left out); E as sbl__lanes_y_channel. */
SBL__INLINE void sbl__lanes_lean_inputs(const sbl__kernel *k, const sbl__lane_rows *W, int x,
                                        int base, const int ch, const sbl__lane_edge *E,
                                        const int lean, sbl__lane_stats *st)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const int i = x - base;
    const float *const q = k->col[0] + i + SBL__CHUNK_POOL(ch);
    const float *const qn = k->col[0] + i + SBL__CHUNK_COLN(ch);
    const sbl__v t = sbl__load(q + SBL__POOL_FT(ch) * SBL__POOL_COLS);
    const int r0 = lean != 3 || k->edge_row != 1, r2 = lean != 3 || k->edge_row != 2;
    sbl__m ok0l, ok0m, ok0r, ok1l, ok1r, ok2l, ok2m, ok2r;
    sbl__v le = zero, ld = zero, xt = zero, rn;
    if (lean == 2) {
        ok0l = ok0m = ok0r = ok1l = ok1r = ok2l = ok2m = ok2r = sbl__true;
        rn = sbl__set1(0.125f);
    } else {
        const float *const v0 = W->v[0] + x, *const v1 = W->v[1] + x, *const v2 = W->v[2] + x;
        ok0l = sbl__gt(sbl__load(v0 - 1), zero);
        ok0m = sbl__gt(sbl__load(v0), zero);
        ok0r = sbl__gt(sbl__load(v0 + 1), zero);
        ok1l = sbl__gt(sbl__load(v1 - 1), zero);
        ok1r = sbl__gt(sbl__load(v1 + 1), zero);
        ok2l = sbl__gt(sbl__load(v2 - 1), zero);
        ok2m = sbl__gt(sbl__load(v2), zero);
        ok2r = sbl__gt(sbl__load(v2 + 1), zero);
        /* the pairs per column (a column outside the image: 0; lean 3: the copy's left
           out, sbl__lanes_columns_cfg) less the centre's */
        rn = sbl__div(one, sbl__max(sbl__sub(sbl__add(sbl__add(sbl__load(qn - 1), sbl__load(qn)),
                                                      sbl__load(qn + 1)), one), one));
    }
#define SBL__LEAN_IN(c) \
    do { \
        const sbl__v xc = sbl__load(W->x[1][c] + x); \
        const sbl__v dy = sbl__sub(sbl__mul(sbl__load(W->y[1][c] + x), t), xc); \
        const sbl__v m8 = sbl__load(q + SBL__POOL_LM8(ch, c) * SBL__POOL_COLS); \
        sbl__v dl = zero, dm = zero, dr = zero, d; \
        le = (c) ? sbl__add(le, sbl__mul(sbl__sub(m8, xc), dy)) : sbl__mul(sbl__sub(m8, xc), dy); \
        ld = (c) ? sbl__add(ld, sbl__mul(dy, dy)) : sbl__mul(dy, dy); \
        if (r0) SBL__XT_ROW(c, 0, ok0l, ok0m, ok0r); \
        SBL__XT_ROW(c, 1, ok1l, ok1l, ok1r); \
        if (r2) SBL__XT_ROW(c, 2, ok2l, ok2m, ok2r); \
        if (E) { /* the border lane's column outside the image */ \
            dl = sbl__sel(E->keep_l, dl, zero); \
            dr = sbl__sel(E->keep_r, dr, zero); \
        } \
        d = sbl__add(sbl__add(dl, dm), dr); \
        xt = (c) ? sbl__add(xt, sbl__mul(d, d)) : sbl__mul(d, d); \
    } while (0)
    SBL__LANES_CH(SBL__LEAN_IN);
#undef SBL__LEAN_IN
    st->rl_e = le;
    st->rl_d = ld;
    st->rl_v8 = sbl__load(q + SBL__POOL_LV8(ch) * SBL__POOL_COLS);
    st->rl_xt = sbl__mul(xt, sbl__mul(rn, rn));
}
#undef SBL__XT_ROW

SBL__INLINE int sbl__rows_valid_in(const sbl__ring_row *const *R, int ca, int cb); /* (below) */

/* sbl__blur_noise in lanes (the same operations): Horner's steps written out, so that each
   coefficient is a constant of the instruction (in a loop it is a load and a broadcast) */
#define SBL__BLUR_HORNER(j) \
    pa = sbl__add(sbl__mul(pa, r), sbl__set1(sbl__blur_fa[j])); \
    ph = sbl__add(sbl__mul(ph, r), sbl__set1(sbl__blur_fh[j])); \
    pk = sbl__add(sbl__mul(pk, r), sbl__set1(sbl__blur_fk[j]))
SBL__INLINE sbl__v sbl__blur_noise_lanes(sbl__v in, sbl__v n, sbl__v v)
{
    const sbl__v one = sbl__set1(1.0f), r = sbl__div(one, sbl__sqrt(sbl__add(one, sbl__mul(n, v))));
    sbl__v pa = sbl__set1(sbl__blur_fa[6]), ph = sbl__set1(sbl__blur_fh[6]), pk = sbl__set1(sbl__blur_fk[6]);
    SBL__BLUR_HORNER(5);
    SBL__BLUR_HORNER(4);
    SBL__BLUR_HORNER(3);
    SBL__BLUR_HORNER(2);
    SBL__BLUR_HORNER(1);
    SBL__BLUR_HORNER(0);
    return sbl__add(sbl__mul(sbl__mul(r, r), pa), sbl__mul(in, sbl__add(ph, sbl__mul(v, pk))));
}
#undef SBL__BLUR_HORNER

/* sbl__blur_var in lanes: floor as floorf (x86: sbl__floor, exact for |m| < 2^31, which
   a valid x*'s motion is; other lanes are discarded) */
SBL__INLINE sbl__v sbl__blur_var_lanes(sbl__v m)
{
    sbl__v f;
#if SBL__VW == 1
    f = sbl__sub(m, floorf(m));
#elif defined(SBL__ROW_GATHER)
    f = sbl__sub(m, sbl__floor(m));
#else
    f = sbl__sub(m, vrndmq_f32(m));
#endif
    return sbl__mul(f, sbl__sub(sbl__set1(1.0f), f));
}

/* Is any lane of v above 0? */
SBL__INLINE int sbl__blur_any(sbl__v v)
{
#if defined(SBL__ROW_GATHER)
    return sbl__mbits(sbl__gt(v, sbl__set1(0.0f))) != 0;
#else
    float a[SBL__VW];
    int l;
    sbl__store(a, v);
    for (l = 0; l < SBL__VW; ++l)
        if (a[l] > 0.0f) return 1;
    return 0;
#endif
}

/* The motion vectors (x components *mx, y *my, in pixels: times kx, ky) of pixels
   [x, x + VW) of row y: two loads and shuffles where the plane is packed */
SBL__INLINE void sbl__blur_motion_lanes(const sbl__temporal_rp *s, int x, int y, sbl__v *mx, sbl__v *my)
{
    const float *mvp = SBL__AT(s->motion, x, y);
    if (s->motion.step == 2) {
        sbl__motion_packed_lanes(mvp, mx, my);
    } else {
        float fx[SBL__VW], fy[SBL__VW];
        int l;
        for (l = 0; l < SBL__VW; ++l) {
            fx[l] = mvp[l * s->motion.step];
            fy[l] = mvp[l * s->motion.step + 1];
        }
        *mx = sbl__load(fx);
        *my = sbl__load(fy);
    }
    *mx = sbl__mul(sbl__set1(SBL__CAST(float, s->motion_kx)), *mx);
    *my = sbl__mul(sbl__set1(SBL__CAST(float, s->motion_ky)), *my);
}

/* The resampling blur's terms of pixels [x, x + VW) (sbl__blur_terms in lanes, float)
   into the chunk's planes BB and BG, for sbl__lanes_stage_weight: the fetch's variances
   (motion vectors in lanes; the camera's positions per pixel, sbl__blur_fraction), S and
   the noise factor (sbl__blur_scalars), the second differences, the 3x3 bound and the
   sum over the channels. R: the ring rows as they are (NULL outside the image), not the
   edge rows' stand-ins. */
SBL__INLINE void sbl__lanes_stage_blur(const sbl__kernel *k, const sbl__ring_row *const *R, int x,
                                       int base, const int ch)
{
    float *const q = k->col[0] + (x - base) + SBL__CHUNK_POOL(ch);
    float cl[SBL__VW], cr[SBL__VW];
    const sbl__ring_row *r = R[1];
    const sbl__temporal_rp *s = k->blur_rp;
    const sbl__v zero = sbl__set1(0.0f), half = sbl__set1(0.5f), two = sbl__set1(2.0f), one = sbl__set1(1.0f);
    sbl__v sx, sy, sum = zero, xl, xr, vl, vr, f[3][3], vx, vy, n, in, hn;
    sbl__m okx, oky, m[3][3];
    int l, c, j;
    if (s->source == SBL_TEMPORAL_MOTION) {
        sbl__blur_motion_lanes(s, x, r->row, &vx, &vy);
        vx = sbl__blur_var_lanes(vx);
        vy = sbl__blur_var_lanes(vy);
    } else { /* the camera's position per pixel (sbl__temporal_rp_pos) */
        float fvx[SBL__VW], fvy[SBL__VW];
        for (l = 0; l < SBL__VW; ++l) {
            fvx[l] = fvy[l] = 0.0f;
            if (r->v[x + l] > 0.0f) sbl__blur_fraction(s, x + l, r->row, fvx + l, fvy + l);
        }
        vx = sbl__load(fvx);
        vy = sbl__load(fvy);
    }
    /* no x*: no blur (and no value of an invalid lane's motion goes further);
       k->rows_valid: x* valid in every column of the row */
    if (!k->rows_valid) {
        const sbl__m ok = sbl__gt(sbl__load(r->v + x), zero);
        vx = sbl__sel(ok, vx, zero);
        vy = sbl__sel(ok, vy, zero);
    }
    if (!sbl__blur_any(sbl__max(vx, vy))) {
        /* a fixed camera, integer motion: no blur */
        sbl__store(q + SBL__POOL_BG(ch) * SBL__POOL_COLS, zero);
        sbl__store(q + SBL__POOL_BB(ch) * SBL__POOL_COLS, zero);
        return;
    }
    /* sbl__blur_scalars */
    n = sbl__load(r->n + x);
    n = sbl__max(sbl__min(n, sbl__set1(k->n_cap)), one);
    in = sbl__div(one, n);
    hn = sbl__mul(half, sbl__add(n, one));
    sx = sbl__mul(hn, vx);
    sy = sbl__mul(hn, vy);
    sbl__store(q + SBL__POOL_BG(ch) * SBL__POOL_COLS,
               sbl__mul(sbl__set1(0.25f), sbl__add(sbl__mul(sbl__mul(sx, sx), sbl__blur_noise_lanes(in, n, vx)),
                                                   sbl__mul(sbl__mul(sy, sy), sbl__blur_noise_lanes(in, n, vy)))));
    if (x > 0 && x + SBL__VW < k->w &&
        (k->rows_valid || (R[0] && R[2] && sbl__rows_valid_in(R, x - 1, x + SBL__VW + 1)))) {
        /* every x* of the lanes' 3x3 windows valid (k->rows_valid: the three rows'; else
           the rows' invalid extents), inside the image: the masked loop below without its
           selects (the same values), its nine loads written out from row pointers */
        /* (the channels written out, SBL__LANES_CH; the sum starts at channel 0's b^2,
           which 0 + b^2 is: b^2 is never -0) */
#define SBL__BLUR_CH(c) \
    do { \
        const float *const p0 = R[0]->x[c] + x, *const p1 = r->x[c] + x, *const p2 = R[2]->x[c] + x; \
        const sbl__v xc = sbl__load(p1), xw = sbl__load(p1 - 1), xe = sbl__load(p1 + 1); \
        const sbl__v u0 = sbl__load(p0 - 1), u1 = sbl__load(p0), u2 = sbl__load(p0 + 1); \
        const sbl__v d0 = sbl__load(p2 - 1), d1 = sbl__load(p2), d2 = sbl__load(p2 + 1); \
        const sbl__v d2x = sbl__sub(sbl__add(xw, xe), sbl__mul(two, xc)); \
        const sbl__v d2y = sbl__sub(sbl__add(u1, d1), sbl__mul(two, xc)); \
        /* (min and max of the nine: x* is finite here, so their order is free) */ \
        const sbl__v lo = sbl__min(sbl__min(sbl__min(sbl__min(u0, u1), sbl__min(u2, xw)), \
                                            sbl__min(sbl__min(xc, xe), sbl__min(d0, d1))), d2); \
        const sbl__v hi = sbl__max(sbl__max(sbl__max(sbl__max(u0, u1), sbl__max(u2, xw)), \
                                            sbl__max(sbl__max(xc, xe), sbl__max(d0, d1))), d2); \
        const sbl__v hb = sbl__mul(half, sbl__sub(hi, lo)); \
        sbl__v b = sbl__mul(half, sbl__add(sbl__mul(sx, d2x), sbl__mul(sy, d2y))); \
        b = sbl__min(sbl__max(b, sbl__sub(zero, hb)), hb); \
        sum = (c) ? sbl__add(sum, sbl__mul(b, b)) : sbl__mul(b, b); \
    } while (0)
        SBL__LANES_CH(SBL__BLUR_CH);
#undef SBL__BLUR_CH
        sbl__store(q + SBL__POOL_BB(ch) * SBL__POOL_COLS, sum);
        return;
    }
    for (l = 0; l < SBL__VW; ++l) {
        cl[l] = x + l > 0 ? 1.0f : 0.0f;
        cr[l] = x + l + 1 < k->w ? 1.0f : 0.0f;
    }
    vl = sbl__load(cl);
    vr = sbl__load(cr);
    /* which of the 3x3's x* exist (v is 0 or 1: products of them, then selects, so no
       value outside them reaches a min) */
    for (j = 0; j < 3; ++j) {
        int i;
        if (!R[j]) {
            f[j][0] = f[j][1] = f[j][2] = zero;
        } else {
            /* (selects, not products: the columns outside the image are padding, whose
               bits a product would carry) */
            f[j][0] = sbl__sel(sbl__gt(vl, zero), sbl__load(R[j]->v + x - 1), zero);
            f[j][1] = sbl__load(R[j]->v + x);
            f[j][2] = sbl__sel(sbl__gt(vr, zero), sbl__load(R[j]->v + x + 1), zero);
        }
        for (i = 0; i < 3; ++i) m[j][i] = sbl__gt(f[j][i], zero);
    }
    okx = sbl__gt(sbl__mul(f[1][0], f[1][2]), zero);
    oky = sbl__gt(sbl__mul(f[0][1], f[2][1]), zero);
    for (c = 0; c < ch; ++c) {
        const sbl__v xc = sbl__load(r->x[c] + x);
        sbl__v lo = xc, hi = xc, b, h, d2x, d2y;
        xl = sbl__load(r->x[c] + x - 1);
        xr = sbl__load(r->x[c] + x + 1);
        d2x = sbl__sel(okx, sbl__sub(sbl__add(xl, xr), sbl__mul(two, xc)), zero);
        d2y = zero;
        if (R[0] && R[2])
            d2y = sbl__sel(oky, sbl__sub(sbl__add(sbl__load(R[0]->x[c] + x), sbl__load(R[2]->x[c] + x)),
                                         sbl__mul(two, xc)), zero);
        for (j = 0; j < 3; ++j) {
            int i;
            if (!R[j]) continue;
            for (i = 0; i < 3; ++i) {
                const sbl__v v = sbl__sel(m[j][i], sbl__load(R[j]->x[c] + x + i - 1), xc);
                lo = sbl__min(lo, v);
                hi = sbl__max(hi, v);
            }
        }
        b = sbl__mul(half, sbl__add(sbl__mul(sx, d2x), sbl__mul(sy, d2y)));
        /* at most half the 3x3 range (sbl__blur_terms) */
        h = sbl__mul(half, sbl__sub(hi, lo));
        b = sbl__min(sbl__max(b, sbl__sub(zero, h)), h);
        sum = sbl__add(sum, sbl__mul(b, b));
    }
    sbl__store(q + SBL__POOL_BB(ch) * SBL__POOL_COLS, sum);
}

/* The weight of the staged lanes (sbl__lanes_weight), into the chunk's plane W: a stage
   of its own, as its chain of divisions and a square root (t2, rho, the posterior, the
   weight) is long; in a loop of its own more vectors' chains overlap. */
SBL__INLINE void sbl__lanes_stage_weight(sbl__kernel *k, const sbl__lane_rows *W, const float *n_row,
                                         const float *nyrow, int x, int base, const int ch,
                                         const int full, const sbl__lane_edge *E, const int lean)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    float *const q = k->col[0] + (x - base) + SBL__CHUNK_POOL(ch); /* pool planes */
    const float *const qn = k->col[0] + (x - base) + SBL__CHUNK_COLN(ch); /* pairs per column */
    sbl__lane_stats st; /* the fields sbl__lanes_weight reads */
    const int mix = SBL_EVIDENCE_MIX && k->wp.evid_mix; /* 3.11: |x* - m|^2 and sh_R */
    sbl__v n_x, n_y, n_xc, nl, nr, cnt, w;
    sbl__lanes_lengths(k, n_row, nyrow, x, &n_x, &n_y, &n_xc);
    nl = full ? sbl__set1(3.0f) : sbl__load(qn - 1);
    nr = full ? sbl__set1(3.0f) : sbl__load(qn + 1);
    cnt = full ? sbl__set1(9.0f) : sbl__add(sbl__add(nl, sbl__load(qn)), nr);
    /* full (sbl__lanes_full): nine pairs */
    st.has_pairs = full ? sbl__true : sbl__gt(cnt, zero);
    st.two_pairs = full ? sbl__true : sbl__gt(cnt, one);
    st.inv_cnt = sbl__div(one, sbl__max(cnt, one));
    st.pool_r = sbl__load(k->pool_r + x);
    st.sev = k->wp.stereo_ev ? sbl__load(k->sev + x) : sbl__set1(0.0f);
    st.tail_t = k->wp.tail ? sbl__load(k->tail_t + x) : sbl__set1(0.0f);
    st.bessel = E ? E->bessel : sbl__set1(9.0f / 8.0f);
    st.lean_s = E ? E->lean_s : sbl__set1(8.0f / 7.0f);
    st.inv_n8 = E ? E->inv_n8 : sbl__set1(0.125f);
    st.evid_sh = mix ? sbl__evidence_shrink_lanes(k, x) : zero;
    if (k->wp.blur) { /* (a constant of the instance) */
        st.blur_b2 = sbl__load(q + SBL__POOL_BB(ch) * SBL__POOL_COLS);
        st.blur_g = sbl__load(q + SBL__POOL_BG(ch) * SBL__POOL_COLS);
    }
    w = sbl__lanes_weight(&k->wp, &st, mix ? sbl__load(q + SBL__POOL_DEV2(ch) * SBL__POOL_COLS) : zero,
                          sbl__load(q + SBL__POOL_S2(ch) * SBL__POOL_COLS),
                          sbl__load(q + SBL__POOL_PD2(ch) * SBL__POOL_COLS),
                          sbl__load(q + SBL__POOL_PV(ch) * SBL__POOL_COLS), n_xc, n_y, 0, ch, 1);
    if (k->wp.lean_restart) { /* (a constant of the instance) */
        /* the weight before the restart lean, for Eq. 5; the lean where some lane takes
           it (sbl__lanes_weight), then clamped as there */
        sbl__store(q + SBL__POOL_A2(ch) * SBL__POOL_COLS, w);
        if (!sbl__all(st.rl_off)) {
            sbl__v lw;
            sbl__lanes_lean_inputs(k, W, x, base, ch, E, lean, &st);
            /* the blur's instances are the ones behind a stereo blend (c > 0): there the
               texture counts 1 + c times (6.10) */
            lw = sbl__lanes_lean_restart(&st, st.rl_w, st.rl_vy, k->wp.blur, 1.0f + k->wp.shared_bias);
            w = sbl__sel(st.rl_off, st.rl_w, sbl__add(st.rl_w, sbl__mul(st.rl_f, sbl__sub(lw, st.rl_w))));
            w = sbl__min(sbl__max(sbl__max(w, sbl__set1(k->wp.alpha_min)), zero), one);
        }
    }
    sbl__store(q + SBL__POOL_W(ch) * SBL__POOL_COLS, w);
}

/* The blend and Eq. 5 of the staged lanes, with the weight of sbl__lanes_stage_weight
   (one for every channel). Eq. 5 counts the weight before the restart lean (plane A2)
   where that runs (wp.lean_restart); elsewhere that is the weight itself */
SBL__INLINE void sbl__lanes_stage_blend(sbl__kernel *k, const sbl__lane_rows *W,
                                        const float *n_row, const float *nyrow, int x, int base,
                                        const int ch, const int full)
{
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    const sbl__v cap = sbl__set1(k->n_cap), half = sbl__set1(0.5f);
    const float *const q = k->col[0] + (x - base) + SBL__CHUNK_POOL(ch); /* pool planes */
    sbl__v n_x, n_y, n_xc, w, w2, one_w, f_w, t, a_mean, a2_mean, one_m, den, n_out;
    sbl__m valid, hi_w;
    sbl__lanes_lengths(k, n_row, nyrow, x, &n_x, &n_y, &n_xc);
    /* full: every x* of the chunk valid (v = 1 exactly where N > 0): no reset lane */
    valid = full ? sbl__true : sbl__gt(n_x, zero);
    w = sbl__load(q + SBL__POOL_W(ch) * SBL__POOL_COLS);
    w2 = k->wp.lean_restart ? sbl__load(q + SBL__POOL_A2(ch) * SBL__POOL_COLS) : w; /* every channel's */
    /* Eq. 5 first (its values then leave the registers), then the blend */
    /* one weight for every channel: its mean is the weight itself (sbl__lanes_vector_fast) */
    a2_mean = w2;
    one_m = sbl__sub(one, a2_mean);
    den = sbl__add(sbl__mul(sbl__mul(one_m, one_m), n_y), sbl__mul(sbl__mul(a2_mean, a2_mean), n_xc));
    /* The guards on den (sbl__lanes_blend) fall away: in a valid lane n_xc, n_y >= 2^-40 (lane-safe N,
       a cap >= 1) and one of (1 - a)^2, a^2 is >= 1/4, so den >= 2^-42 (a normal float:
       > 0, > FLT_MIN); the other lanes take the select below */
    n_out = sbl__min(sbl__div(sbl__mul(n_xc, n_y), den), cap);
    sbl__store(k->stage_n + x, sbl__sel(valid, n_out, k->temporal ? one : n_y));
    t = sbl__load(q + SBL__POOL_FT(ch) * SBL__POOL_COLS); /* (<= 1: see sbl__lanes_vector_fast) */
    hi_w = sbl__gt(w, half);
    one_w = sbl__sub(one, w);
    /* the two-sided lerp: from the end the weight is nearer, by its factor (the same
       expression per lane as both lerps and a select). The factor is min(w, 1 - w), the
       select's value in one instruction (SSE2: a select is three): w is in [0, 1], not NaN
       (sbl__lanes_weight's clamp), and for w > 1/2 the subtraction is exact, 1 - w < w;
       else 1 - w >= 1/2 >= w, and at w = 1/2 both are 1/2 */
    f_w = sbl__min(w, one_w);
#define SBL__STAGE_BLEND(c) \
    do { \
        const sbl__v yc = sbl__load(W->y[1][c] + x), xs = sbl__load(W->x[1][c] + x); \
        const sbl__v yb = sbl__mul(yc, t); /* (sbl__lanes_stage_y's t) */ \
        sbl__v from, to, o; \
        SBL__SEL2(hi_w, yb, xs, from, to); \
        o = sbl__add(from, sbl__mul(f_w, sbl__sub(to, from))); \
        sbl__store(k->stage[c] + x, sbl__sel(valid, o, yc)); \
    } while (0)
    SBL__LANES_CH(SBL__STAGE_BLEND);
#undef SBL__STAGE_BLEND
    a_mean = w;
    sbl__store(k->stage_a + x, sbl__sel(valid, a_mean, one));
}
#undef SBL__LANES_CH

/* The image's border columns in the default configurations' lanes (fast 1: the temporal
   filter's two stages; 2: the stereo blend's sbl__lanes_vector_fast): the vector
   [x, x + VW) holding column 0 in its first lane (side 1) or column w - 1 in its last
   (side 2). The border lane's window has two columns (n = 6: the side column
   outside the image enters empty, sbl__lane_edge); the other lanes are interior pixels
   computed with the interior's constants, so they get the bits they already have. The
   pair terms are the blocks' (sbl__pool_lanes_blocks counts the column outside the
   image as one without pairs). Bit for bit the same on every build (the scalar build
   runs the same lanes, one wide). */
SBL__INLINE void sbl__lanes_edge(sbl__kernel *k, const sbl__lane_rows *W, const float *n_row,
                                 const float *nyrow, int x, int base, int y, const int ch, int side,
                                 const int rows, const int fast, const int mix, const int lean)
{
    /* rows: the window's rows (2 on the image's first and last rows: a corner's window
       holds 4 samples) */
    const float nc = SBL__CAST(float, rows), n9 = 3.0f * nc, n6 = 2.0f * nc;
    float nl[SBL__VW], nr[SBL__VW], inv_n[SBL__VW], inv_n8[SBL__VW], bessel[SBL__VW], lean_s[SBL__VW];
    const sbl__v zero = sbl__set1(0.0f);
    sbl__lane_edge E;
    int j;
    for (j = 0; j < SBL__VW; ++j) {
        const int edge = side == 1 ? j == 0 : j == SBL__VW - 1;
        const float n = edge ? n6 : n9;
        nl[j] = side == 1 && edge ? 0.0f : nc;
        nr[j] = side == 2 && edge ? 0.0f : nc;
        inv_n[j] = 1.0f / n;
        inv_n8[j] = 1.0f / (n - 1.0f);
        bessel[j] = n / (n - 1.0f);
        lean_s[j] = (n - 1.0f) / (n - 2.0f);
    }
    E.n_l = sbl__load(nl);
    E.n_r = sbl__load(nr);
    E.keep_l = sbl__gt(E.n_l, zero);
    E.keep_r = sbl__gt(E.n_r, zero);
    E.inv_n = sbl__load(inv_n);
    E.inv_n8 = sbl__load(inv_n8);
    E.bessel = sbl__load(bessel);
    E.lean_s = sbl__load(lean_s);
    if (fast == 1) {
        sbl__lanes_stage_y(k, W, n_row, x, base, ch, &E, mix, lean);
        sbl__lanes_stage_weight(k, W, n_row, nyrow, x, base, ch, 0, &E, lean);
        sbl__lanes_stage_blend(k, W, n_row, nyrow, x, base, ch, 0);
    } else {
        (void)mix;
        (void)lean;
        sbl__lanes_vector_fast(k, W, n_row, nyrow, x, base, y, ch, fast, 0, &E);
    }
}

SBL__INLINE int sbl__kernel_lanes_ch(const sbl__kernel *k_in, const sbl__ring_row *const *R,
                                     int x0, int x1, const int ch)
{
    /* a copy whose channel count is a constant in each instance below (the stages read
       k->ch): their channel loops unroll, with no plane pointer reloaded per channel */
    sbl__kernel k_ch = *k_in, *k = &k_ch;
    const int y = R[1]->row;
    const float *nyrow = (k->own_n && k->own_n->data) ? sbl__px(k->own_n, 0, y) : NULL;
    const int end = x0 + (x1 - x0) / SBL__VW * SBL__VW; /* whole vectors only */
    sbl__lane_rows W;
    int x = x0;
    k_ch.ch = ch;
    sbl__lane_rows_of(&W, R, ch);
    while (x < end) {
        /* one chunk: its column sums (with the neighbour columns), then its pixels */
        const int ca = x - 1, ce = end - x > SBL__CHUNK ? x + SBL__CHUNK : end;
        sbl__lanes_columns(k, &W, ca, ce + 1, ca);
        for (; x < ce; x += SBL__VW) sbl__lanes_vector(k, &W, R[1]->n, nyrow, x, ca, y, ch);
    }
    return x;
}

static int sbl__kernel_lanes(sbl__kernel *k, const sbl__ring_row *const *R, int x0, int x1)
{
    switch (k->ch) {
    case 1: return sbl__kernel_lanes_ch(k, R, x0, x1, 1);
    case 2: return sbl__kernel_lanes_ch(k, R, x0, x1, 2);
    case 3: return sbl__kernel_lanes_ch(k, R, x0, x1, 3);
    default: return sbl__kernel_lanes_ch(k, R, x0, x1, 4);
    }
}

/* Lane kernel over the pixels of [xa, xb) (interior columns of an interior row) whose
   3x3 window holds no unsafe value; the others are left to the reference path. A run
   of such pixels narrower than a vector is computed by a vector widened inside
   [la, lb) (loaded columns, at least 16 wide), whose extra lanes are either recomputed
   identically or overwritten by the reference path afterwards: lanes are independent,
   so no result depends on the vector width. */
/* The first of bytes [a, b) of p that is not 0, else b; eight bytes at a time. */
static int sbl__find_set(const unsigned char *p, int a, int b)
{
    for (; a + 8 <= b; a += 8) {
        uint64_t w;
        memcpy(&w, p + a, 8);
        if (w) break;
    }
    while (a < b && !p[a]) ++a;
    return a;
}

/* d[i] = a[i] | b[i] | c[i] for i in [0, n), eight bytes at a time. */
static void sbl__or3_bytes(unsigned char *d, const unsigned char *a, const unsigned char *b,
                           const unsigned char *c, int n)
{
    int i = 0;
    for (; i + 8 <= n; i += 8) {
        uint64_t u, v, w;
        memcpy(&u, a + i, 8);
        memcpy(&v, b + i, 8);
        memcpy(&w, c + i, 8);
        u |= v | w;
        memcpy(d + i, &u, 8);
    }
    for (; i < n; ++i) d[i] = SBL__CAST(unsigned char, a[i] | b[i] | c[i]);
}

static void sbl__kernel_lanes_runs(sbl__kernel *k, const sbl__ring_row *const *R, int xa,
                                   int xb, int la, int lb, const unsigned char *win)
{
    int a = xa;
    while (a < xb) {
        int b;
        if (win) {
            while (a < xb && win[a]) ++a;
            if (a >= xb) break;
            b = sbl__find_set(win, a + 1, xb);
        } else {
            b = xb;
        }
        if (b - a >= SBL__VW) {
            int e = sbl__kernel_lanes(k, R, a, b);
            /* the tail: one more vector ending at b, overlapping pixels already done
               (same values), so that every pixel takes the same float path */
            if (e < b) sbl__kernel_lanes(k, R, b - SBL__VW, b);
        } else {
            int s0 = a + SBL__VW <= lb ? a : lb - SBL__VW;
            if (s0 < la) s0 = la;
            sbl__kernel_lanes(k, R, s0, s0 + SBL__VW);
        }
        a = b;
    }
}

/* 1 if x* is valid on every column of [ca, cb) of the three rows, as far as their
   loads' invalid extents (sbl__ring_note_valid) tell; 0: not known */
SBL__INLINE int sbl__rows_valid_in(const sbl__ring_row *const *R, int ca, int cb)
{
    int j;
    for (j = 0; j < 3; ++j)
        if (!(R[j]->all_valid || cb <= R[j]->inv_lo || ca > R[j]->inv_hi)) return 0;
    return 1;
}

/* 1 if every window of the vector at index i of the chunk holds nine pairs (its columns
   i - 1 .. i + VW three each, so every x* of the vector valid too): it may take a full
   chunk's operations (sbl__lanes_vector_fast, the stages' full) */
SBL__INLINE int sbl__lanes_vec_full(const sbl__kernel *k, int i, const int ch)
{
    return sbl__cols_three_pairs(k->col[0] + i + SBL__CHUNK_COLN(ch));
}

/* The pooled estimator's prepass and the lane kernel in one pass over an interior row
   (the three ring rows exist). The prepass's column sums over three rows (pairs N,
   A = sum v (d - t), B, T) are the same operations on the same values as the lane
   kernel's (col_n, DA, DB, T: compare sbl__pool_lanes_columns with sbl__lanes_column),
   so each chunk sums its columns once, over the prepass's reach, and both read them: bit
   for bit what sbl__row_pool then sbl__kernel_lanes_runs give. Computes the ratio of
   pixels [pa, pb) (pb - pa >= 16), and the lanes of the pixels of [xa, xb) (inside
   [1, w - 1), within [pa, pb)) whose window is safe (win: 1 where it is not; NULL: all
   safe). As there, sums over unsafe values only reach pixels that the references
   recompute: the ratio of a pixel with an unsafe value within SBL__POOL_REACH
   (sbl__row_pool_ref, per chunk before its lanes), the lanes of a pixel with an unsafe
   window (sbl__kernel_pixel_ref, after the row). A run of the chunk narrower than a
   vector is covered by one inside [x - span, e + span) and [1, w - 1) (its column sums
   are computed); its extra pixels either take the lanes too (the same values: lanes are
   independent; one past the chunk is computed again by the next) or are recomputed by
   the reference path. */
SBL__INLINE void sbl__kernel_lanes_pooled_ch(sbl__kernel *k_in, const sbl__ring_row *const *R,
                                             int pa, int pb, int xa, int xb,
                                             const unsigned char *win, const int ch, const int cfg)
{
    /* cfg: fast (0, 1, 2), or 3 / 4: the temporal / stereo default (fast 1 / 2) on the
       image's first or last row (k->edge_row; R[0] or R[2] NULL); 5 / 6: 1 / 3 with the
       mix towards the paper's weight (k->wp.evid_mix, 3.11), which the others lack;
       7 .. 10: 1, 3, 5, 6 with the resampling blur's bias (k->wp.blur, 4.12) and the
       restart lean (behind a stereo blend, 6.10); 11 .. 14: 1, 3, 5, 6 with the restart
       lean alone (k->wp.lean_restart, 6.3) */
    const int erow = cfg == 3 || cfg == 4 || cfg == 6 || cfg == 8 || cfg == 10 || cfg == 12 || cfg == 14;
    const int fast = cfg == 3 || cfg >= 5 ? 1 : cfg == 4 ? 2 : cfg;
    const int mix = SBL_EVIDENCE_MIX && (cfg == 5 || cfg == 6 || cfg == 9 || cfg == 10 || cfg == 13 || cfg == 14);
    const int blur = cfg >= 7 && cfg <= 10;
    /* the restart lean (sbl__lanes_lean_inputs): 3 on the image's first or last row, 2 in a
       full chunk (below), else 1 */
    const int lean = cfg >= 11 || (blur && SBL__LEAN_RESTART_ON) ? (erow ? 3 : 1) : 0;
    /* the stereo default, per vector in a chunk that is not full: a vector whose blocks
       or windows hold only valid pairs takes the full chunk's operations (the same
       values). Not the column sums: under -ffast-math gcc reorders the full column's
       differences (x* - y, no select, no product by v) unlike the others', a last-bit
       change wherever a span's chunks start elsewhere than the whole run's
       (tests/test_paths.c, spans vs whole run), and their test per column vector cost
       more than it saved (callgrind, SSE2). Not the temporal default: its chunks that
       are not full hold few such vectors (hard: +7.6 instructions per pixel SSE2) */
    const int vfull = SBL__FULL_CHUNKS && fast == 2 && !erow;
    /* k: a copy with ch (and fast 1: wp.evid_mix) the instance's constants; it never
       escapes (the one call not inlined, sbl__row_pool_ref, takes k_in), so the compiler
       folds its fields' tests in the loops (the weight's of evid_mix too) */
    sbl__kernel k_ch = *k_in, *k = &k_ch;
    const int w = k->w, y = R[1]->row, reach = SBL__POOL_REACH;
#define SBL__POOLED_VECTOR(px) \
    do { \
        if (fast && (full || (vfull && sbl__lanes_vec_full(k, (px) - base, ch)))) \
            sbl__lanes_vector_fast(k, &W, n_row, nyrow, px, base, y, ch, fast, 1, Er); \
        else if (fast) sbl__lanes_vector_fast(k, &W, n_row, nyrow, px, base, y, ch, fast, 0, Er); \
        else sbl__lanes_vector(k, &W, n_row, nyrow, px, base, y, ch); \
    } while (0)
    /* the vectors of the run [lo, b): whole vectors, the last one ending at b; a run
       narrower than a vector: one vector ending at b, inside the chunk's columns */
#define SBL__RUN_VECTORS(stage) \
    do { \
        if (b - lo >= SBL__VW) { \
            for (p = lo; p + SBL__VW <= b; p += SBL__VW) stage; \
            if (p < b) { p = b - SBL__VW; stage; } \
        } else { \
            p = b - SBL__VW; \
            if (p < x - span) p = x - span; \
            if (p < 1) p = 1; \
            stage; \
        } \
    } while (0)
    const int span = SBL__POOL_STEP * SBL__POOL_BLOCKS;
    /* N_Y: the temporal filter's own sample is one frame (sbl_temporal_filter sets no
       own_n), so in its instances (fast 1) nyrow is the constant NULL and the stages'
       N_Y is 1 with no test per vector (sbl__lanes_lengths) */
    const float *nyrow = (fast != 1 && k->own_n && k->own_n->data) ? sbl__px(k->own_n, 0, y) : NULL;
    float *const pm = SBL__POOL_PLANE(k, SBL__POOL_M2(ch)), *const ps = SBL__POOL_PLANE(k, SBL__POOL_SE2(ch));
    const float *const n_row = R[1]->n;
    sbl__lane_rows W;
    sbl__pool_planes Q;
    sbl__pool_rows P;
    sbl__lane_edge E_row; /* erow: every lane's window has two rows */
    const sbl__lane_edge *const Er = erow ? &E_row : NULL;
    int x = pa, unsafe, x_prev = -1, x_prev_end = -1;
    k_ch.ch = ch;
    if (fast == 1) k_ch.wp.evid_mix = mix; /* (the other instances test it at run time) */
    if (fast) k_ch.temporal = fast == 1; /* (sbl__kernel_lanes_pooled: as k->wp.temporal) */
    k_ch.wp.blur = blur; /* (only the default configuration sets it: sbl_temporal_filter) */
    k_ch.wp.lean_restart = lean != 0; /* (likewise) */
    if (erow) {
        /* the missing row: the first row's window takes row 1 as its row 0 too, the
           last row's takes row 0 as its row 2 too; every sum then adds 0 for it (the
           differences of a sample to itself; sbl__lanes_column, sbl__lanes_y_channel)
           and the pairs leave it out of their count (sbl__lanes_columns_cfg) */
        const sbl__ring_row *RW[3];
        const sbl__v two = sbl__set1(2.0f);
        RW[0] = R[0] ? R[0] : R[1];
        RW[1] = R[1];
        RW[2] = R[2] ? R[2] : R[0];
        sbl__lane_rows_of(&W, RW, ch);
        E_row.keep_l = E_row.keep_r = sbl__gt(two, sbl__set1(0.0f));
        E_row.n_l = E_row.n_r = two;
        E_row.inv_n = sbl__set1(1.0f / 6.0f);
        E_row.inv_n8 = sbl__set1(1.0f / 5.0f);
        E_row.bessel = sbl__set1(6.0f / 5.0f);
        E_row.lean_s = sbl__set1(5.0f / 4.0f);
    } else {
        sbl__lane_rows_of(&W, R, ch);
    }
    sbl__pool_planes_of(k, ch, 0, &Q);
    unsafe = sbl__pool_rows_of(&P, R, ch, w, pa, pb);
    while (x < pb) {
        int e = pb - x > SBL__POOL_CHUNK ? x + SBL__POOL_CHUNK : pb, base, lo, hi, p, full;
        int carry;
        if (e - x < SBL__VW) x = e - SBL__VW; /* the last chunk: a whole vector, overlapping */
        /* carry: the chunk starts where the one before ended (its base x_prev - reach),
           whose column sums of [x - reach, x + reach) and blocks of [x - span, x + span)
           are this chunk's first ones (the same values: every column and block is
           computed alike whatever the chunk); they are moved to this chunk's indices
           instead of computed again (the default configurations' planes: no clamp box) */
        carry = fast && x == x_prev_end && x - reach >= 0 && w - (x + reach) >= SBL__VW + 1 &&
                e - x >= SBL__VW;
        if (carry) {
            const int shift = x - x_prev; /* index of a column in the previous chunk, less its index here */
            int c, j;
            float *const col0 = k->col[0];
            for (c = 0; c < ch; ++c)
                for (j = SBL__COL_A; j <= SBL__COL_DB; ++j) {
                    float *const d = col0 + SBL__CHUNK_COL(c) + j * SBL__CHUNK_COLS;
                    memcpy(d, d + shift, sizeof(float[2 * SBL__POOL_REACH]));
                }
            {
                float *const d = col0 + SBL__CHUNK_COLN(ch);
                memcpy(d, d + shift, sizeof(float[2 * SBL__POOL_REACH]));
            }
            {
                /* the blocks' planes (sbl__pool_lanes_blocks with pairs) */
                const int planes[4] = {SBL__POOL_M2(ch), SBL__POOL_SE2(ch), SBL__POOL_PD2(ch), SBL__POOL_PV(ch)};
                for (j = 0; j < 4; ++j) {
                    float *const d = SBL__POOL_PLANE(k, planes[j]) + (reach - span);
                    memcpy(d, d + shift, sizeof(float[2 * SBL__POOL_STEP * SBL__POOL_BLOCKS]));
                }
            }
        }
        x_prev = x;
        x_prev_end = e;
        base = x - reach;
        {
            /* the chunk's columns [ha, cb), of which [ca, cb) are computed (carry: the rest
               moved), and its blocks [ba, bb) computed */
            const int ha = x - reach > 0 ? x - reach : 0, ca = carry ? x + reach : ha;
            const int cb = e + reach < w ? e + reach : w;
            const int ba = carry ? x + span : x - span > 0 ? x - span : 0, bb = e + span < w ? e + span : w;
            /* every pair of the chunk's columns valid: the instances without the selects
               on the pair validity (the same values); the blocks centred on the image's
               first and last columns (whose outer column is empty) excepted */
            full = SBL__FULL_CHUNKS && !erow &&
                   (k->rows_valid || sbl__rows_valid_in(R, ha, cb) || sbl__lanes_full(&W, ha, cb));
            if (full) sbl__lanes_columns_cfg(k, &W, ca, cb, base, fast, 1, 0);
            else sbl__lanes_columns_cfg(k, &W, ca, cb, base, fast, 0, erow);
            if (x - reach < 0) sbl__pool_column_zero(&Q, ch, -1 - base);
            if (e + reach > w) sbl__pool_column_zero(&Q, ch, w - base);
            if (full) {
                int fa = ba, fb = bb;
                if (ba == 0) { sbl__pool_lanes_blocks(k, &Q, ch, 0, SBL__VW, base, 0, fast, 0, 0); fa = 1; }
                if (bb == w) { sbl__pool_lanes_blocks(k, &Q, ch, w - SBL__VW, w, base, 0, fast, 0, 0); fb = w - 1; }
                sbl__pool_lanes_blocks(k, &Q, ch, fa, fb, base, 0, fast, 1, 0);
            } else {
                sbl__pool_lanes_blocks(k, &Q, ch, ba, bb, base, 0, fast, 0, vfull);
            }
        }
        for (p = x - span; p < 0; ++p) pm[p - base] = ps[p - base] = 0.0f;
        for (p = w; p < e + span; ++p) pm[p - base] = ps[p - base] = 0.0f;
        sbl__pool_lanes_ratio(k, ch, x, e, base);
        if (unsafe) {
            int ra, rb;
            for (p = x; p < e && sbl__pool_unsafe_run(&P, w, p, e, &ra, &rb); p = rb)
                sbl__row_pool_ref(k_in, R, ra, rb); /* (k_in: see k) */
        }
        /* the chunk's lanes: each run of safe windows in whole vectors, the last one
           ending at the run's end */
        lo = x > xa ? x : xa;
        hi = e < xb ? e : xb;
        while (lo < hi) {
            int b = hi;
            if (win) {
                while (lo < hi && win[lo]) ++lo;
                if (lo >= hi) break;
                b = sbl__find_set(win, lo + 1, hi);
            }
            if (fast == 1) {
                /* two stages over the run's vectors (sbl__lanes_stage_y) */
                SBL__RUN_VECTORS(sbl__lanes_stage_y(k, &W, n_row, p, base, ch, Er, mix, lean));
                if (blur) SBL__RUN_VECTORS(sbl__lanes_stage_blur(k_in, R, p, base, ch));
                if (full) {
                    SBL__RUN_VECTORS(sbl__lanes_stage_weight(k, &W, n_row, nyrow, p, base, ch, 1, Er, lean ? 2 : 0));
                    SBL__RUN_VECTORS(sbl__lanes_stage_blend(k, &W, n_row, nyrow, p, base, ch, 1));
                } else {
                    SBL__RUN_VECTORS(sbl__lanes_stage_weight(k, &W, n_row, nyrow, p, base, ch, 0, Er, lean));
                    SBL__RUN_VECTORS(sbl__lanes_stage_blend(k, &W, n_row, nyrow, p, base, ch, 0));
                }
            } else {
                SBL__RUN_VECTORS(SBL__POOLED_VECTOR(p));
            }
            lo = b;
        }
        /* the image's border columns (sbl__kernel_run_span asked: their windows are safe) */
        if (fast && (k->edge_ask & 1) && x == 0) {
            if (blur) sbl__lanes_stage_blur(k_in, R, 0, base, ch);
            sbl__lanes_edge(k, &W, n_row, nyrow, 0, base, y, ch, 1, erow ? 2 : 3, fast, mix, lean);
        }
        if (fast && (k->edge_ask & 2) && e == w) {
            if (blur) sbl__lanes_stage_blur(k_in, R, w - SBL__VW, base, ch);
            sbl__lanes_edge(k, &W, n_row, nyrow, w - SBL__VW, base, y, ch, 2, erow ? 2 : 3, fast, mix, lean);
        }
        x = e;
    }
#undef SBL__POOLED_VECTOR
#undef SBL__RUN_VECTORS
}

/* ---- dim values in the default configurations' lanes ----------------------------
   A pixel is flagged unsafe at load for any value outside [2^-40, 2^50) (sbl__lane_value_ok),
   and its 3x3 window then takes the reference path. The 2^-40 serves one purpose: every
   nonzero difference of two such values is a multiple of 2^-63, so its square is a
   normal float. But the default configurations' lanes (the pooled estimator, no
   rectification, one weight: sbl__lanes_vector_fast and the staged temporal lanes) read
   the window's values only through these differences: each column's y - y_top (its
   three rows), the top row's y - y_top_centre (the window's shift), and each pair's
   x* - y; the rest are plain sums of values (means, the firefly sums) and products of
   those differences. So a window whose flagged pixels hold only dim values (normal
   floats below 2^-40) keeps the lanes when every one of those differences that involves
   a flagged pixel is itself 0 or within [2^-40, 2^50): the lanes then see exactly the
   kind of numbers the lane range guarantees (tests/test_paths.c: a dim value by bright
   neighbours, within 1e-4 of the reference). Non-finite, huge or denormal values, an
   unsafe N, and any other configuration keep the reference path. A rule on the input
   alone, the same on every build. */

/* 1 if v is 0 or a normal float below 2^50 in magnitude (a value the differences may
   make lane-safe); inf, NaN, huge and denormal values are not */
static int sbl__lane_value_dim_ok(float v)
{
    unsigned int bits, e;
    memcpy(&bits, &v, sizeof bits);
    e = (bits >> 23) & 0xffu;
    return (bits & 0x7fffffffu) == 0u || e - 1u < 176u;
}

/* 1 if a - b, rounded as the lanes round it, is in the lane range */
static int sbl__lane_diff_ok(float a, float b)
{
    volatile float d = a - b; /* no contraction, no excess precision */
    return sbl__lane_value_ok(d);
}

/* Pixel x of ring row r, flagged at load: 1 if its values are 0 or normal below 2^50,
   its own N as sbl__ring_load_own asks, and (x* valid) its N lane-safe and every pair's
   difference x* - y in the lane range. */
static int sbl__lane_pixel_dim_ok(const sbl__kernel *k, const sbl__ring_row *r, int x)
{
    int c;
    if (k->own_n && k->own_n->data) {
        const float n = *sbl__px(k->own_n, x, r->row);
        if (sbl__step_of(k->own_n) != 1 || !sbl__lane_value_ok(n) || !(n <= 1048576.0f)) return 0;
    }
    for (c = 0; c < k->ch; ++c)
        if (!sbl__lane_value_dim_ok(r->y[c][x])) return 0;
    if (r->v[x] > 0.0f) {
        if (!sbl__lane_value_ok(r->n[x])) return 0;
        for (c = 0; c < k->ch; ++c)
            if (!sbl__lane_value_dim_ok(r->x[c][x]) || !sbl__lane_diff_ok(r->x[c][x], r->y[c][x]))
                return 0;
    }
    return 1;
}

/* 1 if the window of pixel x (interior; R[0..2] exist) may take the default
   configurations' lanes (above); its flagged pixels are the ones to check. */
static int sbl__lane_window_dim_ok(const sbl__kernel *k, const sbl__ring_row *const *R, int x)
{
    const unsigned char *top = R[0]->unsafe;
    int i, j, c;
    for (i = x - 1; i <= x + 1; ++i) {
        const int f0 = top[i], f1 = R[1]->unsafe[i], f2 = R[2]->unsafe[i];
        if (!(f0 | f1 | f2)) continue;
        for (j = 0; j < 3; ++j)
            if (R[j]->unsafe[i] && !sbl__lane_pixel_dim_ok(k, R[j], i)) return 0;
        /* the column about its top sample */
        for (c = 0; c < k->ch; ++c) {
            const float y0 = R[0]->y[c][i];
            if ((f0 | f1) && !sbl__lane_diff_ok(R[1]->y[c][i], y0)) return 0;
            if ((f0 | f2) && !sbl__lane_diff_ok(R[2]->y[c][i], y0)) return 0;
        }
    }
    /* the top row about the window's shift, its top-centre sample */
    for (i = x - 1; i <= x + 1; i += 2)
        if (top[i] | top[x])
            for (c = 0; c < k->ch; ++c)
                if (!sbl__lane_diff_ok(R[0]->y[c][i], R[0]->y[c][x])) return 0;
    return 1;
}

/* The default configurations' lanes (sbl__kernel_lanes_pooled's fast instances). */
static int sbl__kernel_fast(const sbl__kernel *k)
{
    return k->wp.estimator == SBL_ESTIMATOR_POOLED && !k->fill &&
           k->wp.rectify == SBL_RECTIFY_NONE && k->wp.mode == SBL_WEIGHT_SCALAR;
}

/* Clears the window flags of pixels [xa, xb) whose window sbl__lane_window_dim_ok admits. */
static void sbl__lane_windows_dim(const sbl__kernel *k, const sbl__ring_row *const *R,
                                  unsigned char *win, int xa, int xb)
{
    int x;
    for (x = sbl__find_set(win, xa, xb); x < xb; x = sbl__find_set(win, x + 1, xb))
        if (sbl__lane_window_dim_ok(k, R, x)) win[x] = 0;
}

/* one function per channel count and configuration (fast: 1 temporal default, 2 stereo
   default, 0 any other; 3 / 4 their first and last rows; 5 / 6: 1 / 3 with the mix of
   3.11, whose runtime test in the loops cost the temporal default 5.9 instructions per
   pixel where it is off: callgrind, SSE2), each compiled by itself */
#define SBL__POOLED_INSTANCE(chn, f) \
    SBL__NOINLINE void sbl__kernel_lanes_pooled_##chn##_##f( \
        sbl__kernel *k, const sbl__ring_row *const *R, int pa, int pb, int xa, int xb, \
        const unsigned char *win) \
    { \
        sbl__kernel_lanes_pooled_ch(k, R, pa, pb, xa, xb, win, chn, f); \
    }
SBL__POOLED_INSTANCE(1, 0) SBL__POOLED_INSTANCE(2, 0) SBL__POOLED_INSTANCE(3, 0) SBL__POOLED_INSTANCE(4, 0)
SBL__POOLED_INSTANCE(1, 1) SBL__POOLED_INSTANCE(2, 1) SBL__POOLED_INSTANCE(3, 1) SBL__POOLED_INSTANCE(4, 1)
SBL__POOLED_INSTANCE(1, 2) SBL__POOLED_INSTANCE(2, 2) SBL__POOLED_INSTANCE(3, 2) SBL__POOLED_INSTANCE(4, 2)
SBL__POOLED_INSTANCE(1, 3) SBL__POOLED_INSTANCE(2, 3) SBL__POOLED_INSTANCE(3, 3) SBL__POOLED_INSTANCE(4, 3)
SBL__POOLED_INSTANCE(1, 4) SBL__POOLED_INSTANCE(2, 4) SBL__POOLED_INSTANCE(3, 4) SBL__POOLED_INSTANCE(4, 4)
#if SBL_EVIDENCE_MIX
SBL__POOLED_INSTANCE(1, 5) SBL__POOLED_INSTANCE(2, 5) SBL__POOLED_INSTANCE(3, 5) SBL__POOLED_INSTANCE(4, 5)
SBL__POOLED_INSTANCE(1, 6) SBL__POOLED_INSTANCE(2, 6) SBL__POOLED_INSTANCE(3, 6) SBL__POOLED_INSTANCE(4, 6)
SBL__POOLED_INSTANCE(1, 9) SBL__POOLED_INSTANCE(2, 9) SBL__POOLED_INSTANCE(3, 9) SBL__POOLED_INSTANCE(4, 9)
SBL__POOLED_INSTANCE(1, 10) SBL__POOLED_INSTANCE(2, 10) SBL__POOLED_INSTANCE(3, 10) SBL__POOLED_INSTANCE(4, 10)
#endif
/* the resampling blur's bias (4.12) and the restart lean (6.10): the temporal default
   behind a stereo blend */
SBL__POOLED_INSTANCE(1, 7) SBL__POOLED_INSTANCE(2, 7) SBL__POOLED_INSTANCE(3, 7) SBL__POOLED_INSTANCE(4, 7)
SBL__POOLED_INSTANCE(1, 8) SBL__POOLED_INSTANCE(2, 8) SBL__POOLED_INSTANCE(3, 8) SBL__POOLED_INSTANCE(4, 8)
/* the restart lean alone (6.3): the temporal default without a stereo blend behind */
SBL__POOLED_INSTANCE(1, 11) SBL__POOLED_INSTANCE(2, 11) SBL__POOLED_INSTANCE(3, 11) SBL__POOLED_INSTANCE(4, 11)
SBL__POOLED_INSTANCE(1, 12) SBL__POOLED_INSTANCE(2, 12) SBL__POOLED_INSTANCE(3, 12) SBL__POOLED_INSTANCE(4, 12)
#if SBL_EVIDENCE_MIX
SBL__POOLED_INSTANCE(1, 13) SBL__POOLED_INSTANCE(2, 13) SBL__POOLED_INSTANCE(3, 13) SBL__POOLED_INSTANCE(4, 13)
SBL__POOLED_INSTANCE(1, 14) SBL__POOLED_INSTANCE(2, 14) SBL__POOLED_INSTANCE(3, 14) SBL__POOLED_INSTANCE(4, 14)
#endif
#undef SBL__POOLED_INSTANCE

static void sbl__kernel_lanes_pooled(sbl__kernel *k, const sbl__ring_row *const *R, int pa,
                                     int pb, int xa, int xb, const unsigned char *win)
{
    /* the default configuration in its own instances (sbl__lanes_vector_fast) */
    const int fast = sbl__kernel_fast(k);
    k->pool_row = R[1]->row;
    k->edge_done = fast ? k->edge_ask : 0; /* sbl__lanes_edge */
    if (fast && k->wp.temporal && k->wp.blur) {
        /* the blur's instances (a compile-time flag: the others keep their code) */
        const int cfg = (k->edge_row ? 8 : 7) + (SBL_EVIDENCE_MIX && k->wp.evid_mix ? 2 : 0);
        switch (k->ch * 16 + cfg) {
        case 16 + 7: sbl__kernel_lanes_pooled_1_7(k, R, pa, pb, xa, xb, win); break;
        case 32 + 7: sbl__kernel_lanes_pooled_2_7(k, R, pa, pb, xa, xb, win); break;
        case 48 + 7: sbl__kernel_lanes_pooled_3_7(k, R, pa, pb, xa, xb, win); break;
        case 16 + 8: sbl__kernel_lanes_pooled_1_8(k, R, pa, pb, xa, xb, win); break;
        case 32 + 8: sbl__kernel_lanes_pooled_2_8(k, R, pa, pb, xa, xb, win); break;
        case 48 + 8: sbl__kernel_lanes_pooled_3_8(k, R, pa, pb, xa, xb, win); break;
        case 64 + 8: sbl__kernel_lanes_pooled_4_8(k, R, pa, pb, xa, xb, win); break;
#if SBL_EVIDENCE_MIX
        case 16 + 9: sbl__kernel_lanes_pooled_1_9(k, R, pa, pb, xa, xb, win); break;
        case 32 + 9: sbl__kernel_lanes_pooled_2_9(k, R, pa, pb, xa, xb, win); break;
        case 48 + 9: sbl__kernel_lanes_pooled_3_9(k, R, pa, pb, xa, xb, win); break;
        case 64 + 9: sbl__kernel_lanes_pooled_4_9(k, R, pa, pb, xa, xb, win); break;
        case 16 + 10: sbl__kernel_lanes_pooled_1_10(k, R, pa, pb, xa, xb, win); break;
        case 32 + 10: sbl__kernel_lanes_pooled_2_10(k, R, pa, pb, xa, xb, win); break;
        case 48 + 10: sbl__kernel_lanes_pooled_3_10(k, R, pa, pb, xa, xb, win); break;
        case 64 + 10: sbl__kernel_lanes_pooled_4_10(k, R, pa, pb, xa, xb, win); break;
#endif
        default: sbl__kernel_lanes_pooled_4_7(k, R, pa, pb, xa, xb, win); break;
        }
    } else if (fast && k->wp.temporal && k->wp.lean_restart) {
        /* the restart lean's instances (as the blur's) */
        const int cfg = (k->edge_row ? 12 : 11) + (SBL_EVIDENCE_MIX && k->wp.evid_mix ? 2 : 0);
        switch (k->ch * 16 + cfg) {
        case 16 + 11: sbl__kernel_lanes_pooled_1_11(k, R, pa, pb, xa, xb, win); break;
        case 32 + 11: sbl__kernel_lanes_pooled_2_11(k, R, pa, pb, xa, xb, win); break;
        case 48 + 11: sbl__kernel_lanes_pooled_3_11(k, R, pa, pb, xa, xb, win); break;
        case 16 + 12: sbl__kernel_lanes_pooled_1_12(k, R, pa, pb, xa, xb, win); break;
        case 32 + 12: sbl__kernel_lanes_pooled_2_12(k, R, pa, pb, xa, xb, win); break;
        case 48 + 12: sbl__kernel_lanes_pooled_3_12(k, R, pa, pb, xa, xb, win); break;
        case 64 + 12: sbl__kernel_lanes_pooled_4_12(k, R, pa, pb, xa, xb, win); break;
#if SBL_EVIDENCE_MIX
        case 16 + 13: sbl__kernel_lanes_pooled_1_13(k, R, pa, pb, xa, xb, win); break;
        case 32 + 13: sbl__kernel_lanes_pooled_2_13(k, R, pa, pb, xa, xb, win); break;
        case 48 + 13: sbl__kernel_lanes_pooled_3_13(k, R, pa, pb, xa, xb, win); break;
        case 64 + 13: sbl__kernel_lanes_pooled_4_13(k, R, pa, pb, xa, xb, win); break;
        case 16 + 14: sbl__kernel_lanes_pooled_1_14(k, R, pa, pb, xa, xb, win); break;
        case 32 + 14: sbl__kernel_lanes_pooled_2_14(k, R, pa, pb, xa, xb, win); break;
        case 48 + 14: sbl__kernel_lanes_pooled_3_14(k, R, pa, pb, xa, xb, win); break;
        case 64 + 14: sbl__kernel_lanes_pooled_4_14(k, R, pa, pb, xa, xb, win); break;
#endif
        default: sbl__kernel_lanes_pooled_4_11(k, R, pa, pb, xa, xb, win); break;
        }
    } else if (k->edge_row && !k->wp.temporal) {
        /* the image's first or last row (only the default configurations come here) */
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_4(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_4(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_4(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_4(k, R, pa, pb, xa, xb, win); break;
        }
#if SBL_EVIDENCE_MIX
    } else if (k->edge_row && k->wp.evid_mix) {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_6(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_6(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_6(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_6(k, R, pa, pb, xa, xb, win); break;
        }
    } else if (fast && k->wp.temporal && k->wp.evid_mix) {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_5(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_5(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_5(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_5(k, R, pa, pb, xa, xb, win); break;
        }
#endif
    } else if (k->edge_row) {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_3(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_3(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_3(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_3(k, R, pa, pb, xa, xb, win); break;
        }
    } else if (fast && k->wp.temporal) {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_1(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_1(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_1(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_1(k, R, pa, pb, xa, xb, win); break;
        }
    } else if (fast) {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_2(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_2(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_2(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_2(k, R, pa, pb, xa, xb, win); break;
        }
    } else {
        switch (k->ch) {
        case 1: sbl__kernel_lanes_pooled_1_0(k, R, pa, pb, xa, xb, win); break;
        case 2: sbl__kernel_lanes_pooled_2_0(k, R, pa, pb, xa, xb, win); break;
        case 3: sbl__kernel_lanes_pooled_3_0(k, R, pa, pb, xa, xb, win); break;
        default: sbl__kernel_lanes_pooled_4_0(k, R, pa, pb, xa, xb, win); break;
        }
    }
}

/* Ring row r just loaded over [xa, xb): notes whether its x* is valid on every column
   (v is 0 or 1), so that the lanes need not look chunk by chunk (sbl__lanes_full). */
static void sbl__ring_note_valid(sbl__ring_row *r, int xa, int xb)
{
    /* from the left in blocks of four vectors (one test per block), then the block
       that holds the first invalid x* a column at a time; the same from the right */
    const sbl__v half = sbl__set1(0.5f);
    const float *v = r->v;
    int x = xa, j;
    for (; x + 4 * SBL__VW <= xb; x += 4 * SBL__VW) {
        sbl__v m = sbl__min(sbl__min(sbl__load(v + x), sbl__load(v + x + SBL__VW)),
                            sbl__min(sbl__load(v + x + 2 * SBL__VW), sbl__load(v + x + 3 * SBL__VW)));
        if (!sbl__all(sbl__gt(m, half))) break;
    }
    while (x < xb && v[x] > 0.5f) ++x;
    r->inv_lo = x;
    r->inv_hi = xa - 1;
    r->all_valid = x >= xb;
    if (r->all_valid) return;
    for (x = xb; x - 4 * SBL__VW > r->inv_lo; x -= 4 * SBL__VW) {
        j = x - 4 * SBL__VW;
        if (!sbl__all(sbl__gt(sbl__min(sbl__min(sbl__load(v + j), sbl__load(v + j + SBL__VW)),
                                       sbl__min(sbl__load(v + j + 2 * SBL__VW),
                                                sbl__load(v + j + 3 * SBL__VW))),
                              half)))
            break;
    }
    while (x - 1 > r->inv_lo && v[x - 1] > 0.5f) --x;
    r->inv_hi = x - 1;
}

/* Filter columns [x0, x1) of rows [y0, y1) into k->out (and out_n / out_a); nothing
   else of the outputs is written. Every written pixel equals the one a whole-image run
   gives, bit for bit: the ring holds the columns [x0 - 1, x1 + 1) (clamped), widened
   to 18 inside the image when the span is narrower, so that a whole vector fits. */
/* Prefetch, for writing, pixels [x0, x1) of row y of an output view (none: data NULL). */
static void sbl__prefetch_row_w(const sbl_image *im, int y, int x0, int x1)
{
    if (im->data) {
        const float *row = sbl__px(im, x0, y);
        const ptrdiff_t n = SBL__CAST(ptrdiff_t, x1 - x0) * sbl__step_of(im);
        ptrdiff_t o;
        for (o = 0; o < n; o += SBL__LINE_FLOATS) SBL__PREFETCH_W(row, o);
    }
}

static void sbl__stereo_evidence_row(sbl__kernel *k, const sbl__ring_row *r, int y, int x0,
                                     int x1); /* (with the stereo reprojection, below) */

static void sbl__kernel_run_span(sbl__kernel *k, int y0, int y1, int x0, int x1)
{
    /* rows narrower than the widest vector (plus the two border pixels) take the
       reference path on every build, so that no build depends on its vector width */
    const int lanes_w = k->w - 2 >= 16;
    int y, x, j, la = x0, lb = x1, xa, xb;
    if (x0 < 0) x0 = 0;
    if (x1 > k->w) x1 = k->w;
    if (y0 >= y1 || x0 >= x1) return;
    /* lane columns: the span's interior part, widened to 16 inside [1, w - 1) */
    xa = x0 > 1 ? x0 : 1;
    xb = x1 < k->w - 1 ? x1 : k->w - 1;
    la = xa; lb = xb;
    if (lanes_w && lb - la < 16) {
        lb = la + 16;
        if (lb > k->w - 1) { lb = k->w - 1; la = lb - 16; }
    }
    {   /* ring columns: the lane columns and the span, each with its neighbours */
        int ra = (la < x0 ? la : x0) - 1, rb = (lb > x1 ? lb : x1) + 1;
        /* pooled estimator: sbl__row_pool computes [pa, pb) and reads further */
        const int pool = k->wp.estimator == SBL_ESTIMATOR_POOLED && !k->fill;
        const int pa = lanes_w && la < x0 ? la : x0, pb = lanes_w && lb > x1 ? lb : x1;
        if (!lanes_w) { ra = x0 - 1; rb = x1 + 1; }
        if (pool) { ra = pa - SBL__POOL_REACH; rb = pb + SBL__POOL_REACH; }
        if (ra < 0) ra = 0;
        if (rb > k->w) rb = k->w;
        for (j = 0; j < 3; ++j) {
            int ry = y0 - 1 + j;
            k->ring[j].row = -1;
            if (ry >= 0 && ry < k->h) {
                sbl__ring_load(k, &k->ring[j], ry, ra, rb);
                sbl__ring_note_valid(&k->ring[j], ra, rb);
            }
        }
        for (y = y0; y < y1; ++y) {
            const sbl__ring_row *R[3];
            /* the default configurations' lanes also compute the image's border columns
               (sbl__lanes_edge): a span of only those (xa == xb) takes them too, as the
               whole row does */
            const int fast_pool = pool && sbl__kernel_fast(k);
            const int lanes_ok = lanes_w && y > 0 && y + 1 < k->h && (xa < xb || fast_pool);
            /* the image's first or last row (of at least two) in the default
               configurations' lanes, with a two-row window (k->edge_row,
               sbl__kernel_lanes_pooled_ch) */
            const int erow = lanes_w && !lanes_ok && (y == 0 || y + 1 == k->h) && k->h >= 2 &&
                             fast_pool;
            const unsigned char *win = NULL;
            for (j = 0; j < 3; ++j) R[j] = k->ring[j].row >= 0 ? &k->ring[j] : NULL;
            k->edge_row = erow ? (y == 0 ? 1 : 2) : 0;
            if (lanes_ok || erow) {
                /* the window's rows (erow: the missing one is an existing one again, as
                   sbl__kernel_lanes_pooled_ch takes it) */
                const sbl__ring_row *r0 = R[0] ? R[0] : R[1], *r2 = R[2] ? R[2] : R[0];
                if (r0->unsafe_count | R[1]->unsafe_count | r2->unsafe_count) {
                    /* per pixel: 1 if any of the nine values of its window is unsafe (per
                       column over its three rows, then over three columns) */
                    unsigned char *cu = k->column_unsafe;
                    sbl__or3_bytes(cu + xa - 1, r0->unsafe + xa - 1, R[1]->unsafe + xa - 1,
                                   r2->unsafe + xa - 1, xb - xa + 2);
                    sbl__or3_bytes(k->window_unsafe + xa, cu + xa - 1, cu + xa, cu + xa + 1, xb - xa);
                    win = k->window_unsafe;
                    /* dim values the default configurations' lanes can take (interior
                       rows; the border rows' flagged windows keep the reference) */
                    if (lanes_ok && pool && sbl__kernel_fast(k))
                        sbl__lane_windows_dim(k, R, k->window_unsafe, xa, xb);
                }
            }
            /* the image's border columns in lanes (the default configurations) where
               their two-column window is safe (sbl__lanes_edge) */
            k->edge_ask = k->edge_done = 0;
            if ((lanes_ok || erow) && pool && sbl__kernel_fast(k)) {
                const unsigned char *cu = win ? k->column_unsafe : NULL;
                if (x0 == 0 && !(cu && (cu[0] | cu[1]))) k->edge_ask |= 1;
                if (x1 == k->w && !(cu && (cu[k->w - 2] | cu[k->w - 1]))) k->edge_ask |= 2;
            }
            if (k->tail_on) sbl__tail_prepare(k, y, ra, rb);
            if (pool && k->evid_out) sbl__evidence_gather(k, y, pa, pb);
            if (pool && k->evid_out) sbl__evidence_share(k, y); /* 3.10 */
            if (k->sev) sbl__stereo_evidence_row(k, R[1], y, x0, x1); /* 6.15 */
            if (pool && lanes_ok) {
                /* an interior row: prepass and lanes share their column sums */
                k->rows_valid = R[0]->all_valid & R[1]->all_valid & R[2]->all_valid;
                sbl__kernel_lanes_pooled(k, R, pa, pb, xa, xb, win);
                k->rows_valid = 0;
            } else if (erow) {
                sbl__kernel_lanes_pooled(k, R, pa, pb, xa, xb, win);
            } else {
                if (pool) sbl__row_pool(k, R, pa, pb);
                if (lanes_ok) sbl__kernel_lanes_runs(k, R, xa, xb, la, lb, win);
            }
            k->edge_row = 0;
            if (!lanes_ok && !erow) {
                for (x = x0; x < x1; ++x) sbl__kernel_pixel_ref(k, R, x);
            } else {
                /* the reference path: the span's border columns, and inside [xa, xb)
                   the pixels whose window holds an unsafe value */
                for (x = x0; x < xa; ++x)
                    if (!(k->edge_done & 1)) sbl__kernel_pixel_ref(k, R, x);
                if (win)
                    for (x = sbl__find_set(win, xa, xb); x < xb; x = sbl__find_set(win, x + 1, xb))
                        sbl__kernel_pixel_ref(k, R, x);
                for (x = xb; x < x1; ++x)
                    if (!(k->edge_done & 2)) sbl__kernel_pixel_ref(k, R, x);
            }
            {   /* interleave the staged row into the outputs */
                const float *const *stage = SBL__PCAST(const float *const *, k->stage);
                sbl__interleave(sbl__px(&k->out, 0, y), sbl__step_of(&k->out), k->ch, stage, x0, x1);
                if (y + 1 < y1) { /* the next row's output lines, for writing */
                    sbl__prefetch_row_w(&k->out, y + 1, x0, x1);
                    sbl__prefetch_row_w(&k->out_n, y + 1, x0, x1);
                    sbl__prefetch_row_w(&k->out_e, y + 1, x0, x1);
                }
                if (k->out_n.data)
                    sbl__interleave(sbl__px(&k->out_n, 0, y), sbl__step_of(&k->out_n), 1,
                                    SBL__PCAST(const float *const *, &k->stage_n), x0, x1);
                if (k->out_a.data)
                    sbl__interleave(sbl__px(&k->out_a, 0, y), sbl__step_of(&k->out_a), 1,
                                    SBL__PCAST(const float *const *, &k->stage_a), x0, x1);
                if (k->out_e.data) sbl__evidence_store(k, y, x0, x1, pool);
                if (k->out_tail.data) sbl__tail_store(k, y, x0, x1);
            }
            {   /* advance the ring: drop row y-1, load row y+2 */
                sbl__ring_row t = k->ring[0];
                k->ring[0] = k->ring[1];
                k->ring[1] = k->ring[2];
                k->ring[2] = t;
                k->ring[2].row = -1;
                if (y + 1 < y1 && y + 2 < k->h) {
                    sbl__ring_load(k, &k->ring[2], y + 2, ra, rb);
                    sbl__ring_note_valid(&k->ring[2], ra, rb);
                }
            }
        }
    }
}

/* Filter rows [y0, y1) into k->out (and out_n / out_a). */
static void sbl__kernel_run(sbl__kernel *k, int y0, int y1)
{
    sbl__kernel_run_span(k, y0, y1, 0, k->w);
}

/* ------------------------------------------------------------------------ */
/* 7. Temporal filter                                                       */
/* ------------------------------------------------------------------------ */

SBLDEF sbl_temporal_desc sbl_temporal_defaults(const sbl_temporal_desc *desc)
{
    sbl_temporal_desc d;
    if (desc) d = *desc;
    else memset(&d, 0, sizeof d);
    if (sbl__is_zero(d.constant_alpha)) d.constant_alpha = 0.1f;
    if (sbl__is_zero(d.max_history)) d.max_history = 64.0f;
    if (sbl__is_zero(d.clip_gamma)) d.clip_gamma = 1.25f;
    if (sbl__is_zero(d.bias_threshold)) d.bias_threshold = 3.0f;
    /* 0 stays 0 here (no stereo stage): sbl_stereo_temporal_frame makes it 1 */
    if (d.stereo_shared_bias == SBL_SHARED_BIAS_NONE) d.stereo_shared_bias = 0.0f;
    d.reproject = sbl__reproject_defaults(&d.reproject);
    return d;
}

SBLDEF size_t sbl_temporal_scratch_size(int width, int channels)
{
    const size_t kb = sbl__kernel_scratch_size(width, channels);
    /* + the evidence plane's rows: evid_in, evid_out, and three more (the ring rows'
       planes where the plane is gathered in the colour's plan, else its own gather's
       x / n / v) (floats) and unsafe (bytes) */
    /* + the tail plane's rows (2.4): three ring rows' x[0] / x[1] / n / v and unsafe,
       tail_r / tail_t / tail_e / tail_d */
    return kb ? kb + (5 * sizeof(float) + 1) * sbl__plane_floats(width) + 64 +
                    (16 * sizeof(float) + 3) * sbl__plane_floats(width) + 64 : 0;
}

SBLDEF sbl_result sbl_temporal_filter(const sbl_temporal_desc *user_desc,
                                      const sbl_frame *frame, const sbl_history *history,
                                      const sbl_temporal_output *out, int y0, int y1,
                                      void *scratch, size_t scratch_bytes)
{
    sbl_temporal_desc d;
    sbl__temporal_rp s, es, ts;
    sbl__kernel k;
    sbl_result r;
    int w, h, ch, default_cfg; /* the default configuration (the restart lean, the blur) */
    if (!user_desc || !frame || !out) return SBL_ERROR_NULL_POINTER;
    d = sbl_temporal_defaults(user_desc);
    if ((r = sbl__check_image(&frame->color, 0)) != SBL_OK) return r;
    w = frame->color.width;
    h = frame->color.height;
    ch = frame->color.channels;
    if ((r = sbl__check_image(&out->color, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&out->length, 1)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&out->alpha, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&out->evidence, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&out->tail, 2, w, h)) != SBL_OK) return r;
    if (history && history->color.data &&
        ((r = sbl__check_optional(&history->evidence, 1, w, h)) != SBL_OK ||
         (r = sbl__check_optional(&history->tail, 2, w, h)) != SBL_OK))
        return r;
    if (out->color.width != w || out->color.height != h || out->length.width != w ||
        out->length.height != h)
        return SBL_ERROR_SIZE_MISMATCH;
    if (out->color.channels != ch) return SBL_ERROR_CHANNEL_MISMATCH;
    /* the display needs every row filtered first: sbl_temporal_filter_frame, or
       sbl_temporal_display once every band is done */
    if (out->display.data) return SBL_ERROR_INVALID_PARAM;
    if ((r = sbl__check_weight_params(d.estimator, d.rectify, d.weight_mode,
                                      d.constant_alpha, d.alpha_min, d.clip_gamma,
                                      d.bias_threshold)) != SBL_OK)
        return r;
    if (!sbl__finite(d.max_history) || d.max_history < 1.0f) return SBL_ERROR_INVALID_PARAM;
    if (d.stereo_shared_bias == SBL_SHARED_BIAS_NONE) d.stereo_shared_bias = 0.0f;
    if (!sbl__param_ok(d.stereo_shared_bias) || d.stereo_shared_bias > 1.0f)
        return SBL_ERROR_INVALID_PARAM;
    if ((r = sbl__temporal_rp_init(&s, &d.reproject, d.source, frame, history)) != SBL_OK)
        return r;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    {   /* outputs: disjoint from each other and from every input */
        const sbl_image *outs[SBL__PLANES_MAX];
        int o, p, n = sbl__temporal_output_planes(out, outs);
        for (o = 0; o < n; ++o)
            for (p = o + 1; p < n; ++p)
                if (sbl__overlap(outs[o], outs[p])) return SBL_ERROR_OVERLAP;
        for (o = 0; o < n; ++o)
            if (sbl__overlaps_temporal_inputs(outs[o], frame, s.history, 1))
                return SBL_ERROR_OVERLAP;
    }
    if (!scratch) return SBL_ERROR_NULL_POINTER;
    /* 0 = too wide to size (sbl__check_image accepts up to INT_MAX / 4) */
    if (sbl_temporal_scratch_size(w, ch) == 0) return SBL_ERROR_INVALID_SIZE;
    if (scratch_bytes < sbl_temporal_scratch_size(w, ch)) return SBL_ERROR_SCRATCH_TOO_SMALL;

    memset(&k, 0, sizeof k);
    k.w = w; k.h = h; k.ch = ch;
    k.wp = sbl__weight_params_make(d.estimator, d.rectify, d.weight_mode, d.constant_alpha,
                                   d.alpha_min, d.clip_gamma, d.bias_threshold);
    k.wp.temporal = 1;
    k.wp.shared_bias = d.stereo_shared_bias;
    /* the restart lean (docs/ESTIMATORS.md 6.3, 6.4): the default configuration alone,
       with the bilinear fetch it was measured with; behind a stereo blend too (6.10: its
       gate then reads the weight without the blur's term, and the texture, a bias both
       eyes' leans share, counts 1 + c times), where the blur's instances hold it. Not
       with SBL_LEAN_TEMPORAL, whose lean everywhere returns before the restart lean's
       lane terms are set. */
    default_cfg = d.estimator == SBL_ESTIMATOR_POOLED && d.rectify == SBL_RECTIFY_NONE &&
                  d.weight_mode == SBL_WEIGHT_SCALAR && s.history && !s.src.cubic;
    k.wp.lean_restart = SBL__LEAN_RESTART_ON && default_cfg;
    /* the resampling blur's bias (docs/ESTIMATORS.md 4.12): behind a stereo blend, in
       the default configuration (its lanes: sbl__kernel_lanes_pooled's blur instances),
       for the bilinear fetch (Catmull-Rom reproduces quadratics: no second-order blur).
       The lean's condition (less SBL__LEAN_RESTART_ON) plus c > 0, which the lanes
       rely on: the blur's instances hold the lean where SBL__LEAN_RESTART_ON and count
       its texture 1 + c times (wp.blur), where the reference path reads lean_restart
       and shared_bias */
    if (d.stereo_shared_bias > 0.0f && default_cfg) {
        k.wp.blur = 1;
        k.blur_rp = &s;
    }
    k.n_cap = d.max_history;
    k.temporal = 1;
    k.own = &frame->color;
    k.own_n = NULL;
    k.gather = sbl__temporal_rp_pixel;
    k.gather_ctx = &s;
#ifdef SBL__ROW_GATHER
    /* the Catmull-Rom fetch exists only in the per-pixel gather (sbl__gather_cubic) */
    if (s.history && sbl__row_gather_ok(&s.src) && !s.src.cubic)
        k.gather_row = sbl__temporal_rp_row;
#endif
    k.out = out->color;
    k.out_n = out->length;
    k.out_a = out->alpha;
    sbl__kernel_bind(&k, scratch);
    {   /* evidence carried over frames (pooled): the history's plane gathered like the
           colour, with its taps and tests, bilinear (as N); the output plane */
        k.out_e = out->evidence;
        if (s.history && s.history->evidence.data) {
            es = s;
            es.src.color = sbl__flatten(&s.history->evidence);
            es.src.cubic = 0;
            k.evid_ctx = &es;
            k.evid_use = 1;
            k.evid_prev = &s.history->evidence; /* its rows' share of change (3.10) */
        }
        if (k.evid_use || k.out_e.data) {
            const size_t pf = sbl__plane_floats(w);
            float *e = SBL__PCAST(float *, sbl__align64(SBL__PCAST(char *, scratch) +
                                                         sbl__kernel_scratch_size(w, ch)));
            k.evid_buf = k.evid_in = e;
            k.evid_out = e + pf;
            k.evid_ring.x[0] = e + 2 * pf;
            k.evid_ring.n = e + 3 * pf;
            k.evid_ring.v = e + 4 * pf;
            k.evid_ring.unsafe = SBL__PCAST(unsigned char *, e + 5 * pf);
            k.evid_ring.row = -1;
#ifdef SBL__ROW_GATHER
            k.evid_row = k.evid_use && k.gather_row && sbl__row_gather_ok(&es.src);
            if (k.evid_row && sbl__evidence_fused_ok(&s.src, &es.src)) {
                /* in the colour's plan: the ring rows carry the plane (its second-pass
                   planes x / n / v serve as their three) */
                int j;
                k.evid_fused = 1;
                k.gather_row = sbl__temporal_rp_row_ev;
                /* every row the ring loads, the halo rows above and below [y0, y1)
                   too: a row's colour then comes from the same code whichever band
                   loads it. (-ffast-math lets the compiler reassociate the tap sums
                   differently in the instances with and without the plane: with the
                   plane on the band's own rows only, a banded call's halo rows
                   differed from the whole-frame call's in the last bit: session 11) */
                k.evid_y0 = 0;
                k.evid_y1 = h;
                for (j = 0; j < 3; ++j) {
                    k.ring[j].e_plane = e + SBL__CAST(size_t, 2 + j) * pf;
                    k.ring[j].e_rp = &es;
                }
            }
#endif
        }
    }
    k.out_tail = out->tail;
    if ((d.estimator == SBL_ESTIMATOR_ROBUST || d.estimator == SBL_ESTIMATOR_POOLED) &&
        (k.out_tail.data || (s.history && s.history->tail.data))) {
        /* the firefly limit's exceedances carried over frames (2.4): the history's
           plane gathered like the colour (as the evidence plane, in a plan of its own) */
        const size_t pf = sbl__plane_floats(w);
        char *e_end = SBL__PCAST(char *, sbl__align64(SBL__PCAST(char *, scratch) + sbl__kernel_scratch_size(w, ch))) +
                      5 * pf * sizeof(float) + pf; /* past the evidence plane's rows */
        float *t = SBL__PCAST(float *, sbl__align64(e_end));
        int j;
        k.tail_on = 1;
        for (j = 0; j < 3; ++j) {
            k.tail_ring[j].x[0] = t + SBL__CAST(size_t, 4 * j) * pf;
            k.tail_ring[j].x[1] = t + SBL__CAST(size_t, 4 * j + 1) * pf;
            k.tail_ring[j].n = t + SBL__CAST(size_t, 4 * j + 2) * pf;
            k.tail_ring[j].v = t + SBL__CAST(size_t, 4 * j + 3) * pf;
            k.tail_ring[j].unsafe = SBL__PCAST(unsigned char *, t + 16 * pf) + SBL__CAST(size_t, j) * pf;
            k.tail_ring[j].row = -1;
        }
        k.tail_r = t + 12 * pf;
        k.tail_t = t + 13 * pf;
        k.tail_e = t + 14 * pf;
        k.tail_d = t + 15 * pf;
        k.tail_xa = k.tail_xb = -1;
        /* a history plane of zeros only (nothing ever exceeded: most content without
           fireflies) reads as no plane: the gather of zeros gives zeros, the limit's
           share rho / (1 + rho) is then 0 and the floors are 0, so the outputs are the
           same; one pass over the plane's bits, with an early exit */
        if (s.history && s.history->tail.data && sbl__plane_nonzero(&s.history->tail)) {
            ts = s;
            ts.src.color = sbl__flatten(&s.history->tail);
            ts.src.cubic = 0;
            k.tail_ctx = &ts;
            k.tail_use = 1;
            k.wp.tail = 1;
            k.wp.tail_ch = SBL__CAST(float, ch);
#ifdef SBL__ROW_GATHER
            /* in the colour's plan, as the evidence plane: the ring rows carry the plane
               (tail_ring's rate and variance planes serve as theirs), on every row the
               ring loads; else (laid out otherwise) sbl__tail_gather_row's own gather */
            if (k.gather_row && sbl__row_gather_ok(&ts.src) && sbl__tail_fused_ok(&s.src, &ts.src)) {
                k.tail_fused = 1;
                k.gather_row = sbl__temporal_rp_row_ev;
                for (j = 0; j < 3; ++j) {
                    k.ring[j].tl_plane[0] = k.tail_ring[j].x[0];
                    k.ring[j].tl_plane[1] = k.tail_ring[j].x[1];
                    k.ring[j].tl_rp = &ts;
                }
            }
#endif
        }
    }
    sbl__kernel_run(&k, y0, y1);
    return SBL_OK;
}

/* The display lean (docs/ESTIMATORS.md 6.7). */
#ifndef SBL_DISPLAY_LEAN_MAX_N
#define SBL_DISPLAY_LEAN_MAX_N 3.0
#endif

/* The checks of sbl_temporal_display (before sbl_temporal_filter_frame filters) */
static sbl_result sbl__display_check(const sbl_frame *frame, const sbl_temporal_output *filtered,
                                     const sbl_image *display)
{
    sbl_result r;
    int w, h;
    if (!frame || !filtered) return SBL_ERROR_NULL_POINTER;
    if ((r = sbl__check_image(&frame->color, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&filtered->color, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&filtered->length, 1)) != SBL_OK) return r;
    if ((r = sbl__check_image(display, 0)) != SBL_OK) return r;
    w = frame->color.width;
    h = frame->color.height;
    if (filtered->color.width != w || filtered->color.height != h || filtered->length.width != w ||
        filtered->length.height != h || display->width != w || display->height != h)
        return SBL_ERROR_SIZE_MISMATCH;
    if (filtered->color.channels != frame->color.channels ||
        display->channels != frame->color.channels)
        return SBL_ERROR_CHANNEL_MISMATCH;
    if (sbl__overlap(display, &frame->color) || sbl__overlap(display, &filtered->color) ||
        sbl__overlap(display, &filtered->length) ||
        (filtered->alpha.data && sbl__overlap(display, &filtered->alpha)) ||
        (filtered->evidence.data && sbl__overlap(display, &filtered->evidence)) ||
        (filtered->tail.data && sbl__overlap(display, &filtered->tail)))
        return SBL_ERROR_OVERLAP;
    return SBL_OK;
}

/* The noise variance of one sample, summed over the channels, from the differences of
   adjacent samples in a 3x3 window: half their mean square along each of four
   directions (rows, columns, both diagonals), the smallest of the four. A straight edge
   or ramp through the window leaves the differences along it clean, so the edge is not
   read as noise (the window's plain variance is, and the lean would then cross the
   edge: tests/test_accuracy.c test_display_lean). Under pure noise the smallest of the
   four is 0.537 of the variance (Gaussian, 4e5 windows): SBL__DISPLAY_NOISE_SCALE undoes
   it. v: the window's samples, row-major, ch channels each; ok: which are values. */
#define SBL__DISPLAY_NOISE_SCALE (1.0 / 0.537)
static double sbl__display_noise(const double *v, const unsigned char *ok, int ch)
{
    /* the window's adjacent pairs: 6 along rows, 6 along columns, 4 + 4 diagonal */
    static const unsigned char pa[20] = {0, 1, 3, 4, 6, 7, 0, 1, 2, 3, 4, 5, 0, 1, 3, 4, 1, 2, 4, 5};
    static const unsigned char pb[20] = {1, 2, 4, 5, 7, 8, 3, 4, 5, 6, 7, 8, 4, 5, 7, 8, 3, 4, 6, 7};
    static const unsigned char first[5] = {0, 6, 12, 16, 20};
    double sum = 0.0;
    int c, k, q;
    for (c = 0; c < ch; ++c) {
        double best = -1.0;
        for (k = 0; k < 4; ++k) {
            double s2 = 0.0;
            int n = 0;
            for (q = first[k]; q < first[k + 1]; ++q)
                if (ok[pa[q]] && ok[pb[q]]) {
                    const double dv = v[pb[q] * ch + c] - v[pa[q] * ch + c];
                    s2 += dv * dv;
                    ++n;
                }
            if (n > 0 && (best < 0.0 || s2 < best * 2.0 * n)) best = s2 / (2.0 * n);
        }
        if (best > 0.0) sum += best;
    }
    return sum * SBL__DISPLAY_NOISE_SCALE;
}

/* Rows y - 1, y, y + 1 of the samples, the outputs and their N (NULL outside the image) */
typedef struct sbl__display_rows {
    const float *sample[3], *out[3], *length[3];
    int sample_step, out_step, length_step, width, channels;
} sbl__display_rows;

/* The reference display of one young pixel x (N = n, output t finite) into d, which
   holds t already (double; every window: borders, values that are not) */
static void sbl__display_pixel(const sbl__display_rows *r, int x, double n, const float *t,
                               float *d)
{
    const int ch = r->channels;
    double sv[36], m8[4] = {0.0, 0.0, 0.0, 0.0}, q8[4] = {0.0, 0.0, 0.0, 0.0};
    double v, vs, inv_nb = 0.0, vnb, v8u = 0.0, vm, a;
    unsigned char ok[9];
    int n8 = 0, c, i, j;
    /* the window: the samples (for the noise), the neighbours' outputs and N */
    for (j = 0; j < 3; ++j)
        for (i = 0; i < 3; ++i) {
            const int xi = x + i - 1, q = 3 * j + i;
            const float *sp, *tn;
            float nn;
            ok[q] = 0;
            if (!r->sample[j] || xi < 0 || xi >= r->width) continue;
            sp = r->sample[j] + SBL__CAST(ptrdiff_t, xi) * r->sample_step;
            if (!sbl__any_nonfinite(sp, ch)) {
                ok[q] = 1;
                for (c = 0; c < ch; ++c) sv[q * ch + c] = SBL__CAST(double, sp[c]);
            }
            if (q == 4) continue;
            tn = r->out[j] + SBL__CAST(ptrdiff_t, xi) * r->out_step;
            nn = r->length[j][SBL__CAST(ptrdiff_t, xi) * r->length_step];
            if (sbl__any_nonfinite(tn, ch) || !sbl__finite(nn) || !(nn > 0.0f)) continue;
            for (c = 0; c < ch; ++c) {
                m8[c] += SBL__CAST(double, tn[c]);
                q8[c] += SBL__CAST(double, tn[c]) * SBL__CAST(double, tn[c]);
            }
            inv_nb += nn > 1.0f ? 1.0 / SBL__CAST(double, nn) : 1.0;
            ++n8;
        }
    if (n8 < 3) return;
    /* the samples' noise; the output's is that over its N, a neighbour's over its own N
       (the centre's window stands for theirs) */
    vs = sbl__display_noise(sv, ok, ch);
    v = vs / (n > 1.0 ? n : 1.0);
    vnb = vs * inv_nb / n8;
    for (c = 0; c < ch; ++c) {
        /* the neighbours' sample variance (n8 - 1) */
        double dv;
        m8[c] /= n8;
        dv = (q8[c] - n8 * m8[c] * m8[c]) / (n8 - 1);
        if (dv > 0.0) v8u += dv;
    }
    /* V_M: the texture (the neighbours' spread beyond their noise) and the noise of
       their mean */
    vm = (v8u > vnb ? v8u - vnb : 0.0) + vnb / n8;
    if (!(v + vm > 0.0)) return; /* (finite: sums of squares of floats) */
    a = v / (v + vm);
    for (c = 0; c < ch; ++c)
        d[c] = SBL__CAST(float, SBL__CAST(double, t[c]) + a * (m8[c] - SBL__CAST(double, t[c])));
}

/* The lanes: the windows of up to SBL__VW young pixels inside the image, then the
   display of all of them in float over the SIMD layer: the reference's formula, the
   variance in two passes. A lane whose sums are not finite (a value that is not, or so
   large that a square overflows) or that has a neighbour without N > 0 takes the
   reference instead, so at the magnitudes of any render the lanes and the reference
   differ by float rounding only. (Differences so small that their squares near the
   smallest normal float, below about 1e-16, lose precision in the lanes' noise: the lean
   is weaker or none there.)
   The windows reach the lanes two ways. Young pixels here and there are copied lane by
   lane (sbl__display_lane_put). A run of SBL__VW young pixels side by side (a
   disocclusion, a first frame) shares most of its windows' values: the run's three rows
   are deinterleaved once (sbl__display_run_put) and each window value is then one
   unaligned load at an offset: 3 (SBL__VW + 2) copies per value and channel where lane
   by lane takes 9 SBL__VW (a half with four lanes, three eighths with sixteen). */
typedef struct sbl__display_lanes {
    float sample[36 * SBL__VW]; /* value (3 j + i) * 4 + c: channel c at (x + i - 1, y + j - 1) */
    float out[36 * SBL__VW];    /* the outputs, the same layout (q = 4: the pixel's own) */
    float length[9 * SBL__VW];  /* their N */
    float *dst[SBL__VW];
    int x[SBL__VW], count;
} sbl__display_lanes;

/* Where the lanes' window values are: value (j, i, c) of lane 0 at s[j * vj + c * vc + i *
   vi] (samples), the same offsets in t (outputs), N at n[j * nj + i * ni]; lane l at + l */
typedef struct sbl__display_win {
    const float *s, *t, *n;
    int vj, vc, vi, nj, ni;
} sbl__display_win;

/* A run's rows deinterleaved: channel c of row j, pixels x - 1 .. x + SBL__VW */
#define SBL__DISPLAY_RUN (SBL__VW + 2)
typedef struct sbl__display_run {
    float sample[12 * SBL__DISPLAY_RUN], out[12 * SBL__DISPLAY_RUN], length[3 * SBL__DISPLAY_RUN];
    float *dst[SBL__VW];
    int x[SBL__VW];
} sbl__display_run;

/* One pixel's window into the next lane (x inside: 0 < x < width - 1, rows present);
   ch a constant where it is inlined */
SBL__INLINE void sbl__display_lane_put(sbl__display_lanes *l, const sbl__display_rows *r, int x,
                                       float *d, int ch)
{
    const int lane = l->count++;
    int i, j, q4 = 0;
    for (j = 0; j < 3; ++j) {
        const float *sp = r->sample[j] + SBL__CAST(ptrdiff_t, x - 1) * r->sample_step;
        const float *tn = r->out[j] + SBL__CAST(ptrdiff_t, x - 1) * r->out_step;
        const float *nn = r->length[j] + SBL__CAST(ptrdiff_t, x - 1) * r->length_step;
        for (i = 0; i < 3; ++i) {
            float *ls = l->sample + q4 * SBL__VW + lane, *lo = l->out + q4 * SBL__VW + lane;
            /* (the channels spelt out: -O2 does not unroll a loop that grows the code) */
            ls[0] = sp[0];
            lo[0] = tn[0];
            if (ch > 1) { ls[SBL__VW] = sp[1]; lo[SBL__VW] = tn[1]; }
            if (ch > 2) { ls[2 * SBL__VW] = sp[2]; lo[2 * SBL__VW] = tn[2]; }
            if (ch > 3) { ls[3 * SBL__VW] = sp[3]; lo[3 * SBL__VW] = tn[3]; }
            l->length[q4 / 4 * SBL__VW + lane] = *nn;
            q4 += 4;
            sp += r->sample_step;
            tn += r->out_step;
            nn += r->length_step;
        }
    }
    l->x[lane] = x;
    l->dst[lane] = d;
}

/* The rows of the run of SBL__VW young pixels x .. x + SBL__VW - 1 (all inside),
   deinterleaved; d: the first one's display, ds its pixel step */
SBL__INLINE void sbl__display_run_put(sbl__display_run *u, const sbl__display_rows *r, int x,
                                      float *d, int ds, int ch)
{
    int i, j;
    for (j = 0; j < 3; ++j) {
        const float *sp = r->sample[j] + SBL__CAST(ptrdiff_t, x - 1) * r->sample_step;
        const float *tn = r->out[j] + SBL__CAST(ptrdiff_t, x - 1) * r->out_step;
        const float *nn = r->length[j] + SBL__CAST(ptrdiff_t, x - 1) * r->length_step;
        float *us = u->sample + 4 * j * SBL__DISPLAY_RUN, *uo = u->out + 4 * j * SBL__DISPLAY_RUN;
        float *un = u->length + j * SBL__DISPLAY_RUN;
        for (i = 0; i < SBL__DISPLAY_RUN; ++i) {
            us[i] = sp[0];
            uo[i] = tn[0];
            if (ch > 1) { us[SBL__DISPLAY_RUN + i] = sp[1]; uo[SBL__DISPLAY_RUN + i] = tn[1]; }
            if (ch > 2) { us[2 * SBL__DISPLAY_RUN + i] = sp[2]; uo[2 * SBL__DISPLAY_RUN + i] = tn[2]; }
            if (ch > 3) { us[3 * SBL__DISPLAY_RUN + i] = sp[3]; uo[3 * SBL__DISPLAY_RUN + i] = tn[3]; }
            un[i] = *nn;
            sp += r->sample_step;
            tn += r->out_step;
            nn += r->length_step;
        }
    }
    for (i = 0; i < SBL__VW; ++i) {
        u->x[i] = x + i;
        u->dst[i] = d + SBL__CAST(ptrdiff_t, i) * ds;
    }
}

/* The display of `count` lanes' pixels (windows where w says), written to dst[].
   Inlined into its two callers so that each layout's window offsets are constants. */
SBL__INLINE void sbl__display_lanes_run(const sbl__display_win *w, int count, float *const *dst,
                                        const int *xs, const sbl__display_rows *r)
{
    const int ch = r->channels, vw = SBL__VW;
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    sbl__v ok = one, vs = zero, all = zero, v8u = zero, inv_nb = zero, nsum = zero, m8[4];
    sbl__v n, v, vnb, vm, den, a;
    float shown[4 * SBL__VW]; /* the display, channel c at [c * SBL__VW + l] */
    float full[SBL__VW];      /* 1: every neighbour has N > 0 */
    float check[SBL__VW];     /* a sum of the lane's sums: finite if they all are */
    int c, k, q;
#define SBL__DWS(q, c) (w->s + (q) / 3 * w->vj + (c) * w->vc + (q) % 3 * w->vi)
#define SBL__DWT(q, c) (w->t + (q) / 3 * w->vj + (c) * w->vc + (q) % 3 * w->vi)
#define SBL__DWN(q) (w->n + (q) / 3 * w->nj + (q) % 3 * w->ni)
    for (q = 0; q < 9; ++q)
        if (q != 4) {
            /* a neighbour's N: > 0 (else the reference leaves it out), finite (nsum) */
            const sbl__v nq = sbl__load(SBL__DWN(q));
            ok = sbl__min(ok, sbl__sel(sbl__gt(nq, zero), one, zero));
            nsum = sbl__add(nsum, nq);
            inv_nb = sbl__add(inv_nb, sbl__div(one, sbl__max(nq, one)));
        }
    for (c = 0; c < ch; ++c) {
        sbl__v s[9], t[9], dv, rs, cs, ds, as, sum, sq;
        for (q = 0; q < 9; ++q) {
            s[q] = sbl__load(SBL__DWS(q, c));
            t[q] = sbl__load(SBL__DWT(q, c));
        }
#define SBL__DSQ(acc, p, q0) (dv = sbl__sub(s[p], s[q0]), acc = sbl__add(acc, sbl__mul(dv, dv)))
        /* the adjacent pairs: the rows, the columns, the diagonal, the anti-diagonal */
        rs = cs = ds = as = zero;
        SBL__DSQ(rs, 1, 0); SBL__DSQ(rs, 2, 1); SBL__DSQ(rs, 4, 3);
        SBL__DSQ(rs, 5, 4); SBL__DSQ(rs, 7, 6); SBL__DSQ(rs, 8, 7);
        SBL__DSQ(cs, 3, 0); SBL__DSQ(cs, 4, 1); SBL__DSQ(cs, 5, 2);
        SBL__DSQ(cs, 6, 3); SBL__DSQ(cs, 7, 4); SBL__DSQ(cs, 8, 5);
        SBL__DSQ(ds, 4, 0); SBL__DSQ(ds, 5, 1); SBL__DSQ(ds, 7, 3); SBL__DSQ(ds, 8, 4);
        SBL__DSQ(as, 3, 1); SBL__DSQ(as, 4, 2); SBL__DSQ(as, 6, 4); SBL__DSQ(as, 7, 5);
#undef SBL__DSQ
        /* (a min can drop a NaN: the sum of all four keeps it, for the test below) */
        all = sbl__add(all, sbl__add(sbl__add(rs, cs), sbl__add(ds, as)));
        /* half the mean square: 12 row or column pairs, 8 diagonal ones */
        vs = sbl__add(vs, sbl__min(sbl__mul(sbl__min(rs, cs), sbl__set1(1.0f / 12.0f)),
                                   sbl__mul(sbl__min(ds, as), sbl__set1(1.0f / 8.0f))));
        /* the neighbours' mean and sample variance (two passes: no cancellation) */
        sum = sbl__add(sbl__add(sbl__add(t[0], t[1]), sbl__add(t[2], t[3])),
                       sbl__add(sbl__add(t[5], t[6]), sbl__add(t[7], t[8])));
        m8[c] = sbl__mul(sum, sbl__set1(0.125f));
        sq = zero;
        for (q = 0; q < 9; ++q)
            if (q != 4) {
                dv = sbl__sub(t[q], m8[c]);
                sq = sbl__add(sq, sbl__mul(dv, dv));
            }
        v8u = sbl__add(v8u, sbl__mul(sq, sbl__set1(1.0f / 7.0f)));
    }
    vs = sbl__mul(vs, sbl__set1(SBL__CAST(float, SBL__DISPLAY_NOISE_SCALE)));
    n = sbl__load(SBL__DWN(4));
    v = sbl__div(vs, sbl__max(n, one));
    vnb = sbl__mul(sbl__mul(vs, inv_nb), sbl__set1(0.125f));
    vm = sbl__add(sbl__max(sbl__sub(v8u, vnb), zero), sbl__mul(vnb, sbl__set1(0.125f)));
    den = sbl__add(v, vm);
    a = sbl__sel(sbl__gt(den, zero), sbl__div(v, sbl__max(den, sbl__set1(FLT_MIN))), zero);
    sbl__store(check, sbl__add(sbl__add(all, v8u), sbl__add(nsum, den)));
    for (c = 0; c < ch; ++c) {
        const sbl__v t = sbl__load(SBL__DWT(4, c));
        sbl__store(shown + c * vw, sbl__add(t, sbl__mul(a, sbl__sub(m8[c], t))));
    }
    sbl__store(full, ok);
    for (k = 0; k < count; ++k) {
        /* finite on the bits (immune to -ffast-math) */
        float *d = dst[k];
        int good = full[k] == 1.0f && sbl__finite(check[k]);
        for (c = 0; c < ch; ++c) good &= sbl__finite(shown[c * vw + k]);
        if (good) {
            for (c = 0; c < ch; ++c) d[c] = shown[c * vw + k];
        } else {
            float t[4];
            for (c = 0; c < ch; ++c) t[c] = SBL__DWT(4, c)[k];
            sbl__display_pixel(r, xs[k], SBL__CAST(double, SBL__DWN(4)[k]), t, d);
        }
    }
#undef SBL__DWS
#undef SBL__DWT
#undef SBL__DWN
}

/* The lanes' copied windows (l->count of them) through sbl__display_lanes_run */
static void sbl__display_lanes_flush(sbl__display_lanes *l, const sbl__display_rows *r)
{
    const int vw = SBL__VW;
    sbl__display_win w;
    int k, q;
    /* unused lanes repeat lane 0 (values, so that no lane reads memory not written) */
    for (k = l->count; k < vw; ++k) {
        for (q = 0; q < 36; ++q) {
            l->sample[q * vw + k] = l->sample[q * vw];
            l->out[q * vw + k] = l->out[q * vw];
        }
        for (q = 0; q < 9; ++q) l->length[q * vw + k] = l->length[q * vw];
    }
    w.s = l->sample;
    w.t = l->out;
    w.n = l->length;
    w.vj = 12 * vw; w.vc = vw; w.vi = 4 * vw;
    w.nj = 3 * vw; w.ni = vw;
    sbl__display_lanes_run(&w, l->count, l->dst, l->x, r);
    l->count = 0;
}

/* A deinterleaved run through sbl__display_lanes_run: lane l's window starts at offset l */
static void sbl__display_run_flush(const sbl__display_run *u, const sbl__display_rows *r)
{
    sbl__display_win w;
    w.s = u->sample;
    w.t = u->out;
    w.n = u->length;
    w.vj = 4 * SBL__DISPLAY_RUN; w.vc = SBL__DISPLAY_RUN; w.vi = 1;
    w.nj = SBL__DISPLAY_RUN; w.ni = 1;
    sbl__display_lanes_run(&w, SBL__VW, u->dst, u->x, r);
}

/* A pixel the display leans: a young history (0 < N <= nmax; N's finiteness on the bits,
   since the comparisons alone fold under -ffast-math) with an output that is a value */
SBL__INLINE int sbl__display_young(float n, const float *t, int ch, double nmax)
{
    return sbl__finite(n) && n > 0.0f && SBL__CAST(double, n) <= nmax && !sbl__any_nonfinite(t, ch);
}

SBLDEF sbl_result sbl_temporal_display(const sbl_display_desc *desc, const sbl_frame *frame,
                                       const sbl_temporal_output *filtered, sbl_image display,
                                       int y0, int y1)
{
    sbl_result r;
    sbl__display_rows rows;
    sbl__display_lanes lanes;
    sbl__display_run run;
    double nmax = SBL_DISPLAY_LEAN_MAX_N;
    float nmax_f;
    int x, y, c, j, w, h, ch, ts, ds, young_end;
    if (desc) {
        if (!sbl__finite(desc->max_length)) return SBL_ERROR_INVALID_PARAM;
        if (desc->max_length != 0.0f) nmax = SBL__CAST(double, desc->max_length);
    }
    if ((r = sbl__display_check(frame, filtered, &display)) != SBL_OK) return r;
    /* (rounding keeps the order, so the quick test in float never turns away a pixel
       the full test in double takes) */
    nmax_f = SBL__CAST(float, nmax);
    w = frame->color.width;
    h = frame->color.height;
    ch = frame->color.channels;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    rows.sample_step = sbl__step_of(&frame->color);
    rows.out_step = ts = sbl__step_of(&filtered->color);
    rows.length_step = sbl__step_of(&filtered->length);
    rows.width = w;
    rows.channels = ch;
    ds = sbl__step_of(&display);
    lanes.count = 0;
    for (y = y0; y < y1; ++y) {
        const float *trow = sbl__px(&filtered->color, 0, y), *nrow;
        float *drow = sbl__px(&display, 0, y);
        int inside;
        for (j = 0; j < 3; ++j) {
            const int yj = y + j - 1, in = yj >= 0 && yj < h;
            rows.sample[j] = in ? sbl__px(&frame->color, 0, yj) : NULL;
            rows.out[j] = in ? sbl__px(&filtered->color, 0, yj) : NULL;
            rows.length[j] = in ? sbl__px(&filtered->length, 0, yj) : NULL;
        }
        nrow = rows.length[1];
        inside = rows.sample[0] && rows.sample[2];
        /* most pixels are old: the row is copied, then its young pixels lean */
        if (ts == ch && ds == ch) {
            memcpy(drow, trow, SBL__CAST(size_t, w) * SBL__CAST(size_t, ch) * sizeof(float));
        } else {
            for (x = 0; x < w; ++x)
                for (c = 0; c < ch; ++c)
                    drow[SBL__CAST(ptrdiff_t, x) * ds + c] = trow[SBL__CAST(ptrdiff_t, x) * ts + c];
        }
        young_end = 0; /* pixels [x, young_end) are known young */
        for (x = 0; x < w; ++x) {
            const float nf = nrow[SBL__CAST(ptrdiff_t, x) * rows.length_step];
            const float *t;
            float *d;
            /* most pixels are old: one quick test of N first (the full test below reads
               N's bits, which -ffast-math cannot fold) */
            if (x >= young_end && !(nf > 0.0f && nf <= nmax_f)) continue;
            t = trow + SBL__CAST(ptrdiff_t, x) * ts;
            d = drow + SBL__CAST(ptrdiff_t, x) * ds;
            if (x >= young_end) {
                if (!sbl__display_young(nf, t, ch, nmax)) continue;
                if (!inside || x == 0 || x == w - 1) {
                    sbl__display_pixel(&rows, x, SBL__CAST(double, nf), t, d);
                    continue;
                }
                /* how far the young pixels reach (at most a run, inside the image) */
                for (young_end = x + 1; young_end < x + SBL__VW && young_end < w - 1; ++young_end)
                    if (!sbl__display_young(nrow[SBL__CAST(ptrdiff_t, young_end) * rows.length_step],
                                            trow + SBL__CAST(ptrdiff_t, young_end) * ts, ch, nmax))
                        break;
                if (young_end - x == SBL__VW && SBL__VW > 1) {
                    switch (ch) { /* one copy per channel count, its loops unrolled */
                    case 1: sbl__display_run_put(&run, &rows, x, d, ds, 1); break;
                    case 2: sbl__display_run_put(&run, &rows, x, d, ds, 2); break;
                    case 3: sbl__display_run_put(&run, &rows, x, d, ds, 3); break;
                    default: sbl__display_run_put(&run, &rows, x, d, ds, 4); break;
                    }
                    sbl__display_run_flush(&run, &rows);
                    x = young_end - 1;
                    continue;
                }
            }
            switch (ch) {
            case 1: sbl__display_lane_put(&lanes, &rows, x, d, 1); break;
            case 2: sbl__display_lane_put(&lanes, &rows, x, d, 2); break;
            case 3: sbl__display_lane_put(&lanes, &rows, x, d, 3); break;
            default: sbl__display_lane_put(&lanes, &rows, x, d, 4); break;
            }
            if (lanes.count == SBL__VW) sbl__display_lanes_flush(&lanes, &rows);
        }
        if (lanes.count) sbl__display_lanes_flush(&lanes, &rows); /* (rows: this row's) */
    }
    return SBL_OK;
}

SBLDEF sbl_result sbl_temporal_filter_frame(const sbl_temporal_desc *desc,
                                            const sbl_frame *frame,
                                            const sbl_history *history,
                                            const sbl_temporal_output *out)
{
    size_t bytes;
    void *scratch;
    sbl_result r;
    if (!desc || !frame || !out) return SBL_ERROR_NULL_POINTER;
    if ((r = sbl__check_image(&frame->color, 0)) != SBL_OK) return r;
    bytes = sbl_temporal_scratch_size(frame->color.width, frame->color.channels);
    if (bytes == 0) return SBL_ERROR_INVALID_SIZE;
    if (out->display.data) {
        /* (checked before the scratch is allocated) */
        r = sbl__display_check(frame, out, &out->display);
        /* the G-buffer and the history are the next frame's inputs: not written over */
        if (r == SBL_OK && sbl__overlaps_temporal_inputs(&out->display, frame, history, 1))
            r = SBL_ERROR_OVERLAP;
        if (r != SBL_OK) return r;
    }
    scratch = SBL_MALLOC(bytes, desc->alloc_context);
    if (!scratch) return SBL_ERROR_OUT_OF_MEMORY;
    if (out->display.data) {
        /* the display reads the rows above and below: after every row is filtered */
        sbl_temporal_output o = *out;
        o.display.data = NULL;
        if ((r = sbl_temporal_filter(desc, frame, history, &o, 0, frame->color.height, scratch,
                                     bytes)) == SBL_OK)
            r = sbl_temporal_display(NULL, frame, out, out->display, 0, frame->color.height);
    } else {
        r = sbl_temporal_filter(desc, frame, history, out, 0, frame->color.height, scratch, bytes);
    }
    SBL_FREE(scratch, desc->alloc_context);
    return r;
}

/* ------------------------------------------------------------------------ */
/* 8. Stereo                                                                */
/* ------------------------------------------------------------------------ */

SBLDEF sbl_stereo_desc sbl_stereo_defaults(const sbl_stereo_desc *desc)
{
    sbl_stereo_desc d;
    if (desc) d = *desc;
    else memset(&d, 0, sizeof d);
    if (sbl__is_zero(d.constant_beta)) d.constant_beta = 0.5f;
    if (sbl__is_zero(d.clip_gamma)) d.clip_gamma = 1.25f;
    if (sbl__is_zero(d.bias_threshold)) d.bias_threshold = 3.0f;
    d.reproject = sbl__reproject_defaults(&d.reproject);
    return d;
}

struct sbl__stereo_rp;

typedef struct sbl__stereo_rp {
    sbl_stereo_desc d;
    sbl_eye_index target_eye;
    const sbl_eye *target, *source;
    sbl__tap_src src;
    sbl__target_geo geo;
    sbl__flat depth[2], disparity[2];  /* [0] target, [1] source                      */
    double dir[2];            /* -1 for the left eye, +1 for the right: other = p + dir d */
    float fb;                 /* parallel: focal_px * baseline                          */
    double offset;            /* parallel: disparity_offset                             */
    sbl__cam_map to_source, to_target; /* SBL_RIG_MATRICES, SBL_RIG_PINHOLE             */
    int tiles;                /* 1: the row gather's far-tile shortcut (tests: 0)       */
} sbl__stereo_rp;

static sbl_result sbl__check_eye(const sbl_eye *e, sbl_stereo_rig rig, int need_color)
{
    sbl_result r;
    int w, h;
    if (need_color) {
        if ((r = sbl__check_image(&e->color, 0)) != SBL_OK) return r;
        w = e->color.width; h = e->color.height;
    } else {
        /* the target of a fill only needs geometry: take the size from depth/disparity */
        const sbl_image *ref = e->gbuffer.depth.data ? &e->gbuffer.depth : &e->disparity;
        if (!ref->data) return SBL_ERROR_MISSING_INPUT;
        if ((r = sbl__check_image(ref, ref == &e->disparity ? 0 : 1)) != SBL_OK) return r;
        if (ref->channels > 2) return SBL_ERROR_INVALID_CHANNELS;
        w = ref->width; h = ref->height;
        /* a colour given anyway is what sbl__eye_width() reports: it must agree */
        if ((r = sbl__check_optional(&e->color, 0, w, h)) != SBL_OK) return r;
    }
    if ((r = sbl__check_gbuffer(&e->gbuffer, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&e->length, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&e->evidence, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(&e->disparity, 0, w, h)) != SBL_OK) return r;
    if (e->disparity.data && e->disparity.channels > 2) return SBL_ERROR_INVALID_CHANNELS;
    if (rig == SBL_RIG_PARALLEL && !e->gbuffer.depth.data) return SBL_ERROR_MISSING_INPUT;
    if (rig == SBL_RIG_DISPARITY && !e->disparity.data) return SBL_ERROR_MISSING_INPUT;
    if (rig == SBL_RIG_MATRICES && (!e->gbuffer.depth.data || !e->camera))
        return SBL_ERROR_MISSING_INPUT;
    if (rig == SBL_RIG_PINHOLE && !e->gbuffer.depth.data) return SBL_ERROR_MISSING_INPUT;
    return SBL_OK;
}

static int sbl__eye_width(const sbl_eye *e)
{
    return e->color.data ? e->color.width
                         : (e->gbuffer.depth.data ? e->gbuffer.depth.width : e->disparity.width);
}
static int sbl__eye_height(const sbl_eye *e)
{
    return e->color.data ? e->color.height
                         : (e->gbuffer.depth.data ? e->gbuffer.depth.height : e->disparity.height);
}

/* Planar depth of pixel (ix, iy) of an eye's depth view; 0 if not valid geometry. */
SBL__INLINE float sbl__valid_depth(const sbl__flat *depth, int ix, int iy)
{
    float z = *SBL__AT(*depth, ix, iy);
    if (!sbl__depth_is_geometry(z)) return 0.0f;
    return z;
}

/* SBL_RIG_PARALLEL: d = f b / z - offset (sky: -offset), rows aligned. */
SBL__INLINE int sbl__stereo_map_parallel(const struct sbl__stereo_rp *s, int back, int ix, int iy,
                                         double px, double py, double *ox, double *oy, double *oz)
{
    float z = sbl__valid_depth(&s->depth[back], ix, iy), fbz;
    if (z == 0.0f) return 0;
    fbz = sbl__is_pos_inf(z) ? 0.0f : s->fb / z;
    if (!sbl__finite(fbz)) return 0;
    *ox = px + s->dir[back] * (SBL__CAST(double, fbz) - s->offset);
    *oy = py;
    *oz = SBL__CAST(double, z);
    return 1;
}

/* SBL_RIG_DISPARITY: the eye's own map, (d_x[, d_y]) left minus right. */
SBL__INLINE int sbl__stereo_map_disparity(const struct sbl__stereo_rp *s, int back, int ix, int iy,
                                          double px, double py, double *ox, double *oy, double *oz)
{
    const sbl__flat *m = &s->disparity[back];
    const float *d = SBL__AT(*m, ix, iy);
    float dy = m->ch > 1 ? d[1] : 0.0f;
    if (!sbl__finite(d[0]) || !sbl__finite(dy)) return 0;
    *ox = px + s->dir[back] * SBL__CAST(double, d[0]);
    *oy = py + s->dir[back] * SBL__CAST(double, dy);
    *oz = s->depth[back].p ? SBL__CAST(double, *SBL__AT(s->depth[back], ix, iy)) : 0.0;
    return 1;
}

/* SBL_RIG_MATRICES, SBL_RIG_PINHOLE: unproject at the eye's depth, project into the
   other eye. */
static int sbl__stereo_map_cameras(const struct sbl__stereo_rp *s, int back, int ix, int iy,
                                   double px, double py, double *ox, double *oy, double *oz)
{
    float z = sbl__valid_depth(&s->depth[back], ix, iy);
    if (z == 0.0f) return 0;
    return sbl__cam_map_apply(back ? &s->to_target : &s->to_source, px, py, z, ox, oy, oz);
}

/* The pinhole rig as two cameras (the left eye's view space is the world). */
static int sbl__pinhole_rig_maps(sbl__stereo_rp *s, const sbl_pinhole_rig *p, int w, int h)
{
    double view[2][16], proj[2][16];
    float identity[16];
    int e, i, t = SBL__CAST(int, s->target_eye);
    for (i = 0; i < 16; ++i) identity[i] = (i % 5 == 0) ? 1.0f : 0.0f;
    for (e = 0; e < 2; ++e)
        if (!sbl__pinhole_gl(&p->eye[e], e ? p->right_from_left : identity, p->axes,
                             p->integer_pixel_centers, w, h, view[e], proj[e]))
            return 0;
    return sbl__cam_map_init_gl(&s->to_source, view[t], proj[t], w, h, view[!t], proj[!t],
                                w, h) &&
           sbl__cam_map_init_gl(&s->to_target, view[!t], proj[!t], w, h, view[t], proj[t],
                                w, h);
}

/* Two cameras that form a parallel rig (SBL_RIG_MATRICES or SBL_RIG_PINHOLE whose maps
   keep every pixel on its row and its depth, and move it by K / z + B): run as
   SBL_RIG_PARALLEL with f b = dir K and the offset -dir B, whose plans take one float
   division per pixel and no double map (a VR rig given as two eye cameras is mostly
   this). Decided on the double maps: B at the sky and K at the depth whose disparity is
   half the width (found from a first fit at depth 1, so that the scene's units do not
   matter), then both maps checked against the parallel rig's own positions on a 3 x 3
   grid (the image's corners, edge midpoints and centre, on its outer edges: the
   back-check maps positions anywhere in [0, w) x [0, h)) at three inverse depths (0, the
   sky; and the depths whose disparity is the width plus |B|, and half of it). Why 27
   points suffice: in (n0, n1, 1 / z) a static map's position is a ratio whose numerator
   and denominator have degree at most 1 in each (sbl__cam_map_fold), so the model's
   residual times the denominator has degree at most 2 in each, and a polynomial of that
   degree which vanishes on a 3 x 3 x 3 grid vanishes everywhere; the rays' validity is
   affine in n, and the clip w positive on the box if at its corners. Nearer than the
   grid's last depth no match of either rig lies in the image. Float matrices rarely give
   exact zeros: the nodes pass within SBL__RIG_PARALLEL_TOL px (and the depth within 1e-6
   relative), and between the nodes a residual of that degree is at most about twice its
   largest node value, so positions then agree to 1e-3 px. A rig that is not parallel
   (toed in, a vertical or depth offset, a scaled view, focal lengths that differ) keeps
   its cameras. */
#define SBL__RIG_PARALLEL_TOL 5e-4
static int sbl__rig_parallel_at(const sbl__cam_map *m, double dir, float fb, double offset,
                                double px, double py, float z)
{
    double ox, oy, oz;
    const int sky = sbl__is_pos_inf(z);
    float fbz;
    if (!sbl__cam_map_apply(m, px, py, z, &ox, &oy, &oz)) return 0;
    fbz = sky ? 0.0f : fb / z; /* as sbl__stereo_map_parallel */
    if (!(fabs(ox - (px + dir * (SBL__CAST(double, fbz) - offset))) <= SBL__RIG_PARALLEL_TOL &&
          fabs(oy - py) <= SBL__RIG_PARALLEL_TOL))
        return 0;
    return sky || fabs(oz - SBL__CAST(double, z)) <= 1e-6 * SBL__CAST(double, z);
}

static void sbl__rig_as_parallel(sbl__stereo_rp *s, int w, int h)
{
    const double cx = 0.5 * w, cy = 0.5 * h;
    double ox0, ox1, oy, oz, k, b, off, zn;
    float fb, z[3];
    int i, j, e;
    if (!sbl__cam_map_apply(&s->to_source, cx, cy, SBL__CAST(float, HUGE_VAL), &ox0, &oy, &oz) ||
        !sbl__cam_map_apply(&s->to_source, cx, cy, 1.0f, &ox1, &oy, &oz))
        return;
    /* (every double below is tested inside float's range before its cast: a cast of
       one outside it is undefined) */
    b = ox0 - cx;
    k = ox1 - ox0; /* at depth 1 */
    zn = fabs(k) / (0.5 * w); /* disparity w / 2 */
    if (!(zn > 1e-30 && zn < 1e30)) return;
    z[1] = SBL__CAST(float, zn);
    if (!sbl__cam_map_apply(&s->to_source, cx, cy, z[1], &ox1, &oy, &oz)) return;
    k = s->dir[0] * (ox1 - ox0) * SBL__CAST(double, z[1]);
    off = -s->dir[0] * b;
    if (!(k > 1e-30 && k < 1e30) || !(fabs(off) < 1e9)) return;
    fb = SBL__CAST(float, k);
    if (fabs(off) <= 0.25 * SBL__RIG_PARALLEL_TOL) off = 0.0; /* the fused rows' offset */
    zn = SBL__CAST(double, fb) / (SBL__CAST(double, w) + fabs(off));
    if (!(zn > 1e-30)) return;
    z[0] = SBL__CAST(float, HUGE_VAL);
    z[1] = SBL__CAST(float, zn);
    z[2] = SBL__CAST(float, 2.0 * zn);
    for (e = 0; e < 2; ++e)
        for (j = 0; j < 3; ++j)
            for (i = 0; i < 9; ++i)
                if (!sbl__rig_parallel_at(e ? &s->to_target : &s->to_source, s->dir[e], fb, off,
                                          0.5 * w * (i % 3), 0.5 * h * (i / 3), z[j]))
                    return;
    s->d.rig = SBL_RIG_PARALLEL;
    s->fb = fb;
    s->offset = off;
}

static sbl_result sbl__stereo_rp_init(sbl__stereo_rp *s, const sbl_stereo_desc *desc,
                                      sbl_eye_index target_eye, const sbl_eye *target,
                                      const sbl_eye *source, int target_needs_color)
{
    sbl_result r;
    int w, h, e;
    if (!desc || !target || !source) return SBL_ERROR_NULL_POINTER;
    s->d = sbl_stereo_defaults(desc);
    if (SBL__CAST(int, s->d.rig) < 0 || s->d.rig >= SBL_RIG_COUNT) return SBL_ERROR_INVALID_PARAM;
    if (SBL__CAST(int, target_eye) != 0 && SBL__CAST(int, target_eye) != 1)
        return SBL_ERROR_INVALID_PARAM;
    if ((r = sbl__check_reproject_desc(&s->d.reproject)) != SBL_OK) return r;
    if (s->d.rig == SBL_RIG_PARALLEL &&
        (!sbl__finite(s->d.focal_px) || !(s->d.focal_px > 0.0f) ||
         !sbl__finite(s->d.baseline) || !(s->d.baseline > 0.0f) ||
         !sbl__finite(s->d.disparity_offset)))
        return SBL_ERROR_INVALID_PARAM;
    if ((r = sbl__check_eye(target, s->d.rig, target_needs_color)) != SBL_OK) return r;
    if ((r = sbl__check_eye(source, s->d.rig, 1)) != SBL_OK) return r;
    if (sbl__eye_width(target) != source->color.width ||
        sbl__eye_height(target) != source->color.height)
        return SBL_ERROR_SIZE_MISMATCH;
    if (target_needs_color && target->color.channels != source->color.channels)
        return SBL_ERROR_CHANNEL_MISMATCH;
    s->target_eye = target_eye;
    s->target = target;
    s->source = source;
    sbl__tap_src_init(&s->src, &source->color, &source->length, &source->gbuffer,
                      &target->gbuffer, &s->d.reproject);
    w = source->color.width; h = source->color.height;
    s->geo = sbl__target_geo_make(&target->gbuffer, w, h);
    for (e = 0; e < 2; ++e) {
        const sbl_eye *eye = e ? source : target;
        s->depth[e] = sbl__flatten(&eye->gbuffer.depth);
        s->disparity[e] = sbl__flatten(&eye->disparity);
    }
    /* left eye: the other eye's position is p - d; right eye: p + d */
    s->dir[0] = target_eye == SBL_EYE_LEFT ? -1.0 : 1.0;
    s->dir[1] = -s->dir[0];
    s->fb = s->d.focal_px * s->d.baseline;
    s->offset = SBL__CAST(double, s->d.disparity_offset);
    s->tiles = 1;
    switch (s->d.rig) { /* (the maps: sbl__stereo_map) */
    case SBL_RIG_PARALLEL:
    case SBL_RIG_DISPARITY: break;
    case SBL_RIG_PINHOLE:
        if (!sbl__pinhole_rig_maps(s, &s->d.pinhole, w, h)) return SBL_ERROR_INVALID_PARAM;
        break;
    case SBL_RIG_MATRICES:
    case SBL_RIG_COUNT:
        if (!sbl__cam_map_init(&s->to_source, target->camera, w, h, source->camera, w, h) ||
            !sbl__cam_map_init(&s->to_target, source->camera, w, h, target->camera, w, h))
            return SBL_ERROR_INVALID_PARAM;
        break;
    }
    if (s->d.rig == SBL_RIG_MATRICES || s->d.rig == SBL_RIG_PINHOLE) sbl__rig_as_parallel(s, w, h);
    return SBL_OK;
}

/* The other eye's colour at target pixel (x, y) after tap tests and back-check;
   returns its N (0: no valid correspondence). */
/* A rig's correspondence: pixel (ix, iy) of the target eye (back = 0) or of the source
   eye (back = 1), at continuous position (px, py), to its position (ox, oy) in the other
   eye and its planar depth oz there (0 if unknown). Returns 0 if there is none. The rig
   is the call's, so the branch is decided once per call in effect (no pointer call per
   pixel, issue 9). */
SBL__INLINE int sbl__stereo_map(const sbl__stereo_rp *s, int back, int ix, int iy, double px,
                                double py, double *ox, double *oy, double *oz)
{
    switch (s->d.rig) {
    case SBL_RIG_PARALLEL: return sbl__stereo_map_parallel(s, back, ix, iy, px, py, ox, oy, oz);
    case SBL_RIG_DISPARITY: return sbl__stereo_map_disparity(s, back, ix, iy, px, py, ox, oy, oz);
    default: return sbl__stereo_map_cameras(s, back, ix, iy, px, py, ox, oy, oz);
    }
}

static float sbl__stereo_rp_pixel(const void *ctx, int x, int y, float *out)
{
    const sbl__stereo_rp *s = SBL__CAST(const sbl__stereo_rp *, ctx);
    const int sw = s->source->color.width, sh = s->source->color.height;
    double sx, sy, sz, bx, by, bz;
    float z, n;
    sbl__tap_want want;
    int ix, iy;
    if (!sbl__tap_want_init(&want, &s->geo, x, y, &z)) return 0.0f;
    if (!sbl__stereo_map(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz)) return 0.0f;
    /* the match must lie inside the source image: outside it, the bilinear
       renormalisation and the 3x3 fallback would replicate the edge pixels */
    if (!(sx >= 0.0 && sx < SBL__CAST(double, sw) && sy >= 0.0 && sy < SBL__CAST(double, sh)))
        return 0.0f;
    want.depth = SBL__CAST(float, sz);
    n = sbl__gather(&s->src, &want, sx, sy, !s->d.reproject.no_fallback, out);
    if (!(n > 0.0f)) return 0.0f;

    /* back-check: from the nearest source pixel, with the source's own geometry, the
       correspondence must come back to within back_check_pixels of where it started */
    if (s->d.reproject.disabled_tests & SBL_TEST_BACK_CHECK) return n;
    ix = SBL__CAST(int, floor(sx));
    iy = SBL__CAST(int, floor(sy));
    if (!sbl__stereo_map(s, 1, ix, iy, sx, sy, &bx, &by, &bz)) return 0.0f;
    {
        double ex = bx - (x + 0.5), ey = by - (y + 0.5);
        double tol = SBL__CAST(double, s->d.reproject.back_check_pixels);
        if (!(ex * ex + ey * ey <= tol * tol)) return 0.0f;
    }
    return n;
}

/* The stereo blend's change flags of row y, columns [x0, x1), into k->sev
   (docs/ESTIMATORS.md 6.15): 1 where this eye's evidence plane at the pixel, or the other
   eye's at the pixel nearest the match, is above the carried evidence's threshold c_R
   (SBL__EVIDENCE_THR), else 0. The other eye's plane is read only where the colour's
   match is valid (r->n > 0: its taps and the back-check passed), at the position its
   gather started from; the nearest pixel, not bilinear: the plane is a statistic of
   3 x 15 blocks, smooth at the scale of a pixel, and a threshold reads it. A value that is
   not a ratio in (0, SBL__POOL_RATIO_CAP] (sbl__evidence_pixel's test; NaN) shows no
   change. The same flags for the lanes and the reference path. */
static void sbl__stereo_evidence_row(sbl__kernel *k, const sbl__ring_row *r, int y, int x0,
                                     int x1)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, k->sev_rp);
    const float thr = SBL__CAST(float, SBL__EVIDENCE_THR), cap = SBL__CAST(float, SBL__POOL_RATIO_CAP);
    const int sw = s->source->color.width, sh = s->source->color.height;
    int x;
    for (x = x0; x < x1; ++x) {
        int f = 0;
        if (k->sev_own) {
            const float v = *sbl__px(k->sev_own, x, y);
            f = v > thr && v <= cap;
        }
        if (!f && k->sev_other && r->n[x] > 0.0f) {
            double sx, sy, sz;
            if (sbl__stereo_map(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz) &&
                sx >= 0.0 && sx < SBL__CAST(double, sw) && sy >= 0.0 && sy < SBL__CAST(double, sh)) {
                const float v = *sbl__px(k->sev_other, SBL__CAST(int, sx), SBL__CAST(int, sy));
                f = v > thr && v <= cap;
            }
        }
        k->sev[x] = f ? 1.0f : 0.0f;
    }
}

#ifdef SBL__ROW_GATHER
/* Far tiles of the parallel rig (issue 10): where every disparity of a vector of pixels
   is below SBL__FAR_PX (geometry beyond 256 f b), the other eye is read at the pixel
   itself, its one tap tested, instead of a footprint whose second tap weighs |d|. Where
   that tap passes, x* and its N differ from the general path by at most
   (|d| / (1 - |d|) + 2^-23) |c(x +- 1) - c(x)| + 2^-22 |x*|: under 0.4 % of the
   contrast to the neighbour (tests/test_tiles.c); where it fails, the pixel gather
   decides, so validity never changes. The back-check keeps the exact position. This is
   the one result by which a build with the row gather (x86 SIMD) may differ from the
   scalar reference build: within that bound, on far geometry only; hence not in the
   default SBL_SHORTCUTS (bit 16). */
#define SBL__FAR_PX (1.0f / 256.0f)

/* The back-check of the two-camera rigs for the block entries back[0 .. nback) (valid
   matches of columns x0 + entry of row y), VW at a time: from the nearest source pixel,
   at the source's depth there, back into the target, within tol pixels of the start
   (sbl__stereo_rp_pixel's test); a failed one clears its ring column. */
static void sbl__stereo_cam_back(const sbl__stereo_rp *s, sbl__ring_row *r, const sbl__cam_k *k, int y,
                                 int x0, const double *psx, const double *psy, const int *back,
                                 int nback, double tol)
{
    const int ch = s->src.color.ch;
    int b, l;
    for (b = 0; b < nback; b += SBL__VW) {
        float zf[SBL__VW + 4]; /* (sbl__cam_lanes_k reads VW + 4) */
        double px[SBL__VW], py[SBL__VW], bx[SBL__VW], by[SBL__VW], bz[SBL__VW];
        int ix[SBL__VW], iy[SBL__VW], ok, j;
        for (l = 0; l < SBL__VW; ++l) {
            const int e = back[b + l < nback ? b + l : b]; /* past the end: a copy */
            px[l] = psx[e];
            py[l] = psy[e];
        }
        for (j = 0; j < SBL__VW; j += SBL__DW) { /* the nearest source pixel (in the image) */
            sbl__dstorei(ix + j, sbl__dfloor(sbl__dload(px + j)));
            sbl__dstorei(iy + j, sbl__dfloor(sbl__dload(py + j)));
        }
        for (l = 0; l < SBL__VW; ++l) zf[l] = sbl__valid_depth(&s->depth[1], ix[l], iy[l]);
        ok = sbl__cam_lanes_k(k, 0, 0, px, py, zf, bx, by, bz);
        for (l = 0; l < SBL__VW && b + l < nback; ++l) {
            const int x = x0 + back[b + l];
            const double ex = bx[l] - (x + 0.5), ey = by[l] - (y + 0.5);
            if (!(((ok >> l) & 1) && zf[l] != 0.0f && ex * ex + ey * ey <= tol * tol))
                sbl__ring_put(r, x, 0.0f, NULL, ch);
        }
    }
}

/* sbl__stereo_cam_back for the block entries [i, i + VW) in place, on a row in lane mode
   2 (each entry's psx, psy a match inside the source or 0): the bits of the lanes whose
   check fails (meaningful where the match is valid), the test in double lanes with the
   reference's operations (bx - (x + 0.5), by - (y + 0.5), ex ex + ey ey <= tol tol). */
SBL__INLINE int sbl__stereo_cam_back_vec(const sbl__stereo_rp *s, const sbl__block *b, int i, double tol)
{
    const double *px = b->psx + i, *py = b->psy + i;
    const sbl__dv half = sbl__dset1(0.5), tt = sbl__dset1(tol * tol), ey0 = sbl__dset1(b->y + 0.5);
    const sbl__flat *d = &s->depth[1]; /* (the source's depth: s->src.depth) */
    const sbl__dv stride = sbl__dset1(SBL__CAST(double, d->stride)), step = sbl__dset1(SBL__CAST(double, d->step));
    float zf[SBL__VW + 4]; /* (sbl__cam_lanes_k reads VW + 4) */
    double bx[SBL__VW], by[SBL__VW], bz[SBL__VW];
    int idx[SBL__VW], ok, pass = 0, j;
    sbl__v z;
    /* the nearest source pixel (in the image): its depth's index floor(sy) stride +
       floor(sx) step, exact in double and below INT_MAX / 2 (sbl__row_gather_ok); then
       sbl__valid_depth in lanes: geometry (> 0 or +inf, sbl__depth_is_geometry) is > 0 */
    for (j = 0; j < SBL__VW; j += SBL__DW)
        sbl__dstorei(idx + j, sbl__dadd(sbl__dmul(sbl__dfloor(sbl__dload(py + j)), stride),
                                        sbl__dmul(sbl__dfloor(sbl__dload(px + j)), step)));
    z = sbl__gatheri(d->p, idx);
    z = sbl__sel(sbl__gt(z, sbl__set1(0.0f)), z, sbl__set1(0.0f));
    sbl__store(zf, z);
    ok = sbl__cam_lanes_k(&b->cam[1], 0, 0, px, py, zf, bx, by, bz);
    for (j = 0; j < SBL__VW; j += SBL__DW) {
        /* (x + l) + 0.5 is the reference's x + 0.5 exactly */
        const sbl__dv ex = sbl__dsub(sbl__dload(bx + j),
                                     sbl__dadd(sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(SBL__CAST(double, b->x0 + i + j))),
                                               half));
        const sbl__dv ey = sbl__dsub(sbl__dload(by + j), ey0);
        pass |= sbl__dle_bits(sbl__dadd(sbl__dmul(ex, ex), sbl__dmul(ey, ey)), tt) << j;
    }
    return ~(ok & pass & sbl__mbits(sbl__gt(z, sbl__set1(0.0f))));
}

/* The stereo row gather's hooks (sbl__row_gather_blocks): sbl__stereo_rp_pixel with the
   plan in lanes where the rig allows (mode 1 parallel, 4 parallel with a disparity
   offset, 2 two cameras, 3 disparity map), the taps in lanes, the back-check after them
   (in lanes for the two-camera rigs and the parallel rig). */
static int sbl__stereo_block_start(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, ctx);
    const int sw = s->source->color.width, sh = s->source->color.height, y = b->y;
    /* target depth packed and of the source's size, target normals / ids in lanes
       (sbl__lanes_want_nid), an interior row (the depth slack reads both neighbours) */
    const int geo = sbl__geo_nid_lanes_ok(&s->geo) && s->geo.width == sw &&
                    s->geo.height == sh && y >= 1 && y + 1 < sh;
    const int depth = s->geo.depth.p && s->geo.depth.step == 1;
    (void)r;
    if (b->row_state >= 0) { /* decided for this row */
        b->mode = b->row_state;
        return 0;
    }
    if (s->d.rig == SBL_RIG_PARALLEL)
        /* without a disparity offset the float lane plan is exact for m = +-f b / z; with
           one, the positions in double lanes (4) */
        b->mode = geo && depth && sw <= 32768 && sh <= 32768 ? (s->offset == 0.0 ? 1 : 4) : 0;
    else if (s->d.rig == SBL_RIG_DISPARITY)
        /* (a target without depth has no slack and no depth test) */
        b->mode = sbl__geo_nid_lanes_ok(&s->geo) && s->geo.width == sw && s->geo.height == sh &&
                          sw <= 32768 && sh <= 32768 &&
                          (!s->geo.depth.p || (depth && y >= 1 && y + 1 < sh))
                      ? 3
                      : 0;
    else { /* (sbl__plan_lanes_at: images up to 2^15 pixels) */
        b->mode = geo && depth && sw <= 32768 && sh <= 32768 ? 2 : 0;
        /* the maps' constants for this row: back to the target (every back-check in
           lanes), to the source with the row's terms (the plans in lanes) */
        sbl__cam_k_init(&b->cam[1], &s->to_target);
        if (b->mode == 2) {
            sbl__cam_k_init(&b->cam[0], &s->to_source);
            sbl__cam_k_row(&b->cam[0], y);
        }
    }
    b->row_state = b->mode;
    return 0;
}

/* The target side of the parallel rig's lane plans for the VW pixels x .. x + VW - 1 of
   an interior row y: the lanes with valid geometry (and normal / id data) and a finite
   f b / z (sky: f b / inf = 0), their depth z, its slack and m = f b / z (the map's float
   division). */
SBL__INLINE sbl__m sbl__parallel_want_lanes(const sbl__stereo_rp *s, sbl__tap_plan *p, int i, int x, int y,
                                           sbl__v *z, sbl__v *slack, sbl__v *m)
{
    sbl__m keep = sbl__lanes_want(&s->geo.depth, s->geo.width, x, y, z, slack);
    if (s->geo.normals.p || s->geo.ids.p) keep = sbl__lanes_want_nid(&s->geo, &s->src, p, i, x, y, keep);
    *m = sbl__div_exact(sbl__set1(s->fb), *z);
    return sbl__mandnot(keep, sbl__nonfinite(*m));
}

/* The parallel rig's plan for the VW pixels x .. x + VW - 1 of an interior row y with
   the positions in double lanes, from the target side (sbl__parallel_want_lanes):
   sbl__stereo_map_parallel's x + 0.5 + dir (f b / z - offset) (f b / z the same float
   division), then sbl__plan_lanes_at. For a disparity offset (lane mode 4), and for
   the vectors of mode 1 whose disparities the float plan cannot take exactly
   (0 < |f b / z| < 2^-8: geometry beyond 256 f b). Out of line, so that mode 1's float
   plan keeps its registers. */
SBL__NOINLINE int sbl__stereo_plan_parallel_at(const sbl__stereo_rp *s, sbl__block *b, int i, int x, int y,
                                               sbl__m keep, sbl__v z, sbl__v slack, sbl__v m)
{
    float fbz[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    double sx[SBL__VW], sy[SBL__VW];
    int in, l;
    sbl__store(fbz, sbl__sel(keep, m, sbl__set1(0.0f)));
    for (l = 0; l < SBL__VW; l += SBL__DW) {
        sbl__dstore(sx + l, sbl__dadd(sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(x + l + 0.5)),
                                      sbl__dmul(sbl__dset1(s->dir[0]),
                                                sbl__dsub(sbl__dfromf(fbz + l), sbl__dset1(s->offset)))));
        sbl__dstore(sy + l, sbl__dset1(y + 0.5));
    }
    in = sbl__plan_lanes_at(&s->src, &b->p, i, x, sbl__mbits(keep), sx, sy, z, slack);
    for (l = 0; l < SBL__VW; ++l) { /* the matches' positions (0: none) */
        const int mt = (in >> l) & 1;
        b->psx[i + l] = mt ? sx[l] : 0.0;
        b->psy[i + l] = mt ? sy[l] : 0.0;
        b->snapped[i + l] = 0;
    }
    return 0;
}

/* sbl__cam_plan_lanes for the two-camera rigs (lane mode 2): the map to the source with
   the block's constants for row y (sbl__stereo_block_start), its positions written to
   the block's psx, psy (0 where there is no match). */
SBL__INLINE void sbl__stereo_cam_plan(const sbl__stereo_rp *s, sbl__block *b, int i, int x, int y)
{
    float zf[SBL__VW + 4], zo[SBL__VW]; /* (sbl__cam_lanes_k reads VW + 4) */
    double oz[SBL__VW], *ox = b->psx + i, *oy = b->psy + i;
    sbl__v z, slack;
    sbl__m want = sbl__lanes_want(&s->geo.depth, s->geo.width, x, y, &z, &slack);
    int keep, l, out;
    if (s->geo.normals.p || s->geo.ids.p) want = sbl__lanes_want_nid(&s->geo, &s->src, &b->p, i, x, y, want);
    keep = sbl__mbits(want);
    sbl__store(zf, z);
    keep &= sbl__cam_lanes_k(&b->cam[0], 1, x, NULL, NULL, zf, ox, oy, oz);
    for (l = 0; l < SBL__VW; l += SBL__DW) sbl__dstoref(zo + l, sbl__dload(oz + l)); /* the expected depth */
    out = ~sbl__plan_lanes_at(&s->src, &b->p, i, x, keep, ox, oy, sbl__load(zo), slack) & ((1 << SBL__VW) - 1);
    for (l = 0; out; ++l, out >>= 1)
        if (out & 1) ox[l] = oy[l] = 0.0;
}

static int sbl__stereo_plan_vec(const void *ctx, sbl__block *b, int i)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, ctx);
    const int x = b->x0 + i, y = b->y;
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f);
    int l, bits;
    if (!b->mode || x < 0 || x + SBL__VW > s->source->color.width) return -1;
    if (b->mode == 2) {
        sbl__stereo_cam_plan(s, b, i, x, y);
        for (l = 0; l < SBL__VW; ++l) b->snapped[i + l] = 0;
        return 0;
    }
    if (b->mode == 3) {
        /* sbl__stereo_map_disparity in lanes: (x, y) + 0.5 + dir (d_x, d_y) */
        const sbl__flat *dm = &s->disparity[0];
        const float *dp = SBL__AT(*dm, x, y);
        float dxs[SBL__VW], dys[SBL__VW];
        int idx[SBL__VW];
        sbl__v z = zero, slack = zero, mx, my;
        sbl__m keep = s->geo.depth.p ? sbl__lanes_want(&s->geo.depth, s->geo.width, x, y, &z, &slack)
                                     : sbl__gt(one, zero);
        if (s->geo.normals.p || s->geo.ids.p) keep = sbl__lanes_want_nid(&s->geo, &s->src, &b->p, i, x, y, keep);
        for (l = 0; l < SBL__VW; ++l) idx[l] = l * SBL__CAST(int, dm->step);
        mx = sbl__gatheri(dp, idx);
        my = dm->ch > 1 ? sbl__gatheri(dp + 1, idx) : zero;
        keep = sbl__mandnot(sbl__mandnot(keep, sbl__nonfinite(mx)), sbl__nonfinite(my));
        sbl__store(dxs, mx);
        sbl__store(dys, my);
        if (s->dir[0] < 0.0) { mx = sbl__sub(zero, mx); my = sbl__sub(zero, my); }
        bits = sbl__plan_lanes(&s->src, &b->p, i, x, y, keep, z, slack, mx, my, 0);
        for (l = 0; l < SBL__VW; ++l) {
            b->psx[i + l] = x + l + 0.5 + s->dir[0] * SBL__CAST(double, dxs[l]);
            b->psy[i + l] = y + 0.5 + s->dir[0] * SBL__CAST(double, dys[l]);
            b->snapped[i + l] = 0;
        }
        return bits;
    }
    {   /* the parallel rig in lanes: m = dir f b / z */
        float fbz[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
        sbl__v z, slack, fb_z, m;
        sbl__m keep = sbl__parallel_want_lanes(s, &b->p, i, x, y, &z, &slack, &fb_z), far;
        int far_bits;
        if (b->mode == 4) return sbl__stereo_plan_parallel_at(s, b, i, x, y, keep, z, slack, fb_z);
        m = s->dir[0] < 0.0 ? sbl__sub(zero, fb_z) : fb_z;
        /* dir f b / z: the positions finite in every lane (0 where m is not: such a lane
           has no match): sbl__stereo_back_parallel clamps them with a min and a max, whose
           NaN result -ffast-math leaves to the operand order gcc picks */
        sbl__store(fbz, sbl__sel(keep, m, zero));
        /* far lanes: a disparity below SBL__FAR_PX and not 0, so the other eye is read
           at the same pixel (see SBL__FAR_PX). Decided lane by lane, on the lane's own
           disparity: a pixel's result then does not depend on which vector holds it
           (the span's start, the vector width); until session 27 the whole vector was
           far or not, so a pixel next to near geometry could come out either way. */
        far = sbl__mand(sbl__mand(keep, sbl__gt(sbl__set1(SBL__FAR_PX), sbl__abs(m))), sbl__gt(sbl__abs(m), zero));
        far_bits = (SBL_SHORTCUTS & 16) != 0 && s->tiles ? sbl__mbits(far) : 0;
        if (!far_bits) far = sbl__gt(zero, zero);
        bits = sbl__plan_lanes(&s->src, &b->p, i, x, y, keep, z, slack, sbl__sel(far, zero, m), zero, 1);
        /* two or more lanes the float plan leaves (far geometry without the far tiles):
           the vector again in double lanes; a lone one, the scalar plan */
        if ((bits & (bits - 1)) && !far_bits) return sbl__stereo_plan_parallel_at(s, b, i, x, y, keep, z, slack, fb_z);
        for (l = 0; l < SBL__VW; l += SBL__DW) {
            /* x + l + 0.5 + dir (f b / z - offset), as the map: offset is 0 in this lane
               mode and dir = +-1, so dir (f b / z - 0) is the float dir f b / z exactly
               (a zero's sign is moot: x + l + 0.5 > 0) */
            sbl__dstore(b->psx + i + l, sbl__dadd(sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(x + l + 0.5)),
                                                  sbl__dfromf(fbz + l)));
            sbl__dstore(b->psy + i + l, sbl__dset1(y + 0.5));
        }
        for (l = 0; l < SBL__VW; ++l) b->snapped[i + l] = SBL__CAST(unsigned char, (far_bits >> l) & 1);
        return bits;
    }
}

static void sbl__stereo_plan_one(const void *ctx, sbl__block *b, int i)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, ctx);
    const int sw = s->source->color.width, sh = s->source->color.height, x = b->x0 + i, y = b->y;
    sbl__tap_want want;
    double sx, sy, sz;
    float z;
    sbl__tap_plan_reset(&b->p, i);
    b->psx[i] = b->psy[i] = 0.0;
    b->snapped[i] = 0;
    if (!sbl__tap_want_init(&want, &s->geo, x, y, &z)) return;
    if (!sbl__stereo_map(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz)) return;
    if (!(sx >= 0.0 && sx < SBL__CAST(double, sw) && sy >= 0.0 && sy < SBL__CAST(double, sh))) return;
    want.depth = SBL__CAST(float, sz);
    b->psx[i] = sx;
    b->psy[i] = sy;
    if ((SBL_SHORTCUTS & 16) != 0 && b->mode == 1 && s->tiles) {
        /* a far lane as sbl__stereo_plan_vec decides it (the same float f b / z), so that
           an entry gets the same result here as in a vector: the taps at the pixel
           itself, the back-check from the exact position */
        const float fbz = s->fb / z;
        if (fbz != 0.0f && fabsf(fbz) < SBL__FAR_PX) {
            b->snapped[i] = 1;
            sx = x + 0.5;
        }
    }
    sbl__tap_plan_set(&s->src, &b->p, i, &want, sx, sy);
}

/* The block's entries whose taps (at the match's exact position) weigh below 1e-3, not
   far lanes: the pixel gather's 3x3 fallback there (sbl__fallback_lanes: the map's
   position, the planned expected depth and slack); their back-check follows as for any
   valid match (redo 0 now). */
static SBL__RARE void sbl__stereo_fallback_block(const sbl__stereo_rp *s, sbl__ring_row *r,
                                                 sbl__block *b)
{
    double fx[SBL__BLOCK], fy[SBL__BLOCK];
    int e[SBL__BLOCK], n = 0, i;
    for (i = 0; i < b->n; ++i)
        if (b->p.redo[i] == 2 && !b->snapped[i]) {
            b->p.redo[i] = 0;
            fx[n] = b->psx[i];
            fy[n] = b->psy[i];
            e[n++] = i;
        }
    if (n) sbl__fallback_lanes(&s->src, r, b->x0, e, fx, fy, b->p.depth, b->p.slack, n, 0, &b->p);
}

/* After the taps: the entries handed back, and far lanes whose one tap failed, go to
   the pixel gather (the footprint's other tap may carry them); the back-check of the
   others, as
   sbl__stereo_rp_pixel does it: from the nearest source pixel back. `rig` is a
   constant where this is inlined (the map is called directly). */
SBL__INLINE void sbl__stereo_after_one(const sbl__stereo_rp *s, sbl__ring_row *r,
                                       const sbl__block *b, int i, sbl_stereo_rig rig,
                                       int back_check, double tol, int *back, int *nback)
{
    const int cams = rig != SBL_RIG_PARALLEL && rig != SBL_RIG_DISPARITY;
    const int x = b->x0 + i;
    /* (entries whose taps weigh below 1e-3 took the 3x3 fallback already: redo 0 now,
       see sbl__stereo_after_rig) */
    if ((b->snapped[i] && b->p.fast[i] > 0.0f && !(r->v[x] > 0.0f)) || b->p.redo[i]) {
        float tmp[4] = {0, 0, 0, 0};
        sbl__ring_put(r, x, sbl__stereo_rp_pixel(s, x, b->y, tmp), tmp, s->src.color.ch);
        return;
    }
    if (!back_check || !(r->v[x] > 0.0f)) return;
    if (cams) {
        back[(*nback)++] = i; /* in lanes, by the caller */
    } else {
        const int ix = SBL__CAST(int, floor(b->psx[i])), iy = SBL__CAST(int, floor(b->psy[i]));
        double bx, by, bz, ex, ey;
        int ok = rig == SBL_RIG_PARALLEL
                     ? sbl__stereo_map_parallel(s, 1, ix, iy, b->psx[i], b->psy[i], &bx, &by, &bz)
                     : sbl__stereo_map_disparity(s, 1, ix, iy, b->psx[i], b->psy[i], &bx, &by, &bz);
        if (ok) {
            ex = bx - (x + 0.5);
            ey = by - (b->y + 0.5);
            ok = ex * ex + ey * ey <= tol * tol;
        }
        if (!ok) sbl__ring_put(r, x, 0.0f, NULL, s->src.color.ch);
    }
}

/* sbl__stereo_map_parallel's back-check (from the nearest source pixel, at the source's
   depth there, within tol of the start) for block entries [i, i + VW) in lanes, on a
   row in lane mode 1 or 4 (every match lies on the pixel's row, inside the source where
   it is valid): the same double operations in the same order, the
   float division exact. Returns the bits of the lanes whose check fails (meaningful
   where the match is valid; the others read a clamped, valid address). */
SBL__INLINE int sbl__stereo_back_parallel(const sbl__stereo_rp *s, const sbl__block *b, int i,
                                          double tol)
{
    const sbl__flat *d = &s->depth[1];
    const int x = b->x0 + i;
    const sbl__dv hi = sbl__dset1(SBL__CAST(double, s->source->color.width - 1)), lo = sbl__dset1(0.0);
    float fbz[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    int idx[SBL__VW], j, ok = 0;
    sbl__v z, f;
    sbl__m good;
    for (j = 0; j < SBL__VW; j += SBL__DW) /* floor(sx) of sx in [0, w): its truncation */
        sbl__dstorei(idx + j, sbl__dmax(sbl__dmin(sbl__dload(b->psx + i + j), hi), lo));
    if (d->step != 1)
        for (j = 0; j < SBL__VW; ++j) idx[j] *= SBL__CAST(int, d->step);
    z = sbl__gatheri(SBL__AT(*d, 0, b->y), idx);
    /* sbl__valid_depth: z > 0 (+inf included); f b / +inf = 0, as the map's sky case */
    good = sbl__gt(z, sbl__set1(0.0f));
    f = sbl__div_exact(sbl__set1(s->fb), z);
    good = sbl__mandnot(good, sbl__nonfinite(f));
    sbl__store(fbz, f);
    for (j = 0; j < SBL__VW; j += SBL__DW) {
        const sbl__dv bx = sbl__dadd(sbl__dload(b->psx + i + j),
                                     sbl__dmul(sbl__dset1(s->dir[1]),
                                               sbl__dsub(sbl__dfromf(fbz + j), sbl__dset1(s->offset))));
        const sbl__dv ex = sbl__dsub(bx, sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(x + j + 0.5)));
        /* ey = by - (y + 0.5) is 0 (by = the match's y, which is y + 0.5 on this row),
           and ex ex + 0 0 = ex ex exactly */
        ok |= sbl__dle_bits(sbl__dmul(ex, ex), sbl__dset1(tol * tol)) << j;
    }
    return ~(ok & sbl__mbits(good)) & ((1 << SBL__VW) - 1);
}

/* After the taps, per block: sbl__stereo_after_one on every entry; on a parallel-rig
   row in lane mode 1 or 4, VW entries at a time where none is handed back (redo) or far,
   the back-check in lanes. `rig` is a constant where this is inlined. */
SBL__INLINE void sbl__stereo_after_rig(const sbl__stereo_rp *s, sbl__ring_row *r, sbl__block *b,
                                       sbl_stereo_rig rig)
{
    const int back_check = !(s->d.reproject.disabled_tests & SBL_TEST_BACK_CHECK);
    const double tol = SBL__CAST(double, s->d.reproject.back_check_pixels);
    int i = 0, l, back[SBL__BLOCK], nback = 0;
    {   /* (redo is rare: one look at the block first) */
        uint64_t any = 0, u;
        for (i = 0; i + 8 <= b->n; i += 8) { memcpy(&u, b->p.redo + i, 8); any |= u; }
        for (; i < b->n; ++i) any |= b->p.redo[i];
        if (any) sbl__stereo_fallback_block(s, r, b);
        i = 0;
    }
    if (rig == SBL_RIG_PARALLEL && (b->mode == 1 || b->mode == 4) && back_check) {
        for (; i + SBL__VW <= b->n; i += SBL__VW) {
            uint32_t any = 0, u, v;
            int bits;
            for (l = 0; l < SBL__VW; l += 4) {
                memcpy(&u, b->snapped + i + l, 4);
                memcpy(&v, b->p.redo + i + l, 4);
                any |= u | v;
            }
            if (any) {
                for (l = 0; l < SBL__VW; ++l)
                    sbl__stereo_after_one(s, r, b, i + l, rig, back_check, tol, back, &nback);
                continue;
            }
            bits = sbl__mbits(sbl__gt(sbl__load(r->v + b->x0 + i), sbl__set1(0.0f)));
            if (!bits) continue;
            bits &= sbl__stereo_back_parallel(s, b, i, tol);
            for (l = 0; bits; ++l, bits >>= 1)
                if (bits & 1) sbl__ring_put(r, b->x0 + i + l, 0.0f, NULL, s->src.color.ch);
        }
    }
    if (rig != SBL_RIG_PARALLEL && rig != SBL_RIG_DISPARITY && b->mode == 2 && back_check) {
        /* the two cameras: VW entries at a time in place where none is handed back (redo;
           none is far in this mode), the others gathered for sbl__stereo_cam_back */
        for (; i + SBL__VW <= b->n; i += SBL__VW) {
            uint32_t any = 0, u;
            int bits;
            for (l = 0; l < SBL__VW; l += 4) {
                memcpy(&u, b->p.redo + i + l, 4);
                any |= u;
            }
            if (any) {
                for (l = 0; l < SBL__VW; ++l)
                    sbl__stereo_after_one(s, r, b, i + l, rig, back_check, tol, back, &nback);
                continue;
            }
            bits = sbl__mbits(sbl__gt(sbl__load(r->v + b->x0 + i), sbl__set1(0.0f)));
            if (!bits) continue;
            bits &= sbl__stereo_cam_back_vec(s, b, i, tol);
            for (l = 0; bits; ++l, bits >>= 1)
                if (bits & 1) sbl__ring_put(r, b->x0 + i + l, 0.0f, NULL, s->src.color.ch);
        }
    }
    for (; i < b->n; ++i) sbl__stereo_after_one(s, r, b, i, rig, back_check, tol, back, &nback);
    if (nback) sbl__stereo_cam_back(s, r, &b->cam[1], b->y, b->x0, b->psx, b->psy, back, nback, tol);
}

static void sbl__stereo_block_after(const void *ctx, sbl__ring_row *r, sbl__block *b)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, ctx);
    if (s->d.rig == SBL_RIG_PARALLEL) sbl__stereo_after_rig(s, r, b, SBL_RIG_PARALLEL);
    else if (s->d.rig == SBL_RIG_DISPARITY) sbl__stereo_after_rig(s, r, b, SBL_RIG_DISPARITY);
    else sbl__stereo_after_rig(s, r, b, SBL_RIG_MATRICES);
}

/* ---- the parallel rig's fused vectors (issue 9) ----------------------------------
   On a row of the parallel rig in lane mode 1 every match lies on the pixel's row, so
   its footprint is the two taps (x0, y), (x0 + 1, y) with fy = 0; where the VW
   matches of a vector share one integer offset k = floor(m) (a constant or slowly
   varying disparity), both taps of all lanes are two plain vector loads per view at
   x + k and x + k + 1, and the back-check's source pixel floor(sx) is one of them. */

/* Can sbl__stereo_parallel_vec take row y of this call? sbl__stereo_block_start's lane
   mode 1 (target depth packed and of the source's size, an interior row, no disparity
   offset, images up to 2^15 pixels), no target normals or ids (their tests and checks
   stay with the blocks), depth and N tested with packed views (the "full" taps of
   sbl__row_taps_ch), colour packed with 1 or 3 channels. */
SBL__INLINE int sbl__stereo_parallel_ok(const sbl__stereo_rp *s, int y)
{
    const sbl__tap_src *src = &s->src;
    const int sw = src->width, sh = src->height;
    return s->d.rig == SBL_RIG_PARALLEL && s->offset == 0.0 && sw <= 32768 && sh <= 32768 &&
           s->source->color.width == sw && s->geo.width == sw && s->geo.height == sh &&
           y >= 1 && y + 1 < sh && s->geo.depth.p && s->geo.depth.step == 1 &&
           !s->geo.normals.p && !s->geo.ids.p && !src->use_normal && !src->use_id &&
           src->use_depth && src->depth.step == 1 && src->length.p && src->length.step == 1 &&
           ((src->color.ch == 3 && src->color.step == 3) || (src->color.ch == 1 && src->color.step == 1));
}

/* sbl__stereo_parallel_vec's vectors without any match (the image's side beyond the
   other eye's view): every lane either without target geometry or a finite m (keep),
   or kept with an exact m whose position x + l + 1/2 + m lies outside the source
   (sbl__plan_lanes' test, exact): they reset, the ring columns 0. Returns 1 if so. */
SBL__INLINE int sbl__stereo_parallel_none(const sbl__stereo_rp *s, sbl__ring_row *r, int x,
                                          sbl__m keep, sbl__m exact, sbl__v m, const int ch)
{
    const sbl__v zero = sbl__set1(0.0f), half = sbl__set1(0.5f);
    const sbl__v xf = sbl__add(sbl__set1(SBL__CAST(float, x)), sbl__load(sbl__lane_f));
    const sbl__m inside = sbl__mand(sbl__le(sbl__sub(zero, sbl__add(xf, half)), m),
                                    sbl__gt(sbl__sub(sbl__sub(sbl__set1(SBL__CAST(float, s->src.width)), xf), half), m));
    if (sbl__mbits(sbl__mandnot(keep, sbl__mandnot(exact, inside))) != 0) return 0;
    sbl__store(r->n + x, zero);
    sbl__store(r->v + x, zero);
    sbl__store(r->x[0] + x, zero);
    if (ch > 1) {
        sbl__store(r->x[1] + x, zero);
        sbl__store(r->x[2] + x, zero);
    }
    return 1;
}

/* What sbl__stereo_parallel_vec reads of the call and row y, formed once per row (in
   locals: the vectors' stores, bytes among them, would have the call's fields loaded
   and the row pointers formed again per vector): the target depth's row and stride, and
   the source's depth, N and colour rows (column 0), strides and sizes */
typedef struct sbl__parallel_rows {
    const float *z, *d, *n, *c;
    ptrdiff_t zs, ds, ns, cs;
    float fb, tol;
    float half_back; /* half the back-check's tolerance (-1 where it is below 2e-3 pixels) */
    int gw, sw, neg, edge; /* edge: a vector may lie at column 0 or w - VW (sbl__lanes_want_in) */
} sbl__parallel_rows;

SBL__INLINE void sbl__parallel_rows_of(const sbl__stereo_rp *s, int y, int xa, int xb, sbl__parallel_rows *pr)
{
    const sbl__tap_src *src = &s->src;
    pr->z = SBL__AT(s->geo.depth, 0, y);
    pr->zs = s->geo.depth.stride;
    pr->d = src->depth.p + SBL__CAST(ptrdiff_t, y) * src->depth.stride;
    pr->ds = src->depth.stride;
    pr->n = src->length.p + SBL__CAST(ptrdiff_t, y) * src->length.stride;
    pr->ns = src->length.stride;
    pr->c = src->color.p + SBL__CAST(ptrdiff_t, y) * src->color.stride;
    pr->cs = src->color.stride;
    pr->fb = s->fb;
    pr->tol = src->depth_tolerance;
    pr->half_back = s->d.reproject.back_check_pixels >= 2e-3f ? 0.5f * s->d.reproject.back_check_pixels : -1.0f;
    pr->gw = s->geo.width;
    pr->sw = src->width;
    pr->neg = s->dir[0] < 0.0;
    pr->edge = xa == 0 || xb >= pr->gw;
}

/* sbl__stereo_parallel_vec_in's plan: sbl__stereo_plan_vec's m = dir f b / z and
   sbl__plan_lanes' exact motion; returns the lanes to keep */
SBL__INLINE sbl__m sbl__parallel_plan(const sbl__parallel_rows *pr, int x, sbl__v *z, sbl__v *slack, sbl__v *m,
                                      sbl__m *exact)
{
    sbl__m keep = sbl__lanes_want_in(pr->z + x, pr->zs, pr->gw, x, z, slack, pr->edge);
    *m = sbl__div_exact(sbl__set1(pr->fb), *z);
    keep = sbl__mandnot(keep, sbl__nonfinite(*m));
    if (pr->neg) *m = sbl__sub(sbl__set1(0.0f), *m);
    *exact = sbl__motion_exact(*m);
    return keep;
}

/* sbl__stereo_parallel_vec_in after its plan, where every lane has a match whose two
   taps are inside the image at one integer offset k (two = 0), or at k and k + 1 lane
   by lane (two = 1; up: the k + 1 lanes; two is a constant where this is inlined), and
   "full" taps (sbl__full_lanes); the same float and double operations per lane, hence
   the same bits: w0 = (1 - fx) (1 - 0) = 1 - fx and w1 = fx (1 - 0) = fx exactly; the
   sums unmasked where every tap of every lane passes, else masked (which is what the
   unmasked sums give where all pass); the back-check's floor(sx) = x + l + k_l +
   [m >= k_l + 1/2] (sx = x + l + 1/2 + m exact in double, see sbl__plan_lanes), so its
   source depth is the lane's tap 1's or tap 0's. flag: the unsafe values flagged as
   sbl__ring_gather's check would. Returns 0, nothing written, where the taps are not
   full or a lane is to redo. */
SBL__INLINE int sbl__parallel_vec_finish(const sbl__stereo_rp *s, const sbl__parallel_rows *pr,
                                         sbl__ring_row *r, int x, const int ch, int fallback,
                                         int back_check, double tol, int flag, sbl__v z, sbl__v slack,
                                         sbl__v m, sbl__v fm, int k, const int two, sbl__m up)
{
    const int all = (1 << SBL__VW) - 1;
    const sbl__v zero = sbl__set1(0.0f), one = sbl__set1(1.0f), fmax = sbl__set1(FLT_MAX);
    const sbl__v tol_d = sbl__set1(pr->tol);
    float mt[SBL__VW + 4], fs[SBL__VW + 4]; /* (sbl__dfromf reads VW + 4) */
    sbl__v fx, w0, lim, d0, d1, n0, n1 = zero, c0[3], c1[3], acc[3], accn, wsum, inv, n, out[4];
    sbl__m ok0, ok1, lo, nonfinite, valid;
    const float *dp, *np, *cp;
    const int x0 = x + k;
    int skip_x, fail = 0;
    if (!sbl__full_lanes(tol_d, z, slack)) return 0;
    lim = sbl__add(sbl__mul(tol_d, z), slack);
    fx = sbl__add(sbl__sub(m, fm), zero); /* (+ 0: as the plan) */
    w0 = sbl__sub(one, fx);
    skip_x = !sbl__mbits(sbl__gt(fx, zero));
    /* the taps: sbl__lanes_tap_test's full tests (d > 0 implied) */
    dp = pr->d + x0;
    np = pr->n + x0;
    cp = pr->c + SBL__CAST(ptrdiff_t, x0) * ch;
    {   /* the next row's taps (the match's row is the target's: it moves with y) */
        int o;
        for (o = 0; o < ch * SBL__VW; o += SBL__LINE_FLOATS) SBL__PREFETCH(cp, pr->cs + o);
        SBL__PREFETCH(dp, pr->ds);
        SBL__PREFETCH(np, pr->ns);
    }
    if (two) {
        /* each tap the lane's pick of two loads one float apart: the values its own
           offset addresses */
        const sbl__v d_1 = sbl__load(dp + 1), n_1 = sbl__load(np + 1);
        sbl__v c_0[3], c_1[3], c_2[3];
        int c;
        d0 = sbl__sel(up, d_1, sbl__load(dp));
        d1 = sbl__sel(up, sbl__load(dp + 2), d_1);
        n0 = sbl__sel(up, n_1, sbl__load(np));
        n1 = sbl__sel(up, sbl__load(np + 2), n_1);
        if (ch == 3) {
            sbl__rgb_lanes(cp, &c_0[0], &c_0[1], &c_0[2]);
            sbl__rgb_lanes(cp + 3, &c_1[0], &c_1[1], &c_1[2]);
            sbl__rgb_lanes(cp + 6, &c_2[0], &c_2[1], &c_2[2]);
        } else {
            c_0[0] = sbl__load(cp);
            c_1[0] = sbl__load(cp + 1);
            c_2[0] = sbl__load(cp + 2);
        }
        c1[0] = c1[1] = c1[2] = zero;
        for (c = 0; c < ch; ++c) {
            c0[c] = sbl__sel(up, c_1[c], c_0[c]);
            c1[c] = sbl__sel(up, c_2[c], c_1[c]);
        }
        ok0 = sbl__mand(sbl__mand(sbl__gt(w0, zero), sbl__le(sbl__abs(sbl__sub(d0, z)), lim)), sbl__gt(n0, zero));
        ok1 = ok0;
        if (!skip_x)
            ok1 = sbl__mand(sbl__mand(sbl__gt(fx, zero), sbl__le(sbl__abs(sbl__sub(d1, z)), lim)), sbl__gt(n1, zero));
    } else {
        d0 = sbl__load(dp);
        d1 = sbl__load(dp + 1);
        n0 = sbl__load(np);
        c1[0] = c1[1] = c1[2] = zero; /* (set where tap 1 weighs) */
        ok0 = sbl__mand(sbl__mand(sbl__gt(w0, zero), sbl__le(sbl__abs(sbl__sub(d0, z)), lim)), sbl__gt(n0, zero));
        ok1 = ok0;
        if (!skip_x) {
            n1 = sbl__load(np + 1);
            ok1 = sbl__mand(sbl__mand(sbl__gt(fx, zero), sbl__le(sbl__abs(sbl__sub(d1, z)), lim)), sbl__gt(n1, zero));
        }
        if (ch == 3) {
            sbl__rgb_lanes(cp, &c0[0], &c0[1], &c0[2]);
            if (!skip_x) sbl__rgb_lanes(cp + 3, &c1[0], &c1[1], &c1[2]);
        } else {
            c0[0] = sbl__load(cp);
            if (!skip_x) c1[0] = sbl__load(cp + 1);
        }
    }
    /* sbl__lanes_tap_sum's sums, each from 0 in the order tap 0, tap 1 (the channels
       written out: gcc -O2 keeps a loop's sums in memory). N's and the weight's first
       terms are >= +0 (w0 > 0; a tap that passes has N > 0), so 0 + them is them; a
       colour's may be -0. */
#define SBL__PSUM(T) \
    { \
        accn = T(w0, n0, ok0); \
        wsum = T(w0, one, ok0); \
        acc[0] = sbl__add(zero, T(w0, c0[0], ok0)); \
        if (ch > 1) { \
            acc[1] = sbl__add(zero, T(w0, c0[1], ok0)); \
            acc[2] = sbl__add(zero, T(w0, c0[2], ok0)); \
        } \
        if (!skip_x) { \
            accn = sbl__add(accn, T(fx, n1, ok1)); \
            wsum = sbl__add(wsum, T(fx, one, ok1)); \
            acc[0] = sbl__add(acc[0], T(fx, c1[0], ok1)); \
            if (ch > 1) { \
                acc[1] = sbl__add(acc[1], T(fx, c1[1], ok1)); \
                acc[2] = sbl__add(acc[2], T(fx, c1[2], ok1)); \
            } \
        } \
    }
    /* (w one: the weight itself, w 1 = w exactly) */
#define SBL__PTERM(w, v, ok) sbl__mul(w, v)
#define SBL__PTERM_M(w, v, ok) sbl__sel(ok, sbl__mul(w, v), zero)
    if (sbl__mbits(sbl__mand(ok0, ok1)) == all) SBL__PSUM(SBL__PTERM)
    else SBL__PSUM(SBL__PTERM_M)
#undef SBL__PSUM
#undef SBL__PTERM
#undef SBL__PTERM_M
    /* sbl__lanes_taps' end: a lane to redo leaves the vector to the blocks */
    nonfinite = sbl__mor(sbl__nonfinite(accn), sbl__nonfinite(acc[0]));
    if (ch > 1) nonfinite = sbl__mor(nonfinite, sbl__mor(sbl__nonfinite(acc[1]), sbl__nonfinite(acc[2])));
    lo = sbl__gt(sbl__set1(1e-3f), wsum);
    if (sbl__mbits(fallback ? sbl__mor(nonfinite, lo) : nonfinite)) return 0;
    /* wsum = (1 - fx) + fx where both taps pass: 1 in most lanes (fx = 0, or 1 - fx
       exact), and where it is 1 in all, 1 / wsum = 1 with the division skipped */
    inv = sbl__mbits(sbl__mand(sbl__le(wsum, one), sbl__le(one, wsum))) == all ? one
                                                                               : sbl__div_exact(one, wsum);
    n = sbl__min(sbl__max(sbl__mul(accn, inv), sbl__sub(zero, fmax)), fmax);
    valid = sbl__mandnot(sbl__gt(n, zero), lo);
    if (back_check && sbl__mbits(valid)) {
        /* sbl__stereo_back_parallel: the source depth at floor(sx), f b / it, the same
           double operations for ex. Where it equals the target's depth in every lane
           (a surface at one depth along the row: a floor, a wall facing the rig), f b
           / it is |m|, so bx = (x + l + 1/2 + m) - m = x + l + 1/2 exactly (the sum is
           exact, see sbl__plan_lanes), ex = 0: every check passes. */
        const sbl__v zs = sbl__sel(sbl__le(sbl__add(fm, sbl__set1(0.5f)), m), d1, d0);
        if (sbl__mbits(sbl__mand(sbl__le(zs, z), sbl__le(z, zs))) != all) {
            /* ex is (L + m) + dir1 f - L with L = x + l + 1/2, L + m exact, f = f b / zs
               rounded: the real e = m + dir1 f within |L| 2^-52 < 1e-10 (|L| < 2^16),
               and m + dir1 f b / zs within |f| 2^-24. So a lane passes the double test
               (tol >= 2e-3) wherever |m + dir1 f b / zs| <= tol / 2 is certain, which
               needs no division: g = m zs + dir1 f b is within (|m zs| + f b) 2^-23 of
               its real value (FMA or not), tested with 8 times that against tol / 2 zs
               (zs in [1e-20, 1e20]: m zs is normal, |m| >= 2^-8 where not 0; what a
               flush to zero can lose, a denormal f b or the margin, lies far inside the
               gap between tol / 2 and tol; +inf, whose f is 0, is left to the double
               test). Only the other
               lanes take the division and the double test. Depth that varies along
               the row (any surface not facing the rig) comes here at every vector. */
            const sbl__v fbv = sbl__set1(pr->fb), mz = sbl__mul(m, zs);
            const sbl__v g = pr->neg ? sbl__add(mz, fbv) : sbl__sub(mz, fbv);
            const sbl__v margin = sbl__mul(sbl__add(sbl__abs(mz), fbv), sbl__set1(1.0f / 1048576.0f));
            const int sure = sbl__mbits(sbl__mand(sbl__mand(sbl__le(sbl__set1(1e-20f), zs), sbl__le(zs, sbl__set1(1e20f))),
                                                  sbl__le(sbl__add(sbl__abs(g), margin),
                                                          sbl__mul(sbl__set1(pr->half_back), zs))));
            if (sbl__mbits(valid) & ~sure & all) {
                const sbl__v f = sbl__div_exact(fbv, zs);
                const int good = sbl__mbits(sbl__mandnot(sbl__gt(zs, zero), sbl__nonfinite(f)));
                int j, okb = 0;
                sbl__store(mt, m);
                sbl__store(fs, f);
                for (j = 0; j < SBL__VW; j += SBL__DW) {
                    const sbl__dv L = sbl__dadd(sbl__dload(sbl__lane_d), sbl__dset1(x + j + 0.5));
                    const sbl__dv bx = sbl__dadd(sbl__dadd(L, sbl__dfromf(mt + j)),
                                                 sbl__dmul(sbl__dset1(s->dir[1]),
                                                           sbl__dsub(sbl__dfromf(fs + j), sbl__dset1(s->offset))));
                    const sbl__dv ex = sbl__dsub(bx, L);
                    okb |= sbl__dle_bits(sbl__dmul(ex, ex), sbl__dset1(tol * tol)) << j;
                }
                fail = sbl__mbits(valid) & ~(okb & good) & all;
            }
        }
    }
    sbl__store(r->n + x, sbl__sel(valid, n, zero));
    sbl__store(r->v + x, sbl__sel(valid, one, zero));
    out[0] = n;
#define SBL__POUT(c) \
    { \
        out[c + 1] = sbl__min(sbl__max(sbl__mul(acc[c], inv), sbl__sub(zero, fmax)), fmax); \
        sbl__store(r->x[c] + x, sbl__sel(valid, out[c + 1], zero)); \
    }
    SBL__POUT(0);
    if (ch > 1) {
        SBL__POUT(1);
        SBL__POUT(2);
    }
#undef SBL__POUT
    if (flag
#if SBL__VW == 4
        && !sbl__all_safe(out, ch + 1) /* (SSE2: one test first, see sbl__lanes_taps) */
#endif
    ) {
        sbl__m ok = sbl__mand(sbl__lane_ok(out[0]), sbl__lane_ok(out[1]));
        int bits;
        if (ch > 1) ok = sbl__mand(ok, sbl__mand(sbl__lane_ok(out[2]), sbl__lane_ok(out[3])));
        bits = sbl__mbits(sbl__mandnot(valid, ok)) & ~fail;
        if (bits) sbl__ring_flag_bits(r, x, bits);
    }
    if (fail) { /* a failed back-check clears the column (rare) */
        int l;
        for (l = 0; fail; ++l, fail >>= 1)
            if (fail & 1) sbl__ring_put(r, x + l, 0.0f, NULL, ch);
    }
    return 1;
}

/* sbl__stereo_parallel_vec_in's vectors whose lanes lie at two offsets (a surface
   slanted to the rig: the disparity crosses an integer within the vector); out of line,
   so that the one-offset vectors, far more common, keep their registers. Offsets more
   than 1 apart go to the blocks. The plan is formed again here: vectors passed by value
   to a function not inlined are not portable (MSVC x86), and passed by address they
   would leave the caller's registers on its common path. */
SBL__NOINLINE int sbl__stereo_parallel_vec_two(const sbl__stereo_rp *s, const sbl__parallel_rows *pr,
                                               sbl__ring_row *r, int x, const int ch, int fallback,
                                               int back_check, double tol, int flag)
{
    float fms[SBL__VW];
    sbl__v z, slack, m, fm;
    sbl__m exact, keep = sbl__parallel_plan(pr, x, &z, &slack, &m, &exact), up;
    int l, k, kmax;
    fm = sbl__floor(m);
    sbl__store(fms, fm);
    k = kmax = SBL__CAST(int, fms[0]); /* (every lane is kept and exact: |fm| < 2^15) */
    for (l = 1; l < SBL__VW; ++l) {
        const int kl = SBL__CAST(int, fms[l]);
        k = kl < k ? kl : k;
        kmax = kl > kmax ? kl : kmax;
    }
    if (kmax != k + 1 || !(x + k >= 0 && x + k + SBL__VW + 1 <= pr->sw - 1))
        return sbl__stereo_parallel_none(s, r, x, keep, exact, m, ch);
    up = sbl__gt(fm, sbl__set1(SBL__CAST(float, k)));
    /* (ch as a constant in each instance, as in sbl__stereo_parallel_row's calls) */
    return ch == 3 ? sbl__parallel_vec_finish(s, pr, r, x, 3, fallback, back_check, tol, flag, z, slack, m, fm, k, 1, up)
                   : sbl__parallel_vec_finish(s, pr, r, x, 1, fallback, back_check, tol, flag, z, slack, m, fm, k, 1, up);
}

/* sbl__stereo_plan_vec (mode 1), sbl__row_taps and sbl__stereo_after_rig for the VW
   pixels x .. x + VW - 1 of row y (pr: its row's values) (x >= 0, x + VW <= w) in
   registers: the plan here, the rest in sbl__parallel_vec_finish (see there; two
   offsets in sbl__stereo_parallel_vec_two). Returns 0, nothing written, where a lane
   needs more (no match beside matches, a motion sbl__plan_lanes leaves to the scalar
   plan, taps outside the image, offsets more than 1 apart, not full, redo: the blocks
   then decide). */
SBL__INLINE int sbl__stereo_parallel_vec_in(const sbl__stereo_rp *s, const sbl__parallel_rows *pr,
                                            sbl__ring_row *r, int x, const int ch, int fallback,
                                            int back_check, double tol, int flag)
{
    const int all = (1 << SBL__VW) - 1;
    float fms[SBL__VW];
    sbl__v z, slack, m, fm;
    sbl__m exact, keep = sbl__parallel_plan(pr, x, &z, &slack, &m, &exact), kept, one_k;
    int k, x0;
    fm = sbl__floor(m);
    sbl__store(fms, fm);
    k = SBL__CAST(int, fms[0]); /* (used where every lane is kept: |fm| < 2^15) */
    x0 = x + k;
    kept = sbl__mand(keep, exact);
    one_k = sbl__mand(sbl__le(fm, sbl__set1(fms[0])), sbl__le(sbl__set1(fms[0]), fm));
    /* every lane kept, exact, at offset k, its taps inside: x0 + l in [0, w - 2] */
    if (sbl__mbits(sbl__mand(kept, one_k)) != all || !(x0 >= 0 && x0 + SBL__VW <= pr->sw - 1)) {
        if (sbl__mbits(kept) == all && sbl__mbits(one_k) != all)
            return sbl__stereo_parallel_vec_two(s, pr, r, x, ch, fallback, back_check, tol, flag);
        return sbl__stereo_parallel_none(s, r, x, keep, exact, m, ch);
    }
    return sbl__parallel_vec_finish(s, pr, r, x, ch, fallback, back_check, tol, flag, z, slack, m, fm, k, 0,
                                    sbl__gt(z, z));
}

/* sbl__stereo_parallel_vec_in with row y's values formed for this vector alone (tests) */
SBL__INLINE int sbl__stereo_parallel_vec(const sbl__stereo_rp *s, sbl__ring_row *r, int x, int y,
                                         const int ch, int fallback, int back_check, double tol,
                                         int flag)
{
    sbl__parallel_rows pr;
    sbl__parallel_rows_of(s, y, 0, s->geo.width, &pr);
    return sbl__stereo_parallel_vec_in(s, &pr, r, x, ch, fallback, back_check, tol, flag);
}

/* Row y's columns [xa, xb) (xb - xa >= VW) of the parallel rig, vector by vector: the
   fused vectors where they apply, the blocks (sbl__row_gather_blocks) for the runs of
   vectors they leave, whose unsafe values are then checked as sbl__ring_gather would.
   The last vector overlaps the one before; both ways write the same values. */
static void sbl__stereo_parallel_row(const sbl__stereo_rp *s, sbl__ring_row *r, int y, int xa,
                                     int xb)
{
    const int ch = s->src.color.ch, fallback = !s->d.reproject.no_fallback;
    const int back_check = !(s->d.reproject.disabled_tests & SBL_TEST_BACK_CHECK);
    const double tol = SBL__CAST(double, s->d.reproject.back_check_pixels);
    /* rows held for sbl_stereo_consistency and the adaptive cache have no flags */
    const int flag = r->unsafe != NULL;
    int x, pa = -1, pb = -1, done;
    sbl__parallel_rows pr;
    sbl__parallel_rows_of(s, y, xa, xb, &pr);
    if (flag) {
        r->gather_flags = 1;
        r->gather_unsafe = 0;
    }
    for (x = xa;; x += SBL__VW) {
        if (x + SBL__VW > xb) x = xb - SBL__VW;
        done = ch == 3 ? sbl__stereo_parallel_vec_in(s, &pr, r, x, 3, fallback, back_check, tol, flag)
                       : sbl__stereo_parallel_vec_in(s, &pr, r, x, 1, fallback, back_check, tol, flag);
        if (!done) {
            if (pa < 0) pa = x;
            pb = x + SBL__VW;
        }
        if ((done || x + SBL__VW >= xb) && pa >= 0) {
            sbl__row_gather_blocks(s, r, y, pa, pb, &s->src, fallback, sbl__stereo_rp_pixel,
                                   sbl__stereo_block_start, sbl__stereo_plan_vec, sbl__stereo_plan_one,
                                   sbl__stereo_block_after, NULL, NULL, 0, 0);
            if (flag) r->gather_unsafe += sbl__ring_flag_range(r, pa, pb, ch);
            pa = -1;
        }
        if (x + SBL__VW >= xb) break;
    }
}

/* The stereo reprojection of columns [xa, xb) of row y (sbl__row_gather_fn). */
static void sbl__stereo_rp_row(const void *ctx, struct sbl__ring_row *r, int y, int xa, int xb)
{
    const sbl__stereo_rp *s = SBL__PCAST(const sbl__stereo_rp *, ctx);
    if (xb - xa >= SBL__VW && sbl__stereo_parallel_ok(s, y)) {
        sbl__stereo_parallel_row(s, r, y, xa, xb);
        return;
    }
    sbl__row_gather_blocks(ctx, r, y, xa, xb, &s->src, !s->d.reproject.no_fallback,
                           sbl__stereo_rp_pixel, sbl__stereo_block_start, sbl__stereo_plan_vec,
                           sbl__stereo_plan_one, sbl__stereo_block_after, NULL, NULL, 0, 0);
}
#endif

/* An output of a stereo call must not overlap any buffer of either eye. */
static sbl_result sbl__check_outputs_vs_eyes(const sbl_image *o, const sbl_eye *a,
                                             const sbl_eye *b)
{
    return sbl__overlap_eye(o, a) || sbl__overlap_eye(o, b) ? SBL_ERROR_OVERLAP : SBL_OK;
}

SBLDEF sbl_result sbl_reproject_stereo(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                       const sbl_eye *target, const sbl_eye *source,
                                       sbl_image out_color, sbl_image out_valid,
                                       int y0, int y1)
{
    sbl__stereo_rp s;
    sbl_result r;
    int x, y, w, h, ch;
    if ((r = sbl__stereo_rp_init(&s, desc, target_eye, target, source, 0)) != SBL_OK) return r;
    w = source->color.width; h = source->color.height; ch = source->color.channels;
    if ((r = sbl__check_image(&out_color, ch)) != SBL_OK)
        return r == SBL_ERROR_INVALID_CHANNELS && out_color.channels >= 1 &&
                       out_color.channels <= 4 ? SBL_ERROR_CHANNEL_MISMATCH : r;
    if ((r = sbl__check_optional(&out_valid, 1, w, h)) != SBL_OK) return r;
    if (out_color.width != w || out_color.height != h) return SBL_ERROR_SIZE_MISMATCH;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    if (sbl__overlap(&out_color, &out_valid)) return SBL_ERROR_OVERLAP;
    if ((r = sbl__check_outputs_vs_eyes(&out_color, target, source)) != SBL_OK) return r;
    if ((r = sbl__check_outputs_vs_eyes(&out_valid, target, source)) != SBL_OK) return r;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < w; ++x) {
            float v[4] = {0, 0, 0, 0};
            float n = sbl__stereo_rp_pixel(&s, x, y, v);
            int valid = sbl__write_reprojected(&out_color, x, y, v, n, ch);
            if (out_valid.data) *sbl__px(&out_valid, x, y) = valid ? 1.0f : 0.0f;
        }
    return SBL_OK;
}

SBLDEF size_t sbl_stereo_scratch_size(int width, int channels)
{
    const size_t kb = sbl__kernel_scratch_size(width, channels);
    /* + the row of the eyes' change flags (sbl_eye.evidence, 6.15) */
    return kb ? kb + sizeof(float) * sbl__plane_floats(width) + 64 : 0;
}

/* All validation of a stereo blend with its outputs, without writing anything. */
static sbl_result sbl__stereo_output_check(sbl__stereo_rp *s, const sbl_stereo_desc *desc,
                                           sbl_eye_index target_eye, const sbl_eye *target,
                                           const sbl_eye *source, const sbl_image *out_color,
                                           const sbl_image *out_length,
                                           const sbl_image *out_beta)
{
    sbl_result r;
    int w, h;
    if ((r = sbl__stereo_rp_init(s, desc, target_eye, target, source, 1)) != SBL_OK) return r;
    w = target->color.width; h = target->color.height;
    if ((r = sbl__check_weight_params(s->d.estimator, s->d.rectify, s->d.weight_mode,
                                      s->d.constant_beta, 0.0f, s->d.clip_gamma,
                                      s->d.bias_threshold)) != SBL_OK)
        return r;
    if ((r = sbl__check_image(out_color, 0)) != SBL_OK) return r;
    if (out_color->width != w || out_color->height != h) return SBL_ERROR_SIZE_MISMATCH;
    if (out_color->channels != target->color.channels) return SBL_ERROR_CHANNEL_MISMATCH;
    if ((r = sbl__check_optional(out_length, 1, w, h)) != SBL_OK) return r;
    if ((r = sbl__check_optional(out_beta, 1, w, h)) != SBL_OK) return r;
    if (sbl__overlap(out_color, out_length) || sbl__overlap(out_color, out_beta) ||
        sbl__overlap(out_length, out_beta))
        return SBL_ERROR_OVERLAP;
    if ((r = sbl__check_outputs_vs_eyes(out_color, target, source)) != SBL_OK) return r;
    if ((r = sbl__check_outputs_vs_eyes(out_length, target, source)) != SBL_OK) return r;
    if ((r = sbl__check_outputs_vs_eyes(out_beta, target, source)) != SBL_OK) return r;
    return SBL_OK;
}

/* All validation of a stereo blend, without writing anything. */
static sbl_result sbl__stereo_blend_check(sbl__stereo_rp *s, const sbl_stereo_desc *desc,
                                          sbl_eye_index target_eye, const sbl_eye *target,
                                          const sbl_eye *source, const sbl_image *out_color,
                                          const sbl_image *out_length)
{
    sbl_image none;
    memset(&none, 0, sizeof none);
    return sbl__stereo_output_check(s, desc, target_eye, target, source, out_color,
                                    out_length, &none);
}

/* The row kernel of a stereo blend of `target` (validated by the caller); beta may be
   NULL. Shared by sbl_stereo_filter and sbl_stereo_blend_masked. */
static void sbl__stereo_kernel_setup(sbl__kernel *k, const sbl__stereo_rp *s,
                                     const sbl_eye *target, const sbl_image *color,
                                     const sbl_image *length, const sbl_image *beta,
                                     void *scratch)
{
    memset(k, 0, sizeof *k);
    k->w = target->color.width; k->h = target->color.height; k->ch = target->color.channels;
    k->wp = sbl__weight_params_make(s->d.estimator, s->d.rectify, s->d.weight_mode,
                                    s->d.constant_beta, 0.0f, s->d.clip_gamma,
                                    s->d.bias_threshold);
    k->n_cap = FLT_MAX;
    k->temporal = 0;
    k->fill = s->d.fill;
    k->own = &target->color;
    k->own_n = &target->length;
    k->gather = sbl__stereo_rp_pixel;
    k->gather_ctx = s;
#ifdef SBL__ROW_GATHER
    if (sbl__row_gather_ok(&s->src)) k->gather_row = sbl__stereo_rp_row;
#endif
    k->out = *color;
    k->out_n = *length;
    if (beta) k->out_a = *beta;
    sbl__kernel_bind(k, scratch);
    if (s->d.estimator == SBL_ESTIMATOR_POOLED && !s->d.fill &&
        (target->evidence.data || s->source->evidence.data)) {
        /* the eyes' change evidence (6.15): one row of flags after the kernel's scratch */
        k->sev = SBL__PCAST(float *, sbl__align64(SBL__PCAST(char *, scratch) +
                                                  sbl__kernel_scratch_size(k->w, k->ch)));
        k->sev_own = target->evidence.data ? &target->evidence : NULL;
        k->sev_other = s->source->evidence.data ? &s->source->evidence : NULL;
        k->sev_rp = s;
        k->wp.stereo_ev = 1;
    }
}

SBLDEF sbl_result sbl_stereo_filter(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                    const sbl_eye *target, const sbl_eye *source,
                                    const sbl_stereo_output *out, int y0, int y1,
                                    void *scratch, size_t scratch_bytes)
{
    sbl__stereo_rp s;
    sbl__kernel k;
    sbl_result r;
    if (!out) return SBL_ERROR_NULL_POINTER;
    if ((r = sbl__stereo_output_check(&s, desc, target_eye, target, source, &out->color,
                                      &out->length, &out->beta)) != SBL_OK)
        return r;
    if ((r = sbl__check_rows(y0, y1, target->color.height)) != SBL_OK) return r;
    if (!scratch) return SBL_ERROR_NULL_POINTER;
    if (sbl_stereo_scratch_size(target->color.width, target->color.channels) == 0)
        return SBL_ERROR_INVALID_SIZE; /* too wide to size */
    if (scratch_bytes < sbl_stereo_scratch_size(target->color.width, target->color.channels))
        return SBL_ERROR_SCRATCH_TOO_SMALL;
    sbl__stereo_kernel_setup(&k, &s, target, &out->color, &out->length, &out->beta, scratch);
    sbl__kernel_run(&k, y0, y1);
    return SBL_OK;
}

SBLDEF sbl_result sbl_stereo_blend(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                   const sbl_eye *target, const sbl_eye *source,
                                   sbl_image out_color, sbl_image out_length,
                                   int y0, int y1, void *scratch, size_t scratch_bytes)
{
    sbl_stereo_output out;
    memset(&out, 0, sizeof out);
    out.color = out_color;
    out.length = out_length;
    return sbl_stereo_filter(desc, target_eye, target, source, &out, y0, y1, scratch,
                             scratch_bytes);
}

/* ------------------------------------------------------------------------ */
/* Diagnostics                                                              */
/* ------------------------------------------------------------------------ */

/* The walk over named arguments: the first check that fails with the code the call
   returns is the culprit, so the named field always explains the actual result. */
typedef struct sbl__walk {
    sbl_diag *d;
    sbl_result want;
    int found;
} sbl__walk;

static void sbl__diag_copy(char *dst, size_t n, const char *a, const char *b)
{
    size_t i = 0, j;
    for (j = 0; a && a[j] && i + 1 < n; ++j) dst[i++] = a[j];
    for (j = 0; b && b[j] && i + 1 < n; ++j) dst[i++] = b[j];
    dst[i] = '\0';
}

/* Records field (name + suffix) and message if r is the code looked for. */
static int sbl__blame(sbl__walk *w, sbl_result r, const char *name, const char *suffix,
                      const char *message)
{
    if (w->found || r == SBL_OK || r != w->want) return 0;
    w->found = 1;
    sbl__diag_copy(w->d->field, sizeof w->d->field, name, suffix);
    sbl__diag_copy(w->d->message, sizeof w->d->message, message, NULL);
    return 1;
}

static void sbl__warn(sbl_diag *d, const char *name, const char *message)
{
    if (d->warning[0]) return;
    sbl__diag_copy(d->warning, sizeof d->warning, name, message);
}

/* A named view: why sbl__check_image / sbl__check_optional refuse it. w = 0: no size
   to match. Returns the code. */
static sbl_result sbl__walk_image(sbl__walk *wk, const char *name, const sbl_image *im,
                                  int want_ch, int w, int h, int optional)
{
    sbl_result r;
    char msg[160];
    if (!im->data) {
        if (optional) return SBL_OK;
        sbl__blame(wk, SBL_ERROR_NULL_POINTER, name, ".data", "is NULL: the buffer is required");
        return SBL_ERROR_NULL_POINTER;
    }
    r = sbl__check_image(im, want_ch);
    switch (r) {
    case SBL_ERROR_INVALID_SIZE:
        if (im->width <= 0 || im->height <= 0) {
            snprintf(msg, sizeof msg, "%d x %d: width and height must be > 0", im->width,
                     im->height);
            sbl__blame(wk, r, name, ".width", msg);
        } else if (im->size_bytes != 0 && im->width <= INT_MAX / 4 && im->height <= INT_MAX / 4) {
            snprintf(msg, sizeof msg, "%zu bytes, but the layout (rows, strides) reaches over "
                     "%zu bytes: is a pitch in bytes given in the float field `stride`?",
                     im->size_bytes, sbl__footprint(im));
            sbl__blame(wk, r, name, ".size_bytes", msg);
        } else {
            sbl__blame(wk, r, name, ".width", "too large to address");
        }
        break;
    case SBL_ERROR_INVALID_CHANNELS:
        if (want_ch) snprintf(msg, sizeof msg, "%d, this buffer needs %d", im->channels, want_ch);
        else snprintf(msg, sizeof msg, "%d, outside 1..4", im->channels);
        sbl__blame(wk, r, name, ".channels", msg);
        break;
    case SBL_ERROR_INVALID_STRIDE:
        if (im->stride_bytes % SBL__CAST(int, sizeof(float)) != 0) {
            snprintf(msg, sizeof msg, "%d is not a multiple of sizeof(float)", im->stride_bytes);
            sbl__blame(wk, r, name, ".stride_bytes", msg);
        } else if (im->pixel_bytes % SBL__CAST(int, sizeof(float)) != 0 ||
                   (im->pixel_bytes != 0 &&
                    im->pixel_bytes < im->channels * SBL__CAST(int, sizeof(float)))) {
            snprintf(msg, sizeof msg,
                     "%d: must be a multiple of sizeof(float) and hold %d channels",
                     im->pixel_bytes, im->channels);
            sbl__blame(wk, r, name, ".pixel_bytes", msg);
        } else if (im->stride_bytes != 0 && im->stride != 0) {
            snprintf(msg, sizeof msg, "%d bytes disagrees with stride = %d floats (give one)",
                     im->stride_bytes, im->stride);
            sbl__blame(wk, r, name, ".stride_bytes", msg);
        } else {
            snprintf(msg, sizeof msg,
                     "a row of %d pixels does not fit in |row stride| (%td floats): "
                     "rows would overlap", im->width, sbl__stride(im));
            sbl__blame(wk, r, name, im->stride_bytes ? ".stride_bytes" : ".stride", msg);
        }
        break;
    default:
        sbl__blame(wk, r, name, "", sbl_result_string(r));
        break;
    }
    if (r == SBL_OK && w > 0 && (im->width != w || im->height != h)) {
        r = SBL_ERROR_SIZE_MISMATCH;
        snprintf(msg, sizeof msg, "%d x %d, expected %d x %d", im->width, im->height, w, h);
        sbl__blame(wk, r, name, ".width", msg);
    }
    return r;
}

static void sbl__walk_gbuffer(sbl__walk *wk, const char *name, const sbl_gbuffer *g, int w, int h)
{
    char f[64];
    sbl__diag_copy(f, sizeof f, name, ".depth");
    sbl__walk_image(wk, f, &g->depth, 1, w, h, 1);
    sbl__diag_copy(f, sizeof f, name, ".normals");
    sbl__walk_image(wk, f, &g->normals, 3, w, h, 1);
    sbl__diag_copy(f, sizeof f, name, ".ids");
    sbl__walk_image(wk, f, &g->ids, 1, w, h, 1);
    sbl__diag_copy(f, sizeof f, name, ".motion");
    sbl__walk_image(wk, f, &g->motion, 2, w, h, 1);
}

/* Overlap of two views that may not have passed validation (the walk goes on after a
   failure): only valid views have a meaningful footprint. */
static int sbl__overlap_checked(const sbl_image *a, const sbl_image *b)
{
    return a->data && b->data && sbl__check_image(a, 0) == SBL_OK &&
           sbl__check_image(b, 0) == SBL_OK && sbl__overlap(a, b);
}

/* An output against a named list of views it may not share a float with. */
static void sbl__walk_overlap(sbl__walk *wk, const char *name, const sbl_image *o,
                              const sbl_image *const *in, const char *const *in_names, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (in[i] && sbl__overlap_checked(o, in[i]))
            sbl__blame(wk, SBL_ERROR_OVERLAP, name, "", in_names[i]);
}

/* The G-buffer tests a pair of views runs: warn where one side has a buffer the other
   lacks (the test is then silently off). */
static void sbl__warn_gbuffers(sbl_diag *d, const char *a_name, const sbl_gbuffer *a,
                               const char *b_name, const sbl_gbuffer *b)
{
    const sbl_image *ai[3], *bi[3];
    const char *what[3] = {".depth", ".normals", ".ids"};
    const char *test[3] = {": absent while the other view has it, so the depth test is off",
                           ": absent while the other view has it, so the normal test is off",
                           ": absent while the other view has it, so the id test is off"};
    int i;
    char f[96];
    ai[0] = &a->depth; ai[1] = &a->normals; ai[2] = &a->ids;
    bi[0] = &b->depth; bi[1] = &b->normals; bi[2] = &b->ids;
    for (i = 0; i < 3; ++i) {
        if (!ai[i]->data == !bi[i]->data) continue;
        sbl__diag_copy(f, sizeof f, ai[i]->data ? b_name : a_name, what[i]);
        sbl__warn(d, f, test[i]);
    }
}

SBLDEF sbl_result sbl_temporal_validate(const sbl_temporal_desc *desc, const sbl_frame *frame,
                                        const sbl_history *history,
                                        const sbl_temporal_output *out, sbl_diag *diag)
{
    sbl_diag local;
    sbl__walk wk;
    sbl_result r;
    int w, h;
    if (!diag) diag = &local;
    memset(diag, 0, sizeof *diag);
    /* scratch NULL: the filter runs every other check first, so NULL_POINTER with every
       required pointer present means the arguments are valid */
    r = sbl_temporal_filter(desc, frame, history, out, 0, 0, NULL, 0);
    wk.d = diag; wk.want = r; wk.found = 0;
    if (!desc) sbl__blame(&wk, r, "desc", "", "is NULL");
    if (!frame) sbl__blame(&wk, r, "frame", "", "is NULL");
    if (!out) sbl__blame(&wk, r, "out", "", "is NULL");
    if (!desc || !frame || !out) { diag->result = r; return r; }
    w = frame->color.width; h = frame->color.height;
    sbl__walk_image(&wk, "frame->color", &frame->color, 0, 0, 0, 0);
    sbl__walk_image(&wk, "out->color", &out->color, 0, w, h, 0);
    sbl__walk_image(&wk, "out->length", &out->length, 1, w, h, 0);
    sbl__walk_image(&wk, "out->alpha", &out->alpha, 1, w, h, 1);
    sbl__walk_image(&wk, "out->evidence", &out->evidence, 1, w, h, 1);
    sbl__walk_image(&wk, "out->tail", &out->tail, 2, w, h, 1);
    if (out->display.data)
        sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "out->display", ".data",
                   "is written by sbl_temporal_filter_frame or sbl_temporal_display, not by row calls");
    if (r == SBL_ERROR_NULL_POINTER && !wk.found) r = wk.want = SBL_OK; /* the scratch */
    if (out->color.data && out->color.channels != frame->color.channels)
        sbl__blame(&wk, SBL_ERROR_CHANNEL_MISMATCH, "out->color", ".channels",
                   "differs from frame->color.channels");
    {   /* parameters, one at a time against the defaults */
        sbl_temporal_desc z = sbl_temporal_defaults(NULL), u = sbl_temporal_defaults(desc), t;
        char msg[96];
#define SBL__TRY_WEIGHT(fieldname)                                                          \
        t = z; t.fieldname = u.fieldname;                                                   \
        if (sbl__check_weight_params(t.estimator, t.rectify, t.weight_mode, t.constant_alpha, \
                                     t.alpha_min, t.clip_gamma, t.bias_threshold) != SBL_OK) { \
            snprintf(msg, sizeof msg, "%g is out of range or not finite",                   \
                     SBL__CAST(double, u.fieldname));                                           \
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->" #fieldname, "", msg);         \
        }
        SBL__TRY_WEIGHT(estimator)
        SBL__TRY_WEIGHT(rectify)
        SBL__TRY_WEIGHT(weight_mode)
        SBL__TRY_WEIGHT(constant_alpha)
        SBL__TRY_WEIGHT(alpha_min)
        SBL__TRY_WEIGHT(clip_gamma)
        SBL__TRY_WEIGHT(bias_threshold)
#undef SBL__TRY_WEIGHT
        if (!sbl__finite(u.max_history) || u.max_history < 1.0f)
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->max_history", "",
                       "must be finite and >= 1");
        if (!sbl__param_ok(u.stereo_shared_bias) || u.stereo_shared_bias > 1.0f)
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->stereo_shared_bias", "",
                       "must be in [0, 1] or SBL_SHARED_BIAS_NONE");
#define SBL__TRY_RP(fieldname)                                                              \
        t = z; t.reproject.fieldname = u.reproject.fieldname;                               \
        if (sbl__check_reproject_desc(&t.reproject) != SBL_OK)                              \
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->reproject." #fieldname, "",    \
                       "out of range or not finite");
        SBL__TRY_RP(depth_tolerance)
        SBL__TRY_RP(normal_threshold)
        SBL__TRY_RP(back_check_pixels)
        SBL__TRY_RP(motion.units)
        SBL__TRY_RP(disabled_tests)
        SBL__TRY_RP(history_filter)
#undef SBL__TRY_RP
        if (SBL__CAST(int, u.source) < 0 ||
            SBL__CAST(int, u.source) > SBL__CAST(int, SBL_TEMPORAL_CAMERA))
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->source", "",
                       "not an sbl_temporal_source");
        sbl__walk_gbuffer(&wk, "frame->gbuffer", &frame->gbuffer, w, h);
        if (history && history->color.data) {
            sbl__walk_image(&wk, "history->color", &history->color, 0, w, h, 0);
            if (history->color.channels != frame->color.channels)
                sbl__blame(&wk, SBL_ERROR_CHANNEL_MISMATCH, "history->color", ".channels",
                           "differs from frame->color.channels");
            sbl__walk_image(&wk, "history->length", &history->length, 1, w, h, 1);
            sbl__walk_image(&wk, "history->evidence", &history->evidence, 1, w, h, 1);
            sbl__walk_image(&wk, "history->tail", &history->tail, 2, w, h, 1);
            sbl__walk_gbuffer(&wk, "history->gbuffer", &history->gbuffer, w, h);
        }
        if (u.source == SBL_TEMPORAL_MOTION && !frame->gbuffer.motion.data)
            sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, "frame->gbuffer.motion", "",
                       "is absent: SBL_TEMPORAL_MOTION needs motion vectors");
        if (u.source == SBL_TEMPORAL_CAMERA) {
            if (!frame->gbuffer.depth.data)
                sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, "frame->gbuffer.depth", "",
                           "is absent: SBL_TEMPORAL_CAMERA needs depth");
            if (!frame->camera)
                sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, "frame->camera", "",
                           "is NULL: SBL_TEMPORAL_CAMERA needs both frames' cameras");
            if (frame->object_count && !frame->gbuffer.ids.data)
                sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, "frame->gbuffer.ids", "",
                           "is absent: frame->objects are found through the id buffer");
            if (!sbl__objects_ok(frame->objects, frame->object_count))
                sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "frame->objects", "",
                           "need finite, invertible transforms, sorted by distinct ids "
                           "(and object_count >= 0)");
            if (history && history->color.data && !history->camera)
                sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, "history->camera", "",
                           "is NULL: SBL_TEMPORAL_CAMERA needs both frames' cameras");
            if (frame->camera && history && history->color.data && history->camera) {
                sbl__cam_map m;
                if (!sbl__cam_map_init(&m, frame->camera, w, h, history->camera, w, h))
                    sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "frame->camera / history->camera",
                               "", "a matrix is not finite, or a projection or view matrix "
                               "is singular");
            }
        }
    }
    {   /* outputs: disjoint from each other and from every input */
        const sbl_image *o[SBL__PLANES_MAX], *in[5 + SBL__PLANES_MAX];
        const char *on[5] = {"out->color", "out->length", "out->alpha", "out->evidence", "out->tail"};
        const char *names[13] = {
            "overlaps frame->color", "overlaps frame->gbuffer.depth",
            "overlaps frame->gbuffer.normals", "overlaps frame->gbuffer.ids",
            "overlaps frame->gbuffer.motion", "overlaps history->color",
            "overlaps history->length", "overlaps history->gbuffer.depth",
            "overlaps history->gbuffer.normals", "overlaps history->gbuffer.ids",
            "overlaps history->gbuffer.motion", "overlaps history->evidence",
            "overlaps history->tail"};
        int i, j, n;
        const sbl_history *hi = history && history->color.data ? history : NULL;
        /* in the names' order: 5 outputs; the frame's 5 planes, then the history's 8 */
        sbl__temporal_output_planes(out, o);
        n = sbl__frame_planes(frame, in);
        n += sbl__history_planes(hi, in + n, 1);
        for (i = 0; i < 5; ++i)
            for (j = i + 1; j < 5; ++j)
                if (sbl__overlap_checked(o[i], o[j]))
                    sbl__blame(&wk, SBL_ERROR_OVERLAP, on[j], "", on[i]);
        for (i = 0; i < 5; ++i) sbl__walk_overlap(&wk, on[i], o[i], in, names, n);
    }
    if (r != SBL_OK && !wk.found) {
        sbl__diag_copy(diag->field, sizeof diag->field, "(not located)", NULL);
        sbl__diag_copy(diag->message, sizeof diag->message, sbl_result_string(r), NULL);
    }
    /* legal but probably unintended */
    if (history && history->color.data) {
        sbl__warn_gbuffers(diag, "frame->gbuffer", &frame->gbuffer, "history->gbuffer",
                           &history->gbuffer);
        if (!history->length.data)
            sbl__warn(diag, "history->length",
                      ": absent, so N = 1 everywhere (the progressive and history-aware "
                      "estimators then blend 1:1): pass last frame's out->length");
    }
    diag->result = r;
    return r;
}

/* Round-trip error of the rig's correspondence over a sample of target pixels (a grid
   of at most ~64 x 64): target -> source -> back from the nearest source pixel. With the
   right eye assignment it is the error of a nearest-pixel lookup; with the eyes swapped
   the match lands on another point and the error grows with the disparity gradient
   (zero only where the disparity is constant, where a swap cannot be seen). */
static double sbl__sample_roundtrip(const sbl__stereo_rp *s, int w, int h, long *count)
{
    int stx = w / 64 + 1, sty = h / 64 + 1, x, y;
    double sum = 0.0;
    long n = 0;
    for (y = sty / 2; y < h; y += sty)
        for (x = stx / 2; x < w; x += stx) {
            double sx, sy, sz, bx, by, bz, ex, ey;
            float z;
            sbl__tap_want want;
            if (!sbl__tap_want_init(&want, &s->geo, x, y, &z)) continue;
            if (!sbl__stereo_map(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz)) continue;
            if (!(sx >= 0.0 && sx < SBL__CAST(double, w) && sy >= 0.0 && sy < SBL__CAST(double, h)))
                continue;
            if (!sbl__stereo_map(s, 1, SBL__CAST(int, floor(sx)), SBL__CAST(int, floor(sy)), sx, sy, &bx,
                        &by, &bz))
                continue;
            ex = bx - (x + 0.5);
            ey = by - (y + 0.5);
            if (!(ex * ex + ey * ey < 1e6)) continue;
            sum += sqrt(ex * ex + ey * ey);
            ++n;
        }
    *count = n;
    return n ? sum / SBL__CAST(double, n) : 0.0;
}

SBLDEF sbl_result sbl_stereo_validate(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                      const sbl_eye *target, const sbl_eye *source,
                                      const sbl_stereo_output *out, sbl_diag *diag)
{
    sbl_diag local;
    sbl__walk wk;
    sbl__stereo_rp s;
    sbl_result r;
    int e, w, h;
    if (!diag) diag = &local;
    memset(diag, 0, sizeof *diag);
    if (out) {
        r = sbl_stereo_filter(desc, target_eye, target, source, out, 0, 0, NULL, 0);
    } else {
        r = sbl__stereo_rp_init(&s, desc, target_eye, target, source, 0);
        if (r == SBL_OK) r = SBL_ERROR_NULL_POINTER; /* as the filter reports a NULL scratch */
    }
    wk.d = diag; wk.want = r; wk.found = 0;
    if (!desc) sbl__blame(&wk, r, "desc", "", "is NULL");
    if (!target) sbl__blame(&wk, r, "target", "", "is NULL");
    if (!source) sbl__blame(&wk, r, "source", "", "is NULL");
    if (!desc || !target || !source) { diag->result = r; return r; }
    w = source->color.width; h = source->color.height;
    for (e = 0; e < 2; ++e) {
        const sbl_eye *eye = e ? source : target;
        const char *nm = e ? "source" : "target";
        int need = e || out;
        char f[64];
        sbl__diag_copy(f, sizeof f, nm, "->color");
        sbl__walk_image(&wk, f, &eye->color, 0, e ? 0 : w, h, !need);
        sbl__diag_copy(f, sizeof f, nm, "->gbuffer");
        sbl__walk_gbuffer(&wk, f, &eye->gbuffer, w, h);
        sbl__diag_copy(f, sizeof f, nm, "->length");
        sbl__walk_image(&wk, f, &eye->length, 1, w, h, 1);
        sbl__diag_copy(f, sizeof f, nm, "->evidence");
        sbl__walk_image(&wk, f, &eye->evidence, 1, w, h, 1);
        sbl__diag_copy(f, sizeof f, nm, "->disparity");
        sbl__walk_image(&wk, f, &eye->disparity, 0, w, h, 1);
        if (eye->disparity.data && eye->disparity.channels > 2)
            sbl__blame(&wk, SBL_ERROR_INVALID_CHANNELS, f, ".channels",
                       "a disparity map has 1 (d_x) or 2 (d_x, d_y) channels");
        if (!need && !eye->gbuffer.depth.data && !eye->disparity.data)
            sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, nm, "->gbuffer.depth",
                       "is absent: the target's geometry (depth or disparity) is required");
        sbl__diag_copy(f, sizeof f, nm, "->gbuffer.depth");
        if (desc->rig != SBL_RIG_DISPARITY && !eye->gbuffer.depth.data)
            sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, f, "",
                       "is absent: this rig needs both eyes' depth");
        sbl__diag_copy(f, sizeof f, nm, "->disparity");
        if (desc->rig == SBL_RIG_DISPARITY && !eye->disparity.data)
            sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, f, "",
                       "is absent: SBL_RIG_DISPARITY needs both eyes' maps");
        sbl__diag_copy(f, sizeof f, nm, "->camera");
        if (desc->rig == SBL_RIG_MATRICES && !eye->camera)
            sbl__blame(&wk, SBL_ERROR_MISSING_INPUT, f, "",
                       "is NULL: SBL_RIG_MATRICES needs both eyes' cameras");
    }
    if (desc->rig == SBL_RIG_MATRICES && target->camera && source->camera) {
        sbl__cam_map m;
        if (!sbl__cam_map_init(&m, target->camera, w, h, source->camera, w, h))
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "target->camera / source->camera", "",
                       "a matrix is not finite, or a projection or view matrix is singular");
    }
    if (r == SBL_ERROR_NULL_POINTER && !wk.found) r = wk.want = SBL_OK; /* the scratch */
    if (out) {
        sbl__walk_image(&wk, "out->color", &out->color, 0, w, h, 0);
        sbl__walk_image(&wk, "out->length", &out->length, 1, w, h, 1);
        sbl__walk_image(&wk, "out->beta", &out->beta, 1, w, h, 1);
        if (out->color.data && out->color.channels != target->color.channels)
            sbl__blame(&wk, SBL_ERROR_CHANNEL_MISMATCH, "out->color", ".channels",
                       "differs from target->color.channels");
    }
    if (target->color.data && source->color.data &&
        target->color.channels != source->color.channels)
        sbl__blame(&wk, SBL_ERROR_CHANNEL_MISMATCH, "target->color", ".channels",
                   "differs from source->color.channels");
    if (sbl__eye_width(target) != w || sbl__eye_height(target) != h)
        sbl__blame(&wk, SBL_ERROR_SIZE_MISMATCH, "target", "", "differs in size from source");
    {
        sbl_stereo_desc z = sbl_stereo_defaults(NULL), u = sbl_stereo_defaults(desc), t;
        char msg[96];
        if (SBL__CAST(int, u.rig) < 0 || u.rig >= SBL_RIG_COUNT)
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->rig", "", "not an sbl_stereo_rig");
        if (SBL__CAST(int, target_eye) != 0 && SBL__CAST(int, target_eye) != 1)
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "target_eye", "",
                       "must be SBL_EYE_LEFT or SBL_EYE_RIGHT");
        if (u.rig == SBL_RIG_PARALLEL) {
            if (!sbl__finite(u.focal_px) || !(u.focal_px > 0.0f))
                sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->focal_px", "",
                           "must be finite and > 0 for SBL_RIG_PARALLEL");
            if (!sbl__finite(u.baseline) || !(u.baseline > 0.0f))
                sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->baseline", "",
                           "must be finite and > 0 for SBL_RIG_PARALLEL");
            if (!sbl__finite(u.disparity_offset))
                sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->disparity_offset", "",
                           "not finite");
        }
        if (u.rig == SBL_RIG_PINHOLE) {
            double v[16], p[16], inv[16];
            float id[16];
            int i;
            for (i = 0; i < 16; ++i) id[i] = (i % 5 == 0) ? 1.0f : 0.0f;
            for (e = 0; e < 2; ++e)
                if (!sbl__pinhole_gl(&u.pinhole.eye[e], id, u.pinhole.axes, 0, w > 0 ? w : 1,
                                     h > 0 ? h : 1, v, p))
                    sbl__blame(&wk, SBL_ERROR_INVALID_PARAM,
                               e ? "desc->pinhole.eye[1]" : "desc->pinhole.eye[0]", "",
                               "fx, fy must be > 0 and everything finite (or axes invalid)");
            for (i = 0; i < 16; ++i) v[i] = SBL__CAST(double, u.pinhole.right_from_left[i]);
            if (!sbl__mat_invert(inv, v))
                sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->pinhole.right_from_left", "",
                           "not finite or singular (a zero-initialised pose is singular: "
                           "set at least the identity)");
        }
#define SBL__TRY_WEIGHT(fieldname)                                                          \
        t = z; t.fieldname = u.fieldname;                                                   \
        if (out && sbl__check_weight_params(t.estimator, t.rectify, t.weight_mode,           \
                                            t.constant_beta,                                \
                                     0.0f, t.clip_gamma, t.bias_threshold) != SBL_OK) {     \
            snprintf(msg, sizeof msg, "%g is out of range or not finite",                   \
                     SBL__CAST(double, u.fieldname));                                           \
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->" #fieldname, "", msg);         \
        }
        SBL__TRY_WEIGHT(estimator)
        SBL__TRY_WEIGHT(rectify)
        SBL__TRY_WEIGHT(weight_mode)
        SBL__TRY_WEIGHT(constant_beta)
        SBL__TRY_WEIGHT(clip_gamma)
        SBL__TRY_WEIGHT(bias_threshold)
#undef SBL__TRY_WEIGHT
#define SBL__TRY_RP(fieldname)                                                              \
        t = z; t.reproject.fieldname = u.reproject.fieldname;                               \
        if (sbl__check_reproject_desc(&t.reproject) != SBL_OK)                              \
            sbl__blame(&wk, SBL_ERROR_INVALID_PARAM, "desc->reproject." #fieldname, "",    \
                       "out of range or not finite");
        SBL__TRY_RP(depth_tolerance)
        SBL__TRY_RP(normal_threshold)
        SBL__TRY_RP(back_check_pixels)
        SBL__TRY_RP(disabled_tests)
        SBL__TRY_RP(history_filter)
#undef SBL__TRY_RP
    }
    if (out) {
        const sbl_image *o[3], *in[2 * SBL__PLANES_MAX];
        const char *on[3] = {"out->color", "out->length", "out->beta"};
        const char *names[16] = {
            "overlaps target->color", "overlaps target->length", "overlaps target->disparity",
            "overlaps target->evidence",
            "overlaps target->gbuffer.depth", "overlaps target->gbuffer.normals",
            "overlaps target->gbuffer.ids", "overlaps target->gbuffer.motion",
            "overlaps source->color", "overlaps source->length", "overlaps source->disparity",
            "overlaps source->evidence",
            "overlaps source->gbuffer.depth", "overlaps source->gbuffer.normals",
            "overlaps source->gbuffer.ids", "overlaps source->gbuffer.motion"};
        int i, j, n;
        n = sbl__eye_planes(target, in); /* in the names' order: 8 planes an eye */
        n += sbl__eye_planes(source, in + n);
        o[0] = &out->color; o[1] = &out->length; o[2] = &out->beta;
        for (i = 0; i < 3; ++i)
            for (j = i + 1; j < 3; ++j)
                if (sbl__overlap_checked(o[i], o[j]))
                    sbl__blame(&wk, SBL_ERROR_OVERLAP, on[j], "", on[i]);
        for (i = 0; i < 3; ++i) sbl__walk_overlap(&wk, on[i], o[i], in, names, n);
    }
    if (r != SBL_OK && !wk.found) {
        sbl__diag_copy(diag->field, sizeof diag->field, "(not located)", NULL);
        sbl__diag_copy(diag->message, sizeof diag->message, sbl_result_string(r), NULL);
    }
    /* legal but probably unintended */
    if (r == SBL_OK) {
        sbl__warn_gbuffers(diag, "target->gbuffer", &target->gbuffer, "source->gbuffer",
                           &source->gbuffer);
        if (desc->rig != SBL_RIG_MATRICES) {
            /* target_eye decides the direction of the correspondence (and the pinhole
               rig's cameras): with it swapped, the matches land on other surfaces; the
               depth, id and normal tests and the back-check then reject most of them */
            sbl__stereo_rp swapped;
            long n_this, n_swap;
            if (sbl__stereo_rp_init(&s, desc, target_eye, target, source, 0) == SBL_OK &&
                sbl__stereo_rp_init(&swapped, desc, target_eye == SBL_EYE_LEFT ? SBL_EYE_RIGHT
                                                                              : SBL_EYE_LEFT,
                                    target, source, 0) == SBL_OK) {
                double e_this = sbl__sample_roundtrip(&s, w, h, &n_this);
                double e_swap = sbl__sample_roundtrip(&swapped, w, h, &n_swap);
                if (n_this > 0 && n_swap > 0 && e_this > 4.0 * e_swap && e_this > 0.05) {
                    char msg[200];
                    snprintf(msg, sizeof msg, ": the correspondence comes back %.3g px off on "
                             "average, %.3g px with the other eye: are target_eye, or target "
                             "and source, swapped?", e_this, e_swap);
                    sbl__warn(diag, "target_eye", msg);
                }
            }
        }
    }
    diag->result = r;
    return r;
}

SBLDEF sbl_result sbl_stereo_blend_frame(const sbl_stereo_desc *desc, const sbl_eye *left,
                                         const sbl_eye *right, sbl_image out_left,
                                         sbl_image out_right)
{
    sbl__stereo_rp s;
    sbl_image none;
    size_t bytes;
    void *scratch;
    sbl_result r;
    if (!desc || !left || !right) return SBL_ERROR_NULL_POINTER;
    memset(&none, 0, sizeof none);
    /* validate both eyes, and the outputs against each other, before writing either */
    if ((r = sbl__stereo_blend_check(&s, desc, SBL_EYE_LEFT, left, right, &out_left, &none)) != SBL_OK)
        return r;
    if ((r = sbl__stereo_blend_check(&s, desc, SBL_EYE_RIGHT, right, left, &out_right, &none)) != SBL_OK)
        return r;
    if (sbl__overlap(&out_left, &out_right)) return SBL_ERROR_OVERLAP;
    bytes = sbl_stereo_scratch_size(left->color.width, left->color.channels);
    if (bytes == 0) return SBL_ERROR_INVALID_SIZE;
    scratch = SBL_MALLOC(bytes, desc->alloc_context);
    if (!scratch) return SBL_ERROR_OUT_OF_MEMORY;
    r = sbl_stereo_blend(desc, SBL_EYE_LEFT, left, right, out_left, none, 0,
                         left->color.height, scratch, bytes);
    if (r == SBL_OK)
        r = sbl_stereo_blend(desc, SBL_EYE_RIGHT, right, left, out_right, none, 0,
                             right->color.height, scratch, bytes);
    SBL_FREE(scratch, desc->alloc_context);
    return r;
}
/* The eye a stereo blend reads: a temporal output with its frame's geometry. */
static sbl_eye sbl__eye_from_temporal(const sbl_stereo_temporal_io *io, int e)
{
    sbl_eye eye;
    memset(&eye, 0, sizeof eye);
    eye.color = io->temporal[e].color;
    eye.length = io->temporal[e].length;
    eye.evidence = io->temporal[e].evidence; /* (optional: NULL data is none) */
    eye.gbuffer = io->frame[e].gbuffer;
    eye.gbuffer.motion.data = NULL; /* not a stereo input */
    eye.disparity = io->disparity[e];
    eye.camera = io->frame[e].camera;
    return eye;
}

SBLDEF sbl_result sbl_stereo_temporal_frame(const sbl_temporal_desc *td,
                                            const sbl_stereo_desc *sd,
                                            const sbl_stereo_temporal_io *io)
{
    sbl_temporal_desc tdd; /* td with the combined call's default shared bias */
    sbl__stereo_rp s;
    sbl_eye eye[2];
    sbl_image none;
    size_t bytes, b1;
    void *scratch;
    sbl_result r;
    int e;
    if (!td || !sd || !io) return SBL_ERROR_NULL_POINTER;
    /* the display is the stereo blend: the history's bias counts for both eyes
       (docs/ESTIMATORS.md 4.7) unless the caller says otherwise */
    tdd = *td;
    if (sbl__is_zero(tdd.stereo_shared_bias)) tdd.stereo_shared_bias = 1.0f;
    td = &tdd;
    memset(&none, 0, sizeof none);
    /* validate everything first: an empty row range checks all arguments and writes
       nothing (the scratch is not touched, so any non-NULL pointer will do) */
    for (e = 0; e < 2; ++e) {
        if ((r = sbl__check_image(&io->frame[e].color, 0)) != SBL_OK) return r;
        if ((r = sbl_temporal_filter(td, &io->frame[e], io->history[e], &io->temporal[e], 0, 0,
                                     &none, SBL__CAST(size_t, -1))) != SBL_OK)
            return r;
    }
    for (e = 0; e < 2; ++e) {
        /* one eye's temporal outputs may not overlap the other eye's outputs nor its
           inputs (eye 0 runs first: it would change what eye 1 reads) */
        const sbl_image *oe[SBL__PLANES_MAX], *other[SBL__PLANES_MAX];
        int i, n = sbl__temporal_output_planes(&io->temporal[e], oe);
        sbl__temporal_output_planes(&io->temporal[!e], other);
        for (i = 0; i < n; ++i) {
            if (sbl__overlap_frame(oe[i], &io->frame[!e]) || sbl__overlap_history(oe[i], io->history[!e]))
                return SBL_ERROR_OVERLAP;
            if (e == 0 && sbl__overlap_any(oe[i], other, n)) return SBL_ERROR_OVERLAP;
        }
        eye[e] = sbl__eye_from_temporal(io, e);
    }
    for (e = 0; e < 2; ++e)
        if ((r = sbl__stereo_blend_check(&s, sd, SBL__CAST(sbl_eye_index, e), &eye[e], &eye[!e],
                                         &io->display[e], &none)) != SBL_OK)
            return r;
    if (sbl__overlap(&io->display[0], &io->display[1])) return SBL_ERROR_OVERLAP;
    for (e = 0; e < 2; ++e)
        if (sbl__overlap_frame(&io->display[e], &io->frame[0]) || sbl__overlap_frame(&io->display[e], &io->frame[1]) ||
            sbl__overlap_history(&io->display[e], io->history[0]) ||
            sbl__overlap_history(&io->display[e], io->history[1]))
            return SBL_ERROR_OVERLAP;
    bytes = sbl_temporal_scratch_size(io->frame[0].color.width, io->frame[0].color.channels);
    b1 = sbl_temporal_scratch_size(io->frame[1].color.width, io->frame[1].color.channels);
    if (b1 > bytes) bytes = b1;
    if (bytes == 0) return SBL_ERROR_INVALID_SIZE;
    scratch = SBL_MALLOC(bytes, td->alloc_context);
    if (!scratch) return SBL_ERROR_OUT_OF_MEMORY;
    r = SBL_OK;
    for (e = 0; e < 2 && r == SBL_OK; ++e)
        r = sbl_temporal_filter(td, &io->frame[e], io->history[e], &io->temporal[e], 0,
                                io->frame[e].color.height, scratch, bytes);
    for (e = 0; e < 2 && r == SBL_OK; ++e)
        r = sbl_stereo_blend(sd, SBL__CAST(sbl_eye_index, e), &eye[e], &eye[!e], io->display[e], none, 0,
                             eye[e].color.height, scratch, bytes);
    SBL_FREE(scratch, td->alloc_context);
    return r;
}

/* ------------------------------------------------------------------------ */
/* 9. Fill mode                                                             */
/* ------------------------------------------------------------------------ */

/* Does the byte mask [mask, mask + (h - 1) mask_stride + w) overlap image a or b, or
   any plane of eye e0 or e1? Each of the four may be NULL (none). */
static int sbl__mask_overlaps(const unsigned char *mask, int mask_stride, int w, int h,
                              const sbl_image *a, const sbl_image *b,
                              const sbl_eye *e0, const sbl_eye *e1)
{
    const char *m0 = SBL__PCAST(const char *, mask);
    const char *m1 = m0 + SBL__CAST(size_t, h - 1) * SBL__CAST(size_t, mask_stride) + SBL__CAST(size_t, w);
    const sbl_image *p[SBL__PLANES_MAX];
    return (a && sbl__overlap_bytes(m0, m1, a)) || (b && sbl__overlap_bytes(m0, m1, b)) ||
           (e0 && sbl__overlap_bytes_any(m0, m1, p, sbl__eye_planes(e0, p))) ||
           (e1 && sbl__overlap_bytes_any(m0, m1, p, sbl__eye_planes(e1, p)));
}

SBLDEF sbl_result sbl_stereo_fill(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                  const sbl_eye *target, const sbl_eye *source,
                                  sbl_image out_color, unsigned char *mask, int mask_stride,
                                  int y0, int y1, long *needs_ray_count)
{
    sbl__stereo_rp s;
    sbl_result r;
    long count = 0;
    int x, y, w, h, ch;
    if ((r = sbl__stereo_rp_init(&s, desc, target_eye, target, source, 0)) != SBL_OK) return r;
    w = source->color.width; h = source->color.height; ch = source->color.channels;
    if (!mask) return SBL_ERROR_NULL_POINTER;
    if (mask_stride < w) return SBL_ERROR_INVALID_STRIDE;
    if ((r = sbl__check_image(&out_color, 0)) != SBL_OK) return r;
    if (out_color.width != w || out_color.height != h) return SBL_ERROR_SIZE_MISMATCH;
    if (out_color.channels != ch) return SBL_ERROR_CHANNEL_MISMATCH;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    if ((r = sbl__check_outputs_vs_eyes(&out_color, target, source)) != SBL_OK) return r;
    if (sbl__mask_overlaps(mask, mask_stride, w, h, &out_color, NULL, target, source))
        return SBL_ERROR_OVERLAP;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < w; ++x) {
            float v[4] = {0, 0, 0, 0};
            float n = sbl__stereo_rp_pixel(&s, x, y, v);
            unsigned char need = sbl__write_reprojected(&out_color, x, y, v, n, ch) ? 0 : 1;
            mask[SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride) + SBL__CAST(size_t, x)] = need;
            count += need;
        }
    if (needs_ray_count) *needs_ray_count = count;
    return SBL_OK;
}

SBLDEF sbl_result sbl_merge_traced(sbl_image dst, sbl_image traced,
                                   const unsigned char *mask, int mask_stride, int y0, int y1)
{
    sbl_result r;
    int x, y, k;
    if ((r = sbl__check_image(&dst, 0)) != SBL_OK) return r;
    if ((r = sbl__check_image(&traced, 0)) != SBL_OK) return r;
    if (!mask) return SBL_ERROR_NULL_POINTER;
    if (traced.width != dst.width || traced.height != dst.height) return SBL_ERROR_SIZE_MISMATCH;
    if (traced.channels != dst.channels) return SBL_ERROR_CHANNEL_MISMATCH;
    if (mask_stride < dst.width) return SBL_ERROR_INVALID_STRIDE;
    if ((r = sbl__check_rows(y0, y1, dst.height)) != SBL_OK) return r;
    if (sbl__overlap(&dst, &traced)) return SBL_ERROR_OVERLAP;
    /* the mask is read while dst is written */
    if (sbl__mask_overlaps(mask, mask_stride, dst.width, dst.height, &dst, NULL, NULL, NULL))
        return SBL_ERROR_OVERLAP;
    for (y = y0; y < y1; ++y)
        for (x = 0; x < dst.width; ++x)
            if (mask[SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride) + SBL__CAST(size_t, x)]) {
                const float *t = sbl__px(&traced, x, y);
                float *d = sbl__px(&dst, x, y);
                for (k = 0; k < dst.channels; ++k) d[k] = t[k];
            }
    return SBL_OK;
}

/* ------------------------------------------------------------------------ */
/* 10. Adaptive computation                                                 */
/* ------------------------------------------------------------------------ */

/* Weber ratio of two values of one channel (the cases are documented at the
   declaration); in double so that |a - b| of two finite floats cannot overflow. */
static double sbl__weber_ratio(float a, float b)
{
    double da = fabs(SBL__CAST(double, a)), db = fabs(SBL__CAST(double, b));
    double m = da > db ? da : db;
    if (!(m > 0.0)) return 0.0; /* both +-0 */
    return fabs(SBL__CAST(double, a) - SBL__CAST(double, b)) / m;
}

SBLDEF size_t sbl_stereo_consistency_scratch_size(int width, int channels)
{
    if (width <= 0 || channels < 1 || channels > 4 || width > INT_MAX / 8) return 0;
    /* one reprojected row: channels + 2 float planes */
    return SBL__CAST(size_t, channels + 2) * sbl__plane_floats(width) * sizeof(float) + 64;
}

/* Class of one pixel from its own value and the reprojected other value (n > 0: a
   correspondence). */
SBL__INLINE unsigned char sbl__consistency_class(const float *own, const float *other, float n,
                                            int ch, double threshold)
{
    double worst = 0.0;
    int k;
    if (!(n > 0.0f)) return SBL_NO_CORRESPONDENCE;
    if (sbl__any_nonfinite(own, ch)) return SBL_INCONSISTENT;
    for (k = 0; k < ch; ++k) {
        double q = sbl__weber_ratio(own[k], other[k]);
        if (q > worst) worst = q;
    }
    return worst >= threshold ? SBL_INCONSISTENT : SBL_CONSISTENT;
}

SBLDEF sbl_result sbl_stereo_consistency(const sbl_stereo_desc *desc, float threshold,
                                         sbl_eye_index target_eye, const sbl_eye *target,
                                         const sbl_eye *source, sbl_image target_value,
                                         sbl_image source_value, unsigned char *mask,
                                         int mask_stride, int y0, int y1, void *scratch,
                                         size_t scratch_bytes, sbl_consistency_counts *counts)
{
    sbl__stereo_rp s;
    sbl_eye t, o; /* the eyes with the value images as their colour, without N */
    sbl_result r;
    long n_ok = 0, n_bad = 0, n_none = 0;
    int x, y, w, h, ch;
    if (!target || !source) return SBL_ERROR_NULL_POINTER;
    t = *target;
    o = *source;
    t.color = target_value;
    o.color = source_value;
    memset(&t.length, 0, sizeof t.length);
    memset(&o.length, 0, sizeof o.length);
    /* validates the rig, both eyes' geometry and both value images (size, channels) */
    if ((r = sbl__stereo_rp_init(&s, desc, target_eye, &t, &o, 1)) != SBL_OK) return r;
    if (sbl__is_zero(threshold)) threshold = SBL_WEBER_THRESHOLD;
    if (!sbl__finite(threshold) || !(threshold > 0.0f)) return SBL_ERROR_INVALID_PARAM;
    w = target_value.width; h = target_value.height; ch = target_value.channels;
    if (!mask) return SBL_ERROR_NULL_POINTER;
    if (mask_stride < w) return SBL_ERROR_INVALID_STRIDE;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    if (sbl__mask_overlaps(mask, mask_stride, w, h, NULL, NULL, &t, &o) ||
        sbl__mask_overlaps(mask, mask_stride, w, h, NULL, NULL, target, source))
        return SBL_ERROR_OVERLAP;
    if (scratch || scratch_bytes) {
        if (!scratch) return SBL_ERROR_NULL_POINTER;
        if (scratch_bytes < sbl_stereo_consistency_scratch_size(w, ch))
            return SBL_ERROR_SCRATCH_TOO_SMALL;
    }
#ifdef SBL__ROW_GATHER
    if (scratch && sbl__row_gather_ok(&s.src)) {
        /* a row at a time into one ring row (the blend kernel's reprojection) */
        const size_t pf = sbl__plane_floats(w);
        float *p = SBL__PCAST(float *, sbl__align64(scratch));
        sbl__ring_row row;
        int k;
        memset(&row, 0, sizeof row);
        for (k = 0; k < ch; ++k) { row.x[k] = p; p += pf; }
        row.n = p; p += pf;
        row.v = p;
        for (y = y0; y < y1; ++y) {
            unsigned char *m = mask + SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride);
            const float *own = sbl__px(&target_value, 0, y);
            const ptrdiff_t step = sbl__step_of(&target_value);
            long n_cls[3] = {0, 0, 0};
            sbl__stereo_rp_row(&s, &row, y, 0, w);
            for (x = 0; x < w; ++x) {
                float other[4] = {0, 0, 0, 0};
                unsigned char cls;
                for (k = 0; k < ch; ++k) other[k] = row.x[k][x];
                cls = sbl__consistency_class(own + SBL__CAST(ptrdiff_t, x) * step, other, row.n[x], ch,
                                             SBL__CAST(double, threshold));
                m[x] = cls;
                ++n_cls[cls];
            }
            n_ok += n_cls[SBL_CONSISTENT];
            n_bad += n_cls[SBL_INCONSISTENT];
            n_none += n_cls[SBL_NO_CORRESPONDENCE];
        }
    } else
#endif
    for (y = y0; y < y1; ++y) {
        unsigned char *m = mask + SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride);
        for (x = 0; x < w; ++x) {
            float other[4] = {0, 0, 0, 0};
            float n = sbl__stereo_rp_pixel(&s, x, y, other);
            unsigned char cls = sbl__consistency_class(sbl__px(&target_value, x, y), other, n, ch,
                                                       SBL__CAST(double, threshold));
            m[x] = cls;
            n_ok += cls == SBL_CONSISTENT;
            n_bad += cls == SBL_INCONSISTENT;
            n_none += cls == SBL_NO_CORRESPONDENCE;
        }
    }
    if (counts) {
        counts->consistent = n_ok;
        counts->inconsistent = n_bad;
        counts->no_correspondence = n_none;
        counts->inconsistent_ratio =
            n_ok + n_bad > 0 ? SBL__CAST(double, n_bad) / SBL__CAST(double, n_ok + n_bad) : 0.0;
    }
    return SBL_OK;
}

/* Tiles of the adaptive pass: the blend runs on row bands of this height, on the column
   spans of the tiles that hold a marked pixel (sbl__kernel_run_span, bit-identical to the
   whole run there). Each band reloads the two rows around it and each span its two
   border columns (the 3x3 window), so larger tiles waste less; smaller ones follow the
   mask closer. */
#define SBL__ADAPTIVE_TILE 16

/* Does the tile of columns [x0, min(x1, w)) and rows [y0, y1) hold a marked pixel? */
static int sbl__tile_marked(const unsigned char *mask, int mask_stride, int x0, int x1, int w,
                            int y0, int y1)
{
    int x, y;
    if (x1 > w) x1 = w;
    for (y = y0; y < y1; ++y) {
        const unsigned char *m = mask + SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride);
        for (x = x0; x < x1; ++x)
            if (m[x] == SBL_INCONSISTENT) return 1;
    }
    return 0;
}

/* The own colour and N on the unmarked pixels of rows [y0, y1) (after the blend ran on
   their tiles); mask_rows holds row y0's classes. Returns the count of marked pixels. */
static long sbl__keep_own(const sbl__kernel *k, const unsigned char *mask_rows, int mask_stride,
                          int y0, int y1)
{
    long marked = 0;
    int x, y, c;
    for (y = y0; y < y1; ++y) {
        const unsigned char *m = mask_rows + SBL__CAST(size_t, y - y0) * SBL__CAST(size_t, mask_stride);
        for (x = 0; x < k->w; ++x) { /* per pixel: views may have pixel steps */
            const float *own = sbl__px(k->own, x, y);
            float *o = sbl__px(&k->out, x, y);
            if (m[x] == SBL_INCONSISTENT) { ++marked; continue; }
            for (c = 0; c < k->ch; ++c) o[c] = own[c];
            if (k->out_n.data) *sbl__px(&k->out_n, x, y) = sbl__own_n(k, x, y);
        }
    }
    return marked;
}

SBLDEF sbl_result sbl_stereo_blend_masked(const sbl_stereo_desc *desc, sbl_eye_index target_eye,
                                          const sbl_eye *target, const sbl_eye *source,
                                          const unsigned char *mask, int mask_stride,
                                          sbl_image out_color, sbl_image out_length,
                                          int y0, int y1, void *scratch,
                                          size_t scratch_bytes, long *blended_count)
{
    sbl__stereo_rp s;
    sbl__kernel k;
    sbl_result r;
    long marked = 0;
    int w, h, by, full0 = -1;
    /* every check of the full blend: an empty row range validates and writes nothing */
    if ((r = sbl_stereo_blend(desc, target_eye, target, source, out_color, out_length, y0, y0,
                              scratch, scratch_bytes)) != SBL_OK)
        return r;
    w = target->color.width; h = target->color.height;
    if (!mask) return SBL_ERROR_NULL_POINTER;
    if (mask_stride < w) return SBL_ERROR_INVALID_STRIDE;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    /* the mask is read while the outputs are written */
    if (sbl__mask_overlaps(mask, mask_stride, w, h, &out_color, &out_length, NULL, NULL))
        return SBL_ERROR_OVERLAP;
    if ((r = sbl__stereo_blend_check(&s, desc, target_eye, target, source, &out_color,
                                     &out_length)) != SBL_OK)
        return r;
    /* the kernel as sbl_stereo_blend sets it up */
    sbl__stereo_kernel_setup(&k, &s, target, &out_color, &out_length, NULL, scratch);
    /* bands on the absolute tile grid, clipped to [y0, y1); consecutive bands marked
       across the whole width run as one (no ring reload between them) */
    for (by = y0 - y0 % SBL__ADAPTIVE_TILE; by < y1; by += SBL__ADAPTIVE_TILE) {
        int b0 = by > y0 ? by : y0, b1 = by + SBL__ADAPTIVE_TILE < y1 ? by + SBL__ADAPTIVE_TILE : y1;
        int tx, span0 = -1, full = 1;
        for (tx = 0; tx < w && full; tx += SBL__ADAPTIVE_TILE)
            full = sbl__tile_marked(mask, mask_stride, tx, tx + SBL__ADAPTIVE_TILE, w, b0, b1);
        if (full) {
            if (full0 < 0) full0 = b0;
            continue;
        }
        if (full0 >= 0) {
            sbl__kernel_run(&k, full0, b0);
            marked += sbl__keep_own(&k, mask + SBL__CAST(size_t, full0) * SBL__CAST(size_t, mask_stride), mask_stride, full0, b0);
            full0 = -1;
        }
        /* runs of marked tiles along the band become one span each; the step past the
           last tile closes an open span */
        for (tx = 0; tx < w + SBL__ADAPTIVE_TILE; tx += SBL__ADAPTIVE_TILE) {
            int marked_tile = tx < w && sbl__tile_marked(mask, mask_stride, tx,
                                                         tx + SBL__ADAPTIVE_TILE, w, b0, b1);
            if (marked_tile && span0 < 0) span0 = tx;
            if (!marked_tile && span0 >= 0) {
                sbl__kernel_run_span(&k, b0, b1, span0, tx < w ? tx : w);
                span0 = -1;
            }
        }
        marked += sbl__keep_own(&k, mask + SBL__CAST(size_t, b0) * SBL__CAST(size_t, mask_stride), mask_stride, b0, b1);
    }
    if (full0 >= 0) {
        sbl__kernel_run(&k, full0, y1);
        marked += sbl__keep_own(&k, mask + SBL__CAST(size_t, full0) * SBL__CAST(size_t, mask_stride), mask_stride, full0, y1);
    }
    if (blended_count) *blended_count = marked;
    return SBL_OK;
}

/* ---- the one-pass adaptive blend --------------------------------------------------- */

/* Rows of reprojection a band of tiles reads: its own and one above and below (the
   kernel's 3x3 window). Row y lives in slot y % SBL__ADAPTIVE_ROWS: the two rows a
   band shares with the next keep their slots, the others are overwritten only after
   their band is done. */
#define SBL__ADAPTIVE_ROWS (SBL__ADAPTIVE_TILE + 2)

typedef struct sbl__adaptive_cache {
    int w, ch;
    sbl__gather_fn gather;           /* the stereo reprojection (pixel and row forms) */
    sbl__row_gather_fn gather_row;   /* NULL: one pixel at a time                     */
    const void *gather_ctx;
    sbl__ring_row slot[SBL__ADAPTIVE_ROWS]; /* x*, N, validity of row .row (-1: none) */
} sbl__adaptive_cache;

SBLDEF size_t sbl_stereo_adaptive_scratch_size(int width, int channels)
{
    size_t kernel = sbl_stereo_scratch_size(width, channels), pf;
    if (kernel == 0) return 0;
    pf = sbl__plane_floats(width);
    /* per slot: channels + 2 float planes; then one mask byte per pixel of a band */
    return kernel + 64 + SBL__CAST(size_t, SBL__ADAPTIVE_ROWS * (channels + 2)) * pf * sizeof(float) +
           SBL__CAST(size_t, SBL__ADAPTIVE_TILE) * pf;
}

/* The reprojection of image row y, made on first use. */
static const sbl__ring_row *sbl__adaptive_row_of(sbl__adaptive_cache *c, int y)
{
    sbl__ring_row *r = &c->slot[y % SBL__ADAPTIVE_ROWS];
    int x;
    if (r->row == y) return r;
    if (c->gather_row) {
        c->gather_row(c->gather_ctx, r, y, 0, c->w);
    } else {
        for (x = 0; x < c->w; ++x) {
            float tmp[4] = {0, 0, 0, 0};
            sbl__ring_put(r, x, c->gather(c->gather_ctx, x, y, tmp), tmp, c->ch);
        }
    }
    r->row = y;
    return r;
}

/* The kernel's row gather during the adaptive pass: a copy of the cached reprojection
   (equal bit for bit to gathering again). */
static void sbl__adaptive_gather_row(const void *ctx, struct sbl__ring_row *r, int y, int xa,
                                     int xb)
{
    sbl__adaptive_cache *c = *SBL__PCAST(sbl__adaptive_cache *const *, ctx);
    const sbl__ring_row *s = sbl__adaptive_row_of(c, y);
    const size_t bytes = SBL__CAST(size_t, xb - xa) * sizeof(float);
    int k;
    if (xb <= xa) return;
    for (k = 0; k < c->ch; ++k) memcpy(r->x[k] + xa, s->x[k] + xa, bytes);
    memcpy(r->n + xa, s->n + xa, bytes);
    memcpy(r->v + xa, s->v + xa, bytes);
}

/* The own colour and N on rows [y0, y1), columns [x0, x1) (an unmarked tile). */
static void sbl__keep_own_span(const sbl__kernel *k, int y0, int y1, int x0, int x1)
{
    int x, y, c;
    for (y = y0; y < y1; ++y)
        for (x = x0; x < x1; ++x) {
            const float *own = sbl__px(k->own, x, y);
            float *o = sbl__px(&k->out, x, y);
            for (c = 0; c < k->ch; ++c) o[c] = own[c];
            if (k->out_n.data) *sbl__px(&k->out_n, x, y) = sbl__own_n(k, x, y);
        }
}

/* Weber test of one pixel: own colour against the reprojected other eye's. */
static unsigned char sbl__adaptive_class(const float *own, const sbl__ring_row *r, int x,
                                         int ch, int luminance, double threshold)
{
    double worst = 0.0;
    int k;
    if (!(r->v[x] > 0.0f)) return SBL_NO_CORRESPONDENCE;
    if (sbl__any_nonfinite(own, ch)) return SBL_INCONSISTENT;
    if (luminance) {
        /* in double from the floats: a float sum could round both sides differently */
        double a = 0.2126 * SBL__CAST(double, own[0]) + 0.7152 * SBL__CAST(double, own[1]) +
                   0.0722 * SBL__CAST(double, own[2]);
        double b = 0.2126 * SBL__CAST(double, r->x[0][x]) + 0.7152 * SBL__CAST(double, r->x[1][x]) +
                   0.0722 * SBL__CAST(double, r->x[2][x]);
        double m = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
        worst = m > 0.0 ? fabs(a - b) / m : 0.0;
    } else {
        for (k = 0; k < ch; ++k) {
            double q = sbl__weber_ratio(own[k], r->x[k][x]);
            if (q > worst) worst = q;
        }
    }
    return worst >= threshold ? SBL_INCONSISTENT : SBL_CONSISTENT;
}

/* The Weber test on the nearest pixel of the match (sbl_adaptive_desc.nearest): the
   rig's map there and back (the back-check of the reprojection) and the depth test on
   that one pixel; a non-finite value there is no correspondence, as a dropped tap. */
static unsigned char sbl__adaptive_class_nearest(const sbl__stereo_rp *s, const float *own,
                                                 int x, int y, int ch, int luminance,
                                                 double threshold)
{
    const int sw = s->source->color.width, sh = s->source->color.height;
    double sx, sy, sz, bx, by, bz, worst = 0.0;
    const float *other;
    int ix, iy, k;
    /* the parallel rig called directly, so that it inlines */
    const int parallel = s->d.rig == SBL_RIG_PARALLEL;
    if (!(parallel ? sbl__stereo_map_parallel(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz)
                   : sbl__stereo_map(s, 0, x, y, x + 0.5, y + 0.5, &sx, &sy, &sz)))
        return SBL_NO_CORRESPONDENCE;
    if (!(sx >= 0.0 && sx < SBL__CAST(double, sw) && sy >= 0.0 && sy < SBL__CAST(double, sh)))
        return SBL_NO_CORRESPONDENCE;
    ix = SBL__CAST(int, floor(sx));
    iy = SBL__CAST(int, floor(sy));
    if (s->src.use_depth && sz > 0.0 &&
        !sbl__depth_match(SBL__CAST(float, sz), *SBL__AT(s->src.depth, ix, iy), s->src.depth_tolerance, 0.0f))
        return SBL_NO_CORRESPONDENCE;
    if (!(s->d.reproject.disabled_tests & SBL_TEST_BACK_CHECK)) {
        double ex, ey, tol = SBL__CAST(double, s->d.reproject.back_check_pixels);
        if (!(parallel ? sbl__stereo_map_parallel(s, 1, ix, iy, sx, sy, &bx, &by, &bz)
                       : sbl__stereo_map(s, 1, ix, iy, sx, sy, &bx, &by, &bz)))
            return SBL_NO_CORRESPONDENCE;
        ex = bx - (x + 0.5);
        ey = by - (y + 0.5);
        if (!(ex * ex + ey * ey <= tol * tol)) return SBL_NO_CORRESPONDENCE;
    }
    other = sbl__px(&s->source->color, ix, iy);
    if (sbl__any_nonfinite(other, ch)) return SBL_NO_CORRESPONDENCE;
    if (sbl__any_nonfinite(own, ch)) return SBL_INCONSISTENT;
    if (luminance) {
        double a = 0.2126 * SBL__CAST(double, own[0]) + 0.7152 * SBL__CAST(double, own[1]) +
                   0.0722 * SBL__CAST(double, own[2]);
        double b = 0.2126 * SBL__CAST(double, other[0]) + 0.7152 * SBL__CAST(double, other[1]) +
                   0.0722 * SBL__CAST(double, other[2]);
        double m = fabs(a) > fabs(b) ? fabs(a) : fabs(b);
        worst = m > 0.0 ? fabs(a - b) / m : 0.0;
    } else {
        for (k = 0; k < ch; ++k) {
            double q = sbl__weber_ratio(own[k], other[k]);
            if (q > worst) worst = q;
        }
    }
    return worst >= threshold ? SBL_INCONSISTENT : SBL_CONSISTENT;
}

SBLDEF sbl_result sbl_stereo_blend_adaptive(const sbl_stereo_desc *desc,
                                            const sbl_adaptive_desc *adaptive,
                                            sbl_eye_index target_eye, const sbl_eye *target,
                                            const sbl_eye *source, sbl_image out_color,
                                            sbl_image out_length, unsigned char *mask,
                                            int mask_stride, int y0, int y1, void *scratch,
                                            size_t scratch_bytes,
                                            sbl_consistency_counts *counts,
                                            long *tiles_blended, long *tiles_total)
{
    sbl__stereo_rp s;
    sbl__kernel k;
    sbl__adaptive_cache cache, *cache_ptr = &cache; /* the gather's context: a pointer to it */
    sbl_adaptive_desc a;
    sbl_result r;
    unsigned char *band; /* classes of the band's rows, row stride pf */
    size_t pf, need;
    long n_ok = 0, n_bad = 0, n_none = 0, t_run = 0, t_all = 0;
    double threshold;
    int w, h, ch, by, luminance, i, j;
    /* every check of the full blend: an empty row range validates and writes nothing */
    if ((r = sbl_stereo_blend(desc, target_eye, target, source, out_color, out_length, y0, y0,
                              scratch, scratch_bytes)) != SBL_OK)
        return r;
    if (adaptive) a = *adaptive;
    else memset(&a, 0, sizeof a);
    if (sbl__is_zero(a.threshold)) a.threshold = SBL_WEBER_THRESHOLD;
    if (!sbl__finite(a.threshold) || !(a.threshold > 0.0f)) return SBL_ERROR_INVALID_PARAM;
    if (a.per_channel != 0 && a.per_channel != 1) return SBL_ERROR_INVALID_PARAM;
    if (a.per_pixel != 0 && a.per_pixel != 1) return SBL_ERROR_INVALID_PARAM;
    if (a.nearest != 0 && a.nearest != 1) return SBL_ERROR_INVALID_PARAM;
    w = target->color.width; h = target->color.height; ch = target->color.channels;
    if ((r = sbl__check_rows(y0, y1, h)) != SBL_OK) return r;
    if (mask) {
        if (mask_stride < w) return SBL_ERROR_INVALID_STRIDE;
        if (sbl__mask_overlaps(mask, mask_stride, w, h, &out_color, &out_length, target, source))
            return SBL_ERROR_OVERLAP;
    }
    need = sbl_stereo_adaptive_scratch_size(w, ch);
    if (need == 0) return SBL_ERROR_INVALID_SIZE;
    if (scratch_bytes < need) return SBL_ERROR_SCRATCH_TOO_SMALL;
    if ((r = sbl__stereo_blend_check(&s, desc, target_eye, target, source, &out_color,
                                     &out_length)) != SBL_OK)
        return r;
    threshold = SBL__CAST(double, a.threshold);
    luminance = !a.per_channel && ch >= 3;

    /* the kernel as sbl_stereo_blend sets it up (its gather redirected to the cache
       below unless the test reads the nearest pixel) */
    sbl__stereo_kernel_setup(&k, &s, target, &out_color, &out_length, NULL, scratch);
    pf = sbl__plane_floats(w);
    memset(&cache, 0, sizeof cache);
    cache.w = w; cache.ch = ch;
    cache.gather = k.gather; cache.gather_row = k.gather_row; cache.gather_ctx = k.gather_ctx;
    {
        float *p = SBL__PCAST(float *, sbl__align64(SBL__PCAST(char *, scratch) +
                                                    sbl_stereo_scratch_size(w, ch)));
        for (i = 0; i < SBL__ADAPTIVE_ROWS; ++i) {
            for (j = 0; j < ch; ++j) { cache.slot[i].x[j] = p; p += pf; }
            cache.slot[i].n = p; p += pf;
            cache.slot[i].v = p; p += pf;
            cache.slot[i].row = -1;
        }
        band = SBL__PCAST(unsigned char *, p);
    }
    if (!a.nearest) { /* the kernel reads the rows the test reprojected */
        k.gather_row = sbl__adaptive_gather_row;
        k.gather_ctx = &cache_ptr;
    }

    for (by = y0 - y0 % SBL__ADAPTIVE_TILE; by < y1; by += SBL__ADAPTIVE_TILE) {
        /* the tiles' rows [by, t1) decide, whatever part of them this call writes
           ([b0, b1)): row bands give the whole call's output */
        const int t1 = by + SBL__ADAPTIVE_TILE < h ? by + SBL__ADAPTIVE_TILE : h;
        const int b0 = by > y0 ? by : y0, b1 = t1 < y1 ? t1 : y1;
        int y, x, tx, span0 = -1;
        if (b0 >= b1) continue; /* an empty row range */
        /* classify the tiles' pixels from the reprojection the kernel will read */
        for (y = by; y < t1; ++y) {
            const sbl__ring_row *rr = a.nearest ? NULL : sbl__adaptive_row_of(&cache, y);
            const float *own = sbl__px(&target->color, 0, y);
            const ptrdiff_t step = sbl__step_of(&target->color);
            unsigned char *m = band + SBL__CAST(size_t, y - by) * pf;
            long n_cls[3] = {0, 0, 0};
            for (x = 0; x < w; ++x) {
                unsigned char cls =
                    rr ? sbl__adaptive_class(own + SBL__CAST(ptrdiff_t, x) * step, rr, x, ch,
                                             luminance, threshold)
                       : sbl__adaptive_class_nearest(&s, own + SBL__CAST(ptrdiff_t, x) * step, x, y,
                                                     ch, luminance, threshold);
                m[x] = cls;
                ++n_cls[cls];
            }
            if (y < b0 || y >= b1) continue;
            n_ok += n_cls[SBL_CONSISTENT];
            n_bad += n_cls[SBL_INCONSISTENT];
            n_none += n_cls[SBL_NO_CORRESPONDENCE];
            if (mask)
                memcpy(mask + SBL__CAST(size_t, y) * SBL__CAST(size_t, mask_stride), m,
                       SBL__CAST(size_t, w));
        }
        if (a.nearest) {
            /* a band with most tiles marked reads whole reprojected rows from the
               cache (its border rows are then shared with the next band); a sparse
               one reprojects only its spans */
            int n_marked = 0, n_tiles = 0;
            for (tx = 0; tx < w; tx += SBL__ADAPTIVE_TILE, ++n_tiles)
                n_marked += sbl__tile_marked(band, SBL__CAST(int, pf), tx, tx + SBL__ADAPTIVE_TILE, w, 0,
                                             t1 - by);
            if (2 * n_marked >= n_tiles) {
                k.gather_row = sbl__adaptive_gather_row;
                k.gather_ctx = &cache_ptr;
            } else {
                k.gather_row = cache.gather_row;
                k.gather_ctx = cache.gather_ctx;
            }
        }
        /* runs of marked tiles along the band become one span each */
        for (tx = 0; tx < w + SBL__ADAPTIVE_TILE; tx += SBL__ADAPTIVE_TILE) {
            int marked_tile = 0;
            if (tx < w) {
                marked_tile = sbl__tile_marked(band, SBL__CAST(int, pf), tx, tx + SBL__ADAPTIVE_TILE,
                                               w, 0, t1 - by);
                ++t_all;
                t_run += marked_tile;
            }
            if (marked_tile && span0 < 0) span0 = tx;
            if (!marked_tile && span0 >= 0) {
                sbl__kernel_run_span(&k, b0, b1, span0, tx < w ? tx : w);
                span0 = -1;
            }
            if (!marked_tile && tx < w && !a.per_pixel)
                sbl__keep_own_span(&k, b0, b1, tx, tx + SBL__ADAPTIVE_TILE < w ? tx + SBL__ADAPTIVE_TILE : w);
        }
        if (a.per_pixel) sbl__keep_own(&k, band + SBL__CAST(size_t, b0 - by) * pf, SBL__CAST(int, pf), b0, b1);
    }
    if (counts) {
        counts->consistent = n_ok;
        counts->inconsistent = n_bad;
        counts->no_correspondence = n_none;
        counts->inconsistent_ratio =
            n_ok + n_bad > 0 ? SBL__CAST(double, n_bad) / SBL__CAST(double, n_ok + n_bad) : 0.0;
    }
    if (tiles_blended) *tiles_blended = t_run;
    if (tiles_total) *tiles_total = t_all;
    return SBL_OK;
}

#ifdef __cplusplus
}
#endif
#endif /* STEREOBLEND_IMPLEMENTATION_DONE */
#endif /* STEREOBLEND_IMPLEMENTATION */

/*
------------------------------------------------------------------------------
This software is available under 2 licences -- choose whichever you prefer.
------------------------------------------------------------------------------
ALTERNATIVE A - MIT License
Copyright (c) 2026 the stereoblend.h authors
Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:
The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
------------------------------------------------------------------------------
ALTERNATIVE B - Public Domain (www.unlicense.org)
This is free and unencumbered software released into the public domain.
Anyone is free to copy, modify, publish, use, compile, sell, or distribute this
software, either in source code form or as a compiled binary, for any purpose,
commercial or non-commercial, and by any means.
In jurisdictions that recognize copyright laws, the author or authors of this
software dedicate any and all copyright interest in the software to the public
domain. We make this dedication in favor of the public domain to the benefit of
the public at large and to the detriment of our heirs and successors. We intend
this dedication to be an overt act of relinquishment in perpetuity of all
present and future rights to this software under copyright law.
THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER LIABILITY, WHETHER IN AN
ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM, OUT OF OR IN CONNECTION
WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE SOFTWARE.
------------------------------------------------------------------------------
*/
