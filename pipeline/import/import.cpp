#include "crowdbake/pipeline/import.h"

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "asset/asset_wire.h"
#include "crowdbake/pipeline/child_process.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/input_file.h"

namespace crowdbake {
namespace {

// glTF is recognised by content, not by extension: a .glb starts with "glTF", a .gltf
// is JSON whose top level holds an "asset" object.
bool looks_like_gltf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[4096] = {};
  in.read(head, sizeof(head));
  const std::streamsize n = in.gcount();
  if (n >= 4 && std::memcmp(head, "glTF", 4) == 0) return true;
  std::streamsize i = 0;
  while (i < n && std::strchr(" \t\r\n", head[i]) && head[i] != 0) ++i;
  if (i < 3 && n >= 3 && static_cast<unsigned char>(head[0]) == 0xEF) i = 3;  // UTF-8 BOM
  return i < n && head[i] == '{' &&
         std::string(head, static_cast<size_t>(n)).find("\"asset\"") != std::string::npos;
}

const char* importer_name(ImporterKind kind) {
  return kind == ImporterKind::kGltf ? "the glTF importer (tinygltf)" : "the Assimp importer";
}

// While an import runs in this process, its chatter on stdout (some Assimp importers
// print there) goes to stderr: stdout may be a JSON document.
class StdoutToStderr {
 public:
  StdoutToStderr() {
    std::cout.flush();
    std::fflush(stdout);
    saved_ = dup(1);
    if (saved_ >= 0) dup2(2, 1);
  }
  ~StdoutToStderr() {
    std::cout.flush();
    std::fflush(stdout);
    if (saved_ >= 0) dup2(saved_, 1), close(saved_);
  }
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  int saved_ = -1;
};

SkinnedAsset import_here(const std::string& path, ImporterKind kind, const ImportOptions& options) {
  const StdoutToStderr quiet;
  SkinnedAsset asset;
  throw_if_failed(kind == ImporterKind::kGltf ? import_gltf(path, options, asset)
                                              : import_assimp(path, options, asset));
  return asset;
}

std::string number(double value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

SkinnedAsset import_isolated(const std::string& path, ImporterKind kind,
                             const ImportOptions& options) {
  ChildLimits limits;
  limits.timeout_seconds = options.limits.timeout_seconds;
  limits.memory_mib = options.limits.memory_mib;
  const ChildOutcome child =
      run_in_child([&] { return encode_asset(import_here(path, kind, options)); }, limits);
  const std::string importer = importer_name(kind);
  const std::string reexport =
      "; the file is malformed or uses something the importer mishandles: re-export it "
      "(glTF 2.0 .glb reads best)";
  SkinnedAsset asset;
  switch (child.end) {
    case ChildOutcome::End::kReturned:
      if (decode_asset(child.payload, asset)) return asset;
      throw input_error(path, importer + " sent back a damaged result; report this as a bug");
    case ChildOutcome::End::kThrew:
      throw Error(
          child.error_kind == 0 ? Error::Kind::kInput : static_cast<Error::Kind>(child.error_kind),
          child.error_kind == 0 ? path : child.error_file, child.payload);
    case ChildOutcome::End::kOutOfMemory:
      throw input_error(path, importer + " needed more than the import memory limit (" +
                                  number(static_cast<double>(options.limits.memory_mib)) +
                                  " MiB); if the file really is that large, raise it with "
                                  "--import-memory MIB (0: no limit)");
    case ChildOutcome::End::kSignal:
      // note: an allocation failure inside code that cannot throw ends in abort(), and the
      // kernel's OOM killer sends SIGKILL, so those two may be the memory limit.
      throw input_error(
          path, importer + " crashed (" + describe_signal(child.signal) + ") reading this file" +
                    (child.signal == SIGABRT || child.signal == SIGKILL
                         ? " (if it ran out of memory, the limit is " +
                               number(static_cast<double>(options.limits.memory_mib)) +
                               " MiB: --import-memory MIB)"
                         : "") +
                    reexport);
    case ChildOutcome::End::kTimeout:
      throw input_error(path, importer + " did not finish within the import time limit (" +
                                  number(options.limits.timeout_seconds) +
                                  " s); if the file really is that large, raise it with "
                                  "--import-timeout SECONDS (0: no limit)" +
                                  reexport);
    case ChildOutcome::End::kLost:
      break;
  }
  throw input_error(path, importer + " ended without a result" + reexport);
}

}  // namespace

static SkinnedAsset import_or_throw(const std::string& path, const ImportOptions& options) {
  throw_if_failed(check_input_file(path, "a character file (.gltf, .glb, .fbx, ...)"));
  ImporterKind kind = options.importer;
  if (kind == ImporterKind::kAuto) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    kind = ext == ".gltf" || ext == ".glb" || looks_like_gltf(path) ? ImporterKind::kGltf
                                                                    : ImporterKind::kAssimp;
  }
  SkinnedAsset asset = options.limits.isolate ? import_isolated(path, kind, options)
                                              : import_here(path, kind, options);
  throw_if_failed(validate_asset(asset));
  if (options.weld) asset.stats.vertices_welded = static_cast<int>(weld_identical_vertices(asset));
  return asset;
}

Status import_asset(const std::string& path, const ImportOptions& options, SkinnedAsset& out) {
  return capture_errors([&] { out = import_or_throw(path, options); });
}

}  // namespace crowdbake
