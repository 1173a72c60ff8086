// What engines do to the library (docs/INTEGRATION.md, "Misuse"): no abort, a clear error or a
// correct image, and no GL error of the library's own. Every method, on a small built-in scene.
#include <gtest/gtest.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "methods/common/method_base.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/error.hpp"
#include "starnt/oit_method.hpp"
#include "test_support.hpp"

using namespace starnt;

namespace {

const glm::vec3 kBackground(0.875f, 0.75f, 0.625f);

// Drops every GL error queued so far and returns the first one (GL_NO_ERROR when none).
GLenum takeGlError() {
    const GLenum first = glGetError();
    while (glGetError() != GL_NO_ERROR) {
    }
    return first;
}

std::vector<glm::vec4> renderOnce(OitMethod& method, const test::TestScene& c) {
    const FrameDesc f = c.frame();
    method.render(f, c.gpu->callback(f.view, f.projection, {}));
    glFinish();
    const auto floats = gl::readTextureFloats(method.outputTexture(), c.width, c.height, 4);
    std::vector<glm::vec4> out(floats.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec4(floats[4 * i], floats[4 * i + 1], floats[4 * i + 2], floats[4 * i + 3]);
    return out;
}

float largestDifference(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    float d = 0.0f;
    for (size_t i = 0; i < a.size(); ++i)
        for (int ch = 0; ch < 3; ++ch) d = std::max(d, std::abs(a[i][ch] - b[i][ch]));
    return d;
}

// The methods an engine may create, with temporal frames for the neural ones (their temporal
// history is what the corrected frames add).
std::vector<std::pair<std::string, MethodOptions>> everyMethod() {
    std::vector<std::pair<std::string, MethodOptions>> out;
    for (const std::string& name : methodNames()) {
        out.emplace_back(name, MethodOptions{});
        if (name == "starnt" || name == "starnt-d") {
            MethodOptions temporal;
            temporal.neural.temporalInterval = 2;
            out.emplace_back(name, temporal);
        }
    }
    return out;
}

// The test's EGL context as it is current now, to make current again after a test changed it.
struct CurrentEgl {
    EGLDisplay display = eglGetCurrentDisplay();
    EGLContext context = eglGetCurrentContext();
    EGLSurface draw = eglGetCurrentSurface(EGL_DRAW), read = eglGetCurrentSurface(EGL_READ);
    bool restore() const { return eglMakeCurrent(display, draw, read, context); }
};

}  // namespace

// Without a current context: render() throws before any GL call, and destroying a method releases
// nothing (its objects die with their context) instead of aborting in the GL loader.
TEST(Misuse, NoCurrentContextIsAnErrorAndDestroyingIsSafe) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    const CurrentEgl egl;
    const EGLDisplay display = egl.display;
    const EGLContext context = egl.context;
    ASSERT_NE(context, EGL_NO_CONTEXT) << "the test context is EGL";
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        renderOnce(*method, c);
        const FrameDesc f = c.frame();
        const DrawCallback drawScene = c.gpu->callback(f.view, f.projection, {});
        ASSERT_TRUE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT));
        const std::string error = test::errorOf([&] { method->render(f, drawScene); });
        EXPECT_NE(error.find("no OpenGL context"), std::string::npos) << name << ": " << error;
        method.reset();  // must not abort
        ASSERT_TRUE(egl.restore());
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
    }
}

// Sizes no context can render: one error naming the size before anything is allocated; no GL error
// left for the engine, and the memory reported is what exists.
TEST(Misuse, AbsurdSizesFailBeforeAllocating) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        takeGlError();
        // 0x0 first: a method's size before its first frame is 0x0 too, and must not pass for "unchanged".
        for (const auto [w, h] : {std::pair{0, 0}, std::pair{20000, 20000}, std::pair{-64, 32}, std::pair{48, 0}}) {
            FrameDesc f = c.frame();
            f.width = w;
            f.height = h;
            const std::string error = test::errorOf([&] { method->render(f, c.gpu->callback(f.view, f.projection, {})); });
            EXPECT_NE(error.find(std::to_string(w) + "x" + std::to_string(h)), std::string::npos) << name << ": " << error;
            EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name << " " << w << "x" << h;
            EXPECT_LT(method->gpuMemoryBytes(), size_t(64) << 20) << name << ": memory that was never allocated";
        }
        // And it still renders at a sane size afterwards.
        const auto image = renderOnce(*method, c);
        EXPECT_EQ(image.size(), size_t(c.width * c.height)) << name;
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
    }
}

