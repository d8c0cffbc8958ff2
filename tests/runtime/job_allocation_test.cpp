// Every job's Run() allocates nothing: this binary counts global operator new
// calls while a test asks it to.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "crowdbake/runtime/animate_job.h"
#include "crowdbake/runtime/cull_job.h"
#include "crowdbake/runtime/lod_select_job.h"
#include "crowdbake/runtime/reconstruct_job.h"
#include "crowdbake/runtime/scene.h"
#include "crowdbake/runtime/skin_job.h"
#include "runtime/runtime_test_support.h"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<size_t> g_allocations{0};

void* counted(size_t size) {
  if (g_counting.load(std::memory_order_relaxed))
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(size_t size) { return counted(size); }
void* operator new[](size_t size) { return counted(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }
void operator delete[](void* p, size_t) noexcept { std::free(p); }

namespace crowdbake::runtime {
namespace {

class CountAllocations {
 public:
  CountAllocations() {
    g_allocations = 0;
    g_counting = true;
  }
  ~CountAllocations() { g_counting = false; }
  size_t count() const { return g_allocations.load(); }
};

TEST(Jobs, RunAllocatesNothing) {
  Pack pack;
  ASSERT_TRUE(Pack::open(make_memory_source(test::small_pack_bytes()), pack, kPackAll));
  const PackContents& c = pack.contents();
  std::vector<ClipRef> clips;
  for (const PackClip& clip : c.clips) clips.push_back({&clip, 0});
  const size_t n = 64;
  std::vector<uint32_t> type(n, 0), clip(n), row0(n), row1(n), vertices(n);
  std::vector<float> speed(n, 1.1f), offset(n, 0.3f), scale(n, 1.0f), position(3 * n),
      rotation(4 * n, 0.0f);
  std::vector<float> blend(n), world(12 * n), spheres(4 * n);
  std::vector<uint8_t> visible(n);
  std::vector<double> weights(n);
  for (size_t i = 0; i < n; ++i) {
    clip[i] = static_cast<uint32_t>(i % clips.size());
    position[3 * i] = static_cast<float>(i % 8);
    position[3 * i + 2] = -static_cast<float>(i / 8);
    rotation[4 * i + 3] = 1.0f;
  }
  Camera camera;
  camera.position = {4, 2, 8};
  camera.target = {4, 1, -4};
  View view;
  ASSERT_TRUE(make_view(camera, view));
  const std::vector<TypeBounds> bounds{make_type_bounds(pack)};
  LodSettings settings;
  settings.budget = 500;
  settings.mode = LodMode::kDiscrete;
  const std::vector<LodType> lod_types{make_lod_type(pack, settings)};
  std::vector<uint32_t> triangles(c.geometry.triangles.size());
  std::vector<float> palette(12 * c.joints.size()), skinned(c.geometry.positions.size()),
      normals(c.geometry.normals.size());

  AnimateJob animate;
  animate.time = 1.7f;
  animate.filter = FrameFilter::kLinear;
  animate.clips = clips;
  animate.clip = clip;
  animate.speed = speed;
  animate.time_offset = offset;
  animate.position = position;
  animate.rotation = rotation;
  animate.scale = scale;
  animate.row0 = row0;
  animate.row1 = row1;
  animate.blend = blend;
  animate.world = world;
  CullJob cull;
  cull.planes = view.planes;
  cull.bounds = bounds;
  cull.type = type;
  cull.world = world;
  cull.scale = scale;
  cull.spheres = spheres;
  cull.visible = visible;
  LodSelectJob lod;
  lod.settings = settings;
  lod.view = &view;
  lod.types = lod_types;
  lod.type = type;
  lod.spheres = spheres;
  lod.visible = visible;
  lod.weights = weights;
  lod.vertex_count = vertices;
  ReconstructJob reconstruct;
  reconstruct.mesh = progressive_view(c);
  reconstruct.vertices = 9;
  reconstruct.output = triangles;
  PaletteJob palette_job;
  palette_job.texture = &c.animation;
  palette_job.row0 = 1;
  palette_job.row1 = 2;
  palette_job.blend = 0.5f;
  palette_job.palette = palette;
  SkinJob skin;
  skin.positions = c.geometry.positions;
  skin.normals = c.geometry.normals;
  skin.joints = c.geometry.joints;
  skin.weights = c.geometry.weights;
  skin.vertex_count = c.geometry.vertex_count();
  skin.palette = palette;
  skin.world = Span<const float>(world.data(), 12);
  skin.out_positions = skinned;
  skin.out_normals = normals;

  CountAllocations counter;
  EXPECT_TRUE(animate.Run());
  EXPECT_TRUE(cull.Run());
  EXPECT_TRUE(lod.Run());
  EXPECT_TRUE(reconstruct.Run());
  EXPECT_TRUE(palette_job.Run());
  EXPECT_TRUE(skin.Run());
  EXPECT_EQ(counter.count(), 0u);
}

TEST(Jobs, TheCounterSeesAllocations) {
  CountAllocations counter;
  void* p = ::operator new(16);  // note: an explicit call, which a compiler may not elide
  ::operator delete(p);
  EXPECT_EQ(counter.count(), 1u);
}

}  // namespace
}  // namespace crowdbake::runtime
