// Bad input at the library's API, from a program that uses it directly (the scene loader checks
// most of it first): it is refused with std::invalid_argument naming the call, and the world keeps
// what it had.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "character_util.h"
#include "physics/capsule_ragdoll.h"
#include "physics/character.h"
#include "physics/collision.h"
#include "physics/islands.h"
#include "physics/metrics.h"
#include "physics/motion.h"
#include "physics/ragdoll.h"
#include "physics/world.h"

namespace {

using phys::Real;
using phys::Vec3;

// A corner index outside 0 to 7 would read past a particle body's corners, or give a point no corner
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

// position and carrier index the particles or the rigid body a point names: one that does not exist
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

// `call` must refuse an id or index that does not exist with std::invalid_argument naming the call, the
// id and how many there are.
void expectNoSuch(const std::function<void()>& call, const std::string& name, const std::string& what,
                  std::size_t id, std::size_t count) {
  try {
    call();
    ADD_FAILURE() << name << " took " << what << " " << id;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), name + ": " + what + " " + std::to_string(id) +
                                         " does not exist (there are " + std::to_string(count) + ")");
  }
}

// Every query and setter that takes an id or an index refuses one that does not exist, naming itself:
// vector::at's bare out_of_range, or a read past the end, told the caller neither.
TEST(ApiInput, EveryCallRefusesAnIdThatDoesNotExistNamingItself) {
  phys::World w;
  phys::BodyDesc d;
  d.center = Vec3(0.0, 1.0, 0.0);
  w.addBody(d);
  d.model = phys::BodyModel::Rigid;
  d.center.x = 2.0;
  const phys::BodyId rigid = w.addBody(d);
  w.addParticle({});
  const std::size_t bodies = w.bodies().size(), particles = w.particles().size();
  const std::size_t rigids = w.rigidBodies().size(), sticks = w.sticks().size();
  ASSERT_EQ(bodies, 2u);
  ASSERT_EQ(particles, 9u);
  const auto body = phys::BodyId(bodies + 3);
  const auto particle = phys::ParticleId(particles + 3);
  const phys::BodyId first(0);
  const Vec3 at(0.0, 1.0, 0.0);

  const std::pair<std::string, std::function<void()>> onBodies[] = {
      {"bodyPose", [&] { (void)w.bodyPose(body); }},
      {"bodyCentre", [&] { (void)w.bodyCentre(body); }},
      {"bodyMass", [&] { (void)w.bodyMass(body); }},
      {"bodyVelocity", [&] { (void)w.bodyVelocity(body); }},
      {"poseVelocity", [&] { (void)w.poseVelocity(body); }},
      {"rigidDescVelocity", [&] { (void)w.rigidDescVelocity(body); }},
      {"cornerPosition", [&] { (void)w.cornerPosition(body, 0); }},
      {"anchor", [&] { (void)w.anchor(body, at); }},
      {"pointOn", [&] { (void)w.pointOn(body, at); }},
      {"dragAt", [&] { (void)w.dragAt(body, at); }},
      {"setDrag",
       [&] {
         phys::Drag drag;
         drag.body = body;
         w.setDrag(drag);
       }},
      {"bodyDrive", [&] { (void)w.bodyDrive(body); }},
      {"bodyDriveLoad", [&] { (void)w.bodyDriveLoad(body); }},
      {"setBodyDrive", [&] { w.setBodyDrive(body, phys::BodyDrive{}); }},
      {"clearBodyDrive", [&] { w.clearBodyDrive(body); }},
      {"push", [&] { w.push(body, Vec3(1.0, 0.0, 0.0), 1.0); }},
      {"ignoreCollision", [&] { w.ignoreCollision(first, body); }},
      {"addJointFriction", [&] { w.addJointFriction(first, body, 1.0); }},
      {"addParticleJoint", [&] { w.addParticleJoint(first, body, at); }},
      {"addParticleJoint",
       [&] {
         phys::ParticleJoint joint;
         joint.a = first;
         joint.b = body;
         w.addParticleJoint(joint);
       }},
      {"particleJointAt", [&] { (void)w.particleJointAt(first, body, at, at); }},
      {"addJoint",
       [&] {
         phys::JointDesc joint;
         joint.a = rigid;
         joint.b = body;
         w.addJoint(joint);
       }},
  };
  for (const auto& [name, call] : onBodies) expectNoSuch(call, name, "body", body, bodies);

  const std::pair<std::string, std::function<void()>> onParticles[] = {
      {"velocity", [&] { (void)w.velocity(particle); }},
      {"particleName", [&] { (void)w.particleName(particle); }},
      {"position", [&] { (void)w.position(phys::embedParticle(particle)); }},
      {"carrier", [&] { (void)w.carrier(phys::BodyPoint::embedded(phys::embedParticle(particle))); }},
      {"addStick", [&] { w.addStick(phys::ParticleId(0), particle); }},
      {"stick", [&] { w.addRange(phys::ParticleId(0), particle, 0.0, 1.0); }},
      {"addLink",
       [&] { w.addLink(phys::embedParticle(phys::ParticleId(0)), phys::embedParticle(particle)); }},
  };
  for (const auto& [name, call] : onParticles) expectNoSuch(call, name, "particle", particle, particles);

  const phys::BodyPoint onRigid = phys::BodyPoint::onRigid(phys::RigidId(rigids + 3), Vec3(0.0));
  for (const auto& [name, call] : std::initializer_list<std::pair<std::string, std::function<void()>>>{
           {"position", [&] { (void)w.position(onRigid); }},
           {"carrier", [&] { (void)w.carrier(onRigid); }},
           {"addLink", [&] { w.addLink(onRigid, w.pointOn(rigid, at)); }},
       })
    expectNoSuch(call, name, "rigid body", rigids + 3, rigids);

  // No joints, particle joints or characters at all: index 0 is one too many.
  const std::pair<std::string, std::function<void()>> onJoints[] = {
      {"jointDesc", [&] { (void)w.jointDesc(0); }},
      {"jointAngle", [&] { (void)w.jointAngle(0); }},
      {"jointDrive", [&] { (void)w.jointDrive(0); }},
      {"jointDriveTorque", [&] { (void)w.jointDriveTorque(0); }},
      {"jointRest", [&] { (void)w.jointRest(0); }},
      {"setJointDrive", [&] { w.setJointDrive(0, phys::JointDrive{}); }},
  };
  for (const auto& [name, call] : onJoints) expectNoSuch(call, name, "joint", 0, 0);
  const std::pair<std::string, std::function<void()>> onParticleJoints[] = {
      {"particleJointDrive", [&] { (void)w.particleJointDrive(0); }},
      {"particleJointDriveTorque", [&] { (void)w.particleJointDriveTorque(0); }},
      {"setParticleJointDrive", [&] { w.setParticleJointDrive(0, phys::JointDrive{}); }},
  };
  for (const auto& [name, call] : onParticleJoints) expectNoSuch(call, name, "particle joint", 0, 0);
  const std::pair<std::string, std::function<void()>> onCharacters[] = {
      {"playClip", [&] { w.playClip(0, phys::Playback{}, 0.0); }},
      {"queueClip", [&] { w.queueClip(0, phys::Playback{}, 0.0, 0.0); }},
      {"setCharacterStrength", [&] { w.setCharacterStrength(0, 1.0, 0.0); }},
      {"setPartStrength", [&] { w.setPartStrength(0, "head", 1.0); }},
      {"setCharacterBalance", [&] { w.setCharacterBalance(0, 0.0); }},
      {"setCharacterReaction", [&] { w.setCharacterReaction(0, phys::Reaction{}); }},
      {"characterMotion", [&] { (void)w.characterMotion(0); }},
      {"setCharacterMotion", [&] { w.setCharacterMotion(0, phys::CharacterMotion{}); }},
      {"trackingError", [&] { (void)phys::trackingError(w, 0); }},
  };
  for (const auto& [name, call] : onCharacters) expectNoSuch(call, name, "character", 0, 0);
  expectNoSuch([&] { (void)phys::bonePivots(w, phys::Character{}, 0); }, "bonePivots", "bone", 0, 0);

  // What was refused changed nothing, and the ids that exist still answer.
  EXPECT_TRUE(w.pushes().empty() && w.bodyDrives().empty() && w.links().empty() && w.rigidLinks().empty());
  EXPECT_EQ(w.sticks().size(), sticks);
  EXPECT_FALSE(w.drag().has_value());
  EXPECT_NEAR(w.bodyPose(first).center.y, 1.0, 1e-12);
  EXPECT_EQ(w.particleName(phys::ParticleId(particles - 1)), "");
}

