// Scene basics: bounds and counts, format dispatch (loadScene) and validation (validateScene).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>

#include "scene/scene_internal.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"
#include "starnt/log.hpp"

namespace starnt {

namespace detail {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

void warn(const std::string& message) { logMessage(LogLevel::Warning, message); }

Texture toRgba8(const unsigned char* pixels, size_t byteCount, int width, int height, int channels,
                int bits, const std::string& context) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || (bits != 8 && bits != 16))
        throw Error(context + ": unsupported image layout (" + std::to_string(width) + "x" +
                    std::to_string(height) + ", " + std::to_string(channels) + " channels, " +
                    std::to_string(bits) + " bits)");
    const size_t texels = size_t(width) * size_t(height);
    const size_t bytesPerValue = bits / 8;
    if (pixels == nullptr || byteCount < texels * size_t(channels) * bytesPerValue)
        throw Error(context + ": image data is shorter than " + std::to_string(width) + "x" +
                    std::to_string(height) + "x" + std::to_string(channels) + " values");
    auto value = [&](size_t i) -> uint8_t {
        if (bits == 8) return pixels[i];
        uint16_t v;
        std::memcpy(&v, pixels + 2 * i, 2);
        return static_cast<uint8_t>((uint32_t(v) * 255u + 32767u) / 65535u);
    };
    Texture t;
    t.name = context;
    t.width = width;
    t.height = height;
    t.rgba8.resize(texels * 4);
    for (size_t p = 0; p < texels; ++p) {
        const size_t s = p * size_t(channels);
        uint8_t r, g, b, a = 255;
        switch (channels) {
            case 1: r = g = b = value(s); break;
            case 2: r = g = b = value(s); a = value(s + 1); break;
            case 3: r = value(s); g = value(s + 1); b = value(s + 2); break;
            default: r = value(s); g = value(s + 1); b = value(s + 2); a = value(s + 3); break;
        }
        t.rgba8[4 * p + 0] = r;
        t.rgba8[4 * p + 1] = g;
        t.rgba8[4 * p + 2] = b;
        t.rgba8[4 * p + 3] = a;
    }
    return t;
}

}  // namespace detail

Bounds Scene::bounds() const {
    Bounds b;
    bool any = false;
    for (const Mesh& m : meshes) {
        for (const glm::vec3& p : m.positions) {
            if (!any) {
                b.min = b.max = p;
                any = true;
            } else {
                b.min = glm::min(b.min, p);
                b.max = glm::max(b.max, p);
            }
        }
    }
    return b;
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const Mesh& m : meshes) n += m.indices.size() / 3;
    return n;
}

size_t Scene::vertexCount() const {
    size_t n = 0;
    for (const Mesh& m : meshes) n += m.positions.size();
    return n;
}

Scene loadScene(const std::string& spec) {
    static const std::string kBuiltin = "builtin:";
    if (spec.rfind(kBuiltin, 0) == 0) {
        Scene s = makeBuiltinScene(spec.substr(kBuiltin.size()));
        return s;
    }
    std::error_code ec;
    if (std::filesystem::is_directory(spec, ec))
        throw Error(spec + ": is a directory; --scene needs a .gltf, .glb or .obj file (or builtin:NAME)");
    if (!std::filesystem::is_regular_file(spec, ec))
        throw Error(spec + ": scene file not found (expected a .gltf, .glb or .obj file, or builtin:NAME)");
    const std::string ext = detail::lowerExtension(spec);
    Scene s;
    try {
        if (ext == ".gltf" || ext == ".glb") {
            s = loadGltf(spec);
        } else if (ext == ".obj") {
            s = loadObj(spec);
        } else {
            throw Error(spec + ": unknown scene file extension '" + ext +
                        "' (expected .gltf, .glb or .obj, or builtin:NAME)");
        }
    } catch (const std::bad_alloc&) {
        const size_t triangles = s.triangleCount();  // 0 unless the loader had returned
        const auto bytes = std::filesystem::file_size(spec, ec);
        throw Error(spec + ": out of memory while loading the scene (" + (ec ? std::string("?") : std::to_string(bytes)) +
                    "-byte file" + (triangles ? ", " + std::to_string(triangles) + " triangles" : "") +
                    "): the scene is too large for this machine");
    }
    return s;
}

