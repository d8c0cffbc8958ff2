#include "crowdbake/runtime/gpu/gpu_instance.h"

#include <cmath>
#include <string>

#include "crowdbake/runtime/frame.h"

namespace crowdbake::runtime::gpu {
namespace {

Status invalid(const std::string& what) {
  return {StatusCode::kInvalidArgument, "fill_gpu_instances: " + what};
}

bool sized(size_t size, size_t n) { return size == 0 || size == n; }

// out = scene clip `c`, which instance i (of character type `type`) takes as its `what` clip;
// an error when it is not a clip of that type.
Status clip_of_type(const Scene& scene, uint32_t c, uint32_t type, const char* what, size_t i,
                    const PackClip*& out) {
  if (c >= scene.clips.size() || scene.clips[c].type != type)
    return invalid(std::string(what) + " clip of instance " + std::to_string(i) +
                   " is not a clip of its character type");
  out = scene.clips[c].clip;
  return {};
}

}  // namespace

Status fill_gpu_instances(const Scene& scene, const FrameState& state, const EffectFrame* effects,
                          std::vector<GpuInstance>& out) {
  const InstanceArrays& in = scene.instances;
  const size_t n = in.size();
  if (!in.consistent()) return invalid("instance arrays have inconsistent lengths");
  if (state.row0.size() != n || state.row1.size() != n || state.blend.size() != n ||
      state.world.size() != 12 * n)
    return invalid("the frame state was not computed for this scene (run update_frame first)");
  static const EffectFrame kNone;
  const EffectFrame& fx = effects ? *effects : kNone;
  if (!sized(fx.pose.size(), n) || !sized(fx.clip.size(), n) || !sized(fx.time_offset.size(), n) ||
      !sized(fx.fade_clip.size(), n) || !sized(fx.fade_time_offset.size(), n) ||
      !sized(fx.fade_weight.size(), n))
    return invalid("effect arrays must be empty or have one entry per instance");
  if (fx.has_clips() && fx.time_offset.size() != n)
    return invalid("effect clip without time_offset");
  if (fx.has_fades() && (fx.fade_time_offset.size() != n || fx.fade_weight.size() != n))
    return invalid("effect fade_clip without fade_time_offset and fade_weight");

  const FrameFilter filter = scene.animation.filter;
  out.resize(n);
  for (size_t i = 0; i < n; ++i) {
    GpuInstance& g = out[i];
    const uint32_t type = in.type[i];
    g.type = type;
    g.row0 = state.row0[i];
    g.row1 = state.row1[i];
    g.blend = state.blend[i];
    for (int k = 0; k < 12; ++k) g.world[k] = state.world[12 * i + k];
    if (fx.has_clips()) {
      const PackClip* found = nullptr;
      if (Status s = clip_of_type(scene, fx.clip[i], type, "effect", i, found); !s) return s;
      const PackClip& clip = *found;
      FrameChoice frame;
      animate_instance(clip, state.time, in.speed[i], fx.time_offset[i], filter,
                       scene.animation.root_motion, &in.position[3 * i], &in.rotation[4 * i],
                       in.scale[i], frame, g.world);
      g.row0 = clip.first_row + frame.frame0;
      g.row1 = clip.first_row + frame.frame1;
      g.blend = frame.blend;
    }
    g.row2 = g.row0;
    g.row3 = g.row1;
    g.blend23 = g.blend;
    g.crossfade = 0.0f;
    if (fx.has_fades()) {
      const PackClip* found = nullptr;
      if (Status s = clip_of_type(scene, fx.fade_clip[i], type, "fade", i, found); !s) return s;
      const PackClip& clip = *found;
      const FrameChoice frame =
          choose_frame(clip, state.time, in.speed[i], fx.fade_time_offset[i], filter);
      g.row2 = clip.first_row + frame.frame0;
      g.row3 = clip.first_row + frame.frame1;
      g.blend23 = frame.blend;
      g.crossfade = fx.fade_weight[i];
    }
    g.pose = fx.has_poses() ? fx.pose[i] : kNoPose;
    g.textures = (in.textures[i] & ~kImpostorBit) | (state.impostor[i] ? kImpostorBit : 0u);
    g.neck_height = in.neck_height[i];
    g.waist_height = in.waist_height[i];
    g.color[0] = in.color[3 * i];
    g.color[1] = in.color[3 * i + 1];
    g.color[2] = in.color[3 * i + 2];
    g.color[3] = std::fabs(in.scale[i]);
  }
  return {};
}

}  // namespace crowdbake::runtime::gpu
