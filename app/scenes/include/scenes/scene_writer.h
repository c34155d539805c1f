#pragma once
// Saving a world as a scene file (docs/scene-format.md, "Files the sandbox saves"): the world
// as it is now, after any number of steps and with whatever was added at run time, plus its
// settings and a camera, in a file that loadSceneFile builds back into the same world.
#include <filesystem>
#include <stdexcept>
#include <string>

#include "scenes/scene.h"

namespace scenes {

/// A scene that could not be saved. what() reads "file: why"; the old file, if any, is as it was.
class SaveError : public std::runtime_error {
 public:
  SaveError(std::filesystem::path file, const std::string& message);
  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
};

/// The scene as XML, with the camera where `camera` says (the sandbox passes its own).
/// Bodies come from the world's current state: each box as the rigid body fitted to its
/// particles, loose particles, sticks between them, links, and pairs kept from colliding.
/// Throws std::invalid_argument for what no scene file can express (a stick from a loose
/// particle to a box's particle, a non-finite number, a description of more than one line).
/// Characters' clip files are named by their absolute paths, or, with `folder` (the folder the
/// text is to be saved in, its symbolic links resolved), relative to it, as a scene file names them.
std::string writeSceneXml(const Scene& scene, const CameraStart& camera,
                          const std::filesystem::path& folder = {});
/// The same, with the camera the scene was loaded with, or none if it had no <camera>.
std::string writeSceneXml(const Scene& scene);

/// Writes writeSceneXml's text to `file` atomically, clip files named relative to its folder: a temporary
/// file in the same folder, flushed to disk, then renamed over `file`. Throws SaveError naming the file on
/// any error, leaving the old file untouched and no temporary file behind.
void saveSceneFile(const Scene& scene, const CameraStart& camera, const std::filesystem::path& file);
/// The same, with the camera the scene was loaded with, or none if it had no <camera>.
void saveSceneFile(const Scene& scene, const std::filesystem::path& file);

}  // namespace scenes
