// write_pack() and stored_animation() for tests whose contents and options are valid: the
// result, or a test failure with the writer's message (and an empty result).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::test {

inline std::vector<uint8_t> pack_bytes(const PackContents& contents,
                                       const PackWriteOptions& options = {}) {
  std::vector<uint8_t> bytes;
  const Status s = write_pack(contents, options, bytes);
  if (!s) ADD_FAILURE() << "write_pack: " << s.message();
  return bytes;
}

inline std::vector<uint8_t> pack_bytes(const PackContents& contents,
                                       const PackWriteOptions& options,
                                       const StoredAnimation& animation) {
  std::vector<uint8_t> bytes;
  const Status s = write_pack(contents, options, animation, bytes);
  if (!s) ADD_FAILURE() << "write_pack: " << s.message();
  return bytes;
}

inline StoredAnimation stored_or_fail(const PackContents& contents,
                                      const PackWriteOptions& options) {
  StoredAnimation stored;
  const Status s = stored_animation(contents, options, stored);
  if (!s) ADD_FAILURE() << "stored_animation: " << s.message();
  return stored;
}

}  // namespace crowdbake::test
