// Probe for docs/performance.md, "The contact push by manifold (measured, not taken)": the contact
// push between particle bodies timed alone, on the contacts and particles of pyramid-40 after 60
// steps at Gauss-Seidel 10 x 16, in forms that each leave out or change one part of it. Not part of
// the build. From the repository's root, after `cmake --build --preset release`:
//
//   B=build/release
//   g++ -std=c++20 -O3 -flto=auto -fno-math-errno -ffp-contract=off -Iphysics/include -Iphysics/src \
//     -Iapp/scenes/include scripts/probes/contact-pass-bench.cpp $B/app/scenes/libscenes.a \
//     $B/app/clips/libclips.a $B/app/fileio/libfileio.a $B/physics/libphysics.a \
//     -ltbb -lpugixml -lassimp -o /tmp/contact-pass-bench
//   /tmp/contact-pass-bench
//
// Each round starts every form from the same particles and runs 20 substeps of 10 passes: a
// substep's start moves every particle by up to 0.05 mm at random (the same for every form), then
// each pass relaxes the boxes' sticks (which pull back what the contacts pushed, so that most
// contacts push in every pass, as in a step), the form's push (timed), and friction. It prints each
// form's median, least and most thread CPU time per contact and pass over 15 rounds, the forms in
// turn in every round, after the points' kinds (how many particles carry each side). The sticks
// are the world's own, reached by making World's members public here (a probe, not an API).
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#define private public
#include "physics/world.h"
#undef private
#include "passes.h"
#include "scenes/scene.h"

namespace {
using namespace phys;
using namespace phys::detail;

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

using PushForm = void (*)(Particles&, std::span<const BodyContact>, std::span<Real>);

void asItIs(Particles& p, std::span<const BodyContact> c, std::span<Real> push) {
  solveBodyContacts(p, c, 0.0, push, {});
}

// A point's gap: n . (B - A) less its offset, as the push reads it.
Real gapOf(const Particles& p, const BodyContact& c) {
  return glm::dot(c.normal, embeddedPosition(p.position, c.pointB) - embeddedPosition(p.position, c.pointA)) -
         c.offset;
}

// The gap alone: every read of the push, no correction.
void gapOnly(Particles& p, std::span<const BodyContact> contacts, std::span<Real> push) {
  for (std::size_t k = 0; k < contacts.size(); ++k) push[k] = std::max(-gapOf(p, contacts[k]), 0.0);
}

// The push but for writing its corrections: the gap, its branch, the weights and the division.
void noWrites(Particles& p, std::span<const BodyContact> contacts, std::span<Real> push) {
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    const Real gap = gapOf(p, c);
    push[k] = 0.0;
    if (gap >= 0.0) continue;
    const Real denominator =
        embeddedWeight(p.inverseMass, c.pointA) + embeddedWeight(p.inverseMass, c.pointB);
    if (denominator != 0.0) push[k] = -gap / denominator;
  }
}

// The push with both sides' particle counts as constants: one branch a contact on the pair of
// counts (1, 2 or 4 each) in place of the loops' one a particle. The same operations, the same result.
template <int NA, int NB>
Real pushFixed(Vec3* x, const Real* w, const BodyContact& c) {
  Vec3 a(0.0), b(0.0);
  for (int i = 0; i < NA; ++i) a += c.pointA.weight[i] * x[c.pointA.particle[i]];
  for (int j = 0; j < NB; ++j) b += c.pointB.weight[j] * x[c.pointB.particle[j]];
  const Real gap = glm::dot(c.normal, b - a) - c.offset;
  if (gap >= 0.0) return 0.0;
  Real sum = 0.0, sumB = 0.0;
  for (int i = 0; i < NA; ++i) sum += c.pointA.weight[i] * c.pointA.weight[i] * w[c.pointA.particle[i]];
  for (int j = 0; j < NB; ++j) sumB += c.pointB.weight[j] * c.pointB.weight[j] * w[c.pointB.particle[j]];
  const Real denominator = sum + sumB;
  if (denominator == 0.0) return 0.0;
  const Vec3 lambda = (-gap / denominator) * c.normal;
  for (int i = 0; i < NA; ++i) {
    if (w[c.pointA.particle[i]] != 0.0)
      x[c.pointA.particle[i]] += (c.pointA.weight[i] * w[c.pointA.particle[i]]) * -lambda;
  }
  for (int j = 0; j < NB; ++j) {
    if (w[c.pointB.particle[j]] != 0.0)
      x[c.pointB.particle[j]] += (c.pointB.weight[j] * w[c.pointB.particle[j]]) * lambda;
  }
  return -gap;
}

void fixedCounts(Particles& p, std::span<const BodyContact> contacts, std::span<Real> push) {
  Vec3* x = p.position.data();
  const Real* w = p.inverseMass.data();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    switch (c.pointA.count * 8 + c.pointB.count) {
      case 9:
        push[k] = pushFixed<1, 1>(x, w, c);
        break;
      case 12:
        push[k] = pushFixed<1, 4>(x, w, c);
        break;
      case 33:
        push[k] = pushFixed<4, 1>(x, w, c);
        break;
      case 18:
        push[k] = pushFixed<2, 2>(x, w, c);
        break;
      case 10:
        push[k] = pushFixed<1, 2>(x, w, c);
        break;
      case 17:
        push[k] = pushFixed<2, 1>(x, w, c);
        break;
      default:
        solveBodyContacts(p, contacts.subspan(k, 1), 0.0, push.subspan(k, 1), {});
    }
  }
}

