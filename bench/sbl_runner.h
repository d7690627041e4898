/* sbl_runner.h - runs stereoblend.h methods over a stereo sequence and measures them.
   Shared by the demo, the bench and the EXR command-line tool so that all three use the
   same method list, the same pipeline and the same metrics.

   A sequence is loaded whole into memory (synthetic scene or a scene directory in the
   layout of shared/data/atrium). A method is a temporal descriptor (or none) plus a
   stereo mode. The pipeline per frame is the paper's order:
       [fill: right input = left reprojected + traced holes]
       -> temporal filter per eye (history = temporal output)
       -> stereo blend for display (fixed / adaptive beta).
   Metrics over the evaluation frames (frame >= frames / 4, so that accumulating
   methods are measured after warm-up; both eyes): RMSE (sqrt of the mean MSE), SSIM (on
   values clamped to [0,1], dynamic range 1), effective spp against the spp ladder,
   mse(1 spp) / mse(result), and the share of right-eye pixels traced (fill).
   Time: the library calls only, per stereo frame (both eyes), median over frames.

   Single file: #define SBL_RUNNER_IMPLEMENTATION in one .c (which must also provide the
   implementations of stereoblend.h, sbl_scene.h and sbl_metrics.h). */
#ifndef SBL_RUNNER_H
#define SBL_RUNNER_H

#include "../stereoblend.h"
#include "sbl_scene.h"

typedef struct sbr_view {          /* one eye of one frame, all W*H*channels floats */
    float *color, *ref, *depth, *normal, *id, *motion;
    sbl_camera camera;
} sbr_view;

#define SBR_MAX_LADDER 8
typedef struct sbr_ladder {        /* n-spp renders of one frame, both eyes */
    int frame, count;
    int spp[SBR_MAX_LADDER];
    float *img[2][SBR_MAX_LADDER];
} sbr_ladder;

typedef struct sbr_seq {
    char name[64];
    int width, height, frames;
    float focal_px, baseline;
    sbr_view *views;               /* [frame * 2 + eye] */
    int ladder_count;
    sbr_ladder ladder[SBR_MAX_LADDER];
    /* the statistics oracle's inputs (synthetic scenes only, sbr_seq_add_replicas):
       replica[view] holds 1 + replicas images of W*H*3, the r-th at r * W*H*3: a
       reference of its own (r = 0, the mean of var_spp samples), then that reference plus
       independent zero-mean noise of each pixel's 1-spp variance (noise_var[view],
       W*H*3, from the same samples); NULL if none */
    int replicas;
    float **replica;
    float **noise_var;
} sbr_seq;

typedef enum sbr_stereo_mode {
    SBR_STEREO_NONE = 0,
    SBR_STEREO_FILL,      /* trace the left eye; right = left reprojected, holes traced */
    SBR_STEREO_FIXED,     /* beta 0.5 */
    SBR_STEREO_ADAPTIVE,  /* beta by the chosen estimator */
    SBR_STEREO_MASKED,    /* the same blend only where the eyes' luminances differ by
                             the Weber threshold (sbl_stereo_consistency), else own */
    SBR_STEREO_ONE_PASS   /* the same in one call, mask and blend sharing the
                             reprojection (sbl_stereo_blend_adaptive, luminance) */
} sbr_stereo_mode;

/* Oracle weights (bench only): the library's reprojection stage, then
   a = E_X / (E_X + E_Y), E_X and E_Y the 3x3-averaged squared errors of x* and of the
   own sample against the reference: what the blend could reach with the reference known.
   The *statistics* oracle (SBR_ORACLE_STAT_*, needs sbr_seq_add_replicas): the same
   formula with E_X and E_Y each pixel's expected squared errors, bias^2 + variance. The
   weights never see the evaluated image's noise, so they are the same for every noise
   realisation, and the filter is linear in the samples: its expectation is the filter run
   on the references (replica 0, which gives the bias exactly), and its variance is that of
   the filter run on any zero-mean noise with each sample's variance (replicas 1..R,
   Rademacher signs: a low-noise estimate where the renderer's own heavy-tailed noise would
   need thousands of replicas). So this is what exact per-pixel statistics reach, where
   the oracle above also picks, per window, whichever of x* and y happened to land nearer
   the reference. docs/ESTIMATORS.md 6. */
enum { SBR_ORACLE_TEMPORAL = 1, SBR_ORACLE_STEREO = 2, SBR_ORACLE_STAT_TEMPORAL = 4,
       SBR_ORACLE_STAT_STEREO = 8 };

typedef struct sbr_method {
    char name[48];
    int temporal;                  /* 0: no temporal filter */
    int evidence;                  /* 1: the temporal filter carries its evidence plane
                                      (sbl_history.evidence / sbl_temporal_output.evidence) */
    int tail;                      /* 1: and its tail plane (sbl_history.tail /
                                      sbl_temporal_output.tail, 2 channels) */
    int oracle;                    /* SBR_ORACLE_* bits: that stage uses oracle weights */
    int display;                   /* 1: a temporal-only method shows the filter's display
                                      (sbl_temporal_output.display, sbl_temporal_display),
                                      not its history colour */
    sbl_temporal_desc temporal_desc;
    sbr_stereo_mode stereo;
    sbl_stereo_desc stereo_desc;   /* rig / focal / baseline filled in by the runner */
    float weber_threshold;         /* SBR_STEREO_MASKED: 0 -> SBL_WEBER_THRESHOLD */
    /* prototypes (not in the standard table): if set, the temporal stage is the library's
       reprojection, then this blend (y = input, xs / nx = x* and its N, 0 = invalid) */
    void (*temporal_blend)(void *ctx, int w, int h, const float *y, const float *xs,
                           const float *nx, float cap, float *out, float *nout);
    void *temporal_blend_ctx;
    /* prototypes with one carried plane (evidence over frames): as temporal_blend, plus
       zs = the previous frame's plane reprojected with the history's taps (0 where no tap
       is valid) and zout = this frame's plane. Used instead of temporal_blend if set. */
    void (*temporal_blend_carry)(void *ctx, int w, int h, const float *y, const float *xs,
                                 const float *nx, const float *zs, float cap, float *out,
                                 float *nout, float *zout);
    /* prototypes with the carried plane above plus a carried 3-channel plane (ts in, tsout
       out; reprojected the same way, 0 where no tap is valid). Used instead of the above. */
    void (*temporal_blend_carry3)(void *ctx, int w, int h, const float *y, const float *xs,
                                  const float *nx, const float *zs, const float *ts, float cap,
                                  float *out, float *nout, float *zout, float *tsout);
    /* with temporal_blend_carry3: if set (W*H*3 floats), each call first gets the
       history's fetch position per pixel here: the previous frame's pixel coordinates
       (x, y, 1) gathered with the history's taps (0, 0, 0 where no tap is valid), so the
       prototype knows the fetch's fraction (docs/ESTIMATORS.md 4.10) */
    float *fetch_xy;
} sbr_method;

/* Bright pixels: a reference channel above SBR_BRIGHT times the image's mean reference
   value (sub-pixel highlights and their reflections). On content with unclamped direct
   light a few dozen of them hold nearly all of the squared error, so RMSE and effective
   spp there say how a method treats those pixels; the RMSE over the dim rest says how it
   treats the image, and its trails (a dim pixel shown bright). */
#define SBR_BRIGHT 10.0

typedef struct sbr_result {
    double ms;          /* median ms per stereo frame (both eyes), library calls only */
    double rmse, ssim;
    double eff_spp;     /* against the ladder (mean over ladder frames and eyes); 0 if none */
    double indep_spp;   /* mse(1 spp) / mse(result): count of independent 1-spp samples */
    double traced_pct;  /* right-eye pixels that still needed a ray (fill), else 100 */
    /* the squared error split by the reference (sbl_metric_bright_split, SBR_BRIGHT): RMSE
       over the dim pixels, and the bright pixels' share of the MSE (%) and of the pixels (%) */
    double rmse_dim, bright_mse_pct, bright_px_pct;
    int eval_frames;
} sbr_result;

/* Called with each displayed image (W*H*3) if not NULL. */
typedef void (*sbr_frame_fn)(void *ctx, int frame, int eye, const float *rgb, int w, int h);

int  sbr_seq_synthetic(sbr_seq *s, const sbl_scene_desc *desc, const char *name, int with_ladder);
/* The synthetic scene as `make bench` renders it: 160x90, 24 frames, 128-spp reference,
   seed 7 (quick: 96x54, 8 frames, 32 spp). */
