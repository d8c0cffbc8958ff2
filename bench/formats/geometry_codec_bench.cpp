// geometry_codec_bench: the numbers behind docs/pack-format.md "Geometry codecs: size,
// decode time, accuracy". For the generated spectator and every shared asset found, bakes
// the pack contents (real ProgressiveMesh order, regions, materials) and prints markdown:
//   1. GEOM bytes, encode time and decode throughput per codec (default and exact bits);
//   2. position error vs quantisation bits (max |error| / bind-pose bbox diagonal), with
//      GEOM bytes, for Draco and meshopt; normal error (degrees) and UV error vs bits.
// Usage: geometry_codec_bench [--quick] [--assets DIR] [--min-seconds S]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "crowdbake/base/clock.h"
#include "crowdbake/formats/pack.h"
#include "crowdbake/pipeline/bake.h"
#include "crowdbake/pipeline/error.h"
#include "crowdbake/pipeline/import.h"
#include "geometry_codec.h"
#include "pack_chunks.h"
#include "spectator_character.h"

namespace {

using namespace crowdbake;
using Clock = std::chrono::steady_clock;

struct Input {
  std::string name;
  std::string source;  // file, or "generated"
  uintmax_t source_bytes = 0;
  PackContents contents;
};

// Median of repeated runs of f, running for at least min_seconds in total.
template <typename F>
double median_seconds(F&& f, double min_seconds) {
  std::vector<double> times;
  const auto begin = Clock::now();
  do {
    const auto start = Clock::now();
    f();
    times.push_back(seconds_since(start));
  } while (seconds_since(begin) < min_seconds || times.size() < 5);
  std::nth_element(times.begin(), times.begin() + times.size() / 2, times.end());
  return times[times.size() / 2];
}

PackChunk geom_chunk(const std::vector<uint8_t>& bytes) {
  std::vector<PackChunk> chunks;
  read_pack_chunks(bytes.data(), bytes.size(), chunks);
  for (const PackChunk& c : chunks)
    if (c.tag == pack_format::kTagGeom) return c;
  std::fprintf(stderr, "no GEOM chunk\n");
  std::exit(2);
}

double diagonal(const PackGeometry& g) {
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < g.positions.size(); ++i)
    lo[i % 3] = std::min(lo[i % 3], g.positions[i]),
           hi[i % 3] = std::max(hi[i % 3], g.positions[i]);
  double d = 0;
  for (int k = 0; k < 3; ++k) d += double(hi[k] - lo[k]) * (hi[k] - lo[k]);
  return std::sqrt(d);
}

double max_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i)
    worst = std::max(worst, std::fabs(double(a[i]) - b[i]));
  return worst;
}

double max_angle_degrees(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (size_t i = 0; i + 2 < a.size() && i + 2 < b.size(); i += 3) {
    const double la =
        std::sqrt(double(a[i]) * a[i] + double(a[i + 1]) * a[i + 1] + double(a[i + 2]) * a[i + 2]);
    const double lb =
        std::sqrt(double(b[i]) * b[i] + double(b[i + 1]) * b[i + 1] + double(b[i + 2]) * b[i + 2]);
    if (la == 0 || lb == 0) continue;
    const double c =
        (double(a[i]) * b[i] + double(a[i + 1]) * b[i + 1] + double(a[i + 2]) * b[i + 2]) /
        (la * lb);
    worst = std::max(worst, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI);
  }
  return worst;
}

std::vector<uint8_t> packed(const PackContents& contents, const PackWriteOptions& options) {
  std::vector<uint8_t> bytes;
  throw_if_failed(write_pack(contents, options, bytes));
  return bytes;
}

// The contents a GEOM chunk decodes into: the predictive codec needs PROG read first.
PackContents with_progressive(const std::vector<uint8_t>& bytes) {
  std::vector<PackChunk> chunks;
  PackContents out;
  throw_if_failed(read_pack_chunks(bytes.data(), bytes.size(), chunks));
  for (const PackChunk& c : chunks)
    if (c.tag == pack_format::kTagProg)
      throw_if_failed(read_pack_chunk(c, bytes.data() + c.offset, out));
  return out;
}

PackGeometry decode_geom(const std::vector<uint8_t>& bytes) {
  const PackChunk geom = geom_chunk(bytes);
  PackContents out = with_progressive(bytes);
  const Status s = read_pack_chunk(geom, bytes.data() + geom.offset, out);
  if (!s) {
    std::fprintf(stderr, "decode failed: %s\n", s.message().c_str());
    std::exit(2);
  }
  return out.geometry;
}

