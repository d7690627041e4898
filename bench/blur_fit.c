/* The resampling blur's noise factor G(n, v) (docs/ESTIMATORS.md 4.12, 4.13): the fit
   stereoblend.h evaluates in lanes, and its error against the exact sum.

   g(s): the variance of a second difference [1 -2 1] of unit white noise blurred by a
   Gaussian of variance s, (1 / 2 pi) int_{-pi}^{pi} 16 sin^4(w / 2) e^{-s w^2} dw (6 at
   s = 0). G(n, v) = (1 / n) sum_{k < n} g(k v) (bench/proto_estimators.c's blur_g, here
   by quadrature, not a table). The header's form is Euler-Maclaurin's,
       G ~ J(t) + (6 - g(t)) / (2 n) + v (g'(t) - g'(0)) / (12 n),   t = n v,
   J(t) the mean of g over [0, t]; written as three functions of r = 1 / sqrt(1 + t)
   (r in (0, 1]: t = 0 at r = 1, t = inf at r = 0), each smooth in r (g ~ t^-2.5 = r^5
   ..., J's tail ~ t^-1.5 ~ r^3):
       G = r^2 A(r) + (1 / n) (H(r) + v K(r)),
       A = J (1 + t), H = (6 - g) / 2, K = (g' - g'(0)) / 12,
   each a polynomial fitted by least squares on r in [0, 1] (Chebyshev basis, then
   monomials for Horner). Prints the coefficients and the fitted G's largest relative
   error (evaluated in float, the header's order of operations) against the exact sum
   over n = 1 .. 200, v in (0, 1/4], next to Euler-Maclaurin's own (exact A, H, K).

   usage: ./build/blur_fit [degree]     (cc -O2 bench/blur_fit.c -o build/blur_fit -lm) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define QN 4000 /* Simpson intervals on [-pi, pi] (the integrands are smooth: 1e-12 relative) */

/* (1 / 2 pi) int 16 sin^4(w / 2) m(w) dw, m chosen by kind at s: 0 e^{-s w^2} (g),
   1 -w^2 e^{-s w^2} (g'), 2 (1 - e^{-s w^2}) / (s w^2) (J; 1 at s = 0) */
static double quad(int kind, double s)
{
    double acc = 0.0;
    int i;
    for (i = 0; i <= QN; ++i) {
        const double w = -PI + i * (2.0 * PI / QN), sn = sin(0.5 * w), q = 16.0 * sn * sn * sn * sn;
        const double x = s * w * w;
        double m;
        if (kind == 0) m = exp(-x);
        else if (kind == 1) m = -w * w * exp(-x);
        else m = x < 1e-8 ? 1.0 - 0.5 * x : -expm1(-x) / x;
        acc += (i == 0 || i == QN ? 1.0 : (i & 1) ? 4.0 : 2.0) * q * m;
    }
    return acc * (2.0 * PI / QN) / 3.0 / (2.0 * PI);
}

/* at r in (0, 1]: t = 1 / r^2 - 1; r = 0 is t = inf (A's limit int_0^inf g, H = 3, K = -g'(0) / 12) */
static double g_at(double t) { return quad(0, t); }
static double fA(double r, double gp0)
{
    (void)gp0;
    if (r <= 0.0) { /* int_0^inf g = (1 / 2 pi) int 16 sin^4(w / 2) / w^2 dw */
        double acc = 0.0;
        int i;
        for (i = 1; i <= QN; ++i) {
            const double w = i * (PI / QN), sn = sin(0.5 * w);
            acc += (i == QN ? 1.0 : (i & 1) ? 4.0 : 2.0) * 16.0 * sn * sn * sn * sn / (w * w);
        }
        return acc * (PI / QN) / 3.0 / PI;
    }
    {
        const double t = 1.0 / (r * r) - 1.0;
        return quad(2, t) * (1.0 + t);
    }
}
static double fH(double r, double gp0)
{
    (void)gp0;
    return r <= 0.0 ? 3.0 : 0.5 * (6.0 - g_at(1.0 / (r * r) - 1.0));
}
static double fK(double r, double gp0)
{
    return ((r <= 0.0 ? 0.0 : quad(1, 1.0 / (r * r) - 1.0)) - gp0) / 12.0;
}

#define NS 801 /* fit samples in r */

