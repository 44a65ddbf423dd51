#include "device/vrpn/tracker_transform_messages.hpp"

#include <string>

#include "device/vrpn/payload_size.hpp"
#include "device/vrpn/tracker_fields.hpp"

namespace thx::vrpn {

namespace {

template <class Request>
Result<Request> decodeEmpty(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(Request::kTypeName, payload, 0)) return *e;
  return Request{};
}

}  // namespace

void TrackerToRoom::encode(ByteWriter& w) const {
  putAll(w, pos);
  putAll(w, quat);
}

Result<TrackerToRoom> TrackerToRoom::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  TrackerToRoom m;
  getAll(r, m.pos);
  getAll(r, m.quat);
  return m;
}

void TrackerUnitToSensor::encode(ByteWriter& w) const {
  w.i32(sensor);
  w.i32(0);  // stock senders write 0 here (docs/vrpn.md §7), not the sensor again
  putAll(w, pos);
  putAll(w, quat);
}

Result<TrackerUnitToSensor> TrackerUnitToSensor::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  TrackerUnitToSensor m;
  m.sensor = r.i32();
  r.skip(4);
  getAll(r, m.pos);
  getAll(r, m.quat);
  if (auto e = checkSensor(kTypeName, m.sensor)) return *e;
  return m;
}

void TrackerWorkspace::encode(ByteWriter& w) const {
  putAll(w, min);
  putAll(w, max);
}

Result<TrackerWorkspace> TrackerWorkspace::decode(std::span<const std::uint8_t> payload) {
  if (auto e = checkSize(kTypeName, payload, kSize)) return *e;
  ByteReader r(payload);
  TrackerWorkspace m;
  getAll(r, m.min);
  getAll(r, m.max);
  return m;
}

Result<TrackerRequestToRoom> TrackerRequestToRoom::decode(std::span<const std::uint8_t> payload) {
  return decodeEmpty<TrackerRequestToRoom>(payload);
}
Result<TrackerRequestUnitToSensor> TrackerRequestUnitToSensor::decode(std::span<const std::uint8_t> payload) {
  return decodeEmpty<TrackerRequestUnitToSensor>(payload);
}
Result<TrackerRequestWorkspace> TrackerRequestWorkspace::decode(std::span<const std::uint8_t> payload) {
  return decodeEmpty<TrackerRequestWorkspace>(payload);
}

}  // namespace thx::vrpn
