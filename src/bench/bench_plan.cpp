#include "bench/bench_plan.hpp"
#include "render/option_text.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt::bench {
namespace {

namespace fs = std::filesystem;

Variant makeVariant(std::string name, std::string method, std::string description,
                    void (*configure)(MethodOptions&) = nullptr) {
    Variant v{std::move(name), std::move(method), {}, std::move(description)};
    if (configure) configure(v.options);
    return v;
}

// `v`, whose saving is measured against `off` (the same method with `acceleration` off).
Variant accelerated(Variant v, std::string off, std::string acceleration) {
    v.accelerationOff = std::move(off);
    v.acceleration = std::move(acceleration);
    return v;
}

std::string joined(const std::vector<std::string>& names) {
    std::string text;
    for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
    return text;
}

// Alpha used for suite files whose materials are opaque; 0.3 gives visible depth layering without
// washing out (the value the README suggests for render).
constexpr float kOpaqueFileAlpha = 0.3f;

}  // namespace

const std::vector<Variant>& allVariants() {
    static const std::vector<Variant> variants = {
        makeVariant("unsorted", "unsorted", "\"over\" in submission order (the paper's E_random, used by Q)"),
        makeVariant("wboit", "wboit", "weighted blended OIT, McGuire & Bavoil eq. 10 weight"),
        makeVariant("mboit", "mboit", "moment-based OIT, 6 power moments (Muenstermann et al. 2018)",
                    [](MethodOptions& o) { o.mboit.moments = std::string("6"); }),
        makeVariant("mboit-t3", "mboit", "moment-based OIT, 3 trigonometric moments",
                    [](MethodOptions& o) { o.mboit.moments = std::string("t3"); }),
        makeVariant("dfaoit", "dfaoit", "DFAOIT: 12-input network, every pass at full resolution"),
        makeVariant("starnt-full", "starnt", "STAR-NT network, spatial off (all passes at full resolution)",
                    [](MethodOptions& o) { o.neural.spatial = false; }),
        accelerated(makeVariant("starnt", "starnt", "STAR-NT, adaptive tiles on (\"w/o temporal\")",
                                [](MethodOptions& o) { o.neural.spatial = true; }),
                    "starnt-full", "tiles"),
        makeVariant("hybrid", "hybrid", "STAR-NT's passes and tiles, tail in closed form (no network): what the network adds",
                    [](MethodOptions& o) { o.neural.spatial = false; }),
        makeVariant("hybrid-moments", "hybrid-moments",
                    "hybrid with the tail colour weighted by the tail's depth moments (no network; full resolution)"),
        makeVariant("starnt-d", "starnt-d",
                    "STAR-NT's passes with the tail depth moments, a network correcting hybrid-moments' tail (full resolution)"),
        makeVariant("starnt-residual-full", "starnt-residual",
                    "STAR-NT's passes and network size, the network correcting hybrid's closed-form tail; spatial off",
                    [](MethodOptions& o) { o.neural.spatial = false; }),
        accelerated(makeVariant("starnt-residual", "starnt-residual", "starnt-residual with adaptive tiles on",
                                [](MethodOptions& o) { o.neural.spatial = true; }),
                    "starnt-residual-full", "tiles"),
        accelerated(makeVariant("recommended", "recommended",
                                "the recommended configuration, chosen per context: kbuffer-moments where the context has "
                                "framebuffer fetch, else starnt-d with every frame real"),
                    "starnt-d", "the choice per context"),
        // The lead issue's K = 2 against K = 1, for the recommended configuration itself.
        accelerated(makeVariant("recommended-k2", "recommended",
                                "the recommended configuration at K = 2: one real frame, then one corrected interpolated frame",
                                [](MethodOptions& o) { o.neural.temporalInterval = 2; }),
                    "starnt-d", "K = 2 corrected"),
        makeVariant("kbuffer-moments", "kbuffer-moments",
                    "one geometry pass a frame: the nearest three fragments exact by framebuffer fetch, the ordered closed form "
                    "of the depth moments behind them (no network; needs GL_EXT_shader_framebuffer_fetch)"),
        makeVariant("kbuffer-moments-fp32", "kbuffer-moments",
                    "kbuffer-moments with its sums and moments in 32-bit floats (the 16-bit layout's reference)",
                    [](MethodOptions& o) { o.neural.targets = NeuralOptions::Targets::Float32; }),
        // What recommended renders where the context has no framebuffer fetch for kbuffer-moments
        // but the interpolated frames are asked for anyway: starnt-d with K = 8 corrected frames.
        accelerated(makeVariant("starnt-d-k8", "starnt-d",
                                "starnt-d with temporal K = " + std::to_string(kRecommendedTemporalInterval) + " corrected frames",
                                [](MethodOptions& o) { o.neural.temporalInterval = kRecommendedTemporalInterval; }),
                    "starnt-d", "K = " + std::to_string(kRecommendedTemporalInterval) + " corrected"),
        accelerated(makeVariant("starnt-vrs", "starnt",
                                "STAR-NT, tiles on with per-tile pass-3 shading rates through the driver's shading-rate image "
                                "where it has one (GPU; elsewhere the same as starnt)",
                                [](MethodOptions& o) {
                                    o.neural.spatial = true;
                                    o.neural.shadingRateImage = NeuralOptions::ShadingRateImage::Auto;
                                }),
                    "starnt", "per-tile shading rates"),
        makeVariant("starnt-paper", "starnt",
                    "STAR-NT as the paper: tiles on the composite, continuous scales, no guard",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.tileSignal = NeuralOptions::TileSignal::Composite;
                        o.neural.scaleRule = NeuralOptions::ScaleRule::Continuous;
                        o.neural.scaleGuard = false;
                    }),
        accelerated(makeVariant("starnt-total", "starnt",
                    "STAR-NT, tiles on + temporal K = 2, corrected frames (\"Total STAR\"; fresh nearest layer and sums in one geometry pass, the network's correction kept)",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.temporalInterval = 2;
                        o.neural.temporalMode = NeuralOptions::TemporalMode::Correct;
                    }), "starnt", "K = 2 corrected"),
        accelerated(makeVariant("starnt-total-refresh", "starnt", "STAR-NT, tiles on + temporal K = 2, refresh frames (fresh pass 1 over the reprojected back)",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.temporalInterval = 2;
                        o.neural.temporalMode = NeuralOptions::TemporalMode::Refresh;
                    }), "starnt", "K = 2 refresh"),
        accelerated(makeVariant("starnt-total-warp", "starnt", "STAR-NT, tiles on + temporal K = 2, warped frames (the paper's)",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.temporalInterval = 2;
                        o.neural.temporalMode = NeuralOptions::TemporalMode::Warp;
                    }), "starnt", "K = 2 warp"),
        makeVariant("starnt-corners", "starnt", "STAR-NT, tiles on, inference at leaf corners only",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.inference = NeuralOptions::Inference::Corners;
                    }),
        makeVariant("starnt-fp32", "starnt", "STAR-NT, tiles on, every pass target 32-bit float (the earlier 32-bit layout)",
                    [](MethodOptions& o) {
                        o.neural.spatial = true;
                        o.neural.targets = NeuralOptions::Targets::Float32;
                    }),
        makeVariant("dfaoit-fp32", "dfaoit", "DFAOIT with every pass target 32-bit float (the earlier 32-bit layout)",
                    [](MethodOptions& o) { o.neural.targets = NeuralOptions::Targets::Float32; }),
        makeVariant("abuffer", "abuffer", "A-buffer (exact; the ground truth method)"),
        makeVariant("peel", "peel", "depth peeling until empty (exact)"),
    };
    return variants;
}

