// Helpers shared by the tests: where the suite scenes are, temporary folders, a GL context and a
// ready-to-render test scene.
#pragma once
#include <gtest/gtest.h>

#include "starnt/error.hpp"
#include <cctype>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/camera.hpp"

namespace starnt::test {

// ../shared/scenes beside the checkout (or STARNT_TEST_SCENES_DIR); empty path when absent (tests
// then skip with a message, STARNT_SKIP_WITHOUT_SHARED_SCENES).
std::filesystem::path sharedScenesDir();
// Whether the scene folder must be there: STARNT_TEST_REQUIRE_SCENES=1 (set by .ci/run), so that CI
// cannot pass green with the suite-scene tests skipped.
bool sharedScenesRequired();
// A fresh empty folder under the system temp dir, unique per call.
std::filesystem::path makeTempDir(const std::string& tag);
// `name` as a GoogleTest parameter name: every character but letters and digits becomes '_'
// ("starnt-residual" -> "starnt_residual").
inline std::string identifier(std::string name) {
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

}  // namespace starnt::test

// Skips the calling test (returns from it) when ../shared/scenes is absent, or fails it there when
// sharedScenesRequired(). `what` says what goes untested.
#define STARNT_SKIP_WITHOUT_SHARED_SCENES(what)                                                         \
    do {                                                                                               \
        if (::starnt::test::sharedScenesDir().empty()) {                                               \
            if (::starnt::test::sharedScenesRequired())                                                \
                FAIL() << "../shared/scenes not found and STARNT_TEST_REQUIRE_SCENES is set: " << what;  \
            GTEST_SKIP() << "../shared/scenes not found; " << what;                                    \
        }                                                                                              \
    } while (0)

namespace starnt {
class HeadlessGlContext;
}

namespace starnt::test {
// One headless GL context per test process, created on first use. GL errors raised while a test
// runs (KHR_debug) fail it, unless the test clears the ones it provoked with takeExpectedGlErrors().
HeadlessGlContext& glContext();
std::vector<std::string> takeExpectedGlErrors();  // and returns them
// Whether this context delivers KHR_debug error messages (the watch above runs only then).
bool glErrorsWatched();
}  // namespace starnt::test


namespace starnt::test {

// A scene on the GPU with a fixed orbit camera, size and background: what the GL tests render,
// capture and compare. Creates the test GL context on first use.
struct TestScene {
    Scene scene;
    Camera camera;
    std::unique_ptr<SceneGpu> gpu;
    int width = 0, height = 0;
    glm::vec3 background{1.0f};

    TestScene(Scene s, int w, int h, float azimuth, float elevation, glm::vec3 bg);
    float aspect() const { return float(width) / float(height); }
    FrameDesc frame() const;
    RenderOutput render(const std::string& method, const MethodOptions& options = {},
                        const SurfaceOptions& surface = {}) const;
    CapturedFrame capture(const SurfaceOptions& surface = {}) const;
};

}  // namespace starnt::test

namespace starnt::test {

// One run of the starnt binary (STARNT_CLI) with its exit code and captured output.
struct CliRun {
    int exitCode = -1;  // -1: did not exit normally (crash)
    std::string out, err;
};
CliRun run(const std::string& args);
// The same behind a shell prefix, e.g. "ulimit -v 1000000; " or "STARNT_PROGRESS_SECONDS=0 ".
CliRun run(const std::string& args, const std::string& shellPrefix);

// A bad invocation: non-zero exit (no crash), `mentions` on stderr, `mustNotExist` not written and
// no temporary file left in its folder.
void expectCleanFailure(const std::string& args, const std::filesystem::path& mustNotExist, const std::string& mentions);

}  // namespace starnt::test

namespace starnt::test {

// The message of the starnt::Error `fn` throws; a test failure (and "") when it throws nothing or
// another exception.
template <class F>
std::string errorOf(F&& fn) {
    try {
        fn();
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected starnt::Error, got another exception: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected starnt::Error, nothing was thrown";
    return {};
}


// Collects what the library logs (starnt::setLogCallback) while it lives, one "warning: ..." or
// "note: ..." line per message; restores no callback afterwards.
class CapturedLog {
public:
    CapturedLog();
    ~CapturedLog();
    CapturedLog(const CapturedLog&) = delete;
    CapturedLog& operator=(const CapturedLog&) = delete;
    std::string text() const;

private:
    std::shared_ptr<std::string> text_;
};

}  // namespace starnt::test
