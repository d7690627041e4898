/* Validation of tools/sbl_metrics.h. Prints every check; exit status 0 iff all pass.
 *   cc -std=c99 -pedantic -Wall -Wextra -Werror -O2 -Itools tests/test_metrics.c -lm -o /tmp/test_metrics
 * (also builds as C++: g++ -x c++ -std=c++11 ...). */
#define SBL_METRICS_IMPLEMENTATION
#include "sbl_metrics.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int g_fail = 0, g_count = 0;

static void check(int ok, const char *what, double got, double want)
{
    ++g_count;
    if (!ok) ++g_fail;
    printf("%s  %-52s got %.17g  want %.17g\n", ok ? "PASS" : "FAIL", what, got, want);
}

static void check_rel(const char *what, double got, double want, double rel)
{
    double tol = rel * (fabs(want) > 1.0 ? fabs(want) : 1.0);
    check(fabs(got - want) <= tol, what, got, want);
}

static void check_eq(const char *what, double got, double want)
{
    check(got == want, what, got, want);
}

/* ---- hand-computed basics ------------------------------------------------------------ */

static void test_basic(void)
{
    /* 2x2, 1 channel, stored with stride 3; the padding column is NaN so any read of it
     * would poison the result. a = [0 1; 2 3], b = [1 1; 0 3]: diffs 1, 0, -2, 0. */
    float a[6], b[6];
    float nan_ = (float)NAN;
    a[0] = 0.0f; a[1] = 1.0f; a[2] = nan_; a[3] = 2.0f; a[4] = 3.0f; a[5] = nan_;
    b[0] = 1.0f; b[1] = 1.0f; b[2] = nan_; b[3] = 0.0f; b[4] = 3.0f; b[5] = nan_;

    check_eq("mse 2x2 stride 3 = 5/4", sbl_metric_mse(a, 3, b, 3, 2, 2, 1), 1.25);
    check_eq("mae 2x2 stride 3 = 3/4", sbl_metric_mae(a, 3, b, 3, 2, 2, 1), 0.75);
    check_eq("rmse 2x2 stride 3 = sqrt(5)/2", sbl_metric_rmse(a, 3, b, 3, 2, 2, 1),
             1.1180339887498949);
    /* 10 log10(4^2 / 1.25) = 10 log10(12.8) */
    check_rel("psnr peak 4 = 10 log10(12.8)", sbl_metric_psnr(a, 3, b, 3, 2, 2, 1, 4.0),
              11.072099696478683, 1e-14);
    check_eq("psnr identical -> 999", sbl_metric_psnr(a, 3, a, 3, 2, 2, 1, 1.0), 999.0);
    check_eq("mse identical = 0", sbl_metric_mse(a, 3, a, 3, 2, 2, 1), 0.0);

    /* Same numbers seen as one pixel row of 2 channels (stride 2 rows of 2 floats each
     * would hit the NaN, so use w=1, channels=2, stride 3). */
    check_eq("mse w=1 c=2 h=2 stride 3", sbl_metric_mse(a, 3, b, 3, 1, 2, 2), 1.25);

    {   /* 3 channels, 1 pixel: diffs 0.5, -1.5, 0 -> mse (0.25 + 2.25) / 3, mae 2/3 */
        float p[3] = { 1.0f, 2.0f, 3.0f }, q[3] = { 0.5f, 3.5f, 3.0f };
        check_rel("mse 1px rgb = 2.5/3", sbl_metric_mse(p, 3, q, 3, 1, 1, 3), 2.5 / 3.0, 1e-15);
        check_rel("mae 1px rgb = 2/3", sbl_metric_mae(p, 3, q, 3, 1, 1, 3), 2.0 / 3.0, 1e-15);
        check_rel("psnr 1px rgb peak 1 = 10 log10(1.2)", sbl_metric_psnr(p, 3, q, 3, 1, 1, 3, 1.0),
                  0.79181246047624818, 1e-14);
    }

    /* bad args */
    check_eq("mse stride < w*c -> -1", sbl_metric_mse(a, 1, b, 3, 2, 2, 1), -1.0);
    check_eq("mse channels 5 -> -1", sbl_metric_mse(a, 10, b, 10, 1, 1, 5), -1.0);
    check_eq("mse NULL -> -1", sbl_metric_mse(0, 3, b, 3, 2, 2, 1), -1.0);
    check_eq("rmse bad -> -1", sbl_metric_rmse(a, 3, b, 3, 0, 2, 1), -1.0);
    check_eq("psnr peak 0 -> -999", sbl_metric_psnr(a, 3, b, 3, 2, 2, 1, 0.0), -999.0);
}

