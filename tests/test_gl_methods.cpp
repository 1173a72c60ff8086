// The classic methods on a real GL context against the CPU references.
#include <gtest/gtest.h>

#include <cmath>

#include <stb/stb_image_write.h>

#include "gl/gl_util.hpp"
#include "gl/target_clears.hpp"
#include "reference/cpu_raster.hpp"
#include "reference/fragment_capture.hpp"
#include "render/offscreen_renderer.hpp"
#include "starnt/tools/camera.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/families.hpp"
#include "scene_test_helpers.hpp"
#include "test_support.hpp"

using namespace starnt;

namespace {

constexpr int kW = 96, kH = 72;
const glm::vec3 kBackground(0.2f, 0.5f, 0.9f);

using SceneSetup = test::TestScene;

SceneSetup makeSetup(const std::string& builtin, float azimuth = 20.0f) {
    return SceneSetup(makeBuiltinScene(builtin, 7), kW, kH, azimuth, 10.0f, kBackground);
}

RenderOutput render(const SceneSetup& s, const std::string& method, MethodOptions options = {}) {
    return s.render(method, options);
}

CpuRaster cpuReference(const SceneSetup& s) {
    return rasterizeUnlit(s.scene, s.camera.view(), s.camera.projection(s.aspect()), kW, kH, 0.03f);
}

// Compares the GPU image with `expected(list)` on every unambiguous pixel; returns pixels compared.
template <typename F>
size_t expectMatchesReference(const Image& gpu, const CpuRaster& ref, F expected, float tolerance = 1.0f / 255.0f) {
    EXPECT_FALSE(ref.clipped);
    size_t compared = 0, bad = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (ref.ambiguous[size_t(y) * kW + size_t(x)]) continue;
            glm::vec3 want = expected(ref.frame.at(x, y));
            const float* got = gpu.pixel(x, y);
            ++compared;
            for (int c = 0; c < 3; ++c) {
                if (!(std::abs(got[c] - want[c]) <= tolerance)) {
                    if (++bad <= 5) {
                        ADD_FAILURE() << "pixel (" << x << "," << y << ") channel " << c << ": gpu " << got[c]
                                      << " cpu " << want[c] << " (" << ref.frame.at(x, y).size() << " fragments)";
                    }
                }
            }
        }
    }
    EXPECT_EQ(bad, 0u);
    return compared;
}

glm::vec3 exactComposite(FragmentList list) {
    sortByDepth(list);
    return compositeOver(list, kBackground);
}

}  // namespace

// Memory accounting knows every format the methods allocate; any other is an internal error that
// names the format as GL headers spell it (it printed the decimal value after "0x" before).
TEST(GlMethods, TextureBytesPerTexelAndUnknownFormats) {
    EXPECT_EQ(gl::bytesPerTexel(GL_RGBA16F), 8u);
    EXPECT_EQ(gl::bytesPerTexel(GL_R16F), 2u);
    EXPECT_EQ(gl::bytesPerTexel(GL_DEPTH_COMPONENT32F), 4u);
    try {
        gl::bytesPerTexel(GL_RGB8);
        ADD_FAILURE() << "GL_RGB8 is not a format the methods use";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("0x8051"), std::string::npos) << e.what();
    }
}

TEST(GlMethods, AbufferMatchesCpuCompositorOnRandomTriangles) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    ASSERT_GE(ref.frame.maxDepthComplexity(), 4u) << "the scene should overlap";
    size_t n = expectMatchesReference(render(s, "abuffer").image, ref, exactComposite);
    EXPECT_GT(n, size_t(kW * kH) / 2);
}

TEST(GlMethods, PeelMatchesCpuCompositorOnRandomTriangles) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    RenderOutput out = render(s, "peel");
    expectMatchesReference(out.image, ref, exactComposite);
    EXPECT_EQ(out.stats["method_stats"]["layers"].get<size_t>(), out.stats["max_fragments"].get<size_t>());
}

TEST(GlMethods, AbufferMatchesCpuCompositorOnPanes) {
    SceneSetup s = makeSetup("panes", 0.0f);
    expectMatchesReference(render(s, "abuffer").image, cpuReference(s), exactComposite);
}

TEST(GlMethods, UnsortedMatchesSubmissionOrderBlend) {
    SceneSetup s = makeSetup("random");
    expectMatchesReference(render(s, "unsorted").image, cpuReference(s), [](FragmentList list) {
        // Later submissions land on top: composite newest first.
        sortBySubmission(list);
        std::reverse(list.begin(), list.end());
        return compositeOver(list, kBackground);
    });
}

