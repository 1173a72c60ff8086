// Training scene families: the procedural generators, hold-out, per-family errors and
// the CPU WBOIT composite; `starnt train --hold-out` on the command line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "starnt/error.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/tools/families.hpp"
#include "starnt/tools/nn.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::nn;

namespace {

bool sameList(const FragmentList& a, const FragmentList& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(Fragment)) == 0);
}

// Window depth of the sphere centre for the orbit framing the generators use (families.cpp): a unit
// sphere seen from D = 1.02 / sin(22.5 deg), near/far = D -/+ 1.05, and GL's window depth
// far (z - near) / (z (far - near)) at z = D (0.69697; NnFamilies.CentreDepthIsTheOrbitFramings
// checks it against the camera code).
const double kCameraDistance = 1.02 / std::sin(glm::radians(22.5));
const float kCentreDepth = float((kCameraDistance + 1.05) * 1.05 / (kCameraDistance * 2.1));

Fragment frag(glm::vec3 color, float alpha, float depth) {
    Fragment f;
    f.color = color;
    f.alpha = alpha;
    f.depth = depth;
    return f;
}

}  // namespace

TEST(NnFamilies, EveryFamilyGivesValidDeterministicLists) {
    const auto names = proceduralFamilyNames();
    EXPECT_EQ(names, (std::vector<std::string>{"sheets", "particles", "foliage", "shells", "strands"}));
    for (const std::string& name : names) {
        const auto lists = proceduralFamilyLists(name, 3000, 7);
        ASSERT_EQ(lists.size(), 3000u);
        size_t tails = 0;
        for (const FragmentList& list : lists) {
            tails += preparedFragments(list).size() > 3;
            for (const Fragment& f : list) {
                ASSERT_TRUE(f.alpha >= 0.0f && f.alpha <= 1.0f) << name;
                ASSERT_TRUE(f.depth > 0.0f && f.depth < 1.0f) << name;
                for (int k = 0; k < 3; ++k) ASSERT_TRUE(f.color[k] >= 0.0f && f.color[k] <= 1.0f) << name;
            }
        }
        // Every family feeds STAR-NT's network (N > 3) often enough to matter in training.
        EXPECT_GT(tails, 600u) << name;
        const auto again = proceduralFamilyLists(name, 3000, 7), other = proceduralFamilyLists(name, 3000, 8);
        size_t same = 0, sameOther = 0;
        for (size_t i = 0; i < lists.size(); ++i) {
            same += sameList(lists[i], again[i]);
            sameOther += sameList(lists[i], other[i]);
        }
        EXPECT_EQ(same, lists.size()) << name;
        EXPECT_LT(sameOther, 30u) << name;  // only the odd empty list agrees
    }
    // Two families never share a stream for the same seed.
    EXPECT_FALSE(sameList(proceduralFamilyLists("particles", 1, 1)[0], proceduralFamilyLists("strands", 1, 1)[0]));
}

// kCentreDepth is what the project's own orbit framing gives: orbitCamera (45 degrees, a square
// image) around a unit sphere, the centre projected to window depth.
TEST(NnFamilies, CentreDepthIsTheOrbitFramings) {
    const float a = 1.0f / std::sqrt(3.0f);  // Bounds::radius is half the box diagonal: 1
    const Bounds unitSphere{glm::vec3(-a), glm::vec3(a)};
    const Camera cam = orbitCamera(unitSphere, 30.0f, 10.0f, 1.0f);
    const glm::vec4 clip = cam.projection(1.0f) * cam.view() * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(clip.z / clip.w * 0.5f + 0.5f, kCentreDepth, 1e-5f);
    EXPECT_NEAR(kCentreDepth, 0.69697f, 1e-5f);  // the value the formula gives, as a reader checks it
}

