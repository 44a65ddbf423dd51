#pragma once
// The shape every command-line program shares, so that each `main` is one line:
//
//   int main(int argc, char** argv) {
//     return thx::runProgram("scene-info", kHelp, argc, argv, [](const std::vector<std::string>& args) {
//       ...  // parse args, do the work, return the exit status
//     });
//   }
//
// -h or --help anywhere on the command line prints the help text on stdout and exits 0 before
// anything is parsed. Otherwise run(args) gets the arguments after the program's name and its
// return value is the exit status. A thx::Error it throws is printed on stderr as "NAME: message"
// (a usage error followed by "(NAME --help lists the options)") and gives exit status 2 for usage,
// 1 otherwise (thx::exitStatus); any other std::exception is printed the same way and gives 1.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "base/error.hpp"

namespace thx {

// True if `args` holds -h or --help.
inline bool helpRequested(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a == "-h" || a == "--help") return true;
  return false;
}

// The error half of runProgram alone, for a program whose help depends on its arguments
// (texturetool's commands each have their own): returns run(), or prints what it threw as above
// and returns 2 or 1. `name` may hold a command too ("texturetool smooth").
template <class Run>
int reportErrors(const std::string& name, Run&& run) {
  try {
    return run();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    if (e.kind() == Error::Kind::Usage) std::fprintf(stderr, "(%s --help lists the options)\n", name.c_str());
    return exitStatus(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return 1;
  }
}

// A program's whole main: --help, then run(args) with its errors reported (see the top).
template <class Run>
int runProgram(const std::string& name, const char* help, int argc, char** argv, Run&& run) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (helpRequested(args)) {
    std::fputs(help, stdout);
    return 0;
  }
  return reportErrors(name, [&] { return run(args); });
}

}  // namespace thx
