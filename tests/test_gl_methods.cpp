// The classic methods on a real GL context against the CPU references.
#include <gtest/gtest.h>

#include <cmath>

#include "gl/gl_util.hpp"
#include "gl/target_clears.hpp"
#include "reference/cpu_raster.hpp"
#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/families.hpp"
#include "test_support.hpp"

using namespace starnt;

namespace {

constexpr int kW = 96, kH = 72;
const glm::vec3 kBackground(0.2f, 0.5f, 0.9f);

using SceneSetup = test::TestScene;

SceneSetup makeSetup(const std::string& builtin, float azimuth = 20.0f) {
    return SceneSetup(makeBuiltinScene(builtin, 7), kW, kH, azimuth, 10.0f, kBackground);
}

RenderOutput render(const SceneSetup& s, const std::string& method, MethodOptions options = {}) {
    return s.render(method, options);
}

CpuRaster cpuReference(const SceneSetup& s) {
    return rasterizeUnlit(s.scene, s.camera.view(), s.camera.projection(s.aspect()), kW, kH, 0.03f);
}

// Compares the GPU image with `expected(list)` on every unambiguous pixel; returns pixels compared.
template <typename F>
size_t expectMatchesReference(const Image& gpu, const CpuRaster& ref, F expected, float tolerance = 1.0f / 255.0f) {
    EXPECT_FALSE(ref.clipped);
    size_t compared = 0, bad = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (ref.ambiguous[size_t(y) * kW + size_t(x)]) continue;
            glm::vec3 want = expected(ref.frame.at(x, y));
            const float* got = gpu.pixel(x, y);
            ++compared;
            for (int c = 0; c < 3; ++c) {
                if (!(std::abs(got[c] - want[c]) <= tolerance)) {
                    if (++bad <= 5) {
                        ADD_FAILURE() << "pixel (" << x << "," << y << ") channel " << c << ": gpu " << got[c]
                                      << " cpu " << want[c] << " (" << ref.frame.at(x, y).size() << " fragments)";
                    }
                }
            }
        }
    }
    EXPECT_EQ(bad, 0u);
    return compared;
}

glm::vec3 exactComposite(FragmentList list) {
    sortByDepth(list);
    return compositeOver(list, kBackground);
}

}  // namespace

// Memory accounting knows every format the methods allocate; any other is an internal error that
// names the format as GL headers spell it (it printed the decimal value after "0x" before).
TEST(GlMethods, TextureBytesPerTexelAndUnknownFormats) {
    EXPECT_EQ(gl::bytesPerTexel(GL_RGBA16F), 8u);
    EXPECT_EQ(gl::bytesPerTexel(GL_R16F), 2u);
    EXPECT_EQ(gl::bytesPerTexel(GL_DEPTH_COMPONENT32F), 4u);
    try {
        gl::bytesPerTexel(GL_RGB8);
        ADD_FAILURE() << "GL_RGB8 is not a format the methods use";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("0x8051"), std::string::npos) << e.what();
    }
}

TEST(GlMethods, AbufferMatchesCpuCompositorOnRandomTriangles) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    ASSERT_GE(ref.frame.maxDepthComplexity(), 4u) << "the scene should overlap";
    size_t n = expectMatchesReference(render(s, "abuffer").image, ref, exactComposite);
    EXPECT_GT(n, size_t(kW * kH) / 2);
}

TEST(GlMethods, PeelMatchesCpuCompositorOnRandomTriangles) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    RenderOutput out = render(s, "peel");
    expectMatchesReference(out.image, ref, exactComposite);
    EXPECT_EQ(out.stats["method_stats"]["layers"].get<size_t>(), out.stats["max_fragments"].get<size_t>());
}

TEST(GlMethods, AbufferMatchesCpuCompositorOnPanes) {
    SceneSetup s = makeSetup("panes", 0.0f);
    expectMatchesReference(render(s, "abuffer").image, cpuReference(s), exactComposite);
}

TEST(GlMethods, UnsortedMatchesSubmissionOrderBlend) {
    SceneSetup s = makeSetup("random");
    expectMatchesReference(render(s, "unsorted").image, cpuReference(s), [](FragmentList list) {
        // Later submissions land on top: composite newest first.
        sortBySubmission(list);
        std::reverse(list.begin(), list.end());
        return compositeOver(list, kBackground);
    });
}

TEST(GlMethods, WboitMatchesMcGuireBavoilFormula) {
    SceneSetup s = makeSetup("random");
    expectMatchesReference(render(s, "wboit").image, cpuReference(s),
                           [](const FragmentList& list) { return nn::compositeWboit(list, kBackground); });
}

