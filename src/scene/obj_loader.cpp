// Wavefront OBJ loader on top of tinyobjloader (polygons triangulated as fans). One Scene mesh per
// (shape, material). Texture coordinates are converted to the glTF convention used by Scene
// (v = 0 at the first/top row of the image), i.e. v' = 1 - v.
#include <filesystem>
#include <map>
#include <tuple>
#include <unordered_map>

#include <stb_image.h>
#include <tiny_obj_loader.h>

#include "scene/scene_internal.hpp"
#include "starnt/error.hpp"
#include "starnt/scene.hpp"

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

Scene loadObj(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": file not found");
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();

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

}  // namespace starnt
