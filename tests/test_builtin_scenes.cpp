// Built-in procedural scenes: determinism, size, bounds, documented layouts, depth complexity.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"

using namespace starnt;

namespace {

// Maximum number of triangles covering one pixel centre when the scene is projected orthographically
// along -Z onto a size x size grid spanning [-1,1]^2 (what a camera on +Z framing the unit sphere sees,
// up to perspective). Counts surfaces, as D in the suite README does.
int maxDepthComplexity(const Scene& scene, int size) {
    std::vector<int> count(size_t(size) * size_t(size), 0);
    auto toPixel = [&](float v) { return (v + 1.0f) * 0.5f * float(size); };
    for (const Mesh& m : scene.meshes)
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec2 a(toPixel(m.positions[m.indices[t]].x), toPixel(m.positions[m.indices[t]].y));
            const glm::vec2 b(toPixel(m.positions[m.indices[t + 1]].x), toPixel(m.positions[m.indices[t + 1]].y));
            const glm::vec2 c(toPixel(m.positions[m.indices[t + 2]].x), toPixel(m.positions[m.indices[t + 2]].y));
            const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            if (area == 0.0f) continue;
            const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
            const int x1 = std::min(size - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
            const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
            const int y1 = std::min(size - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const glm::vec2 p(float(x) + 0.5f, float(y) + 0.5f);
                    const float w0 = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
                    const float w1 = (c.x - b.x) * (p.y - b.y) - (c.y - b.y) * (p.x - b.x);
                    const float w2 = (a.x - c.x) * (p.y - c.y) - (a.y - c.y) * (p.x - c.x);
                    const bool inside = area > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
                    if (inside) ++count[size_t(y) * size_t(size) + size_t(x)];
                }
        }
    return *std::max_element(count.begin(), count.end());
}

float maxRadius(const Scene& s) {
    float r = 0.0f;
    for (const Mesh& m : s.meshes)
        for (const glm::vec3& p : m.positions) r = std::max(r, glm::length(p));
    return r;
}

}  // namespace

TEST(BuiltinScenes, NamesAreListedAndLoadable) {
    const auto names = builtinSceneNames();
    EXPECT_EQ(names, (std::vector<std::string>{"tubes", "smoke", "panes", "random", "curtains", "courtyard"}));
    for (const std::string& n : names) {
        SCOPED_TRACE(n);
        Scene s = loadScene("builtin:" + n);
        EXPECT_EQ(s.name, n);
        EXPECT_GT(s.triangleCount(), 0u);
        EXPECT_LT(maxRadius(s), 1.5f);
        EXPECT_LT(glm::length(s.bounds().center()), 0.25f);
        EXPECT_GT(s.bounds().radius(), 0.5f);
        // courtyard is the one with opaque (OPAQUE, MASK) parts beside its transparent ones.
        size_t opaque = 0;
        for (const Material& m : s.materials) opaque += m.alphaMode != AlphaMode::Blend;
        EXPECT_EQ(opaque, n == "courtyard" ? 2u : 0u);
        std::printf("  builtin:%-7s %6zu triangles %6zu vertices, max depth complexity %d at 256x256\n", n.c_str(),
                    s.triangleCount(), s.vertexCount(), maxDepthComplexity(s, 256));
    }
}

TEST(BuiltinScenes, DeterministicPerSeed) {
    for (const std::string& n : builtinSceneNames()) {
        SCOPED_TRACE(n);
        const Scene a = makeBuiltinScene(n, 7), b = makeBuiltinScene(n, 7), c = makeBuiltinScene(n, 8);
        ASSERT_EQ(a.meshes.size(), b.meshes.size());
        for (size_t i = 0; i < a.meshes.size(); ++i) {
            EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
            EXPECT_EQ(a.meshes[i].colors, b.meshes[i].colors);
            EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        }
        if (n == "panes") {
            EXPECT_EQ(a.meshes[0].positions, c.meshes[0].positions);  // panes ignore the seed
        } else {
            EXPECT_NE(a.meshes[0].positions, c.meshes[0].positions);
        }
    }
}

