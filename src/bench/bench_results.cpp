#include "bench/bench_results.hpp"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "render/option_text.hpp"

namespace starnt::bench {
namespace {

using nlohmann::json;

json optionalNumber(const std::optional<double>& v) { return v ? json(*v) : json(nullptr); }

// Percent by which `value` is below `baseline` (positive = better / faster).
std::optional<double> reductionPercent(double baseline, double value) {
    if (!(baseline > 0.0) || !std::isfinite(value)) return std::nullopt;
    return (baseline - value) / baseline * 100.0;
}

json variantJson(const Variant& v) {
    return {{"name", v.name},
            {"method", v.method},
            {"description", v.description},
            {"spatial", v.options.neural.spatial ? json(*v.options.neural.spatial) : json(nullptr)},
            {"scales", scalesText(v.options)},
            {"inference", v.options.neural.inference == NeuralOptions::Inference::Corners ? "corners" : "full"},
            {"temporal", temporalText(v.options)},
            // The variant its saving is measured against (report.md, "Against itself"), or null.
            {"acceleration_off", v.accelerationOff.empty() ? json(nullptr) : json(v.accelerationOff)},
            {"acceleration", v.acceleration.empty() ? json(nullptr) : json(v.acceleration)}};
}

json sceneSpecJson(const SceneSpec& s) {
    return {{"name", s.name},
            {"source", s.source},
            {"alpha_override", s.alphaOverride ? json(*s.alphaOverride) : json(nullptr)},
            {"alpha_cutoff", s.alphaCutoff},
            {"paper_depth_complexity", s.paperDepth ? json(s.paperDepth) : json(nullptr)},
            {"settings_note", s.note}};
}

json caseJson(const CaseResult& c) {
    json j = {{"variant", c.variant},
              {"method", c.method},
              {"status", c.ok ? "ok" : "failed"},
              {"error", c.ok ? json(nullptr) : json(c.error)},
              {"wall_seconds", c.wallSeconds},
              {"stats", c.stats},
              {"frames", c.frames},
              {"images", {{"image", c.image}, {"flip_map", c.flipMap}, {"tile_overlay", c.tileOverlay}}}};
    if (c.quality) {
        j["quality"] = {{"mse", c.quality->mse},
                        {"mse_x100", c.quality->mse * 100.0},
                        {"flip", c.quality->flip},
                        {"by_frame_kind", c.quality->byFrameKind},
                        {"last_frame_png", {{"mse", c.quality->pngMse}, {"flip", c.quality->pngFlip}}}};
    } else {
        j["quality"] = nullptr;
        j["quality_missing_reason"] = c.qualityMissingReason;
    }
    j["q_percent_per_ms"] = optionalNumber(c.q);
    j["mse_reduction_vs_wboit_percent"] = optionalNumber(c.mseReductionVsWboit);
    j["flip_reduction_vs_wboit_percent"] = optionalNumber(c.flipReductionVsWboit);
    j["speedup_vs_dfaoit_percent"] = optionalNumber(c.speedupVsDfaoit);
    return j;
}

std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return quoted + "\"";
}

std::string csvNumber(const std::optional<double>& v) {
    if (!v || !std::isfinite(*v)) return "";
    std::ostringstream out;
    out.precision(10);
    out << *v;
    return out.str();
}

std::optional<double> statNumber(const json& stats, const char* key) {
    if (!stats.contains(key) || !stats[key].is_number()) return std::nullopt;
    return stats[key].get<double>();
}

}  // namespace

double CaseResult::frameMs() const {
    // One statistic for every variant, table and plots alike: the cost per displayed frame over a
    // long run. Interpolated frames and guard probe frames make periodic sequences, so a median would
    // report one kind of frame only; and a short window's plain mean counts the real frames of a
    // temporal schedule at a share set by its phase (render/long_run_frame_time.hpp), so each kind's
    // mean is weighted by its share in the schedule. The same as the window mean without temporal frames.
    auto v = statNumber(stats, "frame_ms_long_run");
    if (!v) v = statNumber(stats, "frame_ms_mean");  // results written before the long-run mean
    return v ? *v : std::numeric_limits<double>::quiet_NaN();
}

std::optional<double> CaseResult::gpuFrameMs() const {
    auto v = statNumber(stats, "frame_gpu_ms_long_run");
    return v ? v : statNumber(stats, "frame_gpu_ms_mean");  // results written before the long-run mean
}

double CaseResult::windowFrameMs() const {
    auto v = statNumber(stats, "frame_ms_mean");
    return v ? *v : std::numeric_limits<double>::quiet_NaN();
}

const CaseResult* SceneResult::find(const std::string& variant) const {
    for (const auto& c : cases) {
        if (c.variant == variant) return &c;
    }
    return nullptr;
}

