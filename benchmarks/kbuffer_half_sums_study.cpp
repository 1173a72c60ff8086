// Offline study: what 16-bit float storage of kbuffer-moments' blended sums costs, with the blended
// additions rounded to nearest (GPUs) or toward zero (llvmpipe). Not a test and not part of the
// library; it changes nothing at run time.
//
//   starnt_kbuffer_half_sums_study [--width W] [--scenes a,b,...] [--orbit DEG] [--attribution 0|1]
//
// Scenes: suite scenes (bench::suiteScenes(), read from STARNT_SHARED_SCENES) or builtin:NAME, at
// camera orbit DEG (default 0), elevation 15. Every fragment is captured (A-buffer), each pixel's list
// put in submission order (sortBySubmission: the order the GPU blends and fetches them in), and
// kbuffer-moments' one geometry pass (pass3_accumulate.frag.glsl, STARNT_PACKED_THREE_LAYERS with
// STARNT_BEHIND_MOMENTS) is replayed on the CPU: each fragment (alpha >= the cut-off, window depth
// < 1) is inserted into the nearest three layers (temporal::insertThreeLayers) and its terms added
// into the three sums targets:
//   target 0: (a C, a)                     target 1: (a v^2, -ln(1 - a))
//   target 3: (a C v, a v)                 v = u - pivot, u = depthBehindReference(z, reference),
// the pivot the u of the pixel's first fragment in draw order, the reference depth
// temporal::referenceDepthOnCpu over the nearest layer's keyed depth (as reference_depth.frag.glsl
// with STARNT_REFERENCE_FROM_PACKED reads it; here this frame's own, not the previous frame's).
// The sums are folded in draw order three ways: in 32-bit floats; with each blended addition
// rounded to the nearest 16-bit float (ties to even); truncated toward zero to 16 bits (the
// source term itself unrounded, as nn::sumsInHalfTargets models it). Each is composited as
// correction_composite.frag.glsl does (the nearest layer over max(the second over the third over
// the ordered closed form behind it, 0), orderedClosedFormBehindThreeLayers; the background where
// 1 - a1 <= STARNT_TEMPORAL_MIN_TRANSMITTANCE) and its MSE (sRGB, as the bench) taken against the
// exact composite of the depth-sorted list. A "double" column sums in double (behindMomentsOf).
// --attribution 1 adds the MSE with only one target (or channel) in 16 bits, the others 32-bit,
// the optical depth kept in 32 bits, and truncation of the source term as well as of the sum.
// The last three columns: the mitigation behindThirdTerms (sums over the fragments behind the
// third layer only) in 32 bits, 16 bits to nearest and truncated.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "study_support.hpp"
#include "methods/neural/temporal/packed_nearest.h"
#include "methods/neural/temporal/reprojection_constants.h"
#include "reference/correction_cpu.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/gl_context.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;

