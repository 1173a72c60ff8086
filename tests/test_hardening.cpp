// Inputs from the user campaign that broke the error contract (SPEC 9: one line `starnt: error:
// ...`, non-zero exit, no output files left): each is rejected where the data enters, with the file,
// field and value in the message. Numbered by the item of the hardening round that found them.
#include <cstring>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "scene_test_helpers.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/tools/camera_path.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/image.hpp"
#include "starnt/tools/metrics.hpp"
#include "starnt/tools/nn.hpp"
#include "starnt/tools/scene.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace starnt;
using namespace starnt::test;
using nlohmann::json;

namespace {

#define EXPECT_CONTAINS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << "text: " << (text)


// A failed run: non-zero exit, one `starnt: error:` line on stderr mentioning every part.
void expectOneLineError(const CliRun& r, const std::vector<std::string>& parts, const std::string& what) {
    EXPECT_NE(r.exitCode, 0) << what;
    EXPECT_NE(r.exitCode, -1) << "crashed: " << what;
    EXPECT_EQ(r.err.rfind("starnt: error: ", 0), 0u) << what << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << ": " << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << what << ": " << r.err;
    for (const auto& p : parts) EXPECT_NE(r.err.find(p), std::string::npos) << what << ": " << r.err << " lacks " << p;
}

std::string smallPng(const fs::path& dir, const std::string& name, int w = 16, int h = 12) {
    const std::string path = (dir / name).string();
    savePng(Image(w, h, 0.5f), path);
    return path;
}

// A PNG whose header claims w x h (no pixel data): enough for the size check before decoding.
void writePngHeader(const fs::path& path, uint32_t w, uint32_t h) {
    std::vector<uint8_t> b = {0x89, 'P', 'N', 'G', 0x0d, 0x0a, 0x1a, 0x0a, 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (uint32_t v : {w, h})
        for (int i = 3; i >= 0; --i) b.push_back(uint8_t(v >> (8 * i)));
    for (uint8_t v : {8, 6, 0, 0, 0}) b.push_back(v);  // 8-bit RGBA
    uint32_t crc = 0xffffffffu;
    for (size_t i = 12; i < b.size(); ++i) {
        crc ^= b[i];
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xffffffffu;
    for (int i = 3; i >= 0; --i) b.push_back(uint8_t(crc >> (8 * i)));
    writeBytes(path, b);
}

json shippedWeights() {
    std::ifstream f(fs::path(STARNT_SOURCE_DIR) / "src/methods/starnt/starnt_weights.json");
    return json::parse(f);
}

}  // namespace

// ---- 1. FLIP pixels per degree ----------------------------------------------------------------

TEST(Hardening, CompareRejectsAbsurdPixelsPerDegree) {
    const fs::path dir = makeTempDir("ppd");
    const std::string a = smallPng(dir, "a.png"), b = smallPng(dir, "b.png");
    for (const char* ppd : {"1e12", "1e10", "1e8", "1001", "0.5", "0", "-3", "nan", "inf"}) {
        expectOneLineError(run("compare --reference " + a + " --test " + b + " --ppd " + ppd), {"--ppd", "1..1000"}, ppd);
    }
    CliRun ok = run("compare --reference " + a + " --test " + b + " --ppd 1000 --json");
    EXPECT_EQ(ok.exitCode, 0) << ok.err;
    // The library refuses them too (the radius computation overflowed at 1e12).
    EXPECT_CONTAINS(errorOf([] { flip(Image(4, 4), Image(4, 4), 1e12); }), "1..1000");
    EXPECT_CONTAINS(errorOf([] { flipMean(Image(4, 4), Image(4, 4), 1e8); }), "1e+08");
}

// ---- 10. FLIP in bands: same result, band-sized memory ------------------------------------------

TEST(Hardening, FlipMeanMatchesFlipAndBandsAreSeamless) {
    // Many bands (a few filter halos tall, at most about 2 Mpixel each, run on several threads): the
    // content repeats every 64 rows, so away from the top and bottom edges the error map repeats
    // too, across every band boundary in the rows compared.
    const int w = 8, h = 300000, period = 64;
    Image a(w, h, 1.0f), b(w, h, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const int k = (y % period) * 7 + x * 3 + c;
                a.pixel(x, y)[c] = float((k * 37) % 101) / 100.0f;
                b.pixel(x, y)[c] = float((k * 53) % 97) / 96.0f;
            }
    const FlipResult r = flip(a, b);
    EXPECT_EQ(flipMean(a, b), r.mean);
    for (int y = 262144 - 2000; y < 262144 + 2000; ++y)
        for (int x = 0; x < w; ++x) ASSERT_EQ(r.errorMap.pixel(x, y)[0], r.errorMap.pixel(x, y - 64 * 100)[0]) << x << "," << y;
}

// ---- 2. MiB values that wrapped --------------------------------------------------------------

TEST(Hardening, AbufferCapOutOfRangeIsRejected) {
    const fs::path dir = makeTempDir("cap");
    const std::string out = (dir / "x.png").string();
    for (const char* v : {"1e30", "0", "-5", "nan", "2e6"}) {
        const CliRun r = run("render --scene builtin:panes --method abuffer --width 16 --height 12 --abuffer-cap-mib " +
                             std::string(v) + " --out " + out);
        expectOneLineError(r, {"--abuffer-cap-mib", "positive and at most 1048576 MiB"}, v);
        EXPECT_FALSE(fs::exists(out));
    }
    expectOneLineError(run("bench --abuffer-cap-mib 1e30 --out " + (dir / "b").string()), {"--abuffer-cap-mib"}, "bench");
}

// ---- 3. Bad input that exited 0 ----------------------------------------------------------------

TEST(Hardening, ObjWithUnparsableOrNonFiniteNumbers) {
    const fs::path dir = makeTempDir("objnum");
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    writeText(dir / "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
    std::string msg = errorOf([&] { loadScene((dir / "nan.obj").string()); });
    EXPECT_CONTAINS(msg, "nan.obj:2");
    EXPECT_CONTAINS(msg, "'nan'");
    writeText(dir / "junk.obj", "v 0 0 0\nv 1 0 0\nv 0 1.2.3 0\nf 1 2 3\n");
    msg = errorOf([&] { loadScene((dir / "junk.obj").string()); });
    EXPECT_CONTAINS(msg, "junk.obj:3");
    EXPECT_CONTAINS(msg, "'1.2.3' is not a number");
    writeText(dir / "inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "inf.obj").string()); }), "not a finite number");
    writeText(dir / "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt abc 0\nf 1/1 2/1 3/1\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "uv.obj").string()); }), "vt coordinate 'abc'");
    // MTL colour.
    writeText(dir / "m.mtl", "newmtl red\nKd 1 nan 0\nd 0.5\n");
    writeText(dir / "mtl.obj", "mtllib m.mtl\nusemtl red\n" + tri);
    msg = errorOf([&] { loadScene((dir / "mtl.obj").string()); });
    EXPECT_CONTAINS(msg, "m.mtl:2");
    EXPECT_CONTAINS(msg, "Kd value 'nan'");
    writeText(dir / "d.mtl", "newmtl red\nKd 1 0 0\nd zero\n");
    writeText(dir / "d.obj", "mtllib d.mtl\nusemtl red\n" + tri);
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "d.obj").string()); }), "d value 'zero'");
    // Through the command line: one line, no image.
    const std::string out = (dir / "x.png").string();
    expectOneLineError(run("render --width 16 --height 12 --scene " + (dir / "nan.obj").string() + " --out " + out),
                       {"nan.obj:2"}, "cli");
    EXPECT_FALSE(fs::exists(out));
}