TEST(GlMethods, WboitMatchesMcGuireBavoilFormula) {
    SceneSetup s = makeSetup("random");
    expectMatchesReference(render(s, "wboit").image, cpuReference(s),
                           [](const FragmentList& list) { return nn::compositeWboit(list, kBackground); });
}

TEST(GlMethods, CaptureSeesTheSameFragmentsAsTheCpuRasteriser) {
    SceneSetup s = makeSetup("random");
    CpuRaster ref = cpuReference(s);
    CapturedFrame got = s.capture();
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            if (ref.ambiguous[size_t(y) * kW + size_t(x)]) continue;
            FragmentList a = got.at(x, y), b = ref.frame.at(x, y);
            ASSERT_EQ(a.size(), b.size()) << "pixel " << x << "," << y;
            sortBySubmission(a);
            sortBySubmission(b);
            for (size_t i = 0; i < a.size(); ++i) {
                EXPECT_EQ(a[i].order, b[i].order);
                EXPECT_NEAR(a[i].depth, b[i].depth, 1e-5f);
                EXPECT_NEAR(a[i].alpha, b[i].alpha, 1e-3f);
                // Unlit: the colour is baseColorFactor x COLOR_0 exactly (docs/DESIGN.md, "Shading").
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[i].color[c], b[i].color[c], 1e-5f) << "pixel " << x << "," << y;
            }
        }
    }
}

