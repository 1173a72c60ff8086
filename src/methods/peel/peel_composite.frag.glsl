// Final peel composite: accumulated colour plus the background through the remaining transmittance.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_accum;
#include "methods/common/background.glsl"

void main() {
    vec4 a = texelFetch(u_accum, ivec2(gl_FragCoord.xy), 0);
    outColor = vec4(a.rgb + a.a * background(), outputAlpha(a.a));
}
