#pragma once
// The scene file's generators: many bodies from one element. Each reads its own attributes
// and adds to the world under construction; members are named "<name>[i]".
#include <functional>
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
inline constexpr long kMaxPyramidBase = 200;  // 20100 boxes
inline constexpr int kMaxGridSide = 100;      // per axis
inline constexpr long kMaxGridBoxes = 100000;
inline constexpr long kMaxChainLinks = 100000;
inline constexpr std::size_t kMaxParticles = 2000000;  // whole scene

/// Reads the attributes every box-making element shares (size, mass, model, friction...); a
/// model imposed by the load options replaces the file's.
phys::BoxDesc readBoxCommon(ElementReader& e, const LoadOptions& options);
/// The same for a <capsule>: radius and length (both required: length is the whole length, cap
/// to cap, at least twice the radius) in place of size, as a box of Shape::Capsule that the
/// capsule is inscribed in: size (2 radius, length, 2 radius), along the body's y axis.
phys::BoxDesc readCapsuleCommon(ElementReader& e, const LoadOptions& options);

void generateStack(ElementReader& e, BuildContext& ctx);
void generatePyramid(ElementReader& e, BuildContext& ctx);
void generateGrid(ElementReader& e, BuildContext& ctx);
void generateChain(ElementReader& e, BuildContext& ctx);
/// Not a generator in name, but it makes named bodies from one element: ten boxes
/// (shape="box", physics/ragdoll.h) or eleven capsules (shape="capsule",
/// physics/capsule_ragdoll.h).
void generateRagdoll(ElementReader& e, BuildContext& ctx);

}  // namespace scenes::detail
