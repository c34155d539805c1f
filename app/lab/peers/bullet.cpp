// Bullet (Debian's libbullet-dev, single precision): btDiscreteDynamicsWorld with its default
// parts (btDefaultCollisionConfiguration, btCollisionDispatcher, btDbvtBroadphase,
// btSequentialImpulseConstraintSolver) and the default btContactSolverInfo (10 iterations,
// ERP 0.2, split impulse for penetration), stepped by stepSimulation(dt, 0): one substep of
// exactly dt, no interpolation. Sleeping is left on, as Bullet ships it, unless the description
// asks for none (every body DISABLE_DEACTIVATION).
//
// Mapping: the ground is a btStaticPlaneShape; a box a btBoxShape with our mass and our
// particles' inertia; a capsule a btCapsuleShape, whose core is along its local y as ours (the
// same mass and inertia as its box); a loose particle a btSphereShape of kParticleRadius
// (static when pinned);
// a pin a btPoint2PointConstraint; a stick, range stick or range link a DistanceLimit (below),
// the one constraint Bullet lacks. Friction: Bullet multiplies two bodies' coefficients, so each
// gets the square root of ours and the product is our geometric mean. Restitution likewise
// (sqrt(e) each, so every contact gets e). The world's damping becomes Bullet's per-body linear
// and angular damping, which Bullet applies as (1 - d)^dt: d = 1 - exp(-damping) decays both
// velocities by exp(-damping t), as our wind resistance decays every particle's.
#include <algorithm>
#include <cmath>
#include <string>

#include <btBulletDynamicsCommon.h>

#include "peer_scene.h"

namespace lab::peers {
namespace {

btVector3 bt(const phys::Vec3& v) {
  return {static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z)};
}
btQuaternion bt(const phys::Quat& q) {
  return {static_cast<btScalar>(q.x), static_cast<btScalar>(q.y), static_cast<btScalar>(q.z),
          static_cast<btScalar>(q.w)};
}

// A distance between a point of body A and a point of body B kept within [min, max]: one
// constraint row along the line between the points, made only while the distance is outside
// the range, so it acts like our projection and nothing in between. With min = max it is a
// rigid stick (a bilateral row); otherwise one-sided, pushing apart below min and pulling
// together above max. The Jacobian is exact for points off the centres (r x n terms), so a
// ragdoll's joint stops turn the parts as ours do.
class DistanceLimit : public btTypedConstraint {
 public:
  DistanceLimit(btRigidBody& a, btRigidBody& b, const btVector3& localA, const btVector3& localB, double min,
                double max)
      // The type only matters to Bullet's serializer and debug drawer, which are not used;
      // MAX_CONSTRAINT_TYPE matches none of Bullet's own classes, so nothing casts it to one.
      : btTypedConstraint(MAX_CONSTRAINT_TYPE, a, b),
        localA_(localA),
        localB_(localB),
        min_(min),
        max_(max) {}

  void getInfo1(btConstraintInfo1* info) override {
    measure();
    info->m_numConstraintRows = active_ ? 1 : 0;
    info->nub = active_ && min_ == max_ ? 1 : 0;
  }

  void getInfo2(btConstraintInfo2* info) override {
    // Bullet's rows read J v = c: with J = [n, rA x n, -n, -(rB x n)], J v is the rate at which
    // the distance shrinks, and c = k (d - target) drives it back at Bullet's ERP, as
    // btPoint2PointConstraint does. A positive impulse pulls the points together.
    const btVector3 rA = pointA_ - m_rbA.getCenterOfMassPosition();
    const btVector3 rB = pointB_ - m_rbB.getCenterOfMassPosition();
    const btVector3 angularA = rA.cross(normal_);
    const btVector3 angularB = rB.cross(normal_);
    for (int k = 0; k < 3; ++k) {
      info->m_J1linearAxis[k] = normal_[k];
      info->m_J1angularAxis[k] = angularA[k];
      if (info->m_J2linearAxis != nullptr) info->m_J2linearAxis[k] = -normal_[k];
      if (info->m_J2angularAxis != nullptr) info->m_J2angularAxis[k] = -angularB[k];
    }
    info->m_constraintError[0] = info->fps * info->erp * static_cast<btScalar>(distance_ - target_);
    if (min_ == max_) {
      info->m_lowerLimit[0] = -SIMD_INFINITY;
      info->m_upperLimit[0] = SIMD_INFINITY;
    } else if (distance_ < min_) {
      info->m_lowerLimit[0] = -SIMD_INFINITY;  // push apart only
      info->m_upperLimit[0] = 0;
    } else {
      info->m_lowerLimit[0] = 0;  // pull together only
      info->m_upperLimit[0] = SIMD_INFINITY;
    }
  }

