/* make bench / make bench-quick: error against time for every method of the standard
   table, on the synthetic scenes and on the rendered sequences in ../shared/data.
   Prints one table per scene, writes the rows to bench/out/bench.csv (quick.csv) with
   the header scene,method,ms,rmse,ssim,eff_spp,indep_spp,oracle_pct,traced_pct
   (oracle_pct: eff spp as a percentage of the oracle of the same pipeline), and plots ms against RMSE
   (bench/out/bench.svg, written here; plus bench.png through gnuplot when present).

   usage: bench [--quick] [--reps N] [--data DIR] [--out DIR] [--methods A,B,..]
                [--scenes S,T,..]   (the oracle rows always run) */
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
#include <stdio.h>
#include <sys/stat.h>

#define MAX_ROWS 512
typedef struct row { char scene[64]; char method[48]; sbr_result r; double oracle_pct; } row;
static row rows[MAX_ROWS];
static int row_count;
static const char *only_methods, *only_scenes; /* comma lists; NULL: all */

static int in_list(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p = list;
    if (!list) return 1;
    while (*p) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        if (len == n && strncmp(p, name, n) == 0) return 1;
        if (!e) break;
        p = e + 1;
    }
    return 0;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

/* The oracle a method is measured against: the oracle of the same pipeline (temporal
   only, stereo blend only, or temporal then stereo blend). */
static const char *oracle_of(const sbr_method *m)
{
    int blend = m->stereo == SBR_STEREO_FIXED || m->stereo == SBR_STEREO_ADAPTIVE;
    if (blend) return m->temporal ? "oracle+stereo-oracle" : "stereo-oracle";
    return "oracle";
}

static void bench_scene(const sbr_seq *seq, int reps)
{
    sbr_method m[SBR_MAX_METHODS];
    int n = sbr_standard_methods(m, SBR_MAX_METHODS), i, k, first_row = row_count, kept = 0;
    for (i = 0; i < n; ++i) /* the oracles always run: the other rows are measured against them */
        if (in_list(only_methods, m[i].name) || (m[i].oracle && !getenv("BENCH_SKIP_ORACLE"))) m[kept++] = m[i];
    n = kept;
    printf("\n## %s (%dx%d, %d frames, stereo; metrics over frames %d..%d, both eyes)\n\n",
           seq->name, seq->width, seq->height, seq->frames, seq->frames / 4, seq->frames - 1);
    for (i = 0; i < n && row_count < MAX_ROWS; ++i) {
        double ms[16];
        sbr_result r, first;
        for (k = 0; k < reps && k < 16; ++k) {
            if (sbr_run(seq, &m[i], &r, NULL, NULL) != 0) exit(1);
            if (k == 0) first = r;
            ms[k] = r.ms;
        }
        qsort(ms, (size_t)k, sizeof(double), cmp_double);
        first.ms = ms[k / 2];
        snprintf(rows[row_count].scene, sizeof rows[row_count].scene, "%s", seq->name);
        memcpy(rows[row_count].method, m[i].name, sizeof rows[row_count].method);
        rows[row_count++].r = first;
    }
    printf("| %-24s | %8s | %8s | %7s | %8s | %9s | %8s | %8s |\n", "method", "ms", "RMSE", "SSIM",
           "eff spp", "indep spp", "% oracle", "traced %");
    printf("|--------------------------|---------:|---------:|--------:|---------:|----------:|---------:|---------:|\n");
    for (i = first_row; i < row_count; ++i) {
        const sbr_result *r = &rows[i].r;
        const char *o = oracle_of(&m[i - first_row]);
        int j;
        rows[i].oracle_pct = 0.0;
        for (j = first_row; j < row_count; ++j)
            if (strcmp(rows[j].method, o) == 0 && rows[j].r.eff_spp > 0)
                rows[i].oracle_pct = 100.0 * r->eff_spp / rows[j].r.eff_spp;
        printf("| %-24s | %8.3f | %8.5f | %7.4f | %8.2f | %9.2f | %8.1f | %8.2f |\n", rows[i].method,
               r->ms, r->rmse, r->ssim, r->eff_spp, r->indep_spp, rows[i].oracle_pct, r->traced_pct);
    }
    fflush(stdout);
}

