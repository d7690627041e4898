/* sbl_metrics.h - image metrics for the stereoblend tools, tests and bench.
 *
 * stb-style single file: declarations always; in ONE C or C++ file
 *     #define SBL_METRICS_IMPLEMENTATION
 *     #include "sbl_metrics.h"
 * Define SBL_METRICS_STATIC as well to give every function internal linkage.
 *
 * Images are interleaved float arrays: `channels` (1-4) values per pixel, `stride`
 * floats from the start of one row to the next (stride >= w * channels). All sums are
 * accumulated in double. These are tools, not the library: SSIM allocates with malloc.
 *
 * Error returns (so a bad call never looks like a good score):
 *   mse / rmse / mae / stereo_difference / weber_ratio / effective_spp : -1
 *   psnr : -999 (a real PSNR can be negative)      ssim : -2 (SSIM lies in [-1, 1])
 */
#ifndef SBL_METRICS_H
#define SBL_METRICS_H

#ifdef SBL_METRICS_STATIC
#define SBL_METRICS_DEF static
#else
#define SBL_METRICS_DEF extern
#endif

#define SBL_METRIC_BAD_ARGS      (-1.0)
#define SBL_METRIC_PSNR_BAD_ARGS (-999.0)
#define SBL_METRIC_PSNR_EXACT    999.0   /* returned when mse == 0 instead of +inf */
#define SBL_METRIC_SSIM_BAD_ARGS (-2.0)
#define SBL_METRIC_SSIM_WINDOW   11      /* minimum w and h for SSIM */
#define SBL_METRIC_WEBER_THRESHOLD 0.02  /* Wu 2023: 2 % relative difference */

