// The viewer's camera: an orbit mode (rotate around the scene centre, pan, zoom) and a fly mode
// (look around, move with the keyboard). Pure math on starnt::Camera, no window system, so the
// scripted input of `starnt view --script` and the unit tests drive exactly what the mouse does.
#pragma once
#include <glm/glm.hpp>

#include "starnt/tools/camera.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt::viewer {

enum class CameraMode { Orbit, Fly };

// Movement requested by held keys for one frame, each component in [-1, 1].
struct FlyInput {
    float forward = 0.0f;
    float right = 0.0f;
    float up = 0.0f;
    bool fast = false;
};

class CameraController {
public:
    // Degrees of rotation per pixel of mouse drag.
    static constexpr float kDegreesPerPixel = 0.3f;

    // Frames `bounds` exactly like the headless default (autoFrameCamera).
    void reset(const Bounds& bounds, float aspect);
    void setAspect(float aspect) { aspect_ = aspect; }

    CameraMode mode() const { return mode_; }
    // Switching keeps the current viewpoint: fly starts where the orbit camera is, and orbit
    // resumes from the fly camera's direction around the scene centre.
    void setMode(CameraMode mode);

    // Absolute orbit angles in degrees (orbitCamera's convention); leaves zoom and pan alone.
    void setOrbit(float azimuthDeg, float elevationDeg);
    float azimuthDeg() const { return azimuthDeg_; }
    float elevationDeg() const { return elevationDeg_; }

    // Mouse: primary drag rotates (orbit) or looks around (fly); secondary drag pans (orbit only);
    // scroll zooms (orbit) or changes the fly speed.
    void rotate(float dxPixels, float dyPixels);
    void pan(float dxPixels, float dyPixels, float viewportHeight);
    void scroll(float steps);
    // Keyboard movement in fly mode for a frame of `seconds`.
    void fly(const FlyInput& input, float seconds);

    Camera camera() const;

private:
    Camera flyCamera() const;

    CameraMode mode_ = CameraMode::Orbit;
    Bounds bounds_;
    float aspect_ = 16.0f / 9.0f;
    // Orbit state: angles around the bounds' centre, distance multiplier and a pan offset of the target.
    float azimuthDeg_ = 0.0f, elevationDeg_ = 15.0f, zoom_ = 1.0f;
    glm::vec3 panOffset_{0.0f};
    // Fly state.
    glm::vec3 flyPosition_{0.0f};
    float yawDeg_ = 0.0f, pitchDeg_ = 0.0f, flySpeedScale_ = 1.0f;
};

}  // namespace starnt::viewer
