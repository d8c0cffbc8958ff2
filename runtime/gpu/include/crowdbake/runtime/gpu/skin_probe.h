// SkinProbe: runs the vertex shader's skinning (shaders/skin.glsl, through skin_probe.comp) for
// chosen (instance, vertex) pairs, or an instance's world · S_j for chosen joints, and reads the
// results back — so tests can hold the GPU's skinning against runtime::skin_instance and the
// joint queries without rasterising anything.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/gpu_instance.h"
#include "crowdbake/runtime/gpu/vulkan_context.h"
#include "crowdbake/runtime/status.h"

namespace crowdbake::runtime::gpu {

struct SkinQuery {
  uint32_t instance = 0;
  uint32_t index = 0;  // vertex (kVertex) or joint (kJoint) of the instance's type
  enum Kind : uint32_t { kVertex = 0, kJoint = 1 } kind = kVertex;
};

// Per query: kVertex → world position and unit world normal; kJoint → world · S_j (3x4
// row-major; the joint's world matrix is that times Pack::bind_matrix(j)).
struct SkinResult {
  float position[3] = {0, 0, 0};
  float normal[3] = {0, 0, 0};
  float matrix[12] = {0};
};

class SkinProbe {
 public:
  // draw: supplies the per-type descriptor sets (vertices, animation, pose buffers) and must
  // outlive the probe.
  static Status create(VulkanContext& context, const CrowdDraw& draw,
                       std::unique_ptr<SkinProbe>& out);
  ~SkinProbe();
  SkinProbe(const SkinProbe&) = delete;
  SkinProbe& operator=(const SkinProbe&) = delete;

  // Runs the queries of one character type (every query's instance must be of `type`, its
  // index within that type's vertices or joints) and waits for the results.
  // Returns kInvalidArgument for a bad type, an out-of-range query or a Vulkan failure.
  Status run(uint32_t type, const std::vector<GpuInstance>& instances,
             const std::vector<SkinQuery>& queries, std::vector<SkinResult>& out);

 private:
  struct Impl;
  explicit SkinProbe(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace crowdbake::runtime::gpu
