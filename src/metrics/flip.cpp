// LDR-FLIP, implemented from the description in Andersson, Nilsson, Akenine-Moller, Oskarsson,
// Astrom and Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020.
//
// Colour pipeline: linear RGB -> XYZ -> YCxCz (opponent space); each channel is filtered with the
// paper's contrast sensitivity functions (sums of Gaussians in the spatial domain); the filtered
// values go back to linear RGB, are clamped to [0, 1] and converted to CIELab; chroma gets the Hunt
// adjustment (a, b scaled by 0.01 L); the HyAB distance is raised to q_c and remapped with p_c, p_t
// against the distance between Hunt-adjusted green and blue.
// Feature pipeline: edge (Gaussian first derivative) and point (Gaussian second derivative)
// detectors on the luminance Y/Yn of each input; the larger of the two magnitude differences,
// divided by sqrt(2), raised to q_f. Final error: colour error ^ (1 - feature error).
//
// Choices where the paper leaves room (documented so they can be checked):
//  - Image borders: filters read clamp-to-edge (replicated) pixels, so a flat image stays flat
//    everywhere and a flat pair gives the same error at every pixel.
//  - One kernel radius for all three CSF channels, from the widest Gaussian (b = 0.04):
//    r = ceil(3 * sqrt(b_max / (2 pi^2)) * ppd). Each channel's kernel is normalised to sum 1.
//    The kernels are separable per Gaussian term; the blue-yellow channel (two terms) is filtered
//    with each term separately and the results are combined with the weights the normalised 2D
//    kernel gives them, which is exactly the same as filtering with the normalised 2D kernel.
//  - Feature kernels: sigma = 0.5 * w * ppd pixels (w = 0.082 deg), radius ceil(3 sigma). The
//    derivative kernels are normalised so their positive weights sum to 1 and their negative
//    weights to -1 (the Gaussian factor across the derivative direction is normalised to sum 1,
//    which gives the same sums for the 2D kernel).
//  - XYZ uses the sRGB/D65 matrix; the reference white is XYZ of linear RGB (1, 1, 1).
//  - The image is processed in bands of rows, each read with a halo of the larger filter radius
//    (rows clamped to the image), so the result is exactly the full-image result while the working
//    memory is a band's (about 2 Mpixel) instead of a dozen full-size float planes.
//  - Pixels per degree are limited to kFlipMinPixelsPerDegree..kFlipMaxPixelsPerDegree (1..1000).
//  - The remapped colour error is clamped to [0, 1] (a safety net: in the RGB cube green/blue is the
//    maximum pair the paper uses; no other pair is expected to exceed it).
#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <mutex>
#include <system_error>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

