/* make bench-gather: hardware gathers against per-lane loads and an in-register
   transpose, the two ways the lane paths can read taps at scattered indices (the
   decision behind sbl__gather_pairs and sbl__gatheri, session 18). Reads the same
   floats both ways and checks that the sums agree; prints ns per vector, the best of
   50 passes over 64 K indices (each index one or zero pixels left of its lane's own,
   as random sub-pixel motion makes them), for:
     pairs   the 6 floats of two packed RGB taps per lane (x0 and x0 + 1)
     floats  one float per lane
   at 8 lanes (AVX2) and, where the CPU has it, 16 lanes (AVX-512F).
   usage: gather_mb   (x86-64 with gcc or clang; AVX2 required) */
#define _POSIX_C_SOURCE 200809L
#include <immintrin.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define N (1 << 16)
static float buf[N * 3 + 64];
static int idx[N];

static double now_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

/* the timed loops stay out of line; their helpers are inlined into them */
#define AVX2 __attribute__((target("avx2,fma"), noinline))
#define AVX512 __attribute__((target("avx512f,avx2,fma"), noinline))
#define AVX2_INLINE __attribute__((target("avx2,fma"), always_inline)) inline
#define AVX512_INLINE __attribute__((target("avx512f,avx2,fma"), always_inline)) inline

static float hsum8(__m256 a) __attribute__((target("avx2")));
static float hsum8(__m256 a)
{
    float t[8], s = 0.0f;
    int i;
    _mm256_storeu_ps(t, a);
    for (i = 0; i < 8; ++i) s += t[i];
    return s;
}

/* ---- 8 lanes --------------------------------------------------------------------- */
AVX2 static float pairs_gather8(void)
{
    __m256 acc = _mm256_setzero_ps();
    int i, k;
    for (i = 0; i < N; i += 8) {
        const __m128i lo = _mm_loadu_si128((const __m128i *)(idx + i));
        const __m128i hi = _mm_loadu_si128((const __m128i *)(idx + i + 4));
        for (k = 0; k < 3; ++k) {
            const double *p = (const double *)(const void *)(buf + 2 * k);
            const __m256 a = _mm256_castpd_ps(_mm256_i32gather_pd(p, lo, 4));
            const __m256 b = _mm256_castpd_ps(_mm256_i32gather_pd(p, hi, 4));
            acc = _mm256_add_ps(acc, _mm256_add_ps(_mm256_shuffle_ps(a, b, 0x88), _mm256_shuffle_ps(a, b, 0xdd)));
        }
    }
    return hsum8(acc);
}

/* (written out, as in the header: vector arrays in loops went through the stack) */
#define QUAD8(j) _mm256_set_m128(_mm_loadu_ps(buf + q[(j) + 4]), _mm_loadu_ps(buf + q[j]))
#define TWO(j) \
    _mm_loadh_pi(_mm_castsi128_ps(_mm_loadl_epi64((const __m128i *)(const void *)(buf + q[2 * (j)] + 4))), \
                 (const __m64 *)(const void *)(buf + q[2 * (j) + 1] + 4))
AVX2 static float pairs_loads8(void)
{
    __m256 acc = _mm256_setzero_ps();
    int i;
    for (i = 0; i < N; i += 8) {
        const int *q = idx + i;
        const __m256 v0 = QUAD8(0), v1 = QUAD8(1), v2 = QUAD8(2), v3 = QUAD8(3);
        const __m256 t0 = _mm256_unpacklo_ps(v0, v1), t1 = _mm256_unpackhi_ps(v0, v1);
        const __m256 t2 = _mm256_unpacklo_ps(v2, v3), t3 = _mm256_unpackhi_ps(v2, v3);
        const __m256 e = _mm256_set_m128(TWO(2), TWO(0)), f = _mm256_set_m128(TWO(3), TWO(1));
        acc = _mm256_add_ps(acc, _mm256_add_ps(_mm256_add_ps(t0, t1), _mm256_add_ps(t2, t3)));
        acc = _mm256_add_ps(acc, _mm256_add_ps(_mm256_shuffle_ps(e, f, 0x88), _mm256_shuffle_ps(e, f, 0xdd)));
    }
    return hsum8(acc);
}

AVX2 static float floats_gather8(void)
{
    __m256 acc = _mm256_setzero_ps();
    int i;
    for (i = 0; i < N; i += 8)
        acc = _mm256_add_ps(acc, _mm256_i32gather_ps(buf, _mm256_loadu_si256((const __m256i *)(idx + i)), 4));
    return hsum8(acc);
}

AVX2_INLINE static __m128 load4_at(const int *q)
{
    const __m128 a = _mm_unpacklo_ps(_mm_load_ss(buf + q[0]), _mm_load_ss(buf + q[1]));
    const __m128 c = _mm_unpacklo_ps(_mm_load_ss(buf + q[2]), _mm_load_ss(buf + q[3]));
    return _mm_movelh_ps(a, c);
}

AVX2 static float floats_loads8(void)
{
    __m256 acc = _mm256_setzero_ps();
    int i;
    for (i = 0; i < N; i += 8) acc = _mm256_add_ps(acc, _mm256_set_m128(load4_at(idx + i + 4), load4_at(idx + i)));
    return hsum8(acc);
}

/* ---- 16 lanes -------------------------------------------------------------------- */
AVX512_INLINE static __m512 join8(__m256 lo, __m256 hi)
{
    return _mm512_castpd_ps(_mm512_insertf64x4(_mm512_castpd256_pd512(_mm256_castps_pd(lo)), _mm256_castps_pd(hi), 1));
}

