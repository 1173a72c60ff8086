// Scenes: triangle meshes with the material inputs the OIT methods shade with.
//
// A Scene is plain CPU data (no GL). Meshes are stored in world space: node transforms are baked
// in at load time, so a renderer only needs the camera. Loaders validate what they read and throw
// starnt::Error with the file and the element at fault.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace starnt {

enum class AlphaMode { Opaque, Mask, Blend };

struct Texture {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba8;  // as stored in the file: colour channels sRGB-encoded
    std::string name;            // where it came from (file and image), for messages
};

struct Material {
    glm::vec4 baseColorFactor{1.0f};  // linear RGB + alpha
    int baseColorTexture = -1;        // index into Scene::textures, -1 when none
    bool unlit = false;               // KHR_materials_unlit
    glm::vec3 emissive{0.0f};         // linear RGB added to the shaded colour (emissiveFactor x KHR_materials_emissive_strength)
    bool doubleSided = true;          // false: back faces culled where the file made the material transparent (docs/DESIGN.md, "Scenes")
    AlphaMode alphaMode = AlphaMode::Blend;
    float alphaCutoff = 0.5f;  // for AlphaMode::Mask
};

struct Mesh {
    std::vector<glm::vec3> positions;  // world space
    std::vector<glm::vec3> normals;    // empty: the shader derives face normals
    std::vector<glm::vec2> uvs;        // empty: no texture coordinates; glTF convention: (0,0) is the
                                       // first (top) row of Texture::rgba8 (OBJ v is flipped on load)
    std::vector<glm::vec4> colors;     // COLOR_0, linear RGBA; empty: white
    std::vector<uint32_t> indices;     // triangle list
    int material = 0;                  // index into Scene::materials
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    glm::vec3 center() const { return 0.5f * (min + max); }
    float radius() const { return 0.5f * glm::length(max - min); }
};

struct Scene {
    std::string name;
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Texture> textures;

    Bounds bounds() const;
    size_t triangleCount() const;
    size_t vertexCount() const;
};

// Loads "builtin:NAME" or a .gltf/.glb/.obj path. Validates the result (see validateScene). Running
// out of memory while loading is reported as starnt::Error naming the file.
Scene loadScene(const std::string& spec);

// Loaders for one format each; they also validate.
Scene loadGltf(const std::string& path);
Scene loadObj(const std::string& path);

// Built-in procedural scenes, deterministic for a given seed. Names: see builtinSceneNames().
Scene makeBuiltinScene(const std::string& name, uint32_t seed = 1);
std::vector<std::string> builtinSceneNames();

// The exact layout of the built-in "panes" scene (independent of the seed), so tests can compute the
// expected composite: pane i is the axis-aligned square [min.x,max.x] x [min.y,max.y] at depth z,
// facing +Z, drawn as mesh i with material i (unlit, baseColorFactor = color, no vertex colours,
// no texture). Panes are listed in submission order (not depth order).
struct BuiltinPane {
    glm::vec2 min;
    glm::vec2 max;
    float z;
    glm::vec4 color;  // linear RGB + alpha
};
std::vector<BuiltinPane> builtinPanes();

// Largest vertex coordinate a scene may have: beyond, the bounds' radius (a squared length in
// float) overflows and the image is silently blank.
inline constexpr double kMaxSceneCoordinate = 1e18;

// Checks a scene and normalises it. Throws starnt::Error for: indices out of range, index count
// not a multiple of 3, NaN/Inf positions or |coordinate| > kMaxSceneCoordinate, attribute arrays of the wrong length, material or
// texture indices out of range, a scene with no renderable triangle. Zero-area triangles in an
// otherwise valid mesh are removed (they cover no pixel) and counted in the return value; a
// scene whose triangles are ALL zero-area is an error.
size_t validateScene(Scene& scene, const std::string& source);

}  // namespace starnt
