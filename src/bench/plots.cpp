#include "bench/plots.hpp"
#include "scene/tool_sources.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>

#include "gl/shader.hpp"
#include "starnt/tools/image.hpp"

namespace starnt::bench {
namespace {

namespace fs = std::filesystem;

std::string shellQuoted(const std::string& text) {
    std::string q = "'";
    for (char ch : text) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

struct ProcessResult {
    int status = -1;  // exit status, -1 when it did not exit normally
    std::string output;
};

ProcessResult runCapturing(const std::string& command) {
    ProcessResult result;
    std::FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string lastLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    size_t nl = text.rfind('\n');
    return nl == std::string::npos ? text : text.substr(nl + 1);
}

}  // namespace

PlotsStatus makePlots(const std::string& outDir, const std::string& python) {
    PlotsStatus status;
    if (access(python.c_str(), X_OK) != 0) {
        status.reason = "no Python interpreter at " + python + " (install python3-matplotlib, or pass --python)";
        return status;
    }
    const fs::path plotDir = fs::path(outDir) / "plots";
    fs::create_directories(plotDir);
    const fs::path script = plotDir / "bench_plots.py";
    writeFileAtomic(script.string(), tools::toolSource("bench/bench_plots.py"));
    const ProcessResult run = runCapturing(shellQuoted(python) + " " + shellQuoted(script.string()) + " " +
                                           shellQuoted((fs::path(outDir) / "results.json").string()) + " " +
                                           shellQuoted(plotDir.string()));
    if (run.status != 0) {
        status.reason = (run.status == 3 ? "" : "plot script failed (exit " + std::to_string(run.status) + "): ") + lastLine(run.output);
        return status;
    }
    for (const char* name : {"frame_time.png", "error.png", "quality_vs_time.png"}) {
        if (fs::exists(plotDir / name)) status.files.push_back("plots/" + std::string(name));
    }
    status.made = status.files.size() == 3;
    status.reason = status.made ? "matplotlib via " + python : "plot script did not write every plot: " + lastLine(run.output);
    return status;
}

}  // namespace starnt::bench
