#include "commands/peers.h"

#include <meshoptimizer.h>
#include <unistd.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "commands/child.h"
#include "commands/levels.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"

namespace crowdbake::bench {
namespace {

constexpr int kMaxTrials = 24;
constexpr int kMaxGltfpackTrials = 5;

// Primitive with only the vertices its new index list references, in first-use order.
Primitive compact(const Primitive& src, const std::vector<uint32_t>& indices) {
  Primitive dst;
  dst.name = src.name;
  dst.material = src.material;
  std::vector<uint32_t> remap(src.vertex_count(), UINT32_MAX);
  for (uint32_t i : indices) {
    if (remap[i] == UINT32_MAX) {
      remap[i] = static_cast<uint32_t>(dst.positions.size());
      dst.positions.push_back(src.positions[i]);
      if (!src.normals.empty()) dst.normals.push_back(src.normals[i]);
      if (!src.uvs.empty()) dst.uvs.push_back(src.uvs[i]);
      dst.joints.push_back(src.joints[i]);
      dst.weights.push_back(src.weights[i]);
    }
    dst.indices.push_back(remap[i]);
  }
  return dst;
}

// Maps the imported LoD's joints onto the original skeleton by name and brings its
// vertices into the original's bind space.
// note: the original is skinned with v' = G_j · B_j · v, gltfpack's output with its own
// inverse binds B'_j; the same skinned result needs v = B_j⁻¹ · B'_j · v_out. gltfpack may
// fold a root transform into the mesh (CesiumMan's Z-up rotation), which makes
// B_j⁻¹ · B'_j one matrix for every joint; anything else is reported, not guessed.
void adopt_skeleton(SkinnedAsset& lod, const SkinnedAsset& original) {
  std::vector<int> to_original(lod.skeleton.joints.size(), -1);
  bool have_space = false;
  glm::dmat4 space(1.0);
  for (size_t j = 0; j < lod.skeleton.joints.size(); ++j) {
    const Joint& joint = lod.skeleton.joints[j];
    const int o = original.skeleton.find(joint.name);
    to_original[j] = o;
    if (o < 0) continue;
    const glm::dmat4 m =
        glm::inverse(original.skeleton.joints[o].inverse_bind) * joint.inverse_bind;
    if (!have_space) {
      space = m, have_space = true;
      continue;
    }
    double diff = 0.0, size = 1e-12;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        diff = std::max(diff, std::abs(m[c][r] - space[c][r])),
        size = std::max(size, std::abs(space[c][r]));
    if (diff > 1e-4 * size)
      throw std::runtime_error("gltfpack changed the bind pose of joint '" + joint.name +
                               "' differently from the others");
  }
  const glm::dmat3 normal_space = glm::transpose(glm::inverse(glm::dmat3(space)));
  for (Primitive& p : lod.primitives) {
    for (glm::vec3& v : p.positions) v = glm::vec3(space * glm::dvec4(glm::dvec3(v), 1.0));
    for (glm::vec3& n : p.normals) n = glm::vec3(glm::normalize(normal_space * glm::dvec3(n)));
    for (size_t v = 0; v < p.vertex_count(); ++v)
      for (int k = 0; k < 4; ++k) {
        const int o = to_original[p.joints[v][k]];
        if (o < 0) {
          if (p.weights[v][k] != 0.0f)
            throw std::runtime_error("gltfpack output uses joint '" +
                                     lod.skeleton.joints[p.joints[v][k]].name +
                                     "' the original does not have");
          p.joints[v][k] = 0;
        } else {
          p.joints[v][k] = static_cast<uint16_t>(o);
        }
      }
  }
  lod.skeleton = original.skeleton;
  lod.clips.clear();
}

uint32_t distance(uint32_t a, uint32_t b) { return a > b ? a - b : b - a; }

}  // namespace

// meshopt_simplify on every primitive at ratio × its index count, on a position-welded
// copy of the primitive.
// note: a shadow index buffer alone is not enough in 0.18: the duplicates it leaves
// unreferenced still share the welded vertices' positions, so meshopt classifies those
// vertices as seams and, on corner-split meshes like Fox, collapses nothing. A careful user
// welds the vertex buffer itself (meshopt_generateVertexRemap over positions only) and maps
// the result back to the first original vertex at each position for its attributes.
WeldedPrimitive weld_positions(const Primitive& p) {
  const size_t n = p.indices.size();
  WeldedPrimitive w;
  w.remap.resize(p.vertex_count());
  w.indices.resize(n);
  const size_t count = meshopt_generateVertexRemap(
      w.remap.data(), p.indices.data(), n, p.positions.data(), p.vertex_count(), sizeof(glm::vec3));
  meshopt_remapIndexBuffer(w.indices.data(), p.indices.data(), n, w.remap.data());
  w.positions.resize(count);
  meshopt_remapVertexBuffer(w.positions.data(), p.positions.data(), p.vertex_count(),
                            sizeof(glm::vec3), w.remap.data());
  return w;
}

SkinnedAsset meshopt_simplify_all(const SkinnedAsset& asset, double ratio) {
  SkinnedAsset lod = asset;
  lod.clips.clear();
  lod.primitives.clear();
  for (const Primitive& p : asset.primitives) {
    const size_t n = p.indices.size();
    const WeldedPrimitive w = weld_positions(p);
    std::vector<unsigned int> first(w.positions.size(), UINT32_MAX), out(n);
    for (unsigned int v = 0; v < p.vertex_count(); ++v)
      if (w.remap[v] != ~0u && first[w.remap[v]] == UINT32_MAX) first[w.remap[v]] = v;
    const size_t target = static_cast<size_t>(std::lround(ratio * double(n / 3))) * 3;
    float error = 0.0f;
    // note: no error bound: the target count alone decides where it stops.
    out.resize(meshopt_simplify(out.data(), w.indices.data(), n, &w.positions[0].x,
                                w.positions.size(), sizeof(glm::vec3), target, FLT_MAX, 0, &error));
    for (unsigned int& i : out) i = first[i];
    if (!out.empty()) lod.primitives.push_back(compact(p, out));
  }
  return lod;
}

PeerLod meshopt_lod(const SkinnedAsset& asset, uint32_t target) {
  PeerLod r;
  // note: kept positions grow with the ratio; bisect the ratio, keep the closest trial.
  double lo = 0.0, hi = 1.0, best = 1.0;
  uint32_t best_gap = UINT32_MAX;
  for (int trial = 0; trial < kMaxTrials && best_gap > 0; ++trial) {
    const double ratio = trial == 0 ? 1.0 : 0.5 * (lo + hi);
    const uint32_t kept = count_lod(meshopt_simplify_all(asset, ratio)).positions;
    if (distance(kept, target) < best_gap) best_gap = distance(kept, target), best = ratio;
    if (trial > 0) (kept > target ? hi : lo) = ratio;
    ++r.trials;
    if (trial == 0 && kept <= target) break;  // even no simplification keeps too few
  }
  r.parameter = best;
  const ChildResult timed = run_in_child([&] {
    SkinnedAsset lod = meshopt_simplify_all(asset, best);
    return std::string(1, lod.primitives.empty() ? 0 : 1);
  });
  r.lod = meshopt_simplify_all(asset, best);
  r.seconds = timed.seconds;
  r.peak_rss_mb = timed.peak_rss_mb;
  r.ok = !r.lod.primitives.empty();
  if (!r.ok) r.error = "meshopt_simplify removed every triangle";
  return r;
}

PeerLod gltfpack_lod(const SkinnedAsset& asset, const std::string& gltfpack,
                     const std::string& input_glb, const std::string& work_dir, uint32_t target) {
  PeerLod r;
  const uint32_t total = count_lod(asset).positions;
  double ratio = std::clamp(double(target) / std::max<uint32_t>(total, 1), 1e-4, 1.0);
  uint32_t best_gap = UINT32_MAX;
  double lo = 0.0, hi = 1.0;
  for (int trial = 0; trial < kMaxGltfpackTrials; ++trial) {
    char r_text[32];
    std::snprintf(r_text, sizeof r_text, "%.6g", ratio);
    const std::string out = work_dir + "/gltfpack-out.glb";
    const ChildResult run = run_program(
        {gltfpack, "-i", input_glb, "-o", out, "-si", r_text, "-sp", "-se", "0.5", "-noq"},
        work_dir + "/gltfpack.log");
    ++r.trials;
    if (!run.ok) {
      r.error = run.error;
      break;
    }
    ImportOptions gltf;
    gltf.importer = ImporterKind::kGltf;
    SkinnedAsset lod;
    try {
      throw_if_failed(import_asset(out, gltf, lod));
      adopt_skeleton(lod, asset);
    } catch (const std::exception& e) {
      r.error = std::string("gltfpack output unusable: ") + e.what();
      break;
    }
    const uint32_t kept = count_lod(lod).positions;
    if (distance(kept, target) < best_gap) {
      best_gap = distance(kept, target);
      r.lod = std::move(lod);
      r.seconds = run.seconds;
      r.peak_rss_mb = run.peak_rss_mb;
      r.parameter = std::atof(r_text);
      r.ok = true;
      r.error.clear();
    }
    if (best_gap == 0) break;
    // note: positions follow R roughly linearly; step by the ratio of counts, bracketed.
    (kept > target ? hi : lo) = ratio;
    double next = ratio * double(target) / std::max<uint32_t>(kept, 1);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - ratio) < 1e-6) break;
    ratio = next;
  }
  return r;
}

std::string find_gltfpack() {
  if (const char* env = std::getenv("CROWDBAKE_GLTFPACK"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path local =
        self.parent_path().parent_path() / "npm-gltfpack/node_modules/.bin/gltfpack";
    if (access(local.c_str(), X_OK) == 0) return local.string();
  }
  if (const char* path = std::getenv("PATH")) {
    std::string dirs = path;
    size_t start = 0;
    while (start <= dirs.size()) {
      const size_t end = std::min(dirs.find(':', start), dirs.size());
      const std::string candidate = dirs.substr(start, end - start) + "/gltfpack";
      if (end > start && access(candidate.c_str(), X_OK) == 0) return candidate;
      start = end + 1;
    }
  }
  return {};
}

}  // namespace crowdbake::bench
