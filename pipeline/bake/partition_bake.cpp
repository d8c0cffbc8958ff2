// Partition bake: seed 000 Algorithm 3 with the comparisons of docs/design.md §3.7. The rules
// (heights, region, mask conventions) are documented in partition_bake.h.
#include "crowdbake/pipeline/partition_bake.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "bake/uv_rasterizer.h"
#include "crowdbake/pipeline/error.h"

namespace crowdbake {
namespace {

// Typical adult proportions (partition_bake.h): neck at the base of the neck, waist at
// the hip joint, as fractions of the height along up; the head joint sits about one neck
// length above the neck joint.
constexpr double kBoxNeck = 0.84;
constexpr double kBoxWaist = 0.53;
constexpr double kHeadAboveNeck = 0.05;
constexpr uint32_t kMaxSize = 16384;
constexpr uint32_t kMaxDilate = 64;

Error usage(const SkinnedAsset& asset, const std::string& message) {
  return Error(Error::Kind::kUsage, asset.source, "partition: " + message);
}

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

glm::dvec3 unit_up(const SkinnedAsset& asset, const std::array<float, 3>& axis) {
  const glm::dvec3 a(axis[0], axis[1], axis[2]);
  const double len = glm::length(a);
  if (!std::isfinite(len) || !(len > 0.0))
    throw usage(asset, "up axis (" + num(a.x) + ", " + num(a.y) + ", " + num(a.z) +
                           ") must be finite and non-zero");
  return a / len;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool any() const { return lo <= hi; }
};

Range vertex_heights(const SkinnedAsset& asset, const glm::dvec3& up) {
  Range r;
  for (const Primitive& p : asset.primitives)
    for (const glm::vec3& v : p.positions) {
      const double h = glm::dot(glm::dvec3(v), up);
      if (!std::isfinite(h)) continue;
      r.lo = std::min(r.lo, h);
      r.hi = std::max(r.hi, h);
    }
  return r;
}

// The largest extent of the vertices across up, along the world axes projected onto the
// plane perpendicular to up (the character's width or depth, or length for a quadruped).
double largest_extent_across(const SkinnedAsset& asset, const glm::dvec3& up) {
  double largest = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    glm::dvec3 d(0.0);
    d[axis] = 1.0;
    d -= glm::dot(d, up) * up;
    if (glm::length(d) < 0.5) continue;  // note: (nearly) the up axis itself.
    d = glm::normalize(d);
    Range r;
    for (const Primitive& p : asset.primitives)
      for (const glm::vec3& v : p.positions) {
        const double x = glm::dot(glm::dvec3(v), d);
        if (!std::isfinite(x)) continue;
        r.lo = std::min(r.lo, x);
        r.hi = std::max(r.hi, x);
      }
    if (r.any()) largest = std::max(largest, r.hi - r.lo);
  }
  return largest;
}

// "mixamorig:Neck" -> "neck", "Armature|Hips" -> "hips", "Bip01 Pelvis" -> "bip01 pelvis".
std::string joint_key(const std::string& name) {
  const size_t cut = name.find_last_of(":|");
  std::string key = cut == std::string::npos ? name : name.substr(cut + 1);
  for (char& ch : key) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return key;
}

// The joint closest to the root whose key contains one of `words`; -1 when none.
int find_joint(const Skeleton& skeleton, const std::vector<int>& depth,
               std::initializer_list<const char*> words) {
  int best = -1;
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const std::string key = joint_key(skeleton.joints[j].name);
    bool match = false;
    for (const char* w : words) match = match || key.find(w) != std::string::npos;
    if (match && (best < 0 || depth[j] < depth[size_t(best)])) best = static_cast<int>(j);
  }
  return best;
}

std::vector<int> joint_depths(const Skeleton& skeleton) {
  std::vector<int> depth(skeleton.joints.size(), 0);
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const int parent = skeleton.joints[j].parent;
    // note: validated assets have parent < j; anything else counts as a root here.
    if (parent >= 0 && size_t(parent) < j) depth[j] = depth[size_t(parent)] + 1;
  }
  return depth;
}

// Bind-pose height of a joint: the translation of inverse(inverse_bind) along up.
bool bind_height(const Joint& joint, const glm::dvec3& up, double& height) {
  const double det = glm::determinant(joint.inverse_bind);
  if (!std::isfinite(det) || det == 0.0) return false;
  const glm::dmat4 bind = glm::inverse(joint.inverse_bind);
  height = glm::dot(glm::dvec3(bind[3]), up);
  return std::isfinite(height);
}

struct Pick {
  bool ok = false;
  double value = 0.0;
  std::string source;  // "given", "joint 'Neck'", "joint 'Head' - 0.05 H", "bounding box"
  bool from_joint = false;
  std::string joint;  // the joint's name when from_joint and used as is
};

}  // namespace

