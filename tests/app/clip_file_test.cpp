// Clips from files (docs/physics.md, "Animation"): the project's BVH clips read through assimp as
// scripts/make-clips wrote them; bad files refused with the file and the reason, nothing half read;
// <character> in scenes, its errors, Save As; the run cycle tracked with the root carried, by the box
// ragdoll and the capsule ragdoll.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "bad_scene.h"
#include "clip_refusal.h"
#include "clips/clip_file.h"
#include "physics/character.h"
#include "scenes/scene.h"
#include "scenes/scene_writer.h"
#include "temp_folder.h"
#include "world_compare.h"

namespace {

const std::string kClips = std::string(DATA_DIR) + "/assets/clips/";
constexpr double kDeg = std::numbers::pi / 180.0;

TEST(ClipFile, TheRunCycleIsReadAsWritten) {
  const phys::Clip run = clips::loadClip(kClips + "run.bvh");
  ASSERT_EQ(phys::clipProblem(run), "");
  ASSERT_EQ(run.bones.size(), 10u);
  EXPECT_EQ(run.bones[0], "torso");
  EXPECT_EQ(run.parents[0], -1);
  EXPECT_EQ(run.bones[3], "lower-arm-left");
  EXPECT_EQ(run.bones[static_cast<std::size_t>(run.parents[3])], "upper-arm-left");
  EXPECT_EQ(run.frames(), 37u);
  EXPECT_NEAR(run.duration(), 0.72, 1e-6);  // scripts/make-clips: RUN_PERIOD
  // One loop goes 3 m/s x 0.72 s forward; the torso leans 8 degrees forward throughout.
  EXPECT_NEAR(run.root.back().z - run.root.front().z, 2.16, 1e-4);
  EXPECT_NEAR(2.0 * std::acos(run.turns[0].w), 8.0 * kDeg, 1e-5);
  EXPECT_GT(run.turns[0].x, 0.0);
}

// The message loadClip refuses the file with, or "loaded".
std::string clipError(const std::filesystem::path& file) {
  try {
    clips::loadClip(file);
  } catch (const clips::ClipError& e) {
    return e.what();
  }
  return "loaded";
}

TEST(ClipFile, BadFilesAreRefusedWithTheFileAndTheReason) {
  const testing_app::TempFolder dir;
  const std::string missing = clipError(dir.path / "missing.bvh");
  EXPECT_NE(missing.find("missing.bvh"), std::string::npos) << missing;
  EXPECT_NE(missing.find("No such file or directory"), std::string::npos) << missing;
  // assimp's BVH reader says the line, after its placeholder name for memory: the file's own name
  // stands there, the line kept.
  std::ofstream(dir.path / "cut.bvh") << "HIERARCHY\nROOT a\n{\n  OFFSET 0 0\n";
  const std::string cut = clipError(dir.path / "cut.bvh");
  EXPECT_NE(cut.find("cut.bvh:5: not a clip assimp can read: Unexpected end of file"), std::string::npos)
      << cut;
  EXPECT_EQ(cut.find("magic"), std::string::npos) << cut;
  // A format no clip is read from, refused before assimp; assimp's own refusal of a format it has
  // a reader for comes without its placeholder name for memory.
  std::ofstream(dir.path / "script.sh") << "#!/bin/sh\necho\n";
  const std::string script = clipError(dir.path / "script.sh");
  EXPECT_NE(script.find("script.sh: not a clip file"), std::string::npos) << script;
  std::ofstream(dir.path / "script.fbx") << "#!/bin/sh\necho\n";
  const std::string fbx = clipError(dir.path / "script.fbx");
  EXPECT_NE(fbx.find("script.fbx: not a clip assimp can read: "), std::string::npos) << fbx;
  EXPECT_EQ(fbx.find("magic"), std::string::npos) << fbx;
  // A pipe with no writer would block the loader (and the sandbox) in open(): refused at once, as
  // is a folder.
  ASSERT_EQ(::mkfifo((dir.path / "pipe.bvh").c_str(), 0600), 0);
  const std::string pipe = clipError(dir.path / "pipe.bvh");
  EXPECT_NE(pipe.find("pipe.bvh: is not a regular file"), std::string::npos) << pipe;
  std::filesystem::create_directory(dir.path / "folder.bvh");
  const std::string folder = clipError(dir.path / "folder.bvh");
  EXPECT_NE(folder.find("folder.bvh: is not a regular file"), std::string::npos) << folder;
  // A BVH with a turn no quaternion can hold is refused, with the line (BvhValuesOutOfRange...).
  std::ofstream(dir.path / "nan.bvh") << "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition "
                                         "Yposition Zposition Zrotation Xrotation Yrotation\n}\nMOTION\n"
                                         "Frames: 1\nFrame Time: 0.1\n0 0 0 0 nan 0\n";
  EXPECT_NE(clipError(dir.path / "nan.bvh").find("nan.bvh:10: "), std::string::npos);
  // A Frame Time that is no time, and a header of no frames: assimp took 25 frames a second for the
  // first (played at 0.04 s a frame) and one key of its own for the second; refused, not guessed.
  const std::string header =
      "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Xrotation Yrotation\n}\nMOTION\n";
  for (const char* time : {"-1", "nan", "inf", "1e39", "1e-7", "soon"}) {
    SCOPED_TRACE(time);
    std::ofstream(dir.path / "time.bvh")
        << header << "Frames: 2\nFrame Time: " << time << "\n0 0 0 0 0 0\n0 0 0 0 0 0\n";
    const std::string e = clipError(dir.path / "time.bvh");
    EXPECT_NE(e.find("time.bvh:9: Frame Time: '" + std::string(time) +
                     "' is not a finite number of seconds >= 1e-6"),
              std::string::npos)
        << e;
  }
  std::ofstream(dir.path / "none.bvh") << header << "Frames: 0\nFrame Time: 0.1\n";
  const std::string none = clipError(dir.path / "none.bvh");
  // Refused with its line: assimp keyed it once, and the clip's own check said "it has no frames".
  EXPECT_NE(none.find("none.bvh:8: Frames: 0: a clip has at least one frame"), std::string::npos) << none;
  // Two joints of one name, which the clip's check refused once assimp had read the file, with no line.
  std::ofstream(dir.path / "twice.bvh")
      << "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  JOINT a\n  {\n"
         "    OFFSET 0 1 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n  }\n}\nMOTION\nFrames: 1\n"
         "Frame Time: 0.1\n0 0 0 0 0 0\n";
  const std::string same = clipError(dir.path / "twice.bvh");
  EXPECT_NE(same.find("twice.bvh:6: joint 'a' is named as the one on line 2"), std::string::npos) << same;
  std::ofstream(dir.path / "two.bvh") << header << "Frames: 2\nFrame Time: 0.1\n0 0 0 0 0 0\n0 0 0 0 0 0\n";
  EXPECT_EQ(clipError(dir.path / "two.bvh"), "loaded");
}

// An empty file reached assimp, whose refusal said nothing of the file ("Invalid parameters passed to
// ReadFileFromMemory()"), in every format.
TEST(ClipFile, AnEmptyClipFileIsSaidToBeEmpty) {
  const testing_app::TempFolder dir;
  for (const char* name : {"empty.bvh", "empty.fbx", "empty.gltf", "empty.glb", "empty.dae", "empty.x"}) {
    { std::ofstream empty(dir.path / name); }  // created empty
    const std::string e = clipError(dir.path / name);
    EXPECT_NE(e.find(std::string(name) + ": is empty"), std::string::npos) << e;
    EXPECT_EQ(e.find("ReadFileFromMemory"), std::string::npos) << e;
  }
}

// A reason quotes what the file holds, ours a number, assimp a keyword: a megabyte token that starts
// with a terminal's "clear screen" is cut, saying how much more there was, and its control byte shown.
TEST(ClipFile, AssimpsReasonIsCutAndItsControlBytesShown) {
  const std::string channels =
      "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition "
      "Zrotation Xrotation Yrotation\n";
  const std::string token = "\x1b[2J" + std::string(std::size_t{1} << 20, '9');
  const auto expectCut = [](const std::string& e, const std::string& start) {
    EXPECT_EQ(e.rfind(start, 0), 0u) << e.substr(0, 200);
    EXPECT_LT(e.size(), 600u);
    EXPECT_NE(e.find(" more bytes)"), std::string::npos) << e.substr(0, 600);
    EXPECT_EQ(e.find('\x1b'), std::string::npos);
  };
  expectCut(
      testing_clips::refusal(channels + "}\nMOTION\nFrames: " + token + "\nFrame Time: 0.1\n", "ours.bvh"),
      "ours.bvh:8: Frames: '\\x1b[2J999");
  expectCut(testing_clips::refusal(
                channels + token + "\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0 0 0 0\n", "theirs.bvh"),
            "theirs.bvh:6: not a clip assimp can read: Unknown keyword \"\\x1b[2J999");
  // A short reason is kept whole.
  EXPECT_EQ(testing_clips::refusal(channels + "}\nMOTION\nFrames: x\nFrame Time: 0.1\n", "short.bvh"),
            "short.bvh:8: Frames: 'x' is not a whole number >= 0");
}

const std::string kBvhHeader =
    "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition "
    "Zrotation Xrotation Yrotation\n}\nMOTION\n";  // Frames: on line 8

// A BVH whose root has `joints` joints below it, each inside the one before (`nested`) or all side
// by side, every one turning; one frame, at rest. The root's "{" is on line 3, joint j's on line
// 7 + 4j nested and its JOINT on line 6 + 5j side by side.
std::string skeletonBvh(int joints, bool nested) {
  std::string bvh =
      "HIERARCHY\nROOT root\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation "
      "Xrotation Yrotation\n";
  std::string frame = "0 0 0 0 0 0";
  for (int j = 0; j < joints; ++j) {
    bvh +=
        "JOINT j" + std::to_string(j) + "\n{\n  OFFSET 0 1 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n";
    if (!nested) bvh += "}\n";
    frame += " 0 0 0";
  }
  if (nested) {
    for (int j = 0; j < joints; ++j) bvh += "}\n";
  }
  return bvh + "}\nMOTION\nFrames: 1\nFrame Time: 0.1\n" + frame + "\n";
}

TEST(ClipFile, JointsNestedTooDeepAreRefusedWithTheLine) {
  const testing_app::TempFolder dir;
  // 50,000 levels, 2 MB: assimp's reader, which recurses once a level, overflowed the stack.
  std::ofstream(dir.path / "deep.bvh") << skeletonBvh(50000, true);
  const std::string deep = clipError(dir.path / "deep.bvh");
  EXPECT_NE(deep.find("deep.bvh:1027: joints nested more than 256 deep"), std::string::npos) << deep;
  // 256 levels, the root's and 255 joints', are read; one more is refused.
  std::ofstream(dir.path / "limit.bvh") << skeletonBvh(255, true);
  EXPECT_EQ(clipError(dir.path / "limit.bvh"), "loaded");
  std::ofstream(dir.path / "past.bvh") << skeletonBvh(256, true);
  const std::string past = clipError(dir.path / "past.bvh");
  EXPECT_NE(past.find("past.bvh:1027: joints nested more than 256 deep"), std::string::npos) << past;
}

TEST(ClipFile, MoreJointsThanASkeletonHasAreRefusedWithTheLine) {
  // Each node's channel is looked for among all of them: 50,000 joints side by side took a minute.
  const testing_app::TempFolder dir;
  std::ofstream(dir.path / "wide.bvh") << skeletonBvh(999, false);
  EXPECT_EQ(clipError(dir.path / "wide.bvh"), "loaded");
  std::ofstream(dir.path / "wider.bvh") << skeletonBvh(1000, false);
  const std::string wider = clipError(dir.path / "wider.bvh");
  EXPECT_NE(wider.find("wider.bvh:5001: more than 1000 joints"), std::string::npos) << wider;
}

// The refusals below are ours, so assimp never read the files, and allocated nothing for them.
TEST(ClipFile, AFrameCountTheFileDoesNotHoldIsRefusedWithTheLine) {
  const testing_app::TempFolder dir;
  const auto refusal = [&](const std::string& frames, const std::string& motion) {
    std::ofstream(dir.path / "frames.bvh") << kBvhHeader << "Frames: " << frames << "\nFrame Time: 0.1\n"
                                           << motion;
    return clipError(dir.path / "frames.bvh");
  };
  const std::string two = "0 0 0 0 0 0\n0 0 0 0 0 0\n";
  // assimp read a count as a float and truncated it: 2.7 was 2 frames, -1 or 1e9 a bad_alloc.
  for (const char* frames : {"-1", "2.7", "1e3", "two"}) {
    SCOPED_TRACE(frames);
    const std::string e = refusal(frames, two);
    EXPECT_NE(e.find("frames.bvh:8: Frames: '" + std::string(frames) + "' is not a whole number >= 0"),
              std::string::npos)
        << e;
  }
  const std::string billion = refusal("1000000000", two);
  EXPECT_NE(
      billion.find("frames.bvh:8: Frames: 1000000000 of 6 numbers each is more than the file holds: its "
                   "motion ends on line 11 after 12 numbers"),
      std::string::npos)
      << billion;
  const std::string huge = refusal("99999999999999999999999", two);
  EXPECT_NE(huge.find("frames.bvh:8: Frames: 99999999999999999999999 of 6 numbers each is more"),
            std::string::npos)
      << huge;
  // Motion past the last frame was left unread.
  const std::string extra = refusal("2", two + "0 0 0 0 0 0\n");
  EXPECT_NE(extra.find("frames.bvh:12: motion past its last frame (Frames: 2 on line 8, 6 numbers a frame)"),
            std::string::npos)
      << extra;
  EXPECT_EQ(refusal("2", two), "loaded");
}

// A number past its range became inf or NaN in assimp's float (an angle of 1e308, an OFFSET of
// 1e308), or a root too far for the clip: the clip's own check refused the turn without the line.
// Each value is refused with its line, its frame and its channel.
TEST(ClipFile, BvhValuesOutOfRangeAreRefusedWithTheLine) {
  const testing_app::TempFolder dir;
  const auto refusal = [&](const std::string& head, const std::string& motion) {
    std::ofstream(dir.path / "values.bvh") << head << "Frames: 2\nFrame Time: 0.1\n0 0 0 0 0 0\n" << motion;
    return clipError(dir.path / "values.bvh");
  };
  const std::pair<const char*, const char*> cases[] = {
      {"0 0 0 1e308 0 0",
       "values.bvh:11: frame 1, joint 'a' Zrotation: '1e308' is not an angle within 1e6 "
       "degrees either way"},
      {"0 0 0 0 nan 0", "values.bvh:11: frame 1, joint 'a' Xrotation: 'nan' is not an angle"},
      {"0 0 0 0 0 -inf", "values.bvh:11: frame 1, joint 'a' Yrotation: '-inf' is not an angle"},
      {"0 0 0 0 0 1e400", "values.bvh:11: frame 1, joint 'a' Yrotation: '1e400' is not an angle"},
      {"0 0 0 0 0 2e6", "values.bvh:11: frame 1, joint 'a' Yrotation: '2e6' is not an angle"},
      {"0 0 0 0 0 x", "values.bvh:11: frame 1, joint 'a' Yrotation: 'x' is not an angle"},
      {"0 1e7 0 0 0 0",
       "values.bvh:11: frame 1, joint 'a' Yposition: '1e7' is not a position within 1e6 "
       "of the origin"},
      {"9e5\n9e5 0 0 0 0", "values.bvh:12: frame 1: the root 'a' is farther than 1e6 from the origin"}};
  for (const auto& [motion, says] : cases) {
    SCOPED_TRACE(motion);
    const std::string e = refusal(kBvhHeader, std::string(motion) + "\n");
    EXPECT_NE(e.find(says), std::string::npos) << e;
  }
  std::string offset = kBvhHeader;
  offset.replace(offset.find("OFFSET 0 0 0"), 12, "OFFSET 0 1e308 0");
  const std::string e = refusal(offset, "0 0 0 0 0 0\n");
  EXPECT_NE(e.find("values.bvh:4: OFFSET: '1e308' is not a finite number"), std::string::npos) << e;
  // Every way of writing a number that assimp reads is still read: its fast_atoreal_move takes a
  // decimal comma too.
  EXPECT_EQ(refusal(kBvhHeader, "+1 .5 1. -0 1e2 -359.5\n"), "loaded");
  EXPECT_EQ(refusal(kBvhHeader, "0,5 1,5e2 -0,25 0 0 0\n"), "loaded");
  // A joint's channels are each kept while the skeleton is read: a count past six is refused where
  // it stands, before a file of 64 MB could have all its words kept.
  std::string channels = kBvhHeader;
  channels.replace(channels.find("CHANNELS 6"), 10, "CHANNELS 99999999999");
  const std::string many = refusal(channels, "0 0 0 0 0 0\n");
  EXPECT_NE(many.find("values.bvh:5: CHANNELS 99999999999: a joint has at most 6"), std::string::npos)
      << many;
}

TEST(ClipFile, AFileOfNoChannelsHoldsOneFrame) {
  // Its frames are empty lines, which assimp took on trust, keying every joint at each: three
  // joints and "Frames: 50000000", 200 bytes, made it allocate 3.5 GB.
  const testing_app::TempFolder dir;
  const std::string still =
      "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 0\nJOINT b\n{\nOFFSET 0 1 0\nCHANNELS 0\nJOINT c\n{\n"
      "OFFSET 0 1 0\nCHANNELS 0\n}\n}\n}\nMOTION\n";  // Frames: on line 18
  std::ofstream(dir.path / "still.bvh") << still << "Frames: 1000\nFrame Time: 0.1\n";
  const std::string many = clipError(dir.path / "still.bvh");
  EXPECT_NE(many.find("still.bvh:18: Frames: 1000, but no joint has a channel"), std::string::npos) << many;
  std::ofstream(dir.path / "still.bvh") << still << "Frames: 1\nFrame Time: 0.1\n";
  const phys::Clip pose = clips::loadClip(dir.path / "still.bvh");
  EXPECT_EQ(pose.frames(), 1u);
  EXPECT_EQ(pose.bones.size(), 3u);
}

TEST(ClipFile, MoreKeysThanAClipFileHoldsAreRefused) {
  // A joint of no channels is keyed at every frame all the same, so the frames a root's numbers make
  // are keyed at every joint: 1000 joints at 11,185 frames make more keys than 64 MB of turns.
  const testing_app::TempFolder dir;
  std::string bvh = "HIERARCHY\nROOT a\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  for (int j = 0; j < 999; ++j) bvh += "JOINT j" + std::to_string(j) + " { OFFSET 0 1 0 CHANNELS 0 }\n";
  bvh += "}\nMOTION\nFrames: 11185\nFrame Time: 0.1\n";  // Frames: on line 1007
  for (int f = 0; f < 11185; ++f) bvh += "0 0 0\n";
  std::ofstream(dir.path / "keys.bvh") << bvh;
  const std::string keys = clipError(dir.path / "keys.bvh");
  EXPECT_NE(keys.find("keys.bvh:1007: Frames: 11185 of 1000 joints is more keys than a clip file holds"),
            std::string::npos)
      << keys;
}

TEST(ClipFile, ABvhIsOneInAnyCaseOrByItsFirstWord) {
  // "Frames: 0" refused as no frames in a .bvh, where a .Bvh or .txt loaded as assimp's one key.
  const testing_app::TempFolder dir;
  for (const char* file : {"none.Bvh", "none.BVH", "none.txt", "none"}) {
    SCOPED_TRACE(file);
    std::ofstream(dir.path / file) << kBvhHeader << "Frames: 0\nFrame Time: 0.1\n";
    const std::string e = clipError(dir.path / file);
    EXPECT_NE(e.find(std::string(file) + ":8: Frames: 0: a clip has at least one frame"), std::string::npos)
        << e;
  }
  // And so are the checks before assimp reads the file.
  std::ofstream(dir.path / "frames.txt") << kBvhHeader << "Frames: 2.7\nFrame Time: 0.1\n0 0 0 0 0 0\n";
  const std::string e = clipError(dir.path / "frames.txt");
  EXPECT_NE(e.find("frames.txt:8: Frames: '2.7' is not a whole number"), std::string::npos) << e;
}

std::string characterScene(const std::string& character) {
  return "<scene name=\"c\"><ground/><ragdoll name=\"r\" pos=\"0 0.85 0\" model=\"rigid\"/>\n" + character +
         "\n</scene>";
}

TEST(ClipFile, SceneCharactersLoadAndTheirErrorsNameTheAttribute) {
  const scenes::Scene ok = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + kClips +
                     "run.bvh\" strength=\"0.8\" root-strength=\"1\" "
                     "time=\"0.1\" speed=\"2\" loop=\"false\" root-offset=\"0 0.29 0\"/>"),
      "c.xml");
  ASSERT_EQ(ok.world.characters().size(), 1u);
  const phys::Character& c = ok.world.characters()[0];
  EXPECT_EQ(c.strength, 0.8);
  EXPECT_EQ(c.rootStrength, 1.0);
  EXPECT_EQ(c.now.time, 0.1);
  EXPECT_EQ(c.now.speed, 2.0);
  EXPECT_FALSE(c.now.loop);
  // Put down by hand, a character lies limp: its strengths now 0, whatever it gets up to.
  const scenes::Scene down = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + kClips +
                     "run.bvh\" strength=\"0.8\" root-strength=\"1\" balance=\"0.2\" state=\"down\"/>"),
      "c.xml");
  const phys::Character& limp = down.world.characters()[0];
  EXPECT_EQ(limp.state, phys::CharacterState::Down);
  EXPECT_EQ(limp.strength, 0.0);
  EXPECT_EQ(limp.rootStrength, 0.0);
  EXPECT_EQ(limp.balance, 0.0);
  EXPECT_EQ(limp.goalStrength, 0.8);
  EXPECT_EQ(c.rootOffset, phys::Vec3(0.0, 0.29, 0.0));
  EXPECT_EQ(testsupport::compareScenes(ok, scenes::loadSceneText(scenes::writeSceneXml(ok), "again.xml")),
            "");
  auto error = [](const std::string& character) {
    try {
      scenes::loadSceneText(characterScene(character), "c.xml");
    } catch (const scenes::LoadError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  const std::string missing = error("<character ragdoll=\"r\" clip=\"/nonexistent/run.bvh\"/>");
  EXPECT_NE(missing.find("c.xml:2: <character> attribute 'clip'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("No such file or directory"), std::string::npos) << missing;
  const std::string nobody = error("<character ragdoll=\"q\" clip=\"" + kClips + "run.bvh\"/>");
  EXPECT_NE(nobody.find("attribute 'ragdoll'"), std::string::npos) << nobody;
  const std::string strong =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" strength=\"2\"/>");
  EXPECT_NE(strong.find("attribute 'strength'"), std::string::npos) << strong;
  const std::string far =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" root-offset=\"2e6 0 0\"/>");
  EXPECT_NE(far.find("attribute 'root-offset': must be within"), std::string::npos) << far;
  const std::string backwards =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" speed=\"-1\"/>");
  EXPECT_NE(backwards.find("attribute 'speed'"), std::string::npos) << backwards;
  const std::string share =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" part-strengths=\"head=0.5 tail=1\"/>");
  EXPECT_NE(share.find("attribute 'part-strengths': clip"), std::string::npos) << share;
  EXPECT_NE(share.find("has no bone 'tail'"), std::string::npos) << share;
  const std::string root =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" part-strengths=\"torso=0.5\"/>");
  EXPECT_NE(root.find("attribute 'part-strengths': 'torso' is the clip's root"), std::string::npos) << root;
  const std::string junk =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" part-strengths=\"head:0.5\"/>");
  EXPECT_NE(junk.find("'head:0.5' is not BONE=SHARE"), std::string::npos) << junk;
  const std::string big =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" part-strengths=\"head=2\"/>");
  EXPECT_NE(big.find("'head=2': the share must be from 0 to 1"), std::string::npos) << big;
  // Where a saved character was: each value checked where it is read.
  const std::string asleep =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" state=\"asleep\"/>");
  EXPECT_NE(asleep.find("attribute 'state': 'asleep' must be active, falling, down"), std::string::npos)
      << asleep;
  const std::string early =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" state=\"down\" state-time=\"-1\"/>");
  EXPECT_NE(early.find("attribute 'state-time'"), std::string::npos) << early;
  for (const std::string now : {"strength-now", "root-strength-now", "balance-now"}) {
    const std::string held =
        error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" state=\"down\" " + now + "=\"0.5\"/>");
    EXPECT_NE(held.find("attribute '" + now + "': a character down is limp"), std::string::npos) << held;
  }
  const std::string overStrong =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" strength-now=\"1.5\"/>");
  EXPECT_NE(overStrong.find("attribute 'strength-now'"), std::string::npos) << overStrong;
  const std::string nowhere =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" origin=\"1 nan 0\"/>");
  EXPECT_NE(nowhere.find("attribute 'origin'"), std::string::npos) << nowhere;
  const std::string halfFade =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" blend=\"0.5\"/>");
  EXPECT_NE(halfFade.find("attribute 'blend': a fade under way needs what it fades from"), std::string::npos)
      << halfFade;
  const std::string fewTurns = error("<character ragdoll=\"r\" clip=\"" + kClips +
                                     "run.bvh\" blend=\"0.5\" held-turns=\"1 0 0 0, 1 0 0 0\"/>");
  EXPECT_NE(fewTurns.find("attribute 'held-turns': 2 turns for the clip's 10 bones"), std::string::npos)
      << fewTurns;
  const std::string notUnit =
      error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" blend=\"0.5\" held-turns=\"2 0 0 0\"/>");
  EXPECT_NE(notUnit.find("attribute 'held-turns': '2 0 0 0' is not a unit quaternion"), std::string::npos)
      << notUnit;
  // A get-up or then clip of other bones is blamed on its own attribute, not on the ragdoll.
  const testing_app::TempFolder dir;
  std::ofstream(dir.path / "one.bvh") << "HIERARCHY\nROOT a\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition "
                                         "Yposition Zposition Zrotation Xrotation Yrotation\n}\nMOTION\n"
                                         "Frames: 2\nFrame Time: 0.1\n0 0 0 0 0 0\n0 0 0 0 0 0\n";
  const std::string one = (dir.path / "one.bvh").string();
  for (const char* attribute : {"get-up", "then"}) {
    const std::string other =
        error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" " + attribute + "=\"" + one + "\"/>");
    EXPECT_NE(other.find(std::string("attribute '") + attribute + "': clip"), std::string::npos) << other;
    EXPECT_NE(other.find("has other bones than"), std::string::npos) << other;
    EXPECT_NE(other.find("it lacks 'torso', 'head'"), std::string::npos) << other;
  }
  const std::string pose = error("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" pose=\"stand\"/>");
  EXPECT_NE(pose.find("attribute 'pose': 'stand' must be clip or ragdoll"), std::string::npos) << pose;
  // pose="clip" puts the ragdoll in the clip's first pose: the parts on their targets from the start.
  const scenes::Scene posed = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" pose=\"clip\"/>"), "c.xml");
  EXPECT_LT(phys::trackingError(posed.world, 0), 1e-6);  // acos near 1: 1e-16 of round-off reads 1.5e-8 rad
  EXPECT_GT(phys::trackingError(ok.world, 0), 0.1);      // as made: 30 degrees and more from the run's pose
  // A capsule ragdoll's parts are not the box ragdoll's bones: each side's are named.
  const std::string capsule = error(
      "<ragdoll name=\"k\" shape=\"capsule\" pos=\"3 0.92 0\" model=\"rigid\"/><character ragdoll=\"k\" "
      "clip=\"" +
      kClips + "run.bvh\"/>");
  EXPECT_NE(capsule.find("no part for the bones 'torso'"), std::string::npos) << capsule;
  EXPECT_NE(capsule.find("no bone for the parts 'pelvis'"), std::string::npos) << capsule;
}

