// The recording file's format on its own (app/sandbox/recording_file.h; docs/sandbox.md, "Recording
// files"): a recording made from a project scene stepped here, encoded, decodes as it was, and damage
// of every kind is refused. In the scene tests, so that the sanitizer run (which builds no sandbox)
// reads damaged files too; recording_file_test.cpp drives the same files through the sandbox.
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "physics/world.h"
#include "recording_file.h"
#include "scenes/scene.h"
#include "scenes/scene_writer.h"

namespace {

// chain.xml stepped 30 times, each step kept as the sandbox keeps it: one part, its scene as saved.
sandbox::SavedRecording chainRecording() {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/chain.xml");
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

// tackle-capsules.xml (two characters, the tackler's dive queued) stepped 40 times, the runner told
// to play the tackler's clip on the way, and the clips its characters play, by name, as the
// decoder's source.
struct CharacterRecording {
  sandbox::SavedRecording recording;
  std::map<std::string, std::shared_ptr<const phys::Clip>> clips;
  int asked = 0;
  sandbox::ClipSource source() {
    return [this](const std::string& name) {
      ++asked;
      const auto it = clips.find(name);
      if (it == clips.end()) throw std::runtime_error("no clip '" + name + "'");
      return it->second;
    };
  }
};

CharacterRecording characterRecording() {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/tackle-capsules.xml");
  CharacterRecording out;
  sandbox::SavedRecording& r = out.recording;
  r.sceneName = scene.name;
  sandbox::SavedPart& part = r.parts.emplace_back();
  part.sceneXml = scenes::writeSceneXml(scene);
  part.structure = sandbox::structureKey(scene.world);
  for (int i = 0; i <= 40; ++i) {
    if (i == 20) scene.world.playClip(0, scene.world.characters()[1].now, 0.3);
    if (i > 0) scene.world.step();
    sandbox::SavedStep& s = part.steps.emplace_back();
    s.record.step = scene.world.stepCount();
    s.record.hash = scene.world.stateHash();
    s.motion = scene.world.motion();
  }
  for (const phys::Character& c : scene.world.characters()) {
    phys::forEachPlayback(c, [&out](const phys::Playback& p) {
      if (p.clip) out.clips.emplace(p.clip->name, p.clip);
    });
  }
  return out;
}

// The characters' clocks, fades, strengths and reactions come back as they were, every clip read
// once by name.
TEST(RecordingFormat, CharactersDecodeAsEncoded) {
  CharacterRecording r = characterRecording();
  const sandbox::SavedRecording back =
      sandbox::decodeRecording(sandbox::encodeRecording(r.recording), r.source());
  EXPECT_EQ(static_cast<std::size_t>(r.asked), r.clips.size());
  ASSERT_EQ(back.stepCount(), 41u);
  for (std::size_t k = 0; k < back.parts[0].steps.size(); ++k) {
    const phys::Motion& m = back.parts[0].steps[k].motion;
    const phys::Motion& was = r.recording.parts[0].steps[k].motion;
    ASSERT_EQ(m.characters.size(), 2u);
    EXPECT_EQ(m.hash(), was.hash()) << "step " << k;
    EXPECT_EQ(m.characters[0].now.time, was.characters[0].now.time);
    EXPECT_EQ(m.characters[0].now.clip, was.characters[0].now.clip);
    EXPECT_EQ(m.characters[0].blend, was.characters[0].blend);
    EXPECT_EQ(m.characters[0].before.clip, was.characters[0].before.clip);
  }
  EXPECT_LT(back.parts[0].steps[25].motion.characters[0].blend, 1.0);  // the fade under way
}

// A clip the source cannot give stops the decoding with the source's reason; a file whose checksum
// fails asks for none (a damaged name is not looked for).
TEST(RecordingFormat, ClipsComeFromTheSource) {
  CharacterRecording r = characterRecording();
  const std::string bytes = sandbox::encodeRecording(r.recording);
  r.clips.clear();
  try {
    sandbox::decodeRecording(bytes, r.source());
    ADD_FAILURE() << "decoded without its clips";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no clip '"), std::string::npos) << e.what();
  }
  std::string damaged = bytes;
  damaged[damaged.size() / 2] ^= 0x10;
  r.asked = 0;
  EXPECT_THROW(sandbox::decodeRecording(damaged, r.source()), sandbox::RecordingFormatError);
  EXPECT_EQ(r.asked, 0);
}

// A file whose checksum fails hands nothing over: not its scene's name, not a clip's, not a step,
// however far its headers read well.
TEST(RecordingFormat, ADamagedFileHandsNothingOver) {
  CharacterRecording r = characterRecording();
  const std::string bytes = sandbox::encodeRecording(r.recording);
  int handed = 0;
  const sandbox::RecordingVisitor visit{
      [&handed](const std::string&) { ++handed; }, r.source(),
      [&handed](std::size_t, const sandbox::SavedPart&, const sandbox::SavedStep&) { ++handed; }};
  sandbox::readRecording(bytes, visit);
  EXPECT_EQ(handed, 1 + 41);
  for (const std::size_t at : {std::size_t{30}, bytes.size() / 2, bytes.size() - 20}) {
    std::string damaged = bytes;
    damaged[at] ^= 0x01;
    handed = 0;
    r.asked = 0;
    try {
      sandbox::readRecording(damaged, visit);
      ADD_FAILURE() << "read with byte " << at << " damaged";
    } catch (const sandbox::RecordingFormatError& e) {
      EXPECT_NE(std::string(e.what()).find("the checksum does not match"), std::string::npos) << e.what();
    }
    EXPECT_EQ(handed, 0) << "byte " << at;
    EXPECT_EQ(r.asked, 0) << "byte " << at;
  }
}

// What the reader would refuse is never written: a step whose motion holds a non-finite number or
// an orientation not of unit length stops the encoding, naming the step.
TEST(RecordingFormat, AMotionTheReaderWouldRefuseIsNotWritten) {
  sandbox::SavedRecording r = chainRecording();
  r.parts[0].steps[12].motion.position[3].y = std::numeric_limits<double>::infinity();
  try {
    sandbox::encodeRecording(r);
    ADD_FAILURE() << "encoded a non-finite position";
  } catch (const sandbox::RecordingFormatError& e) {
    EXPECT_NE(std::string(e.what()).find("step 12: a non-finite position or velocity"), std::string::npos)
        << e.what();
  }
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
  CharacterRecording characters = characterRecording();
  for (const std::string& bytes :
       {sandbox::encodeRecording(chainRecording()), sandbox::encodeRecording(characters.recording)}) {
    SCOPED_TRACE(bytes.size());
    std::mt19937 random(20261128);
    auto at = [&](std::size_t size) {
      return std::uniform_int_distribution<std::size_t>(0, size - 1)(random);
    };
    for (int trial = 0; trial < 3000; ++trial) {
      std::string damaged = bytes;
      switch (trial % 4) {
        case 0:  // a few bytes changed
          for (int k = 0; k < 1 + trial % 3; ++k)
            damaged[at(damaged.size())] ^= static_cast<char>(1 + at(255));
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
      EXPECT_THROW(sandbox::decodeRecording(damaged, characters.source()), sandbox::RecordingFormatError)
          << "trial " << trial;
    }
  }
}

}  // namespace
