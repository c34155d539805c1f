// Saving a world as a scene file: settings, then every body in the order the world made them
// (so a reload gives each particle, box and stick the same index, and the solver visits them
// in the same order), then the sticks between loose particles, the links, the joints, the joints' friction
// and the pairs kept from colliding. Each box (or capsule) is saved as the rigid body fitted to its
// particles.
#include "scenes/scene_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "body_state.h"
#include "element_writer.h"
#include "euler_angles.h"
#include "fileio/files.h"
#include "generators.h"
#include "scene_paths.h"

namespace scenes {
namespace {

using detail::ElementWriter;

// One end of a link, as a <link> names it: a box, or a loose particle standing for itself.
struct LinkEnd {
  bool isBox = true;
  std::uint32_t index = 0;  // BodyId or ParticleId
};

// A link's end is carried by one box's particles (World::anchor) or is one loose particle;
// an embedding spread over several bodies has no name in a scene file.
LinkEnd linkEnd(const phys::Embedding& e, std::span<const phys::BodyId> owner) {
  const phys::BodyId first = owner[e.particle[0]];
  for (int i = 1; i < e.count; ++i) {
    if (owner[e.particle[i]] != first) {
      throw std::invalid_argument(
          "a link's end is carried by particles of different bodies; a <link> joins points "
          "of boxes and loose particles");
    }
  }
  if (first != phys::kNoBody) return {true, first};
  if (e.count != 1) {
    throw std::invalid_argument(
        "a link's end is carried by several loose particles; a <link> joins points of boxes "
        "and loose particles");
  }
  return {false, e.particle[0]};
}

// A rigid body's point is that body's.
LinkEnd linkEnd(const phys::World& world, const phys::BodyPoint& p, std::span<const phys::BodyId> owner) {
  if (p.side == phys::ContactSide::Rigid) return {true, world.rigidBodies().body[p.rigid]};
  return linkEnd(p.point, owner);
}

// The rigid bodies, which have no particles, in the order the world made them among the others:
// a rigid body made when the world had p particles comes before particle p (Body::firstParticle).
class RigidInOrder {
 public:
  explicit RigidInOrder(const phys::World& world) : bodies_(world.bodies()) {}
  /// Calls f for each rigid body not yet visited that was made before particle `particle`.
  template <typename F>
  void before(std::size_t particle, F f) {
    for (; next_ < bodies_.size(); ++next_) {
      const phys::Body& b = bodies_[next_];
      if (b.model != phys::BodyModel::Rigid) continue;
      if (b.firstParticle > particle) break;
      f(next_);
    }
  }

 private:
  std::span<const phys::Body> bodies_;
  phys::BodyId next_{};
};

// Unique names for every box (the loader needs them to attach links) and for every loose
// particle that has a name or that a stick or link refers to. Own names are kept in the order
// the world made the bodies (the first of two equal names keeps it); the rest become "box N"
// or "particle N" after their index, with a count appended should that be taken too.
class BodyNames {
 public:
  BodyNames(const phys::World& world, std::span<const phys::BodyId> owner,
            const std::vector<bool>& referenced)
      : box_(world.bodies().size()), particle_(world.particles().size()) {
    const std::span<const phys::Body> boxes = world.bodies();
    RigidInOrder rigid(world);
    for (std::size_t i = 0; i < particle_.size(); ++i) {
      rigid.before(i, [&](phys::BodyId b) { keepOwn(box_[b], boxes[b].name); });
      if (owner[i] == phys::kNoBody) {
        keepOwn(particle_[i], world.particleName(static_cast<phys::ParticleId>(i)));
      } else if (boxes[owner[i]].firstParticle == i) {
        keepOwn(box_[owner[i]], boxes[owner[i]].name);
      }
    }
    rigid.before(particle_.size(), [&](phys::BodyId b) { keepOwn(box_[b], boxes[b].name); });
    for (std::size_t b = 0; b < box_.size(); ++b) {
      if (box_[b].empty()) box_[b] = generated("box " + std::to_string(b));
    }
    for (std::size_t i = 0; i < particle_.size(); ++i) {
      if (owner[i] == phys::kNoBody && referenced[i] && particle_[i].empty()) {
        particle_[i] = generated("particle " + std::to_string(i));
      }
    }
  }

  const std::string& box(std::uint32_t id) const { return box_[id]; }
  const std::string& particle(std::uint32_t id) const { return particle_[id]; }
  const std::string& end(const LinkEnd& e) const { return e.isBox ? box_[e.index] : particle_[e.index]; }

