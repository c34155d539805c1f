// Pushes (World::push): a force held on a body for a time gives it the impulse F t, at its point
// the angular impulse r x F t, on every body model; bad pushes are refused.
#include <cmath>

#include <gtest/gtest.h>

#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::BodyModel;
using phys::Real;
using phys::Vec3;

class Pushes : public ::testing::TestWithParam<BodyModel> {};

phys::BodyDesc cube(BodyModel model) {
  phys::BodyDesc d;
  d.model = model;
  d.center = Vec3(0.0);
  d.size = Vec3(1.0);
  d.mass = 2.0;
  return d;
}

// 10 N for 0.21 s (not a whole number of substeps: the last one takes only what is left) on 2 kg:
// 1.05 m/s, and the push is gone after it.
TEST_P(Pushes, GiveTheImpulseForceTimesDuration) {
  phys::World w = testing_phys::openSpace({}, Vec3(0.0));
  const phys::BodyId id = w.addBody(cube(GetParam()));
  w.push(id, Vec3(10.0, 0.0, 0.0), 0.21);
  ASSERT_EQ(w.pushes().size(), 1u);
  for (int i = 0; i < 60; ++i) w.step();
  EXPECT_TRUE(w.pushes().empty());
  const auto [v, omega] = w.bodyVelocity(id);
  EXPECT_NEAR(v.x, 1.05, 1e-6);
  EXPECT_NEAR(v.y, 0.0, 1e-9);
  EXPECT_NEAR(glm::length(omega), 0.0, 1e-6);
}

// 6 N along x at the top face's centre for 0.1 s on a 2 kg unit cube: L = r x J = (0, 0.5, 0) x
// (0.6, 0, 0) = (0, 0, -0.3) N m s, so w = L / I about z: -0.9 rad/s for the solid cube (I = m/6),
// -0.3 for eight corner particles (I = m/2). The point turns with the body (up to 4.5 degrees by the
// end), so within 1%.
TEST_P(Pushes, AtAPointTheyTurnTheBody) {
  phys::World w = testing_phys::openSpace({}, Vec3(0.0));
  const phys::BodyId id = w.addBody(cube(GetParam()));
  w.push(id, Vec3(6.0, 0.0, 0.0), 0.1, Vec3(0.0, 0.5, 0.0));
  for (int i = 0; i < 12; ++i) w.step();
  const auto [v, omega] = w.bodyVelocity(id);
  EXPECT_NEAR(v.x, 0.3, 0.003);
  const Real expected = -0.3 / w.bodyMass(id).inertia.z;
  if (GetParam() != BodyModel::Tetra) {
    EXPECT_NEAR(expected, GetParam() == BodyModel::Rigid ? -0.9 : -0.3, 1e-9);
  }
  EXPECT_NEAR(omega.z, expected, 0.01 * std::abs(expected));
  EXPECT_NEAR(omega.x, 0.0, 0.001);
}

INSTANTIATE_TEST_SUITE_P(Models, Pushes,
                         ::testing::Values(BodyModel::Corners, BodyModel::Tetra, BodyModel::Rigid),
                         [](const auto& model) { return std::string(phys::toString(model.param)); });

TEST(Push, BadPushesAreRefusedAndNothingIsPushed) {
  phys::World w = testing_phys::openSpace({}, Vec3(0.0));
  const phys::BodyId id = w.addBody(cube(BodyModel::Rigid));
  EXPECT_THROW(w.push(phys::BodyId(7), Vec3(1.0), 1.0), std::invalid_argument);
  EXPECT_THROW(w.push(id, Vec3(NAN, 0.0, 0.0), 1.0), std::invalid_argument);
  EXPECT_THROW(w.push(id, Vec3(1.0), 0.0), std::invalid_argument);
  EXPECT_THROW(w.push(id, Vec3(1.0), INFINITY), std::invalid_argument);
  EXPECT_THROW(w.push(id, Vec3(1.0), 1.0, Vec3(0.0, NAN, 0.0)), std::invalid_argument);
  EXPECT_TRUE(w.pushes().empty());
}

}  // namespace
