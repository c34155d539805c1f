// The soak test's driver: picks a command by weight, draws its arguments, runs it on a
// sandbox::Session as the sandbox's keys, menus and panels would, and checks the invariants.
//
// The sequence of commands and of their arguments depends on the seed and on the session's
// state alone, never on timing: wall time only decides when to stop starting commands, so a
// failure reported as "seed S, command N" comes back with `soak --seed S` on any machine that
// runs the same build (another build of the physics gives other states, so other draws).
#include "soak.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <time.h>
#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "memory_watch.h"
#include "random.h"
#include "session.h"
#include "stats_text.h"
#include "step_budget.h"

namespace soak {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using phys::Vec3;

// ---------------------------------------------------------------------------------------------
// The commands, with their weights: how often each is drawn, out of the sum of the weights.
// Stepping is the most frequent because that is where NaNs are born; the rest are there to put
// the world into states stepping alone never reaches.

enum class Kind {
  Open,
  Reload,
  SaveAndOpen,
  Clear,
  ThrowBox,
  ThrowRagdoll,
  ThrowCapsuleRagdoll,
  Pick,
  Drag,
  Release,
  WorldSettings,
  SolverSettings,
  GravityKeys,
  DampingKeys,
  GravityMode,
  OverlayStart,
  OverlayStop,
  Refused,
  Step,
  Rewind,
  RecordingFile,
  Count
};

struct KindInfo {
  const char* name;
  int weight;
};

constexpr std::array<KindInfo, static_cast<std::size_t>(Kind::Count)> kKinds{{
    {"open", 6},      {"reload", 3},       {"save", 6},         {"clear", 2},        {"box", 4},
    {"ragdoll", 3},   {"capsules", 3},     {"pick", 5},         {"drag", 5},         {"release", 2},
    {"world", 5},     {"solver", 7},       {"gravity-keys", 2}, {"damping-keys", 2}, {"gravity-mode", 2},
    {"overlay", 3},   {"overlay-stop", 2}, {"refused", 4},      {"step", 30},        {"rewind", 4},
    {"recording", 2},
}};

/// Throws into one world stop here until the next open: enough for pile-ups, and it bounds the
/// world's size (and so the memory rules' working set) however long the run.
constexpr int kMaxThrowsPerEpisode = 40;
/// The recording's memory budget in the soak: small, so that the memory rules (a reopened scene
/// costs no more than the first time) see leaks, not keyframes a budget allows.
constexpr std::size_t kRecordingBudget = std::size_t{8} << 20;
/// Steps one step command takes at most (fewer when the budget says so).
constexpr int kMaxStepsPerCommand = 20;
/// Saving a recording steps every step it holds again: a recording whose steps would cost more than
/// this many step commands is not saved (0.5 to 2.5 s; the budget's unit, step_budget.h).
constexpr double kMaxVisitsPerRecordingSave = 10 * kMaxVisitsPerCommand;

/// An invariant that did not hold: what broke, in words.
class Broken : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

void expect(bool holds, const std::string& what) {
  if (!holds) throw Broken(what);
}

// ---------------------------------------------------------------------------------------------
// Text for the command log: every number as it was drawn (17 digits), so a command can be typed
// back in by hand.

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// One snprintf, not string concatenation: GCC 12's -Wrestrict warns, wrongly, on the inlined
// operator+ chain here (and CI builds with -Werror).
std::string vec(const Vec3& v) {
  char text[96];  // three %.17g of at most 24 characters each
  std::snprintf(text, sizeof text, "(%.17g %.17g %.17g)", v.x, v.y, v.z);
  return text;
}

std::string describe(const phys::WorldSettings& w) {
  std::string s = "gravity-mode=" + std::string(phys::toString(w.gravityMode)) +
                  " gravity=" + vec(w.gravity) + " gravity-point=" + vec(w.gravityPoint) +
                  " gravity-strength=" + num(w.gravityStrength) + " damping=" + num(w.damping) +
                  " bound=" + num(w.bound) + " ground=" + (w.ground ? "on" : "off");
  if (w.ground) {
    s += " ground-normal=" + vec(w.groundNormal) + " ground-height=" + num(w.groundHeight) +
         " static-friction=" + num(w.groundMaterial.staticFriction) +
         " dynamic-friction=" + num(w.groundMaterial.dynamicFriction);
  }
  return s;
}

std::string describe(const phys::SolverSettings& s) {
  return "method=" + std::string(phys::toString(s.method)) + " dt=" + num(s.dt) +
         " substeps=" + std::to_string(s.substeps) + " iterations=" + std::to_string(s.iterations) +
         " epsilon=" + num(s.featureEpsilon) + " slop=" + num(s.contactSlop) +
         " body-damping=" + num(s.bodyDamping) + " restitution=" + num(s.restitution) +
         " compliance=" + num(s.compliance) + " depenetration-speed=" + num(s.maxDepenetrationSpeed);
}

// ---------------------------------------------------------------------------------------------
// Comparisons.

/// |v| without overflow: glm::length squares the components, so past 1.3e154 it says inf.
double magnitude(const Vec3& v) {
  const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  return largest == 0.0 || !std::isfinite(largest) ? largest : largest * glm::length(v / largest);
}

/// v scaled to length 1, or zero when it has no direction that a double can say.
Vec3 unit(const Vec3& v) {
  const double m = magnitude(v);
  return m > 0.0 && std::isfinite(m) ? v / m : Vec3(0.0);
}

/// Counts by message, with at most kMaxKeys distinct messages (the rest as "other"), so the
/// soak's own bookkeeping stays small for the heap rule.
void tally(std::map<std::string, long>& counts, const std::string& message) {
  constexpr std::size_t kMaxKeys = 32;
  if (counts.size() >= kMaxKeys && counts.find(message) == counts.end())
    ++counts["other"];
  else
    ++counts[message];
}

// A save's refusal, to tally: the file's name taken out (each command saves to its own), cut short.
std::string refusalReason(const std::string& error, const fs::path& file) {
  std::string reason = error;
  if (const std::size_t at = reason.find(file.string()); at != std::string::npos)
    reason.replace(at, file.string().size(), "FILE");
  return reason.substr(0, 160);
}

bool sameVec(const Vec3& a, const Vec3& b, double tolerance = 0.0) {
  return magnitude(a - b) <= tolerance || a == b;
}

/// What a scene file can say of the world settings: a world without a ground saves no
/// <ground>, so its ground fields come back as the defaults; the loader makes the ground normal
/// a unit vector again (to within rounding).
bool sameWorld(const phys::WorldSettings& a, const phys::WorldSettings& b) {
  const bool same = a.gravityMode == b.gravityMode && a.gravity == b.gravity &&
                    a.gravityPoint == b.gravityPoint && a.gravityStrength == b.gravityStrength &&
                    a.damping == b.damping && a.bound == b.bound && a.ground == b.ground;
  if (!same || !a.ground) return same;
  return sameVec(a.groundNormal, b.groundNormal, 1e-12) && a.groundHeight == b.groundHeight &&
         a.groundMaterial.staticFriction == b.groundMaterial.staticFriction &&
         a.groundMaterial.dynamicFriction == b.groundMaterial.dynamicFriction;
}

bool sameSolver(const phys::SolverSettings& a, const phys::SolverSettings& b) {
  return a.method == b.method && a.dt == b.dt && a.substeps == b.substeps && a.iterations == b.iterations &&
         a.featureEpsilon == b.featureEpsilon && a.contactSlop == b.contactSlop &&
         a.bodyDamping == b.bodyDamping && a.restitution == b.restitution && a.compliance == b.compliance &&
         a.maxDepenetrationSpeed == b.maxDepenetrationSpeed && a.jointProjection == b.jointProjection;
}

/// Everything a refused command must leave as it was.
struct RunState {
  std::uint64_t hash = 0;
  phys::WorldSettings world;
  phys::SolverSettings solver;
  std::size_t boxes = 0, particles = 0, sticks = 0, links = 0;
  bool drag = false;
  Vec3 dragTarget{0.0};
};

struct SessionState {
  std::vector<RunState> runs;
  fs::path file;
  bool dragging = false;
};

SessionState snapshot(const sandbox::Session& session) {
  SessionState s;
  for (const sandbox::Run& run : session.runs()) {
    const phys::World& w = run.scene->world;
    RunState r;
    r.hash = w.stateHash();
    r.world = w.worldSettings();
    r.solver = w.solverSettings();
    r.boxes = w.bodies().size();
    r.particles = w.particles().size();
    r.sticks = w.sticks().size();
    r.links = w.jointCount();
    r.drag = w.drag().has_value();
    if (r.drag) r.dragTarget = w.drag()->target;
    s.runs.push_back(r);
  }
  s.file = session.file();
  s.dragging = session.dragging();
  return s;
}

/// "" when `after` is `before`; else what changed.
std::string changes(const SessionState& before, const SessionState& after) {
  if (before.runs.size() != after.runs.size()) {
    return "the overlay went from " + std::to_string(before.runs.size()) + " runs to " +
           std::to_string(after.runs.size());
  }
  if (before.file != after.file)
    return "the current file went from " + before.file.string() + " to " + after.file.string();
  if (before.dragging != after.dragging)
    return "the drag was " + std::string(before.dragging ? "let go" : "started");
  for (std::size_t i = 0; i < before.runs.size(); ++i) {
    const RunState &a = before.runs[i], &b = after.runs[i];
    const std::string run = "run " + std::to_string(i) + ": ";
    if (a.hash != b.hash) return run + "the particles moved";
    if (!sameWorld(a.world, b.world) || a.world.groundNormal != b.world.groundNormal)
      return run + "the world settings changed from " + describe(a.world) + " to " + describe(b.world);
    if (!sameSolver(a.solver, b.solver))
      return run + "the solver settings changed from " + describe(a.solver) + " to " + describe(b.solver);
    if (a.boxes != b.boxes || a.particles != b.particles || a.sticks != b.sticks || a.links != b.links)
      return run + "bodies or constraints were added or removed";
    if (a.drag != b.drag || a.dragTarget != b.dragTarget) return run + "the drag changed";
  }
  return {};
}

// ---------------------------------------------------------------------------------------------
// The crash handler's view of the command in progress, written before each command starts so a
// signal handler can print it without allocating.

char g_current[2048] = "soak: before the first command";

/// This process's CPU time. unit: s
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

const char* currentCommandForCrashReport() {
  return g_current;
}

namespace {

// ---------------------------------------------------------------------------------------------

/// The state of one failure, kept for the report and the reproducer.
struct Failure {
  long command = 0;
  std::string description;
  std::string what;
  fs::path folder;
};

class Soak {
 public:
  explicit Soak(const Options& options)
      : options_(options),
        random_(options.seed),
        memory_(options.seconds),
        sceneDir_(options.dataDir / "assets" / "scenes") {}

