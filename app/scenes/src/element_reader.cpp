#include "element_reader.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <glm/geometric.hpp>

#include "generators.h"

namespace scenes::detail {
namespace {

std::vector<std::string_view> splitWhitespace(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    const std::size_t start = i;
    while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i > start) parts.push_back(text.substr(start, i - start));
  }
  return parts;
}

std::string withUnit(std::string_view unit) {
  return unit.empty() ? "" : " (" + std::string(unit) + ")";
}

// Why parseReal refused `text`, a number that underflows. It is refused rather than rounded to
// zero: zero often means something else here (a rigid stick's compliance, no friction, no
// damping), so a value a user wrote as non-zero must not quietly become it.
std::string tooSmallMessage(std::string_view text, std::string_view unit) {
  // Appended piece by piece: "'" + std::string(text) trips GCC 12's -Wrestrict false positive
  // (GCC bug 105329).
  std::string message("'");
  message.append(text).append("' is too small to represent (the smallest besides 0 is ");
  return message.append(formatNumber(std::numeric_limits<double>::denorm_min()))
      .append(")")
      .append(withUnit(unit));
}

}  // namespace

static_assert(kMaxSceneBytes <= std::numeric_limits<LineIndex::Offset>::max(),
              "LineIndex's offsets must reach the end of the largest scene file");

LineIndex::LineIndex(const char* begin, std::size_t size) : begin_(begin) {
  assert(size <= kMaxSceneBytes);
  const auto newlines = static_cast<std::size_t>(std::count(begin, begin + size, '\n'));
  newlines_.reserve(newlines);  // exactly: a file of newlines would otherwise hold up to twice that
  for (std::size_t i = 0; i < size; ++i) {
    if (begin[i] == '\n') newlines_.push_back(static_cast<Offset>(i));
  }
}

int LineIndex::lineOf(const char* p) const {
  if (p == nullptr || p < begin_) return 0;
  const auto offset = static_cast<Offset>(p - begin_);
  return static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(), offset) - newlines_.begin()) +
         1;
}

