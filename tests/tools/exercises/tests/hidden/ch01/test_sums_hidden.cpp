#include <climits>
#include <vector>

#include <gtest/gtest.h>

#include "lrt/sums.h"

using namespace lrt;

TEST(Ex1_1_SumOfSquaresHidden, LargeValuesDoNotOverflow) {
    EXPECT_EQ(SumOfSquares({INT_MAX, INT_MAX}), 2 * static_cast<long>(INT_MAX) * INT_MAX);
}

TEST(Ex1_2_ClampHidden, RangeOfOneValue) { EXPECT_EQ(Clamp(7, 3, 3), 3); }
