// Corrected interpolated frames (`--temporal-mode correct`, beyond SPEC 6): passes 1 and 3 rendered
// at the new camera, the closed form behind the nearest layer plus the last real frame's network
// correction, reprojected (correction_cpu.hpp).
#include <cstring>
#include <gtest/gtest.h>

#include <random>


#include "reference/correction_cpu.hpp"
#include "methods/neural/temporal/temporal_frames.hpp"
#include "starnt/error.hpp"
#include "temporal_test_support.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::temporal;
using starnt::test::readRgba;
using starnt::test::renderSequence;
using starnt::test::uploadRgba;

namespace {

const glm::vec3 kBackground(0.9f, 0.85f, 0.8f);

gl::Texture2D uploadRed(const std::vector<float>& p, int w, int h) {
    gl::Texture2D t(GL_R32F, w, h);
    starnt::gl::uploadTexture(t.id(), w, h, GL_RED, GL_FLOAT, p.data());
    return t;
}

gl::Texture2D uploadDepth(const std::vector<float>& p, int w, int h) {
    gl::Texture2D t(GL_DEPTH_COMPONENT32F, w, h);
    starnt::gl::uploadTexture(t.id(), w, h, GL_DEPTH_COMPONENT, GL_FLOAT, p.data());
    return t;
}

// Random layers over a flat surface at one window depth (so that after a small turn most fresh
// points find the same surface in the kept frame), with holes where nothing was drawn.
struct RandomPasses {
    std::vector<glm::vec4> nearest, sums;
    std::vector<float> depth, transmittance;
};
RandomPasses randomPasses(int w, int h, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    RandomPasses p;
    for (int i = 0; i < w * h; ++i) {
        const bool empty = u(rng) < 0.15f;
        const float a1 = empty ? 0.0f : 0.1f + 0.8f * u(rng);
        const glm::vec3 c1(u(rng), u(rng), u(rng));
        const float behindAlpha = empty ? 0.0f : 2.0f * u(rng);  // sum of the alphas behind the nearest
        const glm::vec3 behindMean(u(rng), u(rng), u(rng));
        p.nearest.push_back(glm::vec4(c1, a1));
        p.sums.push_back(glm::vec4(a1 * c1 + behindAlpha * behindMean, a1 + behindAlpha));
        p.transmittance.push_back((1.0f - a1) * std::exp(-behindAlpha));
        p.depth.push_back(empty ? 1.0f : 0.8f);
    }
    return p;
}

MethodOptions correctedOptions() {
    MethodOptions o;
    o.neural.temporalInterval = 2;
    o.neural.temporalMode = NeuralOptions::TemporalMode::Correct;
    o.neural.spatial = false;
    return o;
}

}  // namespace

// The closed form behind the nearest layer: nothing behind -> the background; two layers -> the
// second over the background; opaque nearest layers are the caller's to avoid.
TEST(TemporalCorrected, ClosedFormBehindTheNearestLayer) {
    const glm::vec4 nearest(0.2f, 0.4f, 0.6f, 0.5f);
    EXPECT_EQ(closedFormBehind(nearest, glm::vec4(0.5f * glm::vec3(nearest), 0.5f), 0.5f, kBackground), kBackground);
    const glm::vec3 c2(0.9f, 0.1f, 0.3f);
    const float a2 = 0.25f;
    const glm::vec4 sums(0.5f * glm::vec3(nearest) + a2 * c2, 0.5f + a2);
    const glm::vec3 got = closedFormBehind(nearest, sums, 0.5f * (1.0f - a2), kBackground);
    const glm::vec3 want = a2 * c2 + (1.0f - a2) * kBackground;
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], want[ch], 1e-6f);
}

