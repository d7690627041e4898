/* Tile classification of the row gather (issue 10, part 1): each shortcut against the
   general path with the shortcuts turned off and against the pixel gather, on scenes
   built to trigger it, and banded calls against whole-image calls.
   - rest:    zero motion (+0 and -0), unchanged depth, with hostile pixels: depth moved
              beyond the tolerance, within it, within the slack only; sky over sky, sky
              over geometry; NaN / inf / -0 / denormal / FLT_MAX colours; N 0, < 0, NaN,
              inf; no geometry in the target.
   - void:    rows whose target has no geometry (0, negative, NaN, -inf depth).
   - camera:  the camera source with the frame's and the history's cameras equal (the
              pixel itself, exactly), and that identity against the full matrix chain
              (within the stated tolerance, see test_camera_at_rest).
   - camera moving: the camera source's plan in double lanes against the pixel gather.
   - mixed:   a scene at rest with a moving object (zero and non-zero motion tiles).
   - sky:     target rows of sky (+inf) under moving content, history partly sky.
   - valid:   smooth moving content where every tap passes.
   - stereo cameras: the two-camera rigs' map and back-check in double lanes.
   - stereo disparity: the disparity rig's plan in lanes, every eye / channel count.
   - far:     stereo rows of distant geometry (disparity below 1/256 px), parallel rig.
   Calls internal functions: includes the implementation statically. */
#define STEREOBLEND_STATIC
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"
#include <float.h>

#ifdef SBL__ROW_GATHER
#define view sbt_view

/* 1 if the compiler contracts a * b + c into a fused multiply-add (clang -mfma): the
   general row gather then equals the pixel gather within 1e-6 relative (test_paths);
   the shortcuts' own results stay exact (their products are by 1). */
static int compiler_contracts(void)
{
    volatile float a = 1.0f + 1.0f / 4096.0f, c = -(1.0f + 1.0f / 2048.0f);
    float b = a;
    return a * b + c != 0.0f;
}

static int same_float(float a, float b, int contracts)
{
    if (memcmp(&a, &b, sizeof a) == 0) return 1;
    return contracts && fabs((double)a - b) <= 1e-6 * (fabs(a) + fabs(b)) + 1e-5;
}

enum { SCENE_REST, SCENE_VOID, SCENE_MIXED, SCENE_SKY, SCENE_VALID, SCENE_COUNT };
static const char *scene_names[SCENE_COUNT] = {"rest", "void", "mixed", "sky", "valid"};

typedef struct scene {
    int w, h, ch, with_len, with_depth, bottom_up;
    sbt_img cur, hist, len, depth, pdepth, mv;
    sbl_frame f;
    sbl_history hi;
} scene;

static void scene_free(scene *s)
{
    free(s->cur.mem); free(s->hist.mem); free(s->len.mem); free(s->depth.mem);
    free(s->pdepth.mem); free(s->mv.mem);
}

static void scene_make(scene *s, int kind, int it, sbt_rng *rng)
{
    static const float odd[8] = {0.0f, -0.0f, 1e-39f, FLT_MAX, -FLT_MAX, 1e30f, -1.0f, 2e-13f};
    const float nan = (float)HUGE_VAL - (float)HUGE_VAL, inf = (float)HUGE_VAL;
    int x, y, c;
    s->w = 2 + (int)(sbt_uniform(rng) * (it % 3 == 0 ? 200 : 90));
    s->h = 2 + (int)(sbt_uniform(rng) * 8);
    s->ch = 1 + it % 4;
    s->with_len = it % 5 != 0;
    s->with_depth = kind == SCENE_VOID || kind == SCENE_SKY || it % 7 != 0;
    s->bottom_up = it % 3 == 1;
    s->cur = sbt_img_new(s->w, s->h, s->ch, 1);
    s->hist = sbt_img_new(s->w, s->h, s->ch, 2);
    s->len = sbt_img_new(s->w, s->h, 1, 0);
    s->depth = sbt_img_new(s->w, s->h, 1, 1);
    s->pdepth = sbt_img_new(s->w, s->h, 1, 0);
    s->mv = sbt_img_new(s->w, s->h, 2, 1);
    for (y = 0; y < s->h; ++y)
        for (x = 0; x < s->w; ++x) {
            const double u = sbt_uniform(rng);
            float z = (float)(3.0 + 0.05 * x + 0.02 * y), *m = sbt_at(&s->mv, x, y);
            for (c = 0; c < s->ch; ++c) {
                sbt_at(&s->cur, x, y)[c] = (float)sbt_uniform(rng);
                sbt_at(&s->hist, x, y)[c] = (float)(sbt_uniform(rng) * 2 - 0.2);
            }
            *sbt_at(&s->len, x, y) = (float)(1 + sbt_uniform(rng) * 30);
            *sbt_at(&s->depth, x, y) = z;
            *sbt_at(&s->pdepth, x, y) = z;
            m[0] = m[1] = (x + y) % 3 ? 0.0f : -0.0f;
            if (kind == SCENE_REST || kind == SCENE_MIXED) {
                /* hostile pixels, each also at the image edges */
                float *pz = sbt_at(&s->pdepth, x, y), *hz = sbt_at(&s->depth, x, y);
                float *hc = sbt_at(&s->hist, x, y), *hn = sbt_at(&s->len, x, y);
                if (u < 0.03) *pz = z * 1.5f;                          /* moved far */
                else if (u < 0.06) *pz = z * (1.0f + 0.5f * 0.05f);     /* within tol */
                else if (u < 0.09) *pz = z * 1.05f + 0.03f;             /* slack only */
                else if (u < 0.11) *hz = *pz = inf;                     /* sky on sky */
                else if (u < 0.12) *hz = inf;                           /* sky on geometry */
                else if (u < 0.13) *pz = inf;                           /* geometry on sky */
                else if (u < 0.14) *hz = odd[it % 2 ? 0 : 6];            /* no geometry */
                else if (u < 0.15) *hz = nan;
                else if (u < 0.16) *hz = -inf;
                else if (u < 0.17) *pz = nan;
                else if (u < 0.18) *pz = 0.0f;
                else if (u < 0.21) hc[(x + y) % s->ch] = odd[(x + it) % 8];
                else if (u < 0.22) hc[0] = nan;
                else if (u < 0.23) hc[s->ch - 1] = y % 2 ? inf : -inf;
                else if (u < 0.25) *hn = odd[(y + it) % 8];
                else if (u < 0.26) *hn = y % 2 ? inf : nan;
                if (kind == SCENE_MIXED && x > s->w / 3 && x < s->w / 2 + 5) {
                    m[0] = (float)(sbt_uniform(rng) * 4 - 2); /* a moving object */
                    m[1] = (float)(sbt_uniform(rng) * 2 - 1);
                }
            } else if (kind == SCENE_VOID) {
                static const float none[4] = {0.0f, -2.0f, -1e30f, 0.0f};
                m[0] = (float)(sbt_uniform(rng) * 6 - 3);
                m[1] = (float)(sbt_uniform(rng) * 4 - 2);
                if (y % 2 == 0 || u < 0.5) /* whole rows, and half of the others */
                    *sbt_at(&s->depth, x, y) = u < 0.2 ? nan : (u < 0.3 ? -inf : none[(x + y) % 4]);
            } else if (kind == SCENE_SKY) {
                m[0] = (float)(sbt_uniform(rng) * 6 - 3);
                m[1] = (float)(sbt_uniform(rng) * 4 - 2);
                if (y != s->h / 2) *sbt_at(&s->depth, x, y) = inf; /* one row of geometry */
                if (u < 0.7) *sbt_at(&s->pdepth, x, y) = inf;
                else if (u < 0.75) *sbt_at(&s->len, x, y) = 0.0f;
                else if (u < 0.77) sbt_at(&s->hist, x, y)[0] = nan;
            } else { /* SCENE_VALID: smooth sub-pixel motion, every tap passes */
                m[0] = (float)(0.37 + 0.1 * sin(0.3 * y) + (u < 0.1 ? 1.0 : 0.0));
                m[1] = (float)(-0.21 + 0.05 * sin(0.2 * x));
                if (u < 0.02) *sbt_at(&s->pdepth, x, y) = z * 2.0f; /* a few rejected taps */
            }
        }
    memset(&s->f, 0, sizeof s->f);
    memset(&s->hi, 0, sizeof s->hi);
    s->f.color = view(&s->cur);
    if (s->with_depth) s->f.gbuffer.depth = view(&s->depth);
    s->f.gbuffer.motion = view(&s->mv);
    s->hi.color = view(&s->hist);
    if (s->with_len) s->hi.length = view(&s->len);
    if (s->with_depth) s->hi.gbuffer.depth = view(&s->pdepth);
    if (s->bottom_up) { /* a bottom-up history colour: the last row first */
        s->hi.color.data = sbt_at(&s->hist, 0, s->h - 1);
        s->hi.color.stride = -s->hist.stride;
    }
}

