// build_pack(): simplify → bake animation → bake partition → geometry in progressive
// order → skeleton, clips, materials, bounds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <future>
#include <limits>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "crowdbake/base/clock.h"
#include "crowdbake/base/parallel.h"
#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/pipeline/animated_error.h"
#include "crowdbake/pipeline/animation_bake.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/pose_evaluator.h"
#include "import/node_transform.h"
#include "jpeg_recoding.h"
#include "variant_images.h"

namespace crowdbake {
namespace {

class StageClock {
 public:
  explicit StageClock(BakeReport& report) : report_(report) {}
  void done(const std::string& name) {
    report_.stages.push_back({name, seconds_since(start_)});
    restart();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  BakeReport& report_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The bakes that need only the asset (see build_or_throw).
struct SideBakes {
  AnimationBake animation;
  PartitionBake partition;
  double animation_seconds = 0.0, partition_seconds = 0.0;
};

std::array<float, 12> rows_of(const glm::dmat4& m) {
  std::array<float, 12> out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out[4 * r + c] = static_cast<float>(m[c][r]);
  return out;
}

// Vertex i of the concatenated primitives -> (primitive, index in it).
std::vector<std::pair<uint32_t, uint32_t>> vertex_origins(const SkinnedAsset& asset) {
  std::vector<std::pair<uint32_t, uint32_t>> origin;
  for (uint32_t p = 0; p < asset.primitives.size(); ++p)
    for (uint32_t v = 0; v < asset.primitives[p].vertex_count(); ++v) origin.push_back({p, v});
  return origin;
}

// The vertices' COLOR_0 in pack order as RGBA8 (colour channels sRGB-encoded, the display
// values the renderer shades in; alpha linear); vertices of primitives without colours are
// white. Empty when every vertex is white: such colours change nothing (exporters often write
// them), so they cost no bytes.
std::vector<uint32_t> vertex_colors(const SkinnedAsset& asset, const ProgressiveMesh& pm) {
  const auto origin = vertex_origins(asset);
  const auto byte = [](float x, bool srgb) {
    const double v =
        srgb ? (x <= 0.0031308f ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055) : double{x};
    return static_cast<uint32_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  };
  std::vector<uint32_t> out(pm.vertex_count(), 0xFFFFFFFFu);
  bool any = false;
  for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
    const auto [prim, v] = origin[pm.vertex_source[i]];
    const Primitive& p = asset.primitives[prim];
    if (p.colors.empty()) continue;
    const glm::vec4& c = p.colors[v];
    out[i] =
        byte(c.r, true) | byte(c.g, true) << 8 | byte(c.b, true) << 16 | byte(c.a, false) << 24;
    any = any || out[i] != 0xFFFFFFFFu;
  }
  if (!any) out.clear();
  return out;
}

void fill_geometry(const SkinnedAsset& asset, const ProgressiveMesh& pm,
                   const std::vector<std::vector<uint8_t>>& regions,
                   std::vector<PackMaterial>& materials, PackGeometry& g) {
  const auto origin = vertex_origins(asset);
  const bool normals = std::all_of(asset.primitives.begin(), asset.primitives.end(),
                                   [](const Primitive& p) { return !p.normals.empty(); });
  const bool uvs = std::all_of(asset.primitives.begin(), asset.primitives.end(),
                               [](const Primitive& p) { return !p.uvs.empty(); });
  for (uint32_t i = 0; i < pm.vertex_count(); ++i) {
    const auto [prim, v] = origin[pm.vertex_source[i]];
    const Primitive& p = asset.primitives[prim];
    g.positions.insert(g.positions.end(), {p.positions[v].x, p.positions[v].y, p.positions[v].z});
    if (normals)
      g.normals.insert(g.normals.end(), {p.normals[v].x, p.normals[v].y, p.normals[v].z});
    if (uvs) g.uvs.insert(g.uvs.end(), {p.uvs[v].x, p.uvs[v].y});
    g.joints.insert(g.joints.end(), p.joints[v].begin(), p.joints[v].end());
    g.weights.insert(g.weights.end(), p.weights[v].begin(), p.weights[v].end());
    g.regions.push_back(regions.at(prim).at(v));
  }
  g.triangles = pm.triangles;
  // note: primitives without a material share one default material at the end.
  int default_material = -1;
  for (uint16_t prim : pm.triangle_primitive) {
    int m = asset.primitives[prim].material;
    if (m < 0 || m >= static_cast<int>(materials.size())) {
      if (default_material < 0) {
        default_material = static_cast<int>(materials.size());
        materials.push_back(PackMaterial{"default", {1, 1, 1, 1}, ""});
      }
      m = default_material;
    }
    g.triangle_material.push_back(static_cast<uint16_t>(m));
  }
}

// Skins every vertex with the decoded rows of `texture` (what the runtime draws, root motion
// put back) and compares with direct evaluation of the clips at the same times; also the
// radius of the bounding sphere of the in-place frames around the bind-box centre.
void measure_animation(const SkinnedAsset& asset, const PackContents& pack,
                       const AnimationTexture& texture, double diagonal, const glm::dvec3& centre,
                       int threads, BakeReport& report, float& radius) {
  struct FrameError {
    double sum = 0.0, worst = 0.0, far = 0.0;
    size_t count = 0;
  };
  std::vector<std::pair<size_t, uint32_t>> frames;  // (clip, frame)
  for (size_t c = 0; c < pack.clips.size(); ++c)
    for (uint32_t f = 0; f < pack.clips[c].frame_count; ++f) frames.push_back({c, f});
  std::vector<FrameError> errors(frames.size());
  auto to_mat = [](const float rows[12]) {
    glm::dmat4 m(1.0);
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 4; ++k) m[k][r] = rows[4 * r + k];
    return m;
  };
  // note: frames are measured in parallel and reduced in frame order, so the report does not
  // depend on the thread count.
  struct Scratch {
    std::vector<Transform> local;
    std::vector<glm::dmat4> global, skinning, in_place, moved;
    std::vector<glm::dvec3> exact, baked, still;
  };
  std::vector<Scratch> scratch(thread_count(threads, frames.size()));
  parallel_for_workers(frames.size(), threads, [&](size_t i, size_t worker) {
    Scratch& s = scratch[worker];
    const auto [c, f] = frames[i];
    const PackClip& clip = pack.clips[c];
    // note: an asset without clips bakes its rest pose as one clip.
    const Clip* source = c < asset.clips.size() ? &asset.clips[c] : nullptr;
    if (source)
      sample_clip(asset.skeleton, *source, frame_time(*source, clip.frame_count, f), s.local);
    else
      rest_pose(asset.skeleton, s.local);
    local_to_global(asset.skeleton, s.local, s.global);
    skinning_matrices(asset.skeleton, s.global, s.skinning);
    s.in_place.resize(asset.skeleton.joints.size());
    s.moved.resize(s.in_place.size());
    float motion[12], rows[12], with_motion[12];
    const float none[3] = {0.0f, 0.0f, 0.0f};
    const float* root = clip.root_motion.empty() ? none : &clip.root_motion[3 * f];
    root_motion_matrix(root, motion);
    // note: with no root motion at this frame the moved rows are the in-place rows, value for
    // value, so one skinning serves both.
    const bool no_root_motion = root[0] == 0.0f && root[1] == 0.0f && root[2] == 0.0f;
    for (uint32_t j = 0; j < s.in_place.size(); ++j) {
      decode_joint(texture, clip.first_row + f, j, rows);
      compose_affine(motion, rows, with_motion);
      s.in_place[j] = to_mat(rows);
      s.moved[j] = to_mat(with_motion);
    }
    FrameError& e = errors[i];
    // note: in blocks that stay in cache; three whole skinned copies of a hero mesh per
    // frame made this stage bound by memory. The sums still run over the vertices in order.
    constexpr size_t kBlock = 2048;
    for (const Primitive& p : asset.primitives)
      for (size_t begin = 0; begin < p.positions.size(); begin += kBlock) {
        const size_t end = std::min(p.positions.size(), begin + kBlock);
        skin_positions(p, s.skinning, begin, end, s.exact);
        skin_positions(p, s.moved, begin, end, s.baked);
        if (!no_root_motion) skin_positions(p, s.in_place, begin, end, s.still);
        const std::vector<glm::dvec3>& still = no_root_motion ? s.baked : s.still;
        for (size_t v = 0; v < s.exact.size(); ++v) {
          const double d = glm::length(s.exact[v] - s.baked[v]);
          e.sum += d, e.worst = std::max(e.worst, d), ++e.count;
          e.far = std::max(e.far, glm::length(still[v] - centre));
        }
      }
  });
  double sum = 0.0, worst = 0.0, far = 0.0;
  size_t count = 0;
  for (const FrameError& e : errors)
    sum += e.sum, worst = std::max(worst, e.worst), far = std::max(far, e.far), count += e.count;
  report.animation_mean_error = count ? sum / count / diagonal : 0.0;
  report.animation_max_error = worst / diagonal;
  radius = static_cast<float>(far);
}

// note: the runtime needs each level's error to within its LoD ladder's steps, not to the
// last sample: measuring at most this many points per surface and frame keeps the cost of a
// hero character's table near a crowd character's (docs/bake-config.md). Characters under
// about 20,000 triangles are measured at every point.
constexpr uint32_t kLevelErrorPoints = 32768;

// LERR: each sampled level against the full mesh over the clips, in model units; the full
// mesh itself is exact. A coarser level is never reported better than a finer one (the
// running maximum from fine to coarse), so the runtime's table is monotone.
PackLevelErrors measure_level_errors(const SkinnedAsset& asset, const ProgressiveMesh& pm,
                                     const LevelErrorOptions& options, int threads) {
  PackLevelErrors out;
  const uint32_t vertex_count = static_cast<uint32_t>(pm.collapse_to.size());
  out.vertices = level_error_samples(pm.min_vertices, vertex_count, options.samples);
  if (out.vertices.empty()) return out;
  std::vector<SkinnedAsset> lods(out.vertices.size() - 1);
  parallel_for(lods.size(), threads,
               [&](size_t k) { lods[k] = extract_lod(asset, pm, out.vertices[k]); });
  std::vector<const SkinnedAsset*> pointers;
  for (const SkinnedAsset& l : lods) pointers.push_back(&l);
  AnimatedErrorOptions measure;
  measure.fps = options.fps;
  measure.threads = threads;
  measure.max_points = kLevelErrorPoints;
  measure.bind_pose = false;  // note: the table holds the clips' errors only
  const std::vector<AnimatedError> errors = animated_error(asset, pointers, measure);
  out.max_error.assign(out.vertices.size(), 0.0f);
  out.rms_error.assign(out.vertices.size(), 0.0f);
  for (size_t k = 0; k < errors.size(); ++k) {
    const AnimatedError& e = errors[k];
    // note: a level with no triangles is infinitely far from the mesh; the diagonal is as far
    // as anything inside the character gets, and keeps the table finite.
    const auto finite = [&](double v) {
      const double d = e.diagonal * v;
      return static_cast<float>(std::isfinite(d) ? d : e.diagonal);
    };
    out.max_error[k] = finite(e.max);
    out.rms_error[k] = finite(e.mean_rms);
  }
  for (size_t k = errors.size(); k-- > 0;) {
    out.max_error[k] = std::max(out.max_error[k], out.max_error[k + 1]);
    out.rms_error[k] = std::max(out.rms_error[k], out.rms_error[k + 1]);
  }
  return out;
}

}  // namespace

std::vector<uint32_t> level_error_samples(uint32_t min_vertices, uint32_t vertex_count,
                                          uint32_t samples) {
  std::vector<uint32_t> out;
  if (samples < 2 || vertex_count == 0 || min_vertices >= vertex_count) return out;
  const uint32_t lo = std::max(min_vertices, 1u);
  const double ratio = static_cast<double>(vertex_count) / lo;
  for (uint32_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / (samples - 1);
    const uint32_t n = k + 1 == samples
                           ? vertex_count
                           : static_cast<uint32_t>(std::lround(lo * std::pow(ratio, t)));
    if (out.empty() || n > out.back()) out.push_back(n);
  }
  return out;
}

namespace {

PackContents build_or_throw(const SkinnedAsset& asset, const BakeSettings& settings,
                            BakeReport& report, StoredAnimation* stored_out) {
  StageClock clock(report);
  PackContents pack;
  pack.name = std::filesystem::path(asset.source).stem().string();
  pack.settings_json = bake_settings_json(settings);
  report.warnings = asset.warnings;

  // note: the animation and the partition read only the asset; where more than one thread
  // is allowed they are baked beside the simplifier, whose collapse loop is serial. Their
  // results, warnings and stage times are taken in the same order either way.
  const auto bake_side = [&asset, &settings] {
    SideBakes side;
    auto start = std::chrono::steady_clock::now();
    throw_if_failed(bake_animation(asset, settings.animation, side.animation));
    side.animation_seconds = seconds_since(start);
    start = std::chrono::steady_clock::now();
    throw_if_failed(bake_partition(asset, settings.partition, side.partition));
    side.partition_seconds = seconds_since(start);
    return side;
  };
  std::future<SideBakes> beside;
  if (settings.simplify.threads != 1) beside = std::async(std::launch::async, bake_side);

  ProgressiveMesh pm;
  throw_if_failed(simplify(asset, settings.simplify, pm, &report.simplify));
  report.warnings.insert(report.warnings.end(), report.simplify.warnings.begin(),
                         report.simplify.warnings.end());
  pack.progressive = pm;  // note: the PackProgressive part, as stored
  clock.done("simplify");
#if defined(__GLIBC__)
  // note: the simplifier's hundreds of megabytes on a hero character are free now; hand them
  // back to the system before the level errors allocate theirs, so the peak is the larger
  // of the two, not their sum on a loaded machine.
  malloc_trim(0);
#endif
  pack.level_errors =
      measure_level_errors(asset, pm, settings.level_errors, settings.simplify.threads);
  clock.done("level errors");

  SideBakes side = beside.valid() ? beside.get() : bake_side();
  clock.restart();
  pack.animation = std::move(side.animation.texture);
  pack.clips = std::move(side.animation.clips);
  report.warnings.insert(report.warnings.end(), side.animation.warnings.begin(),
                         side.animation.warnings.end());
  report.stages.push_back({"animation", side.animation_seconds});
  PartitionBake& partition = side.partition;
  pack.partition = std::move(partition.mask);
  report.partition_heights = partition.height_source;
  report.warnings.insert(report.warnings.end(), partition.warnings.begin(),
                         partition.warnings.end());
  report.stages.push_back({"partition", side.partition_seconds});

  for (const Material& m : asset.materials) {
    PackMaterial out;
    out.name = m.name;
    out.base_color = {m.base_color.r, m.base_color.g, m.base_color.b, m.base_color.a};
    out.base_color_texture = m.base_color_texture;
    out.base_color_image = m.base_color_image;
    out.uv_transform = m.uv_transform;
    out.alpha_mode = m.alpha_mode;
    out.alpha_cutoff = m.alpha_cutoff;
    out.double_sided = m.double_sided;
    pack.materials.push_back(std::move(out));
  }
  pack.images = asset.images;
  fill_geometry(asset, pm, partition.vertex_regions, pack.materials, pack.geometry);
  pack.vertex_colors = vertex_colors(asset, pm);
  add_variant_images(settings.variant_images, pack);
  if (settings.optimize_images) report.image_bytes_saved = recode_jpeg_images(pack.images);
  for (const Joint& j : asset.skeleton.joints) {
    PackJoint out;
    out.name = j.name;
    out.parent = j.parent;
    out.inverse_bind = rows_of(j.inverse_bind);
    // note: a pre-transform (non-joint nodes folded in) is part of the rest local matrix.
    Transform rest = j.rest;
    const glm::dmat4 local = j.pre_transform * j.rest.matrix();
    if (local != j.rest.matrix()) rest = decompose_transform(local);
    out.rest_translation = {static_cast<float>(rest.translation.x),
                            static_cast<float>(rest.translation.y),
                            static_cast<float>(rest.translation.z)};
    out.rest_rotation = {static_cast<float>(rest.rotation.x), static_cast<float>(rest.rotation.y),
                         static_cast<float>(rest.rotation.z), static_cast<float>(rest.rotation.w)};
    out.rest_scale = {static_cast<float>(rest.scale.x), static_cast<float>(rest.scale.y),
                      static_cast<float>(rest.scale.z)};
    pack.joints.push_back(out);
  }
  clock.done("geometry");

  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const Primitive& p : asset.primitives)
    for (const glm::vec3& v : p.positions)
      lo = glm::min(lo, glm::dvec3(v)), hi = glm::max(hi, glm::dvec3(v));
  for (int k = 0; k < 3; ++k)
    pack.bounds.min[k] = static_cast<float>(lo[k]), pack.bounds.max[k] = static_cast<float>(hi[k]);
  // note: the bake measures what a reader will get.
  const double diagonal = std::max(glm::length(hi - lo), 1e-30);
  if (settings.impostor.views > 0) {
    if (const Status s = bake_impostor(pack, settings.impostor, pack.impostor); !s)
      throw Error(Error::Kind::kUsage, asset.source, s.message());
    clock.done("impostor");
  }
  StoredAnimation stored;
  if (const Status s = stored_animation(pack, settings.pack, stored); !s)
    throw Error(Error::Kind::kUsage, asset.source, s.message());
  report.animation_coding = stored.error_bounded ? "error-bounded" : "lossless";
  report.animation_coding_max_error = stored.max_error / diagonal;
  report.animation_coding_mean_error = stored.mean_error / diagonal;
  // note: the bound applies to quantized textures in compressed packs only (bake-config.md); a
  // bake that asked for another encoding or none gets no warning for the choice it made.
  const bool codable = settings.animation.encoding == AnimationEncoding::kQuantized &&
                       settings.pack.compression == PackCompression::kZstd;
  if (codable && !stored.lossless_reason.empty() && !stored.lossless_smaller)
    report.warnings.push_back("animation: stored losslessly, not within animation.max_error: " +
                              stored.lossless_reason);
  measure_animation(asset, pack, stored.texture, diagonal, 0.5 * (lo + hi),
                    settings.simplify.threads, report, pack.bounds.radius);
  if (stored_out) *stored_out = std::move(stored);
  clock.done("measure");
  return pack;
}

}  // namespace

Status build_pack(const SkinnedAsset& asset, const BakeSettings& settings, BakeReport& report,
                  PackContents& out, StoredAnimation* stored) {
  return capture_errors([&] { out = build_or_throw(asset, settings, report, stored); });
}

}  // namespace crowdbake
