#pragma once
// The shape every audio command-line program shares (modal-analyze, audio-client,
// wav-spectrogram): -h/--help prints the help text and exits 0 before anything is parsed; a
// thx::Error is printed as "NAME: message" (usage errors with a pointer to --help) and becomes the
// exit status 2 (usage) or 1; any other exception exits 1.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "base/error.hpp"

namespace thx::audio {

template <class Run>
int runTool(const char* name, const char* help, int argc, char** argv, Run&& run) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  for (const std::string& a : args)
    if (a == "-h" || a == "--help") {
      std::fputs(help, stdout);
      return 0;
    }
  try {
    return run(args);
  } catch (const thx::Error& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    if (e.kind() == thx::Error::Kind::Usage) std::fprintf(stderr, "(%s --help lists the options)\n", name);
    return thx::exitStatus(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace thx::audio
