// A world's motion taken out and given to a fresh world of the same structure (World::motion,
// setMotion): the sandbox's recording files rest on it.
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "character_util.h"
#include "test_util.h"

namespace {

using phys::Vec3;
using testing_phys::rigidBox;

// Boxes of the three models on the ground, one on top of another, and a chain of particles
// hanging from a pinned one: contacts, sticks and a rigid body.
phys::World mixedWorld() {
  phys::World world;
  phys::BodyDesc box;
  box.center = {0.0, 0.6, 0.0};
  box.model = phys::BodyModel::Corners;
  world.addBody(box);
  box.center = {0.1, 1.8, 0.0};
  box.orientation = glm::dquat(glm::dvec3(0.2, 0.3, 0.1));
  box.model = phys::BodyModel::Tetra;
  world.addBody(box);
  world.addBody(rigidBox({2.0, 1.5, 0.0}));
  phys::ParticleId previous = world.addParticle({Vec3(-2.0, 4.0, 0.0), Vec3(0.0), 0.0, true});
  for (int i = 1; i <= 4; ++i) {
    const auto p = world.addParticle({Vec3(-2.0 + 0.4 * i, 4.0, 0.0), Vec3(0.0), 1.0});
    world.addStick(previous, p);
    previous = p;
  }
  return world;
}

// A chain and a spinning rigid box in free flight: nothing that keeps history between steps.
phys::World freeWorld() {
  phys::World world = testing_phys::openSpace();
  phys::BodyDesc spinning = rigidBox({3.0, 0.0, 0.0}, Vec3(1.0, 0.5, 0.25));
  spinning.angularVelocity = {1.0, 5.0, 0.3};
  spinning.velocity = {0.0, 4.0, 1.0};
  world.addBody(spinning);
  phys::ParticleId previous = world.addParticle({Vec3(0.0), Vec3(0.0), 0.0, true});
  for (int i = 1; i <= 6; ++i) {
    const auto p = world.addParticle({Vec3(0.3 * i, 0.0, 0.1 * i), Vec3(0.0), 1.0});
    world.addStick(previous, p);
    previous = p;
  }
  return world;
}

void stepTimes(phys::World& world, int steps) {
  for (int i = 0; i < steps; ++i) world.step();
}

// A clip of the box ragdoll's skeleton whose hinges swing by `amplitude` (rad) once a second.
std::shared_ptr<const phys::Clip> swinging(const std::string& name, phys::Real amplitude) {
  phys::Clip c = testing_phys::ragdollClip(61, [amplitude](const std::string& bone, phys::Real t) {
    return bone == "torso" ? 0.0 : amplitude * std::sin(2.0 * M_PI * t);
  });
  c.name = name;
  return std::make_shared<const phys::Clip>(std::move(c));
}

// A character on a rigid ragdoll hung in open space by its root's drive (no contact with anything,
// so nothing but the motion is carried from step to step), playing a swing.
phys::World characterWorld() {
  phys::World world = testing_phys::openSpace(testing_phys::solver(phys::SolverMethod::Xpbd, 2, 4));
  testing_phys::rigidRagdoll(world, "r", phys::Vec3(0.0, 2.0, 0.0));
  phys::CharacterDesc desc;
  desc.ragdoll = "r";
  desc.playback.clip = swinging("swing", 0.6);
  desc.rootStrength = 1.0;
  desc.reaction.getUp.clip = swinging("get-up", 0.1);
  world.addCharacter(desc);
  return world;
}

// A run of it told things on the way: a strength, a fade to another clip, a queued change back.
void characterRun(phys::World& world, int from, int to) {
  for (int s = from; s < to; ++s) {
    if (s == 20) world.setCharacterStrength(0, 0.7, 1.0);
    if (s == 30) world.playClip(0, phys::Playback{swinging("other", -0.4), 0.25, 1.5, true}, 0.4);
    if (s == 35) world.queueClip(0, phys::Playback{swinging("swing", 0.6), 0.0, 1.0, true}, 1.2, 0.3);
    world.step();
  }
}

TEST(Motion, AFreshWorldGivenAMotionHasItsState) {
  phys::World original = mixedWorld();
  stepTimes(original, 90);
  const phys::Motion motion = original.motion();
  EXPECT_EQ(motion.hash(), original.stateHash());
  EXPECT_EQ(motion.steps, 90);

  phys::World resumed = mixedWorld();
  resumed.setMotion(motion);
  EXPECT_EQ(resumed.stateHash(), original.stateHash());
  EXPECT_EQ(resumed.stepCount(), 90);
  EXPECT_DOUBLE_EQ(resumed.time(), original.time());
  for (phys::BodyId b{}; b < original.bodies().size(); ++b) {
    EXPECT_LT(glm::length(resumed.bodyPose(b).center - original.bodyPose(b).center), 1e-12);
  }
}

// Sticks and free rigid bodies keep nothing from step to step but the motion: a world given it
// goes on bit for bit as the original.
TEST(Motion, WithoutContactsTheRunGoesOnExactly) {
  phys::World original = freeWorld();
  stepTimes(original, 50);
  phys::World resumed = freeWorld();
  resumed.setMotion(original.motion());
  stepTimes(original, 120);
  stepTimes(resumed, 120);
  EXPECT_EQ(resumed.stateHash(), original.stateHash());
}

// Contacts carry warm starts and anchors from step to step, which a motion does not hold: the
// resumed run starts them afresh. Over 2 s of the boxes settling it stays within a micrometre and
// a microradian of the original (measured: the particle boxes exactly, the rigid box within
// 1e-16 m and 1e-16 rad: what the contacts carry matters little once they are found again).
TEST(Motion, WithContactsTheRunGoesOnClosely) {
  phys::World original = mixedWorld();
  stepTimes(original, 30);  // the top box still falling onto the bottom one
  phys::World resumed = mixedWorld();
  resumed.setMotion(original.motion());
  stepTimes(original, 120);
  stepTimes(resumed, 120);
  for (phys::BodyId b{}; b < original.bodies().size(); ++b) {
    const phys::BodyPose a = original.bodyPose(b), r = resumed.bodyPose(b);
    EXPECT_LT(glm::length(a.center - r.center), 1e-6) << "body " << b;
    EXPECT_LT(testing_phys::angleBetween(a.orientation, r.orientation), 1e-6) << "body " << b;
  }
}

// A character's clocks, fade, strengths and queued clip are in the motion: a world given it mid-fade
// goes on bit for bit as the original (a world given only the bodies' state played its clips from
// the start again and swung its parts elsewhere).
TEST(Motion, ACharacterGoesOnExactly) {
  phys::World original = characterWorld();
  characterRun(original, 0, 40);  // the fade to "other" under way, the change back queued
  const phys::Motion motion = original.motion();
  ASSERT_EQ(motion.characters.size(), 1u);
  EXPECT_LT(motion.characters[0].blend, 1.0);
  EXPECT_TRUE(motion.characters[0].queued.has_value());
  EXPECT_EQ(motion.hash(), original.stateHash());

  phys::World resumed = characterWorld();
  resumed.setMotion(motion);
  EXPECT_EQ(resumed.stateHash(), original.stateHash());
  characterRun(original, 40, 160);
  characterRun(resumed, 40, 160);
  EXPECT_EQ(resumed.characters()[0].now.clip->name, "swing");  // the queued change came in both
  EXPECT_EQ(resumed.characters()[0].now.time, original.characters()[0].now.time);
  EXPECT_EQ(resumed.stateHash(), original.stateHash());
}

// The hash sees a character's clock, and which clip it plays.
TEST(Motion, HashSeesTheCharacters) {
  phys::World world = characterWorld();
  stepTimes(world, 5);
  const phys::Motion m = world.motion();
  const std::function<void(phys::Motion&)> changes[] = {
      [](phys::Motion& x) { x.characters[0].now.time += 1e-12; },
      [](phys::Motion& x) { x.characters[0].now.clip = swinging("another name", 0.6); },
      [](phys::Motion& x) { x.characters[0].partStrength[3] = 0.5; },
      [](phys::Motion& x) { x.characters[0].state = phys::CharacterState::Down; },
      [](phys::Motion& x) { x.characters[0].pose.turns[2].x += 1e-12; },
  };
  for (const auto& change : changes) {
    phys::Motion x = m;
    change(x);
    EXPECT_NE(x.hash(), m.hash());
  }
}

// A clip's name is the path it was read from: the same scene stepped from another checkout, its
// clips named by other folders, hashes alike.
TEST(Motion, HashSeesAClipsFileNotItsFolder) {
  phys::World world = characterWorld();
  stepTimes(world, 5);
  phys::Motion moved = world.motion();
  moved.characters[0].now.clip = swinging("/elsewhere/swing", 0.6);
  EXPECT_EQ(moved.hash(), world.stateHash());
  moved.characters[0].now.clip = swinging("/elsewhere/swing2", 0.6);
  EXPECT_NE(moved.hash(), world.stateHash());
}

// A motion spoiled in one way is refused with std::invalid_argument (its message printed), and the
// world it was given to is left as it was.
class Refusal {
 public:
  Refusal(phys::World& fresh, phys::Motion good)
      : fresh_(fresh), good_(std::move(good)), before_(fresh.stateHash()) {}
  void operator()(const std::function<void(phys::Motion&)>& spoil, const char* what) {
    phys::Motion m = good_;
    spoil(m);
    try {
      fresh_.setMotion(m);
      ADD_FAILURE() << what << ": accepted";
    } catch (const std::invalid_argument& e) {
      std::printf("%s: %s\n", what, e.what());
    }
    EXPECT_EQ(fresh_.stateHash(), before_) << what;
    EXPECT_EQ(fresh_.stepCount(), 0) << what;
  }

