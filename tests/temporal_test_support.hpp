// Helpers shared by the temporal tests (refresh and corrected frames): texture upload and read-back
// in GL order, a test camera, sequences rendered by the starnt method with a turning camera, and
// per-pixel layer counts from a fragment capture.
#pragma once
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/gl_util.hpp"
#include "methods/registry.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/nn.hpp"
#include "starnt/tools/scene.hpp"
#include "test_support.hpp"

namespace starnt::test {

inline gl::Texture2D uploadRgba(const std::vector<glm::vec4>& p, int w, int h) {
    gl::Texture2D t(GL_RGBA32F, w, h);
    gl::uploadTexture(t.id(), w, h, GL_RGBA, GL_FLOAT, p.data());
    return t;
}

inline std::vector<glm::vec4> readRgba(GLuint texture, int w, int h) {
    std::vector<glm::vec4> out(size_t(w) * size_t(h));
    const std::vector<float> floats = gl::readTextureFloats(texture, w, h, 4);
    std::memcpy(out.data(), floats.data(), floats.size() * sizeof(float));
    return out;
}

// Mean squared error of the RGB channels between two images of the same size (alpha left out).
inline double rgbMse(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        for (int ch = 0; ch < 3; ++ch) sum += double(a[i][ch] - b[i][ch]) * double(a[i][ch] - b[i][ch]);
    return sum / double(3 * a.size());
}

// An RGBA32UI texture's texels in GL order.
inline std::vector<glm::uvec4> readRgbaUint(GLuint texture, int w, int h) {
    std::vector<glm::uvec4> out(size_t(w) * size_t(h));
    gl::readTexture(texture, w, h, GL_RGBA_INTEGER, GL_UNSIGNED_INT, out.data(), out.size() * sizeof(glm::uvec4));
    return out;
}

// A camera 4 units from the origin turned by `yawDeg` about +Y.
inline glm::mat4 turnedViewProj(int w, int h, float yawDeg) {
    const glm::mat4 proj = glm::perspective(glm::radians(50.0f), float(w) / float(h), 0.5f, 20.0f);
    const glm::mat4 view = glm::rotate(glm::mat4(1.0f), glm::radians(yawDeg), glm::vec3(0, 1, 0)) *
                           glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, -0.1f, -4.0f));
    return proj * view;
}

// The scene's frame with its camera turned about its target by +yaw degrees around y.
inline FrameDesc turnedFrame(const TestScene& c, float yaw) {
    Camera cam = c.camera;
    const glm::vec3 offset = cam.position - cam.target;
    cam.position = cam.target + glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(yaw), glm::vec3(0, 1, 0)) * glm::vec4(offset, 0.0f));
    FrameDesc f = c.frame();
    f.view = cam.view();
    f.projection = cam.projection(c.aspect());
    return f;
}

// Renders `yaws` with the starnt method and `options`, the camera turned about its target by +yaw
// around y (over FrameDesc::backgroundTexture `background` where given; the projection
// `clipTransform` x the camera's, e.g. a z flip for a reversed projection); returns each output in
// GL order.
inline std::vector<std::vector<glm::vec4>> renderSequence(TestScene& c, const MethodOptions& options,
                                                          const std::vector<float>& yaws, const std::string& name = "starnt",
                                                          GLuint background = 0, const glm::mat4& clipTransform = glm::mat4(1.0f)) {
    auto method = createMethod(name, SceneGpu::surfaceShader(), options);
    std::vector<std::vector<glm::vec4>> out;
    for (float yaw : yaws) {
        FrameDesc f = turnedFrame(c, yaw);
        f.projection = clipTransform * f.projection;
        f.backgroundTexture = background;
        method->render(f, c.gpu->callback(f.view, f.projection, {}));
        glFinish();
        out.push_back(readRgba(method->outputTexture(), c.width, c.height));
    }
    return out;
}

// Fragments per pixel (GL order) of built-in scene `name` (seed `seed`) seen from azimuth
// `azimuthDeg`, elevation `elevationDeg`: TestScene's azimuth turns the camera as renderSequence's yaw.
inline std::vector<int> layerCounts(const char* name, int seed, int w, int h, float azimuthDeg, float elevationDeg,
                                    const glm::vec3& background) {
    TestScene moved(makeBuiltinScene(name, seed), w, h, azimuthDeg, elevationDeg, background);
    const CapturedFrame f = moved.capture();
    std::vector<int> n(size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) n[size_t(h - 1 - y) * size_t(w) + size_t(x)] = int(nn::sumsFromFragments(f.at(x, y)).count + 0.5f);
    return n;
}

// Pixels at least 3 from the border covered by one fragment in `after` whose 5x5 neighbourhood held
// at most one in `before` (GL order indices).
inline std::vector<size_t> singleLayerPixels(const std::vector<int>& before, const std::vector<int>& after, int w, int h) {
    std::vector<size_t> out;
    for (int y = 3; y < h - 3; ++y)
        for (int x = 3; x < w - 3; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            if (after[i] != 1) continue;
            bool oneAround = true;
            for (int dy = -2; dy <= 2 && oneAround; ++dy)
                for (int dx = -2; dx <= 2; ++dx) oneAround = oneAround && before[size_t((y + dy) * w + x + dx)] <= 1;
            if (oneAround) out.push_back(i);
        }
    return out;
}

}  // namespace starnt::test
