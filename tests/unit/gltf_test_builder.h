#pragma once
// Test helper: builds small glTF documents by hand (nlohmann::json plus a binary buffer), as
// .gltf text with an embedded data: URI or as .glb bytes, so each test states exactly the
// glTF it feeds the loader.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::scene::testing {

inline std::string base64(const std::vector<uint8_t>& data) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    const uint32_t b0 = data[i];
    const uint32_t b1 = i + 1 < data.size() ? data[i + 1] : 0u;
    const uint32_t b2 = i + 2 < data.size() ? data[i + 2] : 0u;
    const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < data.size() ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < data.size() ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

class TestGltf {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<uint8_t> bin;

  // Appends raw bytes as a buffer view plus an accessor; returns the accessor index.
  int accessor(const void* data, size_t bytes, int component_type, const std::string& type,
               size_t count, bool normalized = false) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const size_t offset = bin.size();
    bin.resize(offset + bytes);
    if (bytes > 0) std::memcpy(bin.data() + offset, data, bytes);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    nlohmann::json a = {{"bufferView", doc["bufferViews"].size() - 1},
                        {"componentType", component_type},
                        {"count", count},
                        {"type", type}};
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return static_cast<int>(doc["accessors"].size() - 1);
  }
  int floats(const std::vector<float>& v, const std::string& type, size_t width) {
    return accessor(v.data(), v.size() * 4, 5126, type, v.size() / width);
  }
  int u32(const std::vector<uint32_t>& v) {
    return accessor(v.data(), v.size() * 4, 5125, "SCALAR", v.size());
  }
  int u16(const std::vector<uint16_t>& v) {
    return accessor(v.data(), v.size() * 2, 5123, "SCALAR", v.size());
  }
  int u8(const std::vector<uint8_t>& v) {
    return accessor(v.data(), v.size(), 5121, "SCALAR", v.size());
  }

  // A unit quad in the z = 0 plane facing +z: positions (and, optionally, indices).
  int quad_positions() { return floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3); }
  int quad_indices() { return u32({0, 1, 2, 0, 2, 3}); }

  // A mesh with one primitive; returns the mesh index.
  int mesh(const nlohmann::json& primitive, const std::string& name = "") {
    nlohmann::json m = {{"primitives", nlohmann::json::array({primitive})}};
    if (!name.empty()) m["name"] = name;
    doc["meshes"].push_back(m);
    return static_cast<int>(doc["meshes"].size() - 1);
  }
  int quad_mesh() {
    return mesh({{"attributes", {{"POSITION", quad_positions()}}}, {"indices", quad_indices()}});
  }

  int node(const nlohmann::json& n) {
    doc["nodes"].push_back(n);
    return static_cast<int>(doc["nodes"].size() - 1);
  }
  void scene(const std::vector<int>& roots) { doc["scenes"].push_back({{"nodes", roots}}); }

  // .gltf text with the buffer embedded as a data: URI.
  std::string text() const {
    nlohmann::json d = doc;
    if (!bin.empty()) {
      d["buffers"] =
          nlohmann::json::array({{{"byteLength", bin.size()},
                                  {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    }
    return d.dump();
  }
  std::vector<uint8_t> text_bytes() const {
    const std::string t = text();
    return {t.begin(), t.end()};
  }

  // .glb with the buffer in the BIN chunk.
  std::vector<uint8_t> glb() const {
    nlohmann::json d = doc;
    std::vector<uint8_t> body = bin;
    if (!body.empty()) d["buffers"] = nlohmann::json::array({{{"byteLength", body.size()}}});
    std::string json = d.dump();
    while (json.size() % 4 != 0) json += ' ';
    while (body.size() % 4 != 0) body.push_back(0);
    std::vector<uint8_t> out;
    auto u32le = [&](uint32_t v) {
      for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
    };
    const uint32_t total =
        static_cast<uint32_t>(12 + 8 + json.size() + (body.empty() ? 0 : 8 + body.size()));
    u32le(0x46546C67u);
    u32le(2);
    u32le(total);
    u32le(static_cast<uint32_t>(json.size()));
    u32le(0x4E4F534Au);
    out.insert(out.end(), json.begin(), json.end());
    if (!body.empty()) {
      u32le(static_cast<uint32_t>(body.size()));
      u32le(0x004E4942u);
      out.insert(out.end(), body.begin(), body.end());
    }
    return out;
  }
};

}  // namespace strata::scene::testing
