// The rules the runtime applies to what the tiles measure (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): the tile grid,
// w_bar from the level histogram, w_bar -> pass scales, the scale guard's choice, reduced sizes.
// Runtime code (tiles_gpu.cpp, neural_method.cpp) and the CPU reference (tiles_cpu.*) share them.
#pragma once
#include <array>
#include <cstdint>

#include "starnt/oit_method.hpp"

namespace starnt::tiles {

struct TileGrid {
    int width = 0, height = 0;    // image size in pixels
    int tilesX = 0, tilesY = 0;   // ceil(size / 16)
    static TileGrid forImage(int width, int height);
    int count() const { return tilesX * tilesY; }
};

// sum l N_l / sum N_l; 0 when no tile is occupied.
double meanLevel(const std::array<uint32_t, 4>& histogram);
// s = clamp(2^(w_bar - delta), 0.25, 1) (the paper's formula, rule `continuous`).
float passScale(double wBar, double delta);

// How w_bar becomes a pass scale (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution", `--scale-rule`), and what the tiles measure (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution").
using ScaleRule = NeuralOptions::ScaleRule;
using TileSignal = NeuralOptions::TileSignal;
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
    // Adds another set of sums (a tile's to a total), field by field.
    ScaleGuard& operator+=(const ScaleGuard& o) {
        occupied += o.occupied;
        energy2 += o.energy2;
        energy3 += o.energy3;
        for (size_t k = 0; k < 2; ++k) {
            loss2[k] += o.loss2[k];
            loss3[k] += o.loss3[k];
        }
        return *this;
    }
};
// True when a reading measured something: occupied pixels with something behind the nearest layer
// (energy in pass 2 or pass 3). Without it the reading says nothing about reducing.
inline bool guardMeasured(const ScaleGuard& g) { return g.occupied > 0.0f && (g.energy2 > 0.0f || g.energy3 > 0.0f); }
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

// The shading-rate class of one tile (tile_constants.h, STARNT_SHADING_RATE_*) from its own guard
// sums: the coarsest rate for pass 3 whose predicted loss in the tile (guardPredictedLoss with pass
// 2 at full resolution) is at most `budget` x the tile's occupied pixels; full rate for a tile with
// no occupied pixel. So the whole image stays within the guard's budget too. Float arithmetic, as
// tile_shading_rate.comp.glsl does it.
uint32_t tileShadingRate(const ScaleGuard& tile, float budget);

// ceil(size * scale), at least 1: a reduced pass's size along one axis.
int scaledSize(int size, float scale);

}  // namespace starnt::tiles
