// Shared pieces of the runtime tests: packs baked by the real tools (make_spectator +
// `crowdbake bake`, once per test process), a small hand-built pack with known matrices, and
// a ByteSource that records every read.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/byte_source.h"
#include "pack_bytes.h"

namespace crowdbake::test {

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs a shell command; returns its exit code, its output in *log.
inline int run_command(const std::string& command, std::string* log) {
  static int counter = 0;
  const auto out =
      std::filesystem::temp_directory_path() /
      ("crowdbake-runtime-cmd-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  const int status =
      std::system((command + " >" + quote(out.string()) + " 2>&1 </dev/null").c_str());
  std::ifstream in(out);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::filesystem::remove(out);
  if (log) *log = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Packs baked from the generated spectator by the real executables, once per process, in a
// folder removed at exit:
//   spectator:     make_spectator (detail 1, seed 0), default bake (quantized animation, Draco)
//   spectator_f32: make_spectator --detail 0 --seed 3, float32 animation, raw geometry
//   spectator_impostor: the first with an impostor (8 views, 4 frames a clip, 32 texels high)
class BakedPacks {
 public:
  static const BakedPacks& get() {
    static BakedPacks packs;
    return packs;
  }
  const std::string& spectator() const { return spectator_; }
  const std::string& spectator_f32() const { return spectator_f32_; }
  const std::string& spectator_impostor() const { return spectator_impostor_; }
  const std::string& error() const { return error_; }
  const std::filesystem::path& dir() const { return dir_; }

  ~BakedPacks() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

 private:
  BakedPacks() {
    dir_ = std::filesystem::temp_directory_path() /
           ("crowdbake-runtime-packs-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    const std::string spectator = MAKE_SPECTATOR_EXE, crowdbake = CROWDBAKE_EXE;
    const auto glb = (dir_ / "spectator.glb").string(), glb3 = (dir_ / "spectator3.glb").string();
    const auto config = (dir_ / "f32.json").string(), quick = (dir_ / "quick.json").string();
    // note: few level-error samples over few frames: every test process bakes these packs, and
    // the tests need a LERR table, not an accurate one.
    std::ofstream(config) << R"({"animation": {"encoding": "float32"}, "geometry": {"codec": "raw"},
                              "simplify": {"samples": 8},
                              "level_errors": {"samples": 4, "fps": 0.25}})";
    std::ofstream(quick) << R"({"level_errors": {"samples": 4, "fps": 0.25}})";
    const auto impostor = (dir_ / "impostor.json").string();
    std::ofstream(impostor) << R"({"level_errors": {"samples": 4, "fps": 0.25},
                                 "impostor": {"views": 8, "frames_per_clip": 4, "height": 32}})";
    spectator_impostor_ = (dir_ / "spectator_impostor.crowdpack").string();
    spectator_ = (dir_ / "spectator.crowdpack").string();
    spectator_f32_ = (dir_ / "spectator_f32.crowdpack").string();
    const std::string commands[] = {
        quote(spectator) + " -o " + quote(glb) + " --quiet",
        quote(spectator) + " -o " + quote(glb3) + " --detail 0 --seed 3 --quiet",
        quote(crowdbake) + " bake " + quote(glb) + " -o " + quote(spectator_) + " --config " +
            quote(quick) + " --quiet",
        quote(crowdbake) + " bake " + quote(glb3) + " -o " + quote(spectator_f32_) + " --config " +
            quote(config) + " --quiet",
        quote(crowdbake) + " bake " + quote(glb) + " -o " + quote(spectator_impostor_) +
            " --config " + quote(impostor) + " --quiet",
    };
    for (const std::string& c : commands) {
      std::string log;
      if (run_command(c, &log) != 0) {
        error_ = "command failed: " + c + "\n" + log;
        return;
      }
    }
  }
  std::filesystem::path dir_;
  std::string spectator_, spectator_f32_, spectator_impostor_, error_;
};

#define CROWDBAKE_REQUIRE_BAKED_PACKS()                               \
  do {                                                                \
    ASSERT_TRUE(::crowdbake::test::BakedPacks::get().error().empty()) \
        << ::crowdbake::test::BakedPacks::get().error();              \
  } while (0)

