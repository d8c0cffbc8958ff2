// read_pack_chunks / read_pack_chunk / read_pack: the bytes are hostile. Every field goes
// through a bounds-checked ByteReader; every count is checked against the bytes left
// before anything is allocated; every failure is a Status naming the chunk and field.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "byte_reader.h"
#include "crc32c.h"
#include "crowdbake/formats/pack.h"
#include "pack_chunks.h"
#include "pack_compression.h"
#include "pack_validate.h"

namespace crowdbake {
namespace {

using namespace pack_format;
using pack_io::ByteReader;

Status error(std::string message) { return {StatusCode::kInvalidPack, std::move(message)}; }

// note: fuzzing builds ignore checksum mismatches so the fuzzer reaches the chunk
// decoders (the usual FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION convention).
bool checksum_matches(uint32_t stored, uint32_t computed) {
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
  (void)stored, (void)computed;
  return true;
#else
  return stored == computed;
#endif
}

std::string hex(uint32_t v) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "0x%08x", v);
  return buffer;
}

// A chunk's payload decoder, into its part of the contents (HEAD also fills the counts).
using ChunkDecoder = bool (*)(ByteReader& in, uint32_t version, PackContents& out,
                              PackCounts& counts);

// Adapters from the pack_io decoders to ChunkDecoder: `Decode` fills the contents' `Part`.
template <auto Part, auto Decode>
bool decode_part(ByteReader& in, uint32_t, PackContents& out, PackCounts&) {
  return Decode(in, out.*Part);
}
template <auto Part, auto Decode>
bool decode_versioned_part(ByteReader& in, uint32_t version, PackContents& out, PackCounts&) {
  return Decode(in, version, out.*Part);
}
// GEOM's predictive codec decodes against PROG, which writers store before it.
bool decode_geometry(ByteReader& in, uint32_t version, PackContents& out, PackCounts&) {
  return pack_io::decode_geometry(in, version, out.progressive, out.geometry);
}
bool decode_head(ByteReader& in, uint32_t, PackContents& out, PackCounts& counts) {
  return pack_io::decode_head(in, out, counts);
}

struct KnownChunk {
  uint32_t tag;
  uint32_t version;  // the newest this build reads
  bool required;
  uint32_t oldest;  // the oldest this build reads; 0: only `version`
  ChunkDecoder decode;
};
using C = PackContents;
constexpr KnownChunk kKnownChunks[] = {
    {kTagHead, kHeadVersion, true, 0, decode_head},
    {kTagSkel, kWrappedVersion, true, kSkelVersion,
     decode_part<&C::joints, pack_io::decode_skeleton>},
    {kTagClip, kWrappedVersion, true, kClipVersion, decode_part<&C::clips, pack_io::decode_clips>},
    {kTagMatl, kMatlVersion, true, 0, decode_part<&C::materials, pack_io::decode_materials>},
    {kTagMatx, kMatxVersion, false, 0, decode_part<&C::materials, pack_io::decode_material_extras>},
    {kTagBnds, kBndsVersion, true, 0, decode_part<&C::bounds, pack_io::decode_bounds>},
    {kTagProg, kWrappedVersion, true, kProgVersion,
     decode_part<&C::progressive, pack_io::decode_progressive>},
    {kTagLerr, kLerrVersion, false, 0, decode_part<&C::level_errors, pack_io::decode_level_errors>},
    {kTagGeom, kGeomVersion, true, kGeomOldestVersion, decode_geometry},
    {kTagAnim, kAnimVersion, true, kAnimOldestVersion,
     decode_versioned_part<&C::animation, pack_io::decode_animation>},
    {kTagPart, kWrappedVersion, true, kPartVersion,
     decode_part<&C::partition, pack_io::decode_partition>},
    {kTagImgs, kImgsVersion, false, 0, decode_part<&C::images, pack_io::decode_images>},
    {kTagVcol, kWrappedVersion, false, kVcolVersion,
     decode_part<&C::vertex_colors, pack_io::decode_vertex_colors>},
    {kTagVars, kVarsVersion, false, 0,
     decode_part<&C::variant_images, pack_io::decode_variant_images>},
    {kTagImps, kWrappedVersion, false, kImpsVersion,
     decode_part<&C::impostor, pack_io::decode_impostor>},
};

