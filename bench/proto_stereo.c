/* Prototype / probe of the combined pipeline (scratch, issue 11, docs/ESTIMATORS.md 4.7):
   how much of each eye's temporal error the other eye shares. Runs a temporal method per
   eye (no stereo stage), reprojects the other eye's output into each eye with the
   library's stereo reprojection and reports, over valid matches and the evaluation
   frames, E_own = mean (t - ref)^2, E_oth = mean (x* - ref)^2, C = mean (t - ref)(x* - ref),
   rho = C / sqrt(E_own E_oth), C / E_own (the share of the own error that a stereo
   average keeps), and the MSE of a fixed beta 1/2 blend, (E_own + E_oth + 2 C) / 4.
   usage: proto_stereo [scenes] [methods]   (methods from the standard table, temporal;
   NAME@c sets sbl_temporal_desc.stereo_shared_bias = c (else the table's), NAME#n max_history = n; run:NAME runs the method as the
   bench does, stereo stage included, and prints effective spp / RMSE / SSIM) */
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

int main(int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : NULL;
    const char *mlist = argc > 2 ? argv[2] : "default,ema-0.2,progressive,paper";
    const sbr_synth_scene *const synth = sbr_synth_scenes;
    static const char *const real[] = {"atrium", "gallery"};
    char err[256], path[512], buf[512];
    int s;
    printf("%-18s %-14s %9s %9s %9s %6s %6s %9s %6s\n", "scene", "method", "E_own", "E_oth", "C",
           "rho", "C/Eown", "E_beta.5", "valid%");
    for (s = 0; s < SBR_SYNTH_SCENES + 2; ++s) {
        sbr_seq seq;
        const char *nm = s < SBR_SYNTH_SCENES ? synth[s].name : real[s - SBR_SYNTH_SCENES];
        char *tok;
        if (only && !strstr(only, nm)) continue;
        if (s < SBR_SYNTH_SCENES) {
            sbl_scene_desc d = sbr_bench_scene_desc(synth[s].kind, synth[s].jitter, 0);
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
            float c = 0.0f;
            snprintf(name, sizeof name, "%s", run ? tok + 4 : seeds ? tok + 6 : tok);
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
                d = sbr_bench_scene_desc(synth[s].kind, synth[s].jitter, 0);
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
