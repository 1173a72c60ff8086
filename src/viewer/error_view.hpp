// The "error" view: the FLIP map of the primary method against the exact A-buffer for one camera.
// Computed on request only (a reference render plus FLIP on the CPU take about a second at 720p on
// llvmpipe), and shown only while camera, scene and settings are still the ones it was made for.
#pragma once
#include <optional>
#include <string>

#include "gl/gl_util.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/camera.hpp"
#include "viewer/viewer_settings.hpp"

namespace starnt::viewer {

class ErrorView {
public:
    // Renders the A-buffer at `camera` and compares it with `methodOutput` (the primary method's
    // output texture of the same frame).
    void compute(const SceneGpu& scene, int sceneGeneration, const Camera& camera, glm::ivec2 size,
                 const ViewerSettings& settings, GLuint methodOutput);
    // The heatmap texture when it still matches the inputs, else 0.
    GLuint heatmapFor(int sceneGeneration, const Camera& camera, glm::ivec2 size, const ViewerSettings& settings) const;
    bool computed() const { return bool(heatmap_); }
    double meanFlip() const { return meanFlip_; }
    double mse() const { return mse_; }
    void clear() { heatmap_ = {}; }

private:
    std::string keyOf(int sceneGeneration, const Camera& camera, glm::ivec2 size, const ViewerSettings& settings) const;

    std::unique_ptr<OitMethod> reference_;
    gl::Texture2D heatmap_;
    std::string key_;
    double meanFlip_ = 0.0, mse_ = 0.0;
};

}  // namespace starnt::viewer
