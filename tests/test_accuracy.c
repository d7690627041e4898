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
} seq1;

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
}

static void seq_free(seq1 *s)
{
    free(s->cur); free(s->hist[0]); free(s->hist[1]); free(s->len[0]); free(s->len[1]);
    free(s->depth); free(s->mv); free(s->alpha);
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
       beta. Not blending is better still on this edge at noise 0.02 and 0.05 (printed,
       not checked: the mixed pixels' bias is a few standard errors of their window, whose
       pair spread it inflates itself; docs/ESTIMATORS.md section 4, open) */
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
            if (sigmas[l] >= 0.1) CHECK(eo2 <= ei2);
        }
        g_strong_edge = 0;
    }
}

int main(void)
{
    test_firefly();
    test_convergence_and_step();
    test_moving_light();
    test_stereo_edge_and_flat();
    return sbt_finish("test_accuracy");
}
