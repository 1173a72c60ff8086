// WBOIT resolve: average weighted colour times coverage, plus the background through revealage.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_accum;
layout(binding = 1) uniform sampler2D u_reveal;
#include "methods/common/background.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 accum = texelFetch(u_accum, p, 0);
    float reveal = texelFetch(u_reveal, p, 0).r;
    vec3 avg = accum.rgb / clamp(accum.a, 1e-4, 5e4);
    outColor = vec4(avg * (1.0 - reveal) + background() * reveal, outputAlpha(reveal));
}
