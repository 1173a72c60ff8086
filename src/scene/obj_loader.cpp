// Wavefront OBJ loader on top of tinyobjloader (polygons triangulated as fans). One Scene mesh per
// (shape, material). Texture coordinates are converted to the glTF convention used by Scene
// (v = 0 at the first/top row of the image), i.e. v' = 1 - v.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <set>
#include <sstream>
#include <unordered_map>

#include <stb_image.h>
#include <tiny_obj_loader.h>

#include "scene/scene_internal.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt {

namespace {

// Light grey, opaque, lit, double-sided: used when the OBJ has no (valid) material.
Material defaultObjMaterial() {
    Material m;
    m.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    m.alphaMode = AlphaMode::Blend;
    m.doubleSided = true;
    return m;
}

int loadObjTexture(Scene& scene, std::map<std::string, int>& cache, const std::filesystem::path& file,
                   const std::string& at) {
    const std::string key = file.string();
    if (auto it = cache.find(key); it != cache.end()) return it->second;
    std::error_code ec;
    int result = -1;
    if (!std::filesystem::is_regular_file(file, ec)) {
        detail::warn(at + ": texture '" + key + "' not found; material has no texture");
    } else {
        int w = 0, h = 0, comp = 0;
        stbi_uc* pixels = stbi_load(key.c_str(), &w, &h, &comp, 4);
        if (pixels == nullptr)
            throw Error(at + ": cannot decode texture '" + key + "': " +
                        (stbi_failure_reason() ? stbi_failure_reason() : "unknown error"));
        try {
            scene.textures.push_back(detail::toRgba8(pixels, size_t(w) * size_t(h) * 4, w, h, 4, 8, at));
        } catch (...) {
            stbi_image_free(pixels);
            throw;
        }
        stbi_image_free(pixels);
        result = int(scene.textures.size()) - 1;
    }
    cache[key] = result;
    return result;
}

// tinyobjloader reads a number it cannot parse ("nan", "1.2.3", "abc") as 0 and does not say so,
// and keeps relative face indices that reach before the first vertex. This pass reads the text
// once more and rejects such lines, naming file, line and value: every number on v/vt/vn lines (and
// the colour and opacity lines of the MTL files) must parse completely and be finite, positions
// within |x| <= kMaxSceneCoordinate, and face indices must be non-zero and not reach before vertex 1.
std::string lineLabel(const std::string& path, size_t line) { return path + ":" + std::to_string(line); }

double parseNumber(const std::string& token, const std::string& at, const std::string& what) {
    const char* begin = token.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (end == begin || *end != '\0') throw Error(at + ": " + what + " '" + token + "' is not a number");
    if (!std::isfinite(v) || (errno == ERANGE && std::fabs(v) > 1.0))
        throw Error(at + ": " + what + " '" + token + "' is not a finite number");
    return v;
}

void checkMtlNumbers(const std::filesystem::path& file) {
    std::ifstream in(file);
    if (!in) return;  // tinyobjloader reports missing material libraries as a warning
    std::string line;
    size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        std::istringstream words(line);
        std::string key;
        if (!(words >> key)) continue;
        static const std::set<std::string> numeric = {"Ka", "Kd", "Ks", "Ke", "Tf", "d", "Tr", "Ns", "Ni"};
        if (!numeric.count(key)) continue;
        std::string token;
        while (words >> token) {
            if (token == "spectral" || token == "xyz") break;  // other Tf/Kd forms: left to tinyobjloader
            parseNumber(token, lineLabel(file.string(), number), key + " value");
        }
    }
}

