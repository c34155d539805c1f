// soak: the sandbox's command layer driven headless with random commands for a while, with
// invariants checked after each (docs/sandbox.md, "Soak test").
//
//   soak --seconds N [--seed S] [--commands N] [--data DIR] [--verbose] [--keep-going]
#include <array>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>

#include <signal.h>
#include <unistd.h>

#include "soak.h"

namespace {

constexpr const char* kUsage =
    "usage: soak --seconds N [--seed S] [--commands N] [--data DIR] [--verbose] [--keep-going]\n"
    "  --seconds N    start commands for N seconds of wall time\n"
    "  --seed S       the seed of the sequence of commands, default 1\n"
    "  --commands N   stop after N commands (a failure's replay)\n"
    "  --data DIR     the folder holding assets/scenes, default " DATA_DIR
    "\n"
    "  --verbose      print each command as it starts, and more figures at the end\n"
    "  --keep-going   after a failure, report it, open a fresh scene and go on\n";

int usageError(const std::string& message) {
  std::fprintf(stderr, "soak: %s\n%s", message.c_str(), kUsage);
  return 2;
}

// A crash cannot be caught, but it can be told: which seed and command it was. Only
// async-signal-safe calls here (write, strlen, sigaction, raise); the text was formatted before
// the command started. Then the handler that was there before (the default, or a sanitizer's,
// which prints the stack) gets the signal.
constexpr std::array<int, 5> kCrashSignals{SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
struct sigaction g_previous[kCrashSignals.size()];

extern "C" void onCrash(int signal) {
  const char* head = "\nsoak: CRASHED (a fatal signal) during ";
  const char* current = soak::currentCommandForCrashReport();
  ssize_t ignored = ::write(STDOUT_FILENO, head, std::strlen(head));
  ignored = ::write(STDOUT_FILENO, current, std::strlen(current));
  ignored = ::write(STDOUT_FILENO, "\n", 1);
  (void)ignored;
  for (std::size_t i = 0; i < kCrashSignals.size(); ++i) {
    if (kCrashSignals[i] == signal) sigaction(signal, &g_previous[i], nullptr);
  }
  std::raise(signal);  // delivered to the previous handler once this one returns
}

void installCrashHandler() {
  struct sigaction action {};
  action.sa_handler = onCrash;
  sigemptyset(&action.sa_mask);
  for (std::size_t i = 0; i < kCrashSignals.size(); ++i) sigaction(kCrashSignals[i], &action, &g_previous[i]);
}

/// A whole number >= 0, all of `text`.
bool parseCount(const char* text, unsigned long long& out) {
  if (text == nullptr || *text < '0' || *text > '9') return false;
  char* end = nullptr;
  out = std::strtoull(text, &end, 10);
  return *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  soak::Options options;
  options.dataDir = DATA_DIR;
  bool haveSeconds = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : nullptr;
    const std::string shown = value ? value : "";
    unsigned long long count = 0;
    if (arg == "--seconds") {
      char* end = nullptr;
      const double seconds = value ? std::strtod(value, &end) : 0.0;
      if (!value || *end != '\0' || !(seconds > 0.0 && seconds <= 1e7))
        return usageError("--seconds needs a number of seconds above 0 and up to 1e7, got '" + shown + "'");
      options.seconds = seconds;
      haveSeconds = true;
      ++i;
    } else if (arg == "--seed") {
      if (!parseCount(value, count))
        return usageError("--seed needs a whole number >= 0, got '" + shown + "'");
      options.seed = count;
      ++i;
    } else if (arg == "--commands") {
      if (!parseCount(value, count) || count > 1000000000000ULL)
        return usageError("--commands needs a whole number from 0 to 1e12, got '" + shown + "'");
      options.maxCommands = static_cast<long>(count);
      ++i;
    } else if (arg == "--data") {
      if (!value) return usageError("--data needs a folder");
      options.dataDir = value;
      ++i;
    } else if (arg == "--verbose") {
      options.verbose = true;
    } else if (arg == "--keep-going") {
      options.keepGoing = true;
    } else if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else {
      return usageError("unknown argument '" + std::string(arg) + "'");
    }
  }
  if (!haveSeconds) return usageError("--seconds is required");
  installCrashHandler();
  return soak::run(options);
}
