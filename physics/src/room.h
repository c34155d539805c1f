#pragma once
// Room kept in the arrays the step fills (pairs, contact points), so that the step does not
// allocate (docs/performance.md, "No allocation in the step").
#include <algorithm>
#include <cstddef>
#include <vector>

namespace phys::detail {

/// Room for pairs and for body-body contact points, per body, made when the pairs are found, so
/// that a world whose bodies each touch a few others does not allocate in the step. Measured at
/// most: 2.2 pairs and 0.4 points a body in Bullet's pile, 4 and 1.7 in the 16 ragdolls; a
/// pyramid's 5.2 pairs grow the room in its first second.
inline constexpr std::size_t kRoomPerBody = 3;

/// Makes room in v for `room` elements (what the bodies are given), and for twice what was used
/// last once that passes three quarters of the room there is, so that a step allocates only when
/// the world gathers half as many pairs or contact points again as it had when the room last grew.
/// (At two thirds it was a third again: the box of boxes, settling, crept from 456 points to 609
/// after its first second.)
template <typename T>
void keepRoom(std::vector<T>& v, std::size_t used, std::size_t room) {
  if (4 * used > 3 * v.capacity()) room = std::max(room, 2 * used);
  if (v.capacity() < room) v.reserve(room);
}

}  // namespace phys::detail