// The push on positions of 32 bytes (x, y, z and a pad), so that no position straddles a cache
// line or shares one with a neighbour's half. The copies in and out are timed with it.
void padded(Particles& p, std::span<const BodyContact> contacts, std::span<Real> push) {
  static std::vector<glm::dvec4> x;
  x.resize(p.position.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = glm::dvec4(p.position[i], 0.0);
  const Real* w = p.inverseMass.data();
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const BodyContact& c = contacts[k];
    glm::dvec4 a(0.0), b(0.0);
    for (int i = 0; i < c.pointA.count; ++i) a += c.pointA.weight[i] * x[c.pointA.particle[i]];
    for (int j = 0; j < c.pointB.count; ++j) b += c.pointB.weight[j] * x[c.pointB.particle[j]];
    const Real gap = glm::dot(c.normal, Vec3(b - a)) - c.offset;
    push[k] = 0.0;
    if (gap >= 0.0) continue;
    const Real denominator =
        embeddedWeight(p.inverseMass, c.pointA) + embeddedWeight(p.inverseMass, c.pointB);
    if (denominator == 0.0) continue;
    const glm::dvec4 lambda((-gap / denominator) * c.normal, 0.0);
    for (int i = 0; i < c.pointA.count; ++i) {
      if (w[c.pointA.particle[i]] != 0.0)
        x[c.pointA.particle[i]] -= (c.pointA.weight[i] * w[c.pointA.particle[i]]) * lambda;
    }
    for (int j = 0; j < c.pointB.count; ++j) {
      if (w[c.pointB.particle[j]] != 0.0)
        x[c.pointB.particle[j]] += (c.pointB.weight[j] * w[c.pointB.particle[j]]) * lambda;
    }
    push[k] = -gap;
  }
  for (std::size_t i = 0; i < x.size(); ++i) p.position[i] = Vec3(x[i]);
}

}  // namespace

int main() {
  scenes::Scene scene = scenes::loadSceneFile("assets/scenes/stability/pyramid-40.xml");
  World& world = scene.world;
  SolverSettings solver = world.solverSettings();
  solver.iterations = 10;
  solver.substeps = 16;
  world.setSolverSettings(solver);
  for (int i = 0; i < 60; ++i) world.step();
  const Particles start = world.particles();
  std::vector<BodyContact> contacts(world.bodyContacts().begin(), world.bodyContacts().end());
  const std::span<const BodyContactExtra> extras = world.narrowPhase_.contactExtras();
  std::vector<Real> push(contacts.size());
  int kinds[5][5] = {};  // points by the counts of their two sides' particles
  for (const BodyContact& c : contacts) ++kinds[c.pointA.count][c.pointB.count];
  std::printf("points by particles a side (A/B: count):");
  for (int a = 1; a <= 4; ++a) {
    for (int b = 1; b <= 4; ++b) {
      if (kinds[a][b] > 0) std::printf(" %d/%d: %d", a, b, kinds[a][b]);
    }
  }
  std::printf("\n");
  const std::vector<std::pair<const char*, PushForm>> forms = {{"as it is", asItIs},
                                                               {"gap only", gapOnly},
                                                               {"no writes", noWrites},
                                                               {"fixed counts", fixedCounts},
                                                               {"padded", padded}};
  std::vector<std::vector<double>> ns(forms.size());
  for (int round = 0; round < 15; ++round) {
    for (std::size_t f = 0; f < forms.size(); ++f) {
      Particles p = start;
      unsigned seed = 1;
      double seconds = 0.0;
      for (int pass = 0; pass < 200; ++pass) {
        if (pass % 10 == 0) {
          for (Vec3& x : p.position) {
            for (int a = 0; a < 3; ++a) {
              seed = seed * 1664525u + 1013904223u;
              x[a] += 1e-4 * (static_cast<double>(seed >> 8) / 16777216.0 - 0.5);
            }
          }
        }
        world.constraints_.relaxSticks(p, solver.method, pass % 10 == 0, solver.dt / solver.substeps,
                                       solver.compliance, nullptr);
        const double t = threadSeconds();
        forms[f].second(p, contacts, push);
        seconds += threadSeconds() - t;
        applyBodyFriction(p, contacts, extras, push);
      }
      ns[f].push_back(seconds / 200.0 / static_cast<double>(contacts.size()) * 1e9);
    }
  }
  std::printf("%zu contact points, %zu particles; ns per point and pass over 15 rounds:\n", contacts.size(),
              start.position.size());
  for (std::size_t f = 0; f < forms.size(); ++f) {
    std::sort(ns[f].begin(), ns[f].end());
    std::printf("  %-13s median %5.1f  least %5.1f  most %5.1f\n", forms[f].first, ns[f][ns[f].size() / 2],
                ns[f].front(), ns[f].back());
  }
}