typedef struct ring3 {
    float planes[3][7][256];
    unsigned char unsafe[256];
    sbl__ring_row r[3];
} ring3;

static void ring3_init(ring3 *g)
{
    int i, c;
    memset(g->planes, 0xff, sizeof g->planes); /* NaN: a column not written cannot pass */
    for (i = 0; i < 3; ++i) {
        for (c = 0; c < 4; ++c) g->r[i].x[c] = g->planes[i][c];
        g->r[i].n = g->planes[i][4];
        g->r[i].v = g->planes[i][5];
        g->r[i].y[0] = g->planes[i][6];
        g->r[i].unsafe = g->unsafe;
    }
}

/* Columns [xa, xb) of r[a] and r[b] equal (bit for bit, or within the contraction
   tolerance when `loose`). Returns the number of pixels that differ. */
static int ring_diff_printed;
static int ring_diff(const ring3 *g, int a, int b, int xa, int xb, int ch, int loose,
                     const char *what, int it, int y)
{
    int x, c, bad_count = 0;
    for (x = xa; x < xb; ++x) {
        int bad = !same_float(g->r[a].n[x], g->r[b].n[x], loose) ||
                  memcmp(&g->r[a].v[x], &g->r[b].v[x], 4) != 0;
        for (c = 0; c < ch; ++c) bad |= !same_float(g->r[a].x[c][x], g->r[b].x[c][x], loose);
        if (bad && ring_diff_printed++ < 8)
            printf("  %s case %d pixel (%d,%d): n %.9g vs %.9g, x0 %.9g vs %.9g\n", what, it, x, y,
                   g->r[a].n[x], g->r[b].n[x], g->r[a].x[0][x], g->r[b].x[0][x]);
        bad_count += bad;
    }
    return bad_count;
}

/* The row gather with its shortcuts (r[0]) against itself without them (r[1]) and the
   pixel gather (r[2]) on each scene; counts the tiles of each class seen. */
static void test_scenes(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {2026};
    int kind, it;
    for (kind = 0; kind < SCENE_COUNT; ++kind) {
        long pixels = 0, differ_off = 0, differ_pixel = 0, classes[4] = {0, 0, 0, 0}, reset = 0;
        long flag_differ = 0, flagged = 0;
        for (it = 0; it < 160; ++it) {
            scene sc;
            sbl_reproject_desc rd;
            sbl__temporal_rp rp;
            ring3 g;
            int y, i;
            scene_make(&sc, kind, it, &rng);
            memset(&rd, 0, sizeof rd);
            rd.no_fallback = it % 4 == 1;
            rd.motion.units = (sbl_motion_units)(it % 3 == 2 ? SBL_MOTION_UV : SBL_MOTION_PIXELS);
            if (CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &sc.f, &sc.hi), SBL_OK),
                !sbl__row_gather_ok(&rp.src)) {
                scene_free(&sc);
                continue;
            }
            ring3_init(&g);
            for (y = 0; y < sc.h; ++y) {
                /* whole rows, and random spans (tiles start where the span starts) */
                int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * sc.w);
                int xb = it % 2 ? sc.w : xa + 1 + (int)(sbt_uniform(&rng) * (sc.w - xa));
                int x;
                rp.tiles = 1;
                if (sbl__temporal_tiles_ok(&rp))
                    for (x = xa; x + SBL__VW <= xb; x += SBL__BLOCK) {
                        const int n = xb - x < SBL__BLOCK ? xb - x : SBL__BLOCK;
                        if (n >= SBL__VW) ++classes[sbl__temporal_tile_class(&rp, y, x, n)];
                    }
                memset(g.unsafe, 0, sizeof g.unsafe);
                g.r[0].gather_unsafe = 0;
                sbl__temporal_rp_row(&rp, &g.r[0], y, xa, xb);
                {   /* its unsafe flags, set as it writes (tiles included): exactly the
                       pixels sbl__ring_gather's re-check would flag */
                    int want = 0, c;
                    for (x = xa; x < xb; ++x) {
                        int safe = sbl__lane_value_ok(g.r[0].n[x]);
                        for (c = 0; c < sc.ch; ++c) safe &= sbl__lane_value_ok(g.r[0].x[c][x]);
                        safe |= !(g.r[0].v[x] > 0.0f);
                        flag_differ += g.unsafe[x] != !safe;
                        want += !safe;
                    }
                    flag_differ += g.r[0].gather_flags != 1 || g.r[0].gather_unsafe != want;
                    flagged += want;
                }
                rp.tiles = 0;
                sbl__temporal_rp_row(&rp, &g.r[1], y, xa, xb);
                for (x = xa; x < xb; ++x) {
                    float tmp[4] = {0, 0, 0, 0};
                    sbl__ring_put(&g.r[2], x, sbl__temporal_rp_pixel(&rp, x, y, tmp), tmp, sc.ch);
                    reset += !(g.r[2].n[x] > 0.0f);
                }
                differ_off += ring_diff(&g, 0, 1, xa, xb, sc.ch, 0, scene_names[kind], it, y);
                differ_pixel += ring_diff(&g, 0, 2, xa, xb, sc.ch, contracts, scene_names[kind], it, y);
                pixels += xb - xa;
                for (i = 0; i < 3; ++i) g.r[i].row = y;
            }
            scene_free(&sc);
        }
        printf("  %s %-5s: %ld pixels (%ld without x*), tiles general %ld / void %ld / rest %ld / sky %ld;"
               " differ from no shortcuts %ld, from the pixel gather %ld\n",
               SBL_SIMD_NAME, scene_names[kind], pixels, reset, classes[0], classes[1], classes[2],
               classes[3], differ_off, differ_pixel);
        CHECK(differ_off == 0);
        CHECK(differ_pixel == 0);
        CHECK(reset < pixels);
        printf("  %s %-5s: unsafe flags set as written: %ld pixels flagged, %ld differ from the re-check\n",
               SBL_SIMD_NAME, scene_names[kind], flagged, flag_differ);
        CHECK(flag_differ == 0);
        /* the scene triggers its shortcut */
        if (kind == SCENE_REST) CHECK(classes[SBL__TILE_REST] > 100 && reset > pixels / 50);
        if (kind == SCENE_VOID) CHECK(classes[SBL__TILE_VOID] > 50 && classes[SBL__TILE_GENERAL] > 50);
        if (kind == SCENE_MIXED) CHECK(classes[SBL__TILE_REST] > 20 && classes[SBL__TILE_GENERAL] > 20);
        if (kind == SCENE_SKY) CHECK(classes[SBL__TILE_SKY] > 100 && classes[SBL__TILE_GENERAL] > 20);
    }
}

