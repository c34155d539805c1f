// The step on several threads (SolverSettings::threads) gives the state it gives on one, bit for
// bit: every piece it runs at once shares nothing with the others (docs/physics.md, "Threads").
#include <algorithm>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "physics/capsule_ragdoll.h"
#include "physics/ragdoll.h"
#include "physics/world.h"

namespace {

using phys::Vec3;

// Enough of everything that the threaded stages cut it into several pieces: 40 box ragdolls and 40
// capsule ragdolls (many lane groups of sticks, links and body damping), over 512 bodies (three
// pieces of frames and bounds), with friction in their joints (runs of ragdolls' frictions at once),
// falling into a pile. (Integration takes one piece a thread of at least 2,048 particles: this
// world's 5,704 make two on two threads and three on three.)
phys::World pile(phys::SolverMethod method, int threads) {
  phys::SolverSettings s;
  s.method = method;
  s.iterations = 2;
  s.substeps = 2;
  s.bodyDamping = 0.5;
  s.threads = threads;
  phys::World world({}, s);
  for (int k = 0; k < 40; ++k) {
    phys::RagdollDesc r;
    const int row = k / 8;
    r.hips = Vec3((k % 8) * 2.5, 1.5 + row * 2.0, 0.0);
    r.model = k % 2 == 0 ? phys::RagdollModel::Seed : phys::RagdollModel::Lean;
    r.jointDamping = 2.0;
    phys::addRagdoll(world, r);
    r.hips.z = 3.0;
    phys::addCapsuleRagdoll(world, r);
  }
  for (int k = 0; k < 100; ++k) {
    phys::BodyDesc box;
    const int row = k / 10;
    box.center = Vec3((k % 10) * 1.2, 0.5 + row * 1.1, -4.0);
    box.model = k % 3 == 0 ? phys::BodyModel::Tetra : phys::BodyModel::Corners;
    world.addBody(box);
  }
  return world;
}

TEST(Threads, TheSameStateOnOneTwoAndThreeThreads) {
  for (const auto method : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Xpbd,
                            phys::SolverMethod::Jacobi, phys::SolverMethod::Shake}) {
    phys::World one = pile(method, 1), two = pile(method, 2), three = pile(method, 3);
    ASSERT_GT(one.bodies().size(), 2 * 256u);
    std::size_t mostPairs = 0, mostManifolds = 0;
    for (int i = 0; i < 60; ++i) {
      one.step();
      two.step();
      three.step();
      mostPairs = std::max(mostPairs, one.broadPhasePairs());
      std::set<std::pair<phys::BodyId, phys::BodyId>> manifolds;
      for (const phys::BodyContact& c : one.bodyContacts()) manifolds.emplace(c.bodyA, c.bodyB);
      mostManifolds = std::max(mostManifolds, manifolds.size());
    }
    EXPECT_EQ(two.stateHash(), one.stateHash()) << phys::toString(method);
    EXPECT_EQ(three.stateHash(), one.stateHash()) << phys::toString(method);
    EXPECT_GT(one.metrics().contacts, 100u);  // they fell into each other
    // The narrow phase collides the pairs in pieces of 256 or more, one a thread: the pile made
    // three pieces of pairs, and two of manifolds collided again in later substeps. The ground's
    // points go in pieces of 4,096 (ground_pieces.h): two. The joints' frictions in runs of 256
    // or more between two ragdolls: two.
    EXPECT_GT(mostPairs, 3 * 256u) << phys::toString(method);
    EXPECT_GT(one.jointFrictions().size(), 2 * 256u);
    EXPECT_GT(mostManifolds, 2 * 256u) << phys::toString(method);
    EXPECT_GT(one.groundContacts().size(), 4096u);
  }
}

