/* Prototype / probe of the combined pipeline (scratch, issue 11, docs/ESTIMATORS.md 4.7):
   how much of each eye's temporal error the other eye shares. Runs a temporal method per
   eye (no stereo stage), reprojects the other eye's output into each eye with the
   library's stereo reprojection and reports, over valid matches and the evaluation
   frames, E_own = mean (t - ref)^2, E_oth = mean (x* - ref)^2, C = mean (t - ref)(x* - ref),
   rho = C / sqrt(E_own E_oth), C / E_own (the share of the own error that a stereo
   average keeps), and the MSE of a fixed beta 1/2 blend, (E_own + E_oth + 2 C) / 4.
   usage: proto_stereo [scenes] [methods]   (methods from the standard table, temporal;
   NAME@c sets sbl_temporal_desc.stereo_shared_bias = c (else the table's), NAME#n max_history = n; run:NAME runs the method as the
   bench does, stereo stage included, and prints effective spp / RMSE / SSIM; dump:NAME writes the
   combined pipeline per pixel to $DUMP_DIR/SCENE_NAME.dump and `proto_stereo cmp:A,B` bins two
   dumps (docs/ESTIMATORS.md 4.9)) */
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

typedef struct probe {
    const sbr_seq *s;
    float *t[2], *xs, *valid;
    double e_own, e_oth, c, n;          /* sums over valid matches */
    double e_all;                       /* own error over all pixels */
    double n_all;
} probe;

static void probe_frame(void *ctx, int f, int eye, const float *rgb, int w, int h)
{
    probe *p = (probe *)ctx;
    const sbr_seq *s = p->s;
    size_t n = (size_t)w * (size_t)h, q;
    int e, c;
    memcpy(p->t[eye], rgb, n * 3 * sizeof(float));
    if (eye != 1 || f < s->frames / 4) return;
    for (e = 0; e < 2; ++e) {
        const sbr_view *v = &s->views[f * 2 + e], *o = &s->views[f * 2 + !e];
        sbl_stereo_desc sd;
        sbl_eye te, se;
        memset(&sd, 0, sizeof sd);
        sd.rig = SBL_RIG_PARALLEL; sd.focal_px = s->focal_px; sd.baseline = s->baseline;
        memset(&te, 0, sizeof te); memset(&se, 0, sizeof se);
        te.color = sbl_image_make(p->t[e], w, h, 3);
        te.gbuffer = sbr_gbuffer(v, w, h, 0);
        se.color = sbl_image_make(p->t[!e], w, h, 3);
        se.gbuffer = sbr_gbuffer(o, w, h, 0);
        if (sbl_reproject_stereo(&sd, (sbl_eye_index)e, &te, &se, sbl_image_make(p->xs, w, h, 3),
                                 sbl_image_make(p->valid, w, h, 1), 0, h) != SBL_OK) {
            fprintf(stderr, "reproject failed\n");
            exit(1);
        }
        for (q = 0; q < n; ++q) {
            for (c = 0; c < 3; ++c) {
                double a = (double)p->t[e][q * 3 + c] - v->ref[q * 3 + c];
                p->e_all += a * a;
            }
            p->n_all += 3;
            if (!(p->valid[q] > 0)) continue;
            for (c = 0; c < 3; ++c) {
                double a = (double)p->t[e][q * 3 + c] - v->ref[q * 3 + c];
                double b = (double)p->xs[q * 3 + c] - v->ref[q * 3 + c];
                p->e_own += a * a; p->e_oth += b * b; p->c += a * b;
            }
            p->n += 3;
        }
    }
}

/* seeds:NAME (synthetic scenes): the bias of each eye and its correlation between the
   eyes, free of noise: the method runs on the scene rendered with two noise seeds (the
   references too), and the products of the two runs' errors keep only what does not
   depend on the noise: E[e_A e_B] = E[b^2] per eye, E[e_A(own) e_B(other eye
   reprojected)] = E[b b'] (docs/ESTIMATORS.md 4.8). */
