// The broad phase: every pair whose bounds overlap is found exactly once, in body order, whether
// the bodies moved in the tree since the last update or not (broad_phase.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "test_util.h"

namespace {

using phys::Vec3;

// A k x k grid of 1 m boxes at rest in empty space, `spacing` apart along x and z, and, if asked,
// one wide flat box under all of them.
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
// their corners): k (k - 1) pairs along x, as many along z, 2 (k - 1)^2 diagonal.
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

TEST(BroadPhase, ARowOfBoxesFindsItsNeighbours) {
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

// The pairs, and so the contacts, come in body order whatever order the tree finds them in: the
// contacts are solved in that order, which must depend on the state alone. A grid 5 mm apart
// (within the feature epsilon, so every side neighbour has a contact).
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

// The margin decides how often a body moves in the tree, not which pairs there are: none, the
// default and 2 m find the same pairs, and a tumbling pile steps to the same state.
TEST(BroadPhase, TheMarginChangesNoPair) {
  phys::SolverSettings none, wide;
  none.broadPhase.margin = 0.0;
  wide.broadPhase.margin = 2.0;
  const std::size_t k = 12, neighbours = 2 * k * (k - 1) + 2 * (k - 1) * (k - 1);
  ASSERT_EQ(pairsOfGrid(k, 1.015, false), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false, none), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, false, wide), neighbours);
  EXPECT_EQ(pairsOfGrid(k, 1.015, true, wide), pairsOfGrid(k, 1.015, true));

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
  EXPECT_EQ(pile(none), reference);
  EXPECT_EQ(pile(wide), reference);
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
  broad.update(world.particles(), world.bodies(), world.bodyFrames(), {1.0 / 60.0, 1.0 / 60.0, 0.01, 0.0});
  ASSERT_EQ(broad.pairs().size(), 2u);
  EXPECT_EQ(broad.pairs()[0], std::make_pair(phys::BodyId{0}, phys::BodyId{1}));
  EXPECT_EQ(broad.pairs()[1], std::make_pair(phys::BodyId{1}, phys::BodyId{2}));
  EXPECT_FALSE(broad.needsUpdate(world.bodyFrames()));
  broad.ignore(phys::BodyId{2}, phys::BodyId{1});
  EXPECT_TRUE(broad.needsUpdate(world.bodyFrames()));  // stale: the filter changed
  broad.indexFilters();
  broad.update(world.particles(), world.bodies(), world.bodyFrames(), {1.0 / 60.0, 1.0 / 60.0, 0.01, 0.0});
  EXPECT_EQ(broad.pairs().size(), 1u);
  // A frame moved further than its bounds allowed (at rest: the epsilon alone).
  std::vector<phys::Obb> moved(world.bodyFrames().begin(), world.bodyFrames().end());
  moved[1].center.x += 0.05;
  EXPECT_TRUE(broad.needsUpdate(moved));
}

}  // namespace

