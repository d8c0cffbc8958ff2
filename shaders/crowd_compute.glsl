// Bindings shared by the crowd's compute passes (runtime/gpu/crowd_compute.cpp binds the same
// buffers, in this order, to every pass; the C++ mirrors of the structs are in
// crowd_compute.h (InstanceLod, TypeRange) and crowd_compute.cpp (the rest)).
#ifndef CROWDBAKE_CROWD_COMPUTE_GLSL
#define CROWDBAKE_CROWD_COMPUTE_GLSL

#extension GL_GOOGLE_include_directive : require

#include "instance.glsl"

const uint kGroupSize = 256u;        // instances per workgroup in the per-instance passes
const uint kChunk = 256u;            // corners per reconstruction chunk (one instance, 64 threads)
const uint kChunksPerGroup = 4u;     // chunks per reconstruction workgroup
const uint kBuildCorners = 2048u;    // corners of a cached level per reconstruction workgroup
const uint kMaxTypes = 1024u;        // scan keys (lod_assign's shared running sums)
const uint kMaxLevels = 8u;          // static levels per type (kMaxDiscreteLevels)
const uint kSaturated = 0x7FFFFFFFu;  // corner sums saturate here (never fit the buffer)
const uint kNotDrawn = 0xFFFFFFFFu;

const uint kModeContinuous = 0u;
const uint kModeDiscrete = 1u;
const uint kModeFull = 2u;
const uint kModeError = 3u;
const uint kLadderSteps = 32u;  // kErrorLadderSteps

struct TypeData {
  vec4 bounds;  // bounding sphere of the type (centre, radius), model space
  uint min_vertices, max_vertices, triangles, vertex_count;
  uint level_count, progressive, tri_offset, collapse_offset;  // offsets into mesh_data
  uint tcount_offset, group_offset, mesh_triangles, pad1;  // mesh_triangles: GEOM's count
  uint levels[8];          // discrete levels, finest first
  double type_log_weight;  // lod_type_log_weight(α, triangles)
  double pad2;
  // Level cache (continuous frames on the instanced path): the type's keys are
  // key_base + n' for n' in 0..vertex_count; its slots slot_base .. + slot_count, each
  // slot_stride indices from cache_base; its draw commands cmd_base .. + slot_count.
  uint key_base, slot_base, slot_count, slot_stride;
  uint cache_base, cmd_base;
  uint error_offset, error_count;  // level errors in mesh_data: vertices, then max (float bits)
};

struct InstanceLod {
  uint selected;       // n_i, the selected vertex count (0 = not drawn)
  uint usable;         // n' = usable_vertices(n_i)
  uint corners;        // 3 · triangle_count[n'] (0 when not drawn)
  uint corner_offset;  // first corner in the corner buffer, kNotDrawn when culled/overflowing
  uint local_corner;   // corners of earlier same-type instances in the workgroup
  uint local_draw;     // drawn earlier same-type instances in the workgroup
  uint visible;
  uint local_chunk;    // reconstruction chunks of earlier same-type instances in the workgroup
  float morph;         // the geomorph's continuous count x_i (LodSelectJob::morph; 0: none)
};

struct TypeRange {
  uint corner_base;   // first corner of the type in the corner buffer
  uint corner_total;  // corners the type asked for (saturating)
  uint draw_base;     // first entry of the type in the draw list
  uint draw_total;    // drawn instances of the type (before overflow)
  uint drawn_end;     // end of the type's corners that fit (atomicMax)
  uint chunk_base;    // first reconstruction chunk of the type
  uint chunk_total;   // chunks the type asked for (saturating)
  uint pad0;
};

struct Stats {
  double weight_sum;
  uint visible, drawn, at_max, in_range;
  uint promoted, dropped, overflow, fitting;
  uint drawn_corners, selected_lo, selected_hi, requested_lo;
  uint requested_hi, chunks, levels_drawn, levels_built;  // chunks: reconstruction workgroups
  uint coarser, error_step;  // coarser: instances drawn at a coarser cached level (cache full)
  uint build_corners, pad6;  // the most corners of a level built this frame
};

