// Cookie checks exactly as docs/vrpn.md §2 states them: match through "vrpn: ver. 07.", log
// mode '0'..'3', a different minor number only warns, the other bytes are not checked.
#include <gtest/gtest.h>

#include <string>

#include "device/vrpn/cookie.hpp"

namespace test_cookie {

using namespace thx::vrpn;

namespace {

Cookie cookieFrom(std::string_view text) {
  Cookie c{};
  std::copy(text.begin(), text.end(), c.begin());
  return c;
}

}  // namespace

TEST(Cookie, OursHasTheDocumentedLayout) {
  const Cookie c = makeCookie();
  EXPECT_EQ(std::string(c.begin(), c.begin() + 16), "vrpn: ver. 07.38");
  EXPECT_EQ(c[16], ' ');
  EXPECT_EQ(c[17], ' ');
  EXPECT_EQ(c[18], '0');
  for (std::size_t i = 19; i < 24; ++i) EXPECT_EQ(c[i], 0) << i;
}

TEST(Cookie, LogModeDigitIsClamped) {
  EXPECT_EQ(makeCookie(2)[kLogModeOffset], '2');
  EXPECT_EQ(makeCookie(-1)[kLogModeOffset], '0');
  EXPECT_EQ(makeCookie(9)[kLogModeOffset], '3');
}

TEST(Cookie, AcceptsEveryLogMode) {
  for (int mode = 0; mode <= 3; ++mode) {
    Result<PeerCookie> p = checkCookie(makeCookie(mode));
    ASSERT_TRUE(p) << p.error().reason;
    EXPECT_EQ(p->log_mode, mode);
  }
}

TEST(Cookie, DifferentMinorOnlyWarns) {
  Result<PeerCookie> p = checkCookie(cookieFrom(std::string("vrpn: ver. 07.35  1") + std::string(5, '\0')));
  ASSERT_TRUE(p) << p.error().reason;
  EXPECT_TRUE(p->minor_differs);
  EXPECT_EQ(p->version, "vrpn: ver. 07.35");
  EXPECT_EQ(p->log_mode, 1);
}

TEST(Cookie, BytesOutsideTheRulesAreNotChecked) {
  Cookie c = makeCookie();
  c[16] = 'x';
  c[17] = 0;
  c[19] = 0xff;
  c[23] = 'z';
  EXPECT_TRUE(checkCookie(c));
}

TEST(Cookie, WrongMajorVersionDrops) {
  Result<PeerCookie> p = checkCookie(cookieFrom("vrpn: ver. 08.38  0"));
  ASSERT_FALSE(p);
  EXPECT_EQ(p.error().code, ErrorCode::kBadCookie);
  EXPECT_NE(p.error().reason.find("vrpn: ver. 08.38"), std::string::npos);
}

TEST(Cookie, WrongMagicDrops) {
  EXPECT_EQ(checkCookie(cookieFrom("VRPN: ver. 07.38  0")).error().code, ErrorCode::kBadCookie);
  EXPECT_EQ(checkCookie(cookieFrom("vrpn: ver. 07,38  0")).error().code, ErrorCode::kBadCookie);
  EXPECT_EQ(checkCookie(Cookie{}).error().code, ErrorCode::kBadCookie);
  // The log-file magic is not a network cookie.
  EXPECT_EQ(checkCookie(cookieFrom("vrpn: ver. 04.00  0")).error().code, ErrorCode::kBadCookie);
}

TEST(Cookie, BadLogModeDrops) {
  for (char mode : {'4', '9', '/', 'a', ' ', '\0'}) {
    Cookie c = makeCookie();
    c[kLogModeOffset] = std::uint8_t(mode);
    Result<PeerCookie> p = checkCookie(c);
    ASSERT_FALSE(p) << int(mode);
    EXPECT_EQ(p.error().code, ErrorCode::kBadLogMode);
  }
}

TEST(Cookie, WrongSizeDrops) {
  const Cookie c = makeCookie();
  EXPECT_EQ(checkCookie(std::span(c).first(23)).error().code, ErrorCode::kBadCookie);
  std::vector<std::uint8_t> longer(c.begin(), c.end());
  longer.push_back(0);
  EXPECT_EQ(checkCookie(longer).error().code, ErrorCode::kBadCookie);
}

}  // namespace test_cookie
