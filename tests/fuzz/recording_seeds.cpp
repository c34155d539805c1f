// Writes the recording fuzzer's seed corpus (docs/architecture.md, "Fuzzing"): recordings of a few
// project scenes, made here rather than kept in the repository, so that they are always of the
// format this build reads and name the clips by the paths this checkout has.
//   recording_seeds FOLDER
// Each seed is decoded again with the fuzzer's clip source before it is kept: a seed that did not
// decode would only teach the fuzzer the reader's first refusals.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "fileio/files.h"
#include "physics/world.h"
#include "project_clips.h"
#include "recording_file.h"
#include "scenes/scene.h"
#include "scenes/scene_writer.h"

namespace {

// A new part: the world as it is now, as the sandbox starts one when the structure or a setting
// changes.
sandbox::SavedPart& newPart(sandbox::SavedRecording& r, const scenes::Scene& scene) {
  sandbox::SavedPart& part = r.parts.emplace_back();
  part.sceneXml = scenes::writeSceneXml(scene);
  part.structure = sandbox::structureKey(scene.world);
  return part;
}

void keepStep(sandbox::SavedPart& part, const phys::World& world) {
  sandbox::SavedStep& s = part.steps.emplace_back();
  s.record.step = world.stepCount();
  s.record.hash = world.stateHash();
  s.motion = world.motion();
}

struct Seed {
  const char* scene;  // in assets/scenes
  int steps;          // in each part
  bool secondPart;    // a second part after the solver's iterations change, as a slider does
  bool dragged;       // the steps record a drag target
};

// Small scenes of every kind a motion holds: loose particles, boxes, rigid bodies, characters.
constexpr Seed kSeeds[] = {
    {"chain", 4, false, true},
    {"falling-box", 3, true, false},
    {"rigid", 3, false, false},
    {"tackle-capsules", 3, true, false},
};

std::string encodeSeed(const Seed& seed) {
  scenes::Scene scene = scenes::loadSceneFile(std::string(DATA_DIR "/assets/scenes/") + seed.scene + ".xml");
  sandbox::SavedRecording r;
  r.sceneName = scene.name;
  sandbox::SavedPart* part = &newPart(r, scene);
  for (int i = 0; i < seed.steps; ++i) {
    scene.world.step();
    keepStep(*part, scene.world);
    if (seed.dragged) part->steps.back().record.dragTarget = phys::Vec3(0.1 * i, 1.0, 0.0);
  }
  if (seed.secondPart) {
    phys::SolverSettings settings = scene.world.solverSettings();
    settings.iterations += 1;
    scene.world.setSolverSettings(settings);
    part = &newPart(r, scene);
    for (int i = 0; i < seed.steps; ++i) {
      scene.world.step();
      keepStep(*part, scene.world);
    }
  }
  return sandbox::encodeRecording(r);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: recording_seeds FOLDER\n");
    return 2;
  }
  try {
    const std::filesystem::path folder = argv[1];
    std::filesystem::create_directories(folder);
    for (const Seed& seed : kSeeds) {
      const std::string bytes = encodeSeed(seed);
      const sandbox::SavedRecording back = sandbox::decodeRecording(bytes, fuzz::projectClipSource());
      if (back.stepCount() == 0) throw std::runtime_error(std::string(seed.scene) + ": no steps decoded");
      const std::filesystem::path file = folder / (std::string(seed.scene) + ".jrec");
      fileio::writeAtomically(file, bytes);
      std::printf("%s: %zu bytes, %zu parts, %zu steps\n", file.c_str(), bytes.size(), back.parts.size(),
                  back.stepCount());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "recording_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
