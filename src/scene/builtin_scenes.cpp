// Built-in procedural scenes. All are centred near the origin with radius about 1 and are
// deterministic for a given seed: random numbers come from std::mt19937 (whose output sequence the
// standard fixes) mapped to floats by hand, never through std::*_distribution, whose results differ
// between standard libraries.
//
//   tubes  - hairball-like tangle: 150 smooth random curves inside the unit sphere, each swept as a
//            6-sided tube of radius 0.012 (48 segments), lit, with normals; per-tube colour and
//            alpha (0.2-0.6) in COLOR_0; one mesh, one white material. 86,400 triangles.
//            Max depth complexity from +Z at 256x256: 40-50 surfaces (seeds 1-8; 44 for seed 1).
//   smoke  - 1,200 camera-facing quads (normal +Z, counter-clockwise seen from +Z) with centres in
//            the box [-0.7,0.7]^2 x [-0.6,0.6], half-size 0.04-0.12, per-particle colour and alpha
//            (0.05-0.4) in COLOR_0, unlit. 2,400 triangles; max depth complexity 29-36.
//   panes  - five unlit axis-aligned squares perpendicular to Z; seed-independent, see builtinPanes().
//   random - 60 large triangles in [-1,1]^3 (roughly equilateral, circumradius 0.28-0.5, centres in
//            [-0.55,0.55]^2 x [-0.5,0.5], each vertex's z jittered by 0.2), each with one flat COLOR_0
//            (alpha 0.2-0.8), unlit. Max depth complexity 13-19.
//   curtains - 6 large sheets of clearly different colours (hues spread around the circle) with
//            alpha 0.15-0.7 in COLOR_0 (docs/DESIGN.md, "hybrid-moments and starnt-d" user trial: curtains and glazing): sheets 0, 2, 4
//            are flat glazing panes, sheets 1, 3, 5 pleated curtains (6-10 pleats 0.12-0.25 deep, so
//            oblique views cross one curtain several times); 1.1-1.5 wide, 1.3-1.6 tall, centres at
//            z in [-0.6, 0.6], turned by up to 25 degrees about Y; lit, with normals. Max depth
//            complexity from +Z 6-12.
//   courtyard - opaque and transparent parts together (docs/DESIGN.md, "Opaque geometry"): an OPAQUE
//            floor, back wall and four square pillars (lit, per-face colours in COLOR_0); 8 BLEND
//            glass panes (alpha 0.2-0.5, tinted, lit) at depths in front of, between and behind the
//            pillars; 60 MASK foliage quads (cut-off 0.5, COLOR_0 alpha 0.2 or 0.9 per quad, so about
//            half are cut away) and 240 faint BLEND smoke quads (alpha 0.05-0.25, unlit) around them.
//            Under an alpha override (--alpha) every part is transparent.
//   Depth complexities: maximum triangles over one pixel centre, orthographic along -Z over [-1,1]^2.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "scene/catmull_rom.hpp"
#include "scene/hue_color.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt {

