#include "accuracy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include "bodies.h"
#include "numbers.h"
#include "runner.h"
#include "text.h"

// What "converged" means here. A reference is our own physics run so finely that the settings
// being judged cannot come near it: `shake`, 128 substeps of 4 passes, at the same dt (so a
// dt sweep compares each dt with its own reference, at the same checkpoint steps).
//  - shake, because it is the second-order method for sticks: on the 2 m pendulum released at
//    90 degrees its 64-substep run is 3e-7 m from the exact (elliptic-function) answer after
//    1 s and falls 16 times per 4 times the substeps, while gauss-seidel and xpbd, whose
//    projection bleeds energy at O(h), are still 2.7e-3 m off at 64 substeps and 6.8e-4 m at
//    256 (measured with this file's runs against assets/scenes/pendulum-exact.xml's answers).
//    xpbd instead when the scene asks for compliance, which only xpbd honours.
//  - Substeps rather than passes (Macklin et al. 2019, "Small Steps"), but not one pass: over
//    2 s at 64 substeps, the 20-link chain with its 100:1 end mass still moved 1.3e-2 m between
//    1 and 4 passes, the stack of ten boxes 1.0e-4 m; between 4 and 8 passes, 2e-3 and 1.7e-5 m.
//  - 128 substeps because the run with half as many is the reference's own error bar
//    (AccuracyTarget::uncertainty): on the stack and the chain it is 1e-5 to 1e-2 m after 2 s.
// Contacts, links and friction converge too, but a body that lands on an edge or a tumbling
// ragdoll is chaotic: the reference and its half-substep twin part by 1 to 3 cm within half a
// second of landing and by 22 cm a second later (falling-box, ragdoll). No reference settles
// that; the uncertainty shows it, and the default horizon is kept short (1 s) for it.

namespace lab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

