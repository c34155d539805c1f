#pragma once
// The box that holds what the world draws: what Z frames (engine::FirstPersonCamera::frame).
#include <optional>
#include <utility>

#include <glm/vec3.hpp>

#include "physics/world.h"

namespace sandbox {

/// The axis-aligned bounds (lowest and highest corner, unit: m) of every body's corners and every
/// loose particle (as the cube it is drawn as); none for an empty world.
std::optional<std::pair<glm::vec3, glm::vec3>> sceneBounds(const phys::World& world);

}  // namespace sandbox