namespace starnt {

namespace {

constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;  // colour error remapping
constexpr double kW = 0.082, kQf = 0.5;             // feature detector width (deg), exponent

// linear sRGB (D65) -> XYZ
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};

struct Mat3 {
    double m[3][3];
};

Mat3 inverse(const double (&a)[3][3]) {
    Mat3 r{};
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    r.m[0][0] = (a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det;
    r.m[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
    r.m[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
    r.m[1][0] = (a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det;
    r.m[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
    r.m[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
    r.m[2][0] = (a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det;
    r.m[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
    r.m[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
    return r;
}

// Per-run constants of the colour transforms, in float for the per-pixel work.
struct ColourConstants {
    float toXyz[3][3];
    float toRgb[3][3];
    float white[3];  // Xn, Yn, Zn
    float invWhite[3];
    ColourConstants() {
        const Mat3 inv = inverse(kRgbToXyz);
        for (int i = 0; i < 3; ++i) {
            double w = 0.0;
            for (int j = 0; j < 3; ++j) {
                toXyz[i][j] = float(kRgbToXyz[i][j]);
                toRgb[i][j] = float(inv.m[i][j]);
                w += kRgbToXyz[i][j];
            }
            white[i] = float(w);
            invWhite[i] = float(1.0 / w);
        }
    }
};

const ColourConstants& colour() {
    static const ColourConstants c;
    return c;
}

// Cube root for t > 0: exponent-splitting initial guess (a few % off) refined by two Halley steps
// (cubic convergence: ~3e-2 -> ~3e-5 -> float precision). libm's cbrtf was a quarter of the run time.
inline float fastCbrt(float t) {
    uint32_t bits = std::bit_cast<uint32_t>(t);
    bits = bits / 3u + 709921077u;  // 709921077 = (127 - 127 / 3) << 23, adjusted for the mantissa
    float y = std::bit_cast<float>(bits);
    for (int i = 0; i < 2; ++i) {
        const float y3 = y * y * y;
        y = y * (y3 + 2.0f * t) / (2.0f * y3 + t);
    }
    return y;
}

// CIELab f(t) with its linear segment near 0.
inline float labF(float t) {
    constexpr float d = 6.0f / 29.0f;
    return t > d * d * d ? fastCbrt(t) : t / (3.0f * d * d) + 4.0f / 29.0f;
}

// linear RGB (already clamped) -> Hunt-adjusted CIELab (L, 0.01 L a, 0.01 L b)
inline void rgbToHuntLab(const float rgb[3], float out[3]) {
    const ColourConstants& k = colour();
    float f[3];
    for (int i = 0; i < 3; ++i) {
        const float v = k.toXyz[i][0] * rgb[0] + k.toXyz[i][1] * rgb[1] + k.toXyz[i][2] * rgb[2];
        f[i] = labF(v * k.invWhite[i]);
    }
    const float L = 116.0f * f[1] - 16.0f;
    out[0] = L;
    out[1] = 0.01f * L * 500.0f * (f[0] - f[1]);
    out[2] = 0.01f * L * 200.0f * (f[1] - f[2]);
}

inline float hyab(const float a[3], const float b[3]) {
    const float da = a[1] - b[1], db = a[2] - b[2];
    return std::fabs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

// Maximum colour distance the paper normalises by: HyAB(green, blue)^q_c.
double maxColourDistance() {
    const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    float g[3], b[3];
    rgbToHuntLab(green, g);
    rgbToHuntLab(blue, b);
    return std::pow(double(hyab(g, b)), kQc);
}

// ---- separable filtering with clamp-to-edge borders -------------------------------------------

using Plane = std::vector<float>;

// dst(x, y) = sum_i k[i] * src(clamp(x + i - r), y)
void filterRows(const Plane& src, Plane& dst, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size() / 2);
    std::vector<float> pad(size_t(w + 2 * r));
    dst.assign(size_t(w) * size_t(h), 0.0f);
    for (int y = 0; y < h; ++y) {
        const float* s = &src[size_t(y) * size_t(w)];
        for (int i = 0; i < w + 2 * r; ++i) pad[size_t(i)] = s[std::clamp(i - r, 0, w - 1)];
        float* d = &dst[size_t(y) * size_t(w)];
        for (size_t t = 0; t < k.size(); ++t) {
            const float kt = k[t];
            const float* p = pad.data() + t;
            for (int x = 0; x < w; ++x) d[x] += kt * p[x];
        }
    }
}

// dst(x, y) = sum_i k[i] * src(x, clamp(y + i - r))
void filterCols(const Plane& src, Plane& dst, int w, int h, const std::vector<float>& k) {
    const int r = int(k.size() / 2);
    dst.assign(size_t(w) * size_t(h), 0.0f);
    for (int y = 0; y < h; ++y) {
        float* d = &dst[size_t(y) * size_t(w)];
        for (size_t t = 0; t < k.size(); ++t) {
            const float kt = k[t];
            const float* s = &src[size_t(std::clamp(y + int(t) - r, 0, h - 1)) * size_t(w)];
            for (int x = 0; x < w; ++x) d[x] += kt * s[x];
        }
    }
}

// ---- contrast sensitivity filters ---------------------------------------------------------------

// One Gaussian term a * sqrt(pi / b) * exp(-pi^2 x^2 / b) of the paper's spatial CSF (x in degrees).
struct CsfTerm {
    double a, b;
};
// Achromatic, red-green, blue-yellow (the paper's parameter table; a2 = 0 for the first two).
const std::array<std::vector<CsfTerm>, 3> kCsf = {{
    {{1.0, 0.0047}},
    {{1.0, 0.0053}},
    {{34.1, 0.04}, {13.5, 0.025}},
}};

struct SeparableTerm {
    std::vector<float> kernel;  // 1D, normalised to sum 1
    float weight = 1.0f;        // share of this term in the normalised 2D kernel
};

std::vector<SeparableTerm> csfTerms(const std::vector<CsfTerm>& terms, int radius, double ppd) {
    std::vector<SeparableTerm> out;
    std::vector<double> mass;  // sum of the unnormalised 2D term = a sqrt(pi/b) (sum_i g_i)^2
    double total = 0.0;
    for (const CsfTerm& t : terms) {
        std::vector<double> g(size_t(2 * radius + 1));
        double s = 0.0;
        for (int i = -radius; i <= radius; ++i) {
            const double x = double(i) / ppd;
            g[size_t(i + radius)] = std::exp(-std::numbers::pi * std::numbers::pi * x * x / t.b);
            s += g[size_t(i + radius)];
        }
        SeparableTerm st;
        for (double v : g) st.kernel.push_back(float(v / s));
        const double m = t.a * std::sqrt(std::numbers::pi / t.b) * s * s;
        mass.push_back(m);
        total += m;
        out.push_back(std::move(st));
    }
    for (size_t i = 0; i < out.size(); ++i) out[i].weight = float(mass[i] / total);
    return out;
}

void applyCsf(Plane& plane, int w, int h, const std::vector<SeparableTerm>& terms) {
    Plane tmp, filtered, acc;
    for (size_t i = 0; i < terms.size(); ++i) {
        filterRows(plane, tmp, w, h, terms[i].kernel);
        filterCols(tmp, filtered, w, h, terms[i].kernel);
        if (terms.size() == 1) {
            plane.swap(filtered);
            return;
        }
        if (i == 0) acc.assign(filtered.size(), 0.0f);
        const float wt = terms[i].weight;
        for (size_t p = 0; p < acc.size(); ++p) acc[p] += wt * filtered[p];
    }
    plane.swap(acc);
}

// ---- per-image work -----------------------------------------------------------------------------

struct Prepared {
    std::array<Plane, 3> ycxcz;  // CSF-filtered opponent channels
    Plane luminance;             // Y / Yn of the clamped input, for the feature detectors
};

Prepared prepare(const Image& img, const std::array<std::vector<SeparableTerm>, 3>& csf) {
    const ColourConstants& k = colour();
    const size_t n = img.pixelCount();
    Prepared p;
    for (auto& c : p.ycxcz) c.resize(n);
    p.luminance.resize(n);
    for (size_t i = 0; i < n; ++i) {
        float rgb[3];
        for (int c = 0; c < 3; ++c) {
            const float v = img.rgba[i * 4 + size_t(c)];
            rgb[c] = v > 0.0f ? std::min(v, 1.0f) : 0.0f;  // clamp to [0, 1], NaN -> 0
        }
        float xyz[3];
        for (int r = 0; r < 3; ++r)
            xyz[r] = (k.toXyz[r][0] * rgb[0] + k.toXyz[r][1] * rgb[1] + k.toXyz[r][2] * rgb[2]) * k.invWhite[r];
        p.ycxcz[0][i] = 116.0f * xyz[1] - 16.0f;
        p.ycxcz[1][i] = 500.0f * (xyz[0] - xyz[1]);
        p.ycxcz[2][i] = 200.0f * (xyz[1] - xyz[2]);
        p.luminance[i] = xyz[1];
    }
    for (int c = 0; c < 3; ++c) applyCsf(p.ycxcz[size_t(c)], img.width, img.height, csf[size_t(c)]);
    return p;
}

// Filtered YCxCz at pixel i -> linear RGB clamped to [0, 1] -> Hunt-adjusted Lab.
inline void filteredToHuntLab(const Prepared& p, size_t i, float out[3]) {
    const ColourConstants& k = colour();
    const float yr = (p.ycxcz[0][i] + 16.0f) / 116.0f;  // Y / Yn
    const float xyz[3] = {(p.ycxcz[1][i] / 500.0f + yr) * k.white[0], yr * k.white[1],
                          (yr - p.ycxcz[2][i] / 200.0f) * k.white[2]};
    float rgb[3];
    for (int r = 0; r < 3; ++r) {
        const float v = k.toRgb[r][0] * xyz[0] + k.toRgb[r][1] * xyz[1] + k.toRgb[r][2] * xyz[2];
        rgb[r] = std::clamp(v, 0.0f, 1.0f);
    }
    rgbToHuntLab(rgb, out);
}

struct FeatureKernels {
    std::vector<float> gauss, first, second;
};

// Positive weights scaled to sum to 1, negative ones to sum to -1.
void normaliseSigned(std::vector<double>& k) {
    double pos = 0.0, neg = 0.0;
    for (double v : k) (v > 0 ? pos : neg) += v;
    for (double& v : k) v = v > 0 ? v / pos : (v < 0 ? v / -neg : 0.0);
}

// ceil(extent) as a kernel radius in pixels. flip() checks ppd (<= kFlipMaxPixelsPerDegree) first, so
// the radii stay below 140 pixels; the check here keeps the conversion to int defined regardless.
int kernelRadius(double extent) {
    const double r = std::ceil(extent);
    if (!(r >= 0.0 && r <= 4096.0)) throw Error("flip: filter radius " + std::to_string(r) + " pixels out of range");
    return int(r);
}

FeatureKernels featureKernels(double ppd) {
    const double sigma = 0.5 * kW * ppd;
    const int r = kernelRadius(3.0 * sigma);
    std::vector<double> g, d1, d2;
    double gs = 0.0;
    for (int i = -r; i <= r; ++i) {
        const double x = double(i);
        const double e = std::exp(-x * x / (2.0 * sigma * sigma));
        g.push_back(e);
        gs += e;
        d1.push_back(-x * e);
        d2.push_back((x * x / (sigma * sigma) - 1.0) * e);
    }
    normaliseSigned(d1);
    normaliseSigned(d2);
    FeatureKernels k;
    for (size_t i = 0; i < g.size(); ++i) {
        k.gauss.push_back(float(g[i] / gs));
        k.first.push_back(float(d1[i]));
        k.second.push_back(float(d2[i]));
    }
    return k;
}

// Edge magnitude |(Y*Gx, Y*Gy)| and point magnitude |(Y*Gxx, Y*Gyy)| per pixel.
void featureMagnitudes(const Plane& y, int w, int h, const FeatureKernels& k, Plane& edge, Plane& point) {
    Plane rowsG, rowsD1, rowsD2, a, b;
    filterRows(y, rowsG, w, h, k.gauss);
    filterRows(y, rowsD1, w, h, k.first);
    filterRows(y, rowsD2, w, h, k.second);
    filterCols(rowsD1, a, w, h, k.gauss);  // d/dx
    filterCols(rowsG, b, w, h, k.first);   // d/dy
    edge.resize(a.size());
    for (size_t i = 0; i < a.size(); ++i) edge[i] = std::sqrt(a[i] * a[i] + b[i] * b[i]);
    filterCols(rowsD2, a, w, h, k.gauss);  // d2/dx2
    filterCols(rowsG, b, w, h, k.second);  // d2/dy2
    point.resize(a.size());
    for (size_t i = 0; i < a.size(); ++i) point[i] = std::sqrt(a[i] * a[i] + b[i] * b[i]);
}

std::string sizeText(const Image& im) { return std::to_string(im.width) + "x" + std::to_string(im.height); }

}  // namespace

namespace {

// Rows clamp(y0 - halo) .. clamp(y1 + halo - 1) of `img` as an image of their own: the rows a band
// [y0, y1) of the result reads through filters of radius <= halo, with the image's clamp-to-edge
// borders already applied, so filtering the band gives exactly the full image's values there.
Image bandOf(const Image& img, int y0, int y1, int halo) {
    Image band;
    band.width = img.width;
    band.height = (y1 - y0) + 2 * halo;
    const size_t rowFloats = size_t(img.width) * 4;
    band.rgba.resize(size_t(band.height) * rowFloats);
    for (int r = 0; r < band.height; ++r) {
        const int sy = std::clamp(y0 - halo + r, 0, img.height - 1);
        std::copy_n(img.rgba.begin() + std::ptrdiff_t(size_t(sy) * rowFloats), rowFloats,
                    band.rgba.begin() + std::ptrdiff_t(size_t(r) * rowFloats));
    }
    return band;
}

// The FLIP error of every pixel, computed in bands of rows (each with a halo of the filters'
// radius) so the working memory is a band's, not the image's; the error map is written when asked.
double flipBands(const Image& reference, const Image& test, double pixelsPerDegree, Image* errorMap) {
    if (reference.width != test.width || reference.height != test.height)
        throw Error("flip: image sizes differ: reference " + sizeText(reference) + ", test " + sizeText(test));
    if (reference.width <= 0 || reference.height <= 0)
        throw Error("flip: empty images (" + sizeText(reference) + ")");
    if (reference.rgba.size() != reference.pixelCount() * 4 || test.rgba.size() != test.pixelCount() * 4)
        throw Error("flip: pixel buffer size does not match the image size");
    if (!std::isfinite(pixelsPerDegree) || !(pixelsPerDegree >= kFlipMinPixelsPerDegree) ||
        !(pixelsPerDegree <= kFlipMaxPixelsPerDegree)) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "flip: pixels per degree must be within %g..%g, got %g", kFlipMinPixelsPerDegree,
                      kFlipMaxPixelsPerDegree, pixelsPerDegree);
        throw Error(buf);
    }

    const int w = reference.width, h = reference.height;
    double bMax = 0.0;
    for (const auto& channel : kCsf)
        for (const CsfTerm& t : channel) bMax = std::max(bMax, t.b);
    const int csfRadius = kernelRadius(3.0 * std::sqrt(bMax / (2.0 * std::numbers::pi * std::numbers::pi)) * pixelsPerDegree);
    std::array<std::vector<SeparableTerm>, 3> csf;
    for (size_t c = 0; c < 3; ++c) csf[c] = csfTerms(kCsf[c], csfRadius, pixelsPerDegree);
    const FeatureKernels fk = featureKernels(pixelsPerDegree);
    const int halo = std::max(csfRadius, int(fk.gauss.size() / 2));

    const double dMax = maxColourDistance();
    const float cutoff = float(kPc * dMax);
    const float lowSlope = float(kPt / (kPc * dMax));
    const float highSlope = float((1.0 - kPt) / (dMax - kPc * dMax));
    const float invSqrt2 = float(1.0 / std::numbers::sqrt2);

    if (errorMap) *errorMap = Image(w, h, 1.0f);
    // Bands of at least 4 halos (the halo overhead stays small) and at most about 2 Mpixel (the
    // working memory stays a band's); their count depends on the image alone, never on the thread
    // count, and their sums are added in band order, so the mean is the same on every machine.
    // Bands run on several threads: on a GPU host the bench's CPU FLIP is most of its run time.
    const int bandRows = std::clamp(4 * halo, 16, std::max(16, int((size_t(1) << 21) / size_t(w))));
    const int bandCount = (h + bandRows - 1) / bandRows;
    std::vector<double> bandSums(size_t(bandCount), 0.0);
    const auto runBand = [&](int band) {
        const int y0 = band * bandRows;
        const int y1 = std::min(h, y0 + bandRows);
        const Image refBand = bandOf(reference, y0, y1, halo);
        const Image tstBand = bandOf(test, y0, y1, halo);
        const int bh = refBand.height;
        const Prepared ref = prepare(refBand, csf);
        const Prepared tst = prepare(tstBand, csf);
        Plane edgeR, pointR, edgeT, pointT;
        featureMagnitudes(ref.luminance, w, bh, fk, edgeR, pointR);
        featureMagnitudes(tst.luminance, w, bh, fk, edgeT, pointT);

        double sum = 0.0;
        const size_t first = size_t(halo) * size_t(w), last = first + size_t(y1 - y0) * size_t(w);
        for (size_t i = first; i < last; ++i) {
            float labR[3], labT[3];
            filteredToHuntLab(ref, i, labR);
            filteredToHuntLab(tst, i, labT);
            const float d = std::pow(hyab(labR, labT), float(kQc));
            float colourErr = d < cutoff ? lowSlope * d : float(kPt) + (d - cutoff) * highSlope;
            colourErr = std::clamp(colourErr, 0.0f, 1.0f);

            const float de = std::fabs(edgeR[i] - edgeT[i]);
            const float dp = std::fabs(pointR[i] - pointT[i]);
            static_assert(kQf == 0.5, "the feature exponent is applied as a square root");
            const float featureErr = std::min(1.0f, std::sqrt(std::max(de, dp) * invSqrt2));

            const float e = featureErr == 0.0f ? colourErr : std::pow(colourErr, 1.0f - featureErr);
            if (errorMap) {
                float* px = &errorMap->rgba[(size_t(y0) * size_t(w) + (i - first)) * 4];
                px[0] = px[1] = px[2] = e;
            }
            sum += double(e);
        }
        bandSums[size_t(band)] = sum;
    };
    // Threads take bands in turn; the first error (bad_alloc) is rethrown once they are done.
    std::atomic<int> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    const auto worker = [&] {
        for (int band = next++; band < bandCount; band = next++) {
            try {
                runBand(band);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(failureMutex);
                if (!failure) failure = std::current_exception();
                next = bandCount;
            }
        }
    };
    const int threads = std::min(bandCount, int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u)));
    std::vector<std::thread> pool;
    try {
        for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    } catch (const std::system_error&) {
        // No more threads to be had: the ones started and this one share the bands.
    }
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    double sum = 0.0;
    for (double s : bandSums) sum += s;
    return sum / double(reference.pixelCount());
}

}  // namespace

FlipResult flip(const Image& reference, const Image& test, double pixelsPerDegree) {
    FlipResult result;
    result.mean = flipBands(reference, test, pixelsPerDegree, &result.errorMap);
    return result;
}

double flipMean(const Image& reference, const Image& test, double pixelsPerDegree) {
    return flipBands(reference, test, pixelsPerDegree, nullptr);
}

Image flipHeatmap(const Image& errorMap) {
    // matplotlib magma, sampled at t = 0, 1/8, ..., 1 (sRGB-encoded 8-bit values); linear
    // interpolation between them in sRGB space, then decoded to linear light for the Image.
    static const unsigned char kMagma[9][3] = {
        {0x00, 0x00, 0x04}, {0x1c, 0x10, 0x44}, {0x4f, 0x12, 0x7b}, {0x81, 0x25, 0x81}, {0xb5, 0x36, 0x7a},
        {0xe5, 0x50, 0x64}, {0xfb, 0x87, 0x61}, {0xfe, 0xc2, 0x87}, {0xfc, 0xfd, 0xbf},
    };
    Image out(errorMap.width, errorMap.height, 1.0f);
    const size_t n = std::min(errorMap.pixelCount(), errorMap.rgba.size() / 4);
    for (size_t i = 0; i < n; ++i) {
        float v = errorMap.rgba[i * 4];
        v = v > 0.0f ? std::min(v, 1.0f) : 0.0f;
        const float t = v * 8.0f;
        const int k = std::min(int(t), 7);
        const float f = t - float(k);
        for (int c = 0; c < 3; ++c) {
            const float s = (float(kMagma[k][c]) * (1.0f - f) + float(kMagma[k + 1][c]) * f) / 255.0f;
            out.rgba[i * 4 + size_t(c)] = srgbToLinear(s);
        }
    }
    return out;
}

}  // namespace starnt
