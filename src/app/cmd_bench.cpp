// `starnt bench`: every scene x method of a preset, timed and compared with the A-buffer; writes
// results.json, results.csv, report.md, images and plots into --out (src/bench/ does the work).
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "bench/bench_output.hpp"
#include "bench/bench_plan.hpp"
#include "bench/bench_runner.hpp"
#include "render/option_text.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/error.hpp"

namespace starnt::app {
namespace {

namespace fs = std::filesystem;

// The suite folder beside the checkout this binary was built from, else beside the checkout that
// holds the binary (build/starnt -> ../shared/scenes), else empty (built-in scenes).
std::string defaultSuiteDir() {
    std::error_code ec;
    const fs::path fromSource = fs::path(STARNT_SOURCE_DIR) / ".." / "shared" / "scenes";
    if (fs::is_directory(fromSource, ec)) return fromSource.lexically_normal().string();
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const fs::path fromExe = exe.parent_path().parent_path().parent_path() / "shared" / "scenes";
        if (fs::is_directory(fromExe, ec)) return fromExe.lexically_normal().string();
    }
    return fromSource.lexically_normal().string();  // absent: reported as such in the run
}

std::string joinedList(const std::vector<std::string>& items) {
    std::string text;
    for (const auto& item : items) text += (text.empty() ? "" : ",") + item;
    return text;
}

// The invocation as it would be typed again, for results.json and report.md.
std::string commandLine(const bench::Request& r, const std::string& out, bool noPlots) {
    std::string line = "starnt bench --preset " + r.preset;
    if (!r.scenes.empty()) line += " --scenes " + joinedList(r.scenes);
    if (!r.methods.empty()) line += " --methods " + joinedList(r.methods);
    if (r.width) line += " --width " + std::to_string(r.width);
    if (r.height) line += " --height " + std::to_string(r.height);
    if (r.frames) line += " --frames " + std::to_string(r.frames);
    if (!r.cameraPath.empty()) line += " --camera-path " + r.cameraPath;
    if (r.abufferCapMib > 0.0) line += " --abuffer-cap-mib " + std::to_string(r.abufferCapMib);
    if (r.api != "gl") line += " --api " + r.api;
    if (r.timingRounds != 1) line += " --timing-rounds " + std::to_string(r.timingRounds);
    line += " --suite-dir " + r.suiteDir;
    if (noPlots) line += " --no-plots";
    return line + " --out " + out;
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    struct Args {
        bench::Request request;
        std::string out, python = "/usr/bin/python3";
        bool noPlots = false;
    };
    auto a = std::make_shared<Args>();
    a->request.suiteDir = defaultSuiteDir();
    CLI::App* cmd = app.add_subcommand("bench", "time every method on a scene set and compare it with the A-buffer");
    cmd->add_option("--preset", a->request.preset, "quick (3 scenes, 640x360, 8 frames) | paper (all suite scenes, 1920x1080, 16 frames) | gpu (the six headline scenes, 1920x1080, 8 warm-up + 64 timed frames, 13 variants, errors on 6 frames; for a GPU)")
        ->capture_default_str();
    cmd->add_option("--scenes", a->request.scenes, "suite names, builtin:NAME or scene files (default: the preset's)")->delimiter(',');
    std::string variants, defaults;
    for (const bench::Variant& v : bench::allVariants()) variants += (variants.empty() ? "" : ", ") + v.name;
    for (const std::string& v : bench::defaultVariantNames()) defaults += (defaults.empty() ? "" : ", ") + v;
    cmd->add_option("--methods", a->request.methods,
                    "variants to run, of: " + variants + " (default: the preset's; quick and paper: " + defaults + ")")
        ->delimiter(',');
    cmd->add_option("--out", a->out, "output folder (created; files in it are replaced)")->required();
    cmd->add_option("--suite-dir", a->request.suiteDir, "scene suite folder; built-in scenes when absent")->capture_default_str();
    cmd->add_option("--width", a->request.width, "override the preset's width")->check(CLI::Range(1, kMaxImageSize));
    cmd->add_option("--height", a->request.height, "override the preset's height")->check(CLI::Range(1, kMaxImageSize));
    cmd->add_option("--frames", a->request.frames, "override the preset's frame count (timings skip frame 1)")
        ->check(CLI::Range(1, 10000));
    cmd->add_option("--camera-path", a->request.cameraPath, "override the preset's path: orbit:START,END[,ELEV] or keyframe .json");
    cmd->add_option("--abuffer-cap-mib", a->request.abufferCapMib, "A-buffer memory cap in MiB (0 or absent: the default, 2048)")
        ->check(CLI::Range(0.0, kMaxAbufferCapMib));  // 0: the default
    cmd->add_option("--api", a->request.api, "gl (OpenGL 4.5 core) or gles (OpenGL ES 3.2)")->capture_default_str();
    cmd->add_option("--timing-rounds", a->request.timingRounds,
                    "timed runs of the path per variant, in alternating order; each variant keeps its fastest (1..10; "
                    "2 or more on a noisy machine)")
        ->capture_default_str();
    cmd->add_option("--python", a->python, "Python with matplotlib for the plots")->capture_default_str();
    cmd->add_flag("--no-plots", a->noPlots, "skip the plots");
    cmd->callback([a] {
        const bench::Plan plan = bench::makePlan(a->request);
        std::error_code ec;
        fs::create_directories(a->out, ec);
        if (!fs::is_directory(a->out)) throw Error("--out " + a->out + ": cannot create the folder");
        std::fprintf(stderr, "bench: %zu scenes x %zu methods, %dx%d, %d frames; %s\n", plan.scenes.size(), plan.variants.size(),
                     plan.width, plan.height, plan.frames, plan.suiteNote.c_str());
        bench::Results results = bench::runBench(plan, a->out, stderr);
        results.commandLine = commandLine(a->request, a->out, a->noPlots);
        bench::writeBenchOutputs(results, a->out, a->noPlots ? std::string() : a->python);
        if (!results.plots.made && !a->noPlots) std::fprintf(stderr, "bench: plots skipped: %s\n", results.plots.reason.c_str());
        const size_t failures = results.failureCount();
        std::printf("bench: %s/report.md, results.json, results.csv (%zu failure%s)\n", a->out.c_str(), failures,
                    failures == 1 ? "" : "s");
    });
}

}  // namespace starnt::app