// resetHistory() before the first frame, and an engine callback that throws in the middle of a
// frame: no GL error raised by the library, and the next frame is right.
TEST(Misuse, ResetBeforeTheFirstFrameAndAThrowingCallback) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    for (auto& [name, options] : everyMethod()) {
        auto reference = createMethod(name, SceneGpu::surfaceShader(), options);
        const auto expected = renderOnce(*reference, c);
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        takeGlError();
        method->resetHistory();
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name << ": resetHistory before any frame";
        const FrameDesc f = c.frame();
        EXPECT_THROW(method->render(f, [](const GeometryPass&) { throw std::runtime_error("engine failure"); }), std::runtime_error);
        method->resetHistory();
        const auto image = renderOnce(*method, c);
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name << ": after a throwing callback";
        EXPECT_LE(largestDifference(image, expected), 1e-6f) << name;
        // A callback that draws and then throws: what it drew is not in the next frame (the
        // A-buffer's lists kept it when the next frame's clear was not ordered after its writes).
        const DrawCallback drawScene = c.gpu->callback(f.view, f.projection, {});
        EXPECT_THROW(method->render(f,
                                    [&](const GeometryPass& pass) {
                                        drawScene(pass);
                                        throw std::runtime_error("engine failure after drawing");
                                    }),
                     std::runtime_error);
        method->resetHistory();
        const auto afterDrawing = renderOnce(*method, c);
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name << ": after a callback that drew and threw";
        EXPECT_LE(largestDifference(afterDrawing, expected), 1e-6f) << name << ": after a callback that drew and threw";
    }
}

// State engines leave set that is not in INTEGRATION's preconditions: the methods set what their
// passes depend on, so the image is the undisturbed one.
TEST(Misuse, EngineStateLeftSetDoesNotChangeTheImage) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        const auto undisturbed = renderOnce(*method, c);
        method->resetHistory();
        if (epoxy_is_desktop_gl()) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);  // ES has no polygon mode
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(4.0f, 64.0f);
        glDepthRangef(0.5f, 1.0f);
        const auto disturbed = renderOnce(*method, c);
        EXPECT_LE(largestDifference(disturbed, undisturbed), 0.02f) << name;
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
        if (epoxy_is_desktop_gl()) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDepthRangef(0.0f, 1.0f);
    }
}

// State no pass sets for itself, left by an engine: a sampler object on every unit the methods read
// from (an integer target filtered linearly reads as 0), rasterizer discard (a transform-feedback
// pass) and a logic op. A real and an interpolated frame of every method: the undisturbed images.
TEST(Misuse, EngineSamplersDiscardAndLogicOpDoNotChangeTheImage) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    GLuint sampler = 0;
    glGenSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_REPEAT);
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        EXPECT_EQ(method->name(), name);
        std::vector<std::vector<glm::vec4>> undisturbed;
        for (int i = 0; i < 2; ++i) undisturbed.push_back(renderOnce(*method, c));
        method->resetHistory();
        for (int i = 0; i < 2; ++i) {
            for (GLuint unit = 0; unit < 16; ++unit) glBindSampler(unit, sampler);
            glEnable(GL_RASTERIZER_DISCARD);
            if (epoxy_is_desktop_gl()) {
                glEnable(GL_COLOR_LOGIC_OP);
                glLogicOp(GL_XOR);
            }
            const auto disturbed = renderOnce(*method, c);
            glDisable(GL_RASTERIZER_DISCARD);  // (before anything of the test's own is drawn)
            if (epoxy_is_desktop_gl()) glDisable(GL_COLOR_LOGIC_OP);
            EXPECT_LE(largestDifference(disturbed, undisturbed[i]), 1e-6f) << name << ", frame " << i;
            EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
            GLint bound = 0;
            glActiveTexture(GL_TEXTURE9);
            glGetIntegerv(GL_SAMPLER_BINDING, &bound);
            glActiveTexture(GL_TEXTURE0);
            EXPECT_EQ(GLuint(bound), sampler) << name << ": the engine's units 9 and above are its own";
        }
        for (GLuint unit = 0; unit < 16; ++unit) glBindSampler(unit, 0);
    }
    glDeleteSamplers(1, &sampler);
}

