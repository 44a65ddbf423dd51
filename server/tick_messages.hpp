#pragma once
// One servo tick (TickRecord) as the wire messages of the DEVICE_STATE and CONTACT streams
// (docs/messages.md §5.1, §5.2). Used by the publisher thread, never by the servo.
#include <thx_msgs/contact_t.hpp>
#include <thx_msgs/device_state_t.hpp>

#include "server/tick_record.hpp"

namespace thx::srv {

// device_state_t.FAULT_* of one TickFault bit (FAULT_NONE for 0), and the fault_mask bits
// (1 << FAULT_*) of a set of TickFault bits.
std::int32_t wireFaultCode(std::uint32_t tick_fault);
std::int32_t wireFaultMask(std::uint32_t tick_faults);

// One tick: flags_seen = flags and fault_mask = this tick's faults; a decimated subscription ORs
// them over the ticks it skips (server/subscriptions.cpp). `simulated` sets FLAG_SIMULATED. utime is the tick's deadline in µs (CLOCK_MONOTONIC in real
// time, the virtual clock in lock-step). proxy_world is the renderer's proxy while it is held on the
// surface (FLAG_PROXY_HELD), else p_world itself.
void toDeviceState(const TickRecord& r, bool simulated, thx_msgs::device_state_t& out);
void toContact(const TickRecord& r, thx_msgs::contact_t& out);

}  // namespace thx::srv
