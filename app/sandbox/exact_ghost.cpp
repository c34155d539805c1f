#include "exact_ghost.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "accuracy.h"    // lab_core's referenceSettings: the same reference the lab measures with
#include "stats_text.h"  // figure

namespace sandbox {
namespace {

// The scene's answers as the crosses are drawn. The session opened the scene only once they had
// passed this same check (loadCheckedScene, open_scene.h), so it does not throw here.
std::vector<std::pair<double, glm::vec3>> answersOf(const scenes::Scene& scene) {
  std::vector<std::pair<double, glm::vec3>> out;
  for (const lab::PositionAnswer& a : lab::positionAnswers(scene)) out.emplace_back(a.time, glm::vec3(a.pos));
  return out;
}

// The file's number, or one a slider or a key gave back for it (kSameSetting).
bool same(double a, double b) {
  return std::abs(a - b) <= kSameSetting * std::max(std::abs(a), std::abs(b));
}
bool same(const phys::Vec3& a, const phys::Vec3& b) {
  return glm::length(a - b) <= kSameSetting * std::max(glm::length(a), glm::length(b));
}
bool same(const phys::Material& a, const phys::Material& b) {
  return same(a.staticFriction, b.staticFriction) && same(a.dynamicFriction, b.dynamicFriction);
}

// Gravity as it acts: the vector in uniform mode, the point and the pull in point mode.
bool sameGravity(const phys::WorldSettings& a, const phys::WorldSettings& b) {
  if (a.gravityMode != b.gravityMode) return false;
  if (a.gravityMode == phys::GravityMode::Uniform) return same(a.gravity, b.gravity);
  return same(a.gravityPoint, b.gravityPoint) && same(a.gravityStrength, b.gravityStrength);
}

bool sameGround(const phys::WorldSettings& a, const phys::WorldSettings& b) {
  if (a.ground != b.ground) return false;
  return !a.ground || (same(a.groundNormal, b.groundNormal) && same(a.groundHeight, b.groundHeight));
}

bool sameSleep(const phys::SleepSettings& a, const phys::SleepSettings& b) {
  if (a.enabled != b.enabled) return false;
  return !a.enabled || (same(a.speed, b.speed) && same(a.time, b.time));
}

bool sameProjection(const phys::JointProjectionSettings& a, const phys::JointProjectionSettings& b) {
  if (a.enabled != b.enabled) return false;
  return !a.enabled || (same(a.tolerance, b.tolerance) && a.iterations == b.iterations);
}

bool sameParting(const phys::PartingSettings& a, const phys::PartingSettings& b) {
  return a.plainSweeps == b.plainSweeps && a.overRelaxedSweeps == b.overRelaxedSweeps &&
         same(a.overRelaxation, b.overRelaxation) && same(a.tolerance, b.tolerance) &&
         a.progressSweeps == b.progressSweeps;
}

bool sameReuse(const phys::ManifoldReuseSettings& a, const phys::ManifoldReuseSettings& b) {
  return same(a.maxShift, b.maxShift) && same(a.maxTurn, b.maxTurn);
}

// The settings of w and s that the exact answer depends on and that differ from fw and fs, by
// the panels' names (ExactGhost::settingsChanged).
std::vector<std::string> changedSettings(const phys::WorldSettings& w, const phys::SolverSettings& s,
                                         const phys::WorldSettings& fw, const phys::SolverSettings& fs) {
  std::vector<std::string> changed;
  auto check = [&](bool unchanged, const char* name) {
    if (!unchanged) changed.emplace_back(name);
  };
  // The Simulation panel's, in its order; then the World panel's; then what only a file sets.
  check(same(s.featureEpsilon, fs.featureEpsilon), "feature epsilon");
  check(same(s.restitution, fs.restitution), "restitution");
  check(same(s.compliance, fs.compliance), "compliance");
  check(same(s.bodyDamping, fs.bodyDamping), "body damping");
  check(same(s.maxDepenetrationSpeed, fs.maxDepenetrationSpeed), "depenetration");
  check(sameProjection(s.jointProjection, fs.jointProjection), "joint projection");
  check(sameSleep(s.sleep, fs.sleep), "sleep");
  check(!w.ground || !fw.ground || same(w.groundMaterial, fw.groundMaterial), "ground friction");
  check(sameGravity(w, fw), "gravity");
  check(same(w.damping, fw.damping), "damping");
  check(sameGround(w, fw), "ground");
  check(s.keepSpin == fs.keepSpin, "keep spin");
  check(same(s.contactSlop, fs.contactSlop), "contact slop");
  check(s.broadPhase == fs.broadPhase, "broad phase");
  check(sameParting(s.parting, fs.parting), "parting");
  check(sameReuse(s.manifoldReuse, fs.manifoldReuse), "manifold reuse");
  check(same(w.bound, fw.bound), "world bound");
  check(same(w.shapeCheckInterval, fw.shapeCheckInterval), "shape check interval");
  return changed;
}

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out;
}

}  // namespace

