// What assimp takes on trust in FBX, glTF, COLLADA and .x (format_checks.h).
#include "format_checks.h"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

#include <pugixml.hpp>

#include "clips/clip_file.h"
#include "text_tokens.h"

namespace clips::detail {
namespace {

std::string tooDeep(const std::string& what) {
  return what + " nested more than " + std::to_string(kMaxDepth) + " deep (a skeleton's are tens deep)";
}

// ---- glTF ----

// An open JSON container, and what it is in a glTF: the top-level "nodes" array, a node, or a
// node's "children".
struct JsonFrame {
  char type;        // '{' or '['
  std::string key;  // an object's last key
  bool expectKey = true;
  bool nodes = false;
  bool node = false;
  bool children = false;
  std::size_t nodeIndex = 0;  // a node's, or the node whose children these are
};

// The JSON's containers, nested no deeper than kMaxDepth (assimp's JSON reader recurses once a level:
// 200,000 '[' overflowed the stack), and each node's children; a JSON that is not well formed is
// left to the skeleton-only copy to refuse (gltf_skeleton_only.cpp), which also bounds every size
// and index assimp is given.
std::vector<std::vector<std::uint64_t>> scanGltfJson(std::string_view json, const std::string& name,
                                                     const std::string& where) {
  std::vector<std::vector<std::uint64_t>> children;
  std::vector<JsonFrame> stack;
  std::size_t i = 0;
  const auto fail = [&](const std::string& why) {
    if (where.empty()) throw ClipError(name, lineAt(json, i), why);
    throw ClipError(name, where + "line " + std::to_string(lineAt(json, i)) + ": " + why);
  };
  while (i < json.size()) {
    const char c = json[i];
    if (isSpace(c) || c == ':') {
      ++i;
    } else if (c == ',') {
      if (!stack.empty() && stack.back().type == '{') stack.back().expectKey = true;
      ++i;
    } else if (c == '{' || c == '[') {
      JsonFrame frame{c, "", true};
      if (!stack.empty()) {
        const JsonFrame& parent = stack.back();
        frame.nodes = c == '[' && stack.size() == 1 && parent.type == '{' && parent.key == "nodes";
        frame.node = c == '{' && parent.nodes;
        frame.children = c == '[' && parent.node && parent.key == "children";
        if (frame.node) {
          frame.nodeIndex = children.size();
          children.emplace_back();
        } else if (frame.children) {
          frame.nodeIndex = parent.nodeIndex;
        }
      }
      stack.push_back(frame);
      if (stack.size() > static_cast<std::size_t>(kMaxDepth)) fail(tooDeep("objects and arrays"));
      ++i;
    } else if (c == '}' || c == ']') {
      if (stack.empty()) return children;
      stack.pop_back();
      ++i;
    } else if (c == '"') {
      const std::size_t start = ++i;
      while (i < json.size() && json[i] != '"') i += json[i] == '\\' ? 2 : 1;
      if (i >= json.size()) return children;
      if (!stack.empty() && stack.back().type == '{' && stack.back().expectKey) {
        stack.back().key = std::string(json.substr(start, i - start));
        stack.back().expectKey = false;
      }
      ++i;
    } else {
      const std::size_t start = i;
      while (i < json.size() && !isSpace(json[i]) && std::strchr(",:{}[]\"", json[i]) == nullptr) ++i;
      if (i == start) ++i;
      if (!stack.empty() && stack.back().children) {
        if (const std::optional<std::uint64_t> child = wholeNumber(json.substr(start, i - start)))
          children[stack.back().nodeIndex].push_back(*child);
      }
    }
  }
  return children;
}

// The nodes' tree no deeper than kMaxDepth: assimp's glTF reader recurses once a level, and a chain
// of 100,000 nodes overflowed the stack. A node that is its own ancestor is left for assimp, which
// refuses it.
void checkNodeDepth(const std::vector<std::vector<std::uint64_t>>& children, const std::string& name) {
  const std::size_t n = children.size();
  std::vector<bool> isChild(n, false);
  for (const auto& list : children)
    for (const std::uint64_t c : list)
      if (c < n) isChild[c] = true;
  std::vector<int> level(n, -1);
  std::vector<std::size_t> frontier;
  for (std::size_t i = 0; i < n; ++i)
    if (!isChild[i]) {
      level[i] = 0;
      frontier.push_back(i);
    }
  while (!frontier.empty()) {
    std::vector<std::size_t> next;
    for (const std::size_t parent : frontier) {
      for (const std::uint64_t c : children[parent]) {
        if (c >= n || level[c] >= 0) continue;
        level[c] = level[parent] + 1;
        if (level[c] > kMaxDepth)
          throw ClipError(name, "node " + std::to_string(c) + ": " + tooDeep("nodes"));
        next.push_back(c);
      }
    }
    frontier = std::move(next);
  }
}

// assimp's glTF reader imports a node under each node that lists it as a child, as often as it does,
// recursing once a level: 25 nodes each listing the next twice unfolded to 2^25 (2 GB), and a
// chain of nodes each listed by the root too nests as deep as the chain, which checkNodeDepth's
// shortest levels do not see. Each node's copies and height are counted once, depth first, without
// recursion; a node that is its own ancestor is skipped (assimp refuses it).
void checkNodeCopies(const std::vector<std::vector<std::uint64_t>>& children, const std::string& name) {
  const std::size_t n = children.size();
  enum class Mark { unseen, open, done };
  std::vector<Mark> marks(n, Mark::unseen);
  std::vector<std::uint64_t> unfolded(n, 1);
  std::vector<int> height(n, 0);
  for (std::size_t root = 0; root < n; ++root) {
    if (marks[root] != Mark::unseen) continue;
    marks[root] = Mark::open;
    std::vector<std::pair<std::size_t, std::size_t>> path{{root, 0}};  // a node, and its next child
    while (!path.empty()) {
      auto& [at, next] = path.back();
      if (next < children[at].size()) {
        const std::uint64_t child = children[at][next++];
        if (child >= n || marks[child] != Mark::unseen) continue;
        marks[child] = Mark::open;
        path.emplace_back(child, 0);
        continue;
      }
      for (const std::uint64_t child : children[at]) {
        if (child >= n || marks[child] != Mark::done) continue;
        unfolded[at] = std::min(unfolded[at] + unfolded[child], kMaxUnfoldedNodes + 1);
        height[at] = std::max(height[at], height[child] + 1);
      }
      if (unfolded[at] > kMaxUnfoldedNodes)
        throw ClipError(name, "node " + std::to_string(at) +
                                  " unfolds, a copy under each node that lists it as a child, to more than " +
                                  std::to_string(kMaxUnfoldedNodes) + " nodes (a skeleton has tens)");
      if (height[at] > kMaxDepth)
        throw ClipError(name, "node " + std::to_string(at) + ": " + tooDeep("nodes below it"));
      marks[at] = Mark::done;
      path.pop_back();
    }
  }
}

// The nodes' tree as assimp imports it (checkNodeDepth, checkNodeCopies).
void checkNodes(const std::vector<std::vector<std::uint64_t>>& children, const std::string& name) {
  checkNodeDepth(children, name);
  checkNodeCopies(children, name);
}

// ---- COLLADA ----

// Values a <param> of this type takes in an accessor's stride.
std::uint64_t paramWidth(std::string_view type) {
  const auto digit = [](char c) { return c >= '1' && c <= '9' ? static_cast<std::uint64_t>(c - '0') : 1; };
  if (type.starts_with("float") && type.size() == 8 && type[6] == 'x') return digit(type[5]) * digit(type[7]);
  if (type.starts_with("float") && type.size() == 6) return digit(type[5]);
  return 1;
}

std::uint64_t wordsIn(const char* text) {
  std::uint64_t words = 0;
  bool inWord = false;
  for (; *text != '\0'; ++text) {
    const bool space = isSpace(*text);
    if (!space && !inWord) ++words;
    inWord = !space;
  }
  return words;
}

// Sums and products of counts that stop at the largest count, so that a wrapped one never reads as
// a small one.
std::uint64_t plus(std::uint64_t x, std::uint64_t y) {
  return x > std::numeric_limits<std::uint64_t>::max() - y ? std::numeric_limits<std::uint64_t>::max()
                                                           : x + y;
}
std::uint64_t times(std::uint64_t x, std::uint64_t y) {
  return x != 0 && y > std::numeric_limits<std::uint64_t>::max() / x
             ? std::numeric_limits<std::uint64_t>::max()
             : x * y;
}

// The first word of `text` that is not an index (digits after an optional sign), if any.
std::optional<std::string_view> notAnIndex(std::string_view text) {
  for (auto at = text.begin();;) {
    const auto begin = std::find_if_not(at, text.end(), isSpace);
    if (begin == text.end()) return std::nullopt;
    at = std::find_if(begin, text.end(), isSpace);
    std::string_view word(begin, at);
    const std::string_view whole = word;
    if (word.starts_with('-') || word.starts_with('+')) word.remove_prefix(1);
    if (word.empty() || word.find_first_not_of("0123456789") != std::string_view::npos) return whole;
  }
}

// The sum of the whole numbers in `text` (a <vcount>'s), a word that is none counting 0.
std::uint64_t sumOf(std::string_view text) {
  std::uint64_t sum = 0;
  for (auto at = text.begin();;) {
    const auto begin = std::find_if_not(at, text.end(), isSpace);
    if (begin == text.end()) return sum;
    at = std::find_if(begin, text.end(), isSpace);
    sum = plus(sum, wholeNumber(std::string_view(begin, at)).value_or(0));
  }
}

struct Accessor {
  std::uint64_t count, offset, stride, width;
  std::uint64_t key;  // the numbers assimp reads a key of an animation's output: a matrix 16, else 1 a param
  std::string source;
  std::size_t line;
};

// Counts larger than this are more than any clip file holds (it is read whole, at most 64 MB).
constexpr std::uint64_t kMostValues = std::uint64_t{1} << 32;

class ColladaWalker : public pugi::xml_tree_walker {
 public:
  ColladaWalker(std::string_view text, const std::string& name) : lines_(text), name_(name) {}

