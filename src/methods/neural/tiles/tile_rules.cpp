#include "methods/neural/tiles/tile_rules.hpp"

#include <algorithm>
#include <cmath>

#include "methods/neural/tiles/tile_constants.h"

namespace starnt::tiles {

TileGrid TileGrid::forImage(int width, int height) {
    TileGrid grid;
    grid.width = width;
    grid.height = height;
    grid.tilesX = (width + STARNT_TILE_SIZE - 1) / STARNT_TILE_SIZE;
    grid.tilesY = (height + STARNT_TILE_SIZE - 1) / STARNT_TILE_SIZE;
    return grid;
}

double meanLevel(const std::array<uint32_t, 4>& histogram) {
    double weighted = 0.0, total = 0.0;
    for (int l = 0; l < 4; ++l) {
        weighted += double(l) * histogram[size_t(l)];
        total += histogram[size_t(l)];
    }
    return total > 0.0 ? weighted / total : 0.0;
}

float passScale(double wBar, double delta) {
    return float(std::clamp(std::exp2(wBar - delta), double(STARNT_SCALE_MIN), 1.0));
}

float ruleScale(ScaleRule rule, double wBar, double delta) {
    switch (rule) {
        case ScaleRule::Continuous: return passScale(wBar, delta);
        case ScaleRule::Step: return wBar > 2.0 ? 1.0f : wBar > 1.0 ? 0.5f : 0.25f;
        case ScaleRule::Snapped: break;
    }
    const double snapped = std::exp2(std::round(std::log2(double(passScale(wBar, delta)))));
    return float(std::clamp(snapped, double(STARNT_SCALE_MIN), 1.0));
}

namespace {

// loss[0] / loss[1] are the losses at 1/2 and 1/4; 0 at full resolution.
double lossAt(const std::array<float, 2>& loss, float scale) {
    return scale >= 1.0f ? 0.0 : scale >= 0.5f ? double(loss[0]) : double(loss[1]);
}

}  // namespace

double guardPredictedLoss(const ScaleGuard& guard, float scale2, float scale3) {
    return lossAt(guard.loss2, scale2) + std::max(0.0, lossAt(guard.loss3, scale3) - lossAt(guard.loss3, scale2));
}

PassScales guardScales(const ScaleGuard& guard, double budget) {
    const double allowed = budget * double(guard.occupied);
    const float scales[3] = {1.0f, 0.5f, 0.25f};
    PassScales best;
    double bestCost = 2.0;
    for (float s2 : scales) {
        for (float s3 : scales) {
            if (s3 > s2) continue;
            const double cost = double(s2) * s2 + double(s3) * s3;
            if (cost < bestCost && guardPredictedLoss(guard, s2, s3) <= allowed) {
                best = {s2, s3};
                bestCost = cost;
            }
        }
    }
    return best;
}

uint32_t tileShadingRate(const ScaleGuard& tile, float budget) {
    if (!(tile.occupied > 0.0f)) return STARNT_SHADING_RATE_FULL;
    // With pass 2 at full resolution, a pass-3 rate loses loss3 of its scale (guardPredictedLoss).
    const float allowed = budget * tile.occupied;
    if (tile.loss3[1] <= allowed) return STARNT_SHADING_RATE_QUARTER;
    if (tile.loss3[0] <= allowed) return STARNT_SHADING_RATE_HALF;
    return STARNT_SHADING_RATE_FULL;
}

int scaledSize(int size, float scale) { return std::max(1, int(std::ceil(double(size) * double(scale) - 1e-9))); }

}  // namespace starnt::tiles
