// Bad input at the library's API, from a program that uses it directly (the scene loader checks
// most of it first): it is refused with std::invalid_argument naming the call, and the world keeps
// what it had.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "character_util.h"
#include "physics/capsule_ragdoll.h"
#include "physics/ragdoll.h"
#include "physics/world.h"

namespace {

using phys::Real;
using phys::Vec3;

// is at for a rigid one.
TEST(ApiInput, CornerPositionRefusesACornerThatDoesNotExist) {
  phys::World w;
  phys::BodyDesc d;
  d.center = Vec3(0.0, 1.0, 0.0);
  const phys::BodyId box = w.addBody(d);
  d.model = phys::BodyModel::Rigid;
  const phys::BodyId rigid = w.addBody(d);
  for (const phys::BodyId id : {box, rigid}) {
    EXPECT_THROW(w.cornerPosition(id, 8), std::invalid_argument);
    EXPECT_THROW(w.cornerPosition(id, -1), std::invalid_argument);
    EXPECT_NEAR(w.cornerPosition(id, 7).y, 1.5, 1e-12);
  }
  EXPECT_THROW(w.cornerPosition(phys::BodyId(2), 0), std::invalid_argument);
}

// is refused.
TEST(ApiInput, APointOfParticlesOrBodiesThatDoNotExistIsRefused) {
  phys::World w;
  w.addParticle({});
  phys::Embedding far = phys::embedParticle(phys::ParticleId(100000));
  EXPECT_THROW(w.position(far), std::invalid_argument);
  EXPECT_THROW(w.position(phys::Embedding{}), std::invalid_argument);  // no particles at all
  EXPECT_THROW(w.position(phys::BodyPoint::embedded(far)), std::invalid_argument);
  EXPECT_THROW(w.carrier(phys::BodyPoint::embedded(far)), std::invalid_argument);
  const phys::BodyPoint onRigid = phys::BodyPoint::onRigid(phys::RigidId(100000), Vec3(0.0));
  EXPECT_THROW(w.position(onRigid), std::invalid_argument);
  EXPECT_THROW(w.carrier(onRigid), std::invalid_argument);
  EXPECT_EQ(w.position(phys::embedParticle(phys::ParticleId(0))), Vec3(0.0));
  EXPECT_EQ(w.carrier(phys::BodyPoint::embedded(phys::embedParticle(phys::ParticleId(0)))), phys::kNoBody);
}

// guard froze the ragdoll in its first step) is refused.
TEST(ApiInput, ACharacterWhoseScaleOverflowsItsRootDriveIsRefused) {
  const auto clip = std::make_shared<phys::Clip>(
      testing_phys::ragdollClip(10, [](const std::string&, Real) { return 0.0; }));
  for (const Real scale : {1e-320, 1e307}) {
    phys::World w;
    testing_phys::rigidRagdoll(w, "r");
    phys::CharacterDesc desc;
    desc.ragdoll = "r";
    desc.playback.clip = clip;
    desc.rootStrength = 0.5;
    desc.scale = scale;
    try {
      w.addCharacter(desc);
      ADD_FAILURE() << "scale " << scale << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("addCharacter: scale"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(w.characters().empty());
    EXPECT_TRUE(w.bodyDrives().empty());
  }
}

// any part is in the world.
TEST(ApiInput, ARagdollRefusedHalfWayAddsNothing) {
  struct Case {
    Real mass, scale, strength, rootStrength;
  };
  const Case cases[] = {
      {7e-307, 1.0, 0.0, 0.0},   // a corners box's particle of the head is representable, the forearm's not
      {3e-305, 1.0, 0.0, 0.0},   // the same of the rigid parts' inertia
      {1e300, 1e-10, 0.0, 0.5},  // the root's drive: mass / scale overflows
      {1e306, 1e5, 0.5, 0.0},    // the joints' drives: mass times scale overflows
  };
  int refused = 0;
  for (const phys::RagdollModel model :
       {phys::RagdollModel::Seed, phys::RagdollModel::Lean, phys::RagdollModel::Rigid}) {
    for (const Case& c : cases) {
      for (const bool capsules : {false, true}) {
        phys::World w;
        phys::BodyDesc box;
        box.center = Vec3(5.0, 1.0, 0.0);
        w.addBody(box);  // something the world had
        phys::RagdollDesc d;
        d.model = model;
        d.hips = Vec3(0.0, 1.0, 0.0);
        d.mass = c.mass;
        d.scale = c.scale;
        d.strength = c.strength;
        d.rootStrength = c.rootStrength;
        try {
          if (capsules)
            phys::addCapsuleRagdoll(w, d);
          else
            phys::addRagdoll(w, d);
        } catch (const std::invalid_argument& e) {
          ++refused;
          EXPECT_NE(std::string(e.what()).find(capsules ? "addCapsuleRagdoll: mass" : "addRagdoll: mass"),
                    std::string::npos)
              << e.what();
          EXPECT_EQ(w.bodies().size(), 1u) << e.what();
          EXPECT_EQ(w.particles().size(), 8u);
          EXPECT_TRUE(w.links().empty() && w.rigidJoints().empty() && w.particleJoints().empty());
          EXPECT_TRUE(w.ignoredCollisions().empty() && w.bodyDrives().empty());
          continue;
        }
        // Taken whole: every part.
        EXPECT_EQ(w.bodies().size(), 1u + (capsules ? phys::kCapsuleParts : phys::kRagdollParts));
      }
    }
  }
  EXPECT_GT(refused, 0);
}

// stages, a body it added would leave the rest of the step reading arrays of the old size.
TEST(ApiInput, TheFreezeCallbackRunsWhenTheStepIsDoneAndMayChangeTheWorld) {
  phys::WorldSettings ws;
  ws.bound = 10.0;
  ws.ground = false;
  phys::World w(ws);
  phys::ParticleDesc fast;
  fast.position = Vec3(9.9, 0.0, 0.0);
  fast.velocity = Vec3(100.0, 0.0, 0.0);  // out of the bound in the first substep
  w.addParticle(fast);
  std::vector<long> seenAt;
  w.setFreezeCallback([&](const phys::FreezeReport&) {
    seenAt.push_back(w.stepCount());
    phys::BodyDesc box;
    box.center = Vec3(0.0, 1.0, 0.0);
    w.addBody(box);
    box.model = phys::BodyModel::Rigid;
    box.center.x = 2.0;
    w.addBody(box);
    w.setFreezeCallback(nullptr);  // a callback may replace itself
  });
  w.step();
  ASSERT_EQ(seenAt.size(), 1u);
  EXPECT_EQ(seenAt[0], 1);  // after the step
  EXPECT_EQ(w.bodies().size(), 2u);
  EXPECT_EQ(w.freezes().size(), 1u);
  for (int i = 0; i < 30; ++i) w.step();
  EXPECT_EQ(w.freezes().size(), 1u);
  for (const Vec3& p : w.particles().position) EXPECT_TRUE(phys::finite(p));
  EXPECT_LT(w.bodyPose(phys::BodyId(1)).center.y, 0.0);  // both fell
  EXPECT_LT(w.bodyPose(phys::BodyId(0)).center.y, 0.0);
}

}  // namespace
