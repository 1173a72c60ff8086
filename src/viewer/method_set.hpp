// The OIT methods the viewer shows: the selected one, and a second one for the split screen. They
// are rebuilt whenever the method or its acceleration options change (a rebuild costs a shader
// compile, about half a second on llvmpipe); alpha, background and camera are per-frame inputs.
#pragma once
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "gl/gpu_timer.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/camera.hpp"
#include "viewer/viewer_settings.hpp"

namespace starnt::viewer {

struct RenderedFrame {
    double frameMs = 0.0;                   // the primary method, glFinish to glFinish
    std::map<std::string, double> passMs;   // its per-pass times
    std::map<std::string, gl::PassCounters> passCounters;  // its per-pass work
    FrameStats methodStats;             // its lastFrameStats()
    bool interpolated = false;
};

class MethodSet {
public:
    // Builds the methods of `initial`; throws starnt::Error like configure().
    explicit MethodSet(const ViewerSettings& initial);
    // Builds the methods `settings` asks for when they differ from the current ones. Throws
    // starnt::Error (e.g. bad weights) and then keeps the previous methods.
    void configure(const ViewerSettings& settings);
    // Renders the primary method (timed) and the split method (untimed) at `size`.
    RenderedFrame render(const SceneGpu& scene, const Camera& camera, glm::ivec2 size, const ViewerSettings& settings);
    // Forgets temporal history (scene change, camera cut).
    void resetHistory();

    OitMethod& primary() { return *primary_; }
    OitMethod* split() { return split_.get(); }
    size_t gpuMemoryBytes() const;
    const char* timingMode() const;

private:
    ViewerSettings built_;  // what the methods were made from
    std::unique_ptr<OitMethod> primary_, split_;
    gl::GpuPassTimer timer_;
};

// Surface options (global alpha) of the settings.
SurfaceOptions surfaceOptions(const ViewerSettings& settings);
// FrameDesc of one viewer frame.
FrameDesc frameDesc(const Camera& camera, glm::ivec2 size, const ViewerSettings& settings);

}  // namespace starnt::viewer
