// OpenGL ES 3.2: `starnt render --api gles` gives the desktop image within 1/255
// for every method, with full-resolution and reduced passes, tiles and both kinds of interpolated
// frame, on built-in and suite scenes; and an ES context that lacks what the methods need fails
// with one clear error. The in-process GPU-vs-CPU tests run on ES too (CTest's Gles.* tests).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "starnt/oit_method.hpp"
#include "starnt/tools/image.hpp"
#include "test_support.hpp"

namespace starnt {
namespace {

namespace fs = std::filesystem;

struct ApiRender {
    Image image;
    nlohmann::json stats;
};

// Renders with `args` through the command line on one API; fails the test when the render fails.
ApiRender renderOn(const std::string& api, const std::string& args, const fs::path& dir, const std::string& tag) {
    const fs::path exr = dir / (tag + "_" + api + ".exr"), png = dir / (tag + "_" + api + ".png"),
                   stats = dir / (tag + "_" + api + ".json");
    const test::CliRun r = test::run("render --api " + api + " " + args + " --out " + png.string() + " --exr " +
                                     exr.string() + " --stats " + stats.string());
    EXPECT_EQ(r.exitCode, 0) << api << " " << args << "\n" << r.err;
    ApiRender out;
    if (r.exitCode != 0) return out;
    out.image = loadImage(exr.string());
    std::ifstream in(stats);
    out.stats = nlohmann::json::parse(in);
    return out;
}

float maxAbsDifference(const Image& a, const Image& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    return worst;
}

// Renders `args` on both APIs and checks the images (within 1/255), the API each ran on, and the
// neural methods' chosen scales and tile histogram (the tiles' decisions, equal on both).
void expectSameOnBothApis(const std::string& args, const std::string& tag) {
    const fs::path dir = test::makeTempDir("gles_" + tag);
    const ApiRender gl = renderOn("gl", args, dir, tag), es = renderOn("gles", args, dir, tag);
    if (gl.image.rgba.empty() || es.image.rgba.empty()) return;
    ASSERT_EQ(gl.image.width, es.image.width);
    ASSERT_EQ(gl.image.height, es.image.height);
    EXPECT_LE(maxAbsDifference(gl.image, es.image), 1.0f / 255.0f) << args;
    EXPECT_EQ(gl.stats.value("gl_api", ""), "gl");
    EXPECT_EQ(es.stats.value("gl_api", ""), "gles");
    EXPECT_NE(es.stats.value("gl_version", "").find("OpenGL ES 3.2"), std::string::npos) << es.stats.value("gl_version", "");
    // Something was drawn: not only the background (white here).
    float darkest = 1.0f;
    for (size_t i = 0; i < es.image.rgba.size(); i += 4) darkest = std::min(darkest, es.image.rgba[i]);
    EXPECT_LT(darkest, 0.9f) << args;
    for (const char* key : {"scale_pass2", "scale_pass3", "tile_levels", "w_bar"}) {
        if (gl.stats.contains(key)) EXPECT_EQ(gl.stats[key], es.stats[key]) << key << " " << args;
    }
    fs::remove_all(dir);
}

const char* const kAllMethods[] = {"abuffer", "peel", "unsorted", "wboit", "mboit", "dfaoit", "starnt", "hybrid", "hybrid-moments", "starnt-d"};

TEST(Gles, EveryMethodMatchesDesktopOnBuiltinScenes) {
    for (const char* scene : {"builtin:tubes", "builtin:panes"}) {
        for (const char* method : kAllMethods) {
            expectSameOnBothApis(std::string("--scene ") + scene + " --method " + method +
                                     " --width 96 --height 64 --frames 2 --camera-path orbit:0,10",
                                 std::string(method) + "_" + (scene + 8));
        }
    }
}

// Reduced passes (fractional viewport, tail resolve from copies on ES), the tiles' corner
// inference, and both interpolated-frame modes.
TEST(Gles, ReducedPassesTilesAndInterpolatedFramesMatchDesktop) {
    const std::string base = "--scene builtin:tubes --width 100 --height 70 --camera-path orbit:0,12 ";
    expectSameOnBothApis(base + "--method starnt --scales 50,25 --frames 3", "scales");
    expectSameOnBothApis(base + "--method dfaoit --spatial on --inference corners --frames 6", "corners");
    expectSameOnBothApis(base + "--method starnt --temporal 2 --temporal-mode refresh --frames 5", "refresh");
    expectSameOnBothApis(base + "--method starnt --temporal 2 --temporal-mode warp --frames 5", "warp");
    expectSameOnBothApis(base + "--method starnt --temporal 2 --temporal-mode correct --frames 5", "correct");
    expectSameOnBothApis(base + "--method starnt --temporal 2 --temporal-mode correct --corrected-passes 2 --frames 5",
                         "correct_two_passes");
}

TEST(Gles, EveryMethodMatchesDesktopOnSuiteScenes) {
    STARNT_SKIP_WITHOUT_SHARED_SCENES("--api gles on a suite scene not tested");
    const fs::path suite = test::sharedScenesDir();
    for (const char* file : {"chess/chess_classic_board.glb", "magic_stars/magic_stars_procedural.glb"}) {
        for (const char* method : kAllMethods) {
            expectSameOnBothApis("--scene " + (suite / file).string() + " --method " + method +
                                     " --width 80 --height 60 --frames 2 --camera-path orbit:30,40",
                                 std::string(method) + "_suite");
        }
    }
}

// ES 3.2 blends 32-bit float targets only with GL_EXT_float_blend, which a phone need not offer.
// Without it the library accepts the context; every method that blends no 32-bit float renders the
// same image bit for bit as with it, and the others fail with one error naming the extension and
// write nothing.
TEST(Gles, WithoutFloatBlendingTheSixteenBitMethodsRunAndTheOthersSaySo) {
    const fs::path dir = test::makeTempDir("gles_no_float_blend");
    const std::vector<std::string> run16 = {"abuffer", "dfaoit", "starnt", "hybrid", "starnt-residual", "kbuffer-moments", "recommended"};
    const std::vector<std::string> need32 = {"unsorted", "wboit", "mboit", "peel", "hybrid-moments", "starnt-d"};
    std::vector<std::string> every = run16;
    every.insert(every.end(), need32.begin(), need32.end());
    for (const std::string& method : methodNames()) {
        EXPECT_NE(std::find(every.begin(), every.end(), method), every.end()) << method << ": in neither list";
    }
    for (const std::string& method : every) {
        const std::string args = "render --api gles --scene builtin:tubes --width 48 --height 32 --frames 2 --method " + method;
        const fs::path with = dir / (method + "_with.exr"), without = dir / (method + "_without.exr");
        ASSERT_EQ(test::run(args + " --out " + (dir / "x.png").string() + " --exr " + with.string()).exitCode, 0) << method;
        const test::CliRun r = test::run(args + " --out " + (dir / (method + ".png")).string() + " --exr " + without.string(),
                                         "MESA_EXTENSION_OVERRIDE=-GL_EXT_float_blend ");
        if (std::find(run16.begin(), run16.end(), method) != run16.end()) {
            ASSERT_EQ(r.exitCode, 0) << method << ": " << r.err;
            const Image a = loadImage(with.string()), b = loadImage(without.string());
            EXPECT_EQ(a.rgba, b.rgba) << method << ": another image without the extension";
        } else {
            EXPECT_NE(r.exitCode, 0) << method;
            EXPECT_NE(r.exitCode, -1) << method << ": crashed";
            EXPECT_NE(r.err.find("GL_EXT_float_blend"), std::string::npos) << method << ": " << r.err;
            EXPECT_FALSE(fs::exists(without)) << method;
        }
    }
}

TEST(Gles, ContextsThatLackWhatTheMethodsNeedFailClearly) {
    const fs::path dir = test::makeTempDir("gles_missing");
    const fs::path out = dir / "x.png";
    const std::string render = "render --api gles --scene builtin:tubes --width 32 --height 32 --method starnt --out " +
                               out.string();
    // Mesa's overrides remove an extension or lower the ES version the driver offers. (Without
    // GL_EXT_float_blend starnt runs: WithoutFloatBlending... below.)
    for (const char* ext : {"GL_EXT_color_buffer_float", "GL_OES_texture_float_linear"}) {
        const test::CliRun r = test::run(render, std::string("MESA_EXTENSION_OVERRIDE=-") + ext + " ");
        EXPECT_NE(r.exitCode, 0) << ext;
        EXPECT_NE(r.exitCode, -1) << ext << ": crashed";
        EXPECT_NE(r.err.find(ext), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("starnt: error:"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    {
        const test::CliRun r = test::run(render, "MESA_GLES_VERSION_OVERRIDE=3.1 ");
        EXPECT_NE(r.exitCode, 0);
        EXPECT_NE(r.exitCode, -1) << "crashed";
        EXPECT_NE(r.err.find("OpenGL ES 3.2"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    {
        // Without OES_viewport_array, full-resolution passes still run; reduced ones say why not.
        const std::string noViewportArray = "MESA_EXTENSION_OVERRIDE=-GL_OES_viewport_array ";
        EXPECT_EQ(test::run(render + " --scales 100,100", noViewportArray).exitCode, 0);
        EXPECT_TRUE(fs::exists(out));
        fs::remove(out);
        const test::CliRun r = test::run(render + " --scales 50,50", noViewportArray);
        EXPECT_NE(r.exitCode, 0);
        EXPECT_NE(r.err.find("GL_OES_viewport_array"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    test::expectCleanFailure("render --api vulkan --scene builtin:tubes --out " + out.string(), out, "--api 'vulkan'");
    test::expectCleanFailure("bench --api metal --out " + (dir / "b").string(), dir / "b", "--api 'metal'");
    fs::remove_all(dir);
}

}  // namespace
}  // namespace starnt
