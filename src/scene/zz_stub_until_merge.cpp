// TEMPORARY: replaced by the scene layer from branch wip-scenes.
#include <random>
#include "starnt/error.hpp"
#include "starnt/scene.hpp"
namespace starnt {
Bounds Scene::bounds() const {
    Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (auto& m : meshes) for (auto& p : m.positions) { b.min = glm::min(b.min, p); b.max = glm::max(b.max, p); }
    return b;
}
size_t Scene::triangleCount() const { size_t n = 0; for (auto& m : meshes) n += m.indices.size() / 3; return n; }
size_t Scene::vertexCount() const { size_t n = 0; for (auto& m : meshes) n += m.positions.size(); return n; }
Scene makeBuiltinScene(const std::string& name, uint32_t seed) {
    Scene s; s.name = name;
    Material mat; mat.unlit = true; s.materials.push_back(mat);
    Mesh m;
    std::mt19937 rng(seed);
    auto u = [&] { return float(rng() >> 8) / float(1 << 24); };
    int n = name == "panes" ? 5 : 60;
    for (int i = 0; i < n; ++i) {
        glm::vec4 c(u(), u(), u(), 0.2f + 0.6f * u());
        for (int k = 0; k < 3; ++k) { m.positions.push_back(glm::vec3(u(), u(), u()) * 2.0f - 1.0f); m.colors.push_back(c); m.indices.push_back(uint32_t(m.indices.size())); }
    }
    s.meshes.push_back(m);
    return s;
}
std::vector<std::string> builtinSceneNames() { return {"panes", "random"}; }
Scene loadScene(const std::string& spec) { return makeBuiltinScene(spec.substr(8), 1); }
}
