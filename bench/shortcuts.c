/* make bench-shortcuts: what each adaptive shortcut of the row pipeline saves and what
   error it adds (issue 10), on the synthetic scenes (static: a camera at rest for the
   whole sequence; shadow: at rest, the light moves; dynamic; pan) and ../shared/data.

   The library is built once per shortcut set (bench/shortcuts_variant.c with
   SBL_SHORTCUTS = all, all but one, none) and every build runs the default pipeline
   side by side on the same frames with its own history: the temporal filter per eye
   (the evidence plane carried), then the default stereo blend of both eyes. Per build:
   thread CPU ms per stereo frame (the median of --reps calls on each frame, summed
   over the frames, divided by them) and its ratio to the build with every shortcut,
   the largest difference of any output value (temporal colour / N / evidence, the
   displayed colour) from that build, and the displayed RMSE against the reference over
   frames >= frames / 4. G-buffers: "depth" = depth + motion vectors (the shortcuts'
   case), "full" = + normals + ids (the temporal tiles do not apply: their tests need
   the general path).

   usage: shortcuts [--reps N] [--quick] [--data DIR] [--scenes S,T,..] [--gbuffer depth|full|both]
   Instructions instead of time: sh bench/shortcuts_ipp.sh (callgrind on the build made
   with -DSC_CALLGRIND, which instruments only the library calls). */
#define _POSIX_C_SOURCE 200809L
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#define SBL_SCENE_IMPLEMENTATION
#include "sbl_scene.h"
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"
#define SBL_RUNNER_IMPLEMENTATION
#include "sbl_runner.h"
#include "sbl_exr.h"
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#ifdef SC_CALLGRIND /* bench/shortcuts_ipp.sh: instrument only the library calls */
#include <valgrind/callgrind.h>
#define SC_COUNT_START() CALLGRIND_START_INSTRUMENTATION
#define SC_COUNT_STOP() CALLGRIND_STOP_INSTRUMENTATION
#else
#define SC_COUNT_START() ((void)0)
#define SC_COUNT_STOP() ((void)0)
#endif

typedef sbl_result (*temporal_fn)(const sbl_temporal_desc *, const sbl_frame *, const sbl_history *,
                                  sbl_temporal_output *, void *, size_t);
typedef sbl_result (*stereo_fn)(const sbl_stereo_desc *, sbl_eye_index, const sbl_eye *, const sbl_eye *,
                                sbl_image, sbl_image, void *, size_t);
#define SC_DECLARE(M) \
    sbl_result sc_temporal_##M(const sbl_temporal_desc *, const sbl_frame *, const sbl_history *, \
                               sbl_temporal_output *, void *, size_t); \
    sbl_result sc_stereo_##M(const sbl_stereo_desc *, sbl_eye_index, const sbl_eye *, const sbl_eye *, \
                             sbl_image, sbl_image, void *, size_t);
SC_DECLARE(31)
SC_DECLARE(30)
SC_DECLARE(29)
SC_DECLARE(27)
SC_DECLARE(23)
SC_DECLARE(15)
SC_DECLARE(0)

#define NV 7
static const struct variant {
    const char *name;
    temporal_fn temporal;
    stereo_fn stereo;
} variants[NV] = {
    {"every shortcut", sc_temporal_31, sc_stereo_31},
    {"without void tiles", sc_temporal_30, sc_stereo_30},
    {"without tiles at rest", sc_temporal_29, sc_stereo_29},
    {"without sky tiles", sc_temporal_27, sc_stereo_27},
    {"without full chunks", sc_temporal_23, sc_stereo_23},
    {"without far tiles", sc_temporal_15, sc_stereo_15},
    {"no shortcut", sc_temporal_0, sc_stereo_0},
};

typedef struct state {       /* one build's pipeline state */
    float *hist[2][2], *len[2][2], *evid[2][2], *disp[2], *dlen[2];
    int ping[2];
    double t_ms, s_ms, max_diff, mse;
    long diff_count;
} state;

static float *falloc(size_t n)
{
    float *p = (float *)calloc(n ? n : 1, sizeof(float));
    if (!p) { fprintf(stderr, "out of memory\n"); exit(2); }
    return p;
}

static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* the largest |a - b| (a NaN against a number counts as infinite) and the count of
   values whose bits differ */
static void compare(const float *a, const float *b, size_t n, state *st)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        double d;
        if (memcmp(&a[i], &b[i], sizeof(float)) == 0) continue;
        ++st->diff_count;
        d = (a[i] != a[i]) != (b[i] != b[i]) ? HUGE_VAL : fabs((double)a[i] - (double)b[i]);
        if (d > st->max_diff) st->max_diff = d;
    }
}

static sbl_gbuffer gbuffer_of(const sbr_view *v, int w, int h, int full, int motion)
{
    sbl_gbuffer g;
    memset(&g, 0, sizeof g);
    g.depth = sbl_image_make(v->depth, w, h, 1);
    if (full) {
        g.normals = sbl_image_make(v->normal, w, h, 3);
        g.ids = sbl_image_make(v->id, w, h, 1);
    }
    if (motion) g.motion = sbl_image_make(v->motion, w, h, 2);
    return g;
}

