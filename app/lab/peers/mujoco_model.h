#pragma once
// The scene as MuJoCo's MJCF text (mujoco.cpp loads it), in one of two forms:
//
// - free bodies (the default): every body a <body> with a free joint (none when fixed: a body
//   without a joint is welded to the world), every pin a <connect> equality, so MuJoCo solves the
//   same constraints as Bullet, ODE and ours;
// - a kinematic tree (JointForest): pins that make a ball joint or a hinge become MuJoCo joints
//   between nested bodies, MuJoCo's own form, which needs no constraint rows for them and six
//   times fewer coordinates. Used only when the free-body form is too large for MuJoCo 2.2.2
//   (mujoco.cpp, mujoco_size.h), and said in the table.
//
// Either way: an <inertial> with our mass and inertia; a box, capsule (its core put on the
// body's y by `fromto`) or sphere geom; a stick a spatial tendon held at its length by a
// <tendon> equality, a range stick or range link the same tendon with a limited range (MuJoCo's
// tendon limit is exactly our one-sided distance); ground contact one explicit <pair> per body
// with our friction (the geometric mean; MuJoCo would take the larger); solids meet through
// contype/conaffinity and ignored pairs through <exclude>; spheres meet nothing but the ground.
#include <string>
#include <vector>

#include "peer_scene.h"

namespace lab::peers::mjcf {

struct Model {
  std::string xml;
  bool tree = false;     ///< the kinematic-tree form
  int dofs = 0;          ///< MuJoCo's nv for it
  int equalityRows = 0;  ///< always active: 3 a <connect>, 1 a tendon held at its length
  int limitRows = 0;     ///< at most: 1 a limited tendon, while at its limit
  int contacts = 0;      ///< room for every contact a resting pile makes (nconmax)
  int movable = 0;       ///< bodies that move
  std::vector<std::string> notes;

  /// The rows asked for: every equality and limit, and 4 a contact (a pyramidal cone of condim 3).
  int rowsWanted() const { return equalityRows + limitRows + 4 * contacts + 20; }
  /// The fewest rows worth running with: the equalities and one contact for each moving body.
  /// Fewer, and contacts are dropped as soon as the bodies land (the 136-ragdoll pile in the
  /// free-body form had room for 5 contacts and sank 114 m into the ground).
  int rowsNeeded() const { return equalityRows + 4 * movable; }
};

/// Writes the scene with timestep dt. The sizes in the text are tiny (njmax 1, nconmax 1): the
/// real ones are set on the compiled model (mujoco_size.h).
Model writeModel(const Description& scene, double dt, bool tree);

}  // namespace lab::peers::mjcf
