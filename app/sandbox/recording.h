#pragma once
// Rewind and replay (docs/sandbox.md, "Rewind"): the main run's history, kept so that any recorded
// step can be shown again exactly and the run resumed from it. A full copy of the world (a
// keyframe) every few steps and after every command that changed it (or, for a command that only
// sets values, as a slider does, the command itself), and for each step its state hash and the
// drag's target. A step between keyframes is rebuilt from the keyframe before it,
// stepped again with the same drag targets: the step is deterministic, so the rebuilt world is
// the recorded one bit for bit, which the hashes check step by step. Keyframes are what costs
// memory; the oldest go first when the recording is over its budget. A recording opened from a
// file (recording_file.h) keeps every step as a motion instead, put back in a world built for it.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "physics/world.h"

namespace sandbox {

/// One step of the main run as the recording keeps it.
struct StepRecord {
  long step = 0;                         ///< World::stepCount() after it
  std::uint64_t hash = 0;                ///< World::stateHash() after it
  std::optional<phys::Vec3> dragTarget;  ///< the drag's target it was taken with, if any
};

/// The record of a step just taken by `world`.
StepRecord recordOf(const phys::World& world);

/// A copy of `world` to keep, and the heap it took (unit: bytes): its arrays, whatever their
/// capacity, measured by glibc's count of the heap in use.
std::pair<std::shared_ptr<const phys::World>, std::size_t> keptCopy(const phys::World& world);

/// Default memory budget of a recording (unit: bytes): 10 s of Bullet's 136-ragdoll pile fit.
inline constexpr std::size_t kDefaultRecordingBudget = std::size_t{512} << 20;

class Recording {
 public:
  /// Forgets everything and starts from `world` as it is now.
  void restart(const phys::World& world);
  void clear();
  bool empty() const { return keyframes_.empty(); }

  /// Appends a step of the main run. A step that does not follow the last one recorded (a
  /// run resumed from an earlier step) first drops everything after its predecessor: the run
  /// forks there.
  void stepped(const StepRecord& record);
  /// Keeps a copy of `world` as it is now, after a command changed it (its step's record is
  /// then this state's); keyframeIfDue, when the last keyframe is the interval's steps back, or
  /// none is kept.
  void keyframe(const phys::World& world);
  void keyframeIfDue(const phys::World& world);
  /// After a command that changed `world` by `redo` alone: kept as the change, applied again to the
  /// world rebuilt at this step, instead of a copy of the world (a slider dragged while the world
  /// runs changes it every frame, and a copy a frame filled the budget in seconds). `redo` must be
  /// deterministic and hold its values by copy; `bytes` is what it holds besides itself. A copy
  /// as keyframe() all the same where the change cannot be replayed from the steps kept: a world
  /// not at the last step kept (a fork), one changed at the step of a keyframe (which the copy
  /// replaces) or already changed kMaxChangesPerStep times there (a slider dragged while paused), or
  /// a new dt (seconds() counts each keyframe's).
  void changed(const phys::World& world, std::function<void(phys::World&)> redo, std::size_t bytes);
  static constexpr int kMaxChangesPerStep = 4;
  /// Appends a step kept as its motion (a recording file's): shown as `base` put in it
  /// (World::setMotion), `base` being a world that has not stepped, of the structure and settings
  /// the motion was recorded with, shared by the steps of a file's part; `baseBytes` is its memory
  /// when this step is the first to hold it, else 0. The step must follow the last one kept, or
  /// the recording be empty.
  void appendMotion(std::shared_ptr<const phys::World> base, std::size_t baseBytes, phys::Motion motion,
                    const StepRecord& record);
  /// Steps between keyframes, from how long a step takes: rebuilding a step costs at most this
  /// many steps, about 50 ms of them, within 1 to 120 (a step slower than 50 ms is kept whole).
  void setStepCost(double milliseconds);

  long first() const;  ///< the earliest step that can be shown
  long last() const;   ///< the latest
  bool covers(long step) const { return !empty() && step >= first() && step <= last(); }

  /// The world as it was at `step` (covers(step) must hold), rebuilt from the keyframe before
  /// it, or from `shown` when that is a recorded step between the keyframe and `step` with no
  /// drag on the way (playing the recording forward then costs a step a step). `divergence` gets
  /// "" or which step's hash did not match (which would be a bug: the step is deterministic).
  std::unique_ptr<phys::World> worldAt(long step, std::string& divergence,
                                       const phys::World* shown = nullptr) const;
  /// Visits the world at every step kept, first() to last(), with its record, rebuilding each
  /// once (a recording file is written from these). Stops at a step whose rebuilt hash does not
  /// match the recorded one and returns false with `divergence` saying which.
  bool replay(const std::function<void(const phys::World&, const StepRecord&)>& visit,
              std::string& divergence) const;

  /// Memory the recording holds (unit: bytes): the heap each keyframe's copy took, each step's
  /// record and each change kept; and the budget.
  std::size_t bytes() const { return bytes_; }
  std::size_t budget() const { return budget_; }
  void setBudget(std::size_t bytes);
  /// While another thread allocates (a recording being saved), the heap's growth over a copy is
  /// not the copy's alone: a keyframe then counts what the last one of the same size did.
  void setHeapShared(bool shared) { heapShared_ = shared; }
  /// Simulated seconds recorded.
  double seconds() const;

 private:
  struct Keyframe {
    long step = 0;
    std::shared_ptr<const phys::World> world;  // the world then, or with `motion` the base it is put in
    std::shared_ptr<const phys::Motion> motion;
    std::size_t bytes = 0;
    std::size_t baseBytes = 0;  // of `bytes`, the base world's, counted with this step of its part
  };
  // A command kept as what it did (changed()), applied after step `step` is taken again.
  struct Change {
    long step = 0;
    std::shared_ptr<const std::function<void(phys::World&)>> redo;
    std::size_t bytes = 0;
  };
  static std::unique_ptr<phys::World> build(const Keyframe& k);
  // Step `s` taken again in `world`: the drag's target it had, the step, the changes made after it.
  void stepAgain(phys::World& world, const StepRecord& record) const;
  void dropAfter(long step);
  void dropChangesFrom(long step);  // the changes kept after steps from `step` on
  void keepWithinBudget();

  std::deque<Keyframe> keyframes_;
  std::deque<StepRecord> steps_;  // from the first keyframe's step + 1 to last()
  std::deque<Change> changes_;    // in order, each after a step between keyframes, none at one's
  std::size_t bytes_ = 0;
  std::size_t budget_ = kDefaultRecordingBudget;
  long interval_ = 60;
  double dt_ = 0.0;  // of the latest keyframe, for seconds()
  bool heapShared_ = false;
};

}  // namespace sandbox
