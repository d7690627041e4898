/* Robustness tests: input sanitising (non-finite colour, depth, normals, ids, motion,
   lengths, cameras, parameters), HDR numerics (1e-30 .. 1e30 in one image, constant
   images), a double-precision reference of the whole temporal filter compared with the
   float implementation on random scenes, 10,000-frame accumulation with a derived drift
   bound, the denormal cost, and regression tests for header bugs and fuzzer finds.

   Every image is allocated at its exact size ((h - 1) * stride + w * c floats) with the
   row padding poisoned with a NaN pattern, so ASan / valgrind see any over-read and a
   read of the padding shows up as a non-finite output.

   Must build as C99 (-pedantic -Werror), as C++, at -O0, -O3 -march=native and with
   -ffast-math: finiteness is tested on the bit pattern here too (-ffast-math may fold
   isfinite() to 1), and gcc's -ffast-math links crtfastmath.o, which sets FTZ/DAZ, so
   the denormal expectations ask the FPU which mode it is in. */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"
#include <float.h>
#include <limits.h>
#include <time.h>

#ifdef __FAST_MATH__
#define FAST_MATH 1
#else
#define FAST_MATH 0
#endif

/* ---- floats by bit pattern --------------------------------------------------------- */

static float f_bits(unsigned int u) { float f; memcpy(&f, &u, sizeof f); return f; }
static unsigned int bits_f(float f) { unsigned int u; memcpy(&u, &f, sizeof u); return u; }
static float f_nan(void) { return f_bits(0x7fc00000u); }
static float f_inf(void) { return f_bits(0x7f800000u); }
static float f_ninf(void) { return f_bits(0xff800000u); }
static float f_snan(void) { return f_bits(0x7f800001u); }
static int fin(float f) { return (bits_f(f) & 0x7f800000u) != 0x7f800000u; }
static int dfin(double d)
{
    unsigned long long u;
    memcpy(&u, &d, sizeof u);
    return (u & 0x7ff0000000000000ULL) != 0x7ff0000000000000ULL;
}
static int is_pinf(float f) { return bits_f(f) == 0x7f800000u; }
static int is_nan_bits(float f) { return (bits_f(f) & 0x7fffffffu) > 0x7f800000u; }

/* 1 when the FPU flushes denormal results / inputs to zero (FTZ/DAZ, e.g. gcc's
   -ffast-math start-up code); the volatile keeps the compiler from folding it. */
static int ftz_mode(void)
{
    volatile float tiny = f_bits(0x00800000u); /* FLT_MIN */
    volatile float half = 0.5f;
    float r = tiny * half;
    volatile float den = f_bits(0x00000100u);
    float s = den + den;
    return r == 0.0f || s == 0.0f;
}

/* ---- exact-size images ------------------------------------------------------------- */

#define PAD_BITS 0x7fa5a5a5u /* a NaN: padding that is read poisons the result */

typedef struct rimg { float *mem; int w, h, c, stride; size_t n; } rimg;

static rimg rimg_new(int w, int h, int c, int pad)
{
    rimg im;
    size_t i;
    int x, y;
    im.w = w; im.h = h; im.c = c; im.stride = w * c + pad;
    im.n = (size_t)(h - 1) * (size_t)im.stride + (size_t)w * (size_t)c;
    im.mem = (float *)malloc(im.n * sizeof(float));
    for (i = 0; i < im.n; ++i) im.mem[i] = f_bits(PAD_BITS);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w * c; ++x) im.mem[(size_t)y * im.stride + x] = 0.0f;
    return im;
}
static void rimg_free(rimg *im) { free(im->mem); im->mem = NULL; }
static float *px(const rimg *im, int x, int y) { return im->mem + (size_t)y * im->stride + (size_t)x * im->c; }
static sbl_image vw(const rimg *im)
{
    sbl_image v;
    memset(&v, 0, sizeof v);
    v.data = im->mem; v.width = im->w; v.height = im->h; v.channels = im->c; v.stride = im->stride;
    return v;
}
static void rimg_fill(rimg *im, float v)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k) px(im, x, y)[k] = v;
}
static int rimg_pad_ok(const rimg *im)
{
    int x, y;
    for (y = 0; y + 1 < im->h; ++y)
        for (x = im->w * im->c; x < im->stride; ++x)
            if (bits_f(im->mem[(size_t)y * im->stride + x]) != PAD_BITS) return 0;
    return 1;
}
static int rimg_finite(const rimg *im)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k)
                if (!fin(px(im, x, y)[k])) return 0;
    return 1;
}

/* ---- a temporal test scene ---------------------------------------------------------- */

typedef struct tscene {
    int w, h, c;
    rimg cur, depth, mv, nrm, ids;      /* current frame                          */
    rimg hist, hlen, pdepth, pnrm, pids;/* history                                */
    rimg outc, outn, outa;              /* outputs                                */
    int use_nrm, use_ids, use_hlen, use_pdepth, use_depth;
} tscene;

static void ts_init(tscene *s, int w, int h, int c)
{
    memset(s, 0, sizeof *s);
    s->w = w; s->h = h; s->c = c;
    s->cur = rimg_new(w, h, c, 1);
    s->depth = rimg_new(w, h, 1, 2);
    s->mv = rimg_new(w, h, 2, 1);
    s->nrm = rimg_new(w, h, 3, 0);
    s->ids = rimg_new(w, h, 1, 1);
    s->hist = rimg_new(w, h, c, 2);
    s->hlen = rimg_new(w, h, 1, 0);
    s->pdepth = rimg_new(w, h, 1, 1);
    s->pnrm = rimg_new(w, h, 3, 2);
    s->pids = rimg_new(w, h, 1, 0);
    s->outc = rimg_new(w, h, c, 3);
    s->outn = rimg_new(w, h, 1, 1);
    s->outa = rimg_new(w, h, 1, 2);
    rimg_fill(&s->depth, 2.0f);
    rimg_fill(&s->pdepth, 2.0f);
    rimg_fill(&s->hlen, 4.0f);
    s->use_hlen = s->use_pdepth = s->use_depth = 1;
}
static void ts_free(tscene *s)
{
    rimg_free(&s->cur); rimg_free(&s->depth); rimg_free(&s->mv); rimg_free(&s->nrm);
    rimg_free(&s->ids); rimg_free(&s->hist); rimg_free(&s->hlen); rimg_free(&s->pdepth);
    rimg_free(&s->pnrm); rimg_free(&s->pids); rimg_free(&s->outc); rimg_free(&s->outn);
    rimg_free(&s->outa);
}
static void ts_views(const tscene *s, sbl_frame *f, sbl_history *h, sbl_temporal_output *o)
{
    memset(f, 0, sizeof *f);
    memset(h, 0, sizeof *h);
    memset(o, 0, sizeof *o);
    f->color = vw(&s->cur);
    f->gbuffer.motion = vw(&s->mv);
    if (s->use_depth) f->gbuffer.depth = vw(&s->depth);
    if (s->use_nrm) { f->gbuffer.normals = vw(&s->nrm); h->gbuffer.normals = vw(&s->pnrm); }
    if (s->use_ids) { f->gbuffer.ids = vw(&s->ids); h->gbuffer.ids = vw(&s->pids); }
    h->color = vw(&s->hist);
    if (s->use_hlen) h->length = vw(&s->hlen);
    if (s->use_pdepth) h->gbuffer.depth = vw(&s->pdepth);
    o->color = vw(&s->outc);
    o->length = vw(&s->outn);
    o->alpha = vw(&s->outa);
}
static sbl_result ts_run(tscene *s, const sbl_temporal_desc *d, int with_history)
{
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    ts_views(s, &f, &h, &o);
    return sbl_temporal_filter_frame(d, &f, with_history ? &h : NULL, &o);
}
static int ts_outputs_sane(const tscene *s, float max_history)
{
    int x, y, ok = rimg_finite(&s->outc) && rimg_finite(&s->outn) && rimg_finite(&s->outa);
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            float n = *px(&s->outn, x, y), a = *px(&s->outa, x, y);
            ok &= n >= 0.0f && n <= max_history && a >= 0.0f && a <= 1.0f;
        }
    ok &= rimg_pad_ok(&s->outc) && rimg_pad_ok(&s->outn) && rimg_pad_ok(&s->outa);
    return ok;
}
/* noisy colour around `base`, deterministic */
static void ts_noisy(tscene *s, rimg *im, sbt_rng *rng, double base, double sigma)
{
    int x, y, k;
    (void)s;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k)
                px(im, x, y)[k] = (float)(base + sigma * (sbt_uniform(rng) * 2.0 - 1.0));
}
static int same_bits(const float *a, const float *b, int n)
{
    return memcmp(a, b, sizeof(float) * (size_t)n) == 0;
}

/* Bit-identical, except that under FTZ/DAZ a denormal equals the zero it is read as. */
static int same_value(const float *a, const float *b, int n)
{
    int k, ok = 1;
    if (!ftz_mode()) return same_bits(a, b, n);
    for (k = 0; k < n; ++k) {
        unsigned int ua = bits_f(a[k]), ub = bits_f(b[k]);
        if ((ua & 0x7f800000u) == 0) ua &= 0x80000000u; /* denormal -> signed zero */
        if ((ub & 0x7f800000u) == 0) ub &= 0x80000000u;
        ok &= (ua & 0x7fffffffu) == 0 ? (ub & 0x7fffffffu) == 0 : ua == ub;
    }
    return ok;
}

/* ======================================================================== */
/* Sanitising: colour                                                        */
/* ======================================================================== */

static void test_sanitise_color(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbt_rng rng = {1234};
    int x, y, k;
    memset(&d, 0, sizeof d);
    ts_init(&s, 7, 6, 3);
    ts_noisy(&s, &s.cur, &rng, 0.25, 0.05);
    rimg_fill(&s.hist, 0.25f);
    /* non-finite new samples: NaN, +inf, -inf, a signalling NaN */
    px(&s.cur, 2, 2)[1] = f_nan();
    px(&s.cur, 4, 3)[0] = f_inf();
    px(&s.cur, 5, 1)[2] = f_ninf();
    px(&s.cur, 0, 5)[0] = f_snan();
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    /* no new sample: the pixel keeps its reprojected history (x* = history here, zero
       motion), N stays N_X, alpha = 0 */
    CHECK(same_bits(px(&s.outc, 2, 2), px(&s.hist, 2, 2), 3));
    CHECK(same_bits(px(&s.outc, 4, 3), px(&s.hist, 4, 3), 3));
    CHECK(same_bits(px(&s.outc, 5, 1), px(&s.hist, 5, 1), 3));
    CHECK(same_bits(px(&s.outc, 0, 5), px(&s.hist, 0, 5), 3));
    CHECK_NEAR(*px(&s.outn, 2, 2), 4.0, 0);
    CHECK_NEAR(*px(&s.outa, 4, 3), 0.0, 0);
    /* first frame (no history): black, N = 0 - nothing is known there */
    CHECK_EQ(ts_run(&s, &d, 0), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    for (k = 0; k < 3; ++k) CHECK_EQ(px(&s.outc, 2, 2)[k], 0);
    CHECK_NEAR(*px(&s.outn, 2, 2), 0.0, 0);
    CHECK_NEAR(*px(&s.outn, 3, 3), 1.0, 0);

    /* the moments leave the non-finite neighbour out */
    {
        rimg mean = rimg_new(7, 6, 3, 1), var = rimg_new(7, 6, 3, 0);
        double m = 0, v = 0;
        int n = 0, i, j;
        CHECK_EQ(sbl_moments_3x3(vw(&s.cur), vw(&mean), vw(&var), 0, 6), SBL_OK);
        for (j = 1; j <= 3; ++j)
            for (i = 1; i <= 3; ++i)
                if (!(i == 2 && j == 2)) { m += px(&s.cur, i, j)[1]; ++n; }
        m /= n;
        for (j = 1; j <= 3; ++j)
            for (i = 1; i <= 3; ++i)
                if (!(i == 2 && j == 2)) v += (px(&s.cur, i, j)[1] - m) * (px(&s.cur, i, j)[1] - m);
        v /= n;
        CHECK_NEAR(px(&mean, 2, 2)[1], m, 1e-7);
        CHECK_NEAR(px(&var, 2, 2)[1], v, 1e-9);
        CHECK(rimg_finite(&mean) && rimg_finite(&var) && rimg_pad_ok(&mean) && rimg_pad_ok(&var));
        rimg_free(&mean); rimg_free(&var);
    }

    /* non-finite history colour: that tap is rejected. Zero motion hits one tap; the
       3x3 fallback then averages the eight finite neighbours (all 0.25). */
    ts_noisy(&s, &s.cur, &rng, 0.25, 0.05);
    px(&s.hist, 3, 3)[0] = f_nan();
    px(&s.hist, 1, 1)[2] = f_inf();
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 3, 3), 5.0, 1e-3); /* N_X = 4 from the fallback, then + 1 */
    d.reproject.no_fallback = 1;               /* without the fallback: reset */
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 3, 3), 1.0, 0);
    CHECK(same_bits(px(&s.outc, 3, 3), px(&s.cur, 3, 3), 3));
    CHECK_NEAR(*px(&s.outa, 3, 3), 1.0, 0);
    d.reproject.no_fallback = 0;
    rimg_fill(&s.hist, 0.25f);

    /* history length NaN, inf, 0, negative, -0: that tap is invalid (reset w/o fallback) */
    {
        float bad[5];
        int i;
        bad[0] = f_nan(); bad[1] = f_inf(); bad[2] = 0.0f; bad[3] = -2.0f; bad[4] = f_bits(0x80000000u);
        d.reproject.no_fallback = 1;
        for (i = 0; i < 5; ++i) {
            rimg_fill(&s.hlen, 4.0f);
            *px(&s.hlen, 3, 2) = bad[i];
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            CHECK_NEAR(*px(&s.outn, 3, 2), 1.0, 0);
            CHECK_NEAR(*px(&s.outn, 4, 2), 5.0, 1e-3);
        }
        d.reproject.no_fallback = 0;
        rimg_fill(&s.hlen, 4.0f);
    }

    /* history at +-FLT_MAX and a new sample at the other end: the lerp overflows in
       float; the header forms it the other way and stays finite */
    for (y = 0; y < 6; ++y)
        for (x = 0; x < 7; ++x)
            for (k = 0; k < 3; ++k) {
                px(&s.hist, x, y)[k] = (x + y + k) % 2 ? FLT_MAX : -FLT_MAX;
                px(&s.cur, x, y)[k] = (x + y + k) % 2 ? -FLT_MAX : FLT_MAX;
            }
    {
        int e;
        for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
            int r;
            for (r = 0; r < SBL_RECTIFY_COUNT; ++r) {
                d.estimator = (sbl_estimator)e;
                d.rectify = (sbl_rectify)r;
                CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
                CHECK(ts_outputs_sane(&s, 64.0f));
            }
        }
        memset(&d, 0, sizeof d);
    }
    ts_free(&s);
}

/* Bug 1 (regression): the 3x3 fallback sums up to 9 history values in float before
   dividing; finite values above FLT_MAX / 9 overflow to +inf and the output becomes
   inf or NaN for a finite frame. Fails until the header accumulates in double. */
