#include "server/receiver.hpp"

#include <poll.h>

#include <lcm/lcm-cpp.hpp>
#include <thx_msgs/client_force_t.hpp>
#include <thx_msgs/protocol.hpp>

#include "device/clock.hpp"

namespace thx::srv {

namespace {
std::int64_t monotonicNs() { return dev::monotonicNowNs(); }
constexpr std::int64_t kDefaultTimeoutNs = 50'000'000;  // 50 ms: a few physics steps
}  // namespace

Receiver::Receiver(lcm::LCM& lcm, dev::LatestSlot<ClientForce>& slot, double max_force_n)
    : lcm_(lcm), slot_(slot), table_(max_force_n, kDefaultTimeoutNs) {
  lcm_.subscribe(thx_msgs::kChannelClientForce, &Receiver::onClientForce, this);
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
  return table_.counters();
}

void Receiver::onClientForce(const lcm::ReceiveBuffer* rbuf, const std::string&) {
  thx_msgs::client_force_t m;
  if (thx_msgs::try_decode(rbuf->data, rbuf->data_size, m) < 0) {
    undecodable_.fetch_add(1);
    return;
  }
  const std::int64_t now = monotonicNs();
  bool accepted = false;
  {
    std::lock_guard<std::mutex> lock(table_mutex_);
    accepted = table_.accept(m, now);
  }
  if (accepted) publishSum(now);
}

void Receiver::publishSum(std::int64_t now_ns) {
  Eigen::Vector3d sum;
  int live = 0;
  {
    std::lock_guard<std::mutex> lock(table_mutex_);
    sum = table_.sum(now_ns);
    live = table_.liveEntries();
  }
  if (live == 0 && !was_live_) return;
  ClientForce f;
  f.force_world_n[0] = sum.x();
  f.force_world_n[1] = sum.y();
  f.force_world_n[2] = sum.z();
  slot_.write(f);
  was_live_ = live > 0;
}

void Receiver::run() {
  const int fd = lcm_.getFileno();
  while (!stop_.load()) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 10) > 0) {
      while (lcm_.handleTimeout(0) > 0) {
      }
    }
    publishSum(monotonicNs());
  }
}

}  // namespace thx::srv
