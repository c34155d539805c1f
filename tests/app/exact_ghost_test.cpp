// The exact answer's ghost (exact_ghost.h): in every scene with analytic answers it passes through
// each of them at its time, goes back when time does, and there is none in other scenes.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "exact_ghost.h"
#include "project_session.h"
#include "temp_folder.h"

namespace {

phys::Vec3 positionOf(const phys::World& world, const scenes::NamedBody& body) {
  return body.kind == scenes::NamedBody::Kind::Particle ? world.particles().position[body.particle()]
                                                        : world.bodyPose(body.body()).center;
}

phys::Vec3 parsed(const std::string& text) {
  phys::Vec3 v(0.0);
  EXPECT_EQ(std::sscanf(text.c_str(), "%lf %lf %lf", &v.x, &v.y, &v.z), 3) << text;
  return v;
}

// The ghost and the crosses drawn beside the session's world, and no reason given against them.
void expectShown(sandbox::ExactGhost& ghost, const sandbox::Session& s, const char* when) {
  const sandbox::ExactGhost::Drawn drawn = ghost.beside(s.scene().world);
  EXPECT_NE(drawn.ghost, nullptr) << when;
  EXPECT_EQ(drawn.answers.size(), s.scene().expectations.size()) << when;
  EXPECT_EQ(ghost.hiddenBecause(s.scene().world), "") << when;
}

// Neither drawn, for the reason `why`.
void expectHidden(sandbox::ExactGhost& ghost, const sandbox::Session& s, const char* when,
                  const std::string& why) {
  const sandbox::ExactGhost::Drawn drawn = ghost.beside(s.scene().world);
  EXPECT_EQ(drawn.ghost, nullptr) << when;
  EXPECT_TRUE(drawn.answers.empty()) << when;
  EXPECT_EQ(ghost.hiddenBecause(s.scene().world), why) << when;
}

// The closed-form answers are met within a micrometre at 128 substeps (measured: at most 1.1e-8 m
// for the projectile, 2.7e-8 m for the orbit, 8.2e-8 m for the pendulum): the ghost is the answer
// to the eye, and between the crosses it is where the answer is.
TEST(ExactGhost, PassesThroughEveryAnalyticAnswerAtItsTime) {
  for (const char* name : {"projectile", "circular-orbit", "pendulum-exact"}) {
    SCOPED_TRACE(name);
    const sandbox::Session s = testing_app::openSession(name);
    sandbox::ExactGhost ghost;
    ghost.reset(s.scene());
    ASSERT_TRUE(ghost.active());
    const double dt = s.scene().world.solverSettings().dt;
    int checked = 0;
    for (const scenes::Expectation& e : s.scene().expectations) {
      const double at = std::atof(e.find("at")->c_str());
      const phys::World* world = ghost.at(at, dt);
      ASSERT_NE(world, nullptr);
      EXPECT_NEAR(world->time(), at, dt / 2);
      const std::string& body = *e.find("body");
      for (const scenes::NamedBody& b : s.scene().bodies) {
        if (b.name != body) continue;
        const double off = glm::length(positionOf(*world, b) - parsed(*e.find("pos")));
        EXPECT_LT(off, 1e-6) << body << " at " << at;
        ++checked;
      }
    }
    EXPECT_GE(checked, 4);
  }
}

TEST(ExactGhost, GoesBackWithTheClockAndIsNoneWithoutAnswers) {
  const sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  ghost.reset(s.scene());
  const double dt = s.scene().world.solverSettings().dt;
  const std::uint64_t early = ghost.at(0.5, dt)->stateHash();
  const std::uint64_t later = ghost.at(2.5, dt)->stateHash();
  ghost.at(3.5, dt);
  // Back from 3.5 s: from the copy kept at 2 s, the same state as stepped from the start.
  EXPECT_EQ(ghost.at(2.5, dt)->stateHash(), later);
  EXPECT_EQ(ghost.at(0.5, dt)->stateHash(), early);
  EXPECT_EQ(ghost.at(0.0, dt)->stepCount(), 0);

  ghost.reset(testing_app::openSession("ragdoll").scene());
  EXPECT_FALSE(ghost.active());
  EXPECT_EQ(ghost.at(1.0, dt), nullptr);
  EXPECT_TRUE(ghost.answers().empty());
}

// Back to the start and on again (the timeline dragged back, then to the end): the ghost went on
// from where it was, stepping again every step to the end at 128 substeps (about a second a
// simulated minute), though it had kept copies on the way. It goes from the last copy before the
// time asked for, to the same state.
TEST(ExactGhost, GoesForwardFromTheCopiesKeptAsItGoesBack) {
  const sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  ghost.reset(s.scene());
  const double dt = s.scene().world.solverSettings().dt;
  const std::uint64_t late = ghost.at(30.0, dt)->stateHash();
  ghost.at(0.0, dt);
  const long before = ghost.stepsTaken();
  EXPECT_EQ(ghost.at(30.0, dt)->stateHash(), late);
  EXPECT_LE(ghost.stepsTaken() - before, std::lround(sandbox::kGhostSnapshotEvery / dt) + 1);
}

// Gravity changed for 10 s and set back: the ghost, left where it was hidden, took the 10 s of
// steps at 128 substeps in the frame it came back (a minute's took half a second to a second, a
// freeze). It keeps up while hidden, so coming back costs no more than a frame's step.
TEST(ExactGhost, KeepsUpWhileHiddenSoThatComingBackCostsAFramesStep) {
  sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  ghost.reset(s.scene());
  ASSERT_EQ(s.changeGravity(1.0), "");
  for (int i = 0; i < 600; ++i) {
    s.step();
    EXPECT_EQ(ghost.beside(s.scene().world).ghost, nullptr);  // each frame, as the sandbox draws
  }
  ASSERT_EQ(s.changeGravity(-1.0), "");
  const long before = ghost.stepsTaken();
  const sandbox::ExactGhost::Drawn drawn = ghost.beside(s.scene().world);
  ASSERT_NE(drawn.ghost, nullptr);
  EXPECT_NEAR(drawn.ghost->time(), s.scene().world.time(), 1e-9);
  EXPECT_LE(ghost.stepsTaken() - before, 1);
}

// Exact answers turned on after 30 s with them off: the ghost, not stepped since, would take the
// 1,800 steps at 128 substeps in one frame (a minute's would freeze the sandbox for a second). It catches up
// kGhostStepsPerFrame steps a frame, hidden and saying so until it is there, and then is the same
// state as a ghost stepped there at once.
TEST(ExactGhost, CatchesUpAFramesStepsAtATimeAfterAStretchNotDrawn) {
  sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  ghost.reset(s.scene());
  const int steps = 1800;
  for (int i = 0; i < steps; ++i) s.step();
  const phys::World& world = s.scene().world;
  int frames = 0;
  for (;;) {
    const long before = ghost.stepsTaken();
    const sandbox::ExactGhost::Drawn drawn = ghost.beside(world);
    ++frames;
    EXPECT_LE(ghost.stepsTaken() - before, sandbox::kGhostStepsPerFrame);
    if (drawn.ghost != nullptr) break;
    ASSERT_EQ(ghost.hiddenBecause(world).rfind("catching up with the run (at ", 0), 0U)
        << ghost.hiddenBecause(world);
    ASSERT_LT(frames, steps) << "the ghost never caught up";
  }
  EXPECT_EQ(frames, (steps + sandbox::kGhostStepsPerFrame - 1) / sandbox::kGhostStepsPerFrame);
  EXPECT_EQ(ghost.hiddenBecause(world), "");
  sandbox::ExactGhost atOnce;
  atOnce.reset(testing_app::openSession("projectile").scene());
  const phys::World* direct = atOnce.at(world.time(), world.solverSettings().dt);
  EXPECT_EQ(ghost.beside(world).ghost->stateHash(), direct->stateHash());
  // Caught up, it goes with the run a step a frame.
  s.step();
  const long before = ghost.stepsTaken();
  EXPECT_NE(ghost.beside(world).ghost, nullptr);
  EXPECT_EQ(ghost.stepsTaken() - before, 1);
}

// The crosses are the file's answers, read as the lab reads them (they were parsed apart, with
// sscanf, which took "nan" and "1e39" as numbers).
TEST(ExactGhost, ItsCrossesAreTheFilesAnswers) {
  const sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  ghost.reset(s.scene());
  ASSERT_EQ(ghost.answers().size(), s.scene().expectations.size());
  for (std::size_t i = 0; i < ghost.answers().size(); ++i) {
    const scenes::Expectation& e = s.scene().expectations[i];
    EXPECT_NEAR(ghost.answers()[i].first, std::atof(e.find("at")->c_str()), 1e-12);
    EXPECT_LT(glm::length(glm::dvec3(ghost.answers()[i].second) - parsed(*e.find("pos"))), 1e-5);
  }
}

// The ghost and the crosses are of the scene's bodies: key 0 (Session::clear) takes them away with
// the bodies, and Reload brings them back. They stayed, the ghost of a scene no longer there going
// on beside an empty world. A recording of the scene's run shows them, one of the cleared world
// does not, and a rewind shows them at the time rewound to.
TEST(ExactGhost, GoesWithTheScenesBodiesAndComesBackWithThem) {
  const testing_app::TempFolder dir;
  sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  auto expectShown = [&](const char* when) {
    const sandbox::ExactGhost::Drawn drawn = ghost.beside(s.scene().world);
    ASSERT_NE(drawn.ghost, nullptr) << when;
    EXPECT_NEAR(drawn.ghost->time(), s.scene().world.time(), 1e-9) << when;
    EXPECT_EQ(drawn.answers.size(), s.scene().expectations.size()) << when;
  };
  auto expectNone = [&](const char* when) {
    const sandbox::ExactGhost::Drawn drawn = ghost.beside(s.scene().world);
    EXPECT_EQ(drawn.ghost, nullptr) << when;
    EXPECT_TRUE(drawn.answers.empty()) << when;
  };
  ghost.reset(s.scene());  // as the sandbox does on opening a scene (Sandbox::fitToScene)
  for (int i = 0; i < 40; ++i) {
    s.step();
    ghost.beside(s.scene().world);  // each frame, as the sandbox draws: it steps a frame's worth at most
  }
  ASSERT_EQ(s.spawnBox(phys::Vec3(0.0, 3.0, 6.0), phys::Vec3(0.0)), "");
  s.step();
  expectShown("with a box thrown in");
  ASSERT_EQ(s.rewindTo(20), "");
  expectShown("rewound");
  ASSERT_EQ(s.saveRecording(dir.path / "run.jrec"), "");

  s.clear();
  expectNone("cleared");
  ASSERT_EQ(s.spawnBox(phys::Vec3(0.0, 3.0, 6.0), phys::Vec3(0.0)), "");
  for (int i = 0; i < 10; ++i) s.step();
  expectNone("a box thrown into the cleared world");
  ASSERT_EQ(s.saveRecording(dir.path / "cleared.jrec"), "");

  ASSERT_EQ(s.openRecording(dir.path / "run.jrec"), "");
  expectShown("the scene's run opened from a file");
  ASSERT_EQ(s.openRecording(dir.path / "cleared.jrec"), "");
  expectNone("the cleared world's run opened from a file");

  s.clear();
  ASSERT_EQ(s.reload(), "");
  ghost.reset(s.scene());
  expectShown("reloaded");
}

// The answer is the file's: under other gravity or damping the ghost and the crosses stayed, and
// showed where the body would be under the file's settings, beside a run under the user's. They
// go while any setting the answer depends on differs from the file's, the panel says which, and
// they come back when it is set back (to a float slider's or Y's and H's rounding) or on Reload.
// What the ghost sets itself (method, substeps, iterations), follows (dt) or what changes
// nothing (threads) does not hide it: that is what one changes to watch the run drift from it.
TEST(ExactGhost, GoesWhileASettingItDependsOnDiffersFromTheFilesAndComesBack) {
  sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  auto shown = [&](const char* when) { expectShown(ghost, s, when); };
  auto hidden = [&](const char* when, const std::string& why) { expectHidden(ghost, s, when, why); };
  ghost.reset(s.scene());
  for (int i = 0; i < 30; ++i) s.step();
  shown("as opened");

  ASSERT_EQ(s.changeGravity(1.0), "");  // Y
  hidden("gravity raised", "gravity changed");
  ASSERT_EQ(s.changeDamping(0.1), "");  // U
  hidden("and damping", "gravity and damping changed");
  ASSERT_EQ(s.changeGravity(-1.0), "");  // H: 9.809999999999999
  hidden("gravity back", "damping changed");
  ASSERT_EQ(s.changeDamping(-0.1), "");
  shown("both back");

  ASSERT_EQ(s.toggleGravityMode(), "");  // G
  hidden("gravity towards a point", "gravity changed");
  ASSERT_EQ(s.toggleGravityMode(), "");
  shown("gravity uniform again");

  // The World panel's strength slider, a float: 12, then 9.81 as a float gives it back.
  const phys::Material fileGround = s.scene().world.worldSettings().groundMaterial;
  phys::WorldSettings w = s.scene().world.worldSettings();
  w.gravity = phys::Vec3(0.0, -12.0, 0.0);
  ASSERT_EQ(s.setWorldSettings(w), "");
  hidden("gravity from the slider", "gravity changed");
  w.gravity = phys::Vec3(0.0, -static_cast<double>(9.81f), 0.0);
  ASSERT_EQ(s.setWorldSettings(w), "");
  shown("the slider back at 9.81");
  w.groundMaterial.staticFriction = 0.2;
  ASSERT_EQ(s.setWorldSettings(w), "");
  hidden("ground friction", "ground friction changed");

  const phys::SolverSettings file = s.scene().world.solverSettings();
  w = s.scene().world.worldSettings();
  w.groundMaterial = fileGround;
  ASSERT_EQ(s.setWorldSettings(w), "");
  phys::SolverSettings solver = file;
  solver.method = phys::SolverMethod::Jacobi;
  solver.substeps = 4;
  solver.iterations = 8;
  solver.threads = 2;
  solver.dt = file.dt / 2;
  ASSERT_EQ(s.setSolverSettings(solver), "");
  s.step();
  shown("another method, substeps, iterations, threads and dt");
  solver.restitution = 0.5;
  solver.compliance = 1e-4;
  ASSERT_EQ(s.setSolverSettings(solver), "");
  hidden("restitution and compliance", "restitution and compliance changed");
  ASSERT_EQ(s.setSolverSettings(file), "");
  shown("the file's solver settings");

  ASSERT_EQ(s.changeGravity(2.0), "");
  hidden("gravity again", "gravity changed");
  ASSERT_EQ(s.reload(), "");
  ghost.reset(s.scene());  // as the sandbox does on Reload (Sandbox::fitToScene)
  shown("reloaded");

  // A rewind to a step before the change shows the world as it was then, settings and all.
  for (int i = 0; i < 10; ++i) s.step();
  ASSERT_EQ(s.changeDamping(0.5), "");
  s.step();
  hidden("damping", "damping changed");
  ASSERT_EQ(s.rewindTo(5), "");
  shown("rewound to before the change");
}

// Save As makes the saved file the current one (Reload reads it) and leaves the <expect>s out.
// The ghost went on comparing with the file opened: saved with gravity raised, it said "gravity
// changed" of a world with the saved file's very gravity, and gravity set back to the opened
// file's brought the answer back beside a file that has none. It compares with the file saved,
// says when that file's settings are not the answer's, which cannot be recomputed for them, and
// comes back once the file is saved again with the answer's settings.
TEST(ExactGhost, ComparesWithTheFileSaveAsWroteAndSaysWhenTheAnswerIsNotItsOwn) {
  const testing_app::TempFolder dir;
  sandbox::Session s = testing_app::openSession("projectile");
  sandbox::ExactGhost ghost;
  auto saveAs = [&](const char* name) {
    ASSERT_EQ(s.saveAs(dir.path / name, scenes::CameraStart{}), "");
    ghost.fileSaved(s.scene().world);  // as the sandbox does after Save As (Sandbox::drawDialogs)
  };
  ghost.reset(s.scene());
  for (int i = 0; i < 30; ++i) s.step();
  saveAs("same.xml");
  expectShown(ghost, s, "saved with the answer's settings");

  ASSERT_EQ(s.changeGravity(1.0), "");  // Y
  saveAs("heavier.xml");
  const std::string notItsOwn =
      "saved with gravity changed, and the answer (projectile.xml's) cannot be recomputed for the saved "
      "settings";
  expectHidden(ghost, s, "saved with gravity raised", notItsOwn);
  s.step();
  ASSERT_EQ(s.changeGravity(-1.0), "");  // H: the answer's gravity, no longer the file's
  expectHidden(ghost, s, "gravity set back after the save", notItsOwn);
  ASSERT_EQ(s.changeDamping(0.1), "");
  expectHidden(ghost, s, "and damping", notItsOwn);
  ASSERT_EQ(s.changeDamping(-0.1), "");

  saveAs("back.xml");
  expectShown(ghost, s, "saved again with the answer's settings");
  ASSERT_EQ(s.changeDamping(0.1), "");
  expectHidden(ghost, s, "damping changed from the file saved", "damping changed");

  // Reload reads the file saved, which has no answers: nothing to draw, and nothing to explain.
  ASSERT_EQ(s.reload(), "");
  ghost.reset(s.scene());  // as the sandbox does on Reload (Sandbox::fitToScene)
  EXPECT_FALSE(ghost.active());
  EXPECT_EQ(ghost.hiddenBecause(s.scene().world), "");
}

}  // namespace
