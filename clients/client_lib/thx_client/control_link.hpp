#pragma once
// Where a client sends what is for the server alone: subscription requests, heartbeats, commands,
// client forces (issue 17, docs/clients.md §6).
//
// hapticd names a control URL in its hello (hello_t.control_url): a udpm port only hapticd
// listens on, so 64 clients' heartbeats do not wake the other 63. ControlLink publishes there
// through an LCM that never subscribes, which LCM 1.3.1 opens with its send socket only (no
// receive socket, no receive thread: tests/clients/test_data_ports.cpp checks it). Until a hello
// names a control URL (or when it names none, or it cannot be opened) it sends on the bus, where
// hapticd listens as well: the first request may go out before any hello.
#include <memory>
#include <string>

#include <lcm/lcm-cpp.hpp>

namespace thx::client {

class ControlLink {
 public:
  explicit ControlLink(lcm::LCM& bus) : bus_(bus) {}
  ControlLink(const ControlLink&) = delete;
  ControlLink& operator=(const ControlLink&) = delete;

  // From each hello: opens `url` when it changed ("" = the bus). Returns "" or why `url` could
  // not be opened (the bus is used then).
  std::string use(const std::string& url);
  const std::string& url() const { return url_; }
  bool open() const { return control_ != nullptr; }

  // Publishes on the control URL, else on the bus; LCM's result (0 = sent).
  template <class M>
  int publish(const std::string& channel, const M& m) {
    return (control_ ? *control_ : bus_).publish(channel, &m);
  }

 private:
  lcm::LCM& bus_;
  std::string url_;
  std::unique_ptr<lcm::LCM> control_;
};

}  // namespace thx::client