std::string formatNumber(phys::Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::optional<phys::Real> parseReal(std::string_view text) {
  if (text.empty()) return std::nullopt;
  if (text.front() == '+') text.remove_prefix(1);  // from_chars does not take a leading '+'
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

bool tooSmallToRepresent(std::string_view text) {
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc::result_out_of_range || end != text.data() + text.size()) return false;
  // Out of range either way: too small if its first significant digit stands below the units.
  const std::size_t e = text.find_first_of("eE");
  const std::string_view mantissa = text.substr(0, e);
  long long exponent = 0;
  if (e != std::string_view::npos) {
    std::string_view digits = text.substr(e + 1);
    if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
    const auto parsed = std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
    // An exponent past 1e15 outweighs any mantissa a scene file can hold.
    if (parsed.ec != std::errc() || std::llabs(exponent) > 1'000'000'000'000'000LL)
      return !digits.empty() && digits.front() == '-';
  }
  const std::size_t point = std::min(mantissa.find('.'), mantissa.size());
  const std::size_t first = mantissa.find_first_not_of("0.");
  if (first == std::string_view::npos) return false;  // zero, which is never out of range
  const long long power =
      first < point ? static_cast<long long>(point - first - 1) : -static_cast<long long>(first - point);
  return power + exponent < 0;
}

ElementReader::ElementReader(const pugi::xml_node& node, const LineIndex& lines, const std::string& file)
    : node_(node), lines_(lines), file_(file) {}

int ElementReader::line() const {
  // In-place parsing leaves names and values pointing into our buffer; a text node has no name.
  if (node_.type() == pugi::node_element) return lines_.lineOf(node_.name());
  const char* text = node_.value();
  while (*text != '\0' && std::isspace(static_cast<unsigned char>(*text))) ++text;  // to the first word
  return lines_.lineOf(text);
}

std::string ElementReader::what() const {
  if (node_.type() != pugi::node_element) return "text";
  // Appended piece by piece: "<" + std::string(name) + ">" trips GCC 12's -Wrestrict false
  // positive (GCC bug 105329).
  std::string out("<");
  out.append(node_.name());
  out.push_back('>');
  return out;
}

void ElementReader::fail(const std::string& message) const {
  throw LoadError(file_, line(), "", what() + ": " + message);
}

void ElementReader::fail(std::string_view attribute, const std::string& message) const {
  int at = line();
  for (pugi::xml_attribute a = node_.first_attribute(); a; a = a.next_attribute()) {
    if (attribute == a.name()) at = lines_.lineOf(a.name());
  }
  throw LoadError(file_, at, std::string(attribute),
                  what() + " attribute '" + std::string(attribute) + "': " + message);
}

pugi::xml_attribute ElementReader::find(std::string_view name) {
  asked_.emplace_back(name);
  for (pugi::xml_attribute a = node_.first_attribute(); a; a = a.next_attribute()) {
    if (name == a.name()) return a;
  }
  return {};
}

bool ElementReader::has(std::string_view name) const {
  for (pugi::xml_attribute a = node_.first_attribute(); a; a = a.next_attribute()) {
    if (name == a.name()) return true;
  }
  return false;
}

std::optional<std::string> ElementReader::text(std::string_view name) {
  const pugi::xml_attribute a = find(name);
  if (!a) return std::nullopt;
  std::string value = a.value();
  refuseControlCharacters(name, value);
  return value;
}

// A name holding an escape would reach the sandbox's labels and the lab's terminal and files as
// one. Below U+0020 XML forbids them (but tab, line feed and carriage return), so the file is
// wrong, whatever pugixml takes. U+0080 to U+009F (UTF-8 0xC2 0x80 to 0xC2 0x9F) XML 1.0 lets be,
// but xterm takes U+009B as the start of an escape, as it does ESC [, so a name holding one drove
// the lab's terminal.
std::string controlCharacterProblem(std::string_view value) {
  for (std::size_t i = 0; i < value.size(); ++i) {
    const auto byte = static_cast<unsigned char>(value[i]);
    char code[8];
    if (byte < 0x20 && byte != '\t' && byte != '\n' && byte != '\r') {
      std::snprintf(code, sizeof code, "0x%02X", byte);
      return std::string("holds the control character ") + code +
             ", which XML does not allow (only tab, line feed and carriage return)";
    }
    if (byte != 0xC2 || i + 1 >= value.size()) continue;
    const auto next = static_cast<unsigned char>(value[i + 1]);
    if (next < 0x80 || next > 0x9F) continue;
    std::snprintf(code, sizeof code, "U+%04X", next);
    return std::string("holds the control character ") + code +
           ", which a terminal may take as an escape (U+0080 to U+009F are refused)";
  }
  return {};
}

// The first bytes that are not UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing past
// U+10FFFF): a sequence's lead up to the byte that breaks it; empty if there are none. pugixml
// passes such bytes through, so a Latin-1 name would reach the sandbox's labels and the lab's
// CSVs as bytes no reader can decode.
std::string_view firstNotUtf8(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size()) {
    const auto lead = static_cast<unsigned char>(bytes[i]);
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;  // the second byte's range, narrowed for some leads
    if (lead < 0x80) {
      length = 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) low = 0xA0;   // overlong below U+0800
      if (lead == 0xED) high = 0x9F;  // the surrogates U+D800 to U+DFFF
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) low = 0x90;   // overlong below U+10000
      if (lead == 0xF4) high = 0x8F;  // past U+10FFFF
    } else {
      return bytes.substr(i, 1);  // a continuation byte alone, an overlong lead (C0, C1) or F5 to FF
    }
    for (std::size_t k = 1; k < length; ++k) {
      if (i + k == bytes.size()) return bytes.substr(i);  // cut short by the end of the file
      const auto c = static_cast<unsigned char>(bytes[i + k]);
      if (c < (k == 1 ? low : 0x80) || c > (k == 1 ? high : 0xBF)) return bytes.substr(i, k + 1);
    }
    i += length;
  }
  return {};
}

void ElementReader::refuseControlCharacters(std::string_view attribute, std::string_view value) const {
  if (const std::string problem = controlCharacterProblem(value); !problem.empty()) fail(attribute, problem);
}

std::string ElementReader::requiredText(std::string_view name) {
  std::optional<std::string> value = text(name);
  if (!value) fail(name, "is required");
  if (value->empty()) fail(name, "must not be empty");
  return *value;
}

std::optional<phys::Real> ElementReader::number(std::string_view name, std::string_view unit) {
  const std::optional<std::string> raw = text(name);
  if (!raw) return std::nullopt;
  const std::optional<phys::Real> value = real(name, *raw, unit);
  if (!value) fail(name, "'" + *raw + "' is not a finite number" + withUnit(unit));
  return value;
}

std::optional<phys::Real> ElementReader::real(std::string_view name, std::string_view word,
                                              std::string_view unit) const {
  const std::optional<phys::Real> value = parseReal(word);
  if (!value && tooSmallToRepresent(word)) fail(name, tooSmallMessage(word, unit));
  return value;
}

phys::Real ElementReader::requiredNumber(std::string_view name, std::string_view unit) {
  const std::optional<phys::Real> value = number(name, unit);
  if (!value) fail(name, "is required" + withUnit(unit));
  return *value;
}

