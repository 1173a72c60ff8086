// `starnt bench`: the plan (variants, scenes, presets), the Q formula, and real runs of the
// CLI at a tiny size checking every output file, every JSON field, agreement with `starnt compare`,
// determinism, and that failures are recorded while the run goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sys/wait.h>

#include <nlohmann/json.hpp>

#include "bench/bench_plan.hpp"
#include "bench/bench_results.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace starnt;

namespace {

struct CliRun {
    int exitCode = -1;
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
}

CliRun runCli(const std::string& args) {
    fs::path dir = test::makeTempDir("bench_io");
    std::string cmd = std::string(STARNT_CLI) + " " + args + " >" + (dir / "out").string() + " 2>" + (dir / "err").string();
    const int status = std::system(cmd.c_str());
    CliRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir / "out");
    r.err = slurp(dir / "err");
    fs::remove_all(dir);
    return r;
}

bool systemPythonHasMatplotlib() { return std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") == 0; }

// The tiny run of the issue: built-in scenes, 128x72, 3 frames, every default method.
const std::string kTinyArgs = "bench --preset quick --suite-dir /nonexistent/suite --scenes builtin:panes,builtin:smoke "
                              "--width 128 --height 72 --frames 3";


// The default methods of bench: unsorted, wboit, mboit, mboit-t3, dfaoit, starnt-full, hybrid,
// starnt-residual-full, starnt, starnt-paper, starnt-total, starnt-total-refresh, starnt-total-warp,
// starnt-corners.
constexpr size_t kDefaultVariants = 18;

json readJson(const fs::path& p) {
    std::ifstream f(p);
    return json::parse(f);
}

}  // namespace

TEST(BenchPlan, VariantsCarryTheirOptions) {
    EXPECT_EQ(bench::defaultVariantNames().size(), kDefaultVariants);
    EXPECT_EQ(bench::findVariant("starnt-residual-full").method, "starnt-residual");
    EXPECT_EQ(bench::findVariant("starnt-residual-full").options.neural.spatial, std::optional<bool>(false));
    const auto& paper = bench::findVariant("starnt-paper");
    EXPECT_EQ(paper.options.neural.tileSignal, NeuralOptions::TileSignal::Composite);
    EXPECT_EQ(paper.options.neural.scaleRule, NeuralOptions::ScaleRule::Continuous);
    EXPECT_FALSE(paper.options.neural.scaleGuard);
    EXPECT_EQ(bench::findVariant("starnt").options.neural.scaleRule, NeuralOptions::ScaleRule::Snapped);
    EXPECT_EQ(bench::findVariant("starnt-total-warp").options.neural.temporalMode, NeuralOptions::TemporalMode::Warp);
    EXPECT_EQ(bench::findVariant("starnt-total").options.neural.temporalMode, NeuralOptions::TemporalMode::Correct);
    EXPECT_EQ(bench::findVariant("starnt-total-refresh").options.neural.temporalMode, NeuralOptions::TemporalMode::Refresh);
    EXPECT_EQ(bench::findVariant("starnt-full").options.neural.spatial, std::optional<bool>(false));
    EXPECT_EQ(bench::findVariant("starnt").options.neural.spatial, std::optional<bool>(true));
    EXPECT_EQ(bench::findVariant("starnt").options.neural.temporalInterval, 1);
    const auto& total = bench::findVariant("starnt-total");
    EXPECT_EQ(total.method, "starnt");
    EXPECT_EQ(total.options.neural.spatial, std::optional<bool>(true));
    EXPECT_EQ(total.options.neural.temporalInterval, 2);
    EXPECT_EQ(bench::findVariant("starnt-corners").options.neural.inference, NeuralOptions::Inference::Corners);
    EXPECT_EQ(bench::findVariant("dfaoit").options.neural.spatial, std::nullopt);  // the method's default: off
    EXPECT_EQ(bench::findVariant("mboit").options.mboit.moments, "6");
    EXPECT_EQ(bench::findVariant("mboit-t3").options.mboit.moments, "t3");
    // Savings are measured against the same method with the acceleration off, in the same run.
    const auto& recommended = bench::findVariant("recommended");
    EXPECT_EQ(recommended.method, "recommended");
    EXPECT_EQ(recommended.accelerationOff, "starnt-d");
    const auto& recommendedK2 = bench::findVariant("recommended-k2");
    EXPECT_EQ(recommendedK2.method, "recommended");
    EXPECT_EQ(recommendedK2.options.neural.temporalInterval, 2);
    EXPECT_EQ(recommendedOptions(recommendedK2.options).neural.temporalInterval, 2) << "K = 2 stays 2";
    EXPECT_EQ(recommendedK2.accelerationOff, "starnt-d");
    EXPECT_EQ(total.accelerationOff, "starnt");
    EXPECT_EQ(bench::findVariant("starnt").accelerationOff, "starnt-full");
    EXPECT_EQ(bench::findVariant("starnt-d").accelerationOff, "");
    for (const auto& v : bench::allVariants()) {
        if (v.accelerationOff.empty()) continue;
        EXPECT_EQ(bench::findVariant(v.accelerationOff).method, v.method == "recommended" ? "starnt-d" : v.method) << v.name;
        EXPECT_FALSE(v.acceleration.empty()) << v.name;
    }
    try {
        bench::findVariant("fancy");
        FAIL() << "unknown variant accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("fancy"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("starnt-total"), std::string::npos);  // lists the valid names
    }
}