TEST(Hardening, WeightsWithAbsurdMagnitudes) {
    const fs::path dir = makeTempDir("wmag");
    struct Case {
        const char* name;
        std::function<void(json&)> change;
        const char* mentions;
    };
    const std::vector<Case> cases = {
        {"w1e30.json", [](json& j) { j["layers"][0]["weights"][3] = 1e30; }, "layers[0].weights[3]"},
        {"w3e38.json", [](json& j) { j["layers"][2]["bias"][1] = 3e38; }, "layers[2].bias[1]"},
        {"scale.json", [](json& j) { j["input_scale"][0] = 1e38; }, "input_scale[0]"},
        {"offset.json", [](json& j) { j["input_offset"][4] = -2e6; }, "input_offset[4]"},
    };
    for (const Case& c : cases) {
        json j = shippedWeights();
        c.change(j);
        writeText(dir / c.name, j.dump());
        const std::string msg = errorOf([&] { nn::loadWeights(dir / c.name); });
        EXPECT_CONTAINS(msg, c.name);
        EXPECT_CONTAINS(msg, c.mentions);
        EXPECT_CONTAINS(msg, "|value| <= 1e+06");
    }
    // The shipped file is well inside.
    json j = shippedWeights();
    writeText(dir / "good.json", j.dump());
    EXPECT_NO_THROW(nn::loadWeights(dir / "good.json"));
    // Through render: an error before rendering, no image.
    const std::string out = (dir / "x.png").string();
    expectOneLineError(run("render --scene builtin:panes --method starnt --width 16 --height 12 --weights " +
                           (dir / "scale.json").string() + " --out " + out),
                       {"scale.json", "input_scale[0]"}, "render");
    EXPECT_FALSE(fs::exists(out));
}

// hybrid-moments' and starnt-d's moments are relative to pass 2's depth at the same pixel: no
// reduced passes. starnt-d takes its own kind of weights only.
TEST(Hardening, TailMomentMethodsRefuseReducedPassesAndOtherWeights) {
    const fs::path dir = makeTempDir("hmom");
    const std::string out = (dir / "x.png").string();
    for (const std::string method : {"hybrid-moments", "starnt-d"}) {
        const std::string base = "render --scene builtin:panes --width 16 --height 12 --method " + method + " --out " + out + " ";
        for (const char* flags : {"--spatial on", "--scales 100,50", "--inference corners", "--upsample joint"}) {
            expectOneLineError(run(base + flags), {method, "full resolution"}, flags);
            EXPECT_FALSE(fs::exists(out)) << flags;
        }
        // Its default and full-resolution scales render.
        EXPECT_EQ(run(base + "--scales 100,100").exitCode, 0);
        EXPECT_TRUE(fs::exists(out));
        fs::remove(out);
    }
    const std::string weights = (fs::path(STARNT_SOURCE_DIR) / "src/methods/starnt_residual/starnt_residual_weights.json").string();
    expectOneLineError(run("render --scene builtin:panes --width 16 --height 12 --method starnt-d --out " + out + " --weights " + weights),
                       {"starnt_residual_weights.json", "needs a starnt-d network"}, "starnt-d");
    EXPECT_FALSE(fs::exists(out));
}

TEST(Hardening, WeightsForAMethodWithoutNetworkAndNegativeAlpha) {
    const fs::path dir = makeTempDir("wnet");
    const std::string out = (dir / "x.png").string();
    const std::string weights = (fs::path(STARNT_SOURCE_DIR) / "src/methods/starnt/starnt_weights.json").string();
    const std::string base = "render --scene builtin:panes --width 16 --height 12 --out " + out + " ";
    expectOneLineError(run(base + "--method wboit --weights " + weights), {"--weights", "wboit", "no network"}, "wboit");
    EXPECT_FALSE(fs::exists(out));
    expectOneLineError(run(base + "--method hybrid --weights " + weights), {"--weights", "hybrid", "no network"}, "hybrid");
    EXPECT_FALSE(fs::exists(out));
    // starnt's weights have starnt-residual's inputs and sizes: the kind tells them apart.
    expectOneLineError(run(base + "--method starnt-residual --weights " + weights),
                       {"starnt_weights.json", "needs a starnt-residual network"}, "starnt-residual");
    EXPECT_FALSE(fs::exists(out));
    for (const char* alpha : {"-1", "-0.5", "1.5", "nan"}) {
        expectOneLineError(run(base + "--method wboit --alpha " + alpha), {"--alpha", alpha}, alpha);
        EXPECT_FALSE(fs::exists(out));
    }
    EXPECT_EQ(run(base + "--method wboit --alpha 0").exitCode, 0);
}

