/* Accuracy properties of the default estimators (issue 11), through the public API:
   - a single firefly in a converged history has a bounded effect and decays, and does
     not reset the history of its pixel or of its neighbours;
   - a light edge that moves every frame (zero motion vectors) is followed with a lag
     bounded in frames;
   - the stereo blend on a noisy depth edge (colour filtered across the silhouette,
     depth point-sampled, as in a renderer) is never worse than not blending, and on a
     flat noisy region it is compared with the paper's beta.
   Each property is also measured for the previous default (history-aware) and printed,
   so that the numbers can be compared. */
#define STEREOBLEND_IMPLEMENTATION
#include "../stereoblend.h"
#include "sbl_test.h"

#define TW 48
#define TH 24

typedef struct seq1 {
    int w, h, ch;
    float *cur, *hist[2], *len[2], *depth, *mv, *alpha;
    int ping;
    float *ev[2]; /* the evidence plane, ping-ponged with the history (g_evidence) */
    float *tl[2]; /* the tail plane (2 channels), ping-ponged with the history (g_tail) */
} seq1;

/* 1: seq_step carries the tail plane (sbl_history.tail in, sbl_temporal_output.tail out) */
static int g_tail;

/* set: seq_step asks for the display (sbl_temporal_output.display) into this buffer */
static float *g_display;

/* 1: seq_step carries the evidence plane (history in, output out); 2: only writes it
   (no history plane: the estimator must be today's, bit for bit) */
static int g_evidence;
/* stereo_shared_bias of the firefly runs (test_tail_fireflies: behind a stereo blend) */
static float g_shared;

static void seq_init(seq1 *s, int w, int h, int ch)
{
    size_t n = (size_t)w * (size_t)h;
    int i;
    s->w = w; s->h = h; s->ch = ch; s->ping = 0;
    s->cur = (float *)calloc(n * ch, sizeof(float));
    for (i = 0; i < 2; ++i) {
        s->hist[i] = (float *)calloc(n * ch, sizeof(float));
        s->len[i] = (float *)calloc(n, sizeof(float));
    }
    s->depth = (float *)calloc(n, sizeof(float));
    s->mv = (float *)calloc(n * 2, sizeof(float));
    s->alpha = (float *)calloc(n, sizeof(float));
    for (i = 0; i < (int)n; ++i) s->depth[i] = 1.0f;
    s->ev[0] = (float *)calloc(n, sizeof(float));
    s->ev[1] = (float *)calloc(n, sizeof(float));
    s->tl[0] = (float *)calloc(n * 2, sizeof(float));
    s->tl[1] = (float *)calloc(n * 2, sizeof(float));
}

static void seq_free(seq1 *s)
{
    free(s->cur); free(s->hist[0]); free(s->hist[1]); free(s->len[0]); free(s->len[1]);
    free(s->depth); free(s->mv); free(s->alpha); free(s->ev[0]); free(s->ev[1]);
    free(s->tl[0]); free(s->tl[1]);
}

/* One temporal step: cur -> hist[!ping]; first = no history. */
static int seq_step(seq1 *s, const sbl_temporal_desc *d, int first)
{
    sbl_frame f;
    sbl_history h;
    sbl_temporal_output o;
    int r;
    memset(&f, 0, sizeof f); memset(&h, 0, sizeof h); memset(&o, 0, sizeof o);
    f.color = sbl_image_make(s->cur, s->w, s->h, s->ch);
    f.gbuffer.depth = sbl_image_make(s->depth, s->w, s->h, 1);
    f.gbuffer.motion = sbl_image_make(s->mv, s->w, s->h, 2);
    h.color = sbl_image_make(s->hist[s->ping], s->w, s->h, s->ch);
    h.length = sbl_image_make(s->len[s->ping], s->w, s->h, 1);
    h.gbuffer.depth = f.gbuffer.depth;
    o.color = sbl_image_make(s->hist[!s->ping], s->w, s->h, s->ch);
    o.length = sbl_image_make(s->len[!s->ping], s->w, s->h, 1);
    o.alpha = sbl_image_make(s->alpha, s->w, s->h, 1);
    if (g_evidence) {
        if (g_evidence == 1) h.evidence = sbl_image_make(s->ev[s->ping], s->w, s->h, 1);
        o.evidence = sbl_image_make(s->ev[!s->ping], s->w, s->h, 1);
    }
    if (g_tail) {
        h.tail = sbl_image_make(s->tl[s->ping], s->w, s->h, 2);
        o.tail = sbl_image_make(s->tl[!s->ping], s->w, s->h, 2);
    }
    if (g_display) o.display = sbl_image_make(g_display, s->w, s->h, s->ch);
    r = sbl_temporal_filter_frame(d, &f, first ? NULL : &h, &o);
    s->ping = !s->ping;
    return r;
}

static float *seq_out(seq1 *s, int x, int y) { return s->hist[s->ping] + ((size_t)y * s->w + x) * s->ch; }
static float seq_n(seq1 *s, int x, int y) { return s->len[s->ping][(size_t)y * s->w + x]; }

/* ---- a single firefly in a converged history ------------------------------------ */

typedef struct firefly_result { double err_before, err_after, err_decay, n_before, n_after, n_nb_min; } firefly_result;

static firefly_result firefly_run(sbl_estimator e)
{
    const double mu = 0.5, sigma = 0.1, fire = 500.0;
    const int px = TW / 2, py = TH / 2, warm = 40;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {2024};
    firefly_result r;
    int i, x, y, c;
    memset(&r, 0, sizeof r);
    memset(&d, 0, sizeof d);
    d.estimator = e;
    d.stereo_shared_bias = g_shared;
    seq_init(&s, TW, TH, 3);
    for (i = 0; i < warm + 11; ++i) {
        for (y = 0; y < TH; ++y)
            for (x = 0; x < TW; ++x)
                for (c = 0; c < 3; ++c)
                    s.cur[((size_t)y * TW + x) * 3 + c] = (float)(mu + sigma * sbt_gauss(&rng));
        if (i == warm)
            for (c = 0; c < 3; ++c) s.cur[((size_t)py * TW + px) * 3 + c] = (float)fire;
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i == warm - 1) {
            r.err_before = fabs(seq_out(&s, px, py)[0] - mu);
            r.n_before = seq_n(&s, px, py);
        }
        if (i == warm) {
            int j, k;
            r.err_after = fabs(seq_out(&s, px, py)[0] - mu);
            r.n_after = seq_n(&s, px, py);
            r.n_nb_min = 1e30;
            for (k = -1; k <= 1; ++k)
                for (j = -1; j <= 1; ++j)
                    if ((j || k) && seq_n(&s, px + j, py + k) < r.n_nb_min) r.n_nb_min = seq_n(&s, px + j, py + k);
        }
    }
    r.err_decay = fabs(seq_out(&s, px, py)[0] - mu);
    seq_free(&s);
    return r;
}

static void test_firefly(void)
{
    firefly_result rb = firefly_run(SBL_ESTIMATOR_ROBUST), ha = firefly_run(SBL_ESTIMATOR_HISTORY_AWARE);
    firefly_result po = firefly_run(SBL_ESTIMATOR_POOLED);
    sbl_temporal_desc def;
    memset(&def, 0, sizeof def);
    printf("  firefly (500 in a flat 0.5 +- 0.1 region, after 40 frames): robust: error %.4f -> %.4f -> "
           "%.4f 10 frames later, N %.1f -> %.1f (neighbours >= %.1f); history-aware: error %.4f -> "
           "%.4f -> %.4f, N %.1f -> %.1f\n",
           rb.err_before, rb.err_after, rb.err_decay, rb.n_before, rb.n_after, rb.n_nb_min,
           ha.err_before, ha.err_after, ha.err_decay, ha.n_before, ha.n_after);
    /* bounded: the firefly moves the output by less than the 1-spp noise level, while
       entering it unlimited at 1/(N+1) moves it by about 500/41 */
    CHECK(rb.err_after < 0.1);
    CHECK(ha.err_after > 5.0); /* the effect the limit removes */
    /* no reset: the history keeps its length at the pixel and around it */
    CHECK(rb.n_after > 0.5 * rb.n_before);
    CHECK(rb.n_nb_min > 0.5 * rb.n_before);
    /* decays: 10 frames later the error is back near the converged level */
    CHECK(rb.err_decay < 0.05);
    /* the pooled estimator has the same limit; a firefly must not pass for a change of
       the blocks around it either */
    printf("  firefly, pooled: error %.4f -> %.4f -> %.4f 10 frames later, N %.1f -> %.1f "
           "(neighbours >= %.1f)\n", po.err_before, po.err_after, po.err_decay, po.n_before,
           po.n_after, po.n_nb_min);
    CHECK(po.err_after < 0.1);
    CHECK(po.n_after > 0.5 * po.n_before);
    CHECK(po.n_nb_min > 0.5 * po.n_before);
    CHECK(po.err_decay < 0.05);
}

/* ---- static convergence and a step change (as test_core's, for robust) ----------- */

static double tex(int x, int y) { return 0.5 + 0.3 * sin(0.35 * x) * cos(0.25 * y); }

/* ---- fireflies at a rate: the limit against the plain mean ----------------------- */

/* Heavy-tailed samples whose mean is known (bench scene synthetic-firefly): each sample
   of a static textured scene with noise 0.1 is, with probability r = 0.02, (1 + 25)
   times its value and otherwise 1 times, over 1 + r 25, so that a third of the energy
   arrives in 2 % of the samples and the mean is the texture. Over frames 24-47 the
   default must beat the plain mean of every sample so far (the best linear estimate
   of a static pixel: unbiased, the spikes' variance over N) and EMA 0.2. This is what
   the firefly limit buys: with it off (SBL_FIREFLY_SIGMAS 1e6) the default is worse
   than the mean here. */
static void test_firefly_rate(void)
{
    const int w = 64, h = 48, frames = 48, from = 24;
    const double r = 0.02, g = 25.0, body = 1.0 / (1.0 + r * g), spike = (1.0 + g) * body;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {2025};
    double *mean = (double *)calloc((size_t)w * h, sizeof(double));
    double *ema = (double *)calloc((size_t)w * h, sizeof(double));
    double se_def = 0.0, se_mean = 0.0, se_ema = 0.0;
    long cnt = 0;
    int i, x, y;
    memset(&d, 0, sizeof d);
    d.stereo_shared_bias = g_shared;
    seq_init(&s, w, h, 1);
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const size_t q = (size_t)y * w + x;
                const double f = sbt_uniform(&rng) < r ? spike : body;
                const double v = (tex(x, y) + 0.1 * sbt_gauss(&rng)) * f;
                s.cur[q] = (float)v;
                mean[q] += (v - mean[q]) / (i + 1);
                ema[q] = i ? ema[q] + 0.2 * (v - ema[q]) : v;
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i < from) continue;
        for (y = 1; y < h - 1; ++y)
            for (x = 1; x < w - 1; ++x) {
                const size_t q = (size_t)y * w + x;
                const double t = tex(x, y), a = seq_out(&s, x, y)[0] - t;
                se_def += a * a;
                se_mean += (mean[q] - t) * (mean[q] - t);
                se_ema += (ema[q] - t) * (ema[q] - t);
                cnt++;
            }
    }
    printf("  fireflies at rate 0.02, a third of the energy (frames %d-%d, RMSE against the mean): "
           "default %.4f, plain mean %.4f, EMA 0.2 %.4f\n", from, frames - 1,
           sqrt(se_def / cnt), sqrt(se_mean / cnt), sqrt(se_ema / cnt));
    /* measured (gcc, session 25): 0.1648 against 0.2051 and 0.4172; with the limit off
       0.2279, above the mean */
    CHECK(se_def < 0.9 * 0.9 * se_mean);
    CHECK(se_def < 0.5 * 0.5 * se_ema);
    free(mean); free(ema);
    seq_free(&s);
}

/* 32 frames of a static textured scene, noise 0.2: RMSE of the output against the
   truth, and of the plain mean of the 32 samples; then a step of +1 at frame 16 of a
   24-frame run (noise 0.1): RMSE 8 frames after. */
static void convergence_run(sbl_estimator e, double *rmse, double *rmse_mean, double *step_err)
{
    const int w = 64, h = 48, frames = 32;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {99};
    double *acc = (double *)calloc((size_t)w * h, sizeof(double)), se = 0, sm = 0;
    int i, x, y;
    memset(&d, 0, sizeof d);
    d.estimator = e;
    seq_init(&s, w, h, 1);
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                float v = (float)(tex(x, y) + 0.2 * sbt_gauss(&rng));
                s.cur[y * w + x] = v;
                acc[y * w + x] += v / frames;
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
    }
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double a = seq_out(&s, x, y)[0] - tex(x, y), b = acc[y * w + x] - tex(x, y);
            se += a * a; sm += b * b;
        }
    *rmse = sqrt(se / (w * h));
    *rmse_mean = sqrt(sm / (w * h));
    se = 0;
    for (i = 0; i < 24; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                s.cur[y * w + x] = (float)(tex(x, y) + (i >= 16 ? 1.0 : 0.0) + 0.1 * sbt_gauss(&rng));
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
    }
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x) {
            double a = seq_out(&s, x, y)[0] - (tex(x, y) + 1.0);
            se += a * a;
        }
    *step_err = sqrt(se / (w * h));
    free(acc);
    seq_free(&s);
}

