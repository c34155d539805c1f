#pragma once
// Replacing a file all at once, so a crash or a full disk never leaves half a scene behind.
#include <filesystem>
#include <string_view>

namespace scenes::detail {

/// Writes `content` to a new temporary file beside `file` (same folder, hence same file
/// system), flushes it to disk, then renames it over `file`: readers see the old file or the
/// new one, never a mix. A new file gets the usual permissions (0666 less the umask); a
/// replaced one keeps its own. A symbolic link is followed and its target replaced. On any error
/// the temporary file is removed, `file` is untouched, and SaveError names `file` and the cause.
void replaceFileAtomically(const std::filesystem::path& file, std::string_view content);

}  // namespace scenes::detail
