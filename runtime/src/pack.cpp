// Pack streaming: header and table first, tables at open, bulky chunks on demand. Reading and
// checking are crowdbake_formats' (read_pack_header, read_pack_chunks, read_pack_chunk, and
// check_pack_chunk for the rules between a chunk and HEAD's counts); this file decides what
// to read when.
#include "crowdbake/runtime/pack.h"

#include <cmath>
#include <cstring>
#include <new>

#include "crowdbake/formats/pack_format.h"

namespace crowdbake::runtime {
namespace {

using pack_format::tag_name;

constexpr uint32_t kTableTags[] = {pack_format::kTagHead, pack_format::kTagSkel,
                                   pack_format::kTagClip, pack_format::kTagMatl,
                                   pack_format::kTagBnds, pack_format::kTagProg};
constexpr uint32_t kRequiredTags[] = {
    pack_format::kTagHead, pack_format::kTagSkel, pack_format::kTagClip,
    pack_format::kTagMatl, pack_format::kTagBnds, pack_format::kTagProg,
    pack_format::kTagGeom, pack_format::kTagAnim, pack_format::kTagPart};

// Inverse of a 3x4 affine matrix in double; false when the 3x3 part is singular.
bool invert_affine(const float m[12], float out[12]) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9],
               i = m[10];
  const double c00 = e * i - f * h, c01 = c * h - b * i, c02 = b * f - c * e;
  const double c10 = f * g - d * i, c11 = a * i - c * g, c12 = c * d - a * f;
  const double c20 = d * h - e * g, c21 = b * g - a * h, c22 = a * e - b * d;
  const double det = a * c00 + b * c10 + c * c20;
  double scale = 0.0;  // note: singular relative to the matrix's own magnitude
  for (int k : {0, 1, 2, 4, 5, 6, 8, 9, 10}) scale = std::max(scale, std::fabs(double{m[k]}));
  if (!std::isfinite(det) || scale == 0.0 || std::fabs(det) <= 1e-12 * scale * scale * scale)
    return false;
  const double r[9] = {c00 / det, c01 / det, c02 / det, c10 / det, c11 / det,
                       c12 / det, c20 / det, c21 / det, c22 / det};
  const double t[3] = {m[3], m[7], m[11]};
  for (int row = 0; row < 3; ++row) {
    double tr = 0.0;
    for (int k = 0; k < 3; ++k) {
      out[4 * row + k] = static_cast<float>(r[3 * row + k]);
      tr -= r[3 * row + k] * t[k];
    }
    out[4 * row + 3] = static_cast<float>(tr);
  }
  for (int k = 0; k < 12; ++k)
    if (!std::isfinite(out[k])) return false;
  return true;
}

}  // namespace

struct Pack::Impl {
  std::unique_ptr<ByteSource> source;
  std::string name;
  std::vector<PackChunk> chunks;
  uint16_t major = 0, minor = 0;
  PackCounts counts;
  PackContents contents;
  uint32_t loaded = 0;
  std::vector<float> bind;       // 12 per joint
  std::vector<uint8_t> bind_ok;  // 1 per joint

  Status fail(const std::string& what) const {
    return {StatusCode::kInvalidPack, name + ": " + what};
  }

  const PackChunk* find(uint32_t tag) const {
    for (const PackChunk& c : chunks)
      if (c.tag == tag) return &c;
    return nullptr;
  }

  // Reads one chunk's payload and decodes it into `contents` (HEAD: and `counts`).
  Status read_chunk(uint32_t tag) {
    const PackChunk* chunk = find(tag);
    if (!chunk) return fail("missing chunk " + tag_name(tag));
    std::vector<uint8_t> payload(static_cast<size_t>(chunk->size));
    if (Status s = source->read(chunk->offset, payload.size(), payload.data()); !s) return s;
    const Status decoded = read_pack_chunk(*chunk, payload.data(), contents, &counts);
    if (!decoded) return fail(decoded.message());
    return {};
  }

