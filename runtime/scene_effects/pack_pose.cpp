// Pack data → CPU poses (pack_pose.h).
#include "crowdbake/runtime/effects/pack_pose.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "crowdbake/runtime/skin_job.h"

namespace crowdbake::effects {
namespace {

// Splits an affine matrix into translation · rotation · scale. Decoded rows carry small
// shear/scale errors (quantised encodings): the rotation is the normalised quaternion of the
// scale-free basis, so it is a unit quaternion whatever the input.
Transform decompose(const glm::mat4& m) {
  Transform t;
  t.translation = glm::vec3(m[3]);
  glm::vec3 c[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
  for (int k = 0; k < 3; ++k) {
    t.scale[k] = glm::length(c[k]);
    if (t.scale[k] > 1e-12f) c[k] /= t.scale[k];
  }
  if (glm::dot(glm::cross(c[0], c[1]), c[2]) < 0.0f) {  // a mirror: keep R proper
    t.scale.x = -t.scale.x;
    c[0] = -c[0];
  }
  const glm::quat q = glm::quat_cast(glm::mat3(c[0], c[1], c[2]));
  const float len = glm::length(q);
  t.rotation = len > 0.0f ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return t;
}

}  // namespace

glm::mat4 from_rows(const float m[12]) {
  glm::mat4 out(1.0f);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m[4 * r + c];
  return out;
}

void to_rows(const glm::mat4& m, float out[12]) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out[4 * r + c] = m[c][r];
}

Status skeleton_from_pack(const runtime::Pack& pack, Skeleton& out) {
  const auto& joints = pack.contents().joints;
  Skeleton s;
  for (size_t j = 0; j < joints.size(); ++j) {
    const PackJoint& pj = joints[j];
    s.joint_names.push_back(pj.name);
    s.parents.push_back(pj.parent);
    Transform t;
    t.translation = {pj.rest_translation[0], pj.rest_translation[1], pj.rest_translation[2]};
    t.rotation = glm::normalize(glm::quat(pj.rest_rotation[3], pj.rest_rotation[0],
                                          pj.rest_rotation[1], pj.rest_rotation[2]));
    t.scale = {pj.rest_scale[0], pj.rest_scale[1], pj.rest_scale[2]};
    s.rest_pose.push_back(t);
    if (!pack.bind_matrix(static_cast<uint32_t>(j)))
      return {StatusCode::kInvalidPack,
              pack.source_name() + ": joint '" + pj.name + "' has a singular bind matrix"};
  }
  if (Status valid = s.validate(); !valid) return valid;
  out = std::move(s);
  return {};
}

Status keyframe_clip_from_pack(const runtime::Pack& pack, uint32_t clip, bool hold_last,
                               KeyframeClip& out) {
  const PackContents& c = pack.contents();
  if (!pack.has(runtime::kPackAnimation))
    return {StatusCode::kNotLoaded, pack.source_name() + ": the animation texture is not loaded"};
  if (clip >= c.clips.size())
    return {StatusCode::kInvalidArgument, pack.source_name() + ": no clip " + std::to_string(clip)};
  const PackClip& pc = c.clips[clip];
  const uint32_t joints = static_cast<uint32_t>(c.joints.size());
  const uint32_t first = hold_last ? pc.first_row + pc.frame_count - 1 : pc.first_row;
  const uint32_t frames = hold_last ? 1 : pc.frame_count;
  KeyframeClip k;
  k.name = pc.name;
  k.joint_count = joints;
  k.frame_count = frames;
  k.looping = hold_last ? false : pc.looping;
  k.duration = frames > 1 ? static_cast<float>(frames - 1) / pc.fps : 0.0f;
  k.keys.resize(static_cast<size_t>(joints) * frames);
  std::vector<glm::mat4> global(joints);
  for (uint32_t f = 0; f < frames; ++f) {
    for (uint32_t j = 0; j < joints; ++j) {
      float s[12];
      runtime::decode_skinning_matrix(c.animation, first + f, first + f, 0.0f, j, s);
      global[j] = from_rows(s) * from_rows(pack.bind_matrix(j));
      const int32_t parent = c.joints[j].parent;
      const glm::mat4 local =
          parent < 0 ? global[j] : glm::inverse(global[static_cast<size_t>(parent)]) * global[j];
      k.keys[static_cast<size_t>(f) * joints + j] = decompose(local);
    }
  }
  if (Status valid = k.validate(); !valid) return valid;
  out = std::move(k);
  return {};
}

std::vector<glm::mat4> inverse_bind_matrices(const runtime::Pack& pack) {
  std::vector<glm::mat4> out;
  for (const PackJoint& j : pack.contents().joints) out.push_back(from_rows(j.inverse_bind.data()));
  return out;
}

void skinning_matrices(Span<const glm::mat4> model, Span<const glm::mat4> inverse_bind,
                       float* out) {
  for (size_t j = 0; j < model.size() && j < inverse_bind.size(); ++j)
    to_rows(model[j] * inverse_bind[j], out + 12 * j);
}

}  // namespace crowdbake::effects
