// Saving scenes: a stepped world written as XML loads back into the same world (bodies, joints,
// settings), Euler angles come back exactly, and files are replaced atomically or not at all.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "scenes/scene.h"
#include "scenes/scene_writer.h"
#include "unprivileged.h"

namespace {

namespace fs = std::filesystem;
using phys::Vec3;

scenes::Scene reload(const scenes::Scene& scene) {
  return scenes::loadSceneText(scenes::writeSceneXml(scene), "saved.xml");
}

scenes::Scene load(const std::string& body, const std::string& head = "") {
  return scenes::loadSceneText("<scene name=\"t\">" + head + body + "</scene>", "test.xml");
}

// The angle of the rotation taking a to b, accurate for tiny angles too (acos of the dot
// product would round anything below about 1e-8 rad to zero).
double angleBetween(const phys::Quat& a, const phys::Quat& b) {
  const phys::Quat d = glm::inverse(a) * b;
  return 2.0 * std::atan2(glm::length(Vec3(d.x, d.y, d.z)), std::abs(d.w));
}

Vec3 centreVelocity(const phys::World& world, phys::BodyId id) {
  const phys::Body& box = world.bodies()[id];
  Vec3 sum(0.0);
  for (int j = 0; j < box.particleCount; ++j) sum += world.velocity(box.firstParticle + j);
  return sum / static_cast<double>(box.particleCount);
}

void expectSameSettings(const phys::World& a, const phys::World& b, const std::string& what) {
  const phys::WorldSettings& w = a.worldSettings();
  const phys::WorldSettings& v = b.worldSettings();
  EXPECT_EQ(w.gravityMode, v.gravityMode) << what;
  EXPECT_EQ(w.gravity, v.gravity) << what;
  EXPECT_EQ(w.gravityPoint, v.gravityPoint) << what;
  EXPECT_EQ(w.gravityStrength, v.gravityStrength) << what;
  EXPECT_EQ(w.damping, v.damping) << what;
  EXPECT_EQ(w.ground, v.ground) << what;
  // Normalised again on load: a unit vector may come back an ulp off.
  EXPECT_NEAR(glm::length(w.groundNormal - v.groundNormal), 0.0, 1e-15) << what;
  EXPECT_EQ(w.groundHeight, v.groundHeight) << what;
  EXPECT_EQ(w.groundMaterial.staticFriction, v.groundMaterial.staticFriction) << what;
  EXPECT_EQ(w.groundMaterial.dynamicFriction, v.groundMaterial.dynamicFriction) << what;
  EXPECT_EQ(w.bound, v.bound) << what;
  const phys::SolverSettings& s = a.solverSettings();
  const phys::SolverSettings& t = b.solverSettings();
  EXPECT_EQ(s.method, t.method) << what;
  EXPECT_EQ(s.dt, t.dt) << what;
  EXPECT_EQ(s.substeps, t.substeps) << what;
  EXPECT_EQ(s.iterations, t.iterations) << what;
  EXPECT_EQ(s.featureEpsilon, t.featureEpsilon) << what;
  EXPECT_EQ(s.contactSlop, t.contactSlop) << what;
  EXPECT_EQ(s.bodyDamping, t.bodyDamping) << what;
  EXPECT_EQ(s.keepSpin, t.keepSpin) << what;
  EXPECT_EQ(s.restitution, t.restitution) << what;
  EXPECT_EQ(s.compliance, t.compliance) << what;
  EXPECT_EQ(s.maxDepenetrationSpeed, t.maxDepenetrationSpeed) << what;
}

void expectSameCounts(const phys::World& a, const phys::World& b, const std::string& what) {
  EXPECT_EQ(a.bodies().size(), b.bodies().size()) << what;
  EXPECT_EQ(a.particles().size(), b.particles().size()) << what;
  EXPECT_EQ(a.sticks().size(), b.sticks().size()) << what;
  EXPECT_EQ(a.links().size(), b.links().size()) << what;
  EXPECT_EQ(a.rigidLinks().size(), b.rigidLinks().size()) << what;
  EXPECT_EQ(a.rigidJoints().size(), b.rigidJoints().size()) << what;
  EXPECT_EQ(a.ignoredCollisions(), b.ignoredCollisions()) << what;
}

TEST(SceneWriter, SteppedRagdollReloadsAsTheSameWorld) {
  scenes::Scene original = scenes::loadSceneFile(DATA_DIR "/assets/scenes/ragdoll.xml");
  for (int i = 0; i < 90; ++i) original.world.step();  // 1.5 s: landed and tumbling
  scenes::Scene copy = reload(original);
  const phys::World& a = original.world;
  const phys::World& b = copy.world;

  expectSameCounts(a, b, "ragdoll");
  EXPECT_EQ(a.ignoredCollisions().size(), 9u);
  expectSameSettings(a, b, "ragdoll");
  EXPECT_EQ(copy.name, original.name);
  EXPECT_EQ(copy.description, original.description);
  for (phys::BodyId id{}; id < a.bodies().size(); ++id) {
    EXPECT_EQ(b.bodies()[id].name, a.bodies()[id].name);
    const phys::BodyPose pa = a.bodyPose(id), pb = b.bodyPose(id);
    EXPECT_LT(glm::length(pa.center - pb.center), 1e-3) << a.bodies()[id].name;
    EXPECT_LT(angleBetween(pa.orientation, pb.orientation), 1e-3) << a.bodies()[id].name;
    EXPECT_LT(glm::length(centreVelocity(a, id) - centreVelocity(b, id)), 1e-2) << a.bodies()[id].name;
  }
  // Spin too: each particle moves as it did, less what deformation the rigid fit drops.
  for (phys::ParticleId i{}; i < a.particles().size(); ++i) {
    EXPECT_LT(glm::length(a.velocity(i) - b.velocity(i)), 1e-2) << "particle " << i;
  }
  for (std::size_t k = 0; k < a.links().size(); ++k) {
    EXPECT_EQ(a.links()[k].minLength, b.links()[k].minLength);
    EXPECT_EQ(a.links()[k].maxLength, b.links()[k].maxLength);
    EXPECT_LT(glm::length(a.position(a.links()[k].a) - b.position(b.links()[k].a)), 1e-3) << "link " << k;
    EXPECT_LT(glm::length(a.position(a.links()[k].b) - b.position(b.links()[k].b)), 1e-3) << "link " << k;
  }

  for (int i = 0; i < 30; ++i) {
    original.world.step();
    copy.world.step();
  }
  for (phys::BodyId id{}; id < a.bodies().size(); ++id) {
    EXPECT_LT(glm::length(a.bodyPose(id).center - b.bodyPose(id).center), 0.01) << a.bodies()[id].name;
  }
}

// A ragdoll of rigid parts is saved as rigid boxes, <joint>s and <no-collision>s; each joint with
// both parts' frames as they are, so that a hinge saved at an angle reloads at that angle (with
// the parent's frame alone, the child's angle would become the new zero and the stops would move).
TEST(SceneWriter, RigidRagdollReloadsWithItsJointsAsTheyAre) {
  scenes::Scene original = load(
      "<ragdoll name=\"r\" pos=\"0 2.5 0\" euler=\"70 20 10\" model=\"rigid\" "
      "joint-damping=\"3\" inertia-floor=\"0.4\"/><box name=\"hung\" pos=\"3 1 0\" model=\"rigid\" "
      "size=\"0.2 1 0.2\" inertia-floor=\"0.3\"/>"
      "<particle name=\"nail\" pos=\"3 1.5 0\" pinned=\"true\"/>"
      "<link a=\"nail\" b=\"hung\" point=\"3 1.5 0\"/>",
      "<solver substeps=\"16\" iterations=\"2\"/>");
  for (int i = 0; i < 90; ++i) original.world.step();  // landed, hinges turned
  scenes::Scene copy = reload(original);
  const phys::World& a = original.world;
  const phys::World& b = copy.world;
  expectSameCounts(a, b, "rigid ragdoll");
  ASSERT_EQ(b.rigidJoints().size(), 9u);
  ASSERT_EQ(b.rigidLinks().size(), 1u);
  EXPECT_EQ(b.particles().size(), 1u);
  for (std::size_t k = 0; k < a.rigidJoints().size(); ++k) {
    const phys::JointDesc x = a.jointDesc(k), y = b.jointDesc(k);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.a, y.a);
    EXPECT_EQ(x.b, y.b);
    EXPECT_NEAR(a.jointAngle(k), b.jointAngle(k), 1e-9) << "joint " << k;
    EXPECT_LT(glm::length(x.pivotB - y.pivotB), 1e-9) << "joint " << k;
    EXPECT_NEAR(x.minAngle, y.minAngle, 1e-12);
    EXPECT_NEAR(x.maxAngle, y.maxAngle, 1e-12);
    EXPECT_EQ(y.damping, 3.0);
  }
  EXPECT_LT(glm::length(a.position(a.rigidLinks()[0].b) - b.position(b.rigidLinks()[0].b)), 1e-9);
  // Each part's inertia floor comes back (the ragdoll's 0.4, the box's own 0.3), and with it the
  // same inertia.
  for (phys::BodyId id{}; id < a.bodies().size(); ++id) {
    const phys::Body &x = a.bodies()[id], &y = b.bodies()[id];
    EXPECT_EQ(y.inertiaFloor, x.name == "hung" ? 0.3 : 0.4) << x.name;
    EXPECT_EQ(a.rigidBodies().inverseInertia[x.rigid], b.rigidBodies().inverseInertia[y.rigid]) << x.name;
  }
  for (int i = 0; i < 30; ++i) {
    original.world.step();
    copy.world.step();
  }
  for (phys::BodyId id{}; id < a.bodies().size(); ++id) {
    EXPECT_LT(glm::length(a.bodyPose(id).center - b.bodyPose(id).center), 0.01) << a.bodies()[id].name;
  }
}

