#include "reference/mboit_cpu.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace starnt::mboit {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// Solves M q = rhs (size n + 1 <= 4) by Gaussian elimination with partial pivoting.
std::vector<Complex> solve(std::vector<std::vector<Complex>> m, std::vector<Complex> rhs) {
    const size_t n = rhs.size();
    for (size_t col = 0; col < n; ++col) {
        size_t pivot = col;
        for (size_t r = col + 1; r < n; ++r) {
            if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
        }
        std::swap(m[col], m[pivot]);
        std::swap(rhs[col], rhs[pivot]);
        for (size_t r = col + 1; r < n; ++r) {
            const Complex f = m[r][col] / m[col][col];
            for (size_t c = col; c < n; ++c) m[r][c] -= f * m[col][c];
            rhs[r] -= f * rhs[col];
        }
    }
    std::vector<Complex> x(n);
    for (size_t i = n; i-- > 0;) {
        Complex s = rhs[i];
        for (size_t c = i + 1; c < n; ++c) s -= m[i][c] * x[c];
        x[i] = s / m[i][i];
    }
    return x;
}

Complex evaluate(const std::vector<Complex>& coefficients, Complex x) {
    Complex y = 0.0;
    for (size_t k = coefficients.size(); k-- > 0;) y = y * x + coefficients[k];
    return y;
}

// Roots of sum c_k x^k (degree n = c.size() - 1) by the Durand-Kerner iteration.
std::vector<Complex> polynomialRoots(std::vector<Complex> c) {
    const size_t n = c.size() - 1;
    const Complex lead = c[n];
    for (Complex& v : c) v /= lead;
    std::vector<Complex> roots(n);
    for (size_t i = 0; i < n; ++i) roots[i] = std::pow(Complex(0.4, 0.9), double(i));
    for (int iteration = 0; iteration < 500; ++iteration) {
        double change = 0.0;
        for (size_t i = 0; i < n; ++i) {
            Complex denominator = 1.0;
            for (size_t j = 0; j < n; ++j) {
                if (j != i) denominator *= roots[i] - roots[j];
            }
            const Complex step = evaluate(c, roots[i]) / denominator;
            roots[i] -= step;
            change = std::max(change, std::abs(step));
        }
        if (change < 1e-15) break;
    }
    return roots;
}

// sum_k p_k b_k for the polynomial p of degree n through (x_i, f_i), i = 0..n (Newton form).
Complex interpolatedMomentSum(const std::vector<Complex>& x, const std::vector<double>& f, const std::vector<Complex>& b) {
    const size_t n = x.size() - 1;
    std::vector<Complex> d(f.begin(), f.end());
    for (size_t j = 1; j <= n; ++j) {
        for (size_t i = n; i >= j; --i) d[i] = (d[i] - d[i - 1]) / (x[i] - x[i - j]);
    }
    std::vector<Complex> p{d[n]};  // monomial coefficients, lowest first
    for (size_t i = n; i-- > 0;) {
        std::vector<Complex> next(p.size() + 1, 0.0);
        for (size_t k = 0; k < p.size(); ++k) {
            next[k + 1] += p[k];
            next[k] -= p[k] * x[i];
        }
        next[0] += d[i];
        p = std::move(next);
    }
    Complex sum = 0.0;
    for (size_t k = 0; k <= n; ++k) sum += p[k] * b[k];
    return sum;
}

}  // namespace

DepthWarp DepthWarp::fromProjection(const glm::mat4& projection) {
    const double p22 = projection[2][2], p32 = projection[3][2];
    if (projection[2][3] == 0.0f) return DepthWarp{0.0, 0.0, true};
    return DepthWarp{p32 / (p22 - 1.0), p32 / (p22 + 1.0)};
}

double DepthWarp::viewDepth(double windowDepth) const {
    const double ndc = windowDepth * 2.0 - 1.0;
    return 2.0 * farPlane * nearPlane / ((farPlane + nearPlane) - ndc * (farPlane - nearPlane));
}

double DepthWarp::warp(double windowDepth) const {
    if (affine) return std::clamp(windowDepth * 2.0 - 1.0, -1.0, 1.0);
    const double z = 2.0 * std::log(viewDepth(windowDepth) / nearPlane) / std::log(farPlane / nearPlane) - 1.0;
    return std::clamp(z, -1.0, 1.0);
}

double warpedDepthToPhase(double z) { return (z + 1.0) * (kPi - 0.5 * double(kWrappingZoneAngle)); }

double absorbance(float alpha) { return -std::log(1.0 - double(std::min(alpha, kMaxAlpha))); }

void addMoment(Moments& m, double z, float alpha) {
    const double a = absorbance(alpha);
    const MomentSetting& s = momentSetting(m.kind);
    m.b0 += a;
    if (s.trigonometric) {
        const double phi = warpedDepthToPhase(z);
        for (int k = 0; k < s.count; ++k) m.trig[size_t(k)] += a * std::polar(1.0, double(k + 1) * phi);
    } else {
        double zk = 1.0;
        for (int k = 0; k < s.count; ++k) {
            zk *= z;
            m.power[size_t(k)] += a * zk;
        }
    }
}

