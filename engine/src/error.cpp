#include "engine/error.h"

namespace engine {

Error::Error(const std::string& message) : std::runtime_error(message) {}

}  // namespace engine
