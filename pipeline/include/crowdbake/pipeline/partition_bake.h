// Partition bake (seed 000 Algorithm 3, docs/design.md §3.7): splits a character into head,
// upper body and trousers by two heights measured on the bind pose along the up axis,
// as a UV-space mask texture (for the runtime's per-fragment textureMapping[type][uv])
// and as a region id per vertex.
//
// Region rule (the seed writes the comparisons the other way round, as if the axis
// pointed down; docs/design.md §3.7 fixes them). With h = dot(bind-pose position, up):
//   h >= neck           -> Region::kHead
//   waist <= h < neck   -> Region::kUpperBody
//   h < waist           -> Region::kTrousers
// so a point exactly on a boundary belongs to the region above it.
// Height alone decides, as in the seed: hands hanging below the waist are trousers.
// The up axis is not guessed: a character much longer across it than along it (a Z-up
// mesh read with the default Y up, a quadruped) gets a warning.
//
// Heights (PartitionHeights below), each one independently, first that applies:
//   1. given: PartitionOptions::neck_height / waist_height, in model units along the
//      normalised up axis (absolute: dot(position, up), not relative to the feet).
//   2. joints, by name: a joint's name is lower-cased and everything up to its last ':'
//      or '|' dropped (mixamorig:Neck -> neck, Armature|Hips -> hips); among the joints
//      whose name then contains the key, the one closest to the root (fewest ancestors;
//      then the lowest index) is used, at its bind-pose position (the translation of
//      inverse(inverse_bind)):
//        neck:  "neck" (Neck, neck_01, Bip01 Neck, mixamorig:Neck) at the joint; else
//               "head" (Head, Bip01 Head) 0.05 x the character's height below the joint
//               (common rigs put the head joint one neck length, about 0.05 H, above the
//               neck joint);
//        waist: "hip" or "pelvis" (Hips, hips, pelvis, Bip01 Pelvis, mixamorig:Hips) at
//               the joint; else "spine" (Spine, spine_01) at the joint.
//      A joint height outside the open range of the mesh's vertex heights is ignored
//      (warning) and the bounding box is used for that height.
//   3. bounding box of the bind-pose vertex heights [lo, hi], H = hi - lo:
//      neck = lo + 0.84 H, waist = lo + 0.53 H. Typical adult proportions (the
//      segment-length figure of Drillis & Contini as given in D. A. Winter, "Biomechanics
//      and Motor Control of Human Movement": shoulder 0.818 H, chin 0.870 H, hip joint
//      0.530 H): the neck height sits at the base of the neck between shoulder and chin,
//      where common rigs put their neck joint, and the waist at the hip joint, matching
//      rule 2. Only meaningful for an upright humanoid.
// waist < neck is required. Given heights that are not finite, or that break the order
// (with each other or with a default), throw crowdbake::Error (kUsage). Defaults that
// break it fall back to the bounding box for both, with a warning. A character that is
// flat along the up axis (or has no vertices) gets heights just outside its vertex
// range, so everything is upper body (warning).
//
// Mask (PartitionMask, size x size texels): texel (x, y) covers u in [x/size, (x+1)/size)
// and v in [y/size, (y+1)/size): u -> x, v -> y, row 0 at v = 0, which is the top row of
// the image in glTF's convention (v = 0 at the top). Each triangle is rasterised in UV
// space at texel centres with the bind-pose height interpolated barycentrically, so the
// region boundary is exact per texel:
// - coverage uses exact integer edge functions on UVs snapped to 1/256 texel, with a
//   top-left rule: a texel centre exactly on an edge shared by two triangles is filled
//   by exactly one of them;
// - UVs outside [0, 1] wrap (repeat, glTF's default sampler): each triangle is moved by
//   whole tiles so its smallest u and v lie in [0, 1), and every covered texel centre is
//   written at (x mod size, y mod size). A triangle whose UVs span more than 4 tiles on
//   either axis is not rasterised (warning);
// - where triangles overlap in UV space (mirrored or stacked charts, palette textures),
//   the texel takes the highest height that reaches it (the region of the topmost
//   surface using it): independent of triangle and primitive order, so any reordering
//   of the mesh bakes the same mask. Texels whose covering surfaces disagree on the
//   region are counted in PartitionStats::conflict_texels (warning when nonzero);
// - triangles with non-finite UVs or heights, or zero UV area, are skipped (counted);
//   primitives without UVs get vertex regions only and leave no mark in the mask
//   (warning);
// - texels no triangle covers are Region::kUnused (255), except that PartitionOptions::
//   dilate passes grow the covered texels outward: in each pass every unused texel with
//   a covered 8-neighbour (wrapping at the borders, as the sampler does) takes the region
//   of the neighbour with the highest height. The runtime should sample the mask with
//   nearest filtering (region ids do not interpolate); the dilation keeps fragments at
//   chart borders, whose nearest texel centre lies just outside the chart, off kUnused.
//
// Deterministic: the same asset and options give the same bake. No NaN is produced.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct PartitionOptions {
  uint32_t size = 256;                    // mask is size x size texels; 1..16384
  std::optional<float> neck_height;       // model units along up_axis; unset = default
  std::optional<float> waist_height;      // model units along up_axis; unset = default
  std::array<float, 3> up_axis{0, 1, 0};  // any finite non-zero length; normalised
  uint32_t dilate = 2;                    // dilation passes (texels); 0 = none; <= 64
};

