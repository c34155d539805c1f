// Box-box narrow phase: the separating-axis test on each of its 15 axes, the six contact
// feature cases, and face clipping, on constructed cases whose answers are known.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "physics/collision.h"

namespace {

using phys::Obb;
using phys::Real;
using phys::Vec3;

// The shortest rotation taking unit vector `from` to unit vector `to` (not parallel).
glm::dquat rotationBetween(const Vec3& from, const Vec3& to) {
  return glm::angleAxis(std::acos(glm::dot(from, to)), glm::normalize(glm::cross(from, to)));
}

Obb box(const Vec3& center, const Vec3& half, const glm::dvec3& eulerDegrees = glm::dvec3(0.0)) {
  Obb b;
  b.center = center;
  b.halfExtents = half;
  b.axes = glm::mat3_cast(glm::dquat(glm::radians(eulerDegrees)));
  return b;
}

Vec3 axisOf(const Obb& a, const Obb& b, int index) {
  if (index < 3) return a.axes[index];
  if (index < 6) return b.axes[index - 3];
  const int i = (index - 6) / 3, j = (index - 6) % 3;
  return glm::normalize(glm::cross(a.axes[i], b.axes[j]));
}

// Places b along `axis` from a so that they overlap by exactly `depth` along it.
void placeAlong(const Obb& a, Obb& b, const Vec3& axis, Real depth) {
  b.center = a.center + axis * (phys::projectedRadius(a, axis) + phys::projectedRadius(b, axis) - depth);
}

// Each of the 15 axes made the axis of least overlap: face axes with boxes pushed together
// along that face's normal, edge axes with two long thin rods crossing, each long along the
// edge of the pair.
std::pair<Obb, Obb> caseFor(int index) {
  if (index < 3) {
    glm::dvec3 turn(0.0);
    turn[index] = 10.0;  // B turned about A's axis: its faces are not A's
    Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.0), Vec3(0.4, 0.45, 0.35), turn);
    return {a, b};
  }
  if (index < 6)
    return {box(Vec3(0.0), Vec3(0.5, 0.6, 0.7), {5, 10, 15}), box(Vec3(0.0), Vec3(0.5), {20, 30, 40})};
  const int i = (index - 6) / 3, j = (index - 6) % 3;
  Vec3 ha(0.1), hb(0.1);
  ha[i] = 2.0;
  hb[j] = 2.0;
  return {box(Vec3(0.0), ha), box(Vec3(0.0), hb, {35, 55, 25})};
}

TEST(Sat, EachOfTheFifteenAxesIsFoundWithItsDepth) {
  const Real depth = 0.03;
  for (int index = 0; index < 15; ++index) {
    auto [a, b] = caseFor(index);
    const Vec3 axis = axisOf(a, b, index);
    placeAlong(a, b, axis, depth);
    const phys::SatResult r = phys::satTest(a, b);
    ASSERT_TRUE(r.overlap) << "axis " << index;
    EXPECT_EQ(r.axis, index);
    EXPECT_NEAR(r.depth, depth, 1e-12) << "axis " << index;
    EXPECT_NEAR(glm::dot(r.normal, axis), 1.0, 1e-12) << "normal points from A to B, axis " << index;
  }
}

TEST(Sat, SeparatedAlongEachAxisIsNoContact) {
  for (int index = 0; index < 15; ++index) {
    auto [a, b] = caseFor(index);
    const Vec3 axis = axisOf(a, b, index);
    placeAlong(a, b, axis, -0.02);  // 2 cm apart along that axis
    EXPECT_FALSE(phys::satTest(a, b).overlap) << "axis " << index;
    EXPECT_FALSE(phys::satTest(a, b, 0.01).overlap) << "a 1 cm margin does not reach 2 cm, axis " << index;
    EXPECT_TRUE(phys::satTest(a, b, 0.03).overlap) << "a 3 cm margin does, axis " << index;
  }
}

