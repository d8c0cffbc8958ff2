// Renderer: a small crowd of the baked spectator against a golden image
// (tests/data/gpu/renderer_crowd.ppm; regenerate with CROWDBAKE_UPDATE_GOLDEN=1 after an
// intended change and look at it), determinism, the empty scene, the embedding path
// (prepare + record_draw into a caller's target) and the GPU crossfade in a picture.
#include "crowdbake/runtime/gpu/renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "crowdbake/runtime/geomorph.h"
#include "crowdbake/runtime/gpu/gpu_buffer.h"
#include "runtime/gpu/draw_test_support.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake {
namespace {

using runtime::Scene;
using runtime::gpu::FrameProfile;
using runtime::gpu::Image;
using runtime::gpu::Renderer;
using runtime::gpu::RenderOptions;

const std::string kGolden =
    std::string(CROWDBAKE_SOURCE_DIR) + "/tests/data/gpu/renderer_crowd.ppm";

bool write_ppm(const std::string& path, const Image& image) {
  std::ofstream out(path, std::ios::binary);
  out << "P6\n" << image.width << " " << image.height << "\n255\n";
  for (size_t i = 0; i < image.rgba.size(); i += 4)
    out.write(reinterpret_cast<const char*>(&image.rgba[i]), 3);
  return static_cast<bool>(out);
}

bool read_ppm(const std::string& path, Image& image) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  uint32_t max = 0;
  if (!(in >> magic >> image.width >> image.height >> max) || magic != "P6" || max != 255)
    return false;
  in.get();
  std::vector<char> rgb(size_t{image.width} * image.height * 3);
  if (!in.read(rgb.data(), static_cast<std::streamsize>(rgb.size()))) return false;
  image.rgba.assign(size_t{image.width} * image.height * 4, 255);
  for (size_t p = 0; p < size_t{image.width} * image.height; ++p)
    for (int c = 0; c < 3; ++c) image.rgba[4 * p + c] = static_cast<uint8_t>(rgb[3 * p + c]);
  return true;
}

struct ImageDiff {
  double mean_abs = 0;   // over every RGB channel, in 0..255
  double differing = 0;  // fraction of pixels with a channel more than 24 apart
};

ImageDiff compare(const Image& a, const Image& b) {
  ImageDiff d;
  const size_t pixels = size_t{a.width} * a.height;
  size_t differing = 0;
  for (size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int diff = std::abs(int(a.rgba[4 * p + c]) - int(b.rgba[4 * p + c]));
      d.mean_abs += diff;
      worst = std::max(worst, diff);
    }
    if (worst > 24) ++differing;
  }
  d.mean_abs /= 3.0 * static_cast<double>(pixels);
  d.differing = static_cast<double>(differing) / static_cast<double>(pixels);
  return d;
}

size_t non_background_pixels(const Image& image, const std::array<float, 4>& clear) {
  size_t count = 0;
  for (size_t p = 0; p < size_t{image.width} * image.height; ++p)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(image.rgba[4 * p + c]) - int(std::lround(clear[c] * 255.0f))) > 1) {
        ++count;
        break;
      }
  return count;
}

// Twelve spectators in three rows, seen from the front and above, at 256x144.
void crowd_scene(Scene& scene) {
  runtime::TextureVariants variants;
  variants.head = 3;
  variants.upper_body = 5;
  variants.trousers = 3;
  ASSERT_TRUE(
      test::add_pack_file(scene, "spectator", test::BakedPacks::get().spectator(), variants).ok());
  test::add_grid(scene, 0, 3, 4, 1.3f);
  scene.camera.position = {0.5f, 3.5f, 6.5f};
  scene.camera.target = {0.0f, 0.9f, -1.3f};
  scene.camera.width = 256;
  scene.camera.height = 144;
}

// One spectator close up, its LoD chosen by budget (the geomorph tests).
void close_up_scene(Scene& scene, uint32_t width, uint32_t height) {
  ASSERT_TRUE(test::add_pack_file(scene, "spectator", test::BakedPacks::get().spectator()).ok());
  test::add_grid(scene, 0, 1, 1, 1.0f);
  scene.camera.position = {0.0f, 1.2f, 2.0f};
  scene.camera.target = {0.0f, 0.9f, 0.0f};
  scene.camera.width = width;
  scene.camera.height = height;
  scene.lod.mode = runtime::LodMode::kContinuous;
}

