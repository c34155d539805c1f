#include "peer_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include <glm/geometric.hpp>

#include "bodies.h"
#include "physics/body.h"

namespace lab::peers {
namespace {

using phys::Vec3;

// The velocity a particle has now. World::velocity is the mean over the last substep, (x - x*) / h;
// for a world not yet stepped x* was set so that Verlet's first step is exact under gravity,
// x* = x - (v - g h / 2) h (docs/physics.md), so the velocity of the moment is that mean plus
// g h / 2. The same correction turns a stepped world's mean into the end-of-substep velocity.
Vec3 particleVelocity(const phys::World& world, phys::ParticleId id) {
  const phys::SolverSettings& s = world.solverSettings();
  const double h = s.dt / s.substeps;
  return world.velocity(id) + world.gravityAt(world.particles().position[id]) * (0.5 * h);
}

Vec3 toLocal(const Body& body, const Vec3& p) {
  return glm::inverse(body.orientation) * (p - body.centre);
}

// Box id as a rigid body. Mass, inertia and motion as the physics has them (World::bodyMass,
// poseVelocity). A capsule's particles sit on its box as a box's do, so it gets its box's inertia
// and the engines turn it as ours turns.
Body boxBody(const phys::World& world, phys::BodyId id) {
  const phys::Body& box = world.bodies()[id];
  const phys::BodyPose pose = world.bodyPose(id);
  Body body;
  body.shape = box.shape == phys::Shape::Capsule ? Body::Shape::Capsule : Body::Shape::Box;
  body.name = box.name;
  body.centre = pose.center;
  body.orientation = pose.orientation;
  body.halfExtents = box.halfExtents;
  body.model = box.model;
  if (body.shape == Body::Shape::Capsule) {
    body.radius = box.capsuleRadius();
    body.halfSegment = std::max(0.0, box.capsuleHalfSegment());
  }
  body.friction = box.material.dynamicFriction;
  body.group = box.collisionGroup;
  body.mask = box.collisionMask;
  const phys::BodyMass mass = world.bodyMass(id);
  body.fixed = mass.fixed();
  if (!body.fixed) {
    body.mass = mass.mass;
    body.inertia = mass.inertia;
    std::tie(body.velocity, body.angularVelocity) = world.poseVelocity(id);
  }
  return body;
}

// Loose particle i as a small solid sphere, with the friction of its ground contact (`contact`,
// or null for none: the default material's).
Body looseBody(const phys::World& world, phys::ParticleId i, const phys::GroundContact* contact) {
  const phys::Particles& particles = world.particles();
  Body body;
  body.shape = Body::Shape::Sphere;
  body.name = world.particleName(i);
  body.centre = particles.position[i];
  body.radius = kParticleRadius;
  body.fixed = particles.inverseMass[i] == 0.0;
  body.mass = body.fixed ? 0.0 : 1.0 / particles.inverseMass[i];
  body.inertia = Vec3(0.4 * body.mass * kParticleRadius * kParticleRadius);
  if (!body.fixed) body.velocity = particleVelocity(world, i);
  body.friction = contact != nullptr ? contact->material.dynamicFriction : phys::Material{}.dynamicFriction;
  return body;
}

}  // namespace

Vec3 toWorld(const Vec3& centre, const phys::Quat& orientation, const Vec3& p) {
  return centre + orientation * p;
}

bool Description::collides(int i, int j) const {
  const Body& a = bodies[static_cast<std::size_t>(i)];
  const Body& b = bodies[static_cast<std::size_t>(j)];
  if (i == j || !a.solid() || !b.solid()) return false;
  if ((a.group & b.mask) == 0 || (b.group & a.mask) == 0) return false;
  return !std::binary_search(ignored.begin(), ignored.end(),
                             std::pair<int, int>(std::min(i, j), std::max(i, j)));
}

int Description::solidCount() const {
  return static_cast<int>(
      std::count_if(bodies.begin(), bodies.end(), [](const Body& b) { return b.solid(); }));
}

Description describe(const scenes::Scene& scene) {
  const phys::World& world = scene.world;
  const phys::WorldSettings& ws = world.worldSettings();
  const phys::SolverSettings& solver = world.solverSettings();
  const phys::Particles& particles = world.particles();

  Description d;
  if (ws.gravityMode == phys::GravityMode::Point) {
    d.refused = "point gravity (a pull towards a point)";
  }
  d.gravity = ws.gravity;
  d.ground = ws.ground;
  d.groundNormal = ws.groundNormal;
  d.groundHeight = ws.groundHeight;
  d.groundFriction = ws.groundMaterial.dynamicFriction;
  d.damping = ws.damping;
  d.restitution = solver.restitution;

  // Which body each particle belongs to, in bodies.h order: boxes by id, then loose particles.
  const std::vector<std::size_t> owner = particleBodies(world);
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    d.bodies.push_back(boxBody(world, id));
    if (d.bodies.back().group != 1u || d.bodies.back().mask != 0xffffffffu) d.defaultFiltering = false;
  }

  // Loose particles keep the material of their ground contact point.
  std::vector<const phys::GroundContact*> contactOf(particles.size(), nullptr);
  for (const phys::GroundContact& c : world.groundContacts()) {
    if (c.body == phys::kNoBody && c.point.count == 1) contactOf[c.point.particle[0]] = &c;
  }
  for (const phys::ParticleId i : looseParticles(world))
    d.bodies.push_back(looseBody(world, i, contactOf[i]));

