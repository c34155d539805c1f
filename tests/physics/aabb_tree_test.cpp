// The broad phase's dynamic tree: a query finds exactly the leaves a test of every leaf finds,
// and the tree stays balanced and whole through inserts, moves and removals in any order.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "physics/aabb_tree.h"

namespace {

using phys::Aabb;
using phys::AabbTree;
using phys::BodyId;
using phys::Vec3;

struct Leaves {
  std::vector<Aabb> box;
  std::vector<AabbTree::NodeId> node;  // kNone when not in the tree
};

Aabb randomBox(std::mt19937& random) {
  std::uniform_real_distribution<double> at(0.0, 20.0), size(0.1, 2.0);
  const Vec3 lo(at(random), at(random), at(random));
  return {lo, lo + Vec3(size(random), size(random), size(random))};
}

std::vector<BodyId> queried(const AabbTree& tree, const Aabb& box) {
  std::vector<BodyId> out;
  tree.query(box, [&](BodyId id) { out.push_back(id); });
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<BodyId> bruteForce(const Leaves& leaves, const Aabb& box) {
  std::vector<BodyId> out;
  for (std::size_t i = 0; i < leaves.box.size(); ++i) {
    if (leaves.node[i] != AabbTree::kNone && phys::overlaps(leaves.box[i], box)) out.emplace_back(i);
  }
  return out;
}

TEST(AabbTree, QueriesFindWhatATestOfEveryLeafFinds) {
  std::mt19937 random(11);
  const std::size_t n = 500;
  AabbTree tree;
  tree.reserve(n);
  Leaves leaves;
  for (std::size_t i = 0; i < n; ++i) {
    leaves.box.push_back(randomBox(random));
    leaves.node.push_back(tree.insert(leaves.box[i], BodyId{i}));
  }
  ASSERT_EQ(tree.check(), "");
  EXPECT_EQ(tree.leafCount(), n);
  // Balanced: 11 levels for these 500 (log2 500 is 9); without the rotations a tree built by
  // insertion cost alone can be far deeper. Allowed: an AVL tree's bound, 1.45 log2(n) + 2.
  EXPECT_LE(tree.height(), 15) << "of " << tree.leafCount();
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int round = 0; round < 2000; ++round) {
    const std::size_t i = pick(random);
    const double roll = unit(random);
    if (leaves.node[i] == AabbTree::kNone) {
      leaves.node[i] = tree.insert(leaves.box[i], BodyId{i});
    } else if (roll < 0.2) {
      tree.remove(leaves.node[i]);
      leaves.node[i] = AabbTree::kNone;
    } else {
      leaves.box[i] = randomBox(random);
      tree.move(leaves.node[i], leaves.box[i]);
    }
    if (round % 100 == 0) {
      ASSERT_EQ(tree.check(), "") << "round " << round;
      const Aabb probe = randomBox(random);
      EXPECT_EQ(queried(tree, probe), bruteForce(leaves, probe)) << "round " << round;
    }
  }
  ASSERT_EQ(tree.check(), "");
  for (std::size_t i = 0; i < n; ++i) {
    if (leaves.node[i] == AabbTree::kNone) continue;
    EXPECT_EQ(tree.box(leaves.node[i]).lo, leaves.box[i].lo);
    EXPECT_EQ(queried(tree, leaves.box[i]), bruteForce(leaves, leaves.box[i])) << "leaf " << i;
  }
  EXPECT_LE(tree.height(), 15) << "of " << tree.leafCount();
}

// Leaves inserted in order along one axis (the worst order for a tree that does not rebalance: it
// becomes a list, 1,023 levels) still make a tree of log depth (10 levels here).
TEST(AabbTree, SortedInsertsStayBalanced) {
  AabbTree tree;
  for (int i = 0; i < 1024; ++i) {
    const Vec3 lo(1.5 * i, 0.0, 0.0);
    tree.insert({lo, lo + Vec3(1.0)}, BodyId{i});
  }
  ASSERT_EQ(tree.check(), "");
  EXPECT_LE(tree.height(), 16);  // 1.45 log2(1024) + 2
  // Each box meets none of the others (0.5 m gaps): one hit each, itself.
  EXPECT_EQ(queried(tree, {Vec3(15.0, 0.0, 0.0), Vec3(16.0, 1.0, 1.0)}), std::vector<BodyId>{BodyId{10}});
}

// Removing every leaf in turn leaves an empty tree that a query walks through safely.
TEST(AabbTree, EmptiesAndRefills) {
  AabbTree tree;
  std::vector<AabbTree::NodeId> nodes;
  for (int i = 0; i < 20; ++i) nodes.push_back(tree.insert({Vec3(i), Vec3(i + 1.0)}, BodyId{i}));
  for (const auto node : nodes) tree.remove(node);
  EXPECT_EQ(tree.leafCount(), 0u);
  EXPECT_EQ(tree.height(), 0);
  EXPECT_TRUE(queried(tree, {Vec3(-100.0), Vec3(100.0)}).empty());
  tree.insert({Vec3(0.0), Vec3(1.0)}, BodyId{3});
  EXPECT_EQ(queried(tree, {Vec3(0.5), Vec3(2.0)}), std::vector<BodyId>{BodyId{3}});
  ASSERT_EQ(tree.check(), "");
}

}  // namespace