static void test_regression_fallback_overflow(void)
{
    tscene s;
    sbl_temporal_desc d;
    int e;
    memset(&d, 0, sizeof d);
    ts_init(&s, 5, 5, 1);
    s.use_ids = 1;
    rimg_fill(&s.cur, 1.0f);
    rimg_fill(&s.hist, 1e38f);
    rimg_fill(&s.hlen, 3e38f);
    rimg_fill(&s.ids, 1.0f);
    rimg_fill(&s.pids, 1.0f);
    *px(&s.pids, 2, 2) = 2.0f; /* the only bilinear tap fails: the fallback takes 8 */
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
        d.estimator = (sbl_estimator)e;
        CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
        CHECK(ts_outputs_sane(&s, 64.0f));
    }
    /* and the reprojection stage on its own: x* and N finite */
    {
        sbl_frame f;
        sbl_history h;
        sbl_temporal_output o;
        ts_views(&s, &f, &h, &o);
        CHECK_EQ(sbl_reproject_temporal(&d.reproject, SBL_TEMPORAL_MOTION, &f, &h, o.color, o.length, 0, 5), SBL_OK);
        CHECK(fin(*px(&s.outc, 2, 2)));
        CHECK(fin(*px(&s.outn, 2, 2)));
        CHECK_NEAR(*px(&s.outc, 2, 2), 1e38, 1e32);
    }
    ts_free(&s);
}

/* ======================================================================== */
/* Sanitising: depth                                                         */
/* ======================================================================== */

static void test_sanitise_depth(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbt_rng rng = {4321};
    int i;
    memset(&d, 0, sizeof d);
    ts_init(&s, 9, 7, 3);
    ts_noisy(&s, &s.cur, &rng, 0.5, 0.1);
    ts_noisy(&s, &s.hist, &rng, 0.5, 0.1);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;

    /* current depth with no valid geometry -> reset (N = 1, out = Y exactly) */
    {
        float bad[6];
        bad[0] = 0.0f; bad[1] = -1.0f; bad[2] = f_nan(); bad[3] = f_ninf();
        bad[4] = f_bits(0x80000000u); bad[5] = -FLT_MAX;
        for (i = 0; i < 6; ++i) {
            rimg_fill(&s.depth, 2.0f);
            *px(&s.depth, 4, 3) = bad[i];
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            CHECK_NEAR(*px(&s.outn, 4, 3), 1.0, 0);
            CHECK(same_bits(px(&s.outc, 4, 3), px(&s.cur, 4, 3), 3));
            CHECK_NEAR(*px(&s.outn, 5, 3), 5.0, 1e-4); /* the neighbour is unaffected */
        }
    }
    /* valid extremes: tiny, denormal, huge finite depth, when both frames agree */
    {
        float good[4];
        good[0] = 1e-30f; good[1] = f_bits(0x00000400u); good[2] = 1e30f; good[3] = FLT_MAX;
        for (i = 0; i < 4; ++i) {
            rimg_fill(&s.depth, good[i]);
            rimg_fill(&s.pdepth, good[i]);
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            /* under DAZ (e.g. gcc -ffast-math) a denormal depth compares as 0: reset */
            CHECK_NEAR(*px(&s.outn, 4, 3), (i == 1 && ftz_mode()) ? 1.0 : 5.0, 1e-4);
        }
    }
    /* sky: +inf matches only +inf */
    rimg_fill(&s.depth, 2.0f);
    rimg_fill(&s.pdepth, 2.0f);
    *px(&s.depth, 1, 1) = f_inf();                        /* sky now, geometry before   */
    *px(&s.depth, 6, 4) = f_inf(); *px(&s.pdepth, 6, 4) = f_inf(); /* sky both times  */
    *px(&s.pdepth, 3, 5) = f_inf();                       /* geometry now, sky before   */
    d.reproject.no_fallback = 1;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 1, 1), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 6, 4), 5.0, 1e-4);
    CHECK_NEAR(*px(&s.outn, 3, 5), 1.0, 0);
    /* with the fallback, the sky pixel next to geometry still finds no sky: reset */
    d.reproject.no_fallback = 0;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK_NEAR(*px(&s.outn, 1, 1), 1.0, 0);
    /* invalid history depth at the tap: rejected */
    rimg_fill(&s.depth, 2.0f);
    rimg_fill(&s.pdepth, 2.0f);
    {
        float bad[5];
        bad[0] = 0.0f; bad[1] = -3.0f; bad[2] = f_nan(); bad[3] = f_ninf(); bad[4] = f_inf();
        d.reproject.no_fallback = 1;
        for (i = 0; i < 5; ++i) {
            *px(&s.pdepth, 2, 2) = bad[i];
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            CHECK_NEAR(*px(&s.outn, 2, 2), 1.0, 0);
        }
        d.reproject.no_fallback = 0;
    }
    /* a non-finite neighbour does not open the depth slack (and does not poison it) */
    rimg_fill(&s.pdepth, 2.0f);
    rimg_fill(&s.depth, 2.0f);
    *px(&s.depth, 3, 3) = f_nan();
    *px(&s.depth, 5, 3) = f_inf();
    *px(&s.pdepth, 4, 3) = 2.5f;  /* 25% off: outside the 5% tolerance */
    d.reproject.no_fallback = 1;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 4, 3), 1.0, 0);
    d.reproject.no_fallback = 0;
    /* no history depth at all: the depth test is skipped (documented: optional) */
    rimg_fill(&s.depth, 2.0f);
    s.use_pdepth = 0;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK_NEAR(*px(&s.outn, 4, 3), 5.0, 1e-4);
    s.use_pdepth = 1;
    ts_free(&s);
}

/* ======================================================================== */
/* Sanitising: normals, ids                                                   */
/* ======================================================================== */

static void set_normals(rimg *n, float x, float y, float z)
{
    int i, j;
    for (j = 0; j < n->h; ++j)
        for (i = 0; i < n->w; ++i) { px(n, i, j)[0] = x; px(n, i, j)[1] = y; px(n, i, j)[2] = z; }
}

static void test_sanitise_normals_ids(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbt_rng rng = {99};
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    d.reproject.no_fallback = 1;
    ts_init(&s, 6, 6, 2);
    ts_noisy(&s, &s.cur, &rng, 1.0, 0.1);
    ts_noisy(&s, &s.hist, &rng, 1.0, 0.1);
    s.use_nrm = 1;
    set_normals(&s.nrm, 0, 0, 1);
    set_normals(&s.pnrm, 0, 0, 1);
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK_NEAR(*px(&s.outn, 2, 2), 5.0, 1e-4);
    /* current normal NaN / inf: no tap can pass -> reset */
    px(&s.nrm, 2, 2)[1] = f_nan();
    px(&s.nrm, 3, 3)[0] = f_inf();
    /* history normal NaN / -inf at a tap: that tap fails */
    px(&s.pnrm, 1, 4)[2] = f_nan();
    px(&s.pnrm, 4, 1)[2] = f_ninf();
    /* huge finite normals: |n|^2 overflows float -> treated as invalid (documented) */
    px(&s.nrm, 0, 0)[2] = 1e20f;
    /* tiny normals (|n|^2 < 1e-12) mean "no normal" and match only "no normal" */
    px(&s.nrm, 5, 5)[2] = 1e-7f;
    px(&s.nrm, 5, 0)[2] = 1e-7f; px(&s.pnrm, 5, 0)[2] = 0.0f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 2, 2), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 3, 3), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 1, 4), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 4, 1), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 0, 0), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 5, 5), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 5, 0), 5.0, 1e-4);
    CHECK_NEAR(*px(&s.outn, 1, 1), 5.0, 1e-4);
    /* normal test disabled: a non-finite normal of the pixel itself still resets it
       (its G-buffer is invalid), a non-finite history normal is no longer looked at */
    d.reproject.normal_threshold = -1.0f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 2, 2), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 1, 4), 5.0, 1e-4);
    d.reproject.normal_threshold = 0.0f;
    s.use_nrm = 0;

    /* ids: exact compare; NaN never equals anything, so a NaN id resets / rejects.
       Bug 8 (regression, -ffast-math builds only): there "!=" is compiled as "not
       (equal or unordered)" and a NaN id matches every id; fails until the patch tests
       NaN ids on the bits. */
    s.use_ids = 1;
    rimg_fill(&s.ids, 3.0f);
    rimg_fill(&s.pids, 3.0f);
    *px(&s.ids, 2, 3) = f_nan();
    *px(&s.pids, 4, 4) = f_nan();
    *px(&s.ids, 1, 1) = f_inf(); *px(&s.pids, 1, 1) = f_inf(); /* inf ids compare equal */
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 2, 3), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 4, 4), 1.0, 0);
    CHECK_NEAR(*px(&s.outn, 1, 1), 5.0, 1e-4);
    ts_free(&s);
}

/* ======================================================================== */
/* Sanitising: motion vectors                                                */
/* ======================================================================== */

static void test_sanitise_motion(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbt_rng rng = {7};
    float bad[12];
    int i, u;
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    ts_init(&s, 8, 6, 3);
    ts_noisy(&s, &s.cur, &rng, 0.3, 0.1);
    ts_noisy(&s, &s.hist, &rng, 0.3, 0.1);
    bad[0] = f_nan(); bad[1] = f_inf(); bad[2] = f_ninf(); bad[3] = 1e30f; bad[4] = -1e30f;
    bad[5] = FLT_MAX; bad[6] = -FLT_MAX; bad[7] = 3e9f; bad[8] = -3e9f; bad[9] = 2.2e9f;
    bad[10] = f_snan(); bad[11] = 1e7f;
    for (u = 0; u <= 2; ++u)          /* pixels, UV, NDC */
        for (i = 0; i < 12; ++i) {
            int comp;
            for (comp = 0; comp < 2; ++comp) {
                d.reproject.motion.units = (sbl_motion_units)u;
                d.reproject.motion.forward = i % 2;
                d.reproject.motion.y_up = (i / 2) % 2;
                rimg_fill(&s.mv, 0.0f);
                px(&s.mv, 3, 2)[comp] = bad[i];
                CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
                CHECK(ts_outputs_sane(&s, 64.0f));
                CHECK_NEAR(*px(&s.outn, 3, 2), 1.0, 0);   /* reset */
                CHECK(same_bits(px(&s.outc, 3, 2), px(&s.cur, 3, 2), 3));
                CHECK_NEAR(*px(&s.outn, 4, 2), 5.0, 1e-4); /* neighbour keeps history */
            }
        }
    /* a denormal motion vector is a zero motion vector for every practical purpose */
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    rimg_fill(&s.mv, f_bits(0x00000003u));
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 64.0f));
    CHECK_NEAR(*px(&s.outn, 3, 2), 5.0, 1e-4);
    /* just outside the image on every side: the border fallback may find pixels, and
       beyond 1.5 px nothing is found */
    {
        float mvs[4][2];
        int j;
        mvs[0][0] = -20.0f; mvs[0][1] = 0.0f;
        mvs[1][0] = 20.0f; mvs[1][1] = 0.0f;
        mvs[2][0] = 0.0f; mvs[2][1] = -20.0f;
        mvs[3][0] = 0.0f; mvs[3][1] = 20.0f;
        for (j = 0; j < 4; ++j) {
            int x, y, all_reset = 1;
            for (y = 0; y < 6; ++y)
                for (x = 0; x < 8; ++x) { px(&s.mv, x, y)[0] = mvs[j][0]; px(&s.mv, x, y)[1] = mvs[j][1]; }
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            for (y = 0; y < 6; ++y)
                for (x = 0; x < 8; ++x) all_reset &= *px(&s.outn, x, y) == 1.0f;
            CHECK(all_reset);
        }
    }
    ts_free(&s);
}

/* ======================================================================== */
/* Everything bad at once: the -ffast-math survival test                      */
/* ======================================================================== */

static float special(sbt_rng *r)
{
    switch ((int)(sbt_uniform(r) * 9.0)) {
    case 0: return f_nan();
    case 1: return f_inf();
    case 2: return f_ninf();
    case 3: return f_snan();
    case 4: return f_bits(0xffc00001u); /* negative NaN */
    case 5: return 0.0f;
    case 6: return -1.0f;
    case 7: return FLT_MAX;
    default: return f_bits(0x00000001u);
    }
}

static void sprinkle(rimg *im, sbt_rng *r, double p)
{
    int x, y, k;
    for (y = 0; y < im->h; ++y)
        for (x = 0; x < im->w; ++x)
            for (k = 0; k < im->c; ++k)
                if (sbt_uniform(r) < p) px(im, x, y)[k] = special(r);
}