namespace {

using study::squaredSrgb;

enum class Storage { Double, Float, HalfNearest, HalfTruncated, HalfTruncatedSource };

// One blended addition into a target of the given storage.
float blendAdd(float dst, float src, Storage s) {
    switch (s) {
    case Storage::HalfNearest: return nn::roundToHalf(dst + src, false);
    case Storage::HalfTruncated: return nn::roundToHalf(dst + src, true);
    case Storage::HalfTruncatedSource: return nn::roundToHalf(dst + nn::roundToHalf(src, true), true);
    default: return dst + src;
    }
}

// Per-target storage: target 0 (sum a C, sum a), target 1 .x (sum a v^2), target 1 .y (optical
// depth), target 3 (sum a C v, sum a v).
struct Layout {
    const char* name;
    Storage t0, t1m2, t1od, t3;
};

struct PixelSums {
    glm::vec4 sums{0.0f}, moment1{0.0f};
    float moment2 = 0.0f, opticalDepth = 0.0f;
};

struct Term {
    glm::vec4 sums, moment1;
    float moment2, opticalDepth;
};

PixelSums fold(const std::vector<Term>& terms, const Layout& l) {
    PixelSums p;
    if (l.t0 == Storage::Double) {
        glm::dvec4 s(0.0), m1(0.0);
        double m2 = 0.0, od = 0.0;
        for (const Term& t : terms) {
            s += glm::dvec4(t.sums);
            m1 += glm::dvec4(t.moment1);
            m2 += double(t.moment2);
            od += double(t.opticalDepth);
        }
        return {glm::vec4(s), glm::vec4(m1), float(m2), float(od)};
    }
    for (const Term& t : terms) {
        for (int c = 0; c < 4; ++c) {
            p.sums[c] = blendAdd(p.sums[c], t.sums[c], l.t0);
            p.moment1[c] = blendAdd(p.moment1[c], t.moment1[c], l.t3);
        }
        p.moment2 = blendAdd(p.moment2, t.moment2, l.t1m2);
        p.opticalDepth = blendAdd(p.opticalDepth, t.opticalDepth, l.t1od);
    }
    return p;
}

// A suite scene (as study::captureSuiteScene) or builtin:NAME, camera orbit `azimuth` / elevation 15.
study::CapturedScene captureScene(const std::string& name, int width, int height, float azimuth) {
    bench::SceneSpec spec{"builtin-" + name.substr(std::min<size_t>(8, name.size())), name, std::nullopt, 0.03f, 0, ""};
    std::string source = name;
    if (name.rfind("builtin:", 0) != 0) {
        const auto& specs = bench::suiteScenes();
        const auto it = std::find_if(specs.begin(), specs.end(), [&](const auto& s) { return s.name == name; });
        if (it == specs.end()) throw Error("unknown suite scene '" + name + "'");
        spec = *it;
        source = (std::filesystem::path(STARNT_SHARED_SCENES) / spec.source).string();
    }
    const Scene scene = loadScene(source);
    const float aspect = float(width) / float(height);
    const Camera camera = orbitCamera(scene.bounds(), azimuth, 15.0f, aspect);
    SceneGpu gpu(scene);
    study::CapturedScene out;
    out.spec = spec;
    out.frame.width = width;
    out.frame.height = height;
    out.frame.background = glm::vec3(1.0f);
    out.frame.view = camera.view();
    out.frame.projection = camera.projection(aspect);
    out.frame.alphaCutoff = spec.alphaCutoff;
    FragmentCapture capturer(SceneGpu::surfaceShader());
    out.fragments = capturer.capture(out.frame, gpu.callback(out.frame.view, out.frame.projection, bench::surfaceOptionsFor(spec)));
    return out;
}

Term termOf(const Fragment& f, float reference, float pivot) {
    const float v = temporal::depthBehindReference(f.depth, reference) - pivot;
    const glm::vec4 s(f.color * f.alpha, f.alpha);
    const glm::vec4 m1 = s * v;
    return {s, m1, m1.a * v, -std::log(std::max(1.0f - f.alpha, float(STARNT_ORDERED_MIN_OPENNESS)))};
}

// The mitigation: with framebuffer fetch the shader knows which fragment leaves the three layers
// for good (the old third when a fragment enters them, or the fragment itself behind the third):
// only those are summed, so the composite subtracts no layer's terms from the 16-bit sums. The
// evicted third's terms come from its packed values (quantised colour and alpha, keyed depth).
void behindThirdTerms(const FragmentList& list, float reference, float pivot, std::vector<Term>& out) {
    out.clear();
    constexpr uint32_t lowBits = 32u - STARNT_PACKED_LAYER_KEY_BITS;
    glm::uvec4 layers = temporal::packedLayersEmpty();
    glm::uvec2 third = temporal::packedLayerEmpty();
    for (const Fragment& f : list) {
        const glm::vec4 c(f.color, f.alpha);
        const uint32_t key = temporal::packLayer(f.depth, c).x >> lowBits;
        const uint32_t first = layers.x >> lowBits, second = layers.z >> lowBits, last = third.x >> lowBits;
        const bool tie = key == first || key == second || key == last;
        if (!tie && key > last) {
            out.push_back(termOf(f, reference, pivot));
        } else if (!tie && third.x != temporal::packedLayerEmpty().x) {
            Fragment evicted;
            const glm::vec4 e = temporal::unpackLayer(third, evicted.depth);
            evicted.color = glm::vec3(e);
            evicted.alpha = e.a;
            out.push_back(termOf(evicted, reference, pivot));
        }
        temporal::insertThreeLayers(layers, third, f.depth, c);
    }
}

// The composite of the mitigation: the three layers over the ordered closed form of the sums
// behind the third (moments recentred at u3; ordered_behind.glsl's guards).
glm::vec3 behindThirdComposite(const glm::vec4& l1, const glm::vec4& l2, const glm::vec4& l3, float z3, float reference,
                               float pivot, const PixelSums& p, const glm::vec3& background) {
    const float u3 = temporal::depthBehindReference(z3, reference) - pivot;
    glm::vec4 first = p.moment1 - u3 * p.sums;
    float second = p.moment2 - u3 * (p.moment1.a + first.a);
    if (!(second > float(STARNT_ORDERED_RECENTRED_PRECISION) * p.moment2)) {
        first = glm::vec4(0.0f);
        second = 0.0f;
    }
    glm::vec3 c = temporal::orderedClosedFormBehindFromMoments(glm::vec4(0.0f), p.sums, std::exp(-p.opticalDepth), first, second,
                                                             background);
    for (const glm::vec4& l : {l3, l2}) {
        if (!(l.a > 0.0f)) continue;
        c = 1.0f - l.a > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE) ? l.a * glm::vec3(l) + (1.0f - l.a) * c : glm::vec3(l);
    }
    if (!(1.0f - l1.a > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) c = background;
    return l1.a * glm::vec3(l1) + (1.0f - l1.a) * glm::max(c, glm::vec3(0.0f));
}

}  // namespace