#ifdef __cplusplus
extern "C" {
#endif

/* Mean over all w*h*channels values of (a-b)^2, sqrt of that, mean |a-b|. */
SBL_METRICS_DEF double sbl_metric_mse (const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels);
SBL_METRICS_DEF double sbl_metric_rmse(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels);
SBL_METRICS_DEF double sbl_metric_mae (const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels);

/* 10 log10(peak^2 / mse); 999 when mse == 0; -999 on bad args (incl. peak <= 0). */
SBL_METRICS_DEF double sbl_metric_psnr(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels, double peak);

/* MSE over the pixels with valid[y*w + x] != 0 (valid == NULL: all pixels), averaged over
 * channels too. *out_count (may be NULL) receives the number of pixels used.
 * Returns 0 when no pixel is valid (check the count), -1 on bad args. */
SBL_METRICS_DEF double sbl_metric_mse_masked(const float *a, int stride_a, const float *b, int stride_b,
                                             const unsigned char *valid, int w, int h, int channels,
                                             long *out_count);

/* The squared error split by the reference b: "bright" pixels, where a channel of b
 * exceeds factor times b's mean over all its values (sub-pixel highlights, light
 * sources), and the dim rest. *sse_bright and *sse_dim receive the sums of (a - b)^2 over
 * every channel of each set, *n_bright the bright pixels' count (any may be NULL).
 * Returns the threshold (factor times the mean), -1 on bad args (factor <= 0 too;
 * the outputs are then 0). On renders with unclamped direct light a few dozen bright
 * pixels can hold nearly all of an image's squared error (docs/ESTIMATORS.md 2.6). */
SBL_METRICS_DEF double sbl_metric_bright_split(const float *a, int stride_a, const float *b, int stride_b,
                                               int w, int h, int channels, double factor,
                                               double *sse_bright, double *sse_dim, long *n_bright);

/* SSIM (Wang et al. 2004): 11x11 Gaussian window, sigma 1.5, weights normalised to sum 1,
 * K1 = 0.01, K2 = 0.03, C1 = (K1 L)^2, C2 = (K2 L)^2 with L = dynamic_range given by the
 * caller (the values are used as given: no rescaling, no colour conversion). Local
 * moments are population (biased) moments. The SSIM map is computed only where the whole
 * window lies inside the image (the "valid" region, (w-10) x (h-10) pixels, as in the
 * original MATLAB ssim.m; skimage gets the same by cropping 5 pixels after filtering),
 * averaged there, then averaged over channels.
 * Needs w, h >= 11. Returns -2 on bad args or when malloc fails. */
SBL_METRICS_DEF double sbl_metric_ssim(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels, double dynamic_range);

/* Effective spp (Makitalo et al. 2019): the n at which a plain n-spp render has RMSE `rmse`,
 * read off a measured ladder (spp[i] strictly increasing, rmse_ladder[i] its RMSE), linear
 * in log(n)-log(rmse) between the bracketing entries. Outside the ladder: extrapolate with
 * the log-log slope of the nearest two entries; with one entry, or when that slope is not
 * negative (noisy ladder), assume RMSE ~ n^-1/2. A flat bracketing segment returns the
 * geometric mean of its two n. Result clamped to >= DBL_MIN; rmse == 0 returns HUGE_VAL.
 * Returns -1 on bad args (NULL, count < 1, rmse < 0 or NaN, non-positive or non-increasing
 * ladder entries). */
SBL_METRICS_DEF double sbl_metric_effective_spp(double rmse, const double *spp,
                                                const double *rmse_ladder, int count);

/* Weber stereo inconsistency ratio (Wu 2023, Eq. 2): share of the pixels with a valid
 * correspondence (valid[y*w + x] != 0; valid == NULL: all) for which
 *     |A(p) - A(p*)| / A(p) >= threshold        (threshold: 0.02 in the paper)
 * where a holds A (one eye) and b_reprojected holds A(p*) (the other eye already
 * reprojected into this one). A is channel 0 for 1-2 channels, luminance
 * 0.2126 R + 0.7152 G + 0.0722 B for 3-4 channels (alpha ignored).
 * A(p) <= 0, explicitly: A(p) == 0 -> consistent iff A(p*) == 0 (both black is consistent,
 * anything against black is inconsistent); A(p) < 0 (possible after filtering) uses |A(p)|
 * as the denominator. A NaN / inf in either eye counts as inconsistent.
 * Returns 0 when no pixel is valid, -1 on bad args (incl. threshold < 0 or NaN).
 * The _counts form also reports the counts (either pointer may be NULL). */
SBL_METRICS_DEF double sbl_metric_weber_ratio(const float *a, int stride_a,
                                              const float *b_reprojected, int stride_b,
                                              const unsigned char *valid, int w, int h, int channels,
                                              double threshold);
SBL_METRICS_DEF double sbl_metric_weber_counts(const float *a, int stride_a,
                                               const float *b_reprojected, int stride_b,
                                               const unsigned char *valid, int w, int h, int channels,
                                               double threshold, long *out_inconsistent,
                                               long *out_valid);

/* Reprojected stereo difference (Philippi 2023, Fig. 2): mean squared difference between an
 * eye and the other eye reprojected into it, over the valid pixels and all channels
 * (= sbl_metric_mse_masked). 0 when no pixel is valid, -1 on bad args. */
SBL_METRICS_DEF double sbl_metric_stereo_difference(const float *a, int stride_a,
                                                    const float *b_reprojected, int stride_b,
                                                    const unsigned char *valid, int w, int h,
                                                    int channels);

#ifdef __cplusplus
}
#endif

#endif /* SBL_METRICS_H */

/* ====================================================================================== */
#ifdef SBL_METRICS_IMPLEMENTATION
#ifndef SBL_METRICS_IMPLEMENTATION_DONE
#define SBL_METRICS_IMPLEMENTATION_DONE

#include <float.h>
#include <math.h>
#include <stdlib.h>

