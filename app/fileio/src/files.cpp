#include "fileio/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <memory>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace fileio {
namespace {

namespace fs = std::filesystem;

std::string reason(int error) {
  return std::generic_category().message(error);
}

fs::path folderOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

// Linux follows at most 40 links in one path (path_resolution(7)); so do we, then say ELOOP.
constexpr int kMaxLinks = 40;

// The new content, in a file of its own until it is renamed into place. Its name is unique and
// it is created with O_EXCL, as mkstemp does; unlike mkstemp it asks for mode 0666, so a new
// file ends with the permissions the umask gives any other new file (mkstemp forces 0600).
// O_EXCL also never opens through an existing file or symbolic link of that name.
class TemporaryFile {
 public:
  TemporaryFile(const fs::path& target, const fs::path& reported) : reported_(reported) {
    const fs::path folder = folderOf(target);
    // Hidden, and short enough to stay under NAME_MAX (255 bytes) whatever the target's length.
    const std::string base = target.filename().string().substr(0, 200);
    static thread_local std::mt19937_64 random{std::random_device{}()};
    static constexpr char kLetters[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
    int error = 0;
    for (int attempt = 0; attempt < 100; ++attempt) {
      std::string name(".");
      name.append(base).append(".");
      for (int i = 0; i < 8; ++i) name.push_back(kLetters[random() % (sizeof kLetters - 1)]);
      name.append(".tmp");
      path_ = folder / name;
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
      if (fd_ >= 0) return;
      error = errno;
      if (error != EEXIST) break;
    }
    throw FileError(reported_,
                    "cannot create a temporary file in '" + folder.string() + "': " + reason(error));
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!renamed_) ::unlink(path_.c_str());
  }

  void write(std::string_view content) {
    while (!content.empty()) {
      const ssize_t n = ::write(fd_, content.data(), content.size());
      const int error = errno;  // read before building a message, which may allocate
      if (n < 0 && error == EINTR) continue;
      if (n < 0) fail("cannot write", error);
      // A short write is retried with the rest: the next call reports why (ENOSPC, EFBIG).
      content.remove_prefix(static_cast<std::size_t>(n));
    }
  }

  void copyPermissionsOf(const fs::path& file) {
    struct stat existing {};
    if (::stat(file.c_str(), &existing) != 0) return;  // a new file keeps 0666 less the umask
    if (::fchmod(fd_, existing.st_mode & 07777) != 0) fail("cannot set the permissions", errno);
  }

