// The broad phase: boxes spread over two axes are swept within strips (broad_phase.cpp), and
// every pair whose bounds overlap is found exactly once, wherever the strips' edges fall.
#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Vec3;

// A k x k grid of 1 m boxes at rest in empty space, `spacing` apart along x and z, and, if asked,
// one wide flat box under all of them (wider than any strip: it is tested against every box).
// Bounds are the boxes' own grown by the feature epsilon (0.01 m) and nothing else at rest in
// zero gravity.
std::size_t pairsOfGrid(int k, double spacing, bool floor, const phys::SolverSettings& solver = {}) {
  phys::World world = testing_phys::openSpace(solver, Vec3(0.0));
  phys::BodyDesc box;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      box.center = {spacing * i, 0.5, spacing * j};
      world.addBody(box);
    }
  }
  if (floor) {
    box.center = {spacing * (k - 1) / 2.0, -0.25, spacing * (k - 1) / 2.0};
    box.size = {spacing * k + 2.0, 0.5, spacing * k + 2.0};
    world.addBody(box);
  }
  world.step();
  return world.broadPhasePairs();
}

// Touching within twice the epsilon, a box's bounds meet its 8 neighbours' (the diagonal ones by
// their corners): k (k - 1) pairs along x, as many along z, 2 (k - 1)^2 diagonal. 20 x 20 boxes
// spread over 20 m in x and z make about ten strips, so many pairs straddle an edge.
TEST(BroadPhase, AGridOfBoxesFindsEachNeighbourPairOnce) {
  const int k = 20;
  const std::size_t neighbours = 2 * k * (k - 1) + 2 * (k - 1) * (k - 1);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.03, false), 0u);  // 3 cm apart: the bounds do not meet
}

TEST(BroadPhase, AWideBoxMeetsEveryBoxOnIt) {
  const int k = 20;
  const std::size_t neighbours = 2 * k * (k - 1) + 2 * (k - 1) * (k - 1);
  EXPECT_EQ(pairsOfGrid(k, 1.015, true), neighbours + k * k);
  EXPECT_EQ(pairsOfGrid(k, 1.03, true), static_cast<std::size_t>(k * k));
}

// Along one line the boxes fill one strip across it, which is the plain sweep.
TEST(BroadPhase, ARowOfBoxesIsOneSweep) {
  EXPECT_EQ(pairsOfGrid(1, 1.015, false), 0u);
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  for (int i = 0; i < 50; ++i) {
    box.center = {1.015 * i, 0.5, 0.0};
    world.addBody(box);
  }
  world.step();
  EXPECT_EQ(world.broadPhasePairs(), 49u);
}

// The pairs, and so the contacts, come in body order whatever order the strips find them in: the
// contacts are solved in that order, which must depend on the state alone. A grid 5 mm apart
// (within the feature epsilon, so every side neighbour has a contact) spread over several strips.
TEST(BroadPhase, ContactsComeInBodyOrder) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  const int k = 12;
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      box.center = {1.005 * i, 0.5, 1.005 * j};
      world.addBody(box);
    }
  }
  world.step();
  const auto contacts = world.bodyContacts();
  ASSERT_GE(contacts.size(), static_cast<std::size_t>(2 * k * (k - 1)));
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    ASSERT_LT(contacts[c].bodyA, contacts[c].bodyB) << c;
    if (c == 0) continue;
    const auto before = std::make_pair(contacts[c - 1].bodyA, contacts[c - 1].bodyB);
    const auto now = std::make_pair(contacts[c].bodyA, contacts[c].bodyB);
    EXPECT_LE(before, now) << "contact " << c;
  }
}

}  // namespace

namespace {

// Filtered pairs are dropped whenever the filter is set: before the first step, or between two
// steps (the per-box index of ignored pairs is rebuilt), and only the pairs named.
TEST(BroadPhase, IgnoredPairsAreDroppedWhenSetAndOnlyThose) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  for (int i = 0; i < 4; ++i) {
    box.center = {0.99 * i, 0.5, 0.0};  // a row of touching boxes: pairs 0-1, 1-2, 2-3
    world.addBody(box);
  }
  world.ignoreCollision(phys::BodyId{1}, phys::BodyId{0});
  world.step();
  EXPECT_EQ(world.broadPhasePairs(), 2u);
  world.ignoreCollision(phys::BodyId{2}, phys::BodyId{3});
  world.step();
  EXPECT_EQ(world.broadPhasePairs(), 1u);
  world.ignoreCollision(phys::BodyId{0}, phys::BodyId{3});  // apart: nothing more to drop
  world.step();
  EXPECT_EQ(world.broadPhasePairs(), 1u);
}

}  // namespace