class RendererTest : public test::GpuTest {
 protected:
  void make_renderer(const Scene& scene, const RenderOptions& options = {}) {
    renderer_.reset();
    const runtime::Status s = Renderer::create(context(), scene, options, renderer_);
    ASSERT_TRUE(s.ok()) << s.message();
  }
  // The baked spectators of crowd_scene and a renderer for them.
  void make_crowd_renderer(Scene& scene, const RenderOptions& options = {}) {
    CROWDBAKE_REQUIRE_BAKED_PACKS();
    crowd_scene(scene);
    if (HasFatalFailure()) return;
    make_renderer(scene, options);
  }
  Image render(const Scene& scene, float time, FrameProfile* profile = nullptr,
               const runtime::EffectFrame* effects = nullptr) {
    Image image;
    const runtime::Status s = renderer_->render(scene, time, image, profile, effects);
    EXPECT_TRUE(s.ok()) << s.message();
    return image;
  }
  // The scene at `time` with shadows (lit) and without (unlit), each from a new renderer.
  void render_with_and_without_shadows(const Scene& scene, float time, Image& lit, Image& unlit) {
    make_renderer(scene);
    if (HasFatalFailure()) return;
    lit = render(scene, time);
    RenderOptions options;
    options.shadows = false;
    make_renderer(scene, options);
    if (HasFatalFailure()) return;
    unlit = render(scene, time);
  }
  // A 256x144 colour + depth target the test owns (as an embedding host would) and a buffer
  // its colour is copied to. extra_usage: added to both images' usage.
  struct CallerTarget {
    runtime::gpu::GpuImage color, depth;
    runtime::gpu::GpuBuffer readback;
    runtime::gpu::HostTarget target;
    // Records the copy of the colour image (in TRANSFER_SRC_OPTIMAL) into `readback`.
    void record_copy(VkCommandBuffer cmd) const {
      VkBufferImageCopy copy{};
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {target.width, target.height, 1};
      vkCmdCopyImageToBuffer(cmd, color.image(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                             readback.buffer(), 1, &copy);
    }
  };
  void make_caller_target(VkImageUsageFlags extra_usage, CallerTarget& out) {
    using namespace runtime::gpu;
    ImageDesc color_desc;
    color_desc.width = 256;
    color_desc.height = 144;
    color_desc.usage =
        VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | extra_usage;
    ImageDesc depth_desc = color_desc;
    depth_desc.format = VK_FORMAT_D32_SFLOAT;
    depth_desc.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | extra_usage;
    depth_desc.aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    ASSERT_TRUE(GpuImage::create(context(), color_desc, out.color).ok());
    ASSERT_TRUE(GpuImage::create(context(), depth_desc, out.depth).ok());
    ASSERT_TRUE(GpuBuffer::create(context(), 256 * 144 * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryKind::kHostVisible, out.readback)
                    .ok());
    out.target.color_view = out.color.view();
    out.target.depth_view = out.depth.view();
    out.target.width = 256;
    out.target.height = 144;
  }
  std::unique_ptr<Renderer> renderer_;
};

TEST_F(RendererTest, CrowdMatchesGoldenImage) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  FrameProfile profile;
  const Image image = render(scene, 1.3f, &profile);
  ASSERT_EQ(image.width, 256u);
  ASSERT_EQ(image.height, 144u);
  EXPECT_EQ(profile.instances, 12u);
  EXPECT_EQ(profile.drawn, 12u);
  EXPECT_GT(profile.triangles, 0u);
  const char* update = std::getenv("CROWDBAKE_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    ASSERT_TRUE(write_ppm(kGolden, image)) << kGolden;
    GTEST_SKIP() << "golden image written to " << kGolden;
  }
  Image golden;
  ASSERT_TRUE(read_ppm(kGolden, golden)) << "cannot read " << kGolden;
  ASSERT_EQ(golden.width, image.width);
  ASSERT_EQ(golden.height, image.height);
  const ImageDiff diff = compare(image, golden);
  // note: a different CPU (LLVM code generation) may move edges by a pixel; not more.
  EXPECT_LT(diff.mean_abs, 1.0) << "mean absolute difference to " << kGolden;
  EXPECT_LT(diff.differing, 0.01) << "fraction of differing pixels";
  if (HasFailure()) write_ppm(::testing::TempDir() + "renderer_crowd_actual.ppm", image);
}

