// Refresh frames, at capture (once per real frame): what lay behind the nearest layer at each texel,
// B = (C - a1 C1) / (1 - a1), and the texel's inverse old view depth (row 3 of
// inverse(oldViewProj)), so that the refresh pass resamples B with one fetch per tap
// (temporal::refreshPixel states the rule). Alpha -1: the nearest layer hid what lay behind.
#include "methods/neural/temporal/reprojection_constants.h"

layout(binding = 0) uniform highp sampler2D u_color;        // the kept composite
layout(binding = 1) uniform highp sampler2D u_depth;        // its pass-1 window depth
layout(binding = 3) uniform highp sampler2D u_keptNearest;  // its pass-1 colour + alpha
uniform ivec2 u_size;
uniform vec4 u_sourceScale;

out vec4 o_behind;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 n = texelFetch(u_keptNearest, t, 0);
    float open = 1.0 - n.a;
    if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) {
        o_behind = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    vec2 ndc = (vec2(t) + 0.5) / vec2(u_size) * 2.0 - 1.0;
    float inverseViewDepth = dot(u_sourceScale, vec4(ndc, texelFetch(u_depth, t, 0).r * 2.0 - 1.0, 1.0));
    o_behind = vec4((texelFetch(u_color, t, 0).rgb - n.a * n.rgb) / open, inverseViewDepth);
}
