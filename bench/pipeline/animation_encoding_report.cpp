// Measures the animation texture encodings (docs/animation-encoding.md): for the generated
// spectator and every shared asset in MANIFEST.json, bakes with each encoding and reports
// texture bytes and the skinned vertex error against direct evaluation of the clips
// (pose_evaluator.h), normalised by the bind-pose bounding-box diagonal, for frame-nearest
// and linear sampling, at the baked frame times and half way between them. The runtime path
// is followed exactly: time → sample_joint → root motion re-applied → linear blend skinning.
//
// Not a unit test: run by hand, paste the table into the docs.
//   animation_encoding_report [--keep-root-motion] [--fps N] [--assets DIR]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "animation_bounded_codec.h"
#include "crowdbake/base/clock.h"
#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/import.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "pack_compression.h"
#include "pipeline_calls.h"
#include "spectator_character.h"

namespace {

using namespace crowdbake;

struct Stat {
  double sum = 0.0, max = 0.0;
  size_t count = 0;
  void add(double e) {
    sum += e;
    max = std::max(max, e);
    ++count;
  }
  double mean() const { return count ? sum / static_cast<double>(count) : 0.0; }
};

struct Errors {
  Stat frames[2];          // [filter] at baked frame times
  Stat mid[2];             // [filter] half way between frames
  std::string worst_clip;  // where the largest mid-frame linear error is
};

double bind_diagonal(const SkinnedAsset& a) {
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& v : p.positions) {
      lo = glm::min(lo, glm::dvec3(v));
      hi = glm::max(hi, glm::dvec3(v));
    }
  return glm::length(hi - lo);
}

// Skinned positions the runtime would draw at `time` of a baked clip.
void runtime_positions(const SkinnedAsset& a, const AnimationBake& bake, const PackClip& clip,
                       float time, FrameFilter filter, std::vector<glm::dvec3>& out) {
  const uint32_t joints = bake.texture.joints;
  std::vector<float> mats(12 * static_cast<size_t>(joints));
  float motion[3], motion_matrix[12], baked[12];
  sample_root_motion(clip, time, filter, motion);
  root_motion_matrix(motion, motion_matrix);
  for (uint32_t j = 0; j < joints; ++j) {
    sample_joint(bake.texture, clip, time, filter, j, baked);
    compose_affine(motion_matrix, baked, &mats[12 * j]);
  }
  out.clear();
  for (const Primitive& p : a.primitives)
    for (size_t v = 0; v < p.positions.size(); ++v) {
      const glm::dvec3 x(p.positions[v]);
      glm::dvec3 sum(0.0);
      for (int i = 0; i < 4; ++i) {
        const double w = p.weights[v][i];
        if (w == 0.0) continue;
        const float* m = &mats[12 * p.joints[v][i]];
        for (int r = 0; r < 3; ++r)
          sum[r] += w * (m[4 * r] * x.x + m[4 * r + 1] * x.y + m[4 * r + 2] * x.z + m[4 * r + 3]);
      }
      out.push_back(sum);
    }
}

Errors measure(const SkinnedAsset& a, const AnimationBake& bake, double diagonal) {
  Errors e;
  std::vector<glm::dvec3> got;
  for (size_t c = 0; c < bake.clips.size(); ++c) {
    const PackClip& clip = bake.clips[c];
    const Clip* source = a.clips.empty() ? nullptr : &a.clips[c];
    for (uint32_t k = 0; k < clip.frame_count; ++k) {
      for (int half = 0; half < 2; ++half) {
        if (half && k + 1 >= clip.frame_count) continue;
        const double t = source ? frame_time(*source, clip.frame_count, k + 0.5 * half) : 0.0;
        const std::vector<glm::dvec3> ref = skin_asset(a, source, t);
        for (int f = 0; f < 2; ++f) {
          runtime_positions(a, bake, clip, static_cast<float>(t), static_cast<FrameFilter>(f), got);
          Stat& s = half ? e.mid[f] : e.frames[f];
          const double before = s.max;
          for (size_t v = 0; v < ref.size(); ++v) s.add(glm::length(got[v] - ref[v]) / diagonal);
          if (half && f == 1 && s.max > before) e.worst_clip = clip.name;
        }
      }
    }
  }
  return e;
}

