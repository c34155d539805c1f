// What assimp takes on trust in a BVH (format_checks.h): each refusal names the file and the line.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include "clips/clip_file.h"
#include "format_checks.h"
#include "physics/animation.h"

namespace clips::detail {
namespace {

// A body with hands and a face has a few hundred joints; a BVH of more is refused before assimp
// reads it (50,000 side by side took a minute to read).
constexpr std::uint64_t kMaxBvhJoints = 1000;
// Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation.
constexpr std::uint64_t kMaxBvhChannels = 6;

// The most keys (a joint at a frame) the largest clip file can hold: every joint's three turns at
// every frame, each number a digit and a space. assimp keys every joint at every frame a BVH says
// it has, a joint with no channels too, whatever the file holds: three such joints and "Frames:
// 50000000", 200 bytes, made it allocate 3.5 GB. Under 2^24, so the count is exact in the float
// assimp reads it into.
constexpr std::uint64_t kMaxClipKeys = kMaxClipBytes / 6;

// The largest turn a rotation channel may give, in degrees. assimp multiplies the float by pi
// before dividing by 180, so an angle past FLT_MAX / pi (1e38) became infinite and the turn NaN;
// a turn is a few times 360 degrees at most, and at 1e6 a float still resolves 0.06 degrees.
constexpr double kMostDegrees = 1e6;

// A BVH file's words as assimp's reader splits it (runs of anything but white space, a brace that
// starts one a word of its own), each with its line.
class BvhWords {
 public:
  explicit BvhWords(std::string_view text) : text_(text) {}

