// The terminal prompt of a real session re-asks until the answer is on the scale.
#include <gtest/gtest.h>

#include <sstream>

#include "clients/study/rating_prompt.hpp"

namespace thx::study::test_rating_prompt {
namespace {

TEST(RatingPrompt, ReasksUntilTheAnswerIsOnTheScale) {
  std::istringstream in("\nseven\n11\n 4.5\n  7 \n3\n");
  std::ostringstream out;
  EXPECT_EQ(askRating(in, out, "Ease?", 1, 10), 7);
  EXPECT_EQ(out.str(),
            "Ease? [1-10]:   expected a whole number from 1 to 10, got ''\n"
            "Ease? [1-10]:   expected a whole number from 1 to 10, got 'seven'\n"
            "Ease? [1-10]:   11 is outside the scale; expected 1 to 10\n"
            "Ease? [1-10]:   expected a whole number from 1 to 10, got '4.5'\n"
            "Ease? [1-10]: ");
  EXPECT_EQ(askRating(in, out, "Use?", 1, 5), 3);
  EXPECT_EQ(askRating(in, out, "More?", 1, 5), std::nullopt);  // the input ended
}

}  // namespace
}  // namespace thx::study::test_rating_prompt
