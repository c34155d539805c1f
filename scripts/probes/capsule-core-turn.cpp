// Probe for docs/physics.md, "A capsule turned about its core": the scene of
// CapsuleGround.ALyingCornersCapsuleTurnedAboutItsCoreStaysTurned, a 0.2 m radius, 1.4 m corners
// capsule laid on the ground turned DEG degrees about its core, world damping 0.2. Needs the hook
// of scripts/probes/capsule-core-turn.patch (a call after each stage of a substep). Prints, each
// second, the turn about the core, its rate, how far it moved and the levers of its two ground points
// about its centre; and over the run, per stage, the angular momentum (over the moment of inertia)
// each stage added about the centre and about the ground's line under the core, which gravity and
// friction at the ground leave alone, so the stage that turns it shows. The docs' figures were read
// on the commit before the fix. Not part of the build:
//
//   git apply scripts/probes/capsule-core-turn.patch
//   cmake --build --preset release --target physics
//   g++ -std=c++20 -O2 -Iphysics/include scripts/probes/capsule-core-turn.cpp \
//     build/release/physics/libphysics.a -ltbb -o /tmp/capsule-core-turn
//   /tmp/capsule-core-turn gs 2 4 10 30     # method iterations substeps degrees seconds [options]
//
// options: keepspin, nofriction, nodamping, trace (every stage of the first substeps of each second),
// stages (each second, what each stage added about the ground line in that second)
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "physics/world.h"

namespace phys {
extern void (*gPassProbe)(const char* stage, int pass, const World& world);
}

namespace {

using phys::Vec3;

struct Reading {
  Vec3 centre{0.0}, axis{0.0};
  double turn = 0.0;     // degrees: the box's x edges about the core, from world y towards z
  double omega = 0.0;    // rad/s: angular momentum about the core over the moment of inertia
  double rolling = 0.0;  // rad/s: the same about the ground's line under the core, which friction at
                         // the ground does not change
  double lever[2] = {};  // m: each ground point's (p - c) x n along the core
};

double gH = 1.0 / 60.0;
bool gTrace = false;
int gSubstep = 0;

Reading read(const phys::World& world) {
  const phys::Particles& p = world.particles();
  Reading r;
  for (int i = 0; i < 8; ++i) r.centre += p.position[i] / 8.0;
  Vec3 ex(0.0), ey(0.0);
  for (int i = 0; i < 8; ++i) {
    if ((i & 1) == 0) ex += p.position[i | 1] - p.position[i];
    if ((i & 2) == 0) ey += p.position[i | 2] - p.position[i];
  }
  r.axis = glm::normalize(ey);
  r.turn = std::atan2(ex.z, ex.y) * 180.0 / std::numbers::pi;
  double L = 0.0, I = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 d = p.position[i] - r.centre;
    const Vec3 v = (p.position[i] - p.previous[i]) / gH;
    L += glm::dot(glm::cross(d, v), r.axis);
    const Vec3 perp = d - glm::dot(d, r.axis) * r.axis;
    I += glm::dot(perp, perp);
  }
  r.omega = L / I;
  const Vec3 o(r.centre.x, 0.0, r.centre.z);
  double Lo = 0.0, Io = 0.0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 d = p.position[i] - o;
    const Vec3 v = (p.position[i] - p.previous[i]) / gH;
    Lo += glm::dot(glm::cross(d, v), r.axis);
    const Vec3 perp = d - glm::dot(d, r.axis) * r.axis;
    Io += glm::dot(perp, perp);
  }
  r.rolling = Lo / Io;
  const auto g = world.groundContacts();
  for (std::size_t k = 0; k < g.size() && k < 2; ++k) {
    Vec3 at(0.0);
    for (int j = 0; j < g[k].point.count; ++j)
      at += g[k].point.weight[j] * p.position[g[k].point.particle[j]];
    r.lever[k] = glm::dot(glm::cross(at - r.centre, Vec3(0.0, 1.0, 0.0)), r.axis);
  }
  return r;
}

Reading gLast;
std::map<std::string, double> gAdded, gRolled;  // rad/s of omega, rolling each stage added, summed
std::vector<std::string> gOrder;

