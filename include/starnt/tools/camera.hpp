// Cameras: auto-framing on scene bounds, orbit specs and JSON camera files (docs/USAGE.md, "Command line").
#pragma once
#include <string>

#include <glm/glm.hpp>

#include "starnt/tools/scene.hpp"

namespace starnt {

struct Camera {
    glm::vec3 position{0.0f, 0.0f, 3.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDeg = 45.0f;
    float nearPlane = 0.01f;
    float farPlane = 100.0f;

    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;  // OpenGL clip space (z in [-1, 1])
};

// Orbit around the bounds' centre: azimuth about +Y starting on the +Z axis, elevation above the
// XZ plane, distance chosen so the bounding sphere fits the smaller field of view; near/far hug the
// sphere.
Camera orbitCamera(const Bounds& bounds, float azimuthDeg, float elevationDeg, float aspect, float fovYDeg = 45.0f);

// Sets cam's near and far planes to hug the bounds' sphere seen from cam.position (near at least
// 1e-4 of far; a depth range even where the camera is so far away that the sphere rounds away).
void fitClipPlanes(Camera& cam, const Bounds& bounds);

// The default camera: orbitCamera(bounds, 0, 15, aspect).
Camera autoFrameCamera(const Bounds& bounds, float aspect);

// "orbit:DEG[,ELEV]" or a path to a JSON camera file ({"position", "target", "up", "fov_y_deg",
// "near", "far"}; up, fov and near/far optional). An empty spec gives autoFrameCamera. Throws
// starnt::Error on a malformed spec or file.
Camera parseCameraSpec(const std::string& spec, const Bounds& bounds, float aspect);

}  // namespace starnt
