// The button protocol (docs/study.md §5.2): short press = NEXT on release, a hold = CONFIRM when it
// reaches the long-press time, button 2 = CONFIRM, bounce ignored.
#include <gtest/gtest.h>

#include <vector>

#include "clients/study/button_protocol.hpp"

namespace thx::study::test_button_protocol {
namespace {

// Feeds 1 kHz samples: each pair is (buttons, duration in ms); returns the events with their tick.
std::vector<std::pair<int, ButtonEvent>> feed(ButtonProtocol& p, const std::vector<std::pair<unsigned, int>>& spans) {
  std::vector<std::pair<int, ButtonEvent>> out;
  int tick = 0;
  for (const auto& [b, ms] : spans)
    for (int k = 0; k < ms; ++k, ++tick)
      if (const ButtonEvent e = p.update(tick * 1e-3, b); e != ButtonEvent::None) out.push_back({tick, e});
  return out;
}

TEST(ButtonProtocol, ShortPressIsNextOnRelease) {
  ButtonProtocol p;
  const auto e = feed(p, {{0, 100}, {1, 300}, {0, 100}});
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0], (std::pair<int, ButtonEvent>{400, ButtonEvent::Next}));
}

TEST(ButtonProtocol, HoldIsConfirmAtTheLongPressTime) {
  ButtonProtocol p;
  const auto e = feed(p, {{0, 100}, {1, 2000}, {0, 100}});
  ASSERT_EQ(e.size(), 1u);  // the release after the hold gives nothing
  EXPECT_EQ(e[0], (std::pair<int, ButtonEvent>{900, ButtonEvent::Confirm}));
}

TEST(ButtonProtocol, BounceIsIgnoredAndButtonTwoConfirms) {
  ButtonProtocol p;
  const auto e = feed(p, {{0, 10}, {1, 5}, {0, 10}, {2, 50}, {0, 10}, {1, 100}, {0, 10}});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0], (std::pair<int, ButtonEvent>{25, ButtonEvent::Confirm}));
  EXPECT_EQ(e[1], (std::pair<int, ButtonEvent>{185, ButtonEvent::Next}));
}

TEST(ButtonProtocol, LongPressTimeIsConfigurable) {
  ButtonProtocol p(ButtonProtocolConfig{0.3, 0.02});
  const auto e = feed(p, {{1, 250}, {0, 10}, {1, 400}});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].second, ButtonEvent::Next);
  EXPECT_EQ(e[1], (std::pair<int, ButtonEvent>{560, ButtonEvent::Confirm}));
}

}  // namespace
}  // namespace thx::study::test_button_protocol
