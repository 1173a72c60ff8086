// What warp and refresh frames keep of a real frame when the background changes from frame to frame
// (an engine's opaque scene, a premultiplied output; docs/DESIGN.md, "Opaque geometry"): its
// layers over black and their transmittance, P = C - T bg and T, from the composite over this
// frame's background with T in alpha (OpaqueScene::setTransmittanceInAlpha). The interpolated frames
// composite P + T bg over their own frame's background.
#include "methods/common/background.glsl"
layout(binding = 0) uniform highp sampler2D u_color;
out vec4 o_color;

void main() {
    vec4 c = texelFetch(u_color, ivec2(gl_FragCoord.xy), 0);
    o_color = vec4(c.rgb - c.a * background(), c.a);
}