  bool for_each(pugi::xml_node& node) override {
    if (node.type() != pugi::node_element) return true;
    const std::size_t line =
        lines_.lineOf(static_cast<std::size_t>(std::max<std::ptrdiff_t>(node.offset_debug(), 0)));
    if (depth() >= kMaxDepth) throw ClipError(name_, line, tooDeep("elements"));
    const std::string_view element = node.name();
    if (element.ends_with("_array")) {
      // assimp reads as many values as count says, none without it, and files an array without an
      // id under "", where an accessor's source="#" finds it.
      const std::uint64_t count = node.attribute("count") ? countOf(node, "count", line) : 0;
      const std::uint64_t held = wordsIn(node.child_value());
      if (held < count)
        throw ClipError(name_, line,
                        "<" + std::string(element) + "> says count=\"" + std::to_string(count) +
                            "\" but holds " + std::to_string(held) + " values");
      arrays_[node.attribute("id").value()] = count;
      if (element == "float_array" || element == "Name_array" || element == "IDREF_array")
        holdsNumbers_[node.attribute("id").value()] = element == "float_array";
    } else if (element == "accessor") {
      Accessor a{countOf(node, "count", line), 0, 1, 0, 0, node.attribute("source").value(), line};
      if (node.attribute("offset")) a.offset = countOf(node, "offset", line);
      if (node.attribute("stride")) a.stride = countOf(node, "stride", line);
      for (const pugi::xml_node param : node.children("param")) {
        const std::string_view type = param.attribute("type").value();
        a.width += paramWidth(type);
        if (param.attribute("type")) a.key += type == "float4x4" ? 16 : 1;  // as assimp sizes a key
      }
      if (a.source.starts_with('#')) a.source.erase(0, 1);
      // assimp files the first accessor of a <technique_common> under the id of the <source> it
      // reads: whichever encloses it, for a <source> in a <source>.
      if (std::string_view(node.parent().name()) == "technique_common" &&
          node.parent().child("accessor") == node)
        for (pugi::xml_node up = node.parent(); up; up = up.parent())
          if (std::string_view(up.name()) == "source")
            accessorsOf_[up.attribute("id").value()].push_back(accessors_.size());
      accessors_.push_back(a);
    } else if (element == "input" && std::string_view(node.parent().name()) == "sampler") {
      const std::string_view semantic = node.attribute("semantic").value();
      std::string source = node.attribute("source").value();
      if (source.starts_with('#')) source.erase(0, 1);
      if (semantic == "INPUT" || semantic == "OUTPUT")
        keyInputs_.push_back({line, std::string(semantic), source});
    } else if (isPrimitives(element) && node.attribute("count")) {
      checkIndices(node, line);
    } else if (element == "vertex_weights" && node.attribute("count")) {
      checkWeights(node, line);
    } else if (element == "node") {
      nodeIndex_[node.internal_object()] = nodes_.size();
      nodes_.push_back({line, enclosingNode(node), {}});
      for (const char* key : {"id", "name"})
        if (const char* value = node.attribute(key).value(); *value != '\0')
          nodesNamed_[value].push_back(nodes_.size() - 1);
    } else if (element == "instance_node") {
      std::string url = node.attribute("url").value();
      if (url.starts_with('#')) url.erase(0, 1);
      instances_.push_back({line, enclosingNode(node), std::move(url)});
    }
    return true;
  }