 private:
  void keepOwn(std::string& slot, const std::string& own) {
    if (!own.empty() && taken_.insert(own).second) slot = own;
  }
  std::string generated(const std::string& base) {
    std::string name = base;
    for (int n = 2; !taken_.insert(name).second; ++n) name = base + " (" + std::to_string(n) + ")";
    return name;
  }

  std::vector<std::string> box_;
  std::vector<std::string> particle_;
  std::set<std::string> taken_;
};

std::string worldElement(const phys::WorldSettings& w) {
  return ElementWriter("world")
      .vector("gravity", w.gravity)
      .text("gravity-mode", phys::toString(w.gravityMode))
      .vector("gravity-point", w.gravityPoint)
      .number("gravity-strength", w.gravityStrength)
      .number("damping", w.damping)
      .number("bound", w.bound)
      .empty();
}

std::string solverElement(const phys::SolverSettings& s) {
  ElementWriter solver("solver");
  solver.text("method", phys::toString(s.method))
      .integer("iterations", s.iterations)
      .integer("substeps", s.substeps)
      .number("dt", s.dt)
      .number("epsilon", s.featureEpsilon)
      .number("slop", s.contactSlop)
      .number("body-damping", s.bodyDamping)
      .text("keep-spin", s.keepSpin ? "on" : "off")
      .number("restitution", s.restitution)
      .number("compliance", s.compliance);
  if (std::isfinite(s.maxDepenetrationSpeed))
    solver.number("depenetration-speed", s.maxDepenetrationSpeed);
  else
    solver.text("depenetration-speed", "none");
  solver.integer("threads", s.threads);
  solver.text("sleep", s.sleep.enabled ? "on" : "off")
      .number("sleep-speed", s.sleep.speed)
      .number("sleep-time", s.sleep.time)
      .text("joint-projection", s.jointProjection.enabled ? "on" : "off")
      .number("projection-tolerance", s.jointProjection.tolerance)
      .integer("projection-iterations", s.jointProjection.iterations);
  return solver.empty();
}

std::string groundElement(const phys::WorldSettings& w) {
  return ElementWriter("ground")
      .number("height", w.groundHeight)
      .vector("normal", w.groundNormal)
      .number("static-friction", w.groundMaterial.staticFriction)
      .number("dynamic-friction", w.groundMaterial.dynamicFriction)
      .empty();
}

std::string cameraElement(const CameraStart& camera, double bound) {
  // The loader refuses a camera looking at its own eye, or beyond the world's bound; better to
  // say so now than on reload.
  if (glm::length(camera.eye - camera.target) < 1e-6f) {
    throw std::invalid_argument("the camera's eye and target coincide");
  }
  if (!detail::insideBound(phys::Vec3(camera.eye), bound) ||
      !detail::insideBound(phys::Vec3(camera.target), bound)) {
    throw std::invalid_argument("the camera is beyond the world's bound of " + detail::formatNumber(bound) +
                                " m; bring it back first");
  }
  return ElementWriter("camera").vector("eye", camera.eye).vector("target", camera.target).empty();
}

// A box as a <box>, or one of Shape::Capsule as a <capsule>: the radius and whole length of the
// capsule inscribed in it, which the loader turns back into the same half extents exactly
// (doubling and halving a double are exact).
std::string boxElement(const phys::World& world, phys::BodyId id, const std::string& name) {
  const phys::Body& box = world.bodies()[id];
  const detail::RigidState state = detail::rigidState(world, id);
  const bool capsule = box.shape == phys::Shape::Capsule;
  ElementWriter e(capsule ? "capsule" : "box");
  e.text("name", name)
      .vector("pos", state.pose.center)
      .vector("euler", detail::eulerFromOrientation(state.pose.orientation));
  if (capsule)
    e.number("radius", box.capsuleRadius()).number("length", box.halfExtents.y * 2.0);
  else
    e.vector("size", box.halfExtents * 2.0);
  e.number("mass", state.mass)
      .text("model", phys::toString(box.model))
      .number("static-friction", box.material.staticFriction)
      .number("dynamic-friction", box.material.dynamicFriction);
  if (!state.frozen) {
    e.vector("velocity", state.velocity).vector("angular-velocity", glm::degrees(state.angularVelocity));
  }
  const phys::BodyDesc defaults;
  if (box.inertiaFloor != defaults.inertiaFloor) e.number("inertia-floor", box.inertiaFloor);
  if (box.collisionGroup != defaults.collisionGroup) e.integer("group", box.collisionGroup);
  if (box.collisionMask != defaults.collisionMask) e.integer("mask", box.collisionMask);
  return e.empty();
}

std::string particleElement(const phys::World& world, phys::ParticleId id, const std::string& name) {
  ElementWriter e("particle");
  if (!name.empty()) e.text("name", name);
  e.vector("pos", world.particles().position[id]);
  // Pinned, or frozen by the guard: either way it no longer moves, and a scene says so by pinned.
  const double inverseMass = world.particles().inverseMass[id];
  if (inverseMass == 0.0) {
    e.text("pinned", "true");
  } else {
    e.vector("velocity", detail::loadVelocity(world, id)).number("mass", 1.0 / inverseMass);
  }
  return e.empty();
}

std::string stickElement(const phys::Stick& s, const BodyNames& names) {
  ElementWriter e("stick");
  e.text("a", names.particle(s.a)).text("b", names.particle(s.b));
  if (!s.isRange()) {
    e.number("length", s.minLength);
  } else {
    // Without min or max the loader makes a fixed stick, so a range open at both ends keeps its min.
    const bool openAbove = s.maxLength == phys::kNoMaxLength;
    if (s.minLength > 0.0 || openAbove) e.number("min", s.minLength);
    if (!openAbove) e.number("max", s.maxLength);
  }
  if (s.compliance != 0.0) e.number("compliance", s.compliance);
  return e.empty();
}

// A point the file places on a body (a link's end, a particle joint's pivot) where it is now: the
// loader takes none beyond the bound. A body the guard froze stretched can carry one there while
// all its particles are inside (the fuzzer: a capsule ragdoll under a gravity of 9.1e10 m/s^2, a
// link's end 14 km past a bound of 1e6 m), and such a world is refused rather than saved unloadable.
void requireInsideBound(const phys::Vec3& point, double bound, const std::string& what) {
  if (detail::insideBound(point, bound)) return;
  throw std::invalid_argument(what + " lies at (" + detail::formatNumber(point.x) + ", " +
                              detail::formatNumber(point.y) + ", " + detail::formatNumber(point.z) +
                              "), beyond the world's bound of " + detail::formatNumber(bound) +
                              " m, which no scene file can hold");
}

// A clip's clock as the loader takes it (a character's speed and time, from-speed and from-time): a
// speed set past kMaxClipSpeed through the physics, or a time the physics ran on past
// phys::kMaxClipTime (it bounds neither; at the loader's fastest that takes 11 days), is refused
// rather than saved in a file that would not load.
void requireLoadableClock(const phys::Playback& p, const std::string& what) {
  if (!(p.speed <= detail::kMaxClipSpeed)) {
    throw std::invalid_argument(what + " plays at a speed of " + detail::exactNumber(p.speed) +
                                ", over the " + detail::formatNumber(detail::kMaxClipSpeed) +
                                " a scene file holds");
  }
  if (!(std::abs(p.time) <= phys::kMaxClipTime)) {
    throw std::invalid_argument(what + " is at " + detail::exactNumber(p.time) + " s, beyond the +-" +
                                detail::formatNumber(phys::kMaxClipTime) + " s a scene file holds");
  }
}

std::string linkElement(const phys::World& world, const phys::RigidLink& link,
                        std::span<const phys::BodyId> owner, const BodyNames& names) {
  const LinkEnd endA = linkEnd(world, link.a, owner), endB = linkEnd(world, link.b, owner);
  // The loader refuses a link from a body to itself (a box is rigid: such a link does nothing).
  if (endA.isBox == endB.isBox && endA.index == endB.index) {
    throw std::invalid_argument("a link joins " + names.end(endA) + " to itself; a <link> joins two bodies");
  }
  ElementWriter e("link");
  e.text("a", names.end(endA)).text("b", names.end(endB));
  const phys::Vec3 a = world.position(link.a), b = world.position(link.b);
  const double bound = world.worldSettings().bound;
  const std::string end =
      "the end of the link from '" + names.end(endA) + "' to '" + names.end(endB) + "' on '";
  requireInsideBound(a, bound, end + names.end(endA) + "'");
  requireInsideBound(b, bound, end + names.end(endB) + "'");
  // Each end where it is now, so the reloaded world is this one: a pin whose ends are apart
  // (by what the passes left, or because it was made so) pulls them together in the next step
  // there as it would here. An end that is a loose particle is that particle, wherever written.
  if (a == b)
    e.vector("point", a);
  else
    e.vector("a-point", a).vector("b-point", b);
  if (link.isPin()) return e.empty();
  const bool openAbove = link.maxLength == phys::kNoMaxLength;
  if (link.minLength > 0.0 || openAbove) e.number("min", link.minLength);
  if (!openAbove) e.number("max", link.maxLength);
  return e.empty();
}

// Both bodies' frames as they are now, so that a joint saved away from its rest (at a stop, or
// pulled a little apart) reloads as it is, not with its child's angle taken as the new zero.
std::string jointElement(const phys::JointDesc& d, const phys::JointDrive& drive, const phys::Quat& rest,
                         const BodyNames& names) {
  ElementWriter e("joint");
  e.text("type", d.kind == phys::JointKind::Hinge ? "hinge" : "cone");
  e.text("a", names.box(d.a)).text("b", names.box(d.b));
  e.vector("pivot", d.pivot);
  if (d.pivotB != d.pivot) e.vector("b-pivot", d.pivotB);
  e.vector("axis", d.axis).vector("reference", d.reference);
  if (d.axisB != d.axis || d.referenceB != d.reference)
    e.vector("b-axis", d.axisB).vector("b-reference", d.referenceB);
  if (d.kind == phys::JointKind::Hinge) {
    e.number("min", glm::degrees(d.minAngle)).number("max", glm::degrees(d.maxAngle));
  } else {
    e.number("swing", glm::degrees(d.swing)).number("twist", glm::degrees(d.twist));
  }
  if (d.damping != 0.0) e.number("damping", d.damping);
  const phys::JointDrive defaults;
  if (drive.strength != defaults.strength) e.number("strength", drive.strength);
  if (drive.stiffness != defaults.stiffness) e.number("drive-stiffness", drive.stiffness);
  // A turn of the target off the rest so small that no Euler angle tells it apart is no turn.
  const phys::Quat off = glm::conjugate(rest) * drive.target;
  if (glm::length(glm::dvec3(off.x, off.y, off.z)) > 1e-15)
    e.vector("drive-target", detail::eulerFromOrientation(drive.target));
  return e.empty();
}

// A particle joint as it lies: its two pivots in the world (the same point while the links hold it),
// its rest always (not found again from the bodies' poses on loading), its drive as a <joint>'s.
std::string particleJointElement(const phys::World& world, const phys::ParticleJoint& j,
                                 const phys::JointDrive& drive, const BodyNames& names) {
  ElementWriter e("particle-joint");
  e.text("a", names.box(j.a)).text("b", names.box(j.b));
  const phys::BodyPose a = world.bodyPose(j.a), b = world.bodyPose(j.b);
  const phys::Vec3 pivot = a.center + a.orientation * j.pivotA, pivotB = b.center + b.orientation * j.pivotB;
  const double bound = world.worldSettings().bound;
  requireInsideBound(pivot, bound,
                     "the pivot of the particle joint from " + names.box(j.a) + " to " + names.box(j.b));
  requireInsideBound(pivotB, bound,
                     "the pivot of the particle joint from " + names.box(j.b) + " to " + names.box(j.a));
  e.vector("pivot", pivot);
  if (pivotB != pivot) e.vector("b-pivot", pivotB);
  e.vector("rest", detail::eulerFromOrientation(j.rest));
  const phys::JointDrive defaults;
  if (drive.strength != defaults.strength) e.number("strength", drive.strength);
  if (drive.stiffness != defaults.stiffness) e.number("drive-stiffness", drive.stiffness);
  const phys::Quat off = glm::conjugate(j.rest) * drive.target;
  if (glm::length(glm::dvec3(off.x, off.y, off.z)) > 1e-15)
    e.vector("drive-target", detail::eulerFromOrientation(drive.target));
  return e.empty();
}

// How many elements of the kinds kMaxConstraints holds the file would have: a box's own bracing is
// its <box>'s, every other stick a <stick>.
std::size_t constraintElements(const phys::World& world) {
  const std::span<const phys::BodyId> owner = world.particleBodies();
  const auto braces = std::count_if(world.sticks().begin(), world.sticks().end(), [&](const phys::Stick& s) {
    return owner[s.a] != phys::kNoBody && owner[s.a] == owner[s.b];
  });
  return world.sticks().size() - static_cast<std::size_t>(braces) + world.links().size() +
         world.rigidLinks().size() + world.rigidJoints().size() + world.particleJoints().size() +
         world.jointFrictions().size() + world.ignoredCollisions().size();
}

std::string header(const phys::World& world) {
  char text[160];
  std::snprintf(
      text, sizeof text,
      "<!-- Saved at t = %.6g s (step %ld): each box as the rigid body fitted to its particles. -->",
      world.time(), world.stepCount());
  return text;
}

}  // namespace

SaveError::SaveError(std::filesystem::path file, const std::string& message)
    : std::runtime_error(file.string() + ": " + message), file_(std::move(file)) {}

namespace {

// The scene's text, with a <camera> when `camera` is given.
std::string sceneXml(const Scene& scene, const CameraStart* camera, const std::filesystem::path& folder) {
  const phys::World& world = scene.world;
  const phys::Particles& particles = world.particles();
  if (particles.size() > detail::kMaxParticles) {
    throw std::invalid_argument("the world has " + std::to_string(particles.size()) +
                                " particles; a scene file loads at most " +
                                std::to_string(detail::kMaxParticles));
  }
  if (world.bodies().size() > detail::kMaxBodies) {
    throw std::invalid_argument("the world has " + std::to_string(world.bodies().size()) +
                                " bodies; a scene file loads at most " + std::to_string(detail::kMaxBodies));
  }
  if (const std::size_t n = constraintElements(world); n > detail::kMaxConstraints) {
    throw std::invalid_argument("the world has " + std::to_string(n) +
                                " constraints (sticks, links, joints and pairs that do not collide); a scene "
                                "file loads at most " +
                                std::to_string(detail::kMaxConstraints));
  }
  if (scene.description.find_first_of("\n\r") != std::string::npos)
    throw std::invalid_argument("the scene's description holds a line break; a scene file's is one line");
  const std::span<const phys::BodyId> owner = world.particleBodies();
  // The physics takes any bound > 0; a file holds at most kMaxBound (the loader's limit).
  const double bound = world.worldSettings().bound;
  if (!(bound <= detail::kMaxBound)) {
    throw std::invalid_argument("the world's bound of " + detail::formatNumber(bound) +
                                " m is larger than a scene file holds (at most " +
                                detail::formatNumber(detail::kMaxBound) + " m)");
  }
  // The loader refuses a body beyond the bound (the bound was lowered under it at run time).
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (detail::insideBound(particles.position[i], bound)) continue;
    const std::string body = owner[i] == phys::kNoBody ? "particle " + std::to_string(i)
                                                       : "box " + std::to_string(owner[i]) + " '" +
                                                             world.bodies()[owner[i]].name + "'";
    throw std::invalid_argument(body + " is beyond the world's bound of " + detail::formatNumber(bound) +
                                " m, where a scene file places nothing");
  }
  // A box or capsule is written as its pose and rebuilt at its rest shape: one pressed out of
  // shape against the bound, its particles inside it, can be rebuilt reaching past it. Its
  // particles are placed here as the loader will place them: the pose as written (through Euler
  // angles) and World::addBody's normalised turn.
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    const phys::Body& body = world.bodies()[id];
    if (body.model == phys::BodyModel::Rigid) continue;
    const phys::BodyPose pose = world.bodyPose(id);
    const phys::Quat written = detail::orientationFromEuler(detail::eulerFromOrientation(pose.orientation));
    const phys::Quat turn = written / glm::length(written);
    for (int j = 0; j < body.particleCount; ++j) {
      if (detail::insideBound(pose.center + turn * phys::boxParticleLocal(body.model, body.halfExtents, j),
                              bound))
        continue;
      throw std::invalid_argument(
          "box " + std::to_string(id) + " '" + body.name +
          "', pressed out of shape, would be rebuilt from its pose reaching beyond the "
          "world's bound of " +
          detail::formatNumber(bound) + " m, which no scene file can hold");
    }
  }
  // A rigid body has no particles: its centre is where the file puts it. (Found by the soak: a
  // rigid box flung to 3e261 m under a huge gravity, then the bound lowered, saved a file the
  // loader refused.)
  for (phys::BodyId id{}; id < world.bodies().size(); ++id) {
    if (world.bodies()[id].model != phys::BodyModel::Rigid ||
        detail::insideBound(world.bodyPose(id).center, bound))
      continue;
    throw std::invalid_argument("box " + std::to_string(id) + " '" + world.bodies()[id].name +
                                "' is beyond the world's bound of " + detail::formatNumber(bound) +
                                " m, where a scene file places nothing");
  }

