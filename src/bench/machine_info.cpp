#include "bench/machine_info.hpp"

#include <unistd.h>

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

#include "bench/build_info.hpp"

namespace starnt::bench {
namespace {

std::string cpuModelName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) != 0) continue;
        size_t colon = line.find(':');
        if (colon == std::string::npos) break;
        size_t start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? "unknown" : line.substr(start);
    }
    return "unknown";
}

}  // namespace

MachineInfo collectMachineInfo(const GlContextInfo& gl) {
    MachineInfo info;
    char host[256] = {};
    info.hostname = gethostname(host, sizeof host - 1) == 0 ? host : "unknown";
    info.cpuModel = cpuModelName();
    info.cpuThreads = std::thread::hardware_concurrency();
    if (const char* lp = std::getenv("LP_NUM_THREADS")) info.lpNumThreads = lp;
    info.gl = gl;
    info.buildType = buildType();
    info.commit = buildCommit();
    info.compiler = buildCompiler();
    return info;
}

nlohmann::json toJson(const MachineInfo& info) {
    return {
        {"hostname", info.hostname},
        {"cpu_model", info.cpuModel},
        {"cpu_threads", info.cpuThreads},
        {"lp_num_threads", info.lpNumThreads.empty() ? nlohmann::json(nullptr) : nlohmann::json(info.lpNumThreads)},
        {"gl_platform", info.gl.platform},
        {"gl_displays_refused", info.gl.refused},
        {"gl_vendor", info.gl.vendor},
        {"gl_renderer", info.gl.renderer},
        {"gl_version", info.gl.version},
        {"gl_software", info.gl.software},
        {"build_type", info.buildType},
        {"commit", info.commit},
        {"compiler", info.compiler},
    };
}

std::string isoUtcNow() {
    std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace starnt::bench
