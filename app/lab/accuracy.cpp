#include "accuracy.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "bodies.h"
#include "expect_reader.h"
#include "numbers.h"
#include "run_metrics.h"
#include "runner.h"
#include "text.h"

// What "converged" means here. A reference is our own physics run so finely that the settings
// being judged cannot come near it: `shake`, 128 substeps of 4 passes, at the same dt (so a
// dt sweep compares each dt with its own reference, at the same checkpoint steps).
//  - shake, because it is the second-order method for sticks: on the 2 m pendulum released at
//    90 degrees its 64-substep run is 3.3e-7 m from the exact (elliptic-function) answer at
//    worst over 2 s and falls 16 times per 4 times the substeps, while gauss-seidel and xpbd,
//    whose projection bleeds energy at O(h), are still 0.011 m off at 64 substeps and 2.8e-3 m
//    at 256 (`lab sweep pendulum-exact --methods gauss-seidel,xpbd,shake --substeps 64,256`).
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

// ---- <expect kind="position"> ----------------------------------------------------------------

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

struct PositionExpect {
  std::size_t slot = 0;
  int step = 0;
  phys::Vec3 pos{0.0};
};

PositionExpect readExpect(ExpectReader& r, const scenes::Scene& scene, double dt) {
  // All known up front, so an unknown attribute is named before a missing one.
  for (const char* name : {"kind", "body", "at", "pos"}) r.find(name);
  r.rejectUnknown();
  PositionExpect x;
  const std::string& body = r.required("body");
  const std::optional<std::size_t> slot = bodySlot(scene, body);
  if (!slot) r.fail("body", "'" + body + "' names no box or loose particle of the scene");
  x.slot = *slot;

  const std::string& at = r.required("at");
  const std::optional<double> t = parseNumber(at);
  if (!t || *t <= 0.0) r.fail("at", "'" + at + "' must be a finite number > 0 (s)");
  // The run is compared at whole steps; an answer between two steps cannot be checked.
  const double steps = std::round(*t / dt);
  if (steps > kMaxSteps) {
    r.fail("at", "'" + at + "' s at the scene's dt " + formatNumber(dt) + " s is more than " +
                     std::to_string(kMaxSteps) + " steps");
  }
  // A time within round-off of 0 rounds to step 0, which no run's checkpoints reach.
  if (steps < 1) r.fail("at", "'" + at + "' s is before the first step of " + formatNumber(dt) + " s");
  if (std::abs(steps * dt - *t) > 1e-6 * dt) {
    r.fail("at", "'" + at + "' s is not a whole number of steps of " + formatNumber(dt) + " s");
  }
  x.step = static_cast<int>(steps);

  const std::string& pos = r.required("pos");
  const std::optional<phys::Vec3> p = parseVector(pos);
  if (!p) r.fail("pos", "'" + pos + "' must be three finite numbers (m)");
  // An answer beyond the bound is where no body can be (the guard freezes it first); its error
  // would overflow to the inf of a run that blew up.
  const double bound = scene.world.worldSettings().bound;
  if (!phys::insideBound(*p, bound))
    r.fail("pos", "'" + pos + "' is beyond the world's bound of " + formatNumber(bound) + " m");
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

// A copy of the loaded world (a scene loaded from text has no file to load again), stepped
// with `settings`, recorded after each checkpoint step; `froze` gets how many parts the guard froze.
std::vector<std::vector<phys::Vec3>> recordRun(const phys::World& loaded,
                                               const phys::SolverSettings& settings,
                                               const std::vector<int>& checkpoints, std::size_t& froze) {
  phys::World world = loaded;
  world.setSolverSettings(settings);
  const RunSpec spec{.steps = checkpoints.empty() ? 0 : checkpoints.back(), .checkpoints = checkpoints};
  std::vector<std::vector<phys::Vec3>> positions = runSteps(world, spec).positions;
  froze = world.freezes().size();
  return positions;
}

AccuracyTarget referenceTarget(const scenes::Scene& scene, double dt, int steps) {
  AccuracyTarget t;
  t.kind = "reference";
  t.checkpoints = spreadCheckpoints(steps);
  phys::SolverSettings fine = referenceSettings(scene.world, dt);
  std::size_t froze = 0, frozeCoarse = 0;
  t.expected = recordRun(scene.world, fine, t.checkpoints, froze);
  phys::SolverSettings half = fine;
  half.substeps = fine.substeps / 2;
  const auto coarse = recordRun(scene.world, half, t.checkpoints, frozeCoarse);
  for (std::size_t k = 0; k < t.checkpoints.size(); ++k) {
    double worst = 0.0;
    for (std::size_t b = 0; b < t.expected[k].size(); ++b) {
      keepLargest(worst, glm::length(t.expected[k][b] - coarse[k][b]));
    }
    // A reference the guard froze holds its parts where they went bad: two such runs can agree
    // (0 m) and both be meaningless, so its uncertainty is unknown, which reads as unbounded.
    t.uncertainty.push_back(froze + frozeCoarse > 0 ? kInf : worst);
  }
  t.description = "reference: " + std::string(phys::toString(fine.method)) + ", " +
                  ixsWords(fine.iterations, fine.substeps) + " at dt " + formatNumber(dt) +
                  " s; checkpoints at steps " + joinNumbers(t.checkpoints) +
                  " (t = " + formatNumber(t.checkpoints.front() * dt) + " to " +
                  formatNumber(t.checkpoints.back() * dt) + " s); its uncertainty (change from " +
                  std::to_string(half.substeps) + " substeps): ";
  if (froze + frozeCoarse == 0) {
    t.description += formatFigure(t.uncertainty.front(), " m", 2) + " at the first checkpoint, " +
                     formatFigure(maxUncertainty(t), " m", 2) + " at most";
  } else {
    t.description += "unknown, since the reference itself blew up (the guard froze " +
                     count(std::max(froze, frozeCoarse), "part", "parts") +
                     "), so no error measured against it means anything";
  }
  return t;
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

phys::SolverSettings referenceSettings(const phys::World& world, double dt) {
  phys::SolverSettings s = world.solverSettings();
  s.dt = dt;
  s.method = hasCompliance(world) ? phys::SolverMethod::Xpbd : phys::SolverMethod::Shake;
  s.substeps = std::min(kReferenceSubsteps, phys::kMaxSubsteps);
  s.iterations = kReferenceIterations;
  return s;
}

namespace {

// The scene's <expect kind="position"> elements, each checked at `dt`.
std::vector<PositionExpect> readExpects(const scenes::Scene& scene, double dt) {
  std::vector<PositionExpect> expects;
  for (const scenes::Expectation& e : scene.expectations) {
    const std::string* kind = e.find("kind");
    if (kind == nullptr || *kind != "position") continue;  // other kinds are other commands'
    ExpectReader r(e, scene.file.string(), "<expect kind=\"position\">");
    const PositionExpect x = readExpect(r, scene, dt);
    for (const PositionExpect& earlier : expects) {
      if (earlier.slot == x.slot && earlier.step == x.step) {
        r.fail("at", "the same body and time as an earlier <expect kind=\"position\">");
      }
    }
    expects.push_back(x);
  }
  return expects;
}

}  // namespace

std::vector<PositionAnswer> positionAnswers(const scenes::Scene& scene) {
  const double dt = scene.world.solverSettings().dt;
  std::vector<PositionAnswer> answers;
  for (const PositionExpect& x : readExpects(scene, dt)) answers.push_back({x.step * dt, x.pos});
  return answers;
}

AccuracyTarget accuracyTarget(const scenes::Scene& scene, double dt, int steps) {
  // The reference steps a copy of the loaded world, so it has the run's models without loading
  // the file again.
  const std::vector<PositionExpect> expects = readExpects(scene, dt);
  if (!expects.empty()) return analyticTarget(scene, expects, dt);
  return referenceTarget(scene, dt, std::max(1, steps));
}

int stepsToCover(const scenes::Scene& scene, double dt, int steps) {
  int last = 0;
  for (const PositionExpect& x : readExpects(scene, dt)) last = std::max(last, x.step);
  return std::max(steps, last);
}

double accuracyError(const AccuracyTarget& target, const std::vector<std::vector<phys::Vec3>>& positions) {
  if (positions.size() != target.expected.size()) return kInf;
  double worst = 0.0;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (positions[k].size() != target.expected[k].size()) return kInf;
    for (std::size_t b = 0; b < positions[k].size(); ++b) {
      const phys::Vec3& want = target.expected[k][b];
      if (std::isnan(want.x)) continue;  // the target says nothing of this body here
      if (!phys::finite(positions[k][b])) return kInf;
      worst = std::max(worst, glm::length(positions[k][b] - want));
    }
  }
  return worst;
}

int stepsFor(const AccuracyTarget& target, int steps) {
  return target.checkpoints.empty() ? steps : std::max(steps, target.checkpoints.back());
}

double maxUncertainty(const AccuracyTarget& target) {
  double worst = 0.0;  // std::max keeps it at 0 or above, and passes over a NaN
  for (double u : target.uncertainty) worst = std::max(worst, u);
  return worst;
}

}  // namespace lab
