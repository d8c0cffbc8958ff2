// The crowdbake subcommands. main.cpp parses flags into these structs; each run_*
// returns the process exit code and throws crowdbake::Error for bad input.
#pragma once

#include <string>

#include "crowdbake/pipeline/import.h"

namespace crowdbake::cli {

struct InspectSettings {
  std::string input;
  bool json = false;
  ImportOptions import;
};

int run_inspect(const InspectSettings& settings);

}  // namespace crowdbake::cli
