// Helpers shared by the scene loaders (not part of the public API).
#pragma once
#include <string>

#include "starnt/tools/scene.hpp"

namespace starnt::detail {

// Lower-case extension with the dot (".glb"), "" when none.
std::string lowerExtension(const std::string& path);

// One-line warning on stderr: "starnt: warning: MESSAGE".
void warn(const std::string& message);

// Converts decoded pixels (1-4 channels of 8 or 16 bits, rows top first) into an RGBA8 texture.
// `pixels` holds width*height*channels values of `bits` bits each (16-bit values in native order).
// Throws starnt::Error (prefixed with `context`) when the layout is not one of those.
Texture toRgba8(const unsigned char* pixels, size_t byteCount, int width, int height, int channels,
                int bits, const std::string& context);

}  // namespace starnt::detail
