#pragma once
// A few constraint rows between two rigid bodies solved together (docs/physics.md, "Standing for a
// minute"): a contact patch's points along its normal, its two friction directions and its twist,
// or those of a body's patches on the bodies under it. Each row is a Jacobian: B moves along
// `linear` and turns about `armB`; A the other way. A direct solve over the rows within their
// bounds finds the impulses (an active set), then projected Gauss-Seidel over numbers alone polishes
// them, each row's residual read from the push and turn the impulses so far give the two bodies;
// each body then takes them as one push and one turn. Solved one row after another on the
// bodies, each row turned a box before the next was read, and a patch's friction, applied at its
// face, tipped a box that its points then had to right: a rigid stack of 40 swayed by millimetres
// and its top boxes hopped.
#include <array>
#include <cstddef>
#include <limits>
#include <span>

#include "physics/rigid_bodies.h"
#include "physics/rigid_contacts.h"

namespace phys::detail {

/// The most points a patch solved as a block holds: a box's corners near the ground.
inline constexpr std::size_t kMostBlockPoints = PatchAnchor::kKeptPoints;
/// A patch's rows: its points, two friction directions and its twist.
inline constexpr std::size_t kMostPatchRows = kMostBlockPoints + 3;
/// A block's rows: a body on two held boxes (two patches of 4 points) with room to spare.
inline constexpr std::size_t kMostBlockRows = 16;
/// Projected Gauss-Seidel sweeps over a block's numbers: at most this many, and no more once a
/// sweep moves no row by more than kBlockTolerance (its impulse's change times K_rr: m, or rad for
/// a twist). Measured against the largest impulse instead (1e-3 of it), a sweep that had settled
/// the points stopped before the friction rows had, once the points started where the last substep
/// ended: the stack of 40 leaned 8 cm in a minute at 1 x 1.
inline constexpr int kBlockSweeps = 8;
inline constexpr Real kBlockTolerance = 1e-8;
/// The direct solve's regularisation, relative to the largest K_rr: a face's four points give
/// one body three motions along n, so K is singular, and K + mu I takes the least impulse that
/// closes them (the same at mirrored points: the split of a symmetric load stays symmetric).
/// Against the 1e-3 relative eigenvalue that sets a 0.1 m edge's tilt it is nothing.
inline constexpr Real kBlockRegularisation = 1e-10;
/// Active-set passes of the direct solve before it gives up and leaves the sweeps to finish.
inline constexpr int kMostBlockPivots = 2 * static_cast<int>(kMostBlockRows) + 2;

/// One side of a block: a rigid body that moves, or one that answers nothing (the ground, a
/// frozen body, or one held still by shock propagation).
struct BlockBody {
  bool moves = false;
  RigidId rigid{};
  Real inverseMass = 0.0;  ///< unit: 1/kg
};

/// The rows and their bounds. Bounds are on the impulse this solve adds (delta), so a caller
/// that keeps a row's impulse over several passes gives its lower bound as minus what it has.
class ConstraintBlock {
 public:
  static constexpr Real kFree = std::numeric_limits<Real>::infinity();

  ConstraintBlock(const RigidBodies& bodies, BlockBody a, BlockBody b) : bodies_(bodies), a_(a), b_(b) {}

  bool moves() const { return a_.moves || b_.moves; }
  std::size_t rows() const { return rows_; }
  /// A row: its Jacobian, its error (m or rad), and its impulse's bounds; at most kMostBlockRows
  /// (gatherRun in rigid_contacts.cpp keeps a block within them).
  std::size_t addRow(const Vec3& linear, const Vec3& armA, const Vec3& armB, Real error, Real lower = -kFree,
                     Real upper = kFree);
  /// A row left out of the next solve (its impulse 0), as static friction is when it cannot hold.
  void drop(std::size_t row) { dropped_[row] = true; }
  /// Each row's I^-1 arm and K_rr; once, before the solves.
  void build();
  /// The positional impulses (kg m, or kg m^2 for a turn), one per row: solved directly (an
  /// active set over the bounds, solveDirect), then polished by the sweeps; when the active set
  /// does not settle, the sweeps alone from the ones `delta` holds (a warm start; zeros for none),
  /// each first put within its row's bounds. 0 for a dropped row.
  void solve(std::span<Real> delta) const;
  /// Each moving body given the positional impulses: one push and one turn.
  void apply(RigidBodies& bodies, std::span<const Real> delta) const;

 private:
  template <bool kTurnA>
  void sweep(std::span<Real> delta) const;
  bool solveDirect(std::span<Real> delta) const;

  const RigidBodies& bodies_;
  BlockBody a_, b_;
  std::size_t rows_ = 0;
  std::array<Vec3, kMostBlockRows> linear_, armA_, armB_, turnA_, turnB_;
  std::array<Real, kMostBlockRows> error_{}, lower_{}, upper_{};
  std::array<bool, kMostBlockRows> dropped_{};
  std::array<Real, kMostBlockRows> diagonal_{};         // K_rr: how far a unit impulse moves the row
  std::array<Real, kMostBlockRows> inverseDiagonal_{};  // 1 / K_rr, or 0 for a row nothing answers
};

}  // namespace phys::detail
