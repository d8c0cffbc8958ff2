// What a collapse costs beyond DQEM, and the one geometric refusal: the prices the collapse loop
// adds to a candidate's cost (collapse.h, docs/simplification.md "One set of rules, all the way
// down"). Each reads the mesh as the collapses have left it and changes nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "simplify/posed_mesh_view.h"

namespace crowdbake {

// In every function below, `moved` lists the faces around `from` that the collapse of `from`
// onto `to` keeps (it moves their corner at `from` to `to`).

// True when moving `from` onto `to` turns one of the moved faces by 90° or more in the bind
// pose (a face with no area has no orientation to lose).
bool folds_in_bind_pose(const PosedMeshView& view, uint32_t from, uint32_t to,
                        const std::vector<uint32_t>& moved);

// How far the surface moves away from where `from` was: weight × the bind-pose area around
// `from` × the squared distance from `from` to the nearest moved face after the collapse (or
// to `to`), averaged over the poses.
double left_behind_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                         const std::vector<uint32_t>& moved, double weight);

// How far the moved faces stand off the surface they replace: weight × each moved face's area
// after the collapse × the squared distance from its centroid to the nearest face around
// `from` or `to` before it, summed over the faces and averaged over the poses. `around` is
// scratch.
double stand_off_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                       const std::vector<uint32_t>& moved, double weight,
                       std::vector<uint32_t>& around);

// The faces the collapse flips in the sampled poses other than the bind pose: weight × each
// flipped face's area × the squared length of the move, summed and divided by all the poses
// (a flip in one pose of S costs 1/S of it). Adds the (face, pose) flips to `flips`.
double flip_price(const PosedMeshView& view, uint32_t from, uint32_t to,
                  const std::vector<uint32_t>& moved, double weight, uint32_t& flips);

// What a collapse of cost `cost` (DQEM and the prices above) costs more because the faces
// around `from` cover only `area` of the `floor` it is priced at: (floor / area - 1) × cost
// below the floor, nothing at or above it or where there is no area
// (SimplifyOptions::small_area_floor).
double small_area_price(double cost, double area, double floor);

}  // namespace crowdbake
