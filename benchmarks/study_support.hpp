// What the offline studies (per_tile_scale_study.cpp, half_sums_rounding_study.cpp) share: their
// list options and one suite scene captured at the default camera (every fragment, A-buffer).
#pragma once
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_plan.hpp"
#include "reference/fragment_capture.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt::study {

// Mean over RGB of the squared difference of the sRGB encodings of two linear colours (each
// clamped to [0, 1]): one pixel's share of the MSE the bench reports.
inline double squaredSrgb(glm::vec3 a, glm::vec3 b) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double d = linearToSrgb(std::clamp(a[c], 0.0f, 1.0f)) - linearToSrgb(std::clamp(b[c], 0.0f, 1.0f));
        sum += d * d;
    }
    return sum / 3.0;
}

inline std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

// The studies' command line: --width W (16..4096; the height is W * 9 / 16), --scenes a,b,... and
// the study's own options (`extra`: option -> what to do with its value). On an unknown option or a
// bad width it prints why, prefixed with `study`, and returns false.
inline bool parseStudyArgs(int argc, char** argv, const char* study, int& width, std::vector<std::string>& names,
                           const std::map<std::string, std::function<void(const std::string&)>>& extra = {}) {
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--width") width = std::atoi(value.c_str());
        else if (key == "--scenes") names = splitList(value);
        else if (const auto option = extra.find(key); option != extra.end()) option->second(value);
        else {
            std::fprintf(stderr, "%s: unknown option %s\n", study, key.c_str());
            return false;
        }
    }
    if (width < 16 || width > 4096) {
        std::fprintf(stderr, "%s: --width must be within 16..4096\n", study);
        return false;
    }
    return true;
}

struct CapturedScene {
    bench::SceneSpec spec;
    FrameDesc frame;  // white background, the bench's alpha cut-off
    CapturedFrame fragments;  // row 0 = top
};

// Suite scene `name` (bench::suiteScenes(), read from STARNT_SHARED_SCENES) at width x height, camera
// orbit 0 / elevation 15 (the default camera). Needs a current GL context; throws starnt::Error.
inline CapturedScene captureSuiteScene(const std::string& name, int width, int height) {
    const auto& specs = bench::suiteScenes();
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.name == name; });
    if (spec == specs.end()) throw Error("unknown suite scene '" + name + "'");
    const Scene scene = loadScene((std::filesystem::path(STARNT_SHARED_SCENES) / spec->source).string());
    const float aspect = float(width) / float(height);
    const Camera camera = orbitCamera(scene.bounds(), 0.0f, 15.0f, aspect);
    SceneGpu gpu(scene);
    CapturedScene out;
    out.spec = *spec;
    out.frame.width = width;
    out.frame.height = height;
    out.frame.background = glm::vec3(1.0f);
    out.frame.view = camera.view();
    out.frame.projection = camera.projection(aspect);
    out.frame.alphaCutoff = spec->alphaCutoff;
    FragmentCapture capturer(SceneGpu::surfaceShader());
    out.fragments = capturer.capture(out.frame, gpu.callback(out.frame.view, out.frame.projection, bench::surfaceOptionsFor(*spec)));
    return out;
}

}  // namespace starnt::study
