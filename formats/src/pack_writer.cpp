// write_pack(): validate, encode each chunk, then lay the file out as header, chunk table
// and 16-byte-aligned chunks in the fixed order of pack_format.h (docs/pack-format.md).
#include <cmath>
#include <deque>
#include <future>
#include <stdexcept>
#include <string>
#include <utility>

#include "animation_bounded_codec.h"
#include "byte_writer.h"
#include "crc32c.h"
#include "crowdbake/formats/pack.h"
#include "pack_chunks.h"
#include "pack_compression.h"
#include "pack_validate.h"

namespace crowdbake {
namespace {

using namespace pack_format;
using pack_io::ByteWriter;

struct EncodedChunk {
  uint32_t tag;
  uint32_t version;
  ByteWriter payload;
};

void check_options(const PackWriteOptions& o) {
  const auto bits_ok = [](int bits, int min) {
    return bits == 0 || (bits >= min && bits <= static_cast<int>(kMaxQuantizationBits));
  };
  if (static_cast<uint32_t>(o.codec) > static_cast<uint32_t>(GeometryCodec::kPredictive))
    throw std::invalid_argument("write_pack: unknown geometry codec " +
                                std::to_string(static_cast<uint32_t>(o.codec)));
  if (o.compression != PackCompression::kNone && o.compression != PackCompression::kZstd)
    throw std::invalid_argument("write_pack: unknown animation compression " +
                                std::to_string(static_cast<uint32_t>(o.compression)));
  if (!bits_ok(o.position_bits, 1) || !bits_ok(o.uv_bits, 1) || !bits_ok(o.normal_bits, 2))
    throw std::invalid_argument(
        "write_pack: quantisation bits must be 0 or 1.." + std::to_string(kMaxQuantizationBits) +
        " (normals 2.." + std::to_string(kMaxQuantizationBits) + "), got position " +
        std::to_string(o.position_bits) + ", normal " + std::to_string(o.normal_bits) + ", uv " +
        std::to_string(o.uv_bits));
  if (o.weight_bits < 0 || o.weight_bits > static_cast<int>(kMaxWeightBits))
    throw std::invalid_argument("write_pack: weight bits must be 0 (exact floats) or 1.." +
                                std::to_string(kMaxWeightBits) + ", got " +
                                std::to_string(o.weight_bits));
  if (!(o.animation_error >= 0.0 && o.animation_error <= 1.0))
    throw std::invalid_argument(
        "write_pack: animation error must be 0 (lossless) to 1 (of the bind-pose diagonal), got " +
        std::to_string(o.animation_error));
}

void check_contents(const PackContents& contents) {
  const Status valid = validate_pack_contents(contents);
  if (!valid) throw std::invalid_argument("write_pack: invalid pack contents: " + valid.message());
}

double bind_diagonal(const PackBounds& bounds) {
  double diagonal2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = double{bounds.max[k]} - double{bounds.min[k]};
    diagonal2 += d * d;
  }
  return std::sqrt(diagonal2);
}

// What write_pack() stores of the animation: the error-bounded coding when the options ask
// for it, the contents allow it and it is smaller than the lossless texels; otherwise the
// texels losslessly (with the reason when a bound was asked for).
struct AnimationChoice {
  bool bounded = false;
  pack_io::BoundedAnimationCode code;
  std::vector<uint8_t> frame;  // the bounded stream as one zstd frame
  std::string reason;
  bool lossless_smaller = false;
};

AnimationChoice choose_animation(const PackContents& contents, const PackWriteOptions& options) {
  AnimationChoice choice;
  if (options.animation_error <= 0.0) return choice;
  if (options.compression != PackCompression::kZstd) {
    choice.reason = "pack compression is none";
    return choice;
  }
  std::vector<uint32_t> clip_starts;
  for (const PackClip& clip : contents.clips) clip_starts.push_back(clip.first_row);
  if (!pack_io::encode_bounded_animation(contents.animation, contents.joints, clip_starts,
                                         contents.geometry,
                                         options.animation_error * bind_diagonal(contents.bounds),
                                         choice.code, &choice.reason, options.threads))
    return choice;
  choice.frame = pack_io::zstd_frame(choice.code.stream);
  const size_t lossless = pack_io::compress_animation_texels(contents.animation).size();
  if (choice.frame.size() >= lossless) {
    choice.reason = "the lossless texels are smaller (" + std::to_string(lossless) + " bytes, " +
                    std::to_string(choice.frame.size()) + " coded)";
    choice.lossless_smaller = true;
    return choice;
  }
  choice.bounded = true;
  return choice;
}

// The writer's checks and codecs throw inside this file; callers get a Status (kInvalidArgument
// for contents or options that break a rule, kInternal when a codec fails).
template <typename Write>
Status guarded(Write&& write) {
  try {
    write();
    return {};
  } catch (const std::invalid_argument& e) {
    return {StatusCode::kInvalidArgument, e.what()};
  } catch (const std::bad_alloc&) {
    return {StatusCode::kOutOfMemory, "write_pack: out of memory"};
  } catch (const std::exception& e) {
    return {StatusCode::kInternal, e.what()};
  }
}

StoredAnimation store_animation(const PackContents& contents, const PackWriteOptions& options) {
  check_options(options);
  check_contents(contents);
  StoredAnimation stored;
  AnimationChoice choice = choose_animation(contents, options);
  stored.lossless_reason = choice.reason;
  stored.lossless_smaller = choice.lossless_smaller;
  if (!choice.bounded) {
    stored.texture = contents.animation;
    return stored;
  }
  stored.texture = std::move(choice.code.texture);
  stored.error_bounded = true;
  stored.bound = options.animation_error * bind_diagonal(contents.bounds);
  stored.max_error = choice.code.max_error;
  stored.mean_error = choice.code.mean_error;
  stored.coded = std::move(choice.frame);
  return stored;
}

}  // namespace

