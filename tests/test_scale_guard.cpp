// Scale rules, the scale guard (GPU against its CPU reference, and what it sees), and the
// work counters that show what reduced passes save.
#include <cstring>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include <glm/gtc/type_ptr.hpp>

#include "gl/gl_util.hpp"
#include "render/frame_stats_json.hpp"
#include "gl/gpu_timer.hpp"
#include "methods/neural/tiles/tile_constants.h"
#include "reference/tiles_cpu.hpp"
#include "methods/neural/tiles/tiles_gpu.hpp"
#include "methods/registry.hpp"
#include "methods/common/opaque_scene.hpp"
#include "methods/neural/neural_passes.hpp"
#include "reference/fragment_capture.hpp"
#include "scene/scene_gpu.hpp"
#include "starnt/tools/nn.hpp"
#include "starnt/tools/scene.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::tiles;

namespace {

const glm::vec3 kBackground(0.9f, 0.85f, 0.8f);

std::vector<glm::vec4> readGl(GLuint texture, int w, int h) {
    std::vector<glm::vec4> out(size_t(w) * size_t(h));
    const std::vector<float> floats = starnt::gl::readTextureFloats(texture, w, h, 4);
    std::memcpy(out.data(), floats.data(), floats.size() * sizeof(float));
    return out;
}

gl::Texture2D upload(const std::vector<glm::vec4>& pixels, int w, int h) {
    gl::Texture2D t(GL_RGBA32F, w, h);
    starnt::gl::uploadTexture(t.id(), w, h, GL_RGBA, GL_FLOAT, pixels.data());
    return t;
}

ScaleGuard runGpuGuard(const std::vector<glm::vec4>& composite, const std::vector<glm::vec4>& nearest,
                       const std::vector<glm::vec4>& second, int w, int h) {
    GpuTiles gpu;
    gpu.resize(w, h);
    const gl::Texture2D c = upload(composite, w, h), n = upload(nearest, w, h), s = upload(second, w, h);
    gpu.update(c.id(), n.id(), TileSignal::Back, s.id());
    glFinish();
    EXPECT_TRUE(gpu.pollHistogram());
    EXPECT_TRUE(gpu.hasGuard());
    return gpu.guard();
}

void expectGuardNear(const ScaleGuard& got, const ScaleGuard& want) {
    auto near = [](float a, float b) { return std::abs(a - b) <= 1e-3f * std::max(std::abs(b), 1e-6f); };
    EXPECT_EQ(got.occupied, want.occupied);
    EXPECT_TRUE(near(got.energy2, want.energy2)) << got.energy2 << " vs " << want.energy2;
    EXPECT_TRUE(near(got.energy3, want.energy3)) << got.energy3 << " vs " << want.energy3;
    for (int k = 0; k < 2; ++k) {
        EXPECT_TRUE(near(got.loss2[size_t(k)], want.loss2[size_t(k)])) << k << ": " << got.loss2[size_t(k)] << " vs " << want.loss2[size_t(k)];
        EXPECT_TRUE(near(got.loss3[size_t(k)], want.loss3[size_t(k)])) << k << ": " << got.loss3[size_t(k)] << " vs " << want.loss3[size_t(k)];
    }
}

// A layered image: a constant nearest layer (alpha 0.4) over a back signal given per pixel.
struct Layers {
    std::vector<glm::vec4> composite, nearest, second;
};
Layers layered(int w, int h, const std::function<glm::vec3(int, int)>& behind) {
    Layers l;
    const glm::vec4 n(0.2f, 0.5f, 0.8f, 0.4f), s(0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            l.nearest.push_back(n);
            l.second.push_back(s);
            l.composite.push_back(glm::vec4(n.a * glm::vec3(n) + (1.0f - n.a) * behind(x, y), 1.0f));
        }
    return l;
}

// The exact nearest and second layers of the scene's frame, from a fragment capture, in GL order.
void capturedLayers(const test::TestScene& c, std::vector<glm::vec4>& nearest, std::vector<glm::vec4>& second) {
    const int w = c.width, h = c.height;
    const CapturedFrame frags = c.capture();
    nearest.assign(size_t(w * h), glm::vec4(0.0f));
    second.assign(size_t(w * h), glm::vec4(0.0f));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const nn::PixelSums s = nn::sumsFromFragments(frags.at(x, y));
            const size_t i = size_t(h - 1 - y) * size_t(w) + size_t(x);  // capture rows top-first
            if (s.count > 0.5f) nearest[i] = glm::vec4(s.c1, s.a1);
            if (s.count > 1.5f) second[i] = glm::vec4(s.c2, s.a2);
        }
}

}  // namespace