sbl_scene_desc sbr_bench_scene_desc(sbl_scene_kind kind, int jitter, int quick);
/* The bench's synthetic scenes in its order (the shared renders follow it: atrium,
   gallery); jitter: head-tracking jitter on the camera */
typedef struct sbr_synth_scene {
    const char *name; sbl_scene_kind kind; int jitter;
    float spike_rate, spike_gain; /* heavy-tailed samples (sbl_scene_desc), 0 = none */
} sbr_synth_scene;
#define SBR_SYNTH_SCENES 6
extern const sbr_synth_scene sbr_synth_scenes[SBR_SYNTH_SCENES];
/* sbr_bench_scene_desc for one of sbr_synth_scenes (its kind, jitter and spikes). */
sbl_scene_desc sbr_synth_desc(const sbr_synth_scene *scene, int quick);
int  sbr_seq_dataset(sbr_seq *s, const char *dir, int max_frames, char *err, int err_size);
/* The statistics oracle's inputs for a synthetic sequence made from desc: each pixel's
   1-spp mean and variance from var_spp >= 2 samples (sbl_scene_render_variance), and count
   noise replicas around that mean, for every view (sbr_seq.replica). */
int  sbr_seq_add_replicas(sbr_seq *s, const sbl_scene_desc *desc, int count, int var_spp);
void sbr_seq_free(sbr_seq *s);

/* The standard method table; returns the count written (at most max). */
#define SBR_MAX_METHODS 48
int  sbr_standard_methods(sbr_method *m, int max);
int  sbr_find_method(const char *name, sbr_method *out);

int  sbr_run(const sbr_seq *s, const sbr_method *m, sbr_result *res, sbr_frame_fn fn, void *ctx);
/* The same, and alpha_fn (if not NULL) gets each eye's temporal weight per frame (W*H, one
   channel; only for methods whose temporal stage is the library's filter or the
   statistics oracle). */
int  sbr_run_alpha(const sbr_seq *s, const sbr_method *m, sbr_result *res, sbr_frame_fn fn,
                   sbr_frame_fn alpha_fn, void *ctx);
void sbr_luminance(const float *rgb, float *lum, size_t n);
double sbr_now_ms(void);

#endif

#ifdef SBL_RUNNER_IMPLEMENTATION
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include <float.h>
#include "sbl_metrics.h"
#ifndef SBR_NO_DATASET
#include "sbl_dataset.h"
#endif

