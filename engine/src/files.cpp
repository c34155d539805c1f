#include "files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <string>
#include <system_error>

#include "engine/error.h"

namespace engine::detail {
namespace {

namespace fs = std::filesystem;

std::string reason(int error) {
  return std::generic_category().message(error);
}

[[noreturn]] void fail(const fs::path& file, std::string_view what) {
  throw Error((file.empty() ? std::string("(no file name)") : file.string()) + ": " + std::string(what));
}

// A file descriptor, closed as it goes out of scope (also when the constructor of the OpenFile
// holding it throws).
struct Descriptor {
  int fd = -1;
  Descriptor() = default;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// A file open for reading, with what fstat says of it.
class OpenFile {
 public:
  // Opened without blocking: a named pipe with no writer would hold open() for ever. Reads
  // block again, so a pipe that has a writer is read whole.
  OpenFile(const fs::path& file, std::string_view kind) : file_(file), kind_(kind) {
    if (file.empty()) fail(file, "no " + kind_ + " name given");
    descriptor_.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (descriptor_.fd < 0) failWithErrno("cannot open");
    const int flags = ::fcntl(descriptor_.fd, F_GETFL);
    if (flags < 0 || ::fcntl(descriptor_.fd, F_SETFL, flags & ~O_NONBLOCK) != 0) failWithErrno("cannot read");
    if (::fstat(descriptor_.fd, &info_) != 0) failWithErrno("cannot read");
    if (S_ISDIR(info_.st_mode)) fail(file, "is a folder, not a " + kind_);
  }

  int fd() const { return descriptor_.fd; }
  const struct stat& info() const { return info_; }
  const std::string& kind() const { return kind_; }

  // "FILE: cannot open shader file: the OS's reason". `what` is a literal, so nothing allocates
  // (and may change errno) before errno is read.
  [[noreturn]] void failWithErrno(const char* what) const {
    const int error = errno;
    fail(file_, std::string(what) + " " + kind_ + ": " + reason(error));
  }

 private:
  fs::path file_;
  std::string kind_;
  Descriptor descriptor_;
  struct stat info_ {};
};

}  // namespace

void checkRegularFile(const fs::path& file, std::string_view kind) {
  const OpenFile open(file, kind);
  if (!S_ISREG(open.info().st_mode)) {
    fail(file, "is not a regular file (a device, pipe or socket), so it is not read as a " + open.kind());
  }
}

std::string readWhole(const fs::path& file, std::size_t maxBytes, std::string_view kind) {
  const OpenFile open(file, kind);
  std::string content;
  if (S_ISREG(open.info().st_mode) && static_cast<std::uintmax_t>(open.info().st_size) <= maxBytes) {
    content.reserve(static_cast<std::size_t>(open.info().st_size));
  }
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(open.fd(), buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) open.failWithErrno("cannot read");
    if (n == 0) return content;
    if (content.size() + static_cast<std::size_t>(n) > maxBytes) {
      fail(file,
           "is larger than " + std::to_string(maxBytes) + " bytes, the most a " + open.kind() + " may hold");
    }
    content.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace engine::detail
