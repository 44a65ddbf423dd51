#include "server/untrusted_input.hpp"

namespace thx::srv {

InputProblemLog::PerChannel* InputProblemLog::find(const char* channel) {
  for (PerChannel& c : channels_) {
    if (c.used && c.channel == channel) return &c;
  }
  for (PerChannel& c : channels_) {
    if (!c.used) {
      c.used = true;
      c.channel = channel;
      return &c;
    }
  }
  return &channels_[3];  // more channels than expected: share the last line's budget
}

void InputProblemLog::report(const char* channel, const std::string& problem, std::int64_t now_ns) {
  ++total_;
  PerChannel* c = find(channel);
  if (c->shown_in_window == 0 || now_ns - c->window_start_ns >= interval_ns_) {
    c->window_start_ns = now_ns;
    c->shown_in_window = 0;
  }
  if (c->shown_in_window >= burst_) {
    ++c->unshown;
    return;
  }
  ++c->shown_in_window;
  if (c->unshown > 0) {
    std::fprintf(stderr, "hapticd: warning: ignored a message on %s: %s (and %llu more ignored since the last report)\n",
                 channel, problem.c_str(), (unsigned long long)c->unshown);
  } else {
    std::fprintf(stderr, "hapticd: warning: ignored a message on %s: %s\n", channel, problem.c_str());
  }
  c->unshown = 0;
}

void InputProblemLog::flush() {
  for (PerChannel& c : channels_) {
    if (c.used && c.unshown > 0) {
      std::fprintf(stderr, "hapticd: warning: ignored %llu more messages on %s\n", (unsigned long long)c.unshown,
                   c.channel.c_str());
      c.unshown = 0;
    }
  }
}

}  // namespace thx::srv