static void test_convergence_and_step(void)
{
    double r_rb, m_rb, s_rb, r_ha, m_ha, s_ha, r_po, m_po, s_po;
    convergence_run(SBL_ESTIMATOR_ROBUST, &r_rb, &m_rb, &s_rb);
    convergence_run(SBL_ESTIMATOR_HISTORY_AWARE, &r_ha, &m_ha, &s_ha);
    convergence_run(SBL_ESTIMATOR_POOLED, &r_po, &m_po, &s_po);
    printf("  static, 32 frames, noise 0.2: RMSE pooled %.5f; step +1, 8 frames after: pooled %.4f\n",
           r_po, s_po);
    /* the pooled estimator (the default): as quiet as the history-aware one on a static
       scene, and as fast after a step */
    CHECK(r_po <= 1.20 * m_po);
    CHECK(r_po <= 1.03 * r_ha);
    CHECK(s_po < 0.1);
    CHECK(s_po <= s_ha * 1.05);
    printf("  static, 32 frames, noise 0.2: RMSE robust %.5f, history-aware %.5f, mean of 32 %.5f; "
           "step +1, 8 frames after: robust %.4f, history-aware %.4f\n", r_rb, r_ha, m_rb, s_rb, s_ha);
    /* converges about like the mean of the samples (1/(N+1)): within 20 % of its RMSE
       on this textured scene (measured 1.16; history-aware 1.19) */
    CHECK(r_rb <= 1.20 * m_rb);
    CHECK(r_rb <= 1.03 * r_ha);
    /* and follows a step change */
    CHECK(s_rb < 0.1);
}

/* ---- a light edge that moves every frame ---------------------------------------- */

/* Shading 0.2 + 0.8 smoothstep over a ramp of `ramp` pixels whose centre moves by `v`
   pixels per frame, with zero motion vectors (a moving light, not moving geometry).
   Returns the mean lag of the filtered edge behind the true one, in frames, measured on
   the row-averaged profile (where it crosses the middle value), over frames 20..39. */
static double moving_light_lag(sbl_estimator e, double v, double ramp, double noise, double *rmse_out)
{
    const int w = 96, h = 16, frames = 40;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {77};
    double lag_sum = 0.0, se = 0.0;
    int i, x, y, nlag = 0, nse = 0;
    memset(&d, 0, sizeof d);
    d.estimator = e;
    seq_init(&s, w, h, 1);
    for (i = 0; i < frames; ++i) {
        double edge = 12.0 + v * i;
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                double t = (x + 0.5 - edge) / ramp + 0.5;
                double sm = t <= 0 ? 0 : (t >= 1 ? 1 : t * t * (3 - 2 * t));
                s.cur[(size_t)y * w + x] = (float)(0.2 + 0.8 * sm + noise * sbt_gauss(&rng));
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i >= 20) {
            double prof[96];
            for (x = 0; x < w; ++x) {
                double t = (x + 0.5 - edge) / ramp + 0.5;
                double sm = t <= 0 ? 0 : (t >= 1 ? 1 : t * t * (3 - 2 * t));
                prof[x] = 0;
                for (y = 0; y < h; ++y) {
                    double o = seq_out(&s, x, y)[0], dd = o - (0.2 + 0.8 * sm);
                    prof[x] += o / h;
                    se += dd * dd;
                    ++nse;
                }
            }
            /* the filtered edge lags behind (to the left): last crossing of 0.6 from below */
            for (x = w - 2; x >= 0; --x)
                if (prof[x] < 0.6 && prof[x + 1] >= 0.6) {
                    double pos = x + 0.5 + (0.6 - prof[x]) / (prof[x + 1] - prof[x]);
                    lag_sum += (edge - pos) / v;
                    ++nlag;
                    break;
                }
        }
    }
    seq_free(&s);
    *rmse_out = sqrt(se / (nse ? nse : 1));
    return nlag ? lag_sum / nlag : 1e30;
}

static void test_moving_light(void)
{
    static const double cases[4][3] = {{0.5, 8.0, 0.1}, {2.0, 8.0, 0.1}, {0.5, 16.0, 0.3}, {1.0, 24.0, 0.5}};
    int k;
    for (k = 0; k < 4; ++k) {
        double r_rb, r_ha, r_prog, r_po;
        double lag_rb = moving_light_lag(SBL_ESTIMATOR_ROBUST, cases[k][0], cases[k][1], cases[k][2], &r_rb);
        double lag_po = moving_light_lag(SBL_ESTIMATOR_POOLED, cases[k][0], cases[k][1], cases[k][2], &r_po);
        double lag_ha = moving_light_lag(SBL_ESTIMATOR_HISTORY_AWARE, cases[k][0], cases[k][1], cases[k][2], &r_ha);
        double lag_prog = moving_light_lag(SBL_ESTIMATOR_PROGRESSIVE, cases[k][0], cases[k][1], cases[k][2], &r_prog);
        printf("  moving light edge (%.1f px/frame, ramp %.0f px, noise %.1f): lag in frames robust %.2f "
               "(RMSE %.4f), history-aware %.2f (%.4f), progressive %.2f (%.4f)\n",
               cases[k][0], cases[k][1], cases[k][2], lag_rb, r_rb, lag_ha, r_ha, lag_prog, r_prog);
        /* bounded: within 4.5 frames at every speed and noise level here (progressive
           averaging lags by 14), and not behind the previous default */
        CHECK(lag_rb <= 4.5);
        CHECK(lag_rb <= lag_ha + 0.25);
        CHECK(r_rb <= r_ha * 1.02);
        printf("    pooled: lag %.2f frames (RMSE %.4f)\n", lag_po, r_po);
        CHECK(lag_po <= 4.5);
        CHECK(lag_po <= lag_ha + 0.25);
        CHECK(r_po <= r_ha * 1.02);
        {   /* with the evidence plane carried (the default as the bench runs it) */
            double r_pe, lag_pe;
            g_evidence = 1;
            lag_pe = moving_light_lag(SBL_ESTIMATOR_POOLED, cases[k][0], cases[k][1], cases[k][2], &r_pe);
            g_evidence = 0;
            printf("    pooled with the evidence plane: lag %.2f frames (RMSE %.4f)\n", lag_pe, r_pe);
            CHECK(lag_pe <= 4.5);
            CHECK(lag_pe <= lag_po + 0.25);
            /* measured: better at 0.5-1 px/frame, 3 % worse at 2 px/frame (the carried
               evidence keeps the pixels an edge has just passed young for a few frames) */
            CHECK(r_pe <= r_po * 1.06);
        }
    }
}

/* ---- stereo: a noisy depth edge, and a flat noisy region ------------------------- */

/* Foreground (left-eye u < 24.2, depth 2) over a background at depth 8; parallel rig
   with focal * baseline = 8.6 px: disparities 4.3 and 1.075 (matches between pixel
   centres, so the gather interpolates). Colour is the pixel's box-filtered average of
   8 sub-samples (anti-aliased across the silhouette), depth is point-sampled at the
   pixel centre, as in a renderer: the mixed pixels along the edge match pixels of one
   layer only in the other eye. flat: both layers one colour (only noise). */
#define FG_EDGE 24.2
#define FG_DISP 4.3
#define BG_DISP 1.075
static int g_strong_edge; /* 1: a near-white foreground over a near-black background */
static double layer_colour(int fg, double world_u, int flat)
{
    if (flat) return 0.5;
    if (g_strong_edge) return fg ? 0.95 + 0.03 * sin(world_u * 0.7) : 0.05 + 0.02 * sin(world_u * 1.3);
    return fg ? 0.75 + 0.1 * sin(world_u * 0.7) : 0.2 + 0.05 * sin(world_u * 1.3);
}

/* eye 0 (left) or 1 (right): sub-sample at u (pixels) -> colour, depth */
static void stereo_scene_sample(int eye, double u, int flat, double *col, double *z)
{
    double edge = eye ? FG_EDGE - FG_DISP : FG_EDGE;
    int fg = u < edge;
    double world_u = u + (eye ? (fg ? FG_DISP : BG_DISP) : 0.0);
    *col = layer_colour(fg, world_u, flat);
    *z = fg ? 2.0 : 8.0;
}

static void stereo_measure(sbl_estimator e, int flat, double sigma, unsigned long long seed,
                           double *edge_in, double *edge_out, double *all_in, double *all_out)
{
    enum { W = 48, H = 32 };
    static float col[2][W * H * 3], ref[2][W * H * 3], depth[2][W * H], out[2][W * H * 3];
    sbl_stereo_desc d;
    sbl_eye eye[2];
    sbt_rng rng;
    double se_in = 0, se_out = 0, sa_in = 0, sa_out = 0;
    int ne = 0, na = 0, x, y, c, k, ey;
    rng.s = seed;
    for (ey = 0; ey < 2; ++ey)
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                double acc = 0, cc, z;
                for (k = 0; k < 8; ++k) {
                    stereo_scene_sample(ey, x + (k + 0.5) / 8.0, flat, &cc, &z);
                    acc += cc / 8.0;
                }
                stereo_scene_sample(ey, x + 0.5, flat, &cc, &z);
                depth[ey][y * W + x] = (float)z;
                for (c = 0; c < 3; ++c) {
                    ref[ey][(y * W + x) * 3 + c] = (float)acc;
                    col[ey][(y * W + x) * 3 + c] = (float)(acc + sigma * sbt_gauss(&rng));
                }
            }
    memset(&d, 0, sizeof d);
    d.rig = SBL_RIG_PARALLEL;
    d.focal_px = (float)(FG_DISP * 2.0);
    d.baseline = 1.0f;
    d.estimator = e;
    for (ey = 0; ey < 2; ++ey) {
        memset(&eye[ey], 0, sizeof eye[ey]);
        eye[ey].color = sbl_image_make(col[ey], W, H, 3);
        eye[ey].gbuffer.depth = sbl_image_make(depth[ey], W, H, 1);
    }
    CHECK_EQ(sbl_stereo_blend_frame(&d, &eye[0], &eye[1], sbl_image_make(out[0], W, H, 3),
                                    sbl_image_make(out[1], W, H, 3)), SBL_OK);
    for (ey = 0; ey < 2; ++ey)
        for (y = 0; y < H; ++y)
            for (x = 4; x < W - 4; ++x) {
                double edge = ey ? FG_EDGE - FG_DISP : FG_EDGE;
                int near_edge = fabs(x + 0.5 - edge) <= 2.0;
                for (c = 0; c < 3; ++c) {
                    size_t i = (size_t)(y * W + x) * 3 + c;
                    double a = col[ey][i] - ref[ey][i], b = out[ey][i] - ref[ey][i];
                    sa_in += a * a; sa_out += b * b; ++na;
                    if (near_edge) { se_in += a * a; se_out += b * b; ++ne; }
                }
            }
    *edge_in = sqrt(se_in / ne); *edge_out = sqrt(se_out / ne);
    *all_in = sqrt(sa_in / na); *all_out = sqrt(sa_out / na);
}

static void test_stereo_edge_and_flat(void)
{
    static const sbl_estimator est[5] = {SBL_ESTIMATOR_POOLED, SBL_ESTIMATOR_HISTORY_AWARE,
                                         SBL_ESTIMATOR_PAPER, SBL_ESTIMATOR_CONSTANT,
                                         SBL_ESTIMATOR_ROBUST};
    static const char *const names[5] = {"pooled", "history-aware", "paper", "beta 0.5", "robust"};
    double edge_in[5], edge_out[5], all_in[5], all_out[5], flat_out[5], flat_in[5], dummy1, dummy2;
    int k, s;
    for (k = 0; k < 5; ++k) {
        edge_in[k] = edge_out[k] = all_in[k] = all_out[k] = flat_out[k] = flat_in[k] = 0;
        for (s = 0; s < 8; ++s) {
            double ei, eo, ai, ao, fi, fo;
            stereo_measure(est[k], 0, 0.05, 1000 + (unsigned long long)s, &ei, &eo, &ai, &ao);
            stereo_measure(est[k], 1, 0.05, 2000 + (unsigned long long)s, &dummy1, &dummy2, &fi, &fo);
            edge_in[k] += ei * ei / 8; edge_out[k] += eo * eo / 8;
            all_in[k] += ai * ai / 8; all_out[k] += ao * ao / 8;
            flat_in[k] += fi * fi / 8; flat_out[k] += fo * fo / 8;
        }
        printf("  stereo, noise 0.05, %-13s: depth-edge RMSE %.5f (input %.5f), whole %.5f (input %.5f), "
               "flat %.5f (input %.5f)\n", names[k], sqrt(edge_out[k]), sqrt(edge_in[k]),
               sqrt(all_out[k]), sqrt(all_in[k]), sqrt(flat_out[k]), sqrt(flat_in[k]));
    }
    /* the default blend never makes a depth edge worse than not blending */
    CHECK(edge_out[0] <= edge_in[0]);
    CHECK(all_out[0] < all_in[0]);
    /* it does better than the previous default there */
    CHECK(edge_out[0] <= edge_out[1]);
    /* flat noisy region: at least as good as the paper's beta (issue 11) */
    CHECK(flat_out[0] <= flat_out[2]);
    /* a strong edge (contrast 0.9) at three noise levels: on the flat region at least as
       good as the paper's beta at each level, and on the edge better than the paper's
       beta and never worse than not blending (issue 11). The mixed pixels' bias used to
       inflate their window's pair spread, which hid it from the window's test (0.0312
       against the input's 0.0202 at noise 0.02); the stereo weight now takes its noise
       from the pairs' spread within the window's columns where the columns differ
       (docs/ESTIMATORS.md 4.15, 4.16) */
    {
        static const double sigmas[3] = {0.02, 0.05, 0.1};
        int l;
        g_strong_edge = 1;
        for (l = 0; l < 3; ++l) {
            double ei2 = 0, eo2 = 0, ep2 = 0, fo2 = 0, fp2 = 0;
            for (s = 0; s < 8; ++s) {
                double ei, eo, ep, ai, ao, fi, fo, fp;
                unsigned long long seed = 3000 + 100 * (unsigned long long)l + (unsigned long long)s;
                stereo_measure(SBL_ESTIMATOR_POOLED, 0, sigmas[l], seed, &ei, &eo, &ai, &ao);
                stereo_measure(SBL_ESTIMATOR_PAPER, 0, sigmas[l], seed, &ei, &ep, &ai, &ao);
                stereo_measure(SBL_ESTIMATOR_POOLED, 1, sigmas[l], seed + 50, &dummy1, &dummy2, &fi, &fo);
                stereo_measure(SBL_ESTIMATOR_PAPER, 1, sigmas[l], seed + 50, &dummy1, &dummy2, &fi, &fp);
                ei2 += ei * ei / 8; eo2 += eo * eo / 8; ep2 += ep * ep / 8;
                fo2 += fo * fo / 8; fp2 += fp * fp / 8;
            }
            printf("  stereo, strong edge, noise %.2f: depth-edge RMSE pooled %.5f, paper %.5f (input "
                   "%.5f); flat pooled %.5f, paper %.5f\n", sigmas[l], sqrt(eo2), sqrt(ep2), sqrt(ei2),
                   sqrt(fo2), sqrt(fp2));
            CHECK(eo2 <= ep2);
            CHECK(fo2 <= fp2);
            CHECK(eo2 <= ei2);
        }
        g_strong_edge = 0;
    }
}


