#include "bench/bench_report.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <set>
#include <sstream>

#include "render/option_text.hpp"

namespace starnt::bench {
namespace {

using nlohmann::json;
constexpr const char* kMissing = "–";

std::string fixed(double v, int decimals) {
    if (!std::isfinite(v)) return kMissing;
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, v);
    return text;
}

// Milliseconds with three significant-ish digits: 0.123, 1.23, 12.3, 123.
std::string ms(double v) {
    if (!std::isfinite(v)) return kMissing;
    return fixed(v, v < 1.0 ? 3 : v < 10.0 ? 2 : v < 100.0 ? 1 : 0);
}

std::string percent(const std::optional<double>& v) { return v ? fixed(*v, 1) + "%" : kMissing; }

std::optional<double> passMs(const CaseResult* c, const std::string& pass) {
    if (!c || !c->ok || !c->stats.contains("pass_ms") || !c->stats["pass_ms"].contains(pass)) return std::nullopt;
    return c->stats["pass_ms"][pass].get<double>();
}

// Passes that are neither a geometry pass nor inference: tile evaluation, upsampling, reprojection.
std::optional<double> computeMs(const CaseResult* c) {
    if (!c || !c->ok || !c->stats.contains("pass_ms")) return std::nullopt;
    double sum = 0.0;
    bool any = false;
    for (auto& [name, value] : c->stats["pass_ms"].items()) {
        if (name == "pass1" || name == "pass2" || name == "pass3" || name == "inference") continue;
        sum += value.get<double>();
        any = true;
    }
    return any ? std::optional(sum) : std::nullopt;
}

std::string optMs(const std::optional<double>& v) { return v ? ms(*v) : kMissing; }

double meanOf(const std::vector<double>& values) {
    if (values.empty()) return NAN;
    double s = 0.0;
    for (double v : values) s += v;
    return s / double(values.size());
}

std::string sceneLabel(const SceneResult& s) {
    std::string label = s.spec.name + " (D " + std::to_string(s.maxFragments);
    if (s.spec.paperDepth) label += "; paper " + std::to_string(s.spec.paperDepth);
    return label + ")";
}

// A table with one row per scene and one column per variant, cells from `cell` (failed cases say
// so), and an optional average row over the scenes where `value` exists.
void sceneByVariantTable(std::ostringstream& md, const Results& r, const std::function<std::string(const CaseResult&)>& cell,
                         const std::function<std::optional<double>(const CaseResult&)>& value = nullptr,
                         const std::function<std::string(double)>& formatAverage = nullptr) {
    md << "| scene |";
    for (const auto& v : r.plan.variants) md << ' ' << v.name << " |";
    md << "\n|---|";
    for (size_t i = 0; i < r.plan.variants.size(); ++i) md << "---|";
    md << '\n';
    std::vector<std::vector<double>> columns(r.plan.variants.size());
    for (const auto& s : r.scenes) {
        md << "| " << sceneLabel(s) << " |";
        for (size_t i = 0; i < r.plan.variants.size(); ++i) {
            const CaseResult* c = s.find(r.plan.variants[i].name);
            if (!s.loaded) md << " not loaded |";
            else if (!c || !c->ok) md << " failed |";
            else {
                md << ' ' << cell(*c) << " |";
                if (value) {
                    if (auto v = value(*c)) columns[i].push_back(*v);
                }
            }
        }
        md << '\n';
    }
    if (value && formatAverage) {
        md << "| **average** |";
        for (const auto& column : columns) md << ' ' << (column.empty() ? kMissing : formatAverage(meanOf(column))) << " |";
        md << '\n';
    }
    md << '\n';
}

void header(std::ostringstream& md, const Results& r) {
    const auto& m = r.machine;
    md << "# STAR-NT benchmark\n\n";
    md << "| | |\n|---|---|\n";
    md << "| date (UTC) | " << r.date << " |\n";
    md << "| GL renderer | " << m.gl.renderer << " (" << m.gl.version << ")" << (m.gl.software ? ", software rasteriser" : "") << " |\n";
    md << "| EGL display | " << m.gl.platform << (m.gl.refused.empty() ? "" : " (refused before it: " + m.gl.refused + ")") << " |\n";
    md << "| CPU | " << m.cpuModel << ", " << m.cpuThreads << " threads"
       << (m.lpNumThreads.empty() ? "" : ", LP_NUM_THREADS=" + m.lpNumThreads) << " |\n";
    md << "| build | " << m.buildType << ", commit " << m.commit << ", " << m.compiler << " |\n";
    md << "| preset | " << r.plan.preset << ": " << r.plan.width << "x" << r.plan.height << ", " << r.plan.frames
       << " frames along `" << r.plan.cameraPath << "` |\n";
    md << "| scenes | " << r.plan.suiteNote << " |\n";
    md << "| command | `" << r.commandLine << "` |\n";
    md << "| wall time | " << fixed(r.wallSeconds, 1) << " s |\n\n";
    md << "Frame times are means over the " << r.plan.frames << " timed frames, after " << r.plan.warmupFrames
       << " untimed warm-up frames at the first camera (shader compiles; tiles settle; with interpolated frames, on "
          "to the end of a group, so that the timed frames start at a real one): the same statistic for "
          "every variant, table and plots (interpolated and probe frames make periodic sequences); with interpolated "
          "frames, the long-run mean: the real and the interpolated frames' means weighted by their shares in the "
          "schedule (1/K real), as a window of frames holds a whole number of real ones (at K = 8, 2 in 10 from a "
          "real frame; the plain means are in \"Against itself\"), "
          "in a run of the path with nothing between its frames (the errors come from a second run that "
          "reads every frame back)"
       << (r.plan.timingRounds > 1 ? "; each variant's fastest of " + std::to_string(r.plan.timingRounds) +
                                         " such runs, timed in alternating order (round 2 backwards through the variants)"
                                   : std::string())
       << "; glFinish + wall clock"
       << (m.gl.software ? "; on a CPU rasteriser they rank methods by work done, not by GPU speed" : "")
       << "; per-pass times are " << (m.gl.software ? "glFinish + wall clock around each pass" : "GL_TIMESTAMP pairs")
       << ". Errors are means over "
       << (r.plan.qualityEvery > 1 ? "the frames i with i mod " + std::to_string(r.plan.qualityEvery) + " < 3"
                                   : std::string("every frame"))
       << " against the A-buffer at the same camera. D is the largest "
          "number of fragments on one pixel at the last camera.\n\n";
}

void frameTimeTable(std::ostringstream& md, const Results& r) {
    md << "## Frame time (ms)\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return ms(c.frameMs()); },
        [](const CaseResult& c) { return std::optional(c.frameMs()); }, [](double v) { return ms(v); });
    // On a GPU: the same frames timed by a GL_TIMESTAMP pair around each (the GPU's time alone),
    // long-run means as the table above.
    const auto gpuMs = [](const CaseResult& c) { return c.gpuFrameMs(); };
    bool any = false;
    for (const auto& s : r.scenes)
        for (const auto& c : s.cases) any = any || (c.ok && gpuMs(c));
    if (!any) return;
    md << "GPU time per frame (ms): a GL_TIMESTAMP pair around each timed frame, long-run means; without the "
          "driver's work on the CPU that the table above includes.\n\n";
    sceneByVariantTable(
        md, r, [&](const CaseResult& c) { return gpuMs(c) ? ms(*gpuMs(c)) : std::string(kMissing); }, gpuMs,
        [](double v) { return ms(v); });
}