Moments accumulateMoments(const FragmentList& fragments, MomentKind kind, const DepthWarp& warp) {
    Moments m;
    m.kind = kind;
    for (const Fragment& f : fragments) addMoment(m, warp.warp(f.depth), f.alpha);
    return m;
}

Bounds absorbanceBounds(const Moments& moments, double z) {
    if (!(moments.b0 > 0.0)) return {};
    const MomentSetting& s = momentSetting(moments.kind);
    const size_t n = size_t(s.order);
    const double beta = s.bias;
    // Normalised, biased moments b_0..b_m (b_0 = 1).
    std::vector<Complex> b(size_t(s.count) + 1);
    b[0] = 1.0;
    for (size_t k = 1; k <= size_t(s.count); ++k) {
        if (s.trigonometric) {
            b[k] = (1.0 - beta) * moments.trig[k - 1] / moments.b0;
        } else {
            b[k] = (1.0 - beta) * moments.power[k - 1] / moments.b0 + beta * double(s.biasVector[k - 1]);
        }
    }
    // Hankel (power: M_jk = b_{j+k}) or Toeplitz (trigonometric: M_jk = b_{j-k}, b_{-k} = conj b_k)
    // matrix of the moments: M = sum_i w_i v(x_i) v(x_i)^H with v(x) = (1, x, .., x^n).
    std::vector<std::vector<Complex>> matrix(n + 1, std::vector<Complex>(n + 1));
    for (size_t j = 0; j <= n; ++j) {
        for (size_t k = 0; k <= n; ++k) {
            if (!s.trigonometric) {
                matrix[j][k] = b[j + k];
            } else {
                matrix[j][k] = j >= k ? b[j - k] : std::conj(b[k - j]);
            }
        }
    }
    const double phase = s.trigonometric ? warpedDepthToPhase(z) : 0.0;
    const Complex x0 = s.trigonometric ? std::polar(1.0, phase) : Complex(z);
    std::vector<Complex> v(n + 1);
    for (size_t j = 0; j <= n; ++j) v[j] = std::pow(x0, double(j));
    // The kernel polynomial sum_k conj(q_k) x^k with M q = v(x0) is 1 / w_0 at x0 and zero at the n
    // other support points of the canonical representation of the moments that contains x0.
    std::vector<Complex> q = solve(matrix, v);
    for (Complex& c : q) c = std::conj(c);
    std::vector<Complex> points{x0};
    for (Complex r : polynomialRoots(q)) points.push_back(s.trigonometric ? r / std::abs(r) : Complex(r.real()));
    // Indicator of "in front of x0" at each other support point; the wrapping zone of the circle
    // ramps linearly from behind (0, after the farthest depth) to in front (1, before the nearest).
    std::vector<double> f(n + 1, 0.0);
    for (size_t i = 1; i <= n; ++i) {
        if (!s.trigonometric) {
            f[i] = points[i].real() < z ? 1.0 : 0.0;
        } else {
            double angle = std::arg(points[i]);
            if (angle < 0.0) angle += 2.0 * kPi;
            const double zoneStart = 2.0 * kPi - double(kWrappingZoneAngle);
            f[i] = angle > zoneStart ? (angle - zoneStart) / double(kWrappingZoneAngle) : (angle < phase ? 1.0 : 0.0);
        }
    }
    // sum_i w_i f_i = sum_k p_k b_k for the interpolating polynomial p (the canonical representation
    // reproduces b_0..b_n); f_0 = 0 gives the lower bound, f_0 = 1 the upper bound.
    Bounds bounds;
    bounds.lower = interpolatedMomentSum(points, f, b).real();
    f[0] = 1.0;
    bounds.upper = interpolatedMomentSum(points, f, b).real();
    return bounds;
}

double transmittanceAt(const Moments& moments, double z, double overestimation) {
    if (!(moments.b0 > 0.0)) return 1.0;
    const Bounds bounds = absorbanceBounds(moments, z);
    const double fraction = std::clamp((1.0 - overestimation) * bounds.lower + overestimation * bounds.upper, 0.0, 1.0);
    return std::exp(-moments.b0 * fraction);
}

glm::vec3 compositePixel(const FragmentList& fragments, MomentKind kind, const DepthWarp& warp,
                         const glm::vec3& background) {
    const Moments m = accumulateMoments(fragments, kind, warp);
    if (!(m.b0 > 0.0)) return background;
    glm::dvec3 colour(0.0);
    double weight = 0.0;
    for (const Fragment& f : fragments) {
        const double w = double(f.alpha) * transmittanceAt(m, warp.warp(f.depth));
        colour += glm::dvec3(f.color) * w;
        weight += w;
    }
    const double total = std::exp(-m.b0);
    const glm::dvec3 average = weight > 0.0 ? colour / weight : glm::dvec3(0.0);
    return glm::vec3(average * (1.0 - total) + glm::dvec3(background) * total);
}

}  // namespace starnt::mboit