/* ---- SSIM ---------------------------------------------------------------------------- */

/* Integer image pair, identical to gen_pair() in tools/ssim_reference.py. */
static int tri(int v, int p)
{
    int r = v % (2 * p) - p;
    return r < 0 ? -r : r;
}

static void gen_pair(int w, int h, int ch, int kind, int scale_exp, uint32_t seed,
                     float *a, float *b)
{
    uint32_t s = seed;
    float scale = (float)ldexp(1.0, -scale_exp);
    int x, y, c;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (c = 0; c < ch; ++c) {
                int va, vb;
                s = s * 1664525u + 1013904223u; /* uint32_t arithmetic wraps mod 2^32 */
                va = tri(3 * x + 17 * c, 64) * tri(5 * y + x + 11 * c, 64) * 16;
                if (kind == 0) vb = va + (int)((s >> 16) % 8193u) - 4096;
                else if (kind == 1) vb = va + 3277;
                else vb = ((3 * va) >> 2) + 8192;
                /* |v| < 2^24 and scale a power of two: exact in float */
                a[(y * w + x) * ch + c] = (float)va * scale;
                b[(y * w + x) * ch + c] = (float)vb * scale;
            }
}

typedef struct {
    const char *name;
    int w, h, ch, kind, scale_exp;
    double range;
    uint32_t seed;
    double want;
} ssim_case;

/* Expected values: scikit-image structural_similarity(gaussian_weights=True, sigma=1.5,
 * use_sample_covariance=False, data_range=L, channel_axis=2 for colour) on the same
 * images as float64. Produced by tools/ssim_reference.py (output pasted as is). */
/* SSIM_REFERENCE_BEGIN */
/* skimage 0.19.3, numpy 1.24.2: tools/ssim_reference.py */
static const ssim_case k_ssim_cases[] = {
    { "gray_noise_L1", 32, 24, 1, 0, 16, 1.0, 1u, 0.71231395517005158 },
    { "gray_shift_L1", 32, 24, 1, 1, 16, 1.0, 2u, 0.79754761021701337 },
    { "gray_noise_L255", 32, 24, 1, 0, 8, 255.0, 3u, 0.7245540393572697 },
    { "rgb_noise_L1", 40, 29, 3, 0, 16, 1.0, 4u, 0.81347173100991899 },
    { "rgb_contrast_L255", 40, 29, 3, 2, 8, 255.0, 5u, 0.75536014815027375 },
    { "rgb_shift_L255", 27, 27, 3, 1, 8, 255.0, 6u, 0.82193972708874197 },
    { "gray_min11_L1", 11, 11, 1, 0, 16, 1.0, 7u, 0.93393741598374136 },
    { "rgba_noise_L1", 23, 19, 4, 0, 16, 1.0, 8u, 0.71618659691331055 },
    { "gray_tall_L2", 13, 37, 1, 2, 16, 2.0, 9u, 0.91850536732240828 },
};
/* SSIM_REFERENCE_END */

