// Writes a finished bench run into its folder: results.json, results.csv, plots/ and report.md, in
// that order (the plot script reads results.json; report.md links the plots).
#pragma once
#include <string>

#include "bench/bench_results.hpp"

namespace starnt::bench {

// `python`: interpreter for the plots; empty skips them. Updates results.plots.
void writeBenchOutputs(Results& results, const std::string& outDir, const std::string& python);

}  // namespace starnt::bench
