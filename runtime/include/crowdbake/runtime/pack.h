// Pack: one character type streamed from a .crowdpack file (docs/pack-format.md).
//
// Opening a pack reads the 48-byte header, the chunk table and the small tables (HEAD, SKEL,
// CLIP, MATL, BNDS, PROG: names, skeleton, clips, materials, bounds, ProgressiveMesh arrays)
// and nothing else. The bulky chunks — geometry (GEOM), the animation texture (ANIM) and the
// partition mask (PART) — are read only when load() asks for them, and release() frees them
// again, so a game can keep many character types open and stream their data in and out.
// Several packs are simply several Pack objects; they share nothing.
//
// Pack bytes are untrusted: every chunk's checksum, version, sizes and indices are checked
// (by crowdbake_formats' read_pack_chunk) and so is every rule between chunks (HEAD's counts,
// joint and material indices, clip rows, ProgressiveMesh sizes). When every part is loaded
// the contents satisfy validate_pack_contents(), exactly as after read_pack(). A corrupt,
// truncated or hostile file gives a kInvalidPack Status naming the file, the chunk and the
// field — never a crash or an exception.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "crowdbake/formats/pack.h"
#include "crowdbake/runtime/byte_source.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime {

// Parts of a pack that load separately (bit flags; combine with |).
enum PackPart : uint32_t {
  kPackTables = 1u << 0,     // HEAD SKEL CLIP MATL BNDS PROG: always loaded by open()
  kPackGeometry = 1u << 1,   // GEOM: vertices and triangles
  kPackAnimation = 1u << 2,  // ANIM: the animation texture
  kPackPartition = 1u << 3,  // PART: the partition mask
  kPackAll = kPackTables | kPackGeometry | kPackAnimation | kPackPartition,
};

// The counts HEAD records (formats' PackCounts); known as soon as the pack is open (size
// buffers before streaming).
using crowdbake::PackCounts;

class Pack {
 public:
  Pack();
  ~Pack();
  Pack(Pack&&) noexcept;
  Pack& operator=(Pack&&) noexcept;
  Pack(const Pack&) = delete;
  Pack& operator=(const Pack&) = delete;

  // Opens a pack: reads the header, the chunk table and the tables, then the parts asked for.
  // Returns kInvalidPack (bad magic, unsupported version, corrupt or missing chunk,
  // inconsistent counts...), kIoError (the source failed) or kOutOfMemory; `out` is then
  // left closed. Messages start with the source's name.
  // source: where the bytes come from; must not be null; the pack keeps it to stream later
  // out: receives the open pack (any previous contents are dropped)
  // parts: PackPart flags to load now besides the tables (kPackTables alone = header-only open)
  static Status open(std::unique_ptr<ByteSource> source, Pack& out, uint32_t parts = kPackTables);

  // open() over open_file_source(path).
  static Status open_file(const std::string& path, Pack& out, uint32_t parts = kPackTables);

  bool is_open() const;

  // Reads and decodes the parts not loaded yet (already loaded parts are not read again).
  // Returns kInvalidPack / kIoError / kOutOfMemory; a part that fails stays unloaded (its
  // arrays empty) and parts loaded before stay loaded. kInvalidArgument if the pack is not open.
  // parts: PackPart flags
  Status load(uint32_t parts);

  // Frees the memory of loaded parts (kPackTables is never released); load() reads them again.
  void release(uint32_t parts);

  // PackPart flags of what is in memory now.
  uint32_t loaded_parts() const;
  // True when every part in `parts` is loaded.
  bool has(uint32_t parts) const { return (loaded_parts() & parts) == parts; }

  // The decoded pack. Tables are always filled; geometry, animation and partition only while
  // loaded (empty otherwise). Empty contents when the pack is not open.
  const PackContents& contents() const;
  const PackCounts& counts() const;
  // The chunk table, in file order (unknown chunks included).
  const std::vector<PackChunk>& chunks() const;
  // The source's name (the file path for open_file).
  const std::string& source_name() const;
  uint16_t version_major() const;
  uint16_t version_minor() const;

  // Index of the clip or joint with this exact name, or -1.
  int32_t find_clip(std::string_view name) const;
  int32_t find_joint(std::string_view name) const;
  // The first 12 clip names, for messages ("idle, sit, ...").
  std::string clip_names() const;

  // LoD range in vertices: the ProgressiveMesh's min_vertices and the full vertex count.
  // A pack without progressive data (PROG vertex count 0) has min == max: full resolution only.
  uint32_t min_vertices() const;
  uint32_t max_vertices() const;

  // Centre of the bounding sphere (the bind-pose box centre, model units) and its radius
  // (covers every baked frame; PackBounds::radius).
  std::array<float, 3> bounds_center() const;
  float bounds_radius() const;

  // Joint j's global matrix at the bind pose: the inverse of PackJoint::inverse_bind
  // (3x4 row-major, computed in double when the pack opens). Joint queries use it to turn a
  // skinning matrix back into a joint matrix.
  // Returns nullptr when j is out of range or the inverse bind matrix is singular.
  const float* bind_matrix(uint32_t joint) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crowdbake::runtime