TEST(Hardening, GltfInvalidMaterialVersionAndTexture) {
    const fs::path dir = makeTempDir("gltfbad");
    GltfBuilder g = oneTriangle();
    g.json["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 0.5, 0.2}}}}}});
    g.json["meshes"][0]["primitives"][0]["material"] = 0;
    g.writeGltf(dir / "rgb.gltf");
    std::string msg = errorOf([&] { loadScene((dir / "rgb.gltf").string()); });
    EXPECT_CONTAINS(msg, "rgb.gltf");
    EXPECT_CONTAINS(msg, "baseColorFactor");

    oneTriangle().writeGlb(dir / "v1.glb");
    auto bytes = readBytes(dir / "v1.glb");
    bytes[4] = 1;  // container version 1
    writeBytes(dir / "v1.glb", bytes);
    msg = errorOf([&] { loadScene((dir / "v1.glb").string()); });
    EXPECT_CONTAINS(msg, "v1.glb");
    EXPECT_CONTAINS(msg, "version 1");

    GltfBuilder t = oneTriangle();
    writeText(dir / "broken.png", "this is not a png");
    t.json["images"] = json::array({{{"uri", "broken.png"}}});
    t.json["textures"] = json::array({{{"source", 0}}});
    t.json["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    t.json["meshes"][0]["primitives"][0]["material"] = 0;
    t.writeGltf(dir / "tex.gltf");
    msg = errorOf([&] { loadScene((dir / "tex.gltf").string()); });
    EXPECT_CONTAINS(msg, "tex.gltf");
    EXPECT_CONTAINS(msg, "broken.png");
}

TEST(Hardening, BenchAndTrainCheckTheirOptionsFirst) {
    const fs::path dir = makeTempDir("benchtrain");
    for (const char* opt : {"--width 0", "--height -4", "--width 20000", "--frames 0"}) {
        const CliRun r = run(std::string("bench ") + opt + " --out " + (dir / "b").string());
        expectOneLineError(r, {std::string(opt).substr(0, std::string(opt).find(' '))}, opt);
    }
    EXPECT_FALSE(fs::exists(dir / "b"));
    expectOneLineError(run("train --network starnt --out " + (dir / "x.txt").string()), {"x.txt", ".json"}, "txt");
    expectOneLineError(run("train --network starnt --out /proc/starnt_weights.json"), {"/proc", "cannot write"}, "proc");
    expectOneLineError(run("train --network starnt --out " + (dir / "nope/w.json").string()), {"does not exist"}, "dir");
    for (const auto& e : fs::directory_iterator(dir)) ADD_FAILURE() << "left behind: " << e.path();
}

// ---- 4. Exceptions from deep inside instead of a message ---------------------------------------

TEST(Hardening, DirectoriesWhereFilesBelong) {
    const fs::path dir = makeTempDir("dirs");
    fs::create_directories(dir / "bufdir");
    GltfBuilder g = oneTriangle();
    json j = g.finalJson(true);
    j["buffers"][0]["uri"] = "bufdir";
    writeText(dir / "bufdir.gltf", j.dump());
    std::string msg = errorOf([&] { loadScene((dir / "bufdir.gltf").string()); });
    EXPECT_CONTAINS(msg, "bufdir.gltf");
    EXPECT_CONTAINS(msg, "is a directory");

    const std::string a = smallPng(dir, "a.png");
    expectOneLineError(run("compare --reference " + a + " --test " + (dir / "bufdir").string()), {"bufdir", "is a directory"},
                       "compare");
    fs::create_directories(dir / "d.png");
    expectOneLineError(run("compare --reference " + (dir / "d.png").string() + " --test " + a), {"d.png", "is a directory"},
                       "compare png");
    expectOneLineError(run("render --width 16 --height 12 --scene " + (dir / "bufdir").string() + " --out " +
                           (dir / "x.png").string()),
                       {"bufdir", "is a directory"}, "scene");
    // Found by fuzz/fuzz_camera: a camera or camera-path "file" that is a directory escaped as
    // std::ios_failure from the JSON reader.
    const Bounds bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
    msg = errorOf([&] { parseCameraSpec((dir / "bufdir").string(), bounds, 1.5f); });
    EXPECT_CONTAINS(msg, "bufdir");
    EXPECT_CONTAINS(msg, "is a directory");
    msg = errorOf([&] { parseCameraPathSpec((dir / "bufdir").string(), bounds, 1.5f); });
    EXPECT_CONTAINS(msg, "is a directory");
    expectOneLineError(run("render --width 16 --height 12 --scene builtin:panes --camera " + (dir / "bufdir").string() +
                           " --out " + (dir / "x.png").string()),
                       {"bufdir", "is a directory"}, "camera");
}

TEST(Hardening, ImagesBeyondTheSizeLimit) {
    const fs::path dir = makeTempDir("bigimg");
    writePngHeader(dir / "huge.png", 16384, 16384);
    writePngHeader(dir / "wide.png", 16385, 1);
    for (const char* name : {"huge.png", "wide.png"}) {
        const std::string msg = errorOf([&] { loadImage((dir / name).string()); });
        EXPECT_CONTAINS(msg, name);
        EXPECT_CONTAINS(msg, "8192x8192");
        expectOneLineError(run("compare --reference " + (dir / name).string() + " --test " + (dir / name).string()),
                           {name, "larger than"}, name);
    }
}

// An EXR of a few hundred bytes whose header attribute claims 2 GB: OpenEXR would allocate the
// claimed size before reading it (found by fuzz/fuzz_image); the loader refuses it first.
TEST(Hardening, ExrAttributeLargerThanTheFile) {
    const fs::path dir = makeTempDir("exr_attr");
    const fs::path good = dir / "good.exr", bad = dir / "bad.exr";
    Image image(4, 3);
    for (float& v : image.rgba) v = 0.5f;
    saveImage(image, good.string());
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    // The first attribute follows the 8-byte signature and version: name NUL, type NUL, int32 size.
    const size_t nameEnd = bytes.find('\0', 8), typeEnd = bytes.find('\0', nameEnd + 1);
    ASSERT_NE(typeEnd, std::string::npos);
    const std::string attribute = bytes.substr(8, nameEnd - 8);
    const unsigned char huge[4] = {0x00, 0x00, 0x00, 0x7f};  // 2,130,706,432 bytes, little-endian
    bytes.replace(typeEnd + 1, 4, reinterpret_cast<const char*>(huge), 4);
    std::ofstream(bad, std::ios::binary) << bytes;
    EXPECT_EQ(loadImage(good.string()).width, 4);  // the walk accepts a well-formed file
    const std::string msg = errorOf([&] { loadImage(bad.string()); });
    EXPECT_CONTAINS(msg, "bad.exr");
    EXPECT_CONTAINS(msg, "'" + attribute + "'");
    EXPECT_CONTAINS(msg, "2130706432");
    expectOneLineError(run("compare --reference " + bad.string() + " --test " + good.string()), {"bad.exr", "claims"},
                       "exr attribute");
    // A data window wider than the tool reads is refused by the same walk, before OpenEXR sizes its
    // buffers by it: xMax (the third int32 of the box) becomes 19999.
    std::string wide((std::istreambuf_iterator<char>(std::ifstream(good, std::ios::binary).rdbuf())), {});
    const std::string key = std::string("dataWindow") + '\0' + "box2i" + '\0';
    const size_t box = wide.find(key);
    ASSERT_NE(box, std::string::npos);
    const unsigned char xMax[4] = {0x1f, 0x4e, 0x00, 0x00};  // 19999
    wide.replace(box + key.size() + 4 + 8, 4, reinterpret_cast<const char*>(xMax), 4);
    std::ofstream(dir / "wide.exr", std::ios::binary) << wide;
    const std::string wideMsg = errorOf([&] { loadImage((dir / "wide.exr").string()); });
    EXPECT_CONTAINS(wideMsg, "20000x3");
    EXPECT_CONTAINS(wideMsg, "larger than");
    // The fuzzer's out-of-memory inputs, rebuilt: OpenEXR reads the types it knows by structure and
    // ignores their declared sizes, so a lying size made it read a different header from the one
    // any check saw, here a data window 16,777,216 wide (a 2 GB line buffer). Every declared size
    // must now be true. First a channel list that claims 40 bytes more than it holds; under a
    // 1.5 GB address-space limit the command must end in that error, not in an allocation failure.
    std::string lying = wide;
    const size_t channelsSize = lying.find(std::string("chlist") + '\0') + 7;
    int32_t claimed = 0;
    std::memcpy(&claimed, lying.data() + channelsSize, 4);
    claimed += 40;
    std::memcpy(lying.data() + channelsSize, &claimed, 4);
    const unsigned char xMin[4] = {0x00, 0x00, 0x00, 0xff};  // -16,777,216
    lying.replace(box + key.size() + 4, 4, reinterpret_cast<const char*>(xMin), 4);
    std::ofstream(dir / "lying.exr", std::ios::binary) << lying;
    EXPECT_CONTAINS(errorOf([&] { loadImage((dir / "lying.exr").string()); }), "declares");
    // A data window of 2^32 x 2^32: the size check must not multiply the sides before checking
    // them (signed overflow; UBSan in the sanitizer suite, found by fuzz/fuzz_image).
    std::string giant = wide;
    const unsigned char corners[16] = {0x00, 0x00, 0x00, 0x80, 0x00, 0x00, 0x00, 0x80,
                                       0xff, 0xff, 0xff, 0x7f, 0xff, 0xff, 0xff, 0x7f};
    giant.replace(box + key.size() + 4, 16, reinterpret_cast<const char*>(corners), 16);
    std::ofstream(dir / "giant.exr", std::ios::binary) << giant;
    EXPECT_CONTAINS(errorOf([&] { loadImage((dir / "giant.exr").string()); }), "4294967296x4294967296");
#if !defined(__SANITIZE_ADDRESS__)
    expectOneLineError(run("compare --reference " + (dir / "lying.exr").string() + " --test " + good.string(),
                           "ulimit -v 1500000; "),
                       {"lying.exr", "'channels'", "declares"}, "lying channel list");
#endif
    // A preview attribute of 2^31-1 x 2^31-1 pixels declaring 8 bytes of pixels, inserted before
    // the end of the header: refused by its size (4 x w x h once overflowed the check: UBSan).
    const std::string plain((std::istreambuf_iterator<char>(std::ifstream(good, std::ios::binary).rdbuf())), {});
    size_t headerEnd = 8;
    while (plain[headerEnd] != '\0') {  // name NUL type NUL int32 size value, until an empty name
        const size_t typeStart = plain.find('\0', headerEnd) + 1, sizeAt = plain.find('\0', typeStart) + 1;
        int32_t bytes = 0;
        std::memcpy(&bytes, plain.data() + sizeAt, 4);
        headerEnd = sizeAt + 4 + size_t(bytes);
    }
    std::string preview = std::string("preview") + '\0' + "preview" + '\0';
    const int32_t previewFields[3] = {16, 0x7fffffff, 0x7fffffff};  // size, width, height
    preview.append(reinterpret_cast<const char*>(previewFields), 12).append(8, '\0');
    std::string withPreview = plain;
    withPreview.insert(headerEnd, preview);
    std::ofstream(dir / "preview.exr", std::ios::binary) << withPreview;
    EXPECT_CONTAINS(errorOf([&] { loadImage((dir / "preview.exr").string()); }),
                    "'preview' (a preview of 2147483647x2147483647) has 16 bytes");
    // Then a data window whose box2i declares 0 bytes (OpenEXR reads 16 regardless).
    std::string emptyBox = wide;
    const int32_t zero = 0;
    emptyBox.replace(box + key.size(), 4, reinterpret_cast<const char*>(&zero), 4);
    std::ofstream(dir / "emptybox.exr", std::ios::binary) << emptyBox;
    EXPECT_CONTAINS(errorOf([&] { loadImage((dir / "emptybox.exr").string()); }), "box2i has 0 bytes instead of 16");
    fs::remove_all(dir);
}

TEST(Hardening, SceneExhaustingMemoryNamesFileAndTriangles) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the ulimit this test sets";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    GTEST_SKIP() << "AddressSanitizer reserves more address space than the ulimit this test sets";
#endif
#endif
    // A 1.2 MB buffer of 100k triangles instanced by 3000 nodes: 300 million triangles to bake.
    const fs::path dir = makeTempDir("oom");
    std::vector<float> pos;
    for (int t = 0; t < 100000; ++t) {
        const float x = float(t % 300), y = float(t / 300);
        for (float v : {x, y, 0.0f, x + 1, y, 0.0f, x, y + 1, 0.0f}) pos.push_back(v);
    }
    GltfBuilder g = oneTriangle(pos, {});
    json nodes = json::array();
    json roots = json::array();
    for (int i = 0; i < 3000; ++i) {
        nodes.push_back({{"mesh", 0}, {"translation", {0, 0, double(i)}}});
        roots.push_back(i);
    }
    g.json["nodes"] = nodes;
    g.json["scenes"] = json::array({{{"nodes", roots}}});
    g.writeGlb(dir / "huge.glb");
    const CliRun r = run("render --width 16 --height 12 --scene " + (dir / "huge.glb").string() + " --out " +
                             (dir / "x.png").string(),
                         "ulimit -v 1500000; ");
    expectOneLineError(r, {"huge.glb", "out of memory", "300000000 triangles"}, "oom");
    EXPECT_FALSE(fs::exists(dir / "x.png"));
}

// ---- 5. Geometry and cameras -------------------------------------------------------------------

TEST(Hardening, AbsurdCoordinatesAreRejected) {
    const fs::path dir = makeTempDir("coords");
    oneTriangle({0, 0, 0, 1e19f, 0, 0, 0, 1, 0}).writeGlb(dir / "far.glb");
    std::string msg = errorOf([&] { loadScene((dir / "far.glb").string()); });
    EXPECT_CONTAINS(msg, "far.glb");
    EXPECT_CONTAINS(msg, "vertex 1");
    EXPECT_CONTAINS(msg, "1e18");
    writeText(dir / "far.obj", "v 0 0 0\nv 1 0 0\nv 0 -2e19 0\nf 1 2 3\n");
    msg = errorOf([&] { loadScene((dir / "far.obj").string()); });
    EXPECT_CONTAINS(msg, "far.obj:3");
    EXPECT_CONTAINS(msg, "vertex 3");
    // Large but representable scenes still load.
    oneTriangle({0, 0, 0, 1e17f, 0, 0, 0, 1e17f, 0}).writeGlb(dir / "big.glb");
    EXPECT_NO_THROW(loadScene((dir / "big.glb").string()));
}

TEST(Hardening, CameraUpZeroOrAlongTheView) {
    const fs::path dir = makeTempDir("camup");
    const Bounds b{glm::vec3(-1.0f), glm::vec3(1.0f)};
    writeText(dir / "zero.json", R"({"position": [0, 0, 5], "target": [0, 0, 0], "up": [0, 0, 0]})");
    std::string msg = errorOf([&] { parseCameraSpec((dir / "zero.json").string(), b, 1.0f); });
    EXPECT_CONTAINS(msg, "zero.json");
    EXPECT_CONTAINS(msg, "'up' [0, 0, 0] is a zero vector");
    writeText(dir / "par.json", R"({"position": [0, 5, 0], "target": [0, 0, 0], "up": [0, 2, 0]})");
    msg = errorOf([&] { parseCameraSpec((dir / "par.json").string(), b, 1.0f); });
    EXPECT_CONTAINS(msg, "par.json");
    EXPECT_CONTAINS(msg, "'up' [0, 2, 0] is parallel to the view direction");
    const std::string out = (dir / "x.png").string();
    expectOneLineError(run("render --scene builtin:panes --width 16 --height 12 --camera " + (dir / "zero.json").string() +
                           " --out " + out),
                       {"zero.json", "'up'"}, "cli");
    EXPECT_FALSE(fs::exists(out));
}

TEST(Hardening, KeyframePathThroughThePoleUsesFallbackUp) {
    // Halfway between the keys the camera looks straight down the up axis.
    const Bounds b{glm::vec3(-1.0f), glm::vec3(1.0f)};
    const CameraPath path =
        CameraPath::keyframes({{{-1, 5, 0}, {0, 0, 0}, 45.0f}, {{1, 5, 0}, {0, 0, 0}, 45.0f}}, b, glm::vec3(0, 1, 0));
    const Camera mid = path.at(0.5);
    EXPECT_NEAR(mid.position.x, 0.0f, 1e-6f);
    EXPECT_EQ(mid.up, glm::vec3(0, 0, -1));
    const glm::mat4 view = mid.view();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_TRUE(std::isfinite(view[c][r])) << c << "," << r;
    EXPECT_EQ(path.at(0.2).up, glm::vec3(0, 1, 0));  // elsewhere: the path's own up
}

TEST(Hardening, TextureWiderThanTheGlLimit) {
    const fs::path dir = makeTempDir("bigtex");
    savePng(Image(16385, 1, 0.5f), (dir / "wide.png").string());
    GltfBuilder t = oneTriangle();
    const std::vector<float> uv = {0, 0, 1, 0, 0, 1};
    t.json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = t.data(uv, kF32, 3, "VEC2");
    t.json["images"] = json::array({{{"uri", "wide.png"}}});
    t.json["textures"] = json::array({{{"source", 0}}});
    t.json["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    t.json["meshes"][0]["primitives"][0]["material"] = 0;
    t.writeGltf(dir / "wide.gltf");
    const std::string out = (dir / "x.png").string();
    expectOneLineError(run("render --width 16 --height 12 --scene " + (dir / "wide.gltf").string() + " --out " + out),
                       {"16385x1", "GL_MAX_TEXTURE_SIZE", "wide.gltf"}, "texture");
    EXPECT_FALSE(fs::exists(out));
}

// ---- 6. Command-line parse errors: one line ----------------------------------------------------

TEST(Hardening, ParseErrorsAreOneLine) {
    const fs::path dir = makeTempDir("parse");
    const std::string out = (dir / "x.png").string();
    expectOneLineError(run("render --scene builtin:panes --width abc --out " + out), {"--width"}, "number");
    expectOneLineError(run("render --scene builtin:panes --bogus-flag --out " + out), {"--bogus-flag"}, "unknown flag");
    expectOneLineError(run(""), {"subcommand"}, "no subcommand");
    expectOneLineError(run("render --scene builtin:panes"), {"--out"}, "missing --out");
    expectOneLineError(run("frobnicate"), {"frobnicate"}, "unknown subcommand");
    const CliRun help = run("render --help");
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("--scene"), std::string::npos);
}

// ---- 7. Unclear messages -----------------------------------------------------------------------

TEST(Hardening, ClearMessagesForRelativeFaceIndicesAndUnbackedAccessors) {
    const fs::path dir = makeTempDir("clear");
    writeText(dir / "neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -10 -11 -12\n");
    std::string msg = errorOf([&] { loadScene((dir / "neg.obj").string()); });
    EXPECT_CONTAINS(msg, "neg.obj:4");
    EXPECT_CONTAINS(msg, "vertex index -10 is out of range: only 3 vertices are defined");
    writeText(dir / "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "zero.obj").string()); }), "index '0'");
    // Found by fuzz/fuzz_obj: an index beyond long long saturated to LLONG_MIN, whose negation is
    // undefined behaviour; it is an out-of-range index like any other (either sign).
    writeText(dir / "huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -100000000000000000000000 1 2\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "huge.obj").string()); }), "is out of range");
    writeText(dir / "hugepos.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 100000000000000000000000 1 2\n");
    EXPECT_CONTAINS(errorOf([&] { loadScene((dir / "hugepos.obj").string()); }), "is out of range");

    // POSITION without a buffer view claiming 2^26 vertices in a file of a few hundred bytes.
    GltfBuilder g = oneTriangle();
    g.json["accessors"][0].erase("bufferView");
    g.json["accessors"][0].erase("byteOffset");
    g.json["accessors"][0]["count"] = 1 << 26;
    g.json["meshes"][0]["primitives"][0].erase("indices");
    g.writeGltf(dir / "claim.gltf");
    ASSERT_LT(fs::file_size(dir / "claim.gltf"), 2000u);
    msg = errorOf([&] { loadScene((dir / "claim.gltf").string()); });
    EXPECT_CONTAINS(msg, "claim.gltf");
    EXPECT_CONTAINS(msg, "no buffer view and claims 67108864 elements");
}

// ---- 8. No output left behind ------------------------------------------------------------------

TEST(Hardening, FailedRenderLeavesNoneOfItsOutputs) {
    const fs::path dir = makeTempDir("leftover");
    fs::create_directories(dir / "stats.json");
    const CliRun r = run("render --scene builtin:panes --method wboit --width 16 --height 12 --out " + (dir / "a.png").string() +
                         " --exr " + (dir / "a.exr").string() + " --stats " + (dir / "stats.json").string());
    expectOneLineError(r, {"stats.json", "is a directory"}, "stats dir");
    EXPECT_FALSE(fs::exists(dir / "a.png"));
    EXPECT_FALSE(fs::exists(dir / "a.exr"));

    // A sequence whose third frame cannot be written: no frame is left.
    fs::create_directories(dir / "seq");
    fs::create_directories(dir / "seq/f_0002.png");
    const CliRun s = run("render --scene builtin:panes --method wboit --width 16 --height 12 --frames 4 "
                         "--camera-path orbit:0,30 --out " + (dir / "seq/f_%04d.png").string());
    expectOneLineError(s, {"f_0002.png", "is a directory"}, "sequence");
    for (const auto& e : fs::directory_iterator(dir / "seq"))
        EXPECT_EQ(e.path().filename(), "f_0002.png") << "left behind: " << e.path();
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

// Found by trying the tool as a user would: options that were silently ignored or lost a file.
TEST(Hardening, SilentlyIgnoredOptionsAndCollidingOutputs) {
    const fs::path dir = makeTempDir("ignored");
    const std::string out = (dir / "x.png").string();
    // recommended with every frame real: asked for by name, so an error naming what to use.
    for (const char* t : {"off", "1"}) {
        expectOneLineError(run(std::string("render --scene builtin:panes --method recommended --width 16 --height 12 --temporal ") +
                               t + " --out " + out),
                           {"--temporal", "starnt-d"}, t);
    }
    EXPECT_FALSE(fs::exists(out));
    // Two outputs naming one file.
    expectOneLineError(run("render --scene builtin:panes --method starnt --width 16 --height 12 --out " + out + " --tiles-image " +
                           (dir / "." / "x.png").string()),
                       {"--out and --tiles-image name the same file"}, "same file");
    EXPECT_FALSE(fs::exists(out));
    // The reference A-buffer obeys --abuffer-cap-mib as the rendered one does, and the cap is
    // printed as given.
    const CliRun capped = run("render --scene builtin:panes --method wboit --reference-method abuffer --abuffer-cap-mib 0.01 "
                              "--width 64 --height 48 --out " + out);
    expectOneLineError(capped, {"memory cap of 0.01 MiB"}, "reference cap");
    EXPECT_FALSE(fs::exists(out));
    // A scene the camera does not see: the image is written, with a warning.
    const fs::path obj = dir / "far.obj";
    std::ofstream(obj) << "v 1e12 0 0\nv 1e12 1 0\nv 1e12 0 1\nf 1 2 3\n";
    const CliRun empty = run("render --scene " + obj.string() + " --method wboit --width 16 --height 12 --camera orbit:0 --out " + out);
    EXPECT_EQ(empty.exitCode, 0) << empty.err;
    EXPECT_CONTAINS(empty.err, "no fragment");
    const CliRun seen = run("render --scene builtin:panes --method wboit --width 16 --height 12 --out " + out);
    EXPECT_EQ(seen.err.find("no fragment"), std::string::npos) << seen.err;
}

// A flag the rendered method would ignore is an error naming it, as the acceleration flags were
// silently dropped by the methods without neural passes; two outputs that are one file however
// spelled, or one frame of a numbered sequence; compare's map over its own input; non-finite
// pixels in a compared image.
TEST(Hardening, IgnoredFlagsOutputsThatCollideAndNonFiniteImages) {
    const fs::path dir = makeTempDir("ignored-flags");
    const std::string out = (dir / "x.png").string();
    const std::string small = " --scene builtin:panes --width 16 --height 12 --out " + out;
    expectOneLineError(run("render --method wboit --temporal 2" + small), {"--temporal", "wboit", "no neural passes"}, "wboit temporal");
    expectOneLineError(run("render --method abuffer --scales 50,50" + small), {"--scales", "abuffer"}, "abuffer scales");
    expectOneLineError(run("render --method mboit --spatial on" + small), {"--spatial", "mboit"}, "mboit spatial");
    expectOneLineError(run("render --method starnt --peel-layers 2" + small), {"--peel-layers", "peel"}, "peel layers");
    expectOneLineError(run("render --method starnt --mboit-moments 4" + small), {"--mboit-moments", "mboit"}, "mboit moments");
    expectOneLineError(run("render --method starnt-d --temporal-mode refresh" + small), {"--temporal-mode", "every frame real"}, "mode at K 1");
    expectOneLineError(run("render --method starnt --target-fps 30" + small), {"--target-fps", "--temporal auto"}, "fps without auto");
    expectOneLineError(run("render --method starnt-d --scale-rule step" + small), {"--scale-rule", "no adaptive scales"}, "rule without tiles");
    expectOneLineError(run("render --method starnt --scales 50,50 --scale-guard off" + small), {"--scale-guard", "no adaptive scales"},
                       "guard with fixed scales");
    expectOneLineError(run("render --method starnt-d --tile-signal composite" + small), {"--tile-signal", "no adaptive tiles"},
                       "signal without tiles");
    EXPECT_FALSE(fs::exists(out));
    // What the methods do honour still runs.
    for (const std::string ok : {"render --method wboit --reference-method abuffer --abuffer-cap-mib 64",
                                 "render --method recommended --temporal-mode correct", "render --method starnt --scale-rule step",
                                 "render --method starnt --temporal auto --target-fps 30", "render --method peel --peel-layers 2"}) {
        const CliRun r = run(ok + small);
        EXPECT_EQ(r.exitCode, 0) << ok << ": " << r.err;
    }
    fs::remove(out);
    // Outputs: one file spelled two ways; a file that is one frame of the numbered output.
    const fs::path sub = dir / "sub";
    fs::create_directories(sub);
    const CliRun spelled = run("render --scene builtin:panes --method starnt --width 16 --height 12 --out " + (sub / "a.png").string() +
                               " --tiles-image " + (sub / ".." / "sub" / "a.png").string());
    expectOneLineError(spelled, {"--out and --tiles-image name the same file"}, "spelled two ways");
    const CliRun frame = run("render --scene builtin:panes --method starnt --width 16 --height 12 --frames 3 --out " +
                             (sub / "f_%04d.png").string() + " --tiles-image " + (sub / "f_0002.png").string());
    expectOneLineError(frame, {"--out and --tiles-image name the same file", "f_0002.png"}, "a frame of the sequence");
    expectOneLineError(run("render --scene builtin:panes --method starnt --width 16 --height 12 --frames 2 --out " + (sub / "a.png").string() +
                           " --stats " + (sub / "s_%04d.json").string()),
                       {"--stats", "one file for the whole run"}, "a pattern for the stats");
    EXPECT_TRUE(fs::is_empty(sub));
    // compare: the FLIP map over an input, and NaN in an EXR.
    const std::string ref = smallPng(dir, "ref.png");
    Image withNan(16, 12, 0.5f);
    withNan.rgba[4 * 17 + 1] = std::numeric_limits<float>::quiet_NaN();
    withNan.rgba[4 * 30] = std::numeric_limits<float>::infinity();
    const std::string nanExr = (dir / "nan.exr").string();
    saveExr(withNan, nanExr);
    const auto before = fs::file_size(ref);
    expectOneLineError(run("compare --reference " + ref + " --test " + ref + " --flip-map " + (dir / "." / "ref.png").string()),
                       {"--flip-map", "names an input image"}, "map over an input");
    EXPECT_EQ(fs::file_size(ref), before);
    expectOneLineError(run("compare --reference " + ref + " --test " + nanExr), {"nan.exr", "2 colour values are NaN or infinite", "pixel 1,1"},
                       "NaN in the test image");
    fs::remove_all(dir);
}

// glTF doubleSided false: a single-sided material the file made transparent shows its front faces
// only (its back faces were drawn as a second layer); one the file made opaque shows both when
// --alpha makes it transparent (its author left the back faces to the depth test). Two parallel
// quads of opposite winding: whichever way the camera looks, one faces it.
TEST(Hardening, SingleSidedMaterialsCullTheirBackFaces) {
    const fs::path dir = makeTempDir("single-sided");
    GltfBuilder g;
    const int pos = g.data(std::vector<float>{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, -0.1f, 1, 0, -0.1f, 1, 1, -0.1f, 0, 1, -0.1f},
                           kF32, 8, "VEC3");
    const int idx = g.data(std::vector<uint16_t>{0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6}, kU16, 12, "SCALAR");
    g.json["meshes"] = json::array({{{"primitives", json::array({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}, {"material", 0}}})}}});
    g.json["nodes"] = json::array({{{"mesh", 0}}});
    g.json["scenes"] = json::array({{{"nodes", {0}}}});
    auto maxFragments = [&](const std::string& alphaMode, bool doubleSided, const std::string& extra) {
        g.json["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.4, 0.2, 0.5}}}},
                                            {"alphaMode", alphaMode}, {"doubleSided", doubleSided}}});
        const fs::path file = dir / "quads.gltf";
        g.writeGltf(file);
        const CliRun r = run("render --scene " + file.string() + " --method abuffer --width 32 --height 24 --out " +
                             (dir / "q.png").string() + extra);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        const size_t at = r.out.find("max ");
        return at == std::string::npos ? -1 : std::atoi(r.out.c_str() + at + 4);
    };
    EXPECT_EQ(maxFragments("BLEND", false, ""), 1);
    EXPECT_EQ(maxFragments("BLEND", true, ""), 2);
    EXPECT_EQ(maxFragments("OPAQUE", false, " --alpha 0.5"), 2);
    EXPECT_EQ(maxFragments("BLEND", false, " --alpha 0.5"), 1);
    fs::remove_all(dir);
}

