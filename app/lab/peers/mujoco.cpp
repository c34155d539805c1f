// MuJoCo (Debian's libmujoco-dev 2.2.2): the scene written as MJCF text, loaded with
// mj_loadXML from a virtual file in memory, stepped by mj_step with every option at MuJoCo's
// default but the timestep (= dt) and gravity: Newton solver, pyramidal friction cones, Euler
// integrator, up to 100 iterations, soft constraints at the default solref and solimp (which
// MuJoCo's refsafe keeps at a time constant of at least two steps).
//
// Mapping: the ground is a plane geom; each body a <body> with a free joint (none when pinned:
// a body without a joint is welded to the world), an <inertial> with our mass and inertia, and a
// box or sphere geom. A pin is a <connect> equality; a stick a spatial tendon between two sites
// held at its length by a <tendon> equality; a range stick or range link the same tendon with a
// limited range (MuJoCo's tendon limit is exactly our one-sided distance). Ground contact is one
// explicit <pair> per body, with our friction (the geometric mean), because MuJoCo would combine
// the ground's and the body's coefficients by taking the larger; boxes meet each other through
// contype/conaffinity, ignored pairs through <exclude>. Spheres meet nothing but the ground, as
// our particles. The world's damping is applied each step through xfrc_applied: -c m v on the
// centre and -c I omega about it, what our exp(-c t) decay of every particle's velocity is.
//
// Limits of 2.2.2: its constraint buffers are allocated up front as njmax x njmax and
// njmax x nv, so a large pile cannot be built at all (the table says so), and contacts past
// nconmax are dropped with a warning (the table says that too).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "peer_scene.h"

namespace lab::peers {
namespace {

// MuJoCo reports errors through a global hook that must not return (the engine carries on
// otherwise); throwing is what MuJoCo's own compiler does from it. Warnings would go to
// stdout and a MUJOCO_LOG.TXT in the current folder; they are kept for the table instead.
std::string g_lastWarning;
void throwError(const char* message) { throw std::runtime_error(std::string("MuJoCo error: ") + message); }
void keepWarning(const char* message) { g_lastWarning = message; }

class Hooks {
 public:
  Hooks() : error_(mju_user_error), warning_(mju_user_warning) {
    mju_user_error = &throwError;
    mju_user_warning = &keepWarning;
  }
  ~Hooks() {
    mju_user_error = error_;
    mju_user_warning = warning_;
  }
  Hooks(const Hooks&) = delete;
  Hooks& operator=(const Hooks&) = delete;

 private:
  void (*error_)(const char*);
  void (*warning_)(const char*);
};

std::string num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}
std::string vec(const phys::Vec3& v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }
std::string quat(const phys::Quat& q) { return num(q.w) + " " + num(q.x) + " " + num(q.y) + " " + num(q.z); }
std::string friction(double mu) { return num(mu) + " 0.005 0.0001"; }  // MuJoCo's torsional and rolling defaults

// The MJCF text of the scene, and the sizes it asked MuJoCo for.
struct Model {
  std::string xml;
  int njmax = 0;
  int nconmax = 0;
  std::vector<std::string> notes;
};

Model writeModel(const Description& scene, double dt) {
  Model model;
  // Room for every contact a resting pile makes: up to 8 points for a box on a box and 4 on
  // the ground; 4 rows each (a pyramidal cone of condim 3), plus every equality and limit row.
  model.nconmax = 10 * scene.boxCount() + 2 * static_cast<int>(scene.bodies.size()) + 20;
  model.njmax = 4 * model.nconmax + 3 * static_cast<int>(scene.pins.size()) + static_cast<int>(scene.distances.size()) + 20;

  std::string x;
  x += "<mujoco model=\"peer\">\n";
  x += "  <option timestep=\"" + num(dt) + "\" gravity=\"" + vec(scene.gravity) + "\"/>\n";
  x += "  <size njmax=\"" + std::to_string(model.njmax) + "\" nconmax=\"" + std::to_string(model.nconmax) + "\"/>\n";
  x += "  <worldbody>\n";
  if (scene.ground) {
    // Ground contacts are the explicit pairs below, so the plane takes part in no other.
    x += "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\" pos=\"" + vec(scene.groundNormal * scene.groundHeight) +
         "\" zaxis=\"" + vec(scene.groundNormal) + "\" contype=\"0\" conaffinity=\"0\"/>\n";
  }

  // Sites for the tendons, grouped by body.
  std::vector<std::vector<std::pair<int, phys::Vec3>>> sites(scene.bodies.size());
  for (std::size_t k = 0; k < scene.distances.size(); ++k) {
    const Distance& d = scene.distances[k];
    sites[static_cast<std::size_t>(d.a)].emplace_back(static_cast<int>(2 * k), d.localA);
    sites[static_cast<std::size_t>(d.b)].emplace_back(static_cast<int>(2 * k + 1), d.localB);
  }

  double boxFriction = -1.0;
  bool frictionsDiffer = false;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    const std::string id = std::to_string(i);
    x += "    <body name=\"b" + id + "\" pos=\"" + vec(b.centre) + "\" quat=\"" + quat(b.orientation) + "\">\n";
    if (!b.fixed) {
      x += "      <freejoint/>\n";
      x += "      <inertial pos=\"0 0 0\" mass=\"" + num(b.mass) + "\" diaginertia=\"" + vec(b.inertia) + "\"/>\n";
    }
    if (b.shape == Body::Shape::Box) {
      x += "      <geom name=\"g" + id + "\" type=\"box\" size=\"" + vec(b.halfExtents) + "\" friction=\"" + friction(b.friction) +
           "\" contype=\"1\" conaffinity=\"1\"/>\n";
      if (boxFriction >= 0.0 && boxFriction != b.friction) frictionsDiffer = true;
      boxFriction = b.friction;
    } else {
      x += "      <geom name=\"g" + id + "\" type=\"sphere\" size=\"" + num(b.radius) + "\" contype=\"0\" conaffinity=\"0\"/>\n";
    }
    for (const auto& [site, local] : sites[i]) {
      x += "      <site name=\"s" + std::to_string(site) + "\" pos=\"" + vec(local) + "\"/>\n";
    }
    x += "    </body>\n";
  }
  x += "  </worldbody>\n";
  if (frictionsDiffer) model.notes.push_back("boxes of different friction meet with the larger coefficient (MuJoCo's rule), not the geometric mean");