  // Bullet's tuning hooks (per-constraint ERP and CFM); the defaults are what we measure.
  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }

 private:
  void measure() {
    pointA_ = m_rbA.getCenterOfMassTransform() * localA_;
    pointB_ = m_rbB.getCenterOfMassTransform() * localB_;
    const btVector3 d = pointB_ - pointA_;
    distance_ = static_cast<double>(d.length());
    // Two points on top of each other have no line between them; any direction will do for
    // the one step until they part (only a range with min > 0 can meet this).
    normal_ = distance_ > 1e-9 ? d / static_cast<btScalar>(distance_) : btVector3(0, 1, 0);
    active_ = distance_ < min_ || distance_ > max_;
    target_ = distance_ < min_ ? min_ : max_;  // used only while active
  }

  btVector3 localA_, localB_;
  double min_, max_;
  btVector3 pointA_{0, 0, 0}, pointB_{0, 0, 0}, normal_{0, 1, 0};
  double distance_ = 0.0;
  double target_ = 0.0;
  bool active_ = false;
};

// Bodies collide as they do in our world (Description::collides): the ground with every
// body, boxes with each other by group, mask and ignored pair, loose particles with nothing
// but the ground. Each collision object carries its body's index, the ground -1.
class Filter : public btOverlapFilterCallback {
 public:
  explicit Filter(const Description& scene) : scene_(scene) {}
  bool needBroadphaseCollision(btBroadphaseProxy* p0, btBroadphaseProxy* p1) const override {
    const int a = static_cast<const btCollisionObject*>(p0->m_clientObject)->getUserIndex();
    const int b = static_cast<const btCollisionObject*>(p1->m_clientObject)->getUserIndex();
    if (a < 0 || b < 0) return a != b;
    return scene_.collides(a, b);
  }

 private:
  const Description& scene_;
};

