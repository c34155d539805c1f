#include "session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "clips/clip_file.h"
#include "fileio/files.h"
#include "open_scene.h"
#include "physics/capsule_ragdoll.h"
#include "physics/character.h"
#include "physics/ragdoll.h"
#include "recording_io.h"
#include "scenes/scene_writer.h"
#include "stats_text.h"  // figure

namespace sandbox {
namespace {

using Clock = std::chrono::steady_clock;

// The largest recording file opened (unit: bytes): 10 s of Bullet's 136-ragdoll pile take 166 MB.
constexpr std::size_t kMaxRecordingFile = std::size_t{8} << 30;

// A world with the same settings as `world` and nothing in it.
phys::World emptyLike(const phys::World& world) {
  return phys::World(world.worldSettings(), world.solverSettings());
}

// Where the embedded point sits in the box's frame (so the same point can be found on the same
// box in another run, wherever that box is now).
phys::Vec3 toLocal(const phys::World& w, phys::BodyId box, const phys::Vec3& p) {
  const phys::BodyPose pose = w.bodyPose(box);
  return glm::inverse(pose.orientation) * (p - pose.center);
}

// The largest component's size: scaling by it first keeps glm::length, which squares the
// components, from overflowing when gravity is set near the largest double.
double largestOf(const phys::Vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

// |v| without overflow; infinity only when the length itself is beyond a double.
double lengthOf(const phys::Vec3& v) {
  const double largest = largestOf(v);
  if (largest == 0.0 || !std::isfinite(largest)) return largest;
  return largest * glm::length(v / largest);
}

// The strength of a gravity vector as one number: its length, or the largest double when the
// length is beyond one (three components near the largest double, each valid).
double strengthOf(const phys::Vec3& gravity) {
  return std::min(lengthOf(gravity), std::numeric_limits<double>::max());
}

// Where gravity points, or straight down (the default gravity's way) when it has no strength.
phys::Vec3 directionOf(const phys::Vec3& gravity) {
  const double largest = largestOf(gravity);
  if (largest > 0.0 && std::isfinite(largest)) return glm::normalize(gravity / largest);
  return glm::normalize(phys::WorldSettings{}.gravity);
}

// Gravity of the given strength along a unit direction, or the strongest a vector can hold that
// way: direction * strength can round past the largest double in a component when the strength
// is near it. Found by the soak test (seed 11): pressing H on a gravity whose length was one ulp
// under the largest double rounded it a little longer each time, until a component overflowed
// and the key was refused with "gravity must be finite".
phys::Vec3 gravityAlong(const phys::Vec3& direction, double strength) {
  phys::Vec3 g = direction * strength;
  for (int i = 0; i < 64 && !(std::isfinite(g.x) && std::isfinite(g.y) && std::isfinite(g.z)); ++i) {
    strength = std::nextafter(strength, 0.0);
    g = direction * strength;
  }
  return g;
}

phys::Vec3 toWorld(const phys::World& w, phys::BodyId box, const phys::Vec3& local) {
  const phys::BodyPose pose = w.bodyPose(box);
  return pose.center + pose.orientation * local;
}

// The point of the plane (p0, n) on the ray, or the ray's point at the plane's distance when
// the ray runs along the plane.
phys::Vec3 onPlane(const phys::Vec3& origin, const phys::Vec3& dir, const phys::Vec3& p0,
                   const phys::Vec3& n) {
  const double along = glm::dot(dir, n);
  if (std::abs(along) < 1e-6) return origin + dir * glm::length(p0 - origin);
  return origin + dir * (glm::dot(p0 - origin, n) / along);
}

}  // namespace

Session::Session(const std::filesystem::path& file, const std::filesystem::path& sceneDirectory,
                 std::optional<int> threads)
    : Session(loadCheckedScene(file, sceneLoadOptions(threads)), file, sceneDirectory, threads) {}

Session::Session(std::unique_ptr<scenes::Scene> first, const std::filesystem::path& file,
                 const std::filesystem::path& sceneDirectory, std::optional<int> threads)
    : sceneDirectory_(sceneDirectory), load_(sceneLoadOptions(threads)) {
  if (!first) throw std::invalid_argument("Session: no first scene");
  replaceMain(std::move(first), file);
}

void Session::replaceMain(std::unique_ptr<scenes::Scene> scene, const std::filesystem::path& file) {
  cancelSteps();
  runs_.clear();
  drag_.reset();
  dragTarget_.reset();
  Run run;
  run.scene = std::move(scene);
  run.color = kRunColors[0];
  runs_.push_back(std::move(run));
  file_ = file;
  status_ = "opened " + file.filename().string();
  rewound_ = false;
  recording_.restart(runs_.front().scene->world);
}

std::string Session::open(const std::filesystem::path& file) {
  try {
    replaceMain(loadCheckedScene(file, load_), file);
    return {};
  } catch (const std::exception& e) {  // LoadError, or anything else: keep what we have
    status_ = std::string(e.what()) + " (the current world is kept)";
    return e.what();
  }
}

std::string Session::reload() {
  return open(file_);
}

std::string Session::openBuiltin(std::string_view name) {
  return open(scenes::resolveScene(name, sceneDirectory_));
}

std::string Session::saveAs(const std::filesystem::path& file, const scenes::CameraStart& camera) {
  try {
    if (overlayActive()) {
      // Run 0 under the overlay's setting is a comparison, not the scene: the file gets the
      // settings Stop gives back, so that Reload does not quietly keep the overlay's.
      scenes::Scene main = scene();
      main.world.setSolverSettings(savedSolverSettings());
      scenes::saveSceneFile(main, camera, file);
    } else {
      scenes::saveSceneFile(scene(), camera, file);
    }
    file_ = file;
    status_ = "saved " + file.filename().string();
    return {};
  } catch (const std::exception& e) {
    return e.what();
  }
}

void Session::clear() {
  cancelSteps();
  drag_.reset();
  dragTarget_.reset();
  for (Run& run : runs_) {
    scenes::Scene& s = *run.scene;
    s.world = emptyLike(s.world);
    s.bodies.clear();
  }
  rewound_ = false;
  recording_.restart(scene().world);  // a new world, from step 0
  status_ = "cleared: no bodies; Reload (F5) brings the file's back";
}

std::string Session::startOverlay(std::span<const OverlaySpec> specs) {
  if (specs.size() < static_cast<std::size_t>(kMinOverlayRuns) ||
      specs.size() > static_cast<std::size_t>(kMaxOverlayRuns)) {
    return "the overlay needs " + std::to_string(kMinOverlayRuns) + " to " + std::to_string(kMaxOverlayRuns) +
           " settings, got " + std::to_string(specs.size());
  }
  const phys::SolverSettings base = overlayActive() ? beforeOverlay_ : scene().world.solverSettings();
  // Every setting is judged before anything changes, the drag included: a refused overlay
  // leaves the session as it was.
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (const std::string why = phys::validate(specs[i].applyTo(base)); !why.empty()) {
      return "overlay run " + std::to_string(i + 1) + " '" + specs[i].text + "': SolverSettings: " + why;
    }
  }
  cancelSteps();
  release();  // a copied spring would have no one to let it go
  std::vector<Run> runs;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    Run run;
    run.scene = std::make_unique<scenes::Scene>(scene());
    run.scene->world.setSolverSettings(specs[i].applyTo(base));  // valid: checked above
    run.label = specs[i].text;
    run.color = kRunColors[i];
    runs.push_back(std::move(run));
  }
  beforeOverlay_ = base;
  runs_ = std::move(runs);
  // Run 0 is the main run under its overlay setting, recorded as a slider's change would be: the
  // history before the overlay stays, and is still there to rewind to once it stops (the other
  // runs are not recorded, so rewinding waits for Stop).
  worldChanged();
  status_ = "overlay of " + std::to_string(runs_.size()) + " runs, each from the state the world was in";
  return {};
}