  // assimp copies the node an <instance_node> names into the one it is in, and then what that one
  // instances, recursing once a level: a node that instances itself or a node it is in overflowed
  // the stack, and a few nodes instancing each other twice over would unfold to billions.
  void checkNodeInstances() {
    for (const Instance& instance : instances_) {
      if (instance.in == kNone) continue;
      for (const std::size_t target : nodesNamed_[instance.url])
        nodes_[instance.in].edges.push_back({target, instance.line, instance.url});
    }
    for (std::size_t i = 0; i < nodes_.size(); ++i)
      if (nodes_[i].parent != kNone) nodes_[nodes_[i].parent].edges.push_back({i, 0, {}});
    enum class Mark { unseen, open, done };
    std::vector<Mark> marks(nodes_.size(), Mark::unseen);
    std::vector<std::uint64_t> unfolded(nodes_.size(), 1);
    std::vector<int> height(nodes_.size(), 0);  // the levels below a node, once unfolded
    for (std::size_t root = 0; root < nodes_.size(); ++root) {
      if (marks[root] != Mark::unseen) continue;
      std::vector<std::pair<std::size_t, std::size_t>> path{{root, 0}};  // a node, and its next edge
      marks[root] = Mark::open;
      while (!path.empty()) {
        auto& [at, next] = path.back();
        if (next == nodes_[at].edges.size()) {
          marks[at] = Mark::done;
          for (const Edge& edge : nodes_[at].edges) {
            unfolded[at] = plus(unfolded[at], unfolded[edge.to]);
            height[at] = std::max(height[at], height[edge.to] + 1);
          }
          if (height[at] > kMaxDepth)
            throw ClipError(name_, nodes_[at].line,
                            "<node> unfolds through its <instance_node>s to " + tooDeep("nodes below it"));
          if (unfolded[at] > kMaxUnfoldedNodes)
            throw ClipError(name_, nodes_[at].line,
                            "<node> unfolds through its <instance_node>s to more than " +
                                std::to_string(kMaxUnfoldedNodes) + " nodes (a skeleton has tens)");
          path.pop_back();
          continue;
        }
        const Edge& edge = nodes_[at].edges[next++];
        if (marks[edge.to] == Mark::open)
          throw ClipError(name_, edge.line,
                          "<instance_node url=\"#" + edge.url + "\"> instances a node it is within");
        if (marks[edge.to] == Mark::done) continue;
        marks[edge.to] = Mark::open;
        path.emplace_back(edge.to, 0);
      }
    }
  }