  /// The next word, "" at the end of the file.
  std::string_view next() {
    while (at_ < text_.size() && isSpace(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    const std::size_t start = at_;
    if (at_ < text_.size() && (text_[at_] == '{' || text_[at_] == '}')) {
      ++at_;
    } else {
      while (at_ < text_.size() && !isSpace(text_[at_])) ++at_;
    }
    return text_.substr(start, at_ - start);
  }
  /// The line of the word last read.
  std::size_t line() const { return line_; }

 private:
  static bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

  std::string_view text_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
};

// The count a BVH's count too large for 64 bits is taken as (detail::wholeNumber's): more than any
// file holds.
constexpr std::uint64_t kMostCount = std::numeric_limits<std::uint64_t>::max();

// The count `word` on `line`, after `what`.
std::uint64_t countIn(std::string_view word, std::size_t line, const std::string& name,
                      const std::string& what) {
  const std::optional<std::uint64_t> n = wholeNumber(word);
  if (!n) throw ClipError(name, line, what + " '" + std::string(word) + "' is not a whole number >= 0");
  return *n;
}

// `word` as a number that stays finite in the float assimp reads it into, nullopt if it is not
// one: not a number at all, nan or inf, or past a float's range (1e308 was read as inf). Read as
// assimp's fast_atoreal_move reads it: a leading '+' and a decimal comma ("0,5") are taken.
std::optional<double> floatNumber(std::string_view word) {
  if (word.starts_with('+')) word.remove_prefix(1);
  std::string text(word);
  std::replace(text.begin(), text.end(), ',', '.');
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
      std::abs(value) > static_cast<double>(std::numeric_limits<float>::max()))
    return std::nullopt;
  return value;
}

// One number a frame holds: which joint's, and what it moves.
struct BvhChannel {
  std::string_view joint;
  std::string_view name;  // Xposition ... Zrotation
  bool root = false;      // the first joint's: the clip keeps its positions
  bool position() const { return name.ends_with("position"); }
};

// A BVH's skeleton as far as the motion: its joints and the numbers each frame holds for them.
struct BvhSkeleton {
  std::uint64_t joints = 0;  // ROOT and JOINT: assimp keys each (an End Site is a node of no keys)
  std::uint64_t channels = 0;
  std::vector<BvhChannel> named;  // each channel in the order a frame holds them
  bool complete = false;          // MOTION was reached
};

// Refuses an OFFSET's three numbers unless each stays finite as a float.
void checkOffset(BvhWords& words, const std::string& name) {
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view word = words.next();
    if (word.empty()) return;  // assimp says the file ends
    if (!floatNumber(word))
      throw ClipError(name, words.line(), "OFFSET: '" + std::string(word) + "' is not a finite number");
  }
}

// Reads the skeleton, refusing joints nested deeper than kMaxDepth or more than kMaxBvhJoints
// before assimp's reader meets them; what it does not follow is left for that reader to refuse.
BvhSkeleton readBvhSkeleton(BvhWords& words, const std::string& name) {
  BvhSkeleton skeleton;
  int depth = 0;
  std::string_view joint;
  // Each joint's line by its name: a name used twice was refused only once assimp had read the file,
  // as a clip's two bones of one name, with no line.
  std::unordered_map<std::string_view, std::size_t> jointLines;
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    if (word == "ROOT" || word == "JOINT") {
      if (++skeleton.joints > kMaxBvhJoints)
        throw ClipError(name, words.line(),
                        "more than " + std::to_string(kMaxBvhJoints) + " joints (a skeleton has tens)");
      joint = words.next();  // its name, which may be any word
      if (const auto [first, added] = jointLines.emplace(joint, words.line()); !added)
        throw ClipError(name, words.line(),
                        "joint '" + std::string(joint) + "' is named as the one on line " +
                            std::to_string(first->second) + " (a clip's bones are found by name)");
    } else if (word == "{") {
      if (++depth > kMaxDepth)
        throw ClipError(
            name, words.line(),
            "joints nested more than " + std::to_string(kMaxDepth) + " deep (a skeleton's are tens deep)");
    } else if (word == "}") {
      --depth;
    } else if (word == "OFFSET") {
      checkOffset(words, name);
    } else if (word == "CHANNELS") {
      const std::string_view count = words.next();
      const std::uint64_t channels = countIn(count, words.line(), name, "CHANNELS");
      // Each is kept below: a count past the six a joint can have (assimp refuses any other name)
      // would have a file's words each kept, 2 GB of them for 64 MB of file.
      if (channels > kMaxBvhChannels)
        throw ClipError(name, words.line(),
                        "CHANNELS " + std::string(count) + ": a joint has at most " +
                            std::to_string(kMaxBvhChannels) + " (Xposition ... Zrotation)");
      for (std::uint64_t c = 0; c < channels; ++c) {
        const std::string_view channel = words.next();
        if (channel.empty()) return skeleton;  // the file ends in the channels' names
        skeleton.named.push_back({joint, channel, skeleton.joints == 1});
      }
      skeleton.channels += channels;
    } else if (word == "MOTION") {
      skeleton.complete = true;
      return skeleton;
    }
  }
  return skeleton;
}

// Refuses a Frame Time that is not a number of seconds a clip can play: assimp took -1 as -1 ticks a
// second and nan as nan.
void checkFrameTime(std::string_view word, std::size_t line, const std::string& name) {
  const std::optional<double> seconds = floatNumber(word);
  // As the float assimp keeps: 1e-6 is 9.99999997e-7 there, which the clip's own check refuses.
  if (!seconds || static_cast<double>(static_cast<float>(*seconds)) < phys::kMinFrameTime)
    throw ClipError(name, line,
                    "Frame Time: '" + std::string(word) + "' is not a finite number of seconds >= 1e-6");
}

// The numbers of the frames, each checked against the range the clip keeps as it is counted.
class BvhValues {
 public:
  BvhValues(const BvhSkeleton& skeleton, const std::string& name) : skeleton_(skeleton), name_(name) {}

  // The `index`th number of the motion (from 0), `word` on `line`.
  void check(std::uint64_t index, std::string_view word, std::size_t line) {
    const BvhChannel& channel = skeleton_.named[index % skeleton_.named.size()];
    const std::uint64_t frame = index / skeleton_.named.size();
    const std::optional<double> value = floatNumber(word);
    const double most = channel.position() ? phys::kMaxClipReach : kMostDegrees;
    if (!value || std::abs(*value) > most) {
      throw ClipError(name_, line,
                      "frame " + std::to_string(frame) + ", joint '" + std::string(channel.joint) + "' " +
                          std::string(channel.name) + ": '" + std::string(word) + "' is not " +
                          (channel.position() ? "a position within 1e6 of the origin"
                                              : "an angle within 1e6 degrees either way"));
    }
    if (channel.root && channel.position()) checkRootReach(*value, frame, line);
  }

