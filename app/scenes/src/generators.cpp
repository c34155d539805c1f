#include "generators.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include "element_writer.h"
#include "euler_angles.h"
#include "physics/capsule_ragdoll.h"
#include "physics/ragdoll.h"

namespace scenes::detail {
namespace {

std::string member(const std::string& name, long i) {
  return name + "[" + std::to_string(i) + "]";
}

void addBody(ElementReader& e, BuildContext& ctx, phys::BodyDesc desc, const std::string& name) {
  desc.name = name;
  const phys::BodyId id = ctx.world.addBody(desc);
  ctx.addName(e, name, NamedBody::Kind::Body, id);
}

// inertia-floor, from 0 to 1 (BodyDesc::inertiaFloor, RagdollDesc::inertiaFloor).
std::optional<double> readInertiaFloor(ElementReader& e) {
  return readFraction(e, "inertia-floor");
}

// What every rigid body element reads after its size: mass, model, friction, orientation.
void readBodyCommon(ElementReader& e, const LoadOptions& options, phys::BodyDesc& d) {
  if (auto mass = readMass(e, "mass")) d.mass = *mass;
  if (auto model = e.text("model")) {
    const auto parsed = phys::parseBodyModel(*model);
    if (!parsed) e.fail("model", "'" + *model + "' must be corners, tetra or rigid");
    d.model = *parsed;
  }
  if (auto floor = readInertiaFloor(e)) d.inertiaFloor = *floor;
  e.material(d.material);
  if (auto euler = e.vector("euler", "degrees")) d.orientation = orientationFromEuler(*euler);
  if (options.boxModel) d.model = *options.boxModel;
}

}  // namespace

std::optional<double> readFraction(ElementReader& e, std::string_view attribute) {
  const std::optional<double> value = e.number(attribute, "");
  if (value && !(*value >= 0.0 && *value <= 1.0))
    e.fail(attribute, "'" + formatNumber(*value) + "' must be from 0 to 1");
  return value;
}

std::optional<double> readRagdollScale(ElementReader& e) {
  const std::optional<double> scale = e.number("scale", "");
  if (scale && !(*scale >= kMinRagdollScale && *scale <= kMaxRagdollScale)) {
    e.fail("scale", "'" + formatNumber(*scale) + "' must be from " + formatNumber(kMinRagdollScale) + " to " +
                        formatNumber(kMaxRagdollScale));
  }
  return scale;
}

std::optional<phys::JointDrive> readDrive(ElementReader& e) {
  const std::optional<double> strength = readFraction(e, "strength");
  const std::optional<double> stiffness = e.number("drive-stiffness", "N m/rad");
  if (!strength && !stiffness) return std::nullopt;
  phys::JointDrive drive;
  if (strength) drive.strength = *strength;
  if (stiffness) {
    if (!(*stiffness > 0.0))
      e.fail("drive-stiffness", "'" + formatNumber(*stiffness) + "' must be > 0 (N m/rad)");
    drive.stiffness = *stiffness;
  }
  return drive;
}

std::optional<double> readMass(ElementReader& e, std::string_view attribute, double least) {
  const std::optional<double> mass = e.number(attribute, "kg");
  if (mass && !(*mass >= least && *mass <= kMaxMass)) {
    e.fail(attribute, "'" + formatNumber(*mass) + "' must be from " + formatNumber(least) + " to " +
                          formatNumber(kMaxMass) + " (kg)");
  }
  return mass;
}

void refuseMoreThan(const ElementReader& e, std::size_t count, std::size_t limit, std::string_view what) {
  if (count <= limit) return;
  std::string message = "the scene has more than " + std::to_string(limit) + " ";
  e.fail(message.append(what));
}

void checkInsideBound(ElementReader& e, const phys::World& world, std::string_view attribute,
                      const phys::Vec3& point) {
  const double bound = world.worldSettings().bound;
  if (insideBound(point, bound)) return;
  e.fail(attribute, "puts a body at (" + exactNumber(point.x) + ", " + exactNumber(point.y) + ", " +
                        exactNumber(point.z) + "), beyond the world's bound of " + formatNumber(bound) +
                        " m along an axis (<world bound>)");
}

phys::BodyDesc readBoxCommon(ElementReader& e, const LoadOptions& options) {
  phys::BodyDesc d;
  if (auto size = e.vector("size", "m", true)) {
    const double least = std::min({size->x, size->y, size->z}), most = std::max({size->x, size->y, size->z});
    if (!(least >= kMinBodySize && most <= kMaxBodySize)) {
      e.fail("size", "sizes must be from " + formatNumber(kMinBodySize) + " to " +
                         formatNumber(kMaxBodySize) + " (m)");
    }
    d.size = *size;
  }
  readBodyCommon(e, options, d);
  return d;
}

phys::BodyDesc readCapsuleCommon(ElementReader& e, const LoadOptions& options) {
  phys::BodyDesc d;
  d.shape = phys::Shape::Capsule;
  const double radius = e.requiredNumber("radius", "m");
  if (!(2.0 * radius >= kMinBodySize)) {
    e.fail("radius",
           "'" + formatNumber(radius) + "' must be at least " + formatNumber(kMinBodySize / 2) + " (m)");
  }
  const double length = e.requiredNumber("length", "m");
  if (!(length <= kMaxBodySize))
    e.fail("length", "'" + formatNumber(length) + "' must be at most " + formatNumber(kMaxBodySize) + " (m)");
  // The box it is inscribed in is 2 radius wide: the physics needs size.y >= size.x, computed
  // here the same way, so a sphere (length exactly 2 radius) passes both checks.
  const double diameter = 2.0 * radius;
  if (!(length >= diameter)) {
    e.fail("length", "'" + formatNumber(length) + "' must be at least twice the radius, " +
                         formatNumber(diameter) + " (m): it is the whole length, cap to cap");
  }
  d.size = phys::Vec3(diameter, length, diameter);
  readBodyCommon(e, options, d);
  return d;
}

// Boxes one on another, the bottom one resting on the plane y = pos.y.
void generateStack(ElementReader& e, BuildContext& ctx) {
  const std::string name = e.text("name").value_or("stack");
  const phys::Vec3 pos = e.requiredVector("pos", "m");
  checkInsideBound(e, ctx.world, "pos", pos);
  const long count = e.requiredInteger("count", 1, kMaxStack);
  phys::BodyDesc box = readBoxCommon(e, ctx.options);
  e.rejectUnknownAttributes();
  for (long i = 0; i < count; ++i) {
    box.center = pos + phys::Vec3(0.0, box.size.y * (static_cast<double>(i) + 0.5), 0.0);
    addBody(e, ctx, box, member(name, i));
  }
}

// Rows of boxes along x, each one box shorter, resting on y = pos.y, centred on pos. With
// taper < 1 each row's boxes are that much smaller than the row's below (the seed's pyramid of
// boxes that vary in size).
void generatePyramid(ElementReader& e, BuildContext& ctx) {
  const std::string name = e.text("name").value_or("pyramid");
  const phys::Vec3 pos = e.requiredVector("pos", "m");
  checkInsideBound(e, ctx.world, "pos", pos);
  const long base = e.requiredInteger("base", 1, kMaxPyramidBase);
  const double taper = e.number("taper", "").value_or(1.0);
  if (taper <= 0.0 || taper > 1.0) e.fail("taper", "must be > 0 and at most 1");
  phys::BodyDesc box = readBoxCommon(e, ctx.options);
  e.rejectUnknownAttributes();
  const phys::Vec3 baseSize = box.size;
  // Each row taper times the one below: the top row's boxes must still be a body's size.
  const phys::Vec3 top = baseSize * std::pow(taper, static_cast<double>(base - 1));
  if (!(std::min({top.x, top.y, top.z}) >= kMinBodySize)) {
    e.fail("taper", "'" + formatNumber(taper) + "' makes the top row's boxes " +
                        formatNumber(std::min({top.x, top.y, top.z})) + " m, below the smallest size of " +
                        formatNumber(kMinBodySize) + " m");
  }
  long index = 0;
  double bottom = pos.y;
  for (long row = 0; row < base; ++row) {
    box.size = baseSize * std::pow(taper, static_cast<double>(row));
    const long inRow = base - row;
    for (long i = 0; i < inRow; ++i) {
      const double x = (static_cast<double>(i) - 0.5 * static_cast<double>(inRow - 1)) * box.size.x;
      box.center = phys::Vec3(pos.x + x, bottom + 0.5 * box.size.y, pos.z);
      addBody(e, ctx, box, member(name, index++));
    }
    bottom += box.size.y;
  }
}

// count.x by count.y by count.z boxes, centred on pos in x and z, the bottom layer on y = pos.y;
// spacing (default: the size, so they touch) between centres.
void generateGrid(ElementReader& e, BuildContext& ctx) {
  const std::string name = e.text("name").value_or("grid");
  const phys::Vec3 pos = e.requiredVector("pos", "m");
  checkInsideBound(e, ctx.world, "pos", pos);
  const std::optional<glm::ivec3> count = e.integers3("count", 1, kMaxGridSide);
  if (!count) e.fail("count", "is required (three whole numbers)");
  if (static_cast<long>(count->x) * count->y * count->z > kMaxGridBoxes) {
    e.fail("count", "makes more than " + std::to_string(kMaxGridBoxes) + " boxes");
  }
  phys::BodyDesc box = readBoxCommon(e, ctx.options);
  const phys::Vec3 spacing = e.vector("spacing", "m", true).value_or(box.size);
  if (!(std::min({spacing.x, spacing.y, spacing.z}) > 0.0 &&
        std::max({spacing.x, spacing.y, spacing.z}) <= kMaxBodySize)) {
    e.fail("spacing", "must be > 0 and at most " + formatNumber(kMaxBodySize) + " (m)");
  }
  e.rejectUnknownAttributes();
  long index = 0;
  for (int j = 0; j < count->y; ++j) {
    for (int k = 0; k < count->z; ++k) {
      for (int i = 0; i < count->x; ++i) {
        box.center =
            pos + phys::Vec3((i - 0.5 * (count->x - 1)) * spacing.x, 0.5 * box.size.y + j * spacing.y,
                             (k - 0.5 * (count->z - 1)) * spacing.z);
        addBody(e, ctx, box, member(name, index++));
      }
    }
  }
}

// Particles from pos along direction (default straight down), one link length apart, joined
// by sticks; the first pinned unless pinned="false"; the last weighs end-mass.
void generateChain(ElementReader& e, BuildContext& ctx) {
  const std::string name = e.text("name").value_or("chain");
  const phys::Vec3 pos = e.requiredVector("pos", "m");
  checkInsideBound(e, ctx.world, "pos", pos);
  const long links = e.requiredInteger("links", 1, kMaxChainLinks);
  const double length = e.requiredNumber("length", "m");
  if (length <= 0.0) e.fail("length", "must be > 0 (m)");
  const double mass = readMass(e, "mass").value_or(phys::ParticleDesc{}.mass);
  const double endMass = readMass(e, "end-mass").value_or(mass);
  const bool pinned = e.boolean("pinned").value_or(true);
  const double compliance = e.number("compliance", "m/N").value_or(0.0);
  if (compliance < 0.0 || compliance > phys::kMaxCompliance) {
    e.fail("compliance", "must be from 0 to " + formatNumber(phys::kMaxCompliance) + " (m/N)");
  }
  const phys::Vec3 direction = e.direction("direction").value_or(phys::Vec3(0.0, -1.0, 0.0));
  e.rejectUnknownAttributes();
  phys::ParticleId previous{};
  for (long i = 0; i <= links; ++i) {
    phys::ParticleDesc p;
    p.position = pos + direction * (length * static_cast<double>(i));
    p.mass = i == links ? endMass : mass;
    p.pinned = i == 0 && pinned;
    p.name = member(name, i);
    const phys::ParticleId id = ctx.world.addParticle(p);
    ctx.addName(e, p.name, NamedBody::Kind::Particle, id);
    if (i > 0) ctx.world.addStick(previous, id, length, compliance);
    previous = id;
  }
}

// Ten boxes joined by hinges (physics/ragdoll.h), or with shape="capsule" eleven capsules joined
// by hinges and cones (physics/capsule_ragdoll.h); pos is where its hips are, and at euler 0 it
// stands on its feet facing +z. Parts are named "<name>.head", "<name>.torso" (or
// "<name>.pelvis", "<name>.spine"), ...
void generateRagdoll(ElementReader& e, BuildContext& ctx) {
  phys::RagdollDesc d;
  phys::Shape shape = phys::Shape::Box;
  if (auto text = e.text("shape")) {
    if (*text == phys::toString(phys::Shape::Capsule))
      shape = phys::Shape::Capsule;
    else if (*text != phys::toString(phys::Shape::Box))
      e.fail("shape", "'" + *text + "' must be box or capsule");
  }
  d.name = e.text("name").value_or("ragdoll");
  d.hips = e.requiredVector("pos", "m");
  checkInsideBound(e, ctx.world, "pos", d.hips);
  if (auto euler = e.vector("euler", "degrees")) d.orientation = orientationFromEuler(*euler);
  if (auto scale = readRagdollScale(e)) d.scale = *scale;
  if (auto mass = readMass(e, "mass", kMinRagdollMass)) d.mass = *mass;
  if (auto model = e.text("model")) {
    const auto parsed = phys::parseRagdollModel(*model);
    if (!parsed) e.fail("model", "'" + *model + "' must be seed, lean or rigid");
    d.model = *parsed;
  }
  d.velocity = e.vector("velocity", "m/s").value_or(phys::Vec3(0.0));
  if (auto damping = e.number("joint-damping", "1/s")) {
    if (*damping < 0.0) e.fail("joint-damping", "must be >= 0 (1/s)");
    d.jointDamping = *damping;
  }
  if (auto floor = readInertiaFloor(e)) d.inertiaFloor = *floor;
  if (auto drive = readDrive(e)) {
    d.strength = drive->strength;
    if (e.has("drive-stiffness")) d.driveStiffness = drive->stiffness;
  }
  if (auto root = readFraction(e, "root-strength")) d.rootStrength = *root;
  e.material(d.material);
  e.rejectUnknownAttributes();
  if (ctx.options.ragdollModel) d.model = *ctx.options.ragdollModel;
  auto nameParts = [&](const auto& parts) {
    for (const phys::BodyId id : parts)
      ctx.addName(e, ctx.world.bodies()[id].name, NamedBody::Kind::Body, id);
  };
  if (shape == phys::Shape::Capsule)
    nameParts(phys::addCapsuleRagdoll(ctx.world, d).parts);
  else
    nameParts(phys::addRagdoll(ctx.world, d).parts);
}

}  // namespace scenes::detail
