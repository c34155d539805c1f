// The first-person camera's angles, directions and matrices agree with each other.
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "engine/camera.h"

namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Camera, YawZeroLooksDownMinusZAndYawNinetyAlongPlusX) {
  engine::FirstPersonCamera c;
  expectNear(c.forward(), {0, 0, -1}, 1e-6f);
  expectNear(c.right(), {1, 0, 0}, 1e-6f);
  c.turn(90.0f, 0.0f);
  expectNear(c.forward(), {1, 0, 0}, 1e-6f);
  expectNear(c.right(), {0, 0, 1}, 1e-6f);
}

TEST(Camera, LookingAtPutsTheTargetInTheCentreOfTheImage) {
  const glm::vec3 target{1.0f, 0.5f, -2.0f};
  const auto c = engine::FirstPersonCamera::lookingAt({4.0f, 3.0f, 6.0f}, target);
  const glm::vec4 viewport{0, 0, 1280, 720};
  const glm::vec3 pixel = glm::project(target, c.view(), c.projection(1280.0f / 720.0f), viewport);
  EXPECT_NEAR(pixel.x, 640.0f, 1e-2f);
  EXPECT_NEAR(pixel.y, 360.0f, 1e-2f);
}

TEST(Camera, PitchIsClampedShortOfStraightUp) {
  engine::FirstPersonCamera c;
  c.turn(0.0f, 500.0f);
  EXPECT_FLOAT_EQ(c.pitch, engine::FirstPersonCamera::kMaxPitch);
  c.turn(0.0f, -1000.0f);
  EXPECT_FLOAT_EQ(c.pitch, -engine::FirstPersonCamera::kMaxPitch);
}

TEST(Camera, MoveFollowsTheViewButUpIsWorldUp) {
  engine::FirstPersonCamera c;
  c.position = glm::vec3(0.0f);
  c.turn(0.0f, 30.0f);  // looking up a little
  c.move(0.0f, 2.0f, 0.0f);
  expectNear(c.position, {0, 2, 0}, 1e-6f);
  c.move(1.0f, 0.0f, 0.0f);
  expectNear(c.position, {1, 2, 0}, 1e-6f);
  c.move(0.0f, 0.0f, 1.0f);
  expectNear(c.position, glm::vec3(1, 2, 0) + c.forward(), 1e-6f);
}

}  // namespace