// The GPU capture and composite against the CPU reference on random passes and a turning camera.
TEST(TemporalCorrected, GpuMatchesCpuReference) {
    test::glContext();
    const int w = 47, h = 33;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const RandomPasses real = randomPasses(w, h, rng), fresh = randomPasses(w, h, rng);
    std::vector<glm::vec4> composite;  // a "network" output: anything over the nearest layer
    for (const glm::vec4& n : real.nearest) {
        composite.push_back(glm::vec4(n.a > 0.0f ? glm::vec3(u(rng), u(rng), u(rng)) : kBackground, 1.0f));
    }
    gl::Texture2D rc = uploadRgba(composite, w, h), rd = uploadDepth(real.depth, w, h), rn = uploadRgba(real.nearest, w, h),
                  rs = uploadRgba(real.sums, w, h), rt = uploadRed(real.transmittance, w, h);
    gl::Texture2D fn = uploadRgba(fresh.nearest, w, h), fd = uploadDepth(fresh.depth, w, h), fs = uploadRgba(fresh.sums, w, h),
                  ft = uploadRed(fresh.transmittance, w, h), output(GL_RGBA32F, w, h);
    TemporalFrames temporal(correctedOptions());
    const glm::mat4 oldVP = test::turnedViewProj(w, h, 0.0f), newVP = test::turnedViewProj(w, h, 1.0f);
    ASSERT_TRUE(temporal.beginFrame(w, h));
    EXPECT_THROW(temporal.endRealFrame(rc.id(), {.nearestDepth = rd.id()}, oldVP, w, h, OpaqueScene(kBackground)), Error) << "corrected frames need the nearest layer";
    temporal.endRealFrame(rc.id(), {rn.id(), rd.id(), rs.id(), rt.id()}, oldVP, w, h, OpaqueScene(kBackground));
    ASSERT_FALSE(temporal.beginFrame(w, h));
    temporal.interpolate(newVP, {fn.id(), fd.id(), fs.id(), ft.id()}, OpaqueScene(kBackground), output.id());
    const std::vector<glm::vec4> gpu = readRgba(output.id(), w, h);

    CorrectionSource source{w, h, composite, real.depth, real.nearest, real.sums, real.transmittance};
    const std::vector<glm::vec4> correction = correctionOnCpu(source, oldVP, kBackground);
    size_t off = 0, corrected = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const glm::vec3 want = correctedPixel(x, y, w, h, fresh.nearest[i], fresh.depth[i], fresh.sums[i], fresh.transmittance[i],
                                                  correction, oldVP, newVP, kBackground);
            const glm::vec3 closedOnly = correctedPixel(x, y, w, h, fresh.nearest[i], fresh.depth[i], fresh.sums[i],
                                                        fresh.transmittance[i], {}, oldVP, newVP, kBackground);
            corrected += glm::length(want - closedOnly) > 1e-3f;
            bool near = true;
            for (int ch = 0; ch < 3; ++ch) near = near && std::abs(gpu[i][ch] - want[ch]) <= 1e-4f;
            off += !near;  // a tap on the edge of the same-surface test may go the other way in the shader
            if (fresh.nearest[i].a == 0.0f) ASSERT_EQ(glm::vec3(gpu[i]), kBackground) << x << "," << y;
        }
    EXPECT_LE(off, size_t(w * h / 100)) << "pixels off the CPU reference";
    EXPECT_GT(corrected, size_t(w * h / 2)) << "most pixels must take the kept correction";
}

