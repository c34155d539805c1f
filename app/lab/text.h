#pragma once
// The lab's small text helpers, one of each: numbers as its tables print them, printf's cells as
// a string, comma lists as its options take them, the setting label every command prints, and the
// median of timings.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "physics/settings.h"

namespace lab {

/// The figure of a run that blew up, and one a run does not have (a peer's of ours): formatNumber
/// prints them kBlewUp and "n/a".
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// What every table, summary and sentence of the lab prints for a figure that ran away to
/// infinity (a run that blew up: its error, its gap, its worst ratio), never "inf".
inline constexpr const char* kBlewUp = "blew up";

/// printf's %.{digits}g: "0.0125", "1e-06"; kBlewUp for an infinite figure, and "n/a" for NaN, a
/// figure that is not a number at all (an energy drift of inf - inf), never "inf" or "nan".
std::string formatNumber(double value, int digits = 6);
/// formatNumber and the unit after it ("0.0125 m"), or the words alone for a figure that is not
/// finite ("blew up", not "blew up m").
std::string formatFigure(double value, const std::string& unitAfter, int digits = 6);

/// printf's formatting as a string, however long: the fixed-width cells of the lab's tables
/// ("%-13s %9.2e"). The arguments are numbers and C strings, as printf takes them.
/// The format attribute lets -Wformat check every call's arguments against its format, as it
/// checks printf's.
std::string printed(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// A limit someone wrote (a --target bound, a criterion's max): the shortest text that reads back
/// as the same double ("0.001", "1e-320", "2147483647"), so it prints as written wherever it
/// appears, where %g would round a subnormal's few bits to other digits ("9.99989e-321").
/// Not finite: as formatNumber.
std::string formatLimit(double value);

/// "1 substep", "3 substeps": a count and its noun.
std::string count(std::size_t n, const char* singular, const char* plural);

/// The parts with `separator` between each two.
std::string join(const std::vector<std::string>& parts, const std::string& separator);

/// Whole numbers with `separator` between each two: "1, 3, 10".
std::string joinNumbers(const std::vector<int>& numbers, const std::string& separator = ", ");

/// "a,b,c" split at the commas; nullopt when an item is empty ("a,,b", "a,", "").
std::optional<std::vector<std::string>> splitList(const std::string& text);

/// Appends v unless it is there already: a value listed twice counts once.
template <typename T>
void addOnce(std::vector<T>& list, const T& v) {
  if (std::find(list.begin(), list.end(), v) == list.end()) list.push_back(v);
}

/// The median; 0 for no values. Takes a copy, since it reorders.
double median(std::vector<double> values);

/// "3x1": iterations before substeps, the order the project writes settings in everywhere.
std::string ixs(int iterations, int substeps);
/// "gauss-seidel 3x1": a method and its iterations x substeps.
std::string settingLabel(phys::SolverMethod method, int iterations, int substeps);
/// "3 iterations x 1 substep": the same in words, for prose; `between` in place of " x ".
std::string ixsWords(int iterations, int substeps, const char* between = " x ");

}  // namespace lab
