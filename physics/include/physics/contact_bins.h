#pragma once
// The contacts of particle bodies, between bodies and with the ground, dealt into two bins that
// share no particle, so that two threads can run the passes' contact and friction stages at once
// (docs/physics.md, "Threads"). The contacts between bodies are solved by Gauss-Seidel, each
// reading what the ones before it moved, so they cannot be cut anywhere; but two bodies joined by
// no chain of contacts touch none of the same particles in those stages. So the bodies are joined
// by this step's contacts (a union-find, as Islands joins them, but by contacts alone: the sticks
// and links run in stages of their own), and whole groups go to one bin or the other. Each bin
// takes its contacts, then its ground points, in the order one loop over all of them takes them,
// and a particle is touched by one bin only: the result is the same bit for bit as one loop.
//
// The groups are found when the narrow phase finds its manifolds from the broad phase's pairs. In
// the step's other substeps the manifolds are those pairs' or fewer, so the groups can only have
// come apart, and a bin still shares nothing with the other: only the ranges of the contacts,
// whose indices change as manifolds come and go, are found again.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "physics/constraints.h"
#include "physics/narrow_phase.h"
#include "physics/types.h"

namespace phys {

/// The most of the work one bin may take for the bins to be used: beyond it (a pyramid is one
/// group), the ground's points in pieces and the contacts between bodies on one thread do better.
inline constexpr Real kMostBinShare = 0.7;

class ContactBins {
 public:
  /// Consecutive indices of one bin's contacts or ground points, in the order of the list.
  struct Range {
    std::uint32_t begin = 0, end = 0;
  };

  /// Groups the `bodies` bodies by the manifolds between them (the world deals only without rigid
  /// bodies) and deals the groups, in the order of their first bodies, to the first bin until it
  /// holds half the work (a contact or a ground point each), then to the second; then ranges the
  /// ground points and the contacts. Returns dealt(): whether the larger bin holds at most
  /// kMostBinShare of the work.
  bool deal(std::span<const Manifold> manifolds, std::span<const GroundContact> ground, std::size_t bodies);
  /// Ranges the contacts again by the bins of the last deal (the narrow phase's later substeps).
  void rangeContacts(std::span<const Manifold> manifolds);
  /// Finds whose each ground point is (deal does when their number changed; World::updateLayouts
  /// when bodies were added, which may replace points). Allocates.
  void indexGround(std::span<const GroundContact> ground);
  /// Forgets the bins: dealt() is false until the next deal.
  void clear() { dealt_ = false; }

  bool dealt() const { return dealt_; }
  std::span<const Range> contactRanges(int bin) const { return contactRanges_[bin]; }
  std::span<const Range> groundRanges(int bin) const { return groundRanges_[bin]; }

 private:
  std::uint32_t root(std::uint32_t body);
  static void append(std::vector<Range>& ranges, std::uint32_t begin, std::uint32_t count);

  // The ground's points by owner: a body's run of them, or a loose particle's one.
  struct Owner {
    BodyId body;
    std::uint32_t begin, end;
  };
  std::vector<Owner> owners_;
  std::size_t indexedGround_ = 0;      // the number of ground points owners_ is of
  std::vector<std::uint32_t> parent_;  // per body: union-find over the contacts
  std::vector<std::uint32_t> work_;    // per body: its group's work, at the group's root
  std::vector<std::uint8_t> bin_;      // per body: 0 or 1, its group's bin
  std::vector<Range> contactRanges_[2];
  std::vector<Range> groundRanges_[2];
  bool dealt_ = false;
};

}  // namespace phys
