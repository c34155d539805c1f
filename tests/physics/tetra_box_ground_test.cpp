// A tetra box lying alone on the ground stays where it was laid (docs/physics.md, "A tetra box lying
// still"): its corners are pushed and cut as a free rigid body's (GroundContacts::markFreeTetraBoxes).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Vec3;

struct Setting {
  int iterations;
  int substeps;
};

struct Lying {
  double farthest = 0.0;  // unit: m; the centre's largest distance along the ground from where it was laid
  double turned = 0.0;    // unit: rad; the largest turn from its laid orientation
  double height = 0.0;    // unit: m; the centre's at the end
};

// The box of a 0.2 m by 1 m capsule's size, 1.4 x 0.4 x 0.4 m, laid on the ground and stepped 30 s.
Lying layTetraBox(Setting s, double friction) {
  phys::WorldSettings ws;
  ws.groundMaterial = {friction, friction};
  phys::World world(ws, testing_phys::solver(phys::SolverMethod::GaussSeidel, s.iterations, s.substeps));
  phys::BodyDesc d;
  d.center = Vec3(0.0, 0.2, 0.0);
  d.size = Vec3(1.4, 0.4, 0.4);
  d.model = phys::BodyModel::Tetra;
  d.material = {friction, friction};
  const phys::BodyId id = world.addBody(d);
  const testing_phys::Wander w = testing_phys::wanderOver30s(world, id);
  Lying run;
  run.farthest = w.farthest;
  run.turned = w.mostTurned;
  run.height = world.bodyPose(id).center.y;
  std::printf("%d x %d, friction %.1f: %.3g m off, %.3g rad turned, centre %.6f m up\n", s.iterations,
              s.substeps, friction, run.farthest, run.turned, run.height);
  return run;
}

std::string named(Setting s) {
  return std::to_string(s.iterations) + " x " + std::to_string(s.substeps);
}

TEST(TetraBoxGround, ALyingTetraBoxStaysWhereItWasLaid) {
  // A body at rest stays at rest. Pushed by its corners' weights (1/2, 1/2, 1/2 and -1/2 on its
  // particles for the two embedded bottom corners), its top particles were lifted by its sticks
  // after the push every substep, which turned the chiral 4-particle body about the vertical, and
  // friction, holding its corners against that, walked it: in 30 s up to 4.5 cm off and 10 mrad
  // turned at 10 x 1, 2.4 mm and 1.5 mrad at 3 x 1 (3 mm low), 2.8 mm at 10 x 16. Now it stays to
  // round-off (1e-14 m and rad, its centre at 0.2 m); the tolerances are the lying capsules' (1 mm and
  // 1 mrad).
  for (const Setting s : {Setting{3, 1}, Setting{10, 1}, Setting{2, 4}, Setting{10, 16}}) {
    const Lying run = layTetraBox(s, 0.6);
    EXPECT_LT(run.farthest, 1e-3) << named(s);
    EXPECT_LT(run.turned, 1e-3) << named(s);
    EXPECT_NEAR(run.height, 0.2, 1e-3) << named(s);  // neither sunk nor resting on a corner
  }
}

TEST(TetraBoxGround, AFrictionlessLyingTetraBoxDoesNotSpinUp) {
  // Nothing turns a box lying on frictionless ground about the vertical: the ground pushes along it.
  // Its sticks did, the same angular momentum every step, and it turned faster and faster: 2.0 rad
  // in 30 s at 10 x 1, 0.63 rad at 2 x 4, past half a turn at 3 x 1. Now it turns 3e-14 rad.
  for (const Setting s : {Setting{3, 1}, Setting{10, 1}, Setting{2, 4}}) {
    const Lying run = layTetraBox(s, 0.0);
    EXPECT_LT(run.turned, 1e-3) << named(s);
    EXPECT_LT(run.farthest, 1e-6) << named(s);
  }
}

}  // namespace