  x += "  <contact>\n";
  if (scene.ground) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      if (b.fixed) continue;
      const double mu = std::sqrt(b.friction * scene.groundFriction);
      x += "    <pair geom1=\"ground\" geom2=\"g" + std::to_string(i) + "\" condim=\"3\" friction=\"" + num(mu) + " " + num(mu) +
           " 0.005 0.0001 0.0001\"/>\n";
    }
  }
  // MuJoCo's contype/conaffinity test is an OR of two ANDs; ours (group against mask both
  // ways) is an AND, so pairs our filter keeps apart are excluded one by one.
  std::vector<std::pair<int, int>> excluded = scene.ignored;
  if (!scene.defaultFiltering) {
    excluded.clear();
    const int n = static_cast<int>(scene.bodies.size());
    for (int i = 0; i < n; ++i) {
      if (scene.bodies[static_cast<std::size_t>(i)].shape != Body::Shape::Box) continue;
      for (int j = i + 1; j < n; ++j) {
        if (scene.bodies[static_cast<std::size_t>(j)].shape == Body::Shape::Box && !scene.collides(i, j)) excluded.emplace_back(i, j);
      }
    }
  }
  for (const auto& [a, b] : excluded) {
    x += "    <exclude body1=\"b" + std::to_string(a) + "\" body2=\"b" + std::to_string(b) + "\"/>\n";
  }
  x += "  </contact>\n";

  if (!scene.distances.empty()) {
    x += "  <tendon>\n";
    for (std::size_t k = 0; k < scene.distances.size(); ++k) {
      const Distance& d = scene.distances[k];
      x += "    <spatial name=\"t" + std::to_string(k) + "\"";
      if (!d.rigid()) {
        // A one-sided range has no upper bound; MuJoCo wants a number.
        x += " limited=\"true\" range=\"" + num(d.min) + " " + num(std::isfinite(d.max) ? d.max : 1e10) + "\"";
      }
      x += "><site site=\"s" + std::to_string(2 * k) + "\"/><site site=\"s" + std::to_string(2 * k + 1) + "\"/></spatial>\n";
    }
    x += "  </tendon>\n";
  }

  x += "  <equality>\n";
  bool apart = false;
  for (const Pin& p : scene.pins) {
    // The connect's anchor is in body1's frame; MuJoCo finds body2's point from the pose the
    // model is written in, so a pin whose points start apart would be held apart.
    if (glm::length(p.worldB - p.worldA) > 1e-9) apart = true;
    x += "    <connect body1=\"b" + std::to_string(p.a) + "\" body2=\"b" + std::to_string(p.b) + "\" anchor=\"" + vec(p.localA) + "\"/>\n";
  }
  for (std::size_t k = 0; k < scene.distances.size(); ++k) {
    const Distance& d = scene.distances[k];
    if (!d.rigid()) continue;
    // With one tendon the equality holds its length at the reference (its length as written)
    // plus polycoef[0].
    const double offset = d.min - glm::length(d.worldB - d.worldA);
    x += "    <tendon tendon1=\"t" + std::to_string(k) + "\" polycoef=\"" + num(offset) + " 0 0 0 0\"/>\n";
  }
  x += "  </equality>\n";
  x += "</mujoco>\n";
  if (apart) model.notes.push_back("pins whose points start apart held at their distance");
  if (scene.restitution > 0.0) model.notes.push_back("restitution not expressed");
  model.xml = std::move(x);
  return model;
}

const char* solverName(int s) { return s == mjSOL_PGS ? "PGS" : s == mjSOL_CG ? "CG" : "Newton"; }
const char* integratorName(int i) { return i == mjINT_EULER ? "Euler" : i == mjINT_RK4 ? "RK4" : "implicit"; }

