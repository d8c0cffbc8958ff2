#include "simplify/simplify_mesh.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <numeric>

#include "crowdbake/base/parallel.h"
#include "simplify/position_weld.h"

namespace crowdbake {
namespace {

struct VertexRef {
  const Primitive* primitive;
  uint32_t index;
};

std::vector<VertexRef> flatten(const SkinnedAsset& asset) {
  std::vector<VertexRef> refs;
  refs.reserve(asset.vertex_count());
  for (const Primitive& p : asset.primitives)
    for (uint32_t v = 0; v < p.vertex_count(); ++v) refs.push_back({&p, v});
  return refs;
}

}  // namespace

SimplifyMesh build_simplify_mesh(const SkinnedAsset& asset) {
  SimplifyMesh mesh;
  const std::vector<VertexRef> refs = flatten(asset);
  mesh.vertex_count = static_cast<uint32_t>(refs.size());

  glm::dvec3 vertex_lo(std::numeric_limits<double>::max());
  glm::dvec3 vertex_hi(-std::numeric_limits<double>::max());
  for (const VertexRef& r : refs) {
    const glm::dvec3 x(r.primitive->positions[r.index]);
    vertex_lo = glm::min(vertex_lo, x), vertex_hi = glm::max(vertex_hi, x);
  }
  PositionWeld weld(weld_radius(vertex_lo, vertex_hi));  // 0 for no vertices
  mesh.position_of.resize(refs.size());
  for (uint32_t v = 0; v < refs.size(); ++v) {
    const uint32_t p = weld.add(refs[v].primitive->positions[refs[v].index]);
    if (p == mesh.representative.size()) mesh.representative.push_back(v);
    mesh.position_of[v] = p;
  }
  const uint32_t positions = mesh.position_count();
  for (const Joint& j : asset.skeleton.joints) mesh.joint_parent.push_back(j.parent);
  mesh.dominant_joint.resize(positions);
  for (uint32_t p = 0; p < positions; ++p) {
    const VertexRef& r = refs[mesh.representative[p]];
    const std::array<float, 4>& w = r.primitive->weights[r.index];
    const int k = static_cast<int>(std::max_element(w.begin(), w.end()) - w.begin());
    mesh.dominant_joint[p] = r.primitive->joints[r.index][k];
  }
  mesh.wedge_offset.assign(positions + 1, 0);
  for (uint32_t v = 0; v < refs.size(); ++v) ++mesh.wedge_offset[mesh.position_of[v] + 1];
  std::partial_sum(mesh.wedge_offset.begin(), mesh.wedge_offset.end(), mesh.wedge_offset.begin());
  mesh.wedges.resize(refs.size());
  std::vector<uint32_t> fill(mesh.wedge_offset.begin(), mesh.wedge_offset.end() - 1);
  for (uint32_t v = 0; v < refs.size(); ++v) mesh.wedges[fill[mesh.position_of[v]]++] = v;

  // Attribute classes: same position, primitive and UV (bitwise).
  mesh.class_of.resize(refs.size());
  mesh.uv.resize(refs.size());
  mesh.primitive.resize(refs.size());
  for (uint32_t v = 0; v < refs.size(); ++v) {
    const Primitive& p = *refs[v].primitive;
    mesh.primitive[v] = static_cast<uint16_t>(&p - asset.primitives.data());
    mesh.uv[v] = p.uvs.empty() ? glm::vec2(0.0f) : p.uvs[refs[v].index];
  }
  for (uint32_t p = 0; p < positions; ++p)
    for (uint32_t i = mesh.wedge_offset[p]; i < mesh.wedge_offset[p + 1]; ++i) {
      const uint32_t v = mesh.wedges[i];
      mesh.class_of[v] = v;
      for (uint32_t j = mesh.wedge_offset[p]; j < i; ++j) {
        const uint32_t w = mesh.wedges[j];
        if (mesh.primitive[w] == mesh.primitive[v] &&
            std::memcmp(&mesh.uv[v], &mesh.uv[w], sizeof(glm::vec2)) == 0) {
          mesh.class_of[v] = mesh.class_of[w];
          break;
        }
      }
    }

  uint32_t base = 0;
  for (size_t prim = 0; prim < asset.primitives.size(); ++prim) {
    const Primitive& p = asset.primitives[prim];
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
      const uint32_t a = base + p.indices[t], b = base + p.indices[t + 1],
                     c = base + p.indices[t + 2];
      const uint32_t pa = mesh.position_of[a], pb = mesh.position_of[b], pc = mesh.position_of[c];
      if (pa == pb || pb == pc || pa == pc) {
        ++mesh.degenerate_triangles;
        continue;
      }
      mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
      mesh.triangle_primitive.push_back(static_cast<uint16_t>(prim));
    }
    base += static_cast<uint32_t>(p.vertex_count());
  }

  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (uint32_t p = 0; p < positions; ++p) {
    const VertexRef& r = refs[mesh.representative[p]];
    const glm::dvec3 x(r.primitive->positions[r.index]);
    lo = glm::min(lo, x), hi = glm::max(hi, x);
  }
  if (positions > 0) {
    mesh.centre = 0.5 * (lo + hi);
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    mesh.inverse_scale = extent > 0.0 ? 1.0 / extent : 1.0;
  }
  mesh.normalise = glm::dmat4(mesh.inverse_scale);
  mesh.normalise[3] = glm::dvec4(-mesh.centre * mesh.inverse_scale, 1.0);
  mesh.denormalise = glm::inverse(mesh.normalise);
  return mesh;
}

