#pragma once
// The clip source of the recording fuzzer and of the program that writes its seeds: the project's
// own clips (assets/clips), by the names the scene loader gives them (the file's absolute path in
// the scenes' canonical folder), read once. A recording that names any other clip is refused as
// the sandbox refuses one whose clip cannot be read, with NoSuchClip; no name from a fuzzed file
// is ever opened.
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "clips/clip_file.h"
#include "physics/animation.h"
#include "recording_file.h"

namespace fuzz {

struct NoSuchClip : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline const std::map<std::string, std::shared_ptr<const phys::Clip>>& projectClips() {
  static const auto clips = [] {
    std::map<std::string, std::shared_ptr<const phys::Clip>> byName;
    const std::filesystem::path folder = std::filesystem::weakly_canonical(DATA_DIR "/assets/clips");
    for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
      if (!entry.is_regular_file() || entry.path().extension() != ".bvh") continue;
      const std::string name = entry.path().lexically_normal().string();
      byName.emplace(name, std::make_shared<const phys::Clip>(clips::loadClip(name)));
    }
    return byName;
  }();
  return clips;
}

inline sandbox::ClipSource projectClipSource() {
  return [](const std::string& name) {
    const auto& clips = projectClips();
    const auto it = clips.find(name);
    if (it == clips.end()) throw NoSuchClip("no project clip '" + name + "'");
    return it->second;
  };
}

}  // namespace fuzz