namespace {

// An independent CPU shading of lit and textured surfaces, written here from the documented model
// rather than from the renderer's code (docs/DESIGN.md, "Shading", and "Scenes" for the texture
// transform): every other GPU-vs-CPU test takes its fragment colours from the capture, which runs
// the same surface shader as the methods, so a shading bug would be on both sides.
//   rgb   = base.rgb * (0.35 + 0.65 |n . v|) + emissive,   alpha = base.a,
//   base  = baseColorFactor x texture (sRGB-decoded, bilinear, REPEAT) x COLOR_0,
//   n     = the interpolated vertex normal, or the face normal without normals; v = towards the eye,
//   uv    = KHR_texture_transform: uv' = offset + R (scale uv), R turning counter-clockwise as the
//           image is seen (v pointing down), as the extension's text and its worked example say
//           (offset [0, 1], rotation 90 degrees, scale 0.5: the lower-left quadrant).
// The camera rays are built from the camera's position, target, up and field of view in double
// precision (not from its matrices), and intersected with the file's own triangles, which gives
// the perspective-correct barycentrics directly.
struct LitMeshSpec {
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals;  // empty: face normal
    std::vector<glm::dvec2> uvs;      // empty: no texture
    std::vector<glm::dvec4> colors;   // COLOR_0
    std::vector<uint16_t> indices;
    glm::dvec4 factor;
    glm::dvec3 emissive{0.0};
};

constexpr int kTexSize = 4;
struct TransformSpec {
    glm::dvec2 offset, scale;
    double rotation;
};

double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

glm::dvec2 transformedUv(const TransformSpec& t, glm::dvec2 uv) {
    const glm::dvec2 s = uv * t.scale;
    // Counter-clockwise as seen with v down: in y-up terms (u, -v), turned by +rotation, back to v down.
    const double c = std::cos(t.rotation), sn = std::sin(t.rotation);
    const glm::dvec2 upRotated(s.x * c - (-s.y) * sn, s.x * sn + (-s.y) * c);
    return t.offset + glm::dvec2(upRotated.x, -upRotated.y);
}

// GL_LINEAR magnification with GL_REPEAT on sRGB texels: decode each texel, then filter.
glm::dvec4 sampleBilinear(const std::vector<uint8_t>& rgba, glm::dvec2 uv) {
    const double x = uv.x * kTexSize - 0.5, y = uv.y * kTexSize - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    auto texel = [&](double tx, double ty) {
        const int i = ((int(tx) % kTexSize) + kTexSize) % kTexSize, j = ((int(ty) % kTexSize) + kTexSize) % kTexSize;
        const uint8_t* p = &rgba[size_t(j * kTexSize + i) * 4];
        return glm::dvec4(srgbToLinear(p[0] / 255.0), srgbToLinear(p[1] / 255.0), srgbToLinear(p[2] / 255.0), p[3] / 255.0);
    };
    return (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
           fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

}  // namespace

TEST(GlMethods, CaptureShadesLitTexturedSurfacesAsTheHeadlightModel) {
    using test::kF32;
    using test::kU16;
    // A textured quad with its own normal at each vertex, turned away from the camera, and a
    // triangle without normals (face normal) with an emissive colour, in front of it.
    LitMeshSpec quad{{{-1.0, -0.8, 0.4}, {1.0, -0.7, -0.8}, {0.9, 0.9, -0.6}, {-1.1, 0.8, 0.2}},
                     {{0.3, 0.2, 1.0}, {1.0, -0.4, 0.3}, {0.8, 0.7, 0.2}, {-0.6, 0.6, 0.5}},
                     {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}},
                     {{1.0, 0.9, 0.8, 1.0}, {0.7, 1.0, 0.9, 0.9}, {0.9, 0.8, 1.0, 0.8}, {1.0, 1.0, 0.6, 1.0}},
                     {0, 1, 2, 0, 2, 3},
                     {0.9, 0.8, 0.95, 0.8}};
    for (glm::dvec3& n : quad.normals) n = glm::normalize(n);
    LitMeshSpec tri{{{-0.9, -0.5, 0.9}, {0.4, -0.9, 0.2}, {-0.2, 0.6, 1.1}},
                    {},
                    {},
                    {{0.8, 0.3, 0.2, 0.6}, {0.2, 0.7, 0.3, 0.5}, {0.3, 0.4, 0.9, 0.7}},
                    {0, 1, 2},
                    {1.0, 0.9, 0.8, 0.9},
                    {0.05, 0.1, 0.0}};
    const TransformSpec transform{{0.3, -0.4}, {1.5, 0.75}, 0.6};
    // 4x4 sRGB texels of strongly different colours and alphas.
    std::vector<uint8_t> texels(kTexSize * kTexSize * 4);
    for (int i = 0; i < kTexSize * kTexSize; ++i) {
        texels[size_t(i) * 4 + 0] = uint8_t((i * 67 + 30) % 256);
        texels[size_t(i) * 4 + 1] = uint8_t((i * 131 + 90) % 256);
        texels[size_t(i) * 4 + 2] = uint8_t((i * 29 + 200) % 256);
        texels[size_t(i) * 4 + 3] = uint8_t(150 + (i * 37) % 106);
    }

    test::GltfBuilder g;
    nlohmann::json meshes = nlohmann::json::array(), nodes = nlohmann::json::array();
    int meshIndex = 0;
    for (const LitMeshSpec* m : {&quad, &tri}) {
        auto floats = [](const auto& vs, int n) {
            std::vector<float> out;
            for (const auto& v : vs)
                for (int k = 0; k < n; ++k) out.push_back(float(v[k]));
            return out;
        };
        nlohmann::json attributes = {{"POSITION", g.data(floats(m->positions, 3), kF32, m->positions.size(), "VEC3")},
                                     {"COLOR_0", g.data(floats(m->colors, 4), kF32, m->colors.size(), "VEC4")}};
        if (!m->normals.empty()) attributes["NORMAL"] = g.data(floats(m->normals, 3), kF32, m->normals.size(), "VEC3");
        if (!m->uvs.empty()) attributes["TEXCOORD_0"] = g.data(floats(m->uvs, 2), kF32, m->uvs.size(), "VEC2");
        meshes.push_back({{"primitives", nlohmann::json::array({{{"attributes", attributes},
                                                                  {"indices", g.data(m->indices, kU16, m->indices.size(), "SCALAR")},
                                                                  {"material", meshIndex}}})}});
        nodes.push_back({{"mesh", meshIndex}});
        ++meshIndex;
    }
    std::vector<uint8_t> png;
    stbi_write_png_to_func(
        [](void* ctx, void* data, int size) {
            auto* out = static_cast<std::vector<uint8_t>*>(ctx);
            out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
        },
        &png, kTexSize, kTexSize, 4, texels.data(), kTexSize * 4);
    g.json["meshes"] = meshes;
    g.json["nodes"] = nodes;
    g.json["scenes"] = nlohmann::json::array({{{"nodes", {0, 1}}}});
    g.json["scene"] = 0;
    g.json["images"] = nlohmann::json::array({{{"uri", "data:image/png;base64," + test::base64(png)}}});
    g.json["textures"] = nlohmann::json::array({{{"source", 0}}});
    g.json["materials"] = nlohmann::json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorFactor", {quad.factor.r, quad.factor.g, quad.factor.b, quad.factor.a}},
            {"baseColorTexture",
             {{"index", 0},
              {"extensions", {{"KHR_texture_transform", {{"offset", {transform.offset.x, transform.offset.y}},
                                                         {"rotation", transform.rotation},
                                                         {"scale", {transform.scale.x, transform.scale.y}}}}}}}}}},
          {"alphaMode", "BLEND"},
          {"doubleSided", true}},
         {{"pbrMetallicRoughness", {{"baseColorFactor", {tri.factor.r, tri.factor.g, tri.factor.b, tri.factor.a}}}},
          {"emissiveFactor", {tri.emissive.r, tri.emissive.g, tri.emissive.b}},
          {"alphaMode", "BLEND"},
          {"doubleSided", true}}});
    g.json["extensionsUsed"] = {"KHR_texture_transform"};
    const std::filesystem::path dir = test::makeTempDir("lit_textured");
    g.writeGltf(dir / "lit.gltf");

    SceneSetup s(loadGltf((dir / "lit.gltf").string()), kW, kH, 0.0f, 0.0f, kBackground);
    s.camera.position = glm::vec3(0.4f, 0.3f, 3.2f);
    s.camera.target = glm::vec3(0.0f, 0.0f, 0.0f);
    s.camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    s.camera.fovYDeg = 50.0f;
    s.camera.nearPlane = 0.5f;
    s.camera.farPlane = 10.0f;
    const CapturedFrame got = s.capture();

    const glm::dvec3 eye(s.camera.position), forward = glm::normalize(glm::dvec3(s.camera.target) - eye);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(s.camera.up)));
    const glm::dvec3 upAxis = glm::cross(right, forward);
    const double tanHalf = std::tan(glm::radians(double(s.camera.fovYDeg)) / 2), aspect = double(kW) / kH;
    size_t compared = 0, lambertBelowHalf = 0;
    double worst = 0;
    for (int y = 0; y < kH; ++y) {
        for (int x = 0; x < kW; ++x) {
            const double ndcX = (x + 0.5) / kW * 2 - 1, ndcY = 1 - (y + 0.5) / kH * 2;
            const glm::dvec3 dir = forward + ndcX * tanHalf * aspect * right + ndcY * tanHalf * upAxis;
            for (const Fragment& f : got.at(x, y)) {
                const uint32_t mesh = f.order >> 24, prim = f.order & 0xFFFFFFu;
                ASSERT_LT(mesh, 2u);
                const LitMeshSpec& m = mesh == 0 ? quad : tri;
                ASSERT_LT(size_t(prim) * 3 + 2, m.indices.size());
                const uint16_t i0 = m.indices[prim * 3], i1 = m.indices[prim * 3 + 1], i2 = m.indices[prim * 3 + 2];
                // Ray-triangle intersection (barycentrics b1, b2 of vertices i1, i2).
                const glm::dvec3 e1 = m.positions[i1] - m.positions[i0], e2 = m.positions[i2] - m.positions[i0];
                const glm::dvec3 pv = glm::cross(dir, e2);
                const double det = glm::dot(e1, pv);
                const glm::dvec3 tv = eye - m.positions[i0], qv = glm::cross(tv, e1);
                const double b1 = glm::dot(tv, pv) / det, b2 = glm::dot(dir, qv) / det, b0 = 1 - b1 - b2;
                // A fragment whose centre the ray finds outside its triangle: a capture bug.
                ASSERT_GT(std::min({b0, b1, b2}), -1e-4) << "pixel " << x << "," << y << " mesh " << mesh;
                const glm::dvec3 point = b0 * m.positions[i0] + b1 * m.positions[i1] + b2 * m.positions[i2];
                auto lerp = [&](const auto& a) { return b0 * a[i0] + b1 * a[i1] + b2 * a[i2]; };
                glm::dvec4 base = m.factor * lerp(m.colors);
                if (!m.uvs.empty()) base *= sampleBilinear(texels, transformedUv(transform, lerp(m.uvs)));
                const glm::dvec3 n = m.normals.empty() ? glm::cross(e1, e2) : lerp(m.normals);
                const double lambert = std::abs(glm::dot(glm::normalize(n), glm::normalize(eye - point)));
                if (lambert < 0.5) ++lambertBelowHalf;
                const glm::dvec3 want = glm::dvec3(base) * (0.35 + 0.65 * lambert) + m.emissive;
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(f.color[c]) - want[c]));
                worst = std::max(worst, std::abs(double(f.alpha) - base.a));
                ++compared;
            }
        }
    }
    // Measured on llvmpipe: at most 8.0e-4 (desktop GL and ES), the texture filter's fixed-point
    // weights; the ambient term 0.35 -> 0.30 moves these colours by up to 2e-2.
    EXPECT_LT(worst, 1.2e-3) << compared << " fragments";
    EXPECT_GT(compared, size_t(kW * kH) / 3);
    EXPECT_GT(lambertBelowHalf, compared / 10) << "the surfaces should turn away from the headlight";
    std::printf("worst %.6f over %zu fragments, %zu with |n.v| < 0.5\n", worst, compared, lambertBelowHalf);
}

