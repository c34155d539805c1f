// The pose-based figures the lab judges the peers by (app/lab/peers/pose_measures.h): body
// overlap, ground penetration and joint gap from centres and orientations alone, checked on
// poses placed by hand where the answer is known, and the sort-and-sweep against every pair.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "peers/peer_scene.h"
#include "peers/pose_measures.h"
#include "physics/world.h"
#include "scenes/scene.h"

namespace {

using lab::peers::Description;
using phys::Quat;
using phys::Vec3;

scenes::Scene load(const std::string& body) {
  return scenes::loadSceneText("<scene name=\"m\">\n  <ground/>\n" + body + "</scene>\n",
                               "pose_measures_test");
}

// The description's own poses: the bodies as loaded.
struct Poses {
  std::vector<Vec3> centres;
  std::vector<Quat> orientations;
};
Poses posesOf(const Description& d) {
  Poses p;
  for (const auto& b : d.bodies) {
    p.centres.push_back(b.centre);
    p.orientations.push_back(b.orientation);
  }
  return p;
}

const Quat kIdentity(1.0, 0.0, 0.0, 0.0);
Quat about(double degrees, const Vec3& axis) {
  return glm::angleAxis(glm::radians(degrees), glm::normalize(axis));
}

TEST(PoseMeasures, SeparatedBodiesDoNotOverlap) {
  const Description d = lab::peers::describe(load(
      "  <box name=\"a\" pos=\"0 0.5 0\"/>\n"
      "  <box name=\"b\" pos=\"1.2 0.5 0\" euler=\"0 30 0\"/>\n"  // its corners reach x = 0.517: 17 mm clear
      "  <capsule name=\"c\" pos=\"0 2 0\" radius=\"0.2\" length=\"1\" euler=\"0 0 90\"/>\n"
      "  <capsule name=\"e\" pos=\"0 2.401 0\" radius=\"0.2\" length=\"1\" euler=\"0 0 90\"/>\n"));  // 1 mm
                                                                                                     // above
                                                                                                     // c
  const Poses p = posesOf(d);
  EXPECT_EQ(lab::peers::bodyOverlap(d, p.centres, p.orientations), 0.0);
  EXPECT_LT(lab::peers::groundPenetration(d, p.centres, p.orientations), 1e-12);
  EXPECT_LT(lab::peers::posePenetration(d, p.centres, p.orientations), 1e-12);
}

TEST(PoseMeasures, TwoBoxesOverlapByWhatTheyArePlacedInto) {
  // Two unit cubes 0.9 m apart centre to centre overlap by 0.1 m, whichever way the pair is
  // turned as one; resting on the ground they sink into nothing.
  const Description d = lab::peers::describe(
      load("  <box name=\"a\" pos=\"0 0.5 0\"/>\n  <box name=\"b\" pos=\"3 0.5 0\"/>\n"));
  for (const Quat& turn : {kIdentity, about(37.0, Vec3(0.2, 1.0, -0.4)), about(90.0, Vec3(0.0, 0.0, 1.0))}) {
    const Vec3 centre(0.0, 5.0, 0.0);
    const std::vector<Vec3> centres = {centre, centre + turn * Vec3(0.9, 0.0, 0.0)};
    const std::vector<Quat> orientations = {turn, turn};
    EXPECT_NEAR(lab::peers::bodyOverlap(d, centres, orientations), 0.1, 1e-9);
  }
  // The same overlap on the ground: the body figure, and the ground's when one sinks deeper.
  std::vector<Vec3> centres = {Vec3(0.0, 0.5, 0.0), Vec3(0.95, 0.5, 0.0)};
  const std::vector<Quat> orientations = {kIdentity, kIdentity};
  EXPECT_NEAR(lab::peers::posePenetration(d, centres, orientations), 0.05, 1e-9);
  centres[1].y = 0.42;
  EXPECT_NEAR(lab::peers::groundPenetration(d, centres, orientations), 0.08, 1e-9);
  EXPECT_NEAR(lab::peers::posePenetration(d, centres, orientations), 0.08, 1e-9);
}

TEST(PoseMeasures, PairsThatDoNotCollideAreNotMeasured) {
  // A pair kept apart by <no-collision>, or by its groups and masks, may overlap freely.
  const Description ignored =
      lab::peers::describe(load("  <box name=\"a\" pos=\"0 0.5 0\"/>\n  <box name=\"b\" pos=\"0.5 0.5 "
                                "0\"/>\n  <no-collision a=\"a\" b=\"b\"/>\n"));
  const Poses p = posesOf(ignored);
  EXPECT_EQ(lab::peers::bodyOverlap(ignored, p.centres, p.orientations), 0.0);
  const Description masked =
      lab::peers::describe(load("  <box name=\"a\" pos=\"0 0.5 0\" group=\"1\" mask=\"1\"/>\n  <box "
                                "name=\"b\" pos=\"0.5 0.5 0\" group=\"2\" mask=\"2\"/>\n"));
  EXPECT_EQ(lab::peers::bodyOverlap(masked, p.centres, p.orientations), 0.0);
}

TEST(PoseMeasures, CapsulesOverlapByWhatTheyArePlacedInto) {
  // Two capsules of radius 0.2 lying side by side 0.35 m apart overlap by 0.05 m; crossed at
  // right angles, one 0.3 m above the other, by 0.1 m; one lying on a box's top face with its
  // core 0.15 m above the face, by 0.05 m.
  const Description d = lab::peers::describe(
      load("  <capsule name=\"c\" pos=\"0 3 0\" radius=\"0.2\" length=\"1.4\" euler=\"0 0 90\"/>\n"
           "  <capsule name=\"e\" pos=\"0 3.35 0\" radius=\"0.2\" length=\"1.4\" euler=\"0 0 90\"/>\n"
           "  <box name=\"b\" pos=\"5 0.5 0\"/>\n"));
  Poses p = posesOf(d);
  p.centres[2] = Vec3(20.0, 0.5, 0.0);  // the box out of the way
  EXPECT_NEAR(lab::peers::bodyOverlap(d, p.centres, p.orientations), 0.05, 1e-9);
  p.orientations[1] = about(90.0, Vec3(1.0, 0.0, 0.0));  // e along z, 0.3 m above c
  p.centres[1] = Vec3(0.0, 3.3, 0.0);
  EXPECT_NEAR(lab::peers::bodyOverlap(d, p.centres, p.orientations), 0.1, 1e-9);
  // c lying across the box's top face (y = 1) with its core at y = 1.15.
  p.centres[1] = Vec3(0.0, 9.0, 0.0);
  p.centres[2] = Vec3(0.0, 0.5, 0.0);
  p.centres[0] = Vec3(0.0, 1.15, 0.0);
  EXPECT_NEAR(lab::peers::bodyOverlap(d, p.centres, p.orientations), 0.05, 1e-9);
  p.centres[0].y = 1.2001;
  EXPECT_EQ(lab::peers::bodyOverlap(d, p.centres, p.orientations), 0.0);
}

TEST(PoseMeasures, ACapsulesGroundDepthIsItsSurfacesNotItsBoxCorners) {
  // A capsule of radius 0.2 and core 0.6 m tilted 45 degrees: its lowest point is the lower
  // core end less the radius. Placed touching the ground, it reads 0, though its box's lower
  // corners are 0.2 (sqrt 2 - 1) = 0.083 m below; lowered 0.03 m, it reads 0.03 m.
  const Description d = lab::peers::describe(
      load("  <capsule name=\"c\" pos=\"0 3 0\" radius=\"0.2\" length=\"1\" euler=\"0 0 45\"/>\n"));
  const Quat q = d.bodies[0].orientation;
  const double lowEnd = 0.3 * std::sqrt(0.5);  // how far the lower core end is below the centre
  std::vector<Vec3> centres = {Vec3(0.0, lowEnd + 0.2, 0.0)};
  EXPECT_NEAR(lab::peers::groundPenetration(d, centres, {q}), 0.0, 1e-12);
  centres[0].y -= 0.03;
  EXPECT_NEAR(lab::peers::groundPenetration(d, centres, {q}), 0.03, 1e-12);
}

TEST(PoseMeasures, TheSweepFindsEveryPairThatBruteForceFinds) {
  // 150 boxes and capsules dropped at random into a 4 m cube, every pose turned at random: the
  // deepest overlap over the sorted sweep equals that over all 11,175 pairs, each measured alone.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0), size(0.2, 0.9), angle(-180.0, 180.0);
  std::string body;
  for (int i = 0; i < 150; ++i) {
    const std::string pos =
        std::to_string(u(random)) + " " + std::to_string(u(random) + 5.0) + " " + std::to_string(u(random));
    const std::string euler = std::to_string(angle(random)) + " " + std::to_string(angle(random)) + " " +
                              std::to_string(angle(random));
    if (i % 3 == 0) {
      const double r = 0.5 * size(random);
      body += "  <capsule pos=\"" + pos + "\" radius=\"" + std::to_string(r) + "\" length=\"" +
              std::to_string(2.0 * r + size(random)) + "\" euler=\"" + euler + "\"/>\n";
    } else {
      body += "  <box pos=\"" + pos + "\" size=\"" + std::to_string(size(random)) + " " +
              std::to_string(size(random)) + " " + std::to_string(size(random)) + "\" euler=\"" + euler +
              "\"/>\n";
    }
  }
  const Description d = lab::peers::describe(load(body));
  const Poses p = posesOf(d);
  double brute = 0.0;
  int touching = 0;
  Description pair;  // the two bodies alone, default filtering as in the pile
  for (std::size_t i = 0; i < d.bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < d.bodies.size(); ++j) {
      pair.bodies = {d.bodies[i], d.bodies[j]};
      const double depth =
          lab::peers::bodyOverlap(pair, {p.centres[i], p.centres[j]}, {p.orientations[i], p.orientations[j]});
      brute = std::max(brute, depth);
      touching += depth > 0.0 ? 1 : 0;
    }
  }
  EXPECT_GT(touching, 20) << "too sparse a pile to test the sweep";
  EXPECT_GT(brute, 0.1);
  EXPECT_EQ(lab::peers::bodyOverlap(d, p.centres, p.orientations), brute);
}