namespace {

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite2(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
bool finite4(const glm::vec4& v) { return finite3(glm::vec3(v)) && std::isfinite(v.w); }

std::string meshLabel(const std::string& source, size_t m) { return source + ": mesh " + std::to_string(m); }

}  // namespace

size_t validateScene(Scene& scene, const std::string& source) {
    // Materials and textures.
    for (size_t t = 0; t < scene.textures.size(); ++t) {
        const Texture& tex = scene.textures[t];
        if (tex.width <= 0 || tex.height <= 0 ||
            tex.rgba8.size() != size_t(tex.width) * size_t(tex.height) * 4)
            throw Error(source + ": texture " + std::to_string(t) + " has inconsistent size (" +
                        std::to_string(tex.width) + "x" + std::to_string(tex.height) + ", " +
                        std::to_string(tex.rgba8.size()) + " bytes)");
    }
    for (size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& mat = scene.materials[i];
        if (mat.baseColorTexture < -1 || mat.baseColorTexture >= int(scene.textures.size()))
            throw Error(source + ": material " + std::to_string(i) + " references texture " +
                        std::to_string(mat.baseColorTexture) + " but the scene has " +
                        std::to_string(scene.textures.size()) + " textures");
        if (!finite4(mat.baseColorFactor))
            throw Error(source + ": material " + std::to_string(i) + " has a non-finite baseColorFactor");
    }

    // Per-mesh structure.
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const size_t n = mesh.positions.size();
        if (mesh.material < 0 || mesh.material >= int(scene.materials.size()))
            throw Error(meshLabel(source, m) + " references material " + std::to_string(mesh.material) +
                        " but the scene has " + std::to_string(scene.materials.size()) + " materials");
        if (mesh.indices.size() % 3 != 0)
            throw Error(meshLabel(source, m) + ": index count " + std::to_string(mesh.indices.size()) +
                        " is not a multiple of 3");
        auto checkLength = [&](size_t len, const char* what) {
            if (len != 0 && len != n)
                throw Error(meshLabel(source, m) + ": " + what + " array has " + std::to_string(len) +
                            " entries but there are " + std::to_string(n) + " positions");
        };
        checkLength(mesh.normals.size(), "normals");
        checkLength(mesh.uvs.size(), "uvs");
        checkLength(mesh.colors.size(), "colors");
        for (size_t i = 0; i < mesh.indices.size(); ++i)
            if (mesh.indices[i] >= n)
                throw Error(meshLabel(source, m) + ": index " + std::to_string(i) + " = " +
                            std::to_string(mesh.indices[i]) + " is out of range (" + std::to_string(n) +
                            " vertices)");
        for (size_t v = 0; v < n; ++v) {
            const glm::vec3& p = mesh.positions[v];
            if (!finite3(p))
                throw Error(meshLabel(source, m) + ": vertex " + std::to_string(v) +
                            " has a NaN or infinite position");
            if (std::max({std::fabs(double(p.x)), std::fabs(double(p.y)), std::fabs(double(p.z))}) > kMaxSceneCoordinate)
                throw Error(meshLabel(source, m) + ": vertex " + std::to_string(v) + " position (" +
                            std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z) +
                            ") is beyond the supported range (|coordinate| <= 1e18)");
        }
        for (size_t v = 0; v < mesh.normals.size(); ++v)
            if (!finite3(mesh.normals[v]))
                throw Error(meshLabel(source, m) + ": vertex " + std::to_string(v) +
                            " has a NaN or infinite normal");
        for (size_t v = 0; v < mesh.uvs.size(); ++v)
            if (!finite2(mesh.uvs[v]))
                throw Error(meshLabel(source, m) + ": vertex " + std::to_string(v) +
                            " has a NaN or infinite texture coordinate");
        for (size_t v = 0; v < mesh.colors.size(); ++v)
            if (!finite4(mesh.colors[v]))
                throw Error(meshLabel(source, m) + ": vertex " + std::to_string(v) +
                            " has a NaN or infinite colour");
    }

    // Zero-area triangles: |cross(b-a, c-a)| (twice the area) <= 1e-12 x the triangle's longest edge
    // squared, i.e. its height under 1e-12 of its length: a repeated index, three points on a line,
    // or a sliver no float rasteriser can cover, at any distance. Measured against the triangle's own
    // size, not the scene's: a leaf a centimetre across in a scene ten kilometres wide is small, not
    // degenerate, and the camera may stand beside it. In double, so that float rounding of large
    // coordinates does not count.
    const Bounds b = scene.bounds();
    const glm::dvec3 size = glm::dvec3(b.max) - glm::dvec3(b.min);
    const double extent = std::max({size.x, size.y, size.z});
    size_t removed = 0;
    for (Mesh& mesh : scene.meshes) {
        size_t out = 0;
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {  // size is a multiple of 3 (checked)
            const glm::dvec3 p0(mesh.positions[mesh.indices[t]]);
            const glm::dvec3 p1(mesh.positions[mesh.indices[t + 1]]);
            const glm::dvec3 p2(mesh.positions[mesh.indices[t + 2]]);
            const double twiceArea = glm::length(glm::cross(p1 - p0, p2 - p0));
            const double longest = std::max({glm::dot(p1 - p0, p1 - p0), glm::dot(p2 - p1, p2 - p1), glm::dot(p0 - p2, p0 - p2)});
            if (!(twiceArea > 1e-12 * longest)) {
                ++removed;
                continue;
            }
            if (out != t) {
                mesh.indices[out] = mesh.indices[t];
                mesh.indices[out + 1] = mesh.indices[t + 1];
                mesh.indices[out + 2] = mesh.indices[t + 2];
            }
            out += 3;
        }
        mesh.indices.resize(out);
    }
    // Meshes left without triangles are dropped so renderers never issue empty draws.
    scene.meshes.erase(std::remove_if(scene.meshes.begin(), scene.meshes.end(),
                                      [](const Mesh& m) { return m.indices.empty(); }),
                       scene.meshes.end());
    if (scene.meshes.empty()) {
        // Say why when triangles were there: all of them of zero area.
        throw Error(source + ": scene has no renderable triangles" +
                    (removed > 0 ? " (its " + std::to_string(removed) + " triangle" + (removed == 1 ? " is" : "s are") +
                                       " of zero area: twice the area at most 1e-12 x the longest edge squared)"
                                 : std::string()));
    }
    if (removed > 0)
        detail::warn(source + ": removed " + std::to_string(removed) + " zero-area triangle" +
                     (removed == 1 ? "" : "s"));
    // Far from the origin for its size: float positions (and the view transform, which subtracts
    // the camera's position in float) step by about |x| 2^-23, which snaps the geometry visibly
    // once that is a percent of the scene's extent (six unit quads 1e7 away collapse into one).
    const double farthest = std::max({std::fabs(double(b.min.x)), std::fabs(double(b.min.y)), std::fabs(double(b.min.z)),
                                      std::fabs(double(b.max.x)), std::fabs(double(b.max.y)), std::fabs(double(b.max.z))});
    const double step = farthest * std::ldexp(1.0, -23);
    if (extent > 0.0 && step > 0.01 * extent) {
        char text[256];
        std::snprintf(text, sizeof text,
                      ": the scene is %.3g across and %.3g from the origin: float precision (steps of about %.2g) moves its "
                      "vertices by up to %.2g%% of its size; move it nearer the origin",
                      extent, farthest, step, 100.0 * step / extent);
        detail::warn(source + text);
    }
    return removed;
}

}  // namespace starnt
