/* Tiny test harness shared by the tests: counts checks, prints failures with their
   location, ends with the "N passed, N failed" line CI reads. */
#ifndef SBL_TEST_H
#define SBL_TEST_H
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__) || defined(__clang__)
#define SBT_FN static __attribute__((unused)) /* each test uses a subset */
#else
#define SBT_FN static
#endif

static int sbt_passed, sbt_failed;

#define CHECK(cond) sbt_check((cond) != 0, #cond, __FILE__, __LINE__)
#define CHECK_EQ(a, b) sbt_check_eq((long)(a), (long)(b), #a " == " #b, __FILE__, __LINE__)
#define CHECK_NEAR(a, b, tol) sbt_check_near((double)(a), (double)(b), (double)(tol), #a " ~ " #b, __FILE__, __LINE__)

SBT_FN void sbt_check(int ok, const char *what, const char *file, int line)
{
    if (ok) { ++sbt_passed; return; }
    ++sbt_failed;
    printf("FAIL %s:%d: %s\n", file, line, what);
}
SBT_FN void sbt_check_eq(long a, long b, const char *what, const char *file, int line)
{
    if (a == b) { ++sbt_passed; return; }
    ++sbt_failed;
    printf("FAIL %s:%d: %s (%ld vs %ld)\n", file, line, what, a, b);
}
SBT_FN void sbt_check_near(double a, double b, double tol, const char *what, const char *file, int line)
{
    if (fabs(a - b) <= tol) { ++sbt_passed; return; }
    ++sbt_failed;
    printf("FAIL %s:%d: %s (%.9g vs %.9g, tol %.3g)\n", file, line, what, a, b, tol);
}
SBT_FN int sbt_finish(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, sbt_passed, sbt_failed);
    return sbt_failed ? 1 : 0;
}

/* Deterministic random numbers (xorshift64*), uniform and Gaussian. */
typedef struct sbt_rng { unsigned long long s; } sbt_rng;
SBT_FN double sbt_uniform(sbt_rng *r)
{
    r->s ^= r->s >> 12; r->s ^= r->s << 25; r->s ^= r->s >> 27;
    return (double)((r->s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}
SBT_FN double sbt_gauss(sbt_rng *r)
{
    double u = sbt_uniform(r), v = sbt_uniform(r);
    if (u < 1e-300) u = 1e-300;
    return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

/* An image with `pad` canary floats after every row, allocated at exactly its size so
   that ASan / valgrind catch any over-read. */
#define SBT_CANARY 1234567.0f
typedef struct sbt_img { float *mem; int w, h, c, stride; } sbt_img;
SBT_FN sbt_img sbt_img_new(int w, int h, int c, int pad)
{
    sbt_img im;
    size_t n = (size_t)(w * c + pad) * (size_t)h, i;
    im.w = w; im.h = h; im.c = c; im.stride = w * c + pad;
    im.mem = (float *)malloc(n * sizeof(float));
    for (i = 0; i < n; ++i) im.mem[i] = SBT_CANARY;
    {
        int x, y;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w * c; ++x) im.mem[(size_t)y * im.stride + x] = 0.0f;
    }
    return im;
}
SBT_FN float *sbt_at(const sbt_img *im, int x, int y) { return im->mem + (size_t)y * im->stride + (size_t)x * im->c; }
SBT_FN int sbt_canaries_ok(const sbt_img *im)
{
    int x, y;
    for (y = 0; y < im->h; ++y)
        for (x = im->w * im->c; x < im->stride; ++x)
            if (im->mem[(size_t)y * im->stride + x] != SBT_CANARY) return 0;
    return 1;
}

#ifdef SBL_VERSION_MAJOR /* (after stereoblend.h) */
/* A library view of a test image */
SBT_FN sbl_image sbt_view(const sbt_img *im)
{
    sbl_image v;
    memset(&v, 0, sizeof v);
    v.data = im->mem; v.width = im->w; v.height = im->h; v.channels = im->c; v.stride = im->stride;
    return v;
}

/* A 3-channel view of `src` (3 channels, w x h) in layout `lay`: 0 packed, 1 the first
   three of four channels, 2 channels 1 .. 3 of five, bottom-up, 3 packed bottom-up; `pad`
   canary floats per row (but none in layout 0). *mem gets the buffer to free. */
SBT_FN sbl_image sbt_view3_layout(const sbt_img *src, int lay, int pad, float **mem)
{
    const int w = src->w, h = src->h, c = lay == 1 ? 4 : lay == 2 ? 5 : 3, off = lay == 2 ? 1 : 0;
    sbt_img b = sbt_img_new(w, h, c, lay == 0 ? 0 : pad);
    sbl_image v;
    int x, y, k;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < 3; ++k) sbt_at(&b, x, y)[off + k] = sbt_at(src, x, y)[k];
    v = sbt_view(&b);
    v.channels = 3;
    v.pixel_bytes = c * (int)sizeof(float);
    v.data = b.mem + off;
    if (lay >= 2) {
        v.data = sbt_at(&b, 0, h - 1) + off;
        v.stride = -b.stride;
    }
    *mem = b.mem;
    return v;
}

/* A 1-channel view of `src` (1 channel) in layout `lay`: 0 packed, 1 channel 1 of two,
   2 `pad` canary floats per row. *mem gets the buffer to free. */
SBT_FN sbl_image sbt_view1_layout(const sbt_img *src, int lay, int pad, float **mem)
{
    const int w = src->w, h = src->h, c = lay == 1 ? 2 : 1;
    sbt_img b = sbt_img_new(w, h, c, lay == 2 ? pad : 0);
    sbl_image v;
    int x, y;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) sbt_at(&b, x, y)[c - 1] = *sbt_at(src, x, y);
    v = sbt_view(&b);
    v.channels = 1;
    v.pixel_bytes = c * (int)sizeof(float);
    v.data = b.mem + (c - 1);
    *mem = b.mem;
    return v;
}
#endif
#endif
