#pragma once
// `--help` for every benchmark: the text goes to stdout and the program ends with status 0
// before it parses anything else (benchmarks/run.sh runs them all; docs/benchmarks.md).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/program_main.hpp"

namespace thx::bench {

inline void exitOnHelp(int argc, char** argv, const char* text) {
  if (helpRequested(std::vector<std::string>(argv + 1, argv + argc))) {
    std::fputs(text, stdout);
    std::exit(0);
  }
}

// A benchmark's main(): thx::runProgram (base/program_main.hpp) around run(argc, argv): --help,
// then a thx::Error printed as "NAME: what" with exit status 2 for usage, 1 otherwise.
inline int benchMain(int argc, char** argv, const char* help, const char* name, int (*run)(int, char**)) {
  return runProgram(name, help, argc, argv, [&](const std::vector<std::string>&) { return run(argc, argv); });
}

}  // namespace thx::bench
