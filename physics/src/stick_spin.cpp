// Each particle body's angular momentum kept through its own sticks' passes
// (SolverSettings::keepSpin; docs/physics.md, "Keeping a body's spin through its sticks").
// Gauss-Seidel, Jacobi and XPBD move a stick's ends along its direction after the free move, not
// along the one it had where the substep started. Verlet keeps sum m x* x x (x* the start of the
// substep, x its end; h times the angular momentum), and a correction dx_i changes it by
// m x*_i x dx_i: for a stick's pair of corrections, by (x*_a - x*_b) x k d, which is not zero once
// the stick has turned in the substep. Summed over a spinning body it is a drag on its spin, though
// the sticks are internal forces and should take none. The sticks' own change is measured around
// each pass over them and undone by a rigid turn of the body's particles about its centre, which
// keeps its momentum (Dahl and Bargteil 2019, "Global Momentum Preservation for Position-based
// Dynamics", restore a whole body's momenta after its step; here only what the sticks did is
// undone, since contacts and links change the angular momentum as they should).
//
// The passes bracket a body where they hold its particles: the lane kernels (relax_lanes_kernels.inc,
// LaneSpin, the same operations per lane, with the levers kept lane-major from the substep's first
// pass), the blocks (relax.cpp) and the tetra volumes (tetra_volumes.cpp) call spinLevers,
// stickMoment and keepStickMoment on their copies; only the bodies whose sticks are relaxed in the
// world's arrays (StickLayout::runBodies) are measured and restored here, around the whole pass. Measured
// apart, as a first version did, it cost 1.18 times on pyramid-20 at 10 x 16: two more trips through every
// body's particles a pass.
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "passes.h"

namespace phys::detail {
namespace {

// Whether K (keepStickMoment) is positive definite in its symmetric part, from its diagonal and the
// sums of its off-diagonal pairs (xy = K_xy + K_yx ...): Sylvester's leading minors of K + K^T.
// LaneSpin::restore does the same operations in the same order.
inline bool turnIsAnInertia(Real xx, Real yy, Real zz, Real xy, Real xz, Real yz) {
  const Real a = 2.0 * xx, b = 2.0 * yy, c = 2.0 * zz;
  const Real second = a * b - xy * xy;
  const Real third = a * (b * c - yz * yz) - xy * (xy * c - yz * xz) + xz * (xy * yz - b * xz);
  return a > 0.0 && second > 0.0 && third > 0.0;
}

}  // namespace

// s_i = x*_i - c* is fixed for the substep (the passes never move x*), and sum m s_i = 0, so
// sum m s_i x x_i is the moment about any point: the passes' changes of it are theirs alone.
// LaneSpin::levers does the same operations in the same order: change one, change both.
bool spinLevers(const Particles& p, ParticleId first, int count, SpinLever* lever) {
  Real mass = 0.0;
  Vec3 start(0.0);  // sum of m x*, from the first particle (digits far out)
  for (int i = 0; i < count; ++i) {
    if (p.inverseMass[first + i] == 0.0) {  // pinned, frozen or asleep: not its own
      for (int j = 0; j < count; ++j) lever[j] = SpinLever{};
      return false;
    }
    const Real m = 1.0 / p.inverseMass[first + i];
    mass += m;
    start += m * (p.previous[first + i] - p.previous[first]);
  }
  start = p.previous[first] + start / mass;
  for (int i = 0; i < count; ++i) {
    const Real m = 1.0 / p.inverseMass[first + i];
    lever[i] = {m * (p.previous[first + i] - start), m};
  }
  return true;
}

// Once a substep, before its passes: each run body's levers, or the body left alone.
void startStickSpin(const Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                    std::span<SpinLever> lever, std::span<StickSpin> spin) {
  for (const std::uint32_t k : which) {
    const Body& b = bodies[k];
    spin[k].kept =
        b.particleCount > 0 && spinLevers(p, b.firstParticle, b.particleCount, &lever[b.firstParticle]);
  }
}

Vec3 stickMoment(const Vec3* x, const SpinLever* lever, int count) {
  Vec3 sum(0.0);
  for (int i = 0; i < count; ++i) sum += glm::cross(lever[i].lever, x[i] - x[0]);
  return sum;
}

// A turn dw moves x_i by dw x r_i (r_i = x_i - c, which keeps sum m x) and changes the moment by
// sum m s_i x (dw x r_i) = K dw, K = sum m ((s_i . r_i) 1 - r_i s_i^T): the inertia tensor but for
// the substep's own turn between s and r. Since sum m s_i = 0, K is the same with r_i taken from
// any point; from the first particle, so that one loop finds K, the moment and the centre. Solved
// exactly, the moment is back to what it was before the pass, to round-off. LaneSpin::restore does
// the same operations in the same order: change one, change both.
void keepStickMoment(Vec3* x, const SpinLever* lever, int count, const Vec3& before) {
  Vec3 moment(0.0), centre(0.0);
  Real mass = 0.0;
  glm::dmat3 turn(0.0);  // K
  for (int i = 0; i < count; ++i) {
    const Vec3 r = x[i] - x[0];
    const Vec3& ms = lever[i].lever;
    moment += glm::cross(ms, r);
    turn += glm::dot(ms, r) * glm::dmat3(1.0) - glm::outerProduct(r, ms);
    centre += lever[i].mass * r;
    mass += lever[i].mass;
  }
  // Far from its start's shape (a corner yanked metres in a step), a body has no one rotation for a
  // turn to restore: K is then no inertia, and where its symmetric part is not positive definite a
  // turn about some axis takes the moment the wrong way, and solving for it threw such a box out of
  // the world. Left as it is (its leading minors; a body left alone, K = 0, fails the first).
  if (!turnIsAnInertia(turn[0][0], turn[1][1], turn[2][2], turn[0][1] + turn[1][0], turn[0][2] + turn[2][0],
                       turn[1][2] + turn[2][1]))
    return;
  const Real det = glm::determinant(turn);
  // flat, not finite, or left alone (levers of 0): as it is
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return;
  const Vec3 dw = glm::inverse(turn) * (before - moment);
  if (!std::isfinite(dw.x + dw.y + dw.z)) return;
  centre = x[0] + centre * (1.0 / mass);
  for (int i = 0; i < count; ++i) x[i] += glm::cross(dw, x[i] - centre);
}

void measureStickSpin(const Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                      std::span<const SpinLever> lever, std::span<StickSpin> spin) {
  for (const std::uint32_t k : which) {
    if (!spin[k].kept) continue;
    const ParticleId first = bodies[k].firstParticle;
    spin[k].moment = stickMoment(&p.position[first], &lever[first], bodies[k].particleCount);
  }
}

void restoreStickSpin(Particles& p, std::span<const Body> bodies, std::span<const std::uint32_t> which,
                      std::span<const SpinLever> lever, std::span<const StickSpin> spin) {
  for (const std::uint32_t k : which) {
    if (!spin[k].kept) continue;
    const ParticleId first = bodies[k].firstParticle;
    keepStickMoment(&p.position[first], &lever[first], bodies[k].particleCount, spin[k].moment);
  }
}

}  // namespace phys::detail
