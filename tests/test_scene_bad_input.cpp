// Malformed or hostile scene input: every case must end in starnt::Error naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "scene_test_helpers.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::test;
using nlohmann::json;

namespace {

// Runs `fn`, expects starnt::Error, and returns its message (empty, with a failure, otherwise).

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << "message: " << (text)

std::string loadError(const GltfBuilder& g, const std::string& name) {
    const auto path = makeTempDir("bad") / name;
    if (name.ends_with(".glb")) g.writeGlb(path); else g.writeGltf(path);
    return errorOf([&] { loadScene(path.string()); });
}

Scene triangleScene() {
    Scene s;
    s.materials.emplace_back();
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2};
    s.meshes.push_back(m);
    return s;
}

}  // namespace

TEST(SceneBadInput, MissingFile) {
    const std::string msg = errorOf([] { loadScene("/nonexistent/dir/scene.glb"); });
    EXPECT_CONTAINS(msg, "/nonexistent/dir/scene.glb");
    EXPECT_CONTAINS(msg, "not found");
    EXPECT_CONTAINS(errorOf([] { loadGltf("/nonexistent/a.gltf"); }), "not found");
    EXPECT_CONTAINS(errorOf([] { loadObj("/nonexistent/a.obj"); }), "not found");
}

TEST(SceneBadInput, UnknownExtension) {
    const auto path = makeTempDir("ext") / "mesh.ply";
    writeText(path, "ply\n");
    const std::string msg = errorOf([&] { loadScene(path.string()); });
    EXPECT_CONTAINS(msg, path.string());
    EXPECT_CONTAINS(msg, "unknown scene file extension");
}

TEST(SceneBadInput, MalformedJson) {
    const auto path = makeTempDir("json") / "broken.gltf";
    writeText(path, "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ ");
    const std::string msg = errorOf([&] { loadScene(path.string()); });
    EXPECT_CONTAINS(msg, path.string());
    EXPECT_CONTAINS(msg, "cannot parse glTF");
}

TEST(SceneBadInput, TruncatedGlb) {
    const auto dir = makeTempDir("trunc");
    oneTriangle().writeGlb(dir / "whole.glb");
    auto bytes = readBytes(dir / "whole.glb");
    ASSERT_GT(bytes.size(), 40u);
    for (size_t keep : {bytes.size() - 8, size_t(30), size_t(10)}) {
        writeBytes(dir / "cut.glb", std::vector<uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)));
        EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "cut.glb").string()); }), "cannot parse glTF");
    }
    // A real file, cut in the middle of its binary chunk.
    STARNT_SKIP_WITHOUT_SHARED_SCENES("real truncated .glb not tested");
    const auto shared = sharedScenesDir();
    bytes = readBytes(shared / "chess/chess_classic_board.glb");
    writeBytes(dir / "chess_cut.glb", std::vector<uint8_t>(bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() / 2)));
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "chess_cut.glb").string()); }), "cannot parse glTF");
}

TEST(SceneBadInput, IndexOutOfRange) {
    const std::string msg = loadError(oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 5}), "idx.glb");
    EXPECT_CONTAINS(msg, "out of range");
    EXPECT_CONTAINS(msg, "mesh 0");
    EXPECT_CONTAINS(msg, "primitive 0");
}

TEST(SceneBadInput, NaNPosition) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::string msg = loadError(oneTriangle({0, 0, 0, 1, nan, 0, 0, 1, 0}), "nan.gltf");
    EXPECT_CONTAINS(msg, "NaN");
    EXPECT_CONTAINS(msg, "vertex 1");
    EXPECT_CONTAINS(msg, "mesh 0 primitive 0");
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_CONTAINS(loadError(oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, inf}), "inf.glb"), "vertex 2 has a NaN or infinite");
}

TEST(SceneBadInput, IndexCountNotMultipleOfThree) {
    const std::string msg = loadError(oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2, 0}), "four.glb");
    EXPECT_CONTAINS(msg, "not a multiple of 3");
    // Non-indexed with 4 positions: same problem.
    EXPECT_CONTAINS(loadError(oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {}), "four_ni.glb"),
                    "not a multiple of 3");
}

