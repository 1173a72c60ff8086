// CPU reference of the adaptive tiles (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): mask evaluation with hysteresis, the
// one-level-per-frame limit, neighbour balance, the occupied-tile histogram and the scale guard's
// sums. The rules the runtime applies to their results (w_bar -> scales) are in tile_rules.hpp. The GPU passes (tiles_gpu.*) implement the same rules; tests compare them mask for mask.
//
// Coordinates are GL window coordinates: pixel (0, 0) is bottom-left, tile (0, 0) covers pixels
// 0..15 x 0..15, tiles are stored row-major (index = ty * tilesX + tx). Edge tiles may be partial.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "methods/neural/tiles/tile_rules.hpp"

namespace starnt::tiles {

// Levels 0..3 and the masks that go with them.
int maskLevel(uint32_t mask);
// Every bit of the levels below `level`: the uniform split to that level (0 -> 0, 3 -> 21 bits).
uint32_t uniformMask(int level);
// True when no bit is set without its parent bit.
bool maskIsConsistent(uint32_t mask);

// Composited linear RGB of the image, rows bottom-first (GL order), as the tiles see it.
struct ColorImage {
    int width = 0, height = 0;
    std::vector<glm::vec3> rgb;  // width * height
    const glm::vec3& at(int x, int y) const { return rgb[size_t(y) * size_t(width) + size_t(x)]; }
};

// D of the node with lower-left pixel (x0, y0) and edge `size`: mean of the 6 pairwise distances of
// its 4 corner colours; corners x0 and x0 + size - 1 (same in y), clamped to the image.
float nodeVariation(const ColorImage& image, int x0, int y0, int size);

// Top-down evaluation of one tile with hysteresis against the previous mask.
uint32_t evaluateTileMask(const ColorImage& image, int tx, int ty, uint32_t previousMask);
// Limits the level change against the previous level to one: prunes the bits below prev + 1 or
// adds the uniform split to prev - 1.
uint32_t limitLevelChange(uint32_t mask, int previousLevel);
// One Jacobi iteration: a tile whose finest 4-neighbour is more than one level finer is split
// uniformly (added to its mask) to that neighbour's level minus one.
std::vector<uint32_t> balanceOnce(const std::vector<uint32_t>& masks, const TileGrid& grid);

// N_0..N_3 over occupied tiles (occupiedTiles[i] != 0).
std::array<uint32_t, 4> levelHistogram(const std::vector<uint32_t>& masks, const std::vector<uint8_t>& occupiedTiles);
// The pixel of 2x2 block (blockX, blockY) the guard evaluates, picked by an integer hash of the
// block: one pixel in four, evenly over the classes of the reduced sample grids.
glm::ivec2 guardPixelOfBlock(int blockX, int blockY);
// True for the pixels the guard evaluates.
bool guardSamples(int x, int y);

// The guard's sums of each 16x16 tile (row-major from the bottom), in pixel order, over the pixels
// guardSamples() picks (as the GPU does) or over every pixel (`Every`: offline studies, e.g.
// benchmarks/per_tile_scale_study.cpp).
enum class GuardPixels { Sampled, Every };
std::vector<ScaleGuard> scaleGuardTiles(int width, int height, const std::vector<glm::vec4>& composite,
                                        const std::vector<glm::vec4>& nearest, const std::vector<glm::vec4>& second,
                                        GuardPixels pixels);
// Pixels in GL order (rows bottom-first): composite (rgb), pass-1 colour + alpha, pass-2 colour +
// alpha, all at full resolution. Sums per 16x16 tile in pixel order, then over tiles in order (as
// the GPU does).
ScaleGuard scaleGuardSums(int width, int height, const std::vector<glm::vec4>& composite,
                          const std::vector<glm::vec4>& nearest, const std::vector<glm::vec4>& second);

// What the tiles measure (`--tile-signal`): the composite (the paper) or the composite minus the
// nearest layer's own term, C - a1 C1 (what passes 2 and 3 produce; the default).
ColorImage tileSignalImage(TileSignal signal, int width, int height, const std::vector<glm::vec4>& composite,
                           const std::vector<glm::vec4>& nearest);

// Per tile: 1 when any pixel of it has a transparent fragment (pass-1 alpha > 0).
std::vector<uint8_t> occupiedTiles(const TileGrid& grid, const std::vector<float>& nearestAlpha);

// The quadtree leaf containing pixel (x, y) of a tile with `mask` (lower-left pixel and edge).
struct Leaf {
    int x0 = 0, y0 = 0, size = 16;
};
Leaf leafOf(uint32_t mask, int x, int y);

// CPU reference of spatially selective inference (infer_corners + infer_fill): where `applies`,
// the network output is the bilinear interpolation of the outputs at the pixel's leaf corners
// (x0 and min(x0 + size - 1, W - 1), same in y), weighted to the corners where the network
// applies; without such a corner the pixel evaluates the network itself. Zero elsewhere.
std::vector<glm::vec3> cornerInterpolatedNetwork(const TileGrid& grid, const std::vector<uint32_t>& masks,
                                                 const std::function<bool(int, int)>& applies,
                                                 const std::function<glm::vec3(int, int)>& evaluate);

struct TileUpdate {
    std::vector<uint32_t> masks;
    std::array<uint32_t, 4> histogram{};
    double wBar = 0.0;
};
// The whole per-frame update: evaluate -> limit -> balance (2 iterations) -> histogram -> w_bar.
// `previousMasks` empty means all zero (first frame).
TileUpdate updateTiles(const ColorImage& image, const std::vector<float>& nearestAlpha,
                       const std::vector<uint32_t>& previousMasks);

}  // namespace starnt::tiles