/* The camera source with equal cameras: every pixel maps to itself exactly, the tiles
   are at rest, and the row gather equals the pixel gather bit for bit. Against the full
   matrix chain (at_rest off), which reaches the identity only within double rounding
   (~1e-13 px, which gives the footprint's other taps weights of ~1e-13): the same
   validity and |x* - x*_chain| <= 1e-6 * the largest finite |history| of the 3x3 around
   the pixel, per channel, and N likewise (measured: below 1e-12). */
static void test_camera_at_rest(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {77};
    int it, rest_tiles = 0, differ = 0, chain_bad = 0;
    long pixels = 0;
    double worst = 0.0;
    for (it = 0; it < 60; ++it) {
        scene sc;
        sbl_reproject_desc rd;
        sbl__temporal_rp rp;
        sbl_camera cam;
        sbl_intrinsics k;
        float pose[16];
        ring3 g;
        int y, x, c, i;
        int v = it * 5 + 1 + (it % 3 == 2);
        if (v % 7 == 0) ++v; /* depth present */
        scene_make(&sc, SCENE_REST, v, &rng);
        for (i = 0; i < 16; ++i) pose[i] = i % 5 == 0 ? 1.0f : 0.0f;
        pose[3] = 0.3f; pose[7] = -0.2f; pose[11] = 1.5f; /* a translated camera */
        pose[1] = 0.1f; pose[4] = -0.1f;
        k.fx = k.fy = (float)(0.8 * sc.w + 3); k.cx = 0.5f * sc.w; k.cy = 0.5f * sc.h;
        CHECK_EQ(sbl_camera_from_pinhole(&cam, &k, pose, SBL_AXES_OPENCV, 0, sc.w, sc.h), SBL_OK);
        sc.f.camera = &cam;
        sc.hi.camera = &cam;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 4 == 1;
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_CAMERA, &sc.f, &sc.hi), SBL_OK);
        CHECK(rp.at_rest);
        ring3_init(&g);
        for (y = 0; y < sc.h; ++y) {
            for (x = 0; x + SBL__VW <= sc.w; x += SBL__BLOCK) {
                const int n = sc.w - x < SBL__BLOCK ? sc.w - x : SBL__BLOCK;
                if (sbl__temporal_tiles_ok(&rp))
                    rest_tiles += sbl__temporal_tile_class(&rp, y, x, n) == SBL__TILE_REST;
            }
            sbl__temporal_rp_row(&rp, &g.r[0], y, 0, sc.w);
            for (x = 0; x < sc.w; ++x) {
                float tmp[4] = {0, 0, 0, 0}, chain[4] = {0, 0, 0, 0}, nc;
                float nr = sbl__temporal_rp_pixel(&rp, x, y, tmp);
                sbl__ring_put(&g.r[2], x, nr, tmp, sc.ch);
                rp.at_rest = 0;
                nc = sbl__temporal_rp_pixel(&rp, x, y, chain);
                rp.at_rest = 1;
                if ((nr > 0.0f) != (nc > 0.0f)) {
                    if (chain_bad < 5) printf("  camera case %d (%d,%d) of %dx%d: N %.9g (identity) vs %.9g (chain), depth %g / %g\n", it, x, y, sc.w, sc.h, nr, nc, *sbt_at(&sc.depth, x, y), *sbt_at(&sc.pdepth, x, y));
                    ++chain_bad;
                    continue;
                }
                if (!(nr > 0.0f)) continue;
                {   /* the footprint's largest value: the 3x3 around the pixel */
                    double big = 1e-30, d;
                    int i2, j2;
                    for (j2 = -1; j2 <= 1; ++j2)
                        for (i2 = -1; i2 <= 1; ++i2) {
                            const int xx = x + i2, yy = y + j2;
                            if (xx < 0 || yy < 0 || xx >= sc.w || yy >= sc.h) continue;
                            for (c = 0; c < sc.ch; ++c) {
                                const float *hv = sc.bottom_up ? sbt_at(&sc.hist, xx, sc.h - 1 - yy)
                                                               : sbt_at(&sc.hist, xx, yy);
                                if (isfinite(hv[c]) && fabs(hv[c]) > big) big = fabs(hv[c]);
                            }
                        }
                    for (c = 0; c < sc.ch; ++c) {
                        d = fabs((double)tmp[c] - chain[c]) / big;
                        if (d > worst) worst = d;
                        chain_bad += !(d <= 1e-6);
                    }
                    big = 1e-30;
                    for (j2 = -1; j2 <= 1; ++j2)
                        for (i2 = -1; i2 <= 1; ++i2) {
                            const int xx = x + i2, yy = y + j2;
                            if (xx < 0 || yy < 0 || xx >= sc.w || yy >= sc.h) continue;
                            if (!sc.with_len) big = 1.0;
                            else if (isfinite(*sbt_at(&sc.len, xx, yy)) && fabs(*sbt_at(&sc.len, xx, yy)) > big)
                                big = fabs(*sbt_at(&sc.len, xx, yy));
                        }
                    d = fabs((double)nr - nc) / big;
                    if (d > worst) worst = d;
                    chain_bad += !(d <= 1e-6);
                }
            }
            differ += ring_diff(&g, 0, 2, 0, sc.w, sc.ch, contracts, "camera", it, y);
            pixels += sc.w;
        }
        scene_free(&sc);
    }
    printf("  %s camera at rest: %ld pixels, %d rest tiles, %d differ from the pixel gather;"
           " identity vs matrix chain: worst %.3g of the local magnitude, %d beyond 1e-6\n",
           SBL_SIMD_NAME, pixels, rest_tiles, differ, worst, chain_bad);
    CHECK(differ == 0);
    CHECK(rest_tiles > 50);
    CHECK(chain_bad == 0);
}

