/* make bench / make bench-quick: error against time for every method of the standard
   table, on the synthetic scenes and on the rendered sequences in ../shared/data.
   Prints one table per scene, writes the rows to bench/out/bench.csv (quick.csv) with
   the header scene,method,ms,rmse,ssim,eff_spp,indep_spp,oracle_pct,traced_pct,rmse_dim,
   bright_mse_pct (oracle_pct: eff spp as a percentage of the oracle of the same pipeline;
   rmse_dim: RMSE over the pixels whose reference is not bright, i.e. at most 10 times the
   image's mean, and bright_mse_pct the bright pixels' share of the MSE:
   sbl_metric_bright_split in tools/sbl_metrics.h), and plots
   effective spp against ms per frame, one panel per scene (bench/out/bench.svg, written
   here; plus bench.png through gnuplot when present).

   usage: bench [--quick] [--reps N] [--data DIR] [--out DIR] [--methods A,B,..]
                [--scenes S,T,..]   (with the oracles the chosen methods are measured against)
          bench --plot CSV SVG     (redraw the plot from an earlier run's CSV) */
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
    /* the oracles the selected methods are measured against always run */
    for (i = 0; i < n; ++i) {
        int need = in_list(only_methods, m[i].name), j;
        for (j = 0; j < n && !need; ++j)
            need = in_list(only_methods, m[j].name) && strcmp(oracle_of(&m[j]), m[i].name) == 0;
        if (need) m[kept++] = m[i];
    }
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
    printf("| %-24s | %8s | %8s | %7s | %8s | %9s | %8s | %8s | %8s | %8s |\n", "method", "ms", "RMSE", "SSIM",
           "eff spp", "indep spp", "% oracle", "traced %", "RMSE dim", "bright %");
    printf("|--------------------------|---------:|---------:|--------:|---------:|----------:|---------:|---------:|---------:|---------:|\n");
    for (i = first_row; i < row_count; ++i) {
        const sbr_result *r = &rows[i].r;
        const char *o = oracle_of(&m[i - first_row]);
        int j;
        rows[i].oracle_pct = 0.0;
        for (j = first_row; j < row_count; ++j)
            if (strcmp(rows[j].method, o) == 0 && rows[j].r.eff_spp > 0)
                rows[i].oracle_pct = 100.0 * r->eff_spp / rows[j].r.eff_spp;
        printf("| %-24s | %8.3f | %8.5f | %7.4f | %8.2f | %9.2f | %8.1f | %8.2f | %8.5f | %8.1f |\n", rows[i].method,
               r->ms, r->rmse, r->ssim, r->eff_spp, r->indep_spp, rows[i].oracle_pct, r->traced_pct,
               r->rmse_dim, r->bright_mse_pct);
    }
    fflush(stdout);
}

static void write_csv(const char *path)
{
    FILE *f = fopen(path, "w");
    int i;
    if (!f) { perror(path); return; }
    fprintf(f, "scene,method,ms,rmse,ssim,eff_spp,indep_spp,oracle_pct,traced_pct,rmse_dim,bright_mse_pct\n");
    for (i = 0; i < row_count; ++i)
        fprintf(f, "%s,%s,%.4f,%.6f,%.5f,%.3f,%.3f,%.1f,%.3f,%.6f,%.2f\n", rows[i].scene, rows[i].method,
                rows[i].r.ms, rows[i].r.rmse, rows[i].r.ssim, rows[i].r.eff_spp, rows[i].r.indep_spp,
                rows[i].oracle_pct, rows[i].r.traced_pct, rows[i].r.rmse_dim, rows[i].r.bright_mse_pct);
    fclose(f);
    printf("\nwrote %s\n", path);
}

/* ---- the error-against-time plot (SVG, no dependencies) ----------------------------
   One panel per scene: effective spp (log axis) against ms per stereo frame, one marker
   shape and colour per method family (legend on top), ticks and gridlines, the Pareto
   front (the methods no other beats on both axes; oracles excluded, they need the
   reference) as a dashed line, and every method named in a label column beside the plot,
   in the order of its points' heights, joined to its point by a thin leader line: labels
   are spaced by construction, so they cannot overlap. */
enum { PLOT_FAMILIES = 9 };
static const char *const plot_family_name[PLOT_FAMILIES] = {
    "1 spp input", "constant / EMA", "progressive", "paper", "history-aware",
    "stereo only", "temporal + stereo", "oracle (uses the reference)", "other"};
