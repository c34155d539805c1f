// MuJoCo's two forms of a scene (app/lab/peers/mujoco_model.h): free bodies held by <connect>s,
// and the kinematic tree the adapter falls back to when MuJoCo 2.2.2 cannot allocate the first
// (docs/lab.md, "MuJoCo and the 136-ragdoll pile"). The forest and the text need no MuJoCo; the
// physical checks run when it is built in ("mujoco-tree" forces the tree form).
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "peer.h"
#include "peers/joint_forest.h"
#include "peers/mujoco_model.h"
#include "peers/peer_scene.h"
#include "peers/pose_measures.h"
#include "scenes/scene.h"

namespace {

using lab::peers::TreeJoint;

lab::peers::Description describe(const std::string& body) {
  return lab::peers::describe(
      scenes::loadSceneText("<scene name=\"f\">\n  <ground/>\n" + body + "</scene>\n", "mujoco_form_test"));
}

int count(const lab::peers::JointForest& f, TreeJoint joint) {
  int n = 0;
  for (const auto& node : f.nodes) n += node.joint == joint ? 1 : 0;
  return n;
}

TEST(JointForest, ACapsuleRagdollIsOneTreeOfHingesAndBalls) {
  // Bullet's layout: hinges (two pins) at the spine, knees and elbows, cones (one pin) at the
  // neck, hips and shoulders: 6 + 5 x 1 + 5 x 3 = 26 coordinates against 66 for free bodies.
  const auto d = describe("  <ragdoll name=\"r\" pos=\"0 1 0\" shape=\"capsule\"/>\n");
  const auto tree = lab::peers::jointForest(d, true);
  EXPECT_EQ(tree.roots.size(), 1u);
  EXPECT_EQ(count(tree, TreeJoint::Free), 1);
  EXPECT_EQ(count(tree, TreeJoint::Hinge), 5);
  EXPECT_EQ(count(tree, TreeJoint::Ball), 5);
  EXPECT_EQ(tree.dofs, 26);
  for (std::size_t k = 0; k < d.pins.size(); ++k) EXPECT_TRUE(tree.pinInTree[k]) << "pin " << k;
  const auto free = lab::peers::jointForest(d, false);
  EXPECT_EQ(free.roots.size(), 11u);
  EXPECT_EQ(free.dofs, 66);
  for (std::size_t k = 0; k < d.pins.size(); ++k) EXPECT_FALSE(free.pinInTree[k]);
  // The box ragdoll: nine hinges.
  const auto boxes = lab::peers::jointForest(describe("  <ragdoll name=\"r\" pos=\"0 1 0\"/>\n"), true);
  EXPECT_EQ(count(boxes, TreeJoint::Hinge), 9);
  EXPECT_EQ(boxes.dofs, 15);
}

TEST(JointForest, AHingesAxisRunsThroughItsPins) {
  const auto d = describe(
      "  <box name=\"a\" pos=\"0 2 0\" size=\"0.2 1 0.2\"/>\n"
      "  <box name=\"b\" pos=\"0 0.9 0\" size=\"0.2 1 0.2\"/>\n"
      "  <link a=\"a\" b=\"b\" point=\"-0.1 1.45 0\"/>\n"
      "  <link a=\"a\" b=\"b\" point=\"0.1 1.45 0\"/>\n");
  const auto f = lab::peers::jointForest(d, true);
  ASSERT_EQ(f.nodes[1].joint, TreeJoint::Hinge);
  EXPECT_EQ(f.nodes[1].parent, 0);
  EXPECT_NEAR(std::abs(f.nodes[1].axis.x), 1.0, 1e-12);
  EXPECT_NEAR(f.nodes[1].anchor.y, 1.45, 1e-12);
}

TEST(JointForest, APinThatStartsApartOrClosesALoopStaysAConstraint) {
  // a-b pinned shut, b-c pinned shut, c-a pinned shut (a loop: one of the three stays a
  // <connect>), and d pinned to a with its two points 0.2 m apart (held apart: never a joint).
  const auto d = describe(
      "  <box name=\"a\" pos=\"0 2 0\" size=\"0.5\"/>\n"
      "  <box name=\"b\" pos=\"1 2 0\" size=\"0.5\"/>\n"
      "  <box name=\"c\" pos=\"0.5 2.8 0\" size=\"0.5\"/>\n"
      "  <box name=\"d\" pos=\"-1 2 0\" size=\"0.5\"/>\n"
      "  <link a=\"a\" b=\"b\" point=\"0.5 2 0\"/>\n"
      "  <link a=\"b\" b=\"c\" point=\"0.75 2.4 0\"/>\n"
      "  <link a=\"c\" b=\"a\" point=\"0.25 2.4 0\"/>\n"
      "  <link a=\"a\" b=\"d\" a-point=\"-0.4 2 0\" b-point=\"-0.6 2 0\"/>\n");
  const auto f = lab::peers::jointForest(d, true);
  int inTree = 0;
  for (std::size_t k = 0; k < d.pins.size(); ++k) inTree += f.pinInTree[k] ? 1 : 0;
  EXPECT_EQ(inTree, 2);
  EXPECT_FALSE(f.pinInTree[3]);
  EXPECT_EQ(f.nodes[3].joint, TreeJoint::Free);  // d: a root of its own
  EXPECT_EQ(f.roots.size(), 2u);
  EXPECT_EQ(f.dofs, 6 + 3 + 3 + 6);
  // The text holds a <connect> for each pin left out of the tree, and no more.
  const auto model = lab::peers::mjcf::writeModel(d, 1.0 / 60.0, true);
  std::size_t connects = 0;
  for (std::size_t at = model.xml.find("<connect"); at != std::string::npos;
       at = model.xml.find("<connect", at + 1))
    ++connects;
  EXPECT_EQ(connects, 2u);
  EXPECT_EQ(model.equalityRows, 6);
}

TEST(JointForest, AFixedBodyIsARootAndNeverAChild) {
  // A box hung from a pinned particle by a pin: the particle's sphere is the fixed root, the box
  // a ball joint below it.
  const auto d = describe(
      "  <particle name=\"p\" pos=\"0 3 0\" pinned=\"true\"/>\n"
      "  <box name=\"b\" pos=\"0 2.5 0\" size=\"0.2 1 0.2\"/>\n"
      "  <link a=\"b\" b=\"p\" point=\"0 3 0\"/>\n");
  const auto f = lab::peers::jointForest(d, true);
  ASSERT_EQ(d.bodies.size(), 2u);
  EXPECT_EQ(f.nodes[1].joint, TreeJoint::Fixed);
  EXPECT_EQ(f.nodes[0].joint, TreeJoint::Ball);
  EXPECT_EQ(f.nodes[0].parent, 1);
  EXPECT_EQ(f.dofs, 3);
}

TEST(MujocoModel, TheTreeFormNestsBodiesAndKeepsParentsAndChildrenColliding) {
  const auto d = describe("  <ragdoll name=\"r\" pos=\"0 1 0\" shape=\"capsule\"/>\n");
  const auto tree = lab::peers::mjcf::writeModel(d, 1.0 / 60.0, true);
  EXPECT_TRUE(tree.tree);
  EXPECT_EQ(tree.dofs, 26);
  EXPECT_NE(tree.xml.find("filterparent=\"disable\""), std::string::npos);
  EXPECT_NE(tree.xml.find("type=\"hinge\""), std::string::npos);
  EXPECT_NE(tree.xml.find("type=\"ball\""), std::string::npos);
  EXPECT_EQ(tree.xml.find("<connect"), std::string::npos);
  EXPECT_EQ(tree.rowsNeeded(), 4 * 11);  // no rows for joints: one contact a body
  const auto free = lab::peers::mjcf::writeModel(d, 1.0 / 60.0, false);
  EXPECT_EQ(free.equalityRows, 3 * static_cast<int>(d.pins.size()));
  EXPECT_EQ(free.xml.find("filterparent"), std::string::npos);
  EXPECT_NE(free.xml.find("type=\"capsule\""), std::string::npos);
}

// The same scenes stepped in MuJoCo's tree form.
std::unique_ptr<lab::peers::Engine> mujocoTree(const lab::peers::Description& d) {
  return lab::peers::makeEngine("mujoco-tree", d, 1.0 / 60.0);
}

TEST(MujocoTree, APairThrownApartKeepsEachBodysOwnSpin) {
  // Zero gravity: two bars joined by a ball joint 2 m up, turned 30 degrees about x,
  // each spinning about the joint at 2 rad/s about z, the other way round from each other (each
  // one's joint point at rest, so the pair opens like scissors). In the first 0.1 s each moves
  // as its own spin says: a's centre, 0.5 m from the joint, 0.1 m down, and b's too (had b taken
  // a's spin, as a tree child with no joint velocity would, it would rise).
  const auto d = describe(
      "  <world gravity=\"0 0 0\"/>\n"
      "  <box name=\"a\" pos=\"-0.5 2 0\" size=\"1 0.1 0.1\" euler=\"30 0 0\" velocity=\"0 -1 0\" "
      "angular-velocity=\"0 0 114.59155902616465\"/>\n"
      "  <box name=\"b\" pos=\"0.5 2 0\" size=\"1 0.1 0.1\" euler=\"30 0 0\" velocity=\"0 -1 0\" "
      "angular-velocity=\"0 0 -114.59155902616465\"/>\n"
      "  <link a=\"a\" b=\"b\" point=\"0 2 0\"/>\n"
      "  <no-collision a=\"a\" b=\"b\"/>\n");
  auto e = mujocoTree(d);
  if (e == nullptr) GTEST_SKIP() << "MuJoCo is not built in";
  EXPECT_NE(e->settings.find("kinematic tree"), std::string::npos) << e->settings;
  for (int s = 0; s < 6; ++s) e->step();
  for (int i = 0; i < 2; ++i) {
    SCOPED_TRACE(i);
    const double angle = 2.0 * 0.1;  // rad turned in 0.1 s
    const double x = (i == 0 ? -0.5 : 0.5) * std::cos(angle);
    EXPECT_NEAR(e->position(i).y, 2.0 - 0.5 * std::sin(angle), 0.01);
    EXPECT_NEAR(e->position(i).x, x, 0.01);
  }
}

TEST(MujocoTree, ARagdollLandsWithItsJointsHeldExactly) {
  // The capsule ragdoll dropped on its back, as PeerCapsule's test, in the tree form: a tree's
  // pins cannot open (their gap is round-off), its stops are MuJoCo's tendon limits as before.
  const auto d = describe("  <ragdoll name=\"r\" pos=\"0 1 0\" euler=\"80 0 0\" shape=\"capsule\"/>\n");
  auto e = mujocoTree(d);
  if (e == nullptr) GTEST_SKIP() << "MuJoCo is not built in";
  double pinGap = 0.0, gap = 0.0, depth = 0.0;
  for (int s = 1; s <= 120; ++s) {
    e->step();
    if (s <= 60) continue;
    std::vector<phys::Vec3> c;
    std::vector<phys::Quat> q;
    for (std::size_t i = 0; i < d.bodies.size(); ++i) {
      c.push_back(e->position(static_cast<int>(i)));
      q.push_back(e->orientation(static_cast<int>(i)));
    }
    for (const auto& p : d.pins) {
      const auto ia = static_cast<std::size_t>(p.a), ib = static_cast<std::size_t>(p.b);
      pinGap = std::max(pinGap, glm::length(lab::peers::toWorld(c[ia], q[ia], p.localA) -
                                            lab::peers::toWorld(c[ib], q[ib], p.localB)));
    }
    gap = std::max(gap, lab::peers::jointGap(d, c, q));
    depth = std::max(depth, lab::peers::posePenetration(d, c, q));
  }
  e->finish();
  EXPECT_TRUE(e->notes.empty()) << e->notes.front();
  EXPECT_LT(pinGap, 1e-6);
  EXPECT_LT(gap, 0.02);
  EXPECT_LT(depth, 0.02);
}

}  // namespace