/* The camera source with a moving camera (no tile shortcut; the plan in double lanes):
   the row gather against the pixel gather, bit for bit (or within the contraction
   tolerance), over rotations, translations, sky, invalid depth and hostile history. */
static void test_camera_moving(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {909};
    int it, differ = 0;
    long pixels = 0, none = 0;
    for (it = 0; it < 80; ++it) {
        scene sc;
        sbl_reproject_desc rd;
        sbl__temporal_rp rp;
        sbl_camera cam0, cam1;
        sbl_intrinsics k;
        float pose0[16], pose1[16];
        ring3 g;
        int y, x, i, v = it * 5 + 2;
        if (v % 7 == 0) ++v; /* depth present */
        scene_make(&sc, SCENE_REST, v, &rng);
        for (i = 0; i < 16; ++i) pose0[i] = pose1[i] = i % 5 == 0 ? 1.0f : 0.0f;
        pose1[3] = (float)(sbt_uniform(&rng) * 0.4 - 0.2);  /* translation */
        pose1[7] = (float)(sbt_uniform(&rng) * 0.2 - 0.1);
        pose1[11] = (float)(sbt_uniform(&rng) * 0.4 - 0.2);
        pose1[2] = (float)(sbt_uniform(&rng) * 0.1 - 0.05); /* a small rotation */
        pose1[8] = -pose1[2];
        if (it % 5 == 4) pose1[3] = pose1[7] = pose1[11] = 0.0f; /* rotation only */
        k.fx = k.fy = (float)(0.8 * sc.w + 3); k.cx = 0.5f * sc.w; k.cy = 0.5f * sc.h;
        CHECK_EQ(sbl_camera_from_pinhole(&cam1, &k, pose1, SBL_AXES_OPENCV, it % 3 == 0, sc.w, sc.h), SBL_OK);
        CHECK_EQ(sbl_camera_from_pinhole(&cam0, &k, pose0, SBL_AXES_OPENCV, it % 3 == 0, sc.w, sc.h), SBL_OK);
        sc.f.camera = &cam1;
        sc.hi.camera = &cam0;
        memset(&rd, 0, sizeof rd);
        rd.no_fallback = it % 4 == 1;
        CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_CAMERA, &sc.f, &sc.hi), SBL_OK);
        if (!sbl__row_gather_ok(&rp.src)) { scene_free(&sc); continue; }
        ring3_init(&g);
        for (y = 0; y < sc.h; ++y) {
            sbl__temporal_rp_row(&rp, &g.r[0], y, 0, sc.w);
            for (x = 0; x < sc.w; ++x) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put(&g.r[2], x, sbl__temporal_rp_pixel(&rp, x, y, tmp), tmp, sc.ch);
                none += !(g.r[2].n[x] > 0.0f);
            }
            differ += ring_diff(&g, 0, 2, 0, sc.w, sc.ch, contracts, "camera moving", it, y);
            pixels += sc.w;
        }
        scene_free(&sc);
    }
    printf("  %s camera moving: %ld pixels (%ld without x*), %d differ from the pixel gather\n",
           SBL_SIMD_NAME, pixels, none, differ);
    CHECK(differ == 0);
    CHECK(none > pixels / 50 && none < pixels / 2);
}

/* The two-camera stereo rigs (matrices, pinhole), whose map and back-check run in
   double lanes: the row gather against sbl__stereo_rp_pixel, bit for bit (or within the
   contraction tolerance), both eyes as target, back-check on and off, toed-in and
   vertically offset rigs, sky, invalid depth, hostile colour and N. */
static void test_stereo_cameras(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {5150};
    int it, differ = 0;
    long pixels = 0, none = 0;
    for (it = 0; it < 120; ++it) {
        int w = 4 + (int)(sbt_uniform(&rng) * 120), h = 3 + (int)(sbt_uniform(&rng) * 6);
        int ch = 1 + it % 4, e, x, y, c, tgt = it & 1, i;
        sbt_img col[2], len[2], dep[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl_camera cam[2];
        sbl__stereo_rp rp;
        sbl_intrinsics k;
        float pose[2][16];
        ring3 g;
        k.fx = k.fy = (float)(0.9 * w + 5); k.cx = 0.5f * w; k.cy = 0.5f * h;
        for (e = 0; e < 2; ++e) {
            for (i = 0; i < 16; ++i) pose[e][i] = i % 5 == 0 ? 1.0f : 0.0f;
            pose[e][3] = e ? -0.06f : 0.0f; /* world_to_view: the right eye 6 cm to the right */
        }
        if (it % 3 == 1) { pose[1][2] = 0.02f; pose[1][8] = -0.02f; } /* toed in */
        if (it % 3 == 2) pose[1][7] = 0.004f;                          /* vertical offset */
        for (e = 0; e < 2; ++e) {
            CHECK_EQ(sbl_camera_from_pinhole(&cam[e], &k, pose[e], SBL_AXES_OPENCV, 0, w, h), SBL_OK);
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    const double u = sbt_uniform(&rng);
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)sbt_uniform(&rng);
                    *sbt_at(&len[e], x, y) = (float)(1 + sbt_uniform(&rng) * 20);
                    *sbt_at(&dep[e], x, y) = (float)(1.0 + 0.02 * x + (x % 17 < 3 ? 0.5 : 0.0));
                    if (u < 0.04) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                    else if (u < 0.06) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL - (float)HUGE_VAL;
                    else if (u < 0.07) *sbt_at(&dep[e], x, y) = 0.0f;
                    else if (u < 0.09) *sbt_at(&len[e], x, y) = 0.0f;
                    else if (u < 0.10) sbt_at(&col[e], x, y)[0] = (float)HUGE_VAL;
                }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = view(&col[e]);
            eye[e].length = view(&len[e]);
            eye[e].gbuffer.depth = view(&dep[e]);
            eye[e].camera = &cam[e];
        }
        memset(&sd, 0, sizeof sd);
        sd.rig = it % 2 ? SBL_RIG_PINHOLE : SBL_RIG_MATRICES;
        if (sd.rig == SBL_RIG_PINHOLE) {
            sd.pinhole.eye[0] = sd.pinhole.eye[1] = k;
            for (i = 0; i < 16; ++i) sd.pinhole.right_from_left[i] = i % 5 == 0 ? 1.0f : 0.0f;
            sd.pinhole.right_from_left[3] = -0.06f;
            if (it % 3 == 2) sd.pinhole.right_from_left[7] = 0.004f;
            sd.pinhole.axes = SBL_AXES_OPENCV;
        }
        sd.reproject.no_fallback = it % 5 == 1;
        if (it % 4 == 3) sd.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], 1), SBL_OK);
        rp.d.rig = sd.rig; /* the camera maps (most of these rigs are parallel: sbl__rig_as_parallel) */
        ring3_init(&g);
        for (y = 0; y < h; ++y) {
            int xa = it % 3 ? 0 : (int)(sbt_uniform(&rng) * w), xb = w;
            sbl__stereo_rp_row(&rp, &g.r[0], y, xa, xb);
            for (x = xa; x < xb; ++x) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put(&g.r[2], x, sbl__stereo_rp_pixel(&rp, x, y, tmp), tmp, ch);
                none += !(g.r[2].n[x] > 0.0f);
            }
            differ += ring_diff(&g, 0, 2, xa, xb, ch, contracts, "stereo cameras", it, y);
            pixels += xb - xa;
        }
        for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); free(dep[e].mem); }
    }
    printf("  %s stereo two-camera rigs: %ld pixels (%ld without a match), %d differ from the pixel gather\n",
           SBL_SIMD_NAME, pixels, none, differ);
    CHECK(differ == 0);
    CHECK(none > pixels / 20 && none < pixels / 2);
}

