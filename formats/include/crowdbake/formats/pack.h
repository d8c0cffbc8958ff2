// The crowdbake pack (.crowdpack): everything a runtime needs to draw one character
// type, in one versioned, chunked, little-endian file (docs/pack-format.md).
//
// PackContents is the decoded, in-memory form: the pipeline fills it (pipeline/bake),
// write_pack() serialises it deterministically, read_pack() parses and validates
// untrusted bytes back into it. Vertex and triangle arrays are in ProgressiveMesh order
// (docs/design.md §3.3): the LoD with n vertices uses the first n vertices.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/base/status.h"
#include "crowdbake/formats/pack_format.h"  // kPackVersionMajor/Minor, tags, limits

namespace crowdbake {

// How joint matrices are stored in the animation texture (docs/animation-encoding.md).
enum class AnimationEncoding : uint32_t {
  kFloat32 = 0,    // 3 RGBA32F texels per joint: the three rows of the 3x4 skinning matrix
  kFloat16 = 1,    // the same rows as RGBA16F (IEEE half)
  kQuantized = 2,  // compact: see docs/animation-encoding.md for the exact layout
};

struct PackJoint {
  std::string name;
  int32_t parent = -1;  // < own index; -1 for roots
  std::array<float, 12> inverse_bind{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};  // 3x4 row-major rows
  std::array<float, 3> rest_translation{0, 0, 0};
  std::array<float, 4> rest_rotation{0, 0, 0, 1};  // x, y, z, w
  std::array<float, 3> rest_scale{1, 1, 1};
};

struct PackClip {
  std::string name;
  uint32_t first_row = 0;    // first animation-texture row of this clip
  uint32_t frame_count = 0;  // rows used; >= 1
  float fps = 30.0f;         // bake rate
  float duration = 0.0f;     // seconds
  bool looping = true;
  // Root motion, extracted when the bake asks for it: per frame (x, z, yaw) of the root
  // relative to frame 0 in the model's ground plane; empty when motion stays baked in,
  // otherwise exactly 3 * frame_count floats.
  std::vector<float> root_motion;
};

struct AnimationTexture {
  AnimationEncoding encoding = AnimationEncoding::kFloat32;
  uint32_t joints = 0;               // joints per row
  uint32_t texels_per_joint = 3;     // texels one joint takes in a row
  uint32_t bytes_per_texel = 16;     // RGBA32F = 16, RGBA16F = 8, ...
  uint32_t rows = 0;                 // frames of all clips, stacked
  std::vector<float> decode_params;  // encoding-specific constants (e.g. quantisation ranges)
  std::vector<uint8_t> data;         // rows * joints * texels_per_joint * bytes_per_texel bytes

  uint32_t width() const { return joints * texels_per_joint; }  // texels per row
};

// Region ids in the partition mask and per vertex (seed 000 Algorithm 3).
enum class Region : uint8_t { kHead = 0, kUpperBody = 1, kTrousers = 2, kUnused = 255 };

struct PartitionMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> texels;  // width * height Region values, row 0 = v in [0, 1/height)
  float neck_height = 0.0f;     // bind-pose heights along up_axis, in model units
  float waist_height = 0.0f;
  std::array<float, 3> up_axis{0, 1, 0};
};

// How a material's alpha is used (glTF alphaMode). The renderer draws kBlend as kOpaque.
enum class AlphaMode : uint32_t { kOpaque = 0, kMask = 1, kBlend = 2 };

struct PackMaterial {
  std::string name;
  std::array<float, 4> base_color{1, 1, 1, 1};  // linear RGBA factor
  std::string base_color_texture;  // image name or URI as the source names it; empty: none
  // Index into PackContents::images of the base colour texture; -1 when there is none or its
  // image could not be stored (missing file, unsupported format): the factor alone then.
  int32_t base_color_image = -1;
  // Texture coordinates the image is sampled at: u' = t[0]·u + t[1]·v + t[2],
  // v' = t[3]·u + t[4]·v + t[5] (glTF KHR_texture_transform; identity when absent).
  std::array<float, 6> uv_transform{1, 0, 0, 0, 1, 0};
  AlphaMode alpha_mode = AlphaMode::kOpaque;
  float alpha_cutoff = 0.5f;  // kMask: texels with alpha below it are not drawn
  bool double_sided = false;
};

