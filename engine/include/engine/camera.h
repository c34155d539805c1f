#pragma once
// A first-person camera: a position and two angles, no roll.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace engine {

struct FirstPersonCamera {
  glm::vec3 position{0.0f, 2.0f, 8.0f};  ///< unit: m
  float yaw = 0.0f;                      ///< unit: degrees; 0 looks along -z, positive turns towards +x
  float pitch = 0.0f;                    ///< unit: degrees; positive looks up; kept within +-kMaxPitch
  float fovY = 60.0f;                    ///< unit: degrees; vertical field of view
  float nearPlane = 0.05f;               ///< unit: m
  float farPlane = 500.0f;               ///< unit: m

  static constexpr float kMaxPitch = 89.0f;  ///< short of 90 so the view never flips

  /// A camera at `eye` turned to look at `target`.
  static FirstPersonCamera lookingAt(const glm::vec3& eye, const glm::vec3& target);

  glm::vec3 forward() const;  ///< unit vector along the view
  glm::vec3 right() const;    ///< unit vector to the right, horizontal
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;

  /// Moves along the camera's right, world up and forward directions by the given metres.
  void move(float rightward, float upward, float forwardward);
  /// Turns by the given degrees; pitch is clamped.
  void turn(float yawDegrees, float pitchDegrees);
};

}  // namespace engine