  Status open_front() {
    const uint64_t size = source->size();
    // Header first: it says where the table is. A short or odd header goes to
    // read_pack_chunks as is, which reports the precise problem.
    std::vector<uint8_t> front(
        static_cast<size_t>(std::min<uint64_t>(size, pack_format::kHeaderSize)));
    if (Status s = source->read(0, front.size(), front.data()); !s) return s;
    PackHeader header;
    if (read_pack_header(front.data(), front.size(), header)) {
      const uint64_t table_end =
          header.table_offset + uint64_t{header.chunk_count} * pack_format::kChunkEntrySize;
      if (table_end <= size && table_end > front.size()) {
        const size_t old = front.size();
        front.resize(static_cast<size_t>(table_end));
        if (Status s = source->read(old, front.size() - old, front.data() + old); !s) return s;
      }
    }
    const Status table = read_pack_chunks(front.data(), front.size(), chunks, &major, &minor);
    if (!table) return fail(table.message());
    if (size < header.file_size)
      return fail("truncated pack: " + std::to_string(size) + " bytes, the header records " +
                  std::to_string(header.file_size));
    if (size > header.file_size)
      return fail("pack has " + std::to_string(size - header.file_size) +
                  " trailing bytes after its recorded size " + std::to_string(header.file_size));
    for (uint32_t tag : kRequiredTags)
      if (!find(tag)) return fail("missing chunk " + tag_name(tag));
    return {};
  }

  Status load_tables() {
    if (Status s = read_chunk(pack_format::kTagHead); !s) return s;
    for (uint32_t tag : kTableTags)
      if (tag != pack_format::kTagHead)
        if (Status s = read_chunk(tag); !s) return s;
    // note: LERR is optional (packs of 1.0 have none); it is a small table when present.
    // MATX and IMGS (1.2) are optional too; IMGS holds encoded PNG/JPEG images, a texture's
    // worth, read with the tables because type creation needs them. VARS (1.7) says which of
    // those images are per-region variants.
    for (uint32_t tag : {pack_format::kTagLerr, pack_format::kTagMatx, pack_format::kTagImgs,
                         pack_format::kTagVars})
      if (find(tag))
        if (Status s = read_chunk(tag); !s) return s;
    for (uint32_t tag : {pack_format::kTagSkel, pack_format::kTagClip, pack_format::kTagMatl,
                         pack_format::kTagProg, pack_format::kTagLerr})
      if (Status s = check_pack_chunk(tag, contents, counts); !s) return fail(s.message());
    const PackContents& p = contents;
    bind.assign(size_t{12} * p.joints.size(), 0.0f);
    bind_ok.assign(p.joints.size(), 0);
    for (size_t j = 0; j < p.joints.size(); ++j)
      bind_ok[j] = invert_affine(p.joints[j].inverse_bind.data(), &bind[12 * j]);
    return {};
  }

  void clear(uint32_t parts) {
    if (parts & kPackGeometry) contents.geometry = PackGeometry{}, contents.vertex_colors.clear();
    if (parts & kPackAnimation) contents.animation = AnimationTexture{};
    if (parts & kPackPartition) contents.partition = PartitionMask{}, contents.impostor = {};
    loaded &= ~(parts & ~uint32_t{kPackTables});
  }

  Status load_part(uint32_t part) {
    const uint32_t tag = part == kPackGeometry    ? pack_format::kTagGeom
                         : part == kPackAnimation ? pack_format::kTagAnim
                                                  : pack_format::kTagPart;
    Status s = read_chunk(tag);
    // note: VCOL (1.7, optional) is per-vertex data: it travels with GEOM.
    if (s && part == kPackGeometry && find(pack_format::kTagVcol))
      s = read_chunk(pack_format::kTagVcol);
    // note: IMPS (1.8, optional) is a look of the character, like the partition mask.
    if (s && part == kPackPartition && find(pack_format::kTagImps)) {
      s = read_chunk(pack_format::kTagImps);
      if (s)
        if (Status rules = check_pack_chunk(pack_format::kTagImps, contents, counts); !rules)
          s = fail(rules.message());
    }
    if (s && (part == kPackGeometry || part == kPackAnimation))
      if (Status rules = check_pack_chunk(tag, contents, counts); !rules) s = fail(rules.message());
    if (!s) {
      clear(part);
      return s;
    }
    loaded |= part;
    if (loaded == kPackAll) {
      // note: everything is in memory: the whole-pack rules read_pack guarantees must hold.
      const Status all = validate_pack_contents(contents);
      if (!all) {
        clear(part);
        return fail(all.message());
      }
    }
    return {};
  }
};

Pack::Pack() = default;
Pack::~Pack() = default;
Pack::Pack(Pack&&) noexcept = default;
Pack& Pack::operator=(Pack&&) noexcept = default;

