// report.md: the paper's tables rebuilt from one bench run's figures (frame times, per-pass
// breakdown, speed-up over DFAOIT, MSE x10^2 and FLIP with the reduction against WBOIT, memory,
// Q), plus the settings, the machine and any failures.
#pragma once
#include <string>

#include "bench/bench_results.hpp"

namespace starnt::bench {

std::string reportMarkdown(const Results& results);

}  // namespace starnt::bench
