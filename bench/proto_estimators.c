/* Prototype of temporal estimators (scratch, issue 11): the library's reprojection, then
   a candidate blend written here in double over the whole image, measured with the
   bench's runner on every scene. usage: proto_estimators [scenes] */
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

typedef struct cand {
    const char *name;
    int radius;      /* wide window: 3 rows x (2 radius + 1) columns; 0: none */
    int soft;        /* 0: hard t-test at k; 1: Student-t posterior with the history prior */
    double k, kw;    /* thresholds, 3x3 and wide */
    int firefly;     /* firefly limit of the blended sample */
    int wide_prior;  /* prior odds on the wide test too */
    int combine;     /* 0 max of bias^2; 1 bias from wide only */
    int soft_w;      /* wide test: 0 hard (pd^2 - kw^2 se^2), 1 soft */
    double c_eb;     /* >0: also the empirical-Bayes bias from 5 blocks, c = c_eb */
    int normalized;  /* blocks' bias-to-noise ratio pooled instead of their energy */
    /* evidence over frames (ESTIMATORS 3.7): Z = EWMA of the signed, standardised mean
       paired difference of the pixel's 3x3 window, carried with the history */
    double lambda;   /* > 0: carry Z with this weight of the new z */
    double kt;       /* threshold of Z in its own H0 standard deviations */
    int carry_mode;  /* 1: r = max(r_blocks, Z^2 - kt^2 kappa) into the EB posterior;
                        2: bias^2 >= (Z^2 - kt^2 kappa) se^2 directly; 3: both */
    double zmax;     /* |z| of one frame clamped to this */
    /* trend (ESTIMATORS 3.8): a carried per-channel drift s = EWMA (weight tlam) of the
       3x3 mean paired difference x* - y (firefly-limited y), shrunk by its ratio
       u = |s|^2 / (kappa se^2) as s (1 - tc / u)+, subtracted from x* before the blend */
    double tlam, tc;
    int tmode;       /* bit 1: no R (one-frame pooled); bit 2: shrink by R's r too */
    /* risk-based mixing (ESTIMATORS 3.9): a = a_d + t (a_p - a_d), a_d the default's weight,
       a_p the paper's (scalar), t from the SURE risk pooled over a (2 srx + 1) x (2 sry + 1)
       box. sure: 1 t* clipped to [0, 1]; 2 hard choice (t* >= 1/2); 3 a_p alone (check) */
    int sure, srx, sry;
    int svar;        /* S_i: 0 the default's var_Y (paired split); 1 the paper's s^2 9/8 */
    double sk;       /* > 0: t* shrunk by its significance, (1 - sk / z^2)+ */
    int gate;        /* 1: t only where the default's shrink sh = r / (1 + r) > 0; 2: t <= sh;
                        3: t <= box mean of sh */
    int loo;         /* 1: a_p from the 8 neighbours (m8, v8): independent of y_i, so the
                        risk estimate needs no divergence term for it */
    int svgf;        /* 1: var_Y from temporal moments (carried per-channel variance V,
                        ESTIMATORS 3.9 b) */
    double nu;       /* degrees of freedom of the local test with it (0: 8) */
    int keepn;       /* 1: the mixed weight keeps the default's N (diagnostic: is the static
                        loss the N bookkeeping of the following frames?) */
    /* session 11 (ESTIMATORS 3.10) */
    int off;         /* switch a source of bias evidence off: 1 the local 3x3 test, 2 the
                        one-frame blocks, 4 the carried R (still carried) */
    int diag;        /* 1: decompose the weight's excess over 1/(N+1) by its source */
    /* 3.10 (c): a prior probability of change from the share s of a region's pixels whose
       carried evidence R* (last frame's R, reprojected) passes c_R: s = (k + 1) / (n + 2)
       over the region; region 1: the pixel's row, 2: the whole frame, 3: a 3-row window
       of +-rwin columns. The prior odds against change are multiplied by M = 1 / (2 s)
       (1 at s = 1/2, the rule of succession's prior mean) in the sources of rsrc:
       1 the local test (Beta(2 s, 2 (1 - s)) prior: odds (N + 2) / (2 s) - 1, over the
       same at s = 1/2), 2 the blocks (c + ln M: exponential tail of a unit-spread ratio),
       4 the carried R (c_R - 1 -> sqrt((c_R - 1)^2 + 2 kappa ln M), Gaussian) */
    int region, rsrc, rwin;
    double mmin;     /* M floored at this (0: none) */
    /* session 14 (ESTIMATORS 4.10): the combined pipeline and the resampling blur */
    int stereo;      /* 1: the library's default stereo blend follows (combined pipeline) */
    double cshare;   /* sbl_temporal_desc.stereo_shared_bias: bias^2 counted 1 + c times */
    int blur;        /* the blur's bias B_b^2 from the carried blur variance (S_x, S_y) and
                        the Laplacian of x*: 1 b2 = max(b2, B_b^2), 2 b2 + B_b^2; +4 B_b^2
                        less its noise (Laplacian of independent history noise); +8 the
                        region's M taken to 1 on the local test where S > 0 (4.9's rule);
                        +16 carry S but leave the weight alone (diagnostic); +32 B_b^2
                        counted once (not 1 + c times); +128 the second differences
                        averaged over the 3x3 (a third of the noise); +256 less the noise
                        of the second differences of the history's noise as blurred by its
                        fetches (blur_g), not of independent noise; +64 S from N and this fetch alone,
                        (N + 1) v / 2 (the blur of a history grown from a restart at this
                        fraction every frame), no carried plane */
    double bmax;     /* > 0: the blur's predicted |b| per channel at most bmax times the
                        3x3 range of x* (the Taylor form overshoots when S is large) */
    /* session 16 (3.12): the variance split of pv with the noise level's change: under a
       noise whose spread scales with the signal (a path's relative variance fixed), the
       history's N samples were taken at the brightness of x*, the new one at the window's
       mean m, so var_X = var_Y rho / N, rho = |x*|^2 / |m|^2 (channel sums; |m|^2 less the
       variance of the mean). 1: rho both ways; 2: rho >= 1 only (the history noisier) */
    int vsplit;
} cand;

static double *g_share; /* per pixel: the region's share s */

/* session 14 (ESTIMATORS 3.12): per-pixel state of the candidate, for diag: mode */
typedef struct diagpx {
    float nx, a_d, a, ap, shr, b3, rb, rt, M, R, se2, vy, vx, pd2, b2;
} diagpx;
static diagpx *g_dx;
static double *g_dshare; /* blend_sure: the region's share kept past blend_core (sure 9) */
static double *g_dlocp; /* blend_sure: the local test's posterior per pixel (sure 8) */
static double share_stats[4];

/* 3.10 (a): per source (0 local, 1 blocks, 2 carried R): pixel-frames whose weight exceeds
   1/(N+1) by more than 10 %, sum (a - a0), sum (a - a0)^2 (1 + 1/N), sum of the N lost
   (N + 1 - N_out); [3][0] pixel-frames with a history; plus a histogram of a / a0 */
static double dg[4][4];
static double dg_hist[8];

static double post_t(double pd2, double se2, double k, double nu, double odds)
{
    double t2 = se2 > 0 ? pd2 / se2 : (pd2 > 0 ? HUGE_VAL : 0);
    double rho = (1 + k * k / nu) / (1 + t2 / nu);
    return 1.0 / (1.0 + odds * pow(rho, 0.5 * (nu + 1)));
}

static double g_rb, g_rt; /* 3.10 (a): this pixel's one-frame block ratio and carried one */
/* 4.10: per pixel, the blur variance S_x, S_y of x* (carried plus this fetch's) and the
   predicted blur bias per channel; the final weight out (for the carry) */
static double *g_bsx, *g_bsy, *g_bb, *g_afin;
static double *g_bgx, *g_bgy; /* per pixel: the noise factor of each axis' second difference */
static double blur_stats[6]; /* pixel-frames, sum S, sum B_b^2 / (var_x + var_y), B_b^2 > b2, S > 0, sum a */
static double vs_stats[3]; /* 3.12: pixel-frames, sum rho, sum ln rho */
static double zsum_stats[4]; /* diagnostics: sum Z, sum Z^2, count, count over threshold */
/* risk-based mixing (ESTIMATORS 3.9): blend_core leaves its weight, the firefly-limited
   sample and its var_Y estimate here when these are set */
static double *g_ad, *g_vy, *g_sh, g_shv, *g_shr, g_shrv;
static const double *g_vt; /* SVGF prototype: temporal var_Y + var_X (3x3 mean), 0 = none */
static float *g_yb;

