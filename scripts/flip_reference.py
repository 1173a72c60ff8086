#!/usr/bin/python3
"""An independent LDR-FLIP in Python/numpy, for the pinned values of Flip.MatchesAnIndependentImplementation
(tests/test_metrics.cpp).

Written from the paper (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild, "FLIP: A
Difference Evaluator for Alternating Images", HPG 2020) and its published constants, not from
src/metrics/flip.cpp nor from NVIDIA's code. Where the paper leaves room it takes the choices src/metrics/flip.cpp documents in
its header (docs/DESIGN.md points there): clamp-to-edge borders, one CSF radius for all channels from
the widest Gaussian, each kernel normalised.

    python3 scripts/flip_reference.py    # prints the image pairs' mean FLIP at 67.02 pixels per degree

The image pairs are built from integer formulas repeated in the C++ test (values k / 255 as float32,
linear). NVIDIA's reference (its v1.2 Python `compute_ldrflip`, given the pairs' sRGB encoding, as it
takes sRGB images) gives 0.131816, 0.259295 and 0.524451; this script 0.131813, 0.259296, 0.524454.
"""
import math

import numpy as np

PPD = 67.02
# Colour error remapping and feature detector constants (paper, section 4).
QC, PC, PT = 0.7, 0.4, 0.95
W_FEATURE, QF = 0.082, 0.5
# Spatial contrast sensitivity functions (paper, table of a1, b1, a2, b2; x in degrees):
#   S(x) = a1 sqrt(pi / b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 x^2 / b2)
CSF = {
    "A": (1.0, 0.0047, 0.0, 1e-5),
    "RG": (1.0, 0.0053, 0.0, 1e-5),
    "BY": (34.1, 0.04, 13.5, 0.025),
}

# linear sRGB (D65) -> XYZ; the reference white is XYZ of RGB (1, 1, 1).
RGB_TO_XYZ = np.array([[0.4124564, 0.3575761, 0.1804375],
                       [0.2126729, 0.7151522, 0.0721750],
                       [0.0193339, 0.1191920, 0.9503041]])
XYZ_TO_RGB = np.linalg.inv(RGB_TO_XYZ)
WHITE = RGB_TO_XYZ @ np.ones(3)


def convolve(plane, kernel):
    """2D correlation with clamp-to-edge borders (the kernels here are symmetric or antisymmetric
    along one axis; correlation is what a filter reading neighbours at +offset does)."""
    r = kernel.shape[0] // 2
    padded = np.pad(plane, r, mode="edge")
    h, w = plane.shape
    out = np.zeros_like(plane)
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out += kernel[dy + r, dx + r] * padded[r + dy:r + dy + h, r + dx:r + dx + w]
    return out


def csf_kernel(params, ppd, radius):
    a1, b1, a2, b2 = params
    d = np.arange(-radius, radius + 1) / ppd
    x2 = d[None, :] ** 2 + d[:, None] ** 2
    k = a1 * math.sqrt(math.pi / b1) * np.exp(-math.pi ** 2 * x2 / b1) + \
        a2 * math.sqrt(math.pi / b2) * np.exp(-math.pi ** 2 * x2 / b2)
    return k / k.sum()


def feature_kernels(ppd, sigma_scale=0.5):
    sigma = sigma_scale * W_FEATURE * ppd
    radius = math.ceil(3 * sigma)
    x = np.arange(-radius, radius + 1, dtype=np.float64)
    xx, yy = np.meshgrid(x, x)  # xx varies along columns
    g = np.exp(-(xx ** 2 + yy ** 2) / (2 * sigma ** 2))
    edge = -xx * g                          # first derivative of the Gaussian along x
    point = (xx ** 2 / sigma ** 2 - 1) * g  # second derivative along x

    def normalise(k):
        pos, neg = k[k > 0].sum(), -k[k < 0].sum()
        return np.where(k > 0, k / pos, np.where(k < 0, k / neg, 0.0))

    return normalise(edge), normalise(point)


def lab(rgb):
    xyz = np.einsum("ij,...j->...i", RGB_TO_XYZ, rgb) / WHITE
    eps, kappa = 216 / 24389, 24389 / 27

    def f(t):
        return np.where(t > eps, np.cbrt(t), (kappa * t + 16) / 116)

    fx, fy, fz = f(xyz[..., 0]), f(xyz[..., 1]), f(xyz[..., 2])
    return np.stack([116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)], axis=-1)


