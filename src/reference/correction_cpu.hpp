// Corrected interpolated frames (`--temporal-mode correct`, beyond the paper; docs/DESIGN.md,
// "Corrected frames"): the CPU reference of reprojection_behind.frag.glsl (STARNT_BEHIND_CORRECTION) and
// correction_composite.frag.glsl, in the shaders' float operations. Pixel grids in GL order (index
// y * width + x, row 0 at the bottom).
//
// A real frame keeps, per texel, D = B_net - B_cf: what the network put behind the nearest layer,
// B_net = (C - a1 C1) / (1 - a1), minus what the closed form of the same frame's pass-3 sums puts
// there (closedFormBehind), with the texel's inverse view depth. An interpolated frame renders pass
// 1 and pass 3 at its own camera (no pass 2, no inference) and composites
//   C = a1 C1 + (1 - a1) max(B_cf + D(q), 0)
// with B_cf from its own sums and D resampled bilinearly at q, where the fresh nearest point (its
// pass-1 depth, unprojected) lay in the kept frame, over the texels whose kept nearest surface is
// the same one (inverse view depth within STARNT_TEMPORAL_SAME_SURFACE); without such a texel,
// D = 0. Why: the closed form is right for the sums at this camera (no parallax, no disocclusion:
// every fragment is fresh), and what the network adds to it varies more slowly than the image, so
// moving it by the nearest layer's depth costs less than moving the whole back.
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "methods/neural/temporal/reprojection_math.hpp"
#include "starnt/tools/fragments.hpp"

