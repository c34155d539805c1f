// The same scene stepped twice gives the same state, bit for bit; any change shows in the hash. A
// copy steps as the original does, and a step that may be stopped is the same step.
#include <atomic>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Vec3;

phys::World mixedScene(phys::SolverMethod method) {
  phys::SolverSettings s;
  s.method = method;
  s.substeps = 2;
  phys::World world({}, s);
  for (int i = 0; i < 3; ++i) {
    phys::BodyDesc box;
    box.center = {i * 1.5, 1.0 + i, 0.0};
    box.orientation = glm::dquat(glm::dvec3(0.3 * i, 0.2, 0.1));
    box.model = i % 2 == 0 ? phys::BodyModel::Corners : phys::BodyModel::Tetra;
    world.addBody(box);
  }
  phys::ParticleId previous = world.addParticle({Vec3(0.0, 4.0, 2.0), Vec3(0.0), 0.0, true});
  for (int i = 1; i <= 5; ++i) {
    const auto p = world.addParticle({Vec3(0.3 * i, 4.0, 2.0), Vec3(0.0), 1.0});
    world.addStick(previous, p);
    previous = p;
  }
  return world;
}

TEST(Determinism, SameSceneTwiceGivesTheSameHash) {
  for (auto method : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Jacobi, phys::SolverMethod::Xpbd,
                      phys::SolverMethod::Shake}) {
    phys::World a = mixedScene(method), b = mixedScene(method);
    for (int i = 0; i < 300; ++i) {
      a.step();
      b.step();
    }
    EXPECT_EQ(a.stateHash(), b.stateHash()) << toString(method);
  }
}

TEST(Determinism, HashSeesEveryChange) {
  phys::World a = mixedScene(phys::SolverMethod::GaussSeidel);
  const auto before = a.stateHash();
  a.step();
  EXPECT_NE(a.stateHash(), before);
  phys::World b = mixedScene(phys::SolverMethod::GaussSeidel), c = mixedScene(phys::SolverMethod::Shake);
  for (int i = 0; i < 60; ++i) {
    b.step();
    c.step();
  }
  EXPECT_NE(b.stateHash(), c.stateHash());
}

// The sandbox steps copies on another thread (its time budget) and keeps them in place of the
// world: a copy must go on exactly as the original would have, contacts and islands included.
TEST(Determinism, ACopyStepsAsTheOriginalDoes) {
  phys::World a = mixedScene(phys::SolverMethod::GaussSeidel);
  for (int i = 0; i < 90; ++i) a.step();  // boxes in contact with the ground and each other
  phys::World b = a;
  const std::atomic<bool> go{false};
  for (int i = 0; i < 90; ++i) {
    a.step();
    EXPECT_TRUE(b.step(go));
  }
  EXPECT_EQ(a.stateHash(), b.stateHash());
  EXPECT_EQ(a.stepCount(), b.stepCount());
}

TEST(Determinism, AStopBeforeTheFirstSubstepStepsNothing) {
  phys::World a = mixedScene(phys::SolverMethod::Xpbd);
  a.step();
  const std::uint64_t before = a.stateHash();
  const std::atomic<bool> stop{true};
  EXPECT_FALSE(a.step(stop));
  EXPECT_EQ(a.stateHash(), before);
  EXPECT_EQ(a.stepCount(), 1);
}

}  // namespace