  // A sampler's key times and values are numbers: assimp reads them from the numbers its accessor's
  // array holds, and asserted (aborting) on an accessor of a <Name_array>, which it keeps as names;
  // and a key of values into a 16-number buffer on its stack.
  void checkKeySources() const {
    for (const KeyInput& input : keyInputs_) {
      const auto accessors = accessorsOf_.find(input.source);
      if (accessors == accessorsOf_.end()) continue;  // assimp refuses a source it cannot find
      for (const std::size_t index : accessors->second) {
        const Accessor& a = accessors_[index];
        const auto kind = holdsNumbers_.find(a.source);
        if (kind != holdsNumbers_.end() && !kind->second)
          throw ClipError(name_, input.line,
                          "<input semantic=\"" + input.semantic + "\"> reads numbers from '" + a.source +
                              "', which holds names");
        if (input.semantic == "OUTPUT" && a.key > 16)
          throw ClipError(
              name_, a.line,
              "<accessor> of a key of " + std::to_string(a.key) + " numbers, more than a 4x4 matrix's 16");
      }
    }
  }

  // Each accessor reads its values within its array (assimp 5.2 asserts each index, and aborted on
  // one past the end: stride="4000000000").
  void checkAccessors() const {
    for (const Accessor& a : accessors_) {
      const auto array = arrays_.find(a.source);
      if (array == arrays_.end() || a.count == 0) continue;
      // Each term is at most 2^32 (countOf) and the product under 2^64, but the sum can pass 2^64.
      const std::uint64_t need = plus(plus(a.offset, a.stride * (a.count - 1)), std::max(a.stride, a.width));
      if (need > array->second)
        throw ClipError(name_, a.line,
                        "<accessor> of count=\"" + std::to_string(a.count) + "\" reads " +
                            std::to_string(need) + " values of '" + a.source + "', which holds " +
                            std::to_string(array->second));
    }
  }

