// The four ways to relax sticks. Each is one pass over all sticks; the caller repeats it. A pass
// runs over the StickLayout: its lane groups eight bodies at a time (relax_lanes.h), each block
// (a body) in locals, then the runs in the world's arrays, then the chains of loose particles,
// unless their passes were all run at once (relaxChainsAhead). The same projection code serves
// blocks, runs and chains, and the lanes repeat its operations, so the result is the same.
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "passes.h"
#include "relax_lanes.h"

namespace phys::detail {
namespace {

// The particles a projection reads and writes: a block's locals, or the world's arrays.
struct View {
  Vec3* x;
  const Vec3* previous;  // SHAKE's x*; null for the other methods
  const Real* w;         // inverse masses
};

// What every method needs to know of one stick before it corrects it.
struct StickState {
  Real w1, w2;  // inverse masses
  Vec3 d;       // x2 - x1
  Real length;  // |d|
  Real target;  // the length to move to
};

// False when the stick needs no correction: both ends pinned, or within its bounds.
inline bool measure(const View& v, std::uint32_t a, std::uint32_t b, const Stick& s, StickState& out) {
  out.w1 = v.w[a];
  out.w2 = v.w[b];
  if (out.w1 + out.w2 == 0.0) return false;
  out.d = v.x[b] - v.x[a];
  out.length = glm::length(out.d);
  out.target = stickTarget(s, out.length);
  return out.target >= 0.0;
}

// Jakobsen's projection of one measured stick. A pinned end (w = 0) is never written: 0 times
// a non-finite correction would still be NaN, and a pinned particle must not move.
inline void project(const View& v, std::uint32_t a, std::uint32_t b, const StickState& m) {
  const Real k = (m.length - m.target) / (m.length * (m.w1 + m.w2));
  if (m.w1 != 0.0) v.x[a] += (m.w1 * k) * m.d;
  if (m.w2 != 0.0) v.x[b] -= (m.w2 * k) * m.d;
}

// Calls `f(k)` for every stick of the runs, then of the chains not run ahead (StickLayout::ahead).
template <class F>
void forEachRunStick(const StickLayout& layout, F f) {
  for (const StickRun& run : layout.runs()) {
    for (std::uint32_t k = run.begin; k < run.end; ++k) f(k);
  }
  for (std::size_t c = 0; c < layout.chains().size(); ++c) {
    if (layout.ahead()[c] != 0) continue;
    for (std::uint32_t k = layout.chains()[c].begin; k < layout.chains()[c].end; ++k) f(k);
  }
}

// Runs `relaxStick(view, a, b, stick, index)` over every stick outside the lane groups (which
// relax_lanes.h relaxes) in the layout's order: each block copied into locals (its previous
// positions too when SHAKE needs them), then the runs and chains (forEachRunStick).
// `spin`, if given (keepSpin), keeps each block's moment through its sticks; the runs' bodies are
// the caller's.
template <bool kPrevious, class RelaxStick>
void forEachStick(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                  const SpinPass* spin, RelaxStick relaxStick) {
  Vec3 x[kMaxBlockParticles], previous[kMaxBlockParticles];
  Real w[kMaxBlockParticles];
  const View local{x, kPrevious ? previous : nullptr, w};
  for (const StickBlock& block : layout.blocks()) {
    const std::uint32_t first = block.firstParticle;
    for (int i = 0; i < block.particleCount; ++i) {
      x[i] = p.position[first + i];
      if constexpr (kPrevious) previous[i] = p.previous[first + i];
      w[i] = p.inverseMass[first + i];
    }
    // the levers again each pass: a shape's few bodies left over from its lanes
    const KeptMoment moment(p, block.firstParticle, block.particleCount, x, spin != nullptr);
    for (std::uint32_t k = block.firstStick; k < block.firstStick + block.stickCount; ++k) {
      const Stick& s = sticks[k];
      relaxStick(local, s.a - first, s.b - first, s, k);
    }
    moment.keep(x);
    for (int i = 0; i < block.particleCount; ++i) p.position[first + i] = x[i];
  }
  const View world{p.position.data(), kPrevious ? p.previous.data() : nullptr, p.inverseMass.data()};
  forEachRunStick(layout,
                  [&](std::uint32_t k) { relaxStick(world, sticks[k].a, sticks[k].b, sticks[k], k); });
}

// Passes `passes` times over each chain of the layout at once (StickLayout::chains), pass j at
// stick t - 2j for t = 0, 1, ...: each stick reads what it would one pass after the other, so the
// bits are those. The ground's passes come between the stick passes, and move a loose particle
// only once it is below the plane: a chain with a particle at or below it at any point of this (on
// `ground`, if given) is put back as it was (`saved`, two per stick) and left to the passes, with
// `undo(k)` for each of its sticks. The others are marked ahead.
template <class RelaxStick, class Undo>
void chainsAhead(Particles& p, std::span<const Stick> sticks, StickLayout& layout, int passes,
                 const GroundPlane* ground, std::span<Vec3> saved, RelaxStick relaxStick, Undo undo) {
  const View world{p.position.data(), nullptr, p.inverseMass.data()};
  const std::span<std::uint8_t> ahead = layout.setAhead();
  auto below = [&](ParticleId i) {
    return ground != nullptr && glm::dot(ground->normal, world.x[i]) <= ground->height;
  };
  for (std::size_t c = 0; c < layout.chains().size(); ++c) {
    const StickRun chain = layout.chains()[c];
    const std::uint32_t n = chain.end - chain.begin;
    bool touches = false;
    if (ground != nullptr) {
      for (std::size_t i = 0; i < n; ++i) {
        const Stick& s = sticks[chain.begin + i];
        saved[2 * i] = world.x[s.a];
        saved[2 * i + 1] = world.x[s.b];
        touches = touches || below(s.a) || below(s.b);
      }
    }
    if (!touches) {
      const std::uint32_t lag = 2;
      const std::uint32_t span = n + lag * static_cast<std::uint32_t>(passes - 1);
      for (std::uint32_t t = 0; t < span; ++t) {
        for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(passes) && lag * j <= t; ++j) {
          const std::uint32_t i = t - lag * j;
          if (i >= n) continue;
          const std::uint32_t k = chain.begin + i;
          const Stick& s = sticks[k];
          relaxStick(world, s.a, s.b, s, k);
          if (ground != nullptr) touches = touches || below(s.a) || below(s.b);
        }
      }
    }
    if (touches) {
      for (std::size_t i = 0; i < n; ++i) {
        const Stick& s = sticks[chain.begin + i];
        world.x[s.a] = saved[2 * i];
        world.x[s.b] = saved[2 * i + 1];
        undo(chain.begin + static_cast<std::uint32_t>(i));
      }
    }
    ahead[c] = touches ? 0 : 1;
  }
}

// Gauss-Seidel's stick: Jakobsen's projection.
struct GaussSeidelStick {
  void operator()(const View& v, std::uint32_t a, std::uint32_t b, const Stick& s, std::uint32_t) const {
    StickState m;
    if (!measure(v, a, b, s, m) || m.length == 0.0) return;  // no direction at 0
    project(v, a, b, m);
  }
};

// XPBD's stick, with its multiplier lambda.
struct XpbdStick {
  Real* lambda;
  Real inverseH2, compliance;
  void operator()(const View& v, std::uint32_t a, std::uint32_t b, const Stick& s, std::uint32_t c) const {
    StickState m;
    if (!measure(v, a, b, s, m) || m.length == 0.0) return;
    // finite: both compliances and h are bounded (settings.h)
    const Real alpha = (s.compliance + compliance) * inverseH2;
    const Real dLambda = (-(m.length - m.target) - alpha * lambda[c]) / (m.w1 + m.w2 + alpha);
    lambda[c] += dLambda;
    const Vec3 n = m.d / m.length;
    if (m.w1 != 0.0) v.x[a] -= (m.w1 * dLambda) * n;
    if (m.w2 != 0.0) v.x[b] += (m.w2 * dLambda) * n;
  }
};

// The lane arguments, with keepSpin's lane levers when `spin` is given.
LaneArguments keepingSpin(Particles& p, const StickLayout& layout, const SpinPass* spin) {
  LaneArguments a = laneArguments(p, layout);
  if (spin != nullptr) {
    a.laneSpin = spin->laneLevers.data();
    a.firstPass = spin->firstPass;
  }
  return a;
}

}  // namespace

