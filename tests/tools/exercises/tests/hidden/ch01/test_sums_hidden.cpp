#include <climits>
#include <vector>

#include <gtest/gtest.h>

#include "ch01/exercise_calls.h"

#include "lrt/sums.h"

using namespace lrt;

EXERCISE_TEST(Ex1_1_SumOfSquaresHidden, LargeValuesDoNotOverflow) {
    EXPECT_EQ(ex::SumOfSquares(std::vector<int>{INT_MAX, INT_MAX}), 2 * static_cast<long>(INT_MAX) * INT_MAX);
}

EXERCISE_TEST(Ex1_2_ClampHidden, RangeOfOneValue) { EXPECT_EQ(ex::Clamp(7, 3, 3), 3); }
