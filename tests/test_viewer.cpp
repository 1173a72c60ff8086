// `starnt view` end to end: the real binary under a virtual X display (xvfb-run), driven by
// --script, its screenshots compared with headless renders of the same camera.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "starnt/tools/camera.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

// Screenshots are 8-bit window pixels, the headless reference is rounded to 8 bits by savePng; the
// two sRGB encoders (GLSL in the viewer, C++ in savePng) may round a channel differently by one
// step: (1/255)^2 = 1.5e-5 even if that happened on every channel. Measured: exactly 0 for
// abuffer, peel, wboit and starnt (llvmpipe rasterises the same under GLX and EGL). A different
// method is not far above: starnt against the A-buffer on builtin:tubes at 320x180 is 1.0e-4.
constexpr double kMaxMse = 2e-5;
constexpr int kWidth = 320, kHeight = 180;

struct ProcessResult {
    int exitCode = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

std::string quoted(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

ProcessResult runShell(const std::string& command, const fs::path& dir) {
    const std::string cmd = command + " >" + (dir / "stdout").string() + " 2>" + (dir / "stderr").string();
    const int status = std::system(cmd.c_str());
    ProcessResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir / "stdout");
    r.err = slurp(dir / "stderr");
    return r;
}

bool haveXvfbRun() { return std::system("command -v xvfb-run >/dev/null 2>&1 && command -v Xvfb >/dev/null 2>&1") == 0; }

// `starnt view` at 320x180 on a virtual display with 24-bit colour. The server number search
// starts at a per-process number so parallel runs (other test processes) rarely collide; xvfb-run
// -a then moves on to the next free one.
ProcessResult runViewer(const std::string& args, const std::string& script, const fs::path& dir) {
    const int firstServer = 100 + int(getpid() % 400);
    return runShell("xvfb-run -n " + std::to_string(firstServer) + " -a -s '-screen 0 1024x768x24' " +
                        std::string(STARNT_CLI) + " view --width " + std::to_string(kWidth) + " --height " +
                        std::to_string(kHeight) + " --frames-limit 200 " + args + " --script " + quoted(script),
                    dir);
}

nlohmann::json readJson(const fs::path& p) {
    std::ifstream f(p);
    return nlohmann::json::parse(f);
}

// The headless render (`renderScene`, as `starnt render` does) of the camera a screenshot's stats
// recorded, with the method, alpha and background they name.
starnt::Image headlessRender(const nlohmann::json& stats, const fs::path& dir) {
    starnt::test::glContext();
    const starnt::Scene scene = starnt::loadScene(stats["scene"]);
    const fs::path cameraFile = dir / "camera.json";
    std::ofstream(cameraFile) << stats["camera"].dump();
    starnt::SceneGpu gpu(scene);
    starnt::RenderJob job;
    job.method = stats["method"];
    job.width = stats["width"];
    job.height = stats["height"];
    job.camera = starnt::parseCameraSpec(cameraFile.string(), scene.bounds(), float(job.width) / float(job.height));
    const auto& bg = stats["options"]["background"];
    job.background = glm::vec3(bg[0].get<float>(), bg[1].get<float>(), bg[2].get<float>());
    if (!stats["options"]["alpha"].is_null()) job.surface.alphaOverride = stats["options"]["alpha"].get<float>();
    // Through a PNG, like the screenshot, so both are rounded to 8 bits the same way.
    const fs::path png = dir / "headless.png";
    starnt::saveImage(starnt::renderScene(gpu, job).image, png.string());
    return starnt::loadImage(png.string());
}

// Share of pixels that differ visibly from the top-left pixel (the background there).
double coverage(const starnt::Image& image) {
    const float* corner = image.pixel(0, 0);
    size_t differing = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const float* p = image.pixel(x, y);
            if (std::abs(p[0] - corner[0]) + std::abs(p[1] - corner[1]) + std::abs(p[2] - corner[2]) > 0.02f) ++differing;
        }
    }
    return double(differing) / double(image.pixelCount());
}

