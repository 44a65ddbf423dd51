#include "clients/audio/live/live_audio.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <vector>

#include "base/error.hpp"
#include "clients/audio/live/audio_output.hpp"
#include "clients/audio/live/excitation_feed.hpp"
#include "clients/audio/live/pen_feeds.hpp"
#include "clients/audio/live/live_synth.hpp"
#include "rt/clock.hpp"
#include "thx_client/app.hpp"
#include "thx_client/subscriber.hpp"

namespace thx::audio {

namespace {

struct LatencyStats {
  std::vector<double> from_source_us, from_receipt_us;
  std::uint64_t late = 0;
  std::FILE* csv = nullptr;  // --events-csv
  void add(const PlayedEvent& p) {
    if (csv)
      std::fprintf(csv, "%lld,%lld,%lld,%lld,%d,%d\n", (long long)p.source_ns, (long long)p.receipt_ns, (long long)p.time_ns,
                   (long long)p.block_start_ns, int(p.offset), p.late ? 1 : 0);
    from_source_us.push_back(double(p.block_start_ns - p.source_ns) / 1e3);
    from_receipt_us.push_back(double(p.block_start_ns - p.receipt_ns) / 1e3);
    late += p.late ? 1 : 0;
  }
};

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::min(v.size() - 1, std::size_t(std::ceil(q * double(v.size()))) - (q > 0 ? 1 : 0));
  return v[k];
}

std::string quantiles(const std::vector<double>& v) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "{\"n\": %zu, \"p50\": %.1f, \"p99\": %.1f, \"max\": %.1f}", v.size(), percentile(v, 0.5),
                percentile(v, 0.99), v.empty() ? NAN : *std::max_element(v.begin(), v.end()));
  return buf;
}

client::AppOptions appOptions(const LiveOptions& o, const SurfaceSound& sound) {
  client::AppOptions a;
  a.client_id = "audio";
  if (!o.lcm_url.empty()) a.lcm_url = o.lcm_url;
  a.connect_timeout_s = o.connect_timeout_s;
  a.scene = client::SceneIdentity{sound.surface.scene_name, sound.surface.fingerprint};
  a.allow_different_scene = o.allow_different_scene;
  a.client.device = o.scene_settings.device;  // the kit delivers this pen's batches only,
  a.client.every_device = o.scene_settings.every_device;  // or every pen's
  return a;
}

}  // namespace

