#pragma once
// The pens of a recorded session as audio-client --replay-log renders them (docs/audio.md §5,
// "Several pens"): hapticd --record writes every device's CONTACT samples, each with `device` its
// index (protocol 6, docs/clients.md §3.4, §7). A log whose hellos name one device, or none, is one
// pen's whatever its `device` fields hold (thx_client/logged_devices.hpp: the recorder as protocol
// 6 first shipped left them unset), so such a log renders exactly as before.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "clients/audio/offline/pen_mix.hpp"

namespace thx::audio {

struct SessionPens {
  std::vector<PenPath> pens;  // the devices with samples, by ascending index
  // The session's first CONTACT sample, of any device: sample 0 of the render, whichever pens are
  // kept (so a pen rendered alone lines up with the mix). Unset: the log has no CONTACT sample.
  std::optional<std::int64_t> origin_tick, origin_utime;
  std::size_t ticks() const;  // samples over the pens kept
};

// Every device's samples, or only device `only`'s (a Config error naming the log's devices when
// it has no such device). Throws thx_msgs::LogError when the log does not read.
SessionPens readSessionPens(const std::string& log_path, std::optional<int> only);

}  // namespace thx::audio
