// What a composite goes over (FrameDesc::background, backgroundTexture, premultipliedOutput;
// OpaqueScene::bindBackground sets the uniforms). Every method's output is linear in it:
//   output = composite over black + transmittance * background,
// so a premultiplied output is the same composite with a black background and the transmittance
// in alpha.
#ifndef STARNT_BACKGROUND_GLSL
#define STARNT_BACKGROUND_GLSL
#include "starnt/bindings.h"
uniform vec3 u_background;
uniform int u_backgroundSource;  // 0: u_background, 1: the texture, 2: none (premultiplied output)
// The composite over the background with the transmittance in alpha: the real frames that warp and
// refresh frames keep premultiplied (OpaqueScene::setTransmittanceInAlpha).
uniform bool u_transmittanceInAlpha;
layout(binding = STARNT_UNIT_OPAQUE) uniform highp sampler2D u_backgroundTexture;

vec3 backgroundAt(ivec2 pixel) {
    if (u_backgroundSource == 1) return texelFetch(u_backgroundTexture, pixel, 0).rgb;
    return u_backgroundSource == 0 ? u_background : vec3(0.0);
}
#ifdef STARNT_FRAGMENT_STAGE
vec3 background() { return backgroundAt(ivec2(gl_FragCoord.xy)); }
#endif
// The output's alpha for a pixel whose layers let `transmittance` of the background through.
float outputAlpha(float transmittance) { return u_backgroundSource == 2 || u_transmittanceInAlpha ? transmittance : 1.0; }
#endif