const KnownChunk* find_known(uint32_t tag) {
  for (const KnownChunk& k : kKnownChunks)
    if (k.tag == tag) return &k;
  return nullptr;
}

// The header's own rules; checksum is the stored header/table checksum (the table is needed to
// verify it).
Status parse_header(const uint8_t* data, size_t size, PackHeader& h, uint32_t& checksum) {
  if (data == nullptr && size != 0) return error("no data");
  if (size < kMagic.size() || std::memcmp(data, kMagic.data(), kMagic.size()) != 0)
    return error("not a crowdbake pack (bad magic; expected \\x89CROWD\\r\\n)");
  ByteReader in(data, size, "header");
  in.skip(kMagic.size(), "magic");
  in.u16(h.version_major, "version major");
  in.u16(h.version_minor, "version minor");
  if (!in.ok()) return error("truncated pack: " + in.error());
  if (h.version_major != kPackVersionMajor) {
    if (h.version_major > kPackVersionMajor)
      return error("unsupported pack version " + std::to_string(h.version_major) +
                   " (this build reads <= " + std::to_string(kPackVersionMajor) +
                   "); update crowdbake");
    return error("unsupported pack version " + std::to_string(h.version_major) +
                 " (this build reads " + std::to_string(kPackVersionMajor) + "); re-bake the pack");
  }
  uint32_t flags = 0, reserved = 0, reserved2 = 0;
  in.u32(flags, "flags");
  in.u32(h.chunk_count, "chunk count");
  in.u32(reserved, "reserved");
  in.u64(h.table_offset, "chunk table offset");
  in.u64(h.file_size, "file size");
  in.u32(checksum, "header checksum");
  in.u32(reserved2, "reserved");
  if (!in.ok()) return error("truncated pack: " + in.error());
  if (flags & kRequiredFlagsMask)
    return error("header: unsupported required feature flags " + hex(flags & kRequiredFlagsMask) +
                 " (this build knows none)");
  if (reserved || reserved2) return error("header: reserved fields are not zero");
  if (h.chunk_count > kMaxChunks)
    return error("header: " + std::to_string(h.chunk_count) + " chunks exceed the limit of " +
                 std::to_string(kMaxChunks));
  if (h.table_offset < kHeaderSize || h.table_offset % kAlignment != 0)
    return error("header: chunk table offset " + std::to_string(h.table_offset) +
                 " is not a 16-byte aligned offset after the header");
  const uint64_t table_bytes = uint64_t{h.chunk_count} * kChunkEntrySize;
  if (h.table_offset > h.file_size || table_bytes > h.file_size - h.table_offset)
    return error("header: chunk table at " + std::to_string(h.table_offset) + " (" +
                 std::to_string(table_bytes) + " bytes) runs past the file size " +
                 std::to_string(h.file_size));
  return {};
}

