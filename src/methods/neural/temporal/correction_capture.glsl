// What a real frame keeps for corrected frames at texel t (temporal::correctionOnCpu): D = B - B_cf,
// what lay behind the nearest layer, B = (C - a1 C1) / (1 - a1), minus `closedForm`, what the
// closed form of the same frame puts there (closedFormBehind of its pass-3 sums; for the tail-moment
// methods the ordered closed form, ordered_behind.glsl, or where pass 3 could not sum its moments
// hybrid-moments' composite, tail_moments.glsl), with the texel's inverse old view depth (row 3 of inverse(viewProj),
// `sourceScale`) in alpha for the same-surface test of the interpolated frames. Alpha -1: the
// nearest layer hid what lay behind. Used by the capture pass (reprojection_behind.frag.glsl with
// STARNT_BEHIND_CORRECTION) and by the composite's fused capture (infer_full.frag.glsl with
// STARNT_CAPTURE_CORRECTION), so both keep the same numbers.
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/closed_form_behind.glsl"

vec4 keptCorrection(ivec2 t, ivec2 size, vec4 sourceScale, vec3 composite, vec4 nearest, vec3 closedForm, float depth) {
    float open = 1.0 - nearest.a;
    if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return vec4(0.0, 0.0, 0.0, -1.0);
    vec2 ndc = (vec2(t) + 0.5) / vec2(size) * 2.0 - 1.0;
    float inverseViewDepth = dot(sourceScale, vec4(ndc, depth * 2.0 - 1.0, 1.0));
    vec3 behind = (composite - nearest.a * nearest.rgb) / open;
    return vec4(behind - closedForm, inverseViewDepth);
}