static const char *const plot_family_colour[PLOT_FAMILIES] = { /* Okabe-Ito */
    "#000000", "#E69F00", "#56B4E9", "#D55E00", "#0072B2", "#CC79A7", "#009E73", "#888888", "#999933"};

static int starts_with(const char *s, const char *prefix) { return strncmp(s, prefix, strlen(prefix)) == 0; }

/* the family of a method, from its name in the standard table */
static int plot_family(const char *name)
{
    if (strstr(name, "oracle")) return 7;
    if (starts_with(name, "input")) return 0;
    if (strstr(name, "+stereo") || (starts_with(name, "default") && strstr(name, "stereo"))) return 6;
    if (starts_with(name, "stereo")) return 5;
    if (starts_with(name, "const") || starts_with(name, "ema")) return 1;
    if (starts_with(name, "progressive")) return 2;
    if (starts_with(name, "paper")) return 3;
    if (starts_with(name, "history-aware") || starts_with(name, "default") || starts_with(name, "ha")) return 4;
    return 8;
}

static void plot_marker(FILE *f, int family, double x, double y)
{
    const char *c = plot_family_colour[family];
    const double r = 4.5;
    switch (family) {
    case 0: fprintf(f, "<circle cx='%.1f' cy='%.1f' r='%.1f' fill='%s'/>\n", x, y, r, c); break;
    case 1: fprintf(f, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='%s'/>\n", x - r, y - r, 2 * r, 2 * r, c); break;
    case 2: fprintf(f, "<path d='M%.1f %.1fl%.1f %.1fh%.1fz' fill='%s'/>\n", x, y - r * 1.2, r * 1.1, r * 2, -r * 2.2, c); break;
    case 3: fprintf(f, "<path d='M%.1f %.1fl%.1f %.1fl%.1f %.1fl%.1f %.1fz' fill='%s'/>\n", x, y - r * 1.3, r * 1.1,
                    r * 1.3, -r * 1.1, r * 1.3, -r * 1.1, -r * 1.3, c); break;
    case 4: fprintf(f, "<path d='M%.1f %.1fl%.1f %.1fh%.1fz' fill='%s'/>\n", x, y + r * 1.2, r * 1.1, -r * 2, -r * 2.2, c); break;
    case 5: fprintf(f, "<path d='M%.1f %.1fh%.1fM%.1f %.1fv%.1f' stroke='%s' stroke-width='2.5'/>\n", x - r, y, 2 * r,
                    x, y - r, 2 * r, c); break;
    case 6: fprintf(f, "<circle cx='%.1f' cy='%.1f' r='%.1f' fill='white' stroke='%s' stroke-width='2.2'/>\n", x, y, r, c); break;
    case 7: fprintf(f, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='white' stroke='%s' stroke-width='2'/>\n",
                    x - r, y - r, 2 * r, 2 * r, c); break;
    default: fprintf(f, "<path d='M%.1f %.1fl%.1f %.1fM%.1f %.1fl%.1f %.1f' stroke='%s' stroke-width='2.5'/>\n", x - r,
                     y - r, 2 * r, 2 * r, x - r, y + r, 2 * r, -2 * r, c); break;
    }
}

/* a tick step of 1, 2 or 5 times a power of ten giving about `count` intervals */
static double plot_nice_step(double range, int count)
{
    double raw = range / count, p = pow(10.0, floor(log10(raw))), m = raw / p;
    return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

static void plot_escape(FILE *f, const char *s)
{
    for (; *s; ++s) {
        if (*s == '<') fputs("&lt;", f);
        else if (*s == '>') fputs("&gt;", f);
        else if (*s == '&') fputs("&amp;", f);
        else fputc(*s, f);
    }
}

typedef struct plot_point { int row; double x, y, label_y; } plot_point;

static int cmp_point_y(const void *a, const void *b)
{
    double u = ((const plot_point *)a)->y, v = ((const plot_point *)b)->y;
    return u < v ? -1 : (u > v ? 1 : 0);
}

static void plot_panel(FILE *f, const char *scene, double ox, double oy, double pw, double ph)
{
    const double ml = 58, mt = 26, mb = 40, label_w = 170;
    const double plot_w = pw - ml - label_w - 20, plot_h = ph - mt - mb;
    const double x0 = ox + ml, y0 = oy + mt; /* top left of the plot area */
    plot_point pts[MAX_ROWS];
    int n = 0, skipped = 0, i, j, front[MAX_ROWS], nf = 0;
    double xmax = 0, ylo = 1e300, yhi = 0, lylo, lyhi, step, t, spacing;
    for (i = 0; i < row_count; ++i) {
        if (strcmp(rows[i].scene, scene) != 0) continue;
        if (!(rows[i].r.eff_spp > 0) || !(rows[i].r.ms >= 0)) { ++skipped; continue; }
        pts[n].row = i;
        if (rows[i].r.ms > xmax) xmax = rows[i].r.ms;
        if (rows[i].r.eff_spp < ylo) ylo = rows[i].r.eff_spp;
        if (rows[i].r.eff_spp > yhi) yhi = rows[i].r.eff_spp;
        ++n;
    }
    fprintf(f, "<text x='%.1f' y='%.1f' font-size='14' font-weight='bold'>", x0, oy + 17);
    plot_escape(f, scene);
    fprintf(f, "</text>\n");
    if (n == 0) { fprintf(f, "<text x='%.1f' y='%.1f'>no rows with an effective spp</text>\n", x0, y0 + 20); return; }
    /* axes: x linear from 0, y log10 padded to whole 1-2-5 steps */
    step = plot_nice_step(xmax > 0 ? xmax : 1.0, 5);
    xmax = ceil((xmax > 0 ? xmax * 1.04 : 1.0) / step) * step;
    lylo = log10(ylo) - 0.05;
    lyhi = log10(yhi) + 0.05;
    if (lyhi - lylo < 0.5) { double c = 0.5 * (lylo + lyhi); lylo = c - 0.25; lyhi = c + 0.25; }
#define PX(v) (x0 + plot_w * (v) / xmax)
#define PY(v) (y0 + plot_h * (lyhi - log10(v)) / (lyhi - lylo))
    fprintf(f, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='#fbfbfb' stroke='none'/>\n", x0, y0, plot_w, plot_h);
    for (t = 0; t <= xmax * 1.0001; t += step) { /* x grid and ticks */
        fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#dddddd'/>\n", PX(t), y0, PX(t), y0 + plot_h);
        fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='black'/>\n", PX(t), y0 + plot_h, PX(t), y0 + plot_h + 4);
        fprintf(f, "<text x='%.1f' y='%.1f' text-anchor='middle'>%g</text>\n", PX(t), y0 + plot_h + 16, t);
    }
    {   /* y grid and ticks at 1, 2, 5 x 10^k (every integer too when the range is narrow) */
        int k, narrow = lyhi - lylo < 1.2;
        for (k = (int)floor(lylo); k <= (int)ceil(lyhi); ++k) {
            int m;
            for (m = 1; m < 10; ++m) {
                double v = m * pow(10.0, k), ly = log10(v);
                int major = m == 1 || m == 2 || m == 5;
                if (ly < lylo || ly > lyhi) continue;
                if (!major && !narrow) {
                    fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#eeeeee'/>\n", x0, PY(v), x0 + plot_w, PY(v));
                    continue;
                }
                fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#dddddd'/>\n", x0, PY(v), x0 + plot_w, PY(v));
                fprintf(f, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='black'/>\n", x0 - 4, PY(v), x0, PY(v));
                fprintf(f, "<text x='%.1f' y='%.1f' text-anchor='end'>%g</text>\n", x0 - 7, PY(v) + 4, v);
            }
        }
    }
    fprintf(f, "<rect x='%.1f' y='%.1f' width='%.1f' height='%.1f' fill='none' stroke='black'/>\n", x0, y0, plot_w, plot_h);
    fprintf(f, "<text x='%.1f' y='%.1f' text-anchor='middle'>ms per stereo frame (median)</text>\n", x0 + plot_w / 2,
            y0 + plot_h + 32);
    fprintf(f, "<text transform='translate(%.1f %.1f) rotate(-90)' text-anchor='middle'>effective spp (log)</text>\n",
            ox + 14, y0 + plot_h / 2);
    for (i = 0; i < n; ++i) {
        pts[i].x = PX(rows[pts[i].row].r.ms);
        pts[i].y = PY(rows[pts[i].row].r.eff_spp);
    }
    /* Pareto front: not oracle, and no other non-oracle row at most as slow and at least
       as good with one of the two strictly */
    for (i = 0; i < n; ++i) {
        const sbr_result *a = &rows[pts[i].row].r;
        int dominated = plot_family(rows[pts[i].row].method) == 7;
        for (j = 0; j < n && !dominated; ++j) {
            const sbr_result *b = &rows[pts[j].row].r;
            if (j == i || plot_family(rows[pts[j].row].method) == 7) continue;
            if (b->ms <= a->ms && b->eff_spp >= a->eff_spp && (b->ms < a->ms || b->eff_spp > a->eff_spp)) dominated = 1;
        }
        if (!dominated) front[nf++] = i;
    }
    for (i = 1; i < nf; ++i) /* by time */
        for (j = i; j > 0 && pts[front[j]].x < pts[front[j - 1]].x; --j) { int tmp = front[j]; front[j] = front[j - 1]; front[j - 1] = tmp; }
    if (nf > 1) {
        fprintf(f, "<polyline fill='none' stroke='#444444' stroke-width='1.5' stroke-dasharray='5 3' points='");
        for (i = 0; i < nf; ++i) fprintf(f, "%.1f,%.1f ", pts[front[i]].x, pts[front[i]].y);
        fprintf(f, "'/>\n");
    }
    /* label column: sorted by the points' heights, spaced at least `spacing` apart */
    qsort(pts, (size_t)n, sizeof pts[0], cmp_point_y);
    spacing = plot_h / n < 13.0 ? plot_h / n : 13.0;
    for (i = 0; i < n; ++i) {
        double want = pts[i].y, lo = y0 + 4 + i * spacing;
        pts[i].label_y = want < lo ? lo : want;
        if (i > 0 && pts[i].label_y < pts[i - 1].label_y + spacing) pts[i].label_y = pts[i - 1].label_y + spacing;
    }
    for (i = n - 1; i >= 0; --i) { /* push back up from the bottom edge */
        double hi = y0 + plot_h - 2 - (n - 1 - i) * spacing;
        if (pts[i].label_y > hi) pts[i].label_y = hi;
    }
    for (i = 0; i < n; ++i) {
        const row *r = &rows[pts[i].row];
        int fam = plot_family(r->method), on_front = 0;
        double lx = x0 + plot_w + 14;
        for (j = 0; j < nf; ++j) on_front |= pts[front[j]].row == pts[i].row;
        fprintf(f, "<polyline fill='none' stroke='%s' stroke-opacity='0.35' points='%.1f,%.1f %.1f,%.1f %.1f,%.1f'/>\n",
                plot_family_colour[fam], pts[i].x, pts[i].y, x0 + plot_w + 6, pts[i].label_y, lx - 2, pts[i].label_y);
        fprintf(f, "<text x='%.1f' y='%.1f' font-size='%.1f' fill='%s'%s>", lx, pts[i].label_y + 3.5,
                spacing < 11.0 ? spacing - 1.0 : 10.5, plot_family_colour[fam], on_front ? " font-weight='bold'" : "");
        plot_escape(f, r->method);
        fprintf(f, " (%.2f)</text>\n", r->r.eff_spp);
    }
    for (i = 0; i < n; ++i) plot_marker(f, plot_family(rows[pts[i].row].method), pts[i].x, pts[i].y);
    if (skipped)
        fprintf(f, "<text x='%.1f' y='%.1f' font-size='9' fill='#666666'>%d method%s without an effective spp not shown</text>\n",
                x0 + 4, y0 + 12, skipped, skipped > 1 ? "s" : "");
#undef PX
#undef PY
}

static void write_svg(const char *path)
{
    FILE *f = fopen(path, "w");
    const char *scenes[16];
    int ns = 0, i, j, s, used[PLOT_FAMILIES] = {0}, cols, nrows;
    const double pw = 660, ph = 400, legend_h = 58;
    double lx = 12, ly = 20;
    if (!f) { perror(path); return; }
    for (i = 0; i < row_count; ++i) {
        used[plot_family(rows[i].method)] = 1;
        for (j = 0; j < ns; ++j) if (strcmp(scenes[j], rows[i].scene) == 0) break;
        if (j == ns && ns < 16) scenes[ns++] = rows[i].scene;
    }
    cols = ns > 1 ? 2 : 1;
    nrows = (ns + cols - 1) / cols;
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='%.0f' height='%.0f' font-family='sans-serif' font-size='11'>\n"
               "<rect width='100%%' height='100%%' fill='white'/>\n", pw * cols, legend_h + ph * nrows);
    fprintf(f, "<text x='%.1f' y='%.1f' font-size='13'>Effective spp against time per stereo frame; dashed: the Pareto "
               "front (bold labels); label = method (effective spp)</text>\n", lx, ly);
    ly += 24;
    for (i = 0; i < PLOT_FAMILIES; ++i) {
        if (!used[i]) continue;
        if (lx + 14 + 7.0 * (double)strlen(plot_family_name[i]) > pw * cols) { lx = 12; ly += 18; }
        plot_marker(f, i, lx + 5, ly - 4);
        fprintf(f, "<text x='%.1f' y='%.1f' fill='%s'>%s</text>\n", lx + 14, ly, plot_family_colour[i], plot_family_name[i]);
        lx += 14 + 6.2 * (double)strlen(plot_family_name[i]) + 22;
    }
    for (s = 0; s < ns; ++s) plot_panel(f, scenes[s], (s % cols) * pw, legend_h + (s / cols) * ph, pw, ph);
    fprintf(f, "</svg>\n");
    fclose(f);
    printf("wrote %s\n", path);
}

/* --plot CSV: the rows of an earlier run (scene,method,ms,rmse,ssim,eff_spp,...), to
   redraw the plot without measuring again */
static int read_csv(const char *path)
{
    FILE *f = fopen(path, "r");
    char line[512];
    if (!f) { perror(path); return 1; }
    if (!fgets(line, sizeof line, f)) { fclose(f); return 1; } /* header */
    while (row_count < MAX_ROWS && fgets(line, sizeof line, f)) {
        row *r = &rows[row_count];
        memset(r, 0, sizeof *r);
        if (sscanf(line, "%63[^,],%47[^,],%lf,%lf,%lf,%lf", r->scene, r->method, &r->r.ms, &r->r.rmse,
                   &r->r.ssim, &r->r.eff_spp) == 6)
            ++row_count;
    }
    fclose(f);
    return 0;
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
    int quick = 0, reps = 3, data_given = 0, i;
    const char *data = "../shared/data", *out = "bench/out";
    char path[1024], csv[1024], err[512];
    const sbr_synth_scene *const synth = sbr_synth_scenes;
    for (i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0) quick = 1;
        else if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc) reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--data") == 0 && i + 1 < argc) { data = argv[++i]; data_given = 1; }
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) out = argv[++i];
        else if (strcmp(argv[i], "--methods") == 0 && i + 1 < argc) only_methods = argv[++i];
        else if (strcmp(argv[i], "--scenes") == 0 && i + 1 < argc) only_scenes = argv[++i];
        else if (strcmp(argv[i], "--plot") == 0 && i + 2 < argc) { /* --plot CSV SVG: redraw only */
            if (read_csv(argv[i + 1]) != 0) return 1;
            write_svg(argv[i + 2]);
            return 0;
        }
        else {
            fprintf(stderr, "usage: bench [--quick] [--reps N] [--data DIR] [--out DIR] "
                            "[--methods A,B,..] [--scenes S,T,..]\n");
            return 2;
        }
    }
    if (data_given && !sbl_exr_available()) {
        /* asked for the real renders explicitly: a table without them would pass for one
           with them (measurements were lost that way), so refuse before the long run */
        fprintf(stderr, "bench: --data given but this build has no OpenEXR (built with "
                        "-DSBL_NO_EXR); install libopenexr-dev and pkg-config, then rebuild\n");
        return 2;
    }
    if (quick) reps = 1;
    if (reps < 1) reps = 1;
    mkdir(out, 0777);
    printf("# stereoblend.h bench%s: ms = median library time per stereo frame (both eyes, %d run%s);\n"
           "# RMSE / SSIM (clamped to [0,1]) against the reference; eff spp = spp of a plain render\n"
           "# with equal RMSE (ladder, log-log); indep spp = mse(1 spp) / mse(result);\n"
           "# traced %% = right-eye pixels that still needed a ray.\n",
           quick ? " (quick)" : "", reps, reps > 1 ? "s, median" : "");
    for (i = 0; i < (quick ? 1 : SBR_SYNTH_SCENES); ++i) {
        sbl_scene_desc d;
        sbr_seq seq;
        if (!in_list(only_scenes, synth[i].name)) continue;
        d = sbr_synth_desc(&synth[i], quick);
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
