#include "clients/audio/tools/session_pens.hpp"

#include <map>

#include <thx_msgs/contact_t.hpp>

#include "thx_client/devices.hpp"
#include "thx_client/logged_devices.hpp"
#include "thx_msgs/log_reader.hpp"

namespace thx::audio {

std::size_t SessionPens::ticks() const {
  std::size_t n = 0;
  for (const PenPath& p : pens) n += p.samples.size();
  return n;
}

SessionPens readSessionPens(const std::string& log_path, std::optional<int> only) {
  // Checks `only` against the log's devices; `every`: a one-device log, all of it device 0's.
  const thx::client::LoggedDevice logged = thx::client::loggedDevice(log_path, only.value_or(0));
  SessionPens out;
  std::map<int, std::vector<TimedScrapeSample>> by_device;
  thx_msgs::forEachLogMessage<thx_msgs::contact_t>(log_path, "THX_CONTACT", [&](const thx_msgs::contact_t& c, const auto&) {
    const int device = logged.every ? 0 : c.device;
    if (device < 0 || device >= thx::client::kMaxDevices) return;  // no device of any scene
    if (!out.origin_tick) out.origin_tick = c.tick, out.origin_utime = c.utime;
    if (only && !logged.takes(c.device)) return;
    by_device[device].push_back({c.utime, scrapeSample(c)});
  });
  for (auto& [device, samples] : by_device) out.pens.push_back({device, std::move(samples)});
  return out;
}

}  // namespace thx::audio
