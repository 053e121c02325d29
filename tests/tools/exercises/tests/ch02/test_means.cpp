#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "exercise_calls.h"

#include "lrt/means.h"
#include "lrt/sums.h"

using namespace lrt;

EXERCISE_TEST(Ex2_1_Mean, SmallVectors) {
    EXPECT_DOUBLE_EQ(ex::Mean(std::vector<int>{1, 2, 3, 4}), 2.5);
    EXPECT_DOUBLE_EQ(ex::Mean(std::vector<int>{7}), 7);
}

TEST(Mean, EmptyVectorThrows) { EXPECT_THROW(Mean({}), std::invalid_argument); }

TEST(Mean, TwiceStillWorks) { EXPECT_EQ(Twice(-4), -8); }
