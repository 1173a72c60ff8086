// glTF 2.0 loader (.gltf and .glb) on top of tinygltf (Debian's shared build: no
// TINYGLTF_IMPLEMENTATION here). tinygltf parses JSON, resolves buffers and decodes images; every
// accessor is then bounds-checked here before a byte is read, so malformed files end in
// starnt::Error, never in an out-of-bounds read.
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <type_traits>
#include <limits>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include "scene/scene_internal.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/scene.hpp"

namespace starnt {

namespace {

constexpr int kMaxNodeDepth = 256;

struct GltfContext {
    const std::string& path;
    const tinygltf::Model& model;
    Scene& scene;
    size_t dataBytes = 0;               // the file and its buffers: bounds accessors without a buffer view
    std::map<int, int> textureOfImage;  // glTF image index -> Scene::textures index
    std::map<int, glm::mat3> uvTransformOfMaterial;  // KHR_texture_transform of a material's base colour texture
    int defaultMaterial = -1;           // Scene::materials index of the default material, lazily added
    bool meshQuantization = false;      // the file uses KHR_mesh_quantization
};

std::string primitiveLabel(const GltfContext& ctx, int meshIndex, size_t primIndex) {
    const std::string& name = ctx.model.meshes[size_t(meshIndex)].name;
    return ctx.path + ": mesh " + std::to_string(meshIndex) + (name.empty() ? "" : " '" + name + "'") +
           " primitive " + std::to_string(primIndex);
}

size_t componentSize(int componentType) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

int componentCount(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

// A bounds-checked view of an accessor's elements. base == nullptr: no buffer view, all zeros.
// One component of type T at `p`, as stored or normalised to [0, 1] (unsigned) or [-1, 1] (signed,
// the most negative value clamped), as glTF defines normalised integers.
template <class T>
double readComponent(const unsigned char* p, bool normalized) {
    T v;
    std::memcpy(&v, p, sizeof v);
    if (!normalized) return double(v);
    const double scaled = double(v) / double(std::numeric_limits<T>::max());
    return std::is_signed_v<T> ? std::max(scaled, -1.0) : scaled;
}

struct AccessorView {
    const unsigned char* base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int componentType = 0;
    int components = 0;
    bool normalized = false;

    double component(size_t element, int c) const {
        if (base == nullptr) return 0.0;
        const unsigned char* p = base + element * stride + size_t(c) * componentSize(componentType);
        switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_BYTE: return readComponent<int8_t>(p, normalized);
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return readComponent<uint8_t>(p, normalized);
            case TINYGLTF_COMPONENT_TYPE_SHORT: return readComponent<int16_t>(p, normalized);
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return readComponent<uint16_t>(p, normalized);
            case TINYGLTF_COMPONENT_TYPE_INT: return readComponent<int32_t>(p, false);  // never normalised
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return readComponent<uint32_t>(p, normalized);
            default: return readComponent<float>(p, false);
        }
    }
};

// Validates accessor `index` (used as `what` by the primitive `label`) against its buffer view and
// buffer, and returns a view on it.
AccessorView viewAccessor(const GltfContext& ctx, int index, const std::string& label, const std::string& what) {
    const tinygltf::Model& model = ctx.model;
    const std::string at = label + ": " + what + " accessor " + std::to_string(index);
    if (index < 0 || size_t(index) >= model.accessors.size())
        throw Error(label + ": " + what + " refers to accessor " + std::to_string(index) + " but the file has " +
                    std::to_string(model.accessors.size()) + " accessors");
    const tinygltf::Accessor& acc = model.accessors[size_t(index)];
    if (acc.sparse.isSparse) throw Error(at + " is sparse (sparse accessors are not supported)");
    AccessorView v;
    v.componentType = acc.componentType;
    v.components = componentCount(acc.type);
    v.normalized = acc.normalized;
    v.count = acc.count;
    const size_t csize = componentSize(acc.componentType);
    if (csize == 0) throw Error(at + " has an invalid componentType " + std::to_string(acc.componentType));
    if (v.components == 0) throw Error(at + " has an invalid type " + std::to_string(acc.type));
    const size_t elementSize = csize * size_t(v.components);
    if (acc.bufferView < 0) {  // glTF: no bufferView means all zeros
        // Nothing in the file backs such an accessor, so a count is only plausible up to the size of
        // the file and its buffers (a 735-byte file claiming 2^26 vertices took 1.3 GB before).
        if (acc.count > ctx.dataBytes)
            throw Error(at + " has no buffer view and claims " + std::to_string(acc.count) +
                        " elements, more than the " + std::to_string(ctx.dataBytes) +
                        " bytes of the file and its buffers");
        return v;
    }
    if (size_t(acc.bufferView) >= model.bufferViews.size())
        throw Error(at + " refers to buffer view " + std::to_string(acc.bufferView) + " but the file has " +
                    std::to_string(model.bufferViews.size()) + " buffer views");
    const tinygltf::BufferView& bv = model.bufferViews[size_t(acc.bufferView)];
    const std::string bvLabel = "buffer view " + std::to_string(acc.bufferView);
    if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size())
        throw Error(at + ": " + bvLabel + " refers to buffer " + std::to_string(bv.buffer) + " but the file has " +
                    std::to_string(model.buffers.size()) + " buffers");
    const std::vector<unsigned char>& data = model.buffers[size_t(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
        throw Error(at + ": " + bvLabel + " (offset " + std::to_string(bv.byteOffset) + ", length " +
                    std::to_string(bv.byteLength) + ") extends past the end of buffer " + std::to_string(bv.buffer) +
                    " (" + std::to_string(data.size()) + " bytes)");
    v.stride = bv.byteStride != 0 ? bv.byteStride : elementSize;
    if (v.stride < elementSize)
        throw Error(at + ": byteStride " + std::to_string(v.stride) + " of " + bvLabel +
                    " is smaller than the element size " + std::to_string(elementSize));
    if (acc.count > 0) {
        // Last byte read: byteOffset + stride * (count - 1) + elementSize <= byteLength, overflow-safe.
        const size_t len = bv.byteLength;
        const bool fits = acc.byteOffset <= len && elementSize <= len - acc.byteOffset &&
                          (acc.count - 1) <= (len - acc.byteOffset - elementSize) / v.stride;
        if (!fits)
            throw Error(at + " (offset " + std::to_string(acc.byteOffset) + ", " + std::to_string(acc.count) +
                        " elements of " + std::to_string(elementSize) + " bytes, stride " +
                        std::to_string(v.stride) + ") extends past the end of " + bvLabel + " (" +
                        std::to_string(len) + " bytes)");
    }
    v.base = data.data() + bv.byteOffset + acc.byteOffset;
    return v;
}

std::vector<uint32_t> readIndices(const GltfContext& ctx, int index, const std::string& label) {
    const AccessorView v = viewAccessor(ctx, index, label, "indices");
    if (v.components != 1) throw Error(label + ": indices accessor " + std::to_string(index) + " is not SCALAR");
    if (v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        throw Error(label + ": indices accessor " + std::to_string(index) +
                    " must use unsigned byte, short or int components");
    AccessorView raw = v;
    raw.normalized = false;
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) out[i] = static_cast<uint32_t>(raw.component(i, 0));
    return out;
}

// Reads a float attribute with `N` components. Integer components are normalised when the accessor
// says so, or always when `forceNormalized` (COLOR_0 and TEXCOORD_0 must be normalised in glTF).
template <int N>
std::vector<glm::vec<N, float>> readAttribute(const GltfContext& ctx, int index, const std::string& label,
                                              const std::string& what, bool forceNormalized) {
    AccessorView v = viewAccessor(ctx, index, label, what);
    if (v.components != N)
        throw Error(label + ": " + what + " accessor " + std::to_string(index) + " has " +
                    std::to_string(v.components) + " components, expected " + std::to_string(N));
    if (forceNormalized && v.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) v.normalized = true;
    std::vector<glm::vec<N, float>> out(v.count);
    for (size_t i = 0; i < v.count; ++i)
        for (int c = 0; c < N; ++c) out[i][c] = static_cast<float>(v.component(i, c));
    return out;
}

glm::mat4 localTransform(const GltfContext& ctx, int nodeIndex) {
    const tinygltf::Node& node = ctx.model.nodes[size_t(nodeIndex)];
    const std::string at = ctx.path + ": node " + std::to_string(nodeIndex);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) throw Error(at + ": matrix must have 16 numbers");
        glm::dmat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[size_t(c * 4 + r)];  // column-major
        return glm::mat4(m);
    }
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3) throw Error(at + ": translation must have 3 numbers");
        m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) throw Error(at + ": rotation must have 4 numbers");
        // glTF quaternions are (x, y, z, w); glm::dquat's constructor takes (w, x, y, z).
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double len = glm::length(q);
        if (!(len > 0.0) || !std::isfinite(len)) throw Error(at + ": rotation quaternion is zero or not finite");
        m = m * glm::mat4_cast(q / len);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3) throw Error(at + ": scale must have 3 numbers");
        m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return glm::mat4(m);
}