// The GPU estimate (render/gpu_estimate.hpp) beside, never inside, the measured tables: long-run
// means of each frame's estimate, and the ratio to DFAOIT's estimate in the same run.
void gpuEstimateTable(std::ostringstream& md, const Results& r) {
    const auto estimate = [](const CaseResult& c) -> std::optional<double> {
        if (!c.ok || !c.stats.contains("gpu_estimate_ms_long_run") || !c.stats["gpu_estimate_ms_long_run"].is_number()) return std::nullopt;
        return c.stats["gpu_estimate_ms_long_run"].get<double>();
    };
    bool any = false;
    std::string model;
    for (const auto& s : r.scenes)
        for (const auto& c : s.cases) {
            any = any || estimate(c).has_value();
            if (model.empty() && c.stats.contains("gpu_estimate_model")) model = c.stats["gpu_estimate_model"].get<std::string>();
        }
    if (!any) return;
    md << "## GPU estimate (ms a frame; an estimate, not a measurement)\n\n"
          "What a GPU would take for these frames: each geometry pass's fragments (GL_SAMPLES_PASSED) times a cost "
          "that grows with the bytes each fragment writes by format class (`pass_blend`), each full-screen pass its "
          "pixels; coefficients fitted to "
       << model << " (docs/DESIGN.md, \"Cost on a GPU\"). Long-run means; in brackets the ratio to DFAOIT's estimate.\n\n";
    sceneByVariantTable(
        md, r,
        [&](const CaseResult& c) {
            const auto e = estimate(c);
            if (!e) return std::string(kMissing);
            const SceneResult* scene = nullptr;
            for (const auto& s : r.scenes)
                for (const auto& other : s.cases)
                    if (&other == &c) scene = &s;
            const CaseResult* dfaoit = scene ? scene->find("dfaoit") : nullptr;
            const auto base = dfaoit ? estimate(*dfaoit) : std::nullopt;
            return ms(*e) + (base && *base > 0 ? " (" + fixed(*e / *base, 2) + "x)" : std::string());
        },
        estimate, [](double v) { return ms(v); });
    md << "Bytes a fragment writes into its colour targets per geometry pass (`pass_blend` of the real frames; "
          "32-bit float bytes in brackets) and the bits a pixel of the targets it binds, from the first scene:\n\n"
          "| variant | passes |\n|---|---|\n";
    for (const auto& v : r.plan.variants) {
        for (const auto& s : r.scenes) {
            const CaseResult* c = s.find(v.name);
            if (!c || !c->ok || !c->stats.contains("pass_blend")) continue;
            std::string cell;
            for (auto& [pass, blend] : c->stats["pass_blend"].items()) {
                double bytes = 0;
                for (auto& [cls, value] : blend.items())
                    if (cls != "target_bits_per_pixel") bytes += value.get<double>();
                cell += (cell.empty() ? "" : "; ") + pass + " " + fixed(bytes, 1) + " B (" + fixed(blend.value("float32", 0.0), 1) +
                        "), " + std::to_string(blend.value("target_bits_per_pixel", 0)) + " bits";
            }
            md << "| " << v.name << " | " << (cell.empty() ? std::string(kMissing) : cell) << " |\n";
            break;
        }
    }
    md << '\n';
}

