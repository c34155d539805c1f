// libFuzzer target: the bytes are a scene file. A scene that loads must save, reload and come
// back as the same world, both as loaded and after a few steps (docs/architecture.md,
// "Fuzzing"). Anything else that goes wrong (a crash, a sanitizer report, an exception other
// than the loader's LoadError, a saved file that does not reload or reloads different) prints
// what and aborts, which libFuzzer records as a crash with the input that caused it.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include <pugixml.hpp>

#include "scenes/scene.h"
#include "scenes/scene_writer.h"
#include "world_compare.h"

namespace {

// The work budget. A fuzzed file may ask for a 20,100-box pyramid at 1000 substeps x 1000
// iterations: loading it takes seconds in this build and one step minutes. Two limits keep
// every input to milliseconds, so the fuzzer spends its time on many inputs rather than on a
// few large ones (the property does not depend on the count: a pyramid of 20 boxes saves as a
// pyramid of 20,000 does):
// - an input whose generators and bodies would make more than kMaxParticles particles is not
//   loaded (countParticles reads the counts from the XML first);
// - the harness estimates what a step costs and takes fewer than kMaxSteps steps, or none,
//   when they would be over kStepBudget.
constexpr double kMaxParticles = 10000;  // the largest seeds make 6,560 (pyramid-40) and 5,984
constexpr int kMaxSteps = 4;
// Estimated cost of a step in microseconds of this build (clang -O2, ASan, UBSan, coverage),
// fitted to the project's scenes (SCENE_FUZZ_VERBOSE prints estimate and time). A box costs far
// more than its sticks: the broad phase sorts it every step; its corners are ground contacts;
// boxes near each other run a separating-axis test and contact clipping every substep and
// project their contact points every pass. How many boxes touch is not known before stepping,
// so every box is costed as if it touched. On the project's scenes the measured time was from
// a tenth of the estimate (boxes falling free) to 4.5 times it (boxes resting on an incline):
// rough, but it tells 4 ms from 4 s, which is all the budget needs.
constexpr double kStepCost = 10.0;       // per step
constexpr double kSubstepCost = 5.0;     // per substep
constexpr double kVisitCost = 0.05;      // a particle integrated, a stick projected
constexpr double kLinkVisits = 4.0;      // a link moves up to 8 particles through weights
constexpr double kBoxStepCost = 40.0;    // per box per step: broad phase
constexpr double kBoxSubstepCost = 5.0;  // per box per substep: narrow phase, contacts
constexpr double kBoxPassCost = 20.0;    // per box per pass: its contact points
constexpr double kStepBudget = 40000.0;  // all steps of one input: 40 ms

double stepCost(const phys::World& world) {
  const phys::SolverSettings& s = world.solverSettings();
  const auto particles = static_cast<double>(world.particles().size());
  const auto sticks = static_cast<double>(world.sticks().size());
  const auto links = static_cast<double>(world.links().size());
  const auto boxes = static_cast<double>(world.bodies().size());
  const double pass = kVisitCost * (sticks + kLinkVisits * links) + kBoxPassCost * boxes;
  const double substep =
      kSubstepCost + kVisitCost * particles + kBoxSubstepCost * boxes + s.iterations * pass;
  return kStepCost + kBoxStepCost * boxes + s.substeps * substep;
}

// Steps within the budget: kMaxSteps if they fit, fewer if not, none if one step is over it.
int stepsWithinBudget(const phys::World& world) {
  const double fit = kStepBudget / stepCost(world);
  return fit >= kMaxSteps ? kMaxSteps : static_cast<int>(fit);
}

// A count as the XML gives it, for an estimate: 0 when it is missing or not a number (the
// loader refuses that anyway), the number otherwise (a fraction or an exponent the loader would
// refuse only makes the estimate larger).
double count(const char* text) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return end != text && std::isfinite(value) && value > 0.0 ? value : 0.0;
}

// An upper bound on the particles the scene's elements would make, or 0 when the text is not
// XML that the loader would parse (it then refuses it, quickly).
double countParticles(std::string_view input) {
  pugi::xml_document doc;
  if (!doc.load_buffer(input.data(), input.size(), pugi::parse_default, pugi::encoding_utf8)) return 0.0;
  double total = 0.0;
  for (const pugi::xml_node node : doc.document_element().children()) {
    const std::string_view kind = node.name();
    constexpr double kBox = 8.0;  // the corners model's particles; tetra has 4
    if (kind == "particle") {
      total += 1.0;
    } else if (kind == "box" || kind == "capsule") {
      total += kBox;
    } else if (kind == "ragdoll") {
      // Eleven capsules or ten boxes, of the corners model unless model="lean" (4 particles each).
      const double parts = std::string_view(node.attribute("shape").value()) == "capsule" ? 11.0 : 10.0;
      total += parts * (std::string_view(node.attribute("model").value()) == "lean" ? 4.0 : kBox);
    } else if (kind == "stack") {
      total += kBox * count(node.attribute("count").value());
    } else if (kind == "pyramid") {
      const double base = count(node.attribute("base").value());
      total += kBox * base * (base + 1.0) / 2.0;
    } else if (kind == "grid") {
      const char* text = node.attribute("count").value();
      double boxes = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        char* end = nullptr;
        const double n = std::strtod(text, &end);
        boxes *= end != text && std::isfinite(n) && n > 0.0 ? n : 0.0;
        text = end;
      }
      total += kBox * boxes;
    } else if (kind == "chain") {
      total += count(node.attribute("links").value()) + 1.0;
    }
  }
  return total;
}

