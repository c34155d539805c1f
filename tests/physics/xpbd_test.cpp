// XPBD: a compliant stick's stiffness does not depend on the iteration count or the step.
// A chain of n compliant sticks (compliance alpha each) hanging n unit masses stretches, at
// rest, by alpha m g (n + (n-1) + ... + 1) = alpha m g n (n + 1) / 2 in all.
#include <cstdio>
#include <tuple>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::SolverMethod;
using phys::Vec3;

constexpr int kLinks = 10;
constexpr double kLinkLength = 0.5;   // m
constexpr double kCompliance = 1e-4;  // m/N

double restingStretch(int iterations, int substeps) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.damping = 2.0;  // 1/s: let the bounce die so the static stretch is what remains
  phys::World world(ws, testing_phys::solver(SolverMethod::Xpbd, iterations, substeps));
  phys::ParticleId previous = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
  for (int i = 1; i <= kLinks; ++i) {
    const auto p = world.addParticle({Vec3(0.0, -kLinkLength * i, 0.0), Vec3(0.0), 1.0});
    world.addStick(previous, p, kLinkLength, kCompliance);
    previous = p;
  }
  for (int i = 0; i < 900; ++i) world.step();  // 15 s
  return -world.particles().position[previous].y - kLinks * kLinkLength;
}

// One compliant stick holding a 2 kg mass stretches by alpha m g whatever the iterations, the
// step or the substeps. If the multiplier were not accumulated across iterations (compliance
// applied PBD-style), more iterations would make it stiffer and this would fail.
TEST(Xpbd, CompliantStickStiffnessIsTheSameFor4And40IterationsAndAnyStep) {
  const double mass = 2.0, compliance = 1e-3;  // kg, m/N: 19.6 mm
  const double analytic = compliance * mass * 9.81;
  for (const auto& [iterations, dt, substeps] :
       {std::tuple{4, 1.0 / 60, 1}, std::tuple{40, 1.0 / 60, 1}, std::tuple{4, 1.0 / 30, 1},
        std::tuple{4, 1.0 / 240, 1}, std::tuple{40, 1.0 / 60, 8}}) {
    phys::WorldSettings ws;
    ws.ground = false;
    ws.damping = 2.0;  // 1/s: let the bounce die so the static stretch is what remains
    phys::SolverSettings s = testing_phys::solver(SolverMethod::Xpbd, iterations, substeps);
    s.dt = dt;
    phys::World world(ws, s);
    const auto top = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
    const auto bob = world.addParticle({Vec3(0.0, -1.0, 0.0), Vec3(0.0), mass});
    world.addStick(top, bob, 1.0, compliance);
    while (world.time() < 15.0) world.step();
    const double stretch = -world.particles().position[bob].y - 1.0;
    EXPECT_NEAR(stretch, analytic, 0.02 * analytic)
        << iterations << " iterations, dt " << dt << ", " << substeps << " substeps";
  }
}

// SolverSettings::compliance adds to every stick's own under XPBD: a 2 kg particle hanging from a
// pinned one by a rigid stick stretches it by m g c at rest, and a compliant stick by
// m g (c + its own), to 1e-6 m (measured: under 1e-9 m, 19.620 and 29.430 mm); the other methods
// ignore it, and the rigid stick keeps its length.
TEST(Xpbd, GlobalComplianceAddsToEveryStick) {
  const double mass = 2.0, global = 1e-3, own = 5e-4;  // kg, m/N, m/N
  auto stretch = [&](SolverMethod method, double stickCompliance) {
    phys::WorldSettings ws;
    ws.ground = false;
    ws.damping = 2.0;  // 1/s: let the bounce die so the static stretch is what remains
    phys::SolverSettings s = testing_phys::solver(method, 4, 1);
    s.compliance = global;
    phys::World world(ws, s);
    const auto top = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
    const auto bob = world.addParticle({Vec3(0.0, -1.0, 0.0), Vec3(0.0), mass});
    world.addStick(top, bob, 1.0, stickCompliance);
    while (world.time() < 15.0) world.step();
    return -world.particles().position[bob].y - 1.0;
  };
  const double rigid = stretch(SolverMethod::Xpbd, 0.0), soft = stretch(SolverMethod::Xpbd, own);
  std::printf("global compliance: stretch %.9f m (m g c %.9f m), with the stick's own %.9f m (%.9f m)\n",
              rigid, mass * 9.81 * global, soft, mass * 9.81 * (global + own));
  EXPECT_NEAR(rigid, mass * 9.81 * global, 1e-6);
  EXPECT_NEAR(soft, mass * 9.81 * (global + own), 1e-6);
  EXPECT_LT(std::abs(stretch(SolverMethod::GaussSeidel, 0.0)), 1e-9);
}

