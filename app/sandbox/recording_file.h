#pragma once
// Recording files (docs/sandbox.md, "Recording files"): a recording kept on disk, every step's
// motion (phys::Motion: the whole state the step hash covers) in parts of one structure and one set
// of settings, each part with the world at its start written as a scene file's text, to build the
// world the motions are put back in. Binary, little-endian, with a checksum; this file only encodes
// and decodes, Session reads and writes the files.
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "physics/motion.h"
#include "physics/world.h"
#include "recording.h"

namespace sandbox {

/// What a recording file's name ends in.
inline constexpr std::string_view kRecordingExtension = ".jrec";
/// The format this sandbox writes, and the only one it reads (2: characters' motions added).
inline constexpr std::uint32_t kRecordingFormat = 2;

/// One step: its record (step, hash, drag target) and the world's motion after it.
struct SavedStep {
  StepRecord record;
  phys::Motion motion;
};

/// Steps of one structure and one set of settings: the world at the first of them as a scene file
/// (scenes::writeSceneXml) and its structureKey.
struct SavedPart {
  std::string sceneXml;
  std::uint64_t structure = 0;
  std::vector<SavedStep> steps;
};

struct SavedRecording {
  std::string sceneName;  ///< the scene it was recorded in (scenes::Scene::name)
  std::vector<SavedPart> parts;

  long firstStep() const;
  long lastStep() const;
  std::size_t stepCount() const;
};

/// A hash of what a world is made of (its particles and which body each belongs to, its bodies'
/// models, shapes and particle ranges, its rigid bodies, sticks and joints, its characters' parts),
/// not of where any of it is: equal keys, a motion of one fits the other.
std::uint64_t structureKey(const phys::World& world);

/// A file that is not a recording this sandbox can read; what() says what is wrong and where (the
/// byte offset, the part and the step), without the file's name.
class RecordingFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The clip a recording names (a file's path, phys::Clip::name), for the characters' motions: a
/// clip of that name, or an exception saying why there is none.
using ClipSource = std::function<std::shared_ptr<const phys::Clip>(const std::string& name)>;

/// The name of the scene a recording's bytes were recorded in, read from its header alone (so that a
/// file of another scene is told apart before its clips are looked for). Throws RecordingFormatError
/// as decodeRecording would for a header that is not a recording's of this format.
std::string recordingSceneName(std::string_view bytes);

/// The file's bytes. Characters' clips are written by name, once per part.
std::string encodeRecording(const SavedRecording& recording);
/// Throws RecordingFormatError: not a recording, another format version, truncated, damaged (the
/// checksum, a step out of order, a motion not matching its hash, a non-finite number). The clips
/// the characters play are asked of `clips` by name, once each, and only of a file whose checksum
/// holds; what it throws goes through. A file that names clips needs a source.
SavedRecording decodeRecording(std::string_view bytes, const ClipSource& clips = {});

}  // namespace sandbox