int sceneTexture(GltfContext& ctx, int textureIndex, const std::string& at) {
    const tinygltf::Model& model = ctx.model;
    if (textureIndex < 0 || size_t(textureIndex) >= model.textures.size())
        throw Error(at + ": baseColorTexture refers to texture " + std::to_string(textureIndex) +
                    " but the file has " + std::to_string(model.textures.size()) + " textures");
    const int source = model.textures[size_t(textureIndex)].source;
    if (source < 0 || size_t(source) >= model.images.size())
        throw Error(at + ": texture " + std::to_string(textureIndex) + " refers to image " + std::to_string(source) +
                    " but the file has " + std::to_string(model.images.size()) + " images");
    auto it = ctx.textureOfImage.find(source);
    if (it != ctx.textureOfImage.end()) return it->second;
    const tinygltf::Image& img = model.images[size_t(source)];
    int result = -1;
    if (img.image.empty()) {
        throw Error(at + ": image " + std::to_string(source) +
                    (img.uri.empty() ? std::string() : " ('" + img.uri.substr(0, 200) + "')") +
                    " could not be decoded (missing file or unsupported format)");
    } else {
        ctx.scene.textures.push_back(detail::toRgba8(img.image.data(), img.image.size(), img.width, img.height,
                                                     img.component, img.bits,
                                                     ctx.path + ": image " + std::to_string(source)));
        result = int(ctx.scene.textures.size()) - 1;
    }
    ctx.textureOfImage[source] = result;
    return result;
}

