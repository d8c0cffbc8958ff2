// diff_packs' geometry and progressive-array sections (pack_diff.h states the rules).
#include <algorithm>
#include <array>
#include <numeric>
#include <tuple>

#include "pack_diff_support.h"

namespace crowdbake::diff {
namespace {

using Triangle = std::array<uint32_t, 3>;

// Rotated so the smallest index comes first (the winding is kept).
Triangle canonical(Triangle t) {
  const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  std::rotate(t.begin(), t.begin() + k, t.end());
  return t;
}

// The triangles as a sorted list of canonical triangles, vertex indices first mapped by
// `remap` (identity when empty).
std::vector<Triangle> triangle_set(const std::vector<uint32_t>& indices,
                                   const std::vector<uint32_t>& remap) {
  std::vector<Triangle> out(indices.size() / 3);
  for (size_t t = 0; t < out.size(); ++t) {
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = indices[3 * t + k];
      tri[k] = remap.empty() ? v : remap[v];
    }
    out[t] = canonical(tri);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Vertex indices sorted by position, then UV, then index.
std::vector<uint32_t> sorted_vertices(const PackGeometry& g) {
  std::vector<uint32_t> order(g.vertex_count());
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&g](uint32_t v) {
    const float* p = &g.positions[3 * size_t{v}];
    const float u = g.uvs.empty() ? 0.0f : g.uvs[2 * size_t{v}];
    const float w = g.uvs.empty() ? 0.0f : g.uvs[2 * size_t{v} + 1];
    return std::make_tuple(p[0], p[1], p[2], u, w, v);
  };
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) { return key(x) < key(y); });
  return order;
}

double distance(const float* p, const float* q) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = double{p[k]} - double{q[k]};
    sum += d * d;
  }
  return std::sqrt(sum);
}

// Max |a[v] - b[pair[v]]| per component over vertices v, `per` floats per vertex.
MaxDiff attribute_diff(const std::vector<float>& a, const std::vector<float>& b, size_t per,
                       const std::vector<uint32_t>& pair) {
  MaxDiff m;
  for (size_t v = 0; v < pair.size(); ++v)
    for (size_t k = 0; k < per; ++k)
      m.add(std::abs(double{a[per * v + k]} - double{b[per * size_t{pair[v]} + k]}),
            static_cast<int64_t>(v));
  return m;
}

// The pairing of A's vertices with B's (equal vertex counts): the identity when the vertices
// are in the same order, else the pairing by sorted position when that fits better.
struct VertexPairing {
  std::vector<uint32_t> pair;    // A vertex -> B vertex
  std::vector<uint32_t> b_to_a;  // its inverse, for B's triangles; empty for the identity
  double position_diff = 0.0;
  std::string vertex_order = "not compared", positions = "not compared";
};

VertexPairing pair_vertices(const PackGeometry& a, const PackGeometry& b, const Compare& cmp,
                            DiffSection& s) {
  const uint32_t n = a.vertex_count();
  VertexPairing p;
  p.pair.resize(n);
  std::iota(p.pair.begin(), p.pair.end(), 0u);
  MaxDiff same_order;
  for (uint32_t v = 0; v < n; ++v)
    same_order.add(distance(&a.positions[3 * size_t{v}], &b.positions[3 * size_t{v}]), v);
  MaxDiff position = same_order;
  p.vertex_order = "same";
  if (cmp.length_beyond(same_order.value)) {
    const std::vector<uint32_t> oa = sorted_vertices(a), ob = sorted_vertices(b);
    MaxDiff sorted;
    for (uint32_t k = 0; k < n; ++k)
      sorted.add(distance(&a.positions[3 * size_t{oa[k]}], &b.positions[3 * size_t{ob[k]}]), oa[k]);
    if (sorted.value < same_order.value) {
      p.vertex_order = "differs";
      position = sorted;
      p.b_to_a.resize(n);
      for (uint32_t k = 0; k < n; ++k) p.pair[oa[k]] = ob[k], p.b_to_a[ob[k]] = oa[k];
      uint32_t first = 0;
      while (first < n && p.pair[first] == first) ++first;
      differ(s, "vertex order differs from vertex " + std::to_string(first) +
                    " (vertices paired by position: max distance " +
                    num(sorted.value / cmp.diagonal) + " of the diagonal)");
    }
  }
  p.position_diff = position.value;
  p.positions = cmp.length_beyond(position.value) ? "differ" : "equal";
  s.figures["max_position_diff"] = position.value;
  s.figures["max_position_diff_relative"] = position.value / cmp.diagonal;
  if (p.positions == "differ")
    differ(s, "positions differ: max " + num(position.value / cmp.diagonal) +
                  " of the diagonal at vertex " + std::to_string(position.at));
  return p;
}