/* weights: each function's error as it reaches G relative, at the smallest n that takes
   r (n >= 4 t: v <= 1/4), with J(t) ~ G: A relative (r^2 / J = 1 / A), H / (n J),
   v K / n = t K / (n^2 J) */
static double jt(double r) { return r * r * fA(r, 0.0); }
static double w_A(double r) { return 1.0 / fA(r, 0.0); }
static double w_H(double r)
{
    const double t = r > 0.0 ? 1.0 / (r * r) - 1.0 : 1e30, n = 4.0 * t > 1.0 ? 4.0 * t : 1.0;
    return r > 0.0 ? 1.0 / (n * jt(r)) : 0.0;
}
static double w_K(double r)
{
    const double t = r > 0.0 ? 1.0 / (r * r) - 1.0 : 1e30, n = 4.0 * t > 1.0 ? 4.0 * t : 1.0;
    return r > 0.0 ? t / (n * n * jt(r)) : 0.0;
}
#define MAXD 16

/* least squares of f on Chebyshev T_j(2 r - 1), j <= d, by normal equations in long double
   (d <= 16 on 801 Chebyshev-spaced points: well conditioned), then monomial coefficients */
/* T[j][k]: the coefficient of r^k in the Chebyshev polynomial T_j(2 r - 1), j, k <= d */
static void cheb_monomials(double T[MAXD + 1][MAXD + 1], int d)
{
    int j, k;
    for (j = 0; j <= d; ++j)
        for (k = 0; k <= d; ++k) T[j][k] = 0.0;
    T[0][0] = 1.0;
    if (d > 0) { T[1][0] = -1.0; T[1][1] = 2.0; }
    for (j = 2; j <= d; ++j)
        for (k = 0; k <= j; ++k)
            T[j][k] = 2.0 * ((k > 0 ? 2.0 * T[j - 1][k - 1] : 0.0) - T[j - 1][k]) - T[j - 2][k];
}

static void fit(double (*f)(double, double), double (*wt)(double), double gp0, int d, double *mono)
{
    static double rs[NS], fs[NS], ws[NS];
    long double M[MAXD + 1][MAXD + 2];
    double cheb[MAXD + 1], T[MAXD + 1][MAXD + 1];
    int i, j, k;
    for (i = 0; i < NS; ++i) {
        rs[i] = 0.5 - 0.5 * cos(PI * (i + 0.5) / NS);
        fs[i] = f(rs[i], gp0);
        ws[i] = wt(rs[i]);
        ws[i] *= ws[i];
    }
    for (j = 0; j <= d; ++j)
        for (k = 0; k <= d + 1; ++k) M[j][k] = 0.0L;
    for (i = 0; i < NS; ++i) {
        double b[MAXD + 1];
        const double x = 2.0 * rs[i] - 1.0;
        b[0] = 1.0;
        if (d > 0) b[1] = x;
        for (j = 2; j <= d; ++j) b[j] = 2.0 * x * b[j - 1] - b[j - 2];
        for (j = 0; j <= d; ++j) {
            for (k = 0; k <= d; ++k) M[j][k] += (long double)ws[i] * b[j] * b[k];
            M[j][d + 1] += (long double)ws[i] * b[j] * fs[i];
        }
    }
    for (j = 0; j <= d; ++j) { /* Gauss-Jordan */
        int p = j;
        for (k = j + 1; k <= d; ++k)
            if (fabsl(M[k][j]) > fabsl(M[p][j])) p = k;
        for (k = 0; k <= d + 1; ++k) { long double s = M[j][k]; M[j][k] = M[p][k]; M[p][k] = s; }
        for (i = 0; i <= d; ++i) {
            long double q;
            if (i == j) continue;
            q = M[i][j] / M[j][j];
            for (k = j; k <= d + 1; ++k) M[i][k] -= q * M[j][k];
        }
    }
    for (j = 0; j <= d; ++j) cheb[j] = (double)(M[j][d + 1] / M[j][j]);
    cheb_monomials(T, d);
    for (k = 0; k <= d; ++k) {
        mono[k] = 0.0;
        for (j = k; j <= d; ++j) mono[k] += cheb[j] * T[j][k];
    }
}

/* The three polynomials at once, by least squares of G's relative error against the
   exact sums on the grid (n = 1 .. 200, v = 1/4 iv / nv): absorbs Euler-Maclaurin's own
   error (its remainder at small n) into the coefficients. ex[iv][n]: the exact sums. */
