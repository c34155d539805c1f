#pragma once
// The lab's commands, each a whole program over the arguments after its name: labMain (lab.h)
// makes its command line from the command table, the command adds its options and runs in
// commandMain's frame (command_line.h: exit 2 and its help on an error). docs/lab.md has each
// one's options and output; `lab CMD --help` lists them.
#include <iosfwd>
#include <string>
#include <vector>

namespace lab {

class CommandLine;

/// What every command's main is: commandMainOf (command_line.h) over its options.
using CommandMain = int (*)(CommandLine& line, const std::vector<std::string>& args, std::ostream& out,
                            std::ostream& err);

extern const CommandMain runMain;        ///< lab.cpp
extern const CommandMain sweepMain;      ///< sweep.cpp
extern const CommandMain stabilityMain;  ///< stability.cpp
extern const CommandMain tuneMain;       ///< tune.cpp
extern const CommandMain compareMain;    ///< compare.cpp
extern const CommandMain scaleMain;      ///< scale.cpp
extern const CommandMain convergeMain;   ///< converge.cpp
extern const CommandMain reportMain;     ///< results.cpp

/// What a command did, its streams captured as text.
struct CommandOutput {
  int code = -1;    ///< exit code; -1 until it has run
  std::string out;  ///< what it wrote to `out`
  std::string err;  ///< what it wrote to `err`
};

/// `lab ARGS...` (labMain) with string streams: how lab report quotes its commands' output, and
/// how the tests see exactly what the program would print without starting it.
CommandOutput runCaptured(const std::vector<std::string>& args);
/// The same for `lab COMMAND ARGS...`.
CommandOutput runCaptured(const std::string& command, std::vector<std::string> args);

}  // namespace lab