void probe(const char* stage, int pass, const phys::World& world) {
  const Reading r = read(world);
  std::string name = stage;
  if (pass >= 0) name += " " + std::to_string(pass);
  if (!gAdded.count(name)) gOrder.push_back(name);
  gAdded[name] += r.omega - gLast.omega;
  gRolled[name] += r.rolling - gLast.rolling;
  if (gTrace)
    std::printf(
        "    %-11s turn %+.5f deg  omega %+.6f (%+.6f)  rolling %+.6f (%+.6f) rad/s  levers %+.3f %+.3f mm\n",
        name.c_str(), r.turn, r.omega, r.omega - gLast.omega, r.rolling, r.rolling - gLast.rolling,
        1e3 * r.lever[0], 1e3 * r.lever[1]);
  gLast = r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(
        stderr, "usage: %s gs|xpbd|shake|jacobi ITER SUB DEG SECONDS [keepspin nofriction nodamping trace]\n",
        argv[0]);
    return 2;
  }
  phys::SolverSettings s;
  const std::string m = argv[1];
  s.method = m == "xpbd"     ? phys::SolverMethod::Xpbd
             : m == "shake"  ? phys::SolverMethod::Shake
             : m == "jacobi" ? phys::SolverMethod::Jacobi
                             : phys::SolverMethod::GaussSeidel;
  s.iterations = std::atoi(argv[2]);
  s.substeps = std::atoi(argv[3]);
  const double degrees = std::atof(argv[4]);
  const int seconds = std::atoi(argv[5]);
  bool noFriction = false, noDamping = false, trace = false, stages = false;
  for (int a = 6; a < argc; ++a) {
    if (!std::strcmp(argv[a], "keepspin")) s.keepSpin = true;
    if (!std::strcmp(argv[a], "nofriction")) noFriction = true;
    if (!std::strcmp(argv[a], "nodamping")) noDamping = true;
    if (!std::strcmp(argv[a], "trace")) trace = true;
    if (!std::strcmp(argv[a], "stages")) stages = true;
  }
  gH = s.dt / s.substeps;
  phys::WorldSettings ws;
  ws.damping = noDamping ? 0.0 : 0.2;
  if (noFriction) ws.groundMaterial = {0.0, 0.0};
  phys::World world(ws, s);
  phys::BodyDesc d;
  d.shape = phys::Shape::Capsule;
  d.model = phys::BodyModel::Corners;
  d.center = Vec3(0.0, 0.2, 0.0);
  d.size = Vec3(0.4, 1.4, 0.4);
  if (noFriction) d.material = {0.0, 0.0};
  const phys::Quat lying = glm::angleAxis(std::numbers::pi / 2.0, Vec3(0.0, 0.0, 1.0));
  d.orientation = glm::angleAxis(degrees * std::numbers::pi / 180.0, Vec3(1.0, 0.0, 0.0)) * lying;
  world.addBody(d);
  gLast = read(world);
  phys::gPassProbe = probe;
  const Vec3 start = gLast.centre;
  std::printf("%s %d x %d, laid %.0f degrees%s%s%s\n", m.c_str(), s.iterations, s.substeps, degrees,
              s.keepSpin ? ", keepSpin" : "", noFriction ? ", no friction" : "",
              noDamping ? ", no damping" : "");
  for (int i = 1; i <= seconds * 60; ++i) {
    gTrace = trace && (i % 60 == 1);
    if (gTrace) std::printf("  step %d\n", i);
    world.step();
    if (i % 60 != 0) continue;
    const Reading r = read(world);
    std::printf("%3d s: turn %+8.3f deg  omega %+.5f rad/s  moved %6.2f mm  levers %+.3f %+.3f mm  y %.5f\n",
                i / 60, r.turn, r.omega, 1e3 * std::hypot(r.centre.x - start.x, r.centre.z - start.z),
                1e3 * r.lever[0], 1e3 * r.lever[1], r.centre.y);
    if (stages) {
      std::printf("       ");
      for (const std::string& name : gOrder) {
        static std::map<std::string, double> before;
        std::printf(" %s %+.4f", name.c_str(), gRolled[name] - before[name]);
        before[name] = gRolled[name];
      }
      std::printf("\n");
    }
  }
  std::printf("added per stage over the run (rad/s, summed): about the centre, about the ground line\n");
  for (const std::string& name : gOrder)
    std::printf("  %-11s %+.5f %+.5f\n", name.c_str(), gAdded[name], gRolled[name]);
}
