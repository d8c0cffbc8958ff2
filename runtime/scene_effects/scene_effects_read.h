// What the "effects" section reader's files share (scene_effects_section.cpp reads the
// section, spectators_section.cpp its "spectators" key). Problems are thrown as
// json_reader::JsonError and become a Status where the reader is called.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/base/json_reader.h"
#include "crowdbake/runtime/effects/scene_effects.h"

namespace crowdbake::effects {

inline std::string in_quotes(const std::string& name) { return "\"" + name + "\""; }

// Index of the state with this name, or -1.
int32_t find_state(const std::vector<EffectState>& states, const std::string& name);

// The index of a declared state, or an "unknown state" error at `path`.
uint32_t known_state(const SceneEffects& e, const std::string& name, const std::string& path);

inline float seconds_at_least(const json_reader::Json& v, const std::string& path, double lo,
                              bool inclusive) {
  return static_cast<float>(json_reader::number_at_least(v, path, lo, inclusive));
}

// "effects.spectators"; e.states are already read.
void read_spectators(const json_reader::Json& v, size_t generator_count, SceneEffects& e);

}  // namespace crowdbake::effects
