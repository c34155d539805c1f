#pragma once
// A sandbox session on one of the project's scenes, as the sandbox opens it (tests of the command
// layer, the time budget and the recording).
#include <filesystem>
#include <string>

#include "session.h"

namespace testing_app {

inline const std::filesystem::path kProjectScenes = std::filesystem::path(DATA_DIR) / "assets" / "scenes";

/// assets/scenes/<name>.xml in a new session.
inline sandbox::Session openSession(const std::string& name) {
  return sandbox::Session(kProjectScenes / (name + ".xml"), kProjectScenes);
}

}  // namespace testing_app
