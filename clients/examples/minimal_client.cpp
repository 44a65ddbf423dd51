// A complete hapticd client on the kit (docs/clients.md §5): the pen at 60 Hz, every contact
// sample batched, the physics client's object poses, a 30 Hz loop that prints what it has, and at
// the end each stream's state and how many messages it brought.
// usage: thx-minimal-client [LCM_URL]
#include <cstdint>
#include <cstdio>
#include <string>

#include "thx_client/app.hpp"
#include "thx_client/subscriber.hpp"

int main(int argc, char** argv) {
  const std::string url = argc > 1 ? argv[1] : thx_msgs::kDefaultLcmUrl;
  if (url == "-h" || url == "--help") return std::puts("usage: thx-minimal-client [LCM_URL]"), 0;
  try {
    thx::client::ClientApp app("minimal", url);  // signals, LCM (with the route hint), heartbeats
    auto& client = app.client();
    client.subscribe(thx_msgs::Stream::DeviceState, 60.0);               // the latest pen state, 60 times a second
    client.subscribe(thx_msgs::Stream::Contact, 100.0, /*batch=*/true);  // all 1000 samples/s, 10 per message
    long touching = 0;
    client.onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t /*receipt_ns*/) {
      for (const thx_msgs::contact_t& s : b.samples) touching += s.in_contact;  // e.g. feed audio here
    });
    thx::client::PhysicsPosesSubscriber poses(app.lcm());  // THX_PHYSICS_POSES, if a physics client runs
    poses.onError([](const thx::client::DecodeError& e) { std::fprintf(stderr, "%s\n", e.message().c_str()); });

    const auto hello = app.waitForServer();  // thx::Error after 10 s without hapticd
    if (!hello) return 0;                    // Ctrl-C while waiting
    std::printf("%s, device %s\n", hello->server_name.c_str(), hello->device.c_str());
    app.runPaced(30.0, [&](const thx::rt::TickTiming& t) {
      if (auto s = client.latestDeviceState())
        std::printf("\rtick %lld  p_world = (%+.4f, %+.4f, %+.4f) m  samples in contact: %ld  bodies: %d   ",
                    (long long)s->tick, s->p_world[0], s->p_world[1], s->p_world[2], touching,
                    poses.latest() ? poses.latest()->num_bodies : 0);
      std::fflush(stdout);
      return t.tick < 150;  // 5 s
    });
    for (const auto& st : client.status())
      std::printf("\n%s: %s at %g Hz, %llu messages %s", thx_msgs::stream_name(st.stream), toString(st.state),
                  st.granted_hz, (unsigned long long)st.messages, st.reason.c_str());
    std::printf("\n");
    return 0;
  } catch (const thx::Error& e) {
    std::fprintf(stderr, "thx-minimal-client: %s\n", e.what());
    return thx::exitStatus(e);
  }
}