void codec_table(const std::vector<Input>& inputs, double min_seconds) {
  std::printf("\n### Size and decode speed\n\n");
  std::printf(
      "GEOM chunk bytes (and bytes per vertex), encode time, and decode throughput of the GEOM "
      "chunk "
      "(read_pack_chunk: CRC-32C + codec + validation; median of repeated runs). MB/s counts "
      "decoded "
      "array bytes. Default bits are position 16 / normal 10 / uv 12; \"exact\" is 0 bits (floats "
      "kept).\n\n");
  std::printf(
      "| input | vertices | triangles | codec | bits | GEOM bytes | B/vertex | pack bytes | encode "
      "ms | "
      "decode ms | M vertices/s | MB/s "
      "|\n|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  struct Setting {
    PackWriteOptions options;
    const char* bits;
  };
  const Setting settings[] = {
      {{GeometryCodec::kPredictive, 16, 10, 12}, "default"},
      {{GeometryCodec::kPredictive, 0, 0, 0}, "exact"},
      {{GeometryCodec::kDraco, 16, 10, 12}, "default"},
      {{GeometryCodec::kDraco, 0, 0, 0}, "exact"},
      {{GeometryCodec::kMeshopt, 16, 10, 12}, "default"},
      {{GeometryCodec::kMeshopt, 0, 0, 0}, "exact"},
      {{GeometryCodec::kRaw, 0, 0, 0}, "exact"},
  };
  for (const Input& in : inputs) {
    const PackGeometry& g = in.contents.geometry;
    const pack_io::GeometryLayout layout = pack_io::make_geometry_layout(g, {GeometryCodec::kRaw});
    const double decoded_mb = layout.decoded_bytes() / 1e6;
    for (const Setting& s : settings) {
      std::vector<uint8_t> bytes;
      const double encode =
          median_seconds([&] { bytes = packed(in.contents, s.options); }, min_seconds / 4);
      const PackChunk geom = geom_chunk(bytes);
      PackContents out = with_progressive(bytes);
      const double decode = median_seconds(
          [&] {
            if (!read_pack_chunk(geom, bytes.data() + geom.offset, out)) std::exit(3);
          },
          min_seconds);
      std::printf("| %s | %u | %u | %s | %s | %llu | %.1f | %zu | %.2f | %.3f | %.1f | %.0f |\n",
                  in.name.c_str(), g.vertex_count(), g.triangle_count(),
                  geometry_codec_name(s.options.codec), s.bits,
                  static_cast<unsigned long long>(geom.size),
                  double(geom.size) / std::max(1u, g.vertex_count()), bytes.size(), encode * 1e3,
                  decode * 1e3, g.vertex_count() / decode / 1e6, decoded_mb / decode);
    }
  }
}

void accuracy_tables(const std::vector<Input>& inputs, bool quick) {
  std::printf("\n### Position error vs bits\n\n");
  std::printf(
      "Max position error over all vertices / bind-pose bbox diagonal, and GEOM bytes (normals 10 "
      "bits, "
      "UVs 12 bits). Bound: grid step / 2 = extent / (2 (2^bits - 1)).\n\n");
  std::vector<int> position_bits =
      quick ? std::vector<int>{11, 16} : std::vector<int>{8, 10, 11, 12, 14, 16, 18, 20};
  std::printf("| input | codec |");
  for (int b : position_bits) std::printf(" %d bits |", b);
  std::printf("\n|---|---|");
  for (size_t i = 0; i < position_bits.size(); ++i) std::printf("---:|");
  std::printf("\n");
  for (const Input& in : inputs) {
    const PackGeometry& g = in.contents.geometry;
    const double diag = std::max(diagonal(g), 1e-30);
    for (GeometryCodec codec :
         {GeometryCodec::kPredictive, GeometryCodec::kDraco, GeometryCodec::kMeshopt}) {
      std::printf("| %s | %s |", in.name.c_str(), geometry_codec_name(codec));
      for (int b : position_bits) {
        const std::vector<uint8_t> bytes = packed(in.contents, {codec, b, 10, 12});
        const PackGeometry out = decode_geom(bytes);
        std::printf(" %.2e (%llu B) |", max_abs_difference(g.positions, out.positions) / diag,
                    static_cast<unsigned long long>(geom_chunk(bytes).size));
      }
      std::printf("\n");
    }
  }

  std::printf("\n### Normal and UV error vs bits\n\n");
  std::printf(
      "Max angle between original and decoded normal (degrees), and max UV component error, "
      "positions at 16 bits.\n\n");
  const std::vector<int> bits = quick ? std::vector<int>{10} : std::vector<int>{6, 8, 10, 12, 14};
  std::printf("| input | codec | what |");
  for (int b : bits) std::printf(" %d bits |", b);
  std::printf("\n|---|---|---|");
  for (size_t i = 0; i < bits.size(); ++i) std::printf("---:|");
  std::printf("\n");
  for (const Input& in : inputs) {
    const PackGeometry& g = in.contents.geometry;
    if (g.normals.empty() && g.uvs.empty()) continue;
    for (GeometryCodec codec :
         {GeometryCodec::kPredictive, GeometryCodec::kDraco, GeometryCodec::kMeshopt}) {
      std::string normals = "| " + in.name + " | " + geometry_codec_name(codec) + " | normal ° |";
      std::string uvs = "| " + in.name + " | " + geometry_codec_name(codec) + " | uv |";
      for (int b : bits) {
        const PackGeometry out = decode_geom(packed(in.contents, {codec, 16, b, b}));
        char cell[64];
        std::snprintf(cell, sizeof cell, " %.3f |", max_angle_degrees(g.normals, out.normals));
        normals += cell;
        std::snprintf(cell, sizeof cell, " %.1e |", max_abs_difference(g.uvs, out.uvs));
        uvs += cell;
      }
      if (!g.normals.empty()) std::printf("%s\n", normals.c_str());
      if (!g.uvs.empty()) std::printf("%s\n", uvs.c_str());
    }
  }
}

