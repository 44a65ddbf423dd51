#pragma once
// A gtest fixture for tests that run the real hapticd binary as a user would: from the source
// directory, in a process of its own, with a scratch directory per test. Needs THX_HAPTICD and
// THX_SOURCE_DIR (tests/server/CMakeLists.txt: thx_test_runs_hapticd).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace thx::test {

struct ProcRun {
  int status = -1;  // exit status; -1 if the process did not exit normally
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class HapticdProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* t = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("thx_" + std::string(t->test_suite_name()) + "_" + t->name() + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Runs `hapticd ARGS` to completion; stdout and stderr go to out.txt / err.txt in the scratch
  // directory and come back in the result.
  ProcRun run(const std::string& args) const {
    const std::string cmd = std::string("cd '") + THX_SOURCE_DIR + "' && '" + THX_HAPTICD + "' " + args + " >'" +
                            path("out.txt") + "' 2>'" + path("err.txt") + "'";
    const int raw = std::system(cmd.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(path("out.txt")), slurp(path("err.txt"))};
  }

  std::filesystem::path dir_;
};

}  // namespace thx::test
