#pragma once
// Writes one XML element of a scene file: attribute values escaped, and numbers in the
// shortest text that reads back as the very same number, so a saved world loads back unrounded.
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "physics/types.h"

namespace scenes::detail {

class ElementWriter {
 public:
  explicit ElementWriter(std::string_view name);

  ElementWriter& text(std::string_view attribute, std::string_view value);
  /// Throws std::invalid_argument for NaN or infinity, which no scene file may hold.
  ElementWriter& number(std::string_view attribute, double value);
  ElementWriter& integer(std::string_view attribute, long long value);
  ElementWriter& vector(std::string_view attribute, const phys::Vec3& value);
  /// A float vector (the camera's): written so that it reads back as the same floats.
  ElementWriter& vector(std::string_view attribute, const glm::vec3& value);

  /// `<name a="1"/>`
  std::string empty() const;
  /// `<name a="1">`, for an element with children.
  std::string open() const;

 private:
  std::string name_;
  std::string attributes_;  // ` a="1" b="2"`
};

/// The shortest decimal text that reads back (std::from_chars) as exactly `value`; "0" for -0.
std::string exactNumber(double value);
/// The shortest text that reads back as `value` through the loader's double and a cast to float.
std::string exactNumber(float value);
/// Text safe inside a double-quoted XML attribute: markup and control characters as references
/// (a raw tab or newline would come back as a space).
std::string escapeAttribute(std::string_view text);

}  // namespace scenes::detail