TEST(BuiltinScenes, SizesAndAttributes) {
    const Scene tubes = makeBuiltinScene("tubes");
    EXPECT_EQ(tubes.triangleCount(), 150u * 48u * 6u * 2u);
    for (const Mesh& m : tubes.meshes) {
        EXPECT_EQ(m.normals.size(), m.positions.size());
        ASSERT_EQ(m.colors.size(), m.positions.size());
        for (const glm::vec4& c : m.colors) {
            EXPECT_GE(c.a, 0.2f);
            EXPECT_LE(c.a, 0.6f);
        }
        for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-4);
    }
    EXPECT_FALSE(tubes.materials[0].unlit);

    const Scene smoke = makeBuiltinScene("smoke");
    EXPECT_EQ(smoke.triangleCount(), 2400u);
    EXPECT_TRUE(smoke.materials[0].unlit);
    for (const Mesh& m : smoke.meshes) {
        ASSERT_EQ(m.colors.size(), m.positions.size());
        for (const glm::vec4& c : m.colors) {
            EXPECT_GE(c.a, 0.05f);
            EXPECT_LE(c.a, 0.4f);
        }
        // Quads face +Z: counter-clockwise in xy.
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]], c = m.positions[m.indices[t + 2]];
            EXPECT_EQ(a.z, b.z);
            EXPECT_EQ(a.z, c.z);
            EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
        }
    }

    const Scene random = makeBuiltinScene("random");
    EXPECT_EQ(random.triangleCount(), 60u);
    for (const Mesh& m : random.meshes) {
        ASSERT_EQ(m.colors.size(), m.positions.size());
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            EXPECT_EQ(m.colors[m.indices[t]], m.colors[m.indices[t + 1]]);
            EXPECT_EQ(m.colors[m.indices[t]], m.colors[m.indices[t + 2]]);
            EXPECT_GE(m.colors[m.indices[t]].a, 0.2f);
            EXPECT_LE(m.colors[m.indices[t]].a, 0.8f);
        }
        for (const glm::vec3& p : m.positions) EXPECT_LE(std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}), 1.0f);
    }
    EXPECT_TRUE(random.materials[0].unlit);

    // Curtains: 3 flat panes (2 triangles) and 3 pleated curtains (2 x 6..10 panels); one colour
    // per sheet, alpha 0.15-0.7, lit; the six sheet colours differ clearly.
    const Scene curtains = makeBuiltinScene("curtains");
    EXPECT_GE(curtains.triangleCount(), 3u * 2u + 3u * 24u);
    EXPECT_LE(curtains.triangleCount(), 3u * 2u + 3u * 40u);
    EXPECT_FALSE(curtains.materials[0].unlit);
    std::vector<glm::vec4> sheetColors;
    for (const Mesh& m : curtains.meshes) {
        ASSERT_EQ(m.colors.size(), m.positions.size());
        ASSERT_EQ(m.normals.size(), m.positions.size());
        for (const glm::vec4& c : m.colors) {
            EXPECT_GE(c.a, 0.15f);
            EXPECT_LE(c.a, 0.7f);
            if (sheetColors.empty() || sheetColors.back() != c) sheetColors.push_back(c);
        }
    }
    ASSERT_EQ(sheetColors.size(), 6u);
    for (size_t i = 0; i < 6; ++i)
        for (size_t j = i + 1; j < 6; ++j) EXPECT_GT(glm::length(glm::vec3(sheetColors[i] - sheetColors[j])), 0.3f);
}

TEST(BuiltinScenes, DepthComplexityFromPlusZ) {
    EXPECT_GE(maxDepthComplexity(makeBuiltinScene("tubes"), 256), 35);
    EXPECT_LE(maxDepthComplexity(makeBuiltinScene("tubes"), 256), 75);
    EXPECT_GE(maxDepthComplexity(makeBuiltinScene("smoke"), 256), 20);
    EXPECT_LE(maxDepthComplexity(makeBuiltinScene("smoke"), 256), 45);
    EXPECT_GE(maxDepthComplexity(makeBuiltinScene("random"), 256), 8);
    EXPECT_LE(maxDepthComplexity(makeBuiltinScene("random"), 256), 25);
    EXPECT_GE(maxDepthComplexity(makeBuiltinScene("curtains"), 256), 6);
    EXPECT_LE(maxDepthComplexity(makeBuiltinScene("curtains"), 256), 12);
}

TEST(BuiltinScenes, PanesMatchTheDocumentedLayout) {
    const auto panes = builtinPanes();
    ASSERT_GE(panes.size(), 4u);
    ASSERT_LE(panes.size(), 6u);
    const Scene s = makeBuiltinScene("panes");
    ASSERT_EQ(s.meshes.size(), panes.size());
    std::vector<float> zs;
    for (size_t i = 0; i < panes.size(); ++i) {
        SCOPED_TRACE(i);
        const BuiltinPane& p = panes[i];
        EXPECT_FLOAT_EQ(p.max.x - p.min.x, p.max.y - p.min.y);  // square
        EXPECT_GE(p.color.a, 0.3f);
        EXPECT_LE(p.color.a, 0.7f);
        const Mesh& m = s.meshes[i];
        EXPECT_EQ(m.indices.size(), 6u);
        EXPECT_TRUE(m.colors.empty());
        EXPECT_TRUE(m.uvs.empty());
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (const glm::vec3& v : m.positions) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        EXPECT_EQ(lo, glm::vec3(p.min, p.z));
        EXPECT_EQ(hi, glm::vec3(p.max, p.z));
        const Material& mat = s.materials[size_t(m.material)];
        EXPECT_TRUE(mat.unlit);
        EXPECT_EQ(mat.baseColorFactor, p.color);
        EXPECT_EQ(mat.baseColorTexture, -1);
        zs.push_back(p.z);
    }
    std::sort(zs.begin(), zs.end());
    EXPECT_TRUE(std::adjacent_find(zs.begin(), zs.end()) == zs.end()) << "pane depths must be distinct";
    // Expected composite at one point covered by red (z 0.4), green (0.2) and blue (0.0): front to back.
    const glm::vec2 q(0.0f, 0.0f);
    std::vector<BuiltinPane> covering;
    for (const BuiltinPane& p : panes)
        if (q.x > p.min.x && q.x < p.max.x && q.y > p.min.y && q.y < p.max.y) covering.push_back(p);
    std::sort(covering.begin(), covering.end(), [](const BuiltinPane& a, const BuiltinPane& b) { return a.z > b.z; });
    ASSERT_GE(covering.size(), 3u);
    glm::vec3 color(0.0f);
    float transmittance = 1.0f;
    for (const BuiltinPane& p : covering) {
        color += transmittance * p.color.a * glm::vec3(p.color);
        transmittance *= 1.0f - p.color.a;
    }
    EXPECT_GT(transmittance, 0.0f);
    EXPECT_LT(transmittance, 1.0f);
}

TEST(BuiltinScenes, UnknownNameListsValidNames) {
    try {
        loadScene("builtin:teapot");
        FAIL() << "expected starnt::Error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("teapot"), std::string::npos) << msg;
        for (const std::string& n : builtinSceneNames()) EXPECT_NE(msg.find(n), std::string::npos) << msg;
    }
}
