/* The Monte Carlo programs' random numbers (bench/evidence_null.c, bench/firefly_mc.c,
   bench/sparse_bias.c):
   xorshift64, one stream per program, deterministic. */
#ifndef SBL_BENCH_MC_RNG_H
#define SBL_BENCH_MC_RNG_H
#include <math.h>

static unsigned long long rng_state = 88172645463325252ull;

static double uniform01(void) /* xorshift64, (0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return ((double)(rng_state >> 11) + 0.5) / 9007199254740992.0;
}
#endif
