// ODE (Debian's libode-dev, double precision): a dWorld stepped by dWorldQuickStep, ODE's
// iterative solver (projected Gauss-Seidel, 20 iterations, ERP 0.2 and CFM as the world comes).
// The other stepper, dWorldStep, solves the whole system exactly and costs about the cube of
// the constraint count: minutes a step for a pile of ragdolls, so it is not what anyone runs
// there. Collision: a dHashSpace, dSpaceCollide each step and a contact joint per point dCollide
// finds (up to 8 a pair), dropped after the step.
//
// Mapping: the ground is a dPlane; a box a dBox on a body with our mass and our particles'
// inertia; a capsule a dCapsule (same mass and inertia), whose axis is the geom's local z, so it
// is turned onto the body's y by a geom offset and the body keeps our frame; a loose particle a
// dSphere of kParticleRadius (a geom without a body when pinned);
// a pin a ball joint with each body's own anchor; a stick a double-ball joint (dJointCreateDBall,
// ODE's fixed distance). A range stick or range link has no ODE joint; it becomes what ODE's
// own contacts are, a one-sided contact joint along the line between its points, made each step
// it is outside its range (frictionless, as deep as the range is exceeded). At the midpoint of
// the two points its Jacobian is exactly the distance's, since both points lie on the line.
// Friction: each contact gets the geometric mean of the two coefficients, as ours, with
// dContactApprox1 (the friction limit scales with the normal force: Coulomb's law; ODE's plain
// mode would cap the force at mu newtons). Restitution: dContactBounce with e, never below
// kRestitutionMinSpeed, as ours. The world's damping: ODE scales velocities by (1 - s) each step,
// so s = 1 - exp(-damping dt), linear and angular, with the speed threshold set to 0.
#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <stdexcept>

#include <ode/ode.h>

#include <glm/geometric.hpp>

#include "peer_scene.h"
#include "physics/settings.h"
#include "text.h"

#ifndef LAB_ODE_VERSION
#define LAB_ODE_VERSION ""
#endif

