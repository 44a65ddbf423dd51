#pragma once
// A block of UDP ports that no other test of this machine is using, for a test's own LCM bus
// (udpm, ttl=0) and the ports hapticd takes after it (control +1, client data +2 ..).
//
// Two rules:
// - Below Linux's ephemeral range (net.ipv4.ip_local_port_range, 32768..60999 by default): every
//   LCM publisher binds an ephemeral UDP port, without SO_REUSEADDR, and when one of them had
//   taken a data port of a test, that test's client could not bind it ("bind: Address already in
//   use"; a failed CI run).
// - Reserved with an flock on a file per block, held until the test ends: tests running side by
//   side (ctest -j) never share a block, whatever their pids.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace thx::test {

class PortBlock {
 public:
  static constexpr int kFirstPort = 20000;
  static constexpr int kSize = 40;
  static constexpr int kCount = (32768 - kFirstPort) / kSize;  // 319 blocks, all below 32768

  // Starts looking at a block drawn from `seed` (the pid, say) so that a stale lock costs nothing.
  explicit PortBlock(unsigned seed) {
    for (int k = 0; k < kCount; ++k) {
      const int block = int((seed + unsigned(k)) % unsigned(kCount));
      const std::string lock =
          (std::filesystem::temp_directory_path() / ("thx-test-ports-" + std::to_string(block) + ".lock")).string();
      const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
      if (fd < 0) continue;
      if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
        fd_ = fd;
        first_ = kFirstPort + block * kSize;
        return;
      }
      ::close(fd);
    }
    first_ = kFirstPort + int(seed % unsigned(kCount)) * kSize;  // every lock busy: take our chance
  }
  ~PortBlock() {
    if (fd_ >= 0) ::close(fd_);
  }
  PortBlock(const PortBlock&) = delete;
  PortBlock& operator=(const PortBlock&) = delete;

  int firstPort() const { return first_; }

 private:
  int fd_ = -1;
  int first_ = 0;
};

}  // namespace thx::test
