// What assimp is given of a COLLADA or .x clip (skeleton_only.h).
#include "skeleton_only.h"

namespace clips::detail {

std::optional<std::string> colladaSkeletonOnly(std::string_view /*content*/, const std::string& /*name*/) {
  return std::nullopt;
}

std::optional<std::string> xSkeletonOnly(std::string_view /*content*/, const std::string& /*name*/) {
  return std::nullopt;
}

}  // namespace clips::detail
