#include "runner.h"

#include <chrono>

#include "bodies.h"

namespace lab {
namespace {

class WorldStepper final : public Stepper {
 public:
  explicit WorldStepper(phys::World& world) : world_(world) {}
  void step() override { world_.step(); }
  std::vector<phys::Vec3> positions() const override { return bodyPositions(world_); }
  std::vector<phys::Quat> orientations() const override { return bodyOrientations(world_); }
  const phys::World* world() const override { return &world_; }

 private:
  phys::World& world_;
};

thread_local const std::atomic<bool>* tStopFlag = nullptr;

void throwIfStopped() {
  if (tStopFlag != nullptr && tStopFlag->load(std::memory_order_relaxed)) throw RunStopped();
}

}  // namespace

StopOnFlag::StopOnFlag(const std::atomic<bool>& flag) : outer_(tStopFlag) {
  tStopFlag = &flag;
}

StopOnFlag::~StopOnFlag() {
  tStopFlag = outer_;
}

RunRecord runSteps(Stepper& stepper, const RunSpec& spec) {
  using Clock = std::chrono::steady_clock;
  const phys::World* world = stepper.world();
  RunRecord r;
  if (world != nullptr) r.energyBefore = world->metrics().energy();
  const std::size_t steps = spec.steps > 0 ? static_cast<std::size_t>(spec.steps) : 0;
  if (spec.profile) r.profileTotals.reserve(steps);
  r.positions.reserve(spec.checkpoints.size());
  if (spec.orientations) r.orientations.reserve(spec.checkpoints.size());
  // A bare loop is timed whole; one that records between the steps times each step alone.
  const bool between = spec.maxima || spec.profile || !spec.checkpoints.empty() ||
                       static_cast<bool>(spec.afterStep) || world == nullptr;
  Clock::duration stepping{};
  if (!between) {
    const Clock::time_point start = Clock::now();
    for (int i = 0; i < spec.steps; ++i) {
      stepper.step();
      throwIfStopped();
    }
    stepping = Clock::now() - start;
    r.stepsRun = spec.steps;
  }
  std::size_t next = 0;  // the next checkpoint
  for (int i = 1; between && i <= spec.steps; ++i) {
    const Clock::time_point start = Clock::now();
    stepper.step();
    const Clock::duration took = Clock::now() - start;
    throwIfStopped();
    stepping += took;
    r.stepsRun = i;
    stepper.afterStep(i);
    if (world != nullptr && spec.profile) {
      r.profileTotals.push_back(world->profile().total);
      r.stageSums += world->profile();
    }
    if (world != nullptr && spec.maxima) r.maxima.observe(*world);
    while (next < spec.checkpoints.size() && spec.checkpoints[next] == i) {
      r.positions.push_back(stepper.positions());
      if (spec.orientations) r.orientations.push_back(stepper.orientations());
      ++next;
    }
    if (spec.afterStep && !spec.afterStep(i)) break;
  }
  r.steppingMs = std::chrono::duration<double, std::milli>(stepping).count();
  if (world != nullptr) r.energyAfter = world->metrics().energy();
  return r;
}

RunRecord runSteps(phys::World& world, const RunSpec& spec) {
  WorldStepper stepper(world);
  return runSteps(stepper, spec);
}

}  // namespace lab
