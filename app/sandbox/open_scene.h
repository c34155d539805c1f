#pragma once
// How the sandbox opens every scene file: its first, one opened, Reload, a built-in.
#include <filesystem>
#include <memory>
#include <optional>

#include "scenes/scene.h"

namespace sandbox {

/// The sandbox sleeps unless a scene says `<solver sleep="off">` (a resting pile should cost
/// nothing while the user looks at it: docs/sandbox.md), and `threads`, the command line's
/// --threads, is imposed if given.
scenes::LoadOptions sceneLoadOptions(std::optional<int> threads);

/// `file` loaded with `options`, and its analytic answers, which the sandbox draws as crosses,
/// checked as the lab checks them, so a wrong one is refused with its line. Throws
/// scenes::LoadError (fileio::FileError for a file that is no regular file).
std::unique_ptr<scenes::Scene> loadCheckedScene(const std::filesystem::path& file,
                                                const scenes::LoadOptions& options);

}  // namespace sandbox
