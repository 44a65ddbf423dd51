// A complete hapticd client (docs/clients.md §5): the pen at 60 Hz, every contact sample batched.
// usage: thx-minimal-client [LCM_URL]
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <string>

#include "thx_client/client.hpp"

int main(int argc, char** argv) {
  const std::string url = argc > 1 ? argv[1] : "udpm://239.255.76.67:7667?ttl=0";
  if (url == "-h" || url == "--help") return std::puts("usage: thx-minimal-client [LCM_URL]"), 0;
  lcm::LCM lcm(url);
  if (!lcm.good()) return std::fprintf(stderr, "LCM is not available at %s\n", url.c_str()), 1;

  thx::client::Client client(lcm, "minimal");
  client.subscribe("DEVICE_STATE", 60.0);          // latest pen state, 60 times a second
  client.subscribe("CONTACT", 100.0, /*batch=*/true);  // all 1000 samples/s, 10 per message

  long touching = 0;
  client.onContactBatch([&](const thx_msgs::contact_batch_t& b, std::int64_t /*receipt_ns*/) {
    for (const thx_msgs::contact_t& s : b.samples) touching += s.in_contact;  // e.g. feed audio here
  });

  const std::int64_t end = thx::client::monotonicNs() + 5'000'000'000;  // run 5 s
  while (thx::client::monotonicNs() < end) {
    client.poll(10);  // receive, heartbeat, re-subscribe after a server restart
    if (auto s = client.latestDeviceState()) {
      std::printf("\rtick %lld  p_world = (%+.4f, %+.4f, %+.4f) m  samples in contact: %ld   ", (long long)s->tick,
                  s->p_world[0], s->p_world[1], s->p_world[2], touching);
    }
  }
  for (const auto& st : client.status()) {
    std::printf("\n%s: %s at %g Hz %s", st.stream.c_str(), toString(st.state), st.granted_hz, st.reason.c_str());
  }
  std::printf("\n");
  return 0;
}