// Without a correction (the real frame's pass 3 ran reduced) the interpolated frame is the closed
// form alone, and a frame of another size or a reset makes the next frame real.
TEST(TemporalCorrected, WithoutSumsTheClosedFormAloneAndResetsAreReal) {
    test::glContext();
    const int w = 20, h = 14;
    std::mt19937 rng(3);
    const RandomPasses real = randomPasses(w, h, rng), fresh = randomPasses(w, h, rng);
    std::vector<glm::vec4> composite(real.nearest.size(), glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    gl::Texture2D rc = uploadRgba(composite, w, h), rd = uploadDepth(real.depth, w, h), rn = uploadRgba(real.nearest, w, h);
    gl::Texture2D fn = uploadRgba(fresh.nearest, w, h), fd = uploadDepth(fresh.depth, w, h), fs = uploadRgba(fresh.sums, w, h),
                  ft = uploadRed(fresh.transmittance, w, h), output(GL_RGBA32F, w, h);
    TemporalFrames temporal(correctedOptions());
    const glm::mat4 oldVP = test::turnedViewProj(w, h, 0.0f), newVP = test::turnedViewProj(w, h, 1.0f);
    ASSERT_TRUE(temporal.beginFrame(w, h));
    temporal.endRealFrame(rc.id(), {.nearest = rn.id(), .nearestDepth = rd.id()}, oldVP, w, h, OpaqueScene(kBackground));
    ASSERT_FALSE(temporal.beginFrame(w, h));
    temporal.interpolate(newVP, {fn.id(), fd.id(), fs.id(), ft.id()}, OpaqueScene(kBackground), output.id());
    const std::vector<glm::vec4> gpu = readRgba(output.id(), w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const glm::vec3 want = correctedPixel(x, y, w, h, fresh.nearest[i], fresh.depth[i], fresh.sums[i], fresh.transmittance[i],
                                                  {}, oldVP, newVP, kBackground);
            for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(gpu[i][ch], want[ch], 1e-5f) << x << "," << y;
        }
    EXPECT_TRUE(temporal.beginFrame(w, h)) << "K = 2: real";
    temporal.endRealFrame(rc.id(), {.nearest = rn.id(), .nearestDepth = rd.id()}, oldVP, w, h, OpaqueScene(kBackground));
    EXPECT_TRUE(temporal.beginFrame(w + 1, h)) << "another size: real";
    temporal.reset();
    EXPECT_TRUE(temporal.beginFrame(w, h)) << "after a reset: real";
}

// A still camera: an interpolated frame is the real one up to the rounding of the kept correction
// and of the 16-bit output (the closed form cancels: B_cf + (B_net - B_cf)).
// For the tail-moment methods too, whose corrected frames run pass 3 without the moments (the
// closed form needs sum a C, sum a and the transmittance only): the same sums as the real frame's.
TEST(TemporalCorrected, StillCameraGivesTheRealFrame) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 96, 64, 30.0f, 15.0f, kBackground);
    for (const char* method : {"starnt", "starnt-d", "hybrid-moments", "recommended"}) {
        const auto frames = renderSequence(c, correctedOptions(), {0.0f, 0.0f, 0.0f, 0.0f}, method);
        float largest = 0.0f;
        for (size_t i = 0; i < frames[0].size(); ++i)
            for (int ch = 0; ch < 3; ++ch) largest = std::max(largest, std::abs(frames[1][i][ch] - frames[0][i][ch]));
        EXPECT_LE(largest, 4.0f / 1024.0f) << method << ": a few 16-bit steps at most";  // 0 on llvmpipe
        EXPECT_EQ(frames[2], frames[0]) << method << ": the next real frame";
    }
}

// After a camera move, a pixel covered by one layer only equals a real render at the new camera:
// the fresh layer over the closed form, which is the background there, plus a correction that is
// zero up to rounding where the kept frame had one layer too.
TEST(TemporalCorrected, SingleLayerPixelsMatchARealRenderAfterAMove) {
    const int w = 120, h = 80;
    test::TestScene c(makeBuiltinScene("random", 5), w, h, 25.0f, 10.0f, kBackground);
    const float move = 1.5f;
    MethodOptions real;
    real.neural.spatial = false;
    const auto seq = renderSequence(c, correctedOptions(), {0.0f, move});
    const auto truth = renderSequence(c, real, {move});
    const std::vector<size_t> pixels = test::singleLayerPixels(test::layerCounts("random", 5, w, h, 25.0f, 10.0f, kBackground),
                                                               test::layerCounts("random", 5, w, h, 25.0f + move, 10.0f, kBackground), w, h);
    for (size_t i : pixels) {
        for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(seq[1][i][ch], truth[0][i][ch], 1e-5f + std::abs(truth[0][i][ch]) / 512.0f) << i;
    }
    EXPECT_GT(pixels.size(), 50u);
}

