#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "app/commands.hpp"
#include "app/render_progress.hpp"
#include "methods/mboit/mboit_settings.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "render/option_text.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/nn.hpp"

namespace starnt::app {
namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// Fails before any rendering when an output could not be written: wrong extension or missing folder.
void checkOutputPath(const std::string& path, const std::string& wantedExt, const char* flag) {
    if (path.empty()) return;
    if (lowerExtension(path) != wantedExt) {
        throw Error(std::string(flag) + " " + path + ": expected a " + wantedExt + " file");
    }
    std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) {
        throw Error(std::string(flag) + " " + path + ": folder " + dir.string() + " does not exist");
    }
    if (std::filesystem::is_directory(path, ec)) throw Error(std::string(flag) + " " + path + ": is a directory");
}

// Output names follow printf, so that a name can still hold a literal '%': "%d" or "%0Nd" (N 1..9)
// is the frame number, "%%" a '%'. Returns how many frame numbers the name holds, or -1 when a '%'
// starts neither.
int frameConversions(const std::string& path) {
    int count = 0;
    for (size_t i = 0; i < path.size(); ++i) {
        if (path[i] != '%') continue;
        size_t next = i + 1;
        if (next < path.size() && path[next] == '%') {
            i = next;
            continue;
        }
        if (next + 1 < path.size() && path[next] == '0' && path[next + 1] >= '1' && path[next + 1] <= '9') next += 2;
        if (next >= path.size() || path[next] != 'd') return -1;
        ++count;
        i = next;
    }
    return count;
}

bool isFramePattern(const std::string& path) { return frameConversions(path) > 0; }

// A name with one frame number is a pattern (--out and --exr only); every other '%' must be "%%".
void checkOutputName(const std::string& path, const char* flag, bool framesAllowed) {
    const int conversions = frameConversions(path);
    if (conversions < 0 || conversions > 1 || (conversions == 1 && !framesAllowed)) {
        std::string why = framesAllowed
                              ? ": a frame pattern needs exactly one %d or %0Nd (e.g. frame_%04d.png); write %% for a literal '%'"
                              : ": one file for the whole run (its last frame, or one line a frame); frame patterns are for "
                                "--out and --exr; write %% for a literal '%'";
        throw Error(std::string(flag) + " " + path + why);
    }
}

std::string framePath(const std::string& pattern, int frame) {
    char buf[4096];
    std::snprintf(buf, sizeof buf, pattern.c_str(), frame);
    return buf;
}

// The file a name without a frame number writes ("%%" -> '%'); for a pattern, its frame 0.
std::string fileName(const std::string& path) {
    if (isFramePattern(path)) return framePath(path, 0);
    std::string file;
    for (size_t i = 0; i < path.size(); ++i) {
        file += path[i];
        if (path[i] == '%' && i + 1 < path.size() && path[i + 1] == '%') ++i;
    }
    return file;
}

struct RenderArgs {
    std::string scene = "builtin:tubes", method = "abuffer", camera, cameraPath, background = "1,1,1", out, exr, stats;
    std::string frameStats, tilesImage, referenceMethod;
    AccelerationFlags acceleration;
    int width = 1920, height = 1080, frames = 1, warmup = 0, peelLayers = 0;
    double alpha = -1.0, alphaCutoff = 0.03, abufferCapMib = 2048;
    bool unlit = false;
    std::string wboitWeight = "eq10", weights;
    std::string mboitMoments = "6";
    std::string api = "gl";
    // --alpha, --temporal-mode, --temporal on the command line
    bool alphaGiven = false, temporalModeGiven = false, temporalGiven = false;
    std::vector<std::string> accelerationGiven;          // the acceleration flags on the command line
    std::vector<std::string> perMethodGiven;             // --peel-layers, --wboit-weight, ... on the command line
    std::string alphaText;                               // --alpha as typed
};

