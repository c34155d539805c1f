#pragma once
// The scene file's generators: many bodies from one element. Each reads its own attributes
// and adds to the world under construction; members are named "<name>[i]".
#include <functional>
#include <optional>
#include <string>

#include "element_reader.h"
#include "physics/world.h"

namespace scenes::detail {

/// What the generators need from the loader: the world, and a way to register a name (which
/// the loader checks for uniqueness).
struct BuildContext {
  phys::World& world;
  std::function<void(ElementReader&, const std::string& name, NamedBody::Kind, std::uint32_t index)> addName;
  const LoadOptions& options;  ///< models imposed on the file
};

/// Limits on what one generator may make; a larger count is an error that says so.
inline constexpr long kMaxStack = 1000;
using scenes::kMaxPyramidBase;            // scenes/scene.h
inline constexpr int kMaxGridSide = 100;  // per axis
inline constexpr long kMaxGridBoxes = 100000;
inline constexpr long kMaxChainLinks = 100000;
inline constexpr std::size_t kMaxParticles = 2000000;  // whole scene
/// Whole scene: as many as kMaxParticles make corners boxes. A rigid body has no particles, so
/// the particle limit does not hold rigid bodies back: a million of them take some 18 GB in a step.
inline constexpr std::size_t kMaxBodies = kMaxParticles / 8;
/// Whole scene: the elements that add one constraint each (<stick>, <link>, <joint>,
/// <particle-joint>, <joint-friction>, <no-collision>) together. A stick joins two particles: a
/// cloth of kMaxParticles braced along its rows and its columns has two a particle, and what the
/// generators make within the limits above fits with room (a chain of particles has one a particle,
/// a ragdoll of particle boxes 63 for its 80 particles, a rigid one 18 for its 10 bodies). Only the
/// file's size held them before: a <joint> takes some 900 bytes loading, a <link> 500, so that
/// 512 MiB of short ones asked for 5 to 8 GB; at this limit it is at most 3.6 GB.
inline constexpr std::size_t kMaxConstraints = 2 * kMaxParticles;
/// Whole scene: <expect> elements. The lab checks a handful of figures a scene (the project's
/// scenes have at most 8), and each element's attributes are kept as strings, some 20 times the
/// bytes they take in the file, so that a file of a million would take gigabytes: 1000 is over 100
/// times what any check needs.
inline constexpr std::size_t kMaxExpectations = 1000;

/// What a file may say of one body, so that every body it makes is one the physics can
/// represent and every file the writer saves loads back (docs/scene-format.md, "Limits"). At
/// the largest bound a coordinate is good to 1.2e-7 m, far below the smallest size, so a box's
/// corners stay distinct and its sticks keep their lengths to 1e-4 of the smallest box.
inline constexpr double kMaxBound = 1e9;      ///< unit: m; <world bound> at most
inline constexpr double kMinBodySize = 1e-3;  ///< unit: m; a box's side, a capsule's diameter
/// unit: m; a box's side, a capsule's length: none larger than the largest world is wide (a side of
/// 1e200 m made corners no double tells apart, and a message that named no attribute).
inline constexpr double kMaxBodySize = 2.0 * kMaxBound;
inline constexpr double kMinMass = 1e-6;  ///< unit: kg; a body's or a particle's
inline constexpr double kMaxMass = 1e9;   ///< unit: kg
/// A ragdoll's scale: its thinnest part (0.08 m across at scale 1) is then 1.6 mm, above
/// kMinBodySize with room for the round-off of a saved and reloaded part.
inline constexpr double kMinRagdollScale = 0.02;
inline constexpr double kMaxRagdollScale = 1000.0;
/// unitless: clip seconds a second; a character's clip speed (speed, from-speed) at most. The physics
/// runs a clip's clock on without a bound, and a scene file holds a time within phys::kMaxClipTime
/// (1e9 s): at this speed that lasts 1e6 s of simulated time, over 11 days, where any finite speed
/// was taken (speed="1e9" passed it within a second, and Save As wrote a time the loader refused).
/// Faster says nothing a clip can show: at 1/60 s a step it is 17 s of clip a step, many loops of a
/// run cycle.
inline constexpr double kMaxClipSpeed = 1000.0;
/// A ragdoll's whole mass: its lightest part (a box ragdoll's forearm is 5% of it) is then still
/// kMinMass, so that the part saves as a box the loader takes.
inline constexpr double kMinRagdollMass = kMinMass / 0.05;
/// Largest scene file read (a saved world of kMaxParticles loose particles fits), so that a
/// device such as /dev/zero is refused instead of read until memory runs out.
inline constexpr std::size_t kMaxSceneBytes = std::size_t{512} << 20;

/// Reads a unitless number from 0 to 1 (a strength, an inertia floor), if given.
std::optional<double> readFraction(ElementReader& e, std::string_view attribute);
/// Reads a drive's strength (0 to 1) and drive-stiffness (N m/rad, > 0), if either is given; the
/// one not given keeps JointDrive's default (<joint>, <ragdoll>).
std::optional<phys::JointDrive> readDrive(ElementReader& e);
/// Reads a ragdoll's scale in [kMinRagdollScale, kMaxRagdollScale], if given: a <ragdoll>'s, and
/// the <character>'s that plays on it.
std::optional<double> readRagdollScale(ElementReader& e);
/// Reads a mass in [least, kMaxMass] (kg), if given.
std::optional<double> readMass(ElementReader& e, std::string_view attribute, double least = kMinMass);
/// Fails on the element `e` reads if it brought the scene's `count` of `what` ("bodies") past
/// `limit`, naming the limit: the scene-wide limits above.
void refuseMoreThan(const ElementReader& e, std::size_t count, std::size_t limit, std::string_view what);
/// Fails on `attribute` unless every coordinate of `point` is within the world's bound, the
/// guard's test: a body placed beyond it would be frozen on the first step.
void checkInsideBound(ElementReader& e, const phys::World& world, std::string_view attribute,
                      const phys::Vec3& point);

/// Reads the attributes every box-making element shares (size, mass, model, friction...); a
/// model imposed by the load options replaces the file's.
phys::BodyDesc readBoxCommon(ElementReader& e, const LoadOptions& options);
/// The same for a <capsule>: radius and length (both required: length is the whole length, cap
/// to cap, at least twice the radius) in place of size, as a box of Shape::Capsule that the
/// capsule is inscribed in: size (2 radius, length, 2 radius), along the body's y axis.
phys::BodyDesc readCapsuleCommon(ElementReader& e, const LoadOptions& options);

void generateStack(ElementReader& e, BuildContext& ctx);
void generatePyramid(ElementReader& e, BuildContext& ctx);
void generateGrid(ElementReader& e, BuildContext& ctx);
void generateChain(ElementReader& e, BuildContext& ctx);
/// Not a generator in name, but it makes named bodies from one element: ten boxes
/// (shape="box", physics/ragdoll.h) or eleven capsules (shape="capsule",
/// physics/capsule_ragdoll.h).
void generateRagdoll(ElementReader& e, BuildContext& ctx);

}  // namespace scenes::detail