/* Two temporally filtered eyes under a change both see (a light that moved): the left
   eye's history is old (N 20) and still shows the old value 0.5, the right eye's has
   just restarted (N 1) on the new value 0.6; flat, equal depth, integer disparity. The
   difference of the two eyes is the old eye's lag, not the match's: the pooled beta
   takes the left eye towards the fresh right one, and keeps the right eye on its own
   (docs/ESTIMATORS.md section 4.6; with SBL_STEREO_LAG_SHARE 0, the rule before it, the
   left eye keeps its lag: RMSE 0.09). Returns the RMSE of each eye's output. The left
   eye's value is left_value (0.5: the lag; 0.6: the eyes agree). */
static void stereo_lag_measure_ev(int n_left, int n_right, double left_value, double ev_left,
                                  double ev_right, double *rmse_left, double *rmse_right);
static void stereo_lag_measure(int n_left, int n_right, double left_value, double *rmse_left,
                               double *rmse_right)
{
    stereo_lag_measure_ev(n_left, n_right, left_value, 0.0, 0.0, rmse_left, rmse_right);
}
/* ev_left / ev_right > 0: that eye's evidence plane (sbl_eye.evidence), that value
   everywhere; 0: none */
static void stereo_lag_measure_ev(int n_left, int n_right, double left_value, double ev_left,
                                  double ev_right, double *rmse_left, double *rmse_right)
{
    enum { W = 48, H = 32 };
    static float col[2][W * H * 3], depth[W * H], len[2][W * H], out[2][W * H * 3], ev[2][W * H];
    const double evv[2] = {ev_left, ev_right};
    sbl_stereo_desc d;
    sbl_eye eye[2];
    sbt_rng rng;
    const double truth = 0.6, sigma = 0.05;
    double se[2] = {0, 0};
    int x, y, c, ey, n = 0;
    rng.s = 4242;
    for (ey = 0; ey < 2; ++ey)
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                int nn = ey ? n_right : n_left;
                /* left_value < 0: the left eye lags by -left_value, its sign
                   alternating every 4 columns (a change whose blocks' mean cancels) */
                double v = ey ? truth : left_value >= 0.0 ? left_value
                                      : truth + (((x / 4) & 1) ? left_value : -left_value);
                depth[y * W + x] = 4.0f;
                len[ey][y * W + x] = (float)nn;
                ev[ey][y * W + x] = (float)evv[ey];
                for (c = 0; c < 3; ++c)
                    col[ey][(y * W + x) * 3 + c] = (float)(v + sigma / sqrt((double)nn) * sbt_gauss(&rng));
            }
    memset(&d, 0, sizeof d);
    d.rig = SBL_RIG_PARALLEL;
    d.focal_px = 8.0f; /* disparity 2 px */
    d.baseline = 1.0f;
    for (ey = 0; ey < 2; ++ey) {
        memset(&eye[ey], 0, sizeof eye[ey]);
        eye[ey].color = sbl_image_make(col[ey], W, H, 3);
        eye[ey].length = sbl_image_make(len[ey], W, H, 1);
        eye[ey].gbuffer.depth = sbl_image_make(depth, W, H, 1);
        if (evv[ey] > 0.0) eye[ey].evidence = sbl_image_make(ev[ey], W, H, 1);
    }
    CHECK_EQ(sbl_stereo_blend_frame(&d, &eye[0], &eye[1], sbl_image_make(out[0], W, H, 3),
                                    sbl_image_make(out[1], W, H, 3)), SBL_OK);
    for (y = 1; y < H - 1; ++y)
        for (x = 4; x < W - 4; ++x, ++n)
            for (ey = 0; ey < 2; ++ey)
                for (c = 0; c < 3; ++c) {
                    double e = out[ey][(size_t)(y * W + x) * 3 + c] - truth;
                    se[ey] += e * e / 3;
                }
    *rmse_left = sqrt(se[0] / n);
    *rmse_right = sqrt(se[1] / n);
}

static void test_stereo_lag(void)
{
    double l, r;
    stereo_lag_measure(20, 1, 0.5, &l, &r);
    printf("  stereo, old lagging left eye (N 20, off by 0.1) against a fresh right eye (N 1, "
           "noise 0.05): RMSE left %.4f, right %.4f (input 0.1000, 0.0500)\n", l, r);
    /* the lag is not kept: the old eye moves most of the way to the fresh one */
    CHECK(l < 0.06);
    /* and the fresh eye is not pulled towards the old one's lag */
    CHECK(r < 0.05);
}

/* The eyes' change evidence in the stereo blend (sbl_eye.evidence, docs/ESTIMATORS.md
   6.15). The left eye's history is old (N 16) and lags a change by 0.04, its sign
   alternating every 4 columns (a moving shadow's edges: the blocks' means cancel, so
   only the 3x3 test could see it); the right eye restarted on the change (N 2, noise
   0.05 / sqrt 2). The right eye's carried evidence shows the change (R 4), the left
   eye's does not (R 1.2, below c_R = 2.118): read at the match, it makes the left eye's
   blend take the difference as bias, and the left eye moves towards the fresh one.
   Where the eyes agree, the same flag on both costs little (all of pd^2 taken as bias
   is then the window's noise). A blend that ignored the other eye's plane would keep
   the left eye's RMSE as it is without the planes. */
static void test_stereo_change_evidence(void)
{
    double l0, r0, l1, r1, la, ra, lb, rb;
    stereo_lag_measure_ev(16, 2, -0.04, 0.0, 0.0, &l0, &r0);
    stereo_lag_measure_ev(16, 2, -0.04, 1.2, 4.0, &l1, &r1);
    stereo_lag_measure_ev(16, 2, 0.6, 0.0, 0.0, &la, &ra);
    stereo_lag_measure_ev(16, 2, 0.6, 4.0, 4.0, &lb, &rb);
    printf("  stereo, old left eye (N 16) lagging a change by +-0.04 that the fresh right eye's "
           "evidence shows: RMSE left %.5f -> %.5f, right %.5f -> %.5f with the planes; eyes "
           "that agree, both flagged: %.5f -> %.5f, %.5f -> %.5f\n", l0, l1, r0, r1, la, lb, ra, rb);
    CHECK(l1 < 0.96 * l0); /* measured 0.937 */
    CHECK(r1 <= r0);
    CHECK(lb < 1.08 * la && rb < 1.08 * ra); /* measured +5.0 %, +2.3 % */
}

/* Two young filtered eyes that agree (both N 2: their histories just restarted, flat,
   noise 0.05 / sqrt 2 per eye): the best blend of the two alone has RMSE 0.025; the
   spatial lean (docs/ESTIMATORS.md 4.2) adds the neighbours as a third estimate where
   N_Y <= SBL_STEREO_LEAN_MAX_N and goes below it. A young eye against an old one (N 2
   against N 16: the blend of the two alone 0.05 / sqrt 18 = 0.0118) leans too: the
   stereo lean's q is not divided by the other eye's N_X (6.5; divided, it is about 0).
   Two eyes of N 8 are blended without it. This test's noise is independent from pixel
   to pixel, so the lean would help there as well (0.0108 without the gate): the check
   says the gate is in place; its reason, the neighbours of a longer filtered eye
   sharing its history, is measured on the bench's scenes (6.5), not here. */
static void test_stereo_lean_young(void)
{
    double l2, r2, l8, r8, lo, ro;
    stereo_lag_measure(2, 2, 0.6, &l2, &r2);
    stereo_lag_measure(8, 8, 0.6, &l8, &r8);
    stereo_lag_measure(2, 16, 0.6, &lo, &ro);
    printf("  stereo, two young eyes (N 2, noise 0.05): RMSE %.4f, %.4f (the two-sample blend "
           "0.0250); N 2 against N 16: %.5f (0.01179); two eyes of N 8: %.4f, %.4f (0.0125)\n",
           l2, r2, lo, l8, r8);
    CHECK(l2 < 0.9 * 0.025 && r2 < 0.9 * 0.025);
    CHECK(lo < 0.94 * 0.05 / sqrt(18.0)); /* measured 0.0108; 0.0114 dividing q by N_X */
    CHECK(l8 > 0.95 * 0.0125 && r8 > 0.95 * 0.0125);
}

/* ---- history resampling: Catmull-Rom against bilinear --------------------------- */

/* The frame (colour, depth, motion) and the history (colour, N, depth) of a motion-vector
   reprojection, every buffer tight, w x h. */
static void motion_inputs(sbl_frame *f, sbl_history *hi, int w, int h, int ch, const float *cur,
                          const float *depth, const float *mv, const float *hist,
                          const float *len, const float *hdepth)
{
    memset(f, 0, sizeof *f); memset(hi, 0, sizeof *hi);
    f->color = sbl_image_make(cur, w, h, ch);
    f->gbuffer.depth = sbl_image_make(depth, w, h, 1);
    f->gbuffer.motion = sbl_image_make(mv, w, h, 2);
    hi->color = sbl_image_make(hist, w, h, ch);
    hi->length = sbl_image_make(len, w, h, 1);
    hi->gbuffer.depth = sbl_image_make(hdepth, w, h, 1);
}

/* x* and its N from sbl_reproject_temporal: history `hist` (ch channels, depth hdepth,
   N = 5 everywhere) seen through a constant backward motion (mvx, mvy) in pixels, the
   frame's depth 1 everywhere. */
static void rp_run(int w, int h, int ch, const float *hist, const float *hdepth, double mvx,
                   double mvy, sbl_history_filter filter, float *out, float *out_n)
{
    size_t n = (size_t)w * (size_t)h, i;
    float *len = (float *)malloc(n * sizeof(float)), *mv = (float *)malloc(n * 2 * sizeof(float));
    float *depth = (float *)malloc(n * sizeof(float)), *cur = (float *)calloc(n * ch, sizeof(float));
    sbl_reproject_desc d;
    sbl_frame f;
    sbl_history hi;
    for (i = 0; i < n; ++i) {
        len[i] = 5.0f; depth[i] = 1.0f;
        mv[2 * i] = (float)mvx; mv[2 * i + 1] = (float)mvy;
    }
    memset(&d, 0, sizeof d);
    d.history_filter = filter;
    motion_inputs(&f, &hi, w, h, ch, cur, depth, mv, hist, len, hdepth);
    CHECK_EQ(sbl_reproject_temporal(&d, SBL_TEMPORAL_MOTION, &f, &hi, sbl_image_make(out, w, h, ch),
                                    sbl_image_make(out_n, w, h, 1), 0, h), SBL_OK);
    free(len); free(mv); free(depth); free(cur);
}

/* True where the 4x4 footprint of target pixel (x, y) under motion (mvx, mvy) lies
   inside a w x h image. */
static int cr_inside(int x, int y, int w, int h, double mvx, double mvy)
{
    int x0 = (int)floor(x + mvx), y0 = (int)floor(y + mvy);
    return x0 - 1 >= 0 && y0 - 1 >= 0 && x0 + 2 < w && y0 + 2 < h;
}

