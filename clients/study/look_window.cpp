#include "clients/study/look_window.hpp"

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>

#include "base/error.hpp"

extern char** environ;

namespace thx::study {

void LookWindow::show(const std::string& scene_path, bool objects) {
  stop();
  std::vector<std::string> args{program_, "--scene", scene_path, "--live", "--window", "--allow-different-scene",
                                "--quiet"};
  if (!objects) args.push_back("--no-objects");
  args.insert(args.end(), extra_.begin(), extra_.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const int rc = posix_spawnp(&pid_, program_.c_str(), nullptr, nullptr, argv.data(), environ);
  if (rc != 0) {
    pid_ = -1;
    throw Error(Error::Kind::Io, "cannot start the look window '" + program_ + "': " + std::strerror(rc));
  }
}

void LookWindow::stop() {
  if (pid_ <= 0) return;
  kill(pid_, SIGTERM);
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {}
  pid_ = -1;
}

}  // namespace thx::study
