#pragma once
// A recording to a file's content and back (recording_file.h for the format): the main run's
// recording walked step by step into parts, and a file's parts built back into a recording.
#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

#include "recording.h"
#include "recording_file.h"
#include "scenes/scene.h"

namespace sandbox {

/// Why a recording could not be saved or opened; what() says which step or part and why.
class RecordingIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every step `recording` holds, a new part wherever the structure, the settings or a joint's drive
/// (other than a character's aim) change, each
/// part's world written as a scene with `scene`'s name, description and camera. Throws
/// RecordingIoError when a step cannot be rebuilt or a part's world cannot be written as a scene
/// that loads back into the same structure. `stepDone`, if given, is called after each step.
SavedRecording toSaved(const Recording& recording, const scenes::Scene& scene,
                       const std::function<void()>& stepDone = {});

/// A recording file opened: its steps as a recording, and the file's first step, before the budget
/// left any out.
struct OpenedRecording {
  Recording recording;
  long fileFirst = 0;
};

/// A recording file's content (recording_file.h) as a recording: each part's world loaded with
/// `options`, and each step put in it as it is read, the oldest beyond `budget` bytes let go on the
/// way, so that a file longer than the budget never takes more memory than the budget and a step.
/// `scene` is told the file's scene name before anything else is read and may throw to refuse it;
/// `clips` gives the clips the characters play. Throws RecordingFormatError for a file that is not
/// a recording this sandbox reads, and RecordingIoError when a part's scene does not load, does not
/// have the structure its steps were recorded in, or a step does not fit it.
OpenedRecording recordingFromFile(std::string_view bytes,
                                  const std::function<void(const std::string&)>& scene,
                                  const ClipSource& clips, const scenes::LoadOptions& options,
                                  std::size_t budget);

/// Writes a recording to a file on a thread of its own: saving rebuilds every step, which takes
/// seconds for a big scene (5.5 s for 10 s of Bullet's pile), and the window goes on meanwhile. It
/// works on a copy of the recording (its keyframes are shared, never changed) and of the scene.
class RecordingSaver {
 public:
  RecordingSaver() = default;
  ~RecordingSaver();
  RecordingSaver(const RecordingSaver&) = delete;
  RecordingSaver& operator=(const RecordingSaver&) = delete;

  /// Starts writing; nothing when a save is running.
  void start(Recording recording, scenes::Scene scene, std::filesystem::path file);
  bool running() const { return thread_.joinable() && !done_.load(); }
  /// Steps written of all the recording's, while it runs.
  double progress() const;
  /// Once it is done (waiting for it when `wait`): "" or the message of why nothing was written,
  /// and `saved` says what was; none while it runs or when none was started.
  std::optional<std::string> finish(std::string& saved, bool wait = false);

 private:
  void run(const Recording& recording, const scenes::Scene& scene);

  std::thread thread_;
  std::filesystem::path file_;
  std::atomic<bool> done_{false};
  std::atomic<long> stepsDone_{0};
  long steps_ = 1;
  std::string error_, saved_;  // written by the thread before done_, read after
};

}  // namespace sandbox
