// Material shading: make_gpu_materials turns pack materials into what crowd.frag reads (factor
// in display space, image layer, texture transform, alpha cutoff, images resampled with a mip
// chain), and a rendered character carries its material's colour or its texture's, while
// swatch shading keeps the generated swatches.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "crowdbake/formats/pack_image.h"
#include "crowdbake/runtime/gpu/crowd_draw.h"
#include "crowdbake/runtime/gpu/renderer.h"
#include "pack_bytes.h"
#include "runtime/gpu/draw_test_support.h"
#include "runtime/gpu/gpu_test_support.h"
#include "test_png.h"

namespace crowdbake {
namespace {

using runtime::Scene;
using runtime::Shading;
using runtime::gpu::GpuMaterials;
using runtime::gpu::Image;
using runtime::gpu::make_gpu_materials;
using runtime::gpu::Renderer;

PackImage image_of(uint32_t width, uint32_t height, std::array<uint8_t, 4> rgba) {
  PackImage image;
  std::string why;
  EXPECT_TRUE(make_pack_image("test.png", test::solid_image(width, height, rgba), image, why))
      << why;
  return image;
}

TEST(GpuMaterials, FactorsImagesAndCutoffsAsTheShaderReadsThem) {
  PackContents pack;
  pack.materials.resize(3);
  pack.materials[0].base_color = {0.5f, 0.0f, 1.0f, 0.75f};
  pack.materials[1].base_color_image = 1;
  pack.materials[1].uv_transform = {2, 0, 0.5f, 0, -1, 1};
  pack.materials[2].alpha_mode = AlphaMode::kMask;
  pack.materials[2].alpha_cutoff = 0.25f;
  pack.images = {image_of(4, 2, {255, 0, 0, 255}), image_of(8, 8, {0, 255, 0, 255})};
  GpuMaterials m;
  ASSERT_TRUE(make_gpu_materials(pack, m).ok());
  ASSERT_EQ(m.materials.size(), 3u);
  EXPECT_NEAR(m.materials[0].color[0], 0.7354f, 1e-3);  // sRGB of linear 0.5
  EXPECT_EQ(m.materials[0].color[1], 0.0f);
  EXPECT_EQ(m.materials[0].color[2], 1.0f);
  EXPECT_EQ(m.materials[0].color[3], 0.75f);
  EXPECT_EQ(m.materials[0].uv_u[3], -1.0f);  // untextured
  EXPECT_EQ(m.materials[0].uv_v[3], -1.0f);  // opaque
  EXPECT_EQ(m.materials[1].uv_u[3], 1.0f);   // layer = image 1
  EXPECT_EQ(m.materials[1].uv_u[0], 2.0f);
  EXPECT_EQ(m.materials[1].uv_u[2], 0.5f);
  EXPECT_EQ(m.materials[1].uv_v[1], -1.0f);
  EXPECT_EQ(m.materials[1].uv_v[2], 1.0f);
  EXPECT_EQ(m.materials[2].uv_v[3], 0.25f);
  // Both images at the larger one's size, 8x8, with levels 8, 4, 2, 1.
  EXPECT_EQ(m.width, 8u);
  EXPECT_EQ(m.height, 8u);
  EXPECT_EQ(m.layers, 2u);
  ASSERT_EQ(m.level_offsets.size(), 4u);
  EXPECT_EQ(m.rgba.size(), (64u + 16 + 4 + 1) * 4 * 2);
  EXPECT_EQ(m.rgba[0], 255);                           // layer 0 red (resampled from 4x2)
  EXPECT_EQ(m.rgba[64 * 4 + 1], 255);                  // layer 1 green
  EXPECT_EQ(m.rgba[m.level_offsets[3] + 4 + 1], 255);  // its 1x1 level still green
}

TEST(GpuMaterials, PackWithoutMaterialsOrImagesGetsWhite) {
  GpuMaterials m;
  ASSERT_TRUE(make_gpu_materials(PackContents{}, m).ok());
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].color[0], 1.0f);
  EXPECT_EQ(m.layers, 1u);
  EXPECT_EQ(m.rgba.size(), 4u);
}

