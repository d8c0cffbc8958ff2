// Payload of each chunk (docs/pack-format.md, one section per chunk): an encoder that
// appends it to a ByteWriter and a decoder that parses it from a ByteReader spanning
// exactly the chunk, checks everything local to the chunk, and fills its part of
// PackContents. Decoders return false with the reader's message set.
#pragma once

#include <cstdint>

#include "byte_reader.h"
#include "byte_writer.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

// HEAD's summary counts (PackCounts), so a streaming runtime can size buffers before the
// bulky chunks arrive; every chunk is checked against them (check_pack_chunk).
using HeadCounts = PackCounts;
HeadCounts head_counts(const PackContents& contents);

// check_pack_chunk's rules without the "chunk " in front: "GEOM: vertex 3 uses joint 9, ...",
// or "" when the chunk agrees with `counts`.
std::string chunk_rule_problem(uint32_t tag, const PackContents& contents,
                               const HeadCounts& counts);

void encode_head(const PackContents& c, ByteWriter& out);
bool decode_head(ByteReader& in, PackContents& out, HeadCounts& counts);

void encode_skeleton(const std::vector<PackJoint>& joints, ByteWriter& out);
bool decode_skeleton(ByteReader& in, std::vector<PackJoint>& out);

void encode_clips(const std::vector<PackClip>& clips, ByteWriter& out);
bool decode_clips(ByteReader& in, std::vector<PackClip>& out);

void encode_materials(const std::vector<PackMaterial>& materials, ByteWriter& out);
bool decode_materials(ByteReader& in, std::vector<PackMaterial>& out);
// MATX (1.2): the fields of PackMaterial after MATL's (image, transform, alpha, sides).
void encode_material_extras(const std::vector<PackMaterial>& materials, ByteWriter& out);
bool decode_material_extras(ByteReader& in, std::vector<PackMaterial>& out);
bool has_material_extras(const std::vector<PackMaterial>& materials);
void encode_images(const std::vector<PackImage>& images, ByteWriter& out);
bool decode_images(ByteReader& in, std::vector<PackImage>& out);
// VCOL (1.7): one RGBA8 per vertex.
void encode_vertex_colors(const std::vector<uint32_t>& colors, ByteWriter& out);
bool decode_vertex_colors(ByteReader& in, std::vector<uint32_t>& out);
// VARS (1.7): per region, the first image and how many.
void encode_variant_images(const PackVariantImages& variants, ByteWriter& out);
bool decode_variant_images(ByteReader& in, PackVariantImages& out);
void encode_impostor(const PackImpostor& impostor, ByteWriter& out);
bool decode_impostor(ByteReader& in, PackImpostor& out);
// Counts and rectangle in range (empty when fine); the arrays are not looked at.
std::string impostor_shape_problem(const PackImpostor& impostor);

void encode_bounds(const PackBounds& bounds, ByteWriter& out);
bool decode_bounds(ByteReader& in, PackBounds& out);

void encode_progressive(const PackProgressive& progressive, ByteWriter& out);
bool decode_progressive(ByteReader& in, PackProgressive& out);
void encode_level_errors(const PackLevelErrors& errors, ByteWriter& out);
bool decode_level_errors(ByteReader& in, PackLevelErrors& out);

// The predictive codec codes against `progressive`; its decoder needs the same arrays.
void encode_geometry(const PackGeometry& geometry, const PackProgressive& progressive,
                     const PackWriteOptions& options, ByteWriter& out);
// The GEOM version write_pack uses: v3 for the predictive codec, v2 when weights are
// quantised, else v1 (§3.7).
uint32_t geometry_version(const PackGeometry& geometry, const PackWriteOptions& options);
bool decode_geometry(ByteReader& in, uint32_t version, const PackProgressive& progressive,
                     PackGeometry& out);

// ANIM v2 when `compressed` (the texels as one zstd frame), v1 otherwise.
// `bounded_frame` (may be null): the error-bounded coding's stream as one zstd frame, to store
// instead of the texels (ANIM v3, compression 2).
void encode_animation(const AnimationTexture& animation, bool compressed,
                      const std::vector<uint8_t>* bounded_frame, ByteWriter& out);
bool decode_animation(ByteReader& in, uint32_t version, AnimationTexture& out);

void encode_partition(const PartitionMask& partition, ByteWriter& out);
bool decode_partition(ByteReader& in, PartitionMask& out);

}  // namespace crowdbake::pack_io
