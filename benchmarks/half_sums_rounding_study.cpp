// Offline study: how much of the compact layout's change in MSE comes from llvmpipe's
// truncating blends, and what a GPU's round-to-nearest blending would give. Not a test and not
// part of the library.
//
//   starnt_rounding_study [--width W] [--scenes a,b,...]
//
// For each suite scene (bench::suiteScenes(), default camera orbit 0/15) it captures every fragment
// and composites each pixel three ways on the CPU with the shipped networks: from 32-bit sums
// (nn::sumsFromFragments: the fp32 layout), and from the compact targets' model
// (nn::sumsInHalfTargets: 16-bit sums, R16 transmittance; DFAOIT with its narrow layers) with the
// blended additions rounded to nearest (GPUs) or toward zero (llvmpipe). It prints each one's MSE
// against the exact composite (sRGB, as the bench) and the change against 32-bit sums.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/metrics.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;

namespace {

void setPixel(Image& image, int x, int y, const glm::vec3& c) {
    float* p = image.pixel(x, y);
    p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 1.0f;
}

}  // namespace

int main(int argc, char** argv) {
    int width = 1280;
    std::vector<std::string> names = {"smoke", "hair", "hairball", "tree"};
    if (!study::parseStudyArgs(argc, argv, "rounding_study", width, names)) return 2;
    const int height = width * 9 / 16;
    try {
        HeadlessGlContext context(GlApi::Desktop);
        const nn::Network dfaoit = loadMethodNetwork(*neuralConfig("dfaoit"), {});
        const nn::Network starnt = loadMethodNetwork(*neuralConfig("starnt"), {});
        std::printf("%-12s %-7s %12s %12s %9s %12s %9s\n", "scene", "method", "fp32 sums", "half nearest", "change",
                    "half trunc", "change");
        for (const std::string& name : names) {
            const study::CapturedScene captured = study::captureSuiteScene(name, width, height);
            const bench::SceneSpec* spec = &captured.spec;
            const FrameDesc& frame = captured.frame;
            const CapturedFrame& fragments = captured.fragments;
            for (const bool isDfaoit : {true, false}) {
                Image exact(width, height), full(width, height), nearest(width, height), truncated(width, height);
                for (int y = 0; y < height; ++y) {
                    for (int x = 0; x < width; ++x) {
                        const FragmentList& raw = fragments.at(x, y);
                        auto composite = [&](const nn::PixelSums& s) {
                            return isDfaoit ? nn::compositeDfaoit(dfaoit, s, frame.background)
                                            : nn::compositeStarnt(starnt, s, frame.background);
                        };
                        setPixel(exact, x, y, compositeOver(nn::preparedFragments(raw, spec->alphaCutoff), frame.background));
                        setPixel(full, x, y, composite(nn::sumsFromFragments(raw, spec->alphaCutoff)));
                        setPixel(nearest, x, y, composite(nn::sumsInHalfTargets(raw, false, spec->alphaCutoff, isDfaoit)));
                        setPixel(truncated, x, y, composite(nn::sumsInHalfTargets(raw, true, spec->alphaCutoff, isDfaoit)));
                    }
                }
                const double mseFull = mseSrgb(exact, full), mseNearest = mseSrgb(exact, nearest),
                             mseTruncated = mseSrgb(exact, truncated);
                std::printf("%-12s %-7s %12.4e %12.4e %+8.2f%% %12.4e %+8.2f%%\n", name.c_str(), isDfaoit ? "dfaoit" : "starnt",
                            mseFull, mseNearest, 100.0 * (mseNearest / mseFull - 1.0), mseTruncated,
                            100.0 * (mseTruncated / mseFull - 1.0));
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rounding_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