// Jakobsen 2001, "Advanced Character Physics", stick constraint, with the sign of the printed
// listing corrected (REFERENCES.md): s = (|d| - r) / (|d| (w1 + w2)); x1 += w1 s d; x2 -= w2 s d.
void relaxGaussSeidel(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                      const Workers* workers, const SpinPass* spin) {
  inLanePieces(keepingSpin(p, layout, spin), workers,
               [](const LaneArguments& a) { relaxGaussSeidelLanes(a); });
  forEachStick<false>(p, sticks, layout, spin, GaussSeidelStick{});
}

void relaxChainsAhead(Particles& p, std::span<const Stick> sticks, StickLayout& layout, int passes,
                      const GroundPlane* ground, std::span<Vec3> saved) {
  chainsAhead(p, sticks, layout, passes, ground, saved, GaussSeidelStick{}, [](std::uint32_t) {});
}

// Jacobi: every stick's correction from the same positions, summed per particle. Each stick's
// pair of corrections is scaled by one factor, 1 / the larger number of sticks at either end,
// so the two stay equal and opposite in momentum (averaging each particle by its own count
// would not, and a free body would drift); the factor keeps a particle pulled by many sticks
// from overshooting (Müller et al. 2007 discuss both orders). A block shares no particle with
// any other stick, so it can sum and apply its own corrections before the next block reads.
void relaxJacobi(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                 std::span<const Real> degree, std::span<Vec3> delta, const Workers* workers,
                 const SpinPass* spin) {
  auto correction = [&](const View& v, std::uint32_t a, std::uint32_t b, const Stick& s, Real scale,
                        Vec3* sum) {
    StickState m;
    if (!measure(v, a, b, s, m) || m.length == 0.0) return;
    const Real k = (m.length - m.target) / (m.length * (m.w1 + m.w2) * scale);
    sum[a] += (m.w1 * k) * m.d;
    sum[b] -= (m.w2 * k) * m.d;
  };
  LaneArguments lanes = keepingSpin(p, layout, spin);
  lanes.degree = degree.data();
  inLanePieces(lanes, workers, [](const LaneArguments& a) { relaxJacobiLanes(a); });
  for (const StickBlock& block : layout.blocks()) {
    const std::uint32_t first = block.firstParticle;
    Vec3 x[kMaxBlockParticles], sum[kMaxBlockParticles];
    Real w[kMaxBlockParticles];
    for (int i = 0; i < block.particleCount; ++i) {
      x[i] = p.position[first + i];
      w[i] = p.inverseMass[first + i];
      sum[i] = Vec3(0.0);
    }
    const View local{x, nullptr, w};
    const KeptMoment moment(p, block.firstParticle, block.particleCount, x, spin != nullptr);
    for (std::uint32_t k = block.firstStick; k < block.firstStick + block.stickCount; ++k) {
      const Stick& s = sticks[k];
      correction(local, s.a - first, s.b - first, s, std::max(degree[s.a], degree[s.b]), sum);
    }
    for (int i = 0; i < block.particleCount; ++i) {
      if (w[i] != 0.0) x[i] += sum[i];
    }
    moment.keep(x);
    for (int i = 0; i < block.particleCount; ++i) p.position[first + i] = x[i];
  }
  if (layout.runs().empty() && layout.chains().empty()) return;
  std::fill(delta.begin(), delta.end(), Vec3(0.0));
  const View world{p.position.data(), nullptr, p.inverseMass.data()};
  forEachRunStick(layout, [&](std::uint32_t k) {
    const Stick& s = sticks[k];
    correction(world, s.a, s.b, s, std::max(degree[s.a], degree[s.b]), delta.data());
  });
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (p.inverseMass[i] != 0.0) p.position[i] += delta[i];
  }
}

