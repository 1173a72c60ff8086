// libFuzzer target: camera specs and files. First byte: 0 = camera JSON file, 1 = camera-path JSON
// file, 2 = camera spec text ("orbit:..."), 3 = camera-path spec text. The result is also evaluated
// (a path at a few times), since a spec that parses must give finite cameras.
#include <cmath>

#include "fuzz_input.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/tools/camera_path.hpp"

namespace {

void checkFinite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) std::abort();  // a parsed camera must never give NaN/inf matrices
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const starnt::Bounds bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
    const float aspect = 16.0f / 9.0f;
    const int kind = data[0] % 4;
    const std::string spec = kind < 2 ? starnt::fuzz::writeFile(kind == 0 ? "camera.json" : "path.json", bytes).string()
                                      : std::string(bytes);
    starnt::fuzz::expectCleanOutcome([&] {
        if (kind % 2 == 0) {
            const starnt::Camera c = starnt::parseCameraSpec(spec, bounds, aspect);
            checkFinite(c.view());
            checkFinite(c.projection(aspect));
        } else {
            const starnt::CameraPath path = starnt::parseCameraPathSpec(spec, bounds, aspect);
            for (int i = 0; i < 5; ++i) {
                const starnt::Camera c = path.frame(i, 5);
                checkFinite(c.view());
                checkFinite(c.projection(aspect));
            }
        }
    });
    return 0;
}