TEST(BenchPlan, BuiltinScenesStandInWhenTheSuiteIsAbsent) {
    bench::Request request;
    request.suiteDir = "/nonexistent/suite";
    bench::Plan plan = bench::makePlan(request);
    EXPECT_EQ(plan.width, 640);
    EXPECT_EQ(plan.height, 360);
    ASSERT_EQ(plan.scenes.size(), 3u);
    for (const auto& s : plan.scenes) EXPECT_EQ(s.source.rfind("builtin:", 0), 0u) << s.source;
    EXPECT_NE(plan.suiteNote.find("not found"), std::string::npos);
    EXPECT_TRUE(plan.suiteDir.empty());
    // A suite scene cannot be asked for without the suite.
    request.scenes = {"tree"};
    EXPECT_THROW(bench::makePlan(request), Error);
}

TEST(BenchPlan, SuiteScenesHaveTheirSettings) {
    STARNT_SKIP_WITHOUT_SHARED_SCENES("the bench on suite scenes not tested");
    const fs::path suite = test::sharedScenesDir();
    bench::Request request;
    request.suiteDir = suite.string();
    bench::Plan quick = bench::makePlan(request);
    ASSERT_EQ(quick.scenes.size(), 3u);
    for (const auto& s : quick.scenes) EXPECT_TRUE(fs::exists(s.source)) << s.source;
    request.preset = "paper";
    bench::Plan paper = bench::makePlan(request);
    EXPECT_EQ(paper.width, 1920);
    EXPECT_EQ(paper.scenes.size(), bench::suiteScenes().size());
    for (const auto& s : paper.scenes) {
        EXPECT_TRUE(fs::exists(s.source)) << s.source;
        if (s.name == "smoke") EXPECT_LT(s.alphaCutoff, 0.012f);  // its alphas are 0.012..0.03
        if (s.name == "engine") EXPECT_EQ(s.alphaOverride, std::optional<float>(0.3f));
    }
}

TEST(BenchPlan, RejectsBadRequests) {
    bench::Request request;
    request.suiteDir = "/nonexistent/suite";
    request.preset = "slow";
    EXPECT_THROW(bench::makePlan(request), Error);
    request.preset = "quick";
    request.methods = {"wboit", "wboit"};
    EXPECT_THROW(bench::makePlan(request), Error);
    request.methods = {};
    request.scenes = {"builtin:nope"};
    EXPECT_THROW(bench::makePlan(request), Error);
    request.scenes = {};
    request.cameraPath = "spiral:1";
    EXPECT_THROW(bench::makePlan(request), Error);
    request.cameraPath = {};
    for (int rounds : {0, -1, bench::kMaxTimingRounds + 1}) {
        request.timingRounds = rounds;
        try {
            bench::makePlan(request);
            ADD_FAILURE() << "timing rounds " << rounds << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--timing-rounds"), std::string::npos) << e.what();
        }
    }
}

