// The classic methods on a real GL context against the CPU references.
#include <gtest/gtest.h>

#include <cmath>

#include "gl/gl_util.hpp"
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
