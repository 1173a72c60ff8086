// Camera paths for sequences (include/starnt/tools/camera_path.hpp): orbit endpoints, keyframes passed
// through, and clear errors for bad specs and files.
#include <gtest/gtest.h>

#include <fstream>

#include "starnt/tools/camera_path.hpp"
#include "starnt/error.hpp"
#include "test_support.hpp"

using namespace starnt;
namespace fs = std::filesystem;

namespace {

const Bounds kBounds{glm::vec3(-1.0f, -0.5f, -2.0f), glm::vec3(3.0f, 1.5f, 0.0f)};

void expectSameCamera(const Camera& a, const Camera& b, float tolerance, const std::string& what) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.position[i], b.position[i], tolerance) << what << " position " << i;
        EXPECT_NEAR(a.target[i], b.target[i], tolerance) << what << " target " << i;
    }
    EXPECT_NEAR(a.fovYDeg, b.fovYDeg, tolerance) << what;
}

// Writes `text` to a fresh file and returns its path.
std::string writeFile(const std::string& name, const std::string& text) {
    const fs::path path = test::makeTempDir("camera_path") / name;
    std::ofstream(path) << text;
    return path.string();
}

// parseCameraPathSpec must throw starnt::Error whose message contains `mentions`.
void expectError(const std::string& spec, const std::string& mentions) {
    try {
        parseCameraPathSpec(spec, kBounds, 1.5f);
        ADD_FAILURE() << "accepted: " << spec;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << "message: " << e.what();
    }
}

const char* kTwoKeys = R"({"keys": [
  {"position": [0, 1, 5], "target": [0, 0, 0], "fov_y_deg": 40},
  {"position": [5, 1, 0], "target": [1, 0, 0], "fov_y_deg": 60}]})";

}  // namespace

TEST(CameraPath, OrbitEndpointsAreOrbitCameras) {
    const CameraPath path = parseCameraPathSpec("orbit:10,100,20", kBounds, 1.5f);
    expectSameCamera(path.frame(0, 5), orbitCamera(kBounds, 10.0f, 20.0f, 1.5f), 1e-5f, "start");
    expectSameCamera(path.frame(4, 5), orbitCamera(kBounds, 100.0f, 20.0f, 1.5f), 1e-5f, "end");
    expectSameCamera(path.frame(2, 5), orbitCamera(kBounds, 55.0f, 20.0f, 1.5f), 1e-5f, "middle");
    // One frame: the start. Default elevation 15.
    expectSameCamera(parseCameraPathSpec("orbit:0,90", kBounds, 1.5f).frame(0, 1),
                     orbitCamera(kBounds, 0.0f, 15.0f, 1.5f), 1e-5f, "single frame");
    // t is clamped.
    expectSameCamera(path.at(7.0), path.at(1.0), 0.0f, "clamped");
}

TEST(CameraPath, KeyframesArePassedThrough) {
    std::vector<CameraKey> keys = {{{0, 1, 5}, {0, 0, 0}, 40.0f},
                                   {{5, 1, 0}, {1, 0, 0}, 60.0f},
                                   {{0, 2, -5}, {0, 1, 0}, 50.0f},
                                   {{-4, 0, 1}, {0, 0, 1}, 45.0f}};
    const CameraPath path = CameraPath::keyframes(keys, kBounds);
    for (size_t i = 0; i < keys.size(); ++i) {
        Camera want;
        want.position = keys[i].position;
        want.target = keys[i].target;
        want.fovYDeg = keys[i].fovYDeg;
        // Key i of 4 at t = i / 3: frame i of a 4-frame sequence, and frame 2i of a 7-frame one.
        expectSameCamera(path.frame(int(i), 4), want, 1e-5f, "key " + std::to_string(i));
        expectSameCamera(path.frame(int(2 * i), 7), want, 1e-5f, "key " + std::to_string(i) + " of 7 frames");
    }
    // Between keys the path moves smoothly: the midpoint differs from both neighbours.
    const Camera mid = path.at(0.5 / 3.0);
    EXPECT_GT(glm::length(mid.position - keys[0].position), 0.5f);
    EXPECT_GT(glm::length(mid.position - keys[1].position), 0.5f);
    EXPECT_NEAR(mid.fovYDeg, 50.0f, 1e-4f);  // linear in fov
    // Near/far hug the bounds as seen from the path.
    EXPECT_GT(mid.farPlane, mid.nearPlane);
    EXPECT_GT(mid.nearPlane, 0.0f);
}

