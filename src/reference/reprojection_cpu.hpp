// Reprojection of a real frame to a new camera by a backward search: the shared math and a CPU
// reference of exactly the algorithm reprojection_search.frag.glsl runs.
//
// Pixel grids here are in GL order: index y * width + x, row 0 at the BOTTOM (as textures are
// stored), unlike starnt::Image.
//
// The real frame is a height field: texel t covers the window square [t, t + 1) at its pass-1
// window depth Z[t] (1 = far plane where nothing transparent was drawn). R = newViewProj *
// inverse(oldViewProj) carries a point (old ndc xy, old ndc z, 1) to new clip coordinates scaled by
// 1 / (old view depth).
//
// For output pixel p with centre c (new NDC):
//   solve(z):  the old window position q whose point at depth z lands exactly on c (two linear
//              equations, solved in closed form), with its new view depth d = (R v).w / (S . v),
//              S = row 3 of inverse(oldViewProj).
//   search(z): up to STARNT_TEMPORAL_SEARCH_STEPS times: q = solve(z); stop if d <= 0 (behind the
//              new camera) or q is off the old image (that source was never seen); fetch Z at
//              t = floor(q); if Z[t] == z the source is CONSISTENT (the point at depth z lies in a
//              texel of depth z): a candidate (t, d); else continue with z = Z[t].
//   seeds:     Z[p], and the smallest and largest Z over the 3x3 window of pixels
//              STARNT_TEMPORAL_SEED_STRIDE apart around p (clamped to the image), each searched
//              when it differs from Z[p]. Nearer seeds find occluders moving in, farther ones the
//              background.
//   result:    the colour of the candidate with the smallest new view depth (nearest wins, as a
//              depth test would decide). Without any candidate (a disocclusion: what is now seen
//              was hidden) the colour of the FARTHEST texel any search fetched (what lay behind,
//              not the occluder); when no search fetched a texel (content entering at the border,
//              or behind the old camera) the real frame's colour at the same pixel.
// A camera that does not move finds every pixel's own texel at once (bit-exact copy). For a
// constant depth (a far plane) the first solve is exact, so a turning camera follows the
// homography of the rotation to float precision.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "methods/neural/temporal/reprojection_math.hpp"

namespace starnt::temporal {


// solve(z) above for the new NDC point c and old window depth z, in the shader's float operations.
struct Solution {
    glm::vec2 window{0.0f};    // old window position (pixels)
    float newViewDepth = 0.0f;  // <= 0 or NaN: no usable solution
};
Solution solveSource(glm::vec2 newNdc, float depth, int width, int height, const Reprojection& reprojection);

struct ReprojectionFrame {
    int width = 0, height = 0;
    std::vector<glm::vec4> color;  // linear RGBA, GL order
    std::vector<float> depth;      // window depth in [0, 1], 1 = nothing transparent (far plane)
};

// The whole algorithm on the CPU; returns the reprojected colours in GL order.
std::vector<glm::vec4> reprojectOnCpu(const ReprojectionFrame& frame, const Reprojection& reprojection);
// The same search, returning each output pixel's source: its texel index (GL order), whether it is
// a consistent source (not a fallback), and then its continuous old window position.
struct ReprojectionSource {
    int index = 0;
    bool consistent = false;
    glm::vec2 position{0.0f};
};
std::vector<ReprojectionSource> reprojectionSearchOnCpu(const ReprojectionFrame& frame, const Reprojection& reprojection);
std::vector<int> reprojectionSourcesOnCpu(const ReprojectionFrame& frame, const Reprojection& reprojection);

// Refresh frames (docs/DESIGN.md, "Temporal reprojection", `--temporal-mode refresh`): the nearest layer is rendered fresh at the
// new camera (nearest = C1, a1, straight); what lay behind the kept frame's nearest layer at the
// source texel, B = (C_kept - a1k C1k) / (1 - a1k), is composited under it:
//   C = a1 C1 + (1 - a1) B = r C_kept + (a1 C1 - r a1k C1k),  r = (1 - a1) / (1 - a1k),
// written the second way so that an unchanged pixel (same nearest fragment, r = 1) returns
// C_kept bit for bit. No fragment now (a1 = 0): the background, exactly. A kept nearest layer
// with transmittance <= STARNT_TEMPORAL_MIN_TRANSMITTANCE hid what lay behind: the background
// stands in for B. Where the kept frame had no fragment (a1k = 0, C_kept = background) this
// gives the fresh layer over the background. GLSL: refreshComposite in reprojection_search.frag.glsl.
glm::vec3 refreshComposite(const glm::vec3& keptComposite, const glm::vec4& keptNearest, const glm::vec4& nearest,
                           const glm::vec3& background);
// One refresh pixel as the GPU computes it: where the search found a consistent source and there is
// a fresh nearest fragment, what lay behind the kept nearest layer is resampled bilinearly at the
// source position from the 2x2 texels of the source's surface (view depth within
// STARNT_TEMPORAL_SAME_SURFACE of the source texel's) and composited under the fresh layer; when the
// source texel carries (nearly) all the weight, or otherwise, refreshComposite at the source texel
// (so an unchanged pixel stays bit-exact). `keptNearest` is the kept pass-1 colour + alpha.
glm::vec3 refreshPixel(const ReprojectionFrame& kept, const std::vector<glm::vec4>& keptNearest, const Reprojection& r,
                       const ReprojectionSource& source, const glm::vec4& nearest, const glm::vec3& background);

}  // namespace starnt::temporal