// CPU decode cost per joint matrix (ns): every (row, joint), nearest and blended.
void decode_cost(const AnimationTexture& t, double& nearest_ns, double& linear_ns) {
  float m[12];
  volatile float sink = 0.0f;
  const size_t n = static_cast<size_t>(t.rows) * t.joints;
  const int reps = static_cast<int>(std::max<size_t>(1, 2000000 / std::max<size_t>(n, 1)));
  auto run = [&](bool blend) {
    const auto start = std::chrono::steady_clock::now();
    for (int rep = 0; rep < reps; ++rep)
      for (uint32_t r = 0; r < t.rows; ++r)
        for (uint32_t j = 0; j < t.joints; ++j) {
          if (blend)
            decode_joint_blend(t, r, r + 1 < t.rows ? r + 1 : r, 0.37f, j, m);
          else
            decode_joint(t, r, j, m);
          sink = sink + m[3];
        }
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return 1e9 * s / (static_cast<double>(reps) * static_cast<double>(n));
  };
  nearest_ns = run(false);
  linear_ns = run(true);
}

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1e", v);
  return buf;
}

// Rows: the three encodings (texture bytes), then the quantized texture as the pack stores it
// (on-disk bytes): lossless zstd, and error-bounded at each of kBounds (fractions of the diagonal).
constexpr double kBounds[] = {5e-5, 1e-4, 2e-4};
constexpr int kRows = 4 + static_cast<int>(std::size(kBounds));

std::string row_name(int i) {
  static const AnimationEncoding encodings[] = {
      AnimationEncoding::kFloat32, AnimationEncoding::kFloat16, AnimationEncoding::kQuantized};
  if (i < 3) return animation_encoding_name(encodings[i]);
  if (i == 3) return "quantized, stored lossless";
  return "quantized, stored within " + sci(kBounds[i - 4]);
}

struct Totals {
  double frames_mean[kRows][2] = {}, mid_mean[kRows][2] = {}, frames_max[kRows][2] = {},
         mid_max[kRows][2] = {};
  double bytes[kRows] = {};
  int assets = 0;
};

// The pack's view of an imported asset: what the error-bounded coding needs (parents, the
// skinned vertices in runtime_positions' order, the bind box).
PackContents coding_contents(const SkinnedAsset& a, const AnimationTexture& texture) {
  PackContents c;
  for (const Joint& j : a.skeleton.joints) {
    PackJoint pj;
    pj.parent = j.parent;
    c.joints.push_back(pj);
  }
  c.animation = texture;
  for (const Primitive& p : a.primitives)
    for (size_t v = 0; v < p.positions.size(); ++v)
      for (int i = 0; i < 4; ++i) {
        if (i < 3) c.geometry.positions.push_back(p.positions[v][i]);
        c.geometry.joints.push_back(static_cast<uint16_t>(p.joints[v][i]));
        c.geometry.weights.push_back(p.weights[v][i]);
      }
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const Primitive& p : a.primitives)
    for (const glm::vec3& v : p.positions) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
  c.bounds.min = {lo.x, lo.y, lo.z};
  c.bounds.max = {hi.x, hi.y, hi.z};
  return c;
}

