// hybrid-moments' tail colour from pass 3's depth moments: nn::momentWeightedTailColor states the
// model; this is the same float arithmetic. Include after neural_inputs.glsl.
#include "methods/hybrid_moments/moment_weighted_color.glsl"
layout(binding = STARNT_UNIT_TAIL_MOMENT1) uniform highp sampler2D u_tailMoment1;  // sum a C u, sum a u
layout(binding = STARNT_UNIT_TAIL_MOMENT2) uniform highp sampler2D u_tailMoment2;  // sum a C u^2, sum a u^2

vec3 momentWeightedTailColor(PixelSums s, ivec2 p) {
    float alpha = tailAlphaSum(s);
    if (!(alpha > STARNT_EPS_TAIL_ALPHA)) return vec3(0.0);
    return momentWeightedColor(tailPremultiplied(s), alpha, texelFetch(u_tailMoment1, p, 0), texelFetch(u_tailMoment2, p, 0),
                               tailTransmittance(s), true);
}

// What hybrid-moments puts behind the nearest layer, (C - a1 C1) / (1 - a1) of its composite: what a
// real frame's kept correction is taken against (correction_capture.glsl) where its pass 3 could not
// sum the ordered closed form's moments (fewer than 6 draw buffers; infer_full.frag.glsl). Needs
// 1 - a1 > 0.
#define STARNT_ORDERED_CLOSED_FORM 1
vec3 orderedClosedFormBehindNearest(PixelSums s, vec3 background) {
    vec3 composite = threeLayerComposite(s, (1.0 - tailTransmittance(s)) * momentWeightedTailColor(s, ivec2(gl_FragCoord.xy)),
                                         background);
    return (composite - s.a1 * s.c1) / (1.0 - s.a1);
}
