// A small CPU rasteriser that produces per-pixel fragment lists for scenes of unlit, flat-coloured
// triangles (the built-in `panes` and `random` scenes): the independent reference the GPU methods
// are tested against. Pixels whose centre lies within `edgeMargin` pixels of a triangle edge are
// marked ambiguous (GPU fill rules may legitimately differ there) and should not be compared.
#pragma once
#include <vector>

#include "reference/fragment_capture.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt {

struct CpuRaster {
    CapturedFrame frame;            // rows top first, fragments in submission order
    std::vector<uint8_t> ambiguous;  // 1 where the pixel is near an edge
    bool clipped = false;           // a triangle crossed the near plane (not supported: compare nothing)
};

// Shades like the built-in surface shader for unlit materials: baseColorFactor x COLOR_0 (linear
// interpolation of vertex colours is not modelled: each triangle must have one colour), alpha
// override when >= 0. Fragments with alpha < alphaCutoff are dropped.
CpuRaster rasterizeUnlit(const Scene& scene, const glm::mat4& view, const glm::mat4& projection, int width, int height,
                         float alphaCutoff, float alphaOverride = -1.0f, float edgeMargin = 1.0f);

}  // namespace starnt