TEST(GpuMaterials, ImageThatDoesNotDecodeIsAnError) {
  PackContents pack;
  pack.images = {image_of(16, 16, {1, 2, 3, 255})};
  pack.images[0].data.resize(pack.images[0].data.size() / 2);
  GpuMaterials m;
  const runtime::Status s = make_gpu_materials(pack, m);
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.code(), runtime::StatusCode::kInvalidPack);
  EXPECT_NE(s.message().find("does not decode"), std::string::npos) << s.message();
}

class MaterialShadingTest : public test::GpuTest {
 protected:
  // One spectator close up, its pack's materials changed by `edit`, drawn with `shading`,
  // wearing texture variants `textures` (head | upper body << 8 | trousers << 16).
  Image render_spectator(void (*edit)(PackContents&), Shading shading, uint32_t textures = 0) {
    std::ifstream in(test::BakedPacks::get().spectator(), std::ios::binary);
    const std::vector<uint8_t> bytes{std::istreambuf_iterator<char>(in),
                                     std::istreambuf_iterator<char>()};
    PackContents contents;
    EXPECT_TRUE(read_pack(bytes.data(), bytes.size(), contents).ok());
    edit(contents);
    Scene scene;
    EXPECT_TRUE(test::add_pack_bytes(scene, "spectator", test::pack_bytes(contents)).ok());
    scene.types[0].shading = shading;
    test::add_grid(scene, 0, 1, 1, 1.0f);
    scene.instances.color.assign(3 * scene.instances.size(), 0.0f);
    for (size_t i = 0; i < scene.instances.size(); ++i) scene.instances.color[3 * i + 1] = 1.0f;
    for (size_t i = 0; i < scene.instances.size(); ++i) scene.instances.color[3 * i + 2] = 1.0f;
    scene.instances.textures.assign(scene.instances.size(), textures);
    scene.camera.position = {0.0f, 1.2f, 2.4f};
    scene.camera.target = {0.0f, 0.9f, 0.0f};
    scene.camera.width = 96;
    scene.camera.height = 96;
    std::unique_ptr<Renderer> renderer;
    runtime::gpu::RenderOptions options;
    options.shadows = false;
    options.ground = false;
    Image image;
    if (runtime::Status s = Renderer::create(context(), scene, options, renderer); !s.ok()) {
      ADD_FAILURE() << s.message();
      return image;
    }
    EXPECT_TRUE(renderer->render(scene, 0.5f, image).ok());
    return image;
  }
  // Pixels of the character whose dominant channel is `channel` by a clear margin.
  static size_t dominated_by(const Image& image, int channel) {
    size_t n = 0;
    for (size_t p = 0; p < image.rgba.size(); p += 4) {
      const int c = image.rgba[p + channel];
      const int o1 = image.rgba[p + (channel + 1) % 3], o2 = image.rgba[p + (channel + 2) % 3];
      n += c > 40 && c > 2 * o1 + 10 && c > 2 * o2 + 10;
    }
    return n;
  }
};

void red_materials(PackContents& c) {
  for (PackMaterial& m : c.materials) m.base_color = {1.0f, 0.0f, 0.0f, 1.0f};
}

void green_texture(PackContents& c) {
  c.images = {image_of(16, 16, {0, 230, 0, 255})};
  for (PackMaterial& m : c.materials) {
    m.base_color = {1.0f, 1.0f, 1.0f, 1.0f};
    m.base_color_image = 0;
  }
}

void cut_out(PackContents& c) {
  c.images = {image_of(16, 16, {0, 230, 0, 40})};
  for (PackMaterial& m : c.materials) {
    // note: white factors, so texels the mask failed to cut would show up green.
    m.base_color = {1.0f, 1.0f, 1.0f, 1.0f};
    m.base_color_image = 0;
    m.alpha_mode = AlphaMode::kMask;
    m.alpha_cutoff = 0.5f;
  }
}

TEST_F(MaterialShadingTest, CharacterCarriesItsMaterialColour) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const Image red = render_spectator(red_materials, Shading::kMaterial);
  ASSERT_EQ(red.rgba.size(), 96u * 96 * 4);
  EXPECT_GT(dominated_by(red, 0), 300u);
  EXPECT_EQ(dominated_by(red, 1), 0u);
  // The same pack with swatch shading shows the swatches, not the materials.
  const Image swatches = render_spectator(red_materials, Shading::kSwatches);
  EXPECT_LT(dominated_by(swatches, 0), dominated_by(red, 0) / 4);
}

