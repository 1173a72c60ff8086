// Pass 3: statistics over all fragments (or the tail alone, below), no depth test.
//   target 0 (RGBA32F, blend ONE/ONE):                 sum a_i C_i, sum a_i
//   target 1 (RGBA32F, blend ONE/ONE):                 sum C_i, N
//            (R32F: N alone, with STARNT_COUNT_ONLY: the STAR-NT inputs need no sum of C_i,
//            which only DFAOIT reads; 12 bytes a pixel less)
//   target 2 (R32F,    blend ZERO/ONE_MINUS_SRC_ALPHA): prod (1 - a_i)
// When passes 2 and 3 both run at full resolution (u_tailOnly), the two peeled fragments are left
// out: the targets then hold the tail alone (fragments 3..N), as the tail resolve leaves them after
// reduced passes, and the inference adds the layers back in 32-bit float (neural_inputs.glsl). A
// layer fragment is recognised by its depth, which reproduces bit for bit across passes (invariant
// gl_Position), as pass 2's peeling relies on. Why: the tail features subtract the layers from the
// sums (sum a - a1 - a2), and in 16-bit sums that difference loses the digits the layers take.
// Fragments at exactly a layer's depth besides the layer itself (duplicated faces) leave too.
layout(location = 0) out vec4 outAlphaColor;
layout(location = 1) out vec4 outColorCount;
layout(location = 2) out vec4 outTransmittance;
layout(binding = 0) uniform highp sampler2D u_nearestDepth;  // pass 1, full resolution
layout(binding = 1) uniform highp sampler2D u_secondDepth;   // pass 2, full resolution when read
uniform bool u_tailOnly;

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    if (u_tailOnly) {
        ivec2 p = ivec2(gl_FragCoord.xy);
        if (gl_FragCoord.z == texelFetch(u_nearestDepth, p, 0).r || gl_FragCoord.z == texelFetch(u_secondDepth, p, 0).r) discard;
    }
    outAlphaColor = vec4(s.rgb * s.a, s.a);
#ifdef STARNT_COUNT_ONLY
    outColorCount = vec4(1.0);  // an R32F target keeps .r
#else
    outColorCount = vec4(s.rgb, 1.0);
#endif
    outTransmittance = vec4(0.0, 0.0, 0.0, s.a);
}
