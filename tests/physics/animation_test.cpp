// Animation (docs/physics.md, "Animation"): sampling a clip between frames, looping with the root
// carried on, blending, refusing bad clips; binding a clip to a ragdoll by name, refusing one that
// does not fit with the bones named; a character's drives aimed at the clip's pose and followed.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "character_util.h"
#include "physics/animation.h"
#include "physics/character.h"
#include "physics/debug_draw.h"
#include "physics/ragdoll.h"
#include "physics/world.h"
#include "test_util.h"

namespace {

using phys::Clip;
using phys::ClipPose;
using phys::Quat;
using phys::Real;
using phys::Vec3;
using testing_phys::ragdollClip;
using testing_phys::rigidRagdoll;

const Vec3 kX(1.0, 0.0, 0.0);
const Vec3 kZ(0.0, 0.0, 1.0);
constexpr Real kDeg = std::numbers::pi / 180.0;

Real angleOf(const Quat& q) {
  return 2.0 * std::acos(std::min(1.0, std::abs(q.w)));
}

// One bone, three frames half a second apart: the root goes (0,0,0), (1,0,0), (2,1,0) and turns
// 0, 90 and 180 degrees about z.
Clip threeFrames() {
  Clip c;
  c.name = "three";
  c.bones = {"root"};
  c.parents = {-1};
  c.frameTime = 0.5;
  c.root = {Vec3(0.0), Vec3(1.0, 0.0, 0.0), Vec3(2.0, 1.0, 0.0)};
  for (int f = 0; f < 3; ++f) c.turns.push_back(glm::angleAxis(f * 90.0 * kDeg, kZ));
  return c;
}

TEST(Clip, SamplesBetweenFramesAndClampsOrLoops) {
  const Clip c = threeFrames();
  ASSERT_EQ(phys::clipProblem(c), "");
  EXPECT_DOUBLE_EQ(c.duration(), 1.0);
  ClipPose p;
  phys::sampleClip(c, 0.25, false, p);
  EXPECT_NEAR(glm::length(p.root - Vec3(0.5, 0.0, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(angleOf(p.turns[0]), 45.0 * kDeg, 1e-12);
  phys::sampleClip(c, 0.875, false, p);
  EXPECT_NEAR(glm::length(p.root - Vec3(1.75, 0.75, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(angleOf(p.turns[0]), 157.5 * kDeg, 1e-12);
  // Before the start, the first frame; after the end, the last.
  phys::sampleClip(c, -3.0, false, p);
  EXPECT_EQ(p.root, Vec3(0.0));
  phys::sampleClip(c, 7.0, false, p);
  EXPECT_EQ(p.root, Vec3(2.0, 1.0, 0.0));
  // Looping: two loops done carry the root on by twice the first-to-last displacement.
  phys::sampleClip(c, 2.25, true, p);
  EXPECT_NEAR(glm::length(p.root - Vec3(4.5, 2.0, 0.0)), 0.0, 1e-12);
  EXPECT_NEAR(angleOf(p.turns[0]), 45.0 * kDeg, 1e-12);
  // Times so large that the loops taken off round below zero, or past any clip: still a pose of the
  // clip (a negative frame index was undefined behaviour; the sanitizer build catches it).
  Clip odd = c;
  odd.frameTime = 0.72 / 2.0;  // not a power of two: the remainder rounds
  for (const Real time : {1e14, 3.7e15 + 0.3, 1e17, 1e300, -1e300, 1e9 - 1e-7}) {
    for (const bool loop : {false, true}) {
      phys::sampleClip(odd, time, loop, p);
      EXPECT_TRUE(phys::finite(p.root)) << time;
      EXPECT_LE(glm::length(p.root), 1e10) << time;  // 1e9 s of loops at 0.72 s each, 2.24 m a loop
      for (const Quat& q : p.turns) EXPECT_NEAR(glm::length(q), 1.0, 1e-12) << time;
    }
  }
}

TEST(Clip, BlendsHalfway) {
  ClipPose a, b, out;
  a.root = Vec3(0.0);
  b.root = Vec3(2.0, 0.0, 0.0);
  a.turns = {Quat(1.0, 0.0, 0.0, 0.0)};
  b.turns = {-glm::angleAxis(90.0 * kDeg, kX)};  // the same turn, the other sign: blended the short way
  phys::blendPoses(a, b, 0.5, out);
  EXPECT_EQ(out.root, Vec3(1.0, 0.0, 0.0));
  EXPECT_NEAR(angleOf(out.turns[0]), 45.0 * kDeg, 1e-12);
}

TEST(Clip, ProblemsAreNamed) {
  auto problem = [](auto&& spoil) {
    Clip c = threeFrames();
    spoil(c);
    return phys::clipProblem(c);
  };
  EXPECT_EQ(problem([](Clip& c) { c.bones.clear(); }), "it has no bones");
  EXPECT_EQ(problem([](Clip& c) { c.frameTime = 0.0; }), "its frame time is not finite and >= 1e-6 s");
  EXPECT_EQ(problem([](Clip& c) { c.frameTime = 1e-7; }), "its frame time is not finite and >= 1e-6 s");
  EXPECT_EQ(problem([](Clip& c) { c.root[2].y = 2e6; }),
            "frame 2: the root is farther than 1e6 m from the origin");
  EXPECT_EQ(problem([](Clip& c) { c.turns.pop_back(); }), "it has not one turn a bone a frame");
  EXPECT_EQ(problem([](Clip& c) { c.root[1].x = NAN; }), "frame 1: the root's position is not finite");
  EXPECT_EQ(problem([](Clip& c) { c.turns[2] *= 2.0; }),
            "frame 2: bone 'root' has a turn that is not a unit quaternion");
  EXPECT_EQ(problem([](Clip& c) {
              c.bones.push_back("root");
              c.parents.push_back(0);
            }),
            "two bones are named 'root'");
  EXPECT_EQ(problem([](Clip& c) {
              c.bones.push_back("arm");
              c.parents.push_back(1);
            }),
            "bone 'arm' does not come after its parent");
}

// Clips a character changes between must have its bones: the message names those that differ.
TEST(Clip, SkeletonDifferencesNameTheBones) {
  const auto skeleton = [](const char* name, std::vector<std::string> bones, std::vector<int> parents) {
    Clip c;
    c.name = name;
    c.bones = std::move(bones);
    c.parents = std::move(parents);
    return c;
  };
  const Clip body = skeleton("body", {"torso", "head", "arm"}, {-1, 0, 0});
  EXPECT_EQ(phys::skeletonDifference(body, body), "");
  EXPECT_EQ(phys::skeletonDifference(skeleton("a", {"torso", "neck", "arm"}, {-1, 0, 0}), body),
            "clip 'a' has other bones than 'body': it lacks 'head'; it has 'neck' that 'body' has not");
  EXPECT_EQ(
      phys::skeletonDifference(skeleton("b", {"torso", "head", "arm"}, {-1, 0, 1}), body),
      "clip 'b' has other bones than 'body': the parent of bone 'arm' is 'head' where 'body' has 'torso'");
  EXPECT_EQ(phys::skeletonDifference(skeleton("c", {"torso", "arm", "head"}, {-1, 0, 0}), body),
            "clip 'c' has other bones than 'body': the same bones in another order");
  EXPECT_EQ(phys::skeletonDifference(skeleton("d", {"head", "torso", "arm"}, {-1, 0, 1}), body),
            "clip 'd' has other bones than 'body': the parent of bone 'head' is none (the root) where 'body' "
            "has 'torso'; the parent of bone 'torso' is 'head' where 'body' has none (the root)");
}

TEST(Character, AClipThatDoesNotFitIsRefusedWithTheBonesNamed) {
  phys::World w = testing_phys::openSpace();
  rigidRagdoll(w, "r");
  Clip c = ragdollClip(2, [](const std::string&, Real) { return 0.0; });
  c.bones[1] = "tail";
  try {
    phys::bindClip(w, "r", c);
    FAIL() << "bound";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no part for the bones 'tail'"), std::string::npos) << what;
    EXPECT_NE(what.find("no bone for the parts 'head'"), std::string::npos) << what;
  }
  // The right names in the wrong tree: the head under an arm.
  Clip wrongTree = ragdollClip(2, [](const std::string&, Real) { return 0.0; });
  wrongTree.parents[1] = 0;
  std::swap(wrongTree.bones[1], wrongTree.bones[3]);  // lower-arm-left under the torso
  EXPECT_THROW(phys::bindClip(w, "r", wrongTree), std::invalid_argument);
  EXPECT_THROW(phys::bindClip(w, "nobody", ragdollClip(2, [](const std::string&, Real) { return 0.0; })),
               std::invalid_argument);
  // A particle ragdoll binds through its particle joints; one of mixed parts does not bind.
  rigidRagdoll(w, "p", Vec3(3.0, 0.85, 0.0), phys::RagdollModel::Lean);
  const std::vector<phys::CharacterBone> lean =
      phys::bindClip(w, "p", ragdollClip(2, [](const std::string&, Real) { return 0.0; }));
  for (std::size_t b = 1; b < lean.size(); ++b) {
    const phys::ParticleJoint& j = w.particleJoints()[lean[b].joint];
    EXPECT_TRUE((j.a == lean[b].body) != (j.b == lean[b].body)) << b;
  }
  rigidRagdoll(w, "m", Vec3(6.0, 0.85, 0.0), phys::RagdollModel::Lean);
  phys::BodyDesc odd;
  odd.name = "m.tail";
  odd.model = phys::BodyModel::Rigid;
  odd.center = Vec3(6.0, 3.0, 0.0);
  w.addBody(odd);
  Clip tailed = ragdollClip(2, [](const std::string&, Real) { return 0.0; });
  tailed.bones.push_back("tail");
  tailed.parents.push_back(0);
  for (int f = 0; f < 2; ++f)
    tailed.turns.insert(tailed.turns.begin() + (static_cast<std::ptrdiff_t>(f) + 1) * 11 - 1,
                        Quat(1.0, 0.0, 0.0, 0.0));
  ASSERT_EQ(phys::clipProblem(tailed), "");
  try {
    phys::bindClip(w, "m", tailed);
    FAIL() << "bound";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("part 'tail' is rigid"), std::string::npos) << e.what();
  }
  // Nothing was added by a refused character.
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = std::make_shared<const Clip>(c);
  EXPECT_THROW(w.addCharacter(desc), std::invalid_argument);
  EXPECT_TRUE(w.characters().empty());
}

// The rest pose as a clip aims every joint's drive at the joint's rest; a clip that bends the left
// elbow aims that joint at the bend, as the hinge measures it. The root is held by its drive: a free
// body whose elbow snaps 60 degrees in a step (strength 1 is a rigid drive) starts to turn, since
// velocities taken from a step's change of pose keep angular momentum only for small turns.
TEST(Character, DrivesAreAimedAtTheClipsPose) {
  // Particle parts too, through their particle joints, to a little less (their pins give a little).
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Rigid, phys::RagdollModel::Lean, phys::RagdollModel::Seed}) {
    SCOPED_TRACE(phys::toString(model));
    const bool rigid = model == phys::RagdollModel::Rigid;
    phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
    const phys::Ragdoll r = rigidRagdoll(w, "r", Vec3(0.0, 0.85, 0.0), model);
    const Real bend = -60.0 * kDeg;
    phys::CharacterDesc desc;
    desc.ragdoll = "r";
    desc.playback.clip = std::make_shared<const Clip>(
        ragdollClip(2, [&](const std::string& bone, Real) { return bone == "lower-arm-left" ? bend : 0.0; }));
    desc.rootStrength = 1.0;
    ASSERT_EQ(w.addCharacter(desc), 0u);
    EXPECT_EQ(w.characters()[0].particleParts, !rigid);
    for (int i = 0; i < 120; ++i) w.step();
    const Real within = rigid ? 0.5 * kDeg : 1.0 * kDeg;
    for (int h = 0; h < phys::kRagdollHinges; ++h) {
      const phys::RagdollHinge& hinge = r.hinges[static_cast<std::size_t>(h)];
      const bool elbow = hinge.child == phys::RagdollPart::LowerArmLeft;
      EXPECT_NEAR(phys::hingeAngle(w, r, hinge), elbow ? bend : 0.0, within) << h;
      const std::size_t k = r.firstJoint + static_cast<std::size_t>(h);
      EXPECT_EQ(rigid ? w.jointDrive(k).strength : w.particleJointDrive(k).strength, 1.0);
    }
    EXPECT_LT(phys::trackingError(w, 0), within);
    EXPECT_GT(w.profile()[phys::Stage::Animate], 0.0);
  }
}

// startInPose: the ragdoll is put in the clip's first pose when the character is added, at rest,
// every joint closed (the pivots meet to round-off) and every part on its target, its root on the
// clip's path; without it the parts stay where the ragdoll was made.
TEST(Character, StartsInTheClipsPoseWhenAsked) {
  const Real bend = -60.0 * kDeg;
  const auto clip = std::make_shared<const Clip>(ragdollClip(2, [&](const std::string& bone, Real) {
    return bone.starts_with("lower-") ? bend : bone == "upper-leg-left" ? -30.0 * kDeg : 0.0;
  }));
  for (const bool posed : {false, true}) {
    SCOPED_TRACE(posed ? "in the clip's pose" : "as made");
    phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
    const phys::Ragdoll r = rigidRagdoll(w, "r");
    const phys::BodyId torso = r.parts[static_cast<std::size_t>(phys::RagdollPart::Torso)];
    const Vec3 madeAt = w.bodyPose(torso).center;
    phys::CharacterDesc desc;
    desc.ragdoll = "r";
    desc.playback.clip = clip;
    desc.startInPose = posed;
    w.addCharacter(desc);
    for (std::size_t k = 0; k < w.rigidJoints().size(); ++k) {
      const phys::JointDesc j = w.jointDesc(k);
      EXPECT_LT(glm::length(j.pivot - j.pivotB), 1e-12) << k;
    }
    for (int h = 0; h < phys::kRagdollHinges; ++h) {
      const phys::RagdollHinge& hinge = r.hinges[static_cast<std::size_t>(h)];
      const bool lower =
          hinge.child == phys::RagdollPart::LowerArmLeft || hinge.child == phys::RagdollPart::LowerArmRight ||
          hinge.child == phys::RagdollPart::LowerLegLeft || hinge.child == phys::RagdollPart::LowerLegRight;
      const Real want = !posed                                           ? 0.0
                        : lower                                          ? bend
                        : hinge.child == phys::RagdollPart::UpperLegLeft ? -30.0 * kDeg
                                                                         : 0.0;
      EXPECT_NEAR(phys::hingeAngle(w, r, hinge), want, 1e-9) << h;
    }
    for (const phys::BodyId part : r.parts) EXPECT_EQ(glm::length(w.bodyVelocity(part).first), 0.0);
    // The clip's root is 1.17 m over its floor: in open space the frame's origin is where the torso
    // was made, less that height, so the torso stays put.
    EXPECT_NEAR(glm::length(w.bodyPose(torso).center - madeAt), 0.0, 1e-12);
  }
}

// What the ghost of the target pose draws: one box a part, in the target's orientation and the
// part's own size, placed down the joints from the root where it is.
class GhostRecorder : public phys::DebugDraw {
 public:
  struct Box {
    Vec3 centre;
    Quat orientation;
    Vec3 half;
  };
  std::vector<Box> boxes;
  int lines = 0;
  void line(const Vec3&, const Vec3&, phys::Color) override { ++lines; }
  void point(const Vec3&, Real, phys::Color) override {}
  void box(const Vec3& c, const Quat& q, const Vec3& h, phys::Color color) override {
    EXPECT_EQ(color.b, phys::colors::kTarget.b);
    boxes.push_back({c, q, h});
  }
};

// The ghost (DebugDrawFlags::targets): off, nothing; on, a box and two skeleton lines a jointed part.
// A ragdoll started in its clip's pose is its own ghost (to round-off); one as made is not, its ghost
// turned to the targets with its joints' pivots meeting.
TEST(Character, TheGhostIsTheTargetPosePlacedDownTheJoints) {
  const auto clip = std::make_shared<const Clip>(ragdollClip(
      2, [&](const std::string& bone, Real) { return bone.starts_with("lower-") ? -60.0 * kDeg : 0.0; }));
  phys::DebugDrawFlags ghost;
  ghost.constraints = ghost.contacts = false;
  ghost.targets = true;
  for (const bool posed : {true, false}) {
    SCOPED_TRACE(posed ? "in the clip's pose" : "as made");
    phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
    rigidRagdoll(w, "r");
    phys::CharacterDesc desc;
    desc.ragdoll = "r";
    desc.playback.clip = clip;
    desc.startInPose = posed;
    w.addCharacter(desc);
    GhostRecorder off;
    w.debugDraw(off, phys::DebugDrawFlags{false, false, false, false, false});
    EXPECT_TRUE(off.boxes.empty());
    GhostRecorder on;
    w.debugDraw(on, ghost);
    const phys::Character& c = w.characters()[0];
    ASSERT_EQ(on.boxes.size(), c.bones.size());
    EXPECT_EQ(on.lines, 2 * static_cast<int>(c.bones.size() - 1));
    Real farthest = 0.0, turned = 0.0;
    for (std::size_t b = 0; b < c.bones.size(); ++b) {
      const phys::BodyPose pose = w.bodyPose(c.bones[b].body);
      EXPECT_EQ(on.boxes[b].half, w.bodies()[c.bones[b].body].halfExtents);
      farthest = std::max(farthest, glm::length(on.boxes[b].centre - pose.center));
      turned = std::max(turned, testing_phys::angleBetween(on.boxes[b].orientation, pose.orientation));
    }
    EXPECT_NEAR(glm::length(on.boxes[0].centre - w.bodyPose(c.bones[0].body).center), 0.0, 1e-12);
    if (posed) {
      EXPECT_LT(farthest, 1e-12);
      EXPECT_LT(turned, 1e-6);
    } else {
      EXPECT_GT(turned, 50.0 * kDeg);  // the lower limbs, bent 60 degrees by the clip
      EXPECT_GT(farthest, 0.05);
    }
  }
}

// A swinging clip (the legs and arms as in a run, 1.4 Hz) followed with the root carried by the hand
// of god, at the default stiffness and strength 0.9: the parts lag their targets by a few degrees.
Real followMovingClip(phys::RagdollModel model) {
  phys::WorldSettings ws;
  ws.ground = false;
  phys::World w(ws, testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8));
  rigidRagdoll(w, "r", Vec3(0.0, 0.85, 0.0), model);
  const Real period = 0.72;
  auto angle = [&](const std::string& bone, Real t) {
    const Real s = std::sin(2.0 * std::numbers::pi * t / period);
    if (bone.starts_with("upper-leg"))
      return (bone.ends_with("left") ? -30.0 : 30.0) * s * kDeg - 25.0 * kDeg;
    if (bone.starts_with("upper-arm")) return (bone.ends_with("left") ? 30.0 : -30.0) * s * kDeg;
    if (bone.starts_with("lower-leg")) return 40.0 * kDeg;
    return 0.0;
  };
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = std::make_shared<const Clip>(ragdollClip(44, angle));
  desc.strength = 0.9;
  desc.rootStrength = 1.0;
  w.addCharacter(desc);
  Real sum = 0.0;
  int n = 0;
  for (int i = 0; i < 600; ++i) {
    w.step();
    if (i < 60) continue;  // the first second: the pose comes from the standing one
    const Real e = phys::trackingError(w, 0);
    sum += e * e;
    ++n;
  }
  const Real rms = std::sqrt(sum / n);
  std::printf("swinging clip, %s ragdoll, strength 0.9, root carried: RMS tracking error %.2f degrees\n",
              std::string(phys::toString(model)).c_str(), rms / kDeg);
  EXPECT_TRUE(w.freezes().empty());
  return rms;
}

TEST(Character, FollowsAMovingClipWithTheRootCarried) {
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Rigid, phys::RagdollModel::Lean, phys::RagdollModel::Seed}) {
    SCOPED_TRACE(phys::toString(model));
    EXPECT_LT(followMovingClip(model), 5.0 * kDeg);
  }
}

// A clip whose root is the hip joint (as motion capture's is), with the root offset from it to the torso's
// centre: as the clip pitches its root 60 degrees forwards about the still hips, the hand of god (strength
// 1, in space) carries the torso's centre round the hips, the offset turned with the root; without the
// offset it would hold the centre still and turn the torso about it, 0.29 m from where the clip has it.
TEST(Character, TheRootOffsetTurnsWithTheRoot) {
  phys::WorldSettings ws;
  ws.ground = false;
  const Real pitch = 60.0 * kDeg;
  Clip clip = ragdollClip(
      121, [&](const std::string& bone, Real t) { return bone == "torso" ? pitch * std::min(t, 1.0) : 0.0; });
  for (Vec3& root : clip.root) root = Vec3(0.0, 0.88, 0.0);  // the hips, 0.29 m below the torso's centre
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = std::make_shared<const Clip>(clip);
  desc.playback.loop = false;
  desc.rootStrength = 1.0;
  const Vec3 offset(0.0, 0.29, 0.0);
  // Where the torso's centre starts, and where it is after 2 s of the clip with the root offset given.
  auto torso = [&](const Vec3& rootOffset) {
    phys::World w(ws, testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8));
    const phys::Ragdoll r = rigidRagdoll(w, "r");
    const Vec3 start = w.bodyPose(r.part(phys::RagdollPart::Torso)).center;
    desc.rootOffset = rootOffset;
    w.addCharacter(desc);
    for (int i = 0; i < 120; ++i) w.step();
    return std::pair{start, w.bodyPose(r.part(phys::RagdollPart::Torso)).center};
  };
  const auto [start, turned] = torso(offset);
  const Vec3 hips = start - offset;
  const Vec3 expected = hips + glm::angleAxis(pitch, Vec3(1.0, 0.0, 0.0)) * offset;
  EXPECT_LT(glm::length(turned - expected), 2e-3);
  // Without the offset the centre is held where it started: off by the chord of 60 degrees at 0.29 m.
  const Vec3 held = torso(Vec3(0.0)).second;
  EXPECT_LT(glm::length(held - start), 2e-3);
  EXPECT_NEAR(glm::length(held - expected), 0.29, 4e-3);
  // Refused: an offset no clip's reach allows.
  desc.rootOffset = Vec3(2e6, 0.0, 0.0);
  phys::World other(ws, testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8));
  rigidRagdoll(other, "r");
  EXPECT_THROW(other.addCharacter(desc), std::invalid_argument);
}

