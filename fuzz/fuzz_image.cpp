// libFuzzer target: the image readers `compare` uses. First byte: even = PNG, odd = EXR.
// The decode budget is 256x256 pixels (io/image_limits.hpp): larger declared sizes stop at the
// size check, which is what loadImage does above kMaxImagePixels, and the fuzzer spends its time
// in the decoders instead of in allocating and filling huge images (56 inputs/s -> see the log).
#include "io/image_limits.hpp"
#include "fuzz_input.hpp"
#include "starnt/tools/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const bool budgetSet = [] {
        starnt::detail::setImagePixelBudget(256 * 256);
        return true;
    }();
    (void)budgetSet;
    if (size < 1) return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const auto path = starnt::fuzz::writeFile(data[0] % 2 ? "image.exr" : "image.png", bytes);
    starnt::fuzz::expectCleanOutcome([&] { starnt::loadImage(path.string()); });
    return 0;
}
