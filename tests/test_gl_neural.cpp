// The neural methods on a real GL context against their CPU references (features, MLP, composite).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"
#include "starnt/tools/nn.hpp"
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

// Whether the driver rounds blended writes into 16-bit float targets toward zero (llvmpipe) rather
// than to nearest (GPUs): 1 + 0.75 steps of 2^-10 added onto 1 by blending comes back as 1 or as
// 1 + 2^-10. The CPU model of pass 3's sums follows (nn::sumsInHalfTargets).
bool halfBlendTruncates() {
    test::glContext();
    gl::Texture2D target(GL_RGBA16F, 1, 1);
    const gl::FramebufferHandle fb = gl::makeFramebuffer({&target});
    const gl::Program program = gl::buildProgram("half_blend_probe", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                                                 "layout(location = 0) out vec4 o; void main() { o = vec4(0.75 / 1024.0); }");
    const gl::VertexArrayHandle vao = gl::makeEmptyVertexArray();
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    glViewport(0, 0, 1, 1);
    const float one[4] = {1, 1, 1, 1};
    glClearBufferfv(GL_COLOR, 0, one);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glUseProgram(program.id());
    gl::drawFullscreenTriangle(vao);
    glDisable(GL_BLEND);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const float v = gl::readTextureFloats(target.id(), 1, 1, 4)[0];
    EXPECT_TRUE(v == 1.0f || v == 1.0f + 1.0f / 1024.0f) << v;
    return v == 1.0f;
}

MethodOptions withTargets(NeuralOptions::Targets targets) {
    MethodOptions o;
    o.neural.targets = targets;
    return o;
}
constexpr NeuralOptions::Targets kLayouts[] = {NeuralOptions::Targets::Compact, NeuralOptions::Targets::Float32};

