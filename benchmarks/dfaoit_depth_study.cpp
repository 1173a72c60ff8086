// Offline study: where DFAOIT's error lies against WBOIT's, by the pixel's fragment count N. Not a
// test and not part of the library (docs/DESIGN.md, "DFAOIT's recipe").
//
//   starnt_dfaoit_depth_study [--width W] [--scenes a,b,...] [--dfaoit-weights FILE]
//
// For each suite scene (bench::suiteScenes(), default camera orbit 0/15) it captures every fragment
// and composites each pixel on the CPU: exactly, with WBOIT (nn::compositeWboit), with the shipped
// DFAOIT and starnt networks from 32-bit sums. Per bucket of N it prints the share of pixels and
// each method's contribution to the whole image's MSE (sRGB, as the bench), so the buckets of a
// row sum to the method's MSE.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/families.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;

namespace {

using study::squaredSrgb;

constexpr std::array<int, 8> kBucketEnds = {1, 2, 3, 4, 8, 16, 32, 1 << 30};  // N <= end

int bucketOf(size_t n) {
    for (size_t b = 0; b < kBucketEnds.size(); ++b) {
        if (n <= size_t(kBucketEnds[b])) return int(b);
    }
    return int(kBucketEnds.size()) - 1;
}

}  // namespace

int main(int argc, char** argv) {
    int width = 640;
    std::string dfaoitWeights;
    std::vector<std::string> names = {"magic_stars", "chess", "tree", "hair", "hairball", "engine"};
    if (!study::parseStudyArgs(argc, argv, "dfaoit_depth_study", width, names,
                               {{"--dfaoit-weights", [&](const std::string& v) { dfaoitWeights = v; }}})) {
        return 2;
    }
    const int height = width * 9 / 16;
    try {
        HeadlessGlContext context(GlApi::Desktop);
        const nn::Network dfaoit = dfaoitWeights.empty() ? loadMethodNetwork(*neuralConfig("dfaoit"), {})
                                                        : nn::loadWeights(dfaoitWeights, nn::NetworkKind::DFAOIT);
        const nn::Network starnt = loadMethodNetwork(*neuralConfig("starnt"), {});
        for (const std::string& name : names) {
            const study::CapturedScene captured = study::captureSuiteScene(name, width, height);
            const FrameDesc& frame = captured.frame;
            const float cutoff = captured.spec.alphaCutoff;
            constexpr int kBuckets = int(kBucketEnds.size());
            std::array<double, kBuckets> pixels{}, wboit{}, dfa{}, star{};
            const double total = double(width) * height;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const FragmentList& raw = captured.fragments.at(x, y);
                    const FragmentList sorted = nn::preparedFragments(raw, cutoff);
                    if (sorted.empty()) continue;
                    const int b = bucketOf(sorted.size());
                    const glm::vec3 exact = compositeOver(sorted, frame.background);
                    const nn::PixelSums s = nn::sumsFromFragments(raw, cutoff);
                    pixels[b] += 1.0 / total;
                    wboit[b] += squaredSrgb(exact, nn::compositeWboit(raw, frame.background, cutoff)) / total;
                    dfa[b] += squaredSrgb(exact, nn::compositeDfaoit(dfaoit, s, frame.background)) / total;
                    star[b] += squaredSrgb(exact, nn::compositeStarnt(starnt, s, frame.background)) / total;
                }
            }
            double sums[3] = {0, 0, 0};
            for (int b = 0; b < kBuckets; ++b) sums[0] += wboit[b], sums[1] += dfa[b], sums[2] += star[b];
            std::printf("%s %dx%d: MSE wboit %.3e dfaoit %.3e (%.2fx) starnt %.3e (%.2fx)\n", name.c_str(), width, height,
                        sums[0], sums[1], sums[1] / sums[0], sums[2], sums[2] / sums[0]);
            std::printf("  %-8s %8s %11s %11s %11s %8s\n", "N", "pixels", "wboit", "dfaoit", "starnt", "dfa/wb");
            for (int b = 0; b < kBuckets; ++b) {
                const int lo = b == 0 ? 1 : kBucketEnds[b - 1] + 1;
                char label[32];
                if (b + 1 == kBuckets) std::snprintf(label, sizeof label, ">%d", lo - 1);
                else if (lo == kBucketEnds[b]) std::snprintf(label, sizeof label, "%d", lo);
                else std::snprintf(label, sizeof label, "%d-%d", lo, kBucketEnds[b]);
                std::printf("  %-8s %7.2f%% %11.3e %11.3e %11.3e %8.2f\n", label, 100.0 * pixels[b], wboit[b], dfa[b], star[b],
                            wboit[b] > 0 ? dfa[b] / wboit[b] : 0.0);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "dfaoit_depth_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