void passBreakdownTable(std::ostringstream& md, const Results& r) {
    md << "## Per-pass breakdown (ms)\n\n"
          "As the paper's ablation table: passes 1-3 and inference of DFAOIT (full resolution), Pass N↓ and "
          "inference of STAR-NT with tiles on (scales chosen by the tiles; P2/P3 % are the last frame's), "
          "Compute = every other STAR-NT pass (tiles, upsampling). Totals are whole-frame medians.\n\n";
    md << "| scene (P2%, P3%, D) | Pass 1 | Pass 2 | Pass 2↓ | Pass 3 | Pass 3↓ | Compute | Inf. DFAOIT | Inf. STAR | "
          "Total DFAOIT | Total STAR-NT w/o temporal | Total STAR | Speed-up |\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& s : r.scenes) {
        const CaseResult* dfa = s.find("dfaoit");
        const CaseResult* star = s.find("starnt");
        const CaseResult* total = s.find("starnt-total");
        auto okFrame = [](const CaseResult* c) { return c && c->ok ? std::optional(c->frameMs()) : std::nullopt; };
        std::string p2 = kMissing, p3 = kMissing;
        if (star && star->ok) {
            p2 = fixed(star->stats.value("scale_pass2", NAN) * 100.0, 0);
            p3 = fixed(star->stats.value("scale_pass3", NAN) * 100.0, 0);
        }
        std::optional<double> speedup;
        if (okFrame(dfa) && okFrame(total) && *okFrame(dfa) > 0.0) speedup = (*okFrame(dfa) - *okFrame(total)) / *okFrame(dfa) * 100.0;
        md << "| " << s.spec.name << " (100, " << p2 << ", " << p3 << ", " << s.maxFragments << ") | "
           << optMs(passMs(dfa, "pass1")) << " | " << optMs(passMs(dfa, "pass2")) << " | " << optMs(passMs(star, "pass2")) << " | "
           << optMs(passMs(dfa, "pass3")) << " | " << optMs(passMs(star, "pass3")) << " | " << optMs(computeMs(star)) << " | "
           << optMs(passMs(dfa, "inference")) << " | " << optMs(passMs(star, "inference")) << " | " << optMs(okFrame(dfa))
           << " | " << optMs(okFrame(star)) << " | " << optMs(okFrame(total)) << " | " << percent(speedup) << " |\n";
    }
    md << "\nEvery pass of every method (median ms):\n\n| scene | method | passes |\n|---|---|---|\n";
    for (const auto& s : r.scenes) {
        for (const auto& c : s.cases) {
            if (!c.ok || !c.stats.contains("pass_ms")) continue;
            std::string passes;
            for (auto& [name, value] : c.stats["pass_ms"].items()) passes += (passes.empty() ? "" : ", ") + name + " " + ms(value.get<double>());
            md << "| " << s.spec.name << " | " << c.variant << " | " << (passes.empty() ? kMissing : passes) << " |\n";
        }
    }
    md << '\n';
}

