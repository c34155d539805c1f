#pragma once
// The scene as a rigid-body engine sees it, read once from our loaded world so that the three
// adapters build the same thing: one rigid body per body of bodies.h (a box for each box, a
// capsule for each capsule, a small sphere for each loose particle), the ground, and the
// constraints between bodies. Each
// adapter maps this description into its engine (bullet.cpp, ode.cpp, mujoco.cpp); what an
// engine cannot express it says in words, which end up in `lab compare`'s table.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "physics/body.h"
#include "physics/types.h"
#include "runner.h"
#include "scenes/scene.h"

namespace lab::peers {

/// Radius of the sphere that stands for a loose particle. Ours is a point, which no engine has;
/// 5 cm is small beside our bodies and large enough for the engines' contact margins (Bullet
/// keeps 4 cm around convex shapes). A particle resting on the ground rests this much higher.
inline constexpr double kParticleRadius = 0.05;

/// One rigid body, in bodies.h order.
struct Body {
  /// A capsule is one of our boxes of phys::Shape::Capsule: the capsule inscribed in its box,
  /// core along the body's local y axis. Its mass sits on the box's particles, so its inertia is
  /// the box's particles' (below), not a solid capsule's, in every engine.
  enum class Shape { Box, Sphere, Capsule };
  Shape shape = Shape::Box;
  std::string name;        ///< for messages; may be empty
  phys::Vec3 centre{0.0};  ///< unit: m
  phys::Quat orientation{1.0, 0.0, 0.0, 0.0};
  phys::Vec3 halfExtents{0.0};  ///< unit: m; a box's, or the box a capsule is inscribed in
  double radius = 0.0;          ///< unit: m; a sphere's or a capsule's
  double halfSegment = 0.0;     ///< unit: m; a capsule's core runs from -this to +this along local y
  bool fixed = false;           ///< a pinned particle (or a box holding one): never moves
  double mass = 0.0;            ///< unit: kg; the sum of its particles'
  /// Principal moments about the centre in the body frame, unit: kg m^2. A box gets its
  /// particles' own (three times a solid box's for both models, docs/physics.md), so the same
  /// push turns it the same in every engine; a sphere a solid sphere's.
  phys::Vec3 inertia{0.0};
  phys::BodyModel model = phys::BodyModel::Corners;  ///< a box's or capsule's: where its particles are
  phys::Vec3 velocity{0.0};                          ///< unit: m/s; of the centre
  phys::Vec3 angularVelocity{0.0};                   ///< unit: rad/s; world frame
  double friction = 0.0;                             ///< the material's dynamic coefficient
  std::uint32_t group = 1;                           ///< collision filtering, boxes and capsules only
  std::uint32_t mask = 0xffffffffu;

  /// A box or a capsule: one of our boxes, which collide with each other. A sphere (a loose
  /// particle) collides with the ground alone.
  bool solid() const { return shape != Shape::Sphere; }
};

/// What a constraint joins: a point of body a and a point of body b.
struct Ends {
  int a = 0, b = 0;
  phys::Vec3 localA{0.0}, localB{0.0};  ///< unit: m; in each body's frame
  phys::Vec3 worldA{0.0}, worldB{0.0};  ///< unit: m; where they are at the start
  /// The same ends with b first (an engine that wants a moving body first).
  Ends swapped() const { return {b, a, localB, localA, worldB, worldA}; }
};

/// A ball joint: a point of body a held on a point of body b (our pin link).
struct Pin : Ends {};

/// A distance between a point of body a and a point of body b kept within [min, max]: a stick
/// (min = max), a range stick, or a range link (a ragdoll's joint stop).
struct Distance : Ends {
  double min = 0.0;  ///< unit: m
  double max = 0.0;  ///< unit: m; may be infinite
  /// True for a range link (a joint stop), false for a stick: our joint gap counts links
  /// (Metrics::maxJointError), our stick error sticks, and the peers' are measured alike.
  bool link = false;
  bool rigid() const { return min == max; }
};

struct Description {
  phys::Vec3 gravity{0.0, -9.81, 0.0};  ///< unit: m/s^2
  bool ground = false;
  phys::Vec3 groundNormal{0.0, 1.0, 0.0};
  double groundHeight = 0.0;    ///< unit: m
  double groundFriction = 0.0;  ///< dynamic coefficient
  double damping = 0.0;         ///< unit: 1/s; velocities decay as exp(-damping t)
  double restitution = 0.0;
  /// Whether an engine with sleeping (Bullet's deactivation; ODE's auto-disable is off by default,
  /// MuJoCo 2.2 has none) may put resting bodies to sleep. Not read from the scene: the lab's
  /// choice (`lab compare --sleep`, `--peer-sleep`), off unless asked, as ours.
  bool sleep = false;
  std::vector<Body> bodies;
  std::vector<Pin> pins;
  std::vector<Distance> distances;
  /// Box pairs that never collide (World::ignoredCollisions), as (smaller, larger), sorted.
  std::vector<std::pair<int, int>> ignored;
  /// True when every box has group 1 and the full mask, so filtering is only `ignored`.
  bool defaultFiltering = true;
  /// What no engine here expresses, in words for the table; empty when everything is.
  std::vector<std::string> notes;
  /// Why the scene cannot be run by any engine at all (point gravity); empty when it can.
  std::string refused;