static void blend_core(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                       const float *zs, float cap, float *out, float *nout, float *zout)
{
    const cand *c = (const cand *)ctx;
    int px, py, i, j, ch;
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * w + px;
            double m[3] = {0}, v[3] = {0}, m8[3] = {0}, v8[3] = {0}, pd[3] = {0}, pv[3] = {0};
            double pdw[3] = {0}, pvw[3] = {0};
            double n_x = nx[p], n_y = 1.0, yb[3], a, var_x, var_y, b2 = 0, pd2 = 0, pvs = 0, s2 = 0;
            double dx_b3 = 0, dx_M = 1, dx_se2 = 0;
            int n = 0, np = 0, nw = 0;
            if (g_dx) memset(&g_dx[p], 0, sizeof g_dx[p]);
            if (!(n_x > 0)) {
                for (ch = 0; ch < 3; ++ch) out[p * 3 + ch] = y[p * 3 + ch];
                nout[p] = 1.0f;
                if (zout) zout[p] = 0.0f;
                if (g_ad) {
                    g_ad[p] = 1.0; g_vy[p] = 0.0; g_sh[p] = 1.0;
                    if (g_shr) g_shr[p] = 1.0;
                    for (ch = 0; ch < 3; ++ch) g_yb[p * 3 + ch] = y[p * 3 + ch];
                }
                continue;
            }
            if (n_x > cap) n_x = cap;
            g_shv = 0; g_shrv = 0; g_rb = 0; g_rt = 0;
            /* 3x3 */
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    ++n;
                    for (ch = 0; ch < 3; ++ch) m[ch] += y[q * 3 + ch];
                    if (nx[q] > 0) {
                        ++np;
                        for (ch = 0; ch < 3; ++ch) pd[ch] += (double)xs[q * 3 + ch] - y[q * 3 + ch];
                    }
                }
            for (ch = 0; ch < 3; ++ch) {
                m[ch] /= n;
                m8[ch] = (m[ch] * n - y[p * 3 + ch]) / (n - 1);
                pd[ch] = np ? pd[ch] / np : 0;
            }
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    for (ch = 0; ch < 3; ++ch) {
                        double e = y[q * 3 + ch] - m[ch], e8 = y[q * 3 + ch] - m8[ch];
                        v[ch] += e * e;
                        if (q != p) v8[ch] += e8 * e8;
                        if (nx[q] > 0) {
                            double d = (double)xs[q * 3 + ch] - y[q * 3 + ch] - pd[ch];
                            pv[ch] += d * d;
                        }
                    }
                }
            for (ch = 0; ch < 3; ++ch) {
                v[ch] /= n;
                v8[ch] /= (n - 1);
                pv[ch] = np > 1 ? pv[ch] / (np - 1) : 0;
                pd2 += pd[ch] * pd[ch];
                pvs += pv[ch];
                s2 += v[ch];
            }
            /* wide */
            if (c->radius > 0) {
                for (j = py - 1; j <= py + 1; ++j)
                    for (i = px - c->radius; i <= px + c->radius; ++i) {
                        size_t q;
                        if (i < 0 || j < 0 || i >= w || j >= h) continue;
                        q = (size_t)j * w + i;
                        if (!(nx[q] > 0)) continue;
                        ++nw;
                        for (ch = 0; ch < 3; ++ch) {
                            double d = (double)xs[q * 3 + ch] - y[q * 3 + ch];
                            pdw[ch] += d;
                            pvw[ch] += d * d;
                        }
                    }
            }
            /* firefly limit */
            for (ch = 0; ch < 3; ++ch) yb[ch] = y[p * 3 + ch];
            if (c->firefly) {
                double sy = 0, sm = 0, sx = 0, sv = 0, bound;
                for (ch = 0; ch < 3; ++ch) {
                    sy += y[p * 3 + ch]; sm += m8[ch]; sx += xs[p * 3 + ch]; sv += v8[ch];
                }
                bound = (sm > sx ? sm : sx) + 6.0 * sqrt(sv);
                if (bound < 0) bound = 0;
                if (sy > bound) for (ch = 0; ch < 3; ++ch) yb[ch] *= bound / sy;
            }
            double se2_loc = -1;
            if (g_vt && g_vt[p] > 0 && np > 1) {
                if (c->svgf == 3) se2_loc = (g_vt[p] > pvs ? g_vt[p] : pvs) / np;
                else if (c->svgf != 4) pvs = g_vt[p];
            }
            if (np > 1) {
                double rho = 1.0;
                if (c->vsplit == 1 || c->vsplit == 2) {
                    double Lx = 0, Lm = 0, sd = 0, mu2;
                    for (ch = 0; ch < 3; ++ch) { Lx += xs[p * 3 + ch]; Lm += m[ch]; sd += sqrt(v[ch]); }
                    mu2 = Lm * Lm - sd * sd / (n - 1);
                    if (Lx > 0 && mu2 > 0) rho = Lx * Lx / mu2;
                    else if (Lx > 0) rho = 1e6;
                    if (c->vsplit == 2 && rho < 1) rho = 1;
                    vs_stats[0] += 1; vs_stats[1] += rho; vs_stats[2] += log(rho);
                }
                var_y = pvs * n_x / (n_x + rho * n_y);
                var_x = pvs - var_y;
            } else {
                var_y = n > 1 ? s2 * n / (n - 1) : 0;
                var_x = var_y * n_y / n_x;
            }
            {
                double odds = 0.5 * (n_x + 1), se2 = np > 1 ? pvs / np : var_x + var_y;
                double Mreg = 1.0;
                if (c->region && g_share) {
                    double sr = g_share[p];
                    Mreg = 1.0 / (2.0 * sr);
                    if (c->mmin > 0 && Mreg < c->mmin) Mreg = c->mmin;
                    if ((c->blur & 8) && g_bsx && g_bsx[p] + g_bsy[p] > 0) Mreg = 1.0;
                    if (c->rsrc & 1) {
                        double s_eff = 1.0 / (2.0 * Mreg);
                        odds = 0.5 * ((n_x + 2) / (2 * s_eff) - 1);
                    }
                }
                double b3 = 0, bw = 0;
                if (np > 0) {
                    if (c->soft) b3 = post_t(pd2, se2_loc > 0 ? se2_loc : se2, c->k, g_vt && g_vt[p] > 0 && c->nu > 0 ? c->nu : 8, odds) * pd2;
                    else b3 = pd2 - c->k * c->k * se2 > 0 ? pd2 - c->k * c->k * se2 : 0;
                }
                if (c->off & 1) b3 = 0;
                dx_b3 = b3; dx_M = Mreg; dx_se2 = se2;
                if (g_dlocp) g_dlocp[p] = pd2 > 0 ? b3 / pd2 : 0.0;
                if (nw > 2) {
                    double pdw2 = 0, pvws = 0, sew2;
                    for (ch = 0; ch < 3; ++ch) {
                        double mu = pdw[ch] / nw;
                        double vv = (pvw[ch] - nw * mu * mu) / (nw - 1);
                        pdw2 += mu * mu;
                        pvws += vv > 0 ? vv : 0;
                    }
                    sew2 = pvws / nw;
                    if (c->soft_w) bw = post_t(pdw2, sew2, c->kw, nw - 1, c->wide_prior ? odds : 1.0) * pdw2;
                    else bw = pdw2 - c->kw * c->kw * sew2 > 0 ? pdw2 - c->kw * c->kw * sew2 : 0;
                }
                double r_t = 0, zc = 0, kap = 0;
                if (zout && (c->carry_mode & 4)) {
                    zc = zs[p]; /* the blocks' ratio, carried: updated below */
                } else if (zout) {
                    /* this frame's z: the channel-summed mean paired difference over
                       sqrt(3 se^2) (3 se^2 >= var of the sum, Cauchy-Schwarz) */
                    double pds = pd[0] + pd[1] + pd[2], den = 3.0 * pvs / (np > 0 ? np : 1), z = 0;
                    if (np > 1) {
                        z = den > 0 ? pds / sqrt(den) : (pds > 0 ? c->zmax : (pds < 0 ? -c->zmax : 0));
                        if (z > c->zmax) z = c->zmax;
                        if (z < -c->zmax) z = -c->zmax;
                        zc = (1 - c->lambda) * zs[p] + c->lambda * z;
                    } else {
                        zc = zs[p];
                    }
                    zout[p] = (float)zc;
                    kap = c->lambda / (2 - c->lambda);
                    r_t = zc * zc - c->kt * c->kt * kap;
                    if (r_t < 0) r_t = 0;
                    zsum_stats[0] += zc; zsum_stats[1] += zc * zc; zsum_stats[2] += 1;
                    if (r_t > 0) zsum_stats[3] += 1;
                }
                if (zout && (c->carry_mode & 4) && !(np > 1)) zout[p] = (float)zc;
                if (c->combine == 2 || c->c_eb > 0) {
                    double cc = c->c_eb > 0 ? c->c_eb : c->kw; double bmean = c->combine == 2 ? 0 : bw;
                    double ckt = c->kt;
                    if (c->region && (c->rsrc & 2)) cc += log(Mreg);
                    if (c->region && (c->rsrc & 4)) {
                        double kp = c->lambda / (2 - c->lambda), v = (c->kt - 1) * (c->kt - 1) + 2 * kp * log(Mreg);
                        ckt = 1 + sqrt(v > 0 ? v : 0);
                    }
                    /* empirical Bayes: prior variance of the bias from 5 3x3 blocks at
                       columns px + 3b, b = -2..2 */
                    double zsb = 0, sse = 0; int nb = 0, b;
                    for (b = -2; b <= 2; ++b) {
                        double s1[3] = {0}, s2c[3] = {0}; int cnt = 0, cx = px + 3 * b;
                        for (j = py - 1; j <= py + 1; ++j)
                            for (i = cx - 1; i <= cx + 1; ++i) {
                                size_t q;
                                if (i < 0 || j < 0 || i >= w || j >= h) continue;
                                q = (size_t)j * w + i;
                                if (!(nx[q] > 0)) continue;
                                ++cnt;
                                for (ch = 0; ch < 3; ++ch) {
                                    double d = (double)xs[q * 3 + ch] - y[q * 3 + ch];
                                    s1[ch] += d; s2c[ch] += d * d;
                                }
                            }
                        if (cnt > 2) {
                            double z = 0, m2 = 0, se = 0;
                            for (ch = 0; ch < 3; ++ch) {
                                double mu = s1[ch] / cnt, vv = (s2c[ch] - cnt * mu * mu) / (cnt - 1);
                                z += mu * mu - cc * (vv > 0 ? vv : 0) / cnt;
                                m2 += mu * mu; se += (vv > 0 ? vv : 0) / cnt;
                            }
                            if (c->normalized == 1) z = se > 0 ? m2 / se - cc : (m2 > 0 ? 1e6 : -cc);
                            if (c->normalized == 2) { z = m2; sse += se; }
                            zsb += z; ++nb;
                        }
                    }
                    if (nb > 0 && np > 1) {
                        double tau2 = zsb / nb, sh;
                        if (c->normalized == 2) tau2 = sse > 0 ? zsb / sse - cc : (zsb > 0 ? 1e6 : 0);
                        /* 64: the one-frame ratio through the same garrote,
                           (q - 1)(1 - ((c - 1) / (q - 1))^2)+ instead of q - c */
                        if ((c->carry_mode & 64) && c->normalized == 2 && tau2 > 0) {
                            double q1 = tau2 + cc - 1.0;
                            tau2 = q1 - (cc - 1.0) * (cc - 1.0) / q1;
                        }
                        if (tau2 < 0) tau2 = 0;
                        if (zout && (c->carry_mode & 4)) {
                            double q = sse > 0 ? zsb / sse : (zsb > 0 ? 1e6 : 0);
                            if (q > 1e6) q = 1e6;
                            zc = (1 - c->lambda) * (zs[p] > 0 ? zs[p] : 1.0) + c->lambda * q;
                            zout[p] = (float)zc;
                            r_t = zc - ckt;
                            if (r_t < 0) r_t = 0;
                            /* 8: a gate, then the unbiased estimate R - 1 */
                            if ((c->carry_mode & 8) && r_t > 0) r_t = zc - 1.0;
                            /* 32: non-negative garrote, (R - 1)(1 - ((c - 1) / (R - 1))^2)+:
                               0 up to c_R as the soft threshold, continuous, -> R - 1 */
                            if ((c->carry_mode & 32) && r_t > 0)
                                r_t = (zc - 1.0) - (ckt - 1.0) * (ckt - 1.0) / (zc - 1.0);
                            /* 16: soft gate, (R - 1) P, P = 1 / (1 + ((c - 1) / (R - 1))^4.5) */
                            if (c->carry_mode & 16) {
                                r_t = 0;
                                if (zc > 1.0) {
                                    double rho = (c->kt - 1.0) / (zc - 1.0);
                                    r_t = (zc - 1.0) / (1.0 + pow(rho, 4.5));
                                }
                            }
                            zsum_stats[0] += zc; zsum_stats[1] += zc * zc; zsum_stats[2] += 1;
                            if (r_t > 0) zsum_stats[3] += 1;
                        }
                        if (c->off & 2) tau2 = 0;
                        if (c->off & 4) r_t = 0;
                        g_rb = tau2; g_rt = r_t;
                        if ((c->carry_mode & 5) && r_t > tau2) tau2 = r_t;
                        g_shrv = r_t > 0 ? r_t / (1.0 + r_t) : 0.0;
                        if (c->normalized) tau2 *= se2;
                        sh = tau2 / (tau2 + se2);
                        g_shv = sh;
                        bw = sh * sh * pd2 + sh * se2;
                    }
                    if (bmean > bw) bw = bmean;
                }
                b2 = c->combine == 1 && nw > 2 ? bw : (b3 > bw ? b3 : bw);
                if ((c->carry_mode & 2) && np > 1 && r_t * se2 > b2) b2 = r_t * se2;
            }
            {
                double bb = 0;
                if (g_bb && c->blur && !(c->blur & 16)) {
                    const double sx = g_bsx[p], sy = g_bsy[p];
                    for (ch = 0; ch < 3; ++ch) bb += g_bb[p * 3 + ch] * g_bb[p * 3 + ch];
                    /* the second differences of independent history noise (var_x / channel
                       summed): each has variance 6 var_X, b = (S_x L_x + S_y L_y) / 2 */
                    if (c->blur & 256) bb -= 0.25 * (sx * sx * g_bgx[p] + sy * sy * g_bgy[p]) * var_x;
                    else if (c->blur & 4) bb -= ((c->blur & 128) ? 0.5 : 1.5) * (sx * sx + sy * sy) * var_x;
                    if (bb < 0) bb = 0;
                    blur_stats[2] += var_x + var_y > 0 ? bb / (var_x + var_y) : 0;
                    if (bb > b2) blur_stats[3] += 1;
                }
                if (c->cshare > 0) b2 *= 1.0 + c->cshare;
                if (bb > 0) {
                    double bbc = (c->blur & 32) ? bb : bb * (1.0 + c->cshare);
                    if ((c->blur & 3) == 2) b2 += bbc;
                    else if (bbc > b2) b2 = bbc;
                }
            }
            if (c->svgf == 4 && g_vt && g_vt[p] > var_x && np > 1) {
                /* 3.12: the split of pv by the history's own noise, var_X = V / (N - 1)
                   carried (3x3 mean), where it exceeds the stationary var_Y / N: the
                   history holds samples taken at another noise level (a pixel that went
                   dark); the sum pv, the tests and the bias unchanged */
                var_x = g_vt[p] < pvs ? g_vt[p] : pvs;
                var_y = pvs - var_x;
                vs_stats[0] += 1;
            }
            if ((c->vsplit == 5 || c->vsplit == 6) && np > 1 && g_rt > 0) {
                /* 5: the raw rho (the 3x3 mean of y, >= 1) only where the carried R has passed
                   c_R; 6: rho moved towards 1 by R's own shrink, 1 + sh_R (rho - 1) */
                double Lx = 0, Lm = 0, sd = 0, mu2, rho = 1.0;
                for (ch = 0; ch < 3; ++ch) { Lx += xs[p * 3 + ch]; Lm += m[ch]; sd += sqrt(v[ch]); }
                mu2 = Lm * Lm - sd * sd / (n - 1);
                if (Lx > 0 && mu2 > 0) rho = Lx * Lx / mu2;
                else if (Lx > 0) rho = 1e6;
                if (rho < 1) rho = 1;
                if (c->vsplit == 6) rho = 1 + g_rt / (1 + g_rt) * (rho - 1);
                vs_stats[0] += 1; vs_stats[1] += rho; vs_stats[2] += log(rho);
                var_y = pvs * n_x / (n_x + rho * n_y);
                var_x = pvs - var_y;
            }
            if ((c->vsplit == 3 || c->vsplit == 4) && np > 1) {
                /* 3 / 4: the new samples' brightness from the history's less the posterior
                   mean of the bias, f pd (f the larger shrink of the local test and the
                   pooled evidence): rho = 1 exactly wherever no change is seen (static) */
                double Lx = 0, pdl = 0, f = g_shv, fl = pd2 > 0 ? dx_b3 / pd2 : 0, Ly, rho = 1.0;
                if (fl > f) f = fl;
                for (ch = 0; ch < 3; ++ch) { Lx += xs[p * 3 + ch]; pdl += pd[ch]; }
                Ly = Lx - f * pdl;
                if (f > 0 && Lx > 0) rho = Ly > 0 ? (Lx * Lx) / (Ly * Ly) : 1e6;
                if (rho > 1e6) rho = 1e6;
                if (c->vsplit == 4 && rho < 1) rho = 1;
                vs_stats[0] += 1; vs_stats[1] += rho; vs_stats[2] += log(rho);
                var_y = pvs * n_x / (n_x + rho * n_y);
                var_x = pvs - var_y;
            }
            a = (b2 + var_x + var_y > 0) ? (b2 + var_x) / (b2 + var_x + var_y) : n_y / (n_x + n_y);
            if (a < 0) a = 0;
            if (a > 1) a = 1;
            if (g_ad) {
                g_ad[p] = a; g_vy[p] = var_y; g_sh[p] = g_shv;
                if (g_shr) g_shr[p] = g_shrv;
                for (ch = 0; ch < 3; ++ch) g_yb[p * 3 + ch] = (float)yb[ch];
            }
            for (ch = 0; ch < 3; ++ch)
                out[p * 3 + ch] = (float)((1 - a) * xs[p * 3 + ch] + a * yb[ch]);
            nout[p] = sbl_blend_sample_count((float)a, (float)n_x, (float)n_y);
            if (g_dx) {
                diagpx *d = &g_dx[p];
                d->nx = (float)n_x; d->a_d = d->a = (float)a; d->b3 = (float)dx_b3;
                d->rb = (float)g_rb; d->rt = (float)g_rt; d->M = (float)dx_M;
                d->R = zout ? zout[p] : 0.0f; d->se2 = (float)dx_se2; d->vy = (float)var_y;
                d->vx = (float)var_x; d->pd2 = (float)pd2; d->b2 = (float)b2;
            }
            if (nout[p] > cap) nout[p] = cap;
            if (c->diag) {
                double a0 = n_y / (n_x + n_y), ex = a - a0, rr = a / a0;
                int src, hb;
                dg[3][0] += 1;
                hb = rr < 1.01 ? 0 : rr < 1.1 ? 1 : rr < 1.5 ? 2 : rr < 2 ? 3 : rr < 4 ? 4 : rr < 8 ? 5 : 6;
                dg_hist[hb] += 1;
                if (rr > 1.1) {
                    /* the largest bias term is the one that set b2 */
                    double sh_b = g_rb / (1 + g_rb), sh_t = g_rt / (1 + g_rt);
                    double se2 = np > 1 ? pvs / np : var_x + var_y;
                    double bb = sh_b * sh_b * pd2 + sh_b * se2, bt = sh_t * sh_t * pd2 + sh_t * se2;
                    double b3l = b2;
                    if (bb >= bt && bb >= b2 * 0.999) src = 1;
                    else if (bt > bb && bt >= b2 * 0.999) src = 2;
                    else src = 0;
                    (void)b3l;
                    dg[src][0] += 1;
                    dg[src][1] += ex;
                    dg[src][2] += ex * ex * (1 + 1 / n_x);
                    dg[src][3] += (n_x + 1) - (n_x + 1 < cap ? nout[p] : cap);
                }
            }
        }
}