TEST(SceneBadInput, AccessorPastTheEndOfItsBuffer) {
    // POSITION claims 100 vertices; its buffer view holds 3.
    GltfBuilder g = oneTriangle();
    g.json["accessors"][0]["count"] = 100;
    std::string msg = loadError(g, "past.glb");
    EXPECT_CONTAINS(msg, "past the end");
    EXPECT_CONTAINS(msg, "POSITION");
    // Buffer view larger than the buffer.
    GltfBuilder h = oneTriangle();
    h.json["bufferViews"][0]["byteLength"] = 4000;
    msg = loadError(h, "view.glb");
    EXPECT_FALSE(msg.empty());
    // Accessor byteOffset that pushes the last element out of the view.
    GltfBuilder k = oneTriangle();
    k.json["accessors"][1]["byteOffset"] = 2;  // indices: 3 u16 from offset 2 in a 6-byte view
    msg = loadError(k, "offset.gltf");
    EXPECT_CONTAINS(msg, "past the end");
    EXPECT_CONTAINS(msg, "indices");
    // Stride smaller than the element.
    GltfBuilder s = oneTriangle();
    s.json["bufferViews"][0]["byteStride"] = 4;
    EXPECT_FALSE(loadError(s, "stride.gltf").empty());
    // Attribute referring to a nonexistent accessor.
    GltfBuilder a = oneTriangle();
    a.json["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 42;
    EXPECT_FALSE(loadError(a, "acc.gltf").empty());
}

TEST(SceneBadInput, EmptySceneHasNoRenderableTriangles) {
    GltfBuilder g;
    g.json["nodes"] = json::array({json::object()});
    g.json["scenes"] = json::array({{{"nodes", {0}}}});
    EXPECT_CONTAINS(loadError(g, "empty.gltf"), "scene has no renderable triangles");
    Scene s;
    EXPECT_CONTAINS(errorOf([&] { validateScene(s, "nothing"); }), "scene has no renderable triangles");
}

TEST(SceneBadInput, AllZeroAreaTriangles) {
    const std::string msg = loadError(oneTriangle({0, 0, 0, 1, 1, 1, 2, 2, 2}), "line.glb");
    EXPECT_CONTAINS(msg, "scene has no renderable triangles");
    EXPECT_CONTAINS(msg, "its 1 triangle is of zero area");
    // Not zero in exact terms, but a sliver 1 unit high and 1e18 long: nothing a float can rasterise.
    EXPECT_CONTAINS(loadError(oneTriangle({0, 0, 0, 1e18f, 0, 0, 0, 1, 0}), "sliver.glb"), "of zero area");
    EXPECT_CONTAINS(loadError(oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1}), "rep.glb"),
                    "scene has no renderable triangles");
}

