// MBOIT pass 1: moments of optical depth, additive blending (ONE, ONE), no depth test.
// Per fragment: absorbance A = -ln(1 - min(a, kMaxAlpha)), b_0 += A, b_k += A z^k (power) or
// b_k += A exp(i k phi(z)) (trigonometric), z the warped depth (mboit_common.glsl).
#include "methods/mboit/mboit_common.glsl"

layout(location = 0) out vec4 outB0;
layout(location = 1) out vec4 outMoments;
#if MBOIT_EXTRA
layout(location = 2) out vec4 outExtra;
#endif

uniform float u_maxAlpha;

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    float absorbance = -log(1.0 - min(s.a, u_maxAlpha));
    float z = mboitWarpedDepth(gl_FragCoord.z);
    outB0 = vec4(absorbance, 0.0, 0.0, 0.0);
#if MBOIT_TRIG
    float phi = mboitPhase(z);
    outMoments = absorbance * vec4(cos(phi), sin(phi), cos(2.0 * phi), sin(2.0 * phi));
#if MBOIT_EXTRA
    outExtra = absorbance * vec4(cos(3.0 * phi), sin(3.0 * phi), 0.0, 0.0);
#endif
#else
    float z2 = z * z;
    outMoments = absorbance * vec4(z, z2, z2 * z, z2 * z2);
#if MBOIT_EXTRA
    outExtra = absorbance * vec4(z2 * z2 * z, z2 * z2 * z2, 0.0, 0.0);
#endif
#endif
}