Status stored_animation(const PackContents& contents, const PackWriteOptions& options,
                        StoredAnimation& out) {
  return guarded([&] { out = store_animation(contents, options); });
}

const char* alpha_mode_name(AlphaMode mode) {
  switch (mode) {
    case AlphaMode::kOpaque:
      return "opaque";
    case AlphaMode::kMask:
      return "mask";
    case AlphaMode::kBlend:
      return "blend";
  }
  return "unknown";
}

const char* geometry_codec_name(GeometryCodec codec) {
  switch (codec) {
    case GeometryCodec::kDraco:
      return "draco";
    case GeometryCodec::kMeshopt:
      return "meshopt";
    case GeometryCodec::kRaw:
      return "raw";
    case GeometryCodec::kPredictive:
      return "predictive";
  }
  return "unknown";
}

Status validate_pack_contents(const PackContents& c) {
  using namespace pack_io;
  const std::pair<const char*, std::string> checks[] = {
      {"HEAD", c.name.size() > kMaxStringBytes || c.settings_json.size() > kMaxSettingsBytes
                   ? "name or settings_json exceeds its length limit"
                   : ""},
      {"SKEL", check_joints(c.joints)},
      {"CLIP", check_clips(c.clips)},
      {"MATL", check_materials(c.materials)},
      {"BNDS", check_bounds(c.bounds)},
      {"PROG", check_progressive(c.progressive)},
      {"LERR", check_level_errors(c.level_errors)},
      {"GEOM", check_geometry(c.geometry)},
      {"ANIM", check_animation(c.animation)},
      {"PART", check_partition(c.partition)},
      {"IMGS", check_images(c.images)},
      {"IMPS", check_impostor(c.impostor)},
  };
  for (const auto& [tag, problem] : checks)
    if (!problem.empty())
      return {StatusCode::kInvalidPack, std::string("chunk ") + tag + ": " + problem};
  const std::string cross = check_cross_references(c);
  if (!cross.empty()) return {StatusCode::kInvalidPack, "chunk " + cross};
  return {};
}