static void test_ssim(void)
{
    size_t i;
    char what[128];
    for (i = 0; i < sizeof k_ssim_cases / sizeof k_ssim_cases[0]; ++i) {
        const ssim_case *t = &k_ssim_cases[i];
        size_t n = (size_t)t->w * (size_t)t->h * (size_t)t->ch;
        float *a = (float *)malloc(n * sizeof(float));
        float *b = (float *)malloc(n * sizeof(float));
        double got;
        if (!a || !b) { check(0, "malloc", 0, 0); free(a); free(b); return; }
        gen_pair(t->w, t->h, t->ch, t->kind, t->scale_exp, t->seed, a, b);
        got = sbl_metric_ssim(a, t->w * t->ch, b, t->w * t->ch, t->w, t->h, t->ch, t->range);
        sprintf(what, "ssim vs skimage %s (%dx%dx%d)", t->name, t->w, t->h, t->ch);
        check_rel(what, got, t->want, 1e-5);
        free(a);
        free(b);
    }
}

static void test_ssim_properties(void)
{
    enum { W = 33, H = 21, C = 3, PAD = 5 };
    int stride = W * C + PAD;
    float *a = (float *)malloc((size_t)W * H * C * sizeof(float));
    float *b = (float *)malloc((size_t)W * H * C * sizeof(float));
    float *ap = (float *)malloc((size_t)stride * H * sizeof(float));
    float *bp = (float *)malloc((size_t)stride * H * sizeof(float));
    double s_same, s_noise, s_shift, s_pad;
    int i, y;
    if (!a || !b || !ap || !bp) { check(0, "malloc", 0, 0); free(a); free(b); free(ap); free(bp); return; }

    gen_pair(W, H, C, 0, 16, 42u, a, b); /* b = a + noise */
    s_same = sbl_metric_ssim(a, W * C, a, W * C, W, H, C, 1.0);
    check_rel("ssim(a, a) == 1", s_same, 1.0, 1e-12);
    s_noise = sbl_metric_ssim(a, W * C, b, W * C, W, H, C, 1.0);
    check(s_noise < 0.999 && s_noise > -1.0, "ssim(a, a + noise) < 1", s_noise, 1.0);

    gen_pair(W, H, C, 1, 16, 42u, a, b); /* b = a + constant */
    s_shift = sbl_metric_ssim(a, W * C, b, W * C, W, H, C, 1.0);
    check(s_shift < 0.9999 && s_shift > 0.0, "ssim(a, a + 0.05) < 1", s_shift, 1.0);

    /* Row stride with NaN padding must give the same number (and never read the pad). */
    for (i = 0; i < stride * H; ++i) ap[i] = bp[i] = (float)NAN;
    for (y = 0; y < H; ++y) {
        memcpy(ap + y * stride, a + y * W * C, (size_t)W * C * sizeof(float));
        memcpy(bp + y * stride, b + y * W * C, (size_t)W * C * sizeof(float));
    }
    s_pad = sbl_metric_ssim(ap, stride, bp, stride, W, H, C, 1.0);
    check_eq("ssim with padded stride == packed", s_pad, s_shift);

    check_eq("ssim w 10 -> -2", sbl_metric_ssim(a, W * C, b, W * C, 10, H, C, 1.0), -2.0);
    check_eq("ssim h 10 -> -2", sbl_metric_ssim(a, W * C, b, W * C, W, 10, C, 1.0), -2.0);
    check_eq("ssim L 0 -> -2", sbl_metric_ssim(a, W * C, b, W * C, W, H, C, 0.0), -2.0);
    check_eq("ssim NULL -> -2", sbl_metric_ssim(0, W * C, b, W * C, W, H, C, 1.0), -2.0);
    free(a); free(b); free(ap); free(bp);
}

/* ---- effective spp ------------------------------------------------------------------- */