class BulletEngine : public Engine {
 public:
  BulletEngine(const Description& scene, double dt)
      : Engine(scene.bodies.size()),
        filter_(scene),
        dispatcher_(&config_),
        world_(&dispatcher_, &broadphase_, &solver_, &config_),
        dt_(static_cast<btScalar>(dt)) {
    settings = "Bullet " + std::to_string(btGetVersion() / 100) + "." + std::to_string(btGetVersion() % 100) +
               (sizeof(btScalar) == 8 ? " (double)" : " (float)") + ": sequential impulse, " +
               std::to_string(world_.getSolverInfo().m_numIterations) + " iterations, one step of dt" +
               (scene.sleep ? "" : ", no sleeping");
    world_.getPairCache()->setOverlapFilterCallback(&filter_);
    world_.setGravity(bt(scene.gravity));

    if (scene.ground) {
      shapes_.push_back(std::make_unique<btStaticPlaneShape>(bt(scene.groundNormal),
                                                             static_cast<btScalar>(scene.groundHeight)));
      btRigidBody* ground = addBody(*shapes_.back(), 0.0, btVector3(0, 0, 0), btTransform::getIdentity(), -1);
      ground->setFriction(static_cast<btScalar>(std::sqrt(scene.groundFriction)));
      ground->setRestitution(static_cast<btScalar>(std::sqrt(scene.restitution)));
    }

    const btScalar damping = static_cast<btScalar>(1.0 - std::exp(-scene.damping));
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      const Body& b = scene.bodies[i];
      if (b.shape == Body::Shape::Box) {
        shapes_.push_back(std::make_unique<btBoxShape>(bt(b.halfExtents)));
      } else if (b.shape == Body::Shape::Capsule) {
        // btCapsuleShape(radius, height) is Bullet's y-axis capsule; height is the core's length.
        shapes_.push_back(std::make_unique<btCapsuleShape>(static_cast<btScalar>(b.radius),
                                                           static_cast<btScalar>(2.0 * b.halfSegment)));
      } else {
        shapes_.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(b.radius)));
      }
      btRigidBody* body =
          addBody(*shapes_.back(), b.fixed ? 0.0 : b.mass, b.fixed ? btVector3(0, 0, 0) : bt(b.inertia),
                  btTransform(bt(b.orientation), bt(b.centre)), static_cast<int>(i));
      body->setFriction(static_cast<btScalar>(std::sqrt(b.friction)));
      body->setRestitution(static_cast<btScalar>(std::sqrt(scene.restitution)));
      if (!scene.sleep) body->setActivationState(DISABLE_DEACTIVATION);
      if (!b.fixed) {
        body->setLinearVelocity(bt(b.velocity));
        body->setAngularVelocity(bt(b.angularVelocity));
        body->setDamping(damping, damping);
      }
      bodies_.push_back(body);
    }

    for (const Pin& p : scene.pins)
      constraints_.push_back(
          std::make_unique<btPoint2PointConstraint>(body(p.a), body(p.b), bt(p.localA), bt(p.localB)));
    for (const Distance& d : scene.distances) {
      constraints_.push_back(
          std::make_unique<DistanceLimit>(body(d.a), body(d.b), bt(d.localA), bt(d.localB), d.min, d.max));
    }
    // Joined bodies still collide unless the scene says not (as ours do): the filter decides.
    for (auto& c : constraints_) world_.addConstraint(c.get(), false);
  }

  ~BulletEngine() override {
    // The world refers to the constraints and bodies; take them out before they go.
    for (auto& c : constraints_) world_.removeConstraint(c.get());
    for (auto& b : owned_) world_.removeRigidBody(b.get());
  }

  void step() override { world_.stepSimulation(dt_, 0); }

  // Sleeping makes resting bodies nearly free to step, so the table says when the time
  // measured is partly that of a world gone to sleep.
  void afterStep(int step) override {
    if (allAsleepFrom_ == 0 && moving() > 0 && asleep() == moving()) allAsleepFrom_ = step;
  }

  void finish() override {
    const int n = asleep();
    if (allAsleepFrom_ > 0) {
      notes.push_back("all bodies asleep from step " + std::to_string(allAsleepFrom_) +
                      " (Bullet's default deactivation)" + (n < moving() ? ", some woken since" : ""));
    } else if (n > 0) {
      notes.push_back(std::to_string(n) + " of " + std::to_string(moving()) +
                      " bodies asleep at the end (Bullet's default deactivation)");
    }
  }

  phys::BodyPose pose(int i) const override {
    const btVector3 p = body(i).getCenterOfMassPosition();
    const btQuaternion q = body(i).getOrientation();
    return {{p.x(), p.y(), p.z()}, {q.w(), q.x(), q.y(), q.z()}};
  }

 private:
  // The Bullet body of description body i.
  btRigidBody& body(int i) const { return *bodies_[static_cast<std::size_t>(i)]; }

  int moving() const {
    return static_cast<int>(std::count_if(bodies_.begin(), bodies_.end(),
                                          [](const btRigidBody* b) { return !b->isStaticObject(); }));
  }
  int asleep() const {
    return static_cast<int>(std::count_if(bodies_.begin(), bodies_.end(), [](const btRigidBody* b) {
      return !b->isStaticObject() && b->getActivationState() == ISLAND_SLEEPING;
    }));
  }

  btRigidBody* addBody(btCollisionShape& shape, double mass, const btVector3& inertia,
                       const btTransform& pose, int index) {
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(mass), nullptr, &shape, inertia);
    info.m_startWorldTransform = pose;
    owned_.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* body = owned_.back().get();
    body->setUserIndex(index);
    world_.addRigidBody(body);
    return body;
  }

  // Declared in the order they are needed; destroyed in reverse, the world before its parts.
  Filter filter_;
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> owned_;
  std::vector<std::unique_ptr<btTypedConstraint>> constraints_;
  std::vector<btRigidBody*> bodies_;  // description order
  btScalar dt_;
  int allAsleepFrom_ = 0;  // the first step after which every moving body slept; 0 if none
};

}  // namespace

std::unique_ptr<Engine> makeBullet(const Description& scene, double dt) {
  return std::make_unique<BulletEngine>(scene, dt);
}

}  // namespace lab::peers
