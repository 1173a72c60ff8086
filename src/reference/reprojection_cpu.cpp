#include "reference/reprojection_cpu.hpp"

#include <algorithm>
#include <limits>

#include "methods/neural/temporal/reprojection_constants.h"
#include "starnt/error.hpp"

namespace starnt::temporal {

Solution solveSource(glm::vec2 c, float z, int width, int height, const Reprojection& r) {
    const float zn = z * 2.0f - 1.0f;
    const glm::vec4 a = r.row0 - c.x * r.row3;
    const glm::vec4 b = r.row1 - c.y * r.row3;
    const float det = a.x * b.y - a.y * b.x;
    const glm::vec2 rhs = -glm::vec2(a.z * zn + a.w, b.z * zn + b.w);
    const glm::vec2 ndc = glm::vec2(rhs.x * b.y - a.y * rhs.y, a.x * rhs.y - rhs.x * b.x) / det;
    const glm::vec4 v(ndc, zn, 1.0f);
    Solution s;
    s.newViewDepth = glm::dot(r.row3, v) / glm::dot(r.sourceScale, v);
    s.window = (ndc * 0.5f + 0.5f) * glm::vec2(float(width), float(height));
    return s;
}

namespace {

struct SearchState {
    int bestIndex = -1;
    glm::vec2 bestPosition{0.0f};
    float bestViewDepth = std::numeric_limits<float>::infinity();
    int farIndex = -1;
    float farDepth = -1.0f;
};

void search(const ReprojectionFrame& f, glm::vec2 c, float z, const Reprojection& r, SearchState& state) {
    for (int step = 0; step < STARNT_TEMPORAL_SEARCH_STEPS; ++step) {
        const Solution s = solveSource(c, z, f.width, f.height, r);
        if (!(s.newViewDepth > 0.0f)) return;
        if (step == 0 && !(s.newViewDepth < state.bestViewDepth * STARNT_TEMPORAL_NEARER)) return;
        const glm::vec2 q = s.window;
        if (!(q.x >= 0.0f && q.y >= 0.0f && q.x < float(f.width) && q.y < float(f.height))) return;
        const int index = int(q.y) * f.width + int(q.x);
        const float found = f.depth[size_t(index)];
        if (found > state.farDepth) {
            state.farDepth = found;
            state.farIndex = index;
        }
        if (found == z) {
            if (s.newViewDepth < state.bestViewDepth) {
                state.bestViewDepth = s.newViewDepth;
                state.bestIndex = index;
                state.bestPosition = q;
            }
            return;
        }
        z = found;
    }
}

}  // namespace

std::vector<ReprojectionSource> reprojectionSearchOnCpu(const ReprojectionFrame& f, const Reprojection& r) {
    const int w = f.width, h = f.height;
    const size_t n = size_t(w) * size_t(h);
    if (w < 1 || h < 1 || f.color.size() != n || f.depth.size() != n) {
        throw Error("reprojectOnCpu: colour and depth must both hold width * height values");
    }
    // The seeds: (min, max) depth per block, then over the 3x3 blocks around each block.
    constexpr int B = STARNT_TEMPORAL_SEED_BLOCK;
    const int bw = (w + B - 1) / B, bh = (h + B - 1) / B;
    std::vector<glm::vec2> block(size_t(bw) * size_t(bh), glm::vec2(std::numeric_limits<float>::infinity(),
                                                                    -std::numeric_limits<float>::infinity()));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec2& m = block[size_t(y / B) * size_t(bw) + size_t(x / B)];
            const float z = f.depth[size_t(y) * size_t(w) + size_t(x)];
            m = glm::vec2(std::min(m.x, z), std::max(m.y, z));
        }
    std::vector<glm::vec2> seeds(block.size());
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            glm::vec2 m = block[size_t(by) * size_t(bw) + size_t(bx)];
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::vec2 o = block[size_t(std::clamp(by + dy, 0, bh - 1)) * size_t(bw) +
                                              size_t(std::clamp(bx + dx, 0, bw - 1))];
                    m = glm::vec2(std::min(m.x, o.x), std::max(m.y, o.y));
                }
            seeds[size_t(by) * size_t(bw) + size_t(bx)] = m;
        }

    std::vector<ReprojectionSource> out(n);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const glm::vec2 c = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f - 1.0f;
            const float here = f.depth[size_t(y) * size_t(w) + size_t(x)];
            const glm::vec2 seed = seeds[size_t(y / B) * size_t(bw) + size_t(x / B)];
            const float nearest = seed.x, farthest = seed.y;
            SearchState state;
            search(f, c, here, r, state);
            if (nearest != here) search(f, c, nearest, r, state);
            if (farthest != here && state.bestIndex < 0) search(f, c, farthest, r, state);
            const int source = state.bestIndex >= 0 ? state.bestIndex : state.farIndex >= 0 ? state.farIndex : y * w + x;
            out[size_t(y) * size_t(w) + size_t(x)] = {source, state.bestIndex >= 0, state.bestPosition};
        }
    }
    return out;
}