  // Sticks inside one box are its bracing, which <box> rebuilds; the rest must join two loose
  // particles, as <stick> does.
  std::vector<bool> referenced(particles.size(), false);
  for (const phys::Stick& s : world.sticks()) {
    if (owner[s.a] != phys::kNoBody && owner[s.a] == owner[s.b]) continue;
    if (owner[s.a] != phys::kNoBody || owner[s.b] != phys::kNoBody) {
      auto describe = [&](phys::ParticleId id) {
        std::string which = "particle " + std::to_string(id);
        if (owner[id] == phys::kNoBody) return which;
        const std::string& box = world.bodies()[owner[id]].name;
        return which + " (of box " + (box.empty() ? std::to_string(owner[id]) : "'" + box + "'") + ")";
      };
      throw std::invalid_argument("a stick joins " + describe(s.a) + " and " + describe(s.b) +
                                  "; a <stick> joins two loose particles");
    }
    referenced[s.a] = referenced[s.b] = true;
  }
  for (const phys::Link& link : world.links()) {
    for (const phys::Embedding* end : {&link.a, &link.b}) {
      if (const LinkEnd e = linkEnd(*end, owner); !e.isBox) referenced[e.index] = true;
    }
  }
  for (const phys::RigidLink& link : world.rigidLinks()) {
    for (const phys::BodyPoint* end : {&link.a, &link.b}) {
      if (const LinkEnd e = linkEnd(world, *end, owner); !e.isBox) referenced[e.index] = true;
    }
  }
  const BodyNames names(world, owner, referenced);

