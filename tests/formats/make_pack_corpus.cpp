// Writes the pack reader fuzzer's seed corpus: small real packs (the hand-built test
// character at a few sizes, every codec, quantised and exact, without optional
// attributes, empty) into the folder given as the only argument.
#include <cstdio>
#include <fstream>
#include <string>

#include "crowdbake/formats/pack.h"
#include "pack_test_contents.h"

namespace {

using namespace crowdbake;

// The test character with a short animation (6 rows) so seeds stay a few KB.
PackContents small_contents(uint32_t grid, uint32_t seed) {
  PackContents c = test::make_test_contents(grid, seed);
  uint32_t row = 0;
  for (uint32_t k = 0; k < c.clips.size(); ++k) {
    PackClip& clip = c.clips[k];
    clip.first_row = row;
    clip.frame_count = k + 1;
    clip.duration = k / clip.fps;
    if (!clip.root_motion.empty()) clip.root_motion.resize(3 * clip.frame_count);
    row += clip.frame_count;
  }
  c.animation.rows = row;
  c.animation.data.resize(size_t{row} * c.animation.joints * 3 * 16);
  c.partition.width = 16;
  c.partition.height = 8;
  c.partition.texels.resize(16 * 8);
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_pack_corpus OUTPUT_DIR\n");
    return 2;
  }
  const std::string dir = argv[1];
  int written = 0;
  const auto emit = [&](const std::string& name, const PackContents& c, const PackWriteOptions& o) {
    const std::vector<uint8_t> bytes = write_pack(c, o);
    std::ofstream(dir + "/" + name + ".crowdpack", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    ++written;
  };
  for (GeometryCodec codec :
       {GeometryCodec::kDraco, GeometryCodec::kMeshopt, GeometryCodec::kRaw}) {
    const std::string codec_name = geometry_codec_name(codec);
    for (uint32_t grid : {2u, 3u, 5u}) {
      emit(codec_name + "_grid" + std::to_string(grid), small_contents(grid, grid), {codec});
      emit(codec_name + "_grid" + std::to_string(grid) + "_exact", small_contents(grid, grid + 10),
           {codec, 0, 0, 0});
    }
    PackContents bare = small_contents(3, 30);
    bare.geometry.normals.clear();
    bare.geometry.uvs.clear();
    bare.geometry.regions.clear();
    bare.geometry.triangle_material.clear();
    emit(codec_name + "_bare", bare, {codec});
    PackContents points = small_contents(3, 31);
    points.geometry.triangles.clear();
    points.geometry.triangle_material.clear();
    points.progressive = {};
    emit(codec_name + "_points", points, {codec, 8, 4, 6});
    emit(codec_name + "_empty", PackContents{}, {codec});
  }
  std::printf("wrote %d seed packs to %s\n", written, dir.c_str());
  return 0;
}
