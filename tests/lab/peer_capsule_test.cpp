// Capsules in the peer engines (app/lab/peers/): each engine builds our capsule (its core along
// the body's y) as its own capsule shape, turned where the engine's lies along z, with the mass
// and inertia of the box it is inscribed in. Each physical check runs in every engine built in.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "peer.h"
#include "peers/peer_scene.h"
#include "peers/pose_measures.h"
#include "scenes/scene.h"

namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr int kTwoSeconds = 120;
// How close a resting capsule stays to its exact height, in every engine: each lets contacts
// sink a little. Measured: on the ground all three within 0.2 mm; on a box Bullet and MuJoCo
// within 0.2 mm and ODE 3.8 mm low (its capsule-box contact); 5 mm is the bound.
constexpr double kRestTolerance = 0.005;

scenes::Scene load(const std::string& body) {
  return scenes::loadSceneText(
      "<scene name=\"capsule\">\n  <ground friction=\"0.6\"/>\n" + body + "</scene>\n", "peer_capsule_test");
}

std::vector<std::string> engines() {
  std::vector<std::string> e = lab::peerEngines();
  if (e.empty())
    std::cout << "[ note     ] no peer engines built in; the physical checks have nothing to run\n";
  return e;
}

// The capsule's core direction in the world: the body's y axis.
phys::Vec3 coreAxis(const phys::Quat& q) {
  return q * phys::Vec3(0.0, 1.0, 0.0);
}

TEST(PeerCapsule, DescribedWithItsRadiusCoreAndItsBoxsInertia) {
  const lab::peers::Description d = lab::peers::describe(load(
      "  <capsule name=\"c\" pos=\"0 1 0\" radius=\"0.2\" length=\"1\" mass=\"8\"/>\n"
      "  <capsule name=\"t\" pos=\"3 1 0\" radius=\"0.1\" length=\"0.6\" mass=\"4\" model=\"tetra\"/>\n"));
  ASSERT_EQ(d.bodies.size(), 2u);
  const auto& c = d.bodies[0];
  EXPECT_EQ(c.shape, lab::peers::Body::Shape::Capsule);
  EXPECT_TRUE(c.solid());
  EXPECT_NEAR(c.radius, 0.2, 1e-12);
  EXPECT_NEAR(c.halfSegment, 0.3, 1e-12);
  EXPECT_NEAR(c.halfExtents.y, 0.5, 1e-12);
  EXPECT_NEAR(c.mass, 8.0, 1e-12);
  // Its box's particles' inertia, as a box's: m (hy^2 + hz^2) about x (a 0.4 x 1 x 0.4 m box).
  EXPECT_NEAR(c.inertia.x, 8.0 * (0.25 + 0.04), 1e-9);
  EXPECT_NEAR(c.inertia.y, 8.0 * (0.04 + 0.04), 1e-9);
  EXPECT_NEAR(d.bodies[1].inertia.x, 4.0 * (0.09 + 0.01), 1e-9);  // tetra: the same moments
  EXPECT_TRUE(d.collides(0, 1));
  EXPECT_EQ(d.solidCount(), 2);
}

TEST(PeerCapsule, ALyingCapsuleRestsAtItsRadius) {
  // Radius 0.2 m, 1 m long, lying along x and just touching the ground: after 2 s it is still
  // there, its centre at the radius, its core still along x.
  const scenes::Scene scene = load(
      "  <capsule name=\"c\" pos=\"0.3 0.2 -0.1\" radius=\"0.2\" length=\"1\" euler=\"0 0 90\" "
      "mass=\"2\"/>\n");
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    const phys::Vec3 c = r.positions.at(0).at(0);
    EXPECT_NEAR(c.y, 0.2, kRestTolerance);
    EXPECT_LT(std::hypot(c.x - 0.3, c.z + 0.1), 0.01);
    EXPECT_GT(std::abs(coreAxis(r.orientations.at(0).at(0)).x), 0.999);
    EXPECT_LT(r.maxPenetration, kRestTolerance);
    std::cout << "[ " << engine << " ] lying capsule rests at " << c.y << " m (radius 0.2)\n";
  }
}