Status read_header_and_table(const uint8_t* data, size_t size, PackHeader& h,
                             std::vector<PackChunk>& chunks) {
  chunks.clear();
  uint32_t checksum = 0;
  if (Status s = parse_header(data, size, h, checksum); !s) return s;
  const uint64_t table_bytes = uint64_t{h.chunk_count} * kChunkEntrySize;
  const uint64_t table_end = h.table_offset + table_bytes;
  if (size > h.file_size)
    return error("pack has " + std::to_string(size - h.file_size) +
                 " trailing bytes after its recorded size " + std::to_string(h.file_size));
  if (size < table_end)
    return error("truncated pack: " + std::to_string(size) + " bytes, the chunk table ends at " +
                 std::to_string(table_end) + " (file size " + std::to_string(h.file_size) + ")");
  const uint8_t* table = data + h.table_offset;
  uint32_t crc = pack_io::crc32c(data, 40);
  crc = pack_io::crc32c(table, size_t{h.chunk_count} * kChunkEntrySize, crc);
  if (!checksum_matches(checksum, crc))
    return error("header: checksum mismatch (stored " + hex(checksum) + ", computed " + hex(crc) +
                 "): the header or chunk table is corrupt");

  ByteReader t(table, size_t{h.chunk_count} * kChunkEntrySize, "chunk table");
  uint64_t previous_end = table_end;
  chunks.resize(h.chunk_count);
  for (uint32_t i = 0; i < h.chunk_count; ++i) {
    PackChunk& c = chunks[i];
    uint32_t entry_reserved = 0;
    t.set_item("entry", i);
    t.u32(c.tag, "tag");
    t.u32(c.version, "version");
    t.u64(c.offset, "offset");
    t.u64(c.size, "size");
    t.u32(c.checksum, "checksum");
    t.u32(entry_reserved, "reserved");
    if (!t.ok()) return error(t.error());
    const std::string name = "chunk " + tag_name(c.tag);
    if (entry_reserved) return error(name + ": reserved table field is not zero");
    if (c.offset % kAlignment != 0)
      return error(name + ": offset " + std::to_string(c.offset) + " is not 16-byte aligned");
    if (c.offset < previous_end)
      return error(
          name + ": offset " + std::to_string(c.offset) +
          " overlaps the chunk table or the previous chunk (chunks must be in file order)");
    if (c.offset > h.file_size || c.size > h.file_size - c.offset)
      return error(name + ": " + std::to_string(c.size) + " bytes at offset " +
                   std::to_string(c.offset) + " run past the file size " +
                   std::to_string(h.file_size));
    previous_end = c.offset + c.size;
    for (uint32_t k = 0; k < i; ++k)
      if (chunks[k].tag == c.tag) return error(name + ": appears twice in the chunk table");
  }
  return {};
}

// Decodes one chunk whose payload bytes are [payload, payload + chunk.size).
Status decode_chunk(const PackChunk& chunk, const uint8_t* payload, PackContents& out,
                    PackCounts* counts) {
  const std::string name = "chunk " + tag_name(chunk.tag);
  const uint32_t crc = pack_io::crc32c(payload, static_cast<size_t>(chunk.size));
  if (!checksum_matches(chunk.checksum, crc))
    return error(name + ": checksum mismatch (stored " + hex(chunk.checksum) + ", computed " +
                 hex(crc) + "): the chunk is corrupt");
  const KnownChunk* known = find_known(chunk.tag);
  if (!known) return {};  // note: unknown chunks are skipped (newer minor versions add them)
  const uint32_t oldest = known->oldest ? known->oldest : known->version;
  if (chunk.version < oldest || chunk.version > known->version)
    return error("unsupported " + name + " version " + std::to_string(chunk.version) +
                 " (this build reads <= " + std::to_string(known->version) + ")");
  // note: a wrapped chunk (§2.5) is decoded from its expanded version-1 payload.
  std::vector<uint8_t> expanded;
  size_t size = static_cast<size_t>(chunk.size);
  if (pack_io::is_wrappable(chunk.tag) && chunk.version == kWrappedVersion) {
    std::string why;
    const uint64_t limit = kWrappedExpansionSlack + kWrappedExpansionRatio * chunk.size;
    if (!pack_io::expand_zstd_frame(payload, size, limit, expanded, &why))
      return error(name + ": " + why);
    payload = expanded.data();
    size = expanded.size();
  }
  ByteReader in(payload, size, name);
  PackCounts ignored;
  const bool ok = known->decode(in, chunk.version, out, counts ? *counts : ignored);
  if (!ok) return error(in.ok() ? name + ": invalid" : in.error());
  return {};
}

Status check_head_counts(const PackCounts& h, const PackContents& c) {
  const PackCounts actual = pack_io::head_counts(c);
  const struct {
    const char* what;
    uint32_t head, actual;
  } pairs[] = {
      {"joints", h.joints, actual.joints},
      {"clips", h.clips, actual.clips},
      {"materials", h.materials, actual.materials},
      {"vertices", h.vertices, actual.vertices},
      {"triangles", h.triangles, actual.triangles},
      {"animation rows", h.animation_rows, actual.animation_rows},
  };
  for (const auto& p : pairs)
    if (p.head != p.actual)
      return error("chunk HEAD: says " + std::to_string(p.head) + " " + p.what +
                   ", the pack holds " + std::to_string(p.actual));
  return {};
}

}  // namespace

