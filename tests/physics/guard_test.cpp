// The guard: a particle or body that goes non-finite or leaves the world bound is frozen where
// it last was good, reported by name, and the rest of the world keeps stepping.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "passes.h"
#include "test_util.h"

namespace {

using phys::Vec3;

TEST(Guard, BoxLeavingTheBoundIsFrozenAndReportedByName) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.bound = 100.0;
  phys::World world(ws);
  std::vector<phys::FreezeReport> reported;
  world.setFreezeCallback([&](const phys::FreezeReport& r) { reported.push_back(r); });
  phys::BoxDesc runaway;
  runaway.name = "runaway";
  runaway.center = {90.0, 0.0, 0.0};
  runaway.velocity = {600.0, 0.0, 0.0};  // 10 m per step: out within two steps
  world.addBox(runaway);
  const auto bystander = world.addParticle({Vec3(0.0), Vec3(0.0), 1.0, false, "bystander"});

  for (int i = 0; i < 60; ++i) world.step();

  ASSERT_EQ(reported.size(), 1u);
  EXPECT_EQ(reported[0].name, "runaway");
  EXPECT_NE(reported[0].reason.find("bound"), std::string::npos) << reported[0].reason;
  EXPECT_EQ(world.freezes().size(), 1u);
  EXPECT_EQ(world.metrics().frozen, 8);  // the whole box, not just the first corner
  const phys::BoxPose pose = world.boxPose(0);
  EXPECT_LE(pose.center.x, 110.0);  // stopped where it was caught, not flying on
  // The bystander fell freely all along: 1 s of free fall.
  EXPECT_NEAR(world.particles().position[bystander].y, -0.5 * 9.81, 1e-9);
}

TEST(Guard, NonFinitePositionIsFrozenAtItsLastGoodPlace) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = Vec3(0.0);
  ws.bound = std::numeric_limits<double>::max();  // let it run to overflow
  phys::World world(ws);
  const double big = 1.0e308;
  const auto id = world.addParticle({Vec3(big, 0.0, 0.0), Vec3(1.7e308, 0.0, 0.0), 1.0, false, "overflow"});
  for (int i = 0; i < 100; ++i) world.step();  // overflows to infinity after about 28 steps
  ASSERT_EQ(world.freezes().size(), 1u);
  EXPECT_EQ(world.freezes()[0].name, "overflow");
  EXPECT_EQ(world.freezes()[0].reason, "non-finite position");
  EXPECT_TRUE(std::isfinite(world.particles().position[id].x));
  EXPECT_EQ(world.particles().inverseMass[id], 0.0);
  const auto m = world.metrics();
  EXPECT_TRUE(std::isfinite(m.energy()));
  EXPECT_EQ(m.frozen, 1);
}

// A pinned particle tied to one gone NaN: every method's correction is NaN, but a pinned end is
// never written (0 times NaN would still be NaN), so it stays exactly put for the guard to see
// the real culprit. Tested on the passes themselves, since a NaN cannot be made through the API.
TEST(Guard, PinnedEndOfANaNStickIsNeverWritten) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto fresh = [&] {
    phys::Particles p;
    p.position = {Vec3(0.0), Vec3(nan, 0.0, 0.0)};
    p.previous = {Vec3(0.0), Vec3(1.0, 0.0, 0.0)};
    p.inverseMass = {0.0, 1.0};
    return p;
  };
  const std::vector<phys::Stick> sticks{{0, 1, 1.0, 1.0, 0.0}};
  std::vector<double> lambda(1, 0.0), degree{1.0, 1.0};
  std::vector<Vec3> delta(2, Vec3(0.0));
  phys::Particles p = fresh();
  phys::detail::relaxGaussSeidel(p, sticks);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "gauss-seidel";
  p = fresh();
  phys::detail::relaxJacobi(p, sticks, degree, delta);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "jacobi";
  p = fresh();
  phys::detail::relaxXpbd(p, sticks, lambda, 1.0 / 60.0, 0.0);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "xpbd";
  p = fresh();
  phys::detail::relaxShake(p, sticks);
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "shake";
  p = fresh();
  phys::Embedding both;
  both.particle = {0, 1, 0, 0};
  both.weight = {0.5, 0.5, 0.0, 0.0};
  both.count = 2;
  phys::detail::moveEmbedded(p.position, p.inverseMass, both, Vec3(nan));
  EXPECT_EQ(p.position[0], Vec3(0.0)) << "embedded point";
}

}  // namespace
