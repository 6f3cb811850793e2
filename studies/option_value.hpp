// Command-line value of the option at argv[i] for the study executables that exit with status 2
// on a usage error (ancf-bench-genalpha, ancf-bench-ida-step): advances i to the value; prints
// "OPTION needs a value" and exits 2 when there is none.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace ancf::studies {

inline const char* option_value(int argc, char** argv, int& i) {
  if (i + 1 >= argc) {
    std::fprintf(stderr, "%s needs a value\n", argv[i]);
    std::exit(2);
  }
  return argv[++i];
}

}  // namespace ancf::studies
