// aiAnimation → Clip: one Track per key array of a joint's aiNodeAnim, times in seconds.
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "crowdbake/pipeline/error.h"
#include "import/animated_nodes.h"
#include "import/assimp_scene.h"
#include "import/name_list.h"
#include "import/node_transform.h"

namespace crowdbake::ai {
namespace {

glm::dvec3 to_glm(const aiVector3D& v) { return {v.x, v.y, v.z}; }
glm::dquat to_glm(const aiQuaternion& q) { return {q.w, q.x, q.y, q.z}; }

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
bool finite(const glm::dquat& q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

struct ClipContext {
  const std::string& source;
  const std::string& clip;
  double ticks_per_second;
  bool reordered = false;
};

// Key arrays → Track (Assimp 5.2 keys carry no interpolation mode: LINEAR, quaternions
// slerped by the evaluator). Keys whose times go backwards are sorted.
template <typename Key, typename T>
Track<T> convert_keys(const Key* keys, unsigned count, const std::string& node, const char* what,
                      ClipContext& context) {
  Track<T> track;
  track.interpolation = Interpolation::kLinear;
  if (!keys) count = 0;
  track.times.reserve(count);
  track.values.reserve(count);
  for (unsigned k = 0; k < count; ++k) {
    const double time = keys[k].mTime / context.ticks_per_second;
    const T value = to_glm(keys[k].mValue);
    if (!std::isfinite(time) || !finite(value))
      throw input_error(context.source, "clip '" + context.clip + "', node '" + node +
                                            "': " + what + " key " + std::to_string(k) +
                                            " is NaN or infinite; fix the animation and re-export");
    track.times.push_back(time);
    track.values.push_back(value);
  }
  if (!std::is_sorted(track.times.begin(), track.times.end())) {
    std::vector<size_t> order(count);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return track.times[a] < track.times[b]; });
    Track<T> sorted;
    for (size_t i : order) {
      sorted.times.push_back(track.times[i]);
      sorted.values.push_back(track.values[i]);
    }
    track = std::move(sorted);
    context.reordered = true;
  }
  return track;
}

// Whether an animation channel differs from the node's stored transform (then the node
// moves, and is either kept as a joint or reported).
bool moves(const aiNodeAnim& channel, const glm::dmat4& stored) {
  const Transform rest = decompose_transform(stored);
  for (unsigned k = 0; k < channel.mNumPositionKeys; ++k)
    if (moves_translation(to_glm(channel.mPositionKeys[k].mValue), rest)) return true;
  for (unsigned k = 0; k < channel.mNumRotationKeys; ++k)
    if (moves_rotation(to_glm(channel.mRotationKeys[k].mValue), rest)) return true;
  for (unsigned k = 0; k < channel.mNumScalingKeys; ++k)
    if (moves_scale(to_glm(channel.mScalingKeys[k].mValue), rest)) return true;
  return false;
}

template <typename T>
void shift(Track<T>& track, double by) {
  for (double& t : track.times) t += by;
}

}  // namespace

std::vector<bool> moving_nodes(const aiScene& scene, const NodeTable& table) {
  std::vector<bool> moving(table.nodes.size(), false);
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    const aiAnimation* anim = scene.mAnimations[a];
    if (!anim) continue;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      const aiNodeAnim* channel = anim->mChannels[c];
      if (!channel) continue;
      const auto it = table.by_name.find(channel->mNodeName.C_Str());
      if (it != table.by_name.end() && !moving[it->second])
        moving[it->second] = moves(*channel, table.local[it->second]);
    }
  }
  return moving;
}

