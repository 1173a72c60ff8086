// Storage-buffer bindings of the temporal reprojection shaders (included from C++ and GLSL; keep
// it to #defines). Above the A-buffer's bindings in shaders/shared_constants.h.
#ifndef STARNT_TEMPORAL_REPROJECTION_BINDINGS_H
#define STARNT_TEMPORAL_REPROJECTION_BINDINGS_H

#define STARNT_SSBO_TEMPORAL_COLOR 4          // vec4 per pixel: the last real frame's composite
#define STARNT_SSBO_TEMPORAL_DEPTH 5          // float per pixel: its pass-1 window depth
#define STARNT_SSBO_TEMPORAL_SPLATS 6         // uvec2 per source pixel: (target index, key) or "none"
#define STARNT_SSBO_TEMPORAL_WINNER_KEY 7     // uint per target pixel: nearest key
#define STARNT_SSBO_TEMPORAL_WINNER_SOURCE 8  // uint per target pixel: winning source index

// Holes take the farthest winner within this many pixels (2: a 5x5 window). 1 (3x3) fills only
// 1-pixel disocclusions; with 2 a 2-pixel parallax step is filled with the background.
#define STARNT_TEMPORAL_FILL_RADIUS 2

// "No splat" (matches temporal::kNoSplat in reprojection_reference.hpp).
#define STARNT_TEMPORAL_NONE 0xFFFFFFFFu

#endif
