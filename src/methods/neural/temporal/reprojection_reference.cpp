#include "methods/neural/temporal/reprojection_reference.hpp"

#include <bit>

#include "methods/neural/temporal/reprojection_bindings.h"
#include "starnt/error.hpp"

namespace starnt::temporal {

Reprojection makeReprojection(const glm::mat4& oldViewProj, const glm::mat4& newViewProj) {
    const glm::dmat4 inverseOld = glm::inverse(glm::dmat4(oldViewProj));
    Reprojection r;
    r.matrix = glm::mat4(glm::dmat4(newViewProj) * inverseOld);
    r.sourceScale = glm::vec4(inverseOld[0][3], inverseOld[1][3], inverseOld[2][3], inverseOld[3][3]);  // [column][row]
    return r;
}

SplatTarget splatTarget(int x, int y, float depth, int width, int height, const Reprojection& reprojection) {
    const glm::vec2 size{float(width), float(height)};
    const glm::vec2 centre = (glm::vec2(float(x), float(y)) + 0.5f) / size * 2.0f - 1.0f;
    const glm::vec4 ndc(centre, depth * 2.0f - 1.0f, 1.0f);
    const glm::vec4 clip = reprojection.matrix * ndc;
    SplatTarget out;
    if (!(clip.w > 0.0f)) return out;  // behind the new camera (or NaN)
    const glm::vec2 window = (glm::vec2(clip.x, clip.y) / clip.w * 0.5f + 0.5f) * size;
    // Written so that NaN fails too.
    if (!(window.x >= 0.0f && window.y >= 0.0f && window.x < size.x && window.y < size.y)) return out;
    out.valid = true;
    out.x = int(window.x);  // floor: window >= 0
    out.y = int(window.y);
    out.key = std::bit_cast<uint32_t>(clip.w / glm::dot(reprojection.sourceScale, ndc));
    return out;
}

std::vector<glm::vec4> reprojectOnCpu(const ReprojectionFrame& frame, const Reprojection& reprojection) {
    const int w = frame.width, h = frame.height;
    const size_t n = size_t(w) * size_t(h);
    if (w < 1 || h < 1 || frame.color.size() != n || frame.depth.size() != n) {
        throw Error("reprojectOnCpu: colour and depth must both hold width * height values");
    }
    std::vector<SplatTarget> targets(n);
    std::vector<uint32_t> winnerKey(n, kNoSplat), winnerSource(n, kNoSplat);
    // A: nearest key per target.
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t s = size_t(y) * size_t(w) + size_t(x);
            targets[s] = splatTarget(x, y, frame.depth[s], w, h, reprojection);
            if (!targets[s].valid) continue;
            const size_t t = size_t(targets[s].y) * size_t(w) + size_t(targets[s].x);
            winnerKey[t] = std::min(winnerKey[t], targets[s].key);
        }
    }
    // B: lowest source index among the nearest.
    for (size_t s = 0; s < n; ++s) {
        if (!targets[s].valid) continue;
        const size_t t = size_t(targets[s].y) * size_t(w) + size_t(targets[s].x);
        if (targets[s].key == winnerKey[t]) winnerSource[t] = std::min(winnerSource[t], uint32_t(s));
    }
    // C: winners, hole fill from the farthest neighbour, fallback to the same pixel.
    std::vector<glm::vec4> out(n);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t t = size_t(y) * size_t(w) + size_t(x);
            uint32_t source = winnerSource[t];
            if (source == kNoSplat) {
                uint32_t farthestKey = 0u;
                constexpr int r = STARNT_TEMPORAL_FILL_RADIUS;
                for (int dy = -r; dy <= r; ++dy) {
                    for (int dx = -r; dx <= r; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                        const size_t q = size_t(ny) * size_t(w) + size_t(nx);
                        if (winnerSource[q] == kNoSplat) continue;
                        if (source == kNoSplat || winnerKey[q] > farthestKey) {
                            source = winnerSource[q];
                            farthestKey = winnerKey[q];
                        }
                    }
                }
            }
            out[t] = frame.color[source == kNoSplat ? t : size_t(source)];
        }
    }
    return out;
}

}  // namespace starnt::temporal
