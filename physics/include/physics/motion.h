#pragma once
// A world's motion: everything that changes as it steps and that its state hash covers (particle
// positions and previous positions, rigid bodies' poses and velocities) and its clock. Saved and
// given back to a world of the same structure that has not stepped (World::setMotion), it lets a
// run go on from a state kept in a file: the sandbox's recordings (docs/sandbox.md, "Recording
// files").
#include <cstdint>
#include <string>
#include <vector>

#include "physics/types.h"

namespace phys {

struct Motion {
  std::vector<Vec3> position;              ///< per particle, unit: m
  std::vector<Vec3> previous;              ///< per particle, unit: m; position a substep back
  std::vector<Vec3> rigidPosition;         ///< per rigid body (RigidId), unit: m
  std::vector<Quat> rigidOrientation;      ///< per rigid body, unit quaternion
  std::vector<Vec3> rigidVelocity;         ///< per rigid body, unit: m/s
  std::vector<Vec3> rigidAngularVelocity;  ///< per rigid body, unit: rad/s, world frame
  Real time = 0.0;                         ///< unit: s; World::time()
  long steps = 0;                          ///< World::stepCount()

  /// World::stateHash of a world in this motion: FNV-1a over the bytes of every array above.
  std::uint64_t hash() const;
  /// "" or what World::setMotion would refuse in it whatever the world: a non-finite or negative
  /// number, an orientation not of unit length (within kUnitTolerance). Sizes are the world's to judge.
  std::string problem() const;

  static constexpr Real kUnitTolerance = 1e-6;
};

}  // namespace phys