// KHR_texture_transform as the 3x3 matrix glTF defines, uv' = T(offset) R(rotation) S(scale) uv:
// scale first, then a rotation counter-clockwise as the image is seen (v pointing down), then the offset.
glm::mat3 textureTransform(const tinygltf::Value& t, const std::string& at) {
    auto number = [&](const tinygltf::Value& v, const char* what) {
        if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) throw Error(at + ": " + what + " must be a finite number");
        return float(v.GetNumberAsDouble());
    };
    auto pair = [&](const char* key, glm::vec2 fallback) {
        if (!t.Has(key)) return fallback;
        const tinygltf::Value& v = t.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2) throw Error(at + ": " + key + " must have 2 numbers");
        return glm::vec2(number(v.Get(0), key), number(v.Get(1), key));
    };
    const glm::vec2 offset = pair("offset", glm::vec2(0.0f)), scale = pair("scale", glm::vec2(1.0f));
    const float rotation = t.Has("rotation") ? number(t.Get("rotation"), "rotation") : 0.0f;
    if (t.Has("texCoord") && number(t.Get("texCoord"), "texCoord") != 0.0f)
        detail::warn(at + ": texCoord " + std::to_string(int(number(t.Get("texCoord"), "texCoord"))) + "; only TEXCOORD_0 is loaded");
    const float c = std::cos(rotation), s = std::sin(rotation);
    glm::mat3 m(1.0f);  // column-major: m[column][row]
    m[0][0] = c * scale.x;
    m[0][1] = -s * scale.x;
    m[1][0] = s * scale.y;
    m[1][1] = c * scale.y;
    m[2][0] = offset.x;
    m[2][1] = offset.y;
    return m;
}

