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
#include <glm/mat3x3.hpp>

#include "ground_pieces.h"
#include "passes.h"
#include "physics/world.h"
#include "rigid_motion.h"
#include "room.h"
#include "stage_timer.h"

namespace phys {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Flags per ground point (still, far) for the points [begin, end): none when there are none.
std::span<const std::uint8_t> flagsOf(std::span<const std::uint8_t> flags, std::size_t begin,
                                      std::size_t end) {
  return flags.empty() ? flags : flags.subspan(begin, end - begin);
}

// Zeroes each flag but those of the points left still (GroundContacts::markStill), which keep
// what the step would find for them again.
void clearUnlessStill(std::vector<std::uint8_t>& flags, std::span<const std::uint8_t> still) {
  if (still.empty()) {
    std::fill(flags.begin(), flags.end(), std::uint8_t{0});
    return;
  }
  for (std::size_t k = 0; k < flags.size(); ++k) {
    if (still[k] == 0) flags[k] = 0;
  }
}

// Flags each contact the last pass pushed, and each flag it raises in `alsoFlags` (empty for
// none). Over spans, not the state's vectors: a byte's store may alias anything, so through the
// vectors the loop reloaded their bounds at every element, 3% of the stability suite.
// Each flag is written, raised or as it was, without a branch: so written GCC takes the loop in SIMD
// (16 bytes at a time), where the branch on each push stalled as pushes came and went (its
// comparisons were most of World::relax's own 4% of the suite under perf). `flags[k] |= push[k] >
// 0.0` sets the same flags but is not vectorised by GCC 12.
void flagPushed(std::span<const Real> push, std::span<std::uint8_t> flags,
                std::span<std::uint8_t> alsoFlags = {}) {
  constexpr std::uint8_t kRaised = 1;
  for (std::size_t k = 0; k < push.size(); ++k) flags[k] = push[k] > 0.0 ? kRaised : flags[k];
  for (std::size_t k = 0; k < alsoFlags.size(); ++k) alsoFlags[k] = push[k] > 0.0 ? kRaised : alsoFlags[k];
}

}  // namespace

void World::step() {
  stepUnless(nullptr);
}

bool World::step(const std::atomic<bool>& stop) {
  return stepUnless(&stop);
}

bool World::stepUnless(const std::atomic<bool>* stop) {
  const auto stepStart = Clock::now();
  profile_ = {};
  lastProjection_ = {};
  swept_ = 0;
  workers_.prepare();
  if (restWhileAsleep()) {
    profile_.total = millisecondsSince(stepStart);
    return true;
  }
  updateLayouts();
  const std::size_t freezesBefore = guard_.freezes().size();
  skipSleepers();
  clearUnlessStill(ground_.state().touched, ground_.still());
  std::fill(movedByBoxContact_.begin(), movedByBoxContact_.end(), std::uint8_t{0});
  const Real h = substepDt();
  for (int s = 0; s < solver_.substeps; ++s) {
    if (stop != nullptr && stop->load(std::memory_order_relaxed)) {
      guard_.report();
      return false;
    }
    animate(h);
    integrateParticles(h);
    // Contacts between bodies are found once per step, after the first substep's integration,
    // with a speculative margin of how far the two bodies can go in the step, and kept through the
    // substeps: each substep measures them again from their points embedded in the two bodies
    // (Macklin et al. 2019). Found again only when the broad phase runs again.
    fitBodyFrames();
    const bool newPairs = findPairs(s == 0);
    stopFastBodies();
    findContacts(newPairs, s == 0, h);
    if (newPairs) wakeTouched(s == 0, h);
    dealContacts(newPairs);
    partOverlaps();
    measureApproaches(h);
    startRigidContacts(h);
    const std::span<const Real> linkSlack = limitCorrections(h);
    relax(h, linkSlack);
    projectJoints();
    rigidVelocities(h);
    restitute(h);
    dampBodies();
    time_ += h;
    guard(s + 1 == solver_.substeps && guard_.shapesDue(time_));
  }
  react();
  dampJoints();
  updateIslands(freezesBefore);
  ++steps_;
  profile_.total = millisecondsSince(stepStart);
  guard_.report();  // now that the world is whole: the callback may change it
  return true;
}

