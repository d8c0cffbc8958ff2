// The animation texture's storage measured on packs baked losslessly (`animation.max_error`
// 0): texel bytes; the lossless coding (ANIM v2): stored bytes, ratio, milliseconds to compress
// (bake side) and to expand (load side); the error-bounded coding (ANIM v3) at --max-error
// (default 1e-4 of the diagonal): the ANIM chunk's bytes and ratio, the milliseconds to code
// (with its verification) and to read the chunk back. Times are medians of 5 runs.
//   animation_compression_bench [--max-error E] PACK...   (a markdown table; docs/pack-sizes.md)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/formats/pack_format.h"
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
  PackWriteOptions bounded;
  bounded.animation_error = 1e-4;
  int first = 1;
  if (argc > 2 && !std::strcmp(argv[1], "--max-error")) {
    bounded.animation_error = std::atof(argv[2]);
    first = 3;
  }
  if (argc <= first) {
    std::fprintf(stderr, "usage: animation_compression_bench [--max-error E] PACK...\n");
    return 2;
  }
  std::printf(
      "| pack | joints | rows | texel bytes | lossless bytes | ratio | compress ms | expand ms | "
      "within %g: ANIM bytes | ratio | code ms | read ms |\n",
      bounded.animation_error);
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (int a = first; a < argc; ++a) {
    std::ifstream file(argv[a], std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)), {});
    PackContents pack;
    const Status s = read_pack(bytes.data(), bytes.size(), pack);
    if (!s.ok()) {
      std::fprintf(stderr, "%s: %s\n", argv[a], s.message().c_str());
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
    StoredAnimation stored;
    Status coding;
    const double code = time_ms([&] { coding = stored_animation(pack, bounded, stored); });
    std::vector<uint8_t> coded;
    if (coding) coding = write_pack(pack, bounded, coded);
    if (!coding) {
      std::fprintf(stderr, "%s: %s\n", argv[a], coding.message().c_str());
      return 1;
    }
    std::vector<PackChunk> chunks;
    read_pack_chunks(coded.data(), coded.size(), chunks);
    PackChunk anim;
    for (const PackChunk& c : chunks)
      if (c.tag == pack_format::kTagAnim) anim = c;
    PackContents back;
    const double read =
        time_ms([&] { ok = ok && read_pack_chunk(anim, coded.data() + anim.offset, back).ok(); });
    if (!ok || back.animation.data != stored.texture.data) {
      std::fprintf(stderr, "%s: the coded texels did not come back as stored_animation says\n",
                   argv[a]);
      return 1;
    }
    std::string name = argv[a];
    name = name.substr(name.find_last_of('/') + 1);
    const auto ratio = [&](size_t n) { return n ? static_cast<double>(t.data.size()) / n : 0.0; };
    std::printf("| %s | %u | %u | %zu | %zu | %.1f | %.1f | %.2f | %llu%s | %.1f | %.1f | %.2f |\n",
                name.c_str(), t.joints, t.rows, t.data.size(), frame.size(), ratio(frame.size()),
                compress, expand, static_cast<unsigned long long>(anim.size),
                stored.error_bounded ? "" : " (lossless)", ratio(anim.size), code, read);
  }
  return 0;
}
