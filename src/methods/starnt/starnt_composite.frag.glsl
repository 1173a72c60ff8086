// STAR-NT inference + composite at full resolution (SPEC section 3):
//   inputs  x = [t_tail, N, C_tilde.rgb], t_tail = T_all / T2, C_tilde = tail premultiplied / tail alpha
//   C = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg,
//   tail = 0 (N <= 2), the third fragment exactly (N == 3), f(x) otherwise.
// nnEvaluate() is generated from the weights file and prepended to this file.
#include "methods/neural/neural_inputs.glsl"

uniform vec3 u_background;
layout(location = 0) out vec4 outColor;

void main() {
    PixelSums s = readPixelSums(ivec2(gl_FragCoord.xy));
    float t2 = twoLayerTransmittance(s);
    vec3 tailPremul = tailPremultiplied(s);
    vec3 tail;
    if (s.count < 2.5) {
        tail = vec3(0.0);
    } else if (s.count < 3.5) {
        tail = max(tailPremul, vec3(0.0));
    } else {
        float tTail = t2 > STARNT_EPS_TRANSMITTANCE ? clamp(s.transmittance / t2, 0.0, 1.0) : 0.0;
        float tailAlpha = tailAlphaSum(s);
        vec3 cTilde = tailAlpha > STARNT_EPS_TAIL_ALPHA ? max(tailPremul / tailAlpha, vec3(0.0)) : vec3(0.0);
        float x[STARNT_NN_INPUTS];
        x[0] = tTail;
        x[1] = s.count;
        x[2] = cTilde.r;
        x[3] = cTilde.g;
        x[4] = cTilde.b;
        tail = nnEvaluate(x);
    }
    outColor = vec4(exactTwo(s) + t2 * tail + s.transmittance * u_background, 1.0);
}