TEST(GlMethods, AbufferPoolFarTooSmallStillGivesTheExactImage) {
    SceneSetup s = makeSetup("random");
    MethodOptions tiny;
    tiny.abuffer.initialNodesPerPixel = 0.01;
    // The regrow note goes to the engine's log callback (never to stderr from the library).
    testing::internal::CaptureStderr();
    std::string logged;
    RenderOutput small;
    {
        test::CapturedLog log;
        small = render(s, "abuffer", tiny);
        logged = log.text();
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_NE(logged.find("note: A-buffer pool overflow"), std::string::npos) << logged;
    RenderOutput normal = render(s, "abuffer");
    EXPECT_GE(small.stats["method_stats"]["pool_regrows"].get<int>(), 1);
    EXPECT_EQ(normal.stats["method_stats"]["pool_regrows"].get<int>(), 0);
    ASSERT_EQ(small.image.rgba.size(), normal.image.rgba.size());
    for (size_t i = 0; i < small.image.rgba.size(); ++i) ASSERT_EQ(small.image.rgba[i], normal.image.rgba[i]);
}

TEST(GlMethods, AbufferMemoryCapFailsWithClearError) {
    SceneSetup s = makeSetup("random");
    MethodOptions capped;
    capped.abuffer.initialNodesPerPixel = 0.01;
    capped.abuffer.memoryCapBytes = size_t(kW) * kH * 4 + 4096;
    try {
        render(s, "abuffer", capped);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("memory cap"), std::string::npos) << e.what();
    }
}

