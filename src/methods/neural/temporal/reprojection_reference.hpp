// Forward-splatting reprojection of a real frame to a new camera: the shared math and a CPU
// reference of exactly the algorithm the compute shaders (reprojection_*.comp.glsl) run.
//
// Pixel grids here are in GL order: index y * width + x, row 0 at the BOTTOM (as textures are
// stored), unlike starnt::Image.
//
// Algorithm (one source pixel s = one point, its centre at its pass-1 window depth):
//   A  splat:  ndc_old = (centre / size * 2 - 1, depth * 2 - 1, 1); clip = M * ndc_old with
//              M = newViewProj * inverse(oldViewProj). Dropped when clip.w <= 0 (behind the new
//              camera) or when the window position falls outside the image. Otherwise it targets
//              pixel t = floor(window position) with key = the float bits of its new view depth
//              (positive floats order like their bits); the nearest key per target wins
//              (atomicMin). M yields clip coordinates scaled by 1 / (old view depth), which differs
//              per source, so the depth is clip.w / dot(sourceScale, ndc_old) with sourceScale =
//              row 3 of inverse(oldViewProj). (New NDC z also orders points, and would suit
//              orthographic cameras, but in float it picked points up to ~3e-5 farther near the
//              far plane, from cancellation; the project's cameras are perspective.)
//   B  pick:   among the sources with the winning key, the lowest source index wins (deterministic).
//   C  gather: a target with a winner shows the winner's colour. A target without one (a crack
//              between splats, or a disocclusion) takes the colour of the FARTHEST winner within
//              STARNT_TEMPORAL_FILL_RADIUS = 2 pixels (a 5x5 window), so what was behind shows
//              through; the first in row-major order wins on equal keys. With no winner in the
//              window either (content entering at the border, wide disocclusions), the fallback
//              is the real frame's colour at the same pixel.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace starnt::temporal {

// "No splat" in the key and source buffers.
constexpr uint32_t kNoSplat = 0xFFFFFFFFu;

// What the splat step needs from the two cameras, computed in double and rounded once.
struct Reprojection {
    glm::mat4 matrix{1.0f};             // newViewProj * inverse(oldViewProj)
    glm::vec4 sourceScale{0, 0, 0, 1};  // row 3 of inverse(oldViewProj): . ndc_old = 1 / old view depth
};
Reprojection makeReprojection(const glm::mat4& oldViewProj, const glm::mat4& newViewProj);

struct SplatTarget {
    bool valid = false;
    int x = 0, y = 0;         // target pixel (GL order)
    uint32_t key = kNoSplat;  // bits of the new view depth (> 0); smaller = nearer
};

// Pass A for one source pixel (GL order), same float operations as the shader.
SplatTarget splatTarget(int x, int y, float depth, int width, int height, const Reprojection& reprojection);

struct ReprojectionFrame {
    int width = 0, height = 0;
    std::vector<glm::vec4> color;  // linear RGBA, GL order
    std::vector<float> depth;      // window depth in [0, 1], 1 = nothing transparent (far plane)
};

// The whole algorithm on the CPU; returns the reprojected colours in GL order.
std::vector<glm::vec4> reprojectOnCpu(const ReprojectionFrame& frame, const Reprojection& reprojection);

}  // namespace starnt::temporal
