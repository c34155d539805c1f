#pragma once
// The sandbox's command layer: the scene (or, with the method overlay, the same scene under 2 to
// 4 solver settings), and every command a key, a menu or a panel can give it. No graphics here,
// so the tests drive it directly. A command that fails says why in its return value and leaves
// the world as it was.
#include <array>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "background_steps.h"
#include "overlay_spec.h"
#include "recording_io.h"
#include "run.h"
#include "scenes/scene.h"

namespace sandbox {

/// Each overlay run's colour, in order; the legend shows them.
inline constexpr glm::vec3 kRunColors[kMaxOverlayRuns] = {
    {0.95f, 0.55f, 0.15f}, {0.20f, 0.50f, 0.95f}, {0.25f, 0.80f, 0.30f}, {0.85f, 0.25f, 0.80f}};

/// The spawned box of F: a 0.5 m cube of 10 kg thrown at kThrowSpeed.
inline constexpr double kSpawnBoxSize = 0.5;   ///< unit: m
inline constexpr double kSpawnBoxMass = 10.0;  ///< unit: kg
inline constexpr double kThrowSpeed = 8.0;     ///< unit: m/s; the World panel's throw speed at first
/// How much room a throw needs: a sphere around its centre that no body may reach into (unit: m).
inline constexpr double kBoxThrowRoom = 0.45;      ///< the 0.5 m cube's half diagonal, and a little
inline constexpr double kRagdollThrowRoom = 0.95;  ///< half a ragdoll's height, and a little
/// Places a throw tries, each its own room higher than the last, before it gives up.
inline constexpr int kThrowTries = 5;

/// The strongest gravity changeGravity raises to, and the World panel's slider reaches: three
/// times the Earth's (m/s^2). A scene may set more; raising then leaves it as it is.
inline constexpr double kMaxRaisedGravity = 30.0;
/// unit: s; how long a clip chosen in the Animation block fades in over the one playing.
inline constexpr double kClipBlendTime = 0.3;
/// The Animation block's shoves: a push a balanced character withstands and one that throws it
/// over (the targets), each held kPushTime.
inline constexpr double kPushForce = 200.0;    ///< unit: N
inline constexpr double kKnockForce = 2000.0;  ///< unit: N
inline constexpr double kPushTime = 0.2;       ///< unit: s

class Session {
 public:
  /// Loads the first scene; throws scenes::LoadError if it cannot (there is nothing to keep).
  /// `threads`, if given, is imposed on every scene opened (the command line's --threads).
  Session(const std::filesystem::path& file, const std::filesystem::path& sceneDirectory,
          std::optional<int> threads = std::nullopt);
  /// Starts with `first`, which loadCheckedScene read from `file` with sceneLoadOptions(threads) (the
  /// sandbox opens the scene it is given before its window, to say what is wrong with it without one).
  Session(std::unique_ptr<scenes::Scene> first, const std::filesystem::path& file,
          const std::filesystem::path& sceneDirectory, std::optional<int> threads = std::nullopt);

  // Files. Each returns "" on success, else the message to show; on failure nothing changes.
  std::string open(const std::filesystem::path& file);
  std::string reload();
  /// Writes the main run's world and settings, with the camera where it is, atomically. The
  /// saved file becomes the current one (what Reload reads), as in any editor's Save As. During
  /// the method overlay: run 0's world with the solver settings from before the overlay.
  std::string saveAs(const std::filesystem::path& file, const scenes::CameraStart& camera);
  /// The solver settings saveAs writes: the main run's, or during the overlay those Stop gives back.
  const phys::SolverSettings& savedSolverSettings() const {
    return overlayActive() ? beforeOverlay_ : runs_.front().scene->world.solverSettings();
  }
  /// Opens assets/scenes/<name>.xml (the seed's keys 1, 2, 3).
  std::string openBuiltin(std::string_view name);
  /// Removes every body of every run, keeping the settings (the seed's key 0).
  void clear();
  const std::filesystem::path& file() const { return file_; }

  scenes::Scene& scene() { return *runs_.front().scene; }
  const scenes::Scene& scene() const { return *runs_.front().scene; }
  std::span<const Run> runs() const { return runs_; }
  bool overlayActive() const { return runs_.size() > 1; }

  /// Runs the current world under each of 2 to 4 settings, each from the state it is in now:
  /// run 0 becomes the first of them. Each setting overrides the settings the main run had
  /// before any overlay (so a restart does not stack them). Returns "" or why not (and changes
  /// nothing). A drag in progress is let go.
  std::string startOverlay(std::span<const OverlaySpec> specs);
  /// Keeps run 0 only, with the solver settings it had before the overlay.
  void stopOverlay();

  /// Steps the main run once, and every other run as many times as it takes to reach the main
  /// run's simulated time (a run with half the dt takes two steps), timing each step.
  void step();