namespace lab::peers {
namespace {

// ODE prints its non-fatal messages (an LCP that did not converge, say) to stderr; the table
// is the place for what went wrong, so they are counted instead.
int g_odeMessages = 0;
void countMessage(int, const char*, va_list) {
  ++g_odeMessages;
}

constexpr int kMaxContactsPerPair = 8;

// ODE aborts the whole program (an internal assertion, not an error it returns) for a geom its hash
// space cannot place: it counts cells of at least 2^-3 m in ints, so 2^31 / 8 = 2.7e8 m is as far
// as it reaches (a box at 5e8 m aborted the first collision); and for a quaternion whose
// normalisation overflows, a turn of some 1e150 rad in a step. A scene may lie within our bound of
// up to 1e9 m, and a body thrown at 1e12 m/s or under a gravity of 1e20 m/s^2 gets there in a
// step, so the engine looks before the first step and after each: a scene that starts beyond them
// is not run, and a run that gets there stops, each with a message that says which body and where.
constexpr double kReach = 1e8;            // unit: m, from the origin along any axis
constexpr double kMostTurnPerStep = 1e6;  // unit: rad

// ODE's capsule lies along its geom's z; ours along the body's y. A turn of -90 degrees about x
// takes z to y: the geom's offset from its body, so the body's frame stays ours.
const phys::Quat kCapsuleOffset(std::sqrt(0.5), -std::sqrt(0.5), 0.0, 0.0);

// Why a body at `centre` spinning at `spin` could abort ODE's next step ("body 'b' is at (...) m,
// beyond the 1e+08 m ODE's collision reaches"), or "" when it cannot. No figure in the words is
// ever inf or nan: a state ODE has lost is said to be not finite.
std::string beyondReach(const std::string& name, const phys::Vec3& centre, const phys::Vec3& spin,
                        double dt) {
  const auto who = [&name] { return "body '" + name + "'"; };  // only when it says why: each step, each body
  if (!phys::finite(centre) || !phys::finite(spin))
    return who() + " has a position or spin that is not finite";
  if (!phys::insideBound(centre, kReach)) {
    return who() + " is at (" + formatNumber(centre.x) + ", " + formatNumber(centre.y) + ", " +
           formatNumber(centre.z) + ") m, beyond the " + formatNumber(kReach) + " m ODE's collision reaches";
  }
  // Each axis alone, so that no square overflows: within a factor of sqrt(3) of |w| dt.
  if (!(std::max({std::abs(spin.x), std::abs(spin.y), std::abs(spin.z)}) * dt <= kMostTurnPerStep)) {
    return who() + " spins at (" + formatNumber(spin.x) + ", " + formatNumber(spin.y) + ", " +
           formatNumber(spin.z) + ") rad/s, more than " + formatNumber(kMostTurnPerStep) +
           " rad a step, as far as ODE's integration is given";
  }
  return {};
}

void* tag(int index) {
  return reinterpret_cast<void*>(static_cast<std::intptr_t>(index) + 1);
}
int untag(dGeomID g) {
  return static_cast<int>(reinterpret_cast<std::intptr_t>(dGeomGetData(g))) - 1;
}

class OdeEngine : public Engine {
 public:
  OdeEngine(const Description& scene, double dt) : Engine(scene.bodies.size()), scene_(scene), dt_(dt) {
    // Before anything of ODE's is made, so that a refusal leaves nothing to free.
    for (const Body& b : scene.bodies) {
      if (const std::string why = beyondReach(b.name, b.centre, b.angularVelocity, dt); !why.empty())
        throw std::runtime_error(why);
    }
    dInitODE2(0);
    // dWorldQuickStep shuffles its rows from one random state for the whole process: seeded here,
    // a run is the same whatever ran before it (0 is ODE's own seed, so a first run is as it was).
    dRandSetSeed(0);
    dSetMessageHandler(&countMessage);
    messagesBefore_ = g_odeMessages;
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
    dWorldSetGravity(world_, scene.gravity.x, scene.gravity.y, scene.gravity.z);
    settings = std::string("ODE ") + LAB_ODE_VERSION + " (" + (sizeof(dReal) == 8 ? "double" : "float") +
               "): dWorldQuickStep, " + std::to_string(dWorldGetQuickStepNumIterations(world_)) +
               " iterations, ERP " + formatNumber(static_cast<double>(dWorldGetERP(world_))) + ", CFM " +
               formatNumber(static_cast<double>(dWorldGetCFM(world_)));

    if (scene.ground) {
      const phys::Vec3 n = scene.groundNormal;
      dGeomSetData(dCreatePlane(space_, n.x, n.y, n.z, scene.groundHeight), tag(-1));
    }

    const double damping = 1.0 - std::exp(-scene.damping * dt);
    bodies_.assign(scene.bodies.size(), nullptr);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      dGeomID geom = nullptr;
      if (b.shape == Body::Shape::Box) {
        geom = dCreateBox(space_, 2.0 * b.halfExtents.x, 2.0 * b.halfExtents.y, 2.0 * b.halfExtents.z);
      } else if (b.shape == Body::Shape::Capsule) {
        geom = dCreateCapsule(space_, b.radius, 2.0 * b.halfSegment);  // length: the core's
      } else {
        geom = dCreateSphere(space_, b.radius);
      }
      dGeomSetData(geom, tag(static_cast<int>(i)));
      const dQuaternion q = {b.orientation.w, b.orientation.x, b.orientation.y, b.orientation.z};
      if (b.fixed) {
        // A fixed body has no ODE body to carry an offset: the geom takes the turned pose itself,
        // and position() and orientation() report the pose it was given.
        const phys::Quat g = b.shape == Body::Shape::Capsule ? b.orientation * kCapsuleOffset : b.orientation;
        const dQuaternion gq = {g.w, g.x, g.y, g.z};
        dGeomSetPosition(geom, b.centre.x, b.centre.y, b.centre.z);
        dGeomSetQuaternion(geom, gq);
      } else {
        dBodyID created = dBodyCreate(world_);
        dMass mass;
        dMassSetZero(&mass);
        dMassSetParameters(&mass, b.mass, 0, 0, 0, b.inertia.x, b.inertia.y, b.inertia.z, 0, 0, 0);
        dBodySetMass(created, &mass);
        dBodySetPosition(created, b.centre.x, b.centre.y, b.centre.z);
        dBodySetQuaternion(created, q);
        dBodySetLinearVel(created, b.velocity.x, b.velocity.y, b.velocity.z);
        dBodySetAngularVel(created, b.angularVelocity.x, b.angularVelocity.y, b.angularVelocity.z);
        if (damping > 0.0) {
          dBodySetDamping(created, damping, damping);
          dBodySetLinearDampingThreshold(created, 0);
          dBodySetAngularDampingThreshold(created, 0);
        }
        dGeomSetBody(geom, created);
        if (b.shape == Body::Shape::Capsule) {
          const dQuaternion offset = {kCapsuleOffset.w, kCapsuleOffset.x, kCapsuleOffset.y, kCapsuleOffset.z};
          dGeomSetOffsetQuaternion(geom, offset);
        }
        bodies_[i] = created;
      }
    }