std::vector<int> reprojectionSourcesOnCpu(const ReprojectionFrame& f, const Reprojection& r) {
    const std::vector<ReprojectionSource> found = reprojectionSearchOnCpu(f, r);
    std::vector<int> out(found.size());
    for (size_t i = 0; i < found.size(); ++i) out[i] = found[i].index;
    return out;
}

std::vector<glm::vec4> reprojectOnCpu(const ReprojectionFrame& f, const Reprojection& r) {
    const std::vector<int> sources = reprojectionSourcesOnCpu(f, r);
    std::vector<glm::vec4> out(sources.size());
    for (size_t i = 0; i < sources.size(); ++i) out[i] = f.color[size_t(sources[i])];
    return out;
}

glm::vec3 refreshPixel(const ReprojectionFrame& kept, const std::vector<glm::vec4>& keptNearest, const Reprojection& r,
                       const ReprojectionSource& source, const glm::vec4& nearest, const glm::vec3& background) {
    const int w = kept.width, h = kept.height;
    auto inverseViewDepthAt = [&](int x, int y) {
        const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f - 1.0f;
        return glm::dot(r.sourceScale, glm::vec4(ndc, kept.depth[size_t(y) * size_t(w) + size_t(x)] * 2.0f - 1.0f, 1.0f));
    };
    // (B, 1 / view depth) of a texel as reprojection_behind.frag.glsl stores it; false where the
    // kept nearest layer hid what lay behind.
    auto behindAt = [&](int x, int y, glm::vec3& b, float& inverseDepth) {
        const size_t t = size_t(y) * size_t(w) + size_t(x);
        const float open = 1.0f - keptNearest[t].a;
        if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return false;
        inverseDepth = inverseViewDepthAt(x, y);
        b = (glm::vec3(kept.color[t]) - keptNearest[t].a * glm::vec3(keptNearest[t])) / open;
        return true;
    };
    glm::vec3 unused;
    float reference = 0.0f;
    if (source.consistent && nearest.a > 0.0f && behindAt(source.index % w, source.index / w, unused, reference) &&
        reference > 0.0f) {
        const glm::vec2 f = source.position - 0.5f;
        const glm::ivec2 base(int(std::floor(f.x)), int(std::floor(f.y)));
        const glm::vec2 frac = f - glm::vec2(base);
        const int sx = source.index % w, sy = source.index / w;
        glm::vec3 sum(0.0f);
        float weight = 0.0f, own = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const int tx = std::clamp(base.x + (k & 1), 0, w - 1), ty = std::clamp(base.y + (k >> 1), 0, h - 1);
            const float wk = ((k & 1) ? frac.x : 1.0f - frac.x) * ((k >> 1) ? frac.y : 1.0f - frac.y);
            glm::vec3 b;
            float inverseDepth = 0.0f;
            if (!behindAt(tx, ty, b, inverseDepth) || !(inverseDepth > 0.0f) ||
                std::abs(inverseDepth / reference - 1.0f) > float(STARNT_TEMPORAL_SAME_SURFACE)) {
                continue;
            }
            sum += wk * b;
            weight += wk;
            if (tx == sx && ty == sy) own += wk;
        }
        if (weight > 0.0f && own < 0.999f * weight) {
            return nearest.a * glm::vec3(nearest) + (1.0f - nearest.a) * glm::max(sum / weight, glm::vec3(0.0f));
        }
    }
    const size_t s = size_t(source.index);
    return refreshComposite(glm::vec3(kept.color[s]), keptNearest[s], nearest, background);
}

glm::vec3 refreshComposite(const glm::vec3& keptComposite, const glm::vec4& keptNearest, const glm::vec4& nearest,
                           const glm::vec3& background) {
    if (!(nearest.a > 0.0f)) return background;
    const glm::vec3 front = nearest.a * glm::vec3(nearest);
    const float keptOpen = 1.0f - keptNearest.a;
    if (!(keptOpen > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return front + (1.0f - nearest.a) * background;
    const float r = (1.0f - nearest.a) / keptOpen;
    return glm::max(r * keptComposite + (front - r * (keptNearest.a * glm::vec3(keptNearest))), glm::vec3(0.0f));
}

}  // namespace starnt::temporal