  // Flushed before the rename: otherwise a crash soon after could leave the new name pointing
  // at a file whose data never reached the disk. Some file systems only report a full disk
  // here or at close, which is why both are checked.
  void flushAndClose() {
    if (::fsync(fd_) != 0) fail("cannot flush the new content to disk", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot close the new file", errno);
  }

  void renameTo(const fs::path& target) {
    if (::rename(path_.c_str(), target.c_str()) != 0) fail("cannot replace it with the new file", errno);
    renamed_ = true;
  }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const {
    throw FileError(reported_, what + ": " + reason(error));
  }

  fs::path reported_;
  fs::path path_;
  int fd_ = -1;
  bool renamed_ = false;
};

// Makes the rename itself durable; a folder that cannot be opened or synced (some file systems
// refuse) costs only that guarantee, so failures here are not errors.
void flushFolder(const fs::path& target) {
  const int fd = ::open(folderOf(target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

// A rename replaces whatever has the target's name: refuse what must not be replaced by a
// regular file (a folder is refused by rename too, but only after the whole content is written;
// a device or a pipe would not be, and as root `--dump /dev/null` would replace the device).
void checkReplaceable(const fs::path& target, const fs::path& reported) {
  struct stat existing {};
  if (::stat(target.c_str(), &existing) != 0) return;  // a new file
  if (S_ISDIR(existing.st_mode)) throw FileError(reported, "is a folder, not a file");
  if (!S_ISREG(existing.st_mode)) {
    throw FileError(reported, "is not a regular file (a device, pipe or socket), so it is not replaced");
  }
}

// The file a write of `file` replaces, once its name and what is there now are checked.
fs::path replaceableTarget(const fs::path& file) {
  if (file.empty()) throw FileError(file, "no file name given");
  if (!file.has_filename()) throw FileError(file, "names a folder, not a file");
  // Renaming over a symbolic link would replace the link; replace what it points at instead.
  fs::path target = followLinks(file);
  checkReplaceable(target, file);
  return target;
}

}  // namespace

FileError::FileError(fs::path file, const std::string& message)
    : std::runtime_error((file.empty() ? std::string("(no file name)") : file.string()) + ": " + message),
      file_(std::move(file)),
      message_(message) {}

fs::path followLinks(const fs::path& file) {
  fs::path target = file;
  for (int links = 0;; ++links) {
    struct stat self {};
    if (::lstat(target.c_str(), &self) != 0 || !S_ISLNK(self.st_mode)) return target;
    if (links == kMaxLinks) throw FileError(file, "cannot follow the symbolic link: " + reason(ELOOP));
    std::error_code ec;
    const fs::path next = fs::read_symlink(target, ec);
    if (ec) throw FileError(file, "cannot follow the symbolic link: " + ec.message());
    // A relative link is relative to the folder holding the link, not to the working folder.
    target = next.is_absolute() ? next : folderOf(target) / next;
  }
}

void writeAtomically(const fs::path& file, std::string_view content) {
  const FileContent one{file, content};
  writeAllAtomically(std::span(&one, 1));
}

void checkWritable(const fs::path& file) {
  const fs::path target = replaceableTarget(file);
  TemporaryFile probe(target, file);  // removed again as it goes out of scope
}

void writeAllAtomically(std::span<const FileContent> files) {
  std::vector<fs::path> targets;
  std::vector<std::unique_ptr<TemporaryFile>> written;  // unlinked as they go, unless renamed
  for (const FileContent& f : files) {
    targets.push_back(replaceableTarget(f.file));
    written.push_back(std::make_unique<TemporaryFile>(targets.back(), f.file));
    written.back()->write(f.content);
    written.back()->copyPermissionsOf(targets.back());
    written.back()->flushAndClose();
  }
  for (std::size_t i = 0; i < written.size(); ++i) written[i]->renameTo(targets[i]);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const bool flushed = std::any_of(targets.begin(), targets.begin() + static_cast<std::ptrdiff_t>(i),
                                     [&](const fs::path& t) { return folderOf(t) == folderOf(targets[i]); });
    if (!flushed) flushFolder(targets[i]);
  }
}

void prepareFolder(const fs::path& folder) {
  if (folder.empty()) throw FileError(folder, "no folder name given");
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw FileError(folder, "cannot create the folder: " + ec.message());
  if (const std::string why = folderProblem(folder); !why.empty()) throw FileError(folder, why);
  TemporaryFile probe(folder / "probe", folder);  // removed again as it goes out of scope
}

namespace {

// A file descriptor, closed as it goes out of scope: also when the constructor of the OpenFile
// holding it throws, as members already built are destroyed.
struct Descriptor {
  int fd = -1;
  Descriptor() = default;
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

// A file open for reading, with what fstat says of it; failures say what the file was meant to be
// (`kind`: "cannot open shader file: ..."), or nothing of it when `kind` is empty.
class OpenFile {
 public:
  // Opened without blocking: a named pipe with no writer would hold open() for ever. Reads block
  // again, so a pipe that has a writer (/dev/stdin under a shell's pipe) is read whole.
  OpenFile(const fs::path& file, std::string_view kind) : file_(file), kind_(kind) {
    if (file.empty()) throw FileError(file, "no " + noun() + " name given");
    const int fd = descriptor_.fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) failWithErrno("cannot open");
    if (const int flags = ::fcntl(fd, F_GETFL); flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0)
      failWithErrno("cannot read");
    if (::fstat(fd, &info_) != 0) failWithErrno("cannot read");
    if (S_ISDIR(info_.st_mode)) throw FileError(file, "is a folder, not a " + noun());
  }
  int fd() const { return descriptor_.fd; }
  const struct stat& info() const { return info_; }
  /// What the file is called in messages: its kind, or "file".
  std::string noun() const { return kind_.empty() ? "file" : std::string(kind_); }
  bool hasKind() const { return !kind_.empty(); }

  // "cannot open shader file: the OS's reason". `what` is a literal, so nothing allocates (and
  // may change errno) before errno is read.
  [[noreturn]] void failWithErrno(const char* what) const {
    const int error = errno;
    throw FileError(
        file_, std::string(what) + (kind_.empty() ? "" : " " + std::string(kind_)) + ": " + reason(error));
  }

 private:
  fs::path file_;
  std::string_view kind_;
  Descriptor descriptor_;
  struct stat info_ {};
};

}  // namespace

void checkRegularFile(const fs::path& file, std::string_view kind) {
  const OpenFile open(file, kind);
  if (!S_ISREG(open.info().st_mode)) {
    throw FileError(
        file, "is not a regular file (a device, pipe or socket), so it is not read as a " + open.noun());
  }
}

std::string folderProblem(const fs::path& folder) {
  std::error_code ec;
  const fs::file_status status = fs::status(folder, ec);
  if (ec) return ec.message();
  return fs::is_directory(status) ? "" : std::make_error_code(std::errc::not_a_directory).message();
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
      throw FileError(
          file, "is larger than " + std::to_string(maxBytes) + " bytes, " +
                    (open.hasKind() ? "the most a " + open.noun() + " may hold" : "the most that is read"));
    }
    content.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace fileio