// More state engines leave set, each of which changed an image before the methods guarded it: an
// unpack skip (Mesa applies it to glClearNamedBufferData's one value: the A-buffer's cleared heads
// were read past the value, MSE 0.115 or a 45 GB pool), a line offset (llvmpipe offsets filled
// triangles by it: the neural methods' MSE x13-62), a query buffer (peel's occlusion results went
// into it: MSE 0.043). The engine's values are there after render().
TEST(Misuse, EngineUnpackSkipsLineOffsetAndQueryBufferDoNotChangeTheImage) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    const bool desktop = epoxy_is_desktop_gl();
    GLuint queryBuffer = 0;
    if (desktop) {
        glCreateBuffers(1, &queryBuffer);
        glNamedBufferStorage(queryBuffer, 64, nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        std::vector<std::vector<glm::vec4>> undisturbed;
        for (int i = 0; i < 2; ++i) undisturbed.push_back(renderOnce(*method, c));
        method->resetHistory();
        for (int i = 0; i < 2; ++i) {
            glPixelStorei(GL_UNPACK_SKIP_PIXELS, 2);
            glPixelStorei(GL_UNPACK_SKIP_ROWS, 3);
            glPixelStorei(GL_PACK_SKIP_PIXELS, 1);
            if (desktop) {
                glEnable(GL_POLYGON_OFFSET_LINE);
                glEnable(GL_POLYGON_OFFSET_POINT);
                glPolygonOffset(5.0f, 5.0f);
                glBindBuffer(GL_QUERY_BUFFER, queryBuffer);
            }
            const auto disturbed = renderOnce(*method, c);  // (its read-back packs with the skip set too)
            GLint skipPixels = 0, skipRows = 0, packSkip = 0, boundQueryBuffer = 0;
            glGetIntegerv(GL_UNPACK_SKIP_PIXELS, &skipPixels);
            glGetIntegerv(GL_UNPACK_SKIP_ROWS, &skipRows);
            glGetIntegerv(GL_PACK_SKIP_PIXELS, &packSkip);
            if (desktop) glGetIntegerv(GL_QUERY_BUFFER_BINDING, &boundQueryBuffer);
            glPixelStorei(GL_UNPACK_SKIP_PIXELS, 0);
            glPixelStorei(GL_UNPACK_SKIP_ROWS, 0);
            glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
            if (desktop) {
                glDisable(GL_POLYGON_OFFSET_LINE);
                glDisable(GL_POLYGON_OFFSET_POINT);
                glPolygonOffset(0.0f, 0.0f);
                glBindBuffer(GL_QUERY_BUFFER, 0);
            }
            EXPECT_LE(largestDifference(disturbed, undisturbed[i]), 1e-6f) << name << ", frame " << i;
            EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
            EXPECT_EQ(skipPixels, 2) << name;
            EXPECT_EQ(skipRows, 3) << name;
            EXPECT_EQ(packSkip, 1) << name;
            if (desktop) EXPECT_EQ(GLuint(boundQueryBuffer), queryBuffer) << name;
        }
    }
    if (desktop) glDeleteBuffers(1, &queryBuffer);
}

// A draw callback that throws: the timing hook's calls stay nested (endGeometry, then endPass), so
// a hook that brackets the draws with a query does not begin its next frame inside it.
TEST(Misuse, AThrowingCallbackClosesTheHooksBrackets) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    struct Hook final : PassTimingHook {
        std::vector<std::string> open;  // "pass" / "geometry", innermost last
        bool nested = true;
        void beginPass(const std::string&) override { open.push_back("pass"); }
        void endPass() override { close("pass"); }
        void beginGeometry(const std::string&) override { open.push_back("geometry"); }
        void endGeometry() override { close("geometry"); }
        void close(const char* what) {
            nested = nested && !open.empty() && open.back() == what;
            if (!open.empty()) open.pop_back();
        }
    };
    for (const std::string name : {"wboit", "peel", "starnt-d", "recommended"}) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), MethodOptions{});
        for (int call = 1; call <= 3; ++call) {
            Hook hook;
            FrameDesc f = c.frame();
            f.timing = &hook;
            int calls = 0;
            std::string error;
            try {
                method->render(f, [&](const GeometryPass& pass) {
                    if (++calls == call) throw std::runtime_error("engine failure");
                    c.gpu->callback(f.view, f.projection, {})(pass);
                });
            } catch (const std::runtime_error& e) {
                error = e.what();
            }
            if (calls < call) continue;  // the method draws fewer times
            EXPECT_NE(error.find("engine failure"), std::string::npos) << name;
            EXPECT_TRUE(hook.nested) << name << ", throwing on draw " << call;
            EXPECT_TRUE(hook.open.empty()) << name << ", throwing on draw " << call << ": " << hook.open.size() << " left open";
            method->resetHistory();
        }
    }
}