// A <character> playing the run cycle with `given` after its clip (line 2), refused naming `attribute`.
void expectCharacterRefused(const std::string& given, const char* attribute, const char* says) {
  const std::string xml =
      characterScene("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" " + given + "/>");
  testing_scenes::expectRefused({given.c_str(), xml.c_str(), 2, attribute, says});
}

// A clip's speed is held so that its clock stays where a file can hold it: speed="1e9" loaded and, two
// seconds on, Save As wrote time="2e+09", which the loader refuses. What the physics lets past the
// loader's limit at run time, Save As refuses by name rather than write a file that would not load.
TEST(ClipFile, ClipSpeedsAreHeldSoThatTheClockSavesAndLoads) {
  const std::string clip = kClips + "run.bvh";
  expectCharacterRefused("speed=\"1e9\"", "speed", "'1e+09' must be from 0 to 1000");
  expectCharacterRefused("speed=\"-1\"", "speed", "'-1' must be from 0 to 1000");
  expectCharacterRefused("blend=\"0.5\" from-clip=\"" + clip + "\" from-speed=\"1001\"", "from-speed",
                         "'1001' must be from 0 to 1000");
  // The fastest a file may give: two seconds on, the clock is where a file holds it.
  scenes::Scene fastest = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + clip + "\" speed=\"1000\"/>"), "c.xml");
  for (int i = 0; i < 120; ++i) fastest.world.step();
  EXPECT_NO_THROW(scenes::loadSceneText(scenes::writeSceneXml(fastest), "again.xml"));
  auto refusal = [](const scenes::Scene& scene) {
    try {
      scenes::writeSceneXml(scene);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("saved");
  };
  phys::Playback playback = fastest.world.characters()[0].now;
  playback.speed = 1e9;
  fastest.world.playClip(0, playback, 0.0);
  const std::string fast = refusal(fastest);
  EXPECT_NE(
      fast.find("the clip of character 'r' plays at a speed of 1e+09, over the 1000 a scene file holds"),
      std::string::npos)
      << fast;
  playback.speed = 1.0;
  fastest.world.playClip(0, playback, 0.5);  // fading from the fast one
  const std::string from = refusal(fastest);
  EXPECT_NE(from.find("the clip character 'r' fades from plays at a speed of 1e+09"), std::string::npos)
      << from;
  // A clock run on past 1e9 s (at the fastest, after 11 days).
  playback.speed = 1000.0;
  playback.time = phys::kMaxClipTime - 1.0;
  fastest.world.playClip(0, playback, 0.0);
  fastest.world.step();
  const std::string late = refusal(fastest);
  EXPECT_NE(late.find("the clip of character 'r' is at 1000000015."), std::string::npos) << late;
  EXPECT_NE(late.find("s, beyond the +-1e+09 s a scene file holds"), std::string::npos) << late;
}

