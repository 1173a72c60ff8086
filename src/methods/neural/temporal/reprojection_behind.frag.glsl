// At capture (once per real frame), what lay behind the nearest layer at each texel,
// B = (C - a1 C1) / (1 - a1), with the texel's inverse old view depth (row 3 of
// inverse(oldViewProj)), which the interpolated frame compares to accept a texel as the same surface.
// Alpha -1: the nearest layer hid what lay behind.
//   refresh frames: B itself, resampled under the fresh nearest layer (temporal::refreshPixel);
//   corrected frames (STARNT_BEHIND_CORRECTION): B minus the closed form of the same frame's pass-3
//   sums, D = B - B_cf, added to the fresh closed form (temporal::correctionOnCpu).
#include "methods/neural/temporal/reprojection_constants.h"

layout(binding = 0) uniform highp sampler2D u_color;        // the kept composite
layout(binding = 1) uniform highp sampler2D u_depth;        // its pass-1 window depth
layout(binding = 3) uniform highp sampler2D u_keptNearest;  // its pass-1 colour + alpha
#ifdef STARNT_BEHIND_CORRECTION
#include "methods/neural/temporal/correction_capture.glsl"
layout(binding = 4) uniform highp sampler2D u_sumAlphaColor;  // its pass 3 at full resolution: sum a C, sum a
layout(binding = 5) uniform highp sampler2D u_transmittance;  // its pass 3: prod (1 - a)
#include "methods/common/background.glsl"
#endif
uniform ivec2 u_size;
uniform vec4 u_sourceScale;

out vec4 o_behind;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    vec4 n = texelFetch(u_keptNearest, t, 0);
#ifdef STARNT_BEHIND_CORRECTION
    vec3 closedForm = closedFormBehind(n, texelFetch(u_sumAlphaColor, t, 0), texelFetch(u_transmittance, t, 0).r, background());
    o_behind = keptCorrection(t, u_size, u_sourceScale, texelFetch(u_color, t, 0).rgb, n, closedForm, texelFetch(u_depth, t, 0).r);
#else
    float open = 1.0 - n.a;
    if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) {
        o_behind = vec4(0.0, 0.0, 0.0, -1.0);
        return;
    }
    vec2 ndc = (vec2(t) + 0.5) / vec2(u_size) * 2.0 - 1.0;
    float inverseViewDepth = dot(u_sourceScale, vec4(ndc, texelFetch(u_depth, t, 0).r * 2.0 - 1.0, 1.0));
    vec3 behind = (texelFetch(u_color, t, 0).rgb - n.a * n.rgb) / open;
    o_behind = vec4(behind, inverseViewDepth);
#endif
}
