// The links laid out by ragdoll (physics/link_layout.h): which groups go into lanes, and that the
// lanes relax them to exactly the bits of the plain loop over the links in creation order, with
// every copy of the kernels this machine can run.
#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "passes.h"
#include "physics/capsule_ragdoll.h"
#include "physics/world.h"
#include "relax_lanes.h"

namespace {

using phys::Vec3;

// 18 lean capsule ragdolls: the first 16 alike (two lane groups), the last two joined to each
// other by one more link, which makes them one group of another shape; and one seed ragdoll.
struct Scene {
  phys::World world;
  std::size_t loneLinks = 0;  // links of the groups that are in no lane group

  Scene() {
    std::vector<phys::CapsuleRagdoll> ragdolls;
    for (int i = 0; i < 18; ++i) {
      phys::RagdollDesc desc;
      desc.model = phys::RagdollModel::Lean;
      desc.hips = {2.0 * i, 1.2, 0.0};
      desc.scale = 0.8 + 0.02 * i;
      ragdolls.push_back(phys::addCapsuleRagdoll(world, desc));
    }
    const std::size_t perRagdoll = world.links().size() / 18;
    world.addLink(world.anchor(ragdolls[16].parts[0], {31.0, 1.2, 0.0}),
                  world.anchor(ragdolls[17].parts[0], {33.0, 1.2, 0.0}), 0.0, 3.0);
    const std::size_t before = world.links().size();
    phys::RagdollDesc seed;
    seed.hips = {0.0, 1.2, 5.0};
    phys::addCapsuleRagdoll(world, seed);
    loneLinks = 2 * perRagdoll + 1 + (world.links().size() - before);
  }
};

phys::LinkLayout built(const phys::World& world) {
  phys::LinkLayout layout;
  layout.build(world.links(), world.particles().size());
  return layout;
}

TEST(LinkLayout, RagdollsAlikeGoIntoLanesTheRestStaysInOrder) {
  Scene scene;
  const phys::LinkLayout layout = built(scene.world);
  ASSERT_EQ(layout.lanes().size(), 2u);
  EXPECT_EQ(layout.others().size(), scene.loneLinks);
  std::vector<int> seen(scene.world.links().size(), 0);
  for (const std::uint32_t k : layout.others()) ++seen[k];
  for (const phys::LinkLanes& group : layout.lanes()) {
    for (int l = 0; l < phys::kLinkLanes; ++l) {
      for (int k = 0; k < group.linkCount; ++k) ++seen[layout.laneLinks()[group.links[l] + k]];
    }
  }
  for (std::size_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], 1) << "link " << k;
  EXPECT_TRUE(std::is_sorted(layout.others().begin(), layout.others().end()));
}

// Joints pulled apart, particles of unequal mass, a few pinned and one body frozen whole.
phys::Particles disturbed(const phys::World& world) {
  phys::Particles p = world.particles();
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1), inverseMass(0.2, 5.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.position[i] += Vec3(jitter(random), jitter(random), jitter(random));
    p.inverseMass[i] = inverseMass(random);
  }
  for (const std::size_t pinned : {3u, 50u, 97u}) p.inverseMass[pinned] = 0.0;
  const phys::Body& frozen = world.bodies()[30];
  for (int i = 0; i < frozen.particleCount; ++i) p.inverseMass[frozen.firstParticle + i] = 0.0;
  return p;
}

TEST(LinkLayout, LanesGiveTheBitsOfThePlainLoopInCreationOrder) {
  Scene scene;
  const phys::World& world = scene.world;
  const phys::LinkLayout layout = built(world);
  // With slack (all of it 0) solveLinks takes the plain loop over every link in creation order.
  const std::vector<double> noSlack(world.links().size(), 0.0);
  for (const phys::detail::LaneIsa isa : {phys::detail::LaneIsa::Baseline, phys::detail::laneIsa()}) {
    phys::Particles lanes = disturbed(world), plain = lanes;
    for (int pass = 0; pass < 3; ++pass) {
      phys::detail::solveLinkLanes(phys::detail::linkLaneArguments(lanes, layout), isa);
      for (const std::uint32_t k : layout.others()) {
        phys::detail::solveLinks(lanes, world.links().subspan(k, 1), layout,
                                 std::span<const double>(noSlack).subspan(k, 1));
      }
      phys::detail::solveLinks(plain, world.links(), layout, noSlack);
    }
    EXPECT_EQ(std::memcmp(lanes.position.data(), plain.position.data(), plain.size() * sizeof(Vec3)), 0)
        << (isa == phys::detail::LaneIsa::Avx2 ? "avx2" : "baseline");
    EXPECT_NE(
        std::memcmp(plain.position.data(), disturbed(world).position.data(), plain.size() * sizeof(Vec3)), 0)
        << "the passes must have moved something";
  }
  // And the pass the step runs, lanes and the rest together.
  phys::Particles lanes = disturbed(world), plain = lanes;
  phys::detail::solveLinks(lanes, world.links(), layout);
  phys::detail::solveLinks(plain, world.links(), layout, noSlack);
  EXPECT_EQ(std::memcmp(lanes.position.data(), plain.position.data(), plain.size() * sizeof(Vec3)), 0);
}

// A link added after the first step is in the rebuilt layout: the ragdolls it joins are held.
TEST(LinkLayout, ALinkAddedLaterRebuildsTheLayout) {
  phys::WorldSettings ws;
  ws.ground = false;
  phys::World world(ws);
  for (int i = 0; i < 9; ++i) {
    phys::RagdollDesc desc;
    desc.model = phys::RagdollModel::Lean;
    desc.hips = {2.0 * i, 1.2, 0.0};
    phys::addCapsuleRagdoll(world, desc);
  }
  const phys::ParticleId hook = world.addParticle({Vec3(0.0, 3.0, 0.0), Vec3(0.0), 0.0, true});
  world.step();
  const phys::BodyId pelvis{};
  world.addLink(phys::embedParticle(hook), world.anchor(pelvis, world.particles().position[hook]), 0.0, 0.0);
  for (int i = 0; i < 30; ++i) world.step();
  // Hung from the hook by a pin, the first ragdoll stays there, the pin stretched by about 1 cm
  // under the 70 kg body at 2 x 4 passes; unheld, the ragdoll would have fallen 1.2 m.
  EXPECT_LT(glm::length(world.position(world.links().back().b) - world.particles().position[hook]), 0.05);
}

}  // namespace