// A still camera over many frames, as an engine renders them (no glFinish between the passes): no
// corrected frame may lose the surfaces of the real frame before it. The composite shades only the
// pixels its own pass 1 covered, by an early depth test against a copy of that pass's depth; a copy
// that saw the depth before pass 1 had written it would turn nearly every covered pixel into the
// background. Reported intermittent on llvmpipe, most often with one thread: run it with
// LP_NUM_THREADS=1 too.
TEST(TemporalCorrected, StillCameraNeverDropsTheSurfaces) {
    const int w = 64, h = 64;
    const glm::vec3 background(0.875f, 0.75f, 0.625f);  // exact in a 16-bit output too
    for (const auto& [method, frames] : {std::pair{"starnt-d", 120}, std::pair{"recommended", 60}}) {
        test::TestScene c(makeBuiltinScene("tubes", 3), w, h, 30.0f, 15.0f, background);
        auto m = createMethod(method, SceneGpu::surfaceShader(), correctedOptions());
        const FrameDesc f = c.frame();
        std::vector<glm::vec4> real;
        int interpolated = 0, bad = 0;
        for (int i = 0; i < frames; ++i) {
            m->render(f, c.gpu->callback(f.view, f.projection, {}));
            const bool isInterpolated = m->lastFrameStats().interpolated();
            const std::vector<glm::vec4> out = readRgba(m->outputTexture(), w, h);
            if (!isInterpolated) {
                real = out;
                continue;
            }
            ++interpolated;
            size_t covered = 0, lost = 0;  // surface pixels of the real frame, and those now the background
            for (size_t p = 0; p < out.size(); ++p) {
                if (glm::vec3(real[p]) == background) continue;
                ++covered;
                lost += glm::vec3(out[p]) == background;
            }
            ASSERT_GT(covered, size_t(w * h / 8)) << method << ": the scene must cover part of the frame";
            ASSERT_LT(covered, size_t(w * h)) << method << ": and leave some background";
            if (lost * 4 > covered) {
                ADD_FAILURE() << method << " frame " << i << ": " << lost << " of " << covered << " surface pixels are the background";
                if (++bad == 5) break;
            }
        }
        if (bad == 0) EXPECT_EQ(interpolated, frames / 2) << method << ": K = 2 interpolates every other frame";
    }
}

// The real frame's composite writes the kept correction itself (fusedCorrectionCapture, the
// default) or a pass of its own does: the interpolated frames are the same either way.
TEST(TemporalCorrected, FusedCaptureEqualsTheCapturePass) {
    test::TestScene c(makeBuiltinScene("random", 5), 120, 80, 25.0f, 10.0f, kBackground);
    for (const char* method : {"starnt", "starnt-d"}) {
        MethodOptions fused = correctedOptions(), pass = correctedOptions();
        pass.neural.fusedCorrectionCapture = false;
        const auto a = renderSequence(c, fused, {0.0f, 1.5f, 3.0f, 4.5f}, method);
        const auto b = renderSequence(c, pass, {0.0f, 1.5f, 3.0f, 4.5f}, method);
        for (size_t f = 0; f < a.size(); ++f) {
            float largest = 0.0f;
            for (size_t i = 0; i < a[f].size(); ++i)
                for (int ch = 0; ch < 3; ++ch) largest = std::max(largest, std::abs(a[f][i][ch] - b[f][i][ch]));
            EXPECT_LE(largest, 1.0f / 1024.0f) << method << " frame " << f;  // 0 on llvmpipe, a 16-bit step at most
        }
        EXPECT_NE(a[1], a[0]) << method << ": the camera moved";
    }
}
