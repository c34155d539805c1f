#pragma once
// Scenes: a world ready to step, built from an XML scene file (docs/scene-format.md), plus
// where a viewer's camera starts and which bodies have names. The sandbox, the lab and the
// tests all load scenes through here, so a file means the same world everywhere.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "physics/animation.h"
#include "physics/ragdoll.h"
#include "physics/world.h"

namespace scenes {

/// The largest base row a <pyramid> takes (20100 boxes): public, so that a program generating
/// one (lab scale) refuses a larger size as its own argument, before generating anything.
inline constexpr long kMaxPyramidBase = 200;

/// Where the camera starts, in metres.
struct CameraStart {
  glm::vec3 eye{0.0f, 2.5f, 7.0f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  bool given = false;  ///< the file has a <camera>; without one, the sandbox keeps its camera where it is
};

/// A body a scene file gave a name (its own, or a generator's "stack[3]"). A capsule is a box
/// of Shape::Capsule, so its kind is Body.
struct NamedBody {
  enum class Kind { Body, Particle };
  std::string name;
  Kind kind = Kind::Body;
  std::uint32_t index = 0;  ///< phys::BodyId or phys::ParticleId, as kind says

  phys::BodyId body() const { return phys::BodyId(index); }
  phys::ParticleId particle() const { return phys::ParticleId(index); }
};

/// An <expect> element: something the lab checks of a run of this scene (an analytic answer, a
/// pass criterion; docs/lab.md says which attributes mean what). The loader keeps the
/// attributes as written, with the line, and the lab reads and checks them, so its errors can
/// name the file, the line and the attribute like the loader's. The sandbox ignores them.
struct Expectation {
  int line = 0;                                                 ///< 1-based, in the scene file
  std::vector<std::pair<std::string, std::string>> attributes;  ///< in file order

  /// The attribute's value as written, or nullptr.
  const std::string* find(std::string_view name) const;
};

/// Choices a caller may impose on a file as it is loaded (the lab's --model sweeps them).
struct LoadOptions {
  std::optional<phys::BodyModel> boxModel;         ///< every box, capsule, stack, pyramid and grid box
                                                   ///< (not ragdoll parts: ragdollModel says theirs)
  std::optional<phys::RagdollModel> ragdollModel;  ///< every ragdoll, of boxes or capsules
  /// Sleeping (SolverSettings::sleep) for a scene whose <solver> does not say: the sandbox's is on,
  /// everyone else's the physics' own default, off.
  bool sleepUnlessSaid = false;
  /// Sleeping imposed whatever the file says: the lab's --sleep.
  std::optional<bool> sleep;
  /// SolverSettings::jointProjection's on or off imposed whatever the file says: the lab's
  /// --joint-projection.
  std::optional<bool> jointProjection;
  /// SolverSettings::threads imposed whatever the file says: the sandbox's --threads.
  std::optional<int> threads;
  /// The file is a world written body by body (a recording's part scene, docs/scene-format.md
  /// "Files the sandbox saves"), which never holds an element that makes many bodies from one line
  /// (stack, pyramid, grid, chain, ragdoll): each is refused with its line before anything is built,
  /// as in a damaged file one such line of a few dozen bytes could ask for a gigabyte of boxes.
  bool bodyByBody = false;
};

struct Scene {
  std::string name;
  std::string description;     ///< one line; may be empty
  std::filesystem::path file;  ///< where it was loaded from; empty for a string
  phys::World world;
  CameraStart camera;
  std::vector<NamedBody> bodies;          ///< every named body, in file order
  std::vector<Expectation> expectations;  ///< the file's <expect> elements, in file order
};

/// A scene file that cannot be loaded. what() reads "file:line: <element> attribute 'a': why"
/// (the attribute part only when one attribute is to blame), or "file: why" when the file could
/// not be read at all (why then ends with the OS's reason). What follows "file:line: " and the
/// attribute quote the file, so they are made printable (fileio::printableReason: cut after 1000
/// bytes, control bytes as \xNN); the file's name is kept as given.
class LoadError : public std::runtime_error {
 public:
  LoadError(std::string file, int line, const std::string& attribute, const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }  ///< 1-based; 0 when the file could not be read at all
  const std::string& attribute() const { return attribute_; }

 private:
  std::string file_;
  int line_;
  std::string attribute_;
};

/// A clip file a scene names, as read with the scene: its clip, or why it could not be read
/// (clips::ClipError's what(), which loading gives as the naming attribute's error).
struct ReadClip {
  std::shared_ptr<const phys::Clip> clip;  ///< null when the file could not be read
  std::string error;
};

/// A scene file's text as read once, with what loading needs of the file besides: its name for
/// errors and Scene::file, the folder its relative clip and mesh paths are read from, and the clip
/// files it names. Every world built from it is the same scene, however the file or its clips
/// change after (the lab builds a run's every point from one).
struct SceneSource {
  std::filesystem::path file;
  std::string text;
  std::filesystem::path folder;  ///< where relative paths in the scene lead from
  /// Every clip file the text's <character>s name, by absolute path, read and parsed with the text:
  /// the worlds built from the source share them. A clip not here is read from its file as a world
  /// is built.
  std::map<std::string, ReadClip, std::less<>> clips;
};

/// Loads a scene file; throws LoadError and builds nothing on any error.
Scene loadSceneFile(const std::filesystem::path& file, const LoadOptions& options = {});
/// Reads a scene file and the clip files it names for loadSceneSource; throws LoadError (line 0)
/// when the scene file cannot be read, and, before reading any clip, at an error its text shows
/// without building a body (not XML, an unknown element, a bad setting). A clip that cannot be
/// read is kept as its error, which loading the source reports as loading the file would.
SceneSource readSceneSource(const std::filesystem::path& file);
/// Loads a scene from a file read before, as loadSceneFile loads the file.
Scene loadSceneSource(const SceneSource& source, const LoadOptions& options = {});
/// Loads a scene from text (tests, and files already in memory); `displayName` stands for the
/// file name in errors.
Scene loadSceneText(std::string_view xml, const std::string& displayName, const LoadOptions& options = {});

/// The folder of the project's scenes: <data dir>/assets/scenes.
std::filesystem::path sceneDirectory(const std::filesystem::path& dataDir);
/// A path as given if it names an existing file; otherwise <sceneDir>/<name>.xml (so
/// "pendulum" finds assets/scenes/pendulum.xml), unless there is no such scene and the name is of
/// something else here (a folder), which loading then names. Does not check that the result exists.
std::filesystem::path resolveScene(std::string_view nameOrPath, const std::filesystem::path& sceneDir);
/// The scene the sandbox opens with no argument, as a name for resolveScene.
inline constexpr std::string_view kDefaultScene = "ragdoll";  // the seed's scene 1

}  // namespace scenes