static void test_all_bad_at_once(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbt_rng rng = {2024};
    int trial, bad_out = 0, bad_rc = 0, not_y = 0;
    ts_init(&s, 11, 9, 3);
    s.use_nrm = s.use_ids = 1;
    for (trial = 0; trial < 60; ++trial) {
        int x, y, k, ok = 1;
        memset(&d, 0, sizeof d);
        d.estimator = (sbl_estimator)(trial % SBL_ESTIMATOR_COUNT);
        d.rectify = (sbl_rectify)((trial / 4) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((trial / 12) % SBL_WEIGHT_MODE_COUNT);
        d.reproject.motion.units = (sbl_motion_units)(trial % 3);
        ts_noisy(&s, &s.cur, &rng, 1.0, 0.5);
        ts_noisy(&s, &s.hist, &rng, 1.0, 0.5);
        ts_noisy(&s, &s.mv, &rng, 0.0, 1.5);
        ts_noisy(&s, &s.hlen, &rng, 8.0, 7.5);
        rimg_fill(&s.depth, 3.0f); rimg_fill(&s.pdepth, 3.0f);
        set_normals(&s.nrm, 0, 1, 0); set_normals(&s.pnrm, 0, 1, 0);
        rimg_fill(&s.ids, 1.0f); rimg_fill(&s.pids, 1.0f);
        /* every input but the new colour gets non-finite / degenerate values */
        sprinkle(&s.hist, &rng, 0.1); sprinkle(&s.hlen, &rng, 0.1);
        sprinkle(&s.mv, &rng, 0.1); sprinkle(&s.depth, &rng, 0.1);
        sprinkle(&s.pdepth, &rng, 0.1); sprinkle(&s.nrm, &rng, 0.1);
        sprinkle(&s.pnrm, &rng, 0.1); sprinkle(&s.ids, &rng, 0.1); sprinkle(&s.pids, &rng, 0.1);
        bad_rc += ts_run(&s, &d, 1) != SBL_OK;
        ok &= ts_outputs_sane(&s, 64.0f);
        /* and now the new colour too: outputs still finite (kept history or 0) */
        sprinkle(&s.cur, &rng, 0.15);
        bad_rc += ts_run(&s, &d, 1) != SBL_OK;
        ok &= ts_outputs_sane(&s, 64.0f);
        /* where Y is finite and alpha = 1 (reset, or a blend with weight 1), the output
           is Y bit for bit */
        for (y = 0; y < 9; ++y)
            for (x = 0; x < 11; ++x) {
                int fy = 1;
                for (k = 0; k < 3; ++k) fy &= fin(px(&s.cur, x, y)[k]);
                /* (scalar weights only: per channel, alpha is the mean weight) */
                if (fy && *px(&s.outn, x, y) == 1.0f && *px(&s.outa, x, y) == 1.0f &&
                    d.weight_mode == SBL_WEIGHT_SCALAR)
                    not_y += !same_value(px(&s.outc, x, y), px(&s.cur, x, y), 3);
            }
        bad_out += !ok;
    }
    CHECK_EQ(bad_rc, 0);
    CHECK_EQ(bad_out, 0);
    /* Bug 6 (regression): alpha = 1 must give the new sample exactly; the header's
       x + a (y - x) loses y when |x| >> |y| (here x* = FLT_MAX taps). Fails until the
       patch (two-sided lerp). */
    CHECK_EQ(not_y, 0);
    ts_free(&s);
}

/* ======================================================================== */
/* Parameters and cameras                                                    */
/* ======================================================================== */

static void identity16(float *m) { int i; for (i = 0; i < 16; ++i) m[i] = (i % 5 == 0) ? 1.0f : 0.0f; }
static void perspective(sbl_camera *c, int w, int h, float f)
{
    identity16(c->world_to_view);
    memset(c->view_to_clip, 0, sizeof c->view_to_clip);
    c->view_to_clip[0] = 2.0f * f / (float)w;
    c->view_to_clip[5] = 2.0f * f / (float)h;
    c->view_to_clip[10] = -1.0f;
    c->view_to_clip[11] = -0.2f;
    c->view_to_clip[14] = -1.0f;
}

static void test_params(void)
{
    tscene s;
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    float bad[5];
    int i, p;
    ts_init(&s, 5, 4, 3);
    bad[0] = f_nan(); bad[1] = f_inf(); bad[2] = f_ninf(); bad[3] = -1.0f; bad[4] = f_snan();
    rimg_fill(&s.outc, -7.0f);
    /* every float parameter of the temporal descriptor: non-finite or negative is
       SBL_ERROR_INVALID_PARAM, and nothing is written.
       Bug 7 (regression, -ffast-math builds only): the defaults are applied with
       "v == 0.0f", which -ffast-math compiles so that it is also true for NaN: a NaN
       parameter silently becomes the default and the call succeeds. Fails until the
       patch tests zero on the bits. */
    for (p = 0; p < 8; ++p)
        for (i = 0; i < 5; ++i) {
            memset(&d, 0, sizeof d);
            switch (p) {
            case 0: d.constant_alpha = bad[i]; break;
            case 1: d.alpha_min = bad[i]; break;
            case 2: d.max_history = bad[i]; break;
            case 3: d.clip_gamma = bad[i]; break;
            case 4: d.bias_threshold = bad[i]; break;
            case 5: d.reproject.depth_tolerance = bad[i]; break;
            case 6: d.reproject.back_check_pixels = bad[i]; break;
            default: d.reproject.normal_threshold = i == 3 ? 1.5f : bad[i]; break;
            }
            CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
        }
    /* out of range */
    memset(&d, 0, sizeof d); d.constant_alpha = 1.0001f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
    memset(&d, 0, sizeof d); d.alpha_min = 2.0f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
    memset(&d, 0, sizeof d); d.max_history = 0.5f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
    memset(&d, 0, sizeof d); d.weight_mode = (sbl_weight_mode)2;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
    memset(&d, 0, sizeof d); d.reproject.motion.units = (sbl_motion_units)-1;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
    CHECK_EQ(px(&s.outc, 4, 3)[2], -7);
    CHECK(rimg_pad_ok(&s.outc));
    /* valid edge values */
    memset(&d, 0, sizeof d); d.max_history = 1.0f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 1.0f));
    memset(&d, 0, sizeof d); d.max_history = 1e30f; d.alpha_min = 1.0f;
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
    CHECK(ts_outputs_sane(&s, 1e30f));
    memset(&d, 0, sizeof d); d.reproject.normal_threshold = -1e30f; /* any negative disables */
    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);

    /* cameras: singular or non-finite matrices */
    {
        sbl_camera cc, pc;
        int which, entry;
        memset(&d, 0, sizeof d);
        d.source = SBL_TEMPORAL_CAMERA;
        perspective(&cc, 5, 4, 4.0f);
        perspective(&pc, 5, 4, 4.0f);
        ts_views(&s, &f, &h, &o);
        f.camera = &cc;
        h.camera = &pc;
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_OK);
        CHECK(ts_outputs_sane(&s, 64.0f));
        /* a zero projection is singular: INVALID_PARAM */
        memset(cc.view_to_clip, 0, sizeof cc.view_to_clip);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_INVALID_PARAM);
        perspective(&cc, 5, 4, 4.0f);
        /* Bug 3 (regression): a NaN / inf anywhere in either camera must be
           INVALID_PARAM ("non-finite parameter"); the header only rejects matrices
           whose inversion fails, so e.g. world_to_view[0] = inf inverts to a finite,
           wrong matrix and is used. Fails until the patch. */
        {
            int accepted = 0, tried = 0;
            for (which = 0; which < 4; ++which)
                for (entry = 0; entry < 16; entry += 3) {
                    float *m = which == 0 ? cc.world_to_view : which == 1 ? cc.view_to_clip
                             : which == 2 ? pc.world_to_view : pc.view_to_clip;
                    float keep = m[entry];
                    sbl_result r;
                    m[entry] = entry % 2 ? f_nan() : f_inf();
                    r = sbl_temporal_filter_frame(&d, &f, &h, &o);
                    accepted += r != SBL_ERROR_INVALID_PARAM;
                    ++tried;
                    /* whatever the code, the outputs stay finite */
                    CHECK(r != SBL_OK || ts_outputs_sane(&s, 64.0f));
                    m[entry] = keep;
                }
            if (accepted) printf("  non-finite camera entries accepted: %d of %d\n", accepted, tried);
            CHECK_EQ(accepted, 0);
        }
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_OK);
        /* camera mode without history: first frame, cameras of the history unused */
        h.camera = NULL;
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, NULL, &o), SBL_OK);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &h, &o), SBL_ERROR_MISSING_INPUT);
    }
    /* depth conversion parameters */
    {
        rimg dep = rimg_new(5, 4, 1, 1);
        rimg_fill(&dep, 0.5f);
        CHECK_EQ(sbl_depth_image_to_linear(vw(&dep), vw(&dep), SBL_DEPTH_NDC_GL, f_nan(), 10.0f), SBL_ERROR_INVALID_PARAM);
        CHECK_EQ(sbl_depth_image_to_linear(vw(&dep), vw(&dep), SBL_DEPTH_NDC_GL, 0.0f, 10.0f), SBL_ERROR_INVALID_PARAM);
        CHECK_EQ(sbl_depth_image_to_linear(vw(&dep), vw(&dep), SBL_DEPTH_REVERSED, 0.1f, f_inf()), SBL_ERROR_INVALID_PARAM);
        CHECK_EQ(sbl_depth_image_to_linear(vw(&dep), vw(&dep), SBL_DEPTH_REVERSED_INFINITE, 0.1f, f_nan()), SBL_OK);
        CHECK(rimg_finite(&dep));
        /* encoded values outside the range: beyond far = +inf (sky), nearer than near
           or NaN = NaN (no geometry), never a wrong finite depth */
        CHECK(is_pinf(sbl_depth_to_linear(1.5f, SBL_DEPTH_NDC_ZERO_ONE, 0.1f, 100.0f)));
        CHECK(is_pinf(sbl_depth_to_linear(1.001f, SBL_DEPTH_NDC_ZERO_ONE, 0.1f, 100.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(-0.5f, SBL_DEPTH_NDC_ZERO_ONE, 0.1f, 100.0f)));
        CHECK(is_pinf(sbl_depth_to_linear(-0.5f, SBL_DEPTH_REVERSED_INFINITE, 0.1f, 0.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(1.5f, SBL_DEPTH_REVERSED_INFINITE, 0.1f, 0.0f)));
        CHECK(is_pinf(sbl_depth_to_linear(-0.1f, SBL_DEPTH_REVERSED, 0.1f, 10.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(1.1f, SBL_DEPTH_REVERSED, 0.1f, 10.0f)));
        CHECK(is_pinf(sbl_depth_to_linear(1.1f, SBL_DEPTH_NDC_GL, 0.1f, 10.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(-1.1f, SBL_DEPTH_NDC_GL, 0.1f, 10.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(f_nan(), SBL_DEPTH_NDC_ZERO_ONE, 0.1f, 100.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(f_nan(), SBL_DEPTH_REVERSED_INFINITE, 0.1f, 0.0f)));
        CHECK(is_nan_bits(sbl_depth_to_linear(0.0f, (sbl_depth_encoding)77, 0.1f, 1.0f)));
        /* in place with another stride would overwrite rows before reading them */
        {
            sbl_image src = vw(&dep), dst = vw(&dep);
            dst.stride = src.stride + 1;
            dst.width = 4;
            src.width = 4;
            CHECK_EQ(sbl_depth_image_to_linear(src, dst, SBL_DEPTH_NDC_GL, 0.1f, 10.0f), SBL_ERROR_OVERLAP);
        }
        rimg_free(&dep);
    }
    ts_free(&s);
}

/* Bug 2 (regression): sbl_temporal_scratch_size() returns 0 for widths in
   (INT_MAX / 8, INT_MAX / 4], which sbl__check_image accepts; "scratch_bytes < 0" is
   never true, so a 64-byte scratch passes and the filter writes 3 rows of x* into it.
   An empty row range keeps this test from touching memory (the views are never
   dereferenced: the ranges are only compared). Fails until the patch. */
static void test_regression_scratch_size_hole(void)
{
    static float base[4];
    const int W = INT_MAX / 8 + 1000;
    const size_t span = (size_t)W * 2 * sizeof(float);
    char scratch[64];
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_temporal_output o;
    sbl_result r;
    size_t b = (size_t)base;
    memset(&d, 0, sizeof d); memset(&f, 0, sizeof f); memset(&o, 0, sizeof o);
    /* three disjoint address ranges; frame colour and motion may share one (inputs) */
    f.color = sbl_image_make((float *)b, W, 1, 1);
    f.gbuffer.motion = sbl_image_make((float *)b, W, 1, 2);
    o.color = sbl_image_make((float *)(b + span), W, 1, 1);
    o.length = sbl_image_make((float *)(b + 2 * span), W, 1, 1);
    CHECK_EQ(sbl_temporal_scratch_size(W, 1), 0);
    r = sbl_temporal_filter(&d, &f, NULL, &o, 0, 0, scratch, sizeof scratch);
    CHECK(r == SBL_ERROR_INVALID_SIZE || r == SBL_ERROR_SCRATCH_TOO_SMALL);
}

/* ======================================================================== */
/* HDR numerics                                                              */
/* ======================================================================== */

/* 3x3 moments over values 10^U(-30, 30) (both signs) against a double reference. */
static void test_hdr_moments(void)
{
    const int w = 9, h = 7, c = 3;
    rimg src = rimg_new(w, h, c, 2), mean = rimg_new(w, h, c, 1), var = rimg_new(w, h, c, 0);
    sbt_rng rng = {31337};
    double worst_mean = 0, worst_var = 0;
    int x, y, k, overflowed = 0, var_finite = 1, nonneg = 1;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < c; ++k) {
                double e = -30.0 + 60.0 * sbt_uniform(&rng);
                double v = pow(10.0, e) * (sbt_uniform(&rng) < 0.2 ? -1.0 : 1.0);
                /* channel 2: narrow dynamic range per window, to test precision */
                if (k == 2) v = pow(10.0, (x < 4 ? -30.0 : 30.0)) * (1.0 + 0.01 * sbt_gauss(&rng));
                px(&src, x, y)[k] = (float)v;
            }
    CHECK_EQ(sbl_moments_3x3(vw(&src), vw(&mean), vw(&var), 0, h), SBL_OK);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (k = 0; k < c; ++k) {
                double s = 0, v = 0, m, big = 0;
                int n = 0, i, j;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = x - 1; i <= x + 1; ++i)
                        if (i >= 0 && j >= 0 && i < w && j < h) {
                            double q = px(&src, i, j)[k];
                            s += q; ++n;
                            if (fabs(q) > big) big = fabs(q);
                        }
                m = s / n;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = x - 1; i <= x + 1; ++i)
                        if (i >= 0 && j >= 0 && i < w && j < h) {
                            double q = px(&src, i, j)[k] - m;
                            v += q * q;
                        }
                v /= n;
                /* the mean to float precision of the largest magnitude in the window */
                {
                    double e = fabs(px(&mean, x, y)[k] - m) / big;
                    if (e > worst_mean) worst_mean = e;
                }
                nonneg &= px(&var, x, y)[k] >= 0.0f;
                if (v > FLT_MAX) {
                    ++overflowed;
                    var_finite &= fin(px(&var, x, y)[k]);
                    CHECK(px(&var, x, y)[k] >= FLT_MAX); /* inf now, FLT_MAX after patch */
                } else if (v >= FLT_MIN) {
                    double e = fabs(px(&var, x, y)[k] - v) / v;
                    if (e > worst_var) worst_var = e;
                }
            }
    printf("  HDR moments: max rel error mean %.3g, variance %.3g; %d windows with variance > FLT_MAX\n",
           worst_mean, worst_var, overflowed);
    CHECK(worst_mean <= 2e-7);
    CHECK(worst_var <= 1e-6);
    CHECK(nonneg);
    CHECK(overflowed > 0);
    /* Bug 4 (regression): a variance beyond FLT_MAX is written as +inf; the float
       output should saturate at FLT_MAX so a finite input gives a finite output.
       Fails until the patch. */
    CHECK(var_finite);
    CHECK(rimg_finite(&mean) && rimg_pad_ok(&mean) && rimg_pad_ok(&var));
    rimg_free(&src); rimg_free(&mean); rimg_free(&var);
}

/* Every estimator and rectification is scale invariant: the same scene at 1e-30 ..
   1e30 gives the same alpha and N, and the output scaled by the same factor. In one
   image, a dark half (1e-30) next to a bright half (1e30) must not disturb pixels
   whose 3x3 window is entirely on one side. */
static void fill_scene_scaled(tscene *s, double scale, int split, unsigned long long seed)
{
    sbt_rng rng;
    int x, y, k;
    rng.s = seed;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            double sc = split ? (x < s->w / 2 ? 1e-30 : 1e30) : scale;
            for (k = 0; k < s->c; ++k) {
                double t = 0.5 + 0.2 * sin(0.9 * x + k) + 0.1 * cos(0.7 * y);
                px(&s->cur, x, y)[k] = (float)(sc * (t + 0.1 * sbt_gauss(&rng)));
                px(&s->hist, x, y)[k] = (float)(sc * (t + 0.05 * sbt_gauss(&rng) + (x == 3 && y == 3 ? 0.5 : 0.0)));
            }
            px(&s->mv, x, y)[0] = 0.25f * (float)((x + y) % 3);
            px(&s->mv, x, y)[1] = -0.125f * (float)(x % 2);
            *px(&s->hlen, x, y) = (float)(1 + (x * 7 + y * 3) % 20);
        }
}

static void test_hdr_scale_invariance(void)
{
    const int w = 12, h = 8, c = 3;
    tscene ref, s;
    sbl_temporal_desc d;
    double scales[7];
    double worst_a = 0, worst_c = 0, worst_n = 0;
    int e, r, m, i, x, y, k;
    scales[0] = 1e-30; scales[1] = 1e-20; scales[2] = 1e-10; scales[3] = 1e10;
    scales[4] = 1e20; scales[5] = 1e30; scales[6] = 3e-36; /* near FLT_MIN */
    ts_init(&ref, w, h, c);
    ts_init(&s, w, h, c);
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e)
        for (r = 0; r < SBL_RECTIFY_COUNT; ++r)
            for (m = 0; m < SBL_WEIGHT_MODE_COUNT; ++m) {
                memset(&d, 0, sizeof d);
                d.estimator = (sbl_estimator)e;
                d.rectify = (sbl_rectify)r;
                d.weight_mode = (sbl_weight_mode)m;
                fill_scene_scaled(&ref, 1.0, 0, 555);
                CHECK_EQ(ts_run(&ref, &d, 1), SBL_OK);
                for (i = 0; i < 8; ++i) {
                    int split = i == 7;
                    /* with FTZ the caller gave up results below FLT_MIN: 3e-36 * alpha
                       * (y - x) lands there */
                    if (i == 6 && ftz_mode()) continue;
                    fill_scene_scaled(&s, split ? 1.0 : scales[i], split, 555);
                    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
                    CHECK(ts_outputs_sane(&s, 64.0f));
                    for (y = 0; y < h; ++y)
                        for (x = 0; x < w; ++x) {
                            double sc = split ? (x < w / 2 ? 1e-30 : 1e30) : scales[i];
                            double ea, en;
                            /* in the split image only windows entirely on one side */
                            if (split && (x == w / 2 - 1 || x == w / 2 || x == w / 2 - 2 ||
                                          x == w / 2 + 1))
                                continue;
                            /* the pooled estimator reads blocks up to 7 columns away */
                            if (split && e == SBL_ESTIMATOR_POOLED && x >= w / 2 - 9 && x <= w / 2 + 8)
                                continue;
                            ea = fabs(*px(&s.outa, x, y) - *px(&ref.outa, x, y));
                            en = fabs(*px(&s.outn, x, y) - *px(&ref.outn, x, y)) / *px(&ref.outn, x, y);
                            if (ea > worst_a) worst_a = ea;
                            if (en > worst_n) worst_n = en;
                            for (k = 0; k < c; ++k) {
                                double ec = fabs(px(&s.outc, x, y)[k] / sc - px(&ref.outc, x, y)[k]) /
                                            (fabs(px(&ref.outc, x, y)[k]) + 0.1);
                                if (ec > worst_c) worst_c = ec;
                            }
                        }
                }
            }
    printf("  HDR scale invariance 3e-36..1e30 and split 1e-30|1e30: max |d alpha| %.3g, "
           "rel colour %.3g, rel N %.3g\n", worst_a, worst_c, worst_n);
    /* inputs are rounded to float after scaling (2^-24 relative), which moves moments
       and weights by a few ulps; the bound leaves 100x room */
    CHECK(worst_a <= 2e-5);
    CHECK(worst_c <= 2e-5);
    CHECK(worst_n <= 2e-5);
    ts_free(&ref);
    ts_free(&s);
}