// A sleeping island's particles get inverse mass 0 for the step (Islands::mask), which every
// stage treats as pinned; the lane groups all of whose particles are then still, and the ground
// points still since the step before, are skipped by the passes (as are sleeping bodies' frames
// and bounds, in their stages), so that a pile asleep beside a few moving bodies costs little more
// than they do.
void World::skipSleepers() {
  if (!islands_.anyAsleep()) {
    constraints_.clearStill();
    bodyLayout_.clearStill();
    ground_.clearStill();
    return;
  }
  const detail::StageTimer timer(stageProfile(), Stage::Islands);
  islands_.mask(particles_, rigidBodies_, bodies_);
  constraints_.markStill(particles_.inverseMass);
  bodyLayout_.markStill(particles_.inverseMass);
  ground_.markStill(particles_.inverseMass);
}

// A sleeping island that one of the manifolds just found joins to an awake body wakes now, before
// the passes, as Box2D v3 wakes what a new contact touches right after its narrow phase: woken at
// the step's end (updateIslands), it would meet the awake body as fixed for the whole step and take
// up its blow (docs/physics.md, "Islands and sleeping"). A woken island gets its masses back and
// what the masks let the step skip is done for it: this substep's integration (the same arithmetic
// integrate() does, so its motion goes on as it slept), its frames, its lane groups and ground
// points, and its pairs, among them the pairs of two of its own bodies, which were not collided
// while both slept. The pairs found again may touch another sleeping island, which wakes in turn.
void World::wakeTouched(bool firstSubstep, Real h) {
  if (!islands_.masked()) return;
  for (std::span<const NodeId> woken = islands_.wakeTouched(narrowPhase_.manifolds()); !woken.empty();
       woken = islands_.wakeTouched(narrowPhase_.manifolds())) {
    {
      const detail::StageTimer timer(stageProfile(), Stage::Islands);
      islands_.unmaskWoken(particles_, rigidBodies_, bodies_);
      for (const NodeId n : woken) {
        const BodyId id = islands_.nodeBody_[n];
        if (id == kNoBody) {
          const ParticleId i = islands_.nodeParticle_[n];
          detail::integrateRange(particles_, world_, h, guard_.checked(), i, i + 1);
          continue;
        }
        const Body& body = bodies_[id];
        detail::integrateRange(particles_, world_, h, guard_.checked(), body.firstParticle,
                               body.firstParticle + body.particleCount);
        if (body.model == BodyModel::Rigid) {
          detail::integrateRigidRange(rigidBodies_, world_, h, guard_.checkedRigidPositions(),
                                      guard_.checkedRigidOrientations(), body.rigid, body.rigid + 1);
        }
        frameAsleep_[id] = 0;
        fitFrame(id);
      }
      constraints_.markStill(particles_.inverseMass);
      bodyLayout_.markStill(particles_.inverseMass);
      ground_.unmarkMoving(particles_.inverseMass);
    }
    findPairs(true);
    findContacts(true, firstSubstep, h, true);
  }
}

// When every island sleeps, a step only passes the time (as the substeps would add it up) and
// plays the characters' clips: nothing moves, but a limp character's clip plays on, so that a
// strength given back later finds the clip where the world's clock says; the drives this aims are
// not solved until a wake.
bool World::restWhileAsleep() {
  if (!islands_.allAsleep() || drag_ || !pushes_.empty() || anyCharacterActive()) return false;
  for (int s = 0; s < solver_.substeps; ++s) {
    animate(substepDt());
    time_ += substepDt();
  }
  ++steps_;
  return true;
}

// The sleeping islands get their masses back, then the islands are found again from this step's
// manifolds, and some wake or fall asleep.
void World::updateIslands(std::size_t freezesBefore) {
  // With sleeping off nothing of the step depends on the islands: islands() counts them if asked.
  if (!solver_.sleep.enabled && !islands_.masked()) {
    islands_.forgetCount();  // the step moved the manifolds the last count was of
    return;
  }
  const detail::StageTimer timer(stageProfile(), Stage::Islands);
  // masked(), not anyAsleep(): an island woken in the step was masked too.
  if (islands_.masked()) {
    islands_.unmask(particles_, rigidBodies_, bodies_);
    // The lanes' still groups were still for the masks alone: a pass run between steps
    // (settleWithoutVelocity) must relax them all.
    constraints_.clearStill();
    bodyLayout_.clearStill();
    // A sleeping body the guard froze in this step (crushed too long) stays frozen: unmask gave
    // back the masses the freeze had taken.
    const std::span<const FreezeReport> freezes = guard_.freezes();
    for (std::size_t k = freezesBefore; k < freezes.size(); ++k) refreeze(freezes[k]);
  }
  // Held awake: the moving characters' roots, a drag's nodes, and the bodies pushed (held_ has
  // room for all three).
  std::size_t held = holdMovingCharacters(held_);
  const HeldNodes drag = heldNodes();
  for (int i = 0; i < drag.count; ++i) held_[held++] = drag.nodes[static_cast<std::size_t>(i)];
  for (const Push& p : pushes_) held_[held++] = islands_.nodeOf(p.body);
  islands_.update({particles_, rigidBodies_, bodies_, narrowPhase_.manifolds(), substepDt(), solver_.dt,
                   solver_.sleep, std::span<const NodeId>(held_.data(), held)});
}

