// Training scene families (docs/DESIGN.md, "hybrid-moments and starnt-d"): named groups of per-pixel fragment lists that the project
// owns and generates itself, so that a network can be trained on some families and validated on
// one it never saw (`starnt train --hold-out FAMILY`). The suite scenes stay held out entirely.
//
// Two kinds of family:
//  - captured: the built-in scenes (tubes, smoke, panes, random), rendered and captured with the
//    A-buffer (needs GL; src/train/training_data.hpp);
//  - procedural: per-pixel fragment lists drawn along one view ray through a procedural object
//    (this file, CPU only). Depths are window depths of an orbit camera framing a unit sphere
//    (near/far hugging it, as orbitCamera does), so the depth weights of WBOIT see the same range
//    they see in a render; colours and alphas are coherent per object, as in real geometry.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "starnt/tools/fragments.hpp"
#include "starnt/network.hpp"
#include "starnt/tools/train.hpp"

namespace starnt::nn {

// sheets    few large overlapping coloured sheets (glazing, curtains, some folded), alpha 0.15-0.7
// particles smoke / dust clouds: many small faint particles, near-grey tints, alpha near the cut-off
// foliage   leaf cards: mostly alpha-tested (0.7-1) with soft edges, greens darkening with depth
// shells    nested closed shells: each crossed twice, so the colours repeat mirrored along the ray
// strands   hair-like strands: many thin lit fibres of one hair colour, alpha 0.1-0.6
std::vector<std::string> proceduralFamilyNames();
bool isProceduralFamily(const std::string& name);

// `count` lists of procedural family `name` (unsorted; order = submission order), deterministic
// for `seed`. Throws starnt::Error naming the valid families for an unknown name.
std::vector<FragmentList> proceduralFamilyLists(const std::string& name, size_t count, uint64_t seed);

// A family's lists for training and, drawn separately, for validation.
struct TrainingFamily {
    std::string name;
    std::vector<FragmentList> train, validation;
};

// Throws starnt::Error ("--hold-out NAME: no such training family (families: ...)") unless
// `holdOut` is empty or one of `familyNames`.
void checkHoldOut(const std::vector<std::string>& familyNames, const std::string& holdOut);

// Every family's training lists except the one named `holdOut` (empty: none), in the order given,
// followed by `extra` (the generic synthetic lists), as one training set of `kind`. Throws
// starnt::Error when `holdOut` is not empty and names none of `families`.
TrainingSet buildFamilyTrainingSet(NetworkKind kind, const std::vector<TrainingFamily>& families,
                                   const std::string& holdOut, const std::vector<FragmentList>& extra,
                                   SampleWeighting weighting = SampleWeighting::None);

// Image-space errors on a family's validation lists: mean over pixels with at least one fragment
// after the cut-off and over the 3 channels of (composite - exact composite)^2, over black (the
// background enters every method through the exact total transmittance, so it cancels).
struct FamilyErrors {
    size_t pixels = 0;      // lists with at least one fragment after the cut-off
    size_t tailPixels = 0;  // of which more than 3 (where STAR-NT evaluates its network)
    double network = 0.0;   // starnt or dfaoit, the network given
    double hybrid = 0.0;    // STAR-NT's closed-form tail (1 - t_tail) C_tilde
    double hybridMoments = 0.0;  // hybrid-moments' closed form (1 - t_tail) C_m
    double wboit = 0.0;     // weighted blended OIT, weight eq. 10 (the default)
    // The same means over the tail pixels only (N > 3): where STAR-NT's network decides the colour
    // (below that STAR-NT and hybrid are exact, and the whole-family means flatter them).
    double networkTail = 0.0, hybridTail = 0.0, wboitTail = 0.0;
};
FamilyErrors familyErrors(const Network& net, const std::vector<FragmentList>& lists,
                          float alphaCutoff = kDefaultAlphaCutoff);

// CPU reference of the wboit method (McGuire & Bavoil 2013, eq. 10 weight on window depth, clamped
// to [1e-2, 3e3], accumulated weight clamped to [1e-4, 5e4] as the composite shader does) over the
// fragments with alpha >= cut-off.
glm::vec3 compositeWboit(const FragmentList& fragments, glm::vec3 background, float alphaCutoff = kDefaultAlphaCutoff);

}  // namespace starnt::nn