TEST(ScaleRules, SnappedContinuousAndStep) {
    // Snapped: the paper's value snapped to a power of two in log2.
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 3.0, STARNT_SCALE_DELTA_PASS3), 1.0f);
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 2.6, STARNT_SCALE_DELTA_PASS3), 1.0f);   // 2^-0.4 -> 1
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 2.4, STARNT_SCALE_DELTA_PASS3), 0.5f);   // 2^-0.6 -> 1/2
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 1.4, STARNT_SCALE_DELTA_PASS3), 0.25f);  // 2^-1.6 -> 1/4
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 0.0, STARNT_SCALE_DELTA_PASS3), 0.25f);  // clamped
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 1.6, STARNT_SCALE_DELTA_PASS2), 0.5f);   // 2^-0.6
    EXPECT_EQ(ruleScale(ScaleRule::Snapped, 1.8, STARNT_SCALE_DELTA_PASS2), 1.0f);   // 2^-0.4
    EXPECT_FLOAT_EQ(ruleScale(ScaleRule::Continuous, 2.4, STARNT_SCALE_DELTA_PASS3), float(std::exp2(-0.6)));
    EXPECT_EQ(ruleScale(ScaleRule::Step, 2.01, 0.0), 1.0f);
    EXPECT_EQ(ruleScale(ScaleRule::Step, 2.0, 0.0), 0.5f);
    EXPECT_EQ(ruleScale(ScaleRule::Step, 1.0, 0.0), 0.25f);
}

TEST(ScaleRules, GuardPicksTheCheapestPairWithinTheBudget) {
    ScaleGuard g;
    g.occupied = float(0.1 / STARNT_SCALE_GUARD_BUDGET);  // allowed loss: 0.1
    const double budget = STARNT_SCALE_GUARD_BUDGET;
    g.loss2 = {1.0f, 2.0f};
    g.loss3 = {0.05f, 0.09f};
    PassScales s = guardScales(g, budget);  // pass 2 may not be reduced; pass 3 to 1/4
    EXPECT_EQ(s.pass2, 1.0f);
    EXPECT_EQ(s.pass3, 0.25f);
    g.loss3 = {0.05f, 0.2f};
    s = guardScales(g, budget);
    EXPECT_EQ(s.pass2, 1.0f);
    EXPECT_EQ(s.pass3, 0.5f);
    g.loss2 = {0.08f, 0.5f};  // both at 1/2 (0.08) is cheaper than 1, 1/4 and within budget
    g.loss3 = {0.05f, 0.09f};
    s = guardScales(g, budget);
    EXPECT_EQ(s.pass2, 0.5f);
    EXPECT_EQ(s.pass3, 0.5f);
    EXPECT_NEAR(guardPredictedLoss(g, 0.5f, 0.25f), 0.08 + (0.09 - 0.05), 1e-7);
    g.loss2 = g.loss3 = {5.0f, 9.0f};
    s = guardScales(g, budget);
    EXPECT_EQ(s.pass2, 1.0f);
    EXPECT_EQ(s.pass3, 1.0f);
    g = {};  // nothing occupied: nothing to lose
    g.occupied = 0.0f;
    s = guardScales(g, budget);
    EXPECT_EQ(s.pass2, 0.25f);
    EXPECT_EQ(s.pass3, 0.25f);
}

// Per-tile shading rates: the coarsest pass-3 rate whose loss in the tile stays within the budget
// times the tile's own occupied pixels; pass 2's losses do not count (it stays at full rate), and a
// tile with nothing occupied keeps the full rate.
TEST(ScaleRules, ShadingRatePerTileIsTheCoarsestWithinTheTilesBudget) {
    const float budget = float(STARNT_SCALE_GUARD_BUDGET);
    ScaleGuard t;
    t.occupied = 0.1f / budget;  // allowed loss in this tile: 0.1
    t.loss2 = {50.0f, 90.0f};
    t.loss3 = {0.05f, 0.09f};
    EXPECT_EQ(tileShadingRate(t, budget), STARNT_SHADING_RATE_QUARTER);
    t.loss3 = {0.05f, 0.2f};
    EXPECT_EQ(tileShadingRate(t, budget), STARNT_SHADING_RATE_HALF);
    t.loss3 = {0.11f, 0.2f};
    EXPECT_EQ(tileShadingRate(t, budget), STARNT_SHADING_RATE_FULL);
    t.occupied *= 2.0f;  // twice the pixels, twice the allowance
    EXPECT_EQ(tileShadingRate(t, budget), STARNT_SHADING_RATE_QUARTER);
    t = {};
    EXPECT_EQ(tileShadingRate(t, budget), STARNT_SHADING_RATE_FULL) << "nothing occupied: nothing to reduce";
}

