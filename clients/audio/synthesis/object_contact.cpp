#include "clients/audio/synthesis/object_contact.hpp"

#include <algorithm>

namespace thx::audio {

ContactTravel contactTravel(double slip, double travel, const ObjectContactOptions& o) {
  const double speed = std::max(slip, travel);
  if (!(speed >= o.min_speed_m_per_s) || !(speed > 0.0)) return {};
  return {speed, (slip + o.rolling_share * (speed - slip)) / speed};
}

}  // namespace thx::audio
