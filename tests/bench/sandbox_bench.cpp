// How long a command waits for the sandbox's steps in flight (docs/sandbox.md, "Time budget"):
// a scene at 64 x 64 (a step of 0.1 to 0.5 s), 8 steps started on copies in the background, and a
// command given 0 to 100 ms later (a fixed pseudo-random sequence); the command's wall time is
// what a key press waits before it acts. Reported: the median and the largest, in ms.
//   build/release/tests/sandbox_bench [--benchmark_filter=ragdolls|bullet]
// Also what a recording file of 10 s costs (docs/sandbox.md, "Recording files"): the time to save
// and to open it, and its size in MB of 2^20 bytes:
//   build/release/tests/sandbox_bench --benchmark_filter=RecordingFile
#include <algorithm>
#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>

#include "session.h"

namespace {

using Clock = std::chrono::steady_clock;

void commandDuringSteps(benchmark::State& state, const char* scene) {
  const std::filesystem::path dir = std::filesystem::path(DATA_DIR) / "assets" / "scenes";
  sandbox::Session s(dir / (std::string(scene) + ".xml"), dir);
  phys::SolverSettings slow = s.scene().world.solverSettings();
  slow.iterations = slow.substeps = 64;
  s.setSolverSettings(slow);
  std::mt19937 random(1);
  std::vector<double> waits;
  double sign = 1.0;
  for (auto _ : state) {
    s.startSteps(8, std::chrono::seconds(600));
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(0, 100)(random)));
    const auto start = Clock::now();
    s.changeDamping(sign * 0.01);  // cancels the steps, then acts
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    state.SetIterationTime(seconds);
    waits.push_back(seconds * 1000.0);
    sign = -sign;
  }
  std::sort(waits.begin(), waits.end());
  state.counters["median_ms"] = waits[waits.size() / 2];
  state.counters["max_ms"] = waits.back();
}

BENCHMARK_CAPTURE(commandDuringSteps, ragdolls, "ragdolls")
    ->Iterations(20)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(commandDuringSteps, bullet, "bullet-ragdolls")
    ->Iterations(20)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// 600 steps (10 s) of the scene, then its recording saved and opened once each (iterations = 1:
// a save of Bullet's pile takes seconds).
void recordingFile(benchmark::State& state, const char* scene) {
  const std::filesystem::path dir = std::filesystem::path(DATA_DIR) / "assets" / "scenes";
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "sandbox-bench.jrec";
  sandbox::Session s(dir / (std::string(scene) + ".xml"), dir);
  // All 600 steps kept, however many keyframes the machine's speed makes (setStepCost).
  s.setRecordingBudget(std::size_t{8} << 30);
  for (int i = 0; i < 600; ++i) s.step();
  double saveSeconds = 0.0, openSeconds = 0.0;
  for (auto _ : state) {
    auto start = Clock::now();
    if (!s.saveRecording(file).empty()) state.SkipWithError("the save failed");
    saveSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    sandbox::Session other(dir / (std::string(scene) + ".xml"), dir);
    start = Clock::now();
    if (!other.openRecording(file).empty()) state.SkipWithError("the open failed");
    openSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    state.SetIterationTime(saveSeconds + openSeconds);
    state.counters["opened_MB"] = static_cast<double>(other.recording().bytes()) / (1 << 20);
  }
  state.counters["steps"] = static_cast<double>(s.recording().last() - s.recording().first());
  state.counters["save_s"] = saveSeconds;
  state.counters["open_s"] = openSeconds;
  state.counters["file_MB"] = static_cast<double>(std::filesystem::file_size(file)) / (1 << 20);
  std::filesystem::remove(file);
}

BENCHMARK_CAPTURE(recordingFile, pile16, "ragdolls")
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(recordingFile, bullet, "bullet-ragdolls")
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
