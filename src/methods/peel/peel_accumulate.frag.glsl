// Adds one peeled layer behind the layers so far ("under" operator). The target holds
// (premultiplied colour so far, transmittance so far); blend: rgb = src * dst.a + dst,
// a = dst.a * (1 - src.a).
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D u_layer;

void main() {
    vec4 f = texelFetch(u_layer, ivec2(gl_FragCoord.xy), 0);
    outColor = vec4(f.rgb * f.a, f.a);
}