TEST(GlMethods, TypedFrameStatsFillTheirMethodsGroupOnly) {
    SceneSetup s = makeSetup("random");
    const CapturedFrame captured = s.capture();
    size_t fragments = 0;
    for (const auto& list : captured.pixels) fragments += list.size();
    const FrameDesc frame = s.frame();
    for (const std::string m : {"abuffer", "peel", "mboit", "wboit", "starnt"}) {
        auto method = createMethod(m, SceneGpu::surfaceShader());
        method->render(frame, s.gpu->callback(frame.view, frame.projection, {}));
        const FrameStats st = method->lastFrameStats();
        EXPECT_EQ(st.abuffer.has_value(), m == "abuffer") << m;
        EXPECT_EQ(st.peel.has_value(), m == "peel") << m;
        EXPECT_EQ(st.mboit.has_value(), m == "mboit") << m;
        EXPECT_EQ(st.neural.has_value(), m == "starnt") << m;
        EXPECT_FALSE(st.interpolated()) << m;
        if (st.abuffer) EXPECT_EQ(st.abuffer->fragments, fragments) << m;
        if (st.peel) EXPECT_EQ(size_t(st.peel->layers), captured.maxDepthComplexity()) << m;
        if (st.neural) {
            EXPECT_EQ(st.neural->network, "starnt");
            ASSERT_TRUE(st.neural->tiles.has_value());  // starnt runs its tiles by default
            EXPECT_EQ(st.neural->pass2Size.width, frame.width);  // first frame: full resolution
            EXPECT_EQ(st.neural->scalePass3, 1.0f);
        }
    }
}

TEST(GlMethods, StatsReportMemoryAndFragments) {
    SceneSetup s = makeSetup("random");
    for (const char* m : {"abuffer", "peel", "unsorted", "wboit"}) {
        RenderOutput out = render(s, m);
        EXPECT_GE(out.stats["memory_bytes"].get<size_t>(), size_t(kW) * kH * 16) << m;
        EXPECT_EQ(out.stats["max_fragments"].get<size_t>(), cpuReference(s).frame.maxDepthComplexity()) << m;
    }
}

