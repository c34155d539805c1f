#pragma once
// What the world can tell about itself: accuracy figures, and where the step's time went.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "physics/types.h"

namespace phys {

/// Figures of the current state (World::metrics()).
struct Metrics {
  /// unit: J; from Verlet velocities, pinned particles excluded; a sleeping body is at rest
  Real kineticEnergy = 0.0;
  Real potentialEnergy = 0.0;     ///< unit: J; m g h (uniform) or m s |x - p| (point gravity)
  Real maxConstraintError = 0.0;  ///< unitless; max over sticks of |violation| / rest length
  Real rmsConstraintError = 0.0;  ///< unitless; root mean square of the same
  Real maxJointError = 0.0;   ///< unit: m; max over links of the distance outside [min, max] (a pin's gap)
  Real maxPenetration = 0.0;  ///< unit: m; deepest point below the ground or inside another box now
  Real maxSpeed = 0.0;        ///< unit: m/s; fastest particle, or rigid |v| + |w| half diagonal; asleep 0
  int contacts = 0;           ///< ground contact points pushed, and box-box contact points, in the last step
  int frozen = 0;             ///< particles frozen by the guard so far

  Real energy() const { return kineticEnergy + potentialEnergy; }
};

/// The stages of a substep, in the order World::step runs them (docs/physics.md, "One step").
/// Each stage's time goes to Profile under its own name and nowhere else.
enum class Stage : std::uint8_t {
  Animate,      ///< characters' clips moved on; their drives aimed at the clips' poses
  Integrate,    ///< Verlet with gravity and damping; the mouse drag's spring
  Frames,       ///< each body's frame fitted to its particles
  BroadPhase,   ///< the pairs of bodies whose bounds may meet within the step
  Sweep,        ///< bodies that would pass through another in the substep stopped at its surface
  NarrowPhase,  ///< the contacts of those pairs; capsules' ground points; each contact's depth at x*
  Parting,      ///< deep overlaps parted without velocity
  Sticks,       ///< the bodies' own sticks and the loose ones, by the chosen method
  Links,        ///< the joints and their drives, links created apart closing, rigid joints projected; joint
                ///< friction, once a step
  Contacts,     ///< contact projection, box-box and ground
  Friction,     ///< friction of the contacts just projected
  Velocities,   ///< rigid bodies' velocities from their change of pose; their dynamic friction and bounce
  Restitution,  ///< approach speeds before the passes, bounces after them
  BodyDamping,  ///< each body's inner motion pulled towards its rigid motion
  Guard,        ///< non-finite, out-of-bound and crushed bodies frozen
  Islands,      ///< once a step: the islands, which sleep and which wake (Islands)
};
inline constexpr std::size_t kStageCount = 16;
static_assert(static_cast<std::size_t>(Stage::Islands) + 1 == kStageCount, "Islands is the last stage");

/// The stage's name in outputs: "integrate", "broad-phase", ...
std::string_view toString(Stage stage);

/// Wall-clock time of each stage of the last World::step(), summed over its substeps.
struct Profile {
  std::array<double, kStageCount> stage{};  ///< unit: ms; indexed by Stage
  double total = 0.0;                       ///< unit: ms; the whole step

  double& operator[](Stage s) { return stage[static_cast<std::size_t>(s)]; }
  double operator[](Stage s) const { return stage[static_cast<std::size_t>(s)]; }
  /// The stages' sum; total less this is the step's own bookkeeping and clock reads. unit: ms
  double staged() const;
  /// Adds another profile stage by stage (a run's sums).
  Profile& operator+=(const Profile& other);
};

}  // namespace phys