#ifdef __cplusplus
extern "C" {
#endif

static int sbl__metric_args_ok(const float *a, int stride_a, const float *b, int stride_b,
                               int w, int h, int channels)
{
    if (!a || !b || w < 1 || h < 1 || channels < 1 || channels > 4) return 0;
    /* Compare in long so w * channels cannot overflow an int check. */
    if ((long)stride_a < (long)w * channels || (long)stride_b < (long)w * channels) return 0;
    return 1;
}

/* Shared loop for mse (squared = 1) and mae (squared = 0). */
static double sbl__metric_mean_err(const float *a, int stride_a, const float *b, int stride_b,
                                   int w, int h, int channels, int squared)
{
    double sum = 0.0;
    int x, y, n = w * channels;
    if (!sbl__metric_args_ok(a, stride_a, b, stride_b, w, h, channels)) return SBL_METRIC_BAD_ARGS;
    for (y = 0; y < h; ++y) {
        const float *ra = a + (size_t)y * (size_t)stride_a;
        const float *rb = b + (size_t)y * (size_t)stride_b;
        double row = 0.0; /* per-row partial sums keep the big sum's rounding small */
        for (x = 0; x < n; ++x) {
            double d = (double)ra[x] - (double)rb[x];
            row += squared ? d * d : fabs(d);
        }
        sum += row;
    }
    return sum / ((double)n * (double)h);
}

SBL_METRICS_DEF double sbl_metric_mse(const float *a, int stride_a, const float *b, int stride_b,
                                      int w, int h, int channels)
{
    return sbl__metric_mean_err(a, stride_a, b, stride_b, w, h, channels, 1);
}

SBL_METRICS_DEF double sbl_metric_rmse(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels)
{
    double m = sbl_metric_mse(a, stride_a, b, stride_b, w, h, channels);
    return m < 0.0 ? SBL_METRIC_BAD_ARGS : sqrt(m);
}

SBL_METRICS_DEF double sbl_metric_mae(const float *a, int stride_a, const float *b, int stride_b,
                                      int w, int h, int channels)
{
    return sbl__metric_mean_err(a, stride_a, b, stride_b, w, h, channels, 0);
}

SBL_METRICS_DEF double sbl_metric_psnr(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels, double peak)
{
    double m;
    if (!(peak > 0.0)) return SBL_METRIC_PSNR_BAD_ARGS;
    m = sbl_metric_mse(a, stride_a, b, stride_b, w, h, channels);
    if (m < 0.0) return SBL_METRIC_PSNR_BAD_ARGS;
    if (m == 0.0) return SBL_METRIC_PSNR_EXACT;
    return 10.0 * log10(peak * peak / m);
}

SBL_METRICS_DEF double sbl_metric_mse_masked(const float *a, int stride_a, const float *b, int stride_b,
                                             const unsigned char *valid, int w, int h, int channels,
                                             long *out_count)
{
    double sum = 0.0;
    long count = 0;
    int x, y, c;
    if (out_count) *out_count = 0;
    if (!sbl__metric_args_ok(a, stride_a, b, stride_b, w, h, channels)) return SBL_METRIC_BAD_ARGS;
    for (y = 0; y < h; ++y) {
        const float *ra = a + (size_t)y * (size_t)stride_a;
        const float *rb = b + (size_t)y * (size_t)stride_b;
        const unsigned char *rv = valid ? valid + (size_t)y * (size_t)w : 0;
        double row = 0.0;
        for (x = 0; x < w; ++x) {
            if (rv && !rv[x]) continue;
            for (c = 0; c < channels; ++c) {
                double d = (double)ra[x * channels + c] - (double)rb[x * channels + c];
                row += d * d;
            }
            ++count;
        }
        sum += row;
    }
    if (out_count) *out_count = count;
    return count ? sum / ((double)count * (double)channels) : 0.0;
}

SBL_METRICS_DEF double sbl_metric_bright_split(const float *a, int stride_a, const float *b, int stride_b,
                                               int w, int h, int channels, double factor,
                                               double *sse_bright, double *sse_dim, long *n_bright)
{
    double mean = 0.0, thr, sb = 0.0, sd = 0.0;
    long nb = 0;
    int x, y, c;
    if (sse_bright) *sse_bright = 0.0;
    if (sse_dim) *sse_dim = 0.0;
    if (n_bright) *n_bright = 0;
    if (!sbl__metric_args_ok(a, stride_a, b, stride_b, w, h, channels) || !(factor > 0.0))
        return SBL_METRIC_BAD_ARGS;
    for (y = 0; y < h; ++y) {
        const float *rb = b + (size_t)y * (size_t)stride_b;
        for (x = 0; x < w * channels; ++x) mean += (double)rb[x];
    }
    thr = factor * mean / ((double)w * (double)h * (double)channels);
    for (y = 0; y < h; ++y) {
        const float *ra = a + (size_t)y * (size_t)stride_a;
        const float *rb = b + (size_t)y * (size_t)stride_b;
        for (x = 0; x < w; ++x) {
            double se = 0.0;
            int bright = 0;
            for (c = 0; c < channels; ++c) {
                const double d = (double)ra[x * channels + c] - (double)rb[x * channels + c];
                se += d * d;
                if ((double)rb[x * channels + c] > thr) bright = 1;
            }
            if (bright) { sb += se; ++nb; }
            else sd += se;
        }
    }
    if (sse_bright) *sse_bright = sb;
    if (sse_dim) *sse_dim = sd;
    if (n_bright) *n_bright = nb;
    return thr;
}

/* ---- SSIM ---------------------------------------------------------------------------- */

#define SBL__SSIM_R 5 /* window radius: 11 taps */

SBL_METRICS_DEF double sbl_metric_ssim(const float *a, int stride_a, const float *b, int stride_b,
                                       int w, int h, int channels, double dynamic_range)
{
    double g[2 * SBL__SSIM_R + 1];
    double gsum = 0.0, c1, c2, total = 0.0;
    double *buf;
    int vw, vh, c, x, y, k;
    size_t plane;

    if (!sbl__metric_args_ok(a, stride_a, b, stride_b, w, h, channels)) return SBL_METRIC_SSIM_BAD_ARGS;
    if (w < SBL_METRIC_SSIM_WINDOW || h < SBL_METRIC_SSIM_WINDOW) return SBL_METRIC_SSIM_BAD_ARGS;
    if (!(dynamic_range > 0.0) || dynamic_range > DBL_MAX) return SBL_METRIC_SSIM_BAD_ARGS;

    for (k = -SBL__SSIM_R; k <= SBL__SSIM_R; ++k) {
        g[k + SBL__SSIM_R] = exp(-(double)(k * k) / (2.0 * 1.5 * 1.5));
        gsum += g[k + SBL__SSIM_R];
    }
    for (k = 0; k < 2 * SBL__SSIM_R + 1; ++k) g[k] /= gsum;

    c1 = 0.01 * dynamic_range; c1 *= c1;
    c2 = 0.03 * dynamic_range; c2 *= c2;

    /* Only valid outputs are computed, so no border rule is needed. Horizontal pass: all h
     * rows x vw columns of the 5 moments (a, b, aa, bb, ab); the vertical pass then reads
     * 11 of those rows per output row. */
    vw = w - 2 * SBL__SSIM_R;
    vh = h - 2 * SBL__SSIM_R;
    plane = (size_t)vw * (size_t)h;
    buf = (double *)malloc(5u * plane * sizeof(double));
    if (!buf) return SBL_METRIC_SSIM_BAD_ARGS;

    for (c = 0; c < channels; ++c) {
        double chan_sum = 0.0;
        double *ha = buf, *hb = buf + plane, *haa = buf + 2 * plane;
        double *hbb = buf + 3 * plane, *hab = buf + 4 * plane;

        for (y = 0; y < h; ++y) {
            const float *ra = a + (size_t)y * (size_t)stride_a + c;
            const float *rb = b + (size_t)y * (size_t)stride_b + c;
            size_t o = (size_t)y * (size_t)vw;
            for (x = 0; x < vw; ++x) {
                double sa = 0.0, sb = 0.0, saa = 0.0, sbb = 0.0, sab = 0.0;
                for (k = 0; k < 2 * SBL__SSIM_R + 1; ++k) {
                    double va = (double)ra[(x + k) * channels];
                    double vb = (double)rb[(x + k) * channels];
                    double wk = g[k];
                    sa += wk * va;
                    sb += wk * vb;
                    saa += wk * va * va;
                    sbb += wk * vb * vb;
                    sab += wk * va * vb;
                }
                size_t ox = o + (size_t)x;
                ha[ox] = sa; hb[ox] = sb;
                haa[ox] = saa; hbb[ox] = sbb; hab[ox] = sab;
            }
        }

        for (y = 0; y < vh; ++y) {
            double row_sum = 0.0;
            for (x = 0; x < vw; ++x) {
                double ma = 0.0, mb = 0.0, maa = 0.0, mbb = 0.0, mab = 0.0;
                double va, vb, cov, num, den;
                for (k = 0; k < 2 * SBL__SSIM_R + 1; ++k) {
                    size_t o = (size_t)(y + k) * (size_t)vw + (size_t)x;
                    double wk = g[k];
                    ma += wk * ha[o];
                    mb += wk * hb[o];
                    maa += wk * haa[o];
                    mbb += wk * hbb[o];
                    mab += wk * hab[o];
                }
                va = maa - ma * ma;
                vb = mbb - mb * mb;
                cov = mab - ma * mb;
                num = (2.0 * ma * mb + c1) * (2.0 * cov + c2);
                den = (ma * ma + mb * mb + c1) * (va + vb + c2);
                row_sum += num / den;
            }
            chan_sum += row_sum;
        }
        total += chan_sum / ((double)vw * (double)vh);
    }
    free(buf);
    return total / (double)channels;
}

#undef SBL__SSIM_R

/* ---- effective spp ------------------------------------------------------------------- */

static double sbl__metric_clamp_spp(double ln_n)
{
    double n = exp(ln_n); /* overflow gives HUGE_VAL, which is an honest answer */
    return n < DBL_MIN ? DBL_MIN : n;
}

SBL_METRICS_DEF double sbl_metric_effective_spp(double rmse, const double *spp,
                                                const double *rmse_ladder, int count)
{
    double lr, slope;
    int i, lo, anchor;

    if (!spp || !rmse_ladder || count < 1 || !(rmse >= 0.0)) return SBL_METRIC_BAD_ARGS;
    for (i = 0; i < count; ++i) {
        if (!(spp[i] > 0.0) || !(rmse_ladder[i] > 0.0) || spp[i] > DBL_MAX || rmse_ladder[i] > DBL_MAX)
            return SBL_METRIC_BAD_ARGS;
        if (i > 0 && !(spp[i] > spp[i - 1])) return SBL_METRIC_BAD_ARGS;
    }
    if (rmse == 0.0) return HUGE_VAL;
    if (rmse > DBL_MAX) return DBL_MIN; /* infinite error: clamp to the smallest positive n */
    lr = log(rmse);

    /* First segment that brackets rmse (either orientation, so a slightly non-monotone
     * measured ladder still works). */
    for (i = 0; i + 1 < count; ++i) {
        double r0 = rmse_ladder[i], r1 = rmse_ladder[i + 1];
        if ((rmse <= r0 && rmse >= r1) || (rmse >= r0 && rmse <= r1)) {
            double l0 = log(r0), l1 = log(r1);
            double n0 = log(spp[i]), n1 = log(spp[i + 1]);
            if (l0 == l1) return sbl__metric_clamp_spp(0.5 * (n0 + n1));
            return sbl__metric_clamp_spp(n0 + (lr - l0) * (n1 - n0) / (l1 - l0));
        }
    }

    /* Not bracketed: extrapolate from the nearer end. More error than the first entry
     * means fewer samples than the first entry, otherwise more than the last. */
    anchor = (rmse > rmse_ladder[0]) ? 0 : count - 1;
    slope = -0.5;
    if (count > 1) {
        lo = anchor == 0 ? 0 : count - 2;
        slope = (log(rmse_ladder[lo + 1]) - log(rmse_ladder[lo])) / (log(spp[lo + 1]) - log(spp[lo]));
        if (!(slope < 0.0)) slope = -0.5; /* a flat or rising segment cannot be inverted */
    }
    return sbl__metric_clamp_spp(log(spp[anchor]) + (lr - log(rmse_ladder[anchor])) / slope);
}

/* ---- stereo consistency -------------------------------------------------------------- */

static double sbl__metric_luma(const float *p, int channels)
{
    if (channels < 3) return (double)p[0];
    return 0.2126 * (double)p[0] + 0.7152 * (double)p[1] + 0.0722 * (double)p[2];
}

SBL_METRICS_DEF double sbl_metric_weber_counts(const float *a, int stride_a,
                                               const float *b_reprojected, int stride_b,
                                               const unsigned char *valid, int w, int h, int channels,
                                               double threshold, long *out_inconsistent,
                                               long *out_valid)
{
    long nvalid = 0, nbad = 0;
    int x, y;
    if (out_inconsistent) *out_inconsistent = 0;
    if (out_valid) *out_valid = 0;
    if (!sbl__metric_args_ok(a, stride_a, b_reprojected, stride_b, w, h, channels)) return SBL_METRIC_BAD_ARGS;
    if (!(threshold >= 0.0)) return SBL_METRIC_BAD_ARGS;
    for (y = 0; y < h; ++y) {
        const float *ra = a + (size_t)y * (size_t)stride_a;
        const float *rb = b_reprojected + (size_t)y * (size_t)stride_b;
        const unsigned char *rv = valid ? valid + (size_t)y * (size_t)w : 0;
        for (x = 0; x < w; ++x) {
            double la, lb, diff;
            int bad;
            if (rv && !rv[x]) continue;
            ++nvalid;
            la = sbl__metric_luma(ra + x * channels, channels);
            lb = sbl__metric_luma(rb + x * channels, channels);
            diff = fabs(la - lb);
            if (la == 0.0)
                bad = (lb != 0.0); /* a NaN lb compares != 0 too: inconsistent */
            else
                /* !(rel < t) rather than rel >= t: a NaN or inf anywhere makes rel NaN or
                 * inf, which must count as inconsistent. */
                bad = !(diff / fabs(la) < threshold);
            nbad += bad;
        }
    }
    if (out_inconsistent) *out_inconsistent = nbad;
    if (out_valid) *out_valid = nvalid;
    return nvalid ? (double)nbad / (double)nvalid : 0.0;
}

SBL_METRICS_DEF double sbl_metric_weber_ratio(const float *a, int stride_a,
                                              const float *b_reprojected, int stride_b,
                                              const unsigned char *valid, int w, int h, int channels,
                                              double threshold)
{
    return sbl_metric_weber_counts(a, stride_a, b_reprojected, stride_b, valid, w, h, channels,
                                   threshold, 0, 0);
}

SBL_METRICS_DEF double sbl_metric_stereo_difference(const float *a, int stride_a,
                                                    const float *b_reprojected, int stride_b,
                                                    const unsigned char *valid, int w, int h,
                                                    int channels)
{
    return sbl_metric_mse_masked(a, stride_a, b_reprojected, stride_b, valid, w, h, channels, 0);
}

#ifdef __cplusplus
}
#endif

#endif /* SBL_METRICS_IMPLEMENTATION_DONE */
#endif /* SBL_METRICS_IMPLEMENTATION */