    for (const Pin& pin : scene.pins) {
      const Ends p = bodyFirst(pin);
      dJointID j = dJointCreateBall(world_, nullptr);
      dJointAttach(j, body(p.a), body(p.b));
      dJointSetBallAnchor(j, p.worldA.x, p.worldA.y, p.worldA.z);
      // A pin may start with its points apart: the second anchor on its own. ODE takes this
      // one as it stores it, in the second body's frame (the world's when there is none).
      const phys::Vec3 second = body(p.b) != nullptr ? p.localB : p.worldB;
      dJointSetBallAnchor2(j, second.x, second.y, second.z);
    }
    for (const Distance& d : scene.distances) {
      if (!d.rigid()) {
        ranges_.push_back(&d);
        continue;
      }
      const Ends e = bodyFirst(d);
      dJointID j = dJointCreateDBall(world_, nullptr);
      dJointAttach(j, body(e.a), body(e.b));
      dJointSetDBallAnchor1(j, e.worldA.x, e.worldA.y, e.worldA.z);
      dJointSetDBallAnchor2(j, e.worldB.x, e.worldB.y, e.worldB.z);
      dJointSetDBallDistance(j, d.min);
    }
  }

  ~OdeEngine() override {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // and its geoms
    dWorldDestroy(world_);  // and its bodies and joints
    dCloseODE();
  }

  void step() override {
    dSpaceCollide(space_, this, &OdeEngine::nearCallback);
    for (const Distance* d : ranges_) limit(*d);
    dWorldQuickStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }

  // Outside the step's clock: the run stops here if the next step could abort ODE.
  void afterStep(int step) override {
    if (const std::string why = outOfReach(); !why.empty())
      throw std::runtime_error("after step " + std::to_string(step) + ", " + why);
  }

  void finish() override {
    if (g_odeMessages != messagesBefore_) {
      notes.push_back("ODE printed " + std::to_string(g_odeMessages - messagesBefore_) + " solver messages");
    }
  }

  // The body's pose, not the geom's: a capsule's geom is turned from its body by the offset.
  phys::BodyPose pose(int i) const override {
    const Body& b = scene_.bodies[static_cast<std::size_t>(i)];
    if (body(i) == nullptr) return {b.centre, b.orientation};  // fixed: never moves
    const dReal* p = dBodyGetPosition(body(i));
    const dReal* q = dBodyGetQuaternion(body(i));
    return {{p[0], p[1], p[2]}, {q[0], q[1], q[2], q[3]}};
  }