// XPBD, Macklin, Müller and Chentanez 2016, eq. 18: dlambda = (-C - a~ lambda) / (sum w + a~),
// a~ = compliance / h^2; gradient of C = |x2 - x1| - r is -n for x1 and +n for x2. The world's
// compliance adds to each stick's: compliances in series add, as springs' inverse stiffnesses do.
void relaxXpbd(Particles& p, std::span<const Stick> sticks, const StickLayout& layout, std::span<Real> lambda,
               Real h, Real compliance, const Workers* workers, const SpinPass* spin) {
  const Real inverseH2 = 1.0 / (h * h);
  LaneArguments lanes = keepingSpin(p, layout, spin);
  lanes.lambda = lambda.data();
  lanes.inverseH2 = inverseH2;
  lanes.compliance = compliance;
  inLanePieces(lanes, workers, [](const LaneArguments& a) { relaxXpbdLanes(a); });
  forEachStick<false>(p, sticks, layout, spin, XpbdStick{lambda.data(), inverseH2, compliance});
}

void relaxChainsAheadXpbd(Particles& p, std::span<const Stick> sticks, StickLayout& layout, int passes,
                          const GroundPlane* ground, std::span<Vec3> saved, std::span<Real> lambda, Real h,
                          Real compliance) {
  // The multipliers start the substep at 0, so a chain put back has its own zeroed again.
  chainsAhead(p, sticks, layout, passes, ground, saved, XpbdStick{lambda.data(), 1.0 / (h * h), compliance},
              [&](std::uint32_t k) { lambda[k] = 0.0; });
}

