// Loading the shared suite scenes and small hand-written glTF / OBJ files.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include <stb/stb_image_write.h>

#include "scene_test_helpers.hpp"
#include "starnt/tools/scene.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::test;
using nlohmann::json;

namespace {
// An RGBA8 image encoded as PNG in memory (rows top first).
std::vector<uint8_t> pngBytes(int width, int height, const uint8_t* rgba) {
    std::vector<uint8_t> png;
    stbi_write_png_to_func(
        [](void* ctx, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(ctx);
            out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
        },
        &png, width, height, 4, rgba, width * 4);
    return png;
}
}  // namespace

namespace {

struct SuiteScene {
    const char* file;
    size_t triangles;      // README table (OBJ: after triangulation)
    size_t zeroArea;       // zero-area triangles validateScene removes (measured; almost all repeat an index;
                           // Buggy 2613 and Gearbox 862 when the bound was the scene extent's, not the triangle's)
    bool alphaBelowOne;    // every material has baseColorFactor.a < 1 (see the note below)
    bool normals;          // every mesh has normals
};

// The README says every suite material is BLEND with alpha < 1. That holds for the generated scenes,
// chess and tree, but not for the files below marked `false`: their materials have alpha 1 (engine
// and Fox are even OPAQUE; spot.obj has no .mtl and gets the default light grey material), so
// renderers must use a global alpha override (--alpha) for them.
const SuiteScene kSuite[] = {
    {"engine/2CylinderEngine.glb", 121496, 11160, false, true},
    {"chess/chess_classic_board.glb", 21064, 0, true, true},
    {"clothes/Corset_geom.glb", 18324, 0, false, true},
    {"clothes/SheenCloth_geom.glb", 115200, 0, false, true},
    {"candycat/spot.obj", 5856, 0, false, false},
    {"candycat/Fox.glb", 576, 0, false, false},
    {"tree/tree_grove.glb", 20002, 90, true, true},
    {"powerplant/Buggy_flat.glb", 474329, 2581, false, true},
    {"powerplant/GearboxAssy_flat.glb", 646064, 861, false, true},
    {"hair/hair_procedural.glb", 515166, 64, true, true},
    {"hairball/hairball_procedural.glb", 990000, 0, true, false},
    {"smoke/smoke_procedural.glb", 2800, 0, true, false},
    {"magic_stars/magic_stars_procedural.glb", 7500, 0, true, false},
};

bool finiteVec(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

TEST(SuiteScenes, AllLoadWithTheDocumentedTriangleCounts) {
    STARNT_SKIP_WITHOUT_SHARED_SCENES("suite scenes not tested");
    const auto dir = sharedScenesDir();
    for (const SuiteScene& s : kSuite) {
        SCOPED_TRACE(s.file);
        const auto t0 = std::chrono::steady_clock::now();
        Scene scene;
        std::string warnings;
        {
            CapturedLog log;
            scene = loadScene((dir / s.file).string());
            warnings = log.text();
        }
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::printf("  %-40s %7zu triangles (%5zu zero-area removed) %7zu vertices %4zu meshes %5.0f ms\n", s.file,
                    scene.triangleCount(), s.zeroArea, scene.vertexCount(), scene.meshes.size(), ms);
        // The README counts every triangle in the file; validateScene drops the zero-area ones.
        EXPECT_EQ(scene.triangleCount() + s.zeroArea, s.triangles);
        if (s.zeroArea > 0) {
            EXPECT_NE(warnings.find("removed " + std::to_string(s.zeroArea) + " zero-area"), std::string::npos)
                << warnings;
        } else {
            EXPECT_EQ(warnings, "");
        }
        const Bounds b = scene.bounds();
        EXPECT_TRUE(finiteVec(b.min) && finiteVec(b.max));
        EXPECT_GT(b.radius(), 0.0f);
        const glm::vec3 size = b.max - b.min;
        // Non-degenerate: extent in at least two axes.
        EXPECT_GE(int(size.x > 0) + int(size.y > 0) + int(size.z > 0), 2);
        EXPECT_FALSE(scene.name.empty());
        for (const Mesh& m : scene.meshes) EXPECT_EQ(!m.normals.empty(), s.normals);
        for (const Material& mat : scene.materials) {
            if (s.alphaBelowOne) {
                EXPECT_LT(mat.baseColorFactor.a, 1.0f);
                EXPECT_EQ(mat.alphaMode, AlphaMode::Blend);
                EXPECT_TRUE(mat.doubleSided);
            } else {
                EXPECT_EQ(mat.baseColorFactor.a, 1.0f);
            }
        }
    }
}

TEST(SuiteScenes, SmokeHasVertexColoursAndFoxHasItsTexture) {
    STARNT_SKIP_WITHOUT_SHARED_SCENES("suite scenes not tested");
    const auto dir = sharedScenesDir();
    Scene smoke = loadScene((dir / "smoke/smoke_procedural.glb").string());
    size_t belowOne = 0;
    for (const Mesh& m : smoke.meshes) {
        ASSERT_EQ(m.colors.size(), m.positions.size());
        for (const glm::vec4& c : m.colors) belowOne += c.a < 1.0f;
    }
    EXPECT_GT(belowOne, 0u);
    for (const Material& mat : smoke.materials) EXPECT_LT(mat.baseColorFactor.a, 1.0f);

    Scene fox = loadScene((dir / "candycat/Fox.glb").string());
    ASSERT_EQ(fox.textures.size(), 1u);
    EXPECT_GT(fox.textures[0].width, 0);
    EXPECT_EQ(fox.textures[0].rgba8.size(), size_t(fox.textures[0].width) * fox.textures[0].height * 4);
    ASSERT_FALSE(fox.meshes.empty());
    EXPECT_EQ(fox.materials[size_t(fox.meshes[0].material)].baseColorTexture, 0);
    EXPECT_EQ(fox.meshes[0].uvs.size(), fox.meshes[0].positions.size());
}

// A node hierarchy: parent translates by (10,0,0), child scales by (2,1,1) and holds the mesh; a
// second root node rotates the same mesh by 90 degrees about Z. COLOR_0 is normalised u8, the
// material is unlit with a 2x1 texture, TEXCOORD_0 is float.
TEST(GltfLoader, HandWrittenFileWithHierarchyColoursAndTexture) {
    GltfBuilder g;
    const int pos = g.data(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}, kF32, 3, "VEC3");
    const float s = std::sqrt(0.5f);
    const int nrm = g.data(std::vector<float>{s, s, 0, s, s, 0, s, s, 0}, kF32, 3, "VEC3");
    const int col = g.data(std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0}, kU8, 3, "VEC4", true);
    const int uv = g.data(std::vector<float>{0, 0, 1, 0, 0, 1}, kF32, 3, "VEC2");
    const int idx = g.data(std::vector<uint8_t>{0, 1, 2}, kU8, 3, "SCALAR");
    // 2x1 RGBA PNG: opaque red, half-transparent blue.
    const uint8_t pixels[8] = {255, 0, 0, 255, 0, 0, 255, 128};
    const std::vector<uint8_t> png = pngBytes(2, 1, pixels);
    ASSERT_FALSE(png.empty());
    g.json["images"] = json::array({{{"uri", "data:image/png;base64," + base64(png)}}});
    g.json["textures"] = json::array({{{"source", 0}}});
    g.json["materials"] = json::array({{{"pbrMetallicRoughness",
                                         {{"baseColorFactor", {1.0, 0.5, 0.25, 0.5}}, {"baseColorTexture", {{"index", 0}}}}},
                                        {"alphaMode", "BLEND"},
                                        {"doubleSided", true},
                                        {"extensions", {{"KHR_materials_unlit", json::object()}}}}});
    g.json["extensionsUsed"] = {"KHR_materials_unlit"};
    g.json["meshes"] = json::array(
        {{{"primitives", json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}, {"COLOR_0", col}, {"TEXCOORD_0", uv}}},
                                      {"indices", idx},
                                      {"material", 0}}})}}});
    g.json["nodes"] = json::array({{{"translation", {10, 0, 0}}, {"children", {1}}},
                                   {{"scale", {2, 1, 1}}, {"mesh", 0}},
                                   {{"rotation", {0, 0, s, s}}, {"mesh", 0}}});
    g.json["scenes"] = json::array({{{"nodes", {0, 2}}}});
    g.json["scene"] = 0;

    const auto dir = makeTempDir("gltf_hand");
    for (const char* name : {"hand.gltf", "hand.glb"}) {
        SCOPED_TRACE(name);
        const auto path = dir / name;
        if (std::string(name).ends_with(".glb")) g.writeGlb(path); else g.writeGltf(path);
        Scene scene = loadScene(path.string());
        EXPECT_EQ(scene.name, "hand");
        ASSERT_EQ(scene.meshes.size(), 2u);
        ASSERT_EQ(scene.triangleCount(), 2u);
        const Mesh& a = scene.meshes[0];
        ASSERT_EQ(a.positions.size(), 3u);
        EXPECT_EQ(a.positions[0], glm::vec3(10, 0, 0));
        EXPECT_EQ(a.positions[1], glm::vec3(12, 0, 0));
        EXPECT_EQ(a.positions[2], glm::vec3(10, 1, 0));
        // Normal (1,1,0)/sqrt2 under scale (2,1,1): inverse transpose gives (0.5,1,0), renormalised.
        const glm::vec3 expectedN = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));
        EXPECT_NEAR(a.normals[0].x, expectedN.x, 1e-6);
        EXPECT_NEAR(a.normals[0].y, expectedN.y, 1e-6);
        EXPECT_NEAR(a.normals[0].z, 0.0f, 1e-6);
        // Rotated copy: (1,0,0) -> (0,1,0), (0,1,0) -> (-1,0,0).
        const Mesh& b = scene.meshes[1];
        EXPECT_NEAR(b.positions[1].x, 0.0f, 1e-6);
        EXPECT_NEAR(b.positions[1].y, 1.0f, 1e-6);
        EXPECT_NEAR(b.positions[2].x, -1.0f, 1e-6);
        EXPECT_NEAR(b.positions[2].y, 0.0f, 1e-6);
        // COLOR_0 normalised u8.
        ASSERT_EQ(a.colors.size(), 3u);
        EXPECT_EQ(a.colors[0], glm::vec4(1, 0, 0, 1));
        EXPECT_NEAR(a.colors[1].a, 128.0f / 255.0f, 1e-6);
        EXPECT_EQ(a.uvs[1], glm::vec2(1, 0));
        EXPECT_EQ(a.indices, (std::vector<uint32_t>{0, 1, 2}));
        // Material and texture.
        ASSERT_EQ(scene.materials.size(), 1u);
        const Material& m = scene.materials[0];
        EXPECT_TRUE(m.unlit);
        EXPECT_TRUE(m.doubleSided);
        EXPECT_EQ(m.alphaMode, AlphaMode::Blend);
        EXPECT_EQ(m.baseColorFactor, glm::vec4(1.0f, 0.5f, 0.25f, 0.5f));
        ASSERT_EQ(m.baseColorTexture, 0);
        ASSERT_EQ(scene.textures.size(), 1u);
        EXPECT_EQ(scene.textures[0].width, 2);
        EXPECT_EQ(scene.textures[0].height, 1);
        EXPECT_EQ(scene.textures[0].rgba8, (std::vector<uint8_t>(pixels, pixels + 8)));
    }
}