  std::string out = header(world) + "\n";
  out += ElementWriter("scene")
             .text("name", scene.name.empty() ? "untitled" : scene.name)
             .text("description", scene.description)
             .open() +
         "\n";
  auto line = [&out](const std::string& element) { out.append("  ").append(element).append("\n"); };
  line(worldElement(world.worldSettings()));
  line(solverElement(world.solverSettings()));
  if (world.worldSettings().ground) line(groundElement(world.worldSettings()));
  if (camera != nullptr) line(cameraElement(*camera, world.worldSettings().bound));
  // Bodies and sticks in the order the world made them, so that the reloaded world gives each
  // the same index. The world keeps no such record across kinds, but the sticks show it: a box's
  // bracing is added with the box, and a stick after both its particles.
  std::size_t written = 0;  // particles whose body is written
  RigidInOrder rigid(world);
  auto writeRigid = [&](phys::BodyId b) { line(boxElement(world, b, names.box(b))); };
  auto writeBodiesBelow = [&](std::size_t end) {
    while (written < end) {
      rigid.before(written, writeRigid);
      const auto id = static_cast<phys::ParticleId>(written);
      if (owner[id] == phys::kNoBody) {
        line(particleElement(world, id, names.particle(id)));
        ++written;
      } else {
        const phys::Body& box = world.bodies()[owner[id]];
        line(boxElement(world, owner[id], names.box(owner[id])));
        written = box.firstParticle + box.particleCount;
      }
    }
  };
  for (const phys::Stick& s : world.sticks()) {
    writeBodiesBelow(std::max(s.a, s.b) + std::size_t{1});
    if (owner[s.a] == phys::kNoBody) line(stickElement(s, names));
  }
  writeBodiesBelow(particles.size());
  rigid.before(particles.size(), writeRigid);
  for (const phys::Link& link : world.links()) {
    const phys::RigidLink general{phys::BodyPoint::embedded(link.a), phys::BodyPoint::embedded(link.b),
                                  link.minLength, link.maxLength};
    line(linkElement(world, general, owner, names));
  }
  for (const phys::RigidLink& link : world.rigidLinks()) line(linkElement(world, link, owner, names));
  for (std::size_t k = 0; k < world.rigidJoints().size(); ++k)
    line(jointElement(world.jointDesc(k), world.jointDrive(k), world.jointRest(k), names));
  for (std::size_t k = 0; k < world.particleJoints().size(); ++k)
    line(particleJointElement(world, world.particleJoints()[k], world.particleJointDrive(k), names));
  // A character's root drive is the character's to aim: each substep it rewrites the drive (and
  // drops it while nothing needs it), so the loader refuses a <body-drive> on a character's root.
  // The character's element carries the root's stiffnesses instead, whether or not the root has a
  // drive at this moment.
  std::set<phys::BodyId> roots;
  for (const phys::Character& c : world.characters()) roots.insert(c.bones[0].body);
  for (const phys::DrivenBody& d : world.bodyDrives()) {
    if (roots.contains(d.body)) continue;
    const phys::BodyDrive& drive = d.drive;
    if (!detail::insideBound(drive.position, bound)) {
      throw std::invalid_argument("a body drive's target is beyond the world's bound of " +
                                  detail::formatNumber(bound) + " m");
    }
    ElementWriter e("body-drive");
    e.text("body", names.box(d.body))
        .vector("pos", drive.position)
        .vector("euler", detail::eulerFromOrientation(drive.orientation))
        .number("strength", drive.strength);
    const phys::BodyDrive defaults;
    if (drive.stiffness != defaults.stiffness) e.number("stiffness", drive.stiffness);
    if (drive.angularStiffness != defaults.angularStiffness)
      e.number("angular-stiffness", drive.angularStiffness);
    line(e.empty());
  }
  // A character after its ragdoll's bodies, joints and root drive, which it drives from then on. Its
  // clips by the paths they were loaded from (a clip's name), relative to the file's folder when
  // there is one, so that a scene saved beside its clips moves with them.
  //
  // Where it is (the loader's `state` and the attributes after it): a reaction under way and the
  // strengths it has ramped, written only where they differ from a character just added; and its
  // clip frame, always, so that it goes on along the path it was on rather than one found again
  // from where its root part has got to.
  const auto characterState = [bound](ElementWriter& e, const phys::Character& c) {
    if (c.state != phys::CharacterState::Active) e.text("state", std::string(phys::toString(c.state)));
    if (c.stateTime != 0.0) e.number("state-time", c.stateTime);
    if (c.stillTime != 0.0) e.number("still-time", c.stillTime);
    if (c.strength != c.goalStrength) e.number("strength-now", c.strength);
    if (c.rootStrength != c.goalRootStrength) e.number("root-strength-now", c.rootStrength);
    if (c.balance != c.goalBalance) e.number("balance-now", c.balance);
    if (c.fromStrength != 0.0) e.number("from-strength", c.fromStrength);
    if (c.fromBalance != 0.0) e.number("from-balance", c.fromBalance);
    // What the last step found of its support, which the balance reads in the next: left out, the
    // reload's first step had no balance and went its own way from the saved run's.
    if (c.supported) e.text("supported", "true");
    // A turn-in under way (Character::turnIn), and whether one is still to be looked for: a character
    // just added has one due, which its first substep settles; left out, the reload of a character
    // that had stepped looked again, and one saved lying far from its pose turned in where the
    // saved run did not.
    if (c.turnIn > 0.0) e.number("turn-in-left", c.turnIn);
    if (!c.turnInDue) e.text("turn-in-due", "false");
    e.number("heading", glm::degrees(2.0 * std::atan2(c.frame.y, c.frame.w)));
    // Each change of clip moves the frame on to where the new one starts, wherever the parts are.
    requireInsideBound(c.origin, bound, "the clip frame of character '" + c.ragdoll + "'");
    e.vector("origin", c.origin);
  };
  const auto clipPath = [&folder](const phys::Clip& clip) {
    const std::filesystem::path path(clip.name);
    if (folder.empty() || !path.is_absolute()) return clip.name;
    const std::filesystem::path relative = detail::resolvedClip(path).lexically_relative(folder);
    return relative.empty() ? clip.name : relative.generic_string();
  };
  // A fade under way: how far it has got, and what it fades from (the clip before, or a pose held).
  // The shift and the held root are held to the bound by the loader, as the origin is: a clip
  // that loops on far along its path can leave them beyond it.
  const auto fade = [&clipPath, bound](ElementWriter& e, const phys::Character& c) {
    if (c.blend >= 1.0) return;
    e.number("blend", c.blend).number("blend-time", c.blendTime);
    if (c.before.clip) {
      requireLoadableClock(c.before, "the clip character '" + c.ragdoll + "' fades from");
      requireInsideBound(c.beforeShift, bound,
                         "the shift of the clip character '" + c.ragdoll + "' fades from");
      e.text("from-clip", clipPath(*c.before.clip))
          .number("from-time", c.before.time)
          .number("from-speed", c.before.speed)
          .text("from-loop", c.before.loop ? "true" : "false")
          .vector("from-shift", c.beforeShift);
    }
    if (!c.holding) return;
    requireInsideBound(c.held.root, bound, "the held pose's root of character '" + c.ragdoll + "'");
    std::string turns;
    for (const phys::Quat& q : c.held.turns) {
      if (!turns.empty()) turns += ", ";
      turns += detail::exactNumber(q.w) + ' ' + detail::exactNumber(q.x) + ' ' + detail::exactNumber(q.y) +
               ' ' + detail::exactNumber(q.z);
    }
    e.vector("held-root", c.held.root).text("held-turns", turns);
  };
  for (const phys::Character& c : world.characters()) {
    requireLoadableClock(c.now, "the clip of character '" + c.ragdoll + "'");
    ElementWriter e("character");
    e.text("ragdoll", c.ragdoll)
        .text("clip", clipPath(*c.now.clip))
        .number("time", c.now.time)
        .number("speed", c.now.speed)
        .text("loop", c.now.loop ? "true" : "false")
        .number("strength", c.goalStrength)
        .number("root-strength", c.goalRootStrength);
    if (c.scale != 1.0) e.number("scale", c.scale);
    if (c.rootOffset != phys::Vec3(0.0)) e.vector("root-offset", c.rootOffset);
    if (c.goalBalance > 0.0) e.number("balance", c.goalBalance);
    if (c.turnInTime != phys::kTurnInTime) e.number("turn-in", c.turnInTime);
    e.number("root-stiffness", c.rootStiffness).number("root-angular-stiffness", c.rootAngularStiffness);
    std::string parts;
    for (std::size_t b = 1; b < c.bones.size(); ++b) {
      if (c.partStrength[b] == 1.0) continue;
      if (!parts.empty()) parts += ' ';
      parts += c.now.clip->bones[static_cast<std::size_t>(c.bones[b].clipBone)] + "=" +
               detail::exactNumber(c.partStrength[b]);
    }
    if (!parts.empty()) e.text("part-strengths", parts);
    const phys::Reaction& r = c.reaction;
    const phys::Reaction defaults;
    if (r.threshold > 0.0) e.number("react", r.threshold);
    if (r.fallTime != defaults.fallTime) e.number("fall-time", r.fallTime);
    if (r.restTime != defaults.restTime) e.number("rest-time", r.restTime);
    if (r.armTime != defaults.armTime) e.number("arm-time", r.armTime);
    if (r.restSpeed != defaults.restSpeed) e.number("rest-speed", r.restSpeed);
    if (r.getUpTime != defaults.getUpTime) e.number("get-up-time", r.getUpTime);
    if (r.getUp.clip) e.text("get-up", clipPath(*r.getUp.clip));
    if (c.queued) {
      e.text("then", clipPath(*c.queued->playback.clip))
          .number("then-at", c.queued->at)
          .number("then-blend", c.queued->blendTime)
          .text("then-loop", c.queued->playback.loop ? "true" : "false");
    }
    characterState(e, c);
    fade(e, c);
    line(e.empty());
  }
  for (const phys::JointFriction& f : world.jointFrictions()) {
    line(ElementWriter("joint-friction")
             .text("a", names.box(f.a))
             .text("b", names.box(f.b))
             .number("damping", f.rate)
             .empty());
  }
  for (const auto& [a, b] : world.ignoredCollisions()) {
    line(ElementWriter("no-collision").text("a", names.box(a)).text("b", names.box(b)).empty());
  }
  out += "</scene>\n";
  if (out.size() > detail::kMaxSceneBytes) {
    throw std::invalid_argument("the file would be " + std::to_string(out.size() >> 20) +
                                " MiB; a scene file loads at most " +
                                std::to_string(detail::kMaxSceneBytes >> 20) + " MiB");
  }
  return out;
}

