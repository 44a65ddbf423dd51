#pragma once
// `--help` for every benchmark: the text goes to stdout and the program ends with status 0
// before it parses anything else (benchmarks/run.sh runs them all; docs/benchmarks.md).
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "base/error.hpp"

namespace thx::bench {

inline void exitOnHelp(int argc, char** argv, const char* text) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "-h" || a == "--help") {
      std::fputs(text, stdout);
      std::exit(0);
    }
  }
}

// A benchmark's main(): --help, then run(argc, argv); a thx::Error is printed as "NAME: what" and
// gives the exit status (2 for usage, 1 otherwise).
inline int benchMain(int argc, char** argv, const char* help, const char* name, int (*run)(int, char**)) {
  exitOnHelp(argc, argv, help);
  try {
    return run(argc, argv);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return exitStatus(e);
  }
}

}  // namespace thx::bench
