// The spatial-acceleration options of `starnt render` (SPEC 5, 9): scales, inference, tile images.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "starnt/tools/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using starnt::test::expectCleanFailure;
using starnt::test::run;

namespace {

nlohmann::json readJson(const fs::path& p) {
    std::ifstream f(p);
    return nlohmann::json::parse(f);
}

}  // namespace

TEST(TilesCli, SpatialIsTheStarntDefaultAndWritesTiles) {
    const fs::path dir = starnt::test::makeTempDir("tiles_cli");
    const std::string common = "render --scene builtin:tubes --method starnt --width 96 --height 64 --frames 4 --out " +
                               (dir / "a.png").string() + " --stats " + (dir / "a.json").string();
    auto r = run(common + " --tiles-image " + (dir / "tiles.png").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto stats = readJson(dir / "a.json");
    EXPECT_EQ(stats["method_stats"]["spatial"], true);
    EXPECT_TRUE(stats["w_bar"].is_number());
    const starnt::Image tiles = starnt::loadImage((dir / "tiles.png").string());
    EXPECT_EQ(tiles.width, 96);

    r = run(common + " --spatial off");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readJson(dir / "a.json")["method_stats"]["spatial"], false);
    EXPECT_EQ(readJson(dir / "a.json")["scale_pass3"], 1.0);

    r = run(common + " --scales 50,25 --inference corners");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto fixed = readJson(dir / "a.json");
    EXPECT_EQ(fixed["scale_pass2"], 0.5);
    EXPECT_EQ(fixed["scale_pass3"], 0.25);
    EXPECT_EQ(fixed["method_stats"]["inference"], "corners");
    EXPECT_EQ(fixed["method_stats"]["corner_inference_used"], true);
    fs::remove_all(dir);
}

TEST(TilesCli, BadSpatialOptionsFailCleanly) {
    const fs::path dir = starnt::test::makeTempDir("tiles_cli_bad");
    const fs::path out = dir / "a.png";
    const std::string common = "render --scene builtin:panes --method starnt --width 32 --height 32 --out " + out.string();
    expectCleanFailure(common + " --spatial maybe", out, "--spatial");
    expectCleanFailure(common + " --scales 10,10", out, "25..100");
    expectCleanFailure(common + " --scales 50", out, "P2,P3");
    expectCleanFailure(common + " --inference some", out, "--inference");
    expectCleanFailure(common + " --scale-rule round", out, "snapped, continuous or step");
    expectCleanFailure(common + " --tile-signal depth", out, "back or composite");
    expectCleanFailure(common + " --scale-guard maybe", out, "--scale-guard");
    expectCleanFailure(common + " --temporal 2 --temporal-mode blend", out, "warp, refresh or correct");
    expectCleanFailure(common + " --temporal 2 --corrected-passes 3", out, "expected 1 or 2");
    for (const char* mode : {"refresh", "correct"}) {
        expectCleanFailure("render --scene builtin:panes --method wboit --width 32 --height 32 --temporal-mode " +
                               std::string(mode) + " --out " + out.string(),
                           out, "no interpolated frames");
    }
    expectCleanFailure(common + " --tiles-image " + (dir / "t.jpg").string(), out, ".png");
    expectCleanFailure("render --scene builtin:panes --method wboit --width 32 --height 32 --out " + out.string() +
                           " --tiles-image " + (dir / "t.png").string(),
                       dir / "t.png", "runs no tiles");
    fs::remove_all(dir);
}
