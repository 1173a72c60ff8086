// The CPU reference of the adaptive tiles and of the resolution changes (SPEC 4-5), against hand
// derivations: levels, hysteresis, one level per frame, balance, histogram, scales, resampling.
#include <gtest/gtest.h>

#include <cmath>

#include "methods/neural/tiles/tile_constants.h"
#include "reference/tiles_cpu.hpp"
#include "reference/upsample_cpu.hpp"

using namespace starnt;
using namespace starnt::tiles;

namespace {

ColorImage flatImage(int w, int h, glm::vec3 c) { return {w, h, std::vector<glm::vec3>(size_t(w) * size_t(h), c)}; }

ColorImage checkerboard(int w, int h) {
    ColorImage image = flatImage(w, h, glm::vec3(0.0f));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) image.rgb[size_t(y * w + x)] = glm::vec3(float((x + y) % 2));
    return image;
}

std::vector<float> allOccupied(int w, int h) { return std::vector<float>(size_t(w) * size_t(h), 1.0f); }

std::vector<int> levels(const std::vector<uint32_t>& masks) {
    std::vector<int> out;
    for (uint32_t m : masks) out.push_back(maskLevel(m));
    return out;
}

}  // namespace

TEST(TilesCpu, LevelsAndUniformMasks) {
    for (int l = 0; l < 4; ++l) {
        EXPECT_EQ(maskLevel(uniformMask(l)), l);
        EXPECT_TRUE(maskIsConsistent(uniformMask(l)));
    }
    EXPECT_EQ(maskLevel(0x1u | 0x4u), 2);                      // root + quadrant 1
    EXPECT_EQ(maskLevel(0x1u | 0x8u | (1u << (5 + 4 * 2 + 3))), 3);  // root + quadrant 2 + its child 3
    EXPECT_FALSE(maskIsConsistent(0x2u));                      // quadrant without root
    EXPECT_FALSE(maskIsConsistent(0x1u | (1u << 5)));          // child of quadrant 0 without it
    EXPECT_FALSE(maskIsConsistent(1u << 21));                  // outside the 21 bits
}

TEST(TilesCpu, FlatImageIsAllLevelZero) {
    const TileUpdate u = updateTiles(flatImage(50, 37, glm::vec3(0.3f, 0.5f, 0.7f)), allOccupied(50, 37), {});
    ASSERT_EQ(u.masks.size(), size_t(4 * 3));
    for (uint32_t m : u.masks) EXPECT_EQ(m, 0u);
    EXPECT_EQ(u.histogram[0], 12u);
    EXPECT_DOUBLE_EQ(u.wBar, 0.0);
}

TEST(TilesCpu, CheckerboardRefinesOneLevelPerFrame) {
    const ColorImage image = checkerboard(48, 32);  // whole tiles (partial ones: PartialTiles...)
    std::vector<uint32_t> masks;
    for (int frame = 1; frame <= 4; ++frame) {
        masks = updateTiles(image, allOccupied(48, 32), masks).masks;
        for (int level : levels(masks)) EXPECT_EQ(level, std::min(frame, 3)) << "frame " << frame;
    }
    for (uint32_t m : masks) EXPECT_EQ(m, uniformMask(3));  // every node splits
}

TEST(TilesCpu, LevelDropsOneLevelPerFrame) {
    std::vector<uint32_t> masks(6, uniformMask(3));
    for (int frame = 1; frame <= 3; ++frame) {
        masks = updateTiles(flatImage(48, 32, glm::vec3(0.5f)), allOccupied(48, 32), masks).masks;
        for (int level : levels(masks)) EXPECT_EQ(level, 3 - frame);
    }
}

