#pragma once
// Reading an animation clip from a file: the first animation assimp finds in it, as a phys::Clip. A
// key is a bone's whole local rotation, its rest included (in BVH the rest is the identity), and is
// taken back to the clip's turn from the file's rest pose (docs/physics.md, "Animation"; the
// project's own clips are BVH files written by scripts/make-clips).
#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "physics/animation.h"

namespace clips {

/// A clip file that cannot be read or used. what() reads "FILE: why", or "FILE:LINE: why" where the
/// reason has a line (the OS's reason when the file could not be read, assimp's when it could not
/// be parsed, ours when what it holds is no clip; and ours, before assimp reads the file, for a
/// format no clip is read from and for what assimp would take on trust: nesting too deep, counts the
/// file does not hold; docs/physics.md, "Animation").
class ClipError : public std::runtime_error {
 public:
  ClipError(const std::filesystem::path& file, const std::string& why);
  ClipError(const std::filesystem::path& file, std::size_t line, const std::string& why);
};

/// The file's clip, named after the file: its skeleton (the bones the animation moves, parents
/// before children; nodes it does not move, such as BVH's end sites, are left out), its frame time,
/// the root's position and each bone's turn at every frame. Throws ClipError, having built nothing.
phys::Clip loadClip(const std::filesystem::path& file);
/// The same from a file's content in memory; `format` is the file's extension ("bvh", ...) in any case.
phys::Clip parseClip(std::string_view content, const std::string& name, const std::string& format);

}  // namespace clips