static void test_history_catmull_rom(void)
{
    enum { W = 24, H = 16 };
    static float hist[W * H * 3], depth[W * H], a[W * H * 3], b[W * H * 3], na[W * H], nb[W * H];
    static const double mvs[][2] = {{-0.3, 0.45}, {0.71, -0.2}, {-1.5, -0.5}, {0.125, 2.875}};
    sbt_rng rng = {2024};
    int x, y, k, m, inside = 0, differs = 0;
    double err_cr = 0.0, err_bl = 0.0;
    for (k = 0; k < W * H; ++k) depth[k] = 1.0f;

    /* a monotone quadratic ramp in x and y: Catmull-Rom reproduces polynomials up to
       degree 2 (linear exactly as well), bilinear only degree 1; N stays bilinear's */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x)
            for (k = 0; k < 3; ++k)
                hist[(y * W + x) * 3 + k] = (float)(0.1 + 0.02 * x + 0.001 * x * x + 0.03 * y +
                                                    0.002 * y * y + 0.1 * k);
    for (m = 0; m < 4; ++m) {
        rp_run(W, H, 3, hist, depth, mvs[m][0], mvs[m][1], SBL_HISTORY_CATMULL_ROM, a, na);
        rp_run(W, H, 3, hist, depth, mvs[m][0], mvs[m][1], SBL_HISTORY_BILINEAR, b, nb);
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                double px = x + mvs[m][0], py = y + mvs[m][1];
                if (!cr_inside(x, y, W, H, mvs[m][0], mvs[m][1])) continue;
                ++inside;
                CHECK_EQ(na[y * W + x] == nb[y * W + x], 1);
                for (k = 0; k < 3; ++k) {
                    double t = 0.1 + 0.02 * px + 0.001 * px * px + 0.03 * py + 0.002 * py * py + 0.1 * k;
                    err_cr = fmax(err_cr, fabs(a[(y * W + x) * 3 + k] - t));
                    err_bl = fmax(err_bl, fabs(b[(y * W + x) * 3 + k] - t));
                }
            }
    }
    printf("  history fetch, quadratic ramp: max error Catmull-Rom %.2e, bilinear %.2e (%d pixels)\n",
           err_cr, err_bl, inside);
    CHECK(inside > 4 * 100);
    CHECK(err_cr < 2e-6);
    CHECK(err_bl > 1e-4); /* the ramp can tell the two apart */
    /* a linear ramp, one channel, with the motion's fraction on one axis only */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) hist[y * W + x] = (float)(0.25 + 0.05 * x - 0.01 * y);
    rp_run(W, H, 1, hist, depth, 0.35, 1.0, SBL_HISTORY_CATMULL_ROM, a, na);
    err_cr = 0.0;
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x)
            if (cr_inside(x, y, W, H, 0.35, 1.0))
                err_cr = fmax(err_cr, fabs(a[y * W + x] - (0.25 + 0.05 * (x + 0.35) - 0.01 * (y + 1.0))));
    CHECK(err_cr < 1e-6);

    /* integer offsets: exactly the shifted history (noise), as bilinear */
    for (k = 0; k < W * H * 3; ++k) hist[k] = (float)sbt_uniform(&rng);
    rp_run(W, H, 3, hist, depth, -2.0, 1.0, SBL_HISTORY_CATMULL_ROM, a, na);
    rp_run(W, H, 3, hist, depth, -2.0, 1.0, SBL_HISTORY_BILINEAR, b, nb);
    for (y = 0; y + 1 < H; ++y)
        for (x = 2; x < W; ++x)
            for (k = 0; k < 3; ++k) {
                CHECK_EQ(a[(y * W + x) * 3 + k] == hist[((y + 1) * W + x - 2) * 3 + k], 1);
                CHECK_EQ(a[(y * W + x) * 3 + k] == b[(y * W + x) * 3 + k], 1);
            }

    /* a rejected tap (depth 2 at (8, 6)): every pixel whose 4x4 footprint holds it, and
       every pixel whose footprint leaves the image, gets the bilinear result exactly;
       elsewhere the cubic is used (differs from bilinear on noise) */
    depth[6 * W + 8] = 2.0f;
    rp_run(W, H, 3, hist, depth, 0.3, 0.45, SBL_HISTORY_CATMULL_ROM, a, na);
    rp_run(W, H, 3, hist, depth, 0.3, 0.45, SBL_HISTORY_BILINEAR, b, nb);
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x) {
            /* x0 = x, y0 = y: the footprint is columns x-1..x+2, rows y-1..y+2 */
            int holds = x >= 6 && x <= 9 && y >= 4 && y <= 7;
            int same = 1;
            CHECK_EQ(na[y * W + x] == nb[y * W + x], 1);
            for (k = 0; k < 3; ++k) same &= a[(y * W + x) * 3 + k] == b[(y * W + x) * 3 + k];
            if (holds || !cr_inside(x, y, W, H, 0.3, 0.45)) CHECK_EQ(same, 1);
            else differs += !same;
        }
    CHECK(differs > (W - 3) * (H - 3) - 16 - 20);
    depth[6 * W + 8] = 1.0f;
    /* the same with a NaN colour there (found on the sums): bilinear, finite */
    {
        float keep = hist[(6 * W + 8) * 3 + 1];
        int nonfinite = 0;
        hist[(6 * W + 8) * 3 + 1] = (float)(HUGE_VAL - HUGE_VAL);
        rp_run(W, H, 3, hist, depth, 0.3, 0.45, SBL_HISTORY_CATMULL_ROM, a, na);
        rp_run(W, H, 3, hist, depth, 0.3, 0.45, SBL_HISTORY_BILINEAR, b, nb);
        for (y = 0; y < H; ++y)
            for (x = 0; x < W; ++x) {
                int same = 1;
                for (k = 0; k < 3; ++k) {
                    same &= a[(y * W + x) * 3 + k] == b[(y * W + x) * 3 + k];
                    nonfinite += !(fabs(a[(y * W + x) * 3 + k]) <= 1.0);
                }
                if (x >= 6 && x <= 9 && y >= 4 && y <= 7) CHECK_EQ(same, 1);
            }
        CHECK_EQ(nonfinite, 0);
        hist[(6 * W + 8) * 3 + 1] = keep;
    }

    /* hard edges, non-negative HDR input: never negative, never above the input's
       maximum, always finite (the clamp to the inner taps' range); the cubic without it
       would undershoot next to the edge */
    for (y = 0; y < H; ++y)
        for (x = 0; x < W; ++x)
            for (k = 0; k < 3; ++k) {
                float v = x < 9 ? 0.0f : (k == 0 ? 3.0e38f : 1000.0f);
                if ((x / 3 + y / 3) % 2 == 0 && y > 8) v = (k == 1) ? 1.0f : 0.0f; /* checks */
                if (x == 5 && y == 4) v = 3.0e38f;                                   /* a spike */
                hist[(y * W + x) * 3 + k] = v;
            }
    for (m = 0; m < 64; ++m) {
        double mvx = -1.0 + (m % 8) * 0.27, mvy = -1.0 + (m / 8) * 0.29;
        int bad = 0;
        rp_run(W, H, 3, hist, depth, mvx, mvy, SBL_HISTORY_CATMULL_ROM, a, na);
        for (k = 0; k < W * H * 3; ++k) {
            if (!(na[k / 3] > 0.0f)) continue;
            bad += !(a[k] >= 0.0f && a[k] <= 3.0e38f * (1.0f + 1e-6f)); /* bilinear rounding */
        }
        CHECK_EQ(bad, 0);
    }
}

/* A sharp pattern moved by 0.37 / 0.23 pixels per frame (motion vectors exact, no
   noise) through the temporal filter with a constant weight 0.1 (every frame keeps 90 %
   of the resampled history, so resampling blur accumulates as it does under a converged
   history): the contrast left after 40 frames, as a fraction of the pattern's. */
static double moving_pattern_contrast(sbl_history_filter filter, double *rmse)
{
    const int w = 64, h = 32, frames = 40;
    const double vx = 0.37, vy = 0.23, period = 6.0;
    seq1 s;
    sbl_temporal_desc d;
    double num = 0.0, den = 0.0, se = 0.0;
    int i, x, y, cnt = 0;
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_CONSTANT;
    d.reproject.history_filter = filter;
    seq_init(&s, w, h, 1);
    for (i = 0; i < (int)((size_t)w * h); ++i) {
        s.mv[2 * i] = (float)-vx; /* backward: the history is at x - v */
        s.mv[2 * i + 1] = (float)-vy;
    }
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                double u = x + 0.5 - vx * i, v = y + 0.5 - vy * i; /* pattern coordinates */
                s.cur[y * w + x] = (float)(0.5 + 0.4 * sin(6.283185307179586 * u / period) *
                                                     cos(6.283185307179586 * v / (2 * period)));
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
    }
    /* the contrast: least-squares amplitude of the true pattern in the output, away
       from the left and top edges (where the history restarts) */
    for (y = 8; y < h - 2; ++y)
        for (x = 16; x < w - 2; ++x) {
            double t = s.cur[y * w + x] - 0.5, o = seq_out(&s, x, y)[0] - 0.5;
            num += o * t; den += t * t; se += (o - t) * (o - t); ++cnt;
        }
    seq_free(&s);
    *rmse = sqrt(se / cnt);
    return num / den;
}

static void test_history_sharpness(void)
{
    double r_cr, r_bl;
    double c_cr = moving_pattern_contrast(SBL_HISTORY_CATMULL_ROM, &r_cr);
    double c_bl = moving_pattern_contrast(SBL_HISTORY_BILINEAR, &r_bl);
    printf("  moving pattern (period 6 px, 0.37 / 0.23 px per frame, weight 0.1, 40 frames): "
           "contrast kept Catmull-Rom %.3f, bilinear %.3f; RMSE %.4f, %.4f\n", c_cr, c_bl, r_cr, r_bl);
    /* measured: 0.777 against 0.432, RMSE 0.048 against 0.116 */
    CHECK(c_cr > 1.5 * c_bl);
    CHECK(c_cr < 1.01); /* no overshoot either */
    CHECK(r_cr < 0.6 * r_bl);
}

/* The Catmull-Rom fetch in row bands: the same output, bit for bit, as one call over the
   whole image (the default estimator reads neighbouring rows, and the cubic reaches two
   rows up and down: a band must read them, never its own partial output). */
static void test_history_filter_bands(void)
{
    enum { W = 37, H = 23, C = 3 };
    static float cur[W * H * C], hist[W * H * C], len[W * H], depth[W * H], hdepth[W * H];
    static float mv[W * H * 2], whole[W * H * C], whole_n[W * H], whole_a[W * H];
    static float band[W * H * C], band_n[W * H], band_a[W * H];
    static const int cuts[] = {0, 1, 5, 6, 13, 22, 23};
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history hi;
    sbl_temporal_output o;
    size_t bytes = sbl_temporal_scratch_size(W, C);
    void *scratch = malloc(bytes);
    unsigned rng = 12345u;
    int i, b;
    for (i = 0; i < W * H; ++i) {
        int x = i % W, y = i / W, c;
        for (c = 0; c < C; ++c) {
            rng = rng * 1664525u + 1013904223u;
            cur[i * C + c] = 0.3f + 0.4f * (float)(rng >> 8) / 16777216.0f;
            hist[i * C + c] = (x + y) % 7 < 3 ? 0.9f : 0.1f + 0.01f * (float)c;
        }
        len[i] = (float)(1 + (x * 3 + y) % 9);
        depth[i] = hdepth[i] = x < 20 ? 1.0f : 4.0f; /* a depth edge: some cubic taps fail */
        mv[2 * i] = -0.37f - 0.01f * (float)(y % 3);
        mv[2 * i + 1] = 0.23f;
    }
    memset(&d, 0, sizeof d);
    d.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    motion_inputs(&f, &hi, W, H, C, cur, depth, mv, hist, len, hdepth);
    memset(&o, 0, sizeof o);
    o.color = sbl_image_make(whole, W, H, C);
    o.length = sbl_image_make(whole_n, W, H, 1);
    o.alpha = sbl_image_make(whole_a, W, H, 1);
    CHECK(scratch != NULL);
    if (!scratch) return;
    CHECK_EQ(sbl_temporal_filter(&d, &f, &hi, &o, 0, H, scratch, bytes), SBL_OK);
    o.color = sbl_image_make(band, W, H, C);
    o.length = sbl_image_make(band_n, W, H, 1);
    o.alpha = sbl_image_make(band_a, W, H, 1);
    for (b = 0; b + 1 < (int)(sizeof cuts / sizeof cuts[0]); ++b)
        CHECK_EQ(sbl_temporal_filter(&d, &f, &hi, &o, cuts[b], cuts[b + 1], scratch, bytes), SBL_OK);
    CHECK(memcmp(whole, band, sizeof whole) == 0);
    CHECK(memcmp(whole_n, band_n, sizeof whole_n) == 0);
    CHECK(memcmp(whole_a, band_a, sizeof whole_a) == 0);
    /* and the option did something here: the bilinear fetch gives another image */
    d.reproject.history_filter = SBL_HISTORY_BILINEAR;
    CHECK_EQ(sbl_temporal_filter(&d, &f, &hi, &o, 0, H, scratch, bytes), SBL_OK);
    CHECK(memcmp(whole, band, sizeof whole) != 0);
    free(scratch);
}

/* history_filter: an unknown value is refused by every call that takes the descriptor,
   and sbl_temporal_validate names the field; the stereo calls accept the valid values
   (they stay bilinear). */
static void test_history_filter_params(void)
{
    enum { W = 8, H = 6 };
    static float col[W * H * 3], out[W * H * 3], len[W * H], outn[W * H], depth[W * H], mv[W * H * 2];
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history hi;
    sbl_temporal_output o;
    sbl_diag diag;
    int k;
    for (k = 0; k < W * H; ++k) { depth[k] = 1.0f; len[k] = 1.0f; }
    memset(&d, 0, sizeof d); memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi); memset(&o, 0, sizeof o);
    f.color = sbl_image_make(col, W, H, 3);
    f.gbuffer.depth = sbl_image_make(depth, W, H, 1);
    f.gbuffer.motion = sbl_image_make(mv, W, H, 2);
    hi.color = sbl_image_make(col, W, H, 3);
    hi.length = sbl_image_make(len, W, H, 1);
    hi.gbuffer.depth = f.gbuffer.depth;
    o.color = sbl_image_make(out, W, H, 3);
    o.length = sbl_image_make(outn, W, H, 1);
    d.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_OK);
    CHECK_EQ(sbl_temporal_validate(&d, &f, &hi, &o, &diag), SBL_OK);
    d.reproject.history_filter = (sbl_history_filter)2;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_INVALID_PARAM);
    CHECK_EQ(sbl_reproject_temporal(&d.reproject, SBL_TEMPORAL_MOTION, &f, &hi, o.color, o.length, 0, H),
             SBL_ERROR_INVALID_PARAM);
    CHECK_EQ(sbl_temporal_validate(&d, &f, &hi, &o, &diag), SBL_ERROR_INVALID_PARAM);
    CHECK(strcmp(diag.field, "desc->reproject.history_filter") == 0);
    d.reproject.history_filter = (sbl_history_filter)-1;
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_INVALID_PARAM);
    {   /* stereo: the valid values accepted and read as bilinear, an unknown one refused */
        static float out2[W * H * 3], outn2[W * H];
        sbl_stereo_desc sd;
        sbl_eye eye[2];
        int same = 1;
        memset(&sd, 0, sizeof sd);
        memset(eye, 0, sizeof eye);
        sd.rig = SBL_RIG_PARALLEL; sd.focal_px = 100.0f; sd.baseline = 0.0037f; /* 0.37 px */
        for (k = 0; k < W * H * 3; ++k) col[k] = (float)((k * 7919) % 101) / 101.0f;
        for (k = 0; k < 2; ++k) {
            eye[k].color = sbl_image_make(col, W, H, 3);
            eye[k].gbuffer.depth = f.gbuffer.depth;
        }
        CHECK_EQ(sbl_reproject_stereo(&sd, SBL_EYE_LEFT, &eye[0], &eye[1], o.color, o.length, 0, H), SBL_OK);
        sd.reproject.history_filter = SBL_HISTORY_CATMULL_ROM;
        CHECK_EQ(sbl_reproject_stereo(&sd, SBL_EYE_LEFT, &eye[0], &eye[1], sbl_image_make(out2, W, H, 3),
                                      sbl_image_make(outn2, W, H, 1), 0, H), SBL_OK);
        for (k = 0; k < W * H * 3; ++k) same &= out[k] == out2[k];
        CHECK_EQ(same, 1);
        sd.reproject.history_filter = (sbl_history_filter)5;
        CHECK_EQ(sbl_reproject_stereo(&sd, SBL_EYE_LEFT, &eye[0], &eye[1], o.color, o.length, 0, H),
                 SBL_ERROR_INVALID_PARAM);
    }
}

