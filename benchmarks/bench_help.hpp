#pragma once
// `--help` for every benchmark: the text goes to stdout and the program ends with status 0
// before it parses anything else (benchmarks/run.sh runs them all; docs/benchmarks.md).
#include <cstdio>
#include <cstdlib>
#include <string_view>

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

}  // namespace thx::bench