/* Constant images: zero variance. History equal to Y must give Y exactly; a different
   constant history gives the documented weight of each estimator. */
static void test_constant_images(void)
{
    tscene s;
    sbl_temporal_desc d;
    float vals[7];
    int ftz = ftz_mode(), i, e, r, m;
    vals[0] = 0.0f; vals[1] = 0.5f; vals[2] = 1e-30f; vals[3] = 1e30f; vals[4] = FLT_MAX;
    vals[5] = -3.0f; vals[6] = f_bits(0x00012345u); /* denormal */
    ts_init(&s, 6, 5, 3);
    for (i = 0; i < 7; ++i)
        for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e)
            for (r = 0; r < SBL_RECTIFY_COUNT; ++r)
                for (m = 0; m < SBL_WEIGHT_MODE_COUNT; ++m) {
                    float v = vals[i], other = vals[i] == 0.0f ? 1.0f : vals[i] * 0.5f;
                    float expect_a;
                    int x, y, k, same = 1, wa = 1;
                    memset(&d, 0, sizeof d);
                    d.estimator = (sbl_estimator)e;
                    d.rectify = (sbl_rectify)r;
                    d.weight_mode = (sbl_weight_mode)m;
                    rimg_fill(&s.cur, v);
                    rimg_fill(&s.hist, v);
                    rimg_fill(&s.hlen, 7.0f);
                    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
                    CHECK(ts_outputs_sane(&s, 64.0f));
                    for (y = 0; y < 5; ++y)
                        for (x = 0; x < 6; ++x)
                            for (k = 0; k < 3; ++k)
                                same &= px(&s.outc, x, y)[k] == ((ftz && i == 6) ? px(&s.outc, x, y)[k] : v);
                    CHECK(same);
                    /* a different constant history */
                    rimg_fill(&s.hist, other);
                    CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
                    CHECK(ts_outputs_sane(&s, 64.0f));
                    if (i == 6) continue; /* denormal: 'other' is v/2, weights are ratios of 0 under FTZ */
                    if (r != SBL_RECTIFY_NONE) {
                        /* the 3x3 box of a constant Y is that constant: x* moves onto Y */
                        for (y = 0; y < 5; ++y)
                            for (x = 0; x < 6; ++x)
                                for (k = 0; k < 3; ++k) same &= px(&s.outc, x, y)[k] == v;
                        CHECK(same);
                        continue;
                    }
                    expect_a = e == SBL_ESTIMATOR_PROGRESSIVE ? 1.0f / 8.0f
                             : e == SBL_ESTIMATOR_CONSTANT ? 0.1f : 1.0f; /* bias detected */
                    for (y = 0; y < 5; ++y)
                        for (x = 0; x < 6; ++x)
                            wa &= fabsf(*px(&s.outa, x, y) - expect_a) <= 1e-6f;
                    CHECK(wa);
                }
    ts_free(&s);
}

/* ======================================================================== */
/* Double-precision reference of the temporal filter                          */
/* ======================================================================== */

/* Straightforward and scalar, written from the header's documentation: motion-vector
   reprojection (a source position outside the previous image resets) with bilinear
   taps, each tap tested (depth with relative tolerance and
   one-sided slope slack, +inf sky only matching sky; exact ids; normals by cosine;
   finite colour; finite positive N), renormalised over the valid taps; if they weigh
   less than 1e-3, the 3x3 fallback around the nearest pixel; 3x3 population moments of
   the finite Y values and paired differences x*_i - y_i; the estimator; rectification;
   out = x* + a (y - x*); Eq. 5 for N; the cap. Everything in double. */

typedef struct refp {
    int est, rect, mode, no_fallback;
    int lean; /* the restart lean (docs/ESTIMATORS.md 6.3, 6.4): the default configuration
                 (pooled, no rectification, one weight) with stereo_shared_bias 0 */
    double constant, alpha_min, max_history, gamma, bias_thr, depth_tol, normal_thr;
    sbl_motion_convention mc;
} refp;

typedef struct refin {
    int w, h, c;
    const rimg *cur, *depth, *mv, *nrm, *ids;
    const rimg *hist, *hlen, *pdepth, *pnrm, *pids; /* hist NULL: first frame */
} refin;

static refp ref_params(const sbl_temporal_desc *d)
{
    refp p;
    p.est = (int)d->estimator;
    p.rect = (int)d->rectify;
    p.mode = (int)d->weight_mode;
    p.no_fallback = d->reproject.no_fallback;
    p.constant = d->constant_alpha == 0.0f ? 0.1 : (double)d->constant_alpha;
    p.alpha_min = d->alpha_min;
    p.max_history = d->max_history == 0.0f ? 64.0 : (double)d->max_history;
    p.gamma = d->clip_gamma == 0.0f ? 1.25 : (double)d->clip_gamma;
    p.bias_thr = d->bias_threshold == 0.0f ? 3.0 : (double)d->bias_threshold;
    p.depth_tol = d->reproject.depth_tolerance == 0.0f ? 0.05 : (double)d->reproject.depth_tolerance;
    p.normal_thr = d->reproject.normal_threshold == 0.0f ? 0.9 : (double)d->reproject.normal_threshold;
    p.mc = d->reproject.motion;
    p.lean = d->estimator == SBL_ESTIMATOR_POOLED && d->rectify == SBL_RECTIFY_NONE &&
             d->weight_mode == SBL_WEIGHT_SCALAR && d->stereo_shared_bias == 0.0f &&
             d->reproject.history_filter != SBL_HISTORY_CATMULL_ROM;
    return p;
}

static double ref_slack(const rimg *dep, int x, int y, double z)
{
    double s = 0.0;
    int axis;
    if (!dfin(z)) return 0.0;
    for (axis = 0; axis < 2; ++axis) {
        int n = axis ? dep->h : dep->w, i = axis ? y : x;
        double a, b, da, db, m;
        if (n <= 1) continue;
        a = i > 0 ? *px(dep, axis ? x : i - 1, axis ? i - 1 : y) : z;
        b = i + 1 < n ? *px(dep, axis ? x : i + 1, axis ? i + 1 : y) : z;
        da = fabs(z - a);
        db = fabs(b - z);
        if (i == 0) da = db;
        if (i + 1 == n) db = da;
        m = da < db ? da : db;
        if (dfin(m)) s += m;
    }
    return s;
}

static int ref_tap_ok(const refin *in, const refp *p, int x, int y, int tx, int ty,
                      double expect_z, double slack)
{
    int k;
    if (tx < 0 || ty < 0 || tx >= in->w || ty >= in->h) return 0;
    if (in->depth && in->pdepth) {
        float t = *px(in->pdepth, tx, ty);
        int sky_e = expect_z > DBL_MAX, sky_t = is_pinf(t);
        if (sky_e || sky_t) { if (!(sky_e && sky_t)) return 0; }
        else if (!fin(t) || !(t > 0.0f) || fabs((double)t - expect_z) > p->depth_tol * expect_z + slack)
            return 0;
    }
    if (in->ids && in->pids && !(*px(in->pids, tx, ty) == *px(in->ids, x, y))) return 0;
    if (in->nrm && in->pnrm && !(p->normal_thr < 0.0)) {
        const float *a = px(in->nrm, x, y), *b = px(in->pnrm, tx, ty);
        double dot = 0, aa = 0, bb = 0;
        for (k = 0; k < 3; ++k) {
            if (!fin(a[k]) || !fin(b[k])) return 0;
            dot += (double)a[k] * b[k]; aa += (double)a[k] * a[k]; bb += (double)b[k] * b[k];
        }
        if (aa < 1e-12 || bb < 1e-12) { if (!(aa < 1e-12 && bb < 1e-12)) return 0; }
        else if (dot < p->normal_thr * sqrt(aa * bb)) return 0;
    }
    for (k = 0; k < in->c; ++k)
        if (!fin(px(in->hist, tx, ty)[k])) return 0;
    if (in->hlen) {
        float n = *px(in->hlen, tx, ty);
        if (!fin(n) || !(n > 0.0f)) return 0;
    }
    return 1;
}

/* x* (in xs) and its N for pixel (x, y); 0 = reset */
static double ref_reproject(const refin *in, const refp *p, int x, int y, double *xs)
{
    double z = 0, dx, dy, sx, sy, bx, by, slack = 0, wsum = 0, acc[4] = {0, 0, 0, 0}, accn = 0;
    int k, i, j, x0, y0;
    const float *mv;
    if (!in->hist) return 0.0;
    if (in->depth) {
        float zf = *px(in->depth, x, y);
        if (is_pinf(zf)) z = HUGE_VAL;
        else if (!fin(zf) || !(zf > 0.0f)) return 0.0;
        else z = zf;
        slack = ref_slack(in->depth, x, y, z);
    }
    mv = px(in->mv, x, y);
    if (!fin(mv[0]) || !fin(mv[1])) return 0.0;
    dx = mv[0]; dy = mv[1];
    if (p->mc.units == SBL_MOTION_UV) { dx *= in->w; dy *= in->h; }
    if (p->mc.units == SBL_MOTION_NDC) { dx *= 0.5 * in->w; dy *= 0.5 * in->h; }
    if (p->mc.y_up) dy = -dy;
    if (p->mc.forward) { dx = -dx; dy = -dy; }
    sx = x + 0.5 + dx;
    sy = y + 0.5 + dy;
    /* a position outside the previous image has nothing to reuse */
    if (!(sx >= 0.0 && sx < in->w && sy >= 0.0 && sy < in->h)) return 0.0;
    bx = sx - 0.5;
    by = sy - 0.5;
    if (!(bx > -2.0 && by > -2.0 && bx < in->w + 1.0 && by < in->h + 1.0)) return 0.0;
    x0 = (int)floor(bx);
    y0 = (int)floor(by);
    for (j = 0; j < 2; ++j)
        for (i = 0; i < 2; ++i) {
            double fx = bx - x0, fy = by - y0;
            double wt = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
            if (wt <= 0 || !ref_tap_ok(in, p, x, y, x0 + i, y0 + j, z, slack)) continue;
            for (k = 0; k < in->c; ++k) acc[k] += wt * px(in->hist, x0 + i, y0 + j)[k];
            accn += wt * (in->hlen ? *px(in->hlen, x0 + i, y0 + j) : 1.0);
            wsum += wt;
        }
    if (wsum < 1e-3 && !p->no_fallback) {
        int cx = (int)floor(sx), cy = (int)floor(sy);
        wsum = accn = 0;
        for (k = 0; k < 4; ++k) acc[k] = 0;
        for (j = -1; j <= 1; ++j)
            for (i = -1; i <= 1; ++i)
                if (ref_tap_ok(in, p, x, y, cx + i, cy + j, z, slack)) {
                    for (k = 0; k < in->c; ++k) acc[k] += px(in->hist, cx + i, cy + j)[k];
                    accn += in->hlen ? *px(in->hlen, cx + i, cy + j) : 1.0;
                    wsum += 1;
                }
    }
    if (wsum < 1e-3) return 0.0;
    for (k = 0; k < in->c; ++k) xs[k] = acc[k] / wsum;
    return accn / wsum > 0 ? accn / wsum : 0.0;
}

