// Rewind and replay (recording.h, Session::rewindTo): every recorded step is shown again with its
// recorded state hash, replaying from a rewound step gives the recording again step by step, a
// command on a rewound world forks it, the drag is replayed, steps taken in the background are
// recorded alike, and the memory budget drops the oldest keyframes.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "project_session.h"
#include "session.h"

namespace {

using namespace std::chrono_literals;

sandbox::Session open(const char* name) {
  return testing_app::openSession(name);
}

std::uint64_t hashOf(const sandbox::Session& s) {
  return s.scene().world.stateHash();
}

// The 16-ragdoll pile for 10 s (600 steps at 1/60 s): its fall, its landing and its settling.
TEST(Rewind, TenSecondsOfThePileReplayWithTheSameHashAtEveryStep) {
  sandbox::Session s = open("ragdolls");
  std::vector<std::uint64_t> recorded{hashOf(s)};
  for (int i = 1; i <= 600; ++i) {
    s.step();
    recorded.push_back(hashOf(s));
  }
  ASSERT_EQ(s.recording().first(), 0);
  ASSERT_EQ(s.recording().last(), 600);
  std::printf("10 s of ragdolls recorded in %.1f MB\n", static_cast<double>(s.recording().bytes()) / 1e6);
  // Shown again: every step of the first keyframe intervals (up to 120 steps apart here), then
  // every 13th, which lands anywhere between keyframes.
  for (long n = 0; n <= 600; n += n < 130 ? 1 : 13) {
    ASSERT_EQ(s.rewindTo(n), "") << "step " << n;
    ASSERT_EQ(s.scene().world.stepCount(), n);
    ASSERT_EQ(hashOf(s), recorded[static_cast<std::size_t>(n)]) << "shown at step " << n;
  }
  // Replayed from the start with the same settings: the recording again, step by step.
  ASSERT_EQ(s.rewindTo(0), "");
  for (int i = 1; i <= 600; ++i) {
    s.step();
    ASSERT_EQ(hashOf(s), recorded[static_cast<std::size_t>(i)]) << "replayed step " << i;
  }
  EXPECT_EQ(s.recording().last(), 600);
}

TEST(Rewind, StepsTakenInTheBackgroundAreRecordedAlike) {
  sandbox::Session a = open("ragdolls"), b = open("ragdolls");
  std::vector<std::uint64_t> recorded{hashOf(a)};
  for (int i = 1; i <= 120; ++i) {
    a.step();
    recorded.push_back(hashOf(a));
  }
  while (b.scene().world.stepCount() < 120) {
    b.startSteps(static_cast<int>(std::min<long>(7, 120 - b.scene().world.stepCount())), 600s);
    while (!b.finishSteps()) std::this_thread::sleep_for(1ms);
  }
  ASSERT_EQ(b.recording().last(), 120);
  for (long n : {0L, 1L, 7L, 59L, 60L, 61L, 119L, 120L}) {
    ASSERT_EQ(b.rewindTo(n), "");
    EXPECT_EQ(hashOf(b), recorded[static_cast<std::size_t>(n)]) << "step " << n;
  }
}

TEST(Rewind, ACommandOnARewoundWorldForksTheRecording) {
  sandbox::Session s = open("ragdolls");
  for (int i = 0; i < 100; ++i) s.step();
  ASSERT_EQ(s.rewindTo(50), "");
  EXPECT_EQ(s.recording().last(), 100);  // looking back drops nothing
  ASSERT_EQ(s.spawnBox(phys::Vec3(0.0, 8.0, 0.0), phys::Vec3(0.0)), "");
  EXPECT_EQ(s.recording().last(), 50);  // the run forks at 50, the box in it
  const std::uint64_t withBox = hashOf(s);
  s.step();
  EXPECT_EQ(s.recording().last(), 51);
  ASSERT_EQ(s.rewindTo(50), "");
  EXPECT_EQ(hashOf(s), withBox);
  // Stepping from a rewound world forks it too, with nothing changed.
  for (int i = 0; i < 10; ++i) s.step();
  ASSERT_EQ(s.rewindTo(55), "");
  s.step();
  EXPECT_EQ(s.recording().last(), 56);
}

TEST(Rewind, TheDragIsReplayed) {
  sandbox::Session s = open("ragdoll");
  const phys::Vec3 centre = s.scene().world.bodyPose(phys::BodyId(0)).center;
  const phys::Vec3 eye = centre + phys::Vec3(0.0, 0.0, 5.0);
  for (int i = 0; i < 10; ++i) s.step();
  ASSERT_TRUE(s.pick(eye, centre - eye));
  std::vector<std::uint64_t> recorded;
  for (int i = 0; i < 60; ++i) {
    s.dragAlong(eye, centre + phys::Vec3(0.02 * i, 1.0, 0.0) - eye);  // a moving hand
    s.step();
    recorded.push_back(hashOf(s));
  }
  s.release();
  for (int i = 0; i < 30; ++i) {
    s.step();
    recorded.push_back(hashOf(s));
  }
  for (long n = 11; n <= 100; ++n) {
    ASSERT_EQ(s.rewindTo(n), "");
    ASSERT_EQ(hashOf(s), recorded[static_cast<std::size_t>(n - 11)]) << "step " << n;
  }
  EXPECT_FALSE(s.scene().world.drag().has_value());  // a rewound world holds no drag
  EXPECT_FALSE(s.dragging());
}

TEST(Rewind, TheBudgetDropsTheOldestKeyframes) {
  sandbox::Session s = open("ragdolls");
  s.setRecordingBudget(3u << 20);  // about two keyframes of this pile
  for (int i = 0; i < 600; ++i) s.step();
  EXPECT_GT(s.recording().first(), 0);
  EXPECT_EQ(s.recording().last(), 600);
  EXPECT_LE(s.recording().bytes(), s.recording().budget());
  EXPECT_NE(s.rewindTo(0), "");
  EXPECT_EQ(s.rewindTo(s.recording().first()), "");
}

TEST(Rewind, WhatCannotBeShownSaysWhy) {
  sandbox::Session s = open("falling-box");
  for (int i = 0; i < 10; ++i) s.step();
  EXPECT_EQ(s.rewindTo(11), "step 11 is not recorded (the recording holds steps 0 to 10)");
  EXPECT_EQ(s.scene().world.stepCount(), 10);
  std::vector<sandbox::OverlaySpec> specs(2);
  specs[0] = sandbox::parseOverlaySpec("iterations=2").spec;
  specs[1] = sandbox::parseOverlaySpec("iterations=4").spec;
  ASSERT_EQ(s.startOverlay(specs), "");
  EXPECT_EQ(s.rewindTo(5),
            "stop the method overlay first: only run 0 is recorded, and the others cannot go back");
  s.stopOverlay();
  s.step();
  EXPECT_EQ(s.recording().first(), 0);  // the history from before the overlay is kept
  EXPECT_EQ(s.rewindTo(5), "");
}

}  // namespace

