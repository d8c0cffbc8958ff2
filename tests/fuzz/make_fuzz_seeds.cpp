// Writes generated seed inputs for a fuzz target into a folder (scripts/fuzz.sh runs it
// before each fuzzing session; the hand-written seeds are committed in tests/fuzz/seeds/):
// - packs (pack_reader, pack_load): the hand-built test character at a few sizes, every
//   codec, quantised and exact, without optional attributes, without triangles, empty;
// - gltf_import: the two-joint test character as .gltf (embedded buffer) and as a .glb
//   written by crowdbake's exporter.
//   make_fuzz_seeds packs|gltf OUTPUT_DIR
#include <cstdio>
#include <fstream>
#include <string>

#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/gltf_export.h"
#include "crowdbake/pipeline/import.h"
#include "gltf_test_builder.h"
#include "pipeline_calls.h"
#include "small_pack.h"

namespace {

using namespace crowdbake;

int write_packs(const std::string& dir) {
  int written = 0;
  const auto emit = [&](const std::string& name, const PackContents& c, const PackWriteOptions& o) {
    std::vector<uint8_t> bytes;
    if (const Status s = write_pack(c, o, bytes); !s) {
      std::fprintf(stderr, "make_fuzz_seeds: %s: %s\n", name.c_str(), s.message().c_str());
      return;
    }
    std::ofstream(dir + "/" + name + ".crowdpack", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()),
               static_cast<std::streamsize>(bytes.size()));
    ++written;
  };
  for (GeometryCodec codec : {GeometryCodec::kPredictive, GeometryCodec::kDraco,
                              GeometryCodec::kMeshopt, GeometryCodec::kRaw}) {
    const std::string codec_name = geometry_codec_name(codec);
    for (uint32_t grid : {2u, 3u, 5u}) {
      emit(codec_name + "_grid" + std::to_string(grid), fuzz::small_pack_contents(grid, grid),
           {codec});
      emit(codec_name + "_grid" + std::to_string(grid) + "_exact",
           fuzz::small_pack_contents(grid, grid + 10), {codec, 0, 0, 0, 0});
    }
    PackContents bare = fuzz::small_pack_contents(3, 30);
    bare.geometry.normals.clear();
    bare.geometry.uvs.clear();
    bare.geometry.regions.clear();
    bare.geometry.triangle_material.clear();
    emit(codec_name + "_bare", bare, {codec});
    PackContents points = fuzz::small_pack_contents(3, 31);
    points.geometry.triangles.clear();
    points.geometry.triangle_material.clear();
    points.progressive = {};
    emit(codec_name + "_points", points, {codec, 8, 4, 6});
    emit(codec_name + "_empty", PackContents{}, {codec});
  }
  // ANIM v3: the animation coded within a bound (docs/pack-format.md 3.8).
  PackWriteOptions bounded;
  bounded.animation_error = 1e-2;
  emit("bounded_animation", fuzz::bounded_animation_contents(50), bounded);
  return written;
}

int write_gltf(const std::string& dir) {
  const std::string gltf = test::two_bone_character().write(dir + "/two_bone.gltf").string();
  ImportOptions options;
  options.limits.isolate = false;
  test::export_glb_or_throw(test::import_or_throw(gltf, options), dir + "/two_bone.glb");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string kind = argc == 3 ? argv[1] : "";
  if (kind != "packs" && kind != "gltf") {
    std::fprintf(stderr, "usage: make_fuzz_seeds packs|gltf OUTPUT_DIR\n");
    return 2;
  }
  const int written = kind == "packs" ? write_packs(argv[2]) : write_gltf(argv[2]);
  std::printf("wrote %d seeds to %s\n", written, argv[2]);
  return 0;
}
