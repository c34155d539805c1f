#include "atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <string>
#include <system_error>

#include "scenes/scene_writer.h"

namespace scenes::detail {
namespace {

namespace fs = std::filesystem;

std::string reason(int error) {
  return std::generic_category().message(error);
}

// The temporary file: open while being written, removed unless it was renamed into place.
class TemporaryFile {
 public:
  TemporaryFile(const fs::path& target, const fs::path& reported) : reported_(reported) {
    static std::atomic<unsigned> counter{0};
    int error = 0;
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    // Hidden, named after the target and unique to this process and call. O_EXCL never reuses
    // an existing file (another saver's, or a stray link); a clash just tries the next name.
    for (int attempt = 0; attempt < 100; ++attempt) {
      // Appended piece by piece: "." + std::string trips GCC 12's -Wrestrict false positive
      // (GCC bug 105329).
      std::string name(".");
      name.append(target.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
      name.append("-").append(std::to_string(counter++));
      path_ = folder / name;
      fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd_ >= 0) return;
      error = errno;
      if (error != EEXIST) break;
    }
    throw SaveError(reported_,
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
      const int error = errno;  // read before building the message, which may allocate
      if (n < 0 && error == EINTR) continue;
      if (n < 0) fail("cannot write '" + path_.string() + "'", error);
      content.remove_prefix(static_cast<std::size_t>(n));
    }
  }

  void copyPermissionsOf(const fs::path& file) {
    struct stat existing {};
    if (::stat(file.c_str(), &existing) != 0) return;  // a new file keeps 0666 less the umask
    if (::fchmod(fd_, existing.st_mode & 07777) != 0) {
      const int error = errno;
      fail("cannot set the permissions of '" + path_.string() + "'", error);
    }
  }

  // Flushed before the rename: otherwise a crash soon after could leave the new name pointing
  // at a file whose data never reached the disk.
  void flushAndClose() {
    if (::fsync(fd_) != 0) {
      const int error = errno;
      fail("cannot flush '" + path_.string() + "' to disk", error);
    }
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) {
      const int error = errno;
      fail("cannot close '" + path_.string() + "'", error);
    }
  }

  void renameTo(const fs::path& target) {
    if (::rename(path_.c_str(), target.c_str()) != 0) {
      const int error = errno;
      fail("cannot replace it with the new file", error);
    }
    renamed_ = true;
  }

 private:
  [[noreturn]] void fail(const std::string& what, int error) const {
    throw SaveError(reported_, what + ": " + reason(error));
  }

  fs::path reported_;
  fs::path path_;
  int fd_ = -1;
  bool renamed_ = false;
};

// Makes the rename itself durable; a folder that cannot be opened or synced (some file systems
// refuse) costs only that guarantee, so failures here are not errors.
void flushFolder(const fs::path& target) {
  const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void replaceFileAtomically(const fs::path& file, std::string_view content) {
  if (file.empty()) throw SaveError(file, "no file name given");
  // Renaming over a symbolic link would replace the link; replace what it points at instead.
  fs::path target = file;
  std::error_code ec;
  if (fs::is_symlink(file, ec)) {
    target = fs::weakly_canonical(file, ec);
    if (ec) throw SaveError(file, "cannot follow the symbolic link: " + ec.message());
  }
  TemporaryFile temporary(target, file);
  temporary.write(content);
  temporary.copyPermissionsOf(target);
  temporary.flushAndClose();
  temporary.renameTo(target);
  flushFolder(target);
}

}  // namespace scenes::detail
