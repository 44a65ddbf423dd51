// thx::runProgram, the shape of every program's main: its stdout and stderr captured in temporary
// files (file descriptors 1 and 2 redirected around the one call).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/program_main.hpp"

namespace test_program_main {

namespace {

struct Outcome {
  int status = -1;
  std::string out, err;
};

std::string readAll(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string text;
  char buffer[256];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, f)) > 0;) text.append(buffer, n);
  return text;
}

// Runs `program` (a lambda around thx::runProgram) with stdout and stderr going to temporary files.
template <class Program>
Outcome captured(Program&& program) {
  std::FILE* out = std::tmpfile();
  std::FILE* err = std::tmpfile();
  std::fflush(stdout);
  std::fflush(stderr);
  const int saved_out = ::dup(1), saved_err = ::dup(2);
  ::dup2(::fileno(out), 1);
  ::dup2(::fileno(err), 2);
  Outcome o;
  o.status = program();
  std::fflush(stdout);
  std::fflush(stderr);
  ::dup2(saved_out, 1);
  ::dup2(saved_err, 2);
  ::close(saved_out);
  ::close(saved_err);
  o.out = readAll(out);
  o.err = readAll(err);
  std::fclose(out);
  std::fclose(err);
  return o;
}

const char* const kHelp = "usage: prog [--fail]\n";

// prog ARGS... with `run` as its body.
template <class Run>
Outcome prog(std::vector<std::string> args, Run run) {
  args.insert(args.begin(), "prog");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  return captured([&] { return thx::runProgram("prog", kHelp, int(argv.size()), argv.data(), run); });
}

}  // namespace

TEST(ProgramMain, HelpAnywherePrintsTheHelpAndExits0BeforeAnythingIsParsed) {
  for (const char* help : {"-h", "--help"}) {
    bool ran = false;
    const Outcome o = prog({"--bogus", help, "x"}, [&](const std::vector<std::string>&) {
      ran = true;
      return 3;
    });
    EXPECT_EQ(o.status, 0) << help;
    EXPECT_EQ(o.out, kHelp);
    EXPECT_EQ(o.err, "");
    EXPECT_FALSE(ran) << help;
  }
}

TEST(ProgramMain, RunGetsTheArgumentsAndItsStatusPassesThrough) {
  std::vector<std::string> seen;
  const Outcome o = prog({"a", "--b", "c"}, [&](const std::vector<std::string>& args) {
    seen = args;
    std::printf("done\n");
    return 7;
  });
  EXPECT_EQ(o.status, 7);
  EXPECT_EQ(seen, (std::vector<std::string>{"a", "--b", "c"}));
  EXPECT_EQ(o.out, "done\n");
  EXPECT_EQ(o.err, "");
}

TEST(ProgramMain, UsageErrorExits2WithAPointerToHelp) {
  const Outcome o = prog({"--fail"}, [](const std::vector<std::string>&) -> int {
    throw thx::UsageError("unknown option '--fail'");
  });
  EXPECT_EQ(o.status, 2);
  EXPECT_EQ(o.out, "");
  EXPECT_EQ(o.err, "prog: unknown option '--fail'\n(prog --help lists the options)\n");
}

TEST(ProgramMain, OtherErrorsExit1WithTheirMessageOnly) {
  const Outcome config = prog({}, [](const std::vector<std::string>&) -> int {
    throw thx::Error(thx::Error::Kind::Config, "scene.yaml:3: bad");
  });
  EXPECT_EQ(config.status, 1);
  EXPECT_EQ(config.err, "prog: scene.yaml:3: bad\n");
  const Outcome io = prog({}, [](const std::vector<std::string>&) -> int {
    throw thx::Error(thx::Error::Kind::Io, "out.csv: cannot be written");
  });
  EXPECT_EQ(io.status, 1);
  EXPECT_EQ(io.err, "prog: out.csv: cannot be written\n");
  const Outcome other = prog({}, [](const std::vector<std::string>&) -> int { throw std::runtime_error("boom"); });
  EXPECT_EQ(other.status, 1);
  EXPECT_EQ(other.err, "prog: boom\n");
}

TEST(ProgramMain, ReportErrorsAloneNamesTheCommand) {
  const Outcome o = captured([] {
    return thx::reportErrors("tool smooth", []() -> int { throw thx::UsageError("--sigma: required"); });
  });
  EXPECT_EQ(o.status, 2);
  EXPECT_EQ(o.err, "tool smooth: --sigma: required\n(tool smooth --help lists the options)\n");
  EXPECT_EQ(captured([] { return thx::reportErrors("tool", [] { return 0; }); }).status, 0);
}

}  // namespace test_program_main
