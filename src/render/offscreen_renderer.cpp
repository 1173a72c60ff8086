#include "render/offscreen_renderer.hpp"
#include "render/frame_stats_json.hpp"
#include "render/long_run_frame_time.hpp"
#include "io/texture_readback.hpp"

#include <algorithm>
#include <chrono>
#include <optional>
#include <fstream>
#include <limits>
#include <map>

#include <unistd.h>
#include <numeric>

#include "gl/gl_util.hpp"
#include "gl/gpu_timer.hpp"
#include "render/gpu_estimate.hpp"
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
nlohmann::json nullableMedian(const std::vector<double>& v) { return v.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(v)); }

// `pass_counters`: pass name -> {"vertex_invocations", "fragment_invocations", "primitives",
// "samples_passed" (where counted)},
// each divided by `frames` (the mean per frame over several frames; passes a frame did not run
// count 0 for it).
nlohmann::json countersJson(const std::map<std::string, gl::PassCounters>& counters, size_t frames = 1) {
    nlohmann::json out = nlohmann::json::object();
    const double n = double(std::max<size_t>(frames, 1));
    for (const auto& [name, c] : counters) {
        out[name] = {{"vertex_invocations", double(c.vertexInvocations) / n},
                     {"fragment_invocations", double(c.fragmentInvocations) / n},
                     {"primitives", double(c.primitives) / n}};
        if (c.samplesCounted) out[name]["samples_passed"] = double(c.samplesPassed) / n;
    }
    return out;
}

// `pass_blend` (gl/pass_blend.hpp): pass name -> bytes a fragment writes by format class, always
// naming float32, float16, unorm16, unorm8 and uint32 (0 where unused) so that "float32: 0" is a
// value a check reads, and the bits a pixel of the pass's colour targets hold.
nlohmann::json passBlendJson(const std::map<std::string, gl::PassBlend>& passes) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [name, blend] : passes) {
        nlohmann::json pass = {{"float32", 0.0}, {"float16", 0.0}, {"unorm16", 0.0}, {"unorm8", 0.0}, {"uint32", 0.0}};
        for (const auto& [cls, bytes] : blend.bytesByClass) pass[cls] = bytes;
        pass["target_bits_per_pixel"] = blend.targetBitsPerPixel;
        out[name] = pass;
    }
    return out;
}

}  // namespace

namespace {

// One renderScene call, in the order the data flows: check the job, warm up, then per frame render
// (timed), read back, measure the error against the reference and record; finally the summary.
class SceneRun {
public:
    SceneRun(const SceneGpu& scene, const RenderJob& job)
        : scene_(scene), job_(job), surface_(SceneGpu::surfaceShader()), timer_(gl::wallClockTimingNeeded()),
          gpuFrameTimes_(!gl::wallClockTimingNeeded()) {
        checkImageSize(job.width, job.height);
        if (job.frames < 1) throw Error("--frames must be at least 1");
        method_ = createMethod(job.method, surface_, job.methodOptions);
        if (!job.referenceMethod.empty()) reference_ = createMethod(job.referenceMethod, surface_, job.referenceOptions);
        if (job.referenceImages) {
            if (reference_) throw Error("internal: referenceMethod and referenceImages exclude each other");
            if (job.referenceImages->size() < size_t(job.frames)) throw Error("internal: fewer reference images than frames");
            for (const Image& ref : *job.referenceImages) {
                if (ref.width != job.width || ref.height != job.height) throw Error("internal: reference image size differs from the job's");
            }
        }
        compared_ = reference_ || job.referenceImages;
        frame_.width = job.width;
        frame_.height = job.height;
        frame_.background = job.background;
        frame_.alphaCutoff = job.alphaCutoff;
    }

    RenderOutput run() {
        warmUp();
        for (int i = 0; i < job_.frames; ++i) renderFrame(i);
        return summary();
    }

private:
    Camera cameraOf(int i) const { return job_.path ? job_.path->frame(i, job_.frames) : job_.camera; }
    void aimAt(FrameDesc& frame, const Camera& camera) const {
        frame.view = camera.view();
        frame.projection = camera.projection(float(job_.width) / float(job_.height));
    }