namespace {

// Bounds at rest in zero gravity: the frame's AABB grown by the feature epsilon.
bool boundsMeet(const phys::Obb& a, const phys::Obb& b, double epsilon) {
  for (int k = 0; k < 3; ++k) {
    double ra = epsilon, rb = epsilon;
    for (int j = 0; j < 3; ++j) {
      ra += std::abs(a.axes[j][k]) * a.halfExtents[j];
      rb += std::abs(b.axes[j][k]) * b.halfExtents[j];
    }
    if (std::abs(a.center[k] - b.center[k]) > ra + rb) return false;
  }
  return true;
}

// The tree is kept from one update to the next and only the bodies that left their enlarged
// bounds move in it; the pairs must still be every overlapping pair, once, in body order, as a
// test of all pairs finds them. 150 boxes in a 12 m cube, each update some nudged by less than the
// margin (they stay put in the tree), some carried metres away, and some turned.
TEST(BroadPhase, UpdatesFindWhatATestOfAllPairsFinds) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  const int n = 150;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    box.center = {12.0 * unit(random), 12.0 * unit(random), 12.0 * unit(random)};
    world.addBody(box);
  }
  world.step();  // fits the frames
  std::vector<phys::Obb> frames(world.bodyFrames().begin(), world.bodyFrames().end());
  phys::BroadPhase broad;
  for (int i = 0; i < n; ++i) broad.addBody();
  broad.indexFilters();
  const double epsilon = 0.01, margin = 0.1;
  phys::BroadPhaseStep step{1.0 / 60.0, 1.0 / 60.0, epsilon, 0.0};
  step.settings.margin = margin;
  std::size_t movedInAll = 0;
  for (int update = 0; update < 40; ++update) {
    std::vector<bool> farMoved(n, false);
    if (update > 0) {
      for (int i = 0; i < n; ++i) {
        const double roll = unit(random);
        if (roll < 0.5) {
          frames[i].center += 0.04 * Vec3(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
        } else if (roll < 0.6) {
          frames[i].center = {12.0 * unit(random), 12.0 * unit(random), 12.0 * unit(random)};
          farMoved[i] = true;
        } else if (roll < 0.65) {
          frames[i].axes =
              glm::mat3_cast(glm::angleAxis(6.0 * unit(random), glm::normalize(Vec3(1.0, 2.0, 3.0))));
        }
      }
    }
    broad.update(world.particles(), world.bodies(), frames, step);
    ASSERT_EQ(broad.tree().check(), "") << "update " << update;
    std::vector<phys::BroadPhase::Pair> expected;
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        if (boundsMeet(frames[a], frames[b], epsilon))
          expected.emplace_back(phys::BodyId{a}, phys::BodyId{b});
      }
    }
    const auto found = broad.pairs();
    ASSERT_EQ(std::vector<phys::BroadPhase::Pair>(found.begin(), found.end()), expected)
        << "update " << update;
    if (update == 0) {
      EXPECT_EQ(broad.movedBodies(), static_cast<std::size_t>(n));
    } else {
      // Every body carried far moved in the tree; those nudged 2 cm at most, most of the rest did not.
      std::size_t far = 0;
      for (const bool f : farMoved) far += f;
      EXPECT_GE(broad.movedBodies(), far);
      EXPECT_LT(broad.movedBodies(), static_cast<std::size_t>(n / 2)) << "update " << update;
      movedInAll += broad.movedBodies();
    }
  }
  EXPECT_GT(movedInAll, 0u);
}

// Bodies that stay within their enlarged bounds are not moved in the tree, so a world at rest
// keeps its pairs without asking the tree again.
TEST(BroadPhase, AWorldAtRestMovesNothingInTheTree) {
  phys::World world = testing_phys::openSpace({}, Vec3(0.0));
  phys::BodyDesc box;
  for (int i = 0; i < 10; ++i) {
    box.center = {1.005 * i, 0.5, 0.0};
    world.addBody(box);
  }
  world.step();
  phys::BroadPhase broad;
  for (int i = 0; i < 10; ++i) broad.addBody();
  broad.indexFilters();
  const phys::BroadPhaseStep step{1.0 / 60.0, 1.0 / 60.0, 0.01, 0.0};
  broad.update(world.particles(), world.bodies(), world.bodyFrames(), step);
  EXPECT_EQ(broad.movedBodies(), 10u);
  EXPECT_EQ(broad.pairs().size(), 9u);
  broad.update(world.particles(), world.bodies(), world.bodyFrames(), step);
  EXPECT_EQ(broad.movedBodies(), 0u);
  EXPECT_EQ(broad.pairs().size(), 9u);
  std::vector<phys::Obb> moved(world.bodyFrames().begin(), world.bodyFrames().end());
  moved[4].center.y += 0.2;  // past the margin (0.1 m): out of its enlarged bounds
  broad.update(world.particles(), world.bodies(), moved, step);
  EXPECT_EQ(broad.movedBodies(), 1u);
  EXPECT_EQ(broad.pairs().size(), 9u);
  moved[4].center.y += 1.0;  // clear of both neighbours
  broad.update(world.particles(), world.bodies(), moved, step);
  EXPECT_EQ(broad.pairs().size(), 7u);
}

}  // namespace
