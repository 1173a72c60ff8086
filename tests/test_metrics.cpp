#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"

using namespace starnt;

namespace {

Image flat(int w, int h, double r, double g, double b) {
    Image img(w, h, 1.0f);
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        img.rgba[i * 4 + 0] = float(r);
        img.rgba[i * 4 + 1] = float(g);
        img.rgba[i * 4 + 2] = float(b);
    }
    return img;
}

// Image from sRGB-encoded values (one triple per pixel, row-major).
Image fromSrgb(int w, int h, const std::vector<double>& srgb) {
    Image img(w, h, 1.0f);
    for (size_t i = 0; i < img.pixelCount(); ++i)
        for (int c = 0; c < 3; ++c) img.rgba[i * 4 + size_t(c)] = srgbToLinear(float(srgb[i * 3 + size_t(c)]));
    return img;
}

// ---- independent evaluation of the FLIP colour formulas for a flat pair, in double -------------
// On a flat image the (normalised) CSF filters leave every pixel unchanged and the feature
// detectors give 0, so the per-pixel error is the remapped HyAB distance of the two colours.
struct Lab {
    double L, a, b;
};

Lab cieLab(double r, double g, double b) {
    // sRGB (D65) primaries; the white is XYZ of RGB (1, 1, 1).
    const double X = 0.4124564 * r + 0.3575761 * g + 0.1804375 * b;
    const double Y = 0.2126729 * r + 0.7151522 * g + 0.0721750 * b;
    const double Z = 0.0193339 * r + 0.1191920 * g + 0.9503041 * b;
    const double Xn = 0.4124564 + 0.3575761 + 0.1804375;
    const double Yn = 0.2126729 + 0.7151522 + 0.0721750;
    const double Zn = 0.0193339 + 0.1191920 + 0.9503041;
    const double eps = 216.0 / 24389.0, kappa = 24389.0 / 27.0;  // CIE constants
    auto f = [&](double t) { return t > eps ? std::cbrt(t) : (kappa * t + 16.0) / 116.0; };
    const double fx = f(X / Xn), fy = f(Y / Yn), fz = f(Z / Zn);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double huntHyab(Lab p, Lab q) {
    const double pa = 0.01 * p.L * p.a, pb = 0.01 * p.L * p.b;
    const double qa = 0.01 * q.L * q.a, qb = 0.01 * q.L * q.b;
    return std::abs(p.L - q.L) + std::sqrt((pa - qa) * (pa - qa) + (pb - qb) * (pb - qb));
}

double expectedFlatFlip(double r1, double g1, double b1, double r2, double g2, double b2) {
    const double qc = 0.7, pc = 0.4, pt = 0.95;
    const double dmax = std::pow(huntHyab(cieLab(0, 1, 0), cieLab(0, 0, 1)), qc);
    const double d = std::pow(huntHyab(cieLab(r1, g1, b1), cieLab(r2, g2, b2)), qc);
    if (d < pc * dmax) return d * pt / (pc * dmax);
    return pt + (1.0 - pt) * (d - pc * dmax) / ((1.0 - pc) * dmax);
}

void expectUniformMap(const FlipResult& r, double value, double tol) {
    for (size_t i = 0; i < r.errorMap.pixelCount(); ++i) {
        ASSERT_NEAR(r.errorMap.rgba[i * 4], value, tol) << "pixel " << i;
        ASSERT_EQ(r.errorMap.rgba[i * 4 + 3], 1.0f);
    }
}

Image noiseBase(int w, int h) {
    Image img(w, h, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = img.pixel(x, y);
            p[0] = 0.2f + 0.6f * float(x) / float(w);
            p[1] = 0.5f + 0.2f * std::sin(float(y) * 0.3f);
            p[2] = 0.3f + 0.4f * float(x + y) / float(w + h);
        }
    return img;
}

}  // namespace

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    Image a = noiseBase(40, 30);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float& v : a.rgba) v = u(rng);
    FlipResult r = flip(a, a);
    EXPECT_EQ(r.mean, 0.0);
    for (size_t i = 0; i < r.errorMap.pixelCount(); ++i) ASSERT_EQ(r.errorMap.rgba[i * 4], 0.0f);
}