TEST(BenchResults, QMetricIsImprovementOverUnsortedPerMillisecond) {
    // Half the unsorted error removed (50 %) at 5 ms per frame: 10 % per ms.
    EXPECT_DOUBLE_EQ(*bench::qMetric(0.02, 0.01, 5.0), 10.0);
    EXPECT_DOUBLE_EQ(*bench::qMetric(0.02, 0.02, 5.0), 0.0);  // no better than unsorted
    EXPECT_LT(*bench::qMetric(0.02, 0.03, 5.0), 0.0);         // worse than unsorted
    EXPECT_FALSE(bench::qMetric(0.0, 0.0, 5.0));               // unsorted exact: undefined
    EXPECT_FALSE(bench::qMetric(0.02, 0.01, 0.0));
}

namespace {

void expectEveryFile(const fs::path& dir) {
    for (const char* f : {"results.json", "results.csv", "report.md"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
    json results = readJson(dir / "results.json");
    ASSERT_EQ(results["scenes"].size(), 2u);
    for (const auto& scene : results["scenes"]) {
        EXPECT_TRUE(fs::exists(dir / scene["ground_truth"]["image"].get<std::string>()));
        ASSERT_EQ(scene["methods"].size(), kDefaultVariants);
        for (const auto& c : scene["methods"]) {
            ASSERT_EQ(c["status"], "ok") << c["variant"] << ": " << c["error"];
            EXPECT_TRUE(fs::exists(dir / c["images"]["image"].get<std::string>())) << c["variant"];
            EXPECT_TRUE(fs::exists(dir / c["images"]["flip_map"].get<std::string>())) << c["variant"];
            const std::string tiles = c["images"]["tile_overlay"];
            if (!tiles.empty()) EXPECT_TRUE(fs::exists(dir / tiles)) << tiles;
        }
    }
    // One CSV row per scene and method, each with as many fields as the header.
    std::istringstream csv(slurp(dir / "results.csv"));
    std::string line;
    std::vector<std::string> lines;
    while (std::getline(csv, line)) lines.push_back(line);
    ASSERT_EQ(lines.size(), 1u + 2u * kDefaultVariants);
    auto fields = [](const std::string& l) { return std::count(l.begin(), l.end(), ',') + 1; };
    for (const auto& l : lines) EXPECT_EQ(fields(l), fields(lines[0])) << l;

    const std::string report = slurp(dir / "report.md");
    const std::string recommendedRow = "| **mean** | recommended | the choice per context | starnt-d |";
    for (const std::string& heading : {std::string("## Frame time"), std::string("## Per-pass breakdown"),
                                       std::string("## Speed-up over DFAOIT"), std::string("### MSE x10^2"), std::string("### FLIP"),
                                       std::string("reduction against WBOIT"), std::string("## GPU memory"), std::string("## Q metric"),
                                       std::string("## GPU estimate"), std::string("| kbuffer-moments | pass3 "),
                                       std::string("## Failures"), std::string("## What the network adds"),
                                       std::string("| MSE x10^2 starnt-residual-full | ratio |"), std::string("## Against itself"),
                                       recommendedRow, std::string("| **mean** | starnt | tiles | starnt-full |")}) {
        EXPECT_NE(report.find(heading), std::string::npos) << heading;
    }
    for (const auto& name : bench::defaultVariantNames()) EXPECT_NE(report.find(name), std::string::npos) << name;

    if (systemPythonHasMatplotlib()) {
        EXPECT_TRUE(results["plots"]["made"].get<bool>()) << results["plots"]["reason"];
        for (const char* plot : {"plots/frame_time.png", "plots/error.png", "plots/quality_vs_time.png"}) {
            EXPECT_TRUE(fs::exists(dir / plot)) << plot;
            EXPECT_NE(report.find(plot), std::string::npos) << plot;
        }
    } else {
        EXPECT_FALSE(results["plots"]["made"].get<bool>());
        EXPECT_FALSE(results["plots"]["reason"].get<std::string>().empty());
    }
}

void expectEveryJsonField(const fs::path& dir) {
    json r = readJson(dir / "results.json");
    for (const char* key : {"date", "command_line", "machine", "settings", "variants", "scenes", "plots", "failures", "wall_seconds"}) {
        EXPECT_TRUE(r.contains(key)) << key;
    }
    for (const char* key : {"cpu_model", "cpu_threads", "gl_renderer", "gl_version", "build_type", "commit", "compiler"}) {
        EXPECT_TRUE(r["machine"].contains(key)) << key;
    }
    EXPECT_FALSE(r["machine"]["gl_renderer"].get<std::string>().empty());
    // The device display is tried first: any other one in use says why the device one was refused.
    const std::string platform = r["machine"]["gl_platform"].get<std::string>();
    EXPECT_TRUE(platform == "device" || platform == "surfaceless") << platform;
    if (platform != "device") EXPECT_FALSE(r["machine"]["gl_displays_refused"].get<std::string>().empty());
    EXPECT_TRUE(r["machine"]["gl_displays_refused"].is_string());
    EXPECT_FALSE(r["machine"]["commit"].get<std::string>().empty());  // a hash, or "unknown" outside git
    // Each variant names the one its saving is measured against (scripts/bench_summary.py pairs by it).
    bool sawRecommended = false;
    for (const auto& v : r["variants"]) {
        ASSERT_TRUE(v.contains("acceleration_off") && v.contains("acceleration")) << v["name"];
        if (v["name"] == "recommended") {
            sawRecommended = true;
            EXPECT_EQ(v["acceleration_off"], "starnt-d");
        }
        if (v["name"] == "wboit") EXPECT_TRUE(v["acceleration_off"].is_null());
    }
    EXPECT_TRUE(sawRecommended);
    EXPECT_EQ(r["date"].get<std::string>().size(), 20u);              // 2025-01-31T12:34:56Z
    EXPECT_EQ(r["settings"]["width"], 128);
    EXPECT_EQ(r["settings"]["frames"], 3);
    EXPECT_TRUE(r["settings"]["suite_dir"].is_null());
    EXPECT_EQ(r["failures"], 0);
    for (const auto& scene : r["scenes"]) {
        EXPECT_EQ(scene["ground_truth"]["status"], "ok");
        EXPECT_GE(scene["max_fragments"].get<int>(), 2);
        const json* unsorted = nullptr;
        for (const auto& c : scene["methods"]) {
            if (c["variant"] == "unsorted") unsorted = &c;
        }
        ASSERT_NE(unsorted, nullptr);
        for (const auto& c : scene["methods"]) {
            for (const char* key : {"variant", "method", "status", "error", "stats", "frames", "quality", "images", "q_percent_per_ms",
                                    "mse_reduction_vs_wboit_percent", "flip_reduction_vs_wboit_percent", "speedup_vs_dfaoit_percent"}) {
                EXPECT_TRUE(c.contains(key)) << key;
            }
            for (const char* key : {"frame_ms", "pass_ms", "scale_pass2", "scale_pass3", "w_bar", "tile_levels", "max_fragments",
                                    "memory_bytes", "frames", "interpolated_frames"}) {
                EXPECT_TRUE(c["stats"].contains(key)) << key;
            }
            EXPECT_GT(c["stats"]["frame_ms"].get<double>(), 0.0);
            // The times come from a run of their own (nothing between its frames): the per-frame
            // times are that run's, so their mean over the timed frames (all 3: warm-up frames
            // precede them) is the summary's; the run that measured the errors keeps its mean apart.
            ASSERT_TRUE(c["stats"].contains("frame_ms_mean_with_comparison"));
            EXPECT_GT(c["stats"]["frame_ms_mean_with_comparison"].get<double>(), 0.0);
            double msSum = 0.0;
            for (const auto& f : c["frames"]) msSum += f["frame_ms"].get<double>();
            EXPECT_NEAR(c["stats"]["frame_ms_mean"].get<double>(), msSum / 3.0, 1e-9);
            // The compared time is the long-run one: each kind of frame's mean weighted by its share
            // in the schedule (1/K real), not by its share of these 3 frames (1 real, 2 interpolated at K = 4).
            {
                double real = 0.0, interp = 0.0;
                int realCount = 0, interpCount = 0;
                for (const auto& f : c["frames"]) {
                    (f["interpolated"].get<bool>() ? interp : real) += f["frame_ms"].get<double>();
                    ++(f["interpolated"].get<bool>() ? interpCount : realCount);
                }
                const double share = c["stats"]["real_frame_share"].get<double>();
                const double longRun = c["stats"]["frame_ms_long_run"].get<double>();
                if (c["variant"] == "starnt-total") {
                    EXPECT_DOUBLE_EQ(share, 0.5);
                    ASSERT_EQ(realCount, 2);
                    ASSERT_EQ(interpCount, 1);
                    EXPECT_NEAR(longRun, share * real / 2.0 + (1.0 - share) * interp, 1e-9);
                    // (No comparison of the two kinds of frame's times: a test asserts no speed. Under
                    // the sanitizers an interpolated frame of this tiny run took longer than the real one.)
                } else if (interpCount == 0) {
                    EXPECT_DOUBLE_EQ(share, 1.0);
                    EXPECT_NEAR(longRun, msSum / 3.0, 1e-9);
                }
            }
            // GPU frame times (a timestamp pair around each frame) only where timestamps are GPU
            // times; a software rasteriser's would be submission times, so none there.
            ASSERT_TRUE(c["stats"].contains("frame_gpu_ms_mean"));
            if (r["machine"]["gl_software"].get<bool>()) {
                EXPECT_TRUE(c["stats"]["frame_gpu_ms_mean"].is_null());
                for (const auto& f : c["frames"]) EXPECT_TRUE(f.at("frame_gpu_ms").is_null());
            } else {
                double gpuSum = 0.0;
                for (const auto& f : c["frames"]) gpuSum += f.at("frame_gpu_ms").get<double>();
                EXPECT_NEAR(c["stats"]["frame_gpu_ms_mean"].get<double>(), gpuSum / 3.0, 1e-9);
            }
            EXPECT_GT(c["stats"]["memory_bytes"].get<double>(), 0.0);
            EXPECT_EQ(c["frames"].size(), 3u);  // one record per frame, each with its error
            for (const auto& f : c["frames"]) EXPECT_TRUE(f.contains("mse") && f.contains("flip"));
            // The mean error is the mean of the per-frame errors.
            double mseSum = 0.0;
            for (const auto& f : c["frames"]) mseSum += f["mse"].get<double>();
            EXPECT_NEAR(c["quality"]["mse"].get<double>(), mseSum / 3.0, 1e-15);
            // Q recomputed from the figures beside it.
            const double uMse = (*unsorted)["quality"]["mse"], mse = c["quality"]["mse"], ms = c["stats"]["frame_ms_long_run"];
            if (uMse > 0.0) EXPECT_NEAR(c["q_percent_per_ms"].get<double>(), (uMse - mse) / (ms * uMse) * 100.0, 1e-9);
        }
    }
}

// The bench's last-frame figures are computed on the PNG files it wrote, read back exactly as
// `starnt compare` reads them, so the two must agree to the last printed digit (only the JSON
// double round trip separates them). The per-frame figures are computed on the float images before
// 8-bit quantisation: RMSE is a norm, so the two RMSEs differ by at most the RMS of the
// quantisation difference, under 1/255 (each image is off by at most half a step per channel).
void expectAgreementWithCompare(const fs::path& dir) {
    json r = readJson(dir / "results.json");
    for (const auto& scene : r["scenes"]) {
        const std::string gt = (dir / scene["ground_truth"]["image"].get<std::string>()).string();
        for (const auto& c : scene["methods"]) {
            const std::string image = (dir / c["images"]["image"].get<std::string>()).string();
            CliRun cmp = runCli("compare --reference " + gt + " --test " + image + " --json");
            ASSERT_EQ(cmp.exitCode, 0) << cmp.err;
            json j = json::parse(cmp.out);
            const json& png = c["quality"]["last_frame_png"];
            EXPECT_NEAR(png["mse"].get<double>(), j["mse"].get<double>(), 1e-12) << c["variant"];
            EXPECT_NEAR(png["flip"].get<double>(), j["flip"].get<double>(), 1e-12) << c["variant"];
            const double lastFloatMse = c["frames"].back()["mse"];
            EXPECT_LE(std::abs(std::sqrt(png["mse"].get<double>()) - std::sqrt(lastFloatMse)), 1.0 / 255.0) << c["variant"];
        }
    }
}

void expectSameQuality(const fs::path& dir, const fs::path& again) {
    json first = readJson(dir / "results.json"), second = readJson(again / "results.json");
    EXPECT_FALSE(second["plots"]["made"].get<bool>());
    for (size_t s = 0; s < first["scenes"].size(); ++s) {
        for (size_t m = 0; m < first["scenes"][s]["methods"].size(); ++m) {
            const json& a = first["scenes"][s]["methods"][m];
            const json& b = second["scenes"][s]["methods"][m];
            EXPECT_EQ(a["quality"]["mse"], b["quality"]["mse"]) << a["variant"];
            EXPECT_EQ(a["quality"]["flip"], b["quality"]["flip"]) << a["variant"];
        }
    }
}

}  // namespace

// The tiny run (built-in scenes, 128x72, 3 frames, every default method), checked file by
// file, then run again: renders are deterministic, so the quality figures repeat exactly. One test
// (ctest runs each test in its own process, so separate tests would each render the run again).
TEST(BenchCli, TinyRunProducesEveryFileAndFieldAndRepeats) {
    fs::path dir = test::makeTempDir("bench_tiny");
    CliRun r = runCli(kTinyArgs + " --out " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("left ~"), std::string::npos) << "no progress estimate on stderr: " << r.err;
    expectEveryFile(dir);
    expectEveryJsonField(dir);
    expectAgreementWithCompare(dir);
    fs::path again = test::makeTempDir("bench_again");
    r = runCli(kTinyArgs + " --no-plots --out " + again.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    expectSameQuality(dir, again);
    fs::remove_all(again);
    fs::remove_all(dir);
}

TEST(BenchCli, FailuresAreRecordedAndTheRunGoesOn) {
    fs::path dir = test::makeTempDir("bench_fail");
    // A 0.01 MiB cap cannot hold even the per-pixel heads at 128x72: the ground truth and the
    // abuffer method fail; unsorted still runs and is timed, without quality figures. A missing
    // Python skips the plots with the reason recorded.
    CliRun r = runCli("bench --suite-dir /nonexistent/suite --scenes builtin:panes --methods unsorted,abuffer --width 128 --height 72 "
                      "--frames 2 --abuffer-cap-mib 0.01 --python /nonexistent/python3 --out " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    json j = readJson(dir / "results.json");
    EXPECT_EQ(j["failures"], 2);
    const json& scene = j["scenes"][0];
    EXPECT_EQ(scene["ground_truth"]["status"], "failed");
    EXPECT_NE(scene["ground_truth"]["error"].get<std::string>().find("memory cap"), std::string::npos);
    const json& unsorted = scene["methods"][0];
    const json& abuffer = scene["methods"][1];
    EXPECT_EQ(unsorted["status"], "ok");
    EXPECT_GT(unsorted["stats"]["frame_ms"].get<double>(), 0.0);
    EXPECT_TRUE(unsorted["quality"].is_null());
    EXPECT_NE(unsorted["quality_missing_reason"].get<std::string>().find("ground truth failed"), std::string::npos);
    EXPECT_EQ(abuffer["status"], "failed");
    EXPECT_NE(abuffer["error"].get<std::string>().find("memory cap"), std::string::npos);
    EXPECT_FALSE(j["plots"]["made"].get<bool>());
    EXPECT_NE(j["plots"]["reason"].get<std::string>().find("/nonexistent/python3"), std::string::npos);
    const std::string report = slurp(dir / "report.md");
    EXPECT_NE(report.find("ground truth failed"), std::string::npos);
    EXPECT_NE(report.find("Plots were skipped"), std::string::npos);
    fs::remove_all(dir);
}

// Timing rounds: every variant timed again in a second round; each keeps the times of its faster
// round (frame_ms_long_run is the least of frame_ms_rounds, and its per-frame times are that
// round's: their mean is the summary's), and the errors of its one compared run.
TEST(BenchCli, TimingRoundsKeepEachVariantsFastestRound) {
    fs::path dir = test::makeTempDir("bench_rounds");
    CliRun r = runCli("bench --suite-dir /nonexistent/suite --scenes builtin:panes --methods wboit,dfaoit,recommended --width 64 "
                      "--height 48 --frames 3 --timing-rounds 2 --no-plots --out " + dir.string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json j = readJson(dir / "results.json");
    EXPECT_EQ(j["settings"]["timing_rounds"], 2);
    EXPECT_NE(j["command_line"].get<std::string>().find("--timing-rounds 2"), std::string::npos);
    for (const json& c : j["scenes"][0]["methods"]) {
        ASSERT_EQ(c["status"], "ok") << c["variant"];
        const json& rounds = c["stats"]["frame_ms_rounds"];
        ASSERT_EQ(rounds.size(), 2u) << c["variant"];
        const double fastest = std::min(rounds[0].get<double>(), rounds[1].get<double>());
        EXPECT_DOUBLE_EQ(c["stats"]["frame_ms_long_run"].get<double>(), fastest) << c["variant"];
        const int kept = c["stats"]["timing_round"].get<int>();
        ASSERT_TRUE(kept == 1 || kept == 2) << c["variant"];
        EXPECT_DOUBLE_EQ(rounds[size_t(kept - 1)].get<double>(), fastest) << c["variant"];
        double sum = 0.0;
        for (const json& f : c["frames"]) sum += f["frame_ms"].get<double>();
        EXPECT_NEAR(c["stats"]["frame_ms_mean"].get<double>(), sum / 3.0, 1e-9) << c["variant"];
        EXPECT_TRUE(c["stats"].contains("error")) << c["variant"];
        EXPECT_GT(c["quality"]["mse"].get<double>(), 0.0) << c["variant"];
    }
    EXPECT_NE(slurp(dir / "report.md").find("fastest of 2"), std::string::npos);
    fs::remove_all(dir);
}

TEST(BenchCli, BadArgumentsFailBeforeRendering) {
    fs::path dir = test::makeTempDir("bench_bad") / "out";
    CliRun r = runCli("bench --suite-dir /nonexistent/suite --methods wboit,magic --out " + dir.string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("magic"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir));
    r = runCli("bench --suite-dir /nonexistent/suite --scenes tree --out " + dir.string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("suite"), std::string::npos) << r.err;
}

TEST(RenderStats, WorstInterpolatedFlashComparesWithTheRealFramesBesideIt) {
    // Real frames at 1, 2, 2; interpolated ones at 1.5 (between 1 and 2: ratio 1) and 8 (between 2
    // and 2: ratio 4), and a last one at 3 with a real frame on one side only (ratio 1.5).
    const std::vector<std::pair<bool, double>> frames = {{false, 1.0}, {true, 1.5}, {false, 2.0}, {true, 8.0},
                                                         {false, 2.0}, {true, 3.0}};
    const auto flash = worstInterpolatedFlash(frames);
    ASSERT_TRUE(flash);
    EXPECT_DOUBLE_EQ(flash->ratio, 4.0);
    EXPECT_EQ(flash->frame, 3);
    EXPECT_DOUBLE_EQ(flash->mse, 8.0);
    EXPECT_DOUBLE_EQ(flash->realBeside, 2.0);
    // Real frames equal to the reference beside a frame with some error: an infinite ratio, and
    // what it compares.
    const auto exactReal = worstInterpolatedFlash({{false, 0.0}, {true, 0.5}, {false, 0.0}});
    ASSERT_TRUE(exactReal);
    EXPECT_TRUE(std::isinf(exactReal->ratio));
    EXPECT_DOUBLE_EQ(exactReal->mse, 0.5);
    EXPECT_DOUBLE_EQ(exactReal->realBeside, 0.0);
    const auto tail = worstInterpolatedFlash({{false, 2.0}, {true, 3.0}});
    ASSERT_TRUE(tail);
    EXPECT_DOUBLE_EQ(tail->ratio, 1.5);
    EXPECT_FALSE(worstInterpolatedFlash({{false, 1.0}, {false, 2.0}}));  // nothing interpolated
    EXPECT_FALSE(worstInterpolatedFlash({{true, 1.0}}));                 // no real frame to compare with
}

// The gpu preset: the paper's protocol at 1080p for a GPU, every headline variant, the error on
// three frames in every 32 (FLIP is CPU work; the GPU's timed frames are not).
TEST(BenchPlan, GpuPresetNamesTheHeadlineAndMeasuresErrorOnFewFrames) {
    bench::Request request;
    request.preset = "gpu";
    request.suiteDir = "/nonexistent/suite";
    const bench::Plan plan = bench::makePlan(request);
    EXPECT_EQ(plan.width, 1920);
    EXPECT_EQ(plan.height, 1080);
    EXPECT_EQ(plan.frames, 64);
    EXPECT_EQ(plan.warmupFrames, 8);
    EXPECT_EQ(plan.qualityEvery, 32);
    std::vector<std::string> names;
    for (const auto& v : plan.variants) names.push_back(v.name);
    for (const char* v : {"wboit", "mboit", "mboit-t3", "dfaoit", "starnt-full", "starnt", "hybrid", "hybrid-moments", "starnt-d",
                          "starnt-total", "starnt-total-refresh", "starnt-total-warp", "recommended"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), v), names.end()) << v;
    }
    EXPECT_EQ(bench::findPreset("gpu").suiteNames.size(), 6u);
}

TEST(BenchCli, GpuPresetComparesFramesZeroToTwoInEveryThirtyTwo) {
    const fs::path dir = test::makeTempDir("bench_gpu");
    CliRun r = runCli("bench --preset gpu --suite-dir /nonexistent/suite --scenes builtin:panes --methods wboit,recommended "
                      "--width 32 --height 18 --frames 5 --no-plots --out " + (dir / "out").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json results = readJson(dir / "out" / "results.json");
    for (const auto& c : results["scenes"][0]["methods"]) {
        ASSERT_EQ(c["status"], "ok") << c["variant"] << ": " << c["error"];
        ASSERT_EQ(c["frames"].size(), 5u) << c["variant"];
        double mse = 0.0;
        for (size_t i = 0; i < 5; ++i) {
            EXPECT_EQ(c["frames"][i].contains("mse"), i < 3) << c["variant"] << " frame " << i;
            if (i < 3) mse += c["frames"][i]["mse"].get<double>() / 3.0;
        }
        // The mean over the compared frames alone.
        EXPECT_NEAR(c["quality"]["mse"].get<double>(), mse, 1e-12 + 1e-9 * mse) << c["variant"];
    }
    EXPECT_EQ(results["failures"].get<int>(), 0);
    EXPECT_NE(slurp(dir / "out" / "report.md").find("i mod 32 < 3"), std::string::npos);
}