TEST(Sat, NearlyEqualEdgeAxisLosesToTheFace) {
  // Two cubes face to face, B turned 45 degrees about the normal: the face axis and an
  // edge axis are about as deep; the face wins, so the normal is the face's.
  const Obb a = box(Vec3(0.0), Vec3(0.5));
  const Obb b = box(Vec3(0.0, 0.99, 0.0), Vec3(0.5), {0, 45, 0});
  const phys::SatResult r = phys::satTest(a, b);
  ASSERT_TRUE(r.overlap);
  EXPECT_EQ(r.axis, 1);
  EXPECT_NEAR(r.depth, 0.01, 1e-12);
}

// A cube over the edge of another, tilted 0.3 rad about x and turned 0.1 rad about z: the shallowest
// edge-edge axis is 1 cm shallower than the shallowest face axis (depths 0.0106 and 0.0204 m), but not
// by the face bias (0.95 * 0.0204 - 0.01 = 0.0094 m).
Obb tiltedOverTheEdge(const Vec3& center) {
  Obb b = box(center, Vec3(0.5));
  b.axes =
      glm::mat3_cast(glm::angleAxis(0.1, Vec3(0.0, 0.0, 1.0)) * glm::angleAxis(0.3, Vec3(1.0, 0.0, 0.0)));
  return b;
}

TEST(Sat, AnEdgeAxisOnceTakenIsKeptWhileItIsTheShallowest) {
  const Obb a = box(Vec3(0.0), Vec3(0.5));
  const Obb b = tiltedOverTheEdge(Vec3(0.96, 0.0, 1.105));
  const phys::SatResult first = phys::satTest(a, b);
  ASSERT_TRUE(first.overlap);
  ASSERT_LT(first.axis, 6);  // the bias takes the face
  ASSERT_GE(first.edgeAxis, 6);
  ASSERT_LT(first.edgeDepth, first.depth);
  // After the edge, the edge: the biased test alone gave the face and the edge by turns to a pair
  // on this side of the bias and the other (a limb rocking every other step in a ragdoll pile).
  const phys::SatResult afterEdge = phys::satTest(a, b, 0.0, first.edgeAxis);
  EXPECT_EQ(afterEdge.axis, first.edgeAxis);
  EXPECT_DOUBLE_EQ(afterEdge.depth, first.edgeDepth);
  const phys::SatResult afterFace = phys::satTest(a, b, 0.0, first.axis);
  EXPECT_EQ(afterFace.axis, first.axis);
  // Tipped over the middle of it, every edge axis is deeper than the face (0.0442 m against 0.0250 at
  // the shallowest): an edge taken before gives way to the face.
  Obb tipped = box(Vec3(0.2, 0.1, 1.2), Vec3(0.5));
  tipped.axes =
      glm::mat3_cast(glm::angleAxis(0.1, Vec3(0.0, 0.0, 1.0)) * glm::angleAxis(0.1, Vec3(1.0, 0.0, 0.0)) *
                     glm::angleAxis(0.5, Vec3(0.0, 1.0, 0.0)));
  const phys::SatResult plain = phys::satTest(a, tipped);
  ASSERT_TRUE(plain.overlap);
  ASSERT_LT(plain.axis, 6);
  ASSERT_GE(plain.edgeAxis, 6);
  ASSERT_GT(plain.edgeDepth, plain.depth + 0.01);
  EXPECT_EQ(phys::satTest(a, tipped, 0.0, plain.edgeAxis).axis, plain.axis);
}

