// The command-line contract (SPEC section 9): real runs of the starnt binary, good and bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <cstdio>
#include <fstream>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

using starnt::test::CliRun;
using starnt::test::expectCleanFailure;
using starnt::test::run;

}  // namespace

TEST(Cli, RenderWritesImageStatsAndExr) {
    fs::path dir = starnt::test::makeTempDir("cli");
    CliRun r = run("render --scene builtin:panes --method wboit --width 64 --height 48 --frames 2 --out " +
                (dir / "a.png").string() + " --exr " + (dir / "a.exr").string() + " --stats " + (dir / "a.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    starnt::Image png = starnt::loadImage((dir / "a.png").string());
    starnt::Image exr = starnt::loadImage((dir / "a.exr").string());
    EXPECT_EQ(png.width, 64);
    EXPECT_EQ(png.height, 48);
    EXPECT_LT(starnt::mseSrgb(png, exr), 1e-5);
    std::ifstream f(dir / "a.json");
    nlohmann::json stats = nlohmann::json::parse(f);
    for (const char* key : {"method", "width", "height", "frame_ms", "pass_ms", "scale_pass2", "scale_pass3", "w_bar",
                            "tile_levels", "max_fragments", "memory_bytes", "frames", "interpolated_frames"}) {
        EXPECT_TRUE(stats.contains(key)) << key;
    }
    EXPECT_EQ(stats["method"], "wboit");
    EXPECT_EQ(stats["frames"], 2);
    EXPECT_GT(stats["pass_ms"]["accumulate"].get<double>(), 0.0);
    EXPECT_GE(stats["max_fragments"].get<int>(), 2);
    // Memory by target, summing to the total: wboit's accumulation, revealage and output, at
    // 64x48 (RGBA32F accum and output, R32F revealage).
    ASSERT_TRUE(stats.contains("memory_targets"));
    size_t sum = 0;
    for (const auto& [name, bytes] : stats["memory_targets"].items()) sum += bytes.get<size_t>();
    EXPECT_EQ(sum, stats["memory_bytes"].get<size_t>());
    EXPECT_EQ(stats["memory_targets"]["accum"].get<size_t>(), size_t(64 * 48 * 16));
    EXPECT_EQ(stats["memory_targets"]["revealage"].get<size_t>(), size_t(64 * 48 * 4));
}

// The neural method names its targets and their bytes. Compact targets (the default):
// 36 bytes a pixel at full resolution for STAR-NT, the output written in place over pass 3's sums
// (or pass 2's colour when only pass 3 is reduced), so at 1920x1080 the passes hold 74.6 MB and the
// tiles 0.33 MB: within the paper's 75 MB. Fixed scales keep the tiles updating every frame, so at
// 50/50 neither pass target is free and the output gets a texture of its own. The tile overlay
// exists only when asked for.
TEST(Cli, NeuralMemoryTargetsSumToTheTotal) {
    fs::path dir = starnt::test::makeTempDir("cli");
    struct Case {
        std::string extra;
        size_t colorBytes, outputBytes;
        std::string outputTarget;
    };
    const Case cases[] = {{"--scales 100,100", 8, 0, "pass3_alpha_color"},
                          {"--scales 100,50", 8, 0, "pass2_color"},
                          {"--scales 50,50 --tiles-image " + (dir / "t.png").string(), 8, 8, "output"},
                          {"--scales 100,100 --targets fp32", 16, 0, "pass3_alpha_color"}};
    for (const Case& c : cases) {
        const CliRun r = run("render --scene builtin:tubes --method starnt --width 64 --height 48 " + c.extra + " --out " +
                             (dir / "a.png").string() + " --stats " + (dir / "a.json").string());
        ASSERT_EQ(r.exitCode, 0) << r.err;
        std::ifstream f(dir / "a.json");
        const nlohmann::json stats = nlohmann::json::parse(f);
        const nlohmann::json& targets = stats["memory_targets"];
        size_t sum = 0, tiles = 0;
        for (const auto& [name, bytes] : targets.items()) {
            sum += bytes.get<size_t>();
            if (name.rfind("tile_", 0) == 0) tiles += bytes.get<size_t>();
        }
        EXPECT_EQ(sum, stats["memory_bytes"].get<size_t>()) << c.extra;
        const size_t pixels = 64 * 48, single = c.colorBytes / 4;
        EXPECT_EQ(targets["pass1_color"].get<size_t>(), pixels * c.colorBytes) << c.extra;
        EXPECT_EQ(targets["pass1_depth"].get<size_t>(), pixels * 4) << c.extra;
        EXPECT_EQ(targets["pass2_color"].get<size_t>(), pixels * c.colorBytes) << c.extra;
        EXPECT_EQ(targets["pass3_alpha_color"].get<size_t>(), pixels * c.colorBytes) << c.extra;
        // STAR-NT keeps pass 3's fragment count alone: it reads no sum of C.
        EXPECT_EQ(targets["pass3_count"].get<size_t>(), pixels * single) << c.extra;
        EXPECT_FALSE(targets.contains("pass3_color_count")) << c.extra;
        EXPECT_EQ(targets["output"].get<size_t>(), pixels * c.outputBytes) << c.extra;
        EXPECT_EQ(stats["method_stats"]["output_target"], c.outputTarget) << c.extra;
        EXPECT_EQ(targets["tile_overlay_debug"].get<size_t>(), 0u) << "counted before the overlay is made: " << c.extra;
        if (c.colorBytes == 8 && c.outputBytes == 0) EXPECT_EQ(sum - tiles, pixels * 36) << c.extra;
    }
    // DFAOIT reads the unweighted colour sum: sum C and N stay in one RGBA target.
    const CliRun r = run("render --scene builtin:tubes --method dfaoit --width 64 --height 48 --out " +
                         (dir / "d.png").string() + " --stats " + (dir / "d.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::ifstream f(dir / "d.json");
    const nlohmann::json dfaoit = nlohmann::json::parse(f);
    EXPECT_EQ(dfaoit["memory_targets"]["pass3_color_count"].get<size_t>(), size_t(64 * 48 * 8));
    EXPECT_FALSE(dfaoit["memory_targets"].contains("pass3_count"));
    // Its default (full resolution, no tiles, no temporal frames) runs the narrow layers: 4-byte
    // layer colours, both alphas in one 4-byte target, a 2-byte pass-2 depth, 36 bytes a pixel
    // (74,649,600 bytes at 1920x1080).
    const nlohmann::json& narrow = dfaoit["memory_targets"];
    EXPECT_EQ(narrow["pass1_color"].get<size_t>(), size_t(64 * 48 * 4));
    EXPECT_EQ(narrow["pass2_color"].get<size_t>(), size_t(64 * 48 * 4));
    EXPECT_EQ(narrow["layer_alphas"].get<size_t>(), size_t(64 * 48 * 4));
    EXPECT_EQ(narrow["pass2_depth"].get<size_t>(), size_t(64 * 48 * 2));
    EXPECT_EQ(dfaoit["memory_bytes"].get<size_t>(), size_t(64 * 48 * 36));
    // With the tiles on, the tiles read the layers' alphas from the colour targets: RGBA16F layers.
    const CliRun tiled = run("render --scene builtin:tubes --method dfaoit --spatial on --width 64 --height 48 --out " +
                             (dir / "d.png").string() + " --stats " + (dir / "d.json").string());
    ASSERT_EQ(tiled.exitCode, 0) << tiled.err;
    std::ifstream g(dir / "d.json");
    const nlohmann::json wide = nlohmann::json::parse(g)["memory_targets"];
    EXPECT_EQ(wide["pass1_color"].get<size_t>(), size_t(64 * 48 * 8));
    EXPECT_EQ(wide["layer_alphas"].get<size_t>(), 0u);
    EXPECT_EQ(wide["pass2_depth"].get<size_t>(), size_t(64 * 48 * 4));
}

TEST(Cli, CompareIdenticalIsZeroAndJsonShape) {
    fs::path dir = starnt::test::makeTempDir("cli");
    const CliRun first = run("render --scene builtin:panes --method abuffer --width 40 --height 30 --out " + (dir / "a.png").string());
    ASSERT_EQ(first.exitCode, 0) << first.err;
    ASSERT_EQ(run("render --scene builtin:panes --method unsorted --width 40 --height 30 --out " + (dir / "u.png").string()).exitCode, 0);
    CliRun same = run("compare --reference " + (dir / "a.png").string() + " --test " + (dir / "a.png").string() + " --json");
    ASSERT_EQ(same.exitCode, 0) << same.err;
    nlohmann::json j = nlohmann::json::parse(same.out);
    EXPECT_EQ(j["mse"].get<double>(), 0.0);
    EXPECT_EQ(j["flip"].get<double>(), 0.0);
    CliRun diff = run("compare --reference " + (dir / "a.png").string() + " --test " + (dir / "u.png").string() + " --json");
    nlohmann::json d = nlohmann::json::parse(diff.out);
    // The panes overlap in several orders: unsorted blending must differ from the exact image.
    EXPECT_GT(d["mse"].get<double>(), 1e-5);
    EXPECT_GT(d["flip"].get<double>(), 0.0);
}

TEST(Cli, BadInputFailsCleanly) {
    fs::path dir = starnt::test::makeTempDir("cli_bad");
    const std::string out = (dir / "x.png").string();
    const std::string base = "render --width 32 --height 24 --out " + out + " ";
    expectCleanFailure(base + "--scene /nonexistent/scene.glb", out, "nonexistent");
    expectCleanFailure(base + "--scene builtin:nope", out, "nope");
    {
        std::ofstream(dir / "scene.xyz") << "hello";
        expectCleanFailure(base + "--scene " + (dir / "scene.xyz").string(), out, "xyz");
        std::ofstream(dir / "broken.gltf") << "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ ";
        expectCleanFailure(base + "--scene " + (dir / "broken.gltf").string(), out, "broken.gltf");
        std::ofstream(dir / "empty.gltf") << R"({"asset":{"version":"2.0"}})";
        expectCleanFailure(base + "--scene " + (dir / "empty.gltf").string(), out, "no renderable triangles");
        // A zero-area scene (all three vertices on one line).
        std::ofstream(dir / "flat.obj") << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
        expectCleanFailure(base + "--scene " + (dir / "flat.obj").string(), out, "no renderable triangles");
        std::ofstream(dir / "range.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 999\n";
        expectCleanFailure(base + "--scene " + (dir / "range.obj").string(), out, "range.obj");
    }
    expectCleanFailure("render --scene builtin:panes --width 0 --height 24 --out " + out, out, "out of range");
    expectCleanFailure("render --scene builtin:panes --width 20000 --height 24 --out " + out, out, "out of range");
    expectCleanFailure("render --scene builtin:panes --width 32 --height 24 --method magic --out " + out, out, "magic");
    expectCleanFailure("render --scene builtin:panes --width 32 --height 24 --bogus-flag --out " + out, out, "bogus");
    expectCleanFailure(base + "--scene builtin:panes --background 1,2", out, "R,G,B");
    expectCleanFailure(base + "--scene builtin:panes --camera orbit:abc", out, "orbit");
    expectCleanFailure(base + "--scene builtin:panes --alpha 1.5", out, "alpha");
    expectCleanFailure("render --scene builtin:panes --width 32 --height 24 --out " + (dir / "missing_dir/x.png").string(),
                       dir / "missing_dir", "does not exist");
    // compare: different sizes, missing file.
    ASSERT_EQ(run("render --scene builtin:panes --width 32 --height 24 --out " + (dir / "a.png").string()).exitCode, 0);
    ASSERT_EQ(run("render --scene builtin:panes --width 30 --height 24 --out " + (dir / "b.png").string()).exitCode, 0);
    CliRun r = run("compare --reference " + (dir / "a.png").string() + " --test " + (dir / "b.png").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("differ in size"), std::string::npos) << r.err;
    r = run("compare --reference " + (dir / "a.png").string() + " --test " + (dir / "nothere.png").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("nothere.png"), std::string::npos) << r.err;
}

// The help texts come from the registry and the option parsers, so they cannot go stale: every
// method the library creates, every temporal mode and every bench preset is named.
TEST(Cli, HelpNamesEveryMethodModeAndPreset) {
    const CliRun methods = run("methods");
    ASSERT_EQ(methods.exitCode, 0);
    std::vector<std::string> names;
    std::istringstream in(methods.out);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) names.push_back(line);
    ASSERT_GE(names.size(), 12u);
    EXPECT_NE(std::find(names.begin(), names.end(), "recommended"), names.end());
    for (const char* command : {"render", "view"}) {
        const CliRun help = run(std::string(command) + " --help");
        ASSERT_EQ(help.exitCode, 0) << command;
        for (const auto& name : names) EXPECT_NE(help.out.find(name), std::string::npos) << command << " --help lacks " << name;
        for (const char* mode : {"warp", "refresh", "correct"}) EXPECT_NE(help.out.find(mode), std::string::npos) << command << " " << mode;
        EXPECT_EQ(help.out.find("starnt/dfaoit:"), std::string::npos) << command << ": a stale scope in the help";
    }
    const CliRun bench = run("bench --help");
    for (const char* preset : {"quick", "paper", "gpu"}) EXPECT_NE(bench.out.find(preset), std::string::npos) << preset;
}
