#include "stability_judge.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "bodies.h"
#include "peers/peer_scene.h"
#include "peers/pose_measures.h"
#include "physics/body.h"
#include "run_metrics.h"
#include "text.h"

namespace lab::stability {
namespace {

// A flip is counted when the middle axis points more than 60 degrees the other way from the
// side it was last counted on: the hysteresis keeps a wobble about 90 degrees from counting
// twice, and a real Dzhanibekov flip swings the axis all the way round.
constexpr double kFlipThreshold = 0.5;

// Keeps the extreme of a stays-behind coordinate: the highest for a max plane, the lowest for min.
void keepExtreme(const Criterion& c, double& value, double sample) {
  if (std::isinf(value)) return;  // blown up already: stays so
  if (!std::isfinite(sample))
    value = kInf;
  else if (std::isnan(value))
    value = sample;
  else
    value = c.atLeast ? std::min(value, sample) : std::max(value, sample);
}

// The body-frame axis of the middle side length, which is also that of the middle moment of
// inertia: a box's moment about x is m (hy^2 + hz^2) / 3, so the orders agree.
phys::Vec3 middleAxis(const phys::Vec3& h) {
  const int big = h.x >= h.y && h.x >= h.z ? 0 : (h.y >= h.z ? 1 : 2);
  const int small = h.x <= h.y && h.x <= h.z ? 0 : (h.y <= h.z ? 1 : 2);
  phys::Vec3 axis(0.0);
  axis[3 - big - small] = 1.0;
  return axis;
}

Verdict verdictOf(const Criterion& c, double value) {
  Verdict v;
  v.value = value;
  v.ratio = errorRatio(c, value);
  v.passed = v.ratio <= 1.0;  // NaN and infinity fail
  return v;
}

// Whether a stick joins two loose particles, given particleBodies(world) (their places are after the boxes').
bool isLooseStick(const phys::World& world, const std::vector<std::size_t>& body, const phys::Stick& s) {
  return body[s.a] >= world.bodies().size() && body[s.b] >= world.bodies().size();
}

bool hasLooseSticks(const phys::World& world) {
  const std::vector<std::size_t> body = particleBodies(world);
  return std::any_of(world.sticks().begin(), world.sticks().end(),
                     [&](const phys::Stick& s) { return isLooseStick(world, body, s); });
}

// Stick error from positions: the sticks between two loose particles (a peer's rigid bodies
// keep their own shape exactly, so a box's internal sticks have no error there).
double looseStickError(const phys::World& world, const std::vector<phys::Vec3>& at) {
  const std::vector<std::size_t> body = particleBodies(world);
  double worst = 0.0;
  for (const phys::Stick& s : world.sticks()) {
    if (!isLooseStick(world, body, s)) continue;
    const double d = glm::length(at[body[s.b]] - at[body[s.a]]);
    const double bound = d < s.minLength ? s.minLength : (d > s.maxLength ? s.maxLength : d);
    if (bound > 0.0) worst = std::max(worst, std::abs(d - bound) / bound);
  }
  return worst;
}

// A peer's run as the judge reads it: the bodies' poses after k steps, k = 0 the loaded scene.
struct PeerStates {
  const peers::Description& scene;
  std::vector<std::vector<phys::Vec3>> positions;
  std::vector<std::vector<phys::Quat>> orientations;  // empty when the peer gave none
};

// The fastest point of the bodies from step k - 1 to step k: each box's or capsule's particles
// where ours has them (its corners, or the tetra model's four), carried by the body's poses, and
// each loose particle, so a spinning body's corners count as our particles do (Metrics::maxSpeed).
// Without orientations, the bodies' centres alone.
double peerSpeed(const PeerStates& p, int k, double dt) {
  const auto& now = p.positions[static_cast<std::size_t>(k)];
  const auto& before = p.positions[static_cast<std::size_t>(k - 1)];
  double worst = 0.0;
  for (std::size_t b = 0; b < now.size(); ++b) {
    const peers::Body& body = p.scene.bodies[b];
    if (p.orientations.empty() || !body.solid()) {
      keepLargest(worst, glm::length(now[b] - before[b]) / dt);
      continue;
    }
    const phys::Quat& qNow = p.orientations[static_cast<std::size_t>(k)][b];
    const phys::Quat& qBefore = p.orientations[static_cast<std::size_t>(k - 1)][b];
    // A rigid body has no particles: its corners are where it is fastest.
    const phys::BodyModel model =
        body.model == phys::BodyModel::Rigid ? phys::BodyModel::Corners : body.model;
    for (int j = 0; j < phys::boxParticleCount(model); ++j) {
      const phys::Vec3 local = phys::boxParticleLocal(model, body.halfExtents, j);
      keepLargest(
          worst,
          glm::length(peers::toWorld(now[b], qNow, local) - peers::toWorld(before[b], qBefore, local)) / dt);
    }
  }
  return worst;
}

double judgeOne(const Criterion& c, const phys::World& world, double dt, const PeerStates& p) {
  Tally tally(c, world);
  for (int k = c.fromStep; k <= c.toStep; ++k) {
    const auto at = static_cast<std::size_t>(k);
    const std::vector<phys::Vec3>& now = p.positions[at];
    if (c.metric == Metric::Speed) {
      if (k > 0) tally.sampleFigure(peerSpeed(p, k, dt));
    } else if (c.metric == Metric::StickError) {
      tally.sampleFigure(looseStickError(world, now));
    } else if (c.metric == Metric::Penetration) {
      tally.sampleFigure(peers::posePenetration(p.scene, now, p.orientations[at]));
    } else if (c.metric == Metric::JointGap) {
      tally.sampleFigure(peers::jointGap(p.scene, now, p.orientations[at]));
    } else {
      tally.samplePoses(
          k, [&](std::size_t b) { return now[b]; }, [&](std::size_t b) { return p.orientations[at][b]; });
    }
  }
  return tally.value();
}

}  // namespace

Tally::Tally(const Criterion& criterion, const phys::World& loaded)
    : criterion_(&criterion),
      // NaN for stays-behind: the first sample sets it (min and max both take a number over NaN).
      value_(criterion.metric == Metric::StaysBehind ? kNaN : 0.0) {
  if (criterion.metric == Metric::Flips)
    middleAxis_ = middleAxis(loaded.bodies()[criterion.bodies.front()].halfExtents);
}

void Tally::samplePoses(int step, const std::function<phys::Vec3(std::size_t)>& position,
                        const std::function<phys::Quat(std::size_t)>& orientation) {
  const Criterion& c = *criterion_;
  if (c.metric == Metric::Drift) {
    if (step == c.fromStep) {
      for (std::size_t b : c.bodies) reference_.push_back(position(b));
      return;
    }
    for (std::size_t i = 0; i < c.bodies.size(); ++i)
      sampleFigure(glm::length(position(c.bodies[i]) - reference_[i]));
  } else if (c.metric == Metric::StaysBehind) {
    keepExtreme(c, value_, position(c.bodies.front())[c.axis]);
  } else if (c.metric == Metric::Flips) {
    const phys::Vec3 axis = orientation(c.bodies.front()) * middleAxis_;
    if (!phys::finite(axis)) value_ = kInf;  // blown up: stays so, as infinity + 1 is infinity
    if (step == c.fromStep) {
      axisAtStart_ = axis;
    } else if (glm::dot(axis, axisAtStart_) * sign_ < -kFlipThreshold) {
      sign_ = -sign_;  // a flip (kFlipThreshold)
      value_ += 1.0;
    }
  }
}

void Tally::sampleFigure(double figure) {
  keepLargest(value_, figure);
}

bool Tally::failedForGood() const {
  const Criterion& c = *criterion_;
  // A count only grows: past its max it stays past, but under its min it may yet reach it.
  if (c.metric == Metric::Flips) return value_ > c.upper;
  // The rest keep their largest sample, or the extreme toward a plane the body starts strictly
  // before, so their ratio never falls. NaN: stays-behind before its first sample.
  return !std::isnan(value_) && errorRatio(c, value_) > 1.0;
}

WorldJudge::WorldJudge(const std::vector<Criterion>& criteria, const phys::World& world)
    : criteria_(criteria), loose_(looseParticles(world)) {
  for (const Criterion& c : criteria_) tallies_.emplace_back(c, world);
  observe(world, 0);
}

void WorldJudge::observe(const phys::World& world, int step) {
  const std::size_t boxes = world.bodies().size();
  const auto position = [&](std::size_t b) {
    // the centre alone: a pose's orientation is a polar decomposition, for no figure but flips
    return b < boxes ? world.bodyCentre(phys::BodyId(b)) : world.particles().position[loose_.at(b - boxes)];
  };
  const auto orientation = [&](std::size_t b) { return world.bodyPose(phys::BodyId(b)).orientation; };
  std::optional<phys::Metrics> metrics;  // once per step, for all that need it
  for (std::size_t i = 0; i < criteria_.size(); ++i) {
    if (step < criteria_[i].fromStep || step > criteria_[i].toStep) continue;  // outside its window
    if (const auto figure = metricInfo(criteria_[i].metric).figure) {
      if (!metrics) metrics = world.metrics();
      tallies_[i].sampleFigure(*metrics.*figure);
    } else {
      tallies_[i].samplePoses(step, position, orientation);
    }
  }
}

std::vector<Verdict> WorldJudge::verdicts(bool blewUp) const {
  std::vector<Verdict> out;
  for (std::size_t i = 0; i < criteria_.size(); ++i)
    out.push_back(verdictOf(criteria_[i], blewUp ? kInf : tallies_[i].value()));
  return out;
}

std::optional<std::size_t> WorldJudge::failedForGood() const {
  for (std::size_t i = 0; i < tallies_.size(); ++i)
    if (tallies_[i].failedForGood()) return i;
  return std::nullopt;
}

std::vector<Verdict> judgePeer(const std::vector<Criterion>& criteria, const scenes::Scene& scene, double dt,
                               const std::vector<std::vector<phys::Vec3>>& positions,
                               const std::vector<std::vector<phys::Quat>>& orientations) {
  const phys::World& world = scene.world;
  const peers::Description description = peers::describe(scene);
  // The states after k steps, the loaded scene's for k = 0 (its bodies as the peers were given them).
  PeerStates p{description, {}, {}};
  p.positions.push_back(bodyPositions(world));
  p.positions.insert(p.positions.end(), positions.begin(), positions.end());
  if (!orientations.empty()) {
    p.orientations.push_back(bodyOrientations(world));
    p.orientations.insert(p.orientations.end(), orientations.begin(), orientations.end());
  }
  const std::size_t bodies = description.bodies.size();
  auto complete = [&](const auto& states) {
    return std::all_of(states.begin(), states.end(), [&](const auto& s) { return s.size() == bodies; });
  };
  const bool sameBodies = complete(p.positions) && complete(p.orientations) &&
                          (p.orientations.empty() || p.orientations.size() == p.positions.size());
  std::vector<Verdict> out;
  for (const Criterion& c : criteria) {
    // A box's own sticks, which a peer's rigid body keeps exactly, so its stick error would say
    // nothing; a peer that gave no orientations; and one that recorded too little.
    std::string why;
    if (c.metric == Metric::StickError && !hasLooseSticks(world))
      why = "stick-error: rigid bodies";
    else if (metricInfo(c.metric).needsOrientations && p.orientations.empty())
      why = std::string(metricInfo(c.metric).name) + ": needs orientations";
    else if (!sameBodies || p.positions.size() <= static_cast<std::size_t>(c.toStep)) {
      why = std::string(metricInfo(c.metric).name) + ": the peer recorded " +
            std::to_string(p.positions.size() - 1) + " of " + std::to_string(c.toStep) +
            " steps, or not every body";
    }
    out.push_back(why.empty() ? verdictOf(c, judgeOne(c, world, dt, p))
                              : Verdict{.judged = false, .why = why});
  }
  return out;
}

}  // namespace lab::stability
