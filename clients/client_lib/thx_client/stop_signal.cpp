#include "thx_client/stop_signal.hpp"

#include <atomic>
#include <csignal>

namespace thx::client {

namespace {
std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the handler must not lock");
void onSignal(int) { g_stop.store(true); }
}  // namespace

void installStopSignals() {
  struct sigaction sa {};
  sa.sa_handler = onSignal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stopRequested() { return g_stop.load(); }
void requestStop() { g_stop.store(true); }
void clearStopRequest() { g_stop.store(false); }

}  // namespace thx::client
