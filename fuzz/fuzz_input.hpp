// Shared by the libFuzzer targets: the loaders read files, so each input is written to a file in a
// per-process temporary folder first (tmpfs-backed /tmp keeps this cheap). A starnt::Error is the
// promised outcome for bad input; anything else that escapes (another exception, a crash, a
// sanitizer report) is a finding.
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "starnt/error.hpp"

namespace starnt::fuzz {

inline const std::filesystem::path& workDir() {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() / ("starnt_fuzz_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

inline std::filesystem::path writeFile(const std::string& name, std::string_view bytes) {
    const std::filesystem::path path = workDir() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
    return path;
}

// Splits the input at the first occurrence of `separator`: (before, after); no separator: (all, "").
inline std::pair<std::string_view, std::string_view> split(std::string_view data, std::string_view separator) {
    const size_t at = data.find(separator);
    if (at == std::string_view::npos) return {data, {}};
    return {data.substr(0, at), data.substr(at + separator.size())};
}

// Runs `load`; starnt::Error is fine, everything else propagates (libFuzzer reports it).
template <class F>
void expectCleanOutcome(F&& load) {
    try {
        load();
    } catch (const starnt::Error&) {
    }
}

}  // namespace starnt::fuzz
