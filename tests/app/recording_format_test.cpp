// The recording file's format on its own (app/sandbox/recording_file.h; docs/sandbox.md, "Recording
// files"): a recording made from a project scene stepped here, encoded, decodes as it was, and damage
// of every kind is refused. In the scene tests, so that the sanitizer run (which builds no sandbox)
// reads damaged files too; recording_file_test.cpp drives the same files through the sandbox.
#include <cstddef>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "physics/world.h"
#include "recording_file.h"
#include "scenes/scene.h"
#include "scenes/scene_writer.h"

namespace {

// chain.xml stepped 30 times, each step kept as the sandbox keeps it: one part, its scene as saved.
sandbox::SavedRecording chainRecording() {
  scenes::Scene scene = scenes::loadSceneFile(std::string(DATA_DIR) + "/assets/scenes/chain.xml");
  sandbox::SavedRecording r;
  r.sceneName = scene.name;
  sandbox::SavedPart& part = r.parts.emplace_back();
  part.sceneXml = scenes::writeSceneXml(scene);
  part.structure = sandbox::structureKey(scene.world);
  for (int i = 0; i <= 30; ++i) {
    if (i > 0) scene.world.step();
    sandbox::SavedStep& s = part.steps.emplace_back();
    s.record.step = scene.world.stepCount();
    s.record.hash = scene.world.stateHash();
    s.motion = scene.world.motion();
  }
  return r;
}

TEST(RecordingFormat, DecodesAsEncoded) {
  const sandbox::SavedRecording r = chainRecording();
  const sandbox::SavedRecording back = sandbox::decodeRecording(sandbox::encodeRecording(r));
  EXPECT_EQ(back.sceneName, r.sceneName);
  ASSERT_EQ(back.parts.size(), 1u);
  EXPECT_EQ(back.parts[0].sceneXml, r.parts[0].sceneXml);
  EXPECT_EQ(back.parts[0].structure, r.parts[0].structure);
  ASSERT_EQ(back.stepCount(), 31u);
  for (std::size_t k = 0; k < r.parts[0].steps.size(); ++k) {
    EXPECT_EQ(back.parts[0].steps[k].record.hash, r.parts[0].steps[k].record.hash) << "step " << k;
    EXPECT_EQ(back.parts[0].steps[k].motion.hash(), r.parts[0].steps[k].record.hash) << "step " << k;
  }
}

// Damage of every kind, anywhere (a property test; the sanitizer run includes it): each is refused
// as a format error, never read past the end, never allocated from a damaged count.
TEST(RecordingFormat, RandomDamageIsAlwaysRefused) {
  const std::string bytes = sandbox::encodeRecording(chainRecording());
  std::mt19937 random(20261128);
  auto at = [&](std::size_t size) { return std::uniform_int_distribution<std::size_t>(0, size - 1)(random); };
  for (int trial = 0; trial < 3000; ++trial) {
    std::string damaged = bytes;
    switch (trial % 4) {
      case 0:  // a few bytes changed
        for (int k = 0; k < 1 + trial % 3; ++k) damaged[at(damaged.size())] ^= static_cast<char>(1 + at(255));
        break;
      case 1:  // a count or length made huge: the 8 bytes at a random place set to 0xff
        damaged.replace(at(damaged.size() - 8), 8, 8, '\xff');
        break;
      case 2:  // cut anywhere
        damaged.resize(at(damaged.size()));
        break;
      default:  // bytes put in
        damaged.insert(at(damaged.size()), std::string(1 + at(16), '\x7f'));
        break;
    }
    if (damaged == bytes) continue;
    EXPECT_THROW(sandbox::decodeRecording(damaged), sandbox::RecordingFormatError) << "trial " << trial;
  }
}

}  // namespace