// Drives come back as they were: a ragdoll's strength and stiffness on each joint, and a joint's
// own target away from its rest (a <joint> with drive-target), which a reloaded world pulls towards.
TEST(SceneWriter, JointDrivesReloadAsTheyWere) {
  scenes::Scene original = load(
      "<ragdoll name=\"r\" pos=\"0 0.85 0\" model=\"rigid\" strength=\"0.7\" drive-stiffness=\"800\" "
      "root-strength=\"0.6\"/>"
      "<box name=\"p\" pos=\"3 1 0\" model=\"rigid\"/><box name=\"c\" pos=\"3 2 0\" model=\"rigid\"/>"
      "<joint type=\"cone\" a=\"p\" b=\"c\" pivot=\"3 1.5 0\" axis=\"0 1 0\" reference=\"1 0 0\" "
      "swing=\"60\" "
      "strength=\"0.9\" drive-target=\"20 -10 5\"/>"
      "<body-drive body=\"p\" pos=\"3 1.2 0\" euler=\"0 30 0\" strength=\"0.8\" stiffness=\"500\"/>",
      "<solver substeps=\"8\" iterations=\"2\"/>");
  for (int i = 0; i < 30; ++i) original.world.step();
  scenes::Scene copy = reload(original);
  const phys::World& a = original.world;
  const phys::World& b = copy.world;
  ASSERT_EQ(b.rigidJoints().size(), 10u);
  for (std::size_t k = 0; k < a.rigidJoints().size(); ++k) {
    const phys::JointDrive x = a.jointDrive(k), y = b.jointDrive(k);
    EXPECT_EQ(y.strength, k < 9 ? 0.7 : 0.9) << "joint " << k;
    EXPECT_EQ(y.stiffness, k < 9 ? 800.0 : phys::kDriveStiffness) << "joint " << k;
    EXPECT_LT(angleBetween(x.target, y.target), 1e-12) << "joint " << k;
  }
  // The cone's target is the one the file gave, not its rest.
  const phys::Quat given =
      glm::angleAxis(glm::radians(5.0), phys::Vec3(0.0, 0.0, 1.0)) *
      glm::angleAxis(glm::radians(-10.0), phys::Vec3(0.0, 1.0, 0.0)) *
      glm::angleAxis(glm::radians(20.0), phys::Vec3(1.0, 0.0, 0.0));  // x, then y, then z
  EXPECT_LT(angleBetween(b.jointDrive(9).target, given), 1e-12);
  EXPECT_GT(angleBetween(b.jointDrive(9).target, b.jointRest(9)), 0.3);
  // The hands of god: the ragdoll's on its torso, where it was made, and the box's as the file gave it.
  ASSERT_EQ(b.bodyDrives().size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const phys::DrivenBody &x = a.bodyDrives()[k], &y = b.bodyDrives()[k];
    EXPECT_EQ(b.bodies()[b.rigidBodies().body[y.rigid]].name, k == 0 ? "r.torso" : "p");
    EXPECT_LT(glm::length(x.drive.position - y.drive.position), 1e-12);
    EXPECT_LT(angleBetween(x.drive.orientation, y.drive.orientation), 1e-12);
    EXPECT_EQ(y.drive.strength, k == 0 ? 0.6 : 0.8);
    EXPECT_EQ(y.drive.stiffness, k == 0 ? phys::kBodyDriveStiffness : 500.0);
    EXPECT_EQ(y.drive.angularStiffness, x.drive.angularStiffness);
  }
  EXPECT_LT(glm::length(b.bodyDrives()[1].drive.position - phys::Vec3(3.0, 1.2, 0.0)), 1e-12);
}