TEST(Features, SupportFeatureIsFaceEdgeOrVertexWithinEpsilon) {
  const Obb b = box(Vec3(0.0), Vec3(0.5));
  const phys::SupportFeature face = phys::supportFeature(b, {0, 1, 0}, 0.01);
  EXPECT_EQ(face.feature, phys::Feature::Face);
  for (int k : face.corners) EXPECT_TRUE(k & 2) << "top corners only";
  const phys::SupportFeature edge = phys::supportFeature(b, glm::normalize(Vec3(1, 1, 0)), 0.01);
  EXPECT_EQ(edge.feature, phys::Feature::Edge);
  EXPECT_EQ(std::min(edge.corners[0], edge.corners[1]), 3);
  EXPECT_EQ(std::max(edge.corners[0], edge.corners[1]), 7);
  const phys::SupportFeature vertex = phys::supportFeature(b, glm::normalize(Vec3(1, 1, 1)), 0.01);
  EXPECT_EQ(vertex.feature, phys::Feature::Vertex);
  EXPECT_EQ(vertex.corners[0], 7);
  // Tilted by 0.005 over a 1 m face: still a face within the seed's 0.01; by 0.03, an edge.
  EXPECT_EQ(phys::supportFeature(b, glm::normalize(Vec3(0.005, 1, 0)), 0.01).feature, phys::Feature::Face);
  EXPECT_EQ(phys::supportFeature(b, glm::normalize(Vec3(0.03, 1, 0)), 0.01).feature, phys::Feature::Edge);
}

TEST(Features, EachOfTheSixCasesIsClassified) {
  const Obb cube = box(Vec3(0.0), Vec3(0.5));
  const Obb turned = box(Vec3(0.0), Vec3(0.5), {30, 40, 25});  // generic: a vertex along any n
  const Vec3 up(0, 1, 0), diagonal = glm::normalize(Vec3(1, 1, 0)),
                          generic = glm::normalize(Vec3(0.3, 1.0, 0.2));
  struct Case {
    Obb a;
    Obb b;
    Vec3 n;
    phys::ContactKind kind;
  };
  const Case cases[] = {
      {cube, cube, up, phys::ContactKind::FaceFace},
      {cube, cube, diagonal, phys::ContactKind::EdgeEdge},
      {cube, turned, up, phys::ContactKind::FaceVertex},
      {cube, box(Vec3(0.0), Vec3(0.5), {0, 0, 45}), up, phys::ContactKind::FaceEdge},
      {cube, turned, diagonal, phys::ContactKind::EdgeVertex},
      {turned, turned, generic, phys::ContactKind::VertexVertex},
  };
  for (const Case& c : cases) {
    const auto fa = phys::supportFeature(c.a, c.n, 0.01), fb = phys::supportFeature(c.b, -c.n, 0.01);
    EXPECT_EQ(phys::classify(fa.feature, fb.feature), c.kind) << phys::toString(c.kind);
  }
  EXPECT_EQ(phys::classify(phys::Feature::Edge, phys::Feature::Face), phys::ContactKind::FaceEdge);
  EXPECT_EQ(phys::classify(phys::Feature::Vertex, phys::Feature::Face), phys::ContactKind::FaceVertex);
  EXPECT_EQ(phys::classify(phys::Feature::Vertex, phys::Feature::Edge), phys::ContactKind::EdgeVertex);
}

void expectSeparatesAlongNormal(const phys::BoxContact& c) {
  for (int i = 0; i < c.count; ++i) {
    const phys::ContactPoint& p = c.points[i];
    EXPECT_NEAR(glm::dot(c.sat.normal, p.onB - p.onA), -p.depth, 1e-12);
  }
}

TEST(Contacts, FaceFaceAlignedGivesTheFourCorners) {
  const Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.0, 0.98, 0.0), Vec3(0.5));
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceFace);
  ASSERT_EQ(c.count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(c.points[i].depth, 0.02, 1e-12);
    EXPECT_NEAR(std::abs(c.points[i].onB.x), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(c.points[i].onB.z), 0.5, 1e-12);
  }
  expectSeparatesAlongNormal(c);
}