TEST_F(RendererTest, RerenderingGivesIdenticalPixels) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image first = render(scene, 0.7f);
  render(scene, 2.1f);  // something else in between
  const Image again = render(scene, 0.7f);
  ASSERT_EQ(first.rgba.size(), again.rgba.size());
  EXPECT_TRUE(first.rgba == again.rgba);
  EXPECT_GT(non_background_pixels(first, runtime::gpu::DrawSettings{}.clear_color), 1000u);
}

TEST_F(RendererTest, SceneWithoutInstancesIsTheClearColour) {
  Scene scene;
  ASSERT_TRUE(test::add_pack_bytes(scene, "small",
                                   test::small_pack_bytes_encoded(AnimationEncoding::kFloat32))
                  .ok());
  scene.camera.width = 160;
  scene.camera.height = 90;
  make_renderer(scene);
  if (HasFatalFailure()) return;
  FrameProfile profile;
  const Image image = render(scene, 0.0f, &profile);
  ASSERT_EQ(image.rgba.size(), 160u * 90u * 4u);
  EXPECT_EQ(non_background_pixels(image, runtime::gpu::DrawSettings{}.clear_color), 0u);
  EXPECT_EQ(profile.instances, 0u);
  EXPECT_EQ(profile.triangles, 0u);
}

TEST_F(RendererTest, RefusesAnotherSceneOrABadCamera) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  Image image;
  Scene bigger;
  crowd_scene(bigger);
  ASSERT_TRUE(test::add_pack_bytes(bigger, "small",
                                   test::small_pack_bytes_encoded(AnimationEncoding::kFloat32))
                  .ok());
  EXPECT_FALSE(renderer_->render(bigger, 0.0f, image).ok()) << "types differ from create";
  scene.camera.target = scene.camera.position;
  EXPECT_FALSE(renderer_->render(scene, 0.0f, image).ok()) << "unusable camera";
}

TEST_F(RendererTest, ProfileNamesEveryPassAndCounts) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  crowd_scene(scene);
  scene.lod.budget = 6000;  // not enough for everyone at full resolution
  make_renderer(scene);
  if (HasFatalFailure()) return;
  FrameProfile profile;
  render(scene, 1.0f, &profile);
  std::vector<std::string> names;
  for (const auto& p : profile.passes) {
    names.push_back(p.name);
    EXPECT_GE(p.cpu_ms, 0.0) << p.name;
    EXPECT_GE(p.gpu_ms, 0.0) << p.name;
  }
  for (const char* expected : {"shadow", "colour", "compute: reconstruct", "update (cpu)"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_EQ(profile.instances, 12u);
  EXPECT_LE(profile.drawn, profile.visible);
  EXPECT_LE(profile.vertices, 6000u);
  EXPECT_GT(profile.triangles, 0u);
}

TEST_F(RendererTest, ShadowsDarkenTheGround) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  Image lit, unlit;
  render_with_and_without_shadows(scene, 1.3f, lit, unlit);
  if (HasFatalFailure()) return;
  size_t darker = 0, brighter = 0;
  for (size_t p = 0; p < lit.rgba.size(); p += 4) {
    const int a = lit.rgba[p] + lit.rgba[p + 1] + lit.rgba[p + 2];
    const int b = unlit.rgba[p] + unlit.rgba[p + 1] + unlit.rgba[p + 2];
    darker += a + 30 < b;
    brighter += a > b + 30;
  }
  EXPECT_GT(darker, 100u) << "shadows should darken pixels";
  EXPECT_EQ(brighter, 0u) << "a shadow never brightens";
}

TEST_F(RendererTest, CrossfadeChangesThePictureOnlyBetweenTheEnds) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  runtime::EffectFrame fade;
  const uint32_t clips = static_cast<uint32_t>(scene.types[0].pack.contents().clips.size());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    fade.fade_clip.push_back((scene.instances.clip[i] + 1) % clips);
    fade.fade_time_offset.push_back(0.0f);
    fade.fade_weight.push_back(0.0f);
  }
  const Image plain = render(scene, 1.3f);
  EXPECT_TRUE(render(scene, 1.3f, nullptr, &fade).rgba == plain.rgba);
  for (float& w : fade.fade_weight) w = 0.5f;
  EXPECT_FALSE(render(scene, 1.3f, nullptr, &fade).rgba == plain.rgba);
}

