#include <string>

#include "crowdbake/runtime/animate_job.h"
#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/cull_job.h"
#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/skin_job.h"

namespace crowdbake::runtime {
namespace {

Status invalid(const std::string& what) { return {StatusCode::kInvalidArgument, what}; }

// Visible instances of a type with an impostor whose bounding sphere is less than
// lod.impostor_pixels across leave the mesh path: they are not visible to LoD selection, the
// impostor pass draws them. Full resolution means meshes: no impostors there.
void select_impostors(const Scene& scene, FrameState& state) {
  const size_t n = state.visible.size();
  state.impostor.assign(n, 0);
  state.impostor_count = 0;
  const float limit = scene.lod.impostor_pixels;
  if (!(limit > 0.0f) || scene.lod.mode == LodMode::kFull) return;
  std::vector<uint8_t> has(scene.types.size(), 0);
  bool any = false;
  for (size_t t = 0; t < scene.types.size(); ++t) {
    const Pack& pack = scene.types[t].pack;
    has[t] = pack.has(kPackPartition) && !pack.contents().impostor.empty();
    any = any || has[t];
  }
  if (!any) return;
  const View& v = state.view;
  for (size_t i = 0; i < n; ++i) {
    if (!state.visible[i] || !has[scene.instances.type[i]]) continue;
    const float* s = &state.spheres[4 * i];
    const float dx = s[0] - v.eye[0], dy = s[1] - v.eye[1], dz = s[2] - v.eye[2];
    // note: the distance along the view axis, as the projection scales by it.
    const float depth = dx * v.forward[0] + dy * v.forward[1] + dz * v.forward[2];
    if (!(depth > s[3])) continue;  // close enough to cut the near plane: a mesh
    if (2.0f * s[3] * v.focal_pixels < limit * depth) {
      state.impostor[i] = 1, state.visible[i] = 0;
      ++state.impostor_count, --state.visible_count;
    }
  }
}

}  // namespace

Status update_frame(const Scene& scene, float time, FrameState& state) {
  if (Status s = make_view(scene.camera_at_time(time), state.view); !s) return s;
  if (const Status s = check_lod_settings(scene.lod); !s) return invalid("lod: " + s.message());
  const InstanceArrays& in = scene.instances;
  if (!in.consistent()) return invalid("instance arrays have inconsistent lengths");
  const size_t n = in.size();
  state.time = time;
  state.row0.resize(n);
  state.row1.resize(n);
  state.blend.resize(n);
  state.world.resize(12 * n);
  state.spheres.resize(4 * n);
  state.visible.resize(n);
  state.weights.resize(n);
  state.vertex_count.resize(n);
  state.morph.resize(n);
  state.lod_types.resize(scene.types.size());
  state.bounds.resize(scene.types.size());
  for (size_t t = 0; t < scene.types.size(); ++t) {
    state.lod_types[t] = make_lod_type(scene.types[t].pack, scene.lod);
    state.bounds[t] = make_type_bounds(scene.types[t].pack);
  }

  AnimateJob animate;
  animate.time = time;
  animate.filter = scene.animation.filter;
  animate.root_motion = scene.animation.root_motion;
  animate.clips = scene.clips;
  animate.clip = in.clip;
  animate.speed = in.speed;
  animate.time_offset = in.time_offset;
  animate.position = in.position;
  animate.rotation = in.rotation;
  animate.scale = in.scale;
  animate.row0 = state.row0;
  animate.row1 = state.row1;
  animate.blend = state.blend;
  animate.world = state.world;
  if (!animate.Run())
    return invalid("instance arrays are inconsistent (sizes or clip indices) for the crowd update");
  for (size_t i = 0; i < n; ++i)
    if (scene.clips[in.clip[i]].type != in.type[i])
      return invalid("instance " + std::to_string(i) + " plays a clip of another character type");

  CullJob cull;
  cull.planes = state.view.planes;
  cull.bounds = state.bounds;
  cull.type = in.type;
  cull.world = state.world;
  cull.scale = in.scale;
  cull.spheres = state.spheres;
  cull.visible = state.visible;
  cull.visible_count = &state.visible_count;
  if (!cull.Run())
    return invalid("instance arrays are inconsistent (sizes or type indices) for culling");

  select_impostors(scene, state);

  LodSelectJob lod;
  lod.settings = scene.lod;
  state.lod_note.clear();
  if (scene.lod.mode == LodMode::kError)
    for (size_t t = 0; t < scene.types.size(); ++t)
      if (state.lod_types[t].error_vertices.size() == 0) {
        lod.settings.mode = LodMode::kContinuous;
        state.lod_note = scene.types[t].pack.source_name() +
                         ": no level errors (a pack of format 1.0; re-bake it), so LoD is "
                         "selected by budget (lod.mode \"budget\")";
        break;
      }
  state.lod_mode = lod.settings.mode;
  lod.view = &state.view;
  lod.types = state.lod_types;
  lod.type = in.type;
  lod.spheres = state.spheres;
  lod.visible = state.visible;
  lod.weights = state.weights;
  lod.vertex_count = state.vertex_count;
  lod.morph = state.morph;
  lod.stats = &state.lod;
  if (!lod.Run()) return invalid("LoD selection rejected its inputs");
  return {};
}

Status reconstruct_lod(const Scene& scene, uint32_t type, uint32_t vertices,
                       std::vector<uint32_t>& triangles) {
  if (type >= scene.types.size())
    return invalid("type index " + std::to_string(type) + " out of range");
  const Pack& pack = scene.types[type].pack;
  if (!pack.has(kPackGeometry))
    return {StatusCode::kNotLoaded, pack.source_name() + ": geometry is not loaded"};
  ReconstructJob job;
  job.mesh = progressive_view(pack.contents());
  job.vertices = vertices;
  triangles.resize(3 * size_t{lod_triangle_count(job.mesh, vertices)});
  job.output = triangles;
  if (!job.Run())
    return invalid(pack.source_name() + ": progressive arrays rejected by reconstruction");
  return {};
}

Status skin_instance(const Scene& scene, uint32_t instance, float time, uint32_t vertices,
                     std::vector<float>& positions, std::vector<float>* normals) {
  const InstanceArrays& in = scene.instances;
  if (!in.consistent()) return invalid("instance arrays have inconsistent lengths");
  if (instance >= in.size())
    return invalid("instance " + std::to_string(instance) + " out of range");
  if (in.clip[instance] >= scene.clips.size() || in.type[instance] >= scene.types.size())
    return invalid("instance " + std::to_string(instance) + " has a bad type or clip index");
  const Pack& pack = scene.types[in.type[instance]].pack;
  if (!pack.has(kPackGeometry | kPackAnimation))
    return {StatusCode::kNotLoaded, pack.source_name() + ": geometry and animation must be loaded"};
  const PackContents& c = pack.contents();
  const PackClip& clip = *scene.clips[in.clip[instance]].clip;
  FrameChoice frame;
  float world[12];
  animate_instance(clip, time, in.speed[instance], in.time_offset[instance], scene.animation.filter,
                   scene.animation.root_motion, &in.position[3 * size_t{instance}],
                   &in.rotation[4 * size_t{instance}], in.scale[instance], frame, world);
  std::vector<float> palette(12 * size_t{c.animation.joints});
  PaletteJob pj;
  pj.texture = &c.animation;
  pj.row0 = clip.first_row + frame.frame0;
  pj.row1 = clip.first_row + frame.frame1;
  pj.blend = frame.blend;
  pj.palette = palette;
  if (!pj.Run())
    return invalid(pack.source_name() + ": animation texture rejected by the palette job");
  const uint32_t n = std::min(vertices, c.geometry.vertex_count());
  positions.resize(3 * size_t{n});
  SkinJob sj;
  sj.positions = c.geometry.positions;
  sj.normals = c.geometry.normals;
  sj.joints = c.geometry.joints;
  sj.weights = c.geometry.weights;
  sj.vertex_count = n;
  sj.palette = palette;
  sj.world = Span<const float>(world, 12);
  sj.out_positions = positions;
  if (normals && !c.geometry.normals.empty()) {
    normals->resize(3 * size_t{n});
    sj.out_normals = *normals;
  } else if (normals) {
    normals->clear();
  }
  if (!sj.Run()) return invalid(pack.source_name() + ": geometry rejected by the skinning job");
  return {};
}

}  // namespace crowdbake::runtime
