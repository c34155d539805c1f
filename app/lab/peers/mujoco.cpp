// MuJoCo (Debian's libmujoco-dev 2.2.2): the scene written as MJCF text (mujoco_model.h),
// loaded with mj_loadXML from a virtual file in memory, stepped by mj_step1 and mj_step2 with
// every option at MuJoCo's default but the timestep (= dt) and gravity: Newton solver,
// pyramidal friction cones, Euler integrator, up to 100 iterations, soft constraints at the
// default solref and solimp (which MuJoCo's refsafe keeps at a time constant of at least two
// steps). The world's damping is applied between the two halves of the step through
// xfrc_applied: -c m v on each body's centre and -c I omega about it, what our exp(-c t) decay of
// every particle's velocity is, from the velocities of that very step.
//
// Size: 2.2.2 allocates a step's whole workspace up front in one buffer of at most 2 GiB
// (mujoco_size.h). The scene is written with free bodies first; when that form cannot hold its
// constraint rows, it is written again as a kinematic tree, MuJoCo's own form, which needs no
// rows for its joints and six times fewer coordinates (the table says which); when neither fits,
// MuJoCo refuses the scene and the message gives the numbers. Contacts or rows past what was
// allocated are dropped by MuJoCo with a warning, and the table says that too.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "mujoco_model.h"
#include "mujoco_size.h"
#include "peer_scene.h"

