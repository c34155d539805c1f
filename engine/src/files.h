#pragma once
// How the engine reads its input files (shaders, models), with the failures app/fileio's
// readWhole reports (docs/architecture.md, "Files"): the engine cannot link fileio, which is in
// app/, a layer above it (docs/architecture.md, "Layers"). Every failure throws engine::Error
// "FILE: what failed: the OS's reason", `kind` saying what the file was meant to be.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace engine::detail {

/// Opens `file` and closes it again, so that a reader that says less (assimp: "Unable to open
/// file") is only handed a file it can open. Refuses a folder, and anything but a regular file:
/// assimp would wait for ever to open a pipe that has no writer, and seeks to find a file's size,
/// which a pipe or a device cannot do.
void checkRegularFile(const std::filesystem::path& file, std::string_view kind);

/// The whole content of `file`: a regular file, or a pipe or device read until its end. Refuses
/// a folder, and more than maxBytes (so /dev/zero is refused, not read until memory runs out).
std::string readWhole(const std::filesystem::path& file, std::size_t maxBytes, std::string_view kind);

}  // namespace engine::detail
