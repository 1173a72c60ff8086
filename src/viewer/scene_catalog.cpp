#include "viewer/scene_catalog.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "starnt/tools/scene.hpp"

namespace fs = std::filesystem;

namespace starnt::viewer {
namespace {

bool isSceneFile(const fs::path& p) {
    std::string ext = p.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb" || ext == ".obj";
}

}  // namespace

std::vector<SceneEntry> listScenes(const std::string& folder) {
    std::vector<SceneEntry> entries;
    for (const auto& name : builtinSceneNames()) entries.push_back({"builtin:" + name, "builtin:" + name});
    std::error_code ec;
    if (folder.empty() || !fs::is_directory(folder, ec)) return entries;
    std::vector<SceneEntry> files;
    // A scene folder the user cannot fully read still lists what it can.
    for (auto it = fs::recursive_directory_iterator(folder, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_regular_file(ec) && isSceneFile(it->path())) {
            files.push_back({fs::relative(it->path(), folder, ec).generic_string(), it->path().string()});
        }
    }
    std::sort(files.begin(), files.end(), [](const SceneEntry& a, const SceneEntry& b) { return a.label < b.label; });
    entries.insert(entries.end(), files.begin(), files.end());
    return entries;
}

std::string defaultScenesFolder() {
    std::error_code ec;
    if (const char* env = std::getenv("STARNT_SCENES_DIR"); env && *env) return env;
    if (fs::is_directory("../shared/scenes", ec)) return fs::absolute("../shared/scenes").lexically_normal().string();
#ifdef STARNT_SOURCE_DIR
    const fs::path besideSource = fs::path(STARNT_SOURCE_DIR) / ".." / "shared" / "scenes";
    if (fs::is_directory(besideSource, ec)) return besideSource.lexically_normal().string();
#endif
    return "";
}

}  // namespace starnt::viewer