static double ref_weight(const refp *p, double dev2, double s2, double pd2, double pv,
                         int count, int pairs, double nx, double ny, double pool_r)
{
    double prog = ny / (nx + ny), a;
    if (p->est == SBL_ESTIMATOR_PAPER) a = dev2 + s2 > 0 ? dev2 / (dev2 + s2) : prog;
    else if (p->est == SBL_ESTIMATOR_PROGRESSIVE) a = prog;
    else if (p->est == SBL_ESTIMATOR_CONSTANT) a = p->constant;
    else if (p->est == SBL_ESTIMATOR_ROBUST || p->est == SBL_ESTIMATOR_POOLED) {
        /* as below, the bias weighted by the posterior of change: t^2 = pd2 / se2,
           rho = (1 + k^2/8) / (1 + t^2/8), posterior 1 / (1 + odds rho^4.5) */
        double kk = p->est == SBL_ESTIMATOR_POOLED ? p->bias_thr * 4.0 / 3.0 : p->bias_thr;
        double k2 = kk * kk, vy, vx, se2, b2 = 0;
        if (pairs > 1) {
            vy = pv * nx / (nx + ny);
            vx = pv - vy;
            se2 = pv / pairs;
        } else {
            vy = count > 1 ? s2 * count / (count - 1) : 0.0;
            vx = vy * ny / nx;
            se2 = pairs == 1 ? vx + vy : 0.0;
        }
        if (pairs > 0) {
            double t2 = se2 > 0 ? pd2 / se2 : (pd2 > 0 ? HUGE_VAL : 0.0);
            double rho = (1 + k2 / 8) / (1 + t2 / 8);
            /* prior odds against change (N + 1) / 2 (the temporal filter: rule of
               succession on the history length) */
            b2 = pd2 / (1 + 0.5 * (nx + 1) * pow(rho, 4.5));
        }
        if (p->est == SBL_ESTIMATOR_POOLED && pairs > 1 && pool_r > 0) {
            /* empirical Bayes with the prior bias-to-noise ratio r pooled along the row:
               E[B^2 | pd] = sh^2 pd2 + sh se2, sh = r / (1 + r) */
            double sh = pool_r / (1 + pool_r);
            if (sh * sh * pd2 + sh * se2 > b2) b2 = sh * sh * pd2 + sh * se2;
        }
        a = b2 + vx + vy > 0 ? (b2 + vx) / (b2 + vx + vy) : prog;
    } else {
        /* paired t-test: with two or more pairs, var_X + var_Y from the pairs' sample
           variance pv and bias beyond bias_thr standard errors; else the 3x3 variance */
        double k2 = p->bias_thr * p->bias_thr, vy, vx, b2 = 0;
        if (pairs > 1) {
            vy = pv * nx / (nx + ny);
            vx = pv - vy;
            b2 = pd2 - k2 * pv / pairs;
        } else {
            vy = count > 1 ? s2 * count / (count - 1) : 0.0;
            vx = vy * ny / nx;
            if (pairs == 1) b2 = pd2 - k2 * (vx + vy);
        }
        if (b2 < 0) b2 = 0;
        a = b2 + vx + vy > 0 ? (b2 + vx) / (b2 + vx + vy) : prog;
    }
    if (a < p->alpha_min) a = p->alpha_min;
    if (a < 0) a = 0;
    if (a > 1) a = 1;
    return a;
}

/* The restart lean (docs/ESTIMATORS.md 6.3, 6.4, 6.6; the library's ramps 0.1 .. 0.3
   and 0.05 .. 0.2, written as numbers), then the floor alpha_min: where the weight a
   (before the floor) is above 0.1 and above the progressive 1 / (N + 1) by more
   than 0.05, the spatial lean of 4.2 with q not divided by N, a_l = (a + q e) / (1 + q),
   q = a V_Y / V_M, e = E / D, V_M = the texture + V_Y / n8, the texture the larger of the
   neighbours' sample variance beyond V_Y (v8u = v8 n8 / (n8 - 1)) and the history's
   sum_c (x*_c - the valid neighbours' mean x*_c)^2 (xt < 0: none); the output weight is
   a + f (a_l - a), f the product of the two ramps' shares */
static double ref_restart_lean(const refp *p, double a, double vy, double v8, double le,
                               double ld, double xt, int count, double nx)
{
    double v8u = v8 * (count - 1) / (count - 2), tex, vm, q, al;
    double fw = (a - 0.1) / 0.2, fe = (a - 1.0 / (nx + 1.0) - 0.05) / 0.15;
    fw = fw < 0 ? 0 : fw > 1 ? 1 : fw;
    fe = fe < 0 ? 0 : fe > 1 ? 1 : fe;
    tex = xt >= 0 && xt > v8u - vy ? xt : v8u - vy;
    if (tex < 0) tex = 0;
    vm = tex + vy / (count - 1);
    if (p->lean && count > 2 && fw * fe > 0 && vm > 0) {
        q = a * vy / vm;
        al = (1 + q) * ld > 0 ? (a * ld + q * le) / ((1 + q) * ld) : a;
        a += fw * fe * (al - a);
    }
    if (a < p->alpha_min) a = p->alpha_min;
    if (a < 0) a = 0;
    if (a > 1) a = 1;
    return a;
}

static double ref_eq5(double a, double nx, double ny)
{
    double den = (1 - a) * (1 - a) * ny + a * a * nx;
    return den > 0 ? nx * ny / den : nx + ny;
}

/* outputs: oc[(y * w + x) * c + k], on[y * w + x], oa[y * w + x] */
static void ref_temporal(const refin *in, const refp *p, double *oc, double *on, double *oa,
                         double *oxs)
{
    const int w = in->w, h = in->h, c = in->c;
    double *xs = (double *)malloc(sizeof(double) * (size_t)w * h * c);
    double *xn = (double *)malloc(sizeof(double) * (size_t)w * h);
    double *pool = (double *)malloc(sizeof(double) * (size_t)w * h);
    int x, y, k, i, j;
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double v[4] = {0, 0, 0, 0};
            xn[y * w + x] = ref_reproject(in, p, x, y, v);
            for (k = 0; k < c; ++k) xs[(y * w + x) * c + k] = v[k];
        }
    /* pooled estimator: over the 3x3 blocks centred at x + 3b, |b| <= 2, in the image
       and with >= 3 pairs (valid x*, finite values), the sum of the blocks'
       sum_c mean_c^2 over the sum of their sum_c (sample var_c / n), less 3.5 (capped at
       1e6); r is that if positive, else 0 */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double sm2 = 0, sse2 = 0, r;
            int b;
            pool[y * w + x] = 0;
            if (p->est != SBL_ESTIMATOR_POOLED) continue;
            for (b = -2; b <= 2; ++b) {
                int cx = x + 3 * b, n = 0;
                double s1[4] = {0, 0, 0, 0}, s2[4] = {0, 0, 0, 0};
                if (cx < 0 || cx >= w) continue;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = cx - 1; i <= cx + 1; ++i) {
                        int f = 1;
                        if (i < 0 || j < 0 || i >= w || j >= h || !(xn[j * w + i] > 0)) continue;
                        for (k = 0; k < c; ++k)
                            f &= fin(px(in->cur, i, j)[k]) && fin((float)xs[(j * w + i) * c + k]);
                        if (!f) continue;
                        for (k = 0; k < c; ++k) {
                            double dd = xs[(j * w + i) * c + k] - px(in->cur, i, j)[k];
                            s1[k] += dd;
                            s2[k] += dd * dd;
                        }
                        ++n;
                    }
                if (n < 3) continue;
                for (k = 0; k < c; ++k) {
                    double mu = s1[k] / n, vv = (s2[k] - n * mu * mu) / (n - 1);
                    sm2 += mu * mu;
                    sse2 += (vv > 0 ? vv : 0) / n;
                }
            }
            r = sse2 > 0 ? sm2 / sse2 - 3.5 : (sm2 > 0 ? 1e6 : 0);
            if (r > 1e6) r = 1e6;
            if (r > 0) pool[y * w + x] = r;
        }
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            const float *yv = px(in->cur, x, y);
            double *o = oc + (size_t)(y * w + x) * c, a = 1, nout, nx = xn[y * w + x];
            int finite = 1;
            oxs[y * w + x] = 0;
            for (k = 0; k < c; ++k) {
                finite &= fin(yv[k]);
                if (nx > 0 && fabs(xs[(y * w + x) * c + k]) > oxs[y * w + x])
                    oxs[y * w + x] = fabs(xs[(y * w + x) * c + k]);
            }
            if (!finite) {
                for (k = 0; k < c; ++k) o[k] = nx > 0 ? xs[(y * w + x) * c + k] : 0.0;
                nout = nx > 0 ? nx : 0.0;
                a = 0;
            } else if (!(nx > 0)) {
                for (k = 0; k < c; ++k) o[k] = yv[k];
                nout = 1;
            } else {
                double mean[4], var[4], lo[4], hi[4], pd[4], pv[4], x1[4], ak[4], yl[4], a2, a_raw = 0;
                int cnt = 0, pairs = 0, idx[9][2], ispair[9], centre = 0, pass;
                for (j = y - 1; j <= y + 1; ++j)
                    for (i = x - 1; i <= x + 1; ++i) {
                        int f = 1;
                        if (i < 0 || j < 0 || i >= w || j >= h) continue;
                        for (k = 0; k < c; ++k) f &= fin(px(in->cur, i, j)[k]);
                        if (!f) continue;
                        if (i == x && j == y) centre = cnt;
                        idx[cnt][0] = i; idx[cnt][1] = j;
                        ispair[cnt] = xn[j * w + i] > 0;
                        pairs += ispair[cnt];
                        ++cnt;
                    }
                for (k = 0; k < c; ++k) yl[k] = yv[k];
                /* robust estimator: the centre's own sample limited for the blend */
                for (pass = 0; pass < 2; ++pass) {
#define REF_Y(n, k) ((n) == centre ? yl[k] : (double)px(in->cur, idx[n][0], idx[n][1])[k])
                for (k = 0; k < c; ++k) {
                    double s = 0, v = 0, q = 0;
                    int n;
                    for (n = 0; n < cnt; ++n) s += REF_Y(n, k);
                    mean[k] = s / cnt;
                    lo[k] = hi[k] = REF_Y(0, k);
                    for (n = 0; n < cnt; ++n) {
                        double yy = REF_Y(n, k);
                        v += (yy - mean[k]) * (yy - mean[k]);
                        if (yy < lo[k]) lo[k] = yy;
                        if (yy > hi[k]) hi[k] = yy;
                        if (ispair[n]) q += xs[(idx[n][1] * w + idx[n][0]) * c + k] - yy;
                    }
                    var[k] = v / cnt;
                    pd[k] = pairs ? q / pairs : 0.0;
                    pv[k] = 0.0;
                    if (pairs > 1) {
                        for (n = 0; n < cnt; ++n)
                            if (ispair[n]) {
                                double e = (xs[(idx[n][1] * w + idx[n][0]) * c + k] - REF_Y(n, k)) - pd[k];
                                pv[k] += e * e;
                            }
                        pv[k] /= pairs - 1;
                    }
                    x1[k] = xs[(y * w + x) * c + k];
                }
                if (pass == 0 && (p->est == SBL_ESTIMATOR_ROBUST || p->est == SBL_ESTIMATOR_POOLED) &&
                    cnt > 1) {
                    /* neighbours without the centre: mean and population variance,
                       summed over channels; bound = max(their mean, x*) + 6 sigma
                       sqrt(N + 1), N the capped history length */
                    double sy = 0, sm = 0, sx = 0, sv = 0, bound, t = 1;
                    const double ncap = nx > p->max_history ? p->max_history : nx;
                    int n;
                    for (k = 0; k < c; ++k) {
                        double m8 = 0, v8 = 0;
                        for (n = 0; n < cnt; ++n) if (n != centre) m8 += REF_Y(n, k) / (cnt - 1);
                        for (n = 0; n < cnt; ++n)
                            if (n != centre) v8 += (REF_Y(n, k) - m8) * (REF_Y(n, k) - m8) / (cnt - 1);
                        sy += yv[k]; sm += m8; sx += x1[k]; sv += v8;
                    }
                    bound = (sm > sx ? sm : sx) + 6.0 * sqrt(sv * (ncap + 1.0));
                    bound += 1e-5 * fabs(bound);
                    if (bound < 0) bound = 0;
                    if (sy > bound) t = bound / sy;
                    for (k = 0; k < c; ++k) yl[k] = yv[k] * t;
                }
                break; /* the window statistics keep the raw sample */
#undef REF_Y
                }
                if (nx > p->max_history) nx = p->max_history;
                if (p->rect == SBL_RECTIFY_CLAMP) {
                    for (k = 0; k < c; ++k) x1[k] = x1[k] < lo[k] ? lo[k] : x1[k] > hi[k] ? hi[k] : x1[k];
                } else if (p->rect == SBL_RECTIFY_VARIANCE_CLIP) {
                    double t = 1;
                    for (k = 0; k < c; ++k) {
                        double half = p->gamma * sqrt(var[k]), dd = fabs(x1[k] - mean[k]);
                        if (fabs(yl[k] - mean[k]) > half) half = fabs(yl[k] - mean[k]);
                        if (dd > half && half / dd < t) t = half / dd;
                    }
                    if (t < 1)
                        for (k = 0; k < c; ++k) x1[k] = mean[k] + (x1[k] - mean[k]) * t;
                }
                if (p->mode == SBL_WEIGHT_PER_CHANNEL) {
                    a = 0;
                    for (k = 0; k < c; ++k) {
                        ak[k] = ref_weight(p, (x1[k] - mean[k]) * (x1[k] - mean[k]), var[k],
                                           pd[k] * pd[k], pv[k], cnt, pairs, nx, 1.0, pool[y * w + x]);
                        a += ak[k];
                    }
                    a /= c;
                } else {
                    double dev2 = 0, s2 = 0, pd2 = 0, pvs = 0;
                    for (k = 0; k < c; ++k) {
                        dev2 += (x1[k] - mean[k]) * (x1[k] - mean[k]);
                        s2 += var[k];
                        pd2 += pd[k] * pd[k];
                        pvs += pv[k];
                    }
                    a = ref_weight(p, dev2, s2, pd2, pvs, cnt, pairs, nx, 1.0, pool[y * w + x]);
                    for (k = 0; k < c; ++k) ak[k] = a;
                    if (p->lean) { /* the restart lean reads the weight before the floor */
                        refp p0 = *p;
                        p0.alpha_min = 0;
                        a_raw = ref_weight(&p0, dev2, s2, pd2, pvs, cnt, pairs, nx, 1.0, pool[y * w + x]);
                    }
                }
                a2 = a;
                if (p->lean && cnt > 2) {
                    /* the restart lean's inputs: the neighbours' (raw Y without the
                       centre) mean and population variance, E, D, the history's texture */
                    double v8 = 0, le = 0, ld = 0, xt = -1, vy;
                    int n;
                    if (pairs > 1) xt = 0;
                    for (k = 0; k < c; ++k) {
                        double m8 = 0, s8 = 0, sx = 0;
                        for (n = 0; n < cnt; ++n)
                            if (n != centre) m8 += px(in->cur, idx[n][0], idx[n][1])[k];
                        m8 /= cnt - 1;
                        for (n = 0; n < cnt; ++n)
                            if (n != centre) {
                                double e = px(in->cur, idx[n][0], idx[n][1])[k] - m8;
                                s8 += e * e;
                                if (ispair[n]) sx += xs[(idx[n][1] * w + idx[n][0]) * c + k];
                            }
                        v8 += s8 / (cnt - 1);
                        le += (m8 - x1[k]) * (yl[k] - x1[k]);
                        ld += (yl[k] - x1[k]) * (yl[k] - x1[k]);
                        if (pairs > 1) xt += (x1[k] - sx / (pairs - 1)) * (x1[k] - sx / (pairs - 1));
                    }
                    if (pairs > 1) {
                        double pvs = 0;
                        for (k = 0; k < c; ++k) pvs += pv[k];
                        vy = pvs * nx / (nx + 1.0);
                    } else {
                        double s2 = 0;
                        for (k = 0; k < c; ++k) s2 += var[k];
                        vy = s2 * cnt / (cnt - 1);
                    }
                    a = ref_restart_lean(p, a_raw, vy, v8, le, ld, xt, cnt, nx);
                    for (k = 0; k < c; ++k) ak[k] = a;
                }
                for (k = 0; k < c; ++k) o[k] = x1[k] + ak[k] * (yl[k] - x1[k]);
                nout = ref_eq5(a2, nx, 1.0); /* the weight before the lean */
            }
            if (!(nout <= p->max_history)) nout = p->max_history;
            on[y * w + x] = nout;
            oa[y * w + x] = a;
        }
    free(xs);
    free(xn);
    free(pool);
}