  int run();

 private:
  // The commands.
  void open();
  void reload();
  void saveAndOpen();
  void clear();
  void throwBody(Kind kind);
  void pick();
  void drag();
  void release();
  void worldSettings();
  void solverSettings();
  void gravityKeys();
  void dampingKeys();
  void pressKeys(Kind kind, const char* up, const char* down, double step, const std::string& setting,
                 const std::function<std::string(double)>& press);
  void gravityMode();
  void overlayStart();
  void overlayStop();
  void refused();
  void step();
  void collectBackgroundSteps(int expected);
  void rewind();
  void recordingFile();

  // Drawing arguments.
  phys::WorldSettings randomWorld();
  phys::SolverSettings randomSolver();
  double randomGravityStrength();
  std::string randomOverlayText();
  void moveCamera();
  Vec3 someBodyPoint();

  // Bookkeeping and checks.
  void begin(Kind kind, const std::string& description);
  void amend(const std::string& more);
  void startEpisode(const fs::path& file);
  void afterFreshOpen(const fs::path& file);
  void checkWorlds(bool poses = true);
  void checkUnchanged(const SessionState& before, const std::string& message);
  void fail(const std::string& what);
  bool recover();
  std::string summary(double seconds) const;
  bool isProjectScene(const fs::path& file) const;
  std::string shortName(const fs::path& file) const;
  sandbox::Session& session() { return *session_; }

  Options options_;
  Random random_;
  MemoryWatch memory_;
  fs::path sceneDir_;
  fs::path tempDir_;
  std::unique_ptr<sandbox::Session> session_;

  std::vector<fs::path> scenes_;  // every project scene, sorted
  std::vector<fs::path> cycle_;   // the order they are opened in, reshuffled after each round
  std::size_t nextInCycle_ = 0;

  // The camera the throws, picks and saves come from, as the user walks around.
  Vec3 eye_{0.0, 2.5, 7.0};
  Vec3 look_{0.0, -0.2, -1.0};

  // The episode: the file last opened and the commands since, which reproduce a failure.
  fs::path episodeFile_;
  std::vector<std::string> episode_;
  int throwsThisEpisode_ = 0;
  std::optional<phys::SolverSettings> overlayBase_;  // the main run's settings before the overlay

  long command_ = 0;
  std::string description_;
  std::array<long, static_cast<std::size_t>(Kind::Count)> counts_{};
  long steps_ = 0, lowered_ = 0, skipped_ = 0, overlaysStoppedForBudget_ = 0;
  long saves_ = 0, reopened_ = 0, reloads_ = 0, throwsCapped_ = 0;
  long recordingsSaved_ = 0, recordingsOverBudget_ = 0;
  std::map<std::string, long> saveRefusals_;  // by message, with the file name taken out
  std::map<std::string, long> freezeReasons_;
  std::vector<std::size_t> freezesSeen_;  // per run: freeze reports already counted
  std::vector<bool> opened_;              // per project scene
  std::vector<Failure> failures_;
  Clock::time_point start_ = Clock::now();
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  double longest_ = 0.0;  // s, the longest command's CPU time: the step budget's effect
  std::string longestCommand_;
};

// ---------------------------------------------------------------------------------------------
// Bookkeeping.

bool Soak::isProjectScene(const fs::path& file) const {
  return std::find(scenes_.begin(), scenes_.end(), file) != scenes_.end();
}

std::string Soak::shortName(const fs::path& file) const {
  if (isProjectScene(file)) return file.lexically_relative(sceneDir_).string();
  return file.string();
}

void Soak::begin(Kind kind, const std::string& description) {
  description_ = description;
  ++counts_[static_cast<std::size_t>(kind)];
  episode_.push_back("#" + std::to_string(command_) + " " + description);
  std::snprintf(g_current, sizeof g_current, "soak: seed %llu, command #%ld: %s",
                static_cast<unsigned long long>(options_.seed), command_, description.c_str());
  if (options_.verbose) {
    std::printf("#%ld %s\n", command_, description.c_str());
    std::fflush(stdout);
  }
}

/// Adds to the description of the command in progress what it turned out to do.
void Soak::amend(const std::string& more) {
  description_ += more;
  episode_.back() += more;
  std::snprintf(g_current, sizeof g_current, "soak: seed %llu, command #%ld: %s",
                static_cast<unsigned long long>(options_.seed), command_, description_.c_str());
  if (options_.verbose) std::printf("    %s\n", more.c_str());
}

void Soak::startEpisode(const fs::path& file) {
  // A file saved by an earlier episode is no longer needed once another file is open.
  if (!episodeFile_.empty() && episodeFile_ != file && episodeFile_.parent_path() == tempDir_) {
    std::error_code ignored;
    fs::remove(episodeFile_, ignored);
  }
  episodeFile_ = file;
  episode_.clear();
  throwsThisEpisode_ = 0;
  overlayBase_.reset();
  freezesSeen_.assign(1, 0);
}

void Soak::afterFreshOpen(const fs::path& file) {
  if (!isProjectScene(file)) return;
  opened_[static_cast<std::size_t>(std::find(scenes_.begin(), scenes_.end(), file) - scenes_.begin())] = true;
  const std::string why = memory_.afterFreshOpen(shortName(file), elapsed());
  expect(why.empty(), why);
}

/// The invariants every command must leave true: every particle where a number can say, every
/// box's pose too, the Stats panel's figures not NaN, a drag line that can be drawn. Also counts
/// the guard's freezes, which are allowed (that is its job) but worth reporting.
void Soak::checkWorlds(bool poses) {
  const std::span<const sandbox::Run> runs = session().runs();
  freezesSeen_.resize(runs.size(), 0);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const phys::World& w = runs[r].scene->world;
    const std::string run = runs.size() > 1 ? "run " + std::to_string(r) + ": " : "";
    const phys::Particles& p = w.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!phys::finite(p.position[i]) || !phys::finite(p.previous[i])) {
        const auto id = static_cast<phys::ParticleId>(i);
        throw Broken(run + "particle " + std::to_string(i) + " ('" + w.particleName(id) + "') is at " +
                     vec(p.position[i]) + ", previous " + vec(p.previous[i]) +
                     (p.inverseMass[i] == 0.0 ? " (pinned or frozen)" : ""));
      }
    }
    const std::span<const phys::FreezeReport> freezes = w.freezes();
    for (std::size_t f = freezesSeen_[r]; f < freezes.size(); ++f) tally(freezeReasons_, freezes[f].reason);
    freezesSeen_[r] = freezes.size();
    if (!poses) continue;
    for (std::size_t b = 0; b < w.bodies().size(); ++b) {
      const phys::BodyPose pose = w.bodyPose(static_cast<phys::BodyId>(b));
      const bool finite = phys::finite(pose.center) && std::isfinite(pose.orientation.w) &&
                          std::isfinite(pose.orientation.x) && std::isfinite(pose.orientation.y) &&
                          std::isfinite(pose.orientation.z);
      if (!finite) {
        const phys::Body& box = w.bodies()[b];
        // How far apart its particles are tells a box flung out of range from one crushed flat.
        double nearest = std::numeric_limits<double>::infinity(), farthest = 0.0;
        for (int i = 0; i < box.particleCount; ++i) {
          for (int j = i + 1; j < box.particleCount; ++j) {
            const double d = magnitude(p.position[box.firstParticle + static_cast<std::size_t>(i)] -
                                       p.position[box.firstParticle + static_cast<std::size_t>(j)]);
            nearest = std::min(nearest, d);
            farthest = std::max(farthest, d);
          }
        }
        throw Broken(run + "box " + std::to_string(b) + " ('" + box.name + "') has the pose centre " +
                     vec(pose.center) + ", orientation (" + num(pose.orientation.w) + " " +
                     num(pose.orientation.x) + " " + num(pose.orientation.y) + " " + num(pose.orientation.z) +
                     "); its " + std::to_string(box.particleCount) + " particles are " + num(nearest) +
                     " to " + num(farthest) + " m apart, its size " + vec(box.halfExtents * 2.0) +
                     (p.inverseMass[box.firstParticle] == 0.0 ? " (frozen by the guard or pinned)" : ""));
      }
    }
    // The figures as the Stats panel shows them. The metrics themselves may overflow in an absurd
    // world (docs/physics.md, "Metrics": the energies under a gravity of 1e308 m/s^2); what the
    // user reads must say so, never print nan or inf.
    for (const sandbox::StatsLine& line : sandbox::statsLines(w)) {
      std::string text = line.text;
      if (line.warning) {  // names a body, and a body may be called anything
        const std::string& name = w.freezes().back().name;
        if (const std::size_t at = text.find(name); at != std::string::npos) text.erase(at, name.size());
      }
      expect(text.find("nan") == std::string::npos && text.find("inf") == std::string::npos,
             run + "the Stats panel shows a non-finite figure: " + line.text);
    }
  }
  if (const auto line = session().dragLine()) {
    expect(phys::finite(line->first) && phys::finite(line->second),
           "the drag line runs from " + vec(line->first) + " to " + vec(line->second));
  }
}

