#include "clients/visual/live_client.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "clients/visual/frame_renderer.hpp"
#include "clients/visual/headless_context.hpp"
#include "clients/visual/image_writer.hpp"
#include "clients/visual/live_feed.hpp"
#include "clients/visual/scene_objects.hpp"
#include "clients/visual/window_presenter.hpp"
#include "thx_client/stop_signal.hpp"
#include "scenes/scene_loader.hpp"
#include "scenes/scene_surface.hpp"
#include "textures/smoothing.hpp"
#include "thx_client/scene_check.hpp"

namespace thx::visual {

namespace {

// One scene and its surface; replaced whole on a scene switch.
struct LoadedScene {
  scene::Scene scene;
  scene::SceneSurface surface;
};

std::unique_ptr<LoadedScene> loadScene(const std::string& file) {
  scene::SurfaceTextureOptions texture_options;
  texture_options.smooth = &tex::smoothTexture;
  scene::Scene s = scene::loadScene(file);
  scene::SceneSurface surface = scene::buildSceneSurface(s, texture_options);
  return std::make_unique<LoadedScene>(LoadedScene{std::move(s), std::move(surface)});
}

// What a frame draws: the bodies where the poses put them (at rest without), each drawn device's
// pen where its newest state put it (before the first state, the pens resting where their hand
// scripts start).
std::vector<ObjectInstance> frameObjects(const Options& o, const LoadedScene& l, const LiveView& view) {
  std::vector<ObjectInstance> objects;
  if (!o.no_objects) objects = objectsAt(l.scene, view.bodies);
  if (o.no_pen) return objects;
  const tex::TexturedSurface& surface = l.surface.surface;
  const std::vector<PenView> pens = pensOf(view);
  const std::vector<ObjectInstance> drawn =
      pens.empty() ? pensAtRest(surface, l.scene, o.device, o.pen_xy) : pensAt(surface, pens, &l.scene);
  objects.insert(objects.end(), drawn.begin(), drawn.end());
  return objects;
}

// The server switched scenes: load the same scene from our folder (a name never leaves it).
// With --allow-different-scene the look stays --scene's: nullptr.
std::unique_ptr<LoadedScene> followSwitch(const Options& o, const client::SceneIdentity& to) {
  if (o.allow_different_scene) {
    if (!o.quiet) std::fprintf(stderr, "visual-client: hapticd switched to scene %s; drawing ours\n", to.name.c_str());
    return nullptr;
  }
  std::unique_ptr<LoadedScene> next = loadScene(client::resolveSceneName(to.name, o.scenes_dir));
  if (!o.quiet) std::fprintf(stderr, "visual-client: hapticd switched to scene %s\n", to.name.c_str());
  if (next->surface.fingerprint != to.texture_fingerprint && !o.quiet)
    std::fprintf(stderr, "visual-client: warning: scene '%s' in %s has another texture than hapticd's; drawing ours\n",
                 to.name.c_str(), o.scenes_dir.c_str());
  return next;
}

void printCounts(const char* prefix, const LiveCounts& c) {
  std::fprintf(stderr, "%sloop steps %lld, frames drawn %lld, skipped (nothing moved) %lld, scene switches %lld\n",
               prefix, (long long)c.steps, (long long)c.drawn, (long long)c.skipped, (long long)c.scene_switches);
}

int liveHeadless(const Options& o, LiveFeed& feed, std::unique_ptr<LoadedScene> loaded, bool connected) {
  HeadlessContext context;
  auto renderer = std::make_unique<FrameRenderer>(loaded->surface.surface, o.render, o.width, o.height);
  renderer->setTexturedObjects(loaded->scene);
  std::filesystem::create_directories(o.out_dir);
  LiveCounts counts;
  auto draw = [&](const LiveView& view) {
    const Camera camera(cameraPlacement(o, loaded->scene), loaded->surface.surface.mapping().plane_to_world, o.width,
                        o.height);
    renderer->render(camera, frameObjects(o, *loaded, view));
    writeImage(framePath(o.out_dir, int(counts.drawn), o.frame_format), renderer->framebuffer().readColour(),
               o.png_level);
    ++counts.drawn;
  };
  if (!connected) {
    draw(LiveView{});
    if (!o.quiet) std::fprintf(stderr, "visual-client: wrote the scene at rest to %s\n", o.out_dir.c_str());
    return 0;
  }
  std::optional<LiveView> last;
  std::int64_t last_report_step = 0;
  const std::int64_t steps_per_report = std::max<std::int64_t>(1, std::int64_t(o.replay_rate_hz));
  feed.app().runPaced(o.replay_rate_hz, [&](const rt::TickTiming& t) {
    ++counts.steps;
    std::optional<client::SceneIdentity> to = feed.takeSceneSwitch();
    std::unique_ptr<LoadedScene> next = to ? followSwitch(o, *to) : nullptr;
    if (next) {
      renderer.reset();
      loaded = std::move(next);
      renderer = std::make_unique<FrameRenderer>(loaded->surface.surface, o.render, o.width, o.height);
      renderer->setTexturedObjects(loaded->scene);
      last.reset();
      ++counts.scene_switches;
    }
    const LiveView view = feed.poll();
    if (last && sameView(view, *last)) {
      ++counts.skipped;
    } else {
      draw(view);
      last = view;
    }
    if (o.verbose && counts.steps - last_report_step >= steps_per_report) {
      last_report_step = counts.steps;
      printCounts("visual-client: ", counts);
    }
    const bool enough_frames = o.frames > 0 && counts.drawn >= o.frames;
    const bool enough_time = o.duration_s > 0 && double(t.tick + 1) >= o.duration_s * o.replay_rate_hz;
    return !enough_frames && !enough_time;
  });
  if (!o.quiet) printCounts("visual-client: live: ", counts);
  return 0;
}

int liveWindow(const Options& o, LiveFeed& feed, std::unique_ptr<LoadedScene> loaded, bool connected) {
  LiveCounts counts;
  std::optional<LiveView> last;
  std::unique_ptr<LoadedScene> previous;  // the window's renderer reads it until it rebuilds on the next
  WindowOptions w{o.width, o.height, o.window_frames, o.duration_s, o.quiet, o.window_screenshot, {}, o.replay_rate_hz, {}};
  client::installStopSignals();
  w.stop = [] { return client::stopRequested(); };
  if (connected) {
    w.live_update = [&](std::vector<ObjectInstance>& objects, const tex::TexturedSurface*& surface) {
      ++counts.steps;
      WindowOptions::LiveChange change = WindowOptions::LiveChange::Moved;
      std::optional<client::SceneIdentity> to = feed.takeSceneSwitch();
      std::unique_ptr<LoadedScene> next = to ? followSwitch(o, *to) : nullptr;
      if (next) {
        previous = std::move(loaded);
        loaded = std::move(next);
        surface = &loaded->surface.surface;
        last.reset();
        ++counts.scene_switches;
        change = WindowOptions::LiveChange::NewSurface;
      }
      const LiveView view = feed.poll();
      if (last && sameView(view, *last) && change != WindowOptions::LiveChange::NewSurface) {
        ++counts.skipped;
        return WindowOptions::LiveChange::Same;
      }
      objects = frameObjects(o, *loaded, view);
      last = view;
      ++counts.drawn;
      return change;
    };
  }
  const LoadedScene& first = *loaded;  // runWindow copies what it needs before the first switch
  const int frames = runWindow(first.surface.surface, o.render, cameraPlacement(o, first.scene),
                               frameObjects(o, first, LiveView{}), w);
  if (!o.quiet) {
    std::fprintf(stderr, "visual-client: window closed after %d frames\n", frames);
    if (connected) printCounts("visual-client: live: ", counts);
  }
  return 0;
}

}  // namespace

int runLive(const Options& o) {
  std::unique_ptr<LoadedScene> loaded = loadScene(o.scene);
  LiveFeed feed(o.lcm_url, o.replay_rate_hz, o.connect_timeout_s,
                client::SceneIdentity{loaded->surface.scene_name, loaded->surface.fingerprint}, o.allow_different_scene,
                o.device);
  std::string why;
  const std::optional<thx_msgs::hello_t> hello = feed.connect(why);
  if (!hello) {
    if (!o.quiet) std::fprintf(stderr, "visual-client: %s; drawing the scene at rest\n", why.c_str());
  } else if (!o.quiet) {
    std::fprintf(stderr, "visual-client: live from %s (scene %s) at %g Hz\n", hello->server_name.c_str(),
                 hello->scene_name.c_str(), o.replay_rate_hz);
  }
  return o.window ? liveWindow(o, feed, std::move(loaded), hello.has_value())
                  : liveHeadless(o, feed, std::move(loaded), hello.has_value());
}

}  // namespace thx::visual
