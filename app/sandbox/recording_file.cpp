#include "recording_file.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <type_traits>

#include "physics/fnv1a.h"

namespace sandbox {
namespace {

static_assert(std::endian::native == std::endian::little,
              "recording files are little-endian, as this machine");

constexpr std::string_view kMagic = "JKRECORD";

// The file's checksum and the structure key.
using Fnv = phys::Fnv1a;

class Writer {
 public:
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof(v));
  }
  void text(std::string_view s) {
    value(static_cast<std::uint64_t>(s.size()));
    out_.append(s);
  }
  void vec(const phys::Vec3& v) {
    value(v.x);
    value(v.y);
    value(v.z);
  }
  void quat(const phys::Quat& q) {
    value(q.w);
    value(q.x);
    value(q.y);
    value(q.z);
  }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

// Reads the file from the front; every failure names where it happened.
class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  template <typename T>
  T value() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::string text(const char* what) {
    const auto size = value<std::uint64_t>();
    if (size > bytes_.size() - at_) {
      fail(std::string(what) + " of " + std::to_string(size) +
           " bytes runs past the end of the file: it is truncated");
    }
    std::string s(bytes_.substr(at_, size));
    at_ += size;
    return s;
  }
  phys::Vec3 vec() {
    const double x = value<double>(), y = value<double>(), z = value<double>();
    return {x, y, z};
  }
  phys::Quat quat() {
    const double w = value<double>(), x = value<double>(), y = value<double>(), z = value<double>();
    return {w, x, y, z};
  }
  bool flag(const char* what) {
    const auto f = value<std::uint8_t>();
    if (f > 1) fail(std::string(what) + " is " + std::to_string(f) + ", not 0 or 1: the file is damaged");
    return f == 1;
  }
  void skip(std::size_t n) {
    need(n);
    at_ += n;
  }
  std::size_t offset() const { return at_; }
  std::size_t left() const { return bytes_.size() - at_; }
  /// Where the reader is, for messages: "part 2, step 140".
  void setPlace(std::string place) { place_ = std::move(place); }

  [[noreturn]] void fail(const std::string& why) const {
    throw RecordingFormatError("byte " + std::to_string(at_) + (place_.empty() ? "" : " (" + place_ + ")") +
                               ": " + why);
  }

