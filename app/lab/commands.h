#pragma once
// The lab's commands besides `run`, each a whole program over the arguments after its name: it
// reads them through its CommandLine (command_line.h: exit 2 and its help on an error), runs,
// and reports. docs/lab.md has each one's options and output; `lab CMD --help` lists them.
#include <iosfwd>
#include <string>
#include <vector>

namespace lab {

/// lab sweep SCENE --out DIR [--methods LIST] [--iterations LIST] [--substeps LIST] [--dt LIST]
///                 [--models LIST] [--repeat R] [--steps N]
int sweepMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab stability [--out DIR]
int stabilityMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab tune SCENE --target METRIC=VALUE [...]
int tuneMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab compare SCENE
int compareMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab scale [KIND] [--sizes LIST] [--steps N] [--json] [--out DIR]: cost against size
int scaleMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab converge [SCENE...] [--methods LIST] [--models LIST] [--substeps LIST] [--out DIR]: error
/// against the substep size on scenes with exact answers
int convergeMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab report [--out DIR]: regenerates docs/results.md and its charts
int reportMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// What a command did, its streams captured as text.
struct CommandOutput {
  int code = -1;    ///< exit code; -1 until it has run
  std::string out;  ///< what it wrote to `out`
  std::string err;  ///< what it wrote to `err`
};

/// The signature every command above (and labMain) has.
using CommandMain = int (*)(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

/// Runs a command on args with string streams: how lab report quotes its commands' output, and
/// how the tests see exactly what the program would print without starting it.
CommandOutput runCaptured(CommandMain main, const std::vector<std::string>& args);

}  // namespace lab
