#include "engine/camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

namespace engine {

FirstPersonCamera FirstPersonCamera::lookingAt(const glm::vec3& eye, const glm::vec3& target) {
  FirstPersonCamera camera;
  camera.position = eye;
  const glm::vec3 d = glm::normalize(target - eye);
  camera.yaw = glm::degrees(std::atan2(d.x, -d.z));
  camera.pitch = std::clamp(glm::degrees(std::asin(d.y)), -kMaxPitch, kMaxPitch);
  return camera;
}

glm::vec3 FirstPersonCamera::forward() const {
  const float y = glm::radians(yaw), p = glm::radians(pitch);
  return {std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
}

glm::vec3 FirstPersonCamera::right() const {
  const float y = glm::radians(yaw);
  return {std::cos(y), 0.0f, std::sin(y)};
}

glm::mat4 FirstPersonCamera::view() const {
  return glm::lookAt(position, position + forward(), glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 FirstPersonCamera::projection(float aspect) const {
  return glm::perspective(glm::radians(fovY), aspect, nearPlane, farPlane);
}

void FirstPersonCamera::move(float rightward, float upward, float forwardward) {
  position += right() * rightward + glm::vec3(0.0f, upward, 0.0f) + forward() * forwardward;
}

void FirstPersonCamera::turn(float yawDegrees, float pitchDegrees) {
  yaw = std::fmod(yaw + yawDegrees, 360.0f);
  pitch = std::clamp(pitch + pitchDegrees, -kMaxPitch, kMaxPitch);
}

void FirstPersonCamera::orbit(const glm::vec3& pivot, float yawDegrees, float pitchDegrees) {
  const float distance = glm::length(position - pivot);
  // A pivot at the eye gives no direction to look along (normalising it would make every angle
  // NaN): the camera turns where it stands.
  if (!(distance >= nearPlane)) {
    turn(yawDegrees, pitchDegrees);
    return;
  }
  const FirstPersonCamera looking = lookingAt(position, pivot);
  yaw = looking.yaw;
  pitch = looking.pitch;
  turn(yawDegrees, pitchDegrees);
  position = pivot - forward() * distance;
}

void FirstPersonCamera::dolly(const glm::vec3& pivot, float factor) {
  const glm::vec3 away = position - pivot;
  const float distance = glm::length(away);
  if (!(distance > 0.0f) || !(factor > 0.0f)) return;
  position = pivot + away * (std::max(distance * factor, 2.0f * nearPlane) / distance);
}

bool FirstPersonCamera::frame(const glm::vec3& lo, const glm::vec3& hi, float aspect, float fill) {
  const glm::vec3 centre = 0.5f * (lo + hi);
  const glm::vec3 f = forward();
  const glm::mat4 proj = projection(aspect);
  auto corner = [&](int k) {
    return glm::vec3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
  };
  auto view = [&](float distance) {
    return glm::lookAt(centre - f * distance, centre, glm::vec3(0.0f, 1.0f, 0.0f));
  };
  // The corners' places in the view shrink towards the middle as the camera backs away: the
  // nearest distance at which all of them are within `fill`, by bisection.
  auto fits = [&](float distance) {
    const glm::mat4 v = view(distance);
    for (int k = 0; k < 8; ++k) {
      const glm::vec4 eye = v * glm::vec4(corner(k), 1.0f);
      if (eye.z > -nearPlane) return false;
      const glm::vec4 clip = proj * eye;
      if (std::abs(clip.x / clip.w) > fill || std::abs(clip.y / clip.w) > fill) return false;
    }
    return true;
  };
  auto withinFarPlane = [&](float distance) {
    const glm::mat4 v = view(distance);
    for (int k = 0; k < 8; ++k) {
      if ((v * glm::vec4(corner(k), 1.0f)).z < -farPlane) return false;
    }
    return true;
  };
  float nearer = nearPlane, farther = farPlane;
  const bool fitsSomewhere = fits(farther);
  if (fitsSomewhere) {
    if (fits(nearer)) farther = nearer;
    for (int i = 0; i < 60 && farther - nearer > 1e-4f * farther; ++i) {
      const float middle = 0.5f * (nearer + farther);
      (fits(middle) ? farther : nearer) = middle;
    }
  }
  if (!fitsSomewhere || !withinFarPlane(farther)) {
    // Part of it would not be drawn: its middle, half the far plane away.
    position = centre - f * (0.5f * farPlane);
    return false;
  }
  position = centre - f * farther;
  return true;
}

}  // namespace engine
