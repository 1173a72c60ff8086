#include "starnt/tools/camera_path.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "scene/catmull_rom.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

glm::vec3 readVec3(const nlohmann::json& j, const char* key, const std::string& where) {
    if (!j.contains(key)) throw Error(where + ": missing '" + key + "'");
    const auto& v = j.at(key);
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number()) {
        throw Error(where + ": '" + key + "' must be an array of 3 numbers");
    }
    glm::vec3 out(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
    if (!finite3(out)) throw Error(where + ": '" + key + "' is not finite");
    // Beyond this, lengths and products of coordinates overflow float (a position at 1e20 read as a
    // view direction of length 0, reported as 'up' parallel to it).
    if (std::max({std::fabs(out.x), std::fabs(out.y), std::fabs(out.z)}) > float(kMaxSceneCoordinate))
        throw Error(where + ": '" + key + "' is beyond the supported range (|coordinate| <= 1e18)");
    return out;
}

glm::vec3 fallbackUp(const glm::vec3& up) {
    const glm::vec3 a = glm::abs(up);
    const glm::vec3 axis = (a.x <= a.y && a.x <= a.z) ? glm::vec3(1, 0, 0) : (a.y <= a.z ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1));
    return glm::normalize(glm::cross(up, axis));
}

}  // namespace

CameraPath CameraPath::orbit(const Bounds& bounds, float startDeg, float endDeg, float elevationDeg, float aspect) {
    if (!std::isfinite(startDeg) || !std::isfinite(endDeg) || !(elevationDeg >= -90.0f && elevationDeg <= 90.0f)) {
        throw Error("orbit path: angles must be finite and the elevation within -90..90 degrees");
    }
    CameraPath path;
    path.kind_ = Kind::Orbit;
    path.bounds_ = bounds;
    path.aspect_ = aspect;
    path.startDeg_ = startDeg;
    path.endDeg_ = endDeg;
    path.elevationDeg_ = elevationDeg;
    return path;
}

CameraPath CameraPath::keyframes(std::vector<CameraKey> keys, const Bounds& bounds, glm::vec3 up, const std::string& source) {
    if (keys.size() < 2) throw Error(source + " needs at least two keys, got " + std::to_string(keys.size()));
    if (!finite3(up) || glm::length(up) < 1e-6f) throw Error(source + ": 'up' must be a finite non-zero vector");
    for (size_t i = 0; i < keys.size(); ++i) {
        const CameraKey& k = keys[i];
        const std::string where = source + " key " + std::to_string(i);
        if (!finite3(k.position) || !finite3(k.target)) throw Error(where + ": position/target not finite");
        if (glm::length(k.position - k.target) < 1e-9f) throw Error(where + ": position equals target");
        if (!(k.fovYDeg > 0.5f && k.fovYDeg < 179.0f)) throw Error(where + ": fov_y_deg must be in (0.5, 179)");
        if (glm::length(glm::cross(glm::normalize(k.target - k.position), glm::normalize(up))) < 1e-6f) {
            throw Error(where + ": 'up' is parallel to the view direction");
        }
    }
    CameraPath path;
    path.kind_ = Kind::Keys;
    path.bounds_ = bounds;
    path.keys_ = std::move(keys);
    path.up_ = glm::normalize(up);
    return path;
}

Camera CameraPath::at(double t) const {
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    if (kind_ == Kind::Orbit) {
        return orbitCamera(bounds_, float(startDeg_ + (endDeg_ - startDeg_) * t), elevationDeg_, aspect_);
    }
    const int segments = int(keys_.size()) - 1;
    const double x = t * segments;
    const int i = std::min(int(x), segments - 1);
    const float u = float(x - i);
    auto key = [&](int k) { return keys_[size_t(std::clamp(k, 0, segments))]; };
    Camera cam;
    cam.position = catmullRom(key(i - 1).position, key(i).position, key(i + 1).position, key(i + 2).position, u);
    cam.target = catmullRom(key(i - 1).target, key(i).target, key(i + 1).target, key(i + 2).target, u);
    cam.fovYDeg = key(i).fovYDeg + (key(i + 1).fovYDeg - key(i).fovYDeg) * u;
    cam.up = up_;
    if (glm::length(cam.position - cam.target) < 1e-9f) cam.target = cam.position + (key(i + 1).target - key(i + 1).position);
    // Between keys the view can pass straight along 'up' (keys themselves are checked), where lookAt
    // has no defined roll. Such a frame uses a fallback up perpendicular to 'up': cross(up, A) with A
    // the world axis least aligned with 'up' (for up = +Y: -Z, as orbit cameras use at the poles).
    const glm::vec3 dir = cam.target - cam.position;
    if (glm::length(glm::cross(glm::normalize(dir), up_)) < 1e-4f) cam.up = fallbackUp(up_);
    fitClipPlanes(cam, bounds_);
    return cam;
}

Camera CameraPath::frame(int index, int frames) const { return at(frames > 1 ? double(index) / double(frames - 1) : 0.0); }

CameraPath parseCameraPathSpec(const std::string& spec, const Bounds& bounds, float aspect) {
    if (spec.rfind("orbit:", 0) == 0) {
        const std::string usage = "bad camera path '" + spec + "': expected orbit:START,END[,ELEV] in degrees";
        std::istringstream in(spec.substr(6));
        float start = 0, end = 0, elevation = 15.0f;
        char comma = 0, extra = 0;
        if (!(in >> start >> comma >> end) || comma != ',') throw Error(usage);
        if (in.peek() == ',') {
            in.get();
            if (!(in >> elevation)) throw Error(usage);
        }
        if (in >> extra) throw Error(usage);
        return CameraPath::orbit(bounds, start, end, elevation, aspect);
    }
    std::error_code ec;  // a directory would fail inside the JSON reader (fuzz/fuzz_camera)
    if (std::filesystem::is_directory(spec, ec)) throw Error("camera path '" + spec + "' is a directory");
    std::ifstream file(spec);
    if (!file) throw Error("cannot open camera path '" + spec + "' (expected orbit:START,END[,ELEV] or a .json keyframe file)");
    try {
        nlohmann::json j;
        file >> j;
        if (!j.is_object() || !j.contains("keys") || !j["keys"].is_array()) {
            throw Error("camera path " + spec + ": expected an object with a 'keys' array");
        }
        std::vector<CameraKey> keys;
        for (size_t i = 0; i < j["keys"].size(); ++i) {
            const auto& k = j["keys"][i];
            const std::string where = "camera path " + spec + " key " + std::to_string(i);
            if (!k.is_object()) throw Error(where + ": not an object");
            CameraKey key;
            key.position = readVec3(k, "position", where);
            key.target = readVec3(k, "target", where);
            if (k.contains("fov_y_deg")) {
                if (!k["fov_y_deg"].is_number()) throw Error(where + ": 'fov_y_deg' must be a number");
                key.fovYDeg = k["fov_y_deg"].get<float>();
            }
            keys.push_back(key);
        }
        glm::vec3 up(0, 1, 0);
        if (j.contains("up")) up = readVec3(j, "up", "camera path " + spec);
        return CameraPath::keyframes(std::move(keys), bounds, up, "camera path " + spec);
    } catch (const nlohmann::json::exception& e) {
        throw Error("camera path " + spec + " is not valid JSON: " + e.what());
    }
}

}  // namespace starnt
