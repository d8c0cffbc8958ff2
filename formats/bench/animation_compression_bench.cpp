// ANIM v2's texel compression measured on packs: texel bytes, stored bytes, ratio, and the
// milliseconds to compress (bake side) and to expand (load side), medians of 5 runs.
//   animation_compression_bench PACK...   (prints a markdown table; docs/pack-sizes.md)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "pack_compression.h"

namespace {

double median_ms(const std::vector<double>& runs) {
  std::vector<double> sorted = runs;
  std::sort(sorted.begin(), sorted.end());
  return sorted[sorted.size() / 2];
}

template <class F>
double time_ms(F&& f) {
  std::vector<double> runs;
  for (int k = 0; k < 5; ++k) {
    const auto start = std::chrono::steady_clock::now();
    f();
    runs.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  return median_ms(runs);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace crowdbake;
  if (argc < 2) {
    std::fprintf(stderr, "usage: animation_compression_bench PACK...\n");
    return 2;
  }
  std::printf(
      "| pack | joints | rows | texel bytes | stored bytes | ratio | compress ms | expand ms |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int a = 1; a < argc; ++a) {
    std::ifstream file(argv[a], std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), {});
    PackContents pack;
    const PackStatus s = read_pack(bytes.data(), bytes.size(), pack);
    if (!s.ok) {
      std::fprintf(stderr, "%s: %s\n", argv[a], s.message.c_str());
      return 1;
    }
    const AnimationTexture& t = pack.animation;
    std::vector<uint8_t> frame;
    const double compress = time_ms([&] { frame = pack_io::compress_animation_texels(t); });
    AnimationTexture out = t;
    bool ok = true;
    const double expand = time_ms([&] {
      ok = ok && pack_io::decompress_animation_texels(frame.data(), frame.size(), out, nullptr);
    });
    if (!ok || out.data != t.data) {
      std::fprintf(stderr, "%s: the texels did not come back\n", argv[a]);
      return 1;
    }
    std::string name = argv[a];
    name = name.substr(name.find_last_of('/') + 1);
    std::printf("| %s | %u | %u | %zu | %zu | %.1f | %.1f | %.2f |\n", name.c_str(), t.joints,
                t.rows, t.data.size(), frame.size(),
                frame.empty() ? 0.0 : static_cast<double>(t.data.size()) / frame.size(), compress,
                expand);
  }
  return 0;
}
