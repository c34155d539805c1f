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
  a.still = layout.still().empty() ? nullptr : layout.still().data();
  a.allGroups = a.groups;
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
  a.still = layout.still().empty() ? nullptr : layout.still().data();
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
  a.still = layout.still().empty() ? nullptr : layout.still().data();
  return a;
}

namespace {

template <class Arguments>
using Kernel = void (*)(const Arguments&);

// The copy `isa` asks for where the CPU has it (avx2 is null in a build without that copy), else
// the baseline's; nothing for no groups.
template <class Arguments>
void runKernel(const Arguments& a, [[maybe_unused]] LaneIsa isa, [[maybe_unused]] Kernel<Arguments> avx2,
               Kernel<Arguments> baseline) {
  if (a.groupCount == 0) return;
#if defined(PHYS_AVX2_LANES)
  if (isa == LaneIsa::Avx2 && kBest == LaneIsa::Avx2) return avx2(a);
#endif
  baseline(a);
}

#if defined(PHYS_AVX2_LANES)
#define PHYS_AVX2_KERNEL(name) &avx2::name
#else
#define PHYS_AVX2_KERNEL(name) nullptr
#endif

}  // namespace

void dampBodyLanes(const DampLaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(dampBodyLanes), &baseline::dampBodyLanes);
}

void solveLinkLanes(const LinkLaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(solveLinkLanes), &baseline::solveLinkLanes);
}

void relaxGaussSeidelLanes(const LaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(relaxGaussSeidelLanes), &baseline::relaxGaussSeidelLanes);
}

void relaxXpbdLanes(const LaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(relaxXpbdLanes), &baseline::relaxXpbdLanes);
}

void relaxShakeLanes(const LaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(relaxShakeLanes), &baseline::relaxShakeLanes);
}

void relaxJacobiLanes(const LaneArguments& a, LaneIsa isa) {
  runKernel(a, isa, PHYS_AVX2_KERNEL(relaxJacobiLanes), &baseline::relaxJacobiLanes);
}

#undef PHYS_AVX2_KERNEL

}  // namespace phys::detail
