// Error reporting for the crowd behaviour and placement modules: a code plus a message that
// names the offending item ("state 'cheer' clip 'cheer_2': duration -1 s must be > 0").
// Builders return a Status and leave their output untouched on error.
#pragma once

#include <string>
#include <utility>

namespace crowdbake::crowd {

class Status {
 public:
  enum class Code {
    kOk = 0,
    kInvalidFsm,       // a behaviour FSM definition breaks a rule (behaviour_fsm.h)
    kInvalidScene,     // a crowd, team, event or seat-grid definition breaks a rule
    kInvalidArgument,  // a placement or job parameter is out of range
    kInfeasible,       // valid input that cannot be satisfied (region too small, ...)
    kInternal,         // a geometry backend failed (message says how)
  };

  Status() = default;
  static Status Ok() { return Status(); }
  static Status Error(Code code, std::string message) { return Status(code, std::move(message)); }

  bool ok() const { return code_ == Code::kOk; }
  Code code() const { return code_; }
  const std::string& message() const { return message_; }

 private:
  Status(Code code, std::string message) : code_(code), message_(std::move(message)) {}
  Code code_ = Code::kOk;
  std::string message_;
};

}  // namespace crowdbake::crowd
