#include "exact_ghost.h"

#include "accuracy.h"  // lab_core's referenceSettings: the same reference the lab measures with

namespace sandbox {
namespace {

// The scene's answers as the crosses are drawn. The session opened the scene only once they had
// passed this same check (Session's loadChecked), so it does not throw here.
std::vector<std::pair<double, glm::vec3>> answersOf(const scenes::Scene& scene) {
  std::vector<std::pair<double, glm::vec3>> out;
  for (const lab::PositionAnswer& a : lab::positionAnswers(scene)) out.emplace_back(a.time, glm::vec3(a.pos));
  return out;
}

}  // namespace

void ExactGhost::reset(const scenes::Scene& scene) {
  clear();
  answers_ = answersOf(scene);
  const phys::World& w = scene.world;
  if (answers_.empty()) return;
  for (std::size_t i = 0; i < w.particles().size(); ++i) {
    const phys::ParticleId id(i);
    particles_.push_back({w.particleName(id), w.particles().inverseMass[i], w.particleBodies()[i]});
  }
  for (const phys::Body& b : w.bodies()) bodies_.push_back(b.name);
  if (w.particles().size() + w.rigidBodies().size() > kMaxGhostParticlesAndBodies) return;
  start_.emplace(w);
  start_->clearDrag();
  start_->setSolverSettings(lab::referenceSettings(w, w.solverSettings().dt));
}

void ExactGhost::clear() {
  particles_.clear();
  bodies_.clear();
  answers_.clear();
  start_.reset();
  now_.reset();
  snapshots_.clear();
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
  if (!holds(shown)) return {};
  return {at(shown.time(), shown.solverSettings().dt), answers_};
}

const phys::World* ExactGhost::at(double time, double dt) {
  if (!start_) return nullptr;
  if (!now_ || now_->time() > time + dt / 2) {
    const phys::World* from = &*start_;
    for (const phys::World& s : snapshots_) {
      if (s.time() <= time + dt / 2) from = &s;
    }
    now_ = *from;
  }
  if (now_->solverSettings().dt != dt) now_->setSolverSettings(lab::referenceSettings(*now_, dt));
  // To the step nearest `time`: a dt changed on the way leaves the two clocks a part of a step apart.
  while (now_->time() + dt / 2 < time) {
    now_->step();
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