// A character's scale is a ragdoll's, 0.02 to 1000: 5e-324 loaded and could not be saved (its root
// drive's stiffness, which goes as 1 / scale, was inf), and 1e308 froze the world.
// then-at, then-blend and then-loop say when and how to change to `then`, and from-time, from-speed
// and from-loop how the clip faded from plays: given without it, they were refused as unknown
// attributes, which the format documents.
TEST(ClipFile, AttributesOfAnotherAreRefusedAsGoingWithIt) {
  expectCharacterRefused("then-at=\"1\"", "then-at", "goes with then, which is not given");
  expectCharacterRefused("then-loop=\"true\"", "then-loop", "goes with then");
  expectCharacterRefused("blend=\"0.5\" from-time=\"0.2\"", "from-time",
                         "goes with from-clip, which is not given");
  expectCharacterRefused("from-speed=\"2\"", "from-speed", "goes with from-clip");
}

TEST(ClipFile, ACharactersScaleIsHeldToARagdolls) {
  expectCharacterRefused("scale=\"5e-324\"", "scale", "must be from 0.02 to 1000");
  expectCharacterRefused("scale=\"1e308\"", "scale", "'1e+308' must be from 0.02 to 1000");
  for (const char* scale : {"0.02", "1000"}) {
    SCOPED_TRACE(scale);
    scenes::Scene scene =
        scenes::loadSceneText(characterScene("<character ragdoll=\"r\" clip=\"" + kClips +
                                             "run.bvh\" root-strength=\"1\" scale=\"" + scale + "\"/>"),
                              "c.xml");
    scene.world.step();
    EXPECT_EQ(
        testsupport::compareScenes(scene, scenes::loadSceneText(scenes::writeSceneXml(scene), "again.xml")),
        "");
  }
}

