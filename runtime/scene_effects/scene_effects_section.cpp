// The reader of scene.json's "effects" key (docs/scene-format.md, scene_effects.h), which
// load_scene() calls through SceneLoadOptions::sections: stage 1 reads the declaration before
// any pack is opened; stage 3 checks the names that need the packs (the driven types, clips,
// mask joints, team generators) and applies the renderer-side switches to the scene's data.
#include <algorithm>
#include <utility>

#include "scene_effects_read.h"

namespace crowdbake::effects {

using namespace json_reader;
using runtime::Scene;

constexpr const char* kKey = "effects";

int32_t find_state(const std::vector<EffectState>& states, const std::string& name) {
  for (size_t i = 0; i < states.size(); ++i)
    if (states[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

namespace {

std::string name_list(const std::vector<EffectState>& states) {
  std::string out;
  for (const EffectState& st : states) out += (out.empty() ? "" : ", ") + st.name;
  return out;
}

}  // namespace

uint32_t known_state(const SceneEffects& e, const std::string& name, const std::string& path) {
  const int32_t i = find_state(e.states, name);
  if (i < 0)
    fail(path,
         "unknown state " + in_quotes(name) + " (effects.states: " + name_list(e.states) + ")");
  return static_cast<uint32_t>(i);
}

namespace {

// Stage 1's result: the declaration, and the driven types by name (resolved in stage 3).
struct ReadEffects {
  SceneEffects e;
  std::vector<std::string> types;  // empty = the only type
  std::string types_path;
};

void read_states(const Json& v, SceneEffects& e) {
  const std::string path = "effects.states";
  const Json& arr = array(v, path);
  if (arr.empty()) fail(path, "needs at least one state");
  for (size_t i = 0; i < arr.size(); ++i) {
    const std::string sp = item_path(path, i);
    check_object(arr[i], sp,
                 {"name", "clips", "pose", "pose_in", "pose_out", "rest", "interruptible",
                  "contagious", "additive", "mask", "instances"});
    EffectState st;
    st.name = string(require(arr[i], "name", sp), sp + ".name");
    if (st.name.empty()) fail(sp + ".name", "must not be empty");
    if (find_state(e.states, st.name) >= 0)
      fail(sp + ".name", in_quotes(st.name) + " is declared twice");
    const Json& clips = array(require(arr[i], "clips", sp), sp + ".clips");
    if (clips.empty()) fail(sp + ".clips", "needs at least one clip");
    double total = 0.0;
    for (size_t k = 0; k < clips.size(); ++k) {
      const std::string cp = item_path(sp + ".clips", k);
      EffectClip c;
      if (clips[k].is_string()) {
        c.clip = clips[k].get<std::string>();
      } else {
        check_object(clips[k], cp, {"clip", "weight", "hold"});
        c.clip = string(require(clips[k], "clip", cp), cp + ".clip");
        if (const Json* p = find(clips[k], "weight"))
          c.weight = static_cast<float>(number_at_least(*p, cp + ".weight", 0.0, true));
        if (const Json* p = find(clips[k], "hold")) c.hold = boolean(*p, cp + ".hold");
      }
      if (c.clip.empty()) fail(cp, "the clip name must not be empty");
      total += c.weight;
      st.clips.push_back(std::move(c));
    }
    if (!(total > 0.0)) fail(sp + ".clips", "every clip weight is 0");
    const Json* pose = find(arr[i], "pose");
    const Json* pose_in = find(arr[i], "pose_in");
    const Json* pose_out = find(arr[i], "pose_out");
    if (pose && (pose_in || pose_out))
      fail(sp + ".pose", "give either pose or pose_in/pose_out, not both");
    st.pose_in = st.pose_out = pose ? string(*pose, sp + ".pose") : "default";
    if (pose_in) st.pose_in = string(*pose_in, sp + ".pose_in");
    if (pose_out) st.pose_out = string(*pose_out, sp + ".pose_out");
    if (st.pose_in.empty() || st.pose_out.empty()) fail(sp + ".pose", "must not be empty");
    if (const Json* p = find(arr[i], "rest")) st.rest = boolean(*p, sp + ".rest");
    if (const Json* p = find(arr[i], "interruptible"))
      st.interruptible = boolean(*p, sp + ".interruptible");
    if (const Json* p = find(arr[i], "contagious")) st.contagious = boolean(*p, sp + ".contagious");
    if (const Json* p = find(arr[i], "additive")) st.additive = boolean(*p, sp + ".additive");
    if (st.rest && st.pose_in != st.pose_out)
      fail(sp + ".rest", "a rest state loops, so it must end in the pose it starts in (pose_in " +
                             in_quotes(st.pose_in) + ", pose_out " + in_quotes(st.pose_out) + ")");
    if (const Json* p = find(arr[i], "mask")) {
      const Json& mask = array(*p, sp + ".mask");
      if (!st.additive) fail(sp + ".mask", "only additive states have a skeletal mask");
      for (size_t k = 0; k < mask.size(); ++k)
        st.mask.push_back(string(mask[k], item_path(sp + ".mask", k)));
    }
    if (const Json* p = find(arr[i], "instances"))
      st.instances = static_cast<uint32_t>(integer(*p, sp + ".instances", 1, 1024));
    e.states.push_back(std::move(st));
  }
}

void read_animation_sharing(const Json& v, SceneEffects& e) {
  const std::string path = "effects.animation_sharing";
  e.animation_sharing = true;
  if (v.is_boolean()) {
    e.animation_sharing = v.get<bool>();
    return;
  }
  check_object(v, path, {"instances_per_state", "transitions", "additive_layers"});
  if (const Json* p = find(v, "instances_per_state"))
    e.instances_per_state =
        static_cast<uint32_t>(integer(*p, path + ".instances_per_state", 1, 1024));
  if (const Json* p = find(v, "transitions")) {
    const std::string tp = path + ".transitions";
    if (p->is_boolean()) {
      e.transitions = p->get<bool>();
    } else {
      check_object(*p, tp, {"time", "max", "join_window"});
      e.transitions = true;
      if (const Json* q = find(*p, "time"))
        e.transition_time = seconds_at_least(*q, tp + ".time", 0.0, false);
      if (const Json* q = find(*p, "max"))
        e.max_transitions = static_cast<uint32_t>(integer(*q, tp + ".max", 1, 65536));
      if (const Json* q = find(*p, "join_window"))
        e.transition_join_window = seconds_at_least(*q, tp + ".join_window", 0.0, true);
    }
  }
  if (const Json* p = find(v, "additive_layers"))
    e.additive_layers = boolean(*p, path + ".additive_layers");
}

void read_effects(const Json& v, size_t generator_count, ReadEffects& s) {
  const std::string path = kKey;
  check_object(v, path,
               {"type", "types", "lod", "texture_partition", "color_variety", "states",
                "animation_sharing", "spectators", "crossfade"});
  SceneEffects& e = s.e;
  e.declared = true;
  const Json* type = find(v, "type");
  const Json* types = find(v, "types");
  if (type && types) fail(path + ".types", "give either type or types, not both");
  if (type) {
    s.types.push_back(string(*type, path + ".type"));
    s.types_path = path + ".type";
  }
  if (types) {
    const Json& arr = array(*types, path + ".types");
    if (arr.empty()) fail(path + ".types", "needs at least one character type");
    for (size_t i = 0; i < arr.size(); ++i)
      s.types.push_back(string(arr[i], item_path(path + ".types", i)));
    s.types_path = path + ".types";
  }
  if (const Json* p = find(v, "lod")) e.lod = boolean(*p, path + ".lod");
  if (const Json* p = find(v, "texture_partition"))
    e.texture_partition = boolean(*p, path + ".texture_partition");
  if (const Json* p = find(v, "color_variety"))
    e.color_variety = boolean(*p, path + ".color_variety");
  if (const Json* p = find(v, "states")) read_states(*p, e);
  if (const Json* p = find(v, "animation_sharing")) read_animation_sharing(*p, e);
  if (const Json* p = find(v, "crossfade")) {
    const std::string cp = path + ".crossfade";
    if (p->is_boolean()) {
      e.crossfade = p->get<bool>();
    } else {
      check_object(*p, cp, {"time"});
      e.crossfade = true;
      if (const Json* q = find(*p, "time"))
        e.crossfade_time = seconds_at_least(*q, cp + ".time", 0.0, true);
    }
  }
  const bool uses_states = e.animation_sharing || find(v, "spectators") != nullptr;
  if (uses_states && e.states.empty())
    fail(path + ".states", "missing (animation_sharing and spectators need the states)");
  if (!uses_states && !e.states.empty())
    fail(path + ".states", "declared, but neither animation_sharing nor spectators uses them");
  if (const Json* p = find(v, "spectators")) read_spectators(*p, generator_count, e);
  if (e.crossfade && e.animation_sharing)
    fail(path + ".crossfade",
         "animation_sharing already blends the FSM's changes on the CPU (transitions); declare "
         "one of them");
  if (e.crossfade && !e.spectators)
    fail(path + ".crossfade", "nothing changes clips to fade (declare spectators)");
  for (size_t i = 0; i < e.states.size(); ++i)
    if (e.states[i].additive && !(e.animation_sharing && e.additive_layers))
      fail(item_path(path + ".states", i) + ".additive",
           "additive layers are not declared (effects.animation_sharing.additive_layers)");
}

// Names in the declaration that need the packs: the driven types, clips, mask joints.
void resolve_effects(ReadEffects raw, Scene& scene) {
  SceneEffects& e = raw.e;
  std::vector<uint8_t> driven(scene.types.size(), 0);
  if (raw.types.empty()) {
    if (scene.types.size() != 1 && !e.states.empty())
      fail("effects.type", "missing (required when the scene has several character types)");
    e.types = {0};
  } else {
    for (size_t k = 0; k < raw.types.size(); ++k) {
      const std::string tp = raw.types.size() > 1 || raw.types_path == "effects.types"
                                 ? item_path(raw.types_path, k)
                                 : raw.types_path;
      const int32_t t = scene.find_type(raw.types[k]);
      if (t < 0) fail(tp, "unknown character type \"" + raw.types[k] + "\"");
      if (driven[static_cast<size_t>(t)])
        fail(tp, "character type \"" + raw.types[k] + "\" is listed twice");
      driven[static_cast<size_t>(t)] = 1;
      e.types.push_back(static_cast<uint32_t>(t));
    }
  }
  e.type = e.types.front();
  std::fill(driven.begin(), driven.end(), 0);
  for (uint32_t t : e.types) driven[t] = 1;
  for (uint32_t t : e.types) {
    const runtime::CharacterType& type = scene.types[t];
    for (size_t i = 0; i < e.states.size(); ++i) {
      const std::string sp = item_path("effects.states", i);
      for (size_t k = 0; k < e.states[i].clips.size(); ++k) {
        const EffectClip& c = e.states[i].clips[k];
        const std::string cp = item_path(sp + ".clips", k);
        const int32_t index = type.pack.find_clip(c.clip);
        if (index < 0)
          fail(cp, "character type '" + type.name + "' has no clip \"" + c.clip +
                       "\" (its clips: " + type.pack.clip_names() + ")");
        const PackClip& clip = type.pack.contents().clips[static_cast<size_t>(index)];
        if (c.hold && clip.looping)
          fail(cp + ".hold",
               "clip \"" + c.clip + "\" loops; only a non-looping clip can hold its last frame");
        if (!(clip.duration > 0.0f) && e.spectators)
          fail(cp, "clip \"" + c.clip + "\" lasts " + show(clip.duration) +
                       " s; a behaviour state needs clips longer than 0 s");
      }
      for (size_t k = 0; k < e.states[i].mask.size(); ++k)
        if (type.pack.find_joint(e.states[i].mask[k]) < 0)
          fail(item_path(sp + ".mask", k),
               "character type '" + type.name + "' has no joint \"" + e.states[i].mask[k] + "\"");
    }
  }
  for (size_t t = 0; t < e.teams.size(); ++t)
    for (size_t k = 0; k < e.teams[t].generators.size(); ++k) {
      const runtime::InstanceRange& range = scene.generated[e.teams[t].generators[k]];
      for (uint32_t i = range.first; i < range.first + range.count; ++i)
        if (!driven[scene.instances.type[i]])
          fail(item_path(item_path("effects.spectators.teams", t) + ".generators", k),
               "generator " + std::to_string(e.teams[t].generators[k]) +
                   " makes instances of character type '" +
                   scene.types[scene.instances.type[i]].name +
                   "', which the effects do not drive (effects.type / effects.types)");
    }
  // Renderer-side effects turned off: applied to the data here, so every renderer (and the
  // CPU reference path) shows the same thing without an effect it was told not to use.
  if (!e.lod) scene.lod.mode = runtime::LodMode::kFull;
  if (!e.color_variety)
    for (size_t i = 0; i < scene.instances.size(); ++i) {
      scene.instances.color[3 * i] = 0.0f;
      scene.instances.color[3 * i + 1] = 1.0f;
      scene.instances.color[3 * i + 2] = 1.0f;
    }
  if (!e.texture_partition)
    std::fill(scene.instances.textures.begin(), scene.instances.textures.end(), 0u);
  scene.sections[kKey] = std::move(e);
}

}  // namespace

const SceneEffects* find_scene_effects(const Scene& scene) {
  const auto it = scene.sections.find(kKey);
  return it == scene.sections.end() ? nullptr : std::any_cast<SceneEffects>(&it->second);
}

SceneEffects& declare_scene_effects(Scene& scene) {
  std::any& slot = scene.sections[kKey];
  if (!std::any_cast<SceneEffects>(&slot)) {
    SceneEffects declared;
    declared.declared = true;
    slot = std::move(declared);
  }
  return *std::any_cast<SceneEffects>(&slot);
}

runtime::SceneSection scene_effects_section() {
  runtime::SceneSection section;
  section.key = kKey;
  section.read = [](const Json& value, const runtime::SceneOutline& outline, std::any& data) {
    ReadEffects read;
    const Status s = read_json("", StatusCode::kInvalidScene,
                               [&] { read_effects(value, outline.generators, read); });
    if (s.ok()) data = std::move(read);
    return s;
  };
  section.resolve = [](std::any data, Scene& scene) {
    ReadEffects* read = std::any_cast<ReadEffects>(&data);
    if (!read) return Status{};
    return read_json("", StatusCode::kInvalidScene,
                     [&] { resolve_effects(std::move(*read), scene); });
  };
  return section;
}

}  // namespace crowdbake::effects