static void refin_from(refin *in, const tscene *s, int with_history)
{
    memset(in, 0, sizeof *in);
    in->w = s->w; in->h = s->h; in->c = s->c;
    in->cur = &s->cur;
    in->mv = &s->mv;
    if (s->use_depth) in->depth = &s->depth;
    if (s->use_nrm) in->nrm = &s->nrm;
    if (s->use_ids) in->ids = &s->ids;
    if (with_history) {
        in->hist = &s->hist;
        if (s->use_hlen) in->hlen = &s->hlen;
        if (s->use_pdepth) in->pdepth = &s->pdepth;
        if (s->use_nrm) in->pnrm = &s->pnrm;
        if (s->use_ids) in->pids = &s->pids;
    }
}

/* Compare the library with the reference on the scene as it is. Errors are relative
   to the pixel's own scale (max |y|, |x*|, |out|) so HDR scenes are judged fairly: with
   a float weight, a blend of 1e30 and 1e-30 cannot be better than 2^-24 * 1e30. */
typedef struct cmp_stats { double col, alpha, n; long pixels, mismatched_finiteness; } cmp_stats;

static void compare_with_reference(tscene *s, const sbl_temporal_desc *d, int with_history,
                                   cmp_stats *st)
{
    refin in;
    refp p = ref_params(d);
    const int w = s->w, h = s->h, c = s->c;
    double *oc = (double *)malloc(sizeof(double) * (size_t)w * h * c);
    double *on = (double *)malloc(sizeof(double) * (size_t)w * h);
    double *oa = (double *)malloc(sizeof(double) * (size_t)w * h);
    double *oxs = (double *)malloc(sizeof(double) * (size_t)w * h);
    int x, y, k;
    refin_from(&in, s, with_history);
    CHECK_EQ(ts_run(s, d, with_history), SBL_OK);
    ref_temporal(&in, &p, oc, on, oa, oxs);
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double scale = oxs[y * w + x], e;
            for (k = 0; k < c; ++k) {
                double r = oc[(y * w + x) * c + k], yv = px(&s->cur, x, y)[k];
                if (fabs(r) > scale) scale = fabs(r);
                if (dfin(yv) && fabs(yv) > scale) scale = fabs(yv);
            }
            if (scale < 1e-30) scale = 1e-30;
            for (k = 0; k < c; ++k) {
                float f = px(&s->outc, x, y)[k];
                if (!fin(f)) { ++st->mismatched_finiteness; continue; }
                e = fabs(f - oc[(y * w + x) * c + k]) / scale;
                if (e > st->col) st->col = e;
            }
            e = fabs(*px(&s->outa, x, y) - oa[y * w + x]);
            if (e > st->alpha) st->alpha = e;
            e = fabs(*px(&s->outn, x, y) - on[y * w + x]) / (on[y * w + x] > 1 ? on[y * w + x] : 1.0);
            if (e > st->n) st->n = e;
            ++st->pixels;
        }
    free(oc); free(on); free(oa); free(oxs);
}

static float pick_depth(sbt_rng *r)
{
    static const float objs[4] = {2.0f, 3.0f, 5.0f, 8.0f};
    return objs[(int)(sbt_uniform(r) * 4.0) & 3];
}

/* Random small scenes with random motion (quantised to 1/16 pixel so that float and
   double make the same tap decisions), every estimator / rectification / weight mode /
   motion convention, depth objects, normals, ids, sky, invalid samples sprinkled in,
   several chained frames (the library's output is the next history for both). */
static void test_reference_random(void)
{
    const int w = 16, h = 8; /* powers of two: UV / NDC motion is exact in float */
    cmp_stats st;
    sbt_rng rng = {8086};
    int trial, c;
    memset(&st, 0, sizeof st);
    for (trial = 0; trial < 240; ++trial) {
        tscene s;
        sbl_temporal_desc d;
        int x, y, k, frame, obj_w = 1 + (int)(sbt_uniform(&rng) * 6);
        static const float tols[3] = {0.01f, 0.05f, 0.13f};
        static const float nset[4][3] = {{0, 0, 1}, {1, 0, 0}, {0, 0.6f, 0.8f}, {0, 0, 0}};
        c = 1 + trial % 4;
        ts_init(&s, w, h, c);
        memset(&d, 0, sizeof d);
        d.estimator = (sbl_estimator)(trial % SBL_ESTIMATOR_COUNT);
        d.rectify = (sbl_rectify)((trial / 4) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((trial / 12) % SBL_WEIGHT_MODE_COUNT);
        d.reproject.motion.units = (sbl_motion_units)((trial / 24) % 3);
        d.reproject.motion.forward = (trial / 72) % 2;
        d.reproject.motion.y_up = (trial / 144) % 2;
        d.reproject.no_fallback = sbt_uniform(&rng) < 0.3;
        d.reproject.depth_tolerance = tols[trial % 3];
        d.reproject.normal_threshold = sbt_uniform(&rng) < 0.2 ? -1.0f : 0.0f;
        d.alpha_min = sbt_uniform(&rng) < 0.3 ? (float)(0.3 * sbt_uniform(&rng)) : 0.0f;
        d.constant_alpha = sbt_uniform(&rng) < 0.5 ? (float)sbt_uniform(&rng) : 0.0f;
        d.max_history = sbt_uniform(&rng) < 0.5 ? 0.0f : (float)(1.0 + 99.0 * sbt_uniform(&rng));
        d.clip_gamma = sbt_uniform(&rng) < 0.5 ? 0.0f : (float)(0.5 + 2.0 * sbt_uniform(&rng));
        d.bias_threshold = sbt_uniform(&rng) < 0.5 ? 0.0f : (float)(0.5 + 5.0 * sbt_uniform(&rng));
        s.use_nrm = sbt_uniform(&rng) < 0.5;
        s.use_ids = sbt_uniform(&rng) < 0.5;
        s.use_hlen = sbt_uniform(&rng) < 0.85;
        s.use_depth = sbt_uniform(&rng) < 0.9;
        s.use_pdepth = sbt_uniform(&rng) < 0.9;
        /* objects: vertical stripes of random width, each with depth, normal, id */
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int o = (x / obj_w + (y > h / 2 ? 1 : 0)) & 3;
                double t = 0.5 + 0.3 * sin(0.8 * x + 1.7 * o) + 0.1 * o;
                float z = pick_depth(&rng);
                (void)z;
                *px(&s.depth, x, y) = 2.0f + 3.0f * (float)o;
                *px(&s.pdepth, x, y) = 2.0f + 3.0f * (float)((o + (sbt_uniform(&rng) < 0.1)) & 3);
                for (k = 0; k < 3; ++k) { px(&s.nrm, x, y)[k] = nset[o][k]; px(&s.pnrm, x, y)[k] = nset[o][k]; }
                *px(&s.ids, x, y) = (float)o;
                *px(&s.pids, x, y) = (float)o;
                for (k = 0; k < c; ++k) {
                    px(&s.hist, x, y)[k] = (float)(t + 0.05 * k + 0.1 * sbt_gauss(&rng));
                    px(&s.cur, x, y)[k] = (float)(t + 0.05 * k + 0.2 * sbt_gauss(&rng));
                }
                *px(&s.hlen, x, y) = 0.25f * (float)(int)(1 + 320 * sbt_uniform(&rng));
                if (sbt_uniform(&rng) < 0.03) *px(&s.depth, x, y) = f_inf();
                if (sbt_uniform(&rng) < 0.03) *px(&s.pdepth, x, y) = f_inf();
                if (sbt_uniform(&rng) < 0.02) *px(&s.depth, x, y) = sbt_uniform(&rng) < 0.5 ? 0.0f : f_nan();
                if (sbt_uniform(&rng) < 0.02) *px(&s.hlen, x, y) = sbt_uniform(&rng) < 0.5 ? 0.0f : f_nan();
                if (sbt_uniform(&rng) < 0.02) px(&s.hist, x, y)[0] = f_nan();
            }
        for (frame = 0; frame < 3; ++frame) {
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    /* displacement in pixels, 1/16 steps, in [-2.5, 2.5] */
                    double dx = floor((sbt_uniform(&rng) * 5.0 - 2.5) * 16.0) / 16.0;
                    double dy = floor((sbt_uniform(&rng) * 5.0 - 2.5) * 16.0) / 16.0;
                    sbl_motion_convention mc = d.reproject.motion;
                    if (mc.forward) { dx = -dx; dy = -dy; }
                    if (mc.y_up) dy = -dy;
                    if (mc.units == SBL_MOTION_UV) { dx /= w; dy /= h; }
                    if (mc.units == SBL_MOTION_NDC) { dx *= 2.0 / w; dy *= 2.0 / h; }
                    px(&s.mv, x, y)[0] = (float)dx;
                    px(&s.mv, x, y)[1] = (float)dy;
                    if (sbt_uniform(&rng) < 0.02) px(&s.mv, x, y)[sbt_uniform(&rng) < 0.5] = sbt_uniform(&rng) < 0.5 ? f_nan() : 1e30f;
                    for (k = 0; k < c; ++k)
                        px(&s.cur, x, y)[k] = (float)(0.5 + 0.3 * sin(0.8 * x) + 0.2 * sbt_gauss(&rng));
                    if (sbt_uniform(&rng) < 0.02) px(&s.cur, x, y)[c - 1] = f_nan();
                }
            compare_with_reference(&s, &d, frame > 0 || trial % 5 != 0, &st);
            CHECK(ts_outputs_sane(&s, d.max_history == 0.0f ? 64.0f : d.max_history));
            /* chain: the output (and its N) becomes the next history */
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    for (k = 0; k < c; ++k) px(&s.hist, x, y)[k] = px(&s.outc, x, y)[k];
                    *px(&s.hlen, x, y) = *px(&s.outn, x, y);
                }
        }
        ts_free(&s);
    }
    printf("  float vs double reference (%ld pixels, 240 random scenes x 3 frames): max error "
           "colour %.3g (relative to pixel scale), alpha %.3g, N %.3g (relative)\n",
           st.pixels, st.col, st.alpha, st.n);
    CHECK_EQ(st.mismatched_finiteness, 0);
    CHECK(st.col <= 1e-5);
    /* the history-aware bias term pd^2 - k^2 pv / n is a difference that can be near 0
       at the threshold, where it amplifies float rounding about 100x (measured alpha
       5.8e-6, N 1.6e-5 relative); N inherits about twice the alpha error */
    CHECK(st.alpha <= 3e-5);
    CHECK(st.n <= 6e-5);
}

/* The same reference on an HDR scene: 1e-30 .. 1e30 in one image, values per pixel
   spanning 60 decades. Relative to each pixel's own scale. */
static void test_reference_hdr(void)
{
    cmp_stats st;
    sbt_rng rng = {60};
    int trial;
    memset(&st, 0, sizeof st);
    for (trial = 0; trial < 48; ++trial) {
        tscene s;
        sbl_temporal_desc d;
        int x, y, k;
        ts_init(&s, 10, 7, 3);
        memset(&d, 0, sizeof d);
        d.estimator = (sbl_estimator)(trial % SBL_ESTIMATOR_COUNT);
        d.rectify = (sbl_rectify)((trial / 4) % SBL_RECTIFY_COUNT);
        d.weight_mode = (sbl_weight_mode)((trial / 12) % SBL_WEIGHT_MODE_COUNT);
        for (y = 0; y < 7; ++y)
            for (x = 0; x < 10; ++x) {
                double sc = pow(10.0, trial % 2 ? -30.0 + 60.0 * sbt_uniform(&rng)
                                                : (x + y) % 2 ? 30.0 : -30.0);
                for (k = 0; k < 3; ++k) {
                    px(&s.cur, x, y)[k] = (float)(sc * (1.0 + 0.3 * sbt_gauss(&rng)));
                    px(&s.hist, x, y)[k] = (float)(sc * (1.0 + 0.2 * sbt_gauss(&rng)));
                }
                px(&s.mv, x, y)[0] = (float)(floor(sbt_uniform(&rng) * 32.0 - 16.0) / 16.0);
                px(&s.mv, x, y)[1] = (float)(floor(sbt_uniform(&rng) * 32.0 - 16.0) / 16.0);
                *px(&s.hlen, x, y) = (float)(1 + (int)(60 * sbt_uniform(&rng)));
            }
        compare_with_reference(&s, &d, 1, &st);
        CHECK(ts_outputs_sane(&s, 64.0f));
        ts_free(&s);
    }
    printf("  float vs double reference, HDR 1e-30..1e30: max error colour %.3g (relative "
           "to pixel scale), alpha %.3g, N %.3g\n", st.col, st.alpha, st.n);
    CHECK_EQ(st.mismatched_finiteness, 0);
    CHECK(st.col <= 1e-5);
    CHECK(st.alpha <= 1e-5);
    CHECK(st.n <= 1e-5);
}

/* ======================================================================== */
/* 10,000 frames                                                             */
/* ======================================================================== */

/* Progressive estimator, max_history 64, static scene, new samples mu + U(-h, h).

   After the warm-up the filter is an EMA with a = 1/65: out_t = sum_i w_i y_i with
   w_i >= 0, sum w_i = 1, so out_t - mu = sum w_i e_i. Each e_i is sub-Gaussian with
   variance proxy h^2/3 (uniform), so P(|out_t - mu| > s) <= 2 exp(-s^2 / (2 (h^2/3)
   S_t)) with S_t = sum w_i^2 = (1-a)^2 S_{t-1} + a^2 (-> a/(2-a) = 1/129). A union
   bound over all P pixel-channels and F frames at total probability delta gives

       |out_t - mu| <= h sqrt((2/3) S_t ln(2 P F / delta))            (statistical)

   and, being a convex combination, never more than h.

   Float rounding (u = 2^-24): one step x' = fl(x + fl(a_f fl(y - x))) differs from the
   exact step by at most u (3 |a (y - x)| + 3 |x'|) (three roundings on each form of
   the lerp), plus |da| |y - x| from a_f, whose relative error stays below 64 u through
   the warm-up (N accumulates one rounding per frame until the cap makes it exactly 64).
   Errors contract by (1 - a) per frame, so |out_f - out_exact| <= sup_t L_t / a_t:

       B_num = u (2h (3 + 64) + 3 (|mu| + h) / a_min),  a_min = 1/65       (numerical)

   The test tracks the exact recursion in double beside the library and checks both
   bounds on every pixel of every frame; it also reports the mean signed drift. */
