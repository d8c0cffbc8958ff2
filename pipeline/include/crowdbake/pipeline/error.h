// How the pipeline reports failures. Its public functions return a crowdbake::Status whose
// message names the file, the problem and what to do ("<file>: <message>"); no exception
// crosses the library's boundary.
//
// Error is the exception the pipeline's own code throws inside (deep in an importer or a
// bake, where unwinding is the simplest way out); every public function catches it with
// capture_errors() and returns it as a Status. Programs that report through exceptions too
// (the CLI, the samples) turn a failed Status back into an Error with throw_if_failed().
#pragma once

#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "crowdbake/base/status.h"

namespace crowdbake {

class Error : public std::runtime_error {
 public:
  // The CLI's exit code per kind: a bad input file, bad options, an unwritable output.
  enum class Kind { kInput = 1, kUsage = 2, kOutput = 3 };

  Error(Kind kind, std::string file, const std::string& message)
      : std::runtime_error(message), kind_(kind), file_(std::move(file)) {}

  Kind kind() const { return kind_; }
  const std::string& file() const { return file_; }
  int exit_code() const { return static_cast<int>(kind_); }

 private:
  Kind kind_;
  std::string file_;
};

inline Error input_error(const std::string& file, const std::string& message) {
  return Error(Error::Kind::kInput, file, message);
}

// kInput → kInvalidInput, kUsage → kInvalidArgument, kOutput → kOutputError; the message is
// "<file>: <message>" (the message alone when no file is named).
inline Status status_of(const Error& e) {
  static constexpr StatusCode kCodes[] = {StatusCode::kInvalidInput, StatusCode::kInvalidArgument,
                                          StatusCode::kOutputError};
  const std::string message = e.file().empty() ? e.what() : e.file() + ": " + e.what();
  return Status(kCodes[static_cast<int>(e.kind()) - 1], message);
}

// Runs `body`, which reports failures by throwing, and returns its outcome as a Status: an
// Error as status_of() says, running out of memory as kOutOfMemory, any other exception as
// kInternal (a bug: the message asks for a report).
template <typename Body>
Status capture_errors(Body&& body) noexcept {
  try {
    body();
    return Status();
  } catch (const Error& e) {
    return status_of(e);
  } catch (const std::bad_alloc&) {
    return Status(StatusCode::kOutOfMemory, "out of memory");
  } catch (const std::exception& e) {
    return Status(StatusCode::kInternal, std::string("internal error: ") + e.what() +
                                             " (please report this with the input file)");
  }
}

// For programs that report through exceptions: throws the Error a failed Status stands for
// (its message already names the file, so the Error names none), or std::bad_alloc for
// kOutOfMemory, so that a child process still reports running out of memory as such.
inline void throw_if_failed(const Status& s) {
  if (s.ok()) return;
  if (s.code() == StatusCode::kOutOfMemory) throw std::bad_alloc();
  const Error::Kind kind = s.code() == StatusCode::kInvalidArgument ? Error::Kind::kUsage
                           : s.code() == StatusCode::kOutputError   ? Error::Kind::kOutput
                                                                    : Error::Kind::kInput;
  throw Error(kind, "", s.message());
}

}  // namespace crowdbake
