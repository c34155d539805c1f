#include "text.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <system_error>

namespace lab {

std::string printed(const char* format, ...) {
  std::va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(static_cast<std::size_t>(std::max(size, 0)), '\0');
  std::vsnprintf(out.data(), out.size() + 1, format, again);
  va_end(again);
  return out;
}

std::string formatNumber(double value, int digits) {
  if (std::isnan(value)) return "n/a";
  if (std::isinf(value)) return kBlewUp;
  return printed("%.*g", digits, value);
}

std::string formatFigure(double value, const std::string& unitAfter, int digits) {
  return std::isfinite(value) ? formatNumber(value, digits) + unitAfter : formatNumber(value, digits);
}

std::string formatLimit(double value) {
  if (!std::isfinite(value)) return formatNumber(value);
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return ec == std::errc() ? std::string(buffer, end) : formatNumber(value, 17);
}

std::string count(std::size_t n, const char* singular, const char* plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string out;
  for (const std::string& p : parts) out += (out.empty() ? "" : separator) + p;
  return out;
}

std::string joinNumbers(const std::vector<int>& numbers, const std::string& separator) {
  std::vector<std::string> parts;
  parts.reserve(numbers.size());
  for (const int n : numbers) parts.push_back(std::to_string(n));
  return join(parts, separator);
}

std::optional<std::vector<std::string>> splitList(const std::string& text) {
  std::vector<std::string> items(1);
  for (const char c : text) {
    if (c == ',')
      items.emplace_back();
    else
      items.back() += c;
  }
  const bool anyEmpty =
      std::any_of(items.begin(), items.end(), [](const std::string& i) { return i.empty(); });
  return anyEmpty ? std::nullopt : std::optional(items);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  // The lower middle is the largest of the elements nth_element left before mid.
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

std::string ixs(int iterations, int substeps) {
  return std::to_string(iterations) + "x" + std::to_string(substeps);
}

std::string settingLabel(phys::SolverMethod method, int iterations, int substeps) {
  return std::string(phys::toString(method)) + " " + ixs(iterations, substeps);
}

std::string ixsWords(int iterations, int substeps, const char* between) {
  return count(static_cast<std::size_t>(iterations), "iteration", "iterations") + between +
         count(static_cast<std::size_t>(substeps), "substep", "substeps");
}

}  // namespace lab