// SHAKE for one stick: move x1 by -w1 g r and x2 by +w2 g r, where r is the stick at the start
// of the substep, with g the root of |d + (w1 + w2) g r|^2 = L^2 nearest zero. Where no root
// exists (the stick turned too far within one substep), fall back to Jakobsen's projection.
void relaxShake(Particles& p, std::span<const Stick> sticks, const StickLayout& layout,
                const Workers* workers) {
  inLanePieces(laneArguments(p, layout), workers, [](const LaneArguments& a) { relaxShakeLanes(a); });
  forEachStick<true>(p, sticks, layout, nullptr,
                     [](const View& v, std::uint32_t a, std::uint32_t b, const Stick& s, std::uint32_t) {
                       StickState m;
                       if (!measure(v, a, b, s, m)) return;
                       const Real w1 = m.w1, w2 = m.w2, w = w1 + w2, length = m.length, target = m.target;
                       const Vec3& d = m.d;
                       const Vec3 r = v.previous[b] - v.previous[a];
                       const Real qa = w * w * glm::dot(r, r);
                       const Real qb = 2.0 * w * glm::dot(d, r);
                       const Real qc = glm::dot(d, d) - target * target;
                       const Real discriminant = qb * qb - 4.0 * qa * qc;
                       if (qa > 0.0 && discriminant >= 0.0) {
                         // The numerically stable pair of roots; keep the smaller in magnitude.
                         const Real q = -0.5 * (qb + std::copysign(std::sqrt(discriminant), qb));
                         Real g = 0.0;
                         if (q != 0.0) {
                           const Real g1 = q / qa, g2 = qc / q;
                           g = std::abs(g1) < std::abs(g2) ? g1 : g2;
                         }
                         if (w1 != 0.0) v.x[a] -= (w1 * g) * r;
                         if (w2 != 0.0) v.x[b] += (w2 * g) * r;
                       } else if (length > 0.0) {
                         project(v, a, b, m);
                       }
                     });
}

}  // namespace phys::detail
