// The one step loop (app/lab/runner.h): a StopOnFlag on the thread stops any run after the step
// under way, in the bare timed loop and the recording one alike, and only while it lives.
#include <atomic>

#include <gtest/gtest.h>

#include "physics/world.h"
#include "runner.h"

namespace {

phys::World fallingParticle() {
  phys::World world;
  phys::ParticleDesc p;
  p.position = phys::Vec3(0.0, 10.0, 0.0);
  world.addParticle(p);
  return world;
}

TEST(Runner, AStopFlagStopsTheRunAfterTheStepUnderWay) {
  std::atomic<bool> stop{false};
  const lab::StopOnFlag watch(stop);
  for (const bool recording : {false, true}) {
    phys::World world = fallingParticle();
    lab::RunSpec spec;
    spec.steps = 100;
    spec.maxima = recording;
    EXPECT_EQ(lab::runSteps(world, spec).stepsRun, 100) << recording;  // not set: runs whole
    stop.store(true);
    const double before = world.time();
    EXPECT_THROW(lab::runSteps(world, spec), lab::RunStopped) << recording;
    EXPECT_NEAR(world.time() - before, world.solverSettings().dt, 1e-12) << recording;  // one step
    stop.store(false);
  }
}

TEST(Runner, AStopFlagActsOnlyWhileItLives) {
  std::atomic<bool> stop{true};
  { const lab::StopOnFlag watch(stop); }
  phys::World world = fallingParticle();
  lab::RunSpec spec;
  spec.steps = 10;
  EXPECT_EQ(lab::runSteps(world, spec).stepsRun, 10);
}

}  // namespace
