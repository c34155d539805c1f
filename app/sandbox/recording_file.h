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
/// The format this sandbox writes, and the only one it reads (2: characters' motions added; 3: whether
/// each stands on its support, without which a resumed balancing character lost its balance for a step;
/// 4: each one's turn-in, without which one resumed while turning in from a far pose could fold).
inline constexpr std::uint32_t kRecordingFormat = 4;

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

/// The file's bytes. Characters' clips are written by name, once per part. Throws
/// RecordingFormatError for a step whose motion the reader would refuse (phys::Motion::problem: a
/// non-finite number, an orientation not of unit length): a file that could not be opened is never
/// made.
std::string encodeRecording(const SavedRecording& recording);

/// What readRecording hands over, in the order the file holds it.
struct RecordingVisitor {
  /// The scene's name, once the checksum holds and before any clip is asked for or step read; it
  /// may throw to refuse the file (a recording of another scene: a damaged name is damage, not
  /// another scene's).
  std::function<void(const std::string& sceneName)> scene;
  /// The clips the characters play, by name, asked once each per part; a file that names clips
  /// needs a source. What it throws goes through.
  ClipSource clips;
  /// Each step in order, checked, with its part's index and its part (scene and structure; its
  /// steps left empty). A part of no steps is not handed over.
  std::function<void(std::size_t partIndex, const SavedPart& part, SavedStep step)> step;
};

/// Reads a recording one step at a time, so that a caller keeping only some of them (a budget)
/// never holds the rest. The checksum is checked over the whole file first: a damaged file hands
/// nothing over, and of it only the parts' headers are read (to say "truncated" where it is), no
/// step. Throws RecordingFormatError: not a recording, another format version, truncated, damaged
/// (the checksum, a step out of order, a motion not matching its hash, a non-finite number), or a
/// recording of no steps.
void readRecording(std::string_view bytes, const RecordingVisitor& visit);

/// readRecording with every step kept, for a file known to be small (tests, tools).
SavedRecording decodeRecording(std::string_view bytes, const ClipSource& clips = {});

}  // namespace sandbox
