// hybrid-moments' weighted colour from alpha-weighted depth moments (CPU reference
// nn::momentWeightedColor, the same float arithmetic): `alphaColor`, `alpha` the sums over the
// fragments weighted (sum a C, sum a > 0), `m1` = (sum a C u, sum a u), `m2` = (sum a C u^2, sum a u^2),
// `tTail` their transmittance prod (1 - a). Without `quadraticAllowed` the weight is linear at most
// and m2.rgb is not read (corrected frames sum sum a u^2 alone: ordered_behind.glsl). Used by the tail composite (tail_moments.glsl) and by
// corrected interpolated frames behind the nearest layer (ordered_behind.glsl).
#ifndef STARNT_MOMENT_WEIGHTED_COLOR_GLSL
#define STARNT_MOMENT_WEIGHTED_COLOR_GLSL
#include "methods/hybrid_moments/tail_moments_constants.h"

// I_k = integral over [0, 1] of x^k exp(-tau x), k = 0, 1, 2.
vec3 exponentialMoments(float tau) {
    if (tau < float(STARNT_TAIL_MOMENT_SERIES_BELOW)) {
        vec3 integrals = vec3(0.0);
        float term = 1.0;
        for (int n = 0; n < 12; ++n) {
            integrals += term / vec3(float(n + 1), float(n + 2), float(n + 3));
            term *= -tau / float(n + 1);
        }
        return integrals;
    }
    float e = exp(-tau);
    return vec3((1.0 - e) / tau, (1.0 - e * (1.0 + tau)) / (tau * tau),
                (2.0 - e * (tau * tau + 2.0 * tau + 2.0)) / (tau * tau * tau));
}

vec3 momentWeightedColor(vec3 alphaColor, float alpha, vec4 m1, vec4 m2, float tTail, bool quadraticAllowed) {
    vec3 plain = max(alphaColor / alpha, vec3(0.0));
    float mean = m1.a / alpha;
    float spread = sqrt(max(m2.a / alpha - mean * mean, 0.0));
    if (!(spread > float(STARNT_TAIL_MOMENT_PLAIN_BELOW) * mean)) return plain;
    bool quadratic = quadraticAllowed && spread > float(STARNT_TAIL_MOMENT_LINEAR_BELOW) * mean;
    float maxDepth = float(STARNT_TAIL_MOMENT_MAX_OPTICAL_DEPTH);
    float tau = tTail > 0.0 ? min(-log(tTail), maxDepth) : maxDepth;
    vec3 integral = exponentialMoments(tau);
    float c0 = integral.x, c1 = 3.0 * (2.0 * integral.y - integral.x);
    float c2 = quadratic ? 5.0 * (6.0 * integral.z - 6.0 * integral.y + integral.x) : 0.0;
    // A convex quadratic whose minimum lies before STARNT_TAIL_MOMENT_MIN_VERTEX: the linear weight.
    if (c2 > 0.0 && (2.0 * c1 - 6.0 * c2) + 2.0 * float(STARNT_TAIL_MOMENT_MIN_VERTEX) * (6.0 * c2) > 0.0) c2 = 0.0;
    float b0 = c0 - c1 + c2, b1 = 2.0 * c1 - 6.0 * c2, b2 = 6.0 * c2;
    float halfWidth = sqrt(3.0) * spread, lo = mean - halfWidth, width = 2.0 * halfWidth;
    vec3 firstFromLo = m1.rgb - lo * alphaColor;
    vec3 x1 = firstFromLo / width;
    vec3 x2 = quadratic ? ((m2.rgb - lo * m1.rgb) - lo * firstFromLo) / (width * width) : vec3(0.0);
    return max((b0 * alphaColor + b1 * x1 + b2 * x2) / (c0 * alpha), vec3(0.0));
}
#endif
