// The real scene suite (../shared/scenes): A-buffer against depth peeling, and every file renders
// with every method family. Skipped with a message when the folder is absent.
#include <gtest/gtest.h>

#include <cmath>

#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/camera.hpp"
#include "test_support.hpp"

using namespace starnt;

namespace {

constexpr int kW = 64, kH = 48;

std::string suitePath(const std::string& relative) {
    auto dir = test::sharedScenesDir();
    return dir.empty() ? std::string() : (dir / relative).string();
}

test::TestScene suiteScene(const std::string& file) {
    return test::TestScene(loadScene(suitePath(file)), kW, kH, 35.0f, 20.0f, glm::vec3(1.0f));
}

SurfaceOptions alphaOverride(float alpha) {
    SurfaceOptions surface;
    surface.alphaOverride = alpha;
    return surface;
}

}  // namespace

TEST(SuiteScenes, AbufferEqualsExactDepthPeeling) {
    if (test::sharedScenesDir().empty()) GTEST_SKIP() << "../shared/scenes not present";
    test::glContext();
    for (const char* file : {"chess/chess_classic_board.glb", "magic_stars/magic_stars_procedural.glb",
                             "candycat/spot.obj", "tree/tree_grove.glb"}) {
        test::TestScene ts = suiteScene(file);
        RenderOutput a = ts.render("abuffer", {}, alphaOverride(0.35f));
        RenderOutput p = ts.render("peel", {}, alphaOverride(0.35f));
        EXPECT_GE(p.stats["method_stats"]["layers"].get<unsigned>(), p.stats["max_fragments"].get<unsigned>()) << file;
        EXPECT_GE(a.stats["max_fragments"].get<unsigned>(), 4u) << file;
        // Coincident surfaces (equal depth) are the one legitimate difference: peeling takes them as
        // one layer. Find those pixels from the captured lists and compare every other pixel.
        CapturedFrame frags = ts.capture(alphaOverride(0.35f));
        size_t compared = 0, coincident = 0;
        for (int y = 0; y < kH; ++y) {
            for (int x = 0; x < kW; ++x) {
                FragmentList list = frags.at(x, y);
                sortByDepth(list);
                bool tie = false;
                for (size_t i = 1; i < list.size(); ++i) tie |= list[i].depth == list[i - 1].depth;
                if (tie) {
                    ++coincident;
                    continue;
                }
                ++compared;
                for (int c = 0; c < 3; ++c) {
                    ASSERT_NEAR(a.image.pixel(x, y)[c], p.image.pixel(x, y)[c], 1.0f / 255.0f)
                        << file << " pixel " << x << "," << y << " (" << list.size() << " fragments)";
                }
            }
        }
        EXPECT_GT(compared, size_t(kW * kH) * 9 / 10) << file << ": " << coincident << " coincident pixels";
    }
}

TEST(SuiteScenes, EveryFileRendersWithTheNeuralAndClassicMethods) {
    if (test::sharedScenesDir().empty()) GTEST_SKIP() << "../shared/scenes not present";
    test::glContext();
    for (const char* file : {"engine/2CylinderEngine.glb", "chess/chess_classic_board.glb", "clothes/Corset_geom.glb",
                             "clothes/SheenCloth_geom.glb", "candycat/spot.obj", "candycat/Fox.glb",
                             "tree/tree_grove.glb", "powerplant/Buggy_flat.glb", "powerplant/GearboxAssy_flat.glb",
                             "hair/hair_procedural.glb", "hairball/hairball_procedural.glb",
                             "smoke/smoke_procedural.glb", "magic_stars/magic_stars_procedural.glb"}) {
        test::TestScene ts = suiteScene(file);
        for (const char* method : {"starnt", "wboit"}) {
            RenderOutput out = ts.render(method, {}, alphaOverride(0.4f));
            // Something transparent is on screen: some pixel differs from the white background.
            float darkest = 1.0f;
            for (size_t i = 0; i < out.image.rgba.size(); i += 4) darkest = std::min(darkest, out.image.rgba[i + 1]);
            EXPECT_LT(darkest, 0.9f) << file << " " << method;
            for (float v : out.image.rgba) ASSERT_TRUE(std::isfinite(v)) << file << " " << method;
        }
    }
}
