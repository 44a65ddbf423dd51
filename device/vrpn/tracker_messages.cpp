#include "device/vrpn/tracker_messages.hpp"

#include <string>

#include "device/vrpn/payload_size.hpp"
#include "device/vrpn/tracker_fields.hpp"

namespace thx::vrpn {

void TrackerPosQuat::encode(ByteWriter& w) const {
  w.i32(sensor);
  w.i32(sensor);  // the pad word: stock senders repeat the sensor
  putAll(w, pos);
  putAll(w, quat);
}

Result<TrackerPosQuat> TrackerPosQuat::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  TrackerPosQuat m;
  m.sensor = r.i32();
  r.skip(4);
  getAll(r, m.pos);
  getAll(r, m.quat);
  if (auto e = checkSensor(kTypeName, m.sensor)) return *e;
  return m;
}

void TrackerVelocity::encode(ByteWriter& w) const {
  w.i32(sensor);
  w.i32(sensor);
  putAll(w, vel);
  putAll(w, vel_quat);
  w.f64(vel_quat_dt);
}

Result<TrackerVelocity> TrackerVelocity::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  TrackerVelocity m;
  m.sensor = r.i32();
  r.skip(4);
  getAll(r, m.vel);
  getAll(r, m.vel_quat);
  m.vel_quat_dt = r.f64();
  if (auto e = checkSensor(kTypeName, m.sensor)) return *e;
  return m;
}

void TrackerUpdateRate::encode(ByteWriter& w) const { w.f64(hz); }

Result<TrackerUpdateRate> TrackerUpdateRate::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  return TrackerUpdateRate{r.f64()};
}

Result<TrackerResetOrigin> TrackerResetOrigin::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, 0)) return *e;
  return TrackerResetOrigin{};
}

}  // namespace thx::vrpn
