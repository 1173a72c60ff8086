#include "viewer/display_pass.hpp"
#include "scene/tool_sources.hpp"

#include <algorithm>
#include <vector>

namespace starnt::viewer {

DisplayPass::DisplayPass()
    : program_(gl::buildProgram("viewer_display", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                                tools::toolSource("viewer/display.frag.glsl"))),
      emptyVao_(gl::makeEmptyVertexArray()) {}

void DisplayPass::draw(GLuint left, GLuint right, int splitX, glm::ivec2 size) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    if (!gl::isEs()) glDisable(GL_FRAMEBUFFER_SRGB);  // encoded in the shader (ES never converts a linear window)
    glUseProgram(program_.id());
    glUniform1i(program_.uniform("u_splitX"), right ? splitX : -1);
    gl::bindTexture(0, left);
    gl::bindTexture(1, right ? right : left);
    gl::drawFullscreenTriangle(emptyVao_);
}

Image readWindowImage(glm::ivec2 size) {
    std::vector<unsigned char> bytes(size_t(size.x) * size_t(size.y) * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    Image image(size.x, size.y);
    for (int y = 0; y < size.y; ++y) {
        const unsigned char* row = &bytes[size_t(size.y - 1 - y) * size_t(size.x) * 4];  // GL rows start at the bottom
        for (int x = 0; x < size.x; ++x) {
            float* out = image.pixel(x, y);
            for (int c = 0; c < 3; ++c) out[c] = srgbToLinear(float(row[x * 4 + c]) / 255.0f);
            out[3] = 1.0f;
        }
    }
    return image;
}

gl::Texture2D uploadImage(const Image& image) {
    gl::Texture2D texture(GL_RGBA32F, image.width, image.height);
    const size_t row = size_t(image.width) * 4;
    std::vector<float> flipped(image.rgba.size());
    for (int y = 0; y < image.height; ++y) {
        std::copy_n(&image.rgba[size_t(image.height - 1 - y) * row], row, &flipped[size_t(y) * row]);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl::uploadTexture(texture.id(), image.width, image.height, GL_RGBA, GL_FLOAT, flipped.data());
    return texture;
}

}  // namespace starnt::viewer