/// `what` did nothing, or was refused: then nothing may have changed.
void Soak::checkUnchanged(const SessionState& before, const std::string& what) {
  const std::string changed = changes(before, snapshot(session()));
  expect(changed.empty(), what + ", yet the state changed: " + changed);
}

// ---------------------------------------------------------------------------------------------
// Arguments.

/// Where the user walks: about the scene, up to a body, or far out (as far as the far-1e5 scene).
/// Never past 1e5 m: at 16 m/s nobody walks farther, and a scene file's camera must lie within
/// the world's bound anyway. (Bodies do go farther, when huge gravity flings them.)
void Soak::moveCamera() {
  constexpr double kFarthest = 1e5;  // m
  const double where = random_.uniform();
  const Vec3 body = someBodyPoint();
  if (where < 0.35 && magnitude(body) < kFarthest) {  // close to a body
    const Vec3 away = random_.unitVector();
    eye_ = body + away * random_.uniform(1.5, 10);
  } else if (where < 0.95) {  // walking about the scene
    eye_ = Vec3{random_.uniform(-12, 12), random_.uniform(0.3, 8), random_.uniform(-12, 12)};
  } else {  // walked far away
    const Vec3 away = random_.unitVector();
    eye_ = away * random_.logUniform(1e3, kFarthest);
  }
  // Mostly at something, sometimes anywhere.
  const Vec3 at = random_.chance(0.8) ? someBodyPoint() : eye_ + random_.unitVector();
  look_ = magnitude(at - eye_) > 1e-6 ? unit(at - eye_) : Vec3(0, 0, -1);
}

/// A point on or near a body of the main run, or near the origin in an empty world.
Vec3 Soak::someBodyPoint() {
  const phys::World& w = session().scene().world;
  const Vec3 jitterDirection = random_.unitVector();
  const Vec3 jitter = jitterDirection * random_.uniform(0, 0.3);
  if (!w.bodies().empty() && random_.chance(0.8)) {
    const phys::BodyPose pose = w.bodyPose(static_cast<phys::BodyId>(random_.index(w.bodies().size())));
    if (phys::finite(pose.center)) return pose.center + jitter;
  }
  if (w.particles().size() > 0) return w.particles().position[random_.index(w.particles().size())] + jitter;
  return Vec3(0, 1, 0) + jitter;
}

double Soak::randomGravityStrength() {
  const double u = random_.uniform();
  // Huge values are rare on purpose: they freeze everything they touch, and a world where
  // everything is frozen tests little else.
  if (u < 0.1) return 0.0;
  if (u < 0.55) return random_.uniform(0, 30);
  if (u < 0.92) return random_.logUniform(1e-3, 1e6);
  if (u < 0.98) return random_.logUniform(1e6, 1e300);  // huge
  return std::numeric_limits<double>::max();            // the largest finite
}

/// Every field of phys::WorldSettings, valid (validate() accepts it), its extremes included.
phys::WorldSettings Soak::randomWorld() {
  phys::WorldSettings w = session().scene().world.worldSettings();
  w.gravityMode = random_.chance(0.5) ? phys::GravityMode::Uniform : phys::GravityMode::Point;
  const Vec3 direction = random_.chance(0.7) ? Vec3(0, -1, 0) : random_.unitVector();
  // At the largest finite strength along a slant the components are finite (valid) but the
  // vector's length overflows: an extreme validate() accepts.
  w.gravity = direction * randomGravityStrength();
  w.gravityPoint = random_.chance(0.9)
                       ? Vec3{random_.uniform(-20, 20), random_.uniform(-5, 20), random_.uniform(-20, 20)}
                       : random_.unitVector() * 1e6;
  w.gravityStrength = randomGravityStrength();
  const double d = random_.uniform();
  w.damping = d < 0.3   ? 0.0
              : d < 0.7 ? random_.uniform(0, 2)
              : d < 0.9 ? random_.logUniform(1e-3, 1e3)
                        : random_.logUniform(1e3, 1e300);
  w.ground = random_.chance(0.85);
  w.groundNormal = random_.chance(0.7) ? Vec3(0, 1, 0)
                   : random_.chance(0.8)
                       ? glm::normalize(Vec3{random_.uniform(-0.5, 0.5), 1.0, random_.uniform(-0.5, 0.5)})
                       : random_.unitVector();
  w.groundHeight = random_.chance(0.7)   ? 0.0
                   : random_.chance(0.9) ? random_.uniform(-5, 5)
                                         : random_.uniform(-1e3, 1e3);
  auto friction = [&] {
    const double f = random_.uniform();
    return f < 0.1 ? 0.0 : f < 0.9 ? random_.uniform(0, 2) : random_.logUniform(2, 1e6);
  };
  w.groundMaterial.staticFriction = friction();
  w.groundMaterial.dynamicFriction = friction();
  const double b = random_.uniform();
  w.bound = b < 0.85   ? 1e6
            : b < 0.9  ? random_.logUniform(1, 1e3)
            : b < 0.95 ? random_.logUniform(1e6, 1e300)
                       : std::numeric_limits<double>::infinity();
  return w;
}

/// Every field of phys::SolverSettings, valid, its extremes included: 1000 substeps and
/// iterations, dt from 1e-6 to 1 s, compliance up to 1e6 m/N, no depenetration limit.
phys::SolverSettings Soak::randomSolver() {
  phys::SolverSettings s = session().scene().world.solverSettings();
  s.method = static_cast<phys::SolverMethod>(random_.integer(0, 3));
  auto count = [&](int limit) {
    const double u = random_.uniform();
    return u < 0.1 ? limit : u < 0.2 ? 1 : u < 0.7 ? random_.integer(1, 16) : random_.logInteger(1, limit);
  };
  s.substeps = count(phys::kMaxSubsteps);
  s.iterations = count(phys::kMaxIterations);
  const double t = random_.uniform();
  s.dt = t < 0.12   ? phys::kMinDt
         : t < 0.24 ? phys::kMaxDt
         : t < 0.55 ? 1.0 / random_.pick(std::vector<double>{30, 60, 120, 240})
                    : random_.logUniform(phys::kMinDt, phys::kMaxDt);
  const double e = random_.uniform();
  s.featureEpsilon = e < 0.1 ? 0.0 : e < 0.2 ? random_.logUniform(0.1, 10) : random_.logUniform(1e-5, 0.1);
  const double sl = random_.uniform();
  s.contactSlop = sl < 0.1 ? 0.0 : sl < 0.15 ? random_.logUniform(0.01, 1) : random_.logUniform(1e-6, 0.01);
  auto share = [&] {
    const double u = random_.uniform();
    return u < 0.15 ? 0.0 : u < 0.3 ? 1.0 : random_.uniform();
  };
  s.bodyDamping = share();
  s.restitution = share();
  const double c = random_.uniform();
  s.compliance = c < 0.3   ? 0.0
                 : c < 0.4 ? phys::kMaxCompliance
                           : random_.logUniform(1e-12, phys::kMaxCompliance);
  const double v = random_.uniform();
  s.maxDepenetrationSpeed = v < 0.1    ? std::numeric_limits<double>::infinity()
                            : v < 0.15 ? random_.logUniform(1e-9, 1e-3)
                            : v < 0.2  ? random_.logUniform(1e3, 1e300)
                                       : random_.logUniform(0.1, 100);
  s.jointProjection.enabled = random_.chance(0.5);
  s.jointProjection.tolerance = random_.logUniform(1e-9, 1.0);
  s.jointProjection.iterations = count(phys::kMaxProjectionIterations);
  return s;
}

