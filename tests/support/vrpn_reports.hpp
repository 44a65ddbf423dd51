#pragma once
// Tracker reports a VRPN client reads from hapticd --vrpn-listen while it runs: connects over TCP
// (retrying while hapticd starts), names the senders it wants, pings each once connected, and
// collects each sender's Pos_Quat reports until they are enough for the test, which then stops
// hapticd (it runs with --duration 0): no fixed window to miss however slowly either side starts
// (the sanitizer build under load once took most of a fixed 2.5 s window to start; a client
// starved for 3 s missed a 3 s run). Test support only.
#include <poll.h>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "device/vrpn/base_messages.hpp"
#include "device/vrpn/tcp_connection.hpp"
#include "device/vrpn/tracker_messages.hpp"

namespace thx::test {

struct SenderReports {
  int reports = 0;
  double x_min = 1e9, x_max = -1e9;  // the pen's x over its reports
  int undecodable = 0;
};

struct VrpnReports {
  bool connected = false;
  int unnamed_senders = 0;                      // reports from a sender the client did not name
  std::map<std::string, SenderReports> by_name;  // every name asked for is present
};

// Reads until `enough(reports so far)`, or for `timeout` at most.
inline VrpnReports readVrpnReportsUntil(std::uint16_t port, const std::vector<std::string>& names,
                                        const std::function<bool(const VrpnReports&)>& enough,
                                        std::chrono::seconds timeout) {
  using namespace thx::vrpn;
  VrpnReports out;
  for (const std::string& n : names) out.by_name[n];
  std::unique_ptr<TcpConnection> conn;
  std::map<std::int32_t, std::string> ids;
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!enough(out) && std::chrono::steady_clock::now() < until) {
    if (!conn || !conn->open()) {
      Result<UniqueFd> fd = connectTcp("127.0.0.1", port);
      if (!fd) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        continue;
      }
      conn = std::make_unique<TcpConnection>(std::move(fd).value());
      ids.clear();
      for (const std::string& n : names) ids[conn->endpoint().addSender(n)] = n;
      conn->endpoint().addType(TrackerPosQuat::kTypeName);
    }
    pollfd p{conn->fd(), short(POLLIN | (conn->wantsWrite() ? POLLOUT : 0)), 0};
    ::poll(&p, 1, 5);
    conn->pump();
    while (std::optional<Event> ev = conn->endpoint().poll()) {
      if (std::holds_alternative<Connected>(*ev)) {
        out.connected = true;
        for (const auto& [id, n] : ids) conn->endpoint().sendMessage(id, Ping{});
      } else if (const auto* m = std::get_if<UserMessage>(&*ev); m && m->type_name == TrackerPosQuat::kTypeName) {
        const auto who = ids.find(m->sender);
        if (who == ids.end()) {
          ++out.unnamed_senders;
          continue;
        }
        SenderReports& s = out.by_name[who->second];
        Result<TrackerPosQuat> r = TrackerPosQuat::decode(m->payload);
        if (!r) {
          ++s.undecodable;
          continue;
        }
        ++s.reports;
        s.x_min = std::min(s.x_min, r->pos[0]);
        s.x_max = std::max(s.x_max, r->pos[0]);
      }
    }
  }
  if (conn) conn->close(thx::vrpn::Error{ErrorCode::kPeerClosed, "test done"});
  return out;
}

}  // namespace thx::test
