#include <climits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "lrt/sums.h"

using namespace lrt;

TEST(Ex1_1_SumOfSquares, SmallVectors) {
    EXPECT_EQ(SumOfSquares({3}), 9);
    EXPECT_EQ(SumOfSquares({1, 2, 3}), 14);
}

TEST(Ex1_1_SumOfSquares, NegativeValues) { EXPECT_EQ(SumOfSquares({-2, 2}), 8); }

TEST(SumOfSquares, EmptyVectorThrows) {
    EXPECT_THROW(SumOfSquares({}), std::invalid_argument);
}

TEST(Ex1_2_Clamp, InsideAndOutside) {
    EXPECT_EQ(Clamp(5, 0, 10), 5);
    EXPECT_EQ(Clamp(-5, 0, 10), 0);
    EXPECT_EQ(Clamp(15, 0, 10), 10);
}

TEST(Twice, Doubles) { EXPECT_EQ(Twice(21), 42); }