void Session::stopOverlay() {
  if (!overlayActive()) return;
  cancelSteps();
  release();
  runs_.resize(1);
  runs_.front().label.clear();
  runs_.front().color = kRunColors[0];
  scene().world.setSolverSettings(beforeOverlay_);  // valid: the main run had them
  worldChanged();
  status_ = "overlay off; the solver settings are as before it";
}

void Session::step() {
  cancelSteps();
  beforeStepping();
  stepRuns(runs_);
  const StepRecord record = recordOf(scene().world);
  recordSteps(std::span<const StepRecord>(&record, 1));
}

void Session::beforeStepping() {
  if (!rewound_) return;
  recording_.setHeapShared(saver_.running());
  rewound_ = false;
  recording_.keyframe(scene().world);
}

void Session::recordSteps(std::span<const StepRecord> records) {
  recording_.setHeapShared(saver_.running());
  for (const StepRecord& r : records) recording_.stepped(r);
  recording_.setStepCost(runs_.front().medianMs());
  recording_.keyframeIfDue(scene().world);
}

void Session::worldChanged() {
  recording_.setHeapShared(saver_.running());
  rewound_ = false;
  recording_.keyframe(scene().world);
}

void Session::worldChanged(std::function<void(phys::World&)> redo, std::size_t bytes) {
  recording_.setHeapShared(saver_.running());
  rewound_ = false;
  recording_.changed(scene().world, std::move(redo), bytes);
}