static void bench_scene(const sbr_seq *s, int full, int reps)
{
    const int w = s->width, h = s->height, skip = s->frames / 4;
    const size_t n = (size_t)w * (size_t)h;
    const size_t tbytes = sbl_temporal_scratch_size(w, 3), sbytes = sbl_stereo_scratch_size(w, 3);
    void *tscratch = malloc(tbytes), *sscratch = malloc(sbytes);
    double *times = (double *)malloc(sizeof(double) * (size_t)reps);
    state st[NV];
    sbl_temporal_desc td;
    sbl_stereo_desc sd;
    int k, e, i, f, r, eval = 0, rc = 0;
    if (!tscratch || !sscratch || !times) { fprintf(stderr, "out of memory\n"); exit(2); }
    memset(&td, 0, sizeof td);
    memset(&sd, 0, sizeof sd);
    sd.rig = SBL_RIG_PARALLEL;
    sd.focal_px = s->focal_px;
    sd.baseline = s->baseline;
    memset(st, 0, sizeof st);
    for (k = 0; k < NV; ++k)
        for (e = 0; e < 2; ++e) {
            for (i = 0; i < 2; ++i) {
                st[k].hist[e][i] = falloc(n * 3);
                st[k].len[e][i] = falloc(n);
                st[k].evid[e][i] = falloc(n);
            }
            st[k].disp[e] = falloc(n * 3);
            st[k].dlen[e] = falloc(n);
        }
    for (f = 0; f < s->frames && rc == 0; ++f) {
        for (k = 0; k < NV && rc == 0; ++k) {
            state *q = &st[k];
            sbl_eye eye[2];
            for (e = 0; e < 2 && rc == 0; ++e) { /* temporal filter per eye */
                const sbr_view *v = &s->views[f * 2 + e];
                const sbr_view *pv = f > 0 ? &s->views[(f - 1) * 2 + e] : NULL;
                const int p = q->ping[e];
                sbl_frame fr;
                sbl_history hi;
                sbl_temporal_output out;
                memset(&fr, 0, sizeof fr); memset(&hi, 0, sizeof hi); memset(&out, 0, sizeof out);
                fr.color = sbl_image_make(v->color, w, h, 3);
                fr.gbuffer = gbuffer_of(v, w, h, full, 1);
                fr.camera = &v->camera;
                if (pv) {
                    hi.color = sbl_image_make(q->hist[e][p], w, h, 3);
                    hi.length = sbl_image_make(q->len[e][p], w, h, 1);
                    hi.evidence = sbl_image_make(q->evid[e][p], w, h, 1);
                    hi.gbuffer = gbuffer_of(pv, w, h, full, 0);
                    hi.camera = &pv->camera;
                }
                out.color = sbl_image_make(q->hist[e][!p], w, h, 3);
                out.length = sbl_image_make(q->len[e][!p], w, h, 1);
                out.evidence = sbl_image_make(q->evid[e][!p], w, h, 1);
                for (r = 0; r < reps && rc == 0; ++r) { /* the same inputs: the same outputs */
                    const double t0 = cpu_ms();
                    SC_COUNT_START();
                    rc = variants[k].temporal(&td, &fr, pv ? &hi : NULL, &out, tscratch, tbytes);
                    SC_COUNT_STOP();
                    times[r] = cpu_ms() - t0;
                }
                q->t_ms += median(times, reps);
                q->ping[e] = !p;
            }
            for (e = 0; e < 2; ++e) { /* the stereo blend of the filtered eyes */
                memset(&eye[e], 0, sizeof eye[e]);
                eye[e].color = sbl_image_make(q->hist[e][q->ping[e]], w, h, 3);
                eye[e].length = sbl_image_make(q->len[e][q->ping[e]], w, h, 1);
                eye[e].gbuffer = gbuffer_of(&s->views[f * 2 + e], w, h, full, 0);
            }
            for (e = 0; e < 2 && rc == 0; ++e)
                for (r = 0; r < reps && rc == 0; ++r) {
                    const double t0 = cpu_ms();
                    SC_COUNT_START();
                    rc = variants[k].stereo(&sd, (sbl_eye_index)e, &eye[e], &eye[!e],
                                            sbl_image_make(q->disp[e], w, h, 3),
                                            sbl_image_make(q->dlen[e], w, h, 1), sscratch, sbytes);
                    SC_COUNT_STOP();
                    times[r] = cpu_ms() - t0;
                    if (r == reps - 1) q->s_ms += median(times, reps);
                }
        }
        if (rc) break;
        for (k = 1; k < NV; ++k)
            for (e = 0; e < 2; ++e) {
                const int p = st[0].ping[e];
                compare(st[k].hist[e][p], st[0].hist[e][p], n * 3, &st[k]);
                compare(st[k].len[e][p], st[0].len[e][p], n, &st[k]);
                compare(st[k].evid[e][p], st[0].evid[e][p], n, &st[k]);
                compare(st[k].disp[e], st[0].disp[e], n * 3, &st[k]);
                compare(st[k].dlen[e], st[0].dlen[e], n, &st[k]);
            }
        if (f >= skip && s->views[f * 2].ref) {
            for (k = 0; k < NV; ++k)
                for (e = 0; e < 2; ++e)
                    st[k].mse += sbl_metric_mse(st[k].disp[e], w * 3, s->views[f * 2 + e].ref, w * 3, w, h, 3);
            eval += 2;
        }
    }
    if (rc) {
        printf("%s: %s\n", s->name, sbl_result_string((sbl_result)rc));
    } else {
        printf("\n%s, %dx%d, %d frames, G-buffer %s\n", s->name, w, h, s->frames,
               full ? "full (depth, motion, normals, ids)" : "depth + motion");
        printf("| build | temporal ms | x every | stereo ms | x every | values differing | max diff | RMSE |\n");
        printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
        for (k = 0; k < NV; ++k) {
            const state *q = &st[k];
            printf("| %s | %.3f | %.3f | %.3f | %.3f | %ld | %.3g | %.5f |\n", variants[k].name,
                   q->t_ms / s->frames, q->t_ms / st[0].t_ms, q->s_ms / s->frames, q->s_ms / st[0].s_ms,
                   q->diff_count, q->max_diff, eval ? sqrt(q->mse / eval) : 0.0);
        }
        fflush(stdout);
    }
    for (k = 0; k < NV; ++k)
        for (e = 0; e < 2; ++e) {
            for (i = 0; i < 2; ++i) { free(st[k].hist[e][i]); free(st[k].len[e][i]); free(st[k].evid[e][i]); }
            free(st[k].disp[e]);
            free(st[k].dlen[e]);
        }
    free(tscratch); free(sscratch); free(times);
}

