// Wraps the engine's starntSurface(): applies the alpha cut-off every pass shares (docs/DESIGN.md, "Pipeline and formats":
// fragments with alpha below it are discarded in all passes) and clamps to valid ranges.
uniform float u_alphaCutoff;
#include "starnt/bindings.h"

// The engine's opaque depth for the passes that keep their nearest fragment in a depth target of
// their own (OpaqueScene::clipInShader): a fragment at or behind it is dropped before the surface
// is evaluated. The passes without one test against the same values by the depth test instead.
// A variant of its own (STARNT_OPAQUE_CLIP, SurfaceProgram::clipping), not a uniform branch: llvmpipe
// runs a branch's masked fetch and integer division for every fragment even when a uniform turns it
// off (docs/DESIGN.md, "Findings on Mesa llvmpipe").
#ifdef STARNT_OPAQUE_CLIP
uniform bool u_opaqueReversed;  // the engine's depth is reversed (DepthConvention): near at 1
uniform ivec2 u_opaqueSize, u_opaqueFullSize;
layout(binding = STARNT_UNIT_OPAQUE) uniform highp sampler2D u_opaqueDepthClip;
#endif

vec4 fetchSurfaceOrDiscard() {
#ifdef STARNT_OPAQUE_CLIP
    {
        // A reduced texel i takes the full pixel holding its sample, floor(i F / R + 0.5).
        ivec2 i = ivec2(gl_FragCoord.xy);
        ivec2 p = min((2 * i * u_opaqueFullSize + u_opaqueSize) / (2 * u_opaqueSize), u_opaqueFullSize - 1);
        float opaque = texelFetch(u_opaqueDepthClip, p, 0).r;
        if (!(gl_FragCoord.z < (u_opaqueReversed ? 1.0 - opaque : opaque))) discard;
    }
#endif
    vec4 s = starntSurface();
    // Colours may exceed 1 (linear HDR) up to STARNT_MAX_SURFACE_COLOR, where 16-bit float sums of
    // hundreds of layers still hold them; alpha within [0, 1].
    s = vec4(clamp(s.rgb, vec3(0.0), vec3(STARNT_MAX_SURFACE_COLOR)), clamp(s.a, 0.0, 1.0));
    if (!(s.a >= u_alphaCutoff)) discard;  // also discards NaN alpha
    return s;
}
