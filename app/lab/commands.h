#pragma once
// The lab's commands besides `run`, each a whole program over the arguments after its name:
// it parses them (exit 2 and its usage on an error), runs, and reports. docs/lab.md has each
// one's options and output.
#include <iosfwd>
#include <string>
#include <vector>

namespace lab {

/// lab sweep SCENE [--method LIST] [--iterations LIST] [--substeps LIST] [--dt LIST]
///                 [--model LIST] [--repeat R] [--steps N] --out DIR
int sweepMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab stability [--out DIR]
int stabilityMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab tune SCENE --target METRIC=VALUE [...]
int tuneMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab compare SCENE
int compareMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);
/// lab report [--out DIR]: regenerates docs/results.md and its charts
int reportMain(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace lab
