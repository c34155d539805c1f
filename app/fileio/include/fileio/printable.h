#pragma once
// What a file holds, made fit to quote in a message: a reason that names a token, a number or a
// name from a file (a clip's, a scene's) is shown in the sandbox's status bar and printed by the
// lab, and a file of one long line or of binary bytes can hold megabytes of anything there.
#include <cstddef>
#include <string>
#include <string_view>

namespace fileio {

/// A control byte: below 0x20, or 0x7f (DEL). What printableReason writes \xNN, and what has no
/// place in a line of a script or in a file name (the lab's charts).
constexpr bool isControl(unsigned char byte) {
  return byte < 0x20 || byte == 0x7f;
}

/// The most bytes of a reason printableReason keeps unless told otherwise.
inline constexpr std::size_t kMostReasonBytes = 400;

/// `why` without its trailing white space, cut after `mostBytes` bytes between UTF-8 characters
/// with "... (N more bytes)", and each control byte (below 0x20, and 0x7f) written \xNN, so that
/// it fits a log line or a status bar and cannot drive a terminal.
std::string printableReason(std::string_view why, std::size_t mostBytes = kMostReasonBytes);

}  // namespace fileio
