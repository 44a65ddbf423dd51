#pragma once
// Opening LCM, with the error every program gives for an unusable URL: it names the URL and, for
// udpm, the missing multicast route it nearly always means on a fresh machine.
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>

#include "base/error.hpp"

namespace thx_msgs {

// Throws thx::Error (Io): "LCM is not available at 'URL' (no multicast route? try `ip route add
// 224.0.0.0/4 dev lo` as root, or --lcm-url)".
inline std::unique_ptr<lcm::LCM> openLcm(const std::string& url) {
  auto lcm = std::make_unique<lcm::LCM>(url);
  if (lcm->good()) return lcm;
  std::string hint = " (check --lcm-url)";
  if (url.rfind("udpm://", 0) == 0)
    hint = " (no multicast route? try `ip route add 224.0.0.0/4 dev lo` as root, or --lcm-url)";
  throw thx::Error(thx::Error::Kind::Io, "LCM is not available at '" + url + "'" + hint);
}

}  // namespace thx_msgs
