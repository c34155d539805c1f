#pragma once
// The check the world's adders and the builders make of their input: bad input is refused with
// std::invalid_argument, whose message says what and which call.
#include <sstream>
#include <stdexcept>
#include <string>

namespace phys::detail {

inline void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

/// require for the queries, which may run for every body of every step (metrics, drawing): the
/// message is only made when the check fails.
template <class Message>
void requireLazily(bool ok, const Message& what) {
  if (!ok) throw std::invalid_argument(what());
}

/// A number as a message shows it: "1e+200", "inf", "nan", not std::to_string's 200 digits.
inline std::string numberText(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

}  // namespace phys::detail