// Asked for more threads than the machine runs at once, the step runs on what it has: the same
// state, and nothing on stderr (oneTBB warned that it ignored the workers beyond the machine's).
TEST(Threads, MoreThreadsThanTheMachineHasGiveTheSameStateSilently) {
  testing::internal::CaptureStderr();
  phys::World one = pile(phys::SolverMethod::GaussSeidel, 1),
              many = pile(phys::SolverMethod::GaussSeidel, 64);
  for (int i = 0; i < 20; ++i) {
    one.step();
    many.step();
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(many.stateHash(), one.stateHash());
  EXPECT_EQ(err, "");
}

// On two threads the pile's contacts go in two bins (ContactBins): the bodies of one bin's contacts
// and ground points are none of the other's, and every contact and ground point is in one of them.
TEST(Threads, TheContactBinsShareNoBody) {
  phys::World world = pile(phys::SolverMethod::GaussSeidel, 2);
  int dealt = 0;
  for (int i = 0; i < 60; ++i) {
    world.step();
    const phys::ContactBins& bins = world.contactBins();
    if (!bins.dealt()) continue;
    ++dealt;
    std::set<phys::BodyId> bodies[2];
    std::size_t contacts = 0, points = 0;
    for (int bin = 0; bin < 2; ++bin) {
      for (const phys::ContactBins::Range r : bins.contactRanges(bin)) {
        for (std::uint32_t k = r.begin; k < r.end; ++k) {
          bodies[bin].insert(world.bodyContacts()[k].bodyA);
          bodies[bin].insert(world.bodyContacts()[k].bodyB);
          ++contacts;
        }
      }
      for (const phys::ContactBins::Range r : bins.groundRanges(bin)) {
        for (std::uint32_t k = r.begin; k < r.end; ++k) bodies[bin].insert(world.groundContacts()[k].body);
        points += r.end - r.begin;
      }
    }
    ASSERT_EQ(contacts, world.bodyContacts().size()) << "step " << i;
    ASSERT_EQ(points, world.groundContacts().size()) << "step " << i;
    for (const phys::BodyId b : bodies[0])
      ASSERT_EQ(bodies[1].count(b), 0u) << "body " << b << ", step " << i;
  }
  EXPECT_GT(dealt, 50);  // the pile falls apart into rows and ragdolls: two bins nearly always
  // On one thread there are no bins.
  phys::World one = pile(phys::SolverMethod::GaussSeidel, 1);
  one.step();
  EXPECT_FALSE(one.contactBins().dealt());
}

// The number of threads can change between steps, and a world copied keeps its own threads.
TEST(Threads, ChangingTheThreadsMidRunChangesNothing) {
  phys::World steady = pile(phys::SolverMethod::GaussSeidel, 1);
  phys::World changing = pile(phys::SolverMethod::GaussSeidel, 2);
  for (int i = 0; i < 60; ++i) {
    if (i == 20 || i == 40) {
      phys::SolverSettings s = changing.solverSettings();
      s.threads = i == 20 ? 1 : 4;
      changing.setSolverSettings(s);
    }
    steady.step();
    changing.step();
  }
  EXPECT_EQ(changing.stateHash(), steady.stateHash());
  phys::World copy = changing;
  EXPECT_EQ(copy.solverSettings().threads, 4);
  copy.step();
  steady.step();
  EXPECT_EQ(copy.stateHash(), steady.stateHash());

  // With sleeping on too: changed between steps, the count (and the broad phase's strips, which give
  // the same pairs: BroadPhase.TheStripSettingsChangeNoPair) wakes nothing. It woke every island and
  // started every rest again, so the sandbox's threads slider changed the run.
  for (const phys::BodyModel model : {phys::BodyModel::Corners, phys::BodyModel::Rigid}) {
    auto stack = [model] {
      phys::SolverSettings s;
      s.sleep.enabled = true;
      if (model == phys::BodyModel::Corners) {
        s.iterations = 10;
        s.substeps = 4;
      }
      phys::World world({}, s);
      phys::BodyDesc box;
      box.model = model;
      for (int k = 0; k < 3; ++k) {
        box.center = Vec3(0.05 * k, 0.5 + k, 0.0);
        world.addBody(box);
      }
      box.center = Vec3(4.0, 0.5, 0.0);
      world.addBody(box);
      return world;
    };
    phys::World asleep = stack(), changed = stack();
    for (int i = 0; i < 300; ++i) {
      if (i == 150 || i == 200) {
        ASSERT_EQ(changed.islands().sleepingBodies(), 4u) << phys::toString(model);  // else it cannot fail
        phys::SolverSettings s = changed.solverSettings();
        s.threads = i == 150 ? 2 : 1;
        s.broadPhase.maxStrips = i == 150 ? 1 : phys::BroadPhaseSettings{}.maxStrips;
        changed.setSolverSettings(s);
        EXPECT_EQ(changed.islands().sleepingBodies(), 4u) << phys::toString(model);
      }
      asleep.step();
      changed.step();
    }
    EXPECT_EQ(changed.stateHash(), asleep.stateHash()) << phys::toString(model);
  }
}

TEST(Threads, ANumberOutsideOneTo64IsRefused) {
  phys::World world;
  for (const int threads : {0, -1, phys::kMaxThreads + 1}) {
    phys::SolverSettings s;
    s.threads = threads;
    EXPECT_THROW(world.setSolverSettings(s), std::invalid_argument) << threads;
  }
  EXPECT_EQ(world.solverSettings().threads, 1);
}

}  // namespace
