// Pass 1 (full resolution): the nearest transparent fragment. Depth test LESS with depth write, no
// blending: the survivor of the depth test is the nearest fragment; its colour and alpha land in
// the colour target, its depth in the depth target (used by pass 2 and by reprojection).
#include "methods/neural/half_targets.glsl"
layout(location = 0) out vec4 outNearest;
#ifdef STARNT_SPLIT_ALPHA
layout(location = 1) out vec2 outLayerAlpha;  // a1 in .r (a colour mask keeps .g for pass 2)
#endif

void main() {
#ifdef STARNT_SPLIT_ALPHA
    splitLayerValue(fetchSurfaceOrDiscard(), outNearest, outLayerAlpha);
#else
    outNearest = targetValue(fetchSurfaceOrDiscard());
#endif
}