size_t Results::failureCount() const {
    size_t n = 0;
    for (const auto& s : scenes) {
        if (!s.loaded) ++n;
        if (s.loaded && !s.groundTruthOk) ++n;
        for (const auto& c : s.cases) n += c.ok ? 0 : 1;
    }
    return n;
}

std::optional<double> qMetric(double mseUnsorted, double mseMethod, double frameMs) {
    if (!(mseUnsorted > 0.0) || !(frameMs > 0.0) || !std::isfinite(mseMethod)) return std::nullopt;
    return (mseUnsorted - mseMethod) / (frameMs * mseUnsorted) * 100.0;
}

void computeDerivedFigures(Results& results) {
    for (auto& scene : results.scenes) {
        const CaseResult* unsorted = scene.find("unsorted");
        const CaseResult* wboit = scene.find("wboit");
        const CaseResult* dfaoit = scene.find("dfaoit");
        const bool haveUnsorted = unsorted && unsorted->ok && unsorted->quality;
        const bool haveWboit = wboit && wboit->ok && wboit->quality;
        const bool haveDfaoit = dfaoit && dfaoit->ok;
        for (auto& c : scene.cases) {
            c.q.reset();
            c.mseReductionVsWboit.reset();
            c.flipReductionVsWboit.reset();
            c.speedupVsDfaoit.reset();
            if (!c.ok) continue;
            if (haveDfaoit) c.speedupVsDfaoit = reductionPercent(dfaoit->frameMs(), c.frameMs());
            if (!c.quality) continue;
            if (haveUnsorted) c.q = qMetric(unsorted->quality->mse, c.quality->mse, c.frameMs());
            if (haveWboit) {
                c.mseReductionVsWboit = reductionPercent(wboit->quality->mse, c.quality->mse);
                c.flipReductionVsWboit = reductionPercent(wboit->quality->flip, c.quality->flip);
            }
        }
    }
}

json toJson(const Results& r) {
    json variants = json::array();
    for (const auto& v : r.plan.variants) variants.push_back(variantJson(v));
    json scenes = json::array();
    for (const auto& s : r.scenes) {
        json cases = json::array();
        for (const auto& c : s.cases) cases.push_back(caseJson(c));
        scenes.push_back({{"scene", sceneSpecJson(s.spec)},
                          {"status", !s.loaded ? "failed" : "ok"},
                          {"error", s.loaded ? json(nullptr) : json(s.loadError)},
                          {"triangles", s.triangles},
                          {"opaque_triangles", s.opaqueTriangles},
                          {"max_fragments", s.maxFragments},
                          {"ground_truth",
                           {{"method", "abuffer"},
                            {"status", s.groundTruthOk ? "ok" : "failed"},
                            {"error", s.groundTruthOk ? json(nullptr) : json(s.groundTruthError)},
                            {"image", s.groundTruthImage},
                            {"stats", s.groundTruthStats}}},
                          {"methods", cases}});
    }
    return {
        {"format", "starnt-bench"},
        {"format_version", 1},
        {"date", r.date},
        {"command_line", r.commandLine},
        {"machine", toJson(r.machine)},
        {"settings",
         {{"preset", r.plan.preset},
          {"width", r.plan.width},
          {"height", r.plan.height},
          {"frames", r.plan.frames},
          {"camera_path", r.plan.cameraPath},
          {"suite_dir", r.plan.suiteDir.empty() ? json(nullptr) : json(r.plan.suiteDir)},
          {"scene_source", r.plan.suiteNote},
          {"ground_truth", "abuffer, same cameras, every frame"},
          {"abuffer_memory_cap_bytes", r.plan.abufferCapBytes},
          {"api", glApiName(r.plan.api)},
          {"timing", "mean over the timed frames, after untimed warm-up frames, in a run of the path without readbacks "
                     "or error measurement between frames (frame_ms_mean_with_comparison: the run that measured the "
                     "errors); glFinish + wall clock per frame; with timing_rounds > 1 the fastest of that many such runs "
                     "(frame_ms_rounds), the variants timed in alternating order"},
          {"timing_rounds", r.plan.timingRounds},
          {"quality", "mean over every compared frame (every frame, or those with i mod quality_every < 3) of MSE (sRGB) "
                      "and LDR-FLIP mean (67.02 px/deg) against the ground truth"},
          {"quality_every", r.plan.qualityEvery},
          {"q_metric", "Q = (MSE_unsorted - MSE_method) / (frame_ms * MSE_unsorted) * 100, % per ms"}}},
        {"variants", variants},
        {"scenes", scenes},
        {"plots", {{"made", r.plots.made}, {"reason", r.plots.reason}, {"files", r.plots.files}}},
        {"failures", r.failureCount()},
        {"wall_seconds", r.wallSeconds},
    };
}