// Ragdoll "a"'s parts are the bodies "a.<bone>": "a.b.torso", ragdoll "a.b"'s torso, was taken for a part
// "b.torso" of "a" that no bone of the clip has, so "a" could have no character while "a.b" stood
// beside it, in either order. Each character binds its own ragdoll's parts, and a part that fits no
// bone is still named.
TEST(ClipFile, ARagdollWhoseNameHasADotLeavesAnothersCharacterBe) {
  for (const bool dottedFirst : {false, true}) {
    SCOPED_TRACE(dottedFirst ? "a.b first" : "a first");
    const std::string plain = "<ragdoll name=\"a\" pos=\"0 0.85 0\" model=\"rigid\"/>\n";
    const std::string dotted = "<ragdoll name=\"a.b\" pos=\"2 0.85 0\" model=\"rigid\"/>\n";
    const std::string text = "<scene name=\"c\"><ground/>" + (dottedFirst ? dotted + plain : plain + dotted) +
                             "<character ragdoll=\"a\" clip=\"" + kClips + "stand.bvh\"/>\n" +
                             "<character ragdoll=\"a.b\" clip=\"" + kClips + "stand.bvh\"/>\n</scene>";
    const scenes::Scene scene = scenes::loadSceneText(text, "dots.xml");
    ASSERT_EQ(scene.world.characters().size(), 2u);
    for (const phys::Character& c : scene.world.characters()) {
      ASSERT_EQ(c.bones.size(), 10u) << c.ragdoll;
      for (const phys::CharacterBone& bone : c.bones) {
        const std::string& name = scene.world.bodies()[bone.body].name;
        EXPECT_EQ(name, c.ragdoll + "." + c.now.clip->bones[static_cast<std::size_t>(bone.clipBone)]);
      }
    }
  }
  // A body "r.tail.tip" beside ragdoll "r" is another's ("r.tail"'s), not a part of "r" with no bone
  // in the clip: "r" takes its character. A dotless part with no bone is still named.
  const scenes::Scene tailed = scenes::loadSceneText(
      characterScene(
          "<box name=\"r.tail.tip\" pos=\"0 3 0\" size=\"0.1\"/>\n<character ragdoll=\"r\" clip=\"" + kClips +
          "stand.bvh\"/>"),
      "tail.xml");
  EXPECT_EQ(tailed.world.characters()[0].bones.size(), 10u);
  try {
    scenes::loadSceneText(characterScene("<box name=\"r.tail\" pos=\"0 3 0\" size=\"0.1\"/>\n<character "
                                         "ragdoll=\"r\" clip=\"" +
                                         kClips + "stand.bvh\"/>"),
                          "odd.xml");
    ADD_FAILURE() << "loaded";
  } catch (const scenes::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("the clip has no bone for the parts 'tail'"), std::string::npos)
        << e.what();
  }
}

