// Pass 1 (full resolution): the nearest transparent fragment. Depth test LESS with depth write, no
// blending: the survivor of the depth test is the nearest fragment; its colour and alpha land in
// the colour target, its depth in the depth target (used by pass 2 and by reprojection).
#include "methods/neural/half_targets.glsl"
layout(location = 0) out vec4 outNearest;

void main() {
    outNearest = targetValue(fetchSurfaceOrDiscard());
}