// An image as the source file held it: PNG or JPEG bytes, never re-encoded (docs/pack-format.md
// "IMGS" says why).
struct PackImage {
  std::string name;                // the source's reference (URI, embedded name)
  std::string mime_type;           // "image/png" or "image/jpeg", from the bytes' signature
  uint32_t width = 0, height = 0;  // from the image's header
  std::vector<uint8_t> data;
};

// Images an artist made for one partition region (head, upper body, trousers), which an
// instance may wear there instead of its material's base colour image (VARS, pack 1.7,
// optional; docs/pack-format.md 3.12). They share the character's UV layout. Region r's
// variant k >= 1 (the instance's texture choice; 0 is the character's own look) is
// images[first[r] + k - 1], for k <= count[r].
struct PackVariantImages {
  std::array<uint32_t, 3> first{0, 0, 0};  // index into PackContents::images
  std::array<uint32_t, 3> count{0, 0, 0};  // at most kMaxVariantImages each

  bool empty() const { return count[0] == 0 && count[1] == 0 && count[2] == 0; }
};

struct PackGeometry {
  std::vector<float> positions;             // 3 per vertex, model units
  std::vector<float> normals;               // 3 per vertex, or empty
  std::vector<float> uvs;                   // 2 per vertex, or empty
  std::vector<uint16_t> joints;             // 4 per vertex, < joint count
  std::vector<float> weights;               // 4 per vertex, each vertex sums to 1
  std::vector<uint8_t> regions;             // 1 Region per vertex, or empty
  std::vector<uint32_t> triangles;          // 3 per triangle, permuted order, < vertex count
  std::vector<uint16_t> triangle_material;  // 1 per triangle, < material count

  uint32_t vertex_count() const { return static_cast<uint32_t>(positions.size() / 3); }
  uint32_t triangle_count() const { return static_cast<uint32_t>(triangles.size() / 3); }
};

// The progressive mesh's levels (docs/pack-format.md §3.6; rules, views and reconstruction in
// progressive.h). The pipeline's ProgressiveMesh is one of these plus what built it.
struct PackProgressive {
  std::vector<uint32_t> collapse_to;     // ECol', one per vertex
  std::vector<uint32_t> triangle_count;  // Map, vertex_count + 1 entries
  std::vector<uint32_t> group_start;     // one per vertex
  uint32_t min_vertices = 0;
};

// Geometric error of the progressive mesh's levels (LERR, optional): at each sampled vertex
// count, the surface distance between that level and the full mesh over sampled poses of the
// clips, in model units. Vertex counts strictly increase; errors never increase with them (a
// finer level is never reported worse than a coarser one). Empty: none measured.
struct PackLevelErrors {
  std::vector<uint32_t> vertices;
  std::vector<float> max_error;  // largest distance of any sample (sampled Hausdorff)
  std::vector<float> rms_error;  // area-weighted RMS
};

