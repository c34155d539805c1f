#include "scene_paths.h"

#include <system_error>

#include "fileio/files.h"
#include "scenes/scene.h"

namespace scenes {

std::filesystem::path sceneDirectory(const std::filesystem::path& dataDir) {
  return dataDir / "assets" / "scenes";
}

std::filesystem::path resolveScene(std::string_view nameOrPath, const std::filesystem::path& sceneDir) {
  std::filesystem::path given(nameOrPath);  // not const: returned by move
  std::error_code ec;
  if (std::filesystem::is_regular_file(given, ec)) return given;
  if (given.has_extension() || given.has_parent_path())
    return given;  // a path; let loading say it is missing
  std::filesystem::path project = sceneDir / (std::string(nameOrPath) + ".xml");
  // A bare name that is no project scene but names something here that is not a file (a folder, a
  // pipe, a link in a loop): that, so that loading says what it is ("is a folder, not a file"),
  // not that the project has no such scene.
  if (!std::filesystem::exists(std::filesystem::symlink_status(project, ec)) &&
      std::filesystem::exists(std::filesystem::symlink_status(given, ec)))
    return given;
  return project;
}

}  // namespace scenes

namespace scenes::detail {

std::filesystem::path clipFolder(const std::filesystem::path& sceneFile) {
  std::error_code ec;
  const std::filesystem::path file = std::filesystem::absolute(fileio::followLinks(sceneFile), ec);
  if (!ec) {
    std::filesystem::path folder = std::filesystem::weakly_canonical(file.parent_path(), ec);
    if (!ec) return folder;
  }
  throw fileio::FileError(sceneFile, "cannot find the folder its clips are named from: " + ec.message());
}

std::filesystem::path resolvedClip(const std::filesystem::path& clip) {
  std::error_code ec;
  const std::filesystem::path folder = std::filesystem::weakly_canonical(clip.parent_path(), ec);
  return ec ? clip : folder / clip.filename();
}

}  // namespace scenes::detail