namespace {

struct Skin {
  std::array<uint16_t, 4> joints;
  std::array<float, 4> weights;
  glm::dvec3 bind;
};

Skin skin_of(const SkinnedAsset& asset, uint32_t vertex) {
  for (const Primitive& p : asset.primitives) {
    if (vertex < p.vertex_count())
      return {p.joints[vertex], p.weights[vertex], glm::dvec3(p.positions[vertex])};
    vertex -= static_cast<uint32_t>(p.vertex_count());
  }
  return {};
}

// note: float weights sum to 1 only within rounding; dividing by the sum in double keeps
// the bind pose an exact identity (so one bind pose is exactly classic QEM).
glm::dmat4 blend(const Skin& s, const std::vector<glm::dmat4>& pose) {
  glm::dmat4 m(0.0);
  double sum = 0.0;
  for (int k = 0; k < 4; ++k)
    if (s.weights[k] != 0.0f) {
      m += static_cast<double>(s.weights[k]) * pose[s.joints[k]];
      sum += s.weights[k];
    }
  return sum > 0.0 ? m * (1.0 / sum) : glm::dmat4(1.0);
}

}  // namespace

glm::dmat4 position_transform(const SkinnedAsset& asset, const SimplifyMesh& mesh,
                              uint32_t position, const std::vector<glm::dmat4>& pose) {
  const Skin s = skin_of(asset, mesh.representative[position]);
  // normalised posed = N · A · N⁻¹ · normalised bind, N(x) = (x - centre) * inverse_scale.
  return mesh.normalise * blend(s, pose) * mesh.denormalise;
}

std::vector<glm::dvec3> posed_positions(const SkinnedAsset& asset, const SimplifyMesh& mesh,
                                        const std::vector<std::vector<glm::dmat4>>& poses,
                                        int threads) {
  const uint32_t positions = mesh.position_count();
  std::vector<glm::dvec3> out(poses.size() * positions);
  // note: every position is skinned on its own, so blocks of them run in parallel and the
  // result does not depend on the thread count.
  constexpr uint32_t kBlock = 4096;
  parallel_for((positions + kBlock - 1) / kBlock, threads, [&](size_t block) {
    const uint32_t end = std::min(positions, static_cast<uint32_t>((block + 1) * kBlock));
    for (uint32_t p = static_cast<uint32_t>(block * kBlock); p < end; ++p) {
      const Skin skin = skin_of(asset, mesh.representative[p]);
      for (size_t s = 0; s < poses.size(); ++s) {
        const glm::dvec3 x = glm::dvec3(blend(skin, poses[s]) * glm::dvec4(skin.bind, 1.0));
        out[p * poses.size() + s] = (x - mesh.centre) * mesh.inverse_scale;
      }
    }
  });
  return out;
}

}  // namespace crowdbake
