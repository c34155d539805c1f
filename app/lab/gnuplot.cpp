#include "gnuplot.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <system_error>

namespace lab {

std::filesystem::path findGnuplot() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    std::filesystem::path candidate = std::filesystem::path(dir) / "gnuplot";  // not const: moved out
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec)) return candidate;
  }
  return {};
}

namespace {

// Single quotes for the shell, with any quote inside closed, escaped and reopened.
std::string shellQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// Each chart gnuplot drew, flushed to disk and renamed over its old self; "" or why not.
std::string moveIntoPlace(const std::filesystem::path& from, const std::filesystem::path& folder) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(from, ec)) {
    const std::filesystem::path& chart = entry.path();
    const int fd = ::open(chart.c_str(), O_RDONLY | O_CLOEXEC);
    const bool flushed = fd >= 0 && ::fsync(fd) == 0;
    const int error = errno;
    if (fd >= 0) ::close(fd);
    const std::filesystem::path target = folder / chart.filename();
    if (!flushed || ::rename(chart.c_str(), target.c_str()) != 0) {
      return "cannot move the chart into place as " + target.string() + ": " +
             std::generic_category().message(flushed ? errno : error);
    }
  }
  if (ec) return "cannot list the charts gnuplot drew: " + ec.message();
  return {};
}

}  // namespace

PrivateFolder::PrivateFolder(const std::filesystem::path& parent, const char* prefix) {
  std::string name = (parent / (std::string(prefix) + "XXXXXX")).string();
  if (::mkdtemp(name.data()) != nullptr)
    path_ = name;
  else
    error_ = errno;
}

PrivateFolder::~PrivateFolder() {
  std::error_code ignored;
  if (!path_.empty()) std::filesystem::remove_all(path_, ignored);
}

std::string runGnuplot(const std::filesystem::path& script, const std::filesystem::path& folder,
                       const std::filesystem::path& shownAs) {
  const std::string shown = (shownAs.empty() ? script : shownAs).string();
  const std::filesystem::path gnuplot = findGnuplot();
  if (gnuplot.empty()) {
    return "gnuplot is not installed (Debian: apt-get install gnuplot-nox); the data and " + shown +
           " are written, run gnuplot on it to draw the charts";
  }
  const PrivateFolder drawn(folder, ".charts-");
  if (drawn.path().empty()) {
    return "cannot create a folder for the charts in " + folder.string() + ": " +
           std::generic_category().message(drawn.error());
  }
  // The folder's name is ours (letters and digits), so it needs no quoting inside gnuplot's.
  const std::string command = "cd " + shellQuoted(folder.string()) + " && " + shellQuoted(gnuplot.string()) +
                              " -e " + shellQuoted("outdir='" + drawn.path().filename().string() + "'") +
                              " " + shellQuoted(script.filename().string()) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "cannot start gnuplot";
  std::string output;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return moveIntoPlace(drawn.path(), folder);
  if (output.size() > 400) output = "..." + output.substr(output.size() - 400);
  return "gnuplot failed on " + shown + " (status " + std::to_string(status) + "): " + output;
}

}  // namespace lab
