// Small skeletons and clips for the effects tests and benchmark.
#pragma once

#include <cmath>
#include <cstdint>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <string>
#include <vector>

#include "crowdbake/runtime/effects/anim_sharing.h"
#include "crowdbake/runtime/effects/keyframe_clip.h"
#include "crowdbake/runtime/effects/pose.h"

namespace crowdbake::effects::testing {

// A chain-and-branches skeleton: joint j's parent is (j − 1) / 2 (a binary tree), bones
// 0.1 along +Y.
inline Skeleton make_skeleton(uint32_t joints) {
  Skeleton skeleton;
  for (uint32_t j = 0; j < joints; ++j) {
    skeleton.joint_names.push_back("joint" + std::to_string(j));
    skeleton.parents.push_back(j == 0 ? kNoParent : static_cast<int32_t>((j - 1) / 2));
    Transform rest;
    rest.translation = j == 0 ? glm::vec3(0.0f) : glm::vec3(0.0f, 0.1f, 0.0f);
    skeleton.rest_pose.push_back(rest);
  }
  return skeleton;
}

// A looping clip where joint j swings about a joint-specific axis by
// amplitude · sin(2π · frame / (frames − 1) + phase_j); the last frame equals the first.
// `seed` picks the axes and phases, `amplitude` is in radians.
inline KeyframeClip make_clip(const std::string& name, uint32_t joints, uint32_t frames,
                              float duration, uint32_t seed, float amplitude = 0.8f) {
  KeyframeClip clip;
  clip.name = name;
  clip.joint_count = joints;
  clip.frame_count = frames;
  clip.duration = duration;
  clip.looping = true;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<glm::vec3> axes(joints);
  std::vector<float> phases(joints);
  for (uint32_t j = 0; j < joints; ++j) {
    glm::vec3 axis(unit(rng), unit(rng), unit(rng));
    if (glm::length(axis) < 1e-3f) axis = glm::vec3(0.0f, 0.0f, 1.0f);
    axes[j] = glm::normalize(axis);
    phases[j] = 3.14159265f * unit(rng);
  }
  for (uint32_t f = 0; f < frames; ++f) {
    const float phase = frames > 1 ? 6.28318531f * static_cast<float>(f) / (frames - 1) : 0.0f;
    for (uint32_t j = 0; j < joints; ++j) {
      Transform key;
      key.translation =
          j == 0 ? glm::vec3(0.02f * std::sin(phase), 0.0f, 0.0f) : glm::vec3(0.0f, 0.1f, 0.0f);
      key.rotation = glm::angleAxis(amplitude * std::sin(phase + phases[j]), axes[j]);
      clip.keys.push_back(key);
    }
  }
  return clip;
}

// State ids used by make_setup().
enum : StateId { kIdle = 0, kWalk = 1, kHit = 2, kWave = 3 };

// Four states over `joints` joints: idle and walk (2 clips each), hit, and an additive wave
// masked to the upper half of the joints. The processor plays parameter 0 as the wanted
// state (parameters start at 0 = idle).
inline AnimSharingSetup make_setup(uint32_t joints = 8, uint32_t instances = 4,
                                   uint32_t max_transitions = 4, uint32_t additive_instances = 2) {
  AnimSharingSetup setup;
  setup.skeleton = make_skeleton(joints);
  for (uint32_t c = 0; c < 6; ++c) {
    setup.clips.push_back(
        make_clip("clip" + std::to_string(c), joints, 31, 1.0f + 0.25f * c, 100 + c));
  }
  AnimState idle{kIdle, {0, 1}, false, {}, instances};
  AnimState walk{kWalk, {2, 3}, false, {}, instances};
  AnimState hit{kHit, {4}, false, {}, instances};
  AnimState wave{kWave, {5}, true, std::vector<float>(joints, 0.0f), additive_instances};
  for (uint32_t j = joints / 2; j < joints; ++j) wave.skeletal_mask[j] = 1.0f;
  if (joints > 2) wave.skeletal_mask[joints / 2 - 1] = 0.5f;
  setup.states = {idle, walk, hit, wave};
  setup.processor = [](StateId current, Span<const float> parameters) {
    (void)current;
    return StateDecision{static_cast<StateId>(parameters[0]), true};
  };
  setup.max_transition_count = max_transitions;
  setup.transition_time = 0.25f;
  setup.transition_join_window = 0.05f;
  setup.parameter_count = 1;
  return setup;
}

}  // namespace crowdbake::effects::testing
