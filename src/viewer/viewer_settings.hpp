// Everything the user can switch live in the viewer, as one value: the UI edits it, scripted input
// and the command line set it through set() with the same spellings as `starnt render`.
#pragma once
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "starnt/oit_method.hpp"

namespace starnt::viewer {

enum class ViewMode { Final, Tiles, Error };
const char* viewModeName(ViewMode mode);

struct ViewerSettings {
    std::string method = "recommended";  // docs/INTEGRATION.md, "Choosing a method"
    std::string splitMethod;  // empty: no split screen; else this method on the right half
    ViewMode view = ViewMode::Final;
    MethodOptions options;             // acceleration options (the other fields stay default)
    std::optional<float> alpha;        // global alpha override
    glm::vec3 background{1.0f};        // linear

    // Keys: method, split (NAME|off), view (final|tiles|error), alpha (A|off), background (R,G,B),
    // spatial, scales, inference, temporal, target-fps (as `starnt render`). Throws starnt::Error
    // naming the key on a bad value; leaves the settings unchanged then.
    void set(const std::string& key, const std::string& value);
    static bool isKey(const std::string& key);
};

// True when switching from `a` to `b` needs new method objects (the method or its options
// changed); alpha, background and the view are per-frame inputs and do not.
bool needsNewMethods(const ViewerSettings& a, const ViewerSettings& b);

}  // namespace starnt::viewer
