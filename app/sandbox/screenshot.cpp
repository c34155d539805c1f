#include "screenshot.h"

#include <string>
#include <system_error>

namespace sandbox {

std::filesystem::path screenshotPath(const std::filesystem::path& sceneFile, long step) {
  const std::filesystem::path folder = sceneFile.parent_path();
  const std::string base = sceneFile.stem().string() + "-step" + std::to_string(step);
  std::filesystem::path path = folder / (base + ".png");
  std::error_code ec;
  for (int n = 2; std::filesystem::exists(path, ec); ++n)
    path = folder / (base + "-" + std::to_string(n) + ".png");
  return path;
}

}  // namespace sandbox
