#version 450
// Pass 3: each instance's vertex count n_i (LodSelectJob's pass 2, clamping exactly as
// lod_select_job.h), its usable count n' and corner count 3·T(n'), the workgroup's per-type
// exclusive prefix of (corners, drawn) in instance order, and the statistics.
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"

layout(local_size_x = 256) in;

shared uvec3 lane_values[256];
shared uint lane_types[256];
shared uvec3 type_running[kMaxTypes];
shared uint counts[8];  // visible, drawn, at_max, in_range, promoted, dropped, sel lo, sel hi
shared uint requested_lo, requested_hi;

// usable_vertices (reconstruct_job.cpp).
uint usable_vertices(TypeData t, uint n) {
  if (t.progressive == 0u) return t.vertex_count;
  if (n < t.min_vertices) n = t.min_vertices;
  if (n >= t.vertex_count) return t.vertex_count;
  const uint start = mesh_data[t.group_offset + n];
  return start < n ? start : n;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint lid = gl_LocalInvocationID.x;
  if (lid < 8u) counts[lid] = 0u;
  if (lid == 0u) {
    requested_lo = 0u;
    requested_hi = 0u;
  }
  barrier();

  // Error mode: the smallest ladder step whose Σ n_i fits the budget (lod_weights summed them).
  uint step = kLadderSteps - 1u;
  if (params.mode == kModeError) {
    for (uint j = 0u; j < kLadderSteps; ++j)
      if (ladder_sums[j].y == 0u && double(ladder_sums[j].x) <= params.budget) {
        step = j;
        break;
      }
    if (i == 0u) stats.error_step = step;
  }
  uint type = 0xFFFFFFFFu;
  uint selected = 0u, usable = 0u, corner_count = 0u;
  double morph = 0.0lf;  // LodSelectJob::morph
  if (i < params.instance_count) {
    type = instances[i].type;
    const TypeData t = types[type];
    const bool visible = lods[i].visible != 0u;
    if (visible) {
      atomicAdd(counts[0], 1u);
      if (params.mode == kModeFull) {
        selected = t.max_vertices;
      } else if (params.mode == kModeError) {
        precise double t_step = lod_error_ladder(step) * weights[i];
        selected = lod_vertices_for_error(t, t_step, morph);
        atomicAdd(counts[selected == t.max_vertices ? 2 : 3], 1u);
      } else {
        const double sum = stats.weight_sum;
        precise double vc = sum > 0.0lf ? params.budget * weights[i] / sum : 0.0lf;
        if (params.mode == kModeContinuous) morph = vc;
        if (vc > double(t.max_vertices)) {
          selected = t.max_vertices;
          atomicAdd(counts[2], 1u);
        } else if (vc >= double(t.min_vertices)) {
          selected = uint(floor(vc));
          atomicAdd(counts[3], 1u);
        } else if (params.drop_below_min_t == 0u || vc / double(t.min_vertices) >= params.min_t) {
          selected = t.min_vertices;
          atomicAdd(counts[4], 1u);
        } else {
          atomicAdd(counts[5], 1u);
          morph = 0.0lf;
        }
        if (params.mode == kModeDiscrete && selected > 0u) {
          uint level = t.levels[t.level_count - 1u];
          for (uint k = 0u; k < t.level_count; ++k) {
            if (t.levels[k] <= selected) {
              level = t.levels[k];
              break;
            }
          }
          selected = level;
        }
      }
    }
    if (selected > 0u) {
      atomicAdd(counts[1], 1u);
      ADD64(counts[6], counts[7], selected);
      usable = usable_vertices(t, selected);
      corner_count = min(3u * level_triangles(t, usable), kSaturated);
      ADD64(requested_lo, requested_hi, corner_count);
      // note: the rank within the key is taken in any order (it changes no pixel).
      if (params.cached != 0u) lods[i].local_draw = atomicAdd(key_counts[t.key_base + usable], 1u);
    }
    lods[i].selected = selected;
    lods[i].usable = usable;
    lods[i].corners = corner_count;
    lods[i].morph = float(morph);
  }

  // Per-type exclusive prefix of (corners, drawn, chunks) within the workgroup, in instance
  // order: one thread walks the 256 instances with a running sum per type. (Three barriers
  // whatever the type count; on a CPU device such as llvmpipe, which runs a workgroup's
  // invocations in turn, barriers cost far more than 256 additions.)
  // With instanced static levels the key is the (type, level) slot and only the instance
  // count matters (no corners are written).
  uint key = type;
  if (i < params.instance_count && selected > 0u) key = draw_key(types[type], type, selected);
  lane_values[lid] = params.instanced != 0u
                         ? uvec3(0u, selected > 0u ? 1u : 0u, 0u)
                         : uvec3(corner_count, corner_count > 0u ? 1u : 0u,
                                 (corner_count + kChunk - 1u) / kChunk);
  lane_types[lid] = i < params.instance_count ? key : 0xFFFFFFFFu;
  for (uint t = lid; t < params.key_count; t += 256u) type_running[t] = uvec3(0u);
  barrier();
  if (lid == 0u) {
    for (uint k = 0u; k < 256u; ++k) {
      const uint t = lane_types[k];
      if (t >= params.key_count) continue;
      const uvec3 v = lane_values[k];
      lane_values[k] = type_running[t];
      type_running[t] = sum3(type_running[t], v);
    }
  }
  barrier();
  const uvec3 exclusive = lane_values[lid];
  for (uint t = lid; t < params.key_count; t += 256u)
    group_sums[gl_WorkGroupID.x * params.key_count + t] = uvec4(type_running[t], 0u);
  if (i < params.instance_count && params.cached == 0u) {
    lods[i].local_corner = exclusive.x;
    lods[i].local_draw = exclusive.y;
    lods[i].local_chunk = exclusive.z;
  }

  barrier();
  if (lid == 0u) {
    atomicAdd(stats.visible, counts[0]);
    atomicAdd(stats.drawn, counts[1]);
    atomicAdd(stats.at_max, counts[2]);
    atomicAdd(stats.in_range, counts[3]);
    atomicAdd(stats.promoted, counts[4]);
    atomicAdd(stats.dropped, counts[5]);
    uint old = atomicAdd(stats.selected_lo, counts[6]);
    atomicAdd(stats.selected_hi, counts[7] + (old + counts[6] < old ? 1u : 0u));
    old = atomicAdd(stats.requested_lo, requested_lo);
    atomicAdd(stats.requested_hi, requested_hi + (old + requested_lo < old ? 1u : 0u));
  }
}
