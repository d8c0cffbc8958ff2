// Builds small glTF 2.0 files by hand for importer and CLI tests: the JSON is edited
// directly (so broken files are as easy to make as valid ones) and binary data goes
// into one buffer written as a base64 data URI.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace crowdbake::test {

class GltfBuilder {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}},
                        {"scene", 0},
                        {"scenes", {{{"nodes", nlohmann::json::array()}}}}};

  // Appends raw bytes as a new bufferView (4-byte aligned); returns its index.
  int add_view(const void* data, size_t bytes) {
    while (bin_.size() % 4) bin_.push_back(0);
    const size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    std::memcpy(bin_.data() + offset, data, bytes);
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }

  template <typename T>
  int add_accessor(const std::vector<T>& values, int component_type, const std::string& type,
                   bool normalized = false) {
    const size_t per = components(type);
    const int view = add_view(values.data(), values.size() * sizeof(T));
    nlohmann::json acc = {{"bufferView", view},
                          {"componentType", component_type},
                          {"count", values.size() / per},
                          {"type", type}};
    if (normalized) acc["normalized"] = true;
    doc["accessors"].push_back(acc);
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const std::string& type) {
    return add_accessor(v, 5126, type);
  }
  int u16(const std::vector<uint16_t>& v, const std::string& type) {
    return add_accessor(v, 5123, type);
  }
  int u8(const std::vector<uint8_t>& v, const std::string& type, bool normalized = false) {
    return add_accessor(v, 5121, type, normalized);
  }

  int node(nlohmann::json n, bool scene_root = false) {
    doc["nodes"].push_back(std::move(n));
    const int index = static_cast<int>(doc["nodes"].size()) - 1;
    if (scene_root) doc["scenes"][0]["nodes"].push_back(index);
    return index;
  }

  // Appends a mesh with one triangle-list primitive; returns its index.
  int mesh(const std::string& name, nlohmann::json attributes, int indices = -1) {
    nlohmann::json primitive;
    primitive["attributes"] = std::move(attributes);
    if (indices >= 0) primitive["indices"] = indices;
    nlohmann::json m;
    m["name"] = name;
    m["primitives"] = nlohmann::json::array({primitive});
    doc["meshes"].push_back(m);
    return static_cast<int>(doc["meshes"].size()) - 1;
  }

  std::filesystem::path write(const std::filesystem::path& path) {
    nlohmann::json out = doc;
    out["buffers"] = {{{"byteLength", bin_.size()},
                       {"uri", "data:application/octet-stream;base64," + base64(bin_)}}};
    std::ofstream(path) << out.dump();
    return path;
  }

 private:
  static size_t components(const std::string& type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    return 16;
  }
  static std::string base64(const std::vector<uint8_t>& in) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
      const uint32_t b = (uint32_t{in[i]} << 16) |
                         (i + 1 < in.size() ? uint32_t{in[i + 1]} << 8 : 0u) |
                         (i + 2 < in.size() ? uint32_t{in[i + 2]} : 0u);
      out += table[(b >> 18) & 63];
      out += table[(b >> 12) & 63];
      out += i + 1 < in.size() ? table[(b >> 6) & 63] : '=';
      out += i + 2 < in.size() ? table[b & 63] : '=';
    }
    return out;
  }
  std::vector<uint8_t> bin_;
};

// A two-joint chain: "root" at the origin, "tip" one unit up (+Y), a mesh node that
// uses the skin and carries a translation of (10,0,0) glTF says to ignore, three
// vertices ((0,0,0) and (1,0,0) on root, (0,2,0) on tip) and one clip "bend" that
// turns the tip 90° about +Z between t = 0 and t = 1 (LINEAR).
inline GltfBuilder two_bone_character() {
  GltfBuilder b;
  const int root = b.node({{"name", "root"}, {"children", nlohmann::json::array({1})}}, true);
  b.node({{"name", "tip"}, {"translation", {0.0, 1.0, 0.0}}});
  const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  using nlohmann::json;
  json skin = {{"name", "body"},
               {"joints", json::array({root, 1})},
               {"inverseBindMatrices", b.floats(ibm, "MAT4")}};
  b.doc["skins"] = json::array({skin});
  json primitive;
  primitive["attributes"] = {{"POSITION", b.floats({0, 0, 0, 1, 0, 0, 0, 2, 0}, "VEC3")},
                             {"JOINTS_0", b.u16({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, "VEC4")},
                             {"WEIGHTS_0", b.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4")}};
  primitive["indices"] = b.u16({0, 1, 2}, "SCALAR");
  b.doc["meshes"] = json::array({json{{"name", "body"}, {"primitives", json::array({primitive})}}});
  b.node({{"name", "body"}, {"mesh", 0}, {"skin", 0}, {"translation", {10.0, 0.0, 0.0}}}, true);
  const float h = static_cast<float>(std::sqrt(0.5));
  json sampler = {{"input", b.floats({0, 1}, "SCALAR")},
                  {"output", b.floats({0, 0, 0, 1, 0, 0, h, h}, "VEC4")},
                  {"interpolation", "LINEAR"}};
  json channel = {{"sampler", 0}, {"target", {{"node", 1}, {"path", "rotation"}}}};
  b.doc["animations"] = json::array({json{{"name", "bend"},
                                          {"samplers", json::array({sampler})},
                                          {"channels", json::array({channel})}}});
  return b;
}

}  // namespace crowdbake::test
