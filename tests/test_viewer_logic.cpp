// The viewer's window-free parts: script parsing, live settings, the camera controller, timing
// statistics and the scene list.
#include <gtest/gtest.h>

#include <fstream>

#include "starnt/error.hpp"
#include "test_support.hpp"
#include "viewer/camera_controller.hpp"
#include "viewer/frame_time_medians.hpp"
#include "viewer/scene_catalog.hpp"
#include "viewer/viewer_script.hpp"
#include "viewer/viewer_settings.hpp"

using namespace starnt;
using namespace starnt::viewer;

namespace {

Bounds unitBounds() {
    Bounds b;
    b.min = glm::vec3(-1.0f, -0.5f, -2.0f);
    b.max = glm::vec3(1.0f, 1.5f, 0.0f);
    return b;
}

void expectSameCamera(const Camera& a, const Camera& b, float tolerance = 0.0f) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.position[i], b.position[i], tolerance) << "position " << i;
        EXPECT_NEAR(a.target[i], b.target[i], tolerance) << "target " << i;
    }
    EXPECT_NEAR(a.nearPlane, b.nearPlane, tolerance);
    EXPECT_NEAR(a.farPlane, b.farPlane, tolerance);
}

std::string errorOf(const std::string& script) {
    try {
        parseScript(script);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ViewerScript, ParsesCommandsSeparatorsAndComments) {
    const auto s = parseScript("frames 5; orbit 30 -10\n# a comment line\nmethod wboit # trailing\n\nscreenshot a.png ui;quit");
    ASSERT_EQ(s.size(), 5u);
    EXPECT_EQ(s[0].verb, "frames");
    EXPECT_EQ(s[0].frames, 5);
    EXPECT_EQ(s[1].verb, "orbit");
    ASSERT_EQ(s[1].numbers.size(), 2u);
    EXPECT_EQ(s[1].numbers[0], 30.0f);
    EXPECT_EQ(s[1].numbers[1], -10.0f);
    EXPECT_EQ(s[2].args, std::vector<std::string>{"wboit"});
    EXPECT_EQ(s[3].args, (std::vector<std::string>{"a.png", "ui"}));
    EXPECT_EQ(s[4].verb, "quit");
    EXPECT_TRUE(parseScript("  ;\n ; ").empty());
}

TEST(ViewerScript, RejectsBadCommandsNamingThem) {
    EXPECT_NE(errorOf("frames 2; zoom 3").find("unknown command 'zoom'"), std::string::npos);
    EXPECT_NE(errorOf("orbit 30").find("'orbit 30'"), std::string::npos);
    EXPECT_NE(errorOf("orbit 30 x").find("'x' is not a number"), std::string::npos);
    EXPECT_NE(errorOf("orbit 30 95").find("elevation"), std::string::npos);
    EXPECT_NE(errorOf("frames 0").find("1..100000"), std::string::npos);
    EXPECT_NE(errorOf("frames 2.5").find("whole number"), std::string::npos);
    EXPECT_NE(errorOf("screenshot a.jpg").find(".png"), std::string::npos);
    EXPECT_NE(errorOf("screenshot a.png all").find("[ui]"), std::string::npos);
    EXPECT_NE(errorOf("method nosuch").find("unknown method"), std::string::npos);
    EXPECT_NE(errorOf("temporal 9").find("1..8"), std::string::npos);
    EXPECT_NE(errorOf("scales 10,50").find("25..100"), std::string::npos);
    EXPECT_NE(errorOf("fly 2 0 0 1").find("-1..1"), std::string::npos);
    EXPECT_NE(errorOf("quit now").find("quit"), std::string::npos);
    EXPECT_EQ(errorOf("fly 1 0 -1 0.5; camera fly; drag 5 5; scroll -2; flip; drop x.glb"), "");
}

TEST(ViewerSettings, SetParsesEverySwitchAndLeavesBadValuesOut) {
    ViewerSettings s;
    s.set("method", "dfaoit");
    s.set("split", "wboit");
    s.set("view", "tiles");
    s.set("alpha", "0.25");
    s.set("background", "0,0.5,1");
    s.set("spatial", "off");
    s.set("scales", "50,25");
    s.set("inference", "corners");
    s.set("temporal", "auto");
    EXPECT_EQ(s.options.neural.temporalMode, NeuralOptions::TemporalMode::Correct) << "the default";
    s.set("temporal-mode", "warp");
    s.set("target-fps", "30");
    EXPECT_EQ(s.method, "dfaoit");
    EXPECT_EQ(s.splitMethod, "wboit");
    EXPECT_EQ(s.view, ViewMode::Tiles);
    EXPECT_EQ(s.alpha, 0.25f);
    EXPECT_EQ(s.background, glm::vec3(0.0f, 0.5f, 1.0f));
    EXPECT_EQ(s.options.neural.spatial, false);
    EXPECT_FLOAT_EQ(s.options.neural.fixedScale2, 0.5f);
    EXPECT_FLOAT_EQ(s.options.neural.fixedScale3, 0.25f);
    EXPECT_EQ(s.options.neural.inference, NeuralOptions::Inference::Corners);
    EXPECT_TRUE(s.options.neural.temporalAuto);
    EXPECT_EQ(s.options.neural.temporalMode, NeuralOptions::TemporalMode::Warp);
    EXPECT_EQ(s.options.neural.targetFps, 30.0);

    const ViewerSettings before = s;
    EXPECT_THROW(s.set("alpha", "1.5"), Error);
    EXPECT_THROW(s.set("background", "1,1"), Error);
    EXPECT_THROW(s.set("split", "nosuch"), Error);
    EXPECT_THROW(s.set("target-fps", "0"), Error);
    EXPECT_THROW(s.set("temporal-mode", "blend"), Error);
    EXPECT_THROW(s.set("colour", "red"), Error);
    EXPECT_FALSE(needsNewMethods(before, s));
    EXPECT_EQ(s.alpha, before.alpha);
    EXPECT_EQ(s.splitMethod, "wboit");
    s.set("split", "off");
    EXPECT_TRUE(s.splitMethod.empty());
    s.set("alpha", "off");
    EXPECT_FALSE(s.alpha.has_value());
}

TEST(ViewerSettings, OnlyMethodAndOptionChangesRebuildMethods) {
    ViewerSettings a;
    ViewerSettings b = a;
    b.set("alpha", "0.3");
    b.set("background", "0,0,0");
    b.set("view", "error");
    EXPECT_FALSE(needsNewMethods(a, b));
    for (auto [key, value] : std::vector<std::pair<const char*, const char*>>{
             {"method", "wboit"}, {"split", "peel"}, {"spatial", "on"}, {"scales", "100,50"},
             {"inference", "corners"}, {"temporal", "3"}, {"temporal-mode", "refresh"}, {"target-fps", "90"}}) {
        ViewerSettings c = a;
        c.set(key, value);
        EXPECT_TRUE(needsNewMethods(a, c)) << key;
    }
}

TEST(ViewerCamera, OrbitMatchesTheHeadlessCameras) {
    CameraController c;
    const float aspect = 16.0f / 9.0f;
    c.reset(unitBounds(), aspect);
    expectSameCamera(c.camera(), autoFrameCamera(unitBounds(), aspect));
    c.setOrbit(30.0f, 10.0f);
    expectSameCamera(c.camera(), orbitCamera(unitBounds(), 30.0f, 10.0f, aspect));
    // A 100-pixel drag to the right turns the azimuth by -30 degrees, up by 10 px raises it by 3.
    c.rotate(100.0f, 10.0f);
    EXPECT_NEAR(c.azimuthDeg(), 0.0f, 1e-4f);
    EXPECT_NEAR(c.elevationDeg(), 13.0f, 1e-4f);
    expectSameCamera(c.camera(), orbitCamera(unitBounds(), 0.0f, 13.0f, aspect), 1e-5f);
}

TEST(ViewerCamera, ZoomAndPanKeepTheSceneInsideTheClipPlanes) {
    CameraController c;
    c.reset(unitBounds(), 1.0f);
    const Camera framed = c.camera();
    const float framedDistance = glm::length(framed.position - framed.target);
    c.scroll(2.0f);  // two wheel steps in: 0.9^2 of the distance
    const Camera zoomed = c.camera();
    EXPECT_NEAR(glm::length(zoomed.position - zoomed.target), framedDistance * 0.81f, 1e-4f);
    const float r = unitBounds().radius();
    const float d = glm::length(zoomed.position - unitBounds().center());
    EXPECT_LE(zoomed.nearPlane, d - r + 1e-4f);
    EXPECT_GE(zoomed.farPlane, d + r);
    // Pan moves target and eye together, perpendicular to the view direction.
    c.pan(50.0f, 0.0f, 500.0f);
    const Camera panned = c.camera();
    const glm::vec3 shift = panned.target - zoomed.target;
    EXPECT_GT(glm::length(shift), 0.01f);
    EXPECT_NEAR(glm::dot(shift, glm::normalize(zoomed.target - zoomed.position)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length((panned.position - zoomed.position) - shift), 0.0f, 1e-5f);
}

TEST(ViewerCamera, FlyKeepsTheViewpointAndMovesAlongTheViewDirection) {
    CameraController c;
    c.reset(unitBounds(), 1.5f);
    c.setOrbit(40.0f, 20.0f);
    const Camera orbit = c.camera();
    c.setMode(CameraMode::Fly);
    const Camera fly = c.camera();
    EXPECT_NEAR(glm::length(fly.position - orbit.position), 0.0f, 1e-5f);
    const glm::vec3 dir = glm::normalize(fly.target - fly.position);
    const glm::vec3 orbitDir = glm::normalize(orbit.target - orbit.position);
    EXPECT_NEAR(glm::dot(dir, orbitDir), 1.0f, 1e-5f);
    // Speed 1 is one scene radius per second: half a second forward moves half a radius.
    c.fly({1.0f, 0.0f, 0.0f, false}, 0.5f);
    const Camera moved = c.camera();
    EXPECT_NEAR(glm::length(moved.position - fly.position), unitBounds().radius() * 0.5f, 1e-4f);
    EXPECT_NEAR(glm::dot(glm::normalize(moved.position - fly.position), dir), 1.0f, 1e-5f);
    // Inside the scene the near plane stays positive and the far plane covers it.
    EXPECT_GT(moved.nearPlane, 0.0f);
    EXPECT_GE(moved.farPlane, glm::length(moved.position - unitBounds().center()) + unitBounds().radius());
    // Back to orbit: around the centre, from where the fly camera is.
    c.setMode(CameraMode::Orbit);
    const Camera back = c.camera();
    EXPECT_NEAR(glm::length(back.position - moved.position), 0.0f, 1e-3f);
    EXPECT_NEAR(glm::length(back.target - unitBounds().center()), 0.0f, 1e-5f);
}

TEST(ViewerStatistics, RunningMedianOverAWindow) {
    RunningMedian m(3);
    EXPECT_EQ(m.median(), 0.0);
    m.add(10.0);
    m.add(1.0);
    EXPECT_EQ(m.median(), 5.5);
    m.add(100.0);
    EXPECT_EQ(m.median(), 10.0);
    m.add(2.0);  // 10 drops out: {1, 100, 2}
    EXPECT_EQ(m.median(), 2.0);
    EXPECT_EQ(m.size(), 3u);

    FrameTimeMedians f;
    f.addFrame(5.0, {{"pass1", 2.0}}, false);
    f.addFrame(50.0, {{"pass1", 20.0}}, true);
    f.addFrame(6.0, {{"pass1", 3.0}}, false);
    EXPECT_EQ(f.frameMedianMs(), 6.0);
    EXPECT_EQ(f.passMedianMs().at("pass1"), 3.0);
    EXPECT_EQ(f.realFrames(), 2);
    EXPECT_EQ(f.interpolatedFrames(), 1);
    EXPECT_EQ(f.frameGraphMs().size(), 3u);
    f.clear();
    EXPECT_EQ(f.realFrames(), 0);
    EXPECT_TRUE(f.passMedianMs().empty());
}

TEST(ViewerScenes, ListsBuiltinsThenSceneFilesSorted) {
    const auto dir = test::makeTempDir("viewer_scenes");
    std::filesystem::create_directories(dir / "b");
    std::ofstream(dir / "b" / "z.glb") << "x";
    std::ofstream(dir / "a.OBJ") << "x";
    std::ofstream(dir / "b" / "notes.md") << "x";
    const auto entries = listScenes(dir.string());
    const size_t builtins = builtinSceneNames().size();
    ASSERT_EQ(entries.size(), builtins + 2);
    EXPECT_EQ(entries[0].spec, "builtin:" + builtinSceneNames()[0]);
    EXPECT_EQ(entries[builtins].label, "a.OBJ");
    EXPECT_EQ(entries[builtins + 1].label, "b/z.glb");
    EXPECT_EQ(entries[builtins + 1].spec, (dir / "b" / "z.glb").string());
    EXPECT_EQ(listScenes((dir / "missing").string()).size(), builtins);
    std::filesystem::remove_all(dir);
}