static int in_list(const char *list, const char *name)
{
    size_t len = strlen(name);
    const char *p = list;
    if (!list) return 1;
    while ((p = strstr(p, name)) != NULL) {
        if ((p == list || p[-1] == ',') && (p[len] == ',' || p[len] == 0)) return 1;
        p += len;
    }
    return 0;
}

int main(int argc, char **argv)
{
    int reps = 5, quick = 0, i, g, g0 = 0, g1 = 1;
    const char *data = "../shared/data", *only = NULL;
    char path[1024], err[512];
    static const struct { const char *name; sbl_scene_kind kind; int jitter; } synth[] = {
        {"synthetic-static", SBL_SCENE_STATIC, 0},
        {"synthetic-shadow", SBL_SCENE_SHADOW, 0},
        {"synthetic-dynamic", SBL_SCENE_DYNAMIC, 1},
        {"synthetic-pan", SBL_SCENE_PAN, 0},
    };
    static const char *const real[] = {"atrium", "gallery"};
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--quick") == 0) quick = 1;
        else if (strcmp(argv[i], "--data") == 0 && i + 1 < argc) data = argv[++i];
        else if (strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) only = argv[++i];
        else if (strcmp(argv[i], "--gbuffer") == 0 && i + 1 < argc) {
            ++i;
            if (strcmp(argv[i], "depth") == 0) g1 = 0;
            else if (strcmp(argv[i], "full") == 0) g0 = 1;
            else if (strcmp(argv[i], "both") != 0) { fprintf(stderr, "--gbuffer depth|full|both\n"); return 2; }
        } else {
            fprintf(stderr, "usage: shortcuts [--reps N] [--quick] [--data DIR] [--scenes S,T,..] "
                            "[--gbuffer depth|full|both]\n");
            return 2;
        }
    }
    if (reps < 1) reps = 1;
    printf("# adaptive shortcuts: thread CPU ms per stereo frame (median of %d call%s per frame),\n"
           "# each build against the one with every shortcut (bench/shortcuts.c)\n", reps, reps > 1 ? "s" : "");
    for (i = 0; i < 4; ++i) {
        sbl_scene_desc d;
        sbr_seq seq;
        if (!in_list(only, synth[i].name)) continue;
        d = sbr_bench_scene_desc(synth[i].kind, synth[i].jitter, quick);
        if (sbr_seq_synthetic(&seq, &d, synth[i].name, 0) != 0) { fprintf(stderr, "render failed\n"); return 1; }
        for (g = g0; g <= g1; ++g) bench_scene(&seq, g, reps);
        sbr_seq_free(&seq);
    }
    for (i = 0; i < 2; ++i) {
        sbr_seq seq;
        if (!in_list(only, real[i])) continue;
        if (!sbl_exr_available()) { printf("\n(%s skipped: built without OpenEXR)\n", real[i]); continue; }
        snprintf(path, sizeof path, "%s/%s", data, real[i]);
        if (sbr_seq_dataset(&seq, path, quick ? 8 : 0, err, sizeof err) != 0) {
            printf("\n(%s skipped: %s)\n", path, err);
            continue;
        }
        for (g = g0; g <= g1; ++g) bench_scene(&seq, g, reps);
        sbr_seq_free(&seq);
    }
    return 0;
}