Status Pack::open(std::unique_ptr<ByteSource> source, Pack& out, uint32_t parts) {
  out.impl_.reset();
  if (!source) return {StatusCode::kInvalidArgument, "Pack::open: no byte source"};
  try {
    auto impl = std::make_unique<Impl>();
    impl->name = source->name();
    impl->source = std::move(source);
    if (Status s = impl->open_front(); !s) return s;
    if (Status s = impl->load_tables(); !s) return s;
    impl->loaded = kPackTables;
    out.impl_ = std::move(impl);
    if (Status s = out.load(parts); !s) {
      out.impl_.reset();
      return s;
    }
    return {};
  } catch (const std::bad_alloc&) {
    out.impl_.reset();
    return {StatusCode::kOutOfMemory, "out of memory while opening a pack"};
  } catch (const std::exception& e) {
    out.impl_.reset();
    return {StatusCode::kInvalidPack,
            std::string("unexpected error while opening a pack: ") + e.what()};
  }
}

Status Pack::open_file(const std::string& path, Pack& out, uint32_t parts) {
  out.impl_.reset();
  std::unique_ptr<ByteSource> source;
  if (Status s = open_file_source(path, source); !s) return s;
  return open(std::move(source), out, parts);
}

bool Pack::is_open() const { return impl_ != nullptr; }

Status Pack::load(uint32_t parts) {
  if (!impl_) return {StatusCode::kInvalidArgument, "Pack::load: the pack is not open"};
  uint32_t current = 0;
  try {
    for (uint32_t part : {kPackGeometry, kPackAnimation, kPackPartition}) {
      if (!(parts & part) || (impl_->loaded & part)) continue;
      current = part;
      if (Status s = impl_->load_part(part); !s) return s;
    }
    return {};
  } catch (const std::bad_alloc&) {
    impl_->clear(current);
    return {StatusCode::kOutOfMemory, impl_->name + ": out of memory while loading"};
  } catch (const std::exception& e) {
    impl_->clear(current);
    return {StatusCode::kInvalidPack,
            impl_->name + ": unexpected error while loading: " + e.what()};
  }
}

void Pack::release(uint32_t parts) {
  if (impl_) impl_->clear(parts);
}

uint32_t Pack::loaded_parts() const { return impl_ ? impl_->loaded : 0; }

const PackContents& Pack::contents() const {
  static const PackContents kEmpty;
  return impl_ ? impl_->contents : kEmpty;
}
const PackCounts& Pack::counts() const {
  static const PackCounts kEmpty;
  return impl_ ? impl_->counts : kEmpty;
}
const std::vector<PackChunk>& Pack::chunks() const {
  static const std::vector<PackChunk> kEmpty;
  return impl_ ? impl_->chunks : kEmpty;
}
const std::string& Pack::source_name() const {
  static const std::string kEmpty;
  return impl_ ? impl_->name : kEmpty;
}
uint16_t Pack::version_major() const { return impl_ ? impl_->major : 0; }
uint16_t Pack::version_minor() const { return impl_ ? impl_->minor : 0; }

std::string Pack::clip_names() const {
  std::string out;
  const auto& clips = contents().clips;
  for (size_t i = 0; i < clips.size() && i < 12; ++i) out += (i ? ", " : "") + clips[i].name;
  if (clips.size() > 12) out += ", ...";
  return out;
}

int32_t Pack::find_clip(std::string_view name) const {
  const auto& clips = contents().clips;
  for (size_t i = 0; i < clips.size(); ++i)
    if (clips[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

int32_t Pack::find_joint(std::string_view name) const {
  const auto& joints = contents().joints;
  for (size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return static_cast<int32_t>(i);
  return -1;
}

uint32_t Pack::min_vertices() const {
  const PackProgressive& p = contents().progressive;
  return p.collapse_to.empty() ? counts().vertices : p.min_vertices;
}

uint32_t Pack::max_vertices() const { return counts().vertices; }

std::array<float, 3> Pack::bounds_center() const {
  const PackBounds& b = contents().bounds;
  return {0.5f * (b.min[0] + b.max[0]), 0.5f * (b.min[1] + b.max[1]), 0.5f * (b.min[2] + b.max[2])};
}

float Pack::bounds_radius() const { return contents().bounds.radius; }

const float* Pack::bind_matrix(uint32_t joint) const {
  if (!impl_ || joint >= impl_->bind_ok.size() || !impl_->bind_ok[joint]) return nullptr;
  return &impl_->bind[size_t{12} * joint];
}

}  // namespace crowdbake::runtime
