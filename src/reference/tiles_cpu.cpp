#include "reference/tiles_cpu.hpp"

#include <algorithm>
#include <cmath>

#include "methods/neural/tiles/tile_constants.h"

namespace starnt::tiles {

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

namespace {

float srgbEncode(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

float srgbSquaredError(const glm::vec3& a, const glm::vec3& b) {
    float sum = 0.0f;
    for (int c = 0; c < 3; ++c) {
        const float d = srgbEncode(a[c]) - srgbEncode(b[c]);
        sum += d * d;
    }
    return sum / 3.0f;
}

// The pass shares at one pixel, divided by the transmittance in front of them (what a reduced
// pass interpolates). `valid` is false where that transmittance is too small to divide by.
struct Shares {
    glm::vec3 behind1, behind2;  // (C - a1 C1) / (1 - a1), (C - a1 C1 - (1-a1) a2 C2) / T2
    bool valid1, valid2;
};

Shares sharesAt(const glm::vec4& composite, const glm::vec4& nearest, const glm::vec4& second) {
    const glm::vec3 c = glm::vec3(composite), s2 = c - nearest.a * glm::vec3(nearest);
    const glm::vec3 s3 = s2 - (1.0f - nearest.a) * second.a * glm::vec3(second);
    const float t1 = 1.0f - nearest.a, t2 = t1 * (1.0f - second.a);
    Shares s;
    s.valid1 = t1 > float(STARNT_GUARD_MIN_TRANSMITTANCE);
    s.valid2 = t2 > float(STARNT_GUARD_MIN_TRANSMITTANCE);
    s.behind1 = s.valid1 ? s2 / t1 : glm::vec3(0.0f);
    s.behind2 = s.valid2 ? s3 / t2 : glm::vec3(0.0f);
    return s;
}

}  // namespace

glm::ivec2 guardPixelOfBlock(int blockX, int blockY) {
    uint32_t h = uint32_t(blockX) * 0x8da6b343u ^ uint32_t(blockY) * 0xd8163841u;
    h ^= h >> 13;
    h *= 0x165667b1u;
    h ^= h >> 16;
    return {blockX * 2 + int(h & 1u), blockY * 2 + int((h >> 1) & 1u)};
}

bool guardSamples(int x, int y) { return guardPixelOfBlock(x / 2, y / 2) == glm::ivec2(x, y); }

std::vector<ScaleGuard> scaleGuardTiles(int width, int height, const std::vector<glm::vec4>& composite,
                                        const std::vector<glm::vec4>& nearest, const std::vector<glm::vec4>& second,
                                        GuardPixels pixels) {
    const TileGrid grid = TileGrid::forImage(width, height);
    auto index = [&](int x, int y) { return size_t(y) * size_t(width) + size_t(x); };
    auto shares = [&](int x, int y) { return sharesAt(composite[index(x, y)], nearest[index(x, y)], second[index(x, y)]); };
    std::vector<ScaleGuard> tiles;
    tiles.reserve(size_t(grid.tilesX) * size_t(grid.tilesY));
    for (int ty = 0; ty < grid.tilesY; ++ty) {
        for (int tx = 0; tx < grid.tilesX; ++tx) {
            std::array<float, STARNT_GUARD_VALUES> tile{};
            auto addPixel = [&](int x, int y) {
                if (x >= width || y >= height) return;
                const glm::vec4 n = nearest[index(x, y)], sec = second[index(x, y)];
                if (!(n.a > 0.0f)) return;
                const glm::vec3 c = glm::vec3(composite[index(x, y)]);
                const glm::vec3 front1 = n.a * glm::vec3(n), front2 = front1 + (1.0f - n.a) * sec.a * glm::vec3(sec);
                const float t1 = 1.0f - n.a, t2 = t1 * (1.0f - sec.a);
                tile[STARNT_GUARD_OCCUPIED] += 1.0f;
                tile[STARNT_GUARD_ENERGY_PASS2] += srgbSquaredError(c, front1);
                tile[STARNT_GUARD_ENERGY_PASS3] += srgbSquaredError(c, front2);
                for (int k = 0; k < 2; ++k) {
                    const int step = k == 0 ? 2 : 4;
                    const int lastX = (width - 1) / step * step, lastY = (height - 1) / step * step;
                    const int x0 = x / step * step, y0 = y / step * step;
                    const int x1 = std::min(x0 + step, lastX), y1 = std::min(y0 + step, lastY);
                    const float fx = x1 > x0 ? float(x - x0) / float(step) : 0.0f;
                    const float fy = y1 > y0 ? float(y - y0) / float(step) : 0.0f;
                    const int sx[4] = {x0, x1, x0, x1}, sy[4] = {y0, y0, y1, y1};
                    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
                    glm::vec3 sum1(0.0f), sum2(0.0f);
                    float weight1 = 0.0f, weight2 = 0.0f;
                    for (int i = 0; i < 4; ++i) {
                        const Shares s = shares(sx[i], sy[i]);
                        if (s.valid1) sum1 += w[i] * s.behind1, weight1 += w[i];
                        if (s.valid2) sum2 += w[i] * s.behind2, weight2 += w[i];
                    }
                    const Shares own = shares(x, y);
                    const glm::vec3 behind1 = weight1 > 0.0f ? sum1 / weight1 : own.behind1;
                    const glm::vec3 behind2 = weight2 > 0.0f ? sum2 / weight2 : own.behind2;
                    const glm::vec3 rebuilt2 = own.valid1 ? front1 + t1 * behind1 : c;
                    const glm::vec3 rebuilt3 = own.valid2 ? front2 + t2 * behind2 : c;
                    tile[size_t(STARNT_GUARD_LOSS_PASS2_HALF + k)] += srgbSquaredError(c, rebuilt2);
                    tile[size_t(STARNT_GUARD_LOSS_PASS3_HALF + k)] += srgbSquaredError(c, rebuilt3);
                }
            };
            if (pixels == GuardPixels::Sampled) {
                // One pixel per 2x2 block, blocks in the shader's local invocation order.
                for (int by = 0; by < STARNT_TILE_SIZE / 2; ++by) {
                    for (int bx = 0; bx < STARNT_TILE_SIZE / 2; ++bx) {
                        const glm::ivec2 chosen = guardPixelOfBlock(tx * STARNT_TILE_SIZE / 2 + bx, ty * STARNT_TILE_SIZE / 2 + by);
                        addPixel(chosen.x, chosen.y);
                    }
                }
            } else {
                for (int y = ty * STARNT_TILE_SIZE; y < (ty + 1) * STARNT_TILE_SIZE; ++y) {
                    for (int x = tx * STARNT_TILE_SIZE; x < (tx + 1) * STARNT_TILE_SIZE; ++x) addPixel(x, y);
                }
            }
            ScaleGuard g;
            g.occupied = tile[STARNT_GUARD_OCCUPIED];
            g.energy2 = tile[STARNT_GUARD_ENERGY_PASS2];
            g.energy3 = tile[STARNT_GUARD_ENERGY_PASS3];
            for (int k = 0; k < 2; ++k) {
                g.loss2[size_t(k)] = tile[size_t(STARNT_GUARD_LOSS_PASS2_HALF + k)];
                g.loss3[size_t(k)] = tile[size_t(STARNT_GUARD_LOSS_PASS3_HALF + k)];
            }
            tiles.push_back(g);
        }
    }
    return tiles;
}

ScaleGuard scaleGuardSums(int width, int height, const std::vector<glm::vec4>& composite,
                          const std::vector<glm::vec4>& nearest, const std::vector<glm::vec4>& second) {
    ScaleGuard total;
    for (const ScaleGuard& tile : scaleGuardTiles(width, height, composite, nearest, second, GuardPixels::Sampled)) total += tile;
    return total;
}

ColorImage tileSignalImage(TileSignal signal, int width, int height, const std::vector<glm::vec4>& composite,
                           const std::vector<glm::vec4>& nearest) {
    ColorImage image{width, height, std::vector<glm::vec3>(size_t(width) * size_t(height))};
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        image.rgb[i] = glm::vec3(composite[i]);
        if (signal == TileSignal::Back) image.rgb[i] -= nearest[i].a * glm::vec3(nearest[i]);
    }
    return image;
}

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