  // The time budget (docs/sandbox.md): steps on another thread while the window draws the runs
  // as they are. Every command that changes a world cancels them first and acts on what is shown;
  // moving the drag does not, and its target is applied to the stepped runs instead.
  /// Up to `steps` steps of copies of the runs on another thread, no more once `budget` of wall
  /// time has gone by. Nothing when steps < 1 or steps are already running.
  void startSteps(int steps, std::chrono::duration<double> budget);
  bool stepping() const { return background_.running(); }
  /// When the background steps are done: their runs become these and it says what they took;
  /// nothing while they run or when none were started.
  std::optional<StepsTaken> finishSteps();
  /// Drops the background steps; the runs stay as they are.
  void cancelSteps();

  // Rewind and replay (recording.h): the main run's steps are recorded (not the overlay's).
  const Recording& recording() const { return recording_; }
  /// Shows the main run as it was at `step`, rebuilt from the recording; the next step or
  /// command resumes from there and the recording forks (what came after is dropped). A drag
  /// the recording had is let go. Returns "" or why not (not recorded, the overlay on, or the
  /// rebuilt step not matching the recorded one, which would be a bug).
  std::string rewindTo(long step);
  void setRecordingBudget(std::size_t bytes) { recording_.setBudget(bytes); }
  /// Writes the recording to `file` atomically (recording_file.h; docs/sandbox.md, "Recording
  /// files"), on a thread of its own (RecordingSaver), from a copy of the recording as it is now:
  /// the runs go on stepping meanwhile. Returns "" or why it cannot start (nothing recorded, the
  /// overlay on, a save running); finishSaving says how it ended.
  std::string startSavingRecording(const std::filesystem::path& file);
  /// While a save runs: the share of its steps written, 0 to 1.
  std::optional<double> savingProgress() const;
  /// Once the save is done: "" (status() then says what was saved) or why nothing was written (a
  /// step that cannot be rebuilt or written as a scene, a file error; the old file is as it was).
  /// None while it runs or when none was started. `wait` waits for it.
  std::optional<std::string> finishSaving(bool wait = false);
  /// startSavingRecording and finishSaving(wait): "" or why not.
  std::string saveRecording(const std::filesystem::path& file);
  /// When the program closes, with no window left to show it in: waits for a save still running
  /// and says how it ended ("saved ..." or "the recording was not saved: why"), or how one that
  /// ended unseen did; "" when there was none.
  std::string finishSavingOnClose();
  /// Opens a recording saved from this scene in place of the one kept, and shows its first step
  /// (as rewindTo does: stepping or a command resumes from the step shown). Returns "" or why not
  /// (a file error, not a recording, another format version, truncated or damaged, recorded in
  /// another scene, the overlay on); the current world and recording are then kept.
  std::string openRecording(const std::filesystem::path& file);

  // The seed's world controls; they act on every run, so the overlay keeps comparing methods
  // under the same forces. Each returns "" or why the world refused (then nothing changes), and
  // leaves either in status().
  /// Uniform gravity becomes a pull of the same strength towards the point, and back.
  std::string toggleGravityMode();
  /// Strength of gravity (|g| in uniform mode, the pull in point mode) changed by delta, kept
  /// from 0 to kMaxRaisedGravity (a stronger one, from the scene, is only lowered).
  std::string changeGravity(double delta);
  std::string changeDamping(double delta);
  /// The world settings of every run; "" or the validation message (and nothing changes).
  std::string setWorldSettings(const phys::WorldSettings& settings);
  /// The main run's solver settings (the panel's sliders); "" or the validation message.
  std::string setSolverSettings(const phys::SolverSettings& settings);
  /// Every rigid and particle joint's drive strength (phys::JointDrive::strength, 0 limp to 1
  /// holding its target) in every run, each joint keeping its own target and stiffness, and every
  /// character's strength (World::setCharacterStrength, its root's kept, a reaction under way
  /// stopped: a fallen character is active again where it lies); "" or why not (a strength
  /// outside [0, 1], no joint with a drive in the scene; then nothing changes).
  std::string setDriveStrength(double strength);
  /// Character k's joint strength, balance or reaction threshold (m/s) in every run (World's
  /// setCharacterStrength, setCharacterBalance, setCharacterReaction); "" or why not (then nothing
  /// changes).
  std::string setCharacterStrength(std::size_t k, double strength);
  std::string setCharacterBalance(std::size_t k, double balance);
  /// The share (0 to 1) of character k's strength its bone `bone`'s joint gets (World::setPartStrength).
  std::string setPartStrength(std::size_t k, const std::string& bone, double share);
  std::string setReactionThreshold(std::size_t k, double threshold);
  /// How long character k's turn-ins last (s, >= 0; World::setCharacterTurnIn) in every run; "" or why
  /// not (then nothing changes).
  std::string setCharacterTurnIn(std::size_t k, double seconds);
  /// Pushes character k's root part forwards (along the way it faces) with `newtons` for 0.2 s in
  /// every run: the sandbox's shove, to watch it stagger or fall.
  std::string pushCharacter(std::size_t k, double newtons);
  /// Character k changes to the clip in `file` (any format clips::loadClip reads; its bones must be
  /// the character's), from its start, faded in over kClipBlendTime, in every run; "" or why not (the
  /// file's error, or bones that do not match: then nothing changes).
  std::string playCharacterClip(std::size_t k, const std::filesystem::path& file, bool loop);
  /// Character k plays `playback` from now, faded in over blendTime (s; 0 cuts), in every run
  /// (World::playClip): the panel's scrub and loop switch cut to the same clip at another time or
  /// looping otherwise. "" or why not (then nothing changes).
  std::string setCharacterPlayback(std::size_t k, const phys::Playback& playback, double blendTime);

