// CPU reference of moment-based OIT (double precision): the moments of a pixel's fragment list, the
// bounds and the transmittance reconstructed from them at a depth, and the whole two-pass composite
// of a pixel. It follows the same formulas as the shaders (mboit_reconstruct.glsl) but is written
// independently (generic linear solve with pivoting, iterative polynomial roots), so the GL tests
// can check the shaders against it. Not used at run time.
#pragma once
#include <array>
#include <complex>

#include <glm/glm.hpp>

#include "methods/mboit/mboit_settings.hpp"
#include "starnt/tools/fragments.hpp"

namespace starnt::mboit {

// Window depth -> the paper's logarithmic warped depth in [-1, 1] (mboit_settings.hpp); under an
// affine (orthographic) projection the normalised depth itself (mboit_common.glsl).
struct DepthWarp {
    double nearPlane = 0.1, farPlane = 100.0;
    bool affine = false;
    // near and far of an OpenGL perspective projection (clip z in [-1, 1]), or an affine one.
    static DepthWarp fromProjection(const glm::mat4& projection);
    double viewDepth(double windowDepth) const;
    double warp(double windowDepth) const;  // clamped to [-1, 1]
};

// Phase on the circle of a warped depth (trigonometric moments).
double warpedDepthToPhase(double z);

struct Moments {
    MomentKind kind = MomentKind::Power6;
    double b0 = 0.0;
    std::array<double, 6> power{};                  // b_1..b_m (power settings)
    std::array<std::complex<double>, 3> trig{};     // b_1..b_m (trigonometric settings)
};

// Absorbance of a fragment: -ln(1 - min(alpha, kMaxAlpha)).
double absorbance(float alpha);
Moments accumulateMoments(const FragmentList& fragments, MomentKind kind, const DepthWarp& warp);
// The same for fragments given directly by warped depth z in [-1, 1] and alpha.
void addMoment(Moments& m, double z, float alpha);

// Bounds on the fraction of b_0 that lies in front of warped depth z, over every distribution
// consistent with the (biased, normalised) moments: `lower` counts the mass strictly in front of z,
// `upper` the mass in front of or at z. Transmittance at z is then within
// [exp(-b_0 * upper), exp(-b_0 * lower)]. Undefined (0, 0) when b_0 == 0.
struct Bounds {
    double lower = 0.0, upper = 0.0;
};
Bounds absorbanceBounds(const Moments& moments, double z);
// exp(-b_0 * ((1 - eta) * lower + eta * upper)), the paper's reconstruction with overestimation eta.
double transmittanceAt(const Moments& moments, double z, double overestimation = kOverestimation);

// The composite the method computes for one pixel: pass 1 moments, pass 2 sum of a*T(z)*(C, 1) with
// T reconstructed at each fragment, resolve (1 - exp(-b_0)) * sum(a T C) / sum(a T) + exp(-b_0) * bg.
glm::vec3 compositePixel(const FragmentList& fragments, MomentKind kind, const DepthWarp& warp,
                         const glm::vec3& background);

}  // namespace starnt::mboit