TEST(PoseMeasures, AFreshlyBuiltJointHasNoGapAndAMovedOneItsOffset) {
  // Two boxes pinned at a point between them, and a range link whose points start 0.4 m apart
  // with max 0.5: as loaded the gap is 0. Moving b 0.03 m along z opens the pin by 0.03 m;
  // moving it 0.2 m along y (away from a) takes the range's points 0.6 m apart, 0.1 m past max.
  const Description d = lab::peers::describe(
      load("  <box name=\"a\" pos=\"0 3 0\" size=\"0.2 1 0.2\"/>\n"
           "  <box name=\"b\" pos=\"0 1.9 0\" size=\"0.2 1 0.2\"/>\n"
           "  <link a=\"a\" b=\"b\" point=\"0 2.45 0\"/>\n"
           "  <link a=\"a\" b=\"b\" a-point=\"0 2.6 0\" b-point=\"0 2.2 0\" max=\"0.5\"/>\n"
           "  <no-collision a=\"a\" b=\"b\"/>\n"));
  ASSERT_EQ(d.pins.size(), 1u);
  ASSERT_EQ(d.distances.size(), 1u);
  Poses p = posesOf(d);
  EXPECT_LT(lab::peers::jointGap(d, p.centres, p.orientations), 1e-9);
  p.centres[1].z += 0.03;
  EXPECT_NEAR(lab::peers::jointGap(d, p.centres, p.orientations), 0.03, 1e-9);
  p.centres[1] = d.bodies[1].centre - Vec3(0.0, 0.2, 0.0);
  EXPECT_NEAR(lab::peers::jointGap(d, p.centres, p.orientations), 0.2, 1e-9);  // the pin's 0.2 is the larger
  // Turning b about the pin keeps the pin shut: the gap is the range's alone.
  p.centres[1] =
      Vec3(0.0, 2.45, 0.0) + about(60.0, Vec3(0, 0, 1)) * (d.bodies[1].centre - Vec3(0.0, 2.45, 0.0));
  p.orientations[1] = about(60.0, Vec3(0, 0, 1));
  const double rangeLength = glm::length(
      lab::peers::toWorld(p.centres[1], p.orientations[1], d.distances[0].localB) - d.distances[0].worldA);
  EXPECT_NEAR(lab::peers::jointGap(d, p.centres, p.orientations), std::max(0.0, rangeLength - 0.5), 1e-9);
}

