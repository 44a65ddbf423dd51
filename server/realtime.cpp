#include "server/realtime.hpp"

#include "base/error.hpp"

#include <malloc.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace thx::srv {

RealtimeReport makeThreadRealtime(const RealtimeOptions& options) {
  RealtimeReport report;
  if (options.lock_memory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE | (options.lock_on_fault ? MCL_ONFAULT : 0)) == 0) {
      report.memory_locked = true;
    } else {
      report.warnings.push_back(std::string("mlockall failed (") + std::strerror(errno) +
                                "): page faults may delay ticks; run as root or raise RLIMIT_MEMLOCK (ulimit -l)");
    }
  }
  if (options.fifo) {
    sched_param param{};
    param.sched_priority = options.priority;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (rc == 0) {
      report.fifo = true;
    } else {
      report.warnings.push_back(std::string("SCHED_FIFO priority ") + std::to_string(options.priority) +
                                " refused (" + std::strerror(rc) +
                                "): the servo runs at normal priority; run as root or grant CAP_SYS_NICE / "
                                "an rtprio limit (/etc/security/limits.conf)");
    }
  }
  if (options.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(options.cpu, &set);
    const int rc = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    if (rc == 0) {
      report.pinned = true;
    } else {
      report.warnings.push_back("pinning to CPU " + std::to_string(options.cpu) + " failed (" + std::strerror(rc) + ")");
    }
  }
  if (options.require && !report.warnings.empty()) {
    throw thx::Error(thx::Error::Kind::Io, "real-time setup failed (--require-rt): " + report.warnings.front());
  }
  return report;
}

void prepareProcessForLockedMemory() {
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, 512 * 1024);
  pthread_setattr_default_np(&attr);
  pthread_attr_destroy(&attr);
  mallopt(M_ARENA_MAX, 1);
}

}  // namespace thx::srv
