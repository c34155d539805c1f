// libFuzzer target: the bytes are a recording file (app/sandbox/recording_file.h; docs/architecture.md,
// "Fuzzing"). The reader must refuse what it cannot read with RecordingFormatError (or the clip
// source's refusal of a clip it has not got), read nothing past the end and allocate nothing a
// count in the file asks for beyond what the file holds; and what it reads must be what it promises
// (steps in order, each motion sound and matching its hash) and write back as the same recording.
// Anything else prints what and aborts, which libFuzzer records as a crash with its input.
//
// Each input is read twice: as it is, and with its checksum made to match (the last 8 bytes set to
// the FNV-1a of the rest). Nearly every mutation breaks the checksum, and the reader then walks only
// the parts' headers; the second read takes the mutation on into the parts and their steps.
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "physics/fnv1a.h"
#include "project_clips.h"
#include "recording_file.h"

namespace {

[[noreturn]] void fail(const char* stage, const std::string& why) {
  std::fprintf(stderr, "\n==== recording fuzz failed, the input %s ====\n%s\n", stage, why.c_str());
  std::fflush(stderr);
  std::abort();
}

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// What the reader promises of every recording it hands over; "" when it holds.
std::string broken(const sandbox::SavedRecording& r) {
  if (r.stepCount() == 0) return "a recording of no steps was read";
  long expected = r.firstStep();
  for (const sandbox::SavedPart& part : r.parts) {
    if (part.steps.empty()) return "a part of no steps was handed over";
    for (const sandbox::SavedStep& s : part.steps) {
      const std::string at = "step " + std::to_string(s.record.step) + ": ";
      if (s.record.step != expected) return at + "where step " + std::to_string(expected) + " should be";
      ++expected;
      if (const std::string problem = s.motion.problem(); !problem.empty()) return at + problem;
      if (s.motion.hash() != s.record.hash) return at + "its motion does not match its hash";
    }
  }
  return {};
}

// "" when `b` is the recording `a` is.
std::string difference(const sandbox::SavedRecording& a, const sandbox::SavedRecording& b) {
  if (a.sceneName != b.sceneName) return "the scene's name";
  if (a.parts.size() != b.parts.size()) return "the number of parts";
  for (std::size_t p = 0; p < a.parts.size(); ++p) {
    const sandbox::SavedPart &x = a.parts[p], &y = b.parts[p];
    const std::string at = "part " + std::to_string(p + 1) + ": ";
    if (x.sceneXml != y.sceneXml) return at + "its scene";
    if (x.structure != y.structure) return at + "its structure key";
    if (x.steps.size() != y.steps.size()) return at + "its number of steps";
    for (std::size_t k = 0; k < x.steps.size(); ++k) {
      const sandbox::SavedStep &s = x.steps[k], &t = y.steps[k];
      if (s.record.step != t.record.step || s.record.hash != t.record.hash ||
          s.record.dragTarget != t.record.dragTarget || s.motion.hash() != t.motion.hash() ||
          !sameBits(s.motion.time, t.motion.time))
        return at + "step " + std::to_string(s.record.step);
    }
  }
  return {};
}

void check(std::string_view bytes, const char* stage) {
  std::optional<sandbox::SavedRecording> read;
  try {
    read.emplace(sandbox::decodeRecording(bytes, fuzz::projectClipSource()));
  } catch (const sandbox::RecordingFormatError&) {
    return;  // refused, saying what and where: what the reader is for
  } catch (const fuzz::NoSuchClip&) {
    return;  // a clip the source has not got: the sandbox refuses such a file the same way
  } catch (const std::exception& e) {
    fail(stage, std::string("the reader threw something other than RecordingFormatError: ") + e.what());
  }
  if (const std::string why = broken(*read); !why.empty()) fail(stage, "read, but " + why);
  std::optional<sandbox::SavedRecording> back;
  try {
    back.emplace(sandbox::decodeRecording(sandbox::encodeRecording(*read), fuzz::projectClipSource()));
  } catch (const std::exception& e) {
    fail(stage, std::string("read, but it does not write back and read again: ") + e.what());
  }
  if (const std::string why = difference(*read, *back); !why.empty())
    fail(stage, "read, written back and read again, it differs in " + why);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  check(input, "as given");
  constexpr std::size_t kChecksum = 8;
  if (size > kChecksum) {
    std::string fixed(input);
    phys::Fnv1a checksum;
    checksum.bytes(fixed.data(), fixed.size() - kChecksum);
    const std::uint64_t hash = checksum.hash();
    std::memcpy(fixed.data() + fixed.size() - kChecksum, &hash, kChecksum);
    if (fixed != input) check(fixed, "with its checksum made to match");
  }
  return 0;
}