// GL runs one occlusion query at a time: with the engine's active, peel (which counts each layer's
// samples with one) says so instead of raising a GL error on every layer and ending the engine's.
TEST(Misuse, PeelRefusesAnEnginesActiveOcclusionQuery) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    auto method = createMethod("peel", SceneGpu::surfaceShader(), MethodOptions{});
    const auto expected = renderOnce(*method, c);
    GLuint query = 0;
    glGenQueries(1, &query);
    glBeginQuery(GL_ANY_SAMPLES_PASSED, query);
    const FrameDesc f = c.frame();
    const std::string error = test::errorOf([&] { method->render(f, c.gpu->callback(f.view, f.projection, {})); });
    EXPECT_NE(error.find("GL_ANY_SAMPLES_PASSED query is active"), std::string::npos) << error;
    glEndQuery(GL_ANY_SAMPLES_PASSED);  // the engine's query is still its own to end
    EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR));
    glDeleteQueries(1, &query);
    EXPECT_LE(largestDifference(renderOnce(*method, c), expected), 1e-6f);
}

// A method used with another context current (one of its own, or one sharing the method's objects):
// an error before any draw, not GL errors or another context's objects touched by coincident names.
TEST(Misuse, AnotherContextCurrentIsAnError) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    const CurrentEgl egl;
    const EGLDisplay display = egl.display;
    const EGLContext context = egl.context;
    ASSERT_NE(context, EGL_NO_CONTEXT) << "the test context is EGL";
    EGLint configId = 0, clientType = 0;
    eglQueryContext(display, context, EGL_CONFIG_ID, &configId);
    eglQueryContext(display, context, EGL_CONTEXT_CLIENT_TYPE, &clientType);
    EGLConfig config = EGL_NO_CONFIG_KHR;
    EGLint found = 0;
    const EGLint byId[] = {EGL_CONFIG_ID, configId, EGL_NONE};
    if (configId == 0 || !eglChooseConfig(display, byId, &config, 1, &found) || found == 0) config = EGL_NO_CONFIG_KHR;
    const bool es = clientType == EGL_OPENGL_ES_API;
    ASSERT_TRUE(eglBindAPI(EGLenum(clientType)));
    const std::vector<EGLint> attribs = es ? std::vector<EGLint>{EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 2, EGL_NONE}
                                           : std::vector<EGLint>{EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    // One context of its own, and one sharing the method's objects: buffers and textures are
    // shared, its framebuffers and vertex arrays are not, so the method cannot run there either.
    const EGLContext separate = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs.data());
    const EGLContext sharing = eglCreateContext(display, config, context, attribs.data());
    ASSERT_NE(separate, EGL_NO_CONTEXT);
    ASSERT_NE(sharing, EGL_NO_CONTEXT);
    for (const auto& [name, other] : {std::pair{"wboit", separate}, std::pair{"peel", separate}, std::pair{"recommended", separate},
                                      std::pair{"wboit", sharing}, std::pair{"recommended", sharing}}) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), MethodOptions{});
        const auto expected = renderOnce(*method, c);
        const FrameDesc f = c.frame();
        const DrawCallback drawScene = c.gpu->callback(f.view, f.projection, {});
        ASSERT_TRUE(eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, other));
        // Names in the other context that coincide with the method's.
        std::vector<GLuint> buffers(64);
        glGenBuffers(GLsizei(buffers.size()), buffers.data());
        for (GLuint b : buffers) glBindBuffer(GL_ARRAY_BUFFER, b);
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        const std::string error = test::errorOf([&] { method->render(f, drawScene); });
        EXPECT_NE(error.find("not the one this method was created in"), std::string::npos) << name << ": " << error;
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name << ": in the other context";
        glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
        ASSERT_TRUE(egl.restore());
        method->resetHistory();  // (the refused frame aborted: the next one is real again)
        EXPECT_LE(largestDifference(renderOnce(*method, c), expected), 1e-6f) << name << ": back in its own context";
        EXPECT_EQ(takeGlError(), GLenum(GL_NO_ERROR)) << name;
    }
    eglDestroyContext(display, separate);
    eglDestroyContext(display, sharing);
}

