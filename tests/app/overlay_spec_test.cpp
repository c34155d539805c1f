// The method overlay's settings strings: "key=value,..." with <solver>'s attribute names.
#include <cmath>

#include <gtest/gtest.h>

#include "overlay_spec.h"

namespace {

using sandbox::parseOverlaySpec;

TEST(OverlaySpec, OverridesOnlyTheKeysGiven) {
  const auto parsed = parseOverlaySpec("method=xpbd, substeps=8,iterations=1");
  ASSERT_EQ(parsed.error, "");
  phys::SolverSettings base;
  base.dt = 0.01;
  base.bodyDamping = 0.5;
  const phys::SolverSettings s = parsed.spec.applyTo(base);
  EXPECT_EQ(s.method, phys::SolverMethod::Xpbd);
  EXPECT_EQ(s.substeps, 8);
  EXPECT_EQ(s.iterations, 1);
  EXPECT_EQ(s.dt, 0.01);          // kept from the scene
  EXPECT_EQ(s.bodyDamping, 0.5);  // kept from the scene
  EXPECT_EQ(parsed.spec.text, "method=xpbd, substeps=8,iterations=1");
}

TEST(OverlaySpec, EveryKeyIsRead) {
  const auto parsed =
      parseOverlaySpec("dt=0.005,body-damping=1,restitution=0.3,compliance=1e-4,epsilon=0.02,slop=0.002");
  ASSERT_EQ(parsed.error, "");
  const phys::SolverSettings s = parsed.spec.applyTo({});
  EXPECT_EQ(s.dt, 0.005);
  EXPECT_EQ(s.bodyDamping, 1.0);
  EXPECT_EQ(s.restitution, 0.3);
  EXPECT_EQ(s.compliance, 1e-4);
  EXPECT_EQ(s.featureEpsilon, 0.02);
  EXPECT_EQ(s.contactSlop, 0.002);
}

TEST(OverlaySpec, ErrorsSayWhichKeyAndValue) {
  EXPECT_EQ(parseOverlaySpec("").error, "empty overlay settings; give key=value pairs such as iterations=8");
  EXPECT_EQ(parseOverlaySpec("iterations").error, "'iterations' is not key=value");
  EXPECT_EQ(parseOverlaySpec("iterations=lots").error, "iterations: 'lots' is not a whole number");
  EXPECT_EQ(parseOverlaySpec("method=magic").error,
            "method: 'magic' must be gauss-seidel, jacobi, xpbd or shake");
  EXPECT_NE(parseOverlaySpec("colour=red").error.find("unknown key 'colour'"), std::string::npos);
  // Out of range: the physics' own validation names the field.
  EXPECT_NE(parseOverlaySpec("substeps=0").error.find("substeps must be from 1"), std::string::npos);
  EXPECT_NE(parseOverlaySpec("restitution=2").error.find("restitution must be from 0 to 1"),
            std::string::npos);
}

TEST(OverlaySpec, DescribesSettingsForTheLegend) {
  phys::SolverSettings s;
  s.iterations = 2;
  s.substeps = 4;
  EXPECT_EQ(sandbox::describeSolver(s), "gauss-seidel 2x4 dt 16.7 ms");
}

}  // namespace

namespace {

TEST(OverlaySpec, DepenetrationSpeedIsAKeyToo) {
  const auto parsed = sandbox::parseOverlaySpec("depenetration-speed=0.5");
  ASSERT_EQ(parsed.error, "");
  EXPECT_EQ(parsed.spec.applyTo({}).maxDepenetrationSpeed, 0.5);
  // "none" is no limit, as <solver>'s own name for it; other words are still refused.
  const auto none = sandbox::parseOverlaySpec("depenetration-speed=none");
  ASSERT_EQ(none.error, "");
  EXPECT_TRUE(std::isinf(none.spec.applyTo({}).maxDepenetrationSpeed));
  EXPECT_EQ(sandbox::parseOverlaySpec("depenetration-speed=inf").error,
            "depenetration-speed: 'inf' must be a number > 0 (m/s) or none");
}

}  // namespace