static void test_effective_spp(void)
{
    double spp[6] = { 1, 2, 4, 8, 16, 32 }, r[6];
    int i;
    for (i = 0; i < 6; ++i) r[i] = 0.4 / sqrt(spp[i]); /* exact n^-1/2 ladder */

    check_rel("espp n^-1/2 ladder, on entry n=8", sbl_metric_effective_spp(0.4 / sqrt(8.0), spp, r, 6), 8.0, 1e-12);
    check_rel("espp n^-1/2 ladder, between n=5", sbl_metric_effective_spp(0.4 / sqrt(5.0), spp, r, 6), 5.0, 1e-12);
    check_rel("espp n^-1/2 ladder, between n=27.5", sbl_metric_effective_spp(0.4 / sqrt(27.5), spp, r, 6), 27.5, 1e-12);
    check_rel("espp extrapolate above n=100", sbl_metric_effective_spp(0.04, spp, r, 6), 100.0, 1e-12);
    check_rel("espp extrapolate below n=0.25", sbl_metric_effective_spp(0.8, spp, r, 6), 0.25, 1e-12);

    {   /* Slope -1 segment: 4 spp -> 0.2, 16 spp -> 0.05. Log-log halfway (0.1) is 8;
         * a linear-in-n interpolation would give 12, linear in rmse 4 + 12 * 2/3 = 12. */
        double s2[2] = { 4, 16 }, r2[2] = { 0.2, 0.05 };
        check_rel("espp log-log interp slope -1: rmse 0.1 -> 8", sbl_metric_effective_spp(0.1, s2, r2, 2), 8.0, 1e-12);
        /* rmse 0.2 / 2^0.5 -> n = 4 * 2^0.5 on the same line */
        check_rel("espp log-log interp slope -1: -> 4 sqrt2", sbl_metric_effective_spp(0.2 / sqrt(2.0), s2, r2, 2),
                  4.0 * sqrt(2.0), 1e-12);
        /* extrapolation keeps that segment's slope (-1): 0.025 -> 32 */
        check_rel("espp extrapolate with end slope -1: -> 32", sbl_metric_effective_spp(0.025, s2, r2, 2), 32.0, 1e-12);
    }
    {   /* Mixed ladder: the bracketing pair decides. 1 -> 0.3, 4 -> 0.15 (-1/2), 16 -> 0.0375 (-1) */
        double s3[3] = { 1, 4, 16 }, r3[3] = { 0.3, 0.15, 0.0375 };
        check_rel("espp mixed ladder, 2nd segment: 0.075 -> 8", sbl_metric_effective_spp(0.075, s3, r3, 3), 8.0, 1e-12);
        check_rel("espp mixed ladder, 1st segment: 0.3/sqrt2 -> 2", sbl_metric_effective_spp(0.3 / sqrt(2.0), s3, r3, 3), 2.0, 1e-12);
    }
    {   /* One entry: RMSE ~ n^-1/2 */
        double s1[1] = { 4 }, r1[1] = { 0.1 };
        check_rel("espp single entry: half the rmse -> 4x n", sbl_metric_effective_spp(0.05, s1, r1, 1), 16.0, 1e-12);
        check_rel("espp single entry: twice the rmse -> n/4", sbl_metric_effective_spp(0.2, s1, r1, 1), 1.0, 1e-12);
    }
    check(sbl_metric_effective_spp(1e300, spp, r, 6) > 0.0, "espp huge rmse stays > 0",
          sbl_metric_effective_spp(1e300, spp, r, 6), 0.0);
    check_eq("espp count 0 -> -1", sbl_metric_effective_spp(0.1, spp, r, 0), -1.0);
    check_eq("espp rmse < 0 -> -1", sbl_metric_effective_spp(-0.1, spp, r, 6), -1.0);
    {
        double bad[2] = { 4, 4 }, rr[2] = { 0.2, 0.1 };
        check_eq("espp non-increasing spp -> -1", sbl_metric_effective_spp(0.1, bad, rr, 2), -1.0);
    }
}

/* ---- stereo consistency -------------------------------------------------------------- */