// Static levels (full, discrete) and the level cache (continuous) draw what the corner path
// draws, up to the order of instances within a draw.
TEST_F(RendererTest, InstancedDrawsDrawWhatTheCornerPathDraws) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  crowd_scene(scene);
  for (runtime::LodMode mode :
       {runtime::LodMode::kFull, runtime::LodMode::kDiscrete, runtime::LodMode::kContinuous}) {
    SCOPED_TRACE("mode " + std::to_string(static_cast<int>(mode)));
    scene.lod.mode = mode;
    scene.lod.budget = 20000;
    make_renderer(scene);
    if (HasFatalFailure()) return;
    FrameProfile corner_profile;
    const Image corners = render(scene, 1.1f, &corner_profile);
    // note: with 20000 slots some instances find none and the vertex shader skins them.
    for (uint32_t capacity : {0u, 20000u}) {
      SCOPED_TRACE("skin slots " + std::to_string(capacity));
      RenderOptions options;
      options.compute.instanced_static_levels = true;
      options.skin_slots = capacity;
      make_renderer(scene, options);
      if (HasFatalFailure()) return;
      FrameProfile instanced_profile;
      const Image instanced = render(scene, 1.1f, &instanced_profile);
      EXPECT_TRUE(renderer_->compute().instanced());
      EXPECT_EQ(instanced_profile.drawn, corner_profile.drawn);
      EXPECT_EQ(instanced_profile.triangles, corner_profile.triangles);
      const ImageDiff diff = compare(instanced, corners);
      EXPECT_LT(diff.mean_abs, 0.2);
      EXPECT_LT(diff.differing, 0.002);
    }
  }
}

// 4x MSAA: the same picture with its edges averaged — deterministic, close to the one-sample
// image, with more distinct colours (partly covered pixels); a count the device lacks, or not
// a power of two, is refused.
TEST_F(RendererTest, MultisamplingSmoothsEdgesOnly) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image single = render(scene, 1.2f);
  RenderOptions options;
  options.msaa_samples = 4;
  make_renderer(scene, options);
  if (HasFatalFailure()) return;
  const Image msaa = render(scene, 1.2f);
  EXPECT_TRUE(render(scene, 1.2f).rgba == msaa.rgba) << "deterministic";
  ASSERT_EQ(msaa.rgba.size(), single.rgba.size());
  const ImageDiff diff = compare(msaa, single);
  EXPECT_GT(diff.mean_abs, 0.0);
  EXPECT_LT(diff.mean_abs, 4.0);
  EXPECT_LT(diff.differing, 0.05) << "only edge pixels change much";
  auto colours = [](const Image& image) {
    std::set<uint32_t> seen;
    for (size_t p = 0; p + 3 < image.rgba.size(); p += 4)
      seen.insert(uint32_t{image.rgba[p]} | uint32_t{image.rgba[p + 1]} << 8 |
                  uint32_t{image.rgba[p + 2]} << 16);
    return seen.size();
  };
  EXPECT_GT(colours(msaa), colours(single));
  std::unique_ptr<Renderer> refused;
  for (uint32_t bad : {3u, 0u, 128u}) {
    options.msaa_samples = bad;
    EXPECT_EQ(Renderer::create(context(), scene, options, refused).code(),
              runtime::StatusCode::kInvalidArgument)
        << bad;
  }
}

// Geomorphs change the picture only inside their window: far above every removal point (the
// full mesh, x = budget) the frame is the unmorphed one pixel for pixel; at a mid-range count
// vertices are on their way to their targets. (Their continuity is checked on the CPU,
// tests/runtime/geomorph_test.cpp, and the GPU's vertices against the CPU's below; how much
// popping they remove is measured by `crowdbake bench render`, docs/performance.md.)
TEST_F(RendererTest, GeomorphsMoveVerticesOnlyInsideTheirWindow) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  close_up_scene(scene, 256, 144);
  if (HasFatalFailure()) return;
  make_renderer(scene);
  if (HasFatalFailure()) return;
  for (uint32_t budget : {100000u, 300u}) {
    scene.lod.budget = budget;
    scene.lod.geomorph = 0.0f;
    const Image plain = render(scene, 0.8f);
    scene.lod.geomorph = 0.25f;
    const Image morphed = render(scene, 0.8f);
    EXPECT_EQ(morphed.rgba == plain.rgba, budget == 100000u) << "budget " << budget;
  }
}

