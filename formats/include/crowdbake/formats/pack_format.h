// The one place for the pack's version numbers, magic, chunk tags, chunk versions and
// reader limits (docs/pack-format.md). Bumping kPackVersionMajor or any chunk version
// means old packs must be re-baked: say so in docs/CHANGES.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace crowdbake {

constexpr uint16_t kPackVersionMajor = 1;  // incompatible layout changes: re-bake packs
// additions; 1.3: ANIM v2 (compressed texels); 1.4: GEOM v2 (quantised skin weights);
// 1.5: ANIM v3 (error-bounded animation coding); 1.6: GEOM v3 (the predictive codec);
// 1.7: VARS (per-region variant images), VCOL (vertex colours); 1.8: IMPS (impostor)
constexpr uint16_t kPackVersionMinor = 8;

namespace pack_format {

// "\x89CROWD\r\n": the high byte catches 7-bit transfers, CR LF catches newline translation.
constexpr std::array<uint8_t, 8> kMagic = {0x89, 'C', 'R', 'O', 'W', 'D', '\r', '\n'};
constexpr size_t kHeaderSize = 48;
constexpr size_t kChunkEntrySize = 32;
constexpr size_t kAlignment = 16;  // every chunk starts at a multiple of this

constexpr uint32_t make_tag(char a, char b, char c, char d) {
  return static_cast<uint32_t>(static_cast<uint8_t>(a)) |
         static_cast<uint32_t>(static_cast<uint8_t>(b)) << 8 |
         static_cast<uint32_t>(static_cast<uint8_t>(c)) << 16 |
         static_cast<uint32_t>(static_cast<uint8_t>(d)) << 24;
}

// Chunks in the order the writer stores them: small tables first, bulky data last, so a
// runtime can read the front of the file and stream GEOM, ANIM and PART on demand.
constexpr uint32_t kTagHead = make_tag('H', 'E', 'A', 'D');  // name, settings, counts
constexpr uint32_t kTagSkel = make_tag('S', 'K', 'E', 'L');  // joints
constexpr uint32_t kTagClip = make_tag('C', 'L', 'I', 'P');  // clip table, root motion
constexpr uint32_t kTagMatl = make_tag('M', 'A', 'T', 'L');  // materials
constexpr uint32_t kTagMatx =
    make_tag('M', 'A', 'T', 'X');  // material images, alpha (1.2, optional)
constexpr uint32_t kTagVars =
    make_tag('V', 'A', 'R', 'S');  // per-region variant images (1.7, optional)
constexpr uint32_t kTagBnds = make_tag('B', 'N', 'D', 'S');  // bounds
constexpr uint32_t kTagProg = make_tag('P', 'R', 'O', 'G');  // ProgressiveMesh arrays
constexpr uint32_t kTagLerr = make_tag('L', 'E', 'R', 'R');  // level errors (1.1, optional)
constexpr uint32_t kTagGeom = make_tag('G', 'E', 'O', 'M');  // vertices and triangles
constexpr uint32_t kTagAnim = make_tag('A', 'N', 'I', 'M');  // animation texture
constexpr uint32_t kTagPart = make_tag('P', 'A', 'R', 'T');  // partition mask
constexpr uint32_t kTagVcol =
    make_tag('V', 'C', 'O', 'L');  // vertex colours (1.7, optional; read with GEOM)
constexpr uint32_t kTagImgs = make_tag('I', 'M', 'G', 'S');  // material images (1.2, optional)
constexpr uint32_t kTagImps =
    make_tag('I', 'M', 'P', 'S');  // impostor (1.8, optional; read with PART)

// Layout version of each chunk's payload this build writes and reads (it reads exactly
// these; any other version of a known chunk is rejected).
constexpr uint32_t kHeadVersion = 1;
// SKEL, CLIP, PROG and PART: version 2 is the version-1 payload as one zstd frame (§2.5).
constexpr uint32_t kWrappedVersion = 2;
constexpr uint32_t kSkelVersion = 1;
constexpr uint32_t kClipVersion = 1;
constexpr uint32_t kMatlVersion = 1;
constexpr uint32_t kBndsVersion = 1;
constexpr uint32_t kProgVersion = 1;
constexpr uint32_t kLerrVersion = 1;
constexpr uint32_t kGeomVersion = 3;          // v3: the predictive codec (§3.7)
constexpr uint32_t kGeomWeightsVersion = 2;   // v2: skin weights may be quantised
constexpr uint32_t kGeomOldestVersion = 1;    // written when weights are stored exactly
constexpr uint32_t kAnimVersion = 3;          // v3: error-bounded coding (compression 2)
constexpr uint32_t kAnimLosslessVersion = 2;  // v2: texels stored compressed losslessly
constexpr uint32_t kAnimOldestVersion = 1;    // written with PackCompression::kNone
// ANIM's compression field (v2 and later): 0 none, 1 zstd (lossless), 2 error-bounded (v3).
constexpr uint32_t kAnimCompressionBounded = 2;
constexpr uint32_t kPartVersion = 1;
constexpr uint32_t kMatxVersion = 1;
constexpr uint32_t kImgsVersion = 1;
constexpr uint32_t kVarsVersion = 1;
constexpr uint32_t kVcolVersion = 1;  // 2: the v1 payload as a zstd frame (§2.5)
constexpr uint32_t kImpsVersion = 1;  // 2: the v1 payload as a zstd frame (§2.5)

// Header flags: bits 0-15 are required features (a reader rejects a pack with a bit it
// does not know), bits 16-31 optional hints (ignored when unknown). v1.0 defines none.
constexpr uint32_t kRequiredFlagsMask = 0x0000ffffu;

// Reader limits (docs/pack-format.md "Limits"). Counts above these are rejected before
// anything is allocated.
constexpr uint32_t kMaxChunks = 256;
constexpr uint32_t kMaxVariantImages = 255;        // per region: an instance's choice is one byte
constexpr uint32_t kMaxStringBytes = 65536;        // names, texture references
constexpr uint32_t kMaxSettingsBytes = 16u << 20;  // HEAD settings_json
constexpr uint32_t kMaxJoints = 65535;             // joint indices are uint16
constexpr uint32_t kMaxClips = 65535;
constexpr uint32_t kMaxMaterials = 65535;  // material indices are uint16
constexpr uint32_t kMaxVertices = 1u << 24;
constexpr uint32_t kMaxTriangles = 1u << 25;
constexpr uint32_t kMaxDecodeParams = 4096;
// ANIM v2's decoded texels (compressed, so not bounded by the file's size).
constexpr uint64_t kMaxAnimationBytes = uint64_t{512} << 20;
constexpr uint32_t kMaxTextureSide = 16384;  // partition mask width/height
constexpr uint32_t kMaxImages = 4096;
constexpr uint32_t kMaxImageSide = 8192;        // material image width/height
constexpr uint32_t kMaxImageBytes = 64u << 20;  // one stored (encoded) image
constexpr uint32_t kMaxQuantizationBits = 24;   // 0 = unquantised float
constexpr uint32_t kMaxWeightBits = 16;         // skin weights are stored as uint16
constexpr uint32_t kMaxImpostorSide = 256;      // impostor cell width/height, views
constexpr uint32_t kMaxImpostorFrames = 65535;
constexpr uint64_t kMaxImpostorTexels = uint64_t{1} << 24;
// A compressed GEOM chunk may not decode to more than this many bytes of arrays plus
// kGeomExpansionRatio times its own size: bounds what a small hostile file can allocate.
constexpr uint64_t kGeomExpansionSlack = 1u << 20;
constexpr uint64_t kGeomExpansionRatio = 512;
// The same bound for a zstd-wrapped chunk's payload (§2.5).
constexpr uint64_t kWrappedExpansionSlack = 1u << 20;
constexpr uint64_t kWrappedExpansionRatio = 512;

// "GEOM" for printable tags, "0x1234abcd" otherwise.
std::string tag_name(uint32_t tag);

}  // namespace pack_format
}  // namespace crowdbake