namespace {

// Runs the GPU tiles with shading rates on the layers and checks the rate image and the per-rate
// counts against tiles::tileShadingRate on the CPU reference's per-tile sums. A tile whose loss
// lies within 1e-3 of its threshold may go either way (the GPU's pow differs in the last bits).
// Returns the CPU classes.
std::vector<uint32_t> expectShadingRatesMatchCpu(const std::vector<glm::vec4>& composite, const std::vector<glm::vec4>& nearest,
                                                 const std::vector<glm::vec4>& second, int w, int h) {
    GpuTiles gpu;
    gpu.enableShadingRates();
    gpu.resize(w, h);
    EXPECT_EQ(gpu.shadingRateImage(), 0u) << "no rate image before a guard update";
    const gl::Texture2D c = upload(composite, w, h), n = upload(nearest, w, h), s = upload(second, w, h);
    gpu.update(c.id(), n.id(), TileSignal::Back, s.id());
    glFinish();
    EXPECT_TRUE(gpu.pollHistogram());
    EXPECT_NE(gpu.shadingRateImage(), 0u);
    const std::vector<uint8_t> rates = gpu.readShadingRates();
    const std::vector<ScaleGuard> tiles = scaleGuardTiles(w, h, composite, nearest, second, GuardPixels::Sampled);
    EXPECT_EQ(rates.size(), tiles.size());
    const float budget = float(STARNT_SCALE_GUARD_BUDGET);
    std::array<uint32_t, STARNT_SHADING_RATE_CLASSES> counts{};
    std::vector<uint32_t> classes;
    int borderline = 0;
    for (size_t i = 0; i < tiles.size() && i < rates.size(); ++i) {
        const uint32_t want = tileShadingRate(tiles[i], budget);
        classes.push_back(want);
        if (tiles[i].occupied > 0.0f) ++counts[want];
        const float allowed = budget * tiles[i].occupied;
        const bool nearThreshold = std::abs(tiles[i].loss3[0] - allowed) <= 1e-3f * allowed ||
                                   std::abs(tiles[i].loss3[1] - allowed) <= 1e-3f * allowed;
        if (nearThreshold) {
            ++borderline;
            continue;
        }
        EXPECT_EQ(uint32_t(rates[i]), want) << "tile " << i;
    }
    if (borderline == 0) {
        for (int k = 0; k < STARNT_SHADING_RATE_CLASSES; ++k) EXPECT_EQ(gpu.shadingRateTiles()[size_t(k)], counts[size_t(k)]) << k;
    }
    return classes;
}

}  // namespace

// The shading-rate image computed on the GPU (tile_shading_rate.comp.glsl) against the CPU rule,
// on layers whose back differs by tile column: flat (nothing to lose), a slow gradient, 4-pixel
// stripes (a 2x2 rate keeps some, a 4x4 rate none) and 1-pixel stripes (every reduction loses).
// The rate image needs an r8ui image (desktop GL); no shading-rate hardware is needed to make it.
TEST(ScaleGuard, ShadingRatesGpuMatchCpuPerTile) {
    test::glContext();
    if (gl::isEs()) GTEST_SKIP() << "the shading-rate image is desktop GL's (GL_NV_shading_rate_image, an r8ui image)";
    const int w = 64, h = 48;
    const Layers l = layered(w, h, [](int x, int y) {
        const int column = x / STARNT_TILE_SIZE;
        const glm::vec3 flat(0.3f, 0.6f, 0.2f);  // column 1 starts from it: tile 0's samples at x = 16 see it
        if (column == 0) return flat;
        if (column == 1) return flat + glm::vec3(0.002f * float(x - 16), 0.0f, 0.001f * float(y));
        if (column == 2) return (x / 2) % 2 == 0 ? glm::vec3(0.9f, 0.2f, 0.1f) : glm::vec3(0.1f, 0.3f, 0.9f);
        return x % 2 == 0 ? glm::vec3(1.0f) : glm::vec3(0.0f);
    });
    const std::vector<uint32_t> classes = expectShadingRatesMatchCpu(l.composite, l.nearest, l.second, w, h);
    ASSERT_EQ(classes.size(), size_t(4 * 3));
    for (int row = 0; row < 3; ++row) {  // the premise: the columns get different rates
        EXPECT_EQ(classes[size_t(row * 4 + 0)], STARNT_SHADING_RATE_QUARTER) << row;
        EXPECT_EQ(classes[size_t(row * 4 + 3)], STARNT_SHADING_RATE_FULL) << row;
    }
}

// The same on a real render's layers (the method's composite, layers from a fragment capture).
TEST(ScaleGuard, ShadingRatesGpuMatchCpuOnARealRender) {
    const int w = 160, h = 96;
    test::TestScene c(makeBuiltinScene("smoke", 3), w, h, 30.0f, 15.0f, kBackground);
    if (gl::isEs()) GTEST_SKIP() << "the shading-rate image is desktop GL's (GL_NV_shading_rate_image, an r8ui image)";
    auto method = createMethod("starnt", SceneGpu::surfaceShader(), {});
    const FrameDesc f = c.frame();
    method->render(f, c.gpu->callback(f.view, f.projection, {}));
    glFinish();
    const std::vector<glm::vec4> composite = readGl(method->outputTexture(), w, h);
    std::vector<glm::vec4> nearest, second;
    capturedLayers(c, nearest, second);
    const std::vector<uint32_t> classes = expectShadingRatesMatchCpu(composite, nearest, second, w, h);
    int occupiedTiles = 0;
    for (const ScaleGuard& t : scaleGuardTiles(w, h, composite, nearest, second, GuardPixels::Sampled)) occupiedTiles += t.occupied > 0.0f;
    EXPECT_GT(occupiedTiles, 10) << "the premise: a scene that covers many tiles";
    std::array<int, STARNT_SHADING_RATE_CLASSES> perClass{};
    for (uint32_t k : classes) ++perClass[k];
    // The premise: smoke's tiles differ (at this size 55 full, 3 at 2x2, 2 at 4x4).
    EXPECT_GT(perClass[STARNT_SHADING_RATE_FULL], 0);
    EXPECT_GT(perClass[STARNT_SHADING_RATE_HALF] + perClass[STARNT_SHADING_RATE_QUARTER], 0);
}