// A far character's stand-in (IMPS, pack 1.8, optional; docs/pack-format.md 3.14): the
// full-resolution character seen from `views` directions around the up axis (the partition's
// up_axis), horizontally, at `frames` frames of its clips; one cell of width × height texels
// each, drawn by the runtime as a camera-facing quad where a character is a few pixels tall.
// A texel holds what the colour pass needs of the surface nearest the viewer there, so the
// instance's variety (variant, colour) still applies:
//   word 0: UV as two IEEE halves (u low);
//   word 1: normal, octahedral, two snorm8 (model space, bits 0-15) | material (bits 16-23) |
//           bind-pose height along up_axis, unorm8 over bounds (bits 24-31);
//   material kEmptyTexel: nothing there (word 0 zero, word 1 kEmptyWord1).
struct PackImpostor {
  static constexpr uint32_t kEmptyTexel = 0xFF;
  static constexpr uint32_t kEmptyWord1 = kEmptyTexel << 16;  // an empty texel: words 0 and this
  uint32_t views = 0, frames = 0, width = 0, height = 0;      // views == 0: no impostor
  // The cell's rectangle in model units: across the view from -half_width to half_width around
  // the bind-pose box's centre, along up_axis from bottom to top. Row 0 is the top.
  float half_width = 0.0f, bottom = 0.0f, top = 0.0f;
  // Per animation row, the impostor frame that shows it (< frames).
  std::vector<uint32_t> frame_of_row;
  // 2 words per texel, cells in [view][frame] order, texels row by row.
  std::vector<uint32_t> texels;

  bool empty() const { return views == 0; }
  size_t cell_texels() const { return size_t{width} * height; }
};

struct PackBounds {
  std::array<float, 3> min{0, 0, 0}, max{0, 0, 0};  // bind pose
  float radius = 0.0f;  // bounding sphere over every baked frame, around the bind-box centre
};

struct PackContents {
  std::string name;           // the character's name (input file stem)
  std::string settings_json;  // the bake settings, verbatim (for inspect and diff)
  std::vector<PackJoint> joints;
  std::vector<PackClip> clips;
  std::vector<PackMaterial> materials;
  std::vector<PackImage> images;     // IMGS (1.2, optional): the materials' base colour images
  PackVariantImages variant_images;  // VARS (1.7, optional): per-region image variants
  // VCOL (1.7, optional): the vertices' colours (COLOR_0), one RGBA8 per GEOM vertex in its
  // order, R in the low byte, colour channels sRGB-encoded (display values), alpha linear.
  // Empty: none, or every vertex white (the bake then stores none).
  std::vector<uint32_t> vertex_colors;
  PackGeometry geometry;
  PackProgressive progressive;
  PackLevelErrors level_errors;
  AnimationTexture animation;
  PartitionMask partition;
  PackBounds bounds;
  PackImpostor impostor;  // IMPS (1.8, optional): empty when not baked
};

// The frame the impostor's views are defined in (docs/pack-format.md 3.14), the one place the
// bake and the runtime take it from: `up` the partition's up axis normalised (+Y when it has no
// length), `across` = normalize(up × Z) (up × X when up is within 26° of Z), `toward` =
// across × up (where view 0 looks from), `centre` the bind-pose box's centre (BNDS).
struct ImpostorAxes {
  std::array<double, 3> up, across, toward, centre;
};
ImpostorAxes impostor_axes(const PackContents& contents);

enum class GeometryCodec : uint32_t {
  kDraco = 0,    // Draco sequential encoding (keeps vertex and face order)
  kMeshopt = 1,  // meshoptimizer vertex/index codecs (faster to decode)
  kRaw = 2,      // uncompressed
  // Coded against the progressive mesh (PROG): each vertex predicted from the one it
  // collapses into, each corner from its neighbours (GEOM v3, pack 1.6). The smallest.
  kPredictive = 3,
};

// Quantisation bits apply to kDraco and kMeshopt; kRaw always stores exact floats.
// Each is 0 (store the float exactly) or 1..24 (pack_format::kMaxQuantizationBits);
// normal_bits must be 0 or >= 2 (Draco's octahedral normals need two). Positions and UVs
// are quantised on a grid over their bounding cube: per component the error is at most
// extent / (2 * (2^bits - 1)) (docs/pack-format.md gives the measured figures).
// Skin weights are stored as unsigned integers of weight_bits (1-16; 0 keeps the floats
// exactly): each vertex's four round to integers summing to 2^bits - 1, so they decode to
// weights summing to 1 within float rounding, each within 2.5 / (2^bits - 1) of its
// original. Joints, regions and triangle materials are always stored exactly.
// kZstd (1.3): ANIM v2 stores the texels losslessly compressed (docs/pack-format.md §3.8) and
// SKEL, CLIP, PROG and PART are stored as zstd frames of their v1 payloads (version 2, §2.5).
// kNone: every chunk at version 1, which 1.2 readers read too.
enum class PackCompression : uint32_t { kNone = 0, kZstd = 1 };

