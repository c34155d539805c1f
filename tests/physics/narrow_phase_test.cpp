// The narrow phase keeps a face-on-face manifold from one step to the next while its two bodies
// stay within ManifoldReuseSettings of where they were to each other when it was made, and clips
// it again once they have gone further. A pair's separating axis goes on to its next test.
#include <span>
#include <vector>

#include <glm/gtc/quaternion.hpp>
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

// A cube B passes by the edge of a cube A, turned 0.1 rad about z and 0.1 about x, never touching it
// (its points stay apart, so nothing pushes it and it keeps its velocity), one step of one substep
// at a time. Returns the kind of the pair's contact after each step (-1: none).
std::vector<int> kindsPassingBy(const Vec3& start, int steps) {
  phys::World world = testing_phys::openSpace(phys::SolverSettings{}, Vec3(0.0));
  phys::BodyDesc box;
  world.addBody(box);
  box.center = start;
  box.orientation = glm::angleAxis(0.1, Vec3(0.0, 0.0, 1.0)) * glm::angleAxis(0.1, Vec3(1.0, 0.0, 0.0));
  box.velocity = {-0.6, 0.0, 0.6};  // 1 cm a step along x and z
  world.addBody(box);
  std::vector<int> kinds;
  for (int s = 0; s < steps; ++s) {
    world.step();
    const std::span<const phys::BodyContact> contacts = world.bodyContacts();
    kinds.push_back(contacts.empty() ? -1 : contacts[0].kind);
  }
  return kinds;
}

// B's contact is found where it is after each step: at (0.97, 0, 1.04) an edge-edge axis wins
// outright (the boxes 6.9 mm apart along it); at (0.96, 0, 1.05) the same edge axis is still the
// shallowest (6.9 mm apart along it, 2.6 mm along the best face axis) but not by the face bias, which
// asks for 0.95 * 2.6 + 10 mm. Met there first, the pair takes the face;
// come from the first place, it keeps the edge it had (satTest's previousAxis, passed on by the
// narrow phase from the pair's manifold).
// The contact and friction passes wait on loading their points (docs/performance.md, "The
// contact's seldom read part apart"): a point holds what they read of it in every pass, and the
// rest (a capsule's surface points, a carried slide) is apart. 224 bytes: the two embeddings, the
// normal, offset, materials, anchor and slip end, ids and flags.
TEST(NarrowPhase, APointHoldsOnlyWhatThePassesReadOfIt) {
  EXPECT_LE(sizeof(phys::BodyContact), 224u);
}

TEST(NarrowPhase, APairKeepsTheEdgeAxisItHadWhileItIsTheShallowest) {
  const int edgeEdge = static_cast<int>(phys::ContactKind::EdgeEdge);
  const std::vector<int> comingFromTheEdge = kindsPassingBy({0.98, 0.0, 1.03}, 2);
  EXPECT_EQ(comingFromTheEdge, (std::vector<int>{edgeEdge, edgeEdge}));
  const std::vector<int> metThere = kindsPassingBy({0.97, 0.0, 1.04}, 1);
  ASSERT_EQ(metThere.size(), 1u);
  EXPECT_NE(metThere[0], -1);
  EXPECT_NE(metThere[0], edgeEdge);
}

}  // namespace