TEST(Flip, FlatPairsMatchIndependentHandComputation) {
    struct Pair {
        double a[3], b[3];
    };
    const Pair pairs[] = {
        {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}},     // red vs green (above p_c: upper branch)
        {{0.5, 0.5, 0.5}, {0.2, 0.2, 0.2}},     // two greys
        {{0.8, 0.3, 0.1}, {0.2, 0.5, 0.9}},     // orange vs light blue
        {{0.30, 0.30, 0.30}, {0.32, 0.30, 0.28}},  // small difference (lower branch)
        {{0.001, 0.002, 0.0}, {0.0, 0.0, 0.003}},  // near black (linear segment of the Lab f)
    };
    for (const Pair& p : pairs) {
        const double expected = expectedFlatFlip(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]);
        FlipResult r = flip(flat(32, 24, p.a[0], p.a[1], p.a[2]), flat(32, 24, p.b[0], p.b[1], p.b[2]));
        EXPECT_NEAR(r.mean, expected, 2e-4) << p.a[0] << "," << p.a[1] << "," << p.a[2];
        expectUniformMap(r, expected, 2e-4);
        EXPECT_GT(expected, 0.0);
    }
}

// Black (L* = 0) vs white (L* = 100): HyAB = 100, below the green/blue maximum (~203.3), so the
// remapped error is 0.95 + 0.05 * (100^0.7 - 0.4 dmax) / (0.6 dmax) ~= 0.9675, not 1.0: the paper
// normalises by the green/blue distance, the largest one in the RGB cube.
// Image pair `index` of scripts/flip_reference.py (the same integer formulas, values k / 255).
std::pair<Image, Image> flipPair(int index, int w = 24, int h = 20) {
    Image ref(w, h, 1.0f), test(w, h, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                int r = 0, t = 0;
                if (index == 0) {  // smooth gradient, a coloured square added
                    r = (40 + 8 * x + 5 * y + 60 * c) % 256;
                    t = (x >= 8 && x < 14 && y >= 6 && y < 12) ? ((200 - 90 * c) % 256 + 256) % 256 : r;
                } else if (index == 1) {  // fine noise against a slightly different noise
                    r = (x * 37 + y * 91 + c * 53 + (x * y) % 7 * 11) % 256;
                    t = ((r + (x * 13 + y * 7 + c * 29) % 41 - 20) % 256 + 256) % 256;
                } else {  // two-pixel stripes against their mean grey, with a hue shift
                    r = (x / 2) % 2 == 0 ? 230 : 30;
                    if (c == 2) r = 255 - r;
                    t = c != 1 ? 130 : 110;
                }
                ref.pixel(x, y)[c] = float(r) / 255.0f;
                test.pixel(x, y)[c] = float(t) / 255.0f;
            }
    return {ref, test};
}

// The whole LDR-FLIP (filters included) against pinned means computed with NVIDIA's reference
// implementation (its v1.2 Python, NVlabs/flip commit dde1eca, `compute_ldrflip` at 67.02 pixels
// per degree, run outside the project with a numpy stand-in for OpenCV's filter2D with
// BORDER_REPLICATE; its code is not in the project). It takes sRGB-encoded images and these pairs
// are linear, so it was given their sRGB encoding. scripts/flip_reference.py, an independent
// Python/numpy implementation written from the paper, gives 0.131813, 0.259296 and 0.524454 (within
// 3e-6). The other FLIP tests check the filters only qualitatively; a wrong kernel width changes
// these means by 1e-3 or more (the script prints them with the CSF radius and the feature width
// halved).
TEST(Flip, MatchesNvidiasReferenceImplementation) {
    const double pinned[] = {0.131816, 0.259295, 0.524451};
    for (int i = 0; i < 3; ++i) {
        const auto [ref, test] = flipPair(i);
        EXPECT_NEAR(flipMean(ref, test), pinned[i], 1e-4) << "pair " << i;
    }
}

TEST(Flip, BlackVersusWhiteIsNearOne) {
    const double expected = expectedFlatFlip(0, 0, 0, 1, 1, 1);
    EXPECT_NEAR(expected, 0.9675, 1e-3);
    FlipResult r = flip(flat(24, 24, 0, 0, 0), flat(24, 24, 1, 1, 1));
    EXPECT_NEAR(r.mean, expected, 1e-4);
    expectUniformMap(r, expected, 1e-4);
    // Green vs blue is the normalising pair: exactly the maximum error.
    EXPECT_NEAR(flip(flat(24, 24, 0, 1, 0), flat(24, 24, 0, 0, 1)).mean, 1.0, 1e-5);
}