// gl::TargetClears: on llvmpipe a clear of a 16-byte target becomes copies from a strip
// (docs/DESIGN.md, "Findings on Mesa llvmpipe": clears). The copies must write exactly what
// glClearBufferfv writes under the same state: the scissor box (or the whole target), the value as
// the clear converts it, nothing else; and leave the bindings as they were.
TEST(TargetClears, CopiesWriteWhatTheClearWrites) {
    test::glContext();
    constexpr int w = 70, h = 37;  // not a multiple of the strip (16 x 4 below): partial strips
    std::vector<float> garbage(size_t(w) * h * 4);
    for (size_t i = 0; i < garbage.size(); ++i) garbage[i] = float(i % 97) * 0.25f - 3.0f;
    const float packedEmpty[4] = {1.5e9f, -2.0f, 0.125f, 7.0f};
    struct Case {
        GLenum format;
        bool scissor;
        bool mask;  // a colour mask on the cleared buffer
    } cases[] = {{GL_RGBA32F, true, false}, {GL_RGBA32F, false, false}, {GL_RGBA32F, true, true}, {GL_RGBA16F, true, false}};
    for (const Case& c : cases) {
        SCOPED_TRACE(testing::Message() << "format 0x" << std::hex << c.format << " scissor " << c.scissor << " mask " << c.mask);
        gl::Texture2D targets[2] = {gl::Texture2D(c.format, w, h), gl::Texture2D(c.format, w, h)};
        gl::TargetClears clears[2] = {gl::TargetClears(gl::TargetClears::Path::Copy, 16, 4),
                                      gl::TargetClears(gl::TargetClears::Path::Clear)};
        gl::Texture2D other(GL_RGBA8, w, h), bound(GL_RGBA8, 4, 4);
        for (int k = 0; k < 2; ++k) {
            gl::uploadTexture(targets[k].id(), w, h, GL_RGBA, GL_FLOAT, garbage.data());
            const gl::FramebufferHandle fb = gl::makeFramebuffer({&other, &targets[k]});  // the target at draw buffer 1
            glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
            glActiveTexture(GL_TEXTURE3);  // the active unit's binding, which the copy must leave
            glBindTexture(GL_TEXTURE_2D, bound.id());
            if (c.scissor) {
                glEnable(GL_SCISSOR_TEST);
                glScissor(5, 3, 50, 30);
            }
            if (c.mask) glColorMaski(1, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
            clears[k].color(1, packedEmpty);
            GLint drawFb = 0, unitBinding = 0;
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFb);
            glGetIntegerv(GL_TEXTURE_BINDING_2D, &unitBinding);
            EXPECT_EQ(GLuint(drawFb), fb.id());
            EXPECT_EQ(GLuint(unitBinding), bound.id());
            EXPECT_EQ(bool(glIsEnabled(GL_SCISSOR_TEST)), c.scissor);
            glColorMaski(1, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            glDisable(GL_SCISSOR_TEST);
            glActiveTexture(GL_TEXTURE0);
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
        }
        const std::vector<float> copied = gl::readTextureFloats(targets[0].id(), w, h, 4);
        const std::vector<float> cleared = gl::readTextureFloats(targets[1].id(), w, h, 4);
        size_t differ = 0, changed = 0;
        for (size_t i = 0; i < copied.size(); ++i) {
            differ += copied[i] != cleared[i];
            changed += cleared[i] != garbage[i];
        }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(changed, 0u);  // the clear wrote something, so the comparison means something
        // Strips only where the copy stands in: 16-byte texels without a colour mask.
        const bool copiedByStrip = c.format == GL_RGBA32F && !c.mask;
        EXPECT_EQ(clears[0].bytes(), copiedByStrip ? size_t(16 * 4 * 16) : size_t(0));
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    }
    // A caller whose clear values keep changing reuses strips instead of growing the list; the
    // last value is still the one written.
    gl::Texture2D target(GL_RGBA32F, w, h);
    const gl::FramebufferHandle fb = gl::makeFramebuffer({&target});
    glBindFramebuffer(GL_FRAMEBUFFER, fb.id());
    gl::TargetClears changing(gl::TargetClears::Path::Copy, 16, 4);
    for (int i = 0; i < 9; ++i) {
        const float value[4] = {float(i), 0.5f, -float(i), 1.0f};
        changing.color(0, value);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    EXPECT_EQ(changing.bytes(), size_t(4 * 16 * 4 * 16));
    const std::vector<float> last = gl::readTextureFloats(target.id(), w, h, 4);
    size_t wrong = 0;
    for (size_t i = 0; i < last.size(); i += 4) wrong += last[i] != 8.0f || last[i + 1] != 0.5f || last[i + 2] != -8.0f || last[i + 3] != 1.0f;
    EXPECT_EQ(wrong, 0u);
}
