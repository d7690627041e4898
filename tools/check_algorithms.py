#!/usr/bin/env python3
"""Numerical checks of the claims in docs/ALGORITHMS.md (plain Python 3, no packages).

    python3 tools/check_algorithms.py        # about 30 s; prints each claim and its measurement

Each check states the derived value and the Monte Carlo estimate next to it; the script
exits 1 if one is off by more than its tolerance. Seeds are fixed: the output is the same
on every run."""
import math
import random
import sys

rng = random.Random(12)
failures = 0


def report(what, derived, measured, tol):
    global failures
    ok = abs(derived - measured) <= tol
    failures += not ok
    print("%-4s %-62s derived %9.4f  measured %9.4f" % ("ok" if ok else "FAIL", what, derived, measured))


# --- section 1: the optimal weight minimises MSE(a) = (1-a)^2 (B^2 + var_X) + a^2 var_Y
worst = 0.0
for _ in range(2000):
    b2, vx, vy = rng.uniform(0, 2) ** 2, rng.uniform(0, 2), rng.uniform(0.01, 2)
    a_star = (b2 + vx) / (b2 + vx + vy)
    mse = lambda a: (1 - a) ** 2 * (b2 + vx) + a * a * vy
    grid = min(mse(i / 10000.0) for i in range(10001))
    worst = max(worst, mse(a_star) - grid)
report("1. MSE(a*) - min over a grid of 10^4 weights (2000 cases)", 0.0, worst, 1e-12)
n_x = 7
report("1. no bias, N_X = 7 equal samples: a* = 1/(N+1)", 1 / 8.0, 1.0 / (n_x + 1), 1e-15)

# --- section 3: Eq. 5, the sample count of a blend
a, n_x, n_y, trials = 0.3, 5, 2, 200000
acc = 0.0
for _ in range(trials):
    x = sum(rng.gauss(0, 1) for _ in range(n_x)) / n_x
    y = sum(rng.gauss(0, 1) for _ in range(n_y)) / n_y
    v = (1 - a) * x + a * y
    acc += v * v
report("3. N_out = N_X N_Y / ((1-a)^2 N_Y + a^2 N_X), a 0.3, N 5 and 2",
       n_x * n_y / ((1 - a) ** 2 * n_y + a * a * n_x), trials / acc, 0.1)


# --- section 2: the paper's estimate a = d^2 / (d^2 + s^2) over a 3x3 window
def paper_a(x_star, ys):
    m = sum(ys) / len(ys)
    s2 = sum((y - m) ** 2 for y in ys) / len(ys)
    d2 = (x_star - m) ** 2
    return d2 / (d2 + s2) if d2 + s2 > 0 else 0.5


trials = 100000
def pop_var(ys):
    m = sum(ys) / len(ys)
    return sum((y - m) ** 2 for y in ys) / len(ys)


mean_s2 = sum(pop_var([rng.gauss(0, 1) for _ in range(9)]) for _ in range(trials)) / trials
report("2. E[s^2] = (8/9) var_Y", 8 / 9.0, mean_s2, 0.01)
mean_a = sum(paper_a(0.0, [rng.gauss(0, 1) for _ in range(9)]) for _ in range(trials)) / trials
report("2. exact history (var_X = 0): E[a] = mean of Beta(1/2, 4) = 1/9", 1 / 9.0, mean_a, 0.003)

# the estimate fed back into its own history: a single pixel, static, unbiased
h, a_sum, v_sum, frames, warm = 0.0, 0.0, 0.0, 200000, 1000
for t in range(frames):
    ys = [rng.gauss(0, 1) for _ in range(9)]
    a = paper_a(h, ys)
    h = (1 - a) * h + a * ys[4]
    if t >= warm:
        a_sum += a
        v_sum += h * h
print("     2. paper's estimate in the loop (static, unbiased): mean a %.3f, effective N %.1f"
      " (the floor: it stops converging)" % (a_sum / (frames - warm), (frames - warm) / v_sum))
