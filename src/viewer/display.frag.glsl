// Puts linear method output on the window: sRGB-encodes it (the window framebuffer is not an sRGB
// one, and the UI draws plain 8-bit colours on top), optionally with a second image on the right of
// a split column and a thin divider between them.
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_left;
layout(binding = 1) uniform sampler2D u_right;
uniform int u_splitX;  // first column of the right image; negative: no split

vec3 encodeSrgb(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    bool split = u_splitX >= 0;
    vec3 linear = (split && p.x >= u_splitX) ? texelFetch(u_right, p, 0).rgb : texelFetch(u_left, p, 0).rgb;
    if (split && (p.x == u_splitX || p.x == u_splitX - 1)) linear = vec3(0.2);
    outColor = vec4(encodeSrgb(linear), 1.0);
}