 private:
  std::uint64_t countOf(const pugi::xml_node& node, const char* attribute, std::size_t line) const {
    const std::string_view value = node.attribute(attribute).value();
    const std::optional<std::uint64_t> n = wholeNumber(value);
    if (!n || *n > kMostValues)
      throw ClipError(name_, line,
                      "<" + std::string(node.name()) + "> " + attribute + "=\"" + std::string(value) +
                          "\" is not a whole number of values a file holds");
    return *n;
  }

  static bool isPrimitives(std::string_view element) {
    return element == "triangles" || element == "lines" || element == "polylist" || element == "polygons" ||
           element == "trifans" || element == "tristrips" || element == "linestrips";
  }

  // The indices a mesh's primitives hold: in their <p>s, and a polygon with holes' <p> and <h>s.
  // assimp reads an index where the last one stopped, and a word that is none (`Z`, `1.5`) stopped
  // it for good: it read zeros there until it had asked for gigabytes.
  std::uint64_t indicesIn(const pugi::xml_node& primitives, std::size_t line) const {
    std::uint64_t words = 0;
    const auto add = [&](const pugi::xml_node& list) {
      const char* text = list.child_value();
      if (const std::optional<std::string_view> word = notAnIndex(text))
        throw ClipError(name_, line,
                        "<" + std::string(primitives.name()) + "> <" + list.name() + "> holds '" +
                            std::string(*word) + "', which is not an index");
      words = plus(words, wordsIn(text));
    };
    for (const pugi::xml_node p : primitives.children("p")) add(p);
    for (const pugi::xml_node ph : primitives.children("ph")) {
      for (const pugi::xml_node part : ph.children()) {
        const std::string_view name = part.name();
        if (name == "p" || name == "h") add(part);
      }
    }
    return words;
  }

  // The indices a vertex takes: one for each offset its <input>s use.
  std::uint64_t offsetsOf(const pugi::xml_node& node, std::size_t line) const {
    std::uint64_t offsets = 1;
    for (const pugi::xml_node input : node.children("input"))
      if (input.attribute("offset")) offsets = std::max(offsets, plus(countOf(input, "offset", line), 1));
    return offsets;
  }

  // A mesh's primitives hold the indices their count says (three a triangle, two a line, a
  // <vcount> each in a polylist, at least one a polygon, fan or strip) for each offset their inputs
  // use: assimp reserves that many before it reads any, and count="1000000000" of triangles asked
  // for 24 GB, an <input offset="100000000"> for 2.4 GB.
  void checkIndices(const pugi::xml_node& node, std::size_t line) const {
    const std::string_view element = node.name();
    const std::uint64_t count = countOf(node, "count", line);
    std::uint64_t points = count;
    if (element == "triangles") points = times(count, 3);
    if (element == "lines") points = times(count, 2);
    if (element == "polylist") points = sumOf(node.child("vcount").child_value());
    const std::uint64_t need = times(std::max(points, count), offsetsOf(node, line));
    const std::uint64_t held = indicesIn(node, line);
    if (held < need)
      throw ClipError(name_, line,
                      "<" + std::string(element) + "> of count=\"" + std::to_string(count) + "\" needs " +
                          std::to_string(need) + " indices, but holds " + std::to_string(held));
  }

  // A skin's weights: a <vcount> for each of its count vertices, and in <v> an index for each
  // offset of each weight those give. assimp sizes both before it reads them.
  void checkWeights(const pugi::xml_node& node, std::size_t line) const {
    const std::uint64_t count = countOf(node, "count", line);
    const char* vcount = node.child("vcount").child_value();
    const std::uint64_t counts = wordsIn(vcount);
    const std::uint64_t need = times(sumOf(vcount), offsetsOf(node, line));
    const std::uint64_t held = wordsIn(node.child("v").child_value());
    if (counts < count || held < need)
      throw ClipError(name_, line,
                      "<vertex_weights> of count=\"" + std::to_string(count) + "\" needs " +
                          std::to_string(count) + " counts and " + std::to_string(need) +
                          " indices, but holds " + std::to_string(counts) + " and " + std::to_string(held));
  }

