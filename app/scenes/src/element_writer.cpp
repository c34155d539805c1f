#include "element_writer.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "element_reader.h"

namespace scenes::detail {

std::string exactNumber(double value) {
  if (value == 0.0) return "0";  // also -0, which reads back equal and looks like a typo
  char buffer[32];               // the longest shortest-round-trip double is 24 characters
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (ec != std::errc()) throw std::logic_error("exactNumber: buffer too small");
  return std::string(buffer, end);
}

std::string exactNumber(float value) {
  // The loader reads a double and the camera casts it to float. The float's own shortest text
  // almost always survives that double rounding; when it does not, the float's exact value as
  // a double does, always.
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (ec != std::errc()) throw std::logic_error("exactNumber: buffer too small");
  std::string shortest(buffer, end);
  const std::optional<phys::Real> back = parseReal(shortest);
  if (back && static_cast<float>(*back) == value) return value == 0.0f ? "0" : shortest;
  return exactNumber(static_cast<double>(value));
}

std::string escapeAttribute(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += "&#" + std::to_string(static_cast<int>(c)) + ";";
        } else {
          out += c;
        }
    }
  }
  return out;
}

ElementWriter::ElementWriter(std::string_view name) : name_(name) {}

ElementWriter& ElementWriter::text(std::string_view attribute, std::string_view value) {
  // A name from outside a scene file (a clip file found beside another) may hold what no file
  // loads.
  if (const std::string problem = controlCharacterProblem(value); !problem.empty()) {
    throw std::invalid_argument("<" + name_ + "> attribute '" + std::string(attribute) + "' " + problem +
                                ", which no scene file can hold");
  }
  // A file's name on Linux is bytes, and a clip's may be Latin-1: written as they are, the file
  // would be refused by the loader (scene files are UTF-8).
  if (const std::string_view bad = firstNotUtf8(value); !bad.empty()) {
    std::string hex;
    for (const char c : bad) {
      char byte[8];
      std::snprintf(byte, sizeof byte, " 0x%02X", static_cast<unsigned char>(c));
      hex += byte;
    }
    throw std::invalid_argument("<" + name_ + "> attribute '" + std::string(attribute) + "' holds" + hex +
                                ", which is not UTF-8, and scene files are UTF-8");
  }
  attributes_.append(" ").append(attribute).append("=\"").append(escapeAttribute(value)).append("\"");
  return *this;
}

ElementWriter& ElementWriter::number(std::string_view attribute, double value) {
  if (!std::isfinite(value)) {
    throw std::invalid_argument("<" + name_ + "> attribute '" + std::string(attribute) + "' would be " +
                                std::to_string(value) + ", which no scene file can hold");
  }
  return text(attribute, exactNumber(value));
}

ElementWriter& ElementWriter::integer(std::string_view attribute, long long value) {
  return text(attribute, std::to_string(value));
}

ElementWriter& ElementWriter::vector(std::string_view attribute, const phys::Vec3& value) {
  if (!phys::finite(value)) {
    throw std::invalid_argument("<" + name_ + "> attribute '" + std::string(attribute) +
                                "' would not be finite, which no scene file can hold");
  }
  return text(attribute, exactNumber(value.x) + " " + exactNumber(value.y) + " " + exactNumber(value.z));
}

ElementWriter& ElementWriter::vector(std::string_view attribute, const glm::vec3& value) {
  if (!std::isfinite(value.x) || !std::isfinite(value.y) || !std::isfinite(value.z)) {
    throw std::invalid_argument("<" + name_ + "> attribute '" + std::string(attribute) +
                                "' would not be finite, which no scene file can hold");
  }
  return text(attribute, exactNumber(value.x) + " " + exactNumber(value.y) + " " + exactNumber(value.z));
}

std::string ElementWriter::empty() const {
  return "<" + name_ + attributes_ + "/>";
}

std::string ElementWriter::open() const {
  return "<" + name_ + attributes_ + ">";
}

}  // namespace scenes::detail
