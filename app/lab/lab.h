#pragma once
// The whole `lab` program but main(): the tests call it in-process with string streams, and
// main.cpp with std::cout and std::cerr.
#include <iosfwd>
#include <string>
#include <vector>

#include "options.h"

namespace lab {

/// Exit codes of the program (docs/lab.md).
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  ///< the scene, the overrides or the dump failed
inline constexpr int kExitUsage = 2;    ///< a command-line error

/// Runs the program on the arguments after its name; returns the exit code.
int labMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace lab