static void blend(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                  float cap, float *out, float *nout)
{
    blend_core(ctx, w, h, y, xs, nx, NULL, cap, out, nout, NULL);
}

/* 3.10 (c): the region's share s of pixels whose carried R* passes c_R, into g_share */
static void region_share(const cand *c, int w, int h, const float *nx, const float *zs)
{
    static double *sh_buf;
    static size_t sh_n;
    const size_t n = (size_t)w * h;
    int px, py, i, j;
    double kf = 0, nf = 0;
    if (!c->region || c->region == 4 || !zs) return;
    if (sh_n < n) { free(sh_buf); sh_buf = (double *)malloc(n * sizeof *sh_buf); sh_n = n; }
    for (py = 0; py < h; ++py) {
        double k = 0, m = 0;
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * w + px;
            if (!(nx[p] > 0)) continue;
            m += 1; if (zs[p] > c->kt) k += 1;
        }
        kf += k; nf += m;
        for (px = 0; px < w; ++px) sh_buf[(size_t)py * w + px] = (k + 1) / (m + 2);
    }
    if (c->region == 2)
        for (i = 0; i < (int)n; ++i) sh_buf[i] = (kf + 1) / (nf + 2);
    if (c->region == 3)
        for (py = 0; py < h; ++py)
            for (px = 0; px < w; ++px) {
                double k = 0, m = 0;
                for (j = py - 1; j <= py + 1; ++j)
                    for (i = px - c->rwin; i <= px + c->rwin; ++i) {
                        size_t q;
                        if (i < 0 || j < 0 || i >= w || j >= h) continue;
                        q = (size_t)j * w + i;
                        if (!(nx[q] > 0)) continue;
                        m += 1; if (zs[q] > c->kt) k += 1;
                    }
                sh_buf[(size_t)py * w + px] = (k + 1) / (m + 2);
            }
    for (i = 0; i < (int)n; ++i) {
        share_stats[0] += 1; share_stats[1] += sh_buf[i];
        if (sh_buf[i] < 0.05) share_stats[2] += 1;
        if (sh_buf[i] > 0.25) share_stats[3] += 1;
    }
    g_share = sh_buf;
}

/* region 4: the library's form: the share over rows y - 1 .. y + 1 of last frame's plane
   as it is (not reprojected: any row-range call can read it), s = (k + 1) / (n + 2) over
   all its pixels. The runner calls the blend for eye 0 then eye 1 every frame, so the
   call's parity is the eye; prev_plane[e] is that eye's last output plane. */
static float *prev_plane[2];
static size_t prev_n[2];
static int prev_have[2], call_count;
static void region_share_raw(const cand *c, int w, int h)
{
    static double *sh_buf;
    static size_t sh_n;
    const int e = call_count & 1;
    const size_t n = (size_t)w * h;
    int px, py, j;
    if (c->region != 4) return;
    if (sh_n < n) { free(sh_buf); sh_buf = (double *)malloc(n * sizeof *sh_buf); sh_n = n; }
    for (py = 0; py < h; ++py) {
        double k = 0, m = 0;
        for (j = py - 1; j <= py + 1; ++j) {
            if (j < 0 || j >= h) continue;
            for (px = 0; px < w; ++px) {
                m += 1;
                if (prev_have[e] && prev_plane[e][(size_t)j * w + px] > c->kt) k += 1;
            }
        }
        for (px = 0; px < w; ++px) sh_buf[(size_t)py * w + px] = (k + 1) / (m + 2);
    }
    for (px = 0; px < (int)n; ++px) {
        share_stats[0] += 1; share_stats[1] += sh_buf[px];
        if (sh_buf[px] < 0.05) share_stats[2] += 1;
        if (sh_buf[px] > 0.25) share_stats[3] += 1;
    }
    g_share = sh_buf;
}
static void region_keep(const cand *c, int w, int h, const float *zout)
{
    const int e = call_count & 1;
    const size_t n = (size_t)w * h;
    if (c->region == 4) {
        if (prev_n[e] < n) { /* scenes differ in size */
            free(prev_plane[e]);
            prev_plane[e] = (float *)malloc(n * sizeof(float));
            prev_n[e] = n;
        }
        memcpy(prev_plane[e], zout, n * sizeof(float));
        prev_have[e] = 1;
    }
    ++call_count;
}

static void blend_carry(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                        const float *zs, float cap, float *out, float *nout, float *zout)
{
    region_share((const cand *)ctx, w, h, nx, zs);
    region_share_raw((const cand *)ctx, w, h);
    blend_core(ctx, w, h, y, xs, nx, zs, cap, out, nout, zout);
    region_keep((const cand *)ctx, w, h, zout);
    g_share = NULL;
}

static double sure_stats[8]; /* pixel-frames with history, sum t, count t > 0 */

static void box_sum(const double *src, double *dst, double *tmp, int w, int h, int rx, int ry)
{
    int x, y;
    for (y = 0; y < h; ++y) { /* rows */
        double acc = 0;
        const double *r = src + (size_t)y * w;
        for (x = 0; x < rx && x < w; ++x) acc += r[x];
        for (x = 0; x < w; ++x) {
            if (x + rx < w) acc += r[x + rx];
            if (x - rx - 1 >= 0) acc -= r[x - rx - 1];
            tmp[(size_t)y * w + x] = acc;
        }
    }
    for (x = 0; x < w; ++x) { /* columns */
        double acc = 0;
        for (y = 0; y < ry && y < h; ++y) acc += tmp[(size_t)y * w + x];
        for (y = 0; y < h; ++y) {
            if (y + ry < h) acc += tmp[(size_t)(y + ry) * w + x];
            if (y - ry - 1 >= 0) acc -= tmp[(size_t)(y - ry - 1) * w + x];
            dst[(size_t)y * w + x] = acc;
        }
    }
}