TEST(Contacts, FaceFaceTurned45ClipsToAnOctagon) {
  const Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.0, 0.99, 0.0), Vec3(0.5), {0, 45, 0});
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceFace);
  ASSERT_EQ(c.count, 8);
  // The square |x|, |z| <= 0.5 meets the diamond |x| + |z| <= 0.707 at (+-0.5, +-0.207) and
  // (+-0.207, +-0.5).
  const Real inner = std::sqrt(0.5) - 0.5;
  for (int i = 0; i < 8; ++i) {
    const Vec3& p = c.points[i].onB;
    const Real big = std::max(std::abs(p.x), std::abs(p.z)), small = std::min(std::abs(p.x), std::abs(p.z));
    EXPECT_NEAR(big, 0.5, 1e-9);
    EXPECT_NEAR(small, inner, 1e-9);
    EXPECT_NEAR(p.y, 0.49, 1e-9);
    EXPECT_NEAR(c.points[i].onA.y, 0.5, 1e-9);
  }
  expectSeparatesAlongNormal(c);
}

TEST(Contacts, ReductionKeepsFourPointsSpanningTheOctagon) {
  const Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.0, 0.99, 0.0), Vec3(0.5), {0, 45, 0});
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  const phys::BoxContact all = c;
  phys::reduceToFourPoints(c);
  ASSERT_EQ(c.count, 4);
  EXPECT_EQ(c.dropped, all.count - 4);  // the narrow phase never carries such a manifold whole
  // Each kept point is one of the octagon's, and the four span a quadrilateral of at least
  // 0.4 m^2 of the octagon's 0.83 (two opposite corners of it would give only a sliver).
  for (int i = 0; i < 4; ++i) {
    bool found = false;
    for (int j = 0; j < all.count; ++j) found |= glm::length(all.points[j].onB - c.points[i].onB) < 1e-12;
    EXPECT_TRUE(found);
  }
  auto area = [&](int i, int j, int k) {
    return 0.5 *
           glm::length(glm::cross(c.points[j].onB - c.points[i].onB, c.points[k].onB - c.points[i].onB));
  };
  const double quad = std::max(area(0, 1, 2) + area(0, 1, 3),
                               std::max(area(0, 2, 1) + area(0, 2, 3), area(0, 3, 1) + area(0, 3, 2)));
  EXPECT_GT(quad, 0.4);
}

TEST(Contacts, FaceFaceOffsetClipsToTheOverlap) {
  const Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.6, 0.99, 0.3), Vec3(0.5));
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  ASSERT_EQ(c.count, 4);
  std::vector<std::pair<Real, Real>> got;
  for (int i = 0; i < 4; ++i)
    got.emplace_back(std::round(c.points[i].onB.x * 1e9) / 1e9, std::round(c.points[i].onB.z * 1e9) / 1e9);
  std::sort(got.begin(), got.end());
  const std::vector<std::pair<Real, Real>> expected{{0.1, -0.2}, {0.1, 0.5}, {0.5, -0.2}, {0.5, 0.5}};
  EXPECT_EQ(got, expected);
}

TEST(Contacts, FaceEdgeGivesTheEdgesEnds) {
  // A cube turned 45 degrees about z rests an edge along z on a wide slab.
  const Obb a = box(Vec3(0.0), Vec3(2.0, 0.5, 2.0));
  const Obb b = box(Vec3(0.0, 0.5 + std::sqrt(0.5) - 0.01, 0.0), Vec3(0.5), {0, 0, 45});
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceEdge);
  ASSERT_EQ(c.count, 2);
  EXPECT_NEAR(std::abs(c.points[0].onB.z), 0.5, 1e-9);
  EXPECT_NEAR(c.points[0].onB.z, -c.points[1].onB.z, 1e-9);
  EXPECT_NEAR(c.points[0].depth, 0.01, 1e-9);
  expectSeparatesAlongNormal(c);
}