namespace starnt::temporal {

// What lies behind the nearest layer from the sums over every fragment: the fragments behind it
// cover 1 - T' of the pixel, T' = clamp(T / (1 - a1), 0, 1), with the mean colour
// (sum a C - a1 C1) / (sum a - a1) (clamped at 0; the background when sum a - a1 <=
// STARNT_TEMPORAL_MIN_BEHIND_ALPHA), the background the rest. Needs 1 - a1 > 0.
glm::vec3 closedFormBehind(const glm::vec4& nearest, const glm::vec4& sums, float transmittance, const glm::vec3& background);

// One real frame as the capture reads it (all width x height, GL order).
struct CorrectionSource {
    int width = 0, height = 0;
    std::vector<glm::vec4> composite;   // the real frame's output (rgb)
    std::vector<float> depth;           // its pass-1 window depth
    std::vector<glm::vec4> nearest;     // pass 1: C1, a1
    std::vector<glm::vec4> sums;        // pass 3 at full resolution: sum a C, sum a
    std::vector<float> transmittance;   // pass 3: prod (1 - a)
};
// The kept texels: (D, inverse view depth), alpha -1 where the nearest layer's transmittance was at
// most STARNT_TEMPORAL_MIN_TRANSMITTANCE. `viewProj` of the real frame.
std::vector<glm::vec4> correctionOnCpu(const CorrectionSource& real, const glm::mat4& viewProj, const glm::vec3& background);

// The nearest fragment found by MIN blending (packed_nearest.h, packed_nearest.glsl: the same float
// operations). packNearest: what a fragment at window depth `z` with colour and alpha `c` blends
// in (four floats by their bits); packedEmpty: the clear value; unpackNearest: C1, a1 and the
// window depth of the nearest fragment ({0, 0, 0, 0} and 1 for an empty pixel). blendNearest: the
// GL_MIN blend of two packed values.
glm::vec4 packNearest(float z, const glm::vec4& c);
glm::vec4 packedEmpty();
glm::vec4 unpackNearest(const glm::vec4& packed, float& z);
glm::vec4 blendNearest(const glm::vec4& a, const glm::vec4& b);

// Corrected frames of the tail-moment methods (ordered_behind.glsl, the same float operations):
// keyedDepth, the middle of z's packed key interval; depthBehindReference, u = ln(1 + max(z' - r, 0)
// / (s (1 - r))) with z' = keyedDepth(z) (0 when r = 1); referenceDepthOnCpu, the reference depth of
// a real frame's pass-1 `depth` (one value per STARNT_ORDERED_REFERENCE_TILE pixels squared: the
// nearest over the tile's every STARNT_ORDERED_REFERENCE_STRIDE-th pixel and its eight neighbour
// tiles'; reference_depth.frag.glsl), referenceAt its value at pixel (x, y).
float keyedDepth(float z);
// The nearest two fragments in one RGBA32UI texel (packed_nearest.h, STARNT_PACKED_TWO_LAYERS; the
// same integer and float operations as packed_nearest.glsl): packLayer, a fragment's two words;
// insertLayer, the texel after that fragment met it (draw order); unpackLayer, C and a of a layer
// (0 where none) and its window depth (1 where none).
glm::uvec2 packLayer(float z, const glm::vec4& c);
glm::uvec4 packedLayersEmpty();
glm::uvec4 insertLayer(const glm::uvec4& layers, const glm::uvec2& fragment);
glm::vec4 unpackLayer(const glm::uvec2& layer, float& z);
// Three layers (STARNT_PACKED_THREE_LAYERS): `layers` the nearest two keys, `third` (the .xy of
// an RGBA32UI texel, packedLayerEmpty() when cleared) the next; a fragment whose key equals a kept layer's is
// merged into it, behind it (the layer over the fragment: coplanar fragments in draw order, at
// the layer's key). The fragment: window depth z, straight colour and alpha c (packed once: its own
// colour, or the merge).
void insertThreeLayers(glm::uvec4& layers, glm::uvec2& third, float z, const glm::vec4& c);
glm::uvec2 packedLayerEmpty();
float depthBehindReference(float z, float reference);
std::vector<float> referenceDepthOnCpu(const std::vector<float>& depth, int width, int height);
float referenceAt(const std::vector<float>& reference, int width, int x, int y);
// What an interpolated pixel's pass 3 sums behind the reference depth: (sum a C v, sum a v) and
// sum a v^2 over every fragment, v = u - pivot: the pivot is 0, or with three layers the u of the
// pixel's first fragment in draw order (pass3_accumulate.frag.glsl).
struct OrderedBehind {
    glm::vec4 moment1{0.0f};
    float moment2 = 0.0f;
    float reference = 1.0f;
    float pivot = 0.0f;
};
OrderedBehind behindMomentsOf(const std::vector<Fragment>& fragments, float reference, float pivot = 0.0f);
// What lies behind the nearest layer (C1, a1 at window depth `depth`) weighted by depth: the
// moments recentred at the nearest fragment's u1 (its own terms then vanish), then
// nn::momentWeightedColor, linear at most, over the rest (their alpha sum sum a - a1, transmittance T / (1 - a1);
// the plain mean where their spread is within what a1's rounding in sum a - a1 makes,
// STARNT_ORDERED_ALPHA_ROUNDING), under 1 - T / (1 - a1), the background the rest; the background
// where sum a - a1 <= STARNT_TEMPORAL_MIN_BEHIND_ALPHA.
glm::vec3 orderedClosedFormBehind(const glm::vec4& nearest, float depth, const glm::vec4& sums, float transmittance,
                                  const OrderedBehind& ordered, const glm::vec3& background);
// The same from moments already recentred at the nearest fragment (v = u - u1, its own terms 0):
// what orderedClosedFormBehind makes of the sums over every fragment.
glm::vec3 orderedClosedFormBehindFromMoments(const glm::vec4& nearest, const glm::vec4& sums, float transmittance,
                                             const glm::vec4& moment1, float moment2, const glm::vec3& background);

// What lies behind the nearest layer when the second (C2, a2) is known exactly too
// (ordered_behind.glsl): the second layer over the ordered closed form of what lies behind it; with
// a2 = 0 the one-layer forms (orderedClosedFormBehindFromMoments, orderedClosedFormBehind).
// ...SecondFromMoments: `moment1`, `moment2` summed over the fragments behind the second layer in
// v = u - u2 (a real frame's pass 3 with STARNT_BEHIND_SECOND); ...TwoLayers: from an
// interpolated frame's moments in u over every fragment, recentred at u2, less the nearest's terms.
glm::vec3 orderedClosedFormBehindSecondFromMoments(const glm::vec4& nearest, const glm::vec4& second, const glm::vec4& sums,
                                                   float transmittance, const glm::vec4& moment1, float moment2,
                                                   const glm::vec3& background);
glm::vec3 orderedClosedFormBehindTwoLayers(const glm::vec4& nearest, float depth, const glm::vec4& second, float secondDepth,
                                           const glm::vec4& sums, float transmittance, const OrderedBehind& ordered,
                                           const glm::vec3& background);
// The same with the third layer (C3, a3, behind the second) known too: the second over the third
// over the ordered closed form behind it, the moments recentred at u3 less both nearer layers'
// terms; with a3 = 0 orderedClosedFormBehindTwoLayers.
glm::vec3 orderedClosedFormBehindThreeLayers(const glm::vec4& nearest, float depth, const glm::vec4& second, float secondDepth,
                                             const glm::vec4& third, float thirdDepth, const glm::vec4& sums, float transmittance,
                                             const OrderedBehind& ordered, const glm::vec3& background);

// One interpolated pixel (x, y): `nearest`, `depth`, `sums`, `transmittance` of the fresh passes at
// that pixel; `correction` the kept texels of a frame rendered with `oldViewProj` (empty: the frame
// was kept without a correction, the closed form alone). `ordered`: the tail-moment methods' closed
// form (orderedClosedFormBehind) with this pixel's moments instead of closedFormBehind.
glm::vec3 correctedPixel(int x, int y, int width, int height, const glm::vec4& nearest, float depth, const glm::vec4& sums,
                         float transmittance, const std::vector<glm::vec4>& correction, const glm::mat4& oldViewProj,
                         const glm::mat4& newViewProj, const glm::vec3& background, const OrderedBehind* ordered = nullptr);

}  // namespace starnt::temporal