int runLive(const LiveOptions& o) {
  LiveSceneSettings settings = o.scene_settings;
  settings.max_block = kMaxBlockFrames;
  std::uint32_t generation = 1;
  std::unique_ptr<LiveScene> scene = buildLiveScene(o.scene, settings, generation);

  rt::MonotonicClock clock;
  LiveSynthOptions so;
  so.sample_rate_hz = settings.slab.sample_rate_hz;
  so.adapt_budget = o.adapt_budget;
  so.budget = o.budget;
  // Each pen's batch queues its ticks' events in turn: order them over a batch's span, the micro
  // level's tick before it and a tick of slack (live_synth.hpp).
  so.order_window_ns = std::llround(1e9 / o.batch_hz) + 2'000'000;
  LiveSynth synth(so, clock);
  QueueSink sink(synth.queue());
  PenFeeds feed(sink, settings.every_device ? std::nullopt : std::optional<int>(settings.device));
  feed.setScene(*scene);
  std::size_t scene_modes = scene->synth->modes();  // every body's
  synth.offerScene(std::move(scene->synth));

  const float gain = float(o.gain);
  BlockCallback callback = [&synth, gain](std::span<float> out, std::int64_t start_ns) {
    synth.process(out, start_ns);
    for (float& x : out) x = std::clamp(gain * x, -1.0f, 1.0f);
  };

  // Output: a device when there is one, else the timer thread and the WAV.
  std::unique_ptr<RtAudioOutput> device;
  std::unique_ptr<TimerOutput> timer;
  std::unique_ptr<WavWriter> wav;
  std::string why;
  if (o.output != "timer") device = RtAudioOutput::open(so.sample_rate_hz, o.block_frames, callback, o.audio_api, why);
  if (!device) {
    if (o.output == "device") throw Error(Error::Kind::Io, why + "; --output device asks for one");
    if (o.output == "auto" && !o.quiet)
      std::fprintf(stderr, "audio-client: %s: playing on a timer-driven callback%s\n", why.c_str(),
                   o.wav.empty() ? " (no --wav: the sound is not kept)" : (", writing " + o.wav).c_str());
    if (!o.wav.empty()) wav = std::make_unique<WavWriter>(o.wav, int(std::lround(so.sample_rate_hz)));
    timer = std::make_unique<TimerOutput>(so.sample_rate_hz, o.block_frames, callback, wav ? 256 : 0);
  } else if (!o.quiet) {
    std::fprintf(stderr, "audio-client: playing on %s, %zu-frame blocks, device latency %.1f ms\n",
                 device->description().c_str(), device->blockFrames(), 1e3 * device->deviceLatencyS());
  }

  // The output runs from before the first batch, so the first impulses find a running stream.
  if (device) device->start();
  if (timer) timer->start();
  client::ClientApp app(appOptions(o, *scene->sound));
  client::PhysicsPosesSubscriber physics_poses(app.lcm());
  client::PhysicsContactsSubscriber physics_contacts(app.lcm());
  client::PhysicsImpactSubscriber physics_impacts(app.lcm());
  app.client().onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t t) { feed.contactBatch(b, t); });
  physics_poses.onMessage([&](const thx_msgs::physics_poses_t& m, std::int64_t t) { feed.physicsPoses(m, t); });
  physics_contacts.onMessage([&](const thx_msgs::physics_contacts_t& m, std::int64_t t) { feed.physicsContacts(m, t); });
  physics_impacts.onMessage([&](const thx_msgs::physics_impact_t& m, std::int64_t t) { feed.physicsImpact(m, t); });
  app.client().subscribe(thx_msgs::Stream::Contact, o.batch_hz, /*batch=*/true);
  const std::optional<thx_msgs::hello_t> hello = app.waitForServer();
  if (!hello) return 0;  // stopped while waiting
  std::uint64_t scene_changes_seen = app.client().sceneChanges();
  if (!o.quiet)
    std::fprintf(stderr, "audio-client: live from %s (scene %s), CONTACT batched at %g Hz, playout delay %.1f ms\n",
                 hello->server_name.c_str(), hello->scene_name.c_str(), o.batch_hz,
                 double(settings.playout_delay_ns) / 1e6);

  LatencyStats latency;
  if (!o.events_csv.empty()) {
    latency.csv = std::fopen(o.events_csv.c_str(), "w");
    if (!latency.csv) throw Error(Error::Kind::Io, o.events_csv + ": cannot be written");
    std::fprintf(latency.csv, "source_ns,receipt_ns,time_ns,block_start_ns,offset,late\n");
  }
  std::uint64_t scene_switches = 0;
  std::optional<client::SceneIdentity> wanted;  // the newest switch not being built yet
  client::SceneIdentity building_to;
  std::future<std::unique_ptr<LiveScene>> building;
  auto block = std::make_unique<AudioBlock>();
  auto drain = [&] {
    synth.collect();
    PlayedEvent p;
    while (synth.played().pop(p)) latency.add(p);
    if (wav && timer) {
      while (timer->capture()->pop(*block)) wav->write(std::span<const float>(block->samples, block->frames));
    }
  };
  const std::int64_t t0 = clock.nowNs();
  while (!app.stopRequested()) {
    app.client().poll(2);
    // A scene switch: silence (the sources would walk the old texture), then the new scene is built
    // on another thread (a first modal solve takes seconds) while this one keeps polling, so the
    // kit's heartbeats go on and no batch is lost; installed when ready, unless a newer switch
    // came meanwhile (then that one is built next).
    if (app.client().sceneChanges() != scene_changes_seen && app.client().serverScene()) {
      scene_changes_seen = app.client().sceneChanges();
      wanted = *app.client().serverScene();
      feed.silence();
    }
    if (wanted && !building.valid()) {
      building_to = *wanted;
      wanted.reset();
      building = std::async(std::launch::async, [name = building_to.name, dir = o.scenes_dir, settings, g = ++generation] {
        return buildLiveScene(client::resolveSceneName(name, dir), settings, g);
      });
    }
    if (building.valid() && building.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      std::unique_ptr<LiveScene> next;
      try {
        next = building.get();
      } catch (const Error& e) {
        std::fprintf(stderr, "audio-client: hapticd switched to scene %s, which cannot be played here: %s; silent\n",
                     building_to.name.c_str(), e.what());
      }
      if (next && !wanted) {
        if (!o.quiet) std::fprintf(stderr, "audio-client: hapticd switched to scene %s\n", building_to.name.c_str());
        if (next->sound->surface.fingerprint != building_to.texture_fingerprint && !o.quiet)
          std::fprintf(stderr, "audio-client: warning: scene '%s' in %s has another texture than hapticd's; playing ours\n",
                       building_to.name.c_str(), o.scenes_dir.c_str());
        feed.setScene(*next);
        scene_modes = next->synth->modes();
        synth.offerScene(std::move(next->synth));
        scene = std::move(next);
        ++scene_switches;
      }
    }
    drain();
    if (o.duration_s > 0 && double(clock.nowNs() - t0) >= o.duration_s * 1e9) break;
  }
  if (device) device->stop();
  if (timer) timer->stop();
  drain();
  if (latency.csv) std::fclose(latency.csv);

  const LiveSynthCounters& c = synth.counters();
  const FeedCounters f = feed.total();  // every pen's
  if (!o.quiet)
    std::fprintf(stderr,
                 "audio-client: live: %llu batches, %llu ticks, %llu events played (%llu late, %llu dropped), %llu blocks, "
                 "modes %llu of %zu (fewest %llu), scene switches %llu; latency contact -> block p50 %.0f us, p99 %.0f us\n",
                 (unsigned long long)f.batches, (unsigned long long)f.samples, (unsigned long long)c.events.load(),
                 (unsigned long long)c.late_events.load(), (unsigned long long)sink.dropped(),
                 (unsigned long long)c.blocks.load(), (unsigned long long)c.budget.load(), scene_modes,
                 (unsigned long long)(c.min_rendered_modes.load() == ~std::uint64_t(0) ? 0 : c.min_rendered_modes.load()),
                 (unsigned long long)scene_switches, percentile(latency.from_source_us, 0.5),
                 percentile(latency.from_source_us, 0.99));
  if (!o.stats_json.empty()) {
    std::FILE* j = std::fopen(o.stats_json.c_str(), "w");
    if (!j) throw Error(Error::Kind::Io, o.stats_json + ": cannot be written");
    std::fprintf(j,
                 "{\n  \"output\": \"%s\",\n  \"device_latency_s\": %.6f,\n  \"sample_rate_hz\": %.0f,\n  \"block_frames\": %zu,\n"
                 "  \"playout_delay_ms\": %.3f,\n  \"batch_hz\": %g,\n  \"timer_realtime\": %s,\n  \"timer_max_wake_late_us\": %.1f,\n"
                 "  \"latency_from_source_us\": %s,\n  \"latency_from_receipt_us\": %s,\n"
                 "  \"batches\": %llu, \"ticks\": %llu, \"lost_batches\": %llu, \"server_dropped\": %llu,\n"
                 "  \"duplicate_batches\": %llu, \"resubscriptions\": %llu, \"server_restarts\": %llu,\n"
                 "  \"events\": %llu, \"late_events\": %llu, \"expired_events\": %llu, \"stale_events\": %llu, \"queue_dropped\": %llu,\n"
                 "  \"blocks\": %llu, \"late_blocks\": %llu, \"reanchors\": %llu, \"scene_switches\": %llu,\n"
                 "  \"modes\": %zu, \"budget\": %llu, \"min_rendered_modes\": %llu, \"max_cost_us\": %.1f,\n"
                 "  \"physics_contacts\": %llu, \"physics_impacts\": %llu\n}\n",
                 device ? "device" : "timer", device ? device->deviceLatencyS() : 0.0, so.sample_rate_hz,
                 device ? device->blockFrames() : o.block_frames, double(settings.playout_delay_ns) / 1e6, o.batch_hz,
                 timer && timer->realtimePriority() ? "true" : "false", timer ? double(timer->maxWakeLateNs()) / 1e3 : 0.0,
                 quantiles(latency.from_source_us).c_str(), quantiles(latency.from_receipt_us).c_str(),
                 (unsigned long long)f.batches, (unsigned long long)f.samples, (unsigned long long)f.lost_batches,
                 (unsigned long long)f.server_dropped, (unsigned long long)f.duplicates,
                 (unsigned long long)f.resubscriptions, (unsigned long long)f.restarts, (unsigned long long)c.events.load(),
                 (unsigned long long)c.late_events.load(), (unsigned long long)c.expired_events.load(),
                 (unsigned long long)c.stale_events.load(),
                 (unsigned long long)sink.dropped(), (unsigned long long)c.blocks.load(),
                 (unsigned long long)c.late_blocks.load(), (unsigned long long)c.reanchors.load(),
                 (unsigned long long)scene_switches, scene_modes, (unsigned long long)c.budget.load(),
                 (unsigned long long)(c.min_rendered_modes.load() == ~std::uint64_t(0) ? 0 : c.min_rendered_modes.load()),
                 double(c.max_cost_ns.load()) / 1e3, (unsigned long long)f.physics_contacts,
                 (unsigned long long)f.physics_impacts);
    std::fclose(j);
  }
  return 0;
}

}  // namespace thx::audio