    // Untimed frames at the first camera: shader compiles; the tiles settle. At least
    // job_.warmupFrames, then on to the end of the temporal group they stopped in, so that the timed
    // frames start at a real frame whatever K is (docs/DESIGN.md, "Benchmark").
    void warmUp() {
        int lastReal = 0, interval = 1;
        const int cap = job_.warmupFrames + kMaxTemporalInterval;
        while (warmedUp_ < job_.warmupFrames || (warmedUp_ > 0 && warmedUp_ - lastReal < interval && warmedUp_ < cap)) {
            FrameDesc warm = frame_;
            aimAt(warm, cameraOf(0));
            warm.timing = nullptr;
            scene_.drawOpaque(warm, job_.surface);
            method_->render(warm, scene_.callback(warm.view, warm.projection, job_.surface));
            glFinish();
            const FrameStats stats = method_->lastFrameStats();
            if (!stats.interpolated()) {
                lastReal = warmedUp_;
                interval = stats.neural ? std::max(1, stats.neural->temporalInterval) : 1;
            }
            ++warmedUp_;
        }
    }

    void renderFrame(int i) {
        const Camera camera = cameraOf(i);
        aimAt(frame_, camera);
        frame_.timing = &timer_;
        // The engine's opaque pass (none without OPAQUE or MASK materials): not the method's time.
        scene_.drawOpaque(frame_, job_.surface);
        draw_ = scene_.callback(frame_.view, frame_.projection, job_.surface);

        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        // On a GPU also a GL_TIMESTAMP pair around the whole frame: the GPU's time alone, without the
        // driver's submission on the CPU that glFinish + wall clock includes (docs/DESIGN.md, "Benchmark").
        if (gpuFrameTimes_) frameTimer_.begin("frame");
        method_->render(frame_, draw_);
        if (gpuFrameTimes_) frameTimer_.end();
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        const std::optional<double> gpuMs =
            gpuFrameTimes_ ? std::optional<double>(frameTimer_.collect()["frame"]) : std::nullopt;
        const auto passes = timer_.collect();
        const auto counters = timer_.collectCounters();
        const auto blend = timer_.collectBlend();
        // (none without fragment counts: OpenGL ES has no pipeline statistics queries)
        const std::optional<double> estimateMs =
            timer_.countersAvailable() ? std::optional(gpuEstimateMs(counters, blend, passes, job_.width, job_.height)) : std::nullopt;
        const FrameStats typedStats = method_->lastFrameStats();
        const nlohmann::json methodStats = frameStatsJson(typedStats);
        const bool interpolated = typedStats.interpolated();
        interpolatedFrames_ += interpolated ? 1 : 0;

        FrameRecord record;
        record.index = i;
        record.camera = camera;
        record.stats = {{"frame", i}, {"frame_ms", ms}, {"frame_gpu_ms", gpuMs ? nlohmann::json(*gpuMs) : nlohmann::json(nullptr)},
                        {"interpolated", interpolated}, {"pass_ms", passes},
                        {"pass_counters", countersJson(counters)}, {"pass_blend", passBlendJson(blend)},
                        {"gpu_estimate_ms", estimateMs ? nlohmann::json(*estimateMs) : nlohmann::json(nullptr)},
                        {"memory_bytes", method_->gpuMemoryBytes()},
                        {"rss_bytes", residentMemoryBytes()}};
        for (const char* key : {"scale_pass2", "scale_pass3", "w_bar", "tile_levels", "probe_frame", "shading_rate_image", "shading_rate_tiles"}) {
            if (methodStats.contains(key)) record.stats[key] = methodStats[key];
        }
        // With qualityEvery = n > 1, the error is measured on three frames in every n (a real frame
        // and the interpolated frames beside it at K <= 3): FLIP runs on the CPU, and a long timed
        // run on a GPU would otherwise spend most of its time there.
        const bool compareThis = compared_ && (job_.qualityEvery <= 1 || i % job_.qualityEvery < 3);
        if (job_.readEveryFrame || compareThis || i + 1 == job_.frames) {
            image_ = gl::readTexture(method_->outputTexture(), job_.width, job_.height);
        }
        const Image* referenceOfFrame = compareThis ? referenceOf(i) : nullptr;
        if (referenceOfFrame) measureError(*referenceOfFrame, interpolated, record);
        if (job_.onFrame) {
            record.image = (job_.readEveryFrame || compareThis) ? &image_ : nullptr;
            record.reference = referenceOfFrame;
            job_.onFrame(record);
        }
        if (!blend.empty()) (interpolated ? interpolatedBlend_ : realBlend_) = blend;
        // Without warm-up frames the first frame compiles shaders on first use: not timed then.
        if (i == 0 && job_.frames > 1 && job_.warmupFrames == 0) return;
        frameMs_.push_back(ms);
        if (gpuMs) frameGpuMs_.push_back(*gpuMs);
        (interpolated ? interpolatedMs_ : realMs_).push_back(ms);
        if (estimateMs) {
            estimateMs_.push_back(*estimateMs);
            (interpolated ? interpolatedEstimateMs_ : realEstimateMs_).push_back(*estimateMs);
        }
        if (gpuMs) (interpolated ? interpolatedGpuMs_ : realGpuMs_).push_back(*gpuMs);
        realShareSum_ += typedStats.neural ? 1.0 / double(std::max(typedStats.neural->temporalInterval, 1)) : 1.0;
        for (auto& [name, value] : passes) passMs_[name].push_back(value);
        for (auto& [name, value] : counters) counterSums_[name] += value;
    }