// GPU image vs CPU composite of the captured fragments, per pixel. With the compact targets the CPU
// reference holds what 16-bit targets hold (nn::sumsInHalfTargets) and rounds its output the same.
template <typename Composite>
void expectGpuMatchesCpu(const Case& c, const Image& gpu, Composite composite, float tolerance,
                         NeuralOptions::Targets targets = NeuralOptions::Targets::Compact, bool narrowLayers = false) {
    CapturedFrame frags = c.capture();
    const bool compact = targets == NeuralOptions::Targets::Compact;
    const bool truncates = compact && halfBlendTruncates();
    size_t deep = 0, bad = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const nn::PixelSums sums = compact ? nn::sumsInHalfTargets(frags.at(x, y), truncates, nn::kDefaultAlphaCutoff, narrowLayers)
                                               : nn::sumsFromFragments(frags.at(x, y));
            if (sums.count > 3.5f) ++deep;
            const glm::vec3 want = compact ? nn::roundToHalf(composite(sums)) : composite(sums);
            for (int ch = 0; ch < 3; ++ch) {
                // Compact targets, pixels where the network runs: the GPU blends pass 3's sums in draw
                // order and the CPU in depth order, each rounding to 16 bits after every addition;
                // the network's inputs then differ in their last bits (measured: at most 3 steps of
                // 2^-11 in the output, on 7 of 4800 pixels of smoke), so one more 1e-3 there.
                // Relative above 1 (HDR colours).
                const float allowed = (compact && sums.count > 3.5f ? tolerance + 1e-3f : tolerance) * std::max(1.0f, std::abs(want[ch]));
                if (!(std::abs(gpu.pixel(x, y)[ch] - want[ch]) <= allowed) && ++bad <= 5) {
                    ADD_FAILURE() << "pixel " << x << "," << y << " ch " << ch << ": gpu " << gpu.pixel(x, y)[ch]
                                  << " cpu " << want[ch] << " N=" << sums.count << (compact ? " (compact)" : " (fp32)");
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
        const nn::Network net = loadMethodNetwork(*neuralConfig("starnt"), {});
        for (auto layout : kLayouts) {
            expectGpuMatchesCpu(c, renderWith(c, "starnt", withTargets(layout)),
                                [&](const nn::PixelSums& s) { return nn::compositeStarnt(net, s, kBackground); }, 1e-3f, layout);
        }
    }
}

// The residual network's linear output goes negative (the closed form overshoots): the inference
// and the composite must carry it as the CPU does.
TEST(GlNeural, StarntResidualMatchesCpuReferencePerPixel) {
    for (const char* scene : {"tubes", "smoke"}) {
        Case c = makeCase(scene, 45.0f);
        const nn::Network net = loadMethodNetwork(*neuralConfig("starnt-residual"), {});
        for (auto layout : kLayouts) {
            expectGpuMatchesCpu(c, renderWith(c, "starnt-residual", withTargets(layout)),
                                [&](const nn::PixelSums& s) { return nn::compositeStarntResidual(net, s, kBackground); },
                                1e-3f, layout);
        }
    }
}

TEST(GlNeural, HybridMatchesCpuReferencePerPixel) {
    for (const char* scene : {"tubes", "smoke"}) {
        Case c = makeCase(scene, 60.0f);
        for (auto layout : kLayouts) {
            expectGpuMatchesCpu(c, renderWith(c, "hybrid", withTargets(layout)),
                                [&](const nn::PixelSums& s) { return nn::compositeHybrid(s, kBackground); }, 1e-3f, layout);
        }
    }
}

// hybrid-moments and starnt-d: pass 3's depth moments and the weighted tail colour (and starnt-d's
// network) against the CPU reference. Their compact layout keeps sum a C, sum a and the
// transmittance in 32-bit float (NeuralPasses, tailMoments): the CPU model takes the layers at 16
// bits and those from the 32-bit sums.
class GlTailMoments : public ::testing::TestWithParam<std::string> {};

TEST_P(GlTailMoments, MatchesCpuReferencePerPixel) {
    const std::string method = GetParam();
    const NeuralMethodConfig* config = neuralConfig(method);
    ASSERT_NE(config, nullptr);
    const nn::Network net = loadMethodNetwork(*config, {});
    for (const char* scene : {"tubes", "smoke"}) {
        Case c = makeCase(scene, 75.0f);
        const CapturedFrame frags = c.capture();
        for (auto layout : kLayouts) {
            const bool compact = layout == NeuralOptions::Targets::Compact;
            const bool truncates = compact && halfBlendTruncates();
            const Image gpu = renderWith(c, method, withTargets(layout));
            size_t deep = 0, bad = 0, differsFromHybrid = 0;
            std::ostringstream mismatches;
            for (int y = 0; y < kH; ++y) {
                for (int x = 0; x < kW; ++x) {
                    const FragmentList& list = frags.at(x, y);
                    const nn::PixelSums exact = nn::sumsFromFragments(list);
                    nn::PixelSums sums = compact ? nn::sumsInHalfTargets(list, truncates) : exact;
                    sums.sumAlphaColor = exact.sumAlphaColor;
                    sums.sumAlpha = exact.sumAlpha;
                    sums.transmittance = exact.transmittance;
                    const nn::TailMoments m = nn::tailMomentsFromFragments(list);
                    glm::vec3 want = config->evaluatesNetwork ? nn::compositeNetwork(net, sums, kBackground, &m)
                                                              : nn::compositeHybridMoments(sums, m, kBackground);
                    if (compact) want = nn::roundToHalf(want);
                    if (sums.count > 3.5f) ++deep;
                    differsFromHybrid += glm::length(want - nn::compositeHybrid(sums, kBackground)) > 1e-2f;
                    const float allowed = sums.count > 3.5f ? 2e-3f : 1e-3f;
                    for (int ch = 0; ch < 3; ++ch) {
                        if (!(std::abs(gpu.pixel(x, y)[ch] - want[ch]) <= allowed) && ++bad <= 8) {
                            mismatches << " [pixel " << x << "," << y << " ch " << ch << ": gpu " << gpu.pixel(x, y)[ch]
                                       << " cpu " << want[ch] << " N=" << sums.count << "]";
                        }
                    }
                }
            }
            // The weight switches (quadratic or linear, tail_moments_constants.h) are discrete: a
            // pixel whose moments sit at a threshold may switch on the GPU's log differing from the
            // CPU's in the last bits (measured: one pixel of tubes, 2.6e-3). A few channels of the
            // 14,400 may differ for that.
            EXPECT_LE(bad, 6u) << scene << (compact ? " (compact)" : " (fp32)") << mismatches.str();
            EXPECT_GT(deep, 100u) << scene;
            // The moments change what the tail shows (else this test would not test them).
            EXPECT_GT(differsFromHybrid, 20u) << scene;
        }
    }
}
INSTANTIATE_TEST_SUITE_P(BothMethods, GlTailMoments, ::testing::Values("hybrid-moments", "starnt-d"),
                         [](const auto& info) { return test::identifier(info.param); });

TEST(GlNeural, DfaoitMatchesCpuReferencePerPixel) {
    Case c = makeCase("tubes", 200.0f);
    // The shipped twelve-input network, and the earlier ten-input one (still loadable: the features
    // of ten inputs are the first ten of twelve).
    const std::string tenInputs = std::string(STARNT_SOURCE_DIR) + "/src/methods/dfaoit/dfaoit_weights_10_inputs.json";
    for (const std::string& weights : {std::string(), tenInputs}) {
        MethodOptions base;
        base.neural.weightsPath = weights;
        const nn::Network net = loadMethodNetwork(*neuralConfig("dfaoit"), base);
        ASSERT_EQ(net.inputCount(), weights.empty() ? nn::kDfaoitInputs : nn::kDfaoitTenInputs);
        for (auto layout : kLayouts) {
            MethodOptions options = withTargets(layout);
            options.neural.weightsPath = weights;
            // DFAOIT's default (every pass at full resolution, no tiles, no temporal frames) runs the
            // narrow layers with the compact targets.
            expectGpuMatchesCpu(c, renderWith(c, "dfaoit", options),
                                [&](const nn::PixelSums& s) { return nn::compositeDfaoit(net, s, kBackground); }, 1e-3f,
                                layout, layout == NeuralOptions::Targets::Compact);
        }
    }
    // HDR colours (x50) through the narrow layers: each keeps its power-of-16 scale in the 2-bit
    // alpha (nn::narrowLayerColor), where a plain RGB10_A2 layer clamps them to 1.
    Scene hdr = makeBuiltinScene("tubes", 3);
    for (Mesh& m : hdr.meshes) {
        for (glm::vec4& color : m.colors) color = glm::vec4(glm::vec3(color) * 50.0f, color.a);
    }
    const Case hdrCase(std::move(hdr), kW, kH, 200.0f, 20.0f, kBackground);
    const nn::Network net = loadMethodNetwork(*neuralConfig("dfaoit"), {});
    expectGpuMatchesCpu(hdrCase, renderWith(hdrCase, "dfaoit"),
                        [&](const nn::PixelSums& s) { return nn::compositeDfaoit(net, s, kBackground); }, 1e-3f,
                        NeuralOptions::Targets::Compact, true);
}

// The composites shade only the pixels pass 1 covered and fill the rest with the background
// (methods/neural/empty_pixels.hpp): bit for bit the image of shading every pixel, for every neural
// method, both target layouts, reduced passes (in-place and own outputs) and corner inference.
TEST(GlNeural, SkippingEmptyPixelsChangesNoBit) {
    const Case c = makeCase("tubes", 30.0f);
    struct Variant {
        const char* method;
        float scale2, scale3;
        bool corners;
    };
    const Variant variants[] = {{"starnt", 1.0f, 1.0f, false}, {"starnt", 0.5f, 0.5f, false}, {"starnt", 1.0f, 0.5f, true},
                                {"dfaoit", 1.0f, 1.0f, false}, {"hybrid", 0.5f, 0.25f, false}};
    for (const Variant& v : variants) {
        for (NeuralOptions::Targets targets : kLayouts) {
            MethodOptions options = withTargets(targets);
            options.neural.fixedScale2 = v.scale2;
            options.neural.fixedScale3 = v.scale3;
            if (v.corners) options.neural.inference = NeuralOptions::Inference::Corners;
            MethodOptions shadeAll = options;
            shadeAll.neural.skipEmptyPixels = false;
            const Image skipped = renderWith(c, v.method, options), all = renderWith(c, v.method, shadeAll);
            size_t empty = 0, differ = 0;
            for (int y = 0; y < kH; ++y) {
                for (int x = 0; x < kW; ++x) {
                    differ += std::memcmp(skipped.pixel(x, y), all.pixel(x, y), 3 * sizeof(float)) != 0;
                    const float* p = all.pixel(x, y);
                    empty += glm::vec3(p[0], p[1], p[2]) ==
                             (targets == NeuralOptions::Targets::Compact ? nn::roundToHalf(kBackground) : kBackground);
                }
            }
            EXPECT_EQ(differ, 0u) << v.method << " at " << v.scale2 << "/" << v.scale3 << (v.corners ? " corners" : "");
            EXPECT_GT(empty, size_t(kW * kH / 10)) << "the view must leave empty pixels";
            EXPECT_LT(empty, size_t(kW * kH * 9 / 10)) << "and covered ones";
        }
    }
}

// A stack of 150 sheets facing the camera: the central pixels hold N = 150 fragments, deeper than
// any suite scene (hairball: 136).
Scene deepStack(int sheets) {
    const Camera cam = orbitCamera(Bounds{glm::vec3(-1.0f), glm::vec3(1.0f)}, 0.0f, 0.0f, float(kW) / float(kH));
    const glm::vec3 forward = glm::normalize(cam.target - cam.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0))), up = glm::cross(right, forward);
    Scene scene;
    scene.name = "deep stack";
    for (int i = 0; i < sheets; ++i) {
        const float t = float(i) / float(sheets - 1), g = std::fmod(float(i) * 0.618034f, 1.0f);
        Material m;
        m.unlit = true;
        m.baseColorFactor = glm::vec4(0.2f + 0.7f * g, 0.9f - 0.6f * t, 0.3f + 0.5f * std::fmod(g * 3.0f, 1.0f), 0.05f + 0.3f * g);
        scene.materials.push_back(m);
        Mesh mesh;
        const glm::vec3 c = forward * (1.6f * t - 0.8f);
        const float half = 0.6f + 0.2f * t;  // farther sheets larger: the edges do not line up
        for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            mesh.positions.push_back(c + half * (corner.x * right + corner.y * up));
        }
        mesh.indices = {0, 1, 2, 0, 2, 3};
        mesh.material = i;
        scene.meshes.push_back(mesh);
    }
    return scene;
}

