#include "io/texture_readback.hpp"

#include <algorithm>
#include <vector>

namespace starnt::gl {

Image readTexture(const Texture2D& texture) { return readTexture(texture.id(), texture.width(), texture.height()); }

Image readTexture(GLuint texture, int width, int height) {
    Image img(width, height);
    const std::vector<float> raw = readTextureFloats(texture, width, height, 4);
    const size_t row = size_t(img.width) * 4;
    for (int y = 0; y < img.height; ++y) {
        std::copy_n(&raw[size_t(img.height - 1 - y) * row], row, &img.rgba[size_t(y) * row]);
    }
    return img;
}

}  // namespace starnt::gl
