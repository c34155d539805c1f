// What loading a large scene text costs (docs/performance.md, "Scene loading: one scan before the
// parse"): the scans before the parse, pugixml's parse, reading the elements and building the
// world, from the text in memory (no file is read).
//   build/release/tests/scene_bench [--benchmark_filter=particles|bullet]
// The figures quoted there are instruction counts, stable on a busy machine:
//   valgrind --tool=callgrind build/release/tests/scene_bench --benchmark_filter=particles
#include <string>

#include <benchmark/benchmark.h>

#include "scenes/scene.h"
#include "scenes/scene_writer.h"

namespace {

// A chain of `n` particles, each tied to the one before it by a stick and to the one two before
// by another: about 119 bytes a particle (11.9 MB at 100,000), with quotes of both kinds, a
// comment and a reference, as a file written by hand or by a tool may hold.
std::string particlesAndSticks(int n) {
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- generated: R & D -->\n"
      "<scene name=\"particles &amp; sticks\" description='a chain'>\n";
  // Appended piece by piece: "p" + std::string trips GCC 12's -Wrestrict false positive (GCC bug 105329).
  auto name = [](int i) { return std::string("p").append(std::to_string(i)); };
  for (int i = 0; i < n; ++i) {
    xml.append("  <particle name=\"").append(name(i)).append("\" pos=\"").append(std::to_string(i % 100));
    xml.append(" ").append(std::to_string(1 + i / 100)).append(" 0.5\" mass='1'/>\n");
    if (i >= 1)
      xml.append("  <stick a=\"").append(name(i)).append("\" b=\"").append(name(i - 1)).append("\"/>\n");
    if (i >= 2)
      xml.append("  <stick a='").append(name(i)).append("' b='").append(name(i - 2)).append("'/>\n");
  }
  return xml + "</scene>\n";
}

// Bullet's pile of ragdolls as Save As writes it, body by body: a world file, not its generator.
std::string bulletRagdollsWorld() {
  const scenes::Scene scene =
      scenes::loadSceneFile(std::string(DATA_DIR) + "/assets/scenes/bullet-ragdolls.xml");
  return scenes::writeSceneXml(scene);
}

void loadText(benchmark::State& state, const std::string& xml) {
  for (auto _ : state) {
    scenes::Scene scene = scenes::loadSceneText(xml, "bench.xml");
    benchmark::DoNotOptimize(scene);
  }
  state.counters["MB"] = static_cast<double>(xml.size()) / (1 << 20);
}

void BM_LoadParticlesAndSticks(benchmark::State& state) {
  loadText(state, particlesAndSticks(100000));
}
BENCHMARK(BM_LoadParticlesAndSticks)->Unit(benchmark::kMillisecond);

void BM_LoadBulletRagdollsWorld(benchmark::State& state) {
  loadText(state, bulletRagdollsWorld());
}
BENCHMARK(BM_LoadBulletRagdollsWorld)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
