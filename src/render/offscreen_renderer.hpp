// Renders a scene with one method for N frames and gathers the SPEC section 9 statistics.
// This is what `starnt render`, the tests and the benchmarks call.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "render/scene_gpu.hpp"
#include "starnt/camera.hpp"
#include "starnt/image.hpp"

namespace starnt {

struct RenderJob {
    std::string method = "abuffer";
    MethodOptions methodOptions;
    int width = 1920;
    int height = 1080;
    Camera camera;
    glm::vec3 background{1.0f};
    float alphaCutoff = 0.03f;
    SurfaceOptions surface;
    int frames = 1;  // timings are medians over the frames after the first (shader warm-up)
};

struct RenderOutput {
    Image image;           // last frame, linear
    nlohmann::json stats;  // SPEC section 9 fields plus method counters
};

// Largest width or height accepted (SPEC: over 16384 is an error).
constexpr int kMaxImageSize = 16384;
// Throws starnt::Error unless 1 <= width, height <= kMaxImageSize.
void checkImageSize(int width, int height);

RenderOutput renderScene(const SceneGpu& scene, const RenderJob& job);

double median(std::vector<double> values);

}  // namespace starnt