// Fragment-shader invocations per frame (mean over the timed frames) of the named passes, or of
// every counted pass when `passes` is empty.
std::optional<double> fragments(const CaseResult* c, std::initializer_list<const char*> passes = {}) {
    if (!c || !c->ok || !c->stats.contains("pass_counters") || c->stats["pass_counters"].empty()) return std::nullopt;
    double sum = 0.0;
    for (auto& [name, counters] : c->stats["pass_counters"].items()) {
        bool wanted = passes.size() == 0;
        for (const char* p : passes) wanted = wanted || name == p;
        if (wanted) sum += counters.value("fragment_invocations", 0.0);
    }
    return sum;
}

std::string millions(double v) { return fixed(v / 1e6, 2); }

// Mean of a per-frame number over the real (not interpolated) timed frames.
std::optional<double> realFrameMean(const CaseResult& c, const char* key) {
    double sum = 0.0;
    int n = 0;
    for (const auto& f : c.frames) {
        if (f.value("interpolated", false) || !f.contains(key) || !f[key].is_number()) continue;
        sum += f[key].get<double>();
        ++n;
    }
    return n ? std::optional(sum / n) : std::nullopt;
}

// What the tiles chose and what it saved in work, which does not depend on the machine.
void scalesAndWorkTables(std::ostringstream& md, const Results& r) {
    md << "## Fragments shaded per frame (millions, all geometry passes)\n\n"
          "Fragment-shader invocations (GL_ARB_pipeline_statistics_query), mean per timed frame: the work a GPU "
          "would do, independent of the machine's speed.\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { auto f = fragments(&c); return f ? millions(*f) : kMissing; },
        [](const CaseResult& c) { return fragments(&c); }, [](double v) { return millions(v); });
    md << "## Scales and passes 2 + 3 work of the STAR-NT variants\n\n"
          "P2 / P3: mean pass scales over the real timed frames; w_bar: the last frame's; frag. 2+3: fragments "
          "shaded by passes 2 and 3 per frame (millions, mean); vs full: their reduction against starnt-full "
          "in the same run.\n\n| scene | variant | P2 % | P3 % | w_bar | frag. 2+3 | vs full |\n|---|---|---|---|---|---|---|\n";
    for (const auto& s : r.scenes) {
        const auto full = fragments(s.find("starnt-full"), {"pass2", "pass3"});
        for (const auto& c : s.cases) {
            if (!c.ok || c.method != "starnt") continue;
            const auto p2 = realFrameMean(c, "scale_pass2"), p3 = realFrameMean(c, "scale_pass3");
            const auto f23 = fragments(&c, {"pass2", "pass3"});
            std::optional<double> saved;
            if (full && f23 && *full > 0.0) saved = (*full - *f23) / *full * 100.0;
            const auto& wBar = c.stats.contains("w_bar") ? c.stats["w_bar"] : nlohmann::json(nullptr);
            md << "| " << s.spec.name << " | " << c.variant << " | " << (p2 ? fixed(*p2 * 100.0, 0) : kMissing) << " | "
               << (p3 ? fixed(*p3 * 100.0, 0) : kMissing) << " | " << (wBar.is_number() ? fixed(wBar.get<double>(), 2) : kMissing)
               << " | " << (f23 ? millions(*f23) : kMissing) << " | " << percent(saved) << " |\n";
        }
    }
    md << '\n';
}