static void blend_sure(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                       const float *zs, float cap, float *out, float *nout, float *zout)
{
    const cand *c = (const cand *)ctx;
    const size_t n = (size_t)w * h;
    static size_t have;
    static double *shr;
    static double *ad, *vy, *shp, *ap, *sa, *sb, *sc, *ba, *bb, *bc, *tmp;
    static float *yb;
    size_t p;
    int px, py, i, j, ch;
    if (have < n) {
        free(ad); free(vy); free(ap); free(sa); free(sb); free(sc); free(ba); free(bb); free(bc);
        free(tmp); free(yb); free(shp); free(shr);
        shp = malloc(n * sizeof *shp); shr = malloc(n * sizeof *shr);
        ad = malloc(n * sizeof *ad); vy = malloc(n * sizeof *vy); ap = malloc(n * sizeof *ap);
        sa = malloc(n * sizeof *sa); sb = malloc(n * sizeof *sb); sc = malloc(n * sizeof *sc);
        ba = malloc(n * sizeof *ba); bb = malloc(n * sizeof *bb); bc = malloc(n * sizeof *bc);
        tmp = malloc(n * sizeof *tmp); yb = malloc(n * 3 * sizeof *yb);
        free(g_dlocp); g_dlocp = calloc(n, sizeof *g_dlocp);
        have = n;
    }
    g_ad = ad; g_vy = vy; g_yb = yb; g_sh = shp; g_shr = shr;
    region_share(c, w, h, nx, zs);
    region_share_raw(c, w, h);
    g_dshare = g_share;
    blend_core(ctx, w, h, y, xs, nx, zs, cap, out, nout, zout);
    region_keep(c, w, h, zout);
    g_ad = NULL; g_vy = NULL; g_yb = NULL; g_sh = NULL; g_shr = NULL; g_share = NULL;
    /* the paper's scalar weight: a = d^2 / (d^2 + s^2), d = x* - m1 (3x3), s^2 population */
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            double m1[3] = {0}, m2[3] = {0}, d2 = 0, s2 = 0;
            int cnt = 0;
            p = (size_t)py * w + px;
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    if (c->loo && i == px && j == py) continue;
                    q = (size_t)j * w + i; ++cnt;
                    for (ch = 0; ch < 3; ++ch) { m1[ch] += y[q * 3 + ch]; m2[ch] += (double)y[q * 3 + ch] * y[q * 3 + ch]; }
                }
            for (ch = 0; ch < 3; ++ch) {
                double mu = m1[ch] / cnt, v = m2[ch] / cnt - mu * mu, d = xs[p * 3 + ch] - mu;
                d2 += d * d; s2 += v > 0 ? v : 0;
            }
            ap[p] = nx[p] > 0 ? (d2 + s2 > 0 ? d2 / (d2 + s2) : 1.0) : 1.0;
            if (c->svar == 1) vy[p] = s2 * cnt / (cnt - 1);
        }
    /* per pixel: delta = a_p - a_d; risk'(t) / 2 = sum delta^2 D t - sum delta ((1 - a_d) D - S) */
    for (p = 0; p < n; ++p) {
        double dl = ap[p] - ad[p], D = 0;
        if (!(nx[p] > 0)) { sa[p] = sb[p] = sc[p] = 0; continue; }
        for (ch = 0; ch < 3; ++ch) { double d = (double)xs[p * 3 + ch] - yb[p * 3 + ch]; D += d * d; }
        sa[p] = dl * ((1.0 - ad[p]) * D - vy[p]);
        if (c->sure == 4) { sa[p] = D; sb[p] = vy[p]; sc[p] = 0; continue; }
        sure_stats[3] += (1.0 - ad[p]) * D; sure_stats[4] += vy[p]; sure_stats[5] += dl;
        sure_stats[6] += sa[p]; sure_stats[7] += dl * dl * D;
        sb[p] = dl * dl * D;
        sc[p] = sa[p] * sa[p];
    }
    box_sum(sa, ba, tmp, w, h, c->srx, c->sry);
    box_sum(sb, bb, tmp, w, h, c->srx, c->sry);
    box_sum(sc, bc, tmp, w, h, c->srx, c->sry);
    for (p = 0; p < n; ++p) {
        double t = 0, a;
        if (g_afin) g_afin[p] = 1.0;
        if (!(nx[p] > 0)) continue;
        if (c->sure == 3) t = 1;
        else if (c->sure == 7) { /* no risk: t = the carried evidence's shrink, where a_p > a_d */
            t = shr[p] < 1 ? shr[p] : 1;
            if (ap[p] < ad[p]) t = 0;
        }
        else if (c->sure == 9) { /* t = max(sh_R, the region's share s), where a_p > a_d */
            t = shr[p] < 1 ? shr[p] : 1;
            if (g_dshare && g_dshare[p] > t) t = g_dshare[p];
            if (ap[p] < ad[p]) t = 0;
        }
        else if (c->sure == 10) {
            /* 3.12: t = max(sh_R, P), P the posterior probability of change that 3.10 (c)'s
               model of R gives (Gaussian of variance kappa about 1 under no change, flat
               under change, prior odds M): ln odds = ((R - 1)^2 - (c_R(M) - 1)^2) / (2 kappa),
               one half at c_R(M); where a_p > a_d */
            const double kp = c->lambda / (2 - c->lambda), Rv = zout[p] > 1 ? zout[p] - 1.0 : 0.0;
            double Mr = g_dshare ? 1.0 / (2.0 * g_dshare[p]) : 1.0, v, lo, P;
            v = (c->kt - 1) * (c->kt - 1) + 2 * kp * log(Mr);
            if (v < 0) v = 0;
            lo = (Rv * Rv - v) / (2 * kp);
            P = lo > 50 ? 1.0 : 1.0 / (1.0 + exp(-lo));
            t = shr[p] < 1 ? shr[p] : 1;
            if (P > t) t = P;
            if (ap[p] < ad[p]) t = 0;
        }
        else if (c->sure == 8) { /* t = max(sh, the local test's posterior), where a_p > a_d */
            t = shp[p] > g_dlocp[p] ? shp[p] : g_dlocp[p];
            if (t > 1) t = 1;
            if (ap[p] < ad[p]) t = 0;
        }
        else if (c->sure == 5 || c->sure == 6) { /* no risk: t = the default's own shrink */
            t = shp[p] < 1 ? shp[p] : 1;
            if (c->sure == 6 && ap[p] < ad[p]) t = 0;
        }
        else if (c->sure == 4) { /* the pixel's own a_d, a_p for the whole box: window sums of D, S */
            double dl = ap[p] - ad[p];
            t = dl > 0 && ba[p] > 0 ? ((1.0 - ad[p]) * ba[p] - bb[p]) / (dl * ba[p]) : 0;
            if (t < 0) t = 0;
            if (t > 1) t = 1;
            if (c->gate == 1 && !(shp[p] > 0)) t = 0;
            if (c->gate == 2 && t > shp[p]) t = shp[p];
        }
        else if (bb[p] > 0 && ba[p] > 0) {
            t = ba[p] / bb[p];
            if (c->sk > 0) { /* z^2 of the pooled gradient against its own spread */
                double z2 = bc[p] > 0 ? ba[p] * ba[p] / bc[p] : 1e30;
                t *= z2 > c->sk ? 1.0 - c->sk / z2 : 0.0;
            }
            if (t > 1) t = 1;
            if (c->gate == 1 && !(shp[p] > 0)) t = 0;
            if (c->gate == 2 && t > shp[p]) t = shp[p];
            if (c->gate == 4 && t > shr[p]) t = shr[p];
            if (c->sure == 2) t = t >= 0.5 ? 1 : 0;
        }
        sure_stats[0] += 1; sure_stats[1] += t; if (t > 0) sure_stats[2] += 1;
        if (g_dx) { g_dx[p].ap = (float)ap[p]; g_dx[p].shr = (float)shr[p]; g_dx[p].a = (float)(ad[p] + t * (ap[p] - ad[p])); }
        a = ad[p] + t * (ap[p] - ad[p]);
        if (g_afin) g_afin[p] = a;
        if (t != 0) {
            for (ch = 0; ch < 3; ++ch)
                out[p * 3 + ch] = (float)((1 - a) * xs[p * 3 + ch] + a * yb[p * 3 + ch]);
            if (!c->keepn) {
                nout[p] = sbl_blend_sample_count((float)a, nx[p] < cap ? nx[p] : cap, 1.0f);
                if (nout[p] > cap) nout[p] = cap;
            }
        }
    }
}

static double svgf_stats[3]; /* pixel-frames, with temporal variance, sum pvs_t / pvs_spatial */

static void blend_svgf(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                       const float *zs, const float *ts, float cap, float *out, float *nout,
                       float *zout, float *tsout)
{
    const cand *c = (const cand *)ctx;
    const size_t n = (size_t)w * h;
    static size_t have;
    static double *ad, *vy, *shp, *vt;
    static float *yb;
    size_t p;
    int px, py, i, j, ch;
    if (have < n) {
        free(ad); free(vy); free(shp); free(vt); free(yb);
        ad = malloc(n * sizeof *ad); vy = malloc(n * sizeof *vy); shp = malloc(n * sizeof *shp);
        vt = malloc(n * sizeof *vt); yb = malloc(n * 3 * sizeof *yb);
        have = n;
    }
    /* var_Y + var_X from the carried population variance V of the pixel's own samples
       (N of them): var_Y = V N / (N - 1), var_X = var_Y / N; 3x3 mean over valid
       pixels with N >= 4 (SVGF's rule), else 0 (the spatial estimate) */
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            double acc = 0;
            int cnt = 0;
            p = (size_t)py * w + px;
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    double nq, v;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    nq = nx[q] < cap ? nx[q] : cap;
                    if (!(nq >= 4)) continue;
                    v = (double)ts[q * 3] + ts[q * 3 + 1] + ts[q * 3 + 2];
                    /* svgf 4: the variance of the history's mean, V / (N - 1) */
                    acc += c->svgf == 4 ? v / (nq - 1) : v * nq / (nq - 1) * (1.0 + 1.0 / nq);
                    ++cnt;
                }
            vt[p] = cnt >= 5 ? acc / cnt : 0;
        }
    g_ad = ad; g_vy = vy; g_yb = yb; g_sh = shp; g_vt = vt;
    region_share(c, w, h, nx, zs); /* 3.12: the region prior as blend_carry has it */
    region_share_raw(c, w, h);
    blend_core(ctx, w, h, y, xs, nx, zs, cap, out, nout, zout);
    region_keep(c, w, h, zout);
    g_ad = NULL; g_vy = NULL; g_yb = NULL; g_sh = NULL; g_vt = NULL; g_share = NULL;
    for (p = 0; p < n; ++p) {
        double a = ad[p], pdm[3] = {0, 0, 0};
        svgf_stats[0] += 1;
        if (vt[p] > 0) svgf_stats[1] += 1;
        if (c->svgf == 2 && nx[p] > 0) {
            /* innovations less the window's mean paired difference: a bias shared by
               the 3x3 (a lag under a moving light) is not noise */
            int cnt = 0;
            px = (int)(p % (size_t)w); py = (int)(p / (size_t)w);
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    if (!(nx[q] > 0)) continue;
                    ++cnt;
                    for (ch = 0; ch < 3; ++ch) pdm[ch] += (double)yb[q * 3 + ch] - xs[q * 3 + ch];
                }
            for (ch = 0; ch < 3; ++ch) pdm[ch] /= cnt;
        }
        for (ch = 0; ch < 3; ++ch) {
            double e = (double)yb[p * 3 + ch] - xs[p * 3 + ch] - pdm[ch];
            tsout[p * 3 + ch] = nx[p] > 0 ? (float)((1.0 - a) * (ts[p * 3 + ch] + a * e * e)) : 0.0f;
        }
    }
    (void)c;
}

static float *tr_yl, *tr_xc;
static size_t tr_n;
static double tr_stats[3]; /* diagnostics: pixel-frames, corrected, sum |correction|^2 / se2 */