TEST(PoseMeasures, ABodyGoneToInfinityIsAsBadAsItGets) {
  const Description d = lab::peers::describe(
      load("  <box name=\"a\" pos=\"0 0.5 0\"/>\n  <box name=\"b\" pos=\"3 0.5 0\"/>\n"));
  Poses p = posesOf(d);
  p.centres[1].x = std::nan("");
  EXPECT_TRUE(std::isinf(lab::peers::bodyOverlap(d, p.centres, p.orientations)));
  EXPECT_TRUE(std::isinf(lab::peers::posePenetration(d, p.centres, p.orientations)));
}

// On our own world the pose measure and Metrics::maxPenetration are the same geometry: a stack
// of three boxes settled for a second at 10 x 32, where our boxes are rigid to 2e-6, reads the
// same deepest overlap (ours rests boxes 1 mm into each other) within 1e-5 m. (At 1 x 8 a stack
// of ten squashes by 0.14% and the pose measure, which takes every body as rigid, reads 2.3 mm
// against 1 mm: it is for rigid bodies, the peers', and ours keep World::metrics.)
TEST(PoseMeasures, AgreesWithOurOwnMetricOnOurRigidEnoughWorld) {
  scenes::Scene scene = load(
      "  <solver iterations=\"10\" substeps=\"32\"/>\n  <stack name=\"s\" pos=\"0 0 0\" count=\"3\" "
      "size=\"1\"/>\n");
  for (int s = 0; s < 60; ++s) scene.world.step();
  const Description d = lab::peers::describe(scene);
  const Poses p = posesOf(d);
  const double ours = scene.world.metrics().maxPenetration;
  EXPECT_GT(ours, 1e-4) << "nothing to compare";
  EXPECT_NEAR(lab::peers::posePenetration(d, p.centres, p.orientations), ours, 1e-5);
}

}  // namespace