TEST(CameraPath, JsonFileWithUpAndDefaults) {
    const std::string file = writeFile("path.json", R"({"up": [0, 0, 1], "keys": [
        {"position": [0, 5, 1], "target": [0, 0, 0]},
        {"position": [5, 0, 1], "target": [0, 0, 0], "fov_y_deg": 30}]})");
    const CameraPath path = parseCameraPathSpec(file, kBounds, 1.0f);
    const Camera start = path.frame(0, 2), end = path.frame(1, 2);
    EXPECT_EQ(start.up, glm::vec3(0, 0, 1));
    EXPECT_NEAR(start.fovYDeg, 45.0f, 1e-6f);  // default
    EXPECT_NEAR(end.fovYDeg, 30.0f, 1e-6f);
    EXPECT_NEAR(end.position.x, 5.0f, 1e-5f);
}

TEST(CameraPath, BadSpecsAndFilesGiveClearErrors) {
    expectError("orbit:abc", "orbit:START,END");
    expectError("orbit:10", "orbit:START,END");
    expectError("orbit:10,20,30,40", "orbit:START,END");
    expectError("orbit:0,90,95", "elevation");
    expectError("/nonexistent/path.json", "cannot open camera path");
    expectError(writeFile("broken.json", R"({"keys": [ {"position": [0, 1)"), "not valid JSON");
    expectError(writeFile("nokeys.json", R"({"frames": []})"), "'keys' array");
    expectError(writeFile("one.json", R"({"keys": [{"position": [0, 1, 5], "target": [0, 0, 0]}]})"), "at least two keys");
    expectError(writeFile("one.json", R"({"keys": [{"position": [0, 1, 5], "target": [0, 0, 0]}]})"), "one.json needs at least two keys");
    expectError(writeFile("upview.json", R"({"keys": [{"position": [0, 5, 0], "target": [0, 0, 0]}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "upview.json key 0: 'up' is parallel");
    expectError(writeFile("zero.json", R"({"keys": []})"), "at least two keys");
    expectError(writeFile("notarget.json", R"({"keys": [{"position": [0, 1, 5]}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "missing 'target'");
    expectError(writeFile("short.json", R"({"keys": [{"position": [0, 1], "target": [0, 0, 0]}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "array of 3 numbers");
    // JSON has no NaN literal; a value too large for a float becomes infinite.
    expectError(writeFile("huge.json", R"({"keys": [{"position": [1e60, 1, 5], "target": [0, 0, 0]}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "not finite");
    expectError(writeFile("fov.json", R"({"keys": [{"position": [0, 1, 5], "target": [0, 0, 0], "fov_y_deg": "wide"}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "fov_y_deg");
    // Looking straight along 'up'.
    expectError(writeFile("up.json", R"({"keys": [{"position": [0, 5, 0], "target": [0, 0, 0]}, {"position": [1, 1, 5], "target": [0, 0, 0]}]})"),
                "parallel");
    expectError(writeFile("upzero.json", std::string(kTwoKeys).replace(1, 0, R"("up": [0, 0, 0], )")), "'up'");
    EXPECT_THROW(CameraPath::keyframes({}, kBounds), Error);
}

// Coordinates beyond 1e18 overflow float in the lengths the checks take: a camera at 1e20 read as a
// zero view direction and was reported as 'up' parallel to it. Now the coordinate is named.
TEST(CameraPath, CoordinatesBeyondTheSceneRangeAreNamed) {
    expectError(writeFile("far_key.json", R"({"keys": [
  {"position": [1e20, 0, 0], "target": [0, 0, 0]},
  {"position": [5, 1, 0], "target": [1, 0, 0]}]})"),
                "'position' is beyond the supported range");
    try {
        parseCameraSpec(writeFile("far_camera.json", R"({"position": [0, 0, 1e20], "target": [0, 0, 0]})"), kBounds, 1.5f);
        ADD_FAILURE() << "accepted a camera at 1e20";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'position' is beyond the supported range"), std::string::npos) << e.what();
    }
}

// A key so far from the scene that its sphere rounds away in float (1e18 from a scene of size 1,
// within the coordinate limit): a depth range all the same, not near == far (every depth one value).
TEST(CameraPath, AKeyFarBeyondTheSceneKeepsADepthRange) {
    std::vector<CameraKey> keys(2);
    keys[0].position = {1e18f, 0.0f, 3.0f};
    keys[1].position = {0.0f, 0.0f, 3.0f};
    const CameraPath path = CameraPath::keyframes(keys, kBounds);
    for (double t : {0.0, 0.5}) {
        const Camera c = path.at(t);
        EXPECT_GT(c.nearPlane, 0.0f) << t;
        EXPECT_LT(c.nearPlane, c.farPlane) << t;
        const glm::mat4 p = c.projection(1.5f);
        auto ndc = [&](float d) { const glm::vec4 v = p * glm::vec4(0.0f, 0.0f, -d, 1.0f); return v.z / v.w; };
        EXPECT_NE(ndc(c.nearPlane), ndc(c.farPlane)) << t;
    }
}
