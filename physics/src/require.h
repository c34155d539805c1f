#pragma once
// The check the world's adders and the builders make of their input: bad input is refused with
// std::invalid_argument, whose message says what and which call.
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace phys::detail {

inline void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

/// The message of requireIndex's refusal, made out of line: the check itself stays a compare.
[[noreturn]] inline void refuseIndex(std::string_view call, std::string_view what, std::size_t index,
                                     std::size_t count) {
  throw std::invalid_argument(std::string(call) + ": " + std::string(what) + " " + std::to_string(index) +
                              " does not exist (there are " + std::to_string(count) + ")");
}

/// Refuses an id or index of one of `count` things that does not exist, naming the call and what it
/// indexes: "bodyPose: body 7 does not exist (there are 2)". Nothing is made unless it fails, so a
/// query may check every call.
inline void requireIndex(std::size_t index, std::size_t count, std::string_view call, std::string_view what) {
  if (index >= count) [[unlikely]]
    refuseIndex(call, what, index, count);
}

/// The message of requireEnum's refusal, made out of line as refuseIndex's.
[[noreturn]] inline void refuseEnum(std::string_view call, std::string_view what, std::string_view type,
                                    int value, int count) {
  throw std::invalid_argument(std::string(call) + ": " + std::string(what) + " must be a " +
                              std::string(type) + ", 0 to " + std::to_string(count - 1) + " (is " +
                              std::to_string(value) + ")");
}

/// Refuses a value cast from outside an enum whose `count` values are numbered from 0, before it
/// indexes a table: "Ragdoll::part: part must be a RagdollPart, 0 to 9 (is 40)".
inline void requireEnum(int value, int count, std::string_view call, std::string_view what,
                        std::string_view type) {
  if (value < 0 || value >= count) [[unlikely]]
    refuseEnum(call, what, type, value, count);
}

/// A number as a message shows it: "1e+200", "inf", "nan", not std::to_string's 200 digits.
inline std::string numberText(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

}  // namespace phys::detail
