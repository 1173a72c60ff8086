// Offline study: how many pass-2 + pass-3 fragments per-tile scales would save under the
// scale guard's own loss budget, against the global scales the guard picks today. Not a test and
// not part of the library: it measures what a per-tile shading rate could buy before anyone builds
// one (docs/DESIGN.md, "Scale guard", says why the runtime keeps global scales).
//
//   starnt_per_tile_study [--width W] [--scenes a,b,...] [--budgets b1,b2,...]
//
// For each suite scene (bench::suiteScenes(), read from ../shared/scenes, default camera orbit
// 0/15) it captures every fragment (A-buffer), composites each pixel exactly, and evaluates the
// guard's per-pixel prediction (tiles::scaleGuardTiles, the CPU reference of
// tile_scale_guard.comp.glsl) at EVERY pixel, summed per 16x16 tile, with the tile's fragment count
// (every rasterised fragment: passes 2 and 3 shade each of them at full resolution). Then:
//   global:   tiles::guardScales on the sums over all tiles (what the runtime does);
//   per tile: one pair (s2, s3), s3 <= s2 in {1, 1/2, 1/4}, per tile, minimising the fragments of
//             passes 2 + 3 (N (s2^2 + s3^2) per tile) with the summed predicted loss (the guard's
//             rule, tiles::guardPredictedLoss, per tile) within budget x occupied pixels, by a
//             Lagrangian search (exact for this separable problem up to the convex hull);
//   joint:    the same with s2 = s3 in every tile (one stride map for both passes).
//   rates:    what the runtime's per-tile shading rates do (--shading-rate-image; tiles::tileShadingRate
//             per tile: pass 2 at full rate, pass 3 at the coarsest rate within the tile's own
//             share of the budget): the saving of pass-3 invocations, and of passes 2 + 3.
// Prints the fragment saving against full resolution and the predicted added MSE over the image.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "methods/neural/tiles/tile_constants.h"
#include "methods/neural/tiles/tile_rules.hpp"
#include "reference/tiles_cpu.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;

