// What assimp is given of a glTF clip (skeleton_only.h).
#include "skeleton_only.h"

namespace clips::detail {

std::optional<std::string> gltfSkeletonOnly(std::string_view /*json*/, const std::string& /*name*/) {
  return std::nullopt;
}

std::optional<std::string> glbSkeletonOnly(std::string_view /*content*/, const std::string& /*name*/) {
  return std::nullopt;
}

}  // namespace clips::detail
