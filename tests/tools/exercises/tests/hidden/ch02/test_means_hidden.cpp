#include <vector>

#include <gtest/gtest.h>

#include "ch02/exercise_calls.h"

#include "lrt/means.h"

using namespace lrt;

EXERCISE_TEST(Ex2_1_MeanHiddenCases, MixedSignsCancel) { EXPECT_DOUBLE_EQ(ex::Mean(std::vector<int>{-3, 3, -1, 1}), 0); }
