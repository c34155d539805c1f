#pragma once
// The passes that run eight bodies (or ragdolls) at a time, one per SIMD lane: the four stick
// methods over a StickLayout's lane groups, the links over a LinkLayout's, body damping over a
// BodyLayout's (the layouts' headers say why the order allows it). The kernels are compiled twice,
// for the x86-64 baseline and for AVX2 (relax_lanes_kernels.inc), and these functions pick the
// one the CPU can run, once. Both do per lane exactly what the scalar pass does per body.
#include <cstddef>
#include <cstdint>

#include "physics/body_layout.h"
#include "physics/link_layout.h"
#include "physics/particles.h"
#include "physics/stick_layout.h"
#include "physics/workers.h"

namespace phys::detail {

/// What the lane kernels read and write: raw arrays, so that the AVX2 copy shares no inline
/// function with the rest of the library (one compiled for AVX2 could be picked for both).
struct LaneArguments {
  Real* position = nullptr;  ///< x, y, z of each particle, one after the other
  const Real* inverseMass = nullptr;
  const StickLanes* groups = nullptr;
  std::size_t groupCount = 0;
  const LocalStick* localSticks = nullptr;
  const Real* laneValues = nullptr;     ///< StickLayout::laneValues()
  Real* lambda = nullptr;               ///< XPBD: per stick, in World::sticks() order
  Real inverseH2 = 0.0;                 ///< XPBD: 1 / h^2 (1/s^2)
  Real compliance = 0.0;                ///< XPBD: the world's, added to each stick's (m/N)
  const Real* previous = nullptr;       ///< SHAKE: x* of each particle, x, y, z one after the other
  const Real* degree = nullptr;         ///< Jacobi: per particle, the number of sticks at it
  const std::uint8_t* still = nullptr;  ///< per group, 1 to skip it (StickLayout::still); or none
  /// keepSpin (Gauss-Seidel, XPBD, Jacobi): kLaneSpinValues per lane group of the layout, its
  /// bodies' levers m (x* - c*) and masses, lane-major, so that each pass loads them as vectors;
  /// computed from x* on the substep's first pass. Each lane's body is turned back to the moment it
  /// had before its sticks (LaneSpin). Or none.
  Real* laneSpin = nullptr;
  const StickLanes* allGroups = nullptr;  ///< the layout's first group: where laneSpin starts
  bool firstPass = false;                 ///< the substep's first: laneSpin is computed, not read
};

/// keepSpin's values per lane group: per particle a lever's x, y, z and a mass, one per lane.
inline constexpr std::size_t kLaneSpinValues = std::size_t{kMaxBlockParticles} * 4 * kStickLanes;

/// The arguments for the world's particles and a layout (XPBD's and Jacobi's numbers not set).
LaneArguments laneArguments(Particles& p, const StickLayout& layout);

/// What the link kernel reads and writes, raw as LaneArguments.
struct LinkLaneArguments {
  Real* position = nullptr;
  const Real* inverseMass = nullptr;
  const LinkLanes* groups = nullptr;
  std::size_t groupCount = 0;
  const LocalLink* localLinks = nullptr;
  const Real* laneValues = nullptr;     ///< LinkLayout::laneValues()
  const std::uint8_t* still = nullptr;  ///< per group, 1 to skip it (LinkLayout::still); or none
};

/// What the body damping kernel reads and writes.
struct DampLaneArguments {
  const Real* position = nullptr;
  Real* previous = nullptr;  ///< x* of each particle, x, y, z one after the other
  const Real* inverseMass = nullptr;
  const BodyLanes* groups = nullptr;
  std::size_t groupCount = 0;
  Real fraction = 0.0;                  ///< SolverSettings::bodyDamping
  const std::uint8_t* still = nullptr;  ///< per group, 1 to skip it (BodyLayout::still); or none
};

/// The damping arguments for the world's particles and a layout.
DampLaneArguments dampLaneArguments(Particles& p, const BodyLayout& layout, Real fraction);

/// The link arguments for the world's particles and a layout.
LinkLaneArguments linkLaneArguments(Particles& p, const LinkLayout& layout);

/// Lane groups a piece of a threaded pass takes: a few microseconds of work, against the few the
/// threads take to pick a piece up.
inline constexpr std::size_t kLaneGroupsPerPiece = 16;

/// kernel(args) over all of args' lane groups: at once, on the calling thread without workers; in
/// pieces of kLaneGroupsPerPiece groups on the workers with them. The groups share no particle
/// (the layouts' headers), so the pieces may run in any order and the result is the same.
template <class Arguments, class Kernel>
void inLanePieces(const Arguments& args, const Workers* workers, Kernel kernel) {
  if (workers == nullptr) {
    kernel(args);
    return;
  }
  auto piece = [&](std::size_t begin, std::size_t end) {
    Arguments part = args;
    part.groups += begin;
    part.groupCount = end - begin;
    if (part.still != nullptr) part.still += begin;
    kernel(part);
  };
  workers->forEach(args.groupCount, kLaneGroupsPerPiece, piece);
}

/// Which compiled copy of the kernels runs.
enum class LaneIsa { Baseline, Avx2 };
/// The best the CPU can run: Avx2 where it has AVX2 and the build has that copy.
LaneIsa laneIsa();

/// The kernels of laneIsa(), or of the given copy (which must be laneIsa() or Baseline).
void relaxGaussSeidelLanes(const LaneArguments& a, LaneIsa isa = laneIsa());
void relaxXpbdLanes(const LaneArguments& a, LaneIsa isa = laneIsa());
void relaxShakeLanes(const LaneArguments& a, LaneIsa isa = laneIsa());
void relaxJacobiLanes(const LaneArguments& a, LaneIsa isa = laneIsa());
/// solveLinks() with no slack over the link lane groups.
void solveLinkLanes(const LinkLaneArguments& a, LaneIsa isa = laneIsa());
/// dampBodyMotion() over the body lane groups.
void dampBodyLanes(const DampLaneArguments& a, LaneIsa isa = laneIsa());

namespace baseline {
void relaxGaussSeidelLanes(const LaneArguments& a);
void relaxXpbdLanes(const LaneArguments& a);
void relaxShakeLanes(const LaneArguments& a);
void relaxJacobiLanes(const LaneArguments& a);
void solveLinkLanes(const LinkLaneArguments& a);
void dampBodyLanes(const DampLaneArguments& a);
}  // namespace baseline

namespace avx2 {
void relaxGaussSeidelLanes(const LaneArguments& a);
void relaxXpbdLanes(const LaneArguments& a);
void relaxShakeLanes(const LaneArguments& a);
void relaxJacobiLanes(const LaneArguments& a);
void solveLinkLanes(const LinkLaneArguments& a);
void dampBodyLanes(const DampLaneArguments& a);
}  // namespace avx2

}  // namespace phys::detail