TEST(NnFamilies, FamiliesHaveTheirOwnStatistics) {
    // sheets: few fragments, alpha 0.15-0.7, several clearly different colours along the ray.
    size_t multiColour = 0;
    for (const FragmentList& list : proceduralFamilyLists("sheets", 2000, 3)) {
        EXPECT_LE(list.size(), 18u);
        std::set<std::pair<float, float>> hues;
        for (const Fragment& f : list) {
            EXPECT_GE(f.alpha, 0.15f);
            EXPECT_LE(f.alpha, 0.7f);
            hues.insert({f.color.r, f.color.b});
        }
        multiColour += hues.size() >= 3;
    }
    EXPECT_GT(multiColour, 800u);
    // shells: sorted by depth the colours and alphas are mirrored, and the ray crosses the centre.
    for (const FragmentList& list : proceduralFamilyLists("shells", 500, 3)) {
        FragmentList sorted = list;
        sortByDepth(sorted);
        ASSERT_EQ(sorted.size() % 2, 0u);
        for (size_t i = 0; i < sorted.size() / 2; ++i) {
            EXPECT_EQ(sorted[i].color, sorted[sorted.size() - 1 - i].color);
            EXPECT_EQ(sorted[i].alpha, sorted[sorted.size() - 1 - i].alpha);
            // Mirrored shells: the nearer half in front of the centre, the farther half behind it.
            EXPECT_LE(sorted[i].depth, kCentreDepth + 1e-6f);
            EXPECT_GE(sorted[sorted.size() - 1 - i].depth, kCentreDepth - 1e-6f);
            // ... at mirrored distances: the pair's mean view distance is the centre's, D (window
            // depth d back to distance with the framing's near and far: f n / (f - d (f - n))).
            const double n = kCameraDistance - 1.05, f = kCameraDistance + 1.05;
            auto distance = [&](float d) { return f * n / (f - double(d) * (f - n)); };
            EXPECT_NEAR(0.5 * (distance(sorted[i].depth) + distance(sorted[sorted.size() - 1 - i].depth)), kCameraDistance, 1e-4);
        }
    }
    // particles: faint (many below the cut-off); foliage: mostly alpha-tested; strands: long lists.
    size_t faint = 0, all = 0, opaque = 0, leaves = 0, longLists = 0;
    for (const FragmentList& list : proceduralFamilyLists("particles", 1000, 3)) {
        for (const Fragment& f : list) faint += f.alpha < kDefaultAlphaCutoff, ++all;
    }
    EXPECT_GT(faint, all / 20);
    for (const FragmentList& list : proceduralFamilyLists("foliage", 1000, 3)) {
        for (const Fragment& f : list) opaque += f.alpha >= 0.7f, ++leaves;
    }
    EXPECT_GT(opaque, leaves * 6 / 10);
    for (const FragmentList& list : proceduralFamilyLists("strands", 1000, 3)) longLists += list.size() >= 100;
    EXPECT_GT(longLists, 150u);
}

TEST(NnFamilies, UnknownFamilyNamesTheValidOnes) {
    const std::string message = test::errorOf([] { proceduralFamilyLists("glass", 10, 1); });
    EXPECT_NE(message.find("glass"), std::string::npos) << message;
    EXPECT_NE(message.find("sheets, particles, foliage, shells, strands"), std::string::npos) << message;
    EXPECT_FALSE(isProceduralFamily("glass"));
    EXPECT_TRUE(isProceduralFamily("shells"));
}

TEST(NnFamilies, HeldOutFamilyIsAbsentFromTheTrainingSet) {
    std::vector<TrainingFamily> families;
    for (const std::string name : {"sheets", "particles", "shells"}) {
        families.push_back({name, proceduralFamilyLists(name, 1500, 2), {}});
    }
    const auto extra = syntheticFragmentLists(500, 2);
    for (NetworkKind kind : {NetworkKind::StarNT, NetworkKind::DFAOIT}) {
        const TrainingSet all = buildFamilyTrainingSet(kind, families, "", extra);
        const TrainingSet without = buildFamilyTrainingSet(kind, families, "particles", extra);
        const TrainingSet sheets = buildTrainingSet(kind, families[0].train), particles = buildTrainingSet(kind, families[1].train),
                          shells = buildTrainingSet(kind, families[2].train), synthetic = buildTrainingSet(kind, extra);
        ASSERT_GT(particles.size(), 100u);
        EXPECT_EQ(all.size(), sheets.size() + particles.size() + shells.size() + synthetic.size());
        EXPECT_EQ(without.size(), sheets.size() + shells.size() + synthetic.size());
        // Exactly the other families' samples, in order.
        TrainingSet expected = sheets;
        expected.append(shells);
        expected.append(synthetic);
        EXPECT_EQ(without.x, expected.x);
        EXPECT_EQ(without.y, expected.y);
        // No sample of the held-out family is in it (a particle list's features are distinctive).
        const size_t width = static_cast<size_t>(without.inputs);
        std::set<std::vector<float>> rows;
        for (size_t i = 0; i < without.size(); ++i) rows.insert({without.x.begin() + i * width, without.x.begin() + (i + 1) * width});
        size_t found = 0;
        for (size_t i = 0; i < particles.size(); ++i) {
            found += rows.count({particles.x.begin() + i * width, particles.x.begin() + (i + 1) * width});
        }
        EXPECT_EQ(found, 0u);
    }
    const std::string message = test::errorOf([&] { buildFamilyTrainingSet(NetworkKind::StarNT, families, "hair", extra); });
    EXPECT_NE(message.find("--hold-out hair: no such training family (families: sheets, particles, shells)"),
              std::string::npos)
        << message;
}

