#pragma once
// The ground's points in pieces that share no particle, for the step's threads: a body's points
// share its particles and a loose particle has one point, so a cut between two points of
// different owners leaves each piece its own particles, and the pieces at once do exactly what one
// loop over all the points does (docs/physics.md, "Threads").
#include <algorithm>
#include <cstddef>
#include <span>

#include "physics/constraints.h"
#include "physics/workers.h"

namespace phys::detail {

/// Ground points one thread takes at a time: some tens of microseconds of a pass.
inline constexpr std::size_t kGroundPointsPerPiece = 4096;
/// Fewer points than this are not worth a thread: a few microseconds of a pass.
inline constexpr std::size_t kFewestGroundPointsPerPiece = 1024;

/// f(begin, end) over [0, points.size()): on the step's threads in pieces of about
/// kGroundPointsPerPiece, or one a thread of at least kFewestGroundPointsPerPiece (Bullet's pile
/// has 2,992 points), cut only between owners; or once over all of them without threads.
template <class F>
void forEachGroundPiece(const Workers* workers, std::span<const GroundContact> points, F&& f) {
  const std::size_t count = points.size();
  const std::size_t pieces = workers == nullptr
                                 ? 1
                                 : std::max((count + kGroundPointsPerPiece - 1) / kGroundPointsPerPiece,
                                            std::min(static_cast<std::size_t>(workers->threads()),
                                                     count / kFewestGroundPointsPerPiece));
  if (pieces <= 1) {
    f(std::size_t{0}, count);
    return;
  }
  auto sameOwner = [&](std::size_t a, std::size_t b) {
    return points[a].body != kNoBody
               ? points[a].body == points[b].body
               : points[b].body == kNoBody && points[a].point.particle[0] == points[b].point.particle[0];
  };
  // Where piece k starts: its even share's start, moved on past the points of the owner there.
  auto start = [&](std::size_t k) {
    std::size_t i = count * k / pieces;
    while (i > 0 && i < count && sameOwner(i - 1, i)) ++i;
    return i;
  };
  auto range = [&](std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      const std::size_t begin = start(k), end = start(k + 1);
      if (begin < end) f(begin, end);
    }
  };
  workers->forEach(pieces, 1, range);
}

}  // namespace phys::detail
