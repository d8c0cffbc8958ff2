// The pack's zstd compression (1.3): whole chunk payloads as one zstd frame (§2.5), and the
// animation texels of ANIM v2 (docs/pack-format.md §3.8), whose texels are read as 16-bit lanes
// (every encoding's texels are whole lanes), each (joint, lane) series over the rows is replaced by
// its residual against a linear prediction from the two rows before (wrapping 16-bit arithmetic,
// zigzag-mapped so small residuals of either sign are small), the low bytes of all residuals are
// followed by their high bytes, and the result is one zstd frame. Decoding gives back the texels
// bit for bit, so the animated error is the encoding's own (docs/animation-encoding.md).
//
// Why this filter: joint transforms change smoothly from frame to frame, so the second
// difference of a lane is mostly a few units; the byte planes put the near-constant high
// bytes together. docs/pack-sizes.md measures it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

// The zstd frame of `texture`'s texels (texture.data), as described above.
// Throws std::runtime_error if zstd fails.
std::vector<uint8_t> compress_animation_texels(const AnimationTexture& texture);

// Fills texture.data (texture.rows · width() · bytes_per_texel bytes, which the caller has
// checked against its limits) from `frame`. False with a reason when the frame is not one
// zstd frame of exactly that many bytes.
bool decompress_animation_texels(const uint8_t* frame, size_t size, AnimationTexture& texture,
                                 std::string* why);

// Whether a chunk with this tag may be stored as a zstd frame of its version-1 payload
// (version kWrappedVersion): SKEL, CLIP, PROG and PART.
bool is_wrappable(uint32_t tag);

// A chunk payload stored as one zstd frame (docs/pack-format.md §2.5): `bytes` compressed.
// Throws std::runtime_error if zstd fails.
std::vector<uint8_t> zstd_frame(const std::vector<uint8_t>& bytes);

// Expands one zstd frame of exactly `size` bytes that declares its content size, at most
// `limit` bytes. False with a reason otherwise.
bool expand_zstd_frame(const uint8_t* frame, size_t size, uint64_t limit, std::vector<uint8_t>& out,
                       std::string* why);

}  // namespace crowdbake::pack_io