// Normals, UVs, weights, joints and regions of paired vertices.
void compare_attributes(const PackGeometry& a, const PackGeometry& b,
                        const std::vector<uint32_t>& pair, const Compare& cmp, DiffSection& s) {
  const uint32_t va = a.vertex_count(), vb = b.vertex_count();
  const struct {
    const char* name;
    const std::vector<float>& a;
    const std::vector<float>& b;
    size_t per;
  } attributes[] = {{"normals", a.normals, b.normals, 3},
                    {"uvs", a.uvs, b.uvs, 2},
                    {"weights", a.weights, b.weights, 4}};
  for (const auto& attr : attributes) {
    if (attr.a.size() != attr.b.size() || attr.a.size() != attr.per * va) continue;
    const MaxDiff m = attribute_diff(attr.a, attr.b, attr.per, pair);
    s.figures[std::string("max_") + attr.name + "_diff"] = m.value;
    if (cmp.beyond(m.value))
      differ(s, std::string(attr.name) + " differ: max " + num(m.value) + " at vertex " +
                    std::to_string(m.at));
  }
  // note: the joint of a zero weight is meaningless, so only influences in use compare.
  size_t joints_differ = 0, regions_differ = 0;
  if (a.joints.size() == 4 * size_t{va} && b.joints.size() == 4 * size_t{vb})
    for (uint32_t v = 0; v < va; ++v)
      for (size_t k = 0; k < 4; ++k) {
        const size_t i = 4 * size_t{v} + k, j = 4 * size_t{pair[v]} + k;
        if ((a.weights[i] > 0.0f || b.weights[j] > 0.0f) && a.joints[i] != b.joints[j])
          ++joints_differ;
      }
  if (a.regions.size() == va && b.regions.size() == vb)
    for (uint32_t v = 0; v < va; ++v) regions_differ += a.regions[v] != b.regions[pair[v]];
  if (joints_differ) differ(s, std::to_string(joints_differ) + " joint influences differ");
  if (regions_differ) differ(s, std::to_string(regions_differ) + " vertex regions differ");
  s.figures["joint_influences_differ"] = joints_differ;
  s.figures["regions_differ"] = regions_differ;
}

// Triangle order (equal triangle counts): B's indices go through the pairing when the vertex
// order differs, whatever the positions did.
std::string compare_triangles(const PackGeometry& a, const PackGeometry& b,
                              const std::vector<uint32_t>& b_to_a, DiffSection& s) {
  const auto corner = [&](size_t i) {
    return b_to_a.empty() ? b.triangles[i] : b_to_a[b.triangles[i]];
  };
  int64_t first = -1;
  for (uint32_t t = 0; t < a.triangle_count() && first < 0; ++t)
    for (size_t k = 0; k < 3; ++k)
      if (a.triangles[3 * size_t{t} + k] != corner(3 * size_t{t} + k)) first = t;
  s.figures["first_differing_triangle"] = first;
  if (first < 0) {
    size_t materials_differ = 0;
    for (size_t t = 0; t < a.triangle_material.size() && t < b.triangle_material.size(); ++t)
      materials_differ += a.triangle_material[t] != b.triangle_material[t];
    if (materials_differ)
      differ(s, std::to_string(materials_differ) + " triangle materials differ");
    return "same";
  }
  if (triangle_set(a.triangles, {}) == triangle_set(b.triangles, b_to_a)) {
    differ(s, "triangle order differs from triangle " + std::to_string(first) +
                  " (the same triangles)");
    return "differs";
  }
  differ(s, "triangles differ from triangle " + std::to_string(first));
  return "triangles differ";
}

}  // namespace