/// 1 to 4 of the overlay's keys, with valid values, as a user types them.
std::string Soak::randomOverlayText() {
  const phys::SolverSettings s = randomSolver();
  std::vector<std::string> items{
      "method=" + std::string(phys::toString(s.method)),
      "iterations=" + std::to_string(s.iterations),
      "substeps=" + std::to_string(s.substeps),
      "dt=" + num(s.dt),
      "body-damping=" + num(s.bodyDamping),
      "restitution=" + num(s.restitution),
      "compliance=" + num(s.compliance),
      "epsilon=" + num(s.featureEpsilon),
      "slop=" + num(s.contactSlop),
      // The overlay's text takes finite numbers only; "none" is the scene file's word.
      "depenetration-speed=" + num(std::isfinite(s.maxDepenetrationSpeed) ? s.maxDepenetrationSpeed : 1e9),
  };
  random_.shuffle(items);
  const int keys = random_.integer(1, 4);
  std::string text;
  for (int i = 0; i < keys; ++i) text += (i ? "," : "") + items[static_cast<std::size_t>(i)];
  return text;
}

// ---------------------------------------------------------------------------------------------
// The commands.

void Soak::open() {
  const fs::path file = cycle_[nextInCycle_];
  if (++nextInCycle_ == cycle_.size()) {
    random_.shuffle(cycle_);
    nextInCycle_ = 0;
  }
  // Keys 1, 2, 3 and `sandbox NAME` open a scene by name; the file menu by path.
  const bool byName = file.parent_path() == sceneDir_ && random_.chance(0.25);
  const std::string name = file.stem().string();
  begin(Kind::Open, byName ? "open by name " + name : "open " + shortName(file));
  const std::string error = byName ? session().openBuiltin(name) : session().open(file);
  expect(error.empty(), "a project scene did not open: " + error);
  expect(session().file() == file,
         "opened " + file.string() + " but the current file is " + session().file().string());
  expect(!session().overlayActive() && !session().dragging(), "a fresh scene kept the overlay or the drag");
  startEpisode(file);
  checkWorlds();
  afterFreshOpen(file);
}

void Soak::reload() {
  const fs::path file = session().file();
  begin(Kind::Reload, "reload " + shortName(file));
  // The current file loaded before (or was saved and reopened), so it must load again.
  const std::string error = session().reload();
  expect(error.empty(), "reload of a file that loaded before failed: " + error);
  ++reloads_;
  startEpisode(file);
  checkWorlds();
  afterFreshOpen(file);
}

void Soak::saveAndOpen() {
  if (random_.chance(0.5)) moveCamera();
  fs::path file = tempDir_ / ("saved-" + std::to_string(command_) + ".xml");
  const bool overwrite = session().file().parent_path() == tempDir_ && random_.chance(0.3);
  if (overwrite) file = session().file();  // Save As over the file it came from
  scenes::CameraStart camera;
  camera.eye = glm::vec3(eye_);
  camera.target = glm::vec3(eye_ + look_ * 5.0);
  begin(Kind::SaveAndOpen, "save as " + file.filename().string() + " with the camera at " + vec(eye_) +
                               " looking along " + vec(look_) + ", then open it");

  // What the reloaded world must match.
  const phys::World& w = session().scene().world;
  const SessionState before = snapshot(session());
  const phys::WorldSettings world = w.worldSettings();
  const phys::SolverSettings solver = session().savedSolverSettings();  // during the overlay, not run 0's
  const std::size_t boxes = w.bodies().size(), particles = w.particles().size(), sticks = w.sticks().size(),
                    links = w.links().size(), rigidLinks = w.rigidLinks().size(),
                    joints = w.rigidJoints().size(), ignored = w.ignoredCollisions().size();
  std::vector<phys::BodyPose> poses;
  for (std::size_t b = 0; b < boxes; ++b) poses.push_back(w.bodyPose(static_cast<phys::BodyId>(b)));
  std::vector<Vec3> loose;  // particles of no box: their positions reload exactly
  std::vector<bool> inBox(particles, false);
  for (const phys::Body& box : w.bodies())
    std::fill_n(inBox.begin() + box.firstParticle, box.particleCount, true);
  for (std::size_t i = 0; i < particles; ++i)
    loose.push_back(inBox[i] ? Vec3(0.0) : w.particles().position[i]);
  std::string oldText;
  if (overwrite) oldText = (std::stringstream() << std::ifstream(file).rdbuf()).str();

  const std::string error = session().saveAs(file, camera);
  if (!error.empty()) {
    // A world no scene file can express is refused, and then nothing may change: not the
    // session, not the file on disk.
    tally(saveRefusals_, refusalReason(error, file));
    checkUnchanged(before, "Save As was refused (\"" + error + "\")");
    if (overwrite) {
      const std::string nowText = (std::stringstream() << std::ifstream(file).rdbuf()).str();
      expect(nowText == oldText, "a refused Save As changed the file it refused to replace: " + error);
    } else {
      expect(!fs::exists(file), "a refused Save As left a file behind: " + error);
    }
    return;
  }
  ++saves_;
  expect(session().file() == file, "after Save As the current file is " + session().file().string());
  const std::string reopenError = session().open(file);
  expect(reopenError.empty(), "a scene saved by Save As does not reload: " + reopenError);
  ++reopened_;

  const phys::World& back = session().scene().world;
  auto count = [](const char* what, std::size_t was, std::size_t is) {
    expect(was == is, "the reloaded world has " + std::to_string(is) + " " + what + ", the saved one " +
                          std::to_string(was));
  };
  count("boxes", boxes, back.bodies().size());
  count("particles", particles, back.particles().size());
  count("sticks", sticks, back.sticks().size());
  count("links", links, back.links().size());
  count("links with a rigid end", rigidLinks, back.rigidLinks().size());
  count("joints", joints, back.rigidJoints().size());
  count("pairs kept from colliding", ignored, back.ignoredCollisions().size());
  expect(sameWorld(world, back.worldSettings()), "the world settings did not survive the file: saved " +
                                                     describe(world) + ", reloaded " +
                                                     describe(back.worldSettings()));
  expect(sameSolver(solver, back.solverSettings()), "the solver settings did not survive the file: saved " +
                                                        describe(solver) + ", reloaded " +
                                                        describe(back.solverSettings()));
  // docs/scene-format.md: a box is saved as the pose fitted to its particles, a loose particle
  // where it is. Allow rounding: 1e-9 of the distance from the origin (at least 1 nm), 1e-6 rad.
  for (std::size_t b = 0; b < boxes; ++b) {
    const phys::BodyPose now = back.bodyPose(static_cast<phys::BodyId>(b));
    const double tolerance = 1e-9 * std::max(1.0, magnitude(poses[b].center));
    const double turn =
        2.0 * std::acos(std::min(1.0, std::abs(glm::dot(now.orientation, poses[b].orientation))));
    expect(sameVec(now.center, poses[b].center, tolerance) && turn <= 1e-6,
           "box " + std::to_string(b) + " ('" + back.bodies()[b].name + "') was saved at " +
               vec(poses[b].center) + " and reloads at " + vec(now.center) + ", turned by " + num(turn) +
               " rad");
  }
  for (std::size_t i = 0; i < particles; ++i) {
    if (inBox[i]) continue;
    const Vec3& now = back.particles().position[i];
    expect(
        sameVec(now, loose[i], 1e-12 * std::max(1.0, magnitude(loose[i]))),
        "particle " + std::to_string(i) + " was saved at " + vec(loose[i]) + " and reloads at " + vec(now));
  }
  startEpisode(file);
  checkWorlds();
}

void Soak::clear() {
  begin(Kind::Clear, "clear");
  const SessionState before = snapshot(session());
  session().clear();
  const SessionState after = snapshot(session());
  for (std::size_t i = 0; i < after.runs.size(); ++i) {
    const RunState& r = after.runs[i];
    expect(r.boxes == 0 && r.particles == 0 && r.sticks == 0 && r.links == 0 && !r.drag,
           "run " + std::to_string(i) + " still has bodies or a drag after clear");
    expect(sameWorld(r.world, before.runs[i].world) && sameSolver(r.solver, before.runs[i].solver),
           "clear changed the settings of run " + std::to_string(i));
  }
  expect(!session().dragging(), "clear kept the drag");
  checkWorlds();
}

