#pragma once
// What colour each kind of body is drawn in; the rendering tests look for these.
#include <glm/vec3.hpp>

namespace sandbox {

inline constexpr glm::vec3 kBoxColor{0.90f, 0.50f, 0.15f};       ///< orange
inline constexpr glm::vec3 kParticleColor{0.20f, 0.35f, 0.85f};  ///< blue
inline constexpr float kParticleDrawSize = 0.08f;                ///< unit: m; edge of a particle's cube

/// True when an 8-bit pixel has the hue of `color` under some light level: the lighting
/// scales all channels alike, so the ratios between channels survive it.
bool looksLike(const glm::vec3& color, unsigned char r, unsigned char g, unsigned char b);

}  // namespace sandbox
