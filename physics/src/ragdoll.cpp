#include "physics/ragdoll.h"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string_view>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "joint_builders.h"
#include "require.h"

namespace phys {

using detail::require;

namespace {

constexpr Real kDegree = std::numbers::pi / 180.0;

// The standing body at scale 1, in metres, feet on y = 0, facing +z; the hips (the torso's
// bottom face) at y = 0.88. Mass fractions roughly a person's (hands in the forearms, feet in
// the shins).
struct PartLayout {
  RagdollPart part;
  Vec3 center;
  Vec3 size;
  Real massFraction;
};
constexpr Real kHipHeight = 0.88;
constexpr PartLayout kParts[kRagdollParts] = {
    {RagdollPart::Head, {0.0, 1.59, 0.0}, {0.18, 0.26, 0.20}, 0.08},
    {RagdollPart::Torso, {0.0, 1.17, 0.0}, {0.34, 0.58, 0.20}, 0.30},
    {RagdollPart::UpperArmLeft, {0.23, 1.30, 0.0}, {0.10, 0.32, 0.10}, 0.06},
    {RagdollPart::LowerArmLeft, {0.23, 0.99, 0.0}, {0.09, 0.30, 0.09}, 0.05},
    {RagdollPart::UpperArmRight, {-0.23, 1.30, 0.0}, {0.10, 0.32, 0.10}, 0.06},
    {RagdollPart::LowerArmRight, {-0.23, 0.99, 0.0}, {0.09, 0.30, 0.09}, 0.05},
    {RagdollPart::UpperLegLeft, {0.09, 0.66, 0.0}, {0.14, 0.44, 0.14}, 0.11},
    {RagdollPart::LowerLegLeft, {0.09, 0.22, 0.0}, {0.12, 0.44, 0.12}, 0.09},
    {RagdollPart::UpperLegRight, {-0.09, 0.66, 0.0}, {0.14, 0.44, 0.14}, 0.11},
    {RagdollPart::LowerLegRight, {-0.09, 0.22, 0.0}, {0.12, 0.44, 0.12}, 0.09},
};

// Every hinge turns about x through `pivot`; its two pins sit `halfSpan` either side of the pivot
// along x. The angle is positive by the right-hand rule about +x: a part hanging down swings
// backwards (knees bend that way, elbows and hips the other). The limit links' points lie
// `radius` from the pivot, in the plane of the reference direction (down for limbs, up for the
// head), close enough to both parts that their embedding weights stay small.
struct HingeLayout {
  RagdollPart parent, child;
  Vec3 pivot;
  Real halfSpan;
  Vec3 reference;
  Real minDegrees, maxDegrees;
  Real radius;
};
constexpr Vec3 kDown{0.0, -1.0, 0.0};
constexpr Vec3 kUp{0.0, 1.0, 0.0};
constexpr HingeLayout kHinges[kRagdollHinges] = {
    {RagdollPart::Torso, RagdollPart::Head, {0.0, 1.46, 0.0}, 0.08, kUp, -30.0, 40.0, 0.10},
    {RagdollPart::Torso, RagdollPart::UpperArmLeft, {0.20, 1.40, 0.0}, 0.08, kDown, -120.0, 40.0, 0.10},
    {RagdollPart::UpperArmLeft, RagdollPart::LowerArmLeft, {0.23, 1.14, 0.0}, 0.07, kDown, -140.0, 0.0, 0.08},
    {RagdollPart::Torso, RagdollPart::UpperArmRight, {-0.20, 1.40, 0.0}, 0.08, kDown, -120.0, 40.0, 0.10},
    {RagdollPart::UpperArmRight,
     RagdollPart::LowerArmRight,
     {-0.23, 1.14, 0.0},
     0.07,
     kDown,
     -140.0,
     0.0,
     0.08},
    {RagdollPart::Torso, RagdollPart::UpperLegLeft, {0.09, 0.88, 0.0}, 0.07, kDown, -110.0, 20.0, 0.10},
    {RagdollPart::UpperLegLeft, RagdollPart::LowerLegLeft, {0.09, 0.44, 0.0}, 0.07, kDown, 0.0, 140.0, 0.10},
    {RagdollPart::Torso, RagdollPart::UpperLegRight, {-0.09, 0.88, 0.0}, 0.07, kDown, -110.0, 20.0, 0.10},
    {RagdollPart::UpperLegRight,
     RagdollPart::LowerLegRight,
     {-0.09, 0.44, 0.0},
     0.07,
     kDown,
     0.0,
     140.0,
     0.10},
};

}  // namespace

std::string_view toString(RagdollModel model) {
  detail::requireEnum(static_cast<int>(model), static_cast<int>(RagdollModel::Rigid) + 1,
                      "toString(RagdollModel)", "model", "RagdollModel");
  static constexpr std::array<std::string_view, 3> kNames = {"seed", "lean", "rigid"};
  return kNames[static_cast<std::size_t>(model)];
}

std::optional<RagdollModel> parseRagdollModel(std::string_view name) {
  if (name == "seed") return RagdollModel::Seed;
  if (name == "lean") return RagdollModel::Lean;
  if (name == "rigid") return RagdollModel::Rigid;
  return std::nullopt;
}

RagdollModel ragdollModelOf(BodyModel model) {
  switch (model) {
    case BodyModel::Corners:
      return RagdollModel::Seed;
    case BodyModel::Tetra:
      return RagdollModel::Lean;
    case BodyModel::Rigid:
      break;
  }
  return RagdollModel::Rigid;
}

std::string_view toString(RagdollPart part) {
  constexpr std::string_view kNames[kRagdollParts] = {"head",           "torso",           "upper-arm-left",
                                                      "lower-arm-left", "upper-arm-right", "lower-arm-right",
                                                      "upper-leg-left", "lower-leg-left",  "upper-leg-right",
                                                      "lower-leg-right"};
  detail::requireEnum(static_cast<int>(part), kRagdollParts, "toString(RagdollPart)", "part", "RagdollPart");
  return kNames[static_cast<int>(part)];
}

BodyId Ragdoll::part(RagdollPart p) const {
  detail::requireEnum(static_cast<int>(p), kRagdollParts, "Ragdoll::part", "part", "RagdollPart");
  return parts[static_cast<std::size_t>(p)];
}

namespace {

Ragdoll build(World& world, const RagdollDesc& desc, const detail::RagdollFrame& frame) {
  const detail::PlaceFn& place = frame.place;
  const Quat q = frame.orientation;
  auto ragdoll = detail::startRagdoll<Ragdoll>(world, desc);
  for (const PartLayout& p : kParts) {
    BodyDesc box = detail::ragdollPart(desc, toString(p.part));
    box.center = place(p.center);
    box.size = p.size * desc.scale;
    box.orientation = q;
    box.mass = desc.mass * p.massFraction;
    ragdoll.parts[static_cast<int>(p.part)] = world.addBody(box);
  }

  for (int h = 0; h < kRagdollHinges; ++h) {
    const HingeLayout& layout = kHinges[h];
    const BodyId parent = ragdoll.part(layout.parent), child = ragdoll.part(layout.child);
    const Real minAngle = layout.minDegrees * kDegree, maxAngle = layout.maxDegrees * kDegree;
    detail::HingeSpec spec;
    spec.pivot = layout.pivot;
    spec.axis = Vec3(1.0, 0.0, 0.0);
    spec.reference = layout.reference;
    spec.minAngle = minAngle;
    spec.maxAngle = maxAngle;
    spec.halfSpan = layout.halfSpan;
    spec.radius = layout.radius;
    spec.damping = detail::jointDamping(desc);
    detail::addHinge(world, parent, child, spec, place, desc.scale);
    world.ignoreCollision(parent, child);
    ragdoll.hinges[h] = {layout.parent,    layout.child, Vec3(1.0, 0.0, 0.0),
                         layout.reference, minAngle,     maxAngle};
  }
  detail::driveRagdollJoints(world, desc, ragdoll.firstJoint);
  detail::driveRagdollRoot(world, desc, ragdoll.part(RagdollPart::Torso));
  return ragdoll;
}

}  // namespace

Ragdoll addRagdoll(World& world, const RagdollDesc& desc) {
  // Where a point of the standing layout goes in the world.
  const detail::RagdollFrame frame = detail::ragdollFrame(desc, kHipHeight, "addRagdoll");
  for (const PartLayout& p : kParts) {
    require(finite(frame.place(p.center + p.size)) && finite(frame.place(p.center - p.size)),
            "addRagdoll: position or scale too large to represent");
  }
  detail::buildInEmptyWorld(world, desc, "addRagdoll", [&](World& empty) { build(empty, desc, frame); });
  return build(world, desc, frame);
}

Real hingeAngle(const World& world, const Ragdoll& ragdoll, const RagdollHinge& hinge) {
  // Checked here, so that a bad part or body is refused in hingeAngle's name, not part's or bodyPose's.
  auto body = [&](RagdollPart p, std::string_view end) {
    detail::requireEnum(static_cast<int>(p), kRagdollParts, "hingeAngle", end, "RagdollPart");
    const BodyId id = ragdoll.parts[static_cast<std::size_t>(p)];
    detail::requireIndex(id, world.bodies().size(), "hingeAngle", "body");
    return id;
  };
  const Quat parent = world.bodyPose(body(hinge.parent, "the hinge's parent")).orientation;
  const Quat child = world.bodyPose(body(hinge.child, "the hinge's child")).orientation;
  const Vec3 axis = parent * hinge.axis;
  const Vec3 from = parent * hinge.reference;
  Vec3 to = child * hinge.reference;
  to -= glm::dot(to, axis) * axis;  // a twist off the axis does not count
  return std::atan2(glm::dot(axis, glm::cross(from, to)), glm::dot(from, to));
}

}  // namespace phys
