// Writes into the compact 16-bit float targets (NeuralOptions::Targets::Compact; the programs get
// STARNT_HALF_TARGETS): each value is rounded here to the nearest 16-bit float, ties to even, so the
// conversion the target's write does is exact whatever rounding the driver uses. llvmpipe truncates
// toward zero (measured: pass-1 colours and outputs 1-3 steps of 2^-11 low against a
// round-to-nearest CPU reference), a bias every pixel would carry; GPUs round to nearest, where
// this changes nothing. Blended writes (pass 3's sums) cannot be rounded this way.
// CPU reference: nn::roundToHalf.
#ifndef STARNT_HALF_TARGETS_GLSL
#define STARNT_HALF_TARGETS_GLSL
float nearestHalf(float v) {
    float a = min(abs(v), 65504.0);  // the largest finite 16-bit float
    if (a == 0.0) return 0.0;
    int e;
    frexp(a, e);  // a = m 2^e, m in [0.5, 1): 16-bit floats there are 2^(e - 11) apart (2^-24 below 2^-14)
    float step = ldexp(1.0, max(e - 11, -24));
    return sign(v) * roundEven(a / step) * step;
}

vec4 nearestHalf(vec4 v) { return vec4(nearestHalf(v.x), nearestHalf(v.y), nearestHalf(v.z), nearestHalf(v.w)); }

// The same for an output whose format is known only when the frame runs (`halfOutput`: RGBA16F).
vec4 outputValue(vec4 v, bool halfOutput) { return halfOutput ? nearestHalf(v) : v; }

vec4 targetValue(vec4 v) {
#ifdef STARNT_HALF_TARGETS
    return nearestHalf(v);
#else
    return v;
#endif
}

#ifdef STARNT_SPLIT_ALPHA
// DFAOIT's narrow layers (NeuralPasses, "Narrow layers"): the colour divided by 16^e and rounded
// here to the nearest step of the RGB10_A2 target (1/1023, clamped to [0, 1]), e (0..3) the least
// that brings the largest channel within 1, kept in the target's 2-bit alpha (docs/DESIGN.md,
// "HDR": LDR colours keep e = 0 and their bits; HDR ones up to 4096 keep 10 bits of their scale);
// the alpha to the nearest 16-bit float for the RG16F target. CPU reference:
// nn::narrowLayerColor.
void splitLayerValue(vec4 v, out vec4 color, out vec2 alpha) {
    float peak = max(max(v.r, v.g), v.b);
    // Thresholds half a step above each scale, so that a lit LDR colour rounding a hair above 1 keeps e = 0.
    float e = peak > 1.0 + 0.5 / 1023.0 ? (peak > 16.0 * (1.0 + 0.5 / 1023.0) ? (peak > 256.0 * (1.0 + 0.5 / 1023.0) ? 3.0 : 2.0) : 1.0) : 0.0;
    color = vec4(round(clamp(v.rgb / exp2(4.0 * e), 0.0, 1.0) * 1023.0) / 1023.0, e / 3.0);
    alpha = vec2(nearestHalf(v.a));
}
// The colour a narrow layer holds (splitLayerValue's stored value).
vec3 narrowLayerColor(vec4 stored) { return stored.rgb * exp2(4.0 * round(stored.a * 3.0)); }
#endif
#endif
