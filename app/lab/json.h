#pragma once
// The lab's JSON, through nlohmann/json: objects keep their keys in the order they were set (the
// order docs/lab.md lists them), so scripts and people read the same columns in the same place.
#include <string>

#include <nlohmann/json.hpp>

namespace lab {

using Json = nlohmann::ordered_json;

/// One line of JSON text ending in a newline. A figure that is not finite is written as null
/// (nlohmann's rule, and JSON has no other), and bytes that are not UTF-8 (a scene name in some
/// other encoding) are replaced rather than thrown on.
inline std::string jsonLine(const Json& value) {
  return value.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace lab