std::vector<std::string> defaultVariantNames() {
    return {"unsorted", "wboit", "mboit", "mboit-t3", "dfaoit", "starnt-full", "hybrid", "hybrid-moments", "starnt-d", "recommended", "kbuffer-moments", "starnt-residual-full", "starnt",
            "starnt-paper", "starnt-total", "starnt-total-refresh",
            "starnt-total-warp", "starnt-corners"};
}

const Variant& findVariant(const std::string& name) {
    for (const auto& v : allVariants()) {
        if (v.name == name) return v;
    }
    std::vector<std::string> names;
    for (const auto& v : allVariants()) names.push_back(v.name);
    throw Error("--methods: unknown method '" + name + "' (valid: " + joined(names) + ")");
}

const std::vector<SceneSpec>& suiteScenes() {
    static const std::vector<SceneSpec> scenes = {
        {"engine", "engine/2CylinderEngine.glb", kOpaqueFileAlpha, 0.03f, 24, "opaque materials: alpha 0.3"},
        {"chess", "chess/chess_classic_board.glb", std::nullopt, 0.03f, 12, ""},
        {"clothes", "clothes/Corset_geom.glb", kOpaqueFileAlpha, 0.03f, 13, "alpha 1 materials: alpha 0.3"},
        {"clothes2", "clothes/SheenCloth_geom.glb", kOpaqueFileAlpha, 0.03f, 13, "alpha 1 materials: alpha 0.3"},
        {"candycat", "candycat/spot.obj", kOpaqueFileAlpha, 0.03f, 12, "OBJ without material alpha: alpha 0.3"},
        {"fox", "candycat/Fox.glb", kOpaqueFileAlpha, 0.03f, 12, "opaque material: alpha 0.3"},
        {"tree", "tree/tree_grove.glb", std::nullopt, 0.03f, 58, ""},
        {"powerplant", "powerplant/Buggy_flat.glb", kOpaqueFileAlpha, 0.03f, 98, "alpha 1 materials: alpha 0.3"},
        {"gearbox", "powerplant/GearboxAssy_flat.glb", kOpaqueFileAlpha, 0.03f, 98, "alpha 1 materials: alpha 0.3"},
        {"hair", "hair/hair_procedural.glb", std::nullopt, 0.03f, 80, ""},
        {"hairball", "hairball/hairball_procedural.glb", std::nullopt, 0.03f, 136, ""},
        // Material alpha 0.15 x COLOR_0 alpha 0.08..0.2 = 0.012..0.03: all below the default cut-off 0.03
        // cut-off, so the scene would render empty. Keeping its own (varying) alphas and lowering
        // the cut-off preserves what the scene is about: many faint layers.
        {"smoke", "smoke/smoke_procedural.glb", std::nullopt, 0.002f, 56, "alphas 0.012..0.03: cut-off 0.002"},
        {"magic_stars", "magic_stars/magic_stars_procedural.glb", std::nullopt, 0.03f, 15, ""},
    };
    return scenes;
}