namespace {

// A slider dragged while the world runs sets a setting every frame. Each change once took a copy of
// the whole world: 100 frames of the world's damping dragged on Bullet's ragdolls took the recording
// from 68 MB to 510 MB and the budget dropped the steps before. The changes are now kept as what they
// set, redone on the rebuilt world: the 100 frames add less than one copy of the world, and every
// step shows the state it had, the settings changed after it included. Changes without a step
// between (a slider dragged while paused) keep at most one copy.
TEST(Rewind, ASliderDraggedWhileRunningKeepsItsChangesNotCopies) {
  sandbox::Session s = open("ragdolls");
  for (int i = 0; i < 100; ++i) s.step();
  const std::size_t copy = sandbox::keptCopy(s.scene().world).second;
  const std::size_t before = s.recording().bytes();
  std::vector<std::uint64_t> recorded;
  for (int i = 1; i <= 100; ++i) {
    s.step();
    phys::WorldSettings world = s.scene().world.worldSettings();
    world.damping = 0.002 * i;
    ASSERT_EQ(s.setWorldSettings(world), "");
    if (i % 10 == 0) {  // more passes: the world settles under them at once (path-dependent)
      phys::SolverSettings solver = s.scene().world.solverSettings();
      solver.iterations += 1;
      ASSERT_EQ(s.setSolverSettings(solver), "");
    }
    recorded.push_back(hashOf(s));
  }
  // The steps' own keyframes (one every 50 ms of steps, a few here) come on top of the changes.
  EXPECT_LT(s.recording().bytes() - before, 100 * copy / 4) << "a copy is " << copy << " B";
  EXPECT_EQ(s.recording().first(), 0);
  for (long n = 101; n <= 200; ++n) {
    ASSERT_EQ(s.rewindTo(n), "") << "step " << n;
    ASSERT_EQ(hashOf(s), recorded[static_cast<std::size_t>(n - 101)]) << "step " << n;
  }
  EXPECT_EQ(s.scene().world.worldSettings().damping, 0.2);
  // Paused, many changes: at most one copy more.
  const std::size_t paused = s.recording().bytes();
  for (int i = 1; i <= 50; ++i) {
    phys::WorldSettings world = s.scene().world.worldSettings();
    world.damping = 0.001 * i;
    ASSERT_EQ(s.setWorldSettings(world), "");
  }
  EXPECT_LE(s.recording().bytes(), paused + copy + 4096);
  const std::uint64_t last = hashOf(s);
  ASSERT_EQ(s.rewindTo(199), "");
  ASSERT_EQ(s.rewindTo(200), "");
  EXPECT_EQ(hashOf(s), last);
}

// Each step's record (its hash and drag target) is memory too: an hour of a small scene at 60 steps
// a second is 216,000 of them, 10 MB, which the recording once left out of its count and budget.
TEST(Rewind, EveryStepsRecordCountsInTheMemory) {
  const phys::World world;
  sandbox::Recording recording;
  recording.restart(world);
  const std::size_t keyframe = recording.bytes();
  for (long n = 1; n <= 1000; ++n) recording.stepped(sandbox::StepRecord{n, 0, std::nullopt});
  ASSERT_EQ(recording.last(), 1000);
  EXPECT_EQ(recording.bytes(), keyframe + 1000 * sizeof(sandbox::StepRecord));
  recording.keyframe(world);  // at step 0: a command on a rewound world drops every step after it
  EXPECT_EQ(recording.last(), 0);
  EXPECT_LT(recording.bytes(), keyframe + 100 * sizeof(sandbox::StepRecord));
}

// The time recorded counts each step at the dt it was taken with.
TEST(Rewind, SecondsRecordedFollowADtChangedOnTheWay) {
  sandbox::Session s = testing_app::openSession("ragdoll");
  phys::SolverSettings settings = s.scene().world.solverSettings();
  settings.dt = 1.0 / 60.0;
  ASSERT_EQ(s.setSolverSettings(settings), "");
  for (int i = 0; i < 60; ++i) s.step();
  settings.dt = 1.0 / 240.0;
  ASSERT_EQ(s.setSolverSettings(settings), "");
  for (int i = 0; i < 120; ++i) s.step();
  EXPECT_NEAR(s.recording().seconds(), 1.5, 1e-9);
  EXPECT_NEAR(s.recording().seconds(), s.scene().world.time(), 1e-9);
}

}  // namespace