// The skinning pass's geomorphed vertices are the CPU reference's: skin_instance, then
// geomorph_values at the instance's continuous count.
TEST_F(RendererTest, GeomorphedVerticesMatchTheCpuReference) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  close_up_scene(scene, 64, 64);
  if (HasFatalFailure()) return;
  scene.lod.geomorph = 0.25f;
  make_renderer(scene);
  if (HasFatalFailure()) return;
  const PackContents& pack = scene.types[0].pack.contents();
  const runtime::ProgressiveView mesh = runtime::progressive_view(pack);
  const std::vector<runtime::GeomorphVertex> table = runtime::geomorph_table(mesh);
  runtime::FrameState state;
  for (uint32_t budget : {700u, 574u, 568u, 300u}) {
    SCOPED_TRACE("budget " + std::to_string(budget));
    scene.lod.budget = budget;
    render(scene, 0.8f);
    ASSERT_TRUE(runtime::update_frame(scene, 0.8f, state).ok());
    const uint32_t n = runtime::usable_vertices(mesh, state.vertex_count[0]);
    std::vector<float> gpu, cpu, expected(3 * size_t{n});
    ASSERT_TRUE(renderer_->draw().read_skinned_positions(0, n, gpu).ok());
    ASSERT_TRUE(runtime::skin_instance(scene, 0, 0.8f, n, cpu).ok());
    ASSERT_TRUE(
        runtime::geomorph_values(table, state.morph[0], scene.lod.geomorph, n, cpu, expected));
    ASSERT_EQ(gpu.size(), expected.size());
    float worst = 0.0f;
    uint32_t worst_vertex = 0, morphed = 0;
    for (uint32_t v = 0; v < n; ++v) {
      morphed += runtime::geomorph_weight(table[v], state.morph[0], scene.lod.geomorph) > 0.0f;
      for (int k = 0; k < 3; ++k) {
        const float d = std::abs(gpu[3 * v + k] - expected[3 * v + k]);
        if (d > worst) worst = d, worst_vertex = v;
      }
    }
    EXPECT_GT(morphed, 0u);
    EXPECT_LT(worst, 1e-4f) << "vertex " << worst_vertex << " of " << n << ", x " << state.morph[0];
  }
}

TEST_F(RendererTest, JointPaletteDrawsWhatPerInfluenceDecodingDraws) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image palette = render(scene, 1.7f);
  RenderOptions options;
  options.joint_palette = false;
  make_renderer(scene, options);
  if (HasFatalFailure()) return;
  const Image per_influence = render(scene, 1.7f);
  const ImageDiff diff = compare(palette, per_influence);
  EXPECT_LT(diff.mean_abs, 0.05);
  EXPECT_LT(diff.differing, 0.0005);
}

TEST_F(RendererTest, RecordDrawIntoCallersTargetMatchesRender) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image reference = render(scene, 0.9f);

  using namespace runtime::gpu;
  VkCommandBuffer none = VK_NULL_HANDLE;
  HostTarget empty;
  EXPECT_FALSE(renderer_->record_draw(none, empty).ok()) << "no frame prepared";

  CallerTarget caller;
  make_caller_target(0, caller);
  if (HasFatalFailure()) return;
  HostTarget& target = caller.target;
  target.color_final_layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  runtime::Status recorded;
  ASSERT_TRUE(context()
                  .submit_and_wait([&](VkCommandBuffer cmd) {
                    recorded = renderer_->prepare(scene, 0.9f, cmd);
                    if (recorded.ok()) recorded = renderer_->record_draw(cmd, target);
                    caller.record_copy(cmd);
                  })
                  .ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message();
  Image mine;
  mine.width = 256;
  mine.height = 144;
  mine.rgba.resize(256 * 144 * 4);
  ASSERT_TRUE(caller.readback.download(mine.rgba.data(), mine.rgba.size()).ok());
  EXPECT_TRUE(mine.rgba == reference.rgba);
}

