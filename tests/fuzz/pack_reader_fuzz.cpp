// libFuzzer target for read_pack (scripts/fuzz-pack-reader.sh builds and runs it with
// clang, ASAN and UBSAN; seeds come from make_pack_corpus). Property beyond "no crash,
// no leak, no huge allocation": whatever the reader accepts obeys every validity rule
// and can be written again.
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "crowdbake/formats/pack.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  crowdbake::PackContents contents;
  if (!crowdbake::read_pack(data, size, contents)) return 0;
  if (!crowdbake::validate_pack_contents(contents)) std::abort();
  // note: what the reader accepts, the writer writes again.
  std::vector<uint8_t> bytes;
  if (!crowdbake::write_pack(contents, {crowdbake::GeometryCodec::kRaw, 0, 0, 0}, bytes))
    std::abort();
  return 0;
}