// What --method and the acceleration and per-method flags make of MethodOptions.
MethodOptions methodOptions(const RenderArgs& a) {
    MethodOptions options;
    applyAccelerationFlags(a.acceleration, options);
    options.peel.layers = a.peelLayers;
    options.wboit.weight = a.wboitWeight;
    options.mboit.moments = a.mboitMoments;
    options.neural.weightsPath = a.weights;
    options.abuffer.memoryCapBytes = abufferCapBytes(a.abufferCapMib, "--abuffer-cap-mib");
    return options;
}

void runRender(const RenderArgs& a);

void declareRenderOptions(CLI::App& app, const std::shared_ptr<RenderArgs>& args) {
    RenderArgs& a = *args;
    CLI::App* cmd = app.add_subcommand("render", "render a scene with one OIT method");
    cmd->add_option("--scene", a.scene, "scene file (.gltf/.glb/.obj) or builtin:NAME")->capture_default_str();
    cmd->add_option("--method", a.method, methodNameList())->capture_default_str();
    cmd->add_option("--width", a.width, "image width")->capture_default_str();
    cmd->add_option("--height", a.height, "image height")->capture_default_str();
    cmd->add_option("--camera", a.camera, "orbit:DEG[,ELEV] or a camera .json (default: auto-framed)");
    cmd->add_option("--alpha", a.alpha, "override every material's alpha (0..1)");
    cmd->add_option("--alpha-cutoff", a.alphaCutoff, "discard fragments with alpha below this")->capture_default_str();
    cmd->add_option("--background", a.background, "background colour R,G,B (linear, 0..1)")->capture_default_str();
    cmd->add_flag("--unlit", a.unlit, "output base colour unshaded for every material");
    cmd->add_option("--frames", a.frames, "frames to render; timings are medians without the first")->capture_default_str();
    cmd->add_option("--warmup", a.warmup,
                    "untimed frames at the first camera before the timed ones (shader compiles, tiles settle; with "
                    "interpolated frames, on to the end of a group, so the first timed frame is real); with it, "
                    "the first frame is timed too")
        ->capture_default_str();
    cmd->add_option("--peel-layers", a.peelLayers, "peel: layers (0 = until a layer comes back empty: exact, but coplanar surfaces peel together)")->capture_default_str();
    cmd->add_option("--wboit-weight", a.wboitWeight, "wboit: eq7|eq8|eq9|eq10")->capture_default_str();
    cmd->add_option("--mboit-moments", a.mboitMoments, "mboit: 4|6 power moments, t2|t3 trigonometric moments")
        ->capture_default_str();
    cmd->add_option("--abuffer-cap-mib", a.abufferCapMib, "abuffer: memory cap in MiB")->capture_default_str();
    cmd->add_option("--api", a.api, "gl (OpenGL 4.5 core) or gles (OpenGL ES 3.2, the mobile path)")->capture_default_str();
    cmd->add_option("--camera-path", a.cameraPath, "sequence camera: orbit:START,END[,ELEV] or a keyframe .json");
    addAccelerationOptions(cmd, a.acceleration);
    cmd->add_option("--tiles-image", a.tilesImage, "write the tile levels over the last frame (.png)");
    cmd->add_option("--frame-stats", a.frameStats, "write one JSON line per frame (.jsonl)");
    cmd->add_option("--reference-method", a.referenceMethod,
                    "also render this method (e.g. abuffer) per frame and record MSE/FLIP against it");
    cmd->add_option("--weights", a.weights, "starnt, starnt-residual, starnt-d, dfaoit: weights file (default: the shipped weights)");
    cmd->add_option("--out", a.out, "output image (.png, sRGB); frame_%04d.png writes every frame, %% is a literal %")->required();
    cmd->add_option("--exr", a.exr, "also write linear float EXR");
    cmd->add_option("--stats", a.stats, "write statistics JSON");
    cmd->callback([args, cmd] {
        args->alphaGiven = cmd->get_option("--alpha")->count() > 0;
        if (args->alphaGiven) args->alphaText = cmd->get_option("--alpha")->as<std::string>();
        args->temporalModeGiven = cmd->get_option("--temporal-mode")->count() > 0;
        args->temporalGiven = cmd->get_option("--temporal")->count() > 0;
        args->accelerationGiven = givenAccelerationFlags(cmd);
        args->perMethodGiven.clear();
        for (const char* name : {"--peel-layers", "--wboit-weight", "--mboit-moments", "--abuffer-cap-mib"})
            if (cmd->get_option(name)->count() > 0) args->perMethodGiven.emplace_back(name);
        runRender(*args);
    });
}

