#include "relax_lanes.h"

#include <vector>

namespace phys::detail {
namespace {

LaneIsa detect() {
#if defined(PHYS_AVX2_LANES)
  __builtin_cpu_init();  // needed when this runs before the library's constructors
  if (__builtin_cpu_supports("avx2")) return LaneIsa::Avx2;
#endif
  return LaneIsa::Baseline;
}

const LaneIsa kBest = detect();

// The kernels read the positions as one array of doubles, x, y, z after one another. Cast, not
// &v.data()->x: an empty world's array has no first element to take a member of.
static_assert(sizeof(Vec3) == 3 * sizeof(Real) && alignof(Vec3) == alignof(Real));
Real* coordinates(std::vector<Vec3>& v) {
  return reinterpret_cast<Real*>(v.data());
}

}  // namespace

LaneIsa laneIsa() {
  return kBest;
}

LaneArguments laneArguments(Particles& p, const StickLayout& layout) {
  LaneArguments a;
  a.position = coordinates(p.position);
  a.inverseMass = p.inverseMass.data();
  a.groups = layout.lanes().data();
  a.groupCount = layout.lanes().size();
  a.localSticks = layout.localSticks().data();
  a.laneValues = layout.laneValues().data();
  a.previous = coordinates(p.previous);
  return a;
}

LinkLaneArguments linkLaneArguments(Particles& p, const LinkLayout& layout) {
  LinkLaneArguments a;
  a.position = coordinates(p.position);
  a.inverseMass = p.inverseMass.data();
  a.groups = layout.lanes().data();
  a.groupCount = layout.lanes().size();
  a.localLinks = layout.localLinks().data();
  a.laneValues = layout.laneValues().data();
  return a;
}

DampLaneArguments dampLaneArguments(Particles& p, const BodyLayout& layout, Real fraction) {
  DampLaneArguments a;
  a.position = coordinates(p.position);
  a.previous = coordinates(p.previous);
  a.inverseMass = p.inverseMass.data();
  a.groups = layout.lanes().data();
  a.groupCount = layout.lanes().size();
  a.fraction = fraction;
  return a;
}

void dampBodyLanes(const DampLaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::dampBodyLanes(a);
#endif
  baseline::dampBodyLanes(a);
}

void solveLinkLanes(const LinkLaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::solveLinkLanes(a);
#endif
  baseline::solveLinkLanes(a);
}

void relaxGaussSeidelLanes(const LaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::relaxGaussSeidelLanes(a);
#endif
  baseline::relaxGaussSeidelLanes(a);
}

void relaxXpbdLanes(const LaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::relaxXpbdLanes(a);
#endif
  baseline::relaxXpbdLanes(a);
}

void relaxShakeLanes(const LaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::relaxShakeLanes(a);
#endif
  baseline::relaxShakeLanes(a);
}

void relaxJacobiLanes(const LaneArguments& a, LaneIsa isa) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2::relaxJacobiLanes(a);
#endif
  baseline::relaxJacobiLanes(a);
}

}  // namespace phys::detail
