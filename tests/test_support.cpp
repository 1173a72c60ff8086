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
    RenderJob job;
    job.method = method;
    job.methodOptions = options;
    job.width = width;
    job.height = height;
    job.camera = camera;
    job.background = background;
    job.surface = surface;
    return renderScene(*gpu, job);
}

CapturedFrame TestScene::capture(const SurfaceOptions& surface) const {
    FragmentCapture capturer(SceneGpu::surfaceShader());
    const FrameDesc f = frame();
    return capturer.capture(f, gpu->callback(f.view, f.projection, surface));
}

}  // namespace starnt::test
