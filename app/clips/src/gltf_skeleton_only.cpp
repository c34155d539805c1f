// What assimp is given of a glTF clip (skeleton_only.h): a new document of the nodes, the
// animations' rotation, translation and scale channels, and the accessors, buffer views and buffers
// their keys are read from, each of those checked to lie within what it is read from. assimp 5.2
// bounds an accessor by its component size times its count, not its element size or stride, and
// reads a cubic spline's values three to a time whatever their count (docs/physics.md,
// "Animation").
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "clips/clip_file.h"
#include "format_checks.h"
#include "skeleton_only.h"
#include "text_tokens.h"

namespace clips::detail {
namespace {

using Json = nlohmann::json;

// A glTF's sizes and indices are all within the file's bytes once checkGltf has run; 32 bits is
// assimp's own limit for a stride, and keeps every sum and product below in 64 bits.
constexpr std::uint64_t kMaxWhole = 0xffffffff;
constexpr std::uint32_t kFloat = 5126;  // glTF's componentType for a 32-bit float

// nlohmann's reason without its tag and line ("[json.exception.parse_error.101] parse error at
// line 2, "): the line is given by the ClipError.
std::string jsonReason(std::string_view why) {
  if (why.starts_with('[')) {
    if (const std::size_t end = why.find("] "); end != std::string_view::npos) why.remove_prefix(end + 2);
  }
  if (why.starts_with("parse error at line ")) {
    if (const std::size_t comma = why.find(", "); comma != std::string_view::npos)
      why.remove_prefix(comma + 2);
  }
  return std::string(why);
}

// `json` parsed, or refused naming the line of its error (`chunk`: a .glb's JSON chunk, which is
// named since the file around it has no lines).
Json parseJson(std::string_view json, const std::string& name, bool chunk) {
  try {
    return Json::parse(json.begin(), json.end());
  } catch (const Json::parse_error& e) {
    const std::size_t line = lineAt(json, e.byte > 0 ? e.byte - 1 : 0);
    const std::string why = "not JSON: " + jsonReason(e.what());
    if (chunk) throw ClipError(name, "its JSON chunk, line " + std::to_string(line) + ": " + why);
    throw ClipError(name, line, why);
  } catch (const Json::exception& e) {  // a number past a double's range
    throw ClipError(name, std::string(chunk ? "its JSON chunk: " : "") + "not JSON: " + jsonReason(e.what()));
  }
}

// Indices of what is kept, numbered anew in the order they are first kept.
class Kept {
 public:
  std::uint64_t keep(std::uint64_t old) {
    const auto [at, added] = index_.try_emplace(old, order_.size());
    if (added) order_.push_back(old);
    return at->second;
  }
  const std::vector<std::uint64_t>& order() const { return order_; }

 private:
  std::map<std::uint64_t, std::uint64_t> index_;
  std::vector<std::uint64_t> order_;
};

// The element of a glTF accessor type a clip's keys are stored as, and its number of floats.
struct KeyLayout {
  const char* type;
  std::uint64_t floats;
};
constexpr KeyLayout kTimes{"SCALAR", 1};
constexpr KeyLayout kTurns{"VEC4", 4};
constexpr KeyLayout kVectors{"VEC3", 3};

// `source` with only its members in `keys` (those it has).
Json only(const Json& source, std::initializer_list<const char*> keys) {
  Json kept = Json::object();
  for (const char* key : keys) {
    if (const auto at = source.find(key); at != source.end()) kept[key] = *at;
  }
  return kept;
}

// Builds the skeleton-only document from a parsed glTF, refusing what assimp would read out of
// bounds in it. `binBytes`: a .glb's BIN chunk length (0 if it has none); nullopt for a .gltf.
class SkeletonOnly {
 public:
  SkeletonOnly(const Json& doc, const std::string& name, std::optional<std::uint64_t> binBytes)
      : doc_(doc), name_(name), binBytes_(binBytes) {}