// world.islands() hands out the islands, whose queries indexed their tables unchecked: an id past the
// end read whatever lay beyond them.
TEST(ApiInput, TheIslandsRefuseAnIdThatDoesNotExistNamingTheCall) {
  phys::World w;
  phys::BodyDesc d;
  d.center = Vec3(0.0, 1.0, 0.0);
  const phys::BodyId box = w.addBody(d);
  w.addParticle({});
  const phys::Islands& islands = w.islands();
  const std::size_t particles = w.particles().size(), bodies = w.bodies().size();
  ASSERT_EQ(particles, 9u);
  const std::size_t nodes = 2;  // the box and the loose particle
  expectNoSuch([&] { (void)islands.particleNode(phys::ParticleId(particles + 3)); }, "particleNode",
               "particle", particles + 3, particles);
  expectNoSuch([&] { (void)islands.bodyNode(phys::BodyId(bodies + 3)); }, "bodyNode", "body", bodies + 3,
               bodies);
  expectNoSuch([&] { (void)islands.asleep(phys::NodeId(nodes + 3)); }, "asleep", "node", nodes + 3, nodes);
  expectNoSuch([&] { (void)islands.bodyAsleep(phys::BodyId(bodies + 3)); }, "bodyAsleep", "body", bodies + 3,
               bodies);
  // The ids that exist still answer.
  EXPECT_EQ(islands.particleNode(phys::ParticleId(0)), islands.bodyNode(box));
  EXPECT_EQ(islands.particleNode(phys::ParticleId(particles - 1)), phys::NodeId(1));
  EXPECT_FALSE(islands.asleep(phys::NodeId(nodes - 1)));
  EXPECT_FALSE(islands.bodyAsleep(box));
}

