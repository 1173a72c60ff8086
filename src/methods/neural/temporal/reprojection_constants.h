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
// around (so over at least this many pixels in every direction).
#define STARNT_ORDERED_REFERENCE_TILE 16

#endif
