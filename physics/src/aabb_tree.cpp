// The broad phase's dynamic tree (aabb_tree.h).
#include "physics/aabb_tree.h"

#include <algorithm>
#include <sstream>

namespace phys {
namespace {

Aabb merged(const Aabb& a, const Aabb& b) {
  return {glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
}

// Half the surface area: what a random ray or a box's query hits a node in proportion to.
Real surface(const Aabb& a) {
  const Vec3 d = a.hi - a.lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

}  // namespace

void AabbTree::clear() {
  nodes_.clear();
  root_ = free_ = kNone;
  leaves_ = 0;
}

void AabbTree::reserve(std::size_t leaves) {
  nodes_.reserve(2 * leaves);
  // A query holds at most one pending sibling a level, and the tree is about log2(n) + 3 levels
  // high (18 for 16,000 leaves).
  stack_.reserve(128);
}

AabbTree::NodeId AabbTree::allocate() {
  if (free_ != kNone) {
    const NodeId id = free_;
    free_ = nodes_[id].left;
    nodes_[id] = Node{};
    return id;
  }
  nodes_.emplace_back();
  return static_cast<NodeId>(nodes_.size() - 1);
}

void AabbTree::release(NodeId id) {
  nodes_[id].height = -1;
  nodes_[id].left = free_;
  free_ = id;
}

AabbTree::NodeId AabbTree::insert(const Aabb& box, BodyId body) {
  const NodeId leaf = allocate();
  nodes_[leaf].box = box;
  nodes_[leaf].body = body;
  insertLeaf(leaf);
  ++leaves_;
  return leaf;
}

void AabbTree::remove(NodeId leaf) {
  removeLeaf(leaf);
  release(leaf);
  --leaves_;
}

void AabbTree::move(NodeId leaf, const Aabb& box) {
  removeLeaf(leaf);
  nodes_[leaf].box = box;
  insertLeaf(leaf);
}

// Down from the root, towards the child whose box would grow least, stopping where making the new
// leaf a sibling of the node costs less than going further: the cost of a sibling is the surface
// of the new parent, plus what every ancestor grows by (which any deeper choice pays too).
AabbTree::NodeId AabbTree::bestSibling(const Aabb& box) const {
  NodeId at = root_;
  while (nodes_[at].height > 0) {
    const Node& node = nodes_[at];
    const Real area = surface(node.box);
    const Real combined = surface(merged(node.box, box));
    const Real here = 2.0 * combined;
    const Real inherited = 2.0 * (combined - area);
    auto descend = [&](NodeId child) {
      const Node& c = nodes_[child];
      const Real grown = surface(merged(c.box, box));
      return (c.height == 0 ? grown : grown - surface(c.box)) + inherited;
    };
    const Real left = descend(node.left), right = descend(node.right);
    if (here < left && here < right) break;
    at = left <= right ? node.left : node.right;
  }
  return at;
}

void AabbTree::insertLeaf(NodeId leaf) {
  if (root_ == kNone) {
    root_ = leaf;
    nodes_[leaf].parent = kNone;
    return;
  }
  const NodeId sibling = bestSibling(nodes_[leaf].box);
  const NodeId oldParent = nodes_[sibling].parent;
  const NodeId parent = allocate();
  Node& p = nodes_[parent];
  p.parent = oldParent;
  p.box = merged(nodes_[leaf].box, nodes_[sibling].box);
  p.height = nodes_[sibling].height + 1;
  p.left = sibling;
  p.right = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (oldParent == kNone) {
    root_ = parent;
  } else {
    replaceChild(oldParent, sibling, parent);
  }
  // From the new parent: a sibling chosen high up leaves it leaning, its new leaf beside a subtree.
  fixUpwards(parent);
}

void AabbTree::removeLeaf(NodeId leaf) {
  if (leaf == root_) {
    root_ = kNone;
    return;
  }
  const NodeId parent = nodes_[leaf].parent;
  const NodeId grandparent = nodes_[parent].parent;
  const NodeId sibling = nodes_[parent].left == leaf ? nodes_[parent].right : nodes_[parent].left;
  nodes_[sibling].parent = grandparent;
  release(parent);
  if (grandparent == kNone) {
    root_ = sibling;
    return;
  }
  replaceChild(grandparent, parent, sibling);
  fixUpwards(grandparent);
}

void AabbTree::replaceChild(NodeId parent, NodeId from, NodeId to) {
  Node& p = nodes_[parent];
  if (p.left == from) {
    p.left = to;
  } else {
    p.right = to;
  }
}

void AabbTree::refit(NodeId id) {
  Node& n = nodes_[id];
  n.box = merged(nodes_[n.left].box, nodes_[n.right].box);
  n.height = 1 + std::max(nodes_[n.left].height, nodes_[n.right].height);
}

void AabbTree::fixUpwards(NodeId id) {
  while (id != kNone) {
    id = balance(id);
    refit(id);
    id = nodes_[id].parent;
  }
}

AabbTree::NodeId AabbTree::balance(NodeId a) {
  const Node& n = nodes_[a];
  if (n.height < 2) return a;
  const int lean = nodes_[n.right].height - nodes_[n.left].height;
  if (lean > 1) return rotateUp(a, n.right, true);
  if (lean < -1) return rotateUp(a, n.left, false);
  return a;
}

// `child` (a's taller child, on the side childIsRight says) takes a's place; a keeps its other
// child and takes child's shorter child, and child keeps its taller one, so that both sides of
// child end up within a level of each other.
AabbTree::NodeId AabbTree::rotateUp(NodeId a, NodeId child, bool childIsRight) {
  Node& c = nodes_[child];
  const NodeId tall = nodes_[c.left].height >= nodes_[c.right].height ? c.left : c.right;
  const NodeId shorter = tall == c.left ? c.right : c.left;
  const NodeId above = nodes_[a].parent;

  c.parent = above;
  if (above == kNone) {
    root_ = child;
  } else {
    replaceChild(above, a, child);
  }
  nodes_[a].parent = child;
  if (childIsRight) {
    nodes_[a].right = shorter;
  } else {
    nodes_[a].left = shorter;
  }
  nodes_[shorter].parent = a;
  c.left = a;
  c.right = tall;
  refit(a);
  refit(child);
  return child;
}

std::string AabbTree::check() const {
  std::ostringstream why;
  if (root_ != kNone && nodes_[root_].parent != kNone) why << "the root has a parent; ";
  std::size_t leaves = 0;
  std::vector<NodeId> todo;
  if (root_ != kNone) todo.push_back(root_);
  while (!todo.empty()) {
    const NodeId id = todo.back();
    todo.pop_back();
    const Node& n = nodes_[id];
    if (n.height < 0) {
      why << "node " << id << " is free but in the tree; ";
      continue;
    }
    if (n.height == 0) {
      ++leaves;
      continue;
    }
    const Node &l = nodes_[n.left], &r = nodes_[n.right];
    if (l.parent != id || r.parent != id) why << "node " << id << "'s children have another parent; ";
    if (n.height != 1 + std::max(l.height, r.height)) why << "node " << id << "'s height is wrong; ";
    if (!contains(n.box, l.box) || !contains(n.box, r.box))
      why << "node " << id << "'s box does not hold its children's; ";
    todo.push_back(n.left);
    todo.push_back(n.right);
  }
  if (leaves != leaves_) why << leaves << " leaves in the tree, " << leaves_ << " counted; ";
  return why.str();
}

}  // namespace phys
