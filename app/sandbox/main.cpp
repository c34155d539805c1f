#include "sandbox.h"

int main(int argc, char** argv) {
  return sandbox::runSandbox(argc, argv);
}