std::string toCsv(const Results& r) {
    // Pass columns: the union of pass names over every case, so one file holds every method.
    // Geometry-pass columns likewise: fragments a frame (pass_counters) and what a fragment writes
    // (pass_blend of the real frames): what scripts/fit_gpu_estimate.py fits a GPU's pass times to.
    std::set<std::string> passNames, geometryNames;
    for (const auto& s : r.scenes) {
        for (const auto& c : s.cases) {
            if (c.stats.contains("pass_ms")) {
                for (auto& [name, value] : c.stats["pass_ms"].items()) passNames.insert(name);
            }
            for (const char* key : {"pass_counters", "pass_blend"}) {
                if (!c.stats.contains(key)) continue;
                for (auto& [name, value] : c.stats[key].items()) geometryNames.insert(name);
            }
        }
    }
    auto nested = [](const json& st, const char* group, const std::string& pass, const char* key) -> std::optional<double> {
        if (!st.contains(group) || !st[group].contains(pass) || !st[group][pass].contains(key)) return std::nullopt;
        return st[group][pass][key].get<double>();
    };
    std::ostringstream out;
    out << "scene,variant,method,status,width,height,frames,frame_ms_mean,real_frame_ms,interpolated_frame_ms,frame_ms_long_run";
    for (const auto& p : passNames) out << ",pass_" << p << "_ms";
    out << ",gpu_estimate_ms_long_run";
    for (const auto& p : geometryNames) {
        out << ",pass_" << p << "_fragments,blend_" << p << "_bytes,blend_" << p << "_float32_bytes,blend_" << p << "_bits_per_pixel";
    }
    out << ",scale_pass2,scale_pass3,max_fragments,memory_bytes,mse,mse_x100,flip,last_png_mse,last_png_flip,"
           "mse_reduction_vs_wboit_percent,flip_reduction_vs_wboit_percent,speedup_vs_dfaoit_percent,q_percent_per_ms,error\n";
    for (const auto& s : r.scenes) {
        for (const auto& c : s.cases) {
            const json& st = c.stats;
            out << csvField(s.spec.name) << ',' << c.variant << ',' << c.method << ',' << (c.ok ? "ok" : "failed") << ','
                << r.plan.width << ',' << r.plan.height << ',' << r.plan.frames << ',' << csvNumber(statNumber(st, "frame_ms_mean"))
                << ',' << csvNumber(statNumber(st, "real_frame_ms")) << ',' << csvNumber(statNumber(st, "interpolated_frame_ms"))
                << ',' << csvNumber(statNumber(st, "frame_ms_long_run"));
            for (const auto& p : passNames) {
                std::optional<double> v;
                if (st.contains("pass_ms") && st["pass_ms"].contains(p)) v = st["pass_ms"][p].get<double>();
                out << ',' << csvNumber(v);
            }
            out << ',' << csvNumber(statNumber(st, "gpu_estimate_ms_long_run"));
            for (const auto& p : geometryNames) {
                std::optional<double> bytes;
                if (st.contains("pass_blend") && st["pass_blend"].contains(p)) {
                    bytes = 0.0;
                    for (auto& [cls, value] : st["pass_blend"][p].items()) {
                        if (cls != "target_bits_per_pixel") *bytes += value.get<double>();
                    }
                }
                out << ',' << csvNumber(nested(st, "pass_counters", p, "fragment_invocations")) << ',' << csvNumber(bytes) << ','
                    << csvNumber(nested(st, "pass_blend", p, "float32")) << ','
                    << csvNumber(nested(st, "pass_blend", p, "target_bits_per_pixel"));
            }
            out << ',' << csvNumber(statNumber(st, "scale_pass2")) << ',' << csvNumber(statNumber(st, "scale_pass3")) << ','
                << csvNumber(statNumber(st, "max_fragments")) << ',' << csvNumber(statNumber(st, "memory_bytes"));
            const auto& q = c.quality;
            out << ',' << csvNumber(q ? std::optional(q->mse) : std::nullopt) << ','
                << csvNumber(q ? std::optional(q->mse * 100.0) : std::nullopt) << ','
                << csvNumber(q ? std::optional(q->flip) : std::nullopt) << ','
                << csvNumber(q ? std::optional(q->pngMse) : std::nullopt) << ','
                << csvNumber(q ? std::optional(q->pngFlip) : std::nullopt) << ',' << csvNumber(c.mseReductionVsWboit) << ','
                << csvNumber(c.flipReductionVsWboit) << ',' << csvNumber(c.speedupVsDfaoit) << ',' << csvNumber(c.q) << ','
                << csvField(c.ok ? c.qualityMissingReason : c.error) << '\n';
        }
    }
    return out.str();
}

}  // namespace starnt::bench
