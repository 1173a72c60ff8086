#include "viewer/viewer_ui.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "methods/neural/tiles/tile_constants.h"
#include "render/option_text.hpp"
#include "starnt/error.hpp"

namespace starnt::viewer {
namespace {

const ImVec4 kErrorColour(1.0f, 0.35f, 0.3f, 1.0f);

// A combo box over `items`; returns true when the user picked a different one.
bool combo(const char* label, const std::vector<std::string>& items, std::string& current) {
    bool changed = false;
    if (ImGui::BeginCombo(label, current.c_str())) {
        for (const auto& item : items) {
            const bool selected = item == current;
            if (ImGui::Selectable(item.c_str(), selected) && !selected) {
                current = item;
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

// Applies one textual setting to `next`; the UI only offers valid values, so this cannot throw
// in practice, but a failure is still shown rather than lost.
void setOrReport(ViewerSettings& next, const char* key, const std::string& value, std::string& problem) {
    try {
        next.set(key, value);
    } catch (const Error& e) {
        problem = e.what();
    }
}

// The two panels together need about 900x450 pixels; in a smaller window they would hide the
// scene, so they start collapsed to their title bars there (a click opens them).
bool startCollapsedInSmallWindows() {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const bool small = size.x < 900.0f || size.y < 450.0f;
    if (small) ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver);
    return small;
}

void sceneSection(const UiModel& m, UiRequests& req) {
    ImGui::Text("Scene: %s (%zu triangles)", m.sceneLabel.c_str(), m.sceneTriangles);
    if (ImGui::BeginCombo("scene", m.sceneLabel.c_str())) {
        for (const auto& entry : *m.scenes) {
            if (ImGui::Selectable(entry.label.c_str(), entry.label == m.sceneLabel)) req.loadScene = entry.spec;
        }
        ImGui::EndCombo();
    }
    ImGui::TextDisabled("or drop a .gltf/.glb/.obj file on the window");
}

void methodSection(const UiModel& m, ViewerSettings& next, std::string& problem) {
    const auto names = methodNames();
    std::string method = next.method;
    if (combo("method", names, method)) setOrReport(next, "method", method, problem);
    std::vector<std::string> splitChoices{"off"};
    splitChoices.insert(splitChoices.end(), names.begin(), names.end());
    std::string split = next.splitMethod.empty() ? "off" : next.splitMethod;
    if (combo("split right half", splitChoices, split)) setOrReport(next, "split", split, problem);

    int view = int(next.view);
    ImGui::RadioButton("final", &view, int(ViewMode::Final));
    ImGui::SameLine();
    ImGui::RadioButton("tiles", &view, int(ViewMode::Tiles));
    ImGui::SameLine();
    ImGui::RadioButton("error (FLIP)", &view, int(ViewMode::Error));
    next.view = ViewMode(view);
    if (next.view == ViewMode::Tiles && !m.tilesAvailable) ImGui::TextDisabled("no tiles: this method/option set has none");
}

void surfaceSection(ViewerSettings& next) {
    bool overrideAlpha = next.alpha.has_value();
    float alpha = next.alpha.value_or(0.5f);
    if (ImGui::Checkbox("global alpha", &overrideAlpha)) next.alpha = overrideAlpha ? std::optional<float>(alpha) : std::nullopt;
    if (overrideAlpha) {
        ImGui::SameLine();
        if (ImGui::SliderFloat("##alpha", &alpha, 0.0f, 1.0f, "%.2f")) next.alpha = alpha;
    }
    float bg[3] = {next.background.r, next.background.g, next.background.b};
    if (ImGui::ColorEdit3("background (linear)", bg, ImGuiColorEditFlags_Float)) {
        for (int i = 0; i < 3; ++i) next.background[i] = std::clamp(bg[i], 0.0f, 1.0f);
    }
}

void accelerationSection(ViewerSettings& next, std::string& problem) {
    if (!ImGui::CollapsingHeader("Neural acceleration (starnt, dfaoit)", ImGuiTreeNodeFlags_DefaultOpen)) return;
    std::string spatial = spatialText(next.options);
    if (combo("spatial tiles", {"default", "on", "off"}, spatial)) setOrReport(next, "spatial", spatial, problem);

    bool fixedScales = next.options.neural.fixedScale2 > 0.0f;
    if (ImGui::Checkbox("fixed scales", &fixedScales)) setOrReport(next, "scales", fixedScales ? "100,50" : "auto", problem);
    if (fixedScales) {
        // Quarter steps only: each change rebuilds the method.
        int p2 = int(next.options.neural.fixedScale2 * 4.0f + 0.5f), p3 = int(next.options.neural.fixedScale3 * 4.0f + 0.5f);
        bool changed = ImGui::SliderInt("pass 2 (x25%)", &p2, 1, 4);
        changed |= ImGui::SliderInt("pass 3 (x25%)", &p3, 1, 4);
        if (changed) setOrReport(next, "scales", std::to_string(p2 * 25) + "," + std::to_string(p3 * 25), problem);
    }
    std::string rule = scaleRuleText(next.options.neural.scaleRule);
    if (combo("scale rule", {"snapped", "continuous", "step"}, rule)) setOrReport(next, "scale-rule", rule, problem);
    std::string signal = tileSignalText(next.options.neural.tileSignal);
    if (combo("tile signal", {"back", "composite"}, signal)) setOrReport(next, "tile-signal", signal, problem);
    bool guard = next.options.neural.scaleGuard;
    if (ImGui::Checkbox("scale guard (probe frames)", &guard)) setOrReport(next, "scale-guard", guard ? "on" : "off", problem);
    std::string upsample = upsampleText(next.options.neural.upsample);
    if (combo("upsample", {"bilinear", "joint"}, upsample)) setOrReport(next, "upsample", upsample, problem);
    std::string inference = next.options.neural.inference == NeuralOptions::Inference::Corners ? "corners" : "full";
    if (combo("inference", {"full", "corners"}, inference)) setOrReport(next, "inference", inference, problem);
    std::string temporal = temporalText(next.options);
    if (combo("temporal", {"off", "auto", "2", "3", "4", "8"}, temporal)) setOrReport(next, "temporal", temporal, problem);
    std::string mode = temporalModeText(next.options.neural.temporalMode);
    if (combo("interpolated frames", {"refresh", "correct", "warp"}, mode)) setOrReport(next, "temporal-mode", mode, problem);
    static float targetFps = 60.0f;  // edited locally; applied when the drag ends (a rebuild each step would stall)
    if (!ImGui::IsAnyItemActive()) targetFps = float(next.options.neural.targetFps);
    ImGui::SliderFloat("target FPS", &targetFps, 1.0f, 240.0f, "%.0f");
    if (ImGui::IsItemDeactivatedAfterEdit()) setOrReport(next, "target-fps", std::to_string(targetFps), problem);
}

void cameraSection(const UiModel& m, UiRequests& req) {
    if (!ImGui::CollapsingHeader("Camera")) return;
    int mode = int(m.cameraMode);
    if (ImGui::RadioButton("orbit", &mode, int(CameraMode::Orbit))) req.cameraMode = CameraMode::Orbit;
    ImGui::SameLine();
    if (ImGui::RadioButton("fly", &mode, int(CameraMode::Fly))) req.cameraMode = CameraMode::Fly;
    ImGui::SameLine();
    if (ImGui::Button("reset (R)")) req.resetCamera = true;
    ImGui::TextDisabled("orbit: left drag rotate, right drag pan, wheel zoom");
    ImGui::TextDisabled("fly: WASD move, Q/E down/up, Shift fast, left drag look, wheel speed");
    ImGui::TextDisabled("Tab orbit/fly, H hide UI, P screenshot");
}

void controlPanel(const UiModel& m, UiRequests& req) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    startCollapsedInSmallWindows();
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("STAR-NT", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    ViewerSettings next = *m.settings;
    std::string problem;
    sceneSection(m, req);
    ImGui::Separator();
    methodSection(m, next, problem);
    if (next.view == ViewMode::Error) {
        if (ImGui::Button("compute FLIP vs A-buffer")) req.computeError = true;
        if (m.errorMapCurrent) ImGui::Text("mean FLIP %.4f, MSE %.2e", m.meanFlip, m.mse);
        else ImGui::TextDisabled("no map for this camera yet: press the button");
    }
    surfaceSection(next);
    accelerationSection(next, problem);
    cameraSection(m, req);
    ImGui::Separator();
    if (ImGui::Button("screenshot (P)")) req.screenshot = true;
    if (!m.message.empty()) ImGui::TextWrapped("%s", m.message.c_str());
    const std::string& error = problem.empty() ? m.error : problem;
    if (!error.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 380.0f);
        ImGui::TextColored(kErrorColour, "%s", error.c_str());
        ImGui::PopTextWrapPos();
    }
    ImGui::End();
    if (needsNewMethods(next, *m.settings) || next.view != m.settings->view || next.alpha != m.settings->alpha ||
        next.background != m.settings->background) {
        req.settings = next;
    }
}

void timingPanel(const UiModel& m) {
    const ImGuiIO& io = ImGui::GetIO();
    if (startCollapsedInSmallWindows()) ImGui::SetNextWindowPos(ImVec2(8, 34), ImGuiCond_FirstUseEver);  // under the other title
    else ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x - 8, 8), ImGuiCond_FirstUseEver, ImVec2(1, 0));
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Timing", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
    const FrameTimeMedians& s = *m.stats;
    ImGui::Text("%dx%d  %s", m.width, m.height, m.renderer.c_str());
    ImGui::Text("method frame %.2f ms (median), %.1f FPS", s.frameMedianMs(), s.frameMedianMs() > 0 ? 1000.0 / s.frameMedianMs() : 0.0);
    ImGui::Text("whole frame %.2f ms (with display, UI, swap)", s.displayFrameMedianMs());
    const auto& graph = s.frameGraphMs();
    if (!graph.empty()) {
        const float top = *std::max_element(graph.begin(), graph.end()) * 1.1f;
        ImGui::PlotLines("##frames", graph.data(), int(graph.size()), 0, "frame ms", 0.0f, top, ImVec2(300, 60));
    }
    ImGui::TextDisabled("passes: running medians, %s", m.timingMode.c_str());
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_SizingFixedFit)) {
        for (const auto& [name, ms] : s.passMedianMs()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%8.3f ms", ms);
        }
        ImGui::EndTable();
    }
    if (!m.passCounters.empty()) {
        ImGui::TextDisabled("work of the last frame (pipeline statistics)");
        if (ImGui::BeginTable("counters", 3, ImGuiTableFlags_SizingFixedFit)) {
            for (const auto& [name, c] : m.passCounters) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(name.c_str());
                ImGui::TableNextColumn();
                ImGui::Text("%9.3f M fragments", double(c.fragmentInvocations) / 1e6);
                ImGui::TableNextColumn();
                ImGui::Text("%8.3f M vertices", double(c.vertexInvocations) / 1e6);
            }
            ImGui::EndTable();
        }
    }
    ImGui::Separator();
    const std::optional<NeuralFrameStats>& neural = m.methodStats.neural;
    const bool hasTiles = neural && neural->tiles;
    if (hasTiles && neural->tiles->wBar) ImGui::Text("w_bar %.3f", *neural->tiles->wBar);
    else ImGui::TextDisabled("w_bar: n/a (no tiles)");
    if (neural) ImGui::Text("scales: pass 2 %.2f, pass 3 %.2f", double(neural->scalePass2), double(neural->scalePass3));
    if (hasTiles) {
        float levels[4];
        for (int i = 0; i < 4; ++i) levels[i] = float(neural->tiles->levels[size_t(i)]);
        ImGui::Text("tiles N0..N3: %.0f %.0f %.0f %.0f", levels[0], levels[1], levels[2], levels[3]);
        ImGui::PlotHistogram("##levels", levels, 4, 0, "tile levels", 0.0f, FLT_MAX, ImVec2(300, 50));
        // The scale guard's last probe beside w_bar: what each pass adds and what halving or
        // quartering it would lose, per occupied pixel, and the budget a pair's loss must stay under.
        if (const auto& g = neural->tiles->guard; g && g->occupiedPixels > 0) {
            const double n = double(g->occupiedPixels);
            ImGui::Text("guard (%s, every %d real frames): %.0f occupied pixels, budget %.1e per pixel",
                        neural->tiles->probeFrame.value_or(false) ? "probe" : "last probe",
                        neural->tiles->probeInterval.value_or(STARNT_SCALE_PROBE_INTERVAL), n, STARNT_SCALE_GUARD_BUDGET);
            ImGui::Text("  pass 2 adds %.2e, loses %.2e at 1/2, %.2e at 1/4", g->energyPass2 / n, g->lossPass2[0] / n,
                        g->lossPass2[1] / n);
            ImGui::Text("  pass 3 adds %.2e, loses %.2e at 1/2, %.2e at 1/4", g->energyPass3 / n, g->lossPass3[0] / n,
                        g->lossPass3[1] / n);
        } else if (neural->tiles->scaleGuard) {
            ImGui::TextDisabled("guard: no probe measured yet");
        }
    }
    ImGui::Text("frames: %d real, %d interpolated", s.realFrames(), s.interpolatedFrames());
    ImGui::Text("GPU memory: methods %.1f MiB, scene %.1f MiB", double(m.methodMemoryBytes) / (1 << 20),
                double(m.sceneMemoryBytes) / (1 << 20));
    // What the primary method's memory is made of (`memory_targets` of --stats); empty targets left out.
    if (!m.methodMemoryTargets.empty() && ImGui::TreeNode("memory per target")) {
        for (const auto& [name, bytes] : m.methodMemoryTargets) {
            if (bytes > 0) ImGui::Text("%-28s %8.2f MiB", name.c_str(), double(bytes) / (1 << 20));
        }
        ImGui::TreePop();
    }
    ImGui::End();
}

// Names the two halves of the split screen at the bottom of each.
void splitLabels(const UiModel& m) {
    const ViewerSettings& s = *m.settings;
    if (s.splitMethod.empty() || (s.view == ViewMode::Error && m.errorMapCurrent)) return;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float y = size.y - ImGui::GetFontSize() - 8.0f;
    auto label = [&](float x, const std::string& text) {
        const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
        draw->AddRectFilled(ImVec2(x - 4, y - 2), ImVec2(x + extent.x + 4, y + extent.y + 2), IM_COL32(0, 0, 0, 160));
        draw->AddText(ImVec2(x, y), IM_COL32(255, 255, 255, 255), text.c_str());
    };
    label(8.0f, s.method);
    label(size.x * 0.5f + 8.0f, s.splitMethod);
}

}  // namespace

UiRequests drawUi(const UiModel& model) {
    UiRequests requests;
    controlPanel(model, requests);
    timingPanel(model);
    splitLabels(model);
    return requests;
}

}  // namespace starnt::viewer
