// The sticks and links and their layouts (physics/constraint_graph.h).
#include "physics/constraint_graph.h"

#include <algorithm>

#include "passes.h"
#include "relax_lanes.h"

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
  stale_ = true;  // its pieces are cut again
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

// Each run of frictions reads and writes its own bodies' particles and spins alone, so the runs
// at once give what one loop over them all gives, bit for bit.
void ConstraintGraph::dampJointFriction(Particles& particles, std::span<const Body> bodies, Real dt,
                                        const Workers* workers) {
  const std::span<const JointFriction> all = jointFrictions_;
  if (stale_) {  // frictions were added since the runs were cut
    detail::dampJointFriction(particles, bodies, all, dt, spins_);
    return;
  }
  auto range = [&](std::size_t first, std::size_t last) {
    const std::size_t begin = frictionPieces_[first], end = frictionPieces_[last];
    detail::dampJointFriction(particles, bodies, all.subspan(begin, end - begin), dt, spins_);
  };
  forEachRange(workers, frictionPieces_.size() - 1, 1, range);
}

namespace {

// Joint frictions one thread takes at a time, at least: a few tens of microseconds.
constexpr std::size_t kFrictionsPerPiece = 256;

// Cuts the frictions, in their order, into runs of at least kFrictionsPerPiece that share no body
// with each other: a cut after friction i is allowed when no body of the frictions up to i
// appears after it. Returns the runs' starts and the end.
std::vector<std::size_t> cutFrictions(std::span<const JointFriction> frictions, std::size_t bodies) {
  std::vector<std::size_t> last(bodies, 0);  // per body: the last friction it is in
  for (std::size_t i = 0; i < frictions.size(); ++i) last[frictions[i].a] = last[frictions[i].b] = i;
  std::vector<std::size_t> starts{0};
  std::size_t reach = 0;  // the last friction that a body of the current run is in
  for (std::size_t i = 0; i < frictions.size(); ++i) {
    reach = std::max({reach, last[frictions[i].a], last[frictions[i].b]});
    if (reach == i && i + 1 - starts.back() >= kFrictionsPerPiece && i + 1 < frictions.size())
      starts.push_back(i + 1);
  }
  starts.push_back(frictions.size());
  return starts;
}

}  // namespace

void ConstraintGraph::layOut(std::span<const Body> bodies, std::size_t particleCount) {
  // The particles that links move in the passes, besides the sticks: no chain may have them.
  std::vector<std::uint8_t> held(particleCount, 0);
  auto hold = [&](const Embedding& e) {
    for (int i = 0; i < e.count; ++i) held[e.particle[static_cast<std::size_t>(i)]] = 1;
  };
  for (const Link& link : links_) hold(link.a), hold(link.b);
  for (const RigidLink& link : rigidLinks_) hold(link.a.point), hold(link.b.point);
  stickLayout_.build(sticks_, bodies, particleCount, held);
  std::uint32_t longest = 0;
  for (const StickRun& chain : stickLayout_.chains()) longest = std::max(longest, chain.end - chain.begin);
  chainSaved_.assign(2 * static_cast<std::size_t>(longest), Vec3(0.0));
  laneSpin_.resize(stickLayout_.lanes().size() * detail::kLaneSpinValues);
  linkLayout_.build(links_, particleCount);
  frictionPieces_ = cutFrictions(jointFrictions_, spins_.size());
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
                                  Real compliance, const Workers* workers, bool keepSpin,
                                  const PassesAhead& ahead) {
  detail::SpinPass pass{laneSpin_, firstPass};
  const detail::SpinPass* spin = keepSpin ? &pass : nullptr;
  if (method == SolverMethod::Xpbd && firstPass) {
    // The multipliers accumulate over the substep's passes (Macklin et al. 2016).
    std::fill(lambda_.begin(), lambda_.end(), 0.0);
  }
  if (firstPass) relaxChainsAhead(particles, method, h, compliance, ahead);
  switch (method) {
    case SolverMethod::GaussSeidel:
      detail::relaxGaussSeidel(particles, sticks_, stickLayout_, workers, spin);
      break;
    case SolverMethod::Jacobi:
      detail::relaxJacobi(particles, sticks_, stickLayout_, degree_, jacobiDelta_, workers, spin);
      break;
    case SolverMethod::Xpbd:
      detail::relaxXpbd(particles, sticks_, stickLayout_, lambda_, h, compliance, workers, spin);
      break;
    case SolverMethod::Shake:
      detail::relaxShake(particles, sticks_, stickLayout_, workers);
      break;
  }
}

// Gauss-Seidel's and XPBD's chains run every pass now: the later passes skip them. Jacobi's
// sticks do not depend on each other within a pass, and SHAKE's are left as they are.
void ConstraintGraph::relaxChainsAhead(Particles& particles, SolverMethod method, Real h, Real compliance,
                                       const PassesAhead& ahead) {
  stickLayout_.clearAhead();
  if (stickLayout_.chains().empty() || ahead.passes < 2) return;
  const detail::GroundPlane plane{ahead.groundNormal, ahead.groundHeight};
  const detail::GroundPlane* ground = ahead.ground ? &plane : nullptr;
  if (method == SolverMethod::GaussSeidel) {
    detail::relaxChainsAhead(particles, sticks_, stickLayout_, ahead.passes, ground, chainSaved_);
  } else if (method == SolverMethod::Xpbd) {
    detail::relaxChainsAheadXpbd(particles, sticks_, stickLayout_, ahead.passes, ground, chainSaved_, lambda_,
                                 h, compliance);
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