static void test_stress_progressive_10000(void)
{
    const int w = 8, h = 6, c = 3, F = 10000;
    const double mu[3] = {1.0, 1e-20, 1e20};
    const double delta = 1e-6, u = 1.0 / 16777216.0, a_min = 1.0 / 65.0;
    tscene s[2];
    sbl_temporal_desc d;
    sbt_rng rng = {10000};
    double *xd = (double *)malloc(sizeof(double) * w * h * c);
    double S = 1.0, nd = 1.0, lnterm = log(2.0 * w * h * c * F / delta);
    double worst_stat[3] = {0, 0, 0}, worst_num[3] = {0, 0, 0}, drift_sum[3] = {0, 0, 0};
    double bnum[3], hh[3], final_dev[3] = {0, 0, 0};
    long drift_n = 0;
    int t, x, y, k, ping = 0, fails_stat = 0, fails_num = 0, bad_n = 0;
    for (k = 0; k < 3; ++k) {
        hh[k] = 0.5 * mu[k];
        bnum[k] = u * (2.0 * hh[k] * 67.0 + 3.0 * (fabs(mu[k]) + hh[k]) / a_min);
    }
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    d.max_history = 64.0f;
    ts_init(&s[0], w, h, c);
    ts_init(&s[1], w, h, c);
    for (t = 0; t < F; ++t) {
        tscene *cur = &s[ping], *prev = &s[!ping];
        sbl_frame f;
        sbl_history hi;
        sbl_temporal_output o;
        double a;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                for (k = 0; k < c; ++k)
                    px(&cur->cur, x, y)[k] = (float)(mu[k] + hh[k] * (2.0 * sbt_uniform(&rng) - 1.0));
        ts_views(cur, &f, &hi, &o);
        hi.color = vw(&prev->outc);
        hi.length = vw(&prev->outn);
        CHECK_EQ(sbl_temporal_filter_frame(&d, &f, t == 0 ? NULL : &hi, &o), SBL_OK);
        /* the exact recursion (on the float samples the library saw) */
        a = t == 0 ? 1.0 : 1.0 / (nd + 1.0);
        if (t > 0) {
            nd = ref_eq5(a, nd, 1.0);
            if (nd > 64.0) nd = 64.0;
            S = (1 - a) * (1 - a) * S + a * a;
        }
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                bad_n += !(fabs(*px(&cur->outn, x, y) - nd) <= 1e-3);
                for (k = 0; k < c; ++k) {
                    double *xe = xd + (y * w + x) * c + k, stat_bound, err, dev;
                    double yv = px(&cur->cur, x, y)[k];
                    *xe = t == 0 ? yv : *xe + a * (yv - *xe);
                    err = px(&cur->outc, x, y)[k] - *xe;
                    dev = fabs(px(&cur->outc, x, y)[k] - mu[k]);
                    stat_bound = hh[k] * sqrt((2.0 / 3.0) * S * lnterm);
                    if (stat_bound > hh[k]) stat_bound = hh[k];
                    fails_num += !(fabs(err) <= bnum[k]);
                    fails_stat += !(dev <= stat_bound + bnum[k]);
                    if (fabs(err) / bnum[k] > worst_num[k]) worst_num[k] = fabs(err) / bnum[k];
                    if (t >= 1000 && dev / hh[k] > worst_stat[k]) worst_stat[k] = dev / hh[k];
                    if (t >= 1000) drift_sum[k] += err;
                    if (t == F - 1) final_dev[k] += (px(&cur->outc, x, y)[k] - mu[k]) / (w * h);
                }
            }
        if (t >= 1000) ++drift_n;
        ping = !ping;
    }
    for (k = 0; k < 3; ++k)
        printf("  10000 frames progressive, mu %.0e h %.0e: bound |out-mu| <= %.4f h (stat, "
               "S=1/129) + %.3g (num); measured max |out-mu| %.4f h, max |float-exact| %.3g "
               "(%.1f%% of bound), mean signed drift %.2g (%.2g of mu), final spatial mean "
               "dev %.2g h\n",
               mu[k], hh[k], sqrt((2.0 / 3.0) * (1.0 / 129.0) * lnterm), bnum[k],
               worst_stat[k], worst_num[k] * bnum[k], 100.0 * worst_num[k],
               drift_sum[k] / (drift_n * w * h), drift_sum[k] / (drift_n * w * h) / mu[k],
               final_dev[k] / hh[k]);
    CHECK_EQ(fails_num, 0);
    CHECK_EQ(fails_stat, 0);
    CHECK_EQ(bad_n, 0);
    CHECK(ts_outputs_sane(&s[!ping], 64.0f));
    ts_free(&s[0]);
    ts_free(&s[1]);
    free(xd);
}

/* Every estimator and rectification over a long static run: the output is a convex
   combination of samples, so it never leaves [mu - h, mu + h] (plus rounding), N stays
   in [1, max_history] and alpha in [0, 1]. History-aware: 10,000 frames; the others
   1,500 each (time). */
static void test_stress_all_estimators(void)
{
    const int w = 6, h = 6, c = 3;
    const double mu = 0.5, hw = 0.25, slack = 8.0 * (mu + hw) / 16777216.0;
    int e, r;
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e)
        for (r = 0; r < SBL_RECTIFY_COUNT; ++r) {
            tscene s[2];
            sbl_temporal_desc d;
            sbt_rng rng;
            int frames = (e == SBL_ESTIMATOR_HISTORY_AWARE && r == 0) ? 10000 : 1500;
            int t, x, y, k, ping = 0, outside = 0, badn = 0;
            double lo = 1e9, hi = -1e9;
            rng.s = 77 + (unsigned long long)(e * 3 + r);
            memset(&d, 0, sizeof d);
            d.estimator = (sbl_estimator)e;
            d.rectify = (sbl_rectify)r;
            d.weight_mode = (sbl_weight_mode)(r % 2);
            ts_init(&s[0], w, h, c);
            ts_init(&s[1], w, h, c);
            for (t = 0; t < frames; ++t) {
                tscene *cur = &s[ping], *prev = &s[!ping];
                sbl_frame f;
                sbl_history hi2;
                sbl_temporal_output o;
                ts_noisy(cur, &cur->cur, &rng, mu, hw);
                ts_views(cur, &f, &hi2, &o);
                hi2.color = vw(&prev->outc);
                hi2.length = vw(&prev->outn);
                if (sbl_temporal_filter_frame(&d, &f, t == 0 ? NULL : &hi2, &o) != SBL_OK) ++badn;
                for (y = 0; y < h; ++y)
                    for (x = 0; x < w; ++x) {
                        float n = *px(&cur->outn, x, y), a = *px(&cur->outa, x, y);
                        badn += !(n >= 1.0f && n <= 64.0f && a >= 0.0f && a <= 1.0f);
                        for (k = 0; k < c; ++k) {
                            double v = px(&cur->outc, x, y)[k];
                            outside += !(v >= mu - hw - slack && v <= mu + hw + slack);
                            if (t > frames / 2 && v < lo) lo = v;
                            if (t > frames / 2 && v > hi) hi = v;
                        }
                    }
                ping = !ping;
            }
            if (e == SBL_ESTIMATOR_HISTORY_AWARE && r == 0)
                printf("  10000 frames history-aware: output range in the second half "
                       "[%.4f, %.4f] (samples: [0.25, 0.75])\n", lo, hi);
            CHECK_EQ(outside, 0);
            CHECK_EQ(badn, 0);
            ts_free(&s[0]);
            ts_free(&s[1]);
        }
}

/* A lit static pixel goes black and stays black for 10,000 frames. Progressive
   averaging decays the history by 64/65 per frame: after ~5,600 frames it is
   denormal, and it ends stuck at a few denormal ulps where a * x rounds to 0 (with
   FTZ/DAZ it reaches 0). The history-aware estimator sees the bias and drops the
   history at once. Both stay finite and N stays capped. */
static void test_decay_to_black(void)
{
    const int w = 4, h = 4, c = 1;
    int e;
    for (e = 0; e < 2; ++e) {
        tscene s[2];
        sbl_temporal_desc d;
        int t, ping = 0, first_denormal = -1;
        float last = 0.0f;
        memset(&d, 0, sizeof d);
        d.estimator = e ? SBL_ESTIMATOR_HISTORY_AWARE : SBL_ESTIMATOR_PROGRESSIVE;
        ts_init(&s[0], w, h, c);
        ts_init(&s[1], w, h, c);
        for (t = 0; t < 10000; ++t) {
            tscene *cur = &s[ping], *prev = &s[!ping];
            sbl_frame f;
            sbl_history hi;
            sbl_temporal_output o;
            rimg_fill(&cur->cur, t < 100 ? 1.0f : 0.0f);
            ts_views(cur, &f, &hi, &o);
            hi.color = vw(&prev->outc);
            hi.length = vw(&prev->outn);
            CHECK(sbl_temporal_filter_frame(&d, &f, t == 0 ? NULL : &hi, &o) == SBL_OK);
            last = *px(&cur->outc, 1, 1);
            if (first_denormal < 0 && last != 0.0f && fabsf(last) < FLT_MIN) first_denormal = t;
            if (e == 1 && t == 100) CHECK_EQ(last, 0); /* history-aware: immediately */
            ping = !ping;
        }
        if (e == 0)
            printf("  black after light, progressive: denormal from frame %d on, value after "
                   "10000 frames %.3g (%s)\n", first_denormal, (double)last,
                   ftz_mode() ? "FTZ/DAZ on" : "FTZ/DAZ off");
        CHECK(fin(last) && fabsf(last) < 1e-30f);
        CHECK(ts_outputs_sane(&s[!ping], 64.0f));
        ts_free(&s[0]);
        ts_free(&s[1]);
    }
}

/* ======================================================================== */
/* Denormal cost                                                             */
/* ======================================================================== */

static double time_frames(tscene *s, const sbl_temporal_desc *d, int reps)
{
    double best = 1e30;
    int r, i;
    for (r = 0; r < 5; ++r) {
        clock_t t0 = clock();
        for (i = 0; i < reps; ++i) ts_run(s, d, 1);
        {
            double dt = (double)(clock() - t0) / CLOCKS_PER_SEC;
            if (dt < best) best = dt;
        }
    }
    return best;
}

/* A frame (new samples and history) full of 1e-39 (denormal) against the same frame at
   1.0, and at 1e-20 (normal, but outside the header's fast-path range [1e-15, 1e15], so
   it takes the same double reference path as the denormal frame): 1e-39 / 1e-20 is the
   cost of denormal arithmetic itself, 1e-20 / 1.0 the cost of leaving the fast path.
   Reported, not asserted (a property of the CPU and of the FTZ/DAZ mode the caller runs
   with), and only on request: SBL_DENORMAL_TIMING=1 in the environment times the frames,
   SBL_DENORMAL_MAX_RATIO=<x> also checks 1e-39 / 1.0. Without either, each scale runs
   once for the sanity check of its outputs (timing is the bench's job: make check runs
   this file in ten configurations, at -O0 and under the sanitizers too). */
static void scale_frame(tscene *s, float f)
{
    int x, y, k;
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x)
            for (k = 0; k < s->c; ++k) {
                px(&s->cur, x, y)[k] = f * (1.0f + 0.25f * (float)((x * 7 + y * 3 + k) % 5));
                px(&s->hist, x, y)[k] = f * (1.0f + 0.25f * (float)((x * 5 + y + k) % 4));
            }
}

static void test_denormal_timing(void)
{
    const int w = 64, h = 48, c = 3;
    tscene s;
    sbl_temporal_desc d;
    double ratio_worst = 0;
    const int timed = getenv("SBL_DENORMAL_TIMING") || getenv("SBL_DENORMAL_MAX_RATIO");
    int e;
    ts_init(&s, w, h, c);
    for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
        double tn, tm, td;
        int x, y;
        memset(&d, 0, sizeof d);
        d.estimator = (sbl_estimator)e;
        d.rectify = SBL_RECTIFY_VARIANCE_CLIP;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                px(&s.mv, x, y)[0] = 0.25f; /* bilinear weights: all four taps */
                px(&s.mv, x, y)[1] = 0.5f;
                *px(&s.hlen, x, y) = 8.0f;
            }
        if (!timed) {
            const float scales[3] = {1.0f, 1e-20f, 1e-39f};
            int i;
            for (i = 0; i < 3; ++i) {
                scale_frame(&s, scales[i]);
                ts_run(&s, &d, 1);
                CHECK(ts_outputs_sane(&s, 64.0f));
            }
            continue;
        }
        scale_frame(&s, 1.0f);
        tn = time_frames(&s, &d, 8);
        scale_frame(&s, 1e-20f);
        tm = time_frames(&s, &d, 8);
        scale_frame(&s, 1e-39f);
        td = time_frames(&s, &d, 8);
        printf("  denormal cost, estimator %d: ms/frame 1.0: %.3f, 1e-20: %.3f, 1e-39: %.3f; "
               "1e-39/1.0 = %.2f, 1e-39/1e-20 = %.2f%s\n",
               e, 1e3 * tn / 8, 1e3 * tm / 8, 1e3 * td / 8, td / tn, td / tm,
               ftz_mode() ? " (FTZ/DAZ on)" : "");
        if (td / tn > ratio_worst) ratio_worst = td / tn;
        CHECK(ts_outputs_sane(&s, 64.0f));
    }
    if (!timed) printf("  denormal frames: outputs sane at 1.0, 1e-20, 1e-39 (cost not timed: "
                       "SBL_DENORMAL_TIMING=1 times it)\n");
    {
        const char *env = getenv("SBL_DENORMAL_MAX_RATIO");
        if (env) CHECK(ratio_worst <= atof(env));
    }
    ts_free(&s);
}

/* Bug 6 (regression): with alpha = 1 the output must be the new sample exactly. The
   header blends as x* + a (y - x*), which cancels to 0 (or to rounding noise of x*)
   when |x*| >> |y|: a dim pixel next to a bright history loses its own value even
   though the weight says "take y". Bright / dim pairs inside the fast path's range
   and outside it. Fails until the two-sided lerp patch. */
