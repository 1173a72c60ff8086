// Constants shared by C++ and GLSL (included from both; keep it to #defines).
#ifndef STARNT_SHARED_CONSTANTS_H
#define STARNT_SHARED_CONSTANTS_H

// Texture unit the engine's surface shader may use for its material texture; methods bind their
// own inputs to units below it.
#define STARNT_SURFACE_TEXTURE_UNIT 15

// Shader storage buffer bindings.
#define STARNT_SSBO_ABUFFER_HEADS 0
#define STARNT_SSBO_ABUFFER_NODES 1
#define STARNT_SSBO_ABUFFER_COUNTERS 2
#define STARNT_SSBO_ABUFFER_ORDERS 3
// Adaptive tiles: masks read (previous / current), masks written, per-tile occupancy, histogram.
#define STARNT_SSBO_TILE_MASKS_IN 4
#define STARNT_SSBO_TILE_MASKS_OUT 5
#define STARNT_SSBO_TILE_OCCUPANCY 6
#define STARNT_SSBO_TILE_HISTOGRAM 7
// Scale guard: per-tile sums (STARNT_GUARD_VALUES floats a tile).
#define STARNT_SSBO_TILE_GUARD 8

// A-buffer list terminator.
#define STARNT_ABUFFER_END 0xFFFFFFFFu

// Vertex attribute locations of the built-in scene renderer.
#define STARNT_ATTRIB_POSITION 0
#define STARNT_ATTRIB_NORMAL 1
#define STARNT_ATTRIB_UV 2
#define STARNT_ATTRIB_COLOR 3

#endif