TEST(SceneWriter, EveryProjectSceneRoundTrips) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(scenes::sceneDirectory(DATA_DIR))) {
    if (entry.path().extension() != ".xml") continue;
    ++count;
    const std::string what = entry.path().filename().string();
    scenes::Scene original = scenes::loadSceneFile(entry.path());
    for (int i = 0; i < 60; ++i) original.world.step();
    scenes::Scene copy = reload(original);  // throws, and fails the test, if the text does not load
    expectSameCounts(original.world, copy.world, what);
    expectSameSettings(original.world, copy.world, what);
    EXPECT_EQ(copy.camera.eye, original.camera.eye) << what;
    EXPECT_EQ(copy.camera.target, original.camera.target) << what;
    for (phys::BodyId id{}; id < original.world.bodies().size(); ++id) {
      EXPECT_LT(glm::length(original.world.bodyPose(id).center - copy.world.bodyPose(id).center), 1e-3)
          << what;
    }
    for (std::size_t i = 0; i < original.world.particles().size(); ++i) {
      if (original.world.particles().inverseMass[i] == 0.0) {
        EXPECT_EQ(copy.world.particles().inverseMass[i], 0.0)
            << what << ": particle " << i << " stays pinned";
      }
    }
  }
  EXPECT_GE(count, 6);
}

TEST(SceneWriter, SpinningBoxKeepsItsParticlesMotion) {
  // In free flight, with body damping removing its vibration, a spinning box is stretched only by
  // what the passes leave (about 1e-4 m and 3e-4 m/s here), which the rigid fit drops; its
  // particles otherwise come back where they were and moving as they were (up to 4 m/s here: a
  // wrong spin would be off by metres per second).
  for (const char* model : {"corners", "tetra"}) {
    scenes::Scene original =
        load(std::string("<box pos=\"0 5 0\" size=\"1 0.5 2\" euler=\"10 20 30\" model=\"") + model +
                 "\" velocity=\"1 2 -3\" angular-velocity=\"100 -200 50\" mass=\"3\"/>",
             "<solver body-damping=\"1\" substeps=\"2\"/>");
    for (int i = 0; i < 30; ++i) original.world.step();
    const scenes::Scene copy = reload(original);
    const phys::World& a = original.world;
    const phys::World& b = copy.world;
    for (phys::ParticleId i{}; i < a.particles().size(); ++i) {
      EXPECT_LT(glm::length(a.particles().position[i] - b.particles().position[i]), 1e-3)
          << model << " " << i;
      EXPECT_LT(glm::length(a.velocity(i) - b.velocity(i)), 2e-3) << model << " " << i;
      EXPECT_NEAR(b.particles().inverseMass[i], a.particles().inverseMass[i], 1e-12) << model << " " << i;
    }
  }
}

TEST(SceneWriter, LooseParticlesKeepTheirVerletStateToRoundOff) {
  // Point gravity, so the velocity written depends on where each particle is.
  scenes::Scene original = load(
      "<particle name=\"pivot\" pos=\"0 3 0\" pinned=\"true\"/>"
      "<particle name=\"bob\" pos=\"1.3 3 0.2\" mass=\"0.7\" velocity=\"0.1 0 2\"/>"
      "<particle pos=\"-2 1 0\"/><particle pos=\"-2 2 0\" mass=\"3\"/>"
      "<stick a=\"pivot\" b=\"bob\" compliance=\"0.001\"/>",
      "<world gravity-mode=\"point\" gravity-point=\"0 -10 0\"/><solver method=\"xpbd\" substeps=\"3\"/>");
  for (int i = 0; i < 17; ++i) original.world.step();
  const scenes::Scene copy = reload(original);
  const phys::World& a = original.world;
  const phys::World& b = copy.world;
  expectSameCounts(a, b, "particles");
  for (phys::ParticleId i{}; i < a.particles().size(); ++i) {
    EXPECT_EQ(a.particles().position[i], b.particles().position[i]) << i;
    EXPECT_LT(glm::length(a.velocity(i) - b.velocity(i)), 1e-12) << i;
    EXPECT_NEAR(a.particles().inverseMass[i], b.particles().inverseMass[i], 1e-15) << i;
  }
  EXPECT_EQ(b.sticks()[0].minLength, a.sticks()[0].minLength);
  EXPECT_EQ(b.sticks()[0].compliance, 0.001);
}