TEST(NnFamilies, CpuWboitIsTheWeightedAverageUnderTheExactOpacity) {
    // Two fragments: depth 0 gets the maximum weight 3e3, depth 0.9 gets 3e3 * 0.001 = 3.
    const FragmentList list = {frag({1, 0, 0}, 0.5f, 0.9f), frag({0, 0, 1}, 0.5f, 0.0f), frag({0, 1, 0}, 0.02f, 0.0f)};
    const float wNear = 0.5f * 0.5f * 3e3f, wFar = 0.5f * 0.5f * 3.0f;  // alpha * (alpha * clamp(...))
    const glm::vec3 expected = glm::vec3(wFar, 0.0f, wNear) / (wNear + wFar) * 0.75f + glm::vec3(0.2f) * 0.25f;
    const glm::vec3 got = compositeWboit(list, glm::vec3(0.2f));  // the green fragment is below the cut-off
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], expected[k], 1e-5f);
    EXPECT_EQ(compositeWboit({}, glm::vec3(0.3f)), glm::vec3(0.3f));
}

TEST(NnFamilies, FamilyErrorsCompareWithTheExactComposite) {
    // Up to three fragments STAR-NT and hybrid are exact; WBOIT is not when the order matters.
    const std::vector<FragmentList> lists = {
        {frag({1, 0, 0}, 0.6f, 0.3f), frag({0, 0, 1}, 0.6f, 0.5f), frag({0, 1, 0}, 0.6f, 0.7f)},
        {frag({1, 1, 1}, 0.01f, 0.5f)},  // nothing after the cut-off: not a pixel
        {},
    };
    const Network untrained = makeUntrained(NetworkKind::StarNT, 1);
    const FamilyErrors e = familyErrors(untrained, lists);
    EXPECT_EQ(e.pixels, 1u);
    EXPECT_EQ(e.tailPixels, 0u);
    EXPECT_NEAR(e.network, 0.0, 1e-12);
    EXPECT_NEAR(e.hybrid, 0.0, 1e-12);
    const glm::vec3 d = compositeWboit(lists[0], glm::vec3(0.0f)) - compositeOver(preparedFragments(lists[0]), glm::vec3(0.0f));
    EXPECT_NEAR(e.wboit, glm::dot(d, d) / 3.0f, 1e-9);
    EXPECT_GT(e.wboit, 1e-3);
    // A tail pixel: the untrained network is far off, the errors are per pixel means.
    const auto sheets = proceduralFamilyLists("sheets", 400, 5);
    const FamilyErrors s = familyErrors(untrained, sheets);
    EXPECT_GT(s.tailPixels, 50u);
    EXPECT_GT(s.network, s.hybrid);
    EXPECT_GT(s.wboit, 0.0);
}

