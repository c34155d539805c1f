#include "mujoco_size.h"

#include <algorithm>

#include <mujoco/mjxmacro.h>

namespace lab::peers::mujoco_size {
namespace {

double roundUp8(double bytes) {
  return 8.0 * static_cast<double>(static_cast<std::int64_t>((bytes + 7.0) / 8.0));
}

}  // namespace

double bufferBytes(const mjModel& model, int njmaxRows, int nconmaxContacts) {
  // The X macro reads the sizes from `m`: a copy of the model's header (its pointers are only
  // copied, never followed) with the two sizes asked about.
  mjModel header = model;
  header.njmax = njmaxRows;
  header.nconmax = nconmaxContacts;
  const mjModel* m = &header;
  MJDATA_POINTERS_PREAMBLE(m)
  double bytes = 0.0;
#define X(type, name, nr, nc) \
  bytes += roundUp8(static_cast<double>(sizeof(type)) * static_cast<double>(m->nr) * static_cast<double>(nc));
  MJDATA_POINTERS
#undef X
      // The preamble's sizes are used by the macro's column counts; this keeps the compiler quiet
      // should a MuJoCo version use neither.
      (void) nv;
  (void)njmax;
  return bytes;
}

int largestRows(const mjModel& model, int nconmax, int want) {
  if (want < 1 || bufferBytes(model, 1, nconmax) > kMaxBufferBytes) return 0;
  if (bufferBytes(model, want, nconmax) <= kMaxBufferBytes) return want;
  int lo = 1, hi = want;  // fits at lo, not at hi
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (bufferBytes(model, mid, nconmax) <= kMaxBufferBytes ? lo : hi) = mid;
  }
  return lo;
}

std::int64_t stackFor(const mjModel& model, int njmax) {
  // Measured peaks (mjData::maxuse_stack) over 300 steps of the capsule ragdoll piles: 3.0 nv^2
  // with free bodies (16 and 81 ragdolls), 5.0 nv^2 as kinematic trees (16 and 136): Newton's
  // nv x nv matrices dominate. 6 nv^2 and room per row and dof; untouched stack costs no memory.
  const std::int64_t rows = njmax, nv = model.nv;
  return std::max<std::int64_t>(100000, 6 * nv * nv + 100 * (rows + nv));
}

}  // namespace lab::peers::mujoco_size
