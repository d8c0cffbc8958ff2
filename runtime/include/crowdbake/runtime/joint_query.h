// Joint queries: where joint j of an instance is at a time — the API for attachments (hats,
// weapons, colliders). It matches the skinning path exactly: the same frame choice,
// interpolation and root motion (animate_instance), the same decoded skinning matrix
// (decode_skinning_matrix), so an attached object moves with the drawn mesh.
//
// The animation texture stores skinning matrices S_j = G_j · B_j⁻¹ (G_j the joint's global
// matrix, B_j⁻¹ PackJoint::inverse_bind). The joint's world matrix is
//     J = world · S_j · B_j        (B_j = Pack::bind_matrix(j), the inverse of inverse_bind)
// so a vertex bound 100% to joint j, skinned to world · S_j · v, equals J · B_j⁻¹ · v.
// To attach an object authored in joint j's space: draw it with J · object_matrix.
#pragma once

#include <cstdint>

#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

// Joint j's world matrix J for instance i at scene time t (3x4 row-major).
// Returns kNotLoaded when the type's animation is not loaded, kInvalidArgument when the
// instance or joint index is out of range or the joint's inverse bind matrix is singular.
// time: scene time in seconds (the scene's AnimationSettings apply)
// out: 12 floats
Status joint_world_matrix(const Scene& scene, uint32_t instance, uint32_t joint, float time,
                          float out[12]);

// Every joint's world matrix for instance i at time t: 12 floats per joint, in skeleton
// order (cheaper than one call per joint: the frame is chosen once).
// out: 12 · joint count floats
Status joint_world_matrices(const Scene& scene, uint32_t instance, float time, Span<float> out);

}  // namespace crowdbake::runtime
