#include "exact_ghost.h"

#include "accuracy.h"  // lab_core's referenceSettings: the same reference the lab measures with

namespace sandbox {
namespace {

bool hasPositionAnswers(const scenes::Scene& scene) {
  for (const scenes::Expectation& e : scene.expectations) {
    const std::string* kind = e.find("kind");
    if (kind != nullptr && *kind == "position") return true;
  }
  return false;
}

}  // namespace

void ExactGhost::reset(const scenes::Scene& scene) {
  clear();
  const phys::World& w = scene.world;
  if (!hasPositionAnswers(scene) || w.particles().size() + w.rigidBodies().size() > kMaxGhostBodies) return;
  start_.emplace(w);
  start_->clearDrag();
  start_->setSolverSettings(lab::referenceSettings(w, w.solverSettings().dt));
}

void ExactGhost::clear() {
  start_.reset();
  now_.reset();
}

const phys::World* ExactGhost::at(double time, double dt) {
  if (!start_) return nullptr;
  if (!now_ || now_->time() > time + dt / 2) now_ = start_;
  if (now_->solverSettings().dt != dt) now_->setSolverSettings(lab::referenceSettings(*now_, dt));
  // To the step nearest `time`: a dt changed on the way leaves the two clocks a part of a step apart.
  while (now_->time() + dt / 2 < time) now_->step();
  return &*now_;
}

}  // namespace sandbox
