#pragma once
// Where F12 writes its PNG: next to the scene file, named after the scene and the step shown.
#include <filesystem>

namespace sandbox {

/// `<folder of sceneFile>/<its stem>-step<step>.png`, or with -2, -3... before .png when that
/// file exists already: a screenshot never writes over another.
std::filesystem::path screenshotPath(const std::filesystem::path& sceneFile, long step);

}  // namespace sandbox