report("2. ... its floor on a: mean a in the loop (measured, see text)", 0.167, a_sum / (frames - warm), 0.01)

# --- section 4: the history-aware estimate on a static image (paired differences)
W = H = 20
K = 3.0          # bias_threshold: standard errors
CAP = 64.0       # max_history


def history_aware_frames(frames, step_at=None, step=0.0):
    """Runs the estimate on a static W x H image of constant value 0 (+step after
    step_at), unit noise, 1 sample per frame; returns per-frame (mean a, mse of history)."""
    hist = [0.0] * (W * H)
    n = [0.0] * (W * H)
    out = []
    for t in range(frames):
        truth = step if (step_at is not None and t >= step_at) else 0.0
        y = [truth + rng.gauss(0, 1) for _ in range(W * H)]
        new_h, new_n, a_tot = [0.0] * (W * H), [0.0] * (W * H), 0.0
        for j in range(H):
            for i in range(W):
                p = j * W + i
                if n[p] == 0:                      # first frame: reset, a = 1
                    new_h[p], new_n[p] = y[p], 1.0
                    a_tot += 1.0
                    continue
                diffs = [hist[q] - y[q] for q in
                         (((j + dj) % H) * W + (i + di) % W for dj in (-1, 0, 1) for di in (-1, 0, 1))]
                m = sum(diffs) / 9.0
                pv = sum((d - m) ** 2 for d in diffs) / 8.0          # Bessel
                var_y = pv * n[p] / (n[p] + 1.0)                     # N_Y = 1
                var_x = pv - var_y
                bias2 = max(0.0, m * m - K * K * pv / 9.0)
                a = (bias2 + var_x) / (bias2 + var_x + var_y) if pv > 0 else 1.0 / (n[p] + 1)
                new_h[p] = (1 - a) * hist[p] + a * y[p]
                new_n[p] = min(CAP, n[p] / ((1 - a) ** 2 + a * a * n[p]))
                a_tot += a
        hist, n = new_h, new_n
        out.append((a_tot / (W * H), sum((v - truth) ** 2 for v in hist) / (W * H), sum(n) / (W * H)))
    return out


res = history_aware_frames(64)
for f in (8, 16, 32, 64):
    print("     4. static, frame %2d: mean a %.4f (1/(N+1) = %.4f), effective N of the history %.1f,"
          " tracked N %.1f" % (f, res[f - 1][0], 1.0 / f, 1.0 / res[f - 1][1], res[f - 1][2]))
report("4. static: mean a at frame 16 near 1/16 (false bias detections add)", 1 / 16.0, res[15][0], 0.02)
report("4. static: keeps converging: effective N, frame 64 / frame 16 > 2", 1.0,
       1.0 if res[15][1] / res[63][1] > 2.0 else 0.0, 0.0)
res = history_aware_frames(32, step_at=16, step=3.0)
print("     4. a step of 3 sigma at frame 16: mean a %.3f (frame 15) -> %.3f (frame 16), history"
      " error %.3f -> %.3f (frame 18)" % (res[15][0], res[16][0], math.sqrt(res[15][1]), math.sqrt(res[18][1])))
report("4. ... a rises at the step (> 0.5)", 1.0, 1.0 if res[16][0] > 0.5 else 0.0, 0.0)

# --- section 2 (lag): an EMA of weight a behind a ramp of delta per frame lags delta (1-a)/a
a, delta, o = 0.1, 0.01, 0.0
for t in range(2000):
    o = (1 - a) * o + a * (t * delta)
report("2. lag of an EMA (a 0.1) behind a ramp of 0.01 / frame", delta * (1 - a) / a, 1999 * delta - o, 1e-9)

print("%d check%s failed" % (failures, "" if failures == 1 else "s"))
sys.exit(1 if failures else 0)
