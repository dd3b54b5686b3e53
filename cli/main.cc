// The efc program (shared/spec/cli.md). Exit codes: 0 success, 1 the input is
// wrong, 2 usage or I/O error.
#include <cstdio>
#include <exception>

#include "cli/commands.h"

int main(int argc, char** argv) {
  try {
    return efc::run_cli(argc, argv);
  } catch (const std::exception& e) {
    // Nothing should reach here; if it does, say so instead of aborting.
    std::fprintf(stderr, "efc: internal error: %s\n", e.what());
    return 2;
  }
}
