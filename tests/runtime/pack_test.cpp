// Pack: streaming (header and tables first, bulky chunks on demand), several packs at once,
// and clean errors for corrupt, truncated, inconsistent or missing packs.
#include "crowdbake/runtime/pack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <vector>

#include "crowdbake/formats/pack_format.h"
#include "pack_bytes.h"
#include "runtime/runtime_test_support.h"
#include "temp_dir.h"

namespace crowdbake::runtime {
namespace {

using test::CountingSource;

// ---- Byte surgery on pack files (docs/pack-format.md §2) --------------------------------

uint32_t crc32c(const uint8_t* data, size_t size, uint32_t crc = 0) {
  crc = ~crc;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0x82F63B78u & (0u - (crc & 1u)));
  }
  return ~crc;
}

template <typename T>
T load(const std::vector<uint8_t>& b, size_t at) {
  T v;
  std::memcpy(&v, &b[at], sizeof v);
  return v;
}
template <typename T>
void store(std::vector<uint8_t>& b, size_t at, T v) {
  std::memcpy(&b[at], &v, sizeof v);
}

struct Entry {
  uint32_t tag;
  uint64_t offset, size;
  size_t table_at;
};

std::vector<Entry> table(const std::vector<uint8_t>& b) {
  std::vector<Entry> out;
  const uint32_t count = load<uint32_t>(b, 16);
  const size_t at = static_cast<size_t>(load<uint64_t>(b, 24));
  for (uint32_t i = 0; i < count; ++i) {
    const size_t e = at + 32 * size_t{i};
    out.push_back({load<uint32_t>(b, e), load<uint64_t>(b, e + 8), load<uint64_t>(b, e + 16), e});
  }
  return out;
}

Entry find_chunk(const std::vector<uint8_t>& b, uint32_t tag) {
  for (const Entry& e : table(b))
    if (e.tag == tag) return e;
  ADD_FAILURE() << "no chunk " << pack_format::tag_name(tag);
  return {};
}

// Recomputes every chunk checksum and the header/table checksum after an edit.
void fix_checksums(std::vector<uint8_t>& b) {
  const std::vector<Entry> entries = table(b);
  for (const Entry& e : entries)
    store<uint32_t>(b, e.table_at + 24,
                    crc32c(&b[static_cast<size_t>(e.offset)], static_cast<size_t>(e.size)));
  const size_t at = static_cast<size_t>(load<uint64_t>(b, 24));
  uint32_t crc = crc32c(b.data(), 40);
  crc = crc32c(&b[at], 32 * entries.size(), crc);
  store<uint32_t>(b, 40, crc);
}

// HEAD ends with joints, clips, materials, vertices, triangles, animation rows (u32 each).
void set_head_count(std::vector<uint8_t>& b, int which, uint32_t value) {
  const Entry head = find_chunk(b, pack_format::kTagHead);
  store<uint32_t>(b, static_cast<size_t>(head.offset + head.size - 24 + 4 * which), value);
  fix_checksums(b);
}

Status open_bytes(std::vector<uint8_t> bytes, Pack& pack, uint32_t parts) {
  return Pack::open(make_memory_source(std::move(bytes), "test.crowdpack"), pack, parts);
}

bool overlaps(uint64_t offset, uint64_t size, const Entry& chunk) {
  return offset < chunk.offset + chunk.size && chunk.offset < offset + size;
}

// ---- Loading real packs -----------------------------------------------------------------

