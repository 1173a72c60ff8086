// Texture readback into an Image (starnt::tools: the CLI, viewer and tests read results back; the
// runtime never does).
#pragma once
#include "gl/gl_util.hpp"
#include "starnt/tools/image.hpp"

namespace starnt::gl {

// Reads an RGBA float texture back into an Image (rows flipped so row 0 is the top).
Image readTexture(const Texture2D& texture);
Image readTexture(GLuint texture, int width, int height);

}  // namespace starnt::gl