TEST(Flip, InputsAreClampedToUnitRange) {
    FlipResult r = flip(flat(16, 16, 2.0, 1.5, 1.0), flat(16, 16, 1.0, 1.0, 1.0));
    EXPECT_EQ(r.mean, 0.0);
}

TEST(Flip, MeanGrowsMonotonicallyWithNoise) {
    const int w = 48, h = 40;
    const Image base = noiseBase(w, h);
    std::mt19937 rng(12345);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> noise(base.rgba.size());
    for (float& v : noise) v = u(rng);
    double previous = 0.0;
    for (float amount : {0.01f, 0.03f, 0.08f, 0.15f, 0.3f}) {
        Image noisy = base;
        for (size_t i = 0; i < noisy.rgba.size(); ++i)
            if (i % 4 != 3) noisy.rgba[i] = std::clamp(base.rgba[i] + amount * noise[i], 0.0f, 1.0f);
        const double m = flip(base, noisy).mean;
        EXPECT_GT(m, previous) << "noise amount " << amount;
        previous = m;
    }
    EXPECT_LT(previous, 1.0);
}

TEST(Flip, ErrorMapIsInUnitRangeAndGrey) {
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u(-0.5f, 1.5f);  // also exercises input clamping
    Image a(37, 29), b(37, 29);
    for (float& v : a.rgba) v = u(rng);
    for (float& v : b.rgba) v = u(rng);
    FlipResult r = flip(a, b);
    ASSERT_EQ(r.errorMap.width, 37);
    ASSERT_EQ(r.errorMap.height, 29);
    double sum = 0.0;
    for (size_t i = 0; i < r.errorMap.pixelCount(); ++i) {
        const float* p = &r.errorMap.rgba[i * 4];
        ASSERT_GE(p[0], 0.0f);
        ASSERT_LE(p[0], 1.0f);
        ASSERT_EQ(p[0], p[1]);
        ASSERT_EQ(p[0], p[2]);
        ASSERT_EQ(p[3], 1.0f);
        sum += p[0];
    }
    EXPECT_NEAR(r.mean, sum / double(r.errorMap.pixelCount()), 1e-9);
    EXPECT_GT(r.mean, 0.3);
}

TEST(Flip, IsSymmetric) {
    Image a = noiseBase(33, 21), b = noiseBase(33, 21);
    for (int x = 10; x < 20; ++x) b.pixel(x, 10)[1] = 0.9f;
    EXPECT_EQ(flip(a, b).mean, flip(b, a).mean);
}

// A 1-pixel black/white checkerboard seen from far away (many pixels per degree) blurs into its
// mean: against flat grey of the same linear luminance the error is small. Seen from close by
// (few pixels per degree) the CSF barely blurs and the error is large.
TEST(Flip, CsfHidesFineDetailAtHighPixelsPerDegree) {
    Image checker(64, 64, 1.0f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            for (int c = 0; c < 3; ++c) checker.pixel(x, y)[c] = float((x + y) % 2);
    const Image grey = flat(64, 64, 0.5, 0.5, 0.5);
    const double far = flip(checker, grey, 67.02).mean;
    const double near = flip(checker, grey, 4.0).mean;
    EXPECT_LT(far, 0.1);
    EXPECT_GT(near, 0.5);
}

// One changed pixel: the error is confined to the filters' reach (CSF radius ceil(3 * sqrt(0.04 /
// (2 pi^2)) * 67.02) = 10, feature radius ceil(3 * 0.041 * 67.02) = 9 pixels) and largest there.
TEST(Flip, SinglePixelChangeStaysLocal) {
    const Image a = flat(64, 48, 0.4, 0.4, 0.4);
    Image b = a;
    b.pixel(30, 20)[0] = 1.0f;
    const FlipResult r = flip(a, b);
    float maxErr = 0.0f;
    int maxX = -1, maxY = -1;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            const float e = r.errorMap.pixel(x, y)[0];
            if (std::abs(x - 30) > 10 || std::abs(y - 20) > 10) ASSERT_EQ(e, 0.0f) << x << "," << y;
            if (e > maxErr) maxErr = e, maxX = x, maxY = y;
        }
    EXPECT_EQ(maxX, 30);
    EXPECT_EQ(maxY, 20);
    EXPECT_GT(r.errorMap.pixel(30, 25)[0], 0.0f);  // spread vertically as well as horizontally
    EXPECT_GT(r.errorMap.pixel(35, 20)[0], 0.0f);
}

