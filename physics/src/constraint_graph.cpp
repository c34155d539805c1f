// The sticks and links and their layouts (physics/constraint_graph.h).
#include "physics/constraint_graph.h"

#include <algorithm>

#include "passes.h"

namespace phys {

void ConstraintGraph::addParticle() {
  jacobiDelta_.emplace_back(0.0);
  degree_.push_back(0.0);
}

void ConstraintGraph::addStick(const Stick& stick) {
  sticks_.push_back(stick);
  stale_ = true;
  lambda_.push_back(0.0);
  degree_[stick.a] += 1.0;
  degree_[stick.b] += 1.0;
}

void ConstraintGraph::addLink(const Link& link, Real violation) {
  links_.push_back(link);
  stale_ = true;
  linkSlack_.push_back(violation);
  if (violation != 0.0) ++linksApart_;
}

void ConstraintGraph::addJointFriction(const JointFriction& friction) {
  jointFrictions_.push_back(friction);
  // The pass reads and writes the spins of the bodies it joins alone.
  const std::size_t room = std::size_t{std::max(friction.a, friction.b)} + 1;
  if (spins_.size() < room) spins_.resize(room);
}

void ConstraintGraph::setBodyDrive(const DrivenBody& driven) {
  for (DrivenBody& d : bodyDrives_) {
    if (d.body == driven.body) {
      d.drive = driven.drive;
      return;
    }
  }
  bodyDrives_.push_back(driven);
  bodyDriveLambda_.resize(2 * bodyDrives_.size(), 0.0);
}

void ConstraintGraph::clearBodyDrive(BodyId body) {
  const auto gone = std::remove_if(bodyDrives_.begin(), bodyDrives_.end(),
                                   [body](const DrivenBody& d) { return d.body == body; });
  if (gone == bodyDrives_.end()) return;
  bodyDrives_.erase(gone, bodyDrives_.end());
  bodyDriveLambda_.resize(2 * bodyDrives_.size());
}

void ConstraintGraph::dampJointFriction(Particles& particles, std::span<const Body> bodies, Real dt) {
  detail::dampJointFriction(particles, bodies, jointFrictions_, dt, spins_);
}

void ConstraintGraph::layOut(std::span<const Body> bodies, std::size_t particleCount) {
  stickLayout_.build(sticks_, bodies, particleCount);
  linkLayout_.build(links_, particleCount);
  stale_ = false;
}

void ConstraintGraph::markStill(std::span<const Real> inverseMass) {
  stickLayout_.markStill(inverseMass);
  linkLayout_.markStill(inverseMass);
}

void ConstraintGraph::clearStill() {
  stickLayout_.clearStill();
  linkLayout_.clearStill();
}

void ConstraintGraph::relaxSticks(Particles& particles, SolverMethod method, bool firstPass, Real h,
                                  Real compliance, const Workers* workers) {
  switch (method) {
    case SolverMethod::GaussSeidel:
      detail::relaxGaussSeidel(particles, sticks_, stickLayout_, workers);
      break;
    case SolverMethod::Jacobi:
      detail::relaxJacobi(particles, sticks_, stickLayout_, degree_, jacobiDelta_);
      break;
    case SolverMethod::Xpbd:
      // The multipliers accumulate over the substep's passes (Macklin et al. 2016).
      if (firstPass) std::fill(lambda_.begin(), lambda_.end(), 0.0);
      detail::relaxXpbd(particles, sticks_, stickLayout_, lambda_, h, compliance, workers);
      break;
    case SolverMethod::Shake:
      detail::relaxShake(particles, sticks_, stickLayout_);
      break;
  }
}

std::span<const Real> ConstraintGraph::shrinkLinkSlack(const Particles& particles, Real step) {
  if (linksApart_ == 0) return {};
  linksApart_ = detail::shrinkLinkSlack(particles, links_, step, linkSlack_);
  return linkSlack_;
}

std::span<const Real> ConstraintGraph::linkSlack() const {
  return linksApart_ > 0 ? std::span<const Real>(linkSlack_) : std::span<const Real>();
}

void ConstraintGraph::solveLinks(Particles& particles, std::span<const Real> slack,
                                 const Workers* workers) const {
  detail::solveLinks(particles, links_, linkLayout_, slack, workers);
}

}  // namespace phys