const Islands& World::islands() const {
  // Counted only: a read must not time anyone's rest, wake or put anything to sleep. Counted again
  // after a body, a particle or a join was added, or something woke, since the last count.
  if (!islands_.counted()) islands_.count(narrowPhase_.manifolds());
  return islands_;
}

void World::refreeze(const FreezeReport& freeze) {
  if (freeze.body == kNoBody) {
    particles_.inverseMass[freeze.particle] = 0.0;
    return;
  }
  const Body& body = bodies_[freeze.body];
  for (int j = 0; j < body.particleCount; ++j) particles_.inverseMass[body.firstParticle + j] = 0.0;
  if (body.model != BodyModel::Rigid) return;
  rigidBodies_.inverseMass[body.rigid] = 0.0;
  rigidBodies_.inverseInertia[body.rigid] = Vec3(0.0);
  rigidBodies_.inverseInertiaWorld[body.rigid] = glm::dmat3(0.0);
}

// The nodes a drag holds awake: its rigid body's, or its point's particles'.
World::HeldNodes World::heldNodes() const {
  HeldNodes held;
  if (!drag_) return held;
  if (drag_->body != kNoBody) {
    held.nodes[held.count++] = islands_.nodeOf(drag_->body);
    return held;
  }
  for (int i = 0; i < drag_->point.count; ++i)
    held.nodes[held.count++] = islands_.nodeOf(drag_->point.particle[i]);
  return held;
}

// Rebuilt only after sticks, bodies, links or collision filters were added: the first step of a
// new scene pays for it, and no other step allocates for it.
void World::updateLayouts() {
  if (!layoutsStale_ && !constraints_.stale()) return;
  constraints_.layOut(bodies_, particles_.size());
  bodyLayout_.build(bodies_);
  spinLever_.resize(particles_.size());  // keepSpin: written for the run bodies only
  contactBins_.indexGround(ground_.points());
  broadPhase_.indexFilters();
  layoutsStale_ = false;
}

void World::integrateParticles(Real h) {
  const detail::StageTimer timer(stageProfile(), Stage::Integrate);
  detail::integrate(particles_, world_, h, guard_.checked(), workers());
  detail::integrateRigid(rigidBodies_, world_, h, guard_.checkedRigidPositions(),
                         guard_.checkedRigidOrientations());
  // The mouse spring is a force: applied with gravity, before the passes share it out.
  if (drag_ && drag_->body != kNoBody) {
    detail::applyRigidDrag(rigidBodies_, bodies_[drag_->body].rigid, drag_->local, drag_->target,
                           drag_->stiffness, drag_->damping, h);
  } else if (drag_) {
    const Body* body = dragBody_ != kNoBody ? &bodies_[dragBody_] : nullptr;
    detail::applyDrag(particles_, body, drag_->point, drag_->target, drag_->stiffness, drag_->damping, h);
  }
  if (!pushes_.empty()) applyPushes(h);
}

void World::fitBodyFrames() {
  if (bodies_.size() < 2 && !ground_.hasCapsules()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Frames);
  updateBodyFrames();
}

// Once per step; again when a drag, an impact or a joint took a box past its bounds. True when it
// found the pairs.
bool World::findPairs(bool firstSubstep) {
  if (bodies_.size() < 2) return false;
  const detail::StageTimer timer(stageProfile(), Stage::BroadPhase);
  const std::span<const std::uint8_t> asleep =
      islands_.anyAsleep() ? islands_.bodiesAsleep() : std::span<const std::uint8_t>();
  if (!(firstSubstep || drag_ || broadPhase_.needsUpdate(frames_, asleep, workers()))) return false;
  const BroadPhaseStep step{solver_.dt,         substepDt(),        solver_.featureEpsilon,
                            gravityMagnitude(), solver_.broadPhase, asleep,
                            workers()};
  broadPhase_.update(particles_, rigidBodies_, bodies_, frames_, step);
  const std::size_t pairs = broadPhase_.pairs().size();
  narrowPhase_.reserve(pairs, bodies_.size(), workers_.threads());
  parting_.reserve(pairs, bodies_.size());
  return true;
}

