// Constants of the tools' built-in scene renderer shared by C++ and GLSL (included from both; keep
// it to #defines). The methods' binding points are in the public starnt/bindings.h.
#ifndef STARNT_SHARED_CONSTANTS_H
#define STARNT_SHARED_CONSTANTS_H

#include "starnt/bindings.h"

// Texture unit of the scene renderer's material texture (an engine-side unit, at or above
// STARNT_ENGINE_FIRST_TEXTURE_UNIT).
#define STARNT_SURFACE_TEXTURE_UNIT 15

// Vertex attribute locations of the built-in scene renderer.
#define STARNT_ATTRIB_POSITION 0
#define STARNT_ATTRIB_NORMAL 1
#define STARNT_ATTRIB_UV 2
#define STARNT_ATTRIB_COLOR 3

#endif
