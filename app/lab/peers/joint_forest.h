#pragma once
// The scene's pins as a forest of joints: MuJoCo's own form of a jointed body (a kinematic tree,
// the child's pose given relative to its parent by the joint's few coordinates), which the
// MuJoCo adapter falls back to when the free-body form, every body free and every pin a
// <connect> of 3 rows, is too large for MuJoCo 2.2.2 (mujoco_size.h). Pure bookkeeping on the
// Description, so it is tested without MuJoCo.
//
// The pins between one pair of bodies that all start shut become one joint: at one point a ball
// joint, at two points (or more on one line) a hinge about the line, at points off a line a weld.
// A pin that starts apart, or that would close a loop, stays a constraint beside the tree.
#include <vector>

#include "peer_scene.h"

namespace lab::peers {

/// How a body hangs from its parent, or is held when it is a root.
enum class TreeJoint {
  Free,   ///< a root that moves: 6 coordinates
  Fixed,  ///< a root that never moves (a fixed body): 0
  Ball,   ///< a child turning about one point: 3
  Hinge,  ///< a child turning about one axis: 1
  Weld,   ///< a child held rigidly: 0
};

struct TreeNode {
  int parent = -1;  ///< description index of the parent; -1 for a root
  TreeJoint joint = TreeJoint::Free;
  phys::Vec3 anchor{0.0};  ///< unit: m; the joint's point in the world at the start (ball, hinge)
  phys::Vec3 axis{0.0};    ///< a hinge's unit axis in the world at the start
};

struct JointForest {
  std::vector<TreeNode> nodes;             ///< one per body, description order
  std::vector<std::vector<int>> children;  ///< per body, in description order
  std::vector<int> roots;                  ///< bodies with no parent, in description order
  std::vector<bool> pinInTree;             ///< per Description::pins: held by a joint of the tree
  int dofs = 0;                            ///< the coordinates of motion (MuJoCo's nv)
};

/// The free-body form (tree false: every movable body a Free root, every pin a constraint), or
/// the forest above (tree true).
JointForest jointForest(const Description& scene, bool tree);

}  // namespace lab::peers