// The contacts between bodies are found when the broad phase found its pairs (`newPairs`), and
// measured again in the step's other substeps; the rigid bodies' ground contacts, in the first
// substep and with new pairs.
// `again`: right after the same substep's, for islands woken since (wakeTouched).
void World::findContacts(bool newPairs, bool firstSubstep, Real h, bool again) {
  if (bodies_.size() < 2 && !world_.ground && rigidGround_.empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::NarrowPhase);
  if (bodies_.size() >= 2) {
    const NarrowPhaseInput in = narrowPhaseInput();
    if (again)
      narrowPhase_.rebuild(in);
    else if (newPairs)
      narrowPhase_.build(in);
    else
      narrowPhase_.refresh(in);
    narrowPhase_.measureStarts(in);
  }
  if (world_.ground) {
    // Resting: moving towards the ground no faster than twice a substep's gravity, Müller et al.
    // 2020's threshold below which a contact does not bounce (World::restitute).
    const Real restingMove = 2.0 * gravityMagnitude() * h * h;
    ground_.placeCapsulePoints(bodies_, frames_, particles_, narrowPhase_.manifolds(),
                               islands_.bodiesJoined(), world_.groundNormal, world_.groundHeight, restingMove,
                               workers());
    ground_.markFreeTetraBoxes(bodies_, particles_, narrowPhase_.manifolds(), islands_.bodiesJoined());
    // Each contact's overlap at x*, where the substep starts: what the parting measures, and
    // what the depenetration limit is reckoned from (the narrow phase measures the box-box ones).
    // Each point's own: pieces of them at once.
    detail::forEachGroundPiece(workers(), ground_.points(), [this](std::size_t b, std::size_t e) {
      detail::measureGroundStartDepth(particles_, ground_.points().subspan(b, e - b), world_.groundNormal,
                                      world_.groundHeight,
                                      std::span(ground_.state().allowance).subspan(b, e - b));
    });
  }
  if (firstSubstep || newPairs) collectRigidGround();
  if (rigidGround_.empty()) return;
  placeRigidCapsulePoints();
  detail::measureRigidGroundStarts(rigidPassInput(h), rigidGround_, rigidGroundState_);
}

// On two or more threads, the contacts of particle bodies dealt into two bins that share no
// particle (contact_bins.h), when the narrow phase has found its manifolds from the broad phase's
// pairs; in the step's other substeps only their ranges found again. Not with rigid bodies, whose
// contacts are passes of their own on the calling thread.
void World::dealContacts(bool newPairs) {
  if (workers() == nullptr || rigidBodies_.size() > 0 || bodies_.size() < 2) {
    contactBins_.clear();
    return;
  }
  const detail::StageTimer timer(stageProfile(), Stage::Contacts);
  if (newPairs)
    contactBins_.deal(narrowPhase_.manifolds(), ground_.points(), bodies_.size());
  else if (contactBins_.dealt())
    contactBins_.rangeContacts(narrowPhase_.manifolds());
}

NarrowPhaseInput World::narrowPhaseInput() const {
  return {particles_,
          rigidBodies_,
          bodies_,
          frames_,
          broadPhase_,
          solver_.featureEpsilon,
          solver_.contactSlop,
          solver_.dt,
          gravityMagnitude(),
          solver_.manifoldReuse,
          islands_.anyAsleep() ? islands_.bodiesAsleep() : std::span<const std::uint8_t>(),
          workers()};
}

