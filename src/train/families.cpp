// Procedural training families (include/starnt/tools/families.hpp): each list is what one pixel of a
// procedural object sees along its view ray, with per-object colours and alphas (not per-fragment
// noise), so the colour along the tail is as coherent or as ordered as in real geometry.
#include "starnt/tools/families.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "scene/hue_color.hpp"
#include "nn/random.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"

namespace starnt::nn {

namespace {

using detail::Rng;

// Orbit framing of a unit sphere (orbitCamera with the 45 degree field of view and fitClipPlanes):
// camera distance r / sin(22.5 deg) * 1.02, near/far = distance -/+ 1.05 r.
constexpr double kCameraDistance = 1.02 / 0.38268343236508984;
constexpr double kNear = kCameraDistance - 1.05, kFar = kCameraDistance + 1.05;

// Window depth of a point at signed offset `s` in [-1, 1] from the sphere centre along the ray
// (GL perspective, depth range [0, 1]): far (z - near) / (z (far - near)).
float windowDepth(double s) {
    const double z = kCameraDistance + std::clamp(s, -1.0, 1.0);
    return static_cast<float>(kFar * (z - kNear) / (z * (kFar - kNear)));
}

// The headlight Lambert factor of the project's lit shading (docs/DESIGN.md, "Shading").
double litFactor(double cosine) { return 0.35 + 0.65 * std::fabs(cosine); }

// A saturated colour of any hue (wrapped into [0, 1)), mixed with white by `pastel`.
glm::dvec3 hueColor(double hue, double pastel) { return starnt::hueColor<double>(hue - std::floor(hue), pastel); }

Fragment makeFragment(const glm::dvec3& color, double alpha, double s, uint32_t order) {
    Fragment f;
    f.color = glm::vec3(glm::clamp(color, glm::dvec3(0.0), glm::dvec3(1.0)));
    f.alpha = static_cast<float>(std::clamp(alpha, 0.0, 1.0));
    f.depth = windowDepth(s);
    f.order = order;
    return f;
}

// Few large sheets (glazing, curtains) of clearly different colours, each covering the pixel or
// not; a curtain may fold and cross the ray up to three times close together.
FragmentList sheetsList(Rng& rng) {
    FragmentList list;
    const int sheets = rng.range(2, 6);
    const double pastel = rng.uniform(0.0, 0.4);
    const double coverage = rng.uniform(0.6, 1.0);
    const bool folded = rng.uniform() < 0.5;
    const double hue0 = rng.uniform();
    for (int k = 0; k < sheets; ++k) {
        // Hues spread around the circle so that neighbouring sheets really differ in colour.
        const glm::dvec3 color = hueColor(hue0 + double(k) / sheets + rng.uniform(-0.08, 0.08), pastel);
        const double alpha = rng.uniform(0.15, 0.7);
        const double position = rng.uniform(-0.9, 0.9);
        const double facing = rng.uniform(0.3, 1.0);
        if (rng.uniform() >= coverage) continue;
        const int crossings = folded ? rng.range(1, 3) : 1;
        for (int c = 0; c < crossings; ++c) {
            const double s = position + (c == 0 ? 0.0 : rng.uniform(-0.1, 0.1));
            // Unlit glazing half of the time, lit cloth otherwise.
            const double shade = folded ? litFactor(facing * rng.uniform(0.5, 1.0)) : 1.0;
            list.push_back(makeFragment(color * shade, alpha, s, static_cast<uint32_t>(k)));
        }
    }
    return list;
}

// A cloud of small faint billboards: grey with a faint tint, a denser and sometimes warmer core.
FragmentList particlesList(Rng& rng) {
    FragmentList list;
    const double density = rng.uniform();
    const int count = 1 + static_cast<int>(160.0 * density * density);
    const double baseAlpha = rng.uniform(0.02, 0.35);
    const double grey = rng.uniform(0.3, 0.95);
    const glm::dvec3 tint = hueColor(rng.uniform(), rng.uniform(0.7, 0.95));
    const bool fiery = rng.uniform() < 0.25;
    const double centre = rng.uniform(-0.4, 0.4), halfWidth = rng.uniform(0.2, 0.6);
    for (int i = 0; i < count; ++i) {
        const double s = centre + halfWidth * rng.uniform(-1.0, 1.0);
        const double core = 1.0 - std::fabs(s - centre) / halfWidth;  // 1 at the centre, 0 at the edge
        glm::dvec3 color = grey * tint * rng.uniform(0.85, 1.1);
        if (fiery) color = glm::mix(color, glm::dvec3(1.0, 0.75, 0.2), core);
        const double alpha = baseAlpha * rng.uniform(0.4, 1.2) * (0.6 + 0.4 * core);
        list.push_back(makeFragment(color, alpha, s, static_cast<uint32_t>(i)));
    }
    return list;
}

// Leaf cards in a canopy: alpha-tested texels (alpha 0.7-1) with soft edges, greens (sometimes
// autumn colours) that darken deeper in the canopy, a few branch fragments.
FragmentList foliageList(Rng& rng) {
    FragmentList list;
    const int cards = rng.range(1, 40);
    const double hue = rng.uniform() < 0.8 ? rng.uniform(0.2, 0.4) : rng.uniform(0.0, 0.15);
    const double softEdges = rng.uniform(0.0, 0.4);
    const double centre = rng.uniform(-0.3, 0.3), halfWidth = rng.uniform(0.3, 0.7);
    for (int i = 0; i < cards; ++i) {
        const double s = centre + halfWidth * rng.uniform(-1.0, 1.0);
        const double depthInCanopy = (s - (centre - halfWidth)) / (2.0 * halfWidth);  // 0 front, 1 back
        const bool branch = rng.uniform() < 0.05;
        glm::dvec3 color = branch ? glm::dvec3(0.35, 0.22, 0.12)
                                  : hueColor(hue + rng.uniform(-0.04, 0.04), 0.0) * rng.uniform(0.35, 0.8);
        color *= litFactor(rng.uniform()) * (1.0 - 0.6 * depthInCanopy);
        const double alpha = branch ? 1.0 : rng.uniform() < softEdges ? rng.uniform(0.05, 0.6) : rng.uniform(0.7, 1.0);
        list.push_back(makeFragment(color, alpha, s, static_cast<uint32_t>(i)));
    }
    return list;
}

// Nested closed shells around one centre, seen at impact parameter b: every shell larger than b is
// crossed twice, so the colour sequence along the ray is mirrored (outer ... inner inner ... outer).
FragmentList shellsList(Rng& rng) {
    FragmentList list;
    const int shells = rng.range(2, 8);
    const double b = rng.uniform(0.0, 0.9);
    const double pastel = rng.uniform(0.0, 0.5);
    const bool lit = rng.uniform() < 0.6;
    const double hue0 = rng.uniform(), hueStep = rng.uniform(0.05, 0.35);
    for (int k = 0; k < shells; ++k) {
        const double radius = 1.0 - 0.9 * double(k) / shells;
        if (radius <= b) break;
        const glm::dvec3 color = hueColor(hue0 + hueStep * k, pastel);
        const double alpha = rng.uniform(0.1, 0.6);
        const double half = std::sqrt(radius * radius - b * b);
        const double shade = lit ? litFactor(half / radius) : 1.0;
        list.push_back(makeFragment(color * shade, alpha, -half, static_cast<uint32_t>(2 * k)));
        list.push_back(makeFragment(color * shade, alpha, half, static_cast<uint32_t>(2 * k + 1)));
    }
    return list;
}

// Hair-like strands: many thin lit fibres of one hair colour (black, brown, blond, red or grey),
// each with its own small variation; the far half of the volume is darker (self-shadowing).
FragmentList strandsList(Rng& rng) {
    static const glm::dvec3 kHair[] = {{0.05, 0.04, 0.035}, {0.3, 0.18, 0.1}, {0.85, 0.7, 0.45}, {0.6, 0.2, 0.08},
                                       {0.7, 0.7, 0.7}};
    FragmentList list;
    const double density = rng.uniform();
    const int count = 1 + static_cast<int>(200.0 * density * density);
    const glm::dvec3 hair = kHair[rng.below(5)];
    const double baseAlpha = rng.uniform(0.1, 0.6);
    const double halfWidth = rng.uniform(0.3, 0.9);
    for (int i = 0; i < count; ++i) {
        const double s = halfWidth * rng.uniform(-1.0, 1.0);
        const double surface = s < 0.0 ? 1.0 : 0.7;  // the far half lies in the near half's shadow
        const glm::dvec3 color = hair * rng.uniform(0.8, 1.2) * litFactor(rng.uniform()) * surface;
        const double alpha = baseAlpha * rng.uniform(0.7, 1.3);
        list.push_back(makeFragment(color, alpha, s, static_cast<uint32_t>(i)));
    }
    return list;
}

using ListGenerator = FragmentList (*)(Rng&);

struct ProceduralFamily {
    const char* name;
    ListGenerator generate;
    uint64_t salt;  // keeps the families' random streams apart for the same seed
};

constexpr ProceduralFamily kFamilies[] = {
    {"sheets", sheetsList, 0x5ee7ULL},     {"particles", particlesList, 0x9a27ULL},
    {"foliage", foliageList, 0xf011aULL},  {"shells", shellsList, 0x5e11ULL},
    {"strands", strandsList, 0x57a2dULL},
};

std::string familyList() {
    std::string names;
    for (const ProceduralFamily& f : kFamilies) names += (names.empty() ? "" : ", ") + std::string(f.name);
    return names;
}

double squaredError(const glm::vec3& a, const glm::vec3& b) {
    const glm::dvec3 d = glm::dvec3(a) - glm::dvec3(b);
    return glm::dot(d, d) / 3.0;
}

}  // namespace

std::vector<std::string> proceduralFamilyNames() {
    std::vector<std::string> names;
    for (const ProceduralFamily& f : kFamilies) names.emplace_back(f.name);
    return names;
}

bool isProceduralFamily(const std::string& name) {
    return std::any_of(std::begin(kFamilies), std::end(kFamilies),
                       [&](const ProceduralFamily& f) { return name == f.name; });
}

std::vector<FragmentList> proceduralFamilyLists(const std::string& name, size_t count, uint64_t seed) {
    for (const ProceduralFamily& family : kFamilies) {
        if (name != family.name) continue;
        Rng rng(seed * 0x100000001b3ULL ^ family.salt);
        std::vector<FragmentList> lists(count);
        for (FragmentList& list : lists) list = family.generate(rng);
        return lists;
    }
    throw Error("unknown procedural training family '" + name + "' (valid: " + familyList() + ")");
}

void checkHoldOut(const std::vector<std::string>& familyNames, const std::string& holdOut) {
    if (holdOut.empty() || std::find(familyNames.begin(), familyNames.end(), holdOut) != familyNames.end()) return;
    std::string names;
    for (const std::string& n : familyNames) names += (names.empty() ? "" : ", ") + n;
    throw Error("--hold-out " + holdOut + ": no such training family (families: " + names + ")");
}

TrainingSet buildFamilyTrainingSet(NetworkKind kind, const std::vector<TrainingFamily>& families,
                                   const std::string& holdOut, const std::vector<FragmentList>& extra,
                                   SampleWeighting weighting) {
    std::vector<std::string> names;
    for (const TrainingFamily& f : families) names.push_back(f.name);
    checkHoldOut(names, holdOut);
    TrainingSet set;
    set.inputs = inputCount(kind);
    for (const TrainingFamily& family : families) {
        if (family.name != holdOut) set.append(buildTrainingSet(kind, family.train, kDefaultAlphaCutoff, weighting));
    }
    set.append(buildTrainingSet(kind, extra, kDefaultAlphaCutoff, weighting));
    return set;
}

FamilyErrors familyErrors(const Network& net, const std::vector<FragmentList>& lists,
                          float alphaCutoff) {
    FamilyErrors e;
    const glm::vec3 black(0.0f);
    for (const FragmentList& list : lists) {
        const FragmentList sorted = preparedFragments(list, alphaCutoff);
        if (sorted.empty()) continue;
        ++e.pixels;
        e.tailPixels += sorted.size() > 3;
        const glm::vec3 exact = compositeOver(sorted, black);
        const PixelSums sums = sumsFromFragments(list, alphaCutoff);
        const TailMoments moments = tailMomentsFromFragments(list, alphaCutoff);
        const glm::vec3 predicted = compositeNetwork(net, sums, black, &moments);
        const double network = squaredError(predicted, exact), hybrid = squaredError(compositeHybrid(sums, black), exact),
                     wboit = squaredError(compositeWboit(sorted, black, alphaCutoff), exact);
        e.network += network;
        e.hybrid += hybrid;
        e.hybridMoments += squaredError(compositeHybridMoments(sums, moments, black), exact);
        e.wboit += wboit;
        if (sorted.size() > 3) {
            e.networkTail += network;
            e.hybridTail += hybrid;
            e.wboitTail += wboit;
        }
    }
    const auto mean = [](double& sum, size_t n) { sum = n > 0 ? sum / static_cast<double>(n) : 0.0; };
    for (double* sum : {&e.network, &e.hybrid, &e.hybridMoments, &e.wboit}) mean(*sum, e.pixels);
    for (double* sum : {&e.networkTail, &e.hybridTail, &e.wboitTail}) mean(*sum, e.tailPixels);
    return e;
}

glm::vec3 compositeWboit(const FragmentList& fragments, glm::vec3 background, float alphaCutoff) {
    glm::vec3 weightedColor(0.0f);
    float weightSum = 0.0f, revealage = 1.0f;
    for (const Fragment& f : fragments) {
        if (!(f.alpha >= alphaCutoff)) continue;
        const float d = 1.0f - f.depth;
        const float w = f.alpha * std::clamp(3e3f * d * d * d, 1e-2f, 3e3f);
        weightedColor += f.color * f.alpha * w;
        weightSum += f.alpha * w;
        revealage *= 1.0f - f.alpha;
    }
    return weightedColor / std::clamp(weightSum, 1e-4f, 5e4f) * (1.0f - revealage) + background * revealage;
}

}  // namespace starnt::nn
