// Moment-based OIT (Muenstermann et al. 2018): depth warp and moment layout shared by both geometry
// passes. Compile-time defines (set by mboit.cpp from mboit_settings.hpp):
//   MBOIT_TRIG   0: power moments, 1: trigonometric moments
//   MBOIT_COUNT  m: 4 or 6 power moments, 2 or 3 complex trigonometric moments
//   MBOIT_ORDER  n: m / 2 (power) or m (trigonometric): support points besides the query depth
//   MBOIT_EXTRA  1 when a third target (RG32F: b_5, b_6 or the third complex moment) is used
// Targets: b_0 in R32F; b_1..b_4 (power) or Re/Im of b_1, b_2 (trigonometric) in RGBA32F;
// b_5, b_6 or Re/Im of b_3 in RG32F.
const float MBOIT_PI = 3.14159265358979;

uniform vec2 u_projZ;        // projection[2][2], projection[3][2]: view depth from window depth
uniform bool u_affine;       // an affine (orthographic) projection: depth is linear in distance
uniform vec2 u_warp;         // ln(near), 2 / ln(far / near)
uniform float u_wrapAngle;   // trigonometric wrapping zone (0.1 pi)

// The paper's logarithmic depth warp to [-1, 1] (mboit_settings.hpp); under an affine projection
// normalised depth itself, linear in distance between its near and far planes.
float mboitWarpedDepth(float windowZ) {
    float ndc = windowZ * 2.0 - 1.0;
    float viewDepth = abs(u_projZ.y / (ndc + u_projZ.x));
    float warped = u_affine ? ndc : (log(viewDepth) - u_warp.x) * u_warp.y - 1.0;
    return clamp(warped, -1.0, 1.0);
}

// Phase on the circle for the trigonometric moments: [-1, 1] -> [0, 2 pi - wrapAngle].
float mboitPhase(float z) { return (z + 1.0) * (MBOIT_PI - 0.5 * u_wrapAngle); }