// The suite's GL tests fail on any GL error raised while they run (test_support.cpp, KHR_debug):
// the watch itself sees an error provoked on purpose.
TEST(Misuse, TheSuiteSeesGlErrors) {
    // Desktop GL 4.5 and ES 3.2 both deliver KHR_debug messages on Mesa (the ES runs too).
    ASSERT_TRUE(test::glErrorsWatched()) << "this context delivers no KHR_debug error messages";
    test::takeExpectedGlErrors();
    glDisable(0xBAD1);  // not a capability: GL_INVALID_ENUM on both APIs
    EXPECT_EQ(takeGlError(), GLenum(GL_INVALID_ENUM));
    const std::vector<std::string> seen = test::takeExpectedGlErrors();
    EXPECT_FALSE(seen.empty()) << "the KHR_debug watch missed a GL error";
}

// A process with a desktop context and an ES one (an editor and its preview): the ES context's clip
// control is read there, whichever API read its convention first.
TEST(Misuse, AnEsContextReadsItsOwnClipControlAfterADesktopContext) {
    test::glContext();
    glm::mat4 reversed = glm::perspective(glm::radians(50.0f), 1.5f, 0.1f, 10.0f);
    reversed = glm::mat4(1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, -0.5f, 0.0f, 0.0f, 0.0f, 0.5f, 1.0f) * reversed;
    {
        HeadlessGlContext desktop(GlApi::Desktop);
        desktop.makeCurrent();
        EXPECT_FALSE(readDepthConvention(reversed).zeroToOne);
        HeadlessGlContext es(GlApi::Es);
        es.makeCurrent();
        if (!epoxy_has_gl_extension("GL_EXT_clip_control")) {
            test::glContext();
            GTEST_SKIP() << "no GL_EXT_clip_control";
        }
        glClipControlEXT(GL_LOWER_LEFT_EXT, GL_ZERO_TO_ONE_EXT);
        const DepthConvention c = readDepthConvention(reversed);
        EXPECT_TRUE(c.zeroToOne) << "the ES context's GL_ZERO_TO_ONE";
        EXPECT_TRUE(c.reversed);
        glClipControlEXT(GL_LOWER_LEFT_EXT, GL_NEGATIVE_ONE_TO_ONE_EXT);
    }
    test::glContext();
}

// An error the engine left pending is still there for it after render(): the library does not read
// glGetError on its way (its allocations ask the buffer's size instead).
TEST(Misuse, AGlErrorLeftPendingByTheEngineStaysPending) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 48, 32, 30.0f, 15.0f, kBackground);
    const bool watched = test::glErrorsWatched();
    for (auto& [name, options] : everyMethod()) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), options);
        takeGlError();
        glEnable(GLenum(0xBAD0));  // not a capability: GL_INVALID_ENUM, left pending
        renderOnce(*method, c);  // the first frame allocates every target
        EXPECT_EQ(takeGlError(), GLenum(GL_INVALID_ENUM)) << name;
        if (watched) test::takeExpectedGlErrors();
    }
}

// An initial A-buffer pool that is no number of nodes: one error naming the option.
TEST(Misuse, AnAbsurdInitialABufferPoolIsAnError) {
    test::glContext();
    for (double nodes : {-1.0, std::nan(""), 1e30}) {
        MethodOptions o;
        o.abuffer.initialNodesPerPixel = nodes;
        const std::string error = test::errorOf([&] { createMethod("abuffer", SceneGpu::surfaceShader(), o); });
        EXPECT_NE(error.find("initialNodesPerPixel"), std::string::npos) << nodes << ": " << error;
    }
    MethodOptions none;
    none.abuffer.initialNodesPerPixel = 0.0;  // grows from the smallest pool
    EXPECT_NO_THROW(createMethod("abuffer", SceneGpu::surfaceShader(), none));
}
