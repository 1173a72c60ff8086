// What the opaque depth saves (docs/DESIGN.md, "Opaque geometry"): the built-in courtyard (opaque
// floor, wall and pillars with transparent parts in front and behind) rendered by each method with
// FrameDesc::opaqueDepth given and without it (the same opaque colour as background either way),
// interleaved frame by frame at one camera, glFinish + wall clock, median over the timed frames.
// Also the fragments each pass shaded (pipeline statistics) and the samples that passed its tests
// (GL_SAMPLES_PASSED): llvmpipe counts fragment-shader invocations before its early depth test.
//   build/starnt_opaque_clip_study [WIDTH HEIGHT FRAMES METHOD,...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "gl/gpu_timer.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/error.hpp"
#include "starnt/oit_method.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/scene.hpp"

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
    using namespace starnt;
    const int width = argc > 2 ? std::atoi(argv[1]) : 1280, height = argc > 2 ? std::atoi(argv[2]) : 720;
    const int frames = argc > 3 ? std::atoi(argv[3]) : 8;
    std::vector<std::string> methods = {"wboit", "abuffer", "dfaoit", "starnt-d"};
    if (argc > 4) {
        methods.clear();
        std::string list = argv[4];
        for (size_t p = 0; p <= list.size();) {
            const size_t q = std::min(list.find(',', p), list.size());
            if (q > p) methods.push_back(list.substr(p, q - p));
            p = q + 1;
        }
    }
    try {
        HeadlessGlContext context(GlApi::Desktop);
        const Scene scene = makeBuiltinScene("courtyard", 1);
        const SceneGpu gpu(scene);
        const Camera camera = orbitCamera(scene.bounds(), 20.0f, 15.0f, float(width) / float(height));
        FrameDesc frame;
        frame.width = width;
        frame.height = height;
        frame.view = camera.view();
        frame.projection = camera.projection(float(width) / float(height));
        gpu.drawOpaque(frame, {});
        const GLuint opaqueDepth = frame.opaqueDepth;
        const DrawCallback draw = gpu.callback(frame.view, frame.projection, {});
        gl::GpuPassTimer counters(true);
        GLuint query = 0;
        glGenQueries(1, &query);
        std::printf("courtyard %dx%d, %d timed frames each, interleaved; %s\n", width, height, frames,
                    reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
        std::printf("| method | ms without opaque depth | ms with | ratio | fragments shaded without / with | samples passed without / with |\n|---|---|---|---|---|---|\n");
        for (const std::string& name : methods) {
            auto method = createMethod(name, SceneGpu::surfaceShader());
            std::map<bool, std::vector<double>> ms;
            std::map<bool, double> shaded, passed;
            for (int i = 0; i < frames + 2; ++i) {
                for (bool clip : {false, true}) {
                    FrameDesc f = frame;
                    f.opaqueDepth = clip ? opaqueDepth : 0;
                    f.timing = i == 0 ? &counters : nullptr;
                    glFinish();
                    const auto t0 = std::chrono::steady_clock::now();
                    if (i == 1) glBeginQuery(GL_SAMPLES_PASSED, query);
                    method->render(f, draw);
                    if (i == 1) glEndQuery(GL_SAMPLES_PASSED);
                    glFinish();
                    const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                    if (i == 0) {
                        counters.collect();
                        double sum = 0.0;
                        for (const auto& [pass, c] : counters.collectCounters()) sum += double(c.fragmentInvocations);
                        shaded[clip] = sum;
                    } else if (i == 1) {
                        GLuint samples = 0;
                        glGetQueryObjectuiv(query, GL_QUERY_RESULT, &samples);
                        passed[clip] = double(samples);
                    } else {
                        ms[clip].push_back(t);  // frames 0 and 1 compile shaders and count
                    }
                }
            }
            const double off = median(ms[false]), on = median(ms[true]);
            std::printf("| %s | %.1f | %.1f | %.2f | %.0f / %.0f | %.0f / %.0f |\n", name.c_str(), off, on, on / off, shaded[false],
                        shaded[true], passed[false], passed[true]);
        }
        glDeleteQueries(1, &query);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "opaque_clip_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
