// Constants of the temporal reprojection, shared by its shader and its CPU reference (included
// from C++ and GLSL; keep it to #defines).
#ifndef STARNT_TEMPORAL_REPROJECTION_CONSTANTS_H
#define STARNT_TEMPORAL_REPROJECTION_CONSTANTS_H

// Depth-fetch steps of one search (one per seed); a search that has not met a consistent source by
// then gives up.
#define STARNT_TEMPORAL_SEARCH_STEPS 3
// Seeds: the min and max depth over the 3x3 blocks of this many pixels squared around the output
// pixel's block (so at least this many pixels around it).
#define STARNT_TEMPORAL_SEED_BLOCK 8

// A further seed is searched only when its first solution lies nearer than this fraction of the
// view depth of the source already found (so smooth surfaces do not search twice).
#define STARNT_TEMPORAL_NEARER 0.98
// Refresh frames: below this transmittance through the kept frame's nearest layer, what lay behind
// it is not divided out (it was hardly visible); the background stands in for it.
#define STARNT_TEMPORAL_MIN_TRANSMITTANCE 1e-4
// Refresh frames resample what lay behind the nearest layer bilinearly over the texels of the
// source's surface: those whose view depth differs from the source texel's by at most this fraction.
#define STARNT_TEMPORAL_SAME_SURFACE 0.01

// Corrected interpolated frames (closed_form_behind.glsl): below this alpha sum behind the nearest
// layer there is nothing there to average; the background stands in for the mean colour.
#define STARNT_TEMPORAL_MIN_BEHIND_ALPHA 1e-4

// Corrected frames of the tail-moment methods (ordered_behind.glsl): the reference depth is the
// nearest depth the last real frame's pass 1 kept over this many pixels squared and the tiles
// around (so over at least this many pixels in every direction), read at every STRIDE-th pixel
// of each row and column (a heuristic depth both kinds of frame share, not a bound: 0.6 against
// 2.7 ms a real frame at 720p on llvmpipe for every pixel).
#define STARNT_ORDERED_REFERENCE_TILE 16
#define STARNT_ORDERED_REFERENCE_STRIDE 4
// depthBehindReference's depth scale is STARNT_TAIL_MOMENT_DEPTH_SCALE x (1 - r), at least that
// many times this: a reference on the far plane (r = 1, nothing there in the frame it came from)
// still orders the fragments in front of it, by u ~ -ln(1 - z), the log of the view distance
// (docs/DESIGN.md, "Corrected frames: the reference depth follows the interpolated frames").
#define STARNT_ORDERED_MIN_REFERENCE_GAP 0.000244140625  // 2^-12
// The rounding of the nearest layer's alpha that the ordered closed form allows for when it tells
// a spread of fragments behind from one (ordered_behind.glsl): four steps of the packed layer's
// 11-bit alpha, above a 16-bit float's rounding of any alpha.
#define STARNT_ORDERED_ALPHA_ROUNDING 1e-3
// The ordered closed form's moments, recentred at a layer, are kept only where the tail's sum
// a (u - u_c)^2 is above this share of sum a u^2 about the reference over every fragment (the float32
// rounding of a hundred fragments' sums is 6e-6 of it): ordered_behind.glsl, dropRoundedMoments.
#define STARNT_ORDERED_RECENTRED_PRECISION 1e-5
// Their interpolated frames sum the transmittance as an optical depth, -ln(1 - a) per fragment
// (ordered_behind.glsl), with 1 - a at least this: an opaque fragment adds 39.1, a transmittance
// of 1e-17, so no sum reaches infinity.
#define STARNT_ORDERED_MIN_OPENNESS 1e-17

#endif
