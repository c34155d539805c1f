// A chain's passes run all at once (StickLayout::chains, detail::relaxChainsAhead): which runs of
// sticks are chains, and that running a substep's passes over them at once gives the bits of one
// pass after the other, with the ground's passes between them or without.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "passes.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::Vec3;

// A chain of `sticks` sticks from `start` along `along`, 0.1 m links; `backwards` creates each
// stick from its far particle to its near one. Returns its particles.
std::vector<phys::ParticleId> addChain(phys::World& world, Vec3 start, Vec3 along, int sticks,
                                       bool backwards = false, bool pinned = false) {
  std::vector<phys::ParticleId> ids;
  for (int i = 0; i <= sticks; ++i) {
    phys::ParticleDesc p;
    p.position = start + 0.1 * i * along;
    p.pinned = pinned && i == 0;
    ids.push_back(world.addParticle(p));
    if (i == 0) continue;
    if (backwards) {
      world.addStick(ids[i], ids[i - 1]);
    } else {
      world.addStick(ids[i - 1], ids[i]);
    }
  }
  return ids;
}

struct Shapes {
  phys::World world{phys::WorldSettings{}, phys::SolverSettings{}};
  std::uint32_t forwards = 0, backwards = 0;  // the first sticks of the two chains

  Shapes() {
    phys::BodyDesc box;
    box.center = {0.0, 1.0, 0.0};
    const phys::BodyId body = world.addBody(box);
    forwards = static_cast<std::uint32_t>(world.sticks().size());
    addChain(world, {0, 5, 0}, {1, 0, 0}, 12);  // a chain
    backwards = static_cast<std::uint32_t>(world.sticks().size());
    addChain(world, {0, 6, 0}, {1, 0, 0}, 12, true);  // a chain, its sticks the other way round
    // tied to the box: its first particle is in another stick
    const auto tied = addChain(world, {0, 7, 0}, {1, 0, 0}, 12);
    world.addStick(world.bodies()[body].firstParticle, tied[0]);
    addChain(world, {0, 8, 0}, {1, 0, 0}, static_cast<int>(phys::kMinChainSticks) - 1);  // too short
    const auto ring = addChain(world, {0, 9, 0}, {1, 0, 0}, 12);                         // closed on itself
    world.addStick(ring.back(), ring.front());
    const auto linked = addChain(world, {0, 10, 0}, {1, 0, 0}, 12);  // a link holds its middle
    world.addLink(phys::embedParticle(linked[6]), phys::embedParticle(world.addParticle({Vec3(0, 11, 0)})),
                  0.0, 5.0);
    const auto branched = addChain(world, {0, 12, 0}, {1, 0, 0}, 12);  // a third stick at its middle
    world.addStick(branched[6], world.addParticle({Vec3(0.6, 12.5, 0)}));
  }
};

TEST(ChainsAhead, AreWholePathsOfLooseParticlesThatNothingElseHolds) {
  Shapes shapes;
  const phys::World& world = shapes.world;
  std::vector<std::uint8_t> held(world.particles().size(), 0);
  for (const phys::Link& link : world.links()) {
    for (int i = 0; i < link.a.count; ++i) held[link.a.particle[static_cast<std::size_t>(i)]] = 1;
    for (int i = 0; i < link.b.count; ++i) held[link.b.particle[static_cast<std::size_t>(i)]] = 1;
  }
  phys::StickLayout layout;
  layout.build(world.sticks(), world.bodies(), world.particles().size(), held);
  ASSERT_EQ(layout.chains().size(), 2u);
  EXPECT_EQ(layout.chains()[0].begin, shapes.forwards);
  EXPECT_EQ(layout.chains()[0].end, shapes.forwards + 12);
  EXPECT_EQ(layout.chains()[1].begin, shapes.backwards);
  EXPECT_EQ(layout.chains()[1].end, shapes.backwards + 12);
  EXPECT_EQ(layout.ahead().size(), 2u);
  // Every stick exactly once: the box's own as a block, the rest in runs or chains.
  const std::vector<int> seen = testing_phys::timesLaidOut(layout, world.sticks().size());
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "stick " << k;
}