def hunt(l):
    return np.stack([l[..., 0], 0.01 * l[..., 0] * l[..., 1], 0.01 * l[..., 0] * l[..., 2]], axis=-1)


def hyab(p, q):
    return np.abs(p[..., 0] - q[..., 0]) + np.sqrt((p[..., 1] - q[..., 1]) ** 2 + (p[..., 2] - q[..., 2]) ** 2)


def ycxcz(rgb):
    xyz = np.einsum("ij,...j->...i", RGB_TO_XYZ, rgb) / WHITE
    return np.stack([116 * xyz[..., 1] - 16, 500 * (xyz[..., 0] - xyz[..., 1]), 200 * (xyz[..., 1] - xyz[..., 2])], axis=-1)


def ycxcz_to_rgb(y):
    yy = (y[..., 0] + 16) / 116
    xyz = np.stack([y[..., 1] / 500 + yy, yy, yy - y[..., 2] / 200], axis=-1) * WHITE
    return np.einsum("ij,...j->...i", XYZ_TO_RGB, xyz)


def flip_mean(ref, test, ppd=PPD, csf_radius_scale=1.0, sigma_scale=0.5):
    ref, test = np.clip(ref, 0, 1), np.clip(test, 0, 1)
    b_max = max(p[1] for p in CSF.values())
    radius = math.ceil(csf_radius_scale * 3 * math.sqrt(b_max / (2 * math.pi ** 2)) * ppd)
    kernels = [csf_kernel(CSF[c], ppd, radius) for c in ("A", "RG", "BY")]

    def filtered(img):
        o = ycxcz(img)
        f = np.stack([convolve(o[..., c], kernels[c]) for c in range(3)], axis=-1)
        return hunt(lab(np.clip(ycxcz_to_rgb(f), 0, 1)))

    cmax = hyab(hunt(lab(np.array([0.0, 1.0, 0.0]))), hunt(lab(np.array([0.0, 0.0, 1.0])))) ** QC
    d = hyab(filtered(ref), filtered(test)) ** QC
    colour = np.where(d < PC * cmax, d * PT / (PC * cmax), PT + (d - PC * cmax) / (cmax - PC * cmax) * (1 - PT))
    colour = np.clip(colour, 0, 1)

    edge, point = feature_kernels(ppd, sigma_scale)

    def magnitudes(img):
        lum = (np.einsum("j,...j->...", RGB_TO_XYZ[1], img)) / WHITE[1]
        e = np.hypot(convolve(lum, edge), convolve(lum, edge.T))
        p = np.hypot(convolve(lum, point), convolve(lum, point.T))
        return e, p

    er, pr = magnitudes(ref)
    et, pt = magnitudes(test)
    feature = (np.maximum(np.abs(er - et), np.abs(pr - pt)) / math.sqrt(2)) ** QF
    return float(np.mean(colour ** (1 - feature)))


# ---- the image pairs (repeated in tests/test_metrics.cpp, flipPair) ------------------------------
def pair(index, w=24, h=20):
    ref = np.zeros((h, w, 3), np.float32)
    test = np.zeros((h, w, 3), np.float32)
    for y in range(h):
        for x in range(w):
            for c in range(3):
                if index == 0:    # smooth gradient, a coloured square added
                    r = (40 + 8 * x + 5 * y + 60 * c) % 256
                    t = r if not (8 <= x < 14 and 6 <= y < 12) else (200 - 90 * c) % 256
                elif index == 1:  # fine noise against a slightly different noise
                    r = (x * 37 + y * 91 + c * 53 + (x * y) % 7 * 11) % 256
                    t = (r + (x * 13 + y * 7 + c * 29) % 41 - 20) % 256
                else:             # two-pixel stripes against their mean grey, with a hue shift
                    r = 230 if (x // 2) % 2 == 0 else 30
                    r = r if c != 2 else 255 - r
                    t = 130 if c != 1 else 110
                ref[y, x, c] = np.float32(r) / np.float32(255)
                test[y, x, c] = np.float32(t) / np.float32(255)
    return ref.astype(np.float64), test.astype(np.float64)


if __name__ == "__main__":
    for i in range(3):
        ref, test = pair(i)
        print(f"pair {i}: mean FLIP {flip_mean(ref, test):.6f}"
              f"   (CSF radius halved: {flip_mean(ref, test, csf_radius_scale=0.5):.6f},"
              f" feature width halved: {flip_mean(ref, test, sigma_scale=0.25):.6f})")
