// libFuzzer target: the image readers `compare` uses. First byte: even = PNG, odd = EXR.
#include "fuzz_input.hpp"
#include "starnt/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const auto path = starnt::fuzz::writeFile(data[0] % 2 ? "image.exr" : "image.png", bytes);
    starnt::fuzz::expectCleanOutcome([&] { starnt::loadImage(path.string()); });
    return 0;
}