/* ---- evidence carried over frames (pooled, docs/ESTIMATORS.md 3.7) --------------- */

static float seq_ev(seq1 *s, int x, int y) { return s->ev[s->ping][(size_t)y * s->w + x]; }

/* the header's SBL_EVIDENCE_LAMBDA and c_R (EV_THR), as documented: this file
   may be built against the library's object, without the implementation's macros */
#define EV_LAMBDA (1.0 / 3.0)
#define EV_THR (1.0 + 2.5 * sqrt(EV_LAMBDA / (2.0 - EV_LAMBDA)))

static void fill_flat(seq1 *s, sbt_rng *rng, double mu, double sigma)
{
    size_t i, n = (size_t)s->w * (size_t)s->h * (size_t)s->ch;
    for (i = 0; i < n; ++i) s->cur[i] = (float)(mu + sigma * sbt_gauss(rng));
}

/* Without the history's plane the estimator is today's, bit for bit (the output plane
   may be written or not): a moving edge with noise, 16 frames, in lockstep. */
static void test_evidence_absent(void)
{
    const int w = 40, h = 12;
    seq1 a, b;
    sbl_temporal_desc d;
    sbt_rng rng = {5};
    int i, x, y, same = 1;
    memset(&d, 0, sizeof d);
    seq_init(&a, w, h, 3);
    seq_init(&b, w, h, 3);
    for (i = 0; i < 16; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                int c;
                for (c = 0; c < 3; ++c)
                    a.cur[((size_t)y * w + x) * 3 + c] = b.cur[((size_t)y * w + x) * 3 + c] =
                        (float)((x < 8 + i ? 0.8 : 0.2) + 0.1 * sbt_gauss(&rng));
            }
        g_evidence = 0;
        CHECK_EQ(seq_step(&a, &d, i == 0), SBL_OK);
        g_evidence = 2;
        CHECK_EQ(seq_step(&b, &d, i == 0), SBL_OK);
        same &= memcmp(a.hist[a.ping], b.hist[b.ping], sizeof(float) * (size_t)w * h * 3) == 0;
        same &= memcmp(a.len[a.ping], b.len[b.ping], sizeof(float) * (size_t)w * h) == 0;
    }
    g_evidence = 0;
    CHECK(same);
    seq_free(&a);
    seq_free(&b);
}

/* Static content: the carried ratio sits near its no-change mean 1 (few pixels beyond
   c_R), and after a spurious value of 20 it decays back geometrically, by (1 - lambda)
   per frame, without anything else to go on. */
static void test_evidence_static(void)
{
    const int warm = 30, after = 12;
    const double thr = EV_THR, lam = EV_LAMBDA;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {31};
    double excess[12], over_before = 0, over_end = 0;
    int i, x, y, k;
    memset(&d, 0, sizeof d);
    seq_init(&s, TW, TH, 3);
    g_evidence = 1;
    for (i = 0; i < warm + after; ++i) {
        fill_flat(&s, &rng, 0.5, 0.1);
        if (i == warm)
            for (k = 0; k < TW * TH; ++k) s.ev[s.ping][k] = 20.0f;
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i == warm - 1 || i == warm + after - 1) {
            double over = 0;
            for (y = 0; y < TH; ++y)
                for (x = 0; x < TW; ++x) over += seq_ev(&s, x, y) > thr;
            if (i == warm - 1) over_before = over / (TW * TH);
            else over_end = over / (TW * TH);
        }
        if (i >= warm) {
            double m = 0;
            for (y = 0; y < TH; ++y)
                for (x = 0; x < TW; ++x) m += seq_ev(&s, x, y);
            excess[i - warm] = m / (TW * TH) - 1.0;
        }
    }
    g_evidence = 0;
    printf("  evidence on static content (0.5 +- 0.1): beyond c_R = %.3f: %.2f %% of pixels; after a "
           "spurious 20: mean R - 1 = %.2f, %.2f, %.2f, %.3f after 1, 2, 5, 12 frames (19 (1 - lambda)^k: "
           "%.2f, %.2f, %.2f, %.3f), %.2f %% beyond c_R at the end\n",
           thr, 100 * over_before, excess[0], excess[1], excess[4], excess[11], 19 * (1 - lam),
           19 * pow(1 - lam, 2), 19 * pow(1 - lam, 5), 19 * pow(1 - lam, 12), 100 * over_end);
    CHECK(over_before < 0.02);
    for (k = 0; k < 5; ++k) CHECK(fabs(excess[k] / (19 * pow(1 - lam, k + 1)) - 1) < 0.1);
    CHECK(fabs(excess[11]) < 0.3);
    CHECK(over_end < 0.02);
    seq_free(&s);
}

/* A noise-free jump (0.2 -> 0.8: the blocks see a change with zero noise, q at its cap)
   on content that then stays exactly still, and noise only from frame 20: the carried
   ratio must not hold the jump (found in review: it stayed near 3e5 and reset the
   history for ~30 frames after the noise began, RMSE 3.5x that without the plane). */
static double noise_free_jump_rmse(int evidence, double *r_peak)
{
    const int w = 48, h = 16, frames = 36;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {17};
    double se = 0;
    int i, k, x, y, n = 0;
    const int np = w * h * 3;
    memset(&d, 0, sizeof d);
    g_evidence = evidence;
    seq_init(&s, w, h, 3);
    *r_peak = 0;
    for (i = 0; i < frames; ++i) {
        fill_flat(&s, &rng, i < 5 ? 0.2 : 0.8, i < 20 ? 0.0 : 0.05);
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (evidence && i >= 5)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x)
                    if (seq_ev(&s, x, y) > *r_peak) *r_peak = seq_ev(&s, x, y);
        if (i >= 24) {
            for (k = 0; k < np; ++k) se += (s.hist[s.ping][k] - 0.8) * (s.hist[s.ping][k] - 0.8);
            ++n;
        }
    }
    g_evidence = 0;
    seq_free(&s);
    return sqrt(se / ((double)n * np));
}

static void test_evidence_noise_free_jump(void)
{
    double peak, unused;
    const double with = noise_free_jump_rmse(1, &peak), without = noise_free_jump_rmse(0, &unused);
    printf("  evidence after a noise-free jump, then still, then noise from frame 20: RMSE over "
           "frames 24..35 %.4f with the plane, %.4f without; largest R %.3f\n", with, without, peak);
    CHECK(with <= 1.2 * without);
    /* one frame raises R by at most c - 1 = 1.5, c = 2.5 the blocks' threshold with the
       plane (SBL_POOLED_BLOCK_SE2_REGION, an implementation macro this file cannot see) */
    CHECK(peak <= 1.0 + 1.5 + 1e-4);
}

/* A flat region whose brightness rises by `step` every frame (a light that changes
   every frame by much less than the noise): the mean lag of the filter's output behind
   the true value, in frames, over frames 40..79. */
static double brightness_ramp_lag(int evidence, double step, double noise, double *rmse)
{
    const int w = 64, h = 16, frames = 80;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {99};
    double lag = 0, se = 0;
    int i, k, n = 0;
    const int np = w * h * 3;
    memset(&d, 0, sizeof d);
    g_evidence = evidence;
    seq_init(&s, w, h, 3);
    for (i = 0; i < frames; ++i) {
        const double v = 0.3 + step * i;
        fill_flat(&s, &rng, v, noise);
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i >= 40) {
            double m = 0;
            for (k = 0; k < np; ++k) {
                double o = s.hist[s.ping][k];
                m += o;
                se += (o - v) * (o - v);
            }
            lag += (v - m / np) / step;
            ++n;
        }
    }
    g_evidence = 0;
    seq_free(&s);
    *rmse = sqrt(se / ((double)n * np));
    return lag / n;
}

static void test_evidence_ramp(void)
{
    static const double cases[3][2] = {{0.002, 0.1}, {0.005, 0.1}, {0.02, 0.3}};
    int k;
    for (k = 0; k < 3; ++k) {
        double r0, r1;
        double lag0 = brightness_ramp_lag(0, cases[k][0], cases[k][1], &r0);
        double lag1 = brightness_ramp_lag(1, cases[k][0], cases[k][1], &r1);
        printf("  brightness ramp (%.3f per frame, noise %.1f): lag in frames pooled %.2f (RMSE %.4f), "
               "with the evidence plane %.2f (RMSE %.4f)\n", cases[k][0], cases[k][1], lag0, r0, lag1, r1);
        /* bounded: at most 0.9 of the one-frame estimator's lag (measured 0.80-0.81 with
           the garrote, the default; 0.83-0.86 with SBL_EVIDENCE_GATE 0, 0.69-0.72 with 1) */
        CHECK(lag1 <= 0.9 * lag0);
        CHECK(r1 <= r0 * 1.02);
    }
}

/* The carried evidence through the garrote (docs/ESTIMATORS.md 3.8): beyond c_R the
   history is let go by (R - 1) - (c_R - 1)^2 / (R - 1), which tends to the unbiased
   R - 1, instead of R - c_R, which stays c_R - 1 = 1.1 short of it. On a brightness ramp
   and on a light edge that moves every frame the lag is then a smaller fraction of the
   one-frame estimator's (measured 0.80-0.81 on the ramps and 0.76 on the edge, against
   0.83-0.86 and 0.92 with R - c_R: this test fails on the code before), and static
   content is left alone (test_evidence_static: no pixel beyond c_R). */
static void test_evidence_garrote(void)
{
    static const double ramps[3][2] = {{0.002, 0.1}, {0.005, 0.1}, {0.02, 0.3}};
    double r0, r1, lag0, lag1;
    int k;
    for (k = 0; k < 3; ++k) {
        lag0 = brightness_ramp_lag(0, ramps[k][0], ramps[k][1], &r0);
        lag1 = brightness_ramp_lag(1, ramps[k][0], ramps[k][1], &r1);
        printf("  garrote, brightness ramp (%.3f per frame, noise %.1f): lag %.2f of the one-frame "
               "estimator's (RMSE %.4f against %.4f)\n", ramps[k][0], ramps[k][1], lag1 / lag0, r1, r0);
        CHECK(lag1 <= 0.82 * lag0);
        CHECK(r1 <= r0 * 0.92);
    }
    lag0 = moving_light_lag(SBL_ESTIMATOR_POOLED, 0.5, 16.0, 0.3, &r0);
    g_evidence = 1;
    lag1 = moving_light_lag(SBL_ESTIMATOR_POOLED, 0.5, 16.0, 0.3, &r1);
    g_evidence = 0;
    printf("  garrote, light edge (0.5 px/frame, ramp 16 px, noise 0.3): lag %.2f -> %.2f frames "
           "(RMSE %.4f -> %.4f)\n", lag0, lag1, r0, r1);
    CHECK(lag1 <= 0.85 * lag0);
    CHECK(r1 <= r0);
}

/* A firefly in a converged history with the plane carried: its blocks' ratio stays near
   1 (a firefly adds about as much to a block's squared mean as to its squared standard
   error), so the carried evidence does not take it for a change. */
static void test_evidence_firefly(void)
{
    const double mu = 0.5, sigma = 0.1, fire = 500.0;
    const int px = TW / 2, py = TH / 2, warm = 40;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {2024};
    double err_after = 0, err_decay, n_before = 0, n_after = 0, r_max = 0, r_before = 0;
    int i, x, y, c;
    memset(&d, 0, sizeof d);
    seq_init(&s, TW, TH, 3);
    g_evidence = 1;
    for (i = 0; i < warm + 11; ++i) {
        fill_flat(&s, &rng, mu, sigma);
        if (i == warm)
            for (c = 0; c < 3; ++c) s.cur[((size_t)py * TW + px) * 3 + c] = (float)fire;
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i == warm - 1 || i == warm) {
            double m = 0;
            for (y = py - 2; y <= py + 2; ++y)
                for (x = px - 8; x <= px + 8; ++x)
                    if (seq_ev(&s, x, y) > m) m = seq_ev(&s, x, y);
            if (i == warm - 1) { r_before = m; n_before = seq_n(&s, px, py); }
            else { r_max = m; n_after = seq_n(&s, px, py); err_after = fabs(seq_out(&s, px, py)[0] - mu); }
        }
    }
    err_decay = fabs(seq_out(&s, px, py)[0] - mu);
    g_evidence = 0;
    printf("  firefly with the evidence plane: max R within 8 px %.3f -> %.3f (c_R %.3f), error %.4f -> "
           "%.4f 10 frames later, N %.1f -> %.1f\n", r_before, r_max, EV_THR, err_after,
           err_decay, n_before, n_after);
    CHECK(r_max < EV_THR);
    CHECK(err_after < 0.1);
    CHECK(n_after > 0.5 * n_before);
    CHECK(err_decay < 0.05);
    seq_free(&s);
}

