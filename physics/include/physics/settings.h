#pragma once
// Every tunable of the world and the solver, with its default and unit. The sandbox's panels,
// the scene loader, the lab and the tests read the defaults from here and nowhere else.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "physics/types.h"

namespace phys {

/// Where gravity points: one vector everywhere, or towards a point with a fixed strength.
enum class GravityMode { Uniform, Point };

/// How the constraints are relaxed (docs/physics.md compares them).
enum class SolverMethod {
  GaussSeidel,  ///< Jakobsen: project each stick in turn along its current direction
  Jacobi,       ///< every stick from the same positions, corrections averaged per particle
  Xpbd,         ///< Gauss-Seidel with a Lagrange multiplier per stick, honouring compliance
  Shake,        ///< project along each stick's direction at the start of the substep
};

/// Coulomb friction coefficients; a contact uses the geometric mean of its two materials'.
struct Material {
  Real staticFriction = 0.6;   ///< unitless; tangential motion below mu_s * normal push stops
  Real dynamicFriction = 0.5;  ///< unitless; above it, the motion is cut by mu_d * normal push
  bool operator==(const Material&) const = default;
};

/// Forces, the ground and the world's extent.
struct WorldSettings {
  GravityMode gravityMode = GravityMode::Uniform;
  Vec3 gravity{0.0, -9.81, 0.0};     ///< unit: m/s^2; the acceleration in Uniform mode
  Vec3 gravityPoint{0.0, 5.0, 0.0};  ///< unit: m; what Point mode pulls towards
  Real gravityStrength = 9.81;       ///< unit: m/s^2; the pull's magnitude in Point mode
  /// The seed's "wind resistance": velocity decays as exp(-damping * t). It acts on velocity
  /// only (REFERENCES.md: Jakobsen's "1.99" form pulls resting particles towards the origin).
  Real damping = 0.0;                ///< unit: 1/s
  bool ground = true;                ///< false: nothing below, bodies fall for ever
  Vec3 groundNormal{0.0, 1.0, 0.0};  ///< unit vector; the ground is { x : n . x = groundHeight }
  Real groundHeight = 0.0;           ///< unit: m
  Material groundMaterial;
  /// A particle farther than this from the origin along any axis is frozen and reported.
  Real bound = 1.0e6;  ///< unit: m
  /// How often the guard looks for crushed bodies (kCrushedStickError, kCrushedTime): often enough
  /// to time kCrushedTime to a twentieth.
  Real shapeCheckInterval = 0.1;  ///< unit: s
  bool operator==(const WorldSettings&) const = default;
};

/// A box (or capsule) whose worst stick has been more than kCrushedStickError of its rest length
/// off it for kCrushedTime running is crushed: no longer the body it was, and stuck so (a box
/// pressed flat onto the ground cannot be lifted by sticks that lie in the ground's plane), and
/// the guard freezes it. Hard impacts at coarse settings squeeze bodies past the limit for up
/// to about a second, and they recover (docs/physics.md, "Where energy could come from
/// nowhere"), hence the time.
inline constexpr Real kCrushedStickError = 0.5;  ///< unitless: a share of the rest length
inline constexpr Real kCrushedTime = 2.0;        ///< unit: s

/// Ranges validate() enforces, shared by the scene loader, the lab and the sandbox's sliders.
inline constexpr int kMaxIterations = 1000;  ///< per substep
inline constexpr int kMaxSubsteps = 1000;    ///< per step
inline constexpr Real kMinDt = 1e-6;         ///< unit: s; below this h^2 and XPBD's alpha lose meaning
inline constexpr Real kMaxDt = 1.0;          ///< unit: s
inline constexpr Real kMaxCompliance = 1e6;  ///< unit: m/N; softer than this is no constraint at all
inline constexpr std::size_t kMaxStrips = std::size_t{1} << 24;  ///< BroadPhaseSettings' counts
inline constexpr int kMaxPartingSweeps = 100000;                 ///< PartingSettings' sweep counts
inline constexpr int kMaxThreads = 64;                           ///< SolverSettings::threads

/// SolverSettings::maxDepenetrationSpeed's default.
inline constexpr Real kDefaultMaxDepenetrationSpeed = 3.0;  ///< unit: m/s

/// Tunables of the strips (docs/performance.md, "Broad phase"). Bodies are dealt into strips
/// across a second axis, each twice the bodies' mean extent wide.
struct BroadPhaseSettings {
  std::size_t maxStrips = std::size_t{1} << 16;  ///< strips in all, at most
  std::size_t stripsPerBody = 4;                 ///< strips per body, at most: fixes their room
  /// A body whose bounds cross more strips than this (a floor, or bounds grown by a huge speed) is
  /// tested against every body instead.
  std::size_t maxStripsPerBody = 8;
  bool operator==(const BroadPhaseSettings&) const = default;
};

/// Tunables of the parting of deep overlaps (Parting; docs/physics.md, "Where energy could come
/// from nowhere"): Gauss-Seidel sweeps, plain, then over-relaxed while they make progress.
struct PartingSettings {
  int plainSweeps = 64;        ///< pushing only; enough for the spawned scenes of the suite
  int overRelaxedSweeps = 64;  ///< then accumulated pushes, over-relaxed: a row of Bullet's pile
  Real overRelaxation = 1.7;   ///< unitless, 1 to 2; near the best for a chain of 16 bodies
  Real tolerance = 1e-6;       ///< unit: m; the sweeps stop when no correction is larger
  int progressSweeps = 16;     ///< over-relaxed sweeps between checks that the worst halved
  bool operator==(const PartingSettings&) const = default;
};

/// When a pair's face-on-face manifold is carried into the next step instead of being collided
/// again (NarrowPhase::build): while the two bodies have moved relative to each other by no more
/// than these since it was made, and if it holds every corner of the faces' overlap. Its points are
/// embedded in the bodies, so they stay where they were on each face; beyond these, they are
/// clipped again (looser bounds measured worse: docs/performance.md, "Manifolds carried from step
/// to step"). 0 and 0 collide every pair every step.
struct ManifoldReuseSettings {
  Real maxShift = 0.0001;  ///< unit: m; of B's centre, in A's frame
  Real maxTurn = 0.0002;   ///< unit: rad; of each of B's axes, in A's frame
  bool operator==(const ManifoldReuseSettings&) const = default;
};

/// Sleeping (Islands): an island whose every body has moved slower than `speed` at every point for
/// `time` goes to sleep: it is not stepped until something wakes it, and its state is kept exactly.
/// The figures are Box2D's and Jolt's order (0.05 m/s and 0.03 m/s; half a second in both).
/// Off unless asked: a World steps every body it is given. The sandbox asks for every scene that
/// does not say `<solver sleep="off">`; the lab only under `--sleep on` (docs/physics.md).
struct SleepSettings {
  bool enabled = false;
  Real speed = 0.05;  ///< unit: m/s; of a body's fastest point, at the end of a step
  Real time = 0.5;    ///< unit: s; every body of the island below `speed` this long
  bool operator==(const SleepSettings&) const = default;
};

/// The rigid joints' pins closed and hinges' axes aligned exactly after each substep's passes
/// (JointProjection; docs/physics.md, "Joint projection"). Off unless asked: a joint is then held by
/// the passes alone, as the 2020 XPBD paper solves it, and gives way to the contacts where the two
/// disagree.
struct JointProjectionSettings {
  bool enabled = false;
  /// The projection stops once every pin is this close (m) and every hinge's axes this far out of
  /// line (rad: the gap they open 1 m along the axis); > 0.
  Real tolerance = 1e-4;  ///< unit: m, and rad for the axes
  int iterations = 3;     ///< Newton steps at most, 1 to kMaxProjectionIterations
  bool operator==(const JointProjectionSettings&) const = default;
};
inline constexpr int kMaxProjectionIterations = 100;  ///< JointProjectionSettings::iterations

/// How the equations are stepped and relaxed.
struct SolverSettings {
  SolverMethod method = SolverMethod::GaussSeidel;
  Real dt = 1.0 / 60.0;  ///< unit: s; time advanced by one World::step()
  int substeps = 1;      ///< integrations per step, each of dt / substeps
  int iterations = 3;    ///< relaxation passes per substep (the seed's 3)
  /// Vertices within this distance of the deepest one count as one contact feature (the seed's
  /// 0.01); used by box-box contact classification. Also the depth beyond which an overlap a
  /// substep starts with (box-box or box-ground) is parted by moving boxes whole, without velocity.
  Real featureEpsilon = 0.01;  ///< unit: m
  /// Overlap two boxes may keep without being pushed apart. Without it, boxes touching side by
  /// side fight over a zero gap every substep and never come to rest.
  Real contactSlop = 0.001;  ///< unit: m
  /// Share of each box's internal motion (its particles' velocities less the box's rigid
  /// motion) removed at the end of each substep, keeping the box's momentum and angular
  /// momentum (Müller et al. 2007, 3.5). 1 makes boxes move as rigid bodies; 0 is Jakobsen's
  /// plain scheme, where what the passes leave of a box's deformation turns into vibration.
  /// Ragdolls need it to come to rest; stacks creep with it (docs/physics.md), hence off.
  Real bodyDamping = 0.0;  ///< unitless, 0 to 1
  /// Whether each particle body's own sticks keep its angular momentum: after every pass over the
  /// sticks, the body is turned rigidly about its centre back to the angular momentum it had before
  /// the pass. Gauss-Seidel, Jacobi and XPBD otherwise drag a spinning body's spin down (docs/physics.md,
  /// "Keeping a body's spin through its sticks"); SHAKE keeps it already, and is left as it is.
  bool keepSpin = false;
  /// Share of the normal speed a point keeps when it hits the ground or another box, reversed.
  /// 0 is Jakobsen's plain projection (the point stops); 1 bounces without loss. Impacts slower
  /// than kRestitutionMinSpeed, or than 2 |g| h (the speed a resting contact gains in a substep),
  /// never bounce, so resting contacts stay at rest. The bounce is an impulse on the box as a
  /// rigid body (docs/physics.md, "Restitution").
  Real restitution = 0.0;  ///< unitless, 0 to 1
  /// Added to every stick's own compliance by the xpbd method (the others ignore compliance):
  /// one knob that softens every stick of the world at once. Joints (links between bodies) are
  /// rigid projections in every method and are not softened.
  Real compliance = 0.0;  ///< unit: m/N, 0 to kMaxCompliance
  /// Fastest a contact may push apart an overlap that was already there at the start of a
  /// substep (boxes spawned into each other, or into the ground, or pushed there by a third
  /// box): each substep removes at most this times h of it, the rest waits for later substeps.
  /// Projected at once, an overlap d becomes a speed d / h, and the finer the substep the faster
  /// boxes fly apart (PhysX's maxDepenetrationVelocity, Box2D's contact push speed). A contact
  /// resolving only this substep's approach is always stopped in full. A link (joint) created
  /// outside its bounds, a pin whose points were placed apart, is brought within them at most
  /// this fast too; a link the motion opens is closed in full. Infinity turns it off.
  Real maxDepenetrationSpeed = kDefaultMaxDepenetrationSpeed;  ///< unit: m/s, > 0
  BroadPhaseSettings broadPhase;
  PartingSettings parting;
  ManifoldReuseSettings manifoldReuse;
  SleepSettings sleep;
  JointProjectionSettings jointProjection;
  /// Threads the step may use, the caller's included: the stages whose pieces share nothing
  /// (integration, frames, the stick, link and body-damping lanes) run them at once. The result is
  /// the same bit for bit for any number (docs/physics.md, "Threads").
  int threads = 1;  ///< 1 to kMaxThreads
  bool operator==(const SolverSettings&) const = default;
};

/// Below this normal speed an impact does not bounce (SolverSettings::restitution).
inline constexpr Real kRestitutionMinSpeed = 0.5;  ///< unit: m/s

/// Empty when the settings can be stepped; otherwise says which field is wrong and why.
std::string validate(const WorldSettings& settings);
/// Whether the ground's point nearest the origin lies within the bound along each axis; a ground
/// beyond it would hold every body that lands on it beyond the bound, where the guard freezes it.
/// True when there is no ground or its normal or height cannot be used (validate says why).
bool groundWithinBound(const WorldSettings& settings);
/// Empty when the settings can be stepped; otherwise says which field is wrong and why.
std::string validate(const SolverSettings& settings);
/// Empty when the coefficients are finite and >= 0.
std::string validate(const Material& material);
/// What a contact between the two materials uses: each coefficient the geometric mean of theirs.
Material combine(const Material& a, const Material& b);

/// "gauss-seidel", "jacobi", "xpbd", "shake": the names scene files and the lab use.
std::string_view toString(SolverMethod method);
std::optional<SolverMethod> parseSolverMethod(std::string_view name);
/// "uniform", "point".
std::string_view toString(GravityMode mode);
std::optional<GravityMode> parseGravityMode(std::string_view name);

}  // namespace phys