TEST(TilesCpu, HysteresisKeepsSplitBetweenMergeAndSplit) {
    // One corner of a 16x16 tile differs by a in red: 3 of the 6 corner pairs differ, D = a / 2.
    auto tileWithCornerStep = [](float d) {
        ColorImage image = flatImage(16, 16, glm::vec3(0.2f));
        image.rgb[0] = glm::vec3(0.2f + 2.0f * d, 0.2f, 0.2f);
        return image;
    };
    const float between = 0.5f * float(STARNT_TILE_MERGE_16 + STARNT_TILE_SPLIT_16);  // 0.0375
    const ColorImage image = tileWithCornerStep(between);
    ASSERT_NEAR(nodeVariation(image, 0, 0, 16), between, 1e-6f);
    EXPECT_EQ(evaluateTileMask(image, 0, 0, 0u) & 1u, 0u) << "not split before: D <= split keeps it whole";
    EXPECT_EQ(evaluateTileMask(image, 0, 0, uniformMask(1)) & 1u, 1u) << "split before: D >= merge keeps it split";
    const ColorImage below = tileWithCornerStep(0.9f * float(STARNT_TILE_MERGE_16));
    EXPECT_EQ(evaluateTileMask(below, 0, 0, uniformMask(3)), 0u) << "D < merge merges the root";
    const ColorImage above = tileWithCornerStep(1.1f * float(STARNT_TILE_SPLIT_16));
    EXPECT_EQ(evaluateTileMask(above, 0, 0, 0u) & 1u, 1u);
}

TEST(TilesCpu, LimitLevelChangePrunesOrForceSplits) {
    EXPECT_EQ(limitLevelChange(uniformMask(3), 0), uniformMask(1));
    EXPECT_EQ(limitLevelChange(uniformMask(3), 1), uniformMask(2));
    EXPECT_EQ(limitLevelChange(0u, 3), uniformMask(2));
    const uint32_t partial = 0x1u | 0x2u | (1u << 5);  // level 3 through quadrant 0 only
    EXPECT_EQ(limitLevelChange(partial, 2), partial);
    EXPECT_EQ(limitLevelChange(partial, 1) , 0x1u | 0x2u);
}

TEST(TilesCpu, BalanceLeavesNoNeighboursMoreThanOneLevelApart) {
    // A level-3 tile in a field of level 0: two Jacobi iterations give 3 -> 2 -> 1 -> 0 rings.
    const TileGrid grid = TileGrid::forImage(7 * 16, 7 * 16);
    std::vector<uint32_t> masks(size_t(grid.count()), 0u);
    masks[size_t(3 * 7 + 3)] = uniformMask(3);
    for (int k = 0; k < STARNT_TILE_BALANCE_ITERATIONS; ++k) masks = balanceOnce(masks, grid);
    for (int ty = 0; ty < 7; ++ty) {
        for (int tx = 0; tx < 7; ++tx) {
            const int ring = std::abs(tx - 3) + std::abs(ty - 3);
            EXPECT_EQ(maskLevel(masks[size_t(ty * 7 + tx)]), std::max(0, 3 - ring)) << tx << "," << ty;
            if (tx + 1 < 7) EXPECT_LE(std::abs(maskLevel(masks[size_t(ty * 7 + tx)]) - maskLevel(masks[size_t(ty * 7 + tx + 1)])), 1);
            if (ty + 1 < 7) EXPECT_LE(std::abs(maskLevel(masks[size_t(ty * 7 + tx)]) - maskLevel(masks[size_t(ty * 7 + tx + 7)])), 1);
        }
    }
}

TEST(TilesCpu, HistogramCountsOccupiedTilesOnly) {
    const TileGrid grid = TileGrid::forImage(32, 16);  // 2 tiles
    std::vector<float> alpha(32 * 16, 0.0f);
    alpha[5 * 32 + 20] = 0.5f;  // one pixel in tile 1
    const auto occupied = occupiedTiles(grid, alpha);
    EXPECT_EQ(occupied, (std::vector<uint8_t>{0, 1}));
    const auto h = levelHistogram({uniformMask(3), uniformMask(2)}, occupied);
    EXPECT_EQ(h, (std::array<uint32_t, 4>{0, 0, 1, 0}));
    EXPECT_DOUBLE_EQ(meanLevel(h), 2.0);
    EXPECT_DOUBLE_EQ(meanLevel({0, 0, 0, 0}), 0.0);  // no transparent pixel: w_bar 0
    EXPECT_DOUBLE_EQ(meanLevel({1, 1, 1, 1}), 1.5);
}

