// What assimp is given of a COLLADA or .x clip (skeleton_only.h).
#include "skeleton_only.h"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <sstream>
#include <vector>

#include <pugixml.hpp>

#include "format_checks.h"
#include "text_tokens.h"

namespace clips::detail {
namespace {

// COLLADA elements a clip does not read, with all they hold: each library of them, and each
// instance of one in a node. Probing assimp found a skin's joint index of 50,000,000 written
// unchecked and a weight index read past its array; a mesh's counts are sized before they are read.
constexpr std::string_view kUnreadCollada[] = {
    "library_geometries",  "library_controllers", "library_materials", "library_effects",
    "library_images",      "library_cameras",     "library_lights",    "instance_geometry",
    "instance_controller", "instance_camera",     "instance_light"};

bool unreadCollada(const pugi::xml_node& node) {
  return node.type() == pugi::node_element &&
         std::find(std::begin(kUnreadCollada), std::end(kUnreadCollada), std::string_view(node.name())) !=
             std::end(kUnreadCollada);
}

// An FBX object type assimp knows no class for, of the length of "Geometry": an object renamed to it
// is read as a record and never made a mesh.
constexpr std::string_view kFbxUnread = "Unread__";

// Where each "Geometry" record under "Objects" names itself in a binary FBX (checkBinaryFbx has
// checked that every record lies within its parent and the file). The header is 27 bytes; a record
// is its end, its count of properties and their length (4 bytes each before version 7500, 8 after),
// its name's length in a byte, its name, its properties, then its children.
std::vector<std::size_t> binaryFbxGeometries(std::string_view bytes) {
  constexpr std::size_t kFirstRecord = 27;
  std::vector<std::size_t> names;
  if (bytes.size() < kFirstRecord) return names;
  const std::size_t word = readLittle(bytes, 23, 4) >= 7500 ? 8 : 4;
  const std::size_t header = 3 * word + 1;
  // The records from `at` to `limit`, each given to `visit` with where its name starts, its name,
  // where its children start and where it ends; the walk stops at one that does not lie within them.
  const auto walk = [&](std::uint64_t at, std::uint64_t limit, const auto& visit) {
    while (limit >= header && at <= limit - header) {
      const std::uint64_t end = readLittle(bytes, at, word);
      const std::uint64_t length = static_cast<unsigned char>(bytes[at + 3 * word]);
      if (end == 0 || end <= at || end > limit || at + header + length > end) return;
      const std::uint64_t children = at + header + length + readLittle(bytes, at + 2 * word, word);
      visit(at + header, bytes.substr(at + header, length), std::min(children, end), end);
      at = end;
    }
  };
  walk(kFirstRecord, bytes.size(),
       [&](std::uint64_t, std::string_view name, std::uint64_t from, std::uint64_t end) {
         if (name != "Objects") return;
         walk(from, end, [&](std::uint64_t nameAt, std::string_view child, std::uint64_t, std::uint64_t) {
           if (child == "Geometry") names.push_back(nameAt);
         });
       });
  return names;
}

// Where each "Geometry:" key under "Objects:" starts in a text FBX.
std::vector<std::size_t> textFbxGeometries(std::string_view text) {
  std::vector<std::size_t> names;
  Tokens tokens(text, kFbxText);
  std::string_view key;  // the last key read
  int depth = 0;
  bool inObjects = false;
  for (std::string_view word = tokens.next(); !word.empty(); word = tokens.next()) {
    if (word == "{") {
      if (depth++ == 0) inObjects = key == "Objects:";
    } else if (word == "}") {
      depth = std::max(depth - 1, 0);
    } else if (word.ends_with(':') && !word.starts_with('"')) {
      key = word;
      if (depth == 1 && inObjects && word == "Geometry:") names.push_back(tokens.start());
    }
  }
  return names;
}

}  // namespace

std::optional<std::string> fbxSkeletonOnly(std::string_view content, const std::string& /*name*/) {
  // A mesh's layers (normals, texture coordinates, colours) index tables the reader sized by another
  // count: a layer of texture coordinates indexed per control point with more indices than control
  // points was read past its table. Every Geometry object is renamed, in place so that a binary
  // file's offsets hold, to a type assimp does not read.
  const bool binary = content.starts_with("Kaydara FBX Binary");
  const std::vector<std::size_t> names = binary ? binaryFbxGeometries(content) : textFbxGeometries(content);
  if (names.empty()) return std::nullopt;
  std::string out(content);
  for (const std::size_t at : names) out.replace(at, kFbxUnread.size(), kFbxUnread);
  return out;
}

std::optional<std::string> colladaSkeletonOnly(std::string_view content, const std::string& /*name*/) {
  pugi::xml_document document;
  if (!document.load_buffer(content.data(), content.size())) return std::nullopt;  // assimp says why
  // Found first, then taken out: a node taken out frees what it holds. checkCollada has bounded the
  // nesting, and nothing under an unread element is visited.
  std::vector<pugi::xml_node> unread;
  std::vector<pugi::xml_node> open{document};
  while (!open.empty()) {
    const pugi::xml_node node = open.back();
    open.pop_back();
    for (pugi::xml_node child : node.children()) {
      if (unreadCollada(child))
        unread.push_back(child);
      else
        open.push_back(child);
    }
  }
  if (unread.empty()) return std::nullopt;
  for (pugi::xml_node node : unread) node.parent().remove_child(node);
  // As UTF-8 with no declaration, which is what pugixml made of the file's encoding.
  std::ostringstream out;
  document.save(out, "", pugi::format_raw | pugi::format_no_declaration, pugi::encoding_utf8);
  return out.str();
}

std::optional<std::string> xSkeletonOnly(std::string_view content, const std::string& /*name*/) {
  if (content.size() < kXHeader) return std::nullopt;  // assimp's reader says what it is not
  // Every Mesh block, with what it holds (its normals, materials and skin weights), is made spaces:
  // probing assimp found a face count allocated before the faces, a skin weight's vertex index and
  // a normal's face index written and read unchecked, a face's material read from an empty list.
  // Its lines stay, so that assimp's errors name the lines of the file. checkX has bounded the
  // nesting; a "template Mesh" declares the type and is kept.
  std::string out(content);
  const auto blank = [&](std::size_t from, std::size_t to) {
    std::replace_if(
        out.begin() + static_cast<std::ptrdiff_t>(kXHeader + from),
        out.begin() + static_cast<std::ptrdiff_t>(kXHeader + to), [](char c) { return c != '\n'; }, ' ');
  };
  Tokens tokens(content.substr(kXHeader), kXText);
  std::string_view first;  // the first word of the block's header: its template's name
  std::size_t firstAt = 0;
  bool header = true;
  int depth = 0;
  int meshDepth = 0;  // the depth inside the Mesh being blanked, 0 if none
  std::size_t meshAt = 0;
  for (std::string_view word = tokens.next(); !word.empty(); word = tokens.next()) {
    if (word == "{") {
      ++depth;
      if (meshDepth == 0 && first == "Mesh") {
        meshDepth = depth;
        meshAt = firstAt;
      }
    } else if (word == "}") {
      if (depth == meshDepth) {
        blank(meshAt, tokens.end());
        meshDepth = 0;
      }
      --depth;
    } else if (word != ";" && word != ",") {
      if (header) {
        first = word;
        firstAt = tokens.start();
        header = false;
      }
      continue;
    }
    header = true;
    first = {};
  }
  if (meshDepth > 0) blank(meshAt, content.size() - kXHeader);  // never closed: assimp refuses the rest
  if (out == content) return std::nullopt;
  return out;
}

}  // namespace clips::detail
