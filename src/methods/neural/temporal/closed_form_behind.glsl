// What lies behind the nearest layer, in closed form from pass 3's sums over every fragment (the
// hybrid method's tail applied one layer earlier): the fragments behind the nearest one cover
// 1 - T' of the pixel, T' = T / (1 - a1), with their alpha-weighted mean colour, the background
// the rest. Corrected interpolated frames (correction_composite.frag.glsl) add to it the network's
// correction kept from the last real frame (reprojection_behind.frag.glsl, STARNT_BEHIND_CORRECTION). CPU reference:
// temporal::closedFormBehind (correction_cpu.hpp), which states the guards.
// `nearest` = C1, a1 (a1 < 1 - STARNT_TEMPORAL_MIN_TRANSMITTANCE), `sums` = (sum a C, sum a),
// `t` = prod (1 - a).
vec3 closedFormBehind(vec4 nearest, vec4 sums, float t, vec3 background) {
    float behindT = clamp(t / (1.0 - nearest.a), 0.0, 1.0);
    float behindAlpha = sums.a - nearest.a;
    vec3 mean = behindAlpha > float(STARNT_TEMPORAL_MIN_BEHIND_ALPHA)
                    ? max(sums.rgb - nearest.a * nearest.rgb, vec3(0.0)) / behindAlpha
                    : background;
    return (1.0 - behindT) * mean + behindT * background;
}
