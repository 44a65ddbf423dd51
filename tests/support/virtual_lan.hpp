#pragma once
// A switched LAN of several "hosts" inside this machine (issue 31, docs/clients.md §6, "A pulled cable"), for tests
// and benchmarks that run hapticd on one host and its clients on others:
//   - each host is a network namespace of its own, with `lo` up and one interface `eth0` at
//     10.31.0.H/24 (H = 1, 2, ...) and a multicast route (224.0.0.0/4) on it, as on a LAN;
//   - the hosts' cables (veth pairs) end in one Linux bridge, itself in a namespace of its own
//     (the switch), which floods multicast to every port (no IGMP snooping to wait for);
//   - unplug(H) / plug(H) take the host's switch port down and up: a pulled cable.
// Everything lives in namespaces this object creates, named thx<pid>n<K>s (the switch) and
// thx<pid>n<K>h<H>; the destructor deletes them, which removes their interfaces. Nothing of the
// machine's own network is touched, and two LANs (two tests at once) never see each other.
// Needs root (or CAP_SYS_ADMIN) and iproute2: unavailable() says why not, so a test can skip.
#include <unistd.h>

#include <atomic>
#include <string>
#include <vector>

#include "tests/support/process.hpp"

namespace thx::test {

class VirtualLan {
 public:
  explicit VirtualLan(int hosts) {
    static std::atomic<int> counter{0};
    prefix_ = "thx" + std::to_string(::getpid()) + "n" + std::to_string(counter++);
    if (shellStatus("command -v ip >/dev/null 2>&1") != 0) {
      why_ = "no `ip` command (Debian: iproute2)";
      return;
    }
    std::string script = "set -e\nip netns add " + switchName() + "\n" +
                         "ip -n " + switchName() + " link add br0 type bridge mcast_snooping 0\n" +
                         "ip -n " + switchName() + " link set br0 up\n";
    for (int h = 1; h <= hosts; ++h) {
      const std::string host = hostName(h), port = portName(h);
      script += "ip netns add " + host + "\n" +
                // Both ends are made in the switch, the host's end moved into the host at once.
                "ip -n " + switchName() + " link add " + port + " type veth peer name eth0 netns " + host + "\n" +
                "ip -n " + switchName() + " link set " + port + " master br0\n" +
                "ip -n " + switchName() + " link set " + port + " up\n" +
                "ip -n " + host + " link set lo up\n" +
                "ip -n " + host + " addr add " + address(h) + "/24 dev eth0\n" +
                "ip -n " + host + " link set eth0 up\n" +
                "ip -n " + host + " route add 224.0.0.0/4 dev eth0\n";
    }
    hosts_ = hosts;
    const int rc = shellStatus("( " + script + ") >/dev/null 2>&1");
    if (rc != 0) why_ = "cannot create network namespaces (`ip netns add` needs root or CAP_SYS_ADMIN)";
  }
  ~VirtualLan() {
    std::string script;
    for (int h = 1; h <= hosts_; ++h) script += "ip netns del " + hostName(h) + " 2>/dev/null; ";
    shellStatus(script + "ip netns del " + switchName() + " 2>/dev/null");
  }
  VirtualLan(const VirtualLan&) = delete;
  VirtualLan& operator=(const VirtualLan&) = delete;

  // "" when the LAN is up; otherwise why it could not be made.
  const std::string& unavailable() const { return why_; }
  int hosts() const { return hosts_; }
  std::string address(int host) const { return "10.31.0." + std::to_string(host); }
  std::string hostName(int host) const { return prefix_ + "h" + std::to_string(host); }

  // `argv` run on host H: the same command, inside its namespace (`ip netns exec` execs it, so the
  // pid spawn() returns is the program's own).
  std::vector<std::string> on(int host, std::vector<std::string> argv) const {
    argv.insert(argv.begin(), {"ip", "netns", "exec", hostName(host)});
    return argv;
  }

  // The host's cable pulled out of the switch, and put back. True when `ip` did it.
  bool unplug(int host) { return setPort(host, "down"); }
  bool plug(int host) { return setPort(host, "up"); }

 private:
  std::string switchName() const { return prefix_ + "s"; }
  std::string portName(int host) const { return "p" + std::to_string(host); }
  bool setPort(int host, const std::string& state) {
    return shellStatus("ip -n " + switchName() + " link set " + portName(host) + " " + state + " >/dev/null 2>&1") == 0;
  }

  std::string prefix_, why_;
  int hosts_ = 0;
};

}  // namespace thx::test
