#include "render/offscreen_renderer.hpp"
#include "render/frame_stats_json.hpp"
#include "io/texture_readback.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <limits>
#include <map>

#include <unistd.h>
#include <numeric>

#include "gl/gl_util.hpp"
#include "gl/gpu_timer.hpp"
#include "reference/fragment_capture.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"

namespace starnt {

void checkImageSize(int width, int height) {
    if (width < 1 || height < 1 || width > kMaxImageSize || height > kMaxImageSize) {
        throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range (1.." +
                    std::to_string(kMaxImageSize) + " per side)");
    }
}

size_t residentMemoryBytes() {
    // /proc/self/statm: size resident shared text lib data dt, in pages (Linux only; 0 elsewhere).
    std::ifstream statm("/proc/self/statm");
    size_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return 0;
    const long page = sysconf(_SC_PAGESIZE);
    return resident * size_t(page > 0 ? page : 4096);
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double mean(const std::vector<double>& v) {
    return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

namespace {

nlohmann::json nullableMean(const std::vector<double>& v) { return v.empty() ? nlohmann::json(nullptr) : nlohmann::json(mean(v)); }

// `pass_counters`: pass name -> {"vertex_invocations", "fragment_invocations", "primitives"},
// each divided by `frames` (the mean per frame over several frames; passes a frame did not run
// count 0 for it).
nlohmann::json countersJson(const std::map<std::string, gl::PassCounters>& counters, size_t frames = 1) {
    nlohmann::json out = nlohmann::json::object();
    const double n = double(std::max<size_t>(frames, 1));
    for (const auto& [name, c] : counters) {
        out[name] = {{"vertex_invocations", double(c.vertexInvocations) / n},
                     {"fragment_invocations", double(c.fragmentInvocations) / n},
                     {"primitives", double(c.primitives) / n}};
    }
    return out;
}

}  // namespace

RenderOutput renderScene(const SceneGpu& scene, const RenderJob& job) {
    checkImageSize(job.width, job.height);
    if (job.frames < 1) throw Error("--frames must be at least 1");
    const SurfaceShader surface = SceneGpu::surfaceShader();
    auto method = createMethod(job.method, surface, job.methodOptions);
    std::unique_ptr<OitMethod> reference;
    if (!job.referenceMethod.empty()) reference = createMethod(job.referenceMethod, surface, {});
    if (job.referenceImages) {
        if (reference) throw Error("internal: referenceMethod and referenceImages exclude each other");
        if (job.referenceImages->size() < size_t(job.frames)) throw Error("internal: fewer reference images than frames");
        for (const Image& ref : *job.referenceImages) {
            if (ref.width != job.width || ref.height != job.height) throw Error("internal: reference image size differs from the job's");
        }
    }
    const bool compared = reference || job.referenceImages;

    const float aspect = float(job.width) / float(job.height);
    FrameDesc frame;
    frame.width = job.width;
    frame.height = job.height;
    frame.background = job.background;
    frame.alphaCutoff = job.alphaCutoff;
    gl::GpuPassTimer timer(gl::wallClockTimingNeeded());

    // Per-frame timings; the first frame compiles shaders on first use and is excluded when there
    // are others.
    std::vector<double> frameMs, realMs, interpolatedMs;
    std::map<std::string, std::vector<double>> passMs;
    std::map<std::string, gl::PassCounters> counterSums;  // over the timed frames
    std::vector<double> mseReal, mseInterp, flipReal, flipInterp;
    std::vector<std::pair<bool, double>> msePerFrame;  // (interpolated, MSE) of every compared frame
    int interpolatedFrames = 0;
    Image image, referenceImage;
    DrawCallback draw;
    for (int w = 0; w < job.warmupFrames; ++w) {
        const Camera camera = job.path ? job.path->frame(0, job.frames) : job.camera;
        FrameDesc warm = frame;
        warm.view = camera.view();
        warm.projection = camera.projection(aspect);
        warm.timing = nullptr;
        method->render(warm, scene.callback(warm.view, warm.projection, job.surface));
        glFinish();
    }
    for (int i = 0; i < job.frames; ++i) {
        const Camera camera = job.path ? job.path->frame(i, job.frames) : job.camera;
        frame.view = camera.view();
        frame.projection = camera.projection(aspect);
        frame.timing = &timer;
        draw = scene.callback(frame.view, frame.projection, job.surface);

        glFinish();
        auto t0 = std::chrono::steady_clock::now();
        method->render(frame, draw);
        glFinish();
        auto t1 = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
        auto passes = timer.collect();
        const auto counters = timer.collectCounters();
        const FrameStats typedStats = method->lastFrameStats();
        const nlohmann::json methodStats = frameStatsJson(typedStats);
        const bool interpolated = typedStats.interpolated();
        interpolatedFrames += interpolated ? 1 : 0;

        FrameRecord record;
        record.index = i;
        record.camera = camera;
        record.stats = {{"frame", i}, {"frame_ms", ms}, {"interpolated", interpolated}, {"pass_ms", passes},
                        {"pass_counters", countersJson(counters)}, {"memory_bytes", method->gpuMemoryBytes()},
                        {"rss_bytes", residentMemoryBytes()}};
        for (const char* key : {"scale_pass2", "scale_pass3", "w_bar", "tile_levels", "probe_frame"}) {
            if (methodStats.contains(key)) record.stats[key] = methodStats[key];
        }
        const bool last = i + 1 == job.frames;
        // With qualityEvery = n > 1, the error is measured on three frames in every n (a real frame
        // and the interpolated frames beside it at K <= 3): FLIP runs on the CPU, and a long timed
        // run on a GPU would otherwise spend most of its time there.
        const bool compareThis = compared && (job.qualityEvery <= 1 || i % job.qualityEvery < 3);
        if (job.readEveryFrame || compareThis || last) image = gl::readTexture(method->outputTexture(), job.width, job.height);
        const Image* referenceOfFrame = nullptr;
        if (reference && compareThis) {
            FrameDesc untimed = frame;
            untimed.timing = nullptr;
            reference->render(untimed, draw);
            referenceImage = gl::readTexture(reference->outputTexture(), job.width, job.height);
            referenceOfFrame = &referenceImage;
        } else if (job.referenceImages && compareThis) {
            referenceOfFrame = &(*job.referenceImages)[size_t(i)];
        }
        if (referenceOfFrame) {
            const double mse = mseSrgb(*referenceOfFrame, image);
            const double flipMean = flip(*referenceOfFrame, image, job.flipPixelsPerDegree).mean;
            record.stats["mse"] = mse;
            record.stats["flip"] = flipMean;
            (interpolated ? mseInterp : mseReal).push_back(mse);
            msePerFrame.emplace_back(interpolated, mse);
            (interpolated ? flipInterp : flipReal).push_back(flipMean);
        }
        if (job.onFrame) {
            record.image = (job.readEveryFrame || compareThis) ? &image : nullptr;
            record.reference = referenceOfFrame;
            job.onFrame(record);
        }
        if (i == 0 && job.frames > 1 && job.warmupFrames == 0) continue;
        frameMs.push_back(ms);
        (interpolated ? interpolatedMs : realMs).push_back(ms);
        for (auto& [name, value] : passes) passMs[name].push_back(value);
        for (auto& [name, value] : counters) counterSums[name] += value;
    }

    RenderOutput out;
    out.image = std::move(image);
    // Memory of the frames as rendered: taken before the debug overlay below is allocated.
    const size_t memoryBytes = method->gpuMemoryBytes();
    nlohmann::json memoryTargets = nlohmann::json::object();
    for (const auto& [name, bytes] : method->gpuMemoryTargets()) memoryTargets[name] = bytes;
    if (job.readTileOverlay) {
        if (GLuint overlay = method->tileOverlayTexture()) out.tileOverlay = gl::readTexture(overlay, job.width, job.height);
    }

    // Depth complexity is measured by a separate counting pass at the last camera, outside the
    // timed frames, so every method reports the same max_fragments.
    DepthComplexityCounter counter(surface);
    FrameDesc untimed = frame;
    untimed.timing = nullptr;
    const unsigned maxFragments = counter.count(untimed, draw);

    nlohmann::json passes = nlohmann::json::object();
    for (auto& [name, values] : passMs) passes[name] = median(values);
    nlohmann::json methodStats = frameStatsJson(method->lastFrameStats());
    out.stats = {
        {"method", job.method},
        {"width", job.width},
        {"height", job.height},
        {"frame_ms", median(frameMs)},
        {"frame_ms_mean", mean(frameMs)},
        {"real_frame_ms", realMs.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(realMs))},
        {"interpolated_frame_ms", interpolatedMs.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(interpolatedMs))},
        {"real_frame_ms_mean", realMs.empty() ? nlohmann::json(nullptr) : nlohmann::json(mean(realMs))},
        {"interpolated_frame_ms_mean", interpolatedMs.empty() ? nlohmann::json(nullptr) : nlohmann::json(mean(interpolatedMs))},
        {"pass_ms", passes},
        {"pass_counters", countersJson(counterSums, frameMs.size())},
        {"pass_counters_source", timer.countersAvailable() ? "GL_ARB_pipeline_statistics_query, mean per timed frame"
                                                           : "unavailable (no pipeline statistics queries)"},
        {"scale_pass2", 1.0},
        {"scale_pass3", 1.0},
        {"w_bar", nullptr},
        {"tile_levels", nlohmann::json::array({0, 0, 0, 0})},
        {"max_fragments", maxFragments},
        {"memory_bytes", memoryBytes},
        {"memory_targets", memoryTargets},
        {"scene_memory_bytes", scene.gpuMemoryBytes()},
        {"frames", job.frames},
        {"timed_frames", frameMs.size()},
        {"warmup_frames", job.warmupFrames},
        {"interpolated_frames", interpolatedFrames},
        {"pass_timing", gl::passTimingDescription()},
        {"method_stats", methodStats},
    };
    for (auto& [key, value] : methodStats.items()) {
        if (out.stats.contains(key) && key != "max_fragments" && key != "frames") out.stats[key] = value;
    }
    if (compared) {
        out.stats["reference_method"] = reference ? job.referenceMethod : std::string("precomputed images");
        out.stats["error"] = {
            {"real", {{"frames", mseReal.size()}, {"mse_mean", nullableMean(mseReal)}, {"flip_mean", nullableMean(flipReal)}}},
            {"interpolated",
             {{"frames", mseInterp.size()}, {"mse_mean", nullableMean(mseInterp)}, {"flip_mean", nullableMean(flipInterp)}}},
        };
        if (const auto flash = worstInterpolatedFlash(msePerFrame)) {
            out.stats["error"]["interpolated_flash"] = {{"worst_ratio", flash->ratio}, {"frame", flash->frame}};
        }
    }
    return out;
}

std::optional<InterpolatedFlash> worstInterpolatedFlash(const std::vector<std::pair<bool, double>>& msePerFrame) {
    std::optional<InterpolatedFlash> worst;
    const int n = int(msePerFrame.size());
    for (int i = 0; i < n; ++i) {
        if (!msePerFrame[size_t(i)].first) continue;
        double sum = 0.0;
        int count = 0;
        for (int step : {-1, 1}) {  // the nearest real frame on each side, where there is one
            for (int j = i + step; j >= 0 && j < n; j += step) {
                if (msePerFrame[size_t(j)].first) continue;
                sum += msePerFrame[size_t(j)].second;
                ++count;
                break;
            }
        }
        if (count == 0) continue;
        const double adjacent = sum / count;
        const double mse = msePerFrame[size_t(i)].second;
        const double ratio = adjacent > 0.0 ? mse / adjacent : (mse > 0.0 ? std::numeric_limits<double>::infinity() : 1.0);
        if (!worst || ratio > worst->ratio) worst = InterpolatedFlash{ratio, i};
    }
    return worst;
}

}  // namespace starnt
