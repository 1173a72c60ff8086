#include "viewer/method_set.hpp"

#include <chrono>

namespace starnt::viewer {
namespace {

std::unique_ptr<OitMethod> makeMethod(const std::string& name, const MethodOptions& options) {
    return createMethod(name, SceneGpu::surfaceShader(), options);
}

}  // namespace

SurfaceOptions surfaceOptions(const ViewerSettings& settings) {
    SurfaceOptions surface;
    surface.alphaOverride = settings.alpha;
    return surface;
}

FrameDesc frameDesc(const Camera& camera, glm::ivec2 size, const ViewerSettings& settings) {
    FrameDesc frame;
    frame.width = size.x;
    frame.height = size.y;
    frame.background = settings.background;
    frame.view = camera.view();
    frame.projection = camera.projection(float(size.x) / float(size.y));
    return frame;
}

MethodSet::MethodSet(const ViewerSettings& initial) : built_(initial), timer_(gl::wallClockTimingNeeded()) {
    primary_ = makeMethod(initial.method, initial.options);
    if (!initial.splitMethod.empty()) split_ = makeMethod(initial.splitMethod, initial.options);
}

void MethodSet::configure(const ViewerSettings& settings) {
    if (!needsNewMethods(built_, settings)) return;
    // Build both before replacing either, so a failure leaves a consistent pair.
    auto primary = makeMethod(settings.method, settings.options);
    std::unique_ptr<OitMethod> split;
    if (!settings.splitMethod.empty()) split = makeMethod(settings.splitMethod, settings.options);
    primary_ = std::move(primary);
    split_ = std::move(split);
    built_ = settings;
}

RenderedFrame MethodSet::render(const SceneGpu& scene, const Camera& camera, glm::ivec2 size,
                                const ViewerSettings& settings) {
    FrameDesc frame = frameDesc(camera, size, settings);
    scene.drawOpaque(frame, surfaceOptions(settings));
    const DrawCallback draw = scene.callback(frame.view, frame.projection, surfaceOptions(settings));
    RenderedFrame out;
    frame.timing = &timer_;
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    primary_->render(frame, draw);
    glFinish();
    out.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    out.passMs = timer_.collect();
    out.passCounters = timer_.collectCounters();
    out.methodStats = primary_->lastFrameStats();
    out.interpolated = out.methodStats.interpolated();
    if (split_) {
        frame.timing = nullptr;
        split_->render(frame, draw);
    }
    return out;
}

void MethodSet::resetHistory() {
    primary_->resetHistory();
    if (split_) split_->resetHistory();
}

size_t MethodSet::gpuMemoryBytes() const {
    return primary_->gpuMemoryBytes() + (split_ ? split_->gpuMemoryBytes() : 0);
}

const char* MethodSet::timingMode() const {
    return gl::passTimingDescription();
}

}  // namespace starnt::viewer
