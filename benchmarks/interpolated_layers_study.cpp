// Offline study: what an interpolated frame of the recommended configuration lacks against a real
// frame, layer by layer. Not a test and not part of the library: it tells which exact layer the
// corrected frames would need to come near the real frames (docs/DESIGN.md, "Corrected frames: what
// the interpolated frames lack").
//
//   starnt_interpolated_layers_study [--width W] [--scenes a,b,...]
//
// For each suite scene at the default camera it captures every fragment and composites each pixel
// exactly, then, MSE of sRGB against that (no reprojection: every variant sees the exact fragments
// of this frame, so what differs is only how much of the list is known exactly):
//   ordered:       the exact nearest layer over the ordered closed form of everything behind it
//                  (temporal::orderedClosedFormBehind, the corrected frames' rule without the
//                  network's correction; the reference depth from this frame's nearest depths);
//   + farthest:    the same with the farthest fragment exact too (what a MAX-blended packed target
//                  would give): the closed form covers only the fragments between the two;
//   + second:      the nearest and second layers exact, the closed form behind the second (what a
//                  peeled pass 2 would give);
//   + third:       the nearest three layers exact, the closed form behind the third (what a third
//                  packed layer gives: "Corrected frames: three layers and no correction");
//   starnt-d:      the real frame's composite (two exact layers, the tail moments, the network).
// It also counts the covered pixels with 1, 2 and more fragments.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "reference/correction_cpu.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;

namespace {

using study::squaredSrgb;

// The nearest fragment of `list` (sorted, non-empty) over the ordered closed form of the rest,
// whose background is `behindBackground`, with moments behind `reference`.
glm::vec3 nearestOverOrdered(const FragmentList& list, float reference, glm::vec3 behindBackground) {
    glm::vec4 sums(0.0f);
    float transmittance = 1.0f;
    for (const Fragment& f : list) {
        sums += glm::vec4(f.color * f.alpha, f.alpha);
        transmittance *= 1.0f - f.alpha;
    }
    const glm::vec4 nearest(list[0].color, list[0].alpha);
    if (!(1.0f - nearest.a > 1e-4f)) return glm::vec3(nearest);
    const temporal::OrderedBehind moments = temporal::behindMomentsOf(list, reference);
    const glm::vec3 behind =
        temporal::orderedClosedFormBehind(nearest, list[0].depth, sums, transmittance, moments, behindBackground);
    return nearest.a * glm::vec3(nearest) + (1.0f - nearest.a) * behind;
}

}  // namespace

int main(int argc, char** argv) {
    int width = 640;
    std::vector<std::string> names = {"magic_stars", "chess", "tree", "hair", "hairball", "engine"};
    if (!study::parseStudyArgs(argc, argv, "interpolated_layers_study", width, names)) return 2;
    const int height = width * 9 / 16;
    try {
        HeadlessGlContext context(GlApi::Desktop);
        const nn::Network network = loadMethodNetwork(*neuralConfig("starnt-d"), {});
        std::printf("MSE (sRGB) against the exact composite, %dx%d, default camera\n", width, height);
        std::printf("%-12s %10s %10s %10s %10s %10s | %8s %8s %8s\n", "scene", "ordered", "+farthest", "+second", "+third", "starnt-d",
                    "1 frag", "2 frags", "3+");
        for (const std::string& name : names) {
            const study::CapturedScene captured = study::captureSuiteScene(name, width, height);
            const glm::vec3 background = captured.frame.background;
            const size_t pixels = size_t(width) * size_t(height);
            // Prepared lists and the nearest depths in GL order (rows bottom-first).
            std::vector<FragmentList> lists(pixels);
            std::vector<float> nearestDepth(pixels, 1.0f);
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const size_t i = size_t(y) * size_t(width) + size_t(x);
                    lists[i] = nn::preparedFragments(captured.fragments.at(x, height - 1 - y), captured.spec.alphaCutoff);
                    if (!lists[i].empty()) nearestDepth[i] = lists[i][0].depth;
                }
            }
            const std::vector<float> reference = temporal::referenceDepthOnCpu(nearestDepth, width, height);
            double ordered = 0.0, farthest = 0.0, second = 0.0, third = 0.0, starntD = 0.0;
            long counts[3] = {0, 0, 0};
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const FragmentList& list = lists[size_t(y) * size_t(width) + size_t(x)];
                    if (list.empty()) continue;
                    ++counts[std::min<size_t>(list.size(), 3) - 1];
                    const float r = temporal::referenceAt(reference, width, x, y);
                    const glm::vec3 exact = compositeOver(list, background);
                    ordered += squaredSrgb(nearestOverOrdered(list, r, background), exact);
                    // The farthest fragment exact: the closed form covers what lies between.
                    glm::vec3 withFarthest = exact;
                    if (list.size() > 2) {
                        const Fragment& far = list.back();
                        const FragmentList front(list.begin(), list.end() - 1);
                        withFarthest = nearestOverOrdered(front, r, far.alpha * far.color + (1.0f - far.alpha) * background);
                    }
                    farthest += squaredSrgb(withFarthest, exact);
                    // The second layer exact: the closed form behind it.
                    glm::vec3 withSecond = exact;
                    if (list.size() > 2) {
                        const FragmentList rest(list.begin() + 1, list.end());
                        withSecond = list[0].alpha * list[0].color + (1.0f - list[0].alpha) * nearestOverOrdered(rest, r, background);
                    }
                    second += squaredSrgb(withSecond, exact);
                    // The nearest three layers exact: the closed form behind the third.
                    glm::vec3 withThird = exact;
                    if (list.size() > 3) {
                        const FragmentList rest(list.begin() + 2, list.end());
                        const glm::vec3 behindSecond = nearestOverOrdered(rest, r, background);
                        withThird = list[0].alpha * list[0].color +
                                    (1.0f - list[0].alpha) * (list[1].alpha * list[1].color + (1.0f - list[1].alpha) * behindSecond);
                    }
                    third += squaredSrgb(withThird, exact);
                    const nn::PixelSums s = nn::sumsFromFragments(list, captured.spec.alphaCutoff);
                    const nn::TailMoments m = nn::tailMomentsFromFragments(list, captured.spec.alphaCutoff);
                    starntD += squaredSrgb(nn::compositeStarntDepth(network, s, m, background), exact);
                }
            }
            const double n = double(pixels);
            std::printf("%-12s %10.3e %10.3e %10.3e %10.3e %10.3e | %8ld %8ld %8ld\n", name.c_str(), ordered / n, farthest / n,
                        second / n, third / n, starntD / n, counts[0], counts[1], counts[2]);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "interpolated_layers_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
