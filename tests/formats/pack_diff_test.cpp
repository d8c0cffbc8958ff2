// formats/pack_diff.h: the semantic comparison `crowdbake diff` prints, on packs written from
// generated contents: what it finds, where, and what the tolerance and --ignore change.
#include "crowdbake/formats/pack_diff.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "pack_bytes.h"
#include "pack_test_contents.h"

namespace crowdbake {
namespace {

PackFile pack_of(const PackContents& contents) {
  PackWriteOptions options;
  options.codec = GeometryCodec::kRaw;  // note: exact floats, so a moved vertex is what differs
  const std::vector<uint8_t> bytes = test::pack_bytes(contents, options);
  PackFile pack;
  const Status read = read_pack_file(bytes.data(), bytes.size(), pack);
  EXPECT_TRUE(read) << read.message();
  EXPECT_EQ(pack.bytes, bytes.size());
  return pack;
}

const DiffSection& section(const PackDiff& diff, const std::string& name) {
  const auto it = std::find_if(diff.sections.begin(), diff.sections.end(),
                               [&](const DiffSection& s) { return s.name == name; });
  EXPECT_NE(it, diff.sections.end()) << name;
  return *it;
}

TEST(PackDiff, APackEqualsItself) {
  const PackFile a = pack_of(test::make_test_contents(4, 21));
  const PackDiff diff = diff_packs(a, a, {});
  EXPECT_TRUE(diff.equal()) << diff.differing().front();
  ASSERT_EQ(diff.sections.size(), diff_section_names().size());
  for (size_t k = 0; k < diff.sections.size(); ++k)
    EXPECT_EQ(diff.sections[k].name, diff_section_names()[k]);
  EXPECT_TRUE(section(diff, "sizes").info_only);
  EXPECT_GT(diff.diagonal, 0.0);
}

TEST(PackDiff, AMovedVertexIsFoundAndTheToleranceDecides) {
  const PackContents base = test::make_test_contents(4, 21);
  PackContents moved = base;
  moved.geometry.positions[3 * 5 + 1] += 0.01f;
  const PackFile a = pack_of(base), b = pack_of(moved);
  const PackDiff exact = diff_packs(a, b, {});
  EXPECT_EQ(exact.differing(), std::vector<std::string>{"geometry"});
  const DiffSection& g = section(exact, "geometry");
  ASSERT_FALSE(g.differences.empty());
  EXPECT_NE(g.differences.front().find("at vertex 5"), std::string::npos) << g.differences.front();
  EXPECT_NEAR(g.figures["max_position_diff"].get<double>(), 0.01, 1e-6);

  DiffOptions loose;
  loose.tolerance = 0.02 / exact.diagonal;  // lengths compare relative to the diagonal
  EXPECT_TRUE(diff_packs(a, b, loose).equal());
  DiffOptions ignoring;
  ignoring.ignore = {"geometry"};
  const PackDiff ignored = diff_packs(a, b, ignoring);
  EXPECT_TRUE(ignored.equal());
  EXPECT_TRUE(section(ignored, "geometry").ignored);
}

TEST(PackDiff, TheSameVerticesInAnotherOrderPairUp) {
  const PackContents base = test::make_test_contents(4, 21);
  PackContents swapped = base;
  PackGeometry& g = swapped.geometry;
  // Swap vertices 0 and 1 everywhere, and their uses in the triangles.
  auto swap_rows = [](auto& v, size_t per) {
    for (size_t k = 0; k < per && per * 2 <= v.size(); ++k) std::swap(v[k], v[per + k]);
  };
  swap_rows(g.positions, 3), swap_rows(g.normals, 3), swap_rows(g.uvs, 2);
  swap_rows(g.joints, 4), swap_rows(g.weights, 4), swap_rows(g.regions, 1);
  for (uint32_t& i : g.triangles) i = i == 0 ? 1 : i == 1 ? 0 : i;
  swapped.progressive = PackProgressive{};  // note: the progressive order no longer holds
  PackContents plain = base;
  plain.progressive = PackProgressive{};
  const PackDiff diff = diff_packs(pack_of(plain), pack_of(swapped), {});
  const DiffSection& s = section(diff, "geometry");
  EXPECT_EQ(s.figures["vertex_order"], "differs");
  EXPECT_EQ(s.figures["positions"], "equal");
  EXPECT_EQ(s.figures["triangle_order"], "same") << "triangles compare through the pairing";
}

TEST(PackDiff, AnImpostorIsComparedTexelByTexel) {
  PackContents base = test::make_test_contents(4, 21);
  PackContents with = base;
  PackImpostor& m = with.impostor;
  m.views = 1, m.frames = 1, m.width = 2, m.height = 2;
  m.half_width = 0.5f, m.bottom = 0.0f, m.top = 2.0f;
  m.frame_of_row.assign(with.animation.rows, 0);
  m.texels = {0x3C00u, 0x00007F00u, 0, PackImpostor::kEmptyWord1, 0x3C00u, 0x00017F00u, 7, 0x1u};
  PackContents changed = with;
  changed.impostor.texels[6] = 8;
  const PackFile a = pack_of(base), b = pack_of(with), c = pack_of(changed);
  EXPECT_EQ(diff_packs(b, c, {}).differing(), std::vector<std::string>{"impostor"});
  EXPECT_NE(section(diff_packs(b, c, {}), "impostor").differences.front().find("1 texels differ"),
            std::string::npos);
  const PackDiff added_diff = diff_packs(a, b, {});
  const DiffSection& added = section(added_diff, "impostor");
  ASSERT_TRUE(added.differs);
  EXPECT_NE(added.differences.front().find("none -> 1 views x 1 frames of 2x2"), std::string::npos)
      << added.differences.front();
  EXPECT_FALSE(section(diff_packs(a, a, {}), "impostor").differs);
}

TEST(PackDiff, AClipChangeIsNamed) {
  const PackContents base = test::make_test_contents(4, 21);
  PackContents renamed = base;
  renamed.clips[0].name += "_2";
  const PackDiff diff = diff_packs(pack_of(base), pack_of(renamed), {});
  const std::vector<std::string> differing = diff.differing();
  EXPECT_NE(std::find(differing.begin(), differing.end(), "clips"), differing.end());
}

// Images compare by name, type, size and stored bytes (no re-encoding: equal images are equal
// bytes).
TEST(PackDiff, ImagesDifferInTypeOrBytes) {
  PackFile a;
  a.contents = test::make_test_contents(4, 21);
  PackImage image;
  image.name = "skin";
  image.mime_type = "image/png";
  image.width = image.height = 2;
  image.data = {1, 2, 3, 4};
  a.contents.images.push_back(image);
  PackFile b = a;
  EXPECT_TRUE(diff_packs(a, b, {}).equal());
  b.contents.images[0].mime_type = "image/jpeg";
  PackDiff diff = diff_packs(a, b, {});
  EXPECT_EQ(diff.differing(), std::vector<std::string>{"materials"});
  EXPECT_NE(section(diff, "materials").differences.front().find("type"), std::string::npos);
  b = a;
  b.contents.images[0].data[2] = 9;
  diff = diff_packs(a, b, {});
  EXPECT_NE(section(diff, "materials").differences.front().find("bytes differ"), std::string::npos);
}

}  // namespace
}  // namespace crowdbake