static void write_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    int i;
    if (!f) { perror(path); return; }
    fprintf(f, "scene,method,ms,rmse,ssim,eff_spp,indep_spp,oracle_pct,traced_pct\n");
    for (i = 0; i < row_count; ++i)
        fprintf(f, "%s,%s,%.4f,%.6f,%.5f,%.3f,%.3f,%.1f,%.3f\n", rows[i].scene, rows[i].method,
                rows[i].r.ms, rows[i].r.rmse, rows[i].r.ssim, rows[i].r.eff_spp, rows[i].r.indep_spp,
                rows[i].oracle_pct, rows[i].r.traced_pct);
    fclose(f);
    printf("\nwrote %s\n", path);
}

/* A scatter plot per scene (ms on x, RMSE on y), one SVG, no dependencies. */
static void write_svg(const char *path)
{
    FILE *f = fopen(path, "w");
    const char *scenes[16];
    int ns = 0, i, j, s;
    const int pw = 520, ph = 360, ml = 70, mb = 50, mt = 30, mr = 180;
    if (!f) { perror(path); return; }
    for (i = 0; i < row_count; ++i) {
        for (j = 0; j < ns; ++j) if (strcmp(scenes[j], rows[i].scene) == 0) break;
        if (j == ns && ns < 16) scenes[ns++] = rows[i].scene;
    }
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%d' height='%d' font-family='sans-serif' font-size='10'>\n",
            pw + mr, ph * ns);
    for (s = 0; s < ns; ++s) {
        double xmax = 0, ymax = 0;
        int oy = s * ph;
        for (i = 0; i < row_count; ++i)
            if (strcmp(rows[i].scene, scenes[s]) == 0) {
                if (rows[i].r.ms > xmax) xmax = rows[i].r.ms;
                if (rows[i].r.rmse > ymax) ymax = rows[i].r.rmse;
            }
        xmax = xmax > 0 ? xmax * 1.1 : 1;
        ymax = ymax > 0 ? ymax * 1.1 : 1;
        fprintf(f, "<text x='%d' y='%d' font-size='13'>%s: RMSE vs ms per stereo frame</text>\n", ml, oy + 18, scenes[s]);
        fprintf(f, "<rect x='%d' y='%d' width='%d' height='%d' fill='none' stroke='black'/>\n", ml, oy + mt,
                pw - ml, ph - mt - mb);
        fprintf(f, "<text x='%d' y='%d'>0</text><text x='%d' y='%d'>%.2f ms</text>\n", ml, oy + ph - mb + 14,
                pw - 40, oy + ph - mb + 14, xmax);
        fprintf(f, "<text x='5' y='%d'>%.4f</text><text x='5' y='%d'>0</text>\n", oy + mt + 10, ymax, oy + ph - mb);
        for (i = 0, j = 0; i < row_count; ++i) {
            double px, py;
            if (strcmp(rows[i].scene, scenes[s]) != 0) continue;
            px = ml + (pw - ml) * rows[i].r.ms / xmax;
            py = oy + ph - mb - (ph - mt - mb) * rows[i].r.rmse / ymax;
            fprintf(f, "<circle cx='%.1f' cy='%.1f' r='3' fill='hsl(%d,70%%,40%%)'/>\n", px, py, (j * 47) % 360);
            fprintf(f, "<text x='%.1f' y='%.1f' fill='hsl(%d,70%%,30%%)'>%s</text>\n", px + 5, py - 3, (j * 47) % 360,
                    rows[i].method);
            ++j;
        }
    }
    fprintf(f, "</svg>\n");
    fclose(f);
    printf("wrote %s\n", path);
}