TEST(GlMethods, CaptureSeesTheSameFragmentsAsTheCpuRasteriser) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    CapturedFrame got = s.capture();
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (ref.ambiguous[size_t(y) * kW + size_t(x)]) continue;
            FragmentList a = got.at(x, y), b = ref.frame.at(x, y);
            ASSERT_EQ(a.size(), b.size()) << "pixel " << x << "," << y;
            sortBySubmission(a);
            sortBySubmission(b);
            for (size_t i = 0; i < a.size(); ++i) {
                EXPECT_EQ(a[i].order, b[i].order);
                EXPECT_NEAR(a[i].depth, b[i].depth, 1e-5f);
                EXPECT_NEAR(a[i].alpha, b[i].alpha, 1e-3f);
            }
        }
    }
}

TEST(GlMethods, AbufferPoolFarTooSmallStillGivesTheExactImage) {
    SceneSetup s = makeSetup("random");
    MethodOptions tiny;
    tiny.abuffer.initialNodesPerPixel = 0.01;
    // The regrow note goes to the engine's log callback (never to stderr from the library).
    testing::internal::CaptureStderr();
    std::string logged;
    RenderOutput small;
    {
        test::CapturedLog log;
        small = render(s, "abuffer", tiny);
        logged = log.text();
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_NE(logged.find("note: A-buffer pool overflow"), std::string::npos) << logged;
    RenderOutput normal = render(s, "abuffer");
    EXPECT_GE(small.stats["method_stats"]["pool_regrows"].get<int>(), 1);
    EXPECT_EQ(normal.stats["method_stats"]["pool_regrows"].get<int>(), 0);
    ASSERT_EQ(small.image.rgba.size(), normal.image.rgba.size());
    for (size_t i = 0; i < small.image.rgba.size(); ++i) ASSERT_EQ(small.image.rgba[i], normal.image.rgba[i]);
}

TEST(GlMethods, AbufferMemoryCapFailsWithClearError) {
    SceneSetup s = makeSetup("random");
    MethodOptions capped;
    capped.abuffer.initialNodesPerPixel = 0.01;
    capped.abuffer.memoryCapBytes = size_t(kW) * kH * 4 + 4096;
    try {
        render(s, "abuffer", capped);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("memory cap"), std::string::npos) << e.what();
    }
}

TEST(GlMethods, TypedFrameStatsFillTheirMethodsGroupOnly) {
    SceneSetup s = makeSetup("random");
    const CapturedFrame captured = s.capture();
    size_t fragments = 0;
    for (const auto& list : captured.pixels) fragments += list.size();
    const FrameDesc frame = s.frame();
    for (const std::string m : {"abuffer", "peel", "mboit", "wboit", "starnt"}) {
        auto method = createMethod(m, SceneGpu::surfaceShader());
        method->render(frame, s.gpu->callback(frame.view, frame.projection, {}));
        const FrameStats st = method->lastFrameStats();
        EXPECT_EQ(st.abuffer.has_value(), m == "abuffer") << m;
        EXPECT_EQ(st.peel.has_value(), m == "peel") << m;
        EXPECT_EQ(st.mboit.has_value(), m == "mboit") << m;
        EXPECT_EQ(st.neural.has_value(), m == "starnt") << m;
        EXPECT_FALSE(st.interpolated()) << m;
        if (st.abuffer) EXPECT_EQ(st.abuffer->fragments, fragments) << m;
        if (st.peel) EXPECT_EQ(size_t(st.peel->layers), captured.maxDepthComplexity()) << m;
        if (st.neural) {
            EXPECT_EQ(st.neural->network, "starnt");
            ASSERT_TRUE(st.neural->tiles.has_value());  // starnt runs its tiles by default
            EXPECT_EQ(st.neural->pass2Size.width, frame.width);  // first frame: full resolution
            EXPECT_EQ(st.neural->scalePass3, 1.0f);
        }
    }
}

TEST(GlMethods, StatsReportMemoryAndFragments) {
    SceneSetup s = makeSetup("random");
    for (const char* m : {"abuffer", "peel", "unsorted", "wboit"}) {
        RenderOutput out = render(s, m);
        EXPECT_GE(out.stats["memory_bytes"].get<size_t>(), size_t(kW) * kH * 16) << m;
        EXPECT_EQ(out.stats["max_fragments"].get<size_t>(), cpuReference(s).frame.maxDepthComplexity()) << m;
    }
}

