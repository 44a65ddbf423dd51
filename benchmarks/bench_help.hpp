#pragma once
// `--help` for every benchmark: the text goes to stdout and the program ends with status 0
// before it parses anything else (benchmarks/run.sh runs them all; docs/benchmarks.md).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/error.hpp"
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

// The results files of a benchmark that takes no option but these: --json F, --csv F, --md F
// (each optional; anything else is a usage error naming it).
struct ResultFiles {
  std::string json, csv, md;
};
inline ResultFiles resultFilesOnly(int argc, char** argv) {
  ResultFiles files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) throw UsageError(a + " needs a value (see --help)");
    const std::string v = argv[++i];
    if (a == "--json") files.json = v;
    else if (a == "--csv") files.csv = v;
    else if (a == "--md") files.md = v;
    else throw UsageError("unknown option " + a + " (see --help)");
  }
  return files;
}

}  // namespace thx::bench