void convertMaterials(GltfContext& ctx) {
    for (size_t i = 0; i < ctx.model.materials.size(); ++i) {
        const tinygltf::Material& gm = ctx.model.materials[i];
        const std::string at = ctx.path + ": material " + std::to_string(i) + (gm.name.empty() ? "" : " '" + gm.name + "'");
        Material m;
        const auto& f = gm.pbrMetallicRoughness.baseColorFactor;
        if (f.size() == 4) {
            m.baseColorFactor = glm::vec4(float(f[0]), float(f[1]), float(f[2]), float(f[3]));
            if (glm::any(glm::lessThan(m.baseColorFactor, glm::vec4(0.0f))) || glm::any(glm::greaterThan(m.baseColorFactor, glm::vec4(1.0f)))) {
                char text[160];
                std::snprintf(text, sizeof text, ": baseColorFactor (%g, %g, %g, %g) is outside glTF's range [0, 1]", f[0], f[1], f[2], f[3]);
                detail::warn(at + text);
            }
        } else if (!f.empty()) {
            throw Error(at + ": baseColorFactor must have 4 numbers");
        }
        const tinygltf::TextureInfo& ti = gm.pbrMetallicRoughness.baseColorTexture;
        if (ti.index >= 0) {
            if (ti.texCoord != 0)
                detail::warn(at + ": baseColorTexture uses TEXCOORD_" + std::to_string(ti.texCoord) +
                             "; only TEXCOORD_0 is loaded");
            m.baseColorTexture = sceneTexture(ctx, ti.index, at);
            if (auto t = ti.extensions.find("KHR_texture_transform"); t != ti.extensions.end()) {
                ctx.uvTransformOfMaterial[int(i)] = textureTransform(t->second, at + ": baseColorTexture KHR_texture_transform");
            }
        }
        if (gm.emissiveFactor.size() == 3) {
            double strength = 1.0;
            if (auto e = gm.extensions.find("KHR_materials_emissive_strength"); e != gm.extensions.end()) {
                const tinygltf::Value& v = e->second.Get("emissiveStrength");
                if (v.IsNumber()) strength = v.GetNumberAsDouble();
                if (!(strength >= 0.0) || !std::isfinite(strength))
                    throw Error(at + ": KHR_materials_emissive_strength emissiveStrength must be a finite number >= 0");
            }
            m.emissive = glm::vec3(float(gm.emissiveFactor[0] * strength), float(gm.emissiveFactor[1] * strength),
                                   float(gm.emissiveFactor[2] * strength));
            if (!std::isfinite(m.emissive.r + m.emissive.g + m.emissive.b) || glm::any(glm::lessThan(m.emissive, glm::vec3(0.0f))))
                throw Error(at + ": emissiveFactor must be finite and >= 0");
        }
        if (gm.emissiveTexture.index >= 0 && glm::any(glm::greaterThan(m.emissive, glm::vec3(0.0f)))) {
            // The factor scales the texture (exporters write [1, 1, 1] beside one): alone it would
            // wash the whole surface out.
            detail::warn(at + ": emissiveTexture is not loaded; its emission is left out");
            m.emissive = glm::vec3(0.0f);
        }
        m.unlit = gm.extensions.count("KHR_materials_unlit") != 0;
        m.doubleSided = gm.doubleSided;
        if (gm.alphaMode == "OPAQUE" || gm.alphaMode.empty()) {
            m.alphaMode = AlphaMode::Opaque;
        } else if (gm.alphaMode == "MASK") {
            m.alphaMode = AlphaMode::Mask;
        } else if (gm.alphaMode == "BLEND") {
            m.alphaMode = AlphaMode::Blend;
        } else {
            detail::warn(at + ": unknown alphaMode '" + gm.alphaMode + "', using OPAQUE");
            m.alphaMode = AlphaMode::Opaque;
        }
        m.alphaCutoff = float(gm.alphaCutoff);
        if (m.alphaMode == AlphaMode::Mask && !(m.alphaCutoff >= 0.0f))
            detail::warn(at + ": alphaCutoff " + std::to_string(gm.alphaCutoff) + " is negative (glTF: at least 0); no fragment is cut");
        ctx.scene.materials.push_back(m);
    }
}