 private:
  phys::World& fresh_;
  phys::Motion good_;
  std::uint64_t before_;
};

TEST(Motion, BadCharacterMotionIsRefusedAndChangesNothing) {
  phys::World source = characterWorld();
  stepTimes(source, 10);
  phys::World fresh = characterWorld();
  Refusal refused(fresh, source.motion());
  refused([](phys::Motion& m) { m.characters.clear(); }, "no characters");
  refused([](phys::Motion& m) { m.characters[0].now.clip.reset(); }, "no clip");
  refused([](phys::Motion& m) { m.characters[0].now.time = std::nan(""); }, "NaN clock");
  refused([](phys::Motion& m) { m.characters[0].strength = 1.5; }, "strength over 1");
  refused([](phys::Motion& m) { m.characters[0].reaction.restSpeed = 0.0; }, "a rest speed of 0");
  refused([](phys::Motion& m) { m.characters[0].now.speed = -1.0; }, "a clip played backwards");
  refused([](phys::Motion& m) { m.characters[0].partStrength.pop_back(); }, "a part short");
  refused([](phys::Motion& m) { m.characters[0].stateTime = -1.0; }, "a negative time in its state");
  refused([](phys::Motion& m) { m.characters[0].now.time = 2e9; }, "a clock past 1e9 s");
  refused(
      [](phys::Motion& m) {
        phys::Clip frameless = *m.characters[0].now.clip;
        frameless.root.clear();
        frameless.turns.clear();
        m.characters[0].now.clip = std::make_shared<const phys::Clip>(std::move(frameless));
      },
      "a clip of no frames");
  refused([](phys::Motion& m) { m.characters[0].frame = phys::Quat(0.0, 0.0, 0.0, 0.0); }, "no frame");
  refused(
      [](phys::Motion& m) {
        phys::Clip other = *m.characters[0].now.clip;
        other.bones[1] = "neck";
        other.name = "necked";
        m.characters[0].reaction.getUp.clip = std::make_shared<const phys::Clip>(std::move(other));
      },
      "a get-up clip of other bones");
}

TEST(Motion, BadMotionIsRefusedAndChangesNothing) {
  phys::World source = mixedWorld();
  stepTimes(source, 10);
  const phys::Motion good = source.motion();
  phys::World fresh = mixedWorld();
  Refusal refused(fresh, good);
  refused([](phys::Motion& m) { m.position.pop_back(); }, "a particle short");
  refused([](phys::Motion& m) { m.previous.emplace_back(0.0); }, "a previous position too many");
  refused([](phys::Motion& m) { m.rigidOrientation.clear(); }, "no orientations");
  refused([](phys::Motion& m) { m.position[3].y = std::numeric_limits<double>::quiet_NaN(); }, "NaN");
  refused([](phys::Motion& m) { m.rigidVelocity[0].x = std::numeric_limits<double>::infinity(); }, "inf");
  refused([](phys::Motion& m) { m.rigidOrientation[0] = phys::Quat(2.0, 0.0, 0.0, 0.0); }, "not unit");
  refused([](phys::Motion& m) { m.time = -1.0; }, "negative time");

  EXPECT_THROW(source.setMotion(good), std::invalid_argument) << "a world that has stepped";
}

TEST(Motion, HashSeesEveryArray) {
  phys::World world = mixedWorld();
  stepTimes(world, 5);
  const phys::Motion m = world.motion();
  const std::uint64_t h = m.hash();
  const std::function<void(phys::Motion&)> changes[] = {
      [](phys::Motion& x) { x.position[0].x += 1e-12; },
      [](phys::Motion& x) { x.previous[0].z += 1e-12; },
      [](phys::Motion& x) { x.rigidPosition[0].y += 1e-12; },
      [](phys::Motion& x) { x.rigidOrientation[0].z += 1e-12; },
      [](phys::Motion& x) { x.rigidVelocity[0].x += 1e-12; },
      [](phys::Motion& x) { x.rigidAngularVelocity[0].y += 1e-12; },
  };
  for (const auto& change : changes) {
    phys::Motion x = m;
    change(x);
    EXPECT_NE(x.hash(), h);
  }
}

}  // namespace
