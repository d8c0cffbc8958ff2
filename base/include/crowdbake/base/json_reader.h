// The one way crowdbake reads its JSON files (scene.json and its effect sections, bake
// configs, pose ranges): every value is checked where it is read, and a problem names the key
// path it was found at, in one style:
//
//   <file>: <key path>: <problem>      e.g. "scene.json: lod.budget: must be >= 1, got 0"
//
// A reader calls these checks while it walks a document; the first problem ends the walk with
// a JsonError, which read_json() (or the reader's own entry point) turns into a Status. The
// exception never leaves the library that reads: these functions are inline, so every library
// catches what it throws (no exceptions across library boundaries, base/status.h).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "crowdbake/base/status.h"

namespace crowdbake::json_reader {

using Json = nlohmann::json;

// The first problem of a walk: where ("lod.budget"; "top level" for the document itself; ""
// when `problem` is a whole message already, e.g. a nested reader's Status) and what. A
// problem of the data has no code of its own: read_json() gives it the reader's (kInvalidScene
// for scenes, kInvalidArgument for configs). A reader that finds another kind of problem
// while walking (a file a key names cannot be read) says which.
struct JsonError {
  std::string path;
  std::string problem;
  std::optional<StatusCode> code;

  // "<key path>: <problem>".
  std::string message() const { return path.empty() ? problem : path + ": " + problem; }
};

[[noreturn]] inline void fail(const std::string& path, const std::string& problem,
                              std::optional<StatusCode> code = std::nullopt) {
  throw JsonError{path, problem, code};
}

inline std::string key_path(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}
inline std::string item_path(const std::string& path, size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

// A number as a message shows it (7 significant digits: values are mostly stored as float).
inline std::string show(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.7g", v);
  return buffer;
}

// What was found instead of what a key wants: "string \"abc\"", "number 3", "an array of 2".
inline std::string describe(const Json& v) {
  if (v.is_string()) {
    std::string text = v.get<std::string>();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return "string \"" + text + "\"";
  }
  if (v.is_number()) return "number " + v.dump();
  if (v.is_boolean()) return std::string("boolean ") + (v.get<bool>() ? "true" : "false");
  if (v.is_array()) return "an array of " + std::to_string(v.size());
  if (v.is_object()) return "an object";
  return v.type_name();
}

inline const Json* find(const Json& object, const char* key) {
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// An object whose keys are all in `keys` ("unknown key (expected one of: a, b)" otherwise;
// `hint` follows the list).
template <typename Keys>
void check_keys(const Json& v, const std::string& path, const Keys& keys,
                const std::string& hint = "") {
  if (!v.is_object())
    fail(path.empty() ? "top level" : path, "expected an object, got " + describe(v));
  for (const auto& item : v.items()) {
    bool known = false;
    for (const auto& k : keys) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const auto& k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      fail(key_path(path, item.key()), "unknown key (expected one of: " + list + hint + ")");
    }
  }
}

inline void check_object(const Json& v, const std::string& path,
                         std::initializer_list<const char*> keys) {
  check_keys(v, path, keys);
}

inline const Json& require(const Json& object, const char* key, const std::string& path) {
  const Json* v = find(object, key);
  if (!v) fail(key_path(path, key), "missing (required)");
  return *v;
}

// A finite number within ±1e30 (values end up as float; beyond that they would be infinite).
inline double number(const Json& v, const std::string& path) {
  if (!v.is_number()) fail(path, "expected a number, got " + describe(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(path, "must be a finite number");
  if (std::fabs(d) > 1e30) fail(path, "must be within ±1e30, got " + show(d));
  return d;
}

inline double number_at_least(const Json& v, const std::string& path, double lo, bool inclusive) {
  const double d = number(v, path);
  if (inclusive ? d < lo : d <= lo)
    fail(path,
         std::string("must be ") + (inclusive ? ">= " : "> ") + show(lo) + ", got " + show(d));
  return d;
}

// A number in [lo, hi].
inline double number_in(const Json& v, const std::string& path, double lo, double hi) {
  const double d = number(v, path);
  if (!(d >= lo && d <= hi))
    fail(path, "must be in [" + show(lo) + ", " + show(hi) + "], got " + show(d));
  return d;
}

inline int64_t integer(const Json& v, const std::string& path, int64_t lo, int64_t hi) {
  if (!v.is_number_integer()) fail(path, "expected an integer, got " + describe(v));
  if (v.is_number_unsigned()) {
    const uint64_t u = v.get<uint64_t>();
    if (lo > 0 && u < static_cast<uint64_t>(lo))
      fail(path, "must be at least " + std::to_string(lo) + ", got " + v.dump());
    if (u > static_cast<uint64_t>(hi))
      fail(path, "must be at most " + std::to_string(hi) + ", got " + v.dump());
    return static_cast<int64_t>(u);
  }
  const int64_t i = v.get<int64_t>();
  if (i < lo) fail(path, "must be at least " + std::to_string(lo) + ", got " + std::to_string(i));
  if (i > hi) fail(path, "must be at most " + std::to_string(hi) + ", got " + std::to_string(i));
  return i;
}

inline std::string string(const Json& v, const std::string& path) {
  if (!v.is_string()) fail(path, "expected a string, got " + describe(v));
  return v.get<std::string>();
}

inline bool boolean(const Json& v, const std::string& path) {
  if (!v.is_boolean()) fail(path, "expected true or false, got " + describe(v));
  return v.get<bool>();
}

inline const Json& array(const Json& v, const std::string& path) {
  if (!v.is_array()) fail(path, "expected an array, got " + describe(v));
  return v;
}

template <size_t N>
std::array<float, N> numbers(const Json& v, const std::string& path) {
  if (!v.is_array() || v.size() != N)
    fail(path, "expected an array of " + std::to_string(N) + " numbers, got " + describe(v));
  std::array<float, N> out{};
  for (size_t i = 0; i < N; ++i) out[i] = static_cast<float>(number(v[i], item_path(path, i)));
  return out;
}

// One of `names` (a list of {name, value} pairs), by name.
template <typename T, size_t N>
T choice(const Json& v, const std::string& path,
         const std::array<std::pair<const char*, T>, N>& names) {
  if (v.is_string())
    for (const auto& [name, value] : names)
      if (v.get<std::string>() == name) return value;
  std::string list;
  for (const auto& [name, value] : names) list += std::string(list.empty() ? "" : ", ") + name;
  fail(path, "expected one of " + list + ", got " + describe(v));
}

// Parses JSON text; a syntax error becomes "<name>: not valid JSON: <where and what>".
inline Status parse_json(std::string_view text, const std::string& name, StatusCode code,
                         Json& out) {
  try {
    out = Json::parse(text.begin(), text.end());
    return {};
  } catch (const Json::exception& e) {
    // note: nlohmann prefixes "[json.exception.parse_error.101] "; the rest says where.
    std::string what = e.what();
    const size_t bracket = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
      what = what.substr(bracket + 2);
    return {code, name + ": not valid JSON: " + what};
  }
}

// Runs a reader's walk; its first problem becomes "<name>: <key path>: <problem>" with `code`
// (or the code the problem names); "<key path>: <problem>" when name is empty.
template <typename Walk>
Status read_json(const std::string& name, StatusCode code, Walk&& walk) {
  try {
    walk();
    return {};
  } catch (const JsonError& e) {
    return {e.code.value_or(code), name.empty() ? e.message() : name + ": " + e.message()};
  }
}

}  // namespace crowdbake::json_reader