TEST(SceneWriter, SticksRangesLinksAndCollisionGroupsRoundTrip) {
  scenes::Scene original = load(
      "<particle name=\"p\" pos=\"0 3 0\"/><particle name=\"q\" pos=\"1 3 0\"/><particle name=\"r\" pos=\"0 "
      "4 0\"/>"
      "<stick a=\"p\" b=\"q\" min=\"0.5\" max=\"2\"/><stick a=\"p\" b=\"r\" min=\"0.5\"/>"
      "<stick a=\"q\" b=\"r\" max=\"3\"/><stick a=\"r\" b=\"q\" min=\"0\"/>"
      "<box name=\"A\" pos=\"3 1 0\" model=\"tetra\" group=\"2\" mask=\"4294967293\"/>"
      "<box name=\"B\" pos=\"3 2.5 0\" euler=\"10 20 30\"/>"
      "<link a=\"A\" b=\"B\" point=\"3 1.75 0\"/>"
      "<link a=\"A\" b=\"B\" a-point=\"3.5 1 0\" b-point=\"3.5 2.5 0\" min=\"0.2\" max=\"2\"/>"
      "<link a=\"q\" b=\"B\" point=\"3 3 0\"/>"
      "<no-collision a=\"B\" b=\"A\"/>",
      "<ground/>");
  for (int i = 0; i < 20; ++i) original.world.step();
  const scenes::Scene copy = reload(original);
  const phys::World& a = original.world;
  const phys::World& b = copy.world;
  expectSameCounts(a, b, "joints");
  // Written in the order the world made them, every stick keeps its index. The boxes' bracing
  // is rebuilt at the rigid pose, so its rest lengths come back to round-off only.
  for (std::size_t k = 0; k < a.sticks().size(); ++k) {
    EXPECT_EQ(a.sticks()[k].a, b.sticks()[k].a) << k;
    EXPECT_EQ(a.sticks()[k].b, b.sticks()[k].b) << k;
    EXPECT_NEAR(a.sticks()[k].minLength, b.sticks()[k].minLength, 1e-12) << k;
    EXPECT_EQ(a.sticks()[k].maxLength == phys::kNoMaxLength, b.sticks()[k].maxLength == phys::kNoMaxLength)
        << k;
    if (std::isfinite(a.sticks()[k].maxLength)) {
      EXPECT_NEAR(a.sticks()[k].maxLength, b.sticks()[k].maxLength, 1e-12) << k;
    }
  }
  for (std::size_t k = 0; k < 4; ++k) {  // the loose ones exactly
    EXPECT_EQ(a.sticks()[k].minLength, b.sticks()[k].minLength) << k;
    EXPECT_EQ(a.sticks()[k].maxLength, b.sticks()[k].maxLength) << k;
  }
  ASSERT_EQ(b.links().size(), 3u);
  EXPECT_TRUE(b.links()[0].isPin());
  EXPECT_EQ(b.links()[1].minLength, 0.2);
  EXPECT_EQ(b.links()[1].maxLength, 2.0);
  EXPECT_EQ(b.links()[2].a.count, 1);  // the particle is its own end
  EXPECT_EQ(b.links()[2].a.particle[0], a.links()[2].a.particle[0]);
  EXPECT_EQ(b.bodies()[0].collisionGroup, 2u);
  EXPECT_EQ(b.bodies()[0].collisionMask, 0xfffffffdu);
  EXPECT_EQ(b.bodies()[1].collisionGroup, 1u);
  EXPECT_EQ(b.bodies()[0].model, phys::BodyModel::Tetra);
}

// A pin whose two ends are apart was saved as one midpoint: two boxes pinned 2 m apart were
// 1.08 m from where they should be one step after the reload. Both ends are now saved where
// they are, so the reloaded world steps as the saved one does (to round-off: the reloaded boxes
// are rebuilt rigid at their fitted poses, which these, unstepped, already are).
TEST(SceneWriter, APinWhoseEndsAreApartStepsTheSameAfterReload) {
  for (const char* ends : {"a-point=\"0 1 0\" b-point=\"2 1 0\"",  // two boxes 2 m apart
                           "a-point=\"0.5 1 0\" b-point=\"1.5 1 0\""}) {
    scenes::Scene original =
        load(std::string("<box name=\"A\" pos=\"0 1 0\"/><box name=\"B\" pos=\"2 1 0\"/>") +
                 "<particle name=\"p\" pos=\"0 4 0\"/><link a=\"p\" b=\"B\" a-point=\"0 5 0\" "
                 "b-point=\"2 1.5 0\"/><link a=\"A\" b=\"B\" " +
                 ends + "/>",
             "<world gravity=\"0 0 0\"/>");
    scenes::Scene copy = reload(original);
    ASSERT_EQ(copy.world.links().size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_TRUE(copy.world.links()[k].isPin());
      EXPECT_NEAR(glm::length(copy.world.position(copy.world.links()[k].a) -
                              original.world.position(original.world.links()[k].a)),
                  0.0, 1e-12);
      EXPECT_NEAR(glm::length(copy.world.position(copy.world.links()[k].b) -
                              original.world.position(original.world.links()[k].b)),
                  0.0, 1e-12);
    }
    original.world.step();
    copy.world.step();
    for (std::size_t i = 0; i < original.world.particles().size(); ++i) {
      EXPECT_NEAR(glm::length(original.world.particles().position[i] - copy.world.particles().position[i]),
                  0.0, 1e-9)
          << ends << ", particle " << i;
    }
  }
}

TEST(SceneWriter, EveryBoxGetsAUniqueName) {
  scenes::Scene scene = load("<particle name=\"box 1\" pos=\"0 9 0\"/>");
  phys::BodyDesc box;
  box.center = Vec3(0.0, 1.0, 0.0);
  scene.world.addBody(box);  // unnamed: becomes "box 0"
  box.name = "twin";
  scene.world.addBody(box);
  scene.world.addBody(box);  // a second "twin": the first keeps the name
  box.name = "";
  scene.world.addBody(box);  // "box 3"
  box.name = "box 0";
  scene.world.addBody(box);  // takes "box 0" before the unnamed one is named, which then needs another
  const scenes::Scene copy = reload(scene);
  ASSERT_EQ(copy.world.bodies().size(), 5u);
  EXPECT_EQ(copy.world.bodies()[1].name, "twin");
  EXPECT_EQ(copy.world.bodies()[2].name, "box 2");
  EXPECT_EQ(copy.world.bodies()[3].name, "box 3");
  EXPECT_EQ(copy.world.bodies()[4].name, "box 0");
  EXPECT_EQ(copy.world.bodies()[0].name, "box 0 (2)");
  EXPECT_EQ(copy.world.particleName(phys::ParticleId{0}), "box 1");
}

