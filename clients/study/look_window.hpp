#pragma once
// The candidate look on the participant's screen during a real Study 1 trial (docs/study.md §7):
// visual-client --live --window --allow-different-scene on the candidate's scene, so it draws
// that look while the pen and the ball move as hapticd and the physics client say. One process
// per look: cycling to the next look ends this one and starts the next. Without a visual-client
// path the runner asks the operator to show the look instead (an OPERATOR step).
#include <sys/types.h>

#include <string>
#include <vector>

namespace thx::study {

class LookWindow {
 public:
  // `visual_client`: the program; `extra`: options added to every start (e.g. --lcm-url URL).
  LookWindow(std::string visual_client, std::vector<std::string> extra)
      : program_(std::move(visual_client)), extra_(std::move(extra)) {}
  ~LookWindow() { stop(); }
  LookWindow(const LookWindow&) = delete;
  LookWindow& operator=(const LookWindow&) = delete;

  // Ends the window shown (if any) and shows `scene_path`'s look; `objects` false hides the
  // scene's objects (a trial without the ball). Throws thx::Error when the program cannot start.
  void show(const std::string& scene_path, bool objects);
  // Ends the window (SIGTERM, then waits for it).
  void stop();

 private:
  std::string program_;
  std::vector<std::string> extra_;
  pid_t pid_ = -1;
};

}  // namespace thx::study
