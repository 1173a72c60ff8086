// The viewer's Dear ImGui panels: "STAR-NT" (scene, method, view and live options) and "Timing"
// (per-pass running medians, frame-time graph, method counters). The panels only read the model
// and return what the user asked for; the app applies it at the start of the next frame.
#pragma once
#include <map>

#include "gl/gpu_timer.hpp"
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "starnt/oit_method.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/frame_time_medians.hpp"
#include "viewer/scene_catalog.hpp"
#include "viewer/viewer_settings.hpp"

namespace starnt::viewer {

struct UiModel {
    const ViewerSettings* settings = nullptr;
    const std::vector<SceneEntry>* scenes = nullptr;
    std::string sceneLabel;
    size_t sceneTriangles = 0;
    std::string error;    // shown in red until the next successful action
    std::string message;  // e.g. where the last screenshot went
    CameraMode cameraMode = CameraMode::Orbit;
    const FrameTimeMedians* stats = nullptr;
    FrameStats methodStats;  // the primary method's lastFrameStats()
    std::map<std::string, gl::PassCounters> passCounters;  // the primary method's last frame
    bool tilesAvailable = false;
    // Error view: whether a FLIP map for the current inputs exists, and its numbers.
    bool errorMapCurrent = false;
    double meanFlip = 0.0, mse = 0.0;
    size_t methodMemoryBytes = 0, sceneMemoryBytes = 0;
    OitMethod::MemoryTargets methodMemoryTargets;  // the primary method's, name -> bytes
    std::string renderer, timingMode;
    int width = 0, height = 0;
};

struct UiRequests {
    std::optional<ViewerSettings> settings;  // changed settings
    std::optional<std::string> loadScene;    // a scene spec
    std::optional<CameraMode> cameraMode;
    bool resetCamera = false;
    bool computeError = false;
    bool screenshot = false;
};

UiRequests drawUi(const UiModel& model);

}  // namespace starnt::viewer