static void blend_trend(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                        const float *zs, const float *ts, float cap, float *out, float *nout,
                        float *zout, float *tsout)
{
    const cand *c = (const cand *)ctx;
    const size_t n = (size_t)w * h;
    const double lam = c->tlam, kap = lam / (2.0 - lam);
    int px, py, i, j, ch;
    if (tr_n < n) {
        free(tr_yl); free(tr_xc);
        tr_yl = (float *)malloc(n * 3 * sizeof(float));
        tr_xc = (float *)malloc(n * 3 * sizeof(float));
        tr_n = n;
    }
    /* firefly-limited samples (2.1's bound, each against its own neighbours and x*) */
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * w + px;
            double m8[3] = {0}, v8[3] = {0}, sy = 0, sm = 0, sx = 0, sv = 0, bound;
            int cnt = 0;
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h || (i == px && j == py)) continue;
                    q = (size_t)j * w + i; ++cnt;
                    for (ch = 0; ch < 3; ++ch) m8[ch] += y[q * 3 + ch];
                }
            for (ch = 0; ch < 3; ++ch) m8[ch] /= cnt;
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h || (i == px && j == py)) continue;
                    q = (size_t)j * w + i;
                    for (ch = 0; ch < 3; ++ch) { double e = y[q * 3 + ch] - m8[ch]; v8[ch] += e * e; }
                }
            for (ch = 0; ch < 3; ++ch) {
                v8[ch] /= cnt;
                sy += y[p * 3 + ch]; sm += m8[ch]; sv += v8[ch];
                sx += nx[p] > 0 ? xs[p * 3 + ch] : m8[ch];
            }
            bound = (sm > sx ? sm : sx) + 6.0 * sqrt(sv);
            for (ch = 0; ch < 3; ++ch)
                tr_yl[p * 3 + ch] = (float)(sy > bound && sy > 0 ? y[p * 3 + ch] * (bound > 0 ? bound : 0) / sy
                                                                 : y[p * 3 + ch]);
        }
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * w + px;
            double s1[3] = {0}, s2[3] = {0}, s[3], se2 = 0, ss = 0, sh = 0, rR = 0;
            int np = 0;
            for (ch = 0; ch < 3; ++ch) tr_xc[p * 3 + ch] = xs[p * 3 + ch];
            if (!(nx[p] > 0)) {
                for (ch = 0; ch < 3; ++ch) tsout[p * 3 + ch] = 0.0f;
                continue;
            }
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    if (!(nx[q] > 0)) continue;
                    ++np;
                    for (ch = 0; ch < 3; ++ch) {
                        double d = (double)xs[q * 3 + ch] - tr_yl[q * 3 + ch];
                        s1[ch] += d; s2[ch] += d * d;
                    }
                }
            for (ch = 0; ch < 3; ++ch) {
                double pd = np >= 3 ? s1[ch] / np : 0.0;
                if (np >= 3) {
                    double v = (s2[ch] - np * pd * pd) / (np - 1);
                    se2 += (v > 0 ? v : 0) / np;
                }
                s[ch] = (1.0 - lam) * ts[p * 3 + ch] + (np >= 3 ? lam * pd : 0.0);
                tsout[p * 3 + ch] = (float)s[ch];
                ss += s[ch] * s[ch];
            }
            if (np >= 3 && ss > 0) {
                double u = se2 > 0 ? ss / (kap * se2) : 1e6;
                sh = u > c->tc ? 1.0 - c->tc / u : 0.0;
            }
            if ((c->tmode & 2) && zs[p] > 0) { /* only where the carried R passes c_R */
                rR = zs[p] - c->kt;
                if (!(rR > 0)) sh = 0;
            }
            tr_stats[0] += 1;
            if (sh > 0) {
                tr_stats[1] += 1;
                tr_stats[2] += sh * sh * ss / (se2 > 0 ? se2 : 1);
                for (ch = 0; ch < 3; ++ch) tr_xc[p * 3 + ch] = (float)(xs[p * 3 + ch] - sh * s[ch]);
            }
        }
    blend_core(ctx, w, h, y, tr_xc, nx, zs, cap, out, nout, (c->tmode & 1) ? NULL : zout);
    if (c->tmode & 1)
        for (i = 0; i < (int)n; ++i) zout[i] = 1.0f;
}

/* 4.10: the resampling blur carried with the history. A bilinear fetch at fraction
   (f_x, f_y) convolves the history with a kernel of variance f (1 - f) per axis; the blend
   t = (1 - a) x* + a y leaves a kernel of variance (1 - a)(S) with S = s* + v (s* the
   carried variance gathered with the history's taps, v this fetch's), and to second
   order the blur's bias is (S_x d2/dx2 + S_y d2/dy2) / 2 of the signal, its second
   differences taken from x*'s own 3x3. ts / tsout: (s_x, s_y, 0). */
static float *g_fetch_xy;
/* The variance of a second difference [1 -2 1] of unit white noise blurred by a Gaussian
   of variance s along that axis: (1 / 2 pi) int_{-pi}^{pi} 16 sin^4(w / 2) e^{-s w^2} dw
   (6 at s = 0, 1/6 of it after one half-pixel bilinear fetch), tabulated in steps of 1/32 */
#define BLUR_GT 4096
#define BLUR_PI 3.14159265358979323846
static double blur_g(double sv)
{
    static double t[BLUR_GT + 1];
    static int ready;
    int i;
    if (!ready) {
        for (i = 0; i <= BLUR_GT; ++i) {
            double acc = 0, ss = i / 32.0;
            int k;
            for (k = 0; k < 2000; ++k) {
                double w = -BLUR_PI + (k + 0.5) * (2 * BLUR_PI / 2000), sn = sin(0.5 * w);
                acc += 16 * sn * sn * sn * sn * exp(-ss * w * w);
            }
            t[i] = acc / 2000;
        }
        ready = 1;
    }
    i = (int)(sv * 32.0 + 0.5);
    return t[i < BLUR_GT ? i : BLUR_GT];
}
static void blend_blur(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                       const float *zs, const float *ts, float cap, float *out, float *nout,
                       float *zout, float *tsout)
{
    const cand *c = (const cand *)ctx;
    const size_t n = (size_t)w * h;
    static size_t have;
    static double *sx, *sy, *bb, *af;
    int px, py, ch;
    if (have < n) {
        free(sx); free(sy); free(bb); free(af); free(g_bgx); free(g_bgy);
        g_bgx = malloc(n * sizeof *g_bgx); g_bgy = malloc(n * sizeof *g_bgy);
        sx = malloc(n * sizeof *sx); sy = malloc(n * sizeof *sy); bb = malloc(n * 3 * sizeof *bb);
        af = malloc(n * sizeof *af);
        have = n;
    }
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            const size_t p = (size_t)py * w + px;
            double fx, fy, lx, ly, lo, hi;
            int okx, oky;
            sx[p] = sy[p] = 0;
            for (ch = 0; ch < 3; ++ch) bb[p * 3 + ch] = 0;
            if (!(nx[p] > 0) || !(g_fetch_xy[p * 3 + 2] > 0)) continue;
            fx = g_fetch_xy[p * 3] - floor(g_fetch_xy[p * 3]);
            fy = g_fetch_xy[p * 3 + 1] - floor(g_fetch_xy[p * 3 + 1]);
            if (fx < 1e-4 || fx > 1 - 1e-4) fx = 0; /* float rounding of an integer fetch */
            if (fy < 1e-4 || fy > 1 - 1e-4) fy = 0;
            sx[p] = ts[p * 3] + fx * (1 - fx);
            sy[p] = ts[p * 3 + 1] + fy * (1 - fy);
            if (c->blur & 256) {
                /* the history's noise: sample k of N (equal weights) has been fetched k
                   times at about this fraction, its noise blurred by k v */
                const int nn = (int)(nx[p] < cap ? nx[p] : cap);
                double gx = 0, gy = 0;
                int k;
                for (k = 0; k < nn; ++k) { gx += blur_g(k * fx * (1 - fx)); gy += blur_g(k * fy * (1 - fy)); }
                g_bgx[p] = nn > 0 ? gx / nn : 6; g_bgy[p] = nn > 0 ? gy / nn : 6;
            }
            if (c->blur & 64) { /* no carried plane: the growth from a restart, S = N v / 2 */
                const double nn = nx[p] < cap ? nx[p] : cap;
                sx[p] = 0.5 * (nn + 1) * fx * (1 - fx);
                sy[p] = 0.5 * (nn + 1) * fy * (1 - fy);
            }
            okx = px > 0 && px < w - 1 && nx[p - 1] > 0 && nx[p + 1] > 0;
            oky = py > 0 && py < h - 1 && nx[p - (size_t)w] > 0 && nx[p + (size_t)w] > 0;
            for (ch = 0; ch < 3; ++ch) {
                lx = okx ? (double)xs[(p - 1) * 3 + ch] + xs[(p + 1) * 3 + ch] - 2.0 * xs[p * 3 + ch] : 0;
                ly = oky ? (double)xs[(p - (size_t)w) * 3 + ch] + xs[(p + (size_t)w) * 3 + ch] - 2.0 * xs[p * 3 + ch] : 0;
                if ((c->blur & 128) && px > 0 && py > 0 && px < w - 1 && py < h - 1) {
                    /* the second differences averaged over the 3x3 ([1 -2 1] x [1 1 1] / 3):
                       a third of the noise, where all nine x* are valid */
                    int i, j, all = 1;
                    double sxx = 0, syy = 0;
                    for (j = -1; j <= 1; ++j)
                        for (i = -1; i <= 1; ++i)
                            if (!(nx[p + (ptrdiff_t)j * w + i] > 0)) all = 0;
                    if (all) {
                        for (j = -1; j <= 1; ++j) {
                            const size_t r = p + (ptrdiff_t)j * w, q = p + (ptrdiff_t)j;
                            sxx += (double)xs[(r - 1) * 3 + ch] + xs[(r + 1) * 3 + ch] - 2.0 * xs[r * 3 + ch];
                            syy += (double)xs[(q - (size_t)w) * 3 + ch] + xs[(q + (size_t)w) * 3 + ch] - 2.0 * xs[q * 3 + ch];
                        }
                        lx = sxx / 3; ly = syy / 3;
                    }
                }
                bb[p * 3 + ch] = 0.5 * (sx[p] * lx + sy[p] * ly);
                if (c->bmax > 0) {
                    int i, j;
                    lo = hi = xs[p * 3 + ch];
                    for (j = py - 1; j <= py + 1; ++j)
                        for (i = px - 1; i <= px + 1; ++i) {
                            size_t q;
                            if (i < 0 || j < 0 || i >= w || j >= h) continue;
                            q = (size_t)j * w + i;
                            if (!(nx[q] > 0)) continue;
                            if (xs[q * 3 + ch] < lo) lo = xs[q * 3 + ch];
                            if (xs[q * 3 + ch] > hi) hi = xs[q * 3 + ch];
                        }
                    if (fabs(bb[p * 3 + ch]) > c->bmax * (hi - lo))
                        bb[p * 3 + ch] = bb[p * 3 + ch] > 0 ? c->bmax * (hi - lo) : -c->bmax * (hi - lo);
                }
            }
            blur_stats[0] += 1; blur_stats[1] += sx[p] + sy[p];
            if (sx[p] + sy[p] > 0) blur_stats[4] += 1;
        }
    g_bsx = sx; g_bsy = sy; g_bb = bb; g_afin = af;
    blend_sure(ctx, w, h, y, xs, nx, zs, cap, out, nout, zout);
    g_bsx = g_bsy = g_bb = g_afin = NULL;
    for (size_t p = 0; p < n; ++p) {
        const double a = nx[p] > 0 ? af[p] : 1.0;
        tsout[p * 3] = (float)((1 - a) * sx[p]);
        tsout[p * 3 + 1] = (float)((1 - a) * sy[p]);
        tsout[p * 3 + 2] = 0.0f;
        if (nx[p] > 0) blur_stats[5] += a;
    }
}

