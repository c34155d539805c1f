#include "recording.h"

#include <algorithm>
#include <cmath>

#include <malloc.h>

namespace sandbox {
namespace {

// Bytes the heap has handed out: glibc's blocks in use in its arenas, and the big ones it maps
// on their own (128 KiB and up at first: a big world's arrays).
std::size_t heapInUse() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

}  // namespace

// Made on the window's thread. The Lab section's sweep may allocate meanwhile, which makes the
// figure a little off, never unsafe; a recording being saved allocates much more (setHeapShared).
std::pair<std::shared_ptr<const phys::World>, std::size_t> keptCopy(const phys::World& world) {
  const std::size_t before = heapInUse();
  auto copy = std::make_shared<const phys::World>(world);
  const std::size_t after = heapInUse();
  return {std::move(copy), std::max(after > before ? after - before : 0, sizeof(phys::World))};
}

StepRecord recordOf(const phys::World& world) {
  StepRecord r;
  r.step = world.stepCount();
  r.hash = world.stateHash();
  if (world.drag()) r.dragTarget = world.drag()->target;
  return r;
}

void Recording::clear() {
  keyframes_.clear();
  steps_.clear();
  changes_.clear();
  bytes_ = 0;
}

void Recording::restart(const phys::World& world) {
  clear();
  keyframe(world);
}

long Recording::first() const {
  return keyframes_.empty() ? 0 : keyframes_.front().step;
}

long Recording::last() const {
  if (keyframes_.empty()) return 0;
  return std::max(keyframes_.back().step, steps_.empty() ? 0 : steps_.back().step);
}

double Recording::seconds() const {
  if (keyframes_.empty()) return 0.0;
  // From the keyframes' clocks, so that a dt changed on the way counts as it was; the steps after
  // the last keyframe at the dt they were taken with.
  auto timeOf = [](const Keyframe& k) { return k.motion ? k.motion->time : k.world->time(); };
  return timeOf(keyframes_.back()) - timeOf(keyframes_.front()) +
         static_cast<double>(last() - keyframes_.back().step) * dt_;
}

void Recording::setStepCost(double milliseconds) {
  const double steps = milliseconds > 0.0 ? 50.0 / milliseconds : 120.0;
  interval_ = std::clamp(std::lround(steps), 1L, 120L);
}

void Recording::setBudget(std::size_t bytes) {
  budget_ = bytes;
  keepWithinBudget();
}

void Recording::dropAfter(long step) {
  while (!steps_.empty() && steps_.back().step > step) {
    steps_.pop_back();
    bytes_ -= sizeof(StepRecord);
  }
  dropChangesFrom(step + 1);
  while (keyframes_.size() > 1 && keyframes_.back().step > step) {
    bytes_ -= keyframes_.back().bytes;
    keyframes_.pop_back();
  }
}

void Recording::stepped(const StepRecord& record) {
  if (keyframes_.empty()) return;
  if (record.step - 1 < last()) dropAfter(record.step - 1);  // resumed from an earlier step: a fork
  if (record.step - 1 != last() || record.step <= first()) {
    // Not the next step of anything kept (a world replaced without a keyframe): there is nothing
    // to rebuild it from, so the recording starts again at the next keyframeIfDue.
    clear();
    return;
  }
  steps_.push_back(record);
  bytes_ += sizeof(StepRecord);
}

void Recording::keyframe(const phys::World& world) {
  const long step = world.stepCount();
  // Before everything kept (the budget dropped the keyframes up to a world rewound earlier):
  // nothing kept follows from it.
  if (!keyframes_.empty() && step < first()) clear();
  if (!keyframes_.empty() && step < last()) dropAfter(step);  // a command on a rewound world: a fork
  auto [copy, bytes] = keptCopy(world);
  if (heapShared_ && !keyframes_.empty() && !keyframes_.back().motion &&
      keyframes_.back().world->particles().size() == world.particles().size() &&
      keyframes_.back().world->bodies().size() == world.bodies().size()) {
    bytes = keyframes_.back().bytes;
  }
  // The copy holds the changes made at this step.
  dropChangesFrom(step);
  if (!keyframes_.empty() && keyframes_.back().step == step) {  // a second command in one step
    bytes_ -= keyframes_.back().bytes;
    keyframes_.back() = {step, std::move(copy), nullptr, bytes, 0};
  } else {
    keyframes_.push_back({step, std::move(copy), nullptr, bytes, 0});
  }
  bytes_ += bytes;
  // The state this step is shown as is the one after the command.
  if (!steps_.empty() && steps_.back().step == step) steps_.back() = recordOf(world);
  dt_ = world.solverSettings().dt;
  keepWithinBudget();
}

void Recording::changed(const phys::World& world, std::function<void(phys::World&)> redo, std::size_t bytes) {
  const long step = world.stepCount();
  int atThisStep = 0;  // the changes at this step, the last ones kept
  for (auto c = changes_.rbegin(); c != changes_.rend() && c->step == step; ++c) ++atThisStep;
  if (keyframes_.empty() || step != last() || keyframes_.back().step == step || steps_.empty() ||
      steps_.back().step != step || atThisStep >= kMaxChangesPerStep || world.solverSettings().dt != dt_) {
    keyframe(world);
    return;
  }
  bytes += sizeof(Change) + sizeof(std::function<void(phys::World&)>);
  changes_.push_back(
      {step, std::make_shared<const std::function<void(phys::World&)>>(std::move(redo)), bytes});
  bytes_ += bytes;
  steps_.back() = recordOf(world);  // the state this step is shown as is the one after the command
  keepWithinBudget();
}

void Recording::dropChangesFrom(long step) {
  while (!changes_.empty() && changes_.back().step >= step) {
    bytes_ -= changes_.back().bytes;
    changes_.pop_back();
  }
}

void Recording::appendMotion(std::shared_ptr<const phys::World> base, std::size_t baseBytes,
                             phys::Motion motion, const StepRecord& record) {
  if (!keyframes_.empty() && record.step != last() + 1) clear();  // not the next step: start again
  std::size_t bytes = baseBytes + sizeof(phys::Motion);
  for (const auto* v : {&motion.position, &motion.previous, &motion.rigidPosition, &motion.rigidVelocity,
                        &motion.rigidAngularVelocity}) {
    bytes += v->capacity() * sizeof(phys::Vec3);
  }
  bytes += motion.rigidOrientation.capacity() * sizeof(phys::Quat);
  bytes += motion.characters.capacity() * sizeof(phys::CharacterMotion);
  for (const phys::CharacterMotion& c : motion.characters) {
    bytes += c.partStrength.capacity() * sizeof(phys::Real) +
             (c.pose.turns.capacity() + c.held.turns.capacity()) * sizeof(phys::Quat);
  }
  if (!keyframes_.empty()) {
    steps_.push_back(record);
    bytes_ += sizeof(StepRecord);
  }
  dt_ = base->solverSettings().dt;
  keyframes_.push_back({record.step, std::move(base), std::make_shared<const phys::Motion>(std::move(motion)),
                        bytes, baseBytes});
  bytes_ += bytes;
  keepWithinBudget();
}

void Recording::keyframeIfDue(const phys::World& world) {
  if (keyframes_.empty() || world.stepCount() - keyframes_.back().step >= interval_) keyframe(world);
}

void Recording::keepWithinBudget() {
  while (bytes_ > budget_ && keyframes_.size() > 1) {
    Keyframe& next = keyframes_[1];
    if (keyframes_.front().motion && next.motion && next.world == keyframes_.front().world) {
      // The base world of a file's part stays while any step of it does: the next one carries it.
      next.bytes += keyframes_.front().baseBytes;
      next.baseBytes += keyframes_.front().baseBytes;
      bytes_ -= keyframes_.front().bytes - keyframes_.front().baseBytes;
    } else {
      bytes_ -= keyframes_.front().bytes;
    }
    keyframes_.pop_front();
    const long start = keyframes_.front().step;
    while (!steps_.empty() && steps_.front().step <= start) {
      steps_.pop_front();
      bytes_ -= sizeof(StepRecord);
    }
    while (!changes_.empty() && changes_.front().step <= start) {
      bytes_ -= changes_.front().bytes;
      changes_.pop_front();
    }
  }
}

std::unique_ptr<phys::World> Recording::build(const Keyframe& k) {
  auto world = std::make_unique<phys::World>(*k.world);
  if (k.motion) world->setMotion(*k.motion);
  return world;
}

void Recording::stepAgain(phys::World& world, const StepRecord& record) const {
  if (record.dragTarget && world.drag()) world.setDragTarget(*record.dragTarget);
  world.step();
  auto c = std::lower_bound(changes_.begin(), changes_.end(), record.step,
                            [](const Change& change, long s) { return change.step < s; });
  for (; c != changes_.end() && c->step == record.step; ++c) (*c->redo)(world);
}

std::unique_ptr<phys::World> Recording::worldAt(long step, std::string& divergence,
                                                const phys::World* shown) const {
  divergence.clear();
  // The last keyframe at or before the step.
  auto k = std::upper_bound(keyframes_.begin(), keyframes_.end(), step,
                            [](long s, const Keyframe& f) { return s < f.step; });
  --k;
  auto recordOfStep = [this](long s) {
    return std::lower_bound(steps_.begin(), steps_.end(), s,
                            [](const StepRecord& r, long n) { return r.step < n; });
  };
  // A world shown as recorded has no drag (Session lets it go), so it steps as recorded only
  // where no drag was; and it must be the recorded state (its hash), or it is not used.
  bool fromShown = shown != nullptr && shown->stepCount() >= k->step && shown->stepCount() < step;
  if (fromShown) {
    const auto own = recordOfStep(shown->stepCount());
    fromShown = own != steps_.end() && own->step == shown->stepCount() && own->hash == shown->stateHash();
  }
  for (auto r = recordOfStep(shown != nullptr ? shown->stepCount() + 1 : 0);
       fromShown && r != steps_.end() && r->step <= step; ++r)
    fromShown = !r->dragTarget;
  std::unique_ptr<phys::World> world = fromShown ? std::make_unique<phys::World>(*shown) : build(*k);
  const long from = world->stepCount();
  auto record = recordOfStep(from + 1);
  for (long s = from + 1; s <= step; ++s, ++record) {
    if (record == steps_.end() || record->step != s) {
      divergence = "no record of step " + std::to_string(s);
      break;
    }
    stepAgain(*world, *record);
    if (world->stateHash() != record->hash && divergence.empty()) {
      divergence = "step " + std::to_string(s) + " rebuilt from step " + std::to_string(from) +
                   " differs from the recorded one";
    }
  }
  if (fromShown && !divergence.empty()) return worldAt(step, divergence);  // the keyframe, then
  return world;
}

bool Recording::replay(const std::function<void(const phys::World&, const StepRecord&)>& visit,
                       std::string& divergence) const {
  divergence.clear();
  auto record = steps_.begin();
  for (std::size_t k = 0; k < keyframes_.size(); ++k) {
    const long from = keyframes_[k].step;
    const long to =
        k + 1 < keyframes_.size() ? keyframes_[k + 1].step : last() + 1;  // the next keyframe's is its own
    std::unique_ptr<phys::World> world = build(keyframes_[k]);
    while (record != steps_.end() && record->step < from) ++record;
    visit(*world, record != steps_.end() && record->step == from ? *record : recordOf(*world));
    for (long s = from + 1; s < to; ++s) {
      while (record != steps_.end() && record->step < s) ++record;
      if (record == steps_.end() || record->step != s) {
        divergence = "no record of step " + std::to_string(s);
        return false;
      }
      stepAgain(*world, *record);
      if (world->stateHash() != record->hash) {
        divergence = "step " + std::to_string(s) + " rebuilt from the keyframe at step " +
                     std::to_string(from) + " differs from the recorded one";
        return false;
      }
      visit(*world, *record);
    }
  }
  return true;
}

}  // namespace sandbox
