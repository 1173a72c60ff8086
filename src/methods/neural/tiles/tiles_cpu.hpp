// CPU reference of the adaptive tiles (SPEC sections 4-5): mask evaluation with hysteresis, the
// one-level-per-frame limit, neighbour balance, the occupied-tile histogram, w_bar and the pass
// scales. The GPU passes (tiles_gpu.*) implement the same rules; tests compare them mask for mask.
//
// Coordinates are GL window coordinates: pixel (0, 0) is bottom-left, tile (0, 0) covers pixels
// 0..15 x 0..15, tiles are stored row-major (index = ty * tilesX + tx). Edge tiles may be partial.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "starnt/oit_method.hpp"

namespace starnt::tiles {

struct TileGrid {
    int width = 0, height = 0;    // image size in pixels
    int tilesX = 0, tilesY = 0;   // ceil(size / 16)
    static TileGrid forImage(int width, int height);
    int count() const { return tilesX * tilesY; }
};

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
// sum l N_l / sum N_l; 0 when no tile is occupied.
double meanLevel(const std::array<uint32_t, 4>& histogram);
// s = clamp(2^(w_bar - delta), 0.25, 1) (the paper's formula, rule `continuous`).
float passScale(double wBar, double delta);

// How w_bar becomes a pass scale (SPEC 5, `--scale-rule`).
using ScaleRule = MethodOptions::ScaleRule;
// snapped: 2^round(log2 passScale) in {1, 1/2, 1/4} (the default: integer ratios keep every
// reduced sample on a full-resolution pixel centre); continuous: passScale; step: the authors'
// release (w_bar > 2 -> 1, w_bar > 1 -> 1/2, else 1/4; the same for both passes).
float ruleScale(ScaleRule rule, double wBar, double delta);

// What the reduced passes would lose, measured on a frame whose passes all ran at full
// resolution (tile_scale_guard.comp.glsl; CPU reference scaleGuardSums). Values are sums over
// occupied pixels (pass-1 alpha > 0) of the mean over RGB of squared sRGB differences:
//   energy_p: what pass p adds (the composite against the composite without pass p's share);
//   loss_p[k]: the composite against the one whose pass-p share is reconstructed bilinearly from
//              every 2nd (k = 0) or 4th (k = 1) pixel, as a pass at scale 1/2 or 1/4 samples it.
// Pass 2's share is C - a1 C1 (all behind the nearest layer), pass 3's C - a1 C1 - (1-a1) a2 C2.
// Sums run over the pixels guardSamples() picks.
struct ScaleGuard {
    float occupied = 0.0f;
    float energy2 = 0.0f, energy3 = 0.0f;
    std::array<float, 2> loss2{}, loss3{};
};
// The scales the guard picks: of the pairs (s2, s3) with s3 <= s2 in {1, 1/2, 1/4}, the cheapest
// (fewest fragments, s2^2 + s3^2) whose predicted loss is at most `budget` x the occupied pixels
// (an added MSE of at most `budget` over the pixels with a transparent fragment). Predicted loss of
// a pair: loss2(s2) (pass 2 at s2 interpolates everything behind the nearest layer) plus what pass
// 3 at a coarser s3 loses beyond that, max(0, loss3(s3) - loss3(s2)); loss(1) = 0. Ties go to the
// finer pair.
struct PassScales {
    float pass2 = 1.0f, pass3 = 1.0f;
};
PassScales guardScales(const ScaleGuard& guard, double budget);
// The predicted loss of one pair (as above), for tests and stats.
double guardPredictedLoss(const ScaleGuard& guard, float scale2, float scale3);

// The pixel of 2x2 block (blockX, blockY) the guard evaluates, picked by an integer hash of the
// block: one pixel in four, evenly over the classes of the reduced sample grids.
glm::ivec2 guardPixelOfBlock(int blockX, int blockY);
// True for the pixels the guard evaluates.
bool guardSamples(int x, int y);

// Pixels in GL order (rows bottom-first): composite (rgb), pass-1 colour + alpha, pass-2 colour +
// alpha, all at full resolution. Sums per 16x16 tile in pixel order, then over tiles in order (as
// the GPU does).
ScaleGuard scaleGuardSums(int width, int height, const std::vector<glm::vec4>& composite,
                          const std::vector<glm::vec4>& nearest, const std::vector<glm::vec4>& second);

// What the tiles measure (`--tile-signal`): the composite (the paper) or the composite minus the
// nearest layer's own term, C - a1 C1 (what passes 2 and 3 produce; the default).
using TileSignal = MethodOptions::TileSignal;
ColorImage tileSignalImage(TileSignal signal, int width, int height, const std::vector<glm::vec4>& composite,
                           const std::vector<glm::vec4>& nearest);
// ceil(size * scale), at least 1.
int scaledSize(int size, float scale);

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