// An '&' among them is written as &amp; (the loader refuses one that starts no reference).
TEST(SceneWriter, NamesWithMarkupAndLineBreaksComeBackUnchanged) {
  scenes::Scene scene = load("");
  scene.name = "R&D &amp";
  scene.description = "a \"quoted\" <tag> & \t tab &#10";
  phys::BodyDesc box;
  box.name = "odd & <name> \"x\"\n'y' &";
  scene.world.addBody(box);
  const scenes::Scene copy = reload(scene);
  EXPECT_EQ(copy.name, scene.name);
  EXPECT_EQ(copy.description, scene.description);
  EXPECT_EQ(copy.world.bodies()[0].name, box.name);
}

// The loader refuses a '<' in a value as XML does, so every name the writer puts in one, where a
// body is made and where another element names it, must be escaped: a file written with a markup
// name loads back with the same names and links.
TEST(SceneWriter, MarkupInNamesIsEscapedWhereverANameIsWritten) {
  const std::string p = "p<&\"'", q = "<q>", a = "a < b & \"c\" 'd'", b = "<b";
  const scenes::Scene scene = load(
      "<particle name='p&lt;&amp;&quot;&apos;' pos='0 1 0'/><particle name='&lt;q>' pos='0 2 0'/>"
      "<stick a='p&lt;&amp;&quot;&apos;' b='&lt;q>'/>"
      "<box name='a &lt; b &amp; \"c\" &apos;d&apos;' pos='0 5 0'/><box name=\"&lt;b\" pos='2 5 0'/>"
      "<link a=\"a &lt; b &amp; &quot;c&quot; 'd'\" b='&lt;b' point='1 5 0'/>"
      "<no-collision a='&lt;b' b='a &lt; b &amp; \"c\" &apos;d&apos;'/>");
  ASSERT_EQ(scene.bodies.size(), 4u);
  EXPECT_EQ(scene.bodies[0].name, p);
  EXPECT_EQ(scene.bodies[1].name, q);
  EXPECT_EQ(scene.bodies[2].name, a);
  EXPECT_EQ(scene.bodies[3].name, b);
  const std::string xml = scenes::writeSceneXml(scene);
  EXPECT_NE(xml.find("&lt;"), std::string::npos) << xml;
  const scenes::Scene copy = scenes::loadSceneText(xml, "saved.xml");
  ASSERT_EQ(copy.bodies.size(), scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) EXPECT_EQ(copy.bodies[i].name, scene.bodies[i].name);
  EXPECT_EQ(copy.world.sticks().size(), scene.world.sticks().size());
  EXPECT_EQ(copy.world.links().size(), 1u);
  EXPECT_EQ(copy.world.ignoredCollisions(), scene.world.ignoredCollisions());
}

// A description is one line (the loader refuses a line break in it): not written, rather than
// written into a file that does not load.
TEST(SceneWriter, ADescriptionOfTwoLinesIsRefused) {
  scenes::Scene scene = load("");
  scene.description = "two\nlines";
  EXPECT_THROW(scenes::writeSceneXml(scene), std::invalid_argument);
}

// A name from outside a scene file (a body named through the API, a clip file found beside
// another) may hold a control character the loader refuses, C0 or C1: not written, rather than
// written into a file that does not load, in the loader's words. A no-break space (U+00A0, the
// first character past them) is written and reads back.
TEST(SceneWriter, AControlCharacterTheLoaderRefusesIsNotWritten) {
  for (const char* name : {"red\x1b[31m",
                           "red\xc2\x9b"
                           "31m"}) {
    scenes::Scene scene = load("");
    phys::BodyDesc box;
    box.name = name;
    scene.world.addBody(box);
    try {
      scenes::writeSceneXml(scene);
      ADD_FAILURE() << "written: " << name;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("holds the control character"), std::string::npos) << what;
      EXPECT_NE(what.find("which no scene file can hold"), std::string::npos) << what;
    }
  }
  scenes::Scene scene = load("");
  phys::BodyDesc box;
  box.name =
      "no\xc2\xa0"
      "break";  // split: "\xa0b" would read as one escape
  scene.world.addBody(box);
  EXPECT_EQ(reload(scene).world.bodies()[0].name, box.name);
}

TEST(SceneWriter, CameraIsTheOneGivenAndReadsBackAsTheSameFloats) {
  const scenes::Scene scene = load("", "<camera eye=\"1 2 3\" target=\"0 0 0\"/>");
  const scenes::CameraStart user{glm::vec3(0.1f, -7.3f, 1e-7f), glm::vec3(1.0f / 3.0f, 2.0f, 1234.567f)};
  const scenes::Scene copy = scenes::loadSceneText(scenes::writeSceneXml(scene, user), "saved.xml");
  EXPECT_EQ(copy.camera.eye, user.eye);
  EXPECT_EQ(copy.camera.target, user.target);
  EXPECT_EQ(reload(scene).camera.eye, glm::vec3(1, 2, 3));  // without one, the scene's own
}

// A scene without a <camera> is written without one: the sandbox's default view is not the scene's,
// and need not be within a world bound nearer than it (found by the scene fuzzer).
TEST(SceneWriter, NoCameraGivenNoCameraWritten) {
  const scenes::Scene scene = load("<box pos=\"0 1 0\"/>", "<world bound=\"5\"/>");
  ASSERT_FALSE(scene.camera.given);
  ASSERT_GT(scene.camera.eye.z, 5.0f);  // the default view, beyond the bound
  const std::string xml = scenes::writeSceneXml(scene);
  EXPECT_EQ(xml.find("<camera"), std::string::npos) << xml;
  const scenes::Scene copy = scenes::loadSceneText(xml, "saved.xml");
  EXPECT_FALSE(copy.camera.given);
  EXPECT_EQ(copy.camera.eye, scene.camera.eye);
  // A camera passed in is the user's view, and written.
  const scenes::CameraStart view{glm::vec3(1.0f, 2.0f, 3.0f), glm::vec3(0.0f)};
  EXPECT_TRUE(scenes::loadSceneText(scenes::writeSceneXml(scene, view), "view.xml").camera.given);
}