namespace {

// The strips are a way to find the pairs, not a part of the answer: one strip (every box swept
// against every box along the axis), one strip a box, or every box "wide" (tested against all)
// find the same pairs, and a tumbling pile steps to the same state.
TEST(BroadPhase, TheStripSettingsChangeNoPair) {
  phys::SolverSettings oneStrip, narrow, allWide;
  oneStrip.broadPhase.maxStrips = 1;
  narrow.broadPhase.stripsPerBody = 1;
  allWide.broadPhase.maxStripsPerBody = 1;
  const std::size_t k = 12, neighbours = 2 * k * (k - 1) + 2 * (k - 1) * (k - 1);
  ASSERT_EQ(pairsOfGrid(k, 1.015, false), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false, oneStrip), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false, narrow), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false, allWide), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, true, allWide), pairsOfGrid(k, 1.015, true));

  auto pile = [](const phys::SolverSettings& solver) {
    phys::World world({}, solver);
    phys::BodyDesc box;
    for (int i = 0; i < 40; ++i) {
      box.center = {0.3 * (i % 7), 0.6 + 1.1 * (i / 7), 0.25 * (i % 5)};
      box.orientation = glm::angleAxis(0.3 * i, glm::normalize(Vec3(1.0, 2.0, 0.5)));
      world.addBody(box);
    }
    for (int n = 0; n < 60; ++n) world.step();
    return world.stateHash();
  };
  const std::uint64_t reference = pile({});
  EXPECT_EQ(pile(oneStrip), reference);
  EXPECT_EQ(pile(narrow), reference);
  EXPECT_EQ(pile(allWide), reference);
}

// The class alone, as World drives it: pairs only after an update, found again only when asked.
TEST(BroadPhase, FindsPairsOnlyWhenUpdatedAndSaysWhenItMust) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  for (int i = 0; i < 3; ++i) {
    box.center = {0.99 * i, 0.5, 0.0};
    world.addBody(box);
  }
  world.step();  // fits the frames
  phys::BroadPhase broad;
  for (int i = 0; i < 3; ++i) broad.addBody();
  broad.indexFilters();
  EXPECT_TRUE(broad.pairs().empty());
  EXPECT_TRUE(broad.needsUpdate(world.bodyFrames()));
  broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(),
               {1.0 / 60.0, 1.0 / 60.0, 0.01, 0.0});
  ASSERT_EQ(broad.pairs().size(), 2u);
  EXPECT_EQ(broad.pairs()[0], std::make_pair(phys::BodyId{0}, phys::BodyId{1}));
  EXPECT_EQ(broad.pairs()[1], std::make_pair(phys::BodyId{1}, phys::BodyId{2}));
  EXPECT_FALSE(broad.needsUpdate(world.bodyFrames()));
  broad.ignore(phys::BodyId{2}, phys::BodyId{1});
  EXPECT_TRUE(broad.needsUpdate(world.bodyFrames()));  // stale: the filter changed
  broad.indexFilters();
  broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(),
               {1.0 / 60.0, 1.0 / 60.0, 0.01, 0.0});
  EXPECT_EQ(broad.pairs().size(), 1u);
  // A frame moved further than its bounds allowed (at rest: the epsilon alone).
  std::vector<phys::Obb> moved(world.bodyFrames().begin(), world.bodyFrames().end());
  moved[1].center.x += 0.05;
  EXPECT_TRUE(broad.needsUpdate(moved));
}

