// The shipped weights are what `starnt train` writes with its defaults, byte for byte (issue 15:
// retraining must reproduce them). About 5 s of training per network on llvmpipe + CPU. The
// starnt-residual and starnt-d recipes add --weighting tail-visibility (docs/DESIGN.md, "Training").
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

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
    for (const std::string extra : {"", " --families all --family-lists 0"}) {
        const auto out = dir / (network + ".json");
        const test::CliRun r = test::run("train --network " + network + " --out " + out.string() + GetParam().recipe + extra);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        const std::string got = fileBytes(out), want = fileBytes(shipped);
        ASSERT_FALSE(want.empty());
        EXPECT_TRUE(got == want) << network << extra << ": retrained weights differ from " << shipped;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryNetwork, ShippedWeights,
                         ::testing::Values(Shipped{"starnt", "starnt", ""}, Shipped{"dfaoit", "dfaoit", ""},
                                           Shipped{"starnt-residual", "starnt_residual", " --weighting tail-visibility"},
                                           Shipped{"starnt-d", "starnt_d", " --weighting tail-visibility"}),
                         [](const auto& info) { return info.param.folder; });