TEST(TilesCpu, ScalesFollowTheFormula) {
    EXPECT_FLOAT_EQ(passScale(1.5, STARNT_SCALE_DELTA_PASS2), float(std::exp2(1.5 - 2.2)));
    EXPECT_FLOAT_EQ(passScale(1.5, STARNT_SCALE_DELTA_PASS3), float(std::exp2(-1.5)));
    EXPECT_FLOAT_EQ(passScale(3.0, STARNT_SCALE_DELTA_PASS2), 1.0f);   // 2^0.8 clamps to 1
    EXPECT_FLOAT_EQ(passScale(3.0, STARNT_SCALE_DELTA_PASS3), 1.0f);
    EXPECT_FLOAT_EQ(passScale(0.0, STARNT_SCALE_DELTA_PASS2), 0.25f);  // 2^-2.2 clamps to 0.25
    EXPECT_EQ(scaledSize(1280, 0.5f), 640);
    EXPECT_EQ(scaledSize(1281, 0.5f), 641);
    EXPECT_EQ(scaledSize(1, 0.25f), 1);
    EXPECT_EQ(scaledSize(720, passScale(1.5, 2.2)), int(std::ceil(720 * std::exp2(-0.7))));
}

TEST(TilesCpu, PartialTilesAndOnePixelImages) {
    const TileUpdate one = updateTiles(flatImage(1, 1, glm::vec3(1.0f)), allOccupied(1, 1), {});
    ASSERT_EQ(one.masks.size(), 1u);
    EXPECT_EQ(one.masks[0], 0u);
    EXPECT_EQ(one.histogram[0], 1u);
    // 17x18: the edge tiles are 1 and 2 pixels wide; the checkerboard still refines them, and no
    // quadrant outside the image is split.
    std::vector<uint32_t> masks;
    for (int frame = 0; frame < 3; ++frame) masks = updateTiles(checkerboard(17, 18), allOccupied(17, 18), masks).masks;
    ASSERT_EQ(masks.size(), 4u);
    for (uint32_t m : masks) EXPECT_TRUE(maskIsConsistent(m));
    EXPECT_EQ(maskLevel(masks[0]), 3);
    EXPECT_EQ(masks[1] & 0x4u, 0u) << "quadrant 1 of the 1-pixel-wide edge tile lies outside the image";
}

TEST(TilesCpu, LeafLookupFollowsTheMask) {
    const uint32_t mask = 0x1u | 0x8u | (1u << (5 + 4 * 2 + 1));  // root, quadrant 2, its child 1
    EXPECT_EQ(leafOf(0u, 37, 5).x0, 32);
    EXPECT_EQ(leafOf(0u, 37, 5).size, 16);
    const Leaf q0 = leafOf(mask, 3, 3);
    EXPECT_EQ(q0.size, 8);
    const Leaf child = leafOf(mask, 1, 9);  // quadrant 2 (x 0..7, y 8..15), child 0 (unsplit)
    EXPECT_EQ(child.size, 4);
    EXPECT_EQ(child.y0, 8);
    const Leaf fine = leafOf(mask, 5, 10);  // quadrant 2, child 1 (x 4..7, y 8..11), split to 2x2
    EXPECT_EQ(fine.size, 2);
    EXPECT_EQ(fine.x0, 4);
    EXPECT_EQ(fine.y0, 10);
}

TEST(TilesCpu, CornerInterpolationIsBilinearInsideALeaf) {
    const TileGrid grid = TileGrid::forImage(16, 16);
    // A network output linear in x and y is reproduced exactly by the interpolation.
    auto linear = [](int x, int y) { return glm::vec3(0.1f * x, 0.05f * y, 1.0f); };
    int evaluations = 0;
    const auto out = cornerInterpolatedNetwork(grid, {0u}, [](int, int) { return true; },
                                               [&](int x, int y) { ++evaluations; return linear(x, y); });
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            EXPECT_NEAR(out[size_t(y * 16 + x)].x, linear(x, y).x, 1e-5f);
            EXPECT_NEAR(out[size_t(y * 16 + x)].y, linear(x, y).y, 1e-5f);
        }
    EXPECT_EQ(evaluations, 4 * 256) << "only the 4 corners are evaluated (once per pixel here)";
    // Corners where the network does not apply are left out of the weights.
    const auto partial = cornerInterpolatedNetwork(grid, {0u}, [](int x, int) { return x < 15; },
                                                   [&](int x, int y) { return linear(x, y); });
    EXPECT_NEAR(partial[size_t(7 * 16 + 7)].x, 0.0f, 1e-6f) << "only the x = 0 corners remain";
}