layout(std430, set = 0, binding = 0) readonly buffer ParamsBuffer {
  vec4 eye_focal;  // eye position, focal_pixels
  vec4 planes[6];
  double screen;  // width · height in pixels
  double alpha;
  double budget;
  double min_t;
  uint instance_count;
  uint type_count;
  uint mode;
  uint corner_capacity;
  uint group_count;
  float near_plane;
  uint instanced;      // 1: static levels drawn instanced (full/discrete), no corner buffer
  uint key_count;      // scan keys: types, or types · kMaxLevels when instanced
  uint indexed_slots;  // VkDrawIndexedIndirectCommands in indexed_args (0 when none)
  uint drop_below_min_t;  // 1: the MinT rule drops instances (LodSettings::drop_below_min_t)
  uint cached;  // 1: a continuous frame drawn instanced from the level cache
  uint frame;   // frame number of the level cache's use marks (never 0)
  float max_pixel_error;  // error mode: P
  uint key_total;         // level-cache keys of all types
  uint scan_keys_per_group;  // scan_types: keys per workgroup (bounds a lane's loops)
  uint pad5;
} params;
layout(std430, set = 0, binding = 1) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer Types { TypeData types[]; };
layout(std430, set = 0, binding = 3) readonly buffer MeshData { uint mesh_data[]; };
layout(std430, set = 0, binding = 4) buffer Weights { double weights[]; };
layout(std430, set = 0, binding = 5) buffer Partials { double partials[]; };
layout(std430, set = 0, binding = 6) buffer Lods { InstanceLod lods[]; };
// [group][type]: (corners, drawn, chunks) of the workgroup, then their exclusive prefix
layout(std430, set = 0, binding = 7) buffer GroupSums { uvec4 group_sums[]; };
layout(std430, set = 0, binding = 8) buffer TypeRanges { TypeRange ranges[]; };
// Two per drawn instance, in corner order: (instance, first corner, first chunk, corners) and
// (tri_offset, collapse_offset, usable n', progressive) — all reconstruction needs.
layout(std430, set = 0, binding = 9) buffer DrawList { uvec4 draw_list[]; };
layout(std430, set = 0, binding = 10) writeonly buffer Corners { uvec2 corners[]; };
layout(std430, set = 0, binding = 11) buffer DrawArgs { uint draw_args[]; };  // 4 per type
layout(std430, set = 0, binding = 12) buffer DispatchArgs { uint dispatch_args[]; };
layout(std430, set = 0, binding = 13) buffer StatsBuffer { Stats stats; };
// Draw-list entry of each reconstruction chunk.
layout(std430, set = 0, binding = 14) buffer ChunkTable { uint chunk_entry[]; };
// Instanced static levels: (first index, index count) of slot type · kMaxLevels + level in the
// level index buffer, one VkDrawIndexedIndirectCommand (5 uints) per slot, and the instances
// of each slot (firstInstance = the slot's first entry).
layout(std430, set = 0, binding = 15) readonly buffer LevelRanges { uvec2 level_ranges[]; };
layout(std430, set = 0, binding = 16) buffer IndexedArgs { uint indexed_args[]; };
layout(std430, set = 0, binding = 17) buffer InstanceList { uint instance_list[]; };
// Level cache. Per key: this frame's instance count (cleared every frame); (slot or
// kNotDrawn, first instance-list entry, rank in miss_keys, type) — the slot persists across
// frames, the type is fixed. Per slot: (key or kNotDrawn, frame last drawn), persistent. This
// frame's levels to reconstruct: (slot, key, type, 0). The cached indices. Per type: the clock
// hand of its slots, persistent; this frame's (used slots, kNotDrawn − coarsest drawn key with
// a slot), cleared every frame. This frame's drawn keys without a slot, in key order.
layout(std430, set = 0, binding = 18) buffer KeyCounts { uint key_counts[]; };
layout(std430, set = 0, binding = 19) buffer KeyStates { uvec4 key_states[]; };
layout(std430, set = 0, binding = 20) buffer SlotStates { uvec2 slot_states[]; };
layout(std430, set = 0, binding = 21) buffer BuildList { uvec4 build_list[]; };
layout(std430, set = 0, binding = 22) buffer LevelCache { uint level_cache[]; };
layout(std430, set = 0, binding = 23) buffer CacheHands { uint cache_hands[]; };
// Error mode: Σ n_i at each ladder step, as (lo, hi) 32-bit halves, cleared every frame.
layout(std430, set = 0, binding = 24) buffer LadderSums { uvec2 ladder_sums[]; };
layout(std430, set = 0, binding = 25) buffer TypeMarks { uvec2 type_marks[]; };
layout(std430, set = 0, binding = 26) buffer MissKeys { uint miss_keys[]; };