void speedupTable(std::ostringstream& md, const Results& r) {
    md << "## Speed-up over DFAOIT\n\n"
          "Percent of DFAOIT's frame time saved (positive = faster than DFAOIT), per method.\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return percent(c.speedupVsDfaoit); },
        [](const CaseResult& c) { return c.speedupVsDfaoit; }, [](double v) { return fixed(v, 1) + "%"; });
}

// The same method with and without an acceleration, from one run (docs/DESIGN.md, "Temporal reprojection": a saving is measured
// against the acceleration off, never against the accelerated run's own real frames), beside what
// the interpolated frames cost in error.
void againstItselfTable(std::ostringstream& md, const Results& r) {
    std::vector<const Variant*> pairs;
    for (const auto& v : r.plan.variants) {
        if (v.accelerationOff.empty()) continue;
        for (const auto& s : r.scenes) {
            if (s.find(v.name) && s.find(v.accelerationOff)) {
                pairs.push_back(&v);
                break;
            }
        }
    }
    if (pairs.empty()) return;
    md << "## Against itself\n\n"
          "Mean frame time of each accelerated variant over that of the same method with the acceleration off, in "
          "this run (< 1: the acceleration saves time). With interpolated frames: their FLIP over the real frames' "
          "(means over the path), and the worst interpolated frame's MSE over the mean MSE of the real frames beside "
          "it (a flash). Times are long-run means (header); \"window\" is the ratio of the plain means of the timed frames.\n\n"
          "| scene | variant | acceleration | against | ms | ms off | time ratio | window | FLIP interp / real | worst flash |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Variant* v : pairs) {
        std::vector<double> ratios, windowRatios;
        for (const auto& s : r.scenes) {
            const CaseResult* on = s.find(v->name);
            const CaseResult* off = s.find(v->accelerationOff);
            if (!on || !off || !on->ok || !off->ok) continue;
            const double ratio = on->frameMs() / off->frameMs();
            const double windowRatio = on->windowFrameMs() / off->windowFrameMs();
            if (std::isfinite(ratio)) ratios.push_back(ratio);
            if (std::isfinite(windowRatio)) windowRatios.push_back(windowRatio);
            std::string flipRatio = kMissing, flash = kMissing;
            if (on->quality && on->quality->byFrameKind.is_object()) {
                const json& e = on->quality->byFrameKind;
                const json real = e.value("real", json::object()), interp = e.value("interpolated", json::object());
                if (real.value("flip_mean", json()).is_number() && interp.value("flip_mean", json()).is_number()) {
                    flipRatio = fixed(interp["flip_mean"].get<double>() / real["flip_mean"].get<double>(), 2);
                }
                if (e.contains("interpolated_flash")) {
                    flash = fixed(e["interpolated_flash"].value("worst_ratio", NAN), 2) + " (frame " +
                            std::to_string(e["interpolated_flash"].value("frame", -1)) + ")";
                }
            }
            md << "| " << s.spec.name << " | " << v->name << " | " << v->acceleration << " | " << v->accelerationOff << " | "
               << ms(on->frameMs()) << " | " << ms(off->frameMs()) << " | " << fixed(ratio, 2) << " | " << fixed(windowRatio, 2)
               << " | " << flipRatio << " | "
               << flash << " |\n";
        }
        md << "| **mean** | " << v->name << " | " << v->acceleration << " | " << v->accelerationOff << " | | | "
           << fixed(meanOf(ratios), 2) << " | " << fixed(meanOf(windowRatios), 2) << " | | |\n";
    }
    md << '\n';
}