TEST(PeerCapsule, AStandingCapsuleStandsOnItsCap) {
  // Upright, 1 m tall with radius 0.1, on its lower cap: its centre stays 0.5 m up for the
  // quarter second before it could topple. A capsule built along the wrong axis would lie at
  // 0.1 m at once: this is what checks each engine's turn onto our y.
  const scenes::Scene scene = load("  <capsule name=\"c\" pos=\"0 0.5 0\" radius=\"0.1\" length=\"1\"/>\n");
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, 15, {15});
    ASSERT_TRUE(r.ran) << r.unsupported;
    EXPECT_NEAR(r.positions.at(0).at(0).y, 0.5, kRestTolerance);
    EXPECT_GT(coreAxis(r.orientations.at(0).at(0)).y, 0.999);
  }
}

TEST(PeerCapsule, ACapsuleLyingOnABoxStaysOnIt) {
  // A 1 x 0.4 x 1 m box on the ground and a capsule of radius 0.1 lying across its top face
  // (y = 0.4): after 2 s the capsule's centre is still 0.5 m up and near where it was put. A
  // capsule on a face may roll, which costs nothing: Bullet's rolled 2.2 cm (one contact point a
  // step, its default) before it fell asleep when the lab let it sleep, so 5 cm is allowed
  // sideways; awake (the lab's default since) it stays within that too.
  const scenes::Scene scene = load(
      "  <box name=\"b\" pos=\"0 0.2 0\" size=\"1 0.4 1\" mass=\"5\"/>\n"
      "  <capsule name=\"c\" pos=\"0 0.5 0.1\" radius=\"0.1\" length=\"0.8\" euler=\"0 0 90\" "
      "mass=\"1\"/>\n");
  const lab::peers::Description d = lab::peers::describe(scene);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, {kTwoSeconds});
    ASSERT_TRUE(r.ran) << r.unsupported;
    const phys::Vec3 c = r.positions.at(0).at(1);
    EXPECT_NEAR(c.y, 0.5, kRestTolerance);
    EXPECT_LT(std::hypot(c.x, c.z - 0.1), 0.05);
    EXPECT_GT(std::abs(coreAxis(r.orientations.at(0).at(1)).x), 0.999);
    // Measured on its poses, the capsule sinks into the box by no more than the engine's slop.
    const double overlap = lab::peers::bodyOverlap(d, r.positions.at(0), r.orientations.at(0));
    EXPECT_LT(overlap, kRestTolerance);
    std::cout << "[ " << engine << " ] capsule on a box rests at " << c.y << " m (0.5), overlap " << overlap
              << " m\n";
  }
}

TEST(PeerCapsule, ACapsuleRagdollsJointsHoldInEveryEngine) {
  // One capsule ragdoll (physics/capsule_ragdoll.h) dropped on its back from 1 m: its pins and
  // range links go through each engine's ball joints and distance limits, as a box ragdoll's do.
  const scenes::Scene scene =
      load("  <ragdoll name=\"r\" pos=\"0 1 0\" euler=\"80 0 0\" shape=\"capsule\"/>\n");
  const lab::peers::Description d = lab::peers::describe(scene);
  ASSERT_EQ(d.bodies.size(), 11u);
  for (const auto& b : d.bodies) EXPECT_EQ(b.shape, lab::peers::Body::Shape::Capsule) << b.name;
  EXPECT_GE(d.pins.size(), 10u);
  EXPECT_EQ(d.ignored.size(), 10u);
  std::vector<int> afterLanding;
  for (int s = 61; s <= kTwoSeconds; ++s) afterLanding.push_back(s);
  for (const std::string& engine : engines()) {
    SCOPED_TRACE(engine);
    const lab::PeerResult r = lab::runPeer(engine, scene, kDt, kTwoSeconds, afterLanding);
    ASSERT_TRUE(r.ran) << r.unsupported;
    double gap = 0.0, depth = 0.0;
    for (std::size_t k = 0; k < r.positions.size(); ++k) {
      gap = std::max(gap, lab::peers::jointGap(d, r.positions[k], r.orientations[k]));
      depth = std::max(depth, lab::peers::posePenetration(d, r.positions[k], r.orientations[k]));
    }
    EXPECT_LT(gap, 0.02);
    EXPECT_LT(depth, 0.02);
    std::cout << "[ " << engine << " ] capsule ragdoll at rest: joint gap up to " << gap
              << " m, penetration up to " << depth << " m\n";
  }
}

}  // namespace