/* The planes are validated like the other optional views. */
static void test_evidence_params(void)
{
    const int w = 20, h = 6;
    seq1 s;
    sbl_temporal_desc d;
    sbl_frame f;
    sbl_history hi;
    sbl_temporal_output o;
    static float ev2[20 * 6 * 2], ev_small[19 * 6];
    memset(&d, 0, sizeof d);
    seq_init(&s, w, h, 3);
    memset(&f, 0, sizeof f); memset(&hi, 0, sizeof hi); memset(&o, 0, sizeof o);
    f.color = sbl_image_make(s.cur, w, h, 3);
    f.gbuffer.depth = sbl_image_make(s.depth, w, h, 1);
    f.gbuffer.motion = sbl_image_make(s.mv, w, h, 2);
    hi.color = sbl_image_make(s.hist[0], w, h, 3);
    hi.length = sbl_image_make(s.len[0], w, h, 1);
    hi.gbuffer.depth = f.gbuffer.depth;
    o.color = sbl_image_make(s.hist[1], w, h, 3);
    o.length = sbl_image_make(s.len[1], w, h, 1);
    hi.evidence = sbl_image_make(s.ev[0], w, h, 1);
    o.evidence = sbl_image_make(s.ev[1], w, h, 1);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_OK);
    o.evidence = sbl_image_make(ev2, w, h, 2);
    CHECK(sbl_temporal_filter_frame(&d, &f, &hi, &o) != SBL_OK);
    o.evidence = sbl_image_make(ev_small, w - 1, h, 1);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_SIZE_MISMATCH);
    o.evidence = sbl_image_make(s.ev[1], w, h, 1);
    hi.evidence = sbl_image_make(ev_small, w - 1, h, 1);
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_SIZE_MISMATCH);
    hi.evidence = sbl_image_make(s.ev[1], w, h, 1); /* reads what it writes */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_OVERLAP);
    hi.evidence = sbl_image_make(s.ev[0], w, h, 1);
    o.evidence = sbl_image_make(s.len[1], w, h, 1); /* the same buffer as out.length */
    CHECK_EQ(sbl_temporal_filter_frame(&d, &f, &hi, &o), SBL_ERROR_OVERLAP);
    seq_free(&s);
}

/* ---- the combined pipeline: a bias both eyes share (docs/ESTIMATORS.md 4.7) ------- */

/* Two eyes of one flat region (parallel rig, depth 1, disparity 2 px: matches at pixel
   centres), independent noise, brightness rising by `rate` per frame from frame 20 on
   (a light both eyes see); each eye filtered by the default temporal filter with the
   evidence plane, then the default stereo blend for display. RMSE of the display over
   frames [24, 60) and columns [4, w - 4), against the truth. */
static double shared_bias_run(float c, double rate, double sigma)
{
    enum { W = 40, H = 16, F = 60 };
    static float disp[2][W * H * 3];
    seq1 s[2];
    sbl_temporal_desc d;
    sbl_stereo_desc sd;
    sbt_rng rng = {77};
    double se = 0.0;
    long cnt = 0;
    int f, e, x, y, k;
    memset(&d, 0, sizeof d);
    d.stereo_shared_bias = c;
    memset(&sd, 0, sizeof sd);
    sd.rig = SBL_RIG_PARALLEL;
    sd.focal_px = 2.0f;
    sd.baseline = 1.0f;
    seq_init(&s[0], W, H, 3);
    seq_init(&s[1], W, H, 3);
    g_evidence = 1;
    for (f = 0; f < F; ++f) {
        double mu = 0.3 + (f > 20 ? rate * (f - 20) : 0.0);
        sbl_eye eye[2];
        for (e = 0; e < 2; ++e) {
            for (k = 0; k < W * H * 3; ++k) s[e].cur[k] = (float)(mu + sigma * sbt_gauss(&rng));
            CHECK_EQ(seq_step(&s[e], &d, f == 0), SBL_OK);
            memset(&eye[e], 0, sizeof eye[e]);
            eye[e].color = sbl_image_make(s[e].hist[s[e].ping], W, H, 3);
            eye[e].length = sbl_image_make(s[e].len[s[e].ping], W, H, 1);
            eye[e].gbuffer.depth = sbl_image_make(s[e].depth, W, H, 1);
        }
        CHECK_EQ(sbl_stereo_blend_frame(&sd, &eye[0], &eye[1], sbl_image_make(disp[0], W, H, 3),
                                        sbl_image_make(disp[1], W, H, 3)), SBL_OK);
        if (f < 24) continue;
        for (e = 0; e < 2; ++e)
            for (y = 0; y < H; ++y)
                for (x = 4; x < W - 4; ++x)
                    for (k = 0; k < 3; ++k) {
                        double dv = disp[e][(y * W + x) * 3 + k] - mu;
                        se += dv * dv;
                        ++cnt;
                    }
    }
    g_evidence = 0;
    seq_free(&s[0]);
    seq_free(&s[1]);
    return sqrt(se / (double)cnt);
}

static void test_stereo_shared_bias(void)
{
    if (getenv("SB_SCAN")) {
        static const double rates[] = {0.001, 0.002, 0.004, 0.01, 0.02, 0.05};
        static const double sig[] = {0.05, 0.1, 0.3};
        int i, j;
        for (j = 0; j < 3; ++j)
            for (i = 0; i < 6; ++i)
                printf("rate %.3f sigma %.2f: c0 %.4f c0.5 %.4f c1 %.4f\n", rates[i], sig[j],
                       shared_bias_run(0.0f, rates[i], sig[j]), shared_bias_run(0.5f, rates[i], sig[j]),
                       shared_bias_run(1.0f, rates[i], sig[j]));
    }
    double ramp0 = shared_bias_run(0.0f, 0.05, 0.1), ramp1 = shared_bias_run(1.0f, 0.05, 0.1);
    double mid0 = shared_bias_run(0.0f, 0.01, 0.1), mid1 = shared_bias_run(1.0f, 0.01, 0.1);
    double flat0 = shared_bias_run(0.0f, 0.0, 0.1), flat1 = shared_bias_run(1.0f, 0.0, 0.1);
    printf("  combined pipeline, a light both eyes see rising 0.05 / 0.01 / 0 per frame (noise 0.1): "
           "display RMSE %.4f / %.4f / %.4f with stereo_shared_bias 0, %.4f / %.4f / %.4f with 1 "
           "(SB_SCAN=1 for more rates)\n", ramp0, mid0, flat0, ramp1, mid1, flat1);
    /* the shared lag is what the stereo blend cannot remove: weighting it double
       follows the light: 0.0547 with c = 1 (0.0559 before the mix towards the paper's
       weight, docs/ESTIMATORS.md 3.11). Since 3.12's share floor (SBL_EVIDENCE_MIX 2,
       the temporal filter alone only) the c = 0 filter follows a change that covers the
       region by itself (0.0544), so c = 1 is no longer below it here; the combined
       pipeline keeps c = 1 with the floor off, which the bench prefers on four of six
       scenes (docs/RESULTS.md, session 16). Bounds from the figures at
       SBL_EVIDENCE_MIX 1, where c = 0 gave 0.0551 / 0.0420: */
    CHECK(ramp1 < 0.0551);
    /* the mix's own gain on the ramp (0.0595 without it: fails with SBL_EVIDENCE_MIX 0) */
    CHECK(ramp0 < 0.0575);
    /* the share floor's gain at c = 0 on a change near the detection threshold: 0.0381
       with it, 0.0420 without (fails with SBL_EVIDENCE_MIX 1) */
    CHECK(mid0 < 0.0400);
    /* c = 1 at that change: its bias estimate is mostly noise, counted double (4.7):
       0.0435, within 1.08 x the c = 0 figure without the floor (0.0420) */
    CHECK(mid1 <= 0.0420 * 1.08);
    /* and where nothing changes the false alarms cost little */
    CHECK(flat1 <= flat0 * 1.03);
    {   /* validated: [0, 1], finite */
        sbl_temporal_desc d;
        seq1 s;
        memset(&d, 0, sizeof d);
        seq_init(&s, 12, 6, 3);
        d.stereo_shared_bias = 1.5f;
        CHECK_EQ(seq_step(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
        d.stereo_shared_bias = -0.25f;
        CHECK_EQ(seq_step(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
        d.stereo_shared_bias = (float)HUGE_VAL - (float)HUGE_VAL;
        CHECK_EQ(seq_step(&s, &d, 1), SBL_ERROR_INVALID_PARAM);
        d.stereo_shared_bias = 1.0f;
        CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
        d.stereo_shared_bias = SBL_SHARED_BIAS_NONE; /* per-eye weights, as 0 here */
        CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
        seq_free(&s);
    }
}

/* The region's prior probability of change (docs/ESTIMATORS.md 3.10): on static,
   textured content under heavy-tailed noise almost no pixel of a row's neighbourhood
   carries evidence beyond c_R, so the local test and the one-frame blocks ask for more
   (prior odds times M = 1 / (2 s), s the rows' share of change) and their false alarms,
   which cost the static scene 2-3 % each, become rare. Measured (frames 8-31, MSE over
   progressive averaging's): 0.950 with the plane (the firefly limit takes part of the
   tail), 1.102 without it; 1.103 with the plane on the code before, where this test
   fails. A change over the whole region is still followed at once (test_evidence_ramp,
   test_moving_light, test_evidence_garrote). */
static double region_static_mse(sbl_estimator e, int plane)
{
    const int w = 96, h = 48, frames = 32;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {4242};
    double se = 0;
    long n = 0;
    int i, x, y, c;
    memset(&d, 0, sizeof d);
    d.estimator = e;
    seq_init(&s, w, h, 3);
    g_evidence = plane;
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                {   /* one path per sample drives all three channels: an exponential
                       (mean 1, spread 1) factor, as a 1-spp estimate's heavy right tail */
                    double u = sbt_uniform(&rng), f = -log(u > 1e-12 ? u : 1e-12);
                    for (c = 0; c < 3; ++c) {
                        double t = 0.4 + 0.2 * sin(0.7 * x + 0.3 * c) * cos(0.45 * y) + 0.002 * x;
                        s.cur[((size_t)y * w + x) * 3 + c] = (float)(t * f);
                    }
                }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i >= 8)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x)
                    for (c = 0; c < 3; ++c) {
                        double t = 0.4 + 0.2 * sin(0.7 * x + 0.3 * c) * cos(0.45 * y) + 0.002 * x;
                        double e2 = seq_out(&s, x, y)[c] - t;
                        se += e2 * e2;
                        ++n;
                    }
    }
    g_evidence = 0;
    seq_free(&s);
    return se / (double)n;
}

static void test_evidence_region(void)
{
    const double prog = region_static_mse(SBL_ESTIMATOR_PROGRESSIVE, 0);
    const double def = region_static_mse(SBL_ESTIMATOR_POOLED, 1);
    const double one = region_static_mse(SBL_ESTIMATOR_POOLED, 0);
    printf("  region prior, static texture, exponential 1-spp noise (96x48, frames 8-31): MSE / "
           "progressive's: default with the plane %.4f, without it (one frame's evidence) %.4f\n",
           def / prog, one / prog);
    CHECK(def <= prog * 1.04);
    CHECK(def <= one * 0.95);
}

/* A light sliding over a texture (docs/ESTIMATORS.md 3.11): every pixel's shading changes
   every frame, by a wave of period 48 px moving 0.5 or 1 px per frame, under Gaussian
   noise (sigma 0.3 of the value). With the plane carried, the weight moves towards the
   paper's by the carried evidence's own shrink where that one is the larger: the paper's
   weight follows the change at once, and R, which has seen it for frames, lets it in.
   MSE with the plane / without it (one frame's evidence), 0.5 / 1 px per frame: measured
   0.80 / 0.78 with the mix, 0.88 / 0.88 without it (this test fails on the code before). The static texture
   of test_evidence_region and the light edge of test_evidence_garrote keep their bounds
   (measured 0.943 of progressive's MSE; the edge lags 2.47 frames). */
static double sliding_light_truth(int x, int y, int c, double v, int i)
{
    const double light = 0.6 + 0.4 * sin(6.283185307179586 * (x - v * i) / 48.0);
    return (0.4 + 0.2 * sin(0.7 * x + 0.3 * c) * cos(0.45 * y)) * light;
}

static double sliding_light_mse(int plane, double v)
{
    const int w = 96, h = 48, frames = 48;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {4711};
    double se = 0;
    long n = 0;
    int i, x, y, c;
    memset(&d, 0, sizeof d);
    d.estimator = SBL_ESTIMATOR_POOLED;
    seq_init(&s, w, h, 3);
    g_evidence = plane;
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const double f = 1.0 + 0.3 * sbt_gauss(&rng);
                for (c = 0; c < 3; ++c)
                    s.cur[((size_t)y * w + x) * 3 + c] = (float)(sliding_light_truth(x, y, c, v, i) * f);
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i >= 16)
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x)
                    for (c = 0; c < 3; ++c) {
                        const double e2 = seq_out(&s, x, y)[c] - sliding_light_truth(x, y, c, v, i);
                        se += e2 * e2;
                        ++n;
                    }
    }
    g_evidence = 0;
    seq_free(&s);
    return se / (double)n;
}

static void test_evidence_mix(void)
{
    static const double speeds[2] = {0.5, 1.0};
    int k;
    for (k = 0; k < 2; ++k) {
        const double one = sliding_light_mse(0, speeds[k]), plane = sliding_light_mse(1, speeds[k]);
        printf("  sliding light (%.1f px/frame, noise 0.3): MSE %.5f with the plane, %.5f without "
               "(%.3f)\n", speeds[k], plane, one, plane / one);
        CHECK(plane <= 0.84 * one);
    }
}

/* ---- the resampling blur's bias behind a stereo blend (docs/ESTIMATORS.md 4.12) ----
   A textured pattern (period 6 px) panned by 0.37 / 0.23 px per frame, noise 0.05 per
   sample, through the default temporal filter with the evidence plane and
   stereo_shared_bias c: the contrast the history keeps (least-squares amplitude of the
   true pattern in the output, as moving_pattern_contrast) over frames 24-39, and the
   RMSE against it. mv: the motion per frame (0: a fixed camera). out: if not NULL, the
   last frame's output (w * h * 3 floats). */
