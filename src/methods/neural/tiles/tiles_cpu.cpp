#include "methods/neural/tiles/tiles_cpu.hpp"

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

int maskLevel(uint32_t mask) {
    if (mask & (STARNT_TILE_MASK_LEVEL3 & ~STARNT_TILE_MASK_LEVEL2)) return 3;
    if (mask & (STARNT_TILE_MASK_LEVEL2 & ~STARNT_TILE_MASK_LEVEL1)) return 2;
    if (mask & STARNT_TILE_MASK_LEVEL1) return 1;
    return 0;
}

uint32_t uniformMask(int level) {
    switch (level) {
        case 0: return 0u;
        case 1: return STARNT_TILE_MASK_LEVEL1;
        case 2: return STARNT_TILE_MASK_LEVEL2;
        default: return STARNT_TILE_MASK_LEVEL3;
    }
}

bool maskIsConsistent(uint32_t mask) {
    if (mask & ~uint32_t(STARNT_TILE_MASK_LEVEL3)) return false;
    const bool root = mask & 1u;
    for (uint32_t q = 0; q < 4; ++q) {
        const bool quadrant = mask & (1u << (STARNT_TILE_BIT_QUADRANT0 + q));
        if (quadrant && !root) return false;
        for (uint32_t c = 0; c < 4; ++c) {
            if ((mask & (1u << (STARNT_TILE_BIT_CHILD0 + 4 * q + c))) && !quadrant) return false;
        }
    }
    return true;
}

float nodeVariation(const ColorImage& image, int x0, int y0, int size) {
    const int x1 = std::min(x0 + size - 1, image.width - 1), y1 = std::min(y0 + size - 1, image.height - 1);
    const glm::vec3 c[4] = {image.at(x0, y0), image.at(x1, y0), image.at(x0, y1), image.at(x1, y1)};
    float sum = 0.0f;
    for (int i = 0; i < 4; ++i) {
        for (int j = i + 1; j < 4; ++j) sum += glm::length(c[i] - c[j]);
    }
    return sum / 6.0f;
}

namespace {

// Split decision of one node with hysteresis: split when D > split; kept split while D >= merge.
bool nodeSplits(float variation, bool wasSplit, float split, float merge) {
    return variation > split || (wasSplit && variation >= merge);
}

}  // namespace

uint32_t evaluateTileMask(const ColorImage& image, int tx, int ty, uint32_t previousMask) {
    const int x0 = tx * STARNT_TILE_SIZE, y0 = ty * STARNT_TILE_SIZE;
    uint32_t mask = 0u;
    if (!nodeSplits(nodeVariation(image, x0, y0, 16), previousMask & 1u, float(STARNT_TILE_SPLIT_16),
                    float(STARNT_TILE_MERGE_16))) {
        return mask;
    }
    mask |= 1u;
    for (uint32_t q = 0; q < 4; ++q) {
        const int qx = x0 + int(q & 1u) * 8, qy = y0 + int(q >> 1) * 8;
        // Quadrants wholly outside a partial edge tile never split (they have no pixels).
        if (qx >= image.width || qy >= image.height) continue;
        const uint32_t qBit = 1u << (STARNT_TILE_BIT_QUADRANT0 + q);
        if (!nodeSplits(nodeVariation(image, qx, qy, 8), previousMask & qBit, float(STARNT_TILE_SPLIT_8),
                        float(STARNT_TILE_MERGE_8))) {
            continue;
        }
        mask |= qBit;
        for (uint32_t c = 0; c < 4; ++c) {
            const int cx = qx + int(c & 1u) * 4, cy = qy + int(c >> 1) * 4;
            if (cx >= image.width || cy >= image.height) continue;
            const uint32_t cBit = 1u << (STARNT_TILE_BIT_CHILD0 + 4 * q + c);
            if (nodeSplits(nodeVariation(image, cx, cy, 4), previousMask & cBit, float(STARNT_TILE_SPLIT_4),
                           float(STARNT_TILE_MERGE_4))) {
                mask |= cBit;
            }
        }
    }
    return mask;
}

uint32_t limitLevelChange(uint32_t mask, int previousLevel) {
    const int level = maskLevel(mask);
    if (level > previousLevel + 1) return mask & uniformMask(previousLevel + 1);
    if (level < previousLevel - 1) return mask | uniformMask(previousLevel - 1);
    return mask;
}

std::vector<uint32_t> balanceOnce(const std::vector<uint32_t>& masks, const TileGrid& grid) {
    std::vector<uint32_t> out(masks.size());
    for (int ty = 0; ty < grid.tilesY; ++ty) {
        for (int tx = 0; tx < grid.tilesX; ++tx) {
            const size_t i = size_t(ty) * size_t(grid.tilesX) + size_t(tx);
            int finest = 0;
            if (tx > 0) finest = std::max(finest, maskLevel(masks[i - 1]));
            if (tx + 1 < grid.tilesX) finest = std::max(finest, maskLevel(masks[i + 1]));
            if (ty > 0) finest = std::max(finest, maskLevel(masks[i - size_t(grid.tilesX)]));
            if (ty + 1 < grid.tilesY) finest = std::max(finest, maskLevel(masks[i + size_t(grid.tilesX)]));
            out[i] = maskLevel(masks[i]) < finest - 1 ? masks[i] | uniformMask(finest - 1) : masks[i];
        }
    }
    return out;
}