namespace {

// A click on a body while a recorded step is shown (a double-click to follow it is two) picks it
// and lets go without the world taking a step: nothing of the run changed, so the recording stays
// whole, and Play or N go on along it. It forked at the click, dropping every later step.
TEST(Rewind, AClickOnARewoundWorldKeepsTheRecording) {
  sandbox::Session s = open("ragdoll");
  for (int i = 0; i < 100; ++i) s.step();
  const std::uint64_t at80 = [&] {
    EXPECT_EQ(s.rewindTo(80), "");
    return hashOf(s);
  }();
  ASSERT_EQ(s.rewindTo(50), "");
  const std::uint64_t at50 = hashOf(s);
  const phys::Vec3 centre = s.scene().world.bodyPose(phys::BodyId(0)).center;
  const phys::Vec3 eye = centre + phys::Vec3(0.0, 0.0, 5.0);
  for (int click = 0; click < 2; ++click) {
    ASSERT_TRUE(s.pick(eye, centre - eye));
    s.release();
  }
  EXPECT_EQ(s.recording().last(), 100);
  EXPECT_EQ(hashOf(s), at50);
  ASSERT_EQ(s.rewindTo(80), "");  // along the recording, from the world shown
  EXPECT_EQ(hashOf(s), at80);

  // A drag the world steps with is a command: the run forks there, the spring in it.
  ASSERT_EQ(s.rewindTo(50), "");
  ASSERT_TRUE(s.pick(eye, centre - eye));
  s.dragAlong(eye, centre + phys::Vec3(0.0, 1.0, 0.0) - eye);
  s.step();
  EXPECT_EQ(s.recording().last(), 51);
  const std::uint64_t dragged = hashOf(s);
  s.release();
  ASSERT_EQ(s.rewindTo(51), "");
  EXPECT_EQ(hashOf(s), dragged);
}

}  // namespace
