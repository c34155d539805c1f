#pragma once
// The loader's entry for text with its limits given, so that tests reach the refusal of a text
// over kMaxSceneBytes, or of more than kMaxConstraints constraints (generators.h), without a text
// of that size.
#include <cstddef>
#include <string>
#include <string_view>

#include "generators.h"
#include "scenes/scene.h"

namespace scenes::detail {

/// Limits of one load, each held to the loader's own (a larger one is the loader's).
struct TextLimits {
  std::size_t bytes = kMaxSceneBytes;         ///< the text's size
  std::size_t constraints = kMaxConstraints;  ///< the constraint elements, <stick> to <no-collision>
};

/// scenes::loadSceneText, refusing a text of more than `limits.bytes` before it is copied, and
/// one of more than `limits.constraints` constraints at the first element past them.
Scene loadSceneText(std::string_view xml, const std::string& displayName, const TextLimits& limits,
                    const LoadOptions& options = {});

}  // namespace scenes::detail
