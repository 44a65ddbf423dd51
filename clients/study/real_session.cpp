#include "clients/study/real_session.hpp"

#include <algorithm>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "clients/study/button_protocol.hpp"
#include "clients/study/look_window.hpp"
#include "clients/study/rating_prompt.hpp"
#include "clients/study/scene_stage.hpp"
#include "clients/study/session_csv.hpp"
#include "clients/study/trial_plan.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "thx_client/app.hpp"

namespace thx::study {
namespace {

using client::ClientApp;

class Console {
 public:
  // An operator step the software cannot do yet: printed, confirmed with Enter.
  void operatorStep(const std::string& what) {
    std::cout << "OPERATOR (not automated, docs/study.md §8): " << what << " -- press Enter when done: " << std::flush;
    std::string line;
    if (!std::getline(std::cin, line)) throw Error(Error::Kind::Io, "the terminal closed during an operator step");
  }
  int rating(const std::string& question, int min, int max) {
    const auto v = askRating(std::cin, std::cout, question, min, max);
    if (!v) throw Error(Error::Kind::Io, "the terminal closed before the rating '" + question + "' was given");
    return *v;
  }
};

// Waits for the next button event in hapticd's device_state_t stream (its utime as the clock).
struct ButtonSource {
  ClientApp& app;
  ButtonProtocol protocol;
  std::int64_t last_utime = -1;
  double now_s = 0.0;