void convert_animations(const aiScene& scene, const NodeTable& table,
                        const std::vector<int>& joint_of_node,
                        const std::vector<bool>& reported_node, SkinnedAsset& asset) {
  const size_t joint_count = asset.skeleton.joints.size();
  for (unsigned a = 0; a < scene.mNumAnimations; ++a) {
    const aiAnimation* anim = scene.mAnimations[a];
    if (!anim) continue;
    Clip clip;
    clip.name = anim->mName.C_Str();
    if (clip.name.empty()) clip.name = "animation_" + std::to_string(a);
    double ticks = anim->mTicksPerSecond;
    if (!(ticks > 0.0) || !std::isfinite(ticks)) {
      // note: Assimp's convention for "not specified" is 25 ticks per second.
      ticks = 25.0;
      asset.warnings.push_back("clip '" + clip.name +
                               "' gives no tick rate; assumed Assimp's default of 25 per second");
    }
    ClipContext context{asset.source, clip.name, ticks};
    clip.duration = anim->mDuration / ticks;
    if (!std::isfinite(clip.duration) || clip.duration < 0.0) clip.duration = 0.0;
    clip.channels.resize(joint_count);

    std::vector<bool> filled(joint_count, false);
    std::vector<std::string> moving_non_joints, unknown, repeated;
    bool animates = false;
    for (unsigned c = 0; c < anim->mNumChannels; ++c) {
      const aiNodeAnim* channel = anim->mChannels[c];
      if (!channel) continue;
      const std::string node_name = channel->mNodeName.C_Str();
      const auto it = table.by_name.find(node_name);
      if (it == table.by_name.end()) {
        unknown.push_back(node_name);
        continue;
      }
      const int node = it->second;
      const int joint = joint_of_node[node];
      if (joint < 0) {
        if (reported_node[node] && moves(*channel, table.local[node]))
          moving_non_joints.push_back(node_name);
        continue;
      }
      if (filled[joint]) {
        repeated.push_back(node_name);
        continue;
      }
      filled[joint] = true;
      animates = true;
      JointChannels& out = clip.channels[joint];
      out.translation = convert_keys<aiVectorKey, glm::dvec3>(
          channel->mPositionKeys, channel->mNumPositionKeys, node_name, "position", context);
      out.rotation = convert_keys<aiQuatKey, glm::dquat>(
          channel->mRotationKeys, channel->mNumRotationKeys, node_name, "rotation", context);
      out.scale = convert_keys<aiVectorKey, glm::dvec3>(
          channel->mScalingKeys, channel->mNumScalingKeys, node_name, "scaling", context);
    }
    const std::string who = "clip '" + clip.name + "': ";
    if (!animates) {
      asset.warnings.push_back(who + "animates no joint of the imported character; skipped");
      continue;
    }
    if (!moving_non_joints.empty())
      asset.warnings.push_back(who + "animation of " + std::to_string(moving_non_joints.size()) +
                               " node(s) that move no joint and no mesh is ignored (" +
                               name_list(moving_non_joints) + ")");
    if (!unknown.empty())
      asset.warnings.push_back(who + "channels for nodes not in the scene are ignored (" +
                               name_list(unknown) + ")");
    if (!repeated.empty())
      asset.warnings.push_back(who + "joints animated by more than one channel use the first (" +
                               name_list(repeated) + ")");
    if (anim->mNumMeshChannels > 0 || anim->mNumMorphMeshChannels > 0)
      asset.warnings.push_back(who + "mesh and morph-target animation is ignored");
    if (context.reordered) asset.warnings.push_back(who + "keys out of time order were sorted");

    // Keys must lie in [0, duration]: shift a clip that starts before 0, and stretch the
    // duration over keys past its end.
    double first = 0.0, last = 0.0;
    for (const JointChannels& ch : clip.channels)
      for (const std::vector<double>* times :
           {&ch.translation.times, &ch.rotation.times, &ch.scale.times})
        if (!times->empty()) {
          first = std::min(first, times->front());
          last = std::max(last, times->back());
        }
    if (first < 0.0) {
      for (JointChannels& ch : clip.channels) {
        shift(ch.translation, -first);
        shift(ch.rotation, -first);
        shift(ch.scale, -first);
      }
      asset.warnings.push_back(who + "keys start at " + std::to_string(first) +
                               " s; the clip was shifted to start at 0");
      last -= first;
      clip.duration -= first;
    }
    if (last > clip.duration) {
      if (last - clip.duration > 1e-6 * std::max(1.0, last))
        asset.warnings.push_back(who + "keys run past the stated duration; duration set to " +
                                 std::to_string(last) + " s");
      clip.duration = last;
    }
    asset.clips.push_back(std::move(clip));
  }
}

}  // namespace crowdbake::ai
