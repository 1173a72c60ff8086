// Neural OIT: per-pixel features and composites, the CPU reference of what the GPU computes (part
// of starnt::tools; the network itself, its weights file and its GLSL are in network.hpp):
//   passes 1-3 -> PixelSums (sumsFromFragments), PixelSums -> network inputs (starntFeatures,
//   dfaoitFeatures), inputs -> prediction (Network::forward, same maths as generateInferenceGlsl),
//   prediction -> final pixel colour (compositeStarnt, compositeDfaoit).
//
// Feature guards (the GPU shader must apply the same ones, see the constants below):
//   T2     = (1 - a1)(1 - a2)
//   t_tail = T2 > kTransmittanceEpsilon ? clamp(T_all / T2, 0, 1) : 0
//   A_tail = S_a - a1 - a2
//   C_tilde = A_tail > kTailAlphaEpsilon ? max((S_aC - a1 C1 - a2 C2) / A_tail, 0) : 0
//   DFAOIT: n_tail = N - 2; n_tail > 0.5 ? (a_avg = max(A_tail, 0) / n_tail,
//           C_avg = max(S_C - C1 - C2, 0) / n_tail) : zeros.
// Composite of STAR-NT (exact where the sums determine the tail):
//   tail = N < 2.5 ? 0 : N < 3.5 ? max(S_aC - a1 C1 - a2 C2, 0) : f(x)
//   C    = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg
// The residual kind changes only the deep tail (N > 3): (1 - t_tail) * max(C_tilde + f(x), 0);
// hybrid's is (1 - t_tail) * C_tilde.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "starnt/tools/fragments.hpp"
#include "starnt/network.hpp"

