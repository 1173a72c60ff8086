// The scenes the viewer offers in its scene list: the built-ins and every glTF/OBJ file under a
// scenes folder (../shared/scenes by default).
#pragma once
#include <string>
#include <vector>

namespace starnt::viewer {

struct SceneEntry {
    std::string label;  // shown in the list, e.g. "builtin:tubes" or "chess/chess_classic_board.glb"
    std::string spec;   // what loadScene takes
};

// Built-ins first, then the files under `folder` sorted by path (nothing when the folder is
// missing or empty).
std::vector<SceneEntry> listScenes(const std::string& folder);

// The folder to list when none is given: $STARNT_SCENES_DIR, else ../shared/scenes from the
// working directory, else ../shared/scenes beside the source tree; empty when none exists.
std::string defaultScenesFolder();

}  // namespace starnt::viewer
