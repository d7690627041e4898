/* The carried evidence R's false-alarm rate where nothing changes (docs/ESTIMATORS.md 4.14,
   stereoblend.h SBL__EVIDENCE_FALSE_ALARM): P(R > c_R) under the pooled blocks' own null
   model, the one-frame ratio q ~ Exp(1) (the tail e^-q behind the blocks' threshold
   c + ln M), carried as R = R* + lambda (q - R*) with the header's bounded step
   q <= R* + (c_b - 1) / lambda, lambda = 1/3, c_b = SBL_POOLED_BLOCK_SE2_REGION = 2.5 (the
   blocks' threshold where the plane is; 3.5 before session 36), and c_R = 1 + (c - 1)
   sqrt(lambda / (2 - lambda)), c = SBL_POOLED_BLOCK_SE2 = 3.5. Monte Carlo over one long
   stationary run.
   cc -O2 bench/evidence_null.c -o build/evidence_null -lm && ./build/evidence_null */
#include <math.h>
#include <stdio.h>
#include "mc_rng.h"

int main(void)
{
    const double lam = 1.0 / 3.0, c = 3.5, c_b = 2.5, kap = lam / (2.0 - lam), c_r = 1.0 + (c - 1.0) * sqrt(kap);
    const long samples = 200000000L, burn = 1000;
    double r = 1.0, above = 0.0, n = 0.0, var = 0.0;
    long i;
    for (i = 0; i < samples; ++i) {
        double q = -log(uniform01());
        if (q > r + (c_b - 1.0) / lam) q = r + (c_b - 1.0) / lam;
        r += lam * (q - r);
        if (i < burn) continue;
        n += 1.0;
        above += r > c_r;
        var += (r - 1.0) * (r - 1.0);
    }
    printf("c_R %.4f: P(R > c_R) %.4f (R's variance %.4f, kappa %.4f; a Gaussian R's tail %.4f)\n", c_r,
           above / n, var / n, kap, 0.5 * erfc((c - 1.0) / sqrt(2.0)));
    return 0;
}
