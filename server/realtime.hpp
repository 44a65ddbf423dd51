#pragma once
// Making the calling thread real-time: SCHED_FIFO, memory locked, optional CPU pinning.
// Each step is checked; whether a failure is fatal is the caller's policy (libfranka's
// RealtimeConfig::kEnforce / kIgnore), so a laptop without privileges still runs, and says so.
#include <string>
#include <vector>

namespace thx::srv {

struct RealtimeOptions {
  bool fifo = true;          // try SCHED_FIFO
  int priority = 80;         // above ordinary RT work (ros2_control uses 50), below the kernel's own 99
  bool lock_memory = true;   // mlockall(MCL_CURRENT | MCL_FUTURE): no page faults in the tick
  // MCL_ONFAULT: lock pages when first touched instead of faulting in every mapped page now
  // (whole shared libraries included). Cheaper in memory; the first touch of a page still faults
  // once, so the servo warms up before its first deadline counts.
  bool lock_on_fault = true;
  int cpu = -1;              // pin to this CPU; -1 = no pinning
  bool require = false;      // any failure is an error (throw) instead of a warning
};

struct RealtimeReport {
  bool fifo = false;
  bool memory_locked = false;
  bool pinned = false;
  std::vector<std::string> warnings;  // what failed and what to do about it
};

// For a process that locks its memory, before its threads start: every thread (its own, LCM's
// GLib thread) gets a 512 KiB stack instead of glibc's 8 MiB default (under mlockall(MCL_FUTURE)
// each stack is locked in full, so 8 MiB stacks cost 8 MB of RAM each), and malloc one arena
// (per-thread arenas reserve 64 MiB of address space each, which mlockall counts as locked even
// though it is never touched).
void prepareProcessForLockedMemory();

// Applies the options to the calling thread. Throws std::runtime_error when `require` is set
// and a step failed (the message says which and why).
RealtimeReport makeThreadRealtime(const RealtimeOptions& options);

}  // namespace thx::srv