void Soak::throwBody(Kind kind) {
  if (random_.chance(0.6)) moveCamera();
  const Vec3 at = eye_ + look_ * 2.0;  // as the sandbox throws: 2 m in front of the eye
  const Vec3 velocity = look_ * sandbox::kThrowSpeed;
  const char* what = kind == Kind::ThrowBox       ? "box"
                     : kind == Kind::ThrowRagdoll ? "ragdoll"
                                                  : "capsule ragdoll";
  if (throwsThisEpisode_ >= kMaxThrowsPerEpisode) {
    begin(kind, std::string("throw a ") + what + ": skipped, " + std::to_string(kMaxThrowsPerEpisode) +
                    " thrown since the scene opened");
    ++throwsCapped_;
    return;
  }
  begin(kind, std::string("throw a ") + what + " from " + vec(at) + " at " + vec(velocity) + " m/s");
  ++throwsThisEpisode_;
  std::vector<std::size_t> boxesBefore;
  for (const sandbox::Run& run : session().runs()) boxesBefore.push_back(run.scene->world.bodies().size());
  const SessionState before = snapshot(session());
  const std::string refused = kind == Kind::ThrowBox
                                  ? session().spawnBox(at, velocity)
                                  : session().spawnRagdoll(at, velocity, kind == Kind::ThrowCapsuleRagdoll);
  if (!refused.empty()) {
    // Refused: bodies in the way of every try, or the place it would go is beyond the world's
    // bound (after the bound was lowered; a throw moved up out of a crowd can cross it too).
    // Nothing changes.
    const double bound = session().scene().world.worldSettings().bound;
    const double lift = 2.0 * sandbox::kRagdollThrowRoom * (sandbox::kThrowTries - 1);
    const bool crowded = refused.rfind("nothing thrown: bodies in the way", 0) == 0;
    expect(crowded || std::abs(at.x) > bound || at.y + lift > bound || std::abs(at.y) > bound ||
               std::abs(at.z) > bound,
           "a throw inside the world's bound was refused: " + refused);
    const std::string changed = changes(before, snapshot(session()));
    expect(changed.empty(), "a refused throw changed something: " + changed);
    checkWorlds();
    return;
  }
  const std::size_t added = kind == Kind::ThrowBox ? 1 : kind == Kind::ThrowRagdoll ? 10 : 11;
  for (std::size_t i = 0; i < boxesBefore.size(); ++i) {
    const std::size_t now = session().runs()[i].scene->world.bodies().size();
    expect(now == boxesBefore[i] + added, "run " + std::to_string(i) + " got " +
                                              std::to_string(now - boxesBefore[i]) + " bodies instead of " +
                                              std::to_string(added));
  }
  checkWorlds();
}

void Soak::pick() {
  if (random_.chance(0.5)) moveCamera();
  Vec3 origin = eye_, direction;
  const double u = random_.uniform();
  std::string how;
  if (u < 0.75) {  // at a body, as a user clicks on one; rays need not be unit length
    direction = unit(someBodyPoint() - eye_);
    if (random_.chance(0.2)) direction *= random_.logUniform(1e-3, 1e3);
  } else if (u < 0.9) {  // anywhere
    direction = random_.unitVector();
  } else {  // what a zero-sized window or a broken matrix gives
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const int which = random_.integer(0, 2);
    direction = which == 0 ? Vec3(0.0) : which == 1 ? Vec3(nan, 0, 1) : random_.unitVector();
    if (which == 2) origin = Vec3(std::numeric_limits<double>::infinity(), 0, 0);
    how = " (not a ray)";
  }
  begin(Kind::Pick, "pick along the ray from " + vec(origin) + " towards " + vec(direction) + how);
  const SessionState before = snapshot(session());
  const bool hit = session().pick(origin, direction);
  if (!how.empty()) expect(!hit, "a ray that is not a ray picked something");
  if (!hit) {
    checkUnchanged(before, "the pick hit nothing");
  } else {
    expect(session().dragging(), "a pick that hit leaves no drag");
    for (const sandbox::Run& run : session().runs())
      expect(run.scene->world.drag().has_value(), "a pick that hit did not set the drag in every run");
  }
  checkWorlds();
}

void Soak::drag() {
  Vec3 direction;
  std::string how;
  const auto line = session().dragLine();
  if (random_.chance(0.9)) {
    const Vec3 offset = random_.unitVector();
    const Vec3 towards = (line ? line->second : eye_ + look_ * 5.0) + offset * random_.uniform(0, 3);
    direction = unit(towards - eye_);
    if (random_.chance(0.1)) direction = glm::cross(look_, random_.unitVector());  // along the plane
  } else {
    direction = random_.chance(0.5) ? Vec3(0.0) : Vec3(std::numeric_limits<double>::quiet_NaN(), 1, 0);
    how = " (not a ray)";
  }
  begin(Kind::Drag, "drag along the ray from " + vec(eye_) + " towards " + vec(direction) + how +
                        (session().dragging() ? "" : " (nothing picked)"));
  const SessionState before = snapshot(session());
  session().dragAlong(eye_, direction);
  if (!before.dragging) checkUnchanged(before, "a drag with nothing picked");
  checkWorlds();
}

void Soak::release() {
  begin(Kind::Release, session().dragging() ? "release" : "release (nothing picked)");
  session().release();
  expect(!session().dragging(), "still dragging after release");
  for (const sandbox::Run& run : session().runs())
    expect(!run.scene->world.drag().has_value(), "a run still has a drag after release");
  checkWorlds();
}

void Soak::worldSettings() {
  const phys::WorldSettings s = randomWorld();
  begin(Kind::WorldSettings, "world settings " + describe(s));
  expect(phys::validate(s).empty(), "the soak drew invalid world settings: " + phys::validate(s));
  const std::string error = session().setWorldSettings(s);
  expect(error.empty(), "valid world settings were refused: " + error);
  for (const sandbox::Run& run : session().runs()) {
    expect(sameWorld(run.scene->world.worldSettings(), s),
           "a run has the world settings " + describe(run.scene->world.worldSettings()));
  }
  checkWorlds();
}

void Soak::solverSettings() {
  const phys::SolverSettings s = randomSolver();
  begin(Kind::SolverSettings, "solver settings " + describe(s));
  expect(phys::validate(s).empty(), "the soak drew invalid solver settings: " + phys::validate(s));
  const std::string error = session().setSolverSettings(s);
  expect(error.empty(), "valid solver settings were refused: " + error);
  expect(sameSolver(session().scene().world.solverSettings(), s),
         "run 0 has the solver settings " + describe(session().scene().world.solverSettings()));
  checkWorlds();
}

// One of a pair of keys, up or down by `step`, pressed 1 to 25 times: each press accepted, and
// what it changes (`setting`) changed in every run.
void Soak::pressKeys(Kind kind, const char* up, const char* down, double step, const std::string& setting,
                     const std::function<std::string(double)>& press) {
  const double delta = random_.chance(0.5) ? step : -step;
  const int presses = random_.integer(1, 25);
  begin(kind, std::string(delta > 0 ? up : down) + " pressed " + std::to_string(presses) + " times");
  for (int i = 0; i < presses; ++i) {
    const std::string error = press(delta);
    expect(error.empty(), "a " + setting + " key was refused: " + error);
  }
  const phys::WorldSettings& w = session().scene().world.worldSettings();
  for (const sandbox::Run& run : session().runs())
    expect(sameWorld(run.scene->world.worldSettings(), w),
           "the " + setting + " keys did not act on every run");
}

void Soak::gravityKeys() {
  pressKeys(Kind::GravityKeys, "Y", "H", 1.0, "gravity",
            [&](double d) { return session().changeGravity(d); });
  const phys::WorldSettings& w = session().scene().world.worldSettings();
  expect(w.gravityStrength >= 0.0 && phys::finite(w.gravity), "gravity is " + describe(w));
  checkWorlds();
}

void Soak::dampingKeys() {
  pressKeys(Kind::DampingKeys, "U", "J", 0.1, "damping",
            [&](double d) { return session().changeDamping(d); });
  const phys::WorldSettings& w = session().scene().world.worldSettings();
  expect(w.damping >= 0.0, "damping is " + num(w.damping));
  checkWorlds();
}

void Soak::gravityMode() {
  begin(Kind::GravityMode, "G (gravity mode)");
  const phys::WorldSettings before = session().scene().world.worldSettings();
  const std::string error = session().toggleGravityMode();
  expect(error.empty(), "G was refused: " + error);
  const phys::WorldSettings& after = session().scene().world.worldSettings();
  // docs/sandbox.md: "Switching keeps the strength". In long double, whose range is far wider:
  // a vector of strength 1.8e308 along a slant may round to a length just past the largest double.
  auto strength = [](const phys::WorldSettings& w) -> long double {
    if (w.gravityMode == phys::GravityMode::Point) return w.gravityStrength;
    const long double x = w.gravity.x, y = w.gravity.y, z = w.gravity.z;
    return std::sqrt(x * x + y * y + z * z);
  };
  const long double was = strength(before), is = strength(after);
  expect(after.gravityMode != before.gravityMode, "G did not switch the gravity mode (status: \"" +
                                                      session().status() + "\"; " + describe(before) + ")");
  expect(std::abs(is - was) <= 1e-12L * std::max(1.0L, was),
         "G changed the strength of gravity from " + num(static_cast<double>(was)) + " to " +
             num(static_cast<double>(is)) + " (" + describe(before) + ")");
  checkWorlds();
}