TEST(SceneBadInput, MalformedObj) {
    const auto dir = makeTempDir("obj_bad");
    writeText(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 999\n");
    const std::string msg = errorOf([&] { loadScene((dir / "bad.obj").string()); });
    EXPECT_CONTAINS(msg, "bad.obj");
    EXPECT_CONTAINS(msg, "vertex 999");
    writeText(dir / "empty.obj", "# nothing\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "empty.obj").string()); }), "no renderable triangles");
}

TEST(SceneBadInput, SomeZeroAreaTrianglesAreRemovedAndCounted) {
    // Two good triangles and one degenerate one (repeated vertex) through the loader.
    const std::string path = (makeTempDir("zero") / "some.glb").string();
    oneTriangle({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, {0, 1, 2, 1, 1, 2, 1, 3, 2}).writeGlb(path);
    Scene scene;
    std::string err;
    {
        CapturedLog log;
        scene = loadScene(path);
        err = log.text();
    }
    EXPECT_EQ(scene.triangleCount(), 2u);
    EXPECT_CONTAINS(err, "removed 1 zero-area triangle");
    EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));

    // Directly: a near-degenerate sliver below the relative threshold is removed, a small but real one is kept.
    Scene s = triangleScene();
    s.meshes[0].positions.push_back({0.5f, 1e-14f, 0});
    s.meshes[0].positions.push_back({1.0f, 1e-14f, 0});
    s.meshes[0].positions.push_back({0.0f, 0.5f, 0});
    s.meshes[0].positions.push_back({1e-3f, 0.5f, 0});
    s.meshes[0].positions.push_back({0.0f, 0.5f + 1e-3f, 0});
    s.meshes[0].indices.insert(s.meshes[0].indices.end(), {0, 3, 1, 5, 6, 7});  // sliver, small real one
    {
        CapturedLog log;
        EXPECT_EQ(validateScene(s, "direct"), 1u);
    }
    EXPECT_EQ(s.triangleCount(), 2u);
}

// Small is not degenerate: a 12 x 8 mm quad in front of a backdrop 10 km away (the camera may stand
// beside it) keeps its triangles; the bound is the triangle's own size, not the scene's.
TEST(SceneBadInput, SmallTrianglesInAWideSceneAreKept) {
    Scene s = triangleScene();
    Mesh& m = s.meshes[0];
    m.positions = {{-5e3f, -5e3f, -1e4f}, {5e3f, -5e3f, -1e4f}, {0.0f, 5e3f, -1e4f},
                   {-0.006f, -0.004f, -0.01f}, {0.006f, -0.004f, -0.01f}, {0.006f, 0.004f, -0.01f}, {-0.006f, 0.004f, -0.01f}};
    m.indices = {0, 1, 2, 3, 4, 5, 3, 5, 6};
    {
        CapturedLog log;
        EXPECT_EQ(validateScene(s, "wide"), 0u);
    }
    EXPECT_EQ(s.triangleCount(), 3u);
}

TEST(SceneBadInput, ValidateSceneStructuralErrors) {
    {
        Scene s = triangleScene();
        s.meshes[0].normals = {{0, 0, 1}};
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "normals array has 1 entries");
    }
    {
        Scene s = triangleScene();
        s.meshes[0].colors.assign(3, glm::vec4(1.0f));
        s.meshes[0].colors[2].g = std::numeric_limits<float>::quiet_NaN();
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "vertex 2 has a NaN or infinite colour");
    }
    {
        Scene s = triangleScene();
        s.meshes[0].normals.assign(3, glm::vec3(0, 0, 1));
        s.meshes[0].normals[0].x = std::numeric_limits<float>::infinity();
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "normal");
    }
    {
        Scene s = triangleScene();
        s.meshes[0].material = 3;
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "references material 3");
    }
    {
        Scene s = triangleScene();
        s.materials[0].baseColorTexture = 0;
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "references texture 0");
    }
    {
        Scene s = triangleScene();
        s.meshes[0].indices = {0, 1, 3};
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "out of range");
    }
    {
        Scene s = triangleScene();
        s.meshes[0].positions[0].z = -std::numeric_limits<float>::infinity();
        EXPECT_CONTAINS(errorOf([&] { validateScene(s, "src"); }), "mesh 0: vertex 0 has a NaN or infinite position");
    }
    {
        Scene s = triangleScene();
        EXPECT_EQ(validateScene(s, "src"), 0u);
    }
}

TEST(SceneBadInput, BadReferencesInsideGltf) {
    GltfBuilder g = oneTriangle();
    g.json["meshes"][0]["primitives"][0]["material"] = 7;
    EXPECT_CONTAINS(loadError(g, "mat.gltf"), "material 7");
    GltfBuilder n = oneTriangle();
    n.json["nodes"][0]["children"] = {0};  // cycle
    EXPECT_FALSE(loadError(n, "cycle.gltf").empty());
    GltfBuilder c = oneTriangle();
    c.json["accessors"][0]["type"] = "VEC2";
    EXPECT_CONTAINS(loadError(c, "type.gltf"), "POSITION");
}
