#pragma once
// What colour each kind of body is drawn in; the rendering tests look for these.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "draw_options.h"
#include "physics/world.h"

namespace sandbox {

inline constexpr glm::vec3 kBoxColor{0.90f, 0.50f, 0.15f};       ///< orange
inline constexpr glm::vec3 kParticleColor{0.20f, 0.35f, 0.85f};  ///< blue
inline constexpr float kParticleDrawSize = 0.08f;  ///< unit: m; least diameter of a particle's sphere
inline constexpr glm::vec3 kLooseStickColor{0.80f, 0.82f, 0.88f};  ///< light grey: a stick no mesh covers
inline constexpr glm::vec3 kTrailColor{0.85f, 0.25f, 0.55f};       ///< magenta: Draw > trails
inline constexpr glm::vec3 kExactColor{0.10f, 0.75f, 0.30f};       ///< green: the scene's exact answers
inline constexpr float kGhostAlpha =
    0.35f;  ///< the exact answer's ghost: seen through, the run seen behind it
inline constexpr glm::vec3 kSleepingColor{0.45f, 0.50f, 0.60f};  ///< grey-blue: an island asleep

/// Colour k of the body palette: ten that tell neighbours apart on the grey ground and the blue
/// sky (Tableau's ten, the grey swapped for a teal so that nothing looks asleep), orange first,
/// so a scene of one body or one ragdoll looks as it always did.
glm::vec3 paletteColor(std::size_t k);
/// Per body, its group's number: bodies held together by joints (a ragdoll) are one group;
/// groups are numbered by their first body, so a body thrown in later never renumbers the others.
std::vector<std::uint32_t> jointGroups(const phys::World& world);

/// Body `id`'s colour as `coloring` asks, before its brightness (SceneView shades each body).
/// `groups` (jointGroups) saves finding them again for each body.
glm::vec3 bodyColor(const phys::World& world, phys::BodyId id, BodyColoring coloring,
                    std::span<const std::uint32_t> groups = {});

/// True when an 8-bit pixel has the hue of `color` under some light level: the lighting
/// scales all channels alike, so the ratios between channels survive it.
bool looksLike(const glm::vec3& color, unsigned char r, unsigned char g, unsigned char b);

}  // namespace sandbox