// Returns the number of triangles the faces make (an n-gon makes n - 2).
size_t checkObjText(const std::string& path, const std::filesystem::path& dir) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open OBJ file");
    std::string line;
    size_t number = 0;
    long long vertices = 0, texcoords = 0, normals = 0;
    std::set<std::string> libraries;
    size_t triangles = 0;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        std::string key;
        if (!(words >> key)) continue;
        if (key == "v" || key == "vt" || key == "vn") {
            const std::string at = lineLabel(path, number);
            std::string token;
            int column = 0;
            while (words >> token) {
                if (token[0] == '#') break;
                const double v = parseNumber(token, at, key + " coordinate");
                if (key == "v" && column < 3 && std::fabs(v) > kMaxSceneCoordinate)
                    throw Error(at + ": vertex " + std::to_string(vertices + 1) + " coordinate " + token +
                                " is beyond the supported range (|x| <= 1e18)");
                ++column;
            }
            (key == "v" ? vertices : key == "vt" ? texcoords : normals) += 1;
        } else if (key == "f") {
            const std::string at = lineLabel(path, number);
            std::string token;
            size_t corners = 0;
            while (words >> token) {
                if (token[0] == '#') break;
                ++corners;
                // v, v/vt, v//vn or v/vt/vn
                size_t start = 0;
                for (int part = 0; part < 3 && start <= token.size(); ++part) {
                    const size_t slash = token.find('/', start);
                    const std::string field = token.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
                    if (!field.empty()) {
                        char* end = nullptr;
                        errno = 0;
                        const long long idx = std::strtoll(field.c_str(), &end, 10);
                        const char* kinds[3] = {"vertex", "texture coordinate", "normal"};
                        const char* plural[3] = {"vertices", "texture coordinates", "normals"};
                        const long long defined = part == 0 ? vertices : part == 1 ? texcoords : normals;
                        if (*end != '\0' || idx == 0)
                            throw Error(at + ": face " + kinds[part] + " index '" + field + "' in '" + token +
                                        "' is not a valid index (1-based, or negative for relative)");
                        // Compared without negating idx: strtoll saturates a huge index at LLONG_MIN,
                        // whose negation overflows (found by fuzz/fuzz_obj).
                        if (errno == ERANGE || (idx < 0 && idx < -defined))
                            throw Error(at + ": face " + kinds[part] + " index " + field + " is out of range: only " +
                                        std::to_string(defined) + " " + (defined == 1 ? kinds[part] : plural[part]) +
                                        " are defined before this line");
                    }
                    if (slash == std::string::npos) break;
                    start = slash + 1;
                }
            }
            if (corners >= 3) triangles += corners - 2;
        } else if (key == "mtllib") {
            std::string name;
            while (words >> name) libraries.insert(name);
        }
    }
    for (const std::string& lib : libraries) checkMtlNumbers(dir / lib);
    return triangles;
}

struct VertexKey {
    int v, vt, vn;
    bool operator==(const VertexKey& o) const { return v == o.v && vt == o.vt && vn == o.vn; }
};
struct VertexKeyHash {
    size_t operator()(const VertexKey& k) const {
        return (size_t(uint32_t(k.v)) * 73856093u) ^ (size_t(uint32_t(k.vt)) * 19349663u) ^
               (size_t(uint32_t(k.vn)) * 83492791u);
    }
};

}  // namespace

namespace {
Scene loadCheckedObj(const std::string& path, const std::filesystem::path& dir);
}

Scene loadObj(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": file not found");
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    const size_t triangles = checkObjText(path, dir);
    try {
        return loadCheckedObj(path, dir);
    } catch (const std::bad_alloc&) {
        throw Error(path + ": out of memory while loading the scene (" + std::to_string(triangles) +
                    " triangles in its faces): the scene is too large for this machine");
    }
}

namespace {

Scene loadCheckedObj(const std::string& path, const std::filesystem::path& dir) {

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = true;
    config.mtl_search_path = dir.string();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(path, config)) {
        std::string msg = reader.Error();
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
        for (char& c : msg)
            if (c == '\n') c = ';';
        throw Error(path + ": cannot parse OBJ: " + (msg.empty() ? "unknown tinyobjloader error" : msg));
    }
    if (!reader.Warning().empty()) {
        std::string msg = reader.Warning();
        while (!msg.empty() && msg.back() == '\n') msg.pop_back();
        for (char& c : msg)
            if (c == '\n') c = ';';
        detail::warn(path + ": " + msg);
    }

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const auto& shapes = reader.GetShapes();
    const auto& objMaterials = reader.GetMaterials();
    const int nv = int(attrib.vertices.size() / 3);
    const int nvt = int(attrib.texcoords.size() / 2);
    const int nvn = int(attrib.normals.size() / 3);
    // tinyobjloader fills missing vertex colours with 1: the file has colours iff any differs.
    bool hasColors = attrib.colors.size() == attrib.vertices.size();
    if (hasColors) {
        hasColors = false;
        for (float c : attrib.colors)
            if (c != 1.0f) {
                hasColors = true;
                break;
            }
    }

    Scene scene;
    scene.name = std::filesystem::path(path).stem().string();
    std::map<std::string, int> textureCache;
    for (size_t i = 0; i < objMaterials.size(); ++i) {
        const tinyobj::material_t& om = objMaterials[i];
        const std::string at = path + ": material '" + om.name + "'";
        Material m = defaultObjMaterial();
        m.baseColorFactor = glm::vec4(om.diffuse[0], om.diffuse[1], om.diffuse[2], om.dissolve);
        if (!om.diffuse_texname.empty())
            m.baseColorTexture = loadObjTexture(scene, textureCache, dir / om.diffuse_texname, at);
        scene.materials.push_back(m);
    }
    int defaultMaterial = -1;

