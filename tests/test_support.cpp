#include "test_support.hpp"

#include "starnt/log.hpp"

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <sys/wait.h>

#include <gtest/gtest.h>
#include <unistd.h>

namespace starnt::test {

std::filesystem::path sharedScenesDir() {
    // STARNT_TEST_SCENES_DIR replaces the folder (a missing one shows what the tests do without it).
    const char* dir = std::getenv("STARNT_TEST_SCENES_DIR");
    std::filesystem::path p(dir && *dir ? dir : STARNT_SHARED_SCENES);
    std::error_code ec;
    return std::filesystem::is_directory(p, ec) ? std::filesystem::canonical(p) : std::filesystem::path();
}

bool sharedScenesRequired() {
    const char* v = std::getenv("STARNT_TEST_REQUIRE_SCENES");
    return v && *v && std::string(v) != "0";
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

#include "starnt/tools/gl_context.hpp"

#include <epoxy/gl.h>

#include <cstdio>
#include <string>
#include <vector>

namespace starnt::test {
namespace {

// GL errors of the running test, from the context's KHR_debug output (docs/INTEGRATION.md: the
// library raises no GL error in any documented call sequence). A test that provokes one on purpose
// clears them with takeExpectedGlErrors().
std::vector<std::string>& glErrorsSeen() {
    static std::vector<std::string> errors;
    return errors;
}

void GLAPIENTRY onGlDebugMessage(GLenum, GLenum type, GLuint, GLenum, GLsizei, const GLchar* message, const void*) {
    if (type == GL_DEBUG_TYPE_ERROR && glErrorsSeen().size() < 16) glErrorsSeen().emplace_back(message);
}

// Fails the test process when a test raised a GL error (a listener cannot mark the test failed
// once it has ended; the non-zero exit fails it in CTest, which runs one test per process).
class GlErrorListener : public ::testing::EmptyTestEventListener {
    void OnTestStart(const ::testing::TestInfo&) override { glErrorsSeen().clear(); }
    void OnTestEnd(const ::testing::TestInfo& info) override {
        if (glErrorsSeen().empty()) return;
        std::fprintf(stderr, "FAILED: %s.%s raised %zu GL error(s) (KHR_debug):\n", info.test_suite_name(), info.name(),
                     glErrorsSeen().size());
        for (const auto& e : glErrorsSeen()) std::fprintf(stderr, "  %s\n", e.c_str());
        std::fflush(stderr);
        std::_Exit(3);
    }
};

bool gWatching = false;

// Watches where the context delivers error messages: checked by provoking one. The probe is an
// invalid enum, an error on desktop GL and ES alike (binding a never-generated buffer name, the
// probe before, is an error on a core desktop context only: ES creates the buffer, so the ES runs
// went unwatched).
void watchGlErrors() {
    const bool debug = epoxy_is_desktop_gl() ? epoxy_gl_version() >= 43 : epoxy_gl_version() >= 32;
    if (!debug) return;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onGlDebugMessage, nullptr);
    glEnable(0xBAD0);  // not a capability: GL_INVALID_ENUM
    while (glGetError() != GL_NO_ERROR) {
    }
    gWatching = !glErrorsSeen().empty();
    glErrorsSeen().clear();
    if (gWatching) ::testing::UnitTest::GetInstance()->listeners().Append(new GlErrorListener);
}

}  // namespace

bool glErrorsWatched() {
    glContext();
    return gWatching;
}

std::vector<std::string> takeExpectedGlErrors() {
    std::vector<std::string> taken;
    taken.swap(glErrorsSeen());
    return taken;
}

HeadlessGlContext& glContext() {
    // STARNT_TEST_GL_API=gles runs a GL test executable on an OpenGL ES 3.2 context instead (CTest
    // registers the GL tests a second time that way, as Gles.*).
    static HeadlessGlContext* context = [] {
        const char* api = std::getenv("STARNT_TEST_GL_API");
        auto* made = new HeadlessGlContext(api ? parseGlApi(api) : GlApi::Desktop);
        made->makeCurrent();
        watchGlErrors();
        return made;
    }();  // lives until exit
    context->makeCurrent();
    return *context;
}
}  // namespace starnt::test

namespace starnt::test {

TestScene::TestScene(Scene s, int w, int h, float azimuth, float elevation, glm::vec3 bg)
    : scene(std::move(s)), width(w), height(h), background(bg) {
    glContext();
    camera = orbitCamera(scene.bounds(), azimuth, elevation, aspect());
    gpu = std::make_unique<SceneGpu>(scene);
}

FrameDesc TestScene::frame() const {
    FrameDesc f;
    f.width = width;
    f.height = height;
    f.background = background;
    f.view = camera.view();
    f.projection = camera.projection(aspect());
    return f;
}

RenderOutput TestScene::render(const std::string& method, const MethodOptions& options,
                               const SurfaceOptions& surface) const {
    RenderJob job = sizedJob(width, height, 1, 0, background, 0.03f);
    job.method = method;
    job.methodOptions = options;
    job.camera = camera;
    job.surface = surface;
    return renderScene(*gpu, job);
}

CapturedFrame TestScene::capture(const SurfaceOptions& surface) const {
    FragmentCapture capturer(SceneGpu::surfaceShader());
    const FrameDesc f = frame();
    return capturer.capture(f, gpu->callback(f.view, f.projection, surface));
}

}  // namespace starnt::test

namespace starnt::test {

CliRun run(const std::string& args) { return run(args, ""); }

CliRun run(const std::string& args, const std::string& shellPrefix) {
    namespace fs = std::filesystem;
    fs::path dir = makeTempDir("cli_io");
    std::string cmd = shellPrefix + std::string(STARNT_CLI) + " " + args + " >" + (dir / "out").string() + " 2>" + (dir / "err").string();
    int status = std::system(cmd.c_str());
    CliRun r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    auto slurp = [](const fs::path& p) {
        std::ifstream f(p);
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    r.out = slurp(dir / "out");
    r.err = slurp(dir / "err");
    fs::remove_all(dir);
    return r;
}

void expectCleanFailure(const std::string& args, const std::filesystem::path& mustNotExist, const std::string& mentions) {
    CliRun r = run(args);
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_NE(r.exitCode, -1) << "crashed: " << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_NE(r.err.find(mentions), std::string::npos) << "stderr of `" << args << "` was: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(mustNotExist)) << args;
    for (const auto& e : std::filesystem::directory_iterator(mustNotExist.parent_path())) {
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
    }
}

CapturedLog::CapturedLog() : text_(std::make_shared<std::string>()) {
    setLogCallback([text = text_](LogLevel level, const std::string& message) {
        *text += (level == LogLevel::Warning ? "warning: " : "note: ") + message + "\n";
    });
}
CapturedLog::~CapturedLog() { setLogCallback(nullptr); }
std::string CapturedLog::text() const { return *text_; }

}  // namespace starnt::test