// A bone named twice in part-strengths took the last share without a word.
TEST(ClipFile, PartStrengthsNameEachBoneOnce) {
  expectCharacterRefused("part-strengths=\"head=0.5 lower-arm-left=0.1 head=0.2\"", "part-strengths",
                         "bone 'head' is given twice");
}

TEST(ClipFile, SaveAsKeepsTheCharacter) {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/animated.xml");
  for (int i = 0; i < 30; ++i) scene.world.step();
  scene.world.setPartStrength(1, "head", 1.0 / 3.0);  // a share that needs every digit to read back
  const scenes::Scene again = scenes::loadSceneText(scenes::writeSceneXml(scene), "again.xml");
  ASSERT_EQ(again.world.characters().size(), scene.world.characters().size());
  for (std::size_t k = 0; k < scene.world.characters().size(); ++k) {
    const phys::Character& a = scene.world.characters()[k];
    const phys::Character& b = again.world.characters()[k];
    EXPECT_EQ(a.ragdoll, b.ragdoll);
    EXPECT_EQ(a.now.clip->name, b.now.clip->name);
    EXPECT_DOUBLE_EQ(a.now.time, b.now.time);
    EXPECT_EQ(a.now.loop, b.now.loop);
    EXPECT_EQ(a.strength, b.strength);
    EXPECT_EQ(a.rootStrength, b.rootStrength);
    EXPECT_EQ(a.partStrength, b.partStrength);
  }
  EXPECT_EQ(again.world.characters()[1].partStrength[1], 1.0 / 3.0);
  EXPECT_EQ(testsupport::compareScenes(scene, again), "");
}

// A balancing character turns its root with a drive whose centre stiffness it sets to 0 each substep;
// the reload takes the root's stiffness from the saved drive, so Save As once gave 0 and the hand of
// god (root strength) no longer held the centre up: the line-up's players then sank from 1.17 m to
// 0.70 m in 1.5 s where the saved ones stood. Saved after a step, the reloaded character keeps the
// stiffnesses it was given, and held by its root it stays where the saved one does.
TEST(ClipFile, SaveAsKeepsABalancingCharactersRootStiffness) {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/line-up.xml");
  const phys::World& world = scene.world;
  ASSERT_GT(world.characters()[0].balance, 0.0);
  for (int i = 0; i < 10; ++i) scene.world.step();
  ASSERT_EQ(world.bodyDrive(world.characters()[0].bones[0].body)->stiffness, 0.0);  // balancing now
  scenes::Scene again = scenes::loadSceneText(scenes::writeSceneXml(scene), "again.xml");
  EXPECT_EQ(testsupport::compareScenes(scene, again), "");
  for (std::size_t k = 0; k < world.characters().size(); ++k) {
    EXPECT_GT(again.world.characters()[k].rootStiffness, 0.0) << "character " << k;
    for (scenes::Scene* s : {&scene, &again}) s->world.setCharacterStrength(k, 0.0, 1.0);  // limp, held
  }
  for (int i = 0; i < 90; ++i) {
    scene.world.step();
    again.world.step();
  }
  for (std::size_t k = 0; k < world.characters().size(); ++k) {
    const phys::BodyId root = world.characters()[k].bones[0].body;
    EXPECT_NEAR(again.world.bodyPose(root).center.y, world.bodyPose(root).center.y, 1e-3)
        << "character " << k;
  }
}

// The balance acts in a step only if the last one found the character standing on its support
// (Character::supported), which Save As left out: the reloaded players' first step had no balance,
// and the line-up saved standing at 10 steps was 3.6e-7 m off the saved run's after one step, where
// the contacts' history alone (warm starts and anchors, which no file holds) leaves 3.4e-10 m. Kept,
// the reloaded players balance in their first step as the saved ones do.
TEST(ClipFile, SaveAsKeepsWhetherACharacterStandsOnItsSupport) {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/line-up.xml");
  for (int i = 0; i < 10; ++i) scene.world.step();
  const std::string text = scenes::writeSceneXml(scene);
  EXPECT_NE(text.find("supported=\"true\""), std::string::npos);
  scenes::Scene again = scenes::loadSceneText(text, "again.xml");
  const phys::World& saved = scene.world;
  for (std::size_t k = 0; k < saved.characters().size(); ++k) {
    ASSERT_TRUE(saved.characters()[k].supported) << "character " << k;  // standing
    EXPECT_TRUE(again.world.characters()[k].supported) << "character " << k;
  }
  scene.world.step();
  again.world.step();
  double gap = 0.0;
  for (std::size_t i = 0; i < saved.bodies().size(); ++i) {
    const phys::BodyId id(static_cast<std::uint32_t>(i));
    gap = std::max(gap, glm::length(again.world.bodyPose(id).center - saved.bodyPose(id).center));
  }
  std::printf("line-up saved at 10 steps, one step on: the reload %.3g m from the saved run\n", gap);
  EXPECT_LT(gap, 1e-8);
}

// Saved during a fade, from the clip before or from a pose held (a change of clip during a fade), a
// character reloads with the fade where it had got to: the target poses of the saved and the
// reloaded world agree to the bit for the rest of the fade (saved as the new clip alone, the target
// jumped to it).
// The root's stiffnesses are the character's own (root-stiffness, root-angular-stiffness): Save As
// wrote them only through the root's <body-drive>, which a character with no root strength and no
// balance does not hold, so 500 N/m and 200 N m/rad came back as the defaults, 10000 and 1000, and
// the reload's hand of god, once given a strength, held the root elsewhere.
TEST(ClipFile, SaveAsKeepsTheRootsStiffnessWithNoRootDrive) {
  scenes::Scene scene = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + kClips +
                     "stand.bvh\" root-stiffness=\"500\" root-angular-stiffness=\"200\"/>"),
      "k.xml");
  const phys::World& world = scene.world;
  ASSERT_EQ(world.characters()[0].rootStiffness, 500.0);
  ASSERT_EQ(world.characters()[0].rootAngularStiffness, 200.0);
  for (int i = 0; i < 10; ++i) scene.world.step();
  ASSERT_FALSE(world.bodyDrive(world.characters()[0].bones[0].body).has_value());  // none held now
  scenes::Scene again = scenes::loadSceneText(scenes::writeSceneXml(scene), "again.xml");
  EXPECT_EQ(again.world.characters()[0].rootStiffness, 500.0);
  EXPECT_EQ(again.world.characters()[0].rootAngularStiffness, 200.0);
  EXPECT_EQ(testsupport::compareScenes(scene, again), "");
  for (scenes::Scene* s : {&scene, &again}) s->world.setCharacterStrength(0, 1.0, 0.5);
  for (int i = 0; i < 120; ++i) {
    scene.world.step();
    again.world.step();
  }
  const phys::BodyId root = world.characters()[0].bones[0].body;
  EXPECT_LT(glm::length(again.world.bodyPose(root).center - world.bodyPose(root).center), 1e-3);
}