// A scene far from the origin for its size: float positions step by |x| 2^-23, which snapped six
// unit quads 1e7 away into one block with no word said; now a warning names the distance.
TEST(Hardening, AFarSceneForItsSizeIsWarnedAbout) {
    const fs::path dir = makeTempDir("far-origin");
    auto quadAt = [&](const char* name, double offset) {
        std::ofstream f(dir / name);
        f.precision(17);
        f << "v " << offset << " 0 0\nv " << offset + 1 << " 0 0\nv " << offset + 1 << " 1 0\nv " << offset << " 1 0\nf 1 2 3 4\n";
        return (dir / name).string();
    };
    const CliRun far = run("render --scene " + quadAt("far.obj", 1e7) + " --method wboit --width 16 --height 12 --out " + (dir / "a.png").string());
    EXPECT_EQ(far.exitCode, 0) << far.err;
    EXPECT_CONTAINS(far.err, "from the origin");
    const CliRun near = run("render --scene " + quadAt("near.obj", 1e3) + " --method wboit --width 16 --height 12 --out " + (dir / "b.png").string());
    EXPECT_EQ(near.exitCode, 0) << near.err;
    EXPECT_EQ(near.err.find("from the origin"), std::string::npos) << near.err;
    fs::remove_all(dir);
}