// `call` must refuse `value` cast from outside an enum of `count` values, naming the call and the value.
void expectNotInEnum(const std::function<void()>& call, const std::string& name, const std::string& what,
                     const std::string& type, int value, int count) {
  try {
    call();
    ADD_FAILURE() << name << " took " << type << " " << value;
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), name + ": " + what + " must be a " + type + ", 0 to " +
                                         std::to_string(count - 1) + " (is " + std::to_string(value) + ")");
  }
}

// A part cast from outside RagdollPart or CapsulePart indexed the parts or the names past their end.
TEST(ApiInput, APartOutsideItsEnumIsRefusedNamingTheCall) {
  const phys::Ragdoll ragdoll;
  const phys::CapsuleRagdoll capsules;
  for (const int value : {40, phys::kRagdollParts, -1}) {
    const auto part = static_cast<phys::RagdollPart>(value);
    expectNotInEnum([&] { (void)ragdoll.part(part); }, "Ragdoll::part", "part", "RagdollPart", value,
                    phys::kRagdollParts);
    expectNotInEnum([&] { (void)phys::toString(part); }, "toString(RagdollPart)", "part", "RagdollPart",
                    value, phys::kRagdollParts);
  }
  for (const int value : {40, phys::kCapsuleParts, -1}) {
    const auto part = static_cast<phys::CapsulePart>(value);
    expectNotInEnum([&] { (void)capsules.part(part); }, "CapsuleRagdoll::part", "part", "CapsulePart", value,
                    phys::kCapsuleParts);
    expectNotInEnum([&] { (void)phys::toString(part); }, "toString(CapsulePart)", "part", "CapsulePart",
                    value, phys::kCapsuleParts);
  }
  EXPECT_EQ(phys::toString(phys::RagdollPart::LowerLegRight), "lower-leg-right");
  EXPECT_EQ(phys::toString(phys::CapsulePart::LowerArmRight), "lower-arm-right");
  EXPECT_EQ(ragdoll.part(phys::RagdollPart::LowerLegRight), phys::BodyId(0));
}