// The character drives its root every substep, so a drive the root had from the file was replaced at
// the first (dropped, at root strength 0): a <body-drive> on a character's root, before or after it,
// and a ragdoll's own root-strength are refused, saying where to give the root's drive instead.
TEST(ClipFile, ADriveOnACharactersRootIsRefused) {
  const std::string ragdoll =
      "<scene name=\"c\"><ground/><ragdoll name=\"r\" pos=\"0 0.85 0\" model=\"rigid\"";
  const std::string character = "<character ragdoll=\"r\" clip=\"" + kClips + "stand.bvh\"/>";
  const std::string drive = "<body-drive body=\"r.torso\" strength=\"1\"/>";
  const std::string before = ragdoll + "/>\n" + drive + "\n" + character + "\n</scene>";
  testing_scenes::expectRefused({"a body drive before", before.c_str(), 3, "ragdoll",
                                 "its root part 'r.torso' has the <body-drive> on line 2, which the "
                                 "character would replace"});
  const std::string after = ragdoll + "/>\n" + character + "\n" + drive + "\n</scene>";
  testing_scenes::expectRefused({"a body drive after", after.c_str(), 3, "body",
                                 "'r.torso' is the root of the <character> on line 2, which drives it"});
  const std::string held = ragdoll + " root-strength=\"0.5\"/>\n" + character + "\n</scene>";
  testing_scenes::expectRefused({"a ragdoll's root strength", held.c_str(), 2, "ragdoll",
                                 "ragdoll 'r' holds its root part 'r.torso' by its root-strength"});
  expectCharacterRefused("root-stiffness=\"-1\"", "root-stiffness", "'-1' must be >= 0 (N/m)");
  expectCharacterRefused("root-angular-stiffness=\"0\"", "root-angular-stiffness",
                         "'0' must be > 0 (N m/rad)");
}

TEST(ClipFile, SaveAsKeepsAFadeUnderWay) {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/run-cycle.xml");
  const std::shared_ptr<const phys::Clip> stand =
      std::make_shared<const phys::Clip>(clips::loadClip(kClips + "stand.bvh"));
  for (int i = 0; i < 20; ++i) scene.world.step();
  scene.world.playClip(0, phys::Playback{stand, 0.0, 1.0, true}, 0.5);
  for (const bool holding : {false, true}) {
    SCOPED_TRACE(holding ? "from a pose held" : "from the clip before");
    if (holding) scene.world.playClip(0, scene.world.characters()[0].before, 0.4);  // back, mid-fade
    for (int i = 0; i < 8; ++i) scene.world.step();
    ASSERT_LT(scene.world.characters()[0].blend, 1.0);
    ASSERT_EQ(scene.world.characters()[0].holding, holding);
    scenes::Scene again = scenes::loadSceneText(scenes::writeSceneXml(scene), "again.xml");
    EXPECT_EQ(testsupport::compareScenes(scene, again), "");
    phys::World saved = scene.world;  // the scene goes on unstepped into the next case
    for (int i = 0; i < 40; ++i) {
      saved.step();
      again.world.step();
      const phys::ClipPose &a = saved.characters()[0].pose, &b = again.world.characters()[0].pose;
      ASSERT_EQ(a.root, b.root) << "step " << i;
      ASSERT_EQ(a.turns, b.turns) << "step " << i;
    }
  }
}

// A clip file's name is bytes, and may be no UTF-8 (a Latin-1 name): Save As once wrote it as it was,
// and the file it wrote did not load. It refuses, naming the attribute and the bytes, and the file
// saved before stays as it was.
TEST(ClipFile, SaveAsRefusesAClipNameThatIsNotUtf8) {
  const testing_app::TempFolder dir;
  const std::filesystem::path latin1 = dir.path / "r\xFFn.bvh";
  std::filesystem::copy_file(kClips + "stand.bvh", latin1);
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/run-cycle.xml");
  const std::filesystem::path file = dir.path / "saved.xml";
  scenes::saveSceneFile(scene, file);
  auto content = [&file] {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string before = content();
  scene.world.playClip(
      0, phys::Playback{std::make_shared<const phys::Clip>(clips::loadClip(latin1.string())), 0.0, 1.0, true},
      0.0);
  try {
    scenes::saveSceneFile(scene, file);
    ADD_FAILURE() << "saved a clip name that is not UTF-8";
  } catch (const std::exception& e) {
    const std::string why = e.what();
    EXPECT_NE(why.find("saved.xml: cannot save this world as a scene: <character> attribute 'clip' holds "
                       "0xFF, which is not UTF-8"),
              std::string::npos)
        << why;
  }
  EXPECT_EQ(content(), before);
  EXPECT_EQ(
      std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator()), 2);
}

// Save As names each clip file relative to the saved file's folder, as the project's scenes do, so a
// scene saved beside its clips can move with them; the text for a recording, which has no folder,
// names them by absolute path. Either way the reload plays the same files.
TEST(ClipFile, SaveAsNamesClipsRelativeToTheFile) {
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/tackle.xml");
  for (int i = 0; i < 30; ++i) scene.world.step();
  const testing_app::TempFolder dir;
  std::filesystem::copy(kClips, dir.path / "clips");
  std::filesystem::create_directories(dir.path / "scenes");
  // The scene's clips as if loaded from the copy beside the file (the names are the files' paths).
  scenes::Scene moved = scenes::loadSceneText(scenes::writeSceneXml(scene), "moved.xml");
  const std::string copied = (dir.path / "clips").lexically_normal().string() + "/";
  std::string text = scenes::writeSceneXml(moved);
  for (std::size_t at = 0; (at = text.find(kClips, at)) != std::string::npos; at += copied.size())
    text.replace(at, kClips.size(), copied);
  EXPECT_EQ(text.find(kClips), std::string::npos);
  moved = scenes::loadSceneText(text, "moved.xml");
  const std::filesystem::path file = dir.path / "scenes" / "saved.xml";
  scenes::saveSceneFile(moved, file);
  std::ifstream in(file);
  const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(saved.find("clip=\"../clips/run.bvh\""), std::string::npos) << saved;
  EXPECT_NE(saved.find("then=\"../clips/dive.bvh\""), std::string::npos) << saved;
  EXPECT_EQ(saved.find(dir.path.string()), std::string::npos) << saved;
  // The folder moves with its clips, and the file still plays them.
  const std::filesystem::path elsewhere = dir.path.string() + "-moved";
  std::filesystem::rename(dir.path, elsewhere);
  const scenes::Scene again = scenes::loadSceneFile(elsewhere / "scenes" / "saved.xml");
  std::filesystem::rename(elsewhere, dir.path);
  ASSERT_EQ(again.world.characters().size(), 2u);
  EXPECT_EQ(again.world.characters()[0].now.clip->name, (elsewhere / "clips" / "run.bvh").string());
  ASSERT_TRUE(again.world.characters()[1].queued.has_value());
  EXPECT_EQ(again.world.characters()[1].queued->playback.clip->name,
            (elsewhere / "clips" / "dive.bvh").string());
}

