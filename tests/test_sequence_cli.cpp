// Sequences through the command line (SPEC sections 6 and 9): numbered frames, per-frame stats
// lines, camera paths, and bad input that must fail before anything is written.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "starnt/oit_method.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

using starnt::test::CliRun;
using starnt::test::run;

// The JSON objects of a .jsonl file, one per line.
std::vector<nlohmann::json> readLines(const fs::path& path) {
    std::ifstream f(path);
    std::vector<nlohmann::json> out;
    for (std::string line; std::getline(f, line);) out.push_back(nlohmann::json::parse(line));
    return out;
}

// A small sequence render of builtin:panes into `dir` with extra arguments.
std::string sequence(const fs::path& dir, const std::string& extra) {
    return "render --scene builtin:panes --width 32 --height 24 --out " + (dir / "f_%04d.png").string() +
           " --frame-stats " + (dir / "s.jsonl").string() + " " + extra;
}

// Non-zero exit (not a crash), a message naming the problem, and an empty output folder.
void expectFailureWritingNothing(const std::string& args, const fs::path& dir, const std::string& mentions) {
    const CliRun r = run(args);
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_NE(r.exitCode, -1) << "crashed: " << args;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << "stderr of `" << args << "` was: " << r.err;
    EXPECT_TRUE(fs::is_empty(dir)) << "something was written by: " << args;
}

}  // namespace

TEST(SequenceCli, WritesNumberedFramesAndOneStatsLinePerFrame) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli");
    const CliRun r = run(sequence(dir, "--method wboit --frames 3 --camera-path orbit:0,30"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* name : {"f_0000.png", "f_0001.png", "f_0002.png"}) EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_FALSE(fs::exists(dir / "f_0003.png"));
    EXPECT_FALSE(fs::exists(dir / "f_%04d.png"));
    const std::vector<nlohmann::json> lines = readLines(dir / "s.jsonl");
    ASSERT_EQ(lines.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(lines[size_t(i)]["frame"], i);
        ASSERT_TRUE(lines[size_t(i)].contains("interpolated")) << lines[size_t(i)].dump();
        EXPECT_EQ(lines[size_t(i)]["interpolated"], false) << "wboit has no interpolated frames";
    }
    // The camera moves along the path: first and last frames differ, and each has the frame size.
    const starnt::Image first = starnt::loadImage((dir / "f_0000.png").string());
    const starnt::Image last = starnt::loadImage((dir / "f_0002.png").string());
    EXPECT_EQ(first.width, 32);
    EXPECT_EQ(first.height, 24);
    EXPECT_GT(starnt::mseSrgb(first, last), 1e-5);
}

TEST(SequenceCli, KeyframeFileDrivesTheCamera) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli");
    const fs::path keys = starnt::test::makeTempDir("seq_cli_keys") / "path.json";
    std::ofstream(keys) << R"({"keys": [{"position": [0, 1, 6], "target": [0, 0, 0]},
                                        {"position": [6, 1, 0], "target": [0, 0, 0]}]})";
    const CliRun r = run(sequence(dir, "--method wboit --frames 2 --camera-path " + keys.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(readLines(dir / "s.jsonl").size(), 2u);
    // Each frame is the image of its key's camera given alone (--camera FILE.json), and the two differ.
    const char* poses[] = {R"({"position": [0, 1, 6], "target": [0, 0, 0]})", R"({"position": [6, 1, 0], "target": [0, 0, 0]})"};
    std::vector<starnt::Image> frames;
    for (int k = 0; k < 2; ++k) {
        const fs::path pose = keys.parent_path() / ("key" + std::to_string(k) + ".json");
        std::ofstream(pose) << poses[k];
        const fs::path single = keys.parent_path() / ("key" + std::to_string(k) + ".png");
        const CliRun one = run("render --scene builtin:panes --width 32 --height 24 --method wboit --camera " + pose.string() +
                               " --out " + single.string());
        ASSERT_EQ(one.exitCode, 0) << one.err;
        char name[32];
        std::snprintf(name, sizeof name, "f_%04d.png", k);
        frames.push_back(starnt::loadImage((dir / name).string()));
        EXPECT_LT(starnt::mseSrgb(frames.back(), starnt::loadImage(single.string())), 1e-7) << "frame " << k;  // measured 0
    }
    EXPECT_GT(starnt::mseSrgb(frames[0], frames[1]), 1e-3);  // measured 5.4e-3
}

TEST(SequenceCli, BadPatternsWriteNothing) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli_bad");
    for (const char* pattern : {"f_%s.png", "f_%d_%d.png", "f_%.png", "f_%04x.png"}) {
        expectFailureWritingNothing("render --scene builtin:panes --width 32 --height 24 --frames 2 --out " +
                               (dir / pattern).string() + " --frame-stats " + (dir / "s.jsonl").string(),
                           dir, "frame pattern");
    }
}

