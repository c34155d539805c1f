// The narrow phase keeps a face-on-face manifold from one step to the next while its two bodies
// stay within ManifoldReuseSettings of where they were to each other when it was made, and clips
// it again once they have gone further.
#include <vector>

#include <gtest/gtest.h>

#include "test_util.h"

namespace {

using phys::Vec3;

// A box B lies on a 1 m box A, face on face, in empty space: no force between them, so B keeps the
// motion it is given. Returns, per step after the first, whether the contacts were carried over
// (every point's embedding as the step before left it) rather than clipped again.
std::vector<bool> carriedSteps(const phys::SolverSettings& solver, const Vec3& velocity, const Vec3& spin,
                               int steps, double sizeB = 1.0, double asideB = 0.5) {
  phys::World world = testing_phys::openSpace(solver, Vec3(0.0));
  phys::BodyDesc box;
  box.center = {0.0, 0.5, 0.0};
  world.addBody(box);
  box.center = {asideB, 1.0 + sizeB / 2.0, 0.0};
  box.size = Vec3(sizeB);
  box.velocity = velocity;
  box.angularVelocity = spin;
  world.addBody(box);
  std::vector<bool> carried;
  world.step();
  std::vector<phys::BodyContact> last(world.bodyContacts().begin(), world.bodyContacts().end());
  EXPECT_EQ(last.size(), 4u);  // the corners of the faces' overlap
  for (int s = 1; s < steps; ++s) {
    world.step();
    const std::span<const phys::BodyContact> now = world.bodyContacts();
    bool same = now.size() == last.size();
    for (std::size_t k = 0; same && k < now.size(); ++k) {
      same = now[k].pointA.weight == last[k].pointA.weight && now[k].pointB.weight == last[k].pointB.weight;
    }
    carried.push_back(same);
    last.assign(now.begin(), now.end());
  }
  return carried;
}

// 0.0036 m/s is 0.06 mm a step: carried one step (0.06 mm from where it was made, within 0.1 mm),
// clipped again the next (0.12 mm), and so on.
TEST(NarrowPhase, AManifoldIsCarriedWhileTheBodiesHaveMovedLessThanTheShift) {
  const phys::SolverSettings solver;
  ASSERT_EQ(solver.manifoldReuse.maxShift, 0.0001);
  const std::vector<bool> carried = carriedSteps(solver, {0.0036, 0.0, 0.0}, Vec3(0.0), 7);
  EXPECT_EQ(carried, (std::vector<bool>{true, false, true, false, true, false}));
}

// 0.0072 rad/s about the normal is 0.00012 rad a step: within 0.0002 once, not twice. B is a 0.5 m box
// in the middle of A, so the overlap of the faces stays B's square, 4 points as it turns (where the
// square and A's face both clip it, more corners appear, and a manifold that lost some to the
// reduction to 4 is never carried).
TEST(NarrowPhase, AManifoldIsCarriedWhileTheBodiesHaveTurnedLessThanTheTurn) {
  const phys::SolverSettings solver;
  ASSERT_EQ(solver.manifoldReuse.maxTurn, 0.0002);
  const std::vector<bool> carried = carriedSteps(solver, Vec3(0.0), {0.0, 0.0072, 0.0}, 7, 0.5, 0.0);
  EXPECT_EQ(carried, (std::vector<bool>{true, false, true, false, true, false}));
}

TEST(NarrowPhase, WithoutReuseEveryStepClipsAgain) {
  phys::SolverSettings none;
  none.manifoldReuse = {0.0, 0.0};
  EXPECT_EQ(carriedSteps(none, {0.0036, 0.0, 0.0}, Vec3(0.0), 4), (std::vector<bool>{false, false, false}));
  EXPECT_EQ(carriedSteps(none, Vec3(0.0), {0.0, 0.0072, 0.0}, 4, 0.5, 0.0),
            (std::vector<bool>{false, false, false}));
}

}  // namespace