typedef struct seedprobe {
    const sbr_seq *s, *sa;
    int pass;
    float **keep;                       /* pass 0: [f * 2 + e] temporal outputs */
    float *t[2], *xa, *xb, *valid;
    double bo, bxx, bx, ea, eb, ca, n;
} seedprobe;

static void seed_frame(void *ctx, int f, int eye, const float *rgb, int w, int h)
{
    seedprobe *p = (seedprobe *)ctx;
    const sbr_seq *s = p->s;
    size_t n = (size_t)w * (size_t)h, q;
    int e, c;
    if (f < s->frames / 4) return;
    if (p->pass == 0) {
        p->keep[f * 2 + eye] = sbr_alloc(n * 3);
        memcpy(p->keep[f * 2 + eye], rgb, n * 3 * sizeof(float));
        return;
    }
    memcpy(p->t[eye], rgb, n * 3 * sizeof(float));
    if (eye != 1) return;
    for (e = 0; e < 2; ++e) {
        const sbr_view *v = &s->views[f * 2 + e], *o = &s->views[f * 2 + !e];
        const float *ta = p->keep[f * 2 + e];
        sbl_stereo_desc sd;
        sbl_eye te, se;
        int k;
        memset(&sd, 0, sizeof sd);
        sd.rig = SBL_RIG_PARALLEL; sd.focal_px = s->focal_px; sd.baseline = s->baseline;
        for (k = 0; k < 2; ++k) {
            memset(&te, 0, sizeof te); memset(&se, 0, sizeof se);
            te.color = sbl_image_make(k ? (float *)ta : p->t[e], w, h, 3);
            te.gbuffer = sbr_gbuffer(v, w, h, 0);
            se.color = sbl_image_make(k ? p->keep[f * 2 + !e] : p->t[!e], w, h, 3);
            se.gbuffer = sbr_gbuffer(o, w, h, 0);
            if (sbl_reproject_stereo(&sd, (sbl_eye_index)e, &te, &se,
                                     sbl_image_make(k ? p->xa : p->xb, w, h, 3),
                                     sbl_image_make(p->valid, w, h, 1), 0, h) != SBL_OK) {
                fprintf(stderr, "reproject failed\n");
                exit(1);
            }
            if (k == 0) memcpy(p->valid + n, p->valid, n * sizeof(float));
        }
        for (q = 0; q < n; ++q) {
            if (!(p->valid[q] > 0) || !(p->valid[n + q] > 0)) continue;
            for (c = 0; c < 3; ++c) {
                /* A: the stored run with its own references (refA), B: this run */
                const size_t i = q * 3 + c;
                const double eA = (double)ta[i] - p->sa->views[f * 2 + e].ref[i];
                const double eB = (double)p->t[e][i] - v->ref[i];
                const double xA = (double)p->xa[i] - p->sa->views[f * 2 + e].ref[i];
                const double xB = (double)p->xb[i] - v->ref[i];
                p->bo += eA * eB; p->bxx += xA * xB; p->bx += 0.5 * (eA * xB + eB * xA);
                p->ea += eA * eA; p->eb += eB * eB; p->ca += eA * xA;
            }
            p->n += 3;
        }
    }
}


/* dump:NAME FILE (docs/ESTIMATORS.md 4.9): the combined pipeline as sbr_run runs it for a
   method with the library's temporal filter, the evidence plane and the adaptive stereo
   blend, written per pixel (evaluation frames, both eyes) to FILE as DUMP_F floats: the
   display's, the temporal output's and the other eye's (reprojected) squared errors,
   their cross product, the match's validity, N, the temporal weight, the region's M
   (sbl__evidence_share's formula on the eye's previous evidence plane), this frame's R,
   the stereo weight of the own eye, and the other eye's N reprojected. cmp:A,B bins two
   dumps of the same scene pixel by pixel. */
