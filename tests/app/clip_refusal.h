#pragma once
// What the clip reader says of a file's content (shared by the clip tests).
#include <filesystem>
#include <string>

#include "clips/clip_file.h"

namespace testing_clips {

/// The message parseClip refuses `content` with, named `name` (its extension the format), or
/// "loaded".
inline std::string refusal(const std::string& content, const std::string& name) {
  try {
    clips::parseClip(content, name, std::filesystem::path(name).extension().string().substr(1));
  } catch (const clips::ClipError& e) {
    return e.what();
  }
  return "loaded";
}

}  // namespace testing_clips