TEST(Contacts, FaceVertexGivesTheVertex) {
  // A cube standing on a corner: turn it so its diagonal (1, 1, 1) points straight down.
  const glm::dquat q = rotationBetween(glm::normalize(Vec3(-1, -1, -1)), Vec3(0, -1, 0));
  Obb b;
  b.axes = glm::mat3_cast(q);
  b.halfExtents = Vec3(0.5);
  b.center = Vec3(0.0, 0.5 + std::sqrt(0.75) - 0.01, 0.0);
  const Obb a = box(Vec3(0.0), Vec3(2.0, 0.5, 2.0));
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceVertex);
  ASSERT_EQ(c.count, 1);
  EXPECT_NEAR(c.points[0].onB.y, 0.49, 1e-9);
  EXPECT_NEAR(c.points[0].onA.y, 0.5, 1e-9);
  EXPECT_NEAR(c.points[0].depth, 0.01, 1e-9);
}

TEST(Contacts, EdgeEdgeGivesTheClosestPointsOfTheEdges) {
  auto [a, b] = caseFor(6 + 3 * 0 + 2);  // A long in x, B long in z (turned)
  const Vec3 axis = axisOf(a, b, 6 + 2);
  placeAlong(a, b, axis, 0.02);
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, c));
  EXPECT_EQ(c.kind, phys::ContactKind::EdgeEdge);
  ASSERT_EQ(c.count, 1);
  EXPECT_NEAR(c.points[0].depth, 0.02, 1e-9);
  EXPECT_NEAR(glm::length(c.points[0].onB - c.points[0].onA), 0.02, 1e-9);  // along the normal
  expectSeparatesAlongNormal(c);
}

// Contacts are found once per step (World::step), so two boxes 3 cm apart that close within the
// step need their points now: kept within the margin, and not at all beyond it.
TEST(Contacts, PointsWithinTheMarginAreKeptAsSpeculative) {
  const Obb a = box(Vec3(0.0), Vec3(0.5)), b = box(Vec3(0.0, 1.03, 0.0), Vec3(0.5));
  phys::BoxContact c;
  EXPECT_FALSE(phys::collideBoxes(a, b, 0.01, c)) << "3 cm apart: beyond the feature epsilon";
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, 0.05, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceFace);
  ASSERT_EQ(c.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(c.points[i].depth, -0.03, 1e-9) << i;
  expectSeparatesAlongNormal(c);
  EXPECT_FALSE(phys::collideBoxes(a, b, 0.01, 0.02, c)) << "3 cm apart: beyond a 2 cm margin";
}

// The margin does not tell the features apart: a cube tilted so its far edge is 2 cm higher than
// its near one still rests on an edge, whatever the margin (a margin that made it a face made a
// lean ragdoll jitter at rest), and the far corners come in only as points within the margin.
TEST(Contacts, TheMarginKeepsTheFeaturesOfTheEpsilon) {
  const Real tilt = std::asin(0.02);  // rad: the far edge 2 cm up over the 1 m face
  const Obb a = box(Vec3(0.0), Vec3(2.0, 0.5, 2.0));
  Obb b = box(Vec3(0.0), Vec3(0.5), {0.0, 0.0, glm::degrees(tilt)});
  const Real lowest =
      0.5 * std::cos(tilt) + 0.5 * std::sin(tilt);  // the centre's height over the lowest edge
  b.center = Vec3(0.0, 0.5 + lowest - 0.005, 0.0);  // that edge 5 mm in
  phys::BoxContact c;
  ASSERT_TRUE(phys::collideBoxes(a, b, 0.01, 0.1, c));
  EXPECT_EQ(c.kind, phys::ContactKind::FaceEdge);
  EXPECT_EQ(c.count, 2);
}