/* session 17: + the reference's, the display's, the input's and the 3x3 median reference's
   channel sums (is a pixel-frame's error the reference's firefly or the output's?) */
enum { D_ED, D_ET, D_EX, D_CX, D_VAL, D_N, D_A, D_M, D_R, D_B, D_NX, D_REF, D_DISP, D_IN, D_REFMED, DUMP_F };

static int dump_run(const sbr_seq *s, const sbr_method *m, const char *file)
{
    const int w = s->width, h = s->height;
    const size_t n = (size_t)w * (size_t)h;
    float *hist[2][2], *len[2][2], *ev[2][2], *al[2], *disp[2], *beta[2], *xs, *xn, *valid, *rec;
    int ping[2] = {0, 0}, f, e, i, skip = s->frames / 4;
    double mse = 0;
    long evn = 0;
    FILE *fo = fopen(file, "wb");
    sbl_stereo_desc sd = m->stereo_desc;
    if (!fo) return 1;
    sd.rig = SBL_RIG_PARALLEL; sd.focal_px = s->focal_px; sd.baseline = s->baseline;
    for (e = 0; e < 2; ++e) {
        for (i = 0; i < 2; ++i) { hist[e][i] = sbr_alloc(n * 3); len[e][i] = sbr_alloc(n); ev[e][i] = sbr_alloc(n); }
        al[e] = sbr_alloc(n); disp[e] = sbr_alloc(n * 3); beta[e] = sbr_alloc(n);
    }
    xs = sbr_alloc(n * 3); xn = sbr_alloc(n * 3); valid = sbr_alloc(n); rec = sbr_alloc(n * DUMP_F);
    for (f = 0; f < s->frames; ++f) {
        sbl_eye eye[2];
        float mrow[1024];
        for (e = 0; e < 2; ++e) {
            const sbr_view *v = &s->views[f * 2 + e], *pv = f > 0 ? &s->views[(f - 1) * 2 + e] : NULL;
            sbl_frame fr;
            sbl_history hi;
            sbl_temporal_output out;
            sbr_temporal_bind(v, pv, v->color, w, h, hist[e][ping[e]], len[e][ping[e]], ev[e][ping[e]],
                              hist[e][!ping[e]], len[e][!ping[e]], ev[e][!ping[e]], &fr, &hi, &out);
            out.alpha = sbl_image_make(al[e], w, h, 1);
            if (sbl_temporal_filter_frame(&m->temporal_desc, &fr, pv ? &hi : NULL, &out) != SBL_OK) return 1;
            ping[e] = !ping[e];
        }
        for (e = 0; e < 2; ++e) {
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = sbl_image_make(hist[e][ping[e]], w, h, 3);
            eye[e].length = sbl_image_make(len[e][ping[e]], w, h, 1);
            eye[e].gbuffer = sbr_gbuffer(&s->views[f * 2 + e], w, h, 0);
        }
        for (e = 0; e < 2; ++e) {
            sbl_stereo_output so;
            size_t bytes = sbl_stereo_scratch_size(w, 3);
            void *scr = malloc(bytes);
            memset(&so, 0, sizeof so);
            so.color = sbl_image_make(disp[e], w, h, 3);
            so.beta = sbl_image_make(beta[e], w, h, 1);
            if (m->stereo == SBR_STEREO_FIXED) sd.estimator = SBL_ESTIMATOR_CONSTANT;
            if (sbl_stereo_filter(&sd, (sbl_eye_index)e, &eye[e], &eye[!e], &so, 0, h, scr, bytes) != SBL_OK) return 1;
            free(scr);
        }
        if (f < skip) continue;
        for (e = 0; e < 2; ++e) {
            const sbr_view *v = &s->views[f * 2 + e];
            const float *t = hist[e][ping[e]], *prev = f > 0 ? ev[e][!ping[e]] : NULL;
            const float thr = (float)SBL__EVIDENCE_THR, cap = (float)SBL__POOL_RATIO_CAP;
            sbl_eye xe = eye[!e];
            size_t q;
            int y, x, c;
            /* the other eye's N, reprojected with the same call (N copied to 3 channels) */
            if (sbl_reproject_stereo(&sd, (sbl_eye_index)e, &eye[e], &eye[!e], sbl_image_make(xs, w, h, 3),
                                     sbl_image_make(valid, w, h, 1), 0, h) != SBL_OK) return 1;
            for (q = 0; q < n; ++q) xn[q * 3] = xn[q * 3 + 1] = xn[q * 3 + 2] = len[!e][ping[!e]][q];
            xe.color = sbl_image_make(xn, w, h, 3);
            {
                float *tmpv = sbr_alloc(n), *xnr = sbr_alloc(n * 3);
                if (sbl_reproject_stereo(&sd, (sbl_eye_index)e, &eye[e], &xe, sbl_image_make(xnr, w, h, 3),
                                         sbl_image_make(tmpv, w, h, 1), 0, h) != SBL_OK) return 1;
                for (q = 0; q < n; ++q) rec[q * DUMP_F + D_NX] = xnr[q * 3];
                free(tmpv); free(xnr);
            }
            for (y = 0; y < h && y < 1024; ++y) {
                long cnt = 0, nn = 0;
                int j;
                mrow[y] = 1.0f;
                if (!prev) continue;
                for (j = y - 1; j <= y + 1; ++j) {
                    if (j < 0 || j >= h) continue;
                    for (x = 0; x < w; ++x) cnt += (prev[(size_t)j * w + x] > thr) & (prev[(size_t)j * w + x] <= cap);
                    nn += w;
                }
                mrow[y] = (float)((double)(nn + 2) / (2.0 * (double)(cnt + 1)));
            }
            for (q = 0; q < n; ++q) {
                float *r = rec + q * DUMP_F;
                double ed = 0, et = 0, ex = 0, cx = 0;
                for (c = 0; c < 3; ++c) {
                    const double rf = v->ref[q * 3 + c];
                    const double a = disp[e][q * 3 + c] - rf, b = t[q * 3 + c] - rf, d = xs[q * 3 + c] - rf;
                    ed += a * a; et += b * b;
                    if (valid[q] > 0) { ex += d * d; cx += b * d; }
                }
                mse += ed; evn += 3;
                r[D_ED] = (float)ed; r[D_ET] = (float)et; r[D_EX] = (float)ex; r[D_CX] = (float)cx;
                r[D_VAL] = valid[q] > 0; r[D_N] = len[e][ping[e]][q]; r[D_A] = al[e][q];
                r[D_M] = mrow[q / (size_t)w]; r[D_R] = ev[e][ping[e]][q]; r[D_B] = beta[e][q];
                r[D_REF] = v->ref[q * 3] + v->ref[q * 3 + 1] + v->ref[q * 3 + 2];
                r[D_DISP] = disp[e][q * 3] + disp[e][q * 3 + 1] + disp[e][q * 3 + 2];
                r[D_IN] = v->color[q * 3] + v->color[q * 3 + 1] + v->color[q * 3 + 2];
                {
                    float nb[9], t9;
                    int cnt = 0, px = (int)(q % (size_t)w), py = (int)(q / (size_t)w), dx, dy, i2, j2;
                    for (dy = -1; dy <= 1; ++dy)
                        for (dx = -1; dx <= 1; ++dx) {
                            const int xx = px + dx, yy = py + dy;
                            const size_t qq = (size_t)yy * w + (size_t)xx;
                            if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                            nb[cnt++] = v->ref[qq * 3] + v->ref[qq * 3 + 1] + v->ref[qq * 3 + 2];
                        }
                    for (i2 = 1; i2 < cnt; ++i2) /* insertion sort of <= 9 */
                        for (j2 = i2; j2 > 0 && nb[j2 - 1] > nb[j2]; --j2) { t9 = nb[j2]; nb[j2] = nb[j2 - 1]; nb[j2 - 1] = t9; }
                    r[D_REFMED] = nb[cnt / 2];
                }
            }
            fwrite(rec, sizeof(float), n * DUMP_F, fo);
        }
    }
    fclose(fo);
    printf("%-18s dump %-20s rmse %.5f (%s)\n", s->name, m->name, sqrt(mse / (double)evn), file);
    for (e = 0; e < 2; ++e) {
        for (i = 0; i < 2; ++i) { free(hist[e][i]); free(len[e][i]); free(ev[e][i]); }
        free(al[e]); free(disp[e]); free(beta[e]);
    }
    free(xs); free(xn); free(valid); free(rec);
    return 0;
}