std::string Session::rewindTo(long step) {
  if (overlayActive())
    return "stop the method overlay first: only run 0 is recorded, and the others cannot go back";
  if (!recording_.covers(step)) {
    return "step " + std::to_string(step) + " is not recorded (the recording holds steps " +
           std::to_string(recording_.first()) + " to " + std::to_string(recording_.last()) + ")";
  }
  cancelSteps();
  drag_.reset();
  dragTarget_.reset();
  scene().world.clearDrag();  // a spring picked on a rewound world and not stepped with
  std::string divergence;
  // A world shown as recorded (rewound, and not changed since) is a step to rebuild from.
  std::unique_ptr<phys::World> world =
      recording_.worldAt(step, divergence, rewound_ ? &scene().world : nullptr);
  world->clearDrag();  // the hand that held it is not recorded
  scene().world = std::move(*world);
  rewound_ = true;
  status_ = divergence.empty()
                ? "at step " + std::to_string(step) + " of the recording's " +
                      std::to_string(recording_.first()) + " to " + std::to_string(recording_.last())
                : "the replay differs from the recording: " + divergence;
  return divergence;
}

std::string Session::startSavingRecording(const std::filesystem::path& file) {
  if (overlayActive()) return "nothing to save: the method overlay's runs are not recorded";
  if (recording_.empty()) return "nothing recorded yet";
  if (saver_.running()) return "a recording is being saved: wait for it to finish";
  finishSaving();  // an earlier one, done but not collected
  // A folder that is missing or read-only is said now, not after every step was rebuilt (seconds
  // for a big scene).
  try {
    fileio::checkWritable(file);
  } catch (const std::exception& e) {
    status_ = std::string("the recording was not saved: ") + e.what();
    return e.what();
  }
  saver_.start(recording_, scene(), file);
  status_ = "saving the recording to " + file.filename().string();
  return {};
}

std::optional<double> Session::savingProgress() const {
  if (!saver_.running()) return std::nullopt;
  return saver_.progress();
}

std::optional<std::string> Session::finishSaving(bool wait) {
  std::string saved;
  std::optional<std::string> error = saver_.finish(saved, wait);
  if (error) status_ = error->empty() ? saved : "the recording was not saved: " + *error;
  return error;
}

std::string Session::saveRecording(const std::filesystem::path& file) {
  if (std::string why = startSavingRecording(file); !why.empty()) return why;
  return finishSaving(true).value_or("");
}

std::string Session::finishSavingOnClose() {
  return finishSaving(true) ? status_ : std::string();
}

// The clips a recording's characters play, by name: those the scene's characters hold already (the
// recording is of this scene), else read from the file the name is the path of.
ClipSource Session::recordedClips() const {
  auto known = std::make_shared<std::map<std::string, std::shared_ptr<const phys::Clip>>>();
  for (const phys::Character& c : scene().world.characters()) {
    phys::forEachPlayback(c, [&known](const phys::Playback& p) {
      if (p.clip != nullptr) known->emplace(p.clip->name, p.clip);
    });
  }
  return [known](const std::string& name) {
    const auto it = known->find(name);
    if (it != known->end()) return it->second;
    try {
      auto clip = std::make_shared<const phys::Clip>(clips::loadClip(name));
      known->emplace(name, clip);
      return clip;
    } catch (const clips::ClipError& e) {
      throw std::runtime_error(std::string("a clip its characters play: ") + e.what());
    }
  };
}

