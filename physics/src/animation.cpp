// Animation clips (physics/animation.h): checking a clip and sampling it.
#include "physics/animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/gtc/quaternion.hpp>

namespace phys {
namespace {

bool finiteQuat(const Quat& q) {
  return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
}

// Each bone's index by name: a clip read from a file may have thousands of bones, and looking each
// one up by a walk over all of them made checking and comparing skeletons quadratic.
std::unordered_map<std::string_view, std::size_t> boneIndex(const Clip& clip) {
  std::unordered_map<std::string_view, std::size_t> index;
  index.reserve(clip.bones.size());
  for (std::size_t i = 0; i < clip.bones.size(); ++i) index.emplace(clip.bones[i], i);  // the first of a name
  return index;
}

std::string bonesProblem(const Clip& clip) {
  if (clip.bones.empty()) return "it has no bones";
  if (clip.parents.size() != clip.bones.size()) return "it has not one parent a bone";
  std::unordered_set<std::string_view> seen;
  seen.reserve(clip.bones.size());
  for (std::size_t i = 0; i < clip.bones.size(); ++i) {
    const int parent = clip.parents[i];
    if (i == 0 && parent != -1) return "its first bone '" + clip.bones[0] + "' is not the root";
    if (i > 0 && (parent < 0 || static_cast<std::size_t>(parent) >= i))
      return "bone '" + clip.bones[i] + "' does not come after its parent";
    if (clip.bones[i].empty()) return "bone " + std::to_string(i) + " has no name";
    if (!seen.insert(clip.bones[i]).second) return "two bones are named '" + clip.bones[i] + "'";
  }
  return "";
}

}  // namespace

int Clip::bone(std::string_view boneName) const {
  for (std::size_t i = 0; i < bones.size(); ++i) {
    if (bones[i] == boneName) return static_cast<int>(i);
  }
  return -1;
}

std::string skeletonDifference(const Clip& a, const Clip& b) {
  if (a.bones == b.bones && a.parents == b.parents) return "";
  const auto quoted = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
    return s;
  };
  const auto parentName = [](const Clip& c, std::size_t bone) {
    const int p = bone < c.parents.size() ? c.parents[bone] : -1;
    return p >= 0 && static_cast<std::size_t>(p) < c.bones.size()
               ? "'" + c.bones[static_cast<std::size_t>(p)] + "'"
               : std::string("none (the root)");
  };
  std::vector<std::string> lacks, extra, reparented;
  const std::unordered_map<std::string_view, std::size_t> inA = boneIndex(a), inB = boneIndex(b);
  for (const std::string& bone : b.bones) {
    if (!inA.contains(bone)) lacks.push_back(bone);
  }
  for (std::size_t i = 0; i < a.bones.size(); ++i) {
    const auto j = inB.find(a.bones[i]);
    if (j == inB.end()) {
      extra.push_back(a.bones[i]);
    } else if (const std::string pa = parentName(a, i), pb = parentName(b, j->second); pa != pb) {
      reparented.push_back("the parent of bone '" + a.bones[i] + "' is " + pa + " where '" + b.name +
                           "' has " + pb);
    }
  }
  std::string why = "clip '" + a.name + "' has other bones than '" + b.name + "':";
  if (!lacks.empty()) why += " it lacks " + quoted(lacks) + ";";
  if (!extra.empty()) why += " it has " + quoted(extra) + " that '" + b.name + "' has not;";
  for (const std::string& r : reparented) why += " " + r + ";";
  if (lacks.empty() && extra.empty() && reparented.empty()) why += " the same bones in another order;";
  why.pop_back();
  return why;
}

std::string clipProblem(const Clip& clip) {
  if (std::string problem = bonesProblem(clip); !problem.empty()) return problem;
  if (!(std::isfinite(clip.frameTime) && clip.frameTime >= kMinFrameTime))
    return "its frame time is not finite and >= 1e-6 s";
  if (clip.frames() == 0) return "it has no frames";
  if (clip.turns.size() != clip.frames() * clip.bones.size()) return "it has not one turn a bone a frame";
  for (std::size_t f = 0; f < clip.frames(); ++f) {
    if (!finite(clip.root[f])) return "frame " + std::to_string(f) + ": the root's position is not finite";
    if (glm::length(clip.root[f]) > kMaxClipReach)
      return "frame " + std::to_string(f) + ": the root is farther than 1e6 m from the origin";
    for (std::size_t b = 0; b < clip.bones.size(); ++b) {
      const Quat& q = clip.turns[f * clip.bones.size() + b];
      if (!finiteQuat(q) || std::abs(glm::length(q) - 1.0) > 1e-6)
        return "frame " + std::to_string(f) + ": bone '" + clip.bones[b] +
               "' has a turn that is not a unit quaternion";
    }
  }
  return "";
}

Quat slerpShort(const Quat& a, const Quat& b, Real w) {
  const Quat to = glm::dot(a, b) < 0.0 ? -b : b;
  return glm::normalize(glm::slerp(a, to, w));
}

void sampleClip(const Clip& clip, Real time, bool loop, ClipPose& out) {
  const std::size_t bones = clip.bones.size();
  out.turns.resize(bones);
  const Real duration = clip.duration();
  Vec3 carried(0.0);  // the root's displacement over the loops already done
  Real t = std::isfinite(time) ? std::clamp(time, 0.0, kMaxClipTime) : 0.0;
  if (loop && duration > 0.0) {
    const Real loops = std::floor(t / duration);
    t -= loops * duration;
    carried = loops * (clip.root.back() - clip.root.front());
  }
  // Clamped after the loops are taken off: at a time of 1e14 s and more, t - loops * duration can
  // round below zero, and a negative frame index is undefined behaviour.
  t = std::clamp(t, 0.0, duration);
  const Real at = t / clip.frameTime;
  const std::size_t f0 = std::min(static_cast<std::size_t>(at), clip.frames() - 1);
  const std::size_t f1 = std::min(f0 + 1, clip.frames() - 1);
  const Real w = std::clamp(at - static_cast<Real>(f0), 0.0, 1.0);
  out.root = carried + clip.root[f0] + w * (clip.root[f1] - clip.root[f0]);
  for (std::size_t b = 0; b < bones; ++b)
    out.turns[b] = slerpShort(clip.turns[f0 * bones + b], clip.turns[f1 * bones + b], w);
}

void blendPoses(const ClipPose& a, const ClipPose& b, Real w, ClipPose& out) {
  // A literal message: this runs every substep, where nothing may allocate.
  if (a.turns.size() != b.turns.size()) throw std::invalid_argument("blendPoses: the poses have other bones");
  out.turns.resize(a.turns.size());
  out.root = a.root + w * (b.root - a.root);
  for (std::size_t i = 0; i < a.turns.size(); ++i) out.turns[i] = slerpShort(a.turns[i], b.turns[i], w);
}

}  // namespace phys