static void test_weber(void)
{
    /* 4x2, 1 channel. Relative differences |A - B| / A per pixel:
     *   (0,0) 1.00 vs 1.01   -> 0.01   consistent
     *   (1,0) 1.00 vs 1.03   -> 0.03   inconsistent
     *   (2,0) 50   vs 51     -> 1/50 == 0.02 exactly in double: inconsistent (>=)
     *   (3,0) 0    vs 0      -> both black: consistent
     *   (0,1) 0    vs 0.1    -> black vs not: inconsistent
     *   (1,1) 2.00 vs 1.90   -> 0.05   inconsistent, but masked out
     *   (2,1) 4.00 vs 4.04   -> 0.01   consistent
     *   (3,1) -1.0 vs -1.5   -> 0.5 with |A| as denominator: inconsistent
     * All 8 valid: 5/8. With (1,1) masked out: 4/7. */
    float a[8] = { 1.0f, 1.0f, 50.0f, 0.0f, 0.0f, 2.0f, 4.0f, -1.0f };
    float b[8] = { 1.01f, 1.03f, 51.0f, 0.0f, 0.1f, 1.9f, 4.04f, -1.5f };
    unsigned char valid[8] = { 1, 1, 1, 1, 1, 0, 1, 1 };
    unsigned char none[8] = { 0, 0, 0, 0, 0, 0, 0, 0 };
    long nbad = -1, nvalid = -1;

    check_eq("weber 4x2 all valid = 5/8", sbl_metric_weber_ratio(a, 4, b, 4, 0, 4, 2, 1, 0.02), 5.0 / 8.0);
    check_eq("weber 4x2 masked = 4/7",
             sbl_metric_weber_counts(a, 4, b, 4, valid, 4, 2, 1, 0.02, &nbad, &nvalid), 4.0 / 7.0);
    check(nbad == 4 && nvalid == 7, "weber counts 4 of 7", (double)nbad, 4.0);
    check_eq("weber threshold 0.1 masked = 2/7", sbl_metric_weber_ratio(a, 4, b, 4, valid, 4, 2, 1, 0.1), 2.0 / 7.0);
    check_eq("weber no valid pixel = 0", sbl_metric_weber_ratio(a, 4, b, 4, none, 4, 2, 1, 0.02), 0.0);
    check_eq("weber negative threshold -> -1", sbl_metric_weber_ratio(a, 4, b, 4, 0, 4, 2, 1, -0.1), -1.0);
    {
        float n1[1], n2[1] = { 1.0f };
        n1[0] = (float)NAN;
        check_eq("weber NaN counts inconsistent", sbl_metric_weber_ratio(n1, 1, n2, 1, 0, 1, 1, 1, 0.02), 1.0);
    }

    {   /* RGB uses luminance: pixel 0 differs by 10 % in blue only -> 0.0722 * 0.1 / 1 < 2 %
         * (consistent); pixel 1 differs by 10 % in green -> 7.2 % (inconsistent). */
        float p[6] = { 1.0f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f };
        float q[6] = { 1.0f, 1.0f, 1.1f, 1.0f, 1.1f, 1.0f };
        check_eq("weber rgb luminance = 1/2", sbl_metric_weber_ratio(p, 6, q, 6, 0, 2, 1, 3, 0.02), 0.5);
    }
    {   /* 2 channels: channel 0 only. Pixel 0 differs only in channel 1 (ignored), pixel 1
         * by 50 % in channel 0. */
        float p[4] = { 1.0f, 1.0f, 1.0f, 1.0f };
        float q[4] = { 1.0f, 2.0f, 1.5f, 1.0f };
        check_eq("weber 2ch uses channel 0: 1/2", sbl_metric_weber_ratio(p, 4, q, 4, 0, 2, 1, 2, 0.02), 0.5);
    }

    /* Stereo difference: masked MSE. Over the masked set above (1 channel):
     * squared diffs 1e-4, 9e-4, 1, 0, 1e-2, [masked], 0.0016, 0.25 (up to float rounding). */
    {
        double want = 0.0;
        long cnt = 0;
        int i;
        for (i = 0; i < 8; ++i)
            if (valid[i]) { double d = (double)a[i] - (double)b[i]; want += d * d; }
        want /= 7.0;
        check_rel("stereo difference masked", sbl_metric_stereo_difference(a, 4, b, 4, valid, 4, 2, 1), want, 1e-15);
        check_rel("stereo difference ~ hand value 1.2626 / 7", sbl_metric_stereo_difference(a, 4, b, 4, valid, 4, 2, 1),
                  1.2626 / 7.0, 1e-6);
        sbl_metric_mse_masked(a, 4, b, 4, valid, 4, 2, 1, &cnt);
        check(cnt == 7, "mse_masked count 7", (double)cnt, 7.0);
        check_eq("stereo difference no mask == mse", sbl_metric_stereo_difference(a, 4, b, 4, 0, 4, 2, 1),
                 sbl_metric_mse(a, 4, b, 4, 4, 2, 1));
    }
}

