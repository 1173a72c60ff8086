// Corrected interpolated frames, at capture (once per real frame; temporal::correctionAt states the
// rule): at every texel, what the network put behind the nearest layer, B = (C - a1 C1) / (1 - a1),
// minus what the closed form puts there from the same frame's sums (closed_form_behind.glsl), with
// the texel's inverse old view depth (row 3 of inverse(viewProj)), which the interpolated frame
// compares to accept a texel as the same surface. Alpha -1: the nearest layer hid what lay behind.
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/closed_form_behind.glsl"

layout(binding = 0) uniform highp sampler2D u_composite;       // the real frame's output
layout(binding = 1) uniform highp sampler2D u_depth;           // its pass-1 window depth
layout(binding = 2) uniform highp sampler2D u_nearest;         // its pass-1 colour + alpha
layout(binding = 3) uniform highp sampler2D u_sumAlphaColor;   // pass 3, full resolution: sum a C, sum a
layout(binding = 4) uniform highp sampler2D u_transmittance;   // pass 3: prod (1 - a)
uniform ivec2 u_size;
uniform vec4 u_sourceScale;
uniform vec3 u_background;

out vec4 o_correction;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 n = texelFetch(u_nearest, t, 0);
    float open = 1.0 - n.a;
    if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) {
        o_correction = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    vec2 ndc = (vec2(t) + 0.5) / vec2(u_size) * 2.0 - 1.0;
    float inverseViewDepth = dot(u_sourceScale, vec4(ndc, texelFetch(u_depth, t, 0).r * 2.0 - 1.0, 1.0));
    vec3 network = (texelFetch(u_composite, t, 0).rgb - n.a * n.rgb) / open;
    vec3 closedForm = closedFormBehind(n, texelFetch(u_sumAlphaColor, t, 0), texelFetch(u_transmittance, t, 0).r, u_background);
    o_correction = vec4(network - closedForm, inverseViewDepth);
}
