// Runs a benchmark plan: for every scene, the A-buffer ground truth along the camera path, then
// every method variant along the same path, compared frame by frame with the ground truth. Images
// go to OUT/images/<scene>/; the figures come back as Results. A scene or method that fails is
// recorded with its error and the run goes on.
#pragma once
#include <cstdio>
#include <string>

#include "bench/bench_plan.hpp"
#include "bench/bench_results.hpp"

namespace starnt::bench {

// Needs no GL context (it creates its own). `progressOut` may be null (silent).
Results runBench(const Plan& plan, const std::string& outDir, std::FILE* progressOut);

// Frames of work in a plan (ground truth + every variant, every scene), for the progress estimate.
size_t totalFrames(const Plan& plan);

}  // namespace starnt::bench
