// A block of constraint rows between two rigid bodies (rigid_block.h).
#include "rigid_block.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "rigid_motion.h"

namespace phys::detail {

std::size_t ConstraintBlock::addRow(const Vec3& linear, const Vec3& armA, const Vec3& armB, Real error,
                                    Real lower, Real upper) {
  const std::size_t r = rows_++;
  linear_[r] = linear;
  armA_[r] = armA;
  armB_[r] = armB;
  error_[r] = error;
  lower_[r] = lower;
  upper_[r] = upper;
  return r;
}

void ConstraintBlock::build() {
  const Real linear = a_.inverseMass + b_.inverseMass;
  for (std::size_t r = 0; r < rows_; ++r) {
    turnA_[r] = a_.moves ? bodies_.inverseInertiaWorld[a_.rigid] * armA_[r] : Vec3(0.0);
    turnB_[r] = b_.moves ? bodies_.inverseInertiaWorld[b_.rigid] * armB_[r] : Vec3(0.0);
    const Real k = linear * glm::dot(linear_[r], linear_[r]) + glm::dot(armA_[r], turnA_[r]) +
                   glm::dot(armB_[r], turnB_[r]);
    diagonal_[r] = k;
    inverseDiagonal_[r] = k > 0.0 ? 1.0 / k : 0.0;
  }
}

// Each sweep reads a row's residual from the motion the impulses so far give the two bodies (K
// delta without K: B's push against A's, and each one's turn), so that a sweep costs one pass over
// the rows. A block whose A does not move (the ground, a held body) skips A's turn.
template <bool kTurnA>
void ConstraintBlock::sweep(std::span<Real> delta) const {
  const Real linear = a_.inverseMass + b_.inverseMass;
  Vec3 push(0.0), turnA(0.0), turnB(0.0);
  for (std::size_t r = 0; r < rows_; ++r) {
    push += (delta[r] * linear) * linear_[r];
    turnB += delta[r] * turnB_[r];
    if constexpr (kTurnA) turnA -= delta[r] * turnA_[r];
  }
  for (int sweep = 0; sweep < kBlockSweeps; ++sweep) {
    Real largestMove = 0.0;
    for (std::size_t r = 0; r < rows_; ++r) {
      if (dropped_[r] || inverseDiagonal_[r] == 0.0) continue;
      Real residual = error_[r] + glm::dot(linear_[r], push) + glm::dot(armB_[r], turnB);
      if constexpr (kTurnA) residual -= glm::dot(armA_[r], turnA);
      const Real next = std::clamp(delta[r] - residual * inverseDiagonal_[r], lower_[r], upper_[r]);
      const Real change = next - delta[r];
      delta[r] = next;
      largestMove = std::max(largestMove, std::abs(change) * diagonal_[r]);
      push += (change * linear) * linear_[r];
      turnB += change * turnB_[r];
      if constexpr (kTurnA) turnA -= change * turnA_[r];
    }
    if (largestMove <= kBlockTolerance) break;
  }
}

void ConstraintBlock::solve(std::span<Real> delta) const {
  for (std::size_t r = 0; r < rows_; ++r) {
    delta[r] = dropped_[r] || inverseDiagonal_[r] == 0.0 ? 0.0 : std::clamp(delta[r], lower_[r], upper_[r]);
  }
  if (a_.moves)
    sweep<true>(delta);
  else
    sweep<false>(delta);
}

void ConstraintBlock::apply(RigidBodies& bodies, std::span<const Real> delta) const {
  Vec3 shift(0.0), turnA(0.0), turnB(0.0);
  for (std::size_t r = 0; r < rows_; ++r) {
    shift += delta[r] * linear_[r];
    turnA -= delta[r] * turnA_[r];
    turnB += delta[r] * turnB_[r];
  }
  auto move = [&](const BlockBody& side, const Vec3& push, const Vec3& turn) {
    if (!side.moves) return;
    bodies.position[side.rigid] += push;
    bodies.orientation[side.rigid] = nudged(bodies.orientation[side.rigid], turn);
  };
  move(a_, -a_.inverseMass * shift, turnA);
  move(b_, b_.inverseMass * shift, turnB);
}

}  // namespace phys::detail