  /// Whether bodies i and j collide with each other: two solids (boxes or capsules) whose
  /// groups meet each other's masks and that are not an ignored pair. Our loose particles
  /// collide with the ground alone, so a sphere collides with no body.
  bool collides(int i, int j) const;
  int solidCount() const;  ///< boxes and capsules
};

/// Reads the description from a loaded world (normally not yet stepped).
Description describe(const scenes::Scene& scene);

/// The description our own world's poses are measured by: a loose particle is a point, not the
/// sphere that stands for it in a peer (which rests kParticleRadius up where ours rests at 0).
Description asOurs(Description scene);

/// Depth of the deepest point of any body below the ground: a box's corners, a sphere's surface,
/// a capsule's core ends less its radius (its box's corners are not on it). 0 without a ground.
double groundPenetration(const Description& scene, const std::vector<phys::Vec3>& centres,
                         const std::vector<phys::Quat>& orientations);

/// An engine built from a description, ready to step: the runner (runner.h) steps it as it steps
/// our world, each step() advancing by the dt it was built with and afterStep() called outside
/// the timing with the step's number (1-based).
class Engine : public Stepper {
 public:
  /// `bodies`: the description's count, whose poses positions() and orientations() read.
  explicit Engine(std::size_t bodies) : bodies_(bodies) {}
  /// Where body i (description order) is now, and how it is turned.
  virtual phys::BodyPose pose(int i) const = 0;
  phys::Vec3 position(int i) const { return pose(i).center; }
  phys::Quat orientation(int i) const { return pose(i).orientation; }
  std::vector<phys::Vec3> positions() const override { return each(&Engine::position); }
  std::vector<phys::Quat> orientations() const override { return each(&Engine::orientation); }
  /// Called once after the last step, untimed: adds to `notes` what the run showed (an engine
  /// that dropped contacts or reset itself).
  virtual void finish() {}
  /// What it could not express, in words (joined into PeerResult::unsupported); empty if all.
  std::vector<std::string> notes;
  /// Set by finish() when the engine ran out of the room it allocates up front and dropped
  /// contacts or constraints (MuJoCo 2.2.2's nconmax and njmax): the run is then not its
  /// solver's, and the notes say what was dropped.
  bool dropped = false;
  /// The solver and its settings, one line for the table.
  std::string settings;

 private:
  template <typename T>
  std::vector<T> each(T (Engine::*read)(int) const) const {
    std::vector<T> out;
    out.reserve(bodies_);
    for (std::size_t i = 0; i < bodies_; ++i) out.push_back((this->*read)(static_cast<int>(i)));
    return out;
  }

  std::size_t bodies_;
};

// The adapters, each in its own file and built only when its library is found. They throw
// std::runtime_error when the engine refuses the scene.
std::unique_ptr<Engine> makeBullet(const Description& scene, double dt);
std::unique_ptr<Engine> makeOde(const Description& scene, double dt);
std::unique_ptr<Engine> makeMujoco(const Description& scene, double dt);
/// MuJoCo with the scene's joints as a kinematic tree whatever its size: the form makeMujoco
/// falls back to for scenes too large for free bodies (mujoco_model.h), for the tests.
std::unique_ptr<Engine> makeMujocoTree(const Description& scene, double dt);

/// The engine of that name built from the description, or nullptr when it is not built in
/// (peers.cpp; the tests use it to step an engine themselves). "mujoco-tree" is MuJoCo forced
/// into the kinematic-tree form (makeMujocoTree), which no table lists.
std::unique_ptr<Engine> makeEngine(std::string_view name, const Description& scene, double dt);

/// The local point p of a body at `centre` with `orientation`, in world coordinates.
phys::Vec3 toWorld(const phys::Vec3& centre, const phys::Quat& orientation, const phys::Vec3& p);

}  // namespace lab::peers