inline std::vector<uint8_t> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_file(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A ByteSource over memory that records every read (offset, size) it serves.
class CountingSource final : public runtime::ByteSource {
 public:
  struct Read {
    uint64_t offset, size;
  };
  explicit CountingSource(std::vector<uint8_t> bytes, std::shared_ptr<std::vector<Read>> log)
      : bytes_(std::move(bytes)), log_(std::move(log)) {}
  uint64_t size() const override { return bytes_.size(); }
  const std::string& name() const override { return name_; }
  runtime::Status read(uint64_t offset, size_t count, uint8_t* out) override {
    log_->push_back({offset, count});
    if (offset > bytes_.size() || count > bytes_.size() - offset)
      return {runtime::StatusCode::kIoError, "counting source: read past the end"};
    if (count) std::memcpy(out, bytes_.data() + offset, count);
    return {};
  }

 private:
  std::vector<uint8_t> bytes_;
  std::shared_ptr<std::vector<Read>> log_;
  std::string name_ = "counting";
};

// Row r, joint j of the hand-built pack's animation: RotateY((10 r + 25 j) degrees), scaled
// by 1 + 0.05 j, translated by (0.1 r, j, -0.2 r).
inline void small_pack_matrix(uint32_t row, uint32_t joint, float out[12]) {
  const double a = (10.0 * row + 25.0 * joint) * 3.14159265358979323846 / 180.0;
  const double s = 1.0 + 0.05 * joint;
  const double c = std::cos(a) * s, n = std::sin(a) * s;
  const double m[12] = {c, 0, n, 0.1 * row, 0, s, 0, double(joint), -n, 0, c, -0.2 * row};
  for (int k = 0; k < 12; ++k) out[k] = static_cast<float>(m[k]);
}

// A small pack with every part filled and known values:
//   joints: root (-1), spine (0), head (1); inverse binds are translations by -(0, 0.8 j, 0)
//     with a small rotation about Z for the head;
//   clips (10 fps): "walk" 4 frames, looping, root motion (0.25 k, 0.5 k, 0.1 k) at frame k;
//     "wave" 3 frames, not looping; "pose" 1 frame. 8 rows, float32 (small_pack_matrix);
//   geometry: a (grid x grid) sheet, 4 influences per vertex; vertices 0, 1, 2 are bound 100%
//     to joints 0, 1, 2; ProgressiveMesh arrays that obey every structural rule (groups of
//     one and two vertices);
//   partition: 4 x 4 mask, neck 1.5, waist 0.9; bounds radius 2.
inline PackContents make_small_pack(uint32_t grid = 6, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  PackContents c;
  c.name = "small";
  c.settings_json = "{}";
  const char* names[] = {"root", "spine", "head"};
  for (int j = 0; j < 3; ++j) {
    PackJoint joint;
    joint.name = names[j];
    joint.parent = j - 1;
    joint.inverse_bind = {1, 0, 0, 0, 0, 1, 0, -0.8f * j, 0, 0, 1, 0};
    if (j == 2) {
      const float a = 0.3f, cs = std::cos(a), sn = std::sin(a);
      joint.inverse_bind = {cs, -sn, 0, 0.1f, sn, cs, 0, -1.6f, 0, 0, 1, 0.05f};
    }
    c.joints.push_back(joint);
  }
  const uint32_t frames[] = {4, 3, 1};
  const char* clip_names[] = {"walk", "wave", "pose"};
  uint32_t row = 0;
  for (int k = 0; k < 3; ++k) {
    PackClip clip;
    clip.name = clip_names[k];
    clip.first_row = row;
    clip.frame_count = frames[k];
    clip.fps = 10.0f;
    clip.duration = (frames[k] - 1) / 10.0f;
    clip.looping = k == 0;
    if (k == 0)
      for (uint32_t f = 0; f < frames[k]; ++f)
        clip.root_motion.insert(clip.root_motion.end(), {0.25f * f, 0.5f * f, 0.1f * f});
    row += frames[k];
    c.clips.push_back(clip);
  }
  c.materials = {{"skin", {1, 1, 1, 1}, ""}};

  PackGeometry& g = c.geometry;
  const uint32_t n = std::max<uint32_t>(grid, 3);
  for (uint32_t y = 0; y < n; ++y)
    for (uint32_t x = 0; x < n; ++x) {
      const uint32_t index = y * n + x;
      g.positions.insert(g.positions.end(),
                         {0.3f * x - 0.75f, 1.8f * y / (n - 1), 0.05f * unit(rng)});
      g.normals.insert(g.normals.end(), {0.0f, 0.0f, 1.0f});
      g.uvs.insert(g.uvs.end(), {float(x) / (n - 1), float(y) / (n - 1)});
      if (index < 3) {
        g.joints.insert(g.joints.end(), {uint16_t(index), 0, 0, 0});
        g.weights.insert(g.weights.end(), {1.0f, 0.0f, 0.0f, 0.0f});
      } else {
        float w[4] = {unit(rng), unit(rng), unit(rng), unit(rng)};
        const float sum = w[0] + w[1] + w[2] + w[3];
        for (int k = 0; k < 4; ++k) {
          g.joints.push_back(static_cast<uint16_t>((x + y + k) % 3));
          g.weights.push_back(w[k] / sum);
        }
      }
      g.regions.push_back(static_cast<uint8_t>(y < n / 3 ? 2 : y < 2 * n / 3 ? 1 : 0));
    }
  std::vector<std::array<uint32_t, 3>> tris;
  for (uint32_t y = 0; y + 1 < n; ++y)
    for (uint32_t x = 0; x + 1 < n; ++x) {
      const uint32_t a = y * n + x, b = a + 1, d = a + n, e = d + 1;
      tris.push_back({a, b, e});
      tris.push_back({a, e, d});
    }
  std::shuffle(tris.begin(), tris.end(), rng);
  for (const auto& t : tris) {
    g.triangles.insert(g.triangles.end(), t.begin(), t.end());
    g.triangle_material.push_back(0);
  }
  PackProgressive& p = c.progressive;
  const uint32_t vertices = g.vertex_count(), triangles = g.triangle_count();
  p.min_vertices = 4;
  for (uint32_t i = 0; i < vertices; ++i) {
    if (i < p.min_vertices) {
      p.collapse_to.push_back(i);
      p.group_start.push_back(i);
    } else {
      p.collapse_to.push_back(static_cast<uint32_t>(rng() % i));
      const bool pair = i > p.min_vertices && p.group_start[i - 1] == i - 1 && rng() % 3 == 0;
      p.group_start.push_back(pair ? i - 1 : i);
    }
  }
  for (uint32_t m = 0; m <= vertices; ++m) {
    const uint32_t k = m < p.min_vertices ? 0 : m - p.min_vertices;
    p.triangle_count.push_back(
        2 + static_cast<uint32_t>(uint64_t{triangles - 2} * k / (vertices - p.min_vertices)));
  }

  std::vector<double> matrices;
  for (uint32_t r = 0; r < row; ++r)
    for (uint32_t j = 0; j < 3; ++j) {
      float m[12];
      small_pack_matrix(r, j, m);
      matrices.insert(matrices.end(), m, m + 12);
    }
  c.animation = encode_animation_texture(AnimationEncoding::kFloat32, 3, row, matrices.data());

  PartitionMask& mask = c.partition;
  mask.width = mask.height = 4;
  mask.texels = {2, 2, 2, 2, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 255};
  mask.neck_height = 1.5f;
  mask.waist_height = 0.9f;

  PackBounds& b = c.bounds;
  b.min = {-0.75f, 0.0f, 0.0f};
  b.max = {0.3f * (n - 1) - 0.75f, 1.8f, 0.05f};
  b.radius = 2.0f;
  return c;
}

inline std::vector<uint8_t> small_pack_bytes(uint32_t grid = 6, uint32_t seed = 7) {
  PackWriteOptions options;
  options.codec = GeometryCodec::kRaw;
  return test::pack_bytes(make_small_pack(grid, seed), options);
}

}  // namespace crowdbake::test
