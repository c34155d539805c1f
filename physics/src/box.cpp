#include "physics/box.h"

namespace phys {

Vec3 boxCornerLocal(const Vec3& halfExtents, int k) {
  return {(k & 1) ? halfExtents.x : -halfExtents.x, (k & 2) ? halfExtents.y : -halfExtents.y,
          (k & 4) ? halfExtents.z : -halfExtents.z};
}

}  // namespace phys
