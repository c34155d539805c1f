#include "fileio/printable.h"

#include <cctype>

namespace fileio {
namespace {

// A byte that starts a UTF-8 character (not one of its continuation bytes 10xxxxxx): a cut
// before it leaves whole characters.
bool startsCharacter(unsigned char byte) {
  return (byte & 0xc0) != 0x80;
}

void appendHex(std::string& out, unsigned char byte) {
  static constexpr std::string_view kHex = "0123456789abcdef";
  out += "\\x";
  out += kHex[byte >> 4];
  out += kHex[byte & 15];
}

}  // namespace

std::string printableReason(std::string_view why, std::size_t mostBytes) {
  while (!why.empty() && std::isspace(static_cast<unsigned char>(why.back()))) why.remove_suffix(1);
  std::string out;
  for (std::size_t i = 0; i < why.size(); ++i) {
    const auto byte = static_cast<unsigned char>(why[i]);
    if (out.size() >= mostBytes && startsCharacter(byte)) {
      out += "... (" + std::to_string(why.size() - i) + " more bytes)";
      break;
    }
    if (isControl(byte))
      appendHex(out, byte);
    else
      out += static_cast<char>(byte);
  }
  return out;
}

}  // namespace fileio
