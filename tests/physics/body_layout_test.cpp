// Body damping in SIMD lanes (physics/body_layout.h): the bodies grouped, and every body damped to
// exactly the bits of the one-body-at-a-time pass, with every copy of the kernel this machine runs.
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "passes.h"
#include "physics/world.h"
#include "relax_lanes.h"

namespace {

using phys::Vec3;

phys::World scene() {
  phys::World world;
  for (int i = 0; i < 26; ++i) {
    phys::BodyDesc box;
    box.model = i < 17 ? phys::BodyModel::Tetra : phys::BodyModel::Corners;
    box.center = {2.0 * i, 1.0, 0.0};
    box.size = {0.5 + 0.05 * i, 1.0, 0.7};
    world.addBody(box);
  }
  return world;
}

TEST(BodyLayout, BodiesOfOneParticleCountGoIntoLanes) {
  const phys::World world = scene();
  phys::BodyLayout layout;
  layout.build(world.bodies());
  ASSERT_EQ(layout.lanes().size(), 3u);  // 16 of the 17 tetra boxes, 8 of the 9 corners boxes
  EXPECT_EQ(layout.others().size(), 2u);
  EXPECT_EQ(layout.lanes()[0].particleCount, 4);
}

// Moving bodies (x* scattered), unequal masses, one body with a pinned particle and one frozen:
// those two are left alone by both passes.
phys::Particles moving(const phys::World& world) {
  phys::Particles p = world.particles();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), inverseMass(0.2, 5.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.position[i] += Vec3(jitter(random), jitter(random), jitter(random));
    p.previous[i] += Vec3(jitter(random), jitter(random), jitter(random));
    p.inverseMass[i] = inverseMass(random);
  }
  p.inverseMass[world.bodies()[2].firstParticle + 1] = 0.0;
  const phys::Body& frozen = world.bodies()[20];
  for (int i = 0; i < frozen.particleCount; ++i) p.inverseMass[frozen.firstParticle + i] = 0.0;
  return p;
}

TEST(BodyLayout, LanesDampToTheBitsOfOneBodyAtATime) {
  const phys::World world = scene();
  phys::BodyLayout layout;
  layout.build(world.bodies());
  const double fraction = 0.3;
  phys::Particles oneByOne = moving(world);
  for (std::size_t b = 0; b < world.bodies().size(); ++b) {
    const std::span<const phys::Body> one = world.bodies().subspan(b, 1);
    phys::BodyLayout single;
    single.build(one);
    ASSERT_TRUE(single.lanes().empty());
    phys::detail::dampBodyMotion(oneByOne, one, single, fraction);
  }
  const phys::Particles start = moving(world);
  EXPECT_NE(std::memcmp(oneByOne.previous.data(), start.previous.data(), start.size() * sizeof(Vec3)), 0);
  for (const phys::detail::LaneIsa isa : {phys::detail::LaneIsa::Baseline, phys::detail::laneIsa()}) {
    phys::Particles lanes = moving(world);
    phys::detail::dampBodyLanes(phys::detail::dampLaneArguments(lanes, layout, fraction), isa);
    for (const phys::BodyId b : layout.others()) {
      phys::BodyLayout single;
      single.build(world.bodies().subspan(b, 1));
      phys::detail::dampBodyMotion(lanes, world.bodies().subspan(b, 1), single, fraction);
    }
    EXPECT_EQ(std::memcmp(lanes.previous.data(), oneByOne.previous.data(), start.size() * sizeof(Vec3)), 0)
        << (isa == phys::detail::LaneIsa::Avx2 ? "avx2" : "baseline");
    EXPECT_EQ(std::memcmp(lanes.position.data(), start.position.data(), start.size() * sizeof(Vec3)), 0)
        << "damping moves x* only";
  }
  // The pinned body and the frozen one kept their x*.
  for (const int b : {2, 20}) {
    const phys::Body& box = world.bodies()[b];
    EXPECT_EQ(std::memcmp(&oneByOne.previous[box.firstParticle], &start.previous[box.firstParticle],
                          box.particleCount * sizeof(Vec3)),
              0)
        << "body " << b;
  }
}

}  // namespace