void Soak::overlayStart() {
  const int runs = random_.integer(sandbox::kMinOverlayRuns, sandbox::kMaxOverlayRuns);
  std::vector<std::string> texts(static_cast<std::size_t>(runs));
  for (std::string& text : texts) text = randomOverlayText();
  std::string description = "overlay";
  for (const std::string& t : texts) description += " '" + t + "'";
  begin(Kind::OverlayStart, description);
  std::vector<sandbox::OverlaySpec> specs;
  for (const std::string& t : texts) {
    const sandbox::ParsedOverlaySpec parsed = sandbox::parseOverlaySpec(t);
    expect(parsed.error.empty(), "valid overlay settings '" + t + "' were refused: " + parsed.error);
    specs.push_back(parsed.spec);
  }
  const phys::SolverSettings base = overlayBase_.value_or(session().scene().world.solverSettings());
  const std::size_t boxes = session().scene().world.bodies().size();
  const std::string error = session().startOverlay(specs);
  expect(error.empty(), "valid overlay settings were refused: " + error);
  overlayBase_ = base;
  expect(session().runs().size() == specs.size(),
         "the overlay has " + std::to_string(session().runs().size()) + " runs");
  expect(!session().dragging(), "the overlay kept the drag");
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const phys::World& w = session().runs()[i].scene->world;
    // Each setting on top of the settings from before the overlay, never on another run's.
    expect(sameSolver(w.solverSettings(), specs[i].applyTo(base)),
           "overlay run " + std::to_string(i) + " has " + describe(w.solverSettings()) + ", not '" +
               texts[i] + "' on top of " + describe(base));
    expect(w.bodies().size() == boxes,
           "overlay run " + std::to_string(i) + " does not start from the world as it was");
  }
  freezesSeen_.assign(specs.size(), freezesSeen_.empty() ? 0 : freezesSeen_.front());
  checkWorlds();
}

void Soak::overlayStop() {
  begin(Kind::OverlayStop, session().overlayActive() ? "stop overlay" : "stop overlay (none running)");
  const SessionState before = snapshot(session());
  session().stopOverlay();
  if (!overlayBase_) {
    checkUnchanged(before, "there was no overlay to stop");
  } else {
    expect(session().runs().size() == 1, "the overlay did not stop");
    expect(sameSolver(session().scene().world.solverSettings(), *overlayBase_),
           "after the overlay run 0 has " + describe(session().scene().world.solverSettings()) +
               ", not the settings from before it, " + describe(*overlayBase_));
    overlayBase_.reset();
    freezesSeen_.resize(1);
  }
  checkWorlds();
}

/// Commands that must be refused, with a message, and change nothing: bad settings, a bad
/// overlay, a save with nowhere to go.
void Soak::refused() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const int which = random_.integer(0, 5);
  const SessionState before = snapshot(session());
  std::string error;
  if (which == 0) {
    phys::WorldSettings w = session().scene().world.worldSettings();
    const int field = random_.integer(0, 5);
    if (field == 0) w.gravity.y = nan;
    if (field == 1) w.damping = -random_.logUniform(1e-9, 1e9);
    if (field == 2) w.groundNormal = Vec3(0.0);
    if (field == 3) w.bound = random_.chance(0.5) ? 0.0 : -1.0;
    if (field == 4) w.gravityStrength = random_.chance(0.5) ? -1.0 : inf;
    if (field == 5) w.groundMaterial.staticFriction = -0.1;
    begin(Kind::Refused, "invalid world settings " + describe(w));
    error = session().setWorldSettings(w);
  } else if (which == 1) {
    phys::SolverSettings s = session().scene().world.solverSettings();
    const int field = random_.integer(0, 7);
    if (field == 0) s.dt = random_.pick(std::vector<double>{0.0, phys::kMinDt / 2, 1.0 + 1e-9, nan, inf});
    if (field == 1) s.substeps = random_.chance(0.5) ? 0 : phys::kMaxSubsteps + 1;
    if (field == 2) s.iterations = random_.chance(0.5) ? -1 : phys::kMaxIterations + 1;
    if (field == 3) s.restitution = random_.chance(0.5) ? 1.5 : nan;
    if (field == 4) s.bodyDamping = -0.5;
    if (field == 5) s.compliance = phys::kMaxCompliance * 2;
    if (field == 6) s.maxDepenetrationSpeed = random_.chance(0.5) ? 0.0 : nan;
    if (field == 7) s.featureEpsilon = -1e-3;
    begin(Kind::Refused, "invalid solver settings " + describe(s));
    error = session().setSolverSettings(s);
  } else if (which == 2) {
    // The overlay checks every run before it replaces any: one bad run among good ones.
    const int runs = random_.integer(2, 4);
    std::vector<sandbox::OverlaySpec> specs;
    std::string description = "overlay with a bad run:";
    for (int i = 0; i < runs; ++i) {
      sandbox::OverlaySpec spec = sandbox::parseOverlaySpec(randomOverlayText()).spec;
      specs.push_back(spec);
      description += " '" + spec.text + "'";
    }
    sandbox::OverlaySpec& bad = specs[random_.index(specs.size())];
    bad.iterations = 0;
    bad.text += ",iterations=0";
    begin(Kind::Refused, description + " (iterations=0 added to '" + bad.text + "')");
    error = session().startOverlay(specs);
  } else if (which == 3) {
    const int runs = random_.chance(0.5) ? 1 : 5;
    std::vector<sandbox::OverlaySpec> specs(static_cast<std::size_t>(runs),
                                            sandbox::parseOverlaySpec("iterations=2").spec);
    begin(Kind::Refused, "overlay of " + std::to_string(runs) + " runs");
    error = session().startOverlay(specs);
  } else if (which == 4) {
    const fs::path file = tempDir_ / "no such folder" / "x.xml";
    begin(Kind::Refused, "save as " + file.string());
    error = session().saveAs(file, scenes::CameraStart{});
    expect(!fs::exists(file.parent_path()), "a refused Save As made a folder");
  } else {
    // The sandbox's camera always looks somewhere; a file cannot say a camera that does not.
    scenes::CameraStart camera;
    camera.eye = camera.target = glm::vec3(eye_);
    const fs::path file = tempDir_ / ("eye-on-target-" + std::to_string(command_) + ".xml");
    begin(Kind::Refused, "save as " + file.filename().string() + " with the eye on the target " + vec(eye_));
    error = session().saveAs(file, camera);
    expect(!fs::exists(file), "a refused Save As left a file behind");
  }
  expect(!error.empty(), "was not refused");
  checkUnchanged(before, "refused (\"" + error + "\")");
  checkWorlds();
}

/// Steps as many times as the budget allows (step_budget.h). Over the budget, this lowers
/// substeps and iterations (halving the larger) until one step fits, or stops the overlay whose
/// runs are the cost. That keeps the test meaningful rather than just fast: every extreme is still
/// set, saved and reloaded wherever it is drawn, and stepped as it is wherever it fits, which is
/// on the small scenes and in cleared worlds; only the combination of an extreme with a scene of
/// thousands of bodies, which would take minutes per step, is stepped at reduced settings.
// Waits for the background steps and checks what they did: `expected` steps (any, if 0) and
// worlds as the checks want them.
void Soak::collectBackgroundSteps(int expected) {
  std::optional<sandbox::StepsTaken> taken;
  while (!(taken = session().finishSteps())) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  expect(expected == 0 || taken->steps == expected,
         "the background took " + std::to_string(taken->steps) + " steps of " + std::to_string(expected));
  expect(!taken->cut, "the background steps were cut short by a budget of 600 s");
  steps_ += taken->steps;
  checkWorlds(true);
}

// B and the timeline: any recorded step is shown again, rebuilt from the keyframe before it, and
// every rebuilt step's hash must be the one recorded (Session::rewindTo says which is not).
void Soak::rewind() {
  const sandbox::Recording& r = session().recording();
  if (session().overlayActive() || r.empty()) {
    begin(Kind::Rewind, "rewind: refused while the overlay is on");
    expect(!session().rewindTo(r.last()).empty(), "a rewind with the overlay on was not refused");
    return;
  }
  const long span = r.last() - r.first();  // a soak's recording is far under 2^31 steps
  const long step = random_.chance(0.3)
                        ? r.last() - 1
                        : r.first() + random_.integer(0, static_cast<int>(std::min(span, 1L << 30)));
  begin(Kind::Rewind, "rewind to step " + std::to_string(step) + " of " + std::to_string(r.first()) + " to " +
                          std::to_string(r.last()));
  const std::string error = session().rewindTo(step);
  if (step < r.first()) {
    expect(!error.empty(), "a step before the recording was shown");
    return;
  }
  expect(error.empty(), "rewind: " + error);
  expect(session().scene().world.stepCount() == step,
         "the rewound world is at step " + std::to_string(session().scene().world.stepCount()));
  checkWorlds();
}

