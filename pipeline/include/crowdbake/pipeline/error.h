// Errors the pipeline reports to its callers. The CLI turns each into one line,
// "error: <file>: <message>", and an exit code per kind.
#pragma once

#include <stdexcept>
#include <string>

namespace crowdbake {

class Error : public std::runtime_error {
 public:
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

}  // namespace crowdbake
