// The temporal filter as a user would compose it from OpenCV calls (remap + boxFilter +
// arithmetic), for bench/perf.c to time in the same run as the library. It is the
// paper's per-channel estimator with a single depth test on the bilinearly remapped
// previous depth (OpenCV's remap has no per-tap rejection and no 3x3 fallback, so this
// does less work than the library, not more):
//   x* = remap(history, p + mv), N_X = remap(N), z_prev = remap(previous depth)
//   valid = |z_prev - z| <= 0.05 z
//   m1 = box3x3(y), m2 = box3x3(y*y), s2 = m2 - m1^2, d = x* - m1
//   a = d^2 / (d^2 + s2), out = x* + a (y - x*), N = N_X / ((1-a)^2 + a^2 N_X)
//   out = y, N = 1 where not valid
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

extern "C" int sbl_opencv_temporal(int w, int h, const float *color, const float *depth,
                                   const float *motion, const float *hist, const float *hlen,
                                   const float *prev_depth, float *out, float *out_len,
                                   int threads)
{
    using namespace cv;
    setNumThreads(threads);
    Mat y(h, w, CV_32FC3, (void *)color), z(h, w, CV_32FC1, (void *)depth);
    Mat mv(h, w, CV_32FC2, (void *)motion), hi(h, w, CV_32FC3, (void *)hist);
    Mat hn(h, w, CV_32FC1, (void *)hlen), zp(h, w, CV_32FC1, (void *)prev_depth);
    Mat o(h, w, CV_32FC3, out), on(h, w, CV_32FC1, out_len);
    static thread_local Mat grid;
    if (grid.rows != h || grid.cols != w) {
        grid.create(h, w, CV_32FC2);
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c) grid.at<Vec2f>(r, c) = Vec2f((float)c, (float)r);
    }
    // intermediates kept across calls so that OpenCV reuses their memory (a careful
    // user's composition: no allocation, no page faults after the first frame)
    static thread_local Mat map, xs, nx, zx, valid, invalid, m1, m2, s2, d, d2, a, t, am, n_out,
        zt, one_m, den;
    add(grid, mv, map);                       // source position (pixel centres cancel)
    remap(hi, xs, map, noArray(), INTER_LINEAR, BORDER_CONSTANT);
    remap(hn, nx, map, noArray(), INTER_LINEAR, BORDER_CONSTANT);
    remap(zp, zx, map, noArray(), INTER_LINEAR, BORDER_CONSTANT);
    absdiff(zx, z, t);
    multiply(z, Scalar::all(0.05), zt);
    compare(t, zt, valid, CMP_LE);
    bitwise_not(valid, invalid);
    boxFilter(y, m1, -1, Size(3, 3), Point(-1, -1), true, BORDER_REFLECT);
    multiply(y, y, t);
    boxFilter(t, m2, -1, Size(3, 3), Point(-1, -1), true, BORDER_REFLECT);
    multiply(m1, m1, t);
    subtract(m2, t, s2);
    subtract(xs, m1, d);
    multiply(d, d, d2);
    add(d2, s2, t);
    max(t, Scalar::all(1e-30), t);
    divide(d2, t, a);
    subtract(y, xs, t);
    multiply(a, t, t);
    add(xs, t, o);
    y.copyTo(o, invalid);
    transform(a, am, Matx13f(1.0f / 3, 1.0f / 3, 1.0f / 3));
    subtract(Scalar::all(1.0), am, one_m);
    multiply(one_m, one_m, den);
    multiply(am, am, t);
    multiply(t, nx, t);
    add(den, t, den);
    max(den, Scalar::all(1e-30), den);
    divide(nx, den, n_out);
    n_out.setTo(Scalar::all(1.0), invalid);
    n_out.copyTo(on);
    return 0;
}