    // Frame i of the reference: rendered now by the reference method, or precomputed.
    const Image* referenceOf(int i) {
        if (reference_) {
            FrameDesc untimed = frame_;
            untimed.timing = nullptr;
            reference_->render(untimed, draw_);
            referenceImage_ = gl::readTexture(reference_->outputTexture(), job_.width, job_.height);
            return &referenceImage_;
        }
        return job_.referenceImages ? &(*job_.referenceImages)[size_t(i)] : nullptr;
    }

    void measureError(const Image& reference, bool interpolated, FrameRecord& record) {
        const double mse = mseSrgb(reference, image_);
        const double flipMean = flip(reference, image_, job_.flipPixelsPerDegree).mean;
        record.stats["mse"] = mse;
        record.stats["flip"] = flipMean;
        (interpolated ? mseInterp_ : mseReal_).push_back(mse);
        msePerFrame_.emplace_back(interpolated, mse);
        (interpolated ? flipInterp_ : flipReal_).push_back(flipMean);
    }

    RenderOutput summary() {
        RenderOutput out;
        out.image = std::move(image_);
        // Memory of the frames as rendered: taken before the debug overlay below is allocated.
        const size_t memoryBytes = method_->gpuMemoryBytes();
        nlohmann::json memoryTargets = nlohmann::json::object();
        for (const auto& [name, bytes] : method_->gpuMemoryTargets()) memoryTargets[name] = bytes;
        if (job_.readTileOverlay) {
            if (GLuint overlay = method_->tileOverlayTexture()) out.tileOverlay = gl::readTexture(overlay, job_.width, job_.height);
        }

        // Depth complexity is measured by a separate counting pass at the last camera, outside the
        // timed frames, so every method reports the same max_fragments.
        DepthComplexityCounter counter(surface_);
        FrameDesc untimed = frame_;
        untimed.timing = nullptr;
        const unsigned maxFragments = counter.count(untimed, draw_);

        nlohmann::json passes = nlohmann::json::object();
        for (auto& [name, values] : passMs_) passes[name] = median(values);
        nlohmann::json methodStats = frameStatsJson(method_->lastFrameStats());
        out.stats = {
            {"method", job_.method},
            {"width", job_.width},
            {"height", job_.height},
            {"frame_ms", median(frameMs_)},
            {"frame_ms_mean", mean(frameMs_)},
            {"real_frame_ms", nullableMedian(realMs_)},
            {"interpolated_frame_ms", nullableMedian(interpolatedMs_)},
            {"real_frame_ms_mean", nullableMean(realMs_)},
            {"interpolated_frame_ms_mean", nullableMean(interpolatedMs_)},
            {"frame_gpu_ms_mean", nullableMean(frameGpuMs_)},  // null where timestamps are no GPU times (llvmpipe)
            // The long-run cost per frame (long_run_frame_time.hpp): what a bench compares.
            {"real_frame_share", frameMs_.empty() ? nlohmann::json(nullptr) : nlohmann::json(realShareSum_ / double(frameMs_.size()))},
            {"frame_ms_long_run", longRunOrWindowMean(realMs_, interpolatedMs_, frameMs_)},
            {"frame_gpu_ms_long_run", longRunOrWindowMean(realGpuMs_, interpolatedGpuMs_, frameGpuMs_)},
            {"pass_ms", passes},
            {"pass_counters", countersJson(counterSums_, frameMs_.size())},
            // What each geometry pass writes a fragment (the real frames'; the interpolated frames' apart).
            {"pass_blend", passBlendJson(realBlend_)},
            // A GPU's frame time predicted from the counters and pass_blend (render/gpu_estimate.hpp):
            // an estimate, apart from every measured time.
            {"gpu_estimate_ms_mean", nullableMean(estimateMs_)},
            {"gpu_estimate_ms_long_run", longRunOrWindowMean(realEstimateMs_, interpolatedEstimateMs_, estimateMs_)},
            {"gpu_estimate_model", gpuEstimateModel().source},
            {"pass_counters_source", timer_.countersAvailable() ? "GL_ARB_pipeline_statistics_query, mean per timed frame"
                                                                : "unavailable (no pipeline statistics queries)"},
            {"scale_pass2", 1.0},
            {"scale_pass3", 1.0},
            {"w_bar", nullptr},
            {"tile_levels", nlohmann::json::array({0, 0, 0, 0})},
            {"max_fragments", maxFragments},
            {"memory_bytes", memoryBytes},
            {"memory_targets", memoryTargets},
            {"scene_memory_bytes", scene_.gpuMemoryBytes()},
            {"frames", job_.frames},
            {"timed_frames", frameMs_.size()},
            {"warmup_frames", warmedUp_},
            {"interpolated_frames", interpolatedFrames_},
            {"pass_timing", gl::passTimingDescription()},
            {"method_stats", methodStats},
        };
        if (!interpolatedBlend_.empty()) out.stats["pass_blend_interpolated"] = passBlendJson(interpolatedBlend_);
        for (auto& [key, value] : methodStats.items()) {
            if (out.stats.contains(key) && key != "max_fragments" && key != "frames") out.stats[key] = value;
        }
        if (compared_) {
            out.stats["reference_method"] = reference_ ? job_.referenceMethod : std::string("precomputed images");
            out.stats["error"] = {
                {"real", {{"frames", mseReal_.size()}, {"mse_mean", nullableMean(mseReal_)}, {"flip_mean", nullableMean(flipReal_)}}},
                {"interpolated",
                 {{"frames", mseInterp_.size()}, {"mse_mean", nullableMean(mseInterp_)}, {"flip_mean", nullableMean(flipInterp_)}}},
            };
            if (const auto flash = worstInterpolatedFlash(msePerFrame_)) {
                out.stats["error"]["interpolated_flash"] = {
                    {"worst_ratio", flash->ratio}, {"frame", flash->frame}, {"mse", flash->mse}, {"real_mse_beside", flash->realBeside}};
            }
        }
        return out;
    }