Region partition_region(double height, float neck, float waist) {
  if (!std::isfinite(height)) return Region::kUnused;
  if (height >= double(neck)) return Region::kHead;
  if (height >= double(waist)) return Region::kUpperBody;
  return Region::kTrousers;
}

static PartitionHeights heights_or_throw(const SkinnedAsset& asset,
                                         const PartitionOptions& options) {
  const glm::dvec3 up = unit_up(asset, options.up_axis);
  if (options.neck_height && !std::isfinite(*options.neck_height))
    throw usage(asset, "neck height " + num(*options.neck_height) + " is not finite");
  if (options.waist_height && !std::isfinite(*options.waist_height))
    throw usage(asset, "waist height " + num(*options.waist_height) + " is not finite");

  PartitionHeights out;
  Range range = vertex_heights(asset, up);
  if (!range.any()) {
    out.warnings.push_back(
        "partition: no vertex with a finite position: bounding-box heights "
        "use the range 0..1");
    range.lo = 0.0, range.hi = 1.0;
  }
  const double extent = range.hi - range.lo;
  // note: an upright humanoid is about as tall as its arm span; a character much longer
  // across than along up is lying down in this axis convention (a Z-up export read with
  // Y up) or is not a biped, and heights along up mean little.
  const double across = largest_extent_across(asset, up);
  if (extent < 0.8 * across)
    out.warnings.push_back("partition: the character measures " + num(extent) +
                           " along the up axis but " + num(across) +
                           " across it: is the up axis right? (expected for a quadruped)");

  // The bounding-box heights, or, when the character is flat along up (or float rounding
  // cannot separate them), heights just outside its range: everything is upper body.
  float box_neck = static_cast<float>(range.lo + kBoxNeck * extent);
  float box_waist = static_cast<float>(range.lo + kBoxWaist * extent);
  if (!(box_waist < box_neck)) {
    box_waist =
        std::nextafter(static_cast<float>(range.lo), -std::numeric_limits<float>::infinity());
    box_neck = std::nextafter(static_cast<float>(range.hi), std::numeric_limits<float>::infinity());
    out.warnings.push_back(
        "partition: the character is flat along the up axis (or too far from "
        "the origin for float heights to tell neck from waist): everything "
        "is upper body");
  }

  const std::vector<int> depth = joint_depths(asset.skeleton);
  auto inside = [&](double h) { return h > range.lo && h < range.hi; };
  auto from_joint = [&](std::initializer_list<const char*> words, double offset, const char* what,
                        const std::string& suffix) {
    Pick pick;
    const int j = find_joint(asset.skeleton, depth, words);
    if (j < 0) return pick;
    const Joint& joint = asset.skeleton.joints[size_t(j)];
    double h = 0.0;
    if (!bind_height(joint, up, h)) {
      out.warnings.push_back("partition: joint '" + joint.name +
                             "' has no usable inverse bind matrix: not used for the " + what +
                             " height");
      return pick;
    }
    h += offset;
    if (!inside(h)) {
      out.warnings.push_back("partition: joint '" + joint.name + "' gives a " + what +
                             " height of " + num(h) + ", outside the mesh (" + num(range.lo) +
                             " .. " + num(range.hi) + " along up): not used");
      return pick;
    }
    pick.ok = true;
    pick.value = h;
    pick.source = "joint '" + joint.name + "'" + suffix;
    pick.from_joint = suffix.empty();
    pick.joint = joint.name;
    return pick;
  };

  Pick neck, waist;
  if (options.neck_height) {
    neck = {true, double(*options.neck_height), "given", false, ""};
  } else {
    neck = from_joint({"neck"}, 0.0, "neck", "");
    if (!neck.ok) neck = from_joint({"head"}, -kHeadAboveNeck * extent, "neck", " - 0.05 H");
    if (!neck.ok) neck = {true, double(box_neck), "bounding box", false, ""};
  }
  if (options.waist_height) {
    waist = {true, double(*options.waist_height), "given", false, ""};
  } else {
    waist = from_joint({"hip", "pelvis"}, 0.0, "waist", "");
    if (!waist.ok) waist = from_joint({"spine"}, 0.0, "waist", "");
    if (!waist.ok) waist = {true, double(box_waist), "bounding box", false, ""};
  }

  out.neck = static_cast<float>(neck.value);
  out.waist = static_cast<float>(waist.value);
  if (!(out.waist < out.neck)) {
    if (options.neck_height || options.waist_height)
      throw usage(asset, "waist height " + num(out.waist) + " (" + waist.source +
                             ") must be below neck height " + num(out.neck) + " (" + neck.source +
                             ")");
    out.warnings.push_back("partition: waist height " + num(out.waist) + " (" + waist.source +
                           ") is not below neck height " + num(out.neck) + " (" + neck.source +
                           "): using the bounding box for both");
    neck = {true, double(box_neck), "bounding box", false, ""};
    waist = {true, double(box_waist), "bounding box", false, ""};
    out.neck = box_neck;
    out.waist = box_waist;
  }

  if (neck.from_joint && waist.from_joint)
    out.source = "joints '" + neck.joint + "' and '" + waist.joint + "'";
  else if (neck.source == waist.source)
    out.source = neck.source;
  else
    out.source = "neck: " + neck.source + "; waist: " + waist.source;
  return out;
}

