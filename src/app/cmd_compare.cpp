#include <cmath>
#include <cstdio>
#include <utility>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"

namespace starnt::app {

void addCompareCommand(CLI::App& app) {
    struct Args {
        std::string reference, test, flipMap;
        bool json = false;
        double ppd = 67.02;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand("compare", "MSE and LDR-FLIP of a test image against a reference (PNG or EXR)");
    cmd->add_option("--reference", args->reference, "reference image (.png sRGB or .exr linear)")->required();
    cmd->add_option("--test", args->test, "test image (.png sRGB or .exr linear)")->required();
    cmd->add_flag("--json", args->json, "print {\"mse\": ..., \"flip\": ...}");
    cmd->add_option("--flip-map", args->flipMap, "write the FLIP error map (magma colours) to this PNG");
    cmd->add_option("--ppd", args->ppd, "FLIP pixels per degree, 1..1000 (default 67.02)");
    cmd->callback([args] {
        if (!(args->ppd >= kFlipMinPixelsPerDegree && args->ppd <= kFlipMaxPixelsPerDegree)) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "--ppd %g: pixels per degree must be within %g..%g", args->ppd,
                          kFlipMinPixelsPerDegree, kFlipMaxPixelsPerDegree);
            throw Error(buf);
        }
        if (!args->flipMap.empty()) {
            for (const std::string* input : {&args->reference, &args->test}) {
                if (sameFile(args->flipMap, *input)) {
                    throw Error("--flip-map " + args->flipMap + " names an input image (" + *input + "); it would be overwritten");
                }
            }
        }
        Image ref = loadImage(args->reference);
        Image test = loadImage(args->test);
        // A NaN or infinite pixel has no error to measure; reading it as 0 or 1 would hide it.
        for (const auto& [image, path] : {std::pair{&ref, &args->reference}, std::pair{&test, &args->test}}) {
            size_t bad = 0, first = 0;
            for (size_t i = 0; i < image->rgba.size(); ++i) {
                if (std::isfinite(image->rgba[i])) continue;
                if (bad++ == 0) first = i / 4;
            }
            if (bad > 0) {
                throw Error(*path + ": " + std::to_string(bad) + " colour values are NaN or infinite (the first at pixel " +
                            std::to_string(first % size_t(image->width)) + "," + std::to_string(first / size_t(image->width)) + ")");
            }
        }
        if (ref.width != test.width || ref.height != test.height) {
            throw Error("images differ in size: " + args->reference + " is " + std::to_string(ref.width) + "x" +
                        std::to_string(ref.height) + ", " + args->test + " is " + std::to_string(test.width) + "x" +
                        std::to_string(test.height));
        }
        const double mse = mseSrgb(ref, test);
        FlipResult flipResult;
        if (args->flipMap.empty()) {
            flipResult.mean = flipMean(ref, test, args->ppd);  // no full-size error map
        } else {
            flipResult = flip(ref, test, args->ppd);
            saveImage(flipHeatmap(flipResult.errorMap), args->flipMap);
        }
        if (args->json) {
            std::printf("%s\n", nlohmann::json{{"mse", mse}, {"flip", flipResult.mean}}.dump().c_str());
        } else {
            std::printf("mse: %.8g (x10^2: %.6g)\nflip: %.6g\n", mse, mse * 100.0, flipResult.mean);
        }
    });
}

}  // namespace starnt::app
