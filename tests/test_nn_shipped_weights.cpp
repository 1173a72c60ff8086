// The shipped weights are what `starnt train` writes with its defaults: byte for byte on the machine
// class that made them, and the same recipe and quality elsewhere (docs/DESIGN.md, "Training",
// reproducibility). About 5 s of training per network on llvmpipe + CPU. The starnt-residual and
// starnt-d recipes add --weighting tail-visibility.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

using namespace starnt;

namespace {

std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

}  // namespace

// A shipped network: its kind, its method folder and the options of its recipe beyond the defaults.
struct Shipped {
    std::string network, folder, recipe;
};
void PrintTo(const Shipped& s, std::ostream* os) { *os << s.network << s.recipe; }

class ShippedWeights : public ::testing::TestWithParam<Shipped> {};

TEST_P(ShippedWeights, RetrainingWithTheDefaultsGivesTheSameBytes) {
    const std::string network = GetParam().network, folder = GetParam().folder;
    const auto dir = test::makeTempDir("shipped-weights");
    const auto shipped = std::filesystem::path(STARNT_SOURCE_DIR) / "src/methods" / folder / (folder + "_weights.json");
    // The procedural families with no training lists leave the training set as it is: the same
    // bytes again, with the per-family report on top.
    std::string first;
    for (const std::string extra : {"", " --families all --family-lists 0"}) {
        const auto out = dir / (network + ".json");
        const test::CliRun r = test::run("train --network " + network + " --out " + out.string() + GetParam().recipe + extra);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string got = fileBytes(out), want = fileBytes(shipped);
        ASSERT_FALSE(want.empty());
        // Deterministic on this machine, whatever the options that leave the training set alone.
        if (first.empty()) first = got;
        EXPECT_TRUE(got == first) << network << extra << ": two trainings of the same set differ";
        if (got == want) continue;
        // Another CPU: most likely the C library's transcendental functions and llvmpipe's JIT code,
        // which differ in their last bits between processors (measured: the same input normalisation to the last
        // digit, different weights), and training amplifies that. The file must still be the same
        // recipe (every field but the weights and the validation error) reaching the same quality.
        nlohmann::json a = nlohmann::json::parse(got), b = nlohmann::json::parse(want);
        const double mseGot = a["validation_mse"].get<double>(), mseWant = b["validation_mse"].get<double>();
        EXPECT_NEAR(mseGot, mseWant, 0.03 * mseWant) << network << extra << ": retrained to another quality";
        for (auto* j : {&a, &b}) {
            j->erase("layers");
            j->erase("validation_mse");
        }
        EXPECT_EQ(a, b) << network << extra << ": retrained with another recipe than " << shipped;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryNetwork, ShippedWeights,
                         ::testing::Values(Shipped{"starnt", "starnt", ""}, Shipped{"dfaoit", "dfaoit", ""},
                                           Shipped{"starnt-residual", "starnt_residual", " --weighting tail-visibility"},
                                           Shipped{"starnt-d", "starnt_d", " --weighting tail-visibility"}),
                         [](const auto& info) { return info.param.folder; });
