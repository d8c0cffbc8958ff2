// diff_packs: one static function per section, each filling a DiffSection from the two
// decoded packs. Tolerance rules are in pack_diff.h.
#include "cli/pack_diff.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <tuple>
#include <type_traits>

#include "crowdbake/formats/animation_codec.h"
#include "crowdbake/formats/pack_format.h"

namespace crowdbake::cli {
namespace {

using nlohmann::ordered_json;

// How values compare: lengths relative to D, everything else absolute.
struct Compare {
  double tolerance = 0.0;
  double diagonal = 1.0;
  bool length_beyond(double d) const { return d / diagonal > tolerance; }
  bool beyond(double d) const { return d > tolerance; }
};

// The largest difference seen and where.
struct MaxDiff {
  double value = 0.0;
  int64_t at = -1;
  void add(double d, int64_t where) {
    if (d > value) value = d, at = where;
  }
};

std::string num(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", v);
  return s;
}

std::string quoted(const std::string& s) { return "\"" + s + "\""; }

template <typename T>
std::string arrow(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, std::string>)
    return quoted(a) + " -> " + quoted(b);
  else
    return std::to_string(a) + " -> " + std::to_string(b);
}

// note: enough digits that two different floats never print alike.
std::string arrow_num(double a, double b) {
  char s[64];
  std::snprintf(s, sizeof s, "%.9g -> %.9g", a, b);
  return s;
}

DiffSection section(const char* name) {
  DiffSection s;
  s.name = name;
  return s;
}

void differ(DiffSection& s, std::string line) {
  s.differs = true;
  s.differences.push_back(std::move(line));
}

// First index where two arrays differ over their common length; -1 when that prefix is
// equal (check the lengths separately).
template <typename T>
int64_t first_difference(const std::vector<T>& a, const std::vector<T>& b) {
  const size_t n = std::min(a.size(), b.size());
  for (size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return static_cast<int64_t>(i);
  return -1;
}

// Max |a - b| of the 3x3 part (entries 0-2, 4-6, 8-10) and of the translation (3, 7, 11).
void matrix_diff(const float* a, const float* b, double& linear, double& translation) {
  linear = translation = 0.0;
  for (int k = 0; k < 12; ++k) {
    const double d = std::abs(double{a[k]} - double{b[k]});
    double& slot = k % 4 == 3 ? translation : linear;
    slot = std::max(slot, d);
  }
}

// ---- header ---------------------------------------------------------------------------

DiffSection diff_header(const PackFile& a, const PackFile& b) {
  DiffSection s = section("header");
  const std::string va = std::to_string(a.version_major) + "." + std::to_string(a.version_minor);
  const std::string vb = std::to_string(b.version_major) + "." + std::to_string(b.version_minor);
  if (va != vb) differ(s, "pack version " + va + " -> " + vb);
  if (a.contents.name != b.contents.name)
    differ(s, "name " + arrow(a.contents.name, b.contents.name));
  auto find = [](const PackFile& p, uint32_t tag) -> const PackChunk* {
    for (const PackChunk& c : p.chunks)
      if (c.tag == tag) return &c;
    return nullptr;
  };
  for (const PackChunk& c : a.chunks) {
    const PackChunk* other = find(b, c.tag);
    const std::string tag = pack_format::tag_name(c.tag);
    if (!other)
      differ(s, "chunk " + tag + " only in A");
    else if (other->version != c.version)
      differ(s, "chunk " + tag + " version " + arrow(c.version, other->version));
  }
  for (const PackChunk& c : b.chunks)
    if (!find(a, c.tag)) differ(s, "chunk " + pack_format::tag_name(c.tag) + " only in B");
  s.summary = "pack " + va + ", " + quoted(a.contents.name) + ", " +
              std::to_string(a.chunks.size()) + " chunks";
  s.figures = {{"version", {va, vb}}, {"name", {a.contents.name, b.contents.name}}};
  return s;
}

// ---- settings -------------------------------------------------------------------------

void flatten(const ordered_json& j, const std::string& prefix,
             std::map<std::string, std::string>& out) {
  if (j.is_object() && !j.empty()) {
    for (const auto& [key, value] : j.items())
      flatten(value, prefix.empty() ? key : prefix + "." + key, out);
  } else {
    out[prefix] = j.dump();
  }
}

DiffSection diff_settings(const PackContents& a, const PackContents& b) {
  DiffSection s = section("settings");
  const ordered_json ja = ordered_json::parse(a.settings_json, nullptr, false);
  const ordered_json jb = ordered_json::parse(b.settings_json, nullptr, false);
  std::map<std::string, std::string> fa, fb;
  // note: settings that are not JSON (a foreign writer) compare as text.
  flatten(ja.is_discarded() ? ordered_json(a.settings_json) : ja, "", fa);
  flatten(jb.is_discarded() ? ordered_json(b.settings_json) : jb, "", fb);
  ordered_json changed = ordered_json::object();
  for (const auto& [key, value] : fa) {
    const auto it = fb.find(key);
    const std::string other = it == fb.end() ? "(absent)" : it->second;
    if (other != value) {
      differ(s, (key.empty() ? "settings" : key) + ": " + value + " -> " + other);
      changed[key] = {value, other};
    }
  }
  for (const auto& [key, value] : fb)
    if (!fa.count(key)) {
      differ(s, (key.empty() ? "settings" : key) + ": (absent) -> " + value);
      changed[key] = {"(absent)", value};
    }
  s.summary = std::to_string(fa.size()) + " keys";
  s.figures = {{"changed", changed}};
  return s;
}

// ---- skeleton -------------------------------------------------------------------------

double quaternion_diff(const std::array<float, 4>& a, const std::array<float, 4>& b) {
  double plus = 0.0, minus = 0.0;  // note: q and -q are the same rotation
  for (int k = 0; k < 4; ++k) {
    plus = std::max(plus, std::abs(double{a[k]} - double{b[k]}));
    minus = std::max(minus, std::abs(double{a[k]} + double{b[k]}));
  }
  return std::min(plus, minus);
}

DiffSection diff_skeleton(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("skeleton");
  const size_t na = a.joints.size(), nb = b.joints.size();
  if (na != nb) differ(s, "joint count " + arrow(na, nb));
  const size_t n = std::min(na, nb);
  int64_t name_at = -1, parent_at = -1;
  size_t names_differ = 0;
  MaxDiff linear, translation, rest_translation, rest_unitless;
  for (size_t i = 0; i < n; ++i) {
    const PackJoint& ja = a.joints[i];
    const PackJoint& jb = b.joints[i];
    if (ja.name != jb.name && names_differ++ == 0) name_at = static_cast<int64_t>(i);
    if (ja.parent != jb.parent && parent_at < 0) parent_at = static_cast<int64_t>(i);
    double l = 0.0, t = 0.0;
    matrix_diff(ja.inverse_bind.data(), jb.inverse_bind.data(), l, t);
    linear.add(l, i), translation.add(t, i);
    for (int k = 0; k < 3; ++k) {
      rest_translation.add(std::abs(double{ja.rest_translation[k]} - jb.rest_translation[k]), i);
      rest_unitless.add(std::abs(double{ja.rest_scale[k]} - jb.rest_scale[k]), i);
    }
    rest_unitless.add(quaternion_diff(ja.rest_rotation, jb.rest_rotation), i);
  }
  auto joint = [&](int64_t i) {
    return "joint " + std::to_string(i) + " " + quoted(a.joints[i].name);
  };
  if (name_at >= 0)
    differ(s, std::to_string(names_differ) + " joint names differ, first joint " +
                  std::to_string(name_at) + " " +
                  arrow(a.joints[name_at].name, b.joints[name_at].name));
  if (parent_at >= 0)
    differ(s, joint(parent_at) + " parent " +
                  arrow(a.joints[parent_at].parent, b.joints[parent_at].parent));
  if (cmp.beyond(linear.value) || cmp.length_beyond(translation.value)) {
    const int64_t at = cmp.beyond(linear.value) ? linear.at : translation.at;
    differ(s, "inverse binds differ: max " + num(linear.value) + " (3x3), " +
                  num(translation.value / cmp.diagonal) + " of the diagonal (translation), at " +
                  joint(at));
  }
  if (cmp.length_beyond(rest_translation.value) || cmp.beyond(rest_unitless.value)) {
    const int64_t at = cmp.beyond(rest_unitless.value) ? rest_unitless.at : rest_translation.at;
    differ(s, "rest pose differs: max " + num(rest_translation.value / cmp.diagonal) +
                  " of the diagonal (translation), " + num(rest_unitless.value) +
                  " (rotation, scale), at " + joint(at));
  }
  s.summary = std::to_string(na) + " joints; inverse binds max diff " + num(linear.value) +
              " (3x3), " + num(translation.value / cmp.diagonal) + " (translation / diagonal)";
  s.figures = {{"joints", {na, nb}},
               {"first_name_difference", name_at},
               {"first_parent_difference", parent_at},
               {"inverse_bind_max_diff", linear.value},
               {"inverse_bind_translation_max_diff", translation.value},
               {"rest_translation_max_diff", rest_translation.value},
               {"rest_rotation_scale_max_diff", rest_unitless.value}};
  return s;
}

// ---- clips ----------------------------------------------------------------------------

// Clips of B matched to A's by name: index into b.clips, or -1.
std::vector<int64_t> match_clips(const PackContents& a, const PackContents& b) {
  std::vector<int64_t> match(a.clips.size(), -1);
  std::vector<bool> used(b.clips.size(), false);
  for (size_t i = 0; i < a.clips.size(); ++i)
    for (size_t k = 0; k < b.clips.size(); ++k)
      if (!used[k] && b.clips[k].name == a.clips[i].name) {
        match[i] = static_cast<int64_t>(k), used[k] = true;
        break;
      }
  return match;
}

DiffSection diff_clips(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("clips");
  if (a.clips.size() != b.clips.size())
    differ(s, "clip count " + arrow(a.clips.size(), b.clips.size()));
  const std::vector<int64_t> match = match_clips(a, b);
  std::vector<bool> matched(b.clips.size(), false);
  bool reordered = false;
  MaxDiff motion_length, motion_yaw;
  ordered_json list = ordered_json::array();
  for (size_t i = 0; i < a.clips.size(); ++i) {
    const PackClip& ca = a.clips[i];
    const std::string name = "clip " + quoted(ca.name);
    if (match[i] < 0) {
      differ(s, name + " only in A");
      continue;
    }
    matched[match[i]] = true;
    reordered |= match[i] != static_cast<int64_t>(i);
    const PackClip& cb = b.clips[match[i]];
    if (ca.frame_count != cb.frame_count)
      differ(s, name + ": frames " + arrow(ca.frame_count, cb.frame_count));
    if (cmp.beyond(std::abs(double{ca.fps} - cb.fps)))
      differ(s, name + ": fps " + arrow_num(ca.fps, cb.fps));
    if (cmp.beyond(std::abs(double{ca.duration} - cb.duration)))
      differ(s, name + ": duration " + arrow_num(ca.duration, cb.duration) + " s");
    if (ca.looping != cb.looping)
      differ(s, name + ": looping " + std::string(ca.looping ? "yes -> no" : "no -> yes"));
    const bool ra = !ca.root_motion.empty(), rb = !cb.root_motion.empty();
    double length = 0.0, yaw = 0.0;
    if (ra != rb) {
      differ(s, name + ": root motion " + std::string(ra ? "yes -> no" : "no -> yes"));
    } else if (ra && ca.root_motion.size() == cb.root_motion.size()) {
      for (size_t k = 0; k < ca.root_motion.size(); ++k) {
        const double d = std::abs(double{ca.root_motion[k]} - cb.root_motion[k]);
        double& slot = k % 3 == 2 ? yaw : length;
        slot = std::max(slot, d);
      }
      if (cmp.length_beyond(length) || cmp.beyond(yaw))
        differ(s, name + ": root motion max diff " + num(length / cmp.diagonal) +
                      " of the diagonal (x, z), " + num(yaw) + " rad (yaw)");
      motion_length.add(length, static_cast<int64_t>(i));
      motion_yaw.add(yaw, static_cast<int64_t>(i));
    }
    list.push_back({{"name", ca.name},
                    {"frames", {ca.frame_count, cb.frame_count}},
                    {"fps", {ca.fps, cb.fps}},
                    {"root_motion", {ra, rb}},
                    {"root_motion_max_diff", length},
                    {"root_motion_yaw_max_diff", yaw}});
  }
  for (size_t k = 0; k < b.clips.size(); ++k)
    if (!matched[k]) differ(s, "clip " + quoted(b.clips[k].name) + " only in B");
  if (reordered) differ(s, "clip order differs (clips are used by index)");
  s.summary = std::to_string(a.clips.size()) + " clips; root motion max diff " +
              num(motion_length.value / cmp.diagonal) + " of the diagonal, " +
              num(motion_yaw.value) + " rad";
  s.figures = {{"clips", list}};
  return s;
}

// ---- materials and bounds -------------------------------------------------------------

DiffSection diff_materials(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("materials");
  if (a.materials.size() != b.materials.size())
    differ(s, "material count " + arrow(a.materials.size(), b.materials.size()));
  const size_t n = std::min(a.materials.size(), b.materials.size());
  MaxDiff color;
  for (size_t i = 0; i < n; ++i) {
    const PackMaterial& ma = a.materials[i];
    const PackMaterial& mb = b.materials[i];
    const std::string name = "material " + std::to_string(i);
    if (ma.name != mb.name) differ(s, name + " name " + arrow(ma.name, mb.name));
    if (ma.base_color_texture != mb.base_color_texture)
      differ(s, name + " texture " + arrow(ma.base_color_texture, mb.base_color_texture));
    if (ma.base_color_image != mb.base_color_image)
      differ(s, name + " image " + arrow(ma.base_color_image, mb.base_color_image));
    if (ma.alpha_mode != mb.alpha_mode)
      differ(s, name + " alpha mode " +
                    arrow(std::string(alpha_mode_name(ma.alpha_mode)),
                          std::string(alpha_mode_name(mb.alpha_mode))));
    if (ma.double_sided != mb.double_sided)
      differ(s, name + " double-sided " + arrow(ma.double_sided, mb.double_sided));
    double d = 0.0, t = std::abs(double{ma.alpha_cutoff} - mb.alpha_cutoff);
    for (int k = 0; k < 4; ++k)
      d = std::max(d, std::abs(double{ma.base_color[k]} - mb.base_color[k]));
    for (int k = 0; k < 6; ++k)
      t = std::max(t, std::abs(double{ma.uv_transform[k]} - mb.uv_transform[k]));
    if (cmp.beyond(d)) differ(s, name + " base colour differs by " + num(d));
    if (cmp.beyond(t)) differ(s, name + " texture transform or alpha cutoff differs by " + num(t));
    color.add(d, static_cast<int64_t>(i));
  }
  // Images: compared by their stored bytes (they are never re-encoded, so equal images are
  // equal bytes).
  if (a.images.size() != b.images.size())
    differ(s, "image count " + arrow(a.images.size(), b.images.size()));
  size_t images_differ = 0;
  for (size_t i = 0; i < std::min(a.images.size(), b.images.size()); ++i) {
    const PackImage& ia = a.images[i];
    const PackImage& ib = b.images[i];
    const std::string name = "image " + std::to_string(i);
    if (ia.name != ib.name) differ(s, name + " name " + arrow(ia.name, ib.name));
    if (ia.width != ib.width || ia.height != ib.height)
      differ(s, name + " size " +
                    arrow(std::to_string(ia.width) + "x" + std::to_string(ia.height),
                          std::to_string(ib.width) + "x" + std::to_string(ib.height)));
    else if (ia.data != ib.data) {
      differ(s, name + " bytes differ (" + arrow(ia.data.size(), ib.data.size()) + " bytes)");
      ++images_differ;
    }
  }
  s.summary = std::to_string(a.materials.size()) + " materials, " +
              std::to_string(a.images.size()) + " images; base colour max diff " + num(color.value);
  s.figures = {{"materials", {a.materials.size(), b.materials.size()}},
               {"images", {a.images.size(), b.images.size()}},
               {"images_differ", images_differ},
               {"base_color_max_diff", color.value}};
  return s;
}

DiffSection diff_bounds(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("bounds");
  double box = 0.0;
  for (int k = 0; k < 3; ++k) {
    box = std::max(box, std::abs(double{a.bounds.min[k]} - b.bounds.min[k]));
    box = std::max(box, std::abs(double{a.bounds.max[k]} - b.bounds.max[k]));
  }
  const double radius = std::abs(double{a.bounds.radius} - b.bounds.radius);
  if (cmp.length_beyond(box))
    differ(s, "bind-pose box differs by " + num(box / cmp.diagonal) + " of the diagonal");
  if (cmp.length_beyond(radius))
    differ(s, "radius " + arrow_num(a.bounds.radius, b.bounds.radius) + " (" +
                  num(radius / cmp.diagonal) + " of the diagonal)");
  s.summary = "box max diff " + num(box / cmp.diagonal) + ", radius diff " +
              num(radius / cmp.diagonal) + " of the diagonal " + num(cmp.diagonal);
  s.figures = {{"diagonal", cmp.diagonal}, {"box_max_diff", box}, {"radius_diff", radius}};
  return s;
}

// ---- geometry -------------------------------------------------------------------------

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

// Geometry compares vertex by vertex through a pairing of A's vertices with B's: the
// identity when the vertices are in the same order, else the pairing by sorted position
// when that fits better (the same vertices stored in another order, e.g. after a
// different simplification). Triangles compare through the same pairing.
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

  ordered_json& f = s.figures;
  f["vertices"] = {va, vb};
  f["triangles"] = {ta, tb};
  std::string vertex_order = "not compared", triangle_order = "not compared",
              positions = "not compared";
  std::vector<uint32_t> pair;    // A vertex -> B vertex
  std::vector<uint32_t> b_to_a;  // its inverse, for B's triangles; empty for the identity
  double position_diff = 0.0;
  if (va == vb) {
    pair.resize(va);
    std::iota(pair.begin(), pair.end(), 0u);
    MaxDiff same_order;
    for (uint32_t v = 0; v < va; ++v)
      same_order.add(distance(&a.positions[3 * size_t{v}], &b.positions[3 * size_t{v}]), v);
    MaxDiff position = same_order;
    vertex_order = "same";
    if (cmp.length_beyond(same_order.value)) {
      const std::vector<uint32_t> oa = sorted_vertices(a), ob = sorted_vertices(b);
      MaxDiff sorted;
      for (uint32_t k = 0; k < va; ++k)
        sorted.add(distance(&a.positions[3 * size_t{oa[k]}], &b.positions[3 * size_t{ob[k]}]),
                   oa[k]);
      if (sorted.value < same_order.value) {
        vertex_order = "differs";
        position = sorted;
        b_to_a.resize(vb);
        for (uint32_t k = 0; k < va; ++k) pair[oa[k]] = ob[k], b_to_a[ob[k]] = oa[k];
        uint32_t first = 0;
        while (first < va && pair[first] == first) ++first;
        differ(s, "vertex order differs from vertex " + std::to_string(first) +
                      " (vertices paired by position: max distance " +
                      num(sorted.value / cmp.diagonal) + " of the diagonal)");
      }
    }
    position_diff = position.value;
    positions = cmp.length_beyond(position.value) ? "differ" : "equal";
    f["max_position_diff"] = position.value;
    f["max_position_diff_relative"] = position.value / cmp.diagonal;
    if (positions == "differ")
      differ(s, "positions differ: max " + num(position.value / cmp.diagonal) +
                    " of the diagonal at vertex " + std::to_string(position.at));

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
      f[std::string("max_") + attr.name + "_diff"] = m.value;
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
    f["joint_influences_differ"] = joints_differ;
    f["regions_differ"] = regions_differ;
  }
  // note: triangle indices compare whatever the positions did; B's go through the pairing
  // when the vertex order differs.
  if (ta == tb) {
    const auto corner = [&](size_t i) {
      return b_to_a.empty() ? b.triangles[i] : b_to_a[b.triangles[i]];
    };
    int64_t first = -1;
    for (uint32_t t = 0; t < ta && first < 0; ++t)
      for (size_t k = 0; k < 3; ++k)
        if (a.triangles[3 * size_t{t} + k] != corner(3 * size_t{t} + k)) first = t;
    f["first_differing_triangle"] = first;
    if (first < 0) {
      triangle_order = "same";
      size_t materials_differ = 0;
      for (size_t t = 0; t < a.triangle_material.size() && t < b.triangle_material.size(); ++t)
        materials_differ += a.triangle_material[t] != b.triangle_material[t];
      if (materials_differ)
        differ(s, std::to_string(materials_differ) + " triangle materials differ");
    } else if (triangle_set(a.triangles, {}) == triangle_set(b.triangles, b_to_a)) {
      triangle_order = "differs";
      differ(s, "triangle order differs from triangle " + std::to_string(first) +
                    " (the same triangles)");
    } else {
      triangle_order = "triangles differ";
      differ(s, "triangles differ from triangle " + std::to_string(first));
    }
  }
  f["positions"] = positions;
  f["vertex_order"] = vertex_order;
  f["triangle_order"] = triangle_order;
  s.summary =
      std::to_string(va) + " vertices, " + std::to_string(ta) + " triangles; max position diff " +
      (va == vb ? num(position_diff / cmp.diagonal) : std::string("-")) +
      " of the diagonal; vertex order " + vertex_order + ", triangle order " + triangle_order;
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

// ---- animation texture ----------------------------------------------------------------

DiffSection diff_animation(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("animation");
  const AnimationTexture& ta = a.animation;
  const AnimationTexture& tb = b.animation;
  s.figures["encoding"] = {animation_encoding_name(ta.encoding),
                           animation_encoding_name(tb.encoding)};
  std::string encodings = animation_encoding_name(ta.encoding);
  if (ta.encoding != tb.encoding)
    encodings += " vs " + std::string(animation_encoding_name(tb.encoding));
  if (ta.joints != tb.joints) {
    differ(s, "joints per row " + arrow(ta.joints, tb.joints) + ": matrices not compared");
    s.summary = encodings;
    return s;
  }
  const std::vector<int64_t> match = match_clips(a, b);
  ordered_json clips = ordered_json::array();
  double worst = 0.0;
  for (size_t i = 0; i < a.clips.size(); ++i) {
    if (match[i] < 0) continue;  // note: the clips section reports it
    const PackClip& ca = a.clips[i];
    const PackClip& cb = b.clips[match[i]];
    if (ca.frame_count != cb.frame_count) continue;  // likewise
    MaxDiff linear, translation;
    float ma[12], mb[12];
    for (uint32_t frame = 0; frame < ca.frame_count; ++frame)
      for (uint32_t j = 0; j < ta.joints; ++j) {
        decode_joint(ta, ca.first_row + frame, j, ma);
        decode_joint(tb, cb.first_row + frame, j, mb);
        double l = 0.0, t = 0.0;
        matrix_diff(ma, mb, l, t);
        const int64_t where = int64_t{frame} * ta.joints + j;
        linear.add(l, where), translation.add(t, where);
      }
    const double relative = translation.value / cmp.diagonal;
    const bool beyond = cmp.beyond(linear.value) || cmp.length_beyond(translation.value);
    worst = std::max({worst, linear.value, relative});
    const int64_t at =
        cmp.beyond(linear.value) || linear.value >= relative ? linear.at : translation.at;
    const std::string where = at < 0
                                  ? std::string()
                                  : ", at frame " + std::to_string(at / ta.joints) + " joint " +
                                        quoted(a.joints[static_cast<size_t>(at % ta.joints)].name);
    const std::string line = "clip " + quoted(ca.name) + ": max abs diff " + num(linear.value) +
                             " (3x3), " + num(relative) + " of the diagonal (translation)" + where;
    if (beyond) differ(s, line);
    clips.push_back({{"name", ca.name},
                     {"max_abs_diff", std::max(linear.value, translation.value)},
                     {"max_abs_diff_3x3", linear.value},
                     {"max_abs_diff_translation", translation.value},
                     {"max_diff_translation_relative", relative},
                     {"differs", beyond}});
  }
  s.figures["clips"] = clips;
  s.summary = encodings + ", " + std::to_string(ta.joints) + " joints x " +
              std::to_string(ta.rows) + " rows; decoded matrices max diff " + num(worst) +
              " over " + std::to_string(clips.size()) + " clips";
  return s;
}

// ---- partition mask -------------------------------------------------------------------

DiffSection diff_partition(const PackContents& a, const PackContents& b, const Compare& cmp) {
  DiffSection s = section("partition");
  const PartitionMask& ma = a.partition;
  const PartitionMask& mb = b.partition;
  const std::string size_a = std::to_string(ma.width) + "x" + std::to_string(ma.height);
  const std::string size_b = std::to_string(mb.width) + "x" + std::to_string(mb.height);
  int64_t changed = -1;
  if (size_a != size_b) {
    differ(s, "mask size " + size_a + " -> " + size_b + ": texels not compared");
  } else {
    changed = 0;
    std::map<std::pair<uint8_t, uint8_t>, int64_t> moves;
    for (size_t i = 0; i < ma.texels.size(); ++i)
      if (ma.texels[i] != mb.texels[i]) ++changed, ++moves[{ma.texels[i], mb.texels[i]}];
    if (changed) {
      std::string detail;
      for (const auto& [move, n] : moves)
        detail += (detail.empty() ? "" : ", ") + std::to_string(n) + " " + region_name(move.first) +
                  " -> " + region_name(move.second);
      differ(s, std::to_string(changed) + " texels changed (" + detail + ")");
    }
  }
  const double heights = std::max(std::abs(double{ma.neck_height} - mb.neck_height),
                                  std::abs(double{ma.waist_height} - mb.waist_height));
  if (cmp.length_beyond(heights))
    differ(s, "neck/waist heights " + arrow_num(ma.neck_height, mb.neck_height) + " / " +
                  arrow_num(ma.waist_height, mb.waist_height));
  double axis = 0.0;
  for (int k = 0; k < 3; ++k)
    axis = std::max(axis, std::abs(double{ma.up_axis[k]} - mb.up_axis[k]));
  if (cmp.beyond(axis)) differ(s, "up axis differs by " + num(axis));
  s.summary = size_a + " mask, " + (changed < 0 ? std::string("-") : std::to_string(changed)) +
              " texels changed";
  s.figures = {
      {"size", {size_a, size_b}}, {"changed_texels", changed}, {"height_max_diff", heights}};
  return s;
}

// ---- sizes ----------------------------------------------------------------------------

std::string signed_bytes(int64_t d) { return (d > 0 ? "+" : "") + std::to_string(d); }

DiffSection diff_sizes(const PackFile& a, const PackFile& b) {
  DiffSection s = section("sizes");
  s.info_only = true;
  ordered_json chunks = ordered_json::object();
  std::string line;
  auto add = [&](const std::string& tag, uint64_t sa, uint64_t sb) {
    chunks[tag] = {sa, sb};
    if (sa != sb)
      line += (line.empty() ? "" : ", ") + tag + " " + std::to_string(sa) + " -> " +
              std::to_string(sb) + " (" +
              signed_bytes(static_cast<int64_t>(sb) - static_cast<int64_t>(sa)) + ")";
  };
  auto size_of = [](const PackFile& p, uint32_t tag) -> uint64_t {
    for (const PackChunk& c : p.chunks)
      if (c.tag == tag) return c.size;
    return 0;
  };
  for (const PackChunk& c : a.chunks) add(pack_format::tag_name(c.tag), c.size, size_of(b, c.tag));
  for (const PackChunk& c : b.chunks) {
    bool in_a = false;
    for (const PackChunk& k : a.chunks) in_a |= k.tag == c.tag;
    if (!in_a) add(pack_format::tag_name(c.tag), 0, c.size);
  }
  s.summary = "file " + std::to_string(a.bytes) + " -> " + std::to_string(b.bytes) + " bytes (" +
              signed_bytes(static_cast<int64_t>(b.bytes) - static_cast<int64_t>(a.bytes)) + ")" +
              (line.empty() ? "; every chunk the same size" : "; " + line);
  s.figures = {{"file", {a.bytes, b.bytes}}, {"chunks", chunks}};
  return s;
}

}  // namespace

std::vector<std::string> PackDiff::differing() const {
  std::vector<std::string> names;
  for (const DiffSection& s : sections)
    if (s.differs && !s.ignored && !s.info_only) names.push_back(s.name);
  return names;
}

const std::vector<std::string>& diff_section_names() {
  static const std::vector<std::string> names = {
      "header",   "settings",    "skeleton",  "clips",     "materials", "bounds",
      "geometry", "progressive", "animation", "partition", "sizes"};
  return names;
}

PackDiff diff_packs(const PackFile& a, const PackFile& b, const DiffOptions& options) {
  PackDiff diff;
  diff.tolerance = options.tolerance;
  const double diagonal = std::max(bbox_diagonal(a.contents), bbox_diagonal(b.contents));
  diff.diagonal = diagonal > 0.0 ? diagonal : 1.0;
  const Compare cmp{options.tolerance, diff.diagonal};
  const PackContents& ca = a.contents;
  const PackContents& cb = b.contents;
  diff.sections.push_back(diff_header(a, b));
  diff.sections.push_back(diff_settings(ca, cb));
  diff.sections.push_back(diff_skeleton(ca, cb, cmp));
  diff.sections.push_back(diff_clips(ca, cb, cmp));
  diff.sections.push_back(diff_materials(ca, cb, cmp));
  diff.sections.push_back(diff_bounds(ca, cb, cmp));
  diff.sections.push_back(diff_geometry(ca, cb, cmp));
  diff.sections.push_back(diff_progressive(ca, cb));
  diff.sections.push_back(diff_animation(ca, cb, cmp));
  diff.sections.push_back(diff_partition(ca, cb, cmp));
  diff.sections.push_back(diff_sizes(a, b));
  for (DiffSection& s : diff.sections)
    s.ignored = s.differs && std::find(options.ignore.begin(), options.ignore.end(), s.name) !=
                                 options.ignore.end();
  return diff;
}

}  // namespace crowdbake::cli
