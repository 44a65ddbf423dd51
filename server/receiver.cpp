#include "server/receiver.hpp"

#include <poll.h>
#include <sys/select.h>

#include <chrono>
#include <cstdio>

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/client_force_t.hpp>
#include <thx_msgs/lcm_subscribe.hpp>
#include <thx_msgs/protocol.hpp>

#include "rt/clock.hpp"
#include "base/error.hpp"
#include "server/realtime.hpp"

namespace thx::srv {

namespace {
std::int64_t monotonicNs() { return rt::monotonicNowNs(); }
constexpr std::int64_t kDefaultTimeoutNs = 50'000'000;  // 50 ms: a few physics steps
}  // namespace

Receiver::Receiver(lcm::LCM& lcm, std::vector<ForcedDevice> devices) : lcm_(lcm), lcms_{&lcm} {
  if (devices.empty() || devices.size() > kMaxDevices)
    throw thx::Error(thx::Error::Kind::Config, "Receiver: " + std::to_string(devices.size()) +
                                                   " devices; expected 1 to " + std::to_string(kMaxDevices));
  for (std::size_t i = 0; i < devices.size(); ++i) {
    slots_.push_back(devices[i].slot);
    tables_.emplace_back(devices[i].max_force_n, kDefaultTimeoutNs, int(i));
  }
  was_live_.assign(devices.size(), false);
  listen(lcm_);
}

void Receiver::listen(lcm::LCM& lcm) {
  if (!thx_msgs::subscribeUntyped(lcm, thx_msgs::kChannelClientForce, &Receiver::onClientForce, this)) {
    std::fprintf(stderr,
                 "hapticd: warning: LCM could not listen for %s (its receive socket did not bind: is the port "
                 "held by another program?): client forces sent there are not felt\n",
                 thx_msgs::kChannelClientForce);
  }
}

void Receiver::listenAlsoOn(lcm::LCM& control) {
  listen(control);
  lcms_.push_back(&control);
}

Receiver::~Receiver() { stop(); }

void Receiver::start() { thread_ = std::thread([this] { run(); }); }

void Receiver::stop() {
  if (!thread_.joinable()) return;
  stop_.store(true);
  thread_.join();
}

ClientForceCounters Receiver::counters() const {
  std::lock_guard<std::mutex> lock(table_mutex_);
  ClientForceCounters sum = tables_[0].counters();
  for (std::size_t i = 1; i < tables_.size(); ++i) sum += tables_[i].counters();
  return sum;
}

void Receiver::onClientForce(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::client_force_t m;
  const std::int64_t now = monotonicNs();
  if (const std::string problem = decodeUntrusted(rbuf->data, rbuf->data_size, m); !problem.empty()) {
    undecodable_.fetch_add(1);
    problems_.report(thx_msgs::kChannelClientForce, problem, now);
    return;
  }
  // A device index out of range goes to device 0's table, which refuses and counts it.
  const std::size_t device = m.device >= 0 && std::size_t(m.device) < tables_.size() ? std::size_t(m.device) : 0;
  ClientForceTable& table = tables_[device];
  bool accepted = false;
  ClientForceCounters before, after;
  {
    std::lock_guard<std::mutex> lock(table_mutex_);
    before = table.counters();
    accepted = table.accept(m, now);
    after = table.counters();
  }
  if (accepted) {
    publishSum(device, now);
    return;
  }
  // Refusals a sender should hear about (a stale seq is ordinary reordering: counted only).
  char buf[256];
  if (after.bad_ids != before.bad_ids) {
    std::snprintf(buf, sizeof buf, "client_force_t with an invalid client_id or source (1 to 32 of [A-Za-z0-9_-], source also '.')");
  } else if (after.bad_values != before.bad_values) {
    std::snprintf(buf, sizeof buf, "client_force_t from %s/%s: force (%g, %g, %g) N is not finite or above the device's peak %g N",
                  m.client_id.c_str(), m.source.c_str(), m.f_world[0], m.f_world[1], m.f_world[2], table.maxForceN());
  } else if (after.other_device != before.other_device) {
    std::snprintf(buf, sizeof buf, "client_force_t from %s/%s: device %d; this server's devices are 0 to %d",
                  m.client_id.c_str(), m.source.c_str(), int(m.device), int(tables_.size()) - 1);
  } else if (after.table_full != before.table_full) {
    std::snprintf(buf, sizeof buf, "client_force_t from %s/%s: already %d senders, the most the server keeps",
                  m.client_id.c_str(), m.source.c_str(), ClientForceTable::kMaxEntries);
  } else {
    return;
  }
  problems_.report(thx_msgs::kChannelClientForce, buf, now);
}

void Receiver::publishSums(std::int64_t now_ns) {
  for (std::size_t i = 0; i < tables_.size(); ++i) publishSum(i, now_ns);
}

void Receiver::publishSum(std::size_t device, std::int64_t now_ns) {
  Eigen::Vector3d sum;
  int live = 0;
  {
    std::lock_guard<std::mutex> lock(table_mutex_);
    sum = tables_[device].sum(now_ns);
    live = tables_[device].liveEntries();
  }
  if (live == 0 && !was_live_[device]) return;
  ClientForce f;
  f.force_world_n[0] = sum.x();
  f.force_world_n[1] = sum.y();
  f.force_world_n[2] = sum.z();
  slots_[device]->write(f);
  was_live_[device] = live > 0;
}

// Asks for each descriptor every time: with tcpq:// it changes on every reconnect and is -1 while
// the server is unreachable, and handleTimeout() would FD_SET(-1) (a glibc abort).
void Receiver::drain() {
  for (lcm::LCM* l : lcms_) {
    while (l->getFileno() >= 0 && l->getFileno() < FD_SETSIZE && l->handleTimeout(0) > 0) {
    }
  }
}

void Receiver::run() {
  if (fifo_priority_ > 0) {
    RealtimeOptions rt;
    rt.priority = fifo_priority_;
    rt.lock_memory = false;
    makeThreadRealtime(rt);  // refused without the privilege: runs as before
  }
  std::vector<pollfd> fds;
  while (!stop_.load()) {
    fds.clear();
    for (lcm::LCM* l : lcms_) {
      const int fd = l->getFileno();
      if (fd >= 0 && fd < FD_SETSIZE) fds.push_back(pollfd{fd, POLLIN, 0});
    }
    if (fds.empty()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    } else if (poll(fds.data(), nfds_t(fds.size()), 10) > 0) {
      drain();
    }
    publishSums(monotonicNs());
  }
  // What arrived before the stop is still taken (and counted): a client's last message, such as
  // the release a physics client sends on its way out, is not lost to the moment of shutdown.
  drain();
}

}  // namespace thx::srv
