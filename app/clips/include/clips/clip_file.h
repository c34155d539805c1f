#pragma once
// Reading an animation clip from a file: the first animation assimp finds in it, as a phys::Clip. A
// key is a bone's whole local rotation, its rest included (in BVH the rest is the identity), and is
// taken back to the clip's turn from the file's rest pose (docs/physics.md, "Animation"; the
// project's own clips are BVH files written by scripts/make-clips).
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "physics/animation.h"

namespace clips {

/// A clip file that cannot be read or used. what() reads "FILE: why" (the OS's reason when the file
/// could not be read, assimp's when it could not be parsed, ours when what it holds is no clip).
class ClipError : public std::runtime_error {
 public:
  ClipError(const std::filesystem::path& file, const std::string& why);
};

/// The file's clip, named after the file: its skeleton (the bones the animation moves, parents
/// before children; nodes it does not move, such as BVH's end sites, are left out), its frame time,
/// the root's position and each bone's turn at every frame. Throws ClipError, having built nothing.
phys::Clip loadClip(const std::filesystem::path& file);
/// The same from a file's content in memory; `format` is the file's extension ("bvh", ...).
phys::Clip parseClip(std::string_view content, const std::string& name, const std::string& format);

}  // namespace clips
