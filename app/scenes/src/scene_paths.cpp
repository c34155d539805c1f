#include <system_error>

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
  return sceneDir / (std::string(nameOrPath) + ".xml");
}

}  // namespace scenes