/* The disparity rig in lanes: one- and two-channel maps, both eyes as target (every
   combination), target with and without depth, integer, sub-pixel, tiny and non-finite
   disparities: the row gather against sbl__stereo_rp_pixel. */
static void test_stereo_disparity(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {6060};
    int it, differ = 0;
    long pixels = 0, none = 0;
    for (it = 0; it < 96; ++it) {
        int w = 4 + (int)(sbt_uniform(&rng) * 120), h = 3 + (int)(sbt_uniform(&rng) * 6);
        int ch = 1 + (it / 8) % 4, e, x, y, c, tgt = it & 1, dch = 1 + (it >> 1) % 2;
        int with_depth = (it >> 2) % 2 == 0;
        sbt_img col[2], len[2], dep[2], dsp[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl__stereo_rp rp;
        ring3 g;
        for (e = 0; e < 2; ++e) {
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
            dsp[e] = sbt_img_new(w, h, dch, 1);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    const double u = sbt_uniform(&rng);
                    float *d = sbt_at(&dsp[e], x, y);
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)sbt_uniform(&rng);
                    *sbt_at(&len[e], x, y) = (float)(1 + sbt_uniform(&rng) * 20);
                    *sbt_at(&dep[e], x, y) = u < 0.1 ? 2.0f : 4.0f;
                    d[0] = u < 0.1 ? 5.0f : (float)(2.5 + 0.01 * x);
                    if (dch > 1) d[1] = (float)(sbt_uniform(&rng) * 0.6 - 0.3);
                    if (u > 0.95) d[0] = 3.0f;                               /* integer */
                    else if (u > 0.93) d[0] = (float)(1e-4 * sbt_uniform(&rng)); /* tiny */
                    else if (u > 0.92) d[dch - 1] = (float)HUGE_VAL - (float)HUGE_VAL;
                    else if (u > 0.91) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                    else if (u > 0.89) *sbt_at(&len[e], x, y) = 0.0f;
                }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = view(&col[e]);
            eye[e].length = view(&len[e]);
            if (with_depth) eye[e].gbuffer.depth = view(&dep[e]);
            eye[e].disparity = view(&dsp[e]);
        }
        memset(&sd, 0, sizeof sd);
        sd.rig = SBL_RIG_DISPARITY;
        sd.reproject.no_fallback = it % 5 == 1;
        if (it % 7 == 3) sd.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], 1), SBL_OK);
        ring3_init(&g);
        for (y = 0; y < h; ++y) {
            sbl__stereo_rp_row(&rp, &g.r[0], y, 0, w);
            for (x = 0; x < w; ++x) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put(&g.r[2], x, sbl__stereo_rp_pixel(&rp, x, y, tmp), tmp, ch);
                none += !(g.r[2].n[x] > 0.0f);
            }
            differ += ring_diff(&g, 0, 2, 0, w, ch, contracts, "stereo disparity", it, y);
            pixels += w;
        }
        for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); free(dep[e].mem); free(dsp[e].mem); }
    }
    printf("  %s stereo disparity rig: %ld pixels (%ld without a match), %d differ from the pixel gather\n",
           SBL_SIMD_NAME, pixels, none, differ);
    CHECK(differ == 0);
    CHECK(none > pixels / 20 && none < pixels / 2);
}

/* Far tiles of the parallel rig (SBL_SHORTCUTS bit 16, opt-in since session 27): target
   rows of distant geometry (|d| = f b / z below 1/256 px), with sky, near pixels,
   rejected taps and hostile values mixed in; and spans of each row against the whole
   row (bit for bit without the shortcut). The
   shortcut against the general path (tiles off): the same validity everywhere and, per
   channel and for N, |x* - x*_general| <= (|d| / (1 - |d|) + 2^-23) * the largest finite
   difference to the two neighbours + 2^-22 |x*_general| (the general path's weight of
   the neighbour is itself |d| only to within a float rounding next to 1); the general path against the
   pixel gather bit for bit (or within the contraction tolerance). */
