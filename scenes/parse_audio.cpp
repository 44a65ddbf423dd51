// audio: what the audio client does with the scene. A muted scene is how a study removes the
// sound cue by a scene switch (clients/study/scene_stage.hpp), as it removes the pen and the ball.
#include "scenes/scene_sections.hpp"

namespace thx::scene::detail {

Audio parseAudio(const std::optional<Field>& field) {
  Audio a;
  if (!field) return a;
  field->expectKeys({"mute"});
  if (auto f = field->find("mute")) a.mute = f->choice<bool>({{"false", false}, {"true", true}});
  return a;
}

}  // namespace thx::scene::detail
