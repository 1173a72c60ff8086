#include "test_support.hpp"

#include <atomic>
#include <unistd.h>

namespace starnt::test {

std::filesystem::path sharedScenesDir() {
    std::filesystem::path p(STARNT_SHARED_SCENES);
    std::error_code ec;
    return std::filesystem::is_directory(p, ec) ? std::filesystem::canonical(p) : std::filesystem::path();
}

std::filesystem::path makeTempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    auto dir = std::filesystem::temp_directory_path() /
               ("starnt_test_" + tag + "_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace starnt::test

#include "starnt/gl_context.hpp"

namespace starnt::test {
HeadlessGlContext& glContext() {
    static HeadlessGlContext* context = new HeadlessGlContext();  // lives until exit
    context->makeCurrent();
    return *context;
}
}  // namespace starnt::test