// Every other enum's name: a value cast from outside it was named as one of its values ("rigid",
// "corners", "uniform"), as "?", or read past the end of a table of names.
template <typename Enum>
void expectNameRefused(const std::string& type, const std::string& what, int count) {
  for (const int value : {count, 40, -1}) {
    const auto cast = static_cast<Enum>(value);  // -1 is 255 in Stage's byte
    expectNotInEnum([&] { (void)phys::toString(cast); }, "toString(" + type + ")", what, type,
                    static_cast<int>(cast), count);
  }
}

TEST(ApiInput, AnEnumsNameRefusesAValueOutsideIt) {
  expectNameRefused<phys::RagdollModel>("RagdollModel", "model", 3);
  expectNameRefused<phys::BodyModel>("BodyModel", "model", 3);
  expectNameRefused<phys::Shape>("Shape", "shape", 2);
  expectNameRefused<phys::ContactKind>("ContactKind", "kind", 6);
  expectNameRefused<phys::CharacterState>("CharacterState", "state", 5);
  expectNameRefused<phys::Stage>("Stage", "stage", static_cast<int>(phys::kStageCount));
  expectNameRefused<phys::SolverMethod>("SolverMethod", "method", 4);
  expectNameRefused<phys::GravityMode>("GravityMode", "mode", 2);
  // The last of each still has its name.
  EXPECT_EQ(phys::toString(phys::RagdollModel::Rigid), "rigid");
  EXPECT_EQ(phys::toString(phys::BodyModel::Rigid), "rigid");
  EXPECT_EQ(phys::toString(phys::Shape::Capsule), "capsule");
  EXPECT_EQ(std::string(phys::toString(phys::ContactKind::VertexVertex)), "vertex-vertex");
  EXPECT_EQ(phys::toString(phys::CharacterState::LettingGo), "letting-go");
  EXPECT_EQ(phys::toString(phys::Stage::Islands), "islands");
  EXPECT_EQ(phys::toString(phys::SolverMethod::Shake), "shake");
  EXPECT_EQ(phys::toString(phys::GravityMode::Point), "point");
}

// hingeAngle refuses a bad part or a body the world does not have in its own name: it was refused as
// Ragdoll::part's or bodyPose's, calls the caller never made.
TEST(ApiInput, HingeAngleRefusesABadPartOrBodyNamingItself) {
  phys::World w;
  phys::Ragdoll ragdoll = phys::addRagdoll(w, phys::RagdollDesc{});
  phys::RagdollHinge hinge = ragdoll.hinges[0];
  EXPECT_NO_THROW((void)phys::hingeAngle(w, ragdoll, hinge));
  hinge.parent = static_cast<phys::RagdollPart>(40);
  expectNotInEnum([&] { (void)phys::hingeAngle(w, ragdoll, hinge); }, "hingeAngle", "the hinge's parent",
                  "RagdollPart", 40, phys::kRagdollParts);
  hinge = ragdoll.hinges[0];
  hinge.child = static_cast<phys::RagdollPart>(-1);
  expectNotInEnum([&] { (void)phys::hingeAngle(w, ragdoll, hinge); }, "hingeAngle", "the hinge's child",
                  "RagdollPart", -1, phys::kRagdollParts);
  // A ragdoll of another, larger world.
  const std::size_t bodies = w.bodies().size();
  hinge = ragdoll.hinges[0];
  ragdoll.parts[static_cast<std::size_t>(hinge.child)] = phys::BodyId(bodies + 5);
  expectNoSuch([&] { (void)phys::hingeAngle(w, ragdoll, hinge); }, "hingeAngle", "body", bodies + 5, bodies);
}

