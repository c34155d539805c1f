#pragma once
// Animation clips: a skeleton's poses over time, what an active ragdoll's drives follow
// (docs/physics.md, "Animation"). A clip holds, frame by frame, each bone's turn relative to its
// parent from the skeleton's rest pose and the root's position: what a BVH file holds, and what
// the clips library reads from one. Nothing here reads files.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "physics/types.h"

namespace phys {

/// Bounds that keep sampling well inside a double's range: a clip's time (s; about 32 years), its
/// shortest frame time (s) and its root's farthest position (m).
inline constexpr Real kMaxClipTime = 1e9;
inline constexpr Real kMinFrameTime = 1e-6;
inline constexpr Real kMaxClipReach = 1e6;

/// A skeleton's motion, sampled at a fixed rate.
struct Clip {
  std::string name;                ///< for messages: the file it came from, or a test's name
  std::vector<std::string> bones;  ///< bones[0] is the root; a parent comes before its children
  std::vector<int> parents;        ///< per bone: its parent's index, -1 for the root
  Real frameTime = 1.0 / 30.0;     ///< unit: s; finite, >= kMinFrameTime
  std::vector<Vec3> root;  ///< per frame: the root's position, m, in the clip's frame, within kMaxClipReach
  /// Per frame, per bone (frame-major): the bone's turn from the rest pose relative to its parent's
  /// turn, in the clip's axes carried by the parent's turn (a bone's turn in the clip's frame is its
  /// parent's times its own); the root's relative to the clip's frame. At rest every turn is the
  /// identity.
  std::vector<Quat> turns;

  std::size_t frames() const { return root.size(); }
  /// unit: s; the time from the first frame to the last. A looping clip's last frame is its first
  /// again, so that one loop lasts exactly this long.
  Real duration() const { return frames() > 1 ? static_cast<Real>(frames() - 1) * frameTime : 0.0; }
  /// The bone's index, or -1.
  int bone(std::string_view boneName) const;
};

/// Why the clip cannot be played ("" when it can): no frames or bones, a parent after its child,
/// arrays of the wrong sizes, a name used twice, a non-finite number, a frame time under
/// kMinFrameTime, a root farther than kMaxClipReach, a turn that is not a unit quaternion (within 1e-6).
std::string clipProblem(const Clip& clip);

/// "" when `a` has the same bones as `b`, in the same order, with the same parents: clips one
/// character can change between (World::playClip, queueClip, a reaction's get-up clip). Otherwise
/// why not, naming the bones: "clip 'A' has other bones than 'B': it lacks 'x'; it has 'y' that
/// 'B' has not; the parent of bone 'z' is 'p' where 'B' has 'q'" (or "... in another order").
std::string skeletonDifference(const Clip& a, const Clip& b);

/// A clip's pose at one time: the root's position and each bone's turn, as Clip holds them.
struct ClipPose {
  Vec3 root{0.0};
  std::vector<Quat> turns;  ///< per bone of the clip
};

/// The clip's pose at `time` (s, clamped to kMaxClipTime), between its two nearest frames (positions linear,
/// turns slerped). Before 0 it is the first frame. After the end it is the last, or with `loop` the time
/// taken modulo the duration, the root moved on by the first-to-last displacement once for every loop done
/// (so a run cycle goes forward). `out.turns` is resized to the clip's bones (no allocation once it has that
/// size).
void sampleClip(const Clip& clip, Real time, bool loop, ClipPose& out);

/// `a` blended towards `b` by w (0: a, 1: b): positions linear, turns slerped the short way.
/// Needs poses of the same bones; `out` may be either.
void blendPoses(const ClipPose& a, const ClipPose& b, Real w, ClipPose& out);

/// The turn `a` slerped towards `b` by w, the short way round.
Quat slerpShort(const Quat& a, const Quat& b, Real w);

}  // namespace phys
