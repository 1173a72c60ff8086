// libFuzzer target: the OBJ loader and its MTL file. The input is "OBJ text\n#@mtl\nMTL text"; the
// OBJ can name the MTL as `mtllib m.mtl`.
#include "fuzz_input.hpp"
#include "starnt/tools/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto [obj, mtl] = starnt::fuzz::split({reinterpret_cast<const char*>(data), size}, "\n#@mtl\n");
    starnt::fuzz::writeFile("m.mtl", mtl);
    const auto path = starnt::fuzz::writeFile("scene.obj", obj);
    starnt::fuzz::expectCleanOutcome([&] { starnt::loadObj(path.string()); });
    return 0;
}
