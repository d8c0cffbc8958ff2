// Runs the crowdbake executable as a user would and captures exit code, stdout, stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.h"

namespace crowdbake::test {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline CommandResult run_crowdbake(const std::vector<std::string>& args,
                                   const std::string& env = "") {
  static int counter = 0;
  const auto base =
      std::filesystem::temp_directory_path() /
      ("crowdbake-cli-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::string cmd = env + (env.empty() ? "" : " ") + shell_quote(CROWDBAKE_EXE);
  for (const std::string& a : args) cmd += " " + shell_quote(a);
  cmd += " >" + shell_quote(base.string() + ".out") + " 2>" + shell_quote(base.string() + ".err") +
         " </dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(base.string() + ".out");
  r.err = slurp(base.string() + ".err");
  std::filesystem::remove(base.string() + ".out");
  std::filesystem::remove(base.string() + ".err");
  return r;
}

// CROWDBAKE_REQUIRE_VULKAN=1 (CI): a command that finds no Vulkan device fails the test
// instead of skipping it.
inline bool vulkan_required() {
  const char* v = std::getenv("CROWDBAKE_REQUIRE_VULKAN");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

inline int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace crowdbake::test