#define REQUIRE_VIEWER_AND_XVFB()                                                                               \
    do {                                                                                                        \
        if (!kViewerBuilt) GTEST_SKIP() << "starnt was built without the viewer (STARNT_BUILD_VIEWER=OFF)";     \
        if (!haveXvfbRun()) GTEST_SKIP() << "xvfb-run/Xvfb not installed (apt-get install xvfb xauth): cannot " \
                                            "run the viewer without a display";                                 \
    } while (0)

#ifdef STARNT_HAVE_VIEWER
constexpr bool kViewerBuilt = true;
#else
constexpr bool kViewerBuilt = false;
#endif

}  // namespace

TEST(Viewer, WithoutADisplayExplainsAndPointsToHeadlessCommands) {
    const fs::path dir = starnt::test::makeTempDir("viewer");
    const ProcessResult r = runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(STARNT_CLI) + " view --scene builtin:panes", dir);
    EXPECT_EQ(r.exitCode, 1) << r.err;
    if (kViewerBuilt) EXPECT_NE(r.err.find("needs a display"), std::string::npos) << r.err;
    else EXPECT_NE(r.err.find("built without the viewer"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("starnt render"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

TEST(Viewer, BadScriptIsRejectedBeforeAnyWindowOpens) {
    if (!kViewerBuilt) GTEST_SKIP() << "starnt was built without the viewer";
    const fs::path dir = starnt::test::makeTempDir("viewer");
    // No display on purpose: the script must be refused first, naming the command at fault.
    ProcessResult r = runShell("env -u DISPLAY " + std::string(STARNT_CLI) + " view --script " + quoted("frames 2; orbit 30"), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("'orbit 30'"), std::string::npos) << r.err;
    r = runShell("env -u DISPLAY " + std::string(STARNT_CLI) + " view --script " + quoted("method nosuch"), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("unknown method"), std::string::npos) << r.err;
    r = runShell("env -u DISPLAY " + std::string(STARNT_CLI) + " view --scene builtin:nosuch", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("nosuch"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

// The acceptance test: a few frames, scripted camera input, a screenshot that is not blank
// and equals the headless render of the same camera.
TEST(Viewer, ScriptedScreenshotMatchesHeadlessRender) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    const fs::path shot = dir / "shot.png";
    // The drag goes through the same camera code as the mouse: 100 px right = 30 degrees of azimuth.
    const ProcessResult r = runViewer("--scene builtin:tubes --method abuffer",
                            "frames 3; orbit 60 20; drag 100 0; frames 2; screenshot " + shot.string() + "; quit", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const starnt::Image image = starnt::loadImage(shot.string());
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    EXPECT_GT(coverage(image), 0.05) << "blank screenshot";  // the tube ball covers about 10%

    const nlohmann::json stats = readJson(dir / "shot.json");
    EXPECT_EQ(stats["method"], "abuffer");
    EXPECT_EQ(stats["width"], kWidth);
    EXPECT_GT(stats["frame_ms"].get<double>(), 0.0);
    EXPECT_GT(stats["display_frame_ms"].get<double>(), 0.0);
    EXPECT_GT(stats["pass_ms"].size(), 0u);
    EXPECT_GE(stats["real_frames"].get<int>(), 5);

    // The camera the stats recorded is the orbit camera at azimuth 60 - 30 = 30, elevation 20.
    const starnt::Scene scene = starnt::loadScene("builtin:tubes");
    const starnt::Camera expected = starnt::orbitCamera(scene.bounds(), 30.0f, 20.0f, float(kWidth) / float(kHeight));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(stats["camera"]["position"][i].get<float>(), expected.position[i], 1e-4f);

    const starnt::Image headless = headlessRender(stats, dir);
    EXPECT_LT(starnt::mseSrgb(headless, image), kMaxMse);
    fs::remove_all(dir);
}

// `view --api gles`: a window with an OpenGL ES 3.2 context (GLFW through EGL) shows what the
// desktop headless render of the same camera shows.
TEST(Viewer, EsWindowMatchesTheDesktopHeadlessRender) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    const fs::path shot = dir / "es.png";
    const ProcessResult r = runViewer("--api gles --scene builtin:tubes --method wboit",
                                      "frames 3; orbit 40 15; frames 2; screenshot " + shot.string() + "; quit", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const starnt::Image image = starnt::loadImage(shot.string());
    EXPECT_GT(coverage(image), 0.05) << "blank screenshot";
    const nlohmann::json stats = readJson(dir / "es.json");
    EXPECT_NE(stats["gl_version"].get<std::string>().find("OpenGL ES 3.2"), std::string::npos) << stats["gl_version"];
    EXPECT_EQ(stats["method"], "wboit");
    EXPECT_LT(starnt::mseSrgb(headlessRender(stats, dir), image), kMaxMse);
    fs::remove_all(dir);
}

// Live switches: each screenshot must show what was switched to, equal to the headless render
// with those settings.
TEST(Viewer, LiveSwitchesShowInScreenshotsAndStats) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    auto path = [&](const char* name) { return (dir / name).string(); };
    const std::string script = "frames 2; screenshot " + path("a.png") +
                               "; method wboit; screenshot " + path("b.png") +
                               "; background 0,0,0.2; alpha 0.8; screenshot " + path("c.png") +
                               "; method starnt; spatial on; scales 100,50; inference corners; temporal 2; frames 2; screenshot " +
                               path("d.png") + "; quit";
    const ProcessResult r = runViewer("--scene builtin:panes --method abuffer", script, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;

    const starnt::Image a = starnt::loadImage(path("a.png")), b = starnt::loadImage(path("b.png")),
                        c = starnt::loadImage(path("c.png"));
    EXPECT_EQ(readJson(dir / "a.json")["method"], "abuffer");
    EXPECT_EQ(readJson(dir / "b.json")["method"], "wboit");
    // WBOIT is approximate where panes overlap: the switch must be visible.
    EXPECT_GT(starnt::mseSrgb(a, b), 1e-4);
    for (const char* name : {"a", "b", "c"}) {
        const nlohmann::json stats = readJson(dir / (std::string(name) + ".json"));
        const starnt::Image shot = starnt::loadImage(path((std::string(name) + ".png").c_str()));
        EXPECT_LT(starnt::mseSrgb(headlessRender(stats, dir), shot), kMaxMse) << name;
    }
    // The dark-blue background shows in the corner.
    EXPECT_LT(c.pixel(0, 0)[0], 0.01f);
    EXPECT_NEAR(c.pixel(0, 0)[2], 0.2f, 0.01f);

    const nlohmann::json d = readJson(dir / "d.json");
    EXPECT_EQ(d["method"], "starnt");
    EXPECT_EQ(d["options"]["spatial"], "on");
    EXPECT_EQ(d["options"]["scales"], "100,50");
    EXPECT_EQ(d["options"]["inference"], "corners");
    EXPECT_EQ(d["options"]["temporal"], "2");
    EXPECT_EQ(d["method_stats"]["temporal_mode"], "correct") << "the default interpolated frames";
    EXPECT_GT(coverage(starnt::loadImage(path("d.png"))), 0.05);
    fs::remove_all(dir);
}

TEST(Viewer, SplitScreenAndFlipErrorView) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    auto path = [&](const char* name) { return (dir / name).string(); };
    const ProcessResult r = runViewer("--scene builtin:panes --method abuffer",
                            "split wboit; frames 2; screenshot " + path("split.png") + "; split off; view error; screenshot " +
                                path("same.png") + "; method wboit; flip; screenshot " + path("wboit.png") + "; quit",
                            dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // Split: the left half is the A-buffer, the right half WBOIT, a divider between.
    const starnt::Image split = starnt::loadImage(path("split.png"));
    const starnt::Image abuffer = headlessRender(readJson(dir / "split.json"), dir);
    nlohmann::json wboitStats = readJson(dir / "split.json");
    wboitStats["method"] = "wboit";
    const starnt::Image wboit = headlessRender(wboitStats, dir);
    double leftErr = 0, rightErr = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (std::abs(x - kWidth / 2) <= 1) continue;  // the divider
            const starnt::Image& expected = x < kWidth / 2 ? abuffer : wboit;
            double& err = x < kWidth / 2 ? leftErr : rightErr;
            for (int ch = 0; ch < 3; ++ch) {
                const double d = starnt::linearToSrgb(split.pixel(x, y)[ch]) - starnt::linearToSrgb(expected.pixel(x, y)[ch]);
                err += d * d;
            }
        }
    }
    EXPECT_LT(leftErr / (kWidth * kHeight * 1.5), kMaxMse);
    EXPECT_LT(rightErr / (kWidth * kHeight * 1.5), kMaxMse);

    // Switching to the error view computes a map; `flip` computes a new one. FLIP of the A-buffer
    // against itself is zero; WBOIT's is not, and the heatmap is shown.
    const nlohmann::json same = readJson(dir / "same.json"), other = readJson(dir / "wboit.json");
    EXPECT_EQ(same["view"], "error");
    ASSERT_TRUE(same.contains("error")) << same.dump();
    EXPECT_EQ(same["error"]["flip"].get<double>(), 0.0);
    ASSERT_TRUE(other.contains("error")) << other.dump();
    EXPECT_GT(other["error"]["flip"].get<double>(), 0.001);
    EXPECT_LT(other["error"]["flip"].get<double>(), 1.0);
    // The magma map of a zero error is black everywhere, not the scene.
    const starnt::Image sameShot = starnt::loadImage(path("same.png"));
    EXPECT_LT(sameShot.pixel(kWidth / 2, kHeight / 2)[0] + sameShot.pixel(0, 0)[0], 0.02f);
    fs::remove_all(dir);
}

// A screenshot that cannot be written: the window shows the error and goes on, and the command
// exits non-zero when it closes, so that a scripted run does not lose an output silently.
TEST(Viewer, AScreenshotThatCannotBeWrittenFailsTheCommand) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    const std::string good = (dir / "good.png").string();
    const ProcessResult r = runViewer("--scene builtin:panes --method wboit",
                                      "frames 2; screenshot " + (dir / "missing" / "a.png").string() + "; frames 1; screenshot " +
                                          good + "; quit",
                                      dir);
    EXPECT_NE(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("starnt: error: screenshot " + (dir / "missing" / "a.png").string() + " failed"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(good)) << "the script went on after the failed screenshot";
    fs::remove_all(dir);
}

TEST(Viewer, DroppingAnUnreadableFileShowsTheErrorAndKeepsTheScene) {
    REQUIRE_VIEWER_AND_XVFB();
    const fs::path dir = starnt::test::makeTempDir("viewer");
    std::ofstream(dir / "broken.glb") << "this is not a glTF file";
    auto path = [&](const char* name) { return (dir / name).string(); };
    const ProcessResult r = runViewer("--scene builtin:panes --method wboit",
                            "frames 2; screenshot " + path("before.png") + "; drop " + path("broken.glb") + "; drop " +
                                path("missing.obj") + "; frames 2; screenshot " + path("after.png") +
                                "; scene builtin:tubes; frames 1; screenshot " + path("good.png") + "; quit",
                            dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("broken.glb"), std::string::npos) << r.err;
    const nlohmann::json after = readJson(dir / "after.json");
    EXPECT_EQ(after["scene"], "builtin:panes");
    ASSERT_TRUE(after["last_error"].is_string());
    EXPECT_NE(after["last_error"].get<std::string>().find("missing.obj"), std::string::npos) << after["last_error"];
    EXPECT_EQ(starnt::mseSrgb(starnt::loadImage(path("before.png")), starnt::loadImage(path("after.png"))), 0.0);
    // A good scene afterwards loads and clears the error.
    const nlohmann::json good = readJson(dir / "good.json");
    EXPECT_EQ(good["scene"], "builtin:tubes");
    EXPECT_TRUE(good["last_error"].is_null());
    fs::remove_all(dir);
}