/* v on (0, 1/4]: quadratic spacing, v = 0 included (G = 6 there: S = 0 makes it moot, but v
   may come as close to 0 as a fetch comes to an integer position) */
#define VAT(iv, nv) (0.25 * ((double)(iv) / (nv)) * ((double)(iv) / (nv)))
#define NBIG 60 /* n from 200 to 2e5, geometric, where Euler-Maclaurin's remainder is negligible */
static double big_n(int i) { return 200.0 * pow(1000.0, (i + 1.0) / NBIG); }
static void fit_joint(int d, int nv, double **ex, double **exb, double *A, double *H, double *K)
{
    const int m = 3 * (d + 1);
    static long double M[3 * (MAXD + 1)][3 * (MAXD + 1) + 1];
    double cheb[3 * (MAXD + 1)], T[MAXD + 1][MAXD + 1];
    int iv, n, j, k, i;
    for (j = 0; j < m; ++j)
        for (k = 0; k <= m; ++k) M[j][k] = 0.0L;
    for (iv = 0; iv <= nv; ++iv)
        for (n = 1; n <= 200 + NBIG; ++n) {
            const double nn = n <= 200 ? n : big_n(n - 201), v = VAT(iv, nv), t = nn * v;
            const double r = 1.0 / sqrt(1.0 + t), x = 2.0 * r - 1.0;
            const double w = 1.0 / (n <= 200 ? ex[iv][n] : exb[iv][n - 201]);
            double b[MAXD + 1], row[3 * (MAXD + 1)];
            b[0] = 1.0;
            if (d > 0) b[1] = x;
            for (j = 2; j <= d; ++j) b[j] = 2.0 * x * b[j - 1] - b[j - 2];
            for (j = 0; j <= d; ++j) {
                row[j] = w * r * r * b[j];
                row[d + 1 + j] = w * b[j] / nn;
                row[2 * (d + 1) + j] = w * v * b[j] / nn;
            }
            for (j = 0; j < m; ++j) {
                for (k = 0; k < m; ++k) M[j][k] += (long double)row[j] * row[k];
                M[j][m] += (long double)row[j] * 1.0; /* w * exact */
            }
        }
    for (j = 0; j < m; ++j) {
        int p = j;
        for (k = j + 1; k < m; ++k)
            if (fabsl(M[k][j]) > fabsl(M[p][j])) p = k;
        for (k = 0; k <= m; ++k) { long double s = M[j][k]; M[j][k] = M[p][k]; M[p][k] = s; }
        for (i = 0; i < m; ++i) {
            long double q;
            if (i == j) continue;
            q = M[i][j] / M[j][j];
            for (k = j; k <= m; ++k) M[i][k] -= q * M[j][k];
        }
    }
    for (j = 0; j < m; ++j) cheb[j] = (double)(M[j][m] / M[j][j]);
    cheb_monomials(T, d);
    for (k = 0; k <= d; ++k) {
        A[k] = H[k] = K[k] = 0.0;
        for (j = k; j <= d; ++j) {
            A[k] += cheb[j] * T[j][k];
            H[k] += cheb[d + 1 + j] * T[j][k];
            K[k] += cheb[2 * (d + 1) + j] * T[j][k];
        }
    }
}

static float horner(const float *c, int d, float r)
{
    float p = c[d];
    int j;
    for (j = d - 1; j >= 0; --j) p = p * r + c[j];
    return p;
}

