// rates: how often each part of the system updates.
#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

Rates parseRates(const std::optional<Field>& field) {
  Rates r;
  if (!field) return r;
  field->expectKeys({"servo_hz", "physics_hz", "visual_hz", "audio_hz", "audio_feed_hz"});
  const auto read = [&](const char* key, int& rate, long long min, long long max) {
    if (auto f = field->find(key)) rate = static_cast<int>(f->integer(min, max, "Hz"));
  };
  read("servo_hz", r.servo_hz, 100, 10000);
  read("physics_hz", r.physics_hz, 10, 10000);
  read("visual_hz", r.visual_hz, 1, 1000);
  read("audio_hz", r.audio_hz, 8000, 192000);
  read("audio_feed_hz", r.audio_feed_hz, 10, 10000);
  return r;
}

}  // namespace thx::scene::detail