/* cmp:A,B: A and B dumps of one scene (the same pixels in the same order). Bins by B's
   M and N and by the change of N, and prints each bin's share of the pixels, A's and B's
   display / temporal MSE, the eyes' shared error C / E_own, the stereo weight and N. */
static int cmp_float(const void *a, const void *b)
{
    const float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void cmp_bins(const char *fa, const char *fb)
{
    FILE *pa = fopen(fa, "rb"), *pb = fopen(fb, "rb");
    float ra[DUMP_F], rb[DUMP_F];
    enum { NB = 6, NK = 8 };
    static const char *kname[NK] = {"M (B)", "N (B)", "N B/A", "beta(B)", "beta(A)", "N/Nx(A)",
                                    "errq", "errq*N"};
    /* errq (session 17, 4.14): the quantile of the pixel-frame's own display error (the
       mean of A's and B's, so neither side selects its own noise): 50 / 90 / 99 / 99.9 /
       99.99 %, thresholds from a first pass; errq*N: the same quantiles within B's N 8-16 */
    static double edge[NK][NB - 1] = {{0.9, 2, 5, 15, 40}, {2, 8, 16, 32, 60},
                                      {0.8, 0.95, 1.05, 1.25, 2}, {0.05, 0.3, 0.45, 0.55, 0.95},
                                      {0.05, 0.3, 0.45, 0.55, 0.95}, {0.25, 0.67, 0.9, 1.1, 1.5},
                                      {0, 0, 0, 0, 0}, {0, 0, 0, 0, 0}};
    static const double qs[NB - 1] = {0.5, 0.9, 0.99, 0.999, 0.9999};
    double acc[NK][NB][12];
    double tot = 0, tda = 0, tdb = 0;
    int k, b;
    if (!pa || !pb) { printf("cmp: cannot open\n"); return; }
    memset(acc, 0, sizeof acc);
    {
        size_t cap = 1 << 20, nq = 0, nq8 = 0;
        float *q = (float *)malloc(cap * sizeof(float)), *q8 = (float *)malloc(cap * sizeof(float));
        while (fread(ra, sizeof ra, 1, pa) == 1 && fread(rb, sizeof rb, 1, pb) == 1) {
            if (nq == cap) {
                cap *= 2;
                q = (float *)realloc(q, cap * sizeof(float));
                q8 = (float *)realloc(q8, cap * sizeof(float));
            }
            q[nq++] = 0.5f * (ra[D_ED] + rb[D_ED]);
            if (rb[D_N] >= 8 && rb[D_N] < 16) q8[nq8++] = 0.5f * (ra[D_ED] + rb[D_ED]);
        }
        qsort(q, nq, sizeof(float), cmp_float);
        qsort(q8, nq8, sizeof(float), cmp_float);
        for (b = 0; b < NB - 1; ++b) {
            edge[6][b] = nq ? q[(size_t)(qs[b] * (double)(nq - 1))] : 0;
            edge[7][b] = nq8 ? q8[(size_t)(qs[b] * (double)(nq8 - 1))] : 0;
        }
        printf("errq thresholds (display squared error, mean of A and B):");
        for (b = 0; b < NB - 1; ++b) printf(" %.3g%%:%.4g", 100 * qs[b], edge[6][b]);
        printf("\n");
        free(q); free(q8);
        rewind(pa); rewind(pb);
    }
    while (fread(ra, sizeof ra, 1, pa) == 1 && fread(rb, sizeof rb, 1, pb) == 1) {
        double key[NK];
        key[0] = rb[D_M]; key[1] = rb[D_N]; key[2] = ra[D_N] > 0 ? rb[D_N] / ra[D_N] : 1; key[3] = rb[D_B];
        key[4] = ra[D_B]; key[5] = ra[D_NX] > 0 ? ra[D_N] / ra[D_NX] : 1;
        key[6] = 0.5 * (ra[D_ED] + rb[D_ED]);
        key[7] = rb[D_N] >= 8 && rb[D_N] < 16 ? key[6] : -1; /* -1: not binned */
        tot += 1; tda += ra[D_ED]; tdb += rb[D_ED];
        for (k = 0; k < NK; ++k) {
            double *z;
            if (key[k] < 0) continue; /* errq*N: outside N 8-16 */
            for (b = 0; b < NB - 1 && key[k] >= edge[k][b]; ++b) {}
            z = acc[k][b];
            z[0] += 1; z[1] += ra[D_ED]; z[2] += rb[D_ED]; z[3] += ra[D_ET]; z[4] += rb[D_ET];
            z[5] += ra[D_CX]; z[6] += rb[D_CX]; z[7] += ra[D_VAL] > 0 ? ra[D_ET] : 0; z[8] += rb[D_VAL] > 0 ? rb[D_ET] : 0;
            z[9] += ra[D_B]; z[10] += rb[D_B]; z[11] += rb[D_N] - ra[D_N];
        }
    }
    printf("cmp %s -> %s: display MSE %.4g -> %.4g (%+.2f %%)\n", fa, fb, tda / tot / 3, tdb / tot / 3,
           100 * (tdb / tda - 1));
    for (k = 0; k < NK; ++k) {
        printf("  by %-7s  %5s %10s %10s %8s %10s %10s %6s %6s %6s %6s %7s\n", kname[k], "pix%", "dispA",
               "dispB", "dDisp%", "tempA", "tempB", "C/E A", "C/E B", "betaA", "betaB", "dN");
        for (b = 0; b < NB; ++b) {
            double *z = acc[k][b];
            if (z[0] == 0) continue;
            printf("  %-3s %6.2f  %5.1f %10.4g %10.4g %8.2f %10.4g %10.4g %6.3f %6.3f %6.3f %6.3f %7.2f\n",
                   b == 0 ? "<" : ">=", b == 0 ? edge[k][0] : edge[k][b - 1], 100 * z[0] / tot,
                   z[1] / z[0] / 3, z[2] / z[0] / 3, 100 * (z[2] - z[1]) / tda, z[3] / z[0] / 3, z[4] / z[0] / 3,
                   z[7] > 0 ? z[5] / z[7] : 0, z[8] > 0 ? z[6] / z[8] : 0, z[9] / z[0], z[10] / z[0], z[11] / z[0]);
        }
    }
    /* the pixel-frames above the 99.99 % quantile, one line each (session 17) */
    rewind(pa); rewind(pb);
    {
        long rec = 0, shown = 0;
        printf("  top pixel-frames (> %.4g): rec N(A) N(B) betaB ref refmed3x3 in dispA dispB edA edB\n", edge[6][NB - 2]);
        while (fread(ra, sizeof ra, 1, pa) == 1 && fread(rb, sizeof rb, 1, pb) == 1) {
            if (0.5 * (ra[D_ED] + rb[D_ED]) >= edge[6][NB - 2] && shown < 400) {
                printf("  top %ld %.1f %.1f %.2f %.4g %.4g %.4g %.4g %.4g %.4g %.4g\n", rec, ra[D_N], rb[D_N], rb[D_B],
                       rb[D_REF], rb[D_REFMED], rb[D_IN], ra[D_DISP], rb[D_DISP], ra[D_ED], rb[D_ED]);
                ++shown;
            }
            ++rec;
        }
    }
    fclose(pa); fclose(pb);
}

int main(int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : NULL;
    const char *mlist = argc > 2 ? argv[2] : "default,ema-0.2,progressive,paper";
    const sbr_synth_scene *const synth = sbr_synth_scenes;
    static const char *const real[] = {"atrium", "gallery"};
    char err[256], path[512], buf[512];
    int s;
    if (argc > 1 && !strncmp(argv[1], "cmp:", 4)) {
        char a[512], *b;
        snprintf(a, sizeof a, "%s", argv[1] + 4);
        b = strchr(a, ',');
        if (!b) return 2;
        *b++ = 0;
        cmp_bins(a, b);
        return 0;
    }
    printf("%-18s %-14s %9s %9s %9s %6s %6s %9s %6s\n", "scene", "method", "E_own", "E_oth", "C",
           "rho", "C/Eown", "E_beta.5", "valid%");
    for (s = 0; s < SBR_SYNTH_SCENES + 2; ++s) {
        sbr_seq seq;
        const char *nm = s < SBR_SYNTH_SCENES ? synth[s].name : real[s - SBR_SYNTH_SCENES];
        char *tok;
        if (only && !strstr(only, nm)) continue;
        if (s < SBR_SYNTH_SCENES) {
            sbl_scene_desc d = sbr_synth_desc(&synth[s], 0);
            if (sbr_seq_synthetic(&seq, &d, nm, 1) != 0) return 1;
        } else {
            snprintf(path, sizeof path, "../shared/data/%s", nm);
            if (sbr_seq_dataset(&seq, path, 0, err, sizeof err) != 0) { printf("%s\n", err); continue; }
        }
        snprintf(buf, sizeof buf, "%s", mlist);
        for (tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
            sbr_method m;
            sbr_result r;
            probe p;
            size_t n = (size_t)seq.width * (size_t)seq.height;
            char name[64], *at, *hc, *sl;
            int so = 0;
            float cap = 0.0f;
            int run = strncmp(tok, "run:", 4) == 0, seeds = strncmp(tok, "seeds:", 6) == 0;
            int dump = strncmp(tok, "dump:", 5) == 0;
            float c = 0.0f;
            snprintf(name, sizeof name, "%s", run ? tok + 4 : seeds ? tok + 6 : dump ? tok + 5 : tok);
            /* NAME/paper, NAME/beta, NAME/oracle, NAME/pooled: the stereo stage replaced */
            sl = strchr(name, '/');
            if (sl) {
                *sl = 0;
                so = !strcmp(sl + 1, "paper") ? 1 : !strcmp(sl + 1, "beta") ? 2 : !strcmp(sl + 1, "oracle") ? 3 : 4;
            }
            hc = strchr(name, '#');
            if (hc) { cap = (float)atof(hc + 1); *hc = 0; }
            at = strchr(name, '@');
            if (at) { c = (float)atof(at + 1); *at = 0; }
            if (sbr_find_method(name, &m) != 0) { fprintf(stderr, "no method %s\n", name); return 2; }
            if (at) m.temporal_desc.stereo_shared_bias = c;
            if (cap > 0) m.temporal_desc.max_history = cap;
            if (so == 1) { m.stereo = SBR_STEREO_ADAPTIVE; m.stereo_desc.estimator = SBL_ESTIMATOR_PAPER; }
            if (so == 2) { m.stereo = SBR_STEREO_FIXED; m.stereo_desc.estimator = SBL_ESTIMATOR_CONSTANT; }
            if (so == 3) { m.stereo = SBR_STEREO_ADAPTIVE; m.oracle |= SBR_ORACLE_STEREO; }
            if (so == 4) { m.stereo = SBR_STEREO_ADAPTIVE; memset(&m.stereo_desc, 0, sizeof m.stereo_desc); }
            if (dump) {
                char file[600];
                snprintf(file, sizeof file, "%s/%s_%s.dump", getenv("DUMP_DIR") ? getenv("DUMP_DIR") : "/tmp", nm, name);
                if (dump_run(&seq, &m, file) != 0) return 1;
                fflush(stdout);
                continue;
            }
            if (run) {
                if (sbr_run(&seq, &m, &r, NULL, NULL) != 0) return 1;
                printf("%-18s %-24s eff %6.3f  rmse %.5f  ssim %.4f\n", nm, tok, r.eff_spp, r.rmse, r.ssim);
                fflush(stdout);
                continue;
            }
            m.stereo = SBR_STEREO_NONE;
            if (seeds) {
                sbr_seq sb;
                seedprobe sp;
                sbl_scene_desc d;
                int i;
                if (s >= SBR_SYNTH_SCENES) { printf("%s: seeds needs a synthetic scene\n", nm); continue; }
                d = sbr_synth_desc(&synth[s], 0);
                d.seed = d.seed + 1000;
                if (sbr_seq_synthetic(&sb, &d, nm, 0) != 0) return 1;
                memset(&sp, 0, sizeof sp);
                sp.s = &seq; sp.sa = &seq;
                sp.keep = (float **)calloc((size_t)seq.frames * 2, sizeof(float *));
                if (sbr_run(&seq, &m, &r, seed_frame, &sp) != 0) return 1;
                sp.pass = 1; sp.s = &sb;
                sp.t[0] = sbr_alloc(n * 3); sp.t[1] = sbr_alloc(n * 3);
                sp.xa = sbr_alloc(n * 3); sp.xb = sbr_alloc(n * 3); sp.valid = sbr_alloc(2 * n);
                if (sbr_run(&sb, &m, &r, seed_frame, &sp) != 0) return 1;
                printf("%-18s %-24s E_own %9.3g  bias^2 own %9.3g  other %9.3g  cross %9.3g  c %6.3f  bias share %5.3f  same-seed C/E %5.3f\n",
                       nm, tok, sp.ea / sp.n, sp.bo / sp.n, sp.bxx / sp.n, sp.bx / sp.n,
                       sp.bx / sqrt(sp.bo * sp.bxx), sp.bo / sp.ea, sp.ca / sp.ea);
                fflush(stdout);
                for (i = 0; i < seq.frames * 2; ++i) free(sp.keep[i]);
                free(sp.keep); free(sp.t[0]); free(sp.t[1]); free(sp.xa); free(sp.xb); free(sp.valid);
                sbr_seq_free(&sb);
                continue;
            }
            memset(&p, 0, sizeof p);
            p.s = &seq;
            p.t[0] = sbr_alloc(n * 3); p.t[1] = sbr_alloc(n * 3);
            p.xs = sbr_alloc(n * 3); p.valid = sbr_alloc(n);
            if (sbr_run(&seq, &m, &r, probe_frame, &p) != 0) return 1;
            {
                double eo = p.e_own / p.n, et = p.e_oth / p.n, c = p.c / p.n;
                printf("%-18s %-14s %9.3g %9.3g %9.3g %6.3f %6.3f %9.3g %6.1f  (eff %.2f)\n", nm, tok,
                       eo, et, c, c / sqrt(eo * et), c / eo, 0.25 * (eo + et + 2 * c),
                       100.0 * p.n / p.n_all, r.eff_spp);
            }
            fflush(stdout);
            free(p.t[0]); free(p.t[1]); free(p.xs); free(p.valid);
        }
        sbr_seq_free(&seq);
    }
    return 0;
}
