// Refresh frames (`--temporal-mode refresh`): pass 1 rendered at the new camera, what lay
// behind the kept frame's nearest layer reprojected under it.
#include <cstring>
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "reference/reprojection_cpu.hpp"
#include "methods/neural/temporal/temporal_frames.hpp"
#include "methods/registry.hpp"
#include "reference/fragment_capture.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"
#include "starnt/tools/scene.hpp"
#include "temporal_test_support.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::temporal;
using starnt::test::readRgba;
using starnt::test::renderSequence;
using starnt::test::uploadRgba;

namespace {

const glm::vec3 kBackground(0.9f, 0.85f, 0.8f);

}  // namespace

// The refresh composite on the GPU against the CPU reference (search sources + refreshComposite),
// on random layers and depths with a moving camera; the unchanged-pixel and no-fragment cases are
// exact by construction.
TEST(TemporalRefresh, GpuMatchesCpuReference) {
    test::glContext();
    const int w = 45, h = 31;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ReprojectionFrame kept{w, h, {}, {}};
    std::vector<glm::vec4> keptNearest, nearest;
    std::vector<float> freshDepth;  // pass 1's depth at the new camera: 1 (far plane) where it drew nothing
    for (int i = 0; i < w * h; ++i) {
        const float a1 = u(rng) < 0.2f ? 0.0f : 0.1f + 0.8f * u(rng);
        keptNearest.push_back(glm::vec4(u(rng), u(rng), u(rng), a1));
        kept.color.push_back(glm::vec4(a1 == 0.0f ? kBackground : glm::vec3(u(rng), u(rng), u(rng)), 1.0f));
        kept.depth.push_back(a1 == 0.0f ? 1.0f : 0.6f + 0.3f * u(rng));
        const float n1 = u(rng) < 0.2f ? 0.0f : 0.1f + 0.8f * u(rng);
        nearest.push_back(glm::vec4(u(rng), u(rng), u(rng), n1));
        freshDepth.push_back(n1 == 0.0f ? 1.0f : 0.5f + 0.4f * u(rng));
    }
    gl::Texture2D color = uploadRgba(kept.color, w, h), kn = uploadRgba(keptNearest, w, h), fresh = uploadRgba(nearest, w, h);
    gl::Texture2D depth(GL_R32F, w, h), output(GL_RGBA32F, w, h);
    starnt::gl::uploadTexture(depth.id(), w, h, GL_RED, GL_FLOAT, kept.depth.data());
    gl::Texture2D freshDepthTexture(GL_DEPTH_COMPONENT32F, w, h);
    starnt::gl::uploadTexture(freshDepthTexture.id(), w, h, GL_DEPTH_COMPONENT, GL_FLOAT, freshDepth.data());
    MethodOptions options;
    options.neural.temporalInterval = 2;
    options.neural.temporalMode = NeuralOptions::TemporalMode::Refresh;
    TemporalFrames temporal(options);
    const glm::mat4 oldVP = test::turnedViewProj(w, h, 0.0f), newVP = test::turnedViewProj(w, h, 3.0f);
    ASSERT_TRUE(temporal.beginFrame(w, h));
    EXPECT_THROW(temporal.endRealFrame(color.id(), {.nearestDepth = depth.id()}, oldVP, w, h, OpaqueScene(kBackground)), Error)
        << "refresh needs the nearest layer";
    temporal.endRealFrame(color.id(), {.nearest = kn.id(), .nearestDepth = depth.id()}, oldVP, w, h, OpaqueScene(kBackground));
    ASSERT_FALSE(temporal.beginFrame(w, h));
    EXPECT_EQ(temporal.interpolatedPasses(), TemporalFrames::Passes::Nearest);
    temporal.interpolate(newVP, {.nearest = fresh.id(), .nearestDepth = freshDepthTexture.id()}, OpaqueScene(kBackground), output.id());
    const std::vector<glm::vec4> gpu = readRgba(output.id(), w, h);
    const Reprojection r = makeReprojection(oldVP, newVP);
    const std::vector<ReprojectionSource> sources = reprojectionSearchOnCpu(kept, r);
    size_t moved = 0, resampled = 0, off = 0;
    for (int i = 0; i < w * h; ++i) {
        const ReprojectionSource& s = sources[size_t(i)];
        moved += s.index != i;
        resampled += s.consistent && nearest[size_t(i)].a > 0.0f;
        const glm::vec3 want = refreshPixel(kept, keptNearest, r, s, nearest[size_t(i)], kBackground);
        // A texel on the edge of the same-surface test may be decided differently in the shader's
        // float division: allow a few pixels off, none by more than a colour's range.
        bool near = true;
        for (int ch = 0; ch < 3; ++ch) near = near && std::abs(gpu[size_t(i)][ch] - want[ch]) <= 1e-4f;
        off += !near;
        if (nearest[size_t(i)].a == 0.0f) ASSERT_EQ(glm::vec3(gpu[size_t(i)]), kBackground);
    }
    EXPECT_LE(off, size_t(w * h / 100)) << "pixels off the CPU reference";
    EXPECT_GT(moved, size_t(w * h / 2)) << "the camera move must move most sources";
    EXPECT_GT(resampled, size_t(w * h / 4)) << "most pixels must take the resampled path";
    // Unchanged pixel: same nearest fragment, r = 1: the kept composite bit for bit.
    EXPECT_EQ(refreshComposite(glm::vec3(0.3f, 0.7f, 0.1f), glm::vec4(0.5f, 0.2f, 0.9f, 0.37f),
                               glm::vec4(0.5f, 0.2f, 0.9f, 0.37f), kBackground),
              glm::vec3(0.3f, 0.7f, 0.1f));
}

