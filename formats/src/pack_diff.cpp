// diff_packs: one static function per section, each filling a DiffSection from the two
// decoded packs. Tolerance rules are in pack_diff.h.
#include "crowdbake/formats/pack_diff.h"

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
#include "pack_diff_support.h"

namespace crowdbake {
namespace {

using namespace diff;

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
    if (ia.mime_type != ib.mime_type)
      differ(s, name + " type " + arrow(ia.mime_type, ib.mime_type));
    if (ia.width != ib.width || ia.height != ib.height)
      differ(s, name + " size " +
                    arrow(std::to_string(ia.width) + "x" + std::to_string(ia.height),
                          std::to_string(ib.width) + "x" + std::to_string(ib.height)));
    else if (ia.data != ib.data) {
      differ(s, name + " bytes differ (" + arrow(ia.data.size(), ib.data.size()) + " bytes)");
      ++images_differ;
    }
  }
  // Vertex colours (VCOL): compared byte for byte; vertex order is GEOM's.
  if (a.vertex_colors.size() != b.vertex_colors.size()) {
    differ(s, "vertex colours " + arrow(a.vertex_colors.size(), b.vertex_colors.size()));
  } else {
    size_t changed = 0;
    for (size_t v = 0; v < a.vertex_colors.size(); ++v)
      changed += a.vertex_colors[v] != b.vertex_colors[v];
    if (changed) differ(s, std::to_string(changed) + " vertex colours differ");
  }
  static const char* const kRegions[3] = {"head", "upper body", "trousers"};
  for (int r = 0; r < 3; ++r) {
    const PackVariantImages &va = a.variant_images, &vb = b.variant_images;
    // note: where a region has none, where they would start means nothing.
    if (va.count[r] != vb.count[r] || (va.count[r] > 0 && va.first[r] != vb.first[r]))
      differ(s,
             std::string(kRegions[r]) + " variant images " +
                 arrow(std::to_string(va.count[r]) + " from image " + std::to_string(va.first[r]),
                       std::to_string(vb.count[r]) + " from image " + std::to_string(vb.first[r])));
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

// The impostor (IMPS): shape and texels compared exactly (a re-bake at other settings changes
// every texel, so a count says more than where).
DiffSection diff_impostor(const PackContents& a, const PackContents& b) {
  DiffSection s = section("impostor");
  const PackImpostor &ia = a.impostor, &ib = b.impostor;
  const auto shape = [](const PackImpostor& m) {
    return m.empty() ? std::string("none")
                     : std::to_string(m.views) + " views x " + std::to_string(m.frames) +
                           " frames of " + std::to_string(m.width) + "x" + std::to_string(m.height);
  };
  int64_t changed = -1;
  if (shape(ia) != shape(ib)) {
    differ(s, shape(ia) + " -> " + shape(ib));
  } else {
    changed = 0;
    for (size_t i = 0; i < ia.texels.size(); i += 2)
      changed += ia.texels[i] != ib.texels[i] || ia.texels[i + 1] != ib.texels[i + 1];
    if (changed) differ(s, std::to_string(changed) + " texels differ");
    if (ia.frame_of_row != ib.frame_of_row) differ(s, "frames shown per row differ");
    if (ia.half_width != ib.half_width || ia.bottom != ib.bottom || ia.top != ib.top)
      differ(s, "cell rectangle differs");
  }
  s.summary = shape(ia) + ", " + (changed < 0 ? std::string("-") : std::to_string(changed)) +
              " texels changed";
  s.figures = {{"shape", {shape(ia), shape(ib)}}, {"changed_texels", changed}};
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
      "geometry", "progressive", "animation", "partition", "impostor",  "sizes"};
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
  diff.sections.push_back(diff_impostor(ca, cb));
  diff.sections.push_back(diff_sizes(a, b));
  for (DiffSection& s : diff.sections)
    s.ignored = s.differs && std::find(options.ignore.begin(), options.ignore.end(), s.name) !=
                                 options.ignore.end();
  return diff;
}

}  // namespace crowdbake