namespace lab::peers {
namespace {

// MuJoCo reports errors through a global hook that must not return (the engine carries on
// otherwise); throwing is what MuJoCo's own compiler does from it. Warnings would go to
// stdout and a MUJOCO_LOG.TXT in the current folder; they are kept for the table instead.
std::string g_lastWarning;
void throwError(const char* message) {
  throw std::runtime_error(std::string("MuJoCo error: ") + message);
}
void keepWarning(const char* message) {
  g_lastWarning = message;
}

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

const char* solverName(int s) {
  return s == mjSOL_PGS ? "PGS" : s == mjSOL_CG ? "CG" : "Newton";
}
const char* integratorName(int i) {
  return i == mjINT_EULER ? "Euler" : i == mjINT_RK4 ? "RK4" : "implicit";
}

// Compiles MJCF text; throws with MuJoCo's message when it refuses.
mjModel* compile(const std::string& xml) {
  auto vfs = std::make_unique<mjVFS>();  // about 2 MB: not for the stack
  mj_defaultVFS(vfs.get());
  const char* file = "peer.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(xml.size())) != 0)
    throw std::runtime_error("MuJoCo: no room in its VFS");
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* model = mj_loadXML(file, vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (model == nullptr) throw std::runtime_error("MuJoCo refused the model: " + std::string(error));
  return model;
}

class MujocoEngine : public Engine {
 public:
  MujocoEngine(const Description& scene, double dt, bool forceTree)
      : Engine(scene.bodies.size()), scene_(scene) {
    build(dt, forceTree);
    data_ = mj_makeData(model_);
    if (data_ == nullptr) {
      mj_deleteModel(model_);
      throw std::runtime_error("too large for MuJoCo " + std::string(mj_versionString()) +
                               ": no memory for mjData");
    }
    const mjOption& o = model_->opt;
    settings = "MuJoCo " + std::string(mj_versionString()) + ": " + solverName(o.solver) + ", " +
               (o.cone == mjCONE_PYRAMIDAL ? "pyramidal" : "elliptic") + " cones, " +
               integratorName(o.integrator) + ", up to " + std::to_string(o.iterations) + " iterations" +
               (tree_ ? ", joints as a kinematic tree" : "");
    ids_.resize(scene.bodies.size());
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "b" + std::string.
      std::string name = "b";
      name += std::to_string(i);
      ids_[i] = mj_name2id(model_, mjOBJ_BODY, name.c_str());
    }
    setVelocities();
  }

  ~MujocoEngine() override {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }

  void step() override {
    mj_step1(model_, data_);
    if (scene_.damping > 0.0) damp();
    mj_step2(model_, data_);
    stale_ = true;
    // MuJoCo answers bad numbers by putting the bodies back where they began and going on: poses
    // that look sound but are no run's. From then on the run has blown up (pose reads NaN).
    if (!reset_ && badNumbers()) reset_ = true;
  }

  void finish() override {
    dropped = data_->warning[mjWARN_CONTACTFULL].number > 0 || data_->warning[mjWARN_CNSTRFULL].number > 0;
    if (data_->warning[mjWARN_CONTACTFULL].number > 0) {
      notes.push_back("contacts beyond nconmax " + std::to_string(model_->nconmax) + " dropped");
    }
    if (data_->warning[mjWARN_CNSTRFULL].number > 0) {
      notes.push_back("constraints beyond njmax " + std::to_string(model_->njmax) + " dropped (" +
                      std::to_string(wanted_) + " wanted; MuJoCo 2.2.2's 2 GiB mjData holds no more at nv " +
                      std::to_string(model_->nv) + ")");
    }
    if (reset_)
      notes.push_back("MuJoCo reset the run after bad numbers (its poses from then on read not finite)");
  }

  phys::BodyPose pose(int i) const override {
    if (reset_) {
      constexpr double nan = std::numeric_limits<double>::quiet_NaN();
      return {{nan, nan, nan}, {nan, nan, nan, nan}};
    }
    sync();
    const auto id = static_cast<std::ptrdiff_t>(ids_[static_cast<std::size_t>(i)]);
    const mjtNum* p = data_->xpos + 3 * id;
    const mjtNum* q = data_->xquat + 4 * id;
    return {{p[0], p[1], p[2]}, {q[0], q[1], q[2], q[3]}};
  }

 private:
  // Compiles the scene in the free-body form, or in the tree form when the free-body form's rows
  // do not fit 2.2.2's buffer, and sets the sizes (mujoco_size.h) on the compiled model.
  void build(double dt, bool forceTree) {
    const mjcf::Model free = mjcf::writeModel(scene_, dt, false);
    const int freeRows = compileSized(free), freeDofs = model_->nv;
    const bool freeFits = freeRows >= free.rowsNeeded();
    if (freeFits && !forceTree) {
      use(free, freeRows);
      return;
    }
    mj_deleteModel(model_);
    model_ = nullptr;
    mjcf::Model tree = mjcf::writeModel(scene_, dt, true);
    const int rows = compileSized(tree);
    if (rows < tree.rowsNeeded()) {
      const std::string why = "too large for MuJoCo " + std::string(mj_versionString()) +
                              ", whose mjData buffer (an int of bytes: 2 GiB) grows as " +
                              "12 njmax^2 + 24 njmax nv: with free bodies it needs " +
                              std::to_string(free.rowsNeeded()) + " constraint rows and holds " +
                              std::to_string(freeRows) + " at nv " + std::to_string(freeDofs) +
                              ", as a kinematic tree " + std::to_string(tree.rowsNeeded()) + " and " +
                              std::to_string(rows) + " at nv " + std::to_string(model_->nv);
      mj_deleteModel(model_);
      throw std::runtime_error(why);
    }
    tree_ = true;
    if (!freeFits) {
      tree.notes.push_back("joints as a kinematic tree: with free bodies the pins need " +
                           std::to_string(free.equalityRows) + " rows, and MuJoCo 2.2.2's mjData holds " +
                           std::to_string(freeRows) + " at nv " + std::to_string(freeDofs));
    }
    use(tree, rows);
  }

  // Compiles the written model into model_; the most constraint rows its buffer holds.
  int compileSized(const mjcf::Model& written) {
    model_ = compile(written.xml);
    return mujoco_size::largestRows(*model_, written.contacts, written.rowsWanted());
  }

  // Runs the compiled model_ as `written` with room for `rows` constraint rows.
  void use(const mjcf::Model& written, int rows) {
    notes = written.notes;
    wanted_ = written.rowsWanted();
    model_->njmax = rows;
    model_->nconmax = written.contacts;
    model_->nstack =
        static_cast<int>(std::min<std::int64_t>(mujoco_size::stackFor(*model_, rows), 2147483647));
  }

  // Each body's velocity as the description gives it: a root's free joint takes the centre's
  // velocity (world frame) and the spin (body frame); a ball joint the spin relative to its
  // parent (child frame), a hinge that along its axis.
  void setVelocities() {
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
      const Body& b = scene_.bodies[i];
      const int id = ids_[i];
      if (b.fixed || model_->body_jntnum[id] == 0) continue;
      const int joint = model_->body_jntadr[id];
      const int dof = model_->jnt_dofadr[joint];
      const int parent = model_->body_parentid[id];
      phys::Vec3 parentSpin(0.0);
      for (std::size_t j = 0; j < scene_.bodies.size(); ++j) {
        if (ids_[j] == parent) parentSpin = scene_.bodies[j].angularVelocity;
      }
      const phys::Vec3 spin = glm::inverse(b.orientation) * (b.angularVelocity - parentSpin);
      switch (model_->jnt_type[joint]) {
        case mjJNT_FREE:
          for (int k = 0; k < 3; ++k) {
            data_->qvel[dof + k] = b.velocity[k];
            data_->qvel[dof + 3 + k] = spin[k];
          }
          break;
        case mjJNT_BALL:
          for (int k = 0; k < 3; ++k) data_->qvel[dof + k] = spin[k];
          break;
        case mjJNT_HINGE: {
          const mjtNum* axis =
              model_->jnt_axis + 3 * static_cast<std::ptrdiff_t>(joint);  // in the body's frame
          data_->qvel[dof] = spin.x * axis[0] + spin.y * axis[1] + spin.z * axis[2];
          break;
        }
        default:
          break;
      }
    }
  }

