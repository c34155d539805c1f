// The rotation read back from a body's particles (detail::nearestRotation, World::bodyPose) is a
// rotation, finite, for any matrix a world can hand it: a box crushed flat, two of its corners met,
// one flung near the largest double (found by the soak test: a NaN orientation for all three).
// World::bodyCentre, the centre alone, is the pose's.
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include "physics/world.h"
#include "pose.h"

namespace {

using phys::Vec3;

void expectRotation(const glm::dmat3& R, const std::string& what) {
  for (int c = 0; c < 3; ++c) {
    ASSERT_TRUE(std::isfinite(R[c].x) && std::isfinite(R[c].y) && std::isfinite(R[c].z)) << what;
    EXPECT_NEAR(glm::length(R[c]), 1.0, 1e-9) << what << ", column " << c;
  }
  EXPECT_NEAR(glm::dot(R[0], R[1]), 0.0, 1e-9) << what;
  EXPECT_NEAR(glm::dot(R[1], R[2]), 0.0, 1e-9) << what;
  EXPECT_NEAR(glm::determinant(R), 1.0, 1e-9) << what;
}

TEST(NearestRotation, OfAWellShapedMatrixIsItsRotation) {
  // A turned a quarter about z and stretched along its own axes: the rotation is the quarter turn.
  const glm::dmat3 turn(Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, 0, 1));
  const glm::dmat3 A = turn * glm::dmat3(Vec3(3, 0, 0), Vec3(0, 0.5, 0), Vec3(0, 0, 2));
  const glm::dmat3 R = phys::detail::nearestRotation(A);
  expectRotation(R, "stretched");
  for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(R[c] - turn[c]), 1e-12) << c;
  // Scaled by any factor, even near the ends of the doubles' range, the same rotation.
  for (const double scale : {1e-300, 1e-150, 1e150, 1e300}) {
    const glm::dmat3 S = phys::detail::nearestRotation(A * scale);
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(S[c] - R[c]), 1e-12) << scale;
  }
}

TEST(NearestRotation, OfADegenerateMatrixIsStillARotation) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  struct Case {
    const char* what;
    glm::dmat3 A;
  };
  const Case cases[] = {
      {"crushed flat (rank 2)", glm::dmat3(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 0))},
      {"two corners met (rank 2, round-off det > 0)",
       glm::dmat3(Vec3(1, 2, 3), Vec3(2, 4, 6.000000000000001), Vec3(0, 0, 1e-300))},
      {"a needle (rank 1)", glm::dmat3(Vec3(0, 0, 0), Vec3(0, 5, 0), Vec3(0, 0, 0))},
      {"nearly singular, det a denormal", glm::dmat3(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, tiny))},
      {"flung 1e110 m apart",
       glm::dmat3(Vec3(1e220, 3e219, 0), Vec3(-2e219, 8e219, 1e218), Vec3(0, 1e217, 4e219))},
      {"inverted", glm::dmat3(Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1))},
      {"all zero", glm::dmat3(0.0)},
      {"not finite", glm::dmat3(Vec3(INFINITY, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, NAN))},
  };
  for (const Case& c : cases) expectRotation(phys::detail::nearestRotation(c.A), c.what);
}

// World::bodyCentre is bodyPose's centre bit for bit (lab stability reads it for its drift every
// step in place of the whole pose), for every model and shape, tumbling and resting on each other.
TEST(BodyCentre, IsThePoseCentreBitForBit) {
  phys::World w;
  int k = 0;
  for (const phys::BodyModel model :
       {phys::BodyModel::Corners, phys::BodyModel::Tetra, phys::BodyModel::Rigid}) {
    for (const phys::Shape shape : {phys::Shape::Box, phys::Shape::Capsule}) {
      phys::BodyDesc d;
      d.model = model;
      d.shape = shape;
      d.size = Vec3(0.2, 0.6, 0.2);  // a capsule along y of radius 0.1
      d.center = Vec3(0.05 * k, 0.4 + 0.5 * k, 0.0);
      d.orientation = glm::angleAxis(0.3 + 0.2 * k, glm::normalize(Vec3(1.0, 2.0, 0.5)));
      d.angularVelocity = Vec3(1.0, -2.0, 3.0);
      w.addBody(d);
      ++k;
    }
  }
  for (int step = 0; step <= 60; ++step) {
    for (std::size_t b = 0; b < w.bodies().size(); ++b) {
      const phys::BodyId id(b);
      const Vec3 centre = w.bodyCentre(id), fitted = w.bodyPose(id).center;
      EXPECT_EQ(centre.x, fitted.x) << "body " << b << ", step " << step;
      EXPECT_EQ(centre.y, fitted.y) << "body " << b << ", step " << step;
      EXPECT_EQ(centre.z, fitted.z) << "body " << b << ", step " << step;
    }
    w.step();
  }
}

}  // namespace
