#include "euler_angles.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

namespace scenes::detail {

// glm's quaternion from Euler angles is qz qy qx: a turn about x first, then y, then z, all
// about world axes (the scene-file convention, checked by the writer's tests).
phys::Quat orientationFromEuler(const phys::Vec3& degrees) {
  return phys::Quat(glm::radians(degrees));
}

// With R = Rz(z) Ry(y) Rx(x), the first column is (cy cz, cy sz, -sy), so z = atan2(R10, R00)
// whenever cos y > 0. Rather than read x and y off entries divided by cos y (which lose all
// precision near y = +-90 degrees), undo the z turn: M = Rz(-z) R = Ry(y) Rx(x) has
// M00 = cy, M20 = -sy, M11 = cx and M12 = -sx, each read without a division. Near gimbal lock
// z is ill-defined, but whatever z atan2 returns, x then absorbs it, so the rotation still
// comes back to round-off.
phys::Vec3 eulerFromOrientation(const phys::Quat& q) {
  const glm::dmat3 m = glm::mat3_cast(glm::normalize(q));
  auto r = [&m](int row, int column) { return m[column][row]; };  // glm stores columns
  const double z = std::atan2(r(1, 0), r(0, 0));
  const double cz = std::cos(z), sz = std::sin(z);
  const double y = std::atan2(-r(2, 0), cz * r(0, 0) + sz * r(1, 0));
  const double x = std::atan2(sz * r(0, 2) - cz * r(1, 2), cz * r(1, 1) - sz * r(0, 1));
  return glm::degrees(phys::Vec3(x, y, z));
}

}  // namespace scenes::detail
