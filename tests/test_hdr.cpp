// Linear HDR colours (above 1): every method composites them instead of clamping, and the networks
// see colours scaled into their training range (methods/neural/network_hdr.glsl), so an HDR scene's
// error relative to its exact composite stays at its LDR twin's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "gl/gl_util.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/nn.hpp"
#include "test_support.hpp"

using namespace starnt;

namespace {

constexpr int kW = 96, kH = 72;
constexpr float kScale = 50.0f;

// tubes with every colour multiplied by `scale` (COLOR_0 carries them), over black: the exact
// composite of the twin is `scale` times the LDR one.
test::TestScene twin(float scale) {
    Scene s = makeBuiltinScene("tubes", 3);
    for (Mesh& m : s.meshes) {
        for (glm::vec4& c : m.colors) c = glm::vec4(glm::vec3(c) * scale, c.a);
    }
    return test::TestScene(std::move(s), kW, kH, 30.0f, 20.0f, glm::vec3(0.0f));
}

// Mean squared difference over RGB relative to the reference's mean square.
double relativeError(const Image& test, const Image& reference) {
    double num = 0.0, den = 0.0;
    for (size_t i = 0; i < test.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = double(test.rgba[i]) - double(reference.rgba[i]);
        num += d * d;
        den += double(reference.rgba[i]) * double(reference.rgba[i]);
    }
    return num / den;
}

MethodOptions float32Targets() {
    MethodOptions o;
    o.neural.targets = NeuralOptions::Targets::Float32;
    return o;
}

}  // namespace

TEST(Hdr, EveryMethodKeepsItsLdrTwinsRelativeError) {
    const test::TestScene ldr = twin(1.0f), hdr = twin(kScale);
    const Image ldrTruth = ldr.render("abuffer").image, hdrTruth = hdr.render("abuffer").image;
    // The exact composites: the HDR one is kScale times the LDR one (not clamped).
    double peak = 0.0;
    for (float v : hdrTruth.rgba) peak = std::max(peak, double(v));
    EXPECT_GT(peak, 5.0);
    EXPECT_LT(relativeError(hdrTruth, [&] {
                  Image scaled = ldrTruth;
                  for (size_t i = 0; i < scaled.rgba.size(); ++i) {
                      if (i % 4 != 3) scaled.rgba[i] *= kScale;
                  }
                  return scaled;
              }()),
              1e-5);
    // Every method with its defaults (DFAOIT's narrow layers included), and DFAOIT with 32-bit layers.
    for (const std::string& method : methodNames()) {
        for (const bool wide : {false, true}) {
            if (wide && method != "dfaoit") continue;
            const MethodOptions options = wide ? float32Targets() : MethodOptions{};
            const double ldrError = relativeError(ldr.render(method, options).image, ldrTruth);
            const double hdrError = relativeError(hdr.render(method, options).image, hdrTruth);
            std::printf("[ %s%s ] relative MSE: LDR %.3g, HDR (x%.0f) %.3g\n", method.c_str(), wide ? " fp32" : "", ldrError,
                        kScale, hdrError);
            EXPECT_LE(hdrError, 1.1 * ldrError + 1e-6) << method << (wide ? " fp32" : "");
        }
    }
}

// The scaled inference against its CPU reference (nn::compositeNetwork scales the same way), per
// pixel, relative to the value, on the HDR twin (32-bit targets: the algorithm, not the rounding).
TEST(Hdr, NetworksMatchTheirCpuReferenceOnHdrColours) {
    const test::TestScene hdr = twin(kScale);
    const CapturedFrame frags = hdr.capture();
    for (const char* method : {"starnt", "starnt-residual", "starnt-d", "dfaoit"}) {
        const nn::Network net = loadMethodNetwork(*neuralConfig(method), {});
        const Image gpu = hdr.render(method, float32Targets()).image;
        size_t bad = 0, scaled = 0;
        for (int y = 0; y < kH; ++y) {
            for (int x = 0; x < kW; ++x) {
                const FragmentList& list = frags.at(x, y);
                const nn::PixelSums sums = nn::sumsFromFragments(list);
                const nn::TailMoments moments = nn::tailMomentsFromFragments(list);
                const glm::vec3 want = nn::compositeNetwork(net, sums, glm::vec3(0.0f), &moments);
                scaled += sums.count > 3.5f && glm::length(sums.sumAlphaColor / std::max(sums.sumAlpha, 1e-6f)) > 1.8f;
                for (int c = 0; c < 3; ++c) {
                    const float allowed = 2e-3f * std::max(1.0f, std::abs(want[c]));
                    if (!(std::abs(gpu.pixel(x, y)[c] - want[c]) <= allowed) && ++bad <= 5) {
                        ADD_FAILURE() << method << " pixel " << x << "," << y << " ch " << c << ": gpu " << gpu.pixel(x, y)[c]
                                      << " cpu " << want[c] << " N=" << sums.count;
                    }
                }
            }
        }
        EXPECT_LE(bad, 4u) << method;  // weight switches at thresholds (GlTailMoments says which)
        EXPECT_GT(scaled, 100u) << "pixels whose network ran on scaled colours";
    }
}
