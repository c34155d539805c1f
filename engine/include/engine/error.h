#pragma once
// The one exception type of the engine: a message meant for the user, saying what failed and
// where (a file, a line, a driver's words).
#include <stdexcept>
#include <string>

namespace engine {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
};

}  // namespace engine