void ExactGhost::reset(const scenes::Scene& scene) {
  clear();
  answers_ = answersOf(scene);
  const phys::World& w = scene.world;
  if (answers_.empty()) return;
  answerFile_ = scene.file.filename().string();
  answerWorldSettings_ = fileWorldSettings_ = w.worldSettings();
  answerSolverSettings_ = fileSolverSettings_ = w.solverSettings();
  for (std::size_t i = 0; i < w.particles().size(); ++i) {
    const phys::ParticleId id(i);
    particles_.push_back({w.particleName(id), w.particles().inverseMass[i], w.particleBodies()[i]});
  }
  for (const phys::Body& b : w.bodies()) bodies_.push_back(b.name);
  if (w.particles().size() + w.rigidBodies().size() > kMaxGhostParticlesAndBodies) return;
  start_.emplace(w);
  start_->clearDrag();
  start_->setSolverSettings(lab::referenceSettings(w, w.solverSettings().dt));
  reached_ = start_->time();
}

void ExactGhost::fileSaved(const phys::World& saved) {
  if (answers_.empty()) return;
  fileWorldSettings_ = saved.worldSettings();
  fileSolverSettings_ = saved.solverSettings();
  savedChanged_ =
      changedSettings(fileWorldSettings_, fileSolverSettings_, answerWorldSettings_, answerSolverSettings_);
}

void ExactGhost::clear() {
  answerFile_.clear();
  answerWorldSettings_ = fileWorldSettings_ = {};
  answerSolverSettings_ = fileSolverSettings_ = {};
  savedChanged_.clear();
  particles_.clear();
  bodies_.clear();
  answers_.clear();
  start_.reset();
  now_.reset();
  snapshots_.clear();
  reached_ = 0.0;
  stepsTaken_ = 0;
}

bool ExactGhost::holds(const phys::World& shown) const {
  if (answers_.empty() || shown.particles().size() < particles_.size() ||
      shown.bodies().size() < bodies_.size())
    return false;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Particle& p = particles_[i];
    const phys::ParticleId id(i);
    if (shown.particles().inverseMass[i] != p.inverseMass || shown.particleBodies()[i] != p.body ||
        shown.particleName(id) != p.name)
      return false;
  }
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (shown.bodies()[b].name != bodies_[b]) return false;
  }
  return true;
}

ExactGhost::Drawn ExactGhost::beside(const phys::World& shown) {
  if (answers_.empty()) return {};
  // Kept at the world's time while hidden too: else a setting set back after a minute costs that
  // frame the minute's steps at 128 substeps (a second of them in pendulum-exact).
  const phys::World* ghost = at(shown.time(), shown.solverSettings().dt, kGhostStepsPerFrame);
  if (!hiddenBecause(shown).empty()) return {};
  return {ghost, answers_};
}

std::string ExactGhost::hiddenBecause(const phys::World& shown) const {
  if (answers_.empty()) return "";
  if (!holds(shown)) return "the scene's bodies are gone";
  // Before the world's own changes: no setting brings back an answer the current file has not.
  if (!savedChanged_.empty()) {
    const std::string whose = answerFile_.empty() ? "the scene's" : answerFile_ + "'s";
    return "saved with " + listed(savedChanged_) + " changed, and the answer (" + whose +
           ") cannot be recomputed for the saved settings";
  }
  const std::vector<std::string> changed = settingsChanged(shown);
  if (!changed.empty()) return listed(changed) + " changed";
  // Drawn short of the world's time, the ghost would show the answer where it is not yet.
  const double ghostTime = now_ ? now_->time() : start_ ? start_->time() : shown.time();
  if (ghostTime + shown.solverSettings().dt / 2 < shown.time()) {
    return "catching up with the run (at " + figure("%.1f", ghostTime) + " of " +
           figure("%.1f", shown.time()) + " s)";
  }
  return "";
}

std::vector<std::string> ExactGhost::settingsChanged(const phys::World& shown) const {
  return changedSettings(shown.worldSettings(), shown.solverSettings(), fileWorldSettings_,
                         fileSolverSettings_);
}

const phys::World* ExactGhost::at(double time, double dt, long newSteps) {
  if (!start_) return nullptr;
  // From the last copy not past `time` where that is nearer than the ghost: back in time, and
  // forward past copies kept on an earlier way there (the timeline dragged back, then on).
  const phys::World* from = &*start_;
  for (const phys::World& s : snapshots_) {
    if (s.time() <= time + dt / 2) from = &s;
  }
  if (!now_ || now_->time() > time + dt / 2 || from->time() > now_->time()) now_ = *from;
  if (now_->solverSettings().dt != dt) now_->setSolverSettings(lab::referenceSettings(*now_, dt));
  // To the step nearest `time`: a dt changed on the way leaves the two clocks a part of a step apart.
  // Steps through time already been to are bounded by the copies' spacing; those into new time
  // are as many as the clock jumped, and are what `newSteps` bounds.
  const double known = reached_;
  long fresh = 0;
  while (now_->time() + dt / 2 < time) {
    if (now_->time() + dt / 2 >= known && fresh++ >= newSteps) break;
    now_->step();
    ++stepsTaken_;
    reached_ = std::max(reached_, now_->time());
    const double last = snapshots_.empty() ? start_->time() : snapshots_.back().time();
    if (now_->time() >= last + kGhostSnapshotEvery) {
      snapshots_.push_back(*now_);
      if (snapshots_.size() > kMaxGhostSnapshots) {
        std::vector<phys::World> thinned;
        for (std::size_t i = 1; i < snapshots_.size(); i += 2) thinned.push_back(std::move(snapshots_[i]));
        snapshots_ = std::move(thinned);
      }
    }
  }
  return &*now_;
}

}  // namespace sandbox