namespace pack_format {
std::string tag_name(uint32_t tag) {
  char c[4];
  for (int i = 0; i < 4; ++i) c[i] = static_cast<char>((tag >> (8 * i)) & 0xff);
  for (char ch : c)
    if (ch < 0x20 || ch > 0x7e) return hex(tag);
  return std::string(c, 4);
}
}  // namespace pack_format

Status read_pack_header(const uint8_t* data, size_t size, PackHeader& out) {
  PackHeader h;
  uint32_t checksum = 0;
  if (Status s = parse_header(data, size, h, checksum); !s) return s;
  out = h;
  return {};
}

Status read_pack_chunks(const uint8_t* data, size_t size, std::vector<PackChunk>& chunks,
                        uint16_t* version_major, uint16_t* version_minor) {
  PackHeader h;
  Status status = read_header_and_table(data, size, h, chunks);
  if (version_major) *version_major = h.version_major;
  if (version_minor) *version_minor = h.version_minor;
  if (!status) chunks.clear();
  return status;
}

Status read_pack_chunk(const PackChunk& chunk, const uint8_t* payload, PackContents& out,
                       PackCounts* counts) {
  if (payload == nullptr && chunk.size != 0)
    return error("chunk " + tag_name(chunk.tag) + ": no data");
  return decode_chunk(chunk, payload, out, counts);
}

Status read_pack_file(const uint8_t* data, size_t size, PackFile& out) {
  out.bytes = size;
  Status status = read_pack_chunks(data, size, out.chunks, &out.version_major, &out.version_minor);
  if (status) status = read_pack(data, size, out.contents);
  return status;
}

const char* region_name(uint8_t region) {
  switch (static_cast<Region>(region)) {
    case Region::kHead:
      return "head";
    case Region::kUpperBody:
      return "upper body";
    case Region::kTrousers:
      return "trousers";
    case Region::kUnused:
      return "unused";
  }
  return "unknown";
}

double bbox_diagonal(const PackContents& contents) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = double{contents.bounds.max[k]} - double{contents.bounds.min[k]};
    sum += d * d;
  }
  return std::sqrt(sum);
}

Status read_pack(const uint8_t* data, size_t size, PackContents& out) {
  out = PackContents{};
  PackHeader h;
  std::vector<PackChunk> chunks;
  Status status = read_header_and_table(data, size, h, chunks);
  if (!status) return status;
  if (size != h.file_size)
    return error("truncated pack: " + std::to_string(size) + " bytes, the header records " +
                 std::to_string(h.file_size));
  // Every byte outside the header, the table and the chunks must be zero padding, so a
  // corrupted byte anywhere in the file is detected.
  uint64_t at = h.table_offset + uint64_t{h.chunk_count} * kChunkEntrySize;
  const auto zero_gap = [&](uint64_t from, uint64_t to) -> Status {
    for (uint64_t i = from; i < to; ++i)
      if (data[i] != 0)
        return error("padding byte at offset " + std::to_string(i) + " is not zero");
    return {};
  };
  if (!(status = zero_gap(kHeaderSize, h.table_offset))) return status;
  for (const PackChunk& c : chunks) {
    if (!(status = zero_gap(at, c.offset))) return status;
    at = c.offset + c.size;
  }
  if (!(status = zero_gap(at, h.file_size))) return status;

  PackCounts counts;
  for (const KnownChunk& k : kKnownChunks) {
    const auto it = std::find_if(chunks.begin(), chunks.end(),
                                 [&](const PackChunk& c) { return c.tag == k.tag; });
    if (it == chunks.end() && k.required) return error("missing chunk " + tag_name(k.tag));
  }
  for (const PackChunk& c : chunks) {
    status = decode_chunk(c, data + c.offset, out, &counts);
    if (!status) return status;
  }
  const std::string cross = pack_io::check_cross_references(out);
  if (!cross.empty()) return error("chunk " + cross);
  return check_head_counts(counts, out);
}

}  // namespace crowdbake
