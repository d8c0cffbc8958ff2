// libFuzzer target: pack bytes -> runtime Pack (open, then every part loaded) -> what the
// renderer prepares for upload (LoD and culling views, GPU vertex records, the coarsest
// and finest reconstructed levels). The fuzz build ignores checksum mismatches
// (FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION), so mutations reach the decoders and the
// runtime's own cross-checks. Property beyond "no crash, no leak, no huge allocation":
// an opened pack's counts agree with its contents.
#include <cstdint>
#include <cstdlib>

#include "crowdbake/runtime/byte_source.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/pack.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace crowdbake::runtime;
  Pack pack;
  if (!Pack::open(make_memory_source(std::vector<uint8_t>(data, data + size), "fuzz.crowdpack"),
                  pack, kPackAll))
    return 0;
  const crowdbake::PackContents& c = pack.contents();
  if (c.geometry.vertex_count() != pack.max_vertices()) std::abort();
  (void)make_lod_type(pack, LodSettings{});
  (void)make_type_bounds(pack);
  (void)gpu::make_gpu_vertices(c);
  for (const uint32_t n : {pack.min_vertices(), pack.max_vertices()}) {
    ReconstructJob job;
    job.mesh = progressive_view(c);
    job.vertices = n;
    std::vector<uint32_t> triangles(3 * size_t{lod_triangle_count(job.mesh, n)});
    job.output = triangles;
    if (!job.Run()) std::abort();  // the runtime opened it: every level reconstructs
  }
  pack.release(kPackGeometry);
  (void)pack.load(kPackGeometry);
  return 0;
}
