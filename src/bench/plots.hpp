// Runs the embedded plotting script (bench_plots.py, matplotlib) on a bench's results.json. Plots are
// optional: without Python or matplotlib the bench writes everything else and records why.
#pragma once
#include <string>

#include "bench/bench_results.hpp"

namespace starnt::bench {

// Writes the script to OUT/plots/bench_plots.py (so plots can be redrawn by hand) and runs it with
// `python` on OUT/results.json. Never throws for a missing interpreter or library.
PlotsStatus makePlots(const std::string& outDir, const std::string& python);

}  // namespace starnt::bench
