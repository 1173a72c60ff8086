// STAR-NT features and composite (docs/DESIGN.md, "Pipeline and formats"), read by the inference passes in
// methods/neural/infer_*.frag.glsl:
//   inputs  x = [t_tail, N, C_tilde.rgb], t_tail = T_all / T2, C_tilde = tail premultiplied / tail alpha
//   C = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg,
//   tail = 0 (N <= 2), the third fragment exactly (N == 3), f(x) otherwise.
// nnEvaluate() is generated from the weights file and prepended.
#include "methods/neural/neural_inputs.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return s.count >= 3.5 && s.a2 > 0.0; }  // threeLayerComposite's deep tail

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) { starntInputs(s, x); }

// `networkOutput` is f(x) where networkApplies(s), unused elsewhere.
vec3 compositePixel(PixelSums s, vec3 networkOutput) { return threeLayerComposite(s, networkOutput, background()); }