  Json build() {
    if (!doc_.is_object()) refuse("its JSON is not an object");
    Json out = Json::object();
    if (const auto asset = doc_.find("asset"); asset != doc_.end()) {
      out["asset"] = *asset;
      // Another version is refused by assimp on its asset alone.
      const auto version = asset->find("version");
      if (version != asset->end() && version->is_string() && !version->get<std::string>().starts_with('2'))
        return out;
    }
    if (const auto scene = doc_.find("scene"); scene != doc_.end()) out["scene"] = *scene;
    out["scenes"] = filtered("scenes", "scene", {"name", "nodes"});
    // Every node, so that the indices in scenes, children and channels stay as they were; each with
    // its name, children and rest transform alone (no mesh, skin, camera, morph weights, extensions
    // or extras).
    out["nodes"] =
        filtered("nodes", "node", {"name", "children", "matrix", "translation", "rotation", "scale"});
    if (binBytes_) buffers_.keep(binBuffer());
    Json animations = Json::array();
    const Json& all = items(doc_, "animations", "");
    for (std::size_t a = 0; a < all.size(); ++a) animations.push_back(animation(all[a], a));
    out["animations"] = std::move(animations);
    // In this order: each kept accessor keeps its view, each kept view its buffer.
    out["accessors"] = keptFrom("accessors", accessors_, [&](const Json& accessor, std::uint64_t a) {
      return keptAccessor(accessor, a);
    });
    out["bufferViews"] = keptFrom("bufferViews", views_,
                                  [&](const Json& view, std::uint64_t v) { return keptBufferView(view, v); });
    out["buffers"] = keptBuffers();
    return out;
  }

 private:
  [[noreturn]] void refuse(const std::string& why) const { throw ClipError(name_, why); }

  // `owner`'s array `key`, or an empty one if it has none (`what`: the owner, "" for the file).
  const Json& items(const Json& owner, const char* key, const std::string& what) const {
    const auto at = owner.find(key);
    if (at == owner.end()) return empty_;
    if (!at->is_array()) refuse((what.empty() ? "" : what + ": ") + "\"" + key + "\" is not an array");
    return *at;
  }

  // Item `index` of `array` (`kind` in `among`, "the file's accessors"), an object; refused in
  // `what`'s name if there is none.
  const Json& item(const Json& array, std::uint64_t index, const std::string& kind, const std::string& among,
                   const std::string& what) const {
    if (index >= array.size())
      refuse(what + ": " + kind + " " + std::to_string(index) + " is past " + among + " " +
             std::to_string(array.size()) + " " + kind + "s");
    const Json& found = array[index];
    if (!found.is_object()) refuse(kind + " " + std::to_string(index) + " is not a JSON object");
    return found;
  }

  // `object`'s member `key` as a whole number, nullopt if it has none.
  std::optional<std::uint64_t> whole(const Json& object, const char* key, const std::string& what) const {
    const auto at = object.find(key);
    if (at == object.end()) return std::nullopt;
    if (!at->is_number_unsigned() || at->get<std::uint64_t>() > kMaxWhole)
      refuse(what + ": \"" + key + "\" is " + at->dump() + ", not a whole number from 0 to " +
             std::to_string(kMaxWhole));
    return at->get<std::uint64_t>();
  }

  std::uint64_t required(const Json& object, const char* key, const std::string& what) const {
    const std::optional<std::uint64_t> value = whole(object, key, what);
    if (!value) refuse(what + " has no \"" + key + "\"");
    return *value;
  }

  // The top-level array `key`, each item an object with only the members in `keys`.
  Json filtered(const char* key, const std::string& kind, std::initializer_list<const char*> keys) const {
    Json kept = Json::array();
    const Json& all = items(doc_, key, "");
    for (std::size_t i = 0; i < all.size(); ++i)
      kept.push_back(only(item(all, i, kind, "the file's", ""), keys));
    return kept;
  }

  // The path a channel moves, "" if it names none.
  static std::string pathOf(const Json& channel) {
    const auto target = channel.find("target");
    if (target == channel.end() || !target->is_object()) return "";
    const auto path = target->find("path");
    return path != target->end() && path->is_string() ? path->get<std::string>() : "";
  }