int defaultMaterial(GltfContext& ctx) {
    if (ctx.defaultMaterial < 0) {
        // glTF's default material: white, OPAQUE, single-sided, lit.
        Material m;
        m.baseColorFactor = glm::vec4(1.0f);
        m.alphaMode = AlphaMode::Opaque;
        m.doubleSided = false;
        ctx.scene.materials.push_back(m);
        ctx.defaultMaterial = int(ctx.scene.materials.size()) - 1;
    }
    return ctx.defaultMaterial;
}

// Converts a strip or fan (glTF 2.0 section 3.7.2.1 ordering) or checks a triangle list.
std::vector<uint32_t> toTriangleList(const std::vector<uint32_t>& v, int mode, bool indexed, const std::string& label) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (v.size() % 3 != 0)
            throw Error(label + ": " + (indexed ? "triangle index count " : "non-indexed triangle vertex count ") +
                        std::to_string(v.size()) + " is not a multiple of 3");
        return v;
    }
    if (v.size() < 3) return out;
    out.reserve((v.size() - 2) * 3);
    for (size_t i = 0; i + 2 < v.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            out.push_back(v[i]);
            out.push_back(v[i + 1 + i % 2]);
            out.push_back(v[i + 2 - i % 2]);
        } else {  // fan
            out.push_back(v[i + 1]);
            out.push_back(v[i + 2]);
            out.push_back(v[0]);
        }
    }
    return out;
}

