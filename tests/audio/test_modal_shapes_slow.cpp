// The plate at the sizes of docs/audio.md §8.2: label `slow`.
#include <gtest/gtest.h>

#include "tests/audio/modal_fixtures.hpp"

namespace thx::audio::test_modal_shapes_slow {
namespace {

TEST(ModalShapesSlow, Plate16AllEightModesWithinOneAndAHalfPercentOfKirchhoff) { test::expectPlateNearKirchhoff(16, 8); }

// 33 489 DOF, as in docs/audio.md §8.2 (-0.4 % there; thin-plate theory itself is ~0.5 % high).
TEST(ModalShapesSlow, Plate30AllEightModesWithinOneAndAHalfPercentOfKirchhoff) { test::expectPlateNearKirchhoff(30, 8); }

}  // namespace
}  // namespace thx::audio::test_modal_shapes_slow