// Shapes' particles moved off their places by up to 3 cm, so that every stick needs a correction,
// with unequal masses (a swapped pair of weights would show).
phys::Particles disturbed(const phys::World& world) {
  phys::Particles p = world.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double k = static_cast<double>(i);
    p.position[i] += 0.03 * Vec3(std::sin(1.7 * k), std::cos(2.3 * k), std::sin(0.9 * k));
    if (p.inverseMass[i] != 0.0) p.inverseMass[i] = 0.2 + static_cast<double>(i % 5);
  }
  return p;
}

bool sameBits(const phys::Particles& a, const phys::Particles& b) {
  return std::memcmp(a.position.data(), b.position.data(), a.size() * sizeof(Vec3)) == 0;
}

// `passes` passes of Gauss-Seidel (xpbd false) or XPBD over `p`, the chains first all at once.
void relaxAhead(phys::Particles& p, const phys::World& world, phys::StickLayout& layout, int passes,
                bool xpbd, const phys::detail::GroundPlane* ground, std::vector<double>& lambda) {
  const double h = 1.0 / 240.0, compliance = 1e-6;
  std::vector<Vec3> saved(2 * world.sticks().size());
  if (xpbd) {
    phys::detail::relaxChainsAheadXpbd(p, world.sticks(), layout, passes, ground, saved, lambda, h,
                                       compliance);
  } else {
    phys::detail::relaxChainsAhead(p, world.sticks(), layout, passes, ground, saved);
  }
  for (int pass = 0; pass < passes; ++pass) {
    if (xpbd) {
      phys::detail::relaxXpbd(p, world.sticks(), layout, lambda, h, compliance);
    } else {
      phys::detail::relaxGaussSeidel(p, world.sticks(), layout);
    }
  }
}

void relaxInOrder(phys::Particles& p, const phys::World& world, int passes, bool xpbd,
                  std::vector<double>& lambda) {
  const phys::StickLayout inOrder = phys::StickLayout::inOrder(world.sticks().size());
  for (int pass = 0; pass < passes; ++pass) {
    if (xpbd) {
      phys::detail::relaxXpbd(p, world.sticks(), inOrder, lambda, 1.0 / 240.0, 1e-6);
    } else {
      phys::detail::relaxGaussSeidel(p, world.sticks(), inOrder);
    }
  }
}

TEST(ChainsAhead, GiveTheBitsOfOnePassAfterTheOther) {
  Shapes shapes;
  const phys::World& world = shapes.world;
  phys::StickLayout layout;
  layout.build(world.sticks(), world.bodies(), world.particles().size());
  for (const bool xpbd : {false, true}) {
    for (const int passes : {2, 3, 10}) {
      phys::Particles ahead = disturbed(world), inOrder = ahead;
      std::vector<double> lambdaAhead(world.sticks().size(), 0.0), lambdaInOrder = lambdaAhead;
      relaxAhead(ahead, world, layout, passes, xpbd, nullptr, lambdaAhead);
      EXPECT_EQ(layout.ahead()[0], 1);
      EXPECT_EQ(layout.ahead()[1], 1);
      relaxInOrder(inOrder, world, passes, xpbd, lambdaInOrder);
      EXPECT_TRUE(sameBits(ahead, inOrder)) << (xpbd ? "xpbd " : "gauss-seidel ") << passes << " passes";
      EXPECT_EQ(std::memcmp(lambdaAhead.data(), lambdaInOrder.data(), lambdaAhead.size() * sizeof(double)),
                0);
      EXPECT_FALSE(sameBits(ahead, disturbed(world))) << "the passes must have moved the chains";
      layout.clearAhead();
    }
  }
}

