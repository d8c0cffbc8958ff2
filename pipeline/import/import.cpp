#include "crowdbake/pipeline/import.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

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

}  // namespace

SkinnedAsset import_asset(const std::string& path, const ImportOptions& options) {
  check_input_file(path, "a character file (.gltf, .glb, .fbx, ...)");
  ImporterKind kind = options.importer;
  if (kind == ImporterKind::kAuto) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    kind = ext == ".gltf" || ext == ".glb" || looks_like_gltf(path) ? ImporterKind::kGltf
                                                                    : ImporterKind::kAssimp;
  }
  SkinnedAsset asset =
      kind == ImporterKind::kGltf ? import_gltf(path, options) : import_assimp(path, options);
  validate_asset(asset);
  return asset;
}

}  // namespace crowdbake
