#include "benchmarks/proc_tools.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace thx::bench {

std::vector<Mapping> readSmaps(pid_t pid) {
  std::vector<Mapping> maps;
  std::ifstream f("/proc/" + std::to_string(pid) + "/smaps");
  std::string line;
  while (std::getline(f, line)) {
    // A mapping header is "start-end perms offset dev inode [path]": its first token has a '-'
    // and no ':' (field lines are "Key:   value").
    const std::string first = line.substr(0, line.find(' '));
    if (first.find('-') != std::string::npos && first.find(':') == std::string::npos) {
      unsigned long long a = 0, b = 0;
      char perms[8] = {};
      int consumed = 0;
      if (std::sscanf(line.c_str(), "%llx-%llx %7s %*s %*s %*s%n", &a, &b, perms, &consumed) >= 3 && consumed > 0) {
        Mapping m;
        m.start = a;
        m.end = b;
        m.perms = perms;
        const std::size_t p = line.find_first_not_of(' ', std::size_t(consumed));
        m.path = p == std::string::npos ? "" : line.substr(p);
        maps.push_back(m);
      }
      continue;
    }
    if (maps.empty()) continue;
    char key[64] = {};
    long long kb = 0;
    if (std::sscanf(line.c_str(), "%63[^:]: %lld kB", key, &kb) == 2) {
      Mapping& m = maps.back();
      const std::string k = key;
      if (k == "Size") m.size = kb * 1024;
      else if (k == "Rss") m.rss = kb * 1024;
      else if (k == "Pss") m.pss = kb * 1024;
      else if (k == "Locked") m.locked = kb * 1024;
      else if (k == "Anonymous") m.anonymous = kb * 1024;
    }
  }
  return maps;
}

std::int64_t statusField(pid_t pid, const std::string& key) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind(key + ":", 0) != 0) continue;
    long long v = 0;
    char unit[8] = {};
    const int n = std::sscanf(line.c_str() + key.size() + 1, "%lld %7s", &v, unit);
    if (n < 1) return -1;
    return n == 2 && std::strcmp(unit, "kB") == 0 ? v * 1024 : v;
  }
  return -1;
}

namespace {
template <class Visit>
void forEachTask(pid_t pid, Visit&& visit) {
  const std::string dir = "/proc/" + std::to_string(pid) + "/task";
  DIR* d = opendir(dir.c_str());
  if (!d) return;
  while (dirent* e = readdir(d)) {
    if (e->d_name[0] == '.') continue;
    visit(std::atoi(e->d_name), dir + "/" + e->d_name);
  }
  closedir(d);
}
}  // namespace

std::map<int, int> threadPolicies(pid_t pid) {
  std::map<int, int> out;
  forEachTask(pid, [&](int tid, const std::string& path) {
    const std::string s = test::slurp(path + "/stat");
    const std::size_t close_paren = s.rfind(')');
    if (close_paren == std::string::npos) return;
    // Fields after "(comm)": state is field 3; policy is field 41.
    std::istringstream is(s.substr(close_paren + 2));
    std::string tok;
    for (int field = 3; is >> tok; ++field) {
      if (field == 41) {
        out[tid] = std::atoi(tok.c_str());
        return;
      }
    }
  });
  return out;
}

std::map<int, std::string> threadNames(pid_t pid) {
  std::map<int, std::string> out;
  forEachTask(pid, [&](int tid, const std::string& path) {
    std::string n = test::slurp(path + "/comm");
    while (!n.empty() && (n.back() == '\n' || n.back() == '\r')) n.pop_back();
    out[tid] = n;
  });
  return out;
}

}  // namespace thx::bench