// With per-tile shading rates pass 3 sums only the fragments behind pass 2's layer (a per-pixel
// depth test against its depth), and the inference adds the exact layers back, as after reduced
// passes. Without the rates (setPass3TailsOnly) that is the same frame: every pass-3 target, with
// the two layers put back, against the plain pass 3's (float32 targets; tubes, three layers deep).
TEST(ShadingRateImage, TailOnlyPassThreePlusTheLayersIsThePlainPassThree) {
    test::glContext();
    const int w = 96, h = 64;
    test::TestScene c(makeBuiltinScene("tubes", 3), w, h, 30.0f, 15.0f, kBackground);
    const FrameDesc f = c.frame();
    const DrawCallback draw = c.gpu->callback(f.view, f.projection, {});
    OpaqueScene opaque(kBackground);
    opaque.begin(f);
    NeuralPasses passes(SceneGpu::surfaceShader(), opaque, false, NeuralOptions::Targets::Float32);
    passes.run(f, draw, NeuralPasses::kDefaultPeelEpsilon, {w, h}, {w, h});
    ASSERT_FALSE(passes.pass3HoldsTails());
    // Pass 3's targets: sum a C and sum a, the count, the transmittance.
    struct PassThree {
        std::vector<glm::vec4> sums;
        std::vector<float> count, t;
    };
    const auto readPassThree = [&] {
        return PassThree{readGl(passes.alphaColor().id(), w, h), gl::readTextureFloats(passes.colorCount().id(), w, h, 1),
                         gl::readTextureFloats(passes.transmittance().id(), w, h, 1)};
    };
    const auto [sums, count, t] = readPassThree();
    passes.setPass3TailsOnly(true);
    passes.run(f, draw, NeuralPasses::kDefaultPeelEpsilon, {w, h}, {w, h});
    ASSERT_TRUE(passes.pass3HoldsTails());
    const auto [tailSums, tailCount, tailT] = readPassThree();
    const std::vector<glm::vec4> l1 = readGl(passes.nearest().id(), w, h), l2 = readGl(passes.second().id(), w, h);
    size_t deep = 0, off = 0;
    for (size_t i = 0; i < sums.size(); ++i) {
        const glm::vec4 layers = glm::vec4(glm::vec3(l1[i]) * l1[i].a + glm::vec3(l2[i]) * l2[i].a, l1[i].a + l2[i].a);
        const float layerCount = (l1[i].a > 0.0f ? 1.0f : 0.0f) + (l2[i].a > 0.0f ? 1.0f : 0.0f);
        deep += tailCount[i] > 0.5f;
        bool near = glm::length(tailSums[i] + layers - sums[i]) <= 1e-4f + 1e-4f * glm::length(sums[i]);
        near = near && tailCount[i] + layerCount == count[i];
        near = near && std::abs(tailT[i] * (1.0f - l1[i].a) * (1.0f - l2[i].a) - t[i]) <= 1e-5f;
        off += !near;
    }
    EXPECT_GT(deep, size_t(200)) << "the premise: pixels with more than two layers";
    EXPECT_EQ(off, 0u) << "pixels whose tail plus layers differs from the plain sums";
    passes.setPass3TailsOnly(false);
    passes.run(f, draw, NeuralPasses::kDefaultPeelEpsilon, {w, h}, {w, h});
    EXPECT_FALSE(passes.pass3HoldsTails());
    EXPECT_EQ(readGl(passes.alphaColor().id(), w, h), sums) << "the plain pass 3 again, its clip state restored";
}

