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

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

/// A .x file's header ("xof 0303txt 0032"), and what begins its comments: assimp's reader takes
/// both "//" and "#" (a "#" the checks read as a word let a count after it through).
constexpr std::size_t kXHeader = 16;
inline const std::vector<std::string_view> kXComments = {"//", "#"};

/// A text's tokens: words, strings and braces, each with its offset; a comment begins with one of
/// `comments` where a token would and runs to the end of its line.
class Tokens {
 public:
  Tokens(std::string_view text, std::vector<std::string_view> comments)
      : text_(text), comments_(std::move(comments)) {}

  std::string_view next() {
    for (;;) {
      while (at_ < text_.size() && isSpace(text_[at_])) ++at_;
      if (at_ >= text_.size()) return {};
      const std::string_view rest = text_.substr(at_);
      if (std::none_of(comments_.begin(), comments_.end(),
                       [&](std::string_view comment) { return rest.starts_with(comment); }))
        break;
      while (at_ < text_.size() && text_[at_] != '\n') ++at_;
    }
    start_ = at_;
    if (text_[at_] == '"') {
      const std::size_t close = text_.find('"', at_ + 1);
      at_ = close == std::string_view::npos ? text_.size() : close + 1;
    } else if (std::strchr("{},;", text_[at_]) != nullptr) {
      ++at_;
    } else {
      while (at_ < text_.size() && !isSpace(text_[at_]) && std::strchr("{},;\"", text_[at_]) == nullptr)
        ++at_;
    }
    return text_.substr(start_, at_ - start_);
  }
  /// The line of the token last read, where it starts and ends, and the bytes after it.
  std::size_t line() const { return lineAt(text_, start_); }
  std::size_t start() const { return start_; }
  std::size_t end() const { return at_; }
  std::size_t left() const { return text_.size() - at_; }

 private:
  std::string_view text_;
  std::vector<std::string_view> comments_;
  std::size_t at_ = 0;
  std::size_t start_ = 0;
};

}  // namespace clips::detail