// The <box euler="..."> a world's box is written with.
Vec3 writtenEuler(const scenes::Scene& scene) {
  const std::string xml = scenes::writeSceneXml(scene);
  std::smatch m;
  const std::regex euler("euler=\"(\\S+) (\\S+) (\\S+)\"");
  if (!std::regex_search(xml, m, euler)) return Vec3(NAN);
  return Vec3(std::stod(m[1]), std::stod(m[2]), std::stod(m[3]));
}

TEST(SceneWriter, EulerAnglesReadBackAsTheSameOrientation) {
  const scenes::Scene scene = load("<box pos=\"0 0 0\" euler=\"30 -50 170\"/>");
  // In range (y within +-90, x and z within +-180) the angles are unique, so they come back.
  const Vec3 euler = writtenEuler(scene);
  EXPECT_NEAR(euler.x, 30.0, 1e-9);
  EXPECT_NEAR(euler.y, -50.0, 1e-9);
  EXPECT_NEAR(euler.z, 170.0, 1e-9);
  EXPECT_LT(angleBetween(reload(scene).world.bodyPose(phys::BodyId{0}).orientation,
                         scene.world.bodyPose(phys::BodyId{0}).orientation),
            1e-9);

  // Out of range and at or near gimbal lock the angles differ, but the orientation does not.
  for (const char* angles : {"200 100 -300", "10 90 20", "-40 -90 70", "5 89.999999 -5", "0 0 180", "180 0 0",
                             "-179.9 45 179.9", "123 -89.9999999 321"}) {
    const scenes::Scene s = load(std::string("<box pos=\"1 2 3\" size=\"1 2 3\" euler=\"") + angles + "\"/>");
    const Vec3 e = writtenEuler(s);
    EXPECT_LE(std::abs(e.y), 90.0) << angles;
    EXPECT_LE(std::abs(e.x), 180.0) << angles;
    EXPECT_LE(std::abs(e.z), 180.0) << angles;
    EXPECT_LT(angleBetween(reload(s).world.bodyPose(phys::BodyId{0}).orientation,
                           s.world.bodyPose(phys::BodyId{0}).orientation),
              1e-9)
        << angles;
  }
}

TEST(SceneWriter, EulerAnglesTurnAboutWorldXThenYThenZ) {
  // Local +y turned 90 degrees about x points along +z; then 90 about y takes +z to +x. Taken in
  // the other order (y first) it would end along +z.
  const scenes::Scene s = load("<box pos=\"0 0 0\" euler=\"90 90 0\"/>");
  const Vec3 up = s.world.bodyPose(phys::BodyId{0}).orientation * Vec3(0.0, 1.0, 0.0);
  EXPECT_LT(glm::length(up - Vec3(1.0, 0.0, 0.0)), 1e-12);
  EXPECT_LT(glm::length(writtenEuler(s) - Vec3(90.0, 90.0, 0.0)), 1e-6);  // at gimbal lock: x + z kept
}

TEST(SceneWriter, UnrepresentableWorldIsRefusedByName) {
  scenes::Scene scene = load("<particle name=\"p\" pos=\"0 3 0\"/><box pos=\"0 1 0\"/>");
  scene.world.addStick(phys::ParticleId{0},
                       phys::ParticleId{1});  // from a loose particle to a box's corner: no element says that
  EXPECT_THROW(scenes::writeSceneXml(scene), std::invalid_argument);
}

