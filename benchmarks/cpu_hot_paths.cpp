// Google Benchmark timings of the CPU hot paths: the metrics `starnt bench` runs on every frame of
// every method (MSE, FLIP), and the CPU references the tests and the trainer lean on (exact
// compositing, pass sums, network forward). Built when libbenchmark is installed; not run by ctest:
//   build/starnt_microbench [--benchmark_filter=Flip]
#include <benchmark/benchmark.h>

#include <random>

#include "starnt/tools/fragments.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"
#include "starnt/tools/nn.hpp"

namespace {

starnt::Image noiseImage(int width, int height, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    starnt::Image image(width, height, 1.0f);
    for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = i % 4 == 3 ? 1.0f : unit(rng);
    return image;
}

starnt::FragmentList randomFragments(int count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    starnt::FragmentList fragments(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        starnt::Fragment& f = fragments[static_cast<size_t>(i)];
        f.color = glm::vec3(unit(rng), unit(rng), unit(rng));
        f.alpha = 0.05f + 0.5f * unit(rng);
        f.depth = unit(rng);
        f.order = uint32_t(i);
    }
    return fragments;
}

// Width and height from the benchmark's arguments (the quick and paper preset sizes).
void BM_MseSrgb(benchmark::State& state) {
    const auto a = noiseImage(int(state.range(0)), int(state.range(1)), 1), b = noiseImage(int(state.range(0)), int(state.range(1)), 2);
    for (auto _ : state) benchmark::DoNotOptimize(starnt::mseSrgb(a, b));
    state.SetItemsProcessed(state.iterations() * int64_t(a.pixelCount()));
}
BENCHMARK(BM_MseSrgb)->Args({640, 360})->Args({1920, 1080})->Unit(benchmark::kMillisecond);

void BM_Flip(benchmark::State& state) {
    const auto a = noiseImage(int(state.range(0)), int(state.range(1)), 1), b = noiseImage(int(state.range(0)), int(state.range(1)), 2);
    for (auto _ : state) benchmark::DoNotOptimize(starnt::flip(a, b).mean);
    state.SetItemsProcessed(state.iterations() * int64_t(a.pixelCount()));
}
BENCHMARK(BM_Flip)->Args({640, 360})->Args({1920, 1080})->Unit(benchmark::kMillisecond);

// Sort + exact "over" of one pixel's list, for list lengths of the suite's depth complexities.
void BM_CompositeOverSorted(benchmark::State& state) {
    const auto fragments = randomFragments(int(state.range(0)), 3);
    for (auto _ : state) {
        starnt::FragmentList list = fragments;
        starnt::sortByDepth(list);
        benchmark::DoNotOptimize(starnt::compositeOver(list, glm::vec3(1.0f)));
    }
}
BENCHMARK(BM_CompositeOverSorted)->Arg(8)->Arg(64)->Arg(136);

void BM_PassSums(benchmark::State& state) {
    const auto fragments = randomFragments(int(state.range(0)), 4);
    for (auto _ : state) benchmark::DoNotOptimize(starnt::nn::sumsFromFragments(fragments));
}
BENCHMARK(BM_PassSums)->Arg(8)->Arg(64)->Arg(136);

void BM_StarntComposite(benchmark::State& state) {
    const starnt::nn::Network net = starnt::nn::makeUntrained(starnt::nn::NetworkKind::StarNT, 1);
    const starnt::nn::PixelSums sums = starnt::nn::sumsFromFragments(randomFragments(32, 5));
    for (auto _ : state) benchmark::DoNotOptimize(starnt::nn::compositeStarnt(net, sums, glm::vec3(1.0f)));
}
BENCHMARK(BM_StarntComposite);

}  // namespace

BENCHMARK_MAIN();
