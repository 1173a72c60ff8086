#include "starnt/tools/camera.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "starnt/error.hpp"

namespace starnt {
namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 readVec3(const nlohmann::json& j, const char* key, const std::string& path) {
    const auto& v = j.at(key);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number()) {
        throw Error("camera file " + path + ": '" + key + "' must be an array of 3 numbers");
    }
    glm::vec3 out(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
    if (!finite3(out)) throw Error("camera file " + path + ": '" + key + "' is not finite");
    // Beyond this, lengths and products of coordinates overflow float (a position at 1e20 read as a
    // view direction of length 0, reported as 'up' parallel to it).
    if (std::max({std::fabs(out.x), std::fabs(out.y), std::fabs(out.z)}) > float(kMaxSceneCoordinate))
        throw Error("camera file " + path + ": '" + key + "' is beyond the supported range (|coordinate| <= 1e18)");
    return out;
}

}  // namespace

void fitClipPlanes(Camera& cam, const Bounds& bounds) {
    const float r = std::max(bounds.radius(), 1e-6f);
    const float d = glm::length(cam.position - bounds.center());
    cam.farPlane = d + r * 1.05f;
    cam.nearPlane = std::max(d - r * 1.05f, cam.farPlane * 1e-4f);
    // So far away that d +- r rounds to d in float (a camera 1e18 from a scene of size 1): keep a
    // depth range all the same, for a frame with nothing in it rather than a projection that maps
    // every depth to one value.
    cam.nearPlane = std::min(cam.nearPlane, cam.farPlane * 0.999f);
}

glm::mat4 Camera::view() const { return glm::lookAt(position, target, up); }

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fovYDeg), aspect, nearPlane, farPlane);
}

Camera orbitCamera(const Bounds& bounds, float azimuthDeg, float elevationDeg, float aspect, float fovYDeg) {
    Camera cam;
    cam.fovYDeg = fovYDeg;
    const float r = std::max(bounds.radius(), 1e-6f);
    const float halfY = glm::radians(fovYDeg) * 0.5f;
    const float halfX = std::atan(std::tan(halfY) * aspect);
    const float distance = r / std::sin(std::min(halfX, halfY)) * 1.02f;
    const float az = glm::radians(azimuthDeg), el = glm::radians(elevationDeg);
    const glm::vec3 dir(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    cam.target = bounds.center();
    cam.position = cam.target + dir * distance;
    cam.up = std::abs(el) > glm::radians(89.0f) ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    fitClipPlanes(cam, bounds);
    return cam;
}

Camera autoFrameCamera(const Bounds& bounds, float aspect) { return orbitCamera(bounds, 0.0f, 15.0f, aspect); }

Camera parseCameraSpec(const std::string& spec, const Bounds& bounds, float aspect) {
    if (spec.empty() || spec == "auto") return autoFrameCamera(bounds, aspect);
    if (spec.rfind("orbit:", 0) == 0) {
        std::string args = spec.substr(6);
        float az = 0.0f, el = 15.0f;
        char extra = 0;
        std::istringstream in(args);
        if (!(in >> az)) throw Error("bad camera '" + spec + "': expected orbit:DEG[,ELEV]");
        if (in.peek() == ',') {
            in.get();
            if (!(in >> el)) throw Error("bad camera '" + spec + "': expected orbit:DEG[,ELEV]");
        }
        if (in >> extra) throw Error("bad camera '" + spec + "': expected orbit:DEG[,ELEV]");
        if (!std::isfinite(az) || !std::isfinite(el) || el < -90.0f || el > 90.0f) {
            throw Error("bad camera '" + spec + "': elevation must be within -90..90 degrees");
        }
        return orbitCamera(bounds, az, el, aspect);
    }
    // A directory opens as a stream but fails inside the JSON reader with std::ios_failure
    // (found by fuzz/fuzz_camera): refuse it here with a message.
    std::error_code ec;
    if (std::filesystem::is_directory(spec, ec)) throw Error("camera file '" + spec + "' is a directory");
    std::ifstream file(spec);
    if (!file) throw Error("cannot open camera file '" + spec + "' (expected orbit:DEG[,ELEV] or a .json file)");
    nlohmann::json j;
    try {
        file >> j;
        Camera cam;
        cam.position = readVec3(j, "position", spec);
        cam.target = readVec3(j, "target", spec);
        if (j.contains("up")) cam.up = readVec3(j, "up", spec);
        if (j.contains("fov_y_deg")) cam.fovYDeg = j.at("fov_y_deg").get<float>();
        if (!(cam.fovYDeg > 0.5f && cam.fovYDeg < 179.0f)) throw Error("camera file " + spec + ": fov_y_deg must be in (0.5, 179)");
        if (glm::length(cam.position - cam.target) < 1e-9f) throw Error("camera file " + spec + ": position equals target");
        auto text = [](const glm::vec3& v) {
            std::ostringstream s;
            s << "[" << v.x << ", " << v.y << ", " << v.z << "]";
            return s.str();
        };
        if (!(glm::length(cam.up) > 1e-12f)) {
            throw Error("camera file " + spec + ": 'up' " + text(cam.up) + " is a zero vector (e.g. use [0, 1, 0])");
        }
        const glm::vec3 viewDir = glm::normalize(cam.target - cam.position);
        if (glm::length(glm::cross(viewDir, glm::normalize(cam.up))) < 1e-4f) {
            throw Error("camera file " + spec + ": 'up' " + text(cam.up) +
                        " is parallel to the view direction from 'position' to 'target' " + text(viewDir) +
                        " (choose an 'up' across the view)");
        }
        fitClipPlanes(cam, bounds);
        if (j.contains("near")) cam.nearPlane = j.at("near").get<float>();
        if (j.contains("far")) cam.farPlane = j.at("far").get<float>();
        if (!(cam.nearPlane > 0.0f) || !(cam.farPlane > cam.nearPlane) || !std::isfinite(cam.farPlane)) {
            throw Error("camera file " + spec + ": need 0 < near < far");
        }
        return cam;
    } catch (const nlohmann::json::exception& e) {
        throw Error("camera file " + spec + " is not a valid camera: " + e.what());
    }
}

}  // namespace starnt
