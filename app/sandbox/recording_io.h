#pragma once
// A recording to a file's content and back (recording_file.h for the format): the main run's
// recording walked step by step into parts, and a file's parts built back into a recording.
#include <cstddef>
#include <stdexcept>

#include "recording.h"
#include "recording_file.h"
#include "scenes/scene.h"

namespace sandbox {

/// Why a recording could not be saved or opened; what() says which step or part and why.
class RecordingIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Every step `recording` holds, a new part wherever the structure or the settings change, each
/// part's world written as a scene with `scene`'s name, description and camera. Throws
/// RecordingIoError when a step cannot be rebuilt or a part's world cannot be written as a scene
/// that loads back into the same structure.
SavedRecording toSaved(const Recording& recording, const scenes::Scene& scene);

/// A recording holding the file's steps (within `budget` bytes: the oldest beyond it are left
/// out), each part's world loaded with `options`. Throws RecordingIoError when a part's scene does
/// not load or does not have the structure its steps were recorded in.
Recording fromSaved(const SavedRecording& saved, const scenes::LoadOptions& options, std::size_t budget);

}  // namespace sandbox
