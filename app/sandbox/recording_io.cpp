#include "recording_io.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "fileio/files.h"
#include "scenes/scene_writer.h"

namespace sandbox {
namespace {

// What a part's scene carries that a step's motion (phys::Motion) does not, and that a command can
// change between two steps: the settings, and the joints' drives (the World panel's drive
// strength), less the targets and strengths a character gives its joints every substep from its
// own state, which its motion holds. A step whose world differs in any of these starts a new part,
// or the opened file would put it in a world with the drives it had before the change.
struct PartKey {
  phys::SolverSettings solver;
  phys::WorldSettings world;
  std::vector<phys::JointDrive> drives;  // rigid joints', then particle joints'

  explicit PartKey(const phys::World& w) : solver(w.solverSettings()), world(w.worldSettings()) {
    const std::size_t rigid = w.rigidJoints().size();
    drives.resize(rigid + w.particleJoints().size());
    for (std::size_t k = 0; k < rigid; ++k) drives[k] = w.jointDrive(k);
    for (std::size_t k = 0; k < w.particleJoints().size(); ++k) drives[rigid + k] = w.particleJointDrive(k);
    for (const phys::Character& c : w.characters()) {
      for (std::size_t b = 1; b < c.bones.size(); ++b) {
        phys::JointDrive& aimed = drives[(c.particleParts ? rigid : 0) + c.bones[b].joint];
        aimed.target = phys::Quat{1.0, 0.0, 0.0, 0.0};
        aimed.strength = 0.0;
      }
    }
  }
  bool operator==(const PartKey& o) const {
    auto same = [](const phys::JointDrive& a, const phys::JointDrive& b) {
      return a.target == b.target && a.strength == b.strength && a.stiffness == b.stiffness;
    };
    return solver == o.solver && world == o.world &&
           std::equal(drives.begin(), drives.end(), o.drives.begin(), o.drives.end(), same);
  }
};

// The world as a scene file's text, checked to load back into the same structure: a file that
// could not be opened again is never written.
std::string partScene(const scenes::Scene& scene, const phys::World& world, long step) {
  scenes::Scene at{scene.name, scene.description, scene.file, world, scene.camera, scene.bodies, {}};
  std::string xml;
  try {
    xml = scenes::writeSceneXml(at);
  } catch (const std::exception& e) {
    throw RecordingIoError("the world at step " + std::to_string(step) +
                           " cannot be written as a scene: " + e.what());
  }
  try {
    const scenes::Scene back = scenes::loadSceneText(xml, "the world at step " + std::to_string(step));
    if (structureKey(back.world) != structureKey(world)) {
      throw RecordingIoError("the world at step " + std::to_string(step) +
                             " does not load back with its bodies in the same order");
    }
  } catch (const scenes::LoadError& e) {
    throw RecordingIoError(std::string("the world at step ") + std::to_string(step) +
                           " written as a scene does not load back: " + e.what());
  }
  return xml;
}

}  // namespace

SavedRecording toSaved(const Recording& recording, const scenes::Scene& scene,
                       const std::function<void()>& stepDone) {
  SavedRecording saved;
  saved.sceneName = scene.name;
  std::optional<PartKey> partKey;  // of the current part
  std::string divergence;
  const bool whole = recording.replay(
      [&](const phys::World& world, const StepRecord& record) {
        const std::uint64_t key = structureKey(world);
        PartKey now(world);
        if (saved.parts.empty() || saved.parts.back().structure != key || !(*partKey == now)) {
          saved.parts.push_back({partScene(scene, world, record.step), key, {}});
          partKey = std::move(now);
        }
        saved.parts.back().steps.push_back({record, world.motion()});
        if (stepDone) stepDone();
      },
      divergence);
  if (!whole) throw RecordingIoError("the recording cannot be rebuilt: " + divergence);
  return saved;
}

namespace {

// The world a file's part puts its steps in, and the memory it took: its scene loaded with
// `options`, as a world written body by body (a generator in it is refused before anything is
// built), checked to build the bodies the steps were recorded in.
std::pair<std::shared_ptr<const phys::World>, std::size_t> partBase(const SavedPart& part,
                                                                    const std::string& which,
                                                                    const scenes::LoadOptions& options) {
  scenes::LoadOptions bodyByBody = options;
  bodyByBody.bodyByBody = true;
  std::pair<std::shared_ptr<const phys::World>, std::size_t> base;
  try {
    base = keptCopy(scenes::loadSceneText(part.sceneXml, "the recording's " + which, bodyByBody).world);
  } catch (const scenes::LoadError& e) {
    throw RecordingIoError(which + ": its scene does not load: " + e.what());
  }
  if (structureKey(*base.first) != part.structure) {
    throw RecordingIoError(which +
                           ": its scene builds bodies other than the ones recorded (a scene format or "
                           "loader of another version)");
  }
  return base;
}

}  // namespace

OpenedRecording recordingFromFile(std::string_view bytes,
                                  const std::function<void(const std::string&)>& scene,
                                  const ClipSource& clips, const scenes::LoadOptions& options,
                                  std::size_t budget) {
  constexpr std::size_t kNoPart = std::numeric_limits<std::size_t>::max();
  OpenedRecording out;
  out.recording.setBudget(budget);
  std::size_t current = kNoPart;            // the part being read
  std::shared_ptr<const phys::World> base;  // its world
  auto step = [&](std::size_t index, const SavedPart& part, SavedStep saved) {
    const std::string which = "part " + std::to_string(index + 1);
    std::size_t baseBytes = 0;  // the base's memory, counted with its part's first step
    if (index != current) {
      if (current == kNoPart) out.fileFirst = saved.record.step;
      std::tie(base, baseBytes) = partBase(part, which, options);
      current = index;
    }
    // Every step checked now, against the world it will be put in: a clip file changed since the
    // recording (other bones, no frames) is found on opening, not on a rewind to its step.
    if (const std::string problem = base->motionProblem(saved.motion); !problem.empty())
      throw RecordingIoError(which + ", step " + std::to_string(saved.record.step) + ": " + problem);
    out.recording.appendMotion(base, baseBytes, std::move(saved.motion), saved.record);
  };
  readRecording(bytes, {scene, clips, step});
  return out;
}

RecordingSaver::~RecordingSaver() {
  if (thread_.joinable()) thread_.join();
}

void RecordingSaver::start(Recording recording, scenes::Scene scene, std::filesystem::path file) {
  if (running()) return;
  if (thread_.joinable()) thread_.join();  // an earlier save, done but not collected
  file_ = std::move(file);
  error_.clear();
  saved_.clear();
  stepsDone_ = 0;
  steps_ = std::max(recording.last() - recording.first() + 1, 1L);
  done_ = false;
  thread_ = std::thread([this, r = std::move(recording), s = std::move(scene)] { run(r, s); });
}

void RecordingSaver::run(const Recording& recording, const scenes::Scene& scene) {
  try {
    const SavedRecording saved = toSaved(recording, scene, [this] { ++stepsDone_; });
    const std::string bytes = encodeRecording(saved);
    fileio::writeAtomically(file_, bytes);
    char size[32];
    std::snprintf(size, sizeof size, "%.1f MB", static_cast<double>(bytes.size()) / (1 << 20));
    saved_ = "saved steps " + std::to_string(saved.firstStep()) + " to " + std::to_string(saved.lastStep()) +
             " in " + file_.filename().string() + " (" + size + ")";
  } catch (const RecordingIoError& e) {
    error_ = file_.string() + ": cannot save the recording: " + e.what();
  } catch (const std::exception& e) {  // fileio::FileError (it names the file), or memory
    error_ = e.what();
  }
  done_ = true;
}

double RecordingSaver::progress() const {
  return static_cast<double>(stepsDone_.load()) / static_cast<double>(steps_);
}

std::optional<std::string> RecordingSaver::finish(std::string& saved, bool wait) {
  if (!thread_.joinable() || (!wait && !done_.load())) return std::nullopt;
  thread_.join();
  saved = saved_;
  return error_;
}

}  // namespace sandbox