// Without a shading-rate image (llvmpipe, ES, most drivers) `auto` is the whole-pass scales, frame
// for frame the same images as `off`, and `on` is an error naming what is missing; `on` also needs
// the guard's tiles. On a GPU with GL_NV_shading_rate_image, `on` renders with per-tile rates after
// the settling probes, close to the full-rate image.
TEST(ShadingRateImage, AutoFallsBackToTheWholePassScalesAndOnNamesWhatIsMissing) {
    // Smoke: its guard sums allow 2x2 and 4x4 in some tiles at this size (ShadingRatesGpuMatchCpuOnARealRender).
    test::TestScene c(makeBuiltinScene("smoke", 3), 160, 96, 30.0f, 15.0f, kBackground);
    // `on` where it cannot apply: one error naming the option and what is missing.
    const auto expectRefused = [](const MethodOptions& options, const std::string& mentions) {
        try {
            createMethod("starnt", SceneGpu::surfaceShader(), options);
            ADD_FAILURE() << "--shading-rate-image on must be an error without " << mentions;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--shading-rate-image on"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
        }
    };
    MethodOptions off;
    MethodOptions on;
    on.neural.shadingRateImage = NeuralOptions::ShadingRateImage::On;
    MethodOptions noTiles = on;
    noTiles.neural.spatial = false;
    expectRefused(noTiles, "--spatial on");
    MethodOptions onWithTemporal = on;
    onWithTemporal.neural.temporalInterval = 2;
    expectRefused(onWithTemporal, "--temporal off");
    const bool usable = gl::shadingRateImageSupport(STARNT_TILE_SIZE, STARNT_SHADING_RATE_CLASSES).usable;
    if (!usable) expectRefused(on, "GL_NV_shading_rate_image");
    MethodOptions automatic;
    automatic.neural.shadingRateImage = NeuralOptions::ShadingRateImage::Auto;
    // Without the extension `auto` must be `off` exactly; with it, the reference is full rate
    // (tiles off: no whole-pass reduction either), which the rated frames shade more cheaply.
    MethodOptions fullRate;
    fullRate.neural.spatial = false;
    auto reference = createMethod("starnt", SceneGpu::surfaceShader(), usable ? fullRate : off);
    auto tested = createMethod("starnt", SceneGpu::surfaceShader(), usable ? on : automatic);
    int ratedFrames = 0;
    gl::GpuPassTimer referenceWork, testedWork;
    for (int frame = 0; frame < 14; ++frame) {
        c.camera = orbitCamera(c.scene.bounds(), 30.0f + 1.5f * float(frame), 15.0f, c.aspect());
        FrameDesc f = c.frame();
        f.timing = &referenceWork;
        reference->render(f, c.gpu->callback(f.view, f.projection, {}));
        const std::vector<glm::vec4> want = readGl(reference->outputTexture(), c.width, c.height);
        f.timing = &testedWork;
        tested->render(f, c.gpu->callback(f.view, f.projection, {}));
        const std::vector<glm::vec4> got = readGl(tested->outputTexture(), c.width, c.height);
        referenceWork.collect();
        testedWork.collect();
        const auto referenceCounters = referenceWork.collectCounters(), testedCounters = testedWork.collectCounters();
        const nlohmann::json stats = frameStatsJson(tested->lastFrameStats());
        ASSERT_TRUE(stats.contains("shading_rate_image")) << "asked for: the stats say whether it ran";
        if (!usable) {
            EXPECT_FALSE(stats["shading_rate_image"].get<bool>()) << "frame " << frame;
            ASSERT_EQ(got, want) << "frame " << frame << ": auto without a shading-rate image must be the plain tiles";
        } else {
            // Where the rates ran, pass 3 shaded fewer fragments than at full rate (the hardware
            // coarsened it): a rate image that is stale or all 1x1 would not.
            const bool rated = stats["shading_rate_image"].get<bool>();
            ratedFrames += rated ? 1 : 0;
            if (rated && testedWork.countersAvailable()) {
                EXPECT_LT(testedCounters.at("pass3").fragmentInvocations, referenceCounters.at("pass3").fragmentInvocations)
                    << "frame " << frame;
            }
            double mse = 0.0;
            for (size_t i = 0; i < got.size(); ++i) {
                const glm::vec3 d = glm::vec3(got[i]) - glm::vec3(want[i]);
                mse += double(glm::dot(d, d)) / 3.0;
            }
            EXPECT_LT(mse / double(got.size()), 1e-3) << "frame " << frame;
        }
    }
    if (usable) EXPECT_GT(ratedFrames, 0) << "no frame used the per-tile rates";
}

// The guard sees what a corner test misses: one-pixel strands between the samples of a half-size
// pass lose far more than a smooth gradient of the same range, and the strands sit at odd columns,
// where no corner of a 2x2 leaf (x0 even) looks.
TEST(ScaleGuard, ThinStrandsLoseAndSmoothGradientsDoNot) {
    test::glContext();
    const int w = 64, h = 48;
    const Layers strands = layered(w, h, [](int x, int) { return x % 4 == 1 ? glm::vec3(1.0f, 0.1f, 0.1f) : glm::vec3(0.1f); });
    const Layers smooth = layered(w, h, [&](int x, int y) { return glm::vec3(float(x) / w, float(y) / h, 0.5f); });
    const ScaleGuard thin = scaleGuardSums(w, h, strands.composite, strands.nearest, strands.second);
    const ScaleGuard flat = scaleGuardSums(w, h, smooth.composite, smooth.nearest, smooth.second);
    expectGuardNear(runGpuGuard(strands.composite, strands.nearest, strands.second, w, h), thin);
    expectGuardNear(runGpuGuard(smooth.composite, smooth.nearest, smooth.second, w, h), flat);
    int sampled = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) sampled += guardSamples(x, y);
    EXPECT_EQ(thin.occupied, float(sampled));
    EXPECT_GT(thin.loss2[0] / thin.occupied, 100.0 * STARNT_SCALE_GUARD_BUDGET);
    EXPECT_LT(flat.loss2[1] / flat.occupied, 0.5 * STARNT_SCALE_GUARD_BUDGET);  // 6e-6: the clamped last samples
    EXPECT_EQ(guardScales(thin, STARNT_SCALE_GUARD_BUDGET).pass2, 1.0f);
    EXPECT_EQ(guardScales(flat, STARNT_SCALE_GUARD_BUDGET).pass3, 0.25f);
}

