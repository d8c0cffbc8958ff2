// ByteSource: where a pack's bytes come from. The runtime reads a pack in pieces — the
// header and chunk table first, then each chunk when it is needed — through this interface,
// so a game can stream from its own archive or network layer, and tests can count reads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

class ByteSource {
 public:
  virtual ~ByteSource() = default;

  // Total bytes available (the file size).
  virtual uint64_t size() const = 0;

  // Reads exactly `count` bytes starting at `offset` into `out`.
  // Returns kIoError (message names the source) when fewer bytes could be read; the caller
  // guarantees offset + count <= size().
  // out: at least `count` writable bytes
  virtual Status read(uint64_t offset, size_t count, uint8_t* out) = 0;

  // What to call this source in messages (a file path, "memory", ...).
  virtual const std::string& name() const = 0;
};

// Opens a file for positioned reads (POSIX pread). The size is taken once, at open.
// note: reads rather than mmap, so a file truncated or replaced while a game runs gives a
// clean kIoError instead of SIGBUS.
// Returns kIoError naming the path and the system's reason when the file cannot be opened.
// path: file to read
// out: receives the source on success; untouched on failure
Status open_file_source(const std::string& path, std::unique_ptr<ByteSource>& out);

// A source over bytes held in memory (a pack embedded in the executable, a download).
// bytes: the whole file, moved in
// name: what messages call it
std::unique_ptr<ByteSource> make_memory_source(std::vector<uint8_t> bytes,
                                               std::string name = "memory");

}  // namespace crowdbake::runtime
