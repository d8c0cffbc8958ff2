// crowdbake_runtime: everything a game embeds, in one include.
//
//   Pack            pack.h           open a .crowdpack, stream its parts on demand
//   Scene           scene.h          character types, instance arrays, camera, settings;
//                                    load_scene() reads scene.json (docs/scene-format.md)
//   Camera / View   camera.h         camera, camera paths, frustum planes, matrices
//   frame choice    frame.h          which frame an instance shows, its world matrix
//   jobs            animate_job.h    crowd update (frames, world matrices)
//                   cull_job.h       frustum culling by bounding sphere
//                   lod_select_job.h budgeted continuous LoD (docs/design.md §3.4), discrete, full
//                   reconstruct_job.h triangles of the LoD with n vertices
//                   skin_job.h       joint palette and CPU skinning
//   per frame       cpu_reference.h  update_frame(), reconstruct_lod(), skin_instance()
//   attachments     joint_query.h    a joint's world matrix for an instance at a time
//
// Errors come back as Status (status.h); nothing in the API throws.
#pragma once

#include "crowdbake/runtime/animate_job.h"
#include "crowdbake/runtime/byte_source.h"
#include "crowdbake/runtime/camera.h"
#include "crowdbake/runtime/cpu_reference.h"
#include "crowdbake/runtime/cull_job.h"
#include "crowdbake/runtime/frame.h"
#include "crowdbake/runtime/joint_query.h"
#include "crowdbake/runtime/lod_select_job.h"
#include "crowdbake/runtime/pack.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/skin_job.h"
#include "crowdbake/runtime/span.h"
#include "crowdbake/runtime/status.h"
