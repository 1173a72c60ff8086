// The nearest fragment found by blending (corrected interpolated frames in one geometry pass;
// docs/DESIGN.md, "Corrected frames in one geometry pass"): shared by packed_nearest.glsl and its
// CPU reference temporal::packNearest (included from C++ and GLSL; keep it to #defines).
//
// Every fragment writes, into each channel of an RGBA32F target blended with GL_MIN, the bits
//   0x40000000 | key << STARNT_PACKED_PAYLOAD_BITS | payload
// with `key` its depth (nearer = smaller) and `payload` one of its r, g, b, a. Positive floats order
// as their bits do, so MIN keeps, channel by channel, the payload of the nearest key. Bit 30 set and
// bit 29 clear keep every value a normal float (exponent 0x80..0xBF: no denormal a blender could
// flush, no infinity or NaN).
#ifndef STARNT_PACKED_NEAREST_H
#define STARNT_PACKED_NEAREST_H

#define STARNT_PACKED_KEY_BITS 18
#define STARNT_PACKED_PAYLOAD_BITS 11
// The clear value, in every channel: the largest key with every payload bit set (the empty pixel).
#define STARNT_PACKED_EMPTY_BITS 0x5FFFFFFFu
// key = (bits(1.0) - bits(w)) >> STARNT_PACKED_KEY_SHIFT with w = 1 - z (window depth z) and bits()
// a float's bits: the float's own logarithmic spacing, no transcendental function. A perspective
// projection makes w inversely proportional to the view distance, so the key's step is a fixed
// fraction of the distance (2^-13, about 1.2e-4) from w = 1 down to w = 2^-24 (keys 0..24 * 2^13);
// nearer than that to the far plane, the last key but one. The largest key is the empty pixel's
// (the clear value), never a fragment's.
#define STARNT_PACKED_KEY_SHIFT 10
// Colour payload: x = sqrt(c) / (1 + sqrt(c)) in STARNT_PACKED_STEPS steps, decoded as
// c = (x / (1 - x))^2: c = 1 at x = 1/2 (steps of at most 4e-3 below 1, finer in the darks), and up
// to STARNT_MAX_SURFACE_COLOR (1024) above, in steps of a few %. Alpha: linear steps.
#define STARNT_PACKED_STEPS 2047.0


// Two layers (corrected frames of the tail-moment methods where EXT_shader_framebuffer_fetch exists;
// docs/DESIGN.md, "Corrected frames: the second layer by framebuffer fetch"): an RGBA32UI target
// that every fragment reads and rewrites in draw order, the nearest fragment in .xy and the nearest
// one behind it (a larger key) in .zw, each as 64 bits, from the top: the key
// (STARNT_PACKED_LAYER_KEY_BITS), alpha (STARNT_PACKED_LAYER_ALPHA_BITS, linear steps; it straddles
// the two words), then b, g and r (STARNT_PACKED_LAYER_B_BITS, _G_BITS, _R_BITS) down to bit 0 of
// the second word. A colour c is kept as x = STARNT_PACKED_LAYER_LDR_SHARE sqrt(c) up to c = 1 and
// logarithmically in sqrt(c) above, up to STARNT_MAX_SURFACE_COLOR (1024) at x = 1: three quarters
// of the steps for [0, 1] (10 bits: 2.0e-3 at c = 0.6, finer in the darks; the encoding above spends
// half its steps above 1 and would need 11 bits for that). The logarithm above 1 is read off the
// float bits of sqrt(c) (exponent plus mantissa fraction, linear between powers of two: no
// transcendental function for every fragment to pay), so its steps are 2.0-3.9 % of c rather than
// a true logarithm's 2.7 %.
// The key orders fragments as their window depths z do: from z = STARNT_PACKED_LAYER_EXACT_DEPTH on
// it is the float bits of z less those of that depth, exact, so surfaces closer together than any
// coarser step (chess's board) are ordered as pass 1's and pass 2's depth tests order them, and
// the key decodes to z itself; nearer, in steps of 2^STARNT_PACKED_LAYER_COARSE_SHIFT float ulps
// from STARNT_PACKED_LAYER_NEAREST_DEPTH (z below that counts as that). A fragment whose key equals
// a layer's loses to it (the first drawn stays, as pass 1's LESS depth test and pass 2's peel keep
// it). Clear: x and z STARNT_PACKED_LAYER_EMPTY (the largest key, every other bit set), y and w 0.
// Three layers (STARNT_PACKED_THREE_LAYERS; docs/DESIGN.md, "Corrected frames: three layers and no
// correction"): the third nearest in an RGBA32UI target of its own, in the same 64 bits (.xy),
// cleared to (STARNT_PACKED_LAYER_EMPTY, 0); beside it (.z) the float bits of the pixel's reference
// depth (ordered_behind.glsl), which pass 3 reads there and writes back unchanged: a texel its
// framebuffer fetch has read anyway, where a texture fetch for every fragment cost 35-45 ms of a
// 420-450 ms interpolated frame on llvmpipe (hairball, 1280x720). Written with the clear
// (third_layer_clear.frag.glsl) or by the composite that clears the targets; .w the pixel's pivot,
// the u its first fragment of pass 3 took (pass3_accumulate.frag.glsl), about which the moments
// behind the reference are summed.
#define STARNT_PACKED_LAYER_KEY_BITS 25
#define STARNT_PACKED_LAYER_ALPHA_BITS 10
#define STARNT_PACKED_LAYER_R_BITS 10
#define STARNT_PACKED_LAYER_G_BITS 10
#define STARNT_PACKED_LAYER_B_BITS 9
#define STARNT_PACKED_LAYER_NEAREST_DEPTH 0.015625  // 2^-6
#define STARNT_PACKED_LAYER_NEAREST_BITS 0x3C800000u  // its float bits
#define STARNT_PACKED_LAYER_EXACT_DEPTH 0.25
#define STARNT_PACKED_LAYER_EXACT_BITS 0x3E800000u
#define STARNT_PACKED_LAYER_COARSE_SHIFT 3
#define STARNT_PACKED_LAYER_LDR_SHARE 0.75
#define STARNT_PACKED_LAYER_HDR_LOG2_RANGE 5.0  // log2 sqrt(STARNT_MAX_SURFACE_COLOR)
#define STARNT_PACKED_LAYER_EMPTY 0xFFFFFFFFu

#endif
