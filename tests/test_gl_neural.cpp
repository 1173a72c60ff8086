// The neural methods on a real GL context against their CPU references (features, MLP, composite).
#include <gtest/gtest.h>

#include <cmath>

#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/camera.hpp"
#include "starnt/error.hpp"
#include "starnt/metrics.hpp"
#include "starnt/nn.hpp"
#include "test_support.hpp"

using namespace starnt;
namespace fs = std::filesystem;

namespace {

constexpr int kW = 80, kH = 60;
const glm::vec3 kBackground(0.9f, 0.85f, 0.8f);

using Case = test::TestScene;

Case makeCase(const std::string& builtin, float azimuth) {
    return Case(makeBuiltinScene(builtin, 3), kW, kH, azimuth, 20.0f, kBackground);
}

Image renderWith(const Case& c, const std::string& method, MethodOptions options = {}) {
    return c.render(method, options).image;
}

// GPU image vs CPU composite of the captured fragments, per pixel.
template <typename Composite>
void expectGpuMatchesCpu(const Case& c, const Image& gpu, Composite composite, float tolerance) {
    CapturedFrame frags = c.capture();
    size_t deep = 0, bad = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const nn::PixelSums sums = nn::sumsFromFragments(frags.at(x, y));
            if (sums.count > 3.5f) ++deep;
            const glm::vec3 want = composite(sums);
            for (int ch = 0; ch < 3; ++ch) {
                if (!(std::abs(gpu.pixel(x, y)[ch] - want[ch]) <= tolerance) && ++bad <= 5) {
                    ADD_FAILURE() << "pixel " << x << "," << y << " ch " << ch << ": gpu " << gpu.pixel(x, y)[ch]
                                  << " cpu " << want[ch] << " N=" << sums.count;
                }
            }
        }
    }
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(deep, 100u) << "the scene should have many pixels where the network runs";
}

}  // namespace

TEST(GlNeural, StarntMatchesCpuReferencePerPixel) {
    for (const char* scene : {"tubes", "smoke"}) {
        Case c = makeCase(scene, 30.0f);
        const nn::Network net = loadMethodNetwork(starntConfig(), {});
        expectGpuMatchesCpu(c, renderWith(c, "starnt"),
                            [&](const nn::PixelSums& s) { return nn::compositeStarnt(net, s, kBackground); }, 1e-3f);
    }
}

TEST(GlNeural, HybridMatchesCpuReferencePerPixel) {
    for (const char* scene : {"tubes", "smoke"}) {
        Case c = makeCase(scene, 60.0f);
        expectGpuMatchesCpu(c, renderWith(c, "hybrid"),
                            [&](const nn::PixelSums& s) { return nn::compositeHybrid(s, kBackground); }, 1e-3f);
    }
}

TEST(GlNeural, DfaoitMatchesCpuReferencePerPixel) {
    Case c = makeCase("tubes", 200.0f);
    const nn::Network net = loadMethodNetwork(dfaoitConfig(), {});
    expectGpuMatchesCpu(c, renderWith(c, "dfaoit"),
                        [&](const nn::PixelSums& s) { return nn::compositeDfaoit(net, s, kBackground); }, 1e-3f);
}

TEST(GlNeural, StarntIsExactWhereThreeOrFewerFragments) {
    // Panes: up to 5 layers; wherever N <= 3 the composite must equal the A-buffer.
    Case c = makeCase("panes", 10.0f);
    Image exact = renderWith(c, "abuffer");
    Image neural = renderWith(c, "starnt");
    CapturedFrame frags = c.capture();
    size_t checked[4] = {};
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const size_t n = frags.at(x, y).size();
            if (n > 3) continue;
            ++checked[n];
            for (int ch = 0; ch < 3; ++ch) {
                ASSERT_NEAR(neural.pixel(x, y)[ch], exact.pixel(x, y)[ch], 2e-3f) << x << "," << y << " N=" << n;
            }
        }
    }
    for (int n = 0; n <= 3; ++n) EXPECT_GT(checked[n], 0u) << "no pixel with " << n << " fragments";
}

TEST(GlNeural, StarntBeatsWboitOnABuiltInScene) {
    Case c = makeCase("smoke", 0.0f);
    Image exact = renderWith(c, "abuffer");
    const double wboit = mseSrgb(exact, renderWith(c, "wboit"));
    const double starnt = mseSrgb(exact, renderWith(c, "starnt"));
    EXPECT_LT(starnt, wboit);
}

TEST(GlNeural, WrongWeightsKindIsAClearError) {
    test::glContext();
    fs::path dir = test::makeTempDir("weights");
    nn::saveWeights(nn::makeUntrained(nn::NetworkKind::DFAOIT, 1), dir / "d.json");
    MethodOptions options;
    options.neural.weightsPath = (dir / "d.json").string();
    try {
        createMethod("starnt", SceneGpu::surfaceShader(), options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("dfaoit"), std::string::npos) << e.what();
    }
}

// Joint bilateral upsampling (NeuralOptions::Upsample::Joint) guided by the pass-1 depth: on the
// panes, whose edges overlap at other depths, the half-scale passes 2 + 3 come back with less
// error against the A-buffer than with plain bilinear (measured at 640x360, scales 50,50: MSE
// x10^2 0.00302 bilinear, 0.00189 joint), and at full scale both are the same image.
TEST(GlNeural, JointUpsampleBeatsBilinearAtHalfScaleOnThePanes) {
    Case c(makeBuiltinScene("panes", 3), 160, 96, 30.0f, 20.0f, kBackground);
    const Image exact = renderWith(c, "abuffer");
    auto starnt = [&](NeuralOptions::Upsample filter, float scale) {
        MethodOptions o;
        o.neural.upsample = filter;
        o.neural.fixedScale2 = o.neural.fixedScale3 = scale;
        return renderWith(c, "starnt", o);
    };
    const double bilinear = mseSrgb(exact, starnt(NeuralOptions::Upsample::Bilinear, 0.5f));
    const double joint = mseSrgb(exact, starnt(NeuralOptions::Upsample::Joint, 0.5f));
    EXPECT_LT(joint, 0.9 * bilinear) << "bilinear " << bilinear << " joint " << joint;
    EXPECT_EQ(mseSrgb(starnt(NeuralOptions::Upsample::Bilinear, 1.0f), starnt(NeuralOptions::Upsample::Joint, 1.0f)), 0.0);
}