TEST_F(RendererTest, RecordDrawOverTheHostsPictureKeepsItsBackground) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image reference = render(scene, 0.9f);

  using namespace runtime::gpu;
  CallerTarget caller;
  make_caller_target(VK_IMAGE_USAGE_TRANSFER_DST_BIT, caller);
  if (HasFatalFailure()) return;
  const GpuImage& color = caller.color;
  const GpuImage& depth = caller.depth;
  HostTarget& target = caller.target;
  target.clear = false;
  runtime::Status recorded;
  ASSERT_TRUE(
      context()
          .submit_and_wait([&](VkCommandBuffer cmd) {
            // The host's own picture: black, depth at the far plane.
            transition_image(cmd, color.image(), VK_IMAGE_ASPECT_COLOR_BIT,
                             VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            transition_image(cmd, depth.image(), VK_IMAGE_ASPECT_DEPTH_BIT,
                             VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            const VkClearColorValue black{};
            const VkClearDepthStencilValue far{1.0f, 0};
            const VkImageSubresourceRange color_range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            const VkImageSubresourceRange depth_range{VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(cmd, color.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black,
                                 1, &color_range);
            vkCmdClearDepthStencilImage(cmd, depth.image(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                        &far, 1, &depth_range);
            transition_image(cmd, color.image(), VK_IMAGE_ASPECT_COLOR_BIT,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
            transition_image(cmd, depth.image(), VK_IMAGE_ASPECT_DEPTH_BIT,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
            recorded = renderer_->prepare(scene, 0.9f, cmd);
            if (recorded.ok()) recorded = renderer_->record_draw(cmd, target);
            caller.record_copy(cmd);
          })
          .ok());
  ASSERT_TRUE(recorded.ok()) << recorded.message();
  std::vector<uint8_t> mine(256 * 144 * 4);
  ASSERT_TRUE(caller.readback.download(mine.data(), mine.size()).ok());
  // Where render() shows its clear colour the host's black remains; elsewhere the same crowd.
  const auto clear = DrawSettings{}.clear_color;
  size_t background = 0, crowd = 0, wrong = 0;
  for (size_t p = 0; p < mine.size(); p += 4) {
    bool is_clear = true;
    for (int c = 0; c < 3; ++c)
      is_clear = is_clear &&
                 std::abs(int(reference.rgba[p + c]) - int(std::lround(clear[c] * 255.0f))) <= 1;
    if (is_clear) {
      ++background;
      wrong += mine[p] != 0 || mine[p + 1] != 0 || mine[p + 2] != 0;
    } else {
      ++crowd;
      wrong += mine[p] != reference.rgba[p] || mine[p + 1] != reference.rgba[p + 1] ||
               mine[p + 2] != reference.rgba[p + 2];
    }
  }
  EXPECT_GT(background, 1000u);
  EXPECT_GT(crowd, 1000u);
  EXPECT_EQ(wrong, 0u);
}

// Static geometry (a pitch under the crowd): drawn in its own colour, lit, and receiving the
// crowd's shadows; a scene without it draws none of that colour.
TEST_F(RendererTest, StaticGeometryIsDrawnInItsColourAndReceivesShadows) {
  Scene scene;
  make_crowd_renderer(scene);
  if (HasFatalFailure()) return;
  const Image without = render(scene, 1.3f);
  runtime::Pitch pitch;
  pitch.center = {0.0f, 0.0f, -1.3f};
  pitch.length = 8.0f;
  pitch.width = 10.0f;
  pitch.stripes = 0;
  pitch.color = {0.85f, 0.1f, 0.85f};  // magenta: no swatch, skin or ground colour is
  runtime::add_pitch(pitch, scene.static_geometry);
  ASSERT_FALSE(scene.static_geometry.empty());
  const auto magenta = [](const Image& image, size_t p) {
    const int r = image.rgba[4 * p], g = image.rgba[4 * p + 1], b = image.rgba[4 * p + 2];
    return r > 2 * g + 10 && b > 2 * g + 10 && std::abs(r - b) < 12;
  };
  const size_t pixels = size_t{without.width} * without.height;
  size_t before = 0;
  for (size_t p = 0; p < pixels; ++p) before += magenta(without, p);
  EXPECT_LT(before, 50u) << "the crowd alone should have (almost) no magenta";

  Image lit, unlit;
  render_with_and_without_shadows(scene, 1.3f, lit, unlit);
  if (HasFatalFailure()) return;
  size_t pitch_pixels = 0, shadowed = 0;
  for (size_t p = 0; p < pixels; ++p) {
    if (!magenta(unlit, p)) continue;
    ++pitch_pixels;
    shadowed += lit.rgba[4 * p] + 20 < unlit.rgba[4 * p];
  }
  EXPECT_GT(pitch_pixels, pixels / 4) << "the pitch fills the lower part of the picture";
  EXPECT_GT(shadowed, 100u) << "the crowd's shadows fall on the pitch";
}

}  // namespace
}  // namespace crowdbake