static cand cands[] = {
    {"ha (check)", 0, 0, 3, 3, 0, 0, 0, 0, 0, 0},
    {"s4 + EBs c3", 7, 1, 4, 3.0, 1, 0, 2, 0, 0, 2},
    {"s4 + EBs c2.5", 7, 1, 4, 2.5, 1, 0, 2, 0, 0, 2},
    {"s4 + EBn c3.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 1},
    {"pooled (check)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 0, 0, 0, 0},
    {"Z l1/3 k3 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 3, 1, 4},
    {"Z l1/3 k3 direct", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 3, 2, 4},
    {"Z l1/5 k3 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 3, 1, 4},
    {"Z l1/5 k3 direct", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 3, 2, 4},
    {"Z l1/3 k4 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 4, 1, 4},
    {"Z l1/5 k4 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 4, 1, 4},
    {"Z l1/9 k3 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 9, 3, 1, 4},
    {"Z l1/9 k2 EB", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 9, 2, 1, 4},
    {"R l1/3 c2", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2, 4, 4},
    {"R l1/3 c2.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.5, 4, 4},
    {"R l1/5 c2", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 2, 4, 4},
    {"R l1/3 c1.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 1.5, 4, 4},
    {"R l1/5 c1.75", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 1.75, 4, 4},
    {"R l1/5 c1.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 5, 1.5, 4, 4},
    {"R l1/9 c1.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 9, 1.5, 4, 4},
    {"R l1/9 c1.3", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 9, 1.3, 4, 4},
    {"R l1/3 c1.75", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 1.75, 4, 4},
    {"R l1/3 gate2", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2, 12, 4},
    {"R l1/3 gate2.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.5, 12, 4},
    /* c_R = 1 + (c - 1) sqrt(lambda / (2 - lambda)) = 2.118: the one-frame threshold's
       excess over the H0 mean, in units of the carried ratio's spread */
    {"R l1/3 c2.12", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4},
    {"R l1/3 gate2.12", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 12, 4},
    {"R l1/3 soft2.12", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 20, 4},
    /* 27..: trend (drift carried, subtracted from x*) on top of the default (R plane) */
    {"trend l1/3 c3.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4, 1.0 / 3, 3.5, 0},
    {"trend l1/3 c3.5 noR", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4, 1.0 / 3, 3.5, 1},
    {"trend l1/3 c3.5 Rgate", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4, 1.0 / 3, 3.5, 2},
    {"trend l1/5 c3.5", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4, 1.0 / 5, 3.5, 0},
    {"R l1/3 garrote2.12", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4},
    /* the channels of one path sample are correlated (one light path drives all three):
       |s|^2 / (kappa se^2) is nearer chi^2_1 than chi^2_3 / 3 under H0; 6.63 = its 99 % */
    {"R garrote + 1-frame garrote", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 100, 4},
    {"trend l1/3 c6.63", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 4, 4, 1.0 / 3, 6.63, 0},
    /* 35..: risk-based mixing of the default (garrote, index 31) with the paper's weight */
    {"sure a_p alone (check)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 3, 1, 1, 0, 0},
    {"sure t* 3x15", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 1, 0, 0},
    {"sure t* 7x7", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 3, 3, 0, 0},
    {"sure t* 15x15", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0},
    {"sure t* 31x31", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 15, 15, 0, 0},
    {"sure hard 15x15", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 2, 7, 7, 0, 0},
    {"sure t* 15x15 S paper", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 1, 0},
    {"sure t* 15x15 sk4", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 4},
    {"sure t* 7x7 sk4", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 3, 3, 0, 4},
    /* 44..: leave-one-out paper weight */
    {"sure t* 3x15 loo", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 1, 0, 0, 0, 1},
    {"sure t* 15x15 loo", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 0, 1},
    {"sure t* 31x31 loo", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 15, 15, 0, 0, 0, 1},
    {"sure a_p loo alone", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 3, 1, 1, 0, 0, 0, 1},
    /* 47..: gated by the default's own evidence (sh = r / (1 + r)) */
    {"sure 3x15 gate sh>0", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 1, 0, 0, 1, 0},
    {"sure 3x15 t<=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 1, 0, 0, 2, 0},
    {"sure 15x15 gate sh>0", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 1, 0},
    {"sure 15x15 t<=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 2, 0},
    /* 51..: the pixel's own a_d, a_p over the box (window sums of D and S only) */
    {"sure own 3x15", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 4, 7, 1, 0, 0, 0, 1},
    {"sure own 3x15 t<=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 4, 7, 1, 0, 0, 2, 1},
    /* 53..: t = sh, no risk estimate (a = a_d + sh (a_p - a_d)) */
    {"mix t=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 5, 1, 1, 0, 0, 0, 1},
    {"mix t=sh, a_p > a_d only", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 6, 1, 1, 0, 0, 0, 1},
    {"mix t=sh, a_p full 3x3", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 6, 1, 1, 0, 0, 0, 0},
    /* 56..: var_Y from temporal moments (SVGF), the default otherwise */
    {"svgf var, nu 8", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0},
    {"svgf var, nu 30", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 30},
    /* 58: innovations less the 3x3 mean paired difference */
    {"svgf var - window bias", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0},
    /* 59: the local test's se^2 only, the larger of the spatial and the temporal */
    {"svgf local test: max(pv, V)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 0},
    /* 60..: the mixed weight, the default's N kept (diagnostic) */
    {"sure t* 15x15 loo, keep N", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 0, 1, 0, 0, 1},
    {"sure t* 15x15, keep N", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 0, 0, 0, 0, 1},
    /* 62: t <= the carried evidence's own shrink (R's garrote only, not the one-frame blocks) */
    {"sure 15x15 t<=sh_R", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 1, 7, 7, 0, 0, 4, 0},
    /* 63: no risk: a = a_d + sh_R (a_p - a_d)+, a_p the library's (full 3x3) */
    {"mix t=sh_R, a_p > a_d", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0},
    /* 64..: session 11, 3.10 (a): the default decomposed, and with one source off */
    {"default, diag", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1},
    {"no local test", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1},
    {"no 1-frame blocks", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1},
    {"no carried R", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 1},
    {"none (progressive+limit)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 7, 1},
    {"R only (no local, no blocks)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 1},
    /* 70..: 3.10 (c) region prior */
    {"row prior: local+blocks", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 3, 0, 0},
    {"row prior: local+blocks+R", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 7, 0, 0},
    {"frame prior: local+blocks", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 3, 0, 0},
    {"3x31 prior: local+blocks", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 3, 3, 15, 0},
    {"row prior: local only", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 0, 0},
    {"row prior: blocks only", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 2, 0, 0},
    /* 76..: the row prior (all three sources) with a more eager change rule */
    {"row prior + R gate", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 12, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 7, 0, 0},
    {"row prior + mix t=sh_R", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 7, 0, 0},
    /* 79..: region 4, the library's form (last frame's plane as it is, rows y-1..y+1) */
    {"3-row raw prior: all", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 7, 0, 0},
    {"3-row raw prior + R gate", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 12, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 7, 0, 0},
    /* 81..: the adopted form (last frame's plane rows y-1..y+1, local + blocks) + mix t = sh_R */
    {"lib prior (3) + mix t=sh_R", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 4, 3, 0, 0},
    {"row prior + mix t=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 6, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 7, 0, 0},
    /* 83..: session 14 (4.10): 3.11's default (the plane's prior on all three sources, the
       mix by sh_R), temporal and combined (c = 1, the default stereo blend), then the blur */
#define C311 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0
    {"3.11 (check)", C311, 0, 0, 16, 0},
    {"3.11 combined (check)", C311, 1, 1, 16, 0},
    {"blur max", C311, 0, 0, 1, 0},
    {"blur max, combined", C311, 1, 1, 1, 0},
    {"blur max -noise", C311, 0, 0, 5, 0},
    {"blur max -noise, combined", C311, 1, 1, 5, 0},
    {"blur M->1 (4.9 rule)", C311, 0, 0, 24, 0},
    {"blur M->1, combined", C311, 1, 1, 24, 0},
    {"blur sum, combined", C311, 1, 1, 2, 0},
    {"blur max, bmax 1/2, comb", C311, 1, 1, 1, 0.5},
    {"blur max once, combined", C311, 1, 1, 33, 0},
    {"blur max, S = (N+1)v/2", C311, 0, 0, 65, 0},
    {"blur max, S = (N+1)v/2, comb", C311, 1, 1, 65, 0},
    /* 95..: the second differences averaged over the 3x3 (+128) */
    {"blur 3x3 L", C311, 0, 0, 129, 0},
    {"blur 3x3 L, combined", C311, 1, 1, 129, 0},
    {"blur 3x3 L -noise", C311, 0, 0, 133, 0},
    {"blur 3x3 L -noise, combined", C311, 1, 1, 133, 0},
    {"blur 3x3 L -noise, S from N", C311, 0, 0, 197, 0},
    {"blur 3x3 L -noise, S from N, comb", C311, 1, 1, 197, 0},
    /* 101..: |b| at most half the 3x3 range of x* (a symmetric kernel moves a step's
       value at most half-way) */
    {"blur max, bmax 1/2", C311, 0, 0, 1, 0.5},
    {"blur 3x3 L, bmax 1/2", C311, 0, 0, 129, 0.5},
    {"blur 3x3 L, bmax 1/2, comb", C311, 1, 1, 129, 0.5},
    /* 104..: less the noise of the second differences of the history's blurred noise */
    {"blur max -blurred noise", C311, 0, 0, 257, 0},
    {"blur max -blurred noise, comb", C311, 1, 1, 257, 0},
    {"blur max -blurred noise, S from N", C311, 0, 0, 321, 0},
    {"blur max -blurred noise, S from N, comb", C311, 1, 1, 321, 0},
    {"blur max -blurred noise, bmax 1/2", C311, 0, 0, 257, 0.5},
    {"blur max -blurred noise, bmax 1/2, comb", C311, 1, 1, 257, 0.5},
    /* 110..: the plane-free form with the bound */
    {"blur max, S from N, bmax 1/2", C311, 0, 0, 65, 0.5},
    {"blur max, S from N, bmax 1/2, comb", C311, 1, 1, 65, 0.5},
    /* 112..: the plane-free form, every correction (109 without the plane) */
    {"blur -blurred noise, S from N, bmax 1/2", C311, 0, 0, 321, 0.5},
    {"blur -blurred noise, S from N, bmax 1/2, comb", C311, 1, 1, 321, 0.5},
#undef C311
    /* 114..: session 14 (3.12), the 3.11 default as the library forms it (3-row prior of last
       frame's plane on all three sources, mix t = sh_R where a_p > a_d) */
    {"3.11 default", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0},
    /* 3.12: the mix by the shrink of all the pooled evidence, sh = r / (1 + r),
       r = max(r_blocks, r_R), both under the region prior (3.9's "t = sh" lost static
       to the blocks' one-frame false alarms before the prior protected them) */
    {"3.11 + mix t=sh", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 6, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0},
    /* 3.12: t = max(sh_R, s), s the region's share (its prior probability of change) */
    {"3.11 + mix t=max(shR,s)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 9, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0},
    /* 3.12: the same and the local test's posterior: t = max(sh, P_local) */
    {"3.11 + mix t=max(sh,P)", 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 8, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0},
    /* 118..: session 16 (3.12), the variance split with the noise level's change (vsplit) */
#define C311 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0
    {"3.11 + split rho", C311, 0, 0, 0, 0, 1},
    {"3.11 + split rho>=1", C311, 0, 0, 0, 0, 2},
    {"3.11 + split rho(f pd)", C311, 0, 0, 0, 0, 3},
    {"3.11 + split rho(f pd)>=1", C311, 0, 0, 0, 0, 4},
    {"3.11 + split rho>=1 where R>cR", C311, 0, 0, 0, 0, 5},
    {"3.11 + split 1+shR(rho-1)", C311, 0, 0, 0, 0, 6},
#define C310 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0
    {"3.10 (no mix; check)", C310, 0, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0, 0},
    {"3.10 + split by carried V", C310, 4, 0, 0, 0, 0, 4, 7, 0, 0, 0, 0, 0, 0, 0},
#undef C310
    {"3.11 combined (lib blur)", C311, 1, 1, 321, 0.5, 0},
#undef C311
#define C311S(sure) 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, sure, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0
    {"3.11 + mix max(shR,s), comb", C311S(9), 1, 1, 321, 0.5, 0},
    {"3.11 + mix max(shR,P(R))", C311S(10), 0, 0, 0, 0, 0},
    {"3.11 + mix max(shR,P(R)), comb", C311S(10), 1, 1, 321, 0.5, 0},
#undef C311S
#define C311 7, 1, 4, 3.5, 1, 0, 2, 0, 0, 2, 1.0 / 3, 2.118034, 36, 4, 0, 0, 0, 7, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 4, 7, 0, 0
    {"3.11 + split rho, comb", C311, 1, 1, 321, 0.5, 1},
    {"3.11 + split rho>=1, comb", C311, 1, 1, 321, 0.5, 2},
#undef C311
};

/* ---- diag: (session 14, ESTIMATORS 3.12) where the candidate loses to a library method,
   pixel by pixel. The library method runs first and its displayed images are kept; then
   the candidate runs with its per-pixel state (g_dx) kept per eye, and each evaluated
   frame's squared errors of both against the reference are split by what the reference
   does at the pixel (a fixed camera: the pixel's own reference over the frames). */
static const sbr_seq *dg_seq;
static float *dg_vs[2 * 64];           /* the library method's displayed images [f * 2 + e] */
static diagpx *dg_px[2];               /* the candidate's state per eye, this frame */
static float *dg_x[2], *dg_y[2];       /* its x* and y per eye, this frame */
static float *dg_lmin[2], *dg_lmax[2]; /* the pixel's reference luminance range over frames */
static int dg_keep_vs;
static void diag_keep_vs(void *ctx, int f, int e, const float *rgb, int w, int h)
{
    size_t n = (size_t)w * h * 3;
    (void)ctx;
    if (!dg_vs[f * 2 + e]) dg_vs[f * 2 + e] = (float *)malloc(n * sizeof(float));
    memcpy(dg_vs[f * 2 + e], rgb, n * sizeof(float));
}
static void diag_blend(void *ctx, int w, int h, const float *y, const float *xs, const float *nx,
                       const float *zs, float cap, float *out, float *nout, float *zout)
{
    const int e = call_count & 1;
    const size_t n = (size_t)w * h;
    if (!dg_px[e]) {
        dg_px[e] = (diagpx *)calloc(n, sizeof(diagpx));
        dg_x[e] = (float *)malloc(n * 3 * sizeof(float));
        dg_y[e] = (float *)malloc(n * 3 * sizeof(float));
    }
    memcpy(dg_x[e], xs, n * 3 * sizeof(float));
    memcpy(dg_y[e], y, n * 3 * sizeof(float));
    g_dx = dg_px[e];
    blend_sure(ctx, w, h, y, xs, nx, zs, cap, out, nout, zout);
    g_dx = NULL;
}
/* classes: motion state x level; motion 0 darkening now, 1 brightening now, 2 k = 1 frame
   since the last change, 3 k = 2, 4 k = 3..4, 5 k = 5..8, 6 k > 8 (of the pixel's shadow
   history), 7 never shadowed (range < 5 % of its max); level 0 dark (phi < 0.1),
   1 penumbra, 2 lit (phi > 0.9); phi = (L - Lmin) / (Lmax - Lmin) */
#define DG_MOT 8
#define DG_LEV 3
#define DG_ACC 22
static double dg_acc[DG_MOT][DG_LEV][DG_ACC];
static double dg_nacc[8][DG_ACC];      /* by the history's N bucket */
static double dg_ladder[2];            /* sum eA, sum eB on the ladder frames */
static const char *const dg_mot_name[DG_MOT] = {"darkening now", "brightening now", "1 frame after",
                                                "2 frames after", "3-4 frames after", "5-8 frames after",
                                                ">8 frames after", "never shadowed"};
static double dg_ey2, dg_ex2;
static void dg_extra(const double *a)
{
    double c = a[0] > 0 ? a[0] : 1;
    printf(" | vy %.4f (y err %.4f) vx %.4f (x* err %.4f) b2 %.4f pd2 %.4f\n", a[16] / c, a[17] / c,
           a[18] / c, a[19] / c, a[20] / c, a[21] / c);
}
static const char *const dg_lev_name[DG_LEV] = {"dark", "penumbra", "lit"};
static double lum3(const float *v) { return (double)v[0] + v[1] + v[2]; }
static void dg_add(double *acc, double eA, double eB, const diagpx *d, double a_or, double dk,
                   double ey2, double ex2)
{
    /* 3.12 (session 16): the weight's variance split against the truth: var_Y and var_X as
       the candidate estimated them (summed over channels) and the squared errors of y and
       of x* against the reference; the bias^2 it counted */
    acc[16] += d->vy; acc[17] += ey2; acc[18] += d->vx; acc[19] += ex2; acc[20] += d->b2;
    acc[21] += d->pd2;
    acc[0] += 1; acc[1] += eA; acc[2] += eB;
    acc[3] += d->a; acc[4] += a_or; acc[5] += d->ap; acc[6] += d->a_d; acc[7] += d->shr;
    acc[8] += d->rt > 0; acc[9] += d->rb > 0; acc[10] += d->pd2 > 0 && d->b3 > 0.5 * d->pd2;
    acc[11] += d->M; acc[12] += d->nx; acc[13] += d->R;
    acc[14] += dk;                      /* the pixel's lag: (x* - ref) over sqrt(var_Y) */
    acc[15] += d->a < a_or ? 1 : 0;
}
static void diag_frame(void *ctx, int f, int e, const float *rgb, int w, int h)
{
    const sbr_seq *s = dg_seq;
    const float *ref = s->views[f * 2 + e].ref, *vs = dg_vs[f * 2 + e];
    int px, py, i, j, ch, lad = 0;
    (void)ctx;
    if (f < s->frames / 4 || !vs || !dg_px[e]) return;
    for (i = 0; i < s->ladder_count; ++i) if (s->ladder[i].frame == f) lad = 1;
    for (py = 0; py < h; ++py)
        for (px = 0; px < w; ++px) {
            size_t p = (size_t)py * w + px;
            const diagpx *d = &dg_px[e][p];
            double eA = 0, eB = 0, L = lum3(ref + p * 3), lo = dg_lmin[e][p], hi = dg_lmax[e][p];
            double rg = hi - lo, phi, EX = 0, EY = 0, a_or, dk = 0;
            int mot, lev, k, nb;
            for (ch = 0; ch < 3; ++ch) {
                double da = (double)rgb[p * 3 + ch] - ref[p * 3 + ch], db = (double)vs[p * 3 + ch] - ref[p * 3 + ch];
                eA += da * da; eB += db * db;
            }
            if (lad) { dg_ladder[0] += eA; dg_ladder[1] += eB; }
            if (!(d->nx > 0)) continue;
            for (j = py - 1; j <= py + 1; ++j)
                for (i = px - 1; i <= px + 1; ++i) {
                    size_t q;
                    if (i < 0 || j < 0 || i >= w || j >= h) continue;
                    q = (size_t)j * w + i;
                    for (ch = 0; ch < 3; ++ch) {
                        double ex = (double)dg_x[e][q * 3 + ch] - ref[q * 3 + ch];
                        double ey = (double)dg_y[e][q * 3 + ch] - ref[q * 3 + ch];
                        EX += ex * ex; EY += ey * ey;
                    }
                }
            a_or = EX + EY > 0 ? EX / (EX + EY) : 0;
            {
                double b = lum3(dg_x[e] + p * 3) - L;
                dk = d->vy > 0 ? b / sqrt(d->vy) : 0;
            }
            if (rg < 0.05 * hi) { mot = 7; lev = 2; }
            else {
                phi = (L - lo) / rg;
                lev = phi < 0.1 ? 0 : phi > 0.9 ? 2 : 1;
                for (k = 0; k <= f && k <= 9; ++k) {
                    double c;
                    if (f - k - 1 < 0) { k = 10; break; }
                    c = (lum3(s->views[(f - k) * 2 + e].ref + p * 3) - lum3(s->views[(f - k - 1) * 2 + e].ref + p * 3)) / rg;
                    if (fabs(c) > 0.1) break;
                }
                if (k == 0) {
                    double c = (L - lum3(s->views[(f - 1) * 2 + e].ref + p * 3)) / rg;
                    mot = c < 0 ? 0 : 1;
                } else mot = k == 1 ? 2 : k == 2 ? 3 : k <= 4 ? 4 : k <= 8 ? 5 : 6;
            }
            {
                double ey2 = 0, ex2 = 0;
                for (ch = 0; ch < 3; ++ch) {
                    double ey = (double)dg_y[e][p * 3 + ch] - ref[p * 3 + ch];
                    double ex = (double)dg_x[e][p * 3 + ch] - ref[p * 3 + ch];
                    ey2 += ey * ey; ex2 += ex * ex;
                }
                dg_ey2 = ey2; dg_ex2 = ex2;
            }
            dg_add(dg_acc[mot][lev], eA, eB, d, a_or, dk, dg_ey2, dg_ex2);
            nb = d->nx <= 2 ? 0 : d->nx <= 4 ? 1 : d->nx <= 8 ? 2 : d->nx <= 16 ? 3 : d->nx <= 32 ? 4 : 5;
            dg_add(dg_nacc[nb], eA, eB, d, a_or, dk, dg_ey2, dg_ex2);
        }
}
static void dg_print_row(const char *name, const double *a, double tot)
{
    double c = a[0] > 0 ? a[0] : 1;
    printf("%-34s %6.2f%% %8.4f %8.4f %+7.1f%% | a %.3f or %.3f ap %.3f ad %.3f a<or %3.0f%% shR %.3f R>cR %4.1f%% blk %4.1f%% loc %4.1f%% M %5.1f N %5.1f R %5.2f lag %+.2f\n",
           name, 100 * a[0] / tot, a[1] / c, a[2] / c, 100 * (a[1] - a[2]) / tot,
           a[3] / c, a[4] / c, a[5] / c, a[6] / c, 100 * a[15] / c, a[7] / c, 100 * a[8] / c,
           100 * a[9] / c, 100 * a[10] / c, a[11] / c, a[12] / c, a[13] / c, a[14] / c);
}
static int diag_run(const sbr_seq *seq, int ci, const char *vs_name)
{
    sbr_method m, vm;
    sbr_result r, rv;
    const int w = seq->width, h = seq->height;
    const size_t n = (size_t)w * h;
    double tot_n = 0, tot_dE = 0;
    int f, e, a, b;
    size_t p;
    dg_seq = seq;
    for (e = 0; e < 2; ++e) {
        dg_lmin[e] = (float *)malloc(n * sizeof(float));
        dg_lmax[e] = (float *)malloc(n * sizeof(float));
        for (p = 0; p < n; ++p) { dg_lmin[e][p] = 1e30f; dg_lmax[e][p] = -1e30f; }
        for (f = 0; f < seq->frames; ++f)
            for (p = 0; p < n; ++p) {
                float L = (float)lum3(seq->views[f * 2 + e].ref + p * 3);
                if (L < dg_lmin[e][p]) dg_lmin[e][p] = L;
                if (L > dg_lmax[e][p]) dg_lmax[e][p] = L;
            }
    }
    if (sbr_find_method(vs_name, &vm) != 0) { printf("no method %s\n", vs_name); return 1; }
    if (sbr_run(seq, &vm, &rv, diag_keep_vs, NULL) != 0) return 1;
    memset(&m, 0, sizeof m);
    snprintf(m.name, sizeof m.name, "%s", cands[ci].name);
    m.temporal = 1;
    m.temporal_blend_ctx = &cands[ci];
    m.temporal_blend_carry = diag_blend;
    prev_have[0] = prev_have[1] = 0; call_count = 0;
    memset(dg_acc, 0, sizeof dg_acc); memset(dg_nacc, 0, sizeof dg_nacc); memset(dg_ladder, 0, sizeof dg_ladder);
    if (sbr_run(seq, &m, &r, diag_frame, NULL) != 0) return 1;
    printf("%s: %s eff %.2f rmse %.5f | %s eff %.2f rmse %.5f | ladder frames: sum e %.4g vs %.4g (%+.1f %%)\n",
           seq->name, cands[ci].name, r.eff_spp, r.rmse, vs_name, rv.eff_spp, rv.rmse, dg_ladder[0], dg_ladder[1],
           100 * (dg_ladder[0] - dg_ladder[1]) / dg_ladder[1]);
    for (a = 0; a < DG_MOT; ++a)
        for (b = 0; b < DG_LEV; ++b) { tot_n += dg_acc[a][b][0]; tot_dE += dg_acc[a][b][1] - dg_acc[a][b][2]; }
    printf("pixel-frames with a history %.0f; sum (eA - eB) %.4g; columns: share of pixel-frames, mean eA, mean eB, "
           "(eA - eB) as %% of the vs method's total error, then the candidate's state\n", tot_n, tot_dE);
    {
        double totB = 0;
        for (a = 0; a < DG_MOT; ++a) for (b = 0; b < DG_LEV; ++b) totB += dg_acc[a][b][2];
        for (a = 0; a < DG_MOT; ++a)
            for (b = 0; b < DG_LEV; ++b) {
                char nm[64];
                double row[DG_ACC];
                int k;
                if (dg_acc[a][b][0] == 0) continue;
                for (k = 0; k < DG_ACC; ++k) row[k] = dg_acc[a][b][k];
                row[0] = row[0] * totB / tot_n; /* share printed against tot_n below */
                snprintf(nm, sizeof nm, "%s, %s", dg_mot_name[a], dg_lev_name[b]);
                /* print share of pixel-frames and the error difference as % of eB total */
                {
                    double c = dg_acc[a][b][0];
                    printf("%-34s %6.2f%% %8.4f %8.4f %+7.1f%% | a %.3f or %.3f ap %.3f ad %.3f a<or %3.0f%% shR %.3f R>cR %4.1f%% blk %4.1f%% loc %4.1f%% M %5.1f N %5.1f R %5.2f lag %+.2f",
                           nm, 100 * c / tot_n, dg_acc[a][b][1] / c, dg_acc[a][b][2] / c,
                           100 * (dg_acc[a][b][1] - dg_acc[a][b][2]) / totB,
                           dg_acc[a][b][3] / c, dg_acc[a][b][4] / c, dg_acc[a][b][5] / c, dg_acc[a][b][6] / c,
                           100 * dg_acc[a][b][15] / c, dg_acc[a][b][7] / c, 100 * dg_acc[a][b][8] / c,
                           100 * dg_acc[a][b][9] / c, 100 * dg_acc[a][b][10] / c, dg_acc[a][b][11] / c,
                           dg_acc[a][b][12] / c, dg_acc[a][b][13] / c, dg_acc[a][b][14] / c);
                    dg_extra(dg_acc[a][b]);
                }
            }
        printf("by N:\n");
        for (a = 0; a < 6; ++a) {
            static const char *const nn[6] = {"N <= 2", "N 2-4", "N 4-8", "N 8-16", "N 16-32", "N > 32"};
            double c = dg_nacc[a][0];
            if (c == 0) continue;
            printf("%-34s %6.2f%% %8.4f %8.4f %+7.1f%% | a %.3f or %.3f ap %.3f ad %.3f a<or %3.0f%% shR %.3f R>cR %4.1f%% blk %4.1f%% loc %4.1f%% M %5.1f N %5.1f R %5.2f lag %+.2f",
                   nn[a], 100 * c / tot_n, dg_nacc[a][1] / c, dg_nacc[a][2] / c,
                   100 * (dg_nacc[a][1] - dg_nacc[a][2]) / totB,
                   dg_nacc[a][3] / c, dg_nacc[a][4] / c, dg_nacc[a][5] / c, dg_nacc[a][6] / c,
                   100 * dg_nacc[a][15] / c, dg_nacc[a][7] / c, 100 * dg_nacc[a][8] / c,
                   100 * dg_nacc[a][9] / c, 100 * dg_nacc[a][10] / c, dg_nacc[a][11] / c,
                   dg_nacc[a][12] / c, dg_nacc[a][13] / c, dg_nacc[a][14] / c);
            dg_extra(dg_nacc[a]);
        }
    }
    (void)dg_print_row; (void)dg_keep_vs;
    return 0;
}

int main(int argc, char **argv)
{
    const char *only = argc > 1 ? argv[1] : NULL;
    /* diag:SCENE[:CAND[:METHOD]]: the pixel split of 3.12 (candidate "3.11 default", 114, against
       paper-per-channel unless named) */
    if (only && !strncmp(only, "diag:", 5)) {
        char sc[64], vs[48] = "paper-per-channel";
        int ci = -1, k, nc = (int)(sizeof cands / sizeof cands[0]);
        const char *c2 = strchr(only + 5, ':');
        sbr_seq seq;
        snprintf(sc, sizeof sc, "%.*s", c2 ? (int)(c2 - only - 5) : 63, only + 5);
        for (k = 0; k < nc; ++k) if (!strcmp(cands[k].name, "3.11 default")) ci = k;
        if (c2) {
            ci = atoi(c2 + 1);
            if (ci < 0 || ci >= nc) return 1;
            if (strchr(c2 + 1, ':')) snprintf(vs, sizeof vs, "%s", strchr(c2 + 1, ':') + 1);
        }
        for (k = 0; k < SBR_SYNTH_SCENES; ++k)
            if (!strcmp(sbr_synth_scenes[k].name, sc)) {
                sbl_scene_desc d = sbr_synth_desc(&sbr_synth_scenes[k], 0);
                if (sbr_seq_synthetic(&seq, &d, sc, 1) != 0) return 1;
                return diag_run(&seq, ci, vs);
            }
        printf("diag: synthetic scenes only\n");
        return 1;
    }
    const char *only_c = argc > 2 ? argv[2] : NULL;
    if (only && !strcmp(only, "list")) {
        int k;
        for (k = 0; k < (int)(sizeof cands / sizeof cands[0]); ++k)
            printf("%d %s region %d rsrc %d diag %d sure %d stereo %d c %g blur %d\n", k, cands[k].name, cands[k].region, cands[k].rsrc, cands[k].diag, cands[k].sure, cands[k].stereo, cands[k].cshare, cands[k].blur);
        return 0;
    }
    const sbr_synth_scene *const synth = sbr_synth_scenes;
    static const char *const real[] = {"atrium", "gallery"};
    int s, i, nc = (int)(sizeof cands / sizeof cands[0]);
    char err[256], path[512];
    for (s = 0; s < SBR_SYNTH_SCENES + 2; ++s) {
        sbr_seq seq;
        const char *nm = s < SBR_SYNTH_SCENES ? synth[s].name : real[s - SBR_SYNTH_SCENES];
        if (only && !strstr(only, nm)) continue;
        if (s < SBR_SYNTH_SCENES) {
            sbl_scene_desc d = sbr_synth_desc(&synth[s], 0);
            if (sbr_seq_synthetic(&seq, &d, nm, 1) != 0) return 1;
        } else {
            snprintf(path, sizeof path, "../shared/data/%s", nm);
            if (sbr_seq_dataset(&seq, path, 0, err, sizeof err) != 0) { printf("%s\n", err); continue; }
        }
        for (i = 0; i < nc; ++i) {
            sbr_method m;
            sbr_result r;
            char nbuf[8];
            snprintf(nbuf, sizeof nbuf, ",%d,", i);
            if (only_c && !strstr(only_c, nbuf)) continue;
            memset(&m, 0, sizeof m);
            snprintf(m.name, sizeof m.name, "%s", cands[i].name);
            m.temporal = 1;
            m.temporal_blend_ctx = &cands[i];
            if (cands[i].stereo) m.stereo = SBR_STEREO_ADAPTIVE; /* the library's default blend */
            if (cands[i].blur) {
                free(g_fetch_xy); /* scenes differ in size */
                g_fetch_xy = (float *)malloc((size_t)seq.width * seq.height * 3 * sizeof(float));
                m.fetch_xy = g_fetch_xy;
                m.temporal_blend_carry3 = blend_blur;
            }
            else if (cands[i].svgf) m.temporal_blend_carry3 = blend_svgf;
            else if (cands[i].sure) m.temporal_blend_carry = blend_sure;
            else if (cands[i].tlam > 0) m.temporal_blend_carry3 = blend_trend;
            else if (cands[i].lambda > 0) m.temporal_blend_carry = blend_carry;
            else m.temporal_blend = blend;
            memset(zsum_stats, 0, sizeof zsum_stats);
            memset(vs_stats, 0, sizeof vs_stats);
            memset(tr_stats, 0, sizeof tr_stats);
            memset(sure_stats, 0, sizeof sure_stats);
            memset(svgf_stats, 0, sizeof svgf_stats);
            memset(dg, 0, sizeof dg); memset(dg_hist, 0, sizeof dg_hist);
            memset(share_stats, 0, sizeof share_stats);
            memset(blur_stats, 0, sizeof blur_stats);
            prev_have[0] = prev_have[1] = 0; call_count = 0;
            if (sbr_run(&seq, &m, &r, NULL, NULL) != 0) return 1;
            printf("%-18s %-22s eff %6.2f  rmse %.5f", nm, cands[i].name, r.eff_spp, r.rmse);
            if (zsum_stats[2] > 0)
                printf("  Z mean %+.3f sd %.3f over-threshold %.2f %%", zsum_stats[0] / zsum_stats[2],
                       sqrt(zsum_stats[1] / zsum_stats[2] - (zsum_stats[0] / zsum_stats[2]) * (zsum_stats[0] / zsum_stats[2])),
                       100.0 * zsum_stats[3] / zsum_stats[2]);
            if (vs_stats[0] > 0)
                printf("  rho mean %.3f, geo mean %.3f", vs_stats[1] / vs_stats[0], exp(vs_stats[2] / vs_stats[0]));
            if (tr_stats[0] > 0)
                printf("  trend on %.2f %% (mean corr^2/se2 %.3f)", 100.0 * tr_stats[1] / tr_stats[0],
                       tr_stats[2] / tr_stats[0]);
            if (svgf_stats[0] > 0)
                printf("  temporal var on %.1f %%", 100.0 * svgf_stats[1] / svgf_stats[0]);
            if (share_stats[0] > 0)
                printf("  share mean %.3f, < 0.05 on %.1f %%, > 0.25 on %.1f %%", share_stats[1] / share_stats[0],
                       100 * share_stats[2] / share_stats[0], 100 * share_stats[3] / share_stats[0]);
            if (dg[3][0] > 0) {
                int k;
                printf("\n   a/a0 hist <1.01 %.2f%% <1.1 %.2f%% <1.5 %.2f%% <2 %.2f%% <4 %.2f%% <8 %.2f%% >=8 %.2f%%",
                       100 * dg_hist[0] / dg[3][0], 100 * dg_hist[1] / dg[3][0], 100 * dg_hist[2] / dg[3][0],
                       100 * dg_hist[3] / dg[3][0], 100 * dg_hist[4] / dg[3][0], 100 * dg_hist[5] / dg[3][0],
                       100 * dg_hist[6] / dg[3][0]);
                for (k = 0; k < 3; ++k)
                    printf("\n   %s: a > 1.1 a0 on %.3f%%, mean excess %.4f, sum ex^2(1+1/N) per pf %.3g, N lost per event %.2f",
                           k == 0 ? "local " : k == 1 ? "blocks" : "R     ", 100 * dg[k][0] / dg[3][0],
                           dg[k][0] > 0 ? dg[k][1] / dg[k][0] : 0, dg[k][2] / dg[3][0],
                           dg[k][0] > 0 ? dg[k][3] / dg[k][0] : 0);
            }
            if (blur_stats[0] > 0)
                printf("\n   blur: S mean %.3f, S > 0 on %.1f %%, B_b^2 / (var_x + var_y) mean %.4f, B_b^2 > b2 on %.2f %%, a mean %.4f",
                       blur_stats[1] / blur_stats[0], 100 * blur_stats[4] / blur_stats[0],
                       blur_stats[2] / blur_stats[0], 100 * blur_stats[3] / blur_stats[0],
                       blur_stats[5] / blur_stats[0]);
            if (sure_stats[0] > 0)
                printf("  t mean %.3f, t > 0 on %.1f %% | (1-a)D %.4g S %.4g dl %.4g A %.4g B %.4g",
                       sure_stats[1] / sure_stats[0], 100.0 * sure_stats[2] / sure_stats[0],
                       sure_stats[3] / sure_stats[0], sure_stats[4] / sure_stats[0],
                       sure_stats[5] / sure_stats[0], sure_stats[6] / sure_stats[0],
                       sure_stats[7] / sure_stats[0]);
            printf("\n");
            fflush(stdout);
        }
        sbr_seq_free(&seq);
    }
    return 0;
}