struct PackWriteOptions {
  GeometryCodec codec = GeometryCodec::kPredictive;
  int position_bits = 14;  // position quantisation (0 = lossless float)
  int normal_bits = 10;
  int uv_bits = 12;
  int weight_bits = 12;  // skin weights as integers (0 = exact floats, GEOM v1)
  PackCompression compression = PackCompression::kZstd;
  // With kZstd and a kQuantized texture: the largest distance, as a fraction of the
  // bind-pose bounding-box diagonal (BNDS), that the animation coding may move a skinned
  // vertex at a baked frame from where contents.animation puts it (ANIM v3, error-bounded).
  // 0 stores the texels losslessly (ANIM v2).
  double animation_error = 0.0;
  // Threads the geometry coder may use (0 = every core); the bytes never depend on it.
  int threads = 0;
};

// The rules every pack obeys (counts consistent between parts, indices in range, no NaN,
// ProgressiveMesh structure): what write_pack() requires and read_pack() guarantees.
// docs/pack-format.md "Validity rules" lists them.
Status validate_pack_contents(const PackContents& contents);

// Serialises deterministically into `out`: equal contents and options give identical bytes.
// kInvalidArgument when validate_pack_contents() fails or an option is out of range (the
// message names the rule), kInternal if a codec fails; `out` is left as it was then.
Status write_pack(const PackContents& contents, const PackWriteOptions& options,
                  std::vector<uint8_t>& out);

// The animation texture read_pack() gives back for a pack written with `options`, and what
// the coding cost: contents.animation itself unless options.animation_error asks for the
// error-bounded coding and the texture allows it (docs/pack-format.md 3.8).
struct StoredAnimation {
  AnimationTexture texture;
  bool error_bounded = false;     // ANIM v3 error-bounded coding; false: lossless texels
  double bound = 0.0;             // model units (0 when lossless)
  double max_error = 0.0;         // largest skinned-vertex distance from contents.animation over
  double mean_error = 0.0;        // every vertex at every row, and its mean; model units
  std::string lossless_reason;    // why a requested bound was not used (empty otherwise)
  bool lossless_smaller = false;  // the reason is only that the lossless texels are smaller
  std::vector<uint8_t> coded;     // the coding as ANIM v3 stores it (empty when lossless)
};
// Fails like write_pack().
Status stored_animation(const PackContents& contents, const PackWriteOptions& options,
                        StoredAnimation& out);

// The skin weights read_pack() gives back for `geometry` written with `options` (quantized
// to the layout's weight bits, or as they are), without coding the geometry.
std::vector<float> stored_weights(const PackGeometry& geometry, const PackWriteOptions& options);

// write_pack() with the animation's storage already chosen: `animation` must be what
// stored_animation(contents, options) returned. The same bytes, without coding the animation
// a second time (the coding measures every vertex at every row: seconds on a large character).
// kInvalidArgument also when `animation` does not fit the contents.
Status write_pack(const PackContents& contents, const PackWriteOptions& options,
                  const StoredAnimation& animation, std::vector<uint8_t>& out);

// The pack's summary counts, as HEAD records them before the bulky chunks: what a streaming
// reader sizes its buffers by, and what every chunk loaded later must agree with.
struct PackCounts {
  uint32_t joints = 0, clips = 0, materials = 0, vertices = 0, triangles = 0, animation_rows = 0;
};