// With some bodies asleep (BroadPhaseStep::asleep) the pairs are those a sweep of every body finds,
// less the pairs of two sleeping bodies: each awake body sweeps forward and back over the sleeping
// ones before it, within strips or not, and a wide body is tested against all. 60 boxes tumbled
// into a heap, and sleeping patterns from one body awake to all but one.
TEST(BroadPhase, SleepingBodiesMeetOnlyAwakeOnes) {
  phys::World world;
  phys::BodyDesc box;
  for (int i = 0; i < 60; ++i) {
    box.center = {0.3 * (i % 7), 0.6 + 1.1 * (i / 7), 0.25 * (i % 5)};
    box.orientation = glm::angleAxis(0.3 * i, glm::normalize(Vec3(1.0, 2.0, 0.5)));
    box.size = Vec3(i == 30 ? 6.0 : 1.0, 1.0, 1.0);  // one wide enough to span strips
    world.addBody(box);
  }
  for (int n = 0; n < 40; ++n) world.step();
  phys::BroadPhaseSettings oneStrip, narrow, allWide;
  oneStrip.maxStrips = 1;
  narrow.stripsPerBody = 1;
  allWide.maxStripsPerBody = 1;
  const std::size_t n = world.bodies().size();
  for (const phys::BroadPhaseSettings& strips : {phys::BroadPhaseSettings{}, oneStrip, narrow, allWide}) {
    auto pairsWith = [&](std::span<const std::uint8_t> asleep) {
      phys::BroadPhase broad;
      for (std::size_t i = 0; i < n; ++i) broad.addBody();
      broad.indexFilters();
      const phys::BroadPhaseStep step{1.0 / 60.0, 1.0 / 240.0, 0.01, 9.81, strips, asleep};
      broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(), step);
      broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(),
                   step);  // kept bounds
      return std::vector<phys::BroadPhase::Pair>(broad.pairs().begin(), broad.pairs().end());
    };
    const std::vector<phys::BroadPhase::Pair> all = pairsWith({});
    ASSERT_GT(all.size(), 100u);
    for (int pattern = 0; pattern < 5; ++pattern) {
      std::vector<std::uint8_t> asleep(n);
      for (std::size_t i = 0; i < n; ++i) {
        const bool awake = pattern == 0   ? i == 17
                           : pattern == 1 ? i % 2 == 0
                           : pattern == 2 ? i % 7 == 3
                           : pattern == 3 ? i != 30
                                          : i == 30;
        asleep[i] = awake ? 0 : 1;
      }
      std::vector<phys::BroadPhase::Pair> expected;
      for (const auto& [a, b] : all) {
        if (asleep[a] == 0 || asleep[b] == 0) expected.emplace_back(a, b);
      }
      ASSERT_FALSE(expected.empty());
      EXPECT_EQ(pairsWith(asleep), expected) << "pattern " << pattern << ", max strips " << strips.maxStrips;
    }
  }

  // One broad phase through sleeping and waking, as a world's: a body's kept bounds are found
  // again once it wakes (here after the heap has moved on), and a sleeping body's frame is not
  // asked whether it moved.
  phys::BroadPhase broad;
  for (std::size_t i = 0; i < n; ++i) broad.addBody();
  broad.indexFilters();
  std::vector<std::uint8_t> asleep(n, 1);
  asleep[17] = 0;
  const phys::BroadPhaseStep sleeping{1.0 / 60.0, 1.0 / 240.0, 0.01, 9.81, {}, asleep};
  const phys::BroadPhaseStep awake{1.0 / 60.0, 1.0 / 240.0, 0.01, 9.81, {}, {}};
  broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(), sleeping);
  for (int k = 0; k < 30; ++k) world.step();  // the heap settles on: bounds and pairs change
  broad.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(), awake);
  phys::BroadPhase fresh;
  for (std::size_t i = 0; i < n; ++i) fresh.addBody();
  fresh.indexFilters();
  fresh.update(world.particles(), world.rigidBodies(), world.bodies(), world.bodyFrames(), awake);
  EXPECT_TRUE(
      std::equal(broad.pairs().begin(), broad.pairs().end(), fresh.pairs().begin(), fresh.pairs().end()));
  std::vector<phys::Obb> moved(world.bodyFrames().begin(), world.bodyFrames().end());
  moved[3].center.x += 0.5;
  EXPECT_FALSE(broad.needsUpdate(moved, asleep));  // body 3 sleeps
  EXPECT_TRUE(broad.needsUpdate(moved));
  moved[3] = world.bodyFrames()[3];
  moved[17].center.x += 0.5;
  EXPECT_TRUE(broad.needsUpdate(moved, asleep));  // body 17 is awake
}

}  // namespace

namespace {

// On several threads the strips are swept in pieces, each into pairs of its own (broad_phase.cpp,
// sweepInPieces): the same pairs, and so the same contacts in the same order, as on one. A grid
// 5 mm apart over about a dozen strips, some 700 strip entries: two and three pieces.
TEST(BroadPhase, TheSamePairsOnOneTwoAndThreeThreads) {
  auto contactsOf = [](int threads) {
    phys::SolverSettings solver;
    solver.threads = threads;
    phys::World world = testing_phys::openSpace(solver, Vec3(0.0));
    phys::BodyDesc box;
    for (int i = 0; i < 26; ++i) {
      for (int j = 0; j < 26; ++j) {
        box.center = {1.005 * i, 0.5, 1.005 * j};
        world.addBody(box);
      }
    }
    world.step();
    std::vector<std::pair<phys::BodyId, phys::BodyId>> pairs;
    for (const phys::BodyContact& c : world.bodyContacts()) pairs.emplace_back(c.bodyA, c.bodyB);
    return std::make_pair(world.broadPhasePairs(), pairs);
  };
  const auto one = contactsOf(1);
  EXPECT_EQ(one.first, 2u * 26 * 25 + 2u * 25 * 25);  // as AGridOfBoxesFindsEachNeighbourPairOnce
  for (const int threads : {2, 3}) {
    const auto many = contactsOf(threads);
    EXPECT_EQ(many.first, one.first) << threads << " threads";
    EXPECT_EQ(many.second, one.second) << threads << " threads";
  }
}

}  // namespace