// playClip fades from one clip to another: halfway through the fade the elbow's target is halfway,
// and at the end it is the new clip's. A clip of other bones is refused.
// A part's share of the strength: its joint's drive gets the character's strength times it, from the
// next step, as the desc gives it or setPartStrength sets it; a bone the clip has not, the root and
// a share out of [0, 1] are refused with nothing changed.
TEST(Character, EachJointTakesItsPartsShareOfTheStrength) {
  phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
  const phys::Ragdoll r = rigidRagdoll(w, "r");
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip =
      std::make_shared<const Clip>(ragdollClip(2, [](const std::string&, Real) { return 0.0; }));
  desc.strength = 0.8;
  desc.partStrengths = {{"head", 0.5}};
  w.addCharacter(desc);
  w.step();
  const std::size_t neck = r.firstJoint, elbow = r.firstJoint + 2;  // hinges 0 and 2
  EXPECT_DOUBLE_EQ(w.jointDrive(neck).strength, 0.4);
  EXPECT_DOUBLE_EQ(w.jointDrive(elbow).strength, 0.8);
  w.setPartStrength(0, "lower-arm-left", 0.25);
  w.step();
  EXPECT_DOUBLE_EQ(w.jointDrive(elbow).strength, 0.2);
  EXPECT_THROW(w.setPartStrength(0, "tail", 0.5), std::invalid_argument);
  EXPECT_THROW(w.setPartStrength(0, "torso", 0.5), std::invalid_argument);  // the root: no joint
  EXPECT_THROW(w.setPartStrength(0, "head", 1.5), std::invalid_argument);
  EXPECT_THROW(w.setPartStrength(1, "head", 0.5), std::invalid_argument);
  EXPECT_DOUBLE_EQ(w.characters()[0].partStrength[1], 0.5);  // kept
  phys::World other =
      testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
  rigidRagdoll(other, "r");
  desc.partStrengths = {{"wing", 0.5}};
  try {
    other.addCharacter(desc);
    ADD_FAILURE() << "a bone the clip has not was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no bone 'wing'"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(other.characters().empty());
}

// playClip fades from the pose the last change had reached, even when that change was itself
// still fading in.
TEST(Character, PlayClipFadesBetweenClips) {
  phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
  const phys::Ragdoll r = rigidRagdoll(w, "r");
  auto bent = [](Real degrees) {
    return std::make_shared<const Clip>(ragdollClip(2, [degrees](const std::string& bone, Real) {
      return bone == "lower-arm-left" ? degrees * kDeg : 0.0;
    }));
  };
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = bent(0.0);
  w.addCharacter(desc);
  w.step();
  w.playClip(0, phys::Playback{bent(-80.0), 0.0, 1.0, true}, 0.5);
  const std::size_t elbow = r.firstJoint + 2;  // hinge 2: upper-arm-left to lower-arm-left
  for (int i = 0; i < 15; ++i) w.step();       // a quarter second: half the fade
  EXPECT_NEAR(angleOf(w.jointDrive(elbow).target * glm::conjugate(w.jointRest(elbow))), 40.0 * kDeg, 1e-9);
  for (int i = 0; i < 30; ++i) w.step();
  EXPECT_NEAR(angleOf(w.jointDrive(elbow).target * glm::conjugate(w.jointRest(elbow))), 80.0 * kDeg, 1e-9);
  // A change during a fade fades from where that fade had got to: to -80 degrees, then halfway
  // (-40) off to -20. Cutting the first fade short would jump the target to -80 and back.
  auto bend = [&] { return angleOf(w.jointDrive(elbow).target * glm::conjugate(w.jointRest(elbow))); };
  w.playClip(0, phys::Playback{bent(0.0), 0.0, 1.0, true}, 0.0);
  w.step();
  w.playClip(0, phys::Playback{bent(-80.0), 0.0, 1.0, true}, 0.5);
  for (int i = 0; i < 15; ++i) w.step();
  EXPECT_NEAR(bend(), 40.0 * kDeg, 1e-9);
  w.playClip(0, phys::Playback{bent(-20.0), 0.0, 1.0, true}, 0.5);
  w.step();
  EXPECT_NEAR(bend(), (40.0 - 20.0 / 30.0) * kDeg, 1e-9);  // one step of 30 into the fade
  for (int i = 0; i < 14; ++i) w.step();
  EXPECT_NEAR(bend(), 30.0 * kDeg, 1e-9);
  for (int i = 0; i < 15; ++i) w.step();
  EXPECT_NEAR(bend(), 20.0 * kDeg, 1e-9);
  Clip other = threeFrames();
  EXPECT_THROW(w.playClip(0, phys::Playback{std::make_shared<const Clip>(other)}, 0.1),
               std::invalid_argument);
  EXPECT_THROW(w.setCharacterStrength(0, 1.5, 0.0), std::invalid_argument);
  EXPECT_THROW(w.setCharacterStrength(1, 1.0, 0.0), std::invalid_argument);
}

// The turn-in (CharacterDesc::turnInTime): a particle character made far from its clip's pose (both
// elbows to bend 80 degrees) holds each pass of its joints' drives to kTurnInShare of the gap for its
// time, counted in substeps, and then lets them close the whole gap; one put in its clip's pose, and a
// rigid one, never take it; a cut to a far clip and a strength given back start it again, a fade
// does not; 0 turns it off.
TEST(Character, ATurnInHoldsTheDrivesOnlyWhileTurningFromAFarPose) {
  const auto bent = [](Real degrees) {
    return std::make_shared<const Clip>(ragdollClip(2, [degrees](const std::string& bone, Real) {
      return bone.starts_with("lower-arm") ? degrees * kDeg : 0.0;
    }));
  };
  struct Case {
    const char* what;
    phys::RagdollModel model;
    bool inPose;
    Real time;
    bool turns;
  };
  for (const Case& c :
       {Case{"seed, as made", phys::RagdollModel::Seed, false, phys::kTurnInTime, true},
        Case{"seed, in the clip's pose", phys::RagdollModel::Seed, true, phys::kTurnInTime, false},
        Case{"seed, turn-in 0", phys::RagdollModel::Seed, false, 0.0, false},
        Case{"rigid, as made", phys::RagdollModel::Rigid, false, phys::kTurnInTime, false}}) {
    SCOPED_TRACE(c.what);
    phys::World w = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8), Vec3(0.0));
    const phys::Ragdoll r = rigidRagdoll(w, "r", Vec3(0.0, 0.85, 0.0), c.model);
    phys::CharacterDesc desc;
    desc.ragdoll = "r";
    desc.playback.clip = bent(-80.0);
    desc.rootStrength = 1.0;
    desc.startInPose = c.inPose;
    desc.turnInTime = c.time;
    w.addCharacter(desc);
    const phys::Character& k = w.characters()[0];
    EXPECT_TRUE(k.turnInDue);
    const Real h = w.solverSettings().dt / 8.0;
    const std::size_t elbow = r.firstJoint + 2;  // hinge 2: upper-arm-left to lower-arm-left
    auto share = [&] {
      return c.model == phys::RagdollModel::Rigid ? 1.0 : w.particleJointDriveShare(elbow);
    };
    w.step();
    EXPECT_FALSE(k.turnInDue);
    EXPECT_NEAR(k.turnIn, c.turns ? phys::kTurnInTime - 8.0 * h : 0.0, 1e-12);
    EXPECT_EQ(share(), c.turns ? phys::kTurnInShare : 1.0);
    for (int i = 0; i < 5; ++i) w.step();  // 0.1 s: 48 substeps, the whole turn-in
    EXPECT_EQ(k.turnIn, 0.0);
    w.step();
    EXPECT_EQ(share(), 1.0);
    if (!c.turns) continue;
    // Near its pose now: a fade to a far clip starts from that pose and takes none; a cut does.
    for (int i = 0; i < 60; ++i) w.step();
    w.playClip(0, phys::Playback{bent(0.0), 0.0, 1.0, true}, 0.5);
    w.step();
    EXPECT_EQ(k.turnIn, 0.0);
    for (int i = 0; i < 60; ++i) w.step();  // faded to 0 degrees, and followed
    w.playClip(0, phys::Playback{bent(-80.0), 0.0, 1.0, true}, 0.0);
    w.step();
    EXPECT_GT(k.turnIn, 0.0);
    // Limp (the root held), its targets faded away from where its elbows lie, then given its strength
    // back: that starts a turn-in, letting go does not.
    for (int i = 0; i < 60; ++i) w.step();
    w.setCharacterStrength(0, 0.0, 1.0);
    w.playClip(0, phys::Playback{bent(0.0), 0.0, 1.0, true}, 0.5);
    for (int i = 0; i < 60; ++i) w.step();  // the targets faded to 0 degrees; the elbows limp at -80
    EXPECT_EQ(k.turnIn, 0.0);
    w.setCharacterStrength(0, 1.0, 1.0);
    w.step();
    EXPECT_GT(k.turnIn, 0.0);
  }
  phys::World w = testing_phys::openSpace();
  rigidRagdoll(w, "r", Vec3(0.0, 0.85, 0.0), phys::RagdollModel::Seed);
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = bent(0.0);
  desc.turnInTime = -0.1;
  EXPECT_THROW(w.addCharacter(desc), std::invalid_argument);
  EXPECT_TRUE(w.characters().empty());
  desc.turnInTime = 0.2;
  w.addCharacter(desc);
  EXPECT_THROW(w.setCharacterTurnIn(0, std::nan("")), std::invalid_argument);
  EXPECT_THROW(w.setCharacterTurnIn(1, 0.1), std::invalid_argument);
  w.setCharacterTurnIn(0, 0.05);
  EXPECT_EQ(w.characters()[0].turnInTime, 0.05);
}