// A scene file's clip names start from the folder the file is in once links are followed, in the
// writer and the loader alike (the next test): saving through lk/link.xml -> ../real/scene.xml named a
// clip in lk/ "run.bvh", from the link's folder, in a file in real/ that then did not load.
TEST(ClipFile, SaveAsThroughALinkNamesClipsFromTheFolderTheFileLandsIn) {
  namespace fs = std::filesystem;
  const testing_app::TempFolder dir;
  const fs::path at = fs::canonical(dir.path);  // the temporary folder may itself be reached by a link
  fs::create_directory(dir.path / "lk");
  fs::create_directory(dir.path / "real");
  fs::copy_file(kClips + "run.bvh", dir.path / "lk" / "run.bvh");
  fs::create_symlink("../real/scene.xml", dir.path / "lk" / "link.xml");
  const scenes::Scene scene = scenes::loadSceneText(
      characterScene("<character ragdoll=\"r\" clip=\"" + (at / "lk" / "run.bvh").string() + "\"/>"),
      "c.xml");
  scenes::saveSceneFile(scene, dir.path / "lk" / "link.xml");
  ASSERT_TRUE(fs::is_symlink(dir.path / "lk" / "link.xml"));
  std::ifstream in(dir.path / "real" / "scene.xml");
  const std::string saved((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(saved.find("clip=\"../lk/run.bvh\""), std::string::npos) << saved;
  for (const char* file : {"real/scene.xml", "lk/link.xml"}) {
    SCOPED_TRACE(file);
    const scenes::Scene again = scenes::loadSceneFile(dir.path / file);
    ASSERT_EQ(again.world.characters().size(), 1u);
    EXPECT_EQ(again.world.characters()[0].now.clip->name, (at / "lk" / "run.bvh").string());
  }
}

// A file in real/ naming the clip beside it did not load through a link in lk/: the loader took the
// clip's name from the link's folder.
TEST(ClipFile, ALinkedSceneReadsClipsFromTheFolderItIsIn) {
  namespace fs = std::filesystem;
  const testing_app::TempFolder dir;
  fs::create_directory(dir.path / "lk");
  fs::create_directory(dir.path / "real");
  fs::copy_file(kClips + "run.bvh", dir.path / "real" / "own.bvh");
  std::ofstream(dir.path / "real" / "own.xml")
      << characterScene("<character ragdoll=\"r\" clip=\"own.bvh\"/>");
  fs::create_symlink("../real/own.xml", dir.path / "lk" / "link.xml");
  const scenes::Scene linked = scenes::loadSceneFile(dir.path / "lk" / "link.xml");
  ASSERT_EQ(linked.world.characters().size(), 1u);
  EXPECT_EQ(linked.world.characters()[0].now.clip->name,
            (fs::canonical(dir.path) / "real" / "own.bvh").string());
}

// A scene read once (scenes::SceneSource, the lab's every point) keeps every clip its character names
// (clip, then, get-up, from-clip): with the files gone, each world built from it plays the clips as
// read, the same clip objects, not a parse of each a world. A clip that could not be read is refused
// at each load as the file was, even once it can be.
TEST(ClipFile, ASceneReadOnceKeepsEveryClipItNames) {
  namespace fs = std::filesystem;
  const testing_app::TempFolder dir;
  const char* names[] = {"a.bvh", "b.bvh", "c.bvh", "d.bvh"};
  for (const char* name : names) fs::copy_file(kClips + "run.bvh", dir.path / name);
  std::ofstream(dir.path / "four.xml") << characterScene(
      "<character ragdoll=\"r\" clip=\"a.bvh\" then=\"b.bvh\" get-up=\"c.bvh\" blend=\"0.5\" "
      "from-clip=\"d.bvh\"/>");
  const scenes::Scene asFile = scenes::loadSceneFile(dir.path / "four.xml");
  const scenes::SceneSource source = scenes::readSceneSource(dir.path / "four.xml");
  ASSERT_EQ(source.clips.size(), 4u);
  for (const char* name : names) fs::remove(dir.path / name);
  const scenes::Scene first = scenes::loadSceneSource(source);
  EXPECT_EQ(testsupport::compareScenes(asFile, first), "");
  const scenes::Scene second = scenes::loadSceneSource(source);
  std::vector<const phys::Clip*> played[2];
  for (int i = 0; i < 2; ++i) {
    const scenes::Scene& scene = i == 0 ? first : second;
    ASSERT_EQ(scene.world.characters().size(), 1u);
    forEachPlayback(scene.world.characters()[0],
                    [&](const phys::Playback& p) { played[i].push_back(p.clip.get()); });
  }
  ASSERT_EQ(played[0].size(), 4u);  // a queued clip (then) among them
  EXPECT_EQ(played[0], played[1]);
  for (const phys::Clip* clip : played[0]) EXPECT_NE(clip, nullptr);

  std::ofstream(dir.path / "none.xml") << characterScene("<character ragdoll=\"r\" clip=\"e.bvh\"/>");
  auto error = [](const auto& load) {
    try {
      load();
    } catch (const scenes::LoadError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  const std::string missing = error([&] { scenes::loadSceneFile(dir.path / "none.xml"); });
  EXPECT_NE(missing.find("attribute 'clip'"), std::string::npos) << missing;
  const scenes::SceneSource withoutClip = scenes::readSceneSource(dir.path / "none.xml");
  fs::copy_file(kClips + "run.bvh", dir.path / "e.bvh");
  EXPECT_EQ(error([&] { scenes::loadSceneSource(withoutClip); }), missing);
}

// A scene whose text shows an error alone (one found before any body is built: an unknown
// element, a bad <world>, XML that is not well-formed) says it before any clip it names is read,
// which may be large or slow: reading the source throws the scene's own error, whatever the clip
// is (missing, a pipe with no writer), as loading the file does.
TEST(ClipFile, ASceneWithAnErrorOfItsOwnSaysItBeforeReadingAClip) {
  const testing_app::TempFolder dir;
  ASSERT_EQ(::mkfifo((dir.path / "pipe.bvh").c_str(), 0600), 0);
  const std::filesystem::path file = dir.path / "bad.xml";
  for (const std::string clip : {"pipe.bvh", "missing.bvh"}) {
    const std::string character = "<character ragdoll=\"r\" clip=\"" + clip + "\"/>\n";
    const std::pair<std::string, std::string> cases[] = {
        {character + "<bogus/>", "unknown element"},
        {character + "<world damping=\"-1\"/>", "attribute 'damping': must be >= 0"},
        {character + "<box pos='0 1 0' name='R&D'/>", "an '&' that starts no reference"},
    };
    for (const auto& [bad, says] : cases) {
      std::ofstream(file) << characterScene(bad);
      for (const bool source : {true, false}) {
        try {
          if (source)
            scenes::readSceneSource(file);
          else
            scenes::loadSceneFile(file);
          ADD_FAILURE() << (source ? "read: " : "loaded: ") << bad;
        } catch (const scenes::LoadError& e) {
          const std::string message = e.what();
          EXPECT_EQ(message.rfind(file.string() + ":3: ", 0), 0u) << message;
          EXPECT_NE(message.find(says), std::string::npos) << message;
        }
      }
    }
  }
}

// The target: with the root carried, the parts track the run cycle within 5 degrees RMS at
// 1/60 s (XPBD 2 x 8, strength 0.9, the ragdolls' default stiffness) (the parts against their targets, in the
// clip frame the character chose). `ragdoll` is the <ragdoll> element's attributes past its name.
void expectTheRunTracked(const std::string& ragdoll, const std::string& clipFile) {
  scenes::Scene scene = scenes::loadSceneText(
      "<scene name=\"c\"><ground/><ragdoll name=\"r\" " + ragdoll +
          " model=\"rigid\"/><solver method=\"xpbd\" iterations=\"2\" substeps=\"8\"/><character "
          "ragdoll=\"r\" clip=\"" +
          clipFile + "\" strength=\"0.9\" root-strength=\"1\"/></scene>",
      "run.xml");
  const phys::BodyId root = scene.world.characters()[0].bones[0].body;
  const phys::Clip& clip = *scene.world.characters()[0].now.clip;
  // Where the clip puts the root part: its root path, the clip's floor on the ground, in the clip's
  // frame turned only about the up axis (the clip's first pose leans; the path must not).
  const glm::dvec3 start = scene.world.bodyPose(root).center;
  double sum = 0.0, heightOff = 0.0;
  int n = 0;
  for (int i = 0; i < 600; ++i) {
    scene.world.step();
    if (i < 60) continue;  // the first second: from standing into the run
    const double e = phys::trackingError(scene.world, 0);
    sum += e * e;
    phys::ClipPose pose;
    phys::sampleClip(clip, scene.world.characters()[0].now.time, true, pose);
    const double clipHeight = pose.root.y;
    heightOff = std::max(heightOff, std::abs(scene.world.bodyPose(root).center.y - clipHeight));
    ++n;
  }
  const double rms = std::sqrt(sum / n) / kDeg;
  const glm::dvec3 end = scene.world.bodyPose(root).center;
  std::printf(
      "run cycle, root carried: RMS tracking error %.2f degrees over 9 s; root part off the clip's height by "
      "%.3f m at most; %.2f m run\n",
      rms, heightOff, glm::length(end - start));
  EXPECT_LT(rms, 5.0);
  EXPECT_LT(heightOff, 0.02);  // the hand of god's lag, not a climb
  EXPECT_NEAR(glm::length(glm::dvec2(end.x, end.z) - glm::dvec2(start.x, start.z)), 3.0 * 10.0,
              0.1);  // 3 m/s (scripts/make-clips)
  EXPECT_TRUE(scene.world.freezes().empty());
}

TEST(ClipFile, TheRunCycleIsTrackedWithinFiveDegrees) {
  expectTheRunTracked("pos=\"0 0.85 0\"", kClips + "run.bvh");
}

TEST(ClipFile, TheCapsuleRunCycleIsTrackedWithinFiveDegrees) {
  expectTheRunTracked("shape=\"capsule\" pos=\"0 0.95 0\"", kClips + "capsule/run.bvh");
}

// The seed ragdoll as a character on the run cycle at strength 1, turned from the pose it was made in
// (not pose="clip"), root carried, XPBD 2 x 8 (docs/physics.md, "Turn-in"): a drive of compliance 0
// turns a part by its whole gap in a pass, the joints' pins drag the box's corners, and the drive,
// stiffer than the sticks, keeps the fold: without the turn-in its sticks stayed 13% out from 5 s on
// (max_constraint_error 0.129). With it each pass closes a quarter of the gap for the first 0.1 s,
// and at 5 s the sticks are within a few percent, the fold gone.
TEST(ClipFile, TheSeedRagdollTurnsInFromAFarPoseWithoutFolding) {
  auto sticksAt5s = [](const std::string& turnIn) {
    scenes::Scene scene = scenes::loadSceneText(
        "<scene name=\"c\"><ground/><solver method=\"xpbd\" iterations=\"2\" substeps=\"8\"/>"
        "<ragdoll name=\"r\" pos=\"0 0.85 0\" euler=\"0 180 0\" model=\"seed\"/><character ragdoll=\"r\" "
        "clip=\"" +
            kClips + "run.bvh\" strength=\"1\" root-strength=\"1\" turn-in=\"" + turnIn + "\"/></scene>",
        "seed.xml");
    EXPECT_TRUE(scene.world.characters()[0].particleParts);
    for (int i = 0; i < 300; ++i) scene.world.step();
    EXPECT_TRUE(scene.world.freezes().empty()) << turnIn;
    return scene.world.metrics().maxConstraintError;
  };
  const double without = sticksAt5s("0"), with = sticksAt5s("0.1");
  std::printf(
      "seed ragdoll on the run cycle at strength 1 from its made pose, sticks at 5 s: %.4f without "
      "the turn-in, %.4f with it\n",
      without, with);
  EXPECT_GT(without, 0.1);  // folded: what the turn-in is for
  EXPECT_LT(with, 0.03);
}

// A turn-in under way, and whether one is still due, are saved: a character saved in the middle of
// its turn-in reloads with what is left of it, and one that has stepped past it reloads with none due
// (looked for again, a character lying far from its pose would turn in where the saved run did not).
TEST(ClipFile, SaveAsKeepsTheTurnIn) {
  scenes::Scene scene = scenes::loadSceneText(
      "<scene name=\"c\"><ground/><solver method=\"xpbd\" iterations=\"2\" substeps=\"8\"/>"
      "<ragdoll name=\"r\" pos=\"0 0.85 0\" model=\"lean\"/><character ragdoll=\"r\" clip=\"" +
          kClips + "run.bvh\" strength=\"1\" root-strength=\"1\" turn-in=\"0.25\"/></scene>",
      "lean.xml");
  EXPECT_TRUE(scene.world.characters()[0].turnInDue);
  for (int i = 0; i < 6; ++i) scene.world.step();  // 0.1 s: the turn-in, found far, has 0.15 s left
  const phys::Character& saved = scene.world.characters()[0];
  EXPECT_FALSE(saved.turnInDue);
  EXPECT_NEAR(saved.turnIn, 0.15, 1e-9);
  const std::string text = scenes::writeSceneXml(scene);
  EXPECT_NE(text.find("turn-in=\"0.25\""), std::string::npos) << text;
  scenes::Scene again = scenes::loadSceneText(text, "again.xml");
  const phys::Character& reloaded = again.world.characters()[0];
  EXPECT_EQ(reloaded.turnInTime, 0.25);
  EXPECT_EQ(reloaded.turnIn, saved.turnIn);
  EXPECT_FALSE(reloaded.turnInDue);
  EXPECT_EQ(testsupport::compareScenes(scene, again), "");
  // More left than the turn-in lasts is refused, naming the line and the attribute.
  const std::string turnIn = "<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" turn-in=\"0.1\" ";
  for (const auto& [attributes, says] :
       {std::pair<std::string, std::string>{
            "turn-in-left=\"0.2\"", "attribute 'turn-in-left': '0.2' must be at most turn-in (0.1 s)"},
        {"turn-in-left=\"-1\"", "attribute 'turn-in-left': '-1' must be >= 0"},
        {"turn-in-due=\"maybe\"", "attribute 'turn-in-due'"}}) {
    std::string message = "loaded";
    try {
      scenes::loadSceneText(characterScene(turnIn + attributes + "/>"), "c.xml");
    } catch (const scenes::LoadError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find("c.xml:2: <character> " + says), std::string::npos) << message;
  }
  std::string negative = "loaded";
  try {
    scenes::loadSceneText(
        characterScene("<character ragdoll=\"r\" clip=\"" + kClips + "run.bvh\" turn-in=\"-0.1\"/>"),
        "c.xml");
  } catch (const scenes::LoadError& e) {
    negative = e.what();
  }
  EXPECT_NE(negative.find("attribute 'turn-in': '-0.1' must be >= 0 (s)"), std::string::npos) << negative;
}

// A ragdoll's drive stiffness grows with its mass (RagdollDesc::driveStiffness), and a character
// drives the joints at it: it was set only for a ragdoll of strength > 0, and characters' ragdolls
// have strength 0, so a 700 kg runner's joints held at a 70 kg ragdoll's stiffness tracked within
// 10.1 degrees RMS where 70 kg tracks within 1.26. Ten times the mass and ten times the stiffness
// is the same motion: the two track alike, within 1%.
TEST(ClipFile, AHeavyRagdollsCharacterTracksAsALightOnes) {
  auto tracking = [](const std::string& mass) {
    scenes::Scene scene = scenes::loadSceneText(
        "<scene name=\"c\"><ground/><solver method=\"xpbd\" iterations=\"2\" substeps=\"8\"/>"
        "<ragdoll name=\"p\" pos=\"0 0.85 0\" model=\"rigid\" mass=\"" +
            mass + "\" strength=\"0\"/><character ragdoll=\"p\" clip=\"" + kClips +
            "run.bvh\" strength=\"0.9\" root-strength=\"1\"/></scene>",
        "heavy.xml");
    double sum = 0.0;
    const int steps = 600;
    for (int i = 0; i < steps; ++i) {
      scene.world.step();
      const double e = phys::trackingError(scene.world, 0);
      sum += e * e;
    }
    EXPECT_TRUE(scene.world.freezes().empty()) << mass << " kg";
    return std::sqrt(sum / steps) / kDeg;
  };
  const double light = tracking("70"), heavy = tracking("700");
  std::printf("run cycle: RMS tracking error %.3f degrees at 70 kg, %.3f at 700 kg\n", light, heavy);
  EXPECT_NEAR(heavy / light, 1.0, 0.01);
}

// The capsule ragdoll's clips (scripts/make-clips): Bullet's eleven bones, the pelvis the root, and its
// arms, which rest in a T, turned down by a swing read back through BVH's three rotation channels in
// their order (Z, X, Y): in the stand clip each upper arm's core points 72 degrees from the T, out to
// its own side and down, which a wrong order of the channels would not give.
TEST(ClipFile, TheCapsuleClipsHangTheArmsFromTheT) {
  for (const char* name : {"stand.bvh", "run.bvh", "dive.bvh"}) {
    const phys::Clip clip = clips::loadClip(kClips + "capsule/" + name);
    ASSERT_EQ(phys::clipProblem(clip), "") << name;
    ASSERT_EQ(clip.bones.size(), 11u) << name;
    EXPECT_EQ(clip.bones[0], "pelvis") << name;
  }
  scenes::Scene scene = scenes::loadSceneText(
      "<scene name=\"c\"><ground/><ragdoll name=\"r\" shape=\"capsule\" pos=\"0 0.95 0\" "
      "model=\"rigid\"/><character ragdoll=\"r\" clip=\"" +
          kClips + "capsule/stand.bvh\" pose=\"clip\"/></scene>",
      "stand.xml");
  const phys::Character& c = scene.world.characters()[0];
  std::vector<phys::Quat> targets(c.bones.size());
  phys::targetOrientations(c, c.pose, targets);
  for (const auto& [bone, side] : {std::pair{"upper-arm-left", 1.0}, std::pair{"upper-arm-right", -1.0}}) {
    const int b = c.now.clip->bone(bone);
    ASSERT_GE(b, 0) << bone;
    // A capsule's core runs along its body's y axis.
    const glm::dvec3 core = targets[static_cast<std::size_t>(b)] * glm::dvec3(0.0, 1.0, 0.0);
    EXPECT_NEAR(std::acos(side * core.x) / kDeg, 72.0, 0.01) << bone;
    EXPECT_NEAR(core.y, -std::sin(72.0 * kDeg), 1e-4) << bone;
    EXPECT_NEAR(core.z, 0.0, 1e-4) << bone;
    // pose="clip" put the part there.
    const glm::dvec3 placed = scene.world.bodyPose(c.bones[static_cast<std::size_t>(b)].body).orientation *
                              glm::dvec3(0.0, 1.0, 0.0);
    EXPECT_NEAR(glm::length(placed - core), 0.0, 1e-6) << bone;
  }
}

}  // namespace