int main(int argc, char **argv)
{
    /* degree, then "sep" (each function fitted to its own exact values) or "joint" */
    const int d = argc > 1 ? atoi(argv[1]) : 7, joint = !(argc > 2 && argv[2][0] == 's');
    const int nv = 250;
    const double gp0 = quad(1, 0.0);
    double A[MAXD + 1], H[MAXD + 1], K[MAXD + 1], **ex, **exb, worst_big = 0.0;
    float Af[MAXD + 1], Hf[MAXD + 1], Kf[MAXD + 1];
    double worst_fit = 0.0, worst_em = 0.0, wn_fit = 0, wv_fit = 0, wn_em = 0, wv_em = 0;
    double worst_fit_n4 = 0.0;
    int j, iv, n;
    if (d < 1 || d > MAXD) return 1;
    /* the exact sums, v = 1/4 iv / nv, n = 1 .. 200 (by their running sum) */
    ex = malloc((nv + 1) * sizeof *ex);
    for (iv = 0; iv <= nv; ++iv) {
        const double v = VAT(iv, nv);
        double sum = 0.0;
        ex[iv] = malloc(201 * sizeof **ex);
        for (n = 1; n <= 200; ++n) ex[iv][n] = (sum += g_at((n - 1) * v)) / n;
    }
    /* n above 200: Euler-Maclaurin with the exact functions stands for the sum */
    exb = malloc((nv + 1) * sizeof *exb);
    for (iv = 0; iv <= nv; ++iv) {
        const double v = VAT(iv, nv);
        exb[iv] = malloc(NBIG * sizeof **exb);
        for (j = 0; j < NBIG; ++j) {
            const double nn = big_n(j), r = 1.0 / sqrt(1.0 + nn * v);
            exb[iv][j] = r * r * fA(r, gp0) + (fH(r, gp0) + v * fK(r, gp0)) / nn;
        }
    }
    if (joint) {
        fit_joint(d, nv, ex, exb, A, H, K);
    } else {
        fit(fA, w_A, gp0, d, A);
        fit(fH, w_H, gp0, d, H);
        fit(fK, w_K, gp0, d, K);
    }
    for (j = 0; j <= d; ++j) { Af[j] = (float)A[j]; Hf[j] = (float)H[j]; Kf[j] = (float)K[j]; }
    printf("g'(0) = %.9g, int_0^inf g = %.9g\n", gp0, fA(0.0, gp0));
    printf("degree %d (%s fit), monomial coefficients (r^0 first):\n", d, joint ? "joint" : "separate");
    printf("A:");
    for (j = 0; j <= d; ++j) printf(" %.9g", A[j]);
    printf("\nH:");
    for (j = 0; j <= d; ++j) printf(" %.9g", H[j]);
    printf("\nK:");
    for (j = 0; j <= d; ++j) printf(" %.9g", K[j]);
    printf("\n");
    for (iv = 0; iv <= nv; ++iv)
        for (n = 1; n <= 200; ++n) {
            const double v = VAT(iv, nv), t = n * v, r = 1.0 / sqrt(1.0 + t), exact = ex[iv][n];
            /* the fit in float, as the header evaluates it */
            const float tf = (float)n * (float)v, rf = 1.0f / sqrtf(1.0f + tf), inf = 1.0f / (float)n;
            const float gf = rf * rf * horner(Af, d, rf) + inf * (horner(Hf, d, rf) + (float)v * horner(Kf, d, rf));
            const double e_fit = fabs(gf / exact - 1.0);
            if (e_fit > worst_fit) { worst_fit = e_fit; wn_fit = n; wv_fit = v; }
            if (n >= 4 && e_fit > worst_fit_n4) worst_fit_n4 = e_fit;
            if (!joint) { /* Euler-Maclaurin with the exact functions */
                const double em = r * r * fA(r, gp0) + (fH(r, gp0) + v * fK(r, gp0)) / n;
                const double e_em = fabs(em / exact - 1.0);
                if (e_em > worst_em) { worst_em = e_em; wn_em = n; wv_em = v; }
            }
        }
    for (iv = 0; iv <= nv; ++iv)
        for (j = 0; j < NBIG; ++j) {
            const double v = VAT(iv, nv);
            const float tf = (float)big_n(j) * (float)v, rf = 1.0f / sqrtf(1.0f + tf), inf = 1.0f / (float)big_n(j);
            const float gf = rf * rf * horner(Af, d, rf) + inf * (horner(Hf, d, rf) + (float)v * horner(Kf, d, rf));
            if (fabs(gf / exb[iv][j] - 1.0) > worst_big) worst_big = fabs(gf / exb[iv][j] - 1.0);
        }
    printf("n in (200, 2e5] against Euler-Maclaurin (exact functions): %.5f\n", worst_big);
    printf("n in [1, 200], v in [0, 1/4] (%d values, quadratic spacing): largest relative error against the exact sum\n", nv + 1);
    if (!joint) printf("  Euler-Maclaurin, exact functions: %.5f (n %g, v %.4f)\n", worst_em, wn_em, wv_em);
    printf("  the fit, in float: %.5f (n %g, v %.4f); n >= 4: %.5f\n", worst_fit, wn_fit, wv_fit, worst_fit_n4);
    return 0;
}