TEST(Pack, OpenReadsTablesThatMatchReadPack) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const std::vector<uint8_t> bytes = test::read_file(test::BakedPacks::get().spectator());
  PackContents whole;
  ASSERT_TRUE(read_pack(bytes.data(), bytes.size(), whole));

  Pack pack;
  const Status s = Pack::open_file(test::BakedPacks::get().spectator(), pack);
  ASSERT_TRUE(s) << s.message();
  EXPECT_TRUE(pack.is_open());
  EXPECT_EQ(pack.loaded_parts(), uint32_t{kPackTables});
  EXPECT_EQ(pack.version_major(), kPackVersionMajor);
  EXPECT_EQ(pack.source_name(), test::BakedPacks::get().spectator());
  const PackContents& c = pack.contents();
  EXPECT_EQ(c.name, whole.name);
  EXPECT_EQ(c.settings_json, whole.settings_json);
  ASSERT_EQ(c.joints.size(), whole.joints.size());
  for (size_t j = 0; j < c.joints.size(); ++j) {
    EXPECT_EQ(c.joints[j].name, whole.joints[j].name);
    EXPECT_EQ(c.joints[j].inverse_bind, whole.joints[j].inverse_bind);
  }
  ASSERT_EQ(c.clips.size(), whole.clips.size());
  for (size_t k = 0; k < c.clips.size(); ++k) {
    EXPECT_EQ(c.clips[k].name, whole.clips[k].name);
    EXPECT_EQ(c.clips[k].root_motion, whole.clips[k].root_motion);
  }
  EXPECT_EQ(c.progressive.collapse_to, whole.progressive.collapse_to);
  EXPECT_EQ(c.progressive.triangle_count, whole.progressive.triangle_count);
  EXPECT_EQ(c.bounds.radius, whole.bounds.radius);
  EXPECT_TRUE(c.geometry.positions.empty());
  EXPECT_TRUE(c.animation.data.empty());
  EXPECT_TRUE(c.partition.texels.empty());

  const PackCounts& n = pack.counts();
  EXPECT_EQ(n.joints, whole.joints.size());
  EXPECT_EQ(n.clips, whole.clips.size());
  EXPECT_EQ(n.materials, whole.materials.size());
  EXPECT_EQ(n.vertices, whole.geometry.vertex_count());
  EXPECT_EQ(n.triangles, whole.geometry.triangle_count());
  EXPECT_EQ(n.animation_rows, whole.animation.rows);
  EXPECT_EQ(pack.min_vertices(), whole.progressive.min_vertices);
  EXPECT_EQ(pack.max_vertices(), whole.geometry.vertex_count());
  EXPECT_EQ(pack.find_clip("walk"), 7);
  EXPECT_EQ(pack.find_clip("moonwalk"), -1);
  EXPECT_GE(pack.find_joint("hips"), 0);
  EXPECT_EQ(pack.find_joint("tail"), -1);

  ASSERT_TRUE(pack.load(kPackAll));
  EXPECT_EQ(pack.loaded_parts(), uint32_t{kPackAll});
  EXPECT_EQ(c.geometry.positions, whole.geometry.positions);
  EXPECT_EQ(c.geometry.triangles, whole.geometry.triangles);
  EXPECT_EQ(c.geometry.weights, whole.geometry.weights);
  EXPECT_EQ(c.animation.data, whole.animation.data);
  EXPECT_EQ(c.animation.decode_params, whole.animation.decode_params);
  EXPECT_EQ(c.partition.texels, whole.partition.texels);
  EXPECT_EQ(c.partition.neck_height, whole.partition.neck_height);
}

