// What `starnt bench` runs: the method variants, the scenes with their per-scene settings, and the
// presets. Everything here is plain data and name resolution; bench_runner.hpp does the rendering.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/scene_gpu.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/oit_method.hpp"

namespace starnt::bench {

// One column of the paper's tables: a base method with fixed acceleration options.
struct Variant {
    std::string name;    // what --methods takes, e.g. "starnt-total"
    std::string method;  // createMethod name, e.g. "starnt"
    MethodOptions options;
    std::string description;  // one line for report.md
    // The same method with its acceleration off (tiles off for spatial, K = 1 for temporal): the
    // variant its saving is measured against, in the same run (report.md, "Against itself").
    std::string accelerationOff = {};
    std::string acceleration = {};  // what differs from that variant, e.g. "tiles", "K = 2 corrected"
};

// Every variant `--methods` accepts, in report order. The first nine are the default set; abuffer
// and peel (exact methods) are accepted on request, for their timings.
const std::vector<Variant>& allVariants();
std::vector<std::string> defaultVariantNames();
// Throws starnt::Error for an unknown name, listing the valid ones.
const Variant& findVariant(const std::string& name);

// A scene of the benchmark with the settings it is rendered with.
struct SceneSpec {
    std::string name;    // short name used in tables and file names, e.g. "tree" or "builtin-tubes"
    std::string source;  // loadScene argument: a path or "builtin:NAME"
    std::optional<float> alphaOverride;  // for files whose materials are opaque (alpha 1)
    float alphaCutoff = 0.03f;           // the default; lowered only where a scene's alphas are below it
    int paperDepth = 0;                  // D of the paper scene it stands in for (0: none)
    std::string note;                    // why the settings differ from the defaults
};

// The suite scenes of ../shared/scenes (scenes/README.md) with their settings; `source` is relative
// to the suite folder.
const std::vector<SceneSpec>& suiteScenes();
// The built-in procedural scenes as bench scenes (used when the suite folder is absent).
std::vector<SceneSpec> builtinScenes();

struct Preset {
    std::string name;
    int width = 0, height = 0, frames = 0;
    std::string cameraPath;                 // parseCameraPathSpec form
    std::vector<std::string> suiteNames;    // empty: every suite scene
    std::vector<std::string> builtinNames;  // used instead when the suite folder is absent
    int warmupFrames = 4;                    // kWarmupFrames
    int qualityEvery = 1;                    // RenderJob::qualityEvery
    std::vector<std::string> variantNames;   // the default --methods (empty: defaultVariantNames())
};
// "quick", "paper" or "gpu"; throws starnt::Error otherwise.
const Preset& findPreset(const std::string& name);

// What the user asked for; empty / zero fields take the preset's values.
struct Request {
    std::string preset = "quick";
    std::vector<std::string> scenes;   // suite names, builtin:NAME or scene file paths
    std::vector<std::string> methods;  // variant names
    std::string suiteDir;              // empty or missing folder: built-in scenes
    int width = 0, height = 0, frames = 0;
    std::string cameraPath;
    double abufferCapMib = 0.0;  // 0: MethodOptions default
    std::string api = "gl";      // gl | gles: the context the whole run renders in
    int timingRounds = 1;        // --timing-rounds: Plan::timingRounds
};

// The resolved run: concrete scenes (sources made absolute), variants and sizes.
// Frames rendered before the timed ones, neither timed nor scored: shader compiles, and the
// tiles, which change one level a frame, settle (docs/DESIGN.md, "Scale guard": at least 4).
constexpr int kWarmupFrames = 4;

struct Plan {
    std::string preset;
    int width = 0, height = 0, frames = 0;
    int warmupFrames = kWarmupFrames;
    int qualityEvery = 1;  // RenderJob::qualityEvery
    std::string cameraPath;
    std::vector<SceneSpec> scenes;
    std::vector<Variant> variants;
    std::string suiteDir;  // the folder used, empty when built-ins replaced the suite
    std::string suiteNote;  // one line on where the scenes came from
    size_t abufferCapBytes = 0;
    GlApi api = GlApi::Desktop;
    // Timed runs of the path per variant, 1..kMaxTimingRounds (docs/DESIGN.md, "Benchmark"): after
    // every variant's first, each further round times them all again, in the opposite order to the
    // round before, and a variant keeps its fastest round's times.
    int timingRounds = 1;
};
constexpr int kMaxTimingRounds = 10;

// Resolves names and checks every value before anything renders; throws starnt::Error with the
// offending name or value.
Plan makePlan(const Request& request);

// The surface options a scene is drawn with (its alpha override).
SurfaceOptions surfaceOptionsFor(const SceneSpec& scene);

}  // namespace starnt::bench
