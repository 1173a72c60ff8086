// Links against the runtime alone (pkg-config `starnt`, or starnt::oit from a parent project) and
// checks that the method list and the public contract are there without a GL context.
#include <cstdio>
#include <string>

#include "starnt/bindings.h"
#include "starnt/oit_method.hpp"

int main() {
    const auto names = starnt::methodNames();
    bool hasStarnt = false;
    for (const auto& n : names) hasStarnt = hasStarnt || n == "starnt";
    std::printf("%zu methods; engine texture units from %d\n", names.size(), STARNT_ENGINE_FIRST_TEXTURE_UNIT);
    try {
        starnt::checkGlRequirements();  // no context is current here
        std::fprintf(stderr, "checkGlRequirements accepted a thread without a context\n");
        return 1;
    } catch (const starnt::Error& e) {
        std::printf("without a context: %s\n", e.what());
    }
    return hasStarnt ? 0 : 1;
}