namespace {

struct Choice {
    double fragments = 0.0, loss = 0.0;
};

// The pairs a tile may take, as (s2, s3).
struct Pair {
    float s2, s3;
};
const Pair kPairs[] = {{1.0f, 1.0f}, {1.0f, 0.5f}, {1.0f, 0.25f}, {0.5f, 0.5f}, {0.5f, 0.25f}, {0.25f, 0.25f}};

// Per tile, the pair minimising fragments + lambda x loss; the smallest lambda whose total loss is
// within `allowed` (bisection in log lambda).
Choice perTileChoice(const std::vector<tiles::ScaleGuard>& tiles, const std::vector<double>& fragments, double allowed,
                     bool joint) {
    auto solve = [&](double lambda) {
        Choice c;
        for (size_t t = 0; t < tiles.size(); ++t) {
            double bestValue = 1e300, bestFragments = 0.0, bestLoss = 0.0;
            for (const Pair& p : kPairs) {
                if (joint && p.s2 != p.s3) continue;
                const double f = fragments[t] * (double(p.s2) * p.s2 + double(p.s3) * p.s3);
                const double l = tiles::guardPredictedLoss(tiles[t], p.s2, p.s3);
                if (f + lambda * l < bestValue) bestValue = f + lambda * l, bestFragments = f, bestLoss = l;
            }
            c.fragments += bestFragments;
            c.loss += bestLoss;
        }
        return c;
    };
    double low = 1e-3, high = 1e15;
    Choice best = solve(high);  // (nearly) full resolution wherever anything is lost
    for (int i = 0; i < 100 && high / low > 1.0001; ++i) {
        const double mid = std::sqrt(low * high);
        const Choice c = solve(mid);
        if (c.loss <= allowed) high = mid, best = c;
        else low = mid;
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    int width = 1280;
    std::vector<std::string> names = {"engine", "tree", "powerplant", "gearbox", "hair", "hairball", "smoke",
                                      "chess", "magic_stars"};
    std::vector<double> budgets = {2.5e-5, 1e-4, 4e-4};
    const auto readBudgets = [&](const std::string& value) {
        budgets.clear();
        for (const auto& b : study::splitList(value)) budgets.push_back(std::atof(b.c_str()));
    };
    if (!study::parseStudyArgs(argc, argv, "per_tile_study", width, names, {{"--budgets", readBudgets}})) return 2;
    const int height = width * 9 / 16;
    try {
        HeadlessGlContext context(GlApi::Desktop);
        std::printf("budget = allowed added MSE per occupied pixel (the runtime's STARNT_SCALE_GUARD_BUDGET is %.1e)\n",
                    double(STARNT_SCALE_GUARD_BUDGET));
        std::printf("%-12s %9s %10s | %-8s %12s | %-14s %14s | %s\n", "scene", "budget", "fragments", "global", "saving",
                    "per-tile saving", "joint saving", "rates: pass 3, passes 2+3 saving");
        for (const std::string& name : names) {
            const study::CapturedScene captured = study::captureSuiteScene(name, width, height);
            const bench::SceneSpec* spec = &captured.spec;
            const FrameDesc& frame = captured.frame;
            const CapturedFrame& fragments = captured.fragments;
            // Exact composite, nearest and second layer per pixel, in GL order (rows bottom-first).
            const size_t pixels = size_t(width) * size_t(height);
            std::vector<glm::vec4> composite(pixels), nearest(pixels), second(pixels);
            const tiles::TileGrid grid = tiles::TileGrid::forImage(width, height);
            std::vector<double> tileFragments(size_t(grid.tilesX) * size_t(grid.tilesY), 0.0);
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const FragmentList& raw = fragments.at(x, height - 1 - y);
                    const size_t i = size_t(y) * size_t(width) + size_t(x);
                    tileFragments[size_t(y / STARNT_TILE_SIZE) * size_t(grid.tilesX) + size_t(x / STARNT_TILE_SIZE)] +=
                        double(raw.size());
                    const FragmentList list = nn::preparedFragments(raw, spec->alphaCutoff);
                    composite[i] = glm::vec4(compositeOver(list, frame.background), 1.0f);
                    if (list.size() > 0) nearest[i] = glm::vec4(list[0].color, list[0].alpha);
                    if (list.size() > 1) second[i] = glm::vec4(list[1].color, list[1].alpha);
                }
            }
            const std::vector<tiles::ScaleGuard> tileSums =
                tiles::scaleGuardTiles(width, height, composite, nearest, second, tiles::GuardPixels::Every);
            tiles::ScaleGuard total;
            double allFragments = 0.0;
            for (size_t t = 0; t < tileSums.size(); ++t) {
                total += tileSums[t];
                allFragments += tileFragments[t];
            }
            for (double budget : budgets) {
                const double allowed = budget * double(total.occupied);
                const tiles::PassScales global = tiles::guardScales(total, budget);
                const double globalSaving = 1.0 - (double(global.pass2) * global.pass2 + double(global.pass3) * global.pass3) / 2.0;
                const Choice separate = perTileChoice(tileSums, tileFragments, allowed, false);
                const Choice joint = perTileChoice(tileSums, tileFragments, allowed, true);
                double ratePass3 = 0.0, rateLoss = 0.0;  // the runtime's per-tile rule
                for (size_t t = 0; t < tileSums.size(); ++t) {
                    const uint32_t rate = tiles::tileShadingRate(tileSums[t], float(budget));
                    const float scale = rate == STARNT_SHADING_RATE_QUARTER ? 0.25f : rate == STARNT_SHADING_RATE_HALF ? 0.5f : 1.0f;
                    ratePass3 += tileFragments[t] * double(scale) * scale;
                    rateLoss += tiles::guardPredictedLoss(tileSums[t], 1.0f, scale);
                }
                char globalText[32];
                std::snprintf(globalText, sizeof globalText, "%g/%g", double(global.pass2), double(global.pass3));
                std::printf("%-12s %9.1e %10.0f | %-8s %11.1f%% | %6.1f%% (+%.1e) %6.1f%% (+%.1e) | %6.1f%% %6.1f%% (+%.1e)\n",
                            name.c_str(), budget, allFragments, globalText, 100.0 * globalSaving,
                            100.0 * (1.0 - separate.fragments / (2.0 * allFragments)), separate.loss / double(pixels),
                            100.0 * (1.0 - joint.fragments / (2.0 * allFragments)), joint.loss / double(pixels),
                            100.0 * (1.0 - ratePass3 / allFragments), 100.0 * (1.0 - (allFragments + ratePass3) / (2.0 * allFragments)),
                            rateLoss / double(pixels));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "per_tile_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
