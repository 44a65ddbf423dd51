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

pid_t spawn(const std::vector<std::string>& argv, const std::string& log_path) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    const int fd = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    const int null_fd = open("/dev/null", O_RDONLY);
    if (null_fd >= 0) {
      dup2(null_fd, 0);
      close(null_fd);
    }
    execvp(args[0], args.data());
    std::fprintf(stderr, "exec %s: %s\n", args[0], std::strerror(errno));
    _exit(127);
  }
  return pid;
}

namespace {
int decode(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}
}  // namespace

std::optional<int> poll(pid_t pid) {
  int status = 0;
  const pid_t r = waitpid(pid, &status, WNOHANG);
  if (r == pid) return decode(status);
  if (r < 0) return -1;
  return std::nullopt;
}

int waitFor(pid_t pid) {
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return decode(status);
}

std::string commandLine(const std::vector<std::string>& argv) {
  std::string s;
  for (const std::string& a : argv) {
    if (!s.empty()) s += ' ';
    s += a.find(' ') == std::string::npos ? a : "'" + a + "'";
  }
  return s;
}

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

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
    const std::string s = readFile(path + "/stat");
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
    std::string n = readFile(path + "/comm");
    while (!n.empty() && (n.back() == '\n' || n.back() == '\r')) n.pop_back();
    out[tid] = n;
  });
  return out;
}

namespace {
std::optional<std::size_t> valueStart(const std::string& text, const std::string& object, const std::string& key) {
  std::size_t from = 0, to = text.size();
  if (!object.empty()) {
    // The key "object" followed by ':' (a string value "object" does not count).
    const std::string quoted = "\"" + object + "\"";
    std::size_t o = text.find(quoted);
    while (o != std::string::npos) {
      const std::size_t next = text.find_first_not_of(" \t\r\n", o + quoted.size());
      if (next != std::string::npos && text[next] == ':') break;
      o = text.find(quoted, o + 1);
    }
    if (o == std::string::npos) return std::nullopt;
    from = text.find('{', o);
    if (from == std::string::npos) return std::nullopt;
    to = text.find('}', from);
    if (to == std::string::npos) return std::nullopt;
  }
  const std::string needle = "\"" + key + "\"";
  std::size_t k = text.find(needle, from);
  // At top level, skip matches inside nested objects by requiring brace depth 1.
  while (k != std::string::npos && k < to) {
    int depth = 0;
    for (std::size_t i = from; i < k; ++i) depth += text[i] == '{' ? 1 : (text[i] == '}' ? -1 : 0);
    if (object.empty() ? depth == 1 : true) break;
    k = text.find(needle, k + 1);
  }
  if (k == std::string::npos || k >= to) return std::nullopt;
  const std::size_t colon = text.find(':', k + needle.size());
  if (colon == std::string::npos) return std::nullopt;
  return text.find_first_not_of(" \t\r\n", colon + 1);
}
}  // namespace

std::optional<double> jsonNumber(const std::string& text, const std::string& object, const std::string& key) {
  const auto s = valueStart(text, object, key);
  if (!s || *s == std::string::npos) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str() + *s, &end);
  if (end == text.c_str() + *s) return std::nullopt;
  return v;
}

std::optional<bool> jsonBool(const std::string& text, const std::string& object, const std::string& key) {
  const auto s = valueStart(text, object, key);
  if (!s || *s == std::string::npos) return std::nullopt;
  if (text.compare(*s, 4, "true") == 0) return true;
  if (text.compare(*s, 5, "false") == 0) return false;
  return std::nullopt;
}

}  // namespace thx::bench
