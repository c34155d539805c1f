#pragma once
// The check the world's adders and the builders make of their input: bad input is refused with
// std::invalid_argument, whose message says what and which call.
#include <stdexcept>
#include <string>

namespace phys::detail {

inline void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace phys::detail