static double blur_pan_run_w(int w, float c, sbl_history_filter filter, double vx, double vy,
                             double period, double sigma, double *rmse, float *out)
{
    const int h = 32, frames = 40, x0 = w >= 32 ? 16 : 2;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {777};
    double num = 0.0, den = 0.0, se = 0.0;
    long cnt = 0;
    int i, x, y, k;
    memset(&d, 0, sizeof d);
    d.stereo_shared_bias = c;
    d.reproject.history_filter = filter;
    seq_init(&s, w, h, 3);
    g_evidence = 1;
    for (i = 0; i < w * h; ++i) {
        s.mv[2 * i] = (float)-vx; /* backward: the history is at x - v */
        s.mv[2 * i + 1] = (float)-vy;
    }
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x)
                for (k = 0; k < 3; ++k) {
                    double u = x + 0.5 - vx * i, v = y + 0.5 - vy * i;
                    double t = 0.5 + 0.3 * sin(6.283185307179586 * u / period) *
                                         cos(6.283185307179586 * v / (2 * period)) + 0.05 * k;
                    s.cur[((size_t)y * w + x) * 3 + k] = (float)(t + sigma * sbt_gauss(&rng));
                }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i < 24) continue;
        for (y = 8; y < h - 2; ++y)
            for (x = x0; x < w - 2; ++x)
                for (k = 0; k < 3; ++k) {
                    double u = x + 0.5 - vx * i, v = y + 0.5 - vy * i;
                    double t = 0.3 * sin(6.283185307179586 * u / period) *
                               cos(6.283185307179586 * v / (2 * period));
                    double o = seq_out(&s, x, y)[k] - 0.5 - 0.05 * k;
                    num += o * t; den += t * t; se += (o - t) * (o - t); ++cnt;
                }
    }
    if (out) memcpy(out, s.hist[s.ping], (size_t)w * h * 3 * sizeof(float));
    g_evidence = 0;
    seq_free(&s);
    *rmse = sqrt(se / (double)cnt);
    return num / den;
}
/* 64 pixels wide (the lanes, inside); 16 wide: every pixel on the double reference path */
static double blur_pan_run(float c, sbl_history_filter filter, double vx, double vy,
                           double period, double sigma, double *rmse, float *out)
{
    return blur_pan_run_w(64, c, filter, vx, vy, period, sigma, rmse, out);
}

static void test_blur_bias(void)
{
    static float a[64 * 32 * 3], b[64 * 32 * 3];
    double r0, r1, c0 = blur_pan_run(0.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, 6.0, 0.05, &r0, NULL);
    double c1 = blur_pan_run(1.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, 6.0, 0.05, &r1, NULL);
    int i, same = 1;
    printf("  panned pattern (0.37 / 0.23 px per frame, noise 0.05), default temporal filter: "
           "contrast kept %.3f with stereo_shared_bias 0, %.3f with 1; RMSE %.4f, %.4f\n", c0, c1, r0, r1);
    /* the blur both eyes share is weighed as a bias: a shorter memory where the fetch
       blurs, more contrast kept. Measured 0.913 (RMSE 0.0284) against 0.845 (0.0312) on
       the code before the term (7669060), where both checks fail; c = 0 is unchanged
       (0.801, 0.0350 on both; 0.774, 0.0374 since the restart lean). Since the restart
       lean behind a stereo blend (6.10): 0.895, 0.0285; with its texture counted once,
       not 1 + c times, 0.874 (fails) */
    CHECK(c1 > 0.88);
    CHECK(r1 < 0.0298);
    CHECK(c1 > c0);
    /* a fixed camera and an integer pan: every fetch at an integer position, so the
       blur's term is 0 and c = 1's output is bit for bit what it was without it; the
       Catmull-Rom fetch (which equals bilinear at integer positions, and takes no blur
       term) gives those bits */
    for (i = 0; i < 2; ++i) {
        const double mv = i ? 1.0 : 0.0;
        int j;
        blur_pan_run(1.0f, SBL_HISTORY_BILINEAR, mv, 0.0, 6.0, 0.05, &r0, a);
        blur_pan_run(1.0f, SBL_HISTORY_CATMULL_ROM, mv, 0.0, 6.0, 0.05, &r1, b);
        for (j = 0; j < 64 * 32 * 3; ++j) same &= a[j] == b[j];
    }
    CHECK_EQ(same, 1);
    /* a finer pattern (period 4 px, noise 0.02), where the blur's term drops most of the
       history: the restart lean behind a stereo blend must not take that for a change
       (its gate reads the weight without the blur's term, 6.10). Measured: contrast
       0.914, RMSE 0.0191 (the code before the lean behind a stereo blend: the same);
       with the gate on the whole weight 0.859, 0.0248, where both checks fail */
    c1 = blur_pan_run(1.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, 4.0, 0.02, &r1, NULL);
    printf("  panned pattern, period 4 px, noise 0.02, stereo_shared_bias 1: contrast kept %.3f, RMSE %.4f\n", c1, r1);
    CHECK(c1 > 0.89);
    CHECK(r1 < 0.022);
    /* the same 16 pixels wide: the reference path's gate and texture factor */
    c1 = blur_pan_run_w(16, 1.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, 4.0, 0.02, &r1, NULL);
    printf("  the same 16 wide (the reference path): contrast kept %.3f, RMSE %.4f\n", c1, r1);
    c0 = blur_pan_run_w(16, 1.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, 6.0, 0.05, &r0, NULL);
    printf("  period 6, noise 0.05, 16 wide: contrast kept %.3f, RMSE %.4f\n", c0, r0);
    /* measured 0.907 / 0.0208 and 0.894; the reference's gate on the whole weight
       0.833 / 0.0299, its texture counted once 0.873 at period 6: each fails one */
    CHECK(c1 > 0.88);
    CHECK(r1 < 0.024);
    CHECK(c0 > 0.88);
    /* SB_PAN_SCAN=1: the contrast and RMSE at c = 0 / 1 over periods and noise levels */
    if (getenv("SB_PAN_SCAN")) {
        static const double per[3] = {3.0, 4.0, 6.0}, sg[3] = {0.01, 0.02, 0.05};
        int a1, b1;
        for (a1 = 0; a1 < 3; ++a1)
            for (b1 = 0; b1 < 3; ++b1) {
                double e0, e1, k0 = blur_pan_run(0.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, per[a1], sg[b1], &e0, NULL);
                double k1 = blur_pan_run(1.0f, SBL_HISTORY_BILINEAR, 0.37, 0.23, per[a1], sg[b1], &e1, NULL);
                printf("  scan period %.0f sigma %.2f: contrast %.3f / %.3f, RMSE %.4f / %.4f\n", per[a1], sg[b1], k0, k1, e0, e1);
            }
    }
}

/* The combined pipeline's share floor (docs/ESTIMATORS.md 4.14): with stereo_shared_bias
   c = 1 the mix towards the paper's weight does not go below the region's share of change
   net of the carried R's false alarms, (s - q0) / (1 - q0). On a light both eyes see,
   rising near the detection threshold (0.01 per frame, noise 0.1), the floor lets the
   paper's weight in where most of the region changes: display RMSE 0.0384 / 0.0328 at a
   rise of 0.01 / 0.004 per frame, 0.0435 / 0.0384 without the floor at c = 1 (the code
   before, where this test fails). On flat, unchanging content the share is within its
   false alarms and the floor is 0: 0.0112 with and without it. */
static void test_shared_bias_floor(void)
{
    double mid1 = shared_bias_run(1.0f, 0.01, 0.1), slow1 = shared_bias_run(1.0f, 0.004, 0.1);
    double flat1 = shared_bias_run(1.0f, 0.0, 0.1);
    printf("  combined pipeline (c = 1), a light rising 0.01 / 0.004 / 0 per frame (noise 0.1): "
           "display RMSE %.4f / %.4f / %.4f\n", mid1, slow1, flat1);
    CHECK(mid1 < 0.0410);  /* halfway between 0.0384 and 0.0435 */
    CHECK(slow1 < 0.0356); /* halfway between 0.0328 and 0.0384 */
    CHECK(flat1 < 0.0113); /* 0.0112 before and after */
}

/* ---- hit-or-miss samples: the tail plane keeps the mean --------------------------- */

/* A static region whose 1-spp samples are mu / p with probability p = 0.1 and 0
   otherwise (a small light sampled once per pixel: docs/ESTIMATORS.md 2.3, 2.4;
   bench/sparse_bias.c). Without the tail plane the default loses about half the mean
   (the limit cuts lone hits; a window of misses reads a history above it as a bias).
   With the plane (g_tail) it must stay within a third of the plain mean's error budget:
   |bias| < 30 % and RMSE below the plain mean of every sample so far (progressive
   averaging, unbiased). Behind a stereo blend (stereo_shared_bias c = 1) the limit
   admits more of the hits (6.9): less of the mean is lost. Returns the bias and fills
   the RMSEs. */
static double hits_run(int tail, float shared, int w, double *rmse, double *rmse_mean)
{
    const int h = 48, frames = 60, from = 20;
    const double p = 0.1, mu = 0.5;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {4242};
    double *mean = (double *)calloc((size_t)w * h, sizeof(double));
    double se = 0.0, se_mean = 0.0, bias = 0.0;
    long cnt = 0;
    int i, x, y;
    memset(&d, 0, sizeof d);
    d.stereo_shared_bias = shared;
    seq_init(&s, w, h, 1);
    g_evidence = 1;
    g_tail = tail;
    for (i = 0; i < frames; ++i) {
        for (y = 0; y < h; ++y)
            for (x = 0; x < w; ++x) {
                const size_t q = (size_t)y * w + x;
                const double v = sbt_uniform(&rng) < p ? mu / p : 0.0;
                s.cur[q] = (float)v;
                mean[q] += (v - mean[q]) / (i + 1);
            }
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
        if (i < from) continue;
        for (y = 1; y < h - 1; ++y)
            for (x = 1; x < w - 1; ++x) {
                const size_t q = (size_t)y * w + x;
                const double a = seq_out(&s, x, y)[0] - mu;
                bias += a;
                se += a * a;
                se_mean += (mean[q] - mu) * (mean[q] - mu);
                cnt++;
            }
    }
    g_evidence = g_tail = 0;
    *rmse = sqrt(se / cnt);
    *rmse_mean = sqrt(se_mean / cnt);
    free(mean);
    seq_free(&s);
    return bias / cnt / mu;
}

static void test_tail_hits(void)
{
    double r_on, r_off, m_on, m_off, r_st, m_st, r_n0, r_n1, m_n;
    const double b_on = hits_run(1, 0.0f, 64, &r_on, &m_on), b_off = hits_run(0, 0.0f, 64, &r_off, &m_off);
    const double b_st = hits_run(1, 1.0f, 64, &r_st, &m_st);
    /* 16 pixels wide: every pixel takes the double reference path (sbl__firefly_limit),
       the 64-wide runs above the lanes (sbl__lanes_firefly_t) */
    const double b_n0 = hits_run(1, 0.0f, 16, &r_n0, &m_n), b_n1 = hits_run(1, 1.0f, 16, &r_n1, &m_n);
    printf("  hit-or-miss samples (p = 0.1, frames 20-59): with the tail plane bias %+.1f %% RMSE %.4f; "
           "without %+.1f %% RMSE %.4f; plain mean RMSE %.4f\n", 100.0 * b_on, r_on, 100.0 * b_off,
           r_off, m_on);
    printf("  the same behind a stereo blend (c = 1): bias %+.1f %% RMSE %.4f; 16 wide (reference path) "
           "c = 0 %+.1f %%, c = 1 %+.1f %%\n", 100.0 * b_st, r_st, 100.0 * b_n0, 100.0 * b_n1);
    CHECK(fabs(b_on) < 0.3);
    CHECK(r_on < m_on);
    CHECK(b_off < -0.4); /* what the plane removes (if this fails, revisit the docs) */
    CHECK(b_st > b_on && b_st - b_on > 0.15 * fabs(b_on)); /* measured: a quarter of the loss back */
    CHECK(fabs(b_st) < 0.3);
    CHECK(b_n1 > b_n0 && b_n1 - b_n0 > 0.15 * fabs(b_n0));
}

/* The tail plane must not let fireflies in where they are rare: the single firefly and
   the 2 % spikes of test_firefly and test_firefly_rate, with the plane carried. */
static void test_tail_fireflies(void)
{
    firefly_result po;
    g_tail = 1;
    /* per eye, then behind a stereo blend (c = 1 changes more than the limit's share:
       the weight's bias term, no restart lean; the single firefly's figures at c = 1 do
       not depend on the share, whose r is about 0 there) */
    for (g_shared = 0.0f; g_shared < 1.5f; g_shared += 1.0f) {
        po = firefly_run(SBL_ESTIMATOR_POOLED);
        printf("  firefly, pooled, tail plane, c = %.0f: error %.4f -> %.4f -> %.4f 10 frames later\n",
               g_shared, po.err_before, po.err_after, po.err_decay);
        CHECK(po.err_after < 0.1);
        CHECK(po.err_decay < 0.05);
        test_firefly_rate();
    }
    g_tail = 0;
    g_shared = 0.0f;
}

/* The restart lean (docs/ESTIMATORS.md 6.3): a converged flat history of 0.2, then the
   whole region jumps to 0.8 with noise 0.05. The weight of the new sample is then about 1
   (the history is dropped), so without the lean the first output is about the noisy
   input; with it the neighbours' mean comes in and the output's RMSE against 0.8 falls
   below the input's, behind a stereo blend (stereo_shared_bias 1) too. One channel: the blend moves the output along the
   segment x* .. y only, so in colour the noise across a grey jump's direction (2/3 of
   it) would stay whatever the weight. */
