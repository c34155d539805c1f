#pragma once
// A dynamic bounding-volume tree of axis-aligned boxes, one leaf a body (the broad phase's): a
// leaf that moves is taken out and put back where it adds least surface (Goldsmith and Salmon's
// insertion cost), and every node on the way up whose children differ by more than a level is
// rotated, as an AVL tree is, so that the tree stays about log N deep in any order of inserts. A
// query then visits only the branches whose boxes overlap it, wherever the bodies are spread.
#include <cstdint>
#include <string>
#include <vector>

#include "physics/types.h"

namespace phys {

struct Aabb {
  Vec3 lo{0.0}, hi{0.0};
};

inline bool overlaps(const Aabb& a, const Aabb& b) {
  return (a.lo.x <= b.hi.x) & (b.lo.x <= a.hi.x) & (a.lo.y <= b.hi.y) & (b.lo.y <= a.hi.y) &
         (a.lo.z <= b.hi.z) & (b.lo.z <= a.hi.z);
}

/// Whether `inner` lies within `outer` (false when either has a NaN).
inline bool contains(const Aabb& outer, const Aabb& inner) {
  return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
         inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
}

class AabbTree {
 public:
  using NodeId = std::int32_t;
  static constexpr NodeId kNone = -1;

  /// Empties the tree; keeps its room.
  void clear();
  /// Makes room for `leaves` leaves, so that inserting up to that many does not allocate.
  void reserve(std::size_t leaves);
  /// Adds a leaf for `body`; returns its id, which stays the leaf's until remove().
  NodeId insert(const Aabb& box, BodyId body);
  void remove(NodeId leaf);
  /// Gives a leaf a new box: out of the tree and back in where it now belongs.
  void move(NodeId leaf, const Aabb& box);

  const Aabb& box(NodeId leaf) const { return nodes_[leaf].box; }
  /// Levels below the root (0: one leaf or none).
  int height() const { return root_ == kNone ? 0 : nodes_[root_].height; }
  std::size_t leafCount() const { return leaves_; }

  /// Calls visit(body) for every leaf whose box overlaps `box`, in no particular order.
  template <typename Visit>
  void query(const Aabb& box, Visit&& visit) const {
    if (root_ == kNone) return;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const Node& node = nodes_[stack_.back()];
      stack_.pop_back();
      if (!overlaps(node.box, box)) continue;
      if (node.height == 0) {
        visit(node.body);
      } else {
        stack_.push_back(node.left);
        stack_.push_back(node.right);
      }
    }
  }

  /// Checks every invariant (parents, heights, boxes enclosing their children, the leaf count);
  /// for tests. Empty when they hold, else what broke where.
  std::string check() const;

 private:
  struct Node {
    Aabb box;
    NodeId parent = kNone;
    NodeId left = kNone, right = kNone;  // free nodes chain through `left`
    std::int32_t height = 0;             // 0 a leaf, -1 free
    BodyId body = kNoBody;               // leaves only
  };

  NodeId allocate();
  void release(NodeId id);
  void insertLeaf(NodeId leaf);
  void removeLeaf(NodeId leaf);
  NodeId bestSibling(const Aabb& box) const;
  /// Refits and rebalances from `id` up to the root.
  void fixUpwards(NodeId id);
  /// Rotates the taller grandchild of `a` up if a's children differ by more than one level;
  /// returns the node now in a's place.
  NodeId balance(NodeId a);
  NodeId rotateUp(NodeId a, NodeId child, bool childIsRight);
  void refit(NodeId id);
  void replaceChild(NodeId parent, NodeId from, NodeId to);

  std::vector<Node> nodes_;
  NodeId root_ = kNone;
  NodeId free_ = kNone;
  std::size_t leaves_ = 0;
  mutable std::vector<NodeId> stack_;  // query's, room kept by reserve()
};

}  // namespace phys
