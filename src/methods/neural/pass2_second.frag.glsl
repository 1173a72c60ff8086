// Pass 2: the second-nearest fragment, by peeling against pass 1's depth. A fragment survives
// when its depth exceeds the nearest depth by more than u_peelEpsilon (window-depth units);
// the depth test (LESS, own depth target) then keeps the nearest survivor. At a reduced size the
// nearest depth is the maximum over the full pixels the reduced pixel covers: a variant of its own
// (STARNT_REDUCED_PEEL, built on the first reduced pass 2), since llvmpipe would run its loop and
// integer divisions for every fragment of a full-resolution pass behind a uniform condition too
// (docs/DESIGN.md, "Findings on Mesa llvmpipe").
#ifdef STARNT_REDUCED_PEEL
#include "methods/neural/reduced_peel_depth.glsl"
#endif
#include "methods/neural/half_targets.glsl"
layout(location = 0) out vec4 outSecond;
#ifdef STARNT_SPLIT_ALPHA
layout(location = 1) out vec2 outLayerAlpha;  // a2 in .g (a colour mask keeps pass 1's .r)
#endif
layout(binding = 0) uniform sampler2D u_nearestDepth;  // full resolution
uniform float u_peelEpsilon;
#ifdef STARNT_REDUCED_PEEL
uniform ivec2 u_fullSize;
uniform ivec2 u_reducedSize;
#endif

void main() {
    ivec2 i = ivec2(gl_FragCoord.xy);
#ifdef STARNT_REDUCED_PEEL
    float nearest = reducedPeelDepth(u_nearestDepth, i, u_fullSize, u_reducedSize);
#else
    float nearest = texelFetch(u_nearestDepth, i, 0).r;
#endif
    if (gl_FragCoord.z <= nearest + u_peelEpsilon) discard;
#ifdef STARNT_SPLIT_ALPHA
    splitLayerValue(fetchSurfaceOrDiscard(), outSecond, outLayerAlpha);
#else
    outSecond = targetValue(fetchSurfaceOrDiscard());
#endif
}
