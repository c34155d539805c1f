// lab: the headless physics runner (docs/lab.md). Everything but argument plumbing is in
// lab_core, where the tests can reach it.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <streambuf>
#include <string>
#include <vector>

#include "lab.h"

namespace {

// The standard output, written with write(2) so that the first failure's reason is kept: through
// std::cout and stdio a write that failed is known to have failed, but by the time anyone asks
// its errno is gone. Line by line to a terminal, as stdio would, so that a command's rows show as
// they come; in blocks to a file or a pipe.
class StdoutBuffer : public std::streambuf {
 public:
  /// Writes what is left: 0 when everything written got there, else the errno of the first
  /// write that failed.
  int finish() {
    sync();
    return error_;
  }

 protected:
  // Without a put area every character comes here (streambuf's xsputn calls it for each one).
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    pending_ += traits_type::to_char_type(c);
    const bool line = lineByLine_ && traits_type::to_char_type(c) == '\n';
    return (line || pending_.size() >= kBlock) && !flush() ? traits_type::eof() : c;
  }
  int sync() override { return flush() ? 0 : -1; }

 private:
  static constexpr std::size_t kBlock = 1 << 14;

  bool flush() {
    std::size_t done = 0;
    while (error_ == 0 && done < pending_.size()) {
      const ssize_t n = ::write(STDOUT_FILENO, pending_.data() + done, pending_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        error_ = n < 0 ? errno : EIO;
      else
        done += static_cast<std::size_t>(n);
    }
    pending_.clear();
    return error_ == 0;
  }

  std::string pending_;
  bool lineByLine_ = ::isatty(STDOUT_FILENO) == 1;
  int error_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  StdoutBuffer buffer;
  std::ostream out(&buffer);
  const int code = lab::labMain(args, out, std::cerr);
  // A report that did not get there (a full disk, /dev/full) is a failure: `lab run x --json >
  // r.json` must not end in success with the file empty.
  if (const int error = buffer.finish(); error != 0) {
    std::cerr << "lab: the output could not be written: " << std::strerror(error) << "\n";
    return code == lab::kExitOk ? lab::kExitFailure : code;
  }
  return code;
}
