#include "render/offscreen_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <map>

#include "core/gpu_timer.hpp"
#include "reference/fragment_capture.hpp"
#include "starnt/error.hpp"

namespace starnt {

void checkImageSize(int width, int height) {
    if (width < 1 || height < 1 || width > kMaxImageSize || height > kMaxImageSize) {
        throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range (1.." +
                    std::to_string(kMaxImageSize) + " per side)");
    }
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

RenderOutput renderScene(const SceneGpu& scene, const RenderJob& job) {
    checkImageSize(job.width, job.height);
    if (job.frames < 1) throw Error("--frames must be at least 1");
    const SurfaceShader surface = SceneGpu::surfaceShader();
    auto method = createMethod(job.method, surface, job.methodOptions);

    FrameDesc frame;
    frame.width = job.width;
    frame.height = job.height;
    frame.background = job.background;
    frame.view = job.camera.view();
    frame.projection = job.camera.projection(float(job.width) / float(job.height));
    frame.alphaCutoff = job.alphaCutoff;
    gl::GpuPassTimer timer(gl::currentContextIsSoftware());
    frame.timer = &timer;
    const DrawCallback draw = scene.callback(frame.view, frame.projection, job.surface);

    std::vector<double> frameMs;
    std::map<std::string, std::vector<double>> passMs;
    for (int i = 0; i < job.frames; ++i) {
        glFinish();
        auto t0 = std::chrono::steady_clock::now();
        method->render(frame, draw);
        glFinish();
        auto t1 = std::chrono::steady_clock::now();
        auto passes = timer.collect();
        // The first frame compiles shaders on first use; it is excluded when there are others.
        if (i == 0 && job.frames > 1) continue;
        frameMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        for (auto& [name, ms] : passes) passMs[name].push_back(ms);
    }

    RenderOutput out;
    out.image = gl::readTexture(method->outputTexture(), job.width, job.height);

    // Depth complexity is measured by a separate counting pass, outside the timed frames, so every
    // method reports the same max_fragments.
    DepthComplexityCounter counter(surface);
    FrameDesc untimed = frame;
    untimed.timer = nullptr;
    const unsigned maxFragments = counter.count(untimed, draw);

    nlohmann::json passes = nlohmann::json::object();
    for (auto& [name, values] : passMs) passes[name] = median(values);
    nlohmann::json methodStats = method->lastFrameStats();
    out.stats = {
        {"method", job.method},
        {"width", job.width},
        {"height", job.height},
        {"frame_ms", median(frameMs)},
        {"pass_ms", passes},
        {"scale_pass2", 1.0},
        {"scale_pass3", 1.0},
        {"w_bar", nullptr},
        {"tile_levels", nlohmann::json::array({0, 0, 0, 0})},
        {"max_fragments", maxFragments},
        {"memory_bytes", method->gpuMemoryBytes()},
        {"scene_memory_bytes", scene.gpuMemoryBytes()},
        {"frames", job.frames},
        {"timed_frames", frameMs.size()},
        {"interpolated_frames", 0},
        {"pass_timing", timer.usesWallClock() ? "glFinish + wall clock (software rasteriser)" : "GL_TIMESTAMP pairs"},
        {"method_stats", methodStats},
    };
    for (auto& [key, value] : methodStats.items()) {
        if (out.stats.contains(key) && key != "max_fragments") out.stats[key] = value;
    }
    return out;
}

}  // namespace starnt
