// libFuzzer target: bake configuration JSON (docs/bake-config.md) -> BakeSettings.
// Property beyond "no crash, no leak, no huge allocation": an accepted config prints as
// the canonical JSON a pack stores.
#include <cstdint>
#include <cstdlib>

#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "fuzz_input_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake;
  const std::string path = fuzz::write_input("bake.json", data, size);
  BakeSettings settings;
  const Status s = read_bake_config(path, settings);
  if (s.ok() && bake_settings_json(settings).empty()) std::abort();
  if (!s.ok()) fuzz::refused(s);
  return 0;
}
