// `crowdbake inspect PACK` and `crowdbake diff A B`: packs baked from hand-built glTF
// files (some then edited through the pack reader and writer), checked as a user sees them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli/cli_runner.h"
#include "crowdbake/formats/pack.h"
#include "gltf_test_builder.h"
#include "pack_bytes.h"
#include "test_png.h"

namespace crowdbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::run_crowdbake;

// A tube of `rings` x `segments` vertices (height 2, radius 0.3, with normals and UVs)
// around a two-joint chain "hips" (origin) -> "chest" (y = 1), weights blending between
// y = 0.5 and 1.5, and one clip "sway": the hips move 1 unit along +X (root motion) while
// the chest turns 45 degrees about +Z.
test::GltfBuilder tube_character(int rings = 8, int segments = 8) {
  test::GltfBuilder b;
  const int hips = b.node({{"name", "hips"}, {"children", json::array({1})}}, true);
  b.node({{"name", "chest"}, {"translation", {0.0, 1.0, 0.0}}});
  const std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                                  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
  b.doc["skins"] = json::array(
      {json{{"joints", json::array({hips, 1})}, {"inverseBindMatrices", b.floats(ibm, "MAT4")}}});
  std::vector<float> positions, normals, uvs, weights;
  std::vector<uint16_t> joints, indices;
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const float angle = 6.2831853f * static_cast<float>(s) / static_cast<float>(segments);
      const float y = 2.0f * static_cast<float>(r) / static_cast<float>(rings - 1);
      positions.insert(positions.end(), {0.3f * std::cos(angle), y, 0.3f * std::sin(angle)});
      normals.insert(normals.end(), {std::cos(angle), 0.0f, std::sin(angle)});
      uvs.insert(uvs.end(), {static_cast<float>(s) / static_cast<float>(segments),
                             static_cast<float>(r) / static_cast<float>(rings - 1)});
      const float chest = std::clamp(y - 0.5f, 0.0f, 1.0f);
      joints.insert(joints.end(), {0, 1, 0, 0});
      weights.insert(weights.end(), {1.0f - chest, chest, 0.0f, 0.0f});
    }
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const auto at = [&](int rr, int ss) {
        return static_cast<uint16_t>(rr * segments + (ss % segments));
      };
      indices.insert(indices.end(), {at(r, s), at(r + 1, s), at(r + 1, s + 1)});
      indices.insert(indices.end(), {at(r, s), at(r + 1, s + 1), at(r, s + 1)});
    }
  json primitive;
  primitive["attributes"] = {{"POSITION", b.floats(positions, "VEC3")},
                             {"NORMAL", b.floats(normals, "VEC3")},
                             {"TEXCOORD_0", b.floats(uvs, "VEC2")},
                             {"JOINTS_0", b.u16(joints, "VEC4")},
                             {"WEIGHTS_0", b.floats(weights, "VEC4")}};
  primitive["indices"] = b.u16(indices, "SCALAR");
  b.doc["meshes"] = json::array({json{{"name", "tube"}, {"primitives", json::array({primitive})}}});
  b.node({{"name", "tube"}, {"mesh", 0}, {"skin", 0}}, true);
  const float h = static_cast<float>(std::sin(M_PI / 8)),
              c = static_cast<float>(std::cos(M_PI / 8));
  const int times = b.floats({0, 1}, "SCALAR");
  const json samplers = json::array({json{{"input", times},
                                          {"output", b.floats({0, 0, 0, 1, 0, 0}, "VEC3")},
                                          {"interpolation", "LINEAR"}},
                                     json{{"input", times},
                                          {"output", b.floats({0, 0, 0, 1, 0, 0, h, c}, "VEC4")},
                                          {"interpolation", "LINEAR"}}});
  const json channels =
      json::array({json{{"sampler", 0}, {"target", {{"node", hips}, {"path", "translation"}}}},
                   json{{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}}});
  b.doc["animations"] =
      json::array({json{{"name", "sway"}, {"samplers", samplers}, {"channels", channels}}});
  return b;
}

// Partition heights given explicitly so all three regions show up in the mask.
constexpr const char* kPartition =
    R"("partition": {"size": 64, "neck_height": 1.6, "waist_height": 0.9})";
// Exact floats, so packs written back through write_pack() compare bit for bit.
constexpr const char* kRawGeometry =
    R"("geometry": {"codec": "raw", "position_bits": 0, "normal_bits": 0, "uv_bits": 0})";