// SCENE_FUZZ_VERBOSE=1: what each input holds, its estimated cost and where its time went,
// to fit the costs above (make fuzz-timing).
bool verbose() {
  static const bool on = std::getenv("SCENE_FUZZ_VERBOSE") != nullptr;
  return on;
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// At most `limit` characters of a text, for a report that stays readable.
std::string excerpt(std::string_view text, std::size_t limit = 4000) {
  if (text.size() <= limit) return std::string(text);
  return std::string(text.substr(0, limit)) + "\n[... " + std::to_string(text.size() - limit) +
         " more characters]";
}

[[noreturn]] void fail(const std::string& stage, const std::string& why, std::string_view input,
                       std::string_view saved = {}) {
  std::fprintf(stderr, "\n==== scene round trip failed %s ====\n%s\n---- input ----\n%s\n", stage.c_str(),
               why.c_str(), excerpt(input).c_str());
  if (!saved.empty()) std::fprintf(stderr, "---- saved ----\n%s\n", excerpt(saved).c_str());
  std::fflush(stderr);
  std::abort();
}

// Whether the writer may refuse this world. As loaded, only when the file would be larger
// than the loader reads (a 100-byte <grid> makes 100,000 boxes, whose file is far larger): a
// file that loads otherwise describes a world a file can hold, so load and save must agree
// (issue 12, item 4). After steps, also a number that is no longer finite (the writer's "which no scene file
// can hold"): a scene with magnitudes near the largest double can step into a velocity or pose that
// overflows, and refusing to write it is the writer's documented behaviour (scene_writer.h). Every other
// refusal names something no loaded scene can contain (a stick from a box's particle, a link
// across bodies or to itself, eye and target together) and is a failure.
bool mayRefuse(const std::invalid_argument& e, long steps) {
  const std::string_view why = e.what();
  // The file would be larger than the loader reads: the writer's refusal says so.
  if (why.find("a scene file loads at most") != std::string_view::npos) return true;
  return steps > 0 && why.find("which no scene file can hold") != std::string_view::npos;
}

// Where a round trip's time went (SCENE_FUZZ_VERBOSE).
struct TripTimes {
  double write = 0.0, reload = 0.0, compare = 0.0;  // ms
};

// Saves the scene, reloads the text and compares; aborts with a report on any failure.
TripTimes roundTrip(const scenes::Scene& scene, std::string_view input) {
  TripTimes times;
  const long steps = scene.world.stepCount();
  const std::string stage = steps == 0 ? "as loaded" : "after " + std::to_string(steps) + " steps";
  auto start = std::chrono::steady_clock::now();
  std::string saved;
  try {
    saved = scenes::writeSceneXml(scene);
  } catch (const std::invalid_argument& e) {
    if (mayRefuse(e, steps)) return times;
    fail(stage, std::string("writeSceneXml refused the world: ") + e.what(), input);
  } catch (const std::exception& e) {
    fail(stage, std::string("writeSceneXml threw: ") + e.what(), input);
  }
  times.write = millisecondsSince(start);
  start = std::chrono::steady_clock::now();
  std::optional<scenes::Scene> reloaded;
  try {
    reloaded.emplace(scenes::loadSceneText(saved, "saved.xml"));
  } catch (const std::exception& e) {
    fail(stage, std::string("the saved scene does not reload: ") + e.what(), input, saved);
  }
  times.reload = millisecondsSince(start);
  start = std::chrono::steady_clock::now();
  const std::string difference = testsupport::compareScenes(scene, *reloaded);
  if (!difference.empty()) fail(stage, "the reloaded world differs: " + difference, input, saved);
  times.compare = millisecondsSince(start);
  return times;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  if (countParticles(input) > kMaxParticles) return -1;  // -1: libFuzzer keeps it out of the corpus
  auto start = std::chrono::steady_clock::now();
  std::optional<scenes::Scene> scene;
  try {
    scene.emplace(scenes::loadSceneText(input, "input.xml"));
  } catch (const scenes::LoadError&) {
    return 0;  // refused with file, line and reason: what the loader is for
  } catch (const std::exception& e) {
    fail("on load", std::string("the loader threw something other than LoadError: ") + e.what(), input);
  }
  const double loadMs = millisecondsSince(start);

  const TripTimes first = roundTrip(*scene, input);
  const int steps = stepsWithinBudget(scene->world);
  start = std::chrono::steady_clock::now();
  try {
    for (int i = 0; i < steps; ++i) scene->world.step();
  } catch (const std::exception& e) {
    fail("while stepping", std::string("World::step threw: ") + e.what(), input);
  }
  const double stepMs = millisecondsSince(start);
  const TripTimes second = steps > 0 ? roundTrip(*scene, input) : TripTimes{};
  if (verbose()) {
    const phys::World& w = scene->world;
    std::fprintf(stderr,
                 "%-22s %7zu particles %7zu sticks %6zu links %6zu boxes %4d x %-4d cost %9.3g: %d steps "
                 "%8.2f ms (%4.2f of the estimate); load %7.2f ms; write, reload, compare %.2f %.2f %.2f + "
                 "%.2f %.2f %.2f ms\n",
                 scene->name.c_str(), w.particles().size(), w.sticks().size(), w.links().size(),
                 w.bodies().size(), w.solverSettings().substeps, w.solverSettings().iterations, stepCost(w),
                 steps, stepMs, steps > 0 ? stepMs * 1e3 / (steps * stepCost(w)) : 0.0, loadMs, first.write,
                 first.reload, first.compare, second.write, second.reload, second.compare);
  }
  return 0;
}
