#pragma once
// The words of a text format (FBX and .x as text), shared by the checks and the skeleton-only copy
// so that both read a file as assimp's reader does.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <string_view>
#include <utility>
#include <vector>

namespace clips::detail {

/// The line (from 1) of byte `offset` of `text`.
inline std::size_t lineAt(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<std::size_t>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

/// Lines of a text, counted on from the offset last asked for: linear in the text over offsets that
/// rise, as a reader's do (counting from the start each time made a text FBX of 20,000 models take
/// minutes).
class LineCounter {
 public:
  explicit LineCounter(std::string_view text) : text_(text) {}
  std::size_t lineOf(std::size_t offset) {
    offset = std::min(offset, text_.size());
    if (offset < at_) {
      at_ = 0;
      line_ = 1;
    }
    line_ += static_cast<std::size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(at_),
                                                 text_.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
    at_ = offset;
    return line_;
  }

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
};

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// How a text format's words are read, as assimp's reader of that format reads them: a check or a
/// copy that read them otherwise could be walked around (an FBX "Geometry:1," read as one word hid
/// the key from both; a .x quote read as a string hid a Mesh after it).
struct TextSyntax {
  std::vector<std::string_view> comments;  // each begins a comment where a token would, to the line's end
  bool strings;  // "..." is one token, whatever it holds; otherwise a quote is a character like others
  bool keys;     // a ':' ends its word ("Geometry:1" is the key "Geometry:" and the word "1")
};

/// FBX as text: ';' comments, quoted strings, keys ending at their colon.
inline const TextSyntax kFbxText{{";"}, true, true};
/// DirectX .x as text after its header ("xof 0303txt 0032"): "//" and "#" comments; assimp reads a
/// string as a word like any other.
inline const TextSyntax kXText{{"//", "#"}, false, false};
constexpr std::size_t kXHeader = 16;

/// A text's tokens: words, strings and braces, each with its offset, read as `syntax` says.
class Tokens {
 public:
  Tokens(std::string_view text, const TextSyntax& syntax) : text_(text), syntax_(syntax), lines_(text) {}

  std::string_view next() {
    for (;;) {
      while (at_ < text_.size() && isSpace(text_[at_])) ++at_;
      if (at_ >= text_.size()) return {};
      const std::string_view rest = text_.substr(at_);
      if (std::none_of(syntax_.comments.begin(), syntax_.comments.end(),
                       [&](std::string_view comment) { return rest.starts_with(comment); }))
        break;
      while (at_ < text_.size() && text_[at_] != '\n') ++at_;
    }
    start_ = at_;
    if (syntax_.strings && text_[at_] == '"') {
      const std::size_t close = text_.find('"', at_ + 1);
      at_ = close == std::string_view::npos ? text_.size() : close + 1;
    } else if (std::strchr("{},;", text_[at_]) != nullptr) {
      ++at_;
    } else {
      while (at_ < text_.size() && !isSpace(text_[at_]) && std::strchr("{},;", text_[at_]) == nullptr &&
             !(syntax_.strings && text_[at_] == '"')) {
        if (text_[at_++] == ':' && syntax_.keys) break;
      }
    }
    return text_.substr(start_, at_ - start_);
  }
  /// The line of the token last read, where it starts and ends, and the bytes after it.
  std::size_t line() { return lines_.lineOf(start_); }
  std::size_t start() const { return start_; }
  std::size_t end() const { return at_; }
  std::size_t left() const { return text_.size() - at_; }

 private:
  std::string_view text_;
  const TextSyntax& syntax_;
  LineCounter lines_;
  std::size_t at_ = 0;
  std::size_t start_ = 0;
};

}  // namespace clips::detail
