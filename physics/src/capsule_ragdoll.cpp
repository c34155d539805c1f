#include "physics/capsule_ragdoll.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "joint_builders.h"
#include "require.h"

namespace phys {

using detail::require;

namespace {

constexpr Real kDegree = std::numbers::pi / 180.0;

// Bullet's layout, in metres: its capsules (radius, core length), their centres and its joint
// limits, with x mirrored so that left is +x as in ragdoll.h, and everything raised 0.035 m so
// the feet end on y = 0 (Bullet's lower legs reach 0.035 m below its origin).
constexpr Real kRaise = 0.035;
enum class Lie { Up, Left, Right };  // the core along y, or along +x / -x (the arms, in a T)
struct PartLayout {
  CapsulePart part;
  Vec3 center;
  Real radius;
  Real coreLength;
  Lie lie;
};
constexpr PartLayout kParts[kCapsuleParts] = {
    {CapsulePart::Pelvis, {0.0, 1.0 + kRaise, 0.0}, 0.15, 0.20, Lie::Up},
    {CapsulePart::Spine, {0.0, 1.2 + kRaise, 0.0}, 0.15, 0.28, Lie::Up},
    {CapsulePart::Head, {0.0, 1.6 + kRaise, 0.0}, 0.10, 0.05, Lie::Up},
    {CapsulePart::UpperLegLeft, {0.18, 0.65 + kRaise, 0.0}, 0.07, 0.45, Lie::Up},
    {CapsulePart::LowerLegLeft, {0.18, 0.2 + kRaise, 0.0}, 0.05, 0.37, Lie::Up},
    {CapsulePart::UpperLegRight, {-0.18, 0.65 + kRaise, 0.0}, 0.07, 0.45, Lie::Up},
    {CapsulePart::LowerLegRight, {-0.18, 0.2 + kRaise, 0.0}, 0.05, 0.37, Lie::Up},
    {CapsulePart::UpperArmLeft, {0.35, 1.45 + kRaise, 0.0}, 0.05, 0.33, Lie::Left},
    {CapsulePart::LowerArmLeft, {0.7, 1.45 + kRaise, 0.0}, 0.04, 0.25, Lie::Left},
    {CapsulePart::UpperArmRight, {-0.35, 1.45 + kRaise, 0.0}, 0.05, 0.33, Lie::Right},
    {CapsulePart::LowerArmRight, {-0.7, 1.45 + kRaise, 0.0}, 0.04, 0.25, Lie::Right},
};

// Bullet gives each joint a frame in each body whose origins differ by up to 0.1 m as laid out,
// so its ragdoll starts by snapping together. Our pivots sit midway between the two, and the
// joints hold from the first step. The hip pivots' middle is the ragdoll's `hips`.
constexpr Real kHipHeight = 0.8875 + kRaise;
constexpr Vec3 kUp{0.0, 1.0, 0.0}, kDown{0.0, -1.0, 0.0}, kLeft{1.0, 0.0, 0.0}, kRight{-1.0, 0.0, 0.0};
constexpr Vec3 kAcross{1.0, 0.0, 0.0}, kForward{0.0, 0.0, 1.0};

struct HingeLayout {
  CapsulePart parent, child;
  Vec3 pivot, axis, reference;
  Real minDegrees, maxDegrees, halfSpan, radius;
};
// Positive angles by the right-hand rule: the spine bends forwards, the knees backwards, and the
// elbows forwards (their axis is vertical: Bullet's arms stand out in a T).
constexpr HingeLayout kHinges[] = {
    {CapsulePart::Pelvis,
     CapsulePart::Spine,
     {0.0, 1.10 + kRaise, 0.0},
     kAcross,
     kUp,
     -45.0,
     90.0,
     0.08,
     0.10},
    {CapsulePart::UpperLegLeft,
     CapsulePart::LowerLegLeft,
     {0.18, 0.405 + kRaise, 0.0},
     kAcross,
     kDown,
     0.0,
     90.0,
     0.05,
     0.10},
    {CapsulePart::UpperLegRight,
     CapsulePart::LowerLegRight,
     {-0.18, 0.405 + kRaise, 0.0},
     kAcross,
     kDown,
     0.0,
     90.0,
     0.05,
     0.10},
    {CapsulePart::UpperArmLeft,
     CapsulePart::LowerArmLeft,
     {0.545, 1.45 + kRaise, 0.0},
     kUp,
     kLeft,
     -90.0,
     0.0,
     0.04,
     0.08},
    {CapsulePart::UpperArmRight,
     CapsulePart::LowerArmRight,
     {-0.545, 1.45 + kRaise, 0.0},
     kUp,
     kRight,
     0.0,
     90.0,
     0.04,
     0.08},
};

struct ConeLayout {
  CapsulePart parent, child;
  Vec3 pivot, axis;
  Real swingDegrees, twistDegrees;
};
constexpr ConeLayout kCones[] = {
    {CapsulePart::Spine, CapsulePart::Head, {0.0, 1.48 + kRaise, 0.0}, kUp, 45.0, 90.0},
    {CapsulePart::Pelvis, CapsulePart::UpperLegLeft, {0.18, kHipHeight, 0.0}, kDown, 45.0, 0.0},
    {CapsulePart::Pelvis, CapsulePart::UpperLegRight, {-0.18, kHipHeight, 0.0}, kDown, 45.0, 0.0},
    {CapsulePart::Spine, CapsulePart::UpperArmLeft, {0.185, 1.40 + kRaise, 0.0}, kLeft, 90.0, 0.0},
    {CapsulePart::Spine, CapsulePart::UpperArmRight, {-0.185, 1.40 + kRaise, 0.0}, kRight, 90.0, 0.0},
};
static_assert(std::size(kHinges) + std::size(kCones) == kCapsuleJoints);

Quat lieOrientation(Lie lie) {
  if (lie == Lie::Up) return {1.0, 0.0, 0.0, 0.0};
  // A quarter turn about z takes the body's y axis to -x (positive) or +x (negative).
  return glm::angleAxis((lie == Lie::Left ? -0.5 : 0.5) * std::numbers::pi, Vec3(0.0, 0.0, 1.0));
}

}  // namespace

std::string_view toString(CapsulePart part) {
  constexpr std::string_view kNames[kCapsuleParts] = {"pelvis",          "spine",          "head",
                                                      "upper-leg-left",  "lower-leg-left", "upper-leg-right",
                                                      "lower-leg-right", "upper-arm-left", "lower-arm-left",
                                                      "upper-arm-right", "lower-arm-right"};
  detail::requireEnum(static_cast<int>(part), kCapsuleParts, "toString(CapsulePart)", "part", "CapsulePart");
  return kNames[static_cast<int>(part)];
}

BodyId CapsuleRagdoll::part(CapsulePart p) const {
  detail::requireEnum(static_cast<int>(p), kCapsuleParts, "CapsuleRagdoll::part", "part", "CapsulePart");
  return parts[static_cast<std::size_t>(p)];
}

namespace {

CapsuleRagdoll build(World& world, const RagdollDesc& desc, const detail::RagdollFrame& frame) {
  const detail::PlaceFn& place = frame.place;
  const Quat q = frame.orientation;
  auto ragdoll = detail::startRagdoll<CapsuleRagdoll>(world, desc);
  for (const PartLayout& p : kParts) {
    BodyDesc box = detail::ragdollPart(desc, toString(p.part));
    box.shape = Shape::Capsule;
    box.center = place(p.center);
    box.size = Vec3(2.0 * p.radius, p.coreLength + 2.0 * p.radius, 2.0 * p.radius) * desc.scale;
    box.orientation = q * lieOrientation(p.lie);
    box.mass = desc.mass / kCapsuleParts;
    ragdoll.parts[static_cast<int>(p.part)] = world.addBody(box);
  }

  for (const HingeLayout& h : kHinges) {
    detail::HingeSpec spec;
    spec.pivot = h.pivot;
    spec.axis = h.axis;
    spec.reference = h.reference;
    spec.minAngle = h.minDegrees * kDegree;
    spec.maxAngle = h.maxDegrees * kDegree;
    spec.halfSpan = h.halfSpan;
    spec.radius = h.radius;
    spec.damping = detail::jointDamping(desc);
    detail::addHinge(world, ragdoll.part(h.parent), ragdoll.part(h.child), spec, place, desc.scale);
    world.ignoreCollision(ragdoll.part(h.parent), ragdoll.part(h.child));
  }
  for (const ConeLayout& c : kCones) {
    detail::ConeSpec spec;
    spec.pivot = c.pivot;
    spec.axis = c.axis;
    spec.side = kForward;
    spec.swing = c.swingDegrees * kDegree;
    spec.twist = c.twistDegrees * kDegree;
    spec.damping = detail::jointDamping(desc);
    detail::addCone(world, ragdoll.part(c.parent), ragdoll.part(c.child), spec, place, desc.scale);
    world.ignoreCollision(ragdoll.part(c.parent), ragdoll.part(c.child));
  }
  detail::driveRagdollJoints(world, desc, ragdoll.firstJoint);
  detail::driveRagdollRoot(world, desc, ragdoll.part(CapsulePart::Pelvis));
  return ragdoll;
}

}  // namespace

CapsuleRagdoll addCapsuleRagdoll(World& world, const RagdollDesc& desc) {
  const detail::RagdollFrame frame = detail::ragdollFrame(desc, kHipHeight, "addCapsuleRagdoll");
  for (const PartLayout& p : kParts) {
    const Vec3 reach(p.coreLength + 2.0 * p.radius);
    require(finite(frame.place(p.center + reach)) && finite(frame.place(p.center - reach)),
            "addCapsuleRagdoll: position or scale too large to represent");
  }
  detail::buildInEmptyWorld(world, desc, "addCapsuleRagdoll",
                            [&](World& empty) { build(empty, desc, frame); });
  return build(world, desc, frame);
}

}  // namespace phys
