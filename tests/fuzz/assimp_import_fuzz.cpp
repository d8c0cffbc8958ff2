// libFuzzer target: bytes -> SkinnedAsset through Assimp, isolated as every import is
// (pipeline/import/import.cpp). Assimp's own memory errors end its child process and come
// back as crowdbake::Error; what must hold is that this process never crashes, hangs or
// leaks, whatever the child does, and that crowdbake's conversion of an aiScene is sound.
// The first byte picks the file extension (the format Assimp tries).
#include <pthread.h>
#include <signal.h>

#include <cstdint>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "fuzz_input_file.h"

// Weak: present under the sanitizers, absent in the seed-replay build.
extern "C" __attribute__((weak)) void __sanitizer_set_death_callback(void (*callback)(void));

namespace {

const char* const kExtensions[] = {".fbx", ".dae",  ".obj",      ".x",   ".md5mesh", ".off", ".ply",
                                   ".smd", ".b3d",  ".ms3d",     ".3ds", ".stl",     ".md2", ".mdl",
                                   ".iqm", ".ogex", ".mesh.xml", ".bvh", ".csm",     ".ndo"};

// In the import's child, a crash must end the child by its signal as in production, not
// run libFuzzer's crash handler (which would report the parent's input as a crash of
// crowdbake).
void child_dies_plainly() {
  if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(nullptr);
  for (int s : {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL}) signal(s, SIG_DFL);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pthread_atfork(nullptr, nullptr, child_dies_plainly);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake;
  if (size == 0) return 0;
  const size_t n = sizeof kExtensions / sizeof kExtensions[0];
  const std::string path =
      fuzz::write_input(std::string("in") + kExtensions[data[0] % n], data + 1, size - 1);
  ImportOptions options;
  options.importer = ImporterKind::kAssimp;
  options.limits.timeout_seconds = 1.0;
  SkinnedAsset asset;
  if (const Status s = import_asset(path, options, asset); !s.ok()) fuzz::refused(s);
  return 0;
}