// A scene loaded without a <camera> is written without one, so that it reloads as it loaded (the
// sandbox keeps its view): the default view is not the scene's, and need not be within a small
// world bound (found by the scene fuzzer: <world bound="5"/> and no camera could not be saved).
const CameraStart* ownCamera(const Scene& scene) {
  return scene.camera.given ? &scene.camera : nullptr;
}

void save(const Scene& scene, const CameraStart* camera, const std::filesystem::path& file) {
  std::string xml;
  try {
    // Clips named from the folder the file lands in, a link's target's, as the loader reads them.
    xml = sceneXml(scene, camera, detail::clipFolder(file));
  } catch (const std::invalid_argument& e) {
    throw SaveError(file, std::string("cannot save this world as a scene: ") + e.what());
  } catch (const fileio::FileError& e) {
    throw SaveError(file, e.message());
  }
  try {
    fileio::writeAtomically(file, xml);
  } catch (const fileio::FileError& e) {
    throw SaveError(file, e.message());
  }
}

}  // namespace

std::string writeSceneXml(const Scene& scene, const CameraStart& camera,
                          const std::filesystem::path& folder) {
  return sceneXml(scene, &camera, folder);
}

std::string writeSceneXml(const Scene& scene) {
  return sceneXml(scene, ownCamera(scene), {});
}

void saveSceneFile(const Scene& scene, const CameraStart& camera, const std::filesystem::path& file) {
  save(scene, &camera, file);
}

void saveSceneFile(const Scene& scene, const std::filesystem::path& file) {
  save(scene, ownCamera(scene), file);
}

}  // namespace scenes
