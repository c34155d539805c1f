// The sandbox's time budget (session.h, background_steps.h): steps taken on another thread on
// copies of the runs give the world the session's own steps would, a command cancels them and
// acts on the world shown, the budget ends them after a whole step, and the drag the user moves
// meanwhile reaches the stepped world, and letting go cancels them.
#include <chrono>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "project_session.h"
#include "session.h"

namespace {

using namespace std::chrono_literals;

sandbox::Session open(const char* name) {
  return testing_app::openSession(name);
}

sandbox::StepsTaken waitForSteps(sandbox::Session& s) {
  for (int i = 0; i < 120000; ++i) {
    if (const auto taken = s.finishSteps()) return *taken;
    std::this_thread::sleep_for(1ms);
  }
  ADD_FAILURE() << "the background steps did not finish within two minutes";
  return {};
}

TEST(BackgroundSteps, TakeTheStepsTheSessionWouldHave) {
  sandbox::Session a = open("ragdolls"), b = open("ragdolls");
  for (int i = 0; i < 30; ++i) a.step();
  b.startSteps(30, 600s);
  EXPECT_TRUE(b.stepping());
  const sandbox::StepsTaken taken = waitForSteps(b);
  EXPECT_EQ(taken.steps, 30);
  EXPECT_FALSE(taken.cut);
  EXPECT_FALSE(b.stepping());
  EXPECT_EQ(b.scene().world.stepCount(), 30);
  EXPECT_EQ(b.scene().world.stateHash(), a.scene().world.stateHash());
  EXPECT_EQ(b.runs().front().timed, 30);      // the step times came back with the world
  EXPECT_FALSE(b.finishSteps().has_value());  // collected once
}

TEST(BackgroundSteps, ACommandCancelsThemAndActsOnTheWorldShown) {
  sandbox::Session s = open("ragdolls");
  phys::SolverSettings slow = s.scene().world.solverSettings();
  slow.iterations = slow.substeps = 64;  // about 1.6 s a step on this machine
  ASSERT_EQ(s.setSolverSettings(slow), "");
  s.step();
  const std::uint64_t shown = s.scene().world.stateHash();
  s.startSteps(8, 600s);
  std::this_thread::sleep_for(5ms);
  EXPECT_EQ(s.changeGravity(1.0), "");
  EXPECT_FALSE(s.stepping());
  EXPECT_FALSE(s.finishSteps().has_value());
  EXPECT_EQ(s.scene().world.stepCount(), 1);
  EXPECT_EQ(s.scene().world.stateHash(), shown);  // gravity moves nothing until the next step
  EXPECT_NEAR(s.scene().world.worldSettings().gravity.y, -10.81, 1e-12);
}

TEST(BackgroundSteps, TheBudgetEndsThemAfterAWholeStep) {
  sandbox::Session s = open("pyramid");
  s.startSteps(5, 0s);
  const sandbox::StepsTaken taken = waitForSteps(s);
  EXPECT_EQ(taken.steps, 1);
  EXPECT_TRUE(taken.cut);
  EXPECT_EQ(s.scene().world.stepCount(), 1);
  s.startSteps(0, 600s);  // nothing owed: nothing started
  EXPECT_FALSE(s.stepping());
}

TEST(BackgroundSteps, TheDragMovedMeanwhileReachesTheSteppedWorldAndLettingGoCancels) {
  sandbox::Session s = open("ragdoll");
  const phys::Vec3 centre = s.scene().world.bodyPose(phys::BodyId(0)).center;
  const phys::Vec3 eye = centre + phys::Vec3(0.0, 0.0, 5.0);
  ASSERT_TRUE(s.pick(eye, phys::Vec3(0.0, 0.0, -1.0)));
  s.startSteps(3, 600s);
  const phys::Vec3 up = centre + phys::Vec3(0.0, 1.0, 0.0) - eye;
  s.dragAlong(eye, up);
  const phys::Vec3 target = s.scene().world.drag()->target;
  EXPECT_GT(target.y, centre.y + 0.5);  // on the picked plane, a little in front of the centre
  EXPECT_EQ(waitForSteps(s).steps, 3);
  ASSERT_TRUE(s.scene().world.drag().has_value());
  EXPECT_EQ(s.scene().world.drag()->target, target);

  // Letting go cancels them: the copies hold the drag, and the recording's keyframe after the
  // release must be what every later step starts from.
  s.startSteps(3, 600s);
  s.release();
  EXPECT_FALSE(s.stepping());
  EXPECT_FALSE(s.scene().world.drag().has_value());
  EXPECT_FALSE(s.dragging());
  s.startSteps(3, 600s);
  EXPECT_EQ(waitForSteps(s).steps, 3);
  EXPECT_FALSE(s.scene().world.drag().has_value());
}

}  // namespace
