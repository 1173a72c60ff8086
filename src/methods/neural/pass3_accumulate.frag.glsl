// Pass 3: statistics over ALL fragments, no depth test.
//   target 0 (RGBA32F, blend ONE/ONE):                 sum a_i C_i, sum a_i
//   target 1 (RGBA32F, blend ONE/ONE):                 sum C_i, N
//            (R32F: N alone, with STARNT_COUNT_ONLY: the STAR-NT inputs need no sum of C_i,
//            which only DFAOIT reads; 12 bytes a pixel less)
//   target 2 (R32F,    blend ZERO/ONE_MINUS_SRC_ALPHA): prod (1 - a_i)
layout(location = 0) out vec4 outAlphaColor;
layout(location = 1) out vec4 outColorCount;
layout(location = 2) out vec4 outTransmittance;

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    outAlphaColor = vec4(s.rgb * s.a, s.a);
#ifdef STARNT_COUNT_ONLY
    outColorCount = vec4(1.0);  // an R32F target keeps .r
#else
    outColorCount = vec4(s.rgb, 1.0);
#endif
    outTransmittance = vec4(0.0, 0.0, 0.0, s.a);
}
