#pragma once
// The soak test: the sandbox's command layer (sandbox::Session) driven headless with random
// commands, chosen by a seeded generator, with invariants checked after every command
// (docs/sandbox.md, "Soak test").
#include <cstdint>
#include <filesystem>
#include <string>

namespace soak {

struct Options {
  double seconds = 0.0;           ///< stop starting commands after this much wall time
  long maxCommands = -1;          ///< and after this many; -1: no limit
  std::uint64_t seed = 1;         ///< the whole sequence of commands follows from it
  std::filesystem::path dataDir;  ///< holds assets/scenes
  bool verbose = false;           ///< print every command as it starts
  bool keepGoing = false;         ///< after a failure, report it, open a fresh scene and go on
};

/// Runs the soak; prints failures and the summary line on stdout. Returns the process's exit
/// code: 0 when every invariant held, 1 when one broke.
int run(const Options& options);

/// Called by the crash handler: the seed, the command number and the command in progress.
const char* currentCommandForCrashReport();

}  // namespace soak
