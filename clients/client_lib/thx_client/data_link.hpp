#pragma once
// The LCM a client receives its streams on (issue 17, docs/clients.md §6).
//
// hapticd publishes each client's streams on a udpm port of the client's own and names it in
// every reply (subscribe_reply_t.data_url). On the shared bus every process would wake for every
// datagram of every client (the kernel delivers a multicast datagram to each socket bound to its
// port); on its own port a client wakes only for its own. DataLink opens one LCM on that URL and
// closes it when the server names another (a restart may hand out another port): an LCM left open
// on an old port would keep its receive thread waking for whoever gets that port next.
// An empty data_url (a server with --data-ports off, memq:// tests) means the bus.
#include <memory>
#include <string>

namespace lcm {
class LCM;
}

namespace thx::client {

class DataLink {
 public:
  DataLink();
  ~DataLink();
  DataLink(const DataLink&) = delete;
  DataLink& operator=(const DataLink&) = delete;

  // The URL open now ("" for none).
  const std::string& url() const { return url_; }
  // The open LCM, or null.
  lcm::LCM* lcm() const { return lcm_.get(); }
  // Opens `url` in place of the current one (whose subscriptions the caller has removed). Returns
  // "" or why it could not: "cannot open the data URL 'udpm://...': ..." (then none is open).
  std::string open(const std::string& url);
  void close();
  // Handles every message queued on the data LCM without waiting; < 0 on an LCM error.
  int drain();

 private:
  std::string url_;
  std::unique_ptr<lcm::LCM> lcm_;
};

}  // namespace thx::client