namespace {

std::vector<uint8_t> write_pack_chunks(const PackContents& contents,
                                       const PackWriteOptions& options,
                                       const std::vector<uint8_t>* bounded_animation) {
  // note: a deque, so that a chunk stays where it is while later ones are added.
  std::deque<EncodedChunk> chunks;
  const auto add = [&](uint32_t tag, uint32_t version) -> ByteWriter& {
    chunks.push_back({tag, version, ByteWriter{}});
    return chunks.back().payload;
  };
  const bool compressed = options.compression == PackCompression::kZstd;
  const auto frames_of = [&chunks](size_t begin, size_t end) {
    std::vector<std::vector<uint8_t>> frames(end - begin);
    for (size_t i = begin; i < end; ++i)
      if (pack_io::is_wrappable(chunks[i].tag))
        frames[i - begin] = pack_io::zstd_frame(chunks[i].payload.bytes());
    return frames;
  };
  pack_io::encode_head(contents, add(kTagHead, kHeadVersion));
  pack_io::encode_skeleton(contents.joints, add(kTagSkel, kSkelVersion));
  pack_io::encode_clips(contents.clips, add(kTagClip, kClipVersion));
  pack_io::encode_materials(contents.materials, add(kTagMatl, kMatlVersion));
  if (pack_io::has_material_extras(contents.materials))
    pack_io::encode_material_extras(contents.materials, add(kTagMatx, kMatxVersion));
  if (!contents.variant_images.empty())
    pack_io::encode_variant_images(contents.variant_images, add(kTagVars, kVarsVersion));
  pack_io::encode_bounds(contents.bounds, add(kTagBnds, kBndsVersion));
  pack_io::encode_progressive(contents.progressive, add(kTagProg, kProgVersion));
  if (!contents.level_errors.vertices.empty())
    pack_io::encode_level_errors(contents.level_errors, add(kTagLerr, kLerrVersion));
  // note: the frames of the chunks so far (PROG: a hero mesh's collapse records, as slow at
  // zstd's level 19 as the geometry's longest part) are made beside the geometry's coding.
  const size_t early = chunks.size();
  std::future<std::vector<std::vector<uint8_t>>> early_frames;
  if (compressed)
    early_frames = std::async(options.threads == 1 ? std::launch::deferred : std::launch::async,
                              frames_of, size_t{0}, early);
  pack_io::encode_geometry(contents.geometry, contents.progressive, options,
                           add(kTagGeom, pack_io::geometry_version(contents.geometry, options)));
  if (!contents.vertex_colors.empty())
    pack_io::encode_vertex_colors(contents.vertex_colors, add(kTagVcol, kVcolVersion));
  pack_io::encode_animation(contents.animation, compressed, bounded_animation,
                            add(kTagAnim, bounded_animation ? kAnimVersion
                                          : compressed      ? kAnimLosslessVersion
                                                            : kAnimOldestVersion));
  pack_io::encode_partition(contents.partition, add(kTagPart, kPartVersion));
  if (!contents.images.empty())
    pack_io::encode_images(contents.images, add(kTagImgs, kImgsVersion));
  if (!contents.impostor.empty())
    pack_io::encode_impostor(contents.impostor, add(kTagImps, kImpsVersion));
  if (compressed) {
    std::vector<std::vector<uint8_t>> frames = early_frames.get();
    for (std::vector<uint8_t>& frame : frames_of(early, chunks.size()))
      frames.push_back(std::move(frame));
    for (size_t i = 0; i < chunks.size(); ++i) {
      EncodedChunk& chunk = chunks[i];
      std::vector<uint8_t>& frame = frames[i];
      if (pack_io::is_wrappable(chunk.tag)) {
        // note: version 2 of these chunks is the version-1 payload as one zstd frame; a
        // payload that compresses beyond what readers expand (§6) stays at version 1.
        if (chunk.payload.bytes().size() >
            kWrappedExpansionSlack + kWrappedExpansionRatio * frame.size())
          continue;
        chunk.payload.bytes() = std::move(frame);
        chunk.version = kWrappedVersion;
      }
    }
  }

  ByteWriter file;
  file.raw(kMagic.data(), kMagic.size());
  file.u16(kPackVersionMajor);
  file.u16(kPackVersionMinor);
  file.u32(0);  // flags
  file.u32(static_cast<uint32_t>(chunks.size()));
  file.u32(0);            // reserved
  file.u64(kHeaderSize);  // chunk table right after the header
  const size_t file_size_at = file.size();
  file.u64(0);  // file size, patched below
  const size_t checksum_at = file.size();
  file.u32(0);  // header + table checksum, patched below
  file.u32(0);  // reserved
  const size_t table_at = file.size();
  for (size_t i = 0; i < chunks.size(); ++i) {
    for (int k = 0; k < 4; ++k) file.u64(0);  // patched below
  }
  for (size_t i = 0; i < chunks.size(); ++i) {
    file.zero_pad(kAlignment);
    const std::vector<uint8_t>& payload = chunks[i].payload.bytes();
    const size_t entry = table_at + i * kChunkEntrySize;
    file.patch_u32(entry + 0, chunks[i].tag);
    file.patch_u32(entry + 4, chunks[i].version);
    file.patch_u64(entry + 8, file.size());
    file.patch_u64(entry + 16, payload.size());
    file.patch_u32(entry + 24, pack_io::crc32c(payload.data(), payload.size()));
    file.patch_u32(entry + 28, 0);
    file.raw(payload.data(), payload.size());
  }
  file.zero_pad(kAlignment);
  file.patch_u64(file_size_at, file.size());
  uint32_t crc = pack_io::crc32c(file.bytes().data(), checksum_at);
  crc = pack_io::crc32c(file.bytes().data() + table_at, chunks.size() * kChunkEntrySize, crc);
  file.patch_u32(checksum_at, crc);
  return std::move(file.bytes());
}

}  // namespace

Status write_pack(const PackContents& contents, const PackWriteOptions& options,
                  std::vector<uint8_t>& out) {
  return guarded([&] {
    check_options(options);
    check_contents(contents);
    const AnimationChoice animation = choose_animation(contents, options);
    out = write_pack_chunks(contents, options, animation.bounded ? &animation.frame : nullptr);
  });
}

Status write_pack(const PackContents& contents, const PackWriteOptions& options,
                  const StoredAnimation& animation, std::vector<uint8_t>& out) {
  return guarded([&] {
    check_options(options);
    check_contents(contents);
    if (animation.error_bounded &&
        (animation.coded.empty() || animation.texture.rows != contents.animation.rows ||
         animation.texture.joints != contents.animation.joints))
      throw std::invalid_argument(
          "write_pack: the stored animation does not fit the contents; pass what "
          "stored_animation() returned for them");
    out =
        write_pack_chunks(contents, options, animation.error_bounded ? &animation.coded : nullptr);
  });
}

}  // namespace crowdbake