    for (size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& sm = shapes[s].mesh;
        const std::string at = path + ": shape " + std::to_string(s) + (shapes[s].name.empty() ? "" : " '" + shapes[s].name + "'");
        // Faces grouped by material, in order of first use.
        std::map<int, size_t> meshOfMaterial;
        std::vector<Mesh> meshes;
        std::vector<std::unordered_map<VertexKey, uint32_t, VertexKeyHash>> vertexMaps;
        std::vector<bool> allNormals, allUvs;
        size_t offset = 0;
        for (size_t f = 0; f < sm.num_face_vertices.size(); ++f) {
            const size_t fv = sm.num_face_vertices[f];
            if (offset + fv > sm.indices.size()) throw Error(at + ": face " + std::to_string(f) + " is truncated");
            if (fv != 3) {
                // tinyobjloader leaves faces it could not triangulate; they cannot be drawn.
                offset += fv;
                continue;
            }
            int matId = f < sm.material_ids.size() ? sm.material_ids[f] : -1;
            if (matId >= int(objMaterials.size())) matId = -1;
            if (matId < 0) {
                if (defaultMaterial < 0) {
                    scene.materials.push_back(defaultObjMaterial());
                    defaultMaterial = int(scene.materials.size()) - 1;
                }
                matId = defaultMaterial;
            }
            auto [it, inserted] = meshOfMaterial.try_emplace(matId, meshes.size());
            if (inserted) {
                meshes.emplace_back();
                meshes.back().material = matId;
                vertexMaps.emplace_back();
                allNormals.push_back(true);
                allUvs.push_back(true);
            }
            const size_t mi = it->second;
            Mesh& mesh = meshes[mi];
            for (size_t k = 0; k < fv; ++k) {
                const tinyobj::index_t idx = sm.indices[offset + k];
                if (idx.vertex_index < 0 || idx.vertex_index >= nv)
                    throw Error(at + ": face " + std::to_string(f) + " references vertex " +
                                std::to_string(idx.vertex_index + 1) + " but the file has " + std::to_string(nv) +
                                " vertices");
                if (idx.texcoord_index >= nvt)
                    throw Error(at + ": face " + std::to_string(f) + " references texture coordinate " +
                                std::to_string(idx.texcoord_index + 1) + " but the file has " +
                                std::to_string(nvt));
                if (idx.normal_index >= nvn)
                    throw Error(at + ": face " + std::to_string(f) + " references normal " +
                                std::to_string(idx.normal_index + 1) + " but the file has " + std::to_string(nvn));
                const VertexKey key{idx.vertex_index, idx.texcoord_index, idx.normal_index};
                auto [vit, isNew] = vertexMaps[mi].try_emplace(key, uint32_t(mesh.positions.size()));
                if (isNew) {
                    const size_t v = size_t(idx.vertex_index);
                    mesh.positions.emplace_back(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                                                attrib.vertices[3 * v + 2]);
                    if (idx.normal_index >= 0) {
                        const size_t n = size_t(idx.normal_index);
                        mesh.normals.emplace_back(attrib.normals[3 * n], attrib.normals[3 * n + 1],
                                                  attrib.normals[3 * n + 2]);
                    } else {
                        allNormals[mi] = false;
                        mesh.normals.emplace_back(0.0f);
                    }
                    if (idx.texcoord_index >= 0) {
                        const size_t t = size_t(idx.texcoord_index);
                        mesh.uvs.emplace_back(attrib.texcoords[2 * t], 1.0f - attrib.texcoords[2 * t + 1]);
                    } else {
                        allUvs[mi] = false;
                        mesh.uvs.emplace_back(0.0f);
                    }
                    if (hasColors)
                        mesh.colors.emplace_back(attrib.colors[3 * v], attrib.colors[3 * v + 1],
                                                 attrib.colors[3 * v + 2], 1.0f);
                }
                mesh.indices.push_back(vit->second);
            }
            offset += fv;
        }
        for (size_t mi = 0; mi < meshes.size(); ++mi) {
            // Partial attributes are dropped: normals then come from the faces, uvs are absent.
            if (!allNormals[mi]) meshes[mi].normals.clear();
            if (!allUvs[mi]) meshes[mi].uvs.clear();
            if (!meshes[mi].indices.empty()) scene.meshes.push_back(std::move(meshes[mi]));
        }
    }
    if (scene.materials.empty()) scene.materials.push_back(defaultObjMaterial());
    validateScene(scene, path);
    return scene;
}

}  // namespace

}  // namespace starnt