// The compact layout's 16-bit pass-3 sums at pixels of 150 fragments. The GPU follows the
// CPU model of 16-bit blending (nn::sumsInHalfTargets) there too, and over those pixels the MSE
// against the exact composite stays within 2 % of the 32-bit layout's. At these depths the sum of
// alphas reaches 30, where 16-bit floats are 2^-6 apart and llvmpipe's blending truncates every
// addition (measured: sum a 2.4 % low at worst; the network's inputs are ratios, so it cancels).
TEST(GlNeural, DeepPixelSumsKeepTheirPrecision) {
    const int sheets = 150;
    Case c(deepStack(sheets), kW, kH, 0.0f, 0.0f, kBackground);
    const CapturedFrame frags = c.capture();
    ASSERT_GE(frags.at(kW / 2, kH / 2).size(), size_t(136)) << "the central pixel must be deep";
    const nn::Network net = loadMethodNetwork(*neuralConfig("starnt"), {});
    MethodOptions compactOptions = withTargets(NeuralOptions::Targets::Compact), fp32Options = withTargets(NeuralOptions::Targets::Float32);
    compactOptions.neural.spatial = fp32Options.neural.spatial = false;
    const Image compact = renderWith(c, "starnt", compactOptions), fp32 = renderWith(c, "starnt", fp32Options);
    const bool truncates = halfBlendTruncates();
    size_t deep = 0;
    double modelError = 0.0, compactSquared = 0.0, fp32Squared = 0.0, layoutShift = 0.0, sumAlphaError = 0.0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const FragmentList& list = frags.at(x, y);
            if (list.size() < 136) continue;
            ++deep;
            FragmentList sorted = nn::preparedFragments(list);
            const glm::vec3 exact = compositeOver(sorted, kBackground);
            const nn::PixelSums half = nn::sumsInHalfTargets(list, truncates), full = nn::sumsFromFragments(list);
            sumAlphaError = std::max(sumAlphaError, double(std::abs(half.sumAlpha - full.sumAlpha) / full.sumAlpha));
            const glm::vec3 model = nn::roundToHalf(nn::compositeStarnt(net, half, kBackground));
            for (int ch = 0; ch < 3; ++ch) {
                modelError = std::max(modelError, double(std::abs(compact.pixel(x, y)[ch] - model[ch])));
                compactSquared += std::pow(double(compact.pixel(x, y)[ch] - exact[ch]), 2.0);
                fp32Squared += std::pow(double(fp32.pixel(x, y)[ch] - exact[ch]), 2.0);
                layoutShift = std::max(layoutShift, double(std::abs(compact.pixel(x, y)[ch] - fp32.pixel(x, y)[ch])));
            }
        }
    }
    ASSERT_GT(deep, size_t(100)) << "pixels with N >= 136";
    const double compactMse = compactSquared / double(3 * deep), fp32Mse = fp32Squared / double(3 * deep);
    std::printf("deep pixels %zu: sum a relative error %.4f, GPU vs model %.2e, MSE against the exact composite: "
                "compact %.4e, fp32 %.4e; largest compact - fp32 %.2e\n",
                deep, sumAlphaError, modelError, compactMse, fp32Mse, layoutShift);
    EXPECT_LE(modelError, 2e-3) << "the GPU's 16-bit sums follow the CPU model";
    // The bar for whole images, applied to the deep pixels alone: MSE within 2 %.
    EXPECT_LE(std::abs(compactMse / fp32Mse - 1.0), 0.02) << "16-bit sums must not change the error at deep pixels";
    EXPECT_LE(layoutShift, 4e-3);
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
    // starnt's weights have starnt-residual's inputs and sizes, but not its kind.
    options.neural.weightsPath = (dir / "s.json").string();
    nn::saveWeights(nn::makeUntrained(nn::NetworkKind::StarNT, 1), options.neural.weightsPath);
    const std::string message = test::errorOf([&] { createMethod("starnt-residual", SceneGpu::surfaceShader(), options); });
    EXPECT_NE(message.find("needs a starnt-residual network"), std::string::npos) << message;
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