    const SceneGpu& scene_;
    const RenderJob& job_;
    const SurfaceShader surface_;
    std::unique_ptr<OitMethod> method_, reference_;
    bool compared_ = false;
    FrameDesc frame_;
    gl::GpuPassTimer timer_;
    const bool gpuFrameTimes_;       // timestamps are GPU times (not llvmpipe's, not ES without the extension)
    gl::GpuPassTimer frameTimer_;    // the whole frame, apart from timer_'s passes
    DrawCallback draw_;             // the last frame's, for the depth-complexity count
    Image image_, referenceImage_;  // the last frame read back, and its reference
    // Timed frames (after the warm-up): frame times, per-pass times and work counters.
    std::vector<double> frameMs_, realMs_, interpolatedMs_, frameGpuMs_, realGpuMs_, interpolatedGpuMs_;
    double realShareSum_ = 0.0;  // sum over the timed frames of 1 / K
    std::vector<double> estimateMs_, realEstimateMs_, interpolatedEstimateMs_;  // gpu_estimate.hpp, per timed frame
    std::map<std::string, gl::PassBlend> realBlend_, interpolatedBlend_;       // the last of each kind of frame

    nlohmann::json longRunOrWindowMean(const std::vector<double>& real, const std::vector<double>& interpolated,
                                       const std::vector<double>& all) const {
        if (all.empty()) return nullptr;
        const std::optional<double> v = longRunFrameMs(real, interpolated, realShareSum_ / double(frameMs_.size()));
        return v ? *v : mean(all);
    }
    std::map<std::string, std::vector<double>> passMs_;
    std::map<std::string, gl::PassCounters> counterSums_;
    int interpolatedFrames_ = 0;
    int warmedUp_ = 0;  // warm-up frames rendered (warmUp: at least job_.warmupFrames)
    // Errors of the compared frames, by kind, and in order (for the flash).
    std::vector<double> mseReal_, mseInterp_, flipReal_, flipInterp_;
    std::vector<std::pair<bool, double>> msePerFrame_;
};

}  // namespace

RenderJob sizedJob(int width, int height, int frames, int warmupFrames, const glm::vec3& background, float alphaCutoff) {
    return RenderJob{.width = width,
                     .height = height,
                     .background = background,
                     .alphaCutoff = alphaCutoff,
                     .frames = frames,
                     .warmupFrames = warmupFrames};
}

RenderOutput renderScene(const SceneGpu& scene, const RenderJob& job) { return SceneRun(scene, job).run(); }

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
        if (!worst || ratio > worst->ratio) worst = InterpolatedFlash{ratio, i, mse, adjacent};
    }
    return worst;
}

}  // namespace starnt