TEST(NnFamiliesCli, HoldOutNamingNoFamilyIsAnError) {
    const auto dir = test::makeTempDir("families-cli");
    const std::string out = (dir / "w.json").string();
    const test::CliRun r = test::run("train --network starnt --out " + out + " --hold-out glazing");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.exitCode, -1) << "crashed";
    EXPECT_EQ(r.err.rfind("starnt: error: --hold-out glazing: no such training family (families: tubes, smoke, panes, "
                          "random, sheets, particles, foliage, shells, strands)",
                          0),
              0u)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    const test::CliRun bad = test::run("train --network starnt --out " + out + " --families sheets,glass");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.err.find("glass"), std::string::npos) << bad.err;
    // Bad --weighting and --report are refused before any capture or training.
    const test::CliRun weighting = test::run("train --network starnt --out " + out + " --weighting linear");
    EXPECT_NE(weighting.exitCode, 0);
    EXPECT_EQ(weighting.err, "starnt: error: --weighting linear: expected none or tail-visibility\n");
    const test::CliRun report = test::run("train --network starnt --out " + out + " --report " + (dir / "r.txt").string());
    EXPECT_NE(report.err.find("the report must be a .json file"), std::string::npos) << report.err;
    const test::CliRun folder =
        test::run("train --network starnt --out " + out + " --report " + (dir / "missing" / "r.json").string());
    EXPECT_NE(folder.err.find("does not exist"), std::string::npos) << folder.err;
    // A procedural family left out of --families cannot be held out.
    const test::CliRun notTrained = test::run("train --network starnt --out " + out + " --families sheets --hold-out shells");
    EXPECT_NE(notTrained.err.find("--hold-out shells: no such training family"), std::string::npos) << notTrained.err;
}

TEST(NnFamiliesCli, HoldOutTrainsAndReportsEveryFamily) {
    const auto dir = test::makeTempDir("families-cli");
    const std::string out = (dir / "w.json").string(), report = (dir / "r.json").string();
    const test::CliRun r = test::run("train --network starnt --out " + out + " --report " + report +
                                     " --scenes builtin:panes --capture-width 16 --capture-height 12 --families "
                                     "shells,sheets --hold-out sheets --samples 5000 --synthetic 200 "
                                     "--family-lists 1000 --validation-lists 300");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find(" sheets held out shells 1000;"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("HELD-OUT"), std::string::npos) << r.out;
    std::ifstream in(report);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("held_out"), "sheets");
    ASSERT_EQ(j.at("families").size(), 3u);
    std::vector<std::string> names;
    for (const auto& f : j.at("families")) {
        names.push_back(f.at("family"));
        EXPECT_EQ(f.at("held_out").get<bool>(), f.at("family") == "sheets");
        EXPECT_GT(f.at("validation_pixels").get<size_t>(), 0u);
        EXPECT_GT(f.at("mse_wboit").get<double>(), 0.0);
    }
    // The project's order, not the order given.
    EXPECT_EQ(names, (std::vector<std::string>{"panes", "sheets", "shells"}));
    EXPECT_EQ(j.at("families")[1].at("training_lists"), 0);
    EXPECT_EQ(j.at("families")[2].at("training_lists"), 1000);
    EXPECT_GT(j.at("families")[0].at("training_lists").get<size_t>(), 0u);
}

TEST(NnFamiliesCli, HoldingOutABuiltinSceneDropsItsCaptures) {
    const auto dir = test::makeTempDir("families-cli");
    const std::string out = (dir / "w.json").string(), report = (dir / "r.json").string();
    const test::CliRun r = test::run("train --network dfaoit --out " + out + " --report " + report +
                                     " --scenes builtin:panes builtin:curtains --capture-width 16 --capture-height 12"
                                     " --hold-out curtains --families foliage --family-lists 500 --validation-lists 200"
                                     " --samples 2000 --synthetic 100");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find(" curtains held out foliage 500;"), std::string::npos) << r.err;
    std::ifstream in(report);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("network"), "dfaoit");
    ASSERT_EQ(j.at("families").size(), 3u);
    EXPECT_EQ(j.at("families")[1].at("family"), "curtains");
    EXPECT_TRUE(j.at("families")[1].at("held_out").get<bool>());
    EXPECT_TRUE(j.at("families")[1].at("captured").get<bool>());
    EXPECT_EQ(j.at("families")[1].at("training_lists"), 0);
    EXPECT_GT(j.at("families")[1].at("validation_pixels").get<size_t>(), 20u);
    EXPECT_FALSE(j.at("families")[2].at("captured").get<bool>());
}
