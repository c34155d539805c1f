// World::step and its stages (docs/physics.md, "One step"). Each stage is a member that times
// itself into Profile under its Stage, so step() reads as the list of stages and a stage's time
// is never filed under another's name.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "passes.h"
#include "physics/world.h"

namespace phys {
namespace {

// How often the guard looks at the bodies' shapes (World::guardShapes): often enough to time
// kCrushedTime to a twentieth.
constexpr Real kShapeCheckInterval = 0.1;  // s

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Adds the time from its construction to its destruction to one stage of a profile. A clock read
// costs about 20 ns, a tenth of a microsecond per timer: a stage with nothing to do returns before
// it starts one, so a world of two particles does not pay for the stages of a pile.
class StageTimer {
 public:
  StageTimer(Profile& profile, Stage stage) : slot_(profile[stage]), start_(Clock::now()) {}
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer() { slot_ += millisecondsSince(start_); }

 private:
  double& slot_;
  Clock::time_point start_;
};

}  // namespace

void World::step() {
  const auto stepStart = Clock::now();
  profile_ = {};
  updateLayouts();
  std::fill(touched_.begin(), touched_.end(), std::uint8_t{0});
  std::fill(movedByBoxContact_.begin(), movedByBoxContact_.end(), std::uint8_t{0});
  const Real h = substepDt();
  for (int s = 0; s < solver_.substeps; ++s) {
    integrateParticles(h);
    // Contacts between bodies are found once per step, after the first substep's integration,
    // with a speculative margin of how far the two bodies can go in the step, and kept through the
    // substeps: each substep measures them again from their points embedded in the two bodies
    // (Macklin et al. 2019). Found again only when the broad phase runs again.
    fitBodyFrames();
    const bool newPairs = findPairs(s == 0);
    findContacts(newPairs);
    partOverlaps();
    measureApproaches(h);
    const std::span<const Real> linkSlack = limitCorrections(h);
    relax(h, linkSlack);
    restitute(h);
    dampBodies();
    time_ += h;
    guard(s + 1 == solver_.substeps && time_ >= nextShapeCheck_);
  }
  ++steps_;
  profile_.total = millisecondsSince(stepStart);
}

// Rebuilt only after sticks, bodies, links or collision filters were added: the first step of a
// new scene pays for it, and no other step allocates for it.
void World::updateLayouts() {
  if (!layoutsStale_) return;
  stickLayout_.build(sticks_, boxes_, particles_.size());
  linkLayout_.build(links_, particles_.size());
  bodyLayout_.build(boxes_);
  ignoredStart_.assign(boxes_.size() + 1, 0);
  for (const std::uint64_t key : ignoredPairs_) ++ignoredStart_[(key >> 32) + 1];
  for (std::size_t b = 0; b < boxes_.size(); ++b) ignoredStart_[b + 1] += ignoredStart_[b];
  layoutsStale_ = false;
}

void World::integrateParticles(Real h) {
  const StageTimer timer(profile_, Stage::Integrate);
  detail::integrate(particles_, world_, h, checked_);
  // The mouse spring is a force: applied with gravity, before the passes share it out.
  if (drag_) {
    const Box* box = dragBox_ >= 0 ? &boxes_[static_cast<std::size_t>(dragBox_)] : nullptr;
    detail::applyDrag(particles_, box, drag_->point, drag_->target, drag_->stiffness, drag_->damping, h);
  }
}

void World::fitBodyFrames() {
  if (boxes_.size() < 2 && capsuleGround_.empty()) return;
  const StageTimer timer(profile_, Stage::Frames);
  updateBoxFrames();
}

// Once per step; again when a drag, an impact or a joint took a box past its bounds. True when it
// found the pairs.
bool World::findPairs(bool firstSubstep) {
  if (boxes_.size() < 2) return false;
  const StageTimer timer(profile_, Stage::BroadPhase);
  if (!(firstSubstep || pairsStale_ || drag_ || outgrewPairBounds())) return false;
  findBoxPairs();
  return true;
}

void World::findContacts(bool newPairs) {
  if (boxes_.size() < 2 && !world_.ground) return;
  const StageTimer timer(profile_, Stage::NarrowPhase);
  if (boxes_.size() >= 2) {
    if (newPairs)
      buildBoxContacts();
    else
      refreshBoxContacts();
    measureBoxContactStarts();
  }
  if (!world_.ground) return;
  placeCapsuleGroundPoints();
  // Each contact's overlap at x*, where the substep starts: what the parting measures, and
  // what the depenetration limit is reckoned from (buildBoxContacts fills the box-box ones).
  detail::measureGroundStartDepth(particles_, contactPoints_, world_.groundNormal, world_.groundHeight,
                                  groundAllowance_);
}

void World::partOverlaps() {
  if (boxes_.empty()) return;
  const StageTimer timer(profile_, Stage::Parting);
  partWithoutVelocity();
}

// Restitution needs each contact's approach speed before the passes stop it, and which ground
// contacts the passes push (groundHit_, set by the friction pass, read by restitute() alone).
void World::measureApproaches(Real h) {
  if (solver_.restitution <= 0.0) return;
  const StageTimer timer(profile_, Stage::Restitution);
  std::fill(groundHit_.begin(), groundHit_.end(), std::uint8_t{0});
  detail::measureBodyApproach(particles_, bodyContacts_, h, bodyApproach_);
  if (world_.ground) {
    detail::measureGroundApproach(particles_, contactPoints_, world_.groundNormal, h, groundApproach_);
  }
}

// How much of each contact's overlap may go in this substep: all of what this substep's motion
// brought, and of what was there at its start (x*), at most maxDepenetrationSpeed * h. Projected
// in full, an overlap d left at the start becomes a speed d / h: 9.6 m/s for 1 cm at 16 substeps.
// The same for links created outside their bounds: such a link, a pin whose points were placed
// 1.5 m apart say, closes at most that fast, or its gap g would become a speed g / h. Links the
// motion has opened are closed in full, as the projection does. Returns the links' slack, empty
// when every link is within its bounds.
std::span<const Real> World::limitCorrections(Real h) {
  const Real depenetration = solver_.maxDepenetrationSpeed * h;
  if (!bodyAllowance_.empty() || world_.ground) {
    const StageTimer timer(profile_, Stage::Contacts);
    detail::toAllowance(bodyAllowance_, depenetration);
    if (world_.ground) detail::toAllowance(groundAllowance_, depenetration);
  }
  if (linksApart_ == 0) return {};
  const StageTimer timer(profile_, Stage::Links);
  linksApart_ = detail::shrinkLinkSlack(particles_, links_, depenetration, linkSlack_);
  return linkSlack_;
}

void World::relax(Real h, std::span<const Real> linkSlack) {
  const bool ground = world_.ground;
  const bool contacts = ground || !bodyContacts_.empty();
  for (int it = 0; it < solver_.iterations; ++it) {
    if (!sticks_.empty()) {
      const StageTimer timer(profile_, Stage::Sticks);
      switch (solver_.method) {
        case SolverMethod::GaussSeidel:
          detail::relaxGaussSeidel(particles_, sticks_, stickLayout_);
          break;
        case SolverMethod::Jacobi:
          detail::relaxJacobi(particles_, sticks_, stickLayout_, degree_, jacobiDelta_);
          break;
        case SolverMethod::Xpbd:
          // The multipliers accumulate over the substep's passes (Macklin et al. 2016).
          if (it == 0) std::fill(lambda_.begin(), lambda_.end(), 0.0);
          detail::relaxXpbd(particles_, sticks_, stickLayout_, lambda_, h, solver_.compliance);
          break;
        case SolverMethod::Shake:
          detail::relaxShake(particles_, sticks_, stickLayout_);
          break;
      }
    }
    // Joints after the boxes' own sticks, so each pass ends its constraints with the links
    // between bodies, then the contacts. Links are rigid projections in every method, so the
    // world's compliance, which XPBD adds to the sticks, does not soften them.
    if (!links_.empty()) {
      const StageTimer timer(profile_, Stage::Links);
      detail::solveLinks(particles_, links_, linkLayout_, linkSlack);
    }

    // Contacts, each pass followed by its friction, so the next pass's sticks relax what
    // friction bent (run once after all passes, friction would leave every resting box
    // sheared by the last correction).
    if (!contacts) continue;
    {
      const StageTimer timer(profile_, Stage::Contacts);
      detail::solveBodyContacts(particles_, bodyContacts_, solver_.contactSlop, bodyPush_, movedByBoxContact_,
                                bodyAllowance_);
      if (ground) {
        detail::collideGround(particles_, contactPoints_, world_.groundNormal, world_.groundHeight,
                              normalPush_, groundAllowance_);
      }
    }
    const StageTimer timer(profile_, Stage::Friction);
    detail::applyBodyFriction(particles_, bodyContacts_, bodyPush_);
    for (std::size_t k = 0; k < bodyPush_.size(); ++k) {
      if (bodyPush_[k] > 0.0) bodyTouched_[k] = 1;
    }
    if (ground) {
      detail::applyGroundFriction(particles_, contactPoints_, world_.groundNormal, normalPush_);
      for (std::size_t c = 0; c < touched_.size(); ++c) {
        if (normalPush_[c] > 0.0) touched_[c] = groundHit_[c] = 1;
      }
    }
  }
}

// Restitution, after the position passes: each contact pushed in this substep that approached
// faster than the threshold leaves at e times that speed; the slower ones only stop closing. A
// velocity pass on the boxes as rigid bodies (restitution.cpp): only x* moves, so the passes'
// positions stay. Gauss-Seidel, `iterations` times, because contacts share bodies: a box landing
// on a box that rests on the ground must get its bounce back from the ground through the box below.
// Impacts under 2 |g| h are the speed a resting contact gains in one substep, and never bounce
// (Müller et al. 2020's threshold), so coarse steps and strong gravity do not make boxes hop.
void World::restitute(Real h) {
  if (solver_.restitution <= 0.0) return;
  const StageTimer timer(profile_, Stage::Restitution);
  const Real g = gravityMagnitude();
  const detail::Restitution r{solver_.restitution, std::max(kRestitutionMinSpeed, 2.0 * g * h), h};
  detail::measureRigidStates(particles_, boxes_, h, rigid_);
  for (int it = 0; it < solver_.iterations; ++it) {
    detail::restituteBodyContacts(particles_, rigid_, bodyContacts_, bodyApproach_, bodyTouched_, r);
    if (world_.ground) {
      detail::restituteGround(particles_, rigid_, contactPoints_, world_.groundNormal, groundApproach_,
                              groundHit_, r);
    }
  }
  detail::applyRigidChanges(particles_, boxes_, rigid_, h);
}

void World::dampBodies() {
  if (solver_.bodyDamping <= 0.0 || boxes_.empty()) return;
  const StageTimer timer(profile_, Stage::BodyDamping);
  detail::dampBodyMotion(particles_, boxes_, bodyLayout_, solver_.bodyDamping);
}

// A body is frozen whole, put back as it was at the end of the last substep (integrate() kept
// that in checked_), so all of it from one instant, whichever particle went bad.
void World::guard(bool shapes) {
  const StageTimer timer(profile_, Stage::Guard);
  guardParticles();
  if (shapes) {
    nextShapeCheck_ = time_ + kShapeCheckInterval;
    guardShapes();
  }
}

// Also run after a change of settings has moved particles outside the step (setSolverSettings):
// a particle left non-finite there would otherwise be copied into checked_ by the next
// integration and frozen at NaN (found by the soak test, seed 21: a chain under gravity of 1e244
// m/s^2 given 1000 iterations).
void World::guardParticles() {
  const Real bound = world_.bound;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    const Vec3& x = particles_.position[i];
    const auto id = static_cast<ParticleId>(i);
    if (particles_.inverseMass[i] == 0.0) {
      // Pinned and frozen particles are never written, so this only catches a bug; say so.
      if (!finite(x)) freeze(id, "non-finite position of a pinned particle");
      continue;
    }
    if (!finite(x)) {
      freeze(id, "non-finite position");
    } else if (!finite(particles_.previous[i])) {
      freeze(id, "non-finite velocity");  // x - x*, and so the metrics, must stay finite too
    } else if (std::abs(x.x) > bound || std::abs(x.y) > bound || std::abs(x.z) > bound) {
      char reason[64];
      std::snprintf(reason, sizeof reason, "left the world bound of %g m", bound);
      freeze(id, reason);
    }
  }
}