// A step count near the largest long would overflow the world's counter as it steps (signed
// overflow): setMotion refuses one over Motion::kMaxSteps and takes that one.
TEST(ApiInput, AMotionWhoseStepCountWouldOverflowIsRefused) {
  phys::World w;
  w.addParticle({});
  phys::Motion m = w.motion();
  for (const long steps : {std::numeric_limits<long>::max(), phys::Motion::kMaxSteps + 1}) {
    m.steps = steps;
    EXPECT_NE(m.problem().find("step count " + std::to_string(steps)), std::string::npos) << m.problem();
    try {
      w.setMotion(m);
      ADD_FAILURE() << "step count " << steps << " was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("setMotion: step count"), std::string::npos) << e.what();
    }
    EXPECT_EQ(w.stepCount(), 0);
  }
  m.steps = phys::Motion::kMaxSteps;
  w.setMotion(m);
  w.step();
  EXPECT_EQ(w.stepCount(), phys::Motion::kMaxSteps + 1);
}

// The root's drive stiffnesses are the ragdoll's mass over and times the scale, and the step gives
// them to the root without setBodyDrive's checks: a scale that overflows one to inf (at 1e-320 the
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

// A ragdoll is added part by part: a part addBody refuses (a mass too small to represent for the
// lighter parts only) or a drive whose stiffness overflows (mass times scale) must be refused before
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

// The guard's callback is called once the step is done, and may change the world: between the step's
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

// A value cast from outside an enum is refused: such a method relaxes no stick at all (boxes collapse
// and the guard freezes them as crushed), a gravity mode pulls as Point mode but is named "uniform",
// a body model is made as a tetra box and a joint kind as a cone.
TEST(ApiInput, ValuesOutsideAnEnumAreRefused) {
  phys::SolverSettings solver;
  solver.method = static_cast<phys::SolverMethod>(9);
  EXPECT_NE(phys::validate(solver).find("method"), std::string::npos);
  phys::World w;
  EXPECT_THROW(w.setSolverSettings(solver), std::invalid_argument);
  EXPECT_EQ(w.solverSettings().method, phys::SolverMethod::GaussSeidel);
  phys::WorldSettings world;
  world.gravityMode = static_cast<phys::GravityMode>(5);
  EXPECT_NE(phys::validate(world).find("gravityMode"), std::string::npos);
  EXPECT_THROW(w.setWorldSettings(world), std::invalid_argument);

  phys::BodyDesc box;
  box.model = static_cast<phys::BodyModel>(7);
  EXPECT_THROW(w.addBody(box), std::invalid_argument);
  box = {};
  box.shape = static_cast<phys::Shape>(7);
  EXPECT_THROW(w.addBody(box), std::invalid_argument);
  EXPECT_TRUE(w.bodies().empty());
  EXPECT_TRUE(w.particles().position.empty());

  box = {};
  box.model = phys::BodyModel::Rigid;
  const phys::BodyId a = w.addBody(box);
  box.center.y = 1.0;
  const phys::BodyId b = w.addBody(box);
  phys::JointDesc joint;
  joint.kind = static_cast<phys::JointKind>(7);
  joint.a = a;
  joint.b = b;
  joint.pivot = Vec3(0.0, 0.5, 0.0);
  joint.axis = Vec3(1.0, 0.0, 0.0);
  joint.reference = Vec3(0.0, -1.0, 0.0);
  joint.swing = 1.0;
  EXPECT_THROW(w.addJoint(joint), std::invalid_argument);
  EXPECT_TRUE(w.rigidJoints().empty());
}

}  // namespace
