#include "physics/world.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "passes.h"

namespace phys {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// The sticks that brace a box's 8 corners. 12 edges and one diagonal on each of the 6 faces
// make 18 = 3 * 8 - 6, the fewest that hold 8 points rigid (a convex polyhedron with
// triangulated faces is rigid: Cauchy and Dehn), and the seed's count per box. The 4 body
// diagonals are on top: without them a shear of the whole box must travel through three sticks
// per relaxation pass to be corrected, with them through one.
struct CornerPair {
  int a, b;
};
constexpr CornerPair kBoxSticks[kBoxStickCount] = {
    // edges along x, y and z (corner bits: 1 = x, 2 = y, 4 = z)
    {0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7},
    // one diagonal per face: -x, +x, -y, +y, -z, +z
    {0, 6}, {1, 7}, {0, 5}, {2, 7}, {0, 3}, {4, 7},
    // body diagonals
    {0, 7}, {1, 6}, {2, 5}, {3, 4}};

}  // namespace

World::World(const WorldSettings& world, const SolverSettings& solver) {
  setWorldSettings(world);
  setSolverSettings(solver);
}

void World::setWorldSettings(const WorldSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "WorldSettings: " + why);
  world_ = settings;
}

void World::setSolverSettings(const SolverSettings& settings) {
  const std::string why = validate(settings);
  require(why.empty(), "SolverSettings: " + why);
  solver_ = settings;
}

ParticleId World::addParticle(const ParticleDesc& desc) {
  require(finite(desc.position), "addParticle: position must be finite");
  require(finite(desc.velocity), "addParticle: velocity must be finite");
  require(desc.pinned || (std::isfinite(desc.mass) && desc.mass > 0.0),
          "addParticle: mass must be finite and > 0 (kg) unless pinned");
  // Verlet's x - x* is the velocity half a substep back. For v(t0) = v to hold exactly under
  // the current gravity g, x* = x - (v - g h / 2) h; then free fall is exact to round-off.
  const Real h = substepDt();
  const Vec3 halfStepVelocity = desc.pinned ? Vec3(0.0) : desc.velocity - world_.gravity * (h / 2);
  particles_.position.push_back(desc.position);
  particles_.previous.push_back(desc.position - halfStepVelocity * h);
  particles_.inverseMass.push_back(desc.pinned ? 0.0 : 1.0 / desc.mass);
  groundDepth_.push_back(0.0);
  return static_cast<ParticleId>(particles_.size() - 1);
}

void World::addStick(ParticleId a, ParticleId b) {
  require(a < particles_.size() && b < particles_.size() && a != b,
          "addStick: particle ids must exist and differ");
  addStick(a, b, glm::length(particles_.position[b] - particles_.position[a]));
}

void World::addStick(ParticleId a, ParticleId b, Real length) {
  require(a < particles_.size() && b < particles_.size() && a != b,
          "addStick: particle ids must exist and differ");
  require(std::isfinite(length) && length >= 0.0, "addStick: length must be finite and >= 0 (m)");
  sticks_.push_back({a, b, length});
}

BoxId World::addBox(const BoxDesc& desc) {
  require(finite(desc.center) && finite(desc.velocity), "addBox: center and velocity must be finite");
  require(finite(desc.size) && desc.size.x > 0.0 && desc.size.y > 0.0 && desc.size.z > 0.0,
          "addBox: size must be finite and > 0 (m)");
  require(std::isfinite(desc.mass) && desc.mass > 0.0, "addBox: mass must be finite and > 0 (kg)");
  const Quat q = glm::normalize(desc.orientation);
  require(std::isfinite(q.w) && std::isfinite(q.x), "addBox: orientation must be a finite non-zero quaternion");

  Box box;
  box.halfExtents = desc.size * 0.5;
  box.firstCorner = static_cast<ParticleId>(particles_.size());
  for (int k = 0; k < 8; ++k) {
    addParticle({desc.center + q * boxCornerLocal(box.halfExtents, k), desc.velocity, desc.mass / 8.0});
  }
  for (const CornerPair& pair : kBoxSticks) {
    addStick(box.firstCorner + pair.a, box.firstCorner + pair.b);
  }
  boxes_.push_back(box);
  return static_cast<BoxId>(boxes_.size() - 1);
}

void World::step() {
  const Real h = substepDt();
  for (int s = 0; s < solver_.substeps; ++s) {
    detail::integrate(particles_, world_.gravity, world_.damping, h);
    std::fill(groundDepth_.begin(), groundDepth_.end(), 0.0);
    for (int it = 0; it < solver_.iterations; ++it) {
      detail::relaxSticks(particles_, sticks_);
      if (world_.ground) detail::collideGround(particles_, world_.groundHeight, groundDepth_);
    }
    detail::applyGroundFriction(particles_, groundDepth_, world_.groundStaticFriction,
                                world_.groundDynamicFriction);
  }
  time_ += solver_.dt;
  ++steps_;
}

Vec3 World::velocity(ParticleId id) const {
  return (particles_.position.at(id) - particles_.previous.at(id)) / substepDt();
}

BoxPose World::boxPose(BoxId id) const {
  const Box& box = boxes_.at(id);
  const Vec3* c = &particles_.position[box.firstCorner];
  BoxPose pose;
  for (int k = 0; k < 8; ++k) pose.center += c[k];
  pose.center /= 8.0;
  // Each body axis is the mean of the four corner-to-corner edges along it; Gram-Schmidt then
  // makes the frame orthonormal (x exact, y in the x-y plane, z their cross product).
  Vec3 ex = (c[1] - c[0]) + (c[3] - c[2]) + (c[5] - c[4]) + (c[7] - c[6]);
  Vec3 ey = (c[2] - c[0]) + (c[3] - c[1]) + (c[6] - c[4]) + (c[7] - c[5]);
  ex = glm::normalize(ex);
  ey = glm::normalize(ey - glm::dot(ey, ex) * ex);
  const glm::dmat3 basis(ex, ey, glm::cross(ex, ey));
  pose.orientation = glm::quat_cast(basis);
  return pose;
}

}  // namespace phys