// Past the limit for a moment is an impact; past it for kCrushedTime, a body that will not come
// back. Looked at every kShapeCheckInterval, not every substep: a crush is a matter of seconds,
// and the sticks' lengths cost a pass over them.
void World::guardShapes() {
  for (std::size_t b = 0; b < boxes_.size(); ++b) {
    const Box& box = boxes_[b];
    if (particles_.inverseMass[box.firstParticle] == 0.0) continue;  // frozen
    Real& since = crushedSince_[b];
    const Real error = worstStickError(box);
    if (!(error > kCrushedStickError)) {
      since = std::numeric_limits<Real>::infinity();
      continue;
    }
    since = std::min(since, time_);
    if (time_ - since < kCrushedTime) continue;
    char reason[96];
    std::snprintf(reason, sizeof reason, "crushed: a stick %.0f%% off its length, past %.0f%% for %g s",
                  100.0 * error, 100.0 * kCrushedStickError, kCrushedTime);
    freeze(box.firstParticle, reason);
  }
}

// The largest |length - rest| / rest (the violated bound, for a range) of the box's own sticks
// that are off by more than kCrushedStickError, or 0 if none is: compared squared, so no square
// root is taken while the box is sound.
Real World::worstStickError(const Box& box) const {
  Real worst = 0.0;
  const auto begin = sticks_.begin() + box.firstStick;
  for (auto s = begin; s != begin + box.stickCount; ++s) {
    const Vec3 d = particles_.position[s->b] - particles_.position[s->a];
    const Real squared = glm::dot(d, d);
    const Real shortest = s->minLength * (1.0 - kCrushedStickError);
    const Real longest = s->maxLength * (1.0 + kCrushedStickError);
    if (squared >= shortest * shortest && squared <= longest * longest) continue;
    const Real length = std::sqrt(squared);
    worst = std::max(worst, length < s->minLength ? (s->minLength - length) / s->minLength
                                                  : (length - s->maxLength) / s->maxLength);
  }
  return worst;
}

void World::freeze(ParticleId bad, const std::string& reason) {
  ParticleId first = bad, count = 1;
  std::string name = particleName_[bad].empty() ? "particle " + std::to_string(bad) : particleName_[bad];
  if (const std::int32_t body = particleBody_[bad]; body >= 0) {
    const Box& box = boxes_[static_cast<std::size_t>(body)];
    first = box.firstParticle;
    count = static_cast<ParticleId>(box.particleCount);
    name = box.name.empty() ? "box " + std::to_string(body) : box.name;
  }
  for (ParticleId i = first; i < first + count; ++i) {
    // Where the guard last found the whole body good (or where it was created): finite, and in
    // the bound unless it was created outside it. A frozen particle is never written again.
    particles_.position[i] = particles_.previous[i] = checked_[i];
    particles_.inverseMass[i] = 0.0;
  }
  freezes_.push_back({name, reason, bad, time_});
  if (onFreeze_) onFreeze_(freezes_.back());
}

}  // namespace phys
