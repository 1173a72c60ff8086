// libFuzzer target: the network weights file (JSON), for either network kind.
#include "fuzz_input.hpp"
#include "starnt/tools/nn.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    starnt::fuzz::expectCleanOutcome([&] { starnt::nn::parseWeights(text, "fuzz input"); });
    return 0;
}