TEST(GltfLoader, DefaultMaterialNonIndexedAndMatrixTransform) {
    GltfBuilder g = oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {});
    // Column-major matrix: translate by (1,2,3).
    g.json["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    const auto path = makeTempDir("gltf_default") / "t.gltf";
    g.writeGltf(path);
    Scene scene = loadGltf(path.string());
    ASSERT_EQ(scene.triangleCount(), 1u);
    EXPECT_EQ(scene.meshes[0].positions[1], glm::vec3(2, 2, 3));
    ASSERT_EQ(scene.materials.size(), 1u);
    const Material& m = scene.materials[0];
    EXPECT_EQ(m.baseColorFactor, glm::vec4(1.0f));
    EXPECT_EQ(m.alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(m.unlit);
    EXPECT_TRUE(scene.meshes[0].normals.empty());
    EXPECT_TRUE(scene.meshes[0].colors.empty());
}

TEST(GltfLoader, StripsFansInterleavedStrideAndVec3U16Colours) {
    GltfBuilder g;
    // Interleaved: position (12 bytes) + COLOR_0 RGB u16 normalised (6 bytes) + 2 pad = stride 20.
    std::vector<uint8_t> inter;
    const float quad[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    for (int v = 0; v < 4; ++v) {
        const uint8_t* p = reinterpret_cast<const uint8_t*>(quad[v]);
        inter.insert(inter.end(), p, p + 12);
        const uint16_t c[3] = {65535, uint16_t(v * 1000), 0};
        const uint8_t* q = reinterpret_cast<const uint8_t*>(c);
        inter.insert(inter.end(), q, q + 6);
        inter.push_back(0);
        inter.push_back(0);
    }
    const size_t off = g.append(inter);
    const int view = g.view(off, inter.size(), 20);
    const int pos = g.accessor(view, 0, kF32, 4, "VEC3");
    const int col = g.accessor(view, 12, kU16, 4, "VEC3", true);
    const int stripIdx = g.data(std::vector<uint32_t>{0, 1, 2, 3}, kU32, 4, "SCALAR");
    const int fanIdx = g.data(std::vector<uint16_t>{0, 1, 3, 2}, kU16, 4, "SCALAR");
    g.json["meshes"] = json::array({{{"primitives", json::array({
        {{"attributes", {{"POSITION", pos}, {"COLOR_0", col}}}, {"indices", stripIdx}, {"mode", 5}},
        {{"attributes", {{"POSITION", pos}}}, {"indices", fanIdx}, {"mode", 6}},
        {{"attributes", {{"POSITION", pos}}}, {"mode", 1}},  // lines: skipped with a warning
    })}}});
    g.json["nodes"] = json::array({{{"mesh", 0}}});
    g.json["scenes"] = json::array({{{"nodes", {0}}}});
    const auto path = makeTempDir("gltf_strip") / "s.glb";
    g.writeGlb(path);
    Scene scene;
    std::string err;
    {
        CapturedLog log;
        scene = loadScene(path.string());
        err = log.text();
    }
    EXPECT_NE(err.find("skipping points/lines"), std::string::npos) << err;
    ASSERT_EQ(scene.meshes.size(), 2u);
    // Strip 0,1,2,3 -> (0,1,2), (1,3,2); fan 0,1,3,2 -> (1,3,0), (3,2,0).
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(scene.meshes[1].indices, (std::vector<uint32_t>{1, 3, 0, 3, 2, 0}));
    EXPECT_EQ(scene.meshes[0].positions[3], glm::vec3(1, 1, 0));
    ASSERT_EQ(scene.meshes[0].colors.size(), 4u);
    EXPECT_EQ(scene.meshes[0].colors[2].r, 1.0f);
    EXPECT_NEAR(scene.meshes[0].colors[2].g, 2000.0f / 65535.0f, 1e-6);
    EXPECT_EQ(scene.meshes[0].colors[2].a, 1.0f);
}

TEST(ObjLoader, MaterialsTexturesAndVertexColours) {
    const auto dir = makeTempDir("obj");
    const uint8_t pixels[4] = {10, 20, 30, 255};
    ASSERT_TRUE(stbi_write_png((dir / "tex.png").string().c_str(), 1, 1, 4, pixels, 4));
    writeText(dir / "m.mtl",
              "newmtl glass\nKd 0.2 0.4 0.6\nd 0.25\nmap_Kd tex.png\n"
              "newmtl tr\nKd 1 0 0\nTr 0.75\n");
    writeText(dir / "m.obj",
              "mtllib m.mtl\n"
              "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nv 0 1 0 1 1 1\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
              "usemtl glass\nf 1/1/1 2/2/1 3/3/1 4/4/1\n"
              "usemtl tr\nf 1 3 4\n");
    Scene scene = loadScene((dir / "m.obj").string());
    EXPECT_EQ(scene.name, "m");
    EXPECT_EQ(scene.triangleCount(), 3u);  // quad triangulated + one triangle
    ASSERT_EQ(scene.meshes.size(), 2u);
    const Mesh& quad = scene.meshes[0];
    const Material& glass = scene.materials[size_t(quad.material)];
    EXPECT_NEAR(glass.baseColorFactor.g, 0.4f, 1e-6);
    EXPECT_NEAR(glass.baseColorFactor.a, 0.25f, 1e-6);
    ASSERT_EQ(glass.baseColorTexture, 0);
    EXPECT_EQ(scene.textures[0].rgba8, (std::vector<uint8_t>{10, 20, 30, 255}));
    EXPECT_EQ(quad.normals.size(), quad.positions.size());
    ASSERT_EQ(quad.uvs.size(), quad.positions.size());
    EXPECT_EQ(quad.uvs[0], glm::vec2(0, 1));  // OBJ v flipped to the glTF convention
    ASSERT_EQ(quad.colors.size(), quad.positions.size());
    EXPECT_EQ(quad.colors[1], glm::vec4(0, 1, 0, 1));
    const Mesh& tri = scene.meshes[1];
    EXPECT_TRUE(tri.normals.empty());
    EXPECT_TRUE(tri.uvs.empty());
    EXPECT_NEAR(scene.materials[size_t(tri.material)].baseColorFactor.a, 0.25f, 1e-6);  // 1 - Tr
    EXPECT_EQ(scene.materials[size_t(tri.material)].baseColorTexture, -1);
}

TEST(ObjLoader, NoMaterialGetsLightGreyDefault) {
    const auto dir = makeTempDir("obj_default");
    writeText(dir / "p.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    Scene scene = loadScene((dir / "p.OBJ").string());  // extension is case-insensitive
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColorFactor, glm::vec4(0.8f, 0.8f, 0.8f, 1.0f));
    EXPECT_TRUE(scene.meshes[0].colors.empty());
    EXPECT_TRUE(scene.meshes[0].normals.empty());
}

namespace {
// A 1x1 PNG as a data URI, for files that need a texture to carry a texture transform.
std::string onePixelPng() {
    const uint8_t pixel[4] = {200, 100, 50, 255};
    return "data:image/png;base64," + base64(pngBytes(1, 1, pixel));
}
}  // namespace

// glTF's rest pose includes the morph targets at the mesh's default weights (a node's own weights
// replace them), and a base colour texture's KHR_texture_transform moves the coordinates it
// samples: both were ignored, drawing the base mesh and the untransformed texture.
TEST(GltfLoader, MorphTargetsAtTheirWeightsAndTheTextureTransform) {
    const std::filesystem::path dir = makeTempDir("gltf_morph");
    GltfBuilder g = oneTriangle();
    const int delta = g.data(std::vector<float>{3, 0, 0, 3, 0, 0, 3, 1, 0}, kF32, 3, "VEC3");
    const int uv = g.data(std::vector<float>{0, 0, 1, 0, 0, 1}, kF32, 3, "VEC2");
    g.json["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", delta}}});
    g.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    g.json["meshes"][0]["primitives"][0]["material"] = 0;
    g.json["meshes"][0]["weights"] = {0.5};
    g.json["images"] = json::array({{{"uri", onePixelPng()}}});
    g.json["textures"] = json::array({{{"source", 0}}});
    const double quarter = std::acos(0.0);  // 90 degrees
    g.json["materials"] = json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorTexture",
             {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", quarter}, {"scale", {2.0, 3.0}}}}}}}}}},
          {"emissiveFactor", {0.5, 0.25, 0.0}},
          {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}}});
    g.json["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_emissive_strength"};
    g.json["extensionsRequired"] = {"KHR_texture_transform"};
    g.writeGltf(dir / "mesh.gltf");
    Scene scene = loadGltf((dir / "mesh.gltf").string());
    ASSERT_EQ(scene.meshes.size(), 1u);
    const Mesh& m = scene.meshes[0];
    EXPECT_EQ(m.positions[0], glm::vec3(1.5f, 0.0f, 0.0f));
    EXPECT_EQ(m.positions[2], glm::vec3(1.5f, 1.5f, 0.0f));
    // uv' = offset + R(90 degrees, counter-clockwise as the image is seen) (scale * uv):
    // (1, 0) -> scaled (2, 0) -> rotated (0, -2) -> (0.5, -1.75); (0, 1) -> (0, 3) -> (3, 0) -> (3.5, 0.25).
    EXPECT_NEAR(m.uvs[0].x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.uvs[0].y, 0.25f, 1e-6f);
    EXPECT_NEAR(m.uvs[1].x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.uvs[1].y, -1.75f, 1e-6f);
    EXPECT_NEAR(m.uvs[2].x, 3.5f, 1e-6f);
    EXPECT_NEAR(m.uvs[2].y, 0.25f, 1e-6f);
    EXPECT_EQ(scene.materials[0].emissive, glm::vec3(2.0f, 1.0f, 0.0f));
    // A node's weights replace the mesh's.
    g.json["nodes"][0]["weights"] = {1.0};
    g.writeGltf(dir / "node.gltf");
    EXPECT_EQ(loadGltf((dir / "node.gltf").string()).meshes[0].positions[1], glm::vec3(4.0f, 0.0f, 0.0f));
}