namespace {

// Every vertex's region, and every triangle of every primitive with UVs into the coverage.
void rasterize_regions(const SkinnedAsset& asset, const glm::dvec3& up, UvCoverage& coverage,
                       PartitionBake& bake) {
  PartitionStats& stats = bake.stats;
  const PartitionMask& mask = bake.mask;
  std::vector<double> h;
  bake.vertex_regions.resize(asset.primitives.size());
  for (size_t pi = 0; pi < asset.primitives.size(); ++pi) {
    const Primitive& prim = asset.primitives[pi];
    const size_t n = prim.positions.size();
    h.resize(n);
    std::vector<uint8_t>& regions = bake.vertex_regions[pi];
    regions.resize(n);
    for (size_t v = 0; v < n; ++v) {
      h[v] = glm::dot(glm::dvec3(prim.positions[v]), up);
      const Region r = partition_region(h[v], mask.neck_height, mask.waist_height);
      regions[v] = static_cast<uint8_t>(r);
      if (r == Region::kUnused)
        ++stats.vertices_non_finite;
      else
        ++stats.region_vertices[static_cast<size_t>(r)];
    }
    const std::string label =
        "primitive " + std::to_string(pi) + (prim.name.empty() ? "" : " '" + prim.name + "'");
    if (prim.uvs.size() != n) {
      ++stats.primitives_without_uvs;
      bake.warnings.push_back("partition: " + label +
                              (prim.uvs.empty()
                                   ? " has no UVs"
                                   : " has " + std::to_string(prim.uvs.size()) + " UVs for " +
                                         std::to_string(n) + " vertices") +
                              ": its vertices get regions but it leaves no mark in the mask");
      continue;
    }
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) {
      const uint32_t i0 = prim.indices[t], i1 = prim.indices[t + 1], i2 = prim.indices[t + 2];
      if (i0 >= n || i1 >= n || i2 >= n) {
        ++stats.triangles_skipped;
        continue;
      }
      switch (rasterize_uv_triangle(coverage, {prim.uvs[i0], prim.uvs[i1], prim.uvs[i2]},
                                    {h[i0], h[i1], h[i2]})) {
        case UvRasterStatus::kCovered:
          ++stats.triangles_rasterised;
          break;
        case UvRasterStatus::kNoTexel:
          ++stats.triangles_too_small;
          break;
        case UvRasterStatus::kTooLarge:
        case UvRasterStatus::kDegenerate:
        case UvRasterStatus::kNonFinite:
          ++stats.triangles_skipped;
          break;
      }
    }
  }
}

// Texels: the region of the highest height that reached them. level: that height, filled: 1
// where a surface reached the texel.
void fill_texels(const UvCoverage& coverage, PartitionBake& bake, std::vector<double>& level,
                 std::vector<uint8_t>& filled) {
  PartitionStats& stats = bake.stats;
  PartitionMask& mask = bake.mask;
  // Texels: the region of the highest height that reached them.
  const size_t texel_count = size_t(mask.width) * mask.height;
  mask.texels.assign(texel_count, static_cast<uint8_t>(Region::kUnused));
  level.assign(texel_count, -std::numeric_limits<double>::infinity());
  filled.assign(texel_count, 0);
  for (size_t i = 0; i < texel_count; ++i) {
    if (!coverage.covered(i)) continue;
    const Region top = partition_region(coverage.highest(i), mask.neck_height, mask.waist_height);
    const Region bottom = partition_region(coverage.lowest(i), mask.neck_height, mask.waist_height);
    mask.texels[i] = static_cast<uint8_t>(top);
    level[i] = coverage.highest(i);
    filled[i] = 1;
    ++stats.covered_texels;
    ++stats.region_texels[static_cast<size_t>(top)];
    if (top != bottom) ++stats.conflict_texels;
  }
}