// Per-tile sums (the runtime's subset, and every pixel for the per-tile study): the tiles of the
// sampled subset add up to scaleGuardSums, every pixel counts 256 occupied pixels in a whole tile,
// and only the tiles that hold strands predict a loss.
TEST(ScaleGuard, PerTileSumsLocateTheLoss) {
    const int w = 64, h = 48;  // 4 x 3 tiles
    const Layers l = layered(w, h, [](int x, int y) {
        return x >= 32 && y < 16 && x % 4 == 1 ? glm::vec3(1.0f, 0.1f, 0.1f) : glm::vec3(0.1f);  // strands in tiles 2, 3
    });
    const std::vector<ScaleGuard> sampled = scaleGuardTiles(w, h, l.composite, l.nearest, l.second, GuardPixels::Sampled);
    const std::vector<ScaleGuard> every = scaleGuardTiles(w, h, l.composite, l.nearest, l.second, GuardPixels::Every);
    ASSERT_EQ(sampled.size(), 12u);
    ASSERT_EQ(every.size(), 12u);
    ScaleGuard summed;
    for (const ScaleGuard& t : sampled) {
        summed.occupied += t.occupied;
        summed.loss2[0] += t.loss2[0];
    }
    const ScaleGuard total = scaleGuardSums(w, h, l.composite, l.nearest, l.second);
    EXPECT_EQ(summed.occupied, total.occupied);
    EXPECT_EQ(summed.loss2[0], total.loss2[0]);
    for (size_t t = 0; t < every.size(); ++t) {
        EXPECT_EQ(every[t].occupied, 256.0f) << t;
        // Tiles 2 and 3 hold the strands; tile 1 only reaches them through the bilinear corners at
        // its right edge (x = 32 is the next tile's first column: no strand there, x % 4 == 0).
        if (t == 2 || t == 3) EXPECT_GT(every[t].loss2[0] / 256.0f, 100.0 * STARNT_SCALE_GUARD_BUDGET) << t;
        else EXPECT_EQ(every[t].loss2[0], 0.0f) << t;
    }
}

// The guard's pixel subset: a quarter of the pixels, evenly over the four classes of a 2x2 sample
// grid (no alignment with the reduced passes' samples), and over the 16 classes of a 4x4 grid.
TEST(ScaleGuard, SubsetIsAnEvenQuarter) {
    const int w = 640, h = 360;
    std::array<int, 16> perClass{};
    int total = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (guardSamples(x, y)) {
                ++total;
                ++perClass[size_t((y % 4) * 4 + x % 4)];
            }
    EXPECT_NEAR(double(total) / (w * h), 0.25, 0.01);
    for (int c : perClass) EXPECT_NEAR(double(c) / (w * h / 16), 0.25, 0.03);
}

// GPU against CPU on real data: the method's composite of a real render, with the nearest and
// second layers from a fragment capture of the same frame; and the method's own guard (computed
// from its own pass targets on its first, full-resolution frame) against the same CPU reference.
TEST(ScaleGuard, GpuMatchesCpuOnARealRender) {
    const int w = 120, h = 72;  // partial tiles at the right and top
    test::TestScene c(makeBuiltinScene("tubes", 3), w, h, 30.0f, 15.0f, kBackground);
    auto method = createMethod("starnt", SceneGpu::surfaceShader(), {});
    const FrameDesc f = c.frame();
    method->render(f, c.gpu->callback(f.view, f.projection, {}));
    glFinish();
    const nlohmann::json stats = frameStatsJson(method->lastFrameStats());
    ASSERT_TRUE(stats.contains("guard")) << stats.dump();
    EXPECT_TRUE(stats["probe_frame"].get<bool>());
    const std::vector<glm::vec4> composite = readGl(method->outputTexture(), w, h);
    std::vector<glm::vec4> nearest, second;
    capturedLayers(c, nearest, second);
    const ScaleGuard cpu = scaleGuardSums(w, h, composite, nearest, second);
    expectGuardNear(runGpuGuard(composite, nearest, second, w, h), cpu);
    EXPECT_GT(cpu.occupied, 150.0f);
    EXPECT_GT(cpu.loss2[1], cpu.loss2[0]) << "a quarter-size pass loses more than a half-size one";
    const auto& g = stats["guard"];
    EXPECT_EQ(g["occupied_pixels"].get<float>(), cpu.occupied);
    EXPECT_NEAR(g["energy_pass2"].get<float>(), cpu.energy2, 0.02f * cpu.energy2);
    EXPECT_NEAR(g["loss_pass3"][0].get<float>(), cpu.loss3[0], 0.02f * cpu.loss3[0]);
}

