// Animated error of a simplified character (docs/design.md §4: accuracy is measured on the
// animated character, every frame of every clip). The LoD and the original are skinned
// with the original's skeleton and clips at each frame, and the symmetric surface
// distance between the two skinned surfaces is measured.
//
// Surface distance (surface_distance below): each surface is sampled on its triangles —
// every vertex and every triangle's centroid, and on triangles longer than the sampling
// distance (1.5 × the original's median bind-pose edge length) a barycentric grid at about
// that spacing: points on the edges and inside. So a coarse LoD is sampled about as densely
// as the original. Vertices are welded by position and points shared by triangles are
// sampled once. Every sample point gets the distance to the closest point on the other
// surface's triangles (exact point-triangle distance, double precision, BVH). Both
// directions are pooled:
//   rms = sqrt((Σ_A w·d² + Σ_B w·d²) / (Σ_A w + Σ_B w)),  max = max over both directions,
// where w is the sample's share of the area of the triangles it lies on (the area at
// that frame), so rms approximates the surface integral and does not depend on how
// finely either mesh is tessellated.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

struct SurfaceError {
  double rms = 0.0;  // area-weighted RMS of the symmetric distance
  double max = 0.0;  // largest distance of any sample, both directions (sampled Hausdorff)
  // Where `max` is: the vertex nearest the farthest sample (the one with the largest
  // barycentric weight), on b when max_on_b, else on a; UINT32_MAX for an empty surface.
  uint32_t max_vertex = UINT32_MAX;
  bool max_on_b = false;
};

struct TriangleSurface {
  std::vector<glm::dvec3> positions;
  std::vector<uint32_t> triangles;  // 3 indices each
};

// Symmetric distance between two triangle surfaces, in their units. `spacing` is the
// sampling distance (0 = 1.5 × the median edge length of `a`). Symmetric: swapping a and b
// gives the same answer when the same spacing is passed. An empty surface is infinitely
// far from a non-empty one; two empty surfaces are 0 apart.
SurfaceError surface_distance(const TriangleSurface& a, const TriangleSurface& b,
                              double spacing = 0.0);

struct AnimatedErrorOptions {
  double fps = 30.0;     // frames at t = 0, 1/fps, 2/fps, ... and the clip end
  int frame_stride = 1;  // evaluate every k-th of those frames (quick runs); the end always
  int threads = 0;       // 0 = hardware concurrency; results never depend on it
  // At most this many measured sample points per surface (0: all of them); beyond it one
  // point per run of neighbouring points stands for the run (limit_points), so the cost of a
  // frame stops growing with the triangle count.
  uint32_t max_points = 0;
  // Also measure the bind pose (bind_rms, bind_max). Without it they stay 0, unless the
  // original has no clips (the bind pose is then all there is); a caller that reads only
  // mean_rms and max saves one pose's work.
  bool bind_pose = true;
};

// All numbers but `diagonal` and `frames` are divided by `diagonal`.
struct AnimatedError {
  double diagonal = 0.0;                  // bind-pose bounding-box diagonal of the original
  double bind_rms = 0.0, bind_max = 0.0;  // bind pose only (the stored positions)
  double mean_rms = 0.0;                  // mean over all frames of all clips of the per-frame RMS
  double max = 0.0;                       // max over all frames of the per-frame max
  int frames = 0;                         // frames measured; 0 when the original has no clips (then
                                          // mean_rms and max repeat the bind-pose numbers)
  // Where `max` is: the joint with the largest weight at the vertex nearest the farthest
  // sample (on the original or the LoD), and the clip and time of that frame (the first such
  // frame; clip -1: the bind pose). -1 when nothing was measured.
  int max_joint = -1;
  int max_clip = -1;
  double max_time = 0.0;
  // The farthest sample is on the LoD (its surface strays from the original's) rather than
  // on the original (a part of the original the LoD lacks).
  bool max_on_lod = false;
  // The vertex nearest the farthest sample: an index into the primitives' vertices, taken in
  // order, of the LoD when max_on_lod, else of the original; UINT32_MAX when max_joint is -1.
  uint32_t max_vertex = UINT32_MAX;
};

// Measures every LoD against the original. Each LoD must use the original's skeleton
// (same joint count and order; its clips are ignored: the original's clips drive both).
// Throws std::invalid_argument when a LoD's skeleton differs in joint count.
std::vector<AnimatedError> animated_error(const SkinnedAsset& original,
                                          const std::vector<const SkinnedAsset*>& lods,
                                          const AnimatedErrorOptions& options = {});

AnimatedError animated_error(const SkinnedAsset& original, const SkinnedAsset& lod,
                             const AnimatedErrorOptions& options = {});

// The frame times the measurement uses for one clip.
std::vector<double> clip_frame_times(const Clip& clip, double fps, int frame_stride = 1);

}  // namespace crowdbake