// An extension the file requires and the loader lacks is an error naming it; a scene index past
// the file's scenes is an error; a skin without inverseBindMatrices (optional in glTF) loads.
TEST(GltfLoader, RequiredExtensionsMissingScenesAndSkinsWithoutBindMatrices) {
    const std::filesystem::path dir = makeTempDir("gltf_required");
    GltfBuilder g = oneTriangle();
    g.json["extensionsUsed"] = {"EXT_made_up"};
    g.json["extensionsRequired"] = {"EXT_made_up"};
    g.writeGltf(dir / "required.gltf");
    EXPECT_NE(errorOf([&] { loadGltf((dir / "required.gltf").string()); }).find("requires the glTF extension EXT_made_up"), std::string::npos);
    g.json["extensionsRequired"] = json::array();
    g.writeGltf(dir / "used.gltf");
    EXPECT_EQ(loadGltf((dir / "used.gltf").string()).triangleCount(), 1u);  // used, not required: a warning
    GltfBuilder s = oneTriangle();
    s.json["scene"] = 3;
    s.writeGltf(dir / "scene.gltf");
    EXPECT_NE(errorOf([&] { loadGltf((dir / "scene.gltf").string()); }).find("\"scene\" is 3 but the file has 1 scenes"), std::string::npos);
    GltfBuilder k = oneTriangle();
    k.json["nodes"] = json::array({{{"mesh", 0}, {"skin", 0}}, json::object()});
    k.json["scenes"] = json::array({{{"nodes", {0, 1}}}});
    k.json["skins"] = json::array({{{"joints", {1}}}});
    k.writeGltf(dir / "skin.gltf");
    EXPECT_EQ(loadGltf((dir / "skin.gltf").string()).triangleCount(), 1u);
}
