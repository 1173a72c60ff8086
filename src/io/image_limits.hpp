// The decode budget of loadImage, for the image fuzz target only (fuzz/fuzz_image.cpp).
//
// loadImage accepts up to kMaxImagePixels (starnt/tools/image.hpp) and checks a file's declared size
// before decoding. A fuzzer mutating headers mostly produces images that declare millions of
// pixels; decoding each under AddressSanitizer costs tens of milliseconds (56 inputs/s measured),
// so a million inputs would take hours. The fuzz target lowers the budget so such inputs stop at
// the same size check (which stays fuzzed) while small ones exercise the decoders.
#pragma once

namespace starnt::detail {

// Largest pixel count loadImage decodes; starts at kMaxImagePixels. Not thread-safe: set it once
// before loading.
void setImagePixelBudget(long long pixels);

}  // namespace starnt::detail
