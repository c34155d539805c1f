// The sticks laid out by body (physics/stick_layout.h): which bodies become blocks and lanes, and
// that every method relaxes them to exactly the bits of the plain loop in creation order, with the
// SIMD kernels of every instruction set this machine can run.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "passes.h"
#include "physics/world.h"
#include "relax_lanes.h"
#include "test_util.h"

namespace {

using phys::Vec3;

// 21 tetra boxes (two lane groups and 5 left over), 11 corners boxes (one group, 3 left over), a
// loose chain, and a stick from the chain to box 0, which makes box 0 a run and not a block.
struct Scene {
  phys::World world;
  std::size_t boxesWithOutsideStick = 1;

  Scene() : world(phys::WorldSettings{}, phys::SolverSettings{}) {
    for (int i = 0; i < 32; ++i) {
      phys::BodyDesc box;
      box.model = i < 21 ? phys::BodyModel::Tetra : phys::BodyModel::Corners;
      box.center = {2.0 * i, 1.0, 0.0};
      box.size = {0.5 + 0.05 * i, 1.0, 0.7};
      world.addBody(box);
    }
    phys::ParticleId previous = world.addParticle({Vec3(0.0, 5.0, 0.0)});
    world.addStick(world.bodies()[0].firstParticle, previous);
    for (int i = 1; i < 10; ++i) {
      const phys::ParticleId next = world.addParticle({Vec3(0.3 * i, 5.0, 0.0)});
      world.addRange(previous, next, 0.2, 0.25);
      previous = next;
    }
  }
};

TEST(StickLayout, BodiesOfOneShapeGoIntoLanesTheRestIntoBlocksAndRuns) {
  Scene scene;
  phys::StickLayout layout;
  layout.build(scene.world.sticks(), scene.world.bodies(), scene.world.particles().size());
  // Box 0 has an outside stick: 20 tetra bodies left, 2 groups of 8 and 4 blocks; 11 corners
  // bodies, 1 group and 3 blocks.
  ASSERT_EQ(layout.lanes().size(), 3u);
  EXPECT_EQ(layout.blocks().size(), 7u);
  std::size_t inRuns = 0;
  for (const phys::StickRun& run : layout.runs()) inRuns += run.end - run.begin;
  EXPECT_EQ(inRuns, 6u + 1u + 9u) << "box 0's own sticks, the stick to it, the chain";
  // Every stick exactly once.
  const std::vector<int> seen = testing_phys::timesLaidOut(layout, scene.world.sticks().size());
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "stick " << k;
}

// Positions scattered so that sticks are stretched and squeezed, some particles pinned (one end
// or both of a stick), a range stick within its bounds (no correction) and one of zero length.
phys::Particles disturbed(const phys::World& world) {
  phys::Particles p = world.particles();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2), inverseMass(0.2, 5.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.inverseMass[i] = inverseMass(random);  // unequal, so that a swapped pair of weights shows
    p.position[i] += Vec3(jitter(random), jitter(random), jitter(random));
    p.previous[i] += Vec3(jitter(random), jitter(random), jitter(random));
  }
  const phys::Body& pinned = world.bodies()[3];
  p.inverseMass[pinned.firstParticle] = p.inverseMass[pinned.firstParticle + 1] = 0.0;
  const phys::Body& frozen = world.bodies()[5];
  for (int i = 0; i < frozen.particleCount; ++i) p.inverseMass[frozen.firstParticle + i] = 0.0;
  const phys::Body& collapsed = world.bodies()[9];
  p.position[collapsed.firstParticle + 1] = p.position[collapsed.firstParticle];
  // Body 12 (in a lane group) stretched half again, and turned a quarter about an axis across its
  // first stick at x*: that stick has no SHAKE root (|d| > L, r across d), and falls back to
  // Jakobsen's projection (shakeFallsBack checks it).
  const phys::Body& turned = world.bodies()[12];
  const phys::Stick& first = world.sticks()[turned.firstStick];
  const Vec3 along =
      glm::normalize(world.particles().position[first.b] - world.particles().position[first.a]);
  const Vec3 across =
      glm::normalize(glm::cross(along, std::abs(along.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  const Vec3 center = world.particles().position[turned.firstParticle];
  for (int i = 0; i < turned.particleCount; ++i) {
    const Vec3 r = world.particles().position[turned.firstParticle + i] - center;
    p.position[turned.firstParticle + i] = center + 1.5 * r;
    // A quarter turn about `across`: Rodrigues' formula at 90 degrees.
    p.previous[turned.firstParticle + i] = center + glm::cross(across, r) + across * glm::dot(across, r);
  }
  return p;
}

// Whether the first stick of body 12 in `p` has no SHAKE root (relax.cpp, relaxShake).
bool shakeFallsBack(const phys::World& world, const phys::Particles& p) {
  const phys::Stick& s = world.sticks()[world.bodies()[12].firstStick];
  const double w = p.inverseMass[s.a] + p.inverseMass[s.b];
  const Vec3 d = p.position[s.b] - p.position[s.a], r = p.previous[s.b] - p.previous[s.a];
  const double target = phys::detail::stickTarget(s, glm::length(d));
  const double qa = w * w * glm::dot(r, r), qb = 2.0 * w * glm::dot(d, r);
  const double qc = glm::dot(d, d) - target * target;
  return target >= 0.0 && qa > 0.0 && qb * qb - 4.0 * qa * qc < 0.0;
}

bool sameBits(const phys::Particles& a, const phys::Particles& b) {
  return std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(Vec3)) == 0;
}

TEST(StickLayout, EveryMethodGivesTheBitsOfThePlainLoopInCreationOrder) {
  Scene scene;
  const phys::World& world = scene.world;
  phys::StickLayout layout, inOrder = phys::StickLayout::inOrder(world.sticks().size());
  layout.build(world.sticks(), world.bodies(), world.particles().size());
  std::vector<double> degree(world.particles().size(), 0.0);
  for (const phys::Stick& s : world.sticks()) degree[s.a] += 1.0, degree[s.b] += 1.0;
  std::vector<Vec3> delta(world.particles().size());
  const double h = 1.0 / 240.0, compliance = 1e-5;

  for (int method = 0; method < 4; ++method) {
    phys::Particles byLayout = disturbed(world), plain = byLayout;
    std::vector<double> lambdaLayout(world.sticks().size(), 0.0), lambdaPlain = lambdaLayout;
    for (int pass = 0; pass < 3; ++pass) {
      switch (method) {
        case 0:
          phys::detail::relaxGaussSeidel(byLayout, world.sticks(), layout);
          phys::detail::relaxGaussSeidel(plain, world.sticks(), inOrder);
          break;
        case 1:
          phys::detail::relaxJacobi(byLayout, world.sticks(), layout, degree, delta);
          phys::detail::relaxJacobi(plain, world.sticks(), inOrder, degree, delta);
          break;
        case 2:
          phys::detail::relaxXpbd(byLayout, world.sticks(), layout, lambdaLayout, h, compliance);
          phys::detail::relaxXpbd(plain, world.sticks(), inOrder, lambdaPlain, h, compliance);
          break;
        case 3:
          phys::detail::relaxShake(byLayout, world.sticks(), layout);
          phys::detail::relaxShake(plain, world.sticks(), inOrder);
          break;
      }
    }
    EXPECT_TRUE(sameBits(byLayout, plain)) << "method " << method;
    EXPECT_EQ(std::memcmp(lambdaLayout.data(), lambdaPlain.data(), lambdaPlain.size() * sizeof(double)), 0);
    EXPECT_NE(std::memcmp(byLayout.position.data(), disturbed(world).position.data(),
                          byLayout.size() * sizeof(Vec3)),
              0)
        << "the passes must have moved something, or the comparison shows nothing";
  }
}

// Every particle of the lane groups has the same bits in `lanes` as in `plain`.
void expectLanesEqual(const phys::StickLayout& layout, const phys::Particles& lanes,
                      const phys::Particles& plain, const char* method) {
  for (const phys::StickLanes& group : layout.lanes()) {
    for (int l = 0; l < phys::kStickLanes; ++l) {
      for (int i = 0; i < group.particleCount; ++i) {
        const phys::ParticleId id = group.firstParticle[l] + i;
        EXPECT_EQ(std::memcmp(&lanes.position[id], &plain.position[id], sizeof(Vec3)), 0)
            << method << " particle " << id;
      }
    }
  }
}

// The baseline copy of the lane kernels runs on every machine, the AVX2 one where the CPU has it:
// on a machine with AVX2, both are compared here; the scalar passes are the reference.
TEST(StickLayout, BothCopiesOfTheLaneKernelsGiveTheSameBits) {
  Scene scene;
  const phys::World& world = scene.world;
  phys::StickLayout layout;
  layout.build(world.sticks(), world.bodies(), world.particles().size());
  const phys::StickLayout inOrder = phys::StickLayout::inOrder(world.sticks().size());
  for (const phys::detail::LaneIsa isa : {phys::detail::LaneIsa::Baseline, phys::detail::laneIsa()}) {
    phys::Particles lanes = disturbed(world), plain = lanes;
    phys::detail::relaxGaussSeidelLanes(phys::detail::laneArguments(lanes, layout), isa);
    phys::detail::relaxGaussSeidel(plain, world.sticks(), inOrder);
    // Only the lane groups' particles moved in `lanes`; put the rest back from `plain`.
    for (const phys::StickBlock& block : layout.blocks()) {
      for (int i = 0; i < block.particleCount; ++i)
        lanes.position[block.firstParticle + i] = plain.position[block.firstParticle + i];
    }
    for (const phys::StickRun& run : layout.runs()) {
      for (std::uint32_t k = run.begin; k < run.end; ++k) {
        lanes.position[world.sticks()[k].a] = plain.position[world.sticks()[k].a];
        lanes.position[world.sticks()[k].b] = plain.position[world.sticks()[k].b];
      }
    }
    EXPECT_TRUE(sameBits(lanes, plain)) << (isa == phys::detail::LaneIsa::Avx2 ? "avx2" : "baseline");

    std::vector<double> lambdaLanes(world.sticks().size(), 0.0), lambdaPlain = lambdaLanes;
    lanes = disturbed(world);
    plain = lanes;
    phys::detail::LaneArguments a = phys::detail::laneArguments(lanes, layout);
    a.lambda = lambdaLanes.data();
    a.inverseH2 = 240.0 * 240.0;
    a.compliance = 1e-5;
    phys::detail::relaxXpbdLanes(a, isa);
    phys::detail::relaxXpbd(plain, world.sticks(), inOrder, lambdaPlain, 1.0 / 240.0, 1e-5);
    expectLanesEqual(layout, lanes, plain, "xpbd");
    for (const phys::StickLanes& group : layout.lanes()) {
      for (int l = 0; l < phys::kStickLanes; ++l) {
        for (std::uint32_t k = 0; k < group.stickCount; ++k) {
          EXPECT_EQ(lambdaLanes[group.firstStick[l] + k], lambdaPlain[group.firstStick[l] + k]);
        }
      }
    }

    lanes = disturbed(world);
    plain = lanes;
    ASSERT_TRUE(shakeFallsBack(world, plain)) << "the fallback must be exercised";
    bool inLanes = false;
    for (const phys::StickLanes& group : layout.lanes()) {
      for (int l = 0; l < phys::kStickLanes; ++l)
        inLanes |= group.firstParticle[l] == world.bodies()[12].firstParticle;
    }
    ASSERT_TRUE(inLanes) << "body 12 must be in a lane group";
    phys::detail::relaxShakeLanes(phys::detail::laneArguments(lanes, layout), isa);
    phys::detail::relaxShake(plain, world.sticks(), inOrder);
    expectLanesEqual(layout, lanes, plain, "shake");

    std::vector<double> degree(world.particles().size(), 0.0);
    for (const phys::Stick& s : world.sticks()) degree[s.a] += 1.0, degree[s.b] += 1.0;
    std::vector<Vec3> delta(world.particles().size());
    lanes = disturbed(world);
    plain = lanes;
    a = phys::detail::laneArguments(lanes, layout);
    a.degree = degree.data();
    phys::detail::relaxJacobiLanes(a, isa);
    phys::detail::relaxJacobi(plain, world.sticks(), inOrder, degree, delta);
    expectLanesEqual(layout, lanes, plain, "jacobi");
  }
}

// A stick added after the first step (the layout already built) is relaxed from then on: the
// layout is rebuilt. Without it the box would fall away from the pinned particle, 1.2 m in 0.5 s.
TEST(StickLayout, AddingAStickLaterRebuildsTheLayout) {
  phys::WorldSettings ws;
  ws.ground = false;
  phys::World world(ws);
  for (int i = 0; i < 9; ++i) {
    phys::BodyDesc box;
    box.model = phys::BodyModel::Tetra;
    box.center = {1.5 * i, 2.0, 0.0};
    world.addBody(box);
  }
  const phys::ParticleId loose = world.addParticle({Vec3(6.0, 4.0, 0.0), Vec3(0.0), 0.0, true});
  world.step();
  const phys::ParticleId held = world.bodies()[4].firstParticle;
  world.addStick(held, loose);
  const double rest = world.sticks().back().minLength;
  for (int i = 0; i < 30; ++i) world.step();
  const double length = glm::length(world.particles().position[loose] - world.particles().position[held]);
  EXPECT_NEAR(length, rest, 1e-3 * rest);
}

}  // namespace
