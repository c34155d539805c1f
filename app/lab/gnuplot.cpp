#include "gnuplot.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include <sys/wait.h>

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

std::string singleQuoted(const std::string& text, const std::string& quoteInside) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? quoteInside : std::string(1, c);
  return out + "'";
}

namespace {

// Single quotes for the shell, with any quote inside closed, escaped and reopened.
std::string shellQuoted(const std::string& text) {
  return singleQuoted(text, "'\\''");
}

// What a wait status says: the exit status, or the signal that ended the program (the raw status
// is neither: an exit status of 3 reads 768).
// gnuplot runs under the shell, which exits 128 + N when its child is killed by signal N.
std::string exitText(int status) {
  const auto killedBy = [](int signal) {
    const char* name = ::strsignal(signal);
    return "killed by signal " + std::to_string(signal) + (name != nullptr ? std::string(", ") + name : "");
  };
  if (status == -1) return "its status could not be read";
  if (WIFSIGNALED(status)) return killedBy(WTERMSIG(status));
  if (!WIFEXITED(status)) return "wait status " + std::to_string(status);
  const int code = WEXITSTATUS(status);
  if (code > 128 && code < 128 + 65) return killedBy(code - 128);
  return "exit status " + std::to_string(code);
}

}  // namespace

std::string runGnuplot(const std::filesystem::path& script, const std::filesystem::path& folder,
                       const std::filesystem::path& shownAs) {
  const std::string shown = (shownAs.empty() ? script : shownAs).string();
  const std::filesystem::path gnuplot = findGnuplot();
  if (gnuplot.empty()) {
    return std::string(kGnuplotMissing) + "; the data and " + shown +
           " are written, run gnuplot on it to draw the charts";
  }
  const std::string command = "cd " + shellQuoted(folder.string()) + " && " + shellQuoted(gnuplot.string()) +
                              " " + shellQuoted(script.filename().string()) + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return "cannot start gnuplot";
  std::string output;
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) output += buffer.data();
  const int status = pclose(pipe);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return {};
  if (output.size() > 400) output = "..." + output.substr(output.size() - 400);
  return "gnuplot failed on " + shown + " (" + exitText(status) + "): " + output;
}

}  // namespace lab