// Dilation: Jacobi passes (each reads the previous pass only), so the result does not depend
// on the scan order.
void dilate(uint32_t passes, std::vector<double>& level, std::vector<uint8_t>& filled,
            PartitionBake& bake) {
  PartitionMask& mask = bake.mask;
  const uint32_t size = mask.width;
  std::vector<uint8_t> next_texels, next_filled;
  std::vector<double> next_level;
  for (uint32_t pass = 0; pass < passes; ++pass) {
    next_texels = mask.texels, next_filled = filled, next_level = level;
    uint64_t grown = 0;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) {
        const size_t i = size_t(y) * size + x;
        if (filled[i]) continue;
        bool found = false;
        size_t best = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const auto nx = static_cast<uint32_t>((int64_t(x) + size + dx) % size);
            const auto ny = static_cast<uint32_t>((int64_t(y) + size + dy) % size);
            const size_t j = size_t(ny) * size + nx;
            if (filled[j] && (!found || level[j] > level[best])) found = true, best = j;
          }
        if (!found) continue;
        next_texels[i] = mask.texels[best];
        next_level[i] = level[best];
        next_filled[i] = 1;
        ++grown;
      }
    mask.texels.swap(next_texels), filled.swap(next_filled), level.swap(next_level);
    bake.stats.dilated_texels += grown;
    if (grown == 0) break;
  }
}

// What the user should know about the mask.
void warn_about(PartitionBake& bake) {
  const PartitionStats& stats = bake.stats;
  const PartitionMask& mask = bake.mask;
  if (stats.conflict_texels > 0)
    bake.warnings.push_back("partition: " + std::to_string(stats.conflict_texels) +
                            " texels are shared by surfaces of different regions (overlapping "
                            "UVs): the highest surface's region wins");
  if (stats.triangles_skipped > 0)
    bake.warnings.push_back("partition: " + std::to_string(stats.triangles_skipped) +
                            " triangles not rasterised (non-finite, zero UV area, bad index, or "
                            "UVs spanning more than " +
                            std::to_string(kUvMaxTiles) + " tiles)");
  if (stats.vertices_non_finite > 0)
    bake.warnings.push_back("partition: " + std::to_string(stats.vertices_non_finite) +
                            " vertices with a non-finite position get region 255 (unused)");
  static const char* const kNames[3] = {"head", "upper body", "trousers"};
  const uint64_t vertices =
      stats.region_vertices[0] + stats.region_vertices[1] + stats.region_vertices[2];
  for (int r = 0; r < 3; ++r)
    if (vertices > 0 && stats.region_vertices[size_t(r)] == 0)
      bake.warnings.push_back(std::string("partition: no vertex in the ") + kNames[r] +
                              " region (neck " + num(mask.neck_height) + ", waist " +
                              num(mask.waist_height) + ", " + bake.height_source + ")");
}

}  // namespace

static PartitionBake partition_or_throw(const SkinnedAsset& asset,
                                        const PartitionOptions& options) {
  if (options.size < 1 || options.size > kMaxSize)
    throw usage(asset, "mask size " + std::to_string(options.size) + " is outside 1.." +
                           std::to_string(kMaxSize));
  if (options.dilate > kMaxDilate)
    throw usage(asset, "dilation " + std::to_string(options.dilate) + " is above " +
                           std::to_string(kMaxDilate));
  const glm::dvec3 up = unit_up(asset, options.up_axis);
  PartitionHeights heights = heights_or_throw(asset, options);

  PartitionBake bake;
  PartitionStats& stats = bake.stats;
  bake.height_source = heights.source;
  bake.warnings = std::move(heights.warnings);
  PartitionMask& mask = bake.mask;
  const uint32_t size = options.size;
  mask.width = mask.height = size;
  mask.neck_height = heights.neck;
  mask.waist_height = heights.waist;
  mask.up_axis = {float(up.x), float(up.y), float(up.z)};

  // Vertex regions, then every triangle of every primitive with UVs into the coverage.
  UvCoverage coverage(size);
  rasterize_regions(asset, up, coverage, bake);
  std::vector<double> level;
  std::vector<uint8_t> filled;
  fill_texels(coverage, bake, level, filled);
  dilate(options.dilate, level, filled, bake);
  const size_t texel_count = size_t(size) * size;
  stats.unused_texels = texel_count - stats.covered_texels - stats.dilated_texels;
  warn_about(bake);
  return bake;
}

Status partition_heights(const SkinnedAsset& asset, const PartitionOptions& options,
                         PartitionHeights& out) {
  return capture_errors([&] { out = heights_or_throw(asset, options); });
}

Status bake_partition(const SkinnedAsset& asset, const PartitionOptions& options,
                      PartitionBake& out) {
  return capture_errors([&] { out = partition_or_throw(asset, options); });
}

}  // namespace crowdbake