  LineCounter lines_;  // elements come in the file's order
  const std::string& name_;
  std::map<std::string, std::uint64_t, std::less<>> arrays_;
  std::map<std::string, bool, std::less<>> holdsNumbers_;  // assimp's arrays: float_array, or names
  std::vector<Accessor> accessors_;
  std::map<std::string, std::vector<std::size_t>, std::less<>> accessorsOf_;  // by <source> id
  struct KeyInput {
    std::size_t line;
    std::string semantic, source;
  };
  std::vector<KeyInput> keyInputs_;  // samplers' INPUT and OUTPUT

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  // What a node holds (its child nodes, line 0) or instances (the <instance_node>'s line and url).
  struct Edge {
    std::size_t to, line;
    std::string url;
  };
  struct Node {
    std::size_t line, parent;
    std::vector<Edge> edges;
  };
  struct Instance {
    std::size_t line, in;
    std::string url;
  };

  // The <node> that `element` is in (its index), or kNone.
  std::size_t enclosingNode(const pugi::xml_node& element) const {
    for (pugi::xml_node up = element.parent(); up; up = up.parent()) {
      if (std::string_view(up.name()) != "node") continue;
      const auto found = nodeIndex_.find(up.internal_object());
      return found == nodeIndex_.end() ? kNone : found->second;
    }
    return kNone;
  }

  std::vector<Node> nodes_;
  std::unordered_map<const void*, std::size_t> nodeIndex_;
  std::map<std::string, std::vector<std::size_t>, std::less<>> nodesNamed_;
  std::vector<Instance> instances_;
};

// ---- FBX and .x as text ----

std::optional<std::int64_t> integer(std::string_view word) {
  std::int64_t n = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), n);
  if (word.empty() || end != word.data() + word.size() || error != std::errc()) return std::nullopt;
  return n;
}

// An FBX array's values after its `*N`: `{ a: v,v,... }`, counted, and read into `integers` if given
// (emptied if one is not an integer); nullopt if it is not one.
std::optional<std::uint64_t> fbxArrayValues(Tokens& tokens, std::vector<std::int64_t>* integers) {
  if (tokens.next() != "{" || tokens.next() != "a:") return std::nullopt;
  std::uint64_t values = 0;
  bool allIntegers = true;
  for (std::string_view word = tokens.next(); !word.empty() && word != "}"; word = tokens.next()) {
    if (word == ",") continue;
    ++values;
    if (integers == nullptr || !allIntegers) continue;
    const std::optional<std::int64_t> n = integer(word);
    allIntegers = n.has_value();
    if (n) integers->push_back(*n);
  }
  if (integers != nullptr && !allIntegers) integers->clear();
  return values;
}

std::string_view unquoted(std::string_view word) {
  if (word.size() >= 2 && word.front() == '"' && word.back() == '"') return word.substr(1, word.size() - 2);
  return word;
}

// A text FBX's model property (`P: "name", "type", ...` under Objects, Model, Properties70) that
// assimp cannot take, refused at `line`.
void checkFbxModelProperty(const std::vector<std::string_view>& path, std::string_view key, std::size_t line,
                           const std::vector<std::string_view>& values, const std::string& name) {
  if (key != "P:" || values.size() < 2 || path.size() != 3 || path[0] != "Objects:" || path[1] != "Model:" ||
      path[2] != "Properties70:")
    return;
  if (const std::string why = modelPropertyProblem(unquoted(values[0]), unquoted(values[1])); !why.empty())
    throw ClipError(name, line, why);
}

// A text FBX's models and connections, for FbxCurves: `Model: id, "Model::name", ...` under
// Objects, `C: "OO", source, target` and `C: "OP", source, target, "property"` under Connections,
// the key at `line`.
void gatherFbxLink(const std::vector<std::string_view>& path, std::string_view key, std::size_t line,
                   const std::vector<std::string_view>& values, FbxCurves& curves) {
  if (path.size() != 1) return;
  if (path[0] == "Objects:" && key == "Model:" && values.size() >= 2) {
    std::string_view model = unquoted(values[1]);
    if (model.starts_with("Model::")) model.remove_prefix(7);
    if (const std::optional<std::int64_t> id = integer(values[0])) curves.model(*id, std::string(model));
  } else if (path[0] == "Connections:" && key == "C:" && values.size() >= 3) {
    const std::optional<std::int64_t> source = integer(values[1]), target = integer(values[2]);
    const std::string property = values.size() >= 4 ? std::string(unquoted(values[3])) : "";
    if (source && target) curves.link(*source, *target, property, line, 0);
  }
}

}  // namespace