static void test_stereo_far(void)
{
    const int contracts = compiler_contracts();
    sbt_rng rng = {4711};
    int it, differ_valid = 0, beyond = 0, snapped_differ = 0, differ_pixel = 0, differ_span = 0, spans = 0;
    long pixels = 0;
    for (it = 0; it < 120; ++it) {
        int w = 8 + (int)(sbt_uniform(&rng) * 150), h = 3 + (int)(sbt_uniform(&rng) * 5);
        int ch = 1 + it % 4, e, x, y, c, tgt = it & 1;
        sbt_img col[2], len[2], dep[2];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        sbl__stereo_rp rp;
        ring3 g;
        for (e = 0; e < 2; ++e) {
            col[e] = sbt_img_new(w, h, ch, 1);
            len[e] = sbt_img_new(w, h, 1, 0);
            dep[e] = sbt_img_new(w, h, 1, 1);
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x) {
                    const double u = sbt_uniform(&rng);
                    for (c = 0; c < ch; ++c) sbt_at(&col[e], x, y)[c] = (float)sbt_uniform(&rng);
                    *sbt_at(&len[e], x, y) = (float)(1 + sbt_uniform(&rng) * 20);
                    /* f b = 10: z in [3e3, 3e5] gives |d| in [3.3e-5, 3.3e-3] */
                    *sbt_at(&dep[e], x, y) = (float)(3e3 * pow(100.0, sbt_uniform(&rng)));
                    if (y == 1 && x < w / 3) *sbt_at(&dep[e], x, y) = 4.0f; /* near: d = 2.5 */
                    if (u < 0.05) *sbt_at(&dep[e], x, y) = (float)HUGE_VAL;
                    else if (u < 0.07) *sbt_at(&len[e], x, y) = 0.0f;
                    else if (u < 0.08) sbt_at(&col[e], x, y)[0] = (float)HUGE_VAL - (float)HUGE_VAL;
                    else if (u < 0.10 && e == 1) *sbt_at(&dep[e], x, y) *= 3.0f; /* rejected */
                }
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = view(&col[e]);
            eye[e].length = view(&len[e]);
            eye[e].gbuffer.depth = view(&dep[e]);
        }
        memset(&sd, 0, sizeof sd);
        sd.rig = SBL_RIG_PARALLEL;
        sd.focal_px = 10.0f;
        sd.baseline = 1.0f;
        sd.reproject.no_fallback = it % 3 == 1;
        if (it % 4 == 3) sd.reproject.disabled_tests = SBL_TEST_BACK_CHECK;
        CHECK_EQ(sbl__stereo_rp_init(&rp, &sd, (sbl_eye_index)tgt, &eye[tgt], &eye[!tgt], 1), SBL_OK);
        ring3_init(&g);
        for (y = 0; y < h; ++y) {
            rp.tiles = 1;
            sbl__stereo_rp_row(&rp, &g.r[0], y, 0, w);
            rp.tiles = 0;
            sbl__stereo_rp_row(&rp, &g.r[1], y, 0, w);
            for (x = 0; x < w; ++x) {
                float tmp[4] = {0, 0, 0, 0};
                sbl__ring_put(&g.r[2], x, sbl__stereo_rp_pixel(&rp, x, y, tmp), tmp, ch);
            }
            differ_pixel += ring_diff(&g, 1, 2, 0, w, ch, contracts, "stereo general", it, y);
#if !(SBL_SHORTCUTS & 16)
            {   /* spans of the row against the whole row, bit for bit (the adaptive
                   pipeline gathers spans; with the far tiles, a far pixel's result
                   depended on the vector or block that held it: session 27) */
                int t;
                for (t = 0; t < 4; ++t) {
                    const int xa = (int)(sbt_uniform(&rng) * (w - 1));
                    const int xb = xa + 1 + (int)(sbt_uniform(&rng) * (w - xa));
                    memset(g.planes[2], 0xff, sizeof g.planes[2]); /* NaN, as ring3_init */
                    rp.tiles = 1;
                    sbl__stereo_rp_row(&rp, &g.r[2], y, xa, xb > w ? w : xb);
                    differ_span += ring_diff(&g, 0, 2, xa, xb > w ? w : xb, ch, contracts, "stereo far span", it, y);
                    ++spans;
                }
            }
#endif
            for (x = 0; x < w; ++x) {
                const double z = *sbt_at(&dep[tgt], x, y), d = 10.0 / z;
                const sbt_img *sc = &col[!tgt], *sl = &len[!tgt];
                int k, same = memcmp(&g.r[0].n[x], &g.r[1].n[x], 4) == 0;
                ++pixels;
                if ((g.r[0].v[x] > 0.0f) != (g.r[1].v[x] > 0.0f)) { ++differ_valid; continue; }
                if (!(g.r[1].v[x] > 0.0f)) continue;
                for (k = 0; k <= ch; ++k) { /* channels, then N */
                    const float a = k < ch ? g.r[0].x[k][x] : g.r[0].n[x];
                    const float b = k < ch ? g.r[1].x[k][x] : g.r[1].n[x];
                    double big = 0.0, lim;
                    int i2;
                    same &= memcmp(&a, &b, 4) == 0;
                    for (i2 = -1; i2 <= 1; i2 += 2) {
                        const int xx = x + i2;
                        double v0, v1;
                        if (xx < 0 || xx >= w) continue;
                        v0 = k < ch ? sbt_at(sc, x, y)[k] : *sbt_at(sl, x, y);
                        v1 = k < ch ? sbt_at(sc, xx, y)[k] : *sbt_at(sl, xx, y);
                        if (isfinite(v0) && isfinite(v1) && fabs(v1 - v0) > big) big = fabs(v1 - v0);
                    }
                    /* the general path's weight of the neighbour is |d| to within 2^-24
                       (its fraction is rounded to float next to 1) */
                    lim = (d < 0.5 ? d / (1.0 - d) + 1.0 / 8388608.0 : 1e30) * big + fabs(b) * (1.0 / 4194304.0);
                    if (!(fabs((double)a - b) <= lim)) {
                        if (beyond < 3)
                            printf("  far case %d (%d,%d) k %d: %.9g vs %.9g (d %.3g, lim %.3g) c %.9g %.9g %.9g z %g %g %g tgt %d\n", it, x, y, k, a, b, d, lim,
                                   x > 0 ? sbt_at(sc, x - 1, y)[0] : -1.0f, sbt_at(sc, x, y)[0], x + 1 < w ? sbt_at(sc, x + 1, y)[0] : -1.0f,
                                   *sbt_at(&dep[!tgt], x - 1, y), *sbt_at(&dep[!tgt], x, y), *sbt_at(&dep[!tgt], x + 1, y), tgt);
                        ++beyond;
                    }
                }
                snapped_differ += !same;
            }
            {
                int i;
                for (i = 0; i < 3; ++i) g.r[i].row = y;
            }
        }
        for (e = 0; e < 2; ++e) { free(col[e].mem); free(len[e].mem); free(dep[e].mem); }
    }
    printf("  %s stereo far tiles: %ld pixels, %d differ from the general path (all within the bound: %s),"
           " %d change validity; general vs pixel gather: %d differ\n",
           SBL_SIMD_NAME, pixels, snapped_differ, beyond ? "no" : "yes", differ_valid, differ_pixel);
    CHECK(beyond == 0);
    CHECK(differ_valid == 0);
    CHECK(differ_pixel == 0);
#if SBL_SHORTCUTS & 16
    (void)differ_span;
    (void)spans;
    /* opted in (mk/check.mk's asan configuration): the shortcut ran; a span's end may
       leave a far pixel to the exact pixel gather (a block of fewer than VW entries),
       which the bound above covers, so spans are not compared bit for bit here */
    CHECK(snapped_differ > pixels / 10);