void qualityTables(std::ostringstream& md, const Results& r) {
    md << "## Quality against the A-buffer\n\n### MSE x10^2\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return c.quality ? fixed(c.quality->mse * 100.0, 4) : std::string(kMissing); },
        [](const CaseResult& c) { return c.quality ? std::optional(c.quality->mse * 100.0) : std::nullopt; },
        [](double v) { return fixed(v, 4); });
    md << "### FLIP\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return c.quality ? fixed(c.quality->flip, 4) : std::string(kMissing); },
        [](const CaseResult& c) { return c.quality ? std::optional(c.quality->flip) : std::nullopt; },
        [](double v) { return fixed(v, 4); });
    md << "### MSE reduction against WBOIT (positive = lower error than WBOIT)\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return percent(c.mseReductionVsWboit); },
        [](const CaseResult& c) { return c.mseReductionVsWboit; }, [](double v) { return fixed(v, 1) + "%"; });
    md << "### FLIP reduction against WBOIT\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return percent(c.flipReductionVsWboit); },
        [](const CaseResult& c) { return c.flipReductionVsWboit; }, [](double v) { return fixed(v, 1) + "%"; });
}

// What the network adds: the same three passes with the tail in closed form (hybrid) against the networks
// (starnt-full, and starnt-residual-full, hybrid-moments, starnt-d where they ran), all at full
// resolution, scene by scene.
void networkAddsTable(std::ostringstream& md, const Results& r) {
    // The network variants to set beside hybrid: those that ran with it on some scene.
    std::vector<std::string> networks;
    for (const char* name : {"starnt-full", "starnt-residual-full", "hybrid-moments", "starnt-d"}) {
        for (const auto& s : r.scenes) {
            if (s.find("hybrid") && s.find(name)) {
                networks.emplace_back(name);
                break;
            }
        }
    }
    if (networks.empty() || networks.front() != "starnt-full") return;
    const auto ran = [&](const char* name) { return std::find(networks.begin(), networks.end(), name) != networks.end(); };
    md << "## What the network adds (starnt-full against hybrid)\n\n"
          "All run STAR-NT's three passes at full resolution; hybrid composites the tail in closed form, "
          "(1 - t_tail) C_tilde, where starnt evaluates the paper's network"
       << (ran("starnt-residual-full") ? ", starnt-residual a network of the same size that corrects the closed form, "
                                         "(1 - t_tail) max(C_tilde + f(x), 0)"
                                       : "")
       << (ran("hybrid-moments") ? ", hybrid-moments the closed form with the tail colour weighted by the tail's depth "
                                   "moments (C_m, no network)"
                                 : "")
       << (ran("starnt-d") ? ", starnt-d a network that corrects C_m" : "")
       << ". Ratio < 1: more accurate than hybrid.\n\n| scene | MSE x10^2 hybrid |";
    for (const auto& n : networks) md << " MSE x10^2 " << n << " | ratio |";
    md << " FLIP hybrid |";
    for (const auto& n : networks) md << " FLIP " << n << " |";
    md << " ms hybrid |";
    for (const auto& n : networks) md << " ms " << n << " |";
    md << "\n|---|---|";
    for (size_t i = 0; i < 4 * networks.size() + 2; ++i) md << "---|";
    md << "\n";
    std::vector<std::vector<double>> ratios(networks.size());
    for (const auto& s : r.scenes) {
        const CaseResult* h = s.find("hybrid");
        std::vector<const CaseResult*> cases;
        for (const auto& n : networks) {
            const CaseResult* c = s.find(n);
            cases.push_back(c && c->quality ? c : nullptr);
        }
        if (!h || !h->quality || !cases.front()) continue;
        md << "| " << s.spec.name << " | " << fixed(h->quality->mse * 100.0, 4) << " |";
        for (size_t i = 0; i < cases.size(); ++i) {
            if (!cases[i]) {
                md << " " << kMissing << " | " << kMissing << " |";
                continue;
            }
            const double ratio = h->quality->mse > 0.0 ? cases[i]->quality->mse / h->quality->mse : NAN;
            if (std::isfinite(ratio)) ratios[i].push_back(ratio);
            md << " " << fixed(cases[i]->quality->mse * 100.0, 4) << " | " << fixed(ratio, 2) << " |";
        }
        md << " " << fixed(h->quality->flip, 4) << " |";
        for (const CaseResult* c : cases) md << " " << (c ? fixed(c->quality->flip, 4) : kMissing) << " |";
        md << " " << ms(h->frameMs()) << " |";
        for (const CaseResult* c : cases) md << " " << (c ? ms(c->frameMs()) : kMissing) << " |";
        md << "\n";
    }
    md << "| **mean ratio** | |";
    for (const auto& v : ratios) md << " | " << (v.empty() ? std::string(kMissing) : fixed(meanOf(v), 2)) << " |";
    for (size_t i = 0; i < 2 * networks.size() + 2; ++i) md << " |";
    md << "\n\n";
}

