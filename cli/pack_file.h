// A .crowdpack read from disk for `inspect` and `diff` (formats' PackFile: the chunk table as
// stored plus the decoded, validated contents). Loading throws crowdbake::Error (kind kInput) with
// the reader's message, so every bad pack is one line "error: <file>: <what; what to do>".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::cli {

using crowdbake::PackFile;

// True when the file starts with the pack magic (pack_format::kMagic) or is named
// *.crowdpack (so a damaged pack gets the pack reader's error, not an importer's).
bool looks_like_pack(const std::string& path);

// Reads and validates the whole pack (formats' read_pack_file).
PackFile load_pack_file(const std::string& path);

}  // namespace crowdbake::cli