// A chain of compliant sticks needs its multipliers converged: 40 iterations, or 4 substeps of
// 4, reach the analytic stretch; 4 iterations in one substep leave the chain softer (printed,
// and tabulated in docs/physics.md).
TEST(Xpbd, CompliantChainReachesTheAnalyticStretch) {
  const double analytic = kCompliance * 9.81 * kLinks * (kLinks + 1) / 2.0;
  const double few = restingStretch(4, 1);
  const double many = restingStretch(40, 1);
  const double substepped = restingStretch(4, 4);
  std::printf(
      "compliant chain stretch: analytic %.5f m, 4 iterations %.5f m, 40 iterations %.5f m, "
      "4 substeps x 4 iterations %.5f m\n",
      analytic, few, many, substepped);
  EXPECT_NEAR(many, analytic, 0.02 * analytic);
  EXPECT_NEAR(substepped, analytic, 0.02 * analytic);
  EXPECT_GT(few, many);  // unconverged multipliers only ever make it softer
}

// With zero compliance XPBD's update is Jakobsen's projection written another way: on a
// swinging chain of unequal masses the two agree to round-off, step after step.
TEST(Xpbd, ZeroComplianceIsGaussSeidel) {
  auto chain = [](SolverMethod m) {
    phys::World world = testing_phys::openSpace(testing_phys::solver(m, 3, 2));
    phys::ParticleId previous = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
    for (int i = 1; i <= 8; ++i) {
      const auto p = world.addParticle({Vec3(0.4 * i, 0.0, 0.1 * i), Vec3(0.0), 1.0 + i});
      world.addStick(previous, p);
      previous = p;
    }
    for (int i = 0; i < 120; ++i) world.step();
    return world;
  };
  const phys::World xpbd = chain(SolverMethod::Xpbd), jakobsen = chain(SolverMethod::GaussSeidel);
  for (phys::ParticleId i{}; i < xpbd.particles().size(); ++i) {
    EXPECT_LT(glm::length(xpbd.particles().position[i] - jakobsen.particles().position[i]), 1e-9) << i;
  }
  EXPECT_GT(xpbd.metrics().maxConstraintError, 0.0);  // not trivially exact: 3 passes on 8 links
}

// Only XPBD reads compliance: the same soft chain hangs stretched under XPBD and at the rigid
// length under the other methods (given passes enough to converge).
TEST(Xpbd, OtherMethodsTreatCompliantSticksAsRigid) {
  for (SolverMethod m :
       {SolverMethod::GaussSeidel, SolverMethod::Jacobi, SolverMethod::Shake, SolverMethod::Xpbd}) {
    phys::WorldSettings ws;
    ws.ground = false;
    ws.damping = 2.0;
    phys::World world(ws, testing_phys::solver(m, m == SolverMethod::Jacobi ? 1000 : 200, 1));
    phys::ParticleId previous = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
    for (int i = 1; i <= 5; ++i) {
      const auto p = world.addParticle({Vec3(0.0, -0.5 * i, 0.0), Vec3(0.0), 1.0});
      world.addStick(previous, p, 0.5, 1e-3);  // 1 mm/N: tens of millimetres under XPBD
      previous = p;
    }
    for (int i = 0; i < 300; ++i) world.step();
    const double stretch = -world.particles().position[previous].y - 2.5;
    if (m == SolverMethod::Xpbd)
      EXPECT_GT(stretch, 0.1) << "compliance 1e-3 m/N under 5..1 kg";
    else
      EXPECT_LT(std::abs(stretch), 1e-6) << toString(m);
  }
}

}  // namespace