// A flag the rendered method (or the reference method) would ignore is an error naming it: silently
// ignored, it would label an image with a setting it did not have.
void checkFlagsApply(const RenderArgs& a) {
    const auto names = methodNames();
    if (std::find(names.begin(), names.end(), a.method) == names.end()) return;  // createMethod names the valid ones
    if (!a.accelerationGiven.empty() && !neuralConfig(a.method)) {
        std::string neural;
        for (const std::string& name : methodNames())
            if (neuralConfig(name)) neural += (neural.empty() ? "" : ", ") + name;
        throw Error(a.accelerationGiven.front() + ": method " + a.method +
                    " has no neural passes to accelerate (the acceleration flags apply to " + neural + ")");
    }
    const MethodOptions options = methodOptions(a);
    const bool interpolates = options.neural.temporalInterval > 1 || options.neural.temporalAuto || a.method == "recommended";
    const bool tiles = methodUsesTiles(a.method, options);
    // The scale rule and the guard choose the adaptive scales: spatial on, no fixed --scales.
    const NeuralMethodConfig* config = neuralConfig(a.method);
    const bool adaptiveScales = config && options.neural.spatial.value_or(config->spatialByDefault) && options.neural.fixedScale2 == 0.0f;
    for (const std::string& flag : a.accelerationGiven) {
        const bool temporalOnly = flag == "--temporal-mode" || flag == "--corrected-passes" || flag == "--corrected-layers";
        if (temporalOnly && !interpolates) {
            throw Error(flag + ": method " + a.method + " renders every frame real here; it applies to interpolated frames (--temporal 2..8 or auto)");
        }
        if (flag == "--target-fps" && !options.neural.temporalAuto) throw Error("--target-fps: applies to --temporal auto only");
        if (flag == "--tile-signal" && !tiles) {
            throw Error(flag + ": method " + a.method + " runs no adaptive tiles with these options (use starnt, or --spatial on)");
        }
        if ((flag == "--scale-rule" || flag == "--scale-guard") && !adaptiveScales) {
            throw Error(flag + ": method " + a.method +
                        " chooses no adaptive scales with these options (it needs the tiles, --spatial on, and no fixed --scales)");
        }
    }
    for (const std::string& flag : a.perMethodGiven) {
        const std::string owner = flag == "--peel-layers" ? "peel" : flag == "--wboit-weight" ? "wboit" : flag == "--mboit-moments" ? "mboit" : "abuffer";
        if (a.method != owner && a.referenceMethod != owner) {
            throw Error(flag + ": applies to method " + owner + " (rendered or as --reference-method), not to " + a.method);
        }
    }
}

