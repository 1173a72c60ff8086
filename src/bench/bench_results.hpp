// The figures one `starnt bench` run produces, and their files: results.json (everything),
// results.csv (one row per scene and method). report.md is written by bench_report.hpp.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_plan.hpp"
#include "bench/machine_info.hpp"

namespace starnt::bench {

// Error of a method against the ground truth.
struct Quality {
    double mse = 0.0;   // mean over every frame of the path (sRGB MSE, docs/DESIGN.md, "Benchmark")
    double flip = 0.0;  // mean over every frame of the path (LDR-FLIP mean)
    // The last frame as written to PNG and read back: exactly what `starnt compare` computes on the
    // files in images/ (8-bit sRGB quantisation included).
    double pngMse = 0.0, pngFlip = 0.0;
    nlohmann::json byFrameKind;  // renderScene's error {real, interpolated}
};

// One method (variant) on one scene.
struct CaseResult {
    std::string variant, method;
    bool ok = false;
    std::string error;            // why it failed (ok == false)
    nlohmann::json stats;         // renderScene statistics (frame_ms, pass_ms, memory_bytes, ...)
    nlohmann::json frames;        // per-frame records: frame_ms, interpolated, mse, flip, scales
    std::optional<Quality> quality;    // absent when the method or the ground truth failed
    std::string qualityMissingReason;  // set when quality is absent but the method ran
    double wallSeconds = 0.0;     // rendering + metrics, for the record
    // Files, relative to the output folder ("" when not written).
    std::string image, flipMap, tileOverlay;
    // Derived figures (computeDerivedFigures); absent when an input is missing.
    std::optional<double> q;                      // % MSE improvement over unsorted per ms of frame time
    std::optional<double> mseReductionVsWboit;    // percent, positive = lower error than wboit
    std::optional<double> flipReductionVsWboit;   // percent
    std::optional<double> speedupVsDfaoit;        // percent of frame time saved against dfaoit
    double frameMs() const;                       // stats.frame_ms_long_run (the compared time), NaN when absent
    double windowFrameMs() const;                 // stats.frame_ms_mean: the plain mean of the timed frames
    std::optional<double> gpuFrameMs() const;     // the same long-run time from GL_TIMESTAMP pairs; empty off a GPU
};

struct SceneResult {
    SceneSpec spec;
    bool loaded = false;
    std::string loadError;
    size_t triangles = 0;
    // Triangles drawn first into the opaque colour and depth the methods clip against (OPAQUE and MASK
    // materials; 0 under an alpha override, which makes every material BLEND).
    size_t opaqueTriangles = 0;
    unsigned maxFragments = 0;  // D at the last camera, from the ground-truth render
    bool groundTruthOk = false;
    std::string groundTruthError;
    nlohmann::json groundTruthStats;
    std::string groundTruthImage;  // relative to the output folder
    std::vector<CaseResult> cases;

    const CaseResult* find(const std::string& variant) const;
};

struct PlotsStatus {
    bool made = false;
    std::string reason;  // why not, or which interpreter made them
    std::vector<std::string> files;
};

struct Results {
    Plan plan;
    MachineInfo machine;
    std::string date;  // ISO-8601 UTC, start of the run
    std::string commandLine;
    double wallSeconds = 0.0;
    std::vector<SceneResult> scenes;
    PlotsStatus plots;

    size_t failureCount() const;  // failed scene loads, ground truths and cases
};

// Fills the derived figures of every case (Q, reductions against wboit, speed-up against dfaoit).
void computeDerivedFigures(Results& results);

// Q with frame time standing in for energy (the paper's eq. for Q; see docs/DESIGN.md):
//   Q = (E_unsorted - E_method) / (frame_ms * E_unsorted) * 100, in % per ms.
// Absent when E_unsorted is zero or any input is missing.
std::optional<double> qMetric(double mseUnsorted, double mseMethod, double frameMs);

nlohmann::json toJson(const Results& results);
std::string toCsv(const Results& results);

}  // namespace starnt::bench