// Coplanar layers (overlapping sheets in one plane): pass 2 peels behind pass 1's depth, so it finds
// nothing among them, while pass 3 sums them all. The tail is then more than N - 2 fragments, with
// no second layer: the composites took N for the layers held and dropped or mis-weighed it (MSE
// 5.7e-4 against the A-buffer for starnt-d on 300 sheets at 160x120; 1.3e-9 now).
TEST(Hardening, CoplanarSheetsAreNotDropped) {
    const fs::path dir = makeTempDir("coplanar");
    const fs::path obj = dir / "sheets.obj";
    {
        std::ofstream f(obj);
        uint32_t state = 12345u;
        auto next = [&] {
            state = state * 1664525u + 1013904223u;
            return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
        };
        for (int t = 0; t < 60; ++t) {
            const float cx = next() * 0.7f, cy = next() * 0.7f;
            for (int v = 0; v < 3; ++v) f << "v " << cx + 0.5f * next() << " " << cy + 0.5f * next() << " 0\n";
            f << "f " << 3 * t + 1 << " " << 3 * t + 2 << " " << 3 * t + 3 << "\n";
        }
    }
    for (const char* method : {"starnt", "starnt-d", "hybrid-moments", "recommended"}) {
        const fs::path stats = dir / (std::string(method) + ".json");
        const CliRun r = run("render --scene " + obj.string() + " --alpha 0.4 --method " + method +
                             " --width 64 --height 48 --camera orbit:0 --reference-method abuffer --out " + (dir / "x.png").string() +
                             " --stats " + stats.string());
        ASSERT_EQ(r.exitCode, 0) << method << ": " << r.err;
        std::ifstream in(stats);
        const json j = json::parse(in);
        EXPECT_LT(j["error"]["real"]["mse_mean"].get<double>(), 1e-7) << method;
    }
}

