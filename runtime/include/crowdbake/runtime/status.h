// Status: how every crowdbake_runtime call that can fail reports it.
//
// No function of the runtime's public API throws: failures come back as a Status with a code
// (for programs) and a message (for people: it names the file, the key or the chunk and the
// problem, e.g. "scene.json: lod.budget: must be at least 1, got 0"). Out-of-memory inside a
// loader is caught and reported as kOutOfMemory. Jobs (*_job.h) return bool instead: their
// only failures are caller mistakes that Validate() lists.
#pragma once

#include <string>
#include <utility>

namespace crowdbake::runtime {

enum class StatusCode {
  kOk = 0,
  kIoError,          // a file could not be opened or read
  kInvalidPack,      // pack bytes are corrupt, truncated or inconsistent (untrusted data)
  kInvalidScene,     // scene.json is malformed or names something that does not exist
  kInvalidArgument,  // the caller passed an out-of-range index or inconsistent arrays
  kNotLoaded,        // the call needs a pack part (geometry, animation, ...) not loaded yet
  kOutOfMemory,      // an allocation failed while loading
};

// Short lower-case name of a code: "ok", "io error", "invalid pack", ...
const char* status_code_name(StatusCode code);

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

}  // namespace crowdbake::runtime