double distance(const phys::Vec3& a, const phys::Vec3& b) {
  const phys::Vec3 d = a - b;
  return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

bool finite(const phys::Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// ---- <expect kind="position"> ----------------------------------------------------------------

constexpr std::string_view kKnownAttributes = "kind, body, at, pos";

// Throws the loader's kind of error, worded like its own ("<box> attribute 'size': ...").
[[noreturn]] void fail(const scenes::Scene& scene, const scenes::Expectation& e, std::string_view attribute,
                       const std::string& why) {
  std::string message = "<expect kind=\"position\"> ";
  if (!attribute.empty()) message += "attribute '" + std::string(attribute) + "': ";
  throw scenes::LoadError(scene.file.string(), e.line, std::string(attribute), message + why);
}

const std::string& required(const scenes::Scene& scene, const scenes::Expectation& e, std::string_view name) {
  const std::string* value = e.find(name);
  if (value == nullptr) fail(scene, e, name, "is required");
  return *value;
}

std::optional<phys::Vec3> parseVector(const std::string& text) {
  std::istringstream words(text);
  std::vector<double> values;
  std::string word;
  while (words >> word) {
    const std::optional<double> v = parseNumber(word);
    if (!v) return std::nullopt;
    values.push_back(*v);
  }
  if (values.size() != 3) return std::nullopt;
  return phys::Vec3(values[0], values[1], values[2]);
}

// The body's place in bodyPositions(): boxes by id, then loose particles by id.
std::optional<std::size_t> bodySlot(const scenes::Scene& scene, const std::string& name) {
  for (const scenes::NamedBody& b : scene.bodies) {
    if (b.name != name) continue;
    if (b.kind == scenes::NamedBody::Kind::Body) return b.index;
    return particleSlot(scene.world, b.particle());
  }
  return std::nullopt;
}

struct PositionExpect {
  std::size_t slot = 0;
  int step = 0;
  phys::Vec3 pos{0.0};
};

PositionExpect readExpect(const scenes::Scene& scene, const scenes::Expectation& e, double dt) {
  for (std::size_t i = 0; i < e.attributes.size(); ++i) {
    const std::string& name = e.attributes[i].first;
    if (name != "kind" && name != "body" && name != "at" && name != "pos") {
      fail(scene, e, name, "unknown attribute (known: " + std::string(kKnownAttributes) + ")");
    }
    for (std::size_t j = i + 1; j < e.attributes.size(); ++j) {
      if (e.attributes[j].first == name) fail(scene, e, name, "given twice");
    }
  }
  PositionExpect x;
  const std::string& body = required(scene, e, "body");
  const std::optional<std::size_t> slot = bodySlot(scene, body);
  if (!slot) fail(scene, e, "body", "'" + body + "' names no box or loose particle of the scene");
  x.slot = *slot;

  const std::string& at = required(scene, e, "at");
  const std::optional<double> t = parseNumber(at);
  if (!t || *t <= 0.0) fail(scene, e, "at", "'" + at + "' must be a finite number > 0 (s)");
  // The run is compared at whole steps; an answer between two steps cannot be checked.
  const double steps = std::round(*t / dt);
  if (std::abs(steps * dt - *t) > 1e-6 * dt || steps > 1e9) {
    fail(scene, e, "at", "'" + at + "' s is not a whole number of steps of " + formatNumber(dt) + " s");
  }
  x.step = static_cast<int>(steps);

  const std::string& pos = required(scene, e, "pos");
  const std::optional<phys::Vec3> p = parseVector(pos);
  if (!p) fail(scene, e, "pos", "'" + pos + "' must be three finite numbers (m)");
  x.pos = *p;
  return x;
}

AccuracyTarget analyticTarget(const scenes::Scene& scene, const std::vector<PositionExpect>& expects,
                              double dt) {
  AccuracyTarget t;
  t.kind = "analytic";
  for (const PositionExpect& x : expects) t.checkpoints.push_back(x.step);
  std::sort(t.checkpoints.begin(), t.checkpoints.end());
  t.checkpoints.erase(std::unique(t.checkpoints.begin(), t.checkpoints.end()), t.checkpoints.end());
  const std::size_t bodies = bodyPositions(scene.world).size();
  t.expected.assign(t.checkpoints.size(), std::vector<phys::Vec3>(bodies, phys::Vec3(kNaN)));
  t.uncertainty.assign(t.checkpoints.size(), 0.0);
  for (const PositionExpect& x : expects) {
    const auto k =
        std::lower_bound(t.checkpoints.begin(), t.checkpoints.end(), x.step) - t.checkpoints.begin();
    t.expected[static_cast<std::size_t>(k)][x.slot] = x.pos;
  }
  t.description = "analytic: " + std::to_string(expects.size()) +
                  " positions given by the scene, at t = " + formatNumber(t.checkpoints.front() * dt) +
                  " to " + formatNumber(t.checkpoints.back() * dt) + " s";
  return t;
}

// ---- reference ---------------------------------------------------------------------------------

bool hasCompliance(const phys::World& world) {
  if (world.solverSettings().compliance > 0.0) return true;
  return std::any_of(world.sticks().begin(), world.sticks().end(),
                     [](const phys::Stick& s) { return s.compliance > 0.0; });
}

}  // namespace

std::vector<int> spreadCheckpoints(int steps) {
  std::vector<int> out;
  for (int k = 1; k <= kReferenceCheckpoints; ++k) {
    const int step =
        std::max(1, static_cast<int>(std::lround(static_cast<double>(steps) * k / kReferenceCheckpoints)));
    if (out.empty() || step > out.back()) out.push_back(step);
  }
  return out;
}

namespace {

// A copy of the loaded world (a scene loaded from text has no file to load again), stepped
// with `settings`, recorded after each checkpoint step.
std::vector<std::vector<phys::Vec3>> recordRun(const phys::World& loaded,
                                               const phys::SolverSettings& settings,
                                               const std::vector<int>& checkpoints) {
  phys::World world = loaded;
  world.setSolverSettings(settings);
  RunSpec spec;
  spec.steps = checkpoints.empty() ? 0 : checkpoints.back();
  spec.checkpoints = checkpoints;
  return runSteps(world, spec).positions;
}

std::string stepList(const std::vector<int>& steps) {
  std::string out;
  for (int s : steps) out += (out.empty() ? "" : ", ") + std::to_string(s);
  return out;
}

AccuracyTarget referenceTarget(const scenes::Scene& scene, double dt, int steps) {
  AccuracyTarget t;
  t.kind = "reference";
  t.checkpoints = spreadCheckpoints(steps);
  phys::SolverSettings fine = referenceSettings(scene.world, dt);
  t.expected = recordRun(scene.world, fine, t.checkpoints);
  phys::SolverSettings half = fine;
  half.substeps = fine.substeps / 2;
  const auto coarse = recordRun(scene.world, half, t.checkpoints);
  for (std::size_t k = 0; k < t.checkpoints.size(); ++k) {
    double worst = 0.0;
    for (std::size_t b = 0; b < t.expected[k].size(); ++b) {
      const double d = distance(t.expected[k][b], coarse[k][b]);
      worst = std::isfinite(d) ? std::max(worst, d) : kInf;
    }
    t.uncertainty.push_back(worst);
  }
  t.description = "reference: " + std::string(phys::toString(fine.method)) + ", " +
                  ixsWords(fine.iterations, fine.substeps) + " at dt " + formatNumber(dt) +
                  " s; checkpoints at steps " + stepList(t.checkpoints) +
                  " (t = " + formatNumber(t.checkpoints.front() * dt) + " to " +
                  formatNumber(t.checkpoints.back() * dt) + " s); its uncertainty (change from " +
                  std::to_string(half.substeps) + " substeps): " + formatNumber(t.uncertainty.front(), 2) +
                  " m at the first checkpoint, " + formatNumber(maxUncertainty(t), 2) + " m at most";
  return t;
}

}  // namespace

phys::SolverSettings referenceSettings(const phys::World& world, double dt) {
  phys::SolverSettings s = world.solverSettings();
  s.dt = dt;
  s.method = hasCompliance(world) ? phys::SolverMethod::Xpbd : phys::SolverMethod::Shake;
  s.substeps = std::min(kReferenceSubsteps, phys::kMaxSubsteps);
  s.iterations = kReferenceIterations;
  return s;
}

AccuracyTarget accuracyTarget(const scenes::Scene& scene, const scenes::LoadOptions&, double dt, int steps) {
  // The options were applied when `scene` was loaded; the reference steps a copy of that world,
  // so it has the same models without loading the file again.
  std::vector<PositionExpect> expects;
  for (const scenes::Expectation& e : scene.expectations) {
    const std::string* kind = e.find("kind");
    if (kind == nullptr || *kind != "position") continue;  // other kinds are other commands'
    const PositionExpect x = readExpect(scene, e, dt);
    for (const PositionExpect& earlier : expects) {
      if (earlier.slot == x.slot && earlier.step == x.step) {
        fail(scene, e, "at", "the same body and time as an earlier <expect kind=\"position\">");
      }
    }
    expects.push_back(x);
  }
  if (!expects.empty()) return analyticTarget(scene, expects, dt);
  return referenceTarget(scene, dt, std::max(1, steps));
}

double accuracyError(const AccuracyTarget& target, const std::vector<std::vector<phys::Vec3>>& positions) {
  if (positions.size() != target.expected.size()) return kInf;
  double worst = 0.0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (positions[k].size() != target.expected[k].size()) return kInf;
    for (std::size_t b = 0; b < positions[k].size(); ++b) {
      const phys::Vec3& want = target.expected[k][b];
      if (std::isnan(want.x)) continue;  // the target says nothing of this body here
      if (!finite(positions[k][b])) return kInf;
      worst = std::max(worst, distance(positions[k][b], want));
    }
  }
  return worst;
}

int stepsFor(const AccuracyTarget& target, int steps) {
  return target.checkpoints.empty() ? steps : std::max(steps, target.checkpoints.back());
}

double maxUncertainty(const AccuracyTarget& target) {
  double worst = 0.0;
  for (double u : target.uncertainty) worst = std::max(worst, u);
  return worst;
}

}  // namespace lab
