// Helpers shared by the tests: where the suite scenes are, temporary folders.
#pragma once
#include <filesystem>
#include <string>

namespace starnt::test {

// ../shared/scenes beside the checkout; empty path when absent (tests then skip with a message).
std::filesystem::path sharedScenesDir();
// A fresh empty folder under the system temp dir, unique per call.
std::filesystem::path makeTempDir(const std::string& tag);

}  // namespace starnt::test

namespace starnt {
class HeadlessGlContext;
}

namespace starnt::test {
// One headless GL context per test process, created on first use.
HeadlessGlContext& glContext();
}  // namespace starnt::test
