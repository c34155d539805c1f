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
  /// Turns by the given degrees about `pivot`, staying as far from it and ending up looking at it
  /// (the orbit of MuJoCo's and Jolt's viewers). A pivot nearer than the near plane is turned
  /// about where the camera stands.
  void orbit(const glm::vec3& pivot, float yawDegrees, float pitchDegrees);
  /// Moves along the line to `pivot`, to `factor` times the distance from it (< 1 nearer), so the
  /// pivot stays where it is on the screen; never nearer than twice the near plane.
  void dolly(const glm::vec3& pivot, float factor);
  /// Turned as it is, moved along its view so that the box [lo, hi] is in the middle of the view
  /// and fills `fill` of its half-width or half-height, whichever is reached first, all of it
  /// within the far plane. False when no distance does (a box larger than the view reaches): the
  /// camera is then half the far plane from the box's centre.
  [[nodiscard]] bool frame(const glm::vec3& lo, const glm::vec3& hi, float aspect, float fill = 0.85f);
};

}  // namespace engine