void memoryTable(std::ostringstream& md, const Results& r) {
    md << "## GPU memory per method (MiB)\n\nEvery buffer and texture the method holds (scene geometry excluded).\n\n";
    auto mib = [](const CaseResult& c) { return c.stats.value("memory_bytes", 0.0) / (1024.0 * 1024.0); };
    sceneByVariantTable(md, r, [&](const CaseResult& c) { return fixed(mib(c), 1); });
    // What the memory is made of, from the first scene each variant ran on (the targets depend on
    // the resolution only; the A-buffer's pool also on the scene's fragments).
    md << "Per target, MiB (`memory_targets` of `--stats`; the first scene each variant ran on; targets of 0 bytes "
          "left out):\n\n| variant | scene | targets |\n|---|---|---|\n";
    for (const auto& v : r.plan.variants) {
        for (const auto& s : r.scenes) {
            const CaseResult* c = s.loaded ? s.find(v.name) : nullptr;
            if (!c || !c->ok || !c->stats.contains("memory_targets")) continue;
            std::vector<std::pair<double, std::string>> targets;
            for (const auto& [name, bytes] : c->stats["memory_targets"].items()) {
                const double b = bytes.get<double>();
                if (b > 0.0) targets.emplace_back(b, name);
            }
            std::sort(targets.begin(), targets.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
            md << "| " << v.name << " | " << sceneLabel(s) << " |";
            for (size_t i = 0; i < targets.size(); ++i) {
                md << (i ? ", " : " ") << targets[i].second << " " << fixed(targets[i].first / (1024.0 * 1024.0), 1);
            }
            md << " |\n";
            break;
        }
    }
    md << "\n";
}

void qTable(std::ostringstream& md, const Results& r) {
    md << "## Q metric (% per ms)\n\n"
          "The paper's Q with frame time standing in for energy per frame (no power counter here):\n"
          "`Q = (MSE_unsorted - MSE_method) / (frame_ms * MSE_unsorted) * 100`, the percentage of the unsorted "
          "blend's error removed per millisecond of frame time (higher is better).\n\n";
    sceneByVariantTable(
        md, r, [](const CaseResult& c) { return c.q ? fixed(*c.q, 3) : std::string(kMissing); }, [](const CaseResult& c) { return c.q; },
        [](double v) { return fixed(v, 3); });
}

void imagesSection(std::ostringstream& md, const Results& r) {
    md << "## Images and plots\n\n";
    if (r.plots.made) {
        for (const auto& f : r.plots.files) md << "![" << f << "](" << f << ")\n\n";
    } else {
        md << "Plots were skipped: " << r.plots.reason << "\n\n";
    }
    md << "| scene | method | image | FLIP map | tiles |\n|---|---|---|---|---|\n";
    auto link = [](const std::string& label, const std::string& path) { return path.empty() ? std::string(kMissing) : "[" + label + "](" + path + ")"; };
    for (const auto& s : r.scenes) {
        md << "| " << s.spec.name << " | ground truth (abuffer) | " << link("png", s.groundTruthImage) << " | | |\n";
        for (const auto& c : s.cases) {
            md << "| " << s.spec.name << " | " << c.variant << " | " << link("png", c.image) << " | " << link("png", c.flipMap) << " | "
               << link("png", c.tileOverlay) << " |\n";
        }
    }
    md << '\n';
}

void failuresSection(std::ostringstream& md, const Results& r) {
    md << "## Failures\n\n";
    if (r.failureCount() == 0) {
        md << "None.\n\n";
        return;
    }
    for (const auto& s : r.scenes) {
        if (!s.loaded) md << "- " << s.spec.name << ": scene not loaded: " << s.loadError << "\n";
        if (s.loaded && !s.groundTruthOk) md << "- " << s.spec.name << ": ground truth failed (no errors measured): " << s.groundTruthError << "\n";
        for (const auto& c : s.cases) {
            if (!c.ok) md << "- " << s.spec.name << " / " << c.variant << ": " << c.error << "\n";
        }
    }
    md << '\n';
}

void settingsSection(std::ostringstream& md, const Results& r) {
    md << "## Settings\n\n| method | base | spatial | scales | inference | temporal | what |\n|---|---|---|---|---|---|---|\n";
    for (const auto& v : r.plan.variants) {
        md << "| " << v.name << " | " << v.method << " | " << spatialText(v.options) << " | " << scalesText(v.options) << " | "
           << (v.options.neural.inference == NeuralOptions::Inference::Corners ? "corners" : "full") << " | " << temporalText(v.options)
           << " | " << v.description << " |\n";
    }
    md << "\n| scene | source | triangles | opaque triangles | alpha | alpha cut-off | note |\n|---|---|---|---|---|---|---|\n";
    for (const auto& s : r.scenes) {
        md << "| " << s.spec.name << " | " << s.spec.source << " | " << s.triangles << " | " << s.opaqueTriangles << " | "
           << (s.spec.alphaOverride ? fixed(*s.spec.alphaOverride, 2) : std::string("file")) << " | " << s.spec.alphaCutoff << " | "
           << (s.spec.note.empty() ? kMissing : s.spec.note) << " |\n";
    }
    md << '\n';
}

}  // namespace

std::string reportMarkdown(const Results& results) {
    std::ostringstream md;
    header(md, results);
    frameTimeTable(md, results);
    gpuEstimateTable(md, results);
    passBreakdownTable(md, results);
    scalesAndWorkTables(md, results);
    speedupTable(md, results);
    againstItselfTable(md, results);
    qualityTables(md, results);
    networkAddsTable(md, results);
    memoryTable(md, results);
    qTable(md, results);
    imagesSection(md, results);
    failuresSection(md, results);
    settingsSection(md, results);
    return md.str();
}

}  // namespace starnt::bench
