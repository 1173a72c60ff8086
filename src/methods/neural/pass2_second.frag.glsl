// Pass 2: the second-nearest fragment, by peeling against pass 1's depth. A fragment survives
// when its depth exceeds the nearest depth by more than u_peelEpsilon (window-depth units);
// the depth test (LESS, own depth target) then keeps the nearest survivor.
layout(location = 0) out vec4 outSecond;
layout(binding = 0) uniform sampler2D u_nearestDepth;
uniform float u_peelEpsilon;

void main() {
    float nearest = texelFetch(u_nearestDepth, ivec2(gl_FragCoord.xy), 0).r;
    if (gl_FragCoord.z <= nearest + u_peelEpsilon) discard;
    outSecond = fetchSurfaceOrDiscard();
}
