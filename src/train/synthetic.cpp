// Synthetic per-pixel fragment lists for training and tests.
#include <algorithm>
#include <cmath>

#include "nn/random.hpp"
#include "starnt/tools/train.hpp"

namespace starnt::nn {

namespace {

int drawCount(detail::Rng& rng) {
    const double u = rng.uniform();
    if (u < 0.05) return rng.range(0, 3);     // trivial pixels (exact for STAR-NT)
    if (u < 0.45) return rng.range(4, 12);    // typical overlap
    if (u < 0.75) return rng.range(4, 32);
    if (u < 0.93) {                           // long, geometric-like tail
        const double v = rng.uniform();
        return 4 + static_cast<int>(96.0 * v * v);
    }
    return rng.range(32, 200);                // hair, foliage, smoke
}

enum class AlphaMode { UniformRange, Clustered, NearCutoff, NearOne, Mixed };
enum class ColorMode { Random, Similar, Grey, Palette, Dark };

float clamp01(double v) { return static_cast<float>(std::clamp(v, 0.0, 1.0)); }

}  // namespace

std::vector<FragmentList> syntheticFragmentLists(size_t count, uint64_t seed) {
    detail::Rng rng(seed ^ 0xda7a5e7ULL);
    std::vector<FragmentList> lists(count);
    for (FragmentList& list : lists) {
        const int n = drawCount(rng);
        const auto alphaMode = static_cast<AlphaMode>(rng.below(5));
        const auto colorMode = static_cast<ColorMode>(rng.below(5));
        // Per-list parameters.
        double lo = rng.uniform(0.03, 1.0), hi = rng.uniform(0.03, 1.0);
        if (lo > hi) std::swap(lo, hi);
        const double center = rng.uniform(0.03, 1.0), spread = rng.uniform(0.0, 0.08);
        const glm::dvec3 base(rng.uniform(), rng.uniform(), rng.uniform());
        const double colorSpread = rng.uniform(0.0, 0.15);
        glm::dvec3 palette[3];
        for (auto& p : palette) p = glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform());
        const int paletteSize = rng.range(2, 3);
        const double darkScale = rng.uniform(0.02, 0.3);

        list.resize(static_cast<size_t>(n));
        for (int i = 0; i < n; ++i) {
            Fragment& f = list[static_cast<size_t>(i)];
            double a = 0.0;
            switch (alphaMode) {
                case AlphaMode::UniformRange: a = rng.uniform(lo, hi); break;
                case AlphaMode::Clustered: a = center + spread * rng.normal(); break;
                case AlphaMode::NearCutoff: a = rng.uniform(0.0, 0.12); break;  // some below 0.03
                case AlphaMode::NearOne: a = rng.uniform(0.85, 1.0); break;
                case AlphaMode::Mixed:
                    a = rng.uniform() < 0.5 ? rng.uniform(0.03, 0.3) : rng.uniform(0.5, 1.0);
                    break;
            }
            f.alpha = clamp01(a);
            glm::dvec3 c(0.0);
            switch (colorMode) {
                case ColorMode::Random: c = glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()); break;
                case ColorMode::Similar:
                    c = base + colorSpread * glm::dvec3(rng.normal(), rng.normal(), rng.normal());
                    break;
                case ColorMode::Grey: c = glm::dvec3(rng.uniform()); break;
                case ColorMode::Palette: c = palette[rng.below(static_cast<uint64_t>(paletteSize))]; break;
                case ColorMode::Dark:
                    c = darkScale * glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform());
                    break;
            }
            f.color = glm::vec3(clamp01(c.r), clamp01(c.g), clamp01(c.b));
            f.depth = static_cast<float>(rng.uniform());
            f.order = static_cast<uint32_t>(i);
        }
    }
    return lists;
}

}  // namespace starnt::nn