// A still camera: every interpolated frame equals the real frame exactly, in both modes.
TEST(TemporalRefresh, StillCameraGivesTheRealFrameInBothModes) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 96, 64, 30.0f, 15.0f, kBackground);
    for (auto mode : {NeuralOptions::TemporalMode::Refresh, NeuralOptions::TemporalMode::Warp}) {
        MethodOptions options;
        options.neural.temporalInterval = 2;
        options.neural.temporalMode = mode;
        options.neural.spatial = false;
        const auto frames = renderSequence(c, options, {0.0f, 0.0f, 0.0f, 0.0f});
        EXPECT_EQ(frames[1], frames[0]);
        EXPECT_EQ(frames[3], frames[2]);
    }
}

// After a camera move, a pixel covered by one layer only (and whose neighbourhood had one layer in
// the kept frame) equals a real render at the new camera in refresh mode: the layer is fresh and
// what lies behind it is the background, whatever the search picked.
TEST(TemporalRefresh, SingleLayerPixelsMatchARealRenderAfterAMove) {
    const int w = 120, h = 80;
    test::TestScene c(makeBuiltinScene("random", 5), w, h, 25.0f, 10.0f, kBackground);  // 60 large triangles
    const float move = 1.5f;
    MethodOptions refresh, real;
    refresh.neural.temporalInterval = 2;
    refresh.neural.temporalMode = NeuralOptions::TemporalMode::Refresh;
    refresh.neural.spatial = real.neural.spatial = false;
    const auto seq = renderSequence(c, refresh, {0.0f, move});
    const auto truth = renderSequence(c, real, {move});
    MethodOptions warp = refresh;
    warp.neural.temporalMode = NeuralOptions::TemporalMode::Warp;
    const auto warped = renderSequence(c, warp, {0.0f, move});
    // renderSequence turns the camera about the target by +yaw around y; TestScene's azimuth does
    // the same turn, so the captures see the same views.
    const std::vector<size_t> pixels = test::singleLayerPixels(test::layerCounts("random", 5, w, h, 25.0f, 10.0f, kBackground),
                                                               test::layerCounts("random", 5, w, h, 25.0f + move, 10.0f, kBackground), w, h);
    size_t warpOff = 0;
    for (size_t i : pixels) {
        // Exact up to the output's last bit: with the compact targets (16-bit float output) the
        // refresh composite and the real frame's round the same value computed two ways (one 16-bit
        // step is 2^-11 to 2^-10 of the value).
        for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(seq[1][i][ch], truth[0][i][ch], 1e-5f + std::abs(truth[0][i][ch]) / 1024.0f) << i;
        warpOff += glm::length(glm::vec3(warped[1][i] - truth[0][i])) > 1e-3f;
    }
    EXPECT_GT(pixels.size(), 50u);  // 89 on llvmpipe: the large triangles overlap almost everywhere
    EXPECT_GT(warpOff, 0u) << "warp frames do not re-render the layer: some of these pixels differ there";
}

// Refresh frames search only where the fresh pass 1 drew (empty_pixels.hpp): the same frames, bit
// for bit, as searching every pixel, and the empty pixels hold the background.
TEST(TemporalRefresh, SkippingEmptyPixelsChangesNoBit) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 96, 64, 30.0f, 15.0f, kBackground);
    for (auto targets : {NeuralOptions::Targets::Compact, NeuralOptions::Targets::Float32}) {
        MethodOptions options;
        options.neural.temporalInterval = 2;
        options.neural.temporalMode = NeuralOptions::TemporalMode::Refresh;
        options.neural.targets = targets;
        MethodOptions shadeAll = options;
        shadeAll.neural.skipEmptyPixels = false;
        const std::vector<float> yaws = {0.0f, 4.0f, 8.0f, 12.0f};
        const auto skipped = renderSequence(c, options, yaws), all = renderSequence(c, shadeAll, yaws);
        ASSERT_EQ(skipped.size(), all.size());
        size_t backgroundPixels = 0;
        for (size_t f = 0; f < skipped.size(); ++f) {
            ASSERT_EQ(0, std::memcmp(skipped[f].data(), all[f].data(), skipped[f].size() * sizeof(glm::vec4)))
                << "frame " << f << (f % 2 ? " (refresh)" : " (real)");
            for (const glm::vec4& p : skipped[f]) backgroundPixels += glm::vec3(p) == nn::roundToHalf(kBackground) || glm::vec3(p) == kBackground;
        }
        EXPECT_GT(backgroundPixels, size_t(4 * 96 * 64 / 10)) << "the scene must leave empty pixels";
    }
}
