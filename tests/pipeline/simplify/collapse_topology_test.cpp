// How a position's edges are shared and which collapses keep the surface a manifold, on a square
// fan (centre 4, corners 0..3) and a bowtie, worked out by hand.
#include "simplify/collapse_topology.h"

#include <gtest/gtest.h>

#include <vector>

namespace crowdbake {
namespace {

// Triangles over positions 0..positions-1 (one vertex each, every position at the origin: the
// checks read connectivity only).
struct Faces {
  SimplifyMesh mesh;
  std::vector<glm::dvec3> posed;
  std::vector<uint32_t> corner;
  std::vector<FaceList> incident;
  std::vector<char> small_part;

  Faces(uint32_t positions, std::vector<uint32_t> triangles)
      : posed(positions),
        corner(std::move(triangles)),
        incident(positions),
        small_part(positions, 0) {
    mesh.vertex_count = positions;
    for (uint32_t p = 0; p < positions; ++p) mesh.position_of.push_back(p);
    for (uint32_t t = 0; 3 * t < corner.size(); ++t)
      for (int k = 0; k < 3; ++k) incident[corner[3 * t + k]].push_back(t);
  }
  PosedMeshView view() const { return {mesh, posed, 1, corner, incident}; }
  bool allows(uint32_t from, uint32_t to) const {
    TopologyLists lists;
    bool closing = false;
    return topology_allows(view(), small_part, from, to, closing, lists);
  }
};

Faces square_fan() { return Faces(5, {4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0}); }

TEST(CollapseTopology, PositionsAreInteriorBorderOrLocked) {
  const Faces fan = square_fan();
  std::vector<std::pair<uint32_t, int>> edges;
  EXPECT_EQ(position_kind(fan.view(), 4, edges), PositionKind::kInterior);
  EXPECT_EQ(edges.size(), 4u);
  EXPECT_EQ(position_kind(fan.view(), 0, edges), PositionKind::kBorder);
  // Two triangles that meet at one position only: four border edges there.
  const Faces bowtie(5, {0, 1, 2, 0, 3, 4});
  EXPECT_EQ(position_kind(bowtie.view(), 0, edges), PositionKind::kLocked);
  EXPECT_EQ(position_kind(bowtie.view(), 1, edges), PositionKind::kBorder);
  // A second fan of three faces around 4 that shares the edge 4-0 with the square: four faces
  // on that edge, so 4 lies on a curve where sheets meet.
  const Faces fin(7, {4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 5, 4, 5, 6, 4, 6, 0});
  EXPECT_EQ(position_kind(fin.view(), 4, edges), PositionKind::kFin);
}

TEST(CollapseTopology, ABorderPositionMovesOnlyAlongItsBorder) {
  const Faces fan = square_fan();
  EXPECT_TRUE(fan.allows(4, 0));   // the centre onto a corner
  EXPECT_TRUE(fan.allows(0, 1));   // a corner along the border
  EXPECT_FALSE(fan.allows(0, 4));  // a corner inwards would open the border
  EXPECT_FALSE(fan.allows(0, 2));  // no edge between them
  std::vector<uint32_t> ring;
  EXPECT_EQ(neighbours(fan.view(), 4, ring), (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(CollapseTopology, NoCollapseLeavesTwoFacesBackToBackButOnAPartThatMayVanish) {
  // A closed tetrahedron (0, 1, 2, 3): collapsing any edge would leave two faces back to back
  // (a moved face would duplicate one around the target).
  Faces tetrahedron(4, {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2});
  EXPECT_FALSE(tetrahedron.allows(0, 1));
  // On a part that may vanish, it may: the tetrahedron flattens and the next collapse
  // removes it.
  tetrahedron.small_part.assign(4, 1);
  TopologyLists lists;
  bool closing = false;
  EXPECT_TRUE(topology_allows(tetrahedron.view(), tetrahedron.small_part, 0, 1, closing, lists));
  EXPECT_TRUE(closing);
}

}  // namespace
}  // namespace crowdbake
