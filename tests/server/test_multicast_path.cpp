// hapticd's start line about its udpm traffic (server/multicast_path.hpp): the TTL from the URL,
// and the interface the route to the group picks. Which interface that is depends on the
// machine's routes, so here only its shape; tests/clients/test_other_hosts.cpp checks the line
// hapticd prints on a virtual LAN, where the route is known.
#include <gtest/gtest.h>

#include "server/multicast_path.hpp"

namespace test_multicast_path {

using thx::srv::describeMulticastPath;
using thx::srv::multicastTtl;

TEST(MulticastPath, TheTtlComesFromTheQuery) {
  EXPECT_EQ(multicastTtl(""), 0);
  EXPECT_EQ(multicastTtl("ttl=1"), 1);
  EXPECT_EQ(multicastTtl("recv_buf_size=4194304&ttl=3"), 3);
  EXPECT_EQ(multicastTtl("ttl=0&recv_buf_size=4194304"), 0);
  EXPECT_EQ(multicastTtl("ttl=256"), 0);  // not a TTL: LCM's default
  EXPECT_EQ(multicastTtl("ttl=x"), 0);
}

TEST(MulticastPath, AUdpmUrlIsDescribedAndOthersAreNot) {
  const std::string line = describeMulticastPath("udpm://239.255.76.67:7667?ttl=0");
  EXPECT_EQ(line.rfind("LCM udpm://239.255.76.67:7667?ttl=0: TTL 0, ", 0), 0u) << line;
  // Through an interface, or the reason there is no route: one or the other, never silence.
  EXPECT_TRUE(line.find(", the streams stay on this host through ") != std::string::npos ||
              line.find(", no route to 239.255.76.67 (") != std::string::npos)
      << line;
  EXPECT_EQ(describeMulticastPath("memq://"), "");
  EXPECT_EQ(describeMulticastPath("tcpq://127.0.0.1:7700"), "");
}

}  // namespace test_multicast_path