void addPrimitive(GltfContext& ctx, int meshIndex, size_t primIndex, const glm::mat4& world, const std::vector<double>& weights) {
    const tinygltf::Primitive& prim = ctx.model.meshes[size_t(meshIndex)].primitives[primIndex];
    const std::string label = primitiveLabel(ctx, meshIndex, primIndex);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP)
            detail::warn(label + ": skipping points/lines primitive (mode " + std::to_string(mode) + ")");
        else
            throw Error(label + ": invalid primitive mode " + std::to_string(mode));
        return;
    }
    auto attr = [&](const char* name) {
        auto it = prim.attributes.find(name);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int posIndex = attr("POSITION");
    if (posIndex < 0) throw Error(label + ": has no POSITION attribute");

    Mesh mesh;
    mesh.positions = readAttribute<3>(ctx, posIndex, label, "POSITION", false);
    const size_t n = mesh.positions.size();
    for (size_t i = 0; i < n; ++i) {
        const glm::vec3& p = mesh.positions[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw Error(label + ": vertex " + std::to_string(i) + " has a NaN or infinite POSITION");
    }
    auto checkCount = [&](size_t count, const char* what) {
        if (count != n)
            throw Error(label + ": " + what + " has " + std::to_string(count) + " elements but POSITION has " +
                        std::to_string(n));
    };
    if (int a = attr("NORMAL"); a >= 0) {
        mesh.normals = readAttribute<3>(ctx, a, label, "NORMAL", false);
        checkCount(mesh.normals.size(), "NORMAL");
    }
    if (int a = attr("TEXCOORD_0"); a >= 0) {
        // Integer coordinates are normalised in core glTF (forced for files that forget the flag);
        // KHR_mesh_quantization allows them unnormalised (scaled by a texture transform).
        mesh.uvs = readAttribute<2>(ctx, a, label, "TEXCOORD_0", !ctx.meshQuantization);
        checkCount(mesh.uvs.size(), "TEXCOORD_0");
    }
    if (int a = attr("COLOR_0"); a >= 0) {
        if (size_t(a) < ctx.model.accessors.size() && ctx.model.accessors[size_t(a)].type == TINYGLTF_TYPE_VEC3) {
            for (const glm::vec3& c : readAttribute<3>(ctx, a, label, "COLOR_0", true))
                mesh.colors.emplace_back(c, 1.0f);
        } else {
            mesh.colors = readAttribute<4>(ctx, a, label, "COLOR_0", true);
        }
        checkCount(mesh.colors.size(), "COLOR_0");
    }

    // Morph targets at the node's (or the mesh's) default weights: glTF's rest pose.
    for (size_t t = 0; t < prim.targets.size() && t < weights.size(); ++t) {
        const double w = weights[t];
        if (!std::isfinite(w)) throw Error(label + ": morph target weight " + std::to_string(t) + " is not finite");
        if (w == 0.0) continue;
        const auto& target = prim.targets[t];
        const std::string what = "morph target " + std::to_string(t);
        if (auto it = target.find("POSITION"); it != target.end()) {
            const auto d = readAttribute<3>(ctx, it->second, label, what + " POSITION", false);
            checkCount(d.size(), (what + " POSITION").c_str());
            for (size_t i = 0; i < n; ++i) mesh.positions[i] += float(w) * d[i];
        }
        if (auto it = target.find("NORMAL"); it != target.end() && !mesh.normals.empty()) {
            const auto d = readAttribute<3>(ctx, it->second, label, what + " NORMAL", false);
            checkCount(d.size(), (what + " NORMAL").c_str());
            for (size_t i = 0; i < n; ++i) mesh.normals[i] += float(w) * d[i];
        }
    }
    if (!prim.targets.empty()) {
        for (size_t i = 0; i < n; ++i) {
            const glm::vec3& p = mesh.positions[i];
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw Error(label + ": vertex " + std::to_string(i) + " has a NaN or infinite POSITION after its morph targets");
        }
    }
    if (prim.material >= 0) {
        if (auto it = ctx.uvTransformOfMaterial.find(prim.material); it != ctx.uvTransformOfMaterial.end())
            for (glm::vec2& uv : mesh.uvs) uv = glm::vec2(it->second * glm::vec3(uv, 1.0f));
    }

    std::vector<uint32_t> raw;
    if (prim.indices >= 0) {
        raw = readIndices(ctx, prim.indices, label);
        for (size_t i = 0; i < raw.size(); ++i)
            if (raw[i] >= n)
                throw Error(label + ": index " + std::to_string(i) + " = " + std::to_string(raw[i]) +
                            " is out of range (" + std::to_string(n) + " vertices)");
    } else {
        raw.resize(n);
        for (size_t i = 0; i < n; ++i) raw[i] = uint32_t(i);
    }
    mesh.indices = toTriangleList(raw, mode, prim.indices >= 0, label);

    // Bake the node's world transform. Normals use the inverse transpose; a mirroring transform
    // (negative determinant) flips the winding so counter-clockwise stays front-facing.
    for (glm::vec3& p : mesh.positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(world)));
    for (glm::vec3& nrm : mesh.normals) {
        const glm::vec3 t = normalMatrix * nrm;
        const float len = glm::length(t);
        nrm = (len > 0.0f && std::isfinite(len)) ? t / len : glm::vec3(0.0f);
    }
    if (glm::determinant(glm::mat3(world)) < 0.0f)
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);

    if (prim.material >= 0) {
        if (size_t(prim.material) >= ctx.model.materials.size())
            throw Error(label + ": refers to material " + std::to_string(prim.material) + " but the file has " +
                        std::to_string(ctx.model.materials.size()) + " materials");
        mesh.material = prim.material;
    } else {
        mesh.material = defaultMaterial(ctx);
    }
    if (!mesh.indices.empty()) ctx.scene.meshes.push_back(std::move(mesh));
}

