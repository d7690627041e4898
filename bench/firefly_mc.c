/* When does the firefly limit pay? (docs/ESTIMATORS.md 2.1, session 23.) A pixel's 1-spp
   samples are a body N(0.5, 0.1^2) plus, with probability p, a spike of F = 30 (its
   true mean 0.5 + p F). Each pixel keeps a progressive history (weight 1 / (N + 1), N
   capped at 63, as the default converges on static content) and the limit caps the new
   sample at 0.5 + kappa sigma sqrt(N + 1), kappa = 6 (the header's bound, its mean term
   taken as exact). Three sigmas for the bound:
     none     no limit (the plain mean: unbiased, the spike's variance p F^2 / N)
     body     the body's spread, which is what a 3x3 window's eight neighbours show when
              spikes are rarer than 1/8 (the header today)
     pool36   the spread of 36 other samples of the same distribution, as the pooled
              estimator's four side blocks (columns x +- 2..7 of three rows) would give:
              sqrt(body^2 + k F^2 / 36 (1 - k / 36)), k ~ Binomial(36, p)
   Prints the history's mean squared error against the true mean after it has converged
   (frames 200..400, 20000 pixels). Limiting removes the bias p (F - U) from every
   sample and the variance p F^2 from the history: it pays while p^2 F^2 < p F^2 / N,
   i.e. while spikes are rarer than one per history length (p < 1 / N).
   cc -O2 bench/firefly_mc.c -o build/firefly_mc -lm && ./build/firefly_mc */
#include <math.h>
#include <stdio.h>
#include "mc_rng.h"

static double gauss(void) /* Box-Muller, one of the pair */
{
    return sqrt(-2.0 * log(uniform01())) * cos(6.283185307179586 * uniform01());
}

enum { PIXELS = 20000, FRAMES = 400, SETTLED = 200, POOL = 36 };

int main(void)
{
    static const double rates[] = {0.001, 0.003, 0.01, 0.02, 0.05, 0.1};
    static const char *const names[3] = {"none", "body", "pool36"};
    static double hist[PIXELS], count[PIXELS];
    const double body = 0.1, spike = 30.0, kappa = 6.0;
    int r, mode;
    printf("spike rate p   1/p    history MSE: none / body / pool36\n");
    for (r = 0; r < (int)(sizeof rates / sizeof rates[0]); ++r) {
        const double p = rates[r], mu = 0.5 + p * spike;
        printf("%12.3f %5.0f   ", p, 1.0 / p);
        for (mode = 0; mode < 3; ++mode) {
            double se = 0.0;
            long n_se = 0;
            int i, t;
            for (i = 0; i < PIXELS; ++i) hist[i] = count[i] = 0.0;
            for (t = 0; t < FRAMES; ++t)
                for (i = 0; i < PIXELS; ++i) {
                    double y = 0.5 + body * gauss() + (uniform01() < p ? spike : 0.0);
                    const double n = count[i] < 63.0 ? count[i] : 63.0;
                    double sigma = body;
                    if (mode == 2) {
                        int j, k = 0;
                        for (j = 0; j < POOL; ++j) k += uniform01() < p;
                        sigma = sqrt(body * body + k * spike * spike / POOL * (1.0 - (double)k / POOL));
                    }
                    if (mode > 0) {
                        const double bound = 0.5 + kappa * sigma * sqrt(n + 1.0);
                        if (y > bound) y = bound;
                    }
                    hist[i] = count[i] == 0.0 ? y : hist[i] + (y - hist[i]) / (n + 1.0);
                    count[i] += 1.0;
                    if (t >= SETTLED) { se += (hist[i] - mu) * (hist[i] - mu); ++n_se; }
                }
            printf(" %s %.4f", names[mode], se / (double)n_se);
        }
        printf("\n");
    }
    return 0;
}
