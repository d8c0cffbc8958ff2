// Measures what a pack's images cost (not a test: run by hand, numbers go to docs/materials.md):
// per image its stored (encoded) bytes, its decoded bytes and decode time, then the whole
// make_gpu_materials (decode, resample, mip chain) and the texture bytes it uploads. Times are
// the fastest of 7 runs (the machine is shared).
//   gpu_material_bench PACK...
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_image.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"

using namespace crowdbake;

namespace {

template <typename F>
double fastest_ms(F&& f) {
  double best = 1e30;
  for (int run = 0; run < 7; ++run) {
    const auto start = std::chrono::steady_clock::now();
    f();
    best = std::min(
        best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: gpu_material_bench PACK...\n");
    return 2;
  }
  std::printf("%-24s %-24s %9s %7s %11s %10s | %9s %11s\n", "pack", "image", "size", "type",
              "stored B", "decode ms", "load ms", "texture B");
  for (int a = 1; a < argc; ++a) {
    std::ifstream in(argv[a], std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                     std::istreambuf_iterator<char>()};
    PackContents pack;
    if (const Status s = read_pack(bytes.data(), bytes.size(), pack); !s.ok()) {
      std::fprintf(stderr, "%s: %s\n", argv[a], s.message().c_str());
      return 1;
    }
    for (const PackImage& image : pack.images) {
      std::vector<uint8_t> rgba;
      std::string why;
      const double ms = fastest_ms([&] { decode_pack_image(image, rgba, why); });
      std::printf("%-24s %-24s %4ux%-4u %7s %11zu %10.2f |\n", pack.name.c_str(),
                  image.name.substr(0, 24).c_str(), image.width, image.height,
                  image.mime_type.substr(6).c_str(), image.data.size(), ms);
    }
    runtime::gpu::GpuMaterials materials;
    const double load = fastest_ms([&] { runtime::gpu::make_gpu_materials(pack, materials); });
    std::printf("%-24s %-24s %9s %7s %11s %10s | %9.2f %11zu\n", pack.name.c_str(), "(all)", "", "",
                "", "", load, materials.rgba.size());
  }
  return 0;
}
