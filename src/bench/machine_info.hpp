// Where a benchmark ran: CPU, GL implementation, build. Recorded with every result so figures from
// different machines or builds are never mixed up.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "starnt/tools/gl_context.hpp"

namespace starnt::bench {

struct MachineInfo {
    std::string hostname;
    std::string cpuModel;  // /proc/cpuinfo "model name"; "unknown" elsewhere
    unsigned cpuThreads = 0;
    std::string lpNumThreads;  // LP_NUM_THREADS (llvmpipe's thread count) or "" when unset
    GlContextInfo gl;
    std::string buildType;  // CMAKE_BUILD_TYPE
    std::string commit;     // `git describe --always --dirty` at build time, or "unknown"
    std::string compiler;
};

// Reads the machine and build; `gl` comes from the context the bench renders with.
MachineInfo collectMachineInfo(const GlContextInfo& gl);
nlohmann::json toJson(const MachineInfo& info);

// The current time as ISO-8601 UTC, e.g. "2025-01-31T12:34:56Z".
std::string isoUtcNow();

}  // namespace starnt::bench