// "%%" is a literal '%' in every output name, as in printf; a lone '%' is an error naming the escape.
TEST(SequenceCli, DoublePercentIsALiteralPercentInOutputNames) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli_percent");
    const CliRun one = run("render --scene builtin:panes --method wboit --width 32 --height 24 --out " + (dir / "a_50%%.png").string() +
                           " --stats " + (dir / "s_%%.json").string() + " --frame-stats " + (dir / "f_%%.jsonl").string());
    ASSERT_EQ(one.exitCode, 0) << one.err;
    for (const char* name : {"a_50%.png", "s_%.json", "f_%.jsonl"}) EXPECT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_FALSE(fs::exists(dir / "a_50%%.png"));
    const CliRun frames = run("render --scene builtin:panes --method wboit --width 32 --height 24 --frames 2 --out " +
                              (dir / "b_%%_%02d.png").string());
    ASSERT_EQ(frames.exitCode, 0) << frames.err;
    for (const char* name : {"b_%_00.png", "b_%_01.png"}) EXPECT_TRUE(fs::exists(dir / name)) << name;

    const fs::path bad = starnt::test::makeTempDir("seq_cli_percent_bad");
    expectFailureWritingNothing("render --scene builtin:panes --width 32 --height 24 --out " + (bad / "a_50%.png").string(), bad,
                                "write %% for a literal '%'");
    expectFailureWritingNothing("render --scene builtin:panes --width 32 --height 24 --out " + (bad / "a.png").string() +
                                    " --stats " + (bad / "s_%d.json").string(),
                                bad, "frame patterns are for --out and --exr");
}

TEST(SequenceCli, BadTemporalFramesAndPathsFailClearly) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli_bad");
    expectFailureWritingNothing(sequence(dir, "--method starnt --frames 2 --temporal 9"), dir, "--temporal '9'");
    expectFailureWritingNothing(sequence(dir, "--method starnt --frames 2 --temporal 0"), dir, "--temporal '0'");
    expectFailureWritingNothing(sequence(dir, "--method starnt --frames 2 --temporal x"), dir, "--temporal 'x'");
    expectFailureWritingNothing(sequence(dir, "--method starnt --frames 2 --temporal auto --target-fps 0"), dir, "--target-fps");
    expectFailureWritingNothing(sequence(dir, "--frames 0"), dir, "--frames");
    expectFailureWritingNothing(sequence(dir, "--frames 2 --camera-path /nonexistent/path.json"), dir, "/nonexistent/path.json");
    expectFailureWritingNothing(sequence(dir, "--frames 2 --camera-path orbit:0"), dir, "orbit:START,END");
    const fs::path keys = starnt::test::makeTempDir("seq_cli_keys");
    std::ofstream(keys / "one.json") << R"({"keys": [{"position": [0, 1, 6], "target": [0, 0, 0]}]})";
    expectFailureWritingNothing(sequence(dir, "--frames 2 --camera-path " + (keys / "one.json").string()), dir, "at least two keys");
    std::ofstream(keys / "bad.json") << R"({"keys": [)";
    expectFailureWritingNothing(sequence(dir, "--frames 2 --camera-path " + (keys / "bad.json").string()), dir, "not valid JSON");
    expectFailureWritingNothing(sequence(dir, "--frames 2 --camera orbit:10 --camera-path orbit:0,30"), dir, "exclude");
}