void chunk_table(const std::vector<Input>& inputs) {
  std::printf("\n### Whole pack per chunk (default settings)\n\n| input | source bytes |");
  const char* tags[] = {"HEAD", "SKEL", "CLIP", "MATL", "BNDS", "PROG", "GEOM", "ANIM", "PART"};
  for (const char* t : tags) std::printf(" %s |", t);
  std::printf(" pack |\n|---|---:|");
  for (size_t i = 0; i < std::size(tags); ++i) std::printf("---:|");
  std::printf("---:|\n");
  for (const Input& in : inputs) {
    const std::vector<uint8_t> bytes = packed(in.contents, {});
    std::vector<PackChunk> chunks;
    read_pack_chunks(bytes.data(), bytes.size(), chunks);
    std::printf("| %s | %ju |", in.name.c_str(), in.source_bytes);
    for (const PackChunk& c : chunks)
      std::printf(" %llu |", static_cast<unsigned long long>(c.size));
    std::printf(" %zu |\n", bytes.size());
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string assets = CROWDBAKE_BENCH_ASSETS;
  double min_seconds = 0.3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--quick")
      quick = true, min_seconds = 0.01;
    else if (a == "--assets" && i + 1 < argc)
      assets = argv[++i];
    else if (a == "--min-seconds" && i + 1 < argc)
      min_seconds = std::atof(argv[++i]);
    else {
      std::fprintf(stderr,
                   "usage: geometry_codec_bench [--quick] [--assets DIR] [--min-seconds S]\n");
      return 2;
    }
  }
  BakeSettings settings;
  settings.simplify.samples = quick ? 4 : 16;  // note: order realism matters here, not LoD quality

  std::vector<Input> inputs;
  const auto add = [&](const std::string& name, const std::string& source, uintmax_t bytes,
                       const SkinnedAsset& asset) {
    const auto start = Clock::now();
    BakeReport report;
    PackContents contents;
    throw_if_failed(build_pack(asset, settings, report, contents));
    inputs.push_back({name, source, bytes, std::move(contents)});
    std::fprintf(stderr, "baked %s in %.1f s\n", name.c_str(), seconds_since(start));
  };
  for (int detail : quick ? std::vector<int>{0} : std::vector<int>{1, 2}) {
    samples::SpectatorOptions options;
    options.detail = detail;
    add("spectator d" + std::to_string(detail), "generated", 0,
        samples::make_spectator_character(options));
  }
  const char* files[] = {"Fox/Fox.glb", "CesiumMan/CesiumMan.glb",
                         "Quaternius_MaleCasual/Male_Casual.fbx", "Quaternius_Zombie/Zombie.fbx",
                         "Quaternius_Rat/Rat.fbx"};
  for (const char* f : files) {
    if (quick && std::string(f) != "CesiumMan/CesiumMan.glb") continue;
    const std::filesystem::path path = std::filesystem::path(assets) / f;
    if (!std::filesystem::exists(path)) {
      std::fprintf(stderr, "skipping %s (not found)\n", path.string().c_str());
      continue;
    }
    SkinnedAsset asset;
    throw_if_failed(import_asset(path.string(), {}, asset));
    add(path.stem().string(), path.string(), std::filesystem::file_size(path), asset);
  }
  std::printf("## geometry_codec_bench%s\n", quick ? " (--quick)" : "");
  codec_table(inputs, min_seconds);
  accuracy_tables(inputs, quick);
  chunk_table(inputs);
  return 0;
}