namespace {

// The built-in scenes' own generator (mt19937, 24-bit floats): it fixes their geometry, which every
// figure measured on them depends on, so it stays apart from the trainer's nn::detail::Rng.
class SceneRng {
public:
    explicit SceneRng(uint32_t seed) : gen_(seed) {}
    // Uniform in [0, 1) from the top 24 bits of one mt19937 output.
    float uniform() { return float(gen_() >> 8) * (1.0f / 16777216.0f); }
    float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    // A point uniform in the box [lo, hi], drawn x, then y, then z.
    glm::vec3 inBox(const glm::vec3& lo, const glm::vec3& hi) {
        const float x = range(lo.x, hi.x);
        const float y = range(lo.y, hi.y);
        const float z = range(lo.z, hi.z);
        return {x, y, z};
    }
    glm::vec3 inBall(float radius) {
        for (;;) {
            // One statement per draw: argument evaluation order is unspecified in C++.
            const float x = range(-1.0f, 1.0f);
            const float y = range(-1.0f, 1.0f);
            const float z = range(-1.0f, 1.0f);
            const glm::vec3 p(x, y, z);
            if (glm::dot(p, p) <= 1.0f) return p * radius;
        }
    }

private:
    std::mt19937 gen_;
};

// A saturated-ish random colour: a random hue at full saturation, mixed with white by `pastel`.
glm::vec3 randomColor(SceneRng& rng, float pastel) { return hueColor<float>(rng.uniform(), pastel); }

Material blendMaterial(bool unlit) {
    Material m;
    m.baseColorFactor = glm::vec4(1.0f);
    m.unlit = unlit;
    m.doubleSided = true;
    m.alphaMode = AlphaMode::Blend;
    return m;
}

// The shape of tubes, smoke, random and curtains: one mesh of `count` seeded random items under one
// double-sided blend material; appendItem(rng, mesh, i) adds item i, drawing from rng in order.
template <class AppendItem>
Scene oneMeshScene(uint32_t seed, bool unlit, int count, AppendItem&& appendItem) {
    SceneRng rng(seed);
    Scene s;
    s.materials.push_back(blendMaterial(unlit));
    Mesh mesh;
    for (int i = 0; i < count; ++i) appendItem(rng, mesh, i);
    s.meshes.push_back(std::move(mesh));
    return s;
}

glm::vec3 anyPerpendicular(const glm::vec3& t) {
    const glm::vec3 a = std::fabs(t.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(t, a));
}

// Appends the quad corners[0..3] (counter-clockwise seen from the side `normal` points to) as two
// triangles with one normal and one colour.
void appendQuad(Mesh& mesh, const std::array<glm::vec3, 4>& corners, const glm::vec3& normal, const glm::vec4& color) {
    const uint32_t base = uint32_t(mesh.positions.size());
    for (const glm::vec3& c : corners) {
        mesh.positions.push_back(c);
        mesh.normals.push_back(normal);
        mesh.colors.push_back(color);
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// A square of half-size h around `centre`, facing +Z (a particle, a leaf).
void appendFacingSquare(Mesh& mesh, const glm::vec3& centre, float h, const glm::vec4& color) {
    appendQuad(mesh, {centre + glm::vec3(-h, -h, 0), centre + glm::vec3(h, -h, 0), centre + glm::vec3(h, h, 0), centre + glm::vec3(-h, h, 0)},
               {0, 0, 1}, color);
}

Scene makeTubes(uint32_t seed) {
    static constexpr int kTubes = 150, kControl = 7, kSegments = 48, kSides = 6;
    static constexpr float kRadius = 0.012f, kSphere = 0.85f;
    return oneMeshScene(seed, false, kTubes, [](SceneRng& rng, Mesh& mesh, int) {
        std::vector<glm::vec3> ctrl(kControl);
        for (glm::vec3& c : ctrl) c = rng.inBall(kSphere);
        const glm::vec3 rgb = randomColor(rng, 0.3f);
        const glm::vec4 color(rgb, rng.range(0.2f, 0.6f));
        // Centre line: uniform Catmull-Rom through the inner control points (the ends are guides).
        std::vector<glm::vec3> line(kSegments + 1);
        for (int i = 0; i <= kSegments; ++i) {
            const float u = float(i) / float(kSegments) * float(kControl - 3);
            const int seg = std::min(int(u), kControl - 4);
            line[size_t(i)] = catmullRom(ctrl[size_t(seg)], ctrl[size_t(seg + 1)], ctrl[size_t(seg + 2)],
                                         ctrl[size_t(seg + 3)], u - float(seg));
        }
        // Parallel-transport frames avoid twisting.
        glm::vec3 normal(0.0f);
        const uint32_t base = uint32_t(mesh.positions.size());
        for (int i = 0; i <= kSegments; ++i) {
            const glm::vec3 d = line[size_t(std::min(i + 1, kSegments))] - line[size_t(std::max(i - 1, 0))];
            const glm::vec3 tangent = glm::length(d) > 1e-12f ? glm::normalize(d) : glm::vec3(0, 0, 1);
            glm::vec3 nrm = i == 0 ? anyPerpendicular(tangent) : normal - glm::dot(normal, tangent) * tangent;
            nrm = glm::length(nrm) > 1e-6f ? glm::normalize(nrm) : anyPerpendicular(tangent);
            normal = nrm;
            const glm::vec3 binormal = glm::cross(tangent, nrm);
            for (int k = 0; k < kSides; ++k) {
                const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(kSides);
                const glm::vec3 radial = std::cos(a) * nrm + std::sin(a) * binormal;
                mesh.positions.push_back(line[size_t(i)] + kRadius * radial);
                mesh.normals.push_back(radial);
                mesh.colors.push_back(color);
            }
        }
        // Counter-clockwise seen from outside the tube.
        for (int i = 0; i < kSegments; ++i)
            for (int k = 0; k < kSides; ++k) {
                const uint32_t a = base + uint32_t(i * kSides + k);
                const uint32_t b = base + uint32_t(i * kSides + (k + 1) % kSides);
                const uint32_t c = a + kSides, d = b + kSides;
                mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
            }
    });
}

Scene makeSmoke(uint32_t seed) {
    constexpr int kParticles = 1200;
    return oneMeshScene(seed, true, kParticles, [](SceneRng& rng, Mesh& mesh, int) {
        const glm::vec3 centre = rng.inBox({-0.7f, -0.7f, -0.6f}, {0.7f, 0.7f, 0.6f});
        const float h = rng.range(0.04f, 0.12f);
        const float grey = rng.range(0.55f, 0.95f);
        const glm::vec3 tint = randomColor(rng, 0.85f);
        appendFacingSquare(mesh, centre, h, glm::vec4(grey * tint, rng.range(0.05f, 0.4f)));
    });
}

Scene makePanes() {
    Scene s;
    for (const BuiltinPane& p : builtinPanes()) {
        Material m = blendMaterial(true);
        m.baseColorFactor = p.color;
        s.materials.push_back(m);
        Mesh mesh;
        mesh.positions = {{p.min.x, p.min.y, p.z}, {p.max.x, p.min.y, p.z}, {p.max.x, p.max.y, p.z}, {p.min.x, p.max.y, p.z}};
        mesh.normals.assign(4, glm::vec3(0.0f, 0.0f, 1.0f));
        mesh.indices = {0, 1, 2, 0, 2, 3};
        mesh.material = int(s.materials.size()) - 1;
        s.meshes.push_back(std::move(mesh));
    }
    return s;
}

Scene makeRandom(uint32_t seed) {
    constexpr int kTriangles = 60;
    return oneMeshScene(seed, true, kTriangles, [](SceneRng& rng, Mesh& mesh, int) {
        // A roughly equilateral triangle (circumradius 0.6-0.95, jittered angles) around a centre
        // near the middle, each vertex at its own depth, clamped to the box.
        const glm::vec3 centre = rng.inBox({-0.55f, -0.55f, -0.5f}, {0.55f, 0.55f, 0.5f});
        const glm::vec2 c(centre);
        const float cz = centre.z;
        const float r = rng.range(0.28f, 0.5f);
        const float a0 = rng.range(0.0f, 2.0f * std::numbers::pi_v<float>);
        const glm::vec3 rgb = randomColor(rng, 0.1f);
        const glm::vec4 color(rgb, rng.range(0.2f, 0.8f));
        const uint32_t base = uint32_t(mesh.positions.size());
        for (int k = 0; k < 3; ++k) {
            const float a = a0 + float(k) * 2.0f * std::numbers::pi_v<float> / 3.0f + rng.range(-0.3f, 0.3f);
            const float dz = rng.range(-0.2f, 0.2f);
            glm::vec3 v(c.x + r * std::cos(a), c.y + r * std::sin(a), cz + dz);
            v = glm::clamp(v, glm::vec3(-1.0f), glm::vec3(1.0f));
            mesh.positions.push_back(v);
            mesh.colors.push_back(color);
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
    });
}

Scene makeCurtains(uint32_t seed) {
    static constexpr int kSheets = 6;
    float hue0 = 0.0f;  // drawn first, before sheet 0's own numbers
    return oneMeshScene(seed, false, kSheets, [&hue0](SceneRng& rng, Mesh& mesh, int sheet) {
        if (sheet == 0) hue0 = rng.uniform();
        const bool pleated = sheet % 2 == 1;
        const float width = rng.range(1.1f, 1.5f);
        const float height = rng.range(1.3f, 1.6f);
        const float cx = rng.range(-0.3f, 0.3f);
        const float cy = rng.range(-0.15f, 0.15f);
        const float cz = -0.6f + 1.2f * (float(sheet) + rng.uniform()) / float(kSheets);
        const float turn = glm::radians(rng.range(-25.0f, 25.0f));
        const int pleats = pleated ? 6 + int(rng.uniform() * 5.0f) : 1;
        const float depth = pleated ? rng.range(0.12f, 0.25f) : 0.0f;
        // Hues spread around the circle (with jitter) so that the sheets really differ in colour.
        float hue = hue0 + float(sheet) / float(kSheets) + rng.range(-0.05f, 0.05f);
        hue -= std::floor(hue);
        const glm::vec3 hueRgb = hueColor<float>(hue, rng.range(0.0f, 0.2f));
        const glm::vec4 color(hueRgb, rng.range(0.15f, 0.7f));
        // A zig-zag in the sheet's local x-z plane: pleat corners alternate between z = 0 and z = depth.
        const glm::mat3 rotation(glm::vec3(std::cos(turn), 0.0f, -std::sin(turn)), glm::vec3(0.0f, 1.0f, 0.0f),
                                 glm::vec3(std::sin(turn), 0.0f, std::cos(turn)));
        const int panels = pleated ? 2 * pleats : 1;
        for (int p = 0; p < panels; ++p) {
            const float x0 = -0.5f * width + width * float(p) / float(panels);
            const float x1 = -0.5f * width + width * float(p + 1) / float(panels);
            const float z0 = (p % 2 == 0) ? 0.0f : depth, z1 = (p % 2 == 0) ? depth : 0.0f;
            const glm::vec3 a = rotation * glm::vec3(x0, -0.5f * height, z0), b = rotation * glm::vec3(x1, -0.5f * height, z1);
            const glm::vec3 up = rotation * glm::vec3(0.0f, height, 0.0f);
            const glm::vec3 centre(cx, cy, cz);
            appendQuad(mesh, {centre + a, centre + b, centre + b + up, centre + a + up},
                       glm::normalize(glm::cross(b - a, up)), color);
        }
    });
}

// An axis-aligned box's six faces, outward normals, one colour.
void appendBox(Mesh& mesh, const glm::vec3& lo, const glm::vec3& hi, const glm::vec4& color) {
    const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                            {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    appendQuad(mesh, {c[4], c[5], c[6], c[7]}, {0, 0, 1}, color);   // +z
    appendQuad(mesh, {c[1], c[0], c[3], c[2]}, {0, 0, -1}, color);  // -z
    appendQuad(mesh, {c[5], c[1], c[2], c[6]}, {1, 0, 0}, color);   // +x
    appendQuad(mesh, {c[0], c[4], c[7], c[3]}, {-1, 0, 0}, color);  // -x
    appendQuad(mesh, {c[7], c[6], c[2], c[3]}, {0, 1, 0}, color);   // +y
    appendQuad(mesh, {c[0], c[1], c[5], c[4]}, {0, -1, 0}, color);  // -y
}

Scene makeCourtyard(uint32_t seed) {
    SceneRng rng(seed);
    Scene s;
    Material opaque = blendMaterial(false);
    opaque.alphaMode = AlphaMode::Opaque;
    Material glass = blendMaterial(false);
    Material foliage = blendMaterial(false);
    foliage.alphaMode = AlphaMode::Mask;
    foliage.alphaCutoff = 0.5f;
    Material smoke = blendMaterial(true);
    s.materials = {opaque, glass, foliage, smoke};

    Mesh solid;  // material 0
    const float floorY = -0.75f;
    appendQuad(solid, {glm::vec3(-0.9f, floorY, 0.9f), glm::vec3(0.9f, floorY, 0.9f), glm::vec3(0.9f, floorY, -0.9f),
                       glm::vec3(-0.9f, floorY, -0.9f)},
               {0, 1, 0}, glm::vec4(0.55f, 0.5f, 0.42f, 1.0f));
    appendQuad(solid, {glm::vec3(-0.9f, floorY, -0.9f), glm::vec3(0.9f, floorY, -0.9f), glm::vec3(0.9f, 0.7f, -0.9f),
                       glm::vec3(-0.9f, 0.7f, -0.9f)},
               {0, 0, 1}, glm::vec4(0.7f, 0.68f, 0.62f, 1.0f));
    for (int p = 0; p < 4; ++p) {
        const float x = (p % 2 == 0 ? -0.5f : 0.5f) + rng.range(-0.05f, 0.05f);
        const float z = (p < 2 ? -0.3f : 0.3f) + rng.range(-0.05f, 0.05f);
        const glm::vec3 rgb = randomColor(rng, 0.6f);
        appendBox(solid, {x - 0.08f, floorY, z - 0.08f}, {x + 0.08f, 0.65f, z + 0.08f}, glm::vec4(rgb, 1.0f));
    }
    solid.material = 0;

    Mesh panes;  // material 1: in front of, between and behind the pillars
    for (int i = 0; i < 8; ++i) {
        const float z = -0.8f + 1.6f * (float(i) + rng.uniform()) / 8.0f;
        const float x = rng.range(-0.5f, 0.5f);
        const float y = rng.range(-0.3f, 0.2f);
        const float w = rng.range(0.3f, 0.55f), h = rng.range(0.3f, 0.5f);
        const glm::vec3 tint = randomColor(rng, 0.3f);  // one draw a statement: argument order is unspecified
        const glm::vec4 color(tint, rng.range(0.2f, 0.5f));
        appendQuad(panes, {glm::vec3(x - w, y - h, z), glm::vec3(x + w, y - h, z), glm::vec3(x + w, y + h, z),
                           glm::vec3(x - w, y + h, z)},
                   {0, 0, 1}, color);
    }
    panes.material = 1;

    Mesh leaves;  // material 2: alpha-tested
    for (int i = 0; i < 60; ++i) {
        const glm::vec3 c = rng.inBox({-0.8f, floorY, -0.8f}, {0.8f, 0.1f, 0.8f});
        const float h = rng.range(0.04f, 0.09f);
        const float red = 0.15f + 0.2f * rng.uniform();
        const float green = 0.45f + 0.3f * rng.uniform();
        appendFacingSquare(leaves, c, h, glm::vec4(red, green, 0.12f, rng.uniform() < 0.5f ? 0.2f : 0.9f));
    }
    leaves.material = 2;

    Mesh haze;  // material 3: faint, many layers
    for (int i = 0; i < 240; ++i) {
        const glm::vec3 c = rng.inBox({-0.7f, -0.6f, -0.8f}, {0.7f, 0.5f, 0.8f});
        const float h = rng.range(0.06f, 0.16f);
        const float grey = rng.range(0.6f, 0.95f);
        appendFacingSquare(haze, c, h, glm::vec4(glm::vec3(grey), rng.range(0.05f, 0.25f)));
    }
    haze.material = 3;
    s.meshes = {std::move(solid), std::move(panes), std::move(leaves), std::move(haze)};
    return s;
}

}  // namespace

std::vector<BuiltinPane> builtinPanes() {
    // Submission order differs from depth order on purpose (z: 0, +0.4, -0.4, +0.2, -0.2).
    return {
        {{-0.50f, -0.25f}, {0.50f, 0.75f}, 0.0f, {0.0f, 0.0f, 1.0f, 0.6f}},   // blue
        {{-0.75f, -0.75f}, {0.25f, 0.25f}, 0.4f, {1.0f, 0.0f, 0.0f, 0.5f}},   // red (nearest to +Z camera)
        {{-0.10f, -0.30f}, {0.70f, 0.50f}, -0.4f, {1.0f, 0.0f, 1.0f, 0.7f}},  // magenta (farthest)
        {{-0.25f, -0.75f}, {0.75f, 0.25f}, 0.2f, {0.0f, 1.0f, 0.0f, 0.4f}},   // green
        {{-0.70f, -0.10f}, {0.10f, 0.70f}, -0.2f, {1.0f, 1.0f, 0.0f, 0.3f}},  // yellow
    };
}

std::vector<std::string> builtinSceneNames() { return {"tubes", "smoke", "panes", "random", "curtains", "courtyard"}; }

Scene makeBuiltinScene(const std::string& name, uint32_t seed) {
    Scene s;
    if (name == "tubes") {
        s = makeTubes(seed);
    } else if (name == "smoke") {
        s = makeSmoke(seed);
    } else if (name == "panes") {
        s = makePanes();
    } else if (name == "random") {
        s = makeRandom(seed);
    } else if (name == "curtains") {
        s = makeCurtains(seed);
    } else if (name == "courtyard") {
        s = makeCourtyard(seed);
    } else {
        std::string list;
        for (const std::string& n : builtinSceneNames()) list += (list.empty() ? "" : ", ") + n;
        throw Error("builtin:" + name + ": unknown built-in scene (valid names: " + list + ")");
    }
    s.name = name;
    validateScene(s, "builtin:" + name);
    return s;
}

}  // namespace starnt
