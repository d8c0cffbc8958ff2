#version 450
// Pass 1: cull + LoD weight per instance, and each workgroup's weight sum: 16 runs of 16
// weights added left to right, then the 16 run sums (the order lod_weight_sum replays on the
// CPU; two barriers instead of a tree's eight — barriers are what a CPU device pays for).
#extension GL_GOOGLE_include_directive : require
#include "crowd_compute.glsl"
#include "lod_math.glsl"

layout(local_size_x = 256) in;

shared double lanes[256];
shared double runs[16];
shared uint ladder_lo[kLadderSteps], ladder_hi[kLadderSteps];  // error mode

// CullJob's test, operation by operation (sphere_visible in cull_job.cpp).
bool sphere_visible(vec3 c, float radius) {
  for (int p = 0; p < 6; ++p) {
    const vec4 plane = params.planes[p];
    precise float d = plane.x * c.x + plane.y * c.y + plane.z * c.z + plane.w;
    if (!(d >= -radius)) return false;
  }
  return true;
}

void main() {
  const uint i = gl_GlobalInvocationID.x;
  const uint lid = gl_LocalInvocationID.x;
  const bool error_mode = params.mode == kModeError;
  if (error_mode && lid < kLadderSteps) {
    ladder_lo[lid] = 0u;
    ladder_hi[lid] = 0u;
  }
  if (error_mode) barrier();
  double w = 0.0lf;
  if (i < params.instance_count) {
    const GpuInstance g = instances[i];
    const TypeData t = types[g.type];
    const vec3 b = t.bounds.xyz;
    // CullJob: centre = world · bounds centre, radius = bounds radius · |scale|.
    precise float cx = g.world0.x * b.x + g.world0.y * b.y + g.world0.z * b.z + g.world0.w;
    precise float cy = g.world1.x * b.x + g.world1.y * b.y + g.world1.z * b.z + g.world1.w;
    precise float cz = g.world2.x * b.x + g.world2.y * b.y + g.world2.z * b.z + g.world2.w;
    precise float r = t.bounds.w * g.color.w;
    const vec3 c = vec3(cx, cy, cz);
    // note: an instance drawn as an impostor (update_frame's choice) is not the mesh path's.
    const bool visible = sphere_visible(c, r) && (g.textures & kImpostorBit) == 0u;
    if (visible && error_mode) {
      // τ_i (lod_error_threshold) kept in weights[i]; Σ n_i at every step of the ladder.
      double area, distance;
      lod_area_distance(c, r, params.eye_focal.xyz, params.eye_focal.w, params.near_plane,
                        params.screen, area, distance);
      precise double below = double(params.eye_focal.w) * double(r);
      precise double tau = below > 0.0lf
                               ? (double(params.max_pixel_error) * distance * double(t.bounds.w)) /
                                     below
                               : 1.0lf / 0.0lf;
      w = tau;
      for (uint j = 0u; j < kLadderSteps; ++j) {
        precise double t_step = lod_error_ladder(j) * tau;
        double unused;
        const uint n = lod_vertices_for_error(t, t_step, unused);
        ADD64(ladder_lo[j], ladder_hi[j], n);
      }
    } else if (visible && t.triangles > 0u) {
      double area, distance;
      lod_area_distance(c, r, params.eye_focal.xyz, params.eye_focal.w, params.near_plane,
                        params.screen, area, distance);
      w = lod_weight_root(area, distance, params.alpha, t.type_log_weight);
    }
    weights[i] = w;
    lods[i].visible = visible ? 1u : 0u;
  }
  if (error_mode) {
    barrier();
    if (lid < kLadderSteps) {
      ADD64(ladder_sums[lid].x, ladder_sums[lid].y, ladder_lo[lid]);
      atomicAdd(ladder_sums[lid].y, ladder_hi[lid]);
    }
  }
  lanes[lid] = error_mode ? 0.0lf : w;  // note: error mode sums nothing here
  barrier();
  if (lid < 16u) {
    precise double run = 0.0lf;
    for (uint k = 16u * lid; k < 16u * lid + 16u; ++k) run = run + lanes[k];
    runs[lid] = run;
  }
  barrier();
  if (lid == 0u) {
    precise double block = 0.0lf;
    for (uint j = 0u; j < 16u; ++j) block = block + runs[j];
    partials[gl_WorkGroupID.x] = block;
  }
}
