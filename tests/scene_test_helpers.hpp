// Test helpers for the scene tests: build small glTF files by hand (JSON + one binary buffer) and
// write them as .gltf (base64 data URI) or .glb, plus small file utilities.
#pragma once
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace starnt::test {

inline std::string base64(const std::vector<uint8_t>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t b0 = data[i];
        const uint32_t b1 = i + 1 < data.size() ? data[i + 1] : 0;
        const uint32_t b2 = i + 2 < data.size() ? data[i + 2] : 0;
        const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < data.size() ? table[(v >> 6) & 63] : '=';
        out += i + 2 < data.size() ? table[v & 63] : '=';
    }
    return out;
}

inline void writeBytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

inline void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
}

inline std::vector<uint8_t> readBytes(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// glTF component types and modes used by the tests.
constexpr int kU8 = 5121, kU16 = 5123, kU32 = 5125, kF32 = 5126;

// Accumulates one binary buffer plus the JSON that describes it.
struct GltfBuilder {
    nlohmann::json json = {{"asset", {{"version", "2.0"}}},
                           {"bufferViews", nlohmann::json::array()},
                           {"accessors", nlohmann::json::array()}};
    std::vector<uint8_t> bin;

    // Appends raw bytes (4-byte aligned) and returns their offset.
    size_t append(const void* data, size_t size) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        const auto* p = static_cast<const uint8_t*>(data);
        bin.insert(bin.end(), p, p + size);
        return offset;
    }
    template <class T>
    size_t append(const std::vector<T>& v) { return append(v.data(), v.size() * sizeof(T)); }

    int view(size_t offset, size_t length, size_t stride = 0) {
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
        if (stride) v["byteStride"] = stride;
        json["bufferViews"].push_back(v);
        return int(json["bufferViews"].size()) - 1;
    }
    int accessor(int view, size_t byteOffset, int componentType, size_t count, const std::string& type,
                 bool normalized = false) {
        nlohmann::json a = {{"bufferView", view}, {"byteOffset", byteOffset}, {"componentType", componentType},
                            {"count", count}, {"type", type}};
        if (normalized) a["normalized"] = true;
        json["accessors"].push_back(a);
        return int(json["accessors"].size()) - 1;
    }
    // Convenience: a tightly packed accessor over freshly appended data.
    template <class T>
    int data(const std::vector<T>& values, int componentType, size_t count, const std::string& type,
             bool normalized = false) {
        const size_t offset = append(values);
        return accessor(view(offset, values.size() * sizeof(T)), 0, componentType, count, type, normalized);
    }

    nlohmann::json finalJson(bool dataUri) const {
        nlohmann::json j = json;
        if (bin.empty()) return j;
        nlohmann::json buffer = {{"byteLength", bin.size()}};
        if (dataUri) buffer["uri"] = "data:application/octet-stream;base64," + base64(bin);
        j["buffers"] = nlohmann::json::array({buffer});
        return j;
    }
    void writeGltf(const std::filesystem::path& path) const { writeText(path, finalJson(true).dump()); }
    void writeGlb(const std::filesystem::path& path) const {
        std::string js = finalJson(false).dump();
        while (js.size() % 4) js += ' ';
        std::vector<uint8_t> b = bin;
        while (b.size() % 4) b.push_back(0);
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
        };
        u32(0x46546C67);  // "glTF"
        u32(2);
        u32(uint32_t(12 + 8 + js.size() + 8 + b.size()));
        u32(uint32_t(js.size()));
        u32(0x4E4F534A);  // "JSON"
        out.insert(out.end(), js.begin(), js.end());
        u32(uint32_t(b.size()));
        u32(0x004E4942);  // "BIN\0"
        out.insert(out.end(), b.begin(), b.end());
        writeBytes(path, out);
    }
};

// One triangle mesh, one node, one scene: the smallest valid file, to be altered by tests.
inline GltfBuilder oneTriangle(const std::vector<float>& positions = {0, 0, 0, 1, 0, 0, 0, 1, 0},
                               const std::vector<uint16_t>& indices = {0, 1, 2}) {
    GltfBuilder g;
    const int pos = g.data(positions, kF32, positions.size() / 3, "VEC3");
    nlohmann::json prim = {{"attributes", {{"POSITION", pos}}}};
    if (!indices.empty()) prim["indices"] = g.data(indices, kU16, indices.size(), "SCALAR");
    g.json["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array({prim})}}});
    g.json["nodes"] = nlohmann::json::array({{{"mesh", 0}}});
    g.json["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    g.json["scene"] = 0;
    return g;
}

}  // namespace starnt::test
