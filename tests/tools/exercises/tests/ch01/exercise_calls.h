// The exercise calls of the fixture's chapter 1 (tests/calls/core.h).
#ifndef FIXTURE_CH01_EXERCISE_CALLS_H
#define FIXTURE_CH01_EXERCISE_CALLS_H

#include "calls/core.h"
#include "lrt/sums.h"

#include <vector>

namespace lrt {
namespace direct {
inline long SumOfSquares(std::vector<int> v) { return lrt::SumOfSquares(v); }
inline int Clamp(int v, int lo, int hi) { return lrt::Clamp(v, lo, hi); }
}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(SumOfSquares)
LRT_EXERCISE_CALL(Clamp)

#endif
