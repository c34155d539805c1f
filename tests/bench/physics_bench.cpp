// Step cost of the physics library, per method and box model, on scenes large enough that the
// per-step overhead does not dominate. Run: build/release/tests/physics_bench
// (CTest runs it once, briefly, only to keep it building and running.)
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "physics/animation.h"
#include "physics/capsule_ragdoll.h"
#include "physics/world.h"

namespace {

// side x side boxes resting on the ground in one layer, 0.5 m apart, so each has ground
// contacts and none touches another (box-box contact has its own benchmark).
phys::World restingBoxes(phys::SolverMethod method, phys::BodyModel model, int side) {
  phys::SolverSettings s;
  s.method = method;
  phys::World world({}, s);
  for (int i = 0; i < side; ++i) {
    for (int k = 0; k < side; ++k) {
      phys::BodyDesc box;
      box.model = model;
      box.center = {1.5 * i, 0.5, 1.5 * k};
      world.addBody(box);
    }
  }
  for (int i = 0; i < 30; ++i) world.step();  // settle into contact
  return world;
}

void BM_RestingBoxes(benchmark::State& state) {
  const auto method = static_cast<phys::SolverMethod>(state.range(0));
  const auto model = static_cast<phys::BodyModel>(state.range(1));
  phys::World world = restingBoxes(method, model, 32);  // 1024 boxes
  for (auto _ : state) world.step();
  state.counters["boxes"] = static_cast<double>(world.bodies().size());
  state.counters["particles"] = static_cast<double>(world.particles().size());
  state.SetLabel(std::string(toString(method)) + "/" + std::string(toString(model)));
}
BENCHMARK(BM_RestingBoxes)->ArgsProduct({{0, 1, 2, 3}, {0, 1}})->Unit(benchmark::kMicrosecond);

// A long chain: sticks only, the relaxation loop alone.
void BM_Chain(benchmark::State& state) {
  phys::SolverSettings s;
  s.method = static_cast<phys::SolverMethod>(state.range(0));
  phys::WorldSettings w;
  w.ground = false;
  phys::World world(w, s);
  phys::ParticleId previous = world.addParticle({phys::Vec3(0.0), phys::Vec3(0.0), 0.0, true});
  for (int i = 1; i <= 10000; ++i) {
    const auto p = world.addParticle({phys::Vec3(0.01 * i, 0.0, 0.0)});
    world.addStick(previous, p);
    previous = p;
  }
  for (auto _ : state) world.step();
  state.SetLabel(std::string(toString(s.method)));
  state.SetItemsProcessed(state.iterations() * 10000 * s.iterations);  // stick projections
}
BENCHMARK(BM_Chain)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

// The seed's box of boxes scaled up: a 10 x 10 x 10 block of touching boxes settling on the
// ground, so the broad phase, the SAT and the box-box contacts carry the step.
void BM_BoxBlock(benchmark::State& state) {
  phys::World world;
  for (int y = 0; y < 10; ++y) {
    for (int z = 0; z < 10; ++z) {
      for (int x = 0; x < 10; ++x) {
        phys::BodyDesc box;
        box.center = {x - 4.5, 0.5 + y, z - 4.5};
        world.addBody(box);
      }
    }
  }
  for (int i = 0; i < 30; ++i) world.step();
  for (auto _ : state) world.step();
  state.counters["box_contacts"] = static_cast<double>(world.bodyContacts().size());
  state.counters["pairs"] = static_cast<double>(world.broadPhasePairs());
}
BENCHMARK(BM_BoxBlock)->Unit(benchmark::kMillisecond);

// A pile of lean capsule ragdolls (tetra parts), as `lab scale` builds it: on a grid 2 m apart,
// each tipped 20 degrees onto its neighbours, at the pile's own settings (Gauss-Seidel 2 x 4).
// Counts how many stick and link projections the sticks and links stages make per second of
// their own time (Profile), the figure the pipeline issue sets a target for.
void BM_RagdollPile(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  phys::World world;
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  for (int i = 0; i < n; ++i) {
    phys::RagdollDesc desc;
    desc.model = phys::RagdollModel::Lean;
    desc.hips = {2.0 * (i % side - (side - 1) / 2.0), 1.2, 2.0 * (i / side - (side - 1) / 2.0)};
    const double tip = glm::radians(20.0);
    desc.orientation = phys::Quat(phys::Vec3(i % 2 == 0 ? tip : -tip, 0.0, (i / 2) % 2 == 0 ? tip : -tip));
    phys::addCapsuleRagdoll(world, desc);
  }
  for (int i = 0; i < 60; ++i) world.step();  // into the pile
  double stickMs = 0.0, linkMs = 0.0;
  for (auto _ : state) {
    world.step();
    stickMs += world.profile()[phys::Stage::Sticks];
    linkMs += world.profile()[phys::Stage::Links];
  }
  const phys::SolverSettings& s = world.solverSettings();
  const double passes = static_cast<double>(state.iterations()) * s.iterations * s.substeps;
  const double sticks = passes * static_cast<double>(world.sticks().size());
  const double links = passes * static_cast<double>(world.links().size());
  state.counters["sticks_per_s"] = sticks / (stickMs * 1e-3);
  state.counters["links_per_s"] = links / (linkMs * 1e-3);
  state.counters["projections_per_s"] = (sticks + links) / ((stickMs + linkMs) * 1e-3);
  state.counters["bodies"] = static_cast<double>(world.bodies().size());
}
BENCHMARK(BM_RagdollPile)->Arg(64)->Arg(512)->Unit(benchmark::kMillisecond);

// World::stateHash, which the sandbox's recording takes after every step: 64 rigid boxes and 64
// boxes of particles (576 particles), falling.
void BM_StateHash(benchmark::State& state) {
  phys::World world;
  for (int i = 0; i < 128; ++i) {
    phys::BodyDesc box;
    box.model = i % 2 == 0 ? phys::BodyModel::Rigid : phys::BodyModel::Corners;
    box.center = {1.5 * (i % 16), 1.0 + 1.5 * (i / 16), 0.0};
    world.addBody(box);
  }
  for (int i = 0; i < 10; ++i) world.step();
  for (auto _ : state) benchmark::DoNotOptimize(world.stateHash());
}
BENCHMARK(BM_StateHash)->Unit(benchmark::kMicrosecond);

// A world mostly asleep: BM_RagdollPile's 64 ragdolls come to rest and, with sleeping on
// (argument 1), fall asleep, while a chain of 10 loose particles hung from a pin 30 m away swings
// on for the whole run. With sleeping off (argument 0) the resting pile is stepped in full. What a
// step costs with the pile asleep is what sleeping saves (docs/performance.md, "Islands and
// sleeping": the passes, the broad phase and the ground skip what sleeps).
void BM_SleepingPileBesideAPendulum(benchmark::State& state) {
  phys::SolverSettings s;
  s.sleep.enabled = state.range(0) != 0;
  phys::World world({}, s);
  for (int i = 0; i < 64; ++i) {
    phys::RagdollDesc desc;
    desc.model = phys::RagdollModel::Lean;
    desc.hips = {2.0 * (i % 8 - 3.5), 1.2, 2.0 * (i / 8 - 3.5)};
    const double tip = glm::radians(20.0);
    desc.orientation = phys::Quat(phys::Vec3(i % 2 == 0 ? tip : -tip, 0.0, (i / 2) % 2 == 0 ? tip : -tip));
    phys::addCapsuleRagdoll(world, desc);
  }
  phys::ParticleId previous = world.addParticle({phys::Vec3(30.0, 12.0, 0.0), phys::Vec3(0.0), 0.0, true});
  for (int i = 1; i <= 10; ++i) {
    const phys::ParticleId p = world.addParticle({phys::Vec3(30.0 + i, 12.0, 0.0)});
    world.addStick(previous, p);
    previous = p;
  }
  for (int i = 0; i < 3600 && (i < 600 || world.islands().awakeBodies() > 0); ++i) world.step();
  // The chain must still swing: with everything asleep a step only advances the clock.
  if (world.islands().allAsleep()) state.SkipWithError("the pendulum came to rest");
  for (auto _ : state) world.step();
  state.counters["bodies_asleep"] = static_cast<double>(world.islands().sleepingBodies());
  state.counters["bodies"] = static_cast<double>(world.bodies().size());
}
BENCHMARK(BM_SleepingPileBesideAPendulum)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

// Building Bullet's pile: 136 capsule ragdolls added to a world, as the scene loader adds them
// (addCapsuleRagdoll checks each in an empty world first, so that one refused half way adds nothing).
void BM_AddCapsuleRagdolls(benchmark::State& state) {
  for (auto _ : state) {
    phys::World world;
    for (int i = 0; i < 136; ++i) {
      phys::RagdollDesc d;
      d.hips = phys::Vec3(2.0 * (i % 10), 1.0 + 2.0 * (i / 10), 0.0);
      phys::addCapsuleRagdoll(world, d);
    }
    benchmark::DoNotOptimize(world.bodies().size());
  }
}
BENCHMARK(BM_AddCapsuleRagdolls)->Unit(benchmark::kMillisecond);

// Checking a clip read from a file, and comparing its skeleton with another's, as the scene loader
// does for each character's clips: linear in the bones (a clip may have thousands), with one frame
// so that the turns' check does not hide the bones'.
void BM_ClipBones(benchmark::State& state) {
  const auto bones = static_cast<std::size_t>(state.range(0));
  phys::Clip clip;
  clip.name = "chain";
  clip.frameTime = 1.0 / 30.0;
  clip.root = {phys::Vec3(0.0)};
  for (std::size_t b = 0; b < bones; ++b) {
    clip.bones.push_back("bone" + std::to_string(b));
    clip.parents.push_back(static_cast<int>(b) - 1);
  }
  clip.turns.assign(bones, phys::Quat(1.0, 0.0, 0.0, 0.0));
  phys::Clip other = clip;
  other.bones.back() = "other";
  for (auto _ : state) {
    benchmark::DoNotOptimize(phys::clipProblem(clip));
    benchmark::DoNotOptimize(phys::skeletonDifference(clip, other));
  }
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_ClipBones)->RangeMultiplier(8)->Range(64, 32768)->Complexity()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