static void restart_jump_rmse(float c, int evidence, double *out_rmse, double *in_rmse)
{
    const int w = 48, h = 24, frames = 21;
    seq1 s;
    sbl_temporal_desc d;
    sbt_rng rng = {29};
    double se = 0, si = 0;
    int i, k, x, y, n = 0;
    memset(&d, 0, sizeof d);
    d.stereo_shared_bias = c;
    g_evidence = evidence;
    seq_init(&s, w, h, 1);
    for (i = 0; i < frames; ++i) {
        fill_flat(&s, &rng, i + 1 < frames ? 0.2 : 0.8, 0.05);
        CHECK_EQ(seq_step(&s, &d, i == 0), SBL_OK);
    }
    /* the interior (away from the image's border rows and columns) */
    for (y = 2; y < h - 2; ++y)
        for (x = 2; x < w - 2; ++x)
            for (k = 0; k < 1; ++k) {
                const double o = seq_out(&s, x, y)[k] - 0.8, v = s.cur[(size_t)y * w + x] - 0.8;
                se += o * o;
                si += v * v;
                ++n;
            }
    g_evidence = 0;
    seq_free(&s);
    *out_rmse = sqrt(se / n);
    *in_rmse = sqrt(si / n);
}

static void test_restart_lean(void)
{
    double o0, i0, o1, i1, oe, ie;
    restart_jump_rmse(0.0f, 0, &o0, &i0);
    restart_jump_rmse(0.0f, 1, &oe, &ie);
    restart_jump_rmse(1.0f, 0, &o1, &i1);
    printf("  restart lean, a converged 0.2 jumping to 0.8 (noise 0.05): first output's RMSE "
           "%.4f (%.4f with the evidence plane; input %.4f), %.4f behind a stereo blend "
           "(input %.4f)\n", o0, oe, i0, o1, i1);
    CHECK(o0 < 0.85 * i0); /* measured 0.78 (1.00 without the lean) */
    CHECK(oe < 0.85 * ie);
    /* behind a stereo blend too (6.10; before it the lean was off there: 1.00 of the
       input) */
    CHECK(o1 < 0.85 * i1); /* measured 0.78 */
}

/* ---- the display of a temporal output (docs/ESTIMATORS.md 6.7) --------------------- */

/* RMSE against truth(x) over columns [x0, x1) and rows [2, h - 2) of an image */
static double display_rmse(const float *im, int w, int h, int ch, int x0, int x1, double (*truth)(int))
{
    double se = 0;
    int x, y, k, n = 0;
    for (y = 2; y < h - 2; ++y)
        for (x = x0; x < x1; ++x)
            for (k = 0; k < ch; ++k) {
                const double e = im[((size_t)y * w + x) * ch + k] - truth(x);
                se += e * e;
                ++n;
            }
    return sqrt(se / n);
}
/* edges for test_display_lean: 0 along the rows (0.2 above row 12), 1 the diagonal
   (0.2 where x - y < 12), 2 the anti-diagonal (0.2 where x + y < 36); near: the two
   pixels either side */
static double edge_value(int kind, int x, int y)
{
    const int below = kind == 0 ? y < 12 : kind == 1 ? x - y < 12 : x + y < 36;
    return below ? 0.2 : 0.8;
}
static int edge_near(int kind, int x, int y)
{
    const int v = kind == 0 ? y - 12 : kind == 1 ? x - y - 12 : x + y - 36;
    return v >= -2 && v <= 1;
}
/* a finite test on the bits (-ffast-math builds may fold x - x == 0) */
static int display_finite(float v)
{
    unsigned int b;
    memcpy(&b, &v, sizeof b);
    return (b & 0x7f800000u) != 0x7f800000u;
}
static double truth_flat(int x) { (void)x; return 0.5; }
static double truth_edge(int x) { return x < 24 ? 0.2 : 0.8; }

static void test_display_lean(void)
{
    const int w = 48, h = 24, ch = 3;
    const size_t n = (size_t)w * h * ch;
    float *disp = (float *)calloc(n, sizeof(float)), *copy = (float *)calloc(n, sizeof(float));
    sbl_temporal_desc d;
    seq1 s;
    sbt_rng rng = {31};
    double flat_o, flat_d, edge_o, edge_d, in_o, in_d;
    size_t i;
    int f, x, y;
    memset(&d, 0, sizeof d);
    g_display = disp;
    /* a first frame (N = 1 everywhere): flat 0.5 with noise 0.1 */
    seq_init(&s, w, h, ch);
    for (i = 0; i < n; ++i) s.cur[i] = (float)(0.5 + 0.1 * sbt_gauss(&rng));
    CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
    flat_o = display_rmse(seq_out(&s, 0, 0), w, h, ch, 2, w - 2, truth_flat);
    flat_d = display_rmse(disp, w, h, ch, 2, w - 2, truth_flat);
    /* an edge (0.2 | 0.8 at column 24), noise 0.02: the neighbours' spread is texture */
    for (y = 0; y < h; ++y)
        for (x = 0; x < w; ++x)
            for (f = 0; f < ch; ++f)
                s.cur[((size_t)y * w + x) * ch + f] = (float)(truth_edge(x) + 0.02 * sbt_gauss(&rng));
    CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
    edge_o = display_rmse(seq_out(&s, 0, 0), w, h, ch, 23, 25, truth_edge);
    edge_d = display_rmse(disp, w, h, ch, 23, 25, truth_edge);
    in_o = display_rmse(seq_out(&s, 0, 0), w, h, ch, 2, 20, truth_edge);
    in_d = display_rmse(disp, w, h, ch, 2, 20, truth_edge);
    printf("  display lean, a first frame: flat noise 0.1 RMSE %.4f -> %.4f; an edge, noise 0.02: "
           "its two columns %.4f -> %.4f, the flat side %.4f -> %.4f\n",
           flat_o, flat_d, edge_o, edge_d, in_o, in_d);
    /* edges along rows, the diagonal and the anti-diagonal, noise 0.02: the pixels
       next to each (each direction's pairs must be the ones along it) */
    {
        int kind;
        for (kind = 0; kind < 3; ++kind) {
            double so = 0, sd = 0;
            int cnt = 0;
            for (y = 0; y < h; ++y)
                for (x = 0; x < w; ++x)
                    for (f = 0; f < ch; ++f)
                        s.cur[((size_t)y * w + x) * ch + f] =
                            (float)(edge_value(kind, x, y) + 0.02 * sbt_gauss(&rng));
            CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
            for (y = 2; y < h - 2; ++y)
                for (x = 2; x < w - 2; ++x)
                    if (edge_near(kind, x, y))
                        for (f = 0; f < ch; ++f) {
                            const size_t q = ((size_t)y * w + x) * ch + f;
                            const double tr = edge_value(kind, x, y), eo = seq_out(&s, 0, 0)[q] - tr,
                                         ed = disp[q] - tr;
                            so += eo * eo;
                            sd += ed * ed;
                            ++cnt;
                        }
            printf("  display lean, an edge along %s, noise 0.02: the pixels next to it %.4f -> %.4f\n",
                   kind == 0 ? "the rows" : kind == 1 ? "the diagonal" : "the anti-diagonal",
                   sqrt(so / cnt), sqrt(sd / cnt));
            CHECK(sd < 1.1 * 1.1 * so);
        }
    }
    CHECK(flat_d < 0.5 * flat_o);   /* the neighbours' mean: about a third */
    CHECK(edge_d < 1.1 * edge_o);   /* no lean across the edge */
    CHECK(in_d < 0.6 * in_o);
    /* a second frame of flat noise (N about 2): still young, the display still leans */
    for (f = 0; f < 2; ++f) {
        for (i = 0; i < n; ++i) s.cur[i] = (float)(0.5 + 0.1 * sbt_gauss(&rng));
        CHECK_EQ(seq_step(&s, &d, f == 0), SBL_OK);
    }
    {
        const float n2 = seq_n(&s, w / 2, h / 2);
        const double o2 = display_rmse(seq_out(&s, 0, 0), w, h, ch, 2, w - 2, truth_flat),
                     d2 = display_rmse(disp, w, h, ch, 2, w - 2, truth_flat);
        printf("  display lean, a second frame (N %.2f): flat RMSE %.4f -> %.4f\n", n2, o2, d2);
        CHECK(n2 > 1.5f && n2 <= 3.0f);
        CHECK(d2 < 0.7 * o2);
    }
    /* a converged history (N > 3): the display is the history colour, bit for bit */
    for (f = 0; f < 12; ++f) {
        for (i = 0; i < n; ++i) s.cur[i] = (float)(0.5 + 0.1 * sbt_gauss(&rng));
        CHECK_EQ(seq_step(&s, &d, f == 0), SBL_OK);
    }
    CHECK(seq_n(&s, w / 2, h / 2) > 3.0f);
    CHECK(memcmp(disp, seq_out(&s, 0, 0), n * sizeof(float)) == 0);
    /* the last first-frame again, through sbl_temporal_display: off (max_length < 0) is a
       copy; bands of rows equal one call */
    for (i = 0; i < n; ++i) s.cur[i] = (float)(0.5 + 0.1 * sbt_gauss(&rng));
    CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
    {
        sbl_frame fr;
        sbl_temporal_output o;
        sbl_display_desc dd;
        sbl_image dv = sbl_image_make(copy, w, h, ch);
        memset(&fr, 0, sizeof fr);
        memset(&o, 0, sizeof o);
        memset(&dd, 0, sizeof dd);
        fr.color = sbl_image_make(s.cur, w, h, ch);
        o.color = sbl_image_make(seq_out(&s, 0, 0), w, h, ch);
        o.length = sbl_image_make(s.len[s.ping], w, h, 1);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, dv, 0, 5), SBL_OK);
        CHECK_EQ(sbl_temporal_display(&dd, &fr, &o, dv, 5, 13), SBL_OK);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, dv, 13, h), SBL_OK);
        CHECK(memcmp(disp, copy, n * sizeof(float)) == 0);
        CHECK(memcmp(disp, seq_out(&s, 0, 0), n * sizeof(float)) != 0);
        dd.max_length = -1.0f;
        CHECK_EQ(sbl_temporal_display(&dd, &fr, &o, dv, 0, h), SBL_OK);
        CHECK(memcmp(copy, seq_out(&s, 0, 0), n * sizeof(float)) == 0);
        /* bad input */
        dd.max_length = NAN;
        CHECK_EQ(sbl_temporal_display(&dd, &fr, &o, dv, 0, h), SBL_ERROR_INVALID_PARAM);
        CHECK_EQ(sbl_temporal_display(NULL, NULL, &o, dv, 0, h), SBL_ERROR_NULL_POINTER);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, dv, 0, h + 1), SBL_ERROR_INVALID_ROWS);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, sbl_image_make(copy, w - 1, h, ch), 0, h),
                 SBL_ERROR_SIZE_MISMATCH);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, sbl_image_make(copy, w, h, 1), 0, h),
                 SBL_ERROR_CHANNEL_MISMATCH);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, o.color, 0, h), SBL_ERROR_OVERLAP);
        CHECK_EQ(sbl_temporal_display(NULL, &fr, &o, fr.color, 0, h), SBL_ERROR_OVERLAP);
        /* sbl_temporal_filter_frame: the display may not be the history's colour */
        {
            sbl_frame f2 = fr;
            sbl_history hh;
            sbl_temporal_output o3 = o;
            float *tmp_c = (float *)calloc(n, sizeof(float)), *tmp_n = (float *)calloc(n, sizeof(float));
            memset(&hh, 0, sizeof hh);
            hh.color = o.color;
            hh.length = o.length;
            f2.gbuffer.depth = sbl_image_make(s.depth, w, h, 1);
            f2.gbuffer.motion = sbl_image_make(s.mv, w, h, 2);
            hh.gbuffer.depth = f2.gbuffer.depth;
            o3.color = sbl_image_make(tmp_c, w, h, ch);
            o3.length = sbl_image_make(tmp_n, w, h, 1);
            o3.display = hh.color;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &f2, &hh, &o3), SBL_ERROR_OVERLAP);
            o3.display = dv;
            CHECK_EQ(sbl_temporal_filter_frame(&d, &f2, &hh, &o3), SBL_OK);
            free(tmp_c);
            free(tmp_n);
        }
        /* the row call does not write a display: it says so */
        {
            sbl_temporal_output o2 = o;
            float *tmp_c = (float *)calloc(n, sizeof(float)), *tmp_n = (float *)calloc(n, sizeof(float));
            size_t bytes = sbl_temporal_scratch_size(w, ch);
            void *scratch = malloc(bytes);
            o2.color = sbl_image_make(tmp_c, w, h, ch);
            o2.length = sbl_image_make(tmp_n, w, h, 1);
            o2.display = dv;
            CHECK_EQ(sbl_temporal_filter(&d, &fr, NULL, &o2, 0, h, scratch, bytes), SBL_ERROR_INVALID_PARAM);
            CHECK_EQ(sbl_temporal_validate(&d, &fr, NULL, &o2, NULL), SBL_ERROR_INVALID_PARAM);
            free(scratch);
            free(tmp_c);
            free(tmp_n);
        }
    }
    /* samples that are not values (NaN, inf) near young pixels: a finite display */
    s.cur[((size_t)5 * w + 7) * ch] = NAN;
    s.cur[((size_t)9 * w + 30) * ch + 1] = INFINITY;
    CHECK_EQ(seq_step(&s, &d, 1), SBL_OK);
    {
        int finite = 1;
        for (i = 0; i < n; ++i)
            if (display_finite(seq_out(&s, 0, 0)[i]) && !display_finite(disp[i])) finite = 0;
        CHECK(finite);
    }
    g_display = NULL;
    seq_free(&s);
    free(disp);
    free(copy);
}

int main(void)
{
    test_tail_hits();
    test_tail_fireflies();
    test_evidence_params();
    test_evidence_absent();
    test_evidence_static();
    test_evidence_ramp();
    test_evidence_garrote();
    test_evidence_firefly();
    test_evidence_noise_free_jump();
    test_evidence_region();
    test_evidence_mix();
    test_firefly();
    test_firefly_rate();
    test_convergence_and_step();
    test_moving_light();
    test_stereo_edge_and_flat();
    test_stereo_lag();
    test_stereo_change_evidence();
    test_stereo_lean_young();
    test_history_catmull_rom();
    test_history_sharpness();
    test_history_filter_params();
    test_history_filter_bands();
    test_stereo_shared_bias();
    test_blur_bias();
    test_shared_bias_floor();
    test_restart_lean();
    test_display_lean();
    return sbt_finish("test_accuracy");
}