// Every value checked before any work: a bad one fails with one error naming it.
void checkRenderArgs(const RenderArgs& a) {
    checkImageSize(a.width, a.height);
    parseGlApi(a.api);
    if (a.frames < 1 || a.frames > 100000) throw Error("--frames must be in 1..100000");
    if (a.warmup < 0 || a.warmup > 1000) throw Error("--warmup must be in 0..1000");
    if (a.alphaGiven && !(a.alpha >= 0.0 && a.alpha <= 1.0)) {
        throw Error("--alpha " + a.alphaText + ": must be in [0, 1]");
    }
    if (!(a.alphaCutoff >= 0.0 && a.alphaCutoff <= 1.0)) throw Error("--alpha-cutoff must be in [0, 1]");
    mboit::parseMomentKind(a.mboitMoments);  // a bad value fails before any work
    abufferCapBytes(a.abufferCapMib, "--abuffer-cap-mib");  // a bad value fails before any work
    if (!a.weights.empty()) {
        const NeuralMethodConfig* config = neuralConfig(a.method);
        if (!config || !config->evaluatesNetwork) {
            throw Error("--weights " + a.weights + ": method " + a.method +
                        " has no network (only starnt, starnt-residual, starnt-d and dfaoit read a weights file)");
        }
        nn::loadWeights(a.weights, config->kind);  // a bad file fails before any rendering
    }
    const MethodOptions options = methodOptions(a);  // the acceleration flags' values
    if (!a.camera.empty() && !a.cameraPath.empty()) throw Error("--camera and --camera-path exclude each other");
    if (a.temporalGiven && a.method == "recommended" && options.neural.temporalInterval == 1 && !options.neural.temporalAuto) {
        // recommendedOptions turns "every frame real" into its own interval, which an engine's
        // default options ask for; on the command line it was asked for by name.
        throw Error("--temporal " + a.acceleration.temporal +
                    ": the recommended configuration chooses its frames per context (kbuffer-moments where framebuffer fetch "
                    "exists, else starnt-d); for starnt-d with every frame real use --method starnt-d");
    }
    if (a.temporalModeGiven && !methodHasNearestPass(a.method)) {
        throw Error("--temporal-mode: method " + a.method +
                    " has no interpolated frames to correct, refresh or warp (use starnt, hybrid or dfaoit)");
    }
    checkFlagsApply(a);
    checkOutputName(a.out, "--out", true);
    checkOutputName(a.exr, "--exr", true);
    checkOutputName(a.tilesImage, "--tiles-image", false);
    checkOutputName(a.frameStats, "--frame-stats", false);
    checkOutputName(a.stats, "--stats", false);
    checkOutputPath(fileName(a.out), ".png", "--out");
    checkOutputPath(fileName(a.tilesImage), ".png", "--tiles-image");
    if (!a.tilesImage.empty() && !methodUsesTiles(a.method, options)) {
        throw Error("--tiles-image: method " + a.method +
                    " runs no tiles with these options (use starnt, or dfaoit with --spatial on or --inference corners)");
    }
    checkOutputPath(fileName(a.frameStats), ".jsonl", "--frame-stats");
    if (!a.referenceMethod.empty()) {
        const auto names = methodNames();
        if (std::find(names.begin(), names.end(), a.referenceMethod) == names.end()) {
            throw Error("--reference-method '" + a.referenceMethod + "' is not a method (see `starnt methods`)");
        }
    }
    checkOutputPath(fileName(a.exr), ".exr", "--exr");
    checkOutputPath(fileName(a.stats), ".json", "--stats");
    parseColor(a.background, "--background");
    // Two outputs naming one file (also spelled differently, or one frame of a numbered sequence):
    // one would silently replace the other.
    const std::pair<const char*, const std::string*> outputs[] = {
        {"--out", &a.out}, {"--exr", &a.exr}, {"--tiles-image", &a.tilesImage}, {"--frame-stats", &a.frameStats}, {"--stats", &a.stats}};
    for (size_t i = 0; i < std::size(outputs); ++i) {
        for (size_t j = i + 1; j < std::size(outputs); ++j) {
            const std::string &x = *outputs[i].second, &y = *outputs[j].second;
            if (x.empty() || y.empty() || lowerExtension(x) != lowerExtension(y)) continue;  // (each flag has its own)
            const bool xFrames = isFramePattern(x), yFrames = isFramePattern(y);  // (--out and --exr only)
            bool same = sameFile(fileName(x), fileName(y));
            for (int f = 0; !same && (xFrames || yFrames) && f < a.frames; ++f) {
                same = sameFile(xFrames ? framePath(x, f) : fileName(x), yFrames ? framePath(y, f) : fileName(y));
            }
            if (same) throw Error(std::string(outputs[i].first) + " and " + outputs[j].first + " name the same file, " + y);
        }
    }
}

