// The first-person camera's angles, directions and matrices agree with each other.
#include <algorithm>
#include <cmath>

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

// The sandbox's orbit (middle drag), wheel zoom and framing key.
TEST(Camera, OrbitKeepsTheDistanceAndEndsLookingAtThePivot) {
  auto c = engine::FirstPersonCamera::lookingAt({0.0f, 2.0f, 8.0f}, {0.0f, 1.0f, 0.0f});
  const glm::vec3 pivot{1.0f, 1.0f, -1.0f};
  const float distance = glm::length(c.position - pivot);
  c.orbit(pivot, 40.0f, -15.0f);
  EXPECT_NEAR(glm::length(c.position - pivot), distance, 1e-4f);
  expectNear(c.forward(), glm::normalize(pivot - c.position), 1e-5f);
  const auto looking = engine::FirstPersonCamera::lookingAt(c.position, pivot);
  EXPECT_NEAR(c.yaw, looking.yaw, 1e-3f);
}

// A pivot found inside a body is the eye itself (a ray from inside hits at 0): normalising the
// way to it made every angle NaN, and the sandbox's next raycast from there threw.
TEST(Camera, OrbitAboutThePointItStandsOnTurnsInPlace) {
  auto c = engine::FirstPersonCamera::lookingAt({0.2f, 1.1f, 0.3f}, {0.0f, 1.0f, -5.0f});
  const glm::vec3 eye = c.position;
  const float yaw = c.yaw, pitch = c.pitch;
  c.orbit(eye, 30.0f, 10.0f);
  expectNear(c.position, eye, 0.0f);
  EXPECT_FLOAT_EQ(c.yaw, yaw + 30.0f);
  EXPECT_FLOAT_EQ(c.pitch, pitch + 10.0f);
  c.orbit(eye + glm::vec3(0.0f, 0.0f, 0.01f), 5.0f, 0.0f);  // nearer than the near plane
  EXPECT_TRUE(std::isfinite(c.yaw) && std::isfinite(c.pitch));
  expectNear(c.position, eye, 0.0f);
}

TEST(Camera, OrbitKeepsTheLens) {
  auto c = engine::FirstPersonCamera::lookingAt({0.0f, 2.0f, 8.0f}, {0.0f, 1.0f, 0.0f});
  c.fovY = 35.0f;
  c.nearPlane = 0.2f;
  c.farPlane = 90.0f;
  c.orbit({0.0f, 1.0f, 0.0f}, 20.0f, 5.0f);
  EXPECT_EQ(c.fovY, 35.0f);
  EXPECT_EQ(c.nearPlane, 0.2f);
  EXPECT_EQ(c.farPlane, 90.0f);
}

TEST(Camera, DollyMovesAlongTheLineToThePivotAndStopsShortOfIt) {
  engine::FirstPersonCamera c;
  const glm::vec3 pivot{3.0f, 0.0f, -4.0f}, from = c.position;
  c.dolly(pivot, 0.5f);
  expectNear(c.position, pivot + (from - pivot) * 0.5f, 1e-5f);
  const float yaw = c.yaw;
  for (int i = 0; i < 200; ++i) c.dolly(pivot, 0.5f);
  EXPECT_NEAR(glm::length(c.position - pivot), 2.0f * c.nearPlane, 1e-5f);
  EXPECT_EQ(c.yaw, yaw);  // the view's direction is the camera's own
}

TEST(Camera, FrameFitsTheBoxTightlyInTheMiddleOfTheView) {
  auto c = engine::FirstPersonCamera::lookingAt({5.0f, 6.0f, 9.0f}, {0.0f, 0.0f, 0.0f});
  const float yaw = c.yaw, pitch = c.pitch, aspect = 934.0f / 720.0f;
  const glm::vec3 lo{-1.0f, 0.0f, -0.5f}, hi{2.0f, 6.0f, 0.5f};
  EXPECT_TRUE(c.frame(lo, hi, aspect, 0.8f));
  EXPECT_EQ(c.yaw, yaw);
  EXPECT_EQ(c.pitch, pitch);
  float most = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    const glm::vec4 clip = c.projection(aspect) * c.view() * glm::vec4(corner, 1.0f);
    most = std::max({most, std::abs(clip.x / clip.w), std::abs(clip.y / clip.w)});
  }
  EXPECT_LE(most, 0.8f);
  EXPECT_GE(most, 0.799f);  // no farther than it needs to be
  const glm::vec3 centre = 0.5f * (lo + hi);
  expectNear(glm::normalize(centre - c.position), c.forward(), 1e-5f);
}

// A scene 2 km across (the bound allows 1e6 m) was "framed" from 250 m, showing none of it.
TEST(Camera, FrameSaysWhenTheBoxIsLargerThanTheViewReaches) {
  auto c = engine::FirstPersonCamera::lookingAt({0.0f, 10.0f, 30.0f}, {0.0f, 0.0f, 0.0f});
  const float aspect = 934.0f / 720.0f;
  const glm::vec3 lo{-1005.0f, 0.0f, -5.0f}, hi{1005.0f, 10.0f, 5.0f};
  EXPECT_FALSE(c.frame(lo, hi, aspect));
  expectNear(c.position, 0.5f * (lo + hi) - c.forward() * (0.5f * c.farPlane), 1e-3f);
  // What fits within the far plane is framed, however far back that is.
  const glm::vec3 wide{200.0f, 10.0f, 5.0f};
  EXPECT_TRUE(c.frame(-wide, wide, aspect));
  const glm::vec4 eye = c.view() * glm::vec4(-wide, 1.0f);
  EXPECT_GT(eye.z, -c.farPlane);
}

}  // namespace
