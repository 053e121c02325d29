// The exercise calls of the fixture's chapter 2 (tests/calls/core.h).
#ifndef FIXTURE_CH02_EXERCISE_CALLS_H
#define FIXTURE_CH02_EXERCISE_CALLS_H

#include "calls/core.h"
#include "lrt/means.h"

#include <vector>

namespace lrt {
namespace direct {
inline double Mean(std::vector<int> v) { return lrt::Mean(v); }
}  // namespace direct
}  // namespace lrt

LRT_EXERCISE_CALL(Mean)

#endif