std::string Session::openRecording(const std::filesystem::path& file) {
  if (overlayActive()) return "stop the method overlay first: its runs cannot be shown a recording";
  const std::string kept = " (the current world is kept)";
  try {
    const std::string bytes = fileio::readWhole(file, kMaxRecordingFile);
    // The scene before the clips: a file of another scene is that, whatever clips it names.
    const std::string open = scene().name;
    auto sameScene = [&open](const std::string& name) {
      if (name != open)
        throw RecordingIoError("a recording of the scene '" + name + "', and '" + open + "' is open: open '" +
                               name + "' first");
    };
    cancelSteps();  // the heap the recording's copies are measured by is this thread's alone
    auto [opened, firstSaved] =
        recordingFromFile(bytes, sameScene, recordedClips(), load_, recording_.budget());
    // Everything that can fail before anything changes: the first step's world too.
    std::string divergence;
    std::unique_ptr<phys::World> first = opened.worldAt(opened.first(), divergence);
    drag_.reset();
    dragTarget_.reset();
    recording_ = std::move(opened);
    scene().world = std::move(*first);
    rewound_ = true;
    status_ = "opened " + file.filename().string() + ": steps " + std::to_string(recording_.first()) +
              " to " + std::to_string(recording_.last());
    if (recording_.first() != firstSaved) {
      status_ += "; steps " + std::to_string(firstSaved) + " to " + std::to_string(recording_.first() - 1) +
                 " left out: over the recording's budget";
    }
    return {};
  } catch (const fileio::FileError& e) {
    return e.what() + kept;
  } catch (const std::exception& e) {  // RecordingFormatError, RecordingIoError, a refused motion, memory
    return file.string() + ": " + e.what() + kept;
  }
}

void Session::startSteps(int steps, std::chrono::duration<double> budget) {
  if (steps < 1 || background_.running()) return;
  beforeStepping();
  std::vector<Run> copies;
  copies.reserve(runs_.size());
  for (const Run& run : runs_) copies.push_back(run.copy());
  background_.start(std::move(copies), steps, budget);
}

std::optional<StepsTaken> Session::finishSteps() {
  auto done = background_.collect();
  if (!done) return std::nullopt;
  runs_ = std::move(done->first);
  recordSteps(done->second.records);
  // The drag's target as the user moved it while the copies stepped (a pick or a release cancels
  // the steps, so the copies hold the drag the user holds).
  if (drag_ && dragTarget_) {
    forEachWorld([&](phys::World& w) {
      if (w.drag()) w.setDragTarget(*dragTarget_);
    });
  }
  return done->second;
}

void Session::cancelSteps() {
  background_.cancel();
}

void Session::forEachWorld(const std::function<void(phys::World&)>& apply) {
  for (Run& run : runs_) apply(run.scene->world);
}

std::string Session::setWorldSettings(const phys::WorldSettings& settings) {
  // Every run has the same world settings, so if the first takes them all do.
  const std::string why = phys::validate(settings);
  if (!why.empty()) return "world settings: " + why;
  cancelSteps();
  const auto apply = [settings](phys::World& w) { w.setWorldSettings(settings); };
  forEachWorld(apply);
  worldChanged(apply, sizeof(settings));
  return {};
}