// Save the recording to a file and open it, as the File menu's Save Recording and Open Recording
// do: the file shows the steps it was saved with (the earliest may go, over the recording's
// budget), each as the recording had it, and stepping on from it forks the run there.
void Soak::recordingFile() {
  const fs::path file = tempDir_ / ("recording-" + std::to_string(command_) + ".jrec");
  const sandbox::Recording& r = session().recording();
  if (session().overlayActive() || r.empty()) {
    begin(Kind::RecordingFile,
          "save the recording as " + file.filename().string() + ": nothing recorded (the overlay is on)");
    const SessionState before = snapshot(session());
    expect(!session().saveRecording(file).empty(), "saving a recording of nothing was not refused");
    checkUnchanged(before, "saving a recording of nothing was refused");
    expect(!fs::exists(file), "a refused recording save left a file behind");
    return;
  }
  begin(Kind::RecordingFile, "save the recording of steps " + std::to_string(r.first()) + " to " +
                                 std::to_string(r.last()) + " as " + file.filename().string() +
                                 ", then open it");
  if (session().stepping()) {
    amend(", after collecting the background steps left running");
    collectBackgroundSteps(0);
  }
  const double visits = static_cast<double>(r.last() - r.first()) * stepVisits(session().scene().world);
  if (visits > kMaxVisitsPerRecordingSave) {
    amend(": skipped, saving it would step it again over the budget");
    ++recordingsOverBudget_;
    return;
  }
  const sandbox::Recording original = r;  // shares its keyframes: what the file must give back
  const SessionState before = snapshot(session());
  const std::string error = session().saveRecording(file);
  if (!error.empty()) {
    // A step no scene file can hold (as Save As refuses) is refused, and then nothing changes.
    tally(saveRefusals_, refusalReason(error, file));
    checkUnchanged(before, "saving the recording was refused (\"" + error + "\")");
    expect(!fs::exists(file), "a refused recording save left a file behind: " + error);
    return;
  }
  const std::string openError = session().openRecording(file);
  expect(openError.empty(), "a recording just saved does not open: " + openError);
  ++recordingsSaved_;
  const sandbox::Recording& back = session().recording();
  expect(back.last() == original.last() && back.first() >= original.first(),
         "the recording saved with steps " + std::to_string(original.first()) + " to " +
             std::to_string(original.last()) + " opens with steps " + std::to_string(back.first()) + " to " +
             std::to_string(back.last()));
  expect(session().file() == before.file, "opening a recording changed the current file");
  // The first step kept and the last, each as the recording had it.
  for (const long step : {back.first(), back.last()}) {
    if (step != back.first()) {
      const std::string rewound = session().rewindTo(step);
      expect(rewound.empty(), "the opened recording's step " + std::to_string(step) + ": " + rewound);
    }
    std::string divergence;
    const std::unique_ptr<phys::World> then = original.worldAt(step, divergence);
    expect(divergence.empty(), "the recording before it was saved: " + divergence);
    const phys::World& shown = session().scene().world;
    expect(shown.stepCount() == step && shown.stateHash() == then->stateHash(),
           "the opened recording shows step " + std::to_string(shown.stepCount()) +
               (shown.stateHash() == then->stateHash() ? "" : ", not as it was recorded") + " for step " +
               std::to_string(step));
  }
  fs::remove(file);
  checkWorlds();
}

void Soak::step() {
  const int drawn = random_.chance(0.4) ? 1 : random_.integer(1, kMaxStepsPerCommand);
  begin(Kind::Step, "step up to " + std::to_string(drawn) + " times");
  if (session().stepping()) {  // left running by an earlier step, and no command cancelled them
    amend(", after collecting the background steps left running");
    collectBackgroundSteps(0);
  }
  if (session().overlayActive() && sessionVisits(session(), 1) > kMaxVisitsPerStep) {
    amend(", overlay stopped (over the budget)");
    session().stopOverlay();
    overlayBase_.reset();
    freezesSeen_.resize(1);
    ++overlaysStoppedForBudget_;
  }
  if (sessionVisits(session(), 1) > kMaxVisitsPerStep) {
    phys::SolverSettings s = session().scene().world.solverSettings();
    while (sessionVisits(session(), 1) > kMaxVisitsPerStep && (s.substeps > 1 || s.iterations > 1)) {
      (s.substeps >= s.iterations ? s.substeps : s.iterations) /= 2;
      s.substeps = std::max(1, s.substeps);
      s.iterations = std::max(1, s.iterations);
      const std::string error = session().setSolverSettings(s);
      expect(error.empty(), "the budget's lower settings were refused: " + error);
    }
    ++lowered_;
    amend(", lowered to " + std::to_string(s.iterations) + " iterations x " + std::to_string(s.substeps) +
          " substeps (over the budget)");
    checkWorlds();  // a new substep rescales every velocity (World::setSolverSettings)
  }
  const double one = sessionVisits(session(), 1);
  if (one > kMaxVisitsPerStep) {
    amend(": skipped, one step is over the budget even at 1 x 1");
    ++skipped_;
    return;
  }
  const int steps = std::max(1, std::min(drawn, static_cast<int>(kMaxVisitsPerCommand / one)));
  amend(": " + std::to_string(steps) + (steps == 1 ? " step" : " steps"));
  const double estimate = sessionVisits(session(), steps);
  const double start = cpuSeconds();
  if (random_.chance(0.3)) {
    // As the sandbox steps: on copies, on another thread. Half the time they are left running,
    // for the next command to cancel (or, moving the drag, to leave), or the next step to collect.
    amend(" in the background");
    session().startSteps(steps, std::chrono::seconds(600));
    expect(session().stepping(), "the background steps did not start");
    if (random_.chance(0.5)) {
      amend(", left running");
      return;
    }
    collectBackgroundSteps(steps);
    return;
  }
  for (int i = 0; i < steps; ++i) {
    session().step();
    ++steps_;
    try {
      checkWorlds(i + 1 == steps);  // positions after every step, the rest after the last
    } catch (const Broken& b) {
      throw Broken("after step " + std::to_string(i + 1) + ": " + b.what());
    }
  }
  if (options_.verbose) {  // how well the budget's estimate foretold the time
    const phys::World& w = session().scene().world;
    std::printf("    estimated %.3g visits, took %.3f s of CPU; %zu boxes, %zu broad-phase pairs\n", estimate,
                cpuSeconds() - start, w.bodies().size(), w.broadPhasePairs());
  }
}

// ---------------------------------------------------------------------------------------------
// Failures.

void Soak::fail(const std::string& what) {
  Failure f;
  f.command = command_;
  f.description = description_;
  f.what = what;
  f.folder = tempDir_ / ("failure-" + std::to_string(command_));
  // The reproducer: the file the episode started from, and the commands since.
  std::error_code ec;
  fs::create_directories(f.folder, ec);
  if (!episodeFile_.empty()) fs::copy_file(episodeFile_, f.folder / "episode-start.xml", ec);
  const fs::path saved = session_ ? session_->file() : fs::path();
  if (!saved.empty() && saved != episodeFile_ && saved.parent_path() == tempDir_)
    fs::copy_file(saved, f.folder / "saved.xml", ec);
  std::ofstream commands(f.folder / "commands.txt");
  commands << "# seed " << options_.seed << "; opened " << episodeFile_.string() << ", then:\n";
  for (const std::string& c : episode_) commands << c << "\n";
  commands << "# broke: " << what << "\n";

  std::printf("soak: FAILED at command #%ld (seed %llu): %s\n", command_,
              static_cast<unsigned long long>(options_.seed), description_.c_str());
  std::printf("  what broke: %s\n", what.c_str());
  std::printf("  replay: soak --seed %llu --seconds %g --commands %ld --verbose\n",
              static_cast<unsigned long long>(options_.seed), options_.seconds, command_);
  std::printf(
      "  reproducer: %s (a copy of %s, which the episode opened) and the %zu command%s since, in %s\n",
      (f.folder / "episode-start.xml").c_str(), episodeFile_.c_str(), episode_.size(),
      episode_.size() == 1 ? "" : "s", (f.folder / "commands.txt").c_str());
  std::fflush(stdout);
  failures_.push_back(std::move(f));
}

