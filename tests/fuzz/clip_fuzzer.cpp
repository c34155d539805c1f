// libFuzzer target: the bytes are a clip file (app/clips; docs/architecture.md, "Fuzzing"): a first
// byte of 1 to 5 says the rest is FBX, glTF, binary glTF, COLLADA or .x, and any other first byte
// that the whole is a BVH (so BVH files are seeds as they are). The clip reader (its own checks of
// what assimp would take on trust, then assimp's reader, then its own of the animation assimp
// gives) must refuse what is no clip with ClipError, and a clip it
// returns must play: sampled before its start, within it, at its end, looped many times over and at
// the largest time a clock holds, every pose is finite with turns of unit length. Anything else (a
// crash, a sanitizer report, another exception, a pose that is not sound) prints what and aborts,
// which libFuzzer records as a crash with its input.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>

#include "clips/clip_file.h"
#include "physics/animation.h"

namespace {

[[noreturn]] void fail(const std::string& why) {
  std::fprintf(stderr, "\n==== clip fuzz failed ====\n%s\n", why.c_str());
  std::fflush(stderr);
  std::abort();
}

bool finite(const phys::Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Within the tolerance clipProblem allows a key, and what slerp and blending add to it.
bool unit(const phys::Quat& q) {
  const double length = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return std::abs(length - 1.0) < 1e-5;
}

void checkPlays(const phys::Clip& clip) {
  const double end = clip.duration();
  phys::ClipPose pose;
  for (const double time : {-1.0, 0.0, 0.37 * end, end, 2.5 * end + 0.01, phys::kMaxClipTime}) {
    for (const bool loop : {false, true}) {
      phys::sampleClip(clip, time, loop, pose);
      if (pose.turns.size() != clip.bones.size())
        fail("sampled at " + std::to_string(time) + " s: " + std::to_string(pose.turns.size()) +
             " turns for " + std::to_string(clip.bones.size()) + " bones");
      if (!finite(pose.root))
        fail("sampled at " + std::to_string(time) + " s" + (loop ? ", looped" : "") +
             ": the root is not finite");
      for (std::size_t b = 0; b < pose.turns.size(); ++b) {
        if (!unit(pose.turns[b]))
          fail("sampled at " + std::to_string(time) + " s" + (loop ? ", looped" : "") + ": bone '" +
               clip.bones[b] + "' turns by a quaternion not of unit length");
      }
    }
  }
}

// The formats a first byte of 1 to 5 picks.
constexpr const char* kOtherFormats[] = {"fbx", "gltf", "glb", "dae", "x"};
constexpr std::size_t kOtherFormatCount = std::size(kOtherFormats);

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view input(reinterpret_cast<const char*>(data), size);
  std::string format = "bvh";
  if (size > 0 && data[0] >= 1 && data[0] <= kOtherFormatCount) {
    format = kOtherFormats[data[0] - 1];
    input.remove_prefix(1);
  }
  std::optional<phys::Clip> clip;
  try {
    clip.emplace(clips::parseClip(input, "input." + format, format));
  } catch (const clips::ClipError&) {
    return 0;  // refused with file, line and reason: what the reader is for
  } catch (const std::exception& e) {
    fail(std::string("the reader threw something other than ClipError: ") + e.what());
  }
  if (const std::string problem = phys::clipProblem(*clip); !problem.empty())
    fail("a clip was returned that cannot be played: " + problem);
  checkPlays(*clip);
  return 0;
}
