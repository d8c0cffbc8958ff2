// The reference evaluation every accuracy number is measured against (docs/design.md §3.1):
// clip sampling → local joint transforms → global matrices G_j = G_parent * L_j →
// linear blend skinning v' = Σ w_i · G_i · B_i^-1 · v. Double precision throughout.
#pragma once

#include <vector>

#include "crowdbake/pipeline/skinned_asset.h"

namespace crowdbake {

// Local transforms of every joint at time t (seconds, clamped to [0, duration]).
// Joints without a track keep their rest value.
void sample_clip(const Skeleton& skeleton, const Clip& clip, double t,
                 std::vector<Transform>& local);

// Local transforms of the rest pose (every joint at its stored transform).
void rest_pose(const Skeleton& skeleton, std::vector<Transform>& local);

// G_j = G_parent(j) * pre_j * TRS_j.
void local_to_global(const Skeleton& skeleton, const std::vector<Transform>& local,
                     std::vector<glm::dmat4>& global);

// Skinning matrices S_j = G_j * B_j^-1.
void skinning_matrices(const Skeleton& skeleton, const std::vector<glm::dmat4>& global,
                       std::vector<glm::dmat4>& skinning);

// v'_k = Σ_i w_ki · S_{j_ki} · v_k for every vertex of the primitive.
void skin_positions(const Primitive& primitive, const std::vector<glm::dmat4>& skinning,
                    std::vector<glm::dvec3>& out);
// The same for the vertices [begin, end) only: out[i] is vertex begin + i.
void skin_positions(const Primitive& primitive, const std::vector<glm::dmat4>& skinning,
                    size_t begin, size_t end, std::vector<glm::dvec3>& out);

// Convenience: every primitive's skinned positions, concatenated, at time t of a clip.
// clip == nullptr skins the rest pose.
std::vector<glm::dvec3> skin_asset(const SkinnedAsset& asset, const Clip* clip, double t);

}  // namespace crowdbake
