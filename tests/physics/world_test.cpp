// The world refuses input it cannot step, with a message that names the field.
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "physics/world.h"

namespace {

using phys::Vec3;

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no exception)";
}

TEST(Validation, SolverSettingsNameTheBadField) {
  phys::SolverSettings s;
  EXPECT_EQ(phys::validate(s), "");
  s.dt = 0.0;
  EXPECT_NE(phys::validate(s).find("dt"), std::string::npos);
  s.dt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(phys::validate(s).find("dt"), std::string::npos);
  s = {};
  s.iterations = 0;
  EXPECT_NE(phys::validate(s).find("iterations"), std::string::npos);
  s = {};
  s.substeps = -1;
  EXPECT_NE(phys::validate(s).find("substeps"), std::string::npos);
}

TEST(Validation, WorldSettingsNameTheBadField) {
  phys::WorldSettings w;
  EXPECT_EQ(phys::validate(w), "");
  w.damping = -1.0;
  EXPECT_NE(phys::validate(w).find("damping"), std::string::npos);
  w = {};
  w.gravity.y = std::numeric_limits<double>::infinity();
  EXPECT_NE(phys::validate(w).find("gravity"), std::string::npos);
}

TEST(Validation, RejectedSettingsKeepTheOldOnes) {
  phys::World world;
  phys::SolverSettings bad;
  bad.iterations = 0;
  EXPECT_NE(messageOf([&] { world.setSolverSettings(bad); }).find("iterations"), std::string::npos);
  EXPECT_EQ(world.solverSettings().iterations, phys::SolverSettings{}.iterations);
  EXPECT_THROW(phys::World(phys::WorldSettings{}, bad), std::invalid_argument);
}

TEST(Validation, BadParticlesAndBoxesAreRefused) {
  phys::World world;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(messageOf([&] { world.addParticle({Vec3(nan, 0, 0)}); }).find("position"), std::string::npos);
  EXPECT_NE(messageOf([&] { world.addParticle({Vec3(0.0), Vec3(0.0), -1.0}); }).find("mass"), std::string::npos);
  phys::BoxDesc box;
  box.size = {1.0, 0.0, 1.0};
  EXPECT_NE(messageOf([&] { world.addBox(box); }).find("size"), std::string::npos);
  box = {};
  box.mass = 0.0;
  EXPECT_NE(messageOf([&] { world.addBox(box); }).find("mass"), std::string::npos);
  EXPECT_EQ(world.particles().size(), 0u);  // nothing half-added
  EXPECT_THROW(world.addStick(0, 1), std::invalid_argument);
}

TEST(Sticks, RelaxationRestoresLengthBetweenUnequalMasses) {
  phys::WorldSettings ws;
  ws.gravity = Vec3(0.0);
  ws.ground = false;
  phys::World world(ws);
  // Start stretched by 20%: the corrected projection moves each end in proportion to 1/m, so
  // the length comes back in one pass and the centre of mass stays where it was (the printed
  // listing would move them apart instead).
  const auto a = world.addParticle({Vec3(-0.2, 0.0, 0.0), Vec3(0.0), 1.0});
  const auto b = world.addParticle({Vec3(1.0, 0.0, 0.0), Vec3(0.0), 3.0});
  world.addParticle({Vec3(5.0)});  // unrelated particle, must not matter
  world.addStick(a, b, 1.0);
  world.step();
  const auto& p = world.particles().position;
  EXPECT_NEAR(p[b].x - p[a].x, 1.0, 1e-12);
  const double centreOfMass = (1.0 * p[a].x + 3.0 * p[b].x) / 4.0;
  EXPECT_NEAR(centreOfMass, (1.0 * -0.2 + 3.0 * 1.0) / 4.0, 1e-12);
}

TEST(Sticks, LengthMustBePositiveAndFinite) {
  phys::World world;
  const auto a = world.addParticle({Vec3(0.0)});
  const auto b = world.addParticle({Vec3(1.0)});
  EXPECT_THROW(world.addStick(a, b, -1.0), std::invalid_argument);
  EXPECT_THROW(world.addStick(a, b, std::nan("")), std::invalid_argument);
  EXPECT_TRUE(world.sticks().empty());
}

}  // namespace