AVX512 static float pairs_gather16(void)
{
    __m512 acc = _mm512_setzero_ps();
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    const __m512i odd = _mm512_add_epi32(even, _mm512_set1_epi32(1));
    int i, k;
    for (i = 0; i < N; i += 16) {
        const __m256i lo = _mm256_loadu_si256((const __m256i *)(idx + i));
        const __m256i hi = _mm256_loadu_si256((const __m256i *)(idx + i + 8));
        for (k = 0; k < 3; ++k) {
            const __m512 a = _mm512_castpd_ps(_mm512_i32gather_pd(lo, buf + 2 * k, 4));
            const __m512 b = _mm512_castpd_ps(_mm512_i32gather_pd(hi, buf + 2 * k, 4));
            acc = _mm512_add_ps(acc, _mm512_add_ps(_mm512_permutex2var_ps(a, even, b), _mm512_permutex2var_ps(a, odd, b)));
        }
    }
    return _mm512_reduce_add_ps(acc);
}

#define QUAD16(j) \
    join8(_mm256_set_m128(_mm_loadu_ps(buf + q[(j) + 4]), _mm_loadu_ps(buf + q[j])), \
          _mm256_set_m128(_mm_loadu_ps(buf + q[(j) + 12]), _mm_loadu_ps(buf + q[(j) + 8])))
AVX512 static float pairs_loads16(void)
{
    __m512 acc = _mm512_setzero_ps();
    int i;
    for (i = 0; i < N; i += 16) {
        const int *q = idx + i;
        const __m512 v0 = QUAD16(0), v1 = QUAD16(1), v2 = QUAD16(2), v3 = QUAD16(3);
        const __m512 t0 = _mm512_unpacklo_ps(v0, v1), t1 = _mm512_unpackhi_ps(v0, v1);
        const __m512 t2 = _mm512_unpacklo_ps(v2, v3), t3 = _mm512_unpackhi_ps(v2, v3);
        const __m512 e = join8(_mm256_set_m128(TWO(2), TWO(0)), _mm256_set_m128(TWO(6), TWO(4)));
        const __m512 f = join8(_mm256_set_m128(TWO(3), TWO(1)), _mm256_set_m128(TWO(7), TWO(5)));
        acc = _mm512_add_ps(acc, _mm512_add_ps(_mm512_add_ps(t0, t1), _mm512_add_ps(t2, t3)));
        acc = _mm512_add_ps(acc, _mm512_add_ps(_mm512_shuffle_ps(e, f, 0x88), _mm512_shuffle_ps(e, f, 0xdd)));
    }
    return _mm512_reduce_add_ps(acc);
}

AVX512 static float floats_gather16(void)
{
    __m512 acc = _mm512_setzero_ps();
    int i;
    for (i = 0; i < N; i += 16) acc = _mm512_add_ps(acc, _mm512_i32gather_ps(_mm512_loadu_si512(idx + i), buf, 4));
    return _mm512_reduce_add_ps(acc);
}

AVX512 static float floats_loads16(void)
{
    __m512 acc = _mm512_setzero_ps();
    int i;
    for (i = 0; i < N; i += 16)
        acc = _mm512_add_ps(acc, join8(_mm256_set_m128(load4_at(idx + i + 4), load4_at(idx + i)),
                                       _mm256_set_m128(load4_at(idx + i + 12), load4_at(idx + i + 8))));
    return _mm512_reduce_add_ps(acc);
}

/* best of 50 passes, ns per vector of `lanes`; *sum: the pass's result */
static double best_ns(float (*f)(void), int lanes, float *sum)
{
    double best = 1e30;
    int r;
    for (r = 0; r < 50; ++r) {
        const double t0 = now_ns();
        *sum = f();
        const double t = now_ns() - t0;
        if (t < best) best = t;
    }
    return best / (N / lanes);
}

static int row(const char *what, int lanes, float (*g)(void), float (*l)(void))
{
    float sg, sl;
    const double tg = best_ns(g, lanes, &sg), tl = best_ns(l, lanes, &sl);
    printf("%-7s %2d lanes   gather %6.2f ns   loads + transpose %6.2f ns   gather / loads %.2f%s\n", what, lanes, tg,
           tl, tg / tl, sg == sl ? "" : "   (SUMS DIFFER)");
    return sg == sl;
}

int main(void)
{
    unsigned s = 1u;
    int i, ok = 1;
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2")) {
        printf("gather_mb: no AVX2 on this CPU, nothing measured\n");
        return 0;
    }
    /* small integers: every sum exact, so both ways agree whatever the lane order */
    for (i = 0; i < N * 3 + 64; ++i) buf[i] = (float)(i % 7);
    for (i = 0; i < N; ++i) {
        int x;
        s = s * 1664525u + 1013904223u;
        x = i - (int)((s >> 20) & 1u);
        idx[i] = 3 * (x < 0 ? 0 : x);
    }
    ok &= row("pairs", 8, pairs_gather8, pairs_loads8);
    ok &= row("floats", 8, floats_gather8, floats_loads8);
    if (__builtin_cpu_supports("avx512f")) {
        ok &= row("pairs", 16, pairs_gather16, pairs_loads16);
        ok &= row("floats", 16, floats_gather16, floats_loads16);
    } else {
        printf("(no AVX-512F: 16 lanes not measured)\n");
    }
    return ok ? 0 : 1;
}
