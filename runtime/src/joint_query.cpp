#include "crowdbake/runtime/joint_query.h"

#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/skin_job.h"

namespace crowdbake::runtime {
namespace {

// Frame and world matrix of an instance, checked.
Status prepare(const Scene& scene, uint32_t instance, float time, const Pack** pack,
               const PackClip** clip, FrameChoice& frame, float world[12]) {
  const InstanceArrays& in = scene.instances;
  if (!in.consistent())
    return {StatusCode::kInvalidArgument, "instance arrays have inconsistent lengths"};
  if (instance >= in.size())
    return {StatusCode::kInvalidArgument, "instance " + std::to_string(instance) +
                                              " out of range (" + std::to_string(in.size()) +
                                              " instances)"};
  if (in.clip[instance] >= scene.clips.size() || in.type[instance] >= scene.types.size())
    return {StatusCode::kInvalidArgument,
            "instance " + std::to_string(instance) + " has a bad type or clip index"};
  *pack = &scene.types[in.type[instance]].pack;
  if (!(*pack)->has(kPackAnimation))
    return {StatusCode::kNotLoaded, (*pack)->source_name() + ": animation is not loaded"};
  *clip = scene.clips[in.clip[instance]].clip;
  animate_instance(**clip, time, in.speed[instance], in.time_offset[instance],
                   scene.animation.filter, scene.animation.root_motion,
                   &in.position[3 * size_t{instance}], &in.rotation[4 * size_t{instance}],
                   in.scale[instance], frame, world);
  return {};
}

Status joint_matrix(const Pack& pack, const PackClip& clip, const FrameChoice& frame,
                    const float world[12], uint32_t joint, float out[12]) {
  const float* bind = pack.bind_matrix(joint);
  if (joint >= pack.counts().joints)
    return {StatusCode::kInvalidArgument, "joint " + std::to_string(joint) + " out of range (" +
                                              std::to_string(pack.counts().joints) + " joints)"};
  if (!bind)
    return {StatusCode::kInvalidArgument,
            "joint " + std::to_string(joint) + " has a singular inverse bind matrix"};
  float skin[12], posed[12];
  decode_skinning_matrix(pack.contents().animation, clip.first_row + frame.frame0,
                         clip.first_row + frame.frame1, frame.blend, joint, skin);
  compose_affine(world, skin, posed);
  compose_affine(posed, bind, out);
  return {};
}

}  // namespace

Status joint_world_matrix(const Scene& scene, uint32_t instance, uint32_t joint, float time,
                          float out[12]) {
  const Pack* pack = nullptr;
  const PackClip* clip = nullptr;
  FrameChoice frame;
  float world[12];
  if (Status s = prepare(scene, instance, time, &pack, &clip, frame, world); !s) return s;
  return joint_matrix(*pack, *clip, frame, world, joint, out);
}

Status joint_world_matrices(const Scene& scene, uint32_t instance, float time, Span<float> out) {
  const Pack* pack = nullptr;
  const PackClip* clip = nullptr;
  FrameChoice frame;
  float world[12];
  if (Status s = prepare(scene, instance, time, &pack, &clip, frame, world); !s) return s;
  const uint32_t joints = pack->counts().joints;
  if (out.size() != 12 * size_t{joints})
    return {StatusCode::kInvalidArgument,
            "output holds " + std::to_string(out.size()) + " floats, " + std::to_string(joints) +
                " joints need " + std::to_string(12 * size_t{joints})};
  for (uint32_t j = 0; j < joints; ++j)
    if (Status s = joint_matrix(*pack, *clip, frame, world, j, &out[12 * size_t{j}]); !s) return s;
  return {};
}

}  // namespace crowdbake::runtime