  // An animation with its rotation, translation and scale channels alone and the samplers they use.
  Json animation(const Json& animation, std::size_t a) {
    const std::string where = "animation " + std::to_string(a);
    if (!animation.is_object()) refuse(where + " is not a JSON object");
    const Json& channels = items(animation, "channels", where);
    const Json& samplers = items(animation, "samplers", where);
    Kept keptSamplers;
    Json keptChannels = Json::array();
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const std::string channelAt = where + ", channel " + std::to_string(c);
      if (!channels[c].is_object()) refuse(channelAt + " is not a JSON object");
      const std::string path = pathOf(channels[c]);
      if (path != "rotation" && path != "translation" && path != "scale") continue;
      const std::uint64_t s = required(channels[c], "sampler", channelAt);
      const Json& sampler = item(samplers, s, "sampler", "the animation's", channelAt);
      const std::optional<std::uint64_t> node = whole(channels[c].at("target"), "node", channelAt);
      if (!node) refuse(channelAt + ": its target names no node");
      checkSampler(sampler, where + ", sampler " + std::to_string(s), path == "rotation" ? kTurns : kVectors);
      keptChannels.push_back(
          {{"sampler", keptSamplers.keep(s)}, {"target", {{"node", *node}, {"path", path}}}});
    }
    Json kept = only(animation, {"name"});
    kept["channels"] = std::move(keptChannels);
    kept["samplers"] = Json::array();
    for (const std::uint64_t s : keptSamplers.order()) {
      Json sampler = only(samplers[s], {"interpolation"});
      sampler["input"] = accessors_.keep(required(samplers[s], "input", where));
      sampler["output"] = accessors_.keep(required(samplers[s], "output", where));
      kept["samplers"].push_back(std::move(sampler));
    }
    return kept;
  }

  // A sampler's times and keys: floats of the layout assimp copies them into, a key for each time
  // (three for a cubic spline: an in-tangent, the value and an out-tangent), and at least one.
  void checkSampler(const Json& sampler, const std::string& where, const KeyLayout& keys) const {
    const Json& accessors = items(doc_, "accessors", "");
    const std::uint64_t input = required(sampler, "input", where);
    const std::uint64_t output = required(sampler, "output", where);
    const std::string inputAt = where + ": its input, accessor " + std::to_string(input);
    const std::string outputAt = where + ": its output, accessor " + std::to_string(output);
    const Json& times = item(accessors, input, "accessor", "the file's", where);
    const Json& values = item(accessors, output, "accessor", "the file's", where);
    checkLayout(times, inputAt, kTimes, "times");
    checkLayout(values, outputAt, keys, "keys");
    const std::uint64_t timeCount = required(times, "count", "accessor " + std::to_string(input));
    const std::uint64_t keyCount = required(values, "count", "accessor " + std::to_string(output));
    if (timeCount == 0) refuse(inputAt + ", holds no times");
    const std::string interpolation = interpolationOf(sampler);
    const std::uint64_t needed = interpolation == "CUBICSPLINE" ? 3 * timeCount : timeCount;
    if (keyCount != needed)
      refuse(outputAt + ", holds " + std::to_string(keyCount) + " keys for " + std::to_string(timeCount) +
             " times, where " + interpolation + " needs " + std::to_string(needed) +
             (interpolation == "CUBICSPLINE" ? " (an in-tangent, a value and an out-tangent each)" : ""));
  }

  // assimp reads any interpolation it does not know as LINEAR.
  static std::string interpolationOf(const Json& sampler) {
    const auto at = sampler.find("interpolation");
    const std::string given = at != sampler.end() && at->is_string() ? at->get<std::string>() : "";
    return given == "CUBICSPLINE" || given == "STEP" ? given : "LINEAR";
  }

  // assimp copies an accessor's elements into floats whatever they are: bytes as times left three
  // bytes of each unset, shorts as rotations were read as the halves of floats.
  void checkLayout(const Json& accessor, const std::string& where, const KeyLayout& layout,
                   const std::string& what) const {
    const auto type = accessor.find("type");
    const auto component = accessor.find("componentType");
    const bool floats = component != accessor.end() && component->is_number_unsigned() &&
                        component->get<std::uint64_t>() == kFloat;
    if (type == accessor.end() || *type != layout.type || !floats)
      refuse(where + ", holds " + (type == accessor.end() ? "no type" : type->dump()) + " of componentType " +
             (component == accessor.end() ? "none" : component->dump()) + ", where " + what + " are " +
             layout.type + " of floats (" + std::to_string(kFloat) + ")");
  }

  // The items of the top-level array `key` that `kept` lists, in its order, each made by `keep`.
  template <class Keep>
  Json keptFrom(const char* key, const Kept& kept, Keep keep) {
    Json out = Json::array();
    const Json& all = items(doc_, key, "");
    for (const std::uint64_t i : kept.order()) out.push_back(keep(all[i], i));
    return out;
  }