// Geometry compares vertex by vertex through a pairing of A's vertices with B's (the same
// vertices stored in another order, e.g. after a different simplification, still pair up).
// Triangles compare through the same pairing.
DiffSection diff_geometry(const PackContents& pa, const PackContents& pb, const Compare& cmp) {
  DiffSection s = section("geometry");
  const PackGeometry& a = pa.geometry;
  const PackGeometry& b = pb.geometry;
  const uint32_t va = a.vertex_count(), vb = b.vertex_count();
  const uint32_t ta = a.triangle_count(), tb = b.triangle_count();
  if (va != vb) differ(s, "vertex count " + arrow(va, vb));
  if (ta != tb) differ(s, "triangle count " + arrow(ta, tb));
  const struct {
    const char* name;
    bool a, b;
  } optional[] = {{"normals", !a.normals.empty(), !b.normals.empty()},
                  {"uvs", !a.uvs.empty(), !b.uvs.empty()},
                  {"regions", !a.regions.empty(), !b.regions.empty()}};
  for (const auto& o : optional)
    if (o.a != o.b) differ(s, std::string(o.name) + (o.a ? " only in A" : " only in B"));
  s.figures["vertices"] = {va, vb};
  s.figures["triangles"] = {ta, tb};
  VertexPairing p;
  if (va == vb) {
    p = pair_vertices(a, b, cmp, s);
    compare_attributes(a, b, p.pair, cmp, s);
  }
  const std::string triangle_order =
      ta == tb ? compare_triangles(a, b, p.b_to_a, s) : "not compared";
  s.figures["positions"] = p.positions;
  s.figures["vertex_order"] = p.vertex_order;
  s.figures["triangle_order"] = triangle_order;
  s.summary =
      std::to_string(va) + " vertices, " + std::to_string(ta) + " triangles; max position diff " +
      (va == vb ? num(p.position_diff / cmp.diagonal) : std::string("-")) +
      " of the diagonal; vertex order " + p.vertex_order + ", triangle order " + triangle_order;
  return s;
}

// ---- progressive arrays ---------------------------------------------------------------

DiffSection diff_progressive(const PackContents& a, const PackContents& b) {
  DiffSection s = section("progressive");
  const PackProgressive& pa = a.progressive;
  const PackProgressive& pb = b.progressive;
  if (pa.min_vertices != pb.min_vertices)
    differ(s, "min_vertices " + arrow(pa.min_vertices, pb.min_vertices));
  const struct {
    const char* name;
    const std::vector<uint32_t>& a;
    const std::vector<uint32_t>& b;
  } arrays[] = {{"collapse_to", pa.collapse_to, pb.collapse_to},
                {"triangle_count", pa.triangle_count, pb.triangle_count},
                {"group_start", pa.group_start, pb.group_start}};
  for (const auto& arr : arrays) {
    const int64_t at = first_difference(arr.a, arr.b);
    if (at >= 0)
      differ(s, std::string(arr.name) + " differs first at index " + std::to_string(at) + ": " +
                    arrow(arr.a[at], arr.b[at]));
    if (arr.a.size() != arr.b.size())
      differ(s, std::string(arr.name) + " length " + arrow(arr.a.size(), arr.b.size()));
    s.figures[std::string("first_difference_") + arr.name] =
        at >= 0 || arr.a.size() == arr.b.size()
            ? at
            : static_cast<int64_t>(std::min(arr.a.size(), arr.b.size()));
  }
  s.figures["min_vertices"] = {pa.min_vertices, pb.min_vertices};
  s.summary = "min_vertices " + std::to_string(pa.min_vertices) + ", " +
              std::to_string(pa.collapse_to.size()) + " collapse entries";
  return s;
}

}  // namespace crowdbake::diff