namespace starnt::nn {

// What passes 1-3 produce for one pixel. Pass 1: nearest fragment (c1, a1); pass 2: second nearest
// (c2, a2); both zero when absent. Pass 3: sums over ALL fragments (after the alpha cut-off).
struct PixelSums {
    glm::vec3 c1{0.0f};
    float a1 = 0.0f;
    glm::vec3 c2{0.0f};
    float a2 = 0.0f;
    float count = 0.0f;                // N
    float sumAlpha = 0.0f;             // S_a = sum a_i
    glm::vec3 sumAlphaColor{0.0f};     // S_aC = sum a_i C_i
    glm::vec3 sumColor{0.0f};          // S_C = sum C_i (DFAOIT only)
    float transmittance = 1.0f;        // T_all = prod (1 - a_i)
};

// CPU reference of passes 1-3. `fragments` may be in any order; fragments with alpha < cutoff are
// dropped, the rest sorted by depth (sortByDepth). Sums are accumulated in double, stored as float.
PixelSums sumsFromFragments(FragmentList fragments, float alphaCutoff = kDefaultAlphaCutoff);

// What the compact pass targets (NeuralOptions::Targets::Compact, 16-bit) hold: the two nearest
// colours and alphas rounded to half precision, the pass-3 sums accumulated in 16-bit floats with a
// rounding after every addition, and the transmittance in 16-bit unsigned normalised fixed point
// (GL_R16: 1 - a and every product rounded to the nearest step of 1/65535), as the GPU's blending
// does (in depth order here; the GPU's order is the draw order, so sums may differ in their last
// bits). The count stays exact (16-bit floats hold integers to 2048). The shaders
// round what they write to the nearest 16-bit float; what blending writes is rounded by the driver:
// to nearest on GPUs, toward zero on llvmpipe (`blendTruncates`).
// `narrowLayers`: DFAOIT's narrow layers (NeuralPasses): the two nearest colours clamped to [0, 1]
// and rounded to the nearest step of 1/1023 (RGB10_A2) instead of to half precision.
PixelSums sumsInHalfTargets(FragmentList fragments, bool blendTruncates = false, float alphaCutoff = kDefaultAlphaCutoff,
                            bool narrowLayers = false);
// Round to the nearest 16-bit float (ties to even), as half_targets.glsl does before a write, or
// toward zero.
float roundToHalf(float v, bool towardZero = false);
glm::vec3 roundToHalf(glm::vec3 v, bool towardZero = false);
// Clamp to [0, 1] and round to the nearest step of 1/65535 (a GL_R16 target) or 1/1023 (10 bits).
float roundToUnorm16(float v);
glm::vec3 roundToUnorm10(glm::vec3 v);
// What DFAOIT's narrow layer (RGB10_A2) holds of colour c: c / 16^e rounded to 10 bits, times 16^e,
// e in 0..3 the least that brings the largest channel within 1 (half_targets.glsl, splitLayerValue).
glm::vec3 narrowLayerColor(glm::vec3 c);

// Drops fragments with alpha < cutoff and sorts the rest by depth: the list targets are defined on.
FragmentList preparedFragments(FragmentList fragments, float alphaCutoff = kDefaultAlphaCutoff);

// STAR-NT inputs, in this order: t_tail, N, C_tilde.r, C_tilde.g, C_tilde.b.
std::array<float, kStarntInputs> starntFeatures(const PixelSums& s);
// DFAOIT inputs, in this order: a_avg, C_avg.rgb, S_aC.rgb, C_exact2.rgb, alpha_exact2 = 1 - T2, N
// (a ten-input network reads the first ten).
std::array<float, kDfaoitInputs> dfaoitFeatures(const PixelSums& s);

// Targets, from a list already prepared (cut off and sorted, see preparedFragments).
// STAR-NT: exact tail colour sum_{i>=3} a_i C_i prod_{3<=j<i} (1 - a_j) (zero when N <= 2).
glm::vec3 starntTarget(const FragmentList& sorted);
// The residual kind's target: what f(x) must add to C_tilde so that (1 - t_tail) (C_tilde + f)
// is the exact tail, i.e. tail / (1 - t_tail) - C_tilde, for a list with N > 3 and its sums. Tails
// with 1 - t_tail below kResidualMinTailOpacity, invisible in any image, get 0.
inline constexpr float kResidualMinTailOpacity = 1e-4f;
glm::vec3 starntResidualTarget(const FragmentList& sorted, const PixelSums& sums);
// DFAOIT: whole transparent colour sum_i a_i C_i prod_{j<i} (1 - a_j) (no background).
glm::vec3 dfaoitTarget(const FragmentList& sorted);

// Final pixel colours (CPU reference of the composite shader).
// STAR-NT: see the top of this file (exact for N <= 3, the network is not evaluated there).
glm::vec3 compositeStarnt(const Network& net, const PixelSums& s, glm::vec3 background);
// The residual kind: STAR-NT's composite with the tail (1 - t_tail) max(C_tilde + f(x), 0).
glm::vec3 compositeStarntResidual(const Network& net, const PixelSums& s, glm::vec3 background);
// hybrid (docs/DESIGN.md, "Pipeline and formats"): STAR-NT's composite with the tail in closed form, (1 - t_tail) C_tilde.
glm::vec3 compositeHybrid(const PixelSums& s, glm::vec3 background);
// hybrid-moments: hybrid with the tail's colour weighted by where its opacity lies in depth.
// Pass 3 also sums, over the fragments behind the second layer (window depth z > z2), with u =
// ln(1 + (z - z2) / (s (1 - z2))) a logarithmic depth behind it (s: tail_moments_constants.h):
struct TailMoments {
    glm::vec3 alphaColorU{0.0f};   // sum a C u
    float alphaU = 0.0f;           // sum a u
    glm::vec3 alphaColorU2{0.0f};  // sum a C u^2
    float alphaU2 = 0.0f;          // sum a u^2
};
// CPU reference of those sums (accumulated in double, stored as float), for the same list as
// sumsFromFragments (any order; cut off and sorted here).
TailMoments tailMomentsFromFragments(FragmentList fragments, float alphaCutoff = kDefaultAlphaCutoff);
// The tail's colour: its opacity is modelled as spread evenly over the interval with the mean and
// variance of the alpha-weighted u (x in [0, 1] across it), so a fragment at x shows through
// exp(-tau x) of the tail in front of it, tau = -ln t_tail. That weight's least-squares quadratic
// on [0, 1] (Legendre coefficients of closed-form integrals) turns the moments into the weighted
// mean colour sum a C w(x) / sum a w(x) in closed form: one additive pass, no second pass over the
// fragments. The linear weight replaces a quadratic that would rise again before x = 2 (far
// fragments weighted as if in front); the quadratic (then the linear) term is dropped where 32-bit
// sums cannot centre it (tail_moments_constants.h); C_tilde where the spread is zero. Zero when
// A_tail <= kTailAlphaEpsilon.
glm::vec3 momentWeightedTailColor(const PixelSums& s, const TailMoments& m);
// The same weighting for any fragments: `alphaColor` = sum a C, `alpha` = sum a (> 0), `m` their
// moments, `tTail` their transmittance (corrected frames weigh what lies behind the nearest layer
// with it: temporal::orderedClosedFormBehind).
// Without `quadraticAllowed` the weight is linear at most and m.alphaColorU2 is not read.
glm::vec3 momentWeightedColor(const glm::vec3& alphaColor, float alpha, const TailMoments& m, float tTail,
                              bool quadraticAllowed = true);
// hybrid-moments' composite: hybrid's with the deep tail (1 - t_tail) momentWeightedTailColor.
glm::vec3 compositeHybridMoments(const PixelSums& s, const TailMoments& m, glm::vec3 background);
// starnt-d (NetworkKind::StarNTDepth) inputs, in this order: STAR-NT's five (t_tail, N, C_tilde),
// then C_m = momentWeightedTailColor.
std::array<float, kStarntDepthInputs> starntDepthFeatures(const PixelSums& s, const TailMoments& m);
// Its target, for a list with N > 3: tail / (1 - t_tail) - C_m (0 below kResidualMinTailOpacity).
glm::vec3 starntDepthTarget(const FragmentList& sorted, const PixelSums& sums, const TailMoments& m);
// Its composite: STAR-NT's with the deep tail (1 - t_tail) max(C_m + f(x), 0).
glm::vec3 compositeStarntDepth(const Network& net, const PixelSums& s, const TailMoments& m, glm::vec3 background);
// DFAOIT: f(x) + T_all * C_bg; a pixel without fragments (N < 0.5) is the background alone.
glm::vec3 compositeDfaoit(const Network& net, const PixelSums& s, glm::vec3 background);
// The composite of net.kind. starnt-d reads the tail moments too: `moments` is required for it
// (starnt::Error without), ignored by the others.
glm::vec3 compositeNetwork(const Network& net, const PixelSums& s, glm::vec3 background,
                           const TailMoments* moments = nullptr);

}  // namespace starnt::nn