std::string modelPropertyProblem(std::string_view property, std::string_view type) {
  if (type != "KTime" && type != "ColorAndAlpha") return "";
  return "the model property \"" + std::string(property) + "\" of type " + std::string(type) +
         ": assimp 5.2 stops the program on a model's property of this type";
}

std::optional<std::uint64_t> wholeNumber(std::string_view word) {
  std::uint64_t n = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), n);
  if (word.empty() || end != word.data() + word.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) return std::numeric_limits<std::uint64_t>::max();
  if (error != std::errc()) return std::nullopt;
  return n;
}

void checkGltf(std::string_view json, const std::string& name) {
  checkNodes(scanGltfJson(json, name, ""), name);
}

void checkGlb(std::string_view content, const std::string& name) {
  // The header is magic, version and length, then chunks of (length, type, bytes), the first the
  // JSON, each padded to 4 bytes. assimp allocates every length before it reads the bytes: a JSON
  // chunk said to be 1.7 GB was.
  constexpr std::size_t kHeader = 12, kChunkHeader = 8;
  if (content.size() < kHeader || !content.starts_with("glTF"))
    return;  // assimp's reader says what it is not
  const auto word = [&](std::size_t at) { return readLittle(content, at, 4); };
  if (word(4) == 1) throw ClipError(name, "a glTF 1.0 file: clips are read from glTF 2.0");
  if (const std::uint64_t length = word(8); length > content.size())
    throw ClipError(name, "its header says the file has " + std::to_string(length) + " bytes, but it has " +
                              std::to_string(content.size()));
  std::string_view json;
  for (std::uint64_t at = kHeader; at + kChunkHeader <= content.size();) {
    const std::uint64_t length = word(at), start = at + kChunkHeader;
    if (length > content.size() - start)
      throw ClipError(name, "the chunk at byte " + std::to_string(at) + " says it has " +
                                std::to_string(length) + " bytes, past the file's end (" +
                                std::to_string(content.size()) + " bytes)");
    if (at == kHeader && content.substr(at + 4, 4) == "JSON") json = content.substr(start, length);
    at = (start + length + 3) / 4 * 4;
  }
  checkNodes(scanGltfJson(json, name, "its JSON chunk, "), name);
}

void checkCollada(std::string_view content, const std::string& name) {
  pugi::xml_document document;
  if (!document.load_buffer(content.data(), content.size())) return;  // assimp's reader says why
  ColladaWalker walker(content, name);
  document.traverse(walker);
  walker.checkAccessors();
  walker.checkKeySources();
  walker.checkNodeInstances();
}

