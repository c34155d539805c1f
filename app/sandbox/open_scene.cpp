#include "open_scene.h"

#include "accuracy.h"  // lab_core: <expect kind="position"> checked as the lab checks it

namespace sandbox {

scenes::LoadOptions sceneLoadOptions(std::optional<int> threads) {
  scenes::LoadOptions options;
  options.sleepUnlessSaid = true;
  options.threads = threads;
  return options;
}

std::unique_ptr<scenes::Scene> loadCheckedScene(const std::filesystem::path& file,
                                                const scenes::LoadOptions& options) {
  auto scene = std::make_unique<scenes::Scene>(scenes::loadSceneFile(file, options));
  static_cast<void>(lab::positionAnswers(*scene));
  return scene;
}

}  // namespace sandbox