 private:
  // The root's position is its position channels' values, together within kMaxClipReach.
  void checkRootReach(double value, std::uint64_t frame, std::size_t line) {
    if (frame != frame_) {
      frame_ = frame;
      squared_ = 0.0;
    }
    squared_ += value * value;
    if (squared_ > phys::kMaxClipReach * phys::kMaxClipReach)
      throw ClipError(name_, line,
                      "frame " + std::to_string(frame) + ": the root '" +
                          std::string(skeleton_.named[0].joint) + "' is farther than 1e6 from the origin");
  }

  const BvhSkeleton& skeleton_;
  const std::string& name_;
  std::uint64_t frame_ = 0;
  double squared_ = 0.0;
};

// Reads the motion's header and its numbers, refusing a frame count the file does not hold
// (assimp allocates every key before it finds the numbers missing) or that more numbers follow
// (assimp leaves them unread), more keys than kMaxClipKeys, and a number out of its range.
void checkBvhMotion(BvhWords& words, const BvhSkeleton& skeleton, const std::string& name) {
  if (skeleton.joints == 0 || words.next() != "Frames:") return;  // assimp names what is missing
  const std::string_view count = words.next();
  const std::size_t framesLine = words.line();
  const std::uint64_t frames = countIn(count, framesLine, name, "Frames:");
  const std::string said = "Frames: " + std::string(count);
  // assimp keys "Frames: 0" once, as a frame the file does not hold; refused after it with no line.
  if (frames == 0) throw ClipError(name, framesLine, said + ": a clip has at least one frame");
  // Every frame would be an empty line, keyed by assimp at the rest pose; and a clip whose root
  // has no position channels has one position, which is one frame.
  if (skeleton.channels == 0 && frames > 1)
    throw ClipError(name, framesLine,
                    said + ", but no joint has a channel: a file of no motion holds one frame");
  if (words.next() != "Frame" || words.next() != "Time:") return;
  const std::string_view frameTime = words.next();
  if (frameTime.empty()) return;
  checkFrameTime(frameTime, words.line(), name);
  // A product past 64 bits is also more than any file holds.
  const std::uint64_t wanted = frames > kMostCount / std::max<std::uint64_t>(skeleton.channels, 1)
                                   ? kMostCount
                                   : frames * skeleton.channels;
  BvhValues values(skeleton, name);
  std::uint64_t held = 0;
  std::size_t lastLine = words.line();  // the Frame Time's, while no number is read
  for (std::string_view word = words.next(); !word.empty(); word = words.next()) {
    if (++held > wanted)
      throw ClipError(name, words.line(),
                      "motion past its last frame (" + said + " on line " + std::to_string(framesLine) +
                          ", " + std::to_string(skeleton.channels) + " numbers a frame)");
    values.check(held - 1, word, words.line());
    lastLine = words.line();
  }
  if (held < wanted)
    throw ClipError(name, framesLine,
                    said + " of " + std::to_string(skeleton.channels) +
                        " numbers each is more than the file holds: its motion ends on line " +
                        std::to_string(lastLine) + " after " + std::to_string(held) + " numbers");
  if (frames > kMaxClipKeys / skeleton.joints)
    throw ClipError(name, framesLine,
                    said + " of " + std::to_string(skeleton.joints) +
                        " joints is more keys than a clip file holds (" + std::to_string(kMaxClipKeys) + ")");
}

}  // namespace

bool isBvh(std::string_view content, const std::string& format) {
  return format == "bvh" || BvhWords(content).next() == "HIERARCHY";
}

void checkBvh(std::string_view content, const std::string& name) {
  BvhWords words(content);
  const BvhSkeleton skeleton = readBvhSkeleton(words, name);
  if (skeleton.complete) checkBvhMotion(words, skeleton, name);
}

}  // namespace clips::detail