RenderJob makeRenderJob(const RenderArgs& a, const Scene& scene) {
    RenderJob job = sizedJob(a.width, a.height, a.frames, a.warmup, parseColor(a.background, "--background"), float(a.alphaCutoff));
    job.method = a.method;
    const float aspect = float(a.width) / float(a.height);
    job.camera = parseCameraSpec(a.camera, scene.bounds(), aspect);
    if (!a.cameraPath.empty()) job.path = parseCameraPathSpec(a.cameraPath, scene.bounds(), aspect);
    job.referenceMethod = a.referenceMethod;
    // The reference method takes the per-method options (an A-buffer's memory cap, peel layers,
    // ...), not the acceleration flags, which are the rendered method's.
    const MethodOptions options = methodOptions(a);
    job.referenceOptions.abuffer = options.abuffer;
    job.referenceOptions.peel = options.peel;
    job.referenceOptions.wboit = options.wboit;
    job.referenceOptions.mboit = options.mboit;
    job.readTileOverlay = !a.tilesImage.empty();
    if (a.alphaGiven) job.surface.alphaOverride = float(a.alpha);
    job.surface.forceUnlit = a.unlit;
    job.methodOptions = methodOptions(a);
    return job;
}

void runRender(const RenderArgs& a) {
    checkRenderArgs(a);
    const Scene scene = loadScene(a.scene);
    HeadlessGlContext context(parseGlApi(a.api));
    SceneGpu sceneGpu(scene);
    RenderJob job = makeRenderJob(a, scene);
    if (a.method == "recommended") {
        const std::string chosen = recommendedMethodInContext(job.methodOptions);
        const int interval = recommendedOptionsInContext(job.methodOptions).neural.temporalInterval;
        std::fprintf(stderr, "starnt: note: `recommended` renders %s in this OpenGL context: %s\n",
                     chosen == "kbuffer-moments" ? "kbuffer-moments" : interval == 1 ? "starnt-d, every frame real" : "starnt-d with interpolated frames",
                     chosen == "kbuffer-moments" ? "it has framebuffer fetch for the nearest three layers"
                     : interval > 1           ? "the temporal options asked for them"
                                              : "it lacks GL_EXT_shader_framebuffer_fetch, which kbuffer-moments needs "
                                                "(docs/DESIGN.md, \"The recommended configuration without framebuffer fetch\")");
    }
    // (for the warning when no transparent fragment is seen: a scene with none to draw)
    const bool opaqueOnly = sceneGpu.hasOpaque(job.surface) && !sceneGpu.hasTransparent(job.surface);
    const bool numbered = isFramePattern(a.out);
    std::string frameLines;
    const bool numberedExr = isFramePattern(a.exr);
    if (numbered || numberedExr) job.readEveryFrame = true;
    // Every output is staged under a temporary name and renamed only when all are written, so a
    // failure (a later frame, the stats file) leaves none of them.
    OutputFiles outputs;
    RenderProgress progress(stderr, a.frames);
    std::vector<double> timedMs[2];  // [interpolated]: frame times without the first frame
    job.onFrame = [&](const FrameRecord& record) {
        frameLines += record.stats.dump() + "\n";
        if (numbered) outputs.stageImage(*record.image, framePath(a.out, record.index));
        if (numberedExr) outputs.stageImage(*record.image, framePath(a.exr, record.index));
        if (record.index > 0 || a.frames == 1) {
            timedMs[record.stats.value("interpolated", false) ? 1 : 0].push_back(record.stats.value("frame_ms", 0.0));
        }
        progress.frameDone(record.index);
    };
    RenderOutput out = renderScene(sceneGpu, job);
    if (!a.tilesImage.empty()) {
        if (!out.tileOverlay) throw Error("--tiles-image: method " + a.method + " produced no tile overlay");
        outputs.stageImage(*out.tileOverlay, fileName(a.tilesImage));
    }

    out.stats["scene"] = a.scene;
    out.stats["triangles"] = scene.triangleCount();
    out.stats["gl_renderer"] = context.info().renderer;
    out.stats["gl_api"] = glApiName(context.info().api);
    out.stats["gl_version"] = context.info().version;
    if (!numbered) outputs.stageImage(out.image, fileName(a.out));
    if (!a.exr.empty() && !numberedExr) outputs.stageImage(out.image, fileName(a.exr));
    if (!a.frameStats.empty()) outputs.stage(fileName(a.frameStats), frameLines);
    if (!a.stats.empty()) outputs.stage(fileName(a.stats), out.stats.dump(2) + "\n");
    outputs.commit();
    auto meanOf = [](const std::vector<double>& v) {
        double s = 0.0;
        for (double x : v) s += x;
        return v.empty() ? 0.0 : s / double(v.size());
    };
    if (!timedMs[1].empty()) {
        // Temporal run: the median lands on interpolated frames; give the means instead.
        const size_t timed = timedMs[0].size() + timedMs[1].size();
        char real[64] = "none timed";
        if (!timedMs[0].empty()) std::snprintf(real, sizeof real, "%.2f ms (mean of %zu)", meanOf(timedMs[0]), timedMs[0].size());
        std::printf("%s: %s %dx%d, frame %.2f ms (mean of %zu), real frames %s, interpolated %.2f ms (mean of %zu), "
                    "%.2f ms a frame over a long run, max %u fragments/pixel -> %s\n",
                    a.method.c_str(), a.scene.c_str(), a.width, a.height,
                    (meanOf(timedMs[0]) * double(timedMs[0].size()) + meanOf(timedMs[1]) * double(timedMs[1].size())) /
                        double(timed),
                    timed, real, meanOf(timedMs[1]), timedMs[1].size(), out.stats["frame_ms_long_run"].get<double>(),
                    out.stats["max_fragments"].get<unsigned>(), a.out.c_str());
        if (timedMs[0].empty()) {
            // The first frame (untimed) was the only real one: the long-run figure is then the
            // interpolated frames' mean alone, which no schedule achieves.
            std::printf("no real frame was timed, so the long-run figure leaves the real frames out: render more frames "
                        "than the temporal interval, or add --warmup\n");
        }
    } else {
        std::printf("%s: %s %dx%d, frame %.2f ms (median of %d), max %u fragments/pixel -> %s\n", a.method.c_str(),
                    a.scene.c_str(), a.width, a.height, out.stats["frame_ms"].get<double>(),
                    out.stats["timed_frames"].get<int>(), out.stats["max_fragments"].get<unsigned>(), a.out.c_str());
    }
    if (out.stats["max_fragments"].get<unsigned>() == 0) {
        if (opaqueOnly) {
            std::fprintf(stderr, "starnt: warning: no transparent fragment of %s reached the last frame: its opaque surfaces "
                                 "are drawn as the background (--alpha A renders every surface transparent)\n",
                         a.scene.c_str());
        } else {
            std::fprintf(stderr, "starnt: warning: no fragment of %s reached the last frame: check --camera or --camera-path, and "
                                 "--alpha-cutoff (fragments below it are discarded; a scene far smaller than 1e-6 or farther than "
                                 "about 1e7 from the origin is lost to float precision)\n",
                         a.scene.c_str());
        }
    }
    if (out.stats.contains("error") && out.stats["error"].contains("interpolated_flash")) {
        const auto& flash = out.stats["error"]["interpolated_flash"];
        if (flash["real_mse_beside"].get<double>() > 0.0) {
            std::printf("worst interpolated frame: %d, MSE %.2fx that of the real frames beside it\n", flash["frame"].get<int>(),
                        flash["worst_ratio"].get<double>());
        } else {
            // (real frames equal to the reference: no ratio to give)
            std::printf("worst interpolated frame: %d, MSE %.3g where the real frames beside it have 0\n", flash["frame"].get<int>(),
                        flash["mse"].get<double>());
        }
    }
}

}  // namespace

glm::vec3 parseColor(const std::string& text, const char* flag) {
    std::istringstream in(text);
    glm::vec3 c;
    char comma1 = 0, comma2 = 0, extra = 0;
    if (!(in >> c.r >> comma1 >> c.g >> comma2 >> c.b) || comma1 != ',' || comma2 != ',' || (in >> extra)) {
        throw Error(std::string(flag) + " '" + text + "': expected R,G,B");
    }
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > 1.0f) {
            throw Error(std::string(flag) + " '" + text + "': components must be in [0, 1]");
        }
    }
    return c;
}

void addRenderCommand(CLI::App& app) {
    // CLI11 writes into the arguments and the callback reads them: they live as long as the app.
    declareRenderOptions(app, std::make_shared<RenderArgs>());
}

}  // namespace starnt::app
