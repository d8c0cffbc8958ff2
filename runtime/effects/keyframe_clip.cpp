#include "crowdbake/runtime/effects/keyframe_clip.h"

#include <cmath>

namespace crowdbake::effects {
namespace {

Status invalid(std::string message) { return {StatusCode::kInvalidArgument, std::move(message)}; }

}  // namespace

Status KeyframeClip::validate() const {
  const std::string label = "clip '" + name + "': ";
  if (joint_count == 0) return invalid(label + "no joints");
  if (frame_count == 0) return invalid(label + "no frames");
  if (keys.size() != static_cast<size_t>(joint_count) * frame_count) {
    return invalid(label + std::to_string(keys.size()) + " keys, expected " +
                   std::to_string(static_cast<size_t>(joint_count) * frame_count));
  }
  if (!std::isfinite(duration) || duration < 0.0f) {
    return invalid(label + "duration must be finite and >= 0");
  }
  if (frame_count > 1 && duration <= 0.0f) {
    return invalid(label + "several frames need a duration > 0");
  }
  for (size_t k = 0; k < keys.size(); ++k) {
    if (!is_valid_transform(keys[k])) {
      return invalid(label + "frame " + std::to_string(k / joint_count) + " joint " +
                     std::to_string(k % joint_count) +
                     " is not finite or its rotation is not unit");
    }
  }
  return {};
}

double clip_local_time(const KeyframeClip& clip, double time) {
  const double duration = clip.duration;
  if (!(duration > 0.0) || std::isnan(time)) return 0.0;
  if (!clip.looping) return time < 0.0 ? 0.0 : (time > duration ? duration : time);
  double t = std::fmod(time, duration);
  if (t < 0.0) t += duration;
  // note: fmod of a value just below a multiple can round up to duration after the add.
  return t >= duration ? 0.0 : t;
}

}  // namespace crowdbake::effects
