// Writes the exporter's corner-case characters (edge_case_asset.h) as edge_small.glb and
// edge_large.glb into the given folder, for the Khronos validator CTests.
#include <cstdio>
#include <exception>
#include <string>

#include "crowdbake/pipeline/gltf_export.h"
#include "edge_case_asset.h"
#include "pipeline_calls.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::string dir = argv[1];
    crowdbake::test::export_glb_or_throw(crowdbake::test::edge_case_asset(false),
                                         dir + "/edge_small.glb");
    crowdbake::test::export_glb_or_throw(crowdbake::test::edge_case_asset(true),
                                         dir + "/edge_large.glb");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