static void test_regression_lerp_dim_sample(void)
{
    tscene s;
    sbl_temporal_desc d;
    float pairs[3][2];
    int i, e, bad = 0;
    pairs[0][0] = 1e14f; pairs[0][1] = 3e-14f;  /* fast path */
    pairs[1][0] = 1e30f; pairs[1][1] = 3e-30f;  /* reference path */
    pairs[2][0] = 4.0f; pairs[2][1] = 1e-9f;
    ts_init(&s, 6, 5, 3);
    for (i = 0; i < 3; ++i)
        for (e = 0; e < 2; ++e) {
            int x, y, k;
            memset(&d, 0, sizeof d);
            d.estimator = e ? SBL_ESTIMATOR_PAPER : SBL_ESTIMATOR_HISTORY_AWARE;
            rimg_fill(&s.hist, pairs[i][0]);
            rimg_fill(&s.cur, pairs[i][1]);
            rimg_fill(&s.hlen, 8.0f);
            CHECK_EQ(ts_run(&s, &d, 1), SBL_OK);
            CHECK(ts_outputs_sane(&s, 64.0f));
            for (y = 0; y < 5; ++y)
                for (x = 0; x < 6; ++x) {
                    if (*px(&s.outa, x, y) != 1.0f) { ++bad; continue; } /* bias: a = 1 */
                    for (k = 0; k < 3; ++k) bad += px(&s.outc, x, y)[k] != pairs[i][1];
                }
        }
    CHECK_EQ(bad, 0);
    ts_free(&s);
}

/* ======================================================================== */
/* Stereo sanitising                                                         */
/* ======================================================================== */

typedef struct sscene {
    int w, h, c;
    rimg col[2], dep[2], len[2], disp[2], out[2], outn[2], valid;
    unsigned char *mask;
} sscene;

static void ss_init(sscene *s, int w, int h, int c, sbt_rng *rng)
{
    int e, x, y, k;
    s->w = w; s->h = h; s->c = c;
    for (e = 0; e < 2; ++e) {
        s->col[e] = rimg_new(w, h, c, e);
        s->dep[e] = rimg_new(w, h, 1, 1);
        s->len[e] = rimg_new(w, h, 1, 0);
        s->disp[e] = rimg_new(w, h, 1, 2);
        s->out[e] = rimg_new(w, h, c, 1);
        s->outn[e] = rimg_new(w, h, 1, 1);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                for (k = 0; k < c; ++k) px(&s->col[e], x, y)[k] = (float)(0.5 + 0.1 * sbt_gauss(rng));
                *px(&s->dep[e], x, y) = 4.0f;  /* disparity = focal 8 * baseline 1 / 4 = 2 px */
                *px(&s->disp[e], x, y) = 2.0f;
                *px(&s->len[e], x, y) = 4.0f;
            }
    }
    s->valid = rimg_new(w, h, 1, 0);
    s->mask = (unsigned char *)malloc((size_t)w * h);
}
static void ss_free(sscene *s)
{
    int e;
    for (e = 0; e < 2; ++e) {
        rimg_free(&s->col[e]); rimg_free(&s->dep[e]); rimg_free(&s->len[e]);
        rimg_free(&s->disp[e]); rimg_free(&s->out[e]); rimg_free(&s->outn[e]);
    }
    rimg_free(&s->valid);
    free(s->mask);
}
static void ss_eye(const sscene *s, int e, sbl_eye *eye)
{
    memset(eye, 0, sizeof *eye);
    eye->color = vw(&s->col[e]);
    eye->length = vw(&s->len[e]);
    eye->gbuffer.depth = vw(&s->dep[e]);
    eye->disparity = vw(&s->disp[e]);
}
/* blend the left eye, reproject, fill: all outputs must be finite, N >= 0 */
static int ss_run_all(sscene *s, const sbl_stereo_desc *d)
{
    sbl_eye l, r;
    size_t bytes = sbl_stereo_scratch_size(s->w, s->c);
    void *scratch = malloc(bytes);
    long count = -1, ones = 0;
    int ok = 1, i;
    ss_eye(s, 0, &l);
    ss_eye(s, 1, &r);
    ok &= sbl_stereo_blend(d, SBL_EYE_LEFT, &l, &r, vw(&s->out[0]), vw(&s->outn[0]), 0, s->h, scratch, bytes) == SBL_OK;
    ok &= rimg_finite(&s->out[0]) && rimg_finite(&s->outn[0]) && rimg_pad_ok(&s->out[0]);
    for (i = 0; i < s->w * s->h; ++i) ok &= *px(&s->outn[0], i % s->w, i / s->w) >= 0.0f;
    ok &= sbl_stereo_blend_frame(d, &l, &r, vw(&s->out[0]), vw(&s->out[1])) == SBL_OK;
    ok &= rimg_finite(&s->out[0]) && rimg_finite(&s->out[1]);
    ok &= sbl_reproject_stereo(d, SBL_EYE_RIGHT, &r, &l, vw(&s->out[1]), vw(&s->valid), 0, s->h) == SBL_OK;
    ok &= rimg_finite(&s->out[1]) && rimg_finite(&s->valid);
    ok &= sbl_stereo_fill(d, SBL_EYE_RIGHT, &r, &l, vw(&s->out[1]), s->mask, s->w, 0, s->h, &count) == SBL_OK;
    ok &= rimg_finite(&s->out[1]);
    for (i = 0; i < s->w * s->h; ++i) { ok &= s->mask[i] <= 1; ones += s->mask[i]; }
    ok &= ones == count;
    free(scratch);
    return ok;
}

static void test_stereo_sanitise(void)
{
    sbt_rng rng = {42};
    sscene s;
    sbl_stereo_desc d;
    int rig;
    ss_init(&s, 12, 6, 3, &rng);
    for (rig = 0; rig < 2; ++rig) {
        int e;
        memset(&d, 0, sizeof d);
        d.rig = (sbl_stereo_rig)rig;
        d.focal_px = 8.0f;
        d.baseline = 1.0f;
        for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
            d.estimator = (sbl_estimator)e;
            CHECK(ss_run_all(&s, &d));
        }
        /* non-finite everywhere in both eyes */
        for (e = 0; e < 2; ++e) {
            sprinkle(&s.col[e], &rng, 0.1);
            sprinkle(&s.dep[e], &rng, 0.1);
            sprinkle(&s.len[e], &rng, 0.1);
            sprinkle(&s.disp[e], &rng, 0.1);
        }
        for (e = 0; e < SBL_ESTIMATOR_COUNT; ++e) {
            d.estimator = (sbl_estimator)e;
            d.rectify = (sbl_rectify)(e % 3);
            CHECK(ss_run_all(&s, &d));
            d.fill = 1;
            CHECK(ss_run_all(&s, &d));
            d.fill = 0;
        }
        ss_free(&s);
        ss_init(&s, 12, 6, 3, &rng);
    }
    /* parameters: focal / baseline non-finite or not positive (parallel rig) */
    {
        float bad[5];
        int i;
        sbl_eye l, r;
        bad[0] = f_nan(); bad[1] = f_inf(); bad[2] = 0.0f; bad[3] = -1.0f; bad[4] = f_ninf();
        ss_eye(&s, 0, &l);
        ss_eye(&s, 1, &r);
        for (i = 0; i < 5; ++i) {
            memset(&d, 0, sizeof d);
            d.focal_px = bad[i]; d.baseline = 1.0f;
            CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &l, &r, vw(&s.out[0]), vw(&s.valid), 0, 6), SBL_ERROR_INVALID_PARAM);
            d.focal_px = 8.0f; d.baseline = bad[i];
            CHECK_EQ(sbl_stereo_blend_frame(&d, &l, &r, vw(&s.out[0]), vw(&s.out[1])), SBL_ERROR_INVALID_PARAM);
        }
        memset(&d, 0, sizeof d);
        d.focal_px = 8.0f; d.baseline = 1.0f;
        d.constant_beta = f_nan();
        CHECK_EQ(sbl_stereo_blend_frame(&d, &l, &r, vw(&s.out[0]), vw(&s.out[1])), SBL_ERROR_INVALID_PARAM);
        d.constant_beta = 0.0f; d.rig = (sbl_stereo_rig)3;
        CHECK_EQ(sbl_stereo_blend_frame(&d, &l, &r, vw(&s.out[0]), vw(&s.out[1])), SBL_ERROR_INVALID_PARAM);
        d.rig = SBL_RIG_PARALLEL;
        CHECK_EQ(sbl_reproject_stereo(&d, (sbl_eye_index)2, &l, &r, vw(&s.out[0]), vw(&s.valid), 0, 6), SBL_ERROR_INVALID_PARAM);
        /* focal * baseline overflowing float: every disparity is inf -> no match */
        d.focal_px = 1e30f; d.baseline = 1e30f;
        CHECK(ss_run_all(&s, &d));
        /* matrices rig without cameras */
        d.rig = SBL_RIG_MATRICES;
        CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &l, &r, vw(&s.out[0]), vw(&s.valid), 0, 6), SBL_ERROR_MISSING_INPUT);
        /* a fill / reprojection target needs depth or disparity for its geometry: with
           neither, SBL_ERROR_MISSING_INPUT */
        d.rig = SBL_RIG_DISPARITY;
        d.focal_px = 8.0f; d.baseline = 1.0f;
        l.gbuffer.depth.data = NULL;
        l.disparity.data = NULL;
        {
            long cnt = 0;
            CHECK_EQ(sbl_stereo_fill(&d, SBL_EYE_LEFT, &l, &r, vw(&s.out[0]), s.mask, 12, 0, 6, &cnt), SBL_ERROR_MISSING_INPUT);
            CHECK_EQ(sbl_reproject_stereo(&d, SBL_EYE_LEFT, &l, &r, vw(&s.out[0]), vw(&s.valid), 0, 6), SBL_ERROR_MISSING_INPUT);
        }
    }
    ss_free(&s);
}

/* Bug 5 (regression): the effective sample count of a stereo blend of two eyes whose
   N are near FLT_MAX overflows float to +inf (sbl_blend_sample_count computes in
   double and casts); N should saturate at FLT_MAX. Fails until the patch. */
static void test_regression_sample_count_overflow(void)
{
    sbt_rng rng = {5};
    sscene s;
    sbl_stereo_desc d;
    sbl_eye l, r;
    size_t bytes;
    void *scratch;
    ss_init(&s, 8, 4, 1, &rng);
    rimg_fill(&s.len[0], 3e38f);
    rimg_fill(&s.len[1], 3e38f);
    memset(&d, 0, sizeof d);
    d.rig = SBL_RIG_DISPARITY;
    d.estimator = SBL_ESTIMATOR_PROGRESSIVE;
    ss_eye(&s, 0, &l);
    ss_eye(&s, 1, &r);
    bytes = sbl_stereo_scratch_size(8, 1);
    scratch = malloc(bytes);
    CHECK_EQ(sbl_stereo_blend(&d, SBL_EYE_LEFT, &l, &r, vw(&s.out[0]), vw(&s.outn[0]), 0, 4, scratch, bytes), SBL_OK);
    CHECK(rimg_finite(&s.out[0]));
    CHECK(rimg_finite(&s.outn[0]));
    CHECK(fin(sbl_blend_sample_count(0.5f, 3e38f, 3e38f)));
    free(scratch);
    ss_free(&s);
}

/* The scalar helpers with degenerate arguments: documented cases, and results inside
   [0, 1] / finite for the rest. */
static void test_scalar_helpers(void)
{
    CHECK_NEAR(sbl_optimal_weight(0.0f, f_inf(), 1.0f), 1.0, 0);
    CHECK_NEAR(sbl_optimal_weight(f_inf(), 0.0f, 1.0f), 1.0, 0);
    CHECK_NEAR(sbl_optimal_weight(0.0f, 0.0f, 0.0f), 0.5, 0);
    CHECK_NEAR(sbl_optimal_weight(0.0f, 1e-45f, 1e-45f), 0.5, 1e-6);
    CHECK_NEAR(sbl_optimal_weight(0.0f, 1e38f, 3e38f), 0.25, 1e-6); /* sum > FLT_MAX: double */
    CHECK_NEAR(sbl_optimal_weight(0.0f, 1e-30f, 3e-30f), 0.25, 1e-6);
    CHECK_NEAR(sbl_blend_sample_count(1.0f / 65.0f, 64.0f, 1.0f), 65.0, 1e-4);
    CHECK(fin(sbl_blend_sample_count(0.5f, 1e-45f, 1.0f)));
}

/* sbl_merge_traced with non-finite traced values copies them as they are (it is a copy,
   not a filter) and only where the mask says so; with the shared canary images. */
static void test_merge_traced(void)
{
    sbt_img dst = sbt_img_new(5, 3, 3, 2), tr = sbt_img_new(5, 3, 3, 1);
    unsigned char mask[15];
    int i;
    for (i = 0; i < 15; ++i) mask[i] = (unsigned char)(i % 2);
    sbt_at(&tr, 1, 0)[0] = f_nan();
    sbt_at(&tr, 2, 0)[0] = f_nan();
    {
        sbl_image a, b;
        memset(&a, 0, sizeof a); memset(&b, 0, sizeof b);
        a.data = dst.mem; a.width = 5; a.height = 3; a.channels = 3; a.stride = dst.stride;
        b.data = tr.mem; b.width = 5; b.height = 3; b.channels = 3; b.stride = tr.stride;
        CHECK_EQ(sbl_merge_traced(a, b, mask, 5, 0, 3), SBL_OK);
        CHECK(!fin(sbt_at(&dst, 1, 0)[0]));  /* copied: mask 1 */
        CHECK(fin(sbt_at(&dst, 2, 0)[0]));   /* not copied: mask 0 */
        CHECK_EQ(sbl_merge_traced(a, b, NULL, 5, 0, 3), SBL_ERROR_NULL_POINTER);
        CHECK_EQ(sbl_merge_traced(a, b, mask, 4, 0, 3), SBL_ERROR_INVALID_STRIDE);
        CHECK_EQ(sbl_merge_traced(a, a, mask, 5, 0, 3), SBL_ERROR_OVERLAP);
    }
    CHECK(sbt_canaries_ok(&dst));
    free(dst.mem);
    free(tr.mem);
}

int main(void)
{
    printf("  FTZ/DAZ %s, fast-math %s\n", ftz_mode() ? "on" : "off", FAST_MATH ? "on" : "off");
    test_sanitise_color();
    test_sanitise_depth();
    test_sanitise_normals_ids();
    test_sanitise_motion();
    test_all_bad_at_once();
    test_params();
    test_hdr_moments();
    test_hdr_scale_invariance();
    test_constant_images();
    test_reference_random();
    test_reference_hdr();
    /* the long runs (10,000 frames) check numerical drift, which the sanitizers do not
       change: make check's asan configuration sets SBL_TEST_SKIP_LONG=1, and every
       other configuration runs them */
    if (!getenv("SBL_TEST_SKIP_LONG")) {
        test_stress_progressive_10000();
        test_stress_all_estimators();
        test_decay_to_black();
    } else {
        printf("  10,000-frame drift runs skipped (SBL_TEST_SKIP_LONG is set)\n");
    }
    test_denormal_timing();
    test_stereo_sanitise();
    test_scalar_helpers();
    test_merge_traced();
    test_regression_fallback_overflow();
    test_regression_scratch_size_hole();
    test_regression_sample_count_overflow();
    test_regression_lerp_dim_sample();
    return sbt_finish("test_robust");
}
