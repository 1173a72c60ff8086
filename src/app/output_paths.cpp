#include <filesystem>

#include "app/commands.hpp"

namespace starnt::app {

namespace {
std::filesystem::path normalPath(const std::string& path) {
    std::error_code ec;
    // absolute() first: weakly_canonical leaves a relative path whose first part does not exist
    // as it is, so "a.png" and "./a.png" would differ.
    std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
    return ec ? std::filesystem::path(path).lexically_normal() : p;
}
}  // namespace

bool sameFile(const std::string& a, const std::string& b) { return a == b || normalPath(a) == normalPath(b); }

}  // namespace starnt::app
