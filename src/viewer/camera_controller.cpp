#include "viewer/camera_controller.hpp"

#include <algorithm>
#include <cmath>

namespace starnt::viewer {
namespace {

float sceneRadius(const Bounds& b) { return std::max(b.radius(), 1e-6f); }

// Unit view direction of a yaw (about +Y, 0 looks down -Z) and pitch (up positive), in degrees.
glm::vec3 directionOf(float yawDeg, float pitchDeg) {
    const float yaw = glm::radians(yawDeg), pitch = glm::radians(pitchDeg);
    return {-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

}  // namespace

void CameraController::reset(const Bounds& bounds, float aspect) {
    bounds_ = bounds;
    aspect_ = aspect;
    mode_ = CameraMode::Orbit;
    azimuthDeg_ = 0.0f;
    elevationDeg_ = 15.0f;  // autoFrameCamera's elevation
    zoom_ = 1.0f;
    panOffset_ = glm::vec3(0.0f);
    flySpeedScale_ = 1.0f;
}

void CameraController::setMode(CameraMode mode) {
    if (mode == mode_) return;
    const Camera current = camera();
    if (mode == CameraMode::Fly) {
        const glm::vec3 dir = glm::normalize(current.target - current.position);
        flyPosition_ = current.position;
        pitchDeg_ = glm::degrees(std::asin(std::clamp(dir.y, -1.0f, 1.0f)));
        yawDeg_ = glm::degrees(std::atan2(-dir.x, -dir.z));
    } else {
        // Orbit around the scene centre from the direction the fly camera is at; keep its distance.
        const glm::vec3 fromCentre = flyPosition_ - bounds_.center();
        const float distance = glm::length(fromCentre);
        if (distance > 1e-6f) {
            const glm::vec3 dir = fromCentre / distance;
            elevationDeg_ = std::clamp(glm::degrees(std::asin(std::clamp(dir.y, -1.0f, 1.0f))), -89.0f, 89.0f);
            azimuthDeg_ = glm::degrees(std::atan2(dir.x, dir.z));
            const float framed = glm::length(orbitCamera(bounds_, 0, 0, aspect_).position - bounds_.center());
            zoom_ = std::clamp(distance / framed, 0.05f, 20.0f);
        }
        panOffset_ = glm::vec3(0.0f);
    }
    mode_ = mode;
}

void CameraController::setOrbit(float azimuthDeg, float elevationDeg) {
    if (mode_ != CameraMode::Orbit) setMode(CameraMode::Orbit);
    azimuthDeg_ = azimuthDeg;
    elevationDeg_ = std::clamp(elevationDeg, -90.0f, 90.0f);
}

void CameraController::rotate(float dxPixels, float dyPixels) {
    if (mode_ == CameraMode::Orbit) {
        // Dragging right moves the camera to the left around the scene, i.e. the scene turns right.
        azimuthDeg_ = std::fmod(azimuthDeg_ - dxPixels * kDegreesPerPixel, 360.0f);
        elevationDeg_ = std::clamp(elevationDeg_ + dyPixels * kDegreesPerPixel, -89.0f, 89.0f);
    } else {
        yawDeg_ = std::fmod(yawDeg_ - dxPixels * kDegreesPerPixel, 360.0f);
        pitchDeg_ = std::clamp(pitchDeg_ - dyPixels * kDegreesPerPixel, -89.0f, 89.0f);
    }
}

void CameraController::pan(float dxPixels, float dyPixels, float viewportHeight) {
    if (mode_ != CameraMode::Orbit || viewportHeight <= 0.0f) return;
    const Camera cam = camera();
    const glm::vec3 forward = glm::normalize(cam.target - cam.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, cam.up));
    const glm::vec3 up = glm::cross(right, forward);
    // World units per pixel at the target's distance, so the point under the cursor follows it.
    const float distance = glm::length(cam.target - cam.position);
    const float unitsPerPixel = 2.0f * distance * std::tan(glm::radians(cam.fovYDeg) * 0.5f) / viewportHeight;
    panOffset_ += (-dxPixels * right + dyPixels * up) * unitsPerPixel;
}

void CameraController::scroll(float steps) {
    if (mode_ == CameraMode::Orbit) zoom_ = std::clamp(zoom_ * std::pow(0.9f, steps), 0.05f, 20.0f);
    else flySpeedScale_ = std::clamp(flySpeedScale_ * std::pow(1.25f, steps), 0.01f, 100.0f);
}

void CameraController::fly(const FlyInput& input, float seconds) {
    if (mode_ != CameraMode::Fly) return;
    // Half the scene's diameter per second at speed scale 1: crosses a scene in about two seconds.
    const float speed = sceneRadius(bounds_) * flySpeedScale_ * (input.fast ? 4.0f : 1.0f);
    const glm::vec3 forward = directionOf(yawDeg_, pitchDeg_);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    flyPosition_ += (input.forward * forward + input.right * right + input.up * glm::vec3(0, 1, 0)) * speed * seconds;
}

Camera CameraController::flyCamera() const {
    Camera cam;
    cam.position = flyPosition_;
    cam.target = flyPosition_ + directionOf(yawDeg_, pitchDeg_);
    cam.up = glm::vec3(0, 1, 0);
    // Clip planes cover the whole scene from wherever the camera is, inside or outside it.
    const float r = sceneRadius(bounds_);
    cam.farPlane = glm::length(flyPosition_ - bounds_.center()) + r * 1.05f;
    cam.nearPlane = std::max(r * 1e-3f, cam.farPlane * 1e-4f);
    return cam;
}

Camera CameraController::camera() const {
    if (mode_ == CameraMode::Fly) return flyCamera();
    // Start from the headless orbit camera so that, without zoom and pan, the viewer and
    // `starnt render --camera orbit:AZ,EL` see exactly the same thing.
    Camera cam = orbitCamera(bounds_, azimuthDeg_, elevationDeg_, aspect_);
    if (zoom_ == 1.0f && panOffset_ == glm::vec3(0.0f)) return cam;
    const glm::vec3 offset = (cam.position - cam.target) * zoom_;
    cam.target += panOffset_;
    cam.position = cam.target + offset;
    const float r = sceneRadius(bounds_);
    const float d = glm::length(cam.position - bounds_.center());
    cam.farPlane = d + r * 1.05f;
    cam.nearPlane = std::max(d - r * 1.05f, cam.farPlane * 1e-4f);
    return cam;
}

}  // namespace starnt::viewer