  // An accessor of a kept sampler (its layout checked), its elements within its buffer view.
  Json keptAccessor(const Json& accessor, std::uint64_t a) {
    const std::string where = "accessor " + std::to_string(a);
    if (accessor.contains("sparse")) refuse(where + ": a sparse accessor: a clip's keys are stored whole");
    const std::optional<std::uint64_t> v = whole(accessor, "bufferView", where);
    if (!v) refuse(where + " has no bufferView: a clip's keys are read from a buffer");
    const Json& view = item(items(doc_, "bufferViews", ""), *v, "bufferView", "the file's", where);
    const std::string viewAt = "bufferView " + std::to_string(*v);
    const std::uint64_t viewBytes = required(view, "byteLength", viewAt);
    const std::uint64_t stride = whole(view, "byteStride", viewAt).value_or(0);
    const std::uint64_t offset = whole(accessor, "byteOffset", where).value_or(0);
    const std::uint64_t count = required(accessor, "count", where);
    const std::uint64_t elementBytes = 4 * (accessor.at("type") == kTimes.type   ? kTimes.floats
                                            : accessor.at("type") == kTurns.type ? kTurns.floats
                                                                                 : kVectors.floats);
    if (stride != 0 && stride < elementBytes)
      refuse(viewAt + ": byteStride " + std::to_string(stride) + " is less than the " +
             std::to_string(elementBytes) + " bytes of an element of " + where);
    const std::uint64_t step = stride != 0 ? stride : elementBytes;
    const std::uint64_t end = count == 0 ? offset : offset + (count - 1) * step + elementBytes;
    if (end > viewBytes)
      refuse(where + ": its " + std::to_string(count) + " elements of " + std::to_string(elementBytes) +
             " bytes, " + std::to_string(step) + " apart from byte " + std::to_string(offset) +
             ", end at byte " + std::to_string(end) + ", past the " + std::to_string(viewBytes) +
             " bytes of " + viewAt);
    Json kept = only(accessor, {"name", "componentType", "type"});
    kept["bufferView"] = views_.keep(*v);
    kept["byteOffset"] = offset;
    kept["count"] = count;
    return kept;
  }

  // A buffer view of a kept accessor, within its buffer.
  Json keptBufferView(const Json& view, std::uint64_t v) {
    const std::string where = "bufferView " + std::to_string(v);
    const std::uint64_t b = required(view, "buffer", where);
    const Json& buffer = item(items(doc_, "buffers", ""), b, "buffer", "the file's", where);
    const std::uint64_t offset = whole(view, "byteOffset", where).value_or(0);
    const std::uint64_t length = required(view, "byteLength", where);
    const std::uint64_t bufferBytes = bytesOf(buffer, b);
    if (offset + length > bufferBytes)
      refuse(where + ": bytes " + std::to_string(offset) + " to " + std::to_string(offset + length) +
             " are past the " + std::to_string(bufferBytes) + " bytes of buffer " + std::to_string(b));
    Json kept = only(view, {"name"});
    kept["buffer"] = buffers_.keep(b);
    kept["byteOffset"] = offset;
    kept["byteLength"] = length;
    if (const std::uint64_t stride = whole(view, "byteStride", where).value_or(0); stride != 0)
      kept["byteStride"] = stride;
    return kept;
  }

  // The bytes a buffer says it holds; a .glb's own buffer no more than its BIN chunk holds.
  std::uint64_t bytesOf(const Json& buffer, std::uint64_t b) const {
    const std::string where = "buffer " + std::to_string(b);
    const std::uint64_t bytes = required(buffer, "byteLength", where);
    if (binBytes_ && b == binBuffer() && bytes > *binBytes_)
      refuse(where + " says it holds " + std::to_string(bytes) + " bytes, but the BIN chunk holds " +
             std::to_string(*binBytes_));
    return bytes;
  }

  static bool hasUri(const Json& buffer) {
    const auto uri = buffer.find("uri");
    return uri != buffer.end() && uri->is_string();
  }

  // A .glb's own buffer (its BIN chunk): the first with no uri. assimp takes buffer 0 of a .glb as
  // the BIN chunk, whatever it says, so it is made buffer 0. kNone if there is none.
  std::uint64_t binBuffer() const {
    const Json& all = items(doc_, "buffers", "");
    for (std::size_t b = 0; b < all.size(); ++b) {
      if (all[b].is_object() && !hasUri(all[b])) return b;
    }
    return kNone;
  }

