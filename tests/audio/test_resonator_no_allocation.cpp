// The real-time path of the resonator bank never allocates.
#include <gtest/gtest.h>

#include <vector>

#include "clients/audio/synthesis/resonator_bank.hpp"
#include "tests/support/allocation_counter.hpp"

namespace thx::audio::test_resonator_no_allocation {
namespace {

TEST(ResonatorNoAllocation, SetStrikeAndRenderAllocateNothing) {
  std::vector<double> f(300), d(300), g(300);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = 50.0 + 60.0 * double(k), d[k] = 2.0 + 0.1 * double(k), g[k] = 1e-3;
  ResonatorBank bank(44100.0, 512);
  std::vector<float> block(256);
  std::vector<double> block_d(256);
  const long before = thx::test::t_allocations;
  ASSERT_TRUE(bank.setModes(f, d));
  for (int b = 0; b < 50; ++b) {
    bank.setBudget(b % 2 ? 100 : 300);  // quality scaling under load
    bank.strike(g);
    bank.strikeMode(3, 0.01);
    bank.render(block);
    bank.render(block_d);
  }
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  EXPECT_NE(block[0], 0.0f);  // it did render something
}

TEST(ResonatorNoAllocation, TheFloatBankAndAForcedInstructionSetAllocateNothing) {
  std::vector<double> f(300), d(300), g(300);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = 50.0 + 60.0 * double(k), d[k] = 2.0 + 0.1 * double(k), g[k] = 1e-3;
  ResonatorBankFloat bank(44100.0, 512);
  std::vector<float> block(700);  // longer than the kernel's block: rendered in pieces
  const long before = thx::test::t_allocations;
  ASSERT_TRUE(bank.setIsa(Isa::Default));
  ASSERT_TRUE(bank.setModes(f, d));
  for (int b = 0; b < 20; ++b) {
    bank.setBudget(b % 2 ? 77 : 300);
    bank.strike(g);
    bank.render(block);
  }
  EXPECT_EQ(thx::test::t_allocations - before, 0);
  EXPECT_NE(block[0], 0.0f);
}

}  // namespace
}  // namespace thx::audio::test_resonator_no_allocation