/// After a failure with --keep-going: a fresh project scene, as a user would open one.
bool Soak::recover() {
  const fs::path file = cycle_[nextInCycle_];
  if (++nextInCycle_ == cycle_.size()) nextInCycle_ = 0;
  try {
    session_ = std::make_unique<sandbox::Session>(file, sceneDir_);
    session_->setRecordingBudget(kRecordingBudget);
    startEpisode(file);
    episode_.push_back("# recovered: opened " + shortName(file) + " in a new session");
    return true;
  } catch (const std::exception& e) {
    std::printf("soak: cannot recover, %s does not open: %s\n", file.c_str(), e.what());
    return false;
  }
}

std::string Soak::summary(double seconds) const {
  auto mib = [](std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / kMiB);
    return std::string(text);
  };
  char took[32];
  std::snprintf(took, sizeof took, "%.0f s", seconds);
  std::string s = "soak: seed " + std::to_string(options_.seed) + ", " + std::to_string(command_) +
                  " commands in " + took + " (";
  for (std::size_t k = 0; k < kKinds.size(); ++k)
    s += std::string(k ? " " : "") + kKinds[k].name + " " + std::to_string(counts_[k]);
  long freezes = 0, saveRefusals = 0;
  for (const auto& entry : freezeReasons_) freezes += entry.second;
  for (const auto& entry : saveRefusals_) saveRefusals += entry.second;
  std::snprintf(took, sizeof took, "%.2f s of CPU", longest_);
  s += "); " + std::to_string(steps_) + " steps (budget: " + std::to_string(lowered_) + " lowered, " +
       std::to_string(skipped_) + " skipped, " + std::to_string(overlaysStoppedForBudget_) +
       " overlays stopped); " + std::to_string(throwsCapped_) + " throws capped; " + std::to_string(saves_) +
       " saves (" + std::to_string(reopened_) + " reopened, " + std::to_string(saveRefusals) + " refused); " +
       std::to_string(recordingsSaved_) + " recordings saved and opened (" +
       std::to_string(recordingsOverBudget_) + " over the budget); " + std::to_string(reloads_) +
       " reloads; " + std::to_string(std::count(opened_.begin(), opened_.end(), true)) + "/" +
       std::to_string(scenes_.size()) + " project scenes opened; " + std::to_string(freezes) +
       " guard freezes; peak RSS " + mib(memory_.peakRss()) + "; RSS on reopening (trimmed) " +
       mib(memory_.warmUpRss()) + " in the warm-up, at most " + mib(memory_.laterRss()) + " in " +
       std::to_string(memory_.rssComparisons()) +
       " samples after; heap growth on reopening a scene at most " +
       std::to_string(memory_.largestHeapGrowth()) + " bytes over " +
       std::to_string(memory_.heapComparisons()) + " reopenings; longest command " + took + " (" +
       longestCommand_ + "); " + std::to_string(failures_.size()) +
       (failures_.size() == 1 ? " failure" : " failures");
  return s;
}

// ---------------------------------------------------------------------------------------------

int Soak::run() {
  std::error_code ec;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(sceneDir_, ec)) {
    if (e.is_regular_file() && e.path().extension() == ".xml") scenes_.push_back(e.path());
  }
  if (scenes_.empty()) {
    std::fprintf(stderr, "soak: no scene files in %s (--data DIR names the folder holding assets/)\n",
                 sceneDir_.c_str());
    return 2;
  }
  std::sort(scenes_.begin(), scenes_.end());  // the directory's order is the file system's, not ours
  opened_.assign(scenes_.size(), false);
  cycle_ = scenes_;
  random_.shuffle(cycle_);
  tempDir_ = fs::temp_directory_path() /
             ("soak-" + std::to_string(options_.seed) + "-" + std::to_string(static_cast<long>(::getpid())));
  fs::remove_all(tempDir_, ec);
  if (fs::create_directories(tempDir_, ec); ec) {
    std::fprintf(stderr, "soak: cannot make the folder %s: %s\n", tempDir_.c_str(), ec.message().c_str());
    return 2;
  }

  start_ = Clock::now();
  // Command 0: the sandbox starting on a scene.
  const fs::path first = cycle_[nextInCycle_++];
  description_ = "start on " + shortName(first);
  std::snprintf(g_current, sizeof g_current, "soak: seed %llu, command #0: %s",
                static_cast<unsigned long long>(options_.seed), description_.c_str());
  try {
    session_ = std::make_unique<sandbox::Session>(first, sceneDir_);
    session_->setRecordingBudget(kRecordingBudget);
    startEpisode(first);
    checkWorlds();
    afterFreshOpen(first);
  } catch (const std::exception& e) {
    fail(e.what());
    return 1;
  }

  int totalWeight = 0;
  for (const KindInfo& k : kKinds) totalWeight += k.weight;
  for (;;) {
    const double now = elapsed();
    if (now >= options_.seconds || (options_.maxCommands >= 0 && command_ >= options_.maxCommands)) break;
    const std::size_t peakBefore = memory_.peakRss();
    memory_.sample(now);
    if (options_.verbose && memory_.peakRss() > peakBefore + 16 * kMiB) {
      std::printf(
          "    RSS peak now %.1f MiB (%s, %zu runs, %zu boxes, %zu broad-phase pairs, %zu contacts)\n",
          static_cast<double>(memory_.peakRss()) / kMiB, shortName(session().file()).c_str(),
          session().runs().size(), session().scene().world.bodies().size(),
          session().scene().world.broadPhasePairs(), session().scene().world.bodyContacts().size());
    }
    ++command_;
    int draw = random_.integer(0, totalWeight - 1);
    std::size_t k = 0;
    while (draw >= kKinds[k].weight) draw -= kKinds[k++].weight;
    const std::size_t failuresBefore = failures_.size();
    const double commandStart = cpuSeconds();
    try {
      switch (static_cast<Kind>(k)) {
        case Kind::Open:
          open();
          break;
        case Kind::Reload:
          reload();
          break;
        case Kind::SaveAndOpen:
          saveAndOpen();
          break;
        case Kind::Clear:
          clear();
          break;
        case Kind::ThrowBox:
        case Kind::ThrowRagdoll:
        case Kind::ThrowCapsuleRagdoll:
          throwBody(static_cast<Kind>(k));
          break;
        case Kind::Pick:
          pick();
          break;
        case Kind::Drag:
          drag();
          break;
        case Kind::Release:
          release();
          break;
        case Kind::WorldSettings:
          worldSettings();
          break;
        case Kind::SolverSettings:
          solverSettings();
          break;
        case Kind::GravityKeys:
          gravityKeys();
          break;
        case Kind::DampingKeys:
          dampingKeys();
          break;
        case Kind::GravityMode:
          gravityMode();
          break;
        case Kind::OverlayStart:
          overlayStart();
          break;
        case Kind::OverlayStop:
          overlayStop();
          break;
        case Kind::Refused:
          refused();
          break;
        case Kind::Step:
          step();
          break;
        case Kind::Rewind:
          rewind();
          break;
        case Kind::RecordingFile:
          recordingFile();
          break;
        case Kind::Count:
          break;
      }
    } catch (const Broken& b) {
      fail(b.what());
    } catch (const std::exception& e) {
      fail(std::string("an exception escaped the command: ") + e.what());
    } catch (...) {
      fail("an exception of no standard type escaped the command");
    }
    const double took = cpuSeconds() - commandStart;  // CPU time: the machine may be shared
    if (took > longest_) {
      longest_ = took;
      longestCommand_ = "#" + std::to_string(command_) + " " + kKinds[k].name;
    }
    if (failures_.size() == failuresBefore) continue;
    // Reopening a scene does not give leaked memory back: a memory failure ends the run.
    if (!options_.keepGoing || failures_.back().what.rfind("memory:", 0) == 0 || !recover()) break;
  }
  const double seconds = elapsed();
  std::printf("%s\n", summary(seconds).c_str());
  if (options_.verbose) {
    for (const auto& [reason, n] : saveRefusals_)
      std::printf("  save refused %ld times: %s\n", n, reason.c_str());
    for (const auto& [reason, n] : freezeReasons_)
      std::printf("  guard froze %ld times: %s\n", n, reason.c_str());
    std::string rss;
    for (const std::size_t r : memory_.samples()) rss += " " + std::to_string(r / kMiB);
    std::printf("  RSS samples (MiB, every %.0f s):%s\n", kRssSampleSeconds, rss.c_str());
  }
  if (!memory_.enabled())
    std::printf("soak: memory rules off (AddressSanitizer: LeakSanitizer checks at exit)\n");
  session_.reset();
  if (failures_.empty()) {
    fs::remove_all(tempDir_, ec);
    return 0;
  }
  // Keep the reproducers; the rest of the folder goes.
  for (const fs::directory_entry& e : fs::directory_iterator(tempDir_, ec)) {
    if (e.path().filename().string().rfind("failure-", 0) != 0) fs::remove_all(e.path(), ec);
  }
  std::printf("soak: %zu failure%s; reproducers in %s\n", failures_.size(), failures_.size() == 1 ? "" : "s",
              tempDir_.c_str());
  return 1;
}

}  // namespace

int run(const Options& options) {
  Soak soak(options);
  return soak.run();
}

}  // namespace soak