 private:
  // The ODE body of description body i; null for a fixed one.
  dBodyID body(int i) const { return bodies_[static_cast<std::size_t>(i)]; }

  // ODE wants a body first: a joint to a fixed body holds the other body to the world.
  Ends bodyFirst(const Ends& e) const { return body(e.a) == nullptr ? e.swapped() : e; }

  static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
    static_cast<OdeEngine*>(data)->collide(g1, g2);
  }

  void collide(dGeomID g1, dGeomID g2) {
    const int a = untag(g1), b = untag(g2);
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (b1 == nullptr && b2 == nullptr) return;  // nothing that moves
    const bool withGround = a < 0 || b < 0;
    if (!withGround && !scene_.collides(a, b)) return;
    const double mu1 = a < 0 ? scene_.groundFriction : scene_.bodies[static_cast<std::size_t>(a)].friction;
    const double mu2 = b < 0 ? scene_.groundFriction : scene_.bodies[static_cast<std::size_t>(b)].friction;

    dContact contact[kMaxContactsPerPair];
    const int n = dCollide(g1, g2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    for (int k = 0; k < n; ++k) {
      dContact& c = contact[k];
      c.surface = dSurfaceParameters{};
      c.surface.mode = dContactApprox1;
      c.surface.mu = std::sqrt(mu1 * mu2);
      if (scene_.restitution > 0.0) {
        c.surface.mode |= dContactBounce;
        c.surface.bounce = scene_.restitution;
        c.surface.bounce_vel = phys::kRestitutionMinSpeed;
      }
      dJointID j = dJointCreateContact(world_, contacts_, &c);
      dJointAttach(j, b1, b2);
    }
  }

  // Why the next step could abort ODE, or "" (beyondReach).
  std::string outOfReach() const {
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      if (bodies_[i] == nullptr) continue;
      const dReal* p = dBodyGetPosition(bodies_[i]);
      const dReal* w = dBodyGetAngularVel(bodies_[i]);
      std::string why = beyondReach(scene_.bodies[i].name, {p[0], p[1], p[2]}, {w[0], w[1], w[2]},
                                    static_cast<double>(dt_));
      if (!why.empty()) return why;
    }
    return {};
  }

  // A range stick or link outside its range becomes a frictionless contact for this step.
  void limit(const Distance& d) {
    const phys::Vec3 pa = toWorld(position(d.a), orientation(d.a), d.localA);
    const phys::Vec3 pb = toWorld(position(d.b), orientation(d.b), d.localB);
    const phys::Vec3 between = pb - pa;
    const double length = glm::length(between);
    if (length >= d.min && length <= d.max) return;
    const phys::Vec3 n = length > 1e-9 ? between / length : phys::Vec3(0.0, 1.0, 0.0);
    const bool apart = length < d.min;  // too close: push b away from a
    dContact c{};
    c.surface.mode = 0;
    c.surface.mu = 0;
    const phys::Vec3 mid = 0.5 * (pa + pb);
    c.geom.pos[0] = mid.x;
    c.geom.pos[1] = mid.y;
    c.geom.pos[2] = mid.z;
    // A contact pushes its first body along its normal: b when pushing apart, a when pulling in.
    c.geom.normal[0] = n.x;
    c.geom.normal[1] = n.y;
    c.geom.normal[2] = n.z;
    c.geom.depth = apart ? d.min - length : length - d.max;
    const Ends first = apart ? d.swapped() : Ends(d);
    dJointAttach(dJointCreateContact(world_, contacts_, &c), body(first.a), body(first.b));
  }

  const Description& scene_;
  dReal dt_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<dBodyID> bodies_;  // description order; null for a fixed body
  std::vector<const Distance*> ranges_;
  int messagesBefore_ = 0;
};

}  // namespace

std::unique_ptr<Engine> makeOde(const Description& scene, double dt) {
  return std::make_unique<OdeEngine>(scene, dt);
}

}  // namespace lab::peers
