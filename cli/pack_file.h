// A .crowdpack read from disk for `inspect` and `diff`: the chunk table as stored plus the
// decoded, validated contents. Loading throws crowdbake::Error (kind kInput) with the
// reader's message, so every bad pack is one line "error: <file>: <what; what to do>".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::cli {

struct PackFile {
  std::string path;
  uint64_t bytes = 0;  // file size
  uint16_t version_major = 0, version_minor = 0;
  std::vector<PackChunk> chunks;  // file order, unknown tags included
  PackContents contents;
};

// True when the file starts with the pack magic (pack_format::kMagic) or is named
// *.crowdpack (so a damaged pack gets the pack reader's error, not an importer's).
bool looks_like_pack(const std::string& path);

// Reads and validates the whole pack (read_pack_chunks + read_pack).
PackFile load_pack_file(const std::string& path);

// "head", "upper body", "trousers", "unused"; "unknown" otherwise.
const char* region_name(uint8_t region);

// The bind-pose bounding box diagonal (bounds.min..max); 0 for an empty box.
double bbox_diagonal(const PackContents& contents);

}  // namespace crowdbake::cli