// The fixed header (docs/pack-format.md 2.1): version, where the chunk table is, the recorded
// file size.
struct PackHeader {
  uint16_t version_major = 0, version_minor = 0;
  uint32_t chunk_count = 0;
  uint64_t table_offset = 0;
  uint64_t file_size = 0;
};

struct PackChunk {
  uint32_t tag = 0;      // four ASCII characters, little-endian (pack_format::kTagGeom, ...)
  uint32_t version = 0;  // per-chunk layout version
  uint64_t offset = 0;   // from the start of the file, 16-byte aligned
  uint64_t size = 0;     // payload bytes
  uint32_t checksum = 0;
};

// Reads the header and chunk table only (cheap; for streaming and inspect). `size` may
// be just the front of the file (at least the header and table): chunk offsets and sizes
// are checked against the file size the header records, the header/table checksum is
// verified, nothing else. Chunks are returned in file order, unknown tags included.
Status read_pack_chunks(const uint8_t* data, size_t size, std::vector<PackChunk>& chunks,
                        uint16_t* version_major = nullptr, uint16_t* version_minor = nullptr);

// The header alone, from the file's first bytes (at least pack_format::kHeaderSize): magic,
// version and the table's place, checked for what the header can say by itself. A streaming
// reader reads this, then the table with read_pack_chunks. The checksum covers the table too,
// so read_pack_chunks verifies it.
Status read_pack_header(const uint8_t* data, size_t size, PackHeader& out);

// Verifies one chunk's checksum and decodes it into its part of `out` (HEAD: name and
// settings; SKEL: joints; ...). `payload` points at the chunk's `chunk.size` bytes. Checks
// everything inside the chunk; rules that span chunks are check_pack_chunk's, which read_pack()
// and validate_pack_contents() apply to a whole pack. Unknown tags are accepted and ignored.
// For streaming GEOM, ANIM and PART separately. HEAD's counts go to *counts (may be null).
Status read_pack_chunk(const PackChunk& chunk, const uint8_t* payload, PackContents& out,
                       PackCounts* counts = nullptr);

// The rules between the chunk `tag` (decoded into `contents`) and the others, for a reader
// that loads chunks one at a time: its counts agree with HEAD's `counts`, and its indices are
// in range of them (GEOM: joints, materials; CLIP: texture rows; MATL: the images; PROG and
// LERR: vertices and triangles; ANIM: joints per row). kInvalidPack "chunk GEOM: ..." when
// one is broken; ok for tags without such rules.
Status check_pack_chunk(uint32_t tag, const PackContents& contents, const PackCounts& counts);

// Parses and validates every size, offset, count, index and checksum. Never crashes,
// hangs or allocates more than a small multiple of `size` on any input (a compressed
// GEOM chunk decodes to at most pack_format::kGeomExpansionRatio times its size plus
// pack_format::kGeomExpansionSlack). On failure `out` holds partial contents.
Status read_pack(const uint8_t* data, size_t size, PackContents& out);

// A whole pack as its file holds it: the chunk table as stored and the decoded, validated
// contents (what inspect and diff look at).
struct PackFile {
  std::string path;    // where it was read from (set by the caller; for messages)
  uint64_t bytes = 0;  // file size
  uint16_t version_major = 0, version_minor = 0;
  std::vector<PackChunk> chunks;  // file order, unknown tags included
  PackContents contents;
};

// read_pack_chunks + read_pack into a PackFile (path left as it was).
Status read_pack_file(const uint8_t* data, size_t size, PackFile& out);

// "head", "upper body", "trousers", "unused"; "unknown" otherwise.
const char* region_name(uint8_t region);

// The bind-pose bounding box diagonal (bounds.min..max); 0 for an empty box.
double bbox_diagonal(const PackContents& contents);

// "opaque", "mask", "blend".
const char* alpha_mode_name(AlphaMode mode);

// Short names for reports: "predictive", "draco", "meshopt", "raw".
const char* geometry_codec_name(GeometryCodec codec);

}  // namespace crowdbake
