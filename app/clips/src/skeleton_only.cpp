// What assimp is given of a COLLADA or .x clip (skeleton_only.h).
#include "skeleton_only.h"

#include <algorithm>
#include <iterator>
#include <sstream>
#include <vector>

#include <pugixml.hpp>

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

}  // namespace

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
  Tokens tokens(content.substr(kXHeader), kXComments);
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