TEST_F(MaterialShadingTest, CharacterCarriesItsTexturesColour) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const Image green = render_spectator(green_texture, Shading::kMaterial);
  EXPECT_GT(dominated_by(green, 1), 300u);
  EXPECT_EQ(dominated_by(green, 0), 0u);
}

TEST_F(MaterialShadingTest, MaskedTexelsAreNotDrawn) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const Image green = render_spectator(green_texture, Shading::kMaterial);
  const Image cut = render_spectator(cut_out, Shading::kMaterial);
  EXPECT_GT(dominated_by(green, 1), 300u);
  EXPECT_EQ(dominated_by(cut, 1), 0u) << "alpha 40/255 is below the cutoff 0.5";
}

// Skin-coloured materials without images; a red upper-body variant and a blue trousers one.
void region_variants(PackContents& c) {
  for (PackMaterial& m : c.materials) m.base_color = {0.8f, 0.6f, 0.5f, 1.0f};
  c.images = {image_of(16, 16, {230, 0, 0, 255}), image_of(16, 16, {0, 0, 230, 255})};
  c.variant_images.first = {0, 0, 1};
  c.variant_images.count = {0, 1, 1};
}

TEST_F(MaterialShadingTest, VariantImagesReplaceTheirOwnRegionOnly) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  // auto shading: a pack with variant images is drawn with its materials.
  const Image own = render_spectator(region_variants, Shading::kAuto);
  EXPECT_EQ(dominated_by(own, 0) + dominated_by(own, 2), 0u) << "variant 0 is the character's own";
  const Image shirt = render_spectator(region_variants, Shading::kAuto, 1u << 8);
  EXPECT_GT(dominated_by(shirt, 0), 150u);
  EXPECT_EQ(dominated_by(shirt, 2), 0u);
  const Image trousers = render_spectator(region_variants, Shading::kAuto, 1u << 16);
  EXPECT_GT(dominated_by(trousers, 2), 150u);
  EXPECT_EQ(dominated_by(trousers, 0), 0u);
  const Image both = render_spectator(region_variants, Shading::kAuto, 1u << 8 | 1u << 16);
  EXPECT_GT(dominated_by(both, 0), 150u);
  EXPECT_GT(dominated_by(both, 2), 150u);
  // A choice past the pack's variants (the head has none) keeps the character's own look.
  const Image beyond = render_spectator(region_variants, Shading::kAuto, 3u | 2u << 8);
  EXPECT_EQ(dominated_by(beyond, 0) + dominated_by(beyond, 2), 0u);
}

// White materials; vertex colours (VCOL) red above the pack's waist height, white below.
void red_top_vertex_colours(PackContents& c) {
  for (PackMaterial& m : c.materials) m.base_color = {1.0f, 1.0f, 1.0f, 1.0f};
  const uint32_t n = c.geometry.vertex_count();
  c.vertex_colors.assign(n, 0xFFFFFFFFu);
  const std::array<float, 3> up = c.partition.up_axis;
  for (uint32_t v = 0; v < n; ++v) {
    const float* p = &c.geometry.positions[3 * v];
    if (p[0] * up[0] + p[1] * up[1] + p[2] * up[2] > c.partition.waist_height)
      c.vertex_colors[v] = 0xFF1010E6u;  // R 230, G 16, B 16
  }
}

TEST_F(MaterialShadingTest, VertexColoursMultiplyTheMaterial) {
  CROWDBAKE_REQUIRE_BAKED_PACKS();
  const Image coloured = render_spectator(red_top_vertex_colours, Shading::kMaterial);
  EXPECT_GT(dominated_by(coloured, 0), 300u) << "the upper body carries its vertices' red";
  EXPECT_EQ(dominated_by(coloured, 1) + dominated_by(coloured, 2), 0u);
  const Image white = render_spectator(
      [](PackContents& c) {
        for (PackMaterial& m : c.materials) m.base_color = {1.0f, 1.0f, 1.0f, 1.0f};
      },
      Shading::kMaterial);
  EXPECT_EQ(dominated_by(white, 0), 0u) << "without colours nothing is red";
  // Swatch shading ignores the pack's colours, as it ignores its materials.
  const Image swatches = render_spectator(red_top_vertex_colours, Shading::kSwatches);
  EXPECT_LT(dominated_by(swatches, 0), dominated_by(coloured, 0) / 3);
}

}  // namespace
}  // namespace crowdbake