TEST(Pack, HeaderOnlyOpenReadsNoGeometryAnimationOrPartitionBytes) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const std::vector<uint8_t> bytes = test::read_file(test::BakedPacks::get().spectator());
  const Entry geom = find_chunk(bytes, pack_format::kTagGeom);
  const Entry anim = find_chunk(bytes, pack_format::kTagAnim);
  const Entry part = find_chunk(bytes, pack_format::kTagPart);
  auto log = std::make_shared<std::vector<CountingSource::Read>>();
  Pack pack;
  ASSERT_TRUE(Pack::open(std::make_unique<CountingSource>(bytes, log), pack));
  uint64_t total = 0;
  for (const auto& r : *log) {
    EXPECT_FALSE(overlaps(r.offset, r.size, geom)) << "read " << r.offset << "+" << r.size;
    EXPECT_FALSE(overlaps(r.offset, r.size, anim)) << "read " << r.offset << "+" << r.size;
    EXPECT_FALSE(overlaps(r.offset, r.size, part)) << "read " << r.offset << "+" << r.size;
    total += r.size;
  }
  EXPECT_LT(total, bytes.size() / 4) << "an open should read only the small tables";

  // Geometry on demand: exactly the GEOM chunk, once.
  log->clear();
  ASSERT_TRUE(pack.load(kPackGeometry));
  ASSERT_EQ(log->size(), 1u);
  EXPECT_EQ((*log)[0].offset, geom.offset);
  EXPECT_EQ((*log)[0].size, geom.size);
  EXPECT_TRUE(pack.has(kPackGeometry));
  EXPECT_FALSE(pack.has(kPackAnimation));
  ASSERT_TRUE(pack.load(kPackGeometry));  // already loaded: no read
  EXPECT_EQ(log->size(), 1u);

  log->clear();
  ASSERT_TRUE(pack.load(kPackAnimation | kPackPartition));
  ASSERT_EQ(log->size(), 2u);
  EXPECT_EQ((*log)[0].offset, anim.offset);
  EXPECT_EQ((*log)[1].offset, part.offset);

  // Released parts are freed and streamed again.
  pack.release(kPackGeometry);
  EXPECT_FALSE(pack.has(kPackGeometry));
  EXPECT_TRUE(pack.contents().geometry.positions.empty());
  EXPECT_TRUE(pack.has(kPackTables));  // tables stay
  log->clear();
  ASSERT_TRUE(pack.load(kPackGeometry));
  EXPECT_EQ(log->size(), 1u);
  EXPECT_EQ(pack.contents().geometry.vertex_count(), pack.counts().vertices);
}

TEST(Pack, SeveralPacksAtOnce) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Pack a, b, c;
  ASSERT_TRUE(Pack::open_file(test::BakedPacks::get().spectator(), a, kPackAll));
  ASSERT_TRUE(Pack::open_file(test::BakedPacks::get().spectator_f32(), b));
  ASSERT_TRUE(open_bytes(test::small_pack_bytes(), c, kPackGeometry));
  EXPECT_NE(a.counts().vertices, b.counts().vertices);
  EXPECT_EQ(a.contents().animation.encoding, AnimationEncoding::kQuantized);
  EXPECT_EQ(c.contents().name, "small");
  ASSERT_TRUE(b.load(kPackAnimation));
  EXPECT_EQ(b.contents().animation.encoding, AnimationEncoding::kFloat32);
  EXPECT_FALSE(b.has(kPackGeometry));
  EXPECT_TRUE(a.has(kPackAll));  // loading b changed nothing in a
  a.release(kPackAll);
  EXPECT_TRUE(c.has(kPackGeometry));
  EXPECT_EQ(b.contents().animation.rows, b.counts().animation_rows);
  // Packs move: a moved pack keeps streaming from its source.
  Pack moved = std::move(b);
  EXPECT_FALSE(b.is_open());
  ASSERT_TRUE(moved.load(kPackGeometry));
  EXPECT_EQ(moved.contents().geometry.vertex_count(), moved.counts().vertices);
}

TEST(Pack, DerivedValues) {
  Pack pack;
  ASSERT_TRUE(open_bytes(test::small_pack_bytes(), pack, kPackTables));
  const PackContents small = test::make_small_pack();
  const auto centre = pack.bounds_center();
  EXPECT_FLOAT_EQ(centre[1], 0.9f);
  EXPECT_EQ(pack.bounds_radius(), 2.0f);
  EXPECT_EQ(pack.min_vertices(), 4u);
  EXPECT_EQ(pack.max_vertices(), small.geometry.vertex_count());
  ASSERT_NE(pack.bind_matrix(1), nullptr);
  EXPECT_FLOAT_EQ(pack.bind_matrix(1)[7], 0.8f);  // the inverse of a translation by -0.8
  EXPECT_EQ(pack.bind_matrix(3), nullptr);
  // Without progressive data the LoD range is full resolution only.
  PackContents flat = small;
  flat.progressive = PackProgressive{};
  PackWriteOptions raw;
  raw.codec = GeometryCodec::kRaw;
  Pack flat_pack;
  ASSERT_TRUE(open_bytes(test::pack_bytes(flat, raw), flat_pack, kPackTables));
  EXPECT_EQ(flat_pack.min_vertices(), flat_pack.max_vertices());
}

