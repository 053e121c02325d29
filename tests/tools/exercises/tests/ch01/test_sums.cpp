#include <climits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "exercise_calls.h"

#include "lrt/sums.h"

using namespace lrt;

EXERCISE_TEST(Ex1_1_SumOfSquares, SmallVectors) {
    EXPECT_EQ(ex::SumOfSquares(std::vector<int>{3}), 9);
    EXPECT_EQ(ex::SumOfSquares(std::vector<int>{1, 2, 3}), 14);
}

EXERCISE_TEST(Ex1_1_SumOfSquares, NegativeValues) { EXPECT_EQ(ex::SumOfSquares(std::vector<int>{-2, 2}), 8); }

TEST(SumOfSquares, EmptyVectorThrows) {
    EXPECT_THROW(SumOfSquares({}), std::invalid_argument);
}

EXERCISE_TEST(Ex1_2_Clamp, InsideAndOutside) {
    EXPECT_EQ(ex::Clamp(5, 0, 10), 5);
    EXPECT_EQ(ex::Clamp(-5, 0, 10), 0);
    EXPECT_EQ(ex::Clamp(15, 0, 10), 10);
}

TEST(Twice, Doubles) { EXPECT_EQ(Twice(21), 42); }
