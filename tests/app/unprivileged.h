#pragma once
// Runs a piece of a test as an ordinary user, so that permission checks hold when the tests run
// as root (as CI does): root ignores a folder's missing write bit, nobody does. The piece runs
// in a child process (which drops to nobody when started as root) and its answer comes back as
// text through a pipe; the child never touches GoogleTest's state.
#include <fcntl.h>
#include <grp.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <string>

namespace testing_app {

inline constexpr uid_t kNobody = 65534;  // Debian's nobody and nogroup

/// The text `piece` returned, run as nobody (or as the current user when not root); or a line
/// starting "runAsNobody:" when it could not be run that way.
inline std::string runAsNobody(const std::function<std::string()>& piece) {
  int channel[2];
  if (::pipe(channel) != 0) return std::string("runAsNobody: pipe: ") + std::strerror(errno);
  const pid_t child = ::fork();
  if (child < 0) return std::string("runAsNobody: fork: ") + std::strerror(errno);
  if (child == 0) {
    ::close(channel[0]);
    std::string answer;
    if (::geteuid() == 0 &&
        (::setgroups(0, nullptr) != 0 || ::setgid(kNobody) != 0 || ::setuid(kNobody) != 0)) {
      answer = std::string("runAsNobody: cannot become nobody: ") + std::strerror(errno);
    } else {
      try {
        answer = piece();
      } catch (const std::exception& e) {
        answer = std::string("runAsNobody: threw: ") + e.what();
      }
    }
    for (std::size_t sent = 0; sent < answer.size();) {
      const ssize_t n = ::write(channel[1], answer.data() + sent, answer.size() - sent);
      if (n <= 0) break;
      sent += static_cast<std::size_t>(n);
    }
    ::_exit(0);
  }
  ::close(channel[1]);
  std::string answer;
  char buffer[512];
  for (ssize_t n; (n = ::read(channel[0], buffer, sizeof buffer)) > 0;) answer.append(buffer, n);
  ::close(channel[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (!WIFEXITED(status)) return "runAsNobody: the child died (status " + std::to_string(status) + ")";
  return answer;
}

}  // namespace testing_app