std::string Session::setSolverSettings(const phys::SolverSettings& settings) {
  try {
    cancelSteps();
    scene().world.setSolverSettings(settings);
    worldChanged([settings](phys::World& w) { w.setSolverSettings(settings); }, sizeof(settings));
    return {};
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

std::string Session::setDriveStrength(double strength) {
  if (!(strength >= 0.0 && strength <= 1.0)) return "drives: strength must be from 0 to 1";
  if (scene().world.rigidJoints().empty() && scene().world.particleJoints().empty())
    return "drives: the scene has no joints with drives (rigid joints, or particle joints of ragdolls)";
  cancelSteps();
  const auto apply = [strength](phys::World& w) {
    for (std::size_t k = 0; k < w.rigidJoints().size(); ++k) {
      phys::JointDrive drive = w.jointDrive(k);
      drive.strength = strength;
      w.setJointDrive(k, drive);
    }
    for (std::size_t k = 0; k < w.particleJoints().size(); ++k) {
      phys::JointDrive drive = w.particleJointDrive(k);
      drive.strength = strength;
      w.setParticleJointDrive(k, drive);
    }
    // A character sets its joints' drives from its own strength every substep: it takes the value
    // too, or the slider would hold for one substep.
    for (std::size_t k = 0; k < w.characters().size(); ++k)
      w.setCharacterStrength(k, strength, w.characters()[k].goalRootStrength);
  };
  forEachWorld(apply);
  worldChanged(apply, 0);
  return {};
}

// One change to character k in every run; "" or the world's refusal, and then no run changes: the
// runs hold the same characters, and a World refuses a change before it makes any of it, so the
// first run refuses what every run would.
std::string Session::changeCharacter(std::size_t k, const std::function<void(phys::World&)>& change) {
  if (k >= scene().world.characters().size())
    return "character: the scene has no character " + std::to_string(k);
  cancelSteps();
  try {
    forEachWorld(change);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  worldChanged();
  return {};
}

std::string Session::setCharacterStrength(std::size_t k, double strength) {
  return changeCharacter(k, [k, strength](phys::World& w) {
    w.setCharacterStrength(k, strength, w.characters()[k].goalRootStrength);
  });
}

std::string Session::setCharacterBalance(std::size_t k, double balance) {
  return changeCharacter(k, [k, balance](phys::World& w) { w.setCharacterBalance(k, balance); });
}

std::string Session::setPartStrength(std::size_t k, const std::string& bone, double share) {
  return changeCharacter(k, [&](phys::World& w) { w.setPartStrength(k, bone, share); });
}

std::string Session::setReactionThreshold(std::size_t k, double threshold) {
  return changeCharacter(k, [k, threshold](phys::World& w) {
    phys::Reaction r = w.characters()[k].reaction;
    r.threshold = threshold;
    w.setCharacterReaction(k, r);
  });
}

std::string Session::setCharacterTurnIn(std::size_t k, double seconds) {
  return changeCharacter(k, [k, seconds](phys::World& w) { w.setCharacterTurnIn(k, seconds); });
}

std::string Session::pushCharacter(std::size_t k, double newtons) {
  return changeCharacter(k, [k, newtons](phys::World& w) {
    // Where the body faces now, not where its clip's path was laid (the frame): a player turned
    // away from it, limp or dragged round, was pushed sideways or from behind.
    w.push(w.characters()[k].bones[0].body, newtons * phys::facing(w, k), kPushTime);
  });
}

std::string Session::playCharacterClip(std::size_t k, const std::filesystem::path& file, bool loop) {
  if (k >= scene().world.characters().size())
    return "character: the scene has no character " + std::to_string(k);
  std::shared_ptr<const phys::Clip> clip;
  try {
    clip = std::make_shared<const phys::Clip>(clips::loadClip(file));
  } catch (const clips::ClipError& e) {
    return e.what();
  }
  return setCharacterPlayback(k, phys::Playback{clip, 0.0, scene().world.characters()[k].now.speed, loop},
                              kClipBlendTime);
}

std::string Session::setCharacterPlayback(std::size_t k, const phys::Playback& playback, double blendTime) {
  return changeCharacter(k, [&](phys::World& w) { w.playClip(k, playback, blendTime); });
}

std::string Session::applyWorldSettings(const phys::WorldSettings& settings, const std::string& done) {
  std::string why = setWorldSettings(settings);  // not const: returned by move
  status_ = why.empty() ? done : why;
  return why;
}

std::string Session::toggleGravityMode() {
  phys::WorldSettings s = scene().world.worldSettings();
  const bool toPoint = s.gravityMode == phys::GravityMode::Uniform;
  s.gravityMode = toPoint ? phys::GravityMode::Point : phys::GravityMode::Uniform;
  // One strength for both modes, so G alone never makes gravity stronger or weaker; uniform
  // gravity of strength 0 keeps pointing down, so that strength given in point mode comes back.
  if (toPoint)
    s.gravityStrength = strengthOf(s.gravity);
  else
    s.gravity = gravityAlong(directionOf(s.gravity), s.gravityStrength);
  return applyWorldSettings(s, toPoint ? "gravity: towards the point" : "gravity: uniform");
}

std::string Session::changeGravity(double delta) {
  phys::WorldSettings s = scene().world.worldSettings();
  const bool point = s.gravityMode == phys::GravityMode::Point;
  const double now = point ? s.gravityStrength : strengthOf(s.gravity);
  const double most = std::max(kMaxRaisedGravity, now);
  const double strength = std::clamp(now + delta, 0.0, most);
  if (point)
    s.gravityStrength = strength;
  else
    s.gravity = gravityAlong(directionOf(s.gravity), strength);
  const std::string done = "gravity " + figure("%.10g", strength) + " m/s^2";
  return applyWorldSettings(
      s, delta > 0.0 && strength == most && strength == now ? done + " (the most Y gives)" : done);
}

std::string Session::changeDamping(double delta) {
  phys::WorldSettings s = scene().world.worldSettings();
  // Round to the step so that ten presses up and ten down come back to exactly where they began.
  s.damping = std::max(0.0, std::round((s.damping + delta) * 1000.0) / 1000.0);
  return applyWorldSettings(s, "wind resistance " + figure("%.10g", s.damping) + " 1/s");
}

std::optional<phys::Vec3> Session::clearSpot(const phys::Vec3& at, double room) const {
  const phys::World& w = scene().world;
  auto clear = [&](const phys::Vec3& p) {
    for (phys::BodyId id{}; id < w.bodies().size(); ++id) {
      const double reach = glm::length(w.bodies()[id].halfExtents);  // the body's bounding sphere
      if (glm::length(w.bodyPose(id).center - p) < room + reach) return false;
    }
    const auto owners = w.particleBodies();
    for (std::size_t i = 0; i < owners.size(); ++i) {
      if (owners[i] == phys::kNoBody && glm::length(w.particles().position[i] - p) < room) return false;
    }
    return true;
  };
  for (int k = 0; k < kThrowTries; ++k) {
    const phys::Vec3 p = at + phys::Vec3(0.0, 2.0 * room * k, 0.0);
    if (clear(p)) return p;
  }
  return std::nullopt;
}

std::string Session::placed(const std::string& done, const phys::Vec3& asked, const phys::Vec3& spot) {
  if (spot == asked) return done;
  char higher[32];
  std::snprintf(higher, sizeof higher, "%.1f", spot.y - asked.y);
  return done + ", " + higher + " m higher: a body was in the way";
}

std::string Session::spawnBox(const phys::Vec3& at, const phys::Vec3& velocity) {
  const std::optional<phys::Vec3> spot = clearSpot(at, kBoxThrowRoom);
  if (!spot) {
    status_ = "nothing thrown: bodies in the way at the crosshair and above it";
    return status_;
  }
  phys::BodyDesc d;
  d.name = "thrown box " + std::to_string(spawned_ + 1);
  d.center = *spot;
  d.size = phys::Vec3(kSpawnBoxSize);
  d.mass = kSpawnBoxMass;
  d.model = throwModel_;
  d.velocity = velocity;
  return spawn(*spot, placed("threw a box", at, *spot), [&](phys::World& w) { w.addBody(d); });
}

std::string Session::spawn(const phys::Vec3& at, const std::string& done,
                           const std::function<void(phys::World&)>& add) {
  // What the loader would refuse to load, a throw refuses to make: beyond the bound the guard
  // would freeze it at once, and Save As could not write it.
  const double bound = scene().world.worldSettings().bound;
  if (!phys::insideBound(at, bound)) {
    status_ = "nothing thrown: the camera is beyond the world's bound of " + std::to_string(bound) + " m";
    return status_;
  }
  try {
    cancelSteps();
    // Each run's world is the main one's under other solver settings, so what the first takes
    // the others take.
    add(scene().world);
    for (std::size_t i = 1; i < runs_.size(); ++i) add(runs_[i].scene->world);
  } catch (const std::invalid_argument& e) {
    status_ = std::string("nothing thrown: ") + e.what();
    return status_;
  }
  ++spawned_;
  worldChanged();
  status_ = done;
  return {};
}

std::string Session::spawnRagdoll(const phys::Vec3& at, const phys::Vec3& velocity, bool capsules) {
  const std::optional<phys::Vec3> spot = clearSpot(at, kRagdollThrowRoom);
  if (!spot) {
    status_ = "nothing thrown: bodies in the way at the crosshair and above it";
    return status_;
  }
  phys::RagdollDesc d;
  d.name = (capsules ? "thrown capsule ragdoll " : "thrown ragdoll ") + std::to_string(spawned_ + 1);
  // Face the way it is thrown, lying forward so that it flies head first: from standing
  // (facing +z), turn to the throw's heading, then tip forward by 90 degrees.
  const double heading = std::atan2(velocity.x, velocity.z);
  d.orientation =
      glm::angleAxis(heading, phys::Vec3(0, 1, 0)) * glm::angleAxis(glm::radians(90.0), phys::Vec3(1, 0, 0));
  d.hips = *spot;
  d.velocity = velocity;
  d.model = phys::ragdollModelOf(throwModel_);
  if (capsules) {
    return spawn(*spot, placed("threw a capsule ragdoll", at, *spot),
                 [&](phys::World& w) { phys::addCapsuleRagdoll(w, d); });
  }
  return spawn(*spot, placed("threw a ragdoll", at, *spot), [&](phys::World& w) { phys::addRagdoll(w, d); });
}

bool Session::pick(const phys::Vec3& origin, const phys::Vec3& direction) {
  if (!phys::finite(origin) || !phys::finite(direction) || glm::length(direction) == 0.0) return false;
  const phys::World& w = scene().world;
  const std::optional<phys::RayHit> hit = w.raycast(origin, direction, 1000.0);
  if (!hit) return false;
  DragState d;
  d.isBox = hit->box.has_value();
  d.index = d.isBox ? *hit->box : *hit->particle;
  if (d.isBox) d.local = toLocal(w, *hit->box, hit->point);
  d.planePoint = hit->point;
  d.planeNormal = -direction;
  cancelSteps();
  for (Run& run : runs_) {
    phys::World& rw = run.scene->world;
    phys::Drag drag;
    if (d.isBox) {
      drag = rw.dragAt(phys::BodyId(d.index), toWorld(rw, phys::BodyId(d.index), d.local));
    } else {
      drag.point.particle[0] = phys::ParticleId(d.index);
      drag.point.weight[0] = 1.0;
      drag.point.count = 1;
      drag.target = rw.particles().position[d.index];
    }
    rw.setDrag(drag);
  }
  drag_ = d;
  dragTarget_.reset();
  // A spring the world has not stepped with has moved nothing: a rewound world is still the
  // recorded step, so a click on a body (or a double-click to follow it) leaves the recording
  // whole. It forks once the world steps with the spring (beforeStepping) or a command changes it.
  if (!rewound_) worldChanged();
  return true;
}

void Session::dragAlong(const phys::Vec3& origin, const phys::Vec3& direction) {
  if (!drag_) return;
  const phys::Vec3 target = onPlane(origin, direction, drag_->planePoint, drag_->planeNormal);
  if (!phys::finite(target)) return;  // a degenerate ray: keep the last target
  dragTarget_ = target;
  // Every run pulls its copy of the body towards the same point, so the runs stay comparable.
  forEachWorld([&](phys::World& w) { w.setDragTarget(target); });
}

void Session::release() {
  if (!drag_) return;
  // The copies in flight hold the drag: they are dropped, so the recording's keyframe after the
  // release is the state every later step starts from.
  cancelSteps();
  drag_.reset();
  dragTarget_.reset();
  forEachWorld([](phys::World& w) { w.clearDrag(); });
  if (!rewound_) worldChanged();  // a rewound world the spring never stepped is as recorded (pick)
}

std::optional<std::pair<phys::Vec3, phys::Vec3>> Session::dragLine() const {
  const phys::World& w = scene().world;
  if (!drag_ || !w.drag()) return std::nullopt;
  return std::make_pair(w.dragPoint(), w.drag()->target);
}

}  // namespace sandbox
