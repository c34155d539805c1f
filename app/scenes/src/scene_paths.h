#pragma once
// Where a scene file's clip names start from, for the loader and the writer alike, so that a file
// saved names its clips as loading it reads them.
#include <filesystem>

namespace scenes::detail {

/// The folder a scene file's relative clip names start from: the folder of the file `sceneFile`
/// names once symbolic links are followed, its own as fileio::writeAtomically follows it (Save As
/// through a link writes what the link points at) and every folder's on the way (as the system
/// reads a "../" in a clip's name). The file need not exist. Throws fileio::FileError with the
/// system's reason.
std::filesystem::path clipFolder(const std::filesystem::path& sceneFile);

/// An absolute clip path with its folder's links resolved as clipFolder resolves a scene's, so that
/// the one is named relative to the other by the shortest way; the path as it was if they cannot
/// be (the path still names the file).
std::filesystem::path resolvedClip(const std::filesystem::path& clip);

}  // namespace scenes::detail