// Speculative points never displace touching ones: with four touching, the reduction keeps only
// them; with fewer, all of them and then the nearest speculative ones.
TEST(Contacts, ReductionKeepsTouchingPointsBeforeSpeculativeOnes) {
  phys::BoxContact c;
  c.sat.normal = Vec3(0.0, 1.0, 0.0);
  const Real depths[] = {-0.05, 0.002, -0.03, 0.001, -0.04, 0.0, -0.02};
  c.count = 7;
  for (int i = 0; i < c.count; ++i) {
    c.points[i].depth = depths[i];
    c.points[i].onA = c.points[i].onB = Vec3(std::cos(i), 0.0, std::sin(i));
  }
  phys::BoxContact fewer = c;
  phys::reduceToFourPoints(fewer, 0.01);
  ASSERT_EQ(fewer.count, 4);
  std::vector<Real> kept;
  for (int i = 0; i < 4; ++i) kept.push_back(fewer.points[i].depth);
  EXPECT_EQ(kept, (std::vector<Real>{0.002, 0.001, 0.0, -0.02})) << "three touching, then the nearest";

  c.points[0].depth = 0.003;  // now four touching
  phys::BoxContact four = c;
  phys::reduceToFourPoints(four, 0.01);
  ASSERT_EQ(four.count, 4);
  phys::reduceToFourPoints(four, 0.01);
  EXPECT_EQ(four.dropped, 0) << "four points: nothing to drop, and the count of the last call is gone";
  for (int i = 0; i < 4; ++i) EXPECT_GE(four.points[i].depth, 0.0) << i;
}

// How far a point lies outside a box (m; 0 inside).
Real outside(const Obb& box, const Vec3& p) {
  const Vec3 local = glm::transpose(box.axes) * (p - box.center);
  Vec3 excess(0.0);
  for (int k = 0; k < 3; ++k) excess[k] = std::max(std::abs(local[k]) - box.halfExtents[k], 0.0);
  return glm::length(excess);
}

// Limbs crossed at their edges: the face bias keeps a face axis whose extreme corner on the other
// box may lie far beside the face, below its plane only where the plane extends past the face. A
// point there pushed where the boxes did not touch (up to 0.3 m beside them here; in the pile of
// 16 ragdolls, a corner 0.27 m past the end of a forearm rolled it at 10 rad/s). Every point now
// lies on both boxes, or within the speculative margin of them (of two of a box's sides at once:
// sqrt 2 times it): 20000 random pairs of limb-sized boxes near each other, at a ragdoll's margin
// of 3 cm.
TEST(Contacts, EveryPointLiesOnBothBoxesWithinTheMargin) {
  const Real margin = 0.03, epsilon = 0.01;
  std::uint32_t seed = 12345;
  auto uniform = [&seed](Real lo, Real hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * (static_cast<Real>(seed >> 8) / static_cast<Real>(1u << 24));
  };
  auto limb = [&]() {
    const Vec3 half(uniform(0.04, 0.07), uniform(0.13, 0.22), uniform(0.04, 0.07));
    const glm::dvec3 euler(uniform(-180.0, 180.0), uniform(-90.0, 90.0), uniform(-180.0, 180.0));
    return box(Vec3(uniform(-0.2, 0.2), uniform(-0.2, 0.2), uniform(-0.2, 0.2)), half, euler);
  };
  int touching = 0, worstPair = -1;
  Real worst = 0.0;
  for (int pair = 0; pair < 20000; ++pair) {
    const Obb a = limb(), b = limb();
    phys::BoxContact c;
    if (!phys::collideBoxes(a, b, epsilon, margin, c)) continue;
    ++touching;
    for (int i = 0; i < c.count; ++i) {
      const Real off = std::max(outside(a, c.points[i].onA), outside(b, c.points[i].onB));
      if (off > worst) worst = off, worstPair = pair;
    }
  }
  std::printf("%d of 20000 random limb pairs in contact; farthest point off its box %.4f m (pair %d)\n",
              touching, worst, worstPair);
  EXPECT_GT(touching, 2000) << "the sample reaches the cases";
  EXPECT_LE(worst, std::sqrt(2.0) * margin + 1e-9);
}

}  // namespace
