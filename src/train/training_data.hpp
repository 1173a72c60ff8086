// Training data from real renders: fragment lists captured with the A-buffer from the built-in
// procedural scenes, over several seeds, cameras and alpha overrides. The suite scenes of
// ../shared/scenes are never used: they are the held-out evaluation set.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "starnt/tools/fragments.hpp"

namespace starnt {

struct CaptureSetOptions {
    std::vector<std::string> scenes = {"tubes", "smoke", "panes", "random"};  // built-in names
    std::vector<uint32_t> seeds = {11, 12};
    std::vector<float> azimuths = {0.0f, 70.0f, 150.0f, 250.0f};
    std::vector<float> elevations = {-20.0f, 25.0f};
    std::vector<float> alphaOverrides = {-1.0f, 0.15f, 0.5f};  // -1: the scene's own alphas
    int width = 96;
    int height = 72;
    std::function<void(size_t done, size_t total)> progress;
};

// Every non-empty pixel's fragment list of every capture (needs a current GL context).
std::vector<FragmentList> captureTrainingLists(const CaptureSetOptions& options);

}  // namespace starnt
