// The modal cache reader: the fuzz body's seeds and short run (modal_cache_body.hpp), the bounds
// on the counts a header can give, and the checks behind the checksum.
#include <gtest/gtest.h>

#include <cstring>

#include "tests/fuzz/seed_writer.hpp"
#include "tests/fuzz/short_run.hpp"
#include "tests/fuzz/modal_cache_body.hpp"

namespace test_fuzz_modal_cache {

using namespace thx;
using namespace thx::fuzz;

namespace {

const std::string kTarget = "modal_cache";
constexpr std::uint64_t kKey = 0x0123456789abcdefull;

audio::ModalSolution smallSolution(int rigid, int nodes, int modes) {
  audio::ModalSolution s;
  s.mesh_dofs = 3 * nodes;
  s.free_dofs = 3 * nodes - (rigid ? 0 : 3);
  s.rigid_modes = rigid;
  s.rigid_hz = Eigen::VectorXd::LinSpaced(rigid, -0.5, 0.5);
  s.omega_rad_per_s = Eigen::VectorXd::LinSpaced(modes, 1000.0, 9000.0);
  s.shapes = Eigen::MatrixXd::Zero(s.mesh_dofs, modes);
  for (int m = 0; m < modes; ++m)
    for (int d = 0; d < s.mesh_dofs; ++d) s.shapes(d, m) = std::sin(0.3 * (m + 1) * (d + 1));
  return s;
}

Bytes withMode(std::uint8_t mode, const std::vector<std::uint8_t>& file) {
  Bytes b{mode};
  b.insert(b.end(), file.begin(), file.end());
  return b;
}

// A header (docs/audio.md §2) with the given counts and `doubles` zero values after it, checksummed.
std::vector<std::uint8_t> fileWithCounts(std::uint32_t rigid, std::uint32_t dofs, std::uint32_t modes,
                                         std::size_t doubles) {
  std::vector<std::uint8_t> b(40 + 8 * doubles + 8, 0);
  std::memcpy(b.data(), "THXMODES", 8);
  const std::uint32_t version = 1;
  std::memcpy(b.data() + 8, &version, 4);
  std::memcpy(b.data() + 12, &rigid, 4);
  std::memcpy(b.data() + 16, &kKey, 8);
  std::memcpy(b.data() + 24, &dofs, 4);
  std::memcpy(b.data() + 32, &modes, 4);
  const std::uint64_t sum = modal_detail::fnv1a(b.data(), b.size() - 8);
  std::memcpy(b.data() + b.size() - 8, &sum, 8);
  return b;
}

std::string refusal(const std::vector<std::uint8_t>& file) {
  std::string warning;
  EXPECT_FALSE(audio::decodeModalCache(file, kKey, "x.modes", [&](const std::string& w) { warning = w; }));
  EXPECT_NE(warning.find("x.modes"), std::string::npos) << warning;
  return warning;
}

}  // namespace

TEST(FuzzModalCache, WriteSeedCorpusWhenAsked) {
  writeSeedsWhenAsked({withMode(1, audio::encodeModalCache(kKey, smallSolution(6, 4, 3))),
                                      withMode(1, audio::encodeModalCache(kKey, smallSolution(0, 3, 2))),
                                      withMode(0, audio::encodeModalCache(kKey, smallSolution(0, 2, 0))),
                                      withMode(3, audio::encodeModalCache(kKey, smallSolution(6, 2, 1)))});
}

TEST(FuzzModalCache, SeedsHoldTheProperties) { expectSeedsHold(kTarget, &fuzzModalCacheOnce); }

TEST(FuzzModalCache, CorpusFilesAreAccepted) {
  // Guards the corpus's value: the checksummed seeds must reach the round trip.
  int accepted = 0;
  for (const Bytes& seed : loadCorpus(kTarget)) {
    std::uint64_t key = 0;
    std::memcpy(&key, seed.data() + 1 + 16, 8);
    accepted += audio::decodeModalCache(std::span(seed).subspan(1), key, "seed").has_value();
  }
  EXPECT_EQ(accepted, 4);
}

TEST(FuzzModalCache, ShortRun) { shortRun(kTarget, &fuzzModalCacheOnce, 2000); }

TEST(FuzzModalCache, EncodeDecodeRoundTrip) {
  const audio::ModalSolution s = smallSolution(6, 5, 4);
  const auto back = audio::decodeModalCache(audio::encodeModalCache(kKey, s), kKey, "x.modes");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->rigid_hz, s.rigid_hz);
  EXPECT_EQ(back->omega_rad_per_s, s.omega_rad_per_s);
  EXPECT_EQ(back->shapes, s.shapes);
  EXPECT_EQ(back->free_dofs, s.free_dofs);
  EXPECT_TRUE(back->from_cache);
  EXPECT_EQ(back->cache_file, "x.modes");
}

TEST(FuzzModalCache, RefusesCountsTheFileCannotHold) {
  // D x N = 2^62 doubles promised by a 48-byte file: refused before anything is allocated.
  const std::string w = refusal(fileWithCounts(0, 0x7fffffff, 0x7fffffff, 0));
  EXPECT_NE(w.find("48 bytes where R 0, D 2147483647, N 2147483647 need"), std::string::npos) << w;
  // Trailing data is refused the same way.
  EXPECT_NE(refusal(fileWithCounts(0, 3, 1, 4 + 1)).find("trailing"), std::string::npos);
}

TEST(FuzzModalCache, RefusesCountsBeyondInt) {
  EXPECT_NE(refusal(fileWithCounts(0, 0x80000000u, 0, 0)).find("beyond 2147483647"), std::string::npos);
}

TEST(FuzzModalCache, RefusesValuesBehindAValidChecksum) {
  std::vector<std::uint8_t> f = fileWithCounts(0, 3, 2, 2 + 6);
  const double omega[2] = {2000.0, 1000.0};
  std::memcpy(f.data() + 40, omega, sizeof omega);
  const std::uint64_t sum = modal_detail::fnv1a(f.data(), f.size() - 8);
  std::memcpy(f.data() + f.size() - 8, &sum, 8);
  EXPECT_NE(refusal(f).find("not ascending"), std::string::npos);

  const double nan = std::nan("");
  std::memcpy(f.data() + 40 + 16, &nan, 8);
  std::memcpy(f.data() + 40, &omega[1], 8);
  std::memcpy(f.data() + 48, &omega[0], 8);
  const std::uint64_t sum2 = modal_detail::fnv1a(f.data(), f.size() - 8);
  std::memcpy(f.data() + f.size() - 8, &sum2, 8);
  EXPECT_NE(refusal(f).find("mode shape is not finite"), std::string::npos);
}

}  // namespace test_fuzz_modal_cache