// Each contact with a rigid body: its overlap at the substep's start, of which the substep may remove
// maxDepenetrationSpeed h, its approach speed before the passes, and no impulse yet.
void World::startRigidContacts(Real h) {
  if (rigidBodies_.size() == 0) return;
  const detail::StageTimer timer(stageProfile(), Stage::Contacts);
  const RigidPassInput in = rigidPassInput(h);
  const Real depenetration = solver_.maxDepenetrationSpeed * h;
  // Room for the patches, as for the contacts (room.h): a patch has at least one point.
  const std::size_t room = detail::kRoomPerBody * bodies_.size();
  detail::keepRoom(rigidPatches_, narrowPhase_.rigidContacts().size(), room);
  detail::keepRoom(rigidGroundPatches_, rigidGround_.size(), room);
  detail::startRigidContacts(in, narrowPhase_.rigidContacts(), narrowPhase_.rigidState(), depenetration);
  detail::startRigidContacts(in, rigidGround_, rigidGroundState_, depenetration);
  detail::findPatches(in, narrowPhase_.rigidContacts(), rigidPatches_);
  detail::findPatches(in, rigidGround_, rigidGroundPatches_);
  // An anchor per patch, in two lists that trade places each substep (carryAnchors).
  for (auto [state, patches] : {std::pair{&narrowPhase_.rigidState(), rigidPatches_.size()},
                                std::pair{&rigidGroundState_, rigidGroundPatches_.size()}}) {
    detail::keepRoom(state->anchors, patches, room);
    detail::keepRoom(state->spareAnchors, patches, room);
  }
  detail::carryAnchors(narrowPhase_.rigidContacts(), rigidPatches_, narrowPhase_.rigidState());
  detail::carryAnchors(rigidGround_, rigidGroundPatches_, rigidGroundState_);
}

RigidPassInput World::rigidPassInput(Real h) {
  return {particles_,
          rigidBodies_,
          world_.groundNormal,
          world_.groundHeight,
          h,
          std::max(kRestitutionMinSpeed, 2.0 * gravityMagnitude() * h)};
}

// The velocities from the change of pose, then dynamic friction and restitution (Müller et al.
// 2020, 3.6). Restitution uses the particle models' threshold: impacts under 2 |g| h are what a
// resting contact gains in a substep, and never bounce.
void World::rigidVelocities(Real h) {
  if (rigidBodies_.size() == 0) return;
  const detail::StageTimer timer(stageProfile(), Stage::Velocities);
  detail::deriveRigidVelocities(rigidBodies_, h);
  const RigidPassInput in = rigidPassInput(h);
  detail::dampRigidJoints(in, constraints_.rigidJoints());
  detail::rigidVelocityPass(in, rigidGround_, rigidGroundPatches_, rigidGroundState_, solver_.restitution);
  detail::rigidVelocityPass(in, narrowPhase_.rigidContacts(), rigidPatches_, narrowPhase_.rigidState(),
                            solver_.restitution);
}

void World::partOverlaps() {
  if (bodies_.empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Parting);
  const PartingGround ground{world_.ground, world_.groundNormal, ground_.points(), ground_.state().allowance};
  const PartingRigid rigid{rigidBodies_, narrowPhase_.rigidState().allowance, rigidGround_,
                           rigidGroundState_.allowance};
  parting_.part(particles_, bodies_, narrowPhase_.manifolds(), narrowPhase_.movableContacts(),
                narrowPhase_.state().allowance, ground, rigid, solver_.featureEpsilon, solver_.parting);
}

