// The validity rules of pack contents (docs/pack-format.md "Validity rules"), one
// function per part so the reader can check each chunk as it decodes it. Each returns an
// empty string when the part is valid, otherwise what is wrong (first problem only).
#pragma once

#include <string>

#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

std::string check_joints(const std::vector<PackJoint>& joints);
std::string check_clips(const std::vector<PackClip>& clips);
std::string check_materials(const std::vector<PackMaterial>& materials);
std::string check_images(const std::vector<PackImage>& images);
// "image/png", "image/jpeg" from the bytes' signature; empty for anything else.
std::string image_type(const std::vector<uint8_t>& bytes);
std::string check_bounds(const PackBounds& bounds);
std::string check_progressive(const PackProgressive& progressive);
std::string check_level_errors(const PackLevelErrors& errors);
std::string check_geometry(const PackGeometry& geometry);
std::string check_animation(const AnimationTexture& animation);
std::string check_partition(const PartitionMask& partition);
// Shape, rectangle, frame indices and texels (materials are checked against MATL with the
// cross references).
std::string check_impostor(const PackImpostor& impostor);
// Rules between parts: joint and material indices, clip rows, progressive sizes.
std::string check_cross_references(const PackContents& contents);

}  // namespace crowdbake::pack_io