// A chain that reaches the ground's plane anywhere in its passes is put back and left to them,
// where the ground's passes come between: the bits are again those of one pass after the other.
// Two upright chains of 12 sticks of 0.1 m squeezed to 0.09 m, the passes push each one's lower
// end down; one stands from y = 1, the other from y = 10.
TEST(ChainsAhead, AChainThatReachesTheGroundIsLeftToThePasses) {
  phys::World world(phys::WorldSettings{}, phys::SolverSettings{});
  std::uint32_t low = 0;  // the first stick of the low chain
  for (const double top : {10.0, 1.0}) {
    if (top == 1.0) low = static_cast<std::uint32_t>(world.sticks().size());
    phys::ParticleId previous{};
    for (int i = 0; i <= 12; ++i) {
      const phys::ParticleId id = world.addParticle({Vec3(0.001 * (i % 3), top - 0.09 * i, 0.0)});
      if (i > 0) world.addStick(previous, id, 0.1, 0.0);
      previous = id;
    }
  }
  phys::StickLayout layout;
  layout.build(world.sticks(), world.bodies(), world.particles().size());
  ASSERT_EQ(layout.chains().size(), 2u);
  const phys::Particles start = world.particles();
  auto lowest = [&](const phys::Particles& p) {
    double y = 1e9;
    for (std::uint32_t k = low; k < low + 12; ++k) y = std::min(y, p.position[world.sticks()[k].b].y);
    return y;
  };
  phys::Particles after = start;
  std::vector<double> unused(world.sticks().size(), 0.0);
  relaxInOrder(after, world, 3, false, unused);
  ASSERT_LT(lowest(after), lowest(start) - 1e-3) << "the passes must push the low chain down through a plane";
  // A plane the passes push the low chain through, and one it is on from the start.
  for (const double height : {0.5 * (lowest(start) + lowest(after)), lowest(start)}) {
    const phys::detail::GroundPlane ground{Vec3(0, 1, 0), height};
    for (const bool xpbd : {false, true}) {
      phys::Particles ahead = start, inOrder = start;
      std::vector<double> lambdaAhead(world.sticks().size(), 0.0), lambdaInOrder = lambdaAhead;
      relaxAhead(ahead, world, layout, 3, xpbd, &ground, lambdaAhead);
      EXPECT_EQ(layout.ahead()[0], 1) << "the high chain";
      EXPECT_EQ(layout.ahead()[1], 0) << "the low chain, reaching the plane at " << height;
      relaxInOrder(inOrder, world, 3, xpbd, lambdaInOrder);
      EXPECT_TRUE(sameBits(ahead, inOrder));
      EXPECT_EQ(std::memcmp(lambdaAhead.data(), lambdaInOrder.data(), lambdaAhead.size() * sizeof(double)),
                0);
      layout.clearAhead();
    }
  }
}

// The world's step: a pinned chain released level swings down onto the ground, so that its
// passes run at once while it is above it and one after the other once it reaches it. A link
// that never pulls (0 to 5 m, to a particle 1 m away) keeps the same chain out of the chains in a
// second world: both must end with the same bits.
TEST(ChainsAhead, AChainSwingingOntoTheGroundEndsAsItsPassesOneAfterTheOther) {
  for (const phys::SolverMethod method : {phys::SolverMethod::GaussSeidel, phys::SolverMethod::Xpbd}) {
    phys::SolverSettings solver;
    solver.method = method;
    solver.iterations = 4;
    solver.substeps = 2;
    phys::World ahead(phys::WorldSettings{}, solver), held(phys::WorldSettings{}, solver);
    for (phys::World* world : {&ahead, &held}) {
      const auto chain = addChain(*world, {0, 1.5, 0}, {1, 0, 0}, 30, false, true);
      const phys::ParticleId anchor = world->addParticle({Vec3(1.5, 2.5, 0), Vec3(0.0), 1.0, true});
      if (world == &held)
        world->addLink(phys::embedParticle(chain[15]), phys::embedParticle(anchor), 0.0, 5.0);
    }
    bool reached = false;
    for (int step = 0; step < 240; ++step) {
      ahead.step();
      held.step();
      for (const Vec3& x : ahead.particles().position) reached = reached || x.y < 1e-3;
    }
    EXPECT_TRUE(reached) << "the chain must reach the ground, or the test shows nothing of it";
    EXPECT_EQ(ahead.stateHash(), held.stateHash()) << phys::toString(method);
  }
}

}  // namespace
