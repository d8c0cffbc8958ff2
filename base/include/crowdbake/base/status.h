// Status: how every crowdbake library that does not throw reports a failure (the runtime, its
// crowd and effect modules). A code for programs, a message for people that names the file,
// the key or the item and the problem, e.g. "scene.json: lod.budget: must be at least 1, got 0".
// One type for all of them: a crowd module's failure passes up through the runtime unchanged.
#pragma once

#include <cstddef>
#include <iterator>
#include <string>
#include <utility>

namespace crowdbake {

enum class StatusCode {
  kOk = 0,
  kIoError,          // a file could not be opened or read
  kInvalidPack,      // pack bytes are corrupt, truncated or inconsistent (untrusted data)
  kInvalidScene,     // a scene, crowd, team, event or seat grid is malformed or names nothing
  kInvalidArgument,  // the caller passed an out-of-range value or inconsistent arrays
  kNotLoaded,        // the call needs a pack part (geometry, animation, ...) not loaded yet
  kOutOfMemory,      // an allocation failed while loading
  kInvalidFsm,       // a behaviour state machine breaks a rule (crowd/behaviour_fsm.h)
  kInfeasible,       // valid input that cannot be satisfied (a region too small, ...)
  kInternal,         // a backend failed or a rule the code keeps broke (the message says how)
  kInvalidInput,     // an input file (a character, a bake config, ...) breaks a rule
  kOutputError,      // an output file could not be written
  kLast = kOutputError,
};

// Short lower-case name of a code: "ok", "io error", "invalid pack", ...
inline const char* status_code_name(StatusCode code) {
  // In StatusCode's order.
  constexpr const char* kNames[] = {"ok",
                                    "io error",
                                    "invalid pack",
                                    "invalid scene",
                                    "invalid argument",
                                    "not loaded",
                                    "out of memory",
                                    "invalid behaviour fsm",
                                    "infeasible",
                                    "internal error",
                                    "invalid input",
                                    "output error"};
  static_assert(std::size(kNames) == static_cast<size_t>(StatusCode::kLast) + 1);
  const auto i = static_cast<size_t>(code);
  return i < std::size(kNames) ? kNames[i] : "unknown";
}

class Status {
 public:
  Status() = default;  // ok
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == StatusCode::kOk; }
  explicit operator bool() const { return ok(); }
  StatusCode code() const { return code_; }
  // Empty when ok.
  const std::string& message() const { return message_; }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

}  // namespace crowdbake
