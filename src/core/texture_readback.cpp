#include "core/texture_readback.hpp"

#include <algorithm>
#include <vector>

namespace starnt::gl {

Image readTexture(const Texture2D& texture) { return readTexture(texture.id(), texture.width(), texture.height()); }

Image readTexture(GLuint texture, int width, int height) {
    Image img(width, height);
    std::vector<float> raw(img.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(raw.size() * sizeof(float)), raw.data());
    const size_t row = size_t(img.width) * 4;
    for (int y = 0; y < img.height; ++y) {
        std::copy_n(&raw[size_t(img.height - 1 - y) * row], row, &img.rgba[size_t(y) * row]);
    }
    return img;
}

}  // namespace starnt::gl