std::vector<SceneSpec> builtinScenes() {
    std::vector<SceneSpec> scenes;
    for (const auto& name : builtinSceneNames()) scenes.push_back({"builtin-" + name, "builtin:" + name, std::nullopt, 0.03f, 0, ""});
    return scenes;
}

const Preset& findPreset(const std::string& name) {
    // Both presets move the camera by 2 degrees per frame (smooth motion, as temporal reprojection
    // assumes). quick: low / medium / high depth complexity (D 15, 18, 68 in scenes/README.md).
    static const std::vector<Preset> presets = {
        {"quick", 640, 360, 8, "orbit:0,14,15", {"magic_stars", "chess", "tree"}, {"builtin:panes", "builtin:smoke", "builtin:tubes"}},
        {"paper", 1920, 1080, 16, "orbit:0,30,15", {}, {"builtin:panes", "builtin:smoke", "builtin:tubes", "builtin:random"}},
        // The paper's protocol on a GPU (docs/DESIGN.md, "Benchmark"): 1080p, 8 warm-up and 64 timed
        // frames for stable means, every variant of the headline, the error on frames 0-2 and 32-34
        // (FLIP runs on the CPU); measured on an H100 host: 49-135 s a scene, about 7.5 minutes for the six.
        {"gpu", 1920, 1080, 64, "orbit:0,126,15", {"magic_stars", "chess", "tree", "hair", "hairball", "engine"},
         {"builtin:panes", "builtin:smoke", "builtin:tubes"}, 8, 32,
         {"wboit", "mboit", "mboit-t3", "dfaoit", "starnt-full", "starnt", "hybrid", "hybrid-moments", "starnt-d",
          "starnt-total", "starnt-total-refresh", "starnt-total-warp", "recommended", "starnt-vrs"}},
    };
    for (const auto& p : presets) {
        if (p.name == name) return p;
    }
    throw Error("--preset: unknown preset '" + name + "' (valid: quick, paper, gpu)");
}

SurfaceOptions surfaceOptionsFor(const SceneSpec& scene) {
    SurfaceOptions surface;
    surface.alphaOverride = scene.alphaOverride;
    return surface;
}

