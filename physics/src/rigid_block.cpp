// A block of constraint rows between two rigid bodies (rigid_block.h).
#include "rigid_block.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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

// The impulses by a direct solve of K delta = -error over the rows within their bounds, the others
// held at the bound they pass (an active set: a row whose impulse passes a bound is held there, and
// a held row is let go again once its residual pulls it back inside). The sweeps alone do not
// settle a slender patch: the split of a face's normal impulse between its two long edges, which
// is what tips the body about them, moves by 2 K_tilt / K_rr of its error a sweep, and on the 0.1 m
// edge of a 3 m wall that is 0.7% (K_tilt 3.3e-8 against K_rr 2.5e-5 1/kg). The eight sweeps left
// an unbalanced split that the next substep started from, and the wall, stood still, rocked and
// tipped over at 1 x 1 (docs/physics.md, "A slender body on its edge"). False when the active set
// does not settle within kMostBlockPivots passes.
bool ConstraintBlock::solveDirect(std::span<Real> delta) const {
  std::array<std::size_t, kMostBlockRows> index{};  // the rows that take an impulse
  std::size_t n = 0;
  Real largest = 0.0;
  for (std::size_t r = 0; r < rows_; ++r) {
    if (dropped_[r] || inverseDiagonal_[r] == 0.0) continue;
    index[n++] = r;
    largest = std::max(largest, diagonal_[r]);
  }
  const Real linear = a_.inverseMass + b_.inverseMass;
  // Only the first n rows and columns of k and l are written and read: left unset, not zeroed, as
  // the arrays are larger than a typical block's work (7 rows: a face on the ground).
  std::array<std::array<Real, kMostBlockRows>, kMostBlockRows> k;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      const std::size_t r = index[i], s = index[j];
      k[i][j] = k[j][i] = linear * glm::dot(linear_[r], linear_[s]) + glm::dot(armA_[r], turnA_[s]) +
                          glm::dot(armB_[r], turnB_[s]);
    }
  }
  const Real mu = kBlockRegularisation * largest;
  enum class Held : std::uint8_t { No, Lower, Upper };
  std::array<Held, kMostBlockRows> held{};
  std::array<Real, kMostBlockRows> x{};
  for (int pass = 0; pass < kMostBlockPivots; ++pass) {
    // (K_FF + mu I) x_F = -(error_F + K_FH x_H) over the free rows F, by Cholesky.
    std::array<std::size_t, kMostBlockRows> free{};
    std::size_t m = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (held[i] == Held::No) free[m++] = i;
    }
    std::array<std::array<Real, kMostBlockRows>, kMostBlockRows> l;
    std::array<Real, kMostBlockRows> y{};
    for (std::size_t a = 0; a < m; ++a) {
      Real rhs = -error_[index[free[a]]];
      for (std::size_t i = 0; i < n; ++i) {
        if (held[i] != Held::No) rhs -= k[free[a]][i] * x[i];
      }
      for (std::size_t b = 0; b <= a; ++b) {
        Real sum = k[free[a]][free[b]] + (a == b ? mu : 0.0);
        for (std::size_t c = 0; c < b; ++c) sum -= l[a][c] * l[b][c];
        if (a == b)
          l[a][a] = std::sqrt(std::max(sum, mu));
        else
          l[a][b] = sum / l[b][b];
      }
      for (std::size_t c = 0; c < a; ++c) rhs -= l[a][c] * y[c];
      y[a] = rhs / l[a][a];
    }
    for (std::size_t a = m; a-- > 0;) {
      Real sum = y[a];
      for (std::size_t c = a + 1; c < m; ++c) sum -= l[c][a] * x[free[c]];
      x[free[a]] = sum / l[a][a];
    }
    // Rows past a bound are held there; only when none is, held rows pulled back inside are let go.
    bool changed = false;
    for (std::size_t a = 0; a < m; ++a) {
      const std::size_t i = free[a], r = index[i];
      if (!std::isfinite(x[i])) return false;
      if (x[i] < lower_[r]) {
        held[i] = Held::Lower;
        x[i] = lower_[r];
        changed = true;
      } else if (x[i] > upper_[r]) {
        held[i] = Held::Upper;
        x[i] = upper_[r];
        changed = true;
      }
    }
    if (changed) continue;
    for (std::size_t i = 0; i < n; ++i) {
      if (held[i] == Held::No) continue;
      Real residual = error_[index[i]];
      for (std::size_t j = 0; j < n; ++j) residual += k[i][j] * x[j];
      if ((held[i] == Held::Lower && residual < -kBlockTolerance) ||
          (held[i] == Held::Upper && residual > kBlockTolerance)) {
        held[i] = Held::No;
        changed = true;
      }
    }
    if (changed) continue;
    for (std::size_t r = 0; r < rows_; ++r) delta[r] = 0.0;
    for (std::size_t i = 0; i < n; ++i) delta[index[i]] = x[i];
    return true;
  }
  return false;
}

void ConstraintBlock::solve(std::span<Real> delta) const {
  for (std::size_t r = 0; r < rows_; ++r) {
    delta[r] = dropped_[r] || inverseDiagonal_[r] == 0.0 ? 0.0 : std::clamp(delta[r], lower_[r], upper_[r]);
  }
  solveDirect(delta);
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
