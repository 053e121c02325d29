// Exercise calls, the tests' side: EXERCISE_TEST, which declares a test of
// a graded exercise, and the numbers of its random cases (Seed, Cases). In
// `make test` a test reaching a later assignment's stub is skipped; in the
// judge (LRT_JUDGE) its body runs in rounds (judge.cpp, RunRounds).
//
// Included by core.h in the builds that hold tests (the book's tests and the
// judge; never the worker, which has no GoogleTest) and by judge.cpp.

#ifndef LRT_TESTS_CALLS_EXERCISE_TEST_H
#define LRT_TESTS_CALLS_EXERCISE_TEST_H

#include <gtest/gtest.h>

#include "calls/rpc.h"

#include <cstdint>
#include <stdexcept>

namespace lrt {
namespace calls {

// The seed of a test's random cases: `seed` in `make test`, mixed with the
// grader's secret in the judge, so that graded random cases are new each time.
#ifdef LRT_JUDGE
uint64_t Seed(uint64_t seed);
#else
inline uint64_t Seed(uint64_t seed) { return seed; }
#endif

// How many random cases a test draws: `local` in `make test`, `graded` in the
// judge, where every call crosses to the worker and back (and the student's
// code runs unoptimized).
inline int Cases(int local, int graded) {
#ifdef LRT_JUDGE
    (void)local;
    return graded;
#else
    (void)graded;
    return local;
#endif
}

#ifdef LRT_JUDGE
// judge.cpp: runs the body of an EXERCISE_TEST in rounds.
void RunRounds(void (*body)());
#endif

}  // namespace calls
}  // namespace lrt

// A test of a graded exercise. In the judge its body may run several times
// (see judge.cpp); it must not depend on state left by an earlier run.
#ifdef LRT_JUDGE
#define EXERCISE_TEST(Suite, Name)                                  \
    static void Suite##_##Name##_Body();                            \
    TEST(Suite, Name) { ::lrt::calls::RunRounds(&Suite##_##Name##_Body); } \
    static void Suite##_##Name##_Body()
#else
#define EXERCISE_TEST(Suite, Name)                                  \
    static void Suite##_##Name##_Body();                            \
    TEST(Suite, Name) {                                             \
        try {                                                       \
            Suite##_##Name##_Body();                                \
        } catch (const ::lrt::calls::Later &later) {                \
            GTEST_SKIP() << later.message;                          \
        } catch (const std::logic_error &e) {                       \
            if (!::lrt::calls::IsLater(e)) throw;                   \
            GTEST_SKIP() << e.what();                               \
        }                                                           \
    }                                                               \
    static void Suite##_##Name##_Body()
#endif

#endif  // LRT_TESTS_CALLS_EXERCISE_TEST_H