class MujocoEngine : public Engine {
 public:
  MujocoEngine(const Description& scene, double dt) : scene_(scene) {
    Model written = writeModel(scene, dt);
    notes = written.notes;

    auto vfs = std::make_unique<mjVFS>();  // about 2 MB: not for the stack
    mj_defaultVFS(vfs.get());
    const char* file = "peer.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(written.xml.size())) != 0) throw std::runtime_error("MuJoCo: no room in its VFS");
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], written.xml.data(), written.xml.size());
    char error[1000] = "";
    model_ = mj_loadXML(file, vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (model_ == nullptr) {
      const std::string why = error;
      if (why.find("could not create mjData") != std::string::npos) {
        throw std::runtime_error("too large for MuJoCo " + std::string(mj_versionString()) + ", whose buffers grow as njmax^2 (" +
                                 std::to_string(written.njmax) + " rows)");
      }
      throw std::runtime_error("MuJoCo refused the model: " + why);
    }
    data_ = mj_makeData(model_);
    if (data_ == nullptr) {
      mj_deleteModel(model_);
      throw std::runtime_error("too large for MuJoCo " + std::string(mj_versionString()) + ": no memory for mjData");
    }

    const mjOption& o = model_->opt;
    settings = "MuJoCo " + std::string(mj_versionString()) + ": " + solverName(o.solver) + ", " +
               (o.cone == mjCONE_PYRAMIDAL ? "pyramidal" : "elliptic") + " cones, " + integratorName(o.integrator) + ", up to " +
               std::to_string(o.iterations) + " iterations";

    ids_.resize(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "b" + std::string.
      std::string name = "b";
      name += std::to_string(i);
      const int id = mj_name2id(model_, mjOBJ_BODY, name.c_str());
      ids_[i] = id;
      const Body& b = scene.bodies[i];
      if (b.fixed) continue;
      // A free joint's velocity is the centre's, in the world frame, then the spin in the
      // body's own frame.
      const int dof = model_->body_dofadr[id];
      const phys::Vec3 spin = glm::inverse(b.orientation) * b.angularVelocity;
      for (int k = 0; k < 3; ++k) {
        data_->qvel[dof + k] = b.velocity[k];
        data_->qvel[dof + 3 + k] = spin[k];
      }
    }
  }

  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }

  void step() override {
    if (scene_.damping > 0.0) damp();
    mj_step(model_, data_);
  }

  void finish() override {
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) {
      notes.push_back("contacts beyond nconmax " + std::to_string(model_->nconmax) + " dropped");
    }
    if (data_->warning[mjWARN_CNSTRFULL].number > 0) {
      notes.push_back("constraints beyond njmax " + std::to_string(model_->njmax) + " dropped");
    }
    if (data_->warning[mjWARN_BADQACC].number > 0 || data_->warning[mjWARN_BADQPOS].number > 0 ||
        data_->warning[mjWARN_BADQVEL].number > 0) {
      notes.push_back("MuJoCo reset the run after bad numbers");
    }
  }

  phys::Vec3 position(int i) const override {
    const mjtNum* p = data_->xpos + 3 * ids_[static_cast<std::size_t>(i)];
    return {p[0], p[1], p[2]};
  }
  phys::Quat orientation(int i) const override {
    const mjtNum* q = data_->xquat + 4 * ids_[static_cast<std::size_t>(i)];
    return {q[0], q[1], q[2], q[3]};
  }

 private:
  // Our wind resistance as forces for this step: -c m v and -c I omega (the inertia and spin in
  // the body frame, the torque turned into the world's, which xfrc_applied wants).
  void damp() {
    const double c = scene_.damping;
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
      const Body& b = scene_.bodies[i];
      if (b.fixed) continue;
      const int id = ids_[i];
      const int dof = model_->body_dofadr[id];
      const mjtNum* q = data_->qpos + model_->jnt_qposadr[model_->body_jntadr[id]] + 3;
      const phys::Quat r(q[0], q[1], q[2], q[3]);
      const phys::Vec3 v(data_->qvel[dof], data_->qvel[dof + 1], data_->qvel[dof + 2]);
      const phys::Vec3 w(data_->qvel[dof + 3], data_->qvel[dof + 4], data_->qvel[dof + 5]);
      const phys::Vec3 force = -c * b.mass * v;
      const phys::Vec3 torque = r * (-c * b.inertia * w);
      mjtNum* f = data_->xfrc_applied + 6 * id;
      for (int k = 0; k < 3; ++k) {
        f[k] = force[k];
        f[3 + k] = torque[k];
      }
    }
  }

  const Description& scene_;
  Hooks hooks_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  std::vector<int> ids_;  // MuJoCo body id of each description body
};

}  // namespace

std::unique_ptr<Engine> makeMujoco(const Description& scene, double dt) { return std::make_unique<MujocoEngine>(scene, dt); }

}  // namespace lab::peers
