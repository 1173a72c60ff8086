// MBOIT resolve (the paper's): the exact total transmittance exp(-b_0) lets the background through;
// the accumulated colour is normalised by its weight sum so that its opacity is 1 - exp(-b_0):
//   C = (1 - exp(-b_0)) * sum(a T C) / sum(a T) + exp(-b_0) * background.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_b0;
layout(binding = 1) uniform sampler2D u_accum;
#include "methods/common/background.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float b0 = texelFetch(u_b0, p, 0).r;
    vec4 accum = texelFetch(u_accum, p, 0);
    float total = exp(-max(b0, 0.0));
    vec3 average = accum.a > 0.0 ? accum.rgb / accum.a : vec3(0.0);
    outColor = vec4(average * (1.0 - total) + background() * total, outputAlpha(total));
}
