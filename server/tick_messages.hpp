#pragma once
// One servo tick (TickRecord) as the wire messages of the DEVICE_STATE and CONTACT streams
// (docs/messages.md §5.1, §5.2). Used by the publisher thread, never by the servo.
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>

#include "server/tick_record.hpp"

namespace thx::srv {

// `simulated` sets FLAG_SIMULATED. utime is the tick's deadline in µs (CLOCK_MONOTONIC in real
// time, the virtual clock in lock-step).
void toDeviceState(const TickRecord& r, bool simulated, thx_msgs::device_state_t& out);
void toContact(const TickRecord& r, thx_msgs::contact_t& out);

}  // namespace thx::srv