TEST(Hardening, OutputFilesAppearTogetherOrNotAtAll) {
    const fs::path dir = makeTempDir("outfiles");
    {
        OutputFiles out;
        out.stage((dir / "a.txt").string(), "a");
        out.stage((dir / "b.txt").string(), "b");
        EXPECT_FALSE(fs::exists(dir / "a.txt"));
        fs::create_directories(dir / "b.txt");  // the target turns into a folder before commit
        EXPECT_CONTAINS(errorOf([&] { out.commit(); }), "b.txt");
    }
    EXPECT_FALSE(fs::exists(dir / "a.txt"));
    fs::remove(dir / "b.txt");
    {
        OutputFiles out;
        out.stage((dir / "c.txt").string(), "c");
    }  // never committed
    {
        OutputFiles out;
        out.stage((dir / "d.txt").string(), "d1");
        out.stage((dir / "d.txt").string(), "d2");
        out.commit();
    }
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"d.txt"});
    std::ifstream f(dir / "d.txt");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(f), {}), "d2");
}

// ---- 9. Progress and the temporal summary ------------------------------------------------------

TEST(Hardening, LongRendersShowProgressAndTemporalMeans) {
    const fs::path dir = makeTempDir("progress");
    const CliRun r = run("render --scene builtin:panes --method wboit --width 16 --height 12 --frames 6 --out " +
                             (dir / "a.png").string(),
                         "STARNT_PROGRESS_SECONDS=0 ");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_CONTAINS(r.err, "render: frame 3/6");
    EXPECT_CONTAINS(r.err, "render: frame 6/6");
    const CliRun quiet = run("render --scene builtin:panes --method wboit --width 16 --height 12 --frames 3 --out " +
                             (dir / "b.png").string());
    EXPECT_EQ(quiet.err.find("render: frame"), std::string::npos) << quiet.err;  // short: no progress

    const CliRun t = run("render --scene builtin:panes --method starnt --temporal 2 --width 32 --height 24 --frames 7 "
                         "--camera-path orbit:0,20 --out " + (dir / "t.png").string() + " --stats " + (dir / "t.json").string());
    ASSERT_EQ(t.exitCode, 0) << t.err;
    EXPECT_CONTAINS(t.out, "(mean of 6), real frames");
    EXPECT_CONTAINS(t.out, "interpolated");
    std::ifstream f(dir / "t.json");
    const json stats = json::parse(f);
    EXPECT_TRUE(stats["real_frame_ms_mean"].is_number());
    EXPECT_TRUE(stats["interpolated_frame_ms_mean"].is_number());
    // 6 timed frames of K = 2 hold 3 real ones, their share in the schedule: the long-run mean is the plain one.
    EXPECT_DOUBLE_EQ(stats["real_frame_share"].get<double>(), 0.5);
    EXPECT_NEAR(stats["frame_ms_long_run"].get<double>(),
                0.5 * (stats["real_frame_ms_mean"].get<double>() + stats["interpolated_frame_ms_mean"].get<double>()), 1e-9);
    EXPECT_CONTAINS(t.out, "a frame over a long run");
    EXPECT_EQ(t.out.find("no real frame was timed"), std::string::npos) << t.out;

    // Three frames at K = 4: the untimed first frame is the only real one, which the summary says
    // rather than printing a real-frame mean of nothing.
    const CliRun u = run("render --scene builtin:panes --method starnt --temporal 4 --width 32 --height 24 --frames 3 --out " +
                         (dir / "u.png").string());
    ASSERT_EQ(u.exitCode, 0) << u.err;
    EXPECT_CONTAINS(u.out, "real frames none timed");
    EXPECT_CONTAINS(u.out, "no real frame was timed");
}