void addNode(GltfContext& ctx, int nodeIndex, const glm::mat4& parent, std::vector<int>& path) {
    if (nodeIndex < 0 || size_t(nodeIndex) >= ctx.model.nodes.size())
        throw Error(ctx.path + ": reference to node " + std::to_string(nodeIndex) + " but the file has " +
                    std::to_string(ctx.model.nodes.size()) + " nodes");
    if (std::find(path.begin(), path.end(), nodeIndex) != path.end() || path.size() >= size_t(kMaxNodeDepth))
        throw Error(ctx.path + ": node hierarchy has a cycle or is too deep at node " + std::to_string(nodeIndex));
    const tinygltf::Node& node = ctx.model.nodes[size_t(nodeIndex)];
    // Skinned meshes are baked in their bind pose with the node's transform (no animation).
    const glm::mat4 world = parent * localTransform(ctx, nodeIndex);
    if (node.mesh >= 0) {
        if (size_t(node.mesh) >= ctx.model.meshes.size())
            throw Error(ctx.path + ": node " + std::to_string(nodeIndex) + " refers to mesh " +
                        std::to_string(node.mesh) + " but the file has " + std::to_string(ctx.model.meshes.size()) +
                        " meshes");
        const tinygltf::Mesh& m = ctx.model.meshes[size_t(node.mesh)];
        const std::vector<double>& weights = node.weights.empty() ? m.weights : node.weights;
        for (size_t p = 0; p < m.primitives.size(); ++p) addPrimitive(ctx, node.mesh, p, world, weights);
    }
    path.push_back(nodeIndex);
    for (int child : node.children) addNode(ctx, child, world, path);
    path.pop_back();
}

}  // namespace

