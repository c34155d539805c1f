#include "step_budget.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace soak {
namespace {

constexpr double kVisitsPerIteration = 30.0;  // a pass's own overhead (its timers), however empty
constexpr double kVisitsPerSubstep = 50.0;    // a substep's, likewise: 1000 x 1000 empty is 0.4 s
constexpr double kVisitsPerContact = 3.0;     // a contact point: its projection, and then its friction
constexpr double kVisitsPerBoxFrame = 20.0;
constexpr double kVisitsPerPair = 70.0;
constexpr double kContactsPerNewPair = 4.0;  // a box-box contact keeps at most 4 points
constexpr int kMaxCatchUpSteps = 1000;       // Session::step's cap on a lagging run's steps per call

// |v| without overflow (huge gravity is among the settings drawn).
double magnitude(const phys::Vec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest == 0.0 || !std::isfinite(largest) ? largest
                                                   : largest * std::sqrt(glm::dot(v / largest, v / largest));
}

struct Bounds {
  phys::Vec3 lo, hi;
};

}  // namespace

// The world's broad phase (BroadPhase::update) grows each box's bounds by how far it can go in
// a step: its fastest particle's speed times dt, plus g dt^2, plus the feature epsilon. The
// pairs it found last step say nothing of the next one after dt, gravity or epsilon grew (a
// pyramid of 820 boxes goes from 2,300 pairs to 340,000 at dt = 1 s), so count them here the
// same way, from the corners of each box, by sweep and prune along x.
double estimatedPairs(const phys::World& world) {
  const std::span<const phys::Body> boxes = world.bodies();
  if (boxes.size() < 2) return 0.0;
  const phys::SolverSettings& s = world.solverSettings();
  const phys::WorldSettings& ws = world.worldSettings();
  const double h = s.dt / s.substeps;
  const double g = ws.gravityMode == phys::GravityMode::Uniform ? magnitude(ws.gravity) : ws.gravityStrength;
  const phys::Particles& p = world.particles();
  std::vector<Bounds> bounds;
  bounds.reserve(boxes.size());
  for (phys::BodyId id{}; id < boxes.size(); ++id) {
    const phys::Body& box = boxes[id];
    double fastest = 0.0;
    for (int j = 0; j < box.particleCount; ++j) {
      const std::size_t i = box.firstParticle + static_cast<std::size_t>(j);
      fastest = std::max(fastest, magnitude(p.position[i] - p.previous[i]) / h);
    }
    // A rigid body has no particles: its centre's speed and its corners' turning.
    if (box.model == phys::BodyModel::Rigid) {
      const auto [v, w] = world.bodyVelocity(id);
      fastest = magnitude(v) + magnitude(w) * magnitude(box.halfExtents);
    }
    const double reach = fastest * s.dt + g * s.dt * s.dt + s.featureEpsilon;
    Bounds b{phys::Vec3(std::numeric_limits<double>::infinity()),
             phys::Vec3(-std::numeric_limits<double>::infinity())};
    for (int k = 0; k < 8; ++k) {
      const phys::Vec3 corner = world.cornerPosition(id, k);
      b.lo = glm::min(b.lo, corner);
      b.hi = glm::max(b.hi, corner);
    }
    bounds.push_back({b.lo - phys::Vec3(reach), b.hi + phys::Vec3(reach)});
  }
  std::sort(bounds.begin(), bounds.end(), [](const Bounds& a, const Bounds& b) { return a.lo.x < b.lo.x; });
  double pairs = 0.0;
  for (std::size_t i = 0; i < bounds.size(); ++i) {
    for (std::size_t j = i + 1; j < bounds.size() && bounds[j].lo.x <= bounds[i].hi.x; ++j) {
      if (bounds[j].lo.y <= bounds[i].hi.y && bounds[i].lo.y <= bounds[j].hi.y &&
          bounds[j].lo.z <= bounds[i].hi.z && bounds[i].lo.z <= bounds[j].hi.z)
        ++pairs;
    }
  }
  return pairs;
}

double stepVisits(const phys::World& world) {
  const phys::SolverSettings& settings = world.solverSettings();
  const double pairs = estimatedPairs(world);
  // Pairs beyond last step's may each bring contact points that every iteration relaxes.
  const double newPairs = std::max(0.0, pairs - static_cast<double>(world.broadPhasePairs()));
  const double constraints =
      static_cast<double>(world.particles().size() + world.sticks().size() + world.links().size());
  const double contacts = static_cast<double>(world.groundContacts().size() + world.bodyContacts().size()) +
                          kContactsPerNewPair * newPairs;
  const double relaxed = constraints + kVisitsPerContact * contacts;
  const double perSubstep = settings.iterations * (relaxed + kVisitsPerIteration) + kVisitsPerSubstep +
                            kVisitsPerBoxFrame * static_cast<double>(world.bodies().size()) +
                            kVisitsPerPair * pairs;
  return settings.substeps * perSubstep;
}

double sessionVisits(const sandbox::Session& session, int steps) {
  const std::span<const sandbox::Run> runs = session.runs();
  const phys::World& main = runs.front().scene->world;
  double visits = steps * stepVisits(main);
  const double mainTime = main.time() + steps * main.solverSettings().dt;
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const phys::World& w = runs[i].scene->world;
    const double dt = w.solverSettings().dt;
    const double behind = std::max(0.0, std::ceil((mainTime - w.time()) / dt));
    const double catchUp = std::min(behind, static_cast<double>(kMaxCatchUpSteps) * steps);
    visits += catchUp * stepVisits(w);
  }
  return visits;
}

}  // namespace soak