// What saves must load: the loader holds positions and the camera to the world's bound, so the
// writer refuses, with a message, a world whose bound was lowered under a body at run time, or
// a camera flown beyond it, instead of writing a file that would not reload.
TEST(SceneWriter, WhatTheLoaderWouldRefuseIsNotWritten) {
  auto refusal = [](const scenes::Scene& scene, const scenes::CameraStart& camera) {
    try {
      scenes::writeSceneXml(scene, camera);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  scenes::Scene scene = load("<box name=\"far\" pos=\"0 1 50\"/>");
  EXPECT_EQ(refusal(scene, scene.camera), "");
  phys::WorldSettings smaller = scene.world.worldSettings();
  smaller.bound = 20.0;
  scene.world.setWorldSettings(smaller);
  EXPECT_NE(refusal(scene, scene.camera).find("box 0 'far' is beyond the world's bound of 20 m"),
            std::string::npos);
  // A rigid body too: it has no particles, its centre is what the file places.
  scenes::Scene rigid = load("<box name=\"crate\" pos=\"0 1 50\" model=\"rigid\"/>");
  rigid.world.setWorldSettings(smaller);
  EXPECT_NE(refusal(rigid, rigid.camera).find("box 0 'crate' is beyond the world's bound of 20 m"),
            std::string::npos);
  // A link's end is a point on its body, and may lie beyond the bound while the body does not (a
  // body the guard froze stretched, found by the fuzzer): saved where it is, it would not reload.
  scenes::Scene linked = load(
      "<box name=\"a\" pos=\"0 1 9\"/><box name=\"b\" pos=\"0 1 7\"/>"
      "<link a=\"a\" b=\"b\" a-point=\"0 1 9.9\" b-point=\"0 1 7.9\"/>",
      "<world bound=\"10\"/>");
  EXPECT_EQ(refusal(linked, linked.camera), "");
  phys::WorldSettings under = linked.world.worldSettings();
  under.bound = 9.7;
  linked.world.setWorldSettings(under);
  const std::string pastTheEnd = refusal(linked, linked.camera);
  EXPECT_NE(pastTheEnd.find("the end of the link from 'a' to 'b' on 'a' lies at (0, 1, 9.9), beyond the "
                            "world's bound of 9.7 m, which no scene file can hold"),
            std::string::npos)
      << pastTheEnd;
  scenes::Scene near = load("<box name=\"near\" pos=\"0 1 0\"/>", "<world bound=\"20\"/>");
  scenes::CameraStart flown = near.camera;
  flown.eye.z = 30.0f;
  EXPECT_NE(refusal(near, flown).find("the camera is beyond the world's bound of 20 m"), std::string::npos);
  flown.eye.z = 19.0f;
  EXPECT_NO_THROW(scenes::loadSceneText(scenes::writeSceneXml(near, flown), "near.xml"));
  // A character's clip frame, which each change of clip moves on to where its parts are: the
  // loader holds it to the bound too.
  scenes::Scene acting = load(
      "<ragdoll name=\"r\" pos=\"0 1 0\" model=\"rigid\"/><character ragdoll=\"r\" "
      "clip=\"" DATA_DIR "/assets/clips/run.bvh\"/>",
      "<world bound=\"20\"/>");
  phys::CharacterMotion motion = acting.world.characterMotion(0);
  motion.origin = phys::Vec3(0.0, 0.0, 21.0);
  acting.world.setCharacterMotion(0, motion);
  EXPECT_NE(refusal(acting, acting.camera).find("the clip frame of character 'r' lies at (0, 0, 21), beyond"),
            std::string::npos)
      << refusal(acting, acting.camera);
  // The physics takes any bound; a file holds at most 1e9 m (found by the soak test).
  phys::WorldSettings wider = near.world.worldSettings();
  wider.bound = 4.5e229;
  near.world.setWorldSettings(wider);
  EXPECT_NE(refusal(near, near.camera).find("bound of 4.5e+229 m is larger than a scene file holds"),
            std::string::npos)
      << refusal(near, near.camera);
  wider.bound = 1e9;
  near.world.setWorldSettings(wider);
  EXPECT_NO_THROW(scenes::loadSceneText(scenes::writeSceneXml(near, near.camera), "near.xml"));
}

// A fade's shift and held root are held to the bound by the loader, as the clip frame is; a clip
// that loops on far along its path leaves them beyond it, and such a world would save a file that
// does not reload.
TEST(SceneWriter, AFadesShiftOrHeldRootPastTheBoundIsNotWritten) {
  auto refusal = [](const scenes::Scene& scene) {
    try {
      scenes::writeSceneXml(scene, scene.camera);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string ragdoll = "<ragdoll name=\"r\" pos=\"0 1 0\" model=\"rigid\"/>";
  const std::string character =
      "<character ragdoll=\"r\" clip=\"" DATA_DIR "/assets/clips/run.bvh\" blend=\"0.5\" ";
  scenes::Scene fading =
      load(ragdoll + character + "from-clip=\"" DATA_DIR "/assets/clips/run.bvh\" from-shift=\"5 0 0\"/>",
           "<world bound=\"20\"/>");
  EXPECT_EQ(refusal(fading), "");
  phys::CharacterMotion motion = fading.world.characterMotion(0);
  motion.beforeShift = phys::Vec3(0.0, 0.0, 21.0);
  fading.world.setCharacterMotion(0, motion);
  EXPECT_NE(refusal(fading).find("the shift of the clip character 'r' fades from lies at (0, 0, 21), beyond"),
            std::string::npos)
      << refusal(fading);
  std::string turns = "1 0 0 0";
  for (int bone = 1; bone < 10; ++bone) turns += ", 1 0 0 0";
  scenes::Scene holding =
      load(ragdoll + character + "held-turns=\"" + turns + "\"/>", "<world bound=\"20\"/>");
  EXPECT_EQ(refusal(holding), "");
  motion = holding.world.characterMotion(0);
  motion.held.root = phys::Vec3(-21.0, 0.0, 0.0);
  holding.world.setCharacterMotion(0, motion);
  EXPECT_NE(refusal(holding).find("the held pose's root of character 'r' lies at (-21, 0, 0), beyond"),
            std::string::npos)
      << refusal(holding);
}

// A box or capsule is saved as its pose and rebuilt from it at its rest shape: one pressed out of
// shape with its particles just inside the bound would be rebuilt reaching past it, which the
// loader refuses. Found by the soak test: a capsule squashed by 5.6 cm near a bound of 82 m saved a
// file that did not reload.
TEST(SceneWriter, ABodyThatWouldBeRebuiltPastTheBoundIsNotWritten) {
  // Each reaches 9.9 m along x.
  for (const char* element : {"<box name=\"squashed\" pos=\"9.4 1 0\" size=\"1 1 1\"/>",
                              "<capsule name=\"squashed\" pos=\"9.3 1 0\" euler=\"0 0 90\" radius=\"0.5\" "
                              "length=\"1.2\"/>"}) {
    SCOPED_TRACE(element);
    scenes::Scene scene = load(element, "<world bound=\"10\"/>");
    // Pressed to 70% of its length along x about its centre: its particles then reach 9.75 m
    // (the box) or 9.72 m (the capsule), its rest shape still 9.9 m.
    phys::Motion m = scene.world.motion();
    const double centre = scene.world.bodyPose(phys::BodyId{0}).center.x;
    for (std::size_t i = 0; i < m.position.size(); ++i) {
      for (phys::Vec3* x : {&m.position[i], &m.previous[i]}) x->x = centre + (x->x - centre) * 0.7;
    }
    scene.world.setMotion(m);
    const phys::WorldSettings wide = scene.world.worldSettings();
    phys::WorldSettings tight = wide;
    tight.bound = 9.85;
    scene.world.setWorldSettings(tight);
    std::string text;
    try {
      text = scenes::writeSceneXml(scene);
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("box 0 'squashed', pressed out of shape, would be rebuilt "
                                           "from its pose reaching beyond the world's bound of 9.85 m, "
                                           "which no scene file can hold"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(text, "") << "written, and the loader says: " << [&text] {
      try {
        scenes::loadSceneText(text, "squashed.xml");
      } catch (const scenes::LoadError& e) {
        return std::string(e.what());
      }
      return std::string("nothing");
    }();
    // With room for its rest shape, it is written and reloads.
    scene.world.setWorldSettings(wide);
    EXPECT_NO_THROW(scenes::loadSceneText(scenes::writeSceneXml(scene), "squashed.xml"));
  }
}

// A fresh folder under the system's temporary one, removed with everything in it, read-only
// folders included.
class TempFolder {
 public:
  TempFolder() {
    static int count = 0;
    path_ = fs::temp_directory_path() /
            ("scene-writer-test-" + std::to_string(::getpid()) + "-" + std::to_string(count++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    // Each folder is opened up as it is reached, before the walk descends into it.
    for (auto it = fs::recursive_directory_iterator(path_, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      if (it->is_directory(ec)) fs::permissions(it->path(), fs::perms::owner_all, fs::perm_options::add, ec);
    }
    fs::remove_all(path_, ec);
  }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  const fs::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string readFile(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void expectSaveError(const scenes::Scene& scene, const fs::path& file, const std::string& says) {
  try {
    scenes::saveSceneFile(scene, file);
    ADD_FAILURE() << file << ": saved";
  } catch (const scenes::SaveError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(SceneWriter, SaveReplacesAFileWholeAndKeepsItsPermissions) {
  const TempFolder folder;
  const fs::path file = folder.path() / "saved.xml";
  std::ofstream(file) << std::string(100000, 'x');  // longer than the scene: no tail may survive
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/falling-box.xml");
  for (int i = 0; i < 10; ++i) scene.world.step();
  scenes::saveSceneFile(scene, file);
  EXPECT_EQ(readFile(file), scenes::writeSceneXml(scene));
  EXPECT_EQ(fs::status(file).permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"saved.xml"});  // no temporary file left
  EXPECT_EQ(scenes::loadSceneFile(file).world.bodies().size(), scene.world.bodies().size());
}

TEST(SceneWriter, SaveThroughASymbolicLinkReplacesItsTarget) {
  const TempFolder folder;
  fs::create_directory(folder.path() / "real");
  std::ofstream(folder.path() / "real" / "scene.xml") << "old";
  fs::create_symlink("real/scene.xml", folder.path() / "link.xml");
  const scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/pendulum.xml");
  scenes::saveSceneFile(scene, folder.path() / "link.xml");
  EXPECT_TRUE(fs::is_symlink(folder.path() / "link.xml"));
  EXPECT_EQ(readFile(folder.path() / "real" / "scene.xml"), scenes::writeSceneXml(scene));
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"link.xml", "real"}));
}

TEST(SceneWriter, SaveFailsWithTheFileNamedAndNothingLeftBehind) {
  const TempFolder folder;
  const scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/pendulum.xml");

  expectSaveError(scene, folder.path() / "missing" / "scene.xml", "No such file or directory");
  EXPECT_FALSE(fs::exists(folder.path() / "missing"));

  std::ofstream(folder.path() / "plain") << "a file, not a folder";
  expectSaveError(scene, folder.path() / "plain" / "scene.xml", "Not a directory");
  EXPECT_EQ(readFile(folder.path() / "plain"), "a file, not a folder");

  // A folder in the way is refused before anything is written.
  fs::create_directory(folder.path() / "taken.xml");
  std::ofstream(folder.path() / "taken.xml" / "inside") << "kept";
  expectSaveError(scene, folder.path() / "taken.xml", "is a folder, not a file");
  EXPECT_EQ(readFile(folder.path() / "taken.xml" / "inside"), "kept");
  EXPECT_EQ(folder.entries(), (std::vector<std::string>{"plain", "taken.xml"}));
}

// Root ignores a folder's permissions, and CI runs as root: the save runs as nobody there.
TEST(SceneWriter, SaveIntoAReadOnlyFolderFails) {
  const TempFolder folder;
  const fs::path locked = folder.path() / "locked";
  fs::create_directory(locked);
  std::ofstream(locked / "scene.xml") << "old";
  const auto readable = fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                        fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(folder.path(), readable | fs::perms::owner_write);
  fs::permissions(locked, readable);
  const scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/pendulum.xml");
  const std::string error = testing_app::runAsNobody([&] {
    try {
      scenes::saveSceneFile(scene, locked / "scene.xml");
    } catch (const scenes::SaveError& e) {
      return std::string(e.what());
    }
    return std::string("saved");
  });
  EXPECT_EQ(error.rfind((locked / "scene.xml").string() + ": ", 0), 0u) << error;
  EXPECT_NE(error.find("Permission denied"), std::string::npos) << error;
  EXPECT_EQ(readFile(locked / "scene.xml"), "old");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"locked"});
}

// Save As onto a dangling link replaced the link with a regular file; the docs say a link is
// followed, so the file it names is created and the link stays.
TEST(SceneWriter, SaveThroughADanglingLinkCreatesItsTarget) {
  const TempFolder folder;
  fs::create_directory(folder.path() / "real");
  fs::create_symlink("real/new.xml", folder.path() / "link.xml");
  const scenes::Scene scene = scenes::loadSceneFile(DATA_DIR "/assets/scenes/pendulum.xml");
  scenes::saveSceneFile(scene, folder.path() / "link.xml");
  EXPECT_TRUE(fs::is_symlink(folder.path() / "link.xml"));
  EXPECT_EQ(readFile(folder.path() / "real" / "new.xml"), scenes::writeSceneXml(scene));
  EXPECT_EQ(scenes::loadSceneFile(folder.path() / "link.xml").world.particles().size(),
            scene.world.particles().size());
}

TEST(SceneWriter, AWorldThatCannotBeSavedLeavesTheOldFile) {
  const TempFolder folder;
  const fs::path file = folder.path() / "scene.xml";
  std::ofstream(file) << "old";
  scenes::Scene scene = load("<particle name=\"p\" pos=\"0 3 0\"/><box pos=\"0 1 0\"/>");
  scene.world.addStick(phys::ParticleId{0}, phys::ParticleId{1});
  expectSaveError(scene, file, "cannot save this world");
  EXPECT_EQ(readFile(file), "old");
  EXPECT_EQ(folder.entries(), std::vector<std::string>{"scene.xml"});
}

}  // namespace

namespace {

TEST(SceneWriter, DepenetrationSpeedRoundTripsIncludingNoLimit) {
  for (const double speed : {0.75, std::numeric_limits<double>::infinity()}) {
    scenes::Scene scene = scenes::loadSceneText("<scene name=\"d\"><box pos=\"0 1 0\"/></scene>", "d.xml");
    phys::SolverSettings s = scene.world.solverSettings();
    s.maxDepenetrationSpeed = speed;
    scene.world.setSolverSettings(s);
    const scenes::Scene back = scenes::loadSceneText(scenes::writeSceneXml(scene), "back.xml");
    EXPECT_EQ(back.world.solverSettings().maxDepenetrationSpeed, speed);
  }
}

}  // namespace