int main(int argc, char** argv) {
    int width = 640;
    bool attribution = false;
    float azimuth = 0.0f;
    std::vector<std::string> names = {"magic_stars", "chess", "tree", "hair", "hairball", "engine"};
    if (!study::parseStudyArgs(argc, argv, "kbuffer_half_sums_study", width, names,
                               {{"--attribution", [&](const std::string& v) { attribution = v == "1"; }},
                                {"--orbit", [&](const std::string& v) { azimuth = std::stof(v); }}}))
        return 2;
    const int height = width * 9 / 16;
    std::vector<Layout> layouts = {
        {"double", Storage::Double, Storage::Double, Storage::Double, Storage::Double},
        {"fp32", Storage::Float, Storage::Float, Storage::Float, Storage::Float},
        {"fp16 nearest", Storage::HalfNearest, Storage::HalfNearest, Storage::HalfNearest, Storage::HalfNearest},
        {"fp16 trunc", Storage::HalfTruncated, Storage::HalfTruncated, Storage::HalfTruncated, Storage::HalfTruncated},
    };
    if (attribution) {
        const Storage F = Storage::Float, N = Storage::HalfNearest, T = Storage::HalfTruncated;
        layouts.push_back({"near t0 only", N, F, F, F});
        layouts.push_back({"near m2 only", F, N, F, F});
        layouts.push_back({"near od only", F, F, N, F});
        layouts.push_back({"near t3 only", F, F, F, N});
        layouts.push_back({"near, od fp32", N, N, F, N});
        layouts.push_back({"trunc t0 only", T, F, F, F});
        layouts.push_back({"trunc m2 only", F, T, F, F});
        layouts.push_back({"trunc od only", F, F, T, F});
        layouts.push_back({"trunc t3 only", F, F, F, T});
        layouts.push_back({"trunc, od fp32", T, T, F, T});
        const Storage S = Storage::HalfTruncatedSource;
        layouts.push_back({"trunc src+sum", S, S, S, S});
    }
    try {
        HeadlessGlContext context(GlApi::Desktop);
        std::printf("kbuffer-moments, MSE (sRGB) against the exact composite, %dx%d, default camera (orbit 0/15)\n", width, height);
        std::printf("%-14s %9s %8s", "scene", "frags", "reorder");
        for (const Layout& l : layouts) std::printf(" %14s", l.name);
        std::printf(" %14s %14s %14s", "behind fp32", "behind near", "behind trunc");
        std::printf(" | %9s %9s | %14s %7s\n", "near/fp32", "trunc/fp32", "behind near/32", "trunc/32");
        for (const std::string& name : names) {
            const study::CapturedScene captured = captureScene(name, width, height, azimuth);
            const glm::vec3 background = captured.frame.background;
            const float cutoff = captured.spec.alphaCutoff;
            const size_t pixels = size_t(width) * size_t(height);
            // Draw-order lists (what pass 3 keeps of them) and the packed layers, GL order (rows bottom-first).
            std::vector<FragmentList> drawn(pixels);
            std::vector<glm::uvec4> layers(pixels, temporal::packedLayersEmpty());
            std::vector<glm::uvec2> thirds(pixels, temporal::packedLayerEmpty());
            std::vector<float> nearestDepth(pixels, 1.0f);
            size_t fragmentCount = 0, reordered = 0;
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const size_t i = size_t(y) * size_t(width) + size_t(x);
                    FragmentList list = captured.fragments.at(x, height - 1 - y);
                    const FragmentList asCaptured = list;
                    sortBySubmission(list);
                    bool same = true;
                    for (size_t k = 0; k < list.size(); ++k) same = same && list[k].order == asCaptured[k].order;
                    reordered += !same;
                    std::erase_if(list, [&](const Fragment& f) { return !(f.alpha >= cutoff) || !(f.depth < 1.0f); });
                    fragmentCount += list.size();
                    for (const Fragment& f : list) temporal::insertThreeLayers(layers[i], thirds[i], f.depth, glm::vec4(f.color, f.alpha));
                    float z = 1.0f;
                    temporal::unpackLayer(glm::uvec2(layers[i].x, layers[i].y), z);
                    nearestDepth[i] = z;
                    drawn[i] = std::move(list);
                }
            }
            const std::vector<float> reference = temporal::referenceDepthOnCpu(nearestDepth, width, height);
            std::vector<double> mse(layouts.size(), 0.0);
            std::vector<Term> terms, behindTerms;
            std::vector<double> mseBehind(3, 0.0);
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const size_t i = size_t(y) * size_t(width) + size_t(x);
                    const FragmentList& list = drawn[i];
                    if (list.empty()) continue;
                    const glm::vec3 exact = compositeOver(nn::preparedFragments(captured.fragments.at(x, height - 1 - y), cutoff), background);
                    const float r = temporal::referenceAt(reference, width, x, y);
                    const float pivot = temporal::depthBehindReference(list.front().depth, r);
                    // The shader's float operations per fragment.
                    terms.clear();
                    for (const Fragment& f : list) terms.push_back(termOf(f, r, pivot));
                    behindThirdTerms(list, r, pivot, behindTerms);
                    float z1 = 1.0f, z2 = 1.0f, z3 = 1.0f;
                    const glm::vec4 l1 = temporal::unpackLayer(glm::uvec2(layers[i].x, layers[i].y), z1);
                    const glm::vec4 l2 = temporal::unpackLayer(glm::uvec2(layers[i].z, layers[i].w), z2);
                    const glm::vec4 l3 = temporal::unpackLayer(thirds[i], z3);
                    for (size_t k = 0; k < layouts.size(); ++k) {
                        const PixelSums p = fold(terms, layouts[k]);
                        glm::vec3 out = background;
                        if (l1.a > 0.0f) {
                            const float t = std::exp(-p.opticalDepth);
                            glm::vec3 behind = background;
                            if (1.0f - l1.a > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE)) {
                                const temporal::OrderedBehind m{p.moment1, p.moment2, r, pivot};
                                behind = glm::max(
                                    temporal::orderedClosedFormBehindThreeLayers(l1, z1, l2, z2, l3, z3, p.sums, t, m, background),
                                    glm::vec3(0.0f));
                            }
                            out = l1.a * glm::vec3(l1) + (1.0f - l1.a) * behind;
                        }
                        mse[k] += squaredSrgb(out, exact);
                    }
                    const Storage behindStorage[3] = {Storage::Float, Storage::HalfNearest, Storage::HalfTruncated};
                    for (int k = 0; k < 3; ++k) {
                        const Storage b = behindStorage[k];
                        const PixelSums p = fold(behindTerms, {"", b, b, b, b});
                        const glm::vec3 out = l1.a > 0.0f ? behindThirdComposite(l1, l2, l3, z3, r, pivot, p, background) : background;
                        mseBehind[k] += squaredSrgb(out, exact);
                    }
                }
            }
            for (double& m : mse) m /= double(pixels);
            for (double& m : mseBehind) m /= double(pixels);
            std::printf("%-14s %9zu %8zu", name.c_str(), fragmentCount, reordered);
            for (double m : mse) std::printf(" %14.4e", m);
            for (double m : mseBehind) std::printf(" %14.4e", m);
            std::printf(" | %9.3f %9.3f | behind %7.3f %7.3f\n", mse[2] / mse[1], mse[3] / mse[1], mseBehind[1] / mseBehind[0],
                        mseBehind[2] / mseBehind[0]);
            std::fflush(stdout);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "kbuffer_half_sums_study: %s\n", e.what());
        return 1;
    }
    return 0;
}