TEST(Flip, SizeMismatchAndEmptyImagesThrow) {
    EXPECT_THROW(flip(Image(4, 4), Image(4, 5)), Error);
    EXPECT_THROW(flip(Image(0, 0), Image(0, 0)), Error);
    EXPECT_THROW(flip(Image(4, 4), Image(4, 4), 0.0), Error);
    try {
        flip(Image(4, 4), Image(5, 4));
        FAIL() << "expected starnt::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("4x4"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("5x4"), std::string::npos) << e.what();
    }
}

TEST(Flip, HeatmapUsesMagmaEndsAndRisesInBrightness) {
    Image err(11, 1, 1.0f);
    for (int x = 0; x < 11; ++x)
        for (int c = 0; c < 3; ++c) err.pixel(x, 0)[c] = float(x) / 10.0f;
    const Image heat = flipHeatmap(err);
    ASSERT_EQ(heat.width, 11);
    ASSERT_EQ(heat.height, 1);
    // magma(0) = #000004, magma(1) = #fcfdbf (sRGB)
    EXPECT_NEAR(linearToSrgb(heat.pixel(0, 0)[2]) * 255.0f, 4.0f, 1e-3);
    EXPECT_NEAR(linearToSrgb(heat.pixel(0, 0)[0]) * 255.0f, 0.0f, 1e-3);
    EXPECT_NEAR(linearToSrgb(heat.pixel(10, 0)[0]) * 255.0f, 252.0f, 1e-3);
    EXPECT_NEAR(linearToSrgb(heat.pixel(10, 0)[2]) * 255.0f, 191.0f, 1e-3);
    float previous = -1.0f;
    for (int x = 0; x < 11; ++x) {
        const float* p = heat.pixel(x, 0);
        const float lum = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
        EXPECT_GT(lum, previous) << x;
        previous = lum;
        EXPECT_EQ(p[3], 1.0f);
    }
}

// Timing check, not part of the normal run: build with -O3 (Release) and run
//   test_metrics --gtest_also_run_disabled_tests --gtest_filter='*Timing*'
TEST(Flip, DISABLED_Timing1280x720) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image a(1280, 720, 1.0f), b(1280, 720, 1.0f);
    for (float& v : a.rgba) v = u(rng);
    for (size_t i = 0; i < b.rgba.size(); ++i) b.rgba[i] = std::clamp(a.rgba[i] + 0.1f * (u(rng) - 0.5f), 0.0f, 1.0f);
    flip(a, b);  // warm up
    const int runs = 5;
    const auto t0 = std::chrono::steady_clock::now();
    double m = 0.0;
    for (int i = 0; i < runs; ++i) m += flip(a, b).mean;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / runs;
    std::printf("flip 1280x720: %.3f s per call (mean %.4f)\n", s, m / runs);
    EXPECT_LT(s, 2.0);
}

// ---- MSE ----------------------------------------------------------------------------------------

TEST(Mse, TinyImagesMatchHandComputation) {
    // sRGB values; squared differences: .01, 0, .01 | .01, .04, 0 -> sum .07 over 6 channels.
    const Image ref = fromSrgb(2, 1, {0.5, 0.25, 1.0, 0.0, 0.2, 0.8});
    const Image tst = fromSrgb(2, 1, {0.6, 0.25, 0.9, 0.1, 0.0, 0.8});
    EXPECT_NEAR(mseSrgb(ref, tst), 0.07 / 6.0, 1e-6);
    EXPECT_NEAR(mseSrgb(tst, ref), 0.07 / 6.0, 1e-6);
}

TEST(Mse, ClampsAndIgnoresAlpha) {
    Image a = flat(2, 1, 2.0, -1.0, 0.5), b = flat(2, 1, 1.0, 0.0, 0.5);
    b.rgba[3] = 0.0f;
    EXPECT_EQ(mseSrgb(a, b), 0.0);
    // black vs white in one of three channels: (1 - 0)^2 / 3
    EXPECT_NEAR(mseSrgb(flat(1, 1, 0, 0, 0), flat(1, 1, 1, 0, 0)), 1.0 / 3.0, 1e-12);
}

TEST(Mse, IdenticalIsZero) {
    const Image a = noiseBase(9, 7);
    EXPECT_EQ(mseSrgb(a, a), 0.0);
}

TEST(Mse, SizeMismatchThrowsNamingBothSizes) {
    try {
        mseSrgb(Image(2, 1), Image(1, 2));
        FAIL() << "expected starnt::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2x1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1x2"), std::string::npos) << e.what();
    }
}
