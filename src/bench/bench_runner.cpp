#include "bench/bench_runner.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "bench/progress.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/metrics.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt::bench {
namespace {

namespace fs = std::filesystem;

// Scene names come from suite names or file stems; keep file names portable.
std::string fileSafe(const std::string& name) {
    std::string safe = name;
    for (char& ch : safe) {
        const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_';
        if (!ok) ch = '_';
    }
    return safe;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Everything a scene's jobs share: size, path, background, surface settings.
RenderJob baseJob(const Plan& plan, const SceneSpec& spec, const Scene& scene) {
    // White: the command line's default background.
    RenderJob job = sizedJob(plan.width, plan.height, plan.frames, plan.warmupFrames, glm::vec3(1.0f), spec.alphaCutoff);
    job.qualityEvery = plan.qualityEvery;
    job.surface = surfaceOptionsFor(spec);
    job.path = parseCameraPathSpec(plan.cameraPath, scene.bounds(), float(plan.width) / float(plan.height));
    return job;
}

class SceneBench {
public:
    SceneBench(const Plan& plan, const SceneSpec& spec, const fs::path& outDir, Progress& progress, const std::string& label)
        : plan_(plan), spec_(spec), outDir_(outDir), progress_(progress), label_(label),
          imageDir_(fs::path("images") / fileSafe(spec.name)) {}

    SceneResult run() {
        SceneResult result;
        result.spec = spec_;
        std::optional<Scene> scene;
        try {
            scene = loadScene(spec_.source);
        } catch (const std::exception& e) {
            result.loadError = e.what();
            progress_.skip(size_t(plan_.frames) * (1 + 2 * plan_.variants.size()));
            return result;
        }
        result.loaded = true;
        result.triangles = scene->triangleCount();
        if (!spec_.alphaOverride) {
            for (const Mesh& m : scene->meshes) {
                if (scene->materials[size_t(m.material)].alphaMode != AlphaMode::Blend) result.opaqueTriangles += m.indices.size() / 3;
            }
        }
        fs::create_directories(outDir_ / imageDir_);
        SceneGpu gpu(*scene);
        renderGroundTruth(*scene, gpu, result);
        for (const auto& variant : plan_.variants) result.cases.push_back(runVariant(*scene, gpu, variant, result));
        for (int round = 2; round <= plan_.timingRounds; ++round) retime(*scene, gpu, result, round);
        return result;
    }

private:
    // A-buffer at every camera of the path; its frames stay in memory as the reference of every method.
    void renderGroundTruth(const Scene& scene, const SceneGpu& gpu, SceneResult& result) {
        progress_.begin(label_ + ": ground truth (abuffer)");
        RenderJob job = baseJob(plan_, spec_, scene);
        job.method = "abuffer";
        job.methodOptions.abuffer.memoryCapBytes = plan_.abufferCapBytes;
        job.readEveryFrame = true;
        groundTruth_.clear();
        job.onFrame = [&](const FrameRecord& record) {
            groundTruth_.push_back(*record.image);
            progress_.step("frame " + std::to_string(record.index + 1) + "/" + std::to_string(plan_.frames));
        };
        try {
            RenderOutput out = renderScene(gpu, job);
            result.groundTruthStats = out.stats;
            result.maxFragments = out.stats.value("max_fragments", 0u);
            result.groundTruthImage = (imageDir_ / "ground_truth.png").string();
            saveImage(out.image, (outDir_ / result.groundTruthImage).string());
            result.groundTruthOk = true;
        } catch (const std::exception& e) {
            result.groundTruthError = e.what();
            progress_.skip(size_t(plan_.frames) - groundTruth_.size());
            groundTruth_.clear();
        }
    }

    // The scene's job with the variant's method and options (every run of a variant starts from it).
    RenderJob variantJob(const Scene& scene, const Variant& variant) const {
        RenderJob job = baseJob(plan_, spec_, scene);
        job.method = variant.method;
        job.methodOptions = variant.options;
        return job;
    }

    // Two runs of the path per variant (docs/DESIGN.md, "Benchmark"): the times come from a run with
    // nothing between its frames; the errors from a second run that reads every frame back and
    // measures it against the ground truth (CPU MSE and FLIP), whose frame times are kept only as
    // frame_ms_mean_with_comparison. That work between frames slowed the next frame by 10-60 % on
    // llvmpipe, and not every method alike.
    CaseResult runVariant(const Scene& scene, const SceneGpu& gpu, const Variant& variant, const SceneResult& sceneResult) {
        CaseResult c;
        c.variant = variant.name;
        c.method = variant.method;
        c.frames = nlohmann::json::array();
        progress_.begin(label_ + ": " + variant.name);
        const auto start = std::chrono::steady_clock::now();
        RenderJob job = variantJob(scene, variant);
        // The tile overlay is read after the timed frames; the compared run reads it when there is one.
        job.readTileOverlay = !sceneResult.groundTruthOk;
        size_t framesDone = 0;
        const auto step = [&](const FrameRecord& record) {
            ++framesDone;
            progress_.step("frame " + std::to_string(record.index + 1) + "/" + std::to_string(plan_.frames));
        };
        std::vector<nlohmann::json> timedFrames;
        job.onFrame = [&](const FrameRecord& record) {
            timedFrames.push_back(record.stats);
            step(record);
        };
        try {
            RenderOutput timed = renderScene(gpu, job);
            if (sceneResult.groundTruthOk) {
                job.referenceImages = &groundTruth_;
                job.readTileOverlay = true;
                job.onFrame = [&](const FrameRecord& record) {
                    nlohmann::json frame = record.stats;
                    // The timed run's figures for this frame, the compared run's errors.
                    const nlohmann::json& t = timedFrames.at(size_t(record.index));
                    for (const char* key : {"frame_ms", "frame_gpu_ms", "pass_ms", "pass_counters", "pass_blend", "gpu_estimate_ms"}) frame[key] = t.at(key);
                    c.frames.push_back(std::move(frame));
                    step(record);
                };
                RenderOutput out = renderScene(gpu, job);
                for (const char* key : {"error", "reference_method"}) {
                    if (out.stats.contains(key)) timed.stats[key] = out.stats[key];
                }
                timed.stats["frame_ms_mean_with_comparison"] = out.stats["frame_ms_mean"];
                timed.image = std::move(out.image);
                timed.tileOverlay = std::move(out.tileOverlay);
            } else {
                progress_.skip(size_t(plan_.frames));
                for (auto& frame : timedFrames) c.frames.push_back(std::move(frame));
            }
            c.stats = timed.stats;
            if (plan_.timingRounds > 1) {
                c.stats["frame_ms_rounds"] = nlohmann::json::array({c.frameMs()});
                c.stats["timing_round"] = 1;  // the round whose times the variant keeps
            }
            c.image = (imageDir_ / (fileSafe(variant.name) + ".png")).string();
            saveImage(timed.image, (outDir_ / c.image).string());
            if (timed.tileOverlay) {
                c.tileOverlay = (imageDir_ / (fileSafe(variant.name) + "_tiles.png")).string();
                saveImage(*timed.tileOverlay, (outDir_ / c.tileOverlay).string());
            }
            c.ok = true;
            if (sceneResult.groundTruthOk) {
                c.quality = measureQuality(c, sceneResult, variant);
            } else {
                c.qualityMissingReason = "ground truth failed: " + sceneResult.groundTruthError;
            }
        } catch (const std::exception& e) {
            c.ok = false;
            c.error = e.what();
            progress_.skip(2 * size_t(plan_.frames) - framesDone);
        }
        c.wallSeconds = secondsSince(start);
        return c;
    }

    // A further timing round (Plan::timingRounds; docs/DESIGN.md, "Benchmark"): every variant that
    // rendered is timed again, in the opposite order to the round before, so that a slow stretch of
    // the machine falls on different variants in different rounds; a variant keeps the times of its
    // fastest round (the noise of a shared machine only adds time), the errors of its compared run.
    void retime(const Scene& scene, const SceneGpu& gpu, SceneResult& result, int round) {
        const size_t n = result.cases.size();
        for (size_t k = 0; k < n; ++k) {
            const size_t i = round % 2 == 0 ? n - 1 - k : k;
            CaseResult& c = result.cases[i];
            const Variant& variant = plan_.variants[i];
            progress_.begin(label_ + ": " + variant.name + " (timing round " + std::to_string(round) + ")");
            if (!c.ok) {
                progress_.skip(size_t(plan_.frames));
                continue;
            }
            RenderJob job = variantJob(scene, variant);
            std::vector<nlohmann::json> timedFrames;
            job.onFrame = [&](const FrameRecord& record) {
                timedFrames.push_back(record.stats);
                progress_.step("frame " + std::to_string(record.index + 1) + "/" + std::to_string(plan_.frames));
            };
            try {
                RenderOutput timed = renderScene(gpu, job);
                CaseResult again;
                again.stats = timed.stats;
                const double ms = again.frameMs();
                nlohmann::json rounds = c.stats.at("frame_ms_rounds");
                rounds.push_back(ms);
                if (ms < c.frameMs() && timedFrames.size() == c.frames.size()) {
                    for (const char* key : {"error", "reference_method", "frame_ms_mean_with_comparison"}) {
                        if (c.stats.contains(key)) again.stats[key] = c.stats[key];
                    }
                    again.stats["timing_round"] = round;
                    c.stats = std::move(again.stats);
                    for (size_t f = 0; f < timedFrames.size(); ++f) {
                        for (const char* key : {"frame_ms", "frame_gpu_ms", "pass_ms", "pass_counters", "pass_blend", "gpu_estimate_ms"}) {
                            if (timedFrames[f].contains(key)) c.frames[f][key] = timedFrames[f][key];
                        }
                    }
                }
                c.stats["frame_ms_rounds"] = std::move(rounds);
            } catch (const std::exception& e) {
                // The first round's figures stand; the failure is kept beside them.
                c.stats["timing_round_error"] = e.what();
                progress_.skip(size_t(plan_.frames) - std::min(timedFrames.size(), size_t(plan_.frames)));
            }
        }
    }

    // Means over every compared frame (all, or i mod qualityEvery < 3), plus the last frame measured
    // on the PNG files exactly as `starnt compare` reads them (and the FLIP map from the same pair).
    Quality measureQuality(CaseResult& c, const SceneResult& sceneResult, const Variant& variant) {
        Quality q;
        double mseSum = 0.0, flipSum = 0.0;
        size_t compared = 0;
        for (const auto& frame : c.frames) {
            if (!frame.contains("mse")) continue;
            mseSum += frame.at("mse").get<double>();
            flipSum += frame.at("flip").get<double>();
            ++compared;
        }
        if (compared == 0) throw Error("internal: no frame of " + variant.name + " was compared with the ground truth");
        q.mse = mseSum / double(compared);
        q.flip = flipSum / double(compared);
        q.byFrameKind = c.stats.value("error", nlohmann::json(nullptr));
        const Image reference = loadImage((outDir_ / sceneResult.groundTruthImage).string());
        const Image test = loadImage((outDir_ / c.image).string());
        q.pngMse = mseSrgb(reference, test);
        FlipResult flipResult = flip(reference, test);
        q.pngFlip = flipResult.mean;
        c.flipMap = (imageDir_ / (fileSafe(variant.name) + "_flip.png")).string();
        saveImage(flipHeatmap(flipResult.errorMap), (outDir_ / c.flipMap).string());
        return q;
    }

    const Plan& plan_;
    const SceneSpec& spec_;
    const fs::path outDir_;
    Progress& progress_;
    const std::string label_;
    const fs::path imageDir_;  // relative to outDir_
    std::vector<Image> groundTruth_;
};

}  // namespace

// The ground truth once, every variant twice (timed, then compared), then once a further timing round.
size_t totalFrames(const Plan& plan) {
    return plan.scenes.size() * size_t(plan.frames) * (1 + size_t(1 + plan.timingRounds) * plan.variants.size());
}

Results runBench(const Plan& plan, const std::string& outDir, std::FILE* progressOut) {
    const auto start = std::chrono::steady_clock::now();
    Results results;
    results.plan = plan;
    results.date = isoUtcNow();
    HeadlessGlContext context(plan.api);
    results.machine = collectMachineInfo(context.info());
    fs::create_directories(outDir);
    Progress progress(progressOut, totalFrames(plan));
    for (size_t i = 0; i < plan.scenes.size(); ++i) {
        const std::string label = plan.scenes[i].name + " (" + std::to_string(i + 1) + "/" + std::to_string(plan.scenes.size()) + ")";
        results.scenes.push_back(SceneBench(plan, plan.scenes[i], outDir, progress, label).run());
    }
    progress.finish();
    computeDerivedFigures(results);
    results.wallSeconds = secondsSince(start);
    return results;
}

}  // namespace starnt::bench