// Where the two heights came from.
struct PartitionHeights {
  float neck = 0.0f, waist = 0.0f;  // waist < neck
  std::string source;               // "given", "bounding box", "joints 'Neck' and 'Hips'",
                       // or per height: "neck: joint 'Head' - 0.05 H; waist: bounding box"
  std::vector<std::string> warnings;
};

struct PartitionStats {
  uint64_t covered_texels = 0;                       // texels some triangle's rasterisation reached
  uint64_t dilated_texels = 0;                       // unused texels filled by dilation
  uint64_t unused_texels = 0;                        // kUnused after dilation
  uint64_t conflict_texels = 0;                      // covered by triangles of different regions
  std::array<uint64_t, 3> region_texels{0, 0, 0};    // per region (head, upper, trousers),
                                                     // covered texels only (no dilation)
  std::array<uint64_t, 3> region_vertices{0, 0, 0};  // per region, all primitives
  uint64_t triangles_rasterised = 0;                 // reached at least one texel centre
  uint64_t triangles_too_small = 0;                  // valid, but cover no texel centre
  uint64_t triangles_skipped = 0;  // non-finite, zero UV area, bad index or > 4 tiles
  uint32_t primitives_without_uvs = 0;
  uint64_t vertices_non_finite = 0;  // non-finite height: region kUnused
};

struct PartitionBake {
  PartitionMask mask;
  std::vector<std::vector<uint8_t>> vertex_regions;  // per primitive, per vertex: a Region
  std::string height_source;                         // PartitionHeights::source
  PartitionStats stats;
  std::vector<std::string> warnings;  // each one line, prefixed "partition: "
};

// The region of a point at bind-pose height `height` (see the rule above). A non-finite
// height gives Region::kUnused.
Region partition_region(double height, float neck, float waist);

// The neck and waist heights the bake would use. kInvalidArgument for bad options
// (non-finite or out-of-order given heights, a zero or non-finite up axis).
[[nodiscard]] Status partition_heights(const SkinnedAsset& asset, const PartitionOptions& options,
                                       PartitionHeights& out);

// Bakes the mask and the vertex regions. kInvalidArgument for bad options (size outside
// 1..16384, dilate > 64, and as partition_heights).
[[nodiscard]] Status bake_partition(const SkinnedAsset& asset, const PartitionOptions& options,
                                    PartitionBake& out);

}  // namespace crowdbake