// ---- Bad packs -------------------------------------------------------------------------

TEST(Pack, MissingFileAndNotAFile) {
  Pack pack;
  Status s = Pack::open_file("/nonexistent/dir/x.crowdpack", pack);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("/nonexistent/dir/x.crowdpack"), std::string::npos);
  EXPECT_NE(s.message().find("No such file"), std::string::npos);
  EXPECT_FALSE(pack.is_open());
  test::TempDir dir;
  s = Pack::open_file(dir.path().string(), pack);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("not a regular file"), std::string::npos);
  EXPECT_EQ(pack.load(kPackAll).code(), StatusCode::kInvalidArgument);  // not open
  EXPECT_EQ(Pack::open(nullptr, pack).code(), StatusCode::kInvalidArgument);
}

TEST(Pack, NotAPackAndWrongVersion) {
  Pack pack;
  Status s = open_bytes({}, pack, kPackAll);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("test.crowdpack: "), std::string::npos);
  std::vector<uint8_t> text(200, 'x');
  s = open_bytes(text, pack, kPackAll);
  EXPECT_NE(s.message().find("not a crowdbake pack"), std::string::npos);
  std::vector<uint8_t> bytes = test::small_pack_bytes();
  bytes[8] = 2;  // major version 2
  s = open_bytes(bytes, pack, kPackAll);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("unsupported pack version 2"), std::string::npos);
}

TEST(Pack, TruncatedAndTrailingBytes) {
  const std::vector<uint8_t> bytes = test::small_pack_bytes();
  Pack pack;
  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 16);
  Status s = open_bytes(cut, pack, kPackTables);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("truncated pack"), std::string::npos) << s.message();
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  s = open_bytes(longer, pack, kPackTables);
  EXPECT_NE(s.message().find("trailing"), std::string::npos) << s.message();
  // Every prefix fails cleanly (fresh buffers: ASAN builds see any overrun).
  for (size_t size = 0; size < bytes.size(); ++size) {
    std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(size));
    Pack p;
    EXPECT_FALSE(open_bytes(std::move(prefix), p, kPackAll)) << "prefix of " << size << " bytes";
    EXPECT_FALSE(p.is_open());
  }
}

TEST(Pack, EveryFlippedByteIsCaught) {
  const std::vector<uint8_t> bytes = test::small_pack_bytes();
  // Bytes the reader must check: the header, the table and every chunk payload (padding
  // between chunks is not read by a streaming reader).
  std::vector<std::pair<uint64_t, uint64_t>> covered = {{0, 48 + 32 * table(bytes).size()}};
  for (const Entry& e : table(bytes)) covered.push_back({e.offset, e.offset + e.size});
  int tried = 0;
  for (const auto& [from, to] : covered) {
    for (uint64_t at = from; at < to; ++at) {
      std::vector<uint8_t> flipped = bytes;
      flipped[static_cast<size_t>(at)] ^= 0x5a;
      Pack p;
      const Status s = open_bytes(std::move(flipped), p, kPackAll);
      ASSERT_FALSE(s) << "flipped byte " << at << " went unnoticed";
      ASSERT_EQ(s.code(), StatusCode::kInvalidPack) << s.message();
      ++tried;
    }
  }
  EXPECT_GT(tried, 1000);
}

TEST(Pack, CorruptBulkChunkFailsOnlyWhenLoaded) {
  std::vector<uint8_t> bytes = test::small_pack_bytes();
  const Entry geom = find_chunk(bytes, pack_format::kTagGeom);
  bytes[static_cast<size_t>(geom.offset + geom.size / 2)] ^= 1;
  Pack pack;
  ASSERT_TRUE(open_bytes(bytes, pack, kPackTables));  // GEOM is not read yet
  const Status s = pack.load(kPackAll);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("test.crowdpack: chunk GEOM: checksum mismatch"), std::string::npos)
      << s.message();
  EXPECT_FALSE(pack.has(kPackGeometry));
  EXPECT_TRUE(pack.contents().geometry.positions.empty());
  // The other parts still load.
  ASSERT_TRUE(pack.load(kPackAnimation | kPackPartition));
  EXPECT_TRUE(pack.has(kPackAnimation));
}