#else
    /* the default: no far tiles, the general path's bits on every span */
    printf("  %s stereo far geometry on %d spans against the whole row: %d pixels differ\n", SBL_SIMD_NAME,
           spans, differ_span);
    CHECK(snapped_differ == 0);
    CHECK(differ_span == 0);
#endif
}

/* A whole-image sbl_temporal_filter against row bands of it, bit for bit, on the rest
   and mixed scenes; and against the same data in a layout that turns the shortcuts off
   (depth and N as one channel of two-channel buffers: pixel step 2), bit for bit. */
static void test_bands(void)
{
    sbt_rng rng = {31};
    int it, differ = 0, calls = 0;
    for (it = 0; it < 40; ++it) {
        scene sc0;
        int kind = it % 2 ? 2 : 0; /* rest, mixed */
        int w, h, ch, y0, x, y, c, b;
        sbt_img pair;
        sbl_temporal_desc td;
        sbl_temporal_output o;
        float *out[3], *len[3];
        size_t bytes;
        void *scratch;
        scene_make(&sc0, kind == 2 ? SCENE_MIXED : SCENE_REST, it * 3 + 1, &rng);
        w = sc0.w; h = sc0.h; ch = sc0.ch;
        memset(&td, 0, sizeof td);
        bytes = sbl_temporal_scratch_size(w, ch);
        scratch = malloc(bytes);
        for (b = 0; b < 3; ++b) {
            out[b] = (float *)malloc(sizeof(float) * (size_t)(w * h * ch));
            len[b] = (float *)malloc(sizeof(float) * (size_t)(w * h));
        }
        /* whole image */
        memset(&o, 0, sizeof o);
        o.color = sbl_image_make(out[0], w, h, ch);
        o.length = sbl_image_make(len[0], w, h, 1);
        CHECK_EQ(sbl_temporal_filter(&td, &sc0.f, &sc0.hi, &o, 0, h, scratch, bytes), SBL_OK);
        /* bands */
        o.color = sbl_image_make(out[1], w, h, ch);
        o.length = sbl_image_make(len[1], w, h, 1);
        for (y0 = 0; y0 < h;) {
            int y1 = y0 + 1 + (int)(sbt_uniform(&rng) * 3);
            if (y1 > h) y1 = h;
            CHECK_EQ(sbl_temporal_filter(&td, &sc0.f, &sc0.hi, &o, y0, y1, scratch, bytes), SBL_OK);
            y0 = y1;
        }
        /* the same data with depth and N at a pixel step of 2 (no shortcuts) */
        pair = sbt_img_new(w, h, 2, 0);
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                sbt_at(&pair, x, y)[0] = *sbt_at(&sc0.pdepth, x, y);
                sbt_at(&pair, x, y)[1] = *sbt_at(&sc0.len, x, y);
            }
        {
            sbl_history hi2 = sc0.hi;
            sbl_image *v[2];
            v[0] = &hi2.gbuffer.depth; v[1] = &hi2.length;
            for (c = 0; c < 2; ++c) {
                if (!v[c]->data) continue;
                *v[c] = view(&pair);
                v[c]->data = pair.mem + c;
                v[c]->channels = 1;
                v[c]->pixel_bytes = 2 * (int)sizeof(float);
            }
            {
                sbl__temporal_rp rp;
                sbl_reproject_desc rd = sbl_temporal_defaults(&td).reproject;
                CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, td.source, &sc0.f, &hi2), SBL_OK);
                if (hi2.gbuffer.depth.data || hi2.length.data) CHECK(!sbl__temporal_tiles_ok(&rp));
            }
            o.color = sbl_image_make(out[2], w, h, ch);
            o.length = sbl_image_make(len[2], w, h, 1);
            CHECK_EQ(sbl_temporal_filter(&td, &sc0.f, &hi2, &o, 0, h, scratch, bytes), SBL_OK);
        }
        for (b = 1; b < 3; ++b) {
            const int skip = b == 2 && !sc0.hi.gbuffer.depth.data && !sc0.hi.length.data;
            if (skip) continue;
            if (memcmp(out[0], out[b], sizeof(float) * (size_t)(w * h * ch)) != 0 ||
                memcmp(len[0], len[b], sizeof(float) * (size_t)(w * h)) != 0) {
                if (differ < 3) printf("  bands case %d: %s differs\n", it, b == 1 ? "banded call" : "no-shortcut layout");
                ++differ;
            }
            ++calls;
        }
        free(pair.mem);
        for (b = 0; b < 3; ++b) { free(out[b]); free(len[b]); }
        free(scratch);
        scene_free(&sc0);
    }
    printf("  %s filter: whole image vs bands and vs the no-shortcut layout: %d comparisons, %d differ\n",
           SBL_SIMD_NAME, calls, differ);
    CHECK(differ == 0);
}
#endif

#ifdef SBL__ROW_GATHER
/* ---- normals and ids (the tiles with the normal / id tests) ------------------------
   Each scene of test_scenes with target and history normals and ids added: the row
   gather with its shortcuts against itself without them and against the pixel gather,
   bit for bit. At rest the history's normal and id are the target's but for hostile
   pixels: a normal turned past the threshold, "no normal" on one side or both (0, and
   below 1e-12 squared), backfacing, NaN / inf / overflowing components on either side
   (a non-finite target normal resets the pixel), another id, NaN / -0 ids. The views
   packed, as channels of wider buffers, bottom-up. */
static void nid_scene_normal(float *n, sbt_rng *rng, double u, int hist)
{
    const float nan = (float)HUGE_VAL - (float)HUGE_VAL;
    if (u < 0.03) { n[0] = 0.8f; n[1] = 0.0f; n[2] = 0.6f; return; }          /* turned away */
    if (u < 0.04) { n[0] = n[1] = n[2] = 0.0f; return; }                      /* no normal */
    if (u < 0.05) { n[0] = 1e-7f; n[1] = n[2] = 0.0f; return; }               /* below 1e-12 */
    if (u < 0.06) { n[0] = n[1] = 0.0f; n[2] = -1.0f; return; }               /* backfacing */
    if (u < 0.07) { n[(int)(u * 3000) % 3] = nan; return; }
    if (u < 0.075) { n[2] = hist ? (float)HUGE_VAL : 1e25f; return; }          /* inf / nn overflow */
    if (u < 0.08) { n[0] *= 0.999f; n[1] += 0.3f; return; }                   /* near the cone */
    (void)rng;
}

static sbl_image nid_view3(const sbt_img *src, int lay, float **mem)
{
    return sbt_view3_layout(src, lay, 2, mem);
}

static sbl_image nid_view1(const sbt_img *src, int lay, float **mem)
{
    return sbt_view1_layout(src, lay, 0, mem);
}