  /// Throws a box or a ragdoll (of boxes, or of capsules laid out like Bullet's) from `at` with
  /// velocity `velocity` into every run, never into a body: where a body reaches into the throw's
  /// room (kBoxThrowRoom, kRagdollThrowRoom), it goes from higher up, and the status says how much.
  /// Returns "" or why nothing was thrown: bodies in the way of every try, `at` beyond the world's
  /// bound, or a body the world refuses.
  std::string spawnBox(const phys::Vec3& at, const phys::Vec3& velocity);
  std::string spawnRagdoll(const phys::Vec3& at, const phys::Vec3& velocity, bool capsules = false);
  /// The model of what is thrown from now on: a box of it, a ragdoll of its kind (corners: seed,
  /// tetra: lean, rigid: rigid parts and joints).
  void setThrowModel(phys::BodyModel model) { throwModel_ = model; }
  phys::BodyModel throwModel() const { return throwModel_; }

  /// Left-drag picking: the body or particle hit by the ray gets a spring to the ray's point,
  /// in every run at the same place on the same body. False when the ray hits nothing or is
  /// not a ray (a zero or non-finite direction, as a zero-sized window gives). On a rewound world
  /// the recording forks only once the world steps with the spring: a click changes nothing.
  bool pick(const phys::Vec3& origin, const phys::Vec3& direction);
  /// Moves the spring's far end: the point on the picked plane (through the hit point, facing
  /// the view) under the ray.
  void dragAlong(const phys::Vec3& origin, const phys::Vec3& direction);
  void release();
  bool dragging() const { return drag_.has_value(); }
  /// Where the spring pulls from (the picked point now) and to, in the main run.
  std::optional<std::pair<phys::Vec3, phys::Vec3>> dragLine() const;

  /// What the last command did or why it failed, for the status line.
  const std::string& status() const { return status_; }

 private:
  struct DragState {
    bool isBox = false;
    std::uint32_t index = 0;     // BodyId or ParticleId
    phys::Vec3 local{0.0};       // the picked point in the box's frame
    phys::Vec3 planePoint{0.0};  // the plane the target moves in
    phys::Vec3 planeNormal{0.0};
  };
  void replaceMain(std::unique_ptr<scenes::Scene> scene, const std::filesystem::path& file);
  void forEachWorld(const std::function<void(phys::World&)>& apply);
  std::string changeCharacter(std::size_t k, const std::function<void(phys::World&)>& change);
  /// Where openRecording finds the clips a recording's characters play.
  ClipSource recordedClips() const;
  std::string applyWorldSettings(const phys::WorldSettings& settings, const std::string& done);
  /// A command changed the main run's world: the recording keeps it as it is now (and forks
  /// there if it was rewound).
  void worldChanged();
  /// A command changed it by `redo` alone, which holds `bytes` by copy (Recording::changed): the
  /// recording keeps the command, not a copy of the world, where it can.
  void worldChanged(std::function<void(phys::World&)> redo, std::size_t bytes);
  /// Before the main run steps: a rewound world forks the recording at its step.
  void beforeStepping();
  /// After it stepped, synchronously or in the background.
  void recordSteps(std::span<const StepRecord> records);
  std::string spawn(const phys::Vec3& at, const std::string& done,
                    const std::function<void(phys::World&)>& add);
  /// The first of `at` and the kThrowTries - 1 places above it (each `room` apart) that no body or
  /// loose particle of the main run reaches into; none when all are taken.
  std::optional<phys::Vec3> clearSpot(const phys::Vec3& at, double room) const;
  /// "done", or "done, h m higher: a body was in the way".
  static std::string placed(const std::string& done, const phys::Vec3& asked, const phys::Vec3& spot);

  std::vector<Run> runs_;
  std::filesystem::path file_;
  std::filesystem::path sceneDirectory_;
  scenes::LoadOptions load_;  // how every scene is opened: sleeping unless it says, --threads
  std::optional<DragState> drag_;
  phys::SolverSettings beforeOverlay_;  // the main run's settings when the overlay started
  std::string status_;
  int spawned_ = 0;
  phys::BodyModel throwModel_ = phys::BodyModel::Corners;
  std::optional<phys::Vec3> dragTarget_;  // the drag's last target, for runs stepped meanwhile
  Recording recording_;
  RecordingSaver saver_;
  bool rewound_ = false;        // the main run was rewound and has not stepped since
  BackgroundSteps background_;  // last: its thread stops before the rest goes
};

}  // namespace sandbox