TEST(Pack, HeadCountsMustMatchEveryChunk) {
  Pack pack;
  std::vector<uint8_t> bytes = test::small_pack_bytes();
  set_head_count(bytes, 0, 99);  // joints
  Status s = open_bytes(bytes, pack, kPackTables);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("chunk SKEL: holds 3 joints, HEAD says 99"), std::string::npos)
      << s.message();

  bytes = test::small_pack_bytes();
  set_head_count(bytes, 1, 2);  // clips
  s = open_bytes(bytes, pack, kPackTables);
  EXPECT_NE(s.message().find("chunk CLIP: holds 3 clips, HEAD says 2"), std::string::npos)
      << s.message();

  bytes = test::small_pack_bytes();
  set_head_count(bytes, 5, 7);  // animation rows: clip "pose" uses row 7
  s = open_bytes(bytes, pack, kPackTables);
  EXPECT_NE(s.message().find("chunk CLIP: clip 2 'pose' uses rows 7..7"), std::string::npos)
      << s.message();

  bytes = test::small_pack_bytes();
  set_head_count(bytes, 3, 35);  // vertices (PROG holds 36)
  s = open_bytes(bytes, pack, kPackTables);
  EXPECT_NE(s.message().find("chunk PROG: holds 36 vertices, HEAD says 35"), std::string::npos)
      << s.message();

  // Without progressive data GEOM is the first chunk to disagree, when it is loaded.
  PackContents flat = test::make_small_pack();
  flat.progressive = PackProgressive{};
  PackWriteOptions raw;
  raw.codec = GeometryCodec::kRaw;
  bytes = test::pack_bytes(flat, raw);
  set_head_count(bytes, 3, 37);
  ASSERT_TRUE(open_bytes(bytes, pack, kPackTables));
  s = pack.load(kPackGeometry);
  EXPECT_NE(s.message().find("chunk GEOM: holds 36 vertices, HEAD says 37"), std::string::npos)
      << s.message();
  EXPECT_FALSE(pack.has(kPackGeometry));

  bytes = test::small_pack_bytes();
  set_head_count(bytes, 5, 9);  // animation rows: the texture holds 8
  ASSERT_TRUE(open_bytes(bytes, pack, kPackTables));
  s = pack.load(kPackAnimation);
  EXPECT_NE(s.message().find("chunk ANIM: holds 8 rows, HEAD says 9"), std::string::npos)
      << s.message();
}

TEST(Pack, MissingChunk) {
  std::vector<uint8_t> bytes = test::small_pack_bytes();
  const Entry part = find_chunk(bytes, pack_format::kTagPart);
  store<uint32_t>(bytes, part.table_at, pack_format::make_tag('X', 'T', 'R', 'A'));  // rename PART
  fix_checksums(bytes);
  Pack pack;
  const Status s = open_bytes(bytes, pack, kPackTables);
  EXPECT_EQ(s.code(), StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("missing chunk PART"), std::string::npos) << s.message();
}

TEST(Pack, FileReplacedByAShorterOneWhileOpen) {
  test::TempDir dir;
  const auto path = dir / "small.crowdpack";
  const std::vector<uint8_t> bytes = test::small_pack_bytes();
  test::write_file(path, bytes);
  Pack pack;
  ASSERT_TRUE(Pack::open_file(path.string(), pack));
  std::filesystem::resize_file(path, 100);  // truncated behind the reader's back
  const Status s = pack.load(kPackGeometry);
  EXPECT_EQ(s.code(), StatusCode::kIoError);
  EXPECT_NE(s.message().find("truncated"), std::string::npos) << s.message();
  EXPECT_FALSE(pack.has(kPackGeometry));
}

}  // namespace
}  // namespace crowdbake::runtime