static void test_scenes_normals(void)
{
    const int contracts = compiler_contracts();
    const float nan = (float)HUGE_VAL - (float)HUGE_VAL;
    sbt_rng rng = {3131};
    int kind, it;
    for (kind = 0; kind < SCENE_COUNT; ++kind) {
        long pixels = 0, differ_off = 0, differ_pixel = 0, classes[4] = {0, 0, 0, 0}, reset = 0;
        long nid_reset = 0;
        for (it = 0; it < 120; ++it) {
            scene sc;
            sbl_reproject_desc rd;
            sbl__temporal_rp rp;
            ring3 g;
            sbt_img nrm, pnrm, ids, pids;
            float *mem[4] = {NULL, NULL, NULL, NULL};
            const int tests = it % 4; /* 0 both, 1 normals, 2 ids, 3 target normals only + ids */
            int y, x, i;
            scene_make(&sc, kind, it, &rng);
            nrm = sbt_img_new(sc.w, sc.h, 3, 0);
            pnrm = sbt_img_new(sc.w, sc.h, 3, 0);
            ids = sbt_img_new(sc.w, sc.h, 1, 0);
            pids = sbt_img_new(sc.w, sc.h, 1, 0);
            for (y = 0; y < sc.h; ++y)
                for (x = 0; x < sc.w; ++x) {
                    float *n = sbt_at(&nrm, x, y), *pn = sbt_at(&pnrm, x, y);
                    const double u = sbt_uniform(&rng), v = sbt_uniform(&rng);
                    const float len = (float)(0.5 + sbt_uniform(&rng));
                    n[0] = len * (float)(0.1 * sin(0.2 * x)); n[1] = len * 0.05f; n[2] = len;
                    pn[0] = n[0]; pn[1] = n[1]; pn[2] = n[2];
                    nid_scene_normal(pn, &rng, u, 1);
                    if (v < 0.3) nid_scene_normal(n, &rng, v * 0.25, 0);
                    *sbt_at(&ids, x, y) = *sbt_at(&pids, x, y) = (float)(1 + (x / 9) % 3);
                    if (u > 0.95) *sbt_at(&pids, x, y) = 9.0f;
                    else if (u > 0.94) *sbt_at(&pids, x, y) = nan;
                    else if (u > 0.93) *sbt_at(&ids, x, y) = nan;
                    else if (u > 0.92) { *sbt_at(&ids, x, y) = 0.0f; *sbt_at(&pids, x, y) = -0.0f; }
                }
            if (tests != 2) sc.f.gbuffer.normals = nid_view3(&nrm, it % 4, &mem[0]);
            if (tests < 2) sc.hi.gbuffer.normals = nid_view3(&pnrm, (it / 4) % 4, &mem[1]);
            if (tests != 1) {
                sc.f.gbuffer.ids = nid_view1(&ids, it % 2, &mem[2]);
                sc.hi.gbuffer.ids = nid_view1(&pids, (it / 2) % 2, &mem[3]);
            }
            memset(&rd, 0, sizeof rd);
            rd.no_fallback = it % 4 == 1;
            if (it % 5 == 4) rd.normal_threshold = 0.99f;
            CHECK_EQ(sbl__temporal_rp_init(&rp, &rd, SBL_TEMPORAL_MOTION, &sc.f, &sc.hi), SBL_OK);
            CHECK(sbl__row_gather_ok(&rp.src));
            rp.tiles = 1;
            CHECK(sbl__temporal_tiles_ok(&rp));
            ring3_init(&g);
            for (y = 0; y < sc.h; ++y) {
                int xa = it % 2 ? 0 : (int)(sbt_uniform(&rng) * sc.w);
                int xb = it % 2 ? sc.w : xa + 1 + (int)(sbt_uniform(&rng) * (sc.w - xa));
                sbl__temporal_rp q = rp;
                rp.tiles = 1;
                for (x = xa; x + SBL__VW <= xb; x += SBL__BLOCK) {
                    const int n = xb - x < SBL__BLOCK ? xb - x : SBL__BLOCK;
                    if (n >= SBL__VW) ++classes[sbl__temporal_tile_class(&rp, y, x, n)];
                }
                memset(g.unsafe, 0, sizeof g.unsafe);
                sbl__temporal_rp_row(&rp, &g.r[0], y, xa, xb);
                rp.tiles = 0;
                sbl__temporal_rp_row(&rp, &g.r[1], y, xa, xb);
                q.src.use_normal = q.src.use_id = 0;
                q.geo.normals.p = NULL;
                for (x = xa; x < xb; ++x) {
                    float tmp[4] = {0, 0, 0, 0};
                    sbl__ring_put(&g.r[2], x, sbl__temporal_rp_pixel(&rp, x, y, tmp), tmp, sc.ch);
                    reset += !(g.r[2].n[x] > 0.0f);
                    nid_reset += !(g.r[2].n[x] > 0.0f) && sbl__temporal_rp_pixel(&q, x, y, tmp) > 0.0f;
                }
                differ_off += ring_diff(&g, 0, 1, xa, xb, sc.ch, 0, "normals / ids", it, y);
                differ_pixel += ring_diff(&g, 0, 2, xa, xb, sc.ch, contracts, "normals / ids", it, y);
                pixels += xb - xa;
            }
            for (i = 0; i < 4; ++i) free(mem[i]);
            free(nrm.mem); free(pnrm.mem); free(ids.mem); free(pids.mem);
            scene_free(&sc);
        }
        printf("  %s %-5s with normals / ids: %ld pixels (%ld without x*, %ld by the normal / id tests),"
               " tiles general %ld / void %ld / rest %ld / sky %ld; differ from no shortcuts %ld, from the"
               " pixel gather %ld\n",
               SBL_SIMD_NAME, scene_names[kind], pixels, reset, nid_reset, classes[0], classes[1],
               classes[2], classes[3], differ_off, differ_pixel);
        CHECK(differ_off == 0);
        CHECK(differ_pixel == 0);
        if (kind == SCENE_REST) CHECK(classes[SBL__TILE_REST] > 100 && nid_reset > pixels / 20);
        if (kind == SCENE_VOID) CHECK(classes[SBL__TILE_VOID] > 50);
        if (kind == SCENE_MIXED) CHECK(classes[SBL__TILE_REST] > 20 && nid_reset > pixels / 40);
        if (kind == SCENE_SKY) CHECK(classes[SBL__TILE_SKY] > 100);
    }
}
#endif

int main(void)
{
#ifdef SBL__ROW_GATHER
    test_scenes();
    test_camera_at_rest();
    test_camera_moving();
    test_stereo_cameras();
    test_stereo_disparity();
    test_stereo_far();
    test_bands();
    test_scenes_normals();
#else
    printf("  %s: no row gather on this path (the pixel gather runs, no tile shortcuts)\n",
           SBL_SIMD_NAME);
    CHECK(1);
#endif
    return sbt_finish("test_tiles");
}
