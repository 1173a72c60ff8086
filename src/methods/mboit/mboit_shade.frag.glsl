// MBOIT pass 2: each fragment weighted by the transmittance reconstructed at its depth from the
// pass-1 moments; additive (ONE, ONE) into RGBA32F: (sum a T C, sum a T).
#include "methods/mboit/mboit_reconstruct.glsl"

layout(location = 0) out vec4 outAccum;

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    float t = mboitTransmittance(ivec2(gl_FragCoord.xy), gl_FragCoord.z);
    outAccum = vec4(s.rgb, 1.0) * (s.a * t);
}
