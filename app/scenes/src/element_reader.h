#pragma once
// Reads one XML element's attributes strictly: every attribute must be asked for (an unknown
// one is an error), numbers must parse whole and be finite, and every error names the file,
// the line of the offending attribute and its name.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "physics/settings.h"
#include "physics/types.h"
#include "scenes/scene.h"

namespace scenes::detail {

/// What is wrong with a value that holds a control character a scene file refuses (below U+0020
/// but tab, line feed and carriage return; U+0080 to U+009F), as "holds the control character
/// ...", or empty: one test for the reader and the writer, so that what is written loads.
std::string controlCharacterProblem(std::string_view value);

/// The first bytes of `bytes` that are not UTF-8 (RFC 3629), a sequence's lead up to the byte that
/// breaks it; empty if there are none. One test for the loader, which refuses a file holding
/// them, and the writer, which refuses to write them.
std::string_view firstNotUtf8(std::string_view bytes);

/// Maps a pointer into the parsed buffer back to a 1-based line number.
class LineIndex {
 public:
  /// An offset into the buffer: 32 bits, as a scene is at most kMaxSceneBytes (generators.h), so
  /// that a file of newlines costs 4 bytes of index a byte, not 8.
  using Offset = std::uint32_t;

  /// `size` must not pass kMaxSceneBytes (the loader refuses a longer text first).
  LineIndex(const char* begin, std::size_t size);
  int lineOf(const char* p) const;
  /// The memory the index holds (bytes).
  std::size_t bytes() const { return newlines_.capacity() * sizeof(Offset); }

 private:
  const char* begin_;
  std::vector<Offset> newlines_;  // offsets of '\n'
};

class ElementReader {
 public:
  ElementReader(const pugi::xml_node& node, const LineIndex& lines, const std::string& file);

  /// Errors name this element's line, or the attribute's when one is given.
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail(std::string_view attribute, const std::string& message) const;

  bool has(std::string_view name) const;
  std::optional<std::string> text(std::string_view name);
  std::string requiredText(std::string_view name);
  /// A finite number; `unit` goes into the error message ("m", "kg", ...).
  std::optional<phys::Real> number(std::string_view name, std::string_view unit);
  /// `word`, a piece of attribute `name`'s value, as parseReal reads it (nullopt when it is no
  /// finite number, for the caller to say what was expected), except that a number that
  /// underflows is refused here as too small to represent: the one place that says so.
  std::optional<phys::Real> real(std::string_view name, std::string_view word, std::string_view unit) const;
  phys::Real requiredNumber(std::string_view name, std::string_view unit);
  /// A whole number in [min, max].
  std::optional<long> integer(std::string_view name, long min, long max);
  long requiredInteger(std::string_view name, long min, long max);
  /// Three finite numbers separated by white space; with allowScalar, one number stands for
  /// three equal ones.
  std::optional<phys::Vec3> vector(std::string_view name, std::string_view unit, bool allowScalar = false);
  phys::Vec3 requiredVector(std::string_view name, std::string_view unit, bool allowScalar = false);
  /// A vector of no unit made of length 1: refused when zero (under 1e-9 long) or when its length
  /// overflows (components past about 1e154), which divided it down to zero.
  std::optional<phys::Vec3> direction(std::string_view name);
  /// Three whole numbers in [min, max].
  std::optional<glm::ivec3> integers3(std::string_view name, int min, int max);
  std::optional<bool> boolean(std::string_view name);
  /// friction (both coefficients), then static-friction and dynamic-friction (each alone), all
  /// >= 0, over what `material` already holds.
  void material(phys::Material& material);

  /// Refuses a value that holds a control character XML does not allow (all below U+0020 but tab,
  /// line feed and carriage return), or a C1 control (U+0080 to U+009F), as a byte or as a
  /// reference such as &#27;, which pugixml takes. text() checks every value it reads.
  void refuseControlCharacters(std::string_view attribute, std::string_view value) const;

  /// Call once every attribute has been read: any attribute not asked for is an error.
  void rejectUnknownAttributes() const;
  int line() const;
  /// "<box>", or "text" for a text node: how messages name the node.
  std::string what() const;
  const std::string& file() const { return file_; }

 private:
  pugi::xml_attribute find(std::string_view name);

  pugi::xml_node node_;
  const LineIndex& lines_;
  const std::string& file_;
  std::vector<std::string> asked_;
};

/// A number as the error messages print it: "1e-06", "1000", "0.5".
std::string formatNumber(phys::Real value);

/// Whether a point is within the world's bound along every axis: what a scene file may place, and
/// what the writer may save.
using phys::insideBound;

/// Parses a whole finite number; nullopt for anything else (junk after it, NaN, infinity).
std::optional<phys::Real> parseReal(std::string_view text);
/// Whether parseReal refused `text` only because it is a number nearer zero than any double but
/// zero (it underflows, as 1e-400 does): finite, but not representable.
bool tooSmallToRepresent(std::string_view text);

}  // namespace scenes::detail
