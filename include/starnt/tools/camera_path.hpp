// Camera paths for sequences (docs/DESIGN.md, "Temporal reprojection"): an orbit, or smooth interpolation through JSON
// keyframes.
#pragma once
#include <string>
#include <vector>

#include "starnt/tools/camera.hpp"

namespace starnt {

struct CameraKey {
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f};
    float fovYDeg = 45.0f;
};

class CameraPath {
public:
    // Orbit around the bounds from startDeg to endDeg (azimuth, as orbitCamera) at one elevation.
    static CameraPath orbit(const Bounds& bounds, float startDeg, float endDeg, float elevationDeg, float aspect);
    // Keys are passed through at equal parameter spacing; positions and targets follow a
    // Catmull-Rom spline (end keys repeated), the field of view is interpolated linearly. At least
    // two keys; throws starnt::Error otherwise, its message starting with `source` (the file the
    // keys came from, for one).
    static CameraPath keyframes(std::vector<CameraKey> keys, const Bounds& bounds, glm::vec3 up = {0, 1, 0},
                                const std::string& source = "camera path");

    // t in [0, 1] (clamped).
    Camera at(double t) const;
    // Camera of frame `index` of a `frames`-frame sequence: t = index / (frames - 1) (t = 0 for one frame).
    Camera frame(int index, int frames) const;

private:
    enum class Kind { Orbit, Keys } kind_ = Kind::Orbit;
    Bounds bounds_;
    float aspect_ = 1.0f, startDeg_ = 0.0f, endDeg_ = 0.0f, elevationDeg_ = 15.0f;
    std::vector<CameraKey> keys_;
    glm::vec3 up_{0, 1, 0};
};

// "orbit:START,END[,ELEV]" (degrees; elevation default 15) or a JSON keyframe file:
//   {"keys": [{"position": [x,y,z], "target": [x,y,z], "fov_y_deg": 45}, ...], "up": [0,1,0]}
// (fov_y_deg and up optional). Throws starnt::Error on malformed specs, unreadable files, fewer than
// two keys or non-finite values.
CameraPath parseCameraPathSpec(const std::string& spec, const Bounds& bounds, float aspect);

}  // namespace starnt
