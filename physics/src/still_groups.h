#pragma once
// Which lane groups of a layout a step's passes may skip: those whose every particle has inverse
// mass 0 in this step (a sleeping island's, masked by Islands::mask; pinned; frozen). A pass moves
// no particle of inverse mass 0, so skipping such a group leaves every position as it was.
#include <cstdint>
#include <iterator>
#include <span>
#include <vector>

#include "physics/types.h"

namespace phys::detail {

template <class Group>
void markStillGroups(std::span<const Group> groups, std::span<const Real> inverseMass,
                     std::vector<std::uint8_t>& still) {
  still.resize(groups.size());  // reserved by the layout's build: no allocation in the step
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    bool moving = false;
    for (std::size_t l = 0; l < std::size(group.firstParticle) && !moving; ++l) {
      for (int i = 0; i < group.particleCount; ++i) {
        if (inverseMass[group.firstParticle[l] + i] != 0.0) {
          moving = true;
          break;
        }
      }
    }
    still[g] = moving ? 0 : 1;
  }
}

}  // namespace phys::detail