// gl::TargetClears: on llvmpipe a clear of a 16-byte target becomes copies from a strip
// (docs/DESIGN.md, "Findings on Mesa llvmpipe": clears). The copies must write exactly what
// glClearBufferfv writes under the same state: the scissor box (or the whole target), the value as
// the clear converts it, nothing else; and leave the bindings as they were.
TEST(TargetClears, CopiesWriteWhatTheClearWrites) {
    test::glContext();
    constexpr int w = 70, h = 37;  // not a multiple of the strip (16 x 4 below): partial strips
    std::vector<float> garbage(size_t(w) * h * 4);
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = float(i % 97) * 0.25f - 3.0f;
    const float packedEmpty[4] = {1.5e9f, -2.0f, 0.125f, 7.0f};
    struct Case {
        GLenum format;
        bool scissor;
        bool mask;  // a colour mask on the cleared buffer
    } cases[] = {{GL_RGBA32F, true, false}, {GL_RGBA32F, false, false}, {GL_RGBA32F, true, true}, {GL_RGBA16F, true, false}};
    for (const Case& c : cases) {
        SCOPED_TRACE(testing::Message() << "format 0x" << std::hex << c.format << " scissor " << c.scissor << " mask " << c.mask);
        gl::Texture2D targets[2] = {gl::Texture2D(c.format, w, h), gl::Texture2D(c.format, w, h)};
        gl::TargetClears clears[2] = {gl::TargetClears(gl::TargetClears::Path::Copy, 16, 4),
                                      gl::TargetClears(gl::TargetClears::Path::Clear)};
        gl::Texture2D other(GL_RGBA8, w, h), bound(GL_RGBA8, 4, 4);
        for (int k = 0; k < 2; ++k) {
            gl::uploadTexture(targets[k].id(), w, h, GL_RGBA, GL_FLOAT, garbage.data());
            const gl::FramebufferHandle fb = gl::makeFramebuffer({&other, &targets[k]});  // the target at draw buffer 1
            glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
            glActiveTexture(GL_TEXTURE3);  // the active unit's binding, which the copy must leave
            glBindTexture(GL_TEXTURE_2D, bound.id());
            if (c.scissor) {
                glEnable(GL_SCISSOR_TEST);
                glScissor(5, 3, 50, 30);
            }
            if (c.mask) glColorMaski(1, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
            clears[k].color(1, packedEmpty);
            GLint drawFb = 0, unitBinding = 0;
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFb);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &unitBinding);
            EXPECT_EQ(GLuint(drawFb), fb.id());
            EXPECT_EQ(GLuint(unitBinding), bound.id());
            EXPECT_EQ(bool(glIsEnabled(GL_SCISSOR_TEST)), c.scissor);
            glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDisable(GL_SCISSOR_TEST);
            glActiveTexture(GL_TEXTURE0);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        const std::vector<float> copied = gl::readTextureFloats(targets[0].id(), w, h, 4);
        const std::vector<float> cleared = gl::readTextureFloats(targets[1].id(), w, h, 4);
        size_t differ = 0, changed = 0;
        for (size_t i = 0; i < copied.size(); ++i) {
            differ += copied[i] != cleared[i];
            changed += cleared[i] != garbage[i];
        }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(changed, 0u);  // the clear wrote something, so the comparison means something
        // Strips only where the copy stands in: 16-byte texels without a colour mask.
        const bool copiedByStrip = c.format == GL_RGBA32F && !c.mask;
        EXPECT_EQ(clears[0].bytes(), copiedByStrip ? size_t(16 * 4 * 16) : size_t(0));
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    }
    // A caller whose clear values keep changing reuses strips instead of growing the list; the
    // last value is still the one written.
    gl::Texture2D target(GL_RGBA32F, w, h);
    const gl::FramebufferHandle fb = gl::makeFramebuffer({&target});
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    gl::TargetClears changing(gl::TargetClears::Path::Copy, 16, 4);
    for (int i = 0; i < 9; ++i) {
        const float value[4] = {float(i), 0.5f, -float(i), 1.0f};
        changing.color(0, value);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(changing.bytes(), size_t(4 * 16 * 4 * 16));
    const std::vector<float> last = gl::readTextureFloats(target.id(), w, h, 4);
    size_t wrong = 0;
    for (size_t i = 0; i < last.size(); i += 4) wrong += last[i] != 8.0f || last[i + 1] != 0.5f || last[i + 2] != -8.0f || last[i + 3] != 1.0f;
    EXPECT_EQ(wrong, 0u);
}