void report(const std::string& label, const SkinnedAsset& a, const AnimationBakeOptions& base,
            Totals& totals) {
  const double diagonal = bind_diagonal(a);
  size_t frames = 0;
  int looping = 0;
  std::string root = "-", worst;
  std::printf("\n#### %s\n\n", label.c_str());
  const AnimationEncoding encodings[] = {AnimationEncoding::kFloat32, AnimationEncoding::kFloat16,
                                         AnimationEncoding::kQuantized};
  std::printf(
      "| encoding | bytes | bound | frames nearest mean / max | frames linear mean / max | "
      "mid nearest mean / max | mid linear mean / max | bake ms | decode ns (nearest / linear) |\n"
      "|---|---:|---:|---|---|---|---|---:|---|\n");
  AnimationBake quantized;
  const auto add = [&](int i, const AnimationBake& bake, const Errors& e, double bytes,
                       double bound, double ms, double dn, double dl) {
    std::printf("| %s | %.0f | %s | %s / %s | %s / %s | %s / %s | %s / %s | %.0f | %.0f / %.0f |\n",
                row_name(i).c_str(), bytes, sci(bound / diagonal).c_str(),
                sci(e.frames[0].mean()).c_str(), sci(e.frames[0].max).c_str(),
                sci(e.frames[1].mean()).c_str(), sci(e.frames[1].max).c_str(),
                sci(e.mid[0].mean()).c_str(), sci(e.mid[0].max).c_str(),
                sci(e.mid[1].mean()).c_str(), sci(e.mid[1].max).c_str(), ms, dn, dl);
    for (const std::string& w : bake.warnings)
      std::fprintf(stderr, "  %s: %s\n", label.c_str(), w.c_str());
    for (int f = 0; f < 2; ++f) {
      totals.frames_mean[i][f] += e.frames[f].mean();
      totals.mid_mean[i][f] += e.mid[f].mean();
      totals.frames_max[i][f] = std::max(totals.frames_max[i][f], e.frames[f].max);
      totals.mid_max[i][f] = std::max(totals.mid_max[i][f], e.mid[f].max);
    }
    totals.bytes[i] += bytes;
  };
  for (int i = 0; i < 3; ++i) {
    AnimationBakeOptions o = base;
    o.encoding = encodings[i];
    const auto start = std::chrono::steady_clock::now();
    const AnimationBake bake = test::bake_animation_or_throw(a, o);
    const double ms =
        1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Errors e = measure(a, bake, diagonal);
    double dn, dl;
    decode_cost(bake.texture, dn, dl);
    frames = bake.texture.rows;
    looping = 0;
    for (const PackClip& c : bake.clips) looping += c.looping;
    if (bake.root_joint >= 0) root = a.skeleton.joints[bake.root_joint].name;
    if (i == 0) worst = e.worst_clip;
    add(i, bake, e, static_cast<double>(bake.texture.data.size()), bake.position_error_bound, ms,
        dn, dl);
    if (i == 2) quantized = bake;
  }
  // As stored: 'bake ms' is the coding's time, 'decode ns' the load-time expansion per joint
  // matrix (both columns hold it).
  {
    const auto start = std::chrono::steady_clock::now();
    const std::vector<uint8_t> frame = pack_io::compress_animation_texels(quantized.texture);
    const double ms = 1e3 * seconds_since(start);
    AnimationTexture back = quantized.texture;
    const auto load = std::chrono::steady_clock::now();
    pack_io::decompress_animation_texels(frame.data(), frame.size(), back, nullptr);
    const double ns = 1e9 * seconds_since(load) / (static_cast<double>(back.rows) * back.joints);
    add(3, quantized, measure(a, quantized, diagonal), static_cast<double>(frame.size()),
        quantized.position_error_bound, ms, ns, ns);
  }
  const PackContents contents = coding_contents(a, quantized.texture);
  for (size_t b = 0; b < std::size(kBounds); ++b) {
    const auto start = std::chrono::steady_clock::now();
    pack_io::BoundedAnimationCode code;
    std::string why;
    std::vector<uint32_t> starts;
    for (const PackClip& clip : quantized.clips) starts.push_back(clip.first_row);
    if (!pack_io::encode_bounded_animation(quantized.texture, contents.joints, starts,
                                           contents.geometry, kBounds[b] * diagonal, code, &why)) {
      std::fprintf(stderr, "  %s: error-bounded coding at %g: %s\n", label.c_str(), kBounds[b],
                   why.c_str());
      continue;
    }
    const std::vector<uint8_t> frame = pack_io::zstd_frame(code.stream);
    const double ms = 1e3 * seconds_since(start);
    AnimationTexture back = quantized.texture;
    const auto load = std::chrono::steady_clock::now();
    std::vector<uint8_t> stream;
    pack_io::expand_zstd_frame(frame.data(), frame.size(), code.stream.size(), stream, nullptr);
    pack_io::decode_bounded_animation(stream.data(), stream.size(), back, nullptr);
    const double ns = 1e9 * seconds_since(load) / (static_cast<double>(back.rows) * back.joints);
    AnimationBake stored = quantized;
    stored.texture = back;
    add(4 + static_cast<int>(b), stored, measure(a, stored, diagonal),
        static_cast<double>(frame.size()), quantized.position_error_bound + code.max_error, ms, ns,
        ns);
  }
  ++totals.assets;
  std::printf(
      "\n%zu vertices, %zu joints, %zu clips (%d looping), %zu rows, root motion joint %s, "
      "bind diagonal %.4g; largest mid-frame linear error in '%s'\n",
      a.vertex_count(), a.skeleton.joints.size(), std::max<size_t>(a.clips.size(), 1), looping,
      frames, root.c_str(), diagonal, worst.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  AnimationBakeOptions base;
  std::string assets = CROWDBAKE_SHARED_ASSETS;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--keep-root-motion"))
      base.extract_root_motion = false;
    else if (!std::strcmp(argv[i], "--fps") && i + 1 < argc)
      base.fps = std::atof(argv[++i]);
    else if (!std::strcmp(argv[i], "--assets") && i + 1 < argc)
      assets = argv[++i];
    else {
      std::fprintf(stderr, "usage: %s [--keep-root-motion] [--fps N] [--assets DIR]\n", argv[0]);
      return 2;
    }
  }
  std::printf(
      "Bake rate %g fps, root motion %s. Errors: |runtime − evaluator| / bind diagonal over "
      "every vertex; 'bound' = AnimationBake::position_error_bound / diagonal.\n",
      base.fps, base.extract_root_motion ? "extracted" : "kept");
  Totals totals;
  try {
    report("spectator (generated)", samples::make_spectator_character(), base, totals);
    std::ifstream in(assets + "/MANIFEST.json");
    if (!in) {
      std::fprintf(stderr, "no MANIFEST.json in %s: only the generated sample was measured\n",
                   assets.c_str());
    } else {
      const nlohmann::json manifest = nlohmann::json::parse(in);
      for (const auto& entry : manifest.at("assets")) {
        const std::string path = entry.at("path").get<std::string>();
        report(path, test::import_or_throw(assets + "/" + path), base, totals);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  std::printf("\n#### Summary over %d characters (mean of per-asset means; max of maxima)\n\n",
              totals.assets);
  std::printf(
      "| encoding | total bytes | frames mean / max | mid nearest mean / max | mid linear mean / "
      "max |\n"
      "|---|---:|---|---|---|\n");
  for (int i = 0; i < kRows; ++i)
    std::printf(
        "| %s | %.0f | %s / %s | %s / %s | %s / %s |\n", row_name(i).c_str(), totals.bytes[i],
        sci(totals.frames_mean[i][1] / totals.assets).c_str(), sci(totals.frames_max[i][1]).c_str(),
        sci(totals.mid_mean[i][0] / totals.assets).c_str(), sci(totals.mid_max[i][0]).c_str(),
        sci(totals.mid_mean[i][1] / totals.assets).c_str(), sci(totals.mid_max[i][1]).c_str());
  return 0;
}
