#pragma once
// The world: particles, sticks between them, boxes made of particles, and the step that moves
// them. One step is Jakobsen's loop run substeps times: forces and Verlet integration, then a
// few relaxation passes over the sticks and the ground, then ground friction.
#include <span>
#include <vector>

#include "physics/box.h"
#include "physics/particles.h"
#include "physics/settings.h"

namespace phys {

/// A particle when it is created.
struct ParticleDesc {
  Vec3 position{0.0};  ///< unit: m
  Vec3 velocity{0.0};  ///< unit: m/s, at the time of creation
  Real mass = 1.0;     ///< unit: kg; > 0 unless pinned
  bool pinned = false; ///< a pinned particle never moves (inverse mass 0)
};

/// Keeps two particles at a fixed distance (Jakobsen's stick constraint).
struct Stick {
  ParticleId a = 0;
  ParticleId b = 0;
  Real length = 0.0;  ///< unit: m
};

class World {
 public:
  /// Throws std::invalid_argument when either settings struct fails validate().
  explicit World(const WorldSettings& world = {}, const SolverSettings& solver = {});

  /// Adds one particle; throws std::invalid_argument on a non-finite input or a bad mass.
  ParticleId addParticle(const ParticleDesc& desc);
  /// Adds a stick at the particles' current distance.
  void addStick(ParticleId a, ParticleId b);
  /// Adds a stick of the given rest length (unit: m, finite and >= 0).
  void addStick(ParticleId a, ParticleId b, Real length);
  /// Adds a box of 8 corner particles and kBoxStickCount sticks; throws on bad input.
  BoxId addBox(const BoxDesc& desc);

  /// Advances the world by solverSettings().dt.
  void step();

  /// Replaces the world settings; throws std::invalid_argument (and keeps the old ones) if bad.
  void setWorldSettings(const WorldSettings& settings);
  /// Replaces the solver settings; throws std::invalid_argument (and keeps the old ones) if bad.
  void setSolverSettings(const SolverSettings& settings);

  const WorldSettings& worldSettings() const { return world_; }
  const SolverSettings& solverSettings() const { return solver_; }
  const Particles& particles() const { return particles_; }
  std::span<const Stick> sticks() const { return sticks_; }
  std::span<const Box> boxes() const { return boxes_; }
  Real time() const { return time_; }     ///< unit: s; simulated time since creation
  long stepCount() const { return steps_; }

  /// Velocity of a particle over its last substep. unit: m/s
  Vec3 velocity(ParticleId id) const;
  /// Centre and orientation of a box, fitted to its corner particles.
  BoxPose boxPose(BoxId id) const;

 private:
  Real substepDt() const { return solver_.dt / solver_.substeps; }

  WorldSettings world_;
  SolverSettings solver_;
  Particles particles_;
  std::vector<Stick> sticks_;
  std::vector<Box> boxes_;
  std::vector<Real> groundDepth_;  // per particle, deepest ground penetration this substep
  Real time_ = 0.0;
  long steps_ = 0;
};

}  // namespace phys
