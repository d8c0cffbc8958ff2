// encode_asset/decode_asset: what an isolated import sends back is the asset it read.
#include "asset/asset_wire.h"

#include <gtest/gtest.h>

#include "spectator_character.h"

namespace crowdbake {
namespace {

SkinnedAsset rich_asset() {
  SkinnedAsset a = samples::make_spectator_character();
  a.source = "spectator.glb";
  a.files = {"spectator.glb", "skin tone.png"};
  a.materials.push_back({"cloth", glm::vec4(0.1f, 0.2f, 0.3f, 0.5f), "cloth.png"});
  a.warnings = {"first", ""};
  a.stats.max_influences = 7;
  a.stats.animated_nodes_kept = 2;
  a.clips.at(0).channels.at(1).rotation.interpolation = Interpolation::kCubicSpline;
  return a;
}

TEST(AssetWire, RoundTripKeepsEveryField) {
  const SkinnedAsset a = rich_asset();
  SkinnedAsset b;
  const std::string bytes = encode_asset(a);
  ASSERT_TRUE(decode_asset(bytes, b));
  EXPECT_EQ(encode_asset(b), bytes);
  EXPECT_EQ(b.source, a.source);
  EXPECT_EQ(b.files, a.files);
  ASSERT_EQ(b.skeleton.joints.size(), a.skeleton.joints.size());
  for (size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    EXPECT_EQ(b.skeleton.joints[j].name, a.skeleton.joints[j].name);
    EXPECT_EQ(b.skeleton.joints[j].parent, a.skeleton.joints[j].parent);
    EXPECT_EQ(b.skeleton.joints[j].inverse_bind, a.skeleton.joints[j].inverse_bind);
    EXPECT_EQ(b.skeleton.joints[j].rest.rotation, a.skeleton.joints[j].rest.rotation);
  }
  ASSERT_EQ(b.primitives.size(), a.primitives.size());
  for (size_t p = 0; p < a.primitives.size(); ++p) {
    EXPECT_EQ(b.primitives[p].positions, a.primitives[p].positions);
    EXPECT_EQ(b.primitives[p].indices, a.primitives[p].indices);
    EXPECT_EQ(b.primitives[p].joints, a.primitives[p].joints);
    EXPECT_EQ(b.primitives[p].weights, a.primitives[p].weights);
    EXPECT_EQ(b.primitives[p].uvs, a.primitives[p].uvs);
  }
  ASSERT_EQ(b.clips.size(), a.clips.size());
  EXPECT_EQ(b.clips[0].channels[1].rotation.interpolation, Interpolation::kCubicSpline);
  EXPECT_EQ(b.clips[0].channels[1].rotation.times, a.clips[0].channels[1].rotation.times);
  EXPECT_EQ(b.materials.back().base_color_texture, "cloth.png");
  EXPECT_EQ(b.materials.back().base_color, a.materials.back().base_color);
  EXPECT_EQ(b.warnings, a.warnings);
  EXPECT_EQ(b.stats.max_influences, 7);
  EXPECT_EQ(b.stats.animated_nodes_kept, 2);
}

// A child that dies half-way leaves a prefix; a prefix never decodes, and never crashes.
TEST(AssetWire, EveryTruncationIsRefused) {
  SkinnedAsset a = samples::make_spectator_character();
  const std::string bytes = encode_asset(a);
  SkinnedAsset b;
  const size_t step = std::max<size_t>(1, bytes.size() / 4000);
  for (size_t n = 0; n < bytes.size(); n += step)
    ASSERT_FALSE(decode_asset(bytes.substr(0, n), b)) << n << " of " << bytes.size();
  EXPECT_FALSE(decode_asset(bytes + "x", b));
}

TEST(AssetWire, AbsurdCountsAreRefusedBeforeAllocating) {
  std::string bytes(8, '\0');  // empty source name
  const uint64_t absurd = uint64_t(1) << 60;
  bytes.append(reinterpret_cast<const char*>(&absurd), 8);
  SkinnedAsset b;
  EXPECT_FALSE(decode_asset(bytes, b));
}

}  // namespace
}  // namespace crowdbake