TEST(Resampling, DepthCoverageAndMaxDownsample) {
    // 5 -> 3: reduced samples at full x = 0.5, 2.17, 3.83 with footprints 5/3 wide around them,
    // so reduced pixel 0 covers full 0, pixel 1 covers 1..2, pixel 2 covers 3..4.
    EXPECT_EQ(coverBegin(0, 5, 3), 0);
    EXPECT_EQ(coverBegin(1, 5, 3), 1);
    EXPECT_EQ(coverBegin(2, 5, 3), 3);
    EXPECT_EQ(coverBegin(3, 5, 3), 5);
    // 8 -> 4: reduced pixel i samples full pixel 2i and covers 2i - 1 and 2i.
    for (int i = 1; i <= 4; ++i) EXPECT_EQ(coverBegin(i, 8, 4), 2 * i - 1);
    for (int i = 0; i <= 7; ++i) EXPECT_EQ(coverBegin(i, 7, 7), i);
    const std::vector<float> depth = {0.1f, 0.9f, 0.3f, 0.2f, 0.4f};  // 5x1
    EXPECT_EQ(maxDownsampleDepth(depth, {5, 1}, {3, 1}), (std::vector<float>{0.1f, 0.9f, 0.4f}));
}

TEST(Resampling, ReducedSamplesFallOnFullPixelCentres) {
    // Viewport offset (1 - R/F)/2 reduced pixels: 1/4 at half size, 3/8 at a quarter, 0 at full.
    EXPECT_FLOAT_EQ(reducedViewportOffset(640, 1280), 0.25f);
    EXPECT_FLOAT_EQ(reducedViewportOffset(320, 1280), 0.375f);
    EXPECT_FLOAT_EQ(reducedViewportOffset(1280, 1280), 0.0f);
    // Texel i of R samples full x = i F/R + 0.5: at F = 2R the centre of full pixel 2i.
    for (int i = 0; i < 4; ++i) EXPECT_EQ(nearestSampleTexel(i, 4, 8), 2 * i);
    EXPECT_EQ(nearestSampleTexel(3, 5, 8), 5);   // 4.8 rounds to 5
    EXPECT_EQ(nearestSampleTexel(1, 2, 3), 2);   // 1.5: halves round up
    EXPECT_EQ(nearestSampleTexel(2, 4, 2), 1);   // to a smaller image: 1
    EXPECT_EQ(nearestSampleTexel(9, 10, 5), 4);  // 4.5 rounds to 5, clamped to the last texel
}

TEST(Resampling, BilinearUpsample) {
    const std::vector<glm::vec4> ramp = {glm::vec4(0.0f), glm::vec4(1.0f), glm::vec4(2.0f), glm::vec4(3.0f)};  // 4x1
    const auto up = bilinearUpsample(ramp, {4, 1}, {8, 1}, false);
    // Full pixel x maps to u = x / 2 (texel i sampled full pixel 2i): 0, 0.5, 1, ..., 3, 3 (clamped).
    const float want[8] = {0.0f, 0.5f, 1.0f, 1.5f, 2.0f, 2.5f, 3.0f, 3.0f};
    for (int x = 0; x < 8; ++x) EXPECT_FLOAT_EQ(up[size_t(x)].x, want[x]);
    EXPECT_EQ(bilinearUpsample(ramp, {4, 1}, {4, 1}, false), ramp);
    // Alpha-weighted: a neighbour without a fragment lowers alpha, not the colour.
    const std::vector<glm::vec4> edge = {glm::vec4(0.8f, 0.4f, 0.2f, 0.5f), glm::vec4(0.0f)};
    const auto weighted = bilinearUpsample(edge, {2, 1}, {4, 1}, true);
    EXPECT_EQ(weighted[0], edge[0]);
    EXPECT_FLOAT_EQ(weighted[1].r, 0.8f);
    EXPECT_FLOAT_EQ(weighted[1].a, 0.5f * 0.5f);
    EXPECT_EQ(weighted[2], glm::vec4(0.0f));
    EXPECT_EQ(weighted[3], glm::vec4(0.0f));
}
