#pragma once
// Small helpers shared by the physics tests.
#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/stick_layout.h"
#include "physics/world.h"

namespace testing_phys {

/// Angle between two orientations, in radians.
inline double angleBetween(const phys::Quat& a, const phys::Quat& b) {
  // From the turn between them, by atan2 of its sine and cosine halves: 2 acos(|a . b|) cannot
  // tell anything under 3e-8 rad from 0 (acos near 1).
  const phys::Quat turn = glm::inverse(glm::normalize(a)) * glm::normalize(b);
  return 2.0 * std::atan2(glm::length(glm::dvec3(turn.x, turn.y, turn.z)), std::abs(turn.w));
}

/// A world with no ground and the given gravity and solver.
inline phys::World openSpace(const phys::SolverSettings& solver = {},
                             phys::Vec3 gravity = {0.0, -9.81, 0.0}) {
  phys::WorldSettings ws;
  ws.ground = false;
  ws.gravity = gravity;
  return phys::World(ws, solver);
}

/// Settings in the order the project writes them everywhere: iterations before substeps ("IxS").
inline phys::SolverSettings solver(phys::SolverMethod method, int iterations, int substeps) {
  phys::SolverSettings s;
  s.method = method;
  s.iterations = iterations;
  s.substeps = substeps;
  return s;
}

/// A box of the rigid model.
inline phys::BodyDesc rigidBox(const phys::Vec3& centre, const phys::Vec3& size = phys::Vec3(1.0),
                               phys::Real mass = 1.0) {
  phys::BodyDesc d;
  d.center = centre;
  d.size = size;
  d.mass = mass;
  d.model = phys::BodyModel::Rigid;
  return d;
}

/// A capsule of `model`, `radius` m and `length` m end to end (its core along its y axis).
inline phys::BodyDesc capsule(phys::BodyModel model, const phys::Vec3& centre, phys::Real radius,
                              phys::Real length) {
  phys::BodyDesc d;
  d.shape = phys::Shape::Capsule;
  d.model = model;
  d.center = centre;
  d.size = phys::Vec3(2.0 * radius, length, 2.0 * radius);
  return d;
}

/// A hinge or a cone from a to b at `pivot`; the caller sets its stops, swing or twist.
inline phys::JointDesc joint(phys::JointKind kind, phys::BodyId a, phys::BodyId b, const phys::Vec3& pivot,
                             const phys::Vec3& axis, const phys::Vec3& reference) {
  return {.kind = kind, .a = a, .b = b, .pivot = pivot, .axis = axis, .reference = reference};
}

/// The world of our ragdoll scenes: wind resistance 0.2 1/s, Gauss-Seidel 2 iterations x 4
/// substeps, body damping 1 (also scripts/probes/capsule-ragdoll-drops.cpp's).
inline phys::World ragdollWorld() {
  phys::WorldSettings ws;
  ws.damping = 0.2;
  phys::SolverSettings s;
  s.iterations = 2;
  s.substeps = 4;
  s.bodyDamping = 1.0;
  return phys::World(ws, s);
}

/// How far a body wanders: its centre along the ground (x and z, m) and its turn (rad), the most of
/// each over 30 s of steps of `world` (at its own step).
struct Wander {
  double farthest = 0.0, mostTurned = 0.0;
};

inline Wander wanderOver30s(phys::World& world, phys::BodyId id) {
  const phys::BodyPose start = world.bodyPose(id);
  Wander w;
  const int steps = static_cast<int>(std::lround(30.0 / world.solverSettings().dt));
  for (int i = 0; i < steps; ++i) {
    world.step();
    const phys::BodyPose now = world.bodyPose(id);
    w.farthest =
        std::max(w.farthest, std::hypot(now.center.x - start.center.x, now.center.z - start.center.z));
    w.mostTurned = std::max(w.mostTurned, angleBetween(now.orientation, start.orientation));
  }
  return w;
}

/// How many times `layout` relaxes each of `stickCount` sticks in a pass, over its runs, chains,
/// blocks and lanes: once each, for a layout that loses and repeats none.
inline std::vector<int> timesLaidOut(const phys::StickLayout& layout, std::size_t stickCount) {
  std::vector<int> seen(stickCount, 0);
  for (const auto& list : {layout.runs(), layout.chains()}) {
    for (const phys::StickRun& run : list) {
      for (std::uint32_t k = run.begin; k < run.end; ++k) ++seen[k];
    }
  }
  for (const phys::StickBlock& block : layout.blocks()) {
    for (std::uint32_t k = 0; k < block.stickCount; ++k) ++seen[block.firstStick + k];
  }
  for (const phys::StickLanes& group : layout.lanes()) {
    for (int l = 0; l < phys::kStickLanes; ++l) {
      for (std::uint32_t k = 0; k < group.stickCount; ++k) ++seen[group.firstStick[l] + k];
    }
  }
  return seen;
}

}  // namespace testing_phys