 private:
  void need(std::size_t n) const {
    if (n > bytes_.size() - at_) {
      fail("the file ends after " + std::to_string(bytes_.size()) + " bytes: it is truncated");
    }
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
  std::string place_;
};

// A part's clips: the names its characters' playbacks refer to by index, in the order they first
// appear.
constexpr std::uint32_t kNoClip = std::numeric_limits<std::uint32_t>::max();

std::uint32_t clipIndex(std::vector<std::string>& names, const phys::Playback& p) {
  if (p.clip == nullptr) return kNoClip;
  const auto it = std::find(names.begin(), names.end(), p.clip->name);
  if (it != names.end()) return static_cast<std::uint32_t>(it - names.begin());
  names.push_back(p.clip->name);
  return static_cast<std::uint32_t>(names.size() - 1);
}

std::vector<std::string> clipNames(const SavedPart& part) {
  std::vector<std::string> names;
  for (const SavedStep& s : part.steps) {
    for (const phys::CharacterMotion& c : s.motion.characters)
      phys::forEachPlayback(c, [&names](const phys::Playback& p) { clipIndex(names, p); });
  }
  return names;
}

// Bytes of one character's motion with `bones` bones (docs/sandbox.md, "Recording files"): four
// playbacks of 21, 13 numbers (104), the reaction's 6 (48), the state (1), the root's velocity (24),
// the queued flag and 2 numbers (17), the frame (32), origin and shift (48), the two poses' roots (48)
// the holding and support flags (2), and the turn-in's time, what is left of it and its due flag (17):
// 425; and per bone its strength and two turns, 72.
std::size_t characterBytes(std::size_t bones) {
  constexpr std::size_t kFixed = 425, kPerBone = 72;
  return kFixed + bones * kPerBone;
}

// Bytes one step takes in a part of `particles` particles, `rigid` rigid bodies and characters of
// `bones` bones each.
std::size_t stepBytes(std::size_t particles, std::size_t rigid, std::span<const std::size_t> bones) {
  std::size_t n = 8 + 8 + 8 + 1 + 3 * 8 + particles * 6 * 8 + rigid * 13 * 8;
  for (const std::size_t b : bones) n += characterBytes(b);
  return n;
}

void writePlayback(Writer& w, std::vector<std::string>& names, const phys::Playback& p) {
  w.value(clipIndex(names, p));
  w.value(p.time);
  w.value(p.speed);
  w.value(static_cast<std::uint8_t>(p.loop ? 1 : 0));
}

void writePose(Writer& w, const phys::ClipPose& pose) {
  w.vec(pose.root);
  for (const phys::Quat& q : pose.turns) w.quat(q);
}

void writeCharacter(Writer& w, std::vector<std::string>& names, const phys::CharacterMotion& c) {
  writePlayback(w, names, c.now);
  writePlayback(w, names, c.before);
  writePlayback(w, names, c.reaction.getUp);
  writePlayback(w, names, c.queued ? c.queued->playback : phys::Playback{});
  for (const double v :
       {c.blend, c.blendTime, c.strength, c.rootStrength, c.balance, c.goalStrength, c.goalRootStrength,
        c.goalBalance, c.stateTime, c.fromStrength, c.fromBalance, c.lastImpact, c.stillTime})
    w.value(v);
  for (const double share : c.partStrength) w.value(share);
  const phys::Reaction& r = c.reaction;
  for (const double v : {r.threshold, r.fallTime, r.restSpeed, r.restTime, r.getUpTime, r.armTime})
    w.value(v);
  w.value(static_cast<std::uint8_t>(c.state));
  w.vec(c.lastRootVelocity);
  w.value(static_cast<std::uint8_t>(c.queued ? 1 : 0));
  w.value(c.queued ? c.queued->at : 0.0);
  w.value(c.queued ? c.queued->blendTime : 0.0);
  w.quat(c.frame);
  w.vec(c.origin);
  w.vec(c.beforeShift);
  writePose(w, c.pose);
  writePose(w, c.held);
  w.value(static_cast<std::uint8_t>(c.holding ? 1 : 0));
  w.value(static_cast<std::uint8_t>(c.supported ? 1 : 0));
  w.value(c.turnInTime);
  w.value(c.turnIn);
  w.value(static_cast<std::uint8_t>(c.turnInDue ? 1 : 0));
}

void writeStep(Writer& w, std::vector<std::string>& names, const SavedStep& s) {
  w.value(static_cast<std::int64_t>(s.record.step));
  w.value(s.motion.time);
  w.value(s.record.hash);
  w.value(static_cast<std::uint8_t>(s.record.dragTarget ? 1 : 0));
  w.vec(s.record.dragTarget.value_or(phys::Vec3(0.0)));
  for (const phys::Vec3& p : s.motion.position) w.vec(p);
  for (const phys::Vec3& p : s.motion.previous) w.vec(p);
  for (std::size_t r = 0; r < s.motion.rigidPosition.size(); ++r) {
    w.vec(s.motion.rigidPosition[r]);
    w.quat(s.motion.rigidOrientation[r]);
    w.vec(s.motion.rigidVelocity[r]);
    w.vec(s.motion.rigidAngularVelocity[r]);
  }
  for (const phys::CharacterMotion& c : s.motion.characters) writeCharacter(w, names, c);
}

// A part's clips as the source gave them; none where the file is not to be trusted yet.
using Clips = std::vector<std::shared_ptr<const phys::Clip>>;

phys::Playback readPlayback(Reader& r, const Clips& clips) {
  phys::Playback p;
  const auto clip = r.value<std::uint32_t>();
  if (clip != kNoClip && clip >= clips.size()) {
    r.fail("clip " + std::to_string(clip) + " of a part that names " + std::to_string(clips.size()) +
           ": the file is damaged");
  }
  if (clip != kNoClip) p.clip = clips[clip];
  p.time = r.value<double>();
  p.speed = r.value<double>();
  p.loop = r.flag("a clip's loop flag");
  return p;
}

void readPose(Reader& r, std::size_t bones, phys::ClipPose& pose) {
  pose.root = r.vec();
  pose.turns.resize(bones);
  for (phys::Quat& q : pose.turns) q = r.quat();
}

phys::CharacterMotion readCharacter(Reader& r, const Clips& clips, std::size_t bones) {
  phys::CharacterMotion c;
  c.now = readPlayback(r, clips);
  c.before = readPlayback(r, clips);
  c.reaction.getUp = readPlayback(r, clips);
  const phys::Playback queued = readPlayback(r, clips);
  for (double* v : {&c.blend, &c.blendTime, &c.strength, &c.rootStrength, &c.balance, &c.goalStrength,
                    &c.goalRootStrength, &c.goalBalance, &c.stateTime, &c.fromStrength, &c.fromBalance,
                    &c.lastImpact, &c.stillTime})
    *v = r.value<double>();
  c.partStrength.resize(bones);
  for (double& share : c.partStrength) share = r.value<double>();
  phys::Reaction& reaction = c.reaction;
  for (double* v : {&reaction.threshold, &reaction.fallTime, &reaction.restSpeed, &reaction.restTime,
                    &reaction.getUpTime, &reaction.armTime})
    *v = r.value<double>();
  const auto state = r.value<std::uint8_t>();
  if (state > static_cast<std::uint8_t>(phys::CharacterState::LettingGo))
    r.fail("a character's state " + std::to_string(state) + ": the file is damaged");
  c.state = static_cast<phys::CharacterState>(state);
  c.lastRootVelocity = r.vec();
  const bool hasQueued = r.flag("the queued clip's flag");
  const double at = r.value<double>(), blendTime = r.value<double>();
  if (hasQueued) c.queued = phys::QueuedClip{queued, at, blendTime};
  c.frame = r.quat();
  c.origin = r.vec();
  c.beforeShift = r.vec();
  readPose(r, bones, c.pose);
  readPose(r, bones, c.held);
  c.holding = r.flag("the holding flag");
  c.supported = r.flag("the support flag");
  c.turnInTime = r.value<double>();
  c.turnIn = r.value<double>();
  c.turnInDue = r.flag("the turn-in's due flag");
  return c;
}

bool finite(const phys::Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

SavedStep readStep(Reader& r, std::size_t particles, std::size_t rigid, const Clips& clips,
                   std::span<const std::size_t> bones) {
  SavedStep s;
  const auto step = r.value<std::int64_t>();
  if (step < 0 || step >= std::numeric_limits<long>::max()) {
    r.fail("step number " + std::to_string(step) + " is out of range: the file is damaged");
  }
  s.record.step = static_cast<long>(step);
  s.motion.steps = s.record.step;
  s.motion.time = r.value<double>();
  s.record.hash = r.value<std::uint64_t>();
  const bool hasDrag = r.flag("the drag flag");
  const phys::Vec3 drag = r.vec();
  if (hasDrag) s.record.dragTarget = drag;
  s.motion.position.resize(particles);
  s.motion.previous.resize(particles);
  for (phys::Vec3& p : s.motion.position) p = r.vec();
  for (phys::Vec3& p : s.motion.previous) p = r.vec();
  s.motion.rigidPosition.resize(rigid);
  s.motion.rigidOrientation.resize(rigid);
  s.motion.rigidVelocity.resize(rigid);
  s.motion.rigidAngularVelocity.resize(rigid);
  for (std::size_t k = 0; k < rigid; ++k) {
    s.motion.rigidPosition[k] = r.vec();
    s.motion.rigidOrientation[k] = r.quat();
    s.motion.rigidVelocity[k] = r.vec();
    s.motion.rigidAngularVelocity[k] = r.vec();
  }
  s.motion.characters.reserve(bones.size());
  for (const std::size_t b : bones) s.motion.characters.push_back(readCharacter(r, clips, b));
  return s;
}

// The checks the checksum cannot make: the steps follow each other, every number is finite, and
// each motion is the state its step recorded.
void checkStep(const Reader& r, const SavedStep& s, long expected) {
  if (expected >= 0 && s.record.step != expected) {
    r.fail("step " + std::to_string(s.record.step) + " where step " + std::to_string(expected) +
           " should follow: the file is damaged");
  }
  if (s.record.dragTarget && !finite(*s.record.dragTarget))
    r.fail("a non-finite drag target: the file is damaged");
  if (const std::string problem = s.motion.problem(); !problem.empty())
    r.fail(problem + ": the file is damaged");
  if (s.motion.hash() != s.record.hash) {
    r.fail("the state does not match the step's hash: the file is damaged");
  }
}

}  // namespace

long SavedRecording::firstStep() const {
  return parts.empty() || parts.front().steps.empty() ? 0 : parts.front().steps.front().record.step;
}

long SavedRecording::lastStep() const {
  return parts.empty() || parts.back().steps.empty() ? 0 : parts.back().steps.back().record.step;
}

std::size_t SavedRecording::stepCount() const {
  std::size_t n = 0;
  for (const SavedPart& p : parts) n += p.steps.size();
  return n;
}

std::uint64_t structureKey(const phys::World& world) {
  Fnv f;
  f.value(static_cast<std::uint64_t>(world.particles().size()));
  for (const phys::BodyId b : world.particleBodies()) f.value(static_cast<std::uint32_t>(b));
  f.value(static_cast<std::uint64_t>(world.bodies().size()));
  for (const phys::Body& b : world.bodies()) {
    f.value(b.model);
    f.value(b.shape);
    f.value(static_cast<std::uint32_t>(b.firstParticle));
    f.value(b.particleCount);
    f.value(b.stickCount);
    f.value(static_cast<std::uint32_t>(b.rigid));
  }
  f.value(static_cast<std::uint64_t>(world.rigidBodies().size()));
  f.value(static_cast<std::uint64_t>(world.sticks().size()));
  for (const phys::Stick& s : world.sticks()) {
    f.value(static_cast<std::uint32_t>(s.a));
    f.value(static_cast<std::uint32_t>(s.b));
  }
  f.value(static_cast<std::uint64_t>(world.links().size()));
  f.value(static_cast<std::uint64_t>(world.rigidLinks().size()));
  f.value(static_cast<std::uint64_t>(world.rigidJoints().size()));
  for (const phys::RigidJoint& j : world.rigidJoints()) {
    f.value(j.kind);
    f.value(static_cast<std::uint32_t>(j.a));
    f.value(static_cast<std::uint32_t>(j.b));
  }
  f.value(static_cast<std::uint64_t>(world.jointFrictions().size()));
  f.value(static_cast<std::uint64_t>(world.particleJoints().size()));
  for (const phys::ParticleJoint& j : world.particleJoints()) {
    f.value(static_cast<std::uint32_t>(j.a));
    f.value(static_cast<std::uint32_t>(j.b));
  }
  f.value(static_cast<std::uint64_t>(world.characters().size()));
  for (const phys::Character& c : world.characters()) {
    f.value(static_cast<std::uint64_t>(c.bones.size()));
    for (const phys::CharacterBone& bone : c.bones) {
      f.value(static_cast<std::uint32_t>(bone.body));
      f.value(bone.clipBone);
      f.value(bone.parent);
    }
  }
  return f.hash();
}

// Layout (docs/sandbox.md, "Recording files"): the magic, the format, the scene's name, the parts
// (each: its scene text, structure key, counts, its clips' names, its characters' bone counts, then
// its steps), and the checksum of all before it.
std::string encodeRecording(const SavedRecording& recording) {
  Writer w;
  w.out().append(kMagic);
  w.value(kRecordingFormat);
  w.text(recording.sceneName);
  w.value(static_cast<std::uint32_t>(recording.parts.size()));
  for (const SavedPart& part : recording.parts) {
    const phys::Motion* first = part.steps.empty() ? nullptr : &part.steps.front().motion;
    w.text(part.sceneXml);
    w.value(part.structure);
    w.value(static_cast<std::uint64_t>(first != nullptr ? first->position.size() : 0));
    w.value(static_cast<std::uint64_t>(first != nullptr ? first->rigidPosition.size() : 0));
    w.value(static_cast<std::uint64_t>(part.steps.size()));
    std::vector<std::string> names = clipNames(part);
    w.value(static_cast<std::uint32_t>(names.size()));
    for (const std::string& name : names) w.text(name);
    const std::size_t characters = first != nullptr ? first->characters.size() : 0;
    w.value(static_cast<std::uint32_t>(characters));
    for (std::size_t c = 0; c < characters; ++c)
      w.value(static_cast<std::uint32_t>(first->characters[c].partStrength.size()));
    for (const SavedStep& s : part.steps) {
      if (const std::string problem = s.motion.problem(); !problem.empty()) {
        throw RecordingFormatError("step " + std::to_string(s.record.step) + ": " + problem +
                                   ": a recording holding it could not be opened");
      }
      writeStep(w, names, s);
    }
  }
  Fnv checksum;
  checksum.bytes(w.out().data(), w.out().size());
  w.value(checksum.hash());
  return std::move(w.out());
}

namespace {

// The magic and the format, checked.
void readHeader(Reader& r, std::string_view bytes) {
  if (bytes.size() < kMagic.size() || bytes.substr(0, kMagic.size()) != kMagic) {
    r.fail("not a recording: it does not start with \"" + std::string(kMagic) + "\"");
  }
  r.value<std::array<char, kMagic.size()>>();
  const auto format = r.value<std::uint32_t>();
  if (format != kRecordingFormat) {
    r.fail("a recording of format " + std::to_string(format) +
           ", from another version of the sandbox; this one reads format " +
           std::to_string(kRecordingFormat));
  }
}

}  // namespace

void readRecording(std::string_view bytes, const RecordingVisitor& visit) {
  Reader r(bytes);
  readHeader(r, bytes);
  // The checksum first, so that damage anywhere is called damage, not whatever it looks like.
  if (bytes.size() < kMagic.size() + 4 + 8)
    r.fail("the file ends after " + std::to_string(bytes.size()) + " bytes: it is truncated");
  Fnv checksum;
  checksum.bytes(bytes.data(), bytes.size() - 8);
  std::uint64_t stored = 0;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  const bool checksumOk = checksum.hash() == stored;

  const std::string sceneName = r.text("the scene's name");
  if (checksumOk && visit.scene) visit.scene(sceneName);
  const auto parts = r.value<std::uint32_t>();
  long expected = -1;
  std::size_t stepsRead = 0;
  for (std::uint32_t p = 0; p < parts; ++p) {
    r.setPlace("part " + std::to_string(p + 1) + " of " + std::to_string(parts));
    SavedPart part;
    part.sceneXml = r.text("the part's scene");
    part.structure = r.value<std::uint64_t>();
    const auto particles = r.value<std::uint64_t>();
    const auto rigid = r.value<std::uint64_t>();
    const auto steps = r.value<std::uint64_t>();
    const auto clipCount = r.value<std::uint32_t>();
    if (clipCount > r.left() / 8) r.fail(std::to_string(clipCount) + " clips: the file is truncated");
    std::vector<std::string> names(clipCount);
    for (std::string& name : names) name = r.text("a clip's name");
    const auto characters = r.value<std::uint32_t>();
    if (characters > r.left() / 4) r.fail(std::to_string(characters) + " characters: the file is truncated");
    std::vector<std::size_t> bones(characters);
    std::size_t characterStep = 0;  // each step's bytes of characters, at most what is left
    for (std::size_t& b : bones) {
      b = r.value<std::uint32_t>();
      if (b <= r.left() / 72) characterStep += characterBytes(b);
      if (b > r.left() / 72 || characterStep > r.left())
        r.fail("a character of " + std::to_string(b) + " bones: the file is truncated");
    }
    // Sizes from a damaged file must not allocate what the file cannot hold. Each count is below the
    // file's size, so no sum here can overflow.
    const std::size_t room = r.left() - std::min<std::size_t>(r.left(), 8);  // before the checksum
    const std::size_t each = stepBytes(std::min<std::uint64_t>(particles, bytes.size()),
                                       std::min<std::uint64_t>(rigid, bytes.size()), bones);
    if (particles > bytes.size() || rigid > bytes.size() || steps > room / each) {
      r.fail(std::to_string(steps) + " steps of " + std::to_string(particles) + " particles, " +
             std::to_string(rigid) + " rigid bodies and " + std::to_string(characters) +
             " characters need more than the " + std::to_string(room) + " bytes left: the file is truncated");
    }
    if (!checksumOk) {  // nothing of a damaged file is decoded: a step's size is known without it
      r.skip(steps * each);
      continue;
    }
    // The clips only from a file whose checksum holds: a damaged name must not be looked for.
    Clips clips(names.size());
    if (steps > 0) {
      if (!names.empty() && !visit.clips) r.fail("the recording names clips and no clip source was given");
      for (std::size_t c = 0; c < names.size(); ++c) {
        clips[c] = visit.clips(names[c]);
        if (clips[c] == nullptr) r.fail("the clip source gave no clip for '" + names[c] + "'");
      }
    }
    for (std::uint64_t s = 0; s < steps; ++s) {
      r.setPlace("part " + std::to_string(p + 1) + " of " + std::to_string(parts) + ", its step " +
                 std::to_string(s + 1) + " of " + std::to_string(steps));
      SavedStep step = readStep(r, particles, rigid, clips, bones);
      checkStep(r, step, expected);
      expected = step.record.step + 1;
      ++stepsRead;
      if (visit.step) visit.step(p, part, std::move(step));
    }
  }
  r.setPlace("");
  if (r.left() < 8) r.fail("the checksum is missing: the file is truncated");
  if (!checksumOk) {
    r.fail("the checksum does not match the content: the file is damaged");
  }
  if (r.left() > 8)
    r.fail(std::to_string(r.left() - 8) +
           " bytes before the checksum that belong to nothing: the file is damaged");
  if (stepsRead == 0) r.fail("a recording of no steps");
}

SavedRecording decodeRecording(std::string_view bytes, const ClipSource& clips) {
  SavedRecording out;
  std::size_t lastPart = 0;
  readRecording(bytes, {[&out](const std::string& name) { out.sceneName = name; }, clips,
                        [&](std::size_t index, const SavedPart& part, SavedStep step) {
                          if (out.parts.empty() || index != lastPart)
                            out.parts.push_back({part.sceneXml, part.structure, {}});
                          lastPart = index;
                          out.parts.back().steps.push_back(std::move(step));
                        }});
  return out;
}

}  // namespace sandbox
