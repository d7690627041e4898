#!/usr/bin/env python3
"""Reference SSIM numbers for tests/test_metrics.c, from scikit-image.

The test images are generated with integer arithmetic only (triangle waves and a 32-bit
LCG), then scaled by a power of two, so every value is exactly representable in float32
and the C test (gen_pair() in tests/test_metrics.c) rebuilds bit-identical images. Keep
the two generators in step.

They are passed to skimage as float64: skimage computes in the input's float type, and
float64 keeps its reference free of float32 rounding. Run:  python3 tools/ssim_reference.py
"""
import numpy as np
import skimage
from skimage.metrics import structural_similarity

# name, w, h, channels, kind, scale exponent (value = int * 2**-e), L, seed
CASES = [
    ("gray_noise_L1",      32, 24, 1, "noise",    16,   1.0, 1),
    ("gray_shift_L1",      32, 24, 1, "shift",    16,   1.0, 2),
    ("gray_noise_L255",    32, 24, 1, "noise",     8, 255.0, 3),
    ("rgb_noise_L1",       40, 29, 3, "noise",    16,   1.0, 4),
    ("rgb_contrast_L255",  40, 29, 3, "contrast",  8, 255.0, 5),
    ("rgb_shift_L255",     27, 27, 3, "shift",     8, 255.0, 6),
    ("gray_min11_L1",      11, 11, 1, "noise",    16,   1.0, 7),
    ("rgba_noise_L1",      23, 19, 4, "noise",    16,   1.0, 8),
    ("gray_tall_L2",       13, 37, 1, "contrast", 16,   2.0, 9),
]


def tri(v, p):
    return abs(v % (2 * p) - p)


def gen_pair(w, h, ch, kind, seed):
    """Integer images a, b of shape (h, w, ch); a in [0, 65536]."""
    a = np.zeros((h, w, ch), dtype=np.int64)
    b = np.zeros((h, w, ch), dtype=np.int64)
    s = seed & 0xFFFFFFFF
    for y in range(h):
        for x in range(w):
            for c in range(ch):
                s = (s * 1664525 + 1013904223) & 0xFFFFFFFF  # one step per sample, always
                va = tri(3 * x + 17 * c, 64) * tri(5 * y + x + 11 * c, 64) * 16
                if kind == "noise":
                    vb = va + ((s >> 16) % 8193) - 4096
                elif kind == "shift":
                    vb = va + 3277
                else:  # contrast
                    vb = ((3 * va) >> 2) + 8192
                a[y, x, c] = va
                b[y, x, c] = vb
    return a, b


def main():
    print("/* skimage %s, numpy %s: tools/ssim_reference.py */" % (skimage.__version__, np.__version__))
    for name, w, h, ch, kind, e, L, seed in CASES:
        ia, ib = gen_pair(w, h, ch, kind, seed)
        a = ia.astype(np.float64) * 2.0 ** -e
        b = ib.astype(np.float64) * 2.0 ** -e
        # The C side stores float32: make sure nothing is lost on the way.
        assert np.array_equal(a.astype(np.float32).astype(np.float64), a)
        assert np.array_equal(b.astype(np.float32).astype(np.float64), b)
        kw = dict(gaussian_weights=True, sigma=1.5, use_sample_covariance=False, data_range=L)
        if ch == 1:
            m, smap = structural_similarity(a[:, :, 0], b[:, :, 0], full=True, **kw)
            smap = smap[:, :, None]
        else:
            m, smap = structural_similarity(a, b, channel_axis=2, full=True, **kw)
        # skimage averages the map after cropping (win_size - 1) // 2 = 5 pixels: the
        # pixels whose full 11x11 window lies in the image, i.e. the C "valid" region.
        valid = smap[5:h - 5, 5:w - 5, :].mean(axis=(0, 1)).mean()
        assert abs(valid - m) <= 1e-14 * max(1.0, abs(m)), (name, valid, m)
        print('    { "%s", %d, %d, %d, %d, %d, %.1f, %du, %.17g },'
              % (name, w, h, ch, {"noise": 0, "shift": 1, "contrast": 2}[kind], e, L, seed, m))


if __name__ == "__main__":
    main()
