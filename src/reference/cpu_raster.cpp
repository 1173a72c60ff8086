#include "reference/cpu_raster.hpp"

#include <algorithm>
#include <cmath>

namespace starnt {

CpuRaster rasterizeUnlit(const Scene& scene, const glm::mat4& view, const glm::mat4& projection, int width,
                         int height, float alphaCutoff, float alphaOverride, float edgeMargin) {
    CpuRaster out;
    out.frame.width = width;
    out.frame.height = height;
    out.frame.pixels.resize(size_t(width) * size_t(height));
    out.ambiguous.assign(size_t(width) * size_t(height), 0);
    const glm::mat4 vp = projection * view;
    for (size_t meshIndex = 0; meshIndex < scene.meshes.size(); ++meshIndex) {
        const Mesh& mesh = scene.meshes[meshIndex];
        const Material& mat = scene.materials[size_t(mesh.material)];
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            glm::vec3 win[3];
            bool behind = false;
            for (int k = 0; k < 3; ++k) {
                glm::vec4 clip = vp * glm::vec4(mesh.positions[mesh.indices[t + size_t(k)]], 1.0f);
                if (clip.w <= 1e-6f) behind = true;
                glm::vec3 ndc = glm::vec3(clip) / clip.w;
                // Window coordinates with y pointing down (row 0 = top), depth in [0, 1].
                win[k] = glm::vec3((ndc.x * 0.5f + 0.5f) * float(width), (0.5f - ndc.y * 0.5f) * float(height),
                                   ndc.z * 0.5f + 0.5f);
            }
            if (behind) {
                out.clipped = true;
                continue;
            }
            glm::vec4 color = mat.baseColorFactor *
                              (mesh.colors.empty() ? glm::vec4(1.0f) : mesh.colors[mesh.indices[t]]);
            if (alphaOverride >= 0.0f) color.a = alphaOverride;
            color = glm::clamp(color, glm::vec4(0.0f), glm::vec4(1.0f));
            const double area = double(win[1].x - win[0].x) * double(win[2].y - win[0].y) -
                                double(win[2].x - win[0].x) * double(win[1].y - win[0].y);
            if (std::abs(area) < 1e-12) continue;
            const int x0 = std::max(0, int(std::floor(std::min({win[0].x, win[1].x, win[2].x}) - edgeMargin)));
            const int x1 = std::min(width - 1, int(std::ceil(std::max({win[0].x, win[1].x, win[2].x}) + edgeMargin)));
            const int y0 = std::max(0, int(std::floor(std::min({win[0].y, win[1].y, win[2].y}) - edgeMargin)));
            const int y1 = std::min(height - 1, int(std::ceil(std::max({win[0].y, win[1].y, win[2].y}) + edgeMargin)));
            for (int y = y0; y <= y1; ++y) {
                for (int x = x0; x <= x1; ++x) {
                    const double px = x + 0.5, py = y + 0.5;
                    double w[3], minDist = 1e30;
                    for (int e = 0; e < 3; ++e) {
                        const glm::vec3& a = win[(e + 1) % 3];
                        const glm::vec3& b = win[(e + 2) % 3];
                        const double ex = double(b.x) - a.x, ey = double(b.y) - a.y;
                        const double edge = (px - a.x) * ey - (py - a.y) * ex;  // signed, sign of area inside
                        w[e] = edge / -area;
                        const double dist = (area < 0 ? edge : -edge) / std::sqrt(ex * ex + ey * ey);
                        minDist = std::min(minDist, dist);
                    }
                    const size_t idx = size_t(y) * size_t(width) + size_t(x);
                    if (minDist > -double(edgeMargin) && minDist < double(edgeMargin)) out.ambiguous[idx] = 1;
                    if (minDist < 0) continue;
                    if (color.a < alphaCutoff) continue;
                    Fragment f;
                    f.color = glm::vec3(color);
                    f.alpha = color.a;
                    f.depth = float(w[0] * win[0].z + w[1] * win[1].z + w[2] * win[2].z);
                    f.order = uint32_t(meshIndex << 24) | uint32_t(t / 3);
                    out.frame.pixels[idx].push_back(f);
                }
            }
        }
    }
    return out;
}

}  // namespace starnt
