// lab: the headless physics runner (docs/lab.md). Everything but argument plumbing is in
// lab_core, where the tests can reach it.
#include <iostream>
#include <string>
#include <vector>

#include "lab.h"

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  return lab::labMain(args, std::cout, std::cerr);
}
