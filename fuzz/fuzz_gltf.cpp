// libFuzzer target: the glTF 2.0 loader, binary (GLB) and text (.gltf with data: URIs, or buffers
// and images next to it in the work folder). First byte: even = .glb, odd = .gltf.
#include "fuzz_input.hpp"
#include "starnt/tools/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const std::string_view bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
    const auto path = starnt::fuzz::writeFile(data[0] % 2 ? "scene.gltf" : "scene.glb", bytes);
    starnt::fuzz::expectCleanOutcome([&] { starnt::loadGltf(path.string()); });
    return 0;
}