  // Our wind resistance as forces for this step: -c m v and -c I omega, from the velocities
  // mj_step1 has just computed (mj_objectVelocity: spin and the velocity of the body's origin,
  // its centre, in the world frame), the inertia in the body's frame.
  void damp() {
    const double c = scene_.damping;
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
      const Body& b = scene_.bodies[i];
      if (b.fixed) continue;
      const int id = ids_[i];
      mjtNum v[6];
      mj_objectVelocity(model_, data_, mjOBJ_BODY, id, v, 0);
      const mjtNum* q = data_->xquat + 4 * static_cast<std::ptrdiff_t>(id);
      const phys::Quat r(q[0], q[1], q[2], q[3]);
      const phys::Vec3 spin = glm::inverse(r) * phys::Vec3(v[0], v[1], v[2]);
      const phys::Vec3 force = -c * b.mass * phys::Vec3(v[3], v[4], v[5]);
      const phys::Vec3 torque = r * (-c * b.inertia * spin);
      mjtNum* f = data_->xfrc_applied + 6 * static_cast<std::ptrdiff_t>(id);
      for (int k = 0; k < 3; ++k) {
        f[k] = force[k];
        f[3 + k] = torque[k];
      }
    }
  }

  bool badNumbers() const {
    return data_->warning[mjWARN_BADQACC].number > 0 || data_->warning[mjWARN_BADQPOS].number > 0 ||
           data_->warning[mjWARN_BADQVEL].number > 0;
  }

  // A step computes the bodies' poses (xpos, xquat) from the coordinates it starts with and
  // then integrates them, so after it they are one step old. Read, they are brought up to date
  // first (mj_kinematics: the poses alone), outside the timed step.
  void sync() const {
    if (!stale_) return;
    mj_kinematics(model_, data_);
    stale_ = false;
  }

  const Description& scene_;
  Hooks hooks_;
  mutable bool stale_ = false;  // xpos and xquat lag qpos by the last step
  bool reset_ = false;          // MuJoCo reset the data after bad numbers: no pose is the run's
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  bool tree_ = false;     // written as a kinematic tree
  int wanted_ = 0;        // the constraint rows the scene wants; njmax is fewer when capped
  std::vector<int> ids_;  // MuJoCo body id of each description body
};

}  // namespace

std::unique_ptr<Engine> makeMujoco(const Description& scene, double dt) {
  return std::make_unique<MujocoEngine>(scene, dt, false);
}
std::unique_ptr<Engine> makeMujocoTree(const Description& scene, double dt) {
  return std::make_unique<MujocoEngine>(scene, dt, true);
}

}  // namespace lab::peers