  Json keptBuffers() const {
    Json kept = Json::array();
    const Json& all = items(doc_, "buffers", "");
    for (const std::uint64_t b : buffers_.order()) {
      Json buffer = b == kNone ? Json::object() : only(all[b], {"name", "byteLength"});
      if (binBytes_ && kept.empty()) {  // a .glb's own buffer, which assimp takes to be its BIN chunk
        buffer["byteLength"] = *binBytes_;
      } else if (hasUri(all[b])) {
        buffer["uri"] = all[b].at("uri");
      }
      kept.push_back(std::move(buffer));
    }
    return kept;
  }

  static constexpr std::uint64_t kNone = ~std::uint64_t{0};

  const Json& doc_;
  const std::string& name_;
  std::optional<std::uint64_t> binBytes_;
  const Json empty_ = Json::array();
  Kept accessors_, views_, buffers_;
};

void appendWord(std::string& out, std::uint64_t n) {
  const auto word = static_cast<std::uint32_t>(n);
  out.append(reinterpret_cast<const char*>(&word), sizeof word);
}

constexpr std::size_t kHeaderBytes = 12, kChunkHeaderBytes = 8;

std::size_t padded(std::size_t bytes) {
  return (bytes + 3) / 4 * 4;
}

// A .glb's JSON and BIN chunks (checkGlb has found every chunk within the file).
struct Glb {
  std::string_view json;
  std::optional<std::string_view> bin;
};

// The chunks of a glTF 2.0 .glb whose first chunk is its JSON; nullopt for anything else, which
// assimp refuses by its header alone.
std::optional<Glb> glbChunks(std::string_view content, const std::string& name) {
  if (content.size() < kHeaderBytes + kChunkHeaderBytes || !content.starts_with("glTF") ||
      readLittle(content, 4, 4) != 2 || content.substr(16, 4) != "JSON")
    return std::nullopt;
  const std::size_t jsonBytes = readLittle(content, kHeaderBytes, 4);
  if (jsonBytes > content.size() - kHeaderBytes - kChunkHeaderBytes)
    throw ClipError(name, "its JSON chunk is past the file's end");
  Glb glb;
  glb.json = content.substr(kHeaderBytes + kChunkHeaderBytes, jsonBytes);
  // assimp's JSON reader stops at a zero byte, and some writers pad the chunk with them.
  glb.json = glb.json.substr(0, glb.json.find_last_not_of('\0') + 1);
  const std::size_t binAt = padded(kHeaderBytes + kChunkHeaderBytes + jsonBytes);
  if (binAt + kChunkHeaderBytes <= content.size() &&
      content.substr(binAt + 4, 4) == std::string_view("BIN\0", 4)) {
    const std::size_t binBytes = readLittle(content, binAt, 4);
    if (binBytes > content.size() - binAt - kChunkHeaderBytes)
      throw ClipError(name, "its BIN chunk is past the file's end");
    glb.bin = content.substr(binAt + kChunkHeaderBytes, binBytes);
  }
  return glb;
}

// A .glb of `json` (padded with spaces) and `bin` (with zeros).
std::string glbOf(std::string json, std::optional<std::string_view> bin) {
  json.resize(padded(json.size()), ' ');
  const std::size_t binChunk = bin ? kChunkHeaderBytes + padded(bin->size()) : 0;
  std::string out = "glTF";
  appendWord(out, 2);
  appendWord(out, kHeaderBytes + kChunkHeaderBytes + json.size() + binChunk);
  appendWord(out, json.size());
  out += "JSON";
  out += json;
  if (bin) {
    appendWord(out, bin->size());
    out.append("BIN\0", 4);
    out += *bin;
    out.resize(padded(out.size()), '\0');
  }
  return out;
}

}  // namespace

std::optional<std::string> gltfSkeletonOnly(std::string_view json, const std::string& name) {
  return SkeletonOnly(parseJson(json, name, false), name, std::nullopt).build().dump();
}

std::optional<std::string> glbSkeletonOnly(std::string_view content, const std::string& name) {
  const std::optional<Glb> glb = glbChunks(content, name);
  if (!glb) return std::nullopt;
  const Json doc = parseJson(glb->json, name, true);
  const std::uint64_t binBytes = glb->bin ? glb->bin->size() : 0;
  return glbOf(SkeletonOnly(doc, name, binBytes).build().dump(), glb->bin);
}

}  // namespace clips::detail
