// Stage "infer" (SPEC 2, step 5), full: the network at every pixel where the method uses it, then
// the method's composite. The method's features and composite (networkApplies, networkInputs,
// compositePixel) are included before this file.
#include "methods/neural/half_targets.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    PixelSums s = readPixelSums(ivec2(gl_FragCoord.xy));
    vec3 network = vec3(0.0);
    if (networkApplies(s)) {
        float x[STARNT_NN_INPUTS];
        networkInputs(s, x);
        network = nnEvaluate(x);
    }
    outColor = targetValue(vec4(compositePixel(s, network), 1.0));
}
