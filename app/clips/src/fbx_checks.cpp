// What assimp takes on trust in a binary FBX, and FBX curves out of time order in either form
// (format_checks.h).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <zlib.h>

#include "clips/clip_file.h"
#include "format_checks.h"

namespace clips::detail {
namespace {

// Deflate makes at most 1032 bytes of 1 (RFC 1951's longest match, 258 bytes, in two bits): an
// array that claims more than that of its compressed bytes is not in the file.
constexpr std::uint64_t kMostInflation = 1032;

// assimp computes an array's size in bytes in 32 bits, and reads its count of values out of a
// buffer of the size wrapped: 0x20000001 values of 8 bytes stored in 8 read 4 GB past the end. A
// clip file is at most 64 MB, and no array in one needs 1 GB.
constexpr std::uint64_t kMostArrayBytes = std::uint64_t{1} << 30;

// assimp inflates each array it reads (a curve's keys, a mesh's vertices) and keeps them until the
// file is read: 64 arrays of 1 MB each claiming 1 GB would take 64 GB. Together they may come to four times
// the largest clip file, 256 MB, which is more keys than any clip has.
constexpr std::uint64_t kMostArraysBytes = std::uint64_t{256} << 20;

// Node records nest this deep under one another: the header (23 bytes of magic, a version), then
// records of an end offset, a count of properties, the properties' length in bytes (each 4 bytes
// before version 7500, 8 after), a name of a byte's length, the properties, and the children closed
// by a record of zeros.
constexpr std::size_t kFirstRecord = 27;

std::size_t strideOf(char type) {
  switch (type) {
    case 'f':
    case 'i':
      return 4;
    case 'd':
    case 'l':
      return 8;
    case 'c':
      return 1;
    default:
      return 0;
  }
}

// A node record: its name and where its parts lie in the file.
struct Record {
  std::string name;
  std::uint64_t at, end, properties, listEnd;
  std::uint64_t count;
};

// A property's value as far as the curve check needs it: an integer, a string, an array of int64.
struct Property {
  char type = 0;
  std::int64_t integer = 0;
  std::string text;
  std::optional<std::vector<std::int64_t>> int64s;  // nullopt if not one or it cannot be read
};

class BinaryFbx {
 public:
  BinaryFbx(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  void check() {
    const std::uint32_t version = static_cast<std::uint32_t>(readLittle(bytes_, 23, 4));
    word_ = version >= 7500 ? 8 : 4;
    const std::size_t sentinel = 3 * word_ + 1;
    std::vector<Record> open;  // the records whose children are being read
    std::uint64_t at = kFirstRecord;
    for (;;) {
      const std::uint64_t limit = open.empty() ? bytes_.size() : open.back().end - sentinel;
      if (!open.empty() && at == limit) {  // the children end: the record of zeros, then the parent's end
        at = open.back().end;
        open.pop_back();
        continue;
      }
      if (limit - at < word_) return;  // no more records; what is left is assimp's to judge
      const std::uint64_t end = readLittle(bytes_, at, word_);
      if (end == 0 && open.empty()) break;  // the footer
      Record r = readHeader(at, limit);
      if (r.listEnd < r.end) {
        if (r.end - r.listEnd < sentinel)
          fail(r, "its children end " + std::to_string(r.end - r.listEnd) +
                      " bytes before its end, where the " + std::to_string(sentinel) +
                      " bytes of a closing record of zeros go");
        if (open.size() >= static_cast<std::size_t>(kMaxDepth))
          fail(r, "node records nested more than " + std::to_string(kMaxDepth) +
                      " deep (a skeleton's are tens deep)");
      }
      readProperties(r, open);
      if (r.listEnd < r.end) {
        at = r.listEnd;
        open.push_back(std::move(r));
      } else {
        at = r.end;
      }
    }
  }

  const FbxCurves& curves() const { return curves_; }

 private:
  [[noreturn]] void fail(const Record& r, const std::string& why) const {
    throw ClipError(name_, "node record '" + r.name + "' at byte " + std::to_string(r.at) + ": " + why);
  }

  // The record at `at`, which must end by `limit`, and its properties within its end.
  Record readHeader(std::uint64_t at, std::uint64_t limit) const {
    Record r{"", at, 0, 0, 0, 0};
    if (limit - at < 3 * word_ + 1) {
      throw ClipError(name_,
                      "node record at byte " + std::to_string(at) + ": its header runs past byte " +
                          std::to_string(limit) + ", where " +
                          (limit == bytes_.size() ? std::string("the file") : std::string("its parent")) +
                          " ends");
    }
    r.end = readLittle(bytes_, at, word_);
    r.count = readLittle(bytes_, at + word_, word_);
    const std::uint64_t length = readLittle(bytes_, at + 2 * word_, word_);
    const std::uint64_t nameAt = at + 3 * word_ + 1;
    const std::uint64_t nameLength = static_cast<unsigned char>(bytes_[at + 3 * word_]);
    if (nameLength <= limit - nameAt) r.name = std::string(bytes_.substr(nameAt, nameLength));
    const std::string parent = limit == bytes_.size() ? "the file" : "its parent";
    if (r.end > limit || r.end < nameAt + nameLength)
      fail(r, "it ends at byte " + std::to_string(r.end) + ", outside " + parent + " (bytes " +
                  std::to_string(nameAt + nameLength) + " to " + std::to_string(limit) + ")");
    r.properties = nameAt + nameLength;
    if (length > r.end - r.properties)
      fail(r, "its properties' " + std::to_string(length) + " bytes run past its end at byte " +
                  std::to_string(r.end));
    r.listEnd = r.properties + length;
    // A property is at least its type's byte.
    if (r.count > length)
      fail(r, std::to_string(r.count) + " properties in " + std::to_string(length) + " bytes");
    return r;
  }

  // Each property within the record's list, and an array's count within its bytes; the curves'
  // facts gathered on the way.
  void readProperties(const Record& r, const std::vector<Record>& open) {
    std::vector<Property> properties;
    std::uint64_t at = r.properties;
    for (std::uint64_t p = 0; p < r.count; ++p) {
      const auto left = [&] { return r.listEnd - at; };
      if (left() < 1) fail(r, "property " + std::to_string(p) + " runs past its property list");
      Property property;
      property.type = bytes_[at++];
      const auto need = [&](std::uint64_t n, const char* what) {
        if (n > left())
          fail(r, "property " + std::to_string(p) + " (" + what + ") needs " + std::to_string(n) +
                      " bytes where its property list holds " + std::to_string(left()));
      };
      const std::size_t stride = strideOf(property.type);
      switch (property.type) {
        case 'Y':
          need(2, "a 16-bit integer");
          at += 2;
          break;
        case 'C':
          need(1, "a flag");
          at += 1;
          break;
        case 'I':
        case 'F':
          need(4, "a 4-byte number");
          at += 4;
          break;
        case 'D':
          need(8, "an 8-byte number");
          at += 8;
          break;
        case 'L':
          need(8, "a 64-bit integer");
          property.integer = static_cast<std::int64_t>(readLittle(bytes_, at, 8));
          at += 8;
          break;
        case 'S':
        case 'R': {
          need(4, "a length");
          const std::uint64_t length = readLittle(bytes_, at, 4);
          at += 4;
          need(length, property.type == 'S' ? "a string" : "raw bytes");
          if (property.type == 'S') property.text = std::string(bytes_.substr(at, length));
          at += length;
          break;
        }
        default:
          if (stride == 0) return;  // a type assimp refuses itself, or takes to the end ('b')
          need(12, "an array's count, encoding and length");
          const std::uint64_t count = readLittle(bytes_, at, 4);
          const std::uint64_t encoding = readLittle(bytes_, at + 4, 4);
          const std::uint64_t stored = readLittle(bytes_, at + 8, 4);
          at += 12;
          need(stored, "an array");
          const std::uint64_t bytes = count * stride;  // under 2^35: no wrap in 64 bits
          const std::string says = "an array of " + std::to_string(count) + " values of " +
                                   std::to_string(stride) + " bytes in " + std::to_string(stored) + " bytes";
          if (bytes >= kMostArrayBytes) fail(r, says + ": 1 GB or more, more than a clip file needs");
          if (encoding == 0 && bytes != stored) fail(r, says + ", stored as they are");
          if (encoding == 1 && bytes > stored * kMostInflation) fail(r, says + ", more than they inflate to");
          arraysBytes_ += bytes;
          if (arraysBytes_ > kMostArraysBytes)
            fail(r, says + ": the file's arrays come to " + std::to_string(arraysBytes_) +
                        " bytes, more than 256 MB, more than a clip's keys");
          if (property.type == 'l' && (encoding == 0 || encoding == 1))
            property.int64s = int64s(bytes_.substr(at, stored), count, encoding == 1);
          at += stored;
          break;
      }
      properties.push_back(std::move(property));
    }
    if (at != r.listEnd) return;  // assimp refuses a list its properties do not fill
    gather(r, open, properties);
  }

  // An array of `count` int64 values, inflated if `compressed`; nullopt if it does not inflate to them
  // (assimp's reader then reads zeros: left to the clip's own checks).
  static std::optional<std::vector<std::int64_t>> int64s(std::string_view stored, std::uint64_t count,
                                                         bool compressed) {
    std::string plain(count * 8, '\0');
    if (compressed) {
      uLongf length = static_cast<uLongf>(plain.size());
      const int status =
          uncompress(reinterpret_cast<Bytef*>(plain.data()), &length,
                     reinterpret_cast<const Bytef*>(stored.data()), static_cast<uLong>(stored.size()));
      if (status != Z_OK || length != plain.size()) return std::nullopt;
    } else {
      plain.assign(stored);
    }
    std::vector<std::int64_t> values(count);
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = static_cast<std::int64_t>(readLittle(plain, 8 * i, 8));
    return values;
  }

  // A model's name, a connection, a curve's key times.
  void gather(const Record& r, const std::vector<Record>& open, const std::vector<Property>& properties) {
    const auto under = [&](std::size_t depth, const char* parent) {
      return open.size() == depth && !open.empty() && open[0].name == parent;
    };
    const auto is = [&](std::size_t i, char type) {
      return properties.size() > i && properties[i].type == type;
    };
    if (r.name == "Model" && under(1, "Objects") && is(0, 'L') && is(1, 'S')) {
      // "name\0\1Model": the name, then the class.
      const std::string& text = properties[1].text;
      curves_.model(properties[0].integer, text.substr(0, text.find(std::string_view("\0\1", 2))));
    } else if (r.name == "C" && under(1, "Connections") && is(1, 'L') && is(2, 'L')) {
      curves_.link(properties[1].integer, properties[2].integer, is(3, 'S') ? properties[3].text : "", 0,
                   r.at);
    } else if (r.name == "KeyTime" && open.size() == 2 && open[0].name == "Objects" &&
               open[1].name == "AnimationCurve" && is(0, 'l') && properties[0].int64s) {
      curves_.keyTimes(curveId_, *properties[0].int64s, 0,
                       "node record 'KeyTime' at byte " + std::to_string(r.at) + ": ");
    }
    if (r.name == "P" && open.size() == 3 && open[0].name == "Objects" && open[1].name == "Model" &&
        open[2].name == "Properties70" && is(0, 'S') && is(1, 'S')) {
      if (const std::string why = modelPropertyProblem(properties[0].text, properties[1].text); !why.empty())
        fail(r, why);
    }
    if (r.name == "AnimationCurve" && under(1, "Objects") && is(0, 'L')) curveId_ = properties[0].integer;
  }

  std::string_view bytes_;
  const std::string& name_;
  std::size_t word_ = 4;
  std::int64_t curveId_ = 0;
  std::uint64_t arraysBytes_ = 0;  // the arrays' values read so far, inflated
  FbxCurves curves_;
};

}  // namespace

void FbxCurves::model(std::int64_t id, std::string name) {
  models_.emplace(id, std::move(name));
}

void FbxCurves::link(std::int64_t source, std::int64_t target, std::string property, std::size_t line,
                     std::size_t byte) {
  if (property.empty())
    children_[target].push_back({source, line, byte});
  else
    links_.emplace(source, Link{target, std::move(property)});
}

std::string FbxCurves::modelName(std::int64_t id) const {
  const auto named = models_.find(id);
  return "model " + std::to_string(id) + (named == models_.end() ? "" : " '" + named->second + "'");
}

// The models under the root (0) as assimp converts them, depth first, without recursion.
void FbxCurves::checkModels(const std::string& name) const {
  const auto refuse = [&](const Child& at, const std::string& why) {
    if (at.line > 0) throw ClipError(name, at.line, why);
    throw ClipError(name, "node record 'C' at byte " + std::to_string(at.byte) + ": " + why);
  };
  const std::vector<Child> none;
  const auto childrenOf = [&](std::int64_t id) -> const std::vector<Child>& {
    const auto found = children_.find(id);
    return found == children_.end() ? none : found->second;
  };
  enum class Mark { open, done };
  std::map<std::int64_t, Mark> marks{{0, Mark::open}};
  std::map<std::int64_t, std::uint64_t> unfolded;
  std::map<std::int64_t, int> height;  // the levels below a model, once unfolded
  struct Frame {
    Child self;  // the link that put the model here (none for the root)
    std::size_t next;
  };
  std::vector<Frame> path{{{0, 0, 0}, 0}};
  while (!path.empty()) {
    Frame& top = path.back();
    const std::vector<Child>& children = childrenOf(top.self.id);
    if (top.next < children.size()) {
      const Child& child = children[top.next++];
      if (!models_.contains(child.id)) continue;  // assimp converts models alone
      const auto mark = marks.find(child.id);
      if (mark != marks.end() && mark->second == Mark::open)
        refuse(child, modelName(child.id) + " is linked under " + modelName(top.self.id) +
                          ", which is under it: the models would nest without end");
      if (mark != marks.end()) continue;
      marks.emplace(child.id, Mark::open);
      path.push_back({child, 0});
      continue;
    }
    std::uint64_t nodes = 1;
    int levels = 0;
    for (const Child& child : children) {
      if (!models_.contains(child.id)) continue;
      nodes = std::min(nodes + unfolded[child.id], kMaxUnfoldedNodes + 1);
      levels = std::max(levels, height[child.id] + 1);
    }
    // assimp converts a model's children by recursing once a level, as the clip collects its bones.
    if (levels > kMaxDepth && top.self.id != 0)
      refuse(top.self, modelName(top.self.id) + " has models linked " + std::to_string(levels) +
                           " deep under it: more than " + std::to_string(kMaxDepth) +
                           " (a skeleton's are tens deep)");
    if (nodes > kMaxUnfoldedNodes && top.self.id != 0)
      refuse(top.self, modelName(top.self.id) +
                           " unfolds, a copy under each model it is linked to, to more than " +
                           std::to_string(kMaxUnfoldedNodes) + " nodes (a skeleton has tens)");
    if (nodes > kMaxUnfoldedNodes)
      throw ClipError(name, "the models unfold, a copy under each model they are linked to, to more than " +
                                std::to_string(kMaxUnfoldedNodes) + " nodes (a skeleton has tens)");
    unfolded[top.self.id] = nodes;
    height[top.self.id] = levels;
    marks[top.self.id] = Mark::done;
    path.pop_back();
  }
}

void FbxCurves::keyTimes(std::int64_t curve, const std::vector<std::int64_t>& times, std::size_t line,
                         const std::string& where) {
  if (unordered_) return;
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (times[k] > times[k - 1]) continue;
    unordered_ =
        Unordered{curve, line, where,
                  "key " + std::to_string(k) + " at " + std::to_string(times[k]) + " is not after key " +
                      std::to_string(k - 1) + " at " + std::to_string(times[k - 1])};
    return;
  }
}

void FbxCurves::check(const std::string& name) const {
  checkModels(name);
  if (!unordered_) return;
  // The curve is linked to a component ("d|X") of a curve node, the curve node to a property
  // ("Lcl Rotation") of a model.
  std::string what = "animation curve " + std::to_string(unordered_->curve);
  if (const auto node = links_.find(unordered_->curve); node != links_.end()) {
    what = "the curve " + node->second.property;
    if (const auto model = links_.find(node->second.target); model != links_.end()) {
      what += " of " + model->second.property;
      if (const auto named = models_.find(model->second.target); named != models_.end())
        what += " of node '" + named->second + "'";
    }
  }
  const std::string why = "KeyTime: " + unordered_->why + ": the keys of " + what +
                          " are out of time order (assimp would drop the curve)";
  if (unordered_->line > 0) throw ClipError(name, unordered_->line, why);
  throw ClipError(name, unordered_->where + why);
}

void checkBinaryFbx(std::string_view content, const std::string& name) {
  if (content.size() < kFirstRecord) return;  // assimp's reader refuses it
  BinaryFbx fbx(content, name);
  fbx.check();
  fbx.curves().check(name);
}

}  // namespace clips::detail
