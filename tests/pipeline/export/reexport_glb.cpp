// reexport_glb IN OUT: imports a character with crowdbake's importers and writes it back
// with export_glb, for the Khronos validator CTests on the shared characters.
#include <cstdio>
#include <exception>

#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "pipeline_calls.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s INPUT OUTPUT.glb\n", argv[0]);
    return 2;
  }
  try {
    crowdbake::test::export_glb_or_throw(crowdbake::test::import_or_throw(argv[1]), argv[2]);
  } catch (const crowdbake::Error& e) {
    std::fprintf(stderr, "error: %s\n", crowdbake::status_of(e).message().c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s: %s\n", argv[1], e.what());
    return 1;
  }
  return 0;
}
