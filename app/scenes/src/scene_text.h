#pragma once
// The loader's entry for text with its size limit given, so that tests reach the refusal of a
// text over kMaxSceneBytes (generators.h) without 512 MiB of it.
#include <cstddef>
#include <string>
#include <string_view>

#include "scenes/scene.h"

namespace scenes::detail {

/// scenes::loadSceneText, refusing a text of more than `mostBytes` (at most kMaxSceneBytes) before
/// it is copied.
Scene loadSceneText(std::string_view xml, const std::string& displayName, std::size_t mostBytes,
                    const LoadOptions& options = {});

}  // namespace scenes::detail
