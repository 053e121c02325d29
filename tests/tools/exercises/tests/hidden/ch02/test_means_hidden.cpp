#include <vector>

#include <gtest/gtest.h>

#include "lrt/means.h"

using namespace lrt;

TEST(Ex2_1_MeanHiddenCases, MixedSignsCancel) { EXPECT_DOUBLE_EQ(Mean({-3, 3, -1, 1}), 0); }