static void gnuplot_png(const char *csv, const char *png)
{
    char cmd[4096];
    FILE *p;
    if (system("command -v gnuplot >/dev/null 2>&1") != 0) return;
    snprintf(cmd, sizeof cmd, "gnuplot");
    p = popen(cmd, "w");
    if (!p) return;
    fprintf(p, "set terminal png size 1000,700\nset output '%s'\nset datafile separator ','\n"
               "set xlabel 'ms per stereo frame'\nset ylabel 'RMSE'\nset key off\nset logscale x\n"
               "plot '%s' every ::1 using 3:4:2 with labels point pt 7 offset char 1,0.5 font ',7'\n",
            png, csv);
    if (pclose(p) == 0) printf("wrote %s (gnuplot)\n", png);
}

int main(int argc, char **argv)
{
    int quick = 0, reps = 3, i;
    const char *data = "../shared/data", *out = "bench/out";
    char path[1024], csv[1024], err[512];
    static const struct { const char *name; sbl_scene_kind kind; int jitter; } synth[] = {
        {"synthetic-dynamic", SBL_SCENE_DYNAMIC, 1},
        {"synthetic-static", SBL_SCENE_STATIC, 0},
        {"synthetic-shadow", SBL_SCENE_SHADOW, 0},
        {"synthetic-pan", SBL_SCENE_PAN, 0},
    };
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0) quick = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--data") == 0 && i + 1 < argc) data = argv[++i];
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--methods") == 0 && i + 1 < argc) only_methods = argv[++i];
        else if (strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) only_scenes = argv[++i];
        else {
            fprintf(stderr, "usage: bench [--quick] [--reps N] [--data DIR] [--out DIR] "
                            "[--methods A,B,..] [--scenes S,T,..]\n");
            return 2;
        }
    }
    if (quick) reps = 1;
    if (reps < 1) reps = 1;
    mkdir(out, 0777);
    printf("# stereoblend.h bench%s: ms = median library time per stereo frame (both eyes, %d run%s);\n"
           "# RMSE / SSIM (clamped to [0,1]) against the reference; eff spp = spp of a plain render\n"
           "# with equal RMSE (ladder, log-log); indep spp = mse(1 spp) / mse(result);\n"
           "# traced %% = right-eye pixels that still needed a ray.\n",
           quick ? " (quick)" : "", reps, reps > 1 ? "s, median" : "");
    for (i = 0; i < (quick ? 1 : 4); ++i) {
        sbl_scene_desc d;
        sbr_seq seq;
        if (!in_list(only_scenes, synth[i].name)) continue;
        memset(&d, 0, sizeof d);
        d.kind = synth[i].kind;
        d.jitter = synth[i].jitter;
        d.width = quick ? 96 : 160;
        d.height = quick ? 54 : 90;
        d.frames = quick ? 8 : 24;
        d.ref_spp = quick ? 32 : 128;
        d.seed = 7;
        if (sbr_seq_synthetic(&seq, &d, synth[i].name, 1) != 0) { fprintf(stderr, "render failed\n"); return 1; }
        bench_scene(&seq, reps);
        sbr_seq_free(&seq);
    }
    if (!sbl_exr_available()) {
        printf("\n(real renders skipped: built without OpenEXR; install libopenexr-dev)\n");
    } else {
        static const char *const scenes[] = {"atrium", "gallery"};
        for (i = 0; i < 2; ++i) {
            sbr_seq seq;
            if (!in_list(only_scenes, scenes[i])) continue;
            snprintf(path, sizeof path, "%s/%s", data, scenes[i]);
            if (sbr_seq_dataset(&seq, path, quick ? 8 : 0, err, sizeof err) != 0) {
                printf("\n(%s skipped: %s)\n", path, err);
                continue;
            }
            bench_scene(&seq, reps);
            sbr_seq_free(&seq);
        }
    }
    snprintf(csv, sizeof csv, "%s/%s.csv", out, quick ? "quick" : "bench");
    write_csv(csv);
    snprintf(path, sizeof path, "%s/%s.svg", out, quick ? "quick" : "bench");
    write_svg(path);
    if (!quick) {
        snprintf(path, sizeof path, "%s/bench.png", out);
        gnuplot_png(csv, path);
    }
    return 0;
}
