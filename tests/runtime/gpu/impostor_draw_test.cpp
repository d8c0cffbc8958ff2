// Impostors (runtime/gpu/impostor_draw.cpp, shaders/impostor.glsl): far spectators of a pack
// with an impostor are drawn as quads and counted as drawn; they look like the mesh they stand
// for; with impostors off, or a pack without one, the same crowd draws its meshes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <vector>

#include "crowdbake/runtime/gpu/renderer.h"
#include "runtime/gpu/draw_test_support.h"
#include "runtime/gpu/gpu_test_support.h"

namespace crowdbake {
namespace {

using runtime::Scene;
using runtime::gpu::FrameProfile;
using runtime::gpu::Image;
using runtime::gpu::Renderer;
using runtime::gpu::RenderOptions;

// A 4 x 10 block of spectators `distance` in front of the camera, at 320x180.
void block_scene(Scene& scene, const std::string& pack, float distance, float impostor_pixels) {
  runtime::TextureVariants variants;
  variants.head = 3;
  variants.upper_body = 5;
  variants.trousers = 3;
  ASSERT_TRUE(test::add_pack_file(scene, "spectator", pack, variants).ok());
  test::add_grid(scene, 0, 4, 10, 0.9f);
  scene.camera.position = {0.0f, 2.5f, distance};
  scene.camera.target = {0.0f, 1.0f, -1.5f};
  scene.camera.fov_y_degrees = 12.0f;
  scene.camera.width = 320;
  scene.camera.height = 180;
  scene.lod.mode = runtime::LodMode::kError;
  scene.lod.impostor_pixels = impostor_pixels;
}

// The image shrunk by `factor` in each direction (box filter), RGB as doubles.
std::vector<double> shrink(const Image& image, uint32_t factor) {
  const uint32_t w = image.width / factor, h = image.height / factor;
  std::vector<double> out(size_t{w} * h * 3, 0.0);
  for (uint32_t y = 0; y < h * factor; ++y)
    for (uint32_t x = 0; x < w * factor; ++x)
      for (int c = 0; c < 3; ++c)
        out[3 * (size_t{y / factor} * w + x / factor) + c] +=
            image.rgba[4 * (size_t{y} * image.width + x) + c] / double(factor * factor);
  return out;
}

// Pixels of `image` more than 24 away from `background` in some channel.
size_t changed_pixels(const Image& image, const Image& background) {
  size_t n = 0;
  for (size_t p = 0; p < image.rgba.size(); p += 4) {
    int most = 0;
    for (int c = 0; c < 3; ++c)
      most = std::max(most, std::abs(image.rgba[p + c] - background.rgba[p + c]));
    n += most > 24;
  }
  return n;
}

double psnr(const std::vector<double>& a, const std::vector<double>& b) {
  double se = 0.0;
  for (size_t i = 0; i < a.size(); ++i) se += (a[i] - b[i]) * (a[i] - b[i]);
  return 10.0 * std::log10(255.0 * 255.0 / std::max(se / a.size(), 1e-12));
}

class ImpostorDrawTest : public test::GpuTest {
 protected:
  Image render(const Scene& scene, FrameProfile& profile) {
    std::unique_ptr<Renderer> renderer;
    RenderOptions options;
    options.msaa_samples = 4;
    Image image;
    runtime::Status s = Renderer::create(context(), scene, options, renderer);
    EXPECT_TRUE(s.ok()) << s.message();
    if (!s) return image;
    s = renderer->render(scene, 0.4f, image, &profile);
    EXPECT_TRUE(s.ok()) << s.message();
    return image;
  }
};

TEST_F(ImpostorDrawTest, FarSpectatorsAreImpostorsAndAllDrawn) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  block_scene(scene, test::BakedPacks::get().spectator_impostor(), 120.0f, 1000.0f);
  if (HasFatalFailure()) return;
  FrameProfile profile;
  const Image image = render(scene, profile);
  if (HasFailure()) return;
  EXPECT_EQ(profile.impostors, 40u);
  EXPECT_EQ(profile.visible, 40u);
  EXPECT_EQ(profile.drawn, 40u);
  EXPECT_EQ(profile.triangles, 80u);
  // Off: the same crowd as meshes, nothing as impostors.
  scene.lod.impostor_pixels = 0.0f;
  FrameProfile meshes;
  const Image mesh_image = render(scene, meshes);
  EXPECT_EQ(meshes.impostors, 0u);
  EXPECT_EQ(meshes.drawn, 40u);
  EXPECT_GT(meshes.triangles, 40u * 36u);  // at least the coarsest level each
  // Both show the crowd over about as many pixels.
  scene.instances = {};
  FrameProfile none;
  const Image background = render(scene, none);
  if (HasFailure()) return;
  const double quads = static_cast<double>(changed_pixels(image, background));
  const double mesh = static_cast<double>(changed_pixels(mesh_image, background));
  EXPECT_GT(mesh, 100.0);
  EXPECT_NEAR(quads / mesh, 1.0, 0.35) << quads << " pixels against " << mesh;
}

// Close enough for the impostor's 32 texels to be about 50 pixels: the impostor picture,
// shrunk 4x, close to the full-resolution meshes' (27.2 dB when written; the quads turned
// back to front, mirroring every view, give 21.9 dB).
TEST_F(ImpostorDrawTest, ImpostorsLookLikeTheMeshesTheyStandFor) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  block_scene(scene, test::BakedPacks::get().spectator_impostor(), 30.0f, 1000.0f);
  if (HasFatalFailure()) return;
  FrameProfile impostors, meshes;
  const Image a = render(scene, impostors);
  scene.lod.mode = runtime::LodMode::kFull;
  const Image b = render(scene, meshes);
  if (HasFailure()) return;
  ASSERT_GT(impostors.visible, 30u);
  ASSERT_EQ(impostors.impostors, impostors.visible);
  ASSERT_EQ(meshes.impostors, 0u);
  EXPECT_GT(psnr(shrink(a, 4), shrink(b, 4)), 24.5);
}

TEST_F(ImpostorDrawTest, SmallInstancesOfAPackWithoutImpostorDrawTheirMeshes) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  Scene scene;
  block_scene(scene, test::BakedPacks::get().spectator(), 120.0f, 1000.0f);
  if (HasFatalFailure()) return;
  FrameProfile profile;
  render(scene, profile);
  EXPECT_EQ(profile.impostors, 0u);
  EXPECT_EQ(profile.drawn, 40u);
}

}  // namespace
}  // namespace crowdbake