uint sat_add(uint a, uint b) { return min(a + b, kSaturated); }  // a, b <= kSaturated

// Level cache: a key drawn this frame that holds no slot.
bool level_cache_miss(uint key) { return key_counts[key] > 0u && key_states[key].x == kNotDrawn; }

// note: 64-bit sums as (lo, hi) pairs with carries, so no shaderInt64 is needed.
#define ADD64(lo, hi, value)                      \
  {                                               \
    const uint old_ = atomicAdd(lo, value);       \
    if (old_ + (value) < old_) atomicAdd(hi, 1u); \
  }

// Error mode, as lod_select_job.cpp: λ_j = 2^(j/3) (lod_error_ladder) and n_i(t)
// (lod_vertices_for_error), operation by operation.
double lod_error_ladder(uint step) {
  const double thirds[3] = double[3](1.0lf, 1.2599210498948732lf, 1.5874010519681994lf);
  return ldexp(thirds[step % 3u], int(step / 3u));
}

uint lod_vertices_for_error(TypeData t, double threshold, out double continuous) {
  uint n = t.max_vertices;
  if (t.error_count == 0u ||
      threshold >= double(uintBitsToFloat(mesh_data[t.error_offset + t.error_count]))) {
    n = t.error_count != 0u ? mesh_data[t.error_offset] : t.max_vertices;
    continuous = double(n) + 1.0lf;
  } else {
    for (uint k = 1u; k < t.error_count; ++k) {
      const double hi = double(uintBitsToFloat(mesh_data[t.error_offset + t.error_count + k - 1u]));
      const double lo = double(uintBitsToFloat(mesh_data[t.error_offset + t.error_count + k]));
      if (!(threshold >= lo)) continue;
      const uint v0 = mesh_data[t.error_offset + k - 1u], v1 = mesh_data[t.error_offset + k];
      precise double span = double(v1 - v0);
      precise double at = double(v0) + span * ((hi - threshold) / (hi - lo));
      n = uint(min(ceil(at), double(v1)));
      continuous = at + 1.0lf;
      break;
    }
  }
  return clamp(n, t.min_vertices, t.max_vertices);
}

// Triangles of the usable count n' (ReconstructJob: the pack's prefix T(n')).
uint level_triangles(TypeData t, uint usable) {
  return t.progressive != 0u ? mesh_data[t.tcount_offset + usable] : t.mesh_triangles;
}

// Corner `corner` of level n' (`usable`): the pack's triangle corner walked down the collapse
// chain (`while v >= n'`), as ReconstructJob does.
uint walk_corner(uint tri_offset, uint collapse_offset, bool progressive, uint usable,
                 uint corner) {
  uint v = mesh_data[tri_offset + corner];
  if (progressive) {
    while (v >= usable) {
      const uint next = mesh_data[collapse_offset + v];
      if (next >= v) break;
      v = next;
    }
  }
  return v;
}

uint level_corner(TypeData t, uint usable, uint corner) {
  return walk_corner(t.tri_offset, t.collapse_offset, t.progressive != 0u, usable, corner);
}

// The scan key of a drawn instance: its type, or with instanced static levels its slot
// type · kMaxLevels + level (the first level equal to its count; full mode has one level).
uint draw_key(TypeData t, uint type, uint selected) {
  if (params.instanced == 0u) return type;
  uint level = 0u;
  if (params.mode == kModeDiscrete) {
    for (uint k = 0u; k < t.level_count; ++k) {
      if (t.levels[k] == selected) {
        level = k;
        break;
      }
    }
  }
  return type * kMaxLevels + level;
}

// (corners, drawn, chunks) sums: corners and chunks saturate, drawn counts cannot overflow.
uvec3 sum3(uvec3 a, uvec3 b) { return uvec3(sat_add(a.x, b.x), a.y + b.y, sat_add(a.z, b.z)); }

#endif