Scene loadGltf(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": file not found");

    // .glb by extension, or by the "glTF" magic (some tools write binary files named .gltf).
    bool binary = detail::lowerExtension(path) == ".glb";
    {
        std::ifstream f(path, std::ios::binary);
        char magic[4] = {0, 0, 0, 0};
        if (f.read(magic, 4) && std::memcmp(magic, "glTF", 4) == 0) binary = true;
    }

    if (binary) {
        // GLB header: magic, version (uint32 LE), length. tinygltf reads version 1 files as version 2.
        std::ifstream f(path, std::ios::binary);
        unsigned char header[12] = {};
        if (f.read(reinterpret_cast<char*>(header), 12) && std::memcmp(header, "glTF", 4) == 0) {
            const uint32_t version = uint32_t(header[4]) | uint32_t(header[5]) << 8 | uint32_t(header[6]) << 16 |
                                     uint32_t(header[7]) << 24;
            if (version != 2)
                throw Error(path + ": GLB container version " + std::to_string(version) +
                            " is not supported (only glTF 2.0 binary files, version 2)");
        }
    }

    tinygltf::TinyGLTF loader;
    // Buffer and image files go through here so a uri naming a folder is an error, not an exception
    // from deep inside the stream library.
    tinygltf::FsCallbacks fs{};
    fs.FileExists = &tinygltf::FileExists;
    fs.ExpandFilePath = &tinygltf::ExpandFilePath;
    fs.WriteWholeFile = &tinygltf::WriteWholeFile;
    fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(file, ec)) {
            if (err) *err += "'" + file + "' is " + (std::filesystem::is_directory(file, ec) ? "a directory" : "not a regular file") + "\n";
            return false;
        }
        try {
            return tinygltf::ReadWholeFile(out, err, file, user);
        } catch (const std::exception& e) {
            if (err) *err += "cannot read '" + file + "': " + e.what() + "\n";
            return false;
        }
    };
    fs.user_data = nullptr;
    loader.SetFsCallbacks(fs);
    // tinygltf's decoder, with the image's uri added to its message.
    loader.SetImageLoader(
        [](tinygltf::Image* image, const int index, std::string* err, std::string* warn, int reqW, int reqH,
           const unsigned char* bytes, int size, void* user) {
            const bool ok = tinygltf::LoadImageData(image, index, err, warn, reqW, reqH, bytes, size, user);
            if (!ok && err && image && !image->uri.empty() && image->uri.rfind("data:", 0) != 0) {
                while (!err->empty() && err->back() == '\n') err->pop_back();
                *err += " (uri '" + image->uri.substr(0, 200) + "')\n";
            }
            return ok;
        },
        nullptr);
    tinygltf::Model model;
    std::string err, warnings;
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warnings, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warnings, path);
    if (!ok) {
        std::string msg = err.empty() ? warnings : err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
        for (char& c : msg)
            if (c == '\n') c = ';';
        throw Error(path + ": cannot parse glTF: " + (msg.empty() ? "unknown tinygltf error" : msg));
    }
    {
        // tinygltf calls a skin without inverseBindMatrices an error; glTF allows it (identity
        // matrices), and skins are not applied here (the bind pose is drawn).
        std::string kept, line;
        std::istringstream lines(err);
        while (std::getline(lines, line))
            if (line.find("'inverseBindMatrices' property is missing") == std::string::npos) kept += line + "\n";
        err = kept;
    }
    if (!err.empty()) {
        // tinygltf reports some invalid values (e.g. a baseColorFactor of 3 numbers) in `err` and
        // carries on with defaults: an error here too.
        std::string msg = err;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
        for (char& c : msg)
            if (c == '\n') c = ';';
        throw Error(path + ": invalid glTF: " + msg);
    }

    // Extensions: one the file requires and this loader lacks would be drawn wrong, so it is an
    // error; one it merely uses is ignored with a warning.
    static const std::set<std::string> kSupportedExtensions = {"KHR_materials_unlit", "KHR_texture_transform",
                                                               "KHR_mesh_quantization", "KHR_materials_emissive_strength"};
    std::string supported;
    for (const std::string& e : kSupportedExtensions) supported += (supported.empty() ? "" : ", ") + e;
    for (const std::string& e : model.extensionsRequired)
        if (!kSupportedExtensions.count(e))
            throw Error(path + ": requires the glTF extension " + e.substr(0, 100) + ", which this loader does not support (supported: " + supported + ")");
    for (const std::string& e : model.extensionsUsed)
        if (!kSupportedExtensions.count(e) &&
            std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), e) == model.extensionsRequired.end())
            detail::warn(path + ": uses the glTF extension " + e.substr(0, 100) + ", which is not supported: what it adds is ignored");
    if (model.defaultScene >= 0 && size_t(model.defaultScene) >= model.scenes.size())
        throw Error(path + ": \"scene\" is " + std::to_string(model.defaultScene) + " but the file has " + std::to_string(model.scenes.size()) +
                    " scenes");

    Scene scene;
    scene.name = std::filesystem::path(path).stem().string();
    GltfContext ctx{path, model, scene};
    ctx.meshQuantization = std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_mesh_quantization") !=
                           model.extensionsUsed.end();
    ctx.dataBytes = size_t(std::filesystem::file_size(path, ec));
    for (const tinygltf::Buffer& b : model.buffers) ctx.dataBytes += b.data.size();
    convertMaterials(ctx);

    std::vector<int> roots;
    if (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()) {
        roots = model.scenes[size_t(model.defaultScene)].nodes;
    } else if (!model.scenes.empty()) {
        roots = model.scenes[0].nodes;
    } else {
        std::set<int> children;
        for (const tinygltf::Node& n : model.nodes) children.insert(n.children.begin(), n.children.end());
        for (size_t i = 0; i < model.nodes.size(); ++i)
            if (!children.count(int(i))) roots.push_back(int(i));
    }
    std::vector<int> nodePath;
    try {
        for (int r : roots) addNode(ctx, r, glm::mat4(1.0f), nodePath);
    } catch (const std::bad_alloc&) {
        // Say how large the file claims to be: the triangles of every node's mesh, from the accessors.
        size_t claimed = 0;
        for (const tinygltf::Node& n : model.nodes) {
            if (n.mesh < 0 || size_t(n.mesh) >= model.meshes.size()) continue;
            for (const tinygltf::Primitive& p : model.meshes[size_t(n.mesh)].primitives) {
                const int a = p.indices >= 0 ? p.indices : (p.attributes.count("POSITION") ? p.attributes.at("POSITION") : -1);
                if (a >= 0 && size_t(a) < model.accessors.size()) claimed += model.accessors[size_t(a)].count / 3;
            }
        }
        throw Error(path + ": out of memory while loading the scene (" + std::to_string(claimed) +
                    " triangles in its meshes, " + std::to_string(scene.triangleCount()) + " loaded so far)");
    }

    if (scene.materials.empty()) defaultMaterial(ctx);
    validateScene(scene, path);
    return scene;
}

}  // namespace starnt