/* The bright / dim split: which pixels count as bright, the two sums, bad args. */
static void test_bright_split(void)
{
    /* 3 x 2, 2 channels. Reference mean = 24 / 12 = 2, so factor 2 puts the threshold at
       4: pixel 1 (channel 1 = 9) and pixel 4 (channel 0 = 5) are bright. */
    const float ref[12] = { 1, 1,  0, 9,  1, 1,
                            1, 1,  5, 0,  1, 3 };
    const float out[12] = { 2, 1,  0, 6,  1, 1,
                            1, 0,  1, 0,  1, 3 };
    double sb = -1, sd = -1;
    long nb = -1;
    const double thr = sbl_metric_bright_split(out, 6, ref, 6, 3, 2, 2, 2.0, &sb, &sd, &nb);
    check_eq("bright split threshold 2 x mean", thr, 4.0);
    check(nb == 2, "bright split: two bright pixels", (double)nb, 2.0);
    check_eq("bright split: bright sum 9 + 16", sb, 25.0);
    check_eq("bright split: dim sum 1 + 1", sd, 2.0);
    check_eq("bright split: the two sums are the MSE's", (sb + sd) / 12.0, sbl_metric_mse(out, 6, ref, 6, 3, 2, 2));
    /* factor 4.5: the threshold is 9, and a value equal to it (pixel 1) is dim */
    sbl_metric_bright_split(out, 6, ref, 6, 3, 2, 2, 4.5, &sb, &sd, &nb);
    check(nb == 0, "bright split: a value equal to the threshold is dim", (double)nb, 0.0);
    check_eq("bright split: all dim", sd, 27.0);
    check_eq("bright split bad factor", sbl_metric_bright_split(out, 6, ref, 6, 3, 2, 2, 0.0, &sb, &sd, &nb), -1.0);
    check(sb == 0.0 && sd == 0.0 && nb == 0, "bright split bad args clear the outputs", sb + sd + (double)nb, 0.0);
    check_eq("bright split bad stride", sbl_metric_bright_split(out, 5, ref, 6, 3, 2, 2, 2.0, NULL, NULL, NULL), -1.0);
    {   /* the same images in padded rows (strides 8 and 10) with NaN in the padding: the
           padding is never read (a NaN there would turn a sum or the mean into NaN) */
        float pref[20], pout[16];
        int x, y;
        for (x = 0; x < 20; ++x) pref[x] = (float)NAN;
        for (x = 0; x < 16; ++x) pout[x] = (float)NAN;
        for (y = 0; y < 2; ++y)
            for (x = 0; x < 6; ++x) {
                pref[y * 10 + x] = ref[y * 6 + x];
                pout[y * 8 + x] = out[y * 6 + x];
            }
        check_eq("bright split padded: threshold", sbl_metric_bright_split(pout, 8, pref, 10, 3, 2, 2, 2.0, &sb, &sd, &nb), 4.0);
        check(nb == 2, "bright split padded: two bright pixels", (double)nb, 2.0);
        check_eq("bright split padded: bright sum", sb, 25.0);
        check_eq("bright split padded: dim sum", sd, 2.0);
    }
}

int main(void)
{
    test_basic();
    test_bright_split();
    test_ssim();
    test_ssim_properties();
    test_effective_spp();
    test_weber();
    printf("%d/%d checks passed\n", g_count - g_fail, g_count);
    return g_fail ? 1 : 0;
}