// A scene with no transparent pixel: w_bar 0 and nothing for the guard to measure, so no verdict:
// every real frame probes at full resolution (no pixel is shaded there anyway), and the image is
// exactly the background.
TEST(ScaleGuard, EmptyViewKeepsProbingAndShowsTheBackground) {
    const int w = 64, h = 40;
    test::TestScene away(makeBuiltinScene("panes", 1), w, h, 180.0f, 89.0f, kBackground);
    away.camera.target = away.camera.position + (away.camera.position - away.camera.target);  // look away from the scene
    auto method = createMethod("starnt", SceneGpu::surfaceShader(), {});
    nlohmann::json stats;
    for (int i = 0; i < STARNT_SCALE_SETTLE_FRAMES + 4; ++i) {
        const FrameDesc f = away.frame();
        method->render(f, away.gpu->callback(f.view, f.projection, {}));
        glFinish();
        stats = frameStatsJson(method->lastFrameStats());
        EXPECT_TRUE(stats["probe_frame"].get<bool>()) << "frame " << i;
        EXPECT_EQ(stats["scale_pass3"].get<float>(), 1.0f) << "frame " << i;
    }
    EXPECT_EQ(stats["w_bar"].get<double>(), 0.0);
    // Exactly the background as the output holds it (16-bit floats with the default compact targets).
    for (const glm::vec4& p : readGl(method->outputTexture(), w, h)) ASSERT_EQ(glm::vec3(p), nn::roundToHalf(kBackground));
}

// One probe frame with nothing to measure (the engine drew nothing) among frames of a scene the
// guard keeps at full resolution: no later frame may run reduced on that probe's word.
TEST(ScaleGuard, AProbeWithNothingToMeasureChoosesNoScales) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 96, 64, 30.0f, 15.0f, kBackground);
    auto method = createMethod("starnt", SceneGpu::surfaceShader(), {});
    const DrawCallback nothing = [](const GeometryPass&) {};
    for (int frame = 0; frame < STARNT_SCALE_SETTLE_FRAMES + 12; ++frame) {
        const FrameDesc f = c.frame();
        const bool empty = frame == STARNT_SCALE_SETTLE_FRAMES - 1;  // the last settling probe
        method->render(f, empty ? nothing : c.gpu->callback(f.view, f.projection, {}));
        glFinish();
        const nlohmann::json stats = frameStatsJson(method->lastFrameStats());
        if (empty) ASSERT_TRUE(stats["probe_frame"].get<bool>());
        EXPECT_EQ(stats["scale_pass2"].get<float>(), 1.0f) << "frame " << frame;
        EXPECT_EQ(stats["scale_pass3"].get<float>(), 1.0f) << "frame " << frame;
    }
}

// Sizes that are not multiples of 4: the last reduced texel covers a partial block; the image
// stays close to the full-resolution one everywhere, the last columns and rows included.
TEST(ScaleGuard, ReducedPassesAtSizesNotDivisibleByFour) {
    const int w = 98, h = 70;
    test::TestScene c(makeBuiltinScene("smoke", 2), w, h, 20.0f, 10.0f, kBackground);
    MethodOptions fullOptions, reduced;
    fullOptions.neural.spatial = false;
    reduced.neural.fixedScale2 = reduced.neural.fixedScale3 = 0.25f;
    const Image full = c.render("starnt", fullOptions).image, quarter = c.render("starnt", reduced).image;
    double edgeError = 0.0;
    int edgePixels = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec4 a = glm::make_vec4(full.pixel(x, y)), b = glm::make_vec4(quarter.pixel(x, y));
            ASSERT_TRUE(std::isfinite(b.r) && std::isfinite(b.g) && std::isfinite(b.b));
            if (x >= w - 3 || y >= h - 3) {
                edgeError += double(glm::length(glm::vec3(a - b)));
                ++edgePixels;
            }
        }
    EXPECT_LT(edgeError / edgePixels, 0.05) << "the last columns and rows of a 1/4 pass must interpolate, not smear";
}