  ButtonEvent next() {
    ButtonEvent e = ButtonEvent::None;
    const bool got = app.pollUntil([&] {
      const auto s = app.client().latestDeviceState();
      if (!s || s->utime == last_utime) return false;
      last_utime = s->utime;
      now_s = double(s->utime) * 1e-6;
      e = protocol.update(now_s, std::uint32_t(s->buttons));
      return e != ButtonEvent::None;
    }, 1e9);
    if (!got) throw Error(Error::Kind::Io, "stopped by a signal; the rows written so far are kept");
    return e;
  }
  // The device's clock now (the latest state's utime), s.
  double clock() {
    app.pollUntil([&] {
      const auto s = app.client().latestDeviceState();
      return s && s->utime != last_utime && (now_s = double(s->utime) * 1e-6, true);
    }, 2.0);
    return now_s;
  }
};

void switchTo(ClientApp& app, const std::string& scene_path, const Cues& cues = {}) {
  if (!app.loadScene(stagedSceneName(scene_path, cues)))
    throw Error(Error::Kind::Io, "stopped by a signal while switching the scene; the rows written so far are kept");
}

// The representation a scene's surface is drawn and rendered as.
Representation representationOf(const std::string& scene_path) {
  const scene::Scene sc = scene::loadScene(scene_path);
  return scene::buildSceneSurface(sc).map->isRelief() ? Representation::Relief : Representation::Normal;
}

}  // namespace

Session runRealSession(const StudyManifest& m, const RealSessionOptions& o) {
  ClientApp app("study-run", o.lcm_url.empty() ? std::string(thx_msgs::kDefaultLcmUrl) : o.lcm_url, 10.0);
  app.client().subscribe(thx_msgs::Stream::DeviceState, 250.0);
  if (!app.waitForServer()) throw Error(Error::Kind::Io, "stopped by a signal before hapticd answered");
  ButtonSource button{app, ButtonProtocol(ButtonProtocolConfig{o.long_press_s, 0.02})};
  Console console;

  Session session;
  session.source = o.out_csv;
  session.header = sessionHeaderFor(m, o.participant, o.seed);
  SessionHeader& h = session.header;
  h.extra.push_back({"participant_model", "a person"});
  // Every cue is removed by a staged variant (NAME.nopen, .noball, .nosound); only Study 1's looks
  // without --visual-client are left to the operator.
  h.extra.push_back({"operator_steps", m.study == Study::Identification && o.visual_client.empty()
                                           ? "candidate looks by hand: docs/study.md section 8"
                                           : "none"});
  std::optional<LookWindow> window;
  if (!o.visual_client.empty())
    window.emplace(o.visual_client, o.lcm_url.empty() ? std::vector<std::string>{} : std::vector<std::string>{"--lcm-url", o.lcm_url});
  // The look shown: a window of visual-client, or the operator's step.
  const auto showLook = [&](const std::string& scene, bool ball, const std::string& name, bool first) {
    if (window) window->show(scene, ball);
    else if (first) console.operatorStep("show candidate look " + name);
    else std::cout << "OPERATOR: show candidate look " << name << "\n";
  };
  SessionWriter writer(o.out_csv, h);
  const std::vector<PlannedTrial> plan = planSession(m, o.seed);
  const int n = int(m.surfaces.size());

  if (m.study == Study::Identification) {
    if (m.training) {
      switchTo(app, *m.training);
      if (window) window->show(*m.training, true);  // its own look: nothing to give away
      std::cout << "Training surface: explore it with the pen; confirm (hold the button) when ready.\n";
      while (button.next() != ButtonEvent::Confirm) {}
    }
    for (const PlannedTrial& t : plan) {
      if (window) window->stop();  // never draw the trial's own surface: no window while switching
      switchTo(app, t.scene, t.cues);  // NAME.nopen / .noball / .nosound: no pen force / no ball / silence
      std::cout << "\nTrial " << t.trial << " of " << plan.size() << ": "
                << (t.cues == Cues{} ? std::string("every cue is on") : "one cue is removed: " + cueCondition(t.cues)) << ".\n"
                << "Short press: next look; hold: this is my answer.\n";
      int look = t.first_look;
      showLook(m.surfaces[std::size_t(look)].scene, t.cues.ball, m.surfaces[std::size_t(look)].name, true);
      const double start = button.clock();
      for (;;) {
        const ButtonEvent e = button.next();
        if (e == ButtonEvent::Confirm) break;
        look = (look + 1) % n;
        showLook(m.surfaces[std::size_t(look)].scene, t.cues.ball, m.surfaces[std::size_t(look)].name, false);
      }
      if (window) window->stop();
      TrialRow row;
      row.trial = t.trial;
      row.surface = m.surfaces[std::size_t(t.surface)].name;
      row.cues = t.cues;
      row.representation = representationOf(t.scene);
      row.answer = m.surfaces[std::size_t(look)].name;
      row.correct = look == t.surface;
      row.time_s = std::max(0.0, button.now_s - start);
      row.setRating(Rating::Ease, console.rating("How easy was this trial?", 1, 10));
      const struct { bool on; const char* name; Rating use, acc; } cues[3] = {
          {t.cues.sound, "the sound", Rating::UseSound, Rating::AccSound},
          {t.cues.ball, "the ball's motion", Rating::UseBall, Rating::AccBall},
          {t.cues.pen, "what the pen felt", Rating::UsePen, Rating::AccPen}};
      for (const auto& c : cues) {
        if (!c.on) continue;
        row.setRating(c.use, console.rating(std::string("How much did you use ") + c.name + "?", 1, 5));
        row.setRating(c.acc, console.rating(std::string("How accurate did ") + c.name + " seem?", 1, 10));
      }
      writer.append(row);
      session.trials.push_back(row);
    }
  } else {
    // Free switching: NEXT goes to the next surface not yet rated, CONFIRM rates the one shown.
    std::vector<PlannedTrial> left = plan;
    std::size_t at = 0;
    int trial = 0;
    switchTo(app, left[at].scene);
    double shown_at = button.clock();  // when the surface on show was switched to
    while (!left.empty()) {
      std::cout << "\nSurface " << (at + 1) << " of " << left.size()
                << " still to rate. Short press: next surface; hold: rate this one.\n";
      if (button.next() == ButtonEvent::Next) {
        at = (at + 1) % left.size();
        switchTo(app, left[at].scene);
        shown_at = button.clock();
        continue;
      }
      const PlannedTrial t = left[at];
      TrialRow row;
      row.trial = ++trial;
      row.surface = m.surfaces[std::size_t(t.surface)].name;
      row.representation = t.representation;
      row.time_s = std::max(0.0, button.now_s - shown_at);
      row.setRating(Rating::Realism, console.rating("How realistic does the surface look?", 1, 10));
      row.setRating(Rating::MatchPhysics, console.rating("How well did the ball's motion match what the look led you to expect?", 1, 10));
      row.setRating(Rating::MatchSound, console.rating("How well did the sound match?", 1, 10));
      row.setRating(Rating::MatchHaptics, console.rating("How well did the pen's feel match?", 1, 10));
      row.setRating(Rating::Overall, console.rating("Overall quality?", 1, 10));
      writer.append(row);
      session.trials.push_back(row);
      left.erase(left.begin() + std::ptrdiff_t(at));
      if (left.empty()) break;
      at %= left.size();
      switchTo(app, left[at].scene);
      shown_at = button.clock();
    }
  }
  return session;
}

}  // namespace thx::study