// A limp character (strength 0) lets its ragdoll fall asleep, and its clip keeps the world's time
// while every island sleeps and the step does nothing else: the clock is not frozen with the bodies.
TEST(Character, ALimpCharactersClipPlaysOnWhileEverythingSleeps) {
  phys::SolverSettings settings = testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8);
  settings.sleep.enabled = true;
  phys::World w(phys::WorldSettings{}, settings);
  rigidRagdoll(w, "r");
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.strength = 0.0;
  desc.playback.clip =
      std::make_shared<const Clip>(ragdollClip(120, [](const std::string&, Real t) { return t; }));
  desc.playback.loop = true;
  w.addCharacter(desc);
  int steps = 0;
  while (!w.islands().allAsleep() && steps < 1200) {
    w.step();
    ++steps;
  }
  ASSERT_TRUE(w.islands().allAsleep()) << "still awake after " << steps << " steps";
  const Real clock = w.characters()[0].now.time;
  EXPECT_NEAR(clock, w.time(), 1e-9);
  // The bodies' part of the state: the whole state hash covers the character's clock too, which
  // must move.
  auto bodiesHash = [&w] {
    phys::Motion m = w.motion();
    m.characters.clear();
    return m.hash();
  };
  const std::uint64_t hash = bodiesHash(), whole = w.stateHash();
  for (int i = 0; i < 60; ++i) w.step();
  EXPECT_TRUE(w.islands().allAsleep());
  EXPECT_EQ(bodiesHash(), hash);    // nothing moved
  EXPECT_NE(w.stateHash(), whole);  // but the clock did
  EXPECT_NEAR(w.characters()[0].now.time - clock, 60.0 * settings.dt, 1e-9);
  EXPECT_NEAR(w.characters()[0].now.time, w.time(), 1e-9);
}

// A character on the rest pose at strength 1 and no hand of god stands on flat ground for a minute.
TEST(Character, StandsAMinuteOnItsOwnLegs) {
  phys::World w(phys::WorldSettings{}, testing_phys::solver(phys::SolverMethod::Xpbd, 2, 8));
  const phys::Ragdoll r = rigidRagdoll(w, "r");
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip =
      std::make_shared<const Clip>(ragdollClip(2, [](const std::string&, Real) { return 0.0; }));
  w.addCharacter(desc);
  for (int i = 0; i < 3600; ++i) w.step();
  EXPECT_NEAR(w.bodyPose(r.part(phys::RagdollPart::Head)).center.y, 1.59, 0.01);
  EXPECT_TRUE(w.freezes().empty());
}

}  // namespace