std::array<uint32_t, 4> levelHistogram(const std::vector<uint32_t>& masks, const std::vector<uint8_t>& occupiedTiles) {
    std::array<uint32_t, 4> histogram{};
    for (size_t i = 0; i < masks.size(); ++i) {
        if (occupiedTiles[i]) histogram[size_t(maskLevel(masks[i]))]++;
    }
    return histogram;
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

int scaledSize(int size, float scale) { return std::max(1, int(std::ceil(double(size) * double(scale) - 1e-9))); }

std::vector<uint8_t> occupiedTiles(const TileGrid& grid, const std::vector<float>& nearestAlpha) {
    std::vector<uint8_t> occupied(size_t(grid.count()), 0);
    for (int y = 0; y < grid.height; ++y) {
        for (int x = 0; x < grid.width; ++x) {
            if (nearestAlpha[size_t(y) * size_t(grid.width) + size_t(x)] > 0.0f) {
                occupied[size_t(y / STARNT_TILE_SIZE) * size_t(grid.tilesX) + size_t(x / STARNT_TILE_SIZE)] = 1;
            }
        }
    }
    return occupied;
}

Leaf leafOf(uint32_t mask, int x, int y) {
    Leaf leaf{x / STARNT_TILE_SIZE * STARNT_TILE_SIZE, y / STARNT_TILE_SIZE * STARNT_TILE_SIZE, 16};
    if (!(mask & 1u)) return leaf;
    const int qx = (x - leaf.x0) / 8, qy = (y - leaf.y0) / 8;
    const uint32_t q = uint32_t(qy * 2 + qx);
    leaf = {leaf.x0 + 8 * qx, leaf.y0 + 8 * qy, 8};
    if (!(mask & (1u << (STARNT_TILE_BIT_QUADRANT0 + q)))) return leaf;
    const int cx = (x - leaf.x0) / 4, cy = (y - leaf.y0) / 4;
    const uint32_t c = uint32_t(cy * 2 + cx);
    leaf = {leaf.x0 + 4 * cx, leaf.y0 + 4 * cy, 4};
    if (!(mask & (1u << (STARNT_TILE_BIT_CHILD0 + 4 * q + c)))) return leaf;
    return {leaf.x0 + (x - leaf.x0) / 2 * 2, leaf.y0 + (y - leaf.y0) / 2 * 2, 2};
}

std::vector<glm::vec3> cornerInterpolatedNetwork(const TileGrid& grid, const std::vector<uint32_t>& masks,
                                                 const std::function<bool(int, int)>& applies,
                                                 const std::function<glm::vec3(int, int)>& evaluate) {
    std::vector<glm::vec3> out(size_t(grid.width) * size_t(grid.height), glm::vec3(0.0f));
    for (int y = 0; y < grid.height; ++y) {
        for (int x = 0; x < grid.width; ++x) {
            if (!applies(x, y)) continue;
            const int tile = (y / STARNT_TILE_SIZE) * grid.tilesX + x / STARNT_TILE_SIZE;
            const Leaf leaf = leafOf(masks[size_t(tile)], x, y);
            const int x0 = leaf.x0, y0 = leaf.y0;
            const int x1 = std::min(leaf.x0 + leaf.size - 1, grid.width - 1);
            const int y1 = std::min(leaf.y0 + leaf.size - 1, grid.height - 1);
            const float u = x1 > x0 ? float(x - x0) / float(x1 - x0) : 0.0f;
            const float v = y1 > y0 ? float(y - y0) / float(y1 - y0) : 0.0f;
            const int cx[4] = {x0, x1, x0, x1}, cy[4] = {y0, y0, y1, y1};
            const float w[4] = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
            glm::vec3 sum(0.0f);
            float weight = 0.0f;
            for (int k = 0; k < 4; ++k) {
                if (!applies(cx[k], cy[k])) continue;
                sum += w[k] * evaluate(cx[k], cy[k]);
                weight += w[k];
            }
            out[size_t(y) * size_t(grid.width) + size_t(x)] = weight > 0.0f ? sum / weight : evaluate(x, y);
        }
    }
    return out;
}

TileUpdate updateTiles(const ColorImage& image, const std::vector<float>& nearestAlpha,
                       const std::vector<uint32_t>& previousMasks) {
    const TileGrid grid = TileGrid::forImage(image.width, image.height);
    TileUpdate update;
    update.masks.resize(size_t(grid.count()));
    for (int ty = 0; ty < grid.tilesY; ++ty) {
        for (int tx = 0; tx < grid.tilesX; ++tx) {
            const size_t i = size_t(ty) * size_t(grid.tilesX) + size_t(tx);
            const uint32_t previous = previousMasks.empty() ? 0u : previousMasks[i];
            update.masks[i] = limitLevelChange(evaluateTileMask(image, tx, ty, previous), maskLevel(previous));
        }
    }
    for (int k = 0; k < STARNT_TILE_BALANCE_ITERATIONS; ++k) update.masks = balanceOnce(update.masks, grid);
    update.histogram = levelHistogram(update.masks, occupiedTiles(grid, nearestAlpha));
    update.wBar = meanLevel(update.histogram);
    return update;
}

}  // namespace starnt::tiles
