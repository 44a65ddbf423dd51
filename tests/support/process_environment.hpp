#pragma once
// A test's view of its own process: an environment variable set for one scope, and whether a
// shared object is mapped (opened with dlopen, say). No GoogleTest: plain POSIX and the standard
// library.
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

namespace thx::test {

// Sets an environment variable for one scope and puts back what was there (or unsets it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, had_ = true;
    setenv(name, value, 1);
  }
  ~ScopedEnv() {
    if (had_) setenv(name_, old_.c_str(), 1);
    else unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::string old_;
  bool had_ = false;
};

// Whether a file of this name (e.g. "libthx_mesh_import_module.so") is mapped into the process.
inline bool isMapped(const std::string& file_name) {
  std::ifstream maps("/proc/self/maps");
  const std::string text((std::istreambuf_iterator<char>(maps)), std::istreambuf_iterator<char>());
  return text.find(file_name) != std::string::npos;
}

}  // namespace thx::test