double sbr_now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static float *sbr_alloc(size_t n)
{
    float *p = (float *)calloc(n ? n : 1, sizeof(float));
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

static void sbr_camera_from(sbl_camera *c, const float *world_to_cam, const float *proj)
{
    memcpy(c->world_to_view, world_to_cam, sizeof c->world_to_view);
    memcpy(c->view_to_clip, proj, sizeof c->view_to_clip);
}

const sbr_synth_scene sbr_synth_scenes[SBR_SYNTH_SCENES] = {
    {"synthetic-dynamic", SBL_SCENE_DYNAMIC, 1, 0.0f, 0.0f},
    {"synthetic-static", SBL_SCENE_STATIC, 0, 0.0f, 0.0f},
    {"synthetic-shadow", SBL_SCENE_SHADOW, 0, 0.0f, 0.0f},
    {"synthetic-pan", SBL_SCENE_PAN, 0, 0.0f, 0.0f},
    /* pan with heavy-tailed samples: 2 % of the samples carry a third of the energy
       (unclamped light paths of low probability; the reference is their mean exactly,
       as on the other synthetic scenes, not a render with its own spikes) */
    {"synthetic-firefly", SBL_SCENE_PAN, 0, 0.02f, 25.0f},
    /* pan with hit-or-miss samples: 1 sample in 10 carries all the energy (ten times the
       radiance; the others 1e-5 of it), as a small light or a sub-pixel highlight sampled
       once per pixel. The defaults lose the mean here (the firefly limit cuts lone hits,
       the change tests see too little noise in a window of misses: docs/ESTIMATORS.md 2.3) */
    {"synthetic-sparse", SBL_SCENE_PAN, 0, 0.1f, 1e6f},
};

sbl_scene_desc sbr_bench_scene_desc(sbl_scene_kind kind, int jitter, int quick)
{
    sbl_scene_desc d;
    memset(&d, 0, sizeof d);
    d.kind = kind;
    d.jitter = jitter;
    d.width = quick ? 96 : 160;
    d.height = quick ? 54 : 90;
    d.frames = quick ? 8 : 24;
    d.ref_spp = quick ? 32 : 128;
    d.seed = 7;
    return d;
}

sbl_scene_desc sbr_synth_desc(const sbr_synth_scene *scene, int quick)
{
    sbl_scene_desc d = sbr_bench_scene_desc(scene->kind, scene->jitter, quick);
    d.spike_rate = scene->spike_rate;
    d.spike_gain = scene->spike_gain;
    return d;
}

int sbr_seq_synthetic(sbr_seq *s, const sbl_scene_desc *desc_in, const char *name, int with_ladder)
{
    sbl_scene_desc d = *desc_in;
    size_t n;
    int f, e, i;
    memset(s, 0, sizeof *s);
    sbl_scene_defaults(&d);
    snprintf(s->name, sizeof s->name, "%s", name);
    s->width = d.width; s->height = d.height; s->frames = d.frames;
    n = (size_t)d.width * (size_t)d.height;
    s->views = (sbr_view *)calloc((size_t)d.frames * 2, sizeof(sbr_view));
    if (!s->views) return 1;
    for (f = 0; f < d.frames; ++f)
        for (e = 0; e < 2; ++e) {
            sbr_view *v = &s->views[f * 2 + e];
            sbl_scene_view sv;
            memset(&sv, 0, sizeof sv);
            v->color = sv.color = sbr_alloc(n * 3);
            v->ref = sv.reference = sbr_alloc(n * 3);
            v->depth = sv.depth = sbr_alloc(n);
            v->normal = sv.normal = sbr_alloc(n * 3);
            v->id = sv.id = sbr_alloc(n);
            v->motion = sv.motion = sbr_alloc(n * 2);
            if (sbl_scene_render(&d, f, e, &sv, 0, d.height) != 0) return 1;
            sbr_camera_from(&v->camera, sv.world_to_cam, sv.proj);
            s->focal_px = sv.focal_px;
            s->baseline = sv.baseline;
        }
    if (with_ladder) {
        /* ladder at a few frames after warm-up: 1..32 spp */
        static const int spp[] = {1, 2, 4, 8, 16, 32};
        int lf[3];
        lf[0] = d.frames / 2; lf[1] = (3 * d.frames) / 4; lf[2] = d.frames - 1;
        for (i = 0; i < 3; ++i) {
            sbr_ladder *l = &s->ladder[s->ladder_count++];
            int k;
            l->frame = lf[i];
            l->count = 6;
            for (k = 0; k < 6; ++k) {
                l->spp[k] = spp[k];
                for (e = 0; e < 2; ++e) {
                    l->img[e][k] = sbr_alloc(n * 3);
                    sbl_scene_render_spp(&d, lf[i], e, spp[k], l->img[e][k], 0, d.height);
                }
            }
        }
    }
    return 0;
}

#ifndef SBR_NO_DATASET /* needs tools/sbl_dataset.c and tools/sbl_exr.c */
int sbr_seq_dataset(sbr_seq *s, const char *dir, int max_frames, char *err, int err_size)
{
    sbl_dataset ds;
    size_t n;
    int f, e, i, k;
    const char *base;
    memset(s, 0, sizeof *s);
    if (sbl_dataset_open(&ds, dir, err, err_size) != 0) return 1;
    base = strrchr(dir, '/');
    base = base && base[1] ? base + 1 : dir;
    snprintf(s->name, sizeof s->name, "%s", base);
    s->width = ds.width; s->height = ds.height;
    s->frames = max_frames > 0 && max_frames < ds.frames ? max_frames : ds.frames;
    s->baseline = ds.baseline;
    s->focal_px = ds.focal_px[0][0];
    n = (size_t)ds.width * (size_t)ds.height;
    s->views = (sbr_view *)calloc((size_t)s->frames * 2, sizeof(sbr_view));
    if (!s->views) { sbl_dataset_close(&ds); return 1; }
    for (f = 0; f < s->frames; ++f)
        for (e = 0; e < 2; ++e) {
            sbl_dataset_frame fr;
            sbr_view *v = &s->views[f * 2 + e];
            if (sbl_dataset_load(&ds, f, e, &fr, err, err_size) != 0) {
                sbl_dataset_close(&ds);
                sbr_seq_free(s);
                return 1;
            }
            v->color = fr.noisy; v->ref = fr.ref; v->depth = fr.depth;
            v->normal = fr.normal; v->id = fr.id; v->motion = fr.motion;
            sbr_camera_from(&v->camera, ds.world_to_cam[f][e], ds.proj[f][e]);
        }
    for (i = 0; i < ds.ladder_frame_count && s->ladder_count < SBR_MAX_LADDER; ++i) {
        sbr_ladder *l;
        if (ds.ladder_frames[i] >= s->frames) continue;
        l = &s->ladder[s->ladder_count];
        memset(l, 0, sizeof *l);
        l->frame = ds.ladder_frames[i];
        /* the 1-spp rung is the noisy frame itself */
        l->spp[0] = 1;
        for (e = 0; e < 2; ++e) {
            l->img[e][0] = sbr_alloc(n * 3);
            memcpy(l->img[e][0], s->views[l->frame * 2 + e].color, n * 3 * sizeof(float));
        }
        l->count = 1;
        for (k = 0; k < ds.ladder_spp_count && l->count < SBR_MAX_LADDER; ++k) {
            float *img[2] = {NULL, NULL};
            if (sbl_dataset_load_ladder(&ds, l->frame, 0, ds.ladder_spp[k], &img[0], NULL, 0) != 0 ||
                sbl_dataset_load_ladder(&ds, l->frame, 1, ds.ladder_spp[k], &img[1], NULL, 0) != 0) {
                free(img[0]); free(img[1]);
                continue;
            }
            l->spp[l->count] = ds.ladder_spp[k];
            l->img[0][l->count] = img[0];
            l->img[1][l->count] = img[1];
            l->count++;
        }
        s->ladder_count++;
    }
    sbl_dataset_close(&ds);
    return 0;
}
#endif

int sbr_seq_add_replicas(sbr_seq *s, const sbl_scene_desc *desc_in, int count, int var_spp)
{
    sbl_scene_desc d = *desc_in;
    const size_t n = (size_t)s->width * (size_t)s->height;
    int v, r;
    size_t q;
    sbl_scene_defaults(&d);
    if (count < 1 || var_spp < 2 || s->replica || d.width != s->width || d.height != s->height ||
        d.frames != s->frames)
        return 1;
    s->replica = (float **)calloc((size_t)s->frames * 2, sizeof(float *));
    s->noise_var = (float **)calloc((size_t)s->frames * 2, sizeof(float *));
    if (!s->replica || !s->noise_var) return 1;
    s->replicas = count;
    for (v = 0; v < s->frames * 2; ++v) {
        float *rep = s->replica[v] = sbr_alloc(n * 3 * (size_t)(count + 1));
        /* the bias is measured against this mean: a var_spp-sample one, because the
           bench's reference noise, filtered over frames, would read as a bias of about
           the history's own variance over ref_spp */
        const float *ref = rep, *var;
        s->noise_var[v] = sbr_alloc(n * 3);
        var = s->noise_var[v];
        if (sbl_scene_render_variance(&d, v / 2, v % 2, var_spp, rep, s->noise_var[v], 0, d.height) != 0)
            return 1;
        for (r = 1; r <= count; ++r)
            for (q = 0; q < n * 3; ++q) {
                /* a counter hash (splitmix64's finaliser) of (view, replica, value): one
                   sign per sample, independent of everything else */
                unsigned long long z = ((unsigned long long)v * 1000003ull + (unsigned long long)r) *
                                           0x9E3779B97F4A7C15ull + (unsigned long long)q;
                z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
                z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
                z ^= z >> 31;
                rep[(size_t)r * n * 3 + q] = ref[q] + ((z >> 63) ? 1.0f : -1.0f) * sqrtf(var[q]);
            }
    }
    return 0;
}

void sbr_seq_free(sbr_seq *s)
{
    int i, e, k;
    if (s->replica)
        for (i = 0; i < s->frames * 2; ++i) free(s->replica[i]);
    free(s->replica);
    if (s->noise_var)
        for (i = 0; i < s->frames * 2; ++i) free(s->noise_var[i]);
    free(s->noise_var);
    if (s->views)
        for (i = 0; i < s->frames * 2; ++i) {
            sbr_view *v = &s->views[i];
            free(v->color); free(v->ref); free(v->depth); free(v->normal); free(v->id); free(v->motion);
        }
    free(s->views);
    for (i = 0; i < s->ladder_count; ++i)
        for (e = 0; e < 2; ++e)
            for (k = 0; k < s->ladder[i].count; ++k) free(s->ladder[i].img[e][k]);
    memset(s, 0, sizeof *s);
}

/* ---- methods ---------------------------------------------------------------------- */

static sbr_method sbr_method_make(const char *name, int temporal, sbl_estimator e, sbl_rectify r,
                                  sbl_weight_mode wm, sbr_stereo_mode st, sbl_estimator se)
{
    sbr_method m;
    memset(&m, 0, sizeof m);
    snprintf(m.name, sizeof m.name, "%s", name);
    m.temporal = temporal;
    m.temporal_desc.estimator = e;
    m.temporal_desc.rectify = r;
    m.temporal_desc.weight_mode = wm;
    m.stereo = st;
    m.stereo_desc.estimator = se;
    return m;
}

static sbr_method sbr_method_oracle(const char *name, int temporal, sbr_stereo_mode st, int bits)
{
    sbr_method m = sbr_method_make(name, temporal, SBL_ESTIMATOR_HISTORY_AWARE, SBL_RECTIFY_NONE,
                                   SBL_WEIGHT_SCALAR, st, SBL_ESTIMATOR_HISTORY_AWARE);
    m.oracle = bits;
    return m;
}

/* The library's defaults: every field of both descriptors zero. */
static sbr_method sbr_method_default(const char *name, sbr_stereo_mode st)
{
    sbr_method m;
    memset(&m, 0, sizeof m);
    snprintf(m.name, sizeof m.name, "%s", name);
    m.temporal = 1;
    m.evidence = 1; /* the default as a user gets it: with the evidence and tail planes passed on */
    m.tail = 1;
    m.stereo = st;
    m.display = st == SBR_STEREO_NONE; /* the temporal filter alone shows its display */
    return m;
}

int sbr_standard_methods(sbr_method *m, int max)
{
    sbr_method all[48];
    int n = 0, i;
    const sbl_estimator HA = SBL_ESTIMATOR_HISTORY_AWARE, P = SBL_ESTIMATOR_PAPER,
                        PR = SBL_ESTIMATOR_PROGRESSIVE, C = SBL_ESTIMATOR_CONSTANT;
    const sbl_rectify RN = SBL_RECTIFY_NONE, RC = SBL_RECTIFY_CLAMP, RV = SBL_RECTIFY_VARIANCE_CLIP;
    const sbl_weight_mode WS = SBL_WEIGHT_SCALAR, WP = SBL_WEIGHT_PER_CHANNEL;
    /* temporal only */
    all[n++] = sbr_method_make("input-1spp", 0, HA, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("const-0.1", 1, C, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("const-0.1+clamp", 1, C, RC, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("const-0.1+varclip", 1, C, RV, WS, SBR_STEREO_NONE, HA);
    all[n] = sbr_method_make("ema-0.2", 1, C, RN, WS, SBR_STEREO_NONE, HA);
    all[n++].temporal_desc.constant_alpha = 0.2f;
    all[n++] = sbr_method_make("progressive", 1, PR, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("progressive+varclip", 1, PR, RV, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("paper", 1, P, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("paper-per-channel", 1, P, RN, WP, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("history-aware", 1, HA, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("history-aware-per-ch", 1, HA, RN, WP, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_default("default", SBR_STEREO_NONE);
    all[n++] = sbr_method_make("robust", 1, SBL_ESTIMATOR_ROBUST, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_make("pooled", 1, SBL_ESTIMATOR_POOLED, RN, WS, SBR_STEREO_NONE, HA);
    all[n++] = sbr_method_oracle("oracle", 1, SBR_STEREO_NONE, SBR_ORACLE_TEMPORAL);
    /* stereo alone (on the 1-spp input) */
    all[n++] = sbr_method_make("stereo-fill", 0, HA, RN, WS, SBR_STEREO_FILL, HA);
    all[n++] = sbr_method_make("stereo-beta-0.5", 0, HA, RN, WS, SBR_STEREO_FIXED, C);
    all[n++] = sbr_method_make("stereo-paper", 0, HA, RN, WS, SBR_STEREO_ADAPTIVE, P);
    all[n++] = sbr_method_make("stereo-history-aware", 0, HA, RN, WS, SBR_STEREO_ADAPTIVE, HA);
    all[n++] = sbr_method_make("stereo-robust", 0, HA, RN, WS, SBR_STEREO_ADAPTIVE, SBL_ESTIMATOR_ROBUST);
    all[n++] = sbr_method_make("stereo-pooled", 0, HA, RN, WS, SBR_STEREO_ADAPTIVE, SBL_ESTIMATOR_POOLED);
    all[n++] = sbr_method_oracle("stereo-oracle", 0, SBR_STEREO_ADAPTIVE, SBR_ORACLE_STEREO);
    /* stereo after the temporal filter (history-aware temporal) */
    all[n++] = sbr_method_make("ha+stereo-fill", 1, HA, RN, WS, SBR_STEREO_FILL, HA);
    all[n++] = sbr_method_make("ha+stereo-beta-0.5", 1, HA, RN, WS, SBR_STEREO_FIXED, C);
    all[n++] = sbr_method_make("ha+stereo-paper", 1, HA, RN, WS, SBR_STEREO_ADAPTIVE, P);
    all[n++] = sbr_method_make("ha+stereo-ha", 1, HA, RN, WS, SBR_STEREO_ADAPTIVE, HA);
    /* the paper's pipeline: paper alpha then paper beta */
    all[n++] = sbr_method_make("paper+stereo-paper", 1, P, RN, WS, SBR_STEREO_ADAPTIVE, P);
    /* the strongest one-line baseline with the stereo blend after it */
    all[n] = sbr_method_make("ema-0.2+stereo-beta-0.5", 1, C, RN, WS, SBR_STEREO_FIXED, C);
    all[n++].temporal_desc.constant_alpha = 0.2f;
    all[n++] = sbr_method_make("robust+stereo-robust", 1, SBL_ESTIMATOR_ROBUST, RN, WS,
                               SBR_STEREO_ADAPTIVE, SBL_ESTIMATOR_ROBUST);
    all[n++] = sbr_method_make("robust+stereo-ha", 1, SBL_ESTIMATOR_ROBUST, RN, WS,
                               SBR_STEREO_ADAPTIVE, HA);
    all[n++] = sbr_method_make("pooled+stereo-ha", 1, SBL_ESTIMATOR_POOLED, RN, WS,
                               SBR_STEREO_ADAPTIVE, HA);
    all[n++] = sbr_method_make("pooled+stereo-pooled", 1, SBL_ESTIMATOR_POOLED, RN, WS,
                               SBR_STEREO_ADAPTIVE, SBL_ESTIMATOR_POOLED);
    /* the default temporal filter, then a fixed beta 0.5 / the stereo oracle: what the
       stereo stage could add to the default's temporal output */
    all[n++] = sbr_method_make("pooled+stereo-beta-0.5", 1, SBL_ESTIMATOR_POOLED, RN, WS,
                               SBR_STEREO_FIXED, C);
    all[n] = sbr_method_oracle("default+stereo-oracle", 1, SBR_STEREO_ADAPTIVE, SBR_ORACLE_STEREO);
    all[n].temporal_desc.estimator = SBL_ESTIMATOR_POOLED;
    all[n++].stereo_desc.estimator = SBL_ESTIMATOR_POOLED;
    /* the library's default combined pipeline, and the oracle of the same pipeline */
    all[n] = sbr_method_default("default-stereo", SBR_STEREO_ADAPTIVE);
    /* a stereo blend follows: the history's bias, which both eyes share, counts double
       (docs/ESTIMATORS.md 4.7) */
    all[n++].temporal_desc.stereo_shared_bias = 1.0f;
    /* the two defaults without the tail plane (the defaults before session 31): what
       the plane adds, in accuracy and in time, in the same run (docs/ESTIMATORS.md 2.4) */
    all[n] = sbr_method_default("default-notail", SBR_STEREO_NONE);
    all[n++].tail = 0;
    /* the temporal default showing its history colour, not its display (the default
       before session 39: docs/ESTIMATORS.md 6.7) */
    all[n] = sbr_method_default("default-nodisplay", SBR_STEREO_NONE);
    all[n++].display = 0;
    all[n] = sbr_method_default("default-stereo-notail", SBR_STEREO_ADAPTIVE);
    all[n].temporal_desc.stereo_shared_bias = 1.0f;
    all[n++].tail = 0;
    all[n++] = sbr_method_oracle("oracle+stereo-oracle", 1, SBR_STEREO_ADAPTIVE,
                                 SBR_ORACLE_TEMPORAL | SBR_ORACLE_STEREO);
    /* the same with the Catmull-Rom history fetch (sbl_reproject_desc.history_filter),
       measured against the bilinear oracles above; oracle-cr: the temporal oracle's own
       blend on the Catmull-Rom x* (how much the sharper fetch raises the ceiling) */
    all[n] = sbr_method_default("default-cr", SBR_STEREO_NONE);
    all[n++].temporal_desc.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    all[n] = sbr_method_default("default-stereo-cr", SBR_STEREO_ADAPTIVE);
    all[n].temporal_desc.stereo_shared_bias = 1.0f; /* as default-stereo */
    all[n++].temporal_desc.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    all[n] = sbr_method_oracle("oracle-cr", 1, SBR_STEREO_NONE, SBR_ORACLE_TEMPORAL);
    all[n++].temporal_desc.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    all[n] = sbr_method_oracle("oracle-cr+stereo-oracle", 1, SBR_STEREO_ADAPTIVE,
                               SBR_ORACLE_TEMPORAL | SBR_ORACLE_STEREO);
    all[n++].temporal_desc.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    /* the combined pipeline with per-eye temporal weights (default-stereo before
       docs/ESTIMATORS.md 4.7: stereo_shared_bias 0) */
    all[n++] = sbr_method_default("default-stereo-per-eye", SBR_STEREO_ADAPTIVE);
    for (i = 0; i < n && i < max; ++i) m[i] = all[i];
    return i < n ? i : n;
}

int sbr_find_method(const char *name, sbr_method *out)
{
    sbr_method all[SBR_MAX_METHODS];
    int n = sbr_standard_methods(all, SBR_MAX_METHODS), i;
    for (i = 0; i < n; ++i)
        if (strcmp(all[i].name, name) == 0) { *out = all[i]; return 0; }
    return 1;
}

/* ---- running ---------------------------------------------------------------------- */

static int sbr_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

static double sbr_ssim_clamped(const float *a, const float *b, int w, int h, float *tmp_a, float *tmp_b)
{
    size_t i, n = (size_t)w * (size_t)h * 3;
    for (i = 0; i < n; ++i) {
        float x = a[i], y = b[i];
        tmp_a[i] = x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
        tmp_b[i] = y < 0.0f ? 0.0f : (y > 1.0f ? 1.0f : y);
    }
    return sbl_metric_ssim(tmp_a, w * 3, tmp_b, w * 3, w, h, 3, 1.0);
}

static sbl_gbuffer sbr_gbuffer(const sbr_view *v, int w, int h, int with_motion)
{
    sbl_gbuffer g;
    memset(&g, 0, sizeof g);
    g.depth = sbl_image_make(v->depth, w, h, 1);
    g.normals = sbl_image_make(v->normal, w, h, 3);
    g.ids = sbl_image_make(v->id, w, h, 1);
    if (with_motion) g.motion = sbl_image_make(v->motion, w, h, 2);
    return g;
}

/* The temporal call's descriptors for view v with colour `color`: the history (colour,
   N, evidence) read from the *_in planes, written to the *_out planes; pv the previous
   frame's view (NULL: no history); ev_in / ev_out NULL: no evidence plane. */
static void sbr_temporal_bind(const sbr_view *v, const sbr_view *pv, float *color, int w, int h,
                              float *hist_in, float *len_in, float *ev_in, float *hist_out,
                              float *len_out, float *ev_out, sbl_frame *fr, sbl_history *hi,
                              sbl_temporal_output *out)
{
    memset(fr, 0, sizeof *fr); memset(hi, 0, sizeof *hi); memset(out, 0, sizeof *out);
    fr->color = sbl_image_make(color, w, h, 3);
    fr->gbuffer = sbr_gbuffer(v, w, h, 1);
    fr->camera = &v->camera;
    if (pv) {
        hi->color = sbl_image_make(hist_in, w, h, 3);
        hi->length = sbl_image_make(len_in, w, h, 1);
        hi->gbuffer = sbr_gbuffer(pv, w, h, 0);
        hi->camera = &pv->camera;
        if (ev_in) hi->evidence = sbl_image_make(ev_in, w, h, 1);
    }
    out->color = sbl_image_make(hist_out, w, h, 3);
    out->length = sbl_image_make(len_out, w, h, 1);
    if (ev_out) out->evidence = sbl_image_make(ev_out, w, h, 1);
}

/* The oracle blend of one eye: y = own estimate (N_Y = ny, NULL: 1), xs / nx = the other
   estimate from the library's reprojection stage (nx <= 0: invalid), ref = reference.
   a = E_X / (E_X + E_Y) over the 3x3 pixels whose x* is valid, squared errors summed
   over the channels (one weight per pixel, like the scalar weight mode). */
static void sbr_oracle_blend(int w, int h, const float *y, const float *ny, const float *xs,
                             const float *nx, const float *ref, float cap, int temporal,
                             float *out, float *nout)
{
    int px, py, i, j, c;
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * (size_t)w + (size_t)px;
            double ex = 0.0, ey = 0.0, a;
            float n_y = ny ? ny[p] : 1.0f, n_x = nx[p];
            if (!(n_y > 0.0f)) n_y = 1.0f;
            if (!(n_x > 0.0f)) {
                for (c = 0; c < 3; ++c) out[p * 3 + c] = y[p * 3 + c];
                nout[p] = temporal ? 1.0f : n_y;
                continue;
            }
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * (size_t)w + (size_t)i;
                    if (!(nx[q] > 0.0f)) continue;
                    for (c = 0; c < 3; ++c) {
                        double dx = (double)xs[q * 3 + c] - ref[q * 3 + c];
                        double dy = (double)y[q * 3 + c] - ref[q * 3 + c];
                        ex += dx * dx;
                        ey += dy * dy;
                    }
                }
            a = ex + ey > 0.0 ? ex / (ex + ey) : 0.5;
            for (c = 0; c < 3; ++c)
                out[p * 3 + c] = (float)((1.0 - a) * xs[p * 3 + c] + a * y[p * 3 + c]);
            if (n_x > cap) n_x = cap;
            nout[p] = sbl_blend_sample_count((float)a, n_x, n_y);
            if (nout[p] > cap) nout[p] = cap;
        }
}

/* The statistics oracle's blend (SBR_ORACLE_STAT_*). ys / xss: 1 + R images of W*H*3 (the
   r-th at r * W*H*3), the own estimate and x* of the replicas (sbr_seq.replica): r = 0
   the expectation, r >= 1 zero-mean noise around it; ref: the frame's replica 0 (the
   pixel's mean). E = (r0 - ref)^2 + the replicas'
   mean square about r0, summed over the channels (or for the own estimate, yvar's sum if
   not NULL: a raw sample's variance, known). The one weight a = E_X / (E_X + E_Y) goes to
   the evaluated estimate (y, xs -> out), to every replica (-> outs, unless NULL), and to
   aout if not NULL.
   Validity (nx) comes from the G-buffers, so it is the replicas' too (the caller checks). */
static void sbr_stat_oracle_blend(int w, int h, int R, const float *y, const float *ys,
                                  const float *yvar, const float *ny, const float *xs, const float *xss,
                                  const float *nx, const float *ref, float cap, int temporal,
                                  float *out, float *outs, float *nout, float *aout)
{
    const size_t n = (size_t)w * (size_t)h;
    size_t p, o;
    int r, c;
    for (p = 0; p < n; ++p) {
        double ex = 0.0, ey = 0.0, vx = 0.0, vy = 0.0, a = 1.0;
        float n_y = ny ? ny[p] : 1.0f, n_x = nx[p];
        if (!(n_y > 0.0f)) n_y = 1.0f;
        if (n_x > 0.0f) {
            for (c = 0; c < 3; ++c) {
                const size_t p0 = p * 3 + (size_t)c;
                ex += ((double)xss[p0] - ref[p0]) * ((double)xss[p0] - ref[p0]);
                ey += ((double)ys[p0] - ref[p0]) * ((double)ys[p0] - ref[p0]);
                for (r = 1; r <= R; ++r) {
                    o = (size_t)r * n * 3 + p0;
                    vx += ((double)xss[o] - xss[p0]) * ((double)xss[o] - xss[p0]);
                    vy += ((double)ys[o] - ys[p0]) * ((double)ys[o] - ys[p0]);
                }
            }
            ex += vx / R;
            ey = yvar ? (double)yvar[p * 3] + yvar[p * 3 + 1] + yvar[p * 3 + 2] : ey + vy / R;
            a = ex + ey > 0.0 ? ex / (ex + ey) : 0.5;
        }
        if (aout) aout[p] = (float)a;
        for (c = 0; c < 3; ++c) {
            out[p * 3 + c] = (float)((1.0 - a) * xs[p * 3 + c] + a * y[p * 3 + c]);
            for (r = 0; outs && r <= R; ++r) {
                o = (size_t)r * n * 3 + p * 3 + (size_t)c;
                outs[o] = (float)((1.0 - a) * xss[o] + a * ys[o]);
            }
        }
        if (!(n_x > 0.0f)) {
            nout[p] = temporal ? 1.0f : n_y;
            continue;
        }
        if (n_x > cap) n_x = cap;
        nout[p] = sbl_blend_sample_count((float)a, n_x, n_y);
        if (nout[p] > cap) nout[p] = cap;
    }
}

/* The statistics oracle's replicas share the evaluated image's weights only if each
   reprojection keeps the same taps: its validity / N output must be the same bits. */
static int sbr_same_validity(const char *name, const float *nx, const float *nx_replica, size_t n)
{
    if (memcmp(nx, nx_replica, n * sizeof(float)) == 0) return 0;
    fprintf(stderr, "%s: a replica's reprojection differs in validity\n", name);
    return SBL_ERROR_INVALID_PARAM;
}

/* Rec. 709 luminance of an RGB image (the quantity Weber's law is about). */
void sbr_luminance(const float *rgb, float *lum, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        lum[i] = 0.2126f * rgb[3 * i] + 0.7152f * rgb[3 * i + 1] + 0.0722f * rgb[3 * i + 2];
}

/* SBR_STEREO_MASKED: the consistency mask of each eye on the two eyes' luminances, then
   the stereo blend where it marks a pixel. lum: 2 * W*H floats, mask: W*H bytes. */
static int sbr_stereo_masked(const sbl_stereo_desc *sd, float threshold, const sbl_eye *eye,
                             float *const *disp, float *lum, unsigned char *mask, int w, int h,
                             int one_pass)
{
    const size_t n = (size_t)w * (size_t)h;
    size_t bytes = one_pass ? sbl_stereo_adaptive_scratch_size(w, 3) : sbl_stereo_scratch_size(w, 3);
    void *scratch = malloc(bytes);
    sbl_image L[2];
    sbl_eye geo[2];
    int e, rc = 0;
    if (!scratch) return SBL_ERROR_OUT_OF_MEMORY;
    if (one_pass) {
        sbl_adaptive_desc ad;
        memset(&ad, 0, sizeof ad);
        ad.threshold = threshold;
        for (e = 0; e < 2 && rc == 0; ++e)
            rc = sbl_stereo_blend_adaptive(sd, &ad, (sbl_eye_index)e, &eye[e], &eye[!e],
                                           sbl_image_make(disp[e], w, h, 3), sbl_image_make(NULL, 0, 0, 0),
                                           NULL, 0, 0, h, scratch, bytes, NULL, NULL, NULL);
        free(scratch);
        return rc;
    }
    for (e = 0; e < 2; ++e) {
        sbr_luminance(eye[e].color.data, lum + e * n, n);
        L[e] = sbl_image_make(lum + e * n, w, h, 1);
        geo[e] = eye[e];
        memset(&geo[e].length, 0, sizeof geo[e].length);
    }
    for (e = 0; e < 2 && rc == 0; ++e) {
        rc = sbl_stereo_consistency(sd, threshold, (sbl_eye_index)e, &geo[e], &geo[!e], L[e],
                                    L[!e], mask, w, 0, h, NULL, 0, NULL);
        if (rc == 0)
            rc = sbl_stereo_blend_masked(sd, (sbl_eye_index)e, &eye[e], &eye[!e], mask, w,
                                         sbl_image_make(disp[e], w, h, 3), sbl_image_make(NULL, 0, 0, 0),
                                         0, h, scratch, bytes, NULL);
    }
    free(scratch);
    return rc;
}

/* SBR_FRAME_DEBUG=1: one frame-eye's split (sbl_metric_bright_split's sums and threshold),
   then its bright pixels and its dim pixels shown bright (an error above the threshold:
   trails, fireflies), with the weight (-1 where no temporal weight wrote it) and N */
static void sbr_debug_frame(const char *name, int f, int e, const float *out, const float *ref,
                            const float *in, const float *alpha, const float *len, int w, int h,
                            double sse_b, double sse_d, long nb, double thr)
{
    const long n = (long)w * h;
    long p;
    fprintf(stderr, "frame %s %d %d rmse %.5f rmse_dim %.5f bright_px %ld bright_mse_pct %.1f\n", name, f, e,
            sqrt((sse_b + sse_d) / (3.0 * (double)n)), sqrt(sse_d / (3.0 * (double)(n - nb))), nb,
            sse_b + sse_d > 0 ? 100.0 * sse_b / (sse_b + sse_d) : 0.0);
    for (p = 0; p < n; ++p) {
        const float *o = out + p * 3, *r = ref + p * 3;
        const int bright = r[0] > thr || r[1] > thr || r[2] > thr;
        if (bright || fabs((double)o[0] - r[0]) > thr || fabs((double)o[1] - r[1]) > thr ||
            fabs((double)o[2] - r[2]) > thr)
            fprintf(stderr, "%s %s %d %d x %ld y %ld out %.3f ref %.3f in %.3f alpha %.4f N %.2f\n",
                    bright ? "brightpx" : "dimshownbright", name, f, e, p % w, p / w, o[0], r[0], in[p * 3],
                    alpha ? alpha[p] : -1.0f, len ? len[p] : -1.0f);
    }
}

int sbr_run(const sbr_seq *s, const sbr_method *m, sbr_result *res, sbr_frame_fn fn, void *ctx)
{
    return sbr_run_alpha(s, m, res, fn, NULL, ctx);
}

int sbr_run_alpha(const sbr_seq *s, const sbr_method *m, sbr_result *res, sbr_frame_fn fn,
                  sbr_frame_fn alpha_fn, void *ctx)
{
    const int w = s->width, h = s->height;
    const size_t n = (size_t)w * (size_t)h;
    float *hist[2][2], *len[2][2], *input[2], *tout[2], *disp[2], *tmp_a, *tmp_b;
    float *ox, *onx, *onx2; /* oracle: x*, its N (or validity), the blend's N */
    float *alpha[2];        /* the temporal weights, for alpha_fn */
    float *carry[2][2] = {{NULL, NULL}, {NULL, NULL}}, *carry3 = NULL, *ocarry3 = NULL, *ocarry = NULL;
    float *tcarry[2][2] = {{NULL, NULL}, {NULL, NULL}}, *otcarry = NULL; /* temporal_blend_carry3 */
    float *tailp[2][2] = {{NULL, NULL}, {NULL, NULL}}; /* m->tail: the tail planes, per eye, ping-ponged */
    /* the statistics oracle: the replicas' histories (per eye, ping-ponged), their x*, and
       the replicas each eye shows the stereo stage */
    float *rhist[2][2] = {{NULL, NULL}, {NULL, NULL}}, *rxs = NULL;
    const float *rtout[2] = {NULL, NULL};
    const int R = s->replicas;
    unsigned char *mask;
    double *times, mse_sum = 0, mse1_sum = 0, ssim_sum = 0, eff_sum = 0;
    double sse_bright_sum = 0, sse_dim_sum = 0;
    long bright_px = 0;
    const int frame_debug = getenv("SBR_FRAME_DEBUG") != NULL;
    /* the method shows the library filter's display: the one condition for writing it
       (sbl_temporal_filter_frame's branch) and for not copying the history over it */
    const int shows_display = m->display && m->temporal && m->stereo == SBR_STEREO_NONE &&
                              !(m->oracle & (SBR_ORACLE_TEMPORAL | SBR_ORACLE_STAT_TEMPORAL)) &&
                              !m->temporal_blend && !m->temporal_blend_carry &&
                              !m->temporal_blend_carry3;
    /* the debug lines' alpha: only the library's temporal weights and the statistics oracle
       write it (-1 otherwise) */
    const int alpha_known = m->temporal && !(m->oracle & SBR_ORACLE_TEMPORAL);
    long traced = 0, traced_total = 0;
    int ping[2] = {0, 0}, f, e, i, eval = 0, eff_n = 0, skip = s->frames / 4, rc = 0;
    sbl_stereo_desc sd = m->stereo_desc;
    memset(res, 0, sizeof *res);
    sd.rig = SBL_RIG_PARALLEL;
    sd.focal_px = s->focal_px;
    sd.baseline = s->baseline;
    for (e = 0; e < 2; ++e) {
        for (i = 0; i < 2; ++i) { hist[e][i] = sbr_alloc(n * 3); len[e][i] = sbr_alloc(n); }
        input[e] = sbr_alloc(n * 3);
        disp[e] = sbr_alloc(n * 3);
    }
    mask = (unsigned char *)calloc(n, 1);
    tmp_a = sbr_alloc(n * 3); /* also the luminance planes of SBR_STEREO_MASKED */
    tmp_b = sbr_alloc(n * 3);
    ox = sbr_alloc(n * 3);
    if (m->temporal_blend_carry3) {
        for (e = 0; e < 2; ++e)
            for (i = 0; i < 2; ++i) tcarry[e][i] = sbr_alloc(n * 3);
        otcarry = sbr_alloc(n * 3);
    }
    if (m->temporal_blend_carry || m->temporal_blend_carry3 || m->evidence) {
        for (e = 0; e < 2; ++e)
            for (i = 0; i < 2; ++i) carry[e][i] = sbr_alloc(n);
        carry3 = sbr_alloc(n * 3);
        ocarry3 = sbr_alloc(n * 3);
        ocarry = sbr_alloc(n);
    }
    if (m->tail)
        for (e = 0; e < 2; ++e)
            for (i = 0; i < 2; ++i) tailp[e][i] = sbr_alloc(n * 2);
    alpha[0] = alpha_fn || frame_debug ? sbr_alloc(n) : NULL;
    alpha[1] = alpha_fn || frame_debug ? sbr_alloc(n) : NULL;
    onx = sbr_alloc(n);
    onx2 = sbr_alloc(n);
    times = (double *)calloc((size_t)s->frames, sizeof(double));
    if (!mask || !times) { fprintf(stderr, "out of memory\n"); exit(2); }
    if (m->oracle && !s->views[0].ref) {
        fprintf(stderr, "%s: needs the reference images\n", m->name);
        rc = SBL_ERROR_MISSING_INPUT;
    }
    if ((m->oracle & (SBR_ORACLE_STAT_TEMPORAL | SBR_ORACLE_STAT_STEREO)) &&
        (R < 1 || m->stereo == SBR_STEREO_FILL ||
         /* the replicas' variance is the evaluated image's only through a linear filter:
            the Catmull-Rom fetch's overshoot clamp is not one */
         m->temporal_desc.reproject.history_filter != SBL_HISTORY_BILINEAR ||
         ((m->oracle & SBR_ORACLE_STAT_STEREO) && m->temporal && !(m->oracle & SBR_ORACLE_STAT_TEMPORAL)))) {
        /* the replicas must go through the same weights at every stage */
        fprintf(stderr, "%s: needs sbr_seq_add_replicas, the bilinear fetch and statistics weights at every stage\n",
                m->name);
        rc = SBL_ERROR_MISSING_INPUT;
    } else if (m->oracle & (SBR_ORACLE_STAT_TEMPORAL | SBR_ORACLE_STAT_STEREO)) {
        for (e = 0; e < 2; ++e)
            for (i = 0; i < 2 && (m->oracle & SBR_ORACLE_STAT_TEMPORAL); ++i)
                rhist[e][i] = sbr_alloc(n * 3 * (size_t)(R + 1));
        rxs = sbr_alloc(n * 3 * (size_t)(R + 1));
    }

    for (f = 0; f < s->frames && rc == 0; ++f) {
        const sbr_view *v[2];
        double t0, t1;
        v[0] = &s->views[f * 2];
        v[1] = &s->views[f * 2 + 1];
        for (e = 0; e < 2; ++e) memcpy(input[e], v[e]->color, n * 3 * sizeof(float));
        t0 = sbr_now_ms();
        if (m->stereo == SBR_STEREO_FILL) {
            /* only the left eye is traced in full; the right eye gets the left one
               reprojected, and its own (traced) samples where reprojection failed */
            sbl_eye tgt, src;
            long cnt = 0;
            memset(&tgt, 0, sizeof tgt); memset(&src, 0, sizeof src);
            tgt.gbuffer = sbr_gbuffer(v[1], w, h, 0);
            src.color = sbl_image_make(v[0]->color, w, h, 3);
            src.gbuffer = sbr_gbuffer(v[0], w, h, 0);
            rc = sbl_stereo_fill(&sd, SBL_EYE_RIGHT, &tgt, &src, sbl_image_make(input[1], w, h, 3),
                                 mask, w, 0, h, &cnt);
            if (rc == 0)
                rc = sbl_merge_traced(sbl_image_make(input[1], w, h, 3),
                                      sbl_image_make(v[1]->color, w, h, 3), mask, w, 0, h);
            if (f >= skip) { traced += cnt; traced_total += (long)n; }
        }
        for (e = 0; e < 2 && rc == 0; ++e) {
            if (m->temporal) {
                sbl_frame fr;
                sbl_history hi;
                sbl_temporal_output out;
                const sbr_view *pv = f > 0 ? &s->views[(f - 1) * 2 + e] : NULL;
                sbr_temporal_bind(v[e], pv, input[e], w, h, hist[e][ping[e]], len[e][ping[e]],
                                  m->evidence ? carry[e][ping[e]] : NULL, hist[e][!ping[e]],
                                  len[e][!ping[e]], m->evidence ? carry[e][!ping[e]] : NULL,
                                  &fr, &hi, &out);
                if (m->tail) {
                    if (pv) hi.tail = sbl_image_make(tailp[e][ping[e]], w, h, 2);
                    out.tail = sbl_image_make(tailp[e][!ping[e]], w, h, 2);
                }
                if (alpha[e]) out.alpha = sbl_image_make(alpha[e], w, h, 1);
                if (m->temporal_blend_carry || m->temporal_blend_carry3) {
                    /* the carried plane rides on the history's reprojection: the same call
                       with the plane (copied to three channels) as the history's colour */
                    sbl_temporal_desc td = sbl_temporal_defaults(&m->temporal_desc);
                    size_t q;
                    rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, pv ? &hi : NULL,
                                                sbl_image_make(ox, w, h, 3),
                                                sbl_image_make(onx, w, h, 1), 0, h);
                    if (rc == 0 && pv) {
                        sbl_history hz = hi;
                        for (q = 0; q < n; ++q)
                            carry3[q * 3] = carry3[q * 3 + 1] = carry3[q * 3 + 2] = carry[e][ping[e]][q];
                        hz.color = sbl_image_make(carry3, w, h, 3);
                        rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, &hz,
                                                    sbl_image_make(ocarry3, w, h, 3),
                                                    sbl_image_make(onx2, w, h, 1), 0, h);
                        for (q = 0; q < n; ++q) ocarry[q] = onx2[q] > 0 ? ocarry3[q * 3] : 0.0f;
                        if (rc == 0 && m->temporal_blend_carry3) {
                            hz.color = sbl_image_make(tcarry[e][ping[e]], w, h, 3);
                            rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, &hz,
                                                        sbl_image_make(otcarry, w, h, 3),
                                                        sbl_image_make(onx2, w, h, 1), 0, h);
                            for (q = 0; q < n; ++q)
                                if (!(onx2[q] > 0)) otcarry[q * 3] = otcarry[q * 3 + 1] = otcarry[q * 3 + 2] = 0.0f;
                        }
                        if (rc == 0 && m->temporal_blend_carry3 && m->fetch_xy) {
                            /* the coordinates gather to the taps' weighted position */
                            float *coord = sbr_alloc(n * 3);
                            for (q = 0; q < n; ++q) {
                                coord[q * 3] = (float)(q % (size_t)w);
                                coord[q * 3 + 1] = (float)(q / (size_t)w);
                                coord[q * 3 + 2] = 1.0f;
                            }
                            hz.color = sbl_image_make(coord, w, h, 3);
                            rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, &hz,
                                                        sbl_image_make(m->fetch_xy, w, h, 3),
                                                        sbl_image_make(onx2, w, h, 1), 0, h);
                            for (q = 0; q < n; ++q)
                                if (!(onx2[q] > 0)) m->fetch_xy[q * 3] = m->fetch_xy[q * 3 + 1] = m->fetch_xy[q * 3 + 2] = 0.0f;
                            free(coord);
                        }
                    } else {
                        memset(ocarry, 0, n * sizeof(float));
                        if (otcarry) memset(otcarry, 0, n * 3 * sizeof(float));
                        if (m->fetch_xy) memset(m->fetch_xy, 0, n * 3 * sizeof(float));
                    }
                    if (rc == 0 && m->temporal_blend_carry3)
                        m->temporal_blend_carry3(m->temporal_blend_ctx, w, h, input[e], ox, onx, ocarry,
                                                 otcarry, td.max_history, hist[e][!ping[e]],
                                                 len[e][!ping[e]], carry[e][!ping[e]],
                                                 tcarry[e][!ping[e]]);
                    else if (rc == 0)
                        m->temporal_blend_carry(m->temporal_blend_ctx, w, h, input[e], ox, onx, ocarry,
                                                td.max_history, hist[e][!ping[e]], len[e][!ping[e]],
                                                carry[e][!ping[e]]);
                } else if (m->temporal_blend) {
                    sbl_temporal_desc td = sbl_temporal_defaults(&m->temporal_desc);
                    rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, pv ? &hi : NULL,
                                                sbl_image_make(ox, w, h, 3),
                                                sbl_image_make(onx, w, h, 1), 0, h);
                    if (rc == 0)
                        m->temporal_blend(m->temporal_blend_ctx, w, h, input[e], ox, onx,
                                          td.max_history, hist[e][!ping[e]], len[e][!ping[e]]);
                } else if (m->oracle & SBR_ORACLE_STAT_TEMPORAL) {
                    sbl_temporal_desc td = sbl_temporal_defaults(&m->temporal_desc);
                    int r;
                    rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, pv ? &hi : NULL,
                                                sbl_image_make(ox, w, h, 3),
                                                sbl_image_make(onx, w, h, 1), 0, h);
                    for (r = 0; r <= R && rc == 0; ++r) {
                        sbl_history hr = hi;
                        hr.color = sbl_image_make(rhist[e][ping[e]] + (size_t)r * n * 3, w, h, 3);
                        rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, pv ? &hr : NULL,
                                                    sbl_image_make(rxs + (size_t)r * n * 3, w, h, 3),
                                                    sbl_image_make(onx2, w, h, 1), 0, h);
                        if (rc == 0) rc = sbr_same_validity(m->name, onx, onx2, n);
                    }
                    if (rc == 0)
                        sbr_stat_oracle_blend(w, h, R, input[e], s->replica[f * 2 + e],
                                              s->noise_var[f * 2 + e], NULL, ox, rxs, onx,
                                              s->replica[f * 2 + e], td.max_history, 1, hist[e][!ping[e]],
                                              rhist[e][!ping[e]], len[e][!ping[e]], alpha[e]);
                } else if (m->oracle & SBR_ORACLE_TEMPORAL) {
                    sbl_temporal_desc td = sbl_temporal_defaults(&m->temporal_desc);
                    rc = sbl_reproject_temporal(&td.reproject, td.source, &fr, pv ? &hi : NULL,
                                                sbl_image_make(ox, w, h, 3),
                                                sbl_image_make(onx, w, h, 1), 0, h);
                    if (rc == 0)
                        sbr_oracle_blend(w, h, input[e], NULL, ox, onx, v[e]->ref, td.max_history,
                                         1, hist[e][!ping[e]], len[e][!ping[e]]);
                } else {
                    if (shows_display) out.display = sbl_image_make(disp[e], w, h, 3);
                    rc = sbl_temporal_filter_frame(&m->temporal_desc, &fr, pv ? &hi : NULL, &out);
                }
                ping[e] = !ping[e];
                tout[e] = hist[e][ping[e]];
                rtout[e] = rhist[e][ping[e]];
            } else {
                tout[e] = input[e];
                rtout[e] = R ? s->replica[f * 2 + e] : NULL;
            }
        }
        if (rc == 0 && (m->stereo == SBR_STEREO_FIXED || m->stereo == SBR_STEREO_ADAPTIVE)) {
            sbl_eye eye[2];
            for (e = 0; e < 2; ++e) {
                memset(&eye[e], 0, sizeof eye[e]);
                eye[e].color = sbl_image_make(tout[e], w, h, 3);
                if (m->temporal) eye[e].length = sbl_image_make(len[e][ping[e]], w, h, 1);
                /* this frame's carried evidence (the temporal output's plane) */
                if (m->temporal && m->evidence && carry[e][ping[e]])
                    eye[e].evidence = sbl_image_make(carry[e][ping[e]], w, h, 1);
                eye[e].gbuffer = sbr_gbuffer(v[e], w, h, 0);
            }
            if (m->stereo == SBR_STEREO_FIXED) sd.estimator = SBL_ESTIMATOR_CONSTANT;
            if (m->oracle & SBR_ORACLE_STAT_STEREO) {
                for (e = 0; e < 2 && rc == 0; ++e) {
                    int r;
                    rc = sbl_reproject_stereo(&sd, (sbl_eye_index)e, &eye[e], &eye[!e],
                                              sbl_image_make(ox, w, h, 3),
                                              sbl_image_make(onx, w, h, 1), 0, h);
                    for (r = 0; r <= R && rc == 0; ++r) {
                        sbl_eye er[2];
                        er[0] = eye[0];
                        er[1] = eye[1];
                        er[0].color = sbl_image_make(rtout[0] + (size_t)r * n * 3, w, h, 3);
                        er[1].color = sbl_image_make(rtout[1] + (size_t)r * n * 3, w, h, 3);
                        rc = sbl_reproject_stereo(&sd, (sbl_eye_index)e, &er[e], &er[!e],
                                                  sbl_image_make(rxs + (size_t)r * n * 3, w, h, 3),
                                                  sbl_image_make(onx2, w, h, 1), 0, h);
                        if (rc == 0) rc = sbr_same_validity(m->name, onx, onx2, n);
                    }
                    if (rc == 0)
                        sbr_stat_oracle_blend(w, h, R, tout[e], rtout[e],
                                              m->temporal ? NULL : s->noise_var[f * 2 + e],
                                              m->temporal ? len[e][ping[e]] : NULL, ox, rxs, onx,
                                              s->replica[f * 2 + e], FLT_MAX, 0, disp[e], NULL, onx2, NULL);
                }
            } else if (m->oracle & SBR_ORACLE_STEREO) {
                for (e = 0; e < 2 && rc == 0; ++e) {
                    rc = sbl_reproject_stereo(&sd, (sbl_eye_index)e, &eye[e], &eye[!e],
                                              sbl_image_make(ox, w, h, 3),
                                              sbl_image_make(onx, w, h, 1), 0, h);
                    if (rc == 0)
                        sbr_oracle_blend(w, h, tout[e], m->temporal ? len[e][ping[e]] : NULL, ox,
                                         onx, v[e]->ref, FLT_MAX, 0, disp[e], onx2);
                }
            } else {
                rc = sbl_stereo_blend_frame(&sd, &eye[0], &eye[1], sbl_image_make(disp[0], w, h, 3),
                                            sbl_image_make(disp[1], w, h, 3));
            }
        } else if (rc == 0 && (m->stereo == SBR_STEREO_MASKED || m->stereo == SBR_STEREO_ONE_PASS)) {
            sbl_eye eye[2];
            for (e = 0; e < 2; ++e) {
                memset(&eye[e], 0, sizeof eye[e]);
                eye[e].color = sbl_image_make(tout[e], w, h, 3);
                if (m->temporal) eye[e].length = sbl_image_make(len[e][ping[e]], w, h, 1);
                /* this frame's carried evidence (the temporal output's plane) */
                if (m->temporal && m->evidence && carry[e][ping[e]])
                    eye[e].evidence = sbl_image_make(carry[e][ping[e]], w, h, 1);
                eye[e].gbuffer = sbr_gbuffer(v[e], w, h, 0);
            }
            rc = sbr_stereo_masked(&sd, m->weber_threshold, eye, disp, tmp_a, mask, w, h,
                                   m->stereo == SBR_STEREO_ONE_PASS);
        } else if (rc == 0 && !shows_display) {
            for (e = 0; e < 2; ++e) memcpy(disp[e], tout[e], n * 3 * sizeof(float));
        }
        t1 = sbr_now_ms();
        if (rc != 0) break;
        times[f] = t1 - t0;
        if (fn)
            for (e = 0; e < 2; ++e) fn(ctx, f, e, disp[e], w, h);
        if (alpha_fn && m->temporal && !(m->oracle & SBR_ORACLE_TEMPORAL))
            for (e = 0; e < 2; ++e) alpha_fn(ctx, f, e, alpha[e], w, h);
        if (f >= skip && v[0]->ref) {
            for (e = 0; e < 2; ++e) {
                double sse_b, sse_d, thr;
                long nb;
                /* one pass: the split's two sums are the frame-eye's squared error */
                thr = sbl_metric_bright_split(disp[e], w * 3, v[e]->ref, w * 3, w, h, 3, SBR_BRIGHT,
                                              &sse_b, &sse_d, &nb);
                mse_sum += (sse_b + sse_d) / (3.0 * (double)n);
                sse_bright_sum += sse_b;
                sse_dim_sum += sse_d;
                bright_px += nb;
                if (frame_debug)
                    sbr_debug_frame(m->name, f, e, disp[e], v[e]->ref, v[e]->color,
                                    alpha_known ? alpha[e] : NULL, m->temporal ? len[e][ping[e]] : NULL,
                                    w, h, sse_b, sse_d, nb, thr);
                mse1_sum += sbl_metric_mse(v[e]->color, w * 3, v[e]->ref, w * 3, w, h, 3);
                ssim_sum += sbr_ssim_clamped(disp[e], v[e]->ref, w, h, tmp_a, tmp_b);
            }
            ++eval;
        }
        for (i = 0; i < s->ladder_count; ++i) {
            const sbr_ladder *l = &s->ladder[i];
            if (l->frame != f || f < skip || !v[0]->ref || l->count < 2) continue;
            for (e = 0; e < 2; ++e) {
                double spp[SBR_MAX_LADDER], r[SBR_MAX_LADDER];
                int k;
                for (k = 0; k < l->count; ++k) {
                    spp[k] = l->spp[k];
                    r[k] = sbl_metric_rmse(l->img[e][k], w * 3, v[e]->ref, w * 3, w, h, 3);
                }
                {
                    const double rm = sbl_metric_rmse(disp[e], w * 3, v[e]->ref, w * 3, w, h, 3);
                    const double es = sbl_metric_effective_spp(rm, spp, r, l->count);
                    if (getenv("SBR_EFF_DEBUG"))
                        fprintf(stderr, "eff %s frame %d eye %d rmse %.5f eff %.3f ladder %.5f..%.5f\n", m->name, f, e,
                                rm, es, r[0], r[l->count - 1]);
                    eff_sum += es;
                }
                ++eff_n;
            }
        }
    }
    if (rc == 0) {
        qsort(times, (size_t)s->frames, sizeof(double), sbr_cmp_double);
        res->ms = times[s->frames / 2];
        res->eval_frames = eval;
        if (eval) {
            res->rmse = sqrt(mse_sum / (2.0 * eval));
            res->ssim = ssim_sum / (2.0 * eval);
            res->indep_spp = mse_sum > 0 ? mse1_sum / mse_sum : 0;
            res->rmse_dim = sqrt(sse_dim_sum / (3.0 * ((double)n * 2.0 * eval - (double)bright_px)));
            res->bright_mse_pct = sse_bright_sum + sse_dim_sum > 0
                                      ? 100.0 * sse_bright_sum / (sse_bright_sum + sse_dim_sum) : 0.0;
            res->bright_px_pct = 100.0 * (double)bright_px / ((double)n * 2.0 * eval);
        }
        res->eff_spp = eff_n ? eff_sum / eff_n : 0;
        res->traced_pct = traced_total ? 100.0 * (double)traced / (double)traced_total : 100.0;
    } else {
        fprintf(stderr, "%s: %s\n", m->name, sbl_result_string((sbl_result)rc));
    }
    for (e = 0; e < 2; ++e) {
        for (i = 0; i < 2; ++i) { free(hist[e][i]); free(len[e][i]); }
        free(input[e]); free(disp[e]);
    }
    for (e = 0; e < 2; ++e) { free(carry[e][0]); free(carry[e][1]); }
    free(carry3); free(ocarry3); free(ocarry);
    for (e = 0; e < 2; ++e) { free(tcarry[e][0]); free(tcarry[e][1]); free(tailp[e][0]); free(tailp[e][1]); }
    free(otcarry);
    for (e = 0; e < 2; ++e) { free(rhist[e][0]); free(rhist[e][1]); }
    free(rxs);
    free(mask); free(tmp_a); free(tmp_b); free(times); free(ox); free(onx); free(onx2); free(alpha[0]); free(alpha[1]);
    return rc;
}

#endif /* SBL_RUNNER_IMPLEMENTATION */