class PackCommands : public ::testing::Test {
 protected:
  // Bakes the tube with {kPartition, extra...} as its config; returns the pack's path.
  fs::path bake(const std::string& name, const std::string& extra = "") {
    if (!fs::exists(input_)) tube_character().write(input_);
    const fs::path config = dir_ / (name + ".json");
    std::ofstream(config) << "{" << kPartition << (extra.empty() ? "" : ", ") << extra << "}";
    const fs::path out = dir_ / (name + ".crowdpack");
    const test::CommandResult r =
        run_crowdbake({"bake", input_.string(), "-o", out.string(), "--config", config.string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return out;
  }

  static PackContents read(const fs::path& path) {
    const std::string bytes = test::slurp(path);
    PackContents contents;
    const Status status =
        read_pack(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), contents);
    EXPECT_TRUE(status.ok()) << status.message();
    return contents;
  }

  static std::vector<PackChunk> chunks(const fs::path& path) {
    const std::string bytes = test::slurp(path);
    std::vector<PackChunk> out;
    EXPECT_TRUE(
        read_pack_chunks(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), out).ok());
    return out;
  }

  fs::path write(const std::string& name, const PackContents& contents) {
    PackWriteOptions options;
    options.codec = GeometryCodec::kRaw;
    options.position_bits = options.normal_bits = options.uv_bits = 0;
    const std::vector<uint8_t> bytes = test::pack_bytes(contents, options);
    const fs::path out = dir_ / (name + ".crowdpack");
    std::ofstream(out, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return out;
  }

  // Runs `crowdbake diff A B --json extra...`; the JSON must parse and agree with the exit code.
  json diff_json(const fs::path& a, const fs::path& b, std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"diff", a.string(), b.string(), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::CommandResult r = run_crowdbake(args);
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const json j = json::parse(r.out, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << r.out;
    if (j.is_discarded()) return json::object();
    EXPECT_EQ(j["equal"].get<bool>(), r.exit_code == 0) << r.out;
    return j;
  }

  test::TempDir dir_;
  fs::path input_ = dir_ / "tube.gltf";
};

std::vector<std::string> differences(const json& j) {
  return j["differences"].get<std::vector<std::string>>();
}

// ---- inspect ------------------------------------------------------------------------

TEST_F(PackCommands, InspectTextShowsVersionChunksCountsLodClipsAndBytes) {
  const fs::path pack = bake("tube");
  const PackContents c = read(pack);
  const test::CommandResult r = run_crowdbake({"inspect", pack.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("pack 1." + std::to_string(kPackVersionMinor)), std::string::npos) << r.out;
  for (const char* tag : {"HEAD", "SKEL", "CLIP", "PROG", "GEOM", "ANIM", "PART"})
    EXPECT_NE(r.out.find(tag), std::string::npos) << tag << "\n" << r.out;
  EXPECT_NE(r.out.find("2 joints, 64 vertices, 112 triangles, 1 clips"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(std::to_string(c.progressive.min_vertices) + "..64 vertices"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("sway"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("quantized"), std::string::npos) << "the default encoding\n" << r.out;
  EXPECT_NE(r.out.find("64 x 64 mask"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("encoding=quantized"), std::string::npos) << "bake settings\n" << r.out;
  EXPECT_NE(r.out.find("per vertex"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("model units"), std::string::npos) << "the level errors\n" << r.out;
}

TEST_F(PackCommands, InspectJsonAgreesWithTheReader) {
  const fs::path pack = bake("tube16", R"("animation": {"encoding": "float16"})");
  const PackContents c = read(pack);
  const std::vector<PackChunk> table = chunks(pack);
  const test::CommandResult r = run_crowdbake({"inspect", pack.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["kind"], "pack");
  EXPECT_EQ(j["bytes"], fs::file_size(pack));
  EXPECT_EQ(j["format_version"]["major"], kPackVersionMajor);
  EXPECT_EQ(j["format_version"]["minor"], kPackVersionMinor);
  ASSERT_EQ(j["chunks"].size(), table.size());
  uint64_t geom = 0;
  for (size_t i = 0; i < table.size(); ++i) {
    EXPECT_EQ(j["chunks"][i]["tag"], pack_format::tag_name(table[i].tag));
    EXPECT_EQ(j["chunks"][i]["version"], table[i].version);
    EXPECT_EQ(j["chunks"][i]["offset"], table[i].offset);
    EXPECT_EQ(j["chunks"][i]["size"], table[i].size);
    EXPECT_EQ(j["chunks"][i]["checksum"], table[i].checksum);
    if (table[i].tag == pack_format::kTagGeom) geom = table[i].size;
  }
  EXPECT_EQ(
      j["counts"],
      json({{"joints", 2}, {"vertices", 64}, {"triangles", 112}, {"clips", 1}, {"materials", 1}}));
  EXPECT_EQ(j["lod"]["min_vertices"], c.progressive.min_vertices);
  EXPECT_EQ(j["lod"]["max_vertices"], 64);
  EXPECT_EQ(j["lod"]["min_triangles"], c.progressive.triangle_count[c.progressive.min_vertices]);
  EXPECT_EQ(j["lod"]["max_triangles"], 112);
  // A joint is listed as missing at the coarsest level exactly when it is the heaviest of some
  // vertex and of none the coarsest level keeps.
  std::vector<int> kept(c.joints.size(), 0), any(c.joints.size(), 0);
  for (uint32_t v = 0; v < c.geometry.vertex_count(); ++v) {
    const float* w = &c.geometry.weights[4 * v];
    const int k = static_cast<int>(std::max_element(w, w + 4) - w);
    const uint16_t joint = c.geometry.joints[4 * v + k];
    any[joint] = 1;
    if (v < c.progressive.min_vertices) kept[joint] = 1;
  }
  std::vector<std::string> expected, listed;
  for (size_t k = 0; k < c.joints.size(); ++k)
    if (any[k] && !kept[k]) expected.push_back(c.joints[k].name);
  for (const json& m : j["lod"]["joints_missing_at_min"]) {
    listed.push_back(m["joint"]);
    EXPECT_GT(m["coarsest_level"], c.progressive.min_vertices);
  }
  EXPECT_EQ(listed, expected);
  // Of those, unreached are the ones no joint below them (by the pack's parents) keeps a vertex of.
  const auto below = [&](size_t joint, size_t above) {
    for (int p = c.joints[joint].parent; p >= 0; p = c.joints[p].parent)
      if (static_cast<size_t>(p) == above) return true;
    return false;
  };
  std::vector<std::string> unreached_expected, unreached_listed;
  for (size_t k = 0; k < c.joints.size(); ++k) {
    if (!any[k] || kept[k]) continue;
    bool reached = false;
    for (size_t d = 0; d < c.joints.size(); ++d) reached = reached || (kept[d] && below(d, k));
    if (!reached) unreached_expected.push_back(c.joints[k].name);
  }
  for (const json& m : j["lod"]["joints_unreached_at_min"]) {
    unreached_listed.push_back(m["joint"]);
    EXPECT_GT(m["coarsest_level"], c.progressive.min_vertices);
  }
  EXPECT_EQ(unreached_listed, unreached_expected);
  // The level errors error-driven LoD reads, sample by sample.
  ASSERT_GE(c.level_errors.vertices.size(), 2u);
  ASSERT_EQ(j["level_errors"].size(), c.level_errors.vertices.size());
  for (size_t k = 0; k < c.level_errors.vertices.size(); ++k) {
    EXPECT_EQ(j["level_errors"][k]["vertices"], c.level_errors.vertices[k]);
    EXPECT_EQ(j["level_errors"][k]["max"].get<float>(), c.level_errors.max_error[k]);
  }
  ASSERT_EQ(j["clips"].size(), 1u);
  EXPECT_EQ(j["clips"][0]["name"], "sway");
  EXPECT_EQ(j["clips"][0]["frames"], c.clips[0].frame_count);
  EXPECT_EQ(j["clips"][0]["fps"], 30.0);
  EXPECT_EQ(j["clips"][0]["duration"], 1.0);
  EXPECT_EQ(j["clips"][0]["looping"], c.clips[0].looping);
  EXPECT_EQ(j["clips"][0]["root_motion"], true);
  EXPECT_EQ(j["animation"]["encoding"], "float16");
  EXPECT_EQ(j["animation"]["stored"], "lossless") << "only quantized textures are coded";
  EXPECT_EQ(j["animation"]["width"], c.animation.width());
  EXPECT_EQ(j["animation"]["height"], c.animation.rows);
  EXPECT_EQ(j["partition"]["width"], 64);
  EXPECT_EQ(j["partition"]["height"], 64);
  const json& texels = j["partition"]["texels"];
  EXPECT_EQ(texels["head"].get<int>() + texels["upper_body"].get<int>() +
                texels["trousers"].get<int>() + texels["unused"].get<int>(),
            64 * 64);
  for (const char* region : {"head", "upper_body", "trousers"})
    EXPECT_GT(texels[region], 0) << region;
  EXPECT_EQ(j["settings"]["animation"]["encoding"], "float16");
  EXPECT_EQ(j["settings"]["partition"]["size"], 64);
  EXPECT_EQ(j["bytes_per_component"]["chunks"]["GEOM"], geom);
  EXPECT_DOUBLE_EQ(j["bytes_per_component"]["geometry_per_vertex"].get<double>(), geom / 64.0);
}

// The default bake codes its quantized animation within animation.max_error (ANIM v3); 0 keeps
// it lossless (ANIM v2); inspect says which.
TEST_F(PackCommands, InspectSaysHowTheAnimationIsStored) {
  for (const char* max_error : {"1e-4", "0"}) {
    const bool bounded = std::string(max_error) != "0";
    const fs::path pack = bake(std::string("tube_anim") + (bounded ? "_bounded" : "_lossless"),
                               std::string(R"("animation": {"max_error": )") + max_error + "}");
    uint32_t version = 0;
    for (const PackChunk& chunk : chunks(pack))
      if (chunk.tag == pack_format::kTagAnim) version = chunk.version;
    const test::CommandResult r = run_crowdbake({"inspect", pack.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["animation"]["stored"], version == 3 ? "error-bounded" : "lossless") << max_error;
    if (!bounded) {
      EXPECT_EQ(version, 2u);
    }
  }
  // note: the small tube's lossless texels are the smaller, so its bounded bake stays ANIM v2;
  // the frozen 1.5 spectator is coded (ANIM v3), the 1.4 one is not.
  const fs::path frozen = fs::path(CROWDBAKE_SOURCE_DIR) / "tests" / "data" / "packs";
  for (const auto& [set, stored] : {std::pair{"v1.5", "error-bounded"}, {"v1.4", "lossless"}}) {
    const fs::path pack = frozen / set / "spectator_draco.crowdpack";
    const test::CommandResult r = run_crowdbake({"inspect", pack.string(), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(json::parse(r.out)["animation"]["stored"], stored) << set;
  }
}

TEST_F(PackCommands, InspectOfACharacterFileIsUnchanged) {
  tube_character().write(input_);
  const test::CommandResult r = run_crowdbake({"inspect", input_.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["vertices"], 64);
}

// Bad pack: one line "error: <file>: <what>; <what to do>", the reader's message, exit 1.
void expect_inspect_error(const fs::path& file, const std::string& fragment) {
  const test::CommandResult r = run_crowdbake({"inspect", file.string()});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("error: " + file.string() + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("; "), std::string::npos) << "says what to do\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

// Flips one byte in the middle of a chunk's payload.
fs::path corrupt_chunk(const fs::path& pack, uint32_t tag, const fs::path& out) {
  std::string bytes = test::slurp(pack);
  std::vector<PackChunk> table;
  read_pack_chunks(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), table);
  for (const PackChunk& c : table)
    if (c.tag == tag) bytes[c.offset + c.size / 2] ^= 0x5a;
  std::ofstream(out, std::ios::binary) << bytes;
  return out;
}

TEST_F(PackCommands, InspectCorruptChunkGivesTheReadersError) {
  const fs::path pack = bake("tube");
  expect_inspect_error(corrupt_chunk(pack, pack_format::kTagGeom, dir_ / "bad.crowdpack"),
                       "chunk GEOM: checksum mismatch");
}

TEST_F(PackCommands, InspectTruncatedPack) {
  const std::string bytes = test::slurp(bake("tube"));
  std::ofstream(dir_ / "short.crowdpack", std::ios::binary) << bytes.substr(0, bytes.size() - 16);
  expect_inspect_error(dir_ / "short.crowdpack", "truncated pack");
}

TEST_F(PackCommands, InspectGarbageNamedLikeAPack) {
  std::ofstream(dir_ / "notes.crowdpack") << "not a pack at all\n";
  expect_inspect_error(dir_ / "notes.crowdpack", "not a crowdbake pack");
}

TEST_F(PackCommands, InspectMissingPack) {
  expect_inspect_error(dir_ / "gone.crowdpack", "file not found");
}

// ---- diff ---------------------------------------------------------------------------

TEST_F(PackCommands, DiffOfTwoBakesWithTheSameSettingsIsEqual) {
  const fs::path a = bake("a"), b = bake("b");
  const test::CommandResult r = run_crowdbake({"diff", a.string(), b.string()});
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("equal within tolerance"), std::string::npos) << r.out;
  for (const char* section : {"header", "settings", "skeleton", "clips", "geometry", "progressive",
                              "animation", "partition", "sizes"})
    EXPECT_NE(r.out.find(section), std::string::npos) << section << "\n" << r.out;
  const json j = diff_json(a, b);
  EXPECT_TRUE(j["equal"].get<bool>());
  EXPECT_EQ(j["sections"]["geometry"]["vertex_order"], "same");
  EXPECT_EQ(j["sections"]["geometry"]["first_differing_triangle"], -1);
  EXPECT_EQ(j["sections"]["partition"]["changed_texels"], 0);
}

TEST_F(PackCommands, DiffOfEncodingsNamesTheSettingAndComparesDecodedMatrices) {
  const fs::path a = bake("quantized"),
                 b = bake("float32", R"("animation": {"encoding": "float32"})");
  const test::CommandResult r = run_crowdbake({"diff", a.string(), b.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("animation.encoding: \"quantized\" -> \"float32\""), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("quantized vs float32"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("different: settings"), std::string::npos) << r.out;

  json j = diff_json(a, b);
  const std::vector<std::string> d = differences(j);
  EXPECT_NE(std::find(d.begin(), d.end(), "animation"), d.end()) << j.dump(1);
  ASSERT_EQ(j["sections"]["animation"]["clips"].size(), 1u);
  const double max_diff = j["sections"]["animation"]["clips"][0]["max_abs_diff"];
  EXPECT_GT(max_diff, 0.0);
  EXPECT_LT(max_diff, 1e-3) << "quantized stays close to float32";
  EXPECT_EQ(j["sections"]["geometry"]["differs"], false);

  // Within tolerance once the settings are ignored; the settings still count otherwise.
  j = diff_json(a, b, {"--tolerance", "1e-3", "--ignore", "settings"});
  EXPECT_TRUE(j["equal"].get<bool>()) << j.dump(1);
  EXPECT_EQ(j["sections"]["settings"]["status"], "ignored");
  j = diff_json(a, b, {"--tolerance", "1e-3"});
  EXPECT_EQ(differences(j), std::vector<std::string>{"settings"}) << j.dump(1);
  // Outside a tolerance below the measured difference.
  j = diff_json(a, b, {"--tolerance", std::to_string(max_diff / 4), "--ignore", "settings"});
  EXPECT_FALSE(j["equal"].get<bool>());
  EXPECT_EQ(j["sections"]["animation"]["status"], "DIFFERS") << j.dump(1);
}

TEST_F(PackCommands, DiffPositionToleranceIsRelativeToTheDiagonal) {
  const fs::path exact = bake("raw", kRawGeometry);
  const fs::path coarse =
      bake("draco8",
           R"("geometry": {"codec": "draco", "position_bits": 8, "normal_bits": 8, "uv_bits": 10,
                      "weight_bits": 0})");
  json j = diff_json(exact, coarse, {"--ignore", "settings"});
  EXPECT_EQ(differences(j), std::vector<std::string>{"geometry"}) << j.dump(1);
  const json& g = j["sections"]["geometry"];
  EXPECT_EQ(g["positions"], "differ");
  EXPECT_EQ(g["vertex_order"], "same") << "quantisation keeps the order";
  EXPECT_EQ(g["triangle_order"], "same");
  const double relative = g["max_position_diff_relative"];
  // 8 bits over the bounding cube (side 2 here, diagonal ~2.1): at most 2 / 510 per axis.
  EXPECT_GT(relative, 0.0);
  EXPECT_LT(relative, 4e-3);
  EXPECT_NEAR(relative * j["diagonal"].get<double>(), g["max_position_diff"].get<double>(), 1e-12);

  j = diff_json(exact, coarse, {"--ignore", "settings", "--tolerance", "1e-2"});
  EXPECT_TRUE(j["equal"].get<bool>()) << j.dump(1);
  EXPECT_EQ(j["sections"]["geometry"]["vertex_order"], "same");
  const std::string below = std::to_string(relative * 0.5);
  j = diff_json(exact, coarse, {"--ignore", "settings", "--tolerance", below});
  EXPECT_EQ(differences(j), std::vector<std::string>{"geometry"}) << j.dump(1);
}

TEST_F(PackCommands, DiffOfBakeRatesReportsFrameCounts) {
  const fs::path a = bake("30fps"), b = bake("15fps", R"("animation": {"fps": 15})");
  const test::CommandResult r = run_crowdbake({"diff", a.string(), b.string()});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("clip \"sway\": frames 31 -> 16"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("animation.fps"), std::string::npos) << r.out;
  const std::vector<std::string> d = differences(diff_json(a, b));
  EXPECT_NE(std::find(d.begin(), d.end(), "clips"), d.end());
}

// Same mesh, vertices and triangles stored in another order (no progressive arrays, so
// any order is a valid pack).
TEST_F(PackCommands, DiffTellsOrderFromContent) {
  PackContents base = read(bake("raw", kRawGeometry));
  base.progressive = {};
  const fs::path a = write("unordered", base);

  PackContents reversed = base;
  PackGeometry& g = reversed.geometry;
  const uint32_t n = g.vertex_count();
  auto reverse_vertices = [n](std::vector<float>& v, size_t per) {
    std::vector<float> out(v.size());
    for (uint32_t i = 0; i < n; ++i)
      std::copy_n(v.begin() + per * (n - 1 - i), per, out.begin() + per * i);
    v = out;
  };
  reverse_vertices(g.positions, 3), reverse_vertices(g.normals, 3), reverse_vertices(g.uvs, 2);
  reverse_vertices(g.weights, 4);
  std::vector<uint16_t> joints(g.joints.size());
  for (uint32_t i = 0; i < n; ++i)
    std::copy_n(g.joints.begin() + 4 * (n - 1 - i), 4, joints.begin() + 4 * i);
  g.joints = joints;
  std::reverse(g.regions.begin(), g.regions.end());
  for (uint32_t& v : g.triangles) v = n - 1 - v;
  const fs::path b = write("reversed_vertices", reversed);

  json j = diff_json(a, b);
  EXPECT_EQ(differences(j), std::vector<std::string>{"geometry"}) << j.dump(1);
  EXPECT_EQ(j["sections"]["geometry"]["vertex_order"], "differs");
  EXPECT_EQ(j["sections"]["geometry"]["positions"], "equal") << "once vertices are paired";
  EXPECT_EQ(j["sections"]["geometry"]["max_normals_diff"], 0.0)
      << "attributes compare through the pairing";
  EXPECT_EQ(j["sections"]["geometry"]["regions_differ"], 0);
  EXPECT_EQ(j["sections"]["geometry"]["triangle_order"], "same")
      << "the same triangles once vertices are paired";

  PackContents triangles = base;
  std::vector<uint32_t>& t = triangles.geometry.triangles;
  std::rotate(t.begin() + 3 * 5, t.begin() + 3 * 6, t.begin() + 3 * 7);  // swap triangles 5 and 6
  std::rotate(t.begin() + 3 * 9, t.begin() + 3 * 9 + 1,
              t.begin() + 3 * 10);  // triangle 9: same corners, rotated
  const fs::path c = write("swapped_triangles", triangles);
  j = diff_json(a, c);
  EXPECT_EQ(differences(j), std::vector<std::string>{"geometry"}) << j.dump(1);
  EXPECT_EQ(j["sections"]["geometry"]["vertex_order"], "same");
  EXPECT_EQ(j["sections"]["geometry"]["triangle_order"], "differs");
  EXPECT_EQ(j["sections"]["geometry"]["first_differing_triangle"], 5);
  const test::CommandResult r = run_crowdbake({"diff", a.string(), c.string()});
  EXPECT_NE(r.out.find("triangle order differs from triangle 5 (the same triangles)"),
            std::string::npos)
      << r.out;

  PackContents flipped = base;
  std::swap(flipped.geometry.triangles[3 * 7 + 1],
            flipped.geometry.triangles[3 * 7 + 2]);  // winding
  j = diff_json(a, write("flipped", flipped));
  EXPECT_EQ(j["sections"]["geometry"]["triangle_order"], "triangles differ");
  EXPECT_EQ(j["sections"]["geometry"]["first_differing_triangle"], 7);
}

TEST_F(PackCommands, DiffNamesEachEditedSection) {
  const fs::path a = bake("raw", kRawGeometry);
  const PackContents base = read(a);
  {
    // note: a pack written back unchanged compares equal (the reader and writer agree).
    const json j = diff_json(a, write("same", base));
    EXPECT_TRUE(j["equal"].get<bool>()) << j.dump(1);
  }
  {
    PackContents c = base;
    c.joints[1].name = "spine";
    const json j = diff_json(a, write("renamed", c));
    EXPECT_EQ(differences(j), std::vector<std::string>{"skeleton"}) << j.dump(1);
    EXPECT_EQ(j["sections"]["skeleton"]["first_name_difference"], 1);
  }
  {
    PackContents c = base;
    c.joints[0].inverse_bind[3] += 0.01f;  // translation x
    const json j = diff_json(a, write("rebound", c));
    EXPECT_EQ(differences(j), std::vector<std::string>{"skeleton"}) << j.dump(1);
    EXPECT_NEAR(j["sections"]["skeleton"]["inverse_bind_translation_max_diff"].get<double>(), 0.01,
                1e-6);
    // 0.01 model units is ~0.0047 of the diagonal: within 1e-2, not within 1e-3.
    EXPECT_TRUE(diff_json(a, write("rebound", c), {"--tolerance", "1e-2"})["equal"].get<bool>());
    EXPECT_FALSE(diff_json(a, write("rebound", c), {"--tolerance", "1e-3"})["equal"].get<bool>());
  }
  {
    PackContents c = base;
    for (int i = 0; i < 3; ++i)
      c.partition.texels[100 + i] = static_cast<uint8_t>((c.partition.texels[100 + i] + 1) % 3);
    const json j = diff_json(a, write("repainted", c));
    EXPECT_EQ(differences(j), std::vector<std::string>{"partition"}) << j.dump(1);
    EXPECT_EQ(j["sections"]["partition"]["changed_texels"], 3);
  }
  {
    PackContents c = base;
    const uint32_t last = c.geometry.vertex_count() - 1;
    ASSERT_GE(last, c.progressive.min_vertices);
    c.progressive.collapse_to[last] = c.progressive.collapse_to[last] == 0 ? 1 : 0;
    const json j = diff_json(a, write("recollapsed", c));
    EXPECT_EQ(differences(j), std::vector<std::string>{"progressive"}) << j.dump(1);
    EXPECT_EQ(j["sections"]["progressive"]["first_difference_collapse_to"], last);
    EXPECT_EQ(j["sections"]["progressive"]["first_difference_group_start"], -1);
  }
  {
    PackContents c = base;
    c.clips[0].looping = !c.clips[0].looping;
    c.clips[0].root_motion[3 * 5] += 0.5f;
    const json j = diff_json(a, write("relooped", c));
    EXPECT_EQ(differences(j), std::vector<std::string>{"clips"}) << j.dump(1);
    EXPECT_EQ(j["sections"]["clips"]["differences"].size(), 2u) << j.dump(1);
  }
}

// The tube with one material whose base colour texture is `image` (a glTF image object);
// `png` (when given) is embedded as a buffer view and `image` may refer to it as view -1.
test::GltfBuilder textured_tube(json image, const std::vector<uint8_t>& png = {}) {
  test::GltfBuilder b = tube_character();
  if (!png.empty()) image["bufferView"] = b.add_view(png.data(), png.size());
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["materials"] = json::array(
      {json{{"name", "cloth"},
            {"alphaMode", "MASK"},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {1.0, 0.5, 0.5, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["textures"] = json::array({json{{"source", 0}}});
  b.doc["images"] = json::array({image});
  return b;
}

TEST_F(PackCommands, TexturedBakeShowsItsImageAndDiffComparesIt) {
  const std::vector<uint8_t> png = test::solid_image(4, 4, {200, 100, 50, 255});
  const fs::path input = dir_ / "textured.gltf";
  textured_tube({{"name", "cloth_albedo"}, {"mimeType", "image/png"}}, png).write(input);
  const fs::path pack = dir_ / "textured.crowdpack";
  test::CommandResult r = run_crowdbake({"bake", input.string(), "-o", pack.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_crowdbake({"inspect", pack.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("IMGS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("texture cloth_albedo (image 0)  alpha mask"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("images     1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("image/png 4 x 4, " + std::to_string(png.size()) + " bytes"),
            std::string::npos)
      << r.out;
  r = run_crowdbake({"inspect", pack.string(), "--json"});
  const json j = json::parse(r.out);
  EXPECT_EQ(j["materials"][0]["image"], 0);
  EXPECT_EQ(j["materials"][0]["alpha_mode"], "mask");
  EXPECT_EQ(j["images"][0]["width"], 4);
  EXPECT_EQ(j["images"][0]["bytes"], png.size());
  // The character file itself lists its materials and images the same way.
  r = run_crowdbake({"inspect", input.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("texture cloth_albedo (image 0)  alpha mask"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("image/png 4 x 4, " + std::to_string(png.size()) + " bytes"),
            std::string::npos)
      << r.out;
  r = run_crowdbake({"inspect", input.string(), "--json"});
  const json source = json::parse(r.out);
  EXPECT_EQ(source["materials"], j["materials"]);
  EXPECT_EQ(source["images"], j["images"]);

  PackContents c = read(pack);
  ASSERT_EQ(c.images.size(), 1u);
  EXPECT_EQ(c.images[0].data, png);
  const fs::path rewritten = write("rewritten", c);  // the same writer options on both sides
  c.images[0].data = test::solid_image(4, 4, {10, 100, 50, 255});
  const json d = diff_json(rewritten, write("repainted", c));
  EXPECT_EQ(differences(d), std::vector<std::string>{"materials"}) << d.dump(1);
  EXPECT_EQ(d["sections"]["materials"]["images_differ"], 1) << d.dump(1);
}

TEST_F(PackCommands, MissingTextureWarnsOrFailsWithStrictTextures) {
  const fs::path input = dir_ / "missing_texture.gltf";
  textured_tube({{"uri", "nowhere.png"}}).write(input);
  const fs::path pack = dir_ / "missing_texture.crowdpack";
  const fs::path report = dir_ / "report.json";
  test::CommandResult r = run_crowdbake(
      {"bake", input.string(), "-o", pack.string(), "--report", report.string(), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string warnings = json::parse(test::slurp(report))["warnings"].dump();
  EXPECT_NE(warnings.find("texture 'nowhere.png' of material 'cloth'"), std::string::npos)
      << warnings;
  EXPECT_TRUE(read(pack).images.empty());
  fs::remove(pack);
  r = run_crowdbake({"bake", input.string(), "-o", pack.string(), "--strict-textures", "--quiet"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.rfind("error: " + input.string() + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("nowhere.png"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(pack)) << "nothing half-written";
}

// ---- diff errors: exit 2, one line ---------------------------------------------------

void expect_diff_error(const std::vector<std::string>& args, const std::string& file,
                       const std::string& fragment) {
  const test::CommandResult r = run_crowdbake(args);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(test::count_lines(r.err), 1) << r.err;
  if (!file.empty()) {
    EXPECT_EQ(r.err.rfind("error: " + file + ": ", 0), 0u) << r.err;
  }
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(PackCommands, DiffOfAMissingPackIsExit2) {
  const fs::path a = bake("a");
  const std::string missing = (dir_ / "missing.crowdpack").string();
  expect_diff_error({"diff", a.string(), missing}, missing, "file not found");
  expect_diff_error({"diff", missing, a.string(), "--json"}, missing, "file not found");
}

TEST_F(PackCommands, DiffOfACorruptPackIsExit2) {
  const fs::path a = bake("a");
  const fs::path bad = corrupt_chunk(a, pack_format::kTagAnim, dir_ / "bad.crowdpack");
  expect_diff_error({"diff", a.string(), bad.string()}, bad.string(),
                    "chunk ANIM: checksum mismatch");
  std::ofstream(dir_ / "model.glb") << "glTF not a pack";
  expect_diff_error({"diff", (dir_ / "model.glb").string(), a.string()},
                    (dir_ / "model.glb").string(), "not a crowdbake pack");
}

TEST_F(PackCommands, DiffUsageErrorsAreExit2) {
  const fs::path a = bake("a");
  expect_diff_error({"diff", a.string()}, "", "B is required");
  expect_diff_error({"diff", a.string(), a.string(), "--tolerance", "-1"}, "", "--tolerance");
  expect_diff_error({"diff", a.string(), a.string(), "--ignore", "everything"}, "", "--ignore");
}

}  // namespace
}  // namespace crowdbake