std::optional<long> ElementReader::integer(std::string_view name, long min, long max) {
  const std::optional<std::string> raw = text(name);
  if (!raw) return std::nullopt;
  long value = 0;
  const auto [end, ec] = std::from_chars(raw->data(), raw->data() + raw->size(), value);
  if (ec != std::errc() || end != raw->data() + raw->size() || value < min || value > max) {
    fail(name,
         "'" + *raw + "' must be a whole number from " + std::to_string(min) + " to " + std::to_string(max));
  }
  return value;
}

long ElementReader::requiredInteger(std::string_view name, long min, long max) {
  const std::optional<long> value = integer(name, min, max);
  if (!value)
    fail(name,
         "is required (a whole number from " + std::to_string(min) + " to " + std::to_string(max) + ")");
  return *value;
}

std::optional<phys::Vec3> ElementReader::vector(std::string_view name, std::string_view unit,
                                                bool allowScalar) {
  const std::optional<std::string> raw = text(name);
  if (!raw) return std::nullopt;
  const std::vector<std::string_view> parts = splitWhitespace(*raw);
  const std::string expected = allowScalar ? "one or three finite numbers" : "three finite numbers";
  if (parts.size() != 3 && !(allowScalar && parts.size() == 1)) {
    fail(name, "'" + *raw + "' must be " + expected + withUnit(unit));
  }
  phys::Vec3 v(0.0);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::optional<phys::Real> x = real(name, parts[i], unit);
    if (!x) fail(name, "'" + *raw + "' must be " + expected + withUnit(unit));
    v[static_cast<int>(i)] = *x;
  }
  if (parts.size() == 1) v = phys::Vec3(v.x);
  return v;
}

phys::Vec3 ElementReader::requiredVector(std::string_view name, std::string_view unit, bool allowScalar) {
  const std::optional<phys::Vec3> value = vector(name, unit, allowScalar);
  if (!value) fail(name, "is required" + withUnit(unit));
  return *value;
}

std::optional<phys::Vec3> ElementReader::direction(std::string_view name) {
  const std::optional<phys::Vec3> v = vector(name, "");
  if (!v) return std::nullopt;
  const phys::Real length = glm::length(*v);  // inf for components near 1e308, and v / inf is 0
  if (!std::isfinite(length) || length < 1e-9) fail(name, "must be non-zero and of finite length");
  return *v / length;
}

std::optional<glm::ivec3> ElementReader::integers3(std::string_view name, int min, int max) {
  const std::optional<std::string> raw = text(name);
  if (!raw) return std::nullopt;
  const std::vector<std::string_view> parts = splitWhitespace(*raw);
  const std::string expected =
      "three whole numbers from " + std::to_string(min) + " to " + std::to_string(max);
  if (parts.size() != 3) fail(name, "'" + *raw + "' must be " + expected);
  glm::ivec3 v(0);
  for (int i = 0; i < 3; ++i) {
    const std::string_view p = parts[static_cast<std::size_t>(i)];
    const auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), v[i]);
    if (ec != std::errc() || end != p.data() + p.size() || v[i] < min || v[i] > max) {
      fail(name, "'" + *raw + "' must be " + expected);
    }
  }
  return v;
}

std::optional<bool> ElementReader::boolean(std::string_view name) {
  const std::optional<std::string> raw = text(name);
  if (!raw) return std::nullopt;
  if (*raw == "true") return true;
  if (*raw == "false") return false;
  fail(name, "'" + *raw + "' must be true or false");
}

void ElementReader::material(phys::Material& m) {
  auto coefficient = [this](std::string_view name) {
    const std::optional<phys::Real> mu = number(name, "");
    if (mu && *mu < 0.0) fail(name, "must be >= 0");
    return mu;
  };
  if (auto mu = coefficient("friction")) m = {*mu, *mu};
  if (auto mu = coefficient("static-friction")) m.staticFriction = *mu;
  if (auto mu = coefficient("dynamic-friction")) m.dynamicFriction = *mu;
}

void ElementReader::rejectUnknownAttributes() const {
  for (pugi::xml_attribute a = node_.first_attribute(); a; a = a.next_attribute()) {
    // XML forbids an attribute twice, but pugixml keeps both and find() would read the first.
    for (pugi::xml_attribute b = a.next_attribute(); b; b = b.next_attribute()) {
      if (std::string_view(a.name()) == b.name()) {
        throw LoadError(file_, lines_.lineOf(b.name()), a.name(),
                        what() + " attribute '" + a.name() + "': given twice");
      }
    }
    if (std::find(asked_.begin(), asked_.end(), a.name()) == asked_.end()) {
      std::string known;
      for (const std::string& k : asked_) known += (known.empty() ? "" : ", ") + k;
      fail(a.name(), "unknown attribute" + (known.empty() ? std::string(" (the element takes none)")
                                                          : " (known: " + known + ")"));
    }
  }
}

}  // namespace scenes::detail
