// Depth peeling, one layer: keep the nearest fragment strictly behind the previous layer's depth.
// Depth test LESS with depth write picks the nearest survivor. Depths of the same fragment are
// bit-identical across passes (the vertex shader declares `invariant gl_Position`), so a strict
// comparison peels exactly one surface per layer; coplanar duplicates at identical depth are
// peeled together (the A-buffer keeps both: the one documented difference).
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_previousDepth;
uniform int u_firstLayer;

void main() {
    if (u_firstLayer == 0 && gl_FragCoord.z <= texelFetch(u_previousDepth, ivec2(gl_FragCoord.xy), 0).r) discard;
    outColor = fetchSurfaceOrDiscard();
}
