// Draws linear RGBA32F images (method output, tile overlay, FLIP heatmap) into the window's
// default framebuffer, sRGB-encoded, whole or split in two; and reads the window back for screenshots.
#pragma once
#include <epoxy/gl.h>

#include <glm/glm.hpp>

#include "gl/shader.hpp"
#include "starnt/tools/image.hpp"

namespace starnt::viewer {

class DisplayPass {
public:
    DisplayPass();
    // Both textures must be `size`; `right` is shown from column splitX on (splitX < 0: left only).
    void draw(GLuint left, GLuint right, int splitX, glm::ivec2 size);

private:
    gl::Program program_;
    gl::VertexArrayHandle emptyVao_;
};

// The window's back buffer as a linear Image (decoded from its sRGB bytes), top row first.
Image readWindowImage(glm::ivec2 size);

// An RGBA32F texture holding `image` (top row first, as Image stores it), for display.
gl::Texture2D uploadImage(const Image& image);

}  // namespace starnt::viewer
