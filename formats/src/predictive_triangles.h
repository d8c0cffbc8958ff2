// The triangles of the predictive GEOM codec (docs/pack-format.md 3.7, codec 3): each corner
// is named by its place in a list of likely positions (neighbours of the triangle's other
// corners, the positions of the split that added the triangle, recently used positions) and
// which vertex of that position it is; other corners by their rank among the vertices not
// used yet, or by their distance from the level's vertex count.
#pragma once

#include <cstdint>
#include <vector>

#include "byte_reader.h"
#include "byte_writer.h"
#include "crowdbake/formats/pack.h"

namespace crowdbake::pack_io {

// `position_keys`: three integers per vertex; vertices with equal keys share a position
// (the quantised positions, which the decoder has before the triangles). `prog` may be null
// (then no level is known); it must satisfy PROG's structural rules for `vertex_count`.
// The symbol streams are coded on `threads` (0 = every core); the bytes never depend on it.
void put_predictive_triangles(ByteWriter& out, const std::vector<uint32_t>& triangles,
                              uint32_t vertex_count, const std::vector<uint32_t>& position_keys,
                              const PackProgressive* prog, int threads = 1);

bool get_predictive_triangles(ByteReader& in, uint32_t triangle_count, uint32_t vertex_count,
                              const std::vector<uint32_t>& position_keys,
                              const PackProgressive* prog, std::vector<uint32_t>& triangles);

}  // namespace crowdbake::pack_io
