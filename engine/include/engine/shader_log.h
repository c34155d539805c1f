#pragma once
// Turns a GLSL compiler's log into lines of the form "file:line: message", the form editors and
// terminals link to. Drivers number lines differently; the ones we know are:
//   Mesa:          0:12(5): error: syntax error, unexpected ...
//   NVIDIA:        0(12) : error C0000: syntax error ...
//   AMD and Intel: ERROR: 0:12: 'x' : undeclared identifier
// A log line in none of these forms is kept whole, prefixed with "file: ".
#include <string>
#include <string_view>

namespace engine {

std::string formatShaderLog(std::string_view file, std::string_view driverLog);

}  // namespace engine
