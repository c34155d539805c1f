#include "run.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "physics/character.h"
#include "root_mean_square.h"
#include "runner.h"

namespace lab {

bool xpbdWhateverTheMethod(const phys::World& world) {
  return world.rigidBodies().size() > 0 && world.sticks().empty();
}

scenes::LoadOptions imposedAtLoad(std::optional<phys::BodyModel> model, bool sleep,
                                  std::optional<bool> jointProjection) {
  scenes::LoadOptions load{.boxModel = model, .sleep = sleep, .jointProjection = jointProjection};
  if (model == phys::BodyModel::Rigid) load.ragdollModel = phys::RagdollModel::Rigid;
  return load;
}

void applyOverrides(phys::World& world, const RunOptions& options) {
  phys::SolverSettings s = world.solverSettings();
  if (options.dt) s.dt = *options.dt;
  if (options.method) s.method = *options.method;
  if (options.iterations) s.iterations = *options.iterations;
  if (options.substeps) s.substeps = *options.substeps;
  if (options.threads) s.threads = *options.threads;
  // One call with everything, so the world judges the combination and not each field alone;
  // it keeps every particle's velocity across a new dt or substep count.
  world.setSolverSettings(s);
}

namespace {

// A line now and then while a long run goes on (a pile at 1000 iterations x 1000 substeps takes
// minutes a step), so that it is not taken for a hang.
class ProgressLine {
 public:
  ProgressLine(std::ostream* out, int steps, const ProgressTiming& timing)
      : out_(out), steps_(steps), every_(timing.every), next_(timing.after) {}

  void after(int done) {
    if (out_ == nullptr) return;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < next_) return;
    next_ = elapsed + every_;
    const double perStep = elapsed / done;
    *out_ << printed("lab: run: step %d of %d, %.3g s a step, about %.0f s left\n", done, steps_, perStep,
                     perStep * (steps_ - done))
          << std::flush;
  }

 private:
  using Clock = std::chrono::steady_clock;
  std::ostream* out_;
  int steps_;
  double every_;  // unit: s
  double next_;   // unit: s since the start; when the next line is due
  Clock::time_point start_ = Clock::now();
};

// Each character part's drive read after every step (World::jointDriveTorque, bodyDriveLoad: the
// last substep's), kept as a root mean square and a peak. Sized before the first step.
class DriveLog {
 public:
  explicit DriveLog(const phys::World& world) {
    for (const phys::Character& c : world.characters()) {
      for (const phys::CharacterBone& bone : c.bones)
        parts_.push_back(
            {{c.ragdoll, c.now.clip->bones[std::size_t(bone.clipBone)], bone.parent < 0}, {}, {}});
    }
  }

  void after(const phys::World& world) {
    auto part = parts_.begin();
    for (const phys::Character& c : world.characters()) {
      for (const phys::CharacterBone& bone : c.bones) {
        Part& p = *part++;
        double torque = 0.0, force = 0.0;
        if (bone.parent < 0) {
          const phys::DriveLoad load = world.bodyDriveLoad(bone.body);
          torque = load.torque;
          force = load.force;
        } else {
          torque = c.particleParts ? world.particleJointDriveTorque(bone.joint)
                                   : world.jointDriveTorque(bone.joint);
        }
        p.torque.add(torque);
        p.force.add(force);
        p.figures.peakTorque = std::max(p.figures.peakTorque, torque);
        p.figures.peakForce = std::max(p.figures.peakForce, force);
      }
    }
  }

  std::vector<DriveFigures> finish() const {
    std::vector<DriveFigures> out;
    out.reserve(parts_.size());
    for (const Part& p : parts_) {
      out.push_back(p.figures);
      out.back().rmsTorque = p.torque.value();
      out.back().rmsForce = p.force.value();
    }
    return out;
  }

 private:
  struct Part {
    DriveFigures figures;  // its peaks as the run goes; its RMS figures at the end
    RootMeanSquare torque, force;
  };
  std::vector<Part> parts_;  // every character's parts, in order
};

// Bodies in the island with the most: how evenly islands could be shared between threads
// (docs/performance.md, "The guard's look in ranges, and what the pile's second thread waits on").
std::size_t largestIsland(const phys::Islands& islands) {
  // Numbered below islandCount(), loose particles' islands too: a body is never a pinned node.
  std::vector<std::size_t> bodies(islands.islandCount(), 0);
  for (const std::uint32_t island : islands.bodyIsland()) ++bodies[island];
  return bodies.empty() ? 0 : *std::max_element(bodies.begin(), bodies.end());
}

}  // namespace

RunResult runScene(scenes::Scene& scene, const RunOptions& options, std::ostream* progress,
                   const ProgressTiming& timing) {
  phys::World& world = scene.world;
  applyOverrides(world, options);

  RunResult r;
  r.scene = scene.name;
  r.file = scene.file;
  r.solver = world.solverSettings();
  r.steps = options.steps;
  r.particles = world.particles().size();
  r.constraints = world.sticks().size() + world.jointCount();
  r.joints = world.jointCount();
  r.bodies = world.bodies().size();
  r.xpbdAlone = xpbdWhateverTheMethod(world);

  // Every step's total is kept for the median (up to 80 MB at the 10^7 step limit), reserved
  // before the first step by the runner.
  ProgressLine line(progress, options.steps, timing);
  DriveLog drives(world);
  RunRecord run = runSteps(world, {.steps = options.steps,
                                   .maxima = true,
                                   .profile = true,
                                   .afterStep = [&line, &drives, &world](int step) {
                                     drives.after(world);
                                     line.after(step);
                                     return true;
                                   }});

  r.energyInitial = run.energyBefore;
  r.wallMs = run.steppingMs;
  r.msPerStep = options.steps > 0 ? r.wallMs / options.steps : 0.0;
  r.medianStepMs = median(std::move(run.profileTotals));
  r.stageSums = run.stageSums;
  r.worst = run.maxima;
  r.simulatedTime = world.time();
  r.final = world.metrics();
  r.freezes.assign(world.freezes().begin(), world.freezes().end());
  r.hash = world.stateHash();
  r.islands = world.islands().islandCount();
  r.largestIsland = largestIsland(world.islands());
  r.awakeBodies = world.islands().awakeBodies();
  r.sleepingBodies = world.islands().sleepingBodies();
  r.drives = drives.finish();
  return r;
}

}  // namespace lab
