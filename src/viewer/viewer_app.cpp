#include "viewer/viewer_app.hpp"
#include "render/frame_stats_json.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>

#include "render/option_text.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"
#include "viewer/display_pass.hpp"
#include "viewer/error_view.hpp"
#include "viewer/glfw_window.hpp"
#include "viewer/imgui_layer.hpp"
#include "viewer/method_set.hpp"
#include "viewer/viewer_script.hpp"
#include "viewer/viewer_ui.hpp"

namespace starnt::viewer {
namespace {

nlohmann::json vec3Json(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

// The scene list's label when the scene is in it (so the list can mark it), else the file name.
std::string sceneLabelOf(const std::string& spec, const std::vector<SceneEntry>& list) {
    for (const auto& entry : list) {
        if (entry.spec == spec) return entry.label;
    }
    if (spec.rfind("builtin:", 0) == 0) return spec;
    return std::filesystem::path(spec).filename().string();
}

// "shot.png" -> "shot.json": the stats go next to the image.
std::string statsPathFor(const std::string& png) {
    return std::filesystem::path(png).replace_extension(".json").string();
}

std::string timestampedScreenshotName() {
    char stamp[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(stamp, sizeof stamp, "%Y%m%d_%H%M%S", std::localtime(&now));
    return std::string("starnt_view_") + stamp + ".png";
}

class ViewerApp {
public:
    ViewerApp(const ViewerConfig& config, GlfwWindow& window, const Scene& scene, std::vector<ScriptCommand> script)
        : config_(config), window_(window), imgui_(window.handle()), settings_(config.settings), methods_(config.settings), script_(std::move(script)), showUi_(config.showUi) {
        scenes_ = listScenes(config.scenesFolder);
        renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        glVersion_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
        installScene(scene, config.scene);
        computeErrorRequested_ = settings_.view == ViewMode::Error;  // --view error: one map to start with
        double x = 0, y = 0;
        glfwGetCursorPos(window_.handle(), &x, &y);
        lastCursor_ = {x, y};
    }

    void run() {
        auto last = std::chrono::steady_clock::now();
        while (!window_.closeRequested() && !quit_) {
            glfwPollEvents();
            const auto now = std::chrono::steady_clock::now();
            const float seconds = std::chrono::duration<float>(now - last).count();
            last = now;
            if (framesShown_ > 0) stats_.addDisplayFrame(seconds * 1000.0);
            frame(seconds);
            ++framesShown_;
            if (config_.framesLimit > 0 && framesShown_ >= config_.framesLimit) break;
        }
    }

    // The first screenshot that could not be written (empty if none): the command then fails when
    // the window closes, so that a scripted run cannot lose an output silently.
    const std::string& lostOutput() const { return lostOutput_; }

private:
    void frame(float seconds) {
        const glm::ivec2 size = window_.framebufferSize();
        if (size.x <= 0 || size.y <= 0) {  // minimised: nothing to draw
            glfwWaitEventsTimeout(0.1);
            return;
        }
        applyUiRequests(std::exchange(pendingUi_, {}));
        for (const std::string& path : window_.takeDroppedPaths()) loadSceneOrReport(path, "dropped file");
        runScript(size);
        handleInput(seconds, size);

        camera_.setAspect(float(size.x) / float(size.y));
        const Camera camera = camera_.camera();
        if (!renderMethods(camera, size)) return;
        if (std::exchange(computeErrorRequested_, false)) computeError(camera, size);
        display(camera, size);
        if (screenshotPath_ && !screenshotWithUi_) saveScreenshot(*std::exchange(screenshotPath_, std::nullopt), camera, size);
        if (showUi_) {
            imgui_.beginFrame();
            pendingUi_ = drawUi(uiModel(camera, size));
            imgui_.endFrame();
        }
        if (screenshotPath_) saveScreenshot(*std::exchange(screenshotPath_, std::nullopt), camera, size);
        window_.swapBuffers();
        updateTitle();
    }

    // ---- scene ----

    void installScene(const Scene& scene, const std::string& spec) {
        auto gpu = std::make_unique<SceneGpu>(scene);
        sceneGpu_ = std::move(gpu);
        sceneSpec_ = spec;
        sceneLabel_ = sceneLabelOf(spec, scenes_);
        sceneTriangles_ = scene.triangleCount();
        sceneBounds_ = scene.bounds();
        const glm::ivec2 size = window_.framebufferSize();
        camera_.reset(scene.bounds(), size.y > 0 ? float(size.x) / float(size.y) : 16.0f / 9.0f);
        methods_.resetHistory();
        stats_.clear();
        ++sceneGeneration_;
    }

    // A scene that fails to load is reported and the current one stays (bad input never
    // ends the session).
    void loadSceneOrReport(const std::string& spec, const char* origin) {
        try {
            installScene(loadScene(spec), spec);
            error_.clear();
            message_ = "loaded " + sceneLabel_;
        } catch (const std::exception& e) {
            reportError(std::string("cannot load ") + origin + " '" + spec + "': " + e.what() + " (kept " + sceneLabel_ + ")");
        }
    }

    // ---- settings ----

    void applySettings(const ViewerSettings& next) {
        try {
            const bool rebuild = needsNewMethods(settings_, next);
            methods_.configure(next);
            if (rebuild) stats_.clear();  // timings of a different method would mix in
            // Switching to the error view is the request for a map; later ones use the button.
            if (next.view == ViewMode::Error && settings_.view != ViewMode::Error) computeErrorRequested_ = true;
            settings_ = next;
            error_.clear();
        } catch (const std::exception& e) {
            reportError(std::string("cannot switch: ") + e.what());
        }
    }

    void applyUiRequests(const UiRequests& req) {
        if (req.settings) applySettings(*req.settings);
        if (req.loadScene) loadSceneOrReport(*req.loadScene, "scene");
        if (req.cameraMode) camera_.setMode(*req.cameraMode);
        if (req.resetCamera) resetCamera();
        if (req.computeError) computeErrorRequested_ = true;
        if (req.screenshot) requestScreenshot(timestampedScreenshotName());
    }

    void requestScreenshot(const std::string& path) {
        screenshotPath_ = path;
        screenshotWithUi_ = false;
    }

    void resetCamera() {
        const glm::ivec2 size = window_.framebufferSize();
        camera_.reset(sceneBounds(), float(size.x) / float(std::max(size.y, 1)));
        methods_.resetHistory();  // a cut: nothing to reproject from
    }

    Bounds sceneBounds() const { return sceneBounds_; }

    // ---- scripted input ----

    void runScript(glm::ivec2 size) {
        if (waitFrames_ > 0) {
            --waitFrames_;
            return;
        }
        while (scriptPos_ < script_.size()) {
            const ScriptCommand& cmd = script_[scriptPos_++];
            if (cmd.verb == "frames") {
                waitFrames_ = cmd.frames - 1;  // this frame is the first of them
                return;
            }
            execute(cmd, size);
            // These act on this frame's image: later commands wait for the next frame.
            if (cmd.verb == "screenshot" || cmd.verb == "quit" || cmd.verb == "flip") return;
        }
    }

    void execute(const ScriptCommand& cmd, glm::ivec2 size) {
        const auto& n = cmd.numbers;
        if (cmd.verb == "orbit") {
            camera_.setOrbit(n[0], n[1]);
            methods_.resetHistory();
        } else if (cmd.verb == "drag") {
            camera_.rotate(n[0], n[1]);
        } else if (cmd.verb == "pan") {
            camera_.pan(n[0], n[1], float(size.y));
        } else if (cmd.verb == "scroll") {
            camera_.scroll(n[0]);
        } else if (cmd.verb == "fly") {
            camera_.fly({n[0], n[1], n[2], false}, n[3]);
        } else if (cmd.verb == "camera") {
            if (cmd.args[0] == "reset") resetCamera();
            else camera_.setMode(cmd.args[0] == "fly" ? CameraMode::Fly : CameraMode::Orbit);
        } else if (cmd.verb == "scene" || cmd.verb == "drop") {
            loadSceneOrReport(cmd.args[0], cmd.verb == "drop" ? "dropped file" : "scene");
        } else if (cmd.verb == "flip") {
            ViewerSettings next = settings_;
            next.view = ViewMode::Error;
            applySettings(next);
            computeErrorRequested_ = true;  // also when the view already was the error view
        } else if (cmd.verb == "screenshot") {
            screenshotPath_ = cmd.args[0];
            screenshotWithUi_ = cmd.args.size() == 2;
        } else if (cmd.verb == "quit") {
            quit_ = true;
        } else {
            ViewerSettings next = settings_;
            next.set(cmd.verb, cmd.args[0]);  // validated when the script was parsed
            applySettings(next);
        }
    }

    // ---- input ----

    void handleInput(float seconds, glm::ivec2 size) {
        const bool uiMouse = showUi_ && imgui_.wantsMouse();
        const bool uiKeyboard = showUi_ && imgui_.wantsKeyboard();
        GLFWwindow* w = window_.handle();
        double x = 0, y = 0;
        glfwGetCursorPos(w, &x, &y);
        const glm::dvec2 delta = glm::dvec2(x, y) - lastCursor_;
        lastCursor_ = {x, y};
        const bool primary = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        const bool secondary = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                               glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
        // A drag belongs to the scene only when it started outside the panels.
        if (!primary && !secondary) sceneDrag_ = false;
        else if (!buttonWasDown_) sceneDrag_ = !uiMouse;
        buttonWasDown_ = primary || secondary;
        if (sceneDrag_ && primary) camera_.rotate(float(delta.x), float(delta.y));
        else if (sceneDrag_ && secondary) camera_.pan(float(delta.x), float(delta.y), float(size.y));
        if (const float wheel = window_.takeScroll(); wheel != 0.0f && !uiMouse) camera_.scroll(wheel);

        for (int key : window_.takeKeyPresses()) {
            if (uiKeyboard) continue;
            if (key == GLFW_KEY_TAB) camera_.setMode(camera_.mode() == CameraMode::Orbit ? CameraMode::Fly : CameraMode::Orbit);
            else if (key == GLFW_KEY_R) resetCamera();
            else if (key == GLFW_KEY_H) showUi_ = !showUi_;
            else if (key == GLFW_KEY_P) requestScreenshot(timestampedScreenshotName());
        }
        if (camera_.mode() == CameraMode::Fly && !uiKeyboard) {
            auto held = [w](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
            FlyInput in;
            in.forward = held(GLFW_KEY_W) - held(GLFW_KEY_S);
            in.right = held(GLFW_KEY_D) - held(GLFW_KEY_A);
            in.up = held(GLFW_KEY_E) - held(GLFW_KEY_Q);
            in.fast = held(GLFW_KEY_LEFT_SHIFT) + held(GLFW_KEY_RIGHT_SHIFT) > 0.0f;
            camera_.fly(in, std::min(seconds, 0.25f));  // a long stall must not throw the camera away
        }
    }

    // ---- rendering ----

    // Renders the methods; when one fails, reports it and falls back to wboit.
    bool renderMethods(const Camera& camera, glm::ivec2 size) {
        try {
            lastFrame_ = methods_.render(*sceneGpu_, camera, size, settings_);
        } catch (const std::exception& e) {
            if (settings_.method == "wboit" && settings_.splitMethod.empty()) throw;  // nothing safer to fall back on
            // One pass and bounded memory: the safest method to fall back on (e.g. after the
            // A-buffer hit its memory cap).
            reportError(settings_.method + " failed: " + e.what() + "; switched to wboit");
            ViewerSettings fallback = settings_;
            fallback.method = "wboit";
            fallback.splitMethod.clear();
            methods_.configure(fallback);
            settings_ = fallback;
            return false;
        }
        stats_.addFrame(lastFrame_.frameMs, lastFrame_.passMs, lastFrame_.interpolated);
        return true;
    }

    void computeError(const Camera& camera, glm::ivec2 size) {
        try {
            errorView_.compute(*sceneGpu_, sceneGeneration_, camera, size, settings_, methods_.primary().outputTexture());
            message_ = "FLIP map computed";
        } catch (const std::exception& e) {
            reportError(std::string("cannot compute the error map: ") + e.what());
        }
    }

    void display(const Camera& camera, glm::ivec2 size) {
        GLuint left = methods_.primary().outputTexture();
        GLuint right = methods_.split() ? methods_.split()->outputTexture() : 0;
        if (settings_.view == ViewMode::Tiles) {
            if (GLuint overlay = methods_.primary().tileOverlayTexture()) left = overlay;
            if (methods_.split()) {
                if (GLuint overlay = methods_.split()->tileOverlayTexture()) right = overlay;
            }
        } else if (settings_.view == ViewMode::Error) {
            if (GLuint heatmap = errorView_.heatmapFor(sceneGeneration_, camera, size, settings_)) {
                left = heatmap;
                right = 0;
            }
        }
        displayPass_.draw(left, right, size.x / 2, size);
    }

    // ---- screenshots and stats ----

    void saveScreenshot(const std::string& path, const Camera& camera, glm::ivec2 size) {
        try {
            saveImage(readWindowImage(size), path);
            const std::string statsPath = statsPathFor(path);
            writeFileAtomic(statsPath, currentStats(camera, size).dump(2) + "\n");
            message_ = "saved " + path + " and " + statsPath;
            std::printf("starnt view: screenshot %s, stats %s\n", path.c_str(), statsPath.c_str());
            std::fflush(stdout);
        } catch (const std::exception& e) {
            reportError(std::string("screenshot failed: ") + e.what());
            if (lostOutput_.empty()) lostOutput_ = std::string("screenshot ") + path + " failed: " + e.what();
        }
    }

    nlohmann::json currentStats(const Camera& camera, glm::ivec2 size) const {
        const nlohmann::json ms = frameStatsJson(lastFrame_.methodStats);
        nlohmann::json stats = {
            {"scene", sceneSpec_},
            {"triangles", sceneTriangles_},
            {"method", settings_.method},
            {"split_method", settings_.splitMethod.empty() ? nlohmann::json(nullptr) : nlohmann::json(settings_.splitMethod)},
            {"view", viewModeName(settings_.view)},
            {"width", size.x},
            {"height", size.y},
            {"frame_ms", stats_.frameMedianMs()},
            {"display_frame_ms", stats_.displayFrameMedianMs()},
            {"pass_ms", stats_.passMedianMs()},
            {"pass_timing", methods_.timingMode()},
            {"scale_pass2", ms.value("scale_pass2", 1.0)},
            {"scale_pass3", ms.value("scale_pass3", 1.0)},
            {"w_bar", ms.contains("w_bar") ? ms["w_bar"] : nlohmann::json(nullptr)},
            {"tile_levels", ms.contains("tile_levels") ? ms["tile_levels"] : nlohmann::json::array({0, 0, 0, 0})},
            {"interpolated", lastFrame_.interpolated},
            {"real_frames", stats_.realFrames()},
            {"interpolated_frames", stats_.interpolatedFrames()},
            {"memory_bytes", methods_.gpuMemoryBytes()},
            {"scene_memory_bytes", sceneGpu_->gpuMemoryBytes()},
            {"method_stats", ms},
            {"options",
             {{"spatial", spatialText(settings_.options)},
              {"scales", scalesText(settings_.options)},
              {"inference", settings_.options.neural.inference == NeuralOptions::Inference::Corners ? "corners" : "full"},
              {"temporal", temporalText(settings_.options)},
              {"target_fps", settings_.options.neural.targetFps},
              {"alpha", settings_.alpha ? nlohmann::json(*settings_.alpha) : nlohmann::json(nullptr)},
              {"background", vec3Json(settings_.background)}}},
            // The camera in `starnt render --camera FILE.json` form, to render the same view headless.
            {"camera",
             {{"position", vec3Json(camera.position)},
              {"target", vec3Json(camera.target)},
              {"up", vec3Json(camera.up)},
              {"fov_y_deg", camera.fovYDeg},
              {"near", camera.nearPlane},
              {"far", camera.farPlane},
              {"mode", camera_.mode() == CameraMode::Orbit ? "orbit" : "fly"}}},
            {"gl_renderer", renderer_},
            {"gl_version", glVersion_},
            {"last_error", error_.empty() ? nlohmann::json(nullptr) : nlohmann::json(error_)},
        };
        if (GLuint heatmap = errorView_.heatmapFor(sceneGeneration_, camera, size, settings_); heatmap) {
            stats["error"] = {{"reference_method", "abuffer"}, {"flip", errorView_.meanFlip()}, {"mse", errorView_.mse()}};
        }
        return stats;
    }

    UiModel uiModel(const Camera& camera, glm::ivec2 size) {
        UiModel m;
        m.settings = &settings_;
        m.scenes = &scenes_;
        m.sceneLabel = sceneLabel_;
        m.sceneTriangles = sceneTriangles_;
        m.error = error_;
        m.message = message_;
        m.cameraMode = camera_.mode();
        m.stats = &stats_;
        m.methodStats = lastFrame_.methodStats;
        m.passCounters = lastFrame_.passCounters;
        m.tilesAvailable = methods_.primary().tileOverlayTexture() != 0;
        m.errorMapCurrent = errorView_.heatmapFor(sceneGeneration_, camera, size, settings_) != 0;
        m.meanFlip = errorView_.meanFlip();
        m.mse = errorView_.mse();
        m.methodMemoryBytes = methods_.gpuMemoryBytes();
        m.methodMemoryTargets = methods_.primary().gpuMemoryTargets();
        m.sceneMemoryBytes = sceneGpu_->gpuMemoryBytes();
        m.renderer = renderer_;
        m.timingMode = methods_.timingMode();
        m.width = size.x;
        m.height = size.y;
        return m;
    }

    void reportError(const std::string& message) {
        error_ = message;
        std::fprintf(stderr, "starnt view: %s\n", message.c_str());
    }

    void updateTitle() {
        const auto now = std::chrono::steady_clock::now();
        if (now - lastTitle_ < std::chrono::milliseconds(500)) return;
        lastTitle_ = now;
        char text[512];
        std::snprintf(text, sizeof text, "starnt view - %s - %s - %.1f ms", sceneLabel_.c_str(), settings_.method.c_str(),
                      stats_.frameMedianMs());
        window_.setTitle(text);
    }

    const ViewerConfig& config_;
    GlfwWindow& window_;
    ImGuiLayer imgui_;
    ViewerSettings settings_;
    MethodSet methods_;
    DisplayPass displayPass_;
    ErrorView errorView_;
    CameraController camera_;
    FrameTimeMedians stats_;
    RenderedFrame lastFrame_;
    UiRequests pendingUi_;

    std::unique_ptr<SceneGpu> sceneGpu_;
    Bounds sceneBounds_;
    std::string sceneSpec_, sceneLabel_;
    size_t sceneTriangles_ = 0;
    int sceneGeneration_ = 0;
    std::vector<SceneEntry> scenes_;
    std::string renderer_, glVersion_, error_, message_;

    std::vector<ScriptCommand> script_;
    std::string lostOutput_;
    size_t scriptPos_ = 0;
    int waitFrames_ = 0;
    std::optional<std::string> screenshotPath_;
    bool screenshotWithUi_ = false;  // taken after the panels are drawn
    bool computeErrorRequested_ = false;
    bool quit_ = false;
    bool showUi_ = true;
    int framesShown_ = 0;

    glm::dvec2 lastCursor_{0.0};
    bool buttonWasDown_ = false, sceneDrag_ = false;
    std::chrono::steady_clock::time_point lastTitle_{};
};

}  // namespace

void runViewer(const ViewerConfig& config) {
    // Everything that can be checked without a window is checked first.
    std::vector<ScriptCommand> script = parseScript(config.script);
    checkImageSize(config.width, config.height);
    if (config.framesLimit < 0) throw Error("--frames-limit must not be negative");
    const Scene scene = loadScene(config.scene);
    GlfwWindow window(config.width, config.height, "starnt view", config.api);
    ViewerApp app(config, window, scene, std::move(script));
    app.run();
    if (!app.lostOutput().empty()) throw Error(app.lostOutput());
}

}  // namespace starnt::viewer