void checkFbx(std::string_view content, const std::string& name) {
  if (content.starts_with("Kaydara FBX Binary")) {
    checkBinaryFbx(content, name);
    return;
  }
  Tokens tokens(content, kFbxText);
  std::vector<std::string_view> path;  // the key before each open brace
  std::string_view key;
  std::size_t keyLine = 0;
  std::vector<std::string_view> values;  // the words after `key`, up to a brace or the next key
  FbxCurves curves;
  std::int64_t curve = 0;  // the AnimationCurve the braces are in, if path is {Objects:, AnimationCurve:}
  for (std::string_view word = tokens.next(); !word.empty(); word = tokens.next()) {
    if (word == "{") {
      gatherFbxLink(path, key, keyLine, values, curves);
      checkFbxModelProperty(path, key, keyLine, values, name);
      if (path.size() == 1 && path[0] == "Objects:" && key == "AnimationCurve:" && !values.empty())
        curve = integer(values[0]).value_or(0);
      path.push_back(key);
      values.clear();
      if (path.size() > static_cast<std::size_t>(kMaxDepth))
        throw ClipError(name, tokens.line(), tooDeep("braces"));
    } else if (word == "}") {
      gatherFbxLink(path, key, keyLine, values, curves);
      checkFbxModelProperty(path, key, keyLine, values, name);
      if (!path.empty()) path.pop_back();
      key = {};
      values.clear();
    } else if (word.starts_with('*')) {
      // assimp allocates the N values of `*N` before it reads them: *4000000000 asked for 16 GB.
      const std::size_t line = tokens.line();
      const std::optional<std::uint64_t> count = wholeNumber(word.substr(1));
      if (!count)
        throw ClipError(name, line,
                        std::string(key) + " " + std::string(word) + ": not a whole number of values");
      const bool times =
          key == "KeyTime:" && path.size() == 2 && path[0] == "Objects:" && path[1] == "AnimationCurve:";
      std::vector<std::int64_t> integers;
      const std::optional<std::uint64_t> held = fbxArrayValues(tokens, times ? &integers : nullptr);
      if (!held) continue;  // not an array: left for assimp's reader
      if (*held < *count)
        throw ClipError(
            name, line,
            std::string(key) + " " + std::string(word) + " holds " + std::to_string(*held) + " values");
      // A curve of no times and no values made assimp 5.2 read through a null pointer.
      if (*count == 0 && (key == "KeyTime:" || key == "KeyValueFloat:"))
        throw ClipError(name, line, std::string(key) + " *0: an animation curve of no keys");
      if (times) curves.keyTimes(curve, integers, line, "");
    } else if (word.ends_with(':') && !word.starts_with('"')) {
      gatherFbxLink(path, key, keyLine, values, curves);
      checkFbxModelProperty(path, key, keyLine, values, name);
      key = word;
      keyLine = tokens.line();
      values.clear();
    } else if (word != ",") {
      values.push_back(word);
    }
  }
  curves.check(name);
}

void checkX(std::string_view content, const std::string& name) {
  if (content.size() < 16 || !content.starts_with("xof ")) return;  // assimp's reader says what it is not
  // assimp's binary reader takes counts and lengths on trust as the text one does, and a compressed
  // file (tzip, bzip) is checked by nothing before it is inflated; exporters write .x as text.
  if (const std::string_view form = content.substr(8, 4); form != "txt ")
    throw ClipError(name, 1,
                    "a " +
                        std::string(form == "tzip"   ? "compressed"
                                    : form == "bin " ? "binary"
                                                     : "compressed binary") +
                        " .x file ('" + std::string(content.substr(0, 12)) +
                        "'): clips are read from .x files as text ('xof 0303txt 0032') alone");
  Tokens tokens(content.substr(kXHeader), kXText);
  int depth = 0;
  std::string_view first;  // the first word of the block's header: its template's name
  bool header = true;
  const auto line = [&] { return tokens.line() + lineAt(content, kXHeader) - 1; };
  for (std::string_view word = tokens.next(); !word.empty(); word = tokens.next()) {
    if (word == "{") {
      if (++depth > kMaxDepth) throw ClipError(name, line(), tooDeep("braces"));
      // A mesh's first number is a count of what follows, and assimp allocates them all before
      // reading one: 4000000000 vertices asked for 48 GB.
      if (first == "Mesh" || first == "MeshNormals" || first == "MeshTextureCoords" ||
          first == "MeshVertexColors" || first == "MeshMaterialList") {
        const std::string_view count = tokens.next();
        const std::optional<std::uint64_t> n = wholeNumber(count);
        if (n && *n > tokens.left())
          throw ClipError(name, line(),
                          std::string(first) + " of " + std::string(count) + ", more than the " +
                              std::to_string(tokens.left()) + " bytes after it hold");
      }
      // assimp reads a tick rate of 0 as one the file does not give, and the clip would play at
      // its default of 25; a negative one it wraps to more than 4 billion.
      if (first == "AnimTicksPerSecond") {
        const std::string_view rate = tokens.next();
        const std::optional<std::uint64_t> n = wholeNumber(rate);
        if (!n || *n == 0 || *n > std::numeric_limits<std::uint32_t>::max())
          throw ClipError(name, line(),
                          "AnimTicksPerSecond " + std::string(rate) +
                              ": the ticks a second are not a whole number from 1 to 4294967295");
      }
      header = true;
      first = {};
    } else if (word == "}" || word == ";" || word == ",") {
      if (word == "}") --depth;
      header = true;
      first = {};
    } else if (header) {
      first = word;
      header = false;
    }
  }
}

}  // namespace clips::detail
