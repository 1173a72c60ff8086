// Moment-based OIT (Muenstermann, Krumpen, Klein, Peters, "Moment-Based Order-Independent
// Transparency", Proc. ACM CGIT 1(1), 2018): the moment settings and the constants the paper gives
// for them. Shared by the GPU method (mboit.cpp passes them to the shaders as uniforms) and by the
// CPU reference (mboit_cpu.cpp), so both use the same numbers.
//
// Depth warp (the paper's logarithmic warp): view depth d in [near, far] of the frame's projection
//   z = 2 * ln(d / near) / ln(far / near) - 1   in [-1, 1],
// used directly by the power moments. The trigonometric moments map it to a phase on the circle,
//   phi = (z + 1) * (pi - w / 2)   in [0, 2 pi - w],
// leaving a wrapping zone of angle w = 0.1 pi between the farthest and the nearest depth.
//
// Moments of optical depth per pixel, over its fragments i with alpha a_i and warped depth z_i:
//   absorbance A_i = -ln(1 - min(a_i, kMaxAlpha)),  b_0 = sum A_i,
//   power:         b_k = sum A_i z_i^k, k = 1..m (m = 4 or 6),
//   trigonometric: b_k = sum A_i exp(i k phi_i), k = 1..m (m = 2 or 3 complex moments).
#pragma once
#include <string>

namespace starnt::mboit {

enum class MomentKind { Power4, Power6, Trig2, Trig3 };

struct MomentSetting {
    MomentKind kind;
    const char* name;       // the --mboit-moments value: "4", "6", "t2", "t3"
    bool trigonometric;
    int count;              // m: real power moments (4, 6) or complex trigonometric moments (2, 3)
    int order;              // n: support points besides the query depth = m / 2 (power) or m (trig)
    float bias;             // the paper's moment bias beta for 32-bit float storage
    float biasVector[6];    // power: the moments the bias pulls towards (b_1..b_m); trig: all 0
};

// The paper's recommended values for 32-bit float moments:
//   4 power moments: beta = 5e-7, bias vector (0, 0.375, 0, 0.375)
//   6 power moments: beta = 5e-6, bias vector (0, 0.48, 0, 0.451, 0, 0.45)
//   2 trigonometric: beta = 4e-7, 3 trigonometric: beta = 8e-7, biased towards 0 (the moments of
//   the uniform distribution on the circle): b_k <- (1 - beta) b_k.
// Biasing: b <- (1 - beta) b + beta * biasVector on the moments normalised by b_0.
const MomentSetting& momentSetting(MomentKind kind);
// Parses the --mboit-moments value ("4", "6", "t2", "t3"); throws starnt::Error otherwise.
MomentKind parseMomentKind(const std::string& text);

// The paper's overestimation: the reconstructed optical depth in front of z is
// (1 - eta) * lower bound + eta * upper bound with eta = 0.25 (the value the paper recommends).
constexpr float kOverestimation = 0.25f;
// Angle of the wrapping zone of the trigonometric moments (0.1 pi, the paper's value).
constexpr float kWrappingZoneAngle = 0.1f * 3.14159265358979f;
// Alpha is clamped below 1 before taking the absorbance so that b_0 stays finite (A <= 9.21).
constexpr float kMaxAlpha = 0.9999f;

}  // namespace starnt::mboit