// With --temporal 2 every second frame is interpolated, starting with a real one.
TEST(SequenceCli, TemporalTwoAlternates) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli_temporal");
    const CliRun r = run(sequence(dir, "--method starnt --frames 5 --camera-path orbit:0,8 --temporal 2"));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<nlohmann::json> lines = readLines(dir / "s.jsonl");
    ASSERT_EQ(lines.size(), 5u);
    for (size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(lines[i]["interpolated"], i % 2 == 1) << "frame " << i << ": " << lines[i].dump();
    }
}

// Warm-up frames run on to the end of their temporal group, so the timed frames start at a real
// frame whatever K is: at K = 8 (starnt-d's corrected frames) 3 warm-up frames become 8, and the timed frames are
// one real then seven interpolated; the summary counts the 8.
TEST(SequenceCli, WarmUpEndsAtTheEndOfATemporalGroup) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli_warmup");
    const CliRun r = run(sequence(dir, "--method starnt-d --temporal 8 --frames 9 --warmup 3 --stats " + (dir / "summary.json").string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<nlohmann::json> lines = readLines(dir / "s.jsonl");
    ASSERT_EQ(lines.size(), 9u);
    for (size_t i = 0; i < lines.size(); ++i) {
        EXPECT_EQ(lines[i]["interpolated"], i % starnt::kRecommendedTemporalInterval != 0) << "frame " << i << ": " << lines[i].dump();
    }
    std::ifstream f(dir / "summary.json");
    const nlohmann::json summary = nlohmann::json::parse(f);
    EXPECT_EQ(summary["warmup_frames"], starnt::kRecommendedTemporalInterval);
    // Without temporal frames the warm-up is what was asked.
    const fs::path plain = starnt::test::makeTempDir("seq_cli_warmup_plain");
    ASSERT_EQ(run(sequence(plain, "--method starnt-d --frames 2 --warmup 3 --stats " + (plain / "summary.json").string())).exitCode, 0);
    std::ifstream g(plain / "summary.json");
    EXPECT_EQ(nlohmann::json::parse(g)["warmup_frames"], 3);
}

// Every frame record carries the method's GPU memory and the process's resident memory, so a long
// run shows growth (the 10,000-frame soak in docs/DESIGN.md uses them). Over a short temporal run
// with tiles, the GPU memory stops changing once the history and tiles exist, and the resident
// memory does not climb frame after frame.
TEST(SequenceCli, FrameRecordsCarryMemoryThatStaysFlat) {
    const fs::path dir = starnt::test::makeTempDir("seq_cli");
    const CliRun r = run("render --scene builtin:tubes --width 48 --height 32 --method starnt --temporal 2 --frames 40"
                         " --camera-path orbit:0,40 --out " + (dir / "last.png").string() + " --frame-stats " +
                         (dir / "s.jsonl").string());
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::vector<nlohmann::json> lines = readLines(dir / "s.jsonl");
    ASSERT_EQ(lines.size(), 40u);
    const size_t gpu = lines[4]["memory_bytes"].get<size_t>(), rss = lines[10]["rss_bytes"].get<size_t>();
    EXPECT_GT(gpu, size_t(48 * 32 * 16)) << "at least one RGBA32F target";
    EXPECT_GT(rss, size_t(1) << 20);
    for (size_t i = 4; i < lines.size(); ++i) EXPECT_EQ(lines[i]["memory_bytes"].get<size_t>(), gpu) << "frame " << i;
    EXPECT_LT(lines.back()["rss_bytes"].get<size_t>(), rss + (size_t(16) << 20)) << "resident memory grew by 16 MiB in 30 frames";
}
