#pragma once
// Numbers as the lab reads them from text people write (command-line options, scene
// attributes): the whole text or nothing, so "10x", "1e3" for a count, or "1.5m" is an error
// instead of a silent 10, 1 or 1.5.
#include <optional>
#include <string_view>

namespace lab {

/// The most steps a run may take: --steps, a sweep's horizon or converge's --time over its dt, a
/// scene's answer or window in steps of its dt.
inline constexpr int kMaxSteps = 10000000;

/// A whole number from low to high, nothing else: no sign, spaces, exponent or trailing text.
std::optional<int> parseWholeNumber(std::string_view text, int low, int high);

/// A finite number, nothing else: no leading '+' or spaces, no trailing text, and neither
/// "inf" nor "nan" (which from_chars would otherwise read).
std::optional<double> parseNumber(std::string_view text);

}  // namespace lab