  // The body an embedded point belongs to: all its particles are one body's (a box's anchor
  // or a loose particle); -1 when they are not, which no scene file can make.
  auto bodyOf = [&](const phys::Embedding& e) {
    const std::size_t b = owner[e.particle[0]];
    for (int k = 1; k < e.count; ++k) {
      if (owner[e.particle[static_cast<std::size_t>(k)]] != b) return -1;
    }
    return static_cast<int>(b);
  };
  const auto bodyAt = [&](int i) -> const Body& { return d.bodies[static_cast<std::size_t>(i)]; };
  // A constraint's ends on bodies a and b, at the world points pa and pb.
  const auto endsOf = [&](int a, int b, const Vec3& pa, const Vec3& pb) {
    return Ends{a, b, toLocal(bodyAt(a), pa), toLocal(bodyAt(b), pb), pa, pb};
  };
  // Nothing to hold between two bodies that never move.
  const auto bothFixed = [&](int a, int b) { return bodyAt(a).fixed && bodyAt(b).fixed; };

  bool compliant = false;
  for (const phys::Stick& s : world.sticks()) {
    const int a = static_cast<int>(owner[s.a]), b = static_cast<int>(owner[s.b]);
    if (a == b) continue;  // a box's own sticks: the rigid body is them
    if (s.compliance > 0.0) compliant = true;
    if (bothFixed(a, b)) continue;
    d.distances.push_back(
        {endsOf(a, b, particles.position[s.a], particles.position[s.b]), s.minLength, s.maxLength});
  }
  if (compliant) d.notes.push_back("compliant sticks made rigid");
  if (solver.method == phys::SolverMethod::Xpbd && solver.compliance > 0.0) {
    d.notes.push_back("the global compliance not expressed (sticks rigid)");
  }

  // The body a link's end belongs to: a rigid body, or as bodyOf.
  auto endOf = [&](const phys::BodyPoint& p) {
    return p.side == phys::ContactSide::Rigid ? static_cast<int>(world.rigidBodies().body[p.rigid])
                                              : bodyOf(p.point);
  };
  std::vector<phys::RigidLink> links;
  for (const phys::Link& link : world.links()) {
    links.push_back({phys::BodyPoint::embedded(link.a), phys::BodyPoint::embedded(link.b), link.minLength,
                     link.maxLength});
  }
  links.insert(links.end(), world.rigidLinks().begin(), world.rigidLinks().end());
  int crossing = 0;
  for (const phys::RigidLink& link : links) {
    const int a = endOf(link.a), b = endOf(link.b);
    if (a < 0 || b < 0) {
      ++crossing;
      continue;
    }
    if (a == b) continue;  // both ends in one rigid body: nothing to hold
    if (bothFixed(a, b)) continue;
    const Ends ends = endsOf(a, b, world.position(link.a), world.position(link.b));
    if (link.isPin()) {
      d.pins.push_back({ends});
    } else {
      d.distances.push_back({ends, link.minLength, link.maxLength, true});
    }
  }
  if (crossing > 0)
    d.notes.push_back(std::to_string(crossing) + " links with an end spread over two bodies left out");
  // A rigid joint as pins: one at the pivot, and a hinge's second on its axis; its stops and a
  // cone's limits have no pin or distance to be.
  for (std::size_t k = 0; k < world.rigidJoints().size(); ++k) {
    const phys::JointDesc j = world.jointDesc(k);
    std::vector<std::pair<Vec3, Vec3>> points{{j.pivot, j.pivotB}};
    if (j.kind == phys::JointKind::Hinge)
      points.emplace_back(j.pivot + 0.1 * j.axis, j.pivotB + 0.1 * j.axisB);
    for (const auto& [pa, pb] : points)
      d.pins.push_back({endsOf(static_cast<int>(j.a), static_cast<int>(j.b), pa, pb)});
  }
  if (!world.rigidJoints().empty())
    d.notes.push_back(std::to_string(world.rigidJoints().size()) +
                      " rigid joints as pins, their limits left out");

  for (const auto& [a, b] : world.ignoredCollisions())
    d.ignored.emplace_back(static_cast<int>(a), static_cast<int>(b));
  std::sort(d.ignored.begin(), d.ignored.end());
  return d;
}

Description asOurs(Description scene) {
  for (Body& b : scene.bodies)
    if (b.shape == Body::Shape::Sphere) b.radius = 0.0;
  return scene;
}

double groundPenetration(const Description& scene, const std::vector<phys::Vec3>& centres,
                         const std::vector<phys::Quat>& orientations) {
  if (!scene.ground) return 0.0;
  double deepest = 0.0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& b = scene.bodies[i];
    // A box's or a capsule's lowest point by the physics' own measure (phys::lowestAlong); a
    // sphere's, a loose particle's stand-in, below its centre by its radius.
    const double lowest =
        b.shape == Body::Shape::Sphere
            ? glm::dot(scene.groundNormal, centres[i]) - b.radius
            : phys::lowestAlong(b.shape == Body::Shape::Capsule ? phys::Shape::Capsule : phys::Shape::Box,
                                b.halfExtents, {centres[i], orientations[i]}, scene.groundNormal);
    // A body that has gone off to infinity or NaN is as deep as it gets, not silently skipped.
    if (!std::isfinite(lowest)) return std::numeric_limits<double>::infinity();
    deepest = std::max(deepest, scene.groundHeight - lowest);
  }
  return deepest;
}

}  // namespace lab::peers