namespace {

std::optional<SceneSpec> findSuiteScene(const std::string& name) {
    for (const auto& s : suiteScenes()) {
        if (s.name == name) return s;
    }
    return std::nullopt;
}

// One --scenes entry: a suite name (needs the suite folder), builtin:NAME, or a scene file.
SceneSpec resolveScene(const std::string& entry, const std::string& suiteDir) {
    if (entry.rfind("builtin:", 0) == 0) {
        const std::string name = entry.substr(8);
        const auto names = builtinSceneNames();
        if (std::find(names.begin(), names.end(), name) == names.end()) {
            throw Error("--scenes: unknown built-in scene '" + entry + "' (valid: builtin:" + joined(names) + ")");
        }
        return {"builtin-" + name, entry, std::nullopt, 0.03f, 0, ""};
    }
    if (auto suite = findSuiteScene(entry)) {
        if (suiteDir.empty()) throw Error("--scenes: '" + entry + "' is a suite scene but the suite folder was not found (see --suite-dir)");
        suite->source = (fs::path(suiteDir) / suite->source).string();
        return *suite;
    }
    std::error_code ec;
    if (fs::is_regular_file(entry, ec)) {
        return {fs::path(entry).stem().string(), fs::absolute(entry).string(), std::nullopt, 0.03f, 0, "scene file given on the command line"};
    }
    std::vector<std::string> names;
    for (const auto& s : suiteScenes()) names.push_back(s.name);
    throw Error("--scenes: '" + entry + "' is neither a suite scene (" + joined(names) + "), builtin:NAME nor an existing file");
}

}  // namespace

Plan makePlan(const Request& request) {
    const Preset& preset = findPreset(request.preset);
    Plan plan;
    plan.preset = preset.name;
    plan.width = request.width ? request.width : preset.width;
    plan.height = request.height ? request.height : preset.height;
    plan.frames = request.frames ? request.frames : preset.frames;
    plan.cameraPath = request.cameraPath.empty() ? preset.cameraPath : request.cameraPath;
    plan.warmupFrames = preset.warmupFrames;
    plan.qualityEvery = preset.qualityEvery;
    checkImageSize(plan.width, plan.height);
    if (plan.frames < 1 || plan.frames > 10000) throw Error("--frames must be in 1..10000");
    if (request.timingRounds < 1 || request.timingRounds > kMaxTimingRounds) {
        throw Error("--timing-rounds must be in 1.." + std::to_string(kMaxTimingRounds) + ", got " + std::to_string(request.timingRounds));
    }
    plan.timingRounds = request.timingRounds;
    // 0 = the default cap; anything else is checked and converted without wrapping (1e30 MiB).
    plan.api = parseGlApi(request.api);
    plan.abufferCapBytes = request.abufferCapMib == 0.0 ? AbufferOptions{}.memoryCapBytes
                                                        : abufferCapBytes(request.abufferCapMib, "--abuffer-cap-mib");

    std::error_code ec;
    const bool haveSuite = !request.suiteDir.empty() && fs::is_directory(request.suiteDir, ec);
    if (haveSuite) {
        plan.suiteDir = fs::absolute(request.suiteDir).lexically_normal().string();
        plan.suiteNote = "suite scenes from " + plan.suiteDir;
    } else {
        plan.suiteNote = "suite folder " + (request.suiteDir.empty() ? std::string("(none given)") : request.suiteDir) +
                         " not found: built-in procedural scenes stand in for the suite";
    }

    std::vector<std::string> sceneNames = request.scenes;
    if (sceneNames.empty()) {
        if (!haveSuite) {
            sceneNames = preset.builtinNames;
        } else if (preset.suiteNames.empty()) {
            for (const auto& s : suiteScenes()) sceneNames.push_back(s.name);
        } else {
            sceneNames = preset.suiteNames;
        }
    }
    for (const auto& entry : sceneNames) {
        SceneSpec spec = resolveScene(entry, plan.suiteDir);
        for (const auto& other : plan.scenes) {
            if (other.name == spec.name) throw Error("--scenes: '" + entry + "' is listed twice");
        }
        plan.scenes.push_back(std::move(spec));
    }

    const std::vector<std::string> methodNames =
        !request.methods.empty() ? request.methods : !preset.variantNames.empty() ? preset.variantNames : defaultVariantNames();
    for (const auto& name : methodNames) {
        Variant v = findVariant(name);
        for (const auto& other : plan.variants) {
            if (other.name == name) throw Error("--methods: '" + name + "' is listed twice");
        }
        if (v.method == "abuffer") v.options.abuffer.memoryCapBytes = plan.abufferCapBytes;
        plan.variants.push_back(std::move(v));
    }
    // Fail on a malformed camera path now rather than once per scene.
    parseCameraPathSpec(plan.cameraPath, Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)}, float(plan.width) / float(plan.height));
    return plan;
}

}  // namespace starnt::bench