// Restitution needs each contact's approach speed before the passes stop it, and which ground
// contacts the passes push (GroundContactState::hit, set by the friction pass, read by restitute() alone).
// A character of particle parts that reacts to blows reads the bodies' approach too: it is how hard
// they strike its parts.
void World::measureApproaches(Real h) {
  const bool blows = std::any_of(characters_.begin(), characters_.end(), [](const Character& c) {
    return c.particleParts && c.reaction.threshold > 0.0;
  });
  if (solver_.restitution <= 0.0 && !blows) return;
  const detail::StageTimer timer(stageProfile(), Stage::Restitution);
  detail::measureBodyApproach(particles_, narrowPhase_.contacts(), h, narrowPhase_.state().approach);
  if (solver_.restitution <= 0.0) return;
  clearUnlessStill(ground_.state().hit, ground_.still());
  if (world_.ground) {
    detail::measureGroundApproach(particles_, ground_.points(), world_.groundNormal, h,
                                  ground_.state().approach);
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
  std::vector<Real>& bodyAllowance = narrowPhase_.state().allowance;
  if (!bodyAllowance.empty() || world_.ground) {
    const detail::StageTimer timer(stageProfile(), Stage::Contacts);
    detail::toAllowance(bodyAllowance, depenetration);
    if (world_.ground) detail::toAllowance(ground_.state().allowance, depenetration);
  }
  if (!constraints_.linksApart()) return {};
  const detail::StageTimer timer(stageProfile(), Stage::Links);
  return constraints_.shrinkLinkSlack(particles_, depenetration);
}

void World::relax(Real h, std::span<const Real> linkSlack) {
  const bool ground = world_.ground;
  auto inGroundPieces = [this](auto&& f) { detail::forEachGroundPiece(workers(), ground_.points(), f); };
  auto stillPart = [this](std::size_t b, std::size_t e) { return flagsOf(ground_.still(), b, e); };
  const std::span<const BodyContact> bodyContacts = narrowPhase_.contacts();
  BodyContactState& bodyState = narrowPhase_.state();
  GroundContactState& groundState = ground_.state();
  const bool contacts = ground || !bodyContacts.empty();
  const bool binned = contactBins_.dealt();  // only ever with workers (dealContacts)
  // The bodies' own sticks (and volumes) are internal: what they do to a body's angular momentum
  // is undone (keepSpin). SHAKE's corrections keep it already.
  const bool keepSpin = solver_.keepSpin && solver_.method != SolverMethod::Shake;
  detail::StageLaps laps(stageProfile());
  for (int it = 0; it < solver_.iterations; ++it) {
    if (!constraints_.particleJoints().empty() || !constraints_.bodyDrives().empty()) {
      // Particle bodies' drives first, so each pass ends with their links (the joints' pins and
      // stops) held, as the rigid drives come before their joints below. A drive turns or moves a
      // body whole, which its own sticks do not see.
      detail::driveParticleBodies(particles_, bodies_, constraints_.bodyDrives(),
                                  constraints_.bodyDriveLambda(), it == 0, h);
      detail::driveParticleJoints(particles_, bodies_, constraints_.particleJoints(),
                                  constraints_.particleDrives(), constraints_.particleDriveLambda(),
                                  constraints_.particleDriveShare(), it == 0, h);
      laps.lap(Stage::Links);
    }
    if (!constraints_.sticks().empty()) {
      // The lanes, blocks and volumes keep their bodies' moments on their copies (stick_spin.cpp);
      // the bodies whose sticks are relaxed in the world's arrays are bracketed here.
      const std::span<const std::uint32_t> runBodies = constraints_.stickRunBodies();
      if (keepSpin && it == 0) detail::startStickSpin(particles_, bodies_, runBodies, spinLever_, stickSpin_);
      if (keepSpin) detail::measureStickSpin(particles_, bodies_, runBodies, spinLever_, stickSpin_);
      tetraVolumes_.keep(particles_, solver_.method == SolverMethod::Shake, workers(), keepSpin);
      constraints_.relaxSticks(particles_, solver_.method, it == 0, h, solver_.compliance, workers(),
                               keepSpin,
                               {solver_.iterations, ground, world_.groundNormal, world_.groundHeight});
      if (keepSpin) detail::restoreStickSpin(particles_, bodies_, runBodies, spinLever_, stickSpin_);
      laps.lap(Stage::Sticks);
    }
    // Joints after the boxes' own sticks, so each pass ends its constraints with the links
    // between bodies, then the contacts. Links are rigid projections in every method, so the
    // world's compliance, which XPBD adds to the sticks, does not soften them.
    if (!constraints_.links().empty()) {
      constraints_.solveLinks(particles_, linkSlack, workers());
      laps.lap(Stage::Links);
    }
    if (!constraints_.rigidLinks().empty() || !constraints_.rigidJoints().empty() ||
        !constraints_.bodyDrives().empty()) {
      const RigidPassInput in = rigidPassInput(h);
      detail::solveRigidLinks(in, constraints_.rigidLinks());
      // Drives before the joints' own constraints, so each pass ends with the joint's axes, stops
      // and pin held: a target beyond a stop is pulled towards, never reached.
      detail::driveRigidBodies(in, constraints_.bodyDrives(), constraints_.bodyDriveLambda(), it == 0);
      detail::driveRigidJoints(in, constraints_.rigidJoints(), constraints_.drives(),
                               constraints_.driveLambda(), it == 0);
      detail::solveRigidJoints(in, constraints_.rigidJoints());
      laps.lap(Stage::Links);
    }

    // Rigid bodies' contacts, each patch with its static friction (rigid_contacts.cpp).
    if (!rigidPatches_.empty() || !rigidGroundPatches_.empty()) {
      const RigidPassInput in = rigidPassInput(h);
      // Each pass pushes a capsule's ground points from where they are its lowest now. Placed once a
      // substep, the points turned with the capsule as the joints and the passes turned it, a radian
      // a pass at 0.3 s, and a pass left its end spheres' true lowest points under the ground, by
      // up to their radius (RigidBody.ATumblingCapsuleLandsWithoutSinkingAtLongSteps).
      placeRigidCapsulePoints();
      detail::solveRigidContacts(in, rigidGround_, rigidGroundPatches_, rigidGroundState_);
      detail::solveRigidContacts(in, narrowPhase_.rigidContacts(), rigidPatches_, narrowPhase_.rigidState());
      laps.lap(Stage::Contacts);
    }
    // Contacts, each pass followed by its friction, so the next pass's sticks relax what
    // friction bent (run once after all passes, friction would leave every resting box
    // sheared by the last correction).
    if (!contacts) continue;
    if (binned) {
      relaxContactBins(ground);  // times its own stages
      laps.skip();
      continue;
    }
    detail::solveBodyContacts(particles_, bodyContacts, solver_.contactSlop, bodyState.push,
                              bodyState.allowance);
    if (ground) {
      // Each ground point moves its own body's particles: pieces of them at once (ground_pieces.h).
      inGroundPieces([&](std::size_t b, std::size_t e) {
        detail::collideGround(particles_, ground_.points().subspan(b, e - b), world_.groundNormal,
                              world_.groundHeight, std::span(groundState.push).subspan(b, e - b),
                              std::span(groundState.allowance).subspan(b, e - b), stillPart(b, e),
                              flagsOf(ground_.far(), b, e));
      });
    }
    laps.lap(Stage::Contacts);
    detail::applyBodyFriction(particles_, narrowPhase_.movableContacts(), narrowPhase_.contactExtras(),
                              bodyState.push);
    flagPushed(bodyState.push, bodyState.touched);
    if (ground) {
      inGroundPieces([&](std::size_t b, std::size_t e) {
        const std::span<const Real> push = std::span<const Real>(groundState.push).subspan(b, e - b);
        detail::applyGroundFriction(particles_, ground_.points().subspan(b, e - b), world_.groundNormal, push,
                                    stillPart(b, e), ground_.anyFreeTetraBox());
        flagPushed(push, std::span(groundState.touched).subspan(b, e - b),
                   std::span(groundState.hit).subspan(b, e - b));
      });
    }
    laps.lap(Stage::Friction);
  }
  if (!bodyContacts.empty()) {
    const detail::StageTimer timer(stageProfile(), Stage::Contacts);
    detail::markPushedParticles(bodyContacts, bodyState.touched, movedByBoxContact_);
  }
}

// A pass's contacts and friction as relax() takes them, each bin of contactBins_ on a thread of its
// own: its contacts between bodies, then its ground points; then their friction likewise. The
// same calls as relax()'s own block, over ranges. One function for both (lambdas over ranges, the
// whole lists on one thread) gave the same state but made pyramid-20's friction stage at 10 x 16 on
// one thread 7% slower (318 to 341 ms over 60 steps, four runs each): what the compiler inlines into
// these passes decides their cost (docs/performance.md, "Contact points by fewer particles").
void World::relaxContactBins(bool ground) {
  const std::span<const BodyContact> bodyContacts = narrowPhase_.contacts();
  const std::span<BodyContact> anchoredContacts = narrowPhase_.movableContacts();  // friction moves anchors
  const std::span<const BodyContactExtra> extras = narrowPhase_.contactExtras();
  BodyContactState& bodyState = narrowPhase_.state();
  GroundContactState& groundState = ground_.state();
  const std::span<const GroundContact> points = ground_.points();
  auto inBins = [this](auto&& f) {
    auto range = [&f](std::size_t begin, std::size_t end) {
      for (std::size_t bin = begin; bin < end; ++bin) f(static_cast<int>(bin));
    };
    workers()->forEach(2, 1, range);
  };
  auto part = [](auto& v, ContactBins::Range r) { return std::span(v).subspan(r.begin, r.end - r.begin); };
  auto stillPart = [this](ContactBins::Range r) { return flagsOf(ground_.still(), r.begin, r.end); };
  auto farPart = [this](ContactBins::Range r) { return flagsOf(ground_.far(), r.begin, r.end); };
  {
    const detail::StageTimer timer(stageProfile(), Stage::Contacts);
    inBins([&](int bin) {
      for (const ContactBins::Range r : contactBins_.contactRanges(bin)) {
        detail::solveBodyContacts(particles_, part(bodyContacts, r), solver_.contactSlop,
                                  part(bodyState.push, r), part(bodyState.allowance, r));
      }
      if (!ground) return;
      for (const ContactBins::Range r : contactBins_.groundRanges(bin)) {
        detail::collideGround(particles_, part(points, r), world_.groundNormal, world_.groundHeight,
                              part(groundState.push, r), part(groundState.allowance, r), stillPart(r),
                              farPart(r));
      }
    });
  }
  const detail::StageTimer timer(stageProfile(), Stage::Friction);
  inBins([&](int bin) {
    for (const ContactBins::Range r : contactBins_.contactRanges(bin)) {
      detail::applyBodyFriction(particles_, part(anchoredContacts, r), part(extras, r),
                                part(bodyState.push, r));
      flagPushed(part(bodyState.push, r), part(bodyState.touched, r));
    }
    if (!ground) return;
    for (const ContactBins::Range r : contactBins_.groundRanges(bin)) {
      detail::applyGroundFriction(particles_, part(points, r), world_.groundNormal, part(groundState.push, r),
                                  stillPart(r), ground_.anyFreeTetraBox());
      flagPushed(part(groundState.push, r), part(groundState.touched, r), part(groundState.hit, r));
    }
  });
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
  const detail::StageTimer timer(stageProfile(), Stage::Restitution);
  const Real g = gravityMagnitude();
  const detail::Restitution r{solver_.restitution, std::max(kRestitutionMinSpeed, 2.0 * g * h), h};
  detail::measureRigidStates(particles_, bodies_, h, rigid_);
  for (int it = 0; it < solver_.iterations; ++it) {
    detail::restituteBodyContacts(particles_, rigid_, narrowPhase_.contacts(), narrowPhase_.state().approach,
                                  narrowPhase_.state().touched, r);
    if (world_.ground) {
      detail::restituteGround(particles_, rigid_, ground_.points(), world_.groundNormal,
                              ground_.state().approach, ground_.state().hit, r);
    }
  }
  detail::applyRigidChanges(particles_, bodies_, rigid_, h);
}

void World::dampBodies() {
  if (solver_.bodyDamping <= 0.0 || bodies_.empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::BodyDamping);
  detail::dampBodyMotion(particles_, bodies_, bodyLayout_, solver_.bodyDamping, workers());
}

// Once a step, after the last substep: the friction of particle bodies' joints, from the motion
// over the last substep (x - x*), which the next step's Verlet carries on.
void World::dampJoints() {
  if (constraints_.jointFrictions().empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Links);
  constraints_.dampJointFriction(particles_, bodies_, solver_.dt, workers());
}

// After the passes, before the velocities are taken from the change of pose: the poses moved so that
// every rigid joint's pin closes and every hinge's axes align (joint_projection.h), so that the
// substep's velocities carry the correction, as they carry every pass's. Once a step, after the
// substeps and without touching the velocities (post-stabilisation proper), it kept the piles from
// resting; in the last substep alone it turned a step's worth of opening into one substep's speed
// and blew Bullet's pile apart (docs/physics.md, "Joint projection").
void World::projectJoints() {
  if (!solver_.jointProjection.enabled || constraints_.rigidJoints().empty()) return;
  const detail::StageTimer timer(stageProfile(), Stage::Links);
  const JointProjectionReport r =
      jointProjection_.project(rigidBodies_, constraints_.rigidJoints(), solver_.jointProjection);
  lastProjection_.iterations += r.iterations;
  lastProjection_.errorBefore = std::max(lastProjection_.errorBefore, r.errorBefore);
  lastProjection_.errorAfter = r.errorAfter;
}

// A body is frozen whole, put back as it was at the end of the last substep (integrate() gave the
// guard that), so all of it from one instant, whichever particle went bad.
void World::guard(bool shapes) {
  const detail::StageTimer timer(stageProfile(), Stage::Guard);
  guardParticles();
  guard_.checkRigidBodies(rigidBodies_, bodies_, world_.bound, time_);
  if (shapes) guard_.checkShapes(guardInput(), world_.shapeCheckInterval);
}

// Also run after a change of settings has moved particles outside the step (setSolverSettings):
// a particle left non-finite there would otherwise be copied into the guard's good positions by the
// next integration and frozen at NaN (found by the soak test, seed 21: a chain under gravity of
// 1e244 m/s^2 given 1000 iterations).
void World::guardParticles() {
  guard_.checkParticles(guardInput(), world_.bound, workers());
}

GuardInput World::guardInput() {
  return {particles_, bodies_, constraints_.sticks(), particleName_, particleBody_, time_};
}

}  // namespace phys