// Work counters: the same geometry without a depth test shades the same fragments in WBOIT's
// accumulation and the A-buffer's build; a half-resolution pass 3 shades far fewer than a full one.
TEST(WorkCounters, EqualWorkForEqualPassesAndFewerFragmentsAtHalfScale) {
    const int w = 160, h = 96;
    test::TestScene c(makeBuiltinScene("tubes", 3), w, h, 30.0f, 15.0f, kBackground);
    gl::GpuPassTimer timer(true);
    if (!timer.countersAvailable()) GTEST_SKIP() << "no pipeline statistics queries";
    auto countersOf = [&](const std::string& name, const MethodOptions& o) {
        auto method = createMethod(name, SceneGpu::surfaceShader(), o);
        FrameDesc f = c.frame();
        f.timing = &timer;
        method->render(f, c.gpu->callback(f.view, f.projection, {}));
        glFinish();
        timer.collect();
        return timer.collectCounters();
    };
    const auto wboit = countersOf("wboit", {});
    const auto abuffer = countersOf("abuffer", {});
    ASSERT_TRUE(wboit.count("wboit_accumulate") && abuffer.count("abuffer_build"));
    EXPECT_GT(wboit.at("wboit_accumulate").fragmentInvocations, 10000u);
    EXPECT_EQ(wboit.at("wboit_accumulate").fragmentInvocations, abuffer.at("abuffer_build").fragmentInvocations);
    EXPECT_EQ(wboit.at("wboit_accumulate").primitives, abuffer.at("abuffer_build").primitives);
    EXPECT_EQ(wboit.at("wboit_accumulate").vertexInvocations, abuffer.at("abuffer_build").vertexInvocations);

    MethodOptions full, half;
    full.neural.spatial = false;
    half.neural.fixedScale2 = 1.0f;
    half.neural.fixedScale3 = 0.5f;
    const auto a = countersOf("starnt", full), b = countersOf("starnt", half);
    const double ratio = double(b.at("pass3").fragmentInvocations) / double(a.at("pass3").fragmentInvocations);
    // A quarter of the pixels; llvmpipe shades whole 2x2 quads, so thin triangles round up (measured
    // 0.40 on tree at 640x360). Pass 2 at full resolution does the same work in both.
    EXPECT_GT(ratio, 0.2);
    EXPECT_LT(ratio, 0.5);
    EXPECT_EQ(a.at("pass2").fragmentInvocations, b.at("pass2").fragmentInvocations);
    EXPECT_EQ(a.at("pass1").fragmentInvocations, a.at("pass3").fragmentInvocations) << "no depth test in pass 3";
}

// Probes back off while they keep finding nothing to reduce: after the settling probes the interval
// doubles with each probe that kept full resolution (8, 16, 32, then 32), so a scene that never
// reduces pays for one probe in 32 real frames. Tubes at this size: the guard keeps 100/100.
TEST(ScaleGuard, ProbesBackOffWhileTheyKeepFullResolution) {
    test::TestScene c(makeBuiltinScene("tubes", 3), 96, 64, 30.0f, 15.0f, kBackground);
    auto method = createMethod("starnt", SceneGpu::surfaceShader(), {});
    std::vector<int> probes;
    int lastInterval = 0;
    for (int frame = 0; frame < 100; ++frame) {
        const FrameDesc f = c.frame();
        method->render(f, c.gpu->callback(f.view, f.projection, {}));
        glFinish();
        const nlohmann::json stats = frameStatsJson(method->lastFrameStats());
        ASSERT_EQ(stats["scale_pass3"].get<float>(), 1.0f) << "frame " << frame << ": the premise is a scene kept at full resolution";
        if (stats["probe_frame"].get<bool>()) probes.push_back(frame);
        lastInterval = stats["probe_interval"].get<int>();
    }
    ASSERT_GE(probes.size(), size_t(STARNT_SCALE_SETTLE_FRAMES + 3));
    std::vector<int> gaps;
    for (size_t i = STARNT_SCALE_SETTLE_FRAMES; i < probes.size(); ++i) gaps.push_back(probes[i] - probes[i - 1]);
    // The readback of a probe's verdict may arrive a frame or two later, so a gap may repeat once.
    for (size_t i = 1; i < gaps.size(); ++i) EXPECT_GE(gaps[i], gaps[i - 1]) << "gaps must not shrink";
    EXPECT_EQ(gaps.back(), STARNT_SCALE_PROBE_INTERVAL << STARNT_SCALE_PROBE_BACKOFF);
    EXPECT_EQ(lastInterval, STARNT_SCALE_PROBE_INTERVAL << STARNT_SCALE_PROBE_BACKOFF);
    // A reset starts again from the settling probes and the base interval (the settling probes'
    // verdicts then count towards the back-off like any other).
    method->resetHistory();
    for (int frame = 0; frame < STARNT_SCALE_SETTLE_FRAMES; ++frame) {
        const FrameDesc f = c.frame();
        method->render(f, c.gpu->callback(f.view, f.projection, {}));
        glFinish();
        const nlohmann::json stats = frameStatsJson(method->lastFrameStats());
        EXPECT_TRUE(stats["probe_frame"].get<bool>()) << "settling frame " << frame << " after the reset";
        if (frame == 0) EXPECT_EQ(stats["probe_interval"].get<int>(), STARNT_SCALE_PROBE_INTERVAL);
    }
}
